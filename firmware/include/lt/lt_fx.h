/* lt_fx.h - scalar fixed-point formats and arithmetic (freestanding, integer only).
 * Every op that can overflow says _sat or _wrap in its name; rounding is round-half-up (floor(x + 1/2))
 * unless the name says otherwise. Division by zero saturates (see lt_q16_div_sat). No sentinel values.
 * Public lt_<fmt>_<op> charge their cost; lt__<fmt>_<op> are the uncharged bodies the lane ops reuse.
 * Builds: all (firmware, host, sim).
 *
 * Format table (value = raw / 2^frac):
 * | type        | storage | format  | range                     | resolution       | use                    |
 * |-------------|---------|---------|---------------------------|------------------|------------------------|
 * | lt_q16_t    | int32   | s15.16  | [-32768, 32768 - 2^-16]   | 2^-16 = 1.53e-5  | world coordinates, t   |
 * | lt_q30_t    | int32   | s1.30   | [-2, 2 - 2^-30]           | 2^-30 = 9.31e-10 | unit vectors           |
 * | lt_ql32_t   | int64   | s31.32  | [-2^31, 2^31 - 2^-32]     | 2^-32 = 2.33e-10 | products/accumulators  |
 * | lt_h8_t     | int16   | s7.8    | [-128, 128 - 2^-8]        | 2^-8 = 3.91e-3   | narrow coordinates     |
 * | lt_h14_t    | int16   | s1.14   | [-2, 2 - 2^-14]           | 2^-14 = 6.10e-5  | narrow unit vectors    |
 * Lane-only formats (lt_v16w.h; no scalar type): the number in a name is the count of fractional
 * bits, q for int32 and ql for int64 storage, as in lt_q16_t and lt_ql32_t (lt_vql32_t is the lane
 * twin of lt_ql32_t). They hold exact products between the formats above:
 * | lt_vq6_t    | int32   | s25.6   | [-2^25, 2^25 - 2^-6]      | 2^-6 = 1.56e-2   | qvec = tvec x e1       |
 * | lt_vql22_t  | int64   | s41.22  | [-2^41, 2^41 - 2^-22]     | 2^-22 = 2.38e-7  | tnum = e2 . qvec       |
 * | lt_vql32_t  | int64   | s31.32  | [-2^31, 2^31 - 2^-32]     | 2^-32 = 2.33e-10 | det, u, v, edge fns    |
 * | lt_vql36_t  | int64   | s27.36  | [-2^27, 2^27 - 2^-36]     | 2^-36 = 1.46e-11 | corner forms, qt build |
 * | lt_vql46_t  | int64   | s17.46  | [-2^17, 2^17 - 2^-46]     | 2^-46 = 1.42e-14 | s1.30 x s15.16 exact   |
 * | lt_vql60_t  | int64   | s3.60   | [-8, 8 - 2^-60]           | 2^-60 = 8.67e-19 | w along a ray (s1.30^2)|
 */
#ifndef LT_FX_H
#define LT_FX_H

#include <stdint.h>
#include "lt_port.h"
#include "lt_config.h"
#include "lt_cost.h"
#include "lt_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef int32_t lt_q16_t;  /* s15.16 */
typedef int32_t lt_q30_t;  /* s1.30 */
typedef int64_t lt_ql32_t; /* s31.32 */
typedef int16_t lt_h8_t;   /* s7.8 */
typedef int16_t lt_h14_t;  /* s1.14 */

#define LT_Q16_ONE ((lt_q16_t)0x00010000)
#define LT_Q16_MAX ((lt_q16_t)INT32_MAX)
#define LT_Q16_MIN ((lt_q16_t)INT32_MIN)
#define LT_Q30_ONE ((lt_q30_t)0x40000000)
#define LT_Q30_MAX ((lt_q30_t)INT32_MAX)
#define LT_Q30_MIN ((lt_q30_t)INT32_MIN)
#define LT_H8_ONE ((lt_h8_t)0x0100)
#define LT_H14_ONE ((lt_h14_t)0x4000)

/* Compile-time constants from a literal, rounded half away from zero. Host and tests only (it uses
 * a floating literal): never with a runtime argument, never in fixed-point-only core code. */
#define LT_Q16(x) ((lt_q16_t)((x) >= 0 ? (x) * 65536.0 + 0.5 : (x) * 65536.0 - 0.5))
#define LT_Q30(x) ((lt_q30_t)((x) >= 0 ? (x) * 1073741824.0 + 0.5 : (x) * 1073741824.0 - 0.5))

/* ---- uncharged bodies (shared with the lane ops) -------------------------------------------- */

/* The saturating 32-bit add and subtract. On an Arm core with the DSP extension's saturating
 * instructions (__ARM_FEATURE_QBIT: Cortex-M4, M7, M33, M55) in a build that counts nothing, one
 * QADD / QSUB each (ACLE __qadd / __qsub; the Q flag they set is never read); -DLT_LANES_PORTABLE
 * keeps the portable 64-bit sum, which stays the reference (the same result for every input:
 * tests/golden/vectors.txt on cm4 in both builds; docs/firmware.md, "Lane backends"). */
#if !defined(LT_LANES_PORTABLE) && defined(__ARM_FEATURE_QBIT) && LT_COST_MODE == LT_COST_OFF
#define LT__DSP_SAT 1
#include <arm_acle.h>
LT_INLINE lt_q16_t lt__q16_add_sat(lt_q16_t a, lt_q16_t b)
{
    return (lt_q16_t)__qadd(a, b);
}

LT_INLINE lt_q16_t lt__q16_sub_sat(lt_q16_t a, lt_q16_t b)
{
    return (lt_q16_t)__qsub(a, b);
}
#else
LT_INLINE lt_q16_t lt__q16_add_sat(lt_q16_t a, lt_q16_t b)
{
    int64_t s = (int64_t)a + b;
    LT_EVENT(SAT, s != (int64_t)lt__ssat32(s));
    return lt__ssat32(s);
}

LT_INLINE lt_q16_t lt__q16_sub_sat(lt_q16_t a, lt_q16_t b)
{
    int64_t s = (int64_t)a - b;
    LT_EVENT(SAT, s != (int64_t)lt__ssat32(s));
    return lt__ssat32(s);
}
#endif

LT_INLINE lt_q16_t lt__q16_add_wrap(lt_q16_t a, lt_q16_t b)
{
    return lt__wrap32((int64_t)a + b);
}

LT_INLINE lt_q16_t lt__q16_sub_wrap(lt_q16_t a, lt_q16_t b)
{
    return lt__wrap32((int64_t)a - b);
}

/* int64 (any fraction bits) add and subtract modulo 2^64, computed in unsigned arithmetic; min,
 * max; |a| with |INT64_MIN| wrapping to itself. The bodies of the wide lane ops (lt_v16w.h). */
LT_INLINE int64_t lt__l64_add_wrap(int64_t a, int64_t b)
{
    return (int64_t)((uint64_t)a + (uint64_t)b);
}
LT_INLINE int64_t lt__l64_sub_wrap(int64_t a, int64_t b)
{
    return (int64_t)((uint64_t)a - (uint64_t)b);
}
LT_INLINE int64_t lt__l64_min(int64_t a, int64_t b) { return a < b ? a : b; }
LT_INLINE int64_t lt__l64_max(int64_t a, int64_t b) { return a > b ? a : b; }
LT_INLINE int64_t lt__l64_abs_wrap(int64_t a) { return a < 0 ? lt__l64_sub_wrap(0, a) : a; }

/* Round a signed value with f fractional bits (1..62) to an integer, half up, then saturate to int32. */
LT_INLINE int32_t lt__round_sat32(int64_t v, unsigned f)
{
    /* v + 2^(f-1) cannot overflow for |v| < 2^62; larger inputs are clamped first (they saturate
     * anyway for f <= 31, and for larger f the clamp changes the result by less than 2^-30 ulp). */
    int64_t lim = (int64_t)1 << 62;
    int64_t r;
    if (v > lim)
        v = lim;
    if (v < -lim)
        v = -lim;
    r = lt__asr64(v + ((int64_t)1 << (f - 1u)), f);
    LT_EVENT(SAT, r != (int64_t)lt__ssat32(r));
    return lt__ssat32(r);
}

LT_INLINE lt_q16_t lt__q16_mul_sat(lt_q16_t a, lt_q16_t b)
{
    return lt__round_sat32(lt__mul32x32_64(a, b), 16);
}

/* Truncating (round toward minus infinity) multiply: one add less than the rounded one. */
LT_INLINE lt_q16_t lt__q16_mul_sat_rd(lt_q16_t a, lt_q16_t b)
{
    int64_t r = lt__asr64(lt__mul32x32_64(a, b), 16);
    LT_EVENT(SAT, r != (int64_t)lt__ssat32(r));
    return lt__ssat32(r);
}

/* q16 x q30 -> q16, e.g. a length times a direction component. */
LT_INLINE lt_q16_t lt__q16_mul_q30_sat(lt_q16_t a, lt_q30_t b)
{
    return lt__round_sat32(lt__mul32x32_64(a, b), 30);
}

LT_INLINE lt_q30_t lt__q30_mul_sat(lt_q30_t a, lt_q30_t b)
{
    return lt__round_sat32(lt__mul32x32_64(a, b), 30);
}

LT_INLINE lt_q16_t lt__q16_min(lt_q16_t a, lt_q16_t b) { return a < b ? a : b; }
LT_INLINE lt_q16_t lt__q16_max(lt_q16_t a, lt_q16_t b) { return a > b ? a : b; }

LT_INLINE lt_q16_t lt__q16_clamp(lt_q16_t x, lt_q16_t lo, lt_q16_t hi)
{
    return x < lo ? lo : (x > hi ? hi : x);
}

/* |INT32_MIN| does not exist in int32: it saturates to INT32_MAX. */
LT_INLINE lt_q16_t lt__q16_abs_sat(lt_q16_t a)
{
    LT_EVENT(SAT, a == INT32_MIN);
    return a == INT32_MIN ? INT32_MAX : (a < 0 ? -a : a);
}

LT_INLINE lt_q16_t lt__q16_neg_sat(lt_q16_t a)
{
    LT_EVENT(SAT, a == INT32_MIN);
    return a == INT32_MIN ? INT32_MAX : -a;
}

/* round(a / b) for b != 0, half up; the caller handles b == 0. Any a, b with |a|, |b| < 2^63
 * (no intermediate leaves int64: the remainder is compared with b - r instead of doubled, which
 * overflowed for |b| near 2^62, e.g. the t division of a triangle with 8192-unit edges).
 * floor(a/b + 1/2) = q + (r >= b - r) for q = floor(a/b), r = a - q b in [0, b). */
LT_INLINE int64_t lt__div_round64(int64_t a, int64_t b)
{
    int64_t q, r;
    if (b < 0) {
        a = -a;
        b = -b;
    }
    q = a / b;
    r = a % b;
    if (r < 0) {
        q -= 1;
        r += b;
    }
    return r >= b - r ? q + 1 : q;
}

/* a / b in s15.16. b == 0 saturates toward the sign of a (0 / 0 = 0), counted as a saturation. */
LT_INLINE lt_q16_t lt__q16_div_sat(lt_q16_t a, lt_q16_t b)
{
    int64_t q;
    if (b == 0) {
        LT_EVENT(SAT, a != 0);
        return a > 0 ? INT32_MAX : (a < 0 ? INT32_MIN : 0);
    }
    q = lt__div_round64((int64_t)a * 65536, b);
    LT_EVENT(SAT, q != (int64_t)lt__ssat32(q));
    return lt__ssat32(q);
}

/* Integer square root: floor(sqrt(n)) for any uint64 (bit-by-bit, 32 iterations, no division). */
LT_INLINE uint32_t lt__isqrt64(uint64_t n)
{
    uint64_t r = 0;
    uint64_t bit = (uint64_t)1 << 62;
    while (bit > n)
        bit >>= 2;
    while (bit != 0) {
        if (n >= r + bit) {
            n -= r + bit;
            r = (r >> 1) + bit;
        } else {
            r >>= 1;
        }
        bit >>= 2;
    }
    return (uint32_t)r;
}

/* Exact round-half-up sum of three q16 x q16 products, saturated to q16. Each product may reach
 * 2^62, so the sum is carried as 4*H + L with the two low bits apart, which cannot overflow. */
LT_INLINE lt_q16_t lt__q16_dot3_sat(lt_q16_t a0, lt_q16_t a1, lt_q16_t a2, lt_q16_t b0,
                                    lt_q16_t b1, lt_q16_t b2)
{
    int64_t p0 = lt__mul32x32_64(a0, b0), p1 = lt__mul32x32_64(a1, b1);
    int64_t p2 = lt__mul32x32_64(a2, b2);
    int64_t h0 = lt__asr64(p0, 2), h1 = lt__asr64(p1, 2), h2 = lt__asr64(p2, 2);
    int64_t l = (p0 - 4 * h0) + (p1 - 4 * h1) + (p2 - 4 * h2);
    int64_t r = lt__asr64(h0 + h1 + h2 + ((l + 32768) >> 2), 14);
    LT_EVENT(SAT, r != (int64_t)lt__ssat32(r));
    return lt__ssat32(r);
}

/* ---- public scalar ops (each charges its cost) ----------------------------------------------- */

/* a + b. Format: s15.16 + s15.16 -> s15.16. Range: any. Rounding: exact. Overflow: saturates.
 * Cost: SALU x1. */
LT_INLINE lt_q16_t lt_q16_add_sat(lt_q16_t a, lt_q16_t b)
{
    LT_COST(SALU, 1);
    return lt__q16_add_sat(a, b);
}

/* a - b. Format: s15.16 - s15.16 -> s15.16. Range: any. Rounding: exact. Overflow: saturates.
 * Cost: SALU x1. */
LT_INLINE lt_q16_t lt_q16_sub_sat(lt_q16_t a, lt_q16_t b)
{
    LT_COST(SALU, 1);
    return lt__q16_sub_sat(a, b);
}

/* a + b modulo 2^32. Format: s15.16. Range: any. Rounding: exact. Overflow: wraps. Cost: SALU x1. */
LT_INLINE lt_q16_t lt_q16_add_wrap(lt_q16_t a, lt_q16_t b)
{
    LT_COST(SALU, 1);
    return lt__q16_add_wrap(a, b);
}

/* a - b modulo 2^32. Format: s15.16. Range: any. Rounding: exact. Overflow: wraps. Cost: SALU x1. */
LT_INLINE lt_q16_t lt_q16_sub_wrap(lt_q16_t a, lt_q16_t b)
{
    LT_COST(SALU, 1);
    return lt__q16_sub_wrap(a, b);
}

/* a * b. Format: s15.16 x s15.16 -> s31.32 (exact int64) -> s15.16. Range: any.
 * Rounding: half up. Overflow: saturates. Cost: SMUL x1. */
LT_INLINE lt_q16_t lt_q16_mul_sat(lt_q16_t a, lt_q16_t b)
{
    LT_COST(SMUL, 1);
    return lt__q16_mul_sat(a, b);
}

/* a * b. Format: s15.16 x s15.16 -> s15.16. Range: any. Rounding: toward minus infinity (_rd).
 * Overflow: saturates. Cost: SMUL x1. */
LT_INLINE lt_q16_t lt_q16_mul_sat_rd(lt_q16_t a, lt_q16_t b)
{
    LT_COST(SMUL, 1);
    return lt__q16_mul_sat_rd(a, b);
}

/* a * b. Format: s15.16 x s1.30 -> s17.46 (exact) -> s15.16. Range: any. Rounding: half up.
 * Overflow: saturates. Cost: SMUL x1. */
LT_INLINE lt_q16_t lt_q16_mul_q30_sat(lt_q16_t a, lt_q30_t b)
{
    LT_COST(SMUL, 1);
    return lt__q16_mul_q30_sat(a, b);
}

/* a / b. Format: s15.16 / s15.16 -> s15.16. Range: any; b == 0 gives +max for a > 0, min for a < 0,
 * 0 for a == 0 (a saturation event). Rounding: half up. Overflow: saturates. Cost: SDIV x1. */
LT_INLINE lt_q16_t lt_q16_div_sat(lt_q16_t a, lt_q16_t b)
{
    LT_COST(SDIV, 1);
    return lt__q16_div_sat(a, b);
}

/* 1 / x. Format: s15.16 -> s15.16. Range: any; |x| < 2^-15 saturates, x == 0 gives +max.
 * Rounding: half up. Overflow: saturates. Cost: SDIV x1. */
LT_INLINE lt_q16_t lt_q16_recip_sat(lt_q16_t x)
{
    LT_COST(SDIV, 1);
    return lt__q16_div_sat(LT_Q16_ONE, x);
}

/* min/max. Format: s15.16. Range: any. Rounding: exact. Overflow: none. Cost: SALU x1. */
LT_INLINE lt_q16_t lt_q16_min(lt_q16_t a, lt_q16_t b)
{
    LT_COST(SALU, 1);
    return lt__q16_min(a, b);
}

LT_INLINE lt_q16_t lt_q16_max(lt_q16_t a, lt_q16_t b)
{
    LT_COST(SALU, 1);
    return lt__q16_max(a, b);
}

/* clamp x to [lo, hi] (lo <= hi). Format: s15.16. Overflow: none. Cost: SALU x2. */
LT_INLINE lt_q16_t lt_q16_clamp(lt_q16_t x, lt_q16_t lo, lt_q16_t hi)
{
    LT_COST(SALU, 2);
    return lt__q16_clamp(x, lo, hi);
}

/* |a|. Format: s15.16. Range: any. Rounding: exact. Overflow: |min| saturates to max. Cost: SALU x1. */
LT_INLINE lt_q16_t lt_q16_abs_sat(lt_q16_t a)
{
    LT_COST(SALU, 1);
    return lt__q16_abs_sat(a);
}

/* -a. Format: s15.16. Range: any. Rounding: exact. Overflow: -min saturates to max. Cost: SALU x1. */
LT_INLINE lt_q16_t lt_q16_neg_sat(lt_q16_t a)
{
    LT_COST(SALU, 1);
    return lt__q16_neg_sat(a);
}

/* a.b for 3-vectors. Format: s15.16 x s15.16 -> 3 x s31.32 summed exactly -> s15.16.
 * Range: any. Rounding: half up, once. Overflow: saturates. Cost: SMUL x3, SALU x3. */
LT_INLINE lt_q16_t lt_q16_dot3_sat(const lt_q16_t a[3], const lt_q16_t b[3])
{
    LT_COST(SMUL, 3);
    LT_COST(SALU, 3);
    return lt__q16_dot3_sat(a[0], a[1], a[2], b[0], b[1], b[2]);
}

/* Out-of-line ops (firmware/core/numerics/lt_fx.c). */

/* sqrt(x). Format: s15.16 -> s15.16. Range: x >= 0; x < 0 gives 0 (a saturation event).
 * Rounding: to nearest, half up. Overflow: none (sqrt(max) = 181.02). Cost: SDIV x1 (iterative). */
lt_q16_t lt_q16_sqrt(lt_q16_t x);

/* 1 / sqrt(x). Format: s15.16 -> s15.16. Range: x > 0; x <= 0 gives +max (saturation event).
 * Rounding: to nearest (error <= 1 ulp). Overflow: saturates (never for x > 0: rsqrt(2^-16) = 256).
 * Cost: SDIV x2. */
lt_q16_t lt_q16_rsqrt_sat(lt_q16_t x);

/* a x b for 3-vectors. Format: s15.16 x s15.16 -> s31.32 differences (exact) -> s15.16.
 * Range: any. Rounding: half up, once per component. Overflow: saturates. Cost: SMUL x6, SALU x3. */
void lt_q16_cross3_sat(const lt_q16_t a[3], const lt_q16_t b[3], lt_q16_t out[3]);

/* v / |v| as a unit vector. Format: s15.16 -> s1.30. Range: any nonzero v.
 * Rounding: to nearest, error <= 2 ulp of s1.30 per component (measured <= 1). Overflow: none.
 * Cost: SALU x8, SMUL x3, SDIV x4. Returns: LT_OK, or LT_E_ARG for the zero vector (out untouched). */
lt_status_t lt_q16_normalize3(const lt_q16_t v[3], lt_q30_t out[3]);

/* ---- s1.30 --------------------------------------------------------------------------------- */

/* a * b. Format: s1.30 x s1.30 -> s3.60 (exact) -> s1.30. Range: any. Rounding: half up.
 * Overflow: saturates (only |a*b| >= 2). Cost: SMUL x1. */
LT_INLINE lt_q30_t lt_q30_mul_sat(lt_q30_t a, lt_q30_t b)
{
    LT_COST(SMUL, 1);
    return lt__q30_mul_sat(a, b);
}

/* s15.16 -> s1.30. Range: |x| < 2. Rounding: exact. Overflow: saturates. Cost: SALU x1. */
LT_INLINE lt_q30_t lt_q30_from_q16_sat(lt_q16_t x)
{
    int64_t r = (int64_t)x * 16384;
    LT_COST(SALU, 1);
    LT_EVENT(SAT, r != (int64_t)lt__ssat32(r));
    return lt__ssat32(r);
}

/* s1.30 -> s15.16. Range: any. Rounding: half up. Overflow: none. Cost: SALU x1. */
LT_INLINE lt_q16_t lt_q16_from_q30(lt_q30_t x)
{
    LT_COST(SALU, 1);
    return (lt_q16_t)lt__asr64((int64_t)x + 8192, 14);
}

/* ---- narrow s7.8 and s1.14 ------------------------------------------------------------------ */

LT_INLINE lt_h8_t lt__h8_from_q16_sat(lt_q16_t x)
{
    int64_t w = lt__asr64((int64_t)x + 128, 8);
    LT_EVENT(SAT, w > INT16_MAX || w < INT16_MIN);
    return lt__ssat16(lt__ssat32(w));
}

LT_INLINE lt_h8_t lt__h8_add_sat(lt_h8_t a, lt_h8_t b)
{
    int32_t s = (int32_t)a + b;
    LT_EVENT(SAT, s > INT16_MAX || s < INT16_MIN);
    return lt__ssat16(s);
}

LT_INLINE lt_h8_t lt__h8_sub_sat(lt_h8_t a, lt_h8_t b)
{
    int32_t s = (int32_t)a - b;
    LT_EVENT(SAT, s > INT16_MAX || s < INT16_MIN);
    return lt__ssat16(s);
}

LT_INLINE lt_h8_t lt__h8_mul_sat(lt_h8_t a, lt_h8_t b)
{
    int32_t r = lt__asr32((int32_t)a * b + 128, 8);
    LT_EVENT(SAT, r > INT16_MAX || r < INT16_MIN);
    return lt__ssat16(r);
}

/* s15.16 -> s7.8. Range: |x| < 128. Rounding: half up. Overflow: saturates. Cost: SALU x1. */
LT_INLINE lt_h8_t lt_h8_from_q16_sat(lt_q16_t x)
{
    LT_COST(SALU, 1);
    return lt__h8_from_q16_sat(x);
}

/* s7.8 -> s15.16. Range: any. Rounding: exact. Overflow: none. Cost: SALU x1. */
LT_INLINE lt_q16_t lt_q16_from_h8(lt_h8_t x)
{
    LT_COST(SALU, 1);
    return (lt_q16_t)x * 256;
}

/* a + b, a - b. Format: s7.8. Range: any. Rounding: exact. Overflow: saturates. Cost: SALU x1. */
LT_INLINE lt_h8_t lt_h8_add_sat(lt_h8_t a, lt_h8_t b)
{
    LT_COST(SALU, 1);
    return lt__h8_add_sat(a, b);
}

LT_INLINE lt_h8_t lt_h8_sub_sat(lt_h8_t a, lt_h8_t b)
{
    LT_COST(SALU, 1);
    return lt__h8_sub_sat(a, b);
}

/* a * b. Format: s7.8 x s7.8 -> s15.16 (exact int32) -> s7.8. Range: any. Rounding: half up.
 * Overflow: saturates. Cost: SMUL x1. */
LT_INLINE lt_h8_t lt_h8_mul_sat(lt_h8_t a, lt_h8_t b)
{
    LT_COST(SMUL, 1);
    return lt__h8_mul_sat(a, b);
}

/* s1.30 -> s1.14. Range: |x| < 2. Rounding: half up. Overflow: saturates (only x near +2).
 * Cost: SALU x1. */
LT_INLINE lt_h14_t lt_h14_from_q30_sat(lt_q30_t x)
{
    int64_t w = lt__asr64((int64_t)x + 32768, 16);
    LT_COST(SALU, 1);
    LT_EVENT(SAT, w > INT16_MAX);
    return lt__ssat16(lt__ssat32(w));
}

/* s1.14 -> s1.30. Range: any. Rounding: exact. Overflow: none. Cost: SALU x1. */
LT_INLINE lt_q30_t lt_q30_from_h14(lt_h14_t x)
{
    LT_COST(SALU, 1);
    return (lt_q30_t)x * 65536;
}

#ifdef __cplusplus
}
#endif
#endif /* LT_FX_H */
