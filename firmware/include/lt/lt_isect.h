/* lt_isect.h - 16-ray packets against boxes and triangles: the Kay-Kajiya slab test (Kay & Kajiya
 * 1986 [Kay86]) and the Moller-Trumbore ray/triangle test (Moller & Trumbore 1997 [Moller97]), in
 * s15.16 fixed point and in float32, both compiled from one kernel source
 * (firmware/core/object/lt_isect.inc). Also a flat "chunk" scene (boxes over runs of 16 triangles), the
 * smallest structure that exercises both kernels end to end.
 * Builds: all; float32 entry points only with LT_CFG_FLOAT32.
 */
#ifndef LT_ISECT_H
#define LT_ISECT_H

#include "lt_v16.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The ray/triangle intersector a traversal uses: a field `isect` of every structure's handle
 * (lt_bvh_t, lt_bvhq_t, lt_kd_*_t, lt_grid_*_t; the BVH's also serves the multi-frusta kernels)
 * and a parameter of lt_chunks_trace16_*. The builds set LT_ISECT_WT; set the field after the
 * build to choose Moller-Trumbore. One body per intersector (lt_tri16_wt_* / lt_tri16_*); the
 * choice is made per triangle test on a value that is constant over a trace (not charged: it
 * is loop-invariant, a compiler unswitches it). docs/watertight.md. */
#define LT_ISECT_WT 0u /* watertight (Woop, Benthin, Wald 2013; lt_wt.h): the default */
#define LT_ISECT_MT 1u /* Moller-Trumbore (lt_tri16_*): cheaper, leaks at shared edges */
/* s15.16 only: the watertight test on a grid of step 2^g (lt_tri16_wt32_q16): 32-bit edge functions,
 * watertight, t of the snapped triangle. The value carries g in bits 8..12: LT_ISECT_WT32_G(g). */
#define LT_ISECT_WT32 2u
#define LT_ISECT_WT32_G(g) (LT_ISECT_WT32 | (((uint32_t)(g) & 31u) << 8))
#define LT_ISECT_KIND(v) ((uint32_t)(v) & 0xFFu)
#define LT_ISECT_WT32_SHIFT(v) (((uint32_t)(v) >> 8) & 31u)
/* 1 if v names an intersector the build takes (for a float32 structure: WT or MT only; WT32 needs
 * LT_CFG_WT32). */
#if LT_CFG_WT32
#define LT_ISECT_VALID(v, q16)                                                                     \
    ((v) <= LT_ISECT_MT ||                                                                         \
     ((q16) && LT_ISECT_KIND(v) == LT_ISECT_WT32 && LT_ISECT_WT32_SHIFT(v) <= 13u &&               \
      ((uint32_t)(v) >> 13) == 0u))
#else
#define LT_ISECT_VALID(v, q16) ((void)(q16), (v) <= LT_ISECT_MT)
#endif

/* A packet of 16 rays in fixed point. 16 x 64 B x 11 = 704 bytes, 4-byte aligned. */
typedef struct lt_ray16_q16 {
    lt_vq16_t ox, oy, oz;   /* origin, s15.16 world units (scene-scaled, |x| <= 2^LT_CFG_GEOM_MAX_LOG2) */
    lt_vq30_t dx, dy, dz;   /* unit direction, s1.30 */
    lt_vq16_t rx, ry, rz;   /* 1/d, s15.16, from lt_ray16_q16_setup; |d| < 2^-15 saturates to +-max */
    lt_vq16_t tmin, tmax;   /* parametric interval, s15.16 (world units along the unit direction);
                               tmax < LT_Q16_MAX; a hit shortens tmax */
    lt_mask16_t par[3];     /* per axis: lanes with d == 0 (parallel to the slabs), from setup */
    lt_mask16_t rsat[3];    /* per axis: lanes with d != 0 whose 1/d saturated, from setup */
    uint16_t pad_[2];       /* private: keeps the size a multiple of 16 */
} lt_ray16_q16_t;
LT_STATIC_ASSERT(sizeof(lt_ray16_q16_t) == 11 * 64 + 16, "ray packet is 11 lane vectors + masks");

/* Axis-aligned box, 24 bytes: lo <= hi per axis (a zero-thickness box is valid). */
typedef struct lt_aabb_q16 {
    lt_q16_t lo[3]; /* s15.16 */
    lt_q16_t hi[3]; /* s15.16 */
} lt_aabb_q16_t;
LT_STATIC_ASSERT(sizeof(lt_aabb_q16_t) == 24, "aabb is 24 bytes");

/* Triangle as vertex 0 and two edges, 36 bytes (Moller-Trumbore layout). */
typedef struct lt_tri_q16 {
    lt_q16_t v0[3]; /* s15.16, |v0| <= 2^LT_CFG_GEOM_MAX_LOG2 */
    lt_q16_t e1[3]; /* v1 - v0, s15.16 */
    lt_q16_t e2[3]; /* v2 - v0, s15.16 */
} lt_tri_q16_t;
LT_STATIC_ASSERT(sizeof(lt_tri_q16_t) == 36, "triangle is 36 bytes");

/* Closest hit per lane: triangle id (-1 = none); its distance is the ray's tmax. 64 bytes. */
typedef struct lt_hit16 {
    lt_vi32_t id; /* triangle index, -1 for no hit */
} lt_hit16_t;

/* Compute rx, ry, rz = 1/d and the par/rsat masks. Format: s1.30 -> s15.16 (2^46 / d_raw).
 * Rounding: half up. Overflow: |d| < 2^-15 saturates to +-max (d == 0 gives +max) and is flagged in
 * rsat (or par for d == 0), so the slab test can treat those lanes exactly. Cost: VDIV x3, VCMP x9,
 * VBCAST x9 (per axis: the reciprocal, the d == 0 compare, lt_vq16_cmpsat). */
void lt_ray16_q16_setup(lt_ray16_q16_t *r);

/* Slab test of the lanes in k against box b. Writes the entry distance max(tmin, near planes) to
 * *tnear for hit lanes (others unchanged). A ray parallel to a slab (d == 0) meets it for all t iff
 * its origin lies in the closed slab, and never otherwise. Format: s15.16. Rounding: each t is
 * (plane - o) * (1/d) rounded half up, so a box whose true interval is shorter than the bound in
 * docs/numerics.md may be classified either way. Overflow: lanes whose 1/d saturated compute
 * t = (plane - o) / d by division instead (a rare path), so saturation keeps the classification.
 * Cost: ISECT_SLAB_LOAD (SLOAD x6), ISECT_SLAB_AXIS_FLAG x3 (MASK x3), VALU x19, VMUL x6, VCMP x1,
 * VBCAST x6; + ISECT_Q_SLAB_PAR (VCMP x2, VALU x2) per axis with parallel lanes, ISECT_Q_SLAB_RSAT
 * (VDIV x1) per axis with saturated lanes. Lane by lane (LT_LANEWISE(), lt_v16.h: the
 * Cortex-M4 and Cortex-M55 DSP builds, and the simulator modelling mcu-m4 or mcu-m55) when no lane
 * of k is flagged: ISECT_SLAB_LANES, ISECT_SLAB_LANE per lane of k (the same bits).
 * Returns: the mask of lanes in k whose ray meets the box within [tmin, tmax]. */
lt_mask16_t lt_slab16_q16(const lt_ray16_q16_t *r, lt_mask16_t k, const lt_aabb_q16_t *b,
                          lt_vq16_t *tnear);

/* Moller-Trumbore test of the lanes in k against one triangle, two-sided, edges inclusive. Lanes
 * that hit at tmin < t < tmax get tmax = t and hit->id = id. Format: products kept exact in int64
 * (q30 x q16 -> 46 bits, q16 x q16 -> 32 bits), qvec rounded to s25.6, t = num / det rounded half up
 * to s15.16. Overflow: none for inputs within LT_CFG_GEOM_MAX_LOG2. Cost: ISECT_TRI_LOAD
 * (SLOAD x9), ISECT_TRI_EARLY_OUT (MASK x1), VBCAST x17, VALU x3, VSHIFT x7, VMUL x24, VMULW x19,
 * VCMP x5 (the products of docs/numerics.md, the flip, the barycentric tests); with candidate lanes
 * + TRI_Q_TDIV16 (VDIV x1), VCMP x2, VALU x2, VBCAST x1.
 * Returns: the mask of lanes whose ray was shortened by this triangle. */
lt_mask16_t lt_tri16_q16(lt_ray16_q16_t *r, lt_mask16_t k, const lt_tri_q16_t *tri, int32_t id,
                         lt_hit16_t *hit);

/* ---- flat chunk scene: one box per run of 16 triangles -------------------------------------- */

#define LT_CHUNK_TRIS 16

/* Number of chunk boxes for n triangles. */
#define LT_CHUNK_COUNT(n) (((n) + LT_CHUNK_TRIS - 1) / LT_CHUNK_TRIS)

/* Bounds of each run of 16 triangles into boxes[LT_CHUNK_COUNT(n)]. Cost: BUILD phase,
 * ISECT_CHUNK_BOX_TRI (SALU x24, BRANCH x10) per triangle.
 * Returns: LT_OK, or LT_E_ARG for NULL pointers or n == 0. */
lt_status_t lt_chunks_build_q16(const lt_tri_q16_t *tris, uint32_t n, lt_aabb_q16_t *boxes);

/* Closest hit of a packet against a chunk scene: slab test per chunk (TRAVERSE), triangle tests of
 * the hit chunks (INTERSECT) with the intersector isect (LT_ISECT_WT or LT_ISECT_MT; another value
 * is taken as LT_ISECT_WT). hit->id is reset to -1 first. Cost: TRAVERSE VBCAST x2 per call, per
 * chunk ISECT_CHUNK_STEP, lt_slab16_q16 and MASK x1; INTERSECT per triangle of an entered chunk
 * ISECT_CHUNK_TRI and lt_tri16_q16 (MT) or lt_tri16_wt_q16 (WT; before the first one the
 * packet's lt_ray16_wt_setup_q16). Returns: mask of lanes that hit. */
lt_mask16_t lt_chunks_trace16_q16(const lt_tri_q16_t *tris, uint32_t n, const lt_aabb_q16_t *boxes,
                                  uint32_t isect, lt_ray16_q16_t *r, lt_mask16_t k,
                                  lt_hit16_t *hit);

#if LT_CFG_FLOAT32
/* The same in float32: what a Larrabee-like machine would run. 704 bytes. */
typedef struct lt_ray16_f32 {
    lt_vf32_t ox, oy, oz;   /* origin, world units */
    lt_vf32_t dx, dy, dz;   /* unit direction */
    lt_vf32_t rx, ry, rz;   /* 1/d clamped to +-FLT_MAX (never inf, so 0 * r is never NaN) */
    lt_vf32_t tmin, tmax;   /* parametric interval, tmax < FLT_MAX */
    lt_mask16_t par[3];     /* per axis: lanes with d == +-0, from setup */
    lt_mask16_t rsat[3];    /* always 0 in float32 (kept for the shared kernel source) */
    uint16_t pad_[2];       /* private */
} lt_ray16_f32_t;

typedef struct lt_aabb_f32 {
    float lo[3];
    float hi[3];
} lt_aabb_f32_t;

typedef struct lt_tri_f32 {
    float v0[3];
    float e1[3];
    float e2[3];
} lt_tri_f32_t;

/* 1/d per lane, IEEE division; d == +-0 gives +-FLT_MAX. Cost: FDIV x3, FCMP x6, VALU x3, VBCAST x3. */
void lt_ray16_f32_setup(lt_ray16_f32_t *r);
/* The float32 kernels, as the s15.16 ones. Cost: lt_slab16_f32 ISECT_SLAB_LOAD,
 * ISECT_SLAB_AXIS_FLAG x3, FADD x19, FMUL x6, FCMP x1, VBCAST x6 (+ ISECT_F_SLAB_PAR per axis with
 * parallel lanes); lt_tri16_f32 ISECT_TRI_LOAD, ISECT_TRI_EARLY_OUT, VBCAST x13, FADD x22,
 * FMUL x24, FCMP x5 (+ FDIV x1, FCMP x2, FADD x1, VALU x1, VBCAST x1 with candidate lanes); the
 * chunks as the s15.16 ones with these. */
lt_mask16_t lt_slab16_f32(const lt_ray16_f32_t *r, lt_mask16_t k, const lt_aabb_f32_t *b,
                          lt_vf32_t *tnear);
lt_mask16_t lt_tri16_f32(lt_ray16_f32_t *r, lt_mask16_t k, const lt_tri_f32_t *tri, int32_t id,
                         lt_hit16_t *hit);
lt_status_t lt_chunks_build_f32(const lt_tri_f32_t *tris, uint32_t n, lt_aabb_f32_t *boxes);
lt_mask16_t lt_chunks_trace16_f32(const lt_tri_f32_t *tris, uint32_t n, const lt_aabb_f32_t *boxes,
                                  uint32_t isect, lt_ray16_f32_t *r, lt_mask16_t k,
                                  lt_hit16_t *hit);
#endif

#ifdef __cplusplus
}
#endif
#endif /* LT_ISECT_H */
