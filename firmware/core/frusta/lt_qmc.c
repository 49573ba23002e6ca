/* lt_qmc.c - integer QMC point sets (Kollig & Keller 2002 [Kollig02]) and their 4x4 interleaved
 * split (Keller & Heidrich 2001 [Keller01]) for the soft-shadow frusta of Benthin & Wald 2009
 * [Benthin09], section 4.5. Bit operations only: exact and identical in every build. Builds: all.
 */
#include "lt/lt_qmc.h"

uint32_t lt_qmc_vdc(uint32_t i)
{
    /* swap halves, then bytes, nibbles, pairs and bits: a full 32-bit reversal */
    i = (i << 16) | (i >> 16);
    i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
    i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
    i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
    i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
    return i;
}

uint32_t lt_qmc_lp(uint32_t i)
{
    /* Kollig & Keller's loop: bit k of i flips the top k + 1 bits of the result */
    uint32_t r = 0, v = 0x80000000u;
    for (; i != 0; i >>= 1, v |= v >> 1)
        if ((i & 1u) != 0)
            r ^= v;
    return r;
}

lt_status_t lt_qmc_point(lt_qmc_kind_t kind, uint32_t i, unsigned log2n, uint32_t *u, uint32_t *v)
{
    if (u == NULL || v == NULL || log2n > LT_QMC_MAX_LOG2N ||
        (kind != LT_QMC_HAMMERSLEY && kind != LT_QMC_LP))
        return LT_E_ARG;
    if (log2n < 32u && (i >> log2n) != 0)
        return LT_E_ARG;
    /* i / 2^log2n as a 0.32 fraction; log2n == 0 has the single point i = 0 */
    *u = log2n == 0 ? 0u : (log2n == 32u ? i : i << (32u - log2n));
    *v = kind == LT_QMC_HAMMERSLEY ? lt_qmc_vdc(i) : lt_qmc_lp(i);
    return LT_OK;
}

static unsigned rev4(unsigned x)
{
    return ((x & 1u) << 3) | ((x & 2u) << 1) | ((x & 4u) >> 1) | ((x & 8u) >> 3);
}

lt_status_t lt_qmc_interleave4x4(lt_qmc_kind_t kind, uint32_t scramble, lt_qmc_sets_t *out)
{
    uint32_t i;
    unsigned su = scramble & 0xFFu, sv = (scramble >> 8) & 0xFFu;
    if (out == NULL || (kind != LT_QMC_HAMMERSLEY && kind != LT_QMC_LP))
        return LT_E_ARG;
    /* A (0,8,2)-net has exactly one point in each 1/16 x 1/16 cell, so (a, w) = (top4 u, top4 v)
     * names a point; it goes to set s = a ^ rev4(w) as sample a. The map is a bijection from the
     * 256 points onto (set, sample) pairs, so every slot is written exactly once. */
    for (i = 0; i < 256u; i++) {
        uint32_t pu, pv;
        unsigned u8, v8, a, s;
        (void)lt_qmc_point(kind, i, 8u, &pu, &pv);
        u8 = (unsigned)(pu >> 24) ^ su;
        v8 = (unsigned)(pv >> 24) ^ sv;
        a = u8 >> 4;
        s = a ^ rev4(v8 >> 4);
        out->u[s][a] = (uint8_t)u8;
        out->v[s][a] = (uint8_t)v8;
    }
    return LT_OK;
}
