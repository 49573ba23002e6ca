/* lt_ssb.h - internal header of the screen-space baselines' ray helpers (lt_ssb.c), shared by the
 * sibling screen-space tracers lt_ssdda.c (DDA) and lt_hiz.c (Hi-Z): the per-packet ray state
 * after setup and the lane routines over it, s1.30 (lt__ssb_*_q30) and float32 (lt__ssb_*_f32).
 * Each routine is defined once in lt_ssb.c and charges its own tally (the Cost: lines there); the
 * kernel templates lt_ssdda.inc / lt_hiz.inc reach them through the SS_* traits of lt_ssb_q30.inc
 * and lt_ssb_f32.inc. Not part of the public API. Builds: all; the float32 half only with
 * LT_CFG_FLOAT32.
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
    lt_mask16_t ymaj;    /* |dy| > |dx|: y is the DDA's major axis */
} lt__ssb_setup_q30_t;

/* t = (X - o) / d on axis a for integer pixel coordinates X. Cost: VALU x2, VMUL x1, VSHIFT x2. */
lt_vq30_t lt__ssb_tcross_q30(const lt__ssb_setup_q30_t *S, int a, lt_mask16_t k, lt_vi32_t X);
/* The t span of n half pixels along each lane's major axis. Cost: VALU x1, VMUL x1, VSHIFT x2. */
lt_vq30_t lt__ssb_tspan_q30(const lt__ssb_setup_q30_t *S, lt_mask16_t ky, lt_mask16_t k,
                            lt_vi32_t n);
/* floor(o + d t) on axis a. Cost: VMUL x1, VMULW x1, VSHIFT x1. */
lt_vi32_t lt__ssb_pixel_q30(const lt__ssb_setup_q30_t *S, int a, lt_mask16_t k, lt_vq30_t t);
/* w_ray(t) in s1.60. Cost: VMUL x1, VMULW x1, VSHIFT x1. */
lt_vql60_t lt__ssb_wray_q30(const lt__ssb_setup_q30_t *S, lt_mask16_t k, lt_vq30_t t);
/* w_ray(t) rounded half up to s1.30. Cost: VMUL x1, VMULW x1, VSHIFT x1. */
lt_vq30_t lt__ssb_w_at_q30(const lt__ssb_setup_q30_t *S, lt_mask16_t k, lt_vq30_t t);
/* The zero of a linear function on [tn, tf]. Cost: VDIV x1, VALU x4, VMUL x1. */
lt_vq30_t lt__ssb_hit_t_q30(lt_mask16_t k, lt_vq30_t tn, lt_vq30_t tf, lt_vql60_t fn,
                            lt_vql60_t ff);
/* Lanes past the midline xm of a cell on axis a. Cost: lt__ssb_tcross_q30 + VCMP x2 (+1). */
lt_mask16_t lt__ssb_child_side_q30(const lt__ssb_setup_q30_t *S, int a, lt_mask16_t k,
                                   lt_vq30_t t, lt_vi32_t xm);
/* Ray setup and clip. Cost: VDIV x3, VCMP x13, VALU x12 and four crossings. */
lt_mask16_t lt__ssb_setup_q30(uint32_t width, uint32_t height, const lt_qray16_q30_t *r,
                              lt_mask16_t k, lt__ssb_setup_q30_t *S, lt_vq30_t *t0,
                              lt_vq30_t *t1, lt_mask16_t *bad);
/* w of the pixels base[idx], holes 0. Cost: VGATHER per active lane, VALU x1. */
lt_vq30_t lt__ssb_gather_pix_q30(const lt_q30_t *base, lt_vi32_t idx, lt_mask16_t k);
/* Shell bounds in s1.60: lo = w_s k (VMUL x1), hi = w_s 2^30 (VSHIFT x1). */
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

/* As the s1.30 routines above; costs in lt_ssb.c. */
lt_vf32_t lt__ssb_tcross_f32(const lt__ssb_setup_f32_t *S, int a, lt_mask16_t k, lt_vi32_t X);
lt_vf32_t lt__ssb_tspan_f32(const lt__ssb_setup_f32_t *S, lt_mask16_t ky, lt_mask16_t k,
                            lt_vi32_t n);
lt_vi32_t lt__ssb_pixel_f32(const lt__ssb_setup_f32_t *S, int a, lt_mask16_t k, lt_vf32_t t);
lt_vf32_t lt__ssb_wray_f32(const lt__ssb_setup_f32_t *S, lt_mask16_t k, lt_vf32_t t);
lt_vf32_t lt__ssb_hit_t_f32(lt_mask16_t k, lt_vf32_t tn, lt_vf32_t tf, lt_vf32_t fn,
                            lt_vf32_t ff);
lt_mask16_t lt__ssb_child_side_f32(const lt__ssb_setup_f32_t *S, int a, lt_mask16_t k,
                                   lt_vf32_t t, lt_vi32_t xm);
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
