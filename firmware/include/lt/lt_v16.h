/* lt_v16.h - the 16-lane SIMD model: lane vector types, 16-bit masks and lane ops; the wide
 * (int64) lanes and exact products are lt_v16w.h's, included at the end. Every op is a plain C loop
 * over 16 lanes (the reference; GCC auto-vectorises it on the host) that charges itself through
 * the cost hook; its op class is on the line that defines it (a generator argument or a trailing
 * comment). Naming: lt_v<fmt>_<op>[_m|_z]: _m merges (inactive lanes keep src, LRBni {k}
 * semantics), _z zeroes inactive lanes. Compares return lt_mask16_t (bit i = lane i).
 * Builds: all. Float32 ops exist only with LT_CFG_FLOAT32.
 */
#ifndef LT_V16_H
#define LT_V16_H

#include <stdint.h>
#include "lt_port.h"
#include "lt_config.h"
#include "lt_cost.h"
#include "lt_fx.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LT_LANES 16
typedef uint16_t lt_mask16_t; /* bit i = lane i */
#define LT_MASK_ALL ((lt_mask16_t)0xFFFFu)

typedef struct { int32_t l[LT_LANES]; } lt_vq16_t;  /* 16 x s15.16, 64 bytes */
typedef struct { int32_t l[LT_LANES]; } lt_vq30_t;  /* 16 x s1.30, 64 bytes */
typedef struct { int32_t l[LT_LANES]; } lt_vi32_t;  /* 16 x int32 (indices, ids), 64 bytes */
typedef struct { int16_t l[LT_LANES]; } lt_vh8_t;   /* 16 x s7.8, 32 bytes */
#if LT_CFG_FLOAT32
typedef struct { float l[LT_LANES]; } lt_vf32_t;    /* 16 x IEEE binary32, 64 bytes */
#endif
/* Wide lanes (int64, 128 bytes) and the s25.6 lanes of rounded products are lt_v16w.h's, which
 * this header includes at its end: lt_vql<F>_t carries F fraction bits in its name. */

#define LT__ON(k, i) ((((unsigned)(k)) >> (i)) & 1u)

/* the x86 sequences of a few hot ops, or nothing (the portable loops below) */
#include "lt_v16_x86.h"
#if LT__X86_LANES
#define LT__X86_BLEND32(k, a, b, r) lt__x86_blend32((k), (a), (b), (r))
#else
#define LT__X86_BLEND32(k, a, b, r) ((void)(k), (void)(a), (void)(b), (void)(r))
#endif
#if LT__X86_LANES == 512
#define LT__X86_SET1_32(x, r) lt__x86_set1_32((x), (r))
#define LT__X86_HRED32(k, a, none, isf, ismax) lt__x86_hred32((k), (a), (none), (isf), (ismax))
#else
#define LT__X86_SET1_32(x, r) ((void)(x), (void)(r))
#define LT__X86_HRED32(k, a, none, isf, ismax) ((void)(k), (void)(a), (void)(none))
#endif
/* the Helium (MVE) sequences of the 32-bit integer lane ops on Cortex-M55, or nothing */
#include "lt_v16_mve.h"
#if LT__MVE_LANES
#define LT__MVE_BLEND32(k, a, b, r)                                                                \
    lt__mve_blend32((k), (const int32_t *)(const void *)(a), (const int32_t *)(const void *)(b),    \
                    (int32_t *)(void *)(r))
#else
#define LT__MVE_BLEND32(k, a, b, r) ((void)(k), (void)(a), (void)(b), (void)(r))
#endif

/* LT_LANEWISE(): whether the packet kernels that have a lane-by-lane form (the s15.16 slab test,
 * lt_isect.c, and the watertight test, lt_wt.c) take it - each lane's arithmetic of the lane ops,
 * in registers, over the lanes of the mask only: what a core with one lane and the DSP
 * extension does cheapest (the lane ops pass 64- and 128-byte vectors by value and compute all 16
 * lanes). Builds that count nothing take it on the Arm DSP backends (__ARM_FEATURE_DSP, not
 * LT_LANES_PORTABLE): Cortex-M4, and Cortex-M55, whose Helium lane ops keep every other kernel
 * (the bunny's packets: 4.0x fewer instructions than the portable lane loops there, the Helium
 * lane ops alone 1.5x; docs/firmware.md, "Lane by lane"); so do their on-target counting builds
 * (handler mode: they charge the lane-by-lane recipes). The simulator takes it when the machine
 * it models says so (LT_MACHINE_LANEWISE() in its file: mcu-m4, mcu-m55), so its charges follow
 * the code the target runs. Elsewhere (x86 backends, the portable builds, RV32) the lane ops. The
 * same bits either way (golden vectors and scene hashes compare the builds). */
#if LT_COST_MODE == LT_COST_SIM
#define LT_LANEWISE() (lt__sim_lanewise != 0)
#elif !defined(LT_LANES_PORTABLE) && !LT__X86_LANES && defined(__ARM_FEATURE_DSP)
#define LT_LANEWISE() 1
#else
#define LT_LANEWISE() 0
#endif

/* ---- masks --------------------------------------------------------------------------------- */

/* Mask queries. Format: 16-bit mask. Cost: MASK x1 each. */
LT_INLINE int lt_mask16_any(lt_mask16_t k) /* MASK x1 */
{
    LT_COST(MASK, 1);
    return k != 0;
}

LT_INLINE int lt_mask16_all(lt_mask16_t k) /* MASK x1 */
{
    LT_COST(MASK, 1);
    return k == LT_MASK_ALL;
}

LT_INLINE unsigned lt_mask16_popcount(lt_mask16_t k) /* MASK x1 */
{
    LT_COST(MASK, 1);
    return lt__popcount32(k);
}

/* Index of the lowest set lane (bit-scan forward); 16 for an empty mask. Cost: MASK x1. */
LT_INLINE unsigned lt_mask16_first(lt_mask16_t k) /* MASK x1 */
{
    LT_COST(MASK, 1);
    return k != 0 ? lt__ctz32(k) : 16u;
}

/* k with its lowest set lane cleared: iterate active lanes with
 * for (m = k; m; m = lt_mask16_clear_first(m)) { i = lt_mask16_first(m); ... }. Cost: MASK x1. */
LT_INLINE lt_mask16_t lt_mask16_clear_first(lt_mask16_t k) /* MASK x1 */
{
    LT_COST(MASK, 1);
    return (lt_mask16_t)(k & (k - 1u));
}

/* ---- generators: one body per op, three masking variants ------------------------------------ */

/* Binary op r = f(a, b): plain, merge-masked (_m) and zero-masked (_z). */
#define LT__V16_BIN(VT, name, op, f)                                                               \
    LT_INLINE VT name(VT a, VT b)                                                                  \
    {                                                                                              \
        VT r;                                                                                      \
        int i;                                                                                     \
        LT_COST(op, 1);                                                                            \
        for (i = 0; i < LT_LANES; i++)                                                             \
            r.l[i] = f(a.l[i], b.l[i]);                                                            \
        return r;                                                                                  \
    }                                                                                              \
    LT_INLINE VT name##_m(VT src, lt_mask16_t k, VT a, VT b)                                       \
    {                                                                                              \
        int i;                                                                                     \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                 \
        for (i = 0; i < LT_LANES; i++)                                                             \
            if (LT__ON(k, i))                                                                      \
                src.l[i] = f(a.l[i], b.l[i]);                                                      \
        return src;                                                                                \
    }                                                                                              \
    LT_INLINE VT name##_z(lt_mask16_t k, VT a, VT b)                                               \
    {                                                                                              \
        VT r;                                                                                      \
        int i;                                                                                     \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                 \
        for (i = 0; i < LT_LANES; i++)                                                             \
            r.l[i] = 0;                                                                            \
        for (i = 0; i < LT_LANES; i++)                                                             \
            if (LT__ON(k, i))                                                                      \
                r.l[i] = f(a.l[i], b.l[i]);                                                        \
        return r;                                                                                  \
    }

/* Unary op r = f(a) in the same three variants. */
#define LT__V16_UN(VT, name, op, f)                                                                \
    LT_INLINE VT name(VT a)                                                                        \
    {                                                                                              \
        VT r;                                                                                      \
        int i;                                                                                     \
        LT_COST(op, 1);                                                                            \
        for (i = 0; i < LT_LANES; i++)                                                             \
            r.l[i] = f(a.l[i]);                                                                    \
        return r;                                                                                  \
    }                                                                                              \
    LT_INLINE VT name##_m(VT src, lt_mask16_t k, VT a)                                             \
    {                                                                                              \
        int i;                                                                                     \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                 \
        for (i = 0; i < LT_LANES; i++)                                                             \
            if (LT__ON(k, i))                                                                      \
                src.l[i] = f(a.l[i]);                                                              \
        return src;                                                                                \
    }                                                                                              \
    LT_INLINE VT name##_z(lt_mask16_t k, VT a)                                                     \
    {                                                                                              \
        VT r;                                                                                      \
        int i;                                                                                     \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                 \
        for (i = 0; i < LT_LANES; i++)                                                             \
            r.l[i] = 0;                                                                            \
        for (i = 0; i < LT_LANES; i++)                                                             \
            if (LT__ON(k, i))                                                                      \
                r.l[i] = f(a.l[i]);                                                                \
        return r;                                                                                  \
    }

/* Compare: mask of lanes where a OP b; the _m form compares only lanes in k (others give 0). */
#define LT__V16_CMP(VT, name, op, rel)                                                             \
    LT_INLINE lt_mask16_t name(VT a, VT b)                                                         \
    {                                                                                              \
        unsigned m = 0;                                                                            \
        int i;                                                                                     \
        LT_COST(op, 1);                                                                            \
        for (i = 0; i < LT_LANES; i++)                                                             \
            m |= (unsigned)(a.l[i] rel b.l[i]) << i;                                               \
        return (lt_mask16_t)m;                                                                     \
    }                                                                                              \
    LT_INLINE lt_mask16_t name##_m(lt_mask16_t k, VT a, VT b)                                      \
    {                                                                                              \
        unsigned m = 0;                                                                            \
        int i;                                                                                     \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                 \
        for (i = 0; i < LT_LANES; i++)                                                             \
            m |= (unsigned)(a.l[i] rel b.l[i]) << i;                                               \
        return (lt_mask16_t)(m & k);                                                               \
    }

#if LT__X86_LANES == 512
/* The same ops with an AVX-512 register body lt__x86_##vf (lt_v16_x86.h): one 512-bit store per
 * result, so the next op's 512-bit load forwards from it; masked forms compute every lane and
 * blend or zero by the mask register (SAT events counted for the lanes of k only, as the loop
 * counts them); a compare is one vpcmpd or vcmpps into the mask (lt__x86_cmp_##vc). */
#define LT__V16_BINX(VT, name, op, vf)                                                             \
    LT_INLINE VT name(VT a, VT b)                                                                  \
    {                                                                                              \
        VT r;                                                                                      \
        LT_COST(op, 1);                                                                            \
        _mm512_storeu_si512((void *)r.l, lt__x86_##vf(lt__x86_load16(a.l), lt__x86_load16(b.l),    \
                                                      LT_MASK_ALL));                               \
        return r;                                                                                  \
    }                                                                                              \
    LT_INLINE VT name##_m(VT src, lt_mask16_t k, VT a, VT b)                                       \
    {                                                                                              \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                \
        _mm512_storeu_si512((void *)src.l,                                                         \
                            _mm512_mask_mov_epi32(lt__x86_load16(src.l), (__mmask16)k,             \
                                                  lt__x86_##vf(lt__x86_load16(a.l),                \
                                                               lt__x86_load16(b.l), k)));          \
        return src;                                                                                \
    }                                                                                              \
    LT_INLINE VT name##_z(lt_mask16_t k, VT a, VT b)                                               \
    {                                                                                              \
        VT r;                                                                                      \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                \
        _mm512_storeu_si512((void *)r.l,                                                           \
                            _mm512_maskz_mov_epi32((__mmask16)k,                                   \
                                                   lt__x86_##vf(lt__x86_load16(a.l),               \
                                                                lt__x86_load16(b.l), k)));         \
        return r;                                                                                  \
    }
#define LT__V16_CMPX(VT, name, op, vc, ld)                                                         \
    LT_INLINE lt_mask16_t name(VT a, VT b)                                                         \
    {                                                                                              \
        LT_COST(op, 1);                                                                            \
        return (lt_mask16_t)lt__x86_cmp_##vc(ld(a.l), ld(b.l));                                  \
    }                                                                                              \
    LT_INLINE lt_mask16_t name##_m(lt_mask16_t k, VT a, VT b)                                      \
    {                                                                                              \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                \
        return (lt_mask16_t)(lt__x86_cmp_##vc(ld(a.l), ld(b.l)) & k);                            \
    }
#endif

/* A binary op of 32-bit integer lanes with a Helium body lt__mve_##vf (int32x4_t (int32x4_t,
 * int32x4_t), lt_v16_mve.h) on four quads; the masked forms compute every lane and select (the
 * ops are pure), so they equal the portable loops. vf names the body of each backend (qadd, qsub,
 * add, sub, min, max, or, xor, mul16, mul30; a compare's vc: lt, le, gt, ge, eq). Without MVE
 * or AVX-512 (below): LT__V16_BIN. */
#if LT__MVE_LANES
#define LT__V16_BINV(VT, name, op, f, vf)                                                          \
    LT_INLINE VT name(VT a, VT b)                                                                  \
    {                                                                                              \
        VT r;                                                                                      \
        unsigned q;                                                                                \
        LT_COST(op, 1);                                                                            \
        for (q = 0; q < 4u; q++)                                                                   \
            vst1q_s32(&r.l[4u * q], lt__mve_##vf(vld1q_s32(&a.l[4u * q]), vld1q_s32(&b.l[4u * q])));        \
        return r;                                                                                  \
    }                                                                                              \
    LT_INLINE VT name##_m(VT src, lt_mask16_t k, VT a, VT b)                                       \
    {                                                                                              \
        unsigned q;                                                                                \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                \
        for (q = 0; q < 4u; q++)                                                                   \
            vst1q_s32(&src.l[4u * q],                                                              \
                      vpselq_s32(lt__mve_##vf(vld1q_s32(&a.l[4u * q]), vld1q_s32(&b.l[4u * q])),             \
                                 vld1q_s32(&src.l[4u * q]), lt__mve_pred(k, q)));                  \
        return src;                                                                                \
    }                                                                                              \
    LT_INLINE VT name##_z(lt_mask16_t k, VT a, VT b)                                               \
    {                                                                                              \
        VT r;                                                                                      \
        unsigned q;                                                                                \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                \
        for (q = 0; q < 4u; q++)                                                                   \
            vst1q_s32(&r.l[4u * q],                                                                \
                      vpselq_s32(lt__mve_##vf(vld1q_s32(&a.l[4u * q]), vld1q_s32(&b.l[4u * q])),             \
                                 vdupq_n_s32(0), lt__mve_pred(k, q)));                             \
        return r;                                                                                  \
    }
/* A compare of 32-bit integer lanes with a Helium predicate body vc (lt__mve_lt, ...). */
#define LT__V16_CMPV(VT, name, op, rel, vc)                                                        \
    LT_INLINE lt_mask16_t name(VT a, VT b)                                                         \
    {                                                                                              \
        unsigned m = 0, q;                                                                         \
        LT_COST(op, 1);                                                                            \
        for (q = 0; q < 4u; q++)                                                                   \
            m |= lt__mve_bits(lt__mve_##vc(vld1q_s32(&a.l[4u * q]), vld1q_s32(&b.l[4u * q]))) << (4u * q);  \
        return (lt_mask16_t)m;                                                                     \
    }                                                                                              \
    LT_INLINE lt_mask16_t name##_m(lt_mask16_t k, VT a, VT b)                                      \
    {                                                                                              \
        unsigned m = 0, q;                                                                         \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                \
        for (q = 0; q < 4u; q++)                                                                   \
            m |= lt__mve_bits(lt__mve_##vc(vld1q_s32(&a.l[4u * q]), vld1q_s32(&b.l[4u * q]))) << (4u * q);  \
        return (lt_mask16_t)(m & k);                                                               \
    }
#elif LT__X86_LANES == 512
#define LT__V16_BINV(VT, name, op, f, vf) LT__V16_BINX(VT, name, op, vf)
#define LT__V16_CMPV(VT, name, op, rel, vc) LT__V16_CMPX(VT, name, op, vc, lt__x86_load16)
#elif LT__X86_LANES == 256
/* AVX2: the register bodies lt__x86_##vf##8 (lt_v16_x86.h) on the two 256-bit halves, each
 * written with one 256-bit store; the masked form computes every lane and blends by the mask
 * (SAT events counted for the lanes of k only, as the loop counts them), the zeroing form is the
 * masked form over zero lanes. */
#define LT__V16_BINV(VT, name, op, f, vf)                                                          \
    LT_INLINE VT name(VT a, VT b)                                                                  \
    {                                                                                              \
        VT r;                                                                                      \
        int h;                                                                                     \
        LT_COST(op, 1);                                                                            \
        for (h = 0; h < 2; h++)                                                                    \
            _mm256_storeu_si256((__m256i *)(void *)(r.l + 8 * h),                                  \
                                lt__x86_##vf##8(lt__x86_load8(a.l + 8 * h),                        \
                                                lt__x86_load8(b.l + 8 * h), 0xFFu));               \
        return r;                                                                                  \
    }                                                                                              \
    LT_INLINE VT name##_m(VT src, lt_mask16_t k, VT a, VT b)                                       \
    {                                                                                              \
        int h;                                                                                     \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                \
        for (h = 0; h < 2; h++) {                                                                  \
            unsigned k8 = ((unsigned)k >> (8 * h)) & 0xFFu;                                        \
            __m256i x = lt__x86_##vf##8(lt__x86_load8(a.l + 8 * h), lt__x86_load8(b.l + 8 * h),   \
                                        k8);                                                       \
            _mm256_storeu_si256((__m256i *)(void *)(src.l + 8 * h),                                \
                                _mm256_blendv_epi8(lt__x86_load8(src.l + 8 * h), x,                \
                                                   lt__x86_mask8(k8)));                            \
        }                                                                                          \
        return src;                                                                                \
    }                                                                                              \
    LT_INLINE VT name##_z(lt_mask16_t k, VT a, VT b)                                               \
    {                                                                                              \
        VT z = {{0}}; /* the masked form over zero lanes */                                        \
        return name##_m(z, k, a, b);                                                               \
    }
#define LT__V16_CMPV(VT, name, op, rel, vc)                                                        \
    LT_INLINE lt_mask16_t name(VT a, VT b)                                                         \
    {                                                                                              \
        LT_COST(op, 1);                                                                            \
        return (lt_mask16_t)(lt__x86_cmp8_##vc(lt__x86_load8(a.l), lt__x86_load8(b.l)) |          \
                             lt__x86_cmp8_##vc(lt__x86_load8(a.l + 8), lt__x86_load8(b.l + 8))     \
                                 << 8);                                                            \
    }                                                                                              \
    LT_INLINE lt_mask16_t name##_m(lt_mask16_t k, VT a, VT b)                                      \
    {                                                                                              \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                \
        return (lt_mask16_t)((lt__x86_cmp8_##vc(lt__x86_load8(a.l), lt__x86_load8(b.l)) |         \
                              lt__x86_cmp8_##vc(lt__x86_load8(a.l + 8), lt__x86_load8(b.l + 8))    \
                                  << 8) &                                                          \
                             k);                                                                   \
    }
#else
#define LT__V16_BINV(VT, name, op, f, vf) LT__V16_BIN(VT, name, op, f)
#define LT__V16_CMPV(VT, name, op, rel, vc) LT__V16_CMP(VT, name, op, rel)
#endif
/* float32 compares: the AVX-512 bodies (flt, ...) on that backend, else the loops (Helium's
 * bodies are integer only); float32 arithmetic stays the loops everywhere (measured slower
 * through the backend: the compiler keeps those loops in registers). */
#if LT__X86_LANES == 512
#define LT__V16_CMPF(VT, name, op, rel, vc) LT__V16_CMPX(VT, name, op, vc, lt__x86_load16h)
#elif LT__X86_LANES == 256
#define LT__V16_CMPF(VT, name, op, rel, vc) LT__V16_CMPV(VT, name, op, rel, vc)
#else
#define LT__V16_CMPF(VT, name, op, rel, vc) LT__V16_CMP(VT, name, op, rel)
#endif

/* Compare with zero: mask of lanes where a REL 0 (against a zero register: nothing is broadcast);
 * the _m form compares only lanes in k (others give 0). */
#define LT__V16_CMP0(VT, name, op, rel)                                                            \
    LT_INLINE lt_mask16_t name(VT a)                                                               \
    {                                                                                              \
        unsigned m = 0;                                                                            \
        int i;                                                                                     \
        LT_COST(op, 1);                                                                            \
        for (i = 0; i < LT_LANES; i++)                                                             \
            m |= (unsigned)(a.l[i] rel 0) << i;                                                    \
        return (lt_mask16_t)m;                                                                     \
    }                                                                                              \
    LT_INLINE lt_mask16_t name##_m(lt_mask16_t k, VT a)                                            \
    {                                                                                              \
        unsigned m = 0;                                                                            \
        int i;                                                                                     \
        LT_COST(op, 1);                                                                            \
        LT_UTIL(k);                                                                                \
        for (i = 0; i < LT_LANES; i++)                                                             \
            m |= (unsigned)(a.l[i] rel 0) << i;                                                    \
        return (lt_mask16_t)(m & k);                                                               \
    }

/* Broadcast, blend, load, store, gather and horizontal min/max for a lane type with element ET. */
#define LT__V16_MOVE(VT, ET, pfx, valu, vred)                                                      \
    LT_INLINE VT pfx##_set1(ET x)                                                                  \
    {                                                                                              \
        VT r;                                                                                      \
        int i;                                                                                     \
        LT_COST(VBCAST, 1);                                                                        \
        if (LT__X86_LANES == 512 && sizeof(ET) == 4) {                                             \
            /* one 512-bit store (lt_v16_x86.h, lt__x86_load16) */                                 \
            union {                                                                                \
                ET e;                                                                              \
                int32_t i;                                                                         \
            } u;                                                                                   \
            u.e = x;                                                                               \
            LT__X86_SET1_32(u.i, r.l);                                                             \
            return r;                                                                              \
        }                                                                                          \
        for (i = 0; i < LT_LANES; i++)                                                             \
            r.l[i] = x;                                                                            \
        return r;                                                                                  \
    }                                                                                              \
    /* Lane i = b.l[i] where k has bit i, else a.l[i]. */                                          \
    LT_INLINE VT pfx##_blend(lt_mask16_t k, VT a, VT b)                                            \
    {                                                                                              \
        int i;                                                                                     \
        LT_COST(valu, 1);                                                                          \
        LT_UTIL(k);                                                                                 \
        if (LT__X86_LANES && sizeof(ET) == 4) {                                                    \
            VT r;                                                                                  \
            LT__X86_BLEND32(k, a.l, b.l, r.l);                                                     \
            return r;                                                                              \
        }                                                                                          \
        if (LT__MVE_LANES && sizeof(ET) == 4 && (ET)1 / 2 == 0) {                                   \
            VT r;                                                                                  \
            LT__MVE_BLEND32(k, a.l, b.l, r.l);                                                     \
            return r;                                                                              \
        }                                                                                          \
        for (i = 0; i < LT_LANES; i++)                                                             \
            if (LT__ON(k, i))                                                                      \
                a.l[i] = b.l[i];                                                                   \
        return a;                                                                                  \
    }                                                                                              \
    LT_INLINE VT pfx##_load(const ET *p)                                                           \
    {                                                                                              \
        VT r;                                                                                      \
        int i;                                                                                     \
        LT_COST(VLOAD, 1);                                                                         \
        LT_MEM(p, sizeof(VT), LT_MEM_READ);                                                        \
        for (i = 0; i < LT_LANES; i++)                                                             \
            r.l[i] = p[i];                                                                         \
        return r;                                                                                  \
    }                                                                                              \
    LT_INLINE void pfx##_store(ET *p, VT a)                                                        \
    {                                                                                              \
        int i;                                                                                     \
        LT_COST(VSTORE, 1);                                                                        \
        LT_MEM(p, sizeof(VT), LT_MEM_WRITE);                                                       \
        for (i = 0; i < LT_LANES; i++)                                                             \
            p[i] = a.l[i];                                                                         \
    }                                                                                              \
    /* Store only the lanes in k; memory of inactive lanes is not touched. */                      \
    LT_INLINE void pfx##_store_m(ET *p, lt_mask16_t k, VT a)                                       \
    {                                                                                              \
        int i;                                                                                     \
        LT_COST(VSTORE, 1);                                                                        \
        LT_UTIL(k);                                                                                 \
        LT_MEM(p, sizeof(VT), LT_MEM_WRITE);                                                       \
        for (i = 0; i < LT_LANES; i++)                                                             \
            if (LT__ON(k, i))                                                                      \
                p[i] = a.l[i];                                                                     \
    }                                                                                              \
    /* Lane i = base[idx.l[i]] for lanes in k; others keep src. One VGATHER and one memory        \
     * access per active lane. */                                                                  \
    LT_INLINE VT pfx##_gather_m(VT src, lt_mask16_t k, const ET *base, lt_vi32_t idx)              \
    {                                                                                              \
        int i;                                                                                     \
        LT_COST(VGATHER, lt__popcount32(k));                                                       \
        LT_UTIL(k);                                                                                 \
        for (i = 0; i < LT_LANES; i++)                                                             \
            if (LT__ON(k, i)) {                                                                    \
                LT_MEM(&base[idx.l[i]], sizeof(ET), LT_MEM_READ);                                  \
                src.l[i] = base[idx.l[i]];                                                         \
            }                                                                                      \
        return src;                                                                                \
    }                                                                                              \
    /* Minimum/maximum over the lanes in k; an empty k returns `none` (the caller's identity). */  \
    LT_INLINE ET pfx##_hmin(lt_mask16_t k, VT a, ET none)                                          \
    {                                                                                              \
        int i;                                                                                     \
        LT_COST(vred, 1);                                                                          \
        if (LT__X86_LANES == 512 && sizeof(ET) == 4 && ((ET)1 / 2 != 0 || (ET)-1 < 0)) {          \
            LT__X86_HRED32(k, a.l, &none, (ET)1 / 2 != 0, 0);                                      \
            return none;                                                                           \
        }                                                                                          \
        for (i = 0; i < LT_LANES; i++)                                                             \
            if (LT__ON(k, i) && a.l[i] < none)                                                     \
                none = a.l[i];                                                                     \
        return none;                                                                               \
    }                                                                                              \
    LT_INLINE ET pfx##_hmax(lt_mask16_t k, VT a, ET none)                                          \
    {                                                                                              \
        int i;                                                                                     \
        LT_COST(vred, 1);                                                                          \
        if (LT__X86_LANES == 512 && sizeof(ET) == 4 && ((ET)1 / 2 != 0 || (ET)-1 < 0)) {          \
            LT__X86_HRED32(k, a.l, &none, (ET)1 / 2 != 0, 1);                                      \
            return none;                                                                           \
        }                                                                                          \
        for (i = 0; i < LT_LANES; i++)                                                             \
            if (LT__ON(k, i) && a.l[i] > none)                                                     \
                none = a.l[i];                                                                     \
        return none;                                                                               \
    }

/* ---- s15.16 lanes -------------------------------------------------------------------------- */
/* Each op below has the scalar op's contract per lane (see lt_fx.h): Format s15.16, Rounding half up,
 * Overflow saturates (_sat) or wraps (_wrap). Cost: one op of the class named. */
LT__V16_MOVE(lt_vq16_t, int32_t, lt_vq16, VALU, VRED)
LT__V16_BINV(lt_vq16_t, lt_vq16_add_sat, VALU, lt__q16_add_sat, qadd)
LT__V16_BINV(lt_vq16_t, lt_vq16_sub_sat, VALU, lt__q16_sub_sat, qsub)
LT__V16_BINV(lt_vq16_t, lt_vq16_add_wrap, VALU, lt__q16_add_wrap, add)
LT__V16_BINV(lt_vq16_t, lt_vq16_sub_wrap, VALU, lt__q16_sub_wrap, sub)
LT__V16_BINV(lt_vq16_t, lt_vq16_min, VALU, lt__q16_min, min)
LT__V16_BINV(lt_vq16_t, lt_vq16_max, VALU, lt__q16_max, max)
LT__V16_BINV(lt_vq16_t, lt_vq16_mul_sat, VMUL, lt__q16_mul_sat, mul16)
LT__V16_BIN(lt_vq16_t, lt_vq16_mul_sat_rd, VMUL, lt__q16_mul_sat_rd)
LT__V16_BIN(lt_vq16_t, lt_vq16_div_sat, VDIV, lt__q16_div_sat)
LT__V16_UN(lt_vq16_t, lt_vq16_abs_sat, VALU, lt__q16_abs_sat)
LT__V16_UN(lt_vq16_t, lt_vq16_neg_sat, VALU, lt__q16_neg_sat)
LT__V16_CMPV(lt_vq16_t, lt_vq16_cmplt, VCMP, <, lt)
LT__V16_CMPV(lt_vq16_t, lt_vq16_cmple, VCMP, <=, le)
LT__V16_CMPV(lt_vq16_t, lt_vq16_cmpgt, VCMP, >, gt)
LT__V16_CMPV(lt_vq16_t, lt_vq16_cmpge, VCMP, >=, ge)
LT__V16_CMPV(lt_vq16_t, lt_vq16_cmpeq, VCMP, ==, eq)

LT_INLINE lt_q16_t lt__q16_recip_sat(lt_q16_t x) { return lt__q16_div_sat(LT_Q16_ONE, x); }
/* 1/x per lane. Format: s15.16 -> s15.16; x == 0 gives +max. Rounding: half up. Overflow: saturates.
 * Cost: VDIV x1. */
LT__V16_UN(lt_vq16_t, lt_vq16_recip_sat, VDIV, lt__q16_recip_sat)

/* a * b per lane. Format: s15.16 x s1.30 -> s17.46 (exact) -> s15.16. Rounding: half up.
 * Overflow: saturates. Cost: VMUL x1. */
LT_INLINE lt_vq16_t lt_vq16_mul_q30_sat(lt_vq16_t a, lt_vq30_t b) /* VMUL x1 */
{
#if LT__X86_LANES
    lt_vq16_t r;
    LT_COST(VMUL, 1);
    lt__x86_mul_round_sat(a.l, b.l, r.l, 30, LT_MASK_ALL);
    return r;
#elif LT__MVE_LANES
    lt_vq16_t r;
    LT_COST(VMUL, 1);
    lt__mve_mul_round_sat(a.l, b.l, r.l, 30);
    return r;
#else
    int i;
    LT_COST(VMUL, 1);
    for (i = 0; i < LT_LANES; i++)
        a.l[i] = lt__q16_mul_q30_sat(a.l[i], b.l[i]);
    return a;
#endif
}

/* 1 / d per lane for an s1.30 d (a ray direction): 2^46 / d_raw. Format: s1.30 -> s15.16.
 * Range: any; d == 0 gives `zero` (the caller's choice of side, e.g. +max), |d| < 2^-15
 * saturates. Rounding: half up. Overflow: saturates (a SAT event). Cost: VDIV x1. */
LT_INLINE lt_vq16_t lt_vq16_recip_q30_sat(lt_vq30_t d, lt_q16_t zero) /* VDIV x1 */
{
    lt_vq16_t r;
    int i;
    LT_COST(VDIV, 1);
#if defined(LT__X86_RECIP46_16)
    /* x86 backend, AVX-512DQ: the same quotient from a double estimate, 16 lanes at once */
    {
        unsigned sat;
        lt__x86_recip46_16(d.l, zero, r.l, &sat);
        LT_EVENT(SAT, lt__popcount32(sat));
        (void)sat;
        (void)i;
        return r;
    }
#elif LT__X86_LANES
    /* x86 backend: the same quotient from a double estimate and one remainder test */
    for (i = 0; i < LT_LANES; i++) {
        int64_t q = lt__x86_recip46(d.l[i] == 0 ? 1 : d.l[i]);
        LT_EVENT(SAT, d.l[i] != 0 && q != (int64_t)lt__ssat32(q));
        r.l[i] = d.l[i] == 0 ? zero : lt__ssat32(q);
    }
#else
    for (i = 0; i < LT_LANES; i++) {
        if (d.l[i] == 0) {
            r.l[i] = zero;
        } else {
            int64_t q = lt__div_round64((int64_t)1 << 46, d.l[i]);
            LT_EVENT(SAT, q != (int64_t)lt__ssat32(q));
            r.l[i] = lt__ssat32(q);
        }
    }
#endif
    return r;
}

/* a / n per lane for a count n (int32 lanes), lanes in k with n > 0; other lanes become 0 (the
 * mean of n summed values). Format: s15.16 / int32 -> s15.16. Rounding: half up. Overflow: none
 * (|a / n| <= |a|). Cost: VDIV x1. */
LT_INLINE lt_vq16_t lt_vq16_div_i32_z(lt_mask16_t k, lt_vq16_t a, lt_vi32_t n) /* VDIV x1 */
{
    lt_vq16_t r;
    int i;
    LT_COST(VDIV, 1);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = LT__ON(k, i) && n.l[i] > 0 ? (lt_q16_t)lt__div_round64(a.l[i], n.l[i]) : 0;
    return r;
}

/* Lanes holding a saturated value (+max or min), e.g. a clamped reciprocal. Format: s15.16.
 * Cost: VBCAST x2, VCMP x2 (two broadcasts and two compares). */
LT_INLINE lt_mask16_t lt_vq16_cmpsat(lt_vq16_t a) /* VBCAST x2, VCMP x2 */
{
    return (lt_mask16_t)(lt_vq16_cmpeq(a, lt_vq16_set1(LT_Q16_MAX)) |
                         lt_vq16_cmpeq(a, lt_vq16_set1(LT_Q16_MIN)));
}

/* ---- s1.30 lanes --------------------------------------------------------------------------- */
/* The s15.16 bodies of lt_fx.h are format-free integer ops, so add, sub, min, max, abs and the
 * compares have the contract of their lt_vq16_* twins per lane, in s1.30. */
LT__V16_MOVE(lt_vq30_t, int32_t, lt_vq30, VALU, VRED)
LT__V16_BINV(lt_vq30_t, lt_vq30_mul_sat, VMUL, lt__q30_mul_sat, mul30)
LT__V16_BINV(lt_vq30_t, lt_vq30_add_sat, VALU, lt__q16_add_sat, qadd)
LT__V16_BINV(lt_vq30_t, lt_vq30_sub_sat, VALU, lt__q16_sub_sat, qsub)
LT__V16_BINV(lt_vq30_t, lt_vq30_add_wrap, VALU, lt__q16_add_wrap, add)
LT__V16_BINV(lt_vq30_t, lt_vq30_min, VALU, lt__q16_min, min)
LT__V16_BINV(lt_vq30_t, lt_vq30_max, VALU, lt__q16_max, max)
LT__V16_UN(lt_vq30_t, lt_vq30_abs_sat, VALU, lt__q16_abs_sat)
LT__V16_CMPV(lt_vq30_t, lt_vq30_cmpeq, VCMP, ==, eq)
LT__V16_CMPV(lt_vq30_t, lt_vq30_cmplt, VCMP, <, lt)
LT__V16_CMPV(lt_vq30_t, lt_vq30_cmple, VCMP, <=, le)
LT__V16_CMPV(lt_vq30_t, lt_vq30_cmpgt, VCMP, >, gt)
LT__V16_CMPV(lt_vq30_t, lt_vq30_cmpge, VCMP, >=, ge)
/* Signs of s1.30 lanes (direction components): a REL 0. Cost: VCMP x1. */
LT__V16_CMP0(lt_vq30_t, lt_vq30_cmplt0, VCMP, <)
LT__V16_CMP0(lt_vq30_t, lt_vq30_cmple0, VCMP, <=)
LT__V16_CMP0(lt_vq30_t, lt_vq30_cmpgt0, VCMP, >)
LT__V16_CMP0(lt_vq30_t, lt_vq30_cmpge0, VCMP, >=)

/* s1.30 -> s15.16 per lane. Rounding: half up. Overflow: none. Cost: VCVT x1. */
LT_INLINE lt_vq16_t lt_vq16_from_q30(lt_vq30_t a) /* VCVT x1 */
{
    lt_vq16_t r;
    int i;
    LT_COST(VCVT, 1);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = (int32_t)lt__asr64((int64_t)a.l[i] + 8192, 14);
    return r;
}

/* ---- int32 lanes --------------------------------------------------------------------------- */
/* Indices, pixel and node coordinates, counters. add/sub wrap modulo 2^32 (computed in int64 and
 * wrapped: no undefined behaviour); or/xor act on the two's complement bits. Cost: one op of the
 * class named (VALU, VCMP). */
LT_INLINE int32_t lt__i32_add_wrap(int32_t a, int32_t b) { return lt__wrap32((int64_t)a + b); }
LT_INLINE int32_t lt__i32_sub_wrap(int32_t a, int32_t b) { return lt__wrap32((int64_t)a - b); }
LT_INLINE int32_t lt__i32_or(int32_t a, int32_t b)
{
    return lt__wrap32((int64_t)((uint32_t)a | (uint32_t)b));
}
LT_INLINE int32_t lt__i32_xor(int32_t a, int32_t b)
{
    return lt__wrap32((int64_t)((uint32_t)a ^ (uint32_t)b));
}
LT_INLINE int32_t lt__i32_min(int32_t a, int32_t b) { return a < b ? a : b; }
LT_INLINE int32_t lt__i32_max(int32_t a, int32_t b) { return a > b ? a : b; }
LT__V16_MOVE(lt_vi32_t, int32_t, lt_vi32, VALU, VRED)
LT__V16_BINV(lt_vi32_t, lt_vi32_add_wrap, VALU, lt__i32_add_wrap, add)
LT__V16_BINV(lt_vi32_t, lt_vi32_sub_wrap, VALU, lt__i32_sub_wrap, sub)
LT__V16_BINV(lt_vi32_t, lt_vi32_or, VALU, lt__i32_or, or)
LT__V16_BINV(lt_vi32_t, lt_vi32_xor, VALU, lt__i32_xor, xor)
LT__V16_BINV(lt_vi32_t, lt_vi32_min, VALU, lt__i32_min, min)
LT__V16_BINV(lt_vi32_t, lt_vi32_max, VALU, lt__i32_max, max)
LT__V16_CMPV(lt_vi32_t, lt_vi32_cmpeq, VCMP, ==, eq)
LT__V16_CMPV(lt_vi32_t, lt_vi32_cmplt, VCMP, <, lt)
LT__V16_CMPV(lt_vi32_t, lt_vi32_cmple, VCMP, <=, le)
LT__V16_CMP(lt_vi32_t, lt_vi32_cmpgt, VCMP, >)
LT__V16_CMP(lt_vi32_t, lt_vi32_cmpge, VCMP, >=)

/* 0, 1, ..., 15. Cost: VALU x1. */
LT_INLINE lt_vi32_t lt_vi32_iota(void) /* VALU x1 */
{
    lt_vi32_t r;
    int i;
    LT_COST(VALU, 1);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = i;
    return r;
}

/* a * 2^(s mod 32) per lane, s a lane of its own (the count is taken modulo 32, as a hardware
 * variable shift does). Format: int32. Overflow: wraps modulo 2^32. Cost: VSHIFT x1. */
LT_INLINE lt_vi32_t lt_vi32_shlv_wrap(lt_vi32_t a, lt_vi32_t s) /* VSHIFT x1 */
{
    int i;
    LT_COST(VSHIFT, 1);
    for (i = 0; i < LT_LANES; i++)
        a.l[i] = lt__wrap32((int64_t)a.l[i] * ((int64_t)1 << (s.l[i] & 31)));
    return a;
}

/* a >> (s mod 32) per lane, s a lane of its own. Rounding: toward minus infinity (lt__asr32).
 * Overflow: none. Cost: VSHIFT x1. */
LT_INLINE lt_vi32_t lt_vi32_asrv(lt_vi32_t a, lt_vi32_t s) /* VSHIFT x1 */
{
    int i;
    LT_COST(VSHIFT, 1);
    for (i = 0; i < LT_LANES; i++)
        a.l[i] = lt__asr32(a.l[i], (unsigned)s.l[i] & 31u);
    return a;
}

/* a >> s per lane for one count s (0..31). Rounding: toward minus infinity. Overflow: none.
 * Cost: VSHIFT x1. */
LT_INLINE lt_vi32_t lt_vi32_asr(lt_vi32_t a, unsigned s) /* VSHIFT x1 */
{
    int i;
    LT_COST(VSHIFT, 1);
    for (i = 0; i < LT_LANES; i++)
        a.l[i] = lt__asr32(a.l[i], s);
    return a;
}

/* findMSB per lane in k: 31 - clz(x), the index of the highest set bit (-1 for x == 0); lanes not
 * in k become 0. Cost: VALU x1 (a lane count-leading-zeros, AVX-512 vplzcntd). */
LT_INLINE lt_vi32_t lt_vi32_msb_z(lt_mask16_t k, lt_vi32_t x) /* VALU x1 */
{
    lt_vi32_t r;
    int i;
    LT_COST(VALU, 1);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = LT__ON(k, i) ? 31 - (int32_t)lt__clz32((uint32_t)x.l[i]) : 0;
    return r;
}

/* Reinterpret s15.16 or s1.30 lanes as plain int32 lanes (no cost: a register rename). */
LT_INLINE lt_vi32_t lt_vi32_from_q16(lt_vq16_t a) /* no cost */
{
    lt_vi32_t r;
    int i;
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = a.l[i];
    return r;
}

LT_INLINE lt_vi32_t lt_vi32_from_q30(lt_vq30_t a) /* no cost */
{
    lt_vi32_t r;
    int i;
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = a.l[i];
    return r;
}

/* ---- s7.8 narrow lanes --------------------------------------------------------------------- */
LT__V16_MOVE(lt_vh8_t, int16_t, lt_vh8, VALU, VRED)
LT__V16_BIN(lt_vh8_t, lt_vh8_add_sat, VALU, lt__h8_add_sat)
LT__V16_BIN(lt_vh8_t, lt_vh8_sub_sat, VALU, lt__h8_sub_sat)
LT__V16_BIN(lt_vh8_t, lt_vh8_mul_sat, VMUL, lt__h8_mul_sat)
LT__V16_CMP(lt_vh8_t, lt_vh8_cmplt, VCMP, <)
LT__V16_CMP(lt_vh8_t, lt_vh8_cmple, VCMP, <=)

/* s7.8 -> s15.16 per lane (exact) and back (half up, saturating). Cost: VCVT x1. */
LT_INLINE lt_vq16_t lt_vq16_from_h8(lt_vh8_t a) /* VCVT x1 */
{
    lt_vq16_t r;
    int i;
    LT_COST(VCVT, 1);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = (int32_t)a.l[i] * 256;
    return r;
}

LT_INLINE lt_vh8_t lt_vh8_from_q16_sat(lt_vq16_t a) /* VCVT x1 */
{
    lt_vh8_t r;
    int i;
    LT_COST(VCVT, 1);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = lt__h8_from_q16_sat(a.l[i]);
    return r;
}

/* ---- float32 lanes ------------------------------------------------------------------------- */
#if LT_CFG_FLOAT32
/* IEEE binary32, round to nearest even, no contraction (builds use -ffp-contract=off), so results
 * are bit-identical on every target. min/max return b when either input is NaN (a < b ? a : b). */
LT_INLINE float lt__f32_add(float a, float b) { return a + b; }
LT_INLINE float lt__f32_sub(float a, float b) { return a - b; }
LT_INLINE float lt__f32_mul(float a, float b) { return a * b; }
LT_INLINE float lt__f32_div(float a, float b) { return a / b; }
LT_INLINE float lt__f32_min(float a, float b) { return a < b ? a : b; }
LT_INLINE float lt__f32_max(float a, float b) { return a > b ? a : b; }
LT_INLINE float lt__f32_rcp(float a) { return 1.0f / a; }
/* |a| clears the sign bit (so |-0| = +0 and |-NaN| = +NaN, as fabsf); a union is C99's way to
 * reinterpret the bits. */
LT_INLINE float lt__f32_abs(float a)
{
    union {
        float f;
        uint32_t u;
    } v;
    v.f = a;
    v.u &= 0x7FFFFFFFu;
    return v.f;
}
LT_INLINE float lt__f32_neg(float a) { return -a; }
LT__V16_MOVE(lt_vf32_t, float, lt_vf32, FADD, VRED)
LT__V16_BIN(lt_vf32_t, lt_vf32_add, FADD, lt__f32_add)
LT__V16_BIN(lt_vf32_t, lt_vf32_sub, FADD, lt__f32_sub)
LT__V16_BIN(lt_vf32_t, lt_vf32_mul, FMUL, lt__f32_mul)
LT__V16_BIN(lt_vf32_t, lt_vf32_div, FDIV, lt__f32_div)
LT__V16_BIN(lt_vf32_t, lt_vf32_min, FADD, lt__f32_min)
LT__V16_BIN(lt_vf32_t, lt_vf32_max, FADD, lt__f32_max)
LT__V16_UN(lt_vf32_t, lt_vf32_rcp, FDIV, lt__f32_rcp)
LT__V16_UN(lt_vf32_t, lt_vf32_abs, FADD, lt__f32_abs)
LT__V16_UN(lt_vf32_t, lt_vf32_neg, FADD, lt__f32_neg)
LT__V16_CMPF(lt_vf32_t, lt_vf32_cmplt, FCMP, <, flt)
LT__V16_CMPF(lt_vf32_t, lt_vf32_cmple, FCMP, <=, fle)
LT__V16_CMPF(lt_vf32_t, lt_vf32_cmpgt, FCMP, >, fgt)
LT__V16_CMPF(lt_vf32_t, lt_vf32_cmpge, FCMP, >=, fge)
LT__V16_CMPF(lt_vf32_t, lt_vf32_cmpeq, FCMP, ==, feq)
LT_INLINE float lt__f32_mul3(float a) { return a * 3.0f; }
/* 3 a per lane (one rounding). Cost: FMUL x1. */
LT__V16_UN(lt_vf32_t, lt_vf32_mul3, FMUL, lt__f32_mul3)

/* a * 2^e per lane (exact while the result stays normal; 2^e is built by doubling or halving, so
 * |e| <= 126). Cost: VBCAST x1, FMUL x1 (a broadcast of 2^e and a multiply). */
LT_INLINE lt_vf32_t lt_vf32_mul_pow2(lt_vf32_t a, int e) /* VBCAST x1, FMUL x1 */
{
    float f = 1.0f;
    int j;
    for (j = 0; j < e; j++)
        f = f * 2.0f;
    for (j = 0; j > e; j--)
        f = f * 0.5f;
    return lt_vf32_mul(a, lt_vf32_set1(f));
}

/* a b - c d per lane (one component of a cross product), each product and the difference rounded
 * once, in this order. Cost: FMUL x2, FADD x1. */
LT_INLINE lt_vf32_t lt_vf32_cross(lt_vf32_t a, lt_vf32_t b, lt_vf32_t c,
                                  lt_vf32_t d) /* FMUL x2, FADD x1 */
{
    return lt_vf32_sub(lt_vf32_mul(a, b), lt_vf32_mul(c, d));
}

/* (ax bx + ay by) + az bz per lane, rounded in this order. Cost: FMUL x3, FADD x2. */
LT_INLINE lt_vf32_t lt_vf32_dot3(lt_vf32_t ax, lt_vf32_t ay, lt_vf32_t az, lt_vf32_t bx,
                                 lt_vf32_t by, lt_vf32_t bz) /* FMUL x3, FADD x2 */
{
    return lt_vf32_add(lt_vf32_add(lt_vf32_mul(ax, bx), lt_vf32_mul(ay, by)), lt_vf32_mul(az, bz));
}

/* Lanes holding +-FLT_MAX (a clamped reciprocal). Cost: VBCAST x2, FCMP x2. */
LT_INLINE lt_mask16_t lt_vf32_cmpsat(lt_vf32_t a) /* VBCAST x2, FCMP x2 */
{
    return (lt_mask16_t)(lt_vf32_cmpeq(a, lt_vf32_set1(3.40282347e38f)) |
                         lt_vf32_cmpeq(a, lt_vf32_set1(-3.40282347e38f)));
}

/* a / n per lane for a count n (int32 lanes, converted exactly below 2^24), lanes in k with
 * n > 0; other lanes become 0. IEEE division. Cost: FDIV x1. */
LT_INLINE lt_vf32_t lt_vf32_div_i32_z(lt_mask16_t k, lt_vf32_t a, lt_vi32_t n) /* FDIV x1 */
{
    lt_vf32_t r;
    int i;
    LT_COST(FDIV, 1);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = LT__ON(k, i) && n.l[i] > 0 ? a.l[i] / (float)n.l[i] : 0.0f;
    return r;
}

/* 1 / d per lane, IEEE, then clamped to +-FLT_MAX: +-0 gives +-FLT_MAX (the sign of -0.0 survives
 * through 1/d = -inf), NaN stays NaN. Cost: FDIV x1, FCMP x1, VALU x1 (divide, compare, select). */
LT_INLINE lt_vf32_t lt_vf32_rcp_sat(lt_vf32_t d) /* FDIV x1, FCMP x1, VALU x1 */
{
    lt_vf32_t r;
    int i;
    LT_COST(FDIV, 1);
    LT_COST(FCMP, 1);
    LT_COST(VALU, 1);
    for (i = 0; i < LT_LANES; i++) {
        float q = 1.0f / d.l[i];
        if (q > 3.40282347e38f)
            q = 3.40282347e38f;
        else if (q < -3.40282347e38f)
            q = -3.40282347e38f;
        r.l[i] = q;
    }
    return r;
}

/* 1 / d per lane clamped to +-FLT_MAX, with d == +-0 giving `zero` (the caller's side, e.g.
 * +FLT_MAX for an upper interval end), the float twin of lt_vq16_recip_q30_sat. Cost: FDIV x1
 * (the clamp and the zero select ride on the divide: the tally lt_frusta.c always charged). */
LT_INLINE lt_vf32_t lt_vf32_recip_sat(lt_vf32_t d, float zero) /* FDIV x1 */
{
    lt_vf32_t r;
    int i;
    LT_COST(FDIV, 1);
    for (i = 0; i < LT_LANES; i++) {
        float q = d.l[i] == 0.0f ? zero : 1.0f / d.l[i];
        r.l[i] = q > 3.40282347e38f ? 3.40282347e38f : (q < -3.40282347e38f ? -3.40282347e38f : q);
    }
    return r;
}
#endif

#ifdef __cplusplus
}
#endif

#include "lt_v16w.h"

#endif /* LT_V16_H */
