/* lt_bvh.c - instantiates the BVH kernels of lt_bvh.inc for s15.16 (integer SAH, exact int64
 * products in the single-ray triangle test) and IEEE float32; the traits below are the only place
 * where the two paths differ. Also the arena layout shared by both builders, and the quantised
 * 16-byte node variant (s15.16 only). Builds: all; float32 only with LT_CFG_FLOAT32.
 */
#include "lt/lt_bvh.h"
#include "lt/lt_bvh8.h"
#include "lt_tri.h"
#include "lt_isel.h"

LT__ISEL1_DEFINE(q16, lt_ray1_q16_t, lt_tri_q16_t, lt_wt1_q16_t)
#if LT_CFG_FLOAT32
LT__ISEL1_DEFINE(f32, lt_ray1_f32_t, lt_tri_f32_t, lt_wt1_f32_t)
#endif

/* ---- shared: parameters, arena layout, depth budget ------------------------------------------ */

typedef struct bvh_stack {
    uint32_t node;  /* node index */
    uint32_t depth; /* its depth, root = 0 */
} bvh_stack_t;

/* Arena layout, offsets in bytes from the arena start (which must be 8-byte aligned). */
typedef struct bvh_layout {
    size_t nodes_off, idx_off, boxes_off, bins_off, area_off, cnt_off, stack_off, total;
    uint32_t bins, max_leaf, min_leaf, max_depth, flags; /* resolved parameters */
} bvh_layout_t;

/* One SAH bin: a box (24 B in either path) and a count. */
#define BVH_BIN_BYTES 28u
/* One entry of the SAH sweep's area array: uint64 (s15.16) or float, sized for the larger. */
#define BVH_AREA_BYTES 8u

static uint64_t align8(uint64_t x) { return (x + 7u) & ~(uint64_t)7u; }

static lt_status_t bvh_layout(uint32_t n, const lt_bvh_desc_t *d, bvh_layout_t *L)
{
    uint64_t off;
    L->bins = d != NULL && d->bins != 0 ? d->bins : 16u;
    L->max_leaf = d != NULL && d->max_leaf != 0 ? d->max_leaf : 4u;
    L->min_leaf = d != NULL && d->min_leaf != 0 ? d->min_leaf : 1u;
    L->max_depth = d != NULL && d->max_depth != 0 ? d->max_depth : LT_BVH_MAX_DEPTH;
    L->flags = d != NULL ? d->flags : 0u;
    if (L->bins < 2u || L->bins > LT_BVH_MAX_BINS || L->max_leaf > LT_BVH_MAX_LEAF ||
        L->min_leaf > L->max_leaf || L->max_depth > LT_BVH_MAX_DEPTH ||
        (L->flags & ~LT_BVH_TIGHT) != 0)
        return LT_E_ARG;
    if (n > LT_BVH_MAX_TRIS)
        return LT_E_RANGE;
    L->nodes_off = L->idx_off = L->boxes_off = L->bins_off = 0;
    L->area_off = L->cnt_off = L->stack_off = L->total = 0;
    if (n == 0)
        return LT_OK;
    /* worst case 2n - 1 nodes + the unused slot 1 = 2n slots */
    off = (uint64_t)2u * n * 32u;
    L->idx_off = (size_t)off;
    off = align8(off + (uint64_t)n * 4u);
    L->boxes_off = (size_t)off;
    off += (uint64_t)n * 24u;
    L->bins_off = (size_t)off;
    off = align8(off + (uint64_t)3u * L->bins * BVH_BIN_BYTES);
    L->area_off = (size_t)off;
    off += (uint64_t)L->bins * BVH_AREA_BYTES;
    L->cnt_off = (size_t)off;
    off = align8(off + (uint64_t)L->bins * 4u);
    L->stack_off = (size_t)off;
    off += (uint64_t)(L->max_depth + 1u) * sizeof(bvh_stack_t);
    if (off > (uint64_t)SIZE_MAX)
        return LT_E_RANGE; /* 32-bit hosts: 64n + 36n bytes can exceed the address space */
    L->total = (size_t)off;
    return LT_OK;
}

/* Levels of halving until c triangles fit in leaves of max_leaf: the smallest d with
 * ceil(c / 2^d) <= max_leaf. The object-median split reaches it, so the builder accepts a split
 * only while the deeper child keeps depth + this <= max_depth. */
static uint32_t bvh_need_depth(uint32_t c, uint32_t max_leaf)
{
    uint32_t d = 0;
    while (c > max_leaf) {
        c -= c / 2u;
        d++;
    }
    return d;
}

lt_status_t lt_bvh_size(uint32_t ntris, const lt_bvh_desc_t *desc, size_t *bytes)
{
    bvh_layout_t L;
    lt_status_t st;
    if (bytes == NULL)
        return LT_E_ARG;
    st = bvh_layout(ntris, desc, &L);
    if (st != LT_OK)
        return st;
    *bytes = L.total;
    return LT_OK;
}

/* ---- fixed point: s15.16 boxes, integer SAH --------------------------------------------------- */

/* the raw vertex bound 2^(GEOM+16) must fit int32 with room for doubled centroids */
typedef char bvh_check_geom[LT_CFG_GEOM_MAX_LOG2 <= 14 ? 1 : -1];
/* Vertex bound the q16 builder accepts, raw: |x| <= 2^GEOM world units. Box sides are then
 * <= 2^(GEOM+17) raw = 2^29, and doubled centroids <= 2^29 in magnitude. */
#define GEOM_LIM_Q16 ((int32_t)1 << (LT_CFG_GEOM_MAX_LOG2 + 16))

/* Half surface area of a box in raw units^2 (32 fractional bits): sides < 2^30, so each product
 * < 2^60 and the sum of three < 2^62; exact. */
static uint64_t area_q16(const lt_aabb_q16_t *b)
{
    uint64_t wx = (uint64_t)((int64_t)b->hi[0] - b->lo[0]);
    uint64_t wy = (uint64_t)((int64_t)b->hi[1] - b->lo[1]);
    uint64_t wz = (uint64_t)((int64_t)b->hi[2] - b->lo[2]);
    return wx * wy + wy * wz + wz * wx;
}

/* Right shift that brings a node's area below 2^32: its children's areas (subsets) are then below
 * 2^32 too, and area x count < 2^59 for counts < 2^27, so a split cost (two such terms plus the
 * parent's) cannot overflow uint64. */
static unsigned shift_q16(uint64_t area)
{
    unsigned bits = 64u - lt__clz64(area);
    return bits > 32u ? bits - 32u : 0u;
}

/* Bin mapping without a division per triangle: k = floor(nb 2^32 / (ext + 1)), bin = off k >> 32
 * for off in [0, ext], which is < nb (off k < nb 2^32, no overflow: ext < 2^31). */
static uint64_t binsetup_q16(lt_q16_t cmin, lt_q16_t cmax, uint32_t nb)
{
    uint64_t ext = (uint64_t)((int64_t)cmax - cmin);
    return ((uint64_t)nb << 32) / (ext + 1u);
}

static uint32_t bin_q16(lt_q16_t c, lt_q16_t cmin, uint64_t k, uint32_t nb)
{
    uint64_t off = (uint64_t)((int64_t)c - cmin);
    uint32_t j = (uint32_t)((off * k) >> 32);
    return j < nb ? j : nb - 1u;
}

/* 1/d: 2^46 / d_raw half up, saturating; d == 0 gives +max (lt_ray16_q16_setup per lane). */
void lt_ray1_q16_setup(lt_ray1_q16_t *r)
{
    unsigned a, par = 0, rsat = 0;
    LT_CHARGE(BVH_RAY1_SETUP);
    for (a = 0; a < 3; a++) {
        if (r->d[a] == 0) {
            r->rd[a] = LT_Q16_MAX;
            par |= 1u << a;
        } else {
            int64_t q = lt__div_round64((int64_t)1 << 46, r->d[a]);
            LT_EVENT(SAT, q != (int64_t)lt__ssat32(q));
            r->rd[a] = lt__ssat32(q);
            if (r->rd[a] == LT_Q16_MAX || r->rd[a] == LT_Q16_MIN)
                rsat |= 1u << a;
        }
    }
    r->par = (uint8_t)par;
    r->rsat = (uint8_t)rsat;
    r->pad_[0] = r->pad_[1] = 0;
}

/* Exact path of one slab, as q_slab_fix in lt_isect.c: parallel (d == 0): all t inside the closed
 * slab, none outside; saturated 1/d: t = (plane - o) / d by division, half up, saturating. */
static void slab_fix1_q16(unsigned par, lt_q16_t o, lt_q30_t d, lt_q16_t lo, lt_q16_t hi,
                          lt_q16_t *t0, lt_q16_t *t1)
{
    if (par) {
        int in = o >= lo && o <= hi;
        LT_CHARGE(BVH_SLAB1_FIX);
        *t0 = in ? LT_Q16_MIN : LT_Q16_MAX;
        *t1 = LT_Q16_MAX;
    } else {
        int64_t p0 = (int64_t)lo - o, p1 = (int64_t)hi - o;
        LT_CHARGE(BVH_SLAB1_FIX_DIV);
        *t0 = lt__ssat32(lt__div_round64(p0 * ((int64_t)1 << 30), d));
        *t1 = lt__ssat32(lt__div_round64(p1 * ((int64_t)1 << 30), d));
    }
}

/* t = tnum / det for one ray: lt_tri.h's lane body, charged as a scalar division. */
static lt_q16_t s_tdiv(int64_t n, int64_t d)
{
    LT_CHARGE(BVH_TRI1_TDIV);
    return lt__tri_q16_tdiv1(n, d);
}

/* One plane of the wide node test: t[c] = (p[c] - o) x rd for the 8 children, lt_slab1's
 * operations (the x86 lane backend's sequence on x86 hosts, lt_v16_x86.h). */
static void w_plane8_q16(const lt_q16_t *p, lt_q16_t o, lt_q16_t rd, lt_q16_t *t)
{
#if LT__X86_LANES
    lt__x86_plane8_q16(p, o, rd, t);
#else
    unsigned c;
    for (c = 0; c < LT_BVH8_WIDTH; c++)
        t[c] = lt__q16_mul_sat(lt__q16_sub_sat(p[c], o), rd);
#endif
}

#include "numerics/lt_traits_q16.h"
/* an intersector the structure's path takes (LT_ISECT_WT32: s15.16 only) */
#define LTB_ISECT_OK(v) LT_ISECT_VALID((v), LTB_NUM == LT_BVH_NUM_Q16)
#define LTB_NUM LT_BVH_NUM_Q16
#define LTB_NODE lt_bvh_node_q16_t
#define LTB_AREA_T uint64_t
#define LTB_AREA area_q16
#define LTB_SHIFT shift_q16
#define LTB_COST_T uint64_t
#define LTB_COST(a, s, n) (((a) >> (s)) * (uint64_t)(n))
#define LTB_BINSCALE_T uint64_t
#define LTB_BIN_SETUP binsetup_q16
#define LTB_BIN bin_q16
/* doubled centroid lo + hi: |sum| <= 2^29 for vertices inside GEOM_LIM_Q16 */
#define LTB_CENT(b, a) ((b)->lo[a] + (b)->hi[a])
#define LTB_IN_RANGE(x) ((x) >= -GEOM_LIM_Q16 && (x) <= GEOM_LIM_Q16)
#define LTB_PAD_VALUE(b) ((void)(b), LT_BVH_PAD_Q16)
#define LTB_TMIN_INF LT_Q16_MIN
#define LTN_RAY1 lt_ray1_q16_t
#define LTS_MULR lt__q16_mul_sat
#define LTS_SLAB_FIX slab_fix1_q16
#define LTS_W int64_t
#define LTS_TN int64_t
#define LTS_TRI_CAND lt__tri_q16_cand1
#define LTS_TDIV s_tdiv
#include "lt_bvh.inc"
#define LTW_NODE lt_bvh8_node_q16_t
#define LTW_BLOCK lt_bvh8_tris4_q16_t
#define LTW_ZERO_AREA lt__wt_zero_area_q16
#define LTW_TRIS4 lt__wt_tris4_q16
#define LTW_MERGE 0u
#define LTW_NODE_RECIPE BVH8_NODE_Q16
#define LTW_PLANE8 w_plane8_q16
#if LT__X86_LANES && LT_COST_MODE != LT_COST_SIM
#define LTW_TEST8(r, n, tn, nc)                                                                    \
    lt__x86_wtest8_q16(&(n)->lo[0][0], &(n)->hi[0][0], (n)->cnt, (r)->o, (r)->rd, (r)->tmin,       \
                       (r)->tmax, LT_BVH8_EMPTY, (tn), (nc))
#define LTW_TEST16(f, n, tmin, tmax, tn)                                                           \
    lt__x86_wtest16_q16(&(n)->lo[0][0], &(n)->hi[0][0], (n)->cnt, (f)->olo, (f)->ohi, (f)->rlo,    \
                        (f)->rhi, (int)(f)->same_o, (f)->free, (tmin), (tmax), LT_BVH8_EMPTY, (tn))
#endif
/* the largest |plane| in use, and whether a ray's |origin| + that fits int32 (plane - o exact) */
#define LTW_SPAN(x) ((x) < 0 ? 0u - (uint32_t)(x) : (uint32_t)(x))
#define LTW_NOCLAMP(w, r)                                                                          \
    ((uint64_t)(w)->span + LTW_SPAN((r)->o[0]) <= (uint64_t)INT32_MAX &&                           \
     (uint64_t)(w)->span + LTW_SPAN((r)->o[1]) <= (uint64_t)INT32_MAX &&                           \
     (uint64_t)(w)->span + LTW_SPAN((r)->o[2]) <= (uint64_t)INT32_MAX)
#include "lt_bvh8.inc"
#undef LTW_NODE
#undef LTW_BLOCK
#undef LTW_ZERO_AREA
#undef LTW_TRIS4
#undef LTW_MERGE
#undef LTW_NODE_RECIPE
#undef LTW_PLANE8
#undef LTW_TEST8
#undef LTW_TEST16
#undef LTW_SPAN
#undef LTW_NOCLAMP
/* named compile-time checks (LT_STATIC_ASSERT names its typedef by __LINE__, which could meet a
 * header's line in this translation unit) */
typedef char bvh_check_bin_q16[sizeof(lt__bvh_bin_t_q16) == BVH_BIN_BYTES ? 1 : -1];
typedef char bvh_check_area_q16[sizeof(uint64_t) <= BVH_AREA_BYTES ? 1 : -1];
#include "numerics/lt_traits_undef.h"
#undef LTB_NUM
#undef LTB_NODE
#undef LTB_AREA_T
#undef LTB_AREA
#undef LTB_SHIFT
#undef LTB_COST_T
#undef LTB_COST
#undef LTB_BINSCALE_T
#undef LTB_BIN_SETUP
#undef LTB_BIN
#undef LTB_CENT
#undef LTB_IN_RANGE
#undef LTB_PAD_VALUE
#undef LTB_TMIN_INF
#undef LTN_RAY1
#undef LTS_MULR
#undef LTS_SLAB_FIX
#undef LTS_W
#undef LTS_TN
#undef LTS_TRI_CAND
#undef LTS_TDIV

/* ---- float32 ---------------------------------------------------------------------------------- */
#if LT_CFG_FLOAT32

#define F32_MAX 3.40282347e38f
/* Coordinates the f32 builder accepts: |x| <= 2^48, so a half-area (< 3 x 2^98) times a count
 * (< 2^27) stays finite; NaN fails the test. */
#define F32_LIM 0x1p48f

static float area_f32(const lt_aabb_f32_t *b)
{
    float wx = b->hi[0] - b->lo[0], wy = b->hi[1] - b->lo[1], wz = b->hi[2] - b->lo[2];
    return wx * wy + wy * wz + wz * wx;
}

static float binsetup_f32(float cmin, float cmax, uint32_t nb)
{
    return (float)nb / (cmax - cmin);
}

/* A denormal extent makes k infinite and 0 x inf NaN: converting either to an integer is undefined
 * behaviour, so anything not below nb (including NaN) goes to the last bin. The binning and the
 * partition use this same mapping, so they always agree; a node whose triangles all land in one
 * bin falls back to the object median. */
static uint32_t bin_f32(float c, float cmin, float k, uint32_t nb)
{
    float f = (c - cmin) * k; /* >= 0 or NaN: c >= cmin */
    return f < (float)nb ? (uint32_t)f : nb - 1u;
}

/* Pad of every f32 box: 2^-18 of the largest |coordinate| of the root box (an exact scaling). */
static float pad_f32(const lt_aabb_f32_t *b)
{
    float m = 0.0f;
    unsigned a;
    for (a = 0; a < 3; a++) {
        m = lt__f32_max(m, lt__f32_abs(b->lo[a]));
        m = lt__f32_max(m, lt__f32_abs(b->hi[a]));
    }
    return m * 0x1p-18f;
}

/* 1/d clamped to +-FLT_MAX, as lt_ray16_f32_setup per lane (d == -0 gives -FLT_MAX). */
void lt_ray1_f32_setup(lt_ray1_f32_t *r)
{
    unsigned a, par = 0;
    /* scalar float work is charged to the scalar classes: lt_ops.def has no scalar-float class,
     * and the F* classes are 16-lane ops */
    LT_CHARGE(BVH_RAY1_SETUP);
    for (a = 0; a < 3; a++) {
        float q = 1.0f / r->d[a];
        if (q > F32_MAX)
            q = F32_MAX;
        else if (q < -F32_MAX)
            q = -F32_MAX;
        r->rd[a] = q;
        if (r->d[a] == 0.0f)
            par |= 1u << a;
    }
    r->par = (uint8_t)par;
    r->rsat = 0;
    r->pad_[0] = r->pad_[1] = 0;
}

static void w_plane8_f32(const float *p, float o, float rd, float *t)
{
    unsigned c;
    for (c = 0; c < LT_BVH8_WIDTH; c++)
        t[c] = (p[c] - o) * rd;
}

static void slab_fix1_f32(unsigned par, float o, float d, float lo, float hi, float *t0, float *t1)
{
    (void)par; /* only parallel axes are flagged in float32 */
    (void)d;
    LT_CHARGE(BVH_SLAB1_FIX);
    *t0 = o >= lo && o <= hi ? -F32_MAX : F32_MAX;
    *t1 = F32_MAX;
}

#include "numerics/lt_traits_f32.h"
#define LTB_NUM LT_BVH_NUM_F32
#define LTB_NODE lt_bvh_node_f32_t
#define LTB_AREA_T float
#define LTB_AREA area_f32
#define LTB_SHIFT(a) ((void)(a), 0u)
#define LTB_COST_T float
#define LTB_COST(a, s, n) ((void)(s), (a) * (float)(n))
#define LTB_BINSCALE_T float
#define LTB_BIN_SETUP binsetup_f32
#define LTB_BIN bin_f32
#define LTB_CENT(b, a) ((b)->lo[a] + (b)->hi[a])
#define LTB_IN_RANGE(x) ((x) >= -F32_LIM && (x) <= F32_LIM)
#define LTB_PAD_VALUE pad_f32
#define LTB_TMIN_INF (-F32_MAX)
#define LTN_RAY1 lt_ray1_f32_t
#define LTS_MULR lt__f32_mul
#define LTS_SLAB_FIX slab_fix1_f32
#define LTS_W float
#define LTS_TN float
#define LTS_TRI_CAND lt__tri_f32_cand1
#define LTS_TDIV(n, d) ((n) / (d))
#include "lt_bvh.inc"
#define LTW_NODE lt_bvh8_node_f32_t
#define LTW_BLOCK lt_bvh8_tris4_f32_t
#define LTW_ZERO_AREA lt__wt_zero_area_f32
#define LTW_TRIS4 lt__wt_tris4_f32
#define LTW_MERGE LT_BVH8_MERGE
#define LTW_NODE_RECIPE BVH8_NODE_F32
#define LTW_PLANE8 w_plane8_f32
#if LT__X86_LANES && LT_COST_MODE != LT_COST_SIM
#define LTW_TEST8(r, n, tn, nc)                                                                    \
    lt__x86_wtest8_f32(&(n)->lo[0][0], &(n)->hi[0][0], (n)->cnt, (r)->o, (r)->rd, (r)->tmin,       \
                       (r)->tmax, LT_BVH8_EMPTY, (tn))
#define LTW_TEST16(f, n, tmin, tmax, tn)                                                           \
    lt__x86_wtest16_f32(&(n)->lo[0][0], &(n)->hi[0][0], (n)->cnt, (f)->olo, (f)->ohi, (f)->rlo,    \
                        (f)->rhi, (int)(f)->same_o, (f)->free, (tmin), (tmax), LT_BVH8_EMPTY, (tn))
#endif
#include "lt_bvh8.inc"
#undef LTW_NODE
#undef LTW_BLOCK
#undef LTW_ZERO_AREA
#undef LTW_TRIS4
#undef LTW_MERGE
#undef LTW_NODE_RECIPE
#undef LTW_PLANE8
#undef LTW_TEST8
#undef LTW_TEST16
#undef LTW_SPAN
#undef LTW_NOCLAMP
typedef char bvh_check_bin_f32[sizeof(lt__bvh_bin_t_f32) == BVH_BIN_BYTES ? 1 : -1];

#endif /* LT_CFG_FLOAT32 */

/* ---- quantised 16-byte nodes (s15.16 only) ----------------------------------------------------- */

/* One frame: a node's decoded box and the per-axis step exponents of its children's boxes. */
typedef struct bvhq_frame {
    lt_aabb_q16_t b; /* decoded box, s15.16 */
    uint32_t node;   /* node index */
} bvhq_frame_t;

/* Smallest e >= 0 with ceil(ext / 2^e) <= 65535 for ext = hi - lo >= 0: ext < 2^bits gives
 * ceil(ext / 2^(bits - 16)) <= 2^16, one more step when that is exactly 65536. */
static unsigned q_exp(lt_q16_t lo, lt_q16_t hi)
{
    uint64_t ext = (uint64_t)((int64_t)hi - lo);
    unsigned bits = 64u - lt__clz64(ext), e = bits > 16u ? bits - 16u : 0u;
    if (((ext + ((uint64_t)1 << e) - 1u) >> e) > 65535u)
        e++;
    return e;
}

/* Decode a child record in frame f with exponents e (saturating: never within the geometry bound). */
static void q_decode(const lt_aabb_q16_t *f, const unsigned e[3], const lt_bvhq_node_t *n,
                     lt_aabb_q16_t *out)
{
    unsigned a;
    LT_MEM(n, 12, LT_MEM_READ);
    LT_CHARGE(BVHQ_DECODE);
    for (a = 0; a < 3; a++) {
        out->lo[a] = lt__ssat32((int64_t)f->lo[a] + (int64_t)((uint64_t)n->qlo[a] << e[a]));
        out->hi[a] = lt__ssat32((int64_t)f->lo[a] + (int64_t)((uint64_t)n->qhi[a] << e[a]));
    }
}

static void q_frame_exps(const lt_aabb_q16_t *f, unsigned e[3])
{
    unsigned a;
    LT_CHARGE(BVHQ_FRAME_EXPS);
    for (a = 0; a < 3; a++)
        e[a] = q_exp(f->lo[a], f->hi[a]);
}

/* Scratch of the quantiser: the explicit stack behind the node array. */
#define BVHQ_STACK (LT_BVH_MAX_DEPTH + 1u)

static lt_status_t bvhq_check(const lt_bvh_t *src)
{
    if (src == NULL || src->num != LT_BVH_NUM_Q16 || (src->nnodes != 0 && src->nodes == NULL))
        return LT_E_ARG;
    return LT_OK;
}

lt_status_t lt_bvhq_size(const lt_bvh_t *src, size_t *bytes)
{
    if (bytes == NULL || bvhq_check(src) != LT_OK)
        return LT_E_ARG;
    *bytes = src->nnodes == 0 ? 0u
                              : (size_t)src->nnodes * sizeof(lt_bvhq_node_t) +
                                    BVHQ_STACK * sizeof(bvhq_frame_t);
    return LT_OK;
}

lt_status_t lt_bvhq_build_q16(lt_bvhq_t *out, const lt_bvh_t *src, void *mem, size_t bytes)
{
    const lt_bvh_node_q16_t *sn;
    lt_bvhq_node_t *qn;
    bvhq_frame_t *stk;
    size_t need;
    unsigned sp;
    lt_phase_t prev;

    if (out == NULL || lt_bvhq_size(src, &need) != LT_OK)
        return LT_E_ARG;
    out->nodes = NULL;
    out->idx = src->idx;
    out->nnodes = out->ntris = 0;
    out->bytes = 0;
    out->stats = NULL;
    out->isect = src->isect;
    out->pad_ = 0;
    lt__memset(&out->root, 0, sizeof out->root);
    if (src->nnodes == 0)
        return LT_OK;
    if (mem == NULL || ((uintptr_t)mem & 3u) != 0)
        return LT_E_ARG;
    if (bytes < need) {
        out->bytes = need;
        return LT_E_SPACE;
    }
    prev = LT_PHASE_ENTER(BUILD);
    sn = (const lt_bvh_node_q16_t *)src->nodes;
    qn = (lt_bvhq_node_t *)mem;
    stk = (bvhq_frame_t *)(void *)((unsigned char *)mem + (size_t)src->nnodes * sizeof *qn);
    lt__memset(qn, 0, (size_t)src->nnodes * sizeof *qn); /* slot 1 and node 0's q fields */
    stk[0].b = sn[0].b;
    stk[0].node = 0;
    sp = 1;
    /* top-down: a node's children are quantised in its decoded frame, which the traversal rebuilds
     * the same way, so builder and traversal agree on every decoded box bit for bit */
    while (sp > 0) {
        bvhq_frame_t f = stk[--sp];
        const lt_bvh_node_q16_t *n = &sn[f.node];
        unsigned e[3], c;
        LT_MEM(n, sizeof *n, LT_MEM_READ);
        LT_CHARGE(BVHQ_BUILD_NODE);
        if (LT_BVH_IS_LEAF(n)) {
            if (n->count > LT_BVHQ_MAX_LEAF) {
                LT_PHASE_LEAVE(prev);
                return LT_E_RANGE;
            }
            qn[f.node].link = (n->count << 28) | n->left_first;
            continue;
        }
        qn[f.node].link = n->left_first;
        if (sp + 2u > BVHQ_STACK) {
            LT_PHASE_LEAVE(prev);
            return LT_E_DEPTH; /* a foreign tree deeper than LT_BVH_MAX_DEPTH */
        }
        q_frame_exps(&f.b, e);
        for (c = 0; c < 2; c++) {
            uint32_t ci = n->left_first + c;
            const lt_aabb_q16_t *cb = &sn[ci].b;
            lt_bvhq_node_t *q = &qn[ci];
            unsigned a;
            for (a = 0; a < 3; a++) {
                /* the child lies inside the parent's exact box, which lies inside its decoded
                 * frame, so both offsets are >= 0 and round into 0..65535 */
                uint64_t lo = (uint64_t)((int64_t)cb->lo[a] - f.b.lo[a]);
                uint64_t hi = (uint64_t)((int64_t)cb->hi[a] - f.b.lo[a]);
                uint64_t ql = lo >> e[a], qh = (hi + ((uint64_t)1 << e[a]) - 1u) >> e[a];
                LT_ASSERT(cb->lo[a] >= f.b.lo[a] && qh <= 65535u);
                q->qlo[a] = (uint16_t)(ql > 65535u ? 65535u : ql);
                q->qhi[a] = (uint16_t)(qh > 65535u ? 65535u : qh);
            }
            q_decode(&f.b, e, q, &stk[sp].b);
            stk[sp].node = ci;
            sp++;
        }
    }
    out->nodes = qn;
    out->root = sn[0].b;
    out->nnodes = src->nnodes;
    out->ntris = src->ntris;
    out->bytes = (size_t)src->nnodes * sizeof *qn;
    LT_PHASE_LEAVE(prev);
    return LT_OK;
}

/* Packet traversal of the quantised tree: trav16 of lt_bvh.inc with the frame on the stack. */
typedef struct bvhq_ent16 {
    lt_aabb_q16_t b; /* decoded box of the node: its children's frame */
    uint32_t node;   /* node index */
    lt_mask16_t m;   /* lanes that entered its box */
    uint16_t pad_;   /* private */
    lt_q16_t tn;     /* min tnear over those lanes */
} bvhq_ent16_t;

static lt_status_t bvhq_trav16(const lt_bvhq_t *bvh, const lt_tri_q16_t *tris, lt_ray16_q16_t *r,
                               lt_mask16_t k, lt_hit16_t *hit, int any, lt_mask16_t *occl)
{
    bvhq_ent16_t stk[LT_BVH_MAX_DEPTH];
    const lt_bvhq_node_t *nodes = bvh->nodes;
    lt_bvh_stats_t *stats = bvh->stats;
    lt_status_t rc = LT_OK;
    unsigned sp = 0, maxsp = 0;
    uint32_t ni = 0;
    lt_mask16_t m, done = 0;
    lt_vq16_t tl, tr;
    lt_aabb_q16_t cur = bvh->root;
    lt_phase_t prev;
    lt__isel16_q16 isel;

    lt__isel16_init_q16(&isel, bvh->isect);
    hit->id = lt_vi32_set1(-1);
    if (stats != NULL) {
        stats->calls++;
        stats->rays += lt__popcount32(k);
    }
    if (bvh->nnodes == 0 || k == 0) {
        *occl = 0;
        return LT_OK;
    }
    prev = LT_PHASE_ENTER(TRAVERSE);
    tl = lt_vq16_set1(0);
    tr = lt_vq16_set1(0);
    m = lt_slab16_q16(r, k, &cur, &tl);
    if (stats != NULL)
        stats->boxes++;
    while (m != 0) {
        uint32_t link = nodes[ni].link;
        LT_EVENT(NODES, 1);
        LT_MEM(&nodes[ni].link, sizeof link, LT_MEM_READ);
        LT_CHARGE(BVH_TRAV_NODE1);
        if (stats != NULL) {
            stats->nodes++;
            stats->node_lanes += lt__popcount32(m);
        }
        if (LT_BVHQ_COUNT(link) != 0) {
            uint32_t i, first = LT_BVHQ_INDEX(link), end = first + LT_BVHQ_COUNT(link);
            LT_ASSERT(end <= bvh->ntris);
            (void)LT_PHASE_ENTER(INTERSECT);
            for (i = first; i < end; i++) {
                uint32_t id;
                lt_mask16_t got;
                LT_MEM(&bvh->idx[i], sizeof bvh->idx[i], LT_MEM_READ);
                LT_CHARGE(BVH_TRAV_LEAF_TRI);
                id = bvh->idx[i];
                if (stats != NULL) {
                    stats->tris++;
                    stats->tri_lanes += lt__popcount32(m);
                }
                got = lt__isel16_tri_q16(&isel, r, m, &tris[id], (int32_t)id, hit);
                if (any) {
                    done = (lt_mask16_t)(done | got);
                    m = (lt_mask16_t)(m & ~got);
                    LT_CHARGE(BVH_TRAV_ANY_RETIRE);
                    if (m == 0)
                        break;
                }
            }
            (void)LT_PHASE_ENTER(TRAVERSE);
            LT_CHARGE(BVH_TRAV_ANY_EXIT);
            if (any && (k & ~done) == 0)
                break;
        } else {
            uint32_t l = LT_BVHQ_INDEX(link);
            unsigned e[3];
            lt_aabb_q16_t bl, br;
            lt_mask16_t ml, mr;
            LT_ASSERT(l + 1u < bvh->nnodes);
            q_frame_exps(&cur, e);
            q_decode(&cur, e, &nodes[l], &bl);
            q_decode(&cur, e, &nodes[l + 1u], &br);
            ml = lt_slab16_q16(r, m, &bl, &tl);
            mr = lt_slab16_q16(r, m, &br, &tr);
            if (stats != NULL)
                stats->boxes += 2;
            LT_CHARGE(BVH_TRAV_CHILDREN16);
            if (ml != 0 && mr != 0) {
                lt_q16_t nl = lt_vq16_hmin(ml, tl, LT_Q16_MAX), nr = lt_vq16_hmin(mr, tr, LT_Q16_MAX);
                int lfirst = nl <= nr;
                if (sp < LT_BVH_MAX_DEPTH) {
                    stk[sp].node = lfirst ? l + 1u : l;
                    stk[sp].b = lfirst ? br : bl;
                    stk[sp].m = lfirst ? mr : ml;
                    stk[sp].pad_ = 0;
                    stk[sp].tn = lfirst ? nr : nl;
                    sp++;
                    maxsp = sp > maxsp ? sp : maxsp;
                    LT_CHARGE(BVHQ_TRAV16_PUSH);
                } else {
                    rc = LT_E_DEPTH;
                    if (stats != NULL)
                        stats->overflows++;
                }
                ni = lfirst ? l : l + 1u;
                cur = lfirst ? bl : br;
                m = lfirst ? ml : mr;
                continue;
            }
            if (ml != 0 || mr != 0) {
                ni = ml != 0 ? l : l + 1u;
                cur = ml != 0 ? bl : br;
                m = ml != 0 ? ml : mr;
                continue;
            }
        }
        m = 0;
        while (sp > 0) {
            sp--;
            LT_CHARGE(BVH_TRAV16_POP);
            m = (lt_mask16_t)(stk[sp].m & ~done);
            if (m != 0 && stk[sp].tn <= lt_vq16_hmax(m, r->tmax, LT_Q16_MIN)) {
                ni = stk[sp].node;
                cur = stk[sp].b;
                LT_CHARGE(BVHQ_TRAV16_POP_BOX);
                break;
            }
            m = 0;
        }
    }
    if (stats != NULL && maxsp > stats->max_stack)
        stats->max_stack = maxsp;
    *occl = done;
    LT_PHASE_LEAVE(prev);
    return rc;
}

lt_status_t lt_bvhq_trace16_q16(const lt_bvhq_t *bvh, const lt_tri_q16_t *tris, lt_ray16_q16_t *r,
                                lt_mask16_t k, lt_hit16_t *hit)
{
    lt_mask16_t unused;
    if (bvh == NULL || r == NULL || hit == NULL || !LT_ISECT_VALID(bvh->isect, 1) ||
        (tris == NULL && bvh->nnodes != 0))
        return LT_E_ARG;
    return bvhq_trav16(bvh, tris, r, k, hit, 0, &unused);
}

lt_status_t lt_bvhq_occluded16_q16(const lt_bvhq_t *bvh, const lt_tri_q16_t *tris,
                                   lt_ray16_q16_t *r, lt_mask16_t k, lt_mask16_t *occluded)
{
    lt_hit16_t h;
    if (bvh == NULL || r == NULL || occluded == NULL || !LT_ISECT_VALID(bvh->isect, 1) ||
        (tris == NULL && bvh->nnodes != 0))
        return LT_E_ARG;
    return bvhq_trav16(bvh, tris, r, k, &h, 1, occluded);
}

typedef struct bvhq_ent1 {
    lt_aabb_q16_t b; /* decoded box of the node */
    uint32_t node;   /* node index */
    lt_q16_t tn;     /* tnear of the ray at its box */
} bvhq_ent1_t;

lt_status_t lt_bvhq_trace1_q16(const lt_bvhq_t *bvh, const lt_tri_q16_t *tris, lt_ray1_q16_t *r,
                               int32_t *id)
{
    bvhq_ent1_t stk[LT_BVH_MAX_DEPTH];
    const lt_bvhq_node_t *nodes;
    lt_bvh_stats_t *stats;
    lt_status_t rc = LT_OK;
    unsigned sp = 0, maxsp = 0;
    uint32_t ni = 0;
    int live;
    lt_q16_t tl = 0, tr = 0;
    lt_aabb_q16_t cur;
    lt_phase_t prev;
    lt__isel1_q16 isel;

    if (bvh == NULL || r == NULL || id == NULL || !LT_ISECT_VALID(bvh->isect, 1) ||
        (tris == NULL && bvh->nnodes != 0))
        return LT_E_ARG;
    lt__isel1_init_q16(&isel, bvh->isect);
    nodes = bvh->nodes;
    stats = bvh->stats;
    cur = bvh->root;
    *id = -1;
    if (stats != NULL) {
        stats->calls++;
        stats->rays++;
    }
    if (bvh->nnodes == 0)
        return LT_OK;
    prev = LT_PHASE_ENTER(TRAVERSE);
    live = lt_slab1_q16(r, &cur, &tl);
    if (stats != NULL)
        stats->boxes++;
    while (live) {
        uint32_t link = nodes[ni].link;
        LT_EVENT(NODES, 1);
        LT_MEM(&nodes[ni].link, sizeof link, LT_MEM_READ);
        LT_CHARGE(BVH_TRAV_NODE1);
        if (stats != NULL) {
            stats->nodes++;
            stats->node_lanes++;
        }
        if (LT_BVHQ_COUNT(link) != 0) {
            uint32_t i, first = LT_BVHQ_INDEX(link), end = first + LT_BVHQ_COUNT(link);
            LT_ASSERT(end <= bvh->ntris);
            (void)LT_PHASE_ENTER(INTERSECT);
            for (i = first; i < end; i++) {
                uint32_t t;
                LT_MEM(&bvh->idx[i], sizeof bvh->idx[i], LT_MEM_READ);
                LT_CHARGE(BVH_TRAV_LEAF_TRI);
                t = bvh->idx[i];
                if (stats != NULL) {
                    stats->tris++;
                    stats->tri_lanes++;
                }
                if (lt__isel1_tri_q16(&isel, r, &tris[t]))
                    *id = (int32_t)t;
            }
            (void)LT_PHASE_ENTER(TRAVERSE);
        } else {
            uint32_t l = LT_BVHQ_INDEX(link);
            unsigned e[3];
            lt_aabb_q16_t bl, br;
            int hl, hr;
            LT_ASSERT(l + 1u < bvh->nnodes);
            q_frame_exps(&cur, e);
            q_decode(&cur, e, &nodes[l], &bl);
            q_decode(&cur, e, &nodes[l + 1u], &br);
            hl = lt_slab1_q16(r, &bl, &tl);
            hr = lt_slab1_q16(r, &br, &tr);
            if (stats != NULL)
                stats->boxes += 2;
            LT_CHARGE(BVH_TRAV1_CHILDREN);
            if (hl && hr) {
                int lfirst = tl <= tr;
                if (sp < LT_BVH_MAX_DEPTH) {
                    stk[sp].node = lfirst ? l + 1u : l;
                    stk[sp].b = lfirst ? br : bl;
                    stk[sp].tn = lfirst ? tr : tl;
                    sp++;
                    maxsp = sp > maxsp ? sp : maxsp;
                    LT_CHARGE(BVHQ_TRAV1_PUSH);
                } else {
                    rc = LT_E_DEPTH;
                    if (stats != NULL)
                        stats->overflows++;
                }
                ni = lfirst ? l : l + 1u;
                cur = lfirst ? bl : br;
                continue;
            }
            if (hl || hr) {
                ni = hl ? l : l + 1u;
                cur = hl ? bl : br;
                continue;
            }
        }
        live = 0;
        while (sp > 0) {
            sp--;
            LT_CHARGE(BVH_TRAV1_POP);
            if (stk[sp].tn <= r->tmax) {
                ni = stk[sp].node;
                cur = stk[sp].b;
                live = 1;
                break;
            }
        }
    }
    if (stats != NULL && maxsp > stats->max_stack)
        stats->max_stack = maxsp;
    LT_PHASE_LEAVE(prev);
    return rc;
}

/* ---- wide nodes for single rays (lt_bvh8.h) ------------------------------------------------------ */

/* Wide nodes of a binary tree of either path (each path's collapse counts its own tree). */
lt_status_t lt_bvh8_size_merge(const lt_bvh_t *bvh, uint32_t merge, size_t *bytes)
{
    uint32_t nodes, blocks = 0;
    if (bvh == NULL || bytes == NULL || merge > LT_BVH8_MERGE)
        return LT_E_ARG;
    if (bvh->nnodes == 0) {
        *bytes = 0;
        return LT_OK;
    }
#if LT_CFG_FLOAT32
    if (bvh->num == LT_BVH_NUM_F32) {
        nodes = w_count_f32((const lt_bvh_node_f32_t *)bvh->nodes, 0, merge, &blocks);
        *bytes = (size_t)nodes * sizeof(lt_bvh8_node_f32_t) +
                 (size_t)blocks * sizeof(lt_bvh8_tris4_f32_t);
        return LT_OK;
    }
#endif
    if (bvh->num != LT_BVH_NUM_Q16)
        return LT_E_ARG;
    nodes = w_count_q16((const lt_bvh_node_q16_t *)bvh->nodes, 0, merge, &blocks);
    *bytes = (size_t)nodes * sizeof(lt_bvh8_node_q16_t) +
             (size_t)blocks * sizeof(lt_bvh8_tris4_q16_t);
    return LT_OK;
}

lt_status_t lt_bvh8_size(const lt_bvh_t *bvh, size_t *bytes)
{
    if (bvh == NULL)
        return LT_E_ARG;
    return lt_bvh8_size_merge(bvh, lt_bvh8_merge_default(bvh->num), bytes);
}
