/* lt_bvh.h - bounding volume hierarchy over triangles: a binned SAH builder (Wald 2007 [Wald07]),
 * 32-byte nodes with a primitive index array (Bikker 2016 [Bikker16]), ordered traversal of 16-ray
 * packets with a (node, mask) stack (Benthin & Wald 2009 [Benthin09], Appendix A) and of single
 * rays, in s15.16 and float32 from one source (firmware/core/object/lt_bvh.inc); plus a quantised 16-byte
 * node variant (s15.16 only). Freestanding: the caller hands in one arena sized by lt_bvh_size().
 * See docs/bvh.md.
 * Builds: all; float32 entry points only with LT_CFG_FLOAT32.
 */
#ifndef LT_BVH_H
#define LT_BVH_H

#include "lt_isect.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- limits and build parameters ------------------------------------------------------------ */

#define LT_BVH_MAX_BINS 32      /* SAH bins per axis */
#define LT_BVH_MAX_DEPTH 64     /* tree depth limit, and the size of every traversal stack */
#define LT_BVH_MAX_LEAF 64      /* largest allowed max_leaf */
#define LT_BVH_MAX_TRIS (1u << 27) /* node indices (2n) and byte counts stay inside 32 bits */

/* Flags of lt_bvh_desc_t. */
#define LT_BVH_TIGHT 1u /* store exact triangle bounds (no padding; see LT_BVH_PAD_Q16) */

/* Padding added to every stored node box, s15.16 raw: 2^(LT_CFG_GEOM_MAX_LOG2 - 15) world units
 * (0.125 for the default 4096-unit geometry bound). The slab test computes each plane distance as
 * (plane - o) x round(1/d), which is the exact distance to a plane moved by up to
 * 2^-17 (|plane - o| + 1) units (<= 2^(GEOM-16) units for origin and geometry inside the geometry
 * bound); the pad covers that twice over, so a box test never rejects a ray that meets the
 * triangles inside within the triangle kernel's own error. The float32 build pads by
 * 2^-18 x (largest |coordinate| of the root box) for the same reason (relative error ~3 x 2^-24). */
#define LT_BVH_PAD_Q16 ((lt_q16_t)1 << (LT_CFG_GEOM_MAX_LOG2 + 1))

/* SAH constants (tinybvh's): a node visit costs C_TRAV, a triangle test C_ISECT. */
#define LT_BVH_C_TRAV 1u
#define LT_BVH_C_ISECT 1u

/* Build parameters, 20 bytes. A zeroed struct (or desc == NULL) selects every default. */
typedef struct lt_bvh_desc {
    uint32_t bins;      /* SAH bins per axis, 2..LT_BVH_MAX_BINS; 0 = 16 */
    uint32_t max_leaf;  /* hard limit of triangles per leaf, 1..LT_BVH_MAX_LEAF; 0 = 4 */
    uint32_t min_leaf;  /* a node with <= min_leaf triangles is never split, 1..max_leaf; 0 = 1 */
    uint32_t max_depth; /* deepest leaf (root = depth 0), 1..LT_BVH_MAX_DEPTH; 0 = 64 */
    uint32_t flags;     /* LT_BVH_TIGHT or 0 */
} lt_bvh_desc_t;

/* ---- nodes: 32 bytes, two per 64-byte cache line (Bikker) ------------------------------------ */

/* s15.16 node, 32 bytes, 4-byte aligned (the arena puts node 0 at its start, so an arena aligned
 * to 64 bytes keeps each sibling pair 2k, 2k+1 in one cache line). Leaf iff count > 0. */
typedef struct lt_bvh_node_q16 {
    lt_aabb_q16_t b;     /* bounds lo[3], hi[3], s15.16 world units (24 B), padded unless TIGHT */
    uint32_t left_first; /* leaf: first slot of its triangles in idx[]; interior: left child node
                            index, the right child is left_first + 1 */
    uint32_t count;      /* leaf: triangle count (1..max_leaf); interior: 0 */
} lt_bvh_node_q16_t;
LT_STATIC_ASSERT(sizeof(lt_bvh_node_q16_t) == 32, "q16 BVH node is 32 bytes");

#if LT_CFG_FLOAT32
/* float32 node, 32 bytes, same layout. */
typedef struct lt_bvh_node_f32 {
    lt_aabb_f32_t b;     /* bounds, float world units (24 B) */
    uint32_t left_first; /* as lt_bvh_node_q16_t */
    uint32_t count;      /* as lt_bvh_node_q16_t */
} lt_bvh_node_f32_t;
LT_STATIC_ASSERT(sizeof(lt_bvh_node_f32_t) == 32, "f32 BVH node is 32 bytes");
#endif

/* The leaf predicate, for either node type. */
#define LT_BVH_IS_LEAF(node) ((node)->count != 0u)

/* Optional traversal counters, 72 bytes (host statistics; the sim counts the same through
 * LT_EVENT). */
typedef struct lt_bvh_stats {
    uint64_t calls;      /* trace/occluded calls */
    uint64_t rays;       /* active lanes at entry, summed over calls */
    uint64_t nodes;      /* nodes visited (their box passed, their content processed) */
    uint64_t node_lanes; /* active lanes summed over visited nodes (utilisation = / (16 nodes)) */
    uint64_t boxes;      /* box tests (one per box per packet or ray) */
    uint64_t tris;       /* triangle tests (one per triangle per packet or ray) */
    uint64_t tri_lanes;  /* active lanes summed over triangle tests */
    uint64_t overflows;  /* stack pushes refused (LT_E_DEPTH returned) */
    uint32_t max_stack;  /* deepest stack seen */
    uint32_t pad_;       /* private */
} lt_bvh_stats_t;

#define LT_BVH_NUM_Q16 1u
#define LT_BVH_NUM_F32 2u

/* A built tree: a handle into the caller's arena, 64 bytes on LP64 hosts, 44 on 32-bit targets.
 * Transparent (tests and tools walk it); the core never writes it after the build except through
 * `stats`. */
typedef struct lt_bvh {
    const void *nodes;     /* lt_bvh_node_q16_t or lt_bvh_node_f32_t [nnodes], at the arena start;
                              node 0 is the root, slot 1 is unused so sibling pairs start even */
    const uint32_t *idx;   /* [ntris]: leaf slot -> original triangle id, right after the nodes */
    uint32_t nnodes;       /* node slots used (0 for an empty scene) */
    uint32_t ntris;        /* triangles */
    uint32_t depth;        /* deepest leaf, root = 0 */
    uint32_t leaves;       /* leaf count */
    uint32_t num;          /* LT_BVH_NUM_Q16 or LT_BVH_NUM_F32 */
    uint32_t bad_tri;      /* after LT_E_RANGE: the first triangle outside the range; else 0 */
    uint32_t isect;        /* intersector of every walk over this tree, the multi-frusta ones
                              included: LT_ISECT_WT (set by the build) or LT_ISECT_MT (set it after
                              the build); another value makes the walks return LT_E_ARG */
    size_t bytes;          /* bytes of the arena the tree keeps (nodes + idx; the rest is free
                              after the build); after LT_E_SPACE: the bytes needed */
    lt_bvh_stats_t *stats; /* NULL, or counters the traversal adds to (set it after the build;
                              give each thread its own copy of this handle) */
} lt_bvh_t;

/* ---- single rays ------------------------------------------------------------------------------ */

/* One ray in fixed point, 48 bytes: the packet conventions of lt_ray16_q16_t for one lane. */
typedef struct lt_ray1_q16 {
    lt_q16_t o[3];    /* origin, s15.16 world units (|x| <= 2^LT_CFG_GEOM_MAX_LOG2) */
    lt_q30_t d[3];    /* unit direction, s1.30 */
    lt_q16_t rd[3];   /* 1/d, s15.16 = round(2^46 / d_raw), from lt_ray1_q16_setup */
    lt_q16_t tmin;    /* parametric interval, s15.16 */
    lt_q16_t tmax;    /* < LT_Q16_MAX; a hit shortens it */
    uint8_t par;      /* bit a: d[a] == 0 (parallel to the a slabs), from setup */
    uint8_t rsat;     /* bit a: d[a] != 0 and 1/d saturated, from setup */
    uint8_t pad_[2];  /* private */
} lt_ray1_q16_t;
LT_STATIC_ASSERT(sizeof(lt_ray1_q16_t) == 48, "single q16 ray is 48 bytes");

/* rd = 1/d and the par/rsat bits, exactly as lt_ray16_q16_setup does per lane.
 * Format: s1.30 -> s15.16 (2^46 / d_raw). Rounding: half up. Overflow: |d| < 2^-15 saturates to
 * +-max (d == 0 gives +max) and is flagged so the slab test takes the exact path.
 * Cost: SDIV x3, SALU x9. */
void lt_ray1_q16_setup(lt_ray1_q16_t *r);

/* Slab test of one ray, bit-identical to one lane of lt_slab16_q16 (parallel and saturated axes
 * take the same exact path). Writes max(tmin, near planes) to *tnear on a hit.
 * Format: s15.16. Rounding: (plane - o) x (1/d) half up. Overflow: saturates (monotone, so the
 * classification survives). Cost: BVH_SLAB1 (SLOAD x6, SALU x14, SMUL x6, BRANCH x4); + per axis
 * with d == 0 BVH_SLAB1_FIX (SALU x4), per saturated axis BVH_SLAB1_FIX_DIV (SDIV x2).
 * Returns: 1 if the ray meets the box within [tmin, tmax], else 0. */
int lt_slab1_q16(const lt_ray1_q16_t *r, const lt_aabb_q16_t *b, lt_q16_t *tnear);

/* Moller-Trumbore of one ray, two-sided, edges inclusive, bit-identical to one lane of
 * lt_tri16_q16 (same exact int64 products, qvec in s25.6, same t division).
 * Format: see docs/numerics.md. Rounding: t half up. Overflow: none within the geometry bound.
 * Cost: BVH_TRI1 (SLOAD x9, SMUL x24, SALU x24, BRANCH x2), BVH_TRI1_TDIV (SDIV x1) for hit
 * candidates only.
 * Returns: 1 if tmin < t < tmax (then tmax = t), else 0. */
int lt_tri1_q16(lt_ray1_q16_t *r, const lt_tri_q16_t *tri);

#if LT_CFG_FLOAT32
/* One ray in float32, 48 bytes: the conventions of lt_ray16_f32_t for one lane. */
typedef struct lt_ray1_f32 {
    float o[3];      /* origin, world units */
    float d[3];      /* unit direction */
    float rd[3];     /* 1/d clamped to +-FLT_MAX (d == +-0 gives +-FLT_MAX) */
    float tmin;      /* parametric interval */
    float tmax;      /* < FLT_MAX; a hit shortens it */
    uint8_t par;     /* bit a: d[a] == +-0 */
    uint8_t rsat;    /* always 0 */
    uint8_t pad_[2]; /* private */
} lt_ray1_f32_t;
LT_STATIC_ASSERT(sizeof(lt_ray1_f32_t) == 48, "single f32 ray is 48 bytes");

/* rd = 1/d per axis (IEEE division), +-0 gives +-FLT_MAX and sets the par bit, as
 * lt_ray16_f32_setup per lane. Format: float32. Rounding: to nearest even. Overflow: clamped to
 * +-FLT_MAX. Cost: SDIV x3, SALU x9 (scalar float work is charged to the scalar classes). */
void lt_ray1_f32_setup(lt_ray1_f32_t *r);

/* One lane of lt_slab16_f32, operation for operation. Format: float32. Rounding: each product and
 * difference to nearest even. Overflow: none (1/d is finite).
 * Cost: BVH_SLAB1 (SLOAD x6, SALU x14, SMUL x6, BRANCH x4) + BVH_SLAB1_FIX (SALU x4) per axis
 * with d == +-0.
 * Returns: 1 if the ray meets the box within [tmin, tmax] (*tnear written), else 0. */
int lt_slab1_f32(const lt_ray1_f32_t *r, const lt_aabb_f32_t *b, float *tnear);

/* One lane of lt_tri16_f32, operation for operation (same products in the same order).
 * Format: float32. Rounding: to nearest even. Overflow: none for |x| <= 2^48.
 * Cost: BVH_TRI1 (SLOAD x9, SMUL x24, SALU x24, BRANCH x2).
 * Returns: 1 if tmin < t < tmax (then tmax = t), else 0. */
int lt_tri1_f32(lt_ray1_f32_t *r, const lt_tri_f32_t *tri);
#endif

/* ---- build ------------------------------------------------------------------------------------ */

/* Arena bytes lt_bvh_build_q16/_f32 need for ntris triangles with these parameters (the same for
 * both numeric paths): 2 ntris node slots (2n - 1 nodes at most, plus the unused slot 1), ntris
 * indices, and the builder's scratch (one box per triangle, 3 x bins bins, the SAH sweep and the
 * explicit build stack of max_depth + 1 entries). ntris == 0 needs 0 bytes. Cost: none.
 * Returns: LT_OK, LT_E_ARG (NULL bytes, or a desc field outside its range), LT_E_RANGE
 * (ntris > LT_BVH_MAX_TRIS, or the size does not fit size_t). */
lt_status_t lt_bvh_size(uint32_t ntris, const lt_bvh_desc_t *desc, size_t *bytes);

/* Build the tree of tris[0..n) into arena (8-byte aligned, arena_bytes >= lt_bvh_size()).
 * Binned SAH over centroid bounds on the best of 3 axes (Wald 2007); a node becomes a leaf when
 * count <= min_leaf, or when count <= max_leaf and the SAH prefers no split; a node that must split
 * but has no SAH split (all centroids equal), or whose SAH split would break the depth limit, is
 * split at the object median. n == 0 gives an empty tree that never hits.
 * Format: s15.16 boxes; the SAH in integers: half-areas exact in uint64 (box sides < 2^29 raw, so
 * a side product < 2^58 and the sum < 2^60), each node's areas shifted right until the parent's fits
 * 32 bits, costs = area x count < 2^60 (counts < 2^27). Rounding: areas truncated after the shift
 * (relative 2^-32 of the parent). Overflow: none within the geometry bound.
 * Cost: BUILD phase, the BVH_BUILD_* recipes of lt_recipes.def: per triangle BVH_BUILD_TRI_BOX and
 * BVH_BUILD_IDX_MOVE; per node job BVH_BUILD_NODE_POP; a leaf's box BVH_BUILD_RANGE_BOX per
 * triangle; a split: BVH_BUILD_CENTROID_BOUNDS, BVH_BUILD_BINNING and BVH_BUILD_PARTITION per
 * triangle, BVH_BUILD_BIN_SCALE, BVH_BUILD_SAH_SWEEP and BVH_BUILD_CHILD_BOX per bin,
 * BVH_BUILD_SPLIT_DECIDE (object median: BVH_BUILD_SELECT per element of each partition pass); at
 * the end BVH_BUILD_NODE_FIX per node; LT_MEM on triangles and nodes. One triangle: TRI_BOX,
 * NODE_POP, RANGE_BOX, NODE_FIX, IDX_MOVE.
 * Returns: LT_OK; LT_E_ARG (NULL out, tris with n > 0, arena misaligned, bad desc); LT_E_SPACE
 * (arena too small: out->bytes = the size needed, arena untouched); LT_E_RANGE (a vertex outside
 * |x| <= 2^LT_CFG_GEOM_MAX_LOG2 units: out->bad_tri names the triangle; n > LT_BVH_MAX_TRIS);
 * LT_E_DEPTH (n > max_leaf x 2^max_depth: no tree of that depth exists). */
lt_status_t lt_bvh_build_q16(lt_bvh_t *out, const lt_bvh_desc_t *desc, const lt_tri_q16_t *tris,
                             uint32_t n, void *arena, size_t arena_bytes);

/* ---- packet and single-ray traversal --------------------------------------------------------- */

/* Closest hit of the lanes in k: hit->id = original triangle id or -1, r->tmax = its distance.
 * Ordered traversal: both children are slab-tested (lt_slab16_q16) with the packet's mask; when
 * both are hit, the one with the smaller min tnear over its lanes is entered and the other pushed
 * as (node, mask, min tnear); a popped entry is skipped when its tnear exceeds every remaining
 * tmax. Leaves run the tree's intersector on their lanes: lt_tri16_wt_q16 (LT_ISECT_WT, the
 * default; the packet's lt_ray16_wt_setup_q16 once per call, before its first triangle test)
 * or lt_tri16_q16 (LT_ISECT_MT). The stack holds LT_BVH_MAX_DEPTH entries, which a
 * built tree never exceeds; should a foreign tree need more, the far child is dropped (its lanes
 * may miss a closer hit), nothing is written past the stack, and LT_E_DEPTH is returned.
 * Format: as lt_slab16_q16 / lt_tri16_q16. Cost: VBCAST x1 in the caller's phase (hit->id = -1);
 * TRAVERSE: VBCAST x2 per call, lt_slab16_q16 per box test, per node BVH_TRAV_NODE, interior:
 * BVH_TRAV_CHILDREN16 (+ VRED x2, BVH_TRAV_ORDER, BVH_TRAV16_PUSH with both children entered),
 * leaf: BVH_TRAV_ANY_EXIT after it; BVH_TRAV16_POP per entry popped (+ VRED x1 if it has live
 * lanes); INTERSECT: BVH_TRAV_LEAF_TRI and the intersector per leaf triangle (lt_tri16_wt_q16,
 * and lt_ray16_wt_setup_q16 before the first; or lt_tri16_q16); NODES per node, LT_MEM
 * per node read.
 * Returns: LT_OK, LT_E_ARG (NULL, or a tree of the other numeric path), LT_E_DEPTH (see above). */
lt_status_t lt_bvh_trace16_q16(const lt_bvh_t *bvh, const lt_tri_q16_t *tris, lt_ray16_q16_t *r,
                               lt_mask16_t k, lt_hit16_t *hit);

/* Any hit (shadow rays): *occluded = lanes of k with some triangle at tmin < t < tmax. Lanes leave
 * the packet at their first hit (their tmax becomes that hit's distance); traversal stops when
 * every lane of k is occluded. Cost: as lt_bvh_trace16_q16 (the caller-phase VBCAST x1 is the
 * local hit record's) + BVH_TRAV_ANY_RETIRE per triangle that occludes lanes. Returns: as
 * lt_bvh_trace16_q16. */
lt_status_t lt_bvh_occluded16_q16(const lt_bvh_t *bvh, const lt_tri_q16_t *tris, lt_ray16_q16_t *r,
                                  lt_mask16_t k, lt_mask16_t *occluded);

/* Closest hit of one ray: *id = original triangle id or -1, r->tmax = its distance. The same
 * ordered traversal with a stack of (node, tnear), scalar slab and triangle tests (bit-identical to
 * a packet lane, so the packet and single-ray paths return the same hit): lt_tri1_wt_q16 after
 * one lt_ray1_wt_setup_q16 per call (LT_ISECT_WT), or lt_tri1_q16 (LT_ISECT_MT). Cost: TRAVERSE
 * lt_slab1_q16 per box test, per node BVH_TRAV_NODE, interior: BVH_TRAV1_CHILDREN (+
 * BVH_TRAV_ORDER, BVH_TRAV1_PUSH with both children entered); BVH_TRAV1_POP per entry popped;
 * INTERSECT BVH_TRAV_LEAF_TRI and lt_tri1_wt_q16 (its setup before the first) or lt_tri1_q16
 * per leaf triangle; NODES per node. Returns: as
 * lt_bvh_trace16_q16. */
lt_status_t lt_bvh_trace1_q16(const lt_bvh_t *bvh, const lt_tri_q16_t *tris, lt_ray1_q16_t *r,
                              int32_t *id);

/* Any hit of one ray: *occluded = 1 if some triangle lies at tmin < t < tmax, else 0. Cost: as
 * lt_bvh_trace1_q16, stopping at the first hit. */
lt_status_t lt_bvh_occluded1_q16(const lt_bvh_t *bvh, const lt_tri_q16_t *tris, lt_ray1_q16_t *r,
                                 int *occluded);

#if LT_CFG_FLOAT32
/* float32 twins of the five functions above, from the same source (lt_bvh.inc).
 * Build: float boxes and float SAH costs (area x count), vertices accepted for |x| <= 2^48 (else
 * LT_E_RANGE with bad_tri), boxes padded by 2^-18 of the root box's largest |coordinate|.
 * Traversal: lt_slab16_f32 / lt_tri16_f32 and their single-ray lanes lt_slab1_f32 / lt_tri1_f32.
 * Format: IEEE binary32. Rounding: to nearest even, no contraction. Overflow: none in range.
 * Cost and returns: as the s15.16 functions. */
lt_status_t lt_bvh_build_f32(lt_bvh_t *out, const lt_bvh_desc_t *desc, const lt_tri_f32_t *tris,
                             uint32_t n, void *arena, size_t arena_bytes);
lt_status_t lt_bvh_trace16_f32(const lt_bvh_t *bvh, const lt_tri_f32_t *tris, lt_ray16_f32_t *r,
                               lt_mask16_t k, lt_hit16_t *hit);
lt_status_t lt_bvh_occluded16_f32(const lt_bvh_t *bvh, const lt_tri_f32_t *tris, lt_ray16_f32_t *r,
                                  lt_mask16_t k, lt_mask16_t *occluded);
lt_status_t lt_bvh_trace1_f32(const lt_bvh_t *bvh, const lt_tri_f32_t *tris, lt_ray1_f32_t *r,
                              int32_t *id);
lt_status_t lt_bvh_occluded1_f32(const lt_bvh_t *bvh, const lt_tri_f32_t *tris, lt_ray1_f32_t *r,
                                 int *occluded);
#endif

/* ---- quantised 16-byte nodes (s15.16 only) ---------------------------------------------------- */

/* A node of the quantised tree, 16 bytes (half of lt_bvh_node_q16_t): its box in the frame of its
 * parent's decoded box F, per axis a with step 2^e_a, e_a the smallest e >= 0 with
 * ceil((F.hi[a] - F.lo[a]) / 2^e) <= 65535 (derived from F, so nothing else is stored):
 * lo = F.lo + (qlo << e_a), hi = F.lo + (qhi << e_a). The builder rounds lo down and hi up, so a
 * decoded box always contains the exact one (traversal stays conservative); the error per face is
 * below one step, and the minimal step is < 2 ext / 65535, so < 2^-15 of the parent frame's extent.
 * Same node indices as the source tree. */
typedef struct lt_bvhq_node {
    uint16_t qlo[3]; /* lower corner, steps above the parent frame's lower corner */
    uint16_t qhi[3]; /* upper corner, steps above the parent frame's lower corner */
    uint32_t link;   /* bits 28..31: triangle count of a leaf (1..15), 0 for an interior node;
                        bits 0..27: leaf: first slot in idx[]; interior: left child (right = +1) */
} lt_bvhq_node_t;
LT_STATIC_ASSERT(sizeof(lt_bvhq_node_t) == 16, "quantised BVH node is 16 bytes");

#define LT_BVHQ_COUNT(link) ((link) >> 28)
#define LT_BVHQ_INDEX(link) ((link) & 0x0FFFFFFFu)
#define LT_BVHQ_MAX_LEAF 15u

/* A quantised tree: its own node array plus the source tree's idx[] (keep the source arena). */
typedef struct lt_bvhq {
    const lt_bvhq_node_t *nodes; /* [nnodes] in the caller's buffer; node 0's q fields unused */
    const uint32_t *idx;         /* the source tree's idx[] */
    lt_aabb_q16_t root;          /* root box, exact (the frame of node 0's children) */
    uint32_t nnodes;             /* as the source tree (0 = empty) */
    uint32_t ntris;              /* as the source tree */
    size_t bytes;                /* nnodes x 16 */
    lt_bvh_stats_t *stats;       /* NULL, or traversal counters (as lt_bvh_t) */
    uint32_t isect;              /* intersector of its walks, as lt_bvh_t (the build copies the
                                    source tree's) */
    uint32_t pad_;               /* private */
} lt_bvhq_t;

/* Bytes of the buffer lt_bvhq_build_q16 needs for src: 16 x src->nnodes for the nodes (kept, at
 * the buffer start) + (LT_BVH_MAX_DEPTH + 1) x 28 for the quantiser's explicit stack (free after the
 * build); 0 for an empty tree. Cost: none. Returns: LT_OK, LT_E_ARG (NULL, or src not a q16
 * tree). */
lt_status_t lt_bvhq_size(const lt_bvh_t *src, size_t *bytes);

/* Quantise a built s15.16 tree into mem (4-byte aligned, >= lt_bvhq_size bytes), top-down with an
 * explicit stack in mem (each node quantised in its parent's decoded frame); out->bytes = the
 * bytes kept (16 x nnodes).
 * Format: uint16 steps of 2^e_a raw. Rounding: lo down, hi up (conservative). Overflow: decoded
 * corners saturate to int32 (never within the geometry bound).
 * Cost: BUILD phase, BVHQ_BUILD_NODE (SALU x40) per node. Returns: LT_OK, LT_E_ARG (NULL, src not
 * q16, mem misaligned), LT_E_SPACE (out->bytes = the size needed), LT_E_RANGE (a leaf of more than
 * LT_BVHQ_MAX_LEAF triangles: build the source with max_leaf <= 15). */
lt_status_t lt_bvhq_build_q16(lt_bvhq_t *out, const lt_bvh_t *src, void *mem, size_t bytes);

/* Closest hit / any hit of a packet, and closest hit of a single ray, over the quantised tree: the
 * algorithms of lt_bvh_trace16_q16 / lt_bvh_occluded16_q16 / lt_bvh_trace1_q16 with each child box
 * decoded from the frame carried on the stack (24 more bytes per stack entry).
 * Cost: as those with BVH_TRAV_NODE1 (SLOAD x1) per node instead of BVH_TRAV_NODE and, per interior
 * node, BVHQ_FRAME_EXPS + 2 BVHQ_DECODE (SLOAD x6, SALU x33); the packet walks push and pop the
 * decoded box: BVHQ_TRAV16_PUSH instead of BVH_TRAV16_PUSH, + BVHQ_TRAV16_POP_BOX per entry taken;
 * the single ray BVHQ_TRAV1_PUSH. Returns: as those. */
lt_status_t lt_bvhq_trace16_q16(const lt_bvhq_t *bvh, const lt_tri_q16_t *tris, lt_ray16_q16_t *r,
                                lt_mask16_t k, lt_hit16_t *hit);
lt_status_t lt_bvhq_occluded16_q16(const lt_bvhq_t *bvh, const lt_tri_q16_t *tris,
                                   lt_ray16_q16_t *r, lt_mask16_t k, lt_mask16_t *occluded);
lt_status_t lt_bvhq_trace1_q16(const lt_bvhq_t *bvh, const lt_tri_q16_t *tris, lt_ray1_q16_t *r,
                               int32_t *id);

#ifdef __cplusplus
}
#endif
#endif /* LT_BVH_H */
