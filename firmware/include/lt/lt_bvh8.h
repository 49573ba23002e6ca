/* lt_bvh8.h - the wide BVH for single rays: 8-wide nodes collapsed from a built binary BVH
 * (lt_bvh.h; the binned SAH tree), each node's eight child boxes stored as planes (SoA), so one ray
 * meets all eight in one node test: the slab test of lt_slab1 per child, written as 8-lane loops
 * the host compiler turns into SIMD (and the simulator charges as one vector test); leaves of up to
 * four triangles in blocks of four lanes (SoA, the rebuilt vertices and the ids), tested as 4-lane
 * loops with the watertight test's arithmetic. Closest hit with the children visited near to far,
 * and any hit (shadow rays) with an early exit per ray, in s15.16 and float32 from one source
 * (firmware/core/object/lt_bvh8.inc). The 16-ray packets keep the binary tree (the one the
 * simulator's packet walk models). Freestanding: the caller hands in the memory lt_bvh8_size()
 * names. See docs/bvh.md, "Wide nodes for single rays".
 * Builds: all; float32 entry points only with LT_CFG_FLOAT32.
 */
#ifndef LT_BVH8_H
#define LT_BVH8_H

#include "lt_bvh.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LT_BVH8_WIDTH 8
#define LT_BVH8_EMPTY 0xFFFFu /* cnt of an unused child slot */
#define LT_BVH8_LANES 4       /* triangles per leaf block */
#define LT_BVH8_BLOCKS(n) (((n) + LT_BVH8_LANES - 1u) / LT_BVH8_LANES) /* blocks of n triangles */
/* float32: a binary subtree of at most this many triangles (in one slot range) becomes one wide
 * leaf (s15.16 keeps the binary leaves: its block test is scalar, lane by lane) */
#define LT_BVH8_MERGE 4u
/* a walk's stack: at most 7 far children per level of a tree at most LT_BVH_MAX_DEPTH deep */
#define LT_BVH8_STACK (7u * LT_BVH_MAX_DEPTH + 1u)

/* s15.16 node, 256 bytes (4 cache lines): child c's box is (lo[a][c], hi[a][c]) for axes a, the
 * binary node's (padded) box unchanged; cnt[c] = 0: an interior child, child[c] its node index;
 * 1..LT_BVH_MAX_LEAF: a leaf of cnt[c] triangles in ceil(cnt[c] / 4) blocks starting at block
 * child[c]; LT_BVH8_EMPTY: no child (the slots in use come first). */
typedef struct lt_bvh8_node_q16 {
    lt_q16_t lo[3][LT_BVH8_WIDTH];
    lt_q16_t hi[3][LT_BVH8_WIDTH];
    uint32_t child[LT_BVH8_WIDTH];
    uint16_t cnt[LT_BVH8_WIDTH];
    uint32_t pad_[4]; /* private */
} lt_bvh8_node_q16_t;
LT_STATIC_ASSERT(sizeof(lt_bvh8_node_q16_t) == 256, "q16 wide node is 256 bytes");

/* A leaf block, 160 bytes: four triangles as lanes. v[3 * k + a][l] is axis a of vertex k of lane
 * l's triangle as the triangle tests rebuild it (v0, v0 + e1, v0 + e2, s15.16 saturating adds);
 * id[l] its triangle id; an unused lane has id -1 and zero vertices, a zero-area triangle (which
 * never hits) id -2 - its id. */
typedef struct lt_bvh8_tris4_q16 {
    lt_q16_t v[9][LT_BVH8_LANES];
    int32_t id[LT_BVH8_LANES];
} lt_bvh8_tris4_q16_t;
LT_STATIC_ASSERT(sizeof(lt_bvh8_tris4_q16_t) == 160, "q16 leaf block is 160 bytes");

#if LT_CFG_FLOAT32
/* float32 leaf block, the same layout (float adds). */
typedef struct lt_bvh8_tris4_f32 {
    float v[9][LT_BVH8_LANES];
    int32_t id[LT_BVH8_LANES];
} lt_bvh8_tris4_f32_t;
LT_STATIC_ASSERT(sizeof(lt_bvh8_tris4_f32_t) == 160, "f32 leaf block is 160 bytes");

/* float32 node, the same layout. */
typedef struct lt_bvh8_node_f32 {
    float lo[3][LT_BVH8_WIDTH];
    float hi[3][LT_BVH8_WIDTH];
    uint32_t child[LT_BVH8_WIDTH];
    uint16_t cnt[LT_BVH8_WIDTH];
    uint32_t pad_[4]; /* private */
} lt_bvh8_node_f32_t;
LT_STATIC_ASSERT(sizeof(lt_bvh8_node_f32_t) == 256, "f32 wide node is 256 bytes");
#endif

/* A collapsed tree: a handle into the caller's memory (the nodes) and the binary tree's index
 * array (which must outlive it). Transparent. */
typedef struct lt_bvh8 {
    const void *nodes;   /* lt_bvh8_node_<p>_t [nnodes]; node 0 is the root */
    const void *blocks;  /* lt_bvh8_tris4_<p>_t [nblocks], right behind the nodes */
    const uint32_t *idx; /* the binary tree's leaf slot -> triangle id */
    uint32_t nnodes;     /* 0 for an empty scene */
    uint32_t nblocks;
    uint32_t ntris;
    uint32_t num;        /* LT_BVH_NUM_Q16 or LT_BVH_NUM_F32, as the binary tree */
    uint32_t isect;      /* the binary tree's intersector (LT_ISECT_WT or LT_ISECT_MT) */
    uint32_t children;   /* child slots in use over all nodes (fill = children / (8 nnodes)) */
    uint32_t leaves;     /* leaf children over all nodes */
    uint32_t merge;      /* the largest binary subtree merged into one leaf (0: none) */
    uint32_t span;       /* s15.16: the largest |plane| (raw) of the children in use, so a ray
                            whose |origin| + span fits int32 needs no clamp of plane - origin;
                            float32: 0 */
    size_t bytes;        /* nnodes x 256 + nblocks x 160 */
} lt_bvh8_t;

/* Bytes of the wide nodes and leaf blocks lt_bvh8_build_* makes from bvh (a pass over the binary
 * tree, no memory; the same for both paths). Cost: none. Returns LT_OK, LT_E_ARG (NULL). */
lt_status_t lt_bvh8_size(const lt_bvh_t *bvh, size_t *bytes);

/* The path's merge bound of lt_bvh8_build_* / lt_bvh8_size: LT_BVH8_MERGE in float32 (its single
 * rays test a leaf's four lanes at once), 0 in s15.16. */
LT_INLINE uint32_t lt_bvh8_merge_default(uint32_t num)
{
    return num == LT_BVH_NUM_F32 ? LT_BVH8_MERGE : 0u;
}

/* The same with an explicit merge bound (0..LT_BVH8_MERGE; 0 keeps every binary leaf as one wide
 * leaf: the 16-ray packets' tree, whose leaf tests take the packet's lanes one triangle at a
 * time, so a merged leaf costs more tests than it saves nodes). Returns LT_E_ARG for a larger
 * bound. */
lt_status_t lt_bvh8_size_merge(const lt_bvh_t *bvh, uint32_t merge, size_t *bytes);

/* Collapse the binary tree into 8-wide nodes in mem (8-byte aligned, bytes >= lt_bvh8_size):
 * each wide node takes its binary node's two children and, while it has fewer than 8, opens the
 * interior child with the largest surface area into its two children (the standard greedy
 * collapse); in float32 a child whose subtree holds at most LT_BVH8_MERGE triangles (its binary
 * leaves' slots one range) is not opened but becomes one leaf of those triangles in slot order
 * (s15.16: every binary leaf is one wide leaf); wide nodes
 * are numbered breadth first, each leaf's triangles written into its blocks (from tris, the
 * triangles the binary tree was built over; the zero-area test of lt_tri1_wt once per triangle).
 * Cost: BUILD phase, BVH8_BUILD_NODE per wide node, BVH8_BUILD_OPEN per binary node opened,
 * BVH8_BUILD_TRI and WT_ZERO_AREA per triangle. Returns LT_OK, LT_E_ARG (NULL, misaligned, a
 * tree of the other path), LT_E_SPACE (bytes too small: out->bytes = the size needed). */
lt_status_t lt_bvh8_build_q16(lt_bvh8_t *out, const lt_bvh_t *bvh, const lt_tri_q16_t *tris,
                              void *mem, size_t bytes);
/* With an explicit merge bound (lt_bvh8_size_merge); lt_bvh8_build_q16 uses 0. */
lt_status_t lt_bvh8_build_merge_q16(lt_bvh8_t *out, const lt_bvh_t *bvh,
                                    const lt_tri_q16_t *tris, void *mem, size_t bytes,
                                    uint32_t merge);

/* Closest hit of one ray: *id = triangle id or -1, r->tmax = its distance. At each node the 8
 * child boxes in one test (lt_slab1's arithmetic per child: the same verdicts as the binary
 * tree's tests of the same boxes), the hit children sorted by tnear (one and two without a sort),
 * the nearest entered and the rest pushed far to near; a popped entry beyond tmax is skipped. A
 * leaf's blocks: with the watertight test (the default) the four lanes at once, each lane
 * lt_tri1_wt's arithmetic (the same bits), then the lanes that meet the ray in lane order, each
 * taken when tmin < t < tmax as the triangle loop takes them; with Moller-Trumbore the triangles
 * one by one (lt_tri1 from tris). The closest distance equals the binary walk's; where two
 * triangles meet the ray at exactly that distance (coplanar duplicate faces) either may be
 * reported, as the two walks visit leaves in different orders.
 * Cost: TRAVERSE BVH8_NODE_Q16 / _F32 per node (its 8-lane box test), BVH8_PUSH per child
 * pushed, BVH_TRAV1_POP per entry popped; NODES per node; INTERSECT per leaf block its 160-byte
 * read and per triangle of the block BVH_TRAV_LEAF_TRI and WT_TRI1 (the shear, edge and sign
 * stage; zero area was decided at build), per lane that meets the ray WT_TRI1_T (and
 * WT_F_EDGE_FIX1 where float32 refines a zero edge); Moller-Trumbore: BVH_TRAV_LEAF_TRI and
 * lt_tri1 per triangle. Returns LT_OK, LT_E_ARG. */
lt_status_t lt_bvh8_trace1_q16(const lt_bvh8_t *w, const lt_tri_q16_t *tris, lt_ray1_q16_t *r,
                               int32_t *id);

/* Any hit of one ray: *occluded = 1 if some triangle lies at tmin < t < tmax (the walk stops at
 * the first block that has one; hit children are pushed in slot order, unsorted), else 0: exactly
 * the binary tree's answer. Cost: as lt_bvh8_trace1_q16. */
lt_status_t lt_bvh8_occluded1_q16(const lt_bvh8_t *w, const lt_tri_q16_t *tris, lt_ray1_q16_t *r,
                                  int *occluded);

/* Closest hit of the lanes k of a 16-ray packet through the wide tree (hit->id per lane, -1 for
 * none; a lane's distance is its tmax), the walk of the packet as one frustum: at each node the
 * 8 child boxes against the range of the live lanes' origins and reciprocals (each plane's t at
 * the corners of those ranges bounds every lane's: the path's slab arithmetic is monotone in
 * each), a hit leaf child's own lanes from lt_slab16 of its box (the binary packet walk's test of
 * that box), children near to far by the frustum's tnear, an entry skipped when its tnear is
 * beyond every live lane's tmax; a leaf's triangles tested as the binary packet walk tests them
 * (lt_tri16_wt, or lt_tri16 with Moller-Trumbore), zero-area ones skipped by the watertight test.
 * Every lane meets every leaf box its own test hits, so its closest distance is the binary walk's;
 * where two triangles meet a lane at exactly that distance (coplanar duplicate faces) either may
 * be reported. For coherent packets (a camera tile): an axis on which a live lane is parallel or
 * has a saturated reciprocal bounds nothing, and a packet whose directions differ in sign tests
 * boxes loosely (correct, slower). Cost: TRAVERSE once the frustum (VRED x16), per node
 * LTW_NODE_RECIPE x2 (x4 when the origins differ) and per hit leaf child lt_slab16, BVH8_PUSH per
 * child pushed, BVH_TRAV16_POP per entry popped; INTERSECT per leaf triangle BVH_TRAV_LEAF_TRI
 * and lt_tri16_wt (lt_tri16), VRED x1 per leaf. Returns LT_OK, LT_E_ARG, LT_E_DEPTH (a foreign
 * tree deeper than LT_BVH_MAX_DEPTH). */
lt_status_t lt_bvh8_trace16_q16(const lt_bvh8_t *w, const lt_tri_q16_t *tris, lt_ray16_q16_t *r,
                                lt_mask16_t k, lt_hit16_t *hit);
/* Any hit of the lanes k: *occluded = the lanes with a triangle at tmin < t < tmax (a lane retires
 * at its first hit; the walk ends when all have), the binary walk's answer. Cost: as
 * lt_bvh8_trace16_q16, BVH_TRAV_ANY_RETIRE per triangle test. */
lt_status_t lt_bvh8_occluded16_q16(const lt_bvh8_t *w, const lt_tri_q16_t *tris,
                                   lt_ray16_q16_t *r, lt_mask16_t k, lt_mask16_t *occluded);

#if LT_CFG_FLOAT32
/* The float32 twins. */
lt_status_t lt_bvh8_build_f32(lt_bvh8_t *out, const lt_bvh_t *bvh, const lt_tri_f32_t *tris,
                              void *mem, size_t bytes);
lt_status_t lt_bvh8_build_merge_f32(lt_bvh8_t *out, const lt_bvh_t *bvh,
                                    const lt_tri_f32_t *tris, void *mem, size_t bytes,
                                    uint32_t merge);
lt_status_t lt_bvh8_trace1_f32(const lt_bvh8_t *w, const lt_tri_f32_t *tris, lt_ray1_f32_t *r,
                               int32_t *id);
lt_status_t lt_bvh8_occluded1_f32(const lt_bvh8_t *w, const lt_tri_f32_t *tris, lt_ray1_f32_t *r,
                                  int *occluded);
lt_status_t lt_bvh8_trace16_f32(const lt_bvh8_t *w, const lt_tri_f32_t *tris, lt_ray16_f32_t *r,
                                lt_mask16_t k, lt_hit16_t *hit);
lt_status_t lt_bvh8_occluded16_f32(const lt_bvh8_t *w, const lt_tri_f32_t *tris,
                                   lt_ray16_f32_t *r, lt_mask16_t k, lt_mask16_t *occluded);
#endif

#ifdef __cplusplus
}
#endif

#endif /* LT_BVH8_H */
