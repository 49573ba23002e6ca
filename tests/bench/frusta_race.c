/* frusta_race.c - soft-shadow rays per second, single thread, same rays in the same run: lanetrace
 * multi-frusta (S-Frusta), lanetrace 16-ray packets (S-Packet) and Embree 3 rtcOccluded16 (one
 * packet per pixel: its 16 light samples), after lanetrace's primary pass of the scene's view
 * (lt_ss_view_for). Prints Mrays/s (median of --runs), the ratios, and how often Embree's
 * occlusion bits agree with lanetrace's (float vs s15.16 and two-sided vs back-face culling make
 * a few samples differ). Embree is linked only into this benchmark. Host only; docs/frusta.md.
 * Usage: frusta-race --mesh PATH [--res N] [--runs N] [--num q16|f32] [--leaf N] [--cull LIST]
 */
#include "render/lt_softshadow.h"
#include "cli/lt_cliutil.h"

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

int main(int argc, char **argv)
{
    const char *mesh_path = NULL;
    uint32_t res = 256, leaf = 8, flags = LT_FRUSTA_BACKFACE | LT_FRUSTA_CORNER | LT_FRUSTA_CR;
    int runs = 3, a, run, f32 = 0;
    lt_mesh_t m;
    lt_scene_t sc;
    lt_camera_t cam;
    lt_ss_light_t light;
    lt_ss_opts_t o;
    lt_ss_view_t view;
    lt_softshadow_t *ss;
    lt_ss_counts_t cnt;
    lt_diag_t diag;
    double tf[16], tp[16], te[16], *org, up[3] = {0, 1, 0}, samp[16][16][3];
    uint8_t *lit;
    uint16_t *eocc;
    const uint16_t *locc;
    RTCDevice dev;
    RTCScene scene;
    RTCGeometry g;
    float *vb;
    unsigned *ib;
    uint32_t i, x, y;
    uint64_t agree = 0, total = 0, eo = 0;
    int has_view;

    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--mesh") == 0 && a + 1 < argc)
            mesh_path = argv[++a];
        else if (strcmp(argv[a], "--res") == 0 && a + 1 < argc)
            res = (uint32_t)atoi(argv[++a]);
        else if (strcmp(argv[a], "--runs") == 0 && a + 1 < argc)
            runs = atoi(argv[++a]);
        else if (strcmp(argv[a], "--leaf") == 0 && a + 1 < argc)
            leaf = (uint32_t)atoi(argv[++a]);
        else if (strcmp(argv[a], "--num") == 0 && a + 1 < argc)
            f32 = strcmp(argv[++a], "f32") == 0;
        else if (strcmp(argv[a], "--cull") == 0 && a + 1 < argc) {
            const char *c = argv[++a];
            flags = 0;
            for (; strcmp(c, "none") != 0 && *c != '\0'; c++)
                flags |= *c == 'b' ? LT_FRUSTA_BACKFACE
                                   : (*c == 'c' ? LT_FRUSTA_CORNER : (*c == 'r' ? LT_FRUSTA_CR : 0u));
        } else {
            fprintf(stderr, "usage: frusta-race --mesh PATH [--res N] [--runs 1..15] [--num q16|f32] "
                            "[--leaf N] [--cull LIST]\n");
            return 2;
        }
    }
    if (mesh_path == NULL || res < 4 || res > 8192 || runs < 1 || runs > 15 || leaf < 1 ||
        leaf > LT_BVH_MAX_LEAF) {
        fprintf(stderr, "frusta-race: --mesh PATH, --res 4..8192, --runs 1..15, --leaf 1..%d\n",
                LT_BVH_MAX_LEAF);
        return 2;
    }
    /* flush denormals on both sides, as embree_race does */
    _mm_setcsr(_mm_getcsr() | 0x8040u);
    has_view = lt_ss_view_for(mesh_path, &view);
    if (lt_mesh_load(mesh_path, &m, &diag) != 0) {
        fprintf(stderr, "frusta-race: %s\n", diag.msg);
        return 1;
    }
    if ((!has_view || view.ground) && lt_ss_add_ground(&m, 0.6, &diag) != 0) {
        fprintf(stderr, "frusta-race: %s\n", diag.msg);
        return 1;
    }
    if (lt_scene_prepare(&m, &sc, &diag) != 0) {
        fprintf(stderr, "frusta-race: %s\n", diag.msg);
        return 1;
    }
    if (has_view && view.has_camera) {
        if (lt_camera_look(&sc, view.eye, view.target, up, view.fov, res, res, &cam, &diag) != 0) {
            fprintf(stderr, "frusta-race: %s\n", diag.msg);
            return 1;
        }
    } else {
        lt_camera_default(&sc, res, res, &cam);
    }
    if (!has_view) {
        view.light[0] = 0.5 * (m.lo[0] + m.hi[0]);
        view.light[1] = m.hi[1] + (m.hi[1] - m.lo[1]);
        view.light[2] = 0.5 * (m.lo[2] + m.hi[2]);
        view.size = 0.2 * (m.hi[0] - m.lo[0]);
    }
    if (lt_ss_light_square(&sc, view.light, view.size, &light, &diag) != 0) {
        fprintf(stderr, "frusta-race: %s\n", diag.msg);
        return 1;
    }
    lt_ss_opts_default(&sc, &o);
    o.path = lt_paths_find(f32 ? "f32" : "q16", LT_PATHS_FRUSTA);
    o.leaf = leaf;
    o.flags = flags;
    ss = lt_ss_create(&sc, &cam, &light, &o, &diag);
    if (ss == NULL) {
        fprintf(stderr, "frusta-race: %s\n", diag.msg);
        return 1;
    }
    lt_ss_primary(ss);
    for (run = 0; run < runs; run++) {
        double t0 = lt_now_s();
        lt_ss_shadows_packet(ss);
        tp[run] = lt_now_s() - t0;
        t0 = lt_now_s();
        lt_ss_shadows_frusta(ss);
        tf[run] = lt_now_s() - t0;
    }
    lt_ss_counts(ss, &cnt);

    /* Embree: the same triangles (float vertices of the scaled scene), the same rays */
    dev = rtcNewDevice("threads=1");
    scene = rtcNewScene(dev);
    g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                 (size_t)sc.ntris * 3);
    ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                 3 * sizeof(unsigned), sc.ntris);
    for (i = 0; i < sc.ntris * 9u; i++)
        vb[i] = (float)sc.vd[i];
    for (i = 0; i < sc.ntris * 3u; i++)
        ib[i] = i;
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
    rtcCommitScene(scene);
    org = malloc((size_t)res * res * 3 * sizeof(double));
    lit = malloc((size_t)res * res);
    eocc = calloc((size_t)res * res, sizeof(uint16_t));
    if (org == NULL || lit == NULL || eocc == NULL) {
        fprintf(stderr, "frusta-race: out of memory\n");
        return 1;
    }
    lt_ss_origins(ss, org, lit);
    for (i = 0; i < 16; i++) {
        unsigned j;
        for (j = 0; j < 16; j++)
            lt_ss_sample_point(ss, i, j, samp[i][j]);
    }
    for (run = 0; run < runs; run++) {
        struct RTCIntersectContext ctx;
        double t0 = lt_now_s();
        rtcInitIntersectContext(&ctx);
        for (y = 0; y < res; y++)
            for (x = 0; x < res; x++) {
                size_t q = (size_t)y * res + x;
                struct RTCRay16 ray;
                /* valid[] must be 64-byte aligned (Embree reads it with aligned vector loads): the union
               takes the alignment of Embree's 64-byte aligned ray block */
            union {
                struct RTCRay16 align;
                int v[16];
            } vu;
            int *valid = vu.v, l;
                unsigned s = (x & 3u) + 4u * (y & 3u), oc = 0;
                if (!lit[q])
                    continue;
                for (l = 0; l < 16; l++) {
                    valid[l] = -1;
                    ray.org_x[l] = (float)org[q * 3];
                    ray.org_y[l] = (float)org[q * 3 + 1];
                    ray.org_z[l] = (float)org[q * 3 + 2];
                    /* unnormalized: the segment to the sample point, stopped 2^-10 short */
                    ray.dir_x[l] = (float)(samp[s][l][0] - org[q * 3]);
                    ray.dir_y[l] = (float)(samp[s][l][1] - org[q * 3 + 1]);
                    ray.dir_z[l] = (float)(samp[s][l][2] - org[q * 3 + 2]);
                    ray.tnear[l] = 0.0f;
                    ray.tfar[l] = 1.0f - 1.0f / 1024.0f;
                    ray.time[l] = 0.0f;
                    ray.mask[l] = 0xFFFFFFFFu;
                    ray.id[l] = 0;
                    ray.flags[l] = 0;
                }
                rtcOccluded16(valid, scene, &ctx, &ray);
                for (l = 0; l < 16; l++)
                    oc |= (ray.tfar[l] < 0.0f ? 1u : 0u) << l;
                eocc[q] = (uint16_t)oc;
            }
        te[run] = lt_now_s() - t0;
    }
    locc = lt_ss_occlusion(ss, LT_SS_FRUSTA);
    for (i = 0; i < res * res; i++)
        if (lit[i]) {
            unsigned j;
            for (j = 0; j < 16; j++) {
                total++;
                agree += ((locc[i] ^ eocc[i]) >> j & 1u) == 0;
            }
            eo += lt__popcount32(eocc[i]);
        }
    {
        double mf = median(tf, runs), mp = median(tp, runs), me = median(te, runs);
        double n = (double)cnt.shadow_rays;
        printf("scene     %s: %u triangles, %ux%u, %s, frusta leaf %u, culling %s%s%s, %llu shadow "
               "rays (16 per lit pixel), median of %d runs, one thread\n",
               mesh_path, sc.ntris, res, res, f32 ? "float32" : "s15.16", leaf,
               flags & LT_FRUSTA_BACKFACE ? "b" : "", flags & LT_FRUSTA_CORNER ? "c" : "",
               flags & LT_FRUSTA_CR ? "r" : "", (unsigned long long)cnt.shadow_rays, runs);
        printf("Embree rtcOccluded16 (pixel)   %8.2f Mrays/s (%llu occluded)\n", n / me / 1e6,
               (unsigned long long)eo);
        printf("lanetrace S-Packet             %8.2f Mrays/s = %.3fx Embree\n", n / mp / 1e6,
               me / mp);
        printf("lanetrace S-Frusta             %8.2f Mrays/s = %.3fx Embree = %.2fx S-Packet "
               "(%llu occluded)\n", n / mf / 1e6, me / mf, mp / mf,
               (unsigned long long)cnt.occluded);
        printf("agreement Embree vs lanetrace occlusion bits: %.4f%% of %llu samples (Embree is "
               "two-sided float; lanetrace %s)\n",
               total != 0 ? 100.0 * (double)agree / (double)total : 100.0,
               (unsigned long long)total,
               flags & LT_FRUSTA_BACKFACE ? "culls back faces" : "two-sided");
    }
    free(org);
    free(lit);
    free(eocc);
    rtcReleaseScene(scene);
    rtcReleaseDevice(dev);
    lt_ss_free(ss);
    lt_scene_free(&sc);
    lt_mesh_free(&m);
    return 0;
}
