/* lt_qmc.h - integer quasi-Monte Carlo point sets for area-light sampling (Benthin & Wald 2009
 * [Benthin09], section 4.5; Kollig & Keller 2002 [Kollig02]): the van der Corput radical inverse in
 * base 2 (bit reversal), the Larcher-Pillichshammer radical inverse, the 2D Hammersley and
 * Larcher-Pillichshammer point sets of 2^m points, and the 4x4 interleaved split of a 256-point set
 * into 16 sets of 16 (one set per pixel of a 4x4 block). All values are 0.32 or 0.8 binary
 * fractions computed with bit operations, so they are exact in every build.
 * Builds: all (integer only).
 */
#ifndef LT_QMC_H
#define LT_QMC_H

#include <stddef.h>
#include <stdint.h>
#include "lt_status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LT_QMC_SETS 16     /* interleaved sets: one per pixel of a 4x4 block */
#define LT_QMC_SET_SIZE 16 /* samples per set */
#define LT_QMC_MAX_LOG2N 32u

typedef enum lt_qmc_kind {
    LT_QMC_HAMMERSLEY = 0, /* (i / n, van der Corput(i)) */
    LT_QMC_LP = 1          /* (i / n, Larcher-Pillichshammer(i)) */
} lt_qmc_kind_t;

/* Van der Corput radical inverse in base 2: the bits of i mirrored about the binary point.
 * Format: uint32 index -> 0.32 fraction (value = result / 2^32). Range: any i. Rounding: exact
 * (a permutation of bits). Overflow: none. Cost: none charged (set-up code, once per frame). */
uint32_t lt_qmc_vdc(uint32_t i);

/* Larcher-Pillichshammer radical inverse: bit 31 - b of the result is the parity of i >> b (the
 * generator matrix with all ones on and above the diagonal; Kollig & Keller 2002).
 * Format: uint32 -> 0.32 fraction. Range: any i. Rounding: exact. Overflow: none. Cost: none. */
uint32_t lt_qmc_lp(uint32_t i);

/* Point i of the 2^log2n-point 2D set of `kind`: *u = i / 2^log2n, *v = the radical inverse of i,
 * both 0.32 fractions. Format: 0.32. Range: log2n 0..32, i < 2^log2n. Rounding: exact.
 * Overflow: none. Cost: none. Returns: LT_OK, LT_E_ARG (NULL output, unknown kind, log2n > 32 or
 * i out of range; outputs untouched). */
lt_status_t lt_qmc_point(lt_qmc_kind_t kind, uint32_t i, unsigned log2n, uint32_t *u, uint32_t *v);

/* 16 sets of 16 samples, 512 bytes: sample j of set s lies at ((u[s][j] + 1/2) / 256,
 * (v[s][j] + 1/2) / 256), i.e. at the centre of its cell of the 256 x 256 grid. */
typedef struct lt_qmc_sets {
    uint8_t u[LT_QMC_SETS][LT_QMC_SET_SIZE]; /* 0.8 fraction (cell index) */
    uint8_t v[LT_QMC_SETS][LT_QMC_SET_SIZE]; /* 0.8 fraction (cell index) */
} lt_qmc_sets_t;

/* 4x4 interleaved sampling (Keller & Heidrich 2001): the 256-point set of `kind`, digitally
 * shifted (u ^= scramble & 0xFF, v ^= (scramble >> 8) & 0xFF, which keeps the (0,8,2)-net
 * property), split so that set s holds, for each a in 0..15, the one point whose top four u bits
 * are a and whose top four v bits are rev4(a ^ s); sample j = a. Every set is then a (0,4,2)-net
 * in its top four bits (one point per u and per v stratum of 1/16, one per elementary box of
 * area 1/16), and the union of the 16 sets is the whole 256-point set.
 * Format: 0.8 cell indices. Range: any scramble (bits 16..31 ignored). Rounding: exact.
 * Overflow: none. Cost: none. Returns: LT_OK, LT_E_ARG (NULL out, unknown kind). */
lt_status_t lt_qmc_interleave4x4(lt_qmc_kind_t kind, uint32_t scramble, lt_qmc_sets_t *out);

#ifdef __cplusplus
}
#endif
#endif /* LT_QMC_H */
