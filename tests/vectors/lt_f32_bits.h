/* lt_f32_bits.h - float inputs for the instruction-count loops without float arithmetic: the
 * float nearest to v * 2^-frac (round to nearest even) built from integer operations only, so
 * that on a soft-float target (rv32, -mabi=ilp32) the input generation calls no libgcc float helper whose
 * count would mix with the measured kernel's (tests/bench/opcal.sh counts every call of a helper).
 * For an int32 v, bit-identical to (float)v * 2^-frac (one rounding, then an exact scaling).
 * Freestanding.
 */
#ifndef LT_F32_BITS_H
#define LT_F32_BITS_H

#include <stdint.h>
#include "lt/lt_port.h"

/* v * 2^-frac as float. Format: int64 with frac fraction bits (16: s15.16, 30: s1.30) -> binary32.
 * Range: |v| < 2^62, frac <= 62 (normal results only). Rounding: to nearest, ties to even.
 * Overflow: none in range. Cost: none (test input). */
LT_INLINE float lt_loop_f32_from_fx(int64_t v, unsigned frac)
{
    union {
        uint32_t u;
        float f;
    } r;
    uint64_t m = v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
    uint32_t sign = v < 0 ? 0x80000000u : 0u;
    unsigned p;
    if (m == 0) {
        r.u = 0;
        return r.f;
    }
    p = 63u - lt__clz64(m); /* value = 1.f * 2^(p - frac) */
    if (p > 23u) {
        unsigned sh = p - 23u;
        uint64_t rem = m & (((uint64_t)1 << sh) - 1u), half = (uint64_t)1 << (sh - 1u);
        m >>= sh;
        if (rem > half || (rem == half && (m & 1u) != 0))
            m++;
        if (m == ((uint64_t)1 << 24)) { /* the rounding carried into a new bit */
            m >>= 1;
            p++;
        }
    } else {
        m <<= 23u - p;
    }
    r.u = sign | ((uint32_t)(p + 127u - frac) << 23) | ((uint32_t)m & 0x7FFFFFu);
    return r.f;
}

#endif /* LT_F32_BITS_H */
