/* lt_wt.c - instantiates the watertight ray/triangle kernel of lt_wt.inc (Woop, Benthin, Wald,
 * JCGT 2013) for s15.16 fixed point (exact int64 edge functions, exact 128-bit T and t = T / det)
 * and IEEE float32 (with the paper's double fallback for 0.0f edge functions). The traits below
 * are the only place where the two paths differ. Builds: all; float32 only with LT_CFG_FLOAT32.
 */
#include "lt/lt_wt.h"
#include "lt_isel.h"

/* The bit budget of docs/watertight.md: |A| <= 2^13, sheared |x| <= 2^14 units (2^30 raw), edge
 * functions <= 2^61, det < 2^63. A larger geometry bound would overflow them. */
LT_STATIC_ASSERT(LT_CFG_GEOM_MAX_LOG2 <= 12, "lt_wt's exact int64 edge functions need GEOM <= 12");

/* ---- fixed point: s15.16 positions, s1.30 directions and shear ------------------------------- */

/* Lanes with d[kz] == 0 (the whole direction is zero: d[kz] is its largest component): no shear.
 * Any other direction is accepted; q_norm scales d[kz] for Sz. Cost: VBCAST x1, VALU x1,
 * VCMP x1. */
static lt_mask16_t q_baddir(lt_vq30_t dkz)
{
    return lt_vq30_cmpeq(lt_vq30_abs_sat(dkz), lt_vq30_set1(0));
}

/* Per lane (shared by the packet and the single-ray test): num / den in s1.30, half up, for
 * |num| <= |den| (|S| <= 1); 1 / den as 2^60 / den_raw (|den| > 2^29 after q_norm1: |Sz| < 2);
 * the shift that brings |d[kz]| into (2^29, 2^31) raw, i.e. (1/2, 2): 0 for every |d[kz]| > 1/2
 * (all unit directions), else the smallest sh with |d[kz]| 2^sh > 2^29 (<= 30). */
static lt_q30_t q_ratio1(lt_q30_t num, lt_q30_t den)
{
    return lt__ssat32(lt__div_round64((int64_t)num * 1073741824, den));
}

static lt_q30_t q_recip1(lt_q30_t den) { return lt__ssat32(lt__div_round64((int64_t)1 << 60, den)); }

static unsigned q_norm1(lt_q30_t dkz)
{
    uint32_t a = dkz < 0 ? 0u - (uint32_t)dkz : (uint32_t)dkz;
    unsigned bits = 32u - lt__clz32(a), sh;
    if (a == 0 || bits >= 31u)
        return 0;
    sh = 30u - bits;
    if ((a << sh) == (1u << 29))
        sh++;
    return sh;
}

/* num / den in s1.30 per lane, bad lanes get 0. Cost: VDIV x1. */
static lt_vq30_t q_ratio(lt_vq30_t num, lt_vq30_t den, lt_mask16_t bad)
{
    int i;
    LT_CHARGE(WT_Q_RATIO);
    for (i = 0; i < LT_LANES; i++)
        num.l[i] = LT__ON(bad, i) ? 0 : q_ratio1(num.l[i], den.l[i]);
    return num;
}

/* 1 / den in s1.30 per lane (den normalised by q_norm), bad lanes get 0. Cost: VDIV x1. */
static lt_vq30_t q_recip(lt_vq30_t den, lt_mask16_t bad)
{
    int i;
    LT_CHARGE(WT_Q_RECIP);
    for (i = 0; i < LT_LANES; i++)
        den.l[i] = LT__ON(bad, i) ? 0 : q_recip1(den.l[i]);
    return den;
}

/* The shift of each lane into w->sh, and d[kz] 2^sh (exact: |d[kz]| 2^sh < 2^31). A lane
 * count-leading-zeros, a compare and a variable shift. Cost: WT_Q_NORM (VALU x2, VSHIFT x1). */
static lt_vq30_t q_norm(lt_wt16_q16_t *w, lt_vq30_t dkz)
{
    int i;
    LT_CHARGE(WT_Q_NORM);
    for (i = 0; i < LT_LANES; i++) {
        unsigned sh = q_norm1(dkz.l[i]);
        w->sh[i] = (uint8_t)sh;
        dkz.l[i] = (lt_q30_t)(dkz.l[i] * (int32_t)(1u << sh));
    }
    return dkz;
}

/* 16 signed 128-bit integers, two's complement in two unsigned words: value = hi 2^64 + lo
 * (the sign is bit 63 of hi). 256 bytes. */
typedef struct wt_v128 {
    uint64_t hi[LT_LANES]; /* bits 64..127 */
    uint64_t lo[LT_LANES]; /* bits 0..63 */
} wt_v128_t;

/* (h, l) += a * b exactly, a int64, b int32. a = ah 2^32 + al (al in [0, 2^32)), so a * b =
 * (ah b) 2^32 + al b with |ah b| <= 2^62 and |al b| < 2^63: both fit int64 for any inputs.
 * Adds are modulo 2^128 in unsigned words (carry = the sum wrapped below an addend). */
LT_INLINE void q_mac128(uint64_t *h, uint64_t *l, int64_t a, int32_t b)
{
    int64_t p1 = lt__asr64(a, 32) * (int64_t)b;
    int64_t p0 = (int64_t)((uint64_t)a & 0xFFFFFFFFu) * (int64_t)b;
    uint64_t add = (uint64_t)p1 << 32, s = *l + add;
    *h += (uint64_t)lt__asr64(p1, 32) + (uint64_t)(s < add);
    add = (uint64_t)p0;
    *l = s + add;
    *h += (p0 < 0 ? ~(uint64_t)0 : 0u) + (uint64_t)(*l < add);
}

/* T = U za + V zb + W zc exactly in 128 bits (s31.32 x s15.16 -> 48 fractional bits), lanes in k.
 * |U| <= 2^61, |z| < 2^30 raw: |T| < 2^93. Cost: VMUL x6, VMULW x10. */
static wt_v128_t q_tsum(lt_mask16_t k, lt_vql32_t u, lt_vql32_t v, lt_vql32_t w, lt_vq16_t za,
                        lt_vq16_t zb, lt_vq16_t zc)
{
    wt_v128_t r;
    int i;
    LT_CHARGE(WT_Q_TSUM);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        r.hi[i] = 0;
        r.lo[i] = 0;
        if (!LT__ON(k, i))
            continue;
        q_mac128(&r.hi[i], &r.lo[i], u.l[i], za.l[i]);
        q_mac128(&r.hi[i], &r.lo[i], v.l[i], zb.l[i]);
        q_mac128(&r.hi[i], &r.lo[i], w.l[i], zc.l[i]);
    }
    return r;
}

/* floor(n / d) and n mod d for an unsigned 128-bit n = (nh, nl) < d 2^31 and d > 0: restoring
 * division, one quotient bit per step (31 steps; the quotient is < 2^31), on the targets; the
 * hardware divide on x86-64 hosts (the same exact result; -DLT_LANES_PORTABLE keeps the loop). */
static uint32_t q_udiv128(uint64_t nh, uint64_t nl, uint64_t d, uint64_t *rem)
{
#if defined(__x86_64__) && defined(__GNUC__) && !defined(LT_LANES_PORTABLE)
    /* x86-64 hosts: the hardware's 128/64-bit divide, the same exact floor quotient and remainder
       (nh < d, so the quotient fits and divq cannot fault) */
    uint64_t q, r;
    __asm__("divq %4" : "=a"(q), "=d"(r) : "a"(nl), "d"(nh), "rm"(d) : "cc");
    *rem = r;
    return (uint32_t)q;
#else
    uint32_t q = 0;
    int b;
    for (b = 30; b >= 0; b--) {
        uint64_t dl = d << b, dh = b > 0 ? d >> (64 - b) : 0;
        if (nh > dh || (nh == dh && nl >= dl)) {
            nh = nh - dh - (uint64_t)(nl < dl);
            nl -= dl;
            q |= 1u << b;
        }
    }
    *rem = nl;
    return q;
#endif
}

/* One lane of q_tdiv_m: t = round(T 2^sh / det) as s15.16 (48 - 32 fractional bits), half up
 * from the exact quotient, det != 0. |T| < 2^93 and sh <= 30 keep T 2^sh inside 128 bits. A
 * quotient >= 2^31 (out-of-range input, or a far hit of a short direction) saturates (*sat = 1).
 * For unit directions sh = 0 and this is T / det. */
static lt_q16_t q_tdiv1(uint64_t nh, uint64_t nl, int64_t d, unsigned sh, int *sat)
{
    uint64_t ad, rem;
    uint32_t q;
    int neg = (int)(nh >> 63) != (d < 0);
    *sat = 0;
    /* magnitudes, in unsigned arithmetic (no overflow for any input) */
    if ((nh >> 63) != 0) {
        nl = ~nl + 1u;
        nh = ~nh + (uint64_t)(nl == 0);
    }
    if (sh != 0) {
        nh = (nh << sh) | (nl >> (64u - sh));
        nl <<= sh;
    }
    ad = d < 0 ? 0u - (uint64_t)d : (uint64_t)d;
    /* n >= ad 2^31: the quotient does not fit s15.16 */
    if (nh > (ad >> 33) || (nh == (ad >> 33) && nl >= (ad << 31))) {
        *sat = 1;
        return neg ? LT_Q16_MIN : LT_Q16_MAX;
    }
    q = q_udiv128(nh, nl, ad, &rem);
    /* half up: x = q + f rounds to q + 1 when f >= 1/2; -x rounds to -(q + 1) when f > 1/2 */
    if (neg) {
        q += (uint32_t)(rem > ad - rem);
        return q == 0 ? 0 : -(int32_t)(q - 1u) - 1;
    }
    q += (uint32_t)(rem >= ad - rem);
    return lt__ssat32((int64_t)q);
}

/* t = T 2^sh / det per lane for lanes in k (det != 0 there); other lanes keep src. A hit has
 * |t| <= max |z| 2^sh; saturated quotients count a SAT event. Cost: VDIV x2 (128/64 bits). */
static lt_vq16_t q_tdiv_m(lt_vq16_t src, lt_mask16_t k, wt_v128_t tn, lt_vql32_t det,
                          const lt_wt16_q16_t *w)
{
    int i;
    LT_CHARGE(WT_Q_TDIV);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        int sat;
        if (!LT__ON(k, i))
            continue;
        src.l[i] = q_tdiv1(tn.hi[i], tn.lo[i], det.l[i], w->sh[i], &sat);
        LT_EVENT(SAT, sat);
    }
    return src;
}

/* e1 x e2 == 0 exactly for the rebuilt vertices (s15.16 differences, int64 products compared
 * without subtracting, so no overflow for any input). Uncharged: q_zero_area (a triangle, scalar)
 * and q_zero_area16 (a triangle per lane) charge it. */
static int q_zero_area1(lt_q16_t p[3][3])
{
    int32_t a[3], b[3];
    int i;
    for (i = 0; i < 3; i++) {
        a[i] = lt__ssat32((int64_t)p[1][i] - p[0][i]);
        b[i] = lt__ssat32((int64_t)p[2][i] - p[0][i]);
    }
    return lt__mul32x32_64(a[1], b[2]) == lt__mul32x32_64(a[2], b[1]) &&
           lt__mul32x32_64(a[2], b[0]) == lt__mul32x32_64(a[0], b[2]) &&
           lt__mul32x32_64(a[0], b[1]) == lt__mul32x32_64(a[1], b[0]);
}

/* Cost: SALU x9, SMUL x6. */
static int q_zero_area(lt_q16_t p[3][3])
{
    LT_CHARGE(WT_ZERO_AREA);
    return q_zero_area1(p);
}

/* The ray axis of one ray, as the packet setup computes it per lane from |d|: the largest
 * component, ties to z, then y. */
#define WT1_KZ(ax, ay, az) ((az) >= (ax) && (az) >= (ay) ? 2u : ((ay) >= (ax) ? 1u : 0u))

/* kx, ky from kz and the sign of d[kz]: the next axes in cyclic order, swapped when d[kz] < 0
 * (the masks of the packet setup). */
static void wt1_kxky(unsigned k[3], int neg)
{
    k[0] = (k[2] + (neg ? 2u : 1u)) % 3u;
    k[1] = (k[2] + (neg ? 1u : 2u)) % 3u;
}

/* ---- single rays: one lane of the packet test, scalar ----------------------------------------- */

/* The setup of one ray: the lane arithmetic of lt_ray16_wt_setup_q16 (same primitives, same
 * order), so lt_tri1_wt_q16 equals a packet lane bit for bit. Cost: WT_RAY1_SETUP. */
int lt_ray1_wt_setup_q16(const lt_q16_t o[3], const lt_q30_t d[3], lt_wt1_q16_t *w)
{
    unsigned k[3];
    lt_q30_t dkz;
    int32_t a0 = lt__q16_abs_sat(d[0]), a1 = lt__q16_abs_sat(d[1]), a2 = lt__q16_abs_sat(d[2]);
    LT_CHARGE(WT_RAY1_SETUP);
    k[2] = WT1_KZ(a0, a1, a2);
    dkz = d[k[2]];
    wt1_kxky(k, dkz < 0);
    w->k[0] = (uint8_t)k[0];
    w->k[1] = (uint8_t)k[1];
    w->k[2] = (uint8_t)k[2];
    w->o[0] = o[k[0]];
    w->o[1] = o[k[1]];
    w->o[2] = o[k[2]];
    w->bad = (uint8_t)(lt__q16_abs_sat(dkz) == 0);
    w->sh = (uint8_t)(w->bad ? 0u : q_norm1(dkz));
    w->s[0] = w->bad ? 0 : q_ratio1(d[k[0]], dkz);
    w->s[1] = w->bad ? 0 : q_ratio1(d[k[1]], dkz);
    w->s[2] = w->bad ? 0 : q_recip1((lt_q30_t)(dkz * (int32_t)(1u << w->sh)));
    w->pad_[0] = w->pad_[1] = w->pad_[2] = 0;
    return w->bad;
}

int lt_tri1_wt_q16(const lt_wt1_q16_t *w, const lt_tri_q16_t *tri, lt_q16_t tmin, lt_q16_t *tmax)
{
    lt_q16_t p[3][3], x[3], y[3], zk[3], z[3], t;
    int64_t eu, ev, ew, det;
    uint64_t h = 0, l = 0;
    int i, a, neg, pos, sat;

    LT_CHARGE(WT_TRI1);
    LT_MEM(tri, sizeof *tri, LT_MEM_READ);
    LT_EVENT(TRIS, 1);
    LT_EVENT(TRI_RAYS, 1);
    if (w->bad)
        return 0;
    for (a = 0; a < 3; a++) {
        p[0][a] = tri->v0[a];
        p[1][a] = lt__q16_add_sat(tri->v0[a], tri->e1[a]);
        p[2][a] = lt__q16_add_sat(tri->v0[a], tri->e2[a]);
    }
    if (q_zero_area(p))
        return 0;
    for (i = 0; i < 3; i++) {
        lt_q16_t ax = lt__q16_sub_sat(p[i][w->k[0]], w->o[0]);
        lt_q16_t ay = lt__q16_sub_sat(p[i][w->k[1]], w->o[1]);
        zk[i] = lt__q16_sub_sat(p[i][w->k[2]], w->o[2]);
        x[i] = lt__q16_sub_sat(ax, lt__q16_mul_q30_sat(zk[i], w->s[0]));
        y[i] = lt__q16_sub_sat(ay, lt__q16_mul_q30_sat(zk[i], w->s[1]));
    }
    eu = lt__l64_sub_wrap(lt__mul32x32_64(x[2], y[1]), lt__mul32x32_64(y[2], x[1]));
    ev = lt__l64_sub_wrap(lt__mul32x32_64(x[0], y[2]), lt__mul32x32_64(y[0], x[2]));
    ew = lt__l64_sub_wrap(lt__mul32x32_64(x[1], y[0]), lt__mul32x32_64(y[1], x[0]));
    neg = eu < 0 || ev < 0 || ew < 0;
    pos = eu > 0 || ev > 0 || ew > 0;
    det = lt__l64_add_wrap(lt__l64_add_wrap(eu, ev), ew);
    if ((neg && pos) || det == 0)
        return 0;
    LT_CHARGE(WT_TRI1_T);
    for (i = 0; i < 3; i++)
        z[i] = lt__q16_mul_q30_sat(zk[i], w->s[2]);
    q_mac128(&h, &l, eu, z[0]);
    q_mac128(&h, &l, ev, z[1]);
    q_mac128(&h, &l, ew, z[2]);
    t = q_tdiv1(h, l, det, w->sh, &sat);
    LT_EVENT(SAT, sat);
    if (t > tmin && t < *tmax) {
        *tmax = t;
        LT_EVENT(HITS, 1);
        return 1;
    }
    return 0;
}

/* A leaf block's read and its triangles' terms (lt__wt_tris4_q16 / _f32, lt_isel.h): the
 * charges and events of nt triangle tests. */
static void wt_block_terms(const void *b, size_t bytes, uint32_t nt)
{
    LT_MEM(b, bytes, LT_MEM_READ);
    LT_CHARGE_N(BVH_TRAV_LEAF_TRI, nt);
    LT_CHARGE_N(WT_TRI1, nt);
    LT_EVENT(TRIS, nt);
    LT_EVENT(TRI_RAYS, nt);
    (void)b;
    (void)bytes;
    (void)nt;
}

/* The exact test's edge stage for one ray on its sheared points (x, y): U, V, W exact in int64 into
 * e, their sum into *det; 1 when the signs agree and det != 0 (lt_tri1_wt_q16's arithmetic, which
 * keeps its own copy: the firmware's compiled exact test is priced by the fitted MCU models). */
LT_INLINE int wt1_edges64(const lt_q16_t x[3], const lt_q16_t y[3], int64_t e[3], int64_t *det)
{
    int neg, pos;
    e[0] = lt__l64_sub_wrap(lt__mul32x32_64(x[2], y[1]), lt__mul32x32_64(y[2], x[1]));
    e[1] = lt__l64_sub_wrap(lt__mul32x32_64(x[0], y[2]), lt__mul32x32_64(y[0], x[2]));
    e[2] = lt__l64_sub_wrap(lt__mul32x32_64(x[1], y[0]), lt__mul32x32_64(y[1], x[0]));
    neg = e[0] < 0 || e[1] < 0 || e[2] < 0;
    pos = e[0] > 0 || e[1] > 0 || e[2] > 0;
    *det = lt__l64_add_wrap(lt__l64_add_wrap(e[0], e[1]), e[2]);
    return !((neg && pos) || *det == 0);
}

/* Its t: z = round(Sz zk), the exact 128-bit T = U z0 + V z1 + W z2, t = round(T 2^sh / det). */
LT_INLINE lt_q16_t wt1_t64(const int64_t e[3], int64_t det, const lt_q16_t zk[3], lt_q30_t sz,
                           unsigned sh, int *sat)
{
    uint64_t h = 0, l = 0;
    int i;
    for (i = 0; i < 3; i++)
        q_mac128(&h, &l, e[i], lt__q16_mul_q30_sat(zk[i], sz));
    return q_tdiv1(h, l, det, sh, sat);
}

/* The wide tree's leaf blocks: lt_tri1_wt_q16 per lane (lt_isel.h), lane by lane in scalar code
 * (measured: the 64-bit lanes with their saturation and rounding fix-ups as 2-lane SIMD ran at 0.7x
 * the scalar test on the host), on the block's rebuilt vertices and zero-area flags. */
int32_t lt__wt_tris4_q16(const lt_wt1_q16_t *w, const lt_bvh8_tris4_q16_t *b, uint32_t n,
                         lt_q16_t tmin, lt_q16_t *tmax, int any)
{
    const unsigned k0 = w->k[0], k1 = w->k[1], k2 = w->k[2];
    int32_t res = -1;
    uint32_t done;
    for (done = 0; done < n; done += LT_BVH8_LANES, b++) {
        uint32_t nt = n - done < LT_BVH8_LANES ? n - done : LT_BVH8_LANES;
        unsigned c;
        wt_block_terms(b, sizeof *b, nt);
        if (w->bad)
            continue;
        for (c = 0; c < nt; c++) {
            lt_q16_t x[3], y[3], zk[3], t;
            int64_t e[3], det;
            unsigned v;
            int sat;
            if (b->id[c] < 0)
                continue; /* zero area */
            for (v = 0; v < 3; v++) {
                lt_q16_t ax = lt__q16_sub_sat(b->v[3 * v + k0][c], w->o[0]);
                lt_q16_t ay = lt__q16_sub_sat(b->v[3 * v + k1][c], w->o[1]);
                zk[v] = lt__q16_sub_sat(b->v[3 * v + k2][c], w->o[2]);
                x[v] = lt__q16_sub_sat(ax, lt__q16_mul_q30_sat(zk[v], w->s[0]));
                y[v] = lt__q16_sub_sat(ay, lt__q16_mul_q30_sat(zk[v], w->s[1]));
            }
            if (!wt1_edges64(x, y, e, &det))
                continue;
            LT_CHARGE(WT_TRI1_T);
            t = wt1_t64(e, det, zk, w->s[2], w->sh, &sat);
            LT_EVENT(SAT, sat);
            if (t > tmin && t < *tmax) {
                *tmax = t;
                LT_EVENT(HITS, 1);
                res = b->id[c];
                if (any)
                    return res;
            }
        }
    }
    return res;
}

/* Every lane's t scale set to sh (a lane broadcast of lt__wt16_meet_tris). */
static void memset_sh(uint8_t sh[LT_LANES], uint8_t v)
{
    int i;
    for (i = 0; i < LT_LANES; i++)
        sh[i] = v;
}

/* The packet test lane by lane (LT_LANEWISE(), lt_v16.h: the Cortex-M4 and Cortex-M55 DSP
 * builds, and the simulator when it models mcu-m4 or mcu-m55), after its vertices p and zero-area
 * test: each lane of k (none bad) computes what its lane of wt_edges computes - the same picks,
 * saturating subtracts and products, the exact int64 edges and their signs (wt1_edges64), T and t
 * (wt1_t64) - so the same bits (the other builds keep the lane ops; golden vectors and scene
 * hashes compare them). Its shear stage stays beside lt_tri1_wt_q16's and lt__wt_tris4_q16's:
 * shared through an inline helper it moved the Cortex-M4 and Cortex-M55 images' packet stages by
 * +0.02% and -1% (measured), which the fitted MCU models would have to be refitted for. The lane
 * ops pass 64- and 128-byte vectors by value and compute all 16 lanes (6,384 instructions per
 * 16-ray test on the bunny's Cortex-M55 image, most of them copies; docs/firmware.md, "Lane by
 * lane"). Returns the lanes that meet, t written for them. */
LT_INLINE unsigned q_lane_axis(const lt_mask16_t m[3], unsigned i)
{
    return ((unsigned)m[0] >> i & 1u) != 0 ? 0u : ((unsigned)m[1] >> i & 1u) != 0 ? 1u : 2u;
}

static lt_mask16_t q_meet_lanes(const lt_wt16_q16_t *w, lt_mask16_t k, const lt_q16_t p[3][3],
                                lt_vq16_t *t)
{
    unsigned m = 0, i;
    LT_CHARGE_N(WT_LANE, lt__popcount32(k));
    for (i = 0; i < LT_LANES; i++) {
        unsigned kx, ky, kz, v;
        lt_q16_t x[3], y[3], zk[3];
        int64_t e[3], det;
        int sat;
        if (((unsigned)k >> i & 1u) == 0)
            continue;
        kx = q_lane_axis(w->kx, i);
        ky = q_lane_axis(w->ky, i);
        kz = q_lane_axis(w->kz, i);
        for (v = 0; v < 3; v++) {
            lt_q16_t ax = lt__q16_sub_sat(p[v][kx], w->ox.l[i]);
            lt_q16_t ay = lt__q16_sub_sat(p[v][ky], w->oy.l[i]);
            zk[v] = lt__q16_sub_sat(p[v][kz], w->oz.l[i]);
            x[v] = lt__q16_sub_sat(ax, lt__q16_mul_q30_sat(zk[v], w->sx.l[i]));
            y[v] = lt__q16_sub_sat(ay, lt__q16_mul_q30_sat(zk[v], w->sy.l[i]));
        }
        if (!wt1_edges64(x, y, e, &det))
            continue;
        LT_CHARGE(WT_TRI1_T);
        t->l[i] = wt1_t64(e, det, zk, w->sz.l[i], w->sh[i], &sat);
        LT_EVENT(SAT, sat);
        m |= 1u << i;
    }
    return (lt_mask16_t)m;
}
#define LTN_WT_MEET_LANES q_meet_lanes

#if LT__X86_LANES == 512 && LT_COST_MODE != LT_COST_SIM
/* lt__wt16_meet_q16's test in AVX-512 registers up to the candidate lanes, the same per-lane
 * arithmetic as the lane ops (so the same bits): the pick, the saturating translate
 * (lt__x86_qsub), the s1.30 shear (lt__x86_mulr, half up), the exact s31.32 edges as int64 (each
 * half of the lanes sign-extended, vpmuldq), their signs and det; then the candidates' t through
 * q_tsum / q_tdiv_m as the C body. The lane ops passed their 64- and 128-byte vectors through
 * the stack. No events: the counting build keeps the lane ops. */
static __m512i q_pick_reg(const lt_mask16_t m[3], lt_mask16_t k, int32_t p0, int32_t p1,
                          int32_t p2)
{
    if ((m[0] & k) == k)
        return _mm512_set1_epi32(p0);
    if ((m[1] & k) == k)
        return _mm512_set1_epi32(p1);
    if ((m[2] & k) == k)
        return _mm512_set1_epi32(p2);
    return _mm512_mask_blend_epi32(m[2], _mm512_mask_blend_epi32(m[1], _mm512_set1_epi32(p0),
                                                                  _mm512_set1_epi32(p1)),
                                   _mm512_set1_epi32(p2));
}

/* lanes 8h..8h+7 of v sign-extended to int64 */
LT_INLINE __m512i q_half64(__m512i v, int h)
{
    return _mm512_cvtepi32_epi64(h ? _mm512_extracti64x4_epi64(v, 1) : _mm512_castsi512_si256(v));
}

static lt_mask16_t q_meet_reg(const lt_wt16_q16_t *w, lt_mask16_t k, const lt_q16_t p[3][3],
                              lt_vq16_t *t)
{
    const __m512i ox = _mm512_loadu_si512(w->ox.l), oy = _mm512_loadu_si512(w->oy.l);
    const __m512i oz = _mm512_loadu_si512(w->oz.l), sx = _mm512_loadu_si512(w->sx.l);
    const __m512i sy = _mm512_loadu_si512(w->sy.l), z = _mm512_setzero_si512();
    __m512i x[3], y[3], zk[3], eu[2], ev[2], ew[2], det[2];
    unsigned neg = 0, pos = 0, nz = 0, valid;
    int i, h;
    for (i = 0; i < 3; i++) {
        zk[i] = lt__x86_qsub(q_pick_reg(w->kz, k, p[i][0], p[i][1], p[i][2]), oz, 0);
        x[i] = lt__x86_qsub(lt__x86_qsub(q_pick_reg(w->kx, k, p[i][0], p[i][1], p[i][2]), ox, 0),
                            lt__x86_mulr(zk[i], sx, 30u, 0), 0);
        y[i] = lt__x86_qsub(lt__x86_qsub(q_pick_reg(w->ky, k, p[i][0], p[i][1], p[i][2]), oy, 0),
                            lt__x86_mulr(zk[i], sy, 30u, 0), 0);
    }
    for (h = 0; h < 2; h++) {
        const __m512i x0 = q_half64(x[0], h), x1 = q_half64(x[1], h), x2 = q_half64(x[2], h);
        const __m512i y0 = q_half64(y[0], h), y1 = q_half64(y[1], h), y2 = q_half64(y[2], h);
        unsigned sh = 8u * (unsigned)h;
        eu[h] = _mm512_sub_epi64(_mm512_mul_epi32(x2, y1), _mm512_mul_epi32(y2, x1));
        ev[h] = _mm512_sub_epi64(_mm512_mul_epi32(x0, y2), _mm512_mul_epi32(y0, x2));
        ew[h] = _mm512_sub_epi64(_mm512_mul_epi32(x1, y0), _mm512_mul_epi32(y1, x0));
        det[h] = _mm512_add_epi64(_mm512_add_epi64(eu[h], ev[h]), ew[h]);
        neg |= (unsigned)(_mm512_cmplt_epi64_mask(eu[h], z) | _mm512_cmplt_epi64_mask(ev[h], z) |
                          _mm512_cmplt_epi64_mask(ew[h], z)) << sh;
        pos |= (unsigned)(_mm512_cmpgt_epi64_mask(eu[h], z) | _mm512_cmpgt_epi64_mask(ev[h], z) |
                          _mm512_cmpgt_epi64_mask(ew[h], z)) << sh;
        nz |= (unsigned)_mm512_cmpneq_epi64_mask(det[h], z) << sh;
    }
    valid = (unsigned)k & ~(neg & pos) & nz;
    if (valid == 0)
        return 0;
    {
        const __m512i sz = _mm512_loadu_si512(w->sz.l);
        lt_vql32_t u, v, ww, d;
        lt_vq16_t za, zb, zc;
        for (h = 0; h < 2; h++) {
            _mm512_storeu_si512(u.l + 8 * h, eu[h]);
            _mm512_storeu_si512(v.l + 8 * h, ev[h]);
            _mm512_storeu_si512(ww.l + 8 * h, ew[h]);
            _mm512_storeu_si512(d.l + 8 * h, det[h]);
        }
        _mm512_storeu_si512(za.l, lt__x86_mulr(zk[0], sz, 30u, 0));
        _mm512_storeu_si512(zb.l, lt__x86_mulr(zk[1], sz, 30u, 0));
        _mm512_storeu_si512(zc.l, lt__x86_mulr(zk[2], sz, 30u, 0));
        *t = q_tdiv_m(*t, (lt_mask16_t)valid, q_tsum((lt_mask16_t)valid, u, v, ww, za, zb, zc), d,
                      w);
    }
    return (lt_mask16_t)valid;
}
#define LTN_WT_MEET_REG q_meet_reg
#elif LT__X86_LANES == 256 && LT_COST_MODE != LT_COST_SIM
/* The same on AVX2, one 8-lane half at a time (lt__x86_qsub8, lt__x86_mulr8; the edges as four
 * int64 lanes per quarter). */
static __m256i q_pick8(const lt_mask16_t m[3], unsigned h, unsigned k, int32_t p0, int32_t p1,
                       int32_t p2)
{
    unsigned m0 = (unsigned)m[0] >> h & 0xFFu, m1 = (unsigned)m[1] >> h & 0xFFu;
    unsigned m2 = (unsigned)m[2] >> h & 0xFFu;
    if ((m0 & k) == k)
        return _mm256_set1_epi32(p0);
    if ((m1 & k) == k)
        return _mm256_set1_epi32(p1);
    if ((m2 & k) == k)
        return _mm256_set1_epi32(p2);
    return _mm256_blendv_epi8(_mm256_blendv_epi8(_mm256_set1_epi32(p0), _mm256_set1_epi32(p1),
                                                 lt__x86_mask8(m1)),
                              _mm256_set1_epi32(p2), lt__x86_mask8(m2));
}

/* lanes 4q..4q+3 of an 8-lane half sign-extended to int64 */
LT_INLINE __m256i q_quarter64(__m256i v, int q)
{
    return _mm256_cvtepi32_epi64(q ? _mm256_extracti128_si256(v, 1) : _mm256_castsi256_si128(v));
}

LT_INLINE unsigned q_bits4(__m256i m)
{
    return (unsigned)_mm256_movemask_pd(_mm256_castsi256_pd(m));
}

static lt_mask16_t q_meet_reg(const lt_wt16_q16_t *w, lt_mask16_t k, const lt_q16_t p[3][3],
                              lt_vq16_t *t)
{
    lt_vql32_t u, v, ww, d;
    lt_vq16_t za, zb, zc;
    unsigned h, valid = 0;
    for (h = 0; h < LT_LANES; h += 8) {
        const unsigned k8 = (unsigned)k >> h & 0xFFu;
        const __m256i ox = lt__x86_load8(w->ox.l + h), oy = lt__x86_load8(w->oy.l + h);
        const __m256i oz = lt__x86_load8(w->oz.l + h), sx = lt__x86_load8(w->sx.l + h);
        const __m256i sy = lt__x86_load8(w->sy.l + h), sz = lt__x86_load8(w->sz.l + h);
        const __m256i z = _mm256_setzero_si256();
        __m256i x[3], y[3], zk[3];
        unsigned neg = 0, pos = 0, nz = 0, v8;
        int i, q;
        if (k8 == 0)
            continue;
        for (i = 0; i < 3; i++) {
            zk[i] = lt__x86_qsub8(q_pick8(w->kz, h, k8, p[i][0], p[i][1], p[i][2]), oz, 0);
            x[i] = lt__x86_qsub8(lt__x86_qsub8(q_pick8(w->kx, h, k8, p[i][0], p[i][1], p[i][2]),
                                               ox, 0),
                                 lt__x86_mulr8(zk[i], sx, 30u, 0), 0);
            y[i] = lt__x86_qsub8(lt__x86_qsub8(q_pick8(w->ky, h, k8, p[i][0], p[i][1], p[i][2]),
                                               oy, 0),
                                 lt__x86_mulr8(zk[i], sy, 30u, 0), 0);
        }
        for (q = 0; q < 2; q++) {
            const __m256i x0 = q_quarter64(x[0], q), x1 = q_quarter64(x[1], q);
            const __m256i x2 = q_quarter64(x[2], q), y0 = q_quarter64(y[0], q);
            const __m256i y1 = q_quarter64(y[1], q), y2 = q_quarter64(y[2], q);
            const unsigned sh = 4u * (unsigned)q, at = h + sh;
            __m256i eu = _mm256_sub_epi64(_mm256_mul_epi32(x2, y1), _mm256_mul_epi32(y2, x1));
            __m256i ev = _mm256_sub_epi64(_mm256_mul_epi32(x0, y2), _mm256_mul_epi32(y0, x2));
            __m256i ew = _mm256_sub_epi64(_mm256_mul_epi32(x1, y0), _mm256_mul_epi32(y1, x0));
            __m256i dt = _mm256_add_epi64(_mm256_add_epi64(eu, ev), ew);
            neg |= q_bits4(_mm256_or_si256(_mm256_or_si256(_mm256_cmpgt_epi64(z, eu),
                                                           _mm256_cmpgt_epi64(z, ev)),
                                           _mm256_cmpgt_epi64(z, ew))) << sh;
            pos |= q_bits4(_mm256_or_si256(_mm256_or_si256(_mm256_cmpgt_epi64(eu, z),
                                                           _mm256_cmpgt_epi64(ev, z)),
                                           _mm256_cmpgt_epi64(ew, z))) << sh;
            nz |= (~q_bits4(_mm256_cmpeq_epi64(dt, z)) & 0xFu) << sh;
            _mm256_storeu_si256((__m256i *)(void *)(u.l + at), eu);
            _mm256_storeu_si256((__m256i *)(void *)(v.l + at), ev);
            _mm256_storeu_si256((__m256i *)(void *)(ww.l + at), ew);
            _mm256_storeu_si256((__m256i *)(void *)(d.l + at), dt);
        }
        v8 = k8 & ~(neg & pos) & nz;
        if (v8 == 0)
            continue;
        _mm256_storeu_si256((__m256i *)(void *)(za.l + h), lt__x86_mulr8(zk[0], sz, 30u, 0));
        _mm256_storeu_si256((__m256i *)(void *)(zb.l + h), lt__x86_mulr8(zk[1], sz, 30u, 0));
        _mm256_storeu_si256((__m256i *)(void *)(zc.l + h), lt__x86_mulr8(zk[2], sz, 30u, 0));
        valid |= v8 << h;
    }
    if (valid == 0)
        return 0;
    *t = q_tdiv_m(*t, (lt_mask16_t)valid, q_tsum((lt_mask16_t)valid, u, v, ww, za, zb, zc), d, w);
    return (lt_mask16_t)valid;
}
#define LTN_WT_MEET_REG q_meet_reg
#endif

#include "numerics/lt_traits_q16.h"
#define LTN_WT lt_wt16_q16_t
#define LTN_DV lt_vq30_t
#define LTN_D_ABS lt_vq30_abs_sat
#define LTN_D_CMPGE lt_vq30_cmpge
#define LTN_D_CMPLT0 lt_vq30_cmplt0
#define LTN_D_BLEND lt_vq30_blend
#define LTN_D_SET1 lt_vq30_set1
/* the rest of a lane broadcast (lt__wt16_meet_tris): the t scale */
#define LTN_WT_LANE_EXTRA(r, w, j) memset_sh((r)->sh, (w)->sh[(j)])
#define LTN_WT_BADDIR q_baddir
#define LTN_WT_RATIO q_ratio
#define LTN_WT_RECIP q_recip
#define LTN_WT_NORM q_norm
/* round(S * a): s1.30 x s15.16 -> 46 fractional bits -> s15.16, half up. Cost: VMUL x1. */
#define LTN_WT_MULS(s, a) lt_vq16_mul_q30_sat((a), (s))
#define LTN_E lt_vql32_t /* edge functions and det: s31.32 */
#define LTN_E_ADD lt_vql32_add_wrap
#define LTN_E_ZERO() lt_vql32_set1(0)
#define LTN_E_CMPLT_M lt_vql32_cmplt_m
#define LTN_E_CMPGT_M lt_vql32_cmpgt_m
/* ax by - ay bx exactly: s15.16 x s15.16 -> s31.32. |sheared| <= 2^14 units (2^30 raw) keeps
 * each product within 2^60 and the difference within 2^61. Cost: VMUL x2, VMULW x1. */
#define LTN_WT_CROSS2(ax, ay, bx, by) lt_vql32_cross_q16((ax), (by), (ay), (bx))
#define LTN_WT_EXACT_EDGES 1
#define LTN_TT wt_v128_t
#define LTN_WT_TSUM q_tsum
#define LTN_WT_TDIV_M q_tdiv_m
#define LTN_WT_ZERO_AREA q_zero_area
#define LTN_WT_ZERO_AREA1 q_zero_area1
#define LTN_WT_ZERO_AREA16 WT_Q_ZERO_AREA16
#include "lt_wt.inc"
#include "numerics/lt_traits_undef.h"
#undef LTN_WT
#undef LTN_DV
#undef LTN_D_ABS
#undef LTN_D_CMPGE
#undef LTN_D_CMPLT0
#undef LTN_D_BLEND
#undef LTN_D_SET1
#undef LTN_WT_LANE_EXTRA
#undef LTN_WT_BADDIR
#undef LTN_WT_RATIO
#undef LTN_WT_RECIP
#undef LTN_WT_NORM
#undef LTN_WT_MULS
#undef LTN_E
#undef LTN_E_ADD
#undef LTN_E_ZERO
#undef LTN_E_CMPLT_M
#undef LTN_E_CMPGT_M
#undef LTN_WT_CROSS2
#undef LTN_WT_EXACT_EDGES
#undef LTN_TT
#undef LTN_WT_TSUM
#undef LTN_WT_TDIV_M
#undef LTN_WT_ZERO_AREA
#undef LTN_WT_ZERO_AREA1
#undef LTN_WT_ZERO_AREA16
#undef LTN_WT_MEET_LANES
#undef LTN_WT_MEET_REG

/* ---- s15.16 on a grid: the watertight test with 32-bit edge functions (LT_ISECT_WT32) ---------- */

/* A sheared vertex is snapped to the grid of step 2^g raw when both its coordinates then lie within
 * WT32_LIM steps: each 2D cross product of two snapped points is then below 2^29 and det below
 * 2^31, so edges and det are int32 and T = U z0 + V z1 + W z2 an int64. */
#define WT32_LIM 16383

/* round(x / 2^g), half up, in int64 (no overflow for any x). */
static int64_t wt32_snap1(lt_q16_t x, unsigned g)
{
    return g == 0u ? (int64_t)x : lt__asr64((int64_t)x + ((int64_t)1 << (g - 1u)), g);
}

static int wt32_fits(int64_t a) { return a >= -WT32_LIM && a <= WT32_LIM; }

/* floor(n / d) and n mod d for d != 0 and n < d 2^32 (the quotient fits 32 bits), with 32-bit
 * divides only (one UDIV / divu each on the targets, no 64-bit division helper): Knuth's
 * algorithm D in base 2^16 on the normalised divisor (Hacker's Delight, divlu). */
static uint32_t wt32_udiv(uint64_t n, uint32_t d, uint32_t *rem)
{
    unsigned s = lt__clz32(d);
    uint32_t nh = (uint32_t)(n >> 32), nl = (uint32_t)n, d1, d0, n1, n0, q1, q0, r, u;
    d <<= s;
    if (s != 0u) {
        nh = (nh << s) | (nl >> (32u - s));
        nl <<= s;
    }
    d1 = d >> 16;
    d0 = d & 0xFFFFu;
    n1 = nl >> 16;
    n0 = nl & 0xFFFFu;
    q1 = nh / d1;
    r = nh - q1 * d1;
    while (q1 >= 0x10000u || q1 * d0 > ((r << 16) | n1)) {
        q1--;
        r += d1;
        if (r >= 0x10000u)
            break;
    }
    u = (nh << 16) + n1 - q1 * d; /* the partial remainder, < d (mod 2^32 arithmetic) */
    q0 = u / d1;
    r = u - q0 * d1;
    while (q0 >= 0x10000u || q0 * d0 > ((r << 16) | n0)) {
        q0--;
        r += d1;
        if (r >= 0x10000u)
            break;
    }
    *rem = ((u << 16) + n0 - q0 * d) >> s;
    return (q1 << 16) | q0;
}

/* t = round(T / det) as s15.16 for det != 0: q_tdiv1's quotient, rounding and saturation for a
 * 64-bit numerator and sh = 0 (the same bits as q_tdiv1 on T sign-extended), by one 64/32-bit
 * division (|det| < 2^31). */
static lt_q16_t wt32_tdiv1(int64_t T, int32_t det, int *sat)
{
    uint64_t n = T < 0 ? 0u - (uint64_t)T : (uint64_t)T;
    uint32_t ad = det < 0 ? 0u - (uint32_t)det : (uint32_t)det;
    uint32_t q, rem;
    int neg = (T < 0) != (det < 0);
    *sat = 0;
    if (n >= (uint64_t)ad << 31) {
        *sat = 1;
        return neg ? LT_Q16_MIN : LT_Q16_MAX;
    }
    q = wt32_udiv(n, ad, &rem);
    if (neg) {
        q += (uint32_t)(rem > ad - rem);
        return q == 0 ? 0 : -(int32_t)(q - 1u) - 1;
    }
    q += (uint32_t)(rem >= ad - rem);
    return lt__ssat32((int64_t)q);
}

/* One ray against one triangle on the grid 2^g: the ray's sheared vertices x, y (raw s15.16, as
 * the exact test shears them), their distances along the ray axis zk, its Sz and shift sh. Each
 * vertex is one 2D point per ray: snapped when it fits the grid's range, else its exact sheared
 * point, so an edge shared by two triangles is the same function in both (watertight: the exact
 * test on those points). With every vertex snapped and sh == 0 (every unit direction): int32
 * edges and det, int64 T, a 64/32 division. Otherwise (*wide = 1) the exact test's int64 edges of
 * the same points (snapped ones scaled back by 2^g, exact) and its 128-bit T and division: the
 * same t (the scale 2^2g cancels in T / det). Returns 1 and *t when the ray meets the points'
 * triangle (signs agree, det != 0). */
static int wt32_lane(const lt_q16_t x[3], const lt_q16_t y[3], const lt_q16_t zk[3], lt_q30_t sz,
                     unsigned sh, unsigned g, lt_q16_t *t, int *wide, int *sat)
{
    int64_t sx[3], sy[3], e[3], det;
    lt_q16_t px[3], py[3];
    int fit[3], i;

    *wide = 0;
    *sat = 0;
    g = g > LT_WT32_SHIFT_MAX ? LT_WT32_SHIFT_MAX : g; /* the documented range */
    for (i = 0; i < 3; i++) {
        sx[i] = wt32_snap1(x[i], g);
        sy[i] = wt32_snap1(y[i], g);
        fit[i] = wt32_fits(sx[i]) && wt32_fits(sy[i]);
    }
    if (fit[0] && fit[1] && fit[2]) {
        int32_t a[3], b[3], u, v, w, d;
        lt_q16_t z[3];
        int neg, pos;
        for (i = 0; i < 3; i++) {
            a[i] = (int32_t)sx[i];
            b[i] = (int32_t)sy[i];
        }
        u = a[2] * b[1] - b[2] * a[1];
        v = a[0] * b[2] - b[0] * a[2];
        w = a[1] * b[0] - b[1] * a[0];
        neg = u < 0 || v < 0 || w < 0;
        pos = u > 0 || v > 0 || w > 0;
        d = u + v + w;
        if ((neg && pos) || d == 0)
            return 0;
        for (i = 0; i < 3; i++)
            z[i] = lt__q16_mul_q30_sat(zk[i], sz);
        if (sh == 0u) {
            *t = wt32_tdiv1((int64_t)u * z[0] + (int64_t)v * z[1] + (int64_t)w * z[2], d, sat);
            return 1;
        }
    }
    *wide = 1;
    for (i = 0; i < 3; i++) {
        px[i] = fit[i] ? (lt_q16_t)(sx[i] * ((int64_t)1 << g)) : x[i];
        py[i] = fit[i] ? (lt_q16_t)(sy[i] * ((int64_t)1 << g)) : y[i];
    }
    if (!wt1_edges64(px, py, e, &det))
        return 0;
    *t = wt1_t64(e, det, zk, sz, sh, sat);
    return 1;
}

lt_mask16_t lt__wt32_meet16_q16(const lt_wt16_q16_t *w, unsigned g, lt_mask16_t k,
                                const lt_tri_q16_t *tri, lt_vq16_t *t)
{
    lt_q16_t p[3][3];
    lt_vq16_t x[3], y[3], zk[3];
    lt_mask16_t meet = 0, wide = 0, wmeet = 0;
    int i, a;

    /* The exact test's first stage with its charges (lt_wt.inc, lt__wt16_meet: load, vertices,
     * zero area, translate and permute, shear), written apart so that the compiled exact test,
     * whose firmware instruction counts the fitted MCU models price, stays as it was. */
    LT_CHARGE(WT_TRI_LOAD);
    LT_MEM(tri, sizeof *tri, LT_MEM_READ);
    LT_EVENT(TRIS, 1);
    LT_EVENT(TRI_RAYS, lt__popcount32(k));
    k = (lt_mask16_t)(k & ~w->bad);
    for (a = 0; a < 3; a++) {
        p[0][a] = tri->v0[a];
        p[1][a] = lt__q16_add_sat(tri->v0[a], tri->e1[a]);
        p[2][a] = lt__q16_add_sat(tri->v0[a], tri->e2[a]);
    }
    LT_CHARGE(WT_TRI_VERTS);
    if (k == 0 || q_zero_area(p))
        return 0;
    for (i = 0; i < 3; i++) {
        lt_vq16_t z = lt_vq16_sub_sat(wt_pick_q16(w->kz, k, p[i][0], p[i][1], p[i][2]), w->oz);
        x[i] = lt_vq16_sub_sat(lt_vq16_sub_sat(wt_pick_q16(w->kx, k, p[i][0], p[i][1], p[i][2]),
                                               w->ox),
                               lt_vq16_mul_q30_sat(z, w->sx));
        y[i] = lt_vq16_sub_sat(lt_vq16_sub_sat(wt_pick_q16(w->ky, k, p[i][0], p[i][1], p[i][2]),
                                               w->oy),
                               lt_vq16_mul_q30_sat(z, w->sy));
        zk[i] = z;
    }
    LT_CHARGE(WT32_EDGES);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        lt_q16_t lx[3], ly[3], lz[3], lt;
        int v, wd, sat;
        if (!LT__ON(k, i))
            continue;
        for (v = 0; v < 3; v++) {
            lx[v] = x[v].l[i];
            ly[v] = y[v].l[i];
            lz[v] = zk[v].l[i];
        }
        if (wt32_lane(lx, ly, lz, w->sz.l[i], w->sh[i], g, &lt, &wd, &sat)) {
            t->l[i] = lt;
            if (wd)
                wmeet = (lt_mask16_t)(wmeet | (1u << i));
            else
                meet = (lt_mask16_t)(meet | (1u << i));
        }
        if (wd)
            wide = (lt_mask16_t)(wide | (1u << i));
        LT_EVENT(SAT, sat);
    }
    /* the wide arithmetic only when a lane needs it, t only when a lane meets the triangle */
    LT_CHARGE_N(WT32_T, meet != 0);
    LT_CHARGE_N(WT32_WIDE, wide != 0);
    LT_CHARGE_N(WT32_WIDE_T, wmeet != 0);
    return (lt_mask16_t)(meet | wmeet);
}

lt_mask16_t lt_tri16_wt32_q16(lt_ray16_q16_t *r, const lt_wt16_q16_t *w, unsigned g, lt_mask16_t k,
                              const lt_tri_q16_t *tri, int32_t id, lt_hit16_t *hit)
{
    lt_vq16_t t = r->tmax;
    lt_mask16_t hits = lt__wt32_meet16_q16(w, g, k, tri, &t);
    if (hits == 0)
        return 0;
    hits = lt_vq16_cmpgt_m(hits, t, r->tmin);
    hits = lt_vq16_cmplt_m(hits, t, r->tmax);
    r->tmax = lt_vq16_blend(hits, r->tmax, t);
    hit->id = lt_vi32_blend(hits, hit->id, lt_vi32_set1(id));
    LT_EVENT(HITS, lt__popcount32(hits));
    return hits;
}

/* Its first stage is lt_tri1_wt_q16's, written again on purpose: shared through an inline helper
 * it changed the compiled lt_tri1_wt_q16 on cm4 and rv32 (measured), whose firmware instruction
 * counts the fitted MCU cycle models price. */
int lt_tri1_wt32_q16(const lt_wt1_q16_t *w, unsigned g, const lt_tri_q16_t *tri, lt_q16_t tmin,
                     lt_q16_t *tmax)
{
    lt_q16_t p[3][3], x[3], y[3], zk[3], t;
    int i, a, wide, sat;

    LT_CHARGE(WT32_TRI1);
    LT_MEM(tri, sizeof *tri, LT_MEM_READ);
    LT_EVENT(TRIS, 1);
    LT_EVENT(TRI_RAYS, 1);
    if (w->bad)
        return 0;
    for (a = 0; a < 3; a++) {
        p[0][a] = tri->v0[a];
        p[1][a] = lt__q16_add_sat(tri->v0[a], tri->e1[a]);
        p[2][a] = lt__q16_add_sat(tri->v0[a], tri->e2[a]);
    }
    if (q_zero_area(p))
        return 0;
    for (i = 0; i < 3; i++) {
        lt_q16_t ax = lt__q16_sub_sat(p[i][w->k[0]], w->o[0]);
        lt_q16_t ay = lt__q16_sub_sat(p[i][w->k[1]], w->o[1]);
        zk[i] = lt__q16_sub_sat(p[i][w->k[2]], w->o[2]);
        x[i] = lt__q16_sub_sat(ax, lt__q16_mul_q30_sat(zk[i], w->s[0]));
        y[i] = lt__q16_sub_sat(ay, lt__q16_mul_q30_sat(zk[i], w->s[1]));
    }
    if (!wt32_lane(x, y, zk, w->s[2], w->sh, g, &t, &wide, &sat)) {
        LT_CHARGE_N(WT32_TRI1_WIDE, wide);
        return 0;
    }
    LT_CHARGE_N(WT32_TRI1_WIDE, wide);
    LT_CHARGE_N(WT32_TRI1_T, !wide);
    LT_CHARGE_N(WT_TRI1_T, wide);
    LT_EVENT(SAT, sat);
    if (t > tmin && t < *tmax) {
        *tmax = t;
        LT_EVENT(HITS, 1);
        return 1;
    }
    return 0;
}

/* The largest of |e1|, |e2|, |e2 - e1| over the axes (raw), in int64. */
static int64_t wt32_edge_max(const lt_tri_q16_t *tri)
{
    int64_t m = 0;
    int a;
    for (a = 0; a < 3; a++) {
        int64_t e1 = tri->e1[a], e2 = tri->e2[a], d = e2 - e1;
        e1 = e1 < 0 ? -e1 : e1;
        e2 = e2 < 0 ? -e2 : e2;
        d = d < 0 ? -d : d;
        m = e1 > m ? e1 : m;
        m = e2 > m ? e2 : m;
        m = d > m ? d : m;
    }
    return m;
}

unsigned lt_wt32_shift_q16(const lt_tri_q16_t *tris, uint32_t n)
{
    uint32_t hist[34], i, total = 0, acc = 0;
    unsigned b, g = 0;
    for (b = 0; b < 34u; b++)
        hist[b] = 0;
    for (i = 0; i < n; i++) {
        int64_t m = wt32_edge_max(&tris[i]);
        if (m == 0)
            continue;
        for (b = 0; b < 33u && (m >> b) != 0; b++) {
        }
        hist[b]++; /* m < 2^b */
        total++;
    }
    for (b = 0; b < 34u && total != 0; b++) {
        acc += hist[b];
        if ((uint64_t)acc * 100u >= (uint64_t)total * LT_WT32_SHIFT_PCT) {
            /* |sheared| < 2^(b+1) for a vertex of a triangle the ray meets: 2^(b+1-g) <= 2^13 */
            g = b > 12u ? b - 12u : 0u;
            break;
        }
    }
    return g > LT_WT32_SHIFT_MAX ? LT_WT32_SHIFT_MAX : g;
}

/* ---- float32 -------------------------------------------------------------------------------- */
#if LT_CFG_FLOAT32

/* Lanes with d[kz] == 0 (all of d zero) or NaN. Cost: FADD x1, FCMP x1. */
static lt_mask16_t f_baddir(lt_vf32_t dkz)
{
    return (lt_mask16_t)~lt_vf32_cmpgt(lt_vf32_abs(dkz), lt_vf32_set1(0.0f));
}

/* num / den per lane (IEEE); bad lanes get 0. Cost: FDIV x1. */
static lt_vf32_t f_ratio(lt_vf32_t num, lt_vf32_t den, lt_mask16_t bad)
{
    int i;
    LT_CHARGE(WT_F_RATIO);
    for (i = 0; i < LT_LANES; i++)
        num.l[i] = LT__ON(bad, i) ? 0.0f : num.l[i] / den.l[i];
    return num;
}

static lt_vf32_t f_recip(lt_vf32_t den, lt_mask16_t bad)
{
    int i;
    LT_CHARGE(WT_F_RECIP);
    for (i = 0; i < LT_LANES; i++)
        den.l[i] = LT__ON(bad, i) ? 0.0f : 1.0f / den.l[i];
    return den;
}

#if LT_CFG_WT_F64_FALLBACK
/* A double edge function back to float with its sign kept: a nonzero value below the float range
 * becomes +-FLT_MIN instead of 0 (only for sheared coordinates below ~2^-63 units). */
static float f_narrow(double e)
{
    float f = (float)e;
    if (f == 0.0f && e != 0.0)
        f = e > 0.0 ? 1.17549435e-38f : -1.17549435e-38f;
    return f;
}

/* The paper's fallback: for lanes in z, U, V, W again in double. A float x float product is exact
 * in double (48 <= 53 bits) and the difference of two exact products is rounded with its exact
 * sign, so every recomputed edge sign is exact; both neighbours of an edge run this same code.
 * Cost: FMUL x6, FADD x3 (charged as lane ops). */
static void f_edge_fix(lt_mask16_t z, lt_vf32_t *u, lt_vf32_t *v, lt_vf32_t *w,
                       const lt_vf32_t x[3], const lt_vf32_t y[3])
{
    int i;
    LT_CHARGE(WT_F_EDGE_FIX);
    LT_UTIL(z);
    for (i = 0; i < LT_LANES; i++) {
        double ax, ay, bx, by, cx, cy;
        if (!LT__ON(z, i))
            continue;
        ax = (double)x[0].l[i];
        ay = (double)y[0].l[i];
        bx = (double)x[1].l[i];
        by = (double)y[1].l[i];
        cx = (double)x[2].l[i];
        cy = (double)y[2].l[i];
        u->l[i] = f_narrow(cx * by - cy * bx);
        v->l[i] = f_narrow(ax * cy - ay * cx);
        w->l[i] = f_narrow(bx * ay - by * ax);
    }
}

/* e1 x e2 == 0 exactly: float differences and their products are exact in double for
 * coordinates within a 2^29 ratio of each other. Uncharged, as q_zero_area1. */
static int f_zero_area1(float p[3][3])
{
    double a[3], b[3];
    int i;
    for (i = 0; i < 3; i++) {
        a[i] = (double)p[1][i] - (double)p[0][i];
        b[i] = (double)p[2][i] - (double)p[0][i];
    }
    return a[1] * b[2] == a[2] * b[1] && a[2] * b[0] == a[0] * b[2] && a[0] * b[1] == a[1] * b[0];
}
#define F_EXACT_EDGES 0
#else
/* Without double: products compared in float, so a zero-area triangle is always caught but a
 * sliver whose products round equal is taken as zero-area too. Uncharged, as q_zero_area1. */
static int f_zero_area1(float p[3][3])
{
    float a[3], b[3];
    int i;
    for (i = 0; i < 3; i++) {
        a[i] = p[1][i] - p[0][i];
        b[i] = p[2][i] - p[0][i];
    }
    return a[1] * b[2] == a[2] * b[1] && a[2] * b[0] == a[0] * b[2] && a[0] * b[1] == a[1] * b[0];
}
#define F_EXACT_EDGES 1
#endif

/* Cost: SALU x9, SMUL x6. */
static int f_zero_area(float p[3][3])
{
    LT_CHARGE(WT_ZERO_AREA);
    return f_zero_area1(p);
}

/* ---- single rays in float32: one lane of the packet test ----------------------------------- */

int lt_ray1_wt_setup_f32(const float o[3], const float d[3], lt_wt1_f32_t *w)
{
    unsigned k[3];
    float dkz, a0 = lt__f32_abs(d[0]), a1 = lt__f32_abs(d[1]), a2 = lt__f32_abs(d[2]);
    LT_CHARGE(WT_RAY1_SETUP);
    k[2] = WT1_KZ(a0, a1, a2);
    dkz = d[k[2]];
    wt1_kxky(k, dkz < 0.0f);
    w->k[0] = (uint8_t)k[0];
    w->k[1] = (uint8_t)k[1];
    w->k[2] = (uint8_t)k[2];
    w->o[0] = o[k[0]];
    w->o[1] = o[k[1]];
    w->o[2] = o[k[2]];
    w->bad = (uint8_t)!(lt__f32_abs(dkz) > 0.0f);
    w->s[0] = w->bad ? 0.0f : d[k[0]] / dkz;
    w->s[1] = w->bad ? 0.0f : d[k[1]] / dkz;
    w->s[2] = w->bad ? 0.0f : 1.0f / dkz;
    w->pad_[0] = w->pad_[1] = w->pad_[2] = w->pad_[3] = 0;
    return w->bad;
}

/* The stage of lt_tri1_wt_f32 after the edges: a zero edge recomputed exactly in double, the
 * signs, det, t and the acceptance tmin < t < *tmax; one body with the wide tree's leaf blocks
 * (x, y the sheared vertices, zk their z before the shear, eu, ev, ew the float edges). */
static int f_tri1_tail(const lt_wt1_f32_t *w, const float x[3], const float y[3],
                       const float zk[3], float eu, float ev, float ew, float tmin, float *tmax)
{
    float det, tn, t;
    int neg, pos;
#if !F_EXACT_EDGES
    if (eu == 0.0f || ev == 0.0f || ew == 0.0f) {
        LT_CHARGE(WT_F_EDGE_FIX1);
        eu = f_narrow((double)x[2] * (double)y[1] - (double)y[2] * (double)x[1]);
        ev = f_narrow((double)x[0] * (double)y[2] - (double)y[0] * (double)x[2]);
        ew = f_narrow((double)x[1] * (double)y[0] - (double)y[1] * (double)x[0]);
    }
#endif
    neg = eu < 0.0f || ev < 0.0f || ew < 0.0f;
    pos = eu > 0.0f || ev > 0.0f || ew > 0.0f;
    det = (eu + ev) + ew;
    if ((neg && pos) || !(det < 0.0f || det > 0.0f))
        return 0;
    LT_CHARGE(WT_TRI1_T);
    tn = (eu * (w->s[2] * zk[0]) + ev * (w->s[2] * zk[1])) + ew * (w->s[2] * zk[2]);
    t = tn / det;
    if (t > tmin && t < *tmax) {
        *tmax = t;
        LT_EVENT(HITS, 1);
        return 1;
    }
    return 0;
}

int lt_tri1_wt_f32(const lt_wt1_f32_t *w, const lt_tri_f32_t *tri, float tmin, float *tmax)
{
    float p[3][3], x[3], y[3], zk[3];
    int i, a;

    LT_CHARGE(WT_TRI1);
    LT_MEM(tri, sizeof *tri, LT_MEM_READ);
    LT_EVENT(TRIS, 1);
    LT_EVENT(TRI_RAYS, 1);
    if (w->bad)
        return 0;
    for (a = 0; a < 3; a++) {
        p[0][a] = tri->v0[a];
        p[1][a] = tri->v0[a] + tri->e1[a];
        p[2][a] = tri->v0[a] + tri->e2[a];
    }
    if (f_zero_area(p))
        return 0;
    for (i = 0; i < 3; i++) {
        float ax = p[i][w->k[0]] - w->o[0], ay = p[i][w->k[1]] - w->o[1];
        zk[i] = p[i][w->k[2]] - w->o[2];
        x[i] = ax - w->s[0] * zk[i];
        y[i] = ay - w->s[1] * zk[i];
    }
    return f_tri1_tail(w, x, y, zk, x[2] * y[1] - y[2] * x[1], x[0] * y[2] - y[0] * x[2],
                       x[1] * y[0] - y[1] * x[0], tmin, tmax);
}

/* The wide tree's leaf blocks: lt_tri1_wt_f32 per lane (lt_isel.h). */
int32_t lt__wt_tris4_f32(const lt_wt1_f32_t *w, const lt_bvh8_tris4_f32_t *b, uint32_t n,
                         float tmin, float *tmax, int any)
{
    const unsigned k0 = w->k[0], k1 = w->k[1], k2 = w->k[2];
    int32_t res = -1;
    uint32_t done;
    for (done = 0; done < n; done += LT_BVH8_LANES, b++) {
        uint32_t nt = n - done < LT_BVH8_LANES ? n - done : LT_BVH8_LANES;
        float x[3][LT_BVH8_LANES], y[3][LT_BVH8_LANES], zk[3][LT_BVH8_LANES];
        float eu[LT_BVH8_LANES], ev[LT_BVH8_LANES], ew[LT_BVH8_LANES];
        int32_t ok[LT_BVH8_LANES];
        unsigned c, v, m = 0;
        wt_block_terms(b, sizeof *b, nt);
        if (w->bad)
            continue;
#if LT__X86_LANES && LT_COST_MODE != LT_COST_SIM
        /* the two stages below in registers (lt_v16_x86.h) */
        m = lt__x86_tris4_f32((const float(*)[LT_BVH8_LANES])b->v, b->id, k0, k1, k2, w->o, w->s,
                              !F_EXACT_EDGES, x, y, zk, eu, ev, ew);
        (void)ok;
#else
        /* translate, permute and shear the lanes' vertices (lt_tri1_wt_f32's first stage) */
        for (v = 0; v < 3; v++)
            for (c = 0; c < LT_BVH8_LANES; c++) {
                float ax = b->v[3 * v + k0][c] - w->o[0], ay = b->v[3 * v + k1][c] - w->o[1];
                zk[v][c] = b->v[3 * v + k2][c] - w->o[2];
                x[v][c] = ax - w->s[0] * zk[v][c];
                y[v][c] = ay - w->s[1] * zk[v][c];
            }
        /* edges, signs, det (no short circuits, so the loop stays SIMD): the lanes that may meet
           the ray, a lane with a zero edge among them (the tail recomputes it exactly) */
        for (c = 0; c < LT_BVH8_LANES; c++) {
            int neg, pos, zr;
            float det;
            eu[c] = x[2][c] * y[1][c] - y[2][c] * x[1][c];
            ev[c] = x[0][c] * y[2][c] - y[0][c] * x[2][c];
            ew[c] = x[1][c] * y[0][c] - y[1][c] * x[0][c];
            neg = (eu[c] < 0.0f) | (ev[c] < 0.0f) | (ew[c] < 0.0f);
            pos = (eu[c] > 0.0f) | (ev[c] > 0.0f) | (ew[c] > 0.0f);
            det = (eu[c] + ev[c]) + ew[c];
            zr = ((eu[c] == 0.0f) | (ev[c] == 0.0f) | (ew[c] == 0.0f)) & !F_EXACT_EDGES;
            ok[c] = ((((neg & pos) ^ 1) & ((det < 0.0f) | (det > 0.0f))) | zr) & (b->id[c] >= 0);
        }
        for (c = 0; c < LT_BVH8_LANES; c++)
            m |= (unsigned)ok[c] << c;
#endif
        /* the lanes that may meet the ray, in order: lt_tri1_wt_f32's tail */
        for (; m != 0; m &= m - 1u) {
            float xs[3], ys[3], zs[3];
            c = lt__ctz32(m);
            for (v = 0; v < 3; v++) {
                xs[v] = x[v][c];
                ys[v] = y[v][c];
                zs[v] = zk[v][c];
            }
            if (f_tri1_tail(w, xs, ys, zs, eu[c], ev[c], ew[c], tmin, tmax)) {
                res = b->id[c];
                if (any)
                    return res;
            }
        }
    }
    return res;
}

#if LT__X86_LANES == 512 && LT_COST_MODE != LT_COST_SIM
/* lt__wt16_meet_f32's test (lt_wt.inc: the pick, translate, shear, edge, sign and t stages) in
 * AVX-512 registers (AVX2: two 8-lane halves, below), the same operations in the same order per
 * lane as the lane ops (so the same bits): the lane ops pass their 64-byte vectors through
 * memory, and GCC kept this kernel's arrays of them on the stack between every two ops. Lanes
 * with a zero float edge take f_edge_fix as the C body does. No events: the counting build keeps
 * the lane ops. */
static __m512 f_pick_reg(const lt_mask16_t m[3], lt_mask16_t k, float p0, float p1, float p2)
{
    if ((m[0] & k) == k)
        return _mm512_set1_ps(p0);
    if ((m[1] & k) == k)
        return _mm512_set1_ps(p1);
    if ((m[2] & k) == k)
        return _mm512_set1_ps(p2);
    return _mm512_mask_blend_ps(m[2], _mm512_mask_blend_ps(m[1], _mm512_set1_ps(p0),
                                                            _mm512_set1_ps(p1)),
                                _mm512_set1_ps(p2));
}

static lt_mask16_t f_meet_reg(const lt_wt16_f32_t *w, lt_mask16_t k, const float p[3][3],
                              lt_vf32_t *t)
{
    const __m512 ox = _mm512_loadu_ps(w->ox.l), oy = _mm512_loadu_ps(w->oy.l);
    const __m512 oz = _mm512_loadu_ps(w->oz.l), sx = _mm512_loadu_ps(w->sx.l);
    const __m512 sy = _mm512_loadu_ps(w->sy.l), z = _mm512_setzero_ps();
    __m512 x0, x1, x2, y0, y1, y2, k0, k1, k2, eu, ev, ew, det, tn, sz;
    __mmask16 zero, neg, pos, valid;
#define F_MEET_VERT(i, xi, yi, ki)                                                                 \
    do {                                                                                           \
        ki = _mm512_sub_ps(f_pick_reg(w->kz, k, p[i][0], p[i][1], p[i][2]), oz);                   \
        xi = _mm512_sub_ps(_mm512_sub_ps(f_pick_reg(w->kx, k, p[i][0], p[i][1], p[i][2]), ox),     \
                           _mm512_mul_ps(sx, ki));                                                 \
        yi = _mm512_sub_ps(_mm512_sub_ps(f_pick_reg(w->ky, k, p[i][0], p[i][1], p[i][2]), oy),     \
                           _mm512_mul_ps(sy, ki));                                                 \
    } while (0)
    F_MEET_VERT(0, x0, y0, k0);
    F_MEET_VERT(1, x1, y1, k1);
    F_MEET_VERT(2, x2, y2, k2);
#undef F_MEET_VERT
    eu = _mm512_sub_ps(_mm512_mul_ps(x2, y1), _mm512_mul_ps(y2, x1));
    ev = _mm512_sub_ps(_mm512_mul_ps(x0, y2), _mm512_mul_ps(y0, x2));
    ew = _mm512_sub_ps(_mm512_mul_ps(x1, y0), _mm512_mul_ps(y1, x0));
#if !F_EXACT_EDGES
    zero = (__mmask16)(_mm512_mask_cmp_ps_mask(k, eu, z, _CMP_EQ_OQ) |
                       _mm512_mask_cmp_ps_mask(k, ev, z, _CMP_EQ_OQ) |
                       _mm512_mask_cmp_ps_mask(k, ew, z, _CMP_EQ_OQ));
    if (zero != 0) {
        lt_vf32_t xs[3], ys[3], u, v, ww;
        _mm512_storeu_ps(xs[0].l, x0);
        _mm512_storeu_ps(xs[1].l, x1);
        _mm512_storeu_ps(xs[2].l, x2);
        _mm512_storeu_ps(ys[0].l, y0);
        _mm512_storeu_ps(ys[1].l, y1);
        _mm512_storeu_ps(ys[2].l, y2);
        _mm512_storeu_ps(u.l, eu);
        _mm512_storeu_ps(v.l, ev);
        _mm512_storeu_ps(ww.l, ew);
        f_edge_fix(zero, &u, &v, &ww, xs, ys);
        eu = _mm512_loadu_ps(u.l);
        ev = _mm512_loadu_ps(v.l);
        ew = _mm512_loadu_ps(ww.l);
    }
#else
    (void)zero;
#endif
    neg = (__mmask16)(_mm512_mask_cmp_ps_mask(k, eu, z, _CMP_LT_OQ) |
                      _mm512_mask_cmp_ps_mask(k, ev, z, _CMP_LT_OQ) |
                      _mm512_mask_cmp_ps_mask(k, ew, z, _CMP_LT_OQ));
    pos = (__mmask16)(_mm512_mask_cmp_ps_mask(k, eu, z, _CMP_GT_OQ) |
                      _mm512_mask_cmp_ps_mask(k, ev, z, _CMP_GT_OQ) |
                      _mm512_mask_cmp_ps_mask(k, ew, z, _CMP_GT_OQ));
    valid = (__mmask16)(k & ~(neg & pos));
    det = _mm512_add_ps(_mm512_add_ps(eu, ev), ew);
    valid = (__mmask16)(_mm512_mask_cmp_ps_mask(valid, det, z, _CMP_LT_OQ) |
                        _mm512_mask_cmp_ps_mask(valid, det, z, _CMP_GT_OQ));
    if (valid == 0)
        return 0;
    sz = _mm512_loadu_ps(w->sz.l);
    tn = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(eu, _mm512_mul_ps(sz, k0)),
                                     _mm512_mul_ps(ev, _mm512_mul_ps(sz, k1))),
                       _mm512_mul_ps(ew, _mm512_mul_ps(sz, k2)));
    _mm512_storeu_ps(t->l, _mm512_mask_div_ps(_mm512_loadu_ps(t->l), valid, tn, det));
    return (lt_mask16_t)valid;
}
#define LTN_WT_MEET_REG f_meet_reg
#elif LT__X86_LANES == 256 && LT_COST_MODE != LT_COST_SIM
/* The same on AVX2, one 8-lane half at a time (every op is per lane, so the same bits). */
/* the lanes of m as a float lane mask (the backend's lt__x86_mask8) */
LT_INLINE __m256 f_lanes8(unsigned m) { return _mm256_castsi256_ps(lt__x86_mask8(m)); }

static unsigned f_cmp8(__m256 a, __m256 b, unsigned k, int lt)
{
    return k & (unsigned)_mm256_movemask_ps(lt ? _mm256_cmp_ps(a, b, _CMP_LT_OQ)
                                               : _mm256_cmp_ps(a, b, _CMP_GT_OQ));
}

static __m256 f_pick8(const lt_mask16_t m[3], unsigned h, unsigned k, float p0, float p1, float p2)
{
    unsigned m0 = (unsigned)m[0] >> h & 0xFFu, m1 = (unsigned)m[1] >> h & 0xFFu;
    unsigned m2 = (unsigned)m[2] >> h & 0xFFu;
    if ((m0 & k) == k)
        return _mm256_set1_ps(p0);
    if ((m1 & k) == k)
        return _mm256_set1_ps(p1);
    if ((m2 & k) == k)
        return _mm256_set1_ps(p2);
    return _mm256_blendv_ps(
        _mm256_blendv_ps(_mm256_set1_ps(p0), _mm256_set1_ps(p1), f_lanes8(m1)),
        _mm256_set1_ps(p2), f_lanes8(m2));
}

static lt_mask16_t f_meet_reg(const lt_wt16_f32_t *w, lt_mask16_t k, const float p[3][3],
                              lt_vf32_t *t)
{
    unsigned h, all = 0;
    for (h = 0; h < LT_LANES; h += 8) {
        const unsigned k8 = (unsigned)k >> h & 0xFFu;
        const __m256 ox = _mm256_loadu_ps(w->ox.l + h), oy = _mm256_loadu_ps(w->oy.l + h);
        const __m256 oz = _mm256_loadu_ps(w->oz.l + h), sx = _mm256_loadu_ps(w->sx.l + h);
        const __m256 sy = _mm256_loadu_ps(w->sy.l + h), z = _mm256_setzero_ps();
        __m256 x0, x1, x2, y0, y1, y2, k0, k1, k2, eu, ev, ew, det, tn, sz;
        unsigned zero, neg, pos, valid;
        if (k8 == 0)
            continue;
#define F_MEET_VERT8(i, xi, yi, ki)                                                                \
    do {                                                                                           \
        ki = _mm256_sub_ps(f_pick8(w->kz, h, k8, p[i][0], p[i][1], p[i][2]), oz);                  \
        xi = _mm256_sub_ps(_mm256_sub_ps(f_pick8(w->kx, h, k8, p[i][0], p[i][1], p[i][2]), ox),    \
                           _mm256_mul_ps(sx, ki));                                                 \
        yi = _mm256_sub_ps(_mm256_sub_ps(f_pick8(w->ky, h, k8, p[i][0], p[i][1], p[i][2]), oy),    \
                           _mm256_mul_ps(sy, ki));                                                 \
    } while (0)
        F_MEET_VERT8(0, x0, y0, k0);
        F_MEET_VERT8(1, x1, y1, k1);
        F_MEET_VERT8(2, x2, y2, k2);
#undef F_MEET_VERT8
        eu = _mm256_sub_ps(_mm256_mul_ps(x2, y1), _mm256_mul_ps(y2, x1));
        ev = _mm256_sub_ps(_mm256_mul_ps(x0, y2), _mm256_mul_ps(y0, x2));
        ew = _mm256_sub_ps(_mm256_mul_ps(x1, y0), _mm256_mul_ps(y1, x0));
#if !F_EXACT_EDGES
        zero = k8 & (unsigned)_mm256_movemask_ps(
                        _mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(eu, z, _CMP_EQ_OQ),
                                                  _mm256_cmp_ps(ev, z, _CMP_EQ_OQ)),
                                     _mm256_cmp_ps(ew, z, _CMP_EQ_OQ)));
        if (zero != 0) {
            /* this half's lanes in full vectors: f_edge_fix reads only the lanes of zero */
            lt_vf32_t xs[3], ys[3], u, v, ww;
            _mm256_storeu_ps(xs[0].l + h, x0);
            _mm256_storeu_ps(xs[1].l + h, x1);
            _mm256_storeu_ps(xs[2].l + h, x2);
            _mm256_storeu_ps(ys[0].l + h, y0);
            _mm256_storeu_ps(ys[1].l + h, y1);
            _mm256_storeu_ps(ys[2].l + h, y2);
            _mm256_storeu_ps(u.l + h, eu);
            _mm256_storeu_ps(v.l + h, ev);
            _mm256_storeu_ps(ww.l + h, ew);
            f_edge_fix((lt_mask16_t)(zero << h), &u, &v, &ww, xs, ys);
            eu = _mm256_loadu_ps(u.l + h);
            ev = _mm256_loadu_ps(v.l + h);
            ew = _mm256_loadu_ps(ww.l + h);
        }
#else
        (void)zero;
#endif
        neg = f_cmp8(eu, z, k8, 1) | f_cmp8(ev, z, k8, 1) | f_cmp8(ew, z, k8, 1);
        pos = f_cmp8(eu, z, k8, 0) | f_cmp8(ev, z, k8, 0) | f_cmp8(ew, z, k8, 0);
        valid = k8 & ~(neg & pos);
        det = _mm256_add_ps(_mm256_add_ps(eu, ev), ew);
        valid = f_cmp8(det, z, valid, 1) | f_cmp8(det, z, valid, 0);
        if (valid == 0)
            continue;
        sz = _mm256_loadu_ps(w->sz.l + h);
        tn = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(eu, _mm256_mul_ps(sz, k0)),
                                         _mm256_mul_ps(ev, _mm256_mul_ps(sz, k1))),
                           _mm256_mul_ps(ew, _mm256_mul_ps(sz, k2)));
        _mm256_storeu_ps(t->l + h, _mm256_blendv_ps(_mm256_loadu_ps(t->l + h),
                                                    _mm256_div_ps(tn, det), f_lanes8(valid)));
        all |= valid << h;
    }
    return (lt_mask16_t)all;
}
#define LTN_WT_MEET_REG f_meet_reg
#endif

#include "numerics/lt_traits_f32.h"
#define LTN_WT lt_wt16_f32_t
#define LTN_DV lt_vf32_t
#define LTN_D_ABS lt_vf32_abs
#define LTN_D_CMPGE lt_vf32_cmpge
#define LTN_D_CMPLT0(a) lt_vf32_cmplt((a), lt_vf32_set1(0.0f))
#define LTN_D_BLEND lt_vf32_blend
#define LTN_D_SET1 lt_vf32_set1
#define LTN_WT_LANE_EXTRA(r, w, j) ((void)(r), (void)(w), (void)(j)) /* no t scale in float */
#define LTN_WT_BADDIR f_baddir
#define LTN_WT_RATIO f_ratio
#define LTN_WT_RECIP f_recip
#define LTN_WT_NORM(w, dkz) ((void)(w), (dkz)) /* float needs no scaling */
#define LTN_WT_MULS lt_vf32_mul
#define LTN_E lt_vf32_t
#define LTN_E_ADD lt_vf32_add
#define LTN_E_ZERO() lt_vf32_set1(0.0f)
#define LTN_E_CMPLT_M lt_vf32_cmplt_m
#define LTN_E_CMPGT_M lt_vf32_cmpgt_m
#define LTN_E_CMPEQ_M lt_vf32_cmpeq_m
/* ax by - ay bx */
#define LTN_WT_CROSS2(ax, ay, bx, by) lt_vf32_cross((ax), (by), (ay), (bx))
#define LTN_WT_EXACT_EDGES F_EXACT_EDGES
#define LTN_WT_EDGE_FIX f_edge_fix
#define LTN_TT lt_vf32_t
#define LTN_WT_TSUM(k, u, v, w, za, zb, zc)                                                       \
    ((void)(k), lt_vf32_dot3((u), (v), (w), (za), (zb), (zc)))
#define LTN_WT_TDIV_M(src, k, n, d, w) ((void)(w), lt_vf32_div_m((src), (k), (n), (d)))
#define LTN_WT_ZERO_AREA f_zero_area
#define LTN_WT_ZERO_AREA1 f_zero_area1
#define LTN_WT_ZERO_AREA16 WT_F_ZERO_AREA16
#include "lt_wt.inc"
#include "numerics/lt_traits_undef.h"
#undef LTN_WT_MEET_REG

#endif /* LT_CFG_FLOAT32 */
