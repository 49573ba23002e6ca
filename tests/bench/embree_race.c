/* embree_race.c - lanetrace's native build against Embree 3 (Debian libembree-dev), single thread,
 * the same rays in the same run: 1024x1024 (by default) primary rays of the benchmark view
 * (docs/results.md, "The benchmark view") as single rays and 16-ray packets over 4x4 tiles, and
 * shadow rays from each primary hit to a point light. Prints Mrays/s of each and the lanetrace /
 * Embree ratios. Embree is linked only into this benchmark. Host only; `make bench` runs it.
 * Usage: embree-race [--mesh PATH] [--res N] [--runs N] [--structure NAME]
 */
#include "io/lt_mesh.h"
#include "cli/lt_cliutil.h"
#include "render/lt_render.h"
#include "render/lt_scene.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <xmmintrin.h>

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return v[n / 2];
}

typedef struct race {
    const lt_scene_t *sc;
    lt_camera_t cam;
    RTCScene scene;
    float *dirs;       /* 3 floats per pixel */
    unsigned *eid;     /* Embree primary hit ids per pixel */
    float *et;         /* Embree primary t per pixel */
    float light[3];
} race_t;

static void embree_primary1(race_t *r)
{
    uint32_t i, n = r->cam.width * r->cam.height;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (i = 0; i < n; i++) {
        struct RTCRayHit rh;
        memset(&rh, 0, sizeof rh);
        rh.ray.org_x = (float)r->cam.eye[0];
        rh.ray.org_y = (float)r->cam.eye[1];
        rh.ray.org_z = (float)r->cam.eye[2];
        rh.ray.dir_x = r->dirs[3 * i];
        rh.ray.dir_y = r->dirs[3 * i + 1];
        rh.ray.dir_z = r->dirs[3 * i + 2];
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = INFINITY;
        rh.ray.mask = 0xFFFFFFFFu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(r->scene, &ctx, &rh);
        r->eid[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? RTC_INVALID_GEOMETRY_ID : rh.hit.primID;
        r->et[i] = rh.ray.tfar;
    }
}

/* 4x4 tiles: lane l = pixel (tx + l % 4, ty + l / 4). */
static void embree_primary16(race_t *r)
{
    uint32_t tx, ty, W = r->cam.width, H = r->cam.height;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (ty = 0; ty < H; ty += 4)
        for (tx = 0; tx < W; tx += 4) {
            struct RTCRayHit16 rh;
            /* valid[] must be 64-byte aligned (Embree reads it with aligned vector loads): the union
               takes the alignment of Embree's 64-byte aligned ray block */
            union {
                struct RTCRay16 align;
                int v[16];
            } vu;
            int *valid = vu.v, l;
            memset(&rh, 0, sizeof rh);
            for (l = 0; l < 16; l++) {
                uint32_t x = tx + (uint32_t)(l % 4), y = ty + (uint32_t)(l / 4);
                uint32_t p = y * W + x;
                valid[l] = (x < W && y < H) ? -1 : 0;
                if (!valid[l])
                    continue;
                rh.ray.org_x[l] = (float)r->cam.eye[0];
                rh.ray.org_y[l] = (float)r->cam.eye[1];
                rh.ray.org_z[l] = (float)r->cam.eye[2];
                rh.ray.dir_x[l] = r->dirs[3 * p];
                rh.ray.dir_y[l] = r->dirs[3 * p + 1];
                rh.ray.dir_z[l] = r->dirs[3 * p + 2];
                rh.ray.tfar[l] = INFINITY;
                rh.ray.mask[l] = 0xFFFFFFFFu;
                rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect16(valid, r->scene, &ctx, &rh);
            for (l = 0; l < 16; l++) {
                uint32_t x = tx + (uint32_t)(l % 4), y = ty + (uint32_t)(l / 4);
                if (!valid[l])
                    continue;
                r->eid[y * W + x] = rh.hit.geomID[l] == RTC_INVALID_GEOMETRY_ID
                                        ? RTC_INVALID_GEOMETRY_ID : rh.hit.primID[l];
                r->et[y * W + x] = rh.ray.tfar[l];
            }
        }
}

/* Shadow rays from each primary hit towards the light, 4x4 packets; returns occluded count. */
static uint32_t embree_shadow16(race_t *r, uint32_t *nrays)
{
    uint32_t tx, ty, W = r->cam.width, H = r->cam.height, occ = 0, n = 0;
    float eps = (float)(1e-4 * r->sc->radius);
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (ty = 0; ty < H; ty += 4)
        for (tx = 0; tx < W; tx += 4) {
            struct RTCRay16 ray;
            /* valid[] must be 64-byte aligned (Embree reads it with aligned vector loads): the union
               takes the alignment of Embree's 64-byte aligned ray block */
            union {
                struct RTCRay16 align;
                int v[16];
            } vu;
            int *valid = vu.v, l;
            memset(&ray, 0, sizeof ray);
            for (l = 0; l < 16; l++) {
                uint32_t x = tx + (uint32_t)(l % 4), y = ty + (uint32_t)(l / 4), p = y * W + x;
                float o[3], d[3], len;
                uint32_t a;
                valid[l] = (x < W && y < H && r->eid[p] != RTC_INVALID_GEOMETRY_ID) ? -1 : 0;
                if (!valid[l])
                    continue;
                for (a = 0; a < 3; a++) {
                    o[a] = (float)r->cam.eye[a] + r->et[p] * r->dirs[3 * p + a];
                    d[a] = r->light[a] - o[a];
                }
                len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                ray.org_x[l] = o[0];
                ray.org_y[l] = o[1];
                ray.org_z[l] = o[2];
                ray.dir_x[l] = d[0] / len;
                ray.dir_y[l] = d[1] / len;
                ray.dir_z[l] = d[2] / len;
                ray.tnear[l] = eps;
                ray.tfar[l] = len;
                ray.mask[l] = 0xFFFFFFFFu;
                n++;
            }
            rtcOccluded16(valid, r->scene, &ctx, &ray);
            for (l = 0; l < 16; l++)
                occ += valid[l] && ray.tfar[l] < 0.0f;
        }
    *nrays = n;
    return occ;
}

int main(int argc, char **argv)
{
    const char *mesh_path = "scenes/teapot.obj", *structure = "bvh";
    uint32_t res = 1024, i;
    int runs = 5, a, k;
    lt_mesh_t m;
    lt_scene_t sc;
    race_t r;
    lt_diag_t diag;
    RTCDevice dev;
    RTCGeometry g;
    float *vb;
    unsigned *ib;
    double t0, build_ms, times[16], e1, e16, es16;
    uint32_t shadow_n = 0, occ = 0;
    lt_frame_t fr;

    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--mesh") == 0 && a + 1 < argc)
            mesh_path = argv[++a];
        else if (strcmp(argv[a], "--res") == 0 && a + 1 < argc)
            res = (uint32_t)atoi(argv[++a]);
        else if (strcmp(argv[a], "--runs") == 0 && a + 1 < argc)
            runs = atoi(argv[++a]);
        else if (strcmp(argv[a], "--structure") == 0 && a + 1 < argc)
            structure = argv[++a];
        else {
            fprintf(stderr, "usage: embree-race [--mesh PATH] [--res N] [--runs 1..15] "
                            "[--structure NAME]\n");
            return 2;
        }
    }
    if (res < 4 || res > 8192 || runs < 1 || runs > 15) {
        fprintf(stderr, "embree-race: --res 4..8192, --runs 1..15\n");
        return 2;
    }
    /* flush denormals on both sides (docs/results.md, "The benchmark view") */
    /* MXCSR bits 15 (FTZ) and 6 (DAZ), set directly: the header macros trip -Wsign-conversion */
    _mm_setcsr(_mm_getcsr() | 0x8040u);
    if (lt_mesh_load(mesh_path, &m, &diag) != 0 ||
        lt_scene_prepare(&m, &sc, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return 1;
    }
    memset(&r, 0, sizeof r);
    r.sc = &sc;
    lt_camera_default(&sc, res, res, &r.cam);
    r.dirs = malloc((size_t)res * res * 3 * sizeof(float));
    r.eid = malloc((size_t)res * res * sizeof(unsigned));
    r.et = malloc((size_t)res * res * sizeof(float));
    if (r.dirs == NULL || r.eid == NULL || r.et == NULL ||
        lt_frame_alloc(&fr, res, res, &diag) != 0) {
        fprintf(stderr, "embree-race: out of memory\n");
        return 1;
    }
    for (i = 0; i < res * res; i++) {
        double d[3];
        lt_camera_dir(&r.cam, i % res, i / res, d);
        r.dirs[3 * i] = (float)d[0];
        r.dirs[3 * i + 1] = (float)d[1];
        r.dirs[3 * i + 2] = (float)d[2];
    }
    {
        /* light at centre + 2 radius normalize(-0.5, 1.5, 0.8): the benchmark view's light */
        double l[3] = {-0.5, 1.5, 0.8}, n = sqrt(0.25 + 2.25 + 0.64);
        for (a = 0; a < 3; a++)
            r.light[a] = (float)(2.0 * sc.radius * l[a] / n);
    }

    dev = rtcNewDevice("threads=1");
    r.scene = rtcNewScene(dev);
    g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                 (size_t)sc.ntris * 3);
    ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                 3 * sizeof(unsigned), sc.ntris);
    for (i = 0; i < sc.ntris * 9; i++)
        vb[i] = (float)sc.vd[i];
    for (i = 0; i < sc.ntris * 3; i++)
        ib[i] = i;
    rtcCommitGeometry(g);
    rtcAttachGeometry(r.scene, g);
    rtcReleaseGeometry(g);
    rtcSetSceneBuildQuality(r.scene, RTC_BUILD_QUALITY_MEDIUM);
    t0 = lt_now_s();
    rtcCommitScene(r.scene);
    build_ms = 1e3 * (lt_now_s() - t0);

    for (k = 0; k < runs; k++) {
        t0 = lt_now_s();
        embree_primary1(&r);
        times[k] = lt_now_s() - t0;
    }
    e1 = (double)res * res / median(times, runs) / 1e6;
    for (k = 0; k < runs; k++) {
        t0 = lt_now_s();
        embree_primary16(&r);
        times[k] = lt_now_s() - t0;
    }
    e16 = (double)res * res / median(times, runs) / 1e6;
    for (k = 0; k < runs; k++) {
        t0 = lt_now_s();
        occ = embree_shadow16(&r, &shadow_n);
        times[k] = lt_now_s() - t0;
    }
    es16 = (double)shadow_n / median(times, runs) / 1e6;

    printf("scene %s: %u triangles, %ux%u rays, single thread, median of %d\n", mesh_path,
           sc.ntris, res, res, runs);
    printf("Embree 3 build %.1f ms (quality medium)\n", build_ms);
    printf("Embree rtcIntersect1           %8.2f Mrays/s\n", e1);
    printf("Embree rtcIntersect16 (4x4)    %8.2f Mrays/s\n", e16);
    printf("Embree rtcOccluded16 shadows   %8.2f Mrays/s (%u rays, %u occluded)\n", es16, shadow_n,
           occ);
    for (a = 0; a < 2; a++) {
        lt_accel_t *acc;
        uint32_t same = 0, sn = 0, so = 0;
        double lp, l1 = 0.0, ls = 0.0, lb;
        double light[3] = {r.light[0], r.light[1], r.light[2]};
        const char *name = a == 0 ? "s15.16 " : "float32";
        t0 = lt_now_s();
        acc = lt_accel_build(&sc, structure, lt_paths_find(a ? "f32" : "q16", LT_PATHS_OBJECT),
                             &diag);
        lb = 1e3 * (lt_now_s() - t0);
        if (acc == NULL) {
            fprintf(stderr, "%s\n", diag.msg);
            return 1;
        }
        printf("lanetrace %s %s: build %.1f ms, %zu bytes\n", name, structure, lb,
               lt_accel_bytes(acc));
        if (strcmp(structure, "chunks") != 0) {
            for (k = 0; k < runs; k++) {
                t0 = lt_now_s();
                lt_render_primary1(&sc, acc, &r.cam, &fr, &diag);
                times[k] = lt_now_s() - t0;
            }
            l1 = (double)res * res / median(times, runs) / 1e6;
        }
        for (k = 0; k < runs; k++) {
            t0 = lt_now_s();
            lt_render_primary(&sc, acc, &r.cam, &fr, NULL);
            times[k] = lt_now_s() - t0;
        }
        lp = (double)res * res / median(times, runs) / 1e6;
        for (i = 0; i < res * res; i++) {
            int eh = r.eid[i] != RTC_INVALID_GEOMETRY_ID;
            same += eh ? (fr.id[i] == (int32_t)r.eid[i]) : (fr.id[i] < 0);
        }
        if (strcmp(structure, "chunks") != 0) {
            for (k = 0; k < runs; k++) {
                t0 = lt_now_s();
                lt_render_shadows(&sc, acc, &r.cam, &fr, light, &sn, &so, NULL, &diag);
                times[k] = lt_now_s() - t0;
            }
            ls = (double)sn / median(times, runs) / 1e6;
            printf("lanetrace %s single rays     %8.2f Mrays/s = %.3fx Embree rtcIntersect1\n",
                   name, l1, l1 / e1);
        }
        printf("lanetrace %s 16-ray packets  %8.2f Mrays/s = %.3fx Embree rtcIntersect16; same "
               "triangle as Embree on %.3f%% of pixels\n",
               name, lp, lp / e16, 100.0 * same / (res * res));
        if (strcmp(structure, "chunks") != 0)
            printf("lanetrace %s shadow packets  %8.2f Mrays/s = %.3fx Embree rtcOccluded16 "
                   "(%u rays, %u occluded)\n",
                   name, ls, ls / es16, sn, so);

        lt_accel_free(acc);
    }
    rtcReleaseScene(r.scene);
    rtcReleaseDevice(dev);
    lt_frame_free(&fr);
    free(r.dirs);
    free(r.eid);
    free(r.et);
    lt_scene_free(&sc);
    lt_mesh_free(&m);
    return 0;
}
