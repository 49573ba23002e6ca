/* lt_isect_oracle.h - the ray/triangle test the structure tests compare against: the default
 * intersector of every walk (lt_isect.h: LT_ISECT_WT, the watertight test of lt_wt.h, its setup
 * made per call here), or Moller-Trumbore when a test sets ltt_isect = LT_ISECT_MT for the
 * structures it builds, or (s15.16) the grid test, ltt_isect = LT_ISECT_WT32_G(g). Brute-force
 * oracles call these in place of lt_tri16_* / lt_tri1_*.
 */
#ifndef LT_ISECT_ORACLE_H
#define LT_ISECT_ORACLE_H

#include "lt/lt_bvh.h"
#include "lt/lt_wt.h"

static uint32_t ltt_isect = LT_ISECT_WT;

static inline lt_mask16_t ltt_tri16_q16(lt_ray16_q16_t *r, lt_mask16_t k, const lt_tri_q16_t *tri,
                                        int32_t id, lt_hit16_t *hit)
{
    lt_wt16_q16_t w;
    if (ltt_isect == LT_ISECT_MT)
        return lt_tri16_q16(r, k, tri, id, hit);
    (void)lt_ray16_wt_setup_q16(r, &w);
    if (LT_ISECT_KIND(ltt_isect) == LT_ISECT_WT32)
        return lt_tri16_wt32_q16(r, &w, LT_ISECT_WT32_SHIFT(ltt_isect), k, tri, id, hit);
    return lt_tri16_wt_q16(r, &w, k, tri, id, hit);
}

static inline int ltt_tri1_q16(lt_ray1_q16_t *r, const lt_tri_q16_t *tri)
{
    lt_wt1_q16_t w;
    if (ltt_isect == LT_ISECT_MT)
        return lt_tri1_q16(r, tri);
    (void)lt_ray1_wt_setup_q16(r->o, r->d, &w);
    if (LT_ISECT_KIND(ltt_isect) == LT_ISECT_WT32)
        return lt_tri1_wt32_q16(&w, LT_ISECT_WT32_SHIFT(ltt_isect), tri, r->tmin, &r->tmax);
    return lt_tri1_wt_q16(&w, tri, r->tmin, &r->tmax);
}

#if LT_CFG_FLOAT32
static inline lt_mask16_t ltt_tri16_f32(lt_ray16_f32_t *r, lt_mask16_t k, const lt_tri_f32_t *tri,
                                        int32_t id, lt_hit16_t *hit)
{
    lt_wt16_f32_t w;
    if (ltt_isect == LT_ISECT_MT)
        return lt_tri16_f32(r, k, tri, id, hit);
    (void)lt_ray16_wt_setup_f32(r, &w);
    return lt_tri16_wt_f32(r, &w, k, tri, id, hit);
}

static inline int ltt_tri1_f32(lt_ray1_f32_t *r, const lt_tri_f32_t *tri)
{
    lt_wt1_f32_t w;
    if (ltt_isect == LT_ISECT_MT)
        return lt_tri1_f32(r, tri);
    (void)lt_ray1_wt_setup_f32(r->o, r->d, &w);
    return lt_tri1_wt_f32(&w, tri, r->tmin, &r->tmax);
}
#endif

#endif /* LT_ISECT_ORACLE_H */
