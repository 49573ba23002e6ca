/* lt_fx.c - out-of-line fixed-point ops (square roots, cross product, normalisation), the status
 * status strings. Integer only. Builds: all.
 */
#include "lt/lt_fx.h"

lt_q16_t lt_q16_sqrt(lt_q16_t x)
{
    uint64_t n;
    uint32_t r;
    LT_COST(SDIV, 1);
    if (x <= 0) {
        LT_EVENT(SAT, x < 0);
        return 0;
    }
    /* sqrt(x_raw / 2^16) * 2^16 = sqrt(x_raw * 2^16) */
    n = (uint64_t)x << 16;
    r = lt__isqrt64(n);
    /* round to nearest: (r + 1/2)^2 = r^2 + r + 1/4, so round up iff n - r^2 > r */
    if (n - (uint64_t)r * r > r)
        r++;
    return (lt_q16_t)r;
}

lt_q16_t lt_q16_rsqrt_sat(lt_q16_t x)
{
    uint64_t n;
    uint32_t s;
    unsigned k;
    LT_COST(SDIV, 2);
    if (x <= 0) {
        LT_EVENT(SAT, 1);
        return LT_Q16_MAX;
    }
    /* Normalise x_raw * 4^k into [2^60, 2^62) so the integer root s has 30-31 significant bits:
     * 1/sqrt(x) in s15.16 = 2^24 / sqrt(x_raw) = 2^(24+k) / sqrt(x_raw * 4^k). */
    k = (lt__clz64((uint64_t)x) - 2u) / 2u;
    n = (uint64_t)x << (2u * k);
    s = lt__isqrt64(n);
    /* s = floor(sqrt(n)) is low by < 1 part in 2^30; correct the quotient for that by using
     * s + 1/2 as the root estimate: 2^(25+k) / (2s + 1), rounded half up. */
    {
        uint64_t num = (uint64_t)1 << (25u + k);
        uint64_t den = 2u * (uint64_t)s + 1u;
        uint64_t q = (2u * num + den) / (2u * den);
        return q > (uint64_t)INT32_MAX ? LT_Q16_MAX : (lt_q16_t)q;
    }
}

void lt_q16_cross3_sat(const lt_q16_t a[3], const lt_q16_t b[3], lt_q16_t out[3])
{
    lt_q16_t r0, r1, r2;
    LT_COST(SMUL, 6);
    LT_COST(SALU, 3);
    /* each difference of two products is < 2^63 in magnitude, so it is exact in int64 */
    r0 = lt__round_sat32(lt__mul32x32_64(a[1], b[2]) - lt__mul32x32_64(a[2], b[1]), 16);
    r1 = lt__round_sat32(lt__mul32x32_64(a[2], b[0]) - lt__mul32x32_64(a[0], b[2]), 16);
    r2 = lt__round_sat32(lt__mul32x32_64(a[0], b[1]) - lt__mul32x32_64(a[1], b[0]), 16);
    out[0] = r0;
    out[1] = r1;
    out[2] = r2;
}

lt_status_t lt_q16_normalize3(const lt_q16_t v[3], lt_q30_t out[3])
{
    int64_t c[3];
    uint64_t m = 0, len2 = 0;
    unsigned lz, i;
    uint32_t s;
    LT_COST(SALU, 8);
    LT_COST(SMUL, 3);
    LT_COST(SDIV, 4);
    for (i = 0; i < 3; i++) {
        uint64_t a = v[i] < 0 ? (uint64_t)0 - (uint64_t)(int64_t)v[i] : (uint64_t)v[i];
        if (a > m)
            m = a;
    }
    if (m == 0)
        return LT_E_ARG;
    /* Scale up (never down: a right shift would truncate) so the largest component lies in
     * [2^30, 2^31]: normalisation is scale-free, len^2 <= 3 * 2^62 fits uint64, and the root
     * s = floor(len) has >= 30 significant bits. */
    lz = lt__clz64(m);
    for (i = 0; i < 3; i++) {
        c[i] = (int64_t)v[i];
        if (lz > 33u)
            c[i] = (int64_t)((uint64_t)c[i] << (lz - 33u));
        len2 += (uint64_t)(c[i] * c[i]);
    }
    s = lt__isqrt64(len2);
    for (i = 0; i < 3; i++) {
        /* c * 2^30 / len with len in [s, s + 1) estimated as s + 1/2: c * 2^31 / (2s + 1), half up;
         * |c| <= 2^31 keeps c * 2^31 <= 2^62 */
        int64_t n = c[i] * ((int64_t)1 << 31), d = 2 * (int64_t)s + 1;
        int64_t q = lt__divfloor64(n, d);
        /* half up from the remainder: 2n + d (as lt__div_round64 does) could overflow here */
        if (2 * (n - q * d) >= d)
            q++;
        out[i] = lt__ssat32(q);
    }
    return LT_OK;
}

const char *lt_status_str(lt_status_t s)
{
#if LT_CFG_NO_STATUS_STRINGS
    (void)s;
    return "";
#else
    switch (s) {
    case LT_OK: return "ok";
    case LT_E_ARG: return "invalid argument";
    case LT_E_RANGE: return "value outside its fixed-point format";
    case LT_E_SPACE: return "buffer too small";
    case LT_E_FORMAT: return "malformed input";
    case LT_E_DEPTH: return "stack, tree or step limit reached";
    }
    return "unknown status";
#endif
}
