/* test_adversarial.c - cmocka tests feeding adversarial rays to every traversal kernel, in both
 * numeric paths (issue "Adversarial rays in the unit tests of every kernel"; docs/reliability.md,
 * "Adversarial rays").
 *
 * Scene: the cube [-1, 1]^3 (12 triangles), a quad at z = 0 inside it (2 triangles sharing an
 * edge) and one large triangle on the plane z = -4096 reaching the geometry bound
 * (2^LT_CFG_GEOM_MAX_LOG2 units); the same values in float32 and s15.16 (all exact).
 * Kernels: the 16-lane triangle tests (lt_tri16_*, lt_tri16_wt_* after lt_ray16_wt_setup_*), the
 * chunks (both intersectors), the BVH (packet closest hit, packet any hit, single-ray closest and
 * any hit), the quantised BVH (s15.16), the kd-tree and the grid (closest and any hit).
 * Rays: 1024 per path, each in one adversarial class (the tables cls_f32 / cls_q16 below); the
 * packet kernels run the 64 packets twice, with all lanes active and then with a partial lane
 * mask (the counts printed are active lanes: 1024 + 512).
 * Checks for every ray and kernel: the call returns; the returned mask only holds active lanes;
 * inactive lanes keep their tmax (and id -1); a hit has an id valid for the scene and a distance t
 * (the new tmax) that is finite and within [tmin, tmax] of the ray as given. Classes marked
 * in-contract must have no violation (asserted); classes whose defined result is a miss (NaN or
 * zero direction, NaN tmin/tmax, tmin >= tmax) must have no hit (asserted); a violation in an out-of-contract class is
 * printed as a KNOWN line and not asserted. The asan variant adds ASan+UBSan on all of it.
 * Builds: host, sim, asan.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lt/lt_isect.h"
#include "lt/lt_wt.h"
#include "lt/lt_bvh.h"
#include "lt/lt_kd.h"
#include "lt/lt_grid.h"
#include "lt_test_util.h"

#define NRAYS 1024
#define NPK (NRAYS / LT_LANES)
#define MAXCLS 16
#define MAXFAM 16

/* ---- scene ----------------------------------------------------------------------------------- */

#define NTRIS 15
static const double scene_v[NTRIS][3][3] = {
    /* cube [-1, 1]^3 */
    {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}},   {{-1, -1, -1}, {1, 1, -1}, {-1, 1, -1}},
    {{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}},      {{-1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},
    {{-1, -1, -1}, {1, -1, -1}, {1, -1, 1}},   {{-1, -1, -1}, {1, -1, 1}, {-1, -1, 1}},
    {{-1, 1, -1}, {1, 1, -1}, {1, 1, 1}},      {{-1, 1, -1}, {1, 1, 1}, {-1, 1, 1}},
    {{-1, -1, -1}, {-1, 1, -1}, {-1, 1, 1}},   {{-1, -1, -1}, {-1, 1, 1}, {-1, -1, 1}},
    {{1, -1, -1}, {1, 1, -1}, {1, 1, 1}},      {{1, -1, -1}, {1, 1, 1}, {1, -1, 1}},
    /* quad at z = 0 */
    {{-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0.5, 0.5, 0}}, {{-0.5, -0.5, 0}, {0.5, 0.5, 0}, {-0.5, 0.5, 0}},
    /* large triangle at the geometry bound */
    {{-4096, -4096, -4096}, {4096, -4096, -4096}, {-4096, 4096, -4096}},
};

/* ---- tallies --------------------------------------------------------------------------------- */

typedef struct cls {
    const char *name;
    const char *defined; /* the documented result */
    int in_contract;     /* violations asserted to be 0 */
    int expect_miss;     /* the defined result is a miss: hits asserted to be 0 */
} cls_t;

typedef struct fam {
    const char *name;
    unsigned long rays[MAXCLS], hits[MAXCLS], bad[MAXCLS];
    unsigned long maskbad; /* returned lanes outside k, or inactive lanes modified */
} fam_t;

static int report_families(fam_t *f, unsigned nf, const cls_t *cls, unsigned nc, const char *path)
{
    unsigned i, c;
    int fail = 0;
    for (i = 0; i < nf; i++) {
        unsigned long tot = 0, th = 0;
        for (c = 0; c < nc; c++) {
            tot += f[i].rays[c];
            th += f[i].hits[c];
        }
        ltt_report("%s %s: %lu adversarial rays, %lu hits:", f[i].name, path, tot, th);
        for (c = 0; c < nc; c++)
            ltt_report(" %s %lu/%lu hit (%s)%s", cls[c].name, f[i].hits[c], f[i].rays[c],
                       cls[c].defined, c + 1 < nc ? ";" : "\n");
        for (c = 0; c < nc; c++) {
            if (f[i].bad[c] == 0)
                continue;
            if (cls[c].in_contract) {
                ltt_report("FAIL %s %s: %lu of %lu %s rays hit outside [tmin, tmax] / bad id\n",
                           f[i].name, path, f[i].bad[c], f[i].rays[c], cls[c].name);
                fail = 1;
            } else {
                ltt_report("KNOWN %s %s: %lu of %lu %s rays (out of contract) report a hit with t "
                           "outside [tmin, tmax] or not finite\n",
                           f[i].name, path, f[i].bad[c], f[i].rays[c], cls[c].name);
            }
        }
        for (c = 0; c < nc; c++)
            if (cls[c].expect_miss && f[i].hits[c] != 0) {
                ltt_report("FAIL %s %s: %lu %s rays hit (defined: miss)\n", f[i].name, path,
                           f[i].hits[c], cls[c].name);
                fail = 1;
            }
        if (f[i].maskbad) {
            ltt_report("FAIL %s %s: %lu lanes outside the active mask touched\n", f[i].name, path,
                       f[i].maskbad);
            fail = 1;
        }
    }
    return fail;
}

/* ---- float32 --------------------------------------------------------------------------------- */

enum {
    F_NAN_DIR, F_INF_DIR, F_ZERO_DIR, F_DENORM_MIX, F_DENORM_ALL, F_AXIS, F_NAN_T, F_INF_T,
    F_TMAX_MAX, F_TMIN_GT, F_VERTEX, F_EDGE, F_FACE, F_NCLS
};
static const cls_t cls_f32[F_NCLS] = {
    {"NaN direction", "defined: miss", 0, 1},
    {"+-inf direction", "defined: miss or hit in range", 0, 0},
    {"+-0 direction", "defined: miss", 1, 1},
    {"denormal components", "hit in range", 1, 0},
    {"all-denormal direction", "defined: miss or hit in range", 0, 0},
    {"axis-parallel from vertex/edge/face", "hit in range", 1, 0},
    {"NaN tmin/tmax", "defined: miss", 0, 1},
    {"inf tmin/tmax", "defined: miss or hit in range", 0, 0},
    {"tmax = FLT_MAX", "hit in range", 0, 0},
    {"tmin >= tmax", "defined: miss", 1, 1},
    {"origin on vertex", "hit in range", 1, 0},
    {"origin on edge", "hit in range", 1, 0},
    {"origin on box face", "hit in range", 1, 0},
};

typedef struct rayf {
    float o[3], d[3], tmin, tmax;
    int cls;
} rayf_t;

static void unit_dir(ltt_rng_t *g, double d[3])
{
    double n;
    do {
        d[0] = ltt_rng_uniform(g, -1, 1);
        d[1] = ltt_rng_uniform(g, -1, 1);
        d[2] = ltt_rng_uniform(g, -1, 1);
        n = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    } while (n < 0.01 || n > 1);
    n = sqrt(n);
    d[0] /= n;
    d[1] /= n;
    d[2] /= n;
}

/* Origins (exact in float32 and s15.16): kind 0 vertex, 1 edge, 2 box face, 3 anywhere. */
static void pick_origin(ltt_rng_t *g, unsigned kind, double o[3])
{
    unsigned a = ltt_rng_below(g, 3), t = ltt_rng_below(g, NTRIS - 1), v = ltt_rng_below(g, 3);
    double s = ltt_rng_below(g, 257) / 256.0;
    unsigned b;
    switch (kind) {
    case 0:
        memcpy(o, scene_v[t][v], sizeof(double) * 3);
        break;
    case 1:
        for (b = 0; b < 3; b++)
            o[b] = scene_v[t][v][b] + s * (scene_v[t][(v + 1) % 3][b] - scene_v[t][v][b]);
        break;
    case 2:
        for (b = 0; b < 3; b++)
            o[b] = (double)ltt_rng_range(g, -256, 256) / 256.0;
        o[a] = (ltt_rng_u32(g) & 1u) ? 1.0 : -1.0;
        break;
    default:
        for (b = 0; b < 3; b++)
            o[b] = (double)ltt_rng_range(g, -768, 768) / 256.0;
        break;
    }
}

/* A direction from o towards a point of the scene (so that many rays hit), unit length. */
static void aim(ltt_rng_t *g, const double o[3], double d[3])
{
    double t[3], n;
    unsigned b;
    for (b = 0; b < 3; b++)
        t[b] = ltt_rng_uniform(g, -0.9, 0.9);
    if (ltt_rng_below(g, 8) == 0)
        t[2] = -4096.0 + ltt_rng_uniform(g, 0, 2000);
    for (b = 0; b < 3; b++)
        d[b] = t[b] - o[b];
    n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (n < 1e-6) {
        unit_dir(g, d);
        return;
    }
    for (b = 0; b < 3; b++)
        d[b] /= n;
}

static const float denorms[] = {FLT_MIN / 2, -FLT_MIN / 2, FLT_MIN / 1024, 1.0e-44f, -1.0e-44f,
                                0x1p-149f, -0x1p-149f}; /* the smallest denormal */

static void gen_f32(rayf_t *rs)
{
    ltt_rng_t g;
    unsigned i, b;
    ltt_rng_seed(&g, 0xAD7E125Eu);
    for (i = 0; i < NRAYS; i++) {
        rayf_t *r = &rs[i];
        int c = (int)(i % F_NCLS);
        double o[3], d[3];
        unsigned kind = ltt_rng_below(&g, 4), a = ltt_rng_below(&g, 3), m = ltt_rng_below(&g, 4);
        if (c == F_VERTEX)
            kind = 0;
        else if (c == F_EDGE)
            kind = 1;
        else if (c == F_FACE)
            kind = 2;
        else if (c == F_AXIS)
            kind = ltt_rng_below(&g, 3);
        pick_origin(&g, kind, o);
        aim(&g, o, d);
        for (b = 0; b < 3; b++) {
            r->o[b] = (float)o[b];
            r->d[b] = (float)d[b];
        }
        r->tmin = 0.0f;
        r->tmax = 10000.0f;
        r->cls = c;
        switch (c) {
        case F_NAN_DIR:
            if (m == 0) {
                r->d[0] = r->d[1] = r->d[2] = NAN;
            } else {
                r->d[a] = (m == 1) ? NAN : -NAN;
            }
            break;
        case F_INF_DIR:
            r->d[a] = (ltt_rng_u32(&g) & 1u) ? INFINITY : -INFINITY;
            if (m == 0)
                r->d[(a + 1) % 3] = r->d[(a + 2) % 3] = 0.0f;
            else if (m == 1)
                r->d[(a + 1) % 3] = -r->d[a];
            break;
        case F_ZERO_DIR:
            for (b = 0; b < 3; b++)
                r->d[b] = (ltt_rng_u32(&g) & 1u) ? -0.0f : 0.0f;
            break;
        case F_DENORM_MIX:
            r->d[a] = denorms[ltt_rng_below(&g, 7)];
            if (m == 0)
                r->d[(a + 1) % 3] = denorms[ltt_rng_below(&g, 7)];
            break;
        case F_DENORM_ALL:
            for (b = 0; b < 3; b++)
                r->d[b] = denorms[ltt_rng_below(&g, 7)];
            break;
        case F_AXIS:
            r->d[0] = r->d[1] = r->d[2] = (ltt_rng_u32(&g) & 1u) ? 0.0f : -0.0f;
            r->d[a] = (ltt_rng_u32(&g) & 1u) ? 1.0f : -1.0f;
            break;
        case F_NAN_T:
            if (m != 1)
                r->tmin = NAN;
            if (m != 0)
                r->tmax = NAN;
            break;
        case F_INF_T:
            if (m == 0) {
                r->tmax = INFINITY;
            } else if (m == 1) {
                r->tmin = -INFINITY;
            } else if (m == 2) {
                r->tmin = -INFINITY;
                r->tmax = INFINITY;
            } else {
                r->tmin = INFINITY;
                r->tmax = INFINITY;
            }
            break;
        case F_TMAX_MAX:
            r->tmax = FLT_MAX;
            if (m == 0)
                r->tmin = -FLT_MAX;
            break;
        case F_TMIN_GT:
            r->tmin = (m == 0) ? r->tmax : (float)ltt_rng_uniform(&g, 0.5, 100);
            r->tmax = (m == 0) ? r->tmax : r->tmin * 0.5f;
            if (m == 1)
                r->tmax = -r->tmin;
            break;
        default:
            break;
        }
    }
}

typedef struct scene_f32 {
    lt_tri_f32_t tris[NTRIS];
    lt_aabb_f32_t boxes[LT_CHUNK_COUNT(NTRIS)];
    lt_bvh_t bvh;
    lt_kd_f32_t kd;
    lt_grid_f32_t grid;
    void *m_bvh, *m_kd, *m_grid;
} scene_f32_t;

static void scene_f32_build(scene_f32_t *s)
{
    unsigned i, b;
    size_t sz;
    for (i = 0; i < NTRIS; i++)
        for (b = 0; b < 3; b++) {
            s->tris[i].v0[b] = (float)scene_v[i][0][b];
            s->tris[i].e1[b] = (float)(scene_v[i][1][b] - scene_v[i][0][b]);
            s->tris[i].e2[b] = (float)(scene_v[i][2][b] - scene_v[i][0][b]);
        }
    assert_int_equal(lt_chunks_build_f32(s->tris, NTRIS, s->boxes), LT_OK);
    assert_int_equal(lt_bvh_size(NTRIS, NULL, &sz), LT_OK);
    s->m_bvh = malloc(sz);
    assert_non_null(s->m_bvh);
    assert_int_equal(lt_bvh_build_f32(&s->bvh, NULL, s->tris, NTRIS, s->m_bvh, sz), LT_OK);
    assert_int_equal(lt_kd_size(NTRIS, NULL, &sz), LT_OK);
    s->m_kd = malloc(sz);
    assert_non_null(s->m_kd);
    assert_int_equal(lt_kd_build_f32(&s->kd, s->tris, NTRIS, NULL, s->m_kd, &sz), LT_OK);
    assert_int_equal(lt_grid_size_f32(s->tris, NTRIS, NULL, &sz), LT_OK);
    s->m_grid = malloc(sz);
    assert_non_null(s->m_grid);
    assert_int_equal(lt_grid_build_f32(&s->grid, s->tris, NTRIS, NULL, s->m_grid, &sz), LT_OK);
}

static void scene_f32_free(scene_f32_t *s)
{
    free(s->m_bvh);
    free(s->m_kd);
    free(s->m_grid);
}

/* Packet families: return the mask of lanes reported hit/occluded; *ids: 1 if hit->id is set. */
enum { PK_TRI_MT, PK_TRI_WT, PK_CHUNK_WT, PK_CHUNK_MT, PK_BVH, PK_BVH_OCC, PK_KD, PK_KD_OCC,
       PK_GRID, PK_GRID_OCC, PK_BVHQ, PK_BVHQ_OCC, PK_N };
static const char *const pk_names[PK_N] = {
    "tri16 (Moller-Trumbore)", "tri16_wt (watertight)", "chunks_trace16 (WT)",
    "chunks_trace16 (MT)", "bvh_trace16", "bvh_occluded16", "kd_trace16", "kd_occluded16",
    "grid_trace16", "grid_occluded16", "bvhq_trace16", "bvhq_occluded16",
};

static lt_mask16_t pk_f32(const scene_f32_t *s, int fam, lt_ray16_f32_t *r, lt_mask16_t k,
                          lt_hit16_t *h, int *ids)
{
    lt_mask16_t m = 0;
    unsigned i;
    lt_wt16_f32_t w;
    *ids = 1;
    switch (fam) {
    case PK_TRI_MT:
        for (i = 0; i < NTRIS; i++)
            m |= lt_tri16_f32(r, k, &s->tris[i], (int32_t)i, h);
        return m;
    case PK_TRI_WT:
        (void)lt_ray16_wt_setup_f32(r, &w);
        for (i = 0; i < NTRIS; i++)
            m |= lt_tri16_wt_f32(r, &w, k, &s->tris[i], (int32_t)i, h);
        return m;
    case PK_CHUNK_WT:
        return lt_chunks_trace16_f32(s->tris, NTRIS, s->boxes, LT_ISECT_WT, r, k, h);
    case PK_CHUNK_MT:
        return lt_chunks_trace16_f32(s->tris, NTRIS, s->boxes, LT_ISECT_MT, r, k, h);
    case PK_BVH:
        assert_int_equal(lt_bvh_trace16_f32(&s->bvh, s->tris, r, k, h), LT_OK);
        for (i = 0; i < LT_LANES; i++)
            if (h->id.l[i] != -1)
                m |= (lt_mask16_t)(1u << i);
        return m;
    case PK_BVH_OCC:
        *ids = 0;
        assert_int_equal(lt_bvh_occluded16_f32(&s->bvh, s->tris, r, k, &m), LT_OK);
        return m;
    case PK_KD:
        return lt_kd_trace16_f32(&s->kd, r, k, h);
    case PK_KD_OCC:
        *ids = 0;
        return lt_kd_occluded16_f32(&s->kd, r, k);
    case PK_GRID:
        return lt_grid_trace16_f32(&s->grid, r, k, h);
    case PK_GRID_OCC:
        *ids = 0;
        return lt_grid_occluded16_f32(&s->grid, r, k);
    default:
        fail();
        return 0;
    }
}

/* Check one lane of a result; returns 1 on a violation of the hit rule. */
static int lane_bad_f(int ids, int32_t id, float tmin, float tmax0, float t)
{
    if (ids && (id < 0 || id >= NTRIS))
        return 1;
    if (!isfinite(t))
        return 1;
    return !(t >= tmin && t <= tmax0);
}

static void run_f32(void)
{
    static rayf_t rs[NRAYS];
    static fam_t fam[MAXFAM];
    scene_f32_t *s = calloc(1, sizeof *s);
    unsigned nf = 0, pp, i, f;
    assert_non_null(s);
    memset(fam, 0, sizeof fam);
    gen_f32(rs);
    scene_f32_build(s);
    for (f = 0; f < PK_N; f++) {
        if (f == PK_BVHQ || f == PK_BVHQ_OCC)
            continue;
        fam[nf].name = pk_names[f];
        for (pp = 0; pp < 2 * NPK; pp++) {
            lt_ray16_f32_t r;
            lt_hit16_t h;
            unsigned p = pp % NPK;
            lt_mask16_t k = pp >= NPK ? (lt_mask16_t)(0x5A5Au ^ (p * 0x1111u)) : 0xFFFFu;
            lt_mask16_t m;
            int ids;
            memset(&r, 0, sizeof r);
            for (i = 0; i < LT_LANES; i++) {
                const rayf_t *q = &rs[p * LT_LANES + i];
                r.ox.l[i] = q->o[0];
                r.oy.l[i] = q->o[1];
                r.oz.l[i] = q->o[2];
                r.dx.l[i] = q->d[0];
                r.dy.l[i] = q->d[1];
                r.dz.l[i] = q->d[2];
                r.tmin.l[i] = q->tmin;
                r.tmax.l[i] = q->tmax;
                h.id.l[i] = -1;
            }
            lt_ray16_f32_setup(&r);
            m = pk_f32(s, (int)f, &r, k, &h, &ids);
            if ((m & (lt_mask16_t)~k) != 0)
                fam[nf].maskbad++;
            for (i = 0; i < LT_LANES; i++) {
                const rayf_t *q = &rs[p * LT_LANES + i];
                int on = LTT_ON(k, i), hit = LTT_ON(m, i);
                if (!on) {
                    if (memcmp(&r.tmax.l[i], &q->tmax, sizeof(float)) != 0 ||
                        (ids && h.id.l[i] != -1))
                        fam[nf].maskbad++;
                    continue;
                }
                fam[nf].rays[q->cls]++;
                if (ids && !hit && h.id.l[i] != -1)
                    fam[nf].maskbad++;
                if (!hit)
                    continue;
                fam[nf].hits[q->cls]++;
                fam[nf].bad[q->cls] +=
                    (unsigned long)lane_bad_f(ids, h.id.l[i], q->tmin, q->tmax, r.tmax.l[i]);
            }
        }
        nf++;
    }
    /* single rays: closest and any hit */
    for (f = 0; f < 2; f++) {
        fam[nf].name = f == 0 ? "bvh_trace1" : "bvh_occluded1";
        for (i = 0; i < NRAYS; i++) {
            const rayf_t *q = &rs[i];
            lt_ray1_f32_t r;
            int32_t id = -1;
            int occ = 0, hit;
            memset(&r, 0, sizeof r);
            memcpy(r.o, q->o, sizeof r.o);
            memcpy(r.d, q->d, sizeof r.d);
            r.tmin = q->tmin;
            r.tmax = q->tmax;
            lt_ray1_f32_setup(&r);
            if (f == 0) {
                assert_int_equal(lt_bvh_trace1_f32(&s->bvh, s->tris, &r, &id), LT_OK);
                hit = id != -1;
            } else {
                assert_int_equal(lt_bvh_occluded1_f32(&s->bvh, s->tris, &r, &occ), LT_OK);
                hit = occ != 0;
            }
            fam[nf].rays[q->cls]++;
            if (!hit)
                continue;
            fam[nf].hits[q->cls]++;
            fam[nf].bad[q->cls] += (unsigned long)lane_bad_f(f == 0, id, q->tmin, q->tmax, r.tmax);
        }
        nf++;
    }
    {
        int bad = report_families(fam, nf, cls_f32, F_NCLS, "f32");
        scene_f32_free(s);
        free(s);
        assert_int_equal(bad, 0);
    }
}

/* ---- s15.16 ---------------------------------------------------------------------------------- */

enum {
    Q_ZERO_DIR, Q_EXTREME_DIR, Q_TINY_COMP, Q_AXIS, Q_TMAX_MAX, Q_TMIN_GT, Q_TMIN_NEG, Q_GEOM_BOUND,
    Q_VERTEX, Q_EDGE, Q_FACE, Q_NCLS
};
static const cls_t cls_q16[Q_NCLS] = {
    {"all-zero direction", "defined: miss", 1, 1},
    {"direction at the s1.30 limits", "defined: miss or hit in range", 0, 0},
    {"tiny components (1/d saturates)", "hit in range", 1, 0},
    {"axis-parallel from vertex/edge/face", "hit in range", 1, 0},
    {"tmax = INT32_MAX", "hit in range", 0, 0},
    {"tmin >= tmax", "defined: miss", 1, 1},
    {"tmin negative down to INT32_MIN", "hit in range", 1, 0},
    {"origin at the geometry bound", "hit in range", 1, 0},
    {"origin on vertex", "hit in range", 1, 0},
    {"origin on edge", "hit in range", 1, 0},
    {"origin on box face", "hit in range", 1, 0},
};

typedef struct rayq {
    int32_t o[3], d[3], tmin, tmax;
    int cls;
} rayq_t;

static int32_t q16d(double x) { return (int32_t)lrint(x * 65536.0); }
static int32_t q30d(double x)
{
    double v = x * 1073741824.0;
    if (v >= 2147483647.0)
        return INT32_MAX;
    if (v <= -2147483648.0)
        return INT32_MIN;
    return (int32_t)lrint(v);
}

static const int32_t q30_lim[] = {INT32_MAX, INT32_MIN, -INT32_MAX, 0x40000000, -0x40000000,
                                  0x40000001, -0x40000001, 1, -1};
static const int32_t q30_tiny[] = {1, -1, 2, -2, 0x7FFF, -0x7FFF, 0x8000, -0x8000, 0x3FFF};

static void gen_q16(rayq_t *rs)
{
    ltt_rng_t g;
    unsigned i, b;
    const int32_t bound = (int32_t)1 << (LT_CFG_GEOM_MAX_LOG2 + 16);
    ltt_rng_seed(&g, 0x0AD16u);
    for (i = 0; i < NRAYS; i++) {
        rayq_t *r = &rs[i];
        int c = (int)(i % Q_NCLS);
        double o[3], d[3];
        unsigned kind = ltt_rng_below(&g, 4), a = ltt_rng_below(&g, 3), m = ltt_rng_below(&g, 4);
        if (c == Q_VERTEX)
            kind = 0;
        else if (c == Q_EDGE)
            kind = 1;
        else if (c == Q_FACE)
            kind = 2;
        else if (c == Q_AXIS)
            kind = ltt_rng_below(&g, 3);
        pick_origin(&g, kind, o);
        if (c == Q_GEOM_BOUND) {
            for (b = 0; b < 3; b++)
                if (b == a || (ltt_rng_u32(&g) & 1u))
                    o[b] = (ltt_rng_u32(&g) & 1u) ? bound / 65536.0 : -bound / 65536.0;
        }
        aim(&g, o, d);
        for (b = 0; b < 3; b++) {
            r->o[b] = q16d(o[b]);
            r->d[b] = q30d(d[b]);
        }
        r->tmin = 0;
        r->tmax = q16d(20000.0);
        r->cls = c;
        switch (c) {
        case Q_ZERO_DIR:
            r->d[0] = r->d[1] = r->d[2] = 0;
            break;
        case Q_EXTREME_DIR:
            for (b = 0; b < 3; b++)
                r->d[b] = q30_lim[ltt_rng_below(&g, 9)];
            break;
        case Q_TINY_COMP:
            r->d[a] = q30_tiny[ltt_rng_below(&g, 9)];
            if (m == 0)
                r->d[(a + 1) % 3] = q30_tiny[ltt_rng_below(&g, 9)];
            break;
        case Q_AXIS:
            r->d[0] = r->d[1] = r->d[2] = 0;
            r->d[a] = (ltt_rng_u32(&g) & 1u) ? 0x40000000 : -0x40000000;
            break;
        case Q_TMAX_MAX:
            r->tmax = INT32_MAX;
            if (m == 0)
                r->tmin = INT32_MIN;
            break;
        case Q_TMIN_GT:
            if (m == 0) {
                r->tmin = r->tmax;
            } else if (m == 1) {
                r->tmin = q16d(ltt_rng_uniform(&g, 0.5, 100));
                r->tmax = -r->tmin;
            } else {
                r->tmin = q16d(ltt_rng_uniform(&g, 0.5, 100));
                r->tmax = r->tmin - 1;
            }
            break;
        case Q_TMIN_NEG:
            r->tmin = (m == 0) ? INT32_MIN : (m == 1) ? -1 : -q16d(ltt_rng_uniform(&g, 0, 30000));
            break;
        default:
            break;
        }
    }
}

/* The s15.16 Moller-Trumbore families run on every triangle too: the large triangle (vertices in
 * the geometry bound, edges of 8192 units) used to overflow int64 in lt_tri16_q16's t division
 * (lt__div_round64 doubled det near 2^62; UBSan "signed integer overflow"), fixed in lt_fx.h and
 * held here (in the asan build) and by test_port's test_div_round64. */
#define NTRIS_MT_Q16 NTRIS

typedef struct scene_q16 {
    lt_tri_q16_t tris[NTRIS];
    lt_aabb_q16_t boxes[LT_CHUNK_COUNT(NTRIS)];
    lt_aabb_q16_t boxes_mt[LT_CHUNK_COUNT(NTRIS_MT_Q16)];
    lt_bvh_t bvh;
    lt_bvhq_t bvhq;
    lt_kd_q16_t kd;
    lt_grid_q16_t grid;
    void *m_bvh, *m_bvhq, *m_kd, *m_grid;
} scene_q16_t;

static void scene_q16_build(scene_q16_t *s)
{
    unsigned i, b;
    size_t sz;
    for (i = 0; i < NTRIS; i++)
        for (b = 0; b < 3; b++) {
            s->tris[i].v0[b] = q16d(scene_v[i][0][b]);
            s->tris[i].e1[b] = q16d(scene_v[i][1][b] - scene_v[i][0][b]);
            s->tris[i].e2[b] = q16d(scene_v[i][2][b] - scene_v[i][0][b]);
        }
    assert_int_equal(lt_chunks_build_q16(s->tris, NTRIS, s->boxes), LT_OK);
    assert_int_equal(lt_chunks_build_q16(s->tris, NTRIS_MT_Q16, s->boxes_mt), LT_OK);
    assert_int_equal(lt_bvh_size(NTRIS, NULL, &sz), LT_OK);
    s->m_bvh = malloc(sz);
    assert_non_null(s->m_bvh);
    assert_int_equal(lt_bvh_build_q16(&s->bvh, NULL, s->tris, NTRIS, s->m_bvh, sz), LT_OK);
    assert_int_equal(lt_bvhq_size(&s->bvh, &sz), LT_OK);
    s->m_bvhq = malloc(sz);
    assert_non_null(s->m_bvhq);
    assert_int_equal(lt_bvhq_build_q16(&s->bvhq, &s->bvh, s->m_bvhq, sz), LT_OK);
    assert_int_equal(lt_kd_size(NTRIS, NULL, &sz), LT_OK);
    s->m_kd = malloc(sz);
    assert_non_null(s->m_kd);
    assert_int_equal(lt_kd_build_q16(&s->kd, s->tris, NTRIS, NULL, s->m_kd, &sz), LT_OK);
    assert_int_equal(lt_grid_size_q16(s->tris, NTRIS, NULL, &sz), LT_OK);
    s->m_grid = malloc(sz);
    assert_non_null(s->m_grid);
    assert_int_equal(lt_grid_build_q16(&s->grid, s->tris, NTRIS, NULL, s->m_grid, &sz), LT_OK);
}

static void scene_q16_free(scene_q16_t *s)
{
    free(s->m_bvh);
    free(s->m_bvhq);
    free(s->m_kd);
    free(s->m_grid);
}

static lt_mask16_t pk_q16(const scene_q16_t *s, int fam, lt_ray16_q16_t *r, lt_mask16_t k,
                          lt_hit16_t *h, int *ids)
{
    lt_mask16_t m = 0;
    unsigned i;
    lt_wt16_q16_t w;
    *ids = 1;
    switch (fam) {
    case PK_TRI_MT:
        for (i = 0; i < NTRIS_MT_Q16; i++)
            m |= lt_tri16_q16(r, k, &s->tris[i], (int32_t)i, h);
        return m;
    case PK_TRI_WT:
        (void)lt_ray16_wt_setup_q16(r, &w);
        for (i = 0; i < NTRIS; i++)
            m |= lt_tri16_wt_q16(r, &w, k, &s->tris[i], (int32_t)i, h);
        return m;
    case PK_CHUNK_WT:
        return lt_chunks_trace16_q16(s->tris, NTRIS, s->boxes, LT_ISECT_WT, r, k, h);
    case PK_CHUNK_MT:
        return lt_chunks_trace16_q16(s->tris, NTRIS_MT_Q16, s->boxes_mt, LT_ISECT_MT, r, k, h);
    case PK_BVH:
    case PK_BVHQ:
        if (fam == PK_BVH)
            assert_int_equal(lt_bvh_trace16_q16(&s->bvh, s->tris, r, k, h), LT_OK);
        else
            assert_int_equal(lt_bvhq_trace16_q16(&s->bvhq, s->tris, r, k, h), LT_OK);
        for (i = 0; i < LT_LANES; i++)
            if (h->id.l[i] != -1)
                m |= (lt_mask16_t)(1u << i);
        return m;
    case PK_BVH_OCC:
        *ids = 0;
        assert_int_equal(lt_bvh_occluded16_q16(&s->bvh, s->tris, r, k, &m), LT_OK);
        return m;
    case PK_BVHQ_OCC:
        *ids = 0;
        assert_int_equal(lt_bvhq_occluded16_q16(&s->bvhq, s->tris, r, k, &m), LT_OK);
        return m;
    case PK_KD:
        return lt_kd_trace16_q16(&s->kd, r, k, h);
    case PK_KD_OCC:
        *ids = 0;
        return lt_kd_occluded16_q16(&s->kd, r, k);
    case PK_GRID:
        return lt_grid_trace16_q16(&s->grid, r, k, h);
    case PK_GRID_OCC:
        *ids = 0;
        return lt_grid_occluded16_q16(&s->grid, r, k);
    default:
        fail();
        return 0;
    }
}

static int lane_bad_q(int ids, int32_t id, int32_t tmin, int32_t tmax0, int32_t t)
{
    if (ids && (id < 0 || id >= NTRIS))
        return 1;
    return !(t >= tmin && t <= tmax0);
}

static void run_q16(void)
{
    static rayq_t rs[NRAYS];
    static fam_t fam[MAXFAM];
    scene_q16_t *s = calloc(1, sizeof *s);
    unsigned nf = 0, pp, i, f;
    assert_non_null(s);
    memset(fam, 0, sizeof fam);
    gen_q16(rs);
    scene_q16_build(s);
    for (f = 0; f < PK_N; f++) {
        fam[nf].name = pk_names[f];
        for (pp = 0; pp < 2 * NPK; pp++) {
            lt_ray16_q16_t r;
            lt_hit16_t h;
            unsigned p = pp % NPK;
            lt_mask16_t k = pp >= NPK ? (lt_mask16_t)(0x5A5Au ^ (p * 0x1111u)) : 0xFFFFu;
            lt_mask16_t m;
            int ids;
            memset(&r, 0, sizeof r);
            for (i = 0; i < LT_LANES; i++) {
                const rayq_t *q = &rs[p * LT_LANES + i];
                r.ox.l[i] = q->o[0];
                r.oy.l[i] = q->o[1];
                r.oz.l[i] = q->o[2];
                r.dx.l[i] = q->d[0];
                r.dy.l[i] = q->d[1];
                r.dz.l[i] = q->d[2];
                r.tmin.l[i] = q->tmin;
                r.tmax.l[i] = q->tmax;
                h.id.l[i] = -1;
            }
            lt_ray16_q16_setup(&r);
            m = pk_q16(s, (int)f, &r, k, &h, &ids);
            if ((m & (lt_mask16_t)~k) != 0)
                fam[nf].maskbad++;
            for (i = 0; i < LT_LANES; i++) {
                const rayq_t *q = &rs[p * LT_LANES + i];
                int on = LTT_ON(k, i), hit = LTT_ON(m, i);
                if (!on) {
                    if (r.tmax.l[i] != q->tmax || (ids && h.id.l[i] != -1))
                        fam[nf].maskbad++;
                    continue;
                }
                fam[nf].rays[q->cls]++;
                if (ids && !hit && h.id.l[i] != -1)
                    fam[nf].maskbad++;
                if (!hit)
                    continue;
                fam[nf].hits[q->cls]++;
                fam[nf].bad[q->cls] +=
                    (unsigned long)lane_bad_q(ids, h.id.l[i], q->tmin, q->tmax, r.tmax.l[i]);
            }
        }
        nf++;
    }
    for (f = 0; f < 3; f++) {
        fam[nf].name = f == 0 ? "bvh_trace1" : f == 1 ? "bvh_occluded1" : "bvhq_trace1";
        for (i = 0; i < NRAYS; i++) {
            const rayq_t *q = &rs[i];
            lt_ray1_q16_t r;
            int32_t id = -1;
            int occ = 0, hit;
            memset(&r, 0, sizeof r);
            memcpy(r.o, q->o, sizeof r.o);
            memcpy(r.d, q->d, sizeof r.d);
            r.tmin = q->tmin;
            r.tmax = q->tmax;
            lt_ray1_q16_setup(&r);
            if (f == 0) {
                assert_int_equal(lt_bvh_trace1_q16(&s->bvh, s->tris, &r, &id), LT_OK);
                hit = id != -1;
            } else if (f == 1) {
                assert_int_equal(lt_bvh_occluded1_q16(&s->bvh, s->tris, &r, &occ), LT_OK);
                hit = occ != 0;
            } else {
                assert_int_equal(lt_bvhq_trace1_q16(&s->bvhq, s->tris, &r, &id), LT_OK);
                hit = id != -1;
            }
            fam[nf].rays[q->cls]++;
            if (!hit)
                continue;
            fam[nf].hits[q->cls]++;
            fam[nf].bad[q->cls] += (unsigned long)lane_bad_q(f != 1, id, q->tmin, q->tmax, r.tmax);
        }
        nf++;
    }
    {
        int bad = report_families(fam, nf, cls_q16, Q_NCLS, "q16");
        scene_q16_free(s);
        free(s);
        assert_int_equal(bad, 0);
    }
}

static void test_adversarial_f32(void **state)
{
    (void)state;
    run_f32();
}

static void test_adversarial_q16(void **state)
{
    (void)state;
    run_q16();
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_adversarial_f32),
        cmocka_unit_test(test_adversarial_q16),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
