/* lt_qt.h - the adaptive screen-space acceleration structure of Widmer et al. 2015 [Widmer15]: a
 * quadtree over each of N layers of an inverse-depth buffer whose nodes are planes or min/max-w
 * boxes, built bottom-up (Alg. 1 leaves, Alg. 2 merges) and traversed by 16-ray packets in screen
 * space (Alg. 3 descent/plane/box tests, Alg. 4 next node + findMSB level jump) with the
 * occlusion-aware choice across layers. Depth is stored as normalised inverse depth w = z_ref / z,
 * because a world plane is a plane and a world ray a straight line in (x_s, y_s, w).
 * Three node formats come from one kernel source (firmware/core/screen/lt_qt.inc): 64-bit and 32-bit
 * fixed-point nodes (s1.30 compute) and 16-byte float32 nodes. docs/quadtree.md is the reference.
 * Builds: all; the float32 entry points only with LT_CFG_FLOAT32.
 */
#ifndef LT_QT_H
#define LT_QT_H

#include <stddef.h>
#include <stdint.h>
#include "lt_v16.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- limits ------------------------------------------------------------------------------------ */

#define LT_QT_MAX_DIM_LOG2 14                      /* width, height <= 16384 pixels */
#define LT_QT_MAX_DIM (1u << LT_QT_MAX_DIM_LOG2)
#define LT_QT_MAX_LEVELS (LT_QT_MAX_DIM_LOG2 + 1)  /* level 0 = pixels ... root */
#define LT_QT_MAX_LAYERS 64u
/* Ray end points must satisfy |x|, |y| <= 2^LT_QT_RAY_MAX_LOG2 pixels (s15.16 differences fit). */
#define LT_QT_RAY_MAX_LOG2 14

/* ---- node formats ---------------------------------------------------------------------------- */
/* Node (L, qx, qy) covers pixels [qx 2^L, (qx+1) 2^L) x [qy 2^L, (qy+1) 2^L) (clipped to the
 * image); pixel (i, j) covers [i, i+1) x [j, j+1) with its sample at the centre. A plane node holds
 *   w(x, y) = C + Al u + Be v,  u = (x - xc) / 2^L, v = (y - yc) / 2^L in [-1/2, 1/2],
 * (xc, yc) the centre of the unclipped node: C is w at the centre, Al and Be the change of w across
 * the node's width and height. w is the normalised inverse depth in s1.30 raw units.
 * An AABB node holds wmin <= w <= wmax of every plane below it over its footprint.
 * O (discontinuity) marks planes whose 3x3 neighbourhood had a Laplacian >= lambda_d (Alg. 1) or
 * that merged such a plane (Alg. 2). */

/* 64-bit node, 8 bytes, 4-byte aligned: two words (no bit-field, so the layout is the same on
 * every compiler). Plane:
 *   hi[31] = 0 (plane), hi[30] = O, hi[29:15] = A, hi[14:0] = B (15-bit two's complement),
 *   lo[31:8] = Cm (24 bits, unsigned), lo[7:3] = Es (5 bits), lo[2:0] = Ec (3 bits);
 *   C = Cm * 2^Ec, Al = A * 2^Es, Be = B * 2^Es (s1.30 raw; C >= 0).
 *   C keeps 24 significant bits (as float32 does), the slopes 14 to 15.
 * AABB: hi[31] = 1, hi[30:0] = wmax (u1.30, rounded up), lo[31] = 0, lo[30:0] = wmin (rounded down).
 */
typedef struct lt_qt_n64 {
    uint32_t lo; /* plane: Cm, Es, Ec; AABB: wmin, u1.30 */
    uint32_t hi; /* plane: type, O, A, B; AABB: type, wmax u1.30 */
} lt_qt_n64_t;
LT_STATIC_ASSERT(sizeof(lt_qt_n64_t) == 8, "64-bit quadtree node is 8 bytes");
#define LT_QT_N64_IS_AABB(n) (((n).hi >> 31) != 0u)
#define LT_QT_N64_O(n) (((n).hi >> 30) & 1u)

/* 32-bit node, 4 bytes. Plane: [31] = 0, [30] = O, [29:25] = E (5 bits), [24:13] = Cm (12 bits,
 * unsigned), [12] = K, [11:6] = A (6-bit two's complement), [5:0] = B (6-bit);
 *   C = Cm * 2^E, Al = A * 2^(E + 3K), Be = B * 2^(E + 3K) (s1.30 raw; C >= 0).
 * AABB: [31] = 1, [30:16] = wmax, [15] = 0, [14:0] = wmin, each a 15-bit unsigned minifloat
 *   (5-bit exponent e, 10-bit mantissa m): raw = m for e = 0, (1024 + m) * 2^(e - 1) otherwise;
 *   wmin rounded down, wmax rounded up (relative step 2^-10). */
typedef struct lt_qt_n32 {
    uint32_t v; /* see above */
} lt_qt_n32_t;
LT_STATIC_ASSERT(sizeof(lt_qt_n32_t) == 4, "32-bit quadtree node is 4 bytes");
#define LT_QT_N32_IS_AABB(n) (((n).v >> 31) != 0u)
#define LT_QT_N32_O(n) (((n).v >> 30) & 1u)

#if LT_CFG_FLOAT32
/* float32 node, 16 bytes: plane (c, al, be) as above in w units (not raw); AABB: c = wmin,
 * al = wmax, be = 0. flags bit 31 = AABB, bit 30 = O. */
typedef struct lt_qt_nf32 {
    float c;        /* plane: w at the centre; AABB: wmin */
    float al;       /* plane: w change across the width; AABB: wmax */
    float be;       /* plane: w change across the height; AABB: 0 */
    uint32_t flags; /* bit 31 AABB, bit 30 O */
} lt_qt_nf32_t;
LT_STATIC_ASSERT(sizeof(lt_qt_nf32_t) == 16, "float32 quadtree node is 16 bytes");
#define LT_QT_NF32_IS_AABB(n) (((n).flags >> 31) != 0u)
#define LT_QT_NF32_O(n) (((n).flags >> 30) & 1u)
#endif

typedef enum lt_qt_enc {
    LT_QT_N64 = 0, /* lt_qt_n64_t, s1.30 compute */
    LT_QT_N32 = 1, /* lt_qt_n32_t, s1.30 compute */
    LT_QT_F32 = 2  /* lt_qt_nf32_t, float32 compute (LT_CFG_FLOAT32) */
} lt_qt_enc_t;

/* ---- parameters ------------------------------------------------------------------------------ */

/* Build thresholds in s1.30 (w = z_ref / z, so 1.0 = the reference depth). lambda_h, lambda_d
 * are absolute w differences per pixel, as the supplement's are in its normalised depth buffer;
 * gamma_dist is relative. 16 bytes. Defaults (lt_qt_params_default): lambda_h = lambda_d = 1e-3
 * (the supplement's values), gamma_norm = 1e-3, gamma_dist = 2^-17 (7.6e-6 relative). */
typedef struct lt_qt_params {
    lt_q30_t lambda_h;   /* |dw/dpixel| above this is zeroed (a jump, not a slope), s1.30 >= 0 */
    lt_q30_t lambda_d;   /* |Lx| + |Ly| (second differences) >= this flags a discontinuity O */
    lt_q30_t gamma_norm; /* merge only if 1 - cos(angle) between proxy and child normals, measured
                            as |slope difference|^2 / 2 in screen units of the pyramid size, is
                            below this; s1.30 in [0, 1] */
    lt_q30_t gamma_dist; /* merge only if the proxy stays within gamma_dist * w of each child
                            over the child's footprint (w its smallest value: a relative depth
                            error) plus the encoding errors of both, s1.30 >= 0 */
} lt_qt_params_t;
LT_STATIC_ASSERT(sizeof(lt_qt_params_t) == 16, "quadtree params are 16 bytes");

/* Fill p with the defaults above. Cost: none. */
void lt_qt_params_default(lt_qt_params_t *p);

/* What to build: image size, layers and node format. 16 bytes. */
typedef struct lt_qt_desc {
    uint32_t width;  /* pixels, 1..LT_QT_MAX_DIM */
    uint32_t height; /* pixels, 1..LT_QT_MAX_DIM */
    uint32_t layers; /* depth layers, 1..LT_QT_MAX_LAYERS (layer k+1 lies behind layer k) */
    uint32_t enc;    /* lt_qt_enc_t */
} lt_qt_desc_t;

/* A built quadtree: caller-allocated, fields read-only after lt_qt_build_*. Nodes of layer k,
 * level L, at (qx, qy) are at index k * layer_nodes + off[L] + qy * nx[L] + qx of the arena. */
typedef struct lt_qt {
    uint32_t width, height;            /* pixels */
    uint32_t layers;                   /* depth layers */
    uint32_t levels;                   /* n: level 0 = pixels, level n - 1 = the 1x1 root */
    uint32_t enc;                      /* lt_qt_enc_t */
    uint32_t node_bytes;               /* 8, 4 or 16 */
    uint32_t layer_nodes;              /* nodes per layer */
    uint32_t nx[LT_QT_MAX_LEVELS];     /* nodes per row at each level: ceil(width / 2^L) */
    uint32_t ny[LT_QT_MAX_LEVELS];     /* rows at each level: ceil(height / 2^L) */
    uint32_t off[LT_QT_MAX_LEVELS];    /* first node of each level within a layer */
    lt_qt_params_t params;             /* thresholds used by the build */
    void *nodes;                       /* private: the caller's arena */
} lt_qt_t;

/* Arena bytes for a quadtree: layers * sum over levels of ceil(w/2^L) ceil(h/2^L) * node size.
 * Format: integer. Cost: none.
 * Returns: LT_OK, LT_E_ARG (NULL, zero or oversized dimension, bad layers or enc, F32 without
 * LT_CFG_FLOAT32) or LT_E_RANGE (the size does not fit size_t). */
lt_status_t lt_qt_size(const lt_qt_desc_t *d, size_t *bytes);

/* Build from layers x height x width inverse depths w (layer-major, row-major), d->enc N64 or N32.
 * w = z_ref / z in s1.30; holes (background, NaN/inf/0 depth) are w = 0, and so are negative raws.
 * The arena (4-byte aligned) receives exactly lt_qt_size() bytes; nothing past them is written.
 * Format: s1.30 in, s1.30 compute (int64 for products), nodes as documented above.
 * Range: w in [0, 2^31) raw. Rounding: proxies exact to 2^-6 raw, stored half up; AABB bounds
 * outward. Overflow: none (differences saturate).
 * Cost (phase BUILD; recipes of lt_recipes.def and lane ops by class, in the notation of
 * docs/cost-model.md: V the s1.30 lanes (VALU), VC their compares (VCMP), W the build values:
 * add, sub, blend or abs VMULW, a shift VSHIFT, x3 VMULW x2, from V VCVT): per layer VBCAST x3;
 * per leaf pass (16 pixels of a row): QT_LEAVES_PASS, QT_Q_LOADPIX x3 (+1 per neighbouring row),
 * V x23, VC x5, VCVT x3 and the encoder: n64 QT_N64_ENC_PLANE + QT_N64_ENC_TRY per slope shift
 * retried, n32 QT_N32_ENC_PLANE + QT_N32_ENC_TRY per exponent tried; per merge pass (16 parents
 * of level L >= 1): QT_MERGE_PASS, VBCAST x8, four decodes with bounds (LANE_GATHER per present
 * child's lane, QT_N64_DECODE + QT_N64_DECODE_BOUNDS; n32 QT_N32_*); parents whose children are
 * all planes: QT_MERGE_PROXY, W: 20 adds and 12 from V (the sums), 8 add/blend, 10 shifts, one x3
 * (means, x slope, offset), the y slope 3 add/blend, 2 shifts, one x3 (two child rows; one row:
 * 1 add, 2 shifts), the encoder, a decode without bounds (LANE_GATHER per encoded lane), 4 W from
 * V; per child position QT_MERGE_CHILD, per present child QT_MERGE_CHILD_TESTS, W: 12 add/abs,
 * 7 shifts, 4 from V, QT_Q_RELTOL, QT_Q_ANGLE_OK, VCMP x1; the planes kept QT_COPY_LINE x2 (n32
 * x1); the other parents as AABBs: V x12 and QT_N64_ENC_AABB (n32 QT_N32_ENC_AABB).
 * Returns: LT_OK; LT_E_ARG (NULL, misaligned arena, bad desc/params); LT_E_SPACE when *arena_bytes
 * is too small (the needed size is written back to *arena_bytes, the arena is untouched). */
lt_status_t lt_qt_build_q30(lt_qt_t *qt, const lt_qt_desc_t *d, const lt_qt_params_t *p,
                            const lt_q30_t *w, void *arena, size_t *arena_bytes);

/* ---- rays and results ------------------------------------------------------------------------ */

/* Per-lane result codes (lt_qhit16_*.status). */
#define LT_QT_MISS 0     /* left the screen, the segment or reached w = 0 without a hit */
#define LT_QT_HIT 1      /* hit a surface of layer `layer` at t */
#define LT_QT_OCCLUDED 2 /* went behind the deepest layer at t before any hit: unknown beyond */
#define LT_QT_UNKNOWN 3  /* the step bound was reached; t = where the lane stopped */
#define LT_QT_BADRAY 4   /* end points outside |x|,|y| <= 2^14 px, w < 0 or t range invalid */

/* 16 screen-space segments P(t) = (x, y, w) + t (dx, dy, dw), t in [tmin, tmax] within [0, 1]:
 * the direction is given per unit step, one step being the whole segment (a caller reprojecting a
 * camera ray computes both end points in (x_s, y_s, w)). 512 bytes. */
typedef struct lt_qray16_q30 {
    lt_vq16_t x, y;       /* start, s15.16 pixels */
    lt_vq30_t w;          /* start inverse depth, s1.30 (z_ref / z), >= 0 */
    lt_vq16_t dx, dy;     /* end - start, s15.16 pixels */
    lt_vq30_t dw;         /* end - start inverse depth, s1.30 */
    lt_vq30_t tmin, tmax; /* s1.30 fractions of the step, 0 <= tmin <= tmax <= 1 */
} lt_qray16_q30_t;
LT_STATIC_ASSERT(sizeof(lt_qray16_q30_t) == 8 * 64, "q30 screen-space packet is 512 bytes");

/* Per-lane results. 7 x 64 = 448 bytes. Lanes outside the trace mask are not written. */
typedef struct lt_qhit16_q30 {
    lt_vi32_t status; /* LT_QT_* */
    lt_vq30_t t;      /* HIT: hit parameter; OCCLUDED: first t behind the deepest layer; s1.30 */
    lt_vq30_t w;      /* the ray's inverse depth at t, s1.30 */
    lt_vi32_t layer;  /* layer of the hit or occlusion */
    lt_vi32_t nodes;  /* nodes visited (all layers) */
    lt_vi32_t aabb;   /* ray-AABB tests */
    lt_vi32_t planes; /* ray-plane tests */
} lt_qhit16_q30_t;

/* Trace the lanes in k through every layer (Alg. 3 per layer; layer k+1 only for lanes that went
 * behind layer k before hitting it, over that part of the segment). max_steps bounds the nodes a
 * lane may visit per layer (0 = lt_qt_default_steps(qt)); a lane that reaches it stops with
 * LT_QT_UNKNOWN. Format: s1.30 t and w, s15.16 pixels; node crossings t = (X - x) / dx by a
 * normalised 32-bit reciprocal (error <= 1 ulp, monotonic), plane tests exact in int64 at s1.60.
 * Range: see LT_QT_BADRAY. Rounding: t of a hit half up (<= 1 ulp + the plane's own error).
 * Overflow: none within the ranges.
 * Cost (docs/cost-model.md notation: I int32 lanes VALU, V the t and w lanes VALU, VC their
 * compares VCMP, W and WC the s1.60 values along the ray VMULW and VCMP): VBCAST x1 in the caller's
 * phase. SETUP: lt__ssb_clip_q30 = SSB_Q_CLIP, 4 SSB_Q_TCROSS, I x4, V x8, VC x1, VBCAST x8.
 * TRAVERSE per call: SSB_Q_W_AT, I x11, V x3, VBCAST x6; per layer traced: QT_TRACE_LAYER, I x10,
 * V x5, VBCAST x13 (the deepest: I x12, V x6, VBCAST x14); per node visit: QT_WALK_STEP,
 * QT_WALK_NODE, QTGRID_INDEX, LANE_GATHER per active lane, QT_N64_DECODE (n32: QT_N32_DECODE),
 * 2 SSB_Q_TCROSS, I x4, VSHIFT x2, VCMP x2, VBCAST x1, V x5, VC x1; with plane lanes:
 * 2 QT_Q_PLANE_F, QT_WALK_PLANES, WC x2, VBCAST x2, I x1, V x2 (+ SSB_Q_HIT_T and V x1 with
 * crossing lanes); with box lanes: 2 SSB_Q_WRAY, QT_WALK_BOXES, W x2, VCVT x2, WC x6, I x1 (+
 * SSB_Q_HIT_T, W x6, V x3, VBCAST x1 with lanes entering the box); with descending lanes: I x14,
 * VSHIFT x2 and per axis lt__ssb_child_side_q30 (SSB_Q_TCROSS and VC x2 for moving lanes,
 * SSB_Q_SIDE_PAR for parallel ones); with advancing lanes: QTGRID_OUTSIDE, QT_WALK_ADVANCE, VC x2,
 * I x12, V x2, VSHIFT x2, VBCAST x1; QT_WALK_OVER when lanes reach max_steps. Events: RAYS, NODES
 * (per packet step), AABB / AABB_RAYS; lane ops charge utilisation.
 * Returns: LT_OK, or LT_E_ARG (NULL or an unbuilt / float quadtree). */
lt_status_t lt_qt_trace16_q30(const lt_qt_t *qt, const lt_qray16_q30_t *r, lt_mask16_t k,
                              uint32_t max_steps, lt_qhit16_q30_t *hit);

/* The walk of lt_qt_trace16_q30 one ray at a time: each lane of k is traced alone in scalar C
 * through the same lane bodies (crossings, plane functions, hit parameter, child side, clip) and
 * the same states and steps, so every field of its hit record equals lt_qt_trace16_q30's bit for
 * bit (tests/unit/test_qt.c checks this on real depth images). For cores without wide SIMD
 * (Cortex-M4, RV32), where a packet step costs all 16 lanes' work however few are active and the
 * 64-bit lane vectors are copied whole: the firmware reprojection uses it there
 * (docs/firmware.md). Format, range, rounding, overflow: as lt_qt_trace16_q30.
 * Cost (scalar recipes of lt_recipes.def, per lane of k): QT1_SETUP and QT1_FINISH (SETUP:
 * QT1_SETUP, and for a valid ray QT1_WLIM when dw < 0 and per axis it moves along QT1_RCP and 2
 * QT1_CROSS; the rest TRAVERSE); per layer traced QT1_LAYER; per node visit QT1_STEP, plus
 * QT1_PLANE at a plane node, QT1_BOX at an AABB node, QT1_HIT_T per crossing or box entry,
 * QT1_DESCEND per descent, QT1_ADVANCE per step to a neighbour and QT1_CROSS per node-edge or
 * midline crossing not among the last two of its axis (a per-axis cache). Events: RAYS per lane, NODES
 * per visit, AABB / AABB_RAYS per box. Returns: LT_OK, or LT_E_ARG (NULL or an unbuilt / float
 * quadtree). */
lt_status_t lt_qt_trace1_q30(const lt_qt_t *qt, const lt_qray16_q30_t *r, lt_mask16_t k,
                             uint32_t max_steps, lt_qhit16_q30_t *hit);

/* The default step bound per layer: 8 (width + height) + 4 levels + 16. Cost: none. */
uint32_t lt_qt_default_steps(const lt_qt_t *qt);

#if LT_CFG_FLOAT32
/* float32 path: the same structure with lt_qt_nf32_t nodes (d->enc == LT_QT_F32), w = z_ref / z
 * as float; NaN, +-inf and negative values are holes (w = 0). Format: IEEE binary32, no
 * contraction. Range: any float. Rounding: to nearest even. Overflow: none for w < 2.
 * Cost: as lt_qt_build_q30 with float ops (V FADD, VC FCMP; W add/blend/abs FADD, a shift VBCAST
 * + FMUL, x3 FMUL, from V nothing): QT_F_LOADPIX, every encode QT_F_STORE_ROW, decodes
 * LANE_GATHER x2 per lane + QT_F_DECODE (+ QT_F_DECODE_BOUNDS), per present child FMUL x3,
 * FADD x2, FCMP x2, VBCAST x2 in place of QT_Q_RELTOL, QT_Q_ANGLE_OK and the VCMP, the planes
 * kept QT_COPY_LINE x4. Returns: as lt_qt_build_q30. */
lt_status_t lt_qt_build_f32(lt_qt_t *qt, const lt_qt_desc_t *d, const lt_qt_params_t *p,
                            const float *w, void *arena, size_t *arena_bytes);

/* float32 segments, as lt_qray16_q30_t (pixels, w units, t in [0, 1]). 512 bytes. */
typedef struct lt_qray16_f32 {
    lt_vf32_t x, y;       /* start, pixels */
    lt_vf32_t w;          /* start inverse depth */
    lt_vf32_t dx, dy;     /* end - start, pixels */
    lt_vf32_t dw;         /* end - start inverse depth */
    lt_vf32_t tmin, tmax; /* 0 <= tmin <= tmax <= 1 */
} lt_qray16_f32_t;

/* float32 results, as lt_qhit16_q30_t. 448 bytes. */
typedef struct lt_qhit16_f32 {
    lt_vi32_t status;
    lt_vf32_t t;
    lt_vf32_t w;
    lt_vi32_t layer;
    lt_vi32_t nodes;
    lt_vi32_t aabb;
    lt_vi32_t planes;
} lt_qhit16_f32_t;

/* The traversal of lt_qt_trace16_q30 in float32: crossings (X - x) * (1 / dx) (monotonic in X),
 * plane tests f(t) in float. Format: binary32. Range: as lt_qt_trace16_q30 (BADRAY also for NaN
 * or infinite inputs). Rounding: to nearest even. Overflow: none. Cost: as lt_qt_trace16_q30 with
 * float ops (V FADD, VC FCMP, W FADD, WC FCMP; no VCVT) and the float32 routines:
 * lt__ssb_clip_f32 (SSB_F_CLIP, SSB_F_TCROSS), SSB_F_WRAY for w at t and along the ray,
 * QT_F_DECODE with LANE_GATHER x2 per lane, QT_F_PLANE_F, QT_F_HIT_T at crossings and box entries,
 * SSB_F_SIDE_PAR; events as lt_qt_trace16_q30. Returns: LT_OK, or LT_E_ARG (NULL or not a float32
 * quadtree). */
lt_status_t lt_qt_trace16_f32(const lt_qt_t *qt, const lt_qray16_f32_t *r, lt_mask16_t k,
                              uint32_t max_steps, lt_qhit16_f32_t *hit);
#endif

#ifdef __cplusplus
}
#endif
#endif /* LT_QT_H */
