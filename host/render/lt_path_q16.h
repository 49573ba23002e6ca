/* lt_path_q16.h - the host's s15.16 numeric path (registry entry "q16"): the generic LTH_* names
 * of the host's per-path templates (lt_render_path.inc, lt_softshadow_path.inc) mapped onto the
 * core's _q16 entry points and types by token pasting, and the few conversions and lane helpers
 * whose arithmetic differs between fixed point and float. Include it, then a template, then
 * lt_path_undef.h (lt_render_paths.c shows the pattern). Host only.
 */
#ifndef LTH_Q16_HELPERS
#define LTH_Q16_HELPERS
#include <string.h>
#include "lt/lt.h"
#include "lt/lt_frusta.h"
#include "lt/lt_v16w.h"

/* s1.30 lanes as s15.16 lanes for the sign-agnostic int32 ops and back (a register rename) */
static inline lt_vq16_t lth_q16_as16(lt_vq30_t a)
{
    lt_vq16_t r;
    memcpy(&r, &a, sizeof r);
    return r;
}

static inline lt_vq30_t lth_q16_as30(lt_vq16_t a)
{
    lt_vq30_t r;
    memcpy(&r, &a, sizeof r);
    return r;
}

/* -n on the lanes of m (n elsewhere) */
static inline lt_vq30_t lth_q16_flip(lt_vq30_t n, lt_mask16_t m)
{
    return lth_q16_as30(lt_vq16_neg_sat_m(lth_q16_as16(n), m, lth_q16_as16(n)));
}

/* the lanes of hm whose normal n faces along the ray's direction (n . d > 0, exact in int64) */
static inline lt_mask16_t lth_q16_away(lt_mask16_t hm, const lt_vq30_t n[3],
                                       const lt_ray16_q16_t *r)
{
    lt_vql_t dn = lt_vql_add_wrap(
        lt_vql_add_wrap(lt_vql_mul(lt_vi32_from_q30(n[0]), lt_vi32_from_q30(r->dx)),
                        lt_vql_mul(lt_vi32_from_q30(n[1]), lt_vi32_from_q30(r->dy))),
        lt_vql_mul(lt_vi32_from_q30(n[2]), lt_vi32_from_q30(r->dz)));
    return lt_vql_cmpgt_m(hm, dn, lt_vql_set1(0));
}

/* a primary ray's direction from its tile's ray 0 (c, s1.30 raw) and the view's deltas g */
static inline lt_vq30_t lth_q16_pray_dir(lt_q30_t c, lt_vq30_t g)
{
    return lth_q16_as30(lt_vq16_add_wrap(lt_vq16_set1(c), lth_q16_as16(g)));
}

/* the single ray meets the triangle's front face (det > 0 with the kernel's rounded products) */
static inline int lth_q16_front(const lt_ray1_q16_t *r, const lt_tri_q16_t *t)
{
    int64_t p0 = lt__round_sat32((int64_t)r->d[1] * t->e2[2] - (int64_t)r->d[2] * t->e2[1], 30);
    int64_t p1 = lt__round_sat32((int64_t)r->d[2] * t->e2[0] - (int64_t)r->d[0] * t->e2[2], 30);
    int64_t p2 = lt__round_sat32((int64_t)r->d[0] * t->e2[1] - (int64_t)r->d[1] * t->e2[0], 30);
    return t->e1[0] * p0 + t->e1[1] * p1 + t->e1[2] * p2 > 0;
}
#endif /* LTH_Q16_HELPERS */

#define LTH_FN(name) name##_q16   /* a core entry point, or a host name generated per path */
#define LTH_TY(name) name##_q16_t /* a core type */
#define LTH_MID(a, b) a##_q16##b  /* a core name with the suffix inside: lt_ray16_q16_setup */
#define LTH_TRIS(s) ((s)->tq)     /* the scene's triangles in this path */
#define LTH_T lt_q16_t            /* positions, distances, irradiance: s15.16 */
#define LTH_D lt_q30_t            /* directions, normals: s1.30 */
/* double -> the path (half up, saturating) and back (exact) */
#define LTH_POS(x) lt_q16_from_double_sat(x)
#define LTH_DIR(x) lt_q30_from_double_sat(x)
#define LTH_POS_D(x) ((double)(x) / 65536.0)
#define LTH_DIR_D(x) ((double)(x) / 1073741824.0)
/* a single ray's initial tmax ("infinite") */
#define LTH_TMAX1 (LT_Q16_MAX - 1)
/* object space: the BVH with quantised nodes exists (1) or not (0); the scene check (or NULL) */
#define LTH_IF_BVHQ(x) x
#define LTH_HAS_BVHQ 1
#define LTH_SCENE_CHECK lt_scene_check_q16
/* lanes (the frusta template, lt_softshadow_path.inc): positions LTH_V, directions LTH_VD */
#define LTH_V lt_vq16_t
#define LTH_VD lt_vq30_t
#define LTH_VSET1 lt_vq16_set1
#define LTH_VDSET1 lt_vq30_set1
#define LTH_VMUL lt_vq16_mul_sat
#define LTH_GATHER_D lt_vq30_gather_m
#define LTH_MADD_D(p, t, d) lt_vq16_add_sat((p), lt_vq16_mul_q30_sat((t), (d))) /* p + t d */
#define LTH_FLIP_D(n, m) lth_q16_flip((n), (m))
#define LTH_AWAY(hm, n, r) lth_q16_away((hm), (n), (r))
#define LTH_PRAY_DIR(c, g) lth_q16_pray_dir((c), (g))
#define LTH_VIS16(c) ((lt_q16_t)((c) << 12)) /* c of 16 samples visible, as a fraction */
#define LTH_VISN(c, lg) ((lt_q16_t)((c) << (16 - (lg)))) /* c of 2^lg (<= 2^16) samples visible */
#define LTH_NORMAL_WORD(n0, n1, n2) ((uint32_t)(n0) ^ ((uint32_t)(n1) << 1) ^ ((uint32_t)(n2) << 2))
#define LTH_FRONT(r, t) lth_q16_front((r), (t))
#define LTH_VERT_D(v0, e) ((double)((int64_t)(v0) + (e)) / 65536.0) /* vertex v0 + e as double */
#define LTH_PVIEW(c, flags, v, diag) lt_ss_pview((c), (flags), (v), NULL, (diag))
