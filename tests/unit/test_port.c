/* test_port.c - cmocka tests of the portable primitives of lt_port.h and the freestanding memory
 * helpers of lt_fx.c. Each primitive is checked against an independent reference written another
 * way: shifts against floor division in long double, bit counts against naive bit loops, saturation
 * and wrapping against long double arithmetic, memory helpers against poisoned guard bytes.
 * Builds: host, sim, asan (any LT_COST_MODE: nothing here charges costs).
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lt/lt_fx.h"
#include "lt_test_util.h"

#define N_RANDOM 20000

/* long double must hold every int64 exactly for the references below (x87 80-bit: 64-bit
 * significand). A target without it would need another reference, so refuse to build. */
LT_STATIC_ASSERT(LDBL_MANT_DIG >= 64, "references need a 64-bit long double significand");

/* ---- arithmetic shifts --------------------------------------------------------------------- */

static void test_asr32(void **state)
{
    ltt_rng_t r;
    ltt_stat_t st;
    unsigned s, i;
    (void)state;
    ltt_rng_seed(&r, 1);
    ltt_stat_init(&st, "lt__asr32", "", 0);
    for (i = 0; i < LTT_N_EDGES32 + N_RANDOM; i++) {
        int32_t v = i < LTT_N_EDGES32 ? ltt_edges32[i] : ltt_rng_i32_wide(&r);
        for (s = 0; s < 32; s++) {
            /* floor(v / 2^s), exact in double: v has 32 bits, the quotient is a power-2 scale */
            double ref = floor(ldexp((double)v, -(int)s));
            int32_t got = lt__asr32(v, s);
            if (!ltt_stat_add(&st, (double)got - ref))
                ltt_stat_fail(&st, "v=%ld s=%u got %ld want %.0f", (long)v, s, (long)got, ref);
        }
    }
    ltt_stat_print(&st);
    assert_int_equal(st.bad, 0);
}

static void test_asr64(void **state)
{
    ltt_rng_t r;
    ltt_stat_t st;
    static const int64_t edge[] = { 0, 1, -1, 2, -2, INT64_MAX, INT64_MIN, INT64_MIN + 1,
                                    (int64_t)INT32_MIN, (int64_t)INT32_MAX, -((int64_t)1 << 62),
                                    ((int64_t)1 << 62), -((int64_t)1 << 32) - 1 };
    unsigned s, i, ne = (unsigned)(sizeof edge / sizeof edge[0]);
    (void)state;
    ltt_rng_seed(&r, 2);
    ltt_stat_init(&st, "lt__asr64", "", 0);
    for (i = 0; i < ne + N_RANDOM; i++) {
        int64_t v;
        if (i < ne)
            v = edge[i];
        else /* random magnitude class: shift a random value down by 0..63 */
            v = ltt_rng_i64_shr(&r, 64);
        for (s = 0; s < 64; s++) {
            long double ref = floorl(ldexpl((long double)v, -(int)s));
            int64_t got = lt__asr64(v, s);
            if (!ltt_stat_add(&st, (double)((long double)got - ref)))
                ltt_stat_fail(&st, "v=%lld s=%u got %lld want %.0Lf", (long long)v, s,
                              (long long)got, ref);
        }
    }
    ltt_stat_print(&st);
    assert_int_equal(st.bad, 0);
}

/* ---- bit counts ----------------------------------------------------------------------------- */

static unsigned naive_clz(uint64_t x, unsigned bits)
{
    unsigned n = 0;
    int b;
    for (b = (int)bits - 1; b >= 0; b--) {
        if ((x >> b) & 1u)
            break;
        n++;
    }
    return n;
}

static unsigned naive_ctz32(uint32_t x)
{
    unsigned n = 0;
    while (n < 32 && ((x >> n) & 1u) == 0)
        n++;
    return n;
}

static unsigned naive_popcount32(uint32_t x)
{
    unsigned n = 0, b;
    for (b = 0; b < 32; b++)
        n += (x >> b) & 1u;
    return n;
}

/* Value i of the bit-count case list: 0, all ones, every single bit, every low-ones mask, then
 * random values with a random number of leading zeros. */
static uint64_t bit_case(unsigned i, ltt_rng_t *r)
{
    if (i == 0)
        return 0;
    if (i == 1)
        return ~(uint64_t)0;
    if (i < 2 + 64)
        return (uint64_t)1 << (i - 2);
    if (i < 2 + 128)
        return ((uint64_t)2 << (i - 66)) - 1u;
    return ltt_rng_u64_shr(r, 64);
}

static void test_bitcounts(void **state)
{
    ltt_rng_t r;
    unsigned i, n = 2 + 128 + N_RANDOM, bad = 0;
    (void)state;
    ltt_rng_seed(&r, 3);
    for (i = 0; i < n; i++) {
        uint64_t x = bit_case(i, &r);
        uint32_t lo = (uint32_t)x, hi = (uint32_t)(x >> 32);
        if (lt__clz64(x) != naive_clz(x, 64))
            bad++;
        if (lt__clz32(lo) != naive_clz(lo, 32) || lt__clz32(hi) != naive_clz(hi, 32))
            bad++;
        if (lt__ctz32(lo) != naive_ctz32(lo) || lt__ctz32(hi) != naive_ctz32(hi))
            bad++;
        if (lt__popcount32(lo) != naive_popcount32(lo) ||
            lt__popcount32(hi) != naive_popcount32(hi))
            bad++;
        if (bad != 0) {
            ltt_report("  FAIL bit counts at x=0x%016llx\n", (unsigned long long)x);
            break;
        }
    }
    ltt_report("lt__clz32/clz64/ctz32/popcount32: %u cases (0, all ones, 64 single bits, "
               "64 low masks, random), %u mismatches vs naive loops (bound 0)\n", n, bad);
    assert_int_equal(lt__clz32(0), 32);
    assert_int_equal(lt__clz64(0), 64);
    assert_int_equal(lt__ctz32(0), 32);
    assert_int_equal(lt__popcount32(0), 0);
    assert_int_equal(bad, 0);
}

/* ---- saturation, wrapping, widening multiply, floor division --------------------------------- */

static void test_ssat_wrap(void **state)
{
    ltt_rng_t r;
    ltt_stat_t s32, s16, w32;
    static const int64_t edge[] = { 0, 1, -1, INT32_MAX, (int64_t)INT32_MAX + 1, INT32_MIN,
                                    (int64_t)INT32_MIN - 1, INT64_MAX, INT64_MIN,
                                    (int64_t)UINT32_MAX, (int64_t)UINT32_MAX + 1,
                                    -(int64_t)UINT32_MAX - 1, INT16_MAX, INT16_MAX + 1, INT16_MIN,
                                    INT16_MIN - 1, 0x80000000LL, 0x17FFFFFFFLL };
    unsigned i, ne = (unsigned)(sizeof edge / sizeof edge[0]);
    (void)state;
    ltt_rng_seed(&r, 4);
    ltt_stat_init(&s32, "lt__ssat32", "", 0);
    ltt_stat_init(&s16, "lt__ssat16", "", 0);
    ltt_stat_init(&w32, "lt__wrap32", "", 0);
    for (i = 0; i < ne + N_RANDOM; i++) {
        int64_t v = i < ne ? edge[i] : ltt_rng_i64_shr(&r, 64);
        int32_t v32 = (int32_t)lt__ssat32(v); /* a valid int32 input for ssat16 */
        long double lv = (long double)v;
        long double want32 = lv > 2147483647.0L ? 2147483647.0L
                                                : (lv < -2147483648.0L ? -2147483648.0L : lv);
        long double want16 = v32 > 32767 ? 32767.0L : (v32 < -32768 ? -32768.0L : (long double)v32);
        /* wrap: v - 2^32 * floor((v + 2^31) / 2^32), exact in long double */
        long double wantw = lv - 4294967296.0L * floorl((lv + 2147483648.0L) / 4294967296.0L);
        int32_t g32 = lt__ssat32(v);
        int16_t g16 = lt__ssat16(v32);
        int32_t gw = lt__wrap32(v);
        s32.sat += (long double)g32 != lv;
        s16.sat += g16 != v32;
        if (!ltt_stat_add(&s32, (double)((long double)g32 - want32)))
            ltt_stat_fail(&s32, "v=%lld got %ld", (long long)v, (long)g32);
        if (!ltt_stat_add(&s16, (double)((long double)g16 - want16)))
            ltt_stat_fail(&s16, "v=%ld got %d", (long)v32, (int)g16);
        if (!ltt_stat_add(&w32, (double)((long double)gw - wantw)))
            ltt_stat_fail(&w32, "v=%lld got %ld want %.0Lf", (long long)v, (long)gw, wantw);
    }
    ltt_stat_print(&s32);
    ltt_stat_print(&s16);
    ltt_stat_print(&w32);
    assert_int_equal(s32.bad + s16.bad + w32.bad, 0);
}

static void test_mul32x32_64(void **state)
{
    ltt_rng_t r;
    ltt_stat_t st;
    unsigned i;
    (void)state;
    ltt_rng_seed(&r, 5);
    ltt_stat_init(&st, "lt__mul32x32_64", "", 0);
    for (i = 0; i < LTT_N_EDGES32 * LTT_N_EDGES32 + N_RANDOM; i++) {
        int32_t a, b;
        int64_t got;
        if (i < LTT_N_EDGES32 * LTT_N_EDGES32) {
            a = ltt_edges32[i / LTT_N_EDGES32];
            b = ltt_edges32[i % LTT_N_EDGES32];
        } else {
            a = ltt_rng_i32_wide(&r);
            b = ltt_rng_i32_wide(&r);
        }
        got = lt__mul32x32_64(a, b);
        /* the product has at most 63 significant bits: exact in long double */
        if (!ltt_stat_add(&st, (double)((long double)got - (long double)a * (long double)b)))
            ltt_stat_fail(&st, "%ld * %ld got %lld", (long)a, (long)b, (long long)got);
    }
    ltt_stat_print(&st);
    assert_int_equal(st.bad, 0);
}

static void test_divfloor64(void **state)
{
    ltt_rng_t r;
    ltt_stat_t st;
    static const int64_t edge[] = { 0, 1, -1, 2, -2, 3, -3, 7, -7, INT64_MAX, INT64_MIN,
                                    INT64_MIN + 1, (int64_t)INT32_MIN, (int64_t)INT32_MAX };
    unsigned i, ne = (unsigned)(sizeof edge / sizeof edge[0]);
    (void)state;
    ltt_rng_seed(&r, 6);
    ltt_stat_init(&st, "lt__divfloor64", "", 0);
    for (i = 0; i < ne * ne + N_RANDOM; i++) {
        int64_t a, b, got;
        long double want;
        if (i < ne * ne) {
            a = edge[i / ne];
            b = edge[i % ne];
        } else {
            a = ltt_rng_i64_shr(&r, 64);
            b = ltt_rng_i64_shr(&r, 64);
        }
        /* b == 0 is outside the contract; INT64_MIN / -1 overflows int64 (undefined in C99,
         * and the quotient 2^63 has no int64 value): both are excluded from the domain. */
        if (b == 0 || (a == INT64_MIN && b == -1))
            continue;
        got = lt__divfloor64(a, b);
        /* floor of the long double quotient: its rounding error is below half an ulp of a
         * 64-bit significand, < 1/(2|b|), less than the distance of a/b to any other integer */
        want = floorl((long double)a / (long double)b);
        if (!ltt_stat_add(&st, (double)((long double)got - want)))
            ltt_stat_fail(&st, "%lld / %lld got %lld want %.0Lf", (long long)a, (long long)b,
                          (long long)got, want);
    }
    ltt_stat_print(&st);
    assert_int_equal(st.bad, 0);
}

/* lt__div_round64 (lt_fx.h): round(a / b) half up over the whole int64 range but INT64_MIN (the
 * kernels' t divisions reach |b| ~ 2^62, where the old 2a + b / 2b form overflowed), against the
 * exact floor((2a + b) / 2b) in 128-bit integers. */
#ifdef __SIZEOF_INT128__
__extension__ typedef __int128 ltt_i128_t;
static void test_div_round64(void **state)
{
    ltt_rng_t r;
    ltt_stat_t st;
    static const int64_t edge[] = { 0, 1, -1, 2, -2, 3, -3, 7, -7, INT64_MAX, INT64_MIN + 1,
                                    ((int64_t)1 << 62) + 1, -((int64_t)1 << 62) - 3,
                                    ((int64_t)1 << 62) - 1, (int64_t)INT32_MIN, (int64_t)INT32_MAX };
    unsigned i, ne = (unsigned)(sizeof edge / sizeof edge[0]), ties = 0;
    (void)state;
    ltt_rng_seed(&r, 7);
    ltt_stat_init(&st, "lt__div_round64", "", 0);
    for (i = 0; i < ne * ne + N_RANDOM; i++) {
        int64_t a, b, got;
        ltt_i128_t n, d, q;
        if (i < ne * ne) {
            a = edge[i / ne];
            b = edge[i % ne];
        } else {
            a = ltt_rng_i64_shr(&r, 64);
            b = ltt_rng_i64_shr(&r, 64);
            if ((i & 7) == 0) {
                /* an exact half: a = b k + b / 2 for an even b below 2^40 */
                b = lt__asr64(ltt_rng_i64(&r), 24) * 2;
                a = b * ((int64_t)(i % 17) - 8) + b / 2;
            } else if ((i & 7) <= 3) {
                /* the kernels' range: |a| < 2^62, quotients of every size */
                a = lt__asr64(ltt_rng_i64(&r), 2u + (unsigned)ltt_rng_below(&r, 40));
                b = lt__asr64(ltt_rng_i64(&r), 3u + (unsigned)ltt_rng_below(&r, 60));
            } else if ((i & 7) == 4) {
                /* near an exact half: b k + b / 2 + {-1, 0, 1} with b up to 2^60 */
                b = lt__asr64(ltt_rng_i64(&r), 3u + (unsigned)ltt_rng_below(&r, 60)) | 2;
                a = b * ((int64_t)ltt_rng_below(&r, 9) - 4) + b / 2 +
                    ((int64_t)ltt_rng_below(&r, 3) - 1);
            }
        }
        if (b == 0 || a == INT64_MIN || b == INT64_MIN)
            continue; /* outside the contract */
        n = 2 * (ltt_i128_t)a + b;
        d = 2 * (ltt_i128_t)b;
        if (d < 0) {
            n = -n;
            d = -d;
        }
        q = n / d - ((n % d != 0 && n < 0) ? 1 : 0);
        ties += (2 * (ltt_i128_t)a) % b == 0 && (2 * (ltt_i128_t)a / b) % 2 != 0;
        got = lt__div_round64(a, b);
        if (!ltt_stat_add(&st, (double)((ltt_i128_t)got - q)))
            ltt_stat_fail(&st, "%lld / %lld got %lld", (long long)a, (long long)b, (long long)got);
    }
    ltt_stat_print(&st);
    ltt_report("lt__div_round64: %u exact halves among them (rounded up)\n", ties);
    assert_int_equal(st.bad, 0);
}
#endif

/* ---- lt__memset / lt__memcpy with guard bytes ------------------------------------------------ */

#define MEM_BUF 96
#define MEM_GUARD 16

/* 8-byte aligned storage, so offsets 0..7 give every alignment (the helpers take a word path when
 * dst and src share 4-byte alignment and a byte path otherwise). */
typedef union mem_buf {
    uint64_t align;
    unsigned char b[MEM_GUARD + MEM_BUF + MEM_GUARD];
} mem_buf_t;

static void test_memset_memcpy(void **state)
{
    mem_buf_t dbuf, sbuf;
    unsigned char *dst = dbuf.b, *src = sbuf.b;
    unsigned off, soff, n, i, cases = 0, bad = 0;
    (void)state;
    for (i = 0; i < sizeof sbuf.b; i++)
        src[i] = (unsigned char)(i * 7u + 1u); /* never 0xA5 in the bytes copied */
    for (off = 0; off < 8; off++) {
        for (n = 0; n + off <= MEM_BUF - 8; n++) {
            unsigned char *d = dst + MEM_GUARD + off;
            void *ret;
            size_t head = MEM_GUARD + off, tail = head + n;
            /* memset with a value that differs from the poison */
            ltt_poison(dst, sizeof dbuf.b);
            ret = lt__memset(d, 0x3C, n);
            cases++;
            if (ret != d || ltt_touched(dst, 0, head) != 0 ||
                ltt_touched(dst, tail, sizeof dbuf.b) != 0)
                bad++;
            for (i = 0; i < n; i++)
                bad += d[i] != 0x3C;
            /* c is converted to unsigned char: 0x15A must store 0x5A */
            ltt_poison(dst, sizeof dbuf.b);
            (void)lt__memset(d, 0x15A, n);
            cases++;
            for (i = 0; i < n; i++)
                bad += d[i] != 0x5A;
            bad += ltt_touched(dst, 0, head) != 0 || ltt_touched(dst, tail, sizeof dbuf.b) != 0;
            /* memcpy from every source alignment (same as dst: word path; others: byte path) */
            for (soff = 0; soff < 8; soff++) {
                const unsigned char *sp = src + soff;
                ltt_poison(dst, sizeof dbuf.b);
                ret = lt__memcpy(d, sp, n);
                cases++;
                if (ret != d || ltt_touched(dst, 0, head) != 0 ||
                    ltt_touched(dst, tail, sizeof dbuf.b) != 0)
                    bad++;
                bad += memcmp(d, sp, n) != 0;
            }
        }
    }
    ltt_report("lt__memset/lt__memcpy: %u cases (8 dst x 8 src alignments x lengths 0..%u), 0xA5 "
               "guards of %u B each side, %u violations (bound 0)\n", cases, MEM_BUF - 8,
               MEM_GUARD, bad);
    assert_int_equal(bad, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_asr32),       cmocka_unit_test(test_asr64),
        cmocka_unit_test(test_bitcounts),   cmocka_unit_test(test_ssat_wrap),
        cmocka_unit_test(test_mul32x32_64), cmocka_unit_test(test_divfloor64),
#ifdef __SIZEOF_INT128__
        cmocka_unit_test(test_div_round64),
#endif
        cmocka_unit_test(test_memset_memcpy),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
