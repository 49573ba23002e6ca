/* lt_port.h - the only file that tests the compiler or the architecture.
 * Defines LT_INLINE, LT_ALIGN, LT_RESTRICT, LT_NORETURN, LT_STATIC_ASSERT and the portable integer
 * primitives (clz, saturate, 32x32->64 multiply, arithmetic right shift) that every other file uses.
 * Each primitive has a plain-C body (CMSIS none.h style); tests/unit/test_port.c checks them on every target.
 * Builds: all (freestanding C99).
 */
#ifndef LT_PORT_H
#define LT_PORT_H

#include <stdint.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__) || defined(__clang__)
#define LT_INLINE static inline __attribute__((always_inline))
#define LT_NOINLINE __attribute__((noinline))
#define LT_ALIGN(n) __attribute__((aligned(n)))
#define LT_NORETURN __attribute__((noreturn))
#define LT_UNUSED __attribute__((unused))
#define LT_RESTRICT __restrict__
#else
#define LT_INLINE static inline
#define LT_NOINLINE
#define LT_ALIGN(n)
#define LT_NORETURN
#define LT_UNUSED
#define LT_RESTRICT
#endif

/* C99 compile-time assertion: a negative array size fails the build. */
#define LT__CAT2(a, b) a##b
#define LT__CAT(a, b) LT__CAT2(a, b)
/* The typedef is named after __COUNTER__ where the compiler has it (GCC, Clang), so a header's and
 * a source file's assertions on the same line number do not collide; else after __LINE__. */
#ifdef __COUNTER__
#define LT_STATIC_ASSERT(c, msg) typedef char LT__CAT(lt__static_assert_, __COUNTER__)[(c) ? 1 : -1]
#else
#define LT_STATIC_ASSERT(c, msg) typedef char LT__CAT(lt__static_assert_, __LINE__)[(c) ? 1 : -1]
#endif

/* Arithmetic right shift of a signed 32-bit value by s (0..31), rounding toward minus infinity.
 * C99 leaves >> of a negative value implementation-defined. GCC and Clang define it as the
 * arithmetic shift (GCC manual, "Integers implementation"), one instruction (ASR, SRA, SAR);
 * elsewhere it is built from unsigned ops: complementing a negative value makes it non-negative,
 * shifts it, and complements back. Both give the same bits (tests/unit/test_port.c). */
LT_INLINE int32_t lt__asr32(int32_t v, unsigned s)
{
#if defined(__GNUC__) || defined(__clang__)
    return v >> s;
#else
    if (v >= 0)
        return (int32_t)((uint32_t)v >> s);
    return (int32_t)~(~(uint32_t)v >> s);
#endif
}

/* 64-bit twin of lt__asr32, s in 0..63 (on 32-bit cores GCC inlines the two-word shift). */
LT_INLINE int64_t lt__asr64(int64_t v, unsigned s)
{
#if defined(__GNUC__) || defined(__clang__)
    return v >> s;
#else
    if (v >= 0)
        return (int64_t)((uint64_t)v >> s);
    return (int64_t)~(~(uint64_t)v >> s);
#endif
}

/* Count leading zeros of a 32-bit value; lt__clz32(0) = 32 (defined, unlike __builtin_clz, which
 * GCC and Clang turn into one instruction where the core has it: CLZ on Arm v7-M and v8.1-M, LZCNT
 * or BSR on x86; RV32IMAC has none and gets libgcc's __clzsi2). */
LT_INLINE unsigned lt__clz32(uint32_t x)
{
#if defined(__GNUC__) || defined(__clang__)
    return x == 0 ? 32u : (unsigned)__builtin_clz(x);
#else
    unsigned n = 0;
    if (x == 0)
        return 32;
    if ((x & 0xFFFF0000u) == 0) { n += 16; x <<= 16; }
    if ((x & 0xFF000000u) == 0) { n += 8;  x <<= 8; }
    if ((x & 0xF0000000u) == 0) { n += 4;  x <<= 4; }
    if ((x & 0xC0000000u) == 0) { n += 2;  x <<= 2; }
    if ((x & 0x80000000u) == 0) { n += 1; }
    return n;
#endif
}

/* Count leading zeros of a 64-bit value; lt__clz64(0) = 64. */
LT_INLINE unsigned lt__clz64(uint64_t x)
{
    uint32_t hi = (uint32_t)(x >> 32);
    return hi != 0 ? lt__clz32(hi) : 32u + lt__clz32((uint32_t)x);
}

/* Count trailing zeros; lt__ctz32(0) = 32. Used by the mask bit-scan. */
LT_INLINE unsigned lt__ctz32(uint32_t x)
{
    if (x == 0)
        return 32;
    return 31u - lt__clz32(x & (0u - x));
}

/* Population count of a 32-bit value (SWAR). */
LT_INLINE unsigned lt__popcount32(uint32_t x)
{
    x = x - ((x >> 1) & 0x55555555u);
    x = (x & 0x33333333u) + ((x >> 2) & 0x33333333u);
    x = (x + (x >> 4)) & 0x0F0F0F0Fu;
    return (unsigned)((x * 0x01010101u) >> 24);
}

/* Saturate a 64-bit value to the int32 range. */
LT_INLINE int32_t lt__ssat32(int64_t v)
{
    if (v > INT32_MAX)
        return INT32_MAX;
    if (v < INT32_MIN)
        return INT32_MIN;
    return (int32_t)v;
}

/* Saturate a 32-bit value to the int16 range. */
LT_INLINE int16_t lt__ssat16(int32_t v)
{
    if (v > INT16_MAX)
        return INT16_MAX;
    if (v < INT16_MIN)
        return INT16_MIN;
    return (int16_t)v;
}

/* Wrap a 64-bit value to int32 (two's complement). Converting an out-of-range value to a signed
 * type is implementation-defined in C99, so the wrap goes through uint32_t and a sign test. */
LT_INLINE int32_t lt__wrap32(int64_t v)
{
    uint32_t u = (uint32_t)(uint64_t)v;
    if (u <= (uint32_t)INT32_MAX)
        return (int32_t)u;
    return (int32_t)(u - 0x80000000u) + INT32_MIN;
}

/* Exact signed 32x32 -> 64 product (SMULL on Arm, MUL/MULH on RV32). */
LT_INLINE int64_t lt__mul32x32_64(int32_t a, int32_t b)
{
    return (int64_t)a * (int64_t)b;
}

/* 64-bit division on 32-bit cores. There C's 64-bit '/' is a library call (libgcc's
 * __udivmoddi4: about 100-200 instructions on Cortex-M4), while most of the kernels' divisions
 * have a divisor below 2^32 and a quotient below 2^32 (the hit parameter, the reprojection's
 * divide by H, its clip ratios). Those take lt__udiv64_32, two 32-bit hardware divides. The
 * results are exact either way, so every target gives the same bits. LT_DIV64_NARROW is 1 where
 * pointers are 32 bits wide; a build (or a test, to check this path on the host) may set it. */
#ifndef LT_DIV64_NARROW
#if UINTPTR_MAX <= 0xFFFFFFFFu
#define LT_DIV64_NARROW 1
#else
#define LT_DIV64_NARROW 0
#endif
#endif

/* (n1 2^32 + n0) / d and its remainder *r for n1 < d (so the quotient fits 32 bits): Knuth's
 * algorithm D with 16-bit digits after normalising d (Hacker's Delight, divlu). Every product and
 * sum below is taken mod 2^32 where the true value is known to fit. */
LT_INLINE uint32_t lt__udiv64_32(uint32_t n1, uint32_t n0, uint32_t d, uint32_t *r)
{
    unsigned s = lt__clz32(d);
    uint32_t dn1, dn0, un32, un10, un1, un0, q1, q0, rhat, un21;
    d <<= s;
    dn1 = d >> 16;
    dn0 = d & 0xFFFFu;
    un32 = s == 0 ? n1 : (n1 << s) | (n0 >> (32u - s));
    un10 = n0 << s;
    un1 = un10 >> 16;
    un0 = un10 & 0xFFFFu;
    q1 = un32 / dn1;
    rhat = un32 - q1 * dn1;
    while (q1 > 0xFFFFu || q1 * dn0 > ((rhat << 16) | un1)) {
        q1 -= 1u;
        rhat += dn1;
        if (rhat > 0xFFFFu)
            break;
    }
    un21 = (un32 << 16) + un1 - q1 * d;
    q0 = un21 / dn1;
    rhat = un21 - q0 * dn1;
    while (q0 > 0xFFFFu || q0 * dn0 > ((rhat << 16) | un0)) {
        q0 -= 1u;
        rhat += dn1;
        if (rhat > 0xFFFFu)
            break;
    }
    *r = ((un21 << 16) + un0 - q0 * d) >> s;
    return (q1 << 16) | q0;
}

/* n / d and *r = n % d, d != 0. */
LT_INLINE uint64_t lt__udivmod64(uint64_t n, uint64_t d, uint64_t *r)
{
#if LT_DIV64_NARROW
    if ((d >> 32) == 0 && (n >> 32) < d) {
        uint32_t r32, q = lt__udiv64_32((uint32_t)(n >> 32), (uint32_t)n, (uint32_t)d, &r32);
        *r = r32;
        return q;
    }
#endif
    *r = n % d;
    return n / d;
}

/* |v| as uint64 (INT64_MIN gives 2^63), and the int64 of -u for u <= 2^63, without a conversion
 * of an out-of-range value. */
LT_INLINE uint64_t lt__u64_abs(int64_t v)
{
    return v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
}

LT_INLINE int64_t lt__i64_neg_u(uint64_t u)
{
    return u == 0 ? 0 : -(int64_t)(u - 1u) - 1;
}

/* Floor division of 64-bit values, b != 0 and not (a == INT64_MIN and b == -1): on the
 * magnitudes, then -q, one less when the signs differ and the division was not exact. */
LT_INLINE int64_t lt__divfloor64(int64_t a, int64_t b)
{
    uint64_t r, q = lt__udivmod64(lt__u64_abs(a), lt__u64_abs(b), &r);
    if ((a < 0) == (b < 0))
        return (int64_t)q;
    return lt__i64_neg_u(q + (r != 0));
}

/* Freestanding memory helpers: the core never calls libc, and GCC may emit memcpy/memset for
 * struct copies, which firmware targets provide through these (firmware/targets/common/lt_rt.c). */
void *lt__memset(void *dst, int c, size_t n);
void *lt__memcpy(void *LT_RESTRICT dst, const void *LT_RESTRICT src, size_t n);

#ifdef __cplusplus
}
#endif
#endif /* LT_PORT_H */
