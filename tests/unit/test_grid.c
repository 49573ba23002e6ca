/* test_grid.c - cmocka tests of the uniform grid (lt_grid.h) in s15.16 and float32: the exact
 * size query and arena guards, the grid's invariants (each cell lists exactly the triangles
 * whose bounding box touches it, sorted), and closest hits / occlusion of 16-ray packets by
 * per-lane 3D-DDA against lt_chunks_trace16 (the same triangle kernel over a flat list, tested
 * against double in test_isect.c), against the kd-tree (the two structures must agree), and for
 * the bundled teapot and ../shared/scenes/bunny.obj against the double-precision brute force.
 *
 * Numeric bound (as test_kd.c): the grid and the reference run the same lt_tri16 kernel, so a
 * triangle's t is bit-identical; they differ only in which triangles a lane tests before it
 * stops. A lane stops when its hit lies at or before the cell's exit t, a boundary distance
 * (boundary - o) x (1/d) off by at most 2^-17 (1 + |boundary - o|) in s15.16 (a few ulps of it in
 * float32), and its entry cell is settled against the same boundary t values. A different id is
 * accepted only if both hits are within e = 2^-16 (4 + L) (s15.16) or 2^-20 (4 + L) (float32),
 * L = |origin|_inf + the scene's largest |coordinate|, plus both triangles' t bounds (the grid's
 * hit re-tested alone), or if one side misses and the other side's triangle is neither a sure hit
 * nor a sure miss in double within the kernel's bounds (an edge hit). >= 99.99% of camera rays
 * must get the same id. Builds: host, sim (also prints per-ray counters on the lrb16 model), asan
 * (fewer packets).
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lt/lt_grid.h"
#include "lt/lt_kd.h"
#include "io/lt_fx_float.h"
#include "io/lt_mesh.h"
#include "render/lt_scene.h"
#include "lt_test_util.h"
#include "lt_kdgrid_testlib.h"
/* ---- grid specifics ------------------------------------------------------------------------- */

typedef struct gpair {
    lt_grid_q16_t q;
    void *mq;
    size_t size;
#if LT_CFG_FLOAT32
    lt_grid_f32_t f;
    void *mf;
    size_t fsize;
#endif
} gpair_t;

/* Size query, then LT_E_SPACE one byte short (needed size written back, arena untouched), then
 * the build into exactly that many bytes of a poisoned arena (guard untouched, bytes = size). */
static void g_build_pair(gpair_t *g, const mesh_t *m, const lt_grid_params_t *p)
{
    size_t got;
    assert_int_equal(lt_grid_size_q16(m->tq, m->n, p, &g->size), LT_OK);
    g->mq = malloc(g->size + GUARD);
    assert_non_null(g->mq);
    ltt_poison(g->mq, g->size + GUARD);
    got = g->size - 1;
    assert_int_equal(lt_grid_build_q16(&g->q, m->tq, m->n, p, g->mq, &got), LT_E_SPACE);
    assert_true(got == g->size);
    assert_int_equal(ltt_touched(g->mq, 0, g->size + GUARD), 0);
    got = g->size;
    assert_int_equal(lt_grid_build_q16(&g->q, m->tq, m->n, p, g->mq, &got), LT_OK);
    assert_true(got == g->size && g->q.bytes == g->size);
    assert_int_equal(ltt_touched(g->mq, g->size, g->size + GUARD), 0);
#if LT_CFG_FLOAT32
    assert_int_equal(lt_grid_size_f32(m->tf, m->n, p, &g->fsize), LT_OK);
    g->mf = malloc(g->fsize + GUARD);
    assert_non_null(g->mf);
    ltt_poison(g->mf, g->fsize + GUARD);
    got = g->fsize - 1;
    assert_int_equal(lt_grid_build_f32(&g->f, m->tf, m->n, p, g->mf, &got), LT_E_SPACE);
    assert_true(got == g->fsize);
    assert_int_equal(ltt_touched(g->mf, 0, g->fsize + GUARD), 0);
    got = g->fsize;
    assert_int_equal(lt_grid_build_f32(&g->f, m->tf, m->n, p, g->mf, &got), LT_OK);
    assert_true(got == g->fsize && g->f.bytes == g->fsize);
    assert_int_equal(ltt_touched(g->mf, g->fsize, g->fsize + GUARD), 0);
#endif
}

static void g_free_pair(gpair_t *g)
{
    free(g->mq);
#if LT_CFG_FLOAT32
    free(g->mf);
#endif
}

static lt_mask16_t g_tq(const void *a, lt_ray16_q16_t *r, lt_mask16_t k, lt_hit16_t *h)
{
    return lt_grid_trace16_q16((const lt_grid_q16_t *)a, r, k, h);
}
static lt_mask16_t g_oq(const void *a, lt_ray16_q16_t *r, lt_mask16_t k)
{
    return lt_grid_occluded16_q16((const lt_grid_q16_t *)a, r, k);
}
#if LT_CFG_FLOAT32
static lt_mask16_t g_tf(const void *a, lt_ray16_f32_t *r, lt_mask16_t k, lt_hit16_t *h)
{
    return lt_grid_trace16_f32((const lt_grid_f32_t *)a, r, k, h);
}
static lt_mask16_t g_of(const void *a, lt_ray16_f32_t *r, lt_mask16_t k)
{
    return lt_grid_occluded16_f32((const lt_grid_f32_t *)a, r, k);
}
#endif

static void acc_grid(acc_t *a, const gpair_t *g)
{
    memset(a, 0, sizeof *a);
    a->name = "grid";
    a->q = &g->q;
    a->tq = g_tq;
    a->oq = g_oq;
#if LT_CFG_FLOAT32
    a->f = &g->f;
    a->tf = g_tf;
    a->of = g_of;
#endif
}

/* Grid invariants: resolution within [1, LT_GRID_MAX_RES] per axis and at most max(1, lambda n)
 * cells, the grid box covering the scene, offsets rising to nrefs, and each cell listing exactly
 * (and in increasing order) the triangles whose vertex bounds touch it, where along each axis a
 * bound x lies in cell j = the largest j with boundary_j <= x (clamped to the grid), boundary_j
 * being lo + j x cell as lt_grid.h defines it. */
#define DEFINE_GRID_CHECK(SFX, G, TRI, T, BOUND)                                                   \
    static void g_verify_##SFX(const G *g, const char *what, uint32_t q4)                          \
    {                                                                                              \
        unsigned long bad = 0, expect = 0;                                                         \
        uint32_t t, c, a, *cnt = calloc(g->ncells + 1u, sizeof *cnt), *rg;                         \
        uint64_t target = (uint64_t)g->ntris * q4 / 16u;                                           \
        rg = malloc((size_t)(g->ntris + 1u) * 6u * sizeof *rg);                                    \
        assert_non_null(cnt);                                                                      \
        assert_non_null(rg);                                                                       \
        for (a = 0; a < 3; a++)                                                                    \
            bad += g->res[a] < 1 || g->res[a] > LT_GRID_MAX_RES || !(g->cell[a] > 0);              \
        bad += g->ncells != g->res[0] * g->res[1] * g->res[2];                                     \
        bad += g->ncells > (target < 1 ? 1 : target);                                              \
        for (t = 0; t < g->ntris; t++) {                                                           \
            const TRI *tr = &g->tris[t];                                                           \
            uint64_t cells = 1;                                                                    \
            for (a = 0; a < 3; a++) {                                                              \
                T p0 = tr->v0[a], p1 = (T)(p0 + tr->e1[a]), p2 = (T)(p0 + tr->e2[a]);              \
                T tl = p0 < p1 ? p0 : p1, th = p0 < p1 ? p1 : p0;                                  \
                uint32_t j, lo = g->res[a], hi = 0;                                                \
                tl = p2 < tl ? p2 : tl;                                                            \
                th = p2 > th ? p2 : th;                                                            \
                bad += tl < g->bounds.lo[a] || th > g->bounds.hi[a];                               \
                for (j = 0; j < g->res[a]; j++) {                                                  \
                    int in = (j == 0 || BOUND(g->bounds.lo[a], j, g->cell[a]) <= th) &&            \
                             (j + 1 == g->res[a] || BOUND(g->bounds.lo[a], j + 1, g->cell[a]) > tl); \
                    if (in) {                                                                      \
                        lo = j < lo ? j : lo;                                                      \
                        hi = j;                                                                    \
                    }                                                                              \
                }                                                                                  \
                rg[t * 6 + a] = lo;                                                                \
                rg[t * 6 + 3 + a] = hi;                                                            \
                cells *= hi - lo + 1u;                                                             \
            }                                                                                      \
            expect += cells;                                                                       \
            {                                                                                      \
                uint32_t x, y, z;                                                                  \
                for (z = rg[t * 6 + 2]; z <= rg[t * 6 + 5]; z++)                                   \
                    for (y = rg[t * 6 + 1]; y <= rg[t * 6 + 4]; y++)                               \
                        for (x = rg[t * 6 + 0]; x <= rg[t * 6 + 3]; x++)                           \
                            cnt[x + g->res[0] * (y + g->res[1] * z)]++;                            \
            }                                                                                      \
        }                                                                                          \
        bad += expect != g->nrefs || g->cells[0] != 0 || g->cells[g->ncells] != g->nrefs;          \
        for (c = 0; c < g->ncells && bad == 0; c++) {                                              \
            uint32_t x = c % g->res[0], y = (c / g->res[0]) % g->res[1];                           \
            uint32_t z = c / (g->res[0] * g->res[1]), i;                                           \
            if (g->cells[c + 1] < g->cells[c] || g->cells[c + 1] - g->cells[c] != cnt[c]) {        \
                bad++;                                                                             \
                break;                                                                             \
            }                                                                                      \
            for (i = g->cells[c]; i < g->cells[c + 1]; i++) {                                      \
                uint32_t id = g->refs[i];                                                          \
                if (id >= g->ntris || (i > g->cells[c] && id <= g->refs[i - 1]) ||                 \
                    x < rg[id * 6] || x > rg[id * 6 + 3] || y < rg[id * 6 + 1] ||                  \
                    y > rg[id * 6 + 4] || z < rg[id * 6 + 2] || z > rg[id * 6 + 5])               \
                    bad++;                                                                         \
            }                                                                                      \
        }                                                                                          \
        ltt_report("%s: %ux%ux%u = %u cells (target lambda n = %llu), %u refs (%.2f per "         \
                   "triangle), %zu bytes, %lu invariant violations\n",                             \
                   what, g->res[0], g->res[1], g->res[2], g->ncells,                               \
                   (unsigned long long)(target < 1 ? 1 : target), g->nrefs,                        \
                   g->ntris ? (double)g->nrefs / g->ntris : 0.0, g->bytes, bad);                   \
        free(cnt);                                                                                 \
        free(rg);                                                                                  \
        assert_int_equal(bad, 0);                                                                  \
    }

#define Q_BOUND(lo, j, cs) ((int64_t)(lo) + (int64_t)(j) * (cs))
DEFINE_GRID_CHECK(q16, lt_grid_q16_t, lt_tri_q16_t, lt_q16_t, Q_BOUND)
#if LT_CFG_FLOAT32
#define F_BOUND(lo, j, cs) ((lo) + (float)(j) * (cs))
DEFINE_GRID_CHECK(f32, lt_grid_f32_t, lt_tri_f32_t, float, F_BOUND)
#endif

static uint32_t default_q4(void)
{
    lt_grid_params_t p;
    lt_grid_params_default(&p);
    return p.cells_per_tri_q4;
}

/* Up to 64 cell boundaries (q16 positions, exactly representable in both paths only where the
 * float32 grid has the same boundary, so these mostly exercise the q16 path's exact boundaries). */
static void g_planes(ltt_rng_t *r, const lt_grid_q16_t *g, planes_t *pl)
{
    unsigned i;
    pl->n = 0;
    for (i = 0; i < 64; i++) {
        int a = (int)ltt_rng_below(r, 3);
        uint32_t j = ltt_rng_below(r, g->res[a] + 1u);
        pl->axis[pl->n] = a;
        pl->pos[pl->n] = lt_q16_to_double((lt_q16_t)Q_BOUND(g->bounds.lo[a], j, g->cell[a]));
        pl->n++;
    }
}

/* ---- tests ---------------------------------------------------------------------------------- */

static void test_grid_size_and_arena(void **state)
{
    lt_grid_params_t p, bad;
    ltt_rng_t r;
    double *v;
    mesh_t m;
    gpair_t gp;
    size_t sz, got;
    unsigned char *mem;
    lt_grid_q16_t g;
    (void)state;
    ltt_rng_seed(&r, 0x67726964);
    lt_grid_params_default(&p);
    v = gen_soup(&r, 300, 50.0);
    mesh_init(&m, v, 300);
    g_build_pair(&gp, &m, &p);
    assert_int_equal(lt_grid_size_q16(m.tq, m.n, NULL, &sz), LT_OK);
    assert_true(sz == gp.size);
    assert_true(sz == ((size_t)gp.q.ncells + 1 + gp.q.nrefs) * 4);
    ltt_report("lt_grid_size_q16(300 tris, lambda %.2f) = %zu bytes = (%u cells + 1 + %u refs) x 4, "
               "exact: size-1 -> LT_E_SPACE needing %zu with the arena untouched, size -> LT_OK "
               "with the 0xA5 tail untouched\n",
               p.cells_per_tri_q4 / 16.0, sz, gp.q.ncells, gp.q.nrefs, sz);
    g_verify_q16(&gp.q, "grid q16 soup 300", p.cells_per_tri_q4);
#if LT_CFG_FLOAT32
    g_verify_f32(&gp.f, "grid f32 soup 300", p.cells_per_tri_q4);
#endif
    mem = malloc(sz + GUARD);
    assert_non_null(mem);
    got = 0;
    assert_int_equal(lt_grid_build_q16(&g, m.tq, m.n, &p, NULL, &got), LT_E_SPACE);
    assert_true(got == sz);
    got = sz;
    assert_int_equal(lt_grid_build_q16(NULL, m.tq, m.n, &p, mem, &got), LT_E_ARG);
    assert_int_equal(lt_grid_build_q16(&g, NULL, m.n, &p, mem, &got), LT_E_ARG);
    assert_int_equal(lt_grid_build_q16(&g, m.tq, m.n, &p, mem, NULL), LT_E_ARG);
    assert_int_equal(lt_grid_build_q16(&g, m.tq, m.n, &p, mem + 1, &got), LT_E_ARG);
    assert_int_equal(lt_grid_size_q16(m.tq, m.n, &p, NULL), LT_E_ARG);
    assert_int_equal(lt_grid_size_q16(m.tq, LT_GRID_MAX_TRIS + 1u, &p, &got), LT_E_RANGE);
    bad = p;
    bad.cells_per_tri_q4 = 0;
    assert_int_equal(lt_grid_size_q16(m.tq, m.n, &bad, &got), LT_E_ARG);
    bad.cells_per_tri_q4 = 1025;
    assert_int_equal(lt_grid_size_q16(m.tq, m.n, &bad, &got), LT_E_ARG);
    {
        lt_tri_q16_t t = m.tq[0];
        t.e2[0] = (lt_q16_t)(((int64_t)1 << (LT_CFG_GEOM_MAX_LOG2 + 16)) - t.v0[0] + 1);
        assert_int_equal(lt_grid_size_q16(&t, 1, &p, &got), LT_E_RANGE);
    }
#if LT_CFG_FLOAT32
    {
        lt_tri_f32_t t = m.tf[0];
        t.v0[1] = (float)(0.0 * HUGE_VAL); /* NaN */
        assert_int_equal(lt_grid_size_f32(&t, 1, &p, &got), LT_E_RANGE);
    }
#endif
    ltt_report("lt_grid_build: NULL grid/tris/bytes and misaligned arena -> LT_E_ARG, NULL arena "
               "-> LT_E_SPACE with the size; lambda 0 or > 64 -> LT_E_ARG; n > 2^24, a vertex "
               "beyond 2^%d units or NaN -> LT_E_RANGE\n",
               LT_CFG_GEOM_MAX_LOG2);
    free(mem);
    g_free_pair(&gp);
    mesh_free(&m);
    free(v);
}

/* Random meshes at three resolutions against the chunks and against the kd-tree. */
static void test_grid_random(void **state)
{
    static const uint32_t q4s[] = {32, 1, 512};
    ltt_rng_t r;
    unsigned mi, ci, pk, f32;
    (void)state;
    ltt_rng_seed(&r, 0x67726965);
    for (mi = 0; mi < 2; mi++) {
        uint32_t n = 400;
        double *v = mi == 0 ? gen_soup(&r, n, 60.0) : gen_terrain(&r, 12, 80.0, &n);
        mesh_t m;
        kdpair_t kp;
        acc_t ak, ac, ag;
        mesh_init(&m, v, n);
        kd_build_pair(&kp, &m, NULL);
        acc_kd(&ak, &kp);
        acc_chunks(&ac, &m);
        for (ci = 0; ci < sizeof q4s / sizeof q4s[0]; ci++) {
            lt_grid_params_t p;
            gpair_t gp;
            planes_t pl;
            cmp_t cq, cf, kq, kf;
            unsigned long kinds[LANE_KINDS] = {0};
            char what[160];
            p.cells_per_tri_q4 = q4s[ci];
            g_build_pair(&gp, &m, &p);
            snprintf(what, sizeof what, "grid q16 %s (lambda %.4g)", mi ? "terrain" : "soup",
                     q4s[ci] / 16.0);
            g_verify_q16(&gp.q, what, q4s[ci]);
#if LT_CFG_FLOAT32
            snprintf(what, sizeof what, "grid f32 %s (lambda %.4g)", mi ? "terrain" : "soup",
                     q4s[ci] / 16.0);
            g_verify_f32(&gp.f, what, q4s[ci]);
#endif
            acc_grid(&ag, &gp);
            g_planes(&r, &gp.q, &pl);
            memset(&cq, 0, sizeof cq);
            memset(&cf, 0, sizeof cf);
            memset(&kq, 0, sizeof kq);
            memset(&kf, 0, sizeof kf);
            for (pk = 0; pk < NPACKETS; pk++) {
                pk_t p16;
                gen_packet(&r, &m, &pl, &p16, kinds);
                for (f32 = 0; f32 < 2; f32++) {
                    res16_t rs, rr, rk;
#if !LT_CFG_FLOAT32
                    if (f32)
                        continue;
#endif
                    (f32 ? &cf : &cq)->contract += run(&ag, (int)f32, &p16, &rs);
                    (void)run(&ac, (int)f32, &p16, &rr);
                    (void)run(&ak, (int)f32, &p16, &rk);
                    judge(f32 ? &cf : &cq, "grid", &m, (int)f32, &p16, &rs, &rr);
                    judge(f32 ? &kf : &kq, "grid vs kd", &m, (int)f32, &p16, &rs, &rk);
                }
            }
            snprintf(what, sizeof what, "lt_grid_trace16_q16 vs chunks, %s, lambda %.4g",
                     mi ? "terrain 296 tris" : "soup 400 tris", q4s[ci] / 16.0);
            cmp_print(&cq, what);
            snprintf(what, sizeof what, "lt_grid_trace16_q16 vs lt_kd_trace16_q16, %s, lambda %.4g",
                     mi ? "terrain 296 tris" : "soup 400 tris", q4s[ci] / 16.0);
            cmp_print(&kq, what);
            cmp_assert(&cq, 0.0);
            cmp_assert(&kq, 0.0);
#if LT_CFG_FLOAT32
            snprintf(what, sizeof what, "lt_grid_trace16_f32 vs chunks, %s, lambda %.4g",
                     mi ? "terrain 296 tris" : "soup 400 tris", q4s[ci] / 16.0);
            cmp_print(&cf, what);
            snprintf(what, sizeof what, "lt_grid_trace16_f32 vs lt_kd_trace16_f32, %s, lambda %.4g",
                     mi ? "terrain 296 tris" : "soup 400 tris", q4s[ci] / 16.0);
            cmp_print(&kf, what);
            cmp_assert(&cf, 0.0);
            cmp_assert(&kf, 0.0);
#endif
            if (ci == 0)
                ltt_report("  lanes per kind: %s %lu, %s %lu, %s %lu, %s %lu, %s %lu, %s %lu "
                           "(origins on %u cell boundaries)\n",
                           lane_kind_names[0], kinds[0], lane_kind_names[1], kinds[1],
                           lane_kind_names[2], kinds[2], lane_kind_names[3], kinds[3],
                           lane_kind_names[4], kinds[4], lane_kind_names[5], kinds[5], pl.n);
            g_free_pair(&gp);
        }
        kd_free_pair(&kp);
        mesh_free(&m);
        free(v);
    }
}

/* Empty scene, one triangle, a flat scene (all triangles in z = 3), degenerate triangles. */
static void test_grid_edge_cases(void **state)
{
    static const char *const names[] = {"empty scene (n = 0)", "single triangle",
                                        "flat scene (48 triangles in z = 3)",
                                        "40 degenerate triangles (no lane may hit)"};
    ltt_rng_t r;
    double v[9 * 48] = {0};
    unsigned sc, pk, f32;
    unsigned long kinds[LANE_KINDS] = {0};
    (void)state;
    ltt_rng_seed(&r, 0x67726966);
    for (sc = 0; sc < 4; sc++) {
        uint32_t n = sc == 0 ? 0u : (sc == 1 ? 1u : (sc == 2 ? 48u : 40u)), t;
        mesh_t m;
        gpair_t gp;
        kdpair_t kp;
        acc_t ag, ac, ak;
        cmp_t c, ck;
        char what[160];
        int a;
        for (t = 0; t < n; t++) {
            double *q = &v[t * 9];
            for (a = 0; a < 9; a++)
                q[a] = ltt_rng_uniform(&r, -8, 8);
            if (sc == 2)
                q[2] = q[5] = q[8] = 3.0;
            if (sc == 3) {
                if (t % 3 == 0) {
                    memcpy(&q[3], q, 3 * sizeof *q);
                    memcpy(&q[6], q, 3 * sizeof *q);
                } else if (t % 3 == 1) {
                    for (a = 0; a < 3; a++)
                        q[6 + a] = q[a] + 2.0 * (q[3 + a] - q[a]);
                } else {
                    memcpy(&q[6], &q[3], 3 * sizeof *q);
                }
            }
        }
        mesh_init(&m, v, n);
        if (n == 0) {
            m.lo[0] = m.lo[1] = m.lo[2] = -10;
            m.hi[0] = m.hi[1] = m.hi[2] = 10;
        }
        g_build_pair(&gp, &m, NULL);
        snprintf(what, sizeof what, "grid q16 %s", names[sc]);
        g_verify_q16(&gp.q, what, default_q4());
        kd_build_pair(&kp, &m, NULL);
        acc_grid(&ag, &gp);
        acc_chunks(&ac, &m);
        acc_kd(&ak, &kp);
        memset(&c, 0, sizeof c);
        memset(&ck, 0, sizeof ck);
        for (pk = 0; pk < NPACKETS; pk++) {
            pk_t p;
            res16_t rs, rr, rk;
            gen_packet(&r, &m, NULL, &p, kinds);
            for (f32 = 0; f32 < 2; f32++) {
#if !LT_CFG_FLOAT32
                if (f32)
                    continue;
#endif
                c.contract += run(&ag, (int)f32, &p, &rs);
                (void)run(&ac, (int)f32, &p, &rr);
                ck.contract += run(&ak, (int)f32, &p, &rk);
                judge(&c, "grid", &m, (int)f32, &p, &rs, &rr);
                judge(&ck, "kd", &m, (int)f32, &p, &rk, &rr);
                if (sc == 0 || sc == 3)
                    c.contract += rs.hit != 0 || rs.occ != 0;
            }
        }
        snprintf(what, sizeof what, "grid, %s (q16 + f32) vs chunks", names[sc]);
        cmp_print(&c, what);
        snprintf(what, sizeof what, "kd, %s (q16 + f32) vs chunks", names[sc]);
        cmp_print(&ck, what);
        cmp_assert(&c, 0.0);
        cmp_assert(&ck, 0.0);
        g_free_pair(&gp);
        kd_free_pair(&kp);
        mesh_free(&m);
    }
}

/* Degenerate rays: a zero direction (every axis "parallel"), origins at the s15.16 extremes, and
 * in float32 NaN and infinite components. Neither structure may hang or report a hit for them;
 * the grid's step bound (res_x + res_y + res_z) is what guarantees termination. */
static void test_degenerate_rays(void **state)
{
    ltt_rng_t r;
    double *v;
    mesh_t m;
    gpair_t gp;
    kdpair_t kp;
    unsigned pk, i;
    unsigned long hits = 0, calls = 0;
    (void)state;
    ltt_rng_seed(&r, 0x67726967);
    v = gen_soup(&r, 200, 30.0);
    mesh_init(&m, v, 200);
    g_build_pair(&gp, &m, NULL);
    kd_build_pair(&kp, &m, NULL);
    for (pk = 0; pk < 40; pk++) {
        lt_ray16_q16_t q, q2;
        lt_hit16_t h;
        memset(&q, 0, sizeof q);
        for (i = 0; i < LT_LANES; i++) {
            unsigned w = ltt_rng_below(&r, 3);
            q.ox.l[i] = w == 0 ? LT_Q16_MAX : (w == 1 ? LT_Q16_MIN : lt_q16_from_double_sat(ltt_rng_uniform(&r, -30, 30)));
            q.oy.l[i] = lt_q16_from_double_sat(ltt_rng_uniform(&r, -30, 30));
            q.oz.l[i] = lt_q16_from_double_sat(ltt_rng_uniform(&r, -30, 30));
            q.tmax.l[i] = LT_Q16_MAX - 1;
        }
        lt_ray16_q16_setup(&q);
        q2 = q;
        hits += lt__popcount32(lt_grid_trace16_q16(&gp.q, &q2, 0xFFFF, &h));
        q2 = q;
        hits += lt__popcount32(lt_grid_occluded16_q16(&gp.q, &q2, 0xFFFF));
        q2 = q;
        hits += lt__popcount32(lt_kd_trace16_q16(&kp.q, &q2, 0xFFFF, &h));
        q2 = q;
        hits += lt__popcount32(lt_kd_occluded16_q16(&kp.q, &q2, 0xFFFF));
        calls += 4;
#if LT_CFG_FLOAT32
        {
            lt_ray16_f32_t f, f2;
            memset(&f, 0, sizeof f);
            for (i = 0; i < LT_LANES; i++) {
                unsigned w = ltt_rng_below(&r, 4);
                float nan = (float)(0.0 * HUGE_VAL), inf = (float)HUGE_VAL;
                f.ox.l[i] = (float)ltt_rng_uniform(&r, -30, 30);
                f.oy.l[i] = (float)ltt_rng_uniform(&r, -30, 30);
                f.oz.l[i] = (float)ltt_rng_uniform(&r, -30, 30);
                if (w == 1)
                    f.dx.l[i] = nan;
                else if (w == 2)
                    f.ox.l[i] = nan;
                else if (w == 3)
                    f.dy.l[i] = inf;
                f.tmax.l[i] = 3.0e38f;
            }
            lt_ray16_f32_setup(&f);
            f2 = f;
            hits += lt__popcount32(lt_grid_trace16_f32(&gp.f, &f2, 0xFFFF, &h));
            f2 = f;
            hits += lt__popcount32(lt_grid_occluded16_f32(&gp.f, &f2, 0xFFFF));
            f2 = f;
            hits += lt__popcount32(lt_kd_trace16_f32(&kp.f, &f2, 0xFFFF, &h));
            f2 = f;
            hits += lt__popcount32(lt_kd_occluded16_f32(&kp.f, &f2, 0xFFFF));
            calls += 4;
        }
#endif
    }
    ltt_report("degenerate rays (zero direction, origins at +-32768, f32 NaN/inf components): "
               "%lu grid and kd trace/occluded calls returned, %lu lanes hit (expected 0)\n",
               calls, hits);
    assert_int_equal(hits, 0);
    g_free_pair(&gp);
    kd_free_pair(&kp);
    mesh_free(&m);
    free(v);
}

/* ---- scenes --------------------------------------------------------------------------------- */

#if LT_COST_MODE == LT_COST_SIM
static void ctr_begin(void)
{
    lt_sim_reset();
}

/* Sum of an event over all phases, and total modelled cycles. */
static void ctr_end(uint64_t *nodes, uint64_t *tris, uint64_t *tri_rays, uint64_t *cycles)
{
    lt_sim_totals_t t;
    int ph;
    lt_sim_totals(&t);
    *nodes = *tris = *tri_rays = 0;
    for (ph = 0; ph < LT_PH__COUNT; ph++) {
        *nodes += t.ctr[ph][LT_OP__COUNT + LT_EV_NODES];
        *tris += t.ctr[ph][LT_OP__COUNT + LT_EV_TRIS];
        *tri_rays += t.ctr[ph][LT_OP__COUNT + LT_EV_TRI_RAYS];
    }
    *cycles = t.total_cycles;
}
#endif

/* Load a scene as the tracer does (lt_mesh_load + lt_scene_prepare). Returns 0, or -1 when the
 * file is missing. */
static int load_scene(const char *path, lt_scene_t *s, mesh_t *m)
{
    lt_mesh_t mesh;
    lt_diag_t diag;
    if (lt_mesh_load(path, &mesh, &diag) != 0) {
        ltt_report("  (%s)\n", diag.msg);
        return -1;
    }
    assert_int_equal(lt_scene_prepare(&mesh, s, &diag), 0);
    lt_mesh_free(&mesh);
    mesh_init(m, s->vd, s->ntris);
    return 0;
}

/* The camera's packets in both paths. */
static lt_mask16_t cam_packet(const lt_camera_t *cam, uint32_t tx, uint32_t ty, pk_t *p)
{
    int i;
    memset(p, 0, sizeof *p);
    p->k = lt_camera_packet_q16(cam, tx, ty, &p->q);
#if LT_CFG_FLOAT32
    (void)lt_camera_packet_f32(cam, tx, ty, &p->f);
#endif
    for (i = 0; i < LT_LANES; i++)
        memcpy(p->o[i], cam->eye, sizeof p->o[i]);
    return p->k;
}

/* A whole camera view: the grid against the chunks, against the kd-tree and against the double
 * brute force; per-ray counters in the sim build. */
static void scene_run(const char *path, const char *name, uint32_t res, int bundled)
{
    lt_scene_t s;
    mesh_t m;
    gpair_t gp;
    kdpair_t kp;
    acc_t ag, ac, ak;
    lt_camera_t cam;
    cmp_t cq, cf, kq, kf;
    uint32_t tx, ty, x, y;
    unsigned long dsame[2] = {0, 0}, dn = 0;
    char what[200];
    int i;
    if (load_scene(path, &s, &m) != 0) {
        if (bundled) {
            ltt_report("FAIL %s: the bundled %s is missing (run from the repository root)\n",
                       name, path);
            fail();
        }
        if (getenv("CI") != NULL && strcmp(getenv("CI"), "true") == 0) {
            ltt_report("FAIL %s: %s missing under CI=true\n", name, path);
            fail();
        }
        ltt_report("SKIP %s: %s not found (a fresh clone has no ../shared)\n", name, path);
        return;
    }
    g_build_pair(&gp, &m, NULL);
    snprintf(what, sizeof what, "grid q16 %s", name);
    g_verify_q16(&gp.q, what, default_q4());
#if LT_CFG_FLOAT32
    snprintf(what, sizeof what, "grid f32 %s", name);
    g_verify_f32(&gp.f, what, default_q4());
#endif
    ltt_report("grid %s build memory: lt_grid_size = exact arena q16 %zu bytes (%.1f per "
               "triangle)",
               name, gp.q.bytes, (double)gp.q.bytes / m.n);
#if LT_CFG_FLOAT32
    ltt_report(", f32 %zu bytes", gp.f.bytes);
#endif
    ltt_report("\n");
    kd_build_pair(&kp, &m, NULL);
    acc_grid(&ag, &gp);
    acc_chunks(&ac, &m);
    acc_kd(&ak, &kp);
    lt_camera_default(&s, res, res, &cam);
    memset(&cq, 0, sizeof cq);
    memset(&cf, 0, sizeof cf);
    memset(&kq, 0, sizeof kq);
    memset(&kf, 0, sizeof kf);
    for (ty = 0; ty < res; ty += 4)
        for (tx = 0; tx < res; tx += 4) {
            pk_t p;
            res16_t rs[2], rr, rk;
            unsigned f32;
            (void)cam_packet(&cam, tx, ty, &p);
            for (f32 = 0; f32 < 2; f32++) {
#if !LT_CFG_FLOAT32
                if (f32)
                    continue;
#endif
                (f32 ? &cf : &cq)->contract += run(&ag, (int)f32, &p, &rs[f32]);
                (void)run(&ac, (int)f32, &p, &rr);
                (void)run(&ak, (int)f32, &p, &rk);
                judge(f32 ? &cf : &cq, "grid scene", &m, (int)f32, &p, &rs[f32], &rr);
                judge(f32 ? &kf : &kq, "grid vs kd scene", &m, (int)f32, &p, &rs[f32], &rk);
            }
            for (i = 0; i < LT_LANES; i++) {
                double d[3], t;
                int32_t id;
                x = tx + (uint32_t)(i % 4);
                y = ty + (uint32_t)(i / 4);
                if (!LTT_ON(p.k, i) || (x % 2) != 0 || (y % 2) != 0)
                    continue;
                lt_camera_dir(&cam, x, y, d);
                id = lt_ref_trace(&s, cam.eye, d, &t);
                dn++;
                dsame[0] += rs[0].id[i] == id;
#if LT_CFG_FLOAT32
                dsame[1] += rs[1].id[i] == id;
#endif
            }
        }
    snprintf(what, sizeof what, "lt_grid_trace16_q16 vs chunks, %s %ux%u camera", name, res, res);
    cmp_print(&cq, what);
    snprintf(what, sizeof what, "lt_grid_trace16_q16 vs lt_kd_trace16_q16, %s %ux%u camera", name,
             res, res);
    cmp_print(&kq, what);
#if LT_CFG_FLOAT32
    snprintf(what, sizeof what, "lt_grid_trace16_f32 vs chunks, %s %ux%u camera", name, res, res);
    cmp_print(&cf, what);
    snprintf(what, sizeof what, "lt_grid_trace16_f32 vs lt_kd_trace16_f32, %s %ux%u camera", name,
             res, res);
    cmp_print(&kf, what);
#endif
    ltt_report("grid %s vs double brute force (lt_ref_trace, %lu pixels): same triangle q16 "
               "%.3f%%, f32 %.3f%%\n",
               name, dn, 100.0 * (double)dsame[0] / (double)dn,
               LT_CFG_FLOAT32 ? 100.0 * (double)dsame[1] / (double)dn : 0.0);
    cmp_assert(&cq, 0.9999);
    cmp_assert(&kq, 0.9999);
#if LT_CFG_FLOAT32
    cmp_assert(&cf, 0.9999);
    cmp_assert(&kf, 0.9999);
#endif
    assert_true((double)dsame[0] >= 0.999 * (double)dn);
#if LT_COST_MODE == LT_COST_SIM
    {
        uint64_t nd, tr, trr, cy, rays = 0, npk = 0, nd1, tr1, trr1, cy1;
        unsigned f32;
        lt_diag_t d2;
        assert_int_equal(lt_sim_init(lt_sim_machine_find("lrb16"), NULL, NULL, &d2), 0);
        for (f32 = 0; f32 < 2; f32++) {
            rays = npk = 0;
            ctr_begin();
            for (ty = 0; ty < res; ty += 4)
                for (tx = 0; tx < res; tx += 4) {
                    pk_t p;
                    lt_hit16_t h;
                    (void)cam_packet(&cam, tx, ty, &p);
                    rays += lt__popcount32(p.k);
                    npk++;
                    if (!f32)
                        (void)lt_grid_trace16_q16(&gp.q, &p.q, p.k, &h);
#if LT_CFG_FLOAT32
                    else
                        (void)lt_grid_trace16_f32(&gp.f, &p.f, p.k, &h);
#endif
                }
            ctr_end(&nd, &tr, &trr, &cy);
            ctr_begin();
            for (ty = 0; ty < res; ty += 4)
                for (tx = 0; tx < res; tx += 4) {
                    pk_t p;
                    lt_hit16_t h;
                    (void)cam_packet(&cam, tx, ty, &p);
                    for (i = 0; i < LT_LANES; i++) {
                        pk_t q = p;
                        if (!LTT_ON(p.k, i))
                            continue;
                        if (!f32)
                            (void)lt_grid_trace16_q16(&gp.q, &q.q, (lt_mask16_t)(1u << i), &h);
#if LT_CFG_FLOAT32
                        else
                            (void)lt_grid_trace16_f32(&gp.f, &q.f, (lt_mask16_t)(1u << i), &h);
#endif
                    }
                }
            ctr_end(&nd1, &tr1, &trr1, &cy1);
            ltt_report("grid %s %s %ux%u (lrb16): packets: %.2f cells (lane groups) and %.2f "
                       "triangle tests per packet, %.2f ray-triangle tests per ray, %.0f cycles "
                       "per ray; rays alone: %.2f cells and %.2f triangle tests per ray, %.0f "
                       "cycles per ray\n",
                       name, f32 ? "f32" : "q16", res, res, (double)nd / (double)npk,
                       (double)tr / (double)npk, (double)trr / (double)rays,
                       (double)cy / (double)rays, (double)nd1 / (double)rays,
                       (double)tr1 / (double)rays, (double)cy1 / (double)rays);
#if !LT_CFG_FLOAT32
            break;
#endif
        }
        lt_sim_shutdown();
    }
#else
    ltt_report("grid %s: per-ray cell and triangle-test counts are printed by the sim build "
               "(build/sim/test_grid)\n",
               name);
#endif
    g_free_pair(&gp);
    kd_free_pair(&kp);
    mesh_free(&m);
    lt_scene_free(&s);
}

static void test_grid_teapot(void **state)
{
    (void)state;
    scene_run("scenes/teapot.obj", "teapot", 256 / CAM_SCALE, 1);
}

static void test_grid_bunny(void **state)
{
    (void)state;
    scene_run("../shared/scenes/bunny.obj", "bunny", 128 / CAM_SCALE, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_grid_size_and_arena),
        cmocka_unit_test(test_grid_random),
        cmocka_unit_test(test_grid_edge_cases),
        cmocka_unit_test(test_degenerate_rays),
        cmocka_unit_test(test_grid_teapot),
        cmocka_unit_test(test_grid_bunny),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
