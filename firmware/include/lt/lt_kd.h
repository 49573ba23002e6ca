/* lt_kd.h - kd-tree over triangles: binned SAH build (Wald & Havran 2006 [Wald06]; Stamminger &
 * Grosso 2020 [Stamminger20]; Bikker 2016 [Bikker16]) into caller memory, and 16-ray packet
 * traversal with a per-lane (node, tnear, tfar) stack in near/far order, early exit only for hits
 * inside the current node's interval (the caveat of [Stamminger20]). s15.16 and float32 from one
 * kernel source (firmware/core/object/lt_kd.inc). Also the per-lane plane distance and box span helpers
 * the uniform grid (lt_grid.h) shares.
 * Builds: all; float32 entry points only with LT_CFG_FLOAT32. Layout and numbers: docs/kdtree-grid.md.
 */
#ifndef LT_KD_H
#define LT_KD_H

#include "lt_isect.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Hard limits. LT_KD_MAX_DEPTH bounds the tree depth and so the traversal stack on the C stack
 * (LT_KD_MAX_DEPTH x 136 bytes = 5440 bytes per trace call); LT_KD_MAX_TRIS keeps every SAH cost
 * product inside uint64 (see lt_kd.inc); LT_KD_BINS is the number of SAH bins per axis. */
#define LT_KD_MAX_DEPTH 40
#define LT_KD_MAX_TRIS (1u << 24)
#define LT_KD_BINS 32

/* Build parameters. All integers, so both numeric paths evaluate the SAH identically. */
typedef struct lt_kd_params {
    uint32_t leaf_tris;      /* a node with at most this many references is a leaf, >= 1; default 2 */
    uint32_t max_depth;      /* deepest node level, <= LT_KD_MAX_DEPTH; 0 = 8 + 1.3 log2(n) */
    uint32_t cost_trav;      /* SAH cost of a traversal step, 1..255; default 15 */
    uint32_t cost_isect;     /* SAH cost of a triangle test, 1..255; default 20 */
    uint32_t empty_bonus_q8; /* split cost factor when one child is empty, /256, 1..256; 205 (0.8) */
    uint32_t ref_factor;     /* budget: leaf references <= ref_factor * max(n, 1), shared out down
                                the tree in proportion to reference counts, 1..16; default 4 */
} lt_kd_params_t;

/* Node, 8 bytes, 4-byte aligned; children are allocated in pairs (left = child, right = child + 1).
 *   word 0: inner: split plane (s15.16 in lt_kd_node_q16_t, binary32 in lt_kd_node_f32_t)
 *           leaf:  index of the leaf's first reference in refs[]
 *   word 1: bits 1:0  split axis 0/1/2, or 3 = leaf
 *           bits 31:2 inner: index of the left child; leaf: number of references */
#define LT_KD_LEAF 3u
#define LT_KD_IS_LEAF(nd) (((nd)->info & 3u) == LT_KD_LEAF)
#define LT_KD_AXIS(nd) ((nd)->info & 3u)
#define LT_KD_CHILD(nd) ((nd)->info >> 2)
#define LT_KD_COUNT(nd) ((nd)->info >> 2)

typedef struct lt_kd_node_q16 {
    union {
        lt_q16_t split; /* inner: plane position, s15.16 world units */
        uint32_t first; /* leaf: first index into refs[] */
    } u;
    uint32_t info;      /* axis or leaf flag (bits 1:0), child index or count (bits 31:2) */
} lt_kd_node_q16_t;
LT_STATIC_ASSERT(sizeof(lt_kd_node_q16_t) == 8, "kd node is 8 bytes");

/* A built tree (caller-allocated; fields are read-only after the build). 64 bytes on 32-bit targets. */
typedef struct lt_kd_q16 {
    const lt_kd_node_q16_t *nodes; /* nodes[0] is the root; inside the build arena */
    const uint32_t *refs;          /* triangle indices of the leaves, right after the nodes */
    const lt_tri_q16_t *tris;      /* the caller's triangles: must outlive the tree, unchanged */
    uint32_t ntris;                /* triangles */
    uint32_t nnodes;               /* nodes used */
    uint32_t nrefs;                /* references used (sum of leaf counts) */
    uint32_t nleaves, nempty;      /* leaves, and leaves without references */
    uint32_t depth;                /* deepest leaf level (root = 0) */
    lt_aabb_q16_t bounds;          /* scene bounds (triangle vertices), s15.16 */
    size_t bytes;                  /* bytes the finished tree occupies at the arena start */
    uint32_t isect;                /* intersector of its walks: LT_ISECT_WT (set by the build) or
                                      LT_ISECT_MT (set after the build; lt_isect.h) */
} lt_kd_q16_t;

/* The default parameters above. Cost: none. */
void lt_kd_params_default(lt_kd_params_t *p);

/* Bytes the build of n triangles needs in its arena: a worst-case bound fixed by n and the
 * parameters, R = ref_factor x max(n, 1):
 *   (2R - 1) x 8 (node budget) + (R + n) x 4 (references and build scratch)
 *   + (max_depth + 2) x 48 (pending-node records).
 * The finished tree reports its exact size in kd->bytes (a two-pass caller builds once, then
 * keeps only that prefix of the arena). p may be NULL (defaults). Format: bytes. Range: n <=
 * LT_KD_MAX_TRIS. Rounding: none. Overflow: a size beyond size_t is LT_E_RANGE. Cost: none.
 * Returns: LT_OK, LT_E_ARG (NULL bytes, a parameter out of range), LT_E_RANGE. */
lt_status_t lt_kd_size(uint32_t n, const lt_kd_params_t *p, size_t *bytes);

/* Build a kd-tree over tris[0..n) in mem (4-byte aligned, *bytes long). Binned SAH
 * (LT_KD_BINS planes per axis at equal spacing over the node, triangle bounds not clipped to the
 * node); a triangle touching a plane goes to both sides. n == 0 gives a single empty leaf.
 * Nothing past the size of lt_kd_size() is written; on success the tree is compacted to the first
 * kd->bytes bytes of mem and *bytes is set to kd->bytes (the rest of mem is free again).
 * Format: s15.16 vertices with |x| <= 2^LT_CFG_GEOM_MAX_LOG2. Rounding: none (planes are exact
 * s15.16 values between node bounds). Overflow: none. Cost: BUILD phase, KD_BUILD_BOUNDS_TRI per
 * triangle, KD_BUILD_JOB per job, per job split KD_CHOOSE_BIN_REF per reference, KD_CHOOSE_SAH per
 * candidate plane and KD_BUILD_SPLIT_REF per reference, KD_MOVE_REF per reference moved (into
 * its leaf, in a split, and once more when the tree is compacted). Returns: LT_OK; LT_E_ARG (NULL, misaligned, bad parameter); LT_E_RANGE (a
 * vertex outside the geometry range, n > LT_KD_MAX_TRIS); LT_E_SPACE (*bytes too small: the
 * needed size is written back). */
lt_status_t lt_kd_build_q16(lt_kd_q16_t *kd, const lt_tri_q16_t *tris, uint32_t n,
                            const lt_kd_params_t *p, void *mem, size_t *bytes);

/* Closest hit of the lanes in k. hit->id is reset to -1 on all lanes; lanes that hit get the
 * original triangle index and r->tmax = its distance. Lanes of a packet may point anywhere: each
 * lane keeps its own [tnear, tfar] per node; the packet visits the child that most lanes needing
 * both see first, and lanes seeing it out of order may not stop early in that subtree.
 * Format: t per plane = (plane - o) x (1/d) in s15.16, rounded half up; saturated-reciprocal lanes
 * divide exactly; parallel lanes go to the side of their origin. Range: rays from
 * lt_ray16_q16_setup, tmax < LT_Q16_MAX; any origin, inside or outside the tree. Rounding: a hit within the plane
 * rounding bound (docs/numerics.md slab bound) of a split plane may be passed over in favour of
 * one equally close. Overflow: none. Cost: NODES per node visited (TRAVERSE), the tree's intersector per
 * leaf reference (INTERSECT: lt_tri16_wt_q16 with lt_ray16_wt_setup_q16 before the first, or
 * lt_tri16_q16), LT_MEM per node and leaf reference block; the KD_WALK_* recipes,
 * lt__kd_span16_q16 and lt__kd_tplane16_q16 with their lane ops (not checked by
 * tests/unit/test_costs.c).
 * Returns: the mask of lanes that hit. */
lt_mask16_t lt_kd_trace16_q16(const lt_kd_q16_t *kd, lt_ray16_q16_t *r, lt_mask16_t k,
                              lt_hit16_t *hit);

/* Any hit with tmin < t < tmax for the lanes in k (shadow rays): a lane stops at its first hit,
 * in any node order. r->tmax of occluded lanes is shortened to that hit. Format, Range, Rounding,
 * Overflow, Cost: as lt_kd_trace16_q16. Returns: the mask of occluded lanes. */
lt_mask16_t lt_kd_occluded16_q16(const lt_kd_q16_t *kd, lt_ray16_q16_t *r, lt_mask16_t k);

/* ---- internal, shared with lt_grid.c ------------------------------------------------------- */

/* Per-lane distance to the plane x_axis = plane.l[i]: (plane - o) x (1/d), half up, saturating;
 * lanes in k with a saturated 1/d divide exactly; parallel lanes give LT_Q16_MAX (never crossed).
 * Cost: VALU x2, VMUL x1, VBCAST, (VDIV if flagged lanes). */
lt_vq16_t lt__kd_tplane16_q16(const lt_ray16_q16_t *r, unsigned axis, lt_vq16_t plane,
                              lt_mask16_t k);

/* [tnear, tfar] of the lanes in k inside box b, clipped to [tmin, tmax]; parallel lanes pass a
 * slab iff lo <= o <= hi. Returns: lanes with tnear <= tfar (closed: a flat box can be hit). */
lt_mask16_t lt__kd_span16_q16(const lt_ray16_q16_t *r, lt_mask16_t k, const lt_aabb_q16_t *b,
                              lt_vq16_t *tnear, lt_vq16_t *tfar);

#if LT_CFG_FLOAT32
typedef struct lt_kd_node_f32 {
    union {
        float split;    /* inner: plane position, world units */
        uint32_t first; /* leaf: first index into refs[] */
    } u;
    uint32_t info;      /* as lt_kd_node_q16_t */
} lt_kd_node_f32_t;
LT_STATIC_ASSERT(sizeof(lt_kd_node_f32_t) == 8, "kd node is 8 bytes");

typedef struct lt_kd_f32 {
    const lt_kd_node_f32_t *nodes;
    const uint32_t *refs;
    const lt_tri_f32_t *tris;
    uint32_t ntris, nnodes, nrefs, nleaves, nempty, depth;
    lt_aabb_f32_t bounds;
    size_t bytes;
    uint32_t isect; /* as lt_kd_q16_t */
} lt_kd_f32_t;

/* The float32 twins: same contracts; vertices must be finite (else LT_E_RANGE). */
lt_status_t lt_kd_build_f32(lt_kd_f32_t *kd, const lt_tri_f32_t *tris, uint32_t n,
                            const lt_kd_params_t *p, void *mem, size_t *bytes);
lt_mask16_t lt_kd_trace16_f32(const lt_kd_f32_t *kd, lt_ray16_f32_t *r, lt_mask16_t k,
                              lt_hit16_t *hit);
lt_mask16_t lt_kd_occluded16_f32(const lt_kd_f32_t *kd, lt_ray16_f32_t *r, lt_mask16_t k);
lt_vf32_t lt__kd_tplane16_f32(const lt_ray16_f32_t *r, unsigned axis, lt_vf32_t plane,
                              lt_mask16_t k);
lt_mask16_t lt__kd_span16_f32(const lt_ray16_f32_t *r, lt_mask16_t k, const lt_aabb_f32_t *b,
                              lt_vf32_t *tnear, lt_vf32_t *tfar);
#endif

#ifdef __cplusplus
}
#endif
#endif /* LT_KD_H */
