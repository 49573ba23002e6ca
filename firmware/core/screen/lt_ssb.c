/* lt_ssb.c - ray helpers shared by the two screen-space baselines (lt_ssdda.c: the DDA of McGuire &
 * Mara; lt_hiz.c: the Hi-Z tracer of Uludag / FidelityFX SSSR), sibling screen-space tracers
 * sharing one ray-packet header (lt_ssb.h): ray setup and clip, the crossing function, w along the
 * ray, the hit parameter, surface-shell bounds and pixel gathers, for s1.30 (lt__ssb_*_q30) and
 * float32 (lt__ssb_*_f32). The setup and crossings follow lt_qt.c's (same clip, same
 * normalised-reciprocal crossing) so that all three tracers see the same segment; the quadtree
 * calls the clip, the crossings, w along the ray, the s1.30 hit parameter and the child side
 * itself. They are kernel routines over the lane types of lt_v16.h / lt_v16w.h, each charging its
 * own recipe of lt_recipes.def (SSB_*, on the Cost: lines), defined here once; the baselines reach
 * them through the SS_* traits (lt_ssb_q30.inc, lt_ssb_f32.inc), the quadtree through its LTQ_*
 * traits (lt_qt.c). Builds: all; the float32 half only with LT_CFG_FLOAT32.
 */
#include "lt_ssb.h"

/* ==== s1.30 w and t, s15.16 pixels, int64 wide values ========================================= */

/* t = (X - o) / d on axis a for integer pixel coordinates X, lanes in k (0 elsewhere):
 * (X 2^16 - o) m >> sh, half up, negated for d < 0, saturated to int32. Monotonic in X, error
 * <= 1 ulp for |X - o| <= 2^15 px. Every crossing and every child choice of the three tracers
 * goes through it, so they all agree. Cost: SSB_Q_TCROSS (VALU x2, VMUL x1, VSHIFT x2). */
lt_vq30_t lt__ssb_tcross_q30(const lt__ssb_setup_q30_t *S, int a, lt_mask16_t k, lt_vi32_t X)
{
    const lt_vq16_t *o = a ? &S->r->y : &S->r->x;
    lt_vq30_t t;
    int i;
    LT_CHARGE(SSB_Q_TCROSS);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        t.l[i] = LT__ON(k, i) ? lt__ssb_tcross_lane_q30(o->l[i], S->m[a].l[i], S->sh[a].l[i],
                                                        (int)LT__ON(S->neg[a], i), X.l[i])
                              : 0;
    return t;
}

/* The t span of n half pixels (0 <= n < 2^16) along each lane's major axis (y for lanes in ky):
 * n 2^15 / |d| in s1.30 = (n 2^15) m >> sh, half up, saturated; monotonic in n. Parallel lanes
 * (m = 0) give 0. Cost: SSB_Q_TSPAN (VALU x1 (axis select), VMUL x1, VSHIFT x2). */
lt_vq30_t lt__ssb_tspan_q30(const lt__ssb_setup_q30_t *S, lt_mask16_t ky, lt_mask16_t k,
                            lt_vi32_t n)
{
    lt_vq30_t t;
    int i;
    LT_CHARGE(SSB_Q_TSPAN);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        int a = (int)LT__ON(ky, i);
        t.l[i] = 0;
        if (LT__ON(k, i))
            t.l[i] = lt__ssat32(lt__ssb_rnd_q30((int64_t)n.l[i] * 32768 * S->m[a].l[i],
                                        (unsigned)S->sh[a].l[i]));
    }
    return t;
}

/* floor(o + d t) on axis a: s15.16 2^30 + s15.16 x s1.30 is exact in s.46; the floor is the pixel.
 * Cost: SSB_Q_PIXEL (VMUL x1, VMULW x1, VSHIFT x1). */
lt_vi32_t lt__ssb_pixel_q30(const lt__ssb_setup_q30_t *S, int a, lt_mask16_t k, lt_vq30_t t)
{
    const lt_vq16_t *o = a ? &S->r->y : &S->r->x;
    const lt_vq16_t *d = a ? &S->r->dy : &S->r->dx;
    lt_vi32_t p;
    int i;
    LT_CHARGE(SSB_Q_PIXEL);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        int64_t v = (int64_t)o->l[i] * ((int64_t)1 << 30) + lt__mul32x32_64(d->l[i], t.l[i]);
        p.l[i] = LT__ON(k, i) ? (int32_t)lt__asr64(v, 46) : 0;
    }
    return p;
}

/* w_ray(t) in s1.60 for the lanes in k (0 elsewhere). Cost: SSB_Q_WRAY (VMUL x1, VMULW x1,
 * VSHIFT x1). */
lt_vql60_t lt__ssb_wray_q30(const lt__ssb_setup_q30_t *S, lt_mask16_t k, lt_vq30_t t)
{
    lt_vql60_t f;
    int i;
    LT_CHARGE(SSB_Q_WRAY);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        f.l[i] = LT__ON(k, i) ? lt__ssb_wray1_q30(S->r, i, t.l[i]) : 0;
    return f;
}

/* w_ray(t) rounded half up to s1.30 (saturating). Cost: SSB_Q_W_AT (VMUL x1, VMULW x1,
 * VSHIFT x1). */
lt_vq30_t lt__ssb_w_at_q30(const lt__ssb_setup_q30_t *S, lt_mask16_t k, lt_vq30_t t)
{
    lt_vq30_t w;
    int i;
    LT_CHARGE(SSB_Q_W_AT);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        w.l[i] = LT__ON(k, i) ? lt__ssb_w_at_lane_q30(S->r->w.l[i], S->r->dw.l[i], t.l[i]) : 0;
    return w;
}

/* The zero of a linear function on [tn, tf] with values fn >= 0 at tn and ff <= 0 at tf (s1.60,
 * fn - ff > 0): tn + (tf - tn) fn / (fn - ff), the operands scaled down together below 2^31 so
 * the product fits int64; half up. Lanes with fn - ff == 0 keep tn. The quadtree's crossing and
 * box entry too. Cost: SSB_Q_HIT_T (VDIV x1, VALU x4, VMUL x1). */
lt_vq30_t lt__ssb_hit_t_q30(lt_mask16_t k, lt_vq30_t tn, lt_vq30_t tf, lt_vql60_t fn,
                            lt_vql60_t ff)
{
    lt_vq30_t t = tn;
    int i;
    LT_CHARGE(SSB_Q_HIT_T);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        if (LT__ON(k, i))
            t.l[i] = lt__ssb_hit_t_lane_q30(tn.l[i], tf.l[i], fn.l[i], ff.l[i]);
    return t;
}

/* Lanes in k where the ray at t lies in the upper half (coordinate >= xm) of a cell split at the
 * pixel coordinate xm: past the midline crossing for d > 0, before it for d < 0, by position for
 * d == 0. Uses lt__ssb_tcross_q30, so it agrees with every exit crossing.
 * Cost: lt__ssb_tcross_q30 + the two compares (lt_vq30_cmpge_m, lt_vq30_cmplt_m) when a lane
 * moves on the axis; SSB_Q_SIDE_PAR (VCMP x1) when a lane is parallel to it. */
lt_mask16_t lt__ssb_child_side_q30(const lt__ssb_setup_q30_t *S, int a, lt_mask16_t k,
                                   lt_vq30_t t, lt_vi32_t xm)
{
    lt_mask16_t np = (lt_mask16_t)(k & ~S->par[a]), pp = (lt_mask16_t)(k & S->par[a]), r = 0;
    if (np != 0) {
        lt_vq30_t tm = lt__ssb_tcross_q30(S, a, np, xm);
        r = (lt_mask16_t)(lt_vq30_cmpge_m((lt_mask16_t)(np & ~S->neg[a]), t, tm) |
                          lt_vq30_cmplt_m((lt_mask16_t)(np & S->neg[a]), t, tm));
    }
    if (pp != 0) {
        const lt_vq16_t *o = a ? &S->r->y : &S->r->x;
        int i;
        LT_CHARGE(SSB_Q_SIDE_PAR);
        for (i = 0; i < LT_LANES; i++)
            if (LT__ON(pp, i) && (int64_t)o->l[i] >= (int64_t)xm.l[i] * 65536)
                r = (lt_mask16_t)(r | (1u << i));
    }
    return r;
}

/* The per-ray part of the clip: validity of lane i of r, the normalised reciprocals and signs
 * per axis (m = 0, sh = 1 for a parallel axis) and [tmin, tmax] cut at w = 0 (rounded down).
 * Returns 0 for an invalid ray (outputs at their defaults: t0 = t1 = 0). */
static int ssb_ray_lane_q30(const lt_qray16_q30_t *r, int i, int32_t m[2], int32_t sh[2],
                            int par[2], int neg[2], int32_t *t0, int32_t *t1)
{
    const int64_t lim = (int64_t)1 << (LT_QT_RAY_MAX_LOG2 + 16);
    int64_t x = r->x.l[i], y = r->y.l[i], ex = x + r->dx.l[i], ey = y + r->dy.l[i];
    int a;
    *t0 = *t1 = 0;
    for (a = 0; a < 2; a++) {
        m[a] = 0;
        sh[a] = 1;
        par[a] = neg[a] = 0;
    }
    if (x < -lim || x > lim || y < -lim || y > lim || ex < -lim || ex > lim || ey < -lim ||
        ey > lim || r->w.l[i] < 0 || r->tmin.l[i] < 0 || r->tmin.l[i] > r->tmax.l[i] ||
        r->tmax.l[i] > LT_Q30_ONE)
        return 0;
    for (a = 0; a < 2; a++) {
        int32_t dv = a ? r->dy.l[i] : r->dx.l[i];
        if (dv == 0) {
            par[a] = 1;
        } else {
            uint32_t dd = dv < 0 ? (uint32_t)0 - (uint32_t)dv : (uint32_t)dv;
            unsigned n = lt__clz32(dd);
            uint64_t D = (uint64_t)dd << n;
            uint64_t mm = (((uint64_t)1 << 62) + D / 2u) / D;
            if (mm > (uint64_t)INT32_MAX)
                mm = (uint64_t)INT32_MAX;
            m[a] = (int32_t)mm;
            sh[a] = (int32_t)(32u - n);
            neg[a] = dv < 0;
        }
    }
    *t0 = r->tmin.l[i];
    *t1 = r->tmax.l[i];
    /* w >= 0: stop at the point at infinity (rounded down) */
    if (r->dw.l[i] < 0) {
        int64_t tw = lt__divfloor64((int64_t)r->w.l[i] * ((int64_t)1 << 30), -(int64_t)r->dw.l[i]);
        if (tw < *t1)
            *t1 = (int32_t)tw;
    }
    return 1;
}

/* A parallel ray's coordinate o lies outside [0, ext) pixels. */
LT_INLINE int ssb_par_outside(int32_t o, int32_t ext)
{
    return o < 0 || (int64_t)o >= (int64_t)ext * 65536;
}

int lt__ssb_clip1_q30(uint32_t width, uint32_t height, const lt_qray16_q30_t *r, int i,
                      lt__ssb_ray1_q30_t *R, int32_t *t0, int32_t *t1)
{
    int a;
    R->o[0] = r->x.l[i];
    R->o[1] = r->y.l[i];
    R->d[0] = r->dx.l[i];
    R->d[1] = r->dy.l[i];
    R->w = r->w.l[i];
    R->dw = r->dw.l[i];
    if (!ssb_ray_lane_q30(r, i, R->m, R->sh, R->par, R->neg, t0, t1))
        return 0;
    LT_CHARGE_N(QT1_WLIM, R->dw < 0);
    for (a = 0; a < 2; a++) {
        int32_t ext = (int32_t)(a ? height : width);
        LT_CHARGE_N(QT1_RCP, !R->par[a]);
        LT_CHARGE_N(QT1_CROSS, R->par[a] ? 0 : 2);
        if (R->par[a]) {
            if (ssb_par_outside(R->o[a], ext))
                *t1 = -1;
        } else {
            int32_t te = lt__ssb_tcross1_q30(R, a, R->neg[a] ? ext : 0);
            int32_t tx = lt__ssb_tcross1_q30(R, a, R->neg[a] ? 0 : ext);
            *t0 = *t0 > te ? *t0 : te;
            *t1 = *t1 < tx ? *t1 : tx;
        }
    }
    return 1;
}

/* Ray setup and clip (the quadtree's setup; lt__ssb_setup_q30 adds the major axis): validity
 * (end points |x|, |y| <= 2^14 px, w >= 0, 0 <= tmin <= tmax <= 1), normalised reciprocals per
 * axis, and the clip of [tmin, tmax] to the image (x in [0, W], y in [0, H] through
 * lt__ssb_tcross_q30; a parallel lane is inside iff 0 <= o < ext) and to w >= 0 (rounded down).
 * Returns the lanes with a non-empty interval; *bad receives the invalid lanes (t0 = t1 = 0
 * there); S->ymaj is 0. Cost: SSB_Q_CLIP (VDIV x3, VCMP x12, VALU x12) and four crossings. */
lt_mask16_t lt__ssb_clip_q30(uint32_t width, uint32_t height, const lt_qray16_q30_t *r,
                             lt_mask16_t k, lt__ssb_setup_q30_t *S, lt_vq30_t *t0,
                             lt_vq30_t *t1, lt_mask16_t *bad)
{
    unsigned okm = 0;
    int i, a;

    S->r = r;
    S->par[0] = S->par[1] = S->neg[0] = S->neg[1] = 0;
    S->ymaj = 0;
    LT_CHARGE(SSB_Q_CLIP);
    for (i = 0; i < LT_LANES; i++) {
        int32_t m[2] = {0, 0}, sh[2] = {1, 1};
        int par[2], neg[2];
        t0->l[i] = 0;
        t1->l[i] = 0;
        if (LT__ON(k, i) &&
            ssb_ray_lane_q30(r, i, m, sh, par, neg, &t0->l[i], &t1->l[i])) {
            okm |= 1u << i;
            for (a = 0; a < 2; a++) {
                S->par[a] = (lt_mask16_t)(S->par[a] | ((unsigned)par[a] << i));
                S->neg[a] = (lt_mask16_t)(S->neg[a] | ((unsigned)neg[a] << i));
            }
        }
        for (a = 0; a < 2; a++) {
            S->m[a].l[i] = m[a];
            S->sh[a].l[i] = sh[a];
        }
    }
    *bad = (lt_mask16_t)(k & ~okm);
    k = (lt_mask16_t)okm;
    /* image clip per axis: entering at the near edge, leaving at the far one */
    for (a = 0; a < 2; a++) {
        int32_t ext = (int32_t)(a ? height : width);
        lt_mask16_t kn = (lt_mask16_t)(k & ~S->par[a]), neg = S->neg[a];
        lt_vi32_t lo = lt_vi32_blend(neg, lt_vi32_set1(0), lt_vi32_set1(ext));
        lt_vi32_t hi = lt_vi32_blend(neg, lt_vi32_set1(ext), lt_vi32_set1(0));
        lt_vq30_t te = lt__ssb_tcross_q30(S, a, kn, lo), tx = lt__ssb_tcross_q30(S, a, kn, hi);
        *t0 = lt_vq30_blend(kn, *t0, lt_vq30_max(*t0, te));
        *t1 = lt_vq30_blend(kn, *t1, lt_vq30_min(*t1, tx));
        for (i = 0; i < LT_LANES; i++) {
            if (LT__ON(k & S->par[a], i) && ssb_par_outside(a ? r->y.l[i] : r->x.l[i], ext))
                t1->l[i] = -1;
        }
    }
    return lt_vq30_cmplt_m(k, *t0, *t1);
}

/* Ray setup and clip (lt__ssb_clip_q30), then the major axis of the valid lanes: |dy| > |dx|
 * (ties and point rays: x). Cost: lt__ssb_clip_q30 + SSB_Q_MAJOR (VCMP x1). */
lt_mask16_t lt__ssb_setup_q30(uint32_t width, uint32_t height, const lt_qray16_q30_t *r,
                              lt_mask16_t k, lt__ssb_setup_q30_t *S, lt_vq30_t *t0,
                              lt_vq30_t *t1, lt_mask16_t *bad)
{
    lt_mask16_t lanes = lt__ssb_clip_q30(width, height, r, k, S, t0, t1, bad);
    lt_mask16_t ok = (lt_mask16_t)(k & ~*bad);
    unsigned ym = 0;
    int i;
    LT_CHARGE(SSB_Q_MAJOR);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(ok, i)) {
            uint32_t ax = (uint32_t)r->dx.l[i], ay = (uint32_t)r->dy.l[i];
            ax = r->dx.l[i] < 0 ? (uint32_t)0 - ax : ax;
            ay = r->dy.l[i] < 0 ? (uint32_t)0 - ay : ay;
            if (ay > ax)
                ym |= 1u << i;
        }
    }
    S->ymaj = (lt_mask16_t)ym;
    return lanes;
}

/* w of the pixels base[idx] for the lanes in k (0 elsewhere); negative raws are holes (0).
 * Cost: LANE_GATHER per active lane (VGATHER x1; LT_MEM at each pixel's address),
 * SSB_Q_PIX_HOLES (VALU x1). */
lt_vq30_t lt__ssb_gather_pix_q30(const lt_q30_t *base, lt_vi32_t idx, lt_mask16_t k)
{
    lt_vq30_t r;
    int i;
    LT_CHARGE_N(LANE_GATHER, lt__popcount32(k));
    LT_CHARGE(SSB_Q_PIX_HOLES);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        r.l[i] = 0;
        if (LT__ON(k, i)) {
            const lt_q30_t *p = &base[(uint32_t)idx.l[i]];
            LT_MEM(p, sizeof *p, LT_MEM_READ);
            r.l[i] = *p < 0 ? 0 : *p;
        }
    }
    return r;
}

/* Shell bounds in s1.60: lo = w_s k (s1.30 x s1.30, exact), hi = w_s 2^30 (exact).
 * Cost: SSB_Q_SHELL_LO (VMUL x1); SSB_Q_SHELL_HI (VSHIFT x1). */
lt_vql60_t lt__ssb_shell_lo_q30(lt_mask16_t k, lt_vq30_t ws, lt_q30_t kq)
{
    lt_vql60_t r;
    int i;
    LT_CHARGE(SSB_Q_SHELL_LO);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = LT__ON(k, i) ? lt__mul32x32_64(ws.l[i], kq) : 0;
    return r;
}

lt_vql60_t lt__ssb_shell_hi_q30(lt_mask16_t k, lt_vq30_t ws)
{
    lt_vql60_t r;
    int i;
    LT_CHARGE(SSB_Q_SHELL_HI);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = LT__ON(k, i) ? (int64_t)ws.l[i] * ((int64_t)1 << 30) : 0;
    return r;
}

/* 1 / (1 + theta) in s1.30, half up: 2^60 / (2^30 + theta) (theta >= 0, so in (1/3, 1]). */
lt_q30_t lt__ssb_kthick_q30(lt_q30_t theta)
{
    return (lt_q30_t)lt__div_round64((int64_t)1 << 60, (int64_t)LT_Q30_ONE + theta);
}

/* ==== float32 ================================================================================= */
#if LT_CFG_FLOAT32

/* t = (X - o) * (1 / d): monotonic in X. Cost: SSB_F_TCROSS (VCVT x1, FADD x1, FMUL x1). */
lt_vf32_t lt__ssb_tcross_f32(const lt__ssb_setup_f32_t *S, int a, lt_mask16_t k, lt_vi32_t X)
{
    const lt_vf32_t *o = a ? &S->r->y : &S->r->x;
    lt_vf32_t t;
    int i;
    LT_CHARGE(SSB_F_TCROSS);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        t.l[i] = LT__ON(k, i) ? ((float)X.l[i] - o->l[i]) * S->rcp[a].l[i] : 0.0f;
    return t;
}

/* n half pixels along each lane's major axis: (n * 0.5) * |1 / d|, monotonic in n.
 * Cost: SSB_F_TSPAN (VALU x1, VCVT x1, FMUL x2, FADD x1). */
lt_vf32_t lt__ssb_tspan_f32(const lt__ssb_setup_f32_t *S, lt_mask16_t ky, lt_mask16_t k,
                            lt_vi32_t n)
{
    lt_vf32_t t;
    int i;
    LT_CHARGE(SSB_F_TSPAN);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        int a = (int)LT__ON(ky, i);
        t.l[i] = LT__ON(k, i) ? ((float)n.l[i] * 0.5f) * lt__f32_abs(S->rcp[a].l[i]) : 0.0f;
    }
    return t;
}

/* floor(o + t d) on axis a (|.| < 2^15 for valid rays, so the conversion is defined).
 * Cost: SSB_F_PIXEL (FMUL x1, FADD x1, VCVT x2, FCMP x1). */
lt_vi32_t lt__ssb_pixel_f32(const lt__ssb_setup_f32_t *S, int a, lt_mask16_t k, lt_vf32_t t)
{
    const lt_vf32_t *o = a ? &S->r->y : &S->r->x;
    const lt_vf32_t *d = a ? &S->r->dy : &S->r->dx;
    lt_vi32_t p;
    int i;
    LT_CHARGE(SSB_F_PIXEL);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        p.l[i] = 0;
        if (LT__ON(k, i)) {
            float v = o->l[i] + t.l[i] * d->l[i];
            int32_t q;
            if (!(v > -32768.0f))
                v = -32768.0f;
            if (v > 32767.0f)
                v = 32767.0f;
            q = (int32_t)v;
            if ((float)q > v)
                q--;
            p.l[i] = q;
        }
    }
    return p;
}

/* w + t dw (also the float32 w_at). Cost: SSB_F_WRAY (FMUL x1, FADD x1). */
lt_vf32_t lt__ssb_wray_f32(const lt__ssb_setup_f32_t *S, lt_mask16_t k, lt_vf32_t t)
{
    lt_vf32_t w;
    int i;
    LT_CHARGE(SSB_F_WRAY);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        w.l[i] = LT__ON(k, i) ? S->r->w.l[i] + t.l[i] * S->r->dw.l[i] : 0.0f;
    return w;
}

/* tn + (tf - tn) (fn / (fn - ff)), fn >= 0 >= ff, fn - ff > 0 (else tn).
 * Cost: SSB_F_HIT_T (FDIV x1, FADD x3, FMUL x1). */
lt_vf32_t lt__ssb_hit_t_f32(lt_mask16_t k, lt_vf32_t tn, lt_vf32_t tf, lt_vf32_t fn,
                            lt_vf32_t ff)
{
    int i;
    LT_CHARGE(SSB_F_HIT_T);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(k, i)) {
            float den = fn.l[i] - ff.l[i];
            if (den > 0.0f)
                tn.l[i] = tn.l[i] + (tf.l[i] - tn.l[i]) * (fn.l[i] / den);
        }
    }
    return tn;
}

/* As lt__ssb_child_side_q30. Cost: lt__ssb_tcross_f32 + lt_vf32_cmpge_m, lt_vf32_cmplt_m when a
 * lane moves on the axis; SSB_F_SIDE_PAR (FCMP x1) when a lane is parallel to it. */
lt_mask16_t lt__ssb_child_side_f32(const lt__ssb_setup_f32_t *S, int a, lt_mask16_t k,
                                   lt_vf32_t t, lt_vi32_t xm)
{
    lt_mask16_t np = (lt_mask16_t)(k & ~S->par[a]), pp = (lt_mask16_t)(k & S->par[a]), r = 0;
    if (np != 0) {
        lt_vf32_t tm = lt__ssb_tcross_f32(S, a, np, xm);
        r = (lt_mask16_t)(lt_vf32_cmpge_m((lt_mask16_t)(np & ~S->neg[a]), t, tm) |
                          lt_vf32_cmplt_m((lt_mask16_t)(np & S->neg[a]), t, tm));
    }
    if (pp != 0) {
        const lt_vf32_t *o = a ? &S->r->y : &S->r->x;
        int i;
        LT_CHARGE(SSB_F_SIDE_PAR);
        for (i = 0; i < LT_LANES; i++)
            if (LT__ON(pp, i) && o->l[i] >= (float)xm.l[i])
                r = (lt_mask16_t)(r | (1u << i));
    }
    return r;
}

/* As lt__ssb_clip_q30 in float32 (the quadtree's float32 setup): NaN or infinite inputs are
 * BADRAY. Cost: SSB_F_CLIP (FDIV x3, FCMP x12, FADD x6) and four crossings. */
lt_mask16_t lt__ssb_clip_f32(uint32_t width, uint32_t height, const lt_qray16_f32_t *r,
                             lt_mask16_t k, lt__ssb_setup_f32_t *S, lt_vf32_t *t0,
                             lt_vf32_t *t1, lt_mask16_t *bad)
{
    const float lim = (float)(1u << LT_QT_RAY_MAX_LOG2);
    unsigned okm = 0;
    int i, a;
    S->r = r;
    S->par[0] = S->par[1] = S->neg[0] = S->neg[1] = 0;
    S->ymaj = 0;
    LT_CHARGE(SSB_F_CLIP);
    for (i = 0; i < LT_LANES; i++) {
        float x = r->x.l[i], y = r->y.l[i], ex = x + r->dx.l[i], ey = y + r->dy.l[i];
        t0->l[i] = 0.0f;
        t1->l[i] = 0.0f;
        S->rcp[0].l[i] = S->rcp[1].l[i] = 0.0f;
        if (!LT__ON(k, i))
            continue;
        /* written as negations of the valid ranges so that NaN fails every test */
        if (!(x >= -lim && x <= lim && y >= -lim && y <= lim && ex >= -lim && ex <= lim &&
              ey >= -lim && ey <= lim && r->w.l[i] >= 0.0f && r->w.l[i] <= LT__SSB_F32_MAX &&
              r->dw.l[i] >= -LT__SSB_F32_MAX && r->dw.l[i] <= LT__SSB_F32_MAX && r->tmin.l[i] >= 0.0f &&
              r->tmin.l[i] <= r->tmax.l[i] && r->tmax.l[i] <= 1.0f))
            continue;
        okm |= 1u << i;
        for (a = 0; a < 2; a++) {
            float dv = a ? r->dy.l[i] : r->dx.l[i];
            if (dv == 0.0f) {
                S->par[a] = (lt_mask16_t)(S->par[a] | (1u << i));
            } else {
                S->rcp[a].l[i] = 1.0f / dv;
                if (dv < 0.0f)
                    S->neg[a] = (lt_mask16_t)(S->neg[a] | (1u << i));
            }
        }
        t0->l[i] = r->tmin.l[i];
        t1->l[i] = r->tmax.l[i];
        if (r->dw.l[i] < 0.0f) {
            float tw = r->w.l[i] / -r->dw.l[i];
            if (tw < t1->l[i])
                t1->l[i] = tw;
        }
    }
    *bad = (lt_mask16_t)(k & ~okm);
    k = (lt_mask16_t)okm;
    for (a = 0; a < 2; a++) {
        int32_t ext = (int32_t)(a ? height : width);
        lt_mask16_t kn = (lt_mask16_t)(k & ~S->par[a]), neg = S->neg[a];
        lt_vi32_t lo = lt_vi32_blend(neg, lt_vi32_set1(0), lt_vi32_set1(ext));
        lt_vi32_t hi = lt_vi32_blend(neg, lt_vi32_set1(ext), lt_vi32_set1(0));
        lt_vf32_t te = lt__ssb_tcross_f32(S, a, kn, lo), tx = lt__ssb_tcross_f32(S, a, kn, hi);
        *t0 = lt_vf32_blend(kn, *t0, lt_vf32_max(*t0, te));
        *t1 = lt_vf32_blend(kn, *t1, lt_vf32_min(*t1, tx));
        for (i = 0; i < LT_LANES; i++) {
            if (LT__ON(k & S->par[a], i)) {
                float o = a ? r->y.l[i] : r->x.l[i];
                if (!(o >= 0.0f && o < (float)ext))
                    t1->l[i] = -1.0f;
            }
        }
    }
    return lt_vf32_cmplt_m(k, *t0, *t1);
}

/* As lt__ssb_setup_q30: lt__ssb_clip_f32, then the major axis |dy| > |dx| of the valid lanes.
 * Cost: lt__ssb_clip_f32 + SSB_F_MAJOR (FCMP x1). */
lt_mask16_t lt__ssb_setup_f32(uint32_t width, uint32_t height, const lt_qray16_f32_t *r,
                              lt_mask16_t k, lt__ssb_setup_f32_t *S, lt_vf32_t *t0,
                              lt_vf32_t *t1, lt_mask16_t *bad)
{
    lt_mask16_t lanes = lt__ssb_clip_f32(width, height, r, k, S, t0, t1, bad);
    lt_mask16_t ok = (lt_mask16_t)(k & ~*bad);
    unsigned ym = 0;
    int i;
    LT_CHARGE(SSB_F_MAJOR);
    for (i = 0; i < LT_LANES; i++)
        if (LT__ON(ok, i) && lt__f32_abs(r->dy.l[i]) > lt__f32_abs(r->dx.l[i]))
            ym |= 1u << i;
    S->ymaj = (lt_mask16_t)ym;
    return lanes;
}

/* w of base[idx] for the lanes in k; NaN, +-inf and w <= 0 are holes (0).
 * Cost: LANE_GATHER per active lane (VGATHER x1), SSB_F_PIX_HOLES (FCMP x2). */
lt_vf32_t lt__ssb_gather_pix_f32(const float *base, lt_vi32_t idx, lt_mask16_t k)
{
    lt_vf32_t r;
    int i;
    LT_CHARGE_N(LANE_GATHER, lt__popcount32(k));
    LT_CHARGE(SSB_F_PIX_HOLES);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        r.l[i] = 0.0f;
        if (LT__ON(k, i)) {
            const float *p = &base[(uint32_t)idx.l[i]];
            float v;
            LT_MEM(p, sizeof *p, LT_MEM_READ);
            v = *p;
            r.l[i] = (v > 0.0f && v <= LT__SSB_F32_MAX) ? v : 0.0f;
        }
    }
    return r;
}

/* Shell bounds: lo = w_s k (hi = w_s: lt__ssb_shell_hi_f32, lt_ssb.h). Cost: SSB_F_SHELL_LO
 * (FMUL x1). */
lt_vf32_t lt__ssb_shell_lo_f32(lt_mask16_t k, lt_vf32_t ws, float kf)
{
    int i;
    LT_CHARGE(SSB_F_SHELL_LO);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        ws.l[i] = LT__ON(k, i) ? ws.l[i] * kf : 0.0f;
    return ws;
}

#endif /* LT_CFG_FLOAT32 */
