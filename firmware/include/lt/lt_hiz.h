/* lt_hiz.h - baseline 2 for the screen-space quadtree (lt_qt.h): a hierarchical-Z tracer over
 * min/max inverse-depth mip pyramids, one per depth layer (Uludag, "Hi-Z Screen-Space Cone-Traced
 * Reflections", GPU Pro 5, 2014; AMD FidelityFX SSSR's hierarchical ray march): the ray walks cells
 * of the pyramid, stepping to the cell boundary and going up one level where no surface shell of
 * the cell can meet it, going down one level (at the point where it can first meet one) where one
 * can, and testing single pixels at level 0 with the surface model of lt_ssdda.h. Level 0 is the
 * caller's w = z_ref / z buffer itself; the levels above are built into a caller-allocated arena.
 * Same ray and result packets as lt_qt (lt_qray16_*, lt_qhit16_*). One kernel source
 * (firmware/core/screen/lt_hiz.inc) for s1.30 and float32. docs/ss-baselines.md is the reference.
 * Builds: all; the float32 entry points only with LT_CFG_FLOAT32.
 */
#ifndef LT_HIZ_H
#define LT_HIZ_H

#include <stddef.h>
#include <stdint.h>
#include "lt_ssdda.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LT_HIZ_MAX_LEVELS LT_QT_MAX_LEVELS /* level 0 = pixels ... the 1x1 top */

/* A pyramid cell (L >= 1, qx, qy) covers pixels [qx 2^L, (qx+1) 2^L) x [qy 2^L, (qy+1) 2^L)
 * clipped to the image (as the quadtree's nodes) and holds the min and max of w over its valid
 * pixels (w > 0); a cell without valid pixels holds wmin = the format's maximum, wmax = 0, which
 * no ray interval overlaps. 8 bytes, 4-byte aligned. */
typedef struct lt_hiz_cell_q30 {
    lt_q30_t wmin; /* s1.30, smallest valid w (INT32_MAX if none) */
    lt_q30_t wmax; /* s1.30, largest w (0 if none) */
} lt_hiz_cell_q30_t;
LT_STATIC_ASSERT(sizeof(lt_hiz_cell_q30_t) == 8, "s1.30 Hi-Z cell is 8 bytes");

#if LT_CFG_FLOAT32
typedef struct lt_hiz_cell_f32 {
    float wmin; /* smallest valid w (FLT_MAX if none) */
    float wmax; /* largest w (0 if none) */
} lt_hiz_cell_f32_t;
LT_STATIC_ASSERT(sizeof(lt_hiz_cell_f32_t) == 8, "float32 Hi-Z cell is 8 bytes");
#endif

/* A built pyramid: caller-allocated, fields read-only after lt_hiz_build_*. The cell of layer l,
 * level L >= 1, at (qx, qy) is cell l * layer_cells + off[L] + qy * nx[L] + qx of the arena;
 * level 0 is the w buffer (pixel l * width * height + y * width + x), which must stay valid. */
typedef struct lt_hiz {
    uint32_t width, height;        /* pixels */
    uint32_t layers;               /* depth layers */
    uint32_t levels;               /* n = 1 + ceil(log2(max(width, height))): 0 .. n - 1 */
    uint32_t enc;                  /* lt_ssb_enc_t */
    uint32_t layer_cells;          /* cells per layer over levels 1 .. n - 1 */
    uint32_t nx[LT_HIZ_MAX_LEVELS]; /* cells per row at each level: ceil(width / 2^L) */
    uint32_t ny[LT_HIZ_MAX_LEVELS]; /* rows at each level: ceil(height / 2^L) */
    uint32_t off[LT_HIZ_MAX_LEVELS]; /* first cell of level L >= 1 within a layer (off[0] = 0) */
    lt_ssb_params_t params;         /* surface model */
    lt_q30_t kq;                   /* 1 / (1 + theta), s1.30 */
#if LT_CFG_FLOAT32
    float kf;                      /* 1 / (1 + theta), binary32 */
#endif
    const void *w;                 /* private: level 0, the caller's w buffer */
    void *cells;                   /* private: the caller's arena */
} lt_hiz_t;

/* Arena bytes: layers * 8 * sum over L = 1 .. n - 1 of ceil(w / 2^L) ceil(h / 2^L) (0 for 1x1).
 * Format: integer. Cost: none.
 * Returns: LT_OK, LT_E_ARG (NULL, zero or oversized dimension, bad layers or enc, F32 without
 * LT_CFG_FLOAT32) or LT_E_RANGE (the size does not fit size_t). */
lt_status_t lt_hiz_size(const lt_ssb_desc_t *d, size_t *bytes);

/* Build the min/max levels of an s1.30 w buffer (layers x height x width; d->enc == LT_SSB_Q30).
 * p NULL = defaults. The arena (4-byte aligned; may be NULL when the size is 0) receives exactly
 * lt_hiz_size() bytes; nothing past them is written. Level L from level L - 1, 16 parents of a
 * row per pass: min over the valid children, max over all.
 * Format: s1.30, exact (min/max). Range: any raw; negative raws are holes. Overflow: none.
 * Cost (phase BUILD; docs/cost-model.md notation, V the s1.30 lanes VALU): none for a 1x1 image;
 * per pass of 16 parents of level L >= 1: HIZ_LEVEL_PASS, VBCAST x2, HIZ_STORE_CELL and per child
 * row HIZ_LOAD_PIX2 + HIZ_Q_PIX_TEST (L = 1) or HIZ_LOAD_CELL2 (L > 1), V x4.
 * Returns: LT_OK; LT_E_ARG (NULL, misaligned arena, bad desc/params); LT_E_SPACE when *arena_bytes
 * is too small (the needed size is written back, the arena untouched). */
lt_status_t lt_hiz_build_q30(lt_hiz_t *hz, const lt_ssb_desc_t *d, const lt_ssb_params_t *p,
                             const lt_q30_t *w, void *arena, size_t *arena_bytes);

/* Default cell-visit bound per lane: 8 (width + height) + 4 levels + 16 (as lt_qt's).
 * Cost: none. */
uint32_t lt_hiz_default_steps(const lt_hiz_t *hz);

/* Trace the lanes in k. Start at level 0 in the pixel holding the ray at t0 (after the clip of
 * lt_qt_trace16_q30). Per visited cell, [tn, tf] is the ray's range inside it (tn = where it
 * entered, tf = the first exit crossing or the segment's end) and [wlo, whi] its w over it.
 *   level 0 (a pixel): the surface model of lt_ssdda.h on [tn, tf]: an overlap with a layer's shell
 *     is a HIT (earliest t over the layers); else entirely behind the deepest layer's shell is
 *     OCCLUDED at tn (unless LT_SSB_CONTINUE_BEHIND); else step on.
 *   level L > 0: the cell may hold a hit if [wlo, whi] overlaps [wmin k, wmax] of some layer, an
 *     occlusion if wlo < wmax k of the deepest layer; then go down one level at the first t where
 *     w(t) enters the hull of those ranges (moved back 4 ulps), into the child holding the ray;
 *   otherwise (or after a level-0 pass) step across the exit edge (both at a corner) and go up one
 *     level (FidelityFX's mip + 1 / mip - 1 walk).
 * MISS at the segment's end; UNKNOWN after max_steps cell visits (0 = lt_hiz_default_steps).
 * hit->nodes = cells visited (= texel lookups per layer), aabb = cell tests at L > 0 (a ray-box
 * test in (x, y, w)), planes = pixel tests at level 0.
 * Format: s1.30 t and w, s15.16 pixels; crossings by the normalised reciprocal (error <= 1 ulp,
 * monotonic), w(t) and shell products exact in int64 (s1.60). Range: as lt_qt_trace16_q30.
 * Rounding: hit t half up. Overflow: none within the ranges.
 * Cost (notation of lt_qt_trace16_q30): VBCAST x5 in the caller's phase. SETUP: lt__ssb_setup_q30
 * (the clip of lt_qt_trace16_q30 and SSB_Q_MAJOR), I x4, VBCAST x2, and per axis the start pixel:
 * SSB_Q_PIXEL, I x2, VBCAST x2 (+ 2 SSB_Q_TCROSS, I x5, VBCAST x3, VC x4 when a lane moves on the
 * axis). TRAVERSE per call: SSB_Q_W_AT, I x9, V x4, VBCAST x7; per cell visit: HIZ_WALK_STEP,
 * HIZ_WALK_CELL, QTGRID_INDEX, 2 SSB_Q_TCROSS, 2 SSB_Q_WRAY, I x6, VSHIFT x2, VCMP x2, VBCAST x3,
 * V x4, VC x1, W x2; per layer of a visit: HIZ_WALK_LAYER, VBCAST x2, SSB_Q_SHELL_LO,
 * SSB_Q_SHELL_HI, WC x2 (the deepest: x3), with pixel lanes LANE_GATHER per lane,
 * SSB_Q_PIX_HOLES, VC x1, VBCAST x1, with cell lanes LANE_GATHER per lane, HIZ_GATHER_SPLIT, V x2,
 * VC x1, the deepest layer with cell lanes (unless LT_SSB_CONTINUE_BEHIND) SSB_Q_SHELL_LO, WC x1,
 * W x4, VBCAST x1; pixel lanes inside a shell: HIZ_WALK_PIXEL_HIT, WC x2, VC x1, V x1, I x1,
 * VBCAST x1 (+ W x6 and SSB_Q_HIT_T when the ray enters the shell inside the pixel); cell lanes
 * inside a hull: W x4; hit lanes: V x1, I x1; occluded lanes: V x1, I x1, VBCAST x1; descending
 * lanes: HIZ_WALK_DESCEND, WC x2, I x14, VSHIFT x2, per axis lt__ssb_child_side_q30 (SSB_Q_TCROSS
 * and VC x2 for moving lanes, SSB_Q_SIDE_PAR for parallel ones) (+ W x6, SSB_Q_HIT_T, V x3,
 * VBCAST x1 when the ray enters the hull inside the cell); advancing lanes: QTGRID_OUTSIDE,
 * HIZ_WALK_ADVANCE, VC x2, VCMP x1, I x7, VSHIFT x2, V x1; HIZ_WALK_OVER when lanes reach
 * max_steps. Events RAYS, NODES (per packet step), AABB / AABB_RAYS (cell tests at L > 0).
 * Returns: LT_OK, or LT_E_ARG (NULL, or not an s1.30 pyramid). */
lt_status_t lt_hiz_trace16_q30(const lt_hiz_t *hz, const lt_qray16_q30_t *r, lt_mask16_t k,
                               uint32_t max_steps, lt_qhit16_q30_t *hit);

#if LT_CFG_FLOAT32
/* float32 twins (d->enc == LT_SSB_F32; NaN, +-inf and w <= 0 are holes). Format: binary32, no
 * contraction. Rounding: nearest even. Cost: as the q30 functions with float ops (V FADD, VC
 * FCMP, W FADD, WC FCMP), HIZ_F_PIX_TEST, and the float32 routines of lt_ssb.h (SSB_F_*; SSB_F_WRAY
 * for w at t; the shell's upper bound costs nothing).
 * Returns: as the q30 functions. */
lt_status_t lt_hiz_build_f32(lt_hiz_t *hz, const lt_ssb_desc_t *d, const lt_ssb_params_t *p,
                             const float *w, void *arena, size_t *arena_bytes);
lt_status_t lt_hiz_trace16_f32(const lt_hiz_t *hz, const lt_qray16_f32_t *r, lt_mask16_t k,
                               uint32_t max_steps, lt_qhit16_f32_t *hit);
#endif

#ifdef __cplusplus
}
#endif
#endif /* LT_HIZ_H */
