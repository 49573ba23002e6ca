/* test_adversarial_fq.c - cmocka tests feeding adversarial inputs to the multi-frusta kernels
 * (lt_frusta.h: soft-shadow frusta and primary frusta) and to the screen-space quadtree
 * (lt_qt.h), in both numeric paths (issue #12 "Adversarial rays in the unit tests of every kernel";
 * docs/reliability.md, "Adversarial rays"; the other kernels are tests/unit/test_adversarial.c's).
 *
 * Shadow frusta: a two-sided blocker quad, the cube [-1, 1]^3, a floor triangle on y = -4096 and a
 * wall triangle on x = +4096 (vertices at the geometry bound 2^LT_CFG_GEOM_MAX_LOG2), a triangle in
 * the area light's plane and one across it; 8 lights
 * (area, point, line, tilted, 8192-unit, one with a corner on the bound, end_shift 1 and 30), all
 * 32 flag combinations (BACKFACE, CORNER, CR, LEAFRAY, SPLIT; for shadow frusta FS with CR on
 * every other light and P256 on 4 lights with WT), both intersectors (WT, MT), full
 * and partial lane masks. Origins in classes (table sh_cls): anywhere, on a triangle vertex, on an
 * edge, on a cube face, on the light plane, on a light corner, at the geometry bound, just past it
 * (s15.16), and in float32 NaN, +-inf, huge (1e30, FLT_MAX), denormal and -0 components.
 * Checked: the calls return the documented statuses (table, setup: LT_OK / LT_E_RANGE with exactly
 * the out-of-range lanes dropped and zero-length lanes dropped, occluded16: LT_OK), occl bits only
 * on lanes that were set up, and per lane set up the frusta's occl equals the packet baseline
 * (lt_frusta_rays16 + lt_frusta_packet_occluded16, the same flags and tree) bit for bit.
 *
 * Primary frusta: views with zero steps, zero directions, 1-raw steps, axis-parallel pixels,
 * directions at the s1.30 limit, eyes at +-2^GEOM, on a vertex, an edge, a face and the floor's
 * plane; in float32 also -0 and denormal steps and a 1e30 eye; rejected views (NaN/inf, huge
 * components, the eye past the bound, bad sizes and flags) must return the documented status.
 * Accepted views: every block of the image and one past it, P-Frusta (psetup16 + trace16) equals
 * P-Packet (prays16 + packet_trace16) in t and id per pixel, ids of the scene, misses untouched.
 *
 * Quadtree: inverse-depth images with NaN, +-inf, 0, -0, negative, denormal and huge values (and
 * the s1.30 raws INT32_MAX, INT32_MIN, -1), 1 and 2 layers, odd sizes and 1x1, the three node
 * formats; rays (table qt_cls) with NaN/inf components, NaN tmin/tmax, tmin > tmax, t outside
 * [0, 1], zero / -0 / denormal / 1-raw directions, axis-parallel, starting on pixel corners, on
 * depth samples (on the surface), on the image border, end points exactly at and just past
 * 2^LT_QT_RAY_MAX_LOG2 px, w < 0, w at the format's limits; full and partial masks, the default
 * step bound and a bound of 2. Checked: LT_OK, a status of LT_QT_*, lanes outside the mask not
 * written, BADRAY exactly for the documented invalid classes, a hit's t within [tmin, tmax] (and
 * finite) and its layer valid.
 * In-contract classes are asserted; violations in out-of-contract classes print KNOWN lines.
 * The asan variant adds ASan+UBSan. Builds: host, sim, asan.
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

#include "lt/lt_frusta.h"
#include "lt/lt_qt.h"
#include "lt_test_util.h"

#define U 65536
#define GEOM_RAW ((int32_t)1 << (LT_CFG_GEOM_MAX_LOG2 + 16))
#define GEOM_U ((double)(1 << LT_CFG_GEOM_MAX_LOG2))

static lt_qmc_sets_t g_sets;

/* ---- scene (world units, exact in s15.16 and float32) --------------------------------------- */

#define NT 20
static const double sc_v[NT][3][3] = {
    /* blocker quad at y = 3, both sides */
    {{-2, 3, -2}, {2, 3, -2}, {2, 3, 2}},
    {{-2, 3, -2}, {2, 3, 2}, {-2, 3, 2}},
    {{-2, 3, -2}, {2, 3, 2}, {2, 3, -2}},
    {{-2, 3, -2}, {-2, 3, 2}, {2, 3, 2}},
    /* cube [-1, 1]^3 */
    {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}},
    {{-1, -1, -1}, {1, 1, -1}, {-1, 1, -1}},
    {{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}},
    {{-1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},
    {{-1, -1, -1}, {1, -1, -1}, {1, -1, 1}},
    {{-1, -1, -1}, {1, -1, 1}, {-1, -1, 1}},
    {{-1, 1, -1}, {1, 1, -1}, {1, 1, 1}},
    {{-1, 1, -1}, {1, 1, 1}, {-1, 1, 1}},
    {{-1, -1, -1}, {-1, 1, -1}, {-1, 1, 1}},
    {{-1, -1, -1}, {-1, 1, 1}, {-1, -1, 1}},
    {{1, -1, -1}, {1, 1, -1}, {1, 1, 1}},
    {{1, -1, -1}, {1, 1, 1}, {1, -1, 1}},
    /* floor on y = -4096 and wall on x = 4096, vertices on the geometry bound */
    {{-4096, -4096, -4096}, {4096, -4096, -4096}, {-4096, -4096, 4096}},
    {{4096, -4096, -4096}, {4096, 4096, -4096}, {4096, -4096, 4096}},
    /* in the area light's plane y = 8 beside it, and across that plane at x = 3 */
    {{2, 8, -2}, {4, 8, -2}, {2, 8, 2}},
    {{3, 6, 0}, {3, 10, 0}, {3, 8, 2}},
};

typedef struct scene {
    lt_tri_q16_t tq[NT];
    lt_tri_f32_t tf[NT];
    lt_bvh_t bq, bf;
    void *aq, *af;
} scene_t;

static void scene_build(scene_t *s, uint32_t max_leaf)
{
    lt_bvh_desc_t d;
    size_t bytes;
    unsigned i, a;
    for (i = 0; i < NT; i++)
        for (a = 0; a < 3; a++) {
            s->tq[i].v0[a] = (int32_t)lrint(sc_v[i][0][a] * U);
            s->tq[i].e1[a] = (int32_t)lrint((sc_v[i][1][a] - sc_v[i][0][a]) * U);
            s->tq[i].e2[a] = (int32_t)lrint((sc_v[i][2][a] - sc_v[i][0][a]) * U);
            s->tf[i].v0[a] = (float)sc_v[i][0][a];
            s->tf[i].e1[a] = (float)(sc_v[i][1][a] - sc_v[i][0][a]);
            s->tf[i].e2[a] = (float)(sc_v[i][2][a] - sc_v[i][0][a]);
        }
    memset(&d, 0, sizeof d);
    d.max_leaf = max_leaf;
    d.min_leaf = 1;
    assert_int_equal(lt_bvh_size(NT, &d, &bytes), LT_OK);
    assert_int_equal(posix_memalign(&s->aq, 64, bytes + 64), 0);
    assert_int_equal(posix_memalign(&s->af, 64, bytes + 64), 0);
    assert_int_equal(lt_bvh_build_q16(&s->bq, &d, s->tq, NT, s->aq, bytes), LT_OK);
    assert_int_equal(lt_bvh_build_f32(&s->bf, &d, s->tf, NT, s->af, bytes), LT_OK);
}

static void scene_free(scene_t *s)
{
    free(s->aq);
    free(s->af);
}

/* ---- class tallies ---------------------------------------------------------------------------- */

#define MAXC 20
typedef struct ctab {
    const char *name;
    int in_contract; /* mismatches asserted to be 0 */
} ctab_t;

typedef struct tally {
    unsigned long lanes[MAXC], setup[MAXC], dropped[MAXC], pos[MAXC], bad[MAXC];
    unsigned long status_bad, mask_bad, calls;
} tally_t;

/* One line per class: "name lanes/set-up/dropped/positive, mismatches"; FAIL / KNOWN lines. */
static int tally_report(const char *what, const char *path, const tally_t *t, const ctab_t *c,
                        unsigned nc, const char *pos_name, const char *bad_name)
{
    unsigned i;
    unsigned long tl = 0, ts = 0, tb = 0;
    int fail = 0;
    for (i = 0; i < nc; i++) {
        tl += t->lanes[i];
        ts += t->setup[i];
        tb += t->bad[i];
    }
    ltt_report("%s %s: %lu calls, %lu lanes (%lu set up), %s: %lu (bound 0), wrong statuses %lu, "
               "results on lanes not set up %lu (bound 0); per class lanes/set up/dropped/%s/"
               "mismatches:",
               what, path, t->calls, tl, ts, bad_name, tb, t->status_bad, t->mask_bad, pos_name);
    for (i = 0; i < nc; i++)
        if (t->lanes[i] != 0) /* classes of the other path have none */
            ltt_report(" %s %lu/%lu/%lu/%lu/%lu;", c[i].name, t->lanes[i], t->setup[i],
                       t->dropped[i], t->pos[i], t->bad[i]);
    ltt_report("\n");
    for (i = 0; i < nc; i++) {
        if (t->bad[i] == 0)
            continue;
        if (c[i].in_contract) {
            ltt_report("FAIL %s %s: %lu %s lanes with %s\n", what, path, t->bad[i], c[i].name,
                       bad_name);
            fail = 1;
        } else {
            ltt_report("KNOWN %s %s: %lu %s lanes (out of contract) with %s\n", what, path,
                       t->bad[i], c[i].name, bad_name);
        }
    }
    if (t->status_bad || t->mask_bad)
        fail = 1;
    return fail;
}

/* ==== 1. shadow frusta ========================================================================= */

enum {
    S_ANY, S_VERTEX, S_EDGE, S_FACE, S_LPLANE, S_LCORNER, S_BOUND, S_PAST, S_NAN, S_INF, S_HUGE,
    S_DENORM, S_NCLS
};
static const ctab_t sh_cls[S_NCLS] = {
    {"anywhere", 1},          {"on vertex", 1},        {"on edge", 1},
    {"on cube face", 1},      {"on light plane", 1},   {"on light corner", 1},
    {"at +-2^GEOM", 1},       {"past 2^GEOM (q16)", 1}, {"NaN (f32)", 1},
    {"+-inf (f32)", 1},       {"huge 1e30/FLT_MAX (f32)", 0}, {"denormal/-0 (f32)", 1},
};

#define NLIGHT 8
static const char *const light_name[NLIGHT] = {
    "area 2x2", "point", "line", "tilted", "8192-unit", "corner on the bound", "end_shift 1",
    "end_shift 30"};

/* Light l in world units (edges multiples of 2^-7 units); end shift. */
static void light_def(unsigned l, double c[3], double eu[3], double ev[3], uint32_t *es)
{
    unsigned a;
    for (a = 0; a < 3; a++)
        c[a] = eu[a] = ev[a] = 0.0;
    c[0] = -1;
    c[1] = 8;
    c[2] = -1;
    *es = 0;
    switch (l) {
    case 1: /* point */
        break;
    case 2: /* line */
        eu[0] = 2;
        break;
    case 3: /* tilted */
        eu[0] = 2;
        eu[1] = 1;
        ev[1] = 0.5;
        ev[2] = 2;
        break;
    case 4: /* 8192 units wide, corners on the bound */
        c[0] = -4096;
        c[1] = 4000;
        c[2] = -4096;
        eu[0] = 8192;
        ev[2] = 8192;
        break;
    case 5: /* corner c + eu + ev = (4096, 4096, 4096) */
        c[0] = 4094;
        c[1] = 4096;
        c[2] = 4094;
        eu[0] = 2;
        ev[2] = 2;
        break;
    default:
        eu[0] = 2;
        ev[2] = 2;
        *es = l == 6 ? 1u : (l == 7 ? 30u : 0u);
        break;
    }
}

typedef struct sorg {
    int32_t q[3];
    float f[3];
    int cls;
} sorg_t;

static int32_t q16d(double x) { return (int32_t)lrint(x * U); }

static double rgrid(ltt_rng_t *g, double lo, double hi)
{
    return floor(ltt_rng_uniform(g, lo, hi) * 256.0) / 256.0;
}

/* An origin of class c for light l (float32 values from the same doubles unless overridden). */
static void sh_origin(ltt_rng_t *g, unsigned l, int c, int f32, sorg_t *o)
{
    double p[3], lc[3], eu[3], ev[3];
    uint32_t es;
    unsigned a, t = ltt_rng_below(g, NT), v = ltt_rng_below(g, 3), ax = ltt_rng_below(g, 3);
    double s = ltt_rng_below(g, 257) / 256.0;
    light_def(l, lc, eu, ev, &es);
    for (a = 0; a < 3; a++)
        p[a] = rgrid(g, -6, 6);
    switch (c) {
    case S_VERTEX:
        for (a = 0; a < 3; a++)
            p[a] = sc_v[t][v][a];
        break;
    case S_EDGE:
        for (a = 0; a < 3; a++)
            p[a] = sc_v[t][v][a] + s * (sc_v[t][(v + 1) % 3][a] - sc_v[t][v][a]);
        break;
    case S_FACE:
        for (a = 0; a < 3; a++)
            p[a] = rgrid(g, -1, 1);
        p[ax] = (ltt_rng_u32(g) & 1u) ? 1.0 : -1.0;
        break;
    case S_LPLANE: /* the light's plane: on the light, in it, or beside it */
        for (a = 0; a < 3; a++)
            p[a] = lc[a] + s * eu[a] + (ltt_rng_below(g, 257) / 256.0) * ev[a];
        if (ltt_rng_below(g, 3) == 0) {
            p[0] += rgrid(g, -4, 4);
            if (lc[1] + 4 < GEOM_U)
                p[2] += rgrid(g, -4, 4);
        }
        break;
    case S_LCORNER: {
        unsigned k = ltt_rng_below(g, 4);
        for (a = 0; a < 3; a++)
            p[a] = lc[a] + ((k & 1u) ? eu[a] : 0.0) + ((k & 2u) ? ev[a] : 0.0);
        break;
    }
    case S_BOUND:
    case S_PAST:
        for (a = 0; a < 3; a++)
            if (a == ax || (ltt_rng_u32(g) & 1u))
                p[a] = (ltt_rng_u32(g) & 1u) ? GEOM_U : -GEOM_U;
        break;
    default:
        break;
    }
    o->cls = c;
    for (a = 0; a < 3; a++) {
        p[a] = p[a] > GEOM_U ? GEOM_U : (p[a] < -GEOM_U ? -GEOM_U : p[a]);
        o->q[a] = q16d(p[a]);
        o->f[a] = (float)p[a];
    }
    if (c == S_PAST && !f32) {
        static const int32_t past[] = {GEOM_RAW + 1, -GEOM_RAW - 1, INT32_MAX, INT32_MIN};
        o->q[ax] = past[ltt_rng_below(g, 4)];
    }
    if (f32) {
        switch (c) {
        case S_NAN:
            o->f[ax] = (ltt_rng_u32(g) & 1u) ? NAN : -NAN;
            break;
        case S_INF:
            o->f[ax] = (ltt_rng_u32(g) & 1u) ? INFINITY : -INFINITY;
            break;
        case S_HUGE: {
            static const float huge[] = {1e30f, -1e30f, FLT_MAX, -FLT_MAX, 1e20f};
            o->f[ax] = huge[ltt_rng_below(g, 5)];
            break;
        }
        case S_DENORM: {
            static const float den[] = {FLT_MIN / 2, -FLT_MIN / 2, 0x1p-149f, -0x1p-149f, -0.0f};
            for (a = 0; a < 3; a++)
                if (a == ax || (ltt_rng_u32(g) & 1u))
                    o->f[a] = den[ltt_rng_below(g, 5)];
            break;
        }
        default:
            break;
        }
    }
}

/* Origins per class, for a path: the classes the path has. */
static int sh_has(int c, int f32)
{
    if (f32)
        return c != S_PAST;
    return c < S_NAN;
}

static void sh_light_q16(unsigned l, uint32_t flags, lt_frusta_light_q16_t *lq)
{
    double c[3], eu[3], ev[3];
    unsigned a;
    memset(lq, 0, sizeof *lq);
    light_def(l, c, eu, ev, &lq->end_shift);
    for (a = 0; a < 3; a++) {
        lq->c[a] = q16d(c[a]);
        lq->eu[a] = q16d(eu[a]);
        lq->ev[a] = q16d(ev[a]);
    }
    lq->flags = flags;
}

static void sh_light_f32(unsigned l, uint32_t flags, lt_frusta_light_f32_t *lf)
{
    double c[3], eu[3], ev[3];
    unsigned a;
    memset(lf, 0, sizeof *lf);
    light_def(l, c, eu, ev, &lf->end_shift);
    for (a = 0; a < 3; a++) {
        lf->c[a] = (float)c[a];
        lf->eu[a] = (float)eu[a];
        lf->ev[a] = (float)ev[a];
    }
    lf->flags = flags;
}

#define SH_BATCHES 4

static void run_shadow(int f32, scene_t *sc, tally_t *T)
{
    ltt_rng_t g;
    unsigned l, fl, is, b, f;
    int cls[S_NCLS], ncls = 0, c;
    ltt_rng_seed(&g, f32 ? 0xF5A0F32u : 0xF5A0016u);
    for (c = 0; c < S_NCLS; c++)
        if (sh_has(c, f32))
            cls[ncls++] = c;
    for (is = 0; is < 2; is++) {
        sc->bq.isect = sc->bf.isect = is ? LT_ISECT_MT : LT_ISECT_WT;
        for (l = 0; l < NLIGHT; l++)
            for (fl = 0; fl < 32; fl++) {
                lt_frusta_light_q16_t lq;
                lt_frusta_light_f32_t lf;
                static lt_frusta_table_q16_t tq;
                static lt_frusta_table_f32_t tf;
                /* FS on every other light of the flag sets with CR; P256 (the paper's 256-ray
                   packet comparison, not a default) on lights 2, 3, 6, 7 with the watertight
                   test only: with Moller-Trumbore a spurious off-triangle hit of a ray that misses
                   a box can make box-pruning walks differ at the geometry bound (docs/frusta.md,
                   "Table 2"); the flags never change the inputs drawn */
                uint32_t flg = fl | ((fl & LT_FRUSTA_CR) != 0 && (l & 1u) != 0 ? LT_FRUSTA_FS : 0u) |
                               ((l & 2u) != 0 && is == 0 ? LT_FRUSTA_P256 : 0u);
                if (f32) {
                    sh_light_f32(l, flg, &lf);
                    assert_int_equal(lt_frusta_table_f32(&lf, &g_sets, &tf), LT_OK);
                } else {
                    sh_light_q16(l, flg, &lq);
                    assert_int_equal(lt_frusta_table_q16(&lq, &g_sets, &tq), LT_OK);
                }
                for (b = 0; b < SH_BATCHES; b++) {
                    sorg_t o[LT_LANES];
                    lt_mask16_t k = (b & 1u) ? (lt_mask16_t)ltt_rng_u32(&g) : LT_MASK_ALL;
                    lt_mask16_t want = 0, expect_active = 0, active;
                    static lt_frusta16_q16_t Fq;
                    static lt_frusta16_f32_t Ff;
                    lt_status_t st, est;
                    uint16_t occl[LT_LANES];
                    for (f = 0; f < LT_LANES; f++) {
                        int oc = cls[(b * LT_LANES + f + l + fl) % (unsigned)ncls];
                        double lc[3], eu[3], ev[3];
                        uint32_t es;
                        int ok, zero;
                        sh_origin(&g, l, oc, f32, &o[f]);
                        light_def(l, lc, eu, ev, &es);
                        if (f32)
                            ok = oc != S_NAN && oc != S_INF;
                        else
                            ok = oc != S_PAST;
                        /* zero-length rays: the origin is the whole (point) light */
                        zero = l == 1 && o[f].f[0] == (float)lc[0] && o[f].f[1] == (float)lc[1] &&
                               o[f].f[2] == (float)lc[2] && ok && oc != S_HUGE && oc != S_DENORM;
                        if (LTT_ON(k, f))
                            T->lanes[oc]++;
                        if (ok && LTT_ON(k, f) && !zero)
                            expect_active = (lt_mask16_t)(expect_active | (1u << f));
                        if (!ok && LTT_ON(k, f))
                            want = (lt_mask16_t)(want | (1u << f));
                    }
                    est = want ? LT_E_RANGE : LT_OK;
                    if (f32) {
                        for (f = 0; f < LT_LANES; f++) {
                            Ff.ox.l[f] = o[f].f[0];
                            Ff.oy.l[f] = o[f].f[1];
                            Ff.oz.l[f] = o[f].f[2];
                        }
                        st = lt_frusta_setup16_f32(&tf, k, &Ff);
                        active = Ff.active;
                        assert_int_equal(lt_frusta_occluded16_f32(&sc->bf, sc->tf, &tf, &Ff),
                                         LT_OK);
                        memcpy(occl, Ff.occl, sizeof occl);
                    } else {
                        for (f = 0; f < LT_LANES; f++) {
                            Fq.ox.l[f] = o[f].q[0];
                            Fq.oy.l[f] = o[f].q[1];
                            Fq.oz.l[f] = o[f].q[2];
                        }
                        st = lt_frusta_setup16_q16(&tq, k, &Fq);
                        active = Fq.active;
                        assert_int_equal(lt_frusta_occluded16_q16(&sc->bq, sc->tq, &tq, &Fq),
                                         LT_OK);
                        memcpy(occl, Fq.occl, sizeof occl);
                    }
                    T->calls++;
                    /* the huge float origins are in range (finite) but may be dropped as
                     * zero-length (scale underflow): allowed, not expected */
                    for (f = 0; f < LT_LANES; f++)
                        if (LTT_ON(k, f) && o[f].cls == S_HUGE && !LTT_ON(active, f))
                            expect_active = (lt_mask16_t)(expect_active & ~(1u << f));
                    if (st != est || active != expect_active) {
                        if (T->status_bad++ < 4)
                            ltt_report("  FAIL shadow %s light %s flags %u: setup %d (expected "
                                       "%d), active %04x (expected %04x)\n",
                                       f32 ? "f32" : "q16", light_name[l], fl, (int)st, (int)est,
                                       active, expect_active);
                    }
                    for (f = 0; f < LT_LANES; f++) {
                        lt_mask16_t pk = 0, po = 0;
                        int c2 = o[f].cls;
                        if (!LTT_ON(k, f))
                            continue;
                        if (!LTT_ON(active, f)) {
                            T->mask_bad += occl[f] != 0;
                            if (LTT_ON(want, f)) {
                                lt_status_t s1, s2;
                                T->dropped[c2]++;
                                /* the generators refuse the same origin */
                                if (f32) {
                                    lt_ray16_f32_t pr;
                                    lt_ray1_f32_t r1;
                                    s1 = lt_frusta_rays16_f32(&tf, o[f].f, f, &pr, &pk);
                                    s2 = lt_frusta_ray1_f32(&tf, o[f].f, f, 0, &r1);
                                } else {
                                    lt_ray16_q16_t pr;
                                    lt_ray1_q16_t r1;
                                    s1 = lt_frusta_rays16_q16(&tq, o[f].q, f, &pr, &pk);
                                    s2 = lt_frusta_ray1_q16(&tq, o[f].q, f, 0, &r1);
                                }
                                T->status_bad += s1 != LT_E_RANGE || s2 != LT_E_RANGE;
                            } else {
                                /* zero-length rays: the generator says so too (k = 0) */
                                T->dropped[c2]++;
                                if (f32) {
                                    lt_ray16_f32_t pr;
                                    T->status_bad += lt_frusta_rays16_f32(&tf, o[f].f, f, &pr,
                                                                          &pk) != LT_OK || pk != 0;
                                } else {
                                    lt_ray16_q16_t pr;
                                    T->status_bad += lt_frusta_rays16_q16(&tq, o[f].q, f, &pr,
                                                                          &pk) != LT_OK || pk != 0;
                                }
                            }
                            continue;
                        }
                        T->setup[c2]++;
                        if (f32) {
                            lt_ray16_f32_t pr;
                            T->status_bad += lt_frusta_rays16_f32(&tf, o[f].f, f, &pr, &pk) != LT_OK;
                            T->status_bad += lt_frusta_packet_occluded16_f32(
                                                 &sc->bf, sc->tf, fl, o[f].f, &pr, pk, &po) != LT_OK;
                        } else {
                            lt_ray16_q16_t pr;
                            T->status_bad += lt_frusta_rays16_q16(&tq, o[f].q, f, &pr, &pk) != LT_OK;
                            T->status_bad += lt_frusta_packet_occluded16_q16(
                                                 &sc->bq, sc->tq, fl, o[f].q, &pr, pk, &po) != LT_OK;
                        }
                        T->pos[c2] += lt__popcount32(occl[f]);
                        if (occl[f] != po) {
                            if (T->bad[c2]++ < 3 && sh_cls[c2].in_contract)
                                ltt_report("  mismatch shadow %s %s light %s flags %u %s: origin "
                                           "(%.9g, %.9g, %.9g) frusta %04x packet %04x\n",
                                           f32 ? "f32" : "q16", is ? "MT" : "WT", light_name[l],
                                           fl, sh_cls[c2].name,
                                           f32 ? (double)o[f].f[0] : o[f].q[0] / 65536.0,
                                           f32 ? (double)o[f].f[1] : o[f].q[1] / 65536.0,
                                           f32 ? (double)o[f].f[2] : o[f].q[2] / 65536.0, occl[f],
                                           po);
                        }
                    }
                }
            }
    }
    sc->bq.isect = sc->bf.isect = LT_ISECT_WT;
}

/* Table and setup argument checks: what the tables reject (each asserted). */
static unsigned shadow_args(void)
{
    lt_frusta_light_q16_t lq;
    lt_frusta_light_f32_t lf;
    static lt_frusta_table_q16_t tq;
    static lt_frusta_table_f32_t tf;
    static const float bad[] = {NAN, -NAN, INFINITY, -INFINITY};
    unsigned n = 0, i, a, w;
    sh_light_q16(0, 0, &lq);
    lq.c[0] = GEOM_RAW - 2 * U; /* c + eu on the bound: accepted */
    assert_int_equal(lt_frusta_table_q16(&lq, &g_sets, &tq), LT_OK), n++;
    lq.c[0] = GEOM_RAW - 2 * U + 512; /* c + eu just past it */
    assert_int_equal(lt_frusta_table_q16(&lq, &g_sets, &tq), LT_E_RANGE), n++;
    lq.c[0] = INT32_MIN;
    assert_int_equal(lt_frusta_table_q16(&lq, &g_sets, &tq), LT_E_RANGE), n++;
    sh_light_q16(0, 0, &lq);
    lq.eu[0] = INT32_MIN; /* on the 512 grid, but the corner is out of range */
    assert_int_equal(lt_frusta_table_q16(&lq, &g_sets, &tq), LT_E_RANGE), n++;
    lq.eu[0] = 1; /* off the grid */
    assert_int_equal(lt_frusta_table_q16(&lq, &g_sets, &tq), LT_E_ARG), n++;
    sh_light_q16(0, 0, &lq);
    lq.flags = 256u; /* no such flag */
    assert_int_equal(lt_frusta_table_q16(&lq, &g_sets, &tq), LT_E_ARG), n++;
    lq.flags = 0xFFFFFFFFu;
    assert_int_equal(lt_frusta_table_q16(&lq, &g_sets, &tq), LT_E_ARG), n++;
    lq.flags = 0;
    lq.end_shift = 31;
    assert_int_equal(lt_frusta_table_q16(&lq, &g_sets, &tq), LT_E_ARG), n++;
    lq.end_shift = 0xFFFFFFFFu;
    assert_int_equal(lt_frusta_table_q16(&lq, &g_sets, &tq), LT_E_ARG), n++;
    for (w = 0; w < 3; w++)
        for (a = 0; a < 3; a++)
            for (i = 0; i < 4; i++) {
                sh_light_f32(0, 0, &lf);
                (w == 0 ? lf.c : (w == 1 ? lf.eu : lf.ev))[a] = bad[i];
                assert_int_equal(lt_frusta_table_f32(&lf, &g_sets, &tf), LT_E_ARG), n++;
            }
    sh_light_f32(0, 256u, &lf); /* no such flag */
    assert_int_equal(lt_frusta_table_f32(&lf, &g_sets, &tf), LT_E_ARG), n++;
    sh_light_f32(0, 0, &lf);
    lf.c[0] = FLT_MAX; /* finite: accepted (float lights have no geometry bound) */
    assert_int_equal(lt_frusta_table_f32(&lf, &g_sets, &tf), LT_OK), n++;
    assert_int_equal(lt_frusta_setup16_q16(NULL, LT_MASK_ALL, NULL), LT_E_ARG), n++;
    assert_int_equal(lt_frusta_setup16_f32(NULL, LT_MASK_ALL, NULL), LT_E_ARG), n++;
    return n;
}

static void test_shadow_frusta(void **state)
{
    scene_t *sc = calloc(1, sizeof *sc);
    tally_t *T = calloc(2, sizeof *T);
    unsigned na;
    int p, fail = 0;
    (void)state;
    assert_non_null(sc);
    assert_non_null(T);
    scene_build(sc, 2);
    na = shadow_args();
    ltt_report("shadow frusta tables: %u argument cases (q16: corner on / past 2^GEOM, INT32_MIN "
               "edges -> LT_OK / LT_E_RANGE; off-grid edges, unknown flags, end_shift > 30 -> "
               "LT_E_ARG; f32: NaN/+-inf in c, eu, ev -> LT_E_ARG, FLT_MAX corner -> LT_OK; NULL "
               "-> LT_E_ARG), all as documented\n",
               na);
    for (p = 0; p < 2; p++) {
        run_shadow(p, sc, &T[p]);
        fail |= tally_report("shadow frusta (8 lights x 32 flag sets (with CR: FS on odd lights; P256 "
                             "on 4 lights with WT) x WT/MT, full and partial "
                             "masks)",
                             p ? "f32" : "q16", &T[p], sh_cls, S_NCLS, "occluded samples",
                             "frusta occl != packet baseline");
    }
    scene_free(sc);
    free(sc);
    free(T);
    assert_int_equal(fail, 0);
}

/* ==== 2. primary frusta ======================================================================== */

#define PW 20
#define PH 13

enum {
    P_NORMAL, P_ZSTEP, P_ZDIR, P_TINY, P_AXIS, P_DLIM, P_EYE_BP, P_EYE_BN, P_EYE_VTX, P_EYE_EDGE,
    P_EYE_FACE, P_EYE_FLOOR, P_NEG0, P_DENORM, P_HUGE_EYE, P_NCLS
};
static const ctab_t pv_cls[P_NCLS] = {
    {"normal", 1},           {"zero steps", 1},        {"zero direction", 1},
    {"1-raw steps", 1},      {"axis-parallel", 1},     {"|d| at the s1.30 limit", 1},
    {"eye at +2^GEOM", 1},   {"eye at -2^GEOM", 1},    {"eye on vertex", 1},
    {"eye on edge", 1},      {"eye on face", 1},       {"eye on the floor plane", 1},
    {"-0 components (f32)", 1}, {"denormal steps (f32)", 0}, {"eye at 1e30 (f32)", 0},
};

/* float32: exact convex combinations need d0, dx, dy on the 2^-23 grid (lt_frusta.h); 1-raw
 * (2^-30) and denormal steps are off it, and a 1e30 eye is far outside any tested scale. */
static const ctab_t pv_cls_f32[P_NCLS] = {
    {"normal", 1},           {"zero steps", 1},        {"zero direction", 1},
    {"2^-30 steps", 0},      {"axis-parallel", 1},     {"|d| at 1 - 2^-23", 1},
    {"eye at +2^GEOM", 1},   {"eye at -2^GEOM", 1},    {"eye on vertex", 1},
    {"eye on edge", 1},      {"eye on face", 1},       {"eye on the floor plane", 1},
    {"-0 components", 1},    {"denormal steps", 0},    {"eye at 1e30", 0},
};

typedef struct pview {
    double o[3];
    int32_t d0[3], dx[3], dy[3]; /* s1.30 raw, multiples of 128 (exact in float32) unless noted */
} pview_t;

#define Q30R(x) ((int32_t)lrint((x)*1073741824.0 / 128.0) * 128)

static void pview_def(int c, pview_t *v)
{
    unsigned a;
    memset(v, 0, sizeof *v);
    v->o[0] = 0.5;
    v->o[1] = 1.5;
    v->o[2] = 7;
    v->d0[0] = Q30R(-0.5);
    v->d0[1] = Q30R(-0.4);
    v->d0[2] = Q30R(-0.9);
    v->dx[0] = Q30R(0.05);
    v->dy[1] = Q30R(0.06);
    switch (c) {
    case P_ZSTEP: /* every pixel the ray towards the cube */
        v->d0[0] = Q30R(-0.07);
        v->d0[1] = Q30R(-0.2);
        v->d0[2] = Q30R(-0.97);
        v->dx[0] = v->dy[1] = 0;
        break;
    case P_ZDIR:
        memset(v->d0, 0, sizeof v->d0);
        v->dx[0] = v->dy[1] = 0;
        break;
    case P_TINY:
        v->d0[0] = Q30R(-0.07);
        v->d0[1] = Q30R(-0.2);
        v->d0[2] = Q30R(-0.97);
        v->dx[0] = 1;
        v->dx[1] = -1;
        v->dy[1] = -1;
        v->dy[2] = 1;
        break;
    case P_AXIS: /* pixel (0, 0) along -z, row 0 and column 0 in axis planes */
        v->o[1] = 0.5;
        v->d0[0] = v->d0[1] = 0;
        v->d0[2] = Q30R(-0.75);
        v->dx[0] = Q30R(0.01);
        v->dy[1] = Q30R(0.01);
        break;
    case P_DLIM: {
        /* the corner pixels reach 2^30 - 128 raw on every axis */
        int32_t lim = (1 << 30) - 128;
        for (a = 0; a < 3; a++)
            v->d0[a] = -lim;
        v->dx[0] = (int32_t)(((int64_t)2 * lim / 19) / 128 * 128);
        v->dy[1] = (int32_t)(((int64_t)2 * lim / 15) / 128 * 128);
        v->dx[2] = v->dx[0] / 2 / 128 * 128;
        v->dy[2] = v->dy[1] / 2 / 128 * 128;
        break;
    }
    case P_EYE_BP:
    case P_EYE_BN: {
        double s = c == P_EYE_BP ? 1.0 : -1.0;
        for (a = 0; a < 3; a++) {
            v->o[a] = s * GEOM_U;
            v->d0[a] = Q30R(-s * 0.6);
        }
        v->d0[0] = Q30R(-s * 0.7);
        v->dx[0] = Q30R(s * 0.02);
        v->dy[1] = Q30R(s * 0.02);
        break;
    }
    case P_EYE_VTX:
        v->o[0] = v->o[1] = v->o[2] = 1;
        for (a = 0; a < 3; a++)
            v->d0[a] = Q30R(-0.6);
        v->dx[0] = Q30R(0.05);
        v->dy[1] = Q30R(0.05);
        break;
    case P_EYE_EDGE:
        v->o[0] = 1;
        v->o[1] = 0.25;
        v->o[2] = 1;
        for (a = 0; a < 3; a++)
            v->d0[a] = Q30R(-0.5);
        v->dx[0] = Q30R(0.05);
        v->dy[1] = Q30R(0.05);
        break;
    case P_EYE_FACE: /* on x = 1, the pixels' x direction changing sign */
        v->o[0] = 1;
        v->o[1] = 0.3;
        v->o[2] = 0.2;
        v->d0[0] = Q30R(-0.5);
        v->d0[1] = Q30R(-0.4);
        v->d0[2] = Q30R(-0.3);
        v->dx[0] = Q30R(0.05);
        v->dy[1] = Q30R(0.06);
        break;
    case P_EYE_FLOOR: /* row 0 in the floor's plane, the others up to the cube 4096 above */
        v->o[0] = 0.25;
        v->o[1] = -GEOM_U;
        v->o[2] = 0.5;
        v->d0[0] = Q30R(-0.0002);
        v->d0[1] = 0;
        v->d0[2] = Q30R(-0.0002);
        v->dx[0] = Q30R(0.00002);
        v->dy[1] = Q30R(0.06);
        break;
    default:
        break;
    }
}

static void pview_q16(const pview_t *p, uint32_t flags, lt_frusta_view_q16_t *v)
{
    unsigned a;
    memset(v, 0, sizeof *v);
    for (a = 0; a < 3; a++) {
        v->o[a] = q16d(p->o[a]);
        v->d0[a] = p->d0[a];
        v->dx[a] = p->dx[a];
        v->dy[a] = p->dy[a];
    }
    v->width = PW;
    v->height = PH;
    v->flags = flags;
}

static void pview_f32(int c, const pview_t *p, uint32_t flags, lt_frusta_view_f32_t *v)
{
    unsigned a;
    memset(v, 0, sizeof *v);
    for (a = 0; a < 3; a++) {
        v->o[a] = (float)p->o[a];
        v->d0[a] = (float)(p->d0[a] / 1073741824.0);
        v->dx[a] = (float)(p->dx[a] / 1073741824.0);
        v->dy[a] = (float)(p->dy[a] / 1073741824.0);
    }
    if (c == P_NEG0) {
        v->o[1] = 0.5f;
        v->d0[0] = v->d0[1] = -0.0f;
        v->d0[2] = -0.75f;
        v->dx[1] = v->dx[2] = v->dy[0] = v->dy[2] = -0.0f;
        v->dx[0] = -0.0f;
        v->dy[1] = 0.0078125f;
    } else if (c == P_DENORM) {
        v->d0[0] = -0.0703125f; /* towards the cube, as the zero-step view */
        v->d0[1] = -0.203125f;
        v->d0[2] = -0.96875f;
        v->dx[0] = FLT_MIN / 2;
        v->dx[1] = -0x1p-149f;
        v->dy[1] = 1.0e-44f;
        v->dy[2] = -FLT_MIN / 4;
    } else if (c == P_HUGE_EYE) {
        v->o[0] = 1e30f;
        v->o[1] = -3e29f;
        v->d0[0] = -0.9f;
    }
    v->width = PW;
    v->height = PH;
    v->flags = flags;
}

typedef struct ptally {
    tally_t t;
    unsigned long rejected, hits, rays;
} ptally_t;

/* One view, one flag set: every block, P-Frusta vs P-Packet per pixel. */
static void run_pview_q16(const scene_t *sc, const lt_frusta_view_q16_t *v, int c, ptally_t *P)
{
    static lt_frusta_vtable_q16_t vt;
    static lt_frusta_prim16_q16_t F;
    uint32_t bx, by, f, j;
    if (lt_frusta_vtable_q16(v, &vt) != LT_OK) {
        if (P->t.status_bad++ < 3)
            ltt_report("  FAIL vtable q16 %s flags %u: %d\n", pv_cls[c].name, v->flags,
                       (int)lt_frusta_vtable_q16(v, &vt));
        return;
    }
    for (by = 0; by < PH + 16u; by += 16)
        for (bx = 0; bx < PW + 16u; bx += 16) {
            P->t.calls++;
            P->t.status_bad += lt_frusta_psetup16_q16(&vt, bx, by, &F) != LT_OK;
            P->t.status_bad += lt_frusta_trace16_q16(&sc->bq, sc->tq, &vt, &F) != LT_OK;
            for (f = 0; f < 16; f++) {
                uint32_t tx = bx + 4u * (f & 3u), ty = by + 4u * (f >> 2);
                lt_ray16_q16_t pr;
                lt_hit16_t ph;
                lt_mask16_t k = 0;
                if (F.live[f] == 0) {
                    for (j = 0; j < 16; j++)
                        P->t.mask_bad += F.id[f].l[j] != -1 || F.t[f].l[j] != LT_Q16_MAX - 1;
                    continue;
                }
                P->t.status_bad += lt_frusta_prays16_q16(&vt, tx, ty, &pr, &k) != LT_OK;
                P->t.status_bad += k != F.live[f];
                P->t.status_bad += lt_frusta_packet_trace16_q16(&sc->bq, sc->tq, v->flags, vt.o,
                                                                &pr, k, &ph) != LT_OK;
                for (j = 0; j < 16; j++) {
                    int32_t id = F.id[f].l[j];
                    if (!LTT_ON(k, j)) {
                        P->t.mask_bad += id != -1;
                        continue;
                    }
                    P->t.lanes[c]++;
                    P->t.setup[c]++;
                    P->rays++;
                    P->t.pos[c] += id >= 0;
                    P->t.mask_bad += id < -1 || id >= NT || (id == -1) != (F.t[f].l[j] ==
                                                                            LT_Q16_MAX - 1) ||
                                     F.t[f].l[j] < 0;
                    if (id != ph.id.l[j] || F.t[f].l[j] != pr.tmax.l[j]) {
                        if (P->t.bad[c]++ < 3)
                            ltt_report("  mismatch P-Frusta q16 %s flags %u pixel (%u,%u): frusta "
                                       "id %d t %d, packet id %d t %d\n",
                                       pv_cls[c].name, v->flags, tx + (j & 3u), ty + (j >> 2), id,
                                       F.t[f].l[j], ph.id.l[j], pr.tmax.l[j]);
                    }
                }
            }
        }
}

static void run_pview_f32(const scene_t *sc, const lt_frusta_view_f32_t *v, int c, ptally_t *P)
{
    static lt_frusta_vtable_f32_t vt;
    static lt_frusta_prim16_f32_t F;
    uint32_t bx, by, f, j;
    if (lt_frusta_vtable_f32(v, &vt) != LT_OK) {
        if (P->t.status_bad++ < 3)
            ltt_report("  FAIL vtable f32 %s flags %u: %d\n", pv_cls_f32[c].name, v->flags,
                       (int)lt_frusta_vtable_f32(v, &vt));
        return;
    }
    for (by = 0; by < PH + 16u; by += 16)
        for (bx = 0; bx < PW + 16u; bx += 16) {
            P->t.calls++;
            P->t.status_bad += lt_frusta_psetup16_f32(&vt, bx, by, &F) != LT_OK;
            P->t.status_bad += lt_frusta_trace16_f32(&sc->bf, sc->tf, &vt, &F) != LT_OK;
            for (f = 0; f < 16; f++) {
                uint32_t tx = bx + 4u * (f & 3u), ty = by + 4u * (f >> 2);
                lt_ray16_f32_t pr;
                lt_hit16_t ph;
                lt_mask16_t k = 0;
                if (F.live[f] == 0) {
                    for (j = 0; j < 16; j++)
                        P->t.mask_bad += F.id[f].l[j] != -1 || F.t[f].l[j] != 3.0e38f;
                    continue;
                }
                P->t.status_bad += lt_frusta_prays16_f32(&vt, tx, ty, &pr, &k) != LT_OK;
                P->t.status_bad += k != F.live[f];
                P->t.status_bad += lt_frusta_packet_trace16_f32(&sc->bf, sc->tf, v->flags, vt.o,
                                                                &pr, k, &ph) != LT_OK;
                for (j = 0; j < 16; j++) {
                    int32_t id = F.id[f].l[j];
                    float t = F.t[f].l[j];
                    if (!LTT_ON(k, j)) {
                        P->t.mask_bad += id != -1;
                        continue;
                    }
                    P->t.lanes[c]++;
                    P->t.setup[c]++;
                    P->rays++;
                    P->t.pos[c] += id >= 0;
                    P->t.mask_bad += id < -1 || id >= NT || (id == -1) != (t == 3.0e38f) ||
                                     !(t >= 0.0f && t <= 3.0e38f);
                    if (id != ph.id.l[j] || memcmp(&t, &pr.tmax.l[j], sizeof t) != 0) {
                        if (P->t.bad[c]++ < 3 && pv_cls_f32[c].in_contract)
                            ltt_report("  mismatch P-Frusta f32 %s flags %u pixel (%u,%u): frusta "
                                       "id %d t %.9g, packet id %d t %.9g\n",
                                       pv_cls_f32[c].name, v->flags, tx + (j & 3u), ty + (j >> 2), id,
                                       (double)t, ph.id.l[j], (double)pr.tmax.l[j]);
                    }
                }
            }
        }
}

/* Views the tables must reject (q16 and f32), each asserted; returns the count. */
static unsigned pview_rejects(void)
{
    lt_frusta_view_q16_t v;
    lt_frusta_view_f32_t vf;
    lt_frusta_vtable_q16_t vt;
    lt_frusta_vtable_f32_t vtf;
    pview_t p;
    static const float bad[] = {NAN, -NAN, INFINITY, -INFINITY};
    static const int32_t dbig[] = {1 << 30, -(1 << 30), INT32_MAX, INT32_MIN};
    unsigned n = 0, a, w, i;
    pview_def(P_NORMAL, &p);
    pview_q16(&p, 0, &v);
    assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_OK);
    for (a = 0; a < 3; a++) {
        static const int32_t opast[] = {GEOM_RAW + 1, -GEOM_RAW - 1, INT32_MAX, INT32_MIN};
        for (i = 0; i < 4; i++) {
            pview_q16(&p, 0, &v);
            v.o[a] = opast[i];
            assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_RANGE), n++;
            pview_q16(&p, 0, &v);
            v.d0[a] = dbig[i];
            assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_RANGE), n++;
            pview_q16(&p, 0, &v);
            v.dx[a] = dbig[i];
            assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_RANGE), n++;
            pview_q16(&p, 0, &v);
            v.dy[a] = dbig[i];
            assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_RANGE), n++;
        }
        pview_q16(&p, 0, &v);
        v.o[a] = GEOM_RAW; /* on the bound: accepted */
        assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_OK), n++;
        v.o[a] = -GEOM_RAW;
        assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_OK), n++;
    }
    pview_q16(&p, 0, &v);
    v.dx[0] = Q30R(0.1); /* pixel 0 in range, the far corner (x = 19) past 1 */
    assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_RANGE), n++;
    v.dx[0] = 0;
    v.width = LT_FRUSTA_PMAX_DIM; /* zero steps: every pixel in range */
    assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_OK), n++;
    v.width = LT_FRUSTA_PMAX_DIM + 1;
    assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_ARG), n++;
    v.width = 0;
    assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_ARG), n++;
    v.width = PW;
    v.height = 0xFFFFFFFFu;
    assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_ARG), n++;
    v.height = PH;
    v.flags = 32u;
    assert_int_equal(lt_frusta_vtable_q16(&v, &vt), LT_E_ARG), n++;
    for (w = 0; w < 4; w++)
        for (a = 0; a < 3; a++)
            for (i = 0; i < 4; i++) {
                float *fld;
                pview_f32(P_NORMAL, &p, 0, &vf);
                fld = w == 0 ? vf.o : (w == 1 ? vf.d0 : (w == 2 ? vf.dx : vf.dy));
                fld[a] = bad[i];
                assert_int_equal(lt_frusta_vtable_f32(&vf, &vtf), LT_E_ARG), n++;
                if (w > 0) {
                    static const float fbig[] = {1.0f, -1.0f, FLT_MAX, -FLT_MAX};
                    fld[a] = fbig[i];
                    assert_int_equal(lt_frusta_vtable_f32(&vf, &vtf), LT_E_RANGE), n++;
                }
            }
    pview_f32(P_NORMAL, &p, 0, &vf);
    vf.flags = 32u;
    assert_int_equal(lt_frusta_vtable_f32(&vf, &vtf), LT_E_ARG), n++;
    vf.flags = 0;
    vf.o[0] = FLT_MAX; /* finite eye: accepted */
    assert_int_equal(lt_frusta_vtable_f32(&vf, &vtf), LT_OK), n++;
    assert_int_equal(lt_frusta_psetup16_q16(&vt, 1, 0, NULL), LT_E_ARG), n++;
    return n;
}

static void test_primary_frusta(void **state)
{
    scene_t *sc = calloc(1, sizeof *sc);
    ptally_t *P = calloc(2, sizeof *P);
    unsigned na, is, fl;
    int c, p, fail = 0;
    (void)state;
    assert_non_null(sc);
    assert_non_null(P);
    scene_build(sc, 2);
    na = pview_rejects();
    ltt_report("primary frusta view tables: %u cases (q16: eye past 2^GEOM or at INT32_MIN/MAX, a "
               "direction component at +-2^30 or INT32_MIN/MAX at a corner pixel -> LT_E_RANGE, eye "
               "on +-2^GEOM and 16384-pixel zero-step views -> LT_OK, width 0 / > 16384, unknown "
               "flags -> LT_E_ARG; f32: NaN/+-inf in o, d0, dx, dy -> LT_E_ARG, +-1 or "
               "+-FLT_MAX -> LT_E_RANGE, FLT_MAX eye -> LT_OK), all as documented\n",
               na);
    for (is = 0; is < 2; is++) {
        sc->bq.isect = sc->bf.isect = is ? LT_ISECT_MT : LT_ISECT_WT;
        for (c = 0; c < P_NCLS; c++) {
            pview_t pv;
            pview_def(c, &pv);
            for (fl = 0; fl < 32; fl++) {
                if (c < P_NEG0) {
                    lt_frusta_view_q16_t v;
                    pview_q16(&pv, fl, &v);
                    run_pview_q16(sc, &v, c, &P[0]);
                }
                {
                    lt_frusta_view_f32_t vf;
                    pview_f32(c, &pv, fl, &vf);
                    run_pview_f32(sc, &vf, c, &P[1]);
                }
            }
        }
    }
    for (p = 0; p < 2; p++) {
        if (P[p].t.pos[P_ZDIR] != 0) {
            ltt_report("FAIL primary frusta %s: %lu zero-direction pixels hit (defined: miss)\n",
                       p ? "f32" : "q16", P[p].t.pos[P_ZDIR]);
            fail = 1;
        }
        fail |= tally_report("primary frusta (20x13 views x 32 flag sets x WT/MT, every block "
                             "and one past the image)",
                             p ? "f32" : "q16", &P[p].t, p ? pv_cls_f32 : pv_cls,
                             p ? P_NCLS : P_NEG0,
                             "hits", "P-Frusta != P-Packet (t or id)");
    }
    scene_free(sc);
    free(sc);
    free(P);
    assert_int_equal(fail, 0);
}

/* ==== 3. quadtree ============================================================================== */

#define QW 37
#define QH 29

enum { IM_MIXED, IM_HOLES, IM_EXTREME, IM_ONE, IM_N };
static const char *const im_name[IM_N] = {"37x29x2 mixed", "16x16 all holes", "8x5 extreme",
                                          "1x1 mixed"};
static const uint32_t im_w[IM_N] = {QW, 16, 8, 1}, im_h[IM_N] = {QH, 16, 5, 1},
                      im_l[IM_N] = {2, 1, 1, 2};

/* w of image m, layer L, pixel (x, y), as float (f32 path) and s1.30 raw (q30 path). Special
 * values: f32 NaN, +-inf, 0, -0, negative, denormal, 1.999 (mixed); 2, 4, 1e30, FLT_MAX (extreme,
 * beyond the documented w < 2); q30 raws INT32_MIN, -1, 0, 1, INT32_MAX, 2^30. */
static void im_w_at(int m, uint32_t L, uint32_t x, uint32_t y, float *wf, int32_t *wq)
{
    double base = (L == 0 ? 0.5 : 0.2) + 0.002 * x + 0.001 * y;
    unsigned h = (x * 7u + y * 13u + L * 5u) % 11u;
    *wf = (float)base;
    *wq = (int32_t)lrint(base * 1073741824.0);
    if (m == IM_HOLES) {
        static const float hf[] = {NAN, INFINITY, -INFINITY, 0.0f, -0.0f, -0.5f};
        static const int32_t hq[] = {0, INT32_MIN, -1, 0, -(1 << 29), -2};
        *wf = hf[(x + y) % 6u];
        *wq = hq[(x + y) % 6u];
        return;
    }
    if (m == IM_EXTREME) {
        static const float ef[] = {2.0f, 4.0f, 1e30f, FLT_MAX, 0x1p-149f, 1.5f};
        static const int32_t eq[] = {INT32_MAX, INT32_MAX - 1, 1 << 30, 1, INT32_MAX, 0x60000000};
        *wf = ef[(x + 2 * y) % 6u];
        *wq = eq[(x + 2 * y) % 6u];
        return;
    }
    if (h == 0 || (m == IM_ONE && L == 1)) {
        static const float sf[] = {NAN, INFINITY, -INFINITY, 0.0f, -0.0f, -0.3f, 1e-40f, 1.999f};
        static const int32_t sq[] = {INT32_MIN, -1, 0, 1, INT32_MAX, 1 << 30, -(1 << 30), 7};
        unsigned k = (x + 3u * y + L) % 8u;
        *wf = sf[k];
        *wq = sq[k];
    }
    if (m == IM_MIXED && x >= 20 && x < 26 && y >= 4 && y < 12 && L == 0)
        *wf = 0.9f, *wq = (int32_t)(0.9 * 1073741824.0); /* a step */
}

enum {
    Q_NORMAL, Q_ZERO, Q_DENORM, Q_TINY, Q_AXIS, Q_CORNER, Q_SAMPLE, Q_BORDER, Q_LIMIT, Q_WEXT,
    Q_NAN, Q_INF, Q_NAN_T, Q_TMIN_GT, Q_T_OUT, Q_PAST, Q_WNEG, Q_NCLS
};
static const ctab_t qt_cls[Q_NCLS] = {
    {"normal", 1},
    {"zero/-0 direction", 1},
    {"denormal components (f32)", 1},
    {"1-raw components (q30)", 1},
    {"axis-parallel", 1},
    {"start on pixel corner", 1},
    {"start on depth sample", 1},
    {"start on image border", 1},
    {"end points at +-2^14 px", 1},
    {"w at the format's limit", 1},
    {"NaN component (f32): BADRAY", 1},
    {"+-inf component (f32): BADRAY", 1},
    {"NaN tmin/tmax (f32): BADRAY", 1},
    {"tmin > tmax: BADRAY", 1},
    {"t outside [0, 1]: BADRAY", 1},
    {"end point past 2^14 px: BADRAY", 1},
    {"w < 0: BADRAY", 1},
};
#define Q_FIRST_BAD Q_NAN

typedef struct qray {
    double x, y, w, dx, dy, dw, tmin, tmax; /* the generic ray */
    float f[8];                             /* float32 lanes: x y w dx dy dw tmin tmax */
    int32_t q[8];                           /* s15.16 x, y, dx, dy; s1.30 w, dw, tmin, tmax */
    int cls;
} qray_t;

static int32_t q30s(double x)
{
    double v = x * 1073741824.0;
    if (v >= 2147483647.0)
        return INT32_MAX;
    if (v <= -2147483648.0)
        return INT32_MIN;
    return (int32_t)lrint(v);
}

static void qray_gen(ltt_rng_t *g, int m, int c, qray_t *r)
{
    double W = im_w[m], H = im_h[m], lim = (double)(1u << LT_QT_RAY_MAX_LOG2);
    unsigned a = ltt_rng_below(g, 6), s = ltt_rng_below(g, 4);
    r->cls = c;
    r->x = floor(ltt_rng_uniform(g, -2, W + 2) * 256.0) / 256.0;
    r->y = floor(ltt_rng_uniform(g, -2, H + 2) * 256.0) / 256.0;
    r->w = floor(ltt_rng_uniform(g, 0.3, 1.2) * 65536.0) / 65536.0;
    r->dx = floor(ltt_rng_uniform(g, -W, W) * 256.0) / 256.0;
    r->dy = floor(ltt_rng_uniform(g, -H, H) * 256.0) / 256.0;
    r->dw = -r->w * (ltt_rng_below(g, 4) + 1) / 4.0;
    r->tmin = 0;
    r->tmax = 1;
    if (ltt_rng_below(g, 4) == 0) {
        r->tmin = ltt_rng_below(g, 64) / 256.0;
        r->tmax = 1.0 - ltt_rng_below(g, 64) / 256.0;
    }
    switch (c) {
    case Q_ZERO:
        r->dx = r->dy = 0;
        if (s & 1u)
            r->dw = 0;
        break;
    case Q_AXIS:
        if (s & 1u)
            r->dx = 0;
        else
            r->dy = 0;
        break;
    case Q_CORNER:
        r->x = floor(r->x);
        r->y = floor(r->y);
        if (s == 0) { /* along a pixel row boundary */
            r->dy = 0;
            r->dx = floor(r->dx);
        }
        break;
    case Q_SAMPLE: {
        float wf;
        int32_t wq;
        uint32_t px = ltt_rng_below(g, im_w[m]), py = ltt_rng_below(g, im_h[m]);
        im_w_at(m, 0, px, py, &wf, &wq);
        r->x = px + 0.5;
        r->y = py + 0.5;
        if (wf == wf && wf > 0.0f && wf < 2.0f)
            r->w = (double)wf; /* on the surface */
        break;
    }
    case Q_BORDER:
        if (s == 0) {
            r->x = 0;
            r->dx = (ltt_rng_u32(g) & 1u) ? 0 : fabs(r->dx);
        } else if (s == 1) {
            r->x = W;
            r->dx = (ltt_rng_u32(g) & 1u) ? 0 : -fabs(r->dx);
        } else if (s == 2) {
            r->y = 0;
            r->dy = 0;
        } else {
            r->y = H;
            r->dy = -fabs(r->dy);
        }
        break;
    case Q_LIMIT: /* start and / or end exactly on +-2^14 px (valid) */
        r->x = (s & 1u) ? lim : -lim;
        r->dx = (s & 2u) ? -2.0 * r->x : -r->x + W / 2;
        if (ltt_rng_u32(g) & 1u) {
            r->y = -lim;
            r->dy = 2 * lim;
        }
        break;
    case Q_PAST: /* the start on +-2^14 px, or the end on it (W/2 + dx = +-2^14) */
        if (s & 2u) {
            r->x = (s & 1u) ? lim : -lim;
            r->dx = -r->x;
        } else {
            r->x = floor(W / 2);
            r->dx = ((s & 1u) ? lim : -lim) - r->x;
        }
        break;
    default:
        break;
    }
    /* float32 lanes */
    r->f[0] = (float)r->x;
    r->f[1] = (float)r->y;
    r->f[2] = (float)r->w;
    r->f[3] = (float)r->dx;
    r->f[4] = (float)r->dy;
    r->f[5] = (float)r->dw;
    r->f[6] = (float)r->tmin;
    r->f[7] = (float)r->tmax;
    /* s1.30 / s15.16 lanes (values beyond the formats saturate) */
    r->q[0] = q16d(r->x);
    r->q[1] = q16d(r->y);
    r->q[2] = q30s(r->w);
    r->q[3] = (int32_t)fmax(fmin(r->dx * 65536.0, 2147483647.0), -2147483648.0);
    r->q[4] = (int32_t)fmax(fmin(r->dy * 65536.0, 2147483647.0), -2147483648.0);
    r->q[5] = q30s(r->dw);
    r->q[6] = q30s(r->tmin);
    r->q[7] = q30s(r->tmax);
    switch (c) {
    case Q_ZERO:
        if (s & 2u) { /* -0 everywhere in float32 */
            r->f[3] = r->f[4] = -0.0f;
            if (s & 1u)
                r->f[5] = -0.0f;
        }
        break;
    case Q_AXIS:
        if (s & 2u)
            r->f[(s & 1u) ? 3 : 4] = -0.0f;
        break;
    case Q_DENORM: {
        static const float den[] = {FLT_MIN / 2, -FLT_MIN / 2, 0x1p-149f, -0x1p-149f, 1e-40f};
        r->f[3 + (a % 3u)] = den[ltt_rng_below(g, 5)];
        if (s == 0)
            r->f[3 + ((a + 1u) % 3u)] = den[ltt_rng_below(g, 5)];
        if (s == 1) /* a positive denormal start w (a negative one is w < 0: BADRAY) */
            r->f[2] = den[2u * ltt_rng_below(g, 2)];
        break;
    }
    case Q_TINY: {
        static const int32_t tiny[] = {1, -1, 2, -2, 0};
        r->q[3] = tiny[ltt_rng_below(g, 5)];
        r->q[4] = tiny[ltt_rng_below(g, 5)];
        if (s == 0)
            r->q[5] = tiny[ltt_rng_below(g, 5)];
        break;
    }
    case Q_WEXT: {
        static const float wf[] = {FLT_MAX, 1e30f, 2.0f, 0x1p-149f};
        static const float dwf[] = {-FLT_MAX, FLT_MAX, -1e30f, 0.0f};
        static const int32_t wq[] = {INT32_MAX, INT32_MAX, 0, 1};
        static const int32_t dwq[] = {INT32_MIN, INT32_MAX, INT32_MAX, -1};
        r->f[2] = wf[s];
        r->f[5] = dwf[ltt_rng_below(g, 4)];
        r->q[2] = wq[s];
        r->q[5] = dwq[ltt_rng_below(g, 4)];
        break;
    }
    case Q_NAN:
        r->f[a] = (ltt_rng_u32(g) & 1u) ? NAN : -NAN;
        break;
    case Q_INF:
        r->f[a] = (ltt_rng_u32(g) & 1u) ? INFINITY : -INFINITY;
        break;
    case Q_NAN_T:
        if (s != 1)
            r->f[6] = NAN;
        if (s != 0)
            r->f[7] = NAN;
        break;
    case Q_TMIN_GT:
        r->f[6] = 0.75f;
        r->f[7] = s == 0 ? 0.5f : (s == 1 ? 0.0f : 0x1.7ffffep-1f);
        r->q[6] = 3 << 28;
        r->q[7] = s == 0 ? 1 << 29 : (s == 1 ? INT32_MIN : (3 << 28) - 1);
        break;
    case Q_T_OUT: {
        static const float tf[4][2] = {{-0x1p-149f, 1.0f}, {0.0f, 0x1.000002p0f},
                                       {-FLT_MAX, FLT_MAX}, {-INFINITY, INFINITY}};
        static const int32_t tq[4][2] = {{-1, 1 << 30}, {0, (1 << 30) + 1}, {INT32_MIN, INT32_MAX},
                                         {-(1 << 30), 1 << 29}};
        r->f[6] = tf[s][0];
        r->f[7] = tf[s][1];
        r->q[6] = tq[s][0];
        r->q[7] = tq[s][1];
        break;
    }
    case Q_PAST:
        /* one raw unit (s15.16) / one ulp at 2^14 (float32) beyond the limit, at the start or
         * the end */
        if (s & 2u) {
            r->f[0] = nextafterf(r->f[0], r->f[0] > 0 ? INFINITY : -INFINITY);
            r->q[0] = r->q[0] > 0 ? r->q[0] + 1 : r->q[0] - 1;
        } else {
            r->f[3] += r->f[3] > 0 ? 0x1p-9f : -0x1p-9f;
            r->q[3] = r->q[3] > 0 ? r->q[3] + 1 : r->q[3] - 1;
        }
        break;
    case Q_WNEG: {
        static const float wn[] = {-0x1p-149f, -1.0f, -FLT_MAX, -INFINITY};
        static const int32_t wqn[] = {-1, -(1 << 30), INT32_MIN, -2};
        r->f[2] = wn[s];
        r->q[2] = wqn[s];
        break;
    }
    default:
        break;
    }
}

typedef struct qtally {
    unsigned long lanes[MAXC], hit[MAXC], miss[MAXC], occ[MAXC], unk[MAXC], bad[MAXC],
        badray[MAXC], bad_status[MAXC];
    unsigned long untouched_bad, calls, builds;
} qtally_t;

/* The defined result of a class: 1 = LT_QT_BADRAY, 0 = any other status. */
static int qt_expect_bad(int c)
{
    return c >= Q_FIRST_BAD;
}

static void qt_trace_one(const lt_qt_t *qt, int f32, int m, const qray_t *rs, unsigned n,
                         uint32_t steps, qtally_t *T)
{
    unsigned p, i, pass;
    for (p = 0; p < n; p += 16)
        for (pass = 0; pass < 2; pass++) {
            lt_mask16_t k = pass ? (lt_mask16_t)(0x6C93u ^ (p * 0x0101u)) : LT_MASK_ALL;
            int32_t st[16];
            double t[16], w[16], t0[16], t1[16];
            int32_t layer[16];
            int untouched = 1;
            T->calls++;
            if (f32) {
                lt_qray16_f32_t r;
                lt_qhit16_f32_t h, h0;
                memset(&r, 0, sizeof r);
                for (i = 0; i < 16; i++) {
                    const float *f = rs[p + i].f;
                    r.x.l[i] = f[0];
                    r.y.l[i] = f[1];
                    r.w.l[i] = f[2];
                    r.dx.l[i] = f[3];
                    r.dy.l[i] = f[4];
                    r.dw.l[i] = f[5];
                    r.tmin.l[i] = f[6];
                    r.tmax.l[i] = f[7];
                    t0[i] = (double)f[6];
                    t1[i] = (double)f[7];
                }
                ltt_poison(&h, sizeof h);
                h0 = h;
                assert_int_equal(lt_qt_trace16_f32(qt, &r, k, steps, &h), LT_OK);
                for (i = 0; i < 16; i++) {
                    st[i] = h.status.l[i];
                    t[i] = (double)h.t.l[i];
                    w[i] = (double)h.w.l[i];
                    layer[i] = h.layer.l[i];
                    if (!LTT_ON(k, i))
                        untouched &= h.status.l[i] == h0.status.l[i] &&
                                     h.layer.l[i] == h0.layer.l[i] &&
                                     memcmp(&h.t.l[i], &h0.t.l[i], 4) == 0 &&
                                     h.nodes.l[i] == h0.nodes.l[i];
                }
            } else {
                lt_qray16_q30_t r;
                lt_qhit16_q30_t h, h0;
                for (i = 0; i < 16; i++) {
                    const int32_t *q = rs[p + i].q;
                    r.x.l[i] = q[0];
                    r.y.l[i] = q[1];
                    r.w.l[i] = q[2];
                    r.dx.l[i] = q[3];
                    r.dy.l[i] = q[4];
                    r.dw.l[i] = q[5];
                    r.tmin.l[i] = q[6];
                    r.tmax.l[i] = q[7];
                    t0[i] = q[6];
                    t1[i] = q[7];
                }
                ltt_poison(&h, sizeof h);
                h0 = h;
                assert_int_equal(lt_qt_trace16_q30(qt, &r, k, steps, &h), LT_OK);
                for (i = 0; i < 16; i++) {
                    st[i] = h.status.l[i];
                    t[i] = h.t.l[i];
                    w[i] = h.w.l[i];
                    layer[i] = h.layer.l[i];
                    if (!LTT_ON(k, i))
                        untouched &= h.status.l[i] == h0.status.l[i] &&
                                     h.layer.l[i] == h0.layer.l[i] && h.t.l[i] == h0.t.l[i] &&
                                     h.nodes.l[i] == h0.nodes.l[i];
                }
            }
            T->untouched_bad += !untouched;
            for (i = 0; i < 16; i++) {
                const qray_t *q = &rs[p + i];
                int c = q->cls, eb;
                if (!LTT_ON(k, i))
                    continue;
                T->lanes[c]++;
                if (st[i] < LT_QT_MISS || st[i] > LT_QT_BADRAY) {
                    T->bad_status[c]++;
                    continue;
                }
                eb = qt_expect_bad(c);
                if ((st[i] == LT_QT_BADRAY) != eb) {
                    if (T->bad_status[c]++ < 3)
                        ltt_report("  status %s %s %s: ray %u status %d (BADRAY expected: %d)\n",
                                   f32 ? "f32" : "q30", im_name[m], qt_cls[c].name, p + i, st[i],
                                   eb);
                }
                if (st[i] == LT_QT_BADRAY)
                    T->badray[c]++;
                else if (st[i] == LT_QT_MISS)
                    T->miss[c]++;
                else if (st[i] == LT_QT_OCCLUDED)
                    T->occ[c]++;
                else if (st[i] == LT_QT_UNKNOWN)
                    T->unk[c]++;
                else
                    T->hit[c]++;
                if (st[i] == LT_QT_HIT || st[i] == LT_QT_OCCLUDED) {
                    int okr = t[i] >= t0[i] && t[i] <= t1[i] && w[i] == w[i] && layer[i] >= 0 &&
                              (uint32_t)layer[i] < qt->layers;
                    if (!okr && T->bad[c]++ < 3)
                        ltt_report("  range %s %s %s: ray %u status %d t %.9g not in [%.9g, %.9g] "
                                   "or w %.9g / layer %d invalid\n",
                                   f32 ? "f32" : "q30", im_name[m], qt_cls[c].name, p + i, st[i],
                                   t[i], t0[i], t1[i], w[i], layer[i]);
                }
            }
        }
}

#define QPER 32 /* rays per class */

static void run_qt(int fmt, qtally_t *T, qtally_t *Tx)
{
    int m, c, qcls[Q_NCLS], nq = 0;
    ltt_rng_t g;
    qray_t *rs = malloc(Q_NCLS * QPER * sizeof *rs);
    assert_non_null(rs);
    /* the classes of this path (NaN, inf and denormal lanes are float32's, 1-raw ones s1.30's) */
    for (c = 0; c < Q_NCLS; c++)
        if (fmt == LT_QT_F32 ? c != Q_TINY
                             : (c != Q_NAN && c != Q_INF && c != Q_NAN_T && c != Q_DENORM))
            qcls[nq++] = c;
    ltt_rng_seed(&g, 0x0A17u + (unsigned)fmt);
    for (m = 0; m < IM_N; m++) {
        lt_qt_desc_t d;
        lt_qt_t qt;
        size_t need = 0, n = (size_t)im_w[m] * im_h[m] * im_l[m], i;
        float *wf = malloc(n * sizeof *wf);
        int32_t *wq = malloc(n * sizeof *wq);
        void *arena;
        uint32_t L, x, y;
        unsigned r, s;
        assert_non_null(wf);
        assert_non_null(wq);
        for (L = 0, i = 0; L < im_l[m]; L++)
            for (y = 0; y < im_h[m]; y++)
                for (x = 0; x < im_w[m]; x++, i++)
                    im_w_at(m, L, x, y, &wf[i], &wq[i]);
        d.width = im_w[m];
        d.height = im_h[m];
        d.layers = im_l[m];
        d.enc = (uint32_t)fmt;
        assert_int_equal(lt_qt_size(&d, &need), LT_OK);
        arena = malloc(need + 64);
        assert_non_null(arena);
        if (fmt == LT_QT_F32)
            assert_int_equal(lt_qt_build_f32(&qt, &d, NULL, wf, arena, &need), LT_OK);
        else
            assert_int_equal(lt_qt_build_q30(&qt, &d, NULL, wq, arena, &need), LT_OK);
        if (fmt == LT_QT_F32 && m == IM_EXTREME)
            Tx->builds++;
        else
            T->builds++;
        for (r = 0; r < Q_NCLS * QPER; r++)
            qray_gen(&g, m, qcls[r % (unsigned)nq], &rs[r]);
        /* the f32 extreme image (w >= 2) is outside lt_qt_build_f32's documented range */
        for (s = 0; s < 2; s++)
            qt_trace_one(&qt, fmt == LT_QT_F32, m, rs, Q_NCLS * QPER, s ? 2u : 0u,
                         (fmt == LT_QT_F32 && m == IM_EXTREME) ? Tx : T);
        free(arena);
        free(wf);
        free(wq);
    }
    free(rs);
}

static int qt_report(const char *path, const qtally_t *T, int in_contract)
{
    unsigned c;
    unsigned long tl = 0, tb = 0, ts = 0;
    int fail = 0;
    for (c = 0; c < Q_NCLS; c++) {
        tl += T->lanes[c];
        tb += T->bad[c];
        ts += T->bad_status[c];
    }
    ltt_report("quadtree %s: %lu builds, %lu packets (full and partial masks, default step bound "
               "and 2), %lu lanes; hits/occluded outside [tmin, tmax] or bad w/layer: %lu (bound "
               "0), wrong BADRAY decisions or statuses: %lu (bound 0), lanes outside the mask "
               "written: %lu (bound 0); per class lanes hit/miss/occluded/unknown/badray:",
               path, T->builds, T->calls, tl, tb, ts, T->untouched_bad);
    for (c = 0; c < Q_NCLS; c++)
        if (T->lanes[c])
            ltt_report(" %s %lu %lu/%lu/%lu/%lu/%lu;", qt_cls[c].name, T->lanes[c], T->hit[c],
                       T->miss[c], T->occ[c], T->unk[c], T->badray[c]);
    ltt_report("\n");
    for (c = 0; c < Q_NCLS; c++) {
        if (T->bad[c] == 0 && T->bad_status[c] == 0)
            continue;
        if (in_contract && qt_cls[c].in_contract) {
            ltt_report("FAIL quadtree %s: %s: %lu out-of-range results, %lu wrong statuses\n", path,
                       qt_cls[c].name, T->bad[c], T->bad_status[c]);
            fail = 1;
        } else {
            ltt_report("KNOWN quadtree %s: %s (out of contract): %lu out-of-range results, %lu "
                       "unexpected statuses\n",
                       path, qt_cls[c].name, T->bad[c], T->bad_status[c]);
        }
    }
    if (T->untouched_bad)
        fail = 1;
    return fail;
}

static void test_quadtree(void **state)
{
    qtally_t *T = calloc(4, sizeof *T);
    int fmt, fail = 0;
    static const char *const nm[3] = {"n64 (s1.30)", "n32 (s1.30)", "f32"};
    (void)state;
    assert_non_null(T);
    for (fmt = 0; fmt < 3; fmt++) {
        run_qt(fmt, &T[fmt], &T[3]);
        fail |= qt_report(nm[fmt], &T[fmt], 1);
    }
    fail |= qt_report("f32 on the extreme image (w = 2 .. FLT_MAX, beyond the build's w < 2)",
                      &T[3], 0);
    free(T);
    assert_int_equal(fail, 0);
}

static int setup(void **state)
{
    (void)state;
    return lt_qmc_interleave4x4(LT_QMC_LP, 0, &g_sets) == LT_OK ? 0 : -1;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shadow_frusta),
        cmocka_unit_test(test_primary_frusta),
        cmocka_unit_test(test_quadtree),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
