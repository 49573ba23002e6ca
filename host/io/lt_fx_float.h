/* lt_fx_float.h - host-only conversions between double and the fixed-point formats of lt_fx.h.
 * value = raw / 2^frac. double -> fixed rounds half up (floor(x * 2^frac + 1/2), the core's rule)
 * and saturates to the storage range; NaN converts to 0 (also reported by the _chk forms).
 * fixed -> double is exact for every format (all raws fit the 53-bit significand).
 * Never included by firmware: the core stays integer only. Builds: host, tests (C99 + <math.h>).
 */
#ifndef LT_FX_FLOAT_H
#define LT_FX_FLOAT_H

#include <math.h>
#include <stdint.h>
#include "lt/lt_fx.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Round x * 2^frac half up and clamp to [lo, hi]; *sat (if not NULL) is set to 1 when the value
 * was clamped or NaN, else 0. x * 2^frac is exact (a power-of-two scale of a finite double within
 * range), and so is the + 1/2, because the clamp is tested first and |x * 2^frac| < 2^52. */
static inline int64_t lt__fxf_from_double(double x, int frac, int64_t lo, int64_t hi, int *sat)
{
    /* x * 2^frac by a product with the exact power of two (0 <= frac <= 62): the same double as
       ldexp (both exact, or both inf), without a library call per conversion */
    double v = x * (double)((int64_t)1 << frac);
    int s = 0;
    int64_t r;
    if (v != v) {
        s = 1;
        r = 0;
    } else if (v >= (double)hi + 0.5) {
        s = 1;
        r = hi;
    } else if (v < (double)lo - 0.5) {
        s = 1;
        r = lo;
    } else {
        r = (int64_t)floor(v + 0.5);
    }
    if (sat != NULL)
        *sat = s;
    return r;
}

/* double -> s15.16, half up, saturating: [-32768, 32768 - 2^-16]. */
static inline lt_q16_t lt_q16_from_double_sat(double x)
{
    return (lt_q16_t)lt__fxf_from_double(x, 16, INT32_MIN, INT32_MAX, NULL);
}

/* double -> s1.30, half up, saturating: [-2, 2 - 2^-30]. */
static inline lt_q30_t lt_q30_from_double_sat(double x)
{
    return (lt_q30_t)lt__fxf_from_double(x, 30, INT32_MIN, INT32_MAX, NULL);
}

/* double -> s7.8, half up, saturating: [-128, 128 - 2^-8]. */
static inline lt_h8_t lt_h8_from_double_sat(double x)
{
    return (lt_h8_t)lt__fxf_from_double(x, 8, INT16_MIN, INT16_MAX, NULL);
}

/* double -> s1.14, half up, saturating: [-2, 2 - 2^-14]. */
static inline lt_h14_t lt_h14_from_double_sat(double x)
{
    return (lt_h14_t)lt__fxf_from_double(x, 14, INT16_MIN, INT16_MAX, NULL);
}

/* Checked forms for loaders: the saturated value goes to *out, and the status says whether it was
 * exact-range. Returns: LT_OK, or LT_E_RANGE when x was outside the format (or NaN). */
static inline lt_status_t lt_q16_from_double_chk(double x, lt_q16_t *out)
{
    int s;
    *out = (lt_q16_t)lt__fxf_from_double(x, 16, INT32_MIN, INT32_MAX, &s);
    return s ? LT_E_RANGE : LT_OK;
}

static inline lt_status_t lt_q30_from_double_chk(double x, lt_q30_t *out)
{
    int s;
    *out = (lt_q30_t)lt__fxf_from_double(x, 30, INT32_MIN, INT32_MAX, &s);
    return s ? LT_E_RANGE : LT_OK;
}

/* fixed -> double, exact. */
static inline double lt_q16_to_double(lt_q16_t x) { return ldexp((double)x, -16); }
static inline double lt_q30_to_double(lt_q30_t x) { return ldexp((double)x, -30); }
static inline double lt_h8_to_double(lt_h8_t x) { return ldexp((double)x, -8); }
static inline double lt_h14_to_double(lt_h14_t x) { return ldexp((double)x, -14); }

/* s31.32 -> double: rounded to nearest even by the conversion when |raw| >= 2^53. */
static inline double lt_ql32_to_double(lt_ql32_t x) { return ldexp((double)x, -32); }

/* float conveniences (the float32 path's scalar type); float -> double is exact. */
static inline lt_q16_t lt_q16_from_float_sat(float x) { return lt_q16_from_double_sat((double)x); }
static inline lt_q30_t lt_q30_from_float_sat(float x) { return lt_q30_from_double_sat((double)x); }
static inline float lt_q16_to_float(lt_q16_t x) { return (float)lt_q16_to_double(x); }
static inline float lt_q30_to_float(lt_q30_t x) { return (float)lt_q30_to_double(x); }

#ifdef __cplusplus
}
#endif
#endif /* LT_FX_FLOAT_H */
