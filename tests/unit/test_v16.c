/* test_v16.c - cmocka tests of the 16-lane model of lt_v16.h: every lane op family against the
 * scalar op (or an independent reference) per lane, under every mask pattern class of
 * lt_test_util.h (none, all, each single lane, 0x5555/0xAAAA, 100 random): active lanes must equal
 * the scalar result, inactive lanes must keep src (_m) or become 0 (_z), store_m must leave the
 * memory of inactive lanes (poisoned 0xA5) untouched, and the mask helpers must visit exactly the
 * set lanes. Every family prints "name: N lane results, M mismatches (bound 0)".
 * Builds: host, sim, asan (any LT_COST_MODE); float32 families only with LT_CFG_FLOAT32.
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

#include "lt/lt_v16.h"
#include "lt_test_util.h"

LT_STATIC_ASSERT(LDBL_MANT_DIG >= 64, "references need a 64-bit long double significand");

#define N_REP 32 /* random input vector sets per family (each run under every mask) */

static uint64_t seed_of(const char *s)
{
    uint64_t h = 1469598103934665603u;
    while (*s != '\0')
        h = (h ^ (uint64_t)(unsigned char)*s++) * 1099511628211u;
    return h;
}

/* Print the summary of one family and fail it if anything mismatched. */
static void family_done(const char *name, const char *ref, unsigned long lanes, unsigned long bad)
{
    ltt_report("%s: %lu lane results, %lu mismatches vs %s (bound 0)\n", name, lanes, bad, ref);
    assert_int_equal(bad, 0);
}

static void note_bad(unsigned long *bad, const char *name, unsigned k, int lane)
{
    if ((*bad)++ < 4)
        ltt_report("  FAIL %s: mask 0x%04x lane %d\n", name, k, lane);
}

/* The same with the lane's input(s), result and expected value (%g shows -0 and nan). */
static void note_val(unsigned long *bad, const char *name, unsigned k, int lane, double a, double b,
                     double got, double want)
{
    if ((*bad)++ < 4)
        ltt_report("  FAIL %s: mask 0x%04x lane %d: inputs %.9g, %.9g: got %.9g, want %.9g\n", name,
                   k, lane, a, b, got, want);
}

/* ---- lane generators ---------------------------------------------------------------------- */

static int32_t gen_i32(ltt_rng_t *r)
{
    return ltt_rng_below(r, 16) == 0 ? 0 : ltt_rng_i32_wide(r); /* extra zeros for div/recip */
}

static int16_t gen_i16(ltt_rng_t *r)
{
    static const int16_t e[] = { 0,      1,      -1,      0x7F,   0x80,  0xFF,
                                 0x100,  -0x100, 0x7FFF,  -0x8000, -0x7FFF };
    if (ltt_rng_below(r, 4) == 0)
        return e[ltt_rng_below(r, (uint32_t)(sizeof e / sizeof e[0]))];
    return (int16_t)ltt_rng_i32_shr(r, 16, 16);
}

static int64_t gen_i64(ltt_rng_t *r)
{
    static const int64_t e[] = { 0, 1, -1, INT64_MAX, INT64_MIN, (int64_t)1 << 62,
                                 -((int64_t)1 << 62), ((int64_t)1 << 62) + 1, INT32_MAX, INT32_MIN,
                                 ((int64_t)INT32_MAX << 16) + 0x8000,
                                 (int64_t)INT32_MIN * 65536 - 1 };
    if (ltt_rng_below(r, 8) == 0)
        return e[ltt_rng_below(r, (uint32_t)(sizeof e / sizeof e[0]))];
    return ltt_rng_i64_shr(r, 64);
}

#define GEN_VEC(fn, VT, gen)                                                                       \
    static void fn(ltt_rng_t *r, VT *v)                                                            \
    {                                                                                              \
        int i;                                                                                     \
        for (i = 0; i < LT_LANES; i++)                                                             \
            v->l[i] = gen(r);                                                                      \
    }
GEN_VEC(gen_vq16, lt_vq16_t, gen_i32)
GEN_VEC(gen_vq30, lt_vq30_t, gen_i32)
GEN_VEC(gen_vi32, lt_vi32_t, gen_i32)
GEN_VEC(gen_vql, lt_vql_t, gen_i64)
GEN_VEC(gen_vh8, lt_vh8_t, gen_i16)

#define SAME_INT(x, y) ((x) == (y))

/* ---- binary, unary and compare families ------------------------------------------------------ */

/* plain: every lane = sref; _m: active = sref, inactive = src; _z: active = sref, inactive = 0 */
#define TEST_BIN(vfn, VT, ET, sref, gen, same)                                                     \
    static void test_##vfn(void **state)                                                           \
    {                                                                                              \
        uint16_t masks[LTT_MASK_COUNT];                                                            \
        unsigned nm = ltt_masks(masks, seed_of(#vfn)), m, rep;                                     \
        unsigned long lanes = 0, bad = 0;                                                          \
        int i;                                                                                     \
        ltt_rng_t r;                                                                               \
        (void)state;                                                                               \
        ltt_rng_seed(&r, seed_of(#vfn) + 1u);                                                      \
        for (rep = 0; rep < N_REP; rep++) {                                                        \
            VT a, b, src, p;                                                                       \
            gen(&r, &a);                                                                           \
            gen(&r, &b);                                                                           \
            gen(&r, &src);                                                                         \
            p = vfn(a, b);                                                                         \
            for (i = 0; i < LT_LANES; i++, lanes++)                                                \
                if (!same(p.l[i], sref(a.l[i], b.l[i])))                                           \
                    note_val(&bad, #vfn, 0xFFFFu, i, (double)a.l[i], (double)b.l[i],               \
                             (double)p.l[i], (double)sref(a.l[i], b.l[i]));                        \
            for (m = 0; m < nm; m++) {                                                             \
                lt_mask16_t k = masks[m];                                                          \
                VT rm = vfn##_m(src, k, a, b), rz = vfn##_z(k, a, b);                              \
                for (i = 0; i < LT_LANES; i++, lanes += 2) {                                       \
                    ET want = sref(a.l[i], b.l[i]);                                                \
                    int on = LTT_ON(k, i);                                                         \
                    if (!same(rm.l[i], on ? want : src.l[i]))                                      \
                        note_bad(&bad, #vfn "_m", k, i);                                           \
                    if (!same(rz.l[i], on ? want : (ET)0))                                         \
                        note_bad(&bad, #vfn "_z", k, i);                                           \
                }                                                                                  \
            }                                                                                      \
        }                                                                                          \
        family_done(#vfn "{,_m,_z}", #sref, lanes, bad);                                           \
    }

#define TEST_UN(vfn, VT, ET, sref, gen, same)                                                      \
    static void test_##vfn(void **state)                                                           \
    {                                                                                              \
        uint16_t masks[LTT_MASK_COUNT];                                                            \
        unsigned nm = ltt_masks(masks, seed_of(#vfn)), m, rep;                                     \
        unsigned long lanes = 0, bad = 0;                                                          \
        int i;                                                                                     \
        ltt_rng_t r;                                                                               \
        (void)state;                                                                               \
        ltt_rng_seed(&r, seed_of(#vfn) + 1u);                                                      \
        for (rep = 0; rep < N_REP; rep++) {                                                        \
            VT a, src, p;                                                                          \
            gen(&r, &a);                                                                           \
            gen(&r, &src);                                                                         \
            p = vfn(a);                                                                            \
            for (i = 0; i < LT_LANES; i++, lanes++)                                                \
                if (!same(p.l[i], sref(a.l[i])))                                                   \
                    note_val(&bad, #vfn, 0xFFFFu, i, (double)a.l[i], 0.0, (double)p.l[i],          \
                             (double)sref(a.l[i]));                                                \
            for (m = 0; m < nm; m++) {                                                             \
                lt_mask16_t k = masks[m];                                                          \
                VT rm = vfn##_m(src, k, a), rz = vfn##_z(k, a);                                    \
                for (i = 0; i < LT_LANES; i++, lanes += 2) {                                       \
                    ET want = sref(a.l[i]);                                                        \
                    int on = LTT_ON(k, i);                                                         \
                    if (!same(rm.l[i], on ? want : src.l[i]))                                      \
                        note_bad(&bad, #vfn "_m", k, i);                                           \
                    if (!same(rz.l[i], on ? want : (ET)0))                                         \
                        note_bad(&bad, #vfn "_z", k, i);                                           \
                }                                                                                  \
            }                                                                                      \
        }                                                                                          \
        family_done(#vfn "{,_m,_z}", #sref, lanes, bad);                                           \
    }

/* plain: bit i = (a_i REL b_i); _m: the same ANDed with k. About a quarter of the lanes of b
 * copy a, so equality is exercised. */
#define TEST_CMP(vfn, VT, REL, gen)                                                                \
    static void test_##vfn(void **state)                                                           \
    {                                                                                              \
        uint16_t masks[LTT_MASK_COUNT];                                                            \
        unsigned nm = ltt_masks(masks, seed_of(#vfn)), m, rep;                                     \
        unsigned long lanes = 0, bad = 0;                                                          \
        int i;                                                                                     \
        ltt_rng_t r;                                                                               \
        (void)state;                                                                               \
        ltt_rng_seed(&r, seed_of(#vfn) + 1u);                                                      \
        for (rep = 0; rep < 4 * N_REP; rep++) {                                                    \
            VT a, b;                                                                               \
            unsigned want = 0;                                                                     \
            gen(&r, &a);                                                                           \
            gen(&r, &b);                                                                           \
            for (i = 0; i < LT_LANES; i++) {                                                       \
                if (ltt_rng_below(&r, 4) == 0)                                                     \
                    b.l[i] = a.l[i];                                                               \
                if (a.l[i] REL b.l[i])                                                             \
                    want |= 1u << i;                                                               \
            }                                                                                      \
            lanes += LT_LANES;                                                                     \
            if (vfn(a, b) != want)                                                                 \
                note_bad(&bad, #vfn, 0xFFFFu, -1);                                                 \
            for (m = 0; m < nm; m++) {                                                             \
                lanes += LT_LANES;                                                                 \
                if (vfn##_m(masks[m], a, b) != (want & masks[m]))                                  \
                    note_bad(&bad, #vfn "_m", masks[m], -1);                                       \
            }                                                                                      \
        }                                                                                          \
        family_done(#vfn "{,_m}", "a " #REL " b", lanes, bad);                                     \
    }

/* ---- s15.16 / s1.30 / int32 / int64 / s7.8 scalar references --------------------------------- */

static int32_t ref_i32_add_wrap(int32_t a, int32_t b) { return ltt_i32((uint32_t)a + (uint32_t)b); }
static int64_t ref_l64_add_wrap(int64_t a, int64_t b) { return ltt_i64((uint64_t)a + (uint64_t)b); }
static int64_t ref_l64_sub_wrap(int64_t a, int64_t b) { return ltt_i64((uint64_t)a - (uint64_t)b); }

TEST_BIN(lt_vq16_add_sat, lt_vq16_t, int32_t, lt_q16_add_sat, gen_vq16, SAME_INT)
TEST_BIN(lt_vq16_sub_sat, lt_vq16_t, int32_t, lt_q16_sub_sat, gen_vq16, SAME_INT)
TEST_BIN(lt_vq16_add_wrap, lt_vq16_t, int32_t, lt_q16_add_wrap, gen_vq16, SAME_INT)
TEST_BIN(lt_vq16_sub_wrap, lt_vq16_t, int32_t, lt_q16_sub_wrap, gen_vq16, SAME_INT)
TEST_BIN(lt_vq16_min, lt_vq16_t, int32_t, lt_q16_min, gen_vq16, SAME_INT)
TEST_BIN(lt_vq16_max, lt_vq16_t, int32_t, lt_q16_max, gen_vq16, SAME_INT)
TEST_BIN(lt_vq16_mul_sat, lt_vq16_t, int32_t, lt_q16_mul_sat, gen_vq16, SAME_INT)
TEST_BIN(lt_vq16_mul_sat_rd, lt_vq16_t, int32_t, lt_q16_mul_sat_rd, gen_vq16, SAME_INT)
TEST_BIN(lt_vq16_div_sat, lt_vq16_t, int32_t, lt_q16_div_sat, gen_vq16, SAME_INT)
TEST_UN(lt_vq16_abs_sat, lt_vq16_t, int32_t, lt_q16_abs_sat, gen_vq16, SAME_INT)
TEST_UN(lt_vq16_neg_sat, lt_vq16_t, int32_t, lt_q16_neg_sat, gen_vq16, SAME_INT)
TEST_UN(lt_vq16_recip_sat, lt_vq16_t, int32_t, lt_q16_recip_sat, gen_vq16, SAME_INT)
TEST_CMP(lt_vq16_cmplt, lt_vq16_t, <, gen_vq16)
TEST_CMP(lt_vq16_cmple, lt_vq16_t, <=, gen_vq16)
TEST_CMP(lt_vq16_cmpgt, lt_vq16_t, >, gen_vq16)
TEST_CMP(lt_vq16_cmpge, lt_vq16_t, >=, gen_vq16)
TEST_CMP(lt_vq16_cmpeq, lt_vq16_t, ==, gen_vq16)
TEST_BIN(lt_vq30_mul_sat, lt_vq30_t, int32_t, lt_q30_mul_sat, gen_vq30, SAME_INT)
TEST_BIN(lt_vi32_add_wrap, lt_vi32_t, int32_t, ref_i32_add_wrap, gen_vi32, SAME_INT)
TEST_CMP(lt_vi32_cmpeq, lt_vi32_t, ==, gen_vi32)
TEST_BIN(lt_vql_add_wrap, lt_vql_t, int64_t, ref_l64_add_wrap, gen_vql, SAME_INT)
TEST_BIN(lt_vql_sub_wrap, lt_vql_t, int64_t, ref_l64_sub_wrap, gen_vql, SAME_INT)
TEST_CMP(lt_vql_cmplt, lt_vql_t, <, gen_vql)
TEST_CMP(lt_vql_cmple, lt_vql_t, <=, gen_vql)
TEST_CMP(lt_vql_cmpgt, lt_vql_t, >, gen_vql)
TEST_CMP(lt_vql_cmpge, lt_vql_t, >=, gen_vql)
TEST_BIN(lt_vh8_add_sat, lt_vh8_t, int16_t, lt_h8_add_sat, gen_vh8, SAME_INT)
TEST_BIN(lt_vh8_sub_sat, lt_vh8_t, int16_t, lt_h8_sub_sat, gen_vh8, SAME_INT)
TEST_BIN(lt_vh8_mul_sat, lt_vh8_t, int16_t, lt_h8_mul_sat, gen_vh8, SAME_INT)
TEST_CMP(lt_vh8_cmplt, lt_vh8_t, <, gen_vh8)
TEST_CMP(lt_vh8_cmple, lt_vh8_t, <=, gen_vh8)

/* ---- float32 ------------------------------------------------------------------------------ */
#if LT_CFG_FLOAT32

/* Bit equality, except that any NaN equals any NaN (payload propagation is not specified). */
static int same_f32(float x, float y)
{
    uint32_t a, b;
    if (x != x && y != y)
        return 1;
    memcpy(&a, &x, sizeof a);
    memcpy(&b, &y, sizeof b);
    return a == b;
}

static float gen_f32(ltt_rng_t *r)
{
    static const float e[] = { 0.0f, -0.0f, 1.0f, -1.0f, FLT_MAX, -FLT_MAX, FLT_MIN, 1e-45f,
                               -1e-45f, HUGE_VALF, -HUGE_VALF, NAN };
    uint32_t c = ltt_rng_below(r, 16);
    float m;
    if (c == 0)
        return e[ltt_rng_below(r, (uint32_t)(sizeof e / sizeof e[0]))];
    m = (float)ltt_rng_uniform(r, 1.0, 2.0);
    m = ldexpf(m, (int)ltt_rng_below(r, 61) - 30);
    return (ltt_rng_u32(r) & 1u) ? -m : m;
}
GEN_VEC(gen_vf32, lt_vf32_t, gen_f32)

/* IEEE single ops as C evaluates them (FLT_EVAL_METHOD 0 on the host, -ffp-contract=off). */
static float ref_fadd(float a, float b) { return a + b; }
static float ref_fsub(float a, float b) { return a - b; }
static float ref_fmul(float a, float b) { return a * b; }
static float ref_fdiv(float a, float b) { return a / b; }
/* documented: b when either is NaN, else the smaller (min) / larger (max), b on equality */
static float ref_fmin(float a, float b) { return (a != a || b != b) ? b : (a < b ? a : b); }
static float ref_fmax(float a, float b) { return (a != a || b != b) ? b : (a > b ? a : b); }
static float ref_frcp(float a) { return 1.0f / a; }
/* IEEE 754 abs: the sign bit cleared, for every input including -0 and NaN */
static float ref_fabs(float a) { return fabsf(a); }
static float ref_fneg(float a) { return -a; }

TEST_BIN(lt_vf32_add, lt_vf32_t, float, ref_fadd, gen_vf32, same_f32)
TEST_BIN(lt_vf32_sub, lt_vf32_t, float, ref_fsub, gen_vf32, same_f32)
TEST_BIN(lt_vf32_mul, lt_vf32_t, float, ref_fmul, gen_vf32, same_f32)
TEST_BIN(lt_vf32_div, lt_vf32_t, float, ref_fdiv, gen_vf32, same_f32)
TEST_BIN(lt_vf32_min, lt_vf32_t, float, ref_fmin, gen_vf32, same_f32)
TEST_BIN(lt_vf32_max, lt_vf32_t, float, ref_fmax, gen_vf32, same_f32)
TEST_UN(lt_vf32_rcp, lt_vf32_t, float, ref_frcp, gen_vf32, same_f32)
TEST_UN(lt_vf32_abs, lt_vf32_t, float, ref_fabs, gen_vf32, same_f32)
TEST_UN(lt_vf32_neg, lt_vf32_t, float, ref_fneg, gen_vf32, same_f32)
TEST_CMP(lt_vf32_cmplt, lt_vf32_t, <, gen_vf32)
TEST_CMP(lt_vf32_cmple, lt_vf32_t, <=, gen_vf32)
TEST_CMP(lt_vf32_cmpgt, lt_vf32_t, >, gen_vf32)
TEST_CMP(lt_vf32_cmpge, lt_vf32_t, >=, gen_vf32)
TEST_CMP(lt_vf32_cmpeq, lt_vf32_t, ==, gen_vf32)
#endif

/* ---- move family: set1, blend, load, store, store_m, gather_m, hmin, hmax ------------------- */

#define GUARD 8 /* guard elements each side of a stored vector */
#define POOL 64 /* gather table: indices in [-POOL, 2 POOL) of a 3 POOL array */

/* lo/hi: identities for hmin/hmax (the extremes of ET); gen_nonan: lanes without NaN. */
#define TEST_MOVE(pfx, VT, ET, gen, same, lo_id, hi_id)                                            \
    static void test_##pfx##_move(void **state)                                                    \
    {                                                                                              \
        uint16_t masks[LTT_MASK_COUNT];                                                            \
        unsigned nm = ltt_masks(masks, seed_of(#pfx)), m, rep;                                     \
        unsigned long lanes = 0, bad = 0;                                                          \
        int i;                                                                                     \
        ltt_rng_t r;                                                                               \
        ET buf[GUARD + LT_LANES + GUARD], pool[3 * POOL];                                          \
        (void)state;                                                                               \
        ltt_rng_seed(&r, seed_of(#pfx) + 1u);                                                      \
        for (rep = 0; rep < N_REP; rep++) {                                                        \
            VT a, b, src, p;                                                                       \
            lt_vi32_t idx;                                                                         \
            ET x = gen(&r);                                                                        \
            gen##_vec(&r, &a);                                                                     \
            gen##_vec(&r, &b);                                                                     \
            gen##_vec(&r, &src);                                                                   \
            for (i = 0; i < 3 * POOL; i++)                                                         \
                pool[i] = gen(&r);                                                                 \
            /* set1 */                                                                             \
            p = pfx##_set1(x);                                                                     \
            for (i = 0; i < LT_LANES; i++, lanes++)                                                \
                if (!same(p.l[i], x))                                                              \
                    note_bad(&bad, #pfx "_set1", 0xFFFFu, i);                                      \
            /* load at every offset of the pool window */                                          \
            p = pfx##_load(&pool[rep * 5u]);                                                       \
            for (i = 0; i < LT_LANES; i++, lanes++)                                                \
                if (!same(p.l[i], pool[rep * 5u + (unsigned)i]))                                   \
                    note_bad(&bad, #pfx "_load", 0xFFFFu, i);                                      \
            /* store: exactly the 16 lanes, guards untouched */                                    \
            ltt_poison(buf, sizeof buf);                                                           \
            pfx##_store(&buf[GUARD], a);                                                           \
            for (i = 0; i < LT_LANES; i++, lanes++)                                                \
                if (!same(buf[GUARD + i], a.l[i]))                                                 \
                    note_bad(&bad, #pfx "_store", 0xFFFFu, i);                                     \
            if (ltt_touched(buf, 0, GUARD * sizeof(ET)) != 0 ||                                    \
                ltt_touched(buf, (GUARD + LT_LANES) * sizeof(ET), sizeof buf) != 0)                \
                note_bad(&bad, #pfx "_store guard", 0xFFFFu, -1);                                  \
            for (m = 0; m < nm; m++) {                                                             \
                lt_mask16_t k = masks[m];                                                          \
                ET hmin = hi_id, hmax = lo_id;                                                     \
                /* indices: active lanes anywhere in the pool (negative included) */               \
                for (i = 0; i < LT_LANES; i++)                                                     \
                    idx.l[i] = ltt_rng_range(&r, -POOL, 2 * POOL - 1);                             \
                p = pfx##_blend(k, a, b);                                                          \
                for (i = 0; i < LT_LANES; i++, lanes++)                                            \
                    if (!same(p.l[i], LTT_ON(k, i) ? b.l[i] : a.l[i]))                             \
                        note_bad(&bad, #pfx "_blend", k, i);                                       \
                p = pfx##_gather_m(src, k, &pool[POOL], idx);                                      \
                for (i = 0; i < LT_LANES; i++, lanes++)                                            \
                    if (!same(p.l[i], LTT_ON(k, i) ? pool[POOL + idx.l[i]] : src.l[i]))            \
                        note_bad(&bad, #pfx "_gather_m", k, i);                                    \
                ltt_poison(buf, sizeof buf);                                                       \
                pfx##_store_m(&buf[GUARD], k, a);                                                  \
                for (i = 0; i < LT_LANES; i++, lanes++) {                                          \
                    size_t o = (GUARD + (size_t)i) * sizeof(ET);                                   \
                    if (LTT_ON(k, i) ? !same(buf[GUARD + i], a.l[i])                               \
                                      : ltt_touched(buf, o, o + sizeof(ET)) != 0)                  \
                        note_bad(&bad, #pfx "_store_m", k, i);                                     \
                }                                                                                  \
                if (ltt_touched(buf, 0, GUARD * sizeof(ET)) != 0 ||                                \
                    ltt_touched(buf, (GUARD + LT_LANES) * sizeof(ET), sizeof buf) != 0)            \
                    note_bad(&bad, #pfx "_store_m guard", k, -1);                                  \
                for (i = 0; i < LT_LANES; i++) {                                                   \
                    if (LTT_ON(k, i) && a.l[i] < hmin)                                             \
                        hmin = a.l[i];                                                             \
                    if (LTT_ON(k, i) && a.l[i] > hmax)                                             \
                        hmax = a.l[i];                                                             \
                }                                                                                  \
                lanes += 4;                                                                        \
                if (!same(pfx##_hmin(k, a, hi_id), hmin))                                          \
                    note_bad(&bad, #pfx "_hmin", k, -1);                                           \
                if (!same(pfx##_hmax(k, a, lo_id), hmax))                                          \
                    note_bad(&bad, #pfx "_hmax", k, -1);                                           \
                /* `none` below every lane wins hmin; an empty mask returns it */                  \
                if (!same(pfx##_hmin(k, a, lo_id), lo_id))                                         \
                    note_bad(&bad, #pfx "_hmin none", k, -1);                                      \
                if (!same(pfx##_hmax(k, a, hi_id), hi_id))                                         \
                    note_bad(&bad, #pfx "_hmax none", k, -1);                                      \
            }                                                                                      \
        }                                                                                          \
        family_done(#pfx "_{set1,blend,load,store,store_m,gather_m,hmin,hmax}",                    \
                    "per-lane reference", lanes, bad);                                             \
    }

#define gen_i32_vec gen_vq16
static void gen_q30l_vec(ltt_rng_t *r, lt_vq30_t *v) { gen_vq30(r, v); }
static int32_t gen_q30l(ltt_rng_t *r) { return gen_i32(r); }
static void gen_i32l_vec(ltt_rng_t *r, lt_vi32_t *v) { gen_vi32(r, v); }
static int32_t gen_i32l(ltt_rng_t *r) { return gen_i32(r); }
#define gen_i16_vec gen_vh8
TEST_MOVE(lt_vq16, lt_vq16_t, int32_t, gen_i32, SAME_INT, INT32_MIN, INT32_MAX)
TEST_MOVE(lt_vq30, lt_vq30_t, int32_t, gen_q30l, SAME_INT, INT32_MIN, INT32_MAX)
TEST_MOVE(lt_vi32, lt_vi32_t, int32_t, gen_i32l, SAME_INT, INT32_MIN, INT32_MAX)
TEST_MOVE(lt_vh8, lt_vh8_t, int16_t, gen_i16, SAME_INT, INT16_MIN, INT16_MAX)
#if LT_CFG_FLOAT32
/* finite lanes only: hmin/hmax with a NaN lane have no reference beyond the loop itself */
static float gen_f32fin(ltt_rng_t *r)
{
    float x = gen_f32(r);
    return x != x ? 0.5f : x;
}
static void gen_f32fin_vec(ltt_rng_t *r, lt_vf32_t *v)
{
    int i;
    for (i = 0; i < LT_LANES; i++)
        v->l[i] = gen_f32fin(r);
}
TEST_MOVE(lt_vf32, lt_vf32_t, float, gen_f32fin, same_f32, -HUGE_VALF, HUGE_VALF)
#endif

/* ---- masks ---------------------------------------------------------------------------------- */

static void test_mask_helpers(void **state)
{
    unsigned k, bad = 0;
    (void)state;
    for (k = 0; k <= 0xFFFFu; k++) {
        lt_mask16_t m = (lt_mask16_t)k, it;
        unsigned pop = 0, first = 16, visited = 0, last = 0, steps = 0, i;
        int ordered = 1;
        for (i = 0; i < 16; i++) {
            if LTT_ON(k, i) {
                pop++;
                if (first == 16)
                    first = i;
            }
        }
        bad += lt_mask16_any(m) != (k != 0);
        bad += lt_mask16_all(m) != (k == 0xFFFFu);
        bad += lt_mask16_popcount(m) != pop;
        bad += lt_mask16_first(m) != first;
        /* the documented iteration idiom visits each set lane once, in increasing order */
        for (it = m; it; it = lt_mask16_clear_first(it)) {
            i = lt_mask16_first(it);
            if (i >= 16 || steps > 16) {
                bad++;
                break;
            }
            if (steps != 0 && i <= last)
                ordered = 0;
            visited |= 1u << i;
            last = i;
            steps++;
        }
        bad += visited != k || steps != pop || !ordered;
    }
    ltt_report("lt_mask16_{any,all,popcount,first,clear_first}: all 65536 masks, %u mismatches vs "
               "bit loops; iteration visits exactly the set lanes in order (bound 0)\n", bad);
    assert_int_equal(bad, 0);
}

/* ---- conversions, wide lanes, odd ones out ------------------------------------------------- */

static void test_conversions(void **state)
{
    ltt_rng_t r;
    unsigned rep;
    unsigned long lanes = 0, bad = 0;
    int i;
    (void)state;
    ltt_rng_seed(&r, 501);
    for (rep = 0; rep < 64 * N_REP; rep++) {
        lt_vq16_t a, p;
        lt_vq30_t d;
        lt_vh8_t h, hp;
        lt_vi32_t w, it;
        gen_vq16(&r, &a);
        gen_vq30(&r, &d);
        gen_vh8(&r, &h);
        p = lt_vq16_mul_q30_sat(a, d);
        for (i = 0; i < LT_LANES; i++, lanes++)
            if (p.l[i] != lt_q16_mul_q30_sat(a.l[i], d.l[i]))
                note_bad(&bad, "lt_vq16_mul_q30_sat", 0xFFFFu, i);
        p = lt_vq16_from_q30(d);
        for (i = 0; i < LT_LANES; i++, lanes++)
            if (p.l[i] != lt_q16_from_q30(d.l[i]))
                note_bad(&bad, "lt_vq16_from_q30", 0xFFFFu, i);
        p = lt_vq16_from_h8(h);
        for (i = 0; i < LT_LANES; i++, lanes++)
            if (p.l[i] != lt_q16_from_h8(h.l[i]))
                note_bad(&bad, "lt_vq16_from_h8", 0xFFFFu, i);
        hp = lt_vh8_from_q16_sat(a);
        for (i = 0; i < LT_LANES; i++, lanes++)
            if (hp.l[i] != lt_h8_from_q16_sat(a.l[i]))
                note_bad(&bad, "lt_vh8_from_q16_sat", 0xFFFFu, i);
        w = lt_vi32_from_q16(a);
        it = lt_vi32_from_q30(d);
        for (i = 0; i < LT_LANES; i++, lanes += 2)
            if (w.l[i] != a.l[i] || it.l[i] != d.l[i])
                note_bad(&bad, "lt_vi32_from_q16/q30", 0xFFFFu, i);
    }
    {
        lt_vi32_t io = lt_vi32_iota();
        for (i = 0; i < LT_LANES; i++, lanes++)
            if (io.l[i] != i)
                note_bad(&bad, "lt_vi32_iota", 0xFFFFu, i);
    }
    family_done("lt_vq16_mul_q30_sat/from_q30/from_h8, lt_vh8_from_q16_sat, lt_vi32_iota/from_*",
                "scalar ops", lanes, bad);
}

static void test_vql(void **state)
{
    ltt_rng_t r;
    unsigned rep, f;
    unsigned long lanes = 0, bad = 0;
    int i;
    (void)state;
    ltt_rng_seed(&r, 502);
    for (rep = 0; rep < 8 * N_REP; rep++) {
        lt_vi32_t a, b;
        lt_vql_t p, w, s1;
        int64_t x = gen_i64(&r);
        gen_vi32(&r, &a);
        gen_vi32(&r, &b);
        gen_vql(&r, &w);
        /* exact products: 63 bits fit the long double significand */
        p = lt_vql_mul(a, b);
        for (i = 0; i < LT_LANES; i++, lanes++)
            if ((long double)p.l[i] != (long double)a.l[i] * (long double)b.l[i])
                note_bad(&bad, "lt_vql_mul", 0xFFFFu, i);
        s1 = lt_vql_set1(x);
        for (i = 0; i < LT_LANES; i++, lanes++)
            if (s1.l[i] != x)
                note_bad(&bad, "lt_vql_set1", 0xFFFFu, i);
        /* round away f bits half up, saturate: floor(x / 2^f + 1/2) clamped */
        for (f = 1; f <= 31; f++) {
            lt_vi32_t q = lt_vql_round_sat((f & 1u) ? p : w, f);
            for (i = 0; i < LT_LANES; i++, lanes++) {
                long double v = ldexpl((long double)((f & 1u) ? p.l[i] : w.l[i]), -(int)f);
                long double want = floorl(v + 0.5L);
                want = want > 2147483647.0L ? 2147483647.0L
                                            : (want < -2147483648.0L ? -2147483648.0L : want);
                if ((long double)q.l[i] != want)
                    note_bad(&bad, "lt_vql_round_sat", f, i);
            }
        }
        for (f = 0; f <= 63; f++) {
            lt_vql_t q = lt_vql_asr(w, f);
            for (i = 0; i < LT_LANES; i++, lanes++)
                if ((long double)q.l[i] != floorl(ldexpl((long double)w.l[i], -(int)f)))
                    note_bad(&bad, "lt_vql_asr", f, i);
        }
    }
    family_done("lt_vql_{mul,set1,round_sat (f 1..31),asr (s 0..63)}",
                "long double floor/round reference", lanes, bad);
}

#define T(name) cmocka_unit_test(test_##name)

int main(void)
{
    const struct CMUnitTest tests[] = {
        T(mask_helpers),     T(lt_vq16_add_sat),  T(lt_vq16_sub_sat),    T(lt_vq16_add_wrap),
        T(lt_vq16_sub_wrap), T(lt_vq16_min),      T(lt_vq16_max),        T(lt_vq16_mul_sat),
        T(lt_vq16_mul_sat_rd), T(lt_vq16_div_sat), T(lt_vq16_abs_sat),   T(lt_vq16_neg_sat),
        T(lt_vq16_recip_sat), T(lt_vq16_cmplt),   T(lt_vq16_cmple),      T(lt_vq16_cmpgt),
        T(lt_vq16_cmpge),    T(lt_vq16_cmpeq),    T(lt_vq30_mul_sat),    T(lt_vi32_add_wrap),
        T(lt_vi32_cmpeq),    T(lt_vql_add_wrap),  T(lt_vql_sub_wrap),    T(lt_vql_cmplt),
        T(lt_vql_cmple),     T(lt_vql_cmpgt),     T(lt_vql_cmpge),       T(lt_vh8_add_sat),
        T(lt_vh8_sub_sat),   T(lt_vh8_mul_sat),   T(lt_vh8_cmplt),       T(lt_vh8_cmple),
        T(lt_vq16_move),     T(lt_vq30_move),     T(lt_vi32_move),       T(lt_vh8_move),
        T(conversions),      T(vql),
#if LT_CFG_FLOAT32
        T(lt_vf32_add),      T(lt_vf32_sub),      T(lt_vf32_mul),        T(lt_vf32_div),
        T(lt_vf32_min),      T(lt_vf32_max),      T(lt_vf32_rcp),        T(lt_vf32_abs),
        T(lt_vf32_neg),      T(lt_vf32_cmplt),    T(lt_vf32_cmple),      T(lt_vf32_cmpgt),
        T(lt_vf32_cmpge),    T(lt_vf32_cmpeq),    T(lt_vf32_move),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
