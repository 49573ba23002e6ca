/* lt_wt.h - watertight 16-lane ray/triangle test: Woop, Benthin, Wald, "Watertight Ray/Triangle
 * Intersection", JCGT 2(1) 2013 (translate, permute, shear, 2D edge functions), in s15.16 fixed
 * point with EXACT integer edge functions and in float32 with the paper's double fallback, both
 * compiled from one kernel source (firmware/core/object/lt_wt.inc). docs/watertight.md has the bit widths
 * and the proof sketch. Builds: all; float32 entry points only with LT_CFG_FLOAT32.
 */
#ifndef LT_WT_H
#define LT_WT_H

#include "lt_isect.h"

#ifdef __cplusplus
extern "C" {
#endif


/* Per-packet shear constants of the watertight test, from lt_ray16_wt_setup_q16. 432 bytes,
 * 4-byte aligned. Per lane: kz = the axis of largest |d| (ties prefer z, then y, then x),
 * (kx, ky) = the next two axes in cyclic order, swapped when d[kz] < 0 so that the winding is
 * kept. Recompute after changing a ray's origin or direction. */
typedef struct lt_wt16_q16 {
    lt_vq16_t ox, oy, oz;  /* origin permuted to (kx, ky, kz), s15.16 */
    lt_vq30_t sx, sy, sz;  /* Sx = d[kx]/d[kz], Sy = d[ky]/d[kz] (|S| <= 1), Sz = 1/(d[kz] 2^sh)
                              (1/2 < |Sz| < 2), s1.30, rounded half up */
    lt_mask16_t kx[3];     /* kx[a]: lanes whose sheared x axis is world axis a */
    lt_mask16_t ky[3];     /* ky[a]: lanes whose sheared y axis is world axis a */
    lt_mask16_t kz[3];     /* kz[a]: lanes whose ray axis is world axis a */
    lt_mask16_t bad;       /* lanes with d == 0: never hit */
    uint8_t sh[LT_LANES];  /* per lane: the shift sh >= 0 that brings |d[kz]| 2^sh into
                              (1/2, 2) (0 for every unit direction); t = round(T 2^sh / det) */
    uint16_t pad_[6];      /* private: keeps the size a multiple of 16 */
} lt_wt16_q16_t;
LT_STATIC_ASSERT(sizeof(lt_wt16_q16_t) == 6 * 64 + 48, "wt setup is 6 lane vectors + masks");

/* Permutation and shear constants of each lane of r (its origin and direction) into w.
 * Format: s1.30 / s1.30 -> s1.30 (Sx, Sy: round(d * 2^30 / dz)), 2^60 / (dz_raw 2^sh) (Sz).
 * Range: any nonzero direction in s1.30 (unit or not: the frusta's rays are not); the exact
 * power of two sh normalises d[kz] for Sz and is undone in t, so t is in units of |d| as in
 * lt_tri16_q16; for unit directions sh = 0. Lanes with d == 0 are flagged in w->bad.
 * Rounding: half up. Overflow: none. Cost: WT_SETUP_KZ, WT_SETUP_KXKY, WT_Q_NORM, WT_Q_RATIO x2,
 * WT_Q_RECIP, VALU x16 (abs, permuting blends), VCMP x5, VBCAST x1.
 * Returns: the mask of lanes flagged bad (they never hit). */
lt_mask16_t lt_ray16_wt_setup_q16(const lt_ray16_q16_t *r, lt_wt16_q16_t *w);

/* Watertight test of the lanes in k against one triangle, two-sided, edges inclusive: the contract
 * of lt_tri16_q16. Lanes that hit at tmin < t < tmax get tmax = t and hit->id = id; other lanes
 * and inactive lanes are untouched. The vertices are v0, v0 + e1, v0 + e2 (saturating adds: exact
 * for in-range data), so triangles that share a vertex must store it bit-identically.
 * Format: vertex - origin in s15.16 (exact), sheared x/y = A[kx|ky] - round(S * A[kz]) and
 * z = round(Sz * A[kz]) in s15.16 (s1.30 x s15.16 -> 46 fractional bits -> 16), edge functions
 * U, V, W = 2D cross products of sheared x/y: s31.32 in int64, EXACT; det = U + V + W exact;
 * T = U*Az + V*Bz + W*Cz exact in 128 bits (48 fractional bits); t = T / det.
 * Range: |vertex|, |origin| <= 2^LT_CFG_GEOM_MAX_LOG2 (= 4096) per axis keeps every value above
 * inside its format. Outside it results are defined (saturating / wrapping) but not meaningful.
 * Rounding: t = round(T 2^sh / det) half up from the exact quotient (in units of |d|); t always
 * lies between the vertices' z.
 * Hit rule: U, V, W all >= 0 or all <= 0, det != 0, and the triangle's area is not exactly zero
 * (e1 x e2 != 0, tested exactly): zero-area triangles never hit. No crack: a ray through a shared
 * edge or vertex of triangles with bit-identical shared vertices hits at least one of them
 * whenever it crosses the surface there (docs/watertight.md).
 * Overflow: none in range. Cost (measured in the sim, docs/watertight.md): a packet whose
 * active lanes share one axis permutation: SLOAD x9, SALU x15, SMUL x6 (vertices, zero-area
 * test), BRANCH x1, MASK x27, VBCAST x10, VALU x15, VMUL x12, VMULW x5, VCMP x8; each further
 * permutation in the packet adds up to VBCAST x9, VALU x9, MASK x3-9; a packet with a candidate
 * lane adds VMUL x9, VMULW x10 (exact T), VDIV x2 (128/64 division), VCMP x2, VALU x2, VBCAST x1.
 * Lane by lane (LT_LANEWISE(), lt_v16.h: the Cortex-M4 and Cortex-M55 DSP builds, and the
 * simulator modelling mcu-m4 or mcu-m55): after the vertices and zero-area test, WT_LANE per lane of k and WT_TRI1_T per lane
 * that meets (the same bits).
 * Returns: the mask of lanes whose ray was shortened by this triangle. */
lt_mask16_t lt_tri16_wt_q16(lt_ray16_q16_t *r, const lt_wt16_q16_t *w, lt_mask16_t k,
                            const lt_tri_q16_t *tri, int32_t id, lt_hit16_t *hit);


/* One ray's watertight setup (the scalar twin of a packet lane), 32 bytes. */
typedef struct lt_wt1_q16 {
    lt_q16_t o[3];   /* origin permuted to (kx, ky, kz), s15.16 */
    lt_q30_t s[3];   /* Sx, Sy, Sz as a packet lane's sx, sy, sz (s1.30) */
    uint8_t k[3];    /* kx, ky, kz: world axes */
    uint8_t sh;      /* the lane's shift (see lt_wt16_q16_t) */
    uint8_t bad;     /* d == 0: never hits */
    uint8_t pad_[3]; /* private */
} lt_wt1_q16_t;
LT_STATIC_ASSERT(sizeof(lt_wt1_q16_t) == 32, "single-ray wt setup is 32 bytes");

/* The setup of one ray (origin o, direction d): exactly what lt_ray16_wt_setup_q16 computes for a
 * lane holding that ray, so that lt_tri1_wt_q16 equals the packet test lane for lane, bit for
 * bit (the single-ray BVH walks use it). Format, Range, Rounding: as the packet setup.
 * Cost: WT_RAY1_SETUP (SALU x12, SDIV x3, BRANCH x2). Returns: 1 if the ray is bad (d == 0). */
int lt_ray1_wt_setup_q16(const lt_q16_t o[3], const lt_q30_t d[3], lt_wt1_q16_t *w);

/* One ray against one triangle: one lane of lt_tri16_wt_q16 (the same primitives in the same
 * order). Hit iff the lane would hit: then *tmax = t. Format, Range, Rounding: as the packet
 * test. Cost: WT_TRI1 (SLOAD x9, SALU x27, SMUL x12, BRANCH x2: the shear, the exact edge
 * functions) and WT_ZERO_AREA (none for a bad ray); a candidate adds WT_TRI1_T (SMUL x9,
 * SALU x12, SDIV x2, BRANCH x1: the exact 128-bit T and its division). Returns: 1 if tmin < t < *tmax (then *tmax = t). */
int lt_tri1_wt_q16(const lt_wt1_q16_t *w, const lt_tri_q16_t *tri, lt_q16_t tmin,
                   lt_q16_t *tmax);

/* ---- s15.16 on a grid: LT_ISECT_WT32 (docs/watertight.md, "A narrower test") ----------------
 * The same test with the sheared vertices snapped to a grid of step 2^g raw s15.16 (g from the
 * structure's isect value, LT_ISECT_WT32_SHIFT): a vertex whose snapped coordinates lie within
 * 16383 steps is snapped, any other keeps its exact sheared point. Each vertex is one 2D point per
 * ray, so the test is the exact watertight test on those points: no crack. With the three
 * vertices snapped and a unit direction (sh = 0), the edge functions and det are int32 (2D cross
 * products of 15-bit values, |U| < 2^29, |det| < 2^31), T = U z0 + V z1 + W z2 an int64 and
 * t = round(T / det) one 64/32-bit division; otherwise the exact test's int64 edges and 128-bit T
 * on the same points (the same t: the grid scale cancels).
 * Format: as lt_tri16_wt_q16; U, V, W in grid steps squared. Range: as lt_tri16_wt_q16, g <= LT_WT32_SHIFT_MAX (13; larger g are taken as 13).
 * Rounding: each sheared coordinate to the grid, half up; t half up from the exact quotient.
 * Error against the exact test: the hit point moves by at most 2^(g-1) raw per sheared axis per
 * vertex; a hit or miss changes only for rays within that of an edge, and t is the t of the
 * snapped triangle (tests/unit/test_wt32.c states and checks the bound).
 * Cost: as lt_tri16_wt_q16 up to the shear, then WT32_EDGES (VSHIFT x6, VALU x11, VCMP x12,
 * VMUL x6, MASK x10); a lane that meets adds WT32_T (VMUL x6, VMULW x2, VDIV x1); a lane off the
 * grid's range or with sh > 0 adds WT32_WIDE and, if it meets, WT32_WIDE_T (the exact T).
 * Returns: the mask of lanes whose ray was shortened by this triangle. */
lt_mask16_t lt_tri16_wt32_q16(lt_ray16_q16_t *r, const lt_wt16_q16_t *w, unsigned g, lt_mask16_t k,
                              const lt_tri_q16_t *tri, int32_t id, lt_hit16_t *hit);

/* The lanes of k that meet tri on the grid (lt_tri16_wt32_q16 without the interval), t written for
 * those lanes. */
lt_mask16_t lt__wt32_meet16_q16(const lt_wt16_q16_t *w, unsigned g, lt_mask16_t k,
                                const lt_tri_q16_t *tri, lt_vq16_t *t);

/* One ray: one lane of lt_tri16_wt32_q16, bit for bit. Cost: WT32_TRI1, a candidate WT32_TRI1_T
 * (or, off the grid's range or sh > 0, WT32_TRI1_WIDE and WT_TRI1_T). Returns: 1 if
 * tmin < t < *tmax (then *tmax = t). */
int lt_tri1_wt32_q16(const lt_wt1_q16_t *w, unsigned g, const lt_tri_q16_t *tri, lt_q16_t tmin,
                     lt_q16_t *tmax);

/* The grid for a triangle set: g such that, for LT_WT32_SHIFT_PCT % of its non-degenerate
 * triangles, the sheared vertices of the triangle around a ray that meets it (within twice its
 * largest edge component of the ray) fit the grid's range with a factor 2 to spare: g = b - 12
 * for that percentile's largest edge component < 2^b raw, 0 <= g <= LT_WT32_SHIFT_MAX. At most 13:
 * a snapped vertex moves by at most 2^(g-17) units per sheared axis, 2^-4 sqrt 2 < 0.09 units,
 * inside the 2^(GEOM-15) = 0.125-unit pad of the BVH's boxes, so no walk culls a box the snapped
 * triangle reaches out of (docs/watertight.md). Uncharged (a build-time choice). */
#define LT_WT32_SHIFT_PCT 99u
#define LT_WT32_SHIFT_MAX 13u
unsigned lt_wt32_shift_q16(const lt_tri_q16_t *tris, uint32_t n);

#if LT_CFG_FLOAT32
/* Float32 twin of lt_wt16_q16_t (same layout rules; no shift: Sz = 1/d[kz] in float). 416
 * bytes. */
typedef struct lt_wt16_f32 {
    lt_vf32_t ox, oy, oz;  /* origin permuted to (kx, ky, kz) */
    lt_vf32_t sx, sy, sz;  /* Sx = d[kx]/d[kz], Sy = d[ky]/d[kz], Sz = 1/d[kz] (IEEE division) */
    lt_mask16_t kx[3];     /* kx[a]: lanes whose sheared x axis is world axis a */
    lt_mask16_t ky[3];     /* ky[a]: lanes whose sheared y axis is world axis a */
    lt_mask16_t kz[3];     /* kz[a]: lanes whose ray axis is world axis a */
    lt_mask16_t bad;       /* lanes with d == 0 or NaN: never hit */
    uint16_t pad_[6];      /* private */
} lt_wt16_f32_t;
LT_STATIC_ASSERT(sizeof(lt_wt16_f32_t) == 6 * 64 + 32, "f32 wt setup is 6 lane vectors + masks");

/* Float32 twin of lt_ray16_wt_setup_q16. Range: any finite nonzero direction (t is then in units
 * of |d|). Rounding: IEEE. Cost: FADD x16, FCMP x5, FDIV x3, VBCAST x2, MASK x23.
 * Returns: the mask of lanes flagged bad. */
lt_mask16_t lt_ray16_wt_setup_f32(const lt_ray16_f32_t *r, lt_wt16_f32_t *w);

/* Float32 twin of lt_tri16_wt_q16: the paper's test in IEEE binary32. An edge function that
 * rounds to exactly 0.0f may have the wrong sign, so lanes with one are recomputed in double
 * (LT_CFG_WT_F64_FALLBACK), which makes every edge sign exact; zero area is tested in double.
 * Watertight when shared vertices reconstruct bit-identically (fl(v0 + e1) must give the same
 * float vertex in every triangle that uses it: true when e1 = v1 - v0 was exact in float).
 * Cost (one permutation, candidate lanes): SLOAD x9, SALU x15, SMUL x6, BRANCH x1, MASK x30,
 * VBCAST x11, VALU x1, FADD x23, FMUL x18, FDIV x1, FCMP x13; + FMUL x6, FADD x3 for packets with
 * a 0.0f edge function; mixed permutations as in the s15.16 test (FADD for the blends).
 * Returns: the mask of lanes whose ray was shortened by this triangle. */
lt_mask16_t lt_tri16_wt_f32(lt_ray16_f32_t *r, const lt_wt16_f32_t *w, lt_mask16_t k,
                            const lt_tri_f32_t *tri, int32_t id, lt_hit16_t *hit);

/* Float32 twins of the single-ray setup and test (one lane of the float packet test; the double
 * fallback for 0.0f edge functions charges WT_F_EDGE_FIX1). */
typedef struct lt_wt1_f32 {
    float o[3];      /* origin permuted to (kx, ky, kz) */
    float s[3];      /* Sx, Sy, Sz */
    uint8_t k[3];    /* kx, ky, kz */
    uint8_t bad;     /* d == 0 or NaN */
    uint8_t pad_[4]; /* private */
} lt_wt1_f32_t;
LT_STATIC_ASSERT(sizeof(lt_wt1_f32_t) == 32, "single-ray f32 wt setup is 32 bytes");

int lt_ray1_wt_setup_f32(const float o[3], const float d[3], lt_wt1_f32_t *w);
int lt_tri1_wt_f32(const lt_wt1_f32_t *w, const lt_tri_f32_t *tri, float tmin, float *tmax);
#endif

#ifdef __cplusplus
}
#endif
#endif /* LT_WT_H */
