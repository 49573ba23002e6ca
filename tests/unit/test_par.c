/* test_par.c - cmocka tests of the host's task queue (host/render/lt_par.h) and of the tile loops
 * on it: every task runs exactly once on workers 0..n-1 for any thread count; the charged loops
 * take one worker in the sim build; progress rises to 1; and frames traced through every
 * structure and numeric path (primary rays, single rays, shadow rays, depth peels) are
 * bit-identical for 1, 2, 3 and 7 threads, and bvh's single shadow rays (its wide tree) give the
 * packets' occlusion bits. Builds: host, sim, asan.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/lt_mesh.h"
#include "lt_meter.h"
#include "render/lt_par.h"
#include "render/lt_render.h"
#include "render/lt_scene.h"

typedef struct count_ctx {
    uint32_t *hits;      /* per task, how often it ran */
    uint32_t *worker;    /* per task, the worker that ran it */
    unsigned max_worker; /* workers allowed */
} count_ctx_t;

static void count_task(void *ctx, unsigned w, uint32_t t)
{
    count_ctx_t *c = ctx;
    __atomic_add_fetch(&c->hits[t], 1u, __ATOMIC_RELAXED);
    c->worker[t] = w;
}

static double last_progress;
static int progress_calls, progress_fell;

static void on_progress(double d)
{
    if (d < last_progress)
        progress_fell = 1;
    last_progress = d;
    progress_calls++;
}

static void test_every_task_once(void **state)
{
    static const unsigned threads[] = {1, 2, 3, 7, 64, LT_PAR_MAX_THREADS};
    static const uint32_t ntasks[] = {0, 1, 5, 1000, 100000};
    unsigned a, b, checked = 0;
    (void)state;
    for (a = 0; a < sizeof threads / sizeof threads[0]; a++)
        for (b = 0; b < sizeof ntasks / sizeof ntasks[0]; b++) {
            count_ctx_t c;
            uint32_t t, n = ntasks[b];
            unsigned w, used;
            lt_par_set_threads(threads[a]);
            w = lt_par_workers(n, 0);
            assert_true(w >= 1 && w <= threads[a] && (n == 0 || w <= n));
            c.hits = calloc(n + 1, sizeof *c.hits);
            c.worker = calloc(n + 1, sizeof *c.worker);
            assert_non_null(c.hits);
            assert_non_null(c.worker);
            last_progress = 0.0;
            progress_calls = progress_fell = 0;
            used = lt_par_run(n, w, count_task, &c, on_progress);
            assert_true(used >= 1 && used <= w);
            for (t = 0; t < n; t++) {
                assert_int_equal(c.hits[t], 1);
                assert_true(c.worker[t] < used);
            }
            assert_false(progress_fell);
            assert_true(last_progress == 1.0);
            free(c.hits);
            free(c.worker);
            checked++;
        }
    printf("lt_par_run: %u (threads, tasks) pairs, threads 1..%u, tasks 0..100000: every task "
           "ran once on a worker < the workers used, progress never fell and ended at 1\n",
           checked, LT_PAR_MAX_THREADS);
}

static void test_thread_counts(void **state)
{
    (void)state;
    lt_par_set_threads(0);
    assert_true(lt_par_threads() >= 1);
    printf("lt_par_set_threads(0) = %u online cores\n", lt_par_threads());
    lt_par_set_threads(100000);
    assert_int_equal(lt_par_threads(), LT_PAR_MAX_THREADS);
    lt_par_set_threads(4);
    assert_int_equal(lt_par_workers(2, 0), 2);
    assert_int_equal(lt_par_workers(0, 0), 1);
    /* the charged loops: one worker where the cycle model counts (sim), all otherwise */
    assert_int_equal(lt_par_workers(100, 1), lt_meter_available() ? 1 : 4);
    printf("workers: 4 threads, 2 tasks -> 2; 0 tasks -> 1; charged loop -> %u (%s build)\n",
           lt_par_workers(100, 1), lt_meter_available() ? "sim" : "native");
    lt_par_set_threads(1);
}

/* ---- frames: bit-identical for any thread count ------------------------------------------- */

static int load_teapot(lt_mesh_t *m, lt_scene_t *s)
{
    lt_diag_t diag;
    if (lt_mesh_load("scenes/teapot.obj", m, &diag) != 0 || lt_scene_prepare(m, s, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return -1;
    }
    return 0;
}

/* A hash of everything the loops write for one structure and path at the current thread count:
 * primary frame, single-ray frame, shadow bits and counts, second depth layer. */
static uint32_t frames_hash(const lt_scene_t *s, const lt_accel_t *acc, const lt_camera_t *cam,
                            int shadows)
{
    lt_frame_t f, one, peel;
    lt_diag_t diag;
    uint32_t h, nr = 0, no = 0, i;
    uint8_t *occ;
    double light[3] = {-0.5 * s->radius, 1.5 * s->radius, 0.8 * s->radius};
    size_t n = (size_t)cam->width * cam->height;
    assert_int_equal(lt_frame_alloc(&f, cam->width, cam->height, &diag), 0);
    assert_int_equal(lt_frame_alloc(&one, cam->width, cam->height, &diag), 0);
    assert_int_equal(lt_frame_alloc(&peel, cam->width, cam->height, &diag), 0);
    occ = calloc(n, 1);
    assert_non_null(occ);
    lt_render_primary(s, acc, cam, &f, NULL);
    h = lt_frame_hash(&f);
    assert_int_equal(lt_render_primary1(s, acc, cam, &one, &diag), 0);
    h = h * 16777619u ^ lt_frame_hash(&one);
    if (shadows == 2) {
        /* bvh: the single shadow rays through the wide tree give the packets' occlusion bits */
        uint8_t *occ1 = calloc(n, 1);
        uint32_t nr1 = 0, no1 = 0;
        assert_non_null(occ1);
        assert_int_equal(lt_render_shadows1(s, acc, cam, &f, light, &nr1, &no1, occ1, &diag), 0);
        assert_int_equal(lt_render_shadows(s, acc, cam, &f, light, &nr, &no, occ, &diag), 0);
        assert_int_equal(nr1, nr);
        assert_int_equal(no1, no);
        assert_memory_equal(occ1, occ, n);
        free(occ1);
    }
    if (shadows) {
        assert_int_equal(lt_render_shadows(s, acc, cam, &f, light, &nr, &no, occ, &diag), 0);
        assert_int_equal(lt_render_peel(s, acc, cam, &f, &peel, &diag), 0);
        h = h * 16777619u ^ lt_frame_hash(&peel);
        h = h * 16777619u ^ nr;
        h = h * 16777619u ^ no;
        for (i = 0; i < n; i++)
            h = (h ^ occ[i]) * 16777619u;
    }
    free(occ);
    lt_frame_free(&f);
    lt_frame_free(&one);
    lt_frame_free(&peel);
    return h;
}

static void test_frames_any_thread_count(void **state)
{
    static const char *const paths[] = {"q16", "f32"};
    static const unsigned threads[] = {1, 2, 3, 7};
    lt_mesh_t m;
    lt_scene_t s;
    lt_camera_t cam;
    unsigned p, k, cases = 0;
    int st;
    (void)state;
    if (load_teapot(&m, &s) != 0)
        fail_msg("scenes/teapot.obj (bundled) did not load");
    /* 70 x 38: partial tiles on both edges */
    lt_camera_default(&s, 70, 38, &cam);
    for (p = 0; p < 2; p++)
        for (st = 0; lt_render_structures[st] != NULL; st++) {
            const char *name = lt_render_structures[st];
            lt_diag_t diag;
            lt_accel_t *acc = lt_accel_build(&s, name, lt_paths_find(paths[p], LT_PATHS_OBJECT),
                                             &diag);
            uint32_t h1 = 0;
            if (acc == NULL)
                continue; /* bvhq has no float32 nodes */
            for (k = 0; k < sizeof threads / sizeof threads[0]; k++) {
                uint32_t h;
                lt_par_set_threads(threads[k]);
                /* the loops really run on that many workers (one where the model counts) */
                assert_int_equal(lt_par_workers((cam.height + 3) / 4, 1),
                                 lt_meter_available() ? 1u : threads[k]);
                h = frames_hash(&s, acc, &cam,
                                strcmp(name, "chunks") == 0 ? 0 : (strcmp(name, "bvh") == 0 ? 2 : 1));
                if (k == 0)
                    h1 = h;
                assert_int_equal(h, h1);
            }
            printf("%s %-6s 70x38: primary, single-ray%s frames equal on 1, 2, 3 and 7 threads "
                   "(0x%08x)%s\n", paths[p], name,
                   strcmp(name, "chunks") != 0 ? ", shadow and peel" : "", h1,
                   strcmp(name, "bvh") == 0 ? "; single shadow rays (wide tree) = packets" : "");
            lt_accel_free(acc);
            cases++;
        }
    lt_par_set_threads(1);
    assert_true(cases >= 9);
    lt_scene_free(&s);
    lt_mesh_free(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_task_once),
        cmocka_unit_test(test_thread_counts),
        cmocka_unit_test(test_frames_any_thread_count),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
