/* lt_reproj.c - reprojection ray generation for screen-space view synthesis (Widmer et al.,
 * 2015 [Widmer15]; docs/quadtree.md section 1, docs/reproject.md): the traits that instantiate
 * lt_reproj.inc for the s1.30 mapping (int64 homogeneous points, integer only) and the float32
 * mapping, and lt_reproj_setup, which builds both from two pinhole cameras in double.
 * Builds: all; float32 and the setup only with LT_CFG_FLOAT32.
 */
#include "lt/lt_reproj.h"

/* ==== s1.30 path ============================================================================= */

/* floor(a s / 2^30) for |a| < 2^59 and 0 <= s < 2^31: a = ah 2^32 + al with 0 <= al < 2^32, so
 * a s / 2^30 = 4 ah s + al s / 2^30 and only the second part is floored (exact, no int128). */
static int64_t rpj_mulq30(int64_t a, int32_t s)
{
    int64_t ah = lt__asr64(a, 32);
    uint64_t al = (uint64_t)a & 0xFFFFFFFFu;
    return 4 * ah * (int64_t)s + (int64_t)((al * (uint64_t)s) >> 30);
}

/* n / d as s1.30 in [0, 2^30], 0 <= n <= d, d > 0, d < 2^63. Both are shifted right together
 * until d < 2^32 (relative error < 2^-31 of the ratio, i.e. < 1 ulp), then one 64-bit division;
 * up != 0 rounds up and adds one more ulp, else rounds down and subtracts one: the clip
 * parameter always moves inward, past any rounding. */
static int32_t rpj_ratio(uint64_t n, uint64_t d, int up)
{
    unsigned nb = 64u - lt__clz64(d);
    int64_t s;
    if (nb > 32u) {
        n >>= nb - 32u;
        d >>= nb - 32u;
    }
    if (d == 0)
        return up ? LT_Q30_ONE : 0;
    if (up)
        s = (int64_t)(((n << 30) + d - 1u) / d) + 1;
    else
        s = (int64_t)((n << 30) / d) - 1;
    if (s < 0)
        s = 0;
    if (s > LT_Q30_ONE)
        s = LT_Q30_ONE;
    return (int32_t)s;
}

/* Entering a constraint (ca < 0 <= cb) at s = -ca / (cb - ca), rounded up; leaving (ca >= 0 > cb)
 * at ca / (ca - cb), rounded down. |ca|, |cb| < 2^62, so the sums fit uint64. */
static int32_t rpj_param_in_q30(int64_t ca, int64_t cb)
{
    return rpj_ratio((uint64_t)(-ca), (uint64_t)cb + (uint64_t)(-ca), 1);
}

static int32_t rpj_param_out_q30(int64_t ca, int64_t cb)
{
    return rpj_ratio((uint64_t)ca, (uint64_t)ca + (uint64_t)(-cb), 0);
}

/* g = (2u + 1, 2v + 1, 2^(dst_log2 + 1)): the pixel centre scaled by 2 (exact integers). */
static void rpj_input_q30(const lt_reproj_q30_t *m, uint32_t u, uint32_t v, int64_t g[3])
{
    g[0] = 2 * (int64_t)u + 1;
    g[1] = 2 * (int64_t)v + 1;
    g[2] = (int64_t)1 << (m->dst_log2 + 1u);
}

/* Row . g: |m| <= 2^30, |g| <= 2^15, so each product < 2^45 and the sum < 2^47 (exact). */
static int64_t rpj_dot3_q30(const int32_t row[3], const int64_t g[3])
{
    return (int64_t)row[0] * g[0] + (int64_t)row[1] * g[1] + (int64_t)row[2] * g[2];
}

/* The six constraint values of a homogeneous point (rows X / 2^s, Y / 2^s, W, H):
 * src_w H - 2^s X etc. < 2^14 2^47 2 = 2^62; the w bounds use w_near H / 2^30 (floor). */
static void rpj_constraints_q30(const lt_reproj_q30_t *m, const int64_t p[4], int64_t c[6])
{
    int64_t sx = (int64_t)1 << m->src_log2;
    c[0] = p[0];
    c[1] = (int64_t)m->src_w * p[3] - sx * p[0];
    c[2] = p[1];
    c[3] = (int64_t)m->src_h * p[3] - sx * p[1];
    c[4] = rpj_mulq30(p[3], m->w_near) - p[2];
    c[5] = p[2] - rpj_mulq30(p[3], m->w_far);
}

/* Pa + floor((Pb - Pa) s / 2^30): |Pb - Pa| < 2^48. */
static int64_t rpj_lerp_q30(int64_t a, int64_t b, int32_t s)
{
    return a + rpj_mulq30(b - a, s);
}

/* round(a / b) half up for b > 0, |a| < 2^62. */
static int32_t rpj_divr(int64_t a, int64_t b)
{
    return lt__ssat32(lt__divfloor64(a + b / 2, b));
}

/* (X, Y, W, H) -> x, y s15.16 and w s1.30. H is normalised to [2^30, 2^31) by one shift of all
 * four (floor; relative error 2^-30); the divisions then fit int64 since |X|, |Y| <= 2 H and
 * W <= 2 H (the clipped point has |X|, |Y| <= H and W <= w_near H; more is a degenerate lane
 * whose clip parameter rounding dominated, rejected). Results are clamped to the clip box (they
 * can leave it by rounding only). Returns 0 for a point not in front of the source. */
static int rpj_affine_q30(const lt_reproj_q30_t *m, const int64_t p[4], int32_t out[3])
{
    int64_t x = p[0], y = p[1], w = p[2], h = p[3];
    unsigned nb;
    int32_t xmax = (int32_t)(m->src_w << 16), ymax = (int32_t)(m->src_h << 16), rx, ry, rw;

    if (h <= 0)
        return 0;
    if (x > 2 * h || -x > 2 * h || y > 2 * h || -y > 2 * h || w > 2 * h || -w > 2 * h)
        return 0;
    nb = 64u - lt__clz64((uint64_t)h);
    if (nb > 31u) {
        x = lt__asr64(x, nb - 31u);
        y = lt__asr64(y, nb - 31u);
        w = lt__asr64(w, nb - 31u);
        h = lt__asr64(h, nb - 31u);
    } else {
        int64_t f = (int64_t)1 << (31u - nb);
        x *= f;
        y *= f;
        w *= f;
        h *= f;
    }
    rx = rpj_divr(x * ((int64_t)1 << (m->src_log2 + 16u)), h);
    ry = rpj_divr(y * ((int64_t)1 << (m->src_log2 + 16u)), h);
    rw = rpj_divr(w * ((int64_t)1 << 30), h);
    out[0] = rx < 0 ? 0 : (rx > xmax ? xmax : rx);
    out[1] = ry < 0 ? 0 : (ry > ymax ? ymax : ry);
    out[2] = rw < m->w_far ? m->w_far : (rw > m->w_near ? m->w_near : rw);
    return 1;
}

static lt_status_t rpj_check_q30(const lt_reproj_q30_t *m)
{
    int r, c;
    if (m->src_log2 > LT_QT_MAX_DIM_LOG2 || m->dst_log2 > LT_QT_MAX_DIM_LOG2 ||
        m->src_w == 0 || m->src_h == 0 || m->dst_w == 0 || m->dst_h == 0 ||
        m->src_w > (1u << m->src_log2) || m->src_h > (1u << m->src_log2) ||
        m->dst_w > (1u << m->dst_log2) || m->dst_h > (1u << m->dst_log2))
        return LT_E_ARG;
    if (m->w_near <= 0 || m->w_far < 0 || m->w_far >= m->w_near)
        return LT_E_ARG;
    for (r = 0; r < 4; r++)
        for (c = 0; c < 3; c++)
            if (m->ma[r][c] > LT_Q30_ONE || m->ma[r][c] < -LT_Q30_ONE ||
                m->mb[r][c] > LT_Q30_ONE || m->mb[r][c] < -LT_Q30_ONE)
                return LT_E_ARG;
    return LT_OK;
}

/* The packet's straight-line 16-lane program (docs/reproject.md, "cost"): input 4 VALU + 2
 * VSHIFT; 24 products (VMUL) and 16 wide adds (VMULW) for Pa, Pb; constraints 20 VMULW + 8 VMUL
 * for both ends; per constraint 2 VCMP, 4 VALU, 2 VSHIFT, 1 VDIV and a MASK op; two lerps 16 VMUL
 * + 16 VMULW; two divides to (x, y, w) 8 VCMP, 14 VALU, 8 VSHIFT, 6 VDIV, 6 VMULW; 3 VALU for the
 * differences. Masked lane slots are counted for the utilisation (LANES_ON, LANE_OPS). */
#define RPJ_Q30_OPS (45u + 22u + 48u + 58u + 21u + 12u) /* the masked lane ops above */
static void rpj_charge_q30(unsigned k)
{
    LT_CHARGE(RPJ_Q30_PACKET);
    LT_EVENT(LANES_ON, lt__popcount32(k) * RPJ_Q30_OPS);
    LT_EVENT(LANE_OPS, RPJ_Q30_OPS);
}

#define RPJ_FN(name) name##_q30
#define RPJ_MAP lt_reproj_q30_t
#define RPJ_RAY lt_qray16_q30_t
#define RPJ_H int64_t
#define RPJ_H_ZERO 0
#define RPJ_S int32_t
#define RPJ_S_ZERO 0
#define RPJ_S_ONE LT_Q30_ONE
#define RPJ_XY int32_t
#define RPJ_XY_SUB(a, b) ((a) - (b)) /* both in [0, 2^30] (x, y) or [0, 2^31) (w) */
#define RPJ_T_ZERO 0
#define RPJ_T_ONE LT_Q30_ONE
#define RPJ_INPUT rpj_input_q30
#define RPJ_DOT3 rpj_dot3_q30
#define RPJ_CONSTRAINTS rpj_constraints_q30
#define RPJ_PARAM_IN rpj_param_in_q30
#define RPJ_PARAM_OUT rpj_param_out_q30
#define RPJ_LERP rpj_lerp_q30
#define RPJ_AFFINE rpj_affine_q30
#define RPJ_CHECK_MAP rpj_check_q30
#define RPJ_CHARGE rpj_charge_q30
#include "lt_reproj.inc"

#if LT_CFG_FLOAT32
/* ==== float32 path ============================================================================ */

static void rpj_input_f32(const lt_reproj_f32_t *m, uint32_t u, uint32_t v, float g[3])
{
    (void)m;
    g[0] = (float)u + 0.5f;
    g[1] = (float)v + 0.5f;
    g[2] = 1.0f;
}

static float rpj_dot3_f32(const float row[3], const float g[3])
{
    return row[0] * g[0] + row[1] * g[1] + row[2] * g[2];
}

static void rpj_constraints_f32(const lt_reproj_f32_t *m, const float p[4], float c[6])
{
    c[0] = p[0];
    c[1] = (float)m->src_w * p[3] - p[0];
    c[2] = p[1];
    c[3] = (float)m->src_h * p[3] - p[1];
    c[4] = m->w_near * p[3] - p[2];
    c[5] = p[2] - m->w_far * p[3];
}

static float rpj_param_f32(float ca, float cb)
{
    float s = ca / (ca - cb);
    return s < 0.0f ? 0.0f : (s > 1.0f ? 1.0f : s);
}

static float rpj_lerp_f32(float a, float b, float s)
{
    return a + (b - a) * s;
}

/* x = X / H etc., clamped to the clip box (float rounding of the clip parameter can leave it by
 * an ulp). Returns 0 for H <= 0 or a non-finite result. */
static int rpj_affine_f32(const lt_reproj_f32_t *m, const float p[4], float out[3])
{
    float x, y, w, xm = (float)m->src_w, ym = (float)m->src_h;
    if (!(p[3] > 0.0f))
        return 0;
    x = p[0] / p[3];
    y = p[1] / p[3];
    w = p[2] / p[3];
    if (x - x != 0.0f || y - y != 0.0f || w - w != 0.0f) /* NaN or inf */
        return 0;
    out[0] = x < 0.0f ? 0.0f : (x > xm ? xm : x);
    out[1] = y < 0.0f ? 0.0f : (y > ym ? ym : y);
    out[2] = w < m->w_far ? m->w_far : (w > m->w_near ? m->w_near : w);
    return 1;
}

static lt_status_t rpj_check_f32(const lt_reproj_f32_t *m)
{
    int r, c;
    if (m->src_w == 0 || m->src_h == 0 || m->dst_w == 0 || m->dst_h == 0 ||
        m->src_w > LT_QT_MAX_DIM || m->src_h > LT_QT_MAX_DIM || m->dst_w > LT_QT_MAX_DIM ||
        m->dst_h > LT_QT_MAX_DIM)
        return LT_E_ARG;
    if (!(m->w_near > 0.0f && m->w_near < 2.0f && m->w_far >= 0.0f && m->w_far < m->w_near))
        return LT_E_ARG;
    for (r = 0; r < 4; r++)
        for (c = 0; c < 3; c++)
            if (!(m->ma[r][c] - m->ma[r][c] == 0.0f && m->mb[r][c] - m->mb[r][c] == 0.0f))
                return LT_E_ARG;
    return LT_OK;
}

/* The same program in binary32: FMUL 24 + 12 + 8, FADD 16 + 12 + 8 + 12, FDIV 6 + 6, FCMP 21,
 * VALU 4 + 3 + 12 (input, differences, clamps), MASK 8. */
#define RPJ_F32_OPS (44u + 48u + 12u + 21u + 19u) /* the masked lane ops above */
static void rpj_charge_f32(unsigned k)
{
    LT_CHARGE(RPJ_F32_PACKET);
    LT_EVENT(LANES_ON, lt__popcount32(k) * RPJ_F32_OPS);
    LT_EVENT(LANE_OPS, RPJ_F32_OPS);
}

#define RPJ_FN(name) name##_f32
#define RPJ_MAP lt_reproj_f32_t
#define RPJ_RAY lt_qray16_f32_t
#define RPJ_H float
#define RPJ_H_ZERO 0.0f
#define RPJ_S float
#define RPJ_S_ZERO 0.0f
#define RPJ_S_ONE 1.0f
#define RPJ_XY float
#define RPJ_XY_SUB(a, b) ((a) - (b))
#define RPJ_T_ZERO 0.0f
#define RPJ_T_ONE 1.0f
#define RPJ_INPUT rpj_input_f32
#define RPJ_DOT3 rpj_dot3_f32
#define RPJ_CONSTRAINTS rpj_constraints_f32
#define RPJ_PARAM_IN rpj_param_f32
#define RPJ_PARAM_OUT rpj_param_f32
#define RPJ_LERP rpj_lerp_f32
#define RPJ_AFFINE rpj_affine_f32
#define RPJ_CHECK_MAP rpj_check_f32
#define RPJ_CHARGE rpj_charge_f32
#include "lt_reproj.inc"

/* ==== setup (double) ========================================================================== */

static int rpj_finite(double x)
{
    return x - x == 0.0; /* false for NaN and +-inf, without libm */
}

static double rpj_fabs(double x)
{
    return x < 0.0 ? -x : x;
}

static lt_status_t rpj_check_cam(const lt_reproj_cam_t *c)
{
    int i, j, l;
    if (!rpj_finite(c->fx) || !rpj_finite(c->fy) || !rpj_finite(c->cx) || !rpj_finite(c->cy))
        return LT_E_ARG;
    if (!(c->fx > 0.0) || !(c->fy > 0.0))
        return LT_E_ARG;
    if (c->width == 0 || c->height == 0 || c->width > LT_QT_MAX_DIM || c->height > LT_QT_MAX_DIM)
        return LT_E_ARG;
    for (i = 0; i < 3; i++) {
        if (!rpj_finite(c->c[i]))
            return LT_E_ARG;
        for (j = 0; j < 3; j++)
            if (!rpj_finite(c->r[i][j]))
                return LT_E_ARG;
    }
    /* R R^T = I within 1e-6: a singular or scaled matrix is not a camera pose */
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            double d = 0.0;
            for (l = 0; l < 3; l++)
                d += c->r[i][l] * c->r[j][l];
            if (rpj_fabs(d - (i == j ? 1.0 : 0.0)) > 1e-6)
                return LT_E_ARG;
        }
    return LT_OK;
}

static uint32_t rpj_log2ceil(uint32_t w, uint32_t h)
{
    uint32_t d = w > h ? w : h, s = 0;
    while ((1u << s) < d)
        s++;
    return s;
}

/* Scale m (12 entries) by a power of two so that max |m| lies in [2^29, 2^30) (exact in double).
 * Returns 0, or -1 for an all-zero or non-finite matrix. */
static int rpj_normalise(double m[12], double target)
{
    double mx = 0.0, f = 1.0;
    int i, n = 0;
    for (i = 0; i < 12; i++) {
        if (!rpj_finite(m[i]))
            return -1;
        if (rpj_fabs(m[i]) > mx)
            mx = rpj_fabs(m[i]);
    }
    if (mx == 0.0)
        return -1;
    while (mx * f >= target && n < 2000) {
        f *= 0.5;
        n++;
    }
    while (mx * f < target * 0.5 && n < 2000) {
        f *= 2.0;
        n++;
    }
    for (i = 0; i < 12; i++)
        m[i] *= f;
    return 0;
}

/* Round half away from zero to int32 (|v| <= 2^30 + 1/2 after normalisation). */
static int32_t rpj_round_i32(double v)
{
    return v >= 0.0 ? (int32_t)(v + 0.5) : -(int32_t)(-v + 0.5);
}

lt_status_t lt_reproj_setup(const lt_reproj_cam_t *src, const lt_reproj_cam_t *dst,
                            const lt_reproj_opts_t *o, lt_reproj_q30_t *mq, lt_reproj_f32_t *mf)
{
    double rrel[3][3], trel[3], a[3][3], b[3], kinv[3][3], tmp[3][3];
    double ma[4][3], mb[4][3], wn, wf, qn;
    double zn;
    int i, j, l;

    if (src == NULL || dst == NULL || o == NULL || (mq == NULL && mf == NULL))
        return LT_E_ARG;
    if (rpj_check_cam(src) != LT_OK || rpj_check_cam(dst) != LT_OK)
        return LT_E_ARG;
    if (!rpj_finite(o->z_ref) || !rpj_finite(o->z_near_src) || !rpj_finite(o->z_far_src) ||
        !rpj_finite(o->z_near_dst) || !(o->z_ref > 0.0) || o->z_near_src < 0.0 ||
        o->z_far_src < 0.0 || o->z_near_dst < 0.0)
        return LT_E_ARG;
    zn = o->z_near_src > 0.0 ? o->z_near_src : o->z_ref;
    wn = o->z_ref / zn;
    wf = o->z_far_src > 0.0 ? o->z_ref / o->z_far_src : 0.0;
    if (!(wn < 2.0) || !(wf < wn))
        return LT_E_RANGE;

    /* R_rel = R_s R_t^T (target camera axes in source camera coordinates),
     * t_rel = R_s (c_t - c_s) (target centre in source camera coordinates) */
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            double d = 0.0;
            for (l = 0; l < 3; l++)
                d += src->r[i][l] * dst->r[j][l];
            rrel[i][j] = d;
        }
        trel[i] = 0.0;
        for (l = 0; l < 3; l++)
            trel[i] += src->r[i][l] * (dst->c[l] - src->c[l]);
    }
    /* K_t^-1 */
    kinv[0][0] = 1.0 / dst->fx;
    kinv[0][1] = 0.0;
    kinv[0][2] = -dst->cx / dst->fx;
    kinv[1][0] = 0.0;
    kinv[1][1] = 1.0 / dst->fy;
    kinv[1][2] = -dst->cy / dst->fy;
    kinv[2][0] = kinv[2][1] = 0.0;
    kinv[2][2] = 1.0;
    /* A = K_s R_rel K_t^-1, b = K_s t_rel */
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            double d = 0.0;
            for (l = 0; l < 3; l++)
                d += rrel[i][l] * kinv[l][j];
            tmp[i][j] = d;
        }
    for (j = 0; j < 3; j++) {
        a[0][j] = src->fx * tmp[0][j] + src->cx * tmp[2][j];
        a[1][j] = src->fy * tmp[1][j] + src->cy * tmp[2][j];
        a[2][j] = tmp[2][j];
    }
    b[0] = src->fx * trel[0] + src->cx * trel[2];
    b[1] = src->fy * trel[1] + src->cy * trel[2];
    b[2] = trel[2];

    /* far end, q = 0: (A p, 0); near end, q = 1 / z_near_dst: (A p + q b, z_ref q), or the
     * target centre (b, z_ref) (the limit q -> infinity divided by q) */
    qn = o->z_near_dst > 0.0 ? 1.0 / o->z_near_dst : 0.0;
    for (j = 0; j < 3; j++) {
        mb[0][j] = a[0][j];
        mb[1][j] = a[1][j];
        mb[2][j] = 0.0;
        mb[3][j] = a[2][j];
        if (o->z_near_dst > 0.0) {
            ma[0][j] = a[0][j];
            ma[1][j] = a[1][j];
            ma[2][j] = 0.0;
            ma[3][j] = a[2][j];
        } else {
            ma[0][j] = ma[1][j] = ma[2][j] = ma[3][j] = 0.0;
        }
    }
    if (o->z_near_dst > 0.0) {
        ma[0][2] += qn * b[0];
        ma[1][2] += qn * b[1];
        ma[2][2] = o->z_ref * qn;
        ma[3][2] += qn * b[2];
    } else {
        ma[0][2] = b[0];
        ma[1][2] = b[1];
        ma[2][2] = o->z_ref;
        ma[3][2] = b[2];
    }

    if (mf != NULL) {
        double fa[12], fb[12];
        for (i = 0; i < 4; i++)
            for (j = 0; j < 3; j++) {
                fa[i * 3 + j] = ma[i][j];
                fb[i * 3 + j] = mb[i][j];
            }
        if (rpj_normalise(fa, 1.0) != 0 || rpj_normalise(fb, 1.0) != 0)
            return LT_E_RANGE;
        for (i = 0; i < 4; i++)
            for (j = 0; j < 3; j++) {
                mf->ma[i][j] = (float)fa[i * 3 + j];
                mf->mb[i][j] = (float)fb[i * 3 + j];
            }
        mf->src_w = src->width;
        mf->src_h = src->height;
        mf->dst_w = dst->width;
        mf->dst_h = dst->height;
        mf->w_near = (float)wn;
        mf->w_far = (float)wf;
        if (!(mf->w_near < 2.0f) || !(mf->w_far < mf->w_near))
            return LT_E_RANGE;
    }
    if (mq != NULL) {
        /* g = (2u + 1, 2v + 1, 2^(St + 1)) = 2 (u + 1/2, v + 1/2, 2^St): columns 0, 1 take 1/2,
         * column 2 takes 2^-(St + 1); rows X, Y take 2^-Ss (x in units of the source size) */
        double qa[12], qb[12];
        uint32_t ss = rpj_log2ceil(src->width, src->height);
        uint32_t st = rpj_log2ceil(dst->width, dst->height);
        double cs = 1.0, rs = 1.0;
        for (i = 0; i < (int)st + 1; i++)
            cs *= 0.5;
        for (i = 0; i < (int)ss; i++)
            rs *= 0.5;
        for (i = 0; i < 4; i++)
            for (j = 0; j < 3; j++) {
                double f = (j < 2 ? 0.5 : cs) * (i < 2 ? rs : 1.0);
                qa[i * 3 + j] = ma[i][j] * f;
                qb[i * 3 + j] = mb[i][j] * f;
            }
        if (rpj_normalise(qa, 1073741824.0) != 0 || rpj_normalise(qb, 1073741824.0) != 0)
            return LT_E_RANGE;
        for (i = 0; i < 4; i++)
            for (j = 0; j < 3; j++) {
                mq->ma[i][j] = rpj_round_i32(qa[i * 3 + j]);
                mq->mb[i][j] = rpj_round_i32(qb[i * 3 + j]);
            }
        mq->src_w = src->width;
        mq->src_h = src->height;
        mq->dst_w = dst->width;
        mq->dst_h = dst->height;
        mq->src_log2 = ss;
        mq->dst_log2 = st;
        {
            double vn = wn * 1073741824.0 + 0.5, vf = wf * 1073741824.0 + 0.5;
            if (vn >= 2147483647.0)
                return LT_E_RANGE;
            mq->w_near = (int32_t)vn;
            mq->w_far = (int32_t)vf;
            if (mq->w_near <= 0 || mq->w_far >= mq->w_near)
                return LT_E_RANGE;
        }
    }
    return LT_OK;
}
#endif /* LT_CFG_FLOAT32 */
