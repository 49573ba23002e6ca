/* test_reproj.c - cmocka tests of reprojection ray generation (lt_reproj.h) and view synthesis
 * (host/render/lt_reproject.h), docs/reproject.md:
 *   - the shared 64 x 64 workload hash (tests/vectors/lt_reproj_tile.h; the firmware prints the
 *     same line) and the stored mapping reproduced by lt_reproj_setup;
 *   - an identity camera reprojects every pixel onto itself (x, y exact, w from w_near to 0);
 *   - a pure translation over a fronto-parallel plane hits at the analytic disparity f b / Z;
 *   - segments against an independent double-precision reference of the camera math (clip
 *     interval in target depth, end points, distance of the end points from the true line);
 *   - near-plane clipping, rays leaving the screen, rays pointing away, bad parameters;
 *   - lt_rp_run end to end and the background-biased inpainting.
 * Each test prints what it checked: cases, max error and its bound. Builds: host, sim, asan.
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

#include "lt/lt_reproj.h"
#include "render/lt_qt_ref.h"
#include "render/lt_reproject.h"
#include "lt_reproj_tile.h"
#include "lt_test_util.h"
#if LT_COST_MODE == LT_COST_SIM
#include "lt_sim.h"
#endif

#define Q30 1073741824.0
#define Q16 65536.0
#define PI 3.14159265358979323846

static double urand(ltt_rng_t *r, double lo, double hi)
{
    double u = (double)(ltt_rng_u64(r) >> 11) * (1.0 / 9007199254740992.0);
    return lo + (hi - lo) * u;
}

static void cam_init(lt_reproj_cam_t *c, double f, uint32_t w, uint32_t h)
{
    int i, j;
    memset(c, 0, sizeof *c);
    c->fx = c->fy = f;
    c->cx = 0.5 * w;
    c->cy = 0.5 * h;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            c->r[i][j] = i == j ? 1.0 : 0.0;
    c->width = w;
    c->height = h;
}

/* A random rotation from yaw, pitch, roll in degrees (lt_rp_cam_move's convention). */
static void cam_rotate(lt_reproj_cam_t *c, double yaw, double pitch, double roll)
{
    double mv[3] = {0, 0, 0}, rot[3] = {yaw, pitch, roll};
    lt_reproj_cam_t d;
    lt_rp_cam_move(c, mv, rot, &d);
    *c = d;
}

/* ---- the shared workload --------------------------------------------------------------------- */

static void test_tile_hash(void **state)
{
    uint32_t counts[6], h;
    int same;
    (void)state;
    h = ltrt_hash(counts);
    same = ltrt_setup_matches();
    /* the same line as tests/fw/fw_reproj.c prints */
    printf("reproj fw tile hash: 0x%08x setup %s\n", h, same ? "exact" : "differs");
    printf("reproj tile: 256 tiles, %u lanes kept of 4096; hit %u, miss %u, occluded %u, "
           "unknown %u, badray %u\n",
           counts[5], counts[LT_QT_HIT], counts[LT_QT_MISS], counts[LT_QT_OCCLUDED],
           counts[LT_QT_UNKNOWN], counts[LT_QT_BADRAY]);
    assert_true(h != 0);
    assert_true(same);
    assert_int_equal(counts[LT_QT_BADRAY], 0);
    assert_true(counts[LT_QT_HIT] > 3000);
    assert_int_equal(counts[LT_QT_HIT] + counts[LT_QT_MISS] + counts[LT_QT_OCCLUDED] +
                         counts[LT_QT_UNKNOWN], counts[5]);
}

/* ---- identity --------------------------------------------------------------------------------- */

static void test_identity(void **state)
{
    static const uint32_t dims[4][2] = {{64, 64}, {37, 23}, {100, 60}, {1, 9}};
    ltt_rng_t rng;
    uint64_t cases = 0, lanes_f = 0;
    int32_t maxq = 0, maxw = 0;
    double maxf = 0.0;
    int d, trial;
    (void)state;
    ltt_rng_seed(&rng, 11);
    for (d = 0; d < 4; d++) {
        for (trial = 0; trial < 6; trial++) {
            lt_reproj_cam_t c;
            lt_reproj_opts_t o = {0.5, 0.0, 0.0, 0.0};
            lt_reproj_q30_t mq;
            lt_reproj_f32_t mf;
            uint32_t W = dims[d][0], H = dims[d][1], tx, ty;
            cam_init(&c, urand(&rng, 10.0, 400.0), W, H);
            c.fy = c.fx * urand(&rng, 0.8, 1.25);
            c.cx = urand(&rng, 0.0, (double)W);
            c.cy = urand(&rng, 0.0, (double)H);
            if (trial > 0)
                cam_rotate(&c, urand(&rng, -40, 40), urand(&rng, -40, 40), urand(&rng, -40, 40));
            c.c[0] = urand(&rng, -5, 5);
            c.c[1] = urand(&rng, -5, 5);
            c.c[2] = urand(&rng, -5, 5);
            assert_int_equal(lt_reproj_setup(&c, &c, &o, &mq, &mf), LT_OK);
            for (ty = 0; ty < H; ty += 4)
                for (tx = 0; tx < W; tx += 4) {
                    lt_qray16_q30_t r;
                    lt_qray16_f32_t rf;
                    lt_mask16_t k = 0xFFFF, kf = 0xFFFF;
                    int i;
                    assert_int_equal(lt_reproj_rays16_q30(&mq, tx, ty, &r, &k), LT_OK);
                    assert_int_equal(lt_reproj_rays16_f32(&mf, tx, ty, &rf, &kf), LT_OK);
                    for (i = 0; i < 16; i++) {
                        uint32_t u = tx + (uint32_t)(i & 3), v = ty + (uint32_t)(i >> 2);
                        int on = u < W && v < H;
                        int32_t ex = (int32_t)(2 * u + 1) * 32768, ey = (int32_t)(2 * v + 1) * 32768;
                        int32_t e;
                        assert_int_equal(LT__ON(k, i), (unsigned)on);
                        assert_int_equal(LT__ON(kf, i), (unsigned)on);
                        if (!on)
                            continue;
                        cases++;
                        /* x, y: the pixel centre at both ends (dx = dy = 0): exact */
                        e = abs(r.x.l[i] - ex);
                        e = e > abs(r.y.l[i] - ey) ? e : abs(r.y.l[i] - ey);
                        e = e > abs(r.dx.l[i]) ? e : abs(r.dx.l[i]);
                        e = e > abs(r.dy.l[i]) ? e : abs(r.dy.l[i]);
                        if (e > maxq)
                            maxq = e;
                        /* w: the far end exactly 0; the near end w_near less the inward rounding
                         * of the clip parameter */
                        if (r.w.l[i] + r.dw.l[i] != 0)
                            maxq = 1 << 20;
                        if (mq.w_near - r.w.l[i] > maxw)
                            maxw = mq.w_near - r.w.l[i];
                        if (r.w.l[i] > mq.w_near)
                            maxw = 1 << 30;
                        {
                            double ef = fabs((double)rf.x.l[i] - (u + 0.5)) / (u + 0.5);
                            ef = fmax(ef, fabs((double)rf.y.l[i] - (v + 0.5)) / (v + 0.5));
                            ef = fmax(ef, fabs((double)rf.dx.l[i]) / (u + 0.5));
                            ef = fmax(ef, fabs((double)rf.dy.l[i]) / (v + 0.5));
                            ef = fmax(ef, fabs((double)rf.w.l[i] - 1.0));
                            ef = fmax(ef, fabs((double)(rf.w.l[i] + rf.dw.l[i])));
                            maxf = fmax(maxf, ef);
                            lanes_f++;
                        }
                    }
                }
        }
    }
    printf("reproj identity: %llu pixels (24 cameras, 4 sizes, rotated and moved); s1.30 x, y, dx, "
           "dy, far w max |err| %d ulp (bound 0: exact pixel centres, dx = dy = 0, w -> 0), near "
           "w_near - w max %d ulp (bound 64: inward clip rounding); float32 max relative err %.3g "
           "(bound 2^-20 = %.3g)\n",
           (unsigned long long)cases, maxq, maxw, maxf, ldexp(1.0, -20));
    assert_int_equal(maxq, 0);
    assert_true(maxw <= 64);
    assert_true(maxf <= ldexp(1.0, -20));
    assert_int_equal(lanes_f, cases);
}

/* ---- translation over a fronto-parallel plane ------------------------------------------------- */

static void test_translation_disparity(void **state)
{
    static const lt_qt_enc_t encs[3] = {LT_QT_N64, LT_QT_N32, LT_QT_F32};
    static const char *const names[3] = {"n64", "n32", "f32"};
    /* bounds on |x_s - (u + 1/2 + f b / Z)| in pixels: the hit's t error over |dx| (n64 and f32:
     * w within ~2^-28 of the plane, n32: its 2^-12 relative plane error) */
    static const double bound[3] = {1e-3, 0.05, 1e-3};
    const uint32_t W = 96, H = 64;
    const double f = 80.0, Z = 6.0, zref = 4.0;
    int e, bi;
    (void)state;
    for (e = 0; e < 3; e++) {
        for (bi = 0; bi < 3; bi++) {
            const double b = bi == 0 ? 0.3 : (bi == 1 ? -0.45 : 0.05);
            lt_reproj_cam_t s, t;
            lt_reproj_opts_t o = {zref, 0.0, 0.0, 0.0};
            lt_reproj_q30_t mq;
            lt_reproj_f32_t mf;
            lt_qt_desc_t qd = {96, 64, 1, 0};
            lt_qt_t qt;
            size_t bytes;
            void *arena;
            lt_q30_t *wq = malloc(W * H * sizeof *wq);
            float *wf = malloc(W * H * sizeof *wf);
            uint32_t tx, ty, hits = 0, expect = 0, border = 0;
            double maxe = 0.0, maxz = 0.0, disp = f * b / Z;
            size_t i;
            cam_init(&s, f, W, H);
            t = s;
            t.c[0] = b;
            qd.enc = (uint32_t)encs[e];
            assert_int_equal(lt_qt_size(&qd, &bytes), LT_OK);
            arena = malloc(bytes);
            for (i = 0; i < (size_t)W * H; i++) {
                wq[i] = (lt_q30_t)lrint(zref / Z * Q30);
                wf[i] = (float)(zref / Z);
            }
            assert_int_equal(lt_reproj_setup(&s, &t, &o, &mq, &mf), LT_OK);
            if (encs[e] == LT_QT_F32)
                assert_int_equal(lt_qt_build_f32(&qt, &qd, NULL, wf, arena, &bytes), LT_OK);
            else
                assert_int_equal(lt_qt_build_q30(&qt, &qd, NULL, wq, arena, &bytes), LT_OK);
            for (ty = 0; ty < H; ty += 4)
                for (tx = 0; tx < W; tx += 4) {
                    lt_mask16_t k = 0xFFFF;
                    lt_qray16_q30_t r;
                    lt_qray16_f32_t rf;
                    lt_qhit16_q30_t hq;
                    lt_qhit16_f32_t hf;
                    int l;
                    if (encs[e] == LT_QT_F32) {
                        assert_int_equal(lt_reproj_rays16_f32(&mf, tx, ty, &rf, &k), LT_OK);
                        assert_int_equal(lt_qt_trace16_f32(&qt, &rf, k, 0, &hf), LT_OK);
                    } else {
                        assert_int_equal(lt_reproj_rays16_q30(&mq, tx, ty, &r, &k), LT_OK);
                        assert_int_equal(lt_qt_trace16_q30(&qt, &r, k, 0, &hq), LT_OK);
                    }
                    for (l = 0; l < 16; l++) {
                        uint32_t u = tx + (uint32_t)(l & 3), v = ty + (uint32_t)(l >> 2);
                        double xa = u + 0.5 + disp, xs, ys, w, err;
                        int in = xa > 0.0 && xa < (double)W, st;
                        if (u >= W || v >= H)
                            continue;
                        expect += (uint32_t)in;
                        if (!LT__ON(k, l)) {
                            /* never entered the source view: only possible off screen */
                            if (in && xa > 1.0 && xa < W - 1.0)
                                fail_msg("pixel (%u, %u) cleared but its disparity lands on screen",
                                         u, v);
                            continue;
                        }
                        if (encs[e] == LT_QT_F32) {
                            st = hf.status.l[l];
                            xs = (double)rf.x.l[l] + (double)hf.t.l[l] * (double)rf.dx.l[l];
                            ys = (double)rf.y.l[l] + (double)hf.t.l[l] * (double)rf.dy.l[l];
                            w = (double)hf.w.l[l];
                        } else {
                            double tt = hq.t.l[l] / Q30;
                            st = hq.status.l[l];
                            xs = (r.x.l[l] + tt * r.dx.l[l]) / Q16;
                            ys = (r.y.l[l] + tt * r.dy.l[l]) / Q16;
                            w = hq.w.l[l] / Q30;
                        }
                        if (st != LT_QT_HIT) {
                            if (in && xa > 1.0 && xa < W - 1.0)
                                fail_msg("%s: pixel (%u, %u) status %d, expected a hit at x %.3f",
                                         names[e], u, v, st, xa);
                            border += (uint32_t)in;
                            continue;
                        }
                        hits++;
                        err = fmax(fabs(xs - xa), fabs(ys - (v + 0.5)));
                        maxe = fmax(maxe, err);
                        maxz = fmax(maxz, fabs(lt_rp_target_depth(&s, &t, zref, xs, ys, w) - Z) / Z);
                    }
                }
            printf("reproj disparity %s b %+.2f (f b / Z = %+.3f px): %u hits of %u on-screen "
                   "pixels (%u border misses), max |x - analytic| %.3g px (bound %.3g), target "
                   "depth max rel err %.3g (bound %.3g)\n",
                   names[e], b, disp, hits, expect, border, maxe, bound[e], maxz,
                   encs[e] == LT_QT_N32 ? 1e-3 : 1e-6);
            assert_true(maxe <= bound[e]);
            assert_true(maxz <= (encs[e] == LT_QT_N32 ? 1e-3 : 1e-6));
            assert_true(hits + border >= expect - 2 * H && hits <= expect);
            free(arena);
            free(wq);
            free(wf);
        }
    }
}

/* ---- double reference of the camera math ------------------------------------------------------ */

typedef struct refseg {
    int empty;
    double z0, z1;       /* clipped target depths; z1 = HUGE_VAL: to infinity */
    double e0[3], e1[3]; /* end points (x, y, w) */
    double o[3], d[3];   /* source camera coordinates of the ray: o + z_t d */
} refseg_t;

/* Independent of the core: the target ray in world space, z_t the target depth, mapped into
 * source camera coordinates; each clip condition is a + b z_t >= 0 (after multiplying by Zc > 0);
 * the intersection over z_t >= z_near_dst; end points projected in double. */
static void ref_segment(const lt_reproj_cam_t *s, const lt_reproj_cam_t *t,
                        const lt_reproj_opts_t *op, double u, double v, refseg_t *g)
{
    double p[3], dw[3], a[8], b[8], lo, hi, wn, wf, zn;
    int i, j, nc = 0;
    p[0] = (u - t->cx) / t->fx;
    p[1] = (v - t->cy) / t->fy;
    p[2] = 1.0;
    for (i = 0; i < 3; i++) {
        dw[i] = 0.0;
        for (j = 0; j < 3; j++)
            dw[i] += t->r[j][i] * p[j];
    }
    for (i = 0; i < 3; i++) {
        g->o[i] = g->d[i] = 0.0;
        for (j = 0; j < 3; j++) {
            g->o[i] += s->r[i][j] * (t->c[j] - s->c[j]);
            g->d[i] += s->r[i][j] * dw[j];
        }
    }
    zn = op->z_near_src > 0.0 ? op->z_near_src : op->z_ref;
    wn = op->z_ref / zn;
    wf = op->z_far_src > 0.0 ? op->z_ref / op->z_far_src : 0.0;
    /* Zc >= z_ref / wn (near; implies Zc > 0) */
    a[nc] = g->o[2] - op->z_ref / wn;
    b[nc++] = g->d[2];
    if (wf > 0.0) { /* Zc <= z_ref / wf */
        a[nc] = op->z_ref / wf - g->o[2];
        b[nc++] = -g->d[2];
    }
    /* 0 <= fx X / Z + cx <= W, likewise y */
    a[nc] = s->fx * g->o[0] + s->cx * g->o[2];
    b[nc++] = s->fx * g->d[0] + s->cx * g->d[2];
    a[nc] = s->width * g->o[2] - (s->fx * g->o[0] + s->cx * g->o[2]);
    b[nc++] = s->width * g->d[2] - (s->fx * g->d[0] + s->cx * g->d[2]);
    a[nc] = s->fy * g->o[1] + s->cy * g->o[2];
    b[nc++] = s->fy * g->d[1] + s->cy * g->d[2];
    a[nc] = s->height * g->o[2] - (s->fy * g->o[1] + s->cy * g->o[2]);
    b[nc++] = s->height * g->d[2] - (s->fy * g->d[1] + s->cy * g->d[2]);
    lo = op->z_near_dst;
    hi = HUGE_VAL;
    for (i = 0; i < nc; i++) {
        if (b[i] > 0.0)
            lo = fmax(lo, -a[i] / b[i]);
        else if (b[i] < 0.0)
            hi = fmin(hi, -a[i] / b[i]);
        else if (a[i] < 0.0)
            hi = -1.0;
    }
    g->empty = !(lo <= hi);
    g->z0 = lo;
    g->z1 = hi;
    if (g->empty)
        return;
    for (i = 0; i < 2; i++) {
        double z = i == 0 ? lo : hi, *e = i == 0 ? g->e0 : g->e1, X, Y, Zc;
        if (isinf(z)) { /* vanishing point */
            X = g->d[0];
            Y = g->d[1];
            Zc = g->d[2];
            e[2] = 0.0;
        } else {
            X = g->o[0] + z * g->d[0];
            Y = g->o[1] + z * g->d[1];
            Zc = g->o[2] + z * g->d[2];
            e[2] = op->z_ref / Zc;
        }
        e[0] = s->fx * X / Zc + s->cx;
        e[1] = s->fy * Y / Zc + s->cy;
    }
}

/* Distance of q from the line through a and b, in (x, y, w * scale) space. */
static double line_dist(const double a[3], const double b[3], const double q[3], double scale)
{
    double u[3], r[3], c[3], l;
    int i;
    for (i = 0; i < 3; i++) {
        double f = i == 2 ? scale : 1.0;
        u[i] = (b[i] - a[i]) * f;
        r[i] = (q[i] - a[i]) * f;
    }
    l = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (l < 1e-9)
        return sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    c[0] = u[1] * r[2] - u[2] * r[1];
    c[1] = u[2] * r[0] - u[0] * r[2];
    c[2] = u[0] * r[1] - u[1] * r[0];
    return sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / l;
}

static void test_reference(void **state)
{
    ltt_rng_t rng;
    uint64_t lanes = 0, kept = 0, refne = 0, tangent[2] = {0, 0}, bad = 0;
    double maxline[2] = {0, 0}, maxend[2] = {0, 0}, maxw[2] = {0, 0};
    int trial, fmt;
    /* bounds: distance from the true line (x, y in px, w scaled to the source width): s1.30 ends
     * rounded to 1/2 ulp of s15.16 plus the mapping's 2^-30 relative quantisation: 2^-14 px;
     * float32: 2^-10 px. End points along the line: the clip parameter's inward rounding (2
     * ulps of s1.30 in the homogeneous parameter), float rounding: 2^-6 px. */
    const double bline[2] = {ldexp(1.0, -14), ldexp(1.0, -10)};
    const double bend[2] = {ldexp(1.0, -10), ldexp(1.0, -6)};
    (void)state;
    ltt_rng_seed(&rng, 2024);
    for (trial = 0; trial < 120; trial++) {
        lt_reproj_cam_t s, t;
        lt_reproj_opts_t o;
        lt_reproj_q30_t mq;
        lt_reproj_f32_t mf;
        uint32_t W = 16u + ltt_rng_u32(&rng) % 300u, H = 16u + ltt_rng_u32(&rng) % 200u;
        uint32_t Wt = 16u + ltt_rng_u32(&rng) % 200u, Ht = 16u + ltt_rng_u32(&rng) % 200u;
        double big = trial % 4 == 3 ? 60.0 : 25.0;
        uint32_t tx, ty;
        int i;
        cam_init(&s, urand(&rng, 0.5, 2.0) * W, W, H);
        s.cx = urand(&rng, 0.3, 0.7) * W;
        s.cy = urand(&rng, 0.3, 0.7) * H;
        cam_rotate(&s, urand(&rng, -30, 30), urand(&rng, -30, 30), urand(&rng, -30, 30));
        for (i = 0; i < 3; i++)
            s.c[i] = urand(&rng, -2, 2);
        cam_init(&t, urand(&rng, 0.5, 2.0) * Wt, Wt, Ht);
        t.fy = t.fx * urand(&rng, 0.9, 1.1);
        t.cx = urand(&rng, 0.2, 0.8) * Wt;
        t.cy = urand(&rng, 0.2, 0.8) * Ht;
        {
            double mv[3], rot[3];
            for (i = 0; i < 3; i++) {
                mv[i] = urand(&rng, -1.5, 1.5);
                rot[i] = urand(&rng, -big, big);
            }
            if (trial % 10 == 9)
                rot[0] = urand(&rng, 70, 110); /* looking sideways: most rays never enter */
            lt_rp_cam_move(&s, mv, rot, &t);
            t.fx = urand(&rng, 0.5, 2.0) * Wt;
            t.fy = t.fx;
            t.cx = 0.5 * Wt;
            t.cy = 0.5 * Ht;
            t.width = Wt;
            t.height = Ht;
        }
        o.z_ref = urand(&rng, 0.2, 1.0);
        o.z_near_src = trial % 3 == 0 ? o.z_ref * urand(&rng, 0.6, 3.0) : 0.0;
        o.z_far_src = trial % 5 == 0 ? urand(&rng, 5.0, 30.0) : 0.0;
        o.z_near_dst = trial % 2 == 0 ? urand(&rng, 0.01, 0.5) : 0.0;
        assert_int_equal(lt_reproj_setup(&s, &t, &o, &mq, &mf), LT_OK);
        for (ty = 0; ty < Ht; ty += 4)
            for (tx = 0; tx < Wt; tx += 4) {
                lt_qray16_q30_t r;
                lt_qray16_f32_t rf;
                lt_mask16_t k[2] = {0xFFFF, 0xFFFF};
                assert_int_equal(lt_reproj_rays16_q30(&mq, tx, ty, &r, &k[0]), LT_OK);
                assert_int_equal(lt_reproj_rays16_f32(&mf, tx, ty, &rf, &k[1]), LT_OK);
                for (i = 0; i < 16; i++) {
                    uint32_t u = tx + (uint32_t)(i & 3), v = ty + (uint32_t)(i >> 2);
                    refseg_t g;
                    if (u >= Wt || v >= Ht)
                        continue;
                    lanes++;
                    ref_segment(&s, &t, &o, u + 0.5, v + 0.5, &g);
                    refne += !g.empty;
                    for (fmt = 0; fmt < 2; fmt++) {
                        double e0[3], e1[3], sc = (double)W, ln, en, d0, d1;
                        int on = LT__ON(k[fmt], i);
                        if (on != !g.empty) {
                            /* allowed only where the reference interval is a sliver: the core
                             * moves clip parameters inward by 2 ulps */
                            double len = g.empty ? 0.0
                                                 : sqrt(pow(g.e1[0] - g.e0[0], 2) +
                                                        pow(g.e1[1] - g.e0[1], 2) +
                                                        pow((g.e1[2] - g.e0[2]) * sc, 2));
                            if (!g.empty && len < 1e-2)
                                tangent[fmt]++;
                            else if (g.empty)
                                tangent[fmt]++; /* inward rounding never adds; counted, bounded */
                            else
                                bad++;
                            continue;
                        }
                        if (!on)
                            continue;
                        kept += fmt == 0;
                        if (fmt == 0) {
                            e0[0] = r.x.l[i] / Q16;
                            e0[1] = r.y.l[i] / Q16;
                            e0[2] = r.w.l[i] / Q30;
                            e1[0] = (r.x.l[i] + r.dx.l[i]) / Q16;
                            e1[1] = (r.y.l[i] + r.dy.l[i]) / Q16;
                            e1[2] = (r.w.l[i] + r.dw.l[i]) / Q30;
                        } else {
                            e0[0] = rf.x.l[i];
                            e0[1] = rf.y.l[i];
                            e0[2] = rf.w.l[i];
                            e1[0] = (double)rf.x.l[i] + (double)rf.dx.l[i];
                            e1[1] = (double)rf.y.l[i] + (double)rf.dy.l[i];
                            e1[2] = (double)rf.w.l[i] + (double)rf.dw.l[i];
                        }
                        /* the clip box holds */
                        /* the float far end is x + dx in float: one rounding past the box */
                        double tol = fmt == 0 ? 0.0 : ldexp((double)(W > H ? W : H), -20);
                        assert_true(e0[0] >= 0.0 && e0[0] <= W && e1[0] >= -tol && e1[0] <= W + tol);
                        assert_true(e0[1] >= 0.0 && e0[1] <= H && e1[1] >= -tol && e1[1] <= H + tol);
                        assert_true(e0[2] >= 0.0 && e0[2] < 2.0 && e1[2] >= -tol && e1[2] < 2.0);
                        ln = fmax(line_dist(g.e0, g.e1, e0, sc), line_dist(g.e0, g.e1, e1, sc));
                        d0 = sqrt(pow(e0[0] - g.e0[0], 2) + pow(e0[1] - g.e0[1], 2) +
                                  pow((e0[2] - g.e0[2]) * sc, 2));
                        d1 = sqrt(pow(e1[0] - g.e1[0], 2) + pow(e1[1] - g.e1[1], 2) +
                                  pow((e1[2] - g.e1[2]) * sc, 2));
                        en = fmax(d0, d1);
                        maxline[fmt] = fmax(maxline[fmt], ln);
                        maxend[fmt] = fmax(maxend[fmt], en);
                        maxw[fmt] = fmax(maxw[fmt], fmax(fabs(e0[2] - g.e0[2]),
                                                         fabs(e1[2] - g.e1[2])));
                    }
                }
            }
    }
    printf("reproj reference: 120 camera pairs, %llu pixels, %llu segments non-empty in double, "
           "%llu kept (s1.30); kept != reference: %llu / %llu slivers (< 0.01 px long) s1.30 / "
           "float32, %llu others (bound 0)\n",
           (unsigned long long)lanes, (unsigned long long)refne, (unsigned long long)kept,
           (unsigned long long)tangent[0], (unsigned long long)tangent[1],
           (unsigned long long)bad);
    printf("reproj reference: distance from the true line max s1.30 %.3g px (bound %.3g), float32 "
           "%.3g px (bound %.3g); end points max s1.30 %.3g px (bound %.3g), float32 %.3g px "
           "(bound %.3g); |w - w_ref| max s1.30 %.3g, float32 %.3g\n",
           maxline[0], bline[0], maxline[1], bline[1], maxend[0], bend[0], maxend[1], bend[1],
           maxw[0], maxw[1]);
    assert_int_equal(bad, 0);
    assert_true(maxline[0] <= bline[0] && maxline[1] <= bline[1]);
    assert_true(maxend[0] <= bend[0] && maxend[1] <= bend[1]);
    assert_true(tangent[0] + tangent[1] <= lanes / 1000u + 4u);
}

/* ---- near plane, screen edges, rays pointing away ------------------------------------------- */

static void test_clipping(void **state)
{
    lt_reproj_cam_t s, t;
    lt_reproj_opts_t o = {1.0, 0.0, 0.0, 0.0};
    lt_reproj_q30_t mq;
    lt_qray16_q30_t r;
    lt_mask16_t k;
    double mv[3] = {0, 0, -3.0}, rot[3] = {0, 0, 0};
    uint32_t tx, ty, n = 0, left = 0, away, ncut = 0;
    int i;
    double maxw = 0.0, maxx = 0.0;
    (void)state;
    cam_init(&s, 64.0, 64, 64);
    /* target 3 units behind the source: every ray starts behind the source camera and is cut at
     * the near plane z_s = z_ref (w = 1), never before it */
    lt_rp_cam_move(&s, mv, rot, &t);
    assert_int_equal(lt_reproj_setup(&s, &t, &o, &mq, NULL), LT_OK);
    for (ty = 0; ty < 64; ty += 4)
        for (tx = 0; tx < 64; tx += 4) {
            k = 0xFFFF;
            assert_int_equal(lt_reproj_rays16_q30(&mq, tx, ty, &r, &k), LT_OK);
            for (i = 0; i < 16; i++) {
                uint32_t u = tx + (uint32_t)(i & 3), v = ty + (uint32_t)(i >> 2);
                refseg_t g;
                if (!LT__ON(k, i))
                    continue;
                n++;
                ref_segment(&s, &t, &o, u + 0.5, v + 0.5, &g);
                if (g.empty)
                    continue;
                /* the ray crosses z_s = z_ref on screen: the near plane is the active clip */
                if (fabs(g.e0[2] - 1.0) < 1e-12) {
                    ncut++;
                    maxw = fmax(maxw, fabs(r.w.l[i] / Q30 - 1.0));
                    maxx = fmax(maxx, fmax(fabs(r.x.l[i] / Q16 - g.e0[0]), fabs(r.y.l[i] / Q16 - g.e0[1])));
                } else {
                    /* cut by the screen first: it starts farther, w below w_near */
                    assert_true(r.w.l[i] < mq.w_near);
                }
            }
        }
    /* z_s = 1 is z_t = 4: the near end is the pixel's point at 4 units, 4x its offset from the
     * image centre: only the central 16 x 16 pixels start at the near plane */
    printf("reproj near plane: target 3 behind the source: %u of 4096 rays kept, %u start on the "
           "near plane: max |w - w_near| %.3g (bound 2^-24 = %.3g), start x, y max err %.3g px "
           "(bound 2^-12)\n",
           n, ncut, maxw, ldexp(1.0, -24), maxx);
    assert_int_equal(n, 4096);
    assert_int_equal(ncut, 256);
    assert_true(maxw <= ldexp(1.0, -24) && maxx <= ldexp(1.0, -12));

    /* target looking backwards: every ray points away from the source view */
    rot[0] = 180.0;
    mv[2] = 0.0;
    lt_rp_cam_move(&s, mv, rot, &t);
    assert_int_equal(lt_reproj_setup(&s, &t, &o, &mq, NULL), LT_OK);
    away = 0;
    for (ty = 0; ty < 64; ty += 4)
        for (tx = 0; tx < 64; tx += 4) {
            k = 0xFFFF;
            assert_int_equal(lt_reproj_rays16_q30(&mq, tx, ty, &r, &k), LT_OK);
            away += lt__popcount32(k);
            for (i = 0; i < 16; i++)
                if (!LT__ON(k, i))
                    assert_true(r.x.l[i] == 0 && r.dx.l[i] == 0 && r.tmax.l[i] == 0);
        }
    printf("reproj pointing away: target turned 180 degrees: %u of 4096 rays kept (bound 0)\n",
           away);
    assert_int_equal(away, 0);

    /* target turned 35 degrees right and moved left: rays on the left of the target image cross
     * the source's right edge and are cut there */
    rot[0] = 35.0;
    mv[0] = -0.5;
    lt_rp_cam_move(&s, mv, rot, &t);
    assert_int_equal(lt_reproj_setup(&s, &t, &o, &mq, NULL), LT_OK);
    n = 0;
    for (ty = 0; ty < 64; ty += 4)
        for (tx = 0; tx < 64; tx += 4) {
            k = 0xFFFF;
            assert_int_equal(lt_reproj_rays16_q30(&mq, tx, ty, &r, &k), LT_OK);
            for (i = 0; i < 16; i++) {
                int32_t x1;
                if (!LT__ON(k, i))
                    continue;
                n++;
                x1 = r.x.l[i] + r.dx.l[i];
                assert_true(r.x.l[i] >= 0 && r.x.l[i] <= 64 * 65536 && x1 >= 0 &&
                            x1 <= 64 * 65536);
                if (x1 == 64 * 65536 || r.x.l[i] == 64 * 65536 || x1 == 0 || r.x.l[i] == 0)
                    left++;
            }
        }
    printf("reproj screen: target turned 35 degrees: %u of 4096 rays kept, %u of them cut at the "
           "source's left/right edge, all ends within [0, 64] px\n",
           n, left);
    assert_true(n > 0 && n < 4096 && left > 0);

    /* lanes not asked for, tiles off the image */
    k = 0x00F0;
    assert_int_equal(lt_reproj_rays16_q30(&mq, 0, 0, &r, &k), LT_OK);
    assert_true((k & ~0x00F0u) == 0);
    k = 0xFFFF;
    assert_int_equal(lt_reproj_rays16_q30(&mq, 64, 0, &r, &k), LT_OK);
    assert_int_equal(k, 0);
    k = 0xFFFF;
    assert_int_equal(lt_reproj_rays16_q30(&mq, 0xFFFFFFFEu, 0, &r, &k), LT_OK);
    assert_int_equal(k, 0);
}

/* ---- bad parameters ---------------------------------------------------------------------- */

static void test_errors(void **state)
{
    lt_reproj_cam_t s, t, b;
    lt_reproj_opts_t o = {1.0, 0.0, 0.0, 0.0}, ob;
    lt_reproj_q30_t mq, m2;
    lt_reproj_f32_t mf, f2;
    lt_qray16_q30_t r;
    lt_qray16_f32_t rf;
    lt_mask16_t k = 0xFFFF;
    int n = 0;
    (void)state;
    cam_init(&s, 50.0, 32, 32);
    t = s;
    t.c[0] = 0.1;
#define EXPECT(call, st)                                                                           \
    do {                                                                                           \
        assert_int_equal((call), (st));                                                            \
        n++;                                                                                       \
    } while (0)
    EXPECT(lt_reproj_setup(&s, &t, &o, &mq, &mf), LT_OK);
    b = s;
    b.fx = NAN;
    EXPECT(lt_reproj_setup(&b, &t, &o, &mq, &mf), LT_E_ARG);
    b = s;
    b.fy = 0.0;
    EXPECT(lt_reproj_setup(&b, &t, &o, &mq, &mf), LT_E_ARG);
    b = t;
    b.fx = -5.0;
    EXPECT(lt_reproj_setup(&s, &b, &o, &mq, &mf), LT_E_ARG);
    b = t;
    b.cx = INFINITY;
    EXPECT(lt_reproj_setup(&s, &b, &o, &mq, &mf), LT_E_ARG);
    b = t;
    b.r[1][1] = 0.0; /* singular */
    EXPECT(lt_reproj_setup(&s, &b, &o, &mq, &mf), LT_E_ARG);
    b = t;
    b.r[0][0] = 2.0; /* not orthonormal */
    EXPECT(lt_reproj_setup(&s, &b, &o, &mq, &mf), LT_E_ARG);
    b = t;
    b.c[2] = NAN;
    EXPECT(lt_reproj_setup(&s, &b, &o, &mq, &mf), LT_E_ARG);
    b = t;
    b.width = 0;
    EXPECT(lt_reproj_setup(&s, &b, &o, &mq, &mf), LT_E_ARG);
    b = s;
    b.height = LT_QT_MAX_DIM + 1;
    EXPECT(lt_reproj_setup(&b, &t, &o, &mq, &mf), LT_E_ARG);
    ob = o;
    ob.z_ref = 0.0;
    EXPECT(lt_reproj_setup(&s, &t, &ob, &mq, &mf), LT_E_ARG);
    ob = o;
    ob.z_ref = NAN;
    EXPECT(lt_reproj_setup(&s, &t, &ob, &mq, &mf), LT_E_ARG);
    ob = o;
    ob.z_near_src = 0.4; /* w_near = 2.5 */
    EXPECT(lt_reproj_setup(&s, &t, &ob, &mq, &mf), LT_E_RANGE);
    ob = o;
    ob.z_far_src = 0.9; /* far before near */
    EXPECT(lt_reproj_setup(&s, &t, &ob, &mq, &mf), LT_E_RANGE);
    ob = o;
    ob.z_near_dst = -1.0;
    EXPECT(lt_reproj_setup(&s, &t, &ob, &mq, &mf), LT_E_ARG);
    EXPECT(lt_reproj_setup(NULL, &t, &o, &mq, &mf), LT_E_ARG);
    EXPECT(lt_reproj_setup(&s, &t, &o, NULL, NULL), LT_E_ARG);
    /* bad mappings */
    EXPECT(lt_reproj_setup(&s, &t, &o, &mq, &mf), LT_OK);
    EXPECT(lt_reproj_rays16_q30(NULL, 0, 0, &r, &k), LT_E_ARG);
    EXPECT(lt_reproj_rays16_q30(&mq, 0, 0, NULL, &k), LT_E_ARG);
    EXPECT(lt_reproj_rays16_q30(&mq, 0, 0, &r, NULL), LT_E_ARG);
    m2 = mq;
    m2.src_w = 0;
    EXPECT(lt_reproj_rays16_q30(&m2, 0, 0, &r, &k), LT_E_ARG);
    m2 = mq;
    m2.src_w = 33; /* above 2^src_log2 */
    EXPECT(lt_reproj_rays16_q30(&m2, 0, 0, &r, &k), LT_E_ARG);
    m2 = mq;
    m2.w_near = 0;
    EXPECT(lt_reproj_rays16_q30(&m2, 0, 0, &r, &k), LT_E_ARG);
    m2 = mq;
    m2.w_far = m2.w_near;
    EXPECT(lt_reproj_rays16_q30(&m2, 0, 0, &r, &k), LT_E_ARG);
    m2 = mq;
    m2.mb[3][2] = LT_Q30_ONE + 1; /* outside the entry bound that keeps products in int64 */
    EXPECT(lt_reproj_rays16_q30(&m2, 0, 0, &r, &k), LT_E_ARG);
    f2 = mf;
    f2.w_near = NAN;
    EXPECT(lt_reproj_rays16_f32(&f2, 0, 0, &rf, &k), LT_E_ARG);
    f2 = mf;
    f2.ma[1][1] = INFINITY;
    EXPECT(lt_reproj_rays16_f32(&f2, 0, 0, &rf, &k), LT_E_ARG);
    f2 = mf;
    f2.dst_h = 0;
    EXPECT(lt_reproj_rays16_f32(&f2, 0, 0, &rf, &k), LT_E_ARG);
#undef EXPECT
    printf("reproj errors: %d calls with NaN / zero / negative focal lengths, singular or scaled "
           "rotations, bad sizes, planes and mappings return the documented status\n", n);
}

/* ---- view synthesis end to end ---------------------------------------------------------------- */

/* Flat depth exactly at a power of two (z_ref chosen from it) and a checkerboard of depths 1 and 3,
 * reprojected through the identity camera: every pixel hits, in every node encoding and with the
 * DDA and Hi-Z. With z_ref = the nearest depth the surface sat at w = 1, on the default near plane,
 * and n64/n32 lost it (0% and 50% hits). */
static void test_flat_zref(void **state)
{
    static const float flats[5] = {2.0f, 1.0f, 4.0f, 1024.0f, 0.5f};
    static const lt_qt_enc_t encs[3] = {LT_QT_N64, LT_QT_N32, LT_QT_F32};
    const uint32_t W = 40, H = 24;
    float *z = malloc(W * H * sizeof *z);
    lt_rp_source_t src;
    lt_rp_opts_t o;
    lt_rp_result_t res;
    lt_diag_t diag;
    int f, e, tr, runs = 0, bad = 0;
    size_t i;
    (void)state;
    assert_non_null(z);
    for (f = 0; f < 6; f++) {
        for (i = 0; i < (size_t)W * H; i++) {
            uint32_t x = (uint32_t)(i % W), y = (uint32_t)(i / W);
            z[i] = f < 5 ? flats[f] : (((x / 4) + (y / 4)) % 2 ? 3.0f : 1.0f);
        }
        memset(&src, 0, sizeof src);
        src.width = W;
        src.height = H;
        src.layers = 1;
        src.z = z;
        lt_rp_cam_default(W, H, 0, 0, 0, 0, 60.0, &src.cam);
        for (tr = 0; tr < 3; tr++)
            for (e = 0; e < 3; e++) {
                if (tr > 0 && e == 1)
                    continue; /* the baselines have s1.30 and float32 only */
                lt_rp_opts_default(&o);
                o.enc = encs[e];
                o.tracer = tr == 0 ? LT_RP_QUADTREE : tr == 1 ? LT_RP_DDA : LT_RP_HIZ;
                assert_int_equal(lt_rp_run(&src, &src.cam, &o, &res, &diag), 0);
                runs++;
                if (res.st.cls[LT_RP_HIT] != res.st.pixels) {
                    bad++;
                    printf("  FAIL %s depth, tracer %d, encoding %d: %llu hits of %llu\n",
                           f < 5 ? "flat" : "checkerboard", tr, e,
                           (unsigned long long)res.st.cls[LT_RP_HIT],
                           (unsigned long long)res.st.pixels);
                }
                lt_rp_result_free(&res);
            }
    }
    printf("reproj flat depth at a power of two (0.5, 1, 2, 4, 1024) and a 1/3 checkerboard, "
           "identity view: %d runs (quadtree n64/n32/f32, DDA and Hi-Z s1.30/f32), %d with a "
           "pixel not hit (bound 0)\n", runs, bad);
    assert_int_equal(bad, 0);
    free(z);
}

static void test_view_synthesis(void **state)
{
    const uint32_t W = 48, H = 40;
    float *z = malloc(2 * W * H * sizeof *z), *rgb0 = malloc(3 * W * H * sizeof *rgb0);
    lt_rp_source_t src;
    lt_reproj_cam_t dst;
    lt_rp_opts_t o;
    lt_rp_result_t res;
    lt_diag_t diag;
    double mv[3] = {0.6, 0, 0}, rot[3] = {0, 0, 0}, maxz = 0.0, maxc = 0.0;
    size_t i;
    uint64_t holes;
    (void)state;
    memset(&src, 0, sizeof src);
    /* a box at z = 3 over a wall at z = 8; layer 1 = the wall behind the box */
    for (i = 0; i < (size_t)W * H; i++) {
        uint32_t x = (uint32_t)(i % W), y = (uint32_t)(i / W);
        int box = x >= 16 && x < 32 && y >= 12 && y < 28;
        z[i] = box ? 3.0f : 8.0f;
        z[W * H + i] = box ? 8.0f : INFINITY;
        rgb0[3 * i] = box ? 1.0f : 0.1f;
        rgb0[3 * i + 1] = (float)x / (float)W;
        rgb0[3 * i + 2] = (float)y / (float)H;
    }
    src.width = W;
    src.height = H;
    src.layers = 1;
    src.z = z;
    src.rgb[0] = rgb0;
    lt_rp_cam_default(W, H, 0, 0, 0, 0, 60.0, &src.cam);
    lt_rp_opts_default(&o);
    o.bilinear = 0;
    /* identity: every pixel hits its own source pixel, colour and depth exact */
    assert_int_equal(lt_rp_run(&src, &src.cam, &o, &res, &diag), 0);
    for (i = 0; i < (size_t)W * H; i++) {
        assert_int_equal(res.cls[i], LT_RP_HIT);
        maxz = fmax(maxz, fabs((double)res.z[i] - (double)z[i]) / (double)z[i]);
        maxc = fmax(maxc, fabs((double)res.rgb[3 * i] - (double)rgb0[3 * i]));
        maxc = fmax(maxc, fabs((double)res.rgb[3 * i + 1] - (double)rgb0[3 * i + 1]));
    }
    printf("reproj view identity %ux%u: %llu hits of %llu, colour max |err| %.3g (bound 0), "
           "depth max rel err %.3g (bound 1e-6), %.2f nodes per ray\n",
           W, H, (unsigned long long)res.st.cls[LT_RP_HIT], (unsigned long long)res.st.pixels,
           maxc, maxz, (double)res.st.nodes / (double)res.st.rays);
    assert_true(maxc == 0.0 && maxz <= 1e-6);
    lt_rp_result_free(&res);

    /* moved right: the wall left of the box is disoccluded (one layer); with the wall as layer 1
     * those rays hit it instead */
    lt_rp_cam_move(&src.cam, mv, rot, &dst);
    for (src.layers = 1; src.layers <= 2; src.layers++) {
        uint64_t wall = 0;
        assert_int_equal(lt_rp_run(&src, &dst, &o, &res, &diag), 0);
        holes = res.st.cls[LT_RP_DISOCCLUDED] + res.st.cls[LT_RP_OUTSIDE] + res.st.cls[LT_RP_UNKNOWN];
        for (i = 0; i < (size_t)W * H; i++) {
            /* inpainted: finite colour; depth finite except for background (+inf by design) */
            assert_true(isfinite(res.rgb[3 * i]));
            assert_true(isfinite(res.z[i]) || (res.cls[i] == LT_RP_BACKGROUND && isinf(res.z[i])));
            wall += res.layer[i] == 1;
        }
        printf("reproj view moved %.1f, %u layer(s): hit %llu, background %llu, disoccluded %llu, "
               "outside %llu, layer-1 hits %llu; every hole inpainted (finite colour and depth)\n",
               mv[0], src.layers, (unsigned long long)res.st.cls[LT_RP_HIT],
               (unsigned long long)res.st.cls[LT_RP_BACKGROUND],
               (unsigned long long)res.st.cls[LT_RP_DISOCCLUDED],
               (unsigned long long)res.st.cls[LT_RP_OUTSIDE], (unsigned long long)wall);
        if (src.layers == 1)
            assert_true(res.st.cls[LT_RP_DISOCCLUDED] > 0);
        else
            assert_true(res.st.cls[LT_RP_DISOCCLUDED] < 10 && wall > 0);
        assert_true(holes < res.st.pixels / 4);
        lt_rp_result_free(&res);
    }
    free(z);
    free(rgb0);
}

static void test_inpaint(void **state)
{
    const uint32_t W = 40, H = 20;
    float rgb[3 * 40 * 20], z[40 * 20];
    uint8_t v[40 * 20];
    uint32_t x, y, far = 0, n = 0;
    (void)state;
    /* left half near (z = 1, red), right half far (z = 10, blue), a 6-pixel hole band between */
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            size_t i = (size_t)y * W + x;
            int near = x < 17, hole = x >= 17 && x < 23;
            rgb[3 * i] = near ? 1.0f : 0.0f;
            rgb[3 * i + 1] = 0.0f;
            rgb[3 * i + 2] = near ? 0.0f : 1.0f;
            z[i] = near ? 1.0f : 10.0f;
            v[i] = (uint8_t)!hole;
            if (hole) {
                rgb[3 * i] = rgb[3 * i + 2] = -1.0f;
                z[i] = NAN;
            }
        }
    assert_int_equal(lt_rp_inpaint(rgb, z, v, W, H), 0);
    for (y = 0; y < H; y++)
        for (x = 17; x < 23; x++) {
            size_t i = (size_t)y * W + x;
            n++;
            far += rgb[3 * i + 2] > 0.99f && z[i] > 9.9f;
        }
    printf("reproj inpaint: %u hole pixels between a near and a far region, %u filled from the "
           "far side (background bias; bound: all)\n",
           n, far);
    assert_int_equal(far, n);
    memset(v, 0, sizeof v);
    assert_int_equal(lt_rp_inpaint(rgb, z, v, W, H), -1);
}

/* lt_rp_truth_compare: the accounting on a hand-made 4 x 2 result, then the box-over-wall view
 * synthesis against its analytic ground truth (the world the depth image samples). */
static void test_truth(void **state)
{
    static const uint8_t cls[8] = {LT_RP_HIT, LT_RP_HIT, LT_RP_HIT, LT_RP_BACKGROUND,
                                   LT_RP_BACKGROUND, LT_RP_DISOCCLUDED, LT_RP_OUTSIDE,
                                   LT_RP_UNKNOWN};
    float z8[8] = {10.0f, 10.5f, 4.0f, INFINITY, INFINITY, 7.0f, INFINITY, NAN};
    const float zt8[8] = {10.0f, 10.0f, INFINITY, INFINITY, 5.0f, 7.7f, INFINITY, 3.0f};
    float rel[8];
    lt_rp_result_t r;
    lt_rp_truth_t t;
    (void)state;
    memset(&r, 0, sizeof r);
    r.width = 4;
    r.height = 2;
    r.z = z8;
    r.cls = (uint8_t *)cls;
    assert_int_equal(lt_rp_truth_compare(&r, zt8, 0.0, &t, NULL), -1);
    assert_int_equal(lt_rp_truth_compare(&r, zt8, NAN, &t, NULL), -1);
    assert_int_equal(lt_rp_truth_compare(&r, zt8, 0.01, &t, rel), 0);
    /* known: pixels 0-4; spurious: 2 (hit, truth misses); missed: 4 (background, truth hits);
       common hits 0 (exact) and 1 (5% off); inpainted 5 (10% off), 6 (correct background),
       7 (unfilled) */
    printf("reproj truth accounting 4x2: known %llu, spurious %llu, missed %llu, common %llu "
           "(within %llu), RMSE %.4g (expected 0.25*sqrt(2)), relative RMSE %.4g, inpainted %llu "
           "(wrong %llu, unfilled %llu, common %llu)\n",
           (unsigned long long)t.known, (unsigned long long)t.spurious,
           (unsigned long long)t.missed, (unsigned long long)t.both_hit,
           (unsigned long long)t.within, t.rmse, t.rel_rmse, (unsigned long long)t.inpainted,
           (unsigned long long)t.ip_wrong, (unsigned long long)t.ip_unfilled,
           (unsigned long long)t.ip_both);
    assert_true(t.pixels == 8 && t.truth_hit == 5 && t.known == 5 && t.spurious == 1 &&
                t.missed == 1 && t.both_hit == 2 && t.within == 1 && t.inpainted == 3 &&
                t.ip_wrong == 0 && t.ip_unfilled == 1 && t.ip_both == 1 && t.ip_within == 0);
    assert_true(fabs(t.rmse - 0.5 / sqrt(2.0)) < 1e-12);
    assert_true(fabs(t.rel_rmse - 0.05 / sqrt(2.0)) < 1e-9 && fabs(t.max_rel - 0.05) < 1e-9);
    assert_true(t.rel_p50 == 0.0 && fabs(t.rel_p99 - 0.05) < 1e-9);
    assert_true(fabs(t.ip_rel_rmse - 0.7 / 7.7) < 1e-6);
    assert_true(rel[0] == 0.0f && isnan(rel[2]) && isnan(rel[3]) && isnan(rel[4]) &&
                fabsf(rel[5] - 0.7f / 7.7f) < 1e-6f && isnan(rel[6]) && isnan(rel[7]));

    {
        /* box (source pixels 16..31 x 12..27) at z = 3 over a wall at z = 8, two layers; the
           target moved 0.6 right. Ground truth: the same world traced analytically. */
        const uint32_t W = 48, H = 40;
        float *z = malloc(2 * W * H * sizeof *z), *zt = malloc(W * H * sizeof *zt);
        lt_rp_source_t src;
        lt_reproj_cam_t dst;
        lt_rp_opts_t o;
        lt_rp_result_t res;
        lt_diag_t diag;
        double mv[3] = {0.6, 0, 0}, rot[3] = {0, 0, 0};
        double bx0, bx1, by0, by1;
        size_t i;
        uint32_t x, y, edge = 0;
        memset(&src, 0, sizeof src);
        for (i = 0; i < (size_t)W * H; i++) {
            x = (uint32_t)(i % W);
            y = (uint32_t)(i / W);
            z[i] = x >= 16 && x < 32 && y >= 12 && y < 28 ? 3.0f : 8.0f;
            z[W * H + i] = z[i] == 3.0f ? 8.0f : INFINITY;
        }
        src.width = W;
        src.height = H;
        src.layers = 2;
        src.z = z;
        lt_rp_cam_default(W, H, 0, 0, 0, 0, 60.0, &src.cam);
        lt_rp_cam_move(&src.cam, mv, rot, &dst);
        /* the box's world extent at z = 3: the source pixels' footprints */
        bx0 = (16.0 - src.cam.cx) / src.cam.fx * 3.0;
        bx1 = (32.0 - src.cam.cx) / src.cam.fx * 3.0;
        by0 = (12.0 - src.cam.cy) / src.cam.fy * 3.0;
        by1 = (28.0 - src.cam.cy) / src.cam.fy * 3.0;
        for (y = 0; y < H; y++)
            for (x = 0; x < W; x++) {
                /* target ray: centre (0.6, 0, 0), direction ((x+.5-cx)/fx, (y+.5-cy)/fy, 1) */
                double dx = ((double)x + 0.5 - dst.cx) / dst.fx;
                double dy = ((double)y + 0.5 - dst.cy) / dst.fy;
                double X = 0.6 + 3.0 * dx, Y = 3.0 * dy;
                double ex = fmin(fabs(X - bx0), fabs(X - bx1)) * dst.fx / 3.0;
                double ey = fmin(fabs(Y - by0), fabs(Y - by1)) * dst.fy / 3.0;
                int inbox = X >= bx0 && X < bx1 && Y >= by0 && Y < by1;
                zt[(size_t)y * W + x] = inbox ? 3.0f : 8.0f;
                /* pixels within one pixel of the box outline, or whose wall point lies in the
                   box's shadow edge, may take the other surface: the depth image cannot place
                   an edge between two pixel centres */
                edge += (ex < 1.0 && Y > by0 - 3.0 / dst.fy && Y < by1 + 3.0 / dst.fy) ||
                        (ey < 1.0 && X > bx0 - 3.0 / dst.fx && X < bx1 + 3.0 / dst.fx);
            }
        for (i = 0; i < 9; i++) {
            static const char *const tn[3] = {"quadtree", "DDA", "Hi-Z"};
            lt_rp_opts_default(&o);
            o.enc = (lt_qt_enc_t)(i % 3);
            o.tracer = (lt_rp_tracer_t)(i / 3);
            assert_int_equal(lt_rp_run(&src, &dst, &o, &res, &diag), 0);
            assert_int_equal(lt_rp_truth_compare(&res, zt, 0.01, &t, NULL), 0);
            printf("reproj truth box over wall, %s enc %d, moved 0.6: %llu known pixels, wrong "
                   "hit/miss %llu (bound 0), common hits %llu, outside 1%% %llu (bound: %u outline "
                   "pixels), median relative error %.3g (bound 1e-6), inpainted %llu\n",
                   tn[o.tracer], (int)o.enc, (unsigned long long)t.known,
                   (unsigned long long)(t.spurious + t.missed), (unsigned long long)t.both_hit,
                   (unsigned long long)(t.both_hit - t.within), edge, t.rel_p50,
                   (unsigned long long)t.inpainted);
            assert_true(t.spurious + t.missed == 0);
            assert_true(t.both_hit - t.within <= edge);
            assert_true(t.rel_p50 <= 1e-6);
            assert_true(t.known > (uint64_t)W * H * 9 / 10);
            lt_rp_result_free(&res);
        }
        /* an unknown tracer or encoding is refused with a message, nothing allocated */
        lt_rp_opts_default(&o);
        o.tracer = (lt_rp_tracer_t)3;
        diag.msg[0] = '\0';
        assert_int_equal(lt_rp_run(&src, &dst, &o, &res, &diag), -1);
        assert_true(strstr(diag.msg, "tracer") != NULL && res.z == NULL);
        lt_rp_opts_default(&o);
        o.enc = (lt_qt_enc_t)7;
        assert_int_equal(lt_rp_run(&src, &dst, &o, &res, &diag), -1);
        printf("reproj truth: unknown tracer 3 and encoding 7 refused ('%s')\n", diag.msg);
        free(z);
        free(zt);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tile_hash),
        cmocka_unit_test(test_identity),
        cmocka_unit_test(test_translation_disparity),
        cmocka_unit_test(test_reference),
        cmocka_unit_test(test_clipping),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_flat_zref), cmocka_unit_test(test_view_synthesis),
        cmocka_unit_test(test_inpaint),
        cmocka_unit_test(test_truth),
    };
#if LT_COST_MODE == LT_COST_SIM
    {
        lt_diag_t diag;
        if (lt_sim_init(lt_sim_machine_find("lrb16"), NULL, NULL, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            return 1;
        }
    }
#endif
    return cmocka_run_group_tests(tests, NULL, NULL);
}
