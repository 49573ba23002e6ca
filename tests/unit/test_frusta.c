/* test_frusta.c - multi-frusta soft shadows (lt_frusta.h): frusta visibility against per-ray
 * visibility of every sample (brute force over all triangles with the single-ray kernel, and the
 * packet baseline) for random scenes, partially occluded frusta, frusta grazing boxes and
 * triangles, lights seen edge-on, origins on the light plane, degenerate lights, every flag
 * combination, both BVH shapes; exact in s15.16, checked in float32. Also the ray generator (rays
 * end exactly on their sample points), argument errors, the direct-light term against double, the
 * discontinuity filter's property, a tile hash that host and sim builds must print identically,
 * and the bunny (shared data) with a ground plane. Primary frusta (P-Frusta) and their packet
 * baseline against the per-ray closest hit (t and id, ties included) on random scenes and
 * cameras, constructed edge cases, the empty scene and the bunny. Builds: host, sim, asan.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "lt/lt_frusta.h"
#include "io/lt_fx_float.h"
#include "io/lt_mesh.h"
#include "render/lt_scene.h"
#include "render/lt_softshadow.h"
#include "lt_test_util.h"
#include "lt_isect_oracle.h"
#include "lt_frusta_tile.h"
#if LT_COST_MODE == LT_COST_SIM
#include "lt_sim.h"
#endif

#define U (65536) /* one world unit, s15.16 raw */
#define MAXT 4096

/* ---- scenes -------------------------------------------------------------------------------- */

typedef struct tscene {
    lt_tri_q16_t tq[MAXT];
    lt_tri_f32_t tf[MAXT];
    uint32_t n;
} tscene_t;

static void add_tri(tscene_t *s, const int32_t a[3], const int32_t b[3], const int32_t c[3])
{
    unsigned k;
    lt_tri_q16_t *t = &s->tq[s->n];
    lt_tri_f32_t *f = &s->tf[s->n];
    assert_true(s->n < MAXT);
    for (k = 0; k < 3; k++) {
        t->v0[k] = a[k];
        t->e1[k] = b[k] - a[k];
        t->e2[k] = c[k] - a[k];
        f->v0[k] = (float)a[k] / 65536.0f;
        f->e1[k] = (float)b[k] / 65536.0f - f->v0[k];
        f->e2[k] = (float)c[k] / 65536.0f - f->v0[k];
    }
    s->n++;
}

typedef struct tbvh {
    lt_bvh_t q, f;
    void *aq, *af;
} tbvh_t;

static void build(const tscene_t *s, uint32_t max_leaf, uint32_t min_leaf, tbvh_t *b)
{
    lt_bvh_desc_t d;
    size_t bytes;
    memset(&d, 0, sizeof d);
    d.max_leaf = max_leaf;
    d.min_leaf = min_leaf;
    assert_int_equal(lt_bvh_size(s->n, &d, &bytes), LT_OK);
    assert_int_equal(posix_memalign(&b->aq, 64, bytes + 64), 0);
    assert_int_equal(posix_memalign(&b->af, 64, bytes + 64), 0);
    assert_int_equal(lt_bvh_build_q16(&b->q, &d, s->tq, s->n, b->aq, bytes), LT_OK);
    assert_int_equal(lt_bvh_build_f32(&b->f, &d, s->tf, s->n, b->af, bytes), LT_OK);
    /* the intersector of the walks and of the per-ray references (lt_isect_oracle.h) */
    b->q.isect = b->f.isect = ltt_isect;
}

static void unbuild(tbvh_t *b)
{
    free(b->aq);
    free(b->af);
}

/* ---- per-ray reference --------------------------------------------------------------------- */

/* Sign of the kernel's det (pre-flip) for one ray, recomputed here: pvec = round(d x e2) to
 * s15.16, det = e1 . pvec exactly. Back-face culling keeps a hit only when det > 0. */
static int det_sign_q16(const lt_ray1_q16_t *r, const lt_tri_q16_t *t)
{
    int64_t p[3], det;
    p[0] = lt__round_sat32((int64_t)r->d[1] * t->e2[2] - (int64_t)r->d[2] * t->e2[1], 30);
    p[1] = lt__round_sat32((int64_t)r->d[2] * t->e2[0] - (int64_t)r->d[0] * t->e2[2], 30);
    p[2] = lt__round_sat32((int64_t)r->d[0] * t->e2[1] - (int64_t)r->d[1] * t->e2[0], 30);
    det = t->e1[0] * p[0] + t->e1[1] * p[1] + t->e1[2] * p[2];
    return (det > 0) - (det < 0);
}

static int det_sign_f32(const lt_ray1_f32_t *r, const lt_tri_f32_t *t)
{
    float px = r->d[1] * t->e2[2] - r->d[2] * t->e2[1];
    float py = r->d[2] * t->e2[0] - r->d[0] * t->e2[2];
    float pz = r->d[0] * t->e2[1] - r->d[1] * t->e2[0];
    float det = (t->e1[0] * px + t->e1[1] * py) + t->e1[2] * pz;
    return (det > 0.0f) - (det < 0.0f);
}

/* The kernels' back-face rule for the watertight test: the sign of the Moller-Trumbore tnum of the
 * ray's origin (lt_frusta.c's q_tnum_sign1 / f_tnum_sign1, the rule of the packet baselines), the
 * one per-origin decision all paths share; for Moller-Trumbore it equals det > 0 of every hit. */
static int tnum_sign_q16(const lt_ray1_q16_t *r, const lt_tri_q16_t *t)
{
    int32_t tv[3], q[3];
    int64_t tn;
    int a;
    for (a = 0; a < 3; a++)
        tv[a] = lt__q16_sub_sat(r->o[a], t->v0[a]);
    q[0] = lt__round_sat32((int64_t)tv[1] * t->e1[2] - (int64_t)tv[2] * t->e1[1], 26);
    q[1] = lt__round_sat32((int64_t)tv[2] * t->e1[0] - (int64_t)tv[0] * t->e1[2], 26);
    q[2] = lt__round_sat32((int64_t)tv[0] * t->e1[1] - (int64_t)tv[1] * t->e1[0], 26);
    tn = (int64_t)t->e2[0] * q[0] + (int64_t)t->e2[1] * q[1] + (int64_t)t->e2[2] * q[2];
    return (tn > 0) - (tn < 0);
}

static int tnum_sign_f32(const lt_ray1_f32_t *r, const lt_tri_f32_t *t)
{
    float tx = r->o[0] - t->v0[0], ty = r->o[1] - t->v0[1], tz = r->o[2] - t->v0[2];
    float qx = ty * t->e1[2] - tz * t->e1[1];
    float qy = tz * t->e1[0] - tx * t->e1[2];
    float qz = tx * t->e1[1] - ty * t->e1[0];
    float tn = (t->e2[0] * qx + t->e2[1] * qy) + t->e2[2] * qz;
    return (tn > 0.0f) - (tn < 0.0f);
}

/* Front face for back-face culling, per intersector (see above). */
static int front_q16(const lt_ray1_q16_t *r, const lt_tri_q16_t *t)
{
    return ltt_isect == LT_ISECT_MT ? det_sign_q16(r, t) > 0 : tnum_sign_q16(r, t) > 0;
}

static int front_f32(const lt_ray1_f32_t *r, const lt_tri_f32_t *t)
{
    return ltt_isect == LT_ISECT_MT ? det_sign_f32(r, t) > 0 : tnum_sign_f32(r, t) > 0;
}

/* Brute force: any triangle the single-ray kernel hits (front faces only under back-face
 * culling). */
static int ref_q16(const tscene_t *s, const lt_ray1_q16_t *r0, uint32_t flags)
{
    uint32_t i;
    for (i = 0; i < s->n; i++) {
        lt_ray1_q16_t r = *r0;
        if (ltt_tri1_q16(&r, &s->tq[i]) &&
            ((flags & LT_FRUSTA_BACKFACE) == 0 || front_q16(r0, &s->tq[i])))
            return 1;
    }
    return 0;
}

static int ref_f32(const tscene_t *s, const lt_ray1_f32_t *r0, uint32_t flags)
{
    uint32_t i;
    for (i = 0; i < s->n; i++) {
        lt_ray1_f32_t r = *r0;
        if (ltt_tri1_f32(&r, &s->tf[i]) &&
            ((flags & LT_FRUSTA_BACKFACE) == 0 || front_f32(r0, &s->tf[i])))
            return 1;
    }
    return 0;
}

/* ---- one comparison: 16 origins, one light, one flag set ------------------------------------ */

typedef struct tally {
    unsigned long frusta, samples, occluded, partial, bad_frusta, bad_packet, bad_bvh;
    unsigned long bad_f32, f32_samples;
} tally_t;

static lt_qmc_sets_t g_sets;
static const uint32_t g_flagsets[] = {
    0u, LT_FRUSTA_BACKFACE, LT_FRUSTA_CORNER, LT_FRUSTA_CORNER | LT_FRUSTA_BACKFACE,
    LT_FRUSTA_CORNER | LT_FRUSTA_CR, LT_FRUSTA_CORNER | LT_FRUSTA_CR | LT_FRUSTA_BACKFACE,
    LT_FRUSTA_LEAFRAY, LT_FRUSTA_CORNER | LT_FRUSTA_CR | LT_FRUSTA_BACKFACE | LT_FRUSTA_LEAFRAY,
    LT_FRUSTA_SPLIT,
    LT_FRUSTA_CORNER | LT_FRUSTA_CR | LT_FRUSTA_BACKFACE | LT_FRUSTA_LEAFRAY | LT_FRUSTA_SPLIT,
    LT_FRUSTA_CORNER | LT_FRUSTA_CR | LT_FRUSTA_FS | LT_FRUSTA_BACKFACE,
    LT_FRUSTA_CORNER | LT_FRUSTA_CR | LT_FRUSTA_FS | LT_FRUSTA_BACKFACE | LT_FRUSTA_LEAFRAY |
        LT_FRUSTA_SPLIT,
    LT_FRUSTA_CORNER | LT_FRUSTA_BACKFACE | LT_FRUSTA_P256, /* primary frusta: without P256 */
};
#define NFLAGS (sizeof g_flagsets / sizeof g_flagsets[0])

/* The samples traced per frustum (lt_frusta_restrict16 when not all: lanetrace shadows --spp). */
static uint16_t g_samples = 0xFFFFu;

/* Run all three q16 paths (frusta, packet baseline, lt_bvh_occluded16 when no culling) and the
 * f32 frusta on one set of origins and compare every sample with brute force; only the samples
 * of g_samples are traced (the frusta restricted after setup, the packets masked). */
static void compare(const tscene_t *s, const tbvh_t *b, const lt_frusta_light_q16_t *lq,
                    int32_t org[16][3], lt_mask16_t k, tally_t *t, const char *what)
{
    lt_frusta_table_q16_t tb;
    lt_frusta16_q16_t F;
    lt_frusta_light_f32_t lf;
    lt_frusta_table_f32_t tbf;
    lt_frusta16_f32_t Ff;
    unsigned f, j, a;
    lt_status_t st;

    assert_int_equal(lt_frusta_table_q16(lq, &g_sets, &tb), LT_OK);
    for (a = 0; a < 3; a++) {
        lf.c[a] = (float)lq->c[a] / 65536.0f;
        lf.eu[a] = (float)lq->eu[a] / 65536.0f;
        lf.ev[a] = (float)lq->ev[a] / 65536.0f;
    }
    lf.flags = lq->flags;
    lf.end_shift = lq->end_shift;
    assert_int_equal(lt_frusta_table_f32(&lf, &g_sets, &tbf), LT_OK);
    for (f = 0; f < 16; f++) {
        F.ox.l[f] = org[f][0];
        F.oy.l[f] = org[f][1];
        F.oz.l[f] = org[f][2];
        Ff.ox.l[f] = (float)org[f][0] / 65536.0f;
        Ff.oy.l[f] = (float)org[f][1] / 65536.0f;
        Ff.oz.l[f] = (float)org[f][2] / 65536.0f;
    }
    st = lt_frusta_setup16_q16(&tb, k, &F);
    assert_true(st == LT_OK || st == LT_E_RANGE);
    if (g_samples != 0xFFFFu)
        assert_int_equal(lt_frusta_restrict16_q16(&tb, g_samples, &F), LT_OK);
    assert_int_equal(lt_frusta_occluded16_q16(&b->q, s->tq, &tb, &F), LT_OK);
    st = lt_frusta_setup16_f32(&tbf, k, &Ff);
    assert_true(st == LT_OK || st == LT_E_RANGE);
    if (g_samples != 0xFFFFu)
        assert_int_equal(lt_frusta_restrict16_f32(&tbf, g_samples, &Ff), LT_OK);
    assert_int_equal(lt_frusta_occluded16_f32(&b->f, s->tf, &tbf, &Ff), LT_OK);
    for (f = 0; f < 16; f++) {
        uint16_t ref = 0, reff = 0;
        lt_ray16_q16_t pr;
        lt_ray16_f32_t prf;
        lt_mask16_t pk, po = 0;
        float of[3];
        if (((unsigned)k >> f & 1u) == 0)
            continue;
        for (a = 0; a < 3; a++)
            of[a] = (float)org[f][a] / 65536.0f;
        for (j = 0; j < 16; j++) {
            lt_ray1_q16_t r1;
            lt_ray1_f32_t r1f;
            if (lt_frusta_ray1_q16(&tb, org[f], f, j, &r1) == LT_OK && ref_q16(s, &r1, lq->flags))
                ref = (uint16_t)(ref | (1u << j));
            assert_int_equal(lt_frusta_ray1_f32(&tbf, of, f, j, &r1f), LT_OK);
            if (ref_f32(s, &r1f, lq->flags))
                reff = (uint16_t)(reff | (1u << j));
        }
        ref = (uint16_t)(ref & g_samples);
        reff = (uint16_t)(reff & g_samples);
        t->frusta++;
        t->samples += (unsigned long)lt__popcount32(g_samples);
        t->f32_samples += (unsigned long)lt__popcount32(g_samples);
        t->occluded += lt__popcount32(ref);
        t->partial += ref != 0 && ref != g_samples;
        if (F.occl[f] != ref) {
            if (t->bad_frusta++ < 6)
                printf("  FAIL %s: frustum %u flags %u occl %04x, per-ray %04x\n", what, f,
                       lq->flags, F.occl[f], ref);
        }
        if (Ff.occl[f] != reff) {
            if (t->bad_f32++ < 6)
                printf("  FAIL %s f32: frustum %u flags %u occl %04x, per-ray %04x\n", what, f,
                       lq->flags, Ff.occl[f], reff);
        }
        /* the packet baseline on the deep tree-independent BVH given, same rays */
        if (lt_frusta_rays16_q16(&tb, org[f], f, &pr, &pk) == LT_OK) {
            pk = (lt_mask16_t)(pk & g_samples);
            assert_int_equal(lt_frusta_packet_occluded16_q16(&b->q, s->tq, lq->flags, org[f], &pr,
                                                             pk, &po),
                             LT_OK);
            if (po != ref && t->bad_packet++ < 6)
                printf("  FAIL %s packet: frustum %u flags %u occl %04x, per-ray %04x\n", what, f,
                       lq->flags, po, ref);
            if ((lq->flags & LT_FRUSTA_BACKFACE) == 0) {
                lt_mask16_t bo = 0;
                assert_int_equal(lt_frusta_rays16_q16(&tb, org[f], f, &pr, &pk), LT_OK);
                pk = (lt_mask16_t)(pk & g_samples);
                assert_int_equal(lt_bvh_occluded16_q16(&b->q, s->tq, &pr, pk, &bo), LT_OK);
                if (bo != ref && t->bad_bvh++ < 6)
                    printf("  FAIL %s lt_bvh_occluded16: frustum %u %04x vs %04x\n", what, f, bo,
                           ref);
            }
        }
        assert_int_equal(lt_frusta_rays16_f32(&tbf, of, f, &prf, &pk), LT_OK);
        pk = (lt_mask16_t)(pk & g_samples);
        po = 0;
        assert_int_equal(lt_frusta_packet_occluded16_f32(&b->f, s->tf, lq->flags, of, &prf, pk,
                                                         &po),
                         LT_OK);
        if (po != reff && t->bad_f32++ < 6)
            printf("  FAIL %s f32 packet: frustum %u %04x vs %04x\n", what, f, po, reff);
    }
}

static void tally_print(const char *name, const tally_t *t)
{
    ltt_report("%s: %lu frusta, %lu samples (%lu occluded, %lu partially occluded frusta): "
               "frusta != per-ray %lu, packet != per-ray %lu, lt_bvh_occluded16 != per-ray %lu "
               "(bound 0); f32 %lu samples, %lu mismatches (bound 0)\n",
               name, t->frusta, t->samples, t->occluded, t->partial, t->bad_frusta, t->bad_packet,
               t->bad_bvh, t->f32_samples, t->bad_f32);
}

static void tally_assert(const tally_t *t)
{
    assert_int_equal(t->bad_frusta, 0);
    assert_int_equal(t->bad_packet, 0);
    assert_int_equal(t->bad_bvh, 0);
    assert_int_equal(t->bad_f32, 0);
}

/* ---- random scenes --------------------------------------------------------------------------- */

static int32_t rnd(ltt_rng_t *r, double lo, double hi)
{
    return (int32_t)floor(ltt_rng_uniform(r, lo, hi) * U);
}

/* Blockers between a floor of origins (y around -150) and a light around y = +150. */
static void random_scene(ltt_rng_t *r, tscene_t *s, unsigned n, double size)
{
    unsigned i, k;
    s->n = 0;
    for (i = 0; i < n; i++) {
        int32_t a[3], b[3], c[3];
        a[0] = rnd(r, -200, 200);
        a[1] = rnd(r, -100, 100);
        a[2] = rnd(r, -200, 200);
        for (k = 0; k < 3; k++) {
            b[k] = a[k] + rnd(r, -size, size);
            c[k] = a[k] + rnd(r, -size, size);
        }
        add_tri(s, a, b, c);
    }
}

static void random_light(ltt_rng_t *r, lt_frusta_light_q16_t *l, double size, uint32_t flags)
{
    unsigned a;
    memset(l, 0, sizeof *l);
    l->c[0] = rnd(r, -60, 20);
    l->c[1] = rnd(r, 140, 160);
    l->c[2] = rnd(r, -60, 20);
    for (a = 0; a < 3; a++) {
        /* edges on the 2^-7 grid, mostly horizontal, sometimes tilted */
        l->eu[a] = (int32_t)floor(ltt_rng_uniform(r, -0.3, 1.0) * size * 128.0) * 512;
        l->ev[a] = (int32_t)floor(ltt_rng_uniform(r, -0.3, 1.0) * size * 128.0) * 512;
    }
    l->eu[1] /= 8 * 512;
    l->eu[1] *= 512;
    l->flags = flags;
}

static void random_origins(ltt_rng_t *r, int32_t org[16][3], double spread)
{
    unsigned f;
    double cx = ltt_rng_uniform(r, -150, 150), cz = ltt_rng_uniform(r, -150, 150);
    for (f = 0; f < 16; f++) {
        org[f][0] = (int32_t)floor((cx + ltt_rng_uniform(r, -spread, spread)) * U);
        org[f][1] = rnd(r, -160, -120);
        org[f][2] = (int32_t)floor((cz + ltt_rng_uniform(r, -spread, spread)) * U);
    }
}

static void test_random_scenes(void **state)
{
    ltt_rng_t r;
    tally_t t;
    unsigned sc, fl, rep;
    (void)state;
    memset(&t, 0, sizeof t);
    ltt_rng_seed(&r, 77);
    for (sc = 0; sc < 6; sc++) {
        static tscene_t s;
        tbvh_t shallow, deep;
        unsigned n = sc < 3 ? 200u + 300u * sc : 1500u;
        double size = sc % 3 == 0 ? 5.0 : (sc % 3 == 1 ? 20.0 : 60.0);
        /* odd scenes with Moller-Trumbore: its corner culling is checked too */
        ltt_isect = sc & 1u ? LT_ISECT_MT : LT_ISECT_WT;
        random_scene(&r, &s, n, size);
        build(&s, 16, 8, &shallow);
        build(&s, 4, 1, &deep);
        for (fl = 0; fl < NFLAGS; fl++)
            for (rep = 0; rep < 3; rep++) {
                lt_frusta_light_q16_t l;
                int32_t org[16][3];
                /* TRIPAR (the packet walks' triangle-parallel leaves) on every other run */
                random_light(&r, &l, rep == 0 ? 4.0 : (rep == 1 ? 40.0 : 120.0),
                             g_flagsets[fl] | ((fl + rep) % 2u == 1u ? LT_FRUSTA_TRIPAR : 0u));
                random_origins(&r, org, rep == 2 ? 100.0 : 3.0);
                compare(&s, rep == 1 ? &deep : &shallow, &l, org, LT_MASK_ALL, &t, "random");
                /* random frustum masks, with 4, 8 or all 16 samples per frustum traced */
                g_samples = rep == 0 ? 0x000Fu : (rep == 1 ? 0x00FFu : 0xFFFFu);
                compare(&s, &shallow, &l, org, (lt_mask16_t)ltt_rng_u32(&r), &t, "random mask");
                g_samples = 0xFFFFu;
            }
        unbuild(&shallow);
        unbuild(&deep);
    }
    ltt_isect = LT_ISECT_WT;
    tally_print("random scenes (6 scenes, 13 flag sets, TRIPAR on every other run, 3 light sizes, "
                "coherent and scattered origins, random masks with 4, 8 and 16 samples traced "
                "(lt_frusta_restrict16); odd scenes Moller-Trumbore)", &t);
#if LT_COST_MODE == LT_COST_SIM
    {
        /* the equality above is only worth something if the culling actually removed pairs */
        lt_sim_totals_t tot;
        uint64_t ev[LT_EV__COUNT];
        unsigned e, ph;
        lt_sim_totals(&tot);
        for (e = 0; e < LT_EV__COUNT; e++)
            for (ev[e] = 0, ph = 0; ph < LT_PH__COUNT; ph++)
                ev[e] += tot.ctr[ph][LT_OP__COUNT + e];
        ltt_report("  sim events so far: TRI_FETCH %llu TRI_KEPT %llu CULL_BACK %llu CULL_CORNER %llu "
                   "TRIS %llu HITS %llu AABB %llu\n",
                   (unsigned long long)ev[LT_EV_TRI_FETCH], (unsigned long long)ev[LT_EV_TRI_KEPT],
                   (unsigned long long)ev[LT_EV_CULL_BACK],
                   (unsigned long long)ev[LT_EV_CULL_CORNER], (unsigned long long)ev[LT_EV_TRIS],
                   (unsigned long long)ev[LT_EV_HITS], (unsigned long long)ev[LT_EV_AABB]);
        ltt_report("  sim events so far: LEAF_CULL %llu SPLIT %llu TRIPAR %llu (the leaf culling, "
                   "split walks and triangle-parallel packet leaves of the LEAFRAY / SPLIT / "
                   "TRIPAR flag sets fired)\n",
                   (unsigned long long)ev[LT_EV_LEAF_CULL], (unsigned long long)ev[LT_EV_SPLIT],
                   (unsigned long long)ev[LT_EV_TRIPAR]);
        assert_true(ev[LT_EV_CULL_CORNER] > 1000u);
        assert_true(ev[LT_EV_CULL_BACK] > 1000u);
        assert_true(ev[LT_EV_LEAF_CULL] > 100u);
        assert_true(ev[LT_EV_SPLIT] > 100u);
        assert_true(ev[LT_EV_TRIPAR] > 100u);
    }
#endif
    assert_true(t.partial > 50);
    tally_assert(&t);
}

/* ---- constructed edge cases ----------------------------------------------------------------- */

/* A point on the ray from o through sample j of set f at fraction num / 8 (exact: the ray ends on
 * the sample point, a multiple of 2^-7 units, and o is on the 2^-7 grid too). */
static void on_ray(const lt_frusta_light_q16_t *l, const int32_t o[3], unsigned f, unsigned j,
                   int32_t num, int32_t p[3])
{
    unsigned a;
    int32_t su = 2 * g_sets.u[f][j] + 1, sv = 2 * g_sets.v[f][j] + 1;
    for (a = 0; a < 3; a++) {
        int64_t s = (int64_t)l->c[a] + ((int64_t)su * l->eu[a] + (int64_t)sv * l->ev[a]) / 512;
        p[a] = (int32_t)(o[a] + (s - o[a]) * num / 8);
    }
}

static void test_edge_cases(void **state)
{
    static tscene_t s;
    tally_t t;
    lt_frusta_light_q16_t l;
    int32_t org[16][3];
    unsigned f, fl, i, a;
    ltt_rng_t r;
    (void)state;
    memset(&t, 0, sizeof t);
    ltt_rng_seed(&r, 99);
    memset(&l, 0, sizeof l);
    /* light 64 x 64 units at y = 100, horizontal */
    l.c[0] = -32 * U;
    l.c[1] = 100 * U;
    l.c[2] = -32 * U;
    l.eu[0] = 64 * U;
    l.ev[2] = 64 * U;
    for (f = 0; f < 16; f++) {
        org[f][0] = ((int32_t)(f % 4) * 8 - 12) * U;
        org[f][1] = -20 * U;
        org[f][2] = ((int32_t)(f / 4) * 8 - 12) * U;
    }
    /* (1) grazing: triangles with a vertex exactly on a sample ray (the kernel's inclusive edge),
     * with an edge along the ray, and axis-aligned blockers whose box faces hold ray points */
    s.n = 0;
    for (f = 0; f < 16; f++)
        for (i = 0; i < 4; i++) {
            int32_t p[3], b[3], c[3];
            unsigned j = (f * 5u + i * 3u) & 15u;
            on_ray(&l, org[f], f, j, 2 + (int32_t)i, p);
            for (a = 0; a < 3; a++) {
                b[a] = p[a];
                c[a] = p[a];
            }
            if (i == 0) { /* vertex on the ray, triangle in a vertical plane */
                b[0] += 3 * U;
                c[1] += 3 * U;
            } else if (i == 1) { /* edge along the ray: second vertex further on the same ray */
                on_ray(&l, org[f], f, j, 6, b);
                c[0] += 2 * U;
            } else if (i == 2) { /* horizontal blocker whose face contains the ray point */
                b[0] += 4 * U;
                c[2] += 4 * U;
            } else { /* tiny triangle around the ray point */
                p[0] -= 1;
                b[0] += 1;
                c[2] += 1;
            }
            add_tri(&s, p, b, c);
        }
    {
        tbvh_t b1, b2;
        build(&s, 16, 8, &b1);
        build(&s, 1, 1, &b2);
        for (fl = 0; fl < NFLAGS; fl++) {
            l.flags = g_flagsets[fl];
            compare(&s, &b1, &l, org, LT_MASK_ALL, &t, "grazing");
            compare(&s, &b2, &l, org, LT_MASK_ALL, &t, "grazing leaf 1");
        }
        /* (2) a half-plane blocker cutting through the light as seen from every origin: partially
         * occluded frusta everywhere */
        unbuild(&b1);
        unbuild(&b2);
    }
    {
        int32_t a0[3] = {-300 * U, 40 * U, -300 * U}, a1[3] = {1 * U, 40 * U, -300 * U};
        int32_t a2[3] = {1 * U, 40 * U, 300 * U}, a3[3] = {-300 * U, 40 * U, 300 * U};
        tbvh_t b1;
        s.n = 0;
        add_tri(&s, a0, a1, a2);
        add_tri(&s, a0, a2, a3);
        /* and its back side, so back-face culling has a front face either way */
        add_tri(&s, a0, a2, a1);
        build(&s, 16, 8, &b1);
        for (fl = 0; fl < NFLAGS; fl++) {
            l.flags = g_flagsets[fl];
            compare(&s, &b1, &l, org, LT_MASK_ALL, &t, "half-plane");
        }
        unbuild(&b1);
    }
    /* (3) light seen edge-on and origins on the light plane (y = 100): rays with dy = 0, one
     * origin exactly on a sample point and one on the light's corner */
    random_scene(&r, &s, 600, 10.0);
    {
        tbvh_t b1;
        int32_t org2[16][3];
        for (i = 0; i < s.n; i++) /* lift the blockers to the light's height */
            s.tq[i].v0[1] += 100 * U, s.tf[i].v0[1] += 100.0f;
        build(&s, 16, 8, &b1);
        for (f = 0; f < 16; f++) {
            org2[f][0] = (int32_t)floor(ltt_rng_uniform(&r, -200, 200) * U / 512) * 512;
            org2[f][1] = 100 * U;
            org2[f][2] = (int32_t)floor(ltt_rng_uniform(&r, -200, 200) * U / 512) * 512;
        }
        on_ray(&l, org2[0], 0, 3, 8, org2[0]); /* origin = sample 3 of set 0 */
        org2[1][0] = l.c[0];
        org2[1][2] = l.c[2];
        org2[2][0] = 0; /* inside the light's rectangle */
        org2[2][2] = 0;
        for (fl = 0; fl < NFLAGS; fl++) {
            l.flags = g_flagsets[fl];
            compare(&s, &b1, &l, org2, LT_MASK_ALL, &t, "light plane");
        }
        unbuild(&b1);
    }
    /* (4) degenerate lights: a point (zero area), a line, and an origin on the point light */
    random_scene(&r, &s, 800, 15.0);
    {
        tbvh_t b1;
        lt_frusta_light_q16_t lp = l;
        build(&s, 16, 8, &b1);
        memset(lp.eu, 0, sizeof lp.eu);
        memset(lp.ev, 0, sizeof lp.ev);
        for (fl = 0; fl < NFLAGS; fl++) {
            int32_t org3[16][3];
            lp.flags = g_flagsets[fl];
            random_origins(&r, org3, 50.0);
            org3[5][0] = lp.c[0];
            org3[5][1] = lp.c[1];
            org3[5][2] = lp.c[2];
            compare(&s, &b1, &lp, org3, LT_MASK_ALL, &t, "point light");
            lp.eu[0] = 64 * U;
            compare(&s, &b1, &lp, org3, LT_MASK_ALL, &t, "line light");
            lp.eu[0] = 0;
        }
        /* (5) axis-parallel rays: origins right below a light whose samples share x or z */
        for (f = 0; f < 16; f++) {
            on_ray(&l, org[f], f, f, 8, org[f]);
            org[f][1] = -150 * U;
        }
        for (fl = 0; fl < NFLAGS; fl++) {
            l.flags = g_flagsets[fl];
            compare(&s, &b1, &l, org, LT_MASK_ALL, &t, "axis-parallel");
        }
        unbuild(&b1);
    }
    tally_print("edge cases (vertices and edges on sample rays, box faces through ray points, "
                "half-plane penumbra, light edge-on with origins on the light plane and on a "
                "sample point, point and line lights, axis-parallel rays)", &t);
    assert_true(t.partial > 20);
    tally_assert(&t);
}

/* ---- generator and arguments ------------------------------------------------------------------ */

static void test_generator_and_args(void **state)
{
    lt_frusta_light_q16_t l;
    lt_frusta_table_q16_t tb;
    lt_frusta16_q16_t F;
    ltt_rng_t r;
    unsigned n = 0, bad = 0, i, j, a;
    (void)state;
    ltt_rng_seed(&r, 5);
    for (i = 0; i < 200; i++) {
        int32_t o[3];
        lt_ray16_q16_t pr;
        lt_mask16_t pk;
        unsigned f = i & 15u;
        random_light(&r, &l, 1.0 + 50.0 * ltt_rng_unit(&r), 0);
        assert_int_equal(lt_frusta_table_q16(&l, &g_sets, &tb), LT_OK);
        for (a = 0; a < 3; a++)
            o[a] = rnd(&r, -4000, 4000);
        assert_int_equal(lt_frusta_rays16_q16(&tb, o, f, &pr, &pk), LT_OK);
        for (j = 0; j < 16; j++) {
            lt_ray1_q16_t r1;
            int32_t L;
            int64_t tend;
            assert_int_equal(lt_frusta_ray1_q16(&tb, o, f, j, &r1), LT_OK);
            /* the packet lane and the single ray are the same ray */
            bad += r1.d[0] != pr.dx.l[j] || r1.d[1] != pr.dy.l[j] || r1.d[2] != pr.dz.l[j] ||
                   r1.tmax != pr.tmax.l[j];
            /* the ray ends exactly on its sample point: o + t_end d = c + (su eu + sv ev) / 512 */
            tend = (int64_t)r1.tmax;
            for (L = 0; L < 31 && (((int64_t)1 << (30 - L)) - (((int64_t)1 << (30 - L)) >> 10)) !=
                                      tend;
                 L++)
                ;
            assert_true(L < 31);
            for (a = 0; a < 3; a++) {
                int64_t s = (int64_t)l.c[a] + ((int64_t)tb.su[f].l[j] * l.eu[a] +
                                               (int64_t)tb.sv[f].l[j] * l.ev[a]) / 512;
                /* d = (s - o) << L exactly, and |d| < 2^30 */
                bad += (int64_t)r1.d[a] != (s - o[a]) * ((int64_t)1 << L);
                bad += r1.d[a] >= (1 << 30) || r1.d[a] <= -(1 << 30);
            }
            n++;
        }
    }
    ltt_report("lt_frusta_ray1/rays16_q16: %u rays: packet lane = single ray, direction = (sample "
               "point - o) << L exactly with |d| < 2^30, %u mismatches (bound 0)\n", n, bad);
    assert_int_equal(bad, 0);
    /* argument and range errors */
    memset(&l, 0, sizeof l);
    l.eu[0] = 100; /* off the 512-raw grid */
    assert_int_equal(lt_frusta_table_q16(&l, &g_sets, &tb), LT_E_ARG);
    l.eu[0] = 512;
    l.end_shift = 31;
    assert_int_equal(lt_frusta_table_q16(&l, &g_sets, &tb), LT_E_ARG);
    l.end_shift = 0;
    l.flags = 256; /* no such flag */
    assert_int_equal(lt_frusta_table_q16(&l, &g_sets, &tb), LT_E_ARG);
    l.flags = 0;
    l.c[1] = 4097 * U;
    assert_int_equal(lt_frusta_table_q16(&l, &g_sets, &tb), LT_E_RANGE);
    l.c[1] = 0;
    assert_int_equal(lt_frusta_table_q16(NULL, &g_sets, &tb), LT_E_ARG);
    assert_int_equal(lt_frusta_table_q16(&l, &g_sets, &tb), LT_OK);
    memset(&F, 0, sizeof F);
    F.ox.l[3] = 5000 * U; /* outside the geometry bound: dropped */
    assert_int_equal(lt_frusta_setup16_q16(&tb, LT_MASK_ALL, &F), LT_E_RANGE);
    assert_int_equal(F.active, 0xFFF7u);
    assert_int_equal(lt_frusta_occluded16_q16(NULL, NULL, &tb, &F), LT_E_ARG);
    {
        lt_ray1_q16_t r1;
        int32_t o[3] = {0, 5000 * U, 0};
        assert_int_equal(lt_frusta_ray1_q16(&tb, o, 0, 0, &r1), LT_E_RANGE);
        o[1] = 0;
        assert_int_equal(lt_frusta_ray1_q16(&tb, o, 16, 0, &r1), LT_E_ARG);
        assert_int_equal(lt_frusta_ray1_q16(&tb, o, 0, 16, &r1), LT_E_ARG);
    }
    ltt_report("lt_frusta: edges off the 2^-7 grid, end_shift 31, unknown flags, NULL -> LT_E_ARG; "
               "light or origin outside 2^GEOM -> LT_E_RANGE (the lane is dropped, the others "
               "traced); set or sample >= 16 -> LT_E_ARG\n");
}

/* ---- direct term and filter ------------------------------------------------------------------- */

static void test_direct(void **state)
{
    ltt_rng_t r;
    unsigned n = 0, bad = 0, i, lane;
    double maxe = 0.0;
    (void)state;
    ltt_rng_seed(&r, 8);
    for (i = 0; i < 400; i++) {
        lt_vq16_t p[3], g;
        lt_vq30_t nv[3];
        lt_q16_t m[3];
        lt_q30_t nl[3];
        double nd[3], nld[3] = {0.0, -1.0, 0.0}, md[3];
        lt_mask16_t k;
        unsigned a;
        for (a = 0; a < 3; a++)
            md[a] = ltt_rng_uniform(&r, -500, 500);
        for (a = 0; a < 3; a++) {
            m[a] = lt_q16_from_double_sat(md[a]);
            nl[a] = lt_q30_from_double_sat(nld[a]);
        }
        for (lane = 0; lane < 16; lane++) {
            double len = 0.0;
            for (a = 0; a < 3; a++) {
                nd[a] = ltt_rng_uniform(&r, -1, 1);
                len += nd[a] * nd[a];
            }
            len = sqrt(len);
            for (a = 0; a < 3; a++) {
                p[a].l[lane] = lt_q16_from_double_sat(ltt_rng_uniform(&r, -500, 500));
                nv[a].l[lane] = lt_q30_from_double_sat(nd[a] / len);
            }
        }
        k = lt_frusta_direct16_q16(p, nv, m, nl, LT_MASK_ALL, &g);
        for (lane = 0; lane < 16; lane++) {
            double w[3], w2 = 0.0, ca = 0.0, cb = 0.0, gd;
            for (a = 0; a < 3; a++) {
                w[a] = (double)m[a] / 65536.0 - (double)p[a].l[lane] / 65536.0;
                w2 += w[a] * w[a];
                ca += (double)nv[a].l[lane] / 1073741824.0 * w[a];
                cb -= (double)nl[a] / 1073741824.0 * w[a];
            }
            gd = ca > 0 && cb > 0 ? ca * cb / w2 : 0.0;
            if (fabs(gd - (double)g.l[lane] / 65536.0) > maxe && (((unsigned)k >> lane) & 1u))
                maxe = fabs(gd - (double)g.l[lane] / 65536.0);
            /* bound: 3 ulp of s15.16 plus the rounding of both dots (relative 2^-16 / |w|) */
            if ((((unsigned)k >> lane) & 1u) ? fabs(gd - (double)g.l[lane] / 65536.0) > 4.0 / 65536.0
                                   : gd > 4.0 / 65536.0)
                bad++;
            n++;
        }
    }
    ltt_report("lt_frusta_direct16_q16: %u lanes, max |err| %.3g vs double (bound 4 ulp = %.3g), "
               "%u failed\n", n, maxe, 4.0 / 65536.0, bad);
    assert_int_equal(bad, 0);
}

/* The filter's property: the output is exactly the mean of the pixels that pass both thresholds
 * against the centre (by a double-precision restatement), and changing any pixel that fails a
 * threshold never changes the output. */
static void test_filter(void **state)
{
    enum { W = 37, H = 23 };
    static lt_q16_t e[W * H], z[W * H], out[W * H], out2[W * H];
    static lt_q30_t nx[W * H], ny[W * H], nz[W * H];
    static uint8_t valid[W * H];
    static float ef[W * H], zf[W * H], nxf[W * H], nyf[W * H], nzf[W * H], outf[W * H];
    lt_frusta_filter_q16_t par;
    lt_frusta_filter_f32_t parf;
    ltt_rng_t r;
    unsigned rep, bad = 0, n = 0, isolated = 0, badf = 0;
    double maxe = 0.0;
    (void)state;
    ltt_rng_seed(&r, 12);
    par.depth_rel = LT_Q16(0.05);
    par.cos_min = LT_Q30(0.9);
    parf.depth_rel = 0.05f;
    parf.cos_min = 0.9f;
    for (rep = 0; rep < 20; rep++) {
        uint32_t x, y, i;
        /* patches of constant normal and depth with random edges, noise inside */
        for (i = 0; i < W * H; i++) {
            uint32_t px = i % W, py = i / W;
            unsigned patch = (px * 7u / (3u + rep % 5u) + py * 3u / (2u + rep % 3u)) % 4u;
            double nrm[4][3] = {{0, 1, 0}, {1, 0, 0}, {0.6, 0.8, 0}, {0, 0.8, 0.6}};
            double depth = patch == 3 ? 40.0 : 20.0 + (double)patch * 0.3;
            e[i] = (lt_q16_t)ltt_rng_below(&r, 65537);
            z[i] = lt_q16_from_double_sat(depth * (1.0 + 0.01 * ltt_rng_unit(&r)));
            nx[i] = lt_q30_from_double_sat(nrm[patch][0]);
            ny[i] = lt_q30_from_double_sat(nrm[patch][1]);
            nz[i] = lt_q30_from_double_sat(nrm[patch][2]);
            valid[i] = ltt_rng_below(&r, 10) != 0;
            ef[i] = (float)e[i] / 65536.0f;
            zf[i] = (float)z[i] / 65536.0f;
            nxf[i] = (float)nrm[patch][0];
            nyf[i] = (float)nrm[patch][1];
            nzf[i] = (float)nrm[patch][2];
        }
        for (y = 0; y < H; y++)
            for (x = 0; x < W; x += 16) {
                lt_frusta_filter16_q16(e, z, nx, ny, nz, valid, W, H, x, y, &par, out);
                lt_frusta_filter16_f32(ef, zf, nxf, nyf, nzf, valid, W, H, x, y, &parf, outf);
            }
        for (y = 0; y < H; y++)
            for (x = 0; x < W; x++) {
                uint32_t p = y * W + x;
                int dx, dy, cnt = 0;
                int64_t sum = 0;
                double expect;
                if (!valid[p]) {
                    bad += out[p] != 0;
                    continue;
                }
                for (dy = -1; dy <= 2; dy++)
                    for (dx = -1; dx <= 2; dx++) {
                        int64_t qx = (int64_t)x + dx, qy = (int64_t)y + dy;
                        uint32_t q;
                        double dot = 0.0;
                        if (qx < 0 || qy < 0 || qx >= W || qy >= H)
                            continue;
                        q = (uint32_t)(qy * W + qx);
                        if (!valid[q])
                            continue;
                        dot = ((double)nx[p] * nx[q] + (double)ny[p] * ny[q] +
                               (double)nz[p] * nz[q]) / 1152921504606846976.0;
                        if (q == p || (fabs((double)z[q] - z[p]) <=
                                           (double)lt_q16_mul_sat(z[p], par.depth_rel) &&
                                       dot >= 0.9 - 1e-9)) {
                            sum += e[q];
                            cnt++;
                        }
                    }
                expect = (double)sum / cnt;
                if (fabs(expect - out[p]) > 0.5 + 1e-9) {
                    if (bad++ < 5)
                        printf("  FAIL filter (%u,%u): %d vs %.2f over %d\n", x, y, out[p],
                               expect, cnt);
                }
                if (fabs(expect / 65536.0 - (double)outf[p]) > 1e-5)
                    badf++;
                if (fabs(expect - out[p]) > maxe)
                    maxe = fabs(expect - out[p]);
                isolated += cnt == 1;
                n++;
            }
        /* change every pixel of patch 3 (40 units deep): outputs outside that patch stay equal */
        memcpy(out2, out, sizeof out);
        for (x = 0; x < W * H; x++)
            if (z[x] > 30 * U)
                e[x] = (lt_q16_t)ltt_rng_below(&r, 65537);
        for (y = 0; y < H; y++)
            for (x = 0; x < W; x += 16)
                lt_frusta_filter16_q16(e, z, nx, ny, nz, valid, W, H, x, y, &par, out);
        for (x = 0; x < W * H; x++)
            if (z[x] <= 30 * U && out[x] != out2[x])
                bad++;
    }
    ltt_report("lt_frusta_filter16: %u pixels (20 patch images, 10%% invalid): output = mean of "
               "exactly the window pixels within depth 5%% and normal cos 0.9 of the centre, max "
               "|err| %.3g ulp (bound 0.5); changing a region across a depth edge changes no "
               "output outside it; %u failed; f32 twin %u off by > 1e-5; %u pixels isolated\n",
               n, maxe, bad, badf, isolated);
    assert_int_equal(bad, 0);
    assert_int_equal(badf, 0);
}

/* ---- host = sim tile hash and the bunny --------------------------------------------------------- */

static uint32_t fnv(uint32_t h, uint32_t v)
{
    unsigned i;
    for (i = 0; i < 4; i++) {
        h ^= (v >> (8 * i)) & 0xFFu;
        h *= 16777619u;
    }
    return h;
}

static void test_tile_hash(void **state)
{
    static tscene_t s;
    tbvh_t b;
    ltt_rng_t r;
    uint32_t h = 2166136261u, hf = 2166136261u, fl, rep, f;
    (void)state;
    ltt_rng_seed(&r, 2024);
    random_scene(&r, &s, 1000, 20.0);
    build(&s, 16, 8, &b);
    for (fl = 0; fl < NFLAGS; fl++)
        for (rep = 0; rep < 4; rep++) {
            lt_frusta_light_q16_t l;
            lt_frusta_table_q16_t tb;
            lt_frusta16_q16_t F;
            int32_t org[16][3];
            random_light(&r, &l, 30.0, g_flagsets[fl]);
            random_origins(&r, org, 10.0);
            assert_int_equal(lt_frusta_table_q16(&l, &g_sets, &tb), LT_OK);
            for (f = 0; f < 16; f++) {
                F.ox.l[f] = org[f][0];
                F.oy.l[f] = org[f][1];
                F.oz.l[f] = org[f][2];
            }
            assert_int_equal(lt_frusta_setup16_q16(&tb, LT_MASK_ALL, &F), LT_OK);
            assert_int_equal(lt_frusta_occluded16_q16(&b.q, s.tq, &tb, &F), LT_OK);
            for (f = 0; f < 16; f++)
                h = fnv(h, F.occl[f]);
            {
                lt_frusta_light_f32_t lf;
                lt_frusta_table_f32_t tbf;
                lt_frusta16_f32_t Ff;
                unsigned a;
                for (a = 0; a < 3; a++) {
                    lf.c[a] = (float)l.c[a] / 65536.0f;
                    lf.eu[a] = (float)l.eu[a] / 65536.0f;
                    lf.ev[a] = (float)l.ev[a] / 65536.0f;
                }
                lf.flags = l.flags;
                lf.end_shift = 0;
                assert_int_equal(lt_frusta_table_f32(&lf, &g_sets, &tbf), LT_OK);
                for (f = 0; f < 16; f++) {
                    Ff.ox.l[f] = (float)org[f][0] / 65536.0f;
                    Ff.oy.l[f] = (float)org[f][1] / 65536.0f;
                    Ff.oz.l[f] = (float)org[f][2] / 65536.0f;
                }
                assert_int_equal(lt_frusta_setup16_f32(&tbf, LT_MASK_ALL, &Ff), LT_OK);
                assert_int_equal(lt_frusta_occluded16_f32(&b.f, s.tf, &tbf, &Ff), LT_OK);
                for (f = 0; f < 16; f++)
                    hf = fnv(hf, Ff.occl[f]);
            }
        }
    unbuild(&b);
    /* tests/run.d/frusta.sh compares these lines between the host, sim and asan builds and, for
     * the second one, the firmware images under QEMU (tests/fw/fw_frusta.c) */
    {
        uint32_t fq = ltft_hash_q16(), ff = ltft_hash_f32();
        ltt_report("frusta fw tile hash: q16 0x%08x f32 0x%08x\n", fq, ff);
        assert_true(fq != 0 && ff != 0);
    }
    ltt_report("frusta tile hash: q16 %08x f32 %08x (%u tiles of 16 frusta, %u flag sets)\n", h, hf,
               (unsigned)(4 * NFLAGS), (unsigned)NFLAGS);
}

static int shared_missing(const char *path)
{
    const char *ci = getenv("CI");
    if (ci != NULL && strcmp(ci, "true") == 0) {
        printf("  FAIL %s missing under CI=true\n", path);
        return 1;
    }
    ltt_report("SKIP %s: not found (a fresh clone has no ../shared)\n", path);
    return 0;
}

/* Bunny on a ground plane, origins on random triangles (offset along the normal), a light above:
 * frusta = per-ray visibility on a real mesh. */
static void test_bunny(void **state)
{
    const char *root = getenv("LT_SHARED");
    char path[1024];
    lt_mesh_t m;
    lt_scene_t sc;
    lt_diag_t diag;
    static tscene_t s;
    tally_t t;
    tbvh_t b;
    ltt_rng_t r;
    unsigned rep, fl, i, a;
    (void)state;
    snprintf(path, sizeof path, "%s/scenes/bunny.obj", root != NULL ? root : "../shared");
    if (lt_mesh_load(path, &m, &diag) != 0) {
        assert_int_equal(shared_missing(path), 0);
        return;
    }
    assert_int_equal(lt_scene_prepare(&m, &sc, &diag), 0);
    assert_true(sc.ntris + 2 <= MAXT);
    memset(&t, 0, sizeof t);
    s.n = 0;
    for (i = 0; i < sc.ntris; i++) {
        int32_t p[3][3];
        unsigned v;
        for (v = 0; v < 3; v++)
            for (a = 0; a < 3; a++)
                p[v][a] = sc.tq[i].v0[a] + (v == 1 ? sc.tq[i].e1[a] : v == 2 ? sc.tq[i].e2[a] : 0);
        add_tri(&s, p[0], p[1], p[2]);
    }
    {
        /* ground plane just below the bunny (y min of the scaled mesh) */
        int32_t y0 = INT32_MAX, g0[3], g1[3], g2[3], g3[3];
        for (i = 0; i < s.n; i++)
            y0 = s.tq[i].v0[1] < y0 ? s.tq[i].v0[1] : y0;
        g0[0] = -1500 * U, g0[1] = y0, g0[2] = -1500 * U;
        g1[0] = 1500 * U, g1[1] = y0, g1[2] = -1500 * U;
        g2[0] = 1500 * U, g2[1] = y0, g2[2] = 1500 * U;
        g3[0] = -1500 * U, g3[1] = y0, g3[2] = 1500 * U;
        add_tri(&s, g0, g2, g1);
        add_tri(&s, g0, g3, g2);
    }
    build(&s, 16, 8, &b);
    ltt_rng_seed(&r, 31);
    for (rep = 0; rep < 12; rep++)
        for (fl = 0; fl < NFLAGS; fl += 2) {
            lt_frusta_light_q16_t l;
            int32_t org[16][3];
            unsigned f;
            memset(&l, 0, sizeof l);
            l.c[0] = -200 * U;
            l.c[1] = 1400 * U;
            l.c[2] = -300 * U;
            l.eu[0] = (int32_t)(100 + 60 * rep) * U;
            l.ev[2] = (int32_t)(100 + 60 * rep) * U;
            l.flags = g_flagsets[(fl + (rep & 1u)) % NFLAGS];
            for (f = 0; f < 16; f++) {
                /* a point inside a random triangle, lifted 2^-4 units along its normal */
                const lt_tri_f32_t *tr = &s.tf[ltt_rng_below(&r, s.n)];
                double u = ltt_rng_unit(&r), v = ltt_rng_unit(&r), nn[3], len, p0[3], e1[3], e2[3];
                for (a = 0; a < 3; a++) {
                    p0[a] = (double)tr->v0[a];
                    e1[a] = (double)tr->e1[a];
                    e2[a] = (double)tr->e2[a];
                }
                if (u + v > 1.0)
                    u = 1.0 - u, v = 1.0 - v;
                nn[0] = e1[1] * e2[2] - e1[2] * e2[1];
                nn[1] = e1[2] * e2[0] - e1[0] * e2[2];
                nn[2] = e1[0] * e2[1] - e1[1] * e2[0];
                len = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]) + 1e-30;
                if (nn[1] < 0)
                    len = -len;
                for (a = 0; a < 3; a++)
                    org[f][a] = lt_q16_from_double_sat(p0[a] + u * e1[a] + v * e2[a] +
                                                       nn[a] / len / 16.0);
            }
            compare(&s, &b, &l, org, LT_MASK_ALL, &t, "bunny");
        }
    unbuild(&b);
    lt_scene_free(&sc);
    lt_mesh_free(&m);
    tally_print("bunny + ground plane (3676 triangles, 12 light sizes 100..760 units, origins on "
                "the surface)", &t);
    tally_assert(&t);
}

/* ---- primary frusta (P-Frusta) ------------------------------------------------------------- */

/* Brute-force closest hit of one primary ray: the single-ray kernel over every triangle in index
 * order (strict t < tmax, so among equal t the smallest id), hits with det <= 0 dropped under
 * back-face culling. */
static void pref1_q16(const tscene_t *s, const lt_ray1_q16_t *r0, uint32_t flags, int32_t *id,
                      lt_q16_t *t)
{
    lt_ray1_q16_t cur = *r0;
    uint32_t i;
    *id = -1;
    for (i = 0; i < s->n; i++) {
        lt_ray1_q16_t rr = cur;
        if (ltt_tri1_q16(&rr, &s->tq[i]) &&
            ((flags & LT_FRUSTA_BACKFACE) == 0 || front_q16(r0, &s->tq[i]))) {
            cur = rr;
            *id = (int32_t)i;
        }
    }
    *t = cur.tmax;
}

static void pref1_f32(const tscene_t *s, const lt_ray1_f32_t *r0, uint32_t flags, int32_t *id,
                      float *t)
{
    lt_ray1_f32_t cur = *r0;
    uint32_t i;
    *id = -1;
    for (i = 0; i < s->n; i++) {
        lt_ray1_f32_t rr = cur;
        if (ltt_tri1_f32(&rr, &s->tf[i]) &&
            ((flags & LT_FRUSTA_BACKFACE) == 0 || front_f32(r0, &s->tf[i]))) {
            cur = rr;
            *id = (int32_t)i;
        }
    }
    *t = cur.tmax;
}

typedef struct ptally {
    unsigned long rays, hits, ties, bad_fr, bad_pk, bad_bvh, bvh_ties, bad_gen;
    unsigned long f32_rays, bad_f32, bad_f32_pk, blocks, partial_tiles, spurious, spurious_f32;
} ptally_t;

static int ptie_q16(const tscene_t *s, const lt_ray1_q16_t *r1, int32_t id, lt_q16_t t);

/* Whether a closest-hit answer (id, t) that differs from the reference is still right: it is a
 * kernel hit of the ray (or a miss), and every kernel hit before it in (t, id) order is not
 * genuine. Returns 1 if so. */
static int pexcused_q16(const tscene_t *s, const lt_ray1_q16_t *r1, uint32_t flags, int32_t id,
                        lt_q16_t t)
{
    double o[3], d[3], v[9];
    uint32_t i;
    unsigned a;
    if (id >= 0 && (!ptie_q16(s, r1, id, t) ||
                    ((flags & LT_FRUSTA_BACKFACE) != 0 && !front_q16(r1, &s->tq[id]))))
        return 0;
    for (a = 0; a < 3; a++) {
        o[a] = (double)r1->o[a] / 65536.0;
        d[a] = (double)r1->d[a] / 1073741824.0;
    }
    for (i = 0; i < s->n; i++) {
        lt_ray1_q16_t rr = *r1;
        const lt_tri_q16_t *tr = &s->tq[i];
        if (!ltt_tri1_q16(&rr, tr) ||
            ((flags & LT_FRUSTA_BACKFACE) != 0 && !front_q16(r1, tr)))
            continue;
        if (id >= 0 && (rr.tmax > t || (rr.tmax == t && (int32_t)i >= id)))
            continue;
        for (a = 0; a < 3; a++) {
            v[a] = (double)tr->v0[a] / 65536.0;
            v[3 + a] = (double)((int64_t)tr->v0[a] + tr->e1[a]) / 65536.0;
            v[6 + a] = (double)((int64_t)tr->v0[a] + tr->e2[a]) / 65536.0;
        }
        if (lt_ss_hit_genuine(o, d, v, LT_SS_GENUINE_PAD,
                     (double)rr.tmax / 65536.0))
            return 0;
    }
    return 1;
}

static int pexcused_f32(const tscene_t *s, const lt_ray1_f32_t *r1, uint32_t flags, int32_t id,
                        float t)
{
    double o[3], d[3], v[9], pad = 0.0;
    uint32_t i;
    unsigned a;
    if (id >= 0) {
        lt_ray1_f32_t rr = *r1;
        if ((uint32_t)id >= s->n || !ltt_tri1_f32(&rr, &s->tf[id]) || rr.tmax != t ||
            ((flags & LT_FRUSTA_BACKFACE) != 0 && !front_f32(r1, &s->tf[id])))
            return 0;
    }
    /* the float BVH pads by 2^-18 of the largest coordinate */
    for (i = 0; i < s->n; i++)
        for (a = 0; a < 3; a++) {
            double c = fabs((double)s->tf[i].v0[a]) + fabs((double)s->tf[i].e1[a]) +
                       fabs((double)s->tf[i].e2[a]);
            pad = c > pad ? c : pad;
        }
    pad = ldexp(pad, -20); /* a quarter of the float BVH's pad */
    for (a = 0; a < 3; a++) {
        o[a] = (double)r1->o[a];
        d[a] = (double)r1->d[a];
    }
    for (i = 0; i < s->n; i++) {
        lt_ray1_f32_t rr = *r1;
        const lt_tri_f32_t *tr = &s->tf[i];
        if (!ltt_tri1_f32(&rr, tr) ||
            ((flags & LT_FRUSTA_BACKFACE) != 0 && !front_f32(r1, tr)))
            continue;
        if (id >= 0 && (rr.tmax > t || (rr.tmax == t && (int32_t)i >= id)))
            continue;
        for (a = 0; a < 3; a++) {
            v[a] = (double)tr->v0[a];
            v[3 + a] = (double)tr->v0[a] + (double)tr->e1[a];
            v[6 + a] = (double)tr->v0[a] + (double)tr->e2[a];
        }
        if (lt_ss_hit_genuine(o, d, v, pad, (double)rr.tmax))
            return 0;
    }
    return 1;
}

#define PMAXW 64
#define PMAXH 48

/* Reference per pixel for both culling settings (index 0: two-sided, 1: back-face culled). */
typedef struct pref {
    int32_t idq[2][PMAXH][PMAXW], idf[2][PMAXH][PMAXW];
    lt_q16_t tq[2][PMAXH][PMAXW];
    float tf[2][PMAXH][PMAXW];
    unsigned ties; /* pixels where another triangle gives the same t as the winner (q16) */
} pref_t;

static void pref_fill(const tscene_t *s, const lt_frusta_vtable_q16_t *vq,
                      const lt_frusta_vtable_f32_t *vf, pref_t *R)
{
    uint32_t x, y;
    int c;
    R->ties = 0;
    for (y = 0; y < vq->height; y++)
        for (x = 0; x < vq->width; x++) {
            lt_ray1_q16_t r1;
            lt_ray1_f32_t r1f;
            uint32_t i;
            assert_int_equal(lt_frusta_pray1_q16(vq, x, y, &r1), LT_OK);
            assert_int_equal(lt_frusta_pray1_f32(vf, x, y, &r1f), LT_OK);
            for (c = 0; c < 2; c++) {
                uint32_t fl = c != 0 ? LT_FRUSTA_BACKFACE : 0u;
                pref1_q16(s, &r1, fl, &R->idq[c][y][x], &R->tq[c][y][x]);
                pref1_f32(s, &r1f, fl, &R->idf[c][y][x], &R->tf[c][y][x]);
            }
            /* count exact ties of the two-sided winner (another triangle, the same t) */
            if (R->idq[0][y][x] >= 0)
                for (i = 0; i < s->n; i++) {
                    lt_ray1_q16_t rr = r1;
                    if ((int32_t)i != R->idq[0][y][x] && ltt_tri1_q16(&rr, &s->tq[i]) &&
                        rr.tmax == R->tq[0][y][x]) {
                        R->ties++;
                        break;
                    }
                }
        }
}

/* One triangle alone gives t to the ray (a tie partner of the reference's winner). */
static int ptie_q16(const tscene_t *s, const lt_ray1_q16_t *r1, int32_t id, lt_q16_t t)
{
    lt_ray1_q16_t rr = *r1;
    return id >= 0 && (uint32_t)id < s->n && ltt_tri1_q16(&rr, &s->tq[id]) && rr.tmax == t;
}

/* P-Frusta (shallow tree), P-Packet (deep tree) and, two-sided, lt_bvh_trace16 against the
 * brute-force reference on every pixel of the view, s15.16 and float32; also checks that the
 * packet lanes and single rays are the same rays. Blocks cover the image and one block past it. */
static void pcompare(const tscene_t *s, const tbvh_t *shal, const tbvh_t *deep,
                     const lt_frusta_view_q16_t *v, const lt_frusta_view_f32_t *vfl,
                     const pref_t *R, ptally_t *T, const char *what)
{
    static lt_frusta_prim16_q16_t P;
    static lt_frusta_prim16_f32_t Pf;
    lt_frusta_vtable_q16_t vt;
    lt_frusta_vtable_f32_t vtf;
    uint32_t bx, by, f, j;
    int c = (v->flags & LT_FRUSTA_BACKFACE) != 0;

    assert_int_equal(lt_frusta_vtable_q16(v, &vt), LT_OK);
    assert_int_equal(lt_frusta_vtable_f32(vfl, &vtf), LT_OK);
    for (by = 0; by < v->height + 16u; by += 16)
        for (bx = 0; bx < v->width + 16u; bx += 16) {
            assert_int_equal(lt_frusta_psetup16_q16(&vt, bx, by, &P), LT_OK);
            assert_int_equal(lt_frusta_trace16_q16(&shal->q, s->tq, &vt, &P), LT_OK);
            assert_int_equal(lt_frusta_psetup16_f32(&vtf, bx, by, &Pf), LT_OK);
            assert_int_equal(lt_frusta_trace16_f32(&shal->f, s->tf, &vtf, &Pf), LT_OK);
            assert_int_equal(P.active, Pf.active);
            T->blocks++;
            for (f = 0; f < 16; f++) {
                uint32_t tx = bx + 4u * (f & 3u), ty = by + 4u * (f >> 2);
                lt_ray16_q16_t pr, br;
                lt_ray16_f32_t prf;
                lt_hit16_t ph, bh, phf;
                lt_mask16_t k, kf;
                if (P.live[f] == 0) {
                    assert_true(tx >= v->width || ty >= v->height);
                    continue;
                }
                T->partial_tiles += P.live[f] != 0xFFFFu;
                assert_int_equal(lt_frusta_prays16_q16(&vt, tx, ty, &pr, &k), LT_OK);
                assert_int_equal(k, P.live[f]);
                br = pr;
                assert_int_equal(lt_frusta_packet_trace16_q16(&deep->q, s->tq, v->flags, vt.o,
                                                              &pr, k, &ph),
                                 LT_OK);
                if (!c)
                    assert_int_equal(lt_bvh_trace16_q16(&deep->q, s->tq, &br, k, &bh), LT_OK);
                assert_int_equal(lt_frusta_prays16_f32(&vtf, tx, ty, &prf, &kf), LT_OK);
                assert_int_equal(kf, k);
                assert_int_equal(lt_frusta_packet_trace16_f32(&deep->f, s->tf, v->flags, vtf.o,
                                                              &prf, kf, &phf),
                                 LT_OK);
                for (j = 0; j < 16; j++) {
                    uint32_t x = tx + (j & 3u), y = ty + (j >> 2);
                    lt_ray1_q16_t r1;
                    lt_ray1_f32_t r1f;
                    int32_t rid, ridf;
                    lt_q16_t rt;
                    float rtf;
                    if (((unsigned)k >> j & 1u) == 0)
                        continue;
                    rid = R->idq[c][y][x];
                    rt = R->tq[c][y][x];
                    ridf = R->idf[c][y][x];
                    rtf = R->tf[c][y][x];
                    assert_int_equal(lt_frusta_pray1_q16(&vt, x, y, &r1), LT_OK);
                    assert_int_equal(lt_frusta_pray1_f32(&vtf, x, y, &r1f), LT_OK);
                    /* the packet lane, the single ray and the frusta's generator: the same ray */
                    T->bad_gen += r1.d[0] != br.dx.l[j] || r1.d[1] != br.dy.l[j] ||
                                  r1.d[2] != br.dz.l[j] ||
                                  memcmp(&r1f.d[0], &prf.dx.l[j], 4) != 0 ||
                                  memcmp(&r1f.d[1], &prf.dy.l[j], 4) != 0 ||
                                  memcmp(&r1f.d[2], &prf.dz.l[j], 4) != 0;
                    T->rays++;
                    T->f32_rays++;
                    T->hits += rid >= 0;
                    if ((P.id[f].l[j] != rid || P.t[f].l[j] != rt) &&
                        pexcused_q16(s, &r1, v->flags, P.id[f].l[j], P.t[f].l[j]))
                        T->spurious++;
                    else if (P.id[f].l[j] != rid || P.t[f].l[j] != rt) {
                        if (T->bad_fr++ < 6)
                            printf("  FAIL %s P-Frusta: pixel (%u,%u) flags %u id %d t %d, "
                                   "per-ray %d t %d\n", what, x, y, v->flags, P.id[f].l[j],
                                   P.t[f].l[j], rid, rt);
                    }
                    if ((ph.id.l[j] != rid || pr.tmax.l[j] != rt) &&
                        pexcused_q16(s, &r1, v->flags, ph.id.l[j], pr.tmax.l[j]))
                        T->spurious++;
                    else if (ph.id.l[j] != rid || pr.tmax.l[j] != rt) {
                        if (T->bad_pk++ < 6)
                            printf("  FAIL %s P-Packet: pixel (%u,%u) id %d t %d, per-ray %d t "
                                   "%d\n", what, x, y, ph.id.l[j], pr.tmax.l[j], rid, rt);
                    }
                    if (!c) {
                        /* lt_bvh: the same t; the same id up to exact ties */
                        if ((br.tmax.l[j] != rt ||
                             (bh.id.l[j] != rid && !ptie_q16(s, &r1, bh.id.l[j], rt))) &&
                            !pexcused_q16(s, &r1, 0, bh.id.l[j], br.tmax.l[j])) {
                            if (T->bad_bvh++ < 6)
                                printf("  FAIL %s lt_bvh_trace16: pixel (%u,%u) id %d t %d, "
                                       "per-ray %d t %d\n", what, x, y, bh.id.l[j],
                                       br.tmax.l[j], rid, rt);
                        }
                        T->bvh_ties += bh.id.l[j] != rid && br.tmax.l[j] == rt;
                    }
                    if ((Pf.id[f].l[j] != ridf || memcmp(&Pf.t[f].l[j], &rtf, 4) != 0) &&
                        pexcused_f32(s, &r1f, v->flags, Pf.id[f].l[j], Pf.t[f].l[j]))
                        T->spurious_f32++;
                    else if (Pf.id[f].l[j] != ridf || memcmp(&Pf.t[f].l[j], &rtf, 4) != 0) {
                        if (T->bad_f32++ < 6)
                            printf("  FAIL %s P-Frusta f32: pixel (%u,%u) id %d t %g, per-ray "
                                   "%d t %g\n", what, x, y, Pf.id[f].l[j],
                                   (double)Pf.t[f].l[j], ridf, (double)rtf);
                    }
                    if ((phf.id.l[j] != ridf || memcmp(&prf.tmax.l[j], &rtf, 4) != 0) &&
                        pexcused_f32(s, &r1f, v->flags, phf.id.l[j], prf.tmax.l[j]))
                        T->spurious_f32++;
                    else if (phf.id.l[j] != ridf || memcmp(&prf.tmax.l[j], &rtf, 4) != 0) {
                        if (T->bad_f32_pk++ < 6)
                            printf("  FAIL %s P-Packet f32: pixel (%u,%u) id %d vs %d\n", what,
                                   x, y, phf.id.l[j], ridf);
                    }
                }
            }
        }
}

static void ptally_print(const char *name, const ptally_t *t, unsigned long ties)
{
    ltt_report("%s: %lu blocks, %lu rays (%lu hits, %lu exact ties, %lu partial tiles): "
               "P-Frusta != per-ray closest hit %lu, P-Packet != per-ray %lu, lt_bvh_trace16 t != "
               "per-ray %lu (ids differ only at ties: %lu), generator mismatches %lu (bound 0); "
               "f32 %lu rays, P-Frusta %lu, P-Packet %lu mismatches (bound 0); differences "
               "explained by reference hits that are not genuine (off the padded box or t): q16 %lu, "
               "f32 %lu\n",
               name, t->blocks, t->rays, t->hits, ties, t->partial_tiles, t->bad_fr, t->bad_pk,
               t->bad_bvh, t->bvh_ties, t->bad_gen, t->f32_rays, t->bad_f32, t->bad_f32_pk,
               t->spurious, t->spurious_f32);
}

static void ptally_assert(const ptally_t *t)
{
    assert_int_equal(t->bad_fr, 0);
    assert_int_equal(t->bad_pk, 0);
    assert_int_equal(t->bad_bvh, 0);
    assert_int_equal(t->bad_gen, 0);
    assert_int_equal(t->bad_f32, 0);
    assert_int_equal(t->bad_f32_pk, 0);
}

/* A pinhole camera in scene units (the renderer's lt_camera_t), both views via lt_ss_pview. */
static void pcam(const double eye[3], const double target[3], double fov, uint32_t w, uint32_t h,
                 uint32_t flags, lt_frusta_view_q16_t *vq, lt_frusta_view_f32_t *vf)
{
    lt_camera_t c;
    double up[3] = {0.0, 1.0, 0.0}, len;
    lt_diag_t diag;
    int a;
    memset(&c, 0, sizeof c);
    for (a = 0; a < 3; a++) {
        c.eye[a] = eye[a];
        c.fwd[a] = target[a] - eye[a];
    }
    len = sqrt(c.fwd[0] * c.fwd[0] + c.fwd[1] * c.fwd[1] + c.fwd[2] * c.fwd[2]);
    for (a = 0; a < 3; a++)
        c.fwd[a] /= len;
    if (fabs(c.fwd[1]) > 0.99)
        up[0] = 1.0, up[1] = 0.0;
    c.right[0] = c.fwd[1] * up[2] - c.fwd[2] * up[1];
    c.right[1] = c.fwd[2] * up[0] - c.fwd[0] * up[2];
    c.right[2] = c.fwd[0] * up[1] - c.fwd[1] * up[0];
    len = sqrt(c.right[0] * c.right[0] + c.right[1] * c.right[1] + c.right[2] * c.right[2]);
    for (a = 0; a < 3; a++)
        c.right[a] /= len;
    c.up[0] = c.right[1] * c.fwd[2] - c.right[2] * c.fwd[1];
    c.up[1] = c.right[2] * c.fwd[0] - c.right[0] * c.fwd[2];
    c.up[2] = c.right[0] * c.fwd[1] - c.right[1] * c.fwd[0];
    c.tan_half_fov = tan(0.5 * fov * 3.14159265358979323846 / 180.0);
    c.width = w;
    c.height = h;
    assert_int_equal(lt_ss_pview(&c, flags, vq, vf, &diag), 0);
}

/* Every flag set over one view, with both references computed once. */
static void pcompare_all(const tscene_t *s, const tbvh_t *shal, const tbvh_t *deep,
                         lt_frusta_view_q16_t *vq, lt_frusta_view_f32_t *vf, ptally_t *T,
                         unsigned long *ties, const char *what)
{
    static pref_t R;
    lt_frusta_vtable_q16_t vt;
    lt_frusta_vtable_f32_t vtf;
    unsigned fl;
    assert_true(vq->width <= PMAXW && vq->height <= PMAXH);
    vq->flags = vf->flags = 0;
    assert_int_equal(lt_frusta_vtable_q16(vq, &vt), LT_OK);
    assert_int_equal(lt_frusta_vtable_f32(vf, &vtf), LT_OK);
    pref_fill(s, &vt, &vtf, &R);
    *ties += R.ties;
    for (fl = 0; fl < NFLAGS; fl++) {
        /* FS and P256 are the shadow frusta's; TRIPAR (primary only) on every other set */
        vq->flags = vf->flags = (g_flagsets[fl] & ~(LT_FRUSTA_FS | LT_FRUSTA_P256)) |
                                (fl % 2u == 1u ? LT_FRUSTA_TRIPAR : 0u);
        pcompare(s, shal, deep, vq, vf, &R, T, what);
    }
}

#if LT_COST_MODE == LT_COST_SIM
/* Event totals of the simulator so far (all phases). */
static void sim_events(uint64_t ev[LT_EV__COUNT])
{
    lt_sim_totals_t tot;
    unsigned e, ph;
    lt_sim_totals(&tot);
    for (e = 0; e < LT_EV__COUNT; e++)
        for (ev[e] = 0, ph = 0; ph < LT_PH__COUNT; ph++)
            ev[e] += tot.ctr[ph][LT_OP__COUNT + e];
}
#endif

static void test_primary_random(void **state)
{
    ptally_t t;
    unsigned long ties = 0;
    ltt_rng_t r;
    unsigned sc, cam;
#if LT_COST_MODE == LT_COST_SIM
    uint64_t ev0[LT_EV__COUNT];
    sim_events(ev0);
#endif
    (void)state;
    memset(&t, 0, sizeof t);
    ltt_rng_seed(&r, 4242);
    for (sc = 0; sc < 6; sc++) {
        static tscene_t s;
        tbvh_t shal, deep;
        unsigned n = 150u + 150u * sc;
        double size = sc % 3 == 0 ? 8.0 : (sc % 3 == 1 ? 30.0 : 80.0);
        /* odd scenes with Moller-Trumbore: its corner culling is checked too */
        ltt_isect = sc & 1u ? LT_ISECT_MT : LT_ISECT_WT;
        random_scene(&r, &s, n, size);
        build(&s, sc & 1u ? 16 : 8, sc & 1u ? 8 : 4, &shal);
        build(&s, 4, 1, &deep);
        for (cam = 0; cam < 2; cam++) {
            lt_frusta_view_q16_t vq;
            lt_frusta_view_f32_t vf;
            double eye[3], tgt[3], fov = ltt_rng_uniform(&r, 20.0, 100.0);
            uint32_t w = 17u + ltt_rng_below(&r, 24), h = 13u + ltt_rng_below(&r, 20);
            /* outside looking in, or inside the blockers (triangles behind the eye too) */
            double d = cam == 0 ? 500.0 : 30.0;
            eye[0] = ltt_rng_uniform(&r, -d, d);
            eye[1] = ltt_rng_uniform(&r, cam == 0 ? 150.0 : -50.0, cam == 0 ? 400.0 : 50.0);
            eye[2] = ltt_rng_uniform(&r, -d, d);
            tgt[0] = ltt_rng_uniform(&r, -60, 60);
            tgt[1] = ltt_rng_uniform(&r, -60, 60);
            tgt[2] = ltt_rng_uniform(&r, -60, 60);
            pcam(eye, tgt, fov, w, h, 0, &vq, &vf);
            pcompare_all(&s, &shal, &deep, &vq, &vf, &t, &ties, "random");
        }
        unbuild(&shal);
        unbuild(&deep);
    }
    ltt_isect = LT_ISECT_WT;
    ptally_print("primary random scenes (6 scenes, 2 cameras each, 13 flag sets (FS and P256 are the shadow frusta's; TRIPAR on every other one), leaf 8 and 16; "
                 "odd scenes Moller-Trumbore)",
                 &t, ties);
#if LT_COST_MODE == LT_COST_SIM
    {
        /* the equality is only worth something if the culling removed pairs (this test alone;
         * the brute-force reference fetches no triangles) */
        uint64_t ev[LT_EV__COUNT];
        unsigned e;
        sim_events(ev);
        for (e = 0; e < LT_EV__COUNT; e++)
            ev[e] -= ev0[e];
        ltt_report("  sim events of the primary traces: TRI_FETCH %llu TRI_KEPT %llu CULL_BACK %llu "
                   "CULL_CORNER %llu\n",
                   (unsigned long long)ev[LT_EV_TRI_FETCH], (unsigned long long)ev[LT_EV_TRI_KEPT],
                   (unsigned long long)ev[LT_EV_CULL_BACK],
                   (unsigned long long)ev[LT_EV_CULL_CORNER]);
        ltt_report("  sim events so far: LEAF_CULL %llu SPLIT %llu TRIPAR %llu (the leaf culling, "
                   "split walks and triangle-parallel leaves of the LEAFRAY / SPLIT / TRIPAR flag "
                   "sets fired)\n",
                   (unsigned long long)ev[LT_EV_LEAF_CULL], (unsigned long long)ev[LT_EV_SPLIT],
                   (unsigned long long)ev[LT_EV_TRIPAR]);
        assert_true(ev[LT_EV_CULL_CORNER] > 1000u);
        assert_true(ev[LT_EV_CULL_BACK] > 1000u);
        assert_true(ev[LT_EV_LEAF_CULL] > 100u);
        assert_true(ev[LT_EV_SPLIT] > 100u);
        assert_true(ev[LT_EV_TRIPAR] > 100u);
    }
#endif
    assert_true(t.hits > 1000);
    ptally_assert(&t);
}

/* A view whose directions are multiples of 2^-16 units (2^14 raw s1.30 and 2^-23 in float), so
 * points o + 2^k d are exact s15.16 values: vertices and edges can be put exactly on rays. */
static void pgrid_view(int32_t eye[3], lt_frusta_view_q16_t *vq, lt_frusta_view_f32_t *vf,
                       uint32_t w, uint32_t h, int axis_parallel)
{
    unsigned a;
    for (a = 0; a < 3; a++)
        vq->o[a] = eye[a];
    /* looking down -y; x across, z down the image; axis_parallel: column w/2 and row h/2 have
     * exactly zero x / z components */
    vq->dx[0] = 3 << 20, vq->dx[1] = axis_parallel ? 0 : 1 << 14, vq->dx[2] = 0;
    vq->dy[0] = axis_parallel ? 0 : -(1 << 15), vq->dy[1] = 0, vq->dy[2] = 3 << 20;
    vq->d0[0] = -(int32_t)(w / 2) * vq->dx[0] + (axis_parallel ? 0 : 5 << 14);
    vq->d0[1] = -(1 << 29);
    vq->d0[2] = -(int32_t)(h / 2) * vq->dy[2] + (axis_parallel ? 0 : 3 << 14);
    vq->width = w;
    vq->height = h;
    vq->flags = 0;
    for (a = 0; a < 3; a++) {
        vf->o[a] = (float)eye[a] / 65536.0f;
        vf->d0[a] = (float)vq->d0[a] / 1073741824.0f;
        vf->dx[a] = (float)vq->dx[a] / 1073741824.0f;
        vf->dy[a] = (float)vq->dy[a] / 1073741824.0f;
    }
    vf->width = w;
    vf->height = h;
    vf->flags = 0;
}

/* The point at parameter 2^k on pixel (x, y)'s ray of a grid view (exact). */
static void pon_ray(const lt_frusta_view_q16_t *v, uint32_t x, uint32_t y, unsigned k,
                    int32_t p[3])
{
    unsigned a;
    for (a = 0; a < 3; a++) {
        int64_t d = (int64_t)v->d0[a] + (int64_t)x * v->dx[a] + (int64_t)y * v->dy[a];
        p[a] = (int32_t)(v->o[a] + (d >> 14) * ((int64_t)1 << k));
    }
}

/* TRIPAR events so far (0 outside sim builds). */
static uint64_t tripar_events(void)
{
#if LT_COST_MODE == LT_COST_SIM
    uint64_t ev[LT_EV__COUNT];
    sim_events(ev);
    return ev[LT_EV_TRIPAR];
#else
    return 0;
#endif
}

/* In sim builds: the triangle-parallel leaf ran (TRIPAR events since e0) exactly when asked for
 * and fewer than 8 rays reached the 8-triangle leaf. */
static void tripar_ran(const char *what, uint64_t e0, uint32_t flags, unsigned long nmeet,
                       unsigned long *bad)
{
#if LT_COST_MODE == LT_COST_SIM
    uint64_t e1 = tripar_events();
    if ((e1 != e0) != ((flags & LT_FRUSTA_TRIPAR) != 0 && nmeet < 8)) {
        (*bad)++;
        printf("  FAIL %s: %lu rays, flags %u: TRIPAR events %llu\n", what, nmeet, (unsigned)flags,
               (unsigned long long)(e1 - e0));
    }
#else
    (void)what, (void)e0, (void)flags, (void)nmeet, (void)bad;
#endif
}

/* Lane j of a q16 and a float32 packet from o (of) along the unit (dx, dy, dz), t in [t0, t1]. */
static void tripar_lane(lt_ray16_q16_t *r, lt_ray16_f32_t *rf, int j, const int32_t o[3],
                        const float of[3], double dx, double dy, double dz, double t0, double t1)
{
    r->ox.l[j] = o[0], r->oy.l[j] = o[1], r->oz.l[j] = o[2];
    r->dx.l[j] = lt_q30_from_double_sat(dx);
    r->dy.l[j] = lt_q30_from_double_sat(dy);
    r->dz.l[j] = lt_q30_from_double_sat(dz);
    r->tmin.l[j] = (int32_t)(t0 * U);
    r->tmax.l[j] = (int32_t)(t1 * U);
    rf->ox.l[j] = of[0], rf->oy.l[j] = of[1], rf->oz.l[j] = of[2];
    rf->dx.l[j] = (float)dx, rf->dy.l[j] = (float)dy, rf->dz.l[j] = (float)dz;
    rf->tmin.l[j] = (float)t0;
    rf->tmax.l[j] = (float)t1;
}

/* LT_FRUSTA_TRIPAR in the packet walk (pk_closest, the P-Packet baseline and P-Frusta's split
 * walks): a leaf of 8 exact copies of one triangle (ids 0-7, an 8-way tie) met by 1, 3 or all 16
 * rays of a packet; with and without back-face culling, both paths. The hit must be id 0 (the smallest of a tie) at the same t as without
 * TRIPAR; with fewer rays than triangles the triangle-parallel leaf must have run (sim event). */
static void test_tripar_ties(void **state)
{
    static tscene_t s;
    tbvh_t b;
    int32_t v0[3] = {-4 * U, -4 * U, 0}, v1[3] = {4 * U, -4 * U, 0}, v2[3] = {0, 4 * U, 0};
    int32_t o[3] = {0, 0, -10 * U};
    float of[3] = {0.0f, 0.0f, -10.0f};
    unsigned long cases = 0, bad = 0, nmeet, fl, i;
    (void)state;
    s.n = 0;
    for (i = 0; i < 8; i++) /* facing o (N = e1 x e2 towards -z): back-face culling keeps them */
        add_tri(&s, v0, v2, v1);
    build(&s, 8, 8, &b);
    for (nmeet = 1; nmeet <= 16; nmeet = nmeet == 1 ? 3 : nmeet + 13)
        for (fl = 0; fl < 4; fl++) {
            uint32_t flags = ((fl & 1u) ? LT_FRUSTA_TRIPAR : 0u) |
                             ((fl & 2u) ? LT_FRUSTA_BACKFACE : 0u);
            lt_ray16_q16_t r;
            lt_ray16_f32_t rf;
            lt_hit16_t h, hf;
            uint64_t e0;
            int j;
            memset(&r, 0, sizeof r);
            memset(&rf, 0, sizeof rf);
            for (j = 0; j < LT_LANES; j++) {
                /* lanes below nmeet towards points inside the triangle, the others away */
                double dx = (unsigned)j < nmeet ? 0.01 * j : 0.9, dy = (unsigned)j < nmeet ? 0.0 : 0.3;
                tripar_lane(&r, &rf, j, o, of, dx, dy, sqrt(1.0 - dx * dx - dy * dy), 0.0, 100.0);
            }
            lt_ray16_q16_setup(&r);
            lt_ray16_f32_setup(&rf);
            e0 = tripar_events();
            assert_int_equal(lt_frusta_packet_trace16_q16(&b.q, s.tq, flags, o, &r, 0xFFFFu, &h),
                             LT_OK);
            assert_int_equal(lt_frusta_packet_trace16_f32(&b.f, s.tf, flags, of, &rf, 0xFFFFu, &hf),
                             LT_OK);
            tripar_ran("tripar ties", e0, flags, nmeet, &bad);
            for (j = 0; j < LT_LANES; j++) {
                int e;
                cases++;
                if ((unsigned)j < nmeet)
                    e = h.id.l[j] != 0 || hf.id.l[j] != 0 || r.tmax.l[j] <= 9 * U ||
                        r.tmax.l[j] >= 11 * U || !(rf.tmax.l[j] > 9.0f && rf.tmax.l[j] < 11.0f);
                else
                    e = h.id.l[j] != -1 || hf.id.l[j] != -1;
                if (e && bad++ < 6)
                    printf("  FAIL tripar ties: %lu rays, flags %u, lane %d: id %d / %d t %d / %g\n",
                           nmeet, (unsigned)flags, j, h.id.l[j], hf.id.l[j], r.tmax.l[j],
                           (double)rf.tmax.l[j]);
            }
        }
    unbuild(&b);
    ltt_report("triangle-parallel leaves (LT_FRUSTA_TRIPAR) at an 8-way tie: 8 copies of a triangle "
               "in one leaf, 1, 3 or 16 of a packet's rays meeting it, with and without TRIPAR and "
               "back-face culling, q16 and f32: %lu lane cases, %lu wrong (id 0 at t 10 expected, "
               "-1 elsewhere; in sim builds the triangle-parallel leaf ran exactly when fewer rays "
               "than triangles met it) (bound 0)\n", cases, bad);
    assert_int_equal(bad, 0);
}

/* LT_FRUSTA_TRIPAR in the any-hit packet walk (pk_any: the S-Packet baseline and the shadow
 * frusta's split walks): one leaf of 8 triangles on four planes at t = 10, 20, 40, 70 along +z,
 * two per plane, facing the origin or away (at t = 20 both away), met by 1, 3 or all 16 rays of a
 * packet whose lanes have different (tmin, tmax). A lane is occluded exactly when a plane it may
 * see (all four without back-face culling, 10, 40 and 70 with it) lies strictly inside
 * (tmin, tmax); the same with and without TRIPAR, both paths; in sim builds the triangle-parallel
 * leaf must run exactly when asked for and fewer than 8 rays reach the leaf. */
static void test_tripar_any(void **state)
{
    static tscene_t s;
    tbvh_t b;
    static const double zs[4] = {0.0, 10.0, 30.0, 60.0};     /* t = 10, 20, 40, 70 */
    static const int face[4][2] = {{1, 1}, {0, 0}, {1, 0}, {0, 1}}; /* 1: faces the origin */
    static const double tmins[3] = {0.0, 12.0, 25.0}, tmaxs[4] = {15.0, 30.0, 100.0, 50.0};
    int32_t o[3] = {0, 0, -10 * U};
    float of[3] = {0.0f, 0.0f, -10.0f};
    unsigned long cases = 0, bad = 0, nmeet, fl, i;
    (void)state;
    s.n = 0;
    for (i = 0; i < 8; i++) {
        int32_t z = (int32_t)(zs[i / 2] * U);
        int32_t v0[3] = {-32 * U, -32 * U, z}, v1[3] = {32 * U, -32 * U, z}, v2[3] = {0, 32 * U, z};
        if (face[i / 2][i % 2]) /* N = e1 x e2 towards -z: faces the origin */
            add_tri(&s, v0, v2, v1);
        else
            add_tri(&s, v0, v1, v2);
    }
    build(&s, 8, 8, &b);
    for (nmeet = 1; nmeet <= 16; nmeet = nmeet == 1 ? 3 : nmeet + 13)
        for (fl = 0; fl < 4; fl++) {
            uint32_t flags = ((fl & 1u) ? LT_FRUSTA_TRIPAR : 0u) |
                             ((fl & 2u) ? LT_FRUSTA_BACKFACE : 0u);
            lt_ray16_q16_t r;
            lt_ray16_f32_t rf;
            lt_mask16_t occ = 0, occf = 0;
            uint64_t e0;
            int j;
            memset(&r, 0, sizeof r);
            memset(&rf, 0, sizeof rf);
            for (j = 0; j < LT_LANES; j++) {
                /* lanes below nmeet towards the triangles (x < 11 at t 70), the others back, away
                   from the leaf's box */
                double dx = (unsigned)j < nmeet ? 0.01 * j : 0.9, dy = (unsigned)j < nmeet ? 0.0 : 0.3;
                double dz = ((unsigned)j < nmeet ? 1.0 : -1.0) * sqrt(1.0 - dx * dx - dy * dy);
                tripar_lane(&r, &rf, j, o, of, dx, dy, dz, tmins[j % 3], tmaxs[j % 4]);
            }
            lt_ray16_q16_setup(&r);
            lt_ray16_f32_setup(&rf);
            e0 = tripar_events();
            assert_int_equal(lt_frusta_packet_occluded16_q16(&b.q, s.tq, flags, o, &r, 0xFFFFu, &occ),
                             LT_OK);
            assert_int_equal(
                lt_frusta_packet_occluded16_f32(&b.f, s.tf, flags, of, &rf, 0xFFFFu, &occf), LT_OK);
            tripar_ran("tripar any", e0, flags, nmeet, &bad);
            for (j = 0; j < LT_LANES; j++) {
                double t0 = tmins[j % 3], t1 = tmaxs[j % 4];
                int want = 0, got = (int)((unsigned)occ >> j & 1u), gotf = (int)((unsigned)occf >> j & 1u);
                unsigned p;
                for (p = 0; p < 4 && (unsigned)j < nmeet; p++) {
                    double t = 10.0 + zs[p];
                    int seen = (flags & LT_FRUSTA_BACKFACE) == 0 || face[p][0] || face[p][1];
                    want |= seen && t > t0 && t < t1;
                }
                cases++;
                if ((got != want || gotf != want) && bad++ < 6)
                    printf("  FAIL tripar any: %lu rays, flags %u, lane %d (t %g..%g): occluded "
                           "%d / %d, expected %d\n", nmeet, (unsigned)flags, j, t0, t1, got, gotf,
                           want);
            }
        }
    unbuild(&b);
    ltt_report("triangle-parallel leaves (LT_FRUSTA_TRIPAR) in the any-hit packet walk: a leaf of 8 "
               "triangles on planes at t 10, 20, 40, 70 (some facing away), 1, 3 or 16 rays with "
               "tmin 0/12/25 and tmax 15/30/50/100, with and without TRIPAR and back-face culling, "
               "q16 and f32: %lu lane cases, %lu wrong (occluded exactly when a visible plane lies "
               "inside (tmin, tmax); in sim builds the triangle-parallel leaf ran exactly when fewer "
               "rays than triangles reached it) (bound 0)\n", cases, bad);
    assert_int_equal(bad, 0);
}

static void test_primary_edges(void **state)
{
    static tscene_t s;
    ptally_t t;
    unsigned long ties = 0;
    lt_frusta_view_q16_t vq;
    lt_frusta_view_f32_t vf;
    int32_t eye[3] = {3 * U, 150 * U, -2 * U};
    ltt_rng_t r;
    uint32_t i, w = 37, h = 23;
    tbvh_t shal, deep;
    (void)state;
    memset(&t, 0, sizeof t);
    ltt_rng_seed(&r, 7);
    /* (1) vertices on rays, edges along rays, edges shared by two triangles through ray points
     * (ties at equal t), duplicated triangles (a tie on every pixel they cover), tiny triangles
     * around a ray point, axis-aligned triangles whose box faces hold ray points */
    pgrid_view(eye, &vq, &vf, w, h, 0);
    s.n = 0;
    for (i = 0; i < 40; i++) {
        uint32_t x = ltt_rng_below(&r, w), y = ltt_rng_below(&r, h);
        unsigned k = 7u + ltt_rng_below(&r, 2), a;
        int32_t p[3], b[3], c[3], q[3];
        pon_ray(&vq, x, y, k, p);
        for (a = 0; a < 3; a++)
            b[a] = c[a] = q[a] = p[a];
        switch (i % 6) {
        case 0: /* vertex on the ray */
            b[0] += 5 * U;
            c[2] += 4 * U;
            c[1] += 2 * U;
            add_tri(&s, p, b, c);
            break;
        case 1: /* edge along the ray */
            pon_ray(&vq, x, y, k + 1u, b);
            c[0] += 3 * U;
            add_tri(&s, p, b, c);
            break;
        case 2: /* two triangles sharing an edge through two pixels' ray points */
            pon_ray(&vq, (x + 3u) % w, (y + 2u) % h, k, b);
            c[0] += 6 * U, c[2] -= 6 * U;
            q[0] -= 6 * U, q[2] += 6 * U;
            add_tri(&s, p, b, c);
            add_tri(&s, b, p, q);
            break;
        case 3: /* a duplicate: an exact tie wherever it is hit */
            b[0] += 7 * U;
            c[2] += 7 * U;
            add_tri(&s, p, b, c);
            add_tri(&s, p, b, c);
            break;
        case 4: /* tiny triangle around the ray point */
            p[0] -= 1;
            b[0] += 1;
            c[2] += 1;
            add_tri(&s, p, b, c);
            break;
        default: /* axis-aligned (plane y = const) through the ray point */
            p[0] -= 2 * U;
            b[0] += 3 * U;
            c[2] += 4 * U;
            add_tri(&s, p, b, c);
            break;
        }
    }
    /* (2) grazing: a triangle in a plane through the eye (tnum == 0: never hit), one nearly so */
    {
        int32_t a0[3], a1[3], a2[3];
        pon_ray(&vq, 4, 4, 6, a0);
        pon_ray(&vq, 30, 4, 6, a1);
        pon_ray(&vq, 4, 4, 8, a2);
        add_tri(&s, a0, a1, a2);
        a2[1] += 1;
        add_tri(&s, a0, a1, a2);
    }
    build(&s, 8, 4, &shal);
    build(&s, 4, 1, &deep);
    pcompare_all(&s, &shal, &deep, &vq, &vf, &t, &ties, "edges");
    unbuild(&shal);
    build(&s, 1, 1, &shal);
    pcompare_all(&s, &shal, &deep, &vq, &vf, &t, &ties, "edges leaf 1");
    unbuild(&shal);
    unbuild(&deep);
    /* (3) axis-parallel rays (zero direction components on a column and a row) over a random
     * scene, partly off the image (37 x 23: partial tiles and blocks) */
    random_scene(&r, &s, 400, 20.0);
    pgrid_view(eye, &vq, &vf, w, h, 1);
    build(&s, 8, 4, &shal);
    build(&s, 4, 1, &deep);
    pcompare_all(&s, &shal, &deep, &vq, &vf, &t, &ties, "axis-parallel");
    unbuild(&shal);
    unbuild(&deep);
    /* (4) the empty scene */
    s.n = 0;
    build(&s, 8, 4, &shal);
    build(&s, 4, 1, &deep);
    pcompare_all(&s, &shal, &deep, &vq, &vf, &t, &ties, "empty");
    unbuild(&shal);
    unbuild(&deep);
    ptally_print("primary edge cases (vertices and edges on rays, shared edges and duplicates "
                 "(ties), tiny and axis-aligned triangles, a plane through the eye, axis-parallel "
                 "rays, 37 x 23 with partial tiles, the empty scene)", &t, ties);
    assert_true(ties > 20);
    assert_true(t.partial_tiles > 20);
    ptally_assert(&t);
}

/* Argument and range checks of the primary entry points. */
static void test_primary_args(void **state)
{
    lt_frusta_view_q16_t v;
    lt_frusta_vtable_q16_t vt;
    lt_frusta_view_f32_t vf;
    lt_frusta_vtable_f32_t vtf;
    static lt_frusta_prim16_q16_t P;
    lt_ray16_q16_t pr;
    lt_ray1_q16_t r1;
    lt_mask16_t k;
    int32_t eye[3] = {0, 0, 0};
    unsigned n = 0;
    (void)state;
    pgrid_view(eye, &v, &vf, 20, 20, 0);
    assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_OK);
    assert_int_equal(lt_frusta_vtable_f32(&vf, &vtf), LT_OK);
    assert_int_equal(lt_frusta_vtable_q16(NULL, &vt), LT_E_ARG), n++;
    v.flags = 32u; /* P256: shadow frusta only */
    assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_ARG), n++;
    v.flags = 0u;
    v.width = 0;
    assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_ARG), n++;
    v.width = LT_FRUSTA_PMAX_DIM + 1u;
    assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_ARG), n++;
    v.width = 20;
    v.o[1] = (int32_t)(((int64_t)1 << (LT_CFG_GEOM_MAX_LOG2 + 16)) + 1);
    assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_RANGE), n++;
    v.o[1] = 0;
    /* pixel (19, 19) would need |d| >= 1 */
    v.dx[0] = 1 << 27;
    assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_RANGE), n++;
    vf.dx[0] = 1.0f / 8.0f;
    assert_int_equal(lt_frusta_vtable_f32(&vf, &vtf), LT_E_RANGE), n++;
    vf.dx[0] = 0.0f / 0.0f;
    assert_int_equal(lt_frusta_vtable_f32(&vf, &vtf), LT_E_ARG), n++;
    assert_int_equal(lt_frusta_psetup16_q16(&vt, 2, 0, &P), LT_E_ARG), n++;
    assert_int_equal(lt_frusta_psetup16_q16(NULL, 0, 0, &P), LT_E_ARG), n++;
    assert_int_equal(lt_frusta_prays16_q16(&vt, 0, 5, &pr, &k), LT_E_ARG), n++;
    assert_int_equal(lt_frusta_pray1_q16(&vt, 20, 0, &r1), LT_E_ARG), n++;
    assert_int_equal(lt_frusta_trace16_q16(NULL, NULL, &vt, &P), LT_E_ARG), n++;
    /* a block entirely off the image: nothing active, the trace returns at once */
    assert_int_equal(lt_frusta_psetup16_q16(&vt, 32, 0, &P), LT_OK);
    assert_int_equal(P.active, 0);
    ltt_report("primary frusta arguments: %u rejected as documented (NULL, flags, size, eye and "
               "direction range, unaligned tiles and blocks, pixels off the image)\n", n);
}

/* The bunny on a ground plane seen by the default benchmark camera: every pixel's closest hit
 * by P-Frusta and P-Packet against the per-ray reference (shared data). */
static void test_primary_bunny(void **state)
{
    const char *root = getenv("LT_SHARED");
    char path[1024];
    lt_diag_t diag;
    lt_mesh_t m;
    lt_scene_t sc;
    static tscene_t s;
    ptally_t t;
    unsigned long ties = 0;
    tbvh_t shal, deep;
    lt_camera_t cam;
    lt_frusta_view_q16_t vq;
    lt_frusta_view_f32_t vf;
    uint32_t i;
    unsigned a;
    (void)state;
    snprintf(path, sizeof path, "%s/scenes/bunny.obj", root != NULL ? root : "../shared");
    if (lt_mesh_load(path, &m, &diag) != 0) {
        assert_int_equal(shared_missing(path), 0);
        return;
    }
    assert_int_equal(lt_ss_add_ground(&m, 0.6, &diag), 0);
    assert_int_equal(lt_scene_prepare(&m, &sc, &diag), 0);
    assert_true(sc.ntris <= MAXT);
    memset(&t, 0, sizeof t);
    s.n = 0;
    for (i = 0; i < sc.ntris; i++) {
        int32_t p[3][3];
        unsigned v;
        for (v = 0; v < 3; v++)
            for (a = 0; a < 3; a++)
                p[v][a] = sc.tq[i].v0[a] + (v == 1 ? sc.tq[i].e1[a] : v == 2 ? sc.tq[i].e2[a] : 0);
        add_tri(&s, p[0], p[1], p[2]);
    }
    build(&s, 8, 4, &shal);
    build(&s, 4, 1, &deep);
    lt_camera_default(&sc, PMAXW, PMAXH, &cam);
    cam.tan_half_fov *= 0.5; /* zoom in: the bunny and its shadow fill most of the view */
    assert_int_equal(lt_ss_pview(&cam, 0, &vq, &vf, &diag), 0);
    pcompare_all(&s, &shal, &deep, &vq, &vf, &t, &ties, "bunny");
    unbuild(&shal);
    unbuild(&deep);
    lt_scene_free(&sc);
    lt_mesh_free(&m);
    ptally_print("primary bunny + ground (3678 triangles, default camera zoomed 2x, 64 x 48, "
                 "11 flag sets)",
                 &t, ties);
    assert_true(t.hits > 5000);
    ptally_assert(&t);
}

static int setup_sets(void **state)
{
    (void)state;
#if LT_COST_MODE == LT_COST_SIM
    {
        lt_diag_t diag;
        if (lt_sim_init(lt_sim_machine_find("lrb16"), NULL, NULL, &diag) != 0)
            return -1;
    }
#endif
    return lt_qmc_interleave4x4(LT_QMC_LP, 0, &g_sets) == LT_OK ? 0 : -1;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_generator_and_args),
        cmocka_unit_test(test_random_scenes),
        cmocka_unit_test(test_edge_cases),
        cmocka_unit_test(test_direct),
        cmocka_unit_test(test_filter),
        cmocka_unit_test(test_tile_hash),
        cmocka_unit_test(test_bunny),
        cmocka_unit_test(test_primary_args),
        cmocka_unit_test(test_primary_random),
        cmocka_unit_test(test_primary_edges),
        cmocka_unit_test(test_tripar_ties),
        cmocka_unit_test(test_tripar_any),
        cmocka_unit_test(test_primary_bunny),
    };
    return cmocka_run_group_tests(tests, setup_sets, NULL);
}
