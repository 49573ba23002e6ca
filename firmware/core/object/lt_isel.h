/* lt_isel.h - internal header: the one intersector selection of every traversal (the chunks,
 * BVH, quantised BVH, kd-tree and grid walks, single rays, and the multi-frusta kernels). A
 * traversal keeps one lt__isel16_* (or lt__isel1_*) per call: the intersector (LT_ISECT_WT or
 * LT_ISECT_MT, from the structure's handle) and, for the watertight test, the packet's (or ray's)
 * permutation and shear, computed once per call before its first triangle test, never per
 * triangle. Then each triangle test calls lt__isel16_tri_*: lt_tri16_wt_* or lt_tri16_* on the
 * same ray, the one body of each test. Not part of the public API. Builds: all.
 */
#ifndef LT_ISEL_H
#define LT_ISEL_H

#include "lt/lt_bvh8.h"
#include "lt/lt_wt.h"

/* Watertight meet test of lt_wt.inc without the interval (lt_wt.c): lanes of k whose ray meets
 * tri, t written for those lanes. For kernels that apply their own acceptance rule to t (the
 * frusta). */
lt_mask16_t lt__wt16_meet_q16(const lt_wt16_q16_t *w, lt_mask16_t k, const lt_tri_q16_t *tri,
                              lt_vq16_t *t);
#if LT_CFG_FLOAT32
lt_mask16_t lt__wt16_meet_f32(const lt_wt16_f32_t *w, lt_mask16_t k, const lt_tri_f32_t *tri,
                              lt_vf32_t *t);
#endif

/* The same test in the triangle-parallel layout (lt_wt.inc): ray j of w (its lane j) against
 * tris[idx[i]] in lane i < n (n <= 16), each lane giving the bits lane j of lt__wt16_meet gives
 * against that triangle. Returns the lanes (triangles) the ray meets, t written for those lanes.
 * Cost: LANE_GATHER x 9n, WT_TRIS_VERTS, WT_ZERO_AREA per triangle, WT_TRIS_RAY, VBCAST x6, then
 * the packet test's shear, edge and t stage; events TRIS 1, TRI_RAYS n. */
lt_mask16_t lt__wt16_meet_tris_q16(const lt_wt16_q16_t *w, unsigned j, const lt_tri_q16_t *tris,
                                   const uint32_t *idx, unsigned n, lt_vq16_t *t);
#if LT_CFG_FLOAT32
lt_mask16_t lt__wt16_meet_tris_f32(const lt_wt16_f32_t *w, unsigned j, const lt_tri_f32_t *tris,
                                   const uint32_t *idx, unsigned n, lt_vf32_t *t);
#endif

/* The wide tree's leaf blocks (lt_bvh8.h) for one ray: the n triangles of the blocks at b in lane
 * order, each lane with lt_tri1_wt's arithmetic (the same bits), the shear, edge and sign stage of
 * a block's four lanes as 4-lane loops; then the lanes that meet the ray, in order, each taken when
 * tmin < t < *tmax (*tmax = t), as the triangle loop takes them; with any the first block with a
 * hit ends it. Returns the triangle id of the last hit taken (any: the first), or -1. Cost (in the
 * caller's phase): per block its 160-byte read, BVH_TRAV_LEAF_TRI and WT_TRI1 per triangle of the
 * block, WT_TRI1_T per lane that meets the ray (float32: WT_F_EDGE_FIX1 per lane with a zero edge
 * that is not zero-area); events TRIS, TRI_RAYS per triangle, HITS per hit taken. */
int32_t lt__wt_tris4_q16(const lt_wt1_q16_t *w, const lt_bvh8_tris4_q16_t *b, uint32_t n,
                         lt_q16_t tmin, lt_q16_t *tmax, int any);
/* 1 if the triangle has zero area (e1 x e2 == 0 exactly for its rebuilt vertices: the test of
 * lt_tri1_wt_q16). Uncharged. */
int lt__wt_zero_area_q16(const lt_tri_q16_t *tri);
#if LT_CFG_FLOAT32
int32_t lt__wt_tris4_f32(const lt_wt1_f32_t *w, const lt_bvh8_tris4_f32_t *b, uint32_t n,
                         float tmin, float *tmax, int any);
int lt__wt_zero_area_f32(const lt_tri_f32_t *tri);
#endif

/* LT_ISECT_WT32 in the selection (LT_CFG_WT32): its flag and grid shift, set from the structure's
 * isect value; with LT_CFG_WT32 0 neither exists and the walks compile as without it. */
#if LT_CFG_WT32
#define LT__ISEL_WT32_FIELDS                                                                       \
    uint32_t wt32; /* s15.16: the watertight test on the grid 2^g (LT_ISECT_WT32) */              \
    uint32_t g;    /* its grid shift */
#define LT__ISEL_WT32_INIT(s, isect)                                                               \
    ((s)->wt32 = LT_ISECT_KIND(isect) == LT_ISECT_WT32, (s)->g = LT_ISECT_WT32_SHIFT(isect))
#define LT__ISEL_IS_WT32(s) ((s)->wt32 != 0)
#define LT__ISEL_G(s) ((s)->g)
#else
#define LT__ISEL_WT32_FIELDS
#define LT__ISEL_WT32_INIT(s, isect) ((void)(s), (void)(isect))
#define LT__ISEL_IS_WT32(s) ((void)(s), 0)
#define LT__ISEL_G(s) ((void)(s), 0u)
#endif

/* One selection per packet and per single ray, for both numeric paths. */
#define LT__ISEL_DEFINE(SFX, RAY, TRI, WT16, WT1, T)                                               \
    typedef struct {                                                                               \
        uint32_t mt;    /* Moller-Trumbore chosen */                                               \
        uint32_t ready; /* the watertight setup is computed */                                     \
        LT__ISEL_WT32_FIELDS                                                                       \
        WT16 wt;        /* the packet's watertight setup */                                        \
    } lt__isel16_##SFX;                                                                        \
    LT_INLINE void lt__isel16_init_##SFX(lt__isel16_##SFX *s, uint32_t isect)                  \
    {                                                                                              \
        s->mt = isect == LT_ISECT_MT;                                                              \
        LT__ISEL_WT32_INIT(s, isect);                                                              \
        s->ready = 0;                                                                              \
    }                                                                                              \
    /* The packet's watertight setup, computed on first use (also for kernels that test the       \
     * packet's rays one by one, lt__wt16_meet_tris_*). */                                         \
    LT_INLINE const WT16 *lt__isel16_wt_##SFX(lt__isel16_##SFX *s, const RAY *r)               \
    {                                                                                              \
        if (!s->ready) {                                                                           \
            (void)lt_ray16_wt_setup_##SFX(r, &s->wt);                                              \
            s->ready = 1;                                                                          \
        }                                                                                          \
        return &s->wt;                                                                             \
    }                                                                                              \
    LT_INLINE lt_mask16_t lt__isel16_tri_##SFX(lt__isel16_##SFX *s, RAY *r, lt_mask16_t k,     \
                                               const TRI *tri, int32_t id, lt_hit16_t *hit)        \
    {                                                                                              \
        if (s->mt)                                                                                 \
            return lt_tri16_##SFX(r, k, tri, id, hit);                                             \
        if (LT__ISEL_IS_WT32(s))                                                                   \
            return LT__ISEL16_WT32_##SFX(s, r, k, tri, id, hit);                                   \
        return lt_tri16_wt_##SFX(r, lt__isel16_wt_##SFX(s, r), k, tri, id, hit);                  \
    }

#define LT__ISEL1_DEFINE(SFX, RAY1, TRI, WT1)                                                      \
    typedef struct {                                                                               \
        uint32_t mt;    /* Moller-Trumbore chosen */                                               \
        uint32_t ready; /* the watertight setup is computed */                                     \
        LT__ISEL_WT32_FIELDS                                                                       \
        WT1 wt;         /* the ray's watertight setup */                                           \
    } lt__isel1_##SFX;                                                                         \
    LT_INLINE void lt__isel1_init_##SFX(lt__isel1_##SFX *s, uint32_t isect)                    \
    {                                                                                              \
        s->mt = isect == LT_ISECT_MT;                                                              \
        LT__ISEL_WT32_INIT(s, isect);                                                              \
        s->ready = 0;                                                                              \
    }                                                                                              \
    /* The ray's watertight setup, computed on first use (also for the wide tree's leaf blocks,  \
     * lt__wt_tris4_*). */                                                                         \
    LT_INLINE const WT1 *lt__isel1_wt_##SFX(lt__isel1_##SFX *s, const RAY1 *r)                 \
    {                                                                                              \
        if (!s->ready) {                                                                           \
            (void)lt_ray1_wt_setup_##SFX(r->o, r->d, &s->wt);                                      \
            s->ready = 1;                                                                          \
        }                                                                                          \
        return &s->wt;                                                                             \
    }                                                                                              \
    LT_INLINE int lt__isel1_tri_##SFX(lt__isel1_##SFX *s, RAY1 *r, const TRI *tri)             \
    {                                                                                              \
        if (s->mt)                                                                                 \
            return lt_tri1_##SFX(r, tri);                                                          \
        if (LT__ISEL_IS_WT32(s))                                                                   \
            return LT__ISEL1_WT32_##SFX(s, r, tri);                                                \
        return lt_tri1_wt_##SFX(lt__isel1_wt_##SFX(s, r), tri, r->tmin, &r->tmax);                 \
    }

/* LT_ISECT_WT32 per path: the s15.16 test on the grid; float32 structures never carry it
 * (LT_ISECT_VALID), and take the exact test if one did. */
#define LT__ISEL16_WT32_q16(s, r, k, tri, id, hit)                                                 \
    lt_tri16_wt32_q16((r), lt__isel16_wt_q16((s), (r)), LT__ISEL_G(s), (k), (tri), (id), (hit))
#define LT__ISEL1_WT32_q16(s, r, tri)                                                              \
    lt_tri1_wt32_q16(lt__isel1_wt_q16((s), (r)), LT__ISEL_G(s), (tri), (r)->tmin, &(r)->tmax)
#define LT__ISEL16_WT32_f32(s, r, k, tri, id, hit)                                                 \
    lt_tri16_wt_f32((r), lt__isel16_wt_f32((s), (r)), (k), (tri), (id), (hit))
#define LT__ISEL1_WT32_f32(s, r, tri)                                                              \
    lt_tri1_wt_f32(lt__isel1_wt_f32((s), (r)), (tri), (r)->tmin, &(r)->tmax)

LT__ISEL_DEFINE(q16, lt_ray16_q16_t, lt_tri_q16_t, lt_wt16_q16_t, lt_wt1_q16_t, lt_q16_t)
#if LT_CFG_FLOAT32
LT__ISEL_DEFINE(f32, lt_ray16_f32_t, lt_tri_f32_t, lt_wt16_f32_t, lt_wt1_f32_t, float)
#endif

#endif /* LT_ISEL_H */
