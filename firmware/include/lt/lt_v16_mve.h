/* lt_v16_mve.h - Arm Helium (M-profile Vector Extension, MVE) sequences for the 32-bit lane ops of
 * lt_v16.h: the 16 lanes as four 128-bit vectors of 4 lanes. Saturating and wrapping adds and
 * subtracts (VQADD, VQSUB, VADD, VSUB), min/max, bitwise or/xor, the compares (VCMP to a lane
 * predicate, folded into the 16-bit lane mask), blends (VPSEL) and the rounded, saturated
 * s15.16 / s1.30 products (VMUL + VMULH for the low and high words of the 64-bit product, the
 * rounding carry, a funnel shift and the int32 clamp). Chosen at build time: a compiler with
 * integer MVE (__ARM_FEATURE_MVE bit 0, e.g. -mcpu=cortex-m55) in a build that counts nothing
 * (LT_COST_OFF); -DLT_LANES_PORTABLE keeps the portable loops of lt_v16.h, which stay the
 * reference. Bit-identical to the portable lanes: tests/golden/vectors.txt is compared on cm55 in
 * both builds (docs/firmware.md, "Lane backends"). Builds: firmware (Cortex-M55) only.
 */
#ifndef LT_V16_MVE_H
#define LT_V16_MVE_H

#if !defined(LT_LANES_PORTABLE) && defined(__ARM_FEATURE_MVE) && (__ARM_FEATURE_MVE & 1) &&      \
    LT_COST_MODE == LT_COST_OFF
#define LT__MVE_LANES 1
#undef LT_LANES_BACKEND
#define LT_LANES_BACKEND "mve"
#include <arm_mve.h>

/* The lane predicate of the 4 lanes of quad q (lanes 4q..4q+3) in mask k: 4 predicate bits per
 * 32-bit lane. */
LT_INLINE mve_pred16_t lt__mve_pred(lt_mask16_t k, unsigned q)
{
    unsigned n = ((unsigned)k >> (4u * q)) & 0xFu;
    return (mve_pred16_t)(((n & 1u) ? 0x000Fu : 0u) | ((n & 2u) ? 0x00F0u : 0u) |
                          ((n & 4u) ? 0x0F00u : 0u) | ((n & 8u) ? 0xF000u : 0u));
}

/* The 4 lane bits of a predicate of 32-bit lanes. */
LT_INLINE unsigned lt__mve_bits(mve_pred16_t p)
{
    unsigned v = (unsigned)p;
    return (v & 1u) | ((v >> 3) & 2u) | ((v >> 6) & 4u) | ((v >> 9) & 8u);
}

/* sat32((a * b + 2^(f-1)) >> f) on 4 lanes, 1 <= f <= 31: the 64-bit product's low word (VMUL) and
 * high word (VMULH), the rounding constant added to the low word with its carry into the high
 * word, the result's low 32 bits by a funnel shift, and the clamp where the product >> f does not
 * fit 32 bits (its bits from 31 up, hi >> (f - 1), are not all equal). */
LT_INLINE int32x4_t lt__mve_mul_round_sat4(int32x4_t a, int32x4_t b, unsigned f)
{
    uint32x4_t lo = vreinterpretq_u32_s32(vmulq_s32(a, b));
    int32x4_t hi = vmulhq_s32(a, b);
    uint32x4_t lo2 = vaddq_n_u32(lo, 1u << (f - 1u));
    mve_pred16_t carry = vcmphiq_u32(lo, lo2); /* lo > lo + rnd: the add wrapped */
    int32x4_t top, r;
    hi = vaddq_m_n_s32(hi, hi, 1, carry);
    /* (hi:lo2) >> f, low 32 bits: lo2 >> f | hi << (32 - f) (f = 32 - f = 0 never occurs) */
    r = vreinterpretq_s32_u32(vorrq_u32(vshlq_u32(lo2, vdupq_n_s32(-(int32_t)f)),
                                        vreinterpretq_u32_s32(vshlq_s32(hi, vdupq_n_s32(32 - (int32_t)f)))));
    top = vshlq_s32(hi, vdupq_n_s32(1 - (int32_t)f)); /* arithmetic: hi >> (f - 1) */
    r = vpselq_s32(vdupq_n_s32(INT32_MAX), r, vcmpgtq_n_s32(top, 0));
    r = vpselq_s32(vdupq_n_s32(INT32_MIN), r, vcmpltq_n_s32(top, -1));
    return r;
}

/* The 16 lanes of the rounded saturated product. */
LT_INLINE void lt__mve_mul_round_sat(const int32_t *a, const int32_t *b, int32_t *r, unsigned f)
{
    unsigned q;
    for (q = 0; q < 4u; q++)
        vst1q_s32(r + 4u * q, lt__mve_mul_round_sat4(vld1q_s32(a + 4u * q), vld1q_s32(b + 4u * q), f));
}

/* r = lanes of b where k, else a. */
LT_INLINE void lt__mve_blend32(lt_mask16_t k, const int32_t *a, const int32_t *b, int32_t *r)
{
    unsigned q;
    for (q = 0; q < 4u; q++)
        vst1q_s32(r + 4u * q, vpselq_s32(vld1q_s32(b + 4u * q), vld1q_s32(a + 4u * q),
                                         lt__mve_pred(k, q)));
}

/* The 4-lane bodies of the binary ops (the names lt_v16.h's LT__V16_BINV instantiations give). */
LT_INLINE int32x4_t lt__mve_qadd(int32x4_t a, int32x4_t b) { return vqaddq_s32(a, b); }
LT_INLINE int32x4_t lt__mve_qsub(int32x4_t a, int32x4_t b) { return vqsubq_s32(a, b); }
LT_INLINE int32x4_t lt__mve_add(int32x4_t a, int32x4_t b) { return vaddq_s32(a, b); }
LT_INLINE int32x4_t lt__mve_sub(int32x4_t a, int32x4_t b) { return vsubq_s32(a, b); }
LT_INLINE int32x4_t lt__mve_min(int32x4_t a, int32x4_t b) { return vminq_s32(a, b); }
LT_INLINE int32x4_t lt__mve_max(int32x4_t a, int32x4_t b) { return vmaxq_s32(a, b); }
LT_INLINE int32x4_t lt__mve_or(int32x4_t a, int32x4_t b) { return vorrq_s32(a, b); }
LT_INLINE int32x4_t lt__mve_xor(int32x4_t a, int32x4_t b) { return veorq_s32(a, b); }
LT_INLINE int32x4_t lt__mve_mul16(int32x4_t a, int32x4_t b) { return lt__mve_mul_round_sat4(a, b, 16u); }
LT_INLINE int32x4_t lt__mve_mul30(int32x4_t a, int32x4_t b) { return lt__mve_mul_round_sat4(a, b, 30u); }

/* The compares' 4-lane predicates. */
LT_INLINE mve_pred16_t lt__mve_lt(int32x4_t a, int32x4_t b) { return vcmpltq_s32(a, b); }
LT_INLINE mve_pred16_t lt__mve_le(int32x4_t a, int32x4_t b) { return vcmpleq_s32(a, b); }
LT_INLINE mve_pred16_t lt__mve_gt(int32x4_t a, int32x4_t b) { return vcmpgtq_s32(a, b); }
LT_INLINE mve_pred16_t lt__mve_ge(int32x4_t a, int32x4_t b) { return vcmpgeq_s32(a, b); }
LT_INLINE mve_pred16_t lt__mve_eq(int32x4_t a, int32x4_t b) { return vcmpeqq_s32(a, b); }

#else
#define LT__MVE_LANES 0
#endif

#endif /* LT_V16_MVE_H */
