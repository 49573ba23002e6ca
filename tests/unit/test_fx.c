/* test_fx.c - cmocka tests of every scalar op of lt_fx.h / lt_fx.c against an independent
 * reference. The reference is the real-valued result computed in long double (x87: 64-bit
 * significand, so every 32x32 product and every sum of three of them is exact), then rounded by
 * the op's stated rule (half up = floor(x + 1/2), floor, exact) and clamped for _sat ops. Each
 * op runs a case list of extremes (0, +-1 ulp, carry edges, +-max, min), generated half-way ties
 * and random values of every magnitude, and prints
 * "name: N cases, max |err| E ulp (bound B), S saturated".
 * Bounds: exact ops 0; rounding ops 0.5 ulp with ties going up; saturated results must equal the
 * clamped reference exactly; rsqrt 1 ulp; normalize 2 ulp of s1.30 per component.
 * Builds: host, sim, asan (any LT_COST_MODE).
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
#include "io/lt_fx_float.h"
#include "lt_test_util.h"

LT_STATIC_ASSERT(LDBL_MANT_DIG >= 64, "references need a 64-bit long double significand");

#define N_RANDOM 10000 /* random cases per op */
#define N_TIES 2000    /* generated half-way cases per rounding op */

#define I32_LO (-2147483648.0L)
#define I32_HI 2147483647.0L
#define I16_LO (-32768.0L)
#define I16_HI 32767.0L

/* R_APPROX: any result within the bound (no rounding rule claimed beyond it). */
typedef enum { R_EXACT, R_HALFUP, R_FLOOR, R_APPROX } rmode_t;

/* Check one result against the real reference x (in raw units of the output). Out-of-range
 * references must give the clamped value exactly (counted as saturated, not as error); half-way
 * references must round up; otherwise the error got - x is recorded. Returns 1 if all good. */
static int check_val(ltt_stat_t *st, rmode_t m, long double x, long double lo, long double hi,
                     long double got)
{
    long double want = m == R_HALFUP ? floorl(x + 0.5L) : (m == R_FLOOR ? floorl(x) : x);
    if (want > hi || want < lo) {
        st->cases++;
        st->sat++;
        return got == (want > hi ? hi : lo);
    }
    if (m == R_HALFUP && x - floorl(x) == 0.5L) {
        st->ties++;
        if (got != x + 0.5L) {
            (void)ltt_stat_add(st, (double)(got - x));
            return 0;
        }
    }
    if (!ltt_stat_add(st, (double)(got - x)))
        return 0;
    if (m == R_FLOOR && got > x) /* floor: never above the exact value */
        return 0;
    return 1;
}

/* FNV-1a of an op name: a per-op seed that does not change when ops are added or reordered. */
static uint64_t seed_of(const char *s)
{
    uint64_t h = 1469598103934665603u;
    while (*s != '\0')
        h = (h ^ (uint64_t)(unsigned char)*s++) * 1099511628211u;
    return h;
}

/* ---- value generators ----------------------------------------------------------------------- */

static const int32_t edges16[] = { 0, 1, -1, 2, -2, 0x7F, -0x7F, 0x80, -0x80, 0x81, 0xFF, -0xFF,
                                   0x100, -0x100, 0x101, -0x101, 0x180, -0x180, 0x3FFF, -0x3FFF,
                                   0x4000, -0x4000, 0x4001, 0x7FFE, 0x7FFF, -0x7FFF, -0x8000 };
#define N_EDGES16 (sizeof edges16 / sizeof edges16[0])

static int32_t rng_i16(ltt_rng_t *r)
{
    if (ltt_rng_below(r, 4) == 0)
        return edges16[ltt_rng_below(r, (uint32_t)N_EDGES16)];
    return ltt_rng_i32_shr(r, 16, 16);
}

/* Odd value with |v| < 2^bits (bits >= 1), random sign. */
static int32_t rng_odd(ltt_rng_t *r, unsigned bits)
{
    uint32_t m = (ltt_rng_u32(r) >> (32u - bits)) | 1u;
    int32_t v = (int32_t)(m & 0x7FFFFFFFu);
    return (ltt_rng_u32(r) & 1u) ? -v : v;
}

/* a, b with a * b = odd * 2^(f-1): a tie when f fractional bits are rounded away. */
static void rng_tie_pair(ltt_rng_t *r, unsigned f, int32_t *a, int32_t *b)
{
    unsigned m = ltt_rng_below(r, f);         /* a carries 2^m, b carries 2^(f-1-m) */
    unsigned ma = 30u - m, mb = 30u - (f - 1u - m);
    *a = ltt_i32((uint32_t)rng_odd(r, ltt_rng_below(r, ma) + 1u) << m);
    *b = ltt_i32((uint32_t)rng_odd(r, ltt_rng_below(r, mb) + 1u) << (f - 1u - m));
}

/* ---- binary ops ----------------------------------------------------------------------------- */

typedef struct binop {
    const char *name;
    int32_t (*f)(int32_t, int32_t);
    long double (*ref)(int32_t, int32_t); /* exact real result in output raw units */
    int (*special)(int32_t, int32_t, int32_t *); /* 1 if (a, b) has a defined special result */
    rmode_t mode;
    double bound;
    long double lo, hi; /* output range */
    int in16;           /* inputs are int16 (s7.8) */
    unsigned tie_f;     /* generate product ties at this many fractional bits (0 = none) */
    int div_ties;       /* generate quotient ties */
} binop_t;

#define WRAP2(fn, T)                                                                               \
    static int32_t w_##fn(int32_t a, int32_t b) { return (int32_t)fn((T)a, (T)b); }
WRAP2(lt_q16_add_sat, lt_q16_t)
WRAP2(lt_q16_sub_sat, lt_q16_t)
WRAP2(lt_q16_add_wrap, lt_q16_t)
WRAP2(lt_q16_sub_wrap, lt_q16_t)
WRAP2(lt_q16_mul_sat, lt_q16_t)
WRAP2(lt_q16_mul_sat_rd, lt_q16_t)
WRAP2(lt_q16_mul_q30_sat, lt_q16_t)
WRAP2(lt_q16_div_sat, lt_q16_t)
WRAP2(lt_q16_min, lt_q16_t)
WRAP2(lt_q16_max, lt_q16_t)
WRAP2(lt_q30_mul_sat, lt_q30_t)
WRAP2(lt_h8_add_sat, lt_h8_t)
WRAP2(lt_h8_sub_sat, lt_h8_t)
WRAP2(lt_h8_mul_sat, lt_h8_t)

static long double wrap_ref(long double v)
{
    return v - 4294967296.0L * floorl((v + 2147483648.0L) / 4294967296.0L);
}

static long double r_add(int32_t a, int32_t b) { return (long double)a + (long double)b; }
static long double r_sub(int32_t a, int32_t b) { return (long double)a - (long double)b; }
static long double r_add_wrap(int32_t a, int32_t b) { return wrap_ref(r_add(a, b)); }
static long double r_sub_wrap(int32_t a, int32_t b) { return wrap_ref(r_sub(a, b)); }
static long double r_mul16(int32_t a, int32_t b)
{
    return ldexpl((long double)a * (long double)b, -16);
}
static long double r_mul30(int32_t a, int32_t b)
{
    return ldexpl((long double)a * (long double)b, -30);
}
static long double r_mul8(int32_t a, int32_t b)
{
    return ldexpl((long double)a * (long double)b, -8);
}
/* a * 2^16 / b: the long double quotient is within 2^-34 of the true one for |q| < 2^31, and a
 * true quotient that is not a tie is at least 1/(2|b|) >= 2^-32 away from one, so ties and the
 * rounding direction are decided exactly. */
static long double r_div(int32_t a, int32_t b)
{
    return ldexpl((long double)a, 16) / (long double)b;
}
static long double r_min(int32_t a, int32_t b) { return fminl((long double)a, (long double)b); }
static long double r_max(int32_t a, int32_t b) { return fmaxl((long double)a, (long double)b); }

static int s_div(int32_t a, int32_t b, int32_t *want)
{
    if (b != 0)
        return 0;
    *want = a > 0 ? INT32_MAX : (a < 0 ? INT32_MIN : 0); /* documented division by zero */
    return 1;
}

static binop_t binops[] = {
    { "lt_q16_add_sat", w_lt_q16_add_sat, r_add, NULL, R_EXACT, 0, I32_LO, I32_HI, 0, 0, 0 },
    { "lt_q16_sub_sat", w_lt_q16_sub_sat, r_sub, NULL, R_EXACT, 0, I32_LO, I32_HI, 0, 0, 0 },
    { "lt_q16_add_wrap", w_lt_q16_add_wrap, r_add_wrap, NULL, R_EXACT, 0, I32_LO, I32_HI, 0, 0, 0 },
    { "lt_q16_sub_wrap", w_lt_q16_sub_wrap, r_sub_wrap, NULL, R_EXACT, 0, I32_LO, I32_HI, 0, 0, 0 },
    { "lt_q16_mul_sat", w_lt_q16_mul_sat, r_mul16, NULL, R_HALFUP, 0.5, I32_LO, I32_HI, 0, 16, 0 },
    { "lt_q16_mul_sat_rd", w_lt_q16_mul_sat_rd, r_mul16, NULL, R_FLOOR, 1, I32_LO, I32_HI, 0, 16,
      0 },
    { "lt_q16_mul_q30_sat", w_lt_q16_mul_q30_sat, r_mul30, NULL, R_HALFUP, 0.5, I32_LO, I32_HI, 0,
      30, 0 },
    { "lt_q16_div_sat", w_lt_q16_div_sat, r_div, s_div, R_HALFUP, 0.5, I32_LO, I32_HI, 0, 0, 1 },
    { "lt_q16_min", w_lt_q16_min, r_min, NULL, R_EXACT, 0, I32_LO, I32_HI, 0, 0, 0 },
    { "lt_q16_max", w_lt_q16_max, r_max, NULL, R_EXACT, 0, I32_LO, I32_HI, 0, 0, 0 },
    { "lt_q30_mul_sat", w_lt_q30_mul_sat, r_mul30, NULL, R_HALFUP, 0.5, I32_LO, I32_HI, 0, 30, 0 },
    { "lt_h8_add_sat", w_lt_h8_add_sat, r_add, NULL, R_EXACT, 0, I16_LO, I16_HI, 1, 0, 0 },
    { "lt_h8_sub_sat", w_lt_h8_sub_sat, r_sub, NULL, R_EXACT, 0, I16_LO, I16_HI, 1, 0, 0 },
    { "lt_h8_mul_sat", w_lt_h8_mul_sat, r_mul8, NULL, R_HALFUP, 0.5, I16_LO, I16_HI, 1, 8, 0 },
};
#define N_BINOPS (sizeof binops / sizeof binops[0])

static void test_binop(void **state)
{
    const binop_t *op = (const binop_t *)*state;
    const int32_t *edges = op->in16 ? edges16 : ltt_edges32;
    unsigned ne = op->in16 ? (unsigned)N_EDGES16 : (unsigned)LTT_N_EDGES32;
    unsigned nties = (op->tie_f != 0 || op->div_ties) ? N_TIES : 0;
    unsigned i, n = ne * ne + N_RANDOM + nties;
    ltt_rng_t r;
    ltt_stat_t st;
    ltt_rng_seed(&r, seed_of(op->name));
    ltt_stat_init(&st, op->name, "ulp", op->bound);
    for (i = 0; i < n; i++) {
        int32_t a, b, got, want;
        if (i < ne * ne) {
            a = edges[i / ne];
            b = edges[i % ne];
        } else if (i < ne * ne + N_RANDOM) {
            a = op->in16 ? rng_i16(&r) : ltt_rng_i32_wide(&r);
            b = op->in16 ? rng_i16(&r) : ltt_rng_i32_wide(&r);
        } else if (op->tie_f != 0) {
            if (op->in16) { /* s7.8: a * b = odd * 2^7 with both in int16 */
                unsigned m = ltt_rng_below(&r, 8);
                a = ltt_i32((uint32_t)rng_odd(&r, 14u - m) << m);
                b = ltt_i32((uint32_t)rng_odd(&r, 7u + m) << (7u - m));
            } else {
                rng_tie_pair(&r, op->tie_f, &a, &b);
            }
        } else {
            /* a * 2^16 / b = (2k + 1) / 2: b = m * 2^17, a = m * (2k + 1) */
            int32_t m = ltt_rng_range(&r, 1, 0x3FFF);
            int32_t k = ltt_rng_range(&r, -(0x3FFFFFFF / m) / 2, (0x3FFFFFFF / m) / 2 - 1);
            if (ltt_rng_u32(&r) & 1u)
                m = -m;
            b = m * 0x20000;
            a = m * (2 * k + 1);
        }
        got = op->f(a, b);
        if (op->special != NULL && op->special(a, b, &want)) {
            st.cases++;
            st.sat += want != 0;
            if (got != want)
                ltt_stat_fail(&st, "a=%ld b=%ld got %ld want %ld (special case)", (long)a, (long)b,
                              (long)got, (long)want);
            continue;
        }
        if (!check_val(&st, op->mode, op->ref(a, b), op->lo, op->hi, (long double)got))
            ltt_stat_fail(&st, "a=%ld b=%ld got %ld ref %.6Lf", (long)a, (long)b, (long)got,
                          op->ref(a, b));
    }
    ltt_stat_print(&st);
    assert_int_equal(st.bad, 0);
}

/* ---- unary ops ------------------------------------------------------------------------------ */

typedef struct unop {
    const char *name;
    int32_t (*f)(int32_t);
    long double (*ref)(int32_t);
    int (*special)(int32_t, int32_t *);
    rmode_t mode;
    double bound;
    long double lo, hi;
    int in16;         /* inputs are int16: run all 65536 */
    int32_t sweep_lo; /* also run every x in [sweep_lo, sweep_hi] */
    int32_t sweep_hi;
    unsigned tie_f;   /* generate inputs whose low tie_f bits are exactly 1/2 */
    int positive;     /* random inputs restricted to x > 0 */
} unop_t;

#define WRAP1(fn, T)                                                                               \
    static int32_t w_##fn(int32_t a) { return (int32_t)fn((T)a); }
WRAP1(lt_q16_recip_sat, lt_q16_t)
WRAP1(lt_q16_abs_sat, lt_q16_t)
WRAP1(lt_q16_neg_sat, lt_q16_t)
WRAP1(lt_q16_sqrt, lt_q16_t)
WRAP1(lt_q16_rsqrt_sat, lt_q16_t)
WRAP1(lt_q30_from_q16_sat, lt_q16_t)
WRAP1(lt_q16_from_q30, lt_q30_t)
WRAP1(lt_h8_from_q16_sat, lt_q16_t)
WRAP1(lt_q16_from_h8, lt_h8_t)
WRAP1(lt_h14_from_q30_sat, lt_q30_t)
WRAP1(lt_q30_from_h14, lt_h14_t)

static long double r_recip(int32_t x) { return 4294967296.0L / (long double)x; }
static long double r_abs(int32_t x) { return fabsl((long double)x); }
static long double r_neg(int32_t x) { return -(long double)x; }
/* sqrt(x_raw * 2^16); sqrt of an integer is never within 2^-27 of a half-integer below 2^24,
 * far above the long double error, so the half-up decision is exact. */
static long double r_sqrt(int32_t x) { return sqrtl(ldexpl((long double)x, 16)); }
static long double r_rsqrt(int32_t x) { return 16777216.0L / sqrtl((long double)x); }
static long double r_shl14(int32_t x) { return ldexpl((long double)x, 14); }
static long double r_shr14(int32_t x) { return ldexpl((long double)x, -14); }
static long double r_shr8(int32_t x) { return ldexpl((long double)x, -8); }
static long double r_shl8(int32_t x) { return ldexpl((long double)x, 8); }
static long double r_shr16(int32_t x) { return ldexpl((long double)x, -16); }
static long double r_shl16(int32_t x) { return ldexpl((long double)x, 16); }

static int s_recip(int32_t x, int32_t *want)
{
    if (x != 0)
        return 0;
    *want = INT32_MAX; /* documented: 1/0 = +max */
    return 1;
}

static int s_sqrt(int32_t x, int32_t *want)
{
    if (x > 0)
        return 0;
    *want = 0; /* documented: x < 0 gives 0 */
    return 1;
}

static int s_rsqrt(int32_t x, int32_t *want)
{
    if (x > 0)
        return 0;
    *want = INT32_MAX; /* documented: x <= 0 gives +max */
    return 1;
}

static unop_t unops[] = {
    { "lt_q16_recip_sat", w_lt_q16_recip_sat, r_recip, s_recip, R_HALFUP, 0.5, I32_LO, I32_HI, 0,
      -70000, 70000, 0, 0 },
    { "lt_q16_abs_sat", w_lt_q16_abs_sat, r_abs, NULL, R_EXACT, 0, I32_LO, I32_HI, 0, -1000, 1000,
      0, 0 },
    { "lt_q16_neg_sat", w_lt_q16_neg_sat, r_neg, NULL, R_EXACT, 0, I32_LO, I32_HI, 0, -1000, 1000,
      0, 0 },
    { "lt_q16_sqrt", w_lt_q16_sqrt, r_sqrt, s_sqrt, R_HALFUP, 0.5, I32_LO, I32_HI, 0, -16,
      1 << 18, 0, 0 },
    { "lt_q16_rsqrt_sat", w_lt_q16_rsqrt_sat, r_rsqrt, s_rsqrt, R_APPROX, 1.0, I32_LO, I32_HI, 0,
      -16, 1 << 18, 0, 1 },
    { "lt_q30_from_q16_sat", w_lt_q30_from_q16_sat, r_shl14, NULL, R_EXACT, 0, I32_LO, I32_HI, 0,
      -0x20010, 0x20010, 0, 0 },
    { "lt_q16_from_q30", w_lt_q16_from_q30, r_shr14, NULL, R_HALFUP, 0.5, I32_LO, I32_HI, 0, -40000,
      40000, 14, 0 },
    { "lt_h8_from_q16_sat", w_lt_h8_from_q16_sat, r_shr8, NULL, R_HALFUP, 0.5, I16_LO, I16_HI, 0,
      -0x800100, -0x7FFF00, 8, 0 },
    { "lt_q16_from_h8", w_lt_q16_from_h8, r_shl8, NULL, R_EXACT, 0, I32_LO, I32_HI, 1, 0, -1, 0,
      0 },
    { "lt_h14_from_q30_sat", w_lt_h14_from_q30_sat, r_shr16, NULL, R_HALFUP, 0.5, I16_LO, I16_HI, 0,
      0x7FFF0000, 0x7FFFFFFF, 16, 0 },
    { "lt_q30_from_h14", w_lt_q30_from_h14, r_shl16, NULL, R_EXACT, 0, I32_LO, I32_HI, 1, 0, -1, 0,
      0 },
};
#define N_UNOPS (sizeof unops / sizeof unops[0])

#define N_RANDOM_UN 100000

static void test_unop(void **state)
{
    const unop_t *op = (const unop_t *)*state;
    unsigned long i, nsweep = (unsigned long)((int64_t)op->sweep_hi - op->sweep_lo + 1);
    unsigned long nex = op->in16 ? 65536ul : 0ul;
    unsigned long n = nex + LTT_N_EDGES32 + nsweep + N_RANDOM_UN + (op->tie_f ? N_TIES : 0);
    ltt_rng_t r;
    ltt_stat_t st;
    ltt_rng_seed(&r, seed_of(op->name));
    ltt_stat_init(&st, op->name, "ulp", op->bound);
    for (i = 0; i < n; i++) {
        int32_t x, got, want;
        unsigned long j = i;
        if (j < nex) {
            x = (int32_t)j - 32768;
        } else if ((j -= nex) < LTT_N_EDGES32) {
            x = ltt_edges32[j];
            if (op->in16)
                x = lt__ssat16(x);
        } else if ((j -= LTT_N_EDGES32) < nsweep) {
            x = (int32_t)((int64_t)op->sweep_lo + (int64_t)j);
        } else if ((j -= nsweep) < N_RANDOM_UN) {
            x = op->in16 ? rng_i16(&r) : ltt_rng_i32_wide(&r);
            if (op->positive && x <= 0)
                x = x == INT32_MIN ? INT32_MAX : (x == 0 ? 1 : -x);
        } else {
            /* random high bits, low tie_f bits exactly 100..0 */
            uint32_t u = ltt_rng_u32(&r);
            u >>= ltt_rng_below(&r, 32u - op->tie_f);
            u = (u & ~((1u << op->tie_f) - 1u)) | (1u << (op->tie_f - 1u));
            x = ltt_i32(ltt_rng_u32(&r) & 1u ? 0u - u : u);
        }
        got = op->f(x);
        if (op->special != NULL && op->special(x, &want)) {
            st.cases++;
            st.sat += x != 0 || want != 0;
            if (got != want)
                ltt_stat_fail(&st, "x=%ld got %ld want %ld (special case)", (long)x, (long)got,
                              (long)want);
            continue;
        }
        if (!check_val(&st, op->mode, op->ref(x), op->lo, op->hi, (long double)got))
            ltt_stat_fail(&st, "x=%ld got %ld ref %.6Lf", (long)x, (long)got, op->ref(x));
    }
    ltt_stat_print(&st);
    assert_int_equal(st.bad, 0);
}

/* ---- clamp ---------------------------------------------------------------------------------- */

static void test_clamp(void **state)
{
    ltt_rng_t r;
    ltt_stat_t st;
    unsigned i, j, k, ne = (unsigned)LTT_N_EDGES32;
    (void)state;
    ltt_rng_seed(&r, 77);
    ltt_stat_init(&st, "lt_q16_clamp", "ulp", 0);
    for (i = 0; i < ne * ne * 4 + N_RANDOM; i++) {
        int32_t x, lo, hi, got;
        long double want;
        if (i < ne * ne * 4) {
            j = i / 4 % ne;
            k = i / 4 / ne;
            lo = ltt_edges32[j] < ltt_edges32[k] ? ltt_edges32[j] : ltt_edges32[k];
            hi = ltt_edges32[j] < ltt_edges32[k] ? ltt_edges32[k] : ltt_edges32[j];
            x = (i & 3u) == 0 ? lo : ((i & 3u) == 1 ? hi : ltt_rng_i32_wide(&r));
        } else {
            int32_t a = ltt_rng_i32_wide(&r), b = ltt_rng_i32_wide(&r);
            lo = a < b ? a : b;
            hi = a < b ? b : a;
            x = ltt_rng_i32_wide(&r);
        }
        got = lt_q16_clamp(x, lo, hi);
        want = fminl(fmaxl((long double)x, (long double)lo), (long double)hi);
        if (!ltt_stat_add(&st, (double)((long double)got - want)))
            ltt_stat_fail(&st, "x=%ld lo=%ld hi=%ld got %ld", (long)x, (long)lo, (long)hi,
                          (long)got);
    }
    ltt_stat_print(&st);
    assert_int_equal(st.bad, 0);
}

/* ---- three-vector ops ----------------------------------------------------------------------- */

/* A component for vector cases: edges, wide random, or (class 3) all three of similar size. */
static void rng_vec3(ltt_rng_t *r, lt_q16_t v[3])
{
    unsigned c = ltt_rng_below(r, 4), i;
    for (i = 0; i < 3; i++) {
        if (c == 0)
            v[i] = ltt_edges32[ltt_rng_below(r, (uint32_t)LTT_N_EDGES32)];
        else if (c == 3)
            v[i] = ltt_rng_i32_shr(r, 1, 3); /* 2^28..2^30 */
        else
            v[i] = ltt_rng_i32_wide(r);
    }
}

static void test_dot3(void **state)
{
    ltt_rng_t r;
    ltt_stat_t st;
    unsigned i, ne = (unsigned)LTT_N_EDGES32;
    (void)state;
    ltt_rng_seed(&r, 33);
    ltt_stat_init(&st, "lt_q16_dot3_sat", "ulp", 0.5);
    for (i = 0; i < ne * ne + 3 * N_RANDOM + N_TIES; i++) {
        lt_q16_t a[3], b[3];
        long double x;
        int32_t got;
        if (i < ne * ne) {
            /* (e, e, e) . (f, f, f): three equal extreme products, the largest sums */
            a[0] = a[1] = a[2] = ltt_edges32[i / ne];
            b[0] = b[1] = b[2] = ltt_edges32[i % ne];
            if (i & 1u)
                b[1] = b[1] == INT32_MIN ? INT32_MAX : -b[1];
        } else if (i < ne * ne + 3 * N_RANDOM) {
            rng_vec3(&r, a);
            rng_vec3(&r, b);
        } else {
            /* a0 b0 = odd * 2^15, the others multiples of 2^16: the sum is a tie */
            rng_tie_pair(&r, 16, &a[0], &b[0]);
            a[1] = ltt_rng_i32_wide(&r);
            a[2] = ltt_rng_i32_wide(&r);
            b[1] = ltt_i32((uint32_t)ltt_rng_i32_shr(&r, 16, 16) << 16);
            b[2] = ltt_i32((uint32_t)ltt_rng_i32_shr(&r, 16, 16) << 16);
        }
        got = lt_q16_dot3_sat(a, b);
        /* three 62-bit products and their sum (< 2^64) are exact in long double */
        x = ldexpl((long double)a[0] * b[0] + (long double)a[1] * b[1] + (long double)a[2] * b[2],
                   -16);
        if (!check_val(&st, R_HALFUP, x, I32_LO, I32_HI, (long double)got))
            ltt_stat_fail(&st, "a=(%ld,%ld,%ld) b=(%ld,%ld,%ld) got %ld ref %.3Lf", (long)a[0],
                          (long)a[1], (long)a[2], (long)b[0], (long)b[1], (long)b[2], (long)got, x);
    }
    ltt_stat_print(&st);
    assert_int_equal(st.bad, 0);
}

static void test_cross3(void **state)
{
    ltt_rng_t r;
    ltt_stat_t st;
    unsigned i, c, ne = (unsigned)LTT_N_EDGES32;
    (void)state;
    ltt_rng_seed(&r, 34);
    ltt_stat_init(&st, "lt_q16_cross3_sat", "ulp", 0.5);
    for (i = 0; i < ne * ne + 3 * N_RANDOM + N_TIES; i++) {
        lt_q16_t a[3], b[3], out[4];
        if (i < ne * ne) {
            int32_t e = ltt_edges32[i / ne], f = ltt_edges32[i % ne];
            a[0] = e;
            a[1] = f;
            a[2] = e == INT32_MIN ? 0 : -e;
            b[0] = f;
            b[1] = INT32_MIN;
            b[2] = e;
        } else if (i < ne * ne + 3 * N_RANDOM) {
            rng_vec3(&r, a);
            rng_vec3(&r, b);
        } else {
            /* component 0 = a1 b2 - a2 b1 with a1 b2 a tie and a2 b1 a multiple of 2^16 */
            rng_tie_pair(&r, 16, &a[1], &b[2]);
            a[0] = ltt_rng_i32_wide(&r);
            b[0] = ltt_rng_i32_wide(&r);
            a[2] = ltt_rng_i32_wide(&r);
            b[1] = ltt_i32((uint32_t)ltt_rng_i32_shr(&r, 16, 16) << 16);
        }
        out[3] = 0x5A5A5A5A;
        lt_q16_cross3_sat(a, b, out);
        for (c = 0; c < 3; c++) {
            unsigned c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            long double x = ldexpl((long double)a[c1] * b[c2] - (long double)a[c2] * b[c1], -16);
            if (!check_val(&st, R_HALFUP, x, I32_LO, I32_HI, (long double)out[c]))
                ltt_stat_fail(&st, "a=(%ld,%ld,%ld) b=(%ld,%ld,%ld) out[%u]=%ld ref %.3Lf",
                              (long)a[0], (long)a[1], (long)a[2], (long)b[0], (long)b[1],
                              (long)b[2], c, (long)out[c], x);
        }
        if (out[3] != 0x5A5A5A5A)
            ltt_stat_fail(&st, "wrote past out[2]");
    }
    ltt_stat_print(&st);
    assert_int_equal(st.bad, 0);
}

static void test_normalize3(void **state)
{
    static const int32_t comp[] = { 0, 1, -1, 0x10000, -0x10000, INT32_MAX, INT32_MIN, 0x40000000,
                                    0x3FFFFFFF, 0x20000000, 0x1FFFFFFF, 3, -3, 0x7FFF, 0x8000 };
    unsigned nc = (unsigned)(sizeof comp / sizeof comp[0]);
    ltt_rng_t r;
    ltt_stat_t st;
    unsigned i, c, nzero = 0;
    (void)state;
    ltt_rng_seed(&r, 35);
    ltt_stat_init(&st, "lt_q16_normalize3", "ulp(s1.30)", 2.0);
    /* A vector on which an earlier normalize3 (floored 2-bit pre-shift for an INT32_MIN component)
     * erred by 2.13 ulp; the INT32_MIN class below keeps hunting that corner. */
    static const int32_t found[][3] = { { INT32_MIN, 259895087, -560678477 } };
    unsigned nfound = (unsigned)(sizeof found / sizeof found[0]);
    /* every combination of the component list: axis vectors (unit, 1 ulp, max, min), tiny vectors
     * (+-1 ulp components), huge vectors (max/min), huge with tiny companions, the zero vector;
     * then the found vectors, random vectors, and INT32_MIN with companions = 3 mod 4 */
    for (i = 0; i < nc * nc * nc + nfound + 6 * N_RANDOM; i++) {
        lt_q16_t v[3];
        lt_q30_t out[4] = { 0x5A5A5A5A, 0x5A5A5A5A, 0x5A5A5A5A, 0x5A5A5A5A };
        lt_status_t s;
        long double len;
        if (i < nc * nc * nc) {
            v[0] = comp[i % nc];
            v[1] = comp[i / nc % nc];
            v[2] = comp[i / nc / nc];
        } else if (i < nc * nc * nc + nfound) {
            memcpy(v, found[i - nc * nc * nc], sizeof v);
        } else if (i % 3u == 0) {
            v[0] = INT32_MIN;
            v[1] = ltt_i32((uint32_t)ltt_rng_i32_shr(&r, 1, 30) | 3u);
            v[2] = ltt_i32((uint32_t)ltt_rng_i32_shr(&r, 1, 30) | 3u);
        } else if (i & 1u) {
            rng_vec3(&r, v);
        } else {
            /* one big component (scale 2^0..2^31) with companions 0..30 bits smaller */
            unsigned e = ltt_rng_below(&r, 32);
            for (c = 0; c < 3; c++) {
                unsigned sh = 31u - e + (c == 0 ? 0u : ltt_rng_below(&r, 31));
                v[c] = lt__asr32(ltt_rng_i32(&r), sh > 31u ? 31u : sh);
            }
        }
        s = lt_q16_normalize3(v, out);
        if (v[0] == 0 && v[1] == 0 && v[2] == 0) {
            nzero++;
            if (s != LT_E_ARG || out[0] != 0x5A5A5A5A || out[1] != 0x5A5A5A5A ||
                out[2] != 0x5A5A5A5A)
                ltt_stat_fail(&st, "zero vector: status %d, out touched", (int)s);
            continue;
        }
        if (s != LT_OK) {
            ltt_stat_fail(&st, "v=(%ld,%ld,%ld) status %d", (long)v[0], (long)v[1], (long)v[2],
                          (int)s);
            continue;
        }
        /* squares < 2^62, their sum < 2^64: exact; sqrtl and the quotient add < 2^-33 ulp */
        len = sqrtl((long double)v[0] * v[0] + (long double)v[1] * v[1] + (long double)v[2] * v[2]);
        for (c = 0; c < 3; c++) {
            long double x = ldexpl((long double)v[c], 30) / len;
            if (!check_val(&st, R_APPROX, x, I32_LO, I32_HI, (long double)out[c]))
                ltt_stat_fail(&st, "v=(%ld,%ld,%ld) out[%u]=%ld ref %.3Lf", (long)v[0], (long)v[1],
                              (long)v[2], c, (long)out[c], x);
        }
        if (out[3] != 0x5A5A5A5A)
            ltt_stat_fail(&st, "wrote past out[2]");
    }
    ltt_stat_print(&st);
    ltt_report("lt_q16_normalize3: %u zero vectors -> LT_E_ARG with out untouched\n", nzero);
    assert_int_equal(st.bad, 0);
}

/* ---- status strings, compile-time constants, host conversions ------------------------------- */

static void test_status_str(void **state)
{
    static const lt_status_t codes[] = { LT_OK, LT_E_ARG, LT_E_RANGE, LT_E_SPACE, LT_E_FORMAT,
                                         LT_E_DEPTH };
    const char *str[7];
    unsigned i, j, n = (unsigned)(sizeof codes / sizeof codes[0]);
    (void)state;
    for (i = 0; i < n; i++) {
        str[i] = lt_status_str(codes[i]);
        assert_non_null(str[i]);
        assert_true(str[i][0] != '\0');
        ltt_report("lt_status_str(%d) = \"%s\"\n", (int)codes[i], str[i]);
    }
    str[n] = lt_status_str((lt_status_t)-99);
    assert_non_null(str[n]);
    ltt_report("lt_status_str(-99) = \"%s\"\n", str[n]);
    for (i = 0; i <= n; i++)
        for (j = i + 1; j <= n; j++)
            assert_true(strcmp(str[i], str[j]) != 0);
    assert_string_equal(lt_status_str(LT_OK), "ok");
    ltt_report("lt_status_str: %u codes + 1 unknown, all non-empty and distinct\n", n);
}

static void test_constants_and_host(void **state)
{
    ltt_rng_t r;
    ltt_stat_t st;
    unsigned i, bad = 0;
    int f;
    (void)state;
    /* LT_Q16 / LT_Q30 round half away from zero */
    assert_int_equal(LT_Q16(1.25), 0x14000);
    assert_int_equal(LT_Q16(-1.25), -0x14000);
    assert_int_equal(LT_Q16(0.5 / 65536.0), 1);
    assert_int_equal(LT_Q16(-0.5 / 65536.0), -1);
    assert_int_equal(LT_Q30(1.0), LT_Q30_ONE);
    assert_int_equal(LT_Q30(-2.0), INT32_MIN);
    /* host/io/lt_fx_float.h: fixed -> double -> fixed is the identity; x + 1/2 ulp rounds up (also
     * for negative x); out-of-range and NaN saturate and are flagged by the _chk forms */
    ltt_rng_seed(&r, 36);
    ltt_stat_init(&st, "lt_fx_float.h round trips", "ulp", 0);
    for (i = 0; i < LTT_N_EDGES32 + N_RANDOM; i++) {
        int32_t x = i < LTT_N_EDGES32 ? ltt_edges32[i] : ltt_rng_i32_wide(&r);
        int16_t h = lt__ssat16(lt__asr32(x, 16));
        lt_q16_t q;
        int32_t up = x == INT32_MAX ? INT32_MAX : x + 1;
        f = ltt_stat_add(&st, (double)(lt_q16_from_double_sat(lt_q16_to_double(x)) - (int64_t)x)) &&
            ltt_stat_add(&st, (double)(lt_q30_from_double_sat(lt_q30_to_double(x)) - (int64_t)x)) &&
            ltt_stat_add(&st, (double)(lt_h8_from_double_sat(lt_h8_to_double(h)) - h)) &&
            ltt_stat_add(&st, (double)(lt_h14_from_double_sat(lt_h14_to_double(h)) - h)) &&
            ltt_stat_add(&st, (double)(lt_q16_from_double_sat(ldexp((double)x + 0.5, -16)) -
                                       (int64_t)up)) &&
            ltt_stat_add(&st, (double)(lt_q30_from_double_sat(ldexp((double)x + 0.5, -30)) -
                                       (int64_t)up)) &&
            ltt_stat_add(&st, (double)(lt_q16_from_double_sat(ldexp((double)x + 0.4999, -16)) -
                                       (int64_t)x)) &&
            lt_q16_from_double_chk(lt_q16_to_double(x), &q) == LT_OK && q == x;
        if (!f)
            ltt_stat_fail(&st, "x=%ld", (long)x);
    }
    bad += lt_q16_from_double_sat(32768.0) != INT32_MAX;
    bad += lt_q16_from_double_sat(32768.0 - ldexp(1.0, -17)) != INT32_MAX;
    bad += lt_q16_from_double_sat(-32768.0) != INT32_MIN;
    bad += lt_q16_from_double_sat(-32768.0 - ldexp(1.0, -17)) != INT32_MIN; /* tie up: in range */
    bad += lt_q16_from_double_sat(-32768.0 - ldexp(1.0, -16)) != INT32_MIN;
    bad += lt_q16_from_double_sat(1e300) != INT32_MAX;
    bad += lt_q16_from_double_sat(-HUGE_VAL) != INT32_MIN;
    bad += lt_q16_from_double_sat(nan("")) != 0;
    bad += lt_q30_from_double_sat(2.0) != INT32_MAX;
    bad += lt_q30_from_double_sat(-2.0) != INT32_MIN;
    bad += lt_h8_from_double_sat(200.0) != INT16_MAX;
    bad += lt_h8_from_double_sat(-0.5 / 256.0) != 0;
    bad += lt_h14_from_double_sat(-3.0) != INT16_MIN;
    {
        lt_q16_t q;
        lt_q30_t q30;
        bad += lt_q16_from_double_chk(40000.0, &q) != LT_E_RANGE || q != INT32_MAX;
        bad += lt_q16_from_double_chk(nan(""), &q) != LT_E_RANGE || q != 0;
        bad += lt_q30_from_double_chk(1.5, &q30) != LT_OK || q30 != 0x60000000;
        bad += lt_q30_from_double_chk(-2.5, &q30) != LT_E_RANGE || q30 != INT32_MIN;
    }
    st.cases += 17;
    st.sat += 13;
    if (bad != 0)
        ltt_stat_fail(&st, "%u saturation/NaN checks failed", bad);
    ltt_stat_print(&st);
    assert_int_equal(st.bad, 0);
}

int main(void)
{
    struct CMUnitTest tests[N_BINOPS + N_UNOPS + 7];
    unsigned i, n = 0;
    memset(tests, 0, sizeof tests);
    for (i = 0; i < N_BINOPS; i++, n++) {
        tests[n].name = binops[i].name;
        tests[n].test_func = test_binop;
        tests[n].initial_state = &binops[i];
    }
    for (i = 0; i < N_UNOPS; i++, n++) {
        tests[n].name = unops[i].name;
        tests[n].test_func = test_unop;
        tests[n].initial_state = &unops[i];
    }
    tests[n].name = "lt_q16_clamp";
    tests[n++].test_func = test_clamp;
    tests[n].name = "lt_q16_dot3_sat";
    tests[n++].test_func = test_dot3;
    tests[n].name = "lt_q16_cross3_sat";
    tests[n++].test_func = test_cross3;
    tests[n].name = "lt_q16_normalize3";
    tests[n++].test_func = test_normalize3;
    tests[n].name = "lt_status_str";
    tests[n++].test_func = test_status_str;
    tests[n].name = "constants and host conversions";
    tests[n++].test_func = test_constants_and_host;
    return _cmocka_run_group_tests("test_fx", tests, n, NULL, NULL);
}
