/* lt_ssb.h - internal header of the screen-space ray helpers (lt_ssb.c), shared by the sibling
 * screen-space tracers lt_qt.c (the quadtree), lt_ssdda.c (DDA) and lt_hiz.c (Hi-Z): the
 * per-packet ray state after setup and the lane routines over it, s1.30 (lt__ssb_*_q30) and
 * float32 (lt__ssb_*_f32). Each routine is defined once in lt_ssb.c and charges its own recipe of
 * lt_recipes.def (SSB_*, named on the Cost: lines below); the kernel templates lt_ssdda.inc /
 * lt_hiz.inc reach them through the SS_* traits of lt_ssb_q30.inc and lt_ssb_f32.inc, lt_qt.inc
 * through lt_qt.c's LTQ_* traits. Not part of the public API. Builds: all; the float32 half only
 * with LT_CFG_FLOAT32.
 */
#ifndef LT_SSB_H
#define LT_SSB_H

#include "lt/lt_ssdda.h"

/* ==== s1.30 w and t, s15.16 pixels, int64 wide values ========================================= */

/* Per-lane ray state after setup. */
typedef struct lt__ssb_setup_q30 {
    const lt_qray16_q30_t *r;
    lt_vi32_t m[2];      /* per axis: 2^62 / (|d| 2^n) rounded, in (2^30, 2^31] */
    lt_vi32_t sh[2];     /* per axis: 32 - n, the right shift after the product */
    lt_mask16_t par[2];  /* d == 0 on that axis */
    lt_mask16_t neg[2];  /* d < 0 on that axis */
    lt_mask16_t ymaj;    /* |dy| > |dx|: y is the DDA's major axis (0 after lt__ssb_clip_q30) */
} lt__ssb_setup_q30_t;

/* One ray after setup: lane i of a packet as scalars, the single-ray twin of
 * lt__ssb_setup_q30_t (lt__ssb_clip1_q30 fills it; the quadtree's single-ray walk uses it). */
typedef struct lt__ssb_ray1_q30 {
    int32_t o[2], d[2]; /* x, y and dx, dy, s15.16 */
    int32_t w, dw;      /* s1.30 */
    int32_t m[2], sh[2]; /* as lt__ssb_setup_q30_t's, per axis */
    int par[2], neg[2];  /* d == 0, d < 0 on that axis */
} lt__ssb_ray1_q30_t;

/* The lane bodies: one definition of each routine's per-lane arithmetic, which the 16-lane
 * routines below loop over and the single-ray walk calls directly, so that both give the same
 * bits (no charge: their callers charge). */

/* Round a value with f >= 1 fractional bits to an integer, half up. */
LT_INLINE int64_t lt__ssb_rnd_q30(int64_t v, unsigned f)
{
    return lt__asr64(v + ((int64_t)1 << (f - 1u)), f);
}

/* w of the ray at t in s1.60: w 2^30 + dw t (exact, |.| < 2^62). */
LT_INLINE int64_t lt__ssb_wray_lane_q30(int32_t w, int32_t dw, int32_t t)
{
    return (int64_t)w * ((int64_t)1 << 30) + lt__mul32x32_64(dw, t);
}

/* As lt__ssb_wray_lane_q30 for lane i of a packet. */
LT_INLINE int64_t lt__ssb_wray1_q30(const lt_qray16_q30_t *r, int i, int32_t t)
{
    return lt__ssb_wray_lane_q30(r->w.l[i], r->dw.l[i], t);
}

/* t = (X - o) / d for an integer pixel coordinate X: (X 2^16 - o) m >> sh, half up, negated
 * for d < 0, saturated (lt__ssb_tcross_q30's lane). */
LT_INLINE int32_t lt__ssb_tcross_lane_q30(int32_t o, int32_t m, int32_t sh, int neg, int32_t X)
{
    int64_t num = (int64_t)X * 65536 - o;
    int64_t q = lt__ssb_rnd_q30(num * m, (unsigned)sh);
    return lt__ssat32(neg ? -q : q);
}

/* The zero of a linear function on [tn, tf] (lt__ssb_hit_t_q30's lane; fn - ff == 0 keeps tn). */
LT_INLINE int32_t lt__ssb_hit_t_lane_q30(int32_t tn, int32_t tf, int64_t fn, int64_t ff)
{
    uint64_t num = (uint64_t)fn, den = num + (uint64_t)(-ff);
    unsigned b = 64u - lt__clz64(den), s = b > 31u ? b - 31u : 0u;
    int64_t n = (int64_t)(num >> s), dd = (int64_t)(den >> s);
    int64_t span = (int64_t)tf - tn;
    if (dd == 0)
        return tn;
    return lt__ssat32((int64_t)tn + lt__div_round64(n * span, dd));
}

/* w_ray(t) rounded half up to s1.30, saturated (lt__ssb_w_at_q30's lane). */
LT_INLINE int32_t lt__ssb_w_at_lane_q30(int32_t w, int32_t dw, int32_t t)
{
    return lt__ssat32(lt__ssb_rnd_q30(lt__ssb_wray_lane_q30(w, dw, t), 30u));
}

/* Crossing of one ray after lt__ssb_clip1_q30 on axis a (0 x, 1 y). */
LT_INLINE int32_t lt__ssb_tcross1_q30(const lt__ssb_ray1_q30_t *R, int a, int32_t X)
{
    return lt__ssb_tcross_lane_q30(R->o[a], R->m[a], R->sh[a], R->neg[a], X);
}

/* t = (X - o) / d on axis a for integer pixel coordinates X. Cost: SSB_Q_TCROSS (VALU x2, VMUL x1,
 * VSHIFT x2). */
lt_vq30_t lt__ssb_tcross_q30(const lt__ssb_setup_q30_t *S, int a, lt_mask16_t k, lt_vi32_t X);
/* The t span of n half pixels along each lane's major axis. Cost: SSB_Q_TSPAN (VALU x1, VMUL x1,
 * VSHIFT x2). */
lt_vq30_t lt__ssb_tspan_q30(const lt__ssb_setup_q30_t *S, lt_mask16_t ky, lt_mask16_t k,
                            lt_vi32_t n);
/* floor(o + d t) on axis a. Cost: SSB_Q_PIXEL (VMUL x1, VMULW x1, VSHIFT x1). */
lt_vi32_t lt__ssb_pixel_q30(const lt__ssb_setup_q30_t *S, int a, lt_mask16_t k, lt_vq30_t t);
/* w_ray(t) in s1.60. Cost: SSB_Q_WRAY (VMUL x1, VMULW x1, VSHIFT x1). */
lt_vql60_t lt__ssb_wray_q30(const lt__ssb_setup_q30_t *S, lt_mask16_t k, lt_vq30_t t);
/* w_ray(t) rounded half up to s1.30. Cost: SSB_Q_W_AT (VMUL x1, VMULW x1, VSHIFT x1). */
lt_vq30_t lt__ssb_w_at_q30(const lt__ssb_setup_q30_t *S, lt_mask16_t k, lt_vq30_t t);
/* The zero of a linear function on [tn, tf]. Cost: SSB_Q_HIT_T (VDIV x1, VALU x4, VMUL x1). */
lt_vq30_t lt__ssb_hit_t_q30(lt_mask16_t k, lt_vq30_t tn, lt_vq30_t tf, lt_vql60_t fn,
                            lt_vql60_t ff);
/* Lanes past the midline xm of a cell on axis a. Cost: lt__ssb_tcross_q30 and two compares
 * (lt_vq30_cmpge_m, lt_vq30_cmplt_m) for the moving lanes, SSB_Q_SIDE_PAR (VCMP x1) when a lane is
 * parallel to the axis. */
lt_mask16_t lt__ssb_child_side_q30(const lt__ssb_setup_q30_t *S, int a, lt_mask16_t k,
                                   lt_vq30_t t, lt_vi32_t xm);
/* Ray setup and clip to the image and to w >= 0 (the quadtree's setup; S->ymaj = 0). Cost:
 * SSB_Q_CLIP (VDIV x3, VCMP x12, VALU x12), four crossings (lt__ssb_tcross_q30) and the clip's lane
 * ops (blends, min / max, set1, the final compare). */
lt_mask16_t lt__ssb_clip_q30(uint32_t width, uint32_t height, const lt_qray16_q30_t *r,
                             lt_mask16_t k, lt__ssb_setup_q30_t *S, lt_vq30_t *t0,
                             lt_vq30_t *t1, lt_mask16_t *bad);
/* lt__ssb_clip_q30 for lane i of r alone, into the scalars of *R: the same validity, reciprocals
 * and clip, so [*t0, *t1) equals that lane's. Returns 0 for an invalid ray (*t0 = *t1 = 0), else
 * 1 (the interval may be empty: *t0 >= *t1). Cost: for a valid ray QT1_WLIM when dw < 0 and per
 * axis it moves along QT1_RCP and 2 QT1_CROSS (the rest is the caller's QT1_SETUP). */
int lt__ssb_clip1_q30(uint32_t width, uint32_t height, const lt_qray16_q30_t *r, int i,
                      lt__ssb_ray1_q30_t *R, int32_t *t0, int32_t *t1);
/* lt__ssb_clip_q30 plus the major axis (S->ymaj) of the valid lanes (the DDA's and Hi-Z's setup).
 * Cost: lt__ssb_clip_q30 + SSB_Q_MAJOR (VCMP x1). */
lt_mask16_t lt__ssb_setup_q30(uint32_t width, uint32_t height, const lt_qray16_q30_t *r,
                              lt_mask16_t k, lt__ssb_setup_q30_t *S, lt_vq30_t *t0,
                              lt_vq30_t *t1, lt_mask16_t *bad);
/* w of the pixels base[idx], holes 0. Cost: LANE_GATHER per active lane (VGATHER x1),
 * SSB_Q_PIX_HOLES (VALU x1). */
lt_vq30_t lt__ssb_gather_pix_q30(const lt_q30_t *base, lt_vi32_t idx, lt_mask16_t k);
/* Shell bounds in s1.60: lo = w_s k (SSB_Q_SHELL_LO: VMUL x1), hi = w_s 2^30 (SSB_Q_SHELL_HI:
 * VSHIFT x1). */
lt_vql60_t lt__ssb_shell_lo_q30(lt_mask16_t k, lt_vq30_t ws, lt_q30_t kq);
lt_vql60_t lt__ssb_shell_hi_q30(lt_mask16_t k, lt_vq30_t ws);
/* 1 / (1 + theta) in s1.30, half up (a set-up constant, no charge). */
lt_q30_t lt__ssb_kthick_q30(lt_q30_t theta);

/* ==== float32 ================================================================================= */
#if LT_CFG_FLOAT32

#define LT__SSB_F32_MAX 3.40282347e38f

typedef struct lt__ssb_setup_f32 {
    const lt_qray16_f32_t *r;
    lt_vf32_t rcp[2];    /* 1 / d per axis (0 for parallel lanes) */
    lt_mask16_t par[2];  /* d == +-0 */
    lt_mask16_t neg[2];  /* d < 0 */
    lt_mask16_t ymaj;    /* |dy| > |dx| */
} lt__ssb_setup_f32_t;

/* As the s1.30 routines above, charging the SSB_F_* recipes (lt_ssb.c). */
lt_vf32_t lt__ssb_tcross_f32(const lt__ssb_setup_f32_t *S, int a, lt_mask16_t k, lt_vi32_t X);
lt_vf32_t lt__ssb_tspan_f32(const lt__ssb_setup_f32_t *S, lt_mask16_t ky, lt_mask16_t k,
                            lt_vi32_t n);
lt_vi32_t lt__ssb_pixel_f32(const lt__ssb_setup_f32_t *S, int a, lt_mask16_t k, lt_vf32_t t);
lt_vf32_t lt__ssb_wray_f32(const lt__ssb_setup_f32_t *S, lt_mask16_t k, lt_vf32_t t);
lt_vf32_t lt__ssb_hit_t_f32(lt_mask16_t k, lt_vf32_t tn, lt_vf32_t tf, lt_vf32_t fn,
                            lt_vf32_t ff);
lt_mask16_t lt__ssb_child_side_f32(const lt__ssb_setup_f32_t *S, int a, lt_mask16_t k,
                                   lt_vf32_t t, lt_vi32_t xm);
lt_mask16_t lt__ssb_clip_f32(uint32_t width, uint32_t height, const lt_qray16_f32_t *r,
                             lt_mask16_t k, lt__ssb_setup_f32_t *S, lt_vf32_t *t0,
                             lt_vf32_t *t1, lt_mask16_t *bad);
lt_mask16_t lt__ssb_setup_f32(uint32_t width, uint32_t height, const lt_qray16_f32_t *r,
                              lt_mask16_t k, lt__ssb_setup_f32_t *S, lt_vf32_t *t0,
                              lt_vf32_t *t1, lt_mask16_t *bad);
lt_vf32_t lt__ssb_gather_pix_f32(const float *base, lt_vi32_t idx, lt_mask16_t k);
lt_vf32_t lt__ssb_shell_lo_f32(lt_mask16_t k, lt_vf32_t ws, float kf);

/* Shell upper bound: w_s itself (no op, no charge). */
LT_INLINE lt_vf32_t lt__ssb_shell_hi_f32(lt_mask16_t k, lt_vf32_t ws)
{
    (void)k;
    return ws;
}

#endif /* LT_CFG_FLOAT32 */
#endif /* LT_SSB_H */
