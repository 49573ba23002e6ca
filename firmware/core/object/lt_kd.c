/* lt_kd.c - instantiates the kd-tree kernels of lt_kd.inc for s15.16 and float32 and holds what is
 * path independent: parameters, the memory budget behind lt_kd_size, and the integer SAH cost.
 * The LTN_KD_* traits below are the only place the two numeric paths differ.
 * Builds: all; float32 only with LT_CFG_FLOAT32.
 */
#include "lt/lt_kd.h"
#include "lt_isel.h"

/* Bytes of one pending-node record of the build (6 coordinates + 6 words), the same in both paths. */
#define KD_JOB_BYTES 48u

/* SAH areas are computed from node extents quantised to KD_UNITS steps along the node's longest
 * axis, so that a half area (<= 3 * 2^20) times a reference count (< 2^24) times a cost (< 2^8),
 * two such terms and the empty bonus (<= 2^8) stay below 2^64 in uint64 arithmetic. */
#define KD_UNITS 1024u

/* Everything the build derives from n and the parameters. */
typedef struct kd_cfg {
    uint32_t leaf_tris, max_depth, ct, ci, bonus;
    uint32_t rmax;      /* reference budget */
    uint32_t nodes_max; /* node budget: 2 * rmax - 1 (at most rmax leaves) */
    uint32_t cap;       /* words of the reference/scratch array: rmax + n */
    size_t bytes;       /* arena bytes: nodes, references and scratch, build stack */
} kd_cfg_t;

void lt_kd_params_default(lt_kd_params_t *p)
{
    p->leaf_tris = 2;
    p->max_depth = 0;
    p->cost_trav = 15;
    p->cost_isect = 20;
    p->empty_bonus_q8 = 205;
    p->ref_factor = 4;
}

static unsigned ilog2_u32(uint32_t x)
{
    return x == 0 ? 0u : 31u - lt__clz32(x);
}

/* Validate the parameters and compute the budgets. The arena holds, in this order:
 * nodes_max x 8 bytes of nodes; cap x 4 bytes where leaf references grow up from the bottom and
 * the pending reference lists of the depth-first build grow down from the top (the committed
 * references, leaves plus pending lists, never exceed rmax, and a list being split adds at most
 * one list of <= n entries, so rmax + n words always suffice); (max_depth + 2) x 48 bytes of
 * pending-node records. The budgets are shared out down the tree in proportion to reference
 * counts (lt_kd.inc), so no subtree can starve another. */
static lt_status_t kd_config(uint32_t n, const lt_kd_params_t *p, kd_cfg_t *c)
{
    lt_kd_params_t d;
    uint64_t r, bytes;
    if (p == NULL) {
        lt_kd_params_default(&d);
        p = &d;
    }
    if (n > LT_KD_MAX_TRIS)
        return LT_E_RANGE;
    if (p->leaf_tris < 1 || p->max_depth > LT_KD_MAX_DEPTH || p->cost_trav < 1 ||
        p->cost_trav > 255 || p->cost_isect < 1 || p->cost_isect > 255 || p->empty_bonus_q8 < 1 ||
        p->empty_bonus_q8 > 256 || p->ref_factor < 1 || p->ref_factor > 16)
        return LT_E_ARG;
    c->leaf_tris = p->leaf_tris;
    c->ct = p->cost_trav;
    c->ci = p->cost_isect;
    c->bonus = p->empty_bonus_q8;
    /* Havran's rule of thumb (Havran 2000 [Havran00]), 8 + 1.3 log2 n, with the log rounded down */
    c->max_depth = p->max_depth != 0 ? p->max_depth : 8u + (13u * ilog2_u32(n)) / 10u;
    if (c->max_depth > LT_KD_MAX_DEPTH)
        c->max_depth = LT_KD_MAX_DEPTH;
    r = (uint64_t)p->ref_factor * (n > 0 ? n : 1u);
    c->rmax = (uint32_t)r;
    c->nodes_max = (uint32_t)(2u * r - 1u);
    c->cap = (uint32_t)(r + n);
    bytes = (uint64_t)c->nodes_max * 8u + (uint64_t)c->cap * 4u +
            (uint64_t)(c->max_depth + 2u) * KD_JOB_BYTES;
    if (bytes > (uint64_t)SIZE_MAX)
        return LT_E_RANGE;
    c->bytes = (size_t)bytes;
    return LT_OK;
}

lt_status_t lt_kd_size(uint32_t n, const lt_kd_params_t *p, size_t *bytes)
{
    kd_cfg_t c;
    lt_status_t s;
    if (bytes == NULL)
        return LT_E_ARG;
    s = kd_config(n, p, &c);
    if (s == LT_OK)
        *bytes = c.bytes;
    return s;
}

/* Half surface area of a box of extents x, y, z (in KD_UNITS), <= 3 * 2^20. */
static uint64_t kd_area(uint32_t x, uint32_t y, uint32_t z)
{
    return (uint64_t)x * y + (uint64_t)y * z + (uint64_t)z * x;
}

/* Move count words of base from index `from` to index `to`; the ranges may overlap. */
static void kd_move(uint32_t *base, uint32_t from, uint32_t to, uint32_t count)
{
    uint32_t i;
    LT_MEM(&base[from], count * 4u, LT_MEM_READ);
    LT_MEM(&base[to], count * 4u, LT_MEM_WRITE);
    LT_CHARGE_N(KD_MOVE_REF, count);
    if (to > from) {
        for (i = count; i-- > 0;)
            base[to + i] = base[from + i];
    } else {
        for (i = 0; i < count; i++)
            base[to + i] = base[from + i];
    }
}

/* ---- s15.16 ------------------------------------------------------------------------------- */

/* delta (0 <= delta <= maxext, maxext > 0) in KD_UNITS steps of maxext, rounded down. */
static uint32_t q_kd_units(lt_q16_t delta, lt_q16_t maxext)
{
    return (uint32_t)(((int64_t)delta * KD_UNITS) / maxext);
}

/* Candidate plane j of LT_KD_BINS over [lo, lo + ext]: lo + floor(ext * j / BINS), exact. */
static lt_q16_t q_kd_plane(lt_q16_t lo, lt_q16_t ext, unsigned j)
{
    return lo + (lt_q16_t)(((int64_t)ext * j) / LT_KD_BINS);
}

/* First guess of the bin of x (clamped to 0..BINS); the caller corrects it against the planes. */
static unsigned q_kd_bin(lt_q16_t x, lt_q16_t lo, lt_q16_t ext)
{
    int64_t b;
    if (x <= lo)
        return 0;
    b = (((int64_t)x - lo) * LT_KD_BINS) / ext;
    return b > LT_KD_BINS ? LT_KD_BINS : (unsigned)b;
}

/* A vertex coordinate the triangle kernel accepts: |x| <= 2^LT_CFG_GEOM_MAX_LOG2 world units. */
static int q_kd_coord_ok(int64_t x)
{
    int64_t lim = (int64_t)1 << (LT_CFG_GEOM_MAX_LOG2 + 16);
    return x >= -lim && x <= lim;
}

/* Lane signs of an s1.30 direction component. Cost: VCMP x2. */
static void q_kd_signs(lt_vq30_t d, lt_mask16_t *pos, lt_mask16_t *neg)
{
    *pos = lt_vq30_cmpgt0(d);
    *neg = lt_vq30_cmplt0(d);
}

/* Lanes whose 1/d saturated: t = (plane - o) / d by a 64-bit division, s15.16 / s1.30 -> s15.16,
 * half up, saturating (as the slab test's exact path). Cost: VDIV x1. */
static void q_kd_tfix(lt_mask16_t fx, lt_vq16_t o, lt_vq30_t d, lt_vq16_t plane, lt_vq16_t *t)
{
    int i;
    LT_CHARGE(KD_Q_TFIX);
    LT_UTIL(fx);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(fx, i)) {
            int64_t num = ((int64_t)plane.l[i] - o.l[i]) * ((int64_t)1 << 30);
            t->l[i] = lt__ssat32(lt__div_round64(num, d.l[i]));
        }
    }
}

#include "numerics/lt_traits_q16.h"
#define LTN_DV lt_vq30_t
#define LTN_KD lt_kd_q16_t
#define LTN_KDNODE lt_kd_node_q16_t
#define LTN_KD_NEG_INF LT_Q16_MIN
#define LTN_KD_UNITS q_kd_units
#define LTN_KD_PLANE q_kd_plane
#define LTN_KD_BIN q_kd_bin
#define LTN_KD_TRIPT(v, e) ((int64_t)(v) + (e)) /* a vertex, exact (checked against the range) */
#define LTN_KD_COORD_OK q_kd_coord_ok
#define LTN_KD_SIGNS q_kd_signs
#define LTN_KD_TFIX q_kd_tfix
#include "lt_kd.inc"
LT_STATIC_ASSERT(sizeof(kd_job_q16) == KD_JOB_BYTES, "build record size is in the size query");
#include "numerics/lt_traits_undef.h"
#undef LTN_DV
#undef LTN_KD
#undef LTN_KDNODE
#undef LTN_KD_NEG_INF
#undef LTN_KD_UNITS
#undef LTN_KD_PLANE
#undef LTN_KD_BIN
#undef LTN_KD_TRIPT
#undef LTN_KD_COORD_OK
#undef LTN_KD_SIGNS
#undef LTN_KD_TFIX

/* ---- float32 ------------------------------------------------------------------------------- */
#if LT_CFG_FLOAT32

static uint32_t f_kd_units(float delta, float maxext)
{
    float u = delta / maxext * (float)KD_UNITS;
    if (!(u > 0.0f))
        return 0;
    return u >= (float)KD_UNITS ? KD_UNITS : (uint32_t)u;
}

/* lo + ext * j / BINS; j / BINS is exact (BINS is a power of two), so planes rise with j. */
static float f_kd_plane(float lo, float ext, unsigned j)
{
    return lo + ext * ((float)j / (float)LT_KD_BINS);
}

static unsigned f_kd_bin(float x, float lo, float ext)
{
    float b = (x - lo) / ext * (float)LT_KD_BINS;
    /* compare before converting: a float outside the int range converts with undefined behaviour */
    if (!(b > 0.0f))
        return 0;
    return b >= (float)LT_KD_BINS ? LT_KD_BINS : (unsigned)b;
}

/* Finite and |x| <= 1e30, so that extents and plane distances stay finite. */
static int f_kd_coord_ok(float x)
{
    return x >= -1e30f && x <= 1e30f;
}

/* d == -0 is neither: it is a parallel lane (par mask). Cost: FCMP x2. */
static void f_kd_signs(lt_vf32_t d, lt_mask16_t *pos, lt_mask16_t *neg)
{
    *pos = lt_vf32_cmpgt(d, lt_vf32_set1(0.0f));
    *neg = lt_vf32_cmplt(d, lt_vf32_set1(0.0f));
}

/* float32 rays never flag rsat (1/d is clamped to +-FLT_MAX and parallel lanes are handled by
 * the caller), so there is nothing to fix. */
static void f_kd_tfix(lt_mask16_t fx, lt_vf32_t o, lt_vf32_t d, lt_vf32_t plane, lt_vf32_t *t)
{
    (void)fx;
    (void)o;
    (void)d;
    (void)plane;
    (void)t;
}

#include "numerics/lt_traits_f32.h"
#define LTN_DV lt_vf32_t
#define LTN_KD lt_kd_f32_t
#define LTN_KDNODE lt_kd_node_f32_t
#define LTN_KD_NEG_INF (-3.40282347e38f)
#define LTN_KD_UNITS f_kd_units
#define LTN_KD_PLANE f_kd_plane
#define LTN_KD_BIN f_kd_bin
#define LTN_KD_TRIPT(v, e) ((v) + (e))
#define LTN_KD_COORD_OK f_kd_coord_ok
#define LTN_KD_SIGNS f_kd_signs
#define LTN_KD_TFIX f_kd_tfix
#include "lt_kd.inc"
LT_STATIC_ASSERT(sizeof(kd_job_f32) == KD_JOB_BYTES, "build record size is in the size query");

#endif /* LT_CFG_FLOAT32 */
