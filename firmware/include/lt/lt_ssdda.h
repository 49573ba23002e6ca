/* lt_ssdda.h - baseline 1 for the screen-space quadtree (lt_qt.h): the perspective-correct linear
 * screen-space DDA of McGuire & Mara ("Efficient GPU Screen-Space Ray Tracing", JCGT 3(4), 2014):
 * one pixel per step along the major axis, inverse depth interpolated linearly in screen space,
 * a hit when the ray's inverse-depth interval over the step overlaps a pixel's surface shell of
 * relative thickness theta, tested in every depth layer. It reads the caller's w = z_ref / z
 * buffer (the input of lt_qt_build_*) directly and takes and returns the quadtree's ray and result
 * packets (lt_qray16_*, lt_qhit16_*), so the same rays give comparable answers. One kernel source
 * (firmware/core/screen/lt_ssdda.inc) for s1.30 and float32. docs/ss-baselines.md is the reference.
 * Builds: all; the float32 entry points only with LT_CFG_FLOAT32.
 */
#ifndef LT_SSDDA_H
#define LT_SSDDA_H

#include <stddef.h>
#include <stdint.h>
#include "lt_qt.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- shared by both screen-space baselines (lt_hiz.h includes this header) ------------------- */

#define LT_SSB_MAX_DIM LT_QT_MAX_DIM       /* width, height <= 16384 pixels */
#define LT_SSB_MAX_LAYERS LT_QT_MAX_LAYERS /* depth layers <= 64 */

/* Numeric path of a DDA or Hi-Z object (the w buffer's type). */
typedef enum lt_ssb_enc {
    LT_SSB_Q30 = 0, /* lt_q30_t w, s1.30 compute (int64 products) */
    LT_SSB_F32 = 1  /* float w, binary32 compute (LT_CFG_FLOAT32) */
} lt_ssb_enc_t;

/* flags: the ray goes on behind the deepest layer's shell instead of stopping there. 0 (default)
 * stops it with LT_QT_OCCLUDED, as lt_qt does (unknown beyond); LT_SSB_CONTINUE_BEHIND is the
 * original DDA of McGuire & Mara (a ray that passes behind a thick-enough object continues and
 * may hit what lies further on; never LT_QT_OCCLUDED). */
#define LT_SSB_CONTINUE_BEHIND 1u

/* Surface model shared by the DDA and the Hi-Z tracer, 8 bytes. Pixel (i, j) of layer l with
 * w_s > 0 is a fronto-parallel shell from its depth z_s back to z_s (1 + theta), i.e.
 *   w in [w_s / (1 + theta), w_s]          (w = z_ref / z),
 * McGuire & Mara's depth-buffer "thickness" as a *relative* depth: an absolute camera-space
 * thickness dz at depth z is theta = dz / z. Relative, because in w a constant relative thickness
 * is one multiply (w_s k, k = 1 / (1 + theta), computed once) and scale-free, as the quadtree's
 * gamma_dist is. w_s <= 0 (holes: NaN/inf/0 depth) is background at infinity: never hit. */
typedef struct lt_ssb_params {
    lt_q30_t thickness; /* theta, relative depth, s1.30 in [0, 2): default 2^-6 (1.6%) */
    uint32_t flags;     /* 0 or LT_SSB_CONTINUE_BEHIND */
} lt_ssb_params_t;
LT_STATIC_ASSERT(sizeof(lt_ssb_params_t) == 8, "screen-space baseline params are 8 bytes");

/* Fill p with the defaults above. Cost: none. */
void lt_ssb_params_default(lt_ssb_params_t *p);

/* What to trace: image size, layers, numeric path. 16 bytes. */
typedef struct lt_ssb_desc {
    uint32_t width;  /* pixels, 1..LT_SSB_MAX_DIM */
    uint32_t height; /* pixels, 1..LT_SSB_MAX_DIM */
    uint32_t layers; /* depth layers, 1..LT_SSB_MAX_LAYERS (layer l+1 lies behind layer l) */
    uint32_t enc;    /* lt_ssb_enc_t */
} lt_ssb_desc_t;

/* ---- the DDA --------------------------------------------------------------------------------- */

/* A DDA over the caller's w buffer (layers x height x width, layer-major, row-major; it must stay
 * valid while the object is used). Caller-allocated, no other memory: fields read-only. */
typedef struct lt_ssdda {
    uint32_t width, height, layers; /* pixels, layers */
    uint32_t enc;                   /* lt_ssb_enc_t */
    lt_ssb_params_t params;          /* as given */
    lt_q30_t kq;                    /* 1 / (1 + theta), s1.30, half up (the q30 path) */
#if LT_CFG_FLOAT32
    float kf;                       /* 1 / (1 + theta), binary32 (the float32 path) */
#endif
    const void *w;                  /* private: the caller's buffer */
} lt_ssdda_t;

/* Set up a DDA on an s1.30 w buffer (d->enc == LT_SSB_Q30). p NULL = defaults. w = z_ref / z,
 * negative raws are holes. Format: s1.30; kq = 2^60 / (2^30 + theta). Range: theta in [0, 2).
 * Rounding: kq half up. Overflow: none. Cost: none.
 * Returns: LT_OK or LT_E_ARG (NULL, bad descriptor, thickness < 0, unknown flags). */
lt_status_t lt_ssdda_init_q30(lt_ssdda_t *dda, const lt_ssb_desc_t *d, const lt_ssb_params_t *p,
                              const lt_q30_t *w);

/* The step bound used for max_steps = 0: max(width, height) + 2, so that no clipped segment is cut
 * short by default (a step covers one pixel of the major axis). Cost: none. */
uint32_t lt_ssdda_default_steps(const lt_ssdda_t *dda);

/* Trace the lanes in k. Per lane, the clipped segment (as lt_qt_trace16_q30: image box, w >= 0,
 * [tmin, tmax]) is walked in steps of one pixel along its major axis (|dx| >= |dy|: x), step i
 * covering t in [t0 + (2i - 1) h, t0 + (2i + 1) h] (h = 1 / (2 |d_major|), clipped to the segment)
 * and sampling the pixel under the ray at t0 + 2 i h (McGuire & Mara's P0 + i dP; pixels the
 * minor axis crosses between samples are not visited). The ray's w interval over the step,
 * [min, max] of w(t) at its ends (w is linear in t: the perspective-correct interpolation), is
 * compared with every layer's shell; the earliest overlap is a HIT in that layer at the first t
 * inside the shell; otherwise, if the ray lies entirely behind the shell of the deepest layer
 * (w_s > 0 there), OCCLUDED at the step's start (unless LT_SSB_CONTINUE_BEHIND). MISS at the end
 * of the segment, UNKNOWN after max_steps steps (0 = lt_ssdda_default_steps), BADRAY as lt_qt.
 * hit->nodes = pixels visited (steps), planes = pixel tests (= steps), aabb = 0.
 * Format: s1.30 t and w, s15.16 pixels; step ends t0 + (2i + 1) 2^15 / |d| by the normalised
 * reciprocal (error <= 1 ulp, monotonic in i); w(t) and the shell products exact in int64 (s1.60).
 * Range: as lt_qt_trace16_q30. Rounding: hit t half up. Overflow: none within the ranges.
 * Cost (notation of lt_qt_trace16_q30): VBCAST x6 in the caller's phase. SETUP: lt__ssb_setup_q30
 * (the clip of lt_qt_trace16_q30 and SSB_Q_MAJOR) and DDA_POINT_LANES. TRAVERSE per call:
 * SSB_Q_W_AT, I x9, V x4, VBCAST x8; per packet step: DDA_WALK_STEP, DDA_WALK_END, DDA_INDEX,
 * 2 SSB_Q_TSPAN, 2 SSB_Q_PIXEL, 2 SSB_Q_WRAY, I x8, VCMP x1, VBCAST x5, V x7, VC x1, W x2; per
 * layer of a step: LANE_GATHER per active lane (LT_MEM at each pixel's address),
 * SSB_Q_PIX_HOLES, SSB_Q_SHELL_LO, SSB_Q_SHELL_HI, DDA_WALK_LAYER, VC x1, VBCAST x1, WC x2 (the
 * deepest: x3); a layer whose shell the step meets: DDA_WALK_LAYER_HIT, WC x2, VC x1, V x1, I x1,
 * VBCAST x1 (+ W x6 and SSB_Q_HIT_T when the ray enters the shell inside the step); hit lanes:
 * V x1, I x1; lanes behind the deepest shell: V x1, I x1, VBCAST x1; DDA_WALK_OVER when lanes
 * reach max_steps. Events RAYS, NODES (per packet step); lane ops charge utilisation.
 * Returns: LT_OK, or LT_E_ARG (NULL, or not an s1.30 DDA). */
lt_status_t lt_ssdda_trace16_q30(const lt_ssdda_t *dda, const lt_qray16_q30_t *r, lt_mask16_t k,
                                 uint32_t max_steps, lt_qhit16_q30_t *hit);

#if LT_CFG_FLOAT32
/* float32 twin of lt_ssdda_init_q30 (d->enc == LT_SSB_F32): w as float; NaN, +-inf, <= 0 holes.
 * Format: binary32, kf = 1 / (1 + theta). Range, Overflow: as the q30 twin. Rounding: nearest
 * even. Cost: none. Returns: as lt_ssdda_init_q30. */
lt_status_t lt_ssdda_init_f32(lt_ssdda_t *dda, const lt_ssb_desc_t *d, const lt_ssb_params_t *p,
                              const float *w);

/* float32 twin of lt_ssdda_trace16_q30: step ends t0 + (2i + 1) (0.5 / |d|), w(t) = w + t dw,
 * shells w_s (1 / (1 + theta)) in binary32. Format: binary32, no contraction. Rounding: nearest
 * even. Cost: as the q30 path with float ops (V FADD, VC FCMP, W FADD, WC FCMP) and the float32
 * routines of lt_ssb.h (SSB_F_*; SSB_F_WRAY for w at t; the shell's upper bound costs nothing).
 * Returns: LT_OK or LT_E_ARG. */
lt_status_t lt_ssdda_trace16_f32(const lt_ssdda_t *dda, const lt_qray16_f32_t *r, lt_mask16_t k,
                                 uint32_t max_steps, lt_qhit16_f32_t *hit);
#endif

#ifdef __cplusplus
}
#endif
#endif /* LT_SSDDA_H */
