/* frusta_race.c - soft-shadow rays per second, single thread, same rays in the same run: lanetrace
 * multi-frusta (S-Frusta), lanetrace 16-ray packets (S-Packet) and Embree 3 at its best on this
 * machine, after lanetrace's primary pass of the scene's view (lt_ss_view_for). lanetrace runs its
 * shipped defaults (lt_ss_opts_default: the frusta leaf size and the culling set of `lanetrace
 * shadows`) unless --leaf / --cull say otherwise. Embree traces each lit pixel's 16 light samples
 * as one rtcOccluded16 packet, two rtcOccluded8, four rtcOccluded4 or sixteen rtcOccluded1 calls,
 * each with the incoherent and the coherent context flag; every mode gets a warm-up pass and the
 * median of --runs, and the fastest is Embree's best (every mode is printed). Prints Mrays/s, the
 * ratios against Embree's best, and how often Embree's occlusion bits agree with lanetrace's
 * (float vs s15.16 and two-sided vs back-face culling make a few samples differ); --kv adds one
 * "frusta-race: key value ..." line for tests/bench/frusta_race_doc.sh. Embree is linked only
 * into this benchmark. Host only; docs/frusta.md, "Native speed and Embree".
 * Usage: frusta-race --mesh PATH [--res N] [--runs N] [--num q16|f32] [--leaf N] [--cull LIST]
 *        [--kv]
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

/* One lit pixel's 16 samples through Embree as 16 / w packets of w rays (w = 1, 4, 8, 16) from
 * o to each sample point p[i], unnormalized, stopped 2^-10 short; returns the occluded samples. */
static unsigned embree_pixel(RTCScene scene, unsigned w, int coherent, const double o[3],
                             const double p[16][3])
{
    struct RTCIntersectContext ctx;
    unsigned oc = 0, b, l;
    rtcInitIntersectContext(&ctx);
    ctx.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                         : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
#define FR_FILL(R, l, s)                                                                           \
    do {                                                                                           \
        (R).org_x[l] = (float)o[0];                                                                \
        (R).org_y[l] = (float)o[1];                                                                \
        (R).org_z[l] = (float)o[2];                                                                \
        (R).dir_x[l] = (float)(p[s][0] - o[0]);                                                    \
        (R).dir_y[l] = (float)(p[s][1] - o[1]);                                                    \
        (R).dir_z[l] = (float)(p[s][2] - o[2]);                                                    \
        (R).tnear[l] = 0.0f;                                                                       \
        (R).tfar[l] = 1.0f - 1.0f / 1024.0f;                                                       \
        (R).time[l] = 0.0f;                                                                        \
        (R).mask[l] = 0xFFFFFFFFu;                                                                 \
        (R).id[l] = 0;                                                                             \
        (R).flags[l] = 0;                                                                          \
    } while (0)
    /* valid[] must be as aligned as the ray block (Embree loads it with aligned vector loads) */
#define FR_PACKET(W, TYPE, FN)                                                                     \
    for (b = 0; b < 16u / (W); b++) {                                                              \
        union {                                                                                    \
            struct TYPE align;                                                                     \
            int v[W];                                                                              \
        } vu;                                                                                      \
        struct TYPE r;                                                                             \
        for (l = 0; l < (W); l++) {                                                                \
            vu.v[l] = -1;                                                                          \
            FR_FILL(r, l, b * (W) + l);                                                            \
        }                                                                                          \
        FN(vu.v, scene, &ctx, &r);                                                                 \
        for (l = 0; l < (W); l++)                                                                  \
            oc |= (r.tfar[l] < 0.0f ? 1u : 0u) << (b * (W) + l);                                   \
    }
    if (w == 16) {
        FR_PACKET(16, RTCRay16, rtcOccluded16)
    } else if (w == 8) {
        FR_PACKET(8, RTCRay8, rtcOccluded8)
    } else if (w == 4) {
        FR_PACKET(4, RTCRay4, rtcOccluded4)
    } else {
        for (b = 0; b < 16u; b++) {
            struct RTCRay r;
            r.org_x = (float)o[0];
            r.org_y = (float)o[1];
            r.org_z = (float)o[2];
            r.dir_x = (float)(p[b][0] - o[0]);
            r.dir_y = (float)(p[b][1] - o[1]);
            r.dir_z = (float)(p[b][2] - o[2]);
            r.tnear = 0.0f;
            r.tfar = 1.0f - 1.0f / 1024.0f;
            r.time = 0.0f;
            r.mask = 0xFFFFFFFFu;
            r.id = 0;
            r.flags = 0;
            rtcOccluded1(scene, &ctx, &r);
            oc |= (r.tfar < 0.0f ? 1u : 0u) << b;
        }
    }
#undef FR_PACKET
#undef FR_FILL
    return oc;
}

int main(int argc, char **argv)
{
    const char *mesh_path = NULL;
    uint32_t res = 256, leaf = 0, flags = 0;
    int runs = 3, a, run, f32 = 0, kv = 0, seen_cull = 0;
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
    uint16_t *eocc, *eocc_m[8];
    const uint16_t *locc;
    static const unsigned widths[4] = {1, 4, 8, 16};
    double mrate[8];
    uint64_t mocc[8];
    int mi, best = -1;
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
        else if (strcmp(argv[a], "--kv") == 0)
            kv = 1;
        else if (strcmp(argv[a], "--cull") == 0 && a + 1 < argc) {
            /* the letters of `lanetrace shadows --cull` */
            char bad = '?';
            seen_cull = 1;
            if (lt_ss_parse_cull(argv[++a], 1, &flags, &bad) != 0) {
                fprintf(stderr, "frusta-race: --cull: letters b, c, r, f, l, s, t, p or none, "
                                "not '%c'\n", bad);
                return 2;
            }
        } else {
            fprintf(stderr, "usage: frusta-race --mesh PATH [--res N] [--runs 1..15] [--num q16|f32] "
                            "[--leaf N] [--cull LIST] [--kv]\n");
            return 2;
        }
    }
    if (mesh_path == NULL || res < 4 || res > 8192 || runs < 1 || runs > 15 ||
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
    if (leaf != 0)
        o.leaf = leaf;
    if (seen_cull)
        o.flags = flags;
    leaf = o.leaf;
    flags = o.flags;
    ss = lt_ss_create(&sc, &cam, &light, &o, &diag);
    if (ss == NULL) {
        fprintf(stderr, "frusta-race: %s\n", diag.msg);
        return 1;
    }
    lt_ss_primary(ss);
    /* one warm-up pass of each, then the median of runs */
    for (run = -1; run < runs; run++) {
        double t0 = lt_now_s();
        lt_ss_shadows_packet(ss);
        if (run >= 0)
            tp[run] = lt_now_s() - t0;
        t0 = lt_now_s();
        lt_ss_shadows_frusta(ss);
        if (run >= 0)
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
    for (mi = 0; mi < 8; mi++) {
        eocc_m[mi] = calloc((size_t)res * res, sizeof(uint16_t));
        if (eocc_m[mi] == NULL) {
            fprintf(stderr, "frusta-race: out of memory\n");
            return 1;
        }
    }
    if (org == NULL || lit == NULL) {
        fprintf(stderr, "frusta-race: out of memory\n");
        return 1;
    }
    lt_ss_origins(ss, org, lit);
    for (i = 0; i < 16; i++) {
        unsigned j;
        for (j = 0; j < 16; j++)
            lt_ss_sample_point(ss, i, j, samp[i][j]);
    }
    /* Embree's modes: the 16 samples of a pixel as 16 / w packets of w rays, each mode with the
       incoherent and the coherent flag; one warm-up pass, then the median of runs */
    for (mi = 0; mi < 8; mi++) {
        const unsigned w = widths[mi / 2];
        const int coherent = mi % 2;
        for (run = -1; run < runs; run++) {
            double t0 = lt_now_s();
            uint64_t occ = 0;
            for (y = 0; y < res; y++)
                for (x = 0; x < res; x++) {
                    size_t q = (size_t)y * res + x;
                    unsigned sset = (x & 3u) + 4u * (y & 3u), oc;
                    if (!lit[q])
                        continue;
                    oc = embree_pixel(scene, w, coherent, &org[q * 3],
                                      (const double(*)[3])samp[sset]);
                    eocc_m[mi][q] = (uint16_t)oc;
                    occ += lt__popcount32(oc);
                }
            if (run >= 0)
                te[run] = lt_now_s() - t0;
            mocc[mi] = occ;
        }
        mrate[mi] = (double)cnt.shadow_rays / median(te, runs) / 1e6;
        if (best < 0 || mrate[mi] > mrate[best])
            best = mi;
    }
    eocc = eocc_m[best];
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
        double mf = median(tf, runs), mp = median(tp, runs);
        double n = (double)cnt.shadow_rays, eb = mrate[best], lp = n / mp / 1e6, lf = n / mf / 1e6;
        char cull[16];
        unsigned nc = 0, same = 1;
        static const char letters[] = "bcrflstp";
        static const uint32_t bits[] = {LT_FRUSTA_BACKFACE, LT_FRUSTA_CORNER, LT_FRUSTA_CR,
                                        LT_FRUSTA_FS, LT_FRUSTA_LEAFRAY, LT_FRUSTA_SPLIT,
                                        LT_FRUSTA_TRIPAR, LT_FRUSTA_P256};
        for (i = 0; i < 8; i++)
            if (flags & bits[i])
                cull[nc++] = letters[i];
        if (nc == 0) {
            memcpy(cull, "none", 4);
            nc = 4;
        }
        cull[nc] = '\0';
        for (mi = 0; mi < 8; mi++)
            same &= mocc[mi] == mocc[best];
        printf("scene     %s: %u triangles, %ux%u, %s, frusta leaf %u, culling %s, %llu shadow "
               "rays (16 per lit pixel), median of %d runs after a warm-up pass, one thread\n",
               mesh_path, sc.ntris, res, res, f32 ? "float32" : "s15.16", leaf, cull,
               (unsigned long long)cnt.shadow_rays, runs);
        for (mi = 0; mi < 8; mi++)
            printf("Embree rtcOccluded%-2u %-10s %8.2f Mrays/s (%llu occluded)%s\n",
                   widths[mi / 2], mi % 2 ? "coherent" : "incoherent", mrate[mi],
                   (unsigned long long)mocc[mi], mi == best ? "  <- best" : "");
        printf("lanetrace S-Packet             %8.2f Mrays/s = %.3fx Embree's best\n", lp, lp / eb);
        printf("lanetrace S-Frusta             %8.2f Mrays/s = %.3fx Embree's best = %.2fx S-Packet "
               "(%llu occluded)\n", lf, lf / eb, mp / mf, (unsigned long long)cnt.occluded);
        printf("agreement Embree vs lanetrace occlusion bits: %.4f%% of %llu samples (Embree is "
               "two-sided float; lanetrace %s)%s\n",
               total != 0 ? 100.0 * (double)agree / (double)total : 100.0,
               (unsigned long long)total,
               flags & LT_FRUSTA_BACKFACE ? "culls back faces" : "two-sided",
               same ? "" : "; Embree's modes differ in their occluded counts");
        if (kv)
            printf("frusta-race: scene %s path %s res %u leaf %u cull %s rays %llu embree_best "
                   "rtcOccluded%u_%s embree %.4f packet %.4f frusta %.4f agree %.6f "
                   "e1 %.4f e4 %.4f e8 %.4f e16 %.4f\n",
                   mesh_path, f32 ? "f32" : "q16", res, leaf, cull,
                   (unsigned long long)cnt.shadow_rays, widths[best / 2],
                   best % 2 ? "coherent" : "incoherent", eb, lp, lf,
                   total != 0 ? 100.0 * (double)agree / (double)total : 100.0,
                   mrate[0] > mrate[1] ? mrate[0] : mrate[1], mrate[2] > mrate[3] ? mrate[2] : mrate[3],
                   mrate[4] > mrate[5] ? mrate[4] : mrate[5], mrate[6] > mrate[7] ? mrate[6] : mrate[7]);
    }
    free(org);
    free(lit);
    for (mi = 0; mi < 8; mi++)
        free(eocc_m[mi]);
    rtcReleaseScene(scene);
    rtcReleaseDevice(dev);
    lt_ss_free(ss);
    lt_scene_free(&sc);
    lt_mesh_free(&m);
    return 0;
}
