/* lt_trace_main.c - trace a mesh with 16-ray packets through the chunk scene, in s15.16 and float32,
 * and measure the error of each path against the double-precision reference. Built twice from this
 * one source: build/host/lt-trace (LT_COST_OFF: native speed, wall time) and build/sim/lt-sim
 * (LT_COST_SIM: the same kernels charged to a machine model, with the cycle report).
 * Host only. Exit codes: 0 ok, 1 input or runtime error, 2 usage.
 */
#include "lt/lt.h"
#include "lt_mesh.h"
#include "lt_scene.h"
#if LT_COST_MODE == LT_COST_SIM
#include "lt_sim.h"
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifndef LT_DEFAULT_SCENE
#define LT_DEFAULT_SCENE "scenes/teapot.obj"
#endif

typedef struct opts {
    const char *scene, *machine, *l1, *l2, *json, *num;
    uint32_t w, h;
    int repeat, ref, quiet;
} opts_t;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: %s [options]\n"
            "  --scene PATH     mesh to trace (default " LT_DEFAULT_SCENE ")\n"
            "  --res WxH|N      image size in pixels (default 128x128; at most 8192 per side)\n"
            "  --num q16|f32|both  numeric path (default both)\n"
            "  --repeat N       trace the frame N times (timing; default 1)\n"
            "  --no-ref         skip the double-precision reference and error figures\n"
#if LT_COST_MODE == LT_COST_SIM
            "  --machine NAME   machine model: lrb16 (default) or mcu-m4\n"
            "  --l1 S:W:B       override the L1 cache (sets:ways:line)\n"
            "  --l2 S:W:B       override the L2 cache\n"
            "  --json PATH      also write the cycle reports as JSON\n"
#endif
            "  -q               print only the summary lines\n"
            "  --help           this text\n",
            LT_COST_MODE == LT_COST_SIM ? "lt-sim" : "lt-trace");
}

static int parse_res(const char *s, uint32_t *w, uint32_t *h)
{
    unsigned long a, b;
    char *end;
    a = strtoul(s, &end, 10);
    if (*end == 'x') {
        b = strtoul(end + 1, &end, 10);
    } else {
        b = a;
    }
    if (*end != '\0' || a == 0 || b == 0 || a > 8192 || b > 8192)
        return -1;
    *w = (uint32_t)a;
    *h = (uint32_t)b;
    return 0;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Per-pixel results of one path. */
typedef struct image {
    int32_t *id;
    double *t;
} image_t;

static void trace_q16(const lt_scene_t *s, const lt_camera_t *c, const lt_aabb_q16_t *boxes,
                      image_t *img)
{
    uint32_t tx, ty;
    for (ty = 0; ty < c->height; ty += 4)
        for (tx = 0; tx < c->width; tx += 4) {
            static lt_ray16_q16_t r;
            lt_hit16_t hit;
            lt_mask16_t k;
            int i;
            lt_phase_t prev = LT_PHASE_ENTER(SETUP);
            k = lt_camera_packet_q16(c, tx, ty, &r);
            LT_EVENT(RAYS, lt__popcount32(k));
            LT_PHASE_LEAVE(prev);
            lt_chunks_trace16_q16(s->tq, s->ntris, boxes, &r, k, &hit);
            for (i = 0; i < LT_LANES; i++) {
                uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
                if (((k >> i) & 1u) == 0)
                    continue;
                img->id[y * c->width + x] = hit.id.l[i];
                img->t[y * c->width + x] = (double)r.tmax.l[i] / 65536.0;
            }
        }
}

static void trace_f32(const lt_scene_t *s, const lt_camera_t *c, const lt_aabb_f32_t *boxes,
                      image_t *img)
{
    uint32_t tx, ty;
    for (ty = 0; ty < c->height; ty += 4)
        for (tx = 0; tx < c->width; tx += 4) {
            static lt_ray16_f32_t r;
            lt_hit16_t hit;
            lt_mask16_t k;
            int i;
            lt_phase_t prev = LT_PHASE_ENTER(SETUP);
            k = lt_camera_packet_f32(c, tx, ty, &r);
            LT_EVENT(RAYS, lt__popcount32(k));
            LT_PHASE_LEAVE(prev);
            lt_chunks_trace16_f32(s->tf, s->ntris, boxes, &r, k, &hit);
            for (i = 0; i < LT_LANES; i++) {
                uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
                if (((k >> i) & 1u) == 0)
                    continue;
                img->id[y * c->width + x] = hit.id.l[i];
                img->t[y * c->width + x] = (double)r.tmax.l[i];
            }
        }
}

/* FNV-1a over ids and distance bits: equal across host and sim builds (the hooks never change a
 * result), printed so that tests can compare them. */
static uint32_t image_hash(const image_t *img, uint32_t n)
{
    uint32_t h = 2166136261u, i;
    for (i = 0; i < n; i++) {
        uint64_t tb;
        unsigned char b[12];
        int j;
        memcpy(&tb, &img->t[i], sizeof tb);
        memcpy(b, &img->id[i], 4);
        memcpy(b + 4, &tb, 8);
        for (j = 0; j < 12; j++) {
            h ^= b[j];
            h *= 16777619u;
        }
    }
    return h;
}

/* Error of one path against the reference: id agreement, depth RMSE and max over common hits. */
static void compare(const char *name, const image_t *a, const image_t *ref, uint32_t n,
                    double radius, char *json, size_t jlen)
{
    uint32_t i, same = 0, both = 0, within = 0;
    double se = 0.0, mx = 0.0, tol = 1e-4 * radius;
    for (i = 0; i < n; i++) {
        same += a->id[i] == ref->id[i];
        if (a->id[i] >= 0 && ref->id[i] >= 0) {
            double e = fabs(a->t[i] - ref->t[i]);
            both++;
            se += e * e;
            if (e > mx)
                mx = e;
            within += e <= tol;
        }
    }
    printf("accuracy  %-4s vs double: same triangle %.3f%% of %u pixels, depth RMSE %.3g, max %.3g "
           "(scene radius %.1f), %.2f%% of common hits within 1e-4 radius\n",
           name, 100.0 * same / n, n, both ? sqrt(se / both) : 0.0, mx, radius,
           both ? 100.0 * within / both : 100.0);
    snprintf(json, jlen,
             "{\"accuracy\":{\"path\":\"%s\",\"same_triangle_pct\":%.4f,\"depth_rmse\":%.6g,"
             "\"depth_max_err\":%.6g,\"scene_radius\":%.6g}}",
             name, 100.0 * same / n, both ? sqrt(se / both) : 0.0, mx, radius);
}

int main(int argc, char **argv)
{
    opts_t o;
    lt_mesh_t mesh;
    lt_scene_t sc;
    lt_camera_t cam;
    char err[512], extra[512];
    image_t img[2], ref;
    uint32_t npix, i;
    int a, path, status = 0;
    const char *names[2] = {"q16", "f32"};

    memset(&o, 0, sizeof o);
    o.scene = LT_DEFAULT_SCENE;
    o.machine = "lrb16";
    o.num = "both";
    o.w = o.h = 128;
    o.repeat = 1;
    o.ref = 1;
    for (a = 1; a < argc; a++) {
        const char *v = a + 1 < argc ? argv[a + 1] : NULL;
        if (strcmp(argv[a], "--help") == 0 || strcmp(argv[a], "-h") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(argv[a], "-q") == 0) {
            o.quiet = 1;
        } else if (strcmp(argv[a], "--no-ref") == 0) {
            o.ref = 0;
        } else if (v == NULL) {
            fprintf(stderr, "%s: unknown option or missing value\n", argv[a]);
            usage(stderr);
            return 2;
        } else if (strcmp(argv[a], "--scene") == 0) {
            o.scene = v;
            a++;
        } else if (strcmp(argv[a], "--res") == 0) {
            if (parse_res(v, &o.w, &o.h) != 0) {
                fprintf(stderr, "--res %s: expected WxH or N with 1 <= W, H <= 8192\n", v);
                return 2;
            }
            a++;
        } else if (strcmp(argv[a], "--num") == 0) {
            if (strcmp(v, "q16") != 0 && strcmp(v, "f32") != 0 && strcmp(v, "both") != 0) {
                fprintf(stderr, "--num %s: expected q16, f32 or both\n", v);
                return 2;
            }
            o.num = v;
            a++;
        } else if (strcmp(argv[a], "--repeat") == 0) {
            o.repeat = atoi(v);
            if (o.repeat < 1 || o.repeat > 100000) {
                fprintf(stderr, "--repeat %s: expected 1..100000\n", v);
                return 2;
            }
            a++;
#if LT_COST_MODE == LT_COST_SIM
        } else if (strcmp(argv[a], "--machine") == 0) {
            o.machine = v;
            a++;
        } else if (strcmp(argv[a], "--l1") == 0) {
            o.l1 = v;
            a++;
        } else if (strcmp(argv[a], "--l2") == 0) {
            o.l2 = v;
            a++;
        } else if (strcmp(argv[a], "--json") == 0) {
            o.json = v;
            a++;
#endif
        } else {
            fprintf(stderr, "%s: unknown option\n", argv[a]);
            usage(stderr);
            return 2;
        }
    }
#if LT_COST_MODE == LT_COST_SIM
    {
        const lt_machine_t *m = lt_sim_machine_find(o.machine);
        if (m == NULL) {
            fprintf(stderr, "--machine %s: unknown machine (known: lrb16, mcu-m4)\n", o.machine);
            return 2;
        }
        if (lt_sim_init(m, o.l1, o.l2, err, sizeof err) != 0) {
            fprintf(stderr, "%s\n", err);
            return 2;
        }
    }
#endif
    if (lt_mesh_load(o.scene, &mesh, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    if (lt_scene_prepare(&mesh, &sc, err, sizeof err) != 0) {
        fprintf(stderr, "%s: %s\n", o.scene, err);
        lt_mesh_free(&mesh);
        return 1;
    }
    lt_camera_default(&sc, o.w, o.h, &cam);
    npix = o.w * o.h;
    if (!o.quiet)
        printf("scene     %s: %u triangles, scale %g (file units -> s15.16 units), radius %.1f, "
               "%ux%u pixels, %u packets\n",
               o.scene, sc.ntris, sc.scale, sc.radius, o.w, o.h,
               ((o.w + 3) / 4) * ((o.h + 3) / 4));
    ref.id = malloc(npix * sizeof(int32_t));
    ref.t = malloc(npix * sizeof(double));
    for (path = 0; path < 2; path++) {
        img[path].id = malloc(npix * sizeof(int32_t));
        img[path].t = malloc(npix * sizeof(double));
    }
    if (o.ref) {
        for (i = 0; i < npix; i++) {
            double d[3];
            lt_camera_dir(&cam, i % o.w, i / o.w, d);
            ref.id[i] = lt_ref_trace(&sc, cam.eye, d, &ref.t[i]);
        }
    }
    for (path = 0; path < 2; path++) {
        size_t nb = LT_CHUNK_COUNT(sc.ntris);
        double t0, dt;
        int rep;
        if (strcmp(o.num, "both") != 0 && strcmp(o.num, names[path]) != 0)
            continue;
#if LT_COST_MODE == LT_COST_SIM
        lt_sim_shutdown();
        lt_sim_init(lt_sim_machine_find(o.machine), o.l1, o.l2, err, sizeof err);
        /* fixed simulated addresses: cache behaviour independent of the host allocator */
        lt_sim_region(path == 0 ? (const void *)sc.tq : (const void *)sc.tf,
                      sc.ntris * (path == 0 ? sizeof *sc.tq : sizeof *sc.tf), 0x10000000u);
#endif
        t0 = now_s();
        if (path == 0) {
            lt_aabb_q16_t *boxes = malloc(nb * sizeof *boxes);
#if LT_COST_MODE == LT_COST_SIM
            lt_sim_region(boxes, nb * sizeof *boxes, 0x20000000u);
#endif
            lt_chunks_build_q16(sc.tq, sc.ntris, boxes);
            for (rep = 0; rep < o.repeat; rep++)
                trace_q16(&sc, &cam, boxes, &img[0]);
            free(boxes);
        } else {
            lt_aabb_f32_t *boxes = malloc(nb * sizeof *boxes);
#if LT_COST_MODE == LT_COST_SIM
            lt_sim_region(boxes, nb * sizeof *boxes, 0x20000000u);
#endif
            lt_chunks_build_f32(sc.tf, sc.ntris, boxes);
            for (rep = 0; rep < o.repeat; rep++)
                trace_f32(&sc, &cam, boxes, &img[1]);
            free(boxes);
        }
        dt = now_s() - t0;
        printf("time      %-4s %.3f ms for %d frame(s) of %u rays (%s, %.2f Mrays/s host)\n",
               names[path], 1e3 * dt, o.repeat, npix,
               LT_COST_MODE == LT_COST_SIM ? "counted" : "native",
               (double)npix * o.repeat / dt / 1e6);
        printf("result    %-4s hash 0x%08x\n", names[path], image_hash(&img[path], npix));
        extra[0] = '\0';
        if (o.ref)
            compare(names[path], &img[path], &ref, npix, sc.radius, extra, sizeof extra);
#if LT_COST_MODE == LT_COST_SIM
        {
            char title[256];
            snprintf(title, sizeof title, "%s %ux%u %s, chunk scene, %d frame(s)", o.scene, o.w, o.h,
                     names[path], o.repeat);
            if (!o.quiet)
                lt_sim_report_text(stdout, title, (uint64_t)npix * (uint64_t)o.repeat);
            if (o.json != NULL) {
                char p[1024];
                snprintf(p, sizeof p, "%s%s%s", o.json, strcmp(o.num, "both") == 0 ? "." : "",
                         strcmp(o.num, "both") == 0 ? names[path] : "");
                if (lt_sim_report_json(p, title, (uint64_t)npix * (uint64_t)o.repeat,
                                       extra[0] ? extra : NULL, err, sizeof err) != 0) {
                    fprintf(stderr, "%s\n", err);
                    status = 1;
                } else if (!o.quiet) {
                    printf("json      %s\n", p);
                }
            }
        }
#endif
    }
#if LT_COST_MODE == LT_COST_SIM
    lt_sim_shutdown();
#endif
    for (path = 0; path < 2; path++) {
        free(img[path].id);
        free(img[path].t);
    }
    free(ref.id);
    free(ref.t);
    lt_scene_free(&sc);
    lt_mesh_free(&mesh);
    return status;
}
