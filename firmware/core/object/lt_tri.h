/* lt_tri.h - internal header of the s15.16 Moller-Trumbore triangle test (Moller & Trumbore 1997
 * [Moller97]): its arithmetic written once, for one lane's scalars, and the names of the 16-lane
 * ops that perform the same arithmetic on every lane. Users: the packet kernel lt_tri16_q16
 * (lt_isect.inc via lt_isect.c), the single-ray kernel lt_tri1_q16 (lt_bvh.inc via lt_bvh.c), and
 * the multi-frusta culling and hit tests (lt_frusta.c, lt_frusta.inc), which must evaluate exactly
 * the kernel's tnum, det, u and v. Not part of the public API. Builds: all.
 *
 * The per-lane body (no charges: every caller charges its own tally where it always has, so the
 * cycle figures do not depend on which form runs the arithmetic):
 *
 * | step                       | function               | 16-lane op (lane i = the function)    |
 * |----------------------------|------------------------|---------------------------------------|
 * | tvec = o - v0              | lt__q16_sub_sat        | lt_vq16_sub_sat                       |
 * | pvec = d x e2, s15.16      | lt__tri_q16_pvec1      | LT__TRI_V16_PVEC lt_vq16_cross_q30_sat  |
 * | det = e1.pvec, u = tvec.pvec | lt__tri_q16_dot1     | LT__TRI_V16_DOT lt_vql32_dot3_q16     |
 * | qvec = tvec x e1, s25.6    | lt__tri_q16_qvec1      | LT__TRI_V16_QVEC lt_vq6_cross_q16_sat |
 * | v = d . qvec, s31.32       | lt__tri_q16_v1         | LT__TRI_V16_V lt_vql32_dot3_q30_q6_rd |
 * | tnum = e2 . qvec, s41.22   | lt__tri_q16_dot1       | LT__TRI_V16_TNUM lt_vql22_dot3_q16_q6 |
 * | t = tnum / det             | lt__tri_q16_tdiv1      | lt__tri_tdiv16_q16 (loops tdiv1)      |
 *
 * composed as lt__tri_q16_org1 (the origin-only terms tvec, qvec, tnum), lt__tri_q16_dir1 (pvec,
 * det, u, v for one direction) and lt__tri_q16_cand1 (both, the two-sided flip and the
 * barycentric test: is the lane a candidate for t = tnum / det). The 16-lane ops are lt_v16w.h's
 * typed ops, each a plain loop of the same lt_fx.h scalar primitives in the same order
 * (lt__mul32x32_64, lt__l64_add_wrap / _sub_wrap, lt__round_sat32, lt__asr64), so an elementwise
 * composition of them is the composition of the functions above on every lane; they stay lane ops
 * because each charges its own cost (lt_v16w.h), which a loop over this body would have to
 * re-tally. The division is the one lane op the header itself provides: lt__tri_tdiv16_q16
 * (lt_tri.c) runs lt__tri_q16_tdiv1 on every lane of its mask. tests/unit/test_isect.c checks the
 * lane ops against the functions lane by lane, and the kernels against each other.
 */
#ifndef LT_TRI_H
#define LT_TRI_H

#include "lt/lt_isect.h"

/* Fractional bits of qvec (lt_vq6_t): s25.6 holds |tvec||e1| up to 2^25 square units (tvec up to
 * the scene diagonal, 2^14, times e1 up to a scene-sized edge, 2^11) at a relative resolution far
 * below the s15.16 rounding of t for any triangle bigger than a few units^2 of qvec. */
#define LT__TRI_QV_FRAC 6u

/* t = tnum / det as s15.16 (tnum has 16 + QV_FRAC fractional bits, det 32, det > 0):
 * t_raw = tnum * 2^S / det with S = 32 - QV_FRAC, half up. When tnum * 2^S would overflow, det is
 * shifted down instead; det then still keeps >= 31 significant bits for any t inside the s15.16
 * range, and larger t saturate. */
#define LT__TRI_TDIV_SHIFT (32u - LT__TRI_QV_FRAC)

/* The 16-lane ops of the table above (lane types lt_vq16_t, lt_vq6_t, lt_vql32_t, lt_vql22_t). */
#define LT__TRI_V16_PVEC lt_vq16_cross_q30_sat
#define LT__TRI_V16_DOT lt_vql32_dot3_q16
#define LT__TRI_V16_QVEC lt_vq6_cross_q16_sat
#define LT__TRI_V16_V lt_vql32_dot3_q30_q6_rd
#define LT__TRI_V16_TNUM lt_vql22_dot3_q16_q6

/* ---- one lane ---------------------------------------------------------------------------------- */

/* a b - c d for s1.30 a, c and s15.16 b, d: exact in int64 (46 fractional bits), rounded half up
 * to s15.16, saturating (a SAT event). One component of pvec = d x e2. */
LT_INLINE lt_q16_t lt__tri_q16_pvec1(lt_q30_t a, lt_q16_t b, lt_q30_t c, lt_q16_t d)
{
    return lt__round_sat32(lt__l64_sub_wrap(lt__mul32x32_64(a, b), lt__mul32x32_64(c, d)), 30);
}

/* (ax bx + ay by) + az bz, exact (wrapping adds; the geometry bound keeps the sum in int64). The
 * fractional bits add: s15.16 . s15.16 -> s31.32 (det, u), s15.16 . s25.6 -> s41.22 (tnum). */
LT_INLINE int64_t lt__tri_q16_dot1(int32_t ax, int32_t ay, int32_t az, int32_t bx, int32_t by,
                                   int32_t bz)
{
    return lt__l64_add_wrap(lt__l64_add_wrap(lt__mul32x32_64(ax, bx), lt__mul32x32_64(ay, by)),
                            lt__mul32x32_64(az, bz));
}

/* a b - c d for s15.16 operands: exact (32 fractional bits), rounded half up to s25.6, saturating
 * (a SAT event). One component of qvec = tvec x e1, and of every normal rounded like it (the
 * frusta's e2 x tvec and e2 x e1). */
LT_INLINE int32_t lt__tri_q16_qvec1(lt_q16_t a, lt_q16_t b, lt_q16_t c, lt_q16_t d)
{
    return lt__round_sat32(lt__l64_sub_wrap(lt__mul32x32_64(a, b), lt__mul32x32_64(c, d)),
                           32u - LT__TRI_QV_FRAC);
}

/* v = d . qvec: s1.30 . s25.6 exact (36 fractional bits), floored to 32 (comparable with det). */
LT_INLINE int64_t lt__tri_q16_v1(lt_q30_t dx, lt_q30_t dy, lt_q30_t dz, int32_t qx, int32_t qy,
                                 int32_t qz)
{
    return lt__asr64(lt__tri_q16_dot1(dx, dy, dz, qx, qy, qz), 30u + LT__TRI_QV_FRAC - 32u);
}

/* t = tnum / det (det > 0) as s15.16: tnum pre-shifted by up to LT__TRI_TDIV_SHIFT bits, det
 * shifted down when tnum has no room, half up, saturating (a SAT event; det shifted to 0 gives
 * +-max by tnum's sign). */
LT_INLINE lt_q16_t lt__tri_q16_tdiv1(int64_t n, int64_t d)
{
    uint64_t an = n < 0 ? (uint64_t)0 - (uint64_t)n : (uint64_t)n;
    unsigned room = lt__clz64(an) - 2u; /* a left shift by `room` keeps |n| < 2^62 */
    unsigned s = room >= LT__TRI_TDIV_SHIFT ? LT__TRI_TDIV_SHIFT : room;
    int64_t q;
    n = (int64_t)((uint64_t)n << s); /* via unsigned: left shift of a negative is UB in C99 */
    if (s < LT__TRI_TDIV_SHIFT)
        d = lt__asr64(d, LT__TRI_TDIV_SHIFT - s);
    if (d == 0) {
        LT_EVENT(SAT, 1);
        return n >= 0 ? LT_Q16_MAX : LT_Q16_MIN;
    }
    q = lt__div_round64(n, d);
    LT_EVENT(SAT, q != (int64_t)lt__ssat32(q));
    return lt__ssat32(q);
}

/* The origin-only terms of one ray origin o against tri. */
typedef struct {
    int32_t t[3]; /* tvec = o - v0, s15.16 */
    int32_t q[3]; /* qvec = tvec x e1, s25.6 */
    int64_t tnum; /* e2 . qvec, s41.22 */
} lt__tri_q16_org_t;

LT_INLINE void lt__tri_q16_org1(const lt_q16_t o[3], const lt_tri_q16_t *tri,
                                lt__tri_q16_org_t *s)
{
    unsigned a;
    for (a = 0; a < 3; a++)
        s->t[a] = lt__q16_sub_sat(o[a], tri->v0[a]);
    s->q[0] = lt__tri_q16_qvec1(s->t[1], tri->e1[2], s->t[2], tri->e1[1]);
    s->q[1] = lt__tri_q16_qvec1(s->t[2], tri->e1[0], s->t[0], tri->e1[2]);
    s->q[2] = lt__tri_q16_qvec1(s->t[0], tri->e1[1], s->t[1], tri->e1[0]);
    s->tnum = lt__tri_q16_dot1(tri->e2[0], tri->e2[1], tri->e2[2], s->q[0], s->q[1], s->q[2]);
}

/* The direction terms of one ray (unit direction d, origin terms s): pvec = d x e2, det = e1 .
 * pvec, u = tvec . pvec, v = d . qvec, all s31.32. */
LT_INLINE void lt__tri_q16_dir1(const lt_q30_t d[3], const lt_tri_q16_t *tri,
                                const lt__tri_q16_org_t *s, int64_t *det, int64_t *u, int64_t *v)
{
    lt_q16_t px = lt__tri_q16_pvec1(d[1], tri->e2[2], d[2], tri->e2[1]);
    lt_q16_t py = lt__tri_q16_pvec1(d[2], tri->e2[0], d[0], tri->e2[2]);
    lt_q16_t pz = lt__tri_q16_pvec1(d[0], tri->e2[1], d[1], tri->e2[0]);
    *det = lt__tri_q16_dot1(tri->e1[0], tri->e1[1], tri->e1[2], px, py, pz);
    *u = lt__tri_q16_dot1(s->t[0], s->t[1], s->t[2], px, py, pz);
    *v = lt__tri_q16_v1(d[0], d[1], d[2], s->q[0], s->q[1], s->q[2]);
}

/* One ray (o, d) against tri up to the division: two-sided (a back-facing ray, det < 0, has det,
 * u, v and tnum negated so that det > 0 below), edges inclusive. Returns 1 when det > 0, u >= 0,
 * v >= 0 and u + v <= det, with *tnum and *det ready for lt__tri_q16_tdiv1; a hit then needs
 * tmin < t < tmax. det == 0 (degenerate or edge-on) never passes. */
LT_INLINE int lt__tri_q16_cand1(const lt_q16_t o[3], const lt_q30_t d[3], const lt_tri_q16_t *tri,
                                int64_t *tnum, int64_t *det)
{
    lt__tri_q16_org_t s;
    int64_t u, v;
    lt__tri_q16_org1(o, tri, &s);
    lt__tri_q16_dir1(d, tri, &s, det, &u, &v);
    *tnum = s.tnum;
    if (*det < 0) {
        *det = lt__l64_sub_wrap(0, *det);
        u = lt__l64_sub_wrap(0, u);
        v = lt__l64_sub_wrap(0, v);
        *tnum = lt__l64_sub_wrap(0, *tnum);
    }
    return *det > 0 && u >= 0 && v >= 0 && lt__l64_add_wrap(u, v) <= *det;
}

/* ---- 16 lanes ---------------------------------------------------------------------------------- */

/* t = tnum / det on the lanes of k (det > 0 there), lt__tri_q16_tdiv1 per lane; other lanes keep
 * src. Cost: VDIV x1 (lt_tri.c). */
lt_vq16_t lt__tri_tdiv16_q16(lt_vq16_t src, lt_mask16_t k, lt_vql22_t tnum, lt_vql32_t det);

/* ---- float32: the same body in IEEE binary32 ------------------------------------------------- */
#if LT_CFG_FLOAT32

/* a b - c d, each product rounded, then the difference (lt_vf32_cross per lane). */
LT_INLINE float lt__tri_f32_cross1(float a, float b, float c, float d) { return a * b - c * d; }

/* (ax bx + ay by) + az bz, rounded in this order (lt_vf32_dot3 per lane). */
LT_INLINE float lt__tri_f32_dot1(float ax, float ay, float az, float bx, float by, float bz)
{
    return ax * bx + ay * by + az * bz;
}

/* lt__tri_q16_cand1 in float32 (lt_tri16_f32's lane arithmetic: no roundings but IEEE's); t =
 * tnum / det is a plain division. */
LT_INLINE int lt__tri_f32_cand1(const float o[3], const float d[3], const lt_tri_f32_t *tri,
                                float *tnum, float *det)
{
    float px = lt__tri_f32_cross1(d[1], tri->e2[2], d[2], tri->e2[1]);
    float py = lt__tri_f32_cross1(d[2], tri->e2[0], d[0], tri->e2[2]);
    float pz = lt__tri_f32_cross1(d[0], tri->e2[1], d[1], tri->e2[0]);
    float tx = o[0] - tri->v0[0], ty = o[1] - tri->v0[1], tz = o[2] - tri->v0[2];
    float qx = lt__tri_f32_cross1(ty, tri->e1[2], tz, tri->e1[1]);
    float qy = lt__tri_f32_cross1(tz, tri->e1[0], tx, tri->e1[2]);
    float qz = lt__tri_f32_cross1(tx, tri->e1[1], ty, tri->e1[0]);
    float u = lt__tri_f32_dot1(tx, ty, tz, px, py, pz);
    float v = lt__tri_f32_dot1(d[0], d[1], d[2], qx, qy, qz);
    *det = lt__tri_f32_dot1(tri->e1[0], tri->e1[1], tri->e1[2], px, py, pz);
    *tnum = lt__tri_f32_dot1(tri->e2[0], tri->e2[1], tri->e2[2], qx, qy, qz);
    if (*det < 0.0f) {
        *det = -*det;
        u = -u;
        v = -v;
        *tnum = -*tnum;
    }
    return *det > 0.0f && u >= 0.0f && v >= 0.0f && u + v <= *det;
}

#endif /* LT_CFG_FLOAT32 */

#endif /* LT_TRI_H */
