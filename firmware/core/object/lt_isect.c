/* lt_isect.c - instantiates the packet kernels of lt_isect.inc for each numeric path:
 * s15.16 fixed point (exact int64 products; the triangle test's arithmetic is lt_tri.h's) and IEEE
 * float32. The traits below are the only place where the two paths differ. Builds: all; float32
 * only with LT_CFG_FLOAT32.
 */
#include "lt/lt_isect.h"
#include "lt_tri.h"
#include "lt_isel.h"

/* ---- fixed point: s15.16 positions, s1.30 directions ---------------------------------------- */

void lt_ray16_q16_setup(lt_ray16_q16_t *r)
{
    const lt_vq30_t *d[3];
    lt_vq16_t *rc[3];
    int a;
    d[0] = &r->dx;
    d[1] = &r->dy;
    d[2] = &r->dz;
    rc[0] = &r->rx;
    rc[1] = &r->ry;
    rc[2] = &r->rz;
    for (a = 0; a < 3; a++) {
        /* 1/d: 2^46 / d_raw, half up, saturated; d == 0 gives +max */
        *rc[a] = lt_vq16_recip_q30_sat(*d[a], LT_Q16_MAX);
        r->par[a] = lt_vq30_cmpeq(*d[a], lt_vq30_set1(0));
        r->rsat[a] = (lt_mask16_t)(lt_vq16_cmpsat(*rc[a]) & (unsigned)~r->par[a]);
    }
    r->pad_[0] = r->pad_[1] = 0;
}

/* The exact path of the slab test for flagged lanes. par (d == 0): the slab holds for all t when
 * lo <= o <= hi (closed), else for none. rsat (1/d saturated, d != 0): t = (plane - o) / d by
 * division, s15.16 / s1.30 -> s15.16 half up, saturating, which is right where the product with
 * the clamped reciprocal is not. */
static void q_slab_fix(lt_mask16_t par, lt_mask16_t rsat, lt_vq16_t o, lt_vq30_t d, lt_q16_t lo,
                       lt_q16_t hi, lt_vq16_t *t0, lt_vq16_t *t1)
{
    int i;
    LT_CHARGE_N(ISECT_Q_SLAB_RSAT, rsat != 0);
    LT_CHARGE_N(ISECT_Q_SLAB_PAR, (par != 0));
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(par, i)) {
            int in = o.l[i] >= lo && o.l[i] <= hi;
            t0->l[i] = in ? LT_Q16_MIN : LT_Q16_MAX;
            t1->l[i] = LT_Q16_MAX;
        } else if (LT__ON(rsat, i)) {
            int64_t p0 = (int64_t)lo - o.l[i], p1 = (int64_t)hi - o.l[i];
            t0->l[i] = lt__ssat32(lt__div_round64(p0 * ((int64_t)1 << 30), d.l[i]));
            t1->l[i] = lt__ssat32(lt__div_round64(p1 * ((int64_t)1 << 30), d.l[i]));
        }
    }
}

#include "numerics/lt_traits_q16.h"
#define LTN_QV lt_vq6_t    /* qvec, s25.6 */
#define LTN_W lt_vql32_t   /* det, u, v: s31.32 */
#define LTN_TN lt_vql22_t  /* tnum: s41.22 */
/* the products of the triangle test, one lane op per step of lt_tri.h's per-lane body */
#define LTN_CROSS_DP LT__TRI_V16_PVEC
#define LTN_DOT_PP LT__TRI_V16_DOT
#define LTN_CROSS_PP LT__TRI_V16_QVEC
#define LTN_DOT_DQ LT__TRI_V16_V
#define LTN_DOT_PQ LT__TRI_V16_TNUM
#define LTN_W_ADD lt_vql32_add_wrap
#define LTN_W_NEG_M(k, a) lt_vql32_sub_wrap_m((a), (k), lt_vql32_set1(0), (a))
#define LTN_TN_NEG_M(k, a) lt_vql22_sub_wrap_m((a), (k), lt_vql22_set1(0), (a))
#define LTN_W_CMPLT0(k, a) lt_vql32_cmplt_m((k), (a), lt_vql32_set1(0))
#define LTN_W_CMPGT0(k, a) lt_vql32_cmpgt_m((k), (a), lt_vql32_set1(0))
#define LTN_W_CMPGE0(k, a) lt_vql32_cmpge_m((k), (a), lt_vql32_set1(0))
#define LTN_W_CMPLE_M lt_vql32_cmple_m
#define LTN_TDIV_M lt__tri_tdiv16_q16
#define LTN_SLAB_FIX q_slab_fix
/* The slab test lane by lane (LT_LANEWISE(), lt_v16.h), for lanes none of which takes the fix-up:
 * each lane the lane ops' arithmetic in their order, in registers. */
static lt_mask16_t q_slab16_lanes(const lt_ray16_q16_t *r, lt_mask16_t k, const lt_aabb_q16_t *b,
                                  lt_vq16_t *tnear)
{
    const lt_vq16_t *o[3] = {&r->ox, &r->oy, &r->oz}, *rd[3] = {&r->rx, &r->ry, &r->rz};
    unsigned hit = 0, i, a;
    LT_CHARGE(ISECT_SLAB_LANES);
    LT_CHARGE_N(ISECT_SLAB_LANE, lt__popcount32(k));
    for (i = 0; i < LT_LANES; i++) {
        lt_q16_t tn, tf;
        if (((unsigned)k >> i & 1u) == 0)
            continue;
        tn = r->tmin.l[i];
        tf = r->tmax.l[i];
        for (a = 0; a < 3; a++) {
            lt_q16_t t0 = lt__q16_mul_sat(lt__q16_sub_sat(b->lo[a], o[a]->l[i]), rd[a]->l[i]);
            lt_q16_t t1 = lt__q16_mul_sat(lt__q16_sub_sat(b->hi[a], o[a]->l[i]), rd[a]->l[i]);
            tn = lt__q16_max(tn, lt__q16_min(t0, t1));
            tf = lt__q16_min(tf, lt__q16_max(t0, t1));
        }
        if (tn <= tf) {
            tnear->l[i] = tn;
            hit |= 1u << i;
        }
    }
    return (lt_mask16_t)hit;
}
#define LTN_SLAB16_LANES q_slab16_lanes
#if LT__X86_LANES == 512 && LT_COST_MODE != LT_COST_SIM
/* lt_slab16_q16 where no lane of k is parallel or has a saturated 1/d, in registers: each plane
 * through the backend's register bodies of the lane ops it uses (lt__x86_qsub: the saturating
 * subtract; lt__x86_mulr: the rounded, saturated product), so the same bits; the lane ops passed
 * their vectors through the stack between ops. No events: the counting build keeps the lane ops. */
static lt_mask16_t q_slab16_reg(const lt_ray16_q16_t *r, lt_mask16_t k, const lt_aabb_q16_t *b,
                                lt_vq16_t *tnear)
{
    __m512i tn = _mm512_loadu_si512(r->tmin.l), tf = _mm512_loadu_si512(r->tmax.l);
    __mmask16 hit;
#define Q_SLAB_AXIS(a, o, rd)                                                                      \
    do {                                                                                           \
        __m512i vo = _mm512_loadu_si512(r->o.l), vr = _mm512_loadu_si512(r->rd.l);                 \
        __m512i t0 = lt__x86_mulr(lt__x86_qsub(_mm512_set1_epi32(b->lo[a]), vo, 0), vr, 16u, 0);   \
        __m512i t1 = lt__x86_mulr(lt__x86_qsub(_mm512_set1_epi32(b->hi[a]), vo, 0), vr, 16u, 0);   \
        tn = _mm512_max_epi32(tn, _mm512_min_epi32(t0, t1));                                       \
        tf = _mm512_min_epi32(tf, _mm512_max_epi32(t0, t1));                                       \
    } while (0)
    Q_SLAB_AXIS(0, ox, rx);
    Q_SLAB_AXIS(1, oy, ry);
    Q_SLAB_AXIS(2, oz, rz);
#undef Q_SLAB_AXIS
    hit = _mm512_mask_cmp_epi32_mask(k, tn, tf, _MM_CMPINT_LE);
    _mm512_storeu_si512(tnear->l, _mm512_mask_mov_epi32(_mm512_loadu_si512(tnear->l), hit, tn));
    return (lt_mask16_t)hit;
}
#define LTN_SLAB16_REG q_slab16_reg
#elif LT__X86_LANES == 256 && LT_COST_MODE != LT_COST_SIM
/* The same on AVX2, one 8-lane half at a time through the backend's register bodies of the lane
 * ops (lt__x86_qsub8: saturating subtract; lt__x86_mulr8: the rounded, saturated product). */
static lt_mask16_t q_slab16_reg(const lt_ray16_q16_t *r, lt_mask16_t k, const lt_aabb_q16_t *b,
                                lt_vq16_t *tnear)
{
    unsigned h, all = 0;
    for (h = 0; h < LT_LANES; h += 8) {
        const unsigned k8 = (unsigned)k >> h & 0xFFu;
        __m256i tn = lt__x86_load8(r->tmin.l + h), tf = lt__x86_load8(r->tmax.l + h);
        unsigned hit;
        if (k8 == 0)
            continue;
#define Q_SLAB_AXIS8(a, o, rd)                                                                     \
    do {                                                                                           \
        __m256i vo = lt__x86_load8(r->o.l + h), vr = lt__x86_load8(r->rd.l + h);                   \
        __m256i t0 = lt__x86_mulr8(lt__x86_qsub8(_mm256_set1_epi32(b->lo[a]), vo, 0), vr, 16u, 0); \
        __m256i t1 = lt__x86_mulr8(lt__x86_qsub8(_mm256_set1_epi32(b->hi[a]), vo, 0), vr, 16u, 0); \
        tn = _mm256_max_epi32(tn, _mm256_min_epi32(t0, t1));                                       \
        tf = _mm256_min_epi32(tf, _mm256_max_epi32(t0, t1));                                       \
    } while (0)
        Q_SLAB_AXIS8(0, ox, rx);
        Q_SLAB_AXIS8(1, oy, ry);
        Q_SLAB_AXIS8(2, oz, rz);
#undef Q_SLAB_AXIS8
        hit = k8 & ~lt__x86_bits8(_mm256_cmpgt_epi32(tn, tf));
        _mm256_storeu_si256((__m256i *)(void *)(tnear->l + h),
                            _mm256_blendv_epi8(lt__x86_load8(tnear->l + h), tn, lt__x86_mask8(hit)));
        all |= hit << h;
    }
    return (lt_mask16_t)all;
}
#define LTN_SLAB16_REG q_slab16_reg
#endif
#include "lt_isect.inc"
#include "numerics/lt_traits_undef.h"
#undef LTN_SLAB16_REG
#undef LTN_QV
#undef LTN_W
#undef LTN_TN
#undef LTN_CROSS_DP
#undef LTN_DOT_PP
#undef LTN_CROSS_PP
#undef LTN_DOT_DQ
#undef LTN_DOT_PQ
#undef LTN_W_ADD
#undef LTN_W_NEG_M
#undef LTN_TN_NEG_M
#undef LTN_W_CMPLT0
#undef LTN_W_CMPGT0
#undef LTN_W_CMPGE0
#undef LTN_W_CMPLE_M
#undef LTN_TDIV_M
#undef LTN_SLAB_FIX
#undef LTN_SLAB16_LANES

/* ---- float32 -------------------------------------------------------------------------------- */
#if LT_CFG_FLOAT32

void lt_ray16_f32_setup(lt_ray16_f32_t *r)
{
    /* +-0 -> +-FLT_MAX (the sign bit of -0.0 is tested through 1/d = -inf) */
    r->rx = lt_vf32_rcp_sat(r->dx);
    r->ry = lt_vf32_rcp_sat(r->dy);
    r->rz = lt_vf32_rcp_sat(r->dz);
    /* == compares -0.0 equal to +0.0: both are parallel */
    r->par[0] = lt_vf32_cmpeq(r->dx, lt_vf32_set1(0.0f));
    r->par[1] = lt_vf32_cmpeq(r->dy, lt_vf32_set1(0.0f));
    r->par[2] = lt_vf32_cmpeq(r->dz, lt_vf32_set1(0.0f));
    r->rsat[0] = r->rsat[1] = r->rsat[2] = 0;
    r->pad_[0] = r->pad_[1] = 0;
}

/* Parallel lanes (d == +-0): all t when lo <= o <= hi, none otherwise; FLT_MAX stands for
 * infinity (tmax < FLT_MAX). */
static void f_slab_fix(lt_mask16_t par, lt_mask16_t rsat, lt_vf32_t o, lt_vf32_t d, float lo,
                       float hi, lt_vf32_t *t0, lt_vf32_t *t1)
{
    int i;
    (void)rsat;
    (void)d;
    LT_CHARGE(ISECT_F_SLAB_PAR);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(par, i)) {
            int in = o.l[i] >= lo && o.l[i] <= hi;
            t0->l[i] = in ? -3.40282347e38f : 3.40282347e38f;
            t1->l[i] = 3.40282347e38f;
        }
    }
}


#if LT__X86_LANES == 512 && LT_COST_MODE != LT_COST_SIM
/* lt_slab16_f32 where no lane of k needs the parallel fix-up, in AVX-512 registers (AVX2: two
 * 8-lane halves, below): per axis
 * (lo - o) x 1/d and (hi - o) x 1/d, their min and max into [tn, tf], as the lane ops compute
 * them (vminps / vmaxps take a < b ? a : b and a > b ? a : b, lt__f32_min / max), so the same
 * bits; the lane ops passed every intermediate vector through the stack. No events: the
 * counting build keeps the lane ops. */
static lt_mask16_t f_slab16_reg(const lt_ray16_f32_t *r, lt_mask16_t k, const lt_aabb_f32_t *b,
                                lt_vf32_t *tnear)
{
    __m512 tn = _mm512_loadu_ps(r->tmin.l), tf = _mm512_loadu_ps(r->tmax.l);
    __mmask16 hit;
#define F_SLAB_AXIS(a, o, rd)                                                                      \
    do {                                                                                           \
        __m512 vo = _mm512_loadu_ps(r->o.l), vr = _mm512_loadu_ps(r->rd.l);                        \
        __m512 t0 = _mm512_mul_ps(_mm512_sub_ps(_mm512_set1_ps(b->lo[a]), vo), vr);                \
        __m512 t1 = _mm512_mul_ps(_mm512_sub_ps(_mm512_set1_ps(b->hi[a]), vo), vr);                \
        tn = _mm512_max_ps(tn, _mm512_min_ps(t0, t1));                                             \
        tf = _mm512_min_ps(tf, _mm512_max_ps(t0, t1));                                             \
    } while (0)
    F_SLAB_AXIS(0, ox, rx);
    F_SLAB_AXIS(1, oy, ry);
    F_SLAB_AXIS(2, oz, rz);
#undef F_SLAB_AXIS
    hit = _mm512_mask_cmp_ps_mask(k, tn, tf, _CMP_LE_OQ);
    _mm512_storeu_ps(tnear->l, _mm512_mask_mov_ps(_mm512_loadu_ps(tnear->l), hit, tn));
    return (lt_mask16_t)hit;
}
#define LTN_SLAB16_REG f_slab16_reg
#elif LT__X86_LANES == 256 && LT_COST_MODE != LT_COST_SIM
/* The same on AVX2, one 8-lane half at a time. */
static lt_mask16_t f_slab16_reg(const lt_ray16_f32_t *r, lt_mask16_t k, const lt_aabb_f32_t *b,
                                lt_vf32_t *tnear)
{
    unsigned h, all = 0;
    for (h = 0; h < LT_LANES; h += 8) {
        const unsigned k8 = (unsigned)k >> h & 0xFFu;
        __m256 tn = _mm256_loadu_ps(r->tmin.l + h), tf = _mm256_loadu_ps(r->tmax.l + h);
        unsigned hit;
        if (k8 == 0)
            continue;
#define F_SLAB_AXIS8(a, o, rd)                                                                     \
    do {                                                                                           \
        __m256 vo = _mm256_loadu_ps(r->o.l + h), vr = _mm256_loadu_ps(r->rd.l + h);                \
        __m256 t0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(b->lo[a]), vo), vr);                \
        __m256 t1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(b->hi[a]), vo), vr);                \
        tn = _mm256_max_ps(tn, _mm256_min_ps(t0, t1));                                             \
        tf = _mm256_min_ps(tf, _mm256_max_ps(t0, t1));                                             \
    } while (0)
        F_SLAB_AXIS8(0, ox, rx);
        F_SLAB_AXIS8(1, oy, ry);
        F_SLAB_AXIS8(2, oz, rz);
#undef F_SLAB_AXIS8
        hit = k8 & (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(tn, tf, _CMP_LE_OQ));
        _mm256_storeu_ps(tnear->l + h,
                         _mm256_blendv_ps(_mm256_loadu_ps(tnear->l + h), tn,
                                          _mm256_castsi256_ps(lt__x86_mask8(hit))));
        all |= hit << h;
    }
    return (lt_mask16_t)all;
}
#define LTN_SLAB16_REG f_slab16_reg
#endif

#include "numerics/lt_traits_f32.h"
#define LTN_QV lt_vf32_t
#define LTN_W lt_vf32_t
#define LTN_TN lt_vf32_t
#define LTN_CROSS_DP lt_vf32_cross
#define LTN_DOT_PP lt_vf32_dot3
#define LTN_CROSS_PP lt_vf32_cross
#define LTN_DOT_DQ lt_vf32_dot3
#define LTN_DOT_PQ lt_vf32_dot3
#define LTN_W_ADD lt_vf32_add
#define LTN_W_NEG_M(k, a) lt_vf32_neg_m((a), (k), (a))
#define LTN_TN_NEG_M LTN_W_NEG_M
#define LTN_W_CMPLT0(k, a) lt_vf32_cmplt_m((k), (a), lt_vf32_set1(0.0f))
#define LTN_W_CMPGT0(k, a) lt_vf32_cmpgt_m((k), (a), lt_vf32_set1(0.0f))
#define LTN_W_CMPGE0(k, a) lt_vf32_cmpge_m((k), (a), lt_vf32_set1(0.0f))
#define LTN_W_CMPLE_M lt_vf32_cmple_m
#define LTN_TDIV_M(src, k, n, d) lt_vf32_div_m((src), (k), (n), (d))
#define LTN_SLAB_FIX f_slab_fix
#include "lt_isect.inc"
#undef LTN_SLAB16_REG

#endif /* LT_CFG_FLOAT32 */
