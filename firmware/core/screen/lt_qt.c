/* lt_qt.c - the screen-space quadtree of Widmer et al. 2015 [Widmer15]: layout and size query, the
 * format-specific kernel routines (node codecs, crossings, plane tests, ray setup; the lane ops
 * themselves are lt_v16.h's and lt_v16w.h's), and the traits that instantiate lt_qt.inc three
 * times: 64-bit and 32-bit fixed-point nodes (s1.30 compute, int64 products) and float32 nodes.
 * Node formats are documented in lt_qt.h and docs/quadtree.md. Builds: all; float32 only with
 * LT_CFG_FLOAT32.
 */
#include "lt/lt_qt.h"
#include "lt_qt_grid.h"

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
 * the raw unit (floor). Cost: VMUL x1, VSHIFT x1. */
static lt_vql36_t q_reltol(lt_vq30_t lo, lt_vq30_t g)
{
    lt_vql36_t r;
    int i;
    LT_COST(VMUL, 1);
    LT_COST(VSHIFT, 1);
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

/* min / max of a decoded plane over its footprint: C -+ (|Al| + |Be|) / 2, outward. */
static void qdec_bounds1(qdec_t *d, int i)
{
    int64_t c2 = 2 * (int64_t)d->c.l[i];
    int64_t s = lt__l64_abs_wrap(d->al.l[i]) + lt__l64_abs_wrap(d->be.l[i]);
    d->lo.l[i] = lt__ssat32(lt__asr64(c2 - s, 1));
    d->hi.l[i] = lt__ssat32(lt__asr64(c2 + s + 1, 1));
}

/* ---- 64-bit node codec --------------------------------------------------------------------- */

static void n64_dec1(lt_qt_n64_t n, int bounds, qdec_t *d, int i)
{
    if ((n.hi >> 31) != 0u) {
        d->aabb = (lt_mask16_t)(d->aabb | (1u << i));
        d->lo.l[i] = (int32_t)(n.lo & 0x7FFFFFFFu);
        d->hi.l[i] = (int32_t)(n.hi & 0x7FFFFFFFu);
    } else {
        unsigned ec = n.lo & 7u, s = (n.lo >> 3) & 31u;
        int64_t a = q_sext((n.hi >> 15) & 0x7FFFu, 15), b = q_sext(n.hi & 0x7FFFu, 15);
        if (((n.hi >> 30) & 1u) != 0u)
            d->o = (lt_mask16_t)(d->o | (1u << i));
        d->c.l[i] = lt__ssat32((int64_t)(n.lo >> 8) * ((int64_t)1 << ec));
        d->al.l[i] = lt__ssat32(a * ((int64_t)1 << s));
        d->be.l[i] = lt__ssat32(b * ((int64_t)1 << s));
        /* half a step of C, half a step of each slope at half weight at the node's edge,
         * + 1 for the rounding to raw units before encoding */
        d->eps.l[i] = 1 + (ec != 0 ? (int32_t)(1u << (ec - 1u)) : 0) +
                      (s != 0 ? (int32_t)(1u << (s - 1u)) : 0);
        if (bounds)
            qdec_bounds1(d, i);
    }
}

/* Decode base[i0 + stride * lane] for the lanes in k. Cost: VGATHER per active lane, VSHIFT x4,
 * VALU x6 (+ VALU x4 with bounds). */
static void n64_decode(const lt_qt_n64_t *base, uint32_t i0, uint32_t stride, lt_mask16_t k,
                       int bounds, qdec_t *d)
{
    int i;
    qdec_zero(d);
    LT_COST(VGATHER, lt__popcount32(k));
    LT_COST(VSHIFT, 4);
    LT_COST(VALU, bounds ? 10 : 6);
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
    LT_COST(VGATHER, lt__popcount32(k));
    LT_COST(VSHIFT, 4);
    LT_COST(VALU, 6);
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
 * Cost: VSHIFT x3, VALU x2 per exponent tried, VSTORE x2.
 * Returns: the lanes stored (C < 0, a partial node extrapolated past w = 0, or a value outside
 * int32 is not encodable). */
static lt_mask16_t n64_enc_plane(lt_qt_n64_t *out, uint32_t i0, lt_mask16_t k, lt_vql36_t cw,
                                 lt_vql36_t aw, lt_vql36_t bw, lt_mask16_t o)
{
    unsigned m = 0, tries = 0;
    int i;
    LT_COST(VSHIFT, 3);
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
    LT_COST(VALU, 6u + 2u * tries);
    LT_COST(VSTORE, 2);
    LT_MEM(&out[i0], LT_LANES * sizeof *out, LT_MEM_WRITE);
    return (lt_mask16_t)m;
}

/* AABB nodes: wmin, wmax clamped to [0, 2^31) (rays never have w < 0). Cost: VALU x4, VSTORE x2. */
static void n64_enc_aabb(lt_qt_n64_t *out, uint32_t i0, lt_mask16_t k, lt_vq30_t lo,
                         lt_vq30_t hi)
{
    int i;
    LT_COST(VALU, 4);
    LT_COST(VSTORE, 2);
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

/* Copy the lanes in k of a 16-node scratch row to out[i0 + lane]. Cost: VLOAD x1, VSTORE x1
 * per 64 bytes of the row. */
#define QT_COPY_FN(name, T)                                                                        \
    static void name(T *out, uint32_t i0, const T *tmp, lt_mask16_t k)                            \
    {                                                                                              \
        int i;                                                                                     \
        LT_COST(VLOAD, (sizeof(T) * LT_LANES + 63u) / 64u);                                        \
        LT_COST(VSTORE, (sizeof(T) * LT_LANES + 63u) / 64u);                                       \
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

static void n32_dec1(lt_qt_n32_t n, int bounds, qdec_t *d, int i)
{
    uint32_t v = n.v;
    if ((v >> 31) != 0u) {
        d->aabb = (lt_mask16_t)(d->aabb | (1u << i));
        d->lo.l[i] = mf15_dec(v & 0x7FFFu);
        d->hi.l[i] = mf15_dec((v >> 16) & 0x7FFFu);
    } else {
        unsigned e = (v >> 25) & 31u, ks = e + 3u * ((v >> 12) & 1u);
        if (((v >> 30) & 1u) != 0u)
            d->o = (lt_mask16_t)(d->o | (1u << i));
        d->c.l[i] = lt__ssat32((int64_t)((v >> 13) & 0xFFFu) * ((int64_t)1 << e));
        d->al.l[i] = lt__ssat32((int64_t)q_sext((v >> 6) & 63u, 6) * ((int64_t)1 << ks));
        d->be.l[i] = lt__ssat32((int64_t)q_sext(v & 63u, 6) * ((int64_t)1 << ks));
        /* half a step of C + half a step of each slope at half weight */
        d->eps.l[i] = lt__ssat32(1 + (e != 0 ? ((int64_t)1 << (e - 1u)) : 0) +
                                 (ks != 0 ? ((int64_t)1 << (ks - 1u)) : 0));
        if (bounds)
            qdec_bounds1(d, i);
    }
}

static void n32_decode(const lt_qt_n32_t *base, uint32_t i0, uint32_t stride, lt_mask16_t k,
                       int bounds, qdec_t *d)
{
    int i;
    qdec_zero(d);
    LT_COST(VGATHER, lt__popcount32(k));
    LT_COST(VSHIFT, 6);
    LT_COST(VALU, bounds ? 12 : 8);
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
    LT_COST(VGATHER, lt__popcount32(k));
    LT_COST(VSHIFT, 6);
    LT_COST(VALU, 8);
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
 * past zero) is not encodable. Cost: VSHIFT x3, VALU x3 per exponent tried, VSTORE x1.
 * Returns: the lanes stored. */
static lt_mask16_t n32_enc_plane(lt_qt_n32_t *out, uint32_t i0, lt_mask16_t k, lt_vql36_t cw,
                                 lt_vql36_t aw, lt_vql36_t bw, lt_mask16_t o)
{
    unsigned m = 0, tries = 0;
    int i;
    LT_COST(VSHIFT, 3);
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
    LT_COST(VALU, 3u * tries);
    LT_COST(VSTORE, 1);
    LT_MEM(&out[i0], LT_LANES * sizeof *out, LT_MEM_WRITE);
    return (lt_mask16_t)m;
}

static void n32_enc_aabb(lt_qt_n32_t *out, uint32_t i0, lt_mask16_t k, lt_vq30_t lo, lt_vq30_t hi)
{
    int i;
    LT_COST(VALU, 8);
    LT_COST(VSTORE, 1);
    LT_UTIL(k);
    LT_MEM(&out[i0], LT_LANES * sizeof *out, LT_MEM_WRITE);
    for (i = 0; i < LT_LANES; i++)
        if (LT__ON(k, i))
            out[i0 + (uint32_t)i].v =
                0x80000000u | (mf15_enc(hi.l[i], 1) << 16) | mf15_enc(lo.l[i], 0);
}

/* ---- fixed-point pixels, rays, crossings and plane tests ------------------------------------- */

/* row[start + lane] for the lanes in k (0 elsewhere); negative raws are holes (0).
 * Cost: VLOAD x1, VALU x1. */
static lt_vq30_t q_loadpix_m(const lt_q30_t *row, int32_t start, lt_mask16_t k)
{
    lt_vq30_t r;
    int i;
    LT_COST(VLOAD, 1);
    LT_COST(VALU, 1);
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

/* Per-lane ray state after setup (fixed point). */
typedef struct qsetup {
    const lt_qray16_q30_t *r;
    lt_vi32_t m[2];         /* per axis: 2^62 / (|d| 2^n) rounded, in (2^30, 2^31) */
    lt_vi32_t sh[2];        /* per axis: 32 - n, the right shift after the product */
    lt_mask16_t par[2];     /* d == 0 on that axis */
    lt_mask16_t neg[2];     /* d < 0 on that axis */
} qsetup_t;

/* Lanes' per-layer outputs (see qt_layer in lt_qt.inc). */
typedef struct qlayer_out {
    lt_mask16_t hit, occ, unk;    /* hit / went behind / stopped by the step bound */
    lt_vq30_t thit, tocc, tstop;  /* s1.30 */
    lt_vi32_t nodes, aabb, planes; /* running per-lane counters */
} qlayer_out_t;

/* t = (X - o) / d for the pixel coordinate X per lane in k: (X 2^16 - o) m >> sh, half up, negated
 * for d < 0, saturated to int32. Monotonic in X for a fixed ray, so every crossing and every child
 * choice agrees with every other; |error| <= 1 ulp for |X - o| <= 2^15 px.
 * Cost: VALU x2, VMUL x1, VSHIFT x2. */
static lt_vq30_t q_tcross(const qsetup_t *S, int a, lt_mask16_t k, lt_vi32_t X)
{
    const lt_vq16_t *o = a ? &S->r->y : &S->r->x;
    lt_vq30_t t;
    int i;
    LT_COST(VALU, 2);
    LT_COST(VMUL, 1);
    LT_COST(VSHIFT, 2);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        t.l[i] = 0;
        if (LT__ON(k, i)) {
            int64_t num = (int64_t)X.l[i] * 65536 - o->l[i];
            int64_t q = q_rnd(num * S->m[a].l[i], (unsigned)S->sh[a].l[i]);
            t.l[i] = lt__ssat32(LT__ON(S->neg[a], i) ? -q : q);
        }
    }
    return t;
}

/* w of the ray at t in s1.60: w 2^30 + dw t (exact). */
LT_INLINE int64_t q_wray1(const lt_qray16_q30_t *r, int i, int32_t t)
{
    return (int64_t)r->w.l[i] * ((int64_t)1 << 30) + lt__mul32x32_64(r->dw.l[i], t);
}

/* Offset of the ray at t from the node centre in units of the node size, s1.30:
 * (o 2^30 + d t - (2q + 1) 2^(L + 45)) / 2^(16 + L), half up (o, d in s15.16, so s.46 before). */
LT_INLINE int64_t q_uoff(int32_t o, int32_t d, int32_t t, int32_t q, int32_t L)
{
    int64_t x46 = (int64_t)o * ((int64_t)1 << 30) + lt__mul32x32_64(d, t);
    int64_t c46 = (2 * (int64_t)q + 1) * ((int64_t)1 << (45 + L));
    return q_rnd(x46 - c46, 16u + (unsigned)L);
}

/* f(t) = w_ray(t) - w_plane(x(t), y(t)) in s1.60, for the lanes in k (0 elsewhere). Exact given
 * the rounded u, v: |w error| <= (|Al| + |Be|) 2^-31 raw. Cost: VMUL x5, VMULW x6, VSHIFT x2,
 * VALU x4. */
static lt_vql60_t q_plane_f(const qsetup_t *S, lt_mask16_t k, lt_vq30_t t, lt_vi32_t lvl,
                          lt_vi32_t qx, lt_vi32_t qy, const qdec_t *nd)
{
    const lt_qray16_q30_t *r = S->r;
    lt_vql60_t f;
    int i;
    LT_COST(VMUL, 5);
    LT_COST(VMULW, 6);
    LT_COST(VSHIFT, 2);
    LT_COST(VALU, 4);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        f.l[i] = 0;
        if (LT__ON(k, i)) {
            int64_t u = q_uoff(r->x.l[i], r->dx.l[i], t.l[i], qx.l[i], lvl.l[i]);
            int64_t v = q_uoff(r->y.l[i], r->dy.l[i], t.l[i], qy.l[i], lvl.l[i]);
            f.l[i] = q_wray1(r, i, t.l[i]) - (int64_t)nd->c.l[i] * ((int64_t)1 << 30) -
                     nd->al.l[i] * u - nd->be.l[i] * v;
        }
    }
    return f;
}

/* w_ray(t) in s1.60 for the lanes in k. Cost: VMUL x1, VMULW x1, VSHIFT x1. */
static lt_vql60_t q_wray(const qsetup_t *S, lt_mask16_t k, lt_vq30_t t)
{
    lt_vql60_t f;
    int i;
    LT_COST(VMUL, 1);
    LT_COST(VMULW, 1);
    LT_COST(VSHIFT, 1);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        f.l[i] = LT__ON(k, i) ? q_wray1(S->r, i, t.l[i]) : 0;
    return f;
}

/* w_ray(t) rounded to s1.30 (saturating). Cost: VMUL x1, VMULW x1, VSHIFT x1. */
static lt_vq30_t q_w_at(const qsetup_t *S, lt_mask16_t k, lt_vq30_t t)
{
    lt_vq30_t w;
    int i;
    LT_COST(VMUL, 1);
    LT_COST(VMULW, 1);
    LT_COST(VSHIFT, 1);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        w.l[i] = LT__ON(k, i) ? lt__ssat32(q_rnd(q_wray1(S->r, i, t.l[i]), 30u)) : 0;
    return w;
}

/* The crossing t in [tn, tf] of f (fn >= 0 > ff, s1.60): tn + (tf - tn) fn / (fn - ff), with fn
 * and the denominator scaled down together below 2^31 so the product fits int64; half up.
 * Cost: VDIV x1, VALU x4, VMUL x1. */
static lt_vq30_t q_hit_t(lt_mask16_t k, lt_vq30_t tn, lt_vq30_t tf, lt_vql60_t fn, lt_vql60_t ff)
{
    lt_vq30_t t = tn;
    int i;
    LT_COST(VDIV, 1);
    LT_COST(VALU, 4);
    LT_COST(VMUL, 1);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(k, i)) {
            uint64_t num = (uint64_t)fn.l[i], den = num + (uint64_t)(-ff.l[i]);
            unsigned b = 64u - lt__clz64(den), s = b > 31u ? b - 31u : 0u;
            int64_t n = (int64_t)(num >> s), dd = (int64_t)(den >> s), span;
            span = (int64_t)tf.l[i] - tn.l[i];
            if (dd == 0)
                continue;
            t.l[i] = lt__ssat32((int64_t)tn.l[i] + lt__div_round64(n * span, dd));
        }
    }
    return t;
}

/* Lanes in k where the ray is in the upper half (cx = 1) of a node split at pixel coordinate xm at
 * parameter t: past the midline crossing for d > 0, before it for d < 0, by position for d == 0.
 * Uses q_tcross so that it agrees with the exit crossings of the stepping.
 * Cost: q_tcross + VCMP x2 (+ VCMP for parallel lanes). */
static lt_mask16_t q_child_side(const qsetup_t *S, int a, lt_mask16_t k, lt_vq30_t t,
                                lt_vi32_t xm)
{
    lt_mask16_t np = (lt_mask16_t)(k & ~S->par[a]), pp = (lt_mask16_t)(k & S->par[a]), r = 0;
    if (np != 0) {
        lt_vq30_t tm = q_tcross(S, a, np, xm);
        r = (lt_mask16_t)(lt_vq30_cmpge_m((lt_mask16_t)(np & ~S->neg[a]), t, tm) |
                          lt_vq30_cmplt_m((lt_mask16_t)(np & S->neg[a]), t, tm));
    }
    if (pp != 0) {
        const lt_vq16_t *o = a ? &S->r->y : &S->r->x;
        int i;
        LT_COST(VCMP, 1);
        for (i = 0; i < LT_LANES; i++)
            if (LT__ON(pp, i) && (int64_t)o->l[i] >= (int64_t)xm.l[i] * 65536)
                r = (lt_mask16_t)(r | (1u << i));
    }
    return r;
}

/* Ray setup: validity, reciprocals, and the clip of [tmin, tmax] to the image (x in [0, W],
 * y in [0, H], through q_tcross so the clip agrees with the stepping) and to w >= 0 (the point at
 * infinity: beyond it the projective line wraps behind the camera). Returns the lanes with a
 * non-empty interval; *bad receives the invalid lanes (t0 = 0 there).
 * Cost: VDIV x3, VCMP x12, VALU x12 and six crossings. */
static lt_mask16_t q_setup(const lt_qt_t *qt, const lt_qray16_q30_t *r, lt_mask16_t k,
                           qsetup_t *S, lt_vq30_t *t0, lt_vq30_t *t1, lt_mask16_t *bad)
{
    const int64_t lim = (int64_t)1 << (LT_QT_RAY_MAX_LOG2 + 16);
    unsigned okm = 0;
    int i, a;
    lt_vi32_t lo, hi;

    S->r = r;
    S->par[0] = S->par[1] = S->neg[0] = S->neg[1] = 0;
    LT_COST(VDIV, 3);
    LT_COST(VCMP, 12);
    LT_COST(VALU, 12);
    for (i = 0; i < LT_LANES; i++) {
        int64_t x = r->x.l[i], y = r->y.l[i], ex = x + r->dx.l[i], ey = y + r->dy.l[i];
        const int32_t *d[2];
        d[0] = &r->dx.l[i];
        d[1] = &r->dy.l[i];
        t0->l[i] = 0;
        t1->l[i] = 0;
        for (a = 0; a < 2; a++) {
            S->m[a].l[i] = 0;
            S->sh[a].l[i] = 1;
        }
        if (!LT__ON(k, i))
            continue;
        if (x < -lim || x > lim || y < -lim || y > lim || ex < -lim || ex > lim || ey < -lim ||
            ey > lim || r->w.l[i] < 0 || r->tmin.l[i] < 0 || r->tmin.l[i] > r->tmax.l[i] ||
            r->tmax.l[i] > LT_Q30_ONE)
            continue;
        okm |= 1u << i;
        for (a = 0; a < 2; a++) {
            int32_t dv = *d[a];
            if (dv == 0) {
                S->par[a] = (lt_mask16_t)(S->par[a] | (1u << i));
            } else {
                uint32_t dd = dv < 0 ? (uint32_t)0 - (uint32_t)dv : (uint32_t)dv;
                unsigned n = lt__clz32(dd);
                uint64_t D = (uint64_t)dd << n;
                uint64_t m = (((uint64_t)1 << 62) + D / 2u) / D;
                if (m > (uint64_t)INT32_MAX)
                    m = (uint64_t)INT32_MAX;
                S->m[a].l[i] = (int32_t)m;
                S->sh[a].l[i] = (int32_t)(32u - n);
                if (dv < 0)
                    S->neg[a] = (lt_mask16_t)(S->neg[a] | (1u << i));
            }
        }
        t0->l[i] = r->tmin.l[i];
        t1->l[i] = r->tmax.l[i];
        /* w >= 0: stop at the point at infinity (rounded down) */
        if (r->dw.l[i] < 0) {
            int64_t tw = lt__divfloor64((int64_t)r->w.l[i] * ((int64_t)1 << 30), -(int64_t)r->dw.l[i]);
            if (tw < t1->l[i])
                t1->l[i] = (int32_t)tw;
        }
    }
    *bad = (lt_mask16_t)(k & ~okm);
    k = (lt_mask16_t)okm;
    /* image clip per axis: entering at the near edge, leaving at the far one */
    for (a = 0; a < 2; a++) {
        int32_t ext = (int32_t)(a ? qt->height : qt->width);
        lt_mask16_t kn = (lt_mask16_t)(k & ~S->par[a]), neg = S->neg[a];
        lt_vq30_t te, tx;
        lo = lt_vi32_blend(neg, lt_vi32_set1(0), lt_vi32_set1(ext));
        hi = lt_vi32_blend(neg, lt_vi32_set1(ext), lt_vi32_set1(0));
        te = q_tcross(S, a, kn, lo);
        tx = q_tcross(S, a, kn, hi);
        *t0 = lt_vq30_blend(kn, *t0, lt_vq30_max(*t0, te));
        *t1 = lt_vq30_blend(kn, *t1, lt_vq30_min(*t1, tx));
        /* parallel: inside the half-open [0, ext) or never */
        for (i = 0; i < LT_LANES; i++) {
            if (LT__ON(k & S->par[a], i)) {
                int32_t o = a ? r->y.l[i] : r->x.l[i];
                if (o < 0 || (int64_t)o >= (int64_t)ext * 65536)
                    t1->l[i] = -1;
            }
        }
    }
    return lt_vq30_cmplt_m(k, *t0, *t1);
}

/* Angle test: (dSx^2 + dSy^2) / 2 <= gamma_norm with dS in s1.30 (rounded from LS_FRAC more bits);
 * compared as squares against 2 gamma 2^30 in s2.60, so no square root is needed.
 * Cost: VSHIFT x2, VMUL x2, VMULW x1, VCMP x3. */
static lt_mask16_t q_angle_ok(lt_mask16_t k, lt_vql36_t dsx, lt_vql36_t dsy, int64_t lim)
{
    unsigned m = 0;
    int i;
    LT_COST(VSHIFT, 2);
    LT_COST(VMUL, 2);
    LT_COST(VMULW, 1);
    LT_COST(VCMP, 3);
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
#define LTQ_TCROSS q_tcross
#define LTQ_PLANE_F q_plane_f
#define LTQ_WRAY q_wray
#define LTQ_W_AT q_w_at
#define LTQ_HIT_T q_hit_t
#define LTQ_T_BACK(t) lt_vq30_sub_sat((t), lt_vq30_set1(4))
#define LTQ_CHILD_SIDE q_child_side
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

static void f_decode(const lt_qt_nf32_t *base, uint32_t i0, uint32_t stride, lt_mask16_t k,
                     int bounds, fdec_t *d)
{
    int i;
    fdec_zero(d);
    LT_COST(VGATHER, 2u * lt__popcount32(k));
    LT_COST(VALU, 2);
    if (bounds)
        LT_COST(FADD, 4);
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
    LT_COST(VGATHER, 2u * lt__popcount32(k));
    LT_COST(VALU, 2);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(k, i)) {
            const lt_qt_nf32_t *p = &base[(uint32_t)idx.l[i]];
            LT_MEM(p, sizeof *p, LT_MEM_READ);
            f_dec1(p, 0, d, i);
        }
    }
}

static lt_mask16_t f_enc_plane(lt_qt_nf32_t *out, uint32_t i0, lt_mask16_t k, lt_vf32_t c,
                               lt_vf32_t al, lt_vf32_t be, lt_mask16_t o)
{
    int i;
    LT_COST(VSTORE, 4);
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
    LT_COST(VSTORE, 4);
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

/* row[start + lane]; NaN, +-inf and negative values are holes (0). Cost: VLOAD x1, FCMP x2. */
static lt_vf32_t f_loadpix_m(const float *row, int32_t start, lt_mask16_t k)
{
    lt_vf32_t r;
    int i;
    LT_COST(VLOAD, 1);
    LT_COST(FCMP, 2);
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

typedef struct fsetup {
    const lt_qray16_f32_t *r;
    lt_vf32_t rcp[2];   /* 1 / d per axis (0 for parallel lanes) */
    lt_mask16_t par[2]; /* d == +-0 */
    lt_mask16_t neg[2]; /* d < 0 */
} fsetup_t;

typedef struct flayer_out {
    lt_mask16_t hit, occ, unk;
    lt_vf32_t thit, tocc, tstop;
    lt_vi32_t nodes, aabb, planes;
} flayer_out_t;

/* t = (X - o) / d as (X - o) * (1 / d): monotonic in X. Cost: VCVT x1, FADD x1, FMUL x1. */
static lt_vf32_t f_tcross(const fsetup_t *S, int a, lt_mask16_t k, lt_vi32_t X)
{
    const lt_vf32_t *o = a ? &S->r->y : &S->r->x;
    lt_vf32_t t;
    int i;
    LT_COST(VCVT, 1);
    LT_COST(FADD, 1);
    LT_COST(FMUL, 1);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        t.l[i] = LT__ON(k, i) ? ((float)X.l[i] - o->l[i]) * S->rcp[a].l[i] : 0.0f;
    return t;
}

/* f(t) = (w + t dw) - (c + al u + be v), u = (x + t dx - xc) / 2^L. Cost: VCVT x2, FMUL x7,
 * FADD x8. */
static lt_vf32_t f_plane_f(const fsetup_t *S, lt_mask16_t k, lt_vf32_t t, lt_vi32_t lvl,
                           lt_vi32_t qx, lt_vi32_t qy, const fdec_t *nd)
{
    const lt_qray16_f32_t *r = S->r;
    lt_vf32_t f;
    int i;
    LT_COST(VCVT, 2);
    LT_COST(FMUL, 7);
    LT_COST(FADD, 8);
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

static lt_vf32_t f_wray(const fsetup_t *S, lt_mask16_t k, lt_vf32_t t)
{
    lt_vf32_t w;
    int i;
    LT_COST(FMUL, 1);
    LT_COST(FADD, 1);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        w.l[i] = LT__ON(k, i) ? S->r->w.l[i] + t.l[i] * S->r->dw.l[i] : 0.0f;
    return w;
}

static lt_vf32_t f_hit_t(lt_mask16_t k, lt_vf32_t tn, lt_vf32_t tf, lt_vf32_t fn, lt_vf32_t ff)
{
    int i;
    LT_COST(FDIV, 1);
    LT_COST(FADD, 3);
    LT_COST(FMUL, 1);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++)
        if (LT__ON(k, i))
            tn.l[i] = tn.l[i] + (tf.l[i] - tn.l[i]) * (fn.l[i] / (fn.l[i] - ff.l[i]));
    return tn;
}

static lt_mask16_t f_child_side(const fsetup_t *S, int a, lt_mask16_t k, lt_vf32_t t,
                                lt_vi32_t xm)
{
    lt_mask16_t np = (lt_mask16_t)(k & ~S->par[a]), pp = (lt_mask16_t)(k & S->par[a]), r = 0;
    if (np != 0) {
        lt_vf32_t tm = f_tcross(S, a, np, xm);
        r = (lt_mask16_t)(lt_vf32_cmpge_m((lt_mask16_t)(np & ~S->neg[a]), t, tm) |
                          lt_vf32_cmplt_m((lt_mask16_t)(np & S->neg[a]), t, tm));
    }
    if (pp != 0) {
        const lt_vf32_t *o = a ? &S->r->y : &S->r->x;
        int i;
        LT_COST(FCMP, 1);
        for (i = 0; i < LT_LANES; i++)
            if (LT__ON(pp, i) && o->l[i] >= (float)xm.l[i])
                r = (lt_mask16_t)(r | (1u << i));
    }
    return r;
}

static lt_mask16_t f_setup(const lt_qt_t *qt, const lt_qray16_f32_t *r, lt_mask16_t k,
                           fsetup_t *S, lt_vf32_t *t0, lt_vf32_t *t1, lt_mask16_t *bad)
{
    const float lim = (float)(1u << LT_QT_RAY_MAX_LOG2);
    unsigned okm = 0;
    int i, a;
    S->r = r;
    S->par[0] = S->par[1] = S->neg[0] = S->neg[1] = 0;
    LT_COST(FDIV, 3);
    LT_COST(FCMP, 12);
    LT_COST(FADD, 6);
    for (i = 0; i < LT_LANES; i++) {
        float x = r->x.l[i], y = r->y.l[i], ex = x + r->dx.l[i], ey = y + r->dy.l[i];
        t0->l[i] = 0.0f;
        t1->l[i] = 0.0f;
        S->rcp[0].l[i] = S->rcp[1].l[i] = 0.0f;
        if (!LT__ON(k, i))
            continue;
        /* written as negations of the valid ranges so that NaN fails every test */
        if (!(x >= -lim && x <= lim && y >= -lim && y <= lim && ex >= -lim && ex <= lim &&
              ey >= -lim && ey <= lim && r->w.l[i] >= 0.0f && r->w.l[i] <= F_INF &&
              r->dw.l[i] >= -F_INF && r->dw.l[i] <= F_INF && r->tmin.l[i] >= 0.0f &&
              r->tmin.l[i] <= r->tmax.l[i] && r->tmax.l[i] <= 1.0f))
            continue;
        okm |= 1u << i;
        for (a = 0; a < 2; a++) {
            float dv = a ? r->dy.l[i] : r->dx.l[i];
            if (dv == 0.0f) {
                S->par[a] = (lt_mask16_t)(S->par[a] | (1u << i));
            } else {
                S->rcp[a].l[i] = 1.0f / dv;
                if (dv < 0.0f)
                    S->neg[a] = (lt_mask16_t)(S->neg[a] | (1u << i));
            }
        }
        t0->l[i] = r->tmin.l[i];
        t1->l[i] = r->tmax.l[i];
        if (r->dw.l[i] < 0.0f) {
            float tw = r->w.l[i] / -r->dw.l[i];
            if (tw < t1->l[i])
                t1->l[i] = tw;
        }
    }
    *bad = (lt_mask16_t)(k & ~okm);
    k = (lt_mask16_t)okm;
    for (a = 0; a < 2; a++) {
        int32_t ext = (int32_t)(a ? qt->height : qt->width);
        lt_mask16_t kn = (lt_mask16_t)(k & ~S->par[a]), neg = S->neg[a];
        lt_vi32_t lo = lt_vi32_blend(neg, lt_vi32_set1(0), lt_vi32_set1(ext));
        lt_vi32_t hi = lt_vi32_blend(neg, lt_vi32_set1(ext), lt_vi32_set1(0));
        lt_vf32_t te = f_tcross(S, a, kn, lo), tx = f_tcross(S, a, kn, hi);
        *t0 = lt_vf32_blend(kn, *t0, lt_vf32_max(*t0, te));
        *t1 = lt_vf32_blend(kn, *t1, lt_vf32_min(*t1, tx));
        for (i = 0; i < LT_LANES; i++) {
            if (LT__ON(k & S->par[a], i)) {
                float o = a ? r->y.l[i] : r->x.l[i];
                if (!(o >= 0.0f && o < (float)ext))
                    t1->l[i] = -1.0f;
            }
        }
    }
    return lt_vf32_cmplt_m(k, *t0, *t1);
}

static lt_mask16_t f_angle_ok(lt_mask16_t k, lt_vf32_t dsx, lt_vf32_t dsy, float lim)
{
    lt_vf32_t s = lt_vf32_add(lt_vf32_mul(dsx, dsx), lt_vf32_mul(dsy, dsy));
    return lt_vf32_cmple_m(k, s, lt_vf32_set1(lim));
}

static lt_vf32_t f_w_at(const fsetup_t *S, lt_mask16_t k, lt_vf32_t t)
{
    return f_wray(S, k, t);
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
#define LTQ_TCROSS f_tcross
#define LTQ_PLANE_F f_plane_f
#define LTQ_WRAY f_wray
#define LTQ_W_AT f_w_at
#define LTQ_HIT_T f_hit_t
#define LTQ_T_BACK(t) lt_vf32_sub((t), lt_vf32_set1(4.76837158203125e-7f))
#define LTQ_CHILD_SIDE f_child_side
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
