/* lt_test_util.h - helpers shared by the cmocka unit tests (tests/unit/test_*.c): a seeded xorshift
 * PRNG with edge-heavy value generators, the mask pattern classes every lane test walks, buffer
 * poisoning with tail checks (0xA5, CMSIS ASSERT_EMPTY_TAIL style) and the one-line error reports
 * ("name: N cases, max |err| E ulp (bound B), S saturated"). Header only; every function is static
 * inline so a test that skips one gets no unused-function warning. Builds: host, sim, asan.
 */
#ifndef LT_TEST_UTIL_H
#define LT_TEST_UTIL_H

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "lt/lt_port.h"

/* ---- PRNG: xorshift64* (Vigna), seeded through splitmix64 so any seed (even 0) works --------- */

typedef struct ltt_rng {
    uint64_t s; /* state, never 0 */
} ltt_rng_t;

static inline void ltt_rng_seed(ltt_rng_t *r, uint64_t seed)
{
    uint64_t z = seed + 0x9E3779B97F4A7C15u;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    z ^= z >> 31;
    r->s = z != 0 ? z : 0x2545F4914F6CDD1Du;
}

static inline uint64_t ltt_rng_u64(ltt_rng_t *r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    return r->s * 0x2545F4914F6CDD1Du;
}

static inline uint32_t ltt_rng_u32(ltt_rng_t *r) { return (uint32_t)(ltt_rng_u64(r) >> 32); }

/* Two's complement reinterpretation without implementation-defined conversions. */
static inline int32_t ltt_i32(uint32_t u)
{
    return u <= (uint32_t)INT32_MAX ? (int32_t)u : (int32_t)(u - 0x80000000u) + INT32_MIN;
}

static inline int64_t ltt_i64(uint64_t u)
{
    return u <= (uint64_t)INT64_MAX ? (int64_t)u : (int64_t)(u - 0x8000000000000000u) + INT64_MIN;
}

static inline int32_t ltt_rng_i32(ltt_rng_t *r) { return ltt_i32(ltt_rng_u32(r)); }
static inline int64_t ltt_rng_i64(ltt_rng_t *r) { return ltt_i64(ltt_rng_u64(r)); }

/* Helpers that draw twice keep the draws in separate statements: C leaves the evaluation order of
 * function arguments and operands unspecified, and a different order between builds (seen between
 * -O2 and ASan builds) would change the case list. */

/* Uniform in [0, n), n >= 1 (multiply-shift; bias < 2^-32, irrelevant here). */
static inline uint32_t ltt_rng_below(ltt_rng_t *r, uint32_t n)
{
    return (uint32_t)(((uint64_t)ltt_rng_u32(r) * n) >> 32);
}

/* Uniform in [lo, hi] (inclusive), lo <= hi. */
static inline int32_t ltt_rng_range(ltt_rng_t *r, int32_t lo, int32_t hi)
{
    uint64_t span = (uint64_t)((int64_t)hi - (int64_t)lo) + 1u;
    return (int32_t)((int64_t)lo + (int64_t)((ltt_rng_u64(r) >> 11) % span));
}

/* Random int32 shifted right (arithmetic) by lo + [0, n): magnitudes spread over powers of two. */
static inline int32_t ltt_rng_i32_shr(ltt_rng_t *r, unsigned lo, unsigned n)
{
    unsigned s = lo + ltt_rng_below(r, n);
    return lt__asr32(ltt_rng_i32(r), s);
}

/* Random int64 shifted right (arithmetic) by [0, n), n <= 64. */
static inline int64_t ltt_rng_i64_shr(ltt_rng_t *r, unsigned n)
{
    unsigned s = ltt_rng_below(r, n);
    return lt__asr64(ltt_rng_i64(r), s);
}

/* Random uint64 shifted right by [0, n), n <= 64. */
static inline uint64_t ltt_rng_u64_shr(ltt_rng_t *r, unsigned n)
{
    unsigned s = ltt_rng_below(r, n);
    return ltt_rng_u64(r) >> s;
}

/* Uniform double in [0, 1) with 53 random bits. */
static inline double ltt_rng_unit(ltt_rng_t *r)
{
    return (double)(ltt_rng_u64(r) >> 11) * (1.0 / 9007199254740992.0);
}

/* Uniform double in [lo, hi). */
static inline double ltt_rng_uniform(ltt_rng_t *r, double lo, double hi)
{
    return lo + (hi - lo) * ltt_rng_unit(r);
}

/* The int32 edges every fixed-point case list starts from: 0, +-1 ulp, the 16-bit carry edges
 * (0x7FFF/0x8000/0xFFFF/0x10000), one in s15.16 and s1.30, and the int32 extremes. */
static const int32_t ltt_edges32[] = {
    0, 1, -1, 2, -2, 3, -3,
    0x7FFF, -0x7FFF, 0x8000, -0x8000, 0x8001, -0x8001, 0xFFFF, -0xFFFF,
    0x10000, -0x10000, 0x10001, -0x10001, 0x18000, -0x18000, 0x7FFF8000, -0x7FFF8000,
    0x00FFFFFF, -0x00FFFFFF, 0x01000000, -0x01000000, 0x3FFFFFFF, -0x3FFFFFFF,
    0x40000000, -0x40000000, 0x40000001, 0x7FFF0000, -0x7FFF0000, 0x7FFFFFFE,
    INT32_MAX, -INT32_MAX, INT32_MIN,
};
#define LTT_N_EDGES32 (sizeof ltt_edges32 / sizeof ltt_edges32[0])

/* int32 with a random magnitude class: 1/8 an edge value, 1/8 uniform over int32, otherwise
 * |v| < 2^e for a uniform e in 0..31 with a random sign, so small, mid and huge values (and
 * products near every saturation point) are all common. */
static inline int32_t ltt_rng_i32_wide(ltt_rng_t *r)
{
    uint32_t c = ltt_rng_below(r, 8);
    uint32_t e, m;
    if (c == 0)
        return ltt_edges32[ltt_rng_below(r, (uint32_t)LTT_N_EDGES32)];
    if (c == 1)
        return ltt_rng_i32(r);
    e = ltt_rng_below(r, 32);
    m = e == 0 ? 0u : (ltt_rng_u32(r) >> (32u - e));
    if (ltt_rng_u32(r) & 1u) {
        if (m == 0x80000000u)
            return INT32_MIN;
        return -(int32_t)m;
    }
    return (int32_t)(m & 0x7FFFFFFFu);
}

/* ---- mask pattern classes -------------------------------------------------------------------- */

/* Bit i of mask m as an int (0 or 1), computed in unsigned arithmetic. */
#define LTT_ON(m, i) ((int)((((unsigned)(m)) >> (unsigned)(i)) & 1u))

/* none, all, alternating x2, each single lane, then LTT_MASK_RANDOM random masks. */
#define LTT_MASK_RANDOM 100
#define LTT_MASK_COUNT (4 + 16 + LTT_MASK_RANDOM)

static inline unsigned ltt_masks(uint16_t out[LTT_MASK_COUNT], uint64_t seed)
{
    ltt_rng_t r;
    unsigned n = 0, i;
    ltt_rng_seed(&r, seed);
    out[n++] = 0x0000u;
    out[n++] = 0xFFFFu;
    out[n++] = 0x5555u;
    out[n++] = 0xAAAAu;
    for (i = 0; i < 16; i++)
        out[n++] = (uint16_t)(1u << i);
    for (i = 0; i < LTT_MASK_RANDOM; i++)
        out[n++] = (uint16_t)ltt_rng_u32(&r);
    return n;
}

/* Class name of mask number idx of ltt_masks(), for failure messages. */
static inline const char *ltt_mask_class(unsigned idx)
{
    if (idx == 0)
        return "none";
    if (idx == 1)
        return "all";
    if (idx < 4)
        return "alternating";
    if (idx < 20)
        return "single";
    return "random";
}

/* ---- poison and tail guards ------------------------------------------------------------------ */

#define LTT_POISON 0xA5u

static inline void ltt_poison(void *p, size_t n) { memset(p, (int)LTT_POISON, n); }

/* Number of bytes in [from, to) of p that no longer hold the poison byte (0 = untouched). */
static inline size_t ltt_touched(const void *p, size_t from, size_t to)
{
    const unsigned char *b = (const unsigned char *)p;
    size_t i, n = 0;
    for (i = from; i < to; i++)
        n += b[i] != LTT_POISON;
    return n;
}

/* ---- reports --------------------------------------------------------------------------------- */

/* printf for report lines: everything a test prints goes through here, flushed, so the summaries
 * interleave correctly with cmocka's own output. */
static inline void ltt_report(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    (void)vprintf(fmt, ap);
    va_end(ap);
    (void)fflush(stdout);
}

/* Error statistics of one op: cases, max |err| in `unit`, bound, saturations, ties (half-way
 * rounding cases seen) and bad (cases over the bound or otherwise wrong). */
typedef struct ltt_stat {
    const char *name;
    const char *unit;
    double bound;
    unsigned long cases, sat, ties, bad;
    double max_err;
} ltt_stat_t;

static inline void ltt_stat_init(ltt_stat_t *s, const char *name, const char *unit, double bound)
{
    s->name = name;
    s->unit = unit;
    s->bound = bound;
    s->cases = s->sat = s->ties = s->bad = 0;
    s->max_err = 0.0;
}

/* Record one case with error err; returns 1 if |err| <= bound. */
static inline int ltt_stat_add(ltt_stat_t *s, double err)
{
    double a = err < 0.0 ? -err : err;
    s->cases++;
    if (a > s->max_err)
        s->max_err = a;
    return a <= s->bound;
}

/* Count a failure and print its description (the first 8 per stat only). */
static inline void ltt_stat_fail(ltt_stat_t *s, const char *fmt, ...)
{
    va_list ap;
    if (s->bad++ >= 8)
        return;
    (void)printf("  FAIL %s: ", s->name);
    va_start(ap, fmt);
    (void)vprintf(fmt, ap);
    va_end(ap);
    (void)printf("\n");
    (void)fflush(stdout);
}

/* The one-line summary every numeric test prints: cases, max error with its unit, the bound,
 * saturations (then ties and failures when there are any). */
static inline void ltt_stat_print(const ltt_stat_t *s)
{
    ltt_report("%s: %lu cases, max |err| %.6g%s%s (bound %g), %lu saturated", s->name, s->cases,
               s->max_err, s->unit[0] != '\0' ? " " : "", s->unit, s->bound, s->sat);
    if (s->ties != 0)
        ltt_report(", %lu ties", s->ties);
    if (s->bad != 0)
        ltt_report(", %lu FAILED", s->bad);
    ltt_report("\n");
}

#endif /* LT_TEST_UTIL_H */
