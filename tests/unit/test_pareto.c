/* test_pareto.c - cmocka tests of host/tune/lt_pareto (lanetrace tune's arithmetic): dominance;
 * the front is exactly the non-dominated set on random point sets (property test, with ties,
 * duplicates and NaN, 2..4 objectives, an include mask); budgets: parsing of good input and a
 * clear message naming the input for bad input (unknown metric, negative or non-numeric bound,
 * empty term, missing operator, '%' on a metric that is not a percentage); meets, pick (cheapest,
 * ties on bytes, NaN never meets), binding term; and the tune's fronts per family and machine
 * (lt_tune_mark_fronts) on random measurements. Builds: host, sim, asan.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tune/lt_pareto.h"
#include "tune/lt_tune.h"

/* A small deterministic generator (xorshift32). */
static uint32_t rng = 2463534242u;
static uint32_t next(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng;
}

/* Values from a few levels so that ties happen; sometimes NaN. */
static double value(void)
{
    uint32_t r = next() % 64u;
    if (r == 63u)
        return NAN;
    return (double)(r % 9u) * 0.5;
}

static void test_dominates(void **state)
{
    const double a[3] = {1, 2, 3}, b[3] = {1, 2, 4}, c[3] = {1, 2, 3}, d[3] = {0, 5, 3};
    const double n[2] = {1, NAN}, m[2] = {1, 7};
    (void)state;
    assert_true(lt_pareto_dominates(a, b, 3));
    assert_false(lt_pareto_dominates(b, a, 3));
    assert_false(lt_pareto_dominates(a, c, 3)); /* equal: neither */
    assert_false(lt_pareto_dominates(a, d, 3)); /* a trade */
    assert_false(lt_pareto_dominates(d, a, 3));
    assert_true(lt_pareto_dominates(m, n, 2)); /* NaN is the worst value */
    assert_false(lt_pareto_dominates(n, m, 2));
}

/* Property: on random sets, every front point is dominated by no included point, and every
 * included point off the front is dominated by some included point. */
static void test_front_property(void **state)
{
    int trial;
    (void)state;
    for (trial = 0; trial < 400; trial++) {
        size_t n = 1 + next() % 60u, i, j, m;
        int k = 2 + (int)(next() % 3u);
        double *obj = malloc(n * (size_t)k * sizeof *obj);
        unsigned char *inc = malloc(n), *on = malloc(n);
        size_t count = 0;
        assert_non_null(obj);
        assert_non_null(inc);
        assert_non_null(on);
        for (i = 0; i < n * (size_t)k; i++)
            obj[i] = value();
        if (trial % 3 == 0 && n > 1) /* duplicates */
            memcpy(obj + (size_t)k, obj, (size_t)k * sizeof *obj);
        for (i = 0; i < n; i++)
            inc[i] = (unsigned char)(trial % 2 == 0 || next() % 4u != 0);
        m = lt_pareto_front(obj, n, k, inc, on);
        for (i = 0; i < n; i++) {
            int dominated = 0;
            count += on[i];
            if (!inc[i]) {
                assert_int_equal(on[i], 0);
                continue;
            }
            for (j = 0; j < n; j++)
                if (j != i && inc[j] && lt_pareto_dominates(obj + j * (size_t)k, obj + i * (size_t)k, k))
                    dominated = 1;
            assert_int_equal(on[i], !dominated);
        }
        assert_int_equal(m, count);
        free(obj);
        free(inc);
        free(on);
    }
}

static void test_budget_parse_good(void **state)
{
    lt_budget_t b;
    lt_diag_t d;
    char text[256];
    (void)state;
    assert_int_equal(lt_budget_parse("wrong<=0.5%,cycles<=2e6", &b, &d), 0);
    assert_int_equal(b.n, 2);
    assert_int_equal(b.t[0].metric, LT_M_WRONG);
    assert_int_equal(b.t[0].ge, 0);
    assert_true(b.t[0].bound == 0.5);
    assert_int_equal(b.t[1].metric, LT_M_CYCLES);
    assert_true(b.t[1].bound == 2e6);
    assert_int_equal(lt_budget_parse(" psnr >= 30 , bytes<=65536 ,rel99<=1", &b, &d), 0);
    assert_int_equal(b.n, 3);
    assert_int_equal(b.t[0].metric, LT_M_PSNR);
    assert_int_equal(b.t[0].ge, 1);
    assert_int_equal(b.t[2].metric, LT_M_REL99);
    assert_int_equal(lt_budget_parse("rmse<=0", &b, &d), 0);
    lt_budget_parse("wrong<=0.5%,psnr>=30", &b, &d);
    lt_budget_text(&b, text, sizeof text);
    assert_string_equal(text, "wrong<=0.5%, psnr>=30");
}

/* Each bad budget fails with a message naming the term (or the whole input) and the rule. */
static void test_budget_parse_bad(void **state)
{
    static const struct {
        const char *text, *expect1, *expect2;
    } bad[] = {
        {"speed<=3", "unknown metric 'speed'", "wrong, rmse, rel99, psnr, cycles, bytes"},
        {"wrong<=-1", "'wrong<=-1'", "negative"},
        {"cycles<=abc", "'cycles<=abc'", "not a number"},
        {"cycles<=", "'cycles<='", "not a number"},
        {"cycles<=nan", "'cycles<=nan'", "not a number"},
        {"cycles<=inf", "'cycles<=inf'", "not a number"},
        {"wrong<=1,,cycles<=5", "empty term", "METRIC<=X"},
        {"", "empty", "METRIC<=X"},
        {"   ", "empty", "METRIC<=X"},
        {"wrong=1", "'wrong=1'", "expected <= or >="},
        {"wrong<1", "'wrong<1'", "expected <= or >="},
        {"cycles<=5%", "'cycles<=5%'", "not a percentage"},
        {"cycles<=5x", "'cycles<=5x'", "trailing 'x'"},
        {"<=5", "'<=5'", "unknown metric ''"},
        {"WRONG<=1", "unknown metric", "wrong, rmse"},
    };
    size_t i;
    (void)state;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        lt_budget_t b;
        lt_diag_t d;
        memset(&d, 0, sizeof d);
        assert_int_equal(lt_budget_parse(bad[i].text, &b, &d), -1);
        if (strstr(d.msg, bad[i].expect1) == NULL || strstr(d.msg, bad[i].expect2) == NULL)
            fail_msg("budget \"%s\": message \"%s\" lacks \"%s\" / \"%s\"", bad[i].text, d.msg,
                     bad[i].expect1, bad[i].expect2);
        assert_true(strncmp(d.msg, "--budget", 8) == 0);
        assert_null(strchr(d.msg, '\n'));
    }
    {
        lt_budget_t b;
        assert_int_equal(lt_budget_parse(NULL, &b, NULL), -1);
    }
}

static void row(double *v, double wrong, double rmse, double psnr, double cycles, double bytes)
{
    v[LT_M_WRONG] = wrong;
    v[LT_M_RMSE] = rmse;
    v[LT_M_REL99] = NAN;
    v[LT_M_PSNR] = psnr;
    v[LT_M_CYCLES] = cycles;
    v[LT_M_BYTES] = bytes;
}

static void test_budget_pick(void **state)
{
    double v[5 * LT_M__COUNT];
    unsigned char inc[5] = {1, 1, 1, 1, 1};
    lt_budget_t b;
    lt_diag_t d;
    int failed = -1;
    (void)state;
    row(v + 0 * LT_M__COUNT, 0.0, 1e-6, NAN, 900, 100);  /* most accurate, dearest */
    row(v + 1 * LT_M__COUNT, 0.2, 1e-5, NAN, 500, 300);
    row(v + 2 * LT_M__COUNT, 0.2, 1e-5, NAN, 500, 200);  /* same cycles, fewer bytes */
    row(v + 3 * LT_M__COUNT, 2.0, 1e-3, NAN, 100, 50);   /* cheapest, least accurate */
    row(v + 4 * LT_M__COUNT, NAN, NAN, 30.0, 10, 10);    /* another family's point */
    assert_int_equal(lt_budget_parse("wrong<=0.5%", &b, &d), 0);
    assert_int_equal(lt_budget_pick(&b, v, 5, inc), 2);
    assert_true(lt_budget_meets(&b, v + 2 * LT_M__COUNT, NULL));
    assert_false(lt_budget_meets(&b, v + 4 * LT_M__COUNT, &failed)); /* NaN never meets */
    assert_int_equal(failed, 0);
    assert_int_equal(lt_budget_binding(&b, v, 5, inc, 2), 0); /* without it: row 4 */
    inc[4] = 0;
    assert_int_equal(lt_budget_binding(&b, v, 5, inc, 2), 0); /* without it: row 3 */
    assert_int_equal(lt_budget_parse("wrong<=0.5,bytes<=150", &b, &d), 0);
    assert_int_equal(lt_budget_pick(&b, v, 5, inc), 0);
    /* both bind: without wrong row 3 (800 saved), without bytes row 2 (400 saved) */
    assert_int_equal(lt_budget_binding(&b, v, 5, inc, 0), 0);
    assert_int_equal(lt_budget_parse("cycles<=1e9", &b, &d), 0);
    assert_int_equal(lt_budget_pick(&b, v, 5, inc), 3);
    assert_int_equal(lt_budget_binding(&b, v, 5, inc, 3), -1); /* nothing binds */
    /* row 3 breaks both wrong and rmse: neither alone binds, together they do */
    assert_int_equal(lt_budget_parse("wrong<=0.5%,rmse<=1e-4", &b, &d), 0);
    assert_int_equal(lt_budget_pick(&b, v, 5, inc), 2);
    assert_int_equal(lt_budget_binding(&b, v, 5, inc, 2), LT_BUDGET_JOINT);
    assert_int_equal(lt_budget_parse("wrong<=0.01%,cycles<=800", &b, &d), 0);
    assert_int_equal(lt_budget_pick(&b, v, 5, inc), -1); /* impossible */
    assert_int_equal(lt_budget_parse("psnr>=25", &b, &d), 0);
    inc[4] = 1;
    assert_int_equal(lt_budget_pick(&b, v, 5, inc), 4);
}

/* lt_tune_mark_fronts: per family and machine, on random full measurements. */
static void test_tune_fronts(void **state)
{
    int trial;
    (void)state;
    for (trial = 0; trial < 100; trial++) {
        size_t n = 2 + next() % 80u, i, j;
        lt_tune_point_t *p = calloc(n, sizeof *p);
        assert_non_null(p);
        for (i = 0; i < n; i++) {
            int m;
            p[i].k.family = (int)(next() % 3u);
            p[i].k.machine = (int)(next() % 2u);
            p[i].full.ok = next() % 8u != 0;
            for (m = 0; m < LT_M__COUNT; m++)
                p[i].full.m[m] = value();
            p[i].full.m[LT_M_CYCLES] = 1000.0 + (double)(next() % 5u);
            p[i].full.off = value();
        }
        lt_tune_mark_fronts(p, n);
        for (i = 0; i < n; i++) {
            double a[3], b[3];
            int dominated = 0;
            if (!p[i].full.ok) {
                assert_int_equal(p[i].front, 0);
                continue;
            }
            lt_tune_objectives(p[i].k.family, &p[i].full, a);
            for (j = 0; j < n; j++) {
                if (j == i || !p[j].full.ok || p[j].k.family != p[i].k.family ||
                    p[j].k.machine != p[i].k.machine)
                    continue;
                lt_tune_objectives(p[j].k.family, &p[j].full, b);
                dominated |= lt_pareto_dominates(b, a, 3);
            }
            assert_int_equal(p[i].front, !dominated);
        }
        free(p);
    }
}

static void test_metric_names(void **state)
{
    int m;
    (void)state;
    for (m = 0; m < LT_M__COUNT; m++)
        assert_int_equal(lt_metric_find(lt_metric_names[m]), m);
    assert_null(lt_metric_names[LT_M__COUNT]);
    assert_int_equal(lt_metric_find("psnr"), LT_M_PSNR);
    assert_int_equal(lt_metric_higher_better(LT_M_PSNR), 1);
    assert_int_equal(lt_metric_higher_better(LT_M_CYCLES), 0);
    assert_int_equal(lt_metric_find("speed"), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dominates),         cmocka_unit_test(test_front_property),
        cmocka_unit_test(test_budget_parse_good), cmocka_unit_test(test_budget_parse_bad),
        cmocka_unit_test(test_budget_pick),       cmocka_unit_test(test_tune_fronts),
        cmocka_unit_test(test_metric_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
