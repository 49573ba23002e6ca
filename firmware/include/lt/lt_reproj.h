/* lt_reproj.h - reprojection ray generation for screen-space view synthesis (Widmer et al. 2015
 * [Widmer15], section 5; docs/quadtree.md section 1): a pinhole target camera's pixel ray, seen by
 * the pinhole source camera that took a depth image, is a straight segment in the source's
 * (x_s, y_s, w = z_ref / z) space. A projective mapping precomputed once per camera pair gives, per
 * 4x4 target tile, the 16 clipped segments that lt_qt_trace16_q30 / _f32 take.
 * Builds: all. The s1.30 path is integer only; lt_reproj_setup (double) and the float32 path need
 * LT_CFG_FLOAT32. docs/reproject.md is the reference.
 */
#ifndef LT_REPROJ_H
#define LT_REPROJ_H

#include <stddef.h>
#include <stdint.h>
#include "lt_qt.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the precomputed mapping ----------------------------------------------------------------- */
/* A target pixel (u, v) (centre (u + 1/2, v + 1/2)) and its ray, parameterised by the target's
 * inverse depth q = 1 / z_t, map to the homogeneous source point
 *   P(q) = (X, Y, W, H) = (K_s R_rel K_t^-1 p + q K_s t_rel, z_ref q)   (x_s = X/H, y_s = Y/H,
 *   w = W/H), p = (u + 1/2, v + 1/2, 1): affine in p for each fixed q.
 * The near end (q = 1 / z_near_dst, or the target camera centre) is Pa = ma g, the far end
 * (q = 0, the vanishing point, w = 0) is Pb = mb g; the segment between them is clipped to
 * x_s in [0, src_w], y_s in [0, src_h], w in [w_far, w_near] and H > 0.
 *
 * s1.30 format: the input vector is g = (2u + 1, 2v + 1, 2^(dst_log2 + 1)) (exact integers, so
 * g / 2^(dst_log2 + 1) is the pixel centre in units of the target image's power-of-two size), the
 * outputs are (X / 2^src_log2, Y / 2^src_log2, W, H): every row has the same magnitude on
 * screen. Each matrix is scaled by its own power of two so that its largest entry lies in
 * [2^29, 2^30] (a homogeneous matrix may be scaled freely); entries are int32 mantissas with that
 * implicit common scale, rounded half away from zero by the setup, so P = m g is exact in int64
 * (|P| < 3 * 2^30 * 2^15 < 2^47). 128 bytes, 4-byte aligned. */
typedef struct lt_reproj_q30 {
    int32_t ma[4][3];   /* near end: rows X/2^src_log2, Y/2^src_log2, W, H; columns g0, g1, g2 */
    int32_t mb[4][3];   /* far end, same layout (its W row is 0 for the point at infinity) */
    uint32_t src_w;     /* source image width, pixels, 1..LT_QT_MAX_DIM (screen clip) */
    uint32_t src_h;     /* source image height, pixels */
    uint32_t dst_w;     /* target image width, pixels, 1..LT_QT_MAX_DIM (lanes off it cleared) */
    uint32_t dst_h;     /* target image height, pixels */
    uint32_t src_log2;  /* smallest s with src_w, src_h <= 2^s, 0..LT_QT_MAX_DIM_LOG2 */
    uint32_t dst_log2;  /* smallest s with dst_w, dst_h <= 2^s, 0..LT_QT_MAX_DIM_LOG2 */
    lt_q30_t w_near;    /* clip w <= w_near = z_ref / z_near_src, s1.30 in (0, 2) */
    lt_q30_t w_far;     /* clip w >= w_far = z_ref / z_far_src (0 = to infinity), s1.30 >= 0 */
} lt_reproj_q30_t;
LT_STATIC_ASSERT(sizeof(lt_reproj_q30_t) == 128, "s1.30 reprojection mapping is 128 bytes");

/* The 16 segments of the 4x4 target tile whose top-left pixel is (tx, ty); lane = (y - ty) * 4 +
 * (x - tx), pixel centres. *k: on entry the lanes wanted (0xFFFF for all), on return those with a
 * non-empty segment: lanes off the target image or empty after clipping to the near plane, the
 * far w, H > 0 and the source screen are cleared. Every lane of *r is written (cleared lanes with
 * zeros). Segment of a kept lane: (x, y, w) the near end, (dx, dy, dw) to the far end (w
 * decreases, unless the ray heads toward the source camera), tmin = 0, tmax = 1; both ends satisfy 0 <= x <= src_w, 0 <= y <= src_h,
 * w_far <= w <= w_near (so |x|, |y| <= 2^LT_QT_RAY_MAX_LOG2 and 0 <= w < 2 for lt_qt_trace16_q30).
 * Format: int32 mantissas x int g -> int64 homogeneous P (exact); clip parameters s1.30 (int64
 * division, rounded inward, s in [0, 1]); end points P(s) = Pa + floor((Pb - Pa) s) in int64, then
 * x = X 2^(src_log2 + 16) / H -> s15.16 and w = W 2^30 / H -> s1.30 (rounded half up).
 * Range: the mapping as lt_reproj_setup makes it; tx < dst_w, ty < dst_h need not hold (lanes
 * off the image are cleared). Rounding: end points to nearest (<= 1/2 ulp plus 2^-30 of the
 * homogeneous segment along the line from the clip parameter). Overflow: none for valid mappings
 * (clip products < 2^63); degenerate lanes (rays through the source camera centre) are cleared.
 * Cost: phase SETUP, charged per packet as a straight-line 16-lane program: RPJ_Q30_PACKET (VMUL
 * 48, VMULW 58, VDIV 12, VCMP 21, VALU 45, VSHIFT 22, MASK 8, BRANCH 1) and RPJ_STORE_RAYS
 * (VSTORE 8); docs/reproject.md.
 * Returns: LT_OK; LT_E_ARG (NULL pointer, dimensions or log2 sizes out of range, w_near outside
 * (0, 2) or w_far outside [0, w_near)). */
lt_status_t lt_reproj_rays16_q30(const lt_reproj_q30_t *m, uint32_t tx, uint32_t ty,
                                 lt_qray16_q30_t *r, lt_mask16_t *k);

#if LT_CFG_FLOAT32
/* float32 mapping: the same matrices in plain units: g = (u + 1/2, v + 1/2, 1), outputs
 * (X, Y, W, H) with x_s = X / H in pixels, w = W / H. 120 bytes. */
typedef struct lt_reproj_f32 {
    float ma[4][3];  /* near end, rows X, Y, W, H */
    float mb[4][3];  /* far end */
    uint32_t src_w, src_h; /* source image, pixels */
    uint32_t dst_w, dst_h; /* target image, pixels */
    float w_near;    /* clip w <= w_near, (0, 2) */
    float w_far;     /* clip w >= w_far, [0, w_near) */
} lt_reproj_f32_t;
LT_STATIC_ASSERT(sizeof(lt_reproj_f32_t) == 120, "float32 reprojection mapping is 120 bytes");

/* float32 twin of lt_reproj_rays16_q30 (same lanes, clipping and *k contract), in binary32:
 * P = m g, clip parameters s = da / (da - db), end points Pa + s (Pb - Pa), x = X / H, w = W / H.
 * Format: IEEE binary32, no contraction. Range: as lt_reproj_setup makes it. Rounding: to nearest
 * even per operation. Overflow: none for valid mappings; lanes with a non-finite end point are
 * cleared. Cost: phase SETUP, per packet RPJ_F32_PACKET (FMUL 44, FADD 48, FDIV 12, FCMP 21,
 * VALU 19, MASK 8, BRANCH 1) and RPJ_STORE_RAYS (VSTORE 8).
 * Returns: LT_OK; LT_E_ARG (NULL, bad dimensions, w_near / w_far out of range or not finite). */
lt_status_t lt_reproj_rays16_f32(const lt_reproj_f32_t *m, uint32_t tx, uint32_t ty,
                                 lt_qray16_f32_t *r, lt_mask16_t *k);

/* ---- setup from camera parameters (double: LT_CFG_FLOAT32 builds only) ----------------------- */

/* A pinhole camera: x right, y down, z forward (the OpenCV convention); camera coordinates
 * Xc = R (Xw - c); pixel = (fx Xc/Zc + cx, fy Yc/Zc + cy) in continuous pixel coordinates, where
 * pixel (i, j) covers [i, i+1) x [j, j+1) (so a centred principal point is cx = width / 2).
 * 136 bytes (8-byte aligned). */
typedef struct lt_reproj_cam {
    double fx, fy;   /* focal lengths, pixels, > 0 */
    double cx, cy;   /* principal point, pixels */
    double r[3][3];  /* world-to-camera rotation, rows = camera x, y, z axes in world units */
    double c[3];     /* camera centre, world units */
    uint32_t width;  /* image width, pixels, 1..LT_QT_MAX_DIM */
    uint32_t height; /* image height, pixels */
} lt_reproj_cam_t;

/* Depth parameters of the segment. 32 bytes. */
typedef struct lt_reproj_opts {
    double z_ref;      /* the quadtree's reference depth (w = z_ref / z), world units, > 0 */
    double z_near_src; /* source near plane (clip w <= z_ref / z_near_src); 0 = z_ref (w <= 1) */
    double z_far_src;  /* source far plane (clip w >= z_ref / z_far_src); 0 = infinity (w >= 0) */
    double z_near_dst; /* target near plane: the ray starts at z_t = z_near_dst; 0 = at the
                          target camera centre */
} lt_reproj_opts_t;

/* Precompute the mapping from target camera dst to source camera src (the depth image's).
 * Fills *mq (s1.30) and/or *mf (float32); either may be NULL. Runs wherever double does (host;
 * on MCUs through the soft-double helpers); the s1.30 result is bit-identical on every IEEE-754
 * double target (no libm, no contraction), and tests/vectors/reproj64.h stores one for
 * LT_CFG_FLOAT32 = 0 firmware. Format: double in, s1.30 mantissas (rounded half away from zero) and
 * float32 (rounded to nearest) out. Range: |entries| as above; rotation rows orthonormal within
 * 1e-6. Rounding: as stated. Overflow: none (entries are normalised). Cost: none (host setup).
 * Returns: LT_OK; LT_E_ARG (NULL, non-finite value, fx or fy <= 0, a rotation that is not
 * orthonormal (singular), z_ref <= 0, negative planes, a dimension 0 or > LT_QT_MAX_DIM);
 * LT_E_RANGE (w_near = z_ref / z_near_src >= 2, w_far >= w_near, or an all-zero mapping). */
lt_status_t lt_reproj_setup(const lt_reproj_cam_t *src, const lt_reproj_cam_t *dst,
                            const lt_reproj_opts_t *o, lt_reproj_q30_t *mq, lt_reproj_f32_t *mf);
#endif

#ifdef __cplusplus
}
#endif
#endif /* LT_REPROJ_H */
