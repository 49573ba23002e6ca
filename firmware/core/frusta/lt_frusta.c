/* lt_frusta.c - instantiates the multi-frusta kernels of lt_frusta.inc (Benthin & Wald 2009
 * [Benthin09]) for s15.16 (exact integer rays, proven margins) and float32 (relative margins), and
 * holds what differs between the two paths: the per-frame tables, the direction scaling,
 * reciprocals, the scalar forms of the triangle test's arithmetic for culling (lt_tri.h's per-lane
 * body, the one lt_isect.c's kernel uses, so they are the kernel's tnum, det, u and v) and the
 * margins; for primary frusta the eye's scalar terms, the exact linear camera (s1.30 integer
 * directions; float32 on a 2^-23 grid) and its lane helpers. Builds: all; float32 only with
 * LT_CFG_FLOAT32.
 */
#include "lt/lt_frusta.h"
#include "object/lt_tri.h"
#include "object/lt_isel.h"

/* ---- s15.16 --------------------------------------------------------------------------------- */

/* Geometry bound in raw s15.16: lights and origins inside +-2^GEOM units. */
#define FR_GEOM_RAW ((int64_t)1 << (LT_CFG_GEOM_MAX_LOG2 + 16))

lt_status_t lt_frusta_table_q16(const lt_frusta_light_q16_t *light, const lt_qmc_sets_t *sets,
                                lt_frusta_table_q16_t *tb)
{
    unsigned s, j, a, c;
    if (light == NULL || sets == NULL || tb == NULL || light->end_shift > 30u ||
        (light->flags & ~(LT_FRUSTA_BACKFACE | LT_FRUSTA_CORNER | LT_FRUSTA_CR | LT_FRUSTA_LEAFRAY |
                          LT_FRUSTA_SPLIT | LT_FRUSTA_FS | LT_FRUSTA_P256 | LT_FRUSTA_TRIPAR)) != 0)
        return LT_E_ARG;
    for (a = 0; a < 3; a++)
        if ((light->eu[a] % LT_FRUSTA_GRID) != 0 || (light->ev[a] % LT_FRUSTA_GRID) != 0)
            return LT_E_ARG;
    for (a = 0; a < 3; a++) {
        int64_t p[4];
        p[0] = light->c[a];
        p[1] = p[0] + light->eu[a];
        p[2] = p[0] + light->ev[a];
        p[3] = p[1] + light->ev[a];
        for (c = 0; c < 4; c++)
            if (p[c] > FR_GEOM_RAW || p[c] < -FR_GEOM_RAW)
                return LT_E_RANGE;
    }
    for (a = 0; a < 3; a++) {
        tb->c[a] = light->c[a];
        tb->eu[a] = light->eu[a];
        tb->ev[a] = light->ev[a];
        tb->eu9[a] = light->eu[a] / LT_FRUSTA_GRID; /* exact: checked above */
        tb->ev9[a] = light->ev[a] / LT_FRUSTA_GRID;
        tb->ld[0][a] = 0;
        tb->ld[1][a] = light->eu[a];
        tb->ld[2][a] = light->ev[a];
        tb->ld[3][a] = light->eu[a] + light->ev[a]; /* in range: both corners checked */
    }
    tb->flags = light->flags;
    tb->end_shift = light->end_shift != 0 ? light->end_shift : LT_FRUSTA_END_SHIFT;
    for (s = 0; s < LT_FRUSTA_SETS; s++) {
        int32_t umin = 511, umax = 1, vmin = 511, vmax = 1;
        for (j = 0; j < LT_FRUSTA_SAMPLES; j++) {
            int32_t su = 2 * (int32_t)sets->u[s][j] + 1, sv = 2 * (int32_t)sets->v[s][j] + 1;
            tb->su[s].l[j] = su;
            tb->sv[s].l[j] = sv;
            /* (su eu + sv ev) / 512 = su eu9 + sv ev9 exactly; |.| <= 2^(GEOM+17) raw */
            tb->gx[s].l[j] = su * tb->eu9[0] + sv * tb->ev9[0];
            tb->gy[s].l[j] = su * tb->eu9[1] + sv * tb->ev9[1];
            tb->gz[s].l[j] = su * tb->eu9[2] + sv * tb->ev9[2];
            umin = su < umin ? su : umin;
            umax = su > umax ? su : umax;
            vmin = sv < vmin ? sv : vmin;
            vmax = sv > vmax ? sv : vmax;
        }
        for (a = 0; a < 3; a++) {
            const lt_vq16_t *g = a == 0 ? &tb->gx[s] : (a == 1 ? &tb->gy[s] : &tb->gz[s]);
            int32_t lo = g->l[0], hi = g->l[0];
            for (j = 1; j < LT_FRUSTA_SAMPLES; j++) {
                lo = g->l[j] < lo ? g->l[j] : lo;
                hi = g->l[j] > hi ? g->l[j] : hi;
            }
            tb->gmin[a].l[s] = lo;
            tb->gmax[a].l[s] = hi;
            tb->kd[0][a].l[s] = umin * tb->eu9[a] + vmin * tb->ev9[a];
            tb->kd[1][a].l[s] = umax * tb->eu9[a] + vmin * tb->ev9[a];
            tb->kd[2][a].l[s] = umin * tb->eu9[a] + vmax * tb->ev9[a];
            tb->kd[3][a].l[s] = umax * tb->eu9[a] + vmax * tb->ev9[a];
        }
    }
    return LT_OK;
}

/* Shift L of one frustum from m = max |light corner - o| (raw): the largest L with m << L < 2^30,
 * i.e. 30 - bitlen(m); -1 for m == 0 (all rays have zero length). m < 2^30 within the bound. */
static int32_t q_shift1(int32_t m)
{
    return m == 0 ? -1 : (int32_t)lt__clz32((uint32_t)m) - 2;
}

static lt_vi32_t q_scale(lt_vq16_t m)
{
    lt_vi32_t r;
    int i;
    LT_CHARGE(FR_Q_SCALE);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = q_shift1(m.l[i]);
    return r;
}

/* a << L: s15.16 world vector -> s1.30 direction, exact (|a| << L < 2^30 by the choice of L). */
LT_INLINE int32_t q_shl1(int32_t a, int32_t L)
{
    return lt__wrap32((int64_t)a * ((int64_t)1 << (L < 0 ? 0 : L)));
}

static lt_vq30_t q_tod(lt_vq16_t a, lt_vi32_t L)
{
    lt_vq30_t r;
    int i;
    LT_CHARGE(FR_Q_TOD);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = q_shl1(a.l[i], L.l[i]);
    return r;
}

static lt_vq30_t q_tod_s(lt_vq16_t a, int32_t L)
{
    lt_vq30_t r;
    int i;
    LT_CHARGE(FR_Q_TOD);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = q_shl1(a.l[i], L);
    return r;
}

/* t_end = 2^(30 - L) raw: the light point is o + t_end d. */
LT_INLINE int32_t q_tend1(int32_t L) { return L < 0 ? 0 : (int32_t)((uint32_t)1 << (30 - L)); }

static lt_vq16_t q_tend(lt_vi32_t L)
{
    lt_vq16_t r;
    int i;
    LT_CHARGE(FR_Q_TEND);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = q_tend1(L.l[i]);
    return r;
}

/* tmax = t_end - (t_end >> es) */
LT_INLINE int32_t q_tmax1(int32_t tend, uint32_t es) { return tend - lt__asr32(tend, es); }

static lt_vq16_t q_tmaxv(lt_vq16_t tend, uint32_t es)
{
    lt_vq16_t r;
    int i;
    LT_CHARGE(FR_Q_TMAX);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = q_tmax1(tend.l[i], es);
    return r;
}

/* Box bound margins: lower bounds go down, upper bounds up by LT_FRUSTA_BOX_MARGIN_Q16. */
#define Q_LOWER(x) lt_vq16_sub_sat((x), lt_vq16_set1(LT_FRUSTA_BOX_MARGIN_Q16))
#define Q_UPPER(x) lt_vq16_add_sat((x), lt_vq16_set1(LT_FRUSTA_BOX_MARGIN_Q16))

/* Corner-culling margins, in the forms' 36 fractional bits (U = d . round6(e2 x tvec), D = d .
 * round6(e2 x e1), V = d . qvec). The kernel's u and det differ from the exact linear forms by
 * <= 1/2 |tvec|_1 and 1/2 |e1|_1 (pvec rounding, 32-bit units), each rounded normal puts U/16 or
 * D/16 within |d|_1 / 32 <= C1 / 32 of them (C1 = 3 2^30 bounds |d|_1), and v = floor(V / 16) is
 * exactly monotone: so mu = 8 |tvec|_1 + C1 / 2 (+16), mw = 8 (|e1|_1 + |tvec|_1) + C1 (+32),
 * and V itself needs V < 0 (sigma > 0) or V > 15 (sigma < 0). docs/frusta.md has the derivation.
 * |tvec|_1 <= 3 x 2^29 raw fits int32 within the geometry bound. */
static void q_margins(lt_vq16_t tx, lt_vq16_t ty, lt_vq16_t tz, const lt_tri_q16_t *tri,
                      lt_vql36_t *mu, lt_vql36_t *mw, lt_vql36_t *mvp, lt_vql36_t *mvn)
{
    lt_vq16_t t1 = lt_vq16_add_sat(lt_vq16_add_sat(lt_vq16_abs_sat(tx), lt_vq16_abs_sat(ty)),
                                   lt_vq16_abs_sat(tz));
    int64_t e1 = (int64_t)lt__q16_abs_sat(tri->e1[0]) + lt__q16_abs_sat(tri->e1[1]) +
                 lt__q16_abs_sat(tri->e1[2]);
    /* 8 |tvec|_1: |tvec|_1 (raw s15.16) counted in the forms' 2^-36 units, as the derivation
     * does; sign-extended, then x 8. The shift by 0 does nothing and is charged (VSHIFT x1): it
     * was always there, and removing it would change the cycle figures. */
    lt_vql36_t w8 = lt_vql36_from_vql(lt_vql_from_vi32(lt_vi32_from_q16(t1)));
    w8 = lt_vql36_shl_wrap(lt_vql36_asr(w8, 0), 3);
    LT_CHARGE(FR_Q_MARGINS);
    *mu = lt_vql36_add_wrap(w8, lt_vql36_set1(((int64_t)3 << 29) + 16));
    *mw = lt_vql36_add_wrap(w8, lt_vql36_set1(8 * e1 + ((int64_t)3 << 30) + 32));
    *mvp = lt_vql36_set1(0);
    *mvn = lt_vql36_set1(15);
}

/* Corner-culling margins for the watertight test (LT_ISECT_WT), s15.16 (docs/frusta.md, "Corner
 * culling with the watertight test"). With p_i = v_i - o and P >= max |p_i|_inf, the kernel's
 * sheared vertex coordinates are the exact ones for the ray's direction within
 * delta <= 2^-31 2^13 + 2^-17 <= 3 2^-17 units (Sx, Sy in s1.30, one rounded product), so each of
 * its edge functions is the exact one, F(d) / d_kz with |d_kz| < 1, within
 * delta (|x1| + |y1| + |x2| + |y2|) + 2 delta^2 <= 24 2^-17 P + 2^-30: in the forms' 2^-36 units
 * at most 192 P_raw + 72. The forms' own rounding (one or two 6-bit normals, or qvec) adds C1/2 or
 * C1, so: mu = mv = C1/2 + 256 P_raw + 144, mw = C1 + 256 P_raw + 160 (V needs a margin here: the
 * watertight test does not use qvec). A form beyond its margin at all four corners therefore has
 * the kernel's edge sign against the triangle's side (sigma) for every ray of the frustum; the
 * test could still accept such a ray if it saw the triangle's other winding, i.e. a hit behind
 * the origin, which its t > tmin >= 0 rejects as long as the origin is not within the vertex
 * perturbation of the triangle's plane. Lanes where |tnum| <= 2^-10 P^2 + 2^-13 (|e1|_1 + 2^-14)
 * (|e2|_1 + 2^-14) + 2^-7 |e2|_1 (tnum's own qvec rounding), in tnum's 22 fractional bits, are
 * returned (not corner-culled). All in int64: |tvec|_1 <= 3 2^29 and |e|_1 <= 3 2^30 raw. */
/* One origin's watertight margins (t1 = |tvec|_1, e1, e2 = |e1|_1, |e2|_1, raw) and whether its
 * tnum clears the plane guard: the body shared by q_margins_wt (per lane) and q_pmarg1_wt. */
static int q_wt1(int64_t t1, int64_t e1, int64_t e2, int64_t tnum, int64_t *mu, int64_t *mw)
{
    int64_t pm = t1 + (e1 > e2 ? e1 : e2), ph = (pm >> 8) + 1, g;
    /* 2^-10 P^2 in 2^-22 units: P_raw^2 2^-32 2^-10 2^22 = P_raw^2 2^-20, rounded up; then
     * 2^-13 (|e1|_1 + 4) (|e2|_1 + 4) + 2^-7 |e2|_1, rounded up */
    g = ((ph * ph) >> 4) + 1 + ((((e1 + 4) >> 8) + 1) * (((e2 + 4) >> 8) + 1) >> 7) + 1 +
        (e2 >> 1) + 1;
    *mu = ((int64_t)3 << 29) + 256 * pm + 144;
    *mw = ((int64_t)3 << 30) + 256 * pm + 160;
    return tnum > g || tnum < -g;
}

static lt_mask16_t q_margins_wt(lt_vq16_t tx, lt_vq16_t ty, lt_vq16_t tz, const lt_tri_q16_t *tri,
                                const lt_vql22_t *tnum, lt_vql36_t *mu, lt_vql36_t *mw,
                                lt_vql36_t *mvp, lt_vql36_t *mvn)
{
    int64_t e1 = 0, e2 = 0;
    unsigned m = 0, a;
    int i;
    for (a = 0; a < 3; a++) {
        e1 += lt__q16_abs_sat(tri->e1[a]);
        e2 += lt__q16_abs_sat(tri->e2[a]);
    }
    LT_CHARGE(FR_Q_WTMARGINS);
    for (i = 0; i < LT_LANES; i++) {
        int64_t t1 = (int64_t)lt__q16_abs_sat(tx.l[i]) + lt__q16_abs_sat(ty.l[i]) +
                     lt__q16_abs_sat(tz.l[i]);
        if (!q_wt1(t1, e1, e2, tnum->l[i], &mu->l[i], &mw->l[i]))
            m |= 1u << i;
        mvp->l[i] = mvn->l[i] = mu->l[i];
    }
    return (lt_mask16_t)m;
}

/* e2 x e1 of a triangle rounded to qvec's s25.6, broadcast (a per-triangle constant). */
static void q_tri_a(const lt_tri_q16_t *t, lt_vq6_t *ax, lt_vq6_t *ay, lt_vq6_t *az)
{
    LT_CHARGE(FR_Q_TRI_A);
    *ax = lt_vq6_set1(lt__tri_q16_qvec1(t->e2[1], t->e1[2], t->e2[2], t->e1[1]));
    *ay = lt_vq6_set1(lt__tri_q16_qvec1(t->e2[2], t->e1[0], t->e2[0], t->e1[2]));
    *az = lt_vq6_set1(lt__tri_q16_qvec1(t->e2[0], t->e1[1], t->e2[1], t->e1[0]));
}

/* Lanes whose edge normal (or the triangle's e2 x e1) saturated its s25.6 range. */
static lt_mask16_t q_nsat(lt_vq6_t nx, lt_vq6_t ny, lt_vq6_t nz, lt_vq6_t ax, lt_vq6_t ay,
                          lt_vq6_t az)
{
    unsigned m = 0;
    int i;
    LT_CHARGE(FR_Q_NSAT);
    for (i = 0; i < LT_LANES; i++) {
        int32_t v[6];
        int j;
        v[0] = nx.l[i], v[1] = ny.l[i], v[2] = nz.l[i], v[3] = ax.l[i], v[4] = ay.l[i], v[5] = az.l[i];
        for (j = 0; j < 6; j++)
            if (v[j] == INT32_MAX || v[j] == INT32_MIN)
                m |= 1u << i;
    }
    return (lt_mask16_t)m;
}

/* Scalar sign of the kernel's tnum for one origin (lt__tri_q16_org1, lt_tri.h): a hit of any
 * ray from o has det of this sign (t = tnum / det > tmin >= 0). Cost: FR_TNUM_SIGN (SMUL x9,
 * SALU x9). */
static int q_tnum_sign1(const lt_q16_t o[3], const lt_tri_q16_t *tri)
{
    lt__tri_q16_org_t s;
    lt__tri_q16_org1(o, tri, &s);
    LT_CHARGE(FR_TNUM_SIGN);
    return (s.tnum > 0) - (s.tnum < 0);
}

/* Direct-light term: n.w and nl.w rounded to s15.16 (lt_vq16_dot3_q30_sat: q30 x q16 -> 46 bits),
 * then G = a b / |w|^2 (q16 x q16 = 32 bits over 32 bits) half up to s15.16, per lane. */
static lt_vq16_t q_gterm(lt_mask16_t k, lt_vq16_t a, lt_vq16_t b, lt_vq16_t wx, lt_vq16_t wy,
                         lt_vq16_t wz)
{
    lt_vql32_t num = lt_vql32_mul_q16(a, b);
    lt_vql32_t den = lt_vql32_dot3_q16(wx, wy, wz, wx, wy, wz);
    lt_vq16_t g;
    int i;
    LT_CHARGE(FR_Q_GTERM_DIV);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        g.l[i] = 0;
        /* num <= den (Cauchy-Schwarz with unit normals, up to rounding); both are shifted right
         * until num 2^16 fits below 2^62, which keeps >= 45 significant bits of each */
        if (LT__ON(k, i) && den.l[i] > 0 && num.l[i] > 0) {
            unsigned sh = 64u - lt__clz64((uint64_t)num.l[i]);
            int64_t n = num.l[i], d = den.l[i];
            if (sh > 46u) {
                n = lt__asr64(n, sh - 46u);
                d = lt__asr64(d, sh - 46u);
            }
            g.l[i] = d > 0 ? lt__ssat32(lt__div_round64(n * 65536, d)) : LT_Q16_MAX;
        }
    }
    return g;
}

/* Filter: n_p . n_q >= cos_min for s1.30 unit normals: exact 60-bit dot against cos << 30. */
static lt_mask16_t q_ncmp(lt_mask16_t k, const lt_vq30_t np[3], const lt_vq30_t nq[3], lt_q30_t c)
{
    lt_vql60_t d = lt_vql60_dot3_q30(np[0], np[1], np[2], nq[0], nq[1], nq[2]);
    return lt_vql60_cmpge_m(k, d, lt_vql60_set1((int64_t)c * ((int64_t)1 << 30)));
}

/* Row segment load of 16 lanes at x0 + i, lanes with x outside [0, w) or not in k read as 0
 * (a masked unaligned vector load: one VLOAD, memory charged for the span read). */
static lt_vq16_t q_loadx(const int32_t *row, int64_t x0, uint32_t w, lt_mask16_t *k)
{
    lt_vq16_t r;
    int i;
    unsigned m = 0;
    LT_CHARGE(FR_LOADX);
    for (i = 0; i < LT_LANES; i++) {
        int64_t x = x0 + i;
        r.l[i] = 0;
        if (x >= 0 && x < (int64_t)w && LT__ON(*k, i)) {
            r.l[i] = row[x];
            m |= 1u << i;
        }
    }
    if (m != 0) {
        unsigned f = lt__ctz32(m), l = 31u - lt__clz32(m);
        LT_MEM(&row[x0 + f], (l - f + 1u) * sizeof(int32_t), LT_MEM_READ);
    }
    *k = (lt_mask16_t)m;
    return r;
}


/* ---- primary frusta, s15.16: the eye's scalar terms and s1.30 direction lanes --------------- */

/* The kernel's origin-only terms for rays from one eye, as scalars: tvec = o - v0, qvec = tvec x
 * e1 rounded to s25.6 and tnum = e2 . qvec, lt_tri.h's lt__tri_q16_org1 (the lane arithmetic of
 * lt_tri16_q16, so broadcasting them gives exactly the kernel's lanes). Cost: FR_PTQ (SMUL x9,
 * SALU x12). */
typedef lt__tri_q16_org_t q_stq_t; /* t: tvec s15.16, q: qvec s25.6, tnum: 22 fractional bits */

static void q_ptq1(const lt_q16_t o[3], const lt_tri_q16_t *tri, q_stq_t *s)
{
    lt__tri_q16_org1(o, tri, s);
    LT_CHARGE(FR_PTQ);
}

/* The u edge's normal e2 x tvec rounded to s25.6 (fr_cull's per-lane normal, as a scalar).
 * Returns 1 if a component saturated (no error bound: the caller skips corner culling).
 * Cost: FR_Q_PNRM (SMUL x6, SALU x6). */
static int q_pnrm1(const lt_tri_q16_t *tri, const int32_t t[3], int32_t n[3])
{
    unsigned a;
    int sat = 0;
    n[0] = lt__tri_q16_qvec1(tri->e2[1], t[2], tri->e2[2], t[1]);
    n[1] = lt__tri_q16_qvec1(tri->e2[2], t[0], tri->e2[0], t[2]);
    n[2] = lt__tri_q16_qvec1(tri->e2[0], t[1], tri->e2[1], t[0]);
    for (a = 0; a < 3; a++)
        sat |= n[a] == INT32_MAX || n[a] == INT32_MIN;
    LT_CHARGE(FR_Q_PNRM);
    return sat;
}

/* Whether the broadcast e2 x e1 (q_tri_a) saturated in any component. Cost: FR_Q_ASAT (SALU x3). */
static int q_asat(lt_vq6_t ax, lt_vq6_t ay, lt_vq6_t az)
{
    LT_CHARGE(FR_Q_ASAT);
    return ax.l[0] == INT32_MAX || ax.l[0] == INT32_MIN || ay.l[0] == INT32_MAX ||
           ay.l[0] == INT32_MIN || az.l[0] == INT32_MAX || az.l[0] == INT32_MIN;
}

/* q_margins for one tvec (common eye), scalars: mu = 8 |tvec|_1 + C1 / 2 + 16, mw = 8 (|e1|_1 +
 * |tvec|_1) + C1 + 32, and V's 0 / 15, in the forms' 36 fractional bits (exact int64).
 * Cost: FR_Q_PMARG (SALU x8). */
static void q_pmarg1(const int32_t t[3], const lt_tri_q16_t *tri, int64_t *mu, int64_t *mw,
                     int64_t *mvp, int64_t *mvn)
{
    int64_t t1 = 0, e1 = 0;
    unsigned a;
    for (a = 0; a < 3; a++) {
        t1 += t[a] < 0 ? -(int64_t)t[a] : (int64_t)t[a];
        e1 += tri->e1[a] < 0 ? -(int64_t)tri->e1[a] : (int64_t)tri->e1[a];
    }
    *mu = 8 * t1 + ((int64_t)3 << 29) + 16;
    *mw = 8 * (e1 + t1) + ((int64_t)3 << 30) + 32;
    *mvp = 0;
    *mvn = 15;
    LT_CHARGE(FR_Q_PMARG);
}

/* q_margins_wt for one tvec (common eye), scalars: the margins mu = mv, mw of the watertight test,
 * in the forms' 36 fractional bits. Returns 0 if the eye is within the guard of the triangle's
 * plane (|tnum| too small: no corner culling). Cost: FR_Q_PWTMARG. */
static int q_pmarg1_wt(const int32_t t[3], int64_t tnum, const lt_tri_q16_t *tri, int64_t *mu,
                       int64_t *mw, int64_t *mvp, int64_t *mvn)
{
    int64_t t1 = 0, e1 = 0, e2 = 0;
    unsigned a;
    int ok;
    for (a = 0; a < 3; a++) {
        t1 += t[a] < 0 ? -(int64_t)t[a] : (int64_t)t[a];
        e1 += lt__q16_abs_sat(tri->e1[a]);
        e2 += lt__q16_abs_sat(tri->e2[a]);
    }
    ok = q_wt1(t1, e1, e2, tnum, mu, mw);
    *mvp = *mvn = *mu;
    LT_CHARGE(FR_Q_PWTMARG);
    return ok;
}

/* Direction component of pixel (x, y): d0 + x dx + y dy, exact in int64 (in range by the view
 * table's check), s1.30 raw. */
LT_INLINE int32_t q_pbase1(const lt_frusta_vtable_q16_t *vt, uint32_t x, uint32_t y, unsigned a)
{
    return lt__wrap32((int64_t)vt->d0[a] + (int64_t)x * vt->dx[a] + (int64_t)y * vt->dy[a]);
}

/* q_pbase1 per lane for tile coordinates x, y (lanes). Cost: FR_Q_PBASEV (VMUL x2, VMULW x2,
 * VCVT x1). */
static lt_vq30_t q_pbasev(const lt_frusta_vtable_q16_t *vt, lt_vi32_t x, lt_vi32_t y, unsigned a)
{
    lt_vq30_t r;
    int i;
    LT_CHARGE(FR_Q_PBASEV);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = q_pbase1(vt, (uint32_t)x.l[i], (uint32_t)y.l[i], a);
    return r;
}

/* |d0 + x dx + y dy| < 2^30 raw, exactly. */
static int q_pdir_ok(const lt_frusta_vtable_q16_t *vt, uint32_t x, uint32_t y, unsigned a)
{
    int64_t v = (int64_t)vt->d0[a] + (int64_t)x * vt->dx[a] + (int64_t)y * vt->dy[a];
    return v < ((int64_t)1 << 30) && v > -((int64_t)1 << 30);
}

LT_INLINE int32_t q_pdelta(const lt_frusta_vtable_q16_t *vt, uint32_t jx, uint32_t jy, unsigned a)
{
    return lt__wrap32((int64_t)jx * vt->dx[a] + (int64_t)jy * vt->dy[a]);
}

#include "numerics/lt_traits_q16.h"
#define LTN_VD lt_vq30_t
#define LTN_NT lt_q30_t
#define LTN_W lt_vql32_t  /* det, u, v: s31.32 */
#define LTN_TN lt_vql22_t /* tnum: s41.22 */
#define LTN_WC lt_vql36_t /* corner forms and margins: s27.36 */
#define LTN_QV lt_vq6_t   /* qvec and edge normals: s25.6 */
#define LTN_FR lt_frusta16_q16_t
#define LTN_FR_WT lt_wt16_q16_t
#define LTN_FRT lt_frusta_table_q16_t
#define LTN_FRF lt_frusta_filter_q16_t
#define LTN_RAY1 lt_ray1_q16_t
#define LTN_SC_T int32_t
#define LTN_SC_V lt_vi32_t
#define LTN_SCALE1 q_shift1
#define LTN_SCALE q_scale
#define LTN_SC_VALID(s) ((s) >= 0)
#define LTN_TOD q_tod
#define LTN_TOD_S q_tod_s
#define LTN_TOD1(a, s) q_shl1((a), (s))
#define LTN_TEND q_tend
#define LTN_TEND1 q_tend1
#define LTN_TMAX q_tmaxv
#define LTN_TMAX1 q_tmax1
#define LTN_RECIP_HI(d) lt_vq16_recip_q30_sat((d), LT_Q16_MAX)
#define LTN_RECIP_LO(d) lt_vq16_recip_q30_sat((d), LT_Q16_MIN)
#define LTN_RSAT lt_vq16_cmpsat
#define LTN_ABS lt_vq16_abs_sat
#define LTN_SABS lt__q16_abs_sat
#define LTN_MULLO lt_vq16_mul_sat_rd
#define LTN_LOWER Q_LOWER
#define LTN_UPPER Q_UPPER
#define LTN_MAX_M lt_vq16_max_m
#define LTN_MIN_M lt_vq16_min_m
/* the products of lt_tri16_q16: the lane ops of lt_tri.h's per-lane body */
#define LTN_CROSS_DP LT__TRI_V16_PVEC
#define LTN_DOT_PP LT__TRI_V16_DOT
#define LTN_CROSS_PP LT__TRI_V16_QVEC
#define LTN_DOT_DQ LT__TRI_V16_V
#define LTN_DOT_PQ LT__TRI_V16_TNUM
/* det, u, v (LTN_W, s31.32) */
#define LTN_W_ADD lt_vql32_add_wrap
#define LTN_W_NEG(a) lt_vql32_sub_wrap(lt_vql32_set1(0), (a))
#define LTN_W_LANE(v, f) ((v).l[f])
#define LTN_W_LANE0 ((int64_t)0)
#define LTN_W_CMPGT0(k, a) lt_vql32_cmpgt_m((k), (a), lt_vql32_set1(0))
#define LTN_W_CMPGE0(k, a) lt_vql32_cmpge_m((k), (a), lt_vql32_set1(0))
#define LTN_W_CMPLE_M lt_vql32_cmple_m
/* tnum (LTN_TN, s41.22) */
#define LTN_TN_SET1 lt_vql22_set1
#define LTN_TN_NEG(a) lt_vql22_sub_wrap(lt_vql22_set1(0), (a))
#define LTN_TN_CMPGT0(k, a) lt_vql22_cmpgt_m((k), (a), lt_vql22_set1(0))
#define LTN_TN_CMPLT0(k, a) lt_vql22_cmplt_m((k), (a), lt_vql22_set1(0))
/* the corner forms U, V, D, W and their margins (LTN_WC, s27.36) */
#define LTN_WC_SUB lt_vql36_sub_wrap
#define LTN_WC_ADD lt_vql36_add_wrap
#define LTN_WC_ZERO lt_vql36_set1(0)
#define LTN_WC_SET1 lt_vql36_set1
#define LTN_WC_CMPLT_M lt_vql36_cmplt_m
#define LTN_WC_CMPGT_M lt_vql36_cmpgt_m
#define LTN_QV_SET1 lt_vq6_set1
#define LTN_TDIV_M lt__tri_tdiv16_q16
#define LTN_TRI_A q_tri_a
/* d . n for s1.30 corner rays and an s25.6 normal: exact, 36 fractional bits */
#define LTN_LDOT lt_vql36_dot3_q30_q6
#define LTN_LINEAR_CORNERS 1
#define LTN_NSAT q_nsat
#define LTN_MARGINS q_margins
#define LTN_MARGINS_WT q_margins_wt
#define LTN_MID(lo, hi) ((lt_q16_t)(((int64_t)(lo) + (hi)) >> 1))
/* (angular width w, s1.30) x (distance d, s15.16) x 2 > K x extent, in int64 */
#define LTN_WIDER(w, d, ext) ((((int64_t)(w) * (d)) >> 29) > (int64_t)LT_FRUSTA_SPLIT_K * (ext))
#define LTN_TNUM_SIGN1 q_tnum_sign1
#define LTN_NDOT lt_vq16_dot3_q30_sat
#define LTN_GTERM q_gterm
#define LTN_NCMP q_ncmp
/* mean of n (1..16) values: sum / n half up */
#define LTN_MEAN lt_vq16_div_i32_z
#define LTN_LOADX(p, x0, w, k) q_loadx((p), (x0), (w), (k))
#define LTN_LOADXN(p, x0, w, k) lt__frusta_q30_of(q_loadx((p), (x0), (w), (k)))
#define LTN_VD_SET1 lt_vq30_set1
#define LTN_VD_FROM_V(a) lt__frusta_q30_of(a)
#define LTN_V_ONE LT_Q16_ONE
#define LTB_NODE lt_bvh_node_q16_t
#define LTB_NUM LT_BVH_NUM_Q16
#define LTN_FR_SC(F) ((F)->shift)
#define LTN_CDELTA(tb, u, v, a) ((u) * (tb)->eu9[a] + (v) * (tb)->ev9[a])
#define LTN_O_OK(x) ((int64_t)(x) <= FR_GEOM_RAW && (int64_t)(x) >= -FR_GEOM_RAW)
#define LTN_RAYSETUP lt_ray16_q16_setup
#define LTN_SLAB lt_slab16_q16
#define LTN_RAY1SETUP lt_ray1_q16_setup
#define LTN_ADD_M lt_vq16_add_sat_m
#define LTN_STORE_M lt_vq16_store_m
#define LTN_PVIEW lt_frusta_view_q16_t
#define LTN_PVT lt_frusta_vtable_q16_t
#define LTN_PFR lt_frusta_prim16_q16_t
#define LTN_SQV int32_t
#define LTN_SW int64_t
#define LTN_STQ q_stq_t
#define LTN_PTQ1 q_ptq1
#define LTN_SW_SIGN(x) (((x) > 0) - ((x) < 0))
#define LTN_SW_NEG(x) lt__l64_sub_wrap(0, (x))
#define LTN_PNRM1 q_pnrm1
#define LTN_ASAT q_asat
#define LTN_PMARG1 q_pmarg1
#define LTN_PMARG1_WT q_pmarg1_wt
#define LTN_PBASE1 q_pbase1
#define LTN_PBASEV q_pbasev
#define LTN_PDIR_OK q_pdir_ok
#define LTN_PDELTA q_pdelta
#define LTN_PFINITE(x) ((void)(x), 1)
#define LTN_PTMAX0 (LT_Q16_MAX - 1)
/* s1.30 pixel directions: add (exact: the sums are directions, in range), min, max, sign tests.
 * The sign tests are plain compares ANDed with k: one VCMP each and no lane-utilisation event,
 * the tally this path has always had. */
#define LTN_DADD lt_vq30_add_wrap
#define LTN_DSADD(a, b) lt__wrap32((int64_t)(a) + (b))
#define LTN_DMIN lt_vq30_min
#define LTN_DMAX lt_vq30_max
#define LTN_DCMPGE0(k, a) ((lt_mask16_t)(lt_vq30_cmpge0(a) & (k)))
#define LTN_DCMPLE0(k, a) ((lt_mask16_t)(lt_vq30_cmple0(a) & (k)))
#define LTN_DCMPLT0(k, a) ((lt_mask16_t)(lt_vq30_cmplt0(a) & (k)))
#define LTN_DCMPGT0(k, a) ((lt_mask16_t)(lt_vq30_cmpgt0(a) & (k)))
#define LTN_CMPEQ_M lt_vq16_cmpeq_m
#define LTN_NEXTUP_M(src, k, a) lt_vq16_add_sat_m((src), (k), (a), lt_vq16_set1(1))
LT_INLINE lt_vq30_t lt__frusta_q30_of(lt_vq16_t a)
{
    lt_vq30_t r;
    int i;
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = a.l[i];
    return r;
}
#include "lt_frusta.inc"
#include "numerics/lt_traits_undef.h"
#undef LTN_VD
#undef LTN_NT
#undef LTN_W
#undef LTN_TN
#undef LTN_WC
#undef LTN_TN_SET1
#undef LTN_TN_NEG
#undef LTN_TN_CMPGT0
#undef LTN_TN_CMPLT0
#undef LTN_WC_SUB
#undef LTN_WC_ADD
#undef LTN_WC_ZERO
#undef LTN_WC_SET1
#undef LTN_WC_CMPLT_M
#undef LTN_WC_CMPGT_M
#undef LTN_QV
#undef LTN_FR
#undef LTN_FR_WT
#undef LTN_FRT
#undef LTN_FRF
#undef LTN_RAY1
#undef LTN_SC_T
#undef LTN_SC_V
#undef LTN_SCALE1
#undef LTN_SCALE
#undef LTN_SC_VALID
#undef LTN_TOD
#undef LTN_TOD_S
#undef LTN_TOD1
#undef LTN_TEND
#undef LTN_TEND1
#undef LTN_TMAX
#undef LTN_TMAX1
#undef LTN_RECIP_HI
#undef LTN_RECIP_LO
#undef LTN_RSAT
#undef LTN_ABS
#undef LTN_SABS
#undef LTN_MULLO
#undef LTN_LOWER
#undef LTN_UPPER
#undef LTN_MAX_M
#undef LTN_MIN_M
#undef LTN_CROSS_DP
#undef LTN_DOT_PP
#undef LTN_CROSS_PP
#undef LTN_DOT_DQ
#undef LTN_DOT_PQ
#undef LTN_W_ADD
#undef LTN_W_NEG
#undef LTN_W_LANE
#undef LTN_W_LANE0
#undef LTN_QV_SET1
#undef LTN_W_CMPGE0
#undef LTN_W_CMPLE_M
#undef LTN_TDIV_M
#undef LTN_TRI_A
#undef LTN_LDOT
#undef LTN_LINEAR_CORNERS
#undef LTN_NSAT
#undef LTN_W_CMPGT0
#undef LTN_MARGINS
#undef LTN_MARGINS_WT
#undef LTN_MID
#undef LTN_WIDER
#undef LTN_TNUM_SIGN1
#undef LTN_NDOT
#undef LTN_GTERM
#undef LTN_NCMP
#undef LTN_MEAN
#undef LTN_LOADX
#undef LTN_LOADXN
#undef LTN_VD_SET1
#undef LTN_VD_FROM_V
#undef LTN_V_ONE
#undef LTB_NODE
#undef LTB_NUM
#undef LTN_FR_SC
#undef LTN_CDELTA
#undef LTN_O_OK
#undef LTN_RAYSETUP
#undef LTN_SLAB
#undef LTN_RAY1SETUP
#undef LTN_ADD_M
#undef LTN_STORE_M
#undef LTN_PVIEW
#undef LTN_PVT
#undef LTN_PFR
#undef LTN_SQV
#undef LTN_SW
#undef LTN_STQ
#undef LTN_PTQ1
#undef LTN_SW_SIGN
#undef LTN_SW_NEG
#undef LTN_PNRM1
#undef LTN_ASAT
#undef LTN_PMARG1
#undef LTN_PMARG1_WT
#undef LTN_PBASE1
#undef LTN_PBASEV
#undef LTN_PDIR_OK
#undef LTN_PDELTA
#undef LTN_PFINITE
#undef LTN_PTMAX0
#undef LTN_DADD
#undef LTN_DSADD
#undef LTN_DMIN
#undef LTN_DMAX
#undef LTN_DCMPGE0
#undef LTN_DCMPLE0
#undef LTN_DCMPLT0
#undef LTN_DCMPGT0
#undef LTN_CMPEQ_M
#undef LTN_NEXTUP_M

/* ---- float32 -------------------------------------------------------------------------------- */
#if LT_CFG_FLOAT32

#define F_MAX 3.40282347e38f

LT_INLINE int f_finite(float x) { return x == x && x <= F_MAX && x >= -F_MAX; }

lt_status_t lt_frusta_table_f32(const lt_frusta_light_f32_t *light, const lt_qmc_sets_t *sets,
                                lt_frusta_table_f32_t *tb)
{
    unsigned s, j, a;
    if (light == NULL || sets == NULL || tb == NULL || light->end_shift > 30u ||
        (light->flags & ~(LT_FRUSTA_BACKFACE | LT_FRUSTA_CORNER | LT_FRUSTA_CR | LT_FRUSTA_LEAFRAY |
                          LT_FRUSTA_SPLIT | LT_FRUSTA_FS | LT_FRUSTA_P256 | LT_FRUSTA_TRIPAR)) != 0)
        return LT_E_ARG;
    for (a = 0; a < 3; a++)
        if (!f_finite(light->c[a]) || !f_finite(light->eu[a]) || !f_finite(light->ev[a]))
            return LT_E_ARG;
    for (a = 0; a < 3; a++) {
        tb->c[a] = light->c[a];
        tb->eu[a] = light->eu[a];
        tb->ev[a] = light->ev[a];
        tb->ld[0][a] = 0.0f;
        tb->ld[1][a] = light->eu[a];
        tb->ld[2][a] = light->ev[a];
        tb->ld[3][a] = light->eu[a] + light->ev[a];
    }
    for (j = 0; j < 6; j++)
        tb->unused_[j] = 0;
    tb->flags = light->flags;
    tb->end_shift = light->end_shift != 0 ? light->end_shift : LT_FRUSTA_END_SHIFT;
    for (s = 0; s < LT_FRUSTA_SETS; s++) {
        int32_t umin = 511, umax = 1, vmin = 511, vmax = 1;
        for (j = 0; j < LT_FRUSTA_SAMPLES; j++) {
            int32_t su = 2 * (int32_t)sets->u[s][j] + 1, sv = 2 * (int32_t)sets->v[s][j] + 1;
            float u = (float)su * (1.0f / 512.0f), v = (float)sv * (1.0f / 512.0f);
            tb->su[s].l[j] = su;
            tb->sv[s].l[j] = sv;
            tb->gx[s].l[j] = u * light->eu[0] + v * light->ev[0];
            tb->gy[s].l[j] = u * light->eu[1] + v * light->ev[1];
            tb->gz[s].l[j] = u * light->eu[2] + v * light->ev[2];
            umin = su < umin ? su : umin;
            umax = su > umax ? su : umax;
            vmin = sv < vmin ? sv : vmin;
            vmax = sv > vmax ? sv : vmax;
        }
        for (a = 0; a < 3; a++) {
            const lt_vf32_t *g = a == 0 ? &tb->gx[s] : (a == 1 ? &tb->gy[s] : &tb->gz[s]);
            float lo = g->l[0], hi = g->l[0];
            float u0 = (float)umin * (1.0f / 512.0f), u1 = (float)umax * (1.0f / 512.0f);
            float v0 = (float)vmin * (1.0f / 512.0f), v1 = (float)vmax * (1.0f / 512.0f);
            for (j = 1; j < LT_FRUSTA_SAMPLES; j++) {
                lo = g->l[j] < lo ? g->l[j] : lo;
                hi = g->l[j] > hi ? g->l[j] : hi;
            }
            tb->gmin[a].l[s] = lo;
            tb->gmax[a].l[s] = hi;
            tb->kd[0][a].l[s] = u0 * light->eu[a] + v0 * light->ev[a];
            tb->kd[1][a].l[s] = u1 * light->eu[a] + v0 * light->ev[a];
            tb->kd[2][a].l[s] = u0 * light->eu[a] + v1 * light->ev[a];
            tb->kd[3][a].l[s] = u1 * light->eu[a] + v1 * light->ev[a];
        }
    }
    return LT_OK;
}

/* Scale of one frustum: the power of two 2^-e with m 2^-e in [0.5, 1) (m = max |light corner - o|,
 * from the exponent bits: exact, no libm); 0 for m == 0 (zero-length rays). */
static float f_scale1(float m)
{
    union {
        float f;
        uint32_t u;
    } v, r;
    uint32_t e;
    v.f = m;
    e = (v.u >> 23) & 0xFFu;
    if (!(m > 0.0f) || e >= 253u)
        return 0.0f;
    if (e == 0)
        e = 1; /* denormal m: 2^125 still keeps m scale below 1 */
    r.u = (253u - e) << 23;
    return r.f;
}

static lt_vf32_t f_scale(lt_vf32_t m)
{
    lt_vf32_t r;
    int i;
    LT_CHARGE(FR_F_SCALE);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = f_scale1(m.l[i]);
    return r;
}

LT_INLINE float f_tod1(float a, float s) { return a * s; }

static lt_vf32_t f_tod_s(lt_vf32_t a, float s) { return lt_vf32_mul(a, lt_vf32_set1(s)); }

LT_INLINE float f_tend1(float s) { return s > 0.0f ? 1.0f / s : 0.0f; }

static lt_vf32_t f_tend(lt_vf32_t s)
{
    lt_vf32_t r;
    int i;
    LT_CHARGE(FR_F_TEND);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = f_tend1(s.l[i]);
    return r;
}

/* tmax = t_end - t_end 2^-es: exact (t_end is a power of two) */
LT_INLINE float f_tmax1(float tend, uint32_t es)
{
    union {
        float f;
        uint32_t u;
    } p;
    p.u = (127u - es) << 23;
    return tend - tend * p.f;
}

static lt_vf32_t f_tmaxv(lt_vf32_t tend, uint32_t es)
{
    lt_vf32_t r;
    int i;
    LT_CHARGE(FR_F_TMAX);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = f_tmax1(tend.l[i], es);
    return r;
}

/* Relative box-bound margins 2^-20 |x| (the product's own error is ~2^-23 relative; plane and
 * origin rounding are covered by the BVH's 2^-18 pad, as for lt_slab16_f32). */
static lt_vf32_t f_lower(lt_vf32_t x)
{
    return lt_vf32_sub(x, lt_vf32_mul(lt_vf32_abs(x), lt_vf32_set1(0x1p-20f)));
}

static lt_vf32_t f_upper(lt_vf32_t x)
{
    return lt_vf32_add(x, lt_vf32_mul(lt_vf32_abs(x), lt_vf32_set1(0x1p-20f)));
}

/* Relative corner-culling margins, 2^-16 of each form's magnitude bound (the float kernel's error
 * is a few 2^-24 of it, the corner rays' distance from the exact hull ~2^-23): |d| components < 1,
 * so |u| <= 2 |tvec|_1 |e2|_1, |det| <= 2 |e1|_1 |e2|_1, |v| <= |qvec|_1 <= 2 |tvec|_1 |e1|_1. */
static void f_margins(lt_vf32_t tx, lt_vf32_t ty, lt_vf32_t tz, const lt_tri_f32_t *tri,
                      lt_vf32_t *mu, lt_vf32_t *mw, lt_vf32_t *mvp, lt_vf32_t *mvn)
{
    lt_vf32_t t1 = lt_vf32_add(lt_vf32_add(lt_vf32_abs(tx), lt_vf32_abs(ty)), lt_vf32_abs(tz));
    float e1 = lt__f32_abs(tri->e1[0]) + lt__f32_abs(tri->e1[1]) + lt__f32_abs(tri->e1[2]);
    float e2 = lt__f32_abs(tri->e2[0]) + lt__f32_abs(tri->e2[1]) + lt__f32_abs(tri->e2[2]);
    LT_CHARGE(FR_F_MARGINS);
    *mu = lt_vf32_mul(t1, lt_vf32_set1(e2 * 0x1p-15f));
    *mvp = lt_vf32_mul(t1, lt_vf32_set1(e1 * 0x1p-15f));
    *mvn = *mvp;
    *mw = lt_vf32_add(lt_vf32_add(*mu, *mvp), lt_vf32_set1(e1 * e2 * 0x1p-15f));
}

static void f_tri_a(const lt_tri_f32_t *t, lt_vf32_t *ax, lt_vf32_t *ay, lt_vf32_t *az)
{
    LT_CHARGE(FR_F_TRI_A);
    *ax = lt_vf32_set1(t->e2[1] * t->e1[2] - t->e2[2] * t->e1[1]);
    *ay = lt_vf32_set1(t->e2[2] * t->e1[0] - t->e2[0] * t->e1[2]);
    *az = lt_vf32_set1(t->e2[0] * t->e1[1] - t->e2[1] * t->e1[0]);
}

static int f_tnum_sign1(const float o[3], const lt_tri_f32_t *tri)
{
    float tx = o[0] - tri->v0[0], ty = o[1] - tri->v0[1], tz = o[2] - tri->v0[2];
    float qx = ty * tri->e1[2] - tz * tri->e1[1];
    float qy = tz * tri->e1[0] - tx * tri->e1[2];
    float qz = tx * tri->e1[1] - ty * tri->e1[0];
    float t = (tri->e2[0] * qx + tri->e2[1] * qy) + tri->e2[2] * qz;
    LT_CHARGE(FR_TNUM_SIGN);
    return (t > 0.0f) - (t < 0.0f);
}

static lt_vf32_t f_gterm(lt_mask16_t k, lt_vf32_t a, lt_vf32_t b, lt_vf32_t wx, lt_vf32_t wy,
                         lt_vf32_t wz)
{
    lt_vf32_t den = lt_vf32_dot3(wx, wy, wz, wx, wy, wz);
    lt_vf32_t g = lt_vf32_div_z(k, lt_vf32_mul(a, b), den);
    int i;
    for (i = 0; i < LT_LANES; i++)
        if (!(den.l[i] > 0.0f))
            g.l[i] = 0.0f;
    return g;
}

static lt_mask16_t f_ncmp(lt_mask16_t k, const lt_vf32_t np[3], const lt_vf32_t nq[3], float c)
{
    lt_vf32_t d = lt_vf32_dot3(np[0], np[1], np[2], nq[0], nq[1], nq[2]);
    return lt_vf32_cmpge_m(k, d, lt_vf32_set1(c));
}

static lt_vf32_t f_loadx(const float *row, int64_t x0, uint32_t w, lt_mask16_t *k)
{
    lt_vf32_t r;
    int i;
    unsigned m = 0;
    LT_CHARGE(FR_LOADX);
    for (i = 0; i < LT_LANES; i++) {
        int64_t x = x0 + i;
        r.l[i] = 0.0f;
        if (x >= 0 && x < (int64_t)w && LT__ON(*k, i)) {
            r.l[i] = row[x];
            m |= 1u << i;
        }
    }
    if (m != 0) {
        unsigned f = lt__ctz32(m), l = 31u - lt__clz32(m);
        LT_MEM(&row[x0 + f], (l - f + 1u) * sizeof(float), LT_MEM_READ);
    }
    *k = (lt_mask16_t)m;
    return r;
}


/* ---- primary frusta, float32 ---------------------------------------------------------------- */

typedef struct {
    float t[3];  /* tvec */
    float q[3];  /* qvec */
    float tnum;  /* e2 . qvec */
} f_stq_t;

/* The kernel's eye terms as scalars, the operations of lt_tri16_f32 in the same order. */
static void f_ptq1(const float o[3], const lt_tri_f32_t *tri, f_stq_t *s)
{
    unsigned a;
    for (a = 0; a < 3; a++)
        s->t[a] = o[a] - tri->v0[a];
    s->q[0] = s->t[1] * tri->e1[2] - s->t[2] * tri->e1[1];
    s->q[1] = s->t[2] * tri->e1[0] - s->t[0] * tri->e1[2];
    s->q[2] = s->t[0] * tri->e1[1] - s->t[1] * tri->e1[0];
    s->tnum = (tri->e2[0] * s->q[0] + tri->e2[1] * s->q[1]) + tri->e2[2] * s->q[2];
    LT_CHARGE(FR_PTQ);
}

static int f_pnrm1(const lt_tri_f32_t *tri, const float t[3], float n[3])
{
    n[0] = tri->e2[1] * t[2] - tri->e2[2] * t[1];
    n[1] = tri->e2[2] * t[0] - tri->e2[0] * t[2];
    n[2] = tri->e2[0] * t[1] - tri->e2[1] * t[0];
    LT_CHARGE(FR_F_PNRM);
    return 0;
}

/* f_margins for one tvec, scalars. */
/* The watertight test's margins, float32: f_margins plus 2^-14 P^2 (P = |tvec|_1 + max |e|_1, the
 * sheared coordinates' rounding times the edge's reach), and the lanes whose origin lies within
 * 2^-16 (P^3 + P |e1|_1 |e2|_1) of the triangle's plane in tnum (not corner-culled). Not a proof
 * (as f_margins): checked by the same tests. Cost: FR_F_WTMARGINS. */
/* One origin's float32 watertight margins and plane guard (t1 = |tvec|_1), the body shared by
 * f_margins_wt (per lane) and f_pmarg1_wt. */
static int f_wt1(float t1, float e1, float e2, float tnum, float *mu, float *mw, float *mv)
{
    float pm = t1 + (e1 > e2 ? e1 : e2), w = pm * pm * 0x1p-14f;
    float g = (pm * pm * pm + pm * e1 * e2) * 0x1p-16f;
    *mu = t1 * (e2 * 0x1p-15f) + w;
    *mv = t1 * (e1 * 0x1p-15f) + w;
    *mw = (*mu + *mv) + e1 * e2 * 0x1p-15f + w;
    return tnum > g || tnum < -g;
}

static lt_mask16_t f_margins_wt(lt_vf32_t tx, lt_vf32_t ty, lt_vf32_t tz, const lt_tri_f32_t *tri,
                                const lt_vf32_t *tnum, lt_vf32_t *mu, lt_vf32_t *mw,
                                lt_vf32_t *mvp, lt_vf32_t *mvn)
{
    float e1 = lt__f32_abs(tri->e1[0]) + lt__f32_abs(tri->e1[1]) + lt__f32_abs(tri->e1[2]);
    float e2 = lt__f32_abs(tri->e2[0]) + lt__f32_abs(tri->e2[1]) + lt__f32_abs(tri->e2[2]);
    unsigned m = 0;
    int i;
    LT_CHARGE(FR_F_WTMARGINS);
    for (i = 0; i < LT_LANES; i++) {
        float t1 = lt__f32_abs(tx.l[i]) + lt__f32_abs(ty.l[i]) + lt__f32_abs(tz.l[i]);
        if (!f_wt1(t1, e1, e2, tnum->l[i], &mu->l[i], &mw->l[i], &mvp->l[i]))
            m |= 1u << i;
        mvn->l[i] = mvp->l[i];
    }
    return (lt_mask16_t)m;
}

/* f_margins_wt for one tvec (common eye). Returns 0 within the plane guard. Cost: FR_F_PWTMARG. */
static int f_pmarg1_wt(const float t[3], float tnum, const lt_tri_f32_t *tri, float *mu, float *mw,
                       float *mvp, float *mvn)
{
    float t1 = lt__f32_abs(t[0]) + lt__f32_abs(t[1]) + lt__f32_abs(t[2]);
    float e1 = lt__f32_abs(tri->e1[0]) + lt__f32_abs(tri->e1[1]) + lt__f32_abs(tri->e1[2]);
    float e2 = lt__f32_abs(tri->e2[0]) + lt__f32_abs(tri->e2[1]) + lt__f32_abs(tri->e2[2]);
    int ok = f_wt1(t1, e1, e2, tnum, mu, mw, mvp);
    LT_CHARGE(FR_F_PWTMARG);
    *mvn = *mvp;
    return ok;
}

static void f_pmarg1(const float t[3], const lt_tri_f32_t *tri, float *mu, float *mw, float *mvp,
                     float *mvn)
{
    float t1 = lt__f32_abs(t[0]) + lt__f32_abs(t[1]) + lt__f32_abs(t[2]);
    float e1 = lt__f32_abs(tri->e1[0]) + lt__f32_abs(tri->e1[1]) + lt__f32_abs(tri->e1[2]);
    float e2 = lt__f32_abs(tri->e2[0]) + lt__f32_abs(tri->e2[1]) + lt__f32_abs(tri->e2[2]);
    LT_CHARGE(FR_F_PMARG);
    *mu = t1 * (e2 * 0x1p-15f);
    *mvp = t1 * (e1 * 0x1p-15f);
    *mvn = *mvp;
    *mw = (*mu + *mvp) + e1 * e2 * 0x1p-15f;
}

/* Direction component of pixel (x, y) as (d0 + x dx) + y dy: the same float operations wherever a
 * tile's ray 0 is formed, so every path gets the same bits. */
LT_INLINE float f_pbase1(const lt_frusta_vtable_f32_t *vt, uint32_t x, uint32_t y, unsigned a)
{
    return (vt->d0[a] + (float)x * vt->dx[a]) + (float)y * vt->dy[a];
}

static lt_vf32_t f_pbasev(const lt_frusta_vtable_f32_t *vt, lt_vi32_t x, lt_vi32_t y, unsigned a)
{
    lt_vf32_t r;
    int i;
    LT_CHARGE(FR_F_PBASEV);
    for (i = 0; i < LT_LANES; i++)
        r.l[i] = f_pbase1(vt, (uint32_t)x.l[i], (uint32_t)y.l[i], a);
    return r;
}

/* The direction the generator forms for pixel (x, y) is finite with |.| < 1 (gx.. set first). */
static int f_pdir_ok(const lt_frusta_vtable_f32_t *vt, uint32_t x, uint32_t y, unsigned a)
{
    const lt_vf32_t *g = a == 0 ? &vt->gx : (a == 1 ? &vt->gy : &vt->gz);
    float v = f_pbase1(vt, x & ~3u, y & ~3u, a) + g->l[(x & 3u) + 4u * (y & 3u)];
    return v < 1.0f && v > -1.0f;
}

LT_INLINE float f_pdelta(const lt_frusta_vtable_f32_t *vt, uint32_t jx, uint32_t jy, unsigned a)
{
    return (float)jx * vt->dx[a] + (float)jy * vt->dy[a];
}

/* t one ulp up for lanes of k (a >= 0: the next float). Cost: FR_F_NEXTUP (VALU x1). */
static lt_vf32_t f_nextup_m(lt_vf32_t src, lt_mask16_t k, lt_vf32_t a)
{
    int i;
    LT_CHARGE(FR_F_NEXTUP);
    for (i = 0; i < LT_LANES; i++)
        if (LT__ON(k, i)) {
            union {
                float f;
                uint32_t u;
            } v;
            v.f = a.l[i];
            v.u += 1u;
            src.l[i] = v.f;
        }
    return src;
}

#include "numerics/lt_traits_f32.h"
#define LTN_VD lt_vf32_t
#define LTN_NT float
#define LTN_W lt_vf32_t
#define LTN_TN lt_vf32_t
#define LTN_WC lt_vf32_t
#define LTN_QV lt_vf32_t
#define LTN_FR lt_frusta16_f32_t
#define LTN_FR_WT lt_wt16_f32_t
#define LTN_FRT lt_frusta_table_f32_t
#define LTN_FRF lt_frusta_filter_f32_t
#define LTN_RAY1 lt_ray1_f32_t
#define LTN_SC_T float
#define LTN_SC_V lt_vf32_t
#define LTN_SCALE1 f_scale1
#define LTN_SCALE f_scale
#define LTN_SC_VALID(s) ((s) > 0.0f)
#define LTN_TOD lt_vf32_mul
#define LTN_TOD_S f_tod_s
#define LTN_TOD1 f_tod1
#define LTN_TEND f_tend
#define LTN_TEND1 f_tend1
#define LTN_TMAX f_tmaxv
#define LTN_TMAX1 f_tmax1
#define LTN_RECIP_HI(d) lt_vf32_recip_sat((d), F_MAX)
#define LTN_RECIP_LO(d) lt_vf32_recip_sat((d), -F_MAX)
#define LTN_RSAT lt_vf32_cmpsat
#define LTN_ABS lt_vf32_abs
#define LTN_SABS lt__f32_abs
#define LTN_MULLO lt_vf32_mul
#define LTN_LOWER f_lower
#define LTN_UPPER f_upper
#define LTN_MAX_M lt_vf32_max_m
#define LTN_MIN_M lt_vf32_min_m
#define LTN_CROSS_DP lt_vf32_cross
#define LTN_DOT_PP lt_vf32_dot3
#define LTN_CROSS_PP lt_vf32_cross
#define LTN_DOT_DQ lt_vf32_dot3
#define LTN_DOT_PQ lt_vf32_dot3
#define LTN_W_ADD lt_vf32_add
#define LTN_W_NEG lt_vf32_neg
#define LTN_W_LANE(v, f) ((v).l[f])
#define LTN_W_LANE0 0.0f
#define LTN_TN_SET1 lt_vf32_set1
#define LTN_TN_NEG lt_vf32_neg
#define LTN_TN_CMPGT0(k, a) lt_vf32_cmpgt_m((k), (a), lt_vf32_set1(0.0f))
#define LTN_TN_CMPLT0(k, a) lt_vf32_cmplt_m((k), (a), lt_vf32_set1(0.0f))
#define LTN_WC_SUB lt_vf32_sub
#define LTN_WC_ADD lt_vf32_add
#define LTN_WC_ZERO lt_vf32_set1(0.0f)
#define LTN_WC_SET1 lt_vf32_set1
#define LTN_WC_CMPLT_M lt_vf32_cmplt_m
#define LTN_WC_CMPGT_M lt_vf32_cmpgt_m
#define LTN_QV_SET1 lt_vf32_set1
#define LTN_W_CMPGE0(k, a) lt_vf32_cmpge_m((k), (a), lt_vf32_set1(0.0f))
#define LTN_W_CMPLE_M lt_vf32_cmple_m
#define LTN_TDIV_M(src, k, n, d) lt_vf32_div_m((src), (k), (n), (d))
#define LTN_TRI_A f_tri_a
#define LTN_LDOT lt_vf32_dot3
#define LTN_LINEAR_CORNERS 0
#define LTN_NSAT(nx, ny, nz, ax, ay, az)                                                          \
    ((void)(nx), (void)(ny), (void)(nz), (void)(ax), (void)(ay), (void)(az), (lt_mask16_t)0)
#define LTN_W_CMPGT0(k, a) lt_vf32_cmpgt_m((k), (a), lt_vf32_set1(0.0f))
#define LTN_MARGINS f_margins
#define LTN_MARGINS_WT f_margins_wt
#define LTN_MID(lo, hi) (0.5f * ((lo) + (hi)))
#define LTN_WIDER(w, d, ext) (2.0f * (w) * (d) > (float)LT_FRUSTA_SPLIT_K * (ext))
#define LTN_TNUM_SIGN1 f_tnum_sign1
#define LTN_NDOT lt_vf32_dot3
#define LTN_GTERM f_gterm
#define LTN_NCMP f_ncmp
#define LTN_MEAN lt_vf32_div_i32_z
#define LTN_LOADX(p, x0, w, k) f_loadx((p), (x0), (w), (k))
#define LTN_LOADXN(p, x0, w, k) f_loadx((p), (x0), (w), (k))
#define LTN_VD_SET1 lt_vf32_set1
#define LTN_VD_FROM_V(a) (a)
#define LTN_V_ONE 1.0f
#define LTB_NODE lt_bvh_node_f32_t
#define LTB_NUM LT_BVH_NUM_F32
#define LTN_FR_SC(F) ((F)->scale)
#define LTN_CDELTA(tb, u, v, a)                                                                   \
    ((float)(u) * (1.0f / 512.0f) * (tb)->eu[a] + (float)(v) * (1.0f / 512.0f) * (tb)->ev[a])
#define LTN_O_OK f_finite
#define LTN_RAYSETUP lt_ray16_f32_setup
#define LTN_SLAB lt_slab16_f32
#define LTN_RAY1SETUP lt_ray1_f32_setup
#define LTN_ADD_M lt_vf32_add_m
#define LTN_STORE_M lt_vf32_store_m
#define LTN_PVIEW lt_frusta_view_f32_t
#define LTN_PVT lt_frusta_vtable_f32_t
#define LTN_PFR lt_frusta_prim16_f32_t
#define LTN_SQV float
#define LTN_SW float
#define LTN_STQ f_stq_t
#define LTN_PTQ1 f_ptq1
#define LTN_SW_SIGN(x) (((x) > 0.0f) - ((x) < 0.0f))
#define LTN_SW_NEG(x) (-(x))
#define LTN_PNRM1 f_pnrm1
#define LTN_ASAT(ax, ay, az) ((void)(ax), (void)(ay), (void)(az), 0)
#define LTN_PMARG1 f_pmarg1
#define LTN_PMARG1_WT f_pmarg1_wt
#define LTN_PBASE1 f_pbase1
#define LTN_PBASEV f_pbasev
#define LTN_PDIR_OK f_pdir_ok
#define LTN_PDELTA f_pdelta
#define LTN_PFINITE f_finite
#define LTN_PTMAX0 3.0e38f
#define LTN_DADD lt_vf32_add
#define LTN_DSADD(a, b) ((a) + (b))
#define LTN_DMIN lt_vf32_min
#define LTN_DMAX lt_vf32_max
#define LTN_DCMPGE0(k, a) lt_vf32_cmpge_m((k), (a), lt_vf32_set1(0.0f))
#define LTN_DCMPLE0(k, a) lt_vf32_cmple_m((k), (a), lt_vf32_set1(0.0f))
#define LTN_DCMPLT0(k, a) lt_vf32_cmplt_m((k), (a), lt_vf32_set1(0.0f))
#define LTN_DCMPGT0(k, a) lt_vf32_cmpgt_m((k), (a), lt_vf32_set1(0.0f))
#define LTN_CMPEQ_M lt_vf32_cmpeq_m
#define LTN_NEXTUP_M f_nextup_m
#include "lt_frusta.inc"

#endif /* LT_CFG_FLOAT32 */
