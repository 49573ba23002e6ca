/* lt_qt.c - the screen-space quadtree of Widmer et al. 2015 [Widmer15]: layout and size query, the
 * format-specific kernel routines (node codecs, crossings, plane tests, ray setup; the lane ops
 * themselves are lt_v16.h's and lt_v16w.h's), and the traits that instantiate lt_qt.inc three
 * times: 64-bit and 32-bit fixed-point nodes (s1.30 compute, int64 products) and float32 nodes.
 * Node formats are documented in lt_qt.h and docs/quadtree.md. Builds: all; float32 only with
 * LT_CFG_FLOAT32.
 */
#include "lt/lt_qt.h"
#include "lt_qt_grid.h"
#include "lt_ssb.h"

/* ---- parameters and layout ------------------------------------------------------------------- */

void lt_qt_params_default(lt_qt_params_t *p)
{
    p->lambda_h = 1073742;   /* 1e-3 in s1.30 (round(1e-3 * 2^30)) */
    p->lambda_d = 1073742;   /* 1e-3 */
    p->gamma_norm = 1073742; /* 1e-3 */
    p->gamma_dist = 8192;    /* 2^-17 = 7.6e-6 */
}

static lt_status_t qt_check_params(const lt_qt_params_t *p)
{
    if (p->lambda_h < 0 || p->lambda_d < 0 || p->gamma_dist < 0 || p->gamma_norm < 0 ||
        p->gamma_norm > LT_Q30_ONE)
        return LT_E_ARG;
    return LT_OK;
}

/* Fill the level tables of q from d and compute the arena size. */
static lt_status_t qt_layout(const lt_qt_desc_t *d, lt_qt_t *q, size_t *bytes)
{
    uint32_t n = 1, L, dim;
    uint64_t nodes = 0, total;

    if (d == NULL || bytes == NULL)
        return LT_E_ARG;
    if (d->width == 0 || d->height == 0 || d->width > LT_QT_MAX_DIM ||
        d->height > LT_QT_MAX_DIM || d->layers == 0 || d->layers > LT_QT_MAX_LAYERS)
        return LT_E_ARG;
    switch (d->enc) {
    case LT_QT_N64:
        q->node_bytes = 8;
        break;
    case LT_QT_N32:
        q->node_bytes = 4;
        break;
#if LT_CFG_FLOAT32
    case LT_QT_F32:
        q->node_bytes = 16;
        break;
#endif
    default:
        return LT_E_ARG;
    }
    dim = d->width > d->height ? d->width : d->height;
    while ((1u << (n - 1u)) < dim)
        n++;
    q->width = d->width;
    q->height = d->height;
    q->layers = d->layers;
    q->enc = d->enc;
    q->levels = n;
    for (L = 0; L < LT_QT_MAX_LEVELS; L++) {
        if (L < n) {
            q->nx[L] = (d->width + (1u << L) - 1u) >> L;
            q->ny[L] = (d->height + (1u << L) - 1u) >> L;
            q->off[L] = (uint32_t)nodes;
            nodes += (uint64_t)q->nx[L] * q->ny[L];
        } else {
            q->nx[L] = q->ny[L] = 0;
            q->off[L] = (uint32_t)nodes;
        }
    }
    q->layer_nodes = (uint32_t)nodes;
    total = nodes * d->layers * q->node_bytes;
    if (total > (uint64_t)SIZE_MAX)
        return LT_E_RANGE;
    *bytes = (size_t)total;
    return LT_OK;
}

lt_status_t lt_qt_size(const lt_qt_desc_t *d, size_t *bytes)
{
    lt_qt_t q;
    return qt_layout(d, &q, bytes);
}

uint32_t lt_qt_default_steps(const lt_qt_t *qt)
{
    return 8u * (qt->width + qt->height) + 4u * qt->levels + 16u;
}

/* Common checks of the build entry points: layout into qt, space, arena. */
static lt_status_t qt_prepare(lt_qt_t *qt, const lt_qt_desc_t *d, const lt_qt_params_t *p,
                              const void *w, void *arena, size_t *arena_bytes)
{
    size_t need;
    lt_status_t s;
    if (qt == NULL || w == NULL || arena_bytes == NULL)
        return LT_E_ARG;
    s = qt_layout(d, qt, &need);
    if (s != LT_OK)
        return s;
    if (p != NULL) {
        if (qt_check_params(p) != LT_OK)
            return LT_E_ARG;
        qt->params = *p;
    } else {
        lt_qt_params_default(&qt->params);
    }
    if (*arena_bytes < need) {
        *arena_bytes = need;
        return LT_E_SPACE;
    }
    if (arena == NULL || ((uintptr_t)arena & 3u) != 0)
        return LT_E_ARG;
    qt->nodes = arena;
    return LT_OK;
}

/* Node index and the outside-the-grid test: lt__qtgrid_index / lt__qtgrid_outside (lt_qt_grid.h,
 * shared with lt_hiz.c's cells). */
static lt_vi32_t qt_node_index(const lt_qt_t *qt, lt_mask16_t k, lt_vi32_t lvl, lt_vi32_t qx,
                               lt_vi32_t qy)
{
    return lt__qtgrid_index(qt->off, qt->nx, qt->ny, qt->levels, k, lvl, qx, qy);
}

static lt_mask16_t qt_outside(const lt_qt_t *qt, lt_mask16_t k, lt_vi32_t lvl, lt_vi32_t qx,
                              lt_vi32_t qy)
{
    return lt__qtgrid_outside(qt->nx, qt->ny, k, lvl, qx, qy);
}

/* ==== fixed point: s1.30 w and t, int64 wide values ============================================ */

/* Wide values: build values are lt_vql36_t (s1.30 with LS_FRAC = 6 more fraction bits), values
 * along a ray (w_ray(t), plane functions, AABB bounds) lt_vql60_t (s3.60); both are lt_v16w.h's,
 * and the kernels' bounds keep every sum of them below 2^62 (docs/quadtree.md). */

/* gamma * max(lo, 0) as a wide build value: s1.30 x s1.30 -> s2.60 -> LS_FRAC fractional bits below
 * the raw unit (floor). Cost: QT_Q_RELTOL (VMUL x1, VSHIFT x1). */
static lt_vql36_t q_reltol(lt_vq30_t lo, lt_vq30_t g)
{
    lt_vql36_t r;
    int i;
    LT_CHARGE(QT_Q_RELTOL);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = lt__asr64(lt__mul32x32_64(lo.l[i] > 0 ? lo.l[i] : 0, g.l[i]), 24);
    return r;
}

/* Build values carry LS_FRAC fractional bits below the s1.30 raw unit: the least-squares proxy
 * divides by 2, 4 and 8, which then stays exact (up to the 2^-6 floor of the partial-node shift). */
#define LS_FRAC 6u
LT_STATIC_ASSERT(LS_FRAC == 6u, "build values are lt_vql36_t: 30 + 6 fraction bits");

/* Round a value with f fractional bits to an integer, half up (f >= 1). */
LT_INLINE int64_t q_rnd(int64_t v, unsigned f)
{
    return lt__asr64(v + ((int64_t)1 << (f - 1u)), f);
}

/* Two's complement field of `bits` bits (bits <= 16) as a signed value. */
LT_INLINE int32_t q_sext(uint32_t v, unsigned bits)
{
    return (int32_t)v - (int32_t)(((v >> (bits - 1u)) & 1u) << bits);
}

/* Decoded node lanes. Absent (inactive) lanes decode to zeros, which the merge sums rely on. */
typedef struct qdec {
    lt_mask16_t aabb, o; /* lanes holding an AABB / a plane with the discontinuity flag */
    lt_vq30_t c, al, be; /* plane: w at the centre, change across width / height; raw s1.30 */
    lt_vq30_t lo, hi;    /* AABB wmin / wmax; planes (bounds requested): min / max over footprint */
    lt_vq30_t eps;       /* plane: encoding error bound over the footprint, raw */
} qdec_t;

static void qdec_zero(qdec_t *d)
{
    int i;
    d->aabb = d->o = 0;
    for (i = 0; i < LT_LANES; i++)
        d->c.l[i] = d->al.l[i] = d->be.l[i] = d->lo.l[i] = d->hi.l[i] = d->eps.l[i] = 0;
}

/* One decoded node (the single-ray walk's, and each lane's of qdec_t); fields as qdec_t's. */
typedef struct qnode1 {
    int aabb, o;
    int32_t c, al, be, lo, hi, eps;
} qnode1_t;

/* Lane i of d from one decoded node (absent fields stay zero, as qdec_zero left them). */
LT_INLINE void qdec_set1(qdec_t *d, int i, const qnode1_t *q)
{
    if (q->aabb) {
        d->aabb = (lt_mask16_t)(d->aabb | (1u << i));
        d->lo.l[i] = q->lo;
        d->hi.l[i] = q->hi;
        return;
    }
    d->o = (lt_mask16_t)(d->o | ((unsigned)q->o << i));
    d->c.l[i] = q->c;
    d->al.l[i] = q->al;
    d->be.l[i] = q->be;
    d->eps.l[i] = q->eps;
    d->lo.l[i] = q->lo;
    d->hi.l[i] = q->hi;
}

/* min / max of a decoded plane over its footprint: C -+ (|Al| + |Be|) / 2, outward. */
LT_INLINE void qnode1_bounds(qnode1_t *q)
{
    int64_t c2 = 2 * (int64_t)q->c;
    int64_t s = lt__l64_abs_wrap(q->al) + lt__l64_abs_wrap(q->be);
    q->lo = lt__ssat32(lt__asr64(c2 - s, 1));
    q->hi = lt__ssat32(lt__asr64(c2 + s + 1, 1));
}

/* ---- 64-bit node codec --------------------------------------------------------------------- */

LT_INLINE void n64_node1(lt_qt_n64_t n, int bounds, qnode1_t *q)
{
    q->lo = q->hi = 0;
    q->aabb = (int)(n.hi >> 31);
    if (q->aabb) {
        q->lo = (int32_t)(n.lo & 0x7FFFFFFFu);
        q->hi = (int32_t)(n.hi & 0x7FFFFFFFu);
    } else {
        unsigned ec = n.lo & 7u, s = (n.lo >> 3) & 31u;
        int64_t a = q_sext((n.hi >> 15) & 0x7FFFu, 15), b = q_sext(n.hi & 0x7FFFu, 15);
        q->o = (int)((n.hi >> 30) & 1u);
        q->c = lt__ssat32((int64_t)(n.lo >> 8) * ((int64_t)1 << ec));
        q->al = lt__ssat32(a * ((int64_t)1 << s));
        q->be = lt__ssat32(b * ((int64_t)1 << s));
        /* half a step of C, half a step of each slope at half weight at the node's edge,
         * + 1 for the rounding to raw units before encoding */
        q->eps = 1 + (ec != 0 ? (int32_t)(1u << (ec - 1u)) : 0) +
                 (s != 0 ? (int32_t)(1u << (s - 1u)) : 0);
        if (bounds)
            qnode1_bounds(q);
    }
}

static void n64_dec1(lt_qt_n64_t n, int bounds, qdec_t *d, int i)
{
    qnode1_t q;
    n64_node1(n, bounds, &q);
    qdec_set1(d, i, &q);
}

/* Decode base[i0 + stride * lane] for the lanes in k (n64_decode_idx: base[idx]). Cost:
 * LANE_GATHER per active lane, QT_N64_DECODE (VSHIFT x4, VALU x6), with bounds
 * QT_N64_DECODE_BOUNDS (VALU x4). */
static void n64_decode(const lt_qt_n64_t *base, uint32_t i0, uint32_t stride, lt_mask16_t k,
                       int bounds, qdec_t *d)
{
    int i;
    qdec_zero(d);
    LT_CHARGE_N(LANE_GATHER, lt__popcount32(k));
    LT_CHARGE(QT_N64_DECODE);
    LT_CHARGE_N(QT_N64_DECODE_BOUNDS, bounds != 0);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(k, i)) {
            const lt_qt_n64_t *p = &base[i0 + stride * (uint32_t)i];
            LT_MEM(p, sizeof *p, LT_MEM_READ);
            n64_dec1(*p, bounds, d, i);
        }
    }
}

static void n64_decode_idx(const lt_qt_n64_t *base, lt_vi32_t idx, lt_mask16_t k, qdec_t *d)
{
    int i;
    qdec_zero(d);
    LT_CHARGE_N(LANE_GATHER, lt__popcount32(k));
    LT_CHARGE(QT_N64_DECODE);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(k, i)) {
            const lt_qt_n64_t *p = &base[(uint32_t)idx.l[i]];
            LT_MEM(p, sizeof *p, LT_MEM_READ);
            n64_dec1(*p, 0, d, i);
        }
    }
}

/* Store the planes of the lanes in k (values with LS_FRAC fractional bits) at out[i0 + lane].
 * C is rounded half up to s1.30 and then to the smallest exponent Ec that fits 24 unsigned bits;
 * Al, Be get the smallest shift Es that fits 15 signed bits, each rounded half up.
 * Cost: QT_N64_ENC_PLANE (VSHIFT x3, VALU x6, VSTORE x2), QT_N64_ENC_TRY (VALU x2) per slope
 * shift tried again, summed over the lanes.
 * Returns: the lanes stored (C < 0, a partial node extrapolated past w = 0, or a value outside
 * int32 is not encodable). */
static lt_mask16_t n64_enc_plane(lt_qt_n64_t *out, uint32_t i0, lt_mask16_t k, lt_vql36_t cw,
                                 lt_vql36_t aw, lt_vql36_t bw, lt_mask16_t o)
{
    unsigned m = 0, tries = 0;
    int i;
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        int64_t c, a, b, cm, am = 0, bm = 0;
        unsigned e, ec;
        if (!LT__ON(k, i))
            continue;
        c = q_rnd(cw.l[i], LS_FRAC);
        a = q_rnd(aw.l[i], LS_FRAC);
        b = q_rnd(bw.l[i], LS_FRAC);
        if (c < 0 || c > INT32_MAX || a != (int64_t)lt__ssat32(a) || b != (int64_t)lt__ssat32(b))
            continue;
        ec = c >= ((int64_t)1 << 24) ? 32u - lt__clz32((uint32_t)c) - 24u : 0u;
        cm = ec != 0 ? q_rnd(c, ec) : c;
        if (cm >= ((int64_t)1 << 24)) {
            ec++;
            cm = q_rnd(c, ec);
        }
        /* start at the shift the larger slope needs, then one more if rounding overflows */
        {
            int64_t mx = lt__l64_max(lt__l64_abs_wrap(a), lt__l64_abs_wrap(b));
            e = mx > 16383 ? 32u - lt__clz32((uint32_t)mx) - 14u : 0u;
        }
        for (; e < 32u; e++) {
            am = e != 0 ? q_rnd(a, e) : a;
            bm = e != 0 ? q_rnd(b, e) : b;
            if (am >= -16383 && am <= 16383 && bm >= -16383 && bm <= 16383)
                break;
            tries++;
        }
        out[i0 + (uint32_t)i].hi = (LT__ON(o, i) << 30) | (((uint32_t)am & 0x7FFFu) << 15) |
                                   ((uint32_t)bm & 0x7FFFu);
        out[i0 + (uint32_t)i].lo = ((uint32_t)cm << 8) | (e << 3) | ec;
        m |= 1u << i;
    }
    LT_CHARGE(QT_N64_ENC_PLANE);
    LT_CHARGE_N(QT_N64_ENC_TRY, tries);
    LT_MEM(&out[i0], LT_LANES * sizeof *out, LT_MEM_WRITE);
    return (lt_mask16_t)m;
}

/* AABB nodes: wmin, wmax clamped to [0, 2^31) (rays never have w < 0). Cost: QT_N64_ENC_AABB
 * (VALU x4, VSTORE x2). */
static void n64_enc_aabb(lt_qt_n64_t *out, uint32_t i0, lt_mask16_t k, lt_vq30_t lo,
                         lt_vq30_t hi)
{
    int i;
    LT_CHARGE(QT_N64_ENC_AABB);
    LT_UTIL(k);
    LT_MEM(&out[i0], LT_LANES * sizeof *out, LT_MEM_WRITE);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(k, i)) {
            int32_t a = lo.l[i] < 0 ? 0 : lo.l[i], b = hi.l[i] < 0 ? 0 : hi.l[i];
            out[i0 + (uint32_t)i].lo = (uint32_t)a;
            out[i0 + (uint32_t)i].hi = 0x80000000u | (uint32_t)b;
        }
    }
}

/* Copy the lanes in k of a 16-node scratch row to out[i0 + lane]. Cost: QT_COPY_LINE (VLOAD x1,
 * VSTORE x1) per 64 bytes of the row. */
#define QT_COPY_FN(name, T)                                                                        \
    static void name(T *out, uint32_t i0, const T *tmp, lt_mask16_t k)                            \
    {                                                                                              \
        int i;                                                                                     \
        LT_CHARGE_N(QT_COPY_LINE, (sizeof(T) * LT_LANES + 63u) / 64u);                             \
        LT_UTIL(k);                                                                                \
        LT_MEM(&out[i0], LT_LANES * sizeof(T), LT_MEM_WRITE);                                      \
        for (i = 0; i < LT_LANES; i++)                                                             \
            if (LT__ON(k, i))                                                                      \
                out[i0 + (uint32_t)i] = tmp[i];                                                    \
    }
QT_COPY_FN(n64_copy, lt_qt_n64_t)
QT_COPY_FN(n32_copy, lt_qt_n32_t)

/* ---- 32-bit node codec --------------------------------------------------------------------- */

/* 15-bit unsigned minifloat: e = 0: m; else (1024 + m) 2^(e-1). Exact for raw < 2048. */
static int32_t mf15_dec(uint32_t q)
{
    uint32_t e = q >> 10, m = q & 1023u;
    if (e == 0)
        return (int32_t)m;
    return lt__ssat32((int64_t)(1024u + m) * ((int64_t)1 << (e - 1u)));
}

/* x >= 0 to the minifloat, rounded down (up = 0) or up (up = 1). */
static uint32_t mf15_enc(int32_t x, int up)
{
    uint32_t u = x < 0 ? 0u : (uint32_t)x, e, m, s;
    if (u < 2048u)
        return u < 1024u ? u : (1u << 10) | (u - 1024u);
    e = 32u - lt__clz32(u) - 10u; /* u in [1024, 2048) 2^(e-1) */
    s = e - 1u;
    m = u >> s;
    if (up && (m << s) != u)
        m++;
    if (m == 2048u) {
        e++;
        m = 1024u;
    }
    return (e << 10) | (m - 1024u);
}

LT_INLINE void n32_node1(lt_qt_n32_t n, int bounds, qnode1_t *q)
{
    uint32_t v = n.v;
    q->lo = q->hi = 0;
    q->aabb = (int)(v >> 31);
    if (q->aabb) {
        q->lo = mf15_dec(v & 0x7FFFu);
        q->hi = mf15_dec((v >> 16) & 0x7FFFu);
    } else {
        unsigned e = (v >> 25) & 31u, ks = e + 3u * ((v >> 12) & 1u);
        q->o = (int)((v >> 30) & 1u);
        q->c = lt__ssat32((int64_t)((v >> 13) & 0xFFFu) * ((int64_t)1 << e));
        q->al = lt__ssat32((int64_t)q_sext((v >> 6) & 63u, 6) * ((int64_t)1 << ks));
        q->be = lt__ssat32((int64_t)q_sext(v & 63u, 6) * ((int64_t)1 << ks));
        /* half a step of C + half a step of each slope at half weight */
        q->eps = lt__ssat32(1 + (e != 0 ? ((int64_t)1 << (e - 1u)) : 0) +
                            (ks != 0 ? ((int64_t)1 << (ks - 1u)) : 0));
        if (bounds)
            qnode1_bounds(q);
    }
}

static void n32_dec1(lt_qt_n32_t n, int bounds, qdec_t *d, int i)
{
    qnode1_t q;
    n32_node1(n, bounds, &q);
    qdec_set1(d, i, &q);
}

/* As n64_decode. Cost: LANE_GATHER per active lane, QT_N32_DECODE (VSHIFT x6, VALU x8), with
 * bounds QT_N32_DECODE_BOUNDS (VALU x4). */
static void n32_decode(const lt_qt_n32_t *base, uint32_t i0, uint32_t stride, lt_mask16_t k,
                       int bounds, qdec_t *d)
{
    int i;
    qdec_zero(d);
    LT_CHARGE_N(LANE_GATHER, lt__popcount32(k));
    LT_CHARGE(QT_N32_DECODE);
    LT_CHARGE_N(QT_N32_DECODE_BOUNDS, bounds != 0);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(k, i)) {
            const lt_qt_n32_t *p = &base[i0 + stride * (uint32_t)i];
            LT_MEM(p, sizeof *p, LT_MEM_READ);
            n32_dec1(*p, bounds, d, i);
        }
    }
}

static void n32_decode_idx(const lt_qt_n32_t *base, lt_vi32_t idx, lt_mask16_t k, qdec_t *d)
{
    int i;
    qdec_zero(d);
    LT_CHARGE_N(LANE_GATHER, lt__popcount32(k));
    LT_CHARGE(QT_N32_DECODE);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(k, i)) {
            const lt_qt_n32_t *p = &base[(uint32_t)idx.l[i]];
            LT_MEM(p, sizeof *p, LT_MEM_READ);
            n32_dec1(*p, 0, d, i);
        }
    }
}

/* Planes into 32 bits: the smallest E (and K) for which C fits 12 unsigned bits and both slopes 6
 * signed bits in units of 2^(E + 3K), each rounded half up. C < 0 (a partial node extrapolated
 * past zero) is not encodable. Cost: QT_N32_ENC_PLANE (VSHIFT x3, VSTORE x1), QT_N32_ENC_TRY
 * (VALU x3) per exponent tried by the lane that tried the most.
 * Returns: the lanes stored. */
static lt_mask16_t n32_enc_plane(lt_qt_n32_t *out, uint32_t i0, lt_mask16_t k, lt_vql36_t cw,
                                 lt_vql36_t aw, lt_vql36_t bw, lt_mask16_t o)
{
    unsigned m = 0, tries = 0;
    int i;
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        int64_t c, a, b, cm = 0, am = 0, bm = 0;
        unsigned e, kk = 0, t = 0;
        if (!LT__ON(k, i))
            continue;
        c = q_rnd(cw.l[i], LS_FRAC);
        a = q_rnd(aw.l[i], LS_FRAC);
        b = q_rnd(bw.l[i], LS_FRAC);
        if (c < 0 || c > INT32_MAX || a != (int64_t)lt__ssat32(a) || b != (int64_t)lt__ssat32(b))
            continue;
        e = c >= 4096 ? 32u - lt__clz32((uint32_t)c) - 12u : 0u;
        for (; e < 32u; e++) {
            t++;
            cm = e != 0 ? q_rnd(c, e) : c;
            if (cm > 4095)
                continue;
            for (kk = 0; kk < 2u; kk++) {
                unsigned s = e + 3u * kk;
                am = s != 0 ? q_rnd(a, s) : a;
                bm = s != 0 ? q_rnd(b, s) : b;
                if (am >= -31 && am <= 31 && bm >= -31 && bm <= 31)
                    break;
            }
            if (kk < 2u)
                break;
        }
        if (e >= 32u)
            continue;
        if (t > tries)
            tries = t;
        out[i0 + (uint32_t)i].v = (LT__ON(o, i) << 30) | (e << 25) | ((uint32_t)cm << 13) |
                                  (kk << 12) | (((uint32_t)am & 63u) << 6) | ((uint32_t)bm & 63u);
        m |= 1u << i;
    }
    LT_CHARGE(QT_N32_ENC_PLANE);
    LT_CHARGE_N(QT_N32_ENC_TRY, tries);
    LT_MEM(&out[i0], LT_LANES * sizeof *out, LT_MEM_WRITE);
    return (lt_mask16_t)m;
}

/* AABB nodes: wmin rounded down, wmax up to the 15-bit minifloat. Cost: QT_N32_ENC_AABB
 * (VALU x8, VSTORE x1). */
static void n32_enc_aabb(lt_qt_n32_t *out, uint32_t i0, lt_mask16_t k, lt_vq30_t lo, lt_vq30_t hi)
{
    int i;
    LT_CHARGE(QT_N32_ENC_AABB);
    LT_UTIL(k);
    LT_MEM(&out[i0], LT_LANES * sizeof *out, LT_MEM_WRITE);
    for (i = 0; i < LT_LANES; i++)
        if (LT__ON(k, i))
            out[i0 + (uint32_t)i].v =
                0x80000000u | (mf15_enc(hi.l[i], 1) << 16) | mf15_enc(lo.l[i], 0);
}

/* ---- fixed-point pixels, rays, crossings and plane tests ------------------------------------- */

/* row[start + lane] for the lanes in k (0 elsewhere); negative raws are holes (0).
 * Cost: QT_Q_LOADPIX (VLOAD x1, VALU x1). */
static lt_vq30_t q_loadpix_m(const lt_q30_t *row, int32_t start, lt_mask16_t k)
{
    lt_vq30_t r;
    int i;
    LT_CHARGE(QT_Q_LOADPIX);
    LT_UTIL(k);
    if (k != 0)
        LT_MEM(&row[start + (int32_t)lt__ctz32(k)], LT_LANES * sizeof *row, LT_MEM_READ);
    for (i = 0; i < LT_LANES; i++) {
        r.l[i] = 0;
        if (LT__ON(k, i)) {
            int32_t v = row[start + i];
            r.l[i] = v < 0 ? 0 : v;
        }
    }
    return r;
}

/* Per-lane ray state after setup (fixed point): lt_ssb.h's, shared with the DDA and Hi-Z tracers
 * (ymaj unused here). */
typedef lt__ssb_setup_q30_t qsetup_t;

/* Lanes' per-layer outputs (see qt_layer in lt_qt.inc). */
typedef struct qlayer_out {
    lt_mask16_t hit, occ, unk;    /* hit / went behind / stopped by the step bound */
    lt_vq30_t thit, tocc, tstop;  /* s1.30 */
    lt_vi32_t nodes, aabb, planes; /* running per-lane counters */
} qlayer_out_t;

/* The crossing t = (X - o) / d, w along the ray, the hit parameter, the child side and the ray
 * setup and clip are lt_ssb.c's s1.30 routines (lt_ssb.h), one body for the three screen-space
 * tracers: lt__ssb_tcross_q30, lt__ssb_wray_q30, lt__ssb_w_at_q30, lt__ssb_hit_t_q30,
 * lt__ssb_child_side_q30, lt__ssb_clip_q30 (the traits below). */

/* Offset of the ray at t from the node centre in units of the node size, s1.30:
 * (o 2^30 + d t - (2q + 1) 2^(L + 45)) / 2^(16 + L), half up (o, d in s15.16, so s.46 before). */
LT_INLINE int64_t q_uoff(int32_t o, int32_t d, int32_t t, int32_t q, int32_t L)
{
    int64_t x46 = (int64_t)o * ((int64_t)1 << 30) + lt__mul32x32_64(d, t);
    int64_t c46 = (2 * (int64_t)q + 1) * ((int64_t)1 << (45 + L));
    return q_rnd(x46 - c46, 16u + (unsigned)L);
}

/* f(t) of one ray (q_plane_f's lane body): o, d the ray's pixel origin and direction per axis,
 * w, dw its w; (L, qx, qy) the node and c, al, be its plane. */
LT_INLINE int64_t q_plane_lane(int32_t ox, int32_t oy, int32_t dx, int32_t dy, int32_t w,
                               int32_t dw, int32_t t, int32_t L, int32_t qx, int32_t qy, int32_t c,
                               int32_t al, int32_t be)
{
    int64_t u = q_uoff(ox, dx, t, qx, L);
    int64_t v = q_uoff(oy, dy, t, qy, L);
    return lt__ssb_wray_lane_q30(w, dw, t) - (int64_t)c * ((int64_t)1 << 30) - al * u - be * v;
}

/* f(t) = w_ray(t) - w_plane(x(t), y(t)) in s1.60, for the lanes in k (0 elsewhere). Exact given
 * the rounded u, v: |w error| <= (|Al| + |Be|) 2^-31 raw. Cost: QT_Q_PLANE_F (VMUL x5,
 * VMULW x6, VSHIFT x2, VALU x4). */
static lt_vql60_t q_plane_f(const qsetup_t *S, lt_mask16_t k, lt_vq30_t t, lt_vi32_t lvl,
                          lt_vi32_t qx, lt_vi32_t qy, const qdec_t *nd)
{
    const lt_qray16_q30_t *r = S->r;
    lt_vql60_t f;
    int i;
    LT_CHARGE(QT_Q_PLANE_F);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        f.l[i] = LT__ON(k, i) ? q_plane_lane(r->x.l[i], r->y.l[i], r->dx.l[i], r->dy.l[i],
                                             r->w.l[i], r->dw.l[i], t.l[i], lvl.l[i], qx.l[i],
                                             qy.l[i], nd->c.l[i], nd->al.l[i], nd->be.l[i])
                              : 0;
    return f;
}

/* Ray setup: validity, reciprocals, and the clip of [tmin, tmax] to the image (through
 * lt__ssb_tcross_q30, so the clip agrees with the stepping) and to w >= 0 (the point at infinity:
 * beyond it the projective line wraps behind the camera): lt__ssb_clip_q30 over the image.
 * Returns the lanes with a non-empty interval; *bad receives the invalid lanes (t0 = 0 there).
 * Cost: lt__ssb_clip_q30 (SSB_Q_CLIP and four crossings). */
static lt_mask16_t q_setup(const lt_qt_t *qt, const lt_qray16_q30_t *r, lt_mask16_t k,
                           qsetup_t *S, lt_vq30_t *t0, lt_vq30_t *t1, lt_mask16_t *bad)
{
    return lt__ssb_clip_q30(qt->width, qt->height, r, k, S, t0, t1, bad);
}

/* Angle test: (dSx^2 + dSy^2) / 2 <= gamma_norm with dS in s1.30 (rounded from LS_FRAC more bits);
 * compared as squares against 2 gamma 2^30 in s2.60, so no square root is needed.
 * Cost: QT_Q_ANGLE_OK (VSHIFT x2, VMUL x2, VMULW x1, VCMP x3). */
static lt_mask16_t q_angle_ok(lt_mask16_t k, lt_vql36_t dsx, lt_vql36_t dsy, int64_t lim)
{
    unsigned m = 0;
    int i;
    LT_CHARGE(QT_Q_ANGLE_OK);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        int64_t x, y;
        if (!LT__ON(k, i))
            continue;
        x = lt__l64_abs_wrap(q_rnd(dsx.l[i], LS_FRAC));
        y = lt__l64_abs_wrap(q_rnd(dsy.l[i], LS_FRAC));
        if (x < ((int64_t)1 << 31) && y < ((int64_t)1 << 31) && x * x + y * y <= lim)
            m |= 1u << i;
    }
    return (lt_mask16_t)m;
}

/* ---- fixed-point traits shared by both node formats ---------------------------------------- */
#define LTQ_PIX lt_q30_t
#define LTQ_V lt_vq30_t
#define LTQ_W lt_vql36_t  /* build values */
#define LTQ_WT lt_vql60_t /* values along a ray */
#define LTQ_DEC qdec_t
#define LTQ_SETUP qsetup_t
#define LTQ_LAYER_OUT qlayer_out_t
#define LTQ_RAY lt_qray16_q30_t
#define LTQ_HIT lt_qhit16_q30_t
#define LTQ_ALIM_T int64_t
#define LTQ_ZERO 0
#define LTQ_TINF LT_Q30_MAX
#define LTQ_W_ZERO lt_vql36_set1(0)
#define LTQ_V_PARAM(x) lt_vq30_set1(x)
#define LTQ_V_SET1 lt_vq30_set1
#define LTQ_V_ADD lt_vq30_add_sat
#define LTQ_V_SUB lt_vq30_sub_sat
#define LTQ_V_ABS lt_vq30_abs_sat
#define LTQ_V_MIN lt_vq30_min
#define LTQ_V_MAX lt_vq30_max
#define LTQ_V_BLEND lt_vq30_blend
#define LTQ_V_CMPLT_M lt_vq30_cmplt_m
#define LTQ_V_CMPLE_M lt_vq30_cmple_m
#define LTQ_V_CMPGT_M lt_vq30_cmpgt_m
#define LTQ_V_CMPGE_M lt_vq30_cmpge_m
#define LTQ_W_FROMV lt_vql36_from_q30
#define LTQ_W_ADD lt_vql36_add_wrap
#define LTQ_W_SUB lt_vql36_sub_wrap
#define LTQ_W_ABS lt_vql36_abs_wrap
#define LTQ_W_BLEND lt_vql36_blend
#define LTQ_W_SHR(a, s) lt_vql36_asr((a), (s))
#define LTQ_W_SHL(a, s) lt_vql36_shl_wrap((a), (s))
#define LTQ_W_MUL3 lt_vql36_mul3_wrap
#define LTQ_W_CMPLE_M lt_vql36_cmple_m
#define LTQ_WT_FROMNODE lt_vql60_from_q30
#define LTQ_WT_SUB lt_vql60_sub_wrap
#define LTQ_WT_MIN lt_vql60_min
#define LTQ_WT_MAX lt_vql60_max
#define LTQ_WT_BLEND lt_vql60_blend
#define LTQ_WT_CMPLE_M lt_vql60_cmple_m
#define LTQ_WT_CMPLT_M lt_vql60_cmplt_m
#define LTQ_WT_CMPGT_M lt_vql60_cmpgt_m
#define LTQ_WT_CMPLT0(k, a) lt_vql60_cmplt_m((k), (a), lt_vql60_set1(0))
#define LTQ_LOADPIX_M q_loadpix_m
#define LTQ_ANGLE_LIM(g) ((int64_t)(g) * ((int64_t)1 << 31))
#define LTQ_ANGLE_OK q_angle_ok
#define LTQ_W_RELTOL q_reltol
#define LTQ_TCROSS lt__ssb_tcross_q30
#define LTQ_PLANE_F q_plane_f
#define LTQ_WRAY lt__ssb_wray_q30
#define LTQ_W_AT lt__ssb_w_at_q30
#define LTQ_HIT_T lt__ssb_hit_t_q30
#define LTQ_T_BACK(t) lt_vq30_sub_sat((t), lt_vq30_set1(4))
#define LTQ_CHILD_SIDE lt__ssb_child_side_q30
#define LTQ_SETUP_FN q_setup

/* 64-bit nodes */
#define LTQ_FN(name) name##_n64
#define LTQ_NODE lt_qt_n64_t
#define LTQ_DECODE n64_decode
#define LTQ_DECODE_IDX n64_decode_idx
#define LTQ_ENC_PLANE n64_enc_plane
#define LTQ_ENC_AABB n64_enc_aabb
#define LTQ_COPY n64_copy
#include "lt_qt.inc"
#undef LTQ_FN
#undef LTQ_NODE
#undef LTQ_DECODE
#undef LTQ_DECODE_IDX
#undef LTQ_ENC_PLANE
#undef LTQ_ENC_AABB
#undef LTQ_COPY

/* 32-bit nodes */
#define LTQ_FN(name) name##_n32
#define LTQ_NODE lt_qt_n32_t
#define LTQ_DECODE n32_decode
#define LTQ_DECODE_IDX n32_decode_idx
#define LTQ_ENC_PLANE n32_enc_plane
#define LTQ_ENC_AABB n32_enc_aabb
#define LTQ_COPY n32_copy
#include "lt_qt.inc"
#include "lt_qt_undef.inc"

lt_status_t lt_qt_build_q30(lt_qt_t *qt, const lt_qt_desc_t *d, const lt_qt_params_t *p,
                            const lt_q30_t *w, void *arena, size_t *arena_bytes)
{
    lt_status_t s;
    lt_phase_t prev;
    if (d == NULL || (d->enc != LT_QT_N64 && d->enc != LT_QT_N32))
        return LT_E_ARG;
    s = qt_prepare(qt, d, p, w, arena, arena_bytes);
    if (s != LT_OK)
        return s;
    prev = LT_PHASE_ENTER(BUILD);
    if (d->enc == LT_QT_N64)
        qt_build_all_n64(qt, w);
    else
        qt_build_all_n32(qt, w);
    LT_PHASE_LEAVE(prev);
    return LT_OK;
}

lt_status_t lt_qt_trace16_q30(const lt_qt_t *qt, const lt_qray16_q30_t *r, lt_mask16_t k,
                              uint32_t max_steps, lt_qhit16_q30_t *hit)
{
    if (qt == NULL || r == NULL || hit == NULL || qt->nodes == NULL)
        return LT_E_ARG;
    if (qt->enc == LT_QT_N64)
        return qt_trace_n64(qt, r, k, max_steps, hit);
    if (qt->enc == LT_QT_N32)
        return qt_trace_n32(qt, r, k, max_steps, hit);
    return LT_E_ARG;
}

/* ---- single rays: the walk of qt_layer / qt_trace one ray at a time ---------------------------- */

/* One layer's outputs for one ray (qlayer_out_t's lane). */
typedef struct qlayer1 {
    int hit, occ, unk;
    int32_t thit, tocc, tstop;
    int32_t nodes, aabb, planes;
} qlayer1_t;

/* The node at idx of a layer, decoded (either fixed-point format). LT_MEM at its address. */
LT_INLINE void qt1_node(const lt_qt_t *qt, const void *layer, uint32_t idx, qnode1_t *q)
{
    if (qt->enc == LT_QT_N64) {
        const lt_qt_n64_t *p = (const lt_qt_n64_t *)layer + idx;
        LT_MEM(p, sizeof *p, LT_MEM_READ);
        n64_node1(*p, 0, q);
    } else {
        const lt_qt_n32_t *p = (const lt_qt_n32_t *)layer + idx;
        LT_MEM(p, sizeof *p, LT_MEM_READ);
        n32_node1(*p, 0, q);
    }
}

/* f(t) of the ray R against plane node q at (L, qx, qy). */
LT_INLINE int64_t qt1_plane_f(const lt__ssb_ray1_q30_t *R, int32_t t, int32_t L, int32_t qx,
                              int32_t qy, const qnode1_t *q)
{
    return q_plane_lane(R->o[0], R->o[1], R->d[0], R->d[1], R->w, R->dw, t, L, qx, qy, q->c,
                        q->al, q->be);
}

/* The crossings a walk computed last, per axis: the two most recent (X, t) pairs. A node's exit
 * edge on the axis it did not step along, and a child's edges after a descent (the parent's exit
 * edge or the midline just computed), are among them, so most crossings are found here. The
 * crossing is a function of X alone for a ray, so a found t is the computed one. */
typedef struct qxcache {
    int32_t X[2][2], t[2][2];
} qxcache_t;

LT_INLINE int32_t qt1_cross(const lt__ssb_ray1_q30_t *R, qxcache_t *c, int a, int32_t X)
{
    int32_t t;
    if (c->X[a][0] == X)
        return c->t[a][0];
    if (c->X[a][1] == X)
        return c->t[a][1];
    LT_CHARGE(QT1_CROSS);
    t = lt__ssb_tcross1_q30(R, a, X);
    c->X[a][1] = c->X[a][0];
    c->t[a][1] = c->t[a][0];
    c->X[a][0] = X;
    c->t[a][0] = t;
    return t;
}

/* lt__ssb_child_side_q30's test for one ray, the midline's crossing through the cache: the ray at
 * t lies at coordinate >= xm on axis a. */
LT_INLINE int qt1_side(const lt__ssb_ray1_q30_t *R, qxcache_t *c, int a, int32_t t, int32_t xm)
{
    if (R->par[a])
        return (int64_t)R->o[a] >= (int64_t)xm * 65536;
    return R->neg[a] ? t < qt1_cross(R, c, a, xm) : t >= qt1_cross(R, c, a, xm);
}

/* qt_layer (lt_qt.inc) for one ray over [t0, t1], front = 0 at t0: the same states, tests and
 * steps with each lane mask a flag, so every output equals that lane's of the packet walk. */
static void qt1_layer(const lt_qt_t *qt, const void *layer, const lt__ssb_ray1_q30_t *R,
                      int32_t t0, int32_t t1, int last, uint32_t max_steps, qlayer1_t *res)
{
    const int32_t top = (int32_t)qt->levels - 1;
    int32_t lvl = top, qx = 0, qy = 0, steps = 0, tcur = t0;
    int32_t sgx = R->neg[0] ? -1 : 1, sgy = R->neg[1] ? -1 : 1;
    uint32_t addx = (uint32_t)(!R->neg[0] && !R->par[0]);
    uint32_t addy = (uint32_t)(!R->neg[1] && !R->par[1]);
    int front = 0, behind = 0;
    qxcache_t xc;

    /* pixel coordinates are below 2^16: INT32_MIN is never an edge */
    xc.X[0][0] = xc.X[0][1] = xc.X[1][0] = xc.X[1][1] = INT32_MIN;
    xc.t[0][0] = xc.t[0][1] = xc.t[1][0] = xc.t[1][1] = 0;
    res->hit = res->occ = res->unk = 0;
    res->thit = res->tocc = res->tstop = t0;
    for (;;) {
        qnode1_t nd;
        int32_t tx, ty, tf;
        int hitx = 0, dsc = 0;
        LT_EVENT(NODES, 1);
        LT_CHARGE(QT1_STEP);
        steps = lt__i32_add_wrap(steps, 1);
        if (steps > (int32_t)max_steps) {
            res->unk = 1;
            res->tstop = tcur;
            return;
        }
        res->nodes = lt__i32_add_wrap(res->nodes, 1);
        LT_ASSERT((uint32_t)lvl < qt->levels && (uint32_t)qx < qt->nx[lvl] &&
                  (uint32_t)qy < qt->ny[lvl]);
        qt1_node(qt, layer, qt->off[lvl] + (uint32_t)qy * qt->nx[lvl] + (uint32_t)qx, &nd);

        /* exit crossings; parallel axes never cross */
        tx = R->par[0] ? LT_Q30_MAX
                       : qt1_cross(R, &xc, 0, (int32_t)(((uint32_t)qx + addx) << lvl));
        ty = R->par[1] ? LT_Q30_MAX
                       : qt1_cross(R, &xc, 1, (int32_t)(((uint32_t)qy + addy) << lvl));
        tf = tx < ty ? tx : ty;
        tf = tf < t1 ? tf : t1;

        if (!nd.aabb) {
            /* plane node */
            int64_t fn = qt1_plane_f(R, tcur, lvl, qx, qy, &nd);
            int64_t ff = qt1_plane_f(R, tf, lvl, qx, qy, &nd);
            int nneg = fn < 0, fneg = ff < 0;
            int crack = nneg && front && !nd.o;
            int occ = nneg && !crack && !behind && !res->occ;
            LT_CHARGE(QT1_PLANE);
            res->planes = lt__i32_add_wrap(res->planes, 1);
            if (!nneg && fneg) {
                LT_CHARGE(QT1_HIT_T);
                res->thit = lt__ssb_hit_t_lane_q30(tcur, tf, fn, ff);
                hitx = 1;
            }
            if (crack) {
                res->thit = tcur;
                hitx = 1;
            }
            if (occ) {
                res->occ = 1;
                res->tocc = tcur;
                if (last)
                    return;
            }
            front = !fneg;
            behind = fneg;
        } else {
            /* AABB node */
            int64_t wn = lt__ssb_wray_lane_q30(R->w, R->dw, tcur);
            int64_t wf = lt__ssb_wray_lane_q30(R->w, R->dw, tf);
            int64_t wlo = lt__l64_min(wn, wf), whi = lt__l64_max(wn, wf);
            int64_t bmin = (int64_t)nd.lo * ((int64_t)1 << 30);
            int64_t bmax = (int64_t)nd.hi * ((int64_t)1 << 30);
            int above = wlo > bmax, below = whi < bmin, ehi, elo;
            LT_EVENT(AABB, 1);
            LT_EVENT(AABB_RAYS, 1);
            LT_CHARGE(QT1_BOX);
            res->aabb = lt__i32_add_wrap(res->aabb, 1);
            dsc = !above && !(below && behind);
            front = front || above;
            behind = behind && !above;
            /* Alg. 3 line 32: enter where the ray enters the box (lt_qt.inc) */
            ehi = dsc && wn > bmax && wf <= bmax;
            elo = dsc && behind && wn < bmin && wf >= bmin;
            if (ehi || elo) {
                int64_t fa = elo ? lt__l64_sub_wrap(bmin, wn) : lt__l64_sub_wrap(wn, bmax);
                int64_t fb = elo ? lt__l64_sub_wrap(bmin, wf) : lt__l64_sub_wrap(wf, bmax);
                int32_t te = lt__q16_sub_sat(lt__ssb_hit_t_lane_q30(tcur, tf, fa, fb), 4);
                LT_CHARGE(QT1_HIT_T);
                tcur = te > tcur ? te : tcur;
                front = front || ehi;
            }
        }
        if (hitx) {
            res->hit = 1;
            return;
        }

        if (dsc && lvl > 0) {
            /* descend to the child holding the ray at tcur */
            int32_t lm = lvl - 1;
            int32_t mx = (int32_t)((2u * (uint32_t)qx + 1u) << lm);
            int32_t my = (int32_t)((2u * (uint32_t)qy + 1u) << lm);
            int cx = qt1_side(R, &xc, 0, tcur, mx);
            int cy = qt1_side(R, &xc, 1, tcur, my);
            LT_CHARGE(QT1_DESCEND);
            qx = lt__i32_add_wrap(lt__i32_add_wrap(qx, qx), cx);
            qy = lt__i32_add_wrap(lt__i32_add_wrap(qy, qy), cy);
            lvl = lm;
            continue;
        }

        /* next node (Alg. 4) and level jump */
        if (tf >= t1) {
            res->tstop = tf;
            return;
        }
        {
            int sx = !R->par[0] && tx <= ty, sy = !R->par[1] && ty <= tx;
            int32_t nqx = sx ? lt__i32_add_wrap(qx, sgx) : qx;
            int32_t nqy = sy ? lt__i32_add_wrap(qy, sgy) : qy;
            int32_t up;
            LT_CHARGE(QT1_ADVANCE);
            if (nqx < 0 || nqy < 0 || (uint32_t)nqx >= qt->nx[lvl] ||
                (uint32_t)nqy >= qt->ny[lvl]) {
                res->tstop = tf;
                return;
            }
            up = 31 - (int32_t)lt__clz32((uint32_t)((qx ^ nqx) | (qy ^ nqy)));
            up = up < top - lvl ? up : top - lvl;
            qx = lt__asr32(nqx, (unsigned)up & 31u);
            qy = lt__asr32(nqy, (unsigned)up & 31u);
            lvl = lt__i32_add_wrap(lvl, up);
            tcur = tf;
        }
    }
}

/* qt_trace for lane i of r alone: setup and clip, the layers, the hit record's lane i. */
static void qt1_trace(const lt_qt_t *qt, const lt_qray16_q30_t *r, int i, uint32_t max_steps,
                      lt_qhit16_q30_t *hit)
{
    lt__ssb_ray1_q30_t R;
    qlayer1_t lo;
    int32_t t0, t1, tc, lc = 0, st = LT_QT_MISS;
    int ok, go = 0, cand = 0;
    uint32_t layer;
    lt_phase_t prev = LT_PHASE_ENTER(SETUP);

    LT_EVENT(RAYS, 1);
    LT_CHARGE(QT1_SETUP);
    ok = lt__ssb_clip1_q30(qt->width, qt->height, r, i, &R, &t0, &t1);
    (void)LT_PHASE_ENTER(TRAVERSE);
    hit->t.l[i] = t0;
    hit->layer.l[i] = -1;
    lo.nodes = lo.aabb = lo.planes = 0;
    if (!ok) {
        hit->status.l[i] = LT_QT_BADRAY;
    } else {
        tc = t1;
        go = t0 < t1;
        for (layer = 0; layer < qt->layers && go; layer++) {
            int last = layer + 1u == qt->layers;
            LT_CHARGE(QT1_LAYER);
            qt1_layer(qt, (const uint8_t *)qt->nodes + (size_t)layer * qt->layer_nodes *
                                                          qt->node_bytes,
                      &R, t0, t1, last, max_steps, &lo);
            go = lo.occ && !lo.unk;
            if (lo.unk) { /* step bound: unknown, whatever was found before */
                st = LT_QT_UNKNOWN;
                tc = lo.tstop;
                lc = (int32_t)layer;
            } else if (lo.hit && !lo.occ) { /* a hit with no occlusion before it is final */
                st = LT_QT_HIT;
                tc = lo.thit;
                lc = (int32_t)layer;
            } else if (!go) { /* no hit, no occlusion: the previous candidate, else a miss */
                if (cand)
                    st = LT_QT_HIT;
            } else {
                /* occluded: a later hit is the candidate; continue one layer deeper */
                if (lo.hit) {
                    cand = 1;
                    tc = lo.thit;
                    lc = (int32_t)layer;
                    t1 = lo.thit;
                }
                t0 = lo.tocc;
                if (last) { /* behind the deepest layer: unknown beyond */
                    st = LT_QT_OCCLUDED;
                    tc = lo.tocc;
                    lc = (int32_t)layer;
                }
            }
        }
        hit->status.l[i] = st;
        hit->layer.l[i] = lc;
        hit->t.l[i] = tc;
        hit->w.l[i] = lt__ssb_w_at_lane_q30(R.w, R.dw, tc);
    }
    hit->nodes.l[i] = lo.nodes;
    hit->aabb.l[i] = lo.aabb;
    hit->planes.l[i] = lo.planes;
    LT_CHARGE(QT1_FINISH);
    LT_PHASE_LEAVE(prev);
}

lt_status_t lt_qt_trace1_q30(const lt_qt_t *qt, const lt_qray16_q30_t *r, lt_mask16_t k,
                             uint32_t max_steps, lt_qhit16_q30_t *hit)
{
    int i;
    if (qt == NULL || r == NULL || hit == NULL || qt->nodes == NULL ||
        (qt->enc != LT_QT_N64 && qt->enc != LT_QT_N32))
        return LT_E_ARG;
    if (max_steps == 0)
        max_steps = lt_qt_default_steps(qt);
    for (i = 0; i < LT_LANES; i++)
        if (LT__ON(k, i))
            qt1_trace(qt, r, i, max_steps, hit);
    return LT_OK;
}

/* ==== float32 =================================================================================== */
#if LT_CFG_FLOAT32

#define F_Q30 9.31322574615478515625e-10f /* 2^-30 */
#define F_INF 3.40282347e38f

typedef struct fdec {
    lt_mask16_t aabb, o;
    lt_vf32_t c, al, be, lo, hi, eps;
} fdec_t;

static void fdec_zero(fdec_t *d)
{
    int i;
    d->aabb = d->o = 0;
    for (i = 0; i < LT_LANES; i++)
        d->c.l[i] = d->al.l[i] = d->be.l[i] = d->lo.l[i] = d->hi.l[i] = d->eps.l[i] = 0.0f;
}

static void f_dec1(const lt_qt_nf32_t *n, int bounds, fdec_t *d, int i)
{
    if ((n->flags >> 31) != 0u) {
        d->aabb = (lt_mask16_t)(d->aabb | (1u << i));
        d->lo.l[i] = n->c;
        d->hi.l[i] = n->al;
    } else {
        if (((n->flags >> 30) & 1u) != 0u)
            d->o = (lt_mask16_t)(d->o | (1u << i));
        d->c.l[i] = n->c;
        d->al.l[i] = n->al;
        d->be.l[i] = n->be;
        if (bounds) {
            float s = 0.5f * (lt__f32_abs(n->al) + lt__f32_abs(n->be));
            d->lo.l[i] = n->c - s;
            d->hi.l[i] = n->c + s;
        }
    }
}

/* Decode a row of 16-byte float32 nodes (f_decode_idx: base[idx]). Cost: LANE_GATHER x2 per
 * active lane (two 8-byte elements), QT_F_DECODE (VALU x2), with bounds QT_F_DECODE_BOUNDS
 * (FADD x4). */
static void f_decode(const lt_qt_nf32_t *base, uint32_t i0, uint32_t stride, lt_mask16_t k,
                     int bounds, fdec_t *d)
{
    int i;
    fdec_zero(d);
    LT_CHARGE_N(LANE_GATHER, 2u * lt__popcount32(k));
    LT_CHARGE(QT_F_DECODE);
    LT_CHARGE_N(QT_F_DECODE_BOUNDS, bounds != 0);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(k, i)) {
            const lt_qt_nf32_t *p = &base[i0 + stride * (uint32_t)i];
            LT_MEM(p, sizeof *p, LT_MEM_READ);
            f_dec1(p, bounds, d, i);
        }
    }
}

static void f_decode_idx(const lt_qt_nf32_t *base, lt_vi32_t idx, lt_mask16_t k, fdec_t *d)
{
    int i;
    fdec_zero(d);
    LT_CHARGE_N(LANE_GATHER, 2u * lt__popcount32(k));
    LT_CHARGE(QT_F_DECODE);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(k, i)) {
            const lt_qt_nf32_t *p = &base[(uint32_t)idx.l[i]];
            LT_MEM(p, sizeof *p, LT_MEM_READ);
            f_dec1(p, 0, d, i);
        }
    }
}

/* Planes and (f_enc_aabb) boxes as stored: every float32 value is encodable. Cost:
 * QT_F_STORE_ROW (VSTORE x4). */
static lt_mask16_t f_enc_plane(lt_qt_nf32_t *out, uint32_t i0, lt_mask16_t k, lt_vf32_t c,
                               lt_vf32_t al, lt_vf32_t be, lt_mask16_t o)
{
    int i;
    LT_CHARGE(QT_F_STORE_ROW);
    LT_UTIL(k);
    LT_MEM(&out[i0], LT_LANES * sizeof *out, LT_MEM_WRITE);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(k, i)) {
            out[i0 + (uint32_t)i].c = c.l[i];
            out[i0 + (uint32_t)i].al = al.l[i];
            out[i0 + (uint32_t)i].be = be.l[i];
            out[i0 + (uint32_t)i].flags = LT__ON(o, i) << 30;
        }
    }
    return k;
}

QT_COPY_FN(f_copy, lt_qt_nf32_t)

static void f_enc_aabb(lt_qt_nf32_t *out, uint32_t i0, lt_mask16_t k, lt_vf32_t lo, lt_vf32_t hi)
{
    int i;
    LT_CHARGE(QT_F_STORE_ROW);
    LT_UTIL(k);
    LT_MEM(&out[i0], LT_LANES * sizeof *out, LT_MEM_WRITE);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(k, i)) {
            out[i0 + (uint32_t)i].c = lo.l[i] < 0.0f ? 0.0f : lo.l[i];
            out[i0 + (uint32_t)i].al = hi.l[i] < 0.0f ? 0.0f : hi.l[i];
            out[i0 + (uint32_t)i].be = 0.0f;
            out[i0 + (uint32_t)i].flags = 0x80000000u;
        }
    }
}

/* row[start + lane]; NaN, +-inf and negative values are holes (0). Cost: QT_F_LOADPIX (VLOAD x1,
 * FCMP x2). */
static lt_vf32_t f_loadpix_m(const float *row, int32_t start, lt_mask16_t k)
{
    lt_vf32_t r;
    int i;
    LT_CHARGE(QT_F_LOADPIX);
    LT_UTIL(k);
    if (k != 0)
        LT_MEM(&row[start + (int32_t)lt__ctz32(k)], LT_LANES * sizeof *row, LT_MEM_READ);
    for (i = 0; i < LT_LANES; i++) {
        r.l[i] = 0.0f;
        if (LT__ON(k, i)) {
            float v = row[start + i];
            r.l[i] = (v >= 0.0f && v <= F_INF) ? v : 0.0f;
        }
    }
    return r;
}

/* lt_ssb.h's float32 ray state (ymaj unused here). */
typedef lt__ssb_setup_f32_t fsetup_t;

typedef struct flayer_out {
    lt_mask16_t hit, occ, unk;
    lt_vf32_t thit, tocc, tstop;
    lt_vi32_t nodes, aabb, planes;
} flayer_out_t;

/* The crossing, w along the ray, the child side and the setup are lt_ssb.c's float32 routines
 * (lt__ssb_tcross_f32, lt__ssb_wray_f32, lt__ssb_child_side_f32, lt__ssb_clip_f32). */

/* f(t) = (w + t dw) - (c + al u + be v), u = (x + t dx - xc) / 2^L. Cost: QT_F_PLANE_F (VCVT x2,
 * FMUL x7, FADD x8). */
static lt_vf32_t f_plane_f(const fsetup_t *S, lt_mask16_t k, lt_vf32_t t, lt_vi32_t lvl,
                           lt_vi32_t qx, lt_vi32_t qy, const fdec_t *nd)
{
    const lt_qray16_f32_t *r = S->r;
    lt_vf32_t f;
    int i;
    LT_CHARGE(QT_F_PLANE_F);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        f.l[i] = 0.0f;
        if (LT__ON(k, i)) {
            float s = (float)(1u << (unsigned)lvl.l[i]), inv = 1.0f / s;
            float u = (r->x.l[i] + t.l[i] * r->dx.l[i] - ((float)qx.l[i] + 0.5f) * s) * inv;
            float v = (r->y.l[i] + t.l[i] * r->dy.l[i] - ((float)qy.l[i] + 0.5f) * s) * inv;
            f.l[i] = (r->w.l[i] + t.l[i] * r->dw.l[i]) -
                     (nd->c.l[i] + nd->al.l[i] * u + nd->be.l[i] * v);
        }
    }
    return f;
}

/* The crossing t in [tn, tf] of f (fn >= 0 >= ff, fn - ff > 0 at every call site):
 * tn + (tf - tn) (fn / (fn - ff)). lt__ssb_hit_t_f32 keeps tn where fn - ff > 0 fails (NaN
 * values), this one divides regardless, so the two differ on non-finite input and this one stays
 * the quadtree's own. Cost: QT_F_HIT_T (FDIV x1, FADD x3, FMUL x1). */
static lt_vf32_t f_hit_t(lt_mask16_t k, lt_vf32_t tn, lt_vf32_t tf, lt_vf32_t fn, lt_vf32_t ff)
{
    int i;
    LT_CHARGE(QT_F_HIT_T);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        if (LT__ON(k, i))
            tn.l[i] = tn.l[i] + (tf.l[i] - tn.l[i]) * (fn.l[i] / (fn.l[i] - ff.l[i]));
    return tn;
}

/* Ray setup and clip: lt__ssb_clip_f32 over the image. Cost: lt__ssb_clip_f32. */
static lt_mask16_t f_setup(const lt_qt_t *qt, const lt_qray16_f32_t *r, lt_mask16_t k,
                           fsetup_t *S, lt_vf32_t *t0, lt_vf32_t *t1, lt_mask16_t *bad)
{
    return lt__ssb_clip_f32(qt->width, qt->height, r, k, S, t0, t1, bad);
}

static lt_mask16_t f_angle_ok(lt_mask16_t k, lt_vf32_t dsx, lt_vf32_t dsy, float lim)
{
    lt_vf32_t s = lt_vf32_add(lt_vf32_mul(dsx, dsx), lt_vf32_mul(dsy, dsy));
    return lt_vf32_cmple_m(k, s, lt_vf32_set1(lim));
}

#define LTQ_FN(name) name##_f32
#define LTQ_NODE lt_qt_nf32_t
#define LTQ_DECODE f_decode
#define LTQ_DECODE_IDX f_decode_idx
#define LTQ_ENC_PLANE f_enc_plane
#define LTQ_ENC_AABB f_enc_aabb
#define LTQ_COPY f_copy
#define LTQ_PIX float
#define LTQ_V lt_vf32_t
#define LTQ_W lt_vf32_t
#define LTQ_WT lt_vf32_t
#define LTQ_DEC fdec_t
#define LTQ_SETUP fsetup_t
#define LTQ_LAYER_OUT flayer_out_t
#define LTQ_RAY lt_qray16_f32_t
#define LTQ_HIT lt_qhit16_f32_t
#define LTQ_ALIM_T float
#define LTQ_ZERO 0.0f
#define LTQ_TINF F_INF
#define LTQ_W_ZERO lt_vf32_set1(0.0f)
#define LTQ_V_PARAM(x) lt_vf32_set1((float)(x) * F_Q30)
#define LTQ_V_SET1 lt_vf32_set1
#define LTQ_V_ADD lt_vf32_add
#define LTQ_V_SUB lt_vf32_sub
#define LTQ_V_ABS lt_vf32_abs
#define LTQ_V_MIN lt_vf32_min
#define LTQ_V_MAX lt_vf32_max
#define LTQ_V_BLEND lt_vf32_blend
#define LTQ_V_CMPLT_M lt_vf32_cmplt_m
#define LTQ_V_CMPLE_M lt_vf32_cmple_m
#define LTQ_V_CMPGT_M lt_vf32_cmpgt_m
#define LTQ_V_CMPGE_M lt_vf32_cmpge_m
#define LTQ_W_FROMV(v) (v)
#define LTQ_W_ADD lt_vf32_add
#define LTQ_W_SUB lt_vf32_sub
#define LTQ_W_ABS lt_vf32_abs
#define LTQ_W_BLEND lt_vf32_blend
#define LTQ_W_SHR(a, s) lt_vf32_mul_pow2((a), -(int)(s))
#define LTQ_W_SHL(a, s) lt_vf32_mul_pow2((a), (int)(s))
#define LTQ_W_MUL3 lt_vf32_mul3
#define LTQ_W_CMPLE_M lt_vf32_cmple_m
#define LTQ_WT_FROMNODE(v) (v)
#define LTQ_WT_SUB lt_vf32_sub
#define LTQ_WT_MIN lt_vf32_min
#define LTQ_WT_MAX lt_vf32_max
#define LTQ_WT_BLEND lt_vf32_blend
#define LTQ_WT_CMPLE_M lt_vf32_cmple_m
#define LTQ_WT_CMPLT_M lt_vf32_cmplt_m
#define LTQ_WT_CMPGT_M lt_vf32_cmpgt_m
#define LTQ_WT_CMPLT0(k, a) lt_vf32_cmplt_m((k), (a), lt_vf32_set1(0.0f))
#define LTQ_LOADPIX_M f_loadpix_m
#define LTQ_ANGLE_LIM(g) (2.0f * (float)(g) * F_Q30)
#define LTQ_ANGLE_OK f_angle_ok
#define LTQ_W_RELTOL(lo, g) lt_vf32_mul(lt_vf32_max((lo), lt_vf32_set1(0.0f)), (g))
#define LTQ_TCROSS lt__ssb_tcross_f32
#define LTQ_PLANE_F f_plane_f
#define LTQ_WRAY lt__ssb_wray_f32
#define LTQ_W_AT lt__ssb_wray_f32
#define LTQ_HIT_T f_hit_t
#define LTQ_T_BACK(t) lt_vf32_sub((t), lt_vf32_set1(4.76837158203125e-7f))
#define LTQ_CHILD_SIDE lt__ssb_child_side_f32
#define LTQ_SETUP_FN f_setup
#include "lt_qt.inc"
#include "lt_qt_undef.inc"

lt_status_t lt_qt_build_f32(lt_qt_t *qt, const lt_qt_desc_t *d, const lt_qt_params_t *p,
                            const float *w, void *arena, size_t *arena_bytes)
{
    lt_status_t s;
    lt_phase_t prev;
    if (d == NULL || d->enc != LT_QT_F32)
        return LT_E_ARG;
    s = qt_prepare(qt, d, p, w, arena, arena_bytes);
    if (s != LT_OK)
        return s;
    prev = LT_PHASE_ENTER(BUILD);
    qt_build_all_f32(qt, w);
    LT_PHASE_LEAVE(prev);
    return LT_OK;
}

lt_status_t lt_qt_trace16_f32(const lt_qt_t *qt, const lt_qray16_f32_t *r, lt_mask16_t k,
                              uint32_t max_steps, lt_qhit16_f32_t *hit)
{
    if (qt == NULL || r == NULL || hit == NULL || qt->nodes == NULL || qt->enc != LT_QT_F32)
        return LT_E_ARG;
    return qt_trace_f32(qt, r, k, max_steps, hit);
}

#endif /* LT_CFG_FLOAT32 */
