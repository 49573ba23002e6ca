/* lt_v16w.h - wide lanes of the 16-lane model: int64 lanes whose type carries their fractional
 * bits (lt_vql<F>_t: 16 x int64 with F fractional bits, the lane twin of lt_fx.h's lt_ql32_t),
 * the int32 s25.6 lanes of rounded cross products (lt_vq6_t), the format-free int64 lane
 * (lt_vql_t, as lt_vi32_t is for int32), and the exact products, dot and cross products that make
 * them. A product's name gives its operand formats: lt_vql46_mul_q30_q16 is s1.30 x s15.16 ->
 * s17.46. Sums are _wrap: the kernels bound their inputs so that no sum of products overflows
 * (docs/numerics.md, "Wide lanes"). Every op is a plain C loop that charges itself, as in
 * lt_v16.h, which includes this file. Builds: all.
 */
#ifndef LT_V16W_H
#define LT_V16W_H

#include <stdint.h>
#include "lt_v16.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Format table (value = raw / 2^F), with the products that make each format:
 * | type       | lane  | format | range         | resolution       | made by                      |
 * |------------|-------|--------|---------------|------------------|------------------------------|
 * | lt_vq6_t   | int32 | s25.6  | [-2^25, 2^25) | 2^-6 = 1.56e-2   | s15.16 x s15.16, rounded     |
 * | lt_vql22_t | int64 | s41.22 | [-2^41, 2^41) | 2^-22 = 2.38e-7  | s15.16 x s25.6 (tnum)        |
 * | lt_vql32_t | int64 | s31.32 | [-2^31, 2^31) | 2^-32 = 2.33e-10 | s15.16 x s15.16 (det, edges) |
 * | lt_vql36_t | int64 | s27.36 | [-2^27, 2^27) | 2^-36 = 1.46e-11 | s1.30 x s25.6 (corner forms) |
 * | lt_vql46_t | int64 | s17.46 | [-2^17, 2^17) | 2^-46 = 1.42e-14 | s1.30 x s15.16 (pvec, n . w) |
 * | lt_vql60_t | int64 | s3.60  | [-8, 8)       | 2^-60 = 8.67e-19 | s1.30 x s1.30 (w on a ray)   |
 * | lt_vql_t   | int64 | any    | int64         | the caller's     | int32 x int32 (lt_vql_mul)   |
 * Every wide type is the same struct of 16 int64 (128 bytes): the types differ only in what the
 * compiler lets a kernel mix, so a value changes format only through a named conversion. */
typedef struct { int32_t l[LT_LANES]; } lt_vq6_t;   /* 16 x s25.6, 64 bytes */
typedef struct { int64_t l[LT_LANES]; } lt_vql_t;   /* 16 x int64, format-free, 128 bytes */
typedef struct { int64_t l[LT_LANES]; } lt_vql22_t; /* 16 x s41.22, 128 bytes */
typedef struct { int64_t l[LT_LANES]; } lt_vql32_t; /* 16 x s31.32, 128 bytes */
typedef struct { int64_t l[LT_LANES]; } lt_vql36_t; /* 16 x s27.36, 128 bytes */
typedef struct { int64_t l[LT_LANES]; } lt_vql46_t; /* 16 x s17.46, 128 bytes */
typedef struct { int64_t l[LT_LANES]; } lt_vql60_t; /* 16 x s3.60, 128 bytes */

/* ---- generators ---------------------------------------------------------------------------- */

/* The common ops of one wide lane type VT (prefix pfx), every one a single op of the class named:
 *   pfx_add_wrap, pfx_sub_wrap, pfx_min, pfx_max {,_m,_z}   VMULW x1 (the wide-op class)
 *   pfx_abs_wrap {,_m,_z}                                  VMULW x1 (|INT64_MIN| wraps to itself)
 *   pfx_cmplt, _cmple, _cmpgt, _cmpge, _cmpeq {,_m}        VCMP x1
 *   pfx_blend(k, a, b)                                     VMULW x1 (lane i = b where k, else a)
 *   pfx_set1(x)                                            VBCAST x1
 *   pfx_shl_wrap(a, s), s 0..63                            VSHIFT x1 (a 2^s modulo 2^64)
 *   pfx_asr(a, s), s 0..63                                 VSHIFT x1 (floor(a / 2^s))
 * Format: VT in, VT out (a shift scales the value, the fraction bits stay). */
#define LT__V16W_OPS(VT, pfx)                                                                      \
    LT__V16_BIN(VT, pfx##_add_wrap, VMULW, lt__l64_add_wrap)                                       \
    LT__V16_BIN(VT, pfx##_sub_wrap, VMULW, lt__l64_sub_wrap)                                       \
    LT__V16_BIN(VT, pfx##_min, VMULW, lt__l64_min)                                                 \
    LT__V16_BIN(VT, pfx##_max, VMULW, lt__l64_max)                                                 \
    LT__V16_UN(VT, pfx##_abs_wrap, VMULW, lt__l64_abs_wrap)                                        \
    LT__V16_CMP(VT, pfx##_cmplt, VCMP, <)                                                          \
    LT__V16_CMP(VT, pfx##_cmple, VCMP, <=)                                                         \
    LT__V16_CMP(VT, pfx##_cmpgt, VCMP, >)                                                          \
    LT__V16_CMP(VT, pfx##_cmpge, VCMP, >=)                                                         \
    LT__V16_CMP(VT, pfx##_cmpeq, VCMP, ==)                                                         \
    LT_INLINE VT pfx##_blend(lt_mask16_t k, VT a, VT b)                                            \
    {                                                                                              \
        int i;                                                                                     \
        LT_COST(VMULW, 1);                                                                         \
        LT_UTIL(k);                                                                                \
        for (i = 0; i < LT_LANES; i++)                                                             \
            if (LT__ON(k, i))                                                                      \
                a.l[i] = b.l[i];                                                                   \
        return a;                                                                                  \
    }                                                                                              \
    LT_INLINE VT pfx##_set1(int64_t x)                                                             \
    {                                                                                              \
        VT r;                                                                                      \
        int i;                                                                                     \
        LT_COST(VBCAST, 1);                                                                        \
        for (i = 0; i < LT_LANES; i++)                                                             \
            r.l[i] = x;                                                                            \
        return r;                                                                                  \
    }                                                                                              \
    LT_INLINE VT pfx##_shl_wrap(VT a, unsigned s)                                                  \
    {                                                                                              \
        int i;                                                                                     \
        LT_COST(VSHIFT, 1);                                                                        \
        for (i = 0; i < LT_LANES; i++)                                                             \
            a.l[i] = (int64_t)((uint64_t)a.l[i] << s);                                             \
        return a;                                                                                  \
    }                                                                                              \
    LT_INLINE VT pfx##_asr(VT a, unsigned s)                                                       \
    {                                                                                              \
        int i;                                                                                     \
        LT_COST(VSHIFT, 1);                                                                        \
        for (i = 0; i < LT_LANES; i++)                                                             \
            a.l[i] = lt__asr64(a.l[i], s);                                                         \
        return a;                                                                                  \
    }

/* Format-free int64 lanes seen as VT (no cost: a register rename), for a bound a kernel derives
 * in VT's units. */
#define LT__V16W_RAW(VT, pfx)                                                                      \
    LT_INLINE VT pfx##_from_vql(lt_vql_t a)                                                        \
    {                                                                                              \
        VT r;                                                                                      \
        int i;                                                                                     \
        for (i = 0; i < LT_LANES; i++)                                                             \
            r.l[i] = a.l[i];                                                                       \
        return r;                                                                                  \
    }

/* Exact product per lane: AT x BT -> RT, the fractional bits adding up (int32 x int32 -> int64,
 * never overflows). Cost: VMUL x1. */
#define LT__V16W_MUL(RT, name, AT, BT)                                                             \
    LT_INLINE RT name(AT a, BT b)                                                                  \
    {                                                                                              \
        RT r;                                                                                      \
        int i;                                                                                     \
        LT_COST(VMUL, 1);                                                                          \
        for (i = 0; i < LT_LANES; i++)                                                             \
            r.l[i] = lt__mul32x32_64(a.l[i], b.l[i]);                                              \
        return r;                                                                                  \
    }

/* (ax bx + ay by) + az bz, exact (the sums wrap only past int64, which the kernels' bounds
 * exclude). Cost: VMUL x3, VMULW x2. */
#define LT__V16W_DOT3(RT, name, mul, add, AT, BT)                                                  \
    LT_INLINE RT name(AT ax, AT ay, AT az, BT bx, BT by, BT bz)                                    \
    {                                                                                              \
        return add(add(mul(ax, bx), mul(ay, by)), mul(az, bz));                                    \
    }

/* a b - c d, exact. Cost: VMUL x2, VMULW x1. */
#define LT__V16W_CROSS(RT, name, mul, sub, AT, BT)                                                 \
    LT_INLINE RT name(AT a, BT b, AT c, BT d)                                                      \
    {                                                                                              \
        return sub(mul(a, b), mul(c, d));                                                          \
    }

/* ---- format-free int64 lanes --------------------------------------------------------------- */
LT__V16W_OPS(lt_vql_t, lt_vql)

/* Exact product per lane. Format: int32 x int32 -> int64 (fractional bits add). Overflow: none.
 * Cost: VMUL x1. */
LT__V16W_MUL(lt_vql_t, lt_vql_mul, lt_vi32_t, lt_vi32_t)

/* Round away f fractional bits (1..31), half up, and saturate to int32. Cost: VSHIFT x1. */
LT_INLINE lt_vi32_t lt_vql_round_sat(lt_vql_t a, unsigned f) /* VSHIFT x1 */
{
    lt_vi32_t r;
    int i;
    LT_COST(VSHIFT, 1);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = lt__round_sat32(a.l[i], f);
    return r;
}

/* int32 lanes sign-extended to int64 lanes (the value, and its fraction bits, unchanged).
 * Cost: VCVT x1. */
LT_INLINE lt_vql_t lt_vql_from_vi32(lt_vi32_t a) /* VCVT x1 */
{
    lt_vql_t r;
    int i;
    LT_COST(VCVT, 1);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = a.l[i];
    return r;
}

/* ---- the typed wide lanes ------------------------------------------------------------------ */
LT__V16W_OPS(lt_vql22_t, lt_vql22)
LT__V16W_OPS(lt_vql32_t, lt_vql32)
LT__V16W_OPS(lt_vql36_t, lt_vql36)
LT__V16W_OPS(lt_vql46_t, lt_vql46)
LT__V16W_OPS(lt_vql60_t, lt_vql60)
LT__V16W_RAW(lt_vql22_t, lt_vql22)
LT__V16W_RAW(lt_vql32_t, lt_vql32)
LT__V16W_RAW(lt_vql36_t, lt_vql36)
LT__V16W_RAW(lt_vql46_t, lt_vql46)
LT__V16W_RAW(lt_vql60_t, lt_vql60)

/* s25.6 lanes: broadcast, blend, load, store, gather, hmin, hmax as for lt_vi32_t. */
LT__V16_MOVE(lt_vq6_t, int32_t, lt_vq6, VALU, VRED)

/* Exact products. Format: s15.16 x s15.16 -> s31.32; s1.30 x s15.16 -> s17.46; s1.30 x s1.30 ->
 * s3.60 (s2.60 in value: |a b| < 4); s1.30 x s25.6 -> s27.36; s15.16 x s25.6 -> s41.22.
 * Overflow: none. Cost: VMUL x1 each. */
LT__V16W_MUL(lt_vql32_t, lt_vql32_mul_q16, lt_vq16_t, lt_vq16_t)
LT__V16W_MUL(lt_vql46_t, lt_vql46_mul_q30_q16, lt_vq30_t, lt_vq16_t)
LT__V16W_MUL(lt_vql60_t, lt_vql60_mul_q30, lt_vq30_t, lt_vq30_t)
LT__V16W_MUL(lt_vql36_t, lt_vql36_mul_q30_q6, lt_vq30_t, lt_vq6_t)
LT__V16W_MUL(lt_vql22_t, lt_vql22_mul_q16_q6, lt_vq16_t, lt_vq6_t)

/* Dot products of 3-vectors, exact: the products' format, summed without rounding.
 * Range: |sum| < 2^63 raw (the kernels' geometry bound, docs/numerics.md). Overflow: wraps.
 * Cost: VMUL x3, VMULW x2 each. */
LT__V16W_DOT3(lt_vql32_t, lt_vql32_dot3_q16, lt_vql32_mul_q16, lt_vql32_add_wrap, lt_vq16_t,
              lt_vq16_t)
LT__V16W_DOT3(lt_vql46_t, lt_vql46_dot3_q30_q16, lt_vql46_mul_q30_q16, lt_vql46_add_wrap,
              lt_vq30_t, lt_vq16_t)
LT__V16W_DOT3(lt_vql60_t, lt_vql60_dot3_q30, lt_vql60_mul_q30, lt_vql60_add_wrap, lt_vq30_t,
              lt_vq30_t)
LT__V16W_DOT3(lt_vql36_t, lt_vql36_dot3_q30_q6, lt_vql36_mul_q30_q6, lt_vql36_add_wrap, lt_vq30_t,
              lt_vq6_t)
LT__V16W_DOT3(lt_vql22_t, lt_vql22_dot3_q16_q6, lt_vql22_mul_q16_q6, lt_vql22_add_wrap, lt_vq16_t,
              lt_vq6_t)

/* a b - c d, exact (one component of a cross product). Format: s15.16 -> s31.32; s1.30 x s15.16
 * -> s17.46. Overflow: wraps (never within the geometry bound). Cost: VMUL x2, VMULW x1 each. */
LT__V16W_CROSS(lt_vql32_t, lt_vql32_cross_q16, lt_vql32_mul_q16, lt_vql32_sub_wrap, lt_vq16_t,
               lt_vq16_t)
LT__V16W_CROSS(lt_vql46_t, lt_vql46_cross_q30_q16, lt_vql46_mul_q30_q16, lt_vql46_sub_wrap,
               lt_vq30_t, lt_vq16_t)

/* ---- conversions --------------------------------------------------------------------------- */

/* s17.46 -> s15.16: 30 fraction bits rounded away. Rounding: half up. Overflow: saturates (a SAT
 * event). Cost: VSHIFT x1. */
LT_INLINE lt_vq16_t lt_vq16_from_ql46_sat(lt_vql46_t a) /* VSHIFT x1 */
{
    lt_vq16_t r;
    int i;
    LT_COST(VSHIFT, 1);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = lt__round_sat32(a.l[i], 30);
    return r;
}

/* s31.32 -> s25.6: 26 fraction bits rounded away. Rounding: half up. Overflow: saturates (a SAT
 * event; lanes at +-max then carry no error bound). Cost: VSHIFT x1. */
LT_INLINE lt_vq6_t lt_vq6_from_ql32_sat(lt_vql32_t a) /* VSHIFT x1 */
{
    lt_vq6_t r;
    int i;
    LT_COST(VSHIFT, 1);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = lt__round_sat32(a.l[i], 26);
    return r;
}

/* s27.36 -> s31.32: 4 fraction bits floored away. Rounding: toward minus infinity (_rd).
 * Overflow: none. Cost: VSHIFT x1. */
LT_INLINE lt_vql32_t lt_vql32_from_ql36_rd(lt_vql36_t a) /* VSHIFT x1 */
{
    lt_vql32_t r;
    int i;
    LT_COST(VSHIFT, 1);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = lt__asr64(a.l[i], 4);
    return r;
}

/* s1.30 -> s27.36 (6 more fraction bits) and s1.30 -> s3.60 (30 more), exact. Overflow: none.
 * Cost: VCVT x1 each. */
LT_INLINE lt_vql36_t lt_vql36_from_q30(lt_vq30_t a) /* VCVT x1 */
{
    lt_vql36_t r;
    int i;
    LT_COST(VCVT, 1);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = (int64_t)a.l[i] * ((int64_t)1 << 6);
    return r;
}

LT_INLINE lt_vql60_t lt_vql60_from_q30(lt_vq30_t a) /* VCVT x1 */
{
    lt_vql60_t r;
    int i;
    LT_COST(VCVT, 1);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = (int64_t)a.l[i] * ((int64_t)1 << 30);
    return r;
}

/* 3 a per lane. Format: s27.36. Overflow: wraps (the kernels' values stay below 2^62).
 * Cost: VMULW x2 (a shift and an add on a machine without a wide multiply). */
LT_INLINE lt_vql36_t lt_vql36_mul3_wrap(lt_vql36_t a) /* VMULW x2 */
{
    int i;
    LT_COST(VMULW, 2);
    for (i = 0; i < LT_LANES; i++)
        a.l[i] = lt__l64_add_wrap(lt__l64_add_wrap(a.l[i], a.l[i]), a.l[i]);
    return a;
}

/* ---- fused: products rounded back to a narrow format ----------------------------------------- */

/* a b - c d rounded once. Format: s1.30 x s15.16 -> s17.46 (exact) -> s15.16 (pvec = d x e).
 * Rounding: half up. Overflow: saturates. Cost: VMUL x2, VMULW x1, VSHIFT x1. */
LT_INLINE lt_vq16_t lt_vq16_cross_q30_sat(lt_vq30_t a, lt_vq16_t b, lt_vq30_t c,
                                          lt_vq16_t d) /* VMUL x2, VMULW x1, VSHIFT x1 */
{
    return lt_vq16_from_ql46_sat(lt_vql46_cross_q30_q16(a, b, c, d));
}

/* a b - c d rounded once. Format: s15.16 x s15.16 -> s31.32 (exact) -> s25.6 (qvec = t x e1).
 * Rounding: half up. Overflow: saturates. Cost: VMUL x2, VMULW x1, VSHIFT x1. */
LT_INLINE lt_vq6_t lt_vq6_cross_q16_sat(lt_vq16_t a, lt_vq16_t b, lt_vq16_t c,
                                        lt_vq16_t d) /* VMUL x2, VMULW x1, VSHIFT x1 */
{
    return lt_vq6_from_ql32_sat(lt_vql32_cross_q16(a, b, c, d));
}

/* a . b rounded once. Format: s1.30 . s15.16 -> s17.46 (exact) -> s15.16 (a unit normal dotted
 * with a vector). Rounding: half up. Overflow: saturates. Cost: VMUL x3, VMULW x2, VSHIFT x1. */
LT_INLINE lt_vq16_t lt_vq16_dot3_q30_sat(lt_vq30_t ax, lt_vq30_t ay, lt_vq30_t az, lt_vq16_t bx,
                                         lt_vq16_t by,
                                         lt_vq16_t bz) /* VMUL x3, VMULW x2, VSHIFT x1 */
{
    return lt_vq16_from_ql46_sat(lt_vql46_dot3_q30_q16(ax, ay, az, bx, by, bz));
}

/* d . q floored to 32 fraction bits. Format: s1.30 . s25.6 -> s27.36 (exact) -> s31.32 (v = d .
 * qvec, comparable with det). Rounding: toward minus infinity. Overflow: none.
 * Cost: VMUL x3, VMULW x2, VSHIFT x1. */
LT_INLINE lt_vql32_t lt_vql32_dot3_q30_q6_rd(lt_vq30_t dx, lt_vq30_t dy, lt_vq30_t dz, lt_vq6_t qx,
                                             lt_vq6_t qy,
                                             lt_vq6_t qz) /* VMUL x3, VMULW x2, VSHIFT x1 */
{
    return lt_vql32_from_ql36_rd(lt_vql36_dot3_q30_q6(dx, dy, dz, qx, qy, qz));
}

#ifdef __cplusplus
}
#endif
#endif /* LT_V16W_H */
