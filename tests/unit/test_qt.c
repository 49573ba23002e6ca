/* test_qt.c - cmocka tests of the screen-space quadtree (lt_qt.h, Widmer et al. 2015
 * [Widmer15]) in its three node formats (64-bit and 32-bit fixed point, float32) against
 *   - the double-precision reference that marches every pixel over the leaf planes of Alg. 1
 *     (host/render/lt_qt_ref.c), fed with the exact values each path sees (raw / 2^30, floats as double),
 *     so the figures measure the hierarchy, the merges and the formats, not input rounding;
 *   - analytic scenes (a tilted plane, steps, spheres, depth bands from 1e-3 to 1e4) for the error
 *     of the whole model against the true surface.
 * Each test prints what it checked: cases, agreement, worst error and its bound, nodes visited and
 * ray-AABB / ray-plane tests per ray (mean, max) and the lanes' utilisation.
 * Builds: host, sim, asan (any LT_COST_MODE); float32 parts only with LT_CFG_FLOAT32.
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

#include "lt/lt_qt.h"
#include "io/lt_exr.h"
#include "io/lt_fx_float.h"
#include "render/lt_qt_ref.h"
#include "lt_ssb_testlib.h"
#include "lt_test_util.h"
#if LT_COST_MODE == LT_COST_SIM
#include "lt_sim.h"
#endif

#define Q30 1073741824.0
#define NFMT 3
static const char *const fmt_name[NFMT] = {"n64", "n32", "f32"};

/* Two's complement field of `bits` bits (the node formats of lt_qt.h). */
static int32_t q_sext_test(uint32_t v, unsigned bits)
{
    return (int32_t)v - (int32_t)(((v >> (bits - 1u)) & 1u) << bits);
}

/* ---- scenes: analytic w(x, y) per layer, sampled at pixel centres ------------------------------ */

/* The scene type, the plane, spheres, steps, checker, card and wave fields, sampling and the ray
 * generators are tests/unit/lt_ssb_testlib.h's (shared with test_ssbase.c and ssbench.c). */

/* depth bands: 8 vertical bands at depths 1e-3 .. 1e4 (w = 2^-10 / z), each gently tilted */
static double w_bands(const ss_scene_t *s, int layer, double x, double y)
{
    int b = (int)floor(x / (s->W / 8.0));
    double z = pow(10.0, -3.0 + b);
    (void)layer;
    (void)y;
    return ldexp(1.0, -10) / z * (1.0 + 2e-4 * (x - (b + 0.5) * (s->W / 8.0)));
}

/* ---- building ----------------------------------------------------------------------------- */

typedef struct built {
    lt_qt_t qt[NFMT];
    void *arena[NFMT];
    size_t bytes[NFMT];
    lt_qt_ref_t ref[2]; /* [0] on the s1.30 input, [1] on the float input */
    int nfmt;
} built_t;

static void build_all(const ss_scene_t *s, const lt_qt_params_t *p, built_t *b)
{
    int f;
    lt_qt_params_t dp;
    if (p == NULL) {
        lt_qt_params_default(&dp);
        p = &dp;
    }
    b->nfmt = LT_CFG_FLOAT32 ? 3 : 2;
    for (f = 0; f < b->nfmt; f++) {
        lt_qt_desc_t d;
        size_t need = 0;
        lt_status_t st;
        d.width = s->W;
        d.height = s->H;
        d.layers = s->layers;
        d.enc = (uint32_t)f;
        assert_int_equal(lt_qt_size(&d, &need), LT_OK);
        b->arena[f] = malloc(need + 64);
        assert_non_null(b->arena[f]);
        b->bytes[f] = need;
        if (f < 2) {
            st = lt_qt_build_q30(&b->qt[f], &d, p, s->wq, b->arena[f], &need);
        } else {
#if LT_CFG_FLOAT32
            st = lt_qt_build_f32(&b->qt[f], &d, p, s->wf, b->arena[f], &need);
#else
            st = LT_E_ARG;
#endif
        }
        assert_int_equal(st, LT_OK);
    }
    assert_int_equal(lt_qt_ref_build(&b->ref[0], s->wqd, s->W, s->H, s->layers,
                                     p->lambda_h / Q30, p->lambda_d / Q30),
                     0);
    assert_int_equal(lt_qt_ref_build(&b->ref[1], s->wfd, s->W, s->H, s->layers,
                                     (double)((float)p->lambda_h * 9.31322574615478515625e-10f),
                                     (double)((float)p->lambda_d * 9.31322574615478515625e-10f)),
                     0);
}

static void built_free(built_t *b)
{
    int f;
    for (f = 0; f < b->nfmt; f++)
        free(b->arena[f]);
    lt_qt_ref_free(&b->ref[0]);
    lt_qt_ref_free(&b->ref[1]);
}

/* root node of layer 0 is a plane? */
static int root_is_plane(const built_t *b, int f)
{
    const lt_qt_t *q = &b->qt[f];
    uint32_t r = q->off[q->levels - 1u];
    if (f == 0)
        return !LT_QT_N64_IS_AABB(((const lt_qt_n64_t *)q->nodes)[r]);
    if (f == 1)
        return !LT_QT_N32_IS_AABB(((const lt_qt_n32_t *)q->nodes)[r]);
#if LT_CFG_FLOAT32
    return !LT_QT_NF32_IS_AABB(((const lt_qt_nf32_t *)q->nodes)[r]);
#else
    return 0;
#endif
}

static uint32_t count_planes(const built_t *b, int f)
{
    const lt_qt_t *q = &b->qt[f];
    uint32_t i, n = 0, tot = q->layer_nodes * q->layers;
    for (i = 0; i < tot; i++) {
        if (f == 0)
            n += !LT_QT_N64_IS_AABB(((const lt_qt_n64_t *)q->nodes)[i]);
        else if (f == 1)
            n += !LT_QT_N32_IS_AABB(((const lt_qt_n32_t *)q->nodes)[i]);
#if LT_CFG_FLOAT32
        else
            n += !LT_QT_NF32_IS_AABB(((const lt_qt_nf32_t *)q->nodes)[i]);
#endif
    }
    return n;
}

/* ---- tracing sets of rays ------------------------------------------------------------------ */

/* Every fixed-point packet that trace_set traces is traced again one ray at a time
 * (lt_qt_trace1_q30) and the two hit records compared whole (test_single_rays reports the
 * totals); off while the simulator counts one walk (test_sim_counts). */
static int g_single_check = 1;
static size_t g_single_packets, g_single_lanes, g_single_nodes;

static void check_single_q30(const lt_qt_t *qt, const lt_qray16_q30_t *r, lt_mask16_t k,
                             uint32_t max_steps, const lt_qhit16_q30_t *want_poisoned)
{
    lt_qhit16_q30_t h1;
    int i;
    memset(&h1, 0x5A, sizeof h1);
    assert_int_equal(lt_qt_trace1_q30(qt, r, k, max_steps, &h1), LT_OK);
    if (memcmp(&h1, want_poisoned, sizeof h1) != 0) {
        for (i = 0; i < 16; i++)
            if (h1.status.l[i] != want_poisoned->status.l[i] || h1.t.l[i] != want_poisoned->t.l[i] ||
                h1.w.l[i] != want_poisoned->w.l[i] || h1.nodes.l[i] != want_poisoned->nodes.l[i] ||
                h1.layer.l[i] != want_poisoned->layer.l[i] ||
                h1.aabb.l[i] != want_poisoned->aabb.l[i] ||
                h1.planes.l[i] != want_poisoned->planes.l[i])
                print_error("lane %d (k 0x%04x): single status %d t %d w %d layer %d nodes %d "
                            "aabb %d planes %d, packet %d %d %d %d %d %d %d\n",
                            i, (unsigned)k, h1.status.l[i], h1.t.l[i], h1.w.l[i],
                            h1.layer.l[i], h1.nodes.l[i], h1.aabb.l[i], h1.planes.l[i],
                            want_poisoned->status.l[i], want_poisoned->t.l[i],
                            want_poisoned->w.l[i], want_poisoned->layer.l[i],
                            want_poisoned->nodes.l[i], want_poisoned->aabb.l[i],
                            want_poisoned->planes.l[i]);
        fail_msg("lt_qt_trace1_q30 differs from lt_qt_trace16_q30");
    }
    g_single_packets++;
    for (i = 0; i < 16; i++)
        if (LTT_ON(k, i)) {
            g_single_lanes++;
            g_single_nodes += (size_t)h1.nodes.l[i];
        }
}

/* Trace n rays (double segments) through format f in packets of 16 (lane = index % 16).
 * exact[] receives the segments as the format represents them (for the reference). Returns the
 * lane utilisation: useful lane-steps / (16 x the packets' longest lane). */
static double trace_set(const built_t *b, int f, const lt_qt_ref_ray_t *rays, size_t n,
                        uint32_t max_steps, ss_res_t *out, lt_qt_ref_ray_t *exact)
{
    size_t p, i;
    double used = 0.0, slots = 0.0;
    for (p = 0; p < n; p += 16) {
        size_t cnt = n - p < 16 ? n - p : 16;
        lt_mask16_t k;
        int maxn = 0;
        if (f < 2) {
            lt_qray16_q30_t r;
            lt_qhit16_q30_t h;
            k = ss_pack_q30(rays + p, cnt, &r, exact + p);
            memset(&h, 0x5A, sizeof h);
            assert_int_equal(lt_qt_trace16_q30(&b->qt[f], &r, k, max_steps, &h), LT_OK);
            if (g_single_check)
                check_single_q30(&b->qt[f], &r, k, max_steps, &h);
            ss_res_q30(&h, cnt, out + p);
        } else {
#if LT_CFG_FLOAT32
            lt_qray16_f32_t r;
            lt_qhit16_f32_t h;
            k = ss_pack_f32(rays + p, cnt, &r, exact + p);
            assert_int_equal(lt_qt_trace16_f32(&b->qt[f], &r, k, max_steps, &h), LT_OK);
            ss_res_f32(&h, cnt, out + p);
#endif
        }
        for (i = 0; i < 16 && p + i < n; i++) {
            used += out[p + i].nodes;
            if (out[p + i].nodes > maxn)
                maxn = out[p + i].nodes;
        }
        slots += 16.0 * maxn;
    }
    return slots > 0.0 ? used / slots : 1.0;
}

/* a / b in percent and a / b for counts (explicit conversions for -Wconversion) */
static double pct(size_t a, size_t b) { return b ? 100.0 * (double)a / (double)b : 0.0; }
static double per(double a, size_t b) { return b ? a / (double)b : 0.0; }

/* ---- comparison with the reference --------------------------------------------------------- */

typedef struct cmp {
    size_t n, same_status, same_hit, hits_both;
    double sq_dz, max_dz;   /* relative depth error on rays both call HIT */
    double sum_nodes, sum_aabb, sum_planes, sum_pix;
    int max_nodes, max_aabb, max_planes;
    double util;
} cmp_t;

/* Same hit: same status and, for hits, the same layer and hit points within 1/2 pixel on screen;
 * for occlusions and misses, the same status. */
static void compare(const built_t *b, int f, const lt_qt_ref_ray_t *rays, size_t n,
                    uint32_t max_steps, cmp_t *c, ss_res_t *out, lt_qt_ref_hit_t *refh)
{
    lt_qt_ref_ray_t *ex = (lt_qt_ref_ray_t *)malloc(n * sizeof *ex);
    size_t i;
    assert_non_null(ex);
    memset(c, 0, sizeof *c);
    c->util = trace_set(b, f, rays, n, max_steps, out, ex);
    for (i = 0; i < n; i++) {
        lt_qt_ref_hit_t *h = &refh[i];
        const ss_res_t *o = &out[i];
        lt_qt_ref_trace(&b->ref[f == 2 ? 1 : 0], &ex[i], h);
        c->n++;
        c->sum_nodes += o->nodes;
        c->sum_aabb += o->aabb;
        c->sum_planes += o->planes;
        c->sum_pix += (double)h->pixels;
        if (o->nodes > c->max_nodes)
            c->max_nodes = o->nodes;
        if (o->aabb > c->max_aabb)
            c->max_aabb = o->aabb;
        if (o->planes > c->max_planes)
            c->max_planes = o->planes;
        if (o->status != h->status && getenv("LT_QT_VERBOSE") != NULL)
            ltt_report("  DIFF x %.9g y %.9g w %.9g dx %.9g dy %.9g dw %.9g [%g, %g]: status %d t "
                       "%.9g w %.9g layer %d, reference %d t %.9g w %.9g layer %d\n", ex[i].x,
                       ex[i].y, ex[i].w, ex[i].dx, ex[i].dy, ex[i].dw, ex[i].tmin, ex[i].tmax,
                       o->status, o->t, o->w, o->layer, h->status, h->t, h->w, h->layer);
        if (o->status == h->status) {
            c->same_status++;
            if (o->status == LT_QT_HIT) {
                double len = hypot(ex[i].dx, ex[i].dy) + 1e-30;
                double dz = fabs(1.0 / o->w - 1.0 / h->w) * h->w;
                c->hits_both++;
                c->sq_dz += dz * dz;
                if (dz > c->max_dz)
                    c->max_dz = dz;
                if (o->layer == h->layer && fabs(o->t - h->t) * len <= 0.5)
                    c->same_hit++;
            } else {
                c->same_hit++;
            }
        }
    }
    free(ex);
}

static void print_cmp(const char *scene, int f, const cmp_t *c)
{
    ltt_report("%s %s: %zu rays, same status as reference %.2f%%, same hit %.2f%%, depth vs "
               "reference on %zu common hits: RMSE %.3g max %.3g (relative)\n",
               scene, fmt_name[f], c->n, pct(c->same_status, c->n), pct(c->same_hit, c->n),
               c->hits_both, sqrt(per(c->sq_dz, c->hits_both)), c->max_dz);
    ltt_report("%s %s: per ray nodes visited mean %.2f max %d, ray-AABB tests mean %.2f max %d, "
               "ray-plane tests mean %.2f max %d (reference pixels mean %.1f); lane utilisation "
               "%.1f%%\n",
               scene, fmt_name[f], per(c->sum_nodes, c->n), c->max_nodes, per(c->sum_aabb, c->n),
               c->max_aabb, per(c->sum_planes, c->n), c->max_planes, per(c->sum_pix, c->n),
               100.0 * c->util);
}

/* ---- rays ------------------------------------------------------------------------------------ */

/* Coherent and random packets (lt_ssb_testlib.h's ss_gen_rays_in). The tile range is this file's
 * own: W - 4 in uint32_t, which wraps to ~2^32 for images narrower than 4 px (likewise H), so
 * that there every start lies past the image and clamps to W - 0.5; kept because it defines the
 * ray sets (and printed figures) of test_small_images. */
static void gen_rays(const ss_scene_t *s, ltt_rng_t *g, size_t n, int coherent, lt_qt_ref_ray_t *r)
{
    double xr = s->W - 4 > 0 ? s->W - 4 : 1, yr = s->H - 4 > 0 ? s->H - 4 : 1;
    ss_gen_rays_in(s, g, n, coherent, xr, yr, r);
}

/* ---- analytic ground truth: dense march on the true w(x, y) ------------------------------- */

/* status / t of the first event: a sign change of f = w_ray - w_true; after bisection, a jump of
 * the surface across the final interval marks a discontinuity (occlusion), else a hit. */
static int analytic(const ss_scene_t *s, const lt_qt_ref_ray_t *r, double *t_out)
{
    double t0 = r->tmin, t1 = r->tmax, len = hypot(r->dx, r->dy);
    int a, i, steps;
    double prev_t, prev_f;
    for (a = 0; a < 2; a++) {
        double o = a ? r->y : r->x, d = a ? r->dy : r->dx, ext = a ? s->H : s->W;
        if (d == 0.0) {
            if (!(o >= 0.0 && o < ext))
                return LT_QT_MISS;
        } else {
            double ta = (0.0 - o) / d, tb = (ext - o) / d, tt;
            if (ta > tb) {
                tt = ta;
                ta = tb;
                tb = tt;
            }
            t0 = ta > t0 ? ta : t0;
            t1 = tb < t1 ? tb : t1;
        }
    }
    if (r->dw < 0.0 && r->w / -r->dw < t1)
        t1 = r->w / -r->dw;
    if (!(t0 < t1))
        return LT_QT_MISS;
    steps = (int)(len * (t1 - t0) * 16.0) + 64;
    prev_t = t0;
    prev_f = r->w + t0 * r->dw - s->fn(s, 0, r->x + t0 * r->dx, r->y + t0 * r->dy);
    for (i = 1; i <= steps; i++) {
        double t = t0 + (t1 - t0) * i / steps;
        double f = r->w + t * r->dw - s->fn(s, 0, r->x + t * r->dx, r->y + t * r->dy);
        if (prev_f >= 0.0 && f < 0.0) {
            double lo = prev_t, hi = t, jump;
            int it;
            for (it = 0; it < 60; it++) {
                double m = 0.5 * (lo + hi);
                double fm = r->w + m * r->dw - s->fn(s, 0, r->x + m * r->dx, r->y + m * r->dy);
                if (fm >= 0.0)
                    lo = m;
                else
                    hi = m;
            }
            jump = fabs(s->fn(s, 0, r->x + hi * r->dx, r->y + hi * r->dy) -
                        s->fn(s, 0, r->x + lo * r->dx, r->y + lo * r->dy));
            *t_out = lo;
            return jump > 1e-6 ? LT_QT_OCCLUDED : LT_QT_HIT;
        }
        prev_t = t;
        prev_f = f;
    }
    return LT_QT_MISS;
}

/* The segment's parameter range on the screen: [c0, c1] within [tmin, tmax]. */
static void clip_t(const ss_scene_t *s, const lt_qt_ref_ray_t *r, double *c0, double *c1)
{
    int a;
    *c0 = r->tmin;
    *c1 = r->tmax;
    for (a = 0; a < 2; a++) {
        double o = a ? r->y : r->x, d = a ? r->dy : r->dx, ext = a ? s->H : s->W, ta, tb;
        if (d == 0.0)
            continue;
        ta = (0.0 - o) / d;
        tb = (ext - o) / d;
        if (ta > tb) {
            double u = ta;
            ta = tb;
            tb = u;
        }
        *c0 = ta > *c0 ? ta : *c0;
        *c1 = tb < *c1 ? tb : *c1;
    }
}

/* ---- tests ----------------------------------------------------------------------------------- */

/* Size query against an independent count; arena poisoned 0xA5 and its tail untouched; too small
 * gives LT_E_SPACE with the size needed and no write; bad descriptors give LT_E_ARG. */
static void test_size_query(void **state)
{
    static const uint32_t dims[][3] = {{1, 1, 1},  {1, 17, 1},  {17, 1, 2},  {37, 23, 1},
                                       {64, 64, 1}, {100, 60, 3}, {640, 480, 1}, {3, 5, 2}};
    size_t di, cases = 0, touched = 0;
    int f;
    (void)state;
    for (di = 0; di < sizeof dims / sizeof dims[0]; di++) {
        uint32_t W = dims[di][0], H = dims[di][1], layers = dims[di][2], L;
        size_t n = (size_t)W * H * layers;
        lt_q30_t *w = (lt_q30_t *)malloc(n * sizeof *w);
        float *wf = (float *)malloc(n * sizeof *wf);
        uint64_t nodes = 0;
        assert_non_null(w);
        assert_non_null(wf);
        ss_size_test_w(w, wf, n);
        /* independent count: levels until 1x1 */
        for (L = 0;; L++) {
            uint32_t nx = (W + (1u << L) - 1u) >> L, ny = (H + (1u << L) - 1u) >> L;
            nodes += (uint64_t)nx * ny;
            if (nx == 1 && ny == 1)
                break;
        }
        for (f = 0; f < (LT_CFG_FLOAT32 ? 3 : 2); f++) {
            static const size_t nb[3] = {8, 4, 16};
            lt_qt_desc_t d;
            lt_qt_t qt;
            size_t need = 0, have, expect = (size_t)nodes * layers * nb[f];
            unsigned char *arena;
            lt_status_t st;
            d.width = W;
            d.height = H;
            d.layers = layers;
            d.enc = (uint32_t)f;
            assert_int_equal(lt_qt_size(&d, &need), LT_OK);
            assert_int_equal(need, expect);
            arena = (unsigned char *)malloc(need + 64);
            assert_non_null(arena);
            /* too small: LT_E_SPACE, size written back, arena untouched */
            ltt_poison(arena, need + 64);
            have = need - 1;
            st = f < 2 ? lt_qt_build_q30(&qt, &d, NULL, w, arena, &have)
#if LT_CFG_FLOAT32
                       : lt_qt_build_f32(&qt, &d, NULL, wf, arena, &have);
#else
                       : LT_E_SPACE;
#endif
            assert_int_equal(st, LT_E_SPACE);
            assert_int_equal(have, need);
            assert_int_equal(ltt_touched(arena, 0, need + 64), 0);
            /* exact size: everything before `need` may be written, nothing after */
            have = need;
            st = f < 2 ? lt_qt_build_q30(&qt, &d, NULL, w, arena, &have)
#if LT_CFG_FLOAT32
                       : lt_qt_build_f32(&qt, &d, NULL, wf, arena, &have);
#else
                       : LT_OK;
#endif
            assert_int_equal(st, LT_OK);
            touched += ltt_touched(arena, need, need + 64);
            assert_int_equal(ltt_touched(arena, need, need + 64), 0);
            assert_int_equal(qt.levels, L + 1u);
            /* misaligned arena */
            have = need + 1;
            if (f < 2)
                assert_int_equal(lt_qt_build_q30(&qt, &d, NULL, w, arena + 1, &have), LT_E_ARG);
            free(arena);
            cases++;
        }
        free(w);
        free(wf);
    }
    /* bad descriptors */
    {
        lt_qt_desc_t d = {0, 4, 1, LT_QT_N64};
        size_t b;
        lt_qt_params_t p;
        lt_qt_t qt;
        lt_q30_t w1 = 0;
        assert_int_equal(lt_qt_size(&d, &b), LT_E_ARG);
        d.width = LT_QT_MAX_DIM + 1;
        assert_int_equal(lt_qt_size(&d, &b), LT_E_ARG);
        d.width = 4;
        d.layers = 0;
        assert_int_equal(lt_qt_size(&d, &b), LT_E_ARG);
        d.layers = LT_QT_MAX_LAYERS + 1;
        assert_int_equal(lt_qt_size(&d, &b), LT_E_ARG);
        d.layers = 1;
        d.enc = 7;
        assert_int_equal(lt_qt_size(&d, &b), LT_E_ARG);
        assert_int_equal(lt_qt_size(NULL, &b), LT_E_ARG);
        d.enc = LT_QT_N64;
        d.width = d.height = 1;
        lt_qt_params_default(&p);
        p.gamma_norm = -1;
        b = 64;
        assert_int_equal(lt_qt_build_q30(&qt, &d, &p, &w1, &b, &b), LT_E_ARG);
        assert_int_equal(lt_qt_build_q30(NULL, &d, NULL, &w1, &b, &b), LT_E_ARG);
        d.enc = LT_QT_F32;
        assert_int_equal(lt_qt_build_q30(&qt, &d, NULL, &w1, &b, &b), LT_E_ARG);
    }
    ltt_report("lt_qt_size/build: %zu size queries (1x1, 1xN, Nx1, non-power-of-two, layers 1-3, "
               "3 formats) = independent count, arena tail bytes touched %zu (bound 0), too small -> "
               "LT_E_SPACE with the size, bad desc/params/alignment -> LT_E_ARG\n",
               cases, touched);
}

/* A tilted plane compresses to one node; rays hit it within the format's bound. */
static void test_plane_one_node(void **state)
{
    static const uint32_t sz[2][2] = {{64, 64}, {100, 60}};
    int si, f;
    (void)state;
    for (si = 0; si < 2; si++) {
        ss_scene_t s;
        built_t b;
        ltt_rng_t g;
        size_t n = 2048, i;
        lt_qt_ref_ray_t *rays = (lt_qt_ref_ray_t *)malloc(n * sizeof *rays);
        lt_qt_ref_ray_t *ex = (lt_qt_ref_ray_t *)malloc(n * sizeof *ex);
        ss_res_t *out = (ss_res_t *)malloc(n * sizeof *out);
        assert_non_null(rays);
        assert_non_null(ex);
        assert_non_null(out);
        ss_scene_set(&s, "plane", sz[si][0], sz[si][1], 1, ss_w_plane);
        s.p[0] = 0.45;
        s.p[1] = 2.1e-4;
        s.p[2] = -1.3e-4;
        assert_int_equal(ss_scene_sample(&s), 0);
        build_all(&s, NULL, &b);
        ltt_rng_seed(&g, 100 + (uint64_t)si);
        /* segments from in front of the plane to behind it, crossing at a random pixel */
        for (i = 0; i < n; i++) {
            double xh = ltt_rng_uniform(&g, 0.5, s.W - 0.5), yh = ltt_rng_uniform(&g, 0.5, s.H - 0.5);
            double ux, uy, len, th, wh, dw;
            ss_rng_dir(&g, &ux, &uy);
            len = ltt_rng_uniform(&g, 0, 40);
            th = ltt_rng_uniform(&g, 0.1, 0.9);
            wh = ss_w_plane(&s, 0, xh, yh);
            dw = -ltt_rng_uniform(&g, 0.001, 0.3);
            rays[i].dx = len * ux;
            rays[i].dy = len * uy;
            /* keep rays that approach the plane from in front (f decreasing along the ray) */
            if (dw - s.p[1] * rays[i].dx - s.p[2] * rays[i].dy > -1e-4) {
                i--;
                continue;
            }
            rays[i].dw = dw;
            rays[i].x = xh - th * rays[i].dx;
            rays[i].y = yh - th * rays[i].dy;
            rays[i].w = wh - th * dw;
            rays[i].tmin = 0.0;
            rays[i].tmax = 1.0;
        }
        for (f = 0; f < b.nfmt; f++) {
            double emax = 0.0, bmax = 0.0, tmax_err = 0.0, eplane = 0.0;
            size_t hits = 0, bad = 0, near_end = 0;
            int c;
            (void)trace_set(&b, f, rays, n, 0, out, ex);
            /* the stored root plane against the true plane: linear, so the worst point of the
             * image rectangle is one of its corners */
            {
                const lt_qt_t *q = &b.qt[f];
                uint32_t r = q->off[q->levels - 1u];
                double C, Al, Be, S = ldexp(1.0, (int)q->levels - 1), xc = 0.5 * S, yc = 0.5 * S;
                assert_true(root_is_plane(&b, f));
                if (f == 0) {
                    lt_qt_n64_t nd = ((const lt_qt_n64_t *)q->nodes)[r];
                    C = (double)(nd.lo >> 8) * ldexp(1.0, (int)(nd.lo & 7u)) / Q30;
                    Al = (double)q_sext_test((nd.hi >> 15) & 0x7FFFu, 15) *
                         ldexp(1.0, (int)((nd.lo >> 3) & 31u)) / Q30;
                    Be = (double)q_sext_test(nd.hi & 0x7FFFu, 15) *
                         ldexp(1.0, (int)((nd.lo >> 3) & 31u)) / Q30;
                } else if (f == 1) {
                    uint32_t v = ((const lt_qt_n32_t *)q->nodes)[r].v;
                    int e = (int)((v >> 25) & 31u), ks = e + 3 * (int)((v >> 12) & 1u);
                    C = (double)((v >> 13) & 0xFFFu) * ldexp(1.0, e) / Q30;
                    Al = q_sext_test((v >> 6) & 63u, 6) * ldexp(1.0, ks) / Q30;
                    Be = q_sext_test(v & 63u, 6) * ldexp(1.0, ks) / Q30;
                } else {
#if LT_CFG_FLOAT32
                    lt_qt_nf32_t nd = ((const lt_qt_nf32_t *)q->nodes)[r];
                    C = (double)nd.c;
                    Al = (double)nd.al;
                    Be = (double)nd.be;
#else
                    C = Al = Be = 0.0;
#endif
                }
                for (c = 0; c < 4; c++) {
                    double x = (c & 1) ? s.W : 0.0, y = (c & 2) ? s.H : 0.0;
                    double dv = C + Al * (x - xc) / S + Be * (y - yc) / S - ss_w_plane(&s, 0, x, y);
                    if (fabs(dv) > eplane)
                        eplane = fabs(dv);
                }
            }
            for (i = 0; i < n; i++) {
                const lt_qt_ref_ray_t *e = &ex[i];
                double F1 = e->dw - s.p[1] * e->dx - s.p[2] * e->dy;
                double F0 = e->w - ss_w_plane(&s, 0, e->x, e->y), t = -F0 / F1;
                double err, bound, ulp = f < 2 ? 1.0 / Q30 : ldexp(1.0, -24);
                if (out[i].status != LT_QT_HIT) {
                    /* the stored plane may be crossed outside the segment when the true crossing
                     * is within eplane / |F1| of an end */
                    double margin = (eplane + 4.0 * ulp) / fabs(F1), c0 = 0.0, c1 = 1.0;
                    clip_t(&s, e, &c0, &c1);
                    if (t < c0 + margin || t > c1 - margin) {
                        near_end++;
                        continue;
                    }
                    ltt_report("  FAIL ray x %.9g y %.9g w %.9g dx %.9g dy %.9g dw %.9g: status %d "
                               "t %.9g (exact %.9g, F1 %.3g)\n", e->x, e->y, e->w, e->dx, e->dy,
                               e->dw, out[i].status, out[i].t, t, F1);
                    bad++;
                    continue;
                }
                hits++;
                /* distance of the hit point from the true surface, in w */
                err = fabs(out[i].w - ss_w_plane(&s, 0, e->x + out[i].t * e->dx,
                                              e->y + out[i].t * e->dy));
                /* stored plane's deviation + evaluation (2 ulp) + t rounding (2 ulp of t) */
                bound = eplane + 2.0 * ulp + 2.0 * ulp * fabs(F1) +
                        (f == 2 ? 8.0 * ldexp(1.0, -24) * (fabs(e->w) + fabs(e->dw)) : 0.0);
                if (fabs(out[i].t - t) > tmax_err)
                    tmax_err = fabs(out[i].t - t);
                if (err > emax)
                    emax = err;
                if (bound > bmax)
                    bmax = bound;
                if (err > bound) {
                    if (bad < 4)
                        ltt_report("  FAIL ray x %.9g y %.9g w %.9g dx %.9g dy %.9g dw %.9g: t %.9g "
                                   "(exact %.9g) w %.9g err %.3g bound %.3g nodes %d\n",
                                   e->x, e->y, e->w, e->dx, e->dy, e->dw, out[i].t, t, out[i].w, err,
                                   bound, out[i].nodes);
                    bad++;
                }
            }
            ltt_report("plane %ux%u %s: root is one plane (%u planes stored, %u levels); %zu "
                       "rays, %zu hits, max |w err| %.3g (bound %.3g = stored plane vs true %.3g "
                       "+ rounding), max |t err| %.3g, %zu misses with the true crossing within "
                       "the bound of a segment end, %zu FAILED; nodes visited max %d\n",
                       s.W, s.H, fmt_name[f], count_planes(&b, f), b.qt[f].levels, n, hits, emax,
                       bmax, eplane, tmax_err, near_end, bad, out[0].nodes);
            assert_int_equal(bad, 0);
        }
        built_free(&b);
        ss_scene_free(&s);
        free(rays);
        free(ex);
        free(out);
    }
}

/* Steps and spheres: every format against the reference (same model, exact inputs) and against
 * the analytic surface (the model's own error: pixel planes, lambda rules, merges, formats). */
static void run_scene(ss_scene_t *s, size_t n, uint64_t seed, double min_same)
{
    built_t b;
    ltt_rng_t g;
    lt_qt_ref_ray_t *rays = (lt_qt_ref_ray_t *)malloc(n * sizeof *rays);
    ss_res_t *out = (ss_res_t *)malloc(n * sizeof *out);
    lt_qt_ref_hit_t *refh = (lt_qt_ref_hit_t *)malloc(n * sizeof *refh);
    int f, coh;
    assert_non_null(rays);
    assert_non_null(out);
    assert_non_null(refh);
    assert_int_equal(ss_scene_sample(s), 0);
    build_all(s, NULL, &b);
    for (coh = 1; coh >= 0; coh--) {
        ltt_rng_seed(&g, seed + (uint64_t)coh);
        gen_rays(s, &g, n, coh, rays);
        for (f = 0; f < b.nfmt; f++) {
            cmp_t c;
            size_t i, an = 0, asame = 0, ahit = 0;
            double asq = 0.0, amax = 0.0;
            char name[64];
            compare(&b, f, rays, n, 0, &c, out, refh);
            (void)snprintf(name, sizeof name, "%s %ux%u %s", s->name, s->W, s->H,
                           coh ? "coherent" : "random");
            print_cmp(name, f, &c);
            /* against the analytic surface */
            for (i = 0; i < n; i++) {
                double ta = 0.0;
                int st = analytic(s, &rays[i], &ta);
                an++;
                if (st == out[i].status)
                    asame++;
                if (st == LT_QT_HIT && out[i].status == LT_QT_HIT) {
                    double wa = rays[i].w + ta * rays[i].dw, dz = fabs(wa / out[i].w - 1.0);
                    ahit++;
                    asq += dz * dz;
                    if (dz > amax)
                        amax = dz;
                }
            }
            ltt_report("%s %s: vs analytic surface: same status %.2f%%, depth on %zu common hits "
                       "RMSE %.3g max %.3g (relative)\n",
                       name, fmt_name[f], pct(asame, an), ahit, sqrt(per(asq, ahit)),
                       amax);
            if (f != 1)
                assert_true(pct(c.same_status, c.n) >= min_same);
        }
    }
    for (f = 0; f < b.nfmt; f++)
        ltt_report("%s %s: %u of %u nodes are planes, %zu bytes\n", s->name, fmt_name[f],
                   count_planes(&b, f), b.qt[f].layer_nodes, b.bytes[f]);
    built_free(&b);
    ss_scene_free(s);
    free(rays);
    free(out);
    free(refh);
}

static void test_steps(void **state)
{
    ss_scene_t s;
    (void)state;
    ss_scene_set(&s, "steps", 160, 96, 1, ss_w_steps);
    run_scene(&s, 4096, 7, 99.0);
}

static void test_spheres(void **state)
{
    ss_scene_t s;
    (void)state;
    ss_scene_set(&s, "spheres", 160, 120, 1, ss_w_spheres);
    s.p[0] = 140.0;                     /* focal length, pixels */
    s.p[1] = 0.12;                      /* background plane w = p1 + p2 x + p3 y */
    s.p[2] = 0.0002;
    s.p[3] = 0.0006;
    s.p[4] = 3;                         /* spheres (x, y, z, r) */
    s.p[5] = -0.8, s.p[6] = -0.3, s.p[7] = 3.0, s.p[8] = 0.9;
    s.p[9] = 0.9, s.p[10] = 0.2, s.p[11] = 4.0, s.p[12] = 1.2;
    s.p[13] = 0.1, s.p[14] = 0.9, s.p[15] = 2.2, s.p[16] = 0.35;
    run_scene(&s, 4096, 11, 99.0);
}

/* Checkerboard (every parent an AABB): the step bound on the worst input. Two layers (the second
 * all holes) so that lanes keep walking layer 0 after their first occlusion. */
static void test_checkerboard_bound(void **state)
{
    ss_scene_t s;
    built_t b;
    size_t n = 256, i, unk_small = 0, same = 0;
    lt_qt_ref_ray_t *rays, *ex;
    ss_res_t *out;
    lt_qt_ref_hit_t *refh;
    ltt_rng_t g;
    int f, maxn = 0;
    double sum = 0.0;
    uint32_t bound;
    (void)state;
    ss_scene_set(&s, "checker", 64, 64, 2, ss_w_checker);
    assert_int_equal(ss_scene_sample(&s), 0);
    build_all(&s, NULL, &b);
    rays = (lt_qt_ref_ray_t *)malloc(n * sizeof *rays);
    ex = (lt_qt_ref_ray_t *)malloc(n * sizeof *ex);
    out = (ss_res_t *)malloc(n * sizeof *out);
    refh = (lt_qt_ref_hit_t *)malloc(n * sizeof *refh);
    assert_non_null(rays);
    assert_non_null(ex);
    assert_non_null(out);
    assert_non_null(refh);
    ltt_rng_seed(&g, 5);
    /* long rays at w between the two depths: they overlap every box and never cross a plane */
    ss_gen_checker_rays(&g, n, rays);
    for (f = 0; f < b.nfmt; f++) {
        cmp_t c;
        bound = lt_qt_default_steps(&b.qt[f]);
        compare(&b, f, rays, n, 0, &c, out, refh);
        maxn = 0;
        sum = 0.0;
        for (i = 0; i < n; i++) {
            assert_int_not_equal(out[i].status, LT_QT_UNKNOWN);
            sum += out[i].nodes;
            if (out[i].nodes > maxn)
                maxn = out[i].nodes;
        }
        same = c.same_status;
        /* a small bound: lanes that need more steps stop as UNKNOWN, the others are unchanged */
        (void)trace_set(&b, f, rays, n, 64, out, ex);
        unk_small = 0;
        for (i = 0; i < n; i++)
            unk_small += out[i].status == LT_QT_UNKNOWN;
        ltt_report("checker 64x64 %s: %zu adversarial rays, same status as reference %zu, nodes "
                   "visited mean %.1f max %d (bound %u per layer: 8 (w + h) + 4 levels + 16); "
                   "with max_steps 64: %zu lanes UNKNOWN; %u of %u nodes are planes\n",
                   fmt_name[f], n, same, per(sum, n), maxn, bound, unk_small, count_planes(&b, f),
                   b.qt[f].layer_nodes * 2u);
        assert_int_equal(same, n);
        assert_true((uint32_t)maxn <= 2u * bound);
        assert_true(unk_small > 0);
    }
    built_free(&b);
    ss_scene_free(&s);
    free(rays);
    free(ex);
    free(out);
    free(refh);
}

/* Rays that are hard for a screen-space walk: grazing, parallel to the axes, a point (no screen
 * motion), leaving or entering the screen, reaching w = 0, and invalid ones. */
static void test_edge_rays(void **state)
{
    ss_scene_t s;
    built_t b;
    enum { N = SS_EDGE_N };
    lt_qt_ref_ray_t rays[N];
    ss_res_t out[N];
    lt_qt_ref_hit_t refh[N];
    ltt_rng_t g;
    size_t i;
    int f;
    (void)state;
    ss_scene_set(&s, "plane", 48, 40, 1, ss_w_plane);
    s.p[0] = 0.4;
    s.p[1] = 3e-4;
    s.p[2] = 2e-4;
    assert_int_equal(ss_scene_sample(&s), 0);
    build_all(&s, NULL, &b);
    ltt_rng_seed(&g, 21);
    ss_gen_edge_rays(&s, &g, rays);
    for (f = 0; f < b.nfmt; f++) {
        cmp_t c;
        size_t cls[12] = {0};
        compare(&b, f, rays, N, 0, &c, out, refh);
        for (i = 0; i < N; i++)
            if (out[i].status == refh[i].status)
                cls[i / 16]++;
        ltt_report("edge rays %s: same status as reference per class (of 16): grazing %zu, "
                   "x-parallel %zu, y-parallel %zu, point %zu, leaving %zu, entering %zu, w->0 %zu, "
                   "pixel corners %zu, starting behind %zu, t sub-range %zu, off-screen %zu, "
                   "long %zu; same hit %zu/%d\n",
                   fmt_name[f], cls[0], cls[1], cls[2], cls[3], cls[4], cls[5], cls[6], cls[7],
                   cls[8], cls[9], cls[10], cls[11], c.same_hit, N);
        for (i = 16; i < N; i++) {
            if (out[i].status != refh[i].status)
                ltt_report("  FAIL class %zu: x %.9g y %.9g w %.9g dx %.9g dy %.9g dw %.9g: status %d "
                           "t %.9g, reference %d t %.9g\n", i / 16, rays[i].x, rays[i].y, rays[i].w,
                           rays[i].dx, rays[i].dy, rays[i].dw, out[i].status, out[i].t,
                           refh[i].status, refh[i].t);
            assert_int_equal(out[i].status, refh[i].status);
        }
        if (f != 1)
            assert_true(cls[0] >= 14u);
        for (i = 16 * 10; i < 16 * 11; i++)
            assert_int_equal(out[i].status, LT_QT_MISS);
        for (i = 16 * 8; i < 16 * 9; i++)
            assert_int_equal(out[i].status, LT_QT_OCCLUDED);
    }
    /* invalid lanes */
    {
        lt_qray16_q30_t r;
        lt_qhit16_q30_t h;
        ss_bad_rays_q30(&r);
        assert_int_equal(lt_qt_trace16_q30(&b.qt[0], &r, 0xFFFF, 0, &h), LT_OK);
        for (i = 0; i < 5; i++)
            assert_int_equal(h.status.l[i], LT_QT_BADRAY);
        for (i = 5; i < 16; i++)
            assert_int_not_equal(h.status.l[i], LT_QT_BADRAY);
        assert_int_equal(lt_qt_trace16_q30(NULL, &r, 0xFFFF, 0, &h), LT_E_ARG);
        ltt_report("bad rays: |x| > 2^14 px, w < 0, tmin > tmax, tmax > 1, end beyond 2^14 -> "
                   "LT_QT_BADRAY per lane, other lanes traced; NULL quadtree -> LT_E_ARG\n");
    }
    built_free(&b);
    ss_scene_free(&s);
}

/* Depths from 1e-3 to 1e4 (w = 2^-10 / z from ~1 down to ~1e-7): relative depth error per band. */
static void test_depth_range(void **state)
{
    ss_scene_t s;
    built_t b;
    enum { PER = 64 };
    lt_qt_ref_ray_t rays[8 * PER], ex[8 * PER];
    ss_res_t out[8 * PER];
    ltt_rng_t g;
    int f, band;
    size_t i;
    (void)state;
    ss_scene_set(&s, "bands", 256, 16, 1, w_bands);
    assert_int_equal(ss_scene_sample(&s), 0);
    build_all(&s, NULL, &b);
    ltt_rng_seed(&g, 33);
    for (i = 0; i < 8 * PER; i++) {
        int bd = (int)(i / PER);
        double x = (bd + ltt_rng_uniform(&g, 0.15, 0.85)) * (s.W / 8.0);
        double y = ltt_rng_uniform(&g, 1, s.H - 1), wt = w_bands(&s, 0, x, y);
        double th = ltt_rng_uniform(&g, 0.3, 0.7);
        /* a short segment from w = 1.5 wt to 0.5 wt that crosses the band at parameter th */
        rays[i].dx = ltt_rng_uniform(&g, -2, 2);
        rays[i].dy = ltt_rng_uniform(&g, -2, 2);
        rays[i].x = x - th * rays[i].dx;
        rays[i].y = y - th * rays[i].dy;
        rays[i].w = wt * (1.0 + th);
        rays[i].dw = -wt;
        rays[i].tmin = 0.0;
        rays[i].tmax = 1.0;
    }
    for (f = 0; f < b.nfmt; f++) {
        double worst[8] = {0};
        size_t hits = 0;
        (void)trace_set(&b, f, rays, 8 * PER, 0, out, ex);
        for (i = 0; i < 8 * PER; i++) {
            double ta = 0.0, za, zq;
            int st = analytic(&s, &ex[i], &ta);
            if (st != LT_QT_HIT || out[i].status != LT_QT_HIT)
                continue;
            hits++;
            za = 1.0 / (ex[i].w + ta * ex[i].dw);
            zq = 1.0 / out[i].w;
            if (fabs(zq / za - 1.0) > worst[i / PER])
                worst[i / PER] = fabs(zq / za - 1.0);
            if (fabs(zq / za - 1.0) > 0.1 && f == 0)
                ltt_report("  BIG x %.9g y %.9g w %.9g dx %.9g dy %.9g dw %.9g: t %.9g (analytic %.9g) "
                           "w %.9g nodes %d\n", ex[i].x, ex[i].y, ex[i].w, ex[i].dx, ex[i].dy,
                           ex[i].dw, out[i].t, ta, out[i].w, out[i].nodes);
        }
        ltt_report("depth range %s: %zu/%d hits; max relative depth error per band z = 1e-3 .. "
                   "1e4:",
                   fmt_name[f], hits, 8 * PER);
        for (band = 0; band < 8; band++)
            ltt_report(" %.2g", worst[band]);
        /* bound: half a raw unit of the input and of the stored C, relative to w (s1.30), or the
         * 32-bit format's 12-bit mantissa, or float's 2^-22 */
        ltt_report(" (bound per band: ");
        for (band = 0; band < 8; band++) {
            double wb = ldexp(1.0, -10) / pow(10.0, -3.0 + band);
            double bd = f == 0 ? 4.0 / (wb * Q30) + ldexp(1.0, -21)
                               : (f == 1 ? 4.0 / (wb * Q30) + ldexp(1.0, -9) : ldexp(1.0, -19));
            ltt_report(" %.2g", bd);
            assert_true(worst[band] <= bd);
        }
        ltt_report(")\n");
        assert_true(hits >= (size_t)(8 * PER * 9 / 10));
    }
    built_free(&b);
    ss_scene_free(&s);
}

/* 1x1, 1xN, Nx1 and non-power-of-two images against the reference. */
static void test_small_images(void **state)
{
    static const uint32_t dims[][2] = {{1, 1}, {1, 9}, {13, 1}, {37, 23}, {5, 3}, {2, 2}, {65, 33}};
    size_t di;
    int f;
    (void)state;
    for (di = 0; di < sizeof dims / sizeof dims[0]; di++) {
        ss_scene_t s;
        built_t b;
        ltt_rng_t g;
        size_t n = 256;
        lt_qt_ref_ray_t rays[256];
        ss_res_t out[256];
        lt_qt_ref_hit_t refh[256];
        ss_scene_set(&s, "wave", dims[di][0], dims[di][1], 1, ss_w_wave);
        s.p[0] = 0.002;
        s.p[1] = 0.3 * (double)di;
        s.p[2] = 0.7;
        assert_int_equal(ss_scene_sample(&s), 0);
        build_all(&s, NULL, &b);
        ltt_rng_seed(&g, 40 + di);
        gen_rays(&s, &g, n, 0, rays);
        for (f = 0; f < b.nfmt; f++) {
            cmp_t c;
            compare(&b, f, rays, n, 0, &c, out, refh);
            ltt_report("image %ux%u (%u levels) %s: %zu rays, same status %.1f%%, same hit %.1f%%, "
                       "nodes mean %.2f max %d\n",
                       s.W, s.H, b.qt[f].levels, fmt_name[f], c.n, pct(c.same_status, c.n),
                       pct(c.same_hit, c.n), per(c.sum_nodes, c.n), c.max_nodes);
            if (f != 1)
                assert_true(c.same_status * 100 >= c.n * 98);
        }
        built_free(&b);
        ss_scene_free(&s);
    }
}

/* NaN, +-inf and 0 depths become holes (w = 0, background at infinity) through the host
 * conversion; rays over holes miss, rays that meet valid pixels agree with the reference. */
static void test_holes(void **state)
{
    uint32_t W = 64, H = 48;
    size_t n = (size_t)W * H, holes, hc[2], nrays = 512, i, over_holes = 0, miss_holes = 0;
    float *z = (float *)malloc(n * sizeof *z);
    ss_scene_t s;
    built_t b;
    int e, f;
    ltt_rng_t g;
    lt_qt_ref_ray_t *rays = (lt_qt_ref_ray_t *)malloc(nrays * sizeof *rays);
    ss_res_t *out = (ss_res_t *)malloc(nrays * sizeof *out);
    lt_qt_ref_hit_t *refh = (lt_qt_ref_hit_t *)malloc(nrays * sizeof *refh);
    (void)state;
    assert_non_null(z);
    assert_non_null(rays);
    assert_non_null(out);
    assert_non_null(refh);
    /* a disc of depth 2..3 over a background of holes of every kind */
    ss_holes_depth(z, W, H);
    memset(&s, 0, sizeof s);
    s.name = "holes";
    s.W = W;
    s.H = H;
    /* not sampled: the buffers come from the conversion (hole counts of both paths) */
    assert_int_equal(ss_scene_from_depth(&s, z, hc), 0);
    e = s.zexp;
    holes = hc[0];
    assert_int_equal(hc[1], holes);
    build_all(&s, NULL, &b);
    ltt_rng_seed(&g, 51);
    ss_gen_holes_rays(&g, W, H, nrays, rays);
    for (f = 0; f < b.nfmt; f++) {
        cmp_t c;
        compare(&b, f, rays, nrays, 0, &c, out, refh);
        over_holes = miss_holes = 0;
        for (i = 0; i < nrays; i++) {
            /* rays that stay outside the disc see only holes */
            int k, inside = 0;
            for (k = 0; k <= 64; k++) {
                double t = k / 64.0, px = rays[i].x + t * rays[i].dx, py = rays[i].y + t * rays[i].dy;
                if ((px - 32) * (px - 32) + (py - 24) * (py - 24) < 20.0 * 20.0)
                    inside = 1;
            }
            if (!inside) {
                over_holes++;
                miss_holes += out[i].status == LT_QT_MISS;
            }
        }
        ltt_report("holes %s: %zu of %zu pixels holes (NaN, +-inf, 0, < 0; z_ref = 2^%d); %zu rays, "
                   "same status as reference %.1f%%; %zu rays only over holes, %zu of them miss\n",
                   fmt_name[f], holes, n, e, nrays, pct(c.same_status, c.n), over_holes,
                   miss_holes);
        assert_int_equal(over_holes, miss_holes);
        if (f != 1)
            assert_true(c.same_status * 100 >= c.n * 99);
    }
    assert_true(holes == n - 1018 || holes > n / 2);
    built_free(&b);
    ss_scene_free(&s);
    free(z);
    free(rays);
    free(out);
    free(refh);
}

/* Two layers: a ray that passes behind the card in layer 0 finds the background in layer 1. */
static void test_two_layers(void **state)
{
    ss_scene_t s;
    built_t b;
    size_t n = 2048, i;
    lt_qt_ref_ray_t *rays = (lt_qt_ref_ray_t *)malloc(n * sizeof *rays);
    ss_res_t *out = (ss_res_t *)malloc(n * sizeof *out);
    lt_qt_ref_hit_t *refh = (lt_qt_ref_hit_t *)malloc(n * sizeof *refh);
    ltt_rng_t g;
    int f;
    (void)state;
    assert_non_null(rays);
    assert_non_null(out);
    assert_non_null(refh);
    ss_scene_set(&s, "card", 96, 64, 2, ss_w_card);
    s.p[0] = 30, s.p[1] = 60, s.p[2] = 16, s.p[3] = 48;
    assert_int_equal(ss_scene_sample(&s), 0);
    build_all(&s, NULL, &b);
    /* ray 0: from the left in front of the background, under the card's w, descending onto the
     * background behind the card (x 45, y 32) */
    {
        double xh = 45.0, yh = 32.0, wh = 0.3 + 0.0005 * xh + 0.0002 * yh;
        rays[0].x = 10.0;
        rays[0].y = 32.0;
        rays[0].w = 0.5;
        rays[0].dx = (xh - 10.0) / 0.8;
        rays[0].dy = 0.0;
        rays[0].dw = (wh - 0.5) / 0.8;
        rays[0].tmin = 0.0;
        rays[0].tmax = 1.0;
    }
    ltt_rng_seed(&g, 61);
    gen_rays(&s, &g, n - 16, 1, rays + 16);
    for (i = 1; i < 16; i++) {
        rays[i] = rays[0];
        rays[i].y = 20.0 + 1.7 * (double)i;
    }
    for (f = 0; f < b.nfmt; f++) {
        cmp_t c;
        size_t l1 = 0, occ = 0;
        compare(&b, f, rays, n, 0, &c, out, refh);
        for (i = 0; i < n; i++) {
            l1 += out[i].status == LT_QT_HIT && out[i].layer == 1;
            occ += out[i].status == LT_QT_OCCLUDED;
        }
        ltt_report("two layers %s: ray behind the card -> status %d layer %d t %.6f (expected hit "
                   "layer 1 at t 0.8); %zu rays, same status as reference %.2f%%, same hit %.2f%%, "
                   "%zu hits in layer 1, %zu occluded behind both\n",
                   fmt_name[f], out[0].status, out[0].layer, out[0].t, n,
                   pct(c.same_status, c.n), pct(c.same_hit, c.n), l1, occ);
        print_cmp("two layers", f, &c);
        assert_int_equal(out[0].status, LT_QT_HIT);
        assert_int_equal(out[0].layer, 1);
        assert_true(fabs(out[0].t - 0.8) < 1e-3);
        if (f != 1)
            assert_true(c.same_status * 100 >= c.n * 99);
    }
    built_free(&b);
    ss_scene_free(&s);
    free(rays);
    free(out);
    free(refh);
}

/* Mask patterns: inactive lanes are not written (poisoned hit struct), active lanes give the same
 * result as in a full packet. */
static void test_lanes(void **state)
{
    ss_scene_t s;
    built_t b;
    uint16_t masks[LTT_MASK_COUNT];
    unsigned nm, mi, i, checked = 0;
    lt_qray16_q30_t r;
    lt_qhit16_q30_t full, h;
    ltt_rng_t g;
    lt_qt_ref_ray_t rays[16];
    (void)state;
    ss_scene_set(&s, "spheres", 64, 48, 1, ss_w_steps);
    assert_int_equal(ss_scene_sample(&s), 0);
    build_all(&s, NULL, &b);
    ltt_rng_seed(&g, 71);
    gen_rays(&s, &g, 16, 0, rays);
    memset(&r, 0, sizeof r);
    for (i = 0; i < 16; i++) {
        r.x.l[i] = lt_q16_from_double_sat(rays[i].x);
        r.y.l[i] = lt_q16_from_double_sat(rays[i].y);
        r.w.l[i] = lt_q30_from_double_sat(rays[i].w);
        r.dx.l[i] = lt_q16_from_double_sat(rays[i].dx);
        r.dy.l[i] = lt_q16_from_double_sat(rays[i].dy);
        r.dw.l[i] = lt_q30_from_double_sat(rays[i].dw);
        r.tmax.l[i] = 1 << 30;
    }
    assert_int_equal(lt_qt_trace16_q30(&b.qt[0], &r, 0xFFFF, 0, &full), LT_OK);
    nm = ltt_masks(masks, 72);
    for (mi = 0; mi < nm; mi++) {
        ltt_poison(&h, sizeof h);
        assert_int_equal(lt_qt_trace16_q30(&b.qt[1 - 1], &r, masks[mi], 0, &h), LT_OK);
        for (i = 0; i < 16; i++) {
            if (LTT_ON(masks[mi], i)) {
                assert_int_equal(h.status.l[i], full.status.l[i]);
                assert_int_equal(h.t.l[i], full.t.l[i]);
                assert_int_equal(h.w.l[i], full.w.l[i]);
                assert_int_equal(h.nodes.l[i], full.nodes.l[i]);
            } else {
                ss_assert_untouched_q30(&h, i);
            }
            checked++;
        }
    }
    ltt_report("lanes: %u mask patterns (none, all, alternating, single, random) x 16 lanes: "
               "active lanes = full-packet results, inactive lanes untouched (%u lane checks)\n",
               nm, checked);
    built_free(&b);
    ss_scene_free(&s);
}

#if LT_COST_MODE == LT_COST_SIM
/* Sim only: the events and lane utilisation the cost hook saw for one traced scene. */
static void test_sim_counts(void **state)
{
    ss_scene_t s;
    built_t b;
    size_t n = 1024;
    lt_qt_ref_ray_t *rays = (lt_qt_ref_ray_t *)malloc(n * sizeof *rays);
    lt_qt_ref_ray_t *ex = (lt_qt_ref_ray_t *)malloc(n * sizeof *ex);
    ss_res_t *out = (ss_res_t *)malloc(n * sizeof *out);
    lt_sim_totals_t *t = (lt_sim_totals_t *)malloc(sizeof *t);
    ltt_rng_t g;
    int f;
    lt_diag_t diag;
    (void)state;
    assert_non_null(t);
    assert_int_equal(lt_sim_init(lt_sim_machine_find("lrb16"), NULL, NULL, &diag), 0);
    g_single_check = 0;
    ss_scene_set(&s, "steps", 160, 96, 1, ss_w_steps);
    assert_int_equal(ss_scene_sample(&s), 0);
    ltt_rng_seed(&g, 81);
    gen_rays(&s, &g, n, 1, rays);
    for (f = 0; f < (LT_CFG_FLOAT32 ? 3 : 2); f++) {
        uint64_t on = 0, ops = 0, nodes = 0, aabb = 0, aabbr = 0, vdiv = 0;
        int ph;
        build_all(&s, NULL, &b);
        /* count one build of this format and its traversal only */
        lt_sim_reset();
        {
            lt_qt_desc_t d = {s.W, s.H, 1, (uint32_t)f};
            size_t need = b.bytes[f];
            lt_qt_t q;
            if (f < 2)
                assert_int_equal(lt_qt_build_q30(&q, &d, NULL, s.wq, b.arena[f], &need), LT_OK);
#if LT_CFG_FLOAT32
            else
                assert_int_equal(lt_qt_build_f32(&q, &d, NULL, s.wf, b.arena[f], &need), LT_OK);
#endif
        }
        (void)trace_set(&b, f, rays, n, 0, out, ex);
        lt_sim_totals(t);
        for (ph = 0; ph < LT_PH__COUNT; ph++) {
            on += t->ctr[ph][LT_OP__COUNT + LT_EV_LANES_ON];
            ops += t->ctr[ph][LT_OP__COUNT + LT_EV_LANE_OPS];
        }
        nodes = t->ctr[LT_PH_TRAVERSE][LT_OP__COUNT + LT_EV_NODES];
        aabb = t->ctr[LT_PH_TRAVERSE][LT_OP__COUNT + LT_EV_AABB];
        aabbr = t->ctr[LT_PH_TRAVERSE][LT_OP__COUNT + LT_EV_AABB_RAYS];
        vdiv = t->ctr[LT_PH_TRAVERSE][LT_OP_VDIV];
        ltt_report("sim lrb16 %s (steps 160x96, coherent): %zu rays in %zu packets: NODES %llu "
                   "packet steps, AABB %llu packet box tests (%llu ray-box), TRAVERSE VDIV %llu; "
                   "masked-op lane utilisation %.1f%%; cycles BUILD %llu TRAVERSE %llu SETUP "
                   "%llu\n",
                   fmt_name[f], n, n / 16, (unsigned long long)nodes, (unsigned long long)aabb,
                   (unsigned long long)aabbr, (unsigned long long)vdiv,
                   ops ? 100.0 * (double)on / (16.0 * (double)ops) : 0.0,
                   (unsigned long long)t->cycles[LT_PH_BUILD],
                   (unsigned long long)t->cycles[LT_PH_TRAVERSE],
                   (unsigned long long)t->cycles[LT_PH_SETUP]);
        assert_true(nodes > 0);
        built_free(&b);
    }
    lt_sim_shutdown();
    g_single_check = 1;
    ss_scene_free(&s);
    free(rays);
    free(ex);
    free(out);
    free(t);
}
#endif

/* The single-ray walk (lt_qt_trace1_q30) against the packet walk: every fixed-point packet of the
 * tests before this one (trace_set), then rays the generators do not make: invalid rays (end
 * points past 2^14 px, w < 0, tmin > tmax, tmax > 1), point rays, axis-parallel rays inside and
 * outside the image, rays leaving the image at once, a step bound of 1 to 3, and masks with
 * inactive lanes (untouched, as in the packet walk). Whole hit records are compared. */
static void test_single_rays(void **state)
{
    ss_scene_t s;
    built_t b;
    ltt_rng_t g;
    size_t before = g_single_lanes;
    int f, rep, i;
    uint32_t steps;
    (void)state;
    ss_scene_set(&s, "steps", 37, 29, 2, ss_w_steps);
    assert_int_equal(ss_scene_sample(&s), 0);
    build_all(&s, NULL, &b);
    ltt_rng_seed(&g, 131);
    for (f = 0; f < 2; f++) {
        for (rep = 0; rep < 64; rep++) {
            lt_qray16_q30_t r;
            lt_qhit16_q30_t h;
            lt_mask16_t k = rep % 4 == 3 ? (lt_mask16_t)ltt_rng_u32(&g) : 0xFFFF;
            memset(&r, 0, sizeof r);
            for (i = 0; i < 16; i++) {
                int kind = (int)(ltt_rng_u32(&g) % 12u);
                int32_t px = (int32_t)(ltt_rng_u32(&g) % (s.W * 65536u));
                int32_t py = (int32_t)(ltt_rng_u32(&g) % (s.H * 65536u));
                r.x.l[i] = px;
                r.y.l[i] = py;
                r.w.l[i] = (int32_t)(ltt_rng_u32(&g) >> 2);
                r.dx.l[i] = (int32_t)(ltt_rng_u32(&g) % (80u * 65536u)) - 40 * 65536;
                r.dy.l[i] = (int32_t)(ltt_rng_u32(&g) % (80u * 65536u)) - 40 * 65536;
                r.dw.l[i] = (int32_t)ltt_rng_u32(&g) >> 3;
                r.tmin.l[i] = 0;
                r.tmax.l[i] = LT_Q30_ONE;
                switch (kind) {
                case 0: r.x.l[i] = (1 << 30) + 5; break;            /* past 2^14 px */
                case 1: r.w.l[i] = -1; break;                        /* w < 0 */
                case 2: r.tmin.l[i] = 1000; r.tmax.l[i] = 999; break; /* tmin > tmax */
                case 3: r.tmax.l[i] = LT_Q30_ONE + 1; break;         /* tmax > 1 */
                case 4: r.dx.l[i] = r.dy.l[i] = 0; break;            /* point ray */
                case 5: r.dx.l[i] = 0; break;                        /* parallel to y */
                case 6: r.dy.l[i] = 0; break;                        /* parallel to x */
                case 7: r.dx.l[i] = 0; r.x.l[i] = -65536; break;     /* parallel, outside */
                case 8: r.x.l[i] = -3 * 65536; r.dx.l[i] = -65536; break; /* leaves at once */
                case 9: r.dw.l[i] = -(r.w.l[i] / 2) - 1; break;      /* reaches w = 0 */
                default: break;
                }
            }
            steps = rep % 8 == 5 ? 1u + (uint32_t)(rep % 3) : 0u;
            memset(&h, 0x5A, sizeof h);
            assert_int_equal(lt_qt_trace16_q30(&b.qt[f], &r, k, steps, &h), LT_OK);
            check_single_q30(&b.qt[f], &r, k, steps, &h);
        }
    }
    {
        lt_qray16_q30_t r;
        lt_qhit16_q30_t h;
        memset(&r, 0, sizeof r);
        assert_int_equal(lt_qt_trace1_q30(NULL, &r, 1, 0, &h), LT_E_ARG);
        assert_int_equal(lt_qt_trace1_q30(&b.qt[0], NULL, 1, 0, &h), LT_E_ARG);
        assert_int_equal(lt_qt_trace1_q30(&b.qt[0], &r, 1, 0, NULL), LT_E_ARG);
#if LT_CFG_FLOAT32
        assert_int_equal(lt_qt_trace1_q30(&b.qt[2], &r, 1, 0, &h), LT_E_ARG);
#endif
    }
    ltt_report("single rays: lt_qt_trace1_q30 = lt_qt_trace16_q30 bit for bit (whole hit records, "
               "inactive lanes untouched) on %zu packets, %zu lanes, %zu node visits (%zu lanes "
               "from the tests above: steps, spheres, bands, holes, two layers, the Beachball EXR "
               "when present; the rest crafted: invalid, point, parallel, leaving, w = 0, step "
               "bounds 1-3, partial masks)\n",
               g_single_packets, g_single_lanes, g_single_nodes, before);
    built_free(&b);
    ss_scene_free(&s);
}

/* Optional: the shared beachball depth buffer (skipped when absent, failed when CI=true). */
static void test_exr_beachball(void **state)
{
    const char *path = "../shared/depth/beachball_singlepart.0001.exr";
    lt_exr_depth_t d;
    ss_scene_t s;
    built_t b;
    size_t nr = 2048;
    int e, f;
    ltt_rng_t g;
    lt_qt_ref_ray_t *rays;
    ss_res_t *out;
    lt_qt_ref_hit_t *refh;
    (void)state;
    if (!ss_shared_depth(path, &d))
        return;
    memset(&s, 0, sizeof s);
    s.name = "beachball";
    s.W = (uint32_t)d.width;
    s.H = (uint32_t)d.height;
    assert_int_equal(ss_scene_from_depth(&s, d.z, NULL), 0);
    e = s.zexp;
    build_all(&s, NULL, &b);
    rays = (lt_qt_ref_ray_t *)malloc(nr * sizeof *rays);
    out = (ss_res_t *)malloc(nr * sizeof *out);
    refh = (lt_qt_ref_hit_t *)malloc(nr * sizeof *refh);
    assert_non_null(rays);
    assert_non_null(out);
    assert_non_null(refh);
    ltt_rng_seed(&g, 91);
    ss_gen_buffer_rays(&s, &g, nr, rays);
    for (f = 0; f < b.nfmt; f++) {
        cmp_t c;
        char name[96];
        compare(&b, f, rays, nr, 0, &c, out, refh);
        (void)snprintf(name, sizeof name, "beachball %ux%u (z_ref 2^%d)", s.W, s.H, e);
        print_cmp(name, f, &c);
        ltt_report("beachball %s: %u of %u nodes are planes, %zu bytes\n", fmt_name[f],
                   count_planes(&b, f), b.qt[f].layer_nodes, b.bytes[f]);
        if (f != 1)
            assert_true(c.same_status * 100 >= c.n * 97);
    }
    built_free(&b);
    ss_scene_free(&s);
    lt_exr_depth_free(&d);
    free(rays);
    free(out);
    free(refh);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_size_query),
        cmocka_unit_test(test_plane_one_node),
        cmocka_unit_test(test_steps),
        cmocka_unit_test(test_spheres),
        cmocka_unit_test(test_checkerboard_bound),
        cmocka_unit_test(test_edge_rays),
        cmocka_unit_test(test_depth_range),
        cmocka_unit_test(test_small_images),
        cmocka_unit_test(test_holes),
        cmocka_unit_test(test_two_layers),
        cmocka_unit_test(test_lanes),
#if LT_COST_MODE == LT_COST_SIM
        cmocka_unit_test(test_sim_counts),
#endif
        cmocka_unit_test(test_exr_beachball),
        cmocka_unit_test(test_single_rays),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
