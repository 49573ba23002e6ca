/* lt_qt_ref.h - host side of the screen-space quadtree (firmware/include/lt/lt_qt.h): depth ->
 * normalised inverse depth w = z_ref / z (holes for NaN, inf and non-positive depth), and an
 * independent double-precision reference that marches a ray pixel by pixel over the leaf planes of
 * Alg. 1 of Widmer et al. 2015 [Widmer15] with the same surface model (hit, crack, occlusion, layer
 * choice), so error figures measure the hierarchy and the fixed-point formats, never a path against
 * itself. Host only (C99 + libm, malloc). docs/quadtree.md describes the model.
 */
#ifndef LT_QT_REF_H
#define LT_QT_REF_H

#include <stddef.h>
#include <stdint.h>
#include "lt/lt_fx.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The exponent e of z_ref = 2^e: the largest power of two strictly below the smallest valid
 * (finite, > 0) depth of z[0..n), so every valid w = z_ref / z lies in (0, 1): no surface sits on
 * the reprojection's default near plane w = 1 (lt_reproj_opts_t.z_near_src = 0). Returns 0, or -1
 * when no depth is valid (then *e = 0). */
int lt_qt_zref_exp(const float *z, size_t n, int *e);

/* w = 2^zexp / z per pixel. s1.30: rounded half up in double, saturated to INT32_MAX (w >= 2);
 * float: rounded to nearest. NaN, +-inf and z <= 0 give w = 0 (a hole: background at infinity).
 * Returns the number of holes. */
size_t lt_qt_w_from_depth_q30(const float *z, size_t n, int zexp, lt_q30_t *w);
size_t lt_qt_w_from_depth_f32(const float *z, size_t n, int zexp, float *w);

/* Leaf plane of one pixel in w units: w(x, y) = c + al (x - xc) + be (y - yc) around the pixel
 * centre (xc, yc); o = discontinuity flag. 32 bytes. */
typedef struct lt_qt_ref_plane {
    double c, al, be; /* w, dw/dx, dw/dy per pixel */
    int o;            /* Laplacian >= lambda_d */
} lt_qt_ref_plane_t;

typedef struct lt_qt_ref {
    uint32_t width, height, layers;
    lt_qt_ref_plane_t *planes; /* layers x height x width, owned (lt_qt_ref_free) */
} lt_qt_ref_t;

/* Alg. 1 in double on w (layers x height x width, w units; the caller passes exactly the values
 * the core sees, e.g. raw / 2^30, so input quantisation is not counted as error). Returns 0, or -1
 * on a bad argument or allocation failure. */
int lt_qt_ref_build(lt_qt_ref_t *ref, const double *w, uint32_t width, uint32_t height,
                    uint32_t layers, double lambda_h, double lambda_d);
void lt_qt_ref_free(lt_qt_ref_t *ref);

/* Segment (x, y, w) + t (dx, dy, dw), t in [tmin, tmax] within [0, 1]; pixels and w units. */
typedef struct lt_qt_ref_ray {
    double x, y, w, dx, dy, dw, tmin, tmax;
} lt_qt_ref_ray_t;

typedef struct lt_qt_ref_hit {
    int status;  /* LT_QT_MISS, LT_QT_HIT, LT_QT_OCCLUDED (lt_qt.h) */
    double t, w; /* parameter and the ray's w there */
    int layer;   /* layer of the hit or occlusion, -1 for a miss */
    long pixels; /* pixel intervals visited over all layers */
} lt_qt_ref_hit_t;

/* March the ray over the leaf planes: the pixels it crosses in order of t (the pixel of each
 * interval between consecutive grid-line crossings is the one at its midpoint), per pixel the
 * signs of f = w_ray - w_plane at both ends; then the same layer choice as lt_qt_trace16_*. */
void lt_qt_ref_trace(const lt_qt_ref_t *ref, const lt_qt_ref_ray_t *ray, lt_qt_ref_hit_t *hit);

/* The march's parts, shared with the screen-space baselines' references (tests/unit/
 * lt_ssb_testlib.h). Clip: [*t0, *t1] = [tmin, tmax] cut to the image box per axis (half-open for
 * a parallel ray, which outside it gets *t1 = -1) and to w >= 0; empty when !(*t0 < *t1). */
void lt_qt_ref_clip(uint32_t width, uint32_t height, const lt_qt_ref_ray_t *ray, double *t0,
                    double *t1);
/* Grid-line crossing parameters in (t0, t1) plus both ends, sorted, into ts (at most cap
 * entries; 2 (width + height) + 8 hold every crossing of a clipped ray). Returns the count. */
size_t lt_qt_ref_crossings(const lt_qt_ref_ray_t *r, double t0, double t1, double *ts, size_t cap);

#ifdef __cplusplus
}
#endif
#endif /* LT_QT_REF_H */
