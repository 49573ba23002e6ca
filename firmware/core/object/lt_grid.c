/* lt_grid.c - instantiates the uniform-grid kernels of lt_grid.inc for s15.16 and float32. The
 * LTN_G_* traits below (cell sizes, cell boundaries, the cell of a coordinate) are the only place
 * the two numeric paths differ; the int32 lane helpers are path independent.
 * Builds: all; float32 only with LT_CFG_FLOAT32.
 */
#include "lt/lt_grid.h"
#include "lt_isel.h"
#include "lt/lt_kd.h"

void lt_grid_params_default(lt_grid_params_t *p)
{
    p->cells_per_tri_q4 = 48;
}

/* Cells along an axis of relative extent rel (/65536 of the largest) when the largest axis has m. */
static uint32_t g_res(uint32_t rel, uint32_t m)
{
    uint32_t r = (uint32_t)(((uint64_t)rel * m) >> 16);
    return r < 1u ? 1u : (r > LT_GRID_MAX_RES ? LT_GRID_MAX_RES : r);
}

/* Resolution: the largest m (cells along the longest axis) whose grid has <= target cells; the
 * cell count rises with m, so a bisection finds it. */
static void g_resolution(const uint32_t rel[3], uint64_t target, uint32_t res[3])
{
    uint32_t lo = 1, hi = LT_GRID_MAX_RES;
    unsigned a;
    while (lo < hi) {
        uint32_t m = (lo + hi + 1u) / 2u;
        uint64_t cells = (uint64_t)g_res(rel[0], m) * g_res(rel[1], m) * g_res(rel[2], m);
        LT_CHARGE(GRID_RES_STEP);
        if (cells <= target)
            lo = m;
        else
            hi = m - 1u;
    }
    for (a = 0; a < 3; a++)
        res[a] = g_res(rel[a], lo);
}

/* ---- int32 lane helpers (cell indices) ---------------------------------------------------- */

/* x + rx * (y + ry * z) per lane (indices < 2^30). Cost: VMUL x2, VALU x2. */
static lt_vi32_t g_lin(lt_vi32_t x, lt_vi32_t y, lt_vi32_t z, uint32_t rx, uint32_t ry)
{
    lt_vi32_t r;
    int i;
    LT_CHARGE(GRID_LIN);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = x.l[i] + (int32_t)rx * (y.l[i] + (int32_t)ry * z.l[i]);
    return r;
}

/* Lanes of k whose index lies outside [0, res). Cost: VCMP x2, MASK x1. */
static lt_mask16_t g_outside(lt_mask16_t k, lt_vi32_t c, uint32_t res)
{
    unsigned m = 0;
    int i;
    LT_CHARGE(GRID_OUTSIDE);
    for (i = 0; i < LT_LANES; i++)
        m |= (unsigned)(c.l[i] < 0 || c.l[i] >= (int32_t)res) << i;
    return (lt_mask16_t)(m & k);
}

/* The mailbox: direct-mapped slots of (triangle id, lanes that tested it), Fibonacci hashing. */
typedef struct g_mbox {
    uint32_t id;      /* triangle index, 0xFFFFFFFF = empty */
    lt_mask16_t mask; /* lanes that already tested it */
    uint16_t pad_;    /* 8 bytes */
} g_mbox_t;

LT_INLINE unsigned g_slot(uint32_t id)
{
    return (unsigned)((id * 2654435761u) >> 26); /* 64 slots: top 6 bits */
}
LT_STATIC_ASSERT(LT_GRID_MAILBOX == 64u, "g_slot takes the top 6 bits");

/* ---- s15.16 ------------------------------------------------------------------------------- */

/* ext (0 <= ext <= maxext, maxext > 0) relative to maxext in 1/65536 steps, rounded down. */
static uint32_t q_g_rel(lt_q16_t ext, lt_q16_t maxext)
{
    return (uint32_t)(((int64_t)ext * 65536) / maxext);
}

/* Cell size ceil(ext / res) in whole s15.16 steps, at least 1; the grid then ends at
 * lo + res * size >= hi, and every boundary lo + j * size is exact. */
static lt_q16_t q_g_cellsize(lt_q16_t lo, lt_q16_t hi, uint32_t res)
{
    int64_t e = (int64_t)hi - lo;
    int64_t c = (e + (int64_t)res - 1) / (int64_t)res;
    return c < 1 ? 1 : (lt_q16_t)c;
}

/* Boundary j of an axis: lo + j * size, exact (<= the grid's hi, inside the geometry range). */
static lt_q16_t q_g_bound(lt_q16_t lo, uint32_t j, lt_q16_t cs)
{
    return lt__ssat32((int64_t)lo + (int64_t)j * cs);
}

/* Cell of coordinate x: the largest j with boundary j <= x, clamped to [0, res). Exact. */
static uint32_t q_g_cell(lt_q16_t x, lt_q16_t lo, lt_q16_t cs, uint32_t res)
{
    int64_t c;
    if (x <= lo)
        return 0;
    c = ((int64_t)x - lo) / cs;
    return c >= (int64_t)res ? res - 1u : (uint32_t)c;
}

/* Per lane: boundary (c + off) of the axis. Cost: VMUL x1, VALU x1. */
static lt_vq16_t q_g_boundv(lt_vi32_t c, int32_t off, lt_q16_t lo, lt_q16_t cs)
{
    lt_vq16_t r;
    int i;
    LT_CHARGE(GRID_Q_BOUNDV);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = lt__ssat32((int64_t)lo + ((int64_t)c.l[i] + off) * cs);
    return r;
}

/* Per lane: the cell of coordinate p (as q_g_cell). Cost: VDIV x1, VALU x2. */
static lt_vi32_t q_g_cellv(lt_vq16_t p, lt_q16_t lo, lt_q16_t cs, uint32_t res)
{
    lt_vi32_t r;
    int i;
    LT_CHARGE(GRID_Q_CELLV);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = (int32_t)q_g_cell(p.l[i], lo, cs, res);
    return r;
}

/* o + t * d per lane: s15.16 + s15.16 x s1.30 (half up, saturating). Cost: VMUL x1, VALU x1. */
static lt_vq16_t q_g_pos(lt_vq16_t o, lt_vq16_t t, lt_vq30_t d)
{
    return lt_vq16_add_sat(o, lt_vq16_mul_q30_sat(t, d));
}

static int q_g_coord_ok(int64_t x)
{
    int64_t lim = (int64_t)1 << (LT_CFG_GEOM_MAX_LOG2 + 16);
    return x >= -lim && x <= lim;
}

/* Lane signs of an s1.30 direction component. Cost: VCMP x2. */
static void q_g_signs(lt_vq30_t d, lt_mask16_t *pos, lt_mask16_t *neg)
{
    *pos = lt_vq30_cmpgt0(d);
    *neg = lt_vq30_cmplt0(d);
}

#include "numerics/lt_traits_q16.h"
#define LTN_DV lt_vq30_t
#define LTN_GRID lt_grid_q16_t
#define LTN_G_TRIPT(v, e) ((int64_t)(v) + (e))
#define LTN_G_COORD_OK q_g_coord_ok
#define LTN_G_REL q_g_rel
#define LTN_G_CELLSIZE q_g_cellsize
#define LTN_G_BOUND q_g_bound
#define LTN_G_CELL q_g_cell
#define LTN_G_BOUNDV q_g_boundv
#define LTN_G_CELLV q_g_cellv
#define LTN_G_POS q_g_pos
#define LTN_G_SIGNS q_g_signs
#include "lt_grid.inc"
#include "numerics/lt_traits_undef.h"
#undef LTN_DV
#undef LTN_GRID
#undef LTN_G_TRIPT
#undef LTN_G_COORD_OK
#undef LTN_G_REL
#undef LTN_G_CELLSIZE
#undef LTN_G_BOUND
#undef LTN_G_CELL
#undef LTN_G_BOUNDV
#undef LTN_G_CELLV
#undef LTN_G_POS
#undef LTN_G_SIGNS

/* ---- float32 ------------------------------------------------------------------------------- */
#if LT_CFG_FLOAT32

static uint32_t f_g_rel(float ext, float maxext)
{
    float r = ext / maxext * 65536.0f;
    if (!(r > 0.0f))
        return 0;
    return r >= 65536.0f ? 65536u : (uint32_t)r;
}

static float f_abs(float x)
{
    return x < 0.0f ? -x : x;
}

/* Cell size ext / res, raised to at least 2^-20 of the larger bound magnitude (so consecutive
 * boundaries lo + j x size differ by many ulps) and then until the last boundary reaches hi. */
static float f_g_cellsize(float lo, float hi, uint32_t res)
{
    float big = f_abs(lo) > f_abs(hi) ? f_abs(lo) : f_abs(hi);
    float cs = (hi - lo) / (float)res, floor_cs = (big > 1.0f ? big : 1.0f) * 9.5367431640625e-7f;
    int i;
    if (!(cs > floor_cs))
        cs = floor_cs;
    /* each round adds >= 1 ulp; the quotient is within a few ulps of covering already */
    for (i = 0; i < 64 && lo + (float)res * cs < hi; i++)
        cs += cs * 2.384185791015625e-7f;
    return cs;
}

/* Boundary j: lo + (float)j x size. The lane version below computes the identical expression, so
 * build and traversal agree on every boundary bit for bit. */
static float f_g_bound(float lo, uint32_t j, float cs)
{
    return lo + (float)j * cs;
}

/* Cell of x: the largest j with boundary j <= x, clamped to [0, res); the quotient is a guess
 * that the loops correct against the boundaries themselves. */
static uint32_t f_g_cell(float x, float lo, float cs, uint32_t res)
{
    float q = (x - lo) / cs;
    uint32_t c;
    if (!(q > 0.0f))
        c = 0;
    else if (q >= (float)(res - 1u))
        c = res - 1u;
    else
        c = (uint32_t)q;
    while (c > 0 && x < f_g_bound(lo, c, cs))
        c--;
    while (c + 1u < res && x >= f_g_bound(lo, c + 1u, cs))
        c++;
    return c;
}

/* Cost: VCVT x1, FMUL x1, FADD x1. */
static lt_vf32_t f_g_boundv(lt_vi32_t c, int32_t off, float lo, float cs)
{
    lt_vf32_t r;
    int i;
    LT_CHARGE(GRID_F_BOUNDV);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = lo + (float)(c.l[i] + off) * cs;
    return r;
}

/* Cost: FADD x1, FDIV x1, VCVT x1, FCMP x2. */
static lt_vi32_t f_g_cellv(lt_vf32_t p, float lo, float cs, uint32_t res)
{
    lt_vi32_t r;
    int i;
    LT_CHARGE(GRID_F_CELLV);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = (int32_t)f_g_cell(p.l[i], lo, cs, res);
    return r;
}

static lt_vf32_t f_g_pos(lt_vf32_t o, lt_vf32_t t, lt_vf32_t d)
{
    return lt_vf32_add(o, lt_vf32_mul(t, d));
}

static int f_g_coord_ok(float x)
{
    return x >= -1e30f && x <= 1e30f;
}

static void f_g_signs(lt_vf32_t d, lt_mask16_t *pos, lt_mask16_t *neg)
{
    *pos = lt_vf32_cmpgt(d, lt_vf32_set1(0.0f));
    *neg = lt_vf32_cmplt(d, lt_vf32_set1(0.0f));
}

#include "numerics/lt_traits_f32.h"
#define LTN_DV lt_vf32_t
#define LTN_GRID lt_grid_f32_t
#define LTN_G_TRIPT(v, e) ((v) + (e))
#define LTN_G_COORD_OK f_g_coord_ok
#define LTN_G_REL f_g_rel
#define LTN_G_CELLSIZE f_g_cellsize
#define LTN_G_BOUND f_g_bound
#define LTN_G_CELL f_g_cell
#define LTN_G_BOUNDV f_g_boundv
#define LTN_G_CELLV f_g_cellv
#define LTN_G_POS f_g_pos
#define LTN_G_SIGNS f_g_signs
#include "lt_grid.inc"

#endif /* LT_CFG_FLOAT32 */
