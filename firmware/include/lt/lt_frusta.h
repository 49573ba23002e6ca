/* lt_frusta.h - soft shadows from a quad area light with multi-frusta tracing (Benthin & Wald 2009
 * [Benthin09]): 16 shadow frusta traced in parallel through a BVH, one per lane, each frustum being
 * the 16 shadow rays from one pixel's hit point to its 16 light samples (4x4 interleaved QMC sets,
 * lt_qmc.h). Interval-arithmetic slab test, (node, frusta mask) stack, rays generated on demand
 * inside leaves from the frustum's light corner and the set's delta vectors, back-face and
 * corner-ray culling per triangle, optional corner-ray recomputation (CR). Also the 16-ray packet
 * baseline (one pixel's 16 rays, any hit), the per-ray reference generator, the direct-light term
 * and the 4x4 discontinuity filter. s15.16 and float32 from one source (lt_frusta.inc).
 * In s15.16 the frustum visibility equals per-ray visibility of every sample bit for bit (the
 * culling and box tests are conservative with proven margins; docs/frusta.md).
 * Also primary visibility with frusta (P-Frusta): 16 frusta of 4x4 camera rays each (a 16x16
 * pixel block) from a common eye, closest hit, and its 16-ray packet baseline (P-Packet).
 * Builds: all; float32 entry points only with LT_CFG_FLOAT32.
 */
#ifndef LT_FRUSTA_H
#define LT_FRUSTA_H

#include "lt_bvh.h"
#include "lt_qmc.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LT_FRUSTA_SAMPLES 16 /* shadow rays per frustum (one interleaved set) */
#define LT_FRUSTA_SETS 16    /* sets; frustum lane f uses set f (lane f = pixel f of a 4x4 tile) */

/* Sample numerators: sample coordinate u = su / LT_FRUSTA_GRID with su = 2 u8 + 1 (cell centre). */
#define LT_FRUSTA_GRID 512
/* s15.16 light edges must be multiples of LT_FRUSTA_GRID raw (2^-7 world units), so that every
 * sample point c + (su eu + sv ev) / 512 is an exact s15.16 value and the rays are exact convex
 * combinations of the corner rays (what makes corner-ray culling provably conservative). */

/* Flags of the light (both paths). */
#define LT_FRUSTA_BACKFACE 1u /* back-face culling: a triangle occludes only rays arriving at its
                                 front (N = e1 x e2 facing the ray origin); packets and frusta */
#define LT_FRUSTA_CORNER 2u   /* corner-ray culling of triangles per frustum (frusta only) */
#define LT_FRUSTA_CR 4u       /* recompute the corner rays of partially occluded frusta after a
                                 leaf in which one of their rays terminated (the paper's "CR") */
#define LT_FRUSTA_SPLIT 16u   /* a subtree entered by at most LT_FRUSTA_SPLIT_MAX frusta is walked
                                 by each of them as its own 16-ray packet (slab tests, any hit) */
#define LT_FRUSTA_FS 64u      /* shadow frusta: with the corner rays recomputed (the paper's "FS",
                                 frustum interval shrinking; implies CR), also shrink the
                                 direction intervals the traversal's box test uses to the new
                                 corner rays */
#define LT_FRUSTA_P256 32u    /* shadow frusta only: the walk's box tests are the 16 frusta's rays
                                 as 16 packets of 16 rays (a 256-ray packet, [Benthin09] 5.3's
                                 comparison) instead of the interval test; leaves unchanged */
#define LT_FRUSTA_TRIPAR 128u /* primary frusta, with LEAFRAY and the watertight test: a frustum
                                 with fewer rays in a leaf's box than the leaf has triangles tests
                                 them ray by ray, the leaf's triangles in the lanes (one 16-lane
                                 test per ray instead of one per triangle; the same hits) */
#define LT_FRUSTA_LEAFRAY 8u  /* ray-AABB leaf culling ([Benthin09] Table 2 "Ray-AABB"): at a
                                 leaf, a frustum whose own live rays (a 16-ray packet with
                                 reciprocals, made once per call) miss the leaf's box skips it;
                                 with SPLIT only frusta wide at the leaf are tested */

/* Corner culling runs for a triangle only when at least this many frusta of the leaf still take
 * it (after back-face culling): the culling pass is 16-lane work whatever the number of frusta,
 * about the cost of 2-3 of the 16-ray tests it can save (lrb16; docs/frusta.md, measured: 3 is
 * best of 1, 3, 6, 10 on the dragon and Sibenik at 512 x 512). */
#define LT_FRUSTA_CORNER_MIN 3u

/* LT_FRUSTA_SPLIT's threshold: frusta left in a subtree at or below which they go on as packets. */
#ifndef LT_FRUSTA_SPLIT_MAX
#define LT_FRUSTA_SPLIT_MAX 2u
#endif
/* ... and any frustum whose cross-section at a node's box exceeds this many times the box's
 * largest extent (fr_wide; measured 1, 2, 4: 1 is best on the dense meshes, equal elsewhere). */
#ifndef LT_FRUSTA_SPLIT_K
#define LT_FRUSTA_SPLIT_K 1
#endif
/* Primary frusta apply the width test only where at most this many tiles are left: camera tiles
 * that share a node are coherent, and the per-node test costs more than it finds there
 * (measured 4, 8, 12, 16 on the dragons, Sibenik and Sponza at 256 x 256: 4 is best). */
#ifndef LT_FRUSTA_PSPLIT_WIDE
#define LT_FRUSTA_PSPLIT_WIDE 4u
#endif

/* LT_FRUSTA_TRIPAR's rule: a frustum goes triangle-parallel at a leaf of n triangles (n <= 16)
 * when its rays in the leaf's box number fewer than n NUM / DEN. */
#ifndef LT_FRUSTA_TRIPAR_NUM
#define LT_FRUSTA_TRIPAR_NUM 1u
#endif
#ifndef LT_FRUSTA_TRIPAR_DEN
#define LT_FRUSTA_TRIPAR_DEN 1u
#endif

#define LT_FRUSTA_END_SHIFT 10u /* default: rays stop 2^-10 of their length short of the light */

/* Interval slab test margin, s15.16 raw in t units: a bound (plane - o) x round(1/d) is off the
 * exact (plane - o) / d by at most |plane - o| 2^-17 + 1 ulp <= 2^(GEOM+1) 2^-17 units + 1 ulp;
 * lower bounds are lowered and upper bounds raised by this much (docs/frusta.md). */
#define LT_FRUSTA_BOX_MARGIN_Q16 (((lt_q16_t)1 << LT_CFG_GEOM_MAX_LOG2) + 8)

/* ---- s15.16 ------------------------------------------------------------------------------- */

/* A quad light, 44 bytes: points c + u eu + v ev, u, v in [0, 1]. */
typedef struct lt_frusta_light_q16 {
    lt_q16_t c[3];      /* corner, s15.16 world units, |c| and |c + eu + ev| <= 2^GEOM */
    lt_q16_t eu[3];     /* edge u, s15.16, each a multiple of LT_FRUSTA_GRID raw (may be 0) */
    lt_q16_t ev[3];     /* edge v, s15.16, as eu */
    uint32_t flags;     /* LT_FRUSTA_BACKFACE | CORNER | CR | LEAFRAY | SPLIT */
    uint32_t end_shift; /* rays end at t_end - t_end / 2^end_shift (1..30; 0 = default 10) */
} lt_frusta_light_q16_t;
LT_STATIC_ASSERT(sizeof(lt_frusta_light_q16_t) == 44, "q16 light is 44 bytes");

/* Per-frame table of the light and its 16 x 16 samples, 6388 bytes (lanes: see fields).
 * Built by lt_frusta_table_q16 from a light and an interleaved sample set. */
typedef struct lt_frusta_table_q16 {
    lt_vq16_t gx[LT_FRUSTA_SETS], gy[LT_FRUSTA_SETS], gz[LT_FRUSTA_SETS]; /* set s, lane j: delta of
                                   sample j, (su eu + sv ev) / 512, s15.16 (exact) */
    lt_vi32_t su[LT_FRUSTA_SETS], sv[LT_FRUSTA_SETS]; /* set s, lane j: numerators 1..511 */
    lt_vq16_t gmin[3], gmax[3]; /* lane s: min / max over set s's deltas per axis, s15.16 */
    lt_vq16_t kd[4][3];         /* lane s: deltas of the corners of set s's (u, v) bounding
                                   rectangle: (umin,vmin) (umax,vmin) (umin,vmax) (umax,vmax) */
    lt_q16_t ld[4][3];          /* deltas of the light's own corners: 0, eu, ev, eu + ev */
    lt_q16_t c[3], eu[3], ev[3]; /* the light, s15.16 */
    int32_t eu9[3], ev9[3];     /* eu / 512, ev / 512 (exact integers) */
    uint32_t flags, end_shift;  /* from the light; end_shift resolved */
} lt_frusta_table_q16_t;
LT_STATIC_ASSERT(sizeof(lt_frusta_table_q16_t) == 6388, "q16 frusta table is 6388 bytes");

/* 16 shadow frusta (lane f: the pixel whose hit point is its origin, using set f), 1824 bytes.
 * Fill ox, oy, oz, call lt_frusta_setup16_q16, trace, read occl[]. */
typedef struct lt_frusta16_q16 {
    lt_vq16_t ox, oy, oz;           /* origins, s15.16 world units (|o| <= 2^GEOM) */
    lt_vq16_t cx, cy, cz;           /* light corner c - o, s15.16 */
    lt_vq16_t tmin, tmax;           /* ray interval in t units of the frustum's rays (s15.16) */
    lt_vq16_t rlo[3], rhi[3];       /* reciprocals of the direction interval ends, s15.16 */
    lt_vq30_t kx[4], ky[4], kz[4];  /* corner rays, s1.30 (recomputed under CR) */
    lt_vi32_t shift;                /* L: direction = (light point - o) << L, s15.16 -> s1.30 */
    lt_mask16_t alo[3], aup[3];     /* per axis: (lo - o) x rhi is a lower / an upper t bound */
    lt_mask16_t blo[3], bup[3];     /* per axis: (hi - o) x rlo is a lower / an upper t bound */
    lt_mask16_t active;             /* frusta with samples still unoccluded */
    uint16_t live[LT_LANES];        /* per frustum: samples not yet occluded */
    uint16_t occl[LT_LANES];        /* per frustum: occluded samples (the result) */
    uint16_t pad_[3];               /* private */
} lt_frusta16_q16_t;
LT_STATIC_ASSERT(sizeof(lt_frusta16_q16_t) == 1824, "q16 frusta packet is 1824 bytes");

/* Build the per-frame table. Format: s15.16 light, 0.8 sample cells -> exact s15.16 deltas.
 * Range: |c|, |c + eu|, |c + ev|, |c + eu + ev| <= 2^GEOM; eu, ev multiples of 512 raw.
 * Rounding: exact. Overflow: none in range. Cost: none charged (once per frame, SETUP).
 * Returns: LT_OK, LT_E_ARG (NULL, edges not on the 512-raw grid, end_shift > 30, unknown flags),
 * LT_E_RANGE (a light corner outside the geometry bound). */
lt_status_t lt_frusta_table_q16(const lt_frusta_light_q16_t *light, const lt_qmc_sets_t *sets,
                                lt_frusta_table_q16_t *tb);

/* Set up the frusta of the lanes in k from F->ox/oy/oz: light corner, shift L (the largest L with
 * every |(light corner - o) << L| < 2^30), t_end = 2^(30 - L) raw, tmin = 0, tmax = t_end -
 * (t_end >> end_shift), direction intervals and reciprocals, corner rays; live = 0xFFFF, occl = 0.
 * A lane whose origin lies outside the geometry bound is dropped (LT_E_RANGE); a lane whose rays
 * all have zero length (origin on a zero-area light) is dropped as unoccluded.
 * Format: s15.16 / s1.30. Rounding: exact except the reciprocals (half up). Overflow: none in
 * range. Cost: SETUP phase, per call FR_SETUP, FR_Q_SCALE, FR_Q_TEND, FR_Q_TMAX, FR_Q_TOD x18 and
 * VALU x57, VDIV x6 (the reciprocals), VCMP x24, VBCAST x32.
 * Returns: LT_OK, LT_E_ARG (NULL), LT_E_RANGE (some lane dropped; the others are set up). */
lt_status_t lt_frusta_setup16_q16(const lt_frusta_table_q16_t *tb, lt_mask16_t k,
                                  lt_frusta16_q16_t *F);

/* Fewer samples per pixel: after lt_frusta_setup16, keep only the samples in `samples` (bit j:
 * sample j of each frustum's set) live; a frustum left with none becomes inactive (unoccluded).
 * With CR (or FS) in the table's flags the corner rays of the remaining frusta are recomputed
 * through their live samples, and with FS their direction intervals too, so the walk bounds only
 * the rays it answers. occl is untouched (0 after setup).
 * Format, Rounding, Overflow: as CR / FS. Cost: SETUP phase, FR_RECORNER per active frustum (with
 * CR or FS), then fr_shrink once (with FS; lt_frusta_occluded16's Cost line).
 * Returns: LT_OK, LT_E_ARG (NULL). */
lt_status_t lt_frusta_restrict16_q16(const lt_frusta_table_q16_t *tb, uint16_t samples,
                                     lt_frusta16_q16_t *F);

/* Multi-frusta traversal: any hit of every live sample of every active frustum; sets occl[f].
 * Interval slab test of the 16 frusta per box (TRAVERSE, one AABB event per box), (node, mask)
 * stack, near child first (hmin of entry distances). Leaves (INTERSECT): per triangle the sign of
 * the kernel's tnum over the frusta (a hit needs tnum != 0; > 0 with BACKFACE), then, with CORNER,
 * the kernel's edge functions at the four corner rays against proven margins; then per frustum
 * with a surviving triangle (bit-scan), its 16 rays generated from the corner and the set's deltas
 * and lt_tri16 on the live samples. Events: TRI_FETCH per triangle fetched per leaf visit,
 * TRI_KEPT per triangle surviving culling for some frustum, CULL_BACK / CULL_CORNER per
 * frustum-triangle pair culled, TRIS per 16-ray test.
 * Cost (none when no frustum is active; a rounded cross product is VMUL x2, VMULW x1, VSHIFT x1, a
 * dot product VMUL x3, VMULW x2, d . qvec + VSHIFT x1): TRAVERSE per call VBCAST x2; per box test
 * (fr_box) FR_BOX_LOAD, VBCAST x10, VALU x22, VMUL x6, VCMP x1; per node BVH_TRAV_NODE, interior:
 * BVH_TRAV_CHILDREN16 (+ BVH_TRAV_ORDER, FR_TRAV_PUSH with both children entered), leaf:
 * FR_ACTIVE_EXIT after it; FR_TRAV_POP per entry popped. INTERSECT per leaf triangle: FR_LEAF_TRI
 * and fr_cull: FR_CULL_BACK, VBCAST x11, VALU x3, 3 rounded cross products, a dot product,
 * VCMP x2 (BACKFACE: VBCAST x10, VCMP x1) (+ with CORNER the corner rays: FR_Q_TRI_A, FR_Q_MARGINS,
 * FR_Q_NSAT, FR_CULL_CORNER per corner evaluated and their lane ops); a bit-scan of the frusta
 * keeping it (MASK x3 per frustum + 1) and per such frustum FR_LEAF_FRUSTUM, on first use its rays
 * (fr_gen: FR_GEN, VBCAST x3, VALU x3, FR_Q_TOD x3), the test (fr_tri: FR_TRI, VBCAST x16, 3
 * rounded cross products, 2 dot products, d . qvec, VCMP x4, VMULW x1; tnum < 0: VMULW x4,
 * VBCAST x4; candidates: TRI_Q_TDIV16, VBCAST x3, VCMP x2), FR_LEAF_OCCLUDED when rays were newly
 * occluded; with CR FR_RECORNER per such frustum after the leaf, and with FS then once fr_shrink
 * (FR_SHRINK; per axis VALU x6 for the minima and maxima, the two reciprocals of the box test's
 * setup, VCMP x4 and the saturation compares). With LEAFRAY, before the leaf's
 * triangles (with SPLIT too: fr_wide of the leaf's box, FR_WIDE, and only its wide frusta), per
 * frustum in the leaf's mask: FR_LEAF_RAYBOX, VBCAST x2 and lt_slab16_q16 on the
 * leaf's box with its live rays over [tmin, tmax] (dropped from the leaf when none meets it), and
 * on the frustum's first leaf of the call its packet: fr_gen, VBCAST x5, lt_ray16_q16_setup.
 * With SPLIT: once per call FR_DWID; per node FR_SPLIT_TEST and, with more than
 * LT_FRUSTA_SPLIT_MAX frusta, fr_wide (FR_WIDE); per frustum going on as a packet FR_SPLIT,
 * VBCAST x2, on first use its packet (as LEAFRAY's), then the packet baseline's walk from that
 * node (its costs below, from one lt_slab16_q16 of the node's box), FR_LEAF_OCCLUDED (+ CR's
 * FR_RECORNER, FS's fr_shrink) when rays were newly occluded, and FR_ACTIVE_EXIT. With P256 every
 * box test (fr_box above) is instead, per frustum of the mask, FR_P256_BOX, VRED x1, VBCAST x2 and
 * lt_slab16_q16 of its packet (on first use fr_gen, VBCAST x5, lt_ray16_q16_setup).
 * Format: as lt_slab16 / lt_tri16. Rounding: conservative (docs/frusta.md). Overflow: none.
 * Returns: LT_OK, LT_E_ARG (NULL, a tree of the other path), LT_E_DEPTH (foreign tree too deep). */
lt_status_t lt_frusta_occluded16_q16(const lt_bvh_t *bvh, const lt_tri_q16_t *tris,
                                     const lt_frusta_table_q16_t *tb, lt_frusta16_q16_t *F);

/* The 16 rays of one frustum as a packet (lane j = sample j of set s) from origin o: exactly the
 * rays the frusta generate, with lt_ray16_q16_setup applied. *k = 0xFFFF, or 0 for zero-length
 * rays. Format: s15.16 origin, s1.30 direction. Rounding: exact. Overflow: none in range.
 * Cost (in the caller's phase): FR_RAYS, FR_Q_TOD x3, VALU x3, VBCAST x8 and lt_ray16_q16_setup
 * (VDIV x3, VCMP x9, VBCAST x9). Returns: LT_OK, LT_E_ARG, LT_E_RANGE. */
lt_status_t lt_frusta_rays16_q16(const lt_frusta_table_q16_t *tb, const lt_q16_t o[3],
                                 unsigned set, lt_ray16_q16_t *r, lt_mask16_t *k);

/* One of those rays as a single ray (sample j of set s from origin o), with lt_ray1_q16_setup
 * applied; zero-length rays get tmax = 0 (never hit). The per-ray reference of the tests.
 * Cost (in the caller's phase): lt_ray1_q16_setup's BVH_RAY1_SETUP (SDIV x3, SALU x9).
 * Returns: LT_OK, LT_E_ARG, LT_E_RANGE. */
lt_status_t lt_frusta_ray1_q16(const lt_frusta_table_q16_t *tb, const lt_q16_t o[3], unsigned set,
                               unsigned j, lt_ray1_q16_t *r);

/* Packet baseline: any hit of the lanes in k of a packet whose lanes share the origin o (one
 * pixel's samples, from lt_frusta_rays16_q16), through a BVH, with early termination (the any-hit
 * path of lt_bvh_occluded16_q16) and, with BACKFACE in flags, triangles facing away from o skipped
 * (decided by the sign of the kernel's own tnum, so it equals per-ray culling of det < 0). With
 * TRIPAR in flags (watertight test only), a leaf of n <= 16 triangles reached by fewer than n
 * live lanes is tested ray by ray, its front triangles in the lanes (lt__wt16_meet_tris): the same
 * occluded lanes (event TRIPAR; cost FR_PACKET_TRIPAR_TEST per leaf, per ray FR_PTRIS_RAY, the
 * test, FR_PTRIS_ANY when it meets a lane).
 * Events: TRI_FETCH, TRI_KEPT, CULL_BACK. Without BACKFACE *occluded equals lt_bvh_occluded16_q16.
 * Cost: TRAVERSE per call VBCAST x2; lt_slab16_q16 per box test; per node BVH_TRAV_NODE,
 * interior: BVH_TRAV_CHILDREN16 (+ BVH_TRAV_ORDER, FR_TRAV_PUSH with both children entered),
 * leaf: BVH_TRAV_ANY_EXIT after it; FR_TRAV_POP per entry popped. INTERSECT per leaf triangle:
 * BVH_TRAV_LEAF_TRI (BACKFACE: + FR_PACKET_TRI_LOAD, FR_TNUM_SIGN), lt_tri16_q16 when kept,
 * BVH_TRAV_ANY_RETIRE when it occludes lanes.
 * Returns: as lt_bvh_occluded16_q16. */
lt_status_t lt_frusta_packet_occluded16_q16(const lt_bvh_t *bvh, const lt_tri_q16_t *tris,
                                            uint32_t flags, const lt_q16_t o[3],
                                            lt_ray16_q16_t *r, lt_mask16_t k,
                                            lt_mask16_t *occluded);

/* Direct-light geometry term of 16 points toward the light centre m with unit normal nl:
 * w = m - p, G = max(0, n.w) max(0, -nl.w) / |w|^2 (the cosines at both ends; no distance
 * falloff, which keeps G in [0, 1]). Format: p s15.16, n and nl s1.30 unit -> G s15.16 in [0, 1];
 * dots exact in int64, one division. Rounding: dots half up to s15.16, G half up. Overflow: none
 * for |w| <= 2^(GEOM+1). Cost (in the caller's phase, SHADE in the renderer): VMUL x10, VMULW x6,
 * VSHIFT x2, VALU x4, VCMP x3, VBCAST x7 and FR_Q_GTERM_DIV (VDIV x1).
 * Returns: mask of lanes of k with G > 0 (those need shadow rays). */
lt_mask16_t lt_frusta_direct16_q16(const lt_vq16_t p[3], const lt_vq30_t n[3], const lt_q16_t m[3],
                                   const lt_q30_t nl[3], lt_mask16_t k, lt_vq16_t *g);

/* Discontinuity filter parameters (both paths use the same meaning). */
typedef struct lt_frusta_filter_q16 {
    lt_q16_t depth_rel; /* neighbour q joins pixel p iff |z_q - z_p| <= depth_rel x z_p (s15.16) */
    lt_q30_t cos_min;   /* ... and n_p . n_q >= cos_min (s1.30) */
} lt_frusta_filter_q16_t;

/* 4x4 discontinuity filter ([Benthin09], section 4.5) of row y, pixels x0 .. x0 + 15 (lanes): each
 * output is the mean of e over the pixels q of the window x - 1 .. x + 2, y - 1 .. y + 2 (inside
 * the image) that are valid (valid[q] != 0) and pass both thresholds against p; p itself always
 * joins. Every 4x4 window holds each interleaved set once, so a pixel with all 16 neighbours joined
 * averages all 256 samples. Invalid pixels output 0. Arrays are row-major w x h.
 * Format: e, z s15.16, n s1.30 (unit) -> out s15.16. Rounding: mean half up. Overflow: none
 * (sums of <= 16 values saturate; never for e in [0, 1]). Cost: VBCAST x1 in the caller's phase;
 * FILTER per call: FR_VMASK, FR_LOADX x4, VMUL x1, VBCAST x2, VDIV x1 (the mean), VSTORE x1; per
 * window offset on an image row: FR_FILTER_OFFSET, FR_VMASK, and with a valid neighbour
 * FR_LOADX x5, VALU x4, VCMP x2, VMUL x3 and VMULW x2 (the normals' dot), VBCAST x2. */
void lt_frusta_filter16_q16(const lt_q16_t *e, const lt_q16_t *z, const lt_q30_t *nx,
                            const lt_q30_t *ny, const lt_q30_t *nz, const uint8_t *valid,
                            uint32_t w, uint32_t h, uint32_t x0, uint32_t y,
                            const lt_frusta_filter_q16_t *par, lt_q16_t *out);

/* ---- primary visibility with frusta (P-Frusta) -------------------------------------------- */

/* Primary frusta ([Benthin09], Appendix A, "common origin"): one frustum per 4x4 pixel tile, 16
 * frusta per call = the 4 x 4 tiles of a 16 x 16 pixel block (lane f: tile (f & 3, f >> 2) of the
 * block; ray j of a tile: pixel (j & 3, j >> 2) of the tile). Every ray starts at the eye, and
 * pixel (x, y) has the direction d0 + x dx + y dy: a linear pinhole camera in exact integer (s1.30)
 * arithmetic, so every ray of a tile is an exact convex (bilinear) combination of the tile's four
 * corner rays and the packet baseline, the per-ray reference and the frusta trace the very same
 * rays. Closest hit, per ray: the smallest t, and among equal t the smallest triangle id (what the
 * single-ray kernel over every triangle in index order returns). */
#define LT_FRUSTA_PMAX_DIM 16384u /* largest image width / height of a view */

/* A linear pinhole view, 60 bytes. Pixel (x, y), 0 <= x < width, 0 <= y < height: ray from o with
 * direction d0 + x dx + y dy (not unit length; t is in units of |d|). */
typedef struct lt_frusta_view_q16 {
    lt_q16_t o[3];         /* eye, s15.16 world units, |o| <= 2^GEOM */
    lt_q30_t d0[3];        /* direction of pixel (0, 0), s1.30 raw */
    lt_q30_t dx[3], dy[3]; /* direction step per pixel in x and in y, s1.30 raw */
    uint32_t width;        /* image width in pixels, 1..LT_FRUSTA_PMAX_DIM */
    uint32_t height;       /* image height in pixels, 1..LT_FRUSTA_PMAX_DIM */
    uint32_t flags;        /* LT_FRUSTA_BACKFACE | CORNER | CR | LEAFRAY | SPLIT (see
                              below) */
} lt_frusta_view_q16_t;
LT_STATIC_ASSERT(sizeof(lt_frusta_view_q16_t) == 60, "q16 view is 60 bytes");

/* Per-frame table of a view, 256 bytes: the ray deltas inside a tile and the view itself. */
typedef struct lt_frusta_vtable_q16 {
    lt_vq30_t gx, gy, gz;   /* lane j: (j & 3) dx + (j >> 2) dy, s1.30 raw (ray j minus ray 0) */
    lt_q16_t o[3];          /* the view's eye */
    lt_q30_t d0[3], dx[3], dy[3]; /* the view's directions */
    uint32_t width, height; /* the view's image size */
    uint32_t flags;         /* the view's flags */
    uint32_t pad_;          /* private */
} lt_frusta_vtable_q16_t;
LT_STATIC_ASSERT(sizeof(lt_frusta_vtable_q16_t) == 256, "q16 view table is 256 bytes");

/* 16 primary frusta (a 16 x 16 pixel block), 3592 bytes: set up by lt_frusta_psetup16_q16,
 * traced by lt_frusta_trace16_q16, results in t[] and id[]. */
typedef struct lt_frusta_prim16_q16 {
    lt_vq30_t cx, cy, cz;          /* lane f: direction of ray 0 of tile f, s1.30 raw */
    lt_vq16_t tmin, tmax;          /* lane f: t interval of the frustum; tmax = the farthest
                                      current hit among its live rays (shrinks during the trace) */
    lt_vq16_t rlo[3], rhi[3];      /* reciprocals of the direction interval ends, s15.16 */
    lt_vq30_t kx[4], ky[4], kz[4]; /* corner rays, s1.30 raw (rays of the tile's corner pixels) */
    lt_vq16_t t[LT_LANES];         /* frustum f, lane j: nearest hit of ray j, s15.16 in units of
                                      |d| (LT_Q16_MAX - 1: none) */
    lt_vi32_t id[LT_LANES];        /* frustum f, lane j: triangle id of that hit, -1 for none */
    lt_mask16_t alo[3], aup[3];    /* per axis: (lo - o) x rhi is a lower / an upper t bound */
    lt_mask16_t blo[3], bup[3];    /* per axis: (hi - o) x rlo is a lower / an upper t bound */
    lt_mask16_t active;            /* frusta with a pixel on the image */
    uint16_t live[LT_LANES];       /* per frustum: rays whose pixel lies on the image */
    uint16_t pad_[3];              /* private */
    uint32_t bx, by;               /* top-left pixel of the block */
} lt_frusta_prim16_q16_t;
LT_STATIC_ASSERT(sizeof(lt_frusta_prim16_q16_t) == 3592, "q16 primary frusta are 3592 bytes");

/* Check a view and build its table. Every direction the frusta may use (all pixels of the 4x4
 * tiles that touch the image) must have each component in (-2^30, 2^30) raw, i.e. |d| < 1 per
 * axis: checked exactly at the four corner pixels (the directions are affine in x, y).
 * Format: s15.16 eye, s1.30 raw directions. Rounding: exact (int64). Overflow: none.
 * Cost: none charged (once per frame). Returns: LT_OK, LT_E_ARG (NULL, unknown flags, width or
 * height 0 or above LT_FRUSTA_PMAX_DIM), LT_E_RANGE (eye outside the geometry bound, a direction
 * component out of range). */
lt_status_t lt_frusta_vtable_q16(const lt_frusta_view_q16_t *view, lt_frusta_vtable_q16_t *vt);

/* Set up the 16 frusta of the 16 x 16 block whose top-left pixel is (bx, by) (multiples of 4):
 * live rays = pixels on the image, active = frusta with a live ray, tmin = 0, tmax = t[] =
 * LT_Q16_MAX - 1, id[] = -1; corner rays through the tile's corner pixels, or, with
 * LT_FRUSTA_CR, through the corners of the bounding rectangle of the live pixels (the paper's CR
 * applied to the only event that removes primary rays: the image border); direction intervals
 * per axis = min / max over the corner rays (exact), and their reciprocals.
 * Format: s1.30 directions, s15.16 reciprocals. Rounding: exact except the reciprocals (half up).
 * Overflow: none. Cost: SETUP phase, per call FR_PSETUP_TILE x16, FR_PSETUP_CR x16,
 * FR_PSETUP_CORNERS, FR_Q_PBASEV x3 and VALU x18, VDIV x6 (the reciprocals), VCMP x24,
 * VBCAST x46.
 * Returns: LT_OK, LT_E_ARG (NULL, bx or by not a multiple of 4). */
lt_status_t lt_frusta_psetup16_q16(const lt_frusta_vtable_q16_t *vt, uint32_t bx, uint32_t by,
                                   lt_frusta_prim16_q16_t *P);

/* Multi-frusta closest hit of every live ray of the 16 frusta: interval slab test with the common
 * origin (the box planes minus the eye are scalars, TRAVERSE, one AABB event per box), clipped to
 * each frustum's [tmin, tmax]; a (node, frusta mask, nearest entry t) stack, near child first; a
 * popped entry keeps only frusta whose tmax still reaches its entry distance. Leaves (INTERSECT),
 * triangle by triangle: the origin-only terms of the kernel (tvec, qvec, tnum) once as scalars; a
 * hit needs det of tnum's sign, so tnum == 0 culls the triangle for all frusta, and with
 * LT_FRUSTA_BACKFACE tnum < 0 does (exactly per-ray det <= 0 culling, decided once: all rays
 * share the eye); with LT_FRUSTA_CORNER the kernel's edge functions at the four corner rays of
 * all 16 frusta against proven margins; then per surviving frustum (bit-scan) its 16 rays
 * generated (ray 0 + the table's deltas) and tested with lt_tri16's arithmetic; a ray takes a hit
 * with t < its t, or t equal and a smaller id. After the leaf, frusta that took a hit set tmax to
 * the largest t of their live rays. Events: as lt_frusta_occluded16_q16 (TRI_FETCH, TRI_KEPT,
 * CULL_BACK, CULL_CORNER per frustum-triangle pair, TRIS per 16-ray test).
 * Cost (as lt_frusta_occluded16_q16's terms): TRAVERSE per call VBCAST x2; per box test (pr_box)
 * FR_PBOX_LOAD, VBCAST x10, VALU x16, VMUL x6, VCMP x1; per node BVH_TRAV_NODE, interior:
 * BVH_TRAV_CHILDREN16 (+ BVH_TRAV_ORDER, BVH_TRAV16_PUSH with both children entered);
 * FR_PTRAV_POP per entry popped. INTERSECT per leaf triangle: FR_PLEAF_TRI, FR_PTQ; past the sign
 * test FR_PLEAF_KEPT (+ with CORNER pr_cull: FR_Q_TRI_A, FR_PCULL, FR_Q_PNRM, FR_Q_ASAT,
 * FR_Q_PMARG, FR_PCULL_CORNER per corner evaluated and their lane ops); kept: VBCAST x13, a
 * bit-scan of the frusta (MASK x3 per frustum + 1) and per frustum FR_PLEAF_FRUSTUM, on first use
 * its rays (pr_gen: FR_PGEN, VBCAST x3, VALU x3), the test (pr_tri: FR_PTRI, 3 rounded cross
 * products, 2 dot products, d . qvec, VCMP x4, VBCAST x3, VMULW x1; sigma < 0: VMULW x3,
 * VBCAST x3; candidates: TRI_Q_TDIV16, VCMP x3, VBCAST x2, FR_PTRI_HITS, VALU x2, + FR_IDGT on a
 * tie); then a bit-scan of the frusta that took a hit, per frustum FR_PLEAF_TMAX and VRED x1.
 * With LEAFRAY, before the leaf's triangles (with SPLIT too: FR_WIDE, and only the tiles wide
 * at the leaf), per frustum in the leaf's mask: FR_LEAF_RAYBOX, VBCAST x1 and lt_slab16_q16 on the leaf's box with its live rays from tmin up to each ray's
 * nearest hit so far (dropped from the leaf when none meets it), and on the frustum's first leaf
 * of the call its packet: pr_gen, VBCAST x5, lt_ray16_q16_setup. With SPLIT: once per call
 * VBCAST x3 and FR_DWID; per node FR_SPLIT_TEST and, with more than LT_FRUSTA_SPLIT_MAX and at
 * most LT_FRUSTA_PSPLIT_WIDE tiles, fr_wide (FR_WIDE); per tile going on as a packet FR_SPLIT, VBCAST x1, on first use its packet,
 * then the packet baseline's closest-hit walk from that node, FR_PLEAF_TMAX and VRED x1.
 * Format: as lt_slab16 / lt_tri16. Rounding: conservative (docs/frusta.md). Overflow: none.
 * Returns: LT_OK, LT_E_ARG (NULL, a tree of the other path), LT_E_DEPTH (foreign tree too deep). */
lt_status_t lt_frusta_trace16_q16(const lt_bvh_t *bvh, const lt_tri_q16_t *tris,
                                  const lt_frusta_vtable_q16_t *vt, lt_frusta_prim16_q16_t *P);

/* The 16 rays of the tile whose top-left pixel is (tx, ty) (multiples of 4) as a packet (lane j:
 * pixel (tx + (j & 3), ty + (j >> 2))): exactly the rays the frusta generate, tmin = 0, tmax =
 * LT_Q16_MAX - 1, lt_ray16_q16_setup applied; *k = lanes whose pixel lies on the image.
 * Format: s15.16 origin, s1.30 direction. Rounding: exact. Cost (in the caller's phase):
 * FR_PRAYS, VALU x3, VBCAST x8 and lt_ray16_q16_setup (VDIV x3, VCMP x9, VBCAST x9).
 * Returns: LT_OK, LT_E_ARG (NULL, tx or ty not a multiple of 4). */
lt_status_t lt_frusta_prays16_q16(const lt_frusta_vtable_q16_t *vt, uint32_t tx, uint32_t ty,
                                  lt_ray16_q16_t *r, lt_mask16_t *k);

/* Pixel (x, y)'s ray as a single ray (the same bits as its packet lane), lt_ray1_q16_setup
 * applied: the per-ray reference of the tests. Cost (in the caller's phase): lt_ray1_q16_setup's
 * BVH_RAY1_SETUP (SDIV x3, SALU x9). Returns: LT_OK, LT_E_ARG (NULL, off the image). */
lt_status_t lt_frusta_pray1_q16(const lt_frusta_vtable_q16_t *vt, uint32_t x, uint32_t y,
                                lt_ray1_q16_t *r);

/* Packet baseline for primary rays (P-Packet): closest hit of the lanes in k of a packet whose
 * lanes share the origin o, through a BVH, with the ordered traversal of lt_bvh_trace16_q16 and
 * lt_tri16_q16 per triangle; with LT_FRUSTA_BACKFACE in flags a triangle facing away from o
 * (the scalar sign of the kernel's tnum <= 0) is skipped for the whole packet; a lane takes a hit
 * with t < tmax, or t == tmax and a smaller id than its current one (for that triangle tmax is
 * raised by one ulp around the kernel call), so ties resolve as in the per-ray reference.
 * hit->id = triangle or -1, r->tmax = its t. Without BACKFACE: the same t as lt_bvh_trace16_q16
 * bit for bit, and the same id except where two triangles give the same t.
 * Events: TRI_FETCH, TRI_KEPT, CULL_BACK. Cost: VBCAST x1 in the caller's phase; TRAVERSE per
 * call VBCAST x2; lt_slab16_q16 per box test; per node BVH_TRAV_NODE, interior:
 * BVH_TRAV_CHILDREN16 (+ BVH_TRAV_ORDER, BVH_TRAV16_PUSH with both children entered);
 * BVH_TRAV16_POP per entry popped. INTERSECT per leaf triangle: BVH_TRAV_LEAF_TRI (BACKFACE: +
 * FR_PACKET_TRI_LOAD, FR_TNUM_SIGN), when kept FR_IDGT, FR_PACKET_TIE, lt_tri16_q16 (+ on ties
 * lt_vq16_add_sat_m, lt_vq16_set1 and lt_vq16_blend around it). Returns: as lt_bvh_trace16_q16. */
lt_status_t lt_frusta_packet_trace16_q16(const lt_bvh_t *bvh, const lt_tri_q16_t *tris,
                                         uint32_t flags, const lt_q16_t o[3], lt_ray16_q16_t *r,
                                         lt_mask16_t k, lt_hit16_t *hit);

/* ---- float32 ------------------------------------------------------------------------------ */
#if LT_CFG_FLOAT32
typedef struct lt_frusta_light_f32 {
    float c[3], eu[3], ev[3]; /* corner and edges, world units (any edges) */
    uint32_t flags;           /* as the q16 light */
    uint32_t end_shift;       /* as the q16 light */
} lt_frusta_light_f32_t;
LT_STATIC_ASSERT(sizeof(lt_frusta_light_f32_t) == 44, "f32 light is 44 bytes");

typedef struct lt_frusta_table_f32 {
    lt_vf32_t gx[LT_FRUSTA_SETS], gy[LT_FRUSTA_SETS], gz[LT_FRUSTA_SETS]; /* deltas
                                   (su/512) eu + (sv/512) ev, rounded to nearest */
    lt_vi32_t su[LT_FRUSTA_SETS], sv[LT_FRUSTA_SETS]; /* numerators 1..511 */
    lt_vf32_t gmin[3], gmax[3];  /* lane s: min / max of set s's deltas */
    lt_vf32_t kd[4][3];          /* lane s: corner deltas of set s's bounding rectangle */
    float ld[4][3];              /* the light's corner deltas */
    float c[3], eu[3], ev[3];    /* the light */
    int32_t unused_[6];          /* private (layout twin of the q16 table) */
    uint32_t flags, end_shift;
} lt_frusta_table_f32_t;
LT_STATIC_ASSERT(sizeof(lt_frusta_table_f32_t) == 6388, "f32 frusta table is 6388 bytes");

typedef struct lt_frusta16_f32 {
    lt_vf32_t ox, oy, oz;
    lt_vf32_t cx, cy, cz;
    lt_vf32_t tmin, tmax;
    lt_vf32_t rlo[3], rhi[3];
    lt_vf32_t kx[4], ky[4], kz[4];
    lt_vf32_t scale;                /* direction = (light point - o) x scale (a power of two) */
    lt_mask16_t alo[3], aup[3];
    lt_mask16_t blo[3], bup[3];
    lt_mask16_t active;
    uint16_t live[LT_LANES];
    uint16_t occl[LT_LANES];
    uint16_t pad_[3];
} lt_frusta16_f32_t;
LT_STATIC_ASSERT(sizeof(lt_frusta16_f32_t) == 1824, "f32 frusta packet is 1824 bytes");

/* float32 twins of the functions above, from the same source. The margins are relative (2^-20 on
 * box bounds, 2^-16 of the magnitude bound on edge functions) instead of proven; the tests check
 * frusta = per-ray visibility on the same cases as s15.16. Returns: as the q16 functions
 * (lt_frusta_table_f32: LT_E_ARG also for non-finite input). Cost: as the q16 functions with the
 * float classes (FADD for VALU and the wide adds, FMUL for VMUL, FCMP for VCMP, FDIV for VDIV and
 * TRI_Q_TDIV16; a cross product FMUL x2, FADD x1, a dot product FMUL x3, FADD x2) and FR_F_*
 * recipes; the differences: setup16 FR_F_SCALE, FR_F_TEND, FR_F_TMAX, FMUL x18, FADD x57, FDIV
 * x6, FCMP x24, VBCAST x32; fr_box + FADD x2, FMUL x2 (the relative margins); fr_gen VBCAST x6,
 * FMUL x3; the tnum < 0 flip of fr_tri FADD x4 only; rays16 FR_RAYS, FADD x3, FMUL x3, VBCAST
 * x11 and lt_ray16_f32_setup; direct16 FADD x10, FMUL x10, FDIV x1, FCMP x3, VBCAST x7; filter16
 * per offset with a valid neighbour FR_LOADX x5, FADD x5, VALU x1, FCMP x2, FMUL x3, VBCAST x2. */
lt_status_t lt_frusta_table_f32(const lt_frusta_light_f32_t *light, const lt_qmc_sets_t *sets,
                                lt_frusta_table_f32_t *tb);
lt_status_t lt_frusta_setup16_f32(const lt_frusta_table_f32_t *tb, lt_mask16_t k,
                                  lt_frusta16_f32_t *F);
lt_status_t lt_frusta_restrict16_f32(const lt_frusta_table_f32_t *tb, uint16_t samples,
                                     lt_frusta16_f32_t *F);
lt_status_t lt_frusta_occluded16_f32(const lt_bvh_t *bvh, const lt_tri_f32_t *tris,
                                     const lt_frusta_table_f32_t *tb, lt_frusta16_f32_t *F);
lt_status_t lt_frusta_rays16_f32(const lt_frusta_table_f32_t *tb, const float o[3], unsigned set,
                                 lt_ray16_f32_t *r, lt_mask16_t *k);
lt_status_t lt_frusta_ray1_f32(const lt_frusta_table_f32_t *tb, const float o[3], unsigned set,
                               unsigned j, lt_ray1_f32_t *r);
lt_status_t lt_frusta_packet_occluded16_f32(const lt_bvh_t *bvh, const lt_tri_f32_t *tris,
                                            uint32_t flags, const float o[3], lt_ray16_f32_t *r,
                                            lt_mask16_t k, lt_mask16_t *occluded);
lt_mask16_t lt_frusta_direct16_f32(const lt_vf32_t p[3], const lt_vf32_t n[3], const float m[3],
                                   const float nl[3], lt_mask16_t k, lt_vf32_t *g);

/* Primary frusta in float32: directions d0 + x dx + y dy evaluated as ((d0 + x dx) + y dy) + g_j,
 * the same operations in the frusta, the packets and the single rays (so the same bits); exact,
 * and then every ray a convex combination of its corner rays, when d0, dx, dy are multiples of
 * 2^-23 and every component stays below 1 (the renderer snaps them so). */
typedef struct lt_frusta_view_f32 {
    float o[3];            /* eye */
    float d0[3];           /* direction of pixel (0, 0) */
    float dx[3], dy[3];    /* steps per pixel */
    uint32_t width, height; /* 1..LT_FRUSTA_PMAX_DIM */
    uint32_t flags;        /* as the q16 view */
} lt_frusta_view_f32_t;
LT_STATIC_ASSERT(sizeof(lt_frusta_view_f32_t) == 60, "f32 view is 60 bytes");

typedef struct lt_frusta_vtable_f32 {
    lt_vf32_t gx, gy, gz;   /* lane j: (j & 3) dx + (j >> 2) dy */
    float o[3];
    float d0[3], dx[3], dy[3];
    uint32_t width, height;
    uint32_t flags;
    uint32_t pad_;
} lt_frusta_vtable_f32_t;
LT_STATIC_ASSERT(sizeof(lt_frusta_vtable_f32_t) == 256, "f32 view table is 256 bytes");

typedef struct lt_frusta_prim16_f32 {
    lt_vf32_t cx, cy, cz;
    lt_vf32_t tmin, tmax;
    lt_vf32_t rlo[3], rhi[3];
    lt_vf32_t kx[4], ky[4], kz[4];
    lt_vf32_t t[LT_LANES];         /* nearest hit per ray (3.0e38: none) */
    lt_vi32_t id[LT_LANES];
    lt_mask16_t alo[3], aup[3];
    lt_mask16_t blo[3], bup[3];
    lt_mask16_t active;
    uint16_t live[LT_LANES];
    uint16_t pad_[3];
    uint32_t bx, by;
} lt_frusta_prim16_f32_t;
LT_STATIC_ASSERT(sizeof(lt_frusta_prim16_f32_t) == 3592, "f32 primary frusta are 3592 bytes");

/* float32 twins of the primary-frusta functions (relative margins as for shadows; the tests
 * check frusta = per-ray closest hit on the same cases as s15.16). lt_frusta_vtable_f32 also
 * returns LT_E_ARG for non-finite input and LT_E_RANGE for |d| >= 1. Cost: as the q16 functions
 * with the float classes of the shadow twins; psetup16 FR_F_PBASEV x3, FADD x18, FDIV x6,
 * FCMP x24, VBCAST x58; pr_box FADD x18, FMUL x8, FCMP x1, VBCAST x10; prays16 FR_PRAYS, FADD x3,
 * VBCAST x8 and lt_ray16_f32_setup; ties of the packet baseline FR_F_NEXTUP. */
lt_status_t lt_frusta_vtable_f32(const lt_frusta_view_f32_t *view, lt_frusta_vtable_f32_t *vt);
lt_status_t lt_frusta_psetup16_f32(const lt_frusta_vtable_f32_t *vt, uint32_t bx, uint32_t by,
                                   lt_frusta_prim16_f32_t *P);
lt_status_t lt_frusta_trace16_f32(const lt_bvh_t *bvh, const lt_tri_f32_t *tris,
                                  const lt_frusta_vtable_f32_t *vt, lt_frusta_prim16_f32_t *P);
lt_status_t lt_frusta_prays16_f32(const lt_frusta_vtable_f32_t *vt, uint32_t tx, uint32_t ty,
                                  lt_ray16_f32_t *r, lt_mask16_t *k);
lt_status_t lt_frusta_pray1_f32(const lt_frusta_vtable_f32_t *vt, uint32_t x, uint32_t y,
                                lt_ray1_f32_t *r);
lt_status_t lt_frusta_packet_trace16_f32(const lt_bvh_t *bvh, const lt_tri_f32_t *tris,
                                         uint32_t flags, const float o[3], lt_ray16_f32_t *r,
                                         lt_mask16_t k, lt_hit16_t *hit);

typedef struct lt_frusta_filter_f32 {
    float depth_rel; /* as lt_frusta_filter_q16_t */
    float cos_min;
} lt_frusta_filter_f32_t;

void lt_frusta_filter16_f32(const float *e, const float *z, const float *nx, const float *ny,
                            const float *nz, const uint8_t *valid, uint32_t w, uint32_t h,
                            uint32_t x0, uint32_t y, const lt_frusta_filter_f32_t *par, float *out);
#endif

#ifdef __cplusplus
}
#endif
#endif /* LT_FRUSTA_H */
