/* lt_path_f32.h - the host's float32 numeric path (registry entry "f32"): the generic LTH_* names
 * of the host's per-path templates mapped onto the core's _f32 entry points and types; see
 * lt_path_q16.h. Host only.
 */
#ifndef LTH_F32_HELPERS
#define LTH_F32_HELPERS
#include <string.h>
#include "lt/lt.h"
#include "lt/lt_frusta.h"

static inline lt_mask16_t lth_f32_away(lt_mask16_t hm, const lt_vf32_t n[3],
                                       const lt_ray16_f32_t *r)
{
    lt_vf32_t dn = lt_vf32_add(lt_vf32_add(lt_vf32_mul(n[0], r->dx), lt_vf32_mul(n[1], r->dy)),
                               lt_vf32_mul(n[2], r->dz));
    return lt_vf32_cmpgt_m(hm, dn, lt_vf32_set1(0.0f));
}

static inline int lth_f32_front(const lt_ray1_f32_t *r, const lt_tri_f32_t *t)
{
    float px = r->d[1] * t->e2[2] - r->d[2] * t->e2[1];
    float py = r->d[2] * t->e2[0] - r->d[0] * t->e2[2];
    float pz = r->d[0] * t->e2[1] - r->d[1] * t->e2[0];
    return (t->e1[0] * px + t->e1[1] * py) + t->e1[2] * pz > 0.0f;
}

static inline uint32_t lth_f32_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}
#endif /* LTH_F32_HELPERS */

#define LTH_FN(name) name##_f32
#define LTH_TY(name) name##_f32_t
#define LTH_MID(a, b) a##_f32##b
#define LTH_TRIS(s) ((s)->tf)
#define LTH_T float
#define LTH_D float
#define LTH_POS(x) ((float)(x))
#define LTH_DIR(x) ((float)(x))
#define LTH_POS_D(x) ((double)(x))
#define LTH_DIR_D(x) ((double)(x))
#define LTH_TMAX1 3.0e38f
#define LTH_IF_BVHQ(x) NULL
#define LTH_HAS_BVHQ 0
#define LTH_SCENE_CHECK NULL
#define LTH_W float
#define LTH_W_BYTES 0
#define LTH_XY_D(x) ((double)(x))
#define LTH_W_D(x) ((double)(x))
#define LTH_REPROJ_SETUP(src, dst, o, map) lt_reproj_setup((src), (dst), (o), NULL, (map))
/* no single-ray quadtree walk in float32 */
#define LTH_IF_QT1(x) NULL
#define LTH_HAS_QT1 0
#define LTH_V lt_vf32_t
#define LTH_VD lt_vf32_t
#define LTH_VSET1 lt_vf32_set1
#define LTH_VDSET1 lt_vf32_set1
#define LTH_VMUL lt_vf32_mul
#define LTH_GATHER_D lt_vf32_gather_m
#define LTH_MADD_D(p, t, d) lt_vf32_add((p), lt_vf32_mul((t), (d)))
#define LTH_FLIP_D(n, m) lt_vf32_neg_m((n), (m), (n))
#define LTH_AWAY(hm, n, r) lth_f32_away((hm), (n), (r))
#define LTH_PRAY_DIR(c, g) lt_vf32_add(lt_vf32_set1(c), (g))
#define LTH_VIS16(c) ((float)(c) * 0.0625f)
#define LTH_VISN(c, lg) ((float)(c) / (float)(1u << (lg))) /* exact for lg <= 24 */
#define LTH_NORMAL_WORD(n0, n1, n2) lth_f32_bits(n0)
#define LTH_FRONT(r, t) lth_f32_front((r), (t))
#define LTH_VERT_D(v0, e) ((double)(v0) + (double)(e))
#define LTH_PVIEW(c, flags, v, diag) lt_ss_pview((c), (flags), NULL, (v), (diag))
