/* test_qmc.c - the integer QMC point sets of lt_qmc.h against their definitions: van der Corput
 * as the sum of bits b_k 2^-(k+1), Larcher-Pillichshammer as the all-ones upper-triangular generator
 * matrix (bit 31 - b = parity of i >> b) and Kollig & Keller's loop, Hammersley/LP points, the
 * (0,m,2)-net property of both 2D sets, and the 4x4 interleaved split (each set a (0,4,2)-net,
 * union = the 256-point set, scrambles keep both). Builds: host, sim, asan.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>

#include "lt/lt_qmc.h"
#include "lt_test_util.h"

/* van der Corput by definition: value = sum of bit k of i times 2^-(k+1), as a 0.32 fraction
 * (each term 2^(31-k) exact). */
static uint32_t vdc_def(uint32_t i)
{
    uint64_t v = 0;
    unsigned k;
    for (k = 0; k < 32; k++)
        if ((i >> k) & 1u)
            v += (uint64_t)1 << (31 - k);
    return (uint32_t)v;
}

/* LP by its generator matrix: output bit at weight 2^-(b+1) = XOR over k >= b of bit k of i. */
static uint32_t lp_def(uint32_t i)
{
    uint32_t r = 0;
    unsigned b;
    for (b = 0; b < 32; b++) {
        unsigned par = 0, k;
        for (k = b; k < 32; k++)
            par ^= (i >> k) & 1u;
        r |= (uint32_t)par << (31 - b);
    }
    return r;
}

/* Kollig & Keller 2002, listed as printed (double version's integer core). */
static uint32_t lp_kk(uint32_t i)
{
    uint32_t r = 0;
    for (uint32_t v = 1u << 31; i; i >>= 1, v |= v >> 1)
        if (i & 1u)
            r ^= v;
    return r;
}

static void test_radical_inverses(void **state)
{
    ltt_rng_t rng;
    unsigned n = 0, bad_vdc = 0, bad_lp = 0, bad_kk = 0;
    uint32_t i;
    (void)state;
    ltt_rng_seed(&rng, 4);
    for (i = 0; i < 70000u; i++) {
        uint32_t x = i < 66000u ? i : ltt_rng_u32(&rng);
        bad_vdc += lt_qmc_vdc(x) != vdc_def(x);
        bad_lp += lt_qmc_lp(x) != lp_def(x);
        bad_kk += lt_qmc_lp(x) != lp_kk(x);
        n++;
    }
    /* extremes */
    assert_int_equal(lt_qmc_vdc(0), 0u);
    assert_int_equal(lt_qmc_vdc(1), 0x80000000u);
    assert_int_equal(lt_qmc_vdc(0xFFFFFFFFu), 0xFFFFFFFFu);
    assert_int_equal(lt_qmc_lp(1), 0x80000000u);
    assert_int_equal(lt_qmc_lp(2), 0xC0000000u);
    assert_int_equal(lt_qmc_lp(3), 0x40000000u);
    ltt_report("lt_qmc_vdc / lt_qmc_lp: %u indices (0..65999 and random), %u / %u / %u mismatches "
               "vs bit-sum definition / generator matrix / Kollig-Keller loop (bound 0)\n",
               n, bad_vdc, bad_lp, bad_kk);
    assert_int_equal(bad_vdc, 0);
    assert_int_equal(bad_lp, 0);
    assert_int_equal(bad_kk, 0);
}

/* Every elementary interval [a 2^-k1, (a+1) 2^-k1) x [b 2^-k2, ...) with k1 + k2 = m holds exactly
 * one of the 2^m points (u, v given as their top m bits). */
static unsigned net_violations(const uint32_t *u, const uint32_t *v, unsigned m)
{
    unsigned k1, bad = 0, n = 1u << m;
    static unsigned char cnt[1u << 12];
    for (k1 = 0; k1 <= m; k1++) {
        unsigned k2 = m - k1, i;
        memset(cnt, 0, n);
        for (i = 0; i < n; i++) {
            unsigned a = k1 == 0 ? 0u : (unsigned)(u[i] >> (32 - k1));
            unsigned b = k2 == 0 ? 0u : (unsigned)(v[i] >> (32 - k2));
            cnt[(a << k2) | b]++;
        }
        for (i = 0; i < n; i++)
            bad += cnt[i] != 1;
    }
    return bad;
}

static void test_point_sets(void **state)
{
    static uint32_t u[4096], v[4096];
    unsigned m, kind, i, total = 0;
    (void)state;
    for (kind = 0; kind < 2; kind++)
        for (m = 0; m <= 12; m++) {
            unsigned bad;
            for (i = 0; i < (1u << m); i++) {
                assert_int_equal(lt_qmc_point((lt_qmc_kind_t)kind, i, m, &u[i], &v[i]), LT_OK);
                assert_int_equal(u[i], m == 0 ? 0u : i << (32 - m));
                assert_int_equal(v[i], kind == 0 ? vdc_def(i) : lp_def(i));
            }
            bad = net_violations(u, v, m);
            total += 1u << m;
            assert_int_equal(bad, 0);
        }
    ltt_report("lt_qmc_point: Hammersley and LP sets of 2^0..2^12 points, %u points: u = i/n, v = "
               "definition, every set a (0,m,2)-net in base 2 (0 elementary intervals off 1)\n",
               total);
    /* arguments */
    assert_int_equal(lt_qmc_point(LT_QMC_LP, 16, 4, &u[0], &v[0]), LT_E_ARG);
    assert_int_equal(lt_qmc_point(LT_QMC_LP, 0, 33, &u[0], &v[0]), LT_E_ARG);
    assert_int_equal(lt_qmc_point((lt_qmc_kind_t)7, 0, 4, &u[0], &v[0]), LT_E_ARG);
    assert_int_equal(lt_qmc_point(LT_QMC_LP, 0, 4, NULL, &v[0]), LT_E_ARG);
    assert_int_equal(lt_qmc_point(LT_QMC_HAMMERSLEY, 0xFFFFFFFFu, 32, &u[0], &v[0]), LT_OK);
    assert_int_equal(u[0], 0xFFFFFFFFu);
    ltt_report("lt_qmc_point: index out of range, log2n > 32, unknown kind, NULL -> LT_E_ARG\n");
}

static unsigned rev4(unsigned x)
{
    return ((x & 1u) << 3) | ((x & 2u) << 1) | ((x & 4u) >> 1) | ((x & 8u) >> 3);
}

static void test_interleave(void **state)
{
    static const uint32_t scr[] = {0u, 0x00A5u, 0x5A00u, 0xFFFFu, 0x1234u};
    unsigned kind, si, checked = 0;
    (void)state;
    for (kind = 0; kind < 2; kind++)
        for (si = 0; si < sizeof scr / sizeof scr[0]; si++) {
            lt_qmc_sets_t S;
            static unsigned char seen[256][256];
            uint32_t uu[256], vv[256], us[16], vs[16];
            unsigned s, j, i;
            memset(&S, 0xA5, sizeof S);
            memset(seen, 0, sizeof seen);
            assert_int_equal(lt_qmc_interleave4x4((lt_qmc_kind_t)kind, scr[si], &S), LT_OK);
            /* the expected 256 points: the set's (u, v) cells after the digital shift */
            for (i = 0; i < 256; i++) {
                uint32_t pu, pv;
                lt_qmc_point((lt_qmc_kind_t)kind, i, 8, &pu, &pv);
                uu[i] = ((pu >> 24) ^ (scr[si] & 0xFFu)) << 24;
                vv[i] = ((pv >> 24) ^ ((scr[si] >> 8) & 0xFFu)) << 24;
                seen[uu[i] >> 24][vv[i] >> 24] = 1;
            }
            /* a digitally shifted net is still a (0,8,2)-net */
            assert_int_equal(net_violations(uu, vv, 8), 0);
            for (s = 0; s < 16; s++) {
                for (j = 0; j < 16; j++) {
                    unsigned a = S.u[s][j] >> 4, w = S.v[s][j] >> 4;
                    /* each (set, sample) is one of the 256 points, used exactly once */
                    assert_int_equal(seen[S.u[s][j]][S.v[s][j]], 1);
                    seen[S.u[s][j]][S.v[s][j]] = 2;
                    /* sample j has top u bits j and top v bits rev4(j ^ s) */
                    assert_int_equal(a, j);
                    assert_int_equal(w, rev4(j ^ s));
                    us[j] = (uint32_t)S.u[s][j] << 24;
                    vs[j] = (uint32_t)S.v[s][j] << 24;
                }
                /* every set a (0,4,2)-net in its top 4 bits */
                assert_int_equal(net_violations(us, vs, 4), 0);
                checked++;
            }
        }
    ltt_report("lt_qmc_interleave4x4: 2 kinds x 5 scrambles: %u sets of 16, each a (0,4,2)-net, "
               "their union exactly the shifted 256-point (0,8,2)-net (every point once)\n", checked);
    assert_int_equal(lt_qmc_interleave4x4(LT_QMC_LP, 0, NULL), LT_E_ARG);
    assert_int_equal(lt_qmc_interleave4x4((lt_qmc_kind_t)3, 0, (lt_qmc_sets_t *)&checked),
                     LT_E_ARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_radical_inverses),
        cmocka_unit_test(test_point_sets),
        cmocka_unit_test(test_interleave),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
