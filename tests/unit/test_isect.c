/* test_isect.c - cmocka tests of the packet kernels of lt_isect.h (slab test, Moller-Trumbore,
 * chunk scene) in s15.16 and float32, against references written independently in double.
 * The references take the kernels' own inputs (fixed or float values, converted exactly to double),
 * so input quantisation is never counted as error. A classification disagreement is allowed only
 * when the reference margin is within the error bound derived below from the format; every test
 * prints its case count, disagreements (allowed / unexplained) and max |t| error against the bound.
 * Builds: host, sim, asan (any LT_COST_MODE); the float32 half only with LT_CFG_FLOAT32.
 *
 * Slab bound (s15.16). setup gives rd = round(2^46 / d_raw) / 2^16, so |rd - 1/D| <= 2^-17 while
 * |D| >= 2^-15 (D the s1.30 direction as a real). Each plane distance t = round((P - O) * rd) has
 * |t - (P - O) / D| <= 2^-17 |P - O| + 2^-17 = 2^-17 (1 + |P - O|), i.e. half an ulp times
 * (1 + |plane - origin|) in world units; P - O is exact for |coords| <= 2^12. The interval ends are
 * max/min of such values and of the exact tmin/tmax, so an end is off by at most the bound of the
 * plane that defines it, and the order of two ends a, b from different axes (or tmin/tmax) can flip
 * only if |a - b| <= e_a + e_b. Rays with 0 < |D| < 2^-15 (saturated reciprocal) are kept out of
 * the random sets: their t has no such bound (see test_slab_parallel for what that does).
 * Slab bound (float32): each t has relative error about 3 * 2^-24 (subtraction, reciprocal,
 * product); we allow the brief's relative 1e-5 per end.
 *
 * Triangle bound (s15.16). The kernel rounds pvec = d x e2 to s15.16 (|error| <= 2^-17 per
 * component, norm <= sqrt3 2^-17) and qvec = tvec x e1 to s25.6 as lt_isect.h documents (QV_FRAC
 * below: error 2^-(QV_FRAC+1) per component, norm <= sqrt3 2^-7); v is floored to 32 fractional
 * bits (2^-32); det, u and tnum are then exact. Hence |d det| <= |e1| sqrt3 2^-17, |d u| <= |tvec|
 * sqrt3 2^-17, |d v| <= sqrt3 2^-7 + 2^-32, |d tnum| <= |e2| sqrt3 2^-7, and in barycentric units
 * each of u, v, 1 - u - v moves by at most (du + dv + ddet (1 + |u| + |v|)) / (|det| - ddet);
 * t = tnum / det moves by at most (dtnum + |t| ddet) / (|det| - ddet) + 2^-17 (final rounding)
 * + |t| 2^-30 (det pre-shift). |det| <= 2 ddet means the format cannot tell the side at all.
 * Triangle bound (float32): relative 1e-5 of the same error terms' magnitudes (|tvec||e|,
 * |e1||e2|).
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lt/lt_isect.h"
#include "lt/lt_bvh.h"
/* the core's internal triangle header (the per-lane body the kernels share) */
#include "../../firmware/core/object/lt_tri.h"
#include "io/lt_fx_float.h"
#include "lt_test_util.h"

#define FMT_Q16 0
#define FMT_F32 1
#define ULP16 (1.0 / 65536.0)
#define SQRT3 1.7320508075688772
#define REL_F32 1e-5
#define QV_FRAC 6 /* qvec fractional bits documented by lt_tri16_q16 (s25.6); update with it */

/* ---- exact double images of kernel inputs ------------------------------------------------- */

typedef struct dray {
    double o[3], d[3], tmin, tmax;
} dray_t;

typedef struct dbox {
    double lo[3], hi[3];
} dbox_t;

typedef struct dtri {
    double v0[3], e1[3], e2[3];
} dtri_t;

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double norm3(const double a[3]) { return sqrt(dot3(a, a)); }

static void normalize(double d[3])
{
    double n = norm3(d);
    d[0] /= n;
    d[1] /= n;
    d[2] /= n;
}

static void rng_unit(ltt_rng_t *r, double d[3])
{
    do {
        d[0] = ltt_rng_uniform(r, -1, 1);
        d[1] = ltt_rng_uniform(r, -1, 1);
        d[2] = ltt_rng_uniform(r, -1, 1);
    } while (dot3(d, d) > 1.0 || dot3(d, d) < 1e-4);
    normalize(d);
}

/* ---- packet lanes ------------------------------------------------------------------------- */

static lt_vq16_t *q16_o(lt_ray16_q16_t *p, int a)
{
    return a == 0 ? &p->ox : (a == 1 ? &p->oy : &p->oz);
}

static lt_vq30_t *q16_d(lt_ray16_q16_t *p, int a)
{
    return a == 0 ? &p->dx : (a == 1 ? &p->dy : &p->dz);
}

/* Lane i of a fixed-point packet from a double ray (d unit). Every other ray normalises through
 * lt_q16_normalize3 instead of a direct double -> s1.30 conversion. ex receives the exact
 * values. */
static void q16_lane(lt_ray16_q16_t *p, int i, const double o[3], const double d[3], double tmax,
                     int via_normalize3, dray_t *ex)
{
    lt_q30_t dq[3];
    int a;
    if (via_normalize3) {
        lt_q16_t v[3];
        for (a = 0; a < 3; a++)
            v[a] = lt_q16_from_double_sat(d[a] * 1000.0);
        if (lt_q16_normalize3(v, dq) != LT_OK)
            dq[0] = dq[1] = dq[2] = 0;
    } else {
        for (a = 0; a < 3; a++)
            dq[a] = lt_q30_from_double_sat(d[a]);
    }
    for (a = 0; a < 3; a++) {
        q16_o(p, a)->l[i] = lt_q16_from_double_sat(o[a]);
        q16_d(p, a)->l[i] = dq[a];
        ex->o[a] = lt_q16_to_double(q16_o(p, a)->l[i]);
        ex->d[a] = lt_q30_to_double(dq[a]);
    }
    p->tmin.l[i] = 0;
    p->tmax.l[i] = lt_q16_from_double_sat(tmax);
    ex->tmin = 0;
    ex->tmax = lt_q16_to_double(p->tmax.l[i]);
}

static void q16_box(const double lo[3], const double hi[3], lt_aabb_q16_t *b, dbox_t *ex)
{
    int a;
    for (a = 0; a < 3; a++) {
        b->lo[a] = lt_q16_from_double_sat(lo[a]);
        b->hi[a] = lt_q16_from_double_sat(hi[a]);
        ex->lo[a] = lt_q16_to_double(b->lo[a]);
        ex->hi[a] = lt_q16_to_double(b->hi[a]);
    }
}

/* Triangle from three vertices: vertices rounded to s15.16, edges exact differences. */
static void q16_tri(const double v[3][3], lt_tri_q16_t *t, dtri_t *ex)
{
    int a;
    for (a = 0; a < 3; a++) {
        lt_q16_t p0 = lt_q16_from_double_sat(v[0][a]), p1 = lt_q16_from_double_sat(v[1][a]);
        lt_q16_t p2 = lt_q16_from_double_sat(v[2][a]);
        t->v0[a] = p0;
        t->e1[a] = p1 - p0;
        t->e2[a] = p2 - p0;
        ex->v0[a] = lt_q16_to_double(p0);
        ex->e1[a] = lt_q16_to_double(t->e1[a]);
        ex->e2[a] = lt_q16_to_double(t->e2[a]);
    }
}

/* True if the s1.30 reciprocal of lane i saturated on some axis with a nonzero direction. */
static int q16_rd_saturated(const lt_ray16_q16_t *p, int i)
{
    int a;
    for (a = 0; a < 3; a++) {
        int32_t d = (a == 0 ? p->dx : (a == 1 ? p->dy : p->dz)).l[i];
        if (d != 0 && (d > -32768 && d < 32768))
            return 1;
    }
    return 0;
}

#if LT_CFG_FLOAT32
static lt_vf32_t *f32_o(lt_ray16_f32_t *p, int a)
{
    return a == 0 ? &p->ox : (a == 1 ? &p->oy : &p->oz);
}

static lt_vf32_t *f32_d(lt_ray16_f32_t *p, int a)
{
    return a == 0 ? &p->dx : (a == 1 ? &p->dy : &p->dz);
}

static void f32_lane(lt_ray16_f32_t *p, int i, const double o[3], const double d[3], double tmax,
                     dray_t *ex)
{
    int a;
    for (a = 0; a < 3; a++) {
        f32_o(p, a)->l[i] = (float)o[a];
        f32_d(p, a)->l[i] = (float)d[a];
        ex->o[a] = (double)f32_o(p, a)->l[i];
        ex->d[a] = (double)f32_d(p, a)->l[i];
    }
    p->tmin.l[i] = 0.0f;
    p->tmax.l[i] = (float)tmax;
    ex->tmin = 0.0;
    ex->tmax = (double)p->tmax.l[i];
}

static void f32_box(const double lo[3], const double hi[3], lt_aabb_f32_t *b, dbox_t *ex)
{
    int a;
    for (a = 0; a < 3; a++) {
        b->lo[a] = (float)lo[a];
        b->hi[a] = (float)hi[a];
        ex->lo[a] = (double)b->lo[a];
        ex->hi[a] = (double)b->hi[a];
    }
}

static void f32_tri(const double v[3][3], lt_tri_f32_t *t, dtri_t *ex)
{
    int a;
    for (a = 0; a < 3; a++) {
        t->v0[a] = (float)v[0][a];
        t->e1[a] = (float)(v[1][a] - v[0][a]);
        t->e2[a] = (float)(v[2][a] - v[0][a]);
        ex->v0[a] = (double)t->v0[a];
        ex->e1[a] = (double)t->e1[a];
        ex->e2[a] = (double)t->e2[a];
    }
}
#endif

/* ---- classification with margins ---------------------------------------------------------- */

/* A classification is a conjunction of conditions "margin >= 0", each known to bound. */
#define MAX_COND 32
typedef struct verdict {
    int hit;                 /* reference result */
    int n;                   /* conditions */
    double m[MAX_COND];      /* margins */
    double e[MAX_COND];      /* their error bounds */
    double t, t_bound;       /* reference t (tnear or hit distance) and its bound */
} verdict_t;

static void cond(verdict_t *v, double margin, double bound)
{
    v->m[v->n] = margin;
    v->e[v->n] = bound;
    v->n++;
}

/* Could a kernel within the bounds have answered `got`? */
static int explainable(const verdict_t *v, int got)
{
    int i;
    if (got == v->hit)
        return 1;
    if (v->hit) { /* a hit became a miss: one condition close enough to flip */
        for (i = 0; i < v->n; i++)
            if (v->m[i] <= v->e[i])
                return 1;
        return 0;
    }
    for (i = 0; i < v->n; i++) /* a miss became a hit: every failed condition close enough */
        if (v->m[i] < 0 && -v->m[i] > v->e[i])
            return 0;
    return 1;
}

/* Slab reference in double. Ends of the interval are tmin, tmax and the per-axis near/far plane
 * distances; conditions are "far end - near end >= 0" for pairs from different axes (a pair from
 * one axis is ordered by construction in the kernel). A zero direction component makes the axis a
 * pure inside/outside test of the origin (closed slab), with no error. */
static verdict_t slab_ref(const dray_t *r, const dbox_t *b, int fmt)
{
    double lo_t[4], hi_t[4], lo_e[4], hi_e[4];
    int ax[4], n = 0, i, j, a;
    verdict_t v;
    memset(&v, 0, sizeof v);
    lo_t[0] = r->tmin;
    hi_t[0] = r->tmax;
    lo_e[0] = hi_e[0] = 0;
    ax[0] = -1;
    n = 1;
    for (a = 0; a < 3; a++) {
        double t0, t1, e0, e1;
        if (r->d[a] == 0) {
            /* parallel: inside the closed slab or not, exactly */
            cond(&v, r->o[a] - b->lo[a], 0);
            cond(&v, b->hi[a] - r->o[a], 0);
            continue;
        }
        t0 = (b->lo[a] - r->o[a]) / r->d[a];
        t1 = (b->hi[a] - r->o[a]) / r->d[a];
        if (fmt == FMT_Q16) {
            e0 = 0.5 * ULP16 * (1.0 + fabs(b->lo[a] - r->o[a]));
            e1 = 0.5 * ULP16 * (1.0 + fabs(b->hi[a] - r->o[a]));
        } else {
            e0 = REL_F32 * fabs(t0);
            e1 = REL_F32 * fabs(t1);
        }
        lo_t[n] = t0 < t1 ? t0 : t1;
        lo_e[n] = t0 < t1 ? e0 : e1;
        hi_t[n] = t0 < t1 ? t1 : t0;
        hi_e[n] = t0 < t1 ? e1 : e0;
        ax[n++] = a;
    }
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++)
            if (i == 0 || j == 0 || ax[i] != ax[j])
                cond(&v, hi_t[i] - lo_t[j], hi_e[i] + lo_e[j]);
    v.hit = 1;
    for (i = 0; i < v.n; i++)
        if (v.m[i] < 0)
            v.hit = 0;
    /* tnear = the largest near end; its error is at most the largest near-end bound */
    v.t = lo_t[0];
    v.t_bound = 0;
    for (i = 0; i < n; i++) {
        if (lo_t[i] > v.t)
            v.t = lo_t[i];
        if (lo_e[i] > v.t_bound)
            v.t_bound = lo_e[i];
    }
    return v;
}

/* Moller-Trumbore in double (two-sided, edges inclusive, tmin < t < tmax), with the bounds of the
 * file header. det == 0 or |det| within its own error: a miss that any answer may contradict. */
static verdict_t tri_ref(const dray_t *r, const dtri_t *tr, int fmt)
{
    double p[3], tv[3], q[3], det, u, w, tn, ub, vb, t;
    double ddet, du, dv, dtn, dd, bb;
    int a;
    verdict_t v;
    memset(&v, 0, sizeof v);
    cross3(r->d, tr->e2, p);
    det = dot3(tr->e1, p);
    for (a = 0; a < 3; a++)
        tv[a] = r->o[a] - tr->v0[a];
    u = dot3(tv, p);
    cross3(tv, tr->e1, q);
    w = dot3(r->d, q);
    tn = dot3(tr->e2, q);
    if (fmt == FMT_Q16) {
        ddet = norm3(tr->e1) * SQRT3 * ldexp(1.0, -17);
        du = norm3(tv) * SQRT3 * ldexp(1.0, -17);
        dv = SQRT3 * ldexp(1.0, -(QV_FRAC + 1)) + ldexp(1.0, -32);
        dtn = norm3(tr->e2) * SQRT3 * ldexp(1.0, -(QV_FRAC + 1));
    } else {
        double l1 = norm3(tr->e1), l2 = norm3(tr->e2), lt = norm3(tv);
        ddet = REL_F32 * l1 * l2;
        du = REL_F32 * lt * l2;
        dv = REL_F32 * lt * l1;
        dtn = REL_F32 * lt * l1 * l2;
    }
    if (fabs(det) <= 2.0 * ddet) {
        v.hit = 0;
        cond(&v, -1.0, HUGE_VAL); /* side undecidable in this format: anything goes */
        return v;
    }
    ub = u / det;
    vb = w / det;
    t = tn / det;
    dd = fabs(det) - ddet;
    bb = (du + dv + ddet * (1.0 + fabs(ub) + fabs(vb))) / dd;
    v.t = t;
    v.t_bound = (dtn + fabs(t) * ddet) / dd +
                (fmt == FMT_Q16 ? 0.5 * ULP16 + fabs(t) * ldexp(1.0, -30) : REL_F32 * fabs(t));
    cond(&v, ub, bb);
    cond(&v, vb, bb);
    cond(&v, 1.0 - ub - vb, bb);
    cond(&v, t - r->tmin, v.t_bound);
    cond(&v, r->tmax - t, v.t_bound);
    v.hit = ub >= 0 && vb >= 0 && ub + vb <= 1.0 && t > r->tmin && t < r->tmax;
    return v;
}

/* ---- per-test tallies --------------------------------------------------------------------- */

typedef struct tally {
    const char *name;
    unsigned long cases, hits, close, allowed, bad, t_bad; /* close: a margin within its bound */
    double max_terr, max_terr_ulp; /* max |t - t_ref| in world units; in units of the bound */
} tally_t;

static void tally_init(tally_t *t, const char *name)
{
    memset(t, 0, sizeof *t);
    t->name = name;
}

static void tally_case(tally_t *ty, const verdict_t *v, int got, int have_t, double t_got,
                       const char *what, int lane)
{
    int i;
    ty->cases++;
    ty->hits += got != 0;
    for (i = 0; i < v->n; i++) {
        if (fabs(v->m[i]) <= v->e[i]) {
            ty->close++;
            break;
        }
    }
    if (got != v->hit) {
        if (explainable(v, got)) {
            ty->allowed++;
        } else if (ty->bad++ < 6) {
            ltt_report("  FAIL %s: %s lane %d: got %s, reference %s (t_ref %.9g)\n", ty->name, what,
                       lane, got ? "hit" : "miss", v->hit ? "hit" : "miss", v->t);
        }
        return;
    }
    if (got && have_t) {
        double e = fabs(t_got - v->t);
        if (e > ty->max_terr)
            ty->max_terr = e;
        if (v->t_bound > 0 && e / v->t_bound > ty->max_terr_ulp)
            ty->max_terr_ulp = e / v->t_bound;
        if (e > v->t_bound && ty->t_bad++ < 6)
            ltt_report("  FAIL %s: %s lane %d: t %.9g vs reference %.9g (bound %.3g)\n", ty->name,
                       what, lane, t_got, v->t, v->t_bound);
    }
}

static void tally_print(const tally_t *t, const char *bound_text)
{
    ltt_report("%s: %lu cases, %lu hits, %lu within the bound of a boundary, %lu disagreements "
               "(all such), %lu unexplained; max |t err| %.3g (%.3g of its bound; bound %s)%s\n",
               t->name, t->cases, t->hits, t->close, t->allowed, t->bad, t->max_terr,
               t->max_terr_ulp, bound_text, t->t_bad ? ", t OUT OF BOUND" : "");
}

/* ---- slab: random rays and boxes ---------------------------------------------------------- */

#define SLAB_PACKETS 600 /* x 16 rays, per path */

/* One random ray/box pair of category c (0 aimed at the box, 1 random direction, 2 origin inside,
 * 3 box behind, 4 grazing an edge within 1e-3 (log-uniform down to 1e-9), 5 zero-thickness box
 * aimed at), as doubles. tmax is 1000 or uniform in [0, 400]. Zero direction components are left
 * to test_slab_parallel. */
static void slab_case(ltt_rng_t *r, unsigned c, double lo[3], double hi[3], double o[3],
                      double d[3], double *tmax)
{
    double tgt[3];
    int a;
    for (a = 0; a < 3; a++) {
        double s = ltt_rng_uniform(r, 0.01, 60);
        lo[a] = ltt_rng_uniform(r, -150, 150);
        hi[a] = lo[a] + s;
        o[a] = ltt_rng_uniform(r, -300, 300);
        tgt[a] = ltt_rng_uniform(r, lo[a], hi[a]);
    }
    *tmax = ltt_rng_below(r, 2) ? 1000.0 : ltt_rng_uniform(r, 0, 400);
    switch (c) {
    case 0:
    case 5:
        if (c == 5) {
            a = (int)ltt_rng_below(r, 3);
            hi[a] = tgt[a] = lo[a];
        }
        for (a = 0; a < 3; a++)
            d[a] = tgt[a] + ltt_rng_uniform(r, -2, 2) - o[a];
        break;
    case 2:
        for (a = 0; a < 3; a++)
            o[a] = ltt_rng_uniform(r, lo[a], hi[a]);
        rng_unit(r, d);
        break;
    case 3:
        for (a = 0; a < 3; a++)
            d[a] = o[a] - tgt[a];
        break;
    case 4: {
        /* a point on a random edge, nudged by < 1e-3, and a ray through it */
        int ax = (int)ltt_rng_below(r, 3);
        double back;
        for (a = 0; a < 3; a++) {
            double scale;
            if (a != ax)
                tgt[a] = ltt_rng_below(r, 2) ? lo[a] : hi[a];
            scale = pow(10.0, -6.0 * ltt_rng_unit(r));
            tgt[a] += ltt_rng_uniform(r, -1e-3, 1e-3) / SQRT3 * scale;
        }
        rng_unit(r, d);
        back = ltt_rng_uniform(r, 1, 200);
        for (a = 0; a < 3; a++)
            o[a] = tgt[a] - back * d[a];
        break;
    }
    default:
        rng_unit(r, d);
        break;
    }
    if (dot3(d, d) < 1e-12)
        d[0] = 1;
    normalize(d);
    /* keep clear of zero and of the saturated-reciprocal band |d| < 2^-15 (see the header) */
    for (a = 0; a < 3; a++)
        if (fabs(d[a]) < 1e-4)
            d[a] = d[a] < 0 ? -1e-4 : 1e-4;
    normalize(d);
}

#define N_SLAB_CAT 6

static void test_slab_random_q16(void **state)
{
    ltt_rng_t r;
    tally_t ty;
    unsigned pk;
    int i;
    (void)state;
    ltt_rng_seed(&r, 1001);
    tally_init(&ty, "lt_slab16_q16 random");
    for (pk = 0; pk < SLAB_PACKETS; pk++) {
        lt_ray16_q16_t p;
        lt_aabb_q16_t box[LT_LANES];
        dbox_t dbox[LT_LANES];
        dray_t dr[LT_LANES];
        lt_vq16_t tn;
        lt_mask16_t hit;
        memset(&p, 0, sizeof p);
        for (i = 0; i < LT_LANES; i++) {
            double lo[3], hi[3], o[3], d[3], tmax;
            slab_case(&r, (pk * LT_LANES + (unsigned)i) % N_SLAB_CAT, lo, hi, o, d, &tmax);
            q16_lane(&p, i, o, d, tmax, i & 1, &dr[i]);
            q16_box(lo, hi, &box[i], &dbox[i]);
        }
        lt_ray16_q16_setup(&p);
        /* one box per call: lane i's own box, tested with only lane i active... and the whole
         * packet against lane 0's box, so every lane sees every mask position */
        for (i = 0; i < LT_LANES; i++) {
            verdict_t v;
            if (q16_rd_saturated(&p, i))
                continue;
            tn = lt_vq16_set1(0x5A5A5A5A);
            hit = lt_slab16_q16(&p, (lt_mask16_t)(1u << i), &box[i], &tn);
            v = slab_ref(&dr[i], &dbox[i], FMT_Q16);
            tally_case(&ty, &v, LTT_ON(hit, i), 1, lt_q16_to_double(tn.l[i]), "own box", i);
            if ((hit & ~(1u << i)) != 0 || (!LTT_ON(hit, i) && tn.l[i] != 0x5A5A5A5A)) {
                ty.bad++;
                ltt_report("  FAIL %s: inactive lane hit or tnear written on a miss\n", ty.name);
            }
        }
        tn = lt_vq16_set1(0x5A5A5A5A);
        hit = lt_slab16_q16(&p, LT_MASK_ALL, &box[0], &tn);
        for (i = 0; i < LT_LANES; i++) {
            verdict_t v;
            if (q16_rd_saturated(&p, i))
                continue;
            v = slab_ref(&dr[i], &dbox[0], FMT_Q16);
            tally_case(&ty, &v, LTT_ON(hit, i), 1, lt_q16_to_double(tn.l[i]), "box 0", i);
        }
    }
    tally_print(&ty, "2^-17 (1 + |P - O|) per interval end");
    assert_int_equal(ty.bad + ty.t_bad, 0);
}

#if LT_CFG_FLOAT32
static void test_slab_random_f32(void **state)
{
    ltt_rng_t r;
    tally_t ty;
    unsigned pk;
    int i;
    (void)state;
    ltt_rng_seed(&r, 1001);
    tally_init(&ty, "lt_slab16_f32 random");
    for (pk = 0; pk < SLAB_PACKETS; pk++) {
        lt_ray16_f32_t p;
        lt_aabb_f32_t box[LT_LANES];
        dbox_t dbox[LT_LANES];
        dray_t dr[LT_LANES];
        lt_vf32_t tn;
        lt_mask16_t hit;
        memset(&p, 0, sizeof p);
        for (i = 0; i < LT_LANES; i++) {
            double lo[3], hi[3], o[3], d[3], tmax;
            slab_case(&r, (pk * LT_LANES + (unsigned)i) % N_SLAB_CAT, lo, hi, o, d, &tmax);
            f32_lane(&p, i, o, d, tmax, &dr[i]);
            f32_box(lo, hi, &box[i], &dbox[i]);
        }
        lt_ray16_f32_setup(&p);
        for (i = 0; i < LT_LANES; i++) {
            verdict_t v;
            tn = lt_vf32_set1(-7.0f);
            hit = lt_slab16_f32(&p, (lt_mask16_t)(1u << i), &box[i], &tn);
            v = slab_ref(&dr[i], &dbox[i], FMT_F32);
            tally_case(&ty, &v, LTT_ON(hit, i), 1, (double)tn.l[i], "own box", i);
            if ((hit & ~(1u << i)) != 0 || (!LTT_ON(hit, i) && tn.l[i] != -7.0f)) {
                ty.bad++;
                ltt_report("  FAIL %s: inactive lane hit or tnear written on a miss\n", ty.name);
            }
        }
        tn = lt_vf32_set1(-7.0f);
        hit = lt_slab16_f32(&p, LT_MASK_ALL, &box[0], &tn);
        for (i = 0; i < LT_LANES; i++) {
            verdict_t v = slab_ref(&dr[i], &dbox[0], FMT_F32);
            tally_case(&ty, &v, LTT_ON(hit, i), 1, (double)tn.l[i], "box 0", i);
        }
    }
    tally_print(&ty, "relative 1e-5 per interval end");
    assert_int_equal(ty.bad + ty.t_bad, 0);
}
#endif

/* ---- slab: axis-parallel rays ------------------------------------------------------------- */

/* Box [10, 20]^3. On the parallel axis `par` the origin sits at one of the offsets below from a
 * slab plane; the ray runs along another axis (or a diagonal in the plane of two others) from
 * 5 units (near) or 200 units (far) outside the box, tmax = 1000. Expected: hit iff
 * lo <= o_par <= hi, the closed slab, exactly (the zero component makes the slab an exact test). */
static const struct {
    const char *name;
    int plane;  /* 0: relative to lo, 1: relative to hi */
    double off; /* world units */
    int ulps;   /* or: this many ulps of the path's format */
} par_pos[] = {
    { "lo - 1", 0, -1.0, 0 },     { "lo - 1e-3", 0, -1e-3, 0 }, { "lo - 1ulp", 0, 0, -1 },
    { "on lo", 0, 0, 0 },         { "lo + 1ulp", 0, 0, 1 },     { "lo + 1e-3", 0, 1e-3, 0 },
    { "mid", 0, 5.0, 0 },         { "hi - 1e-3", 1, -1e-3, 0 }, { "hi - 1ulp", 1, 0, -1 },
    { "on hi", 1, 0, 0 },         { "hi + 1ulp", 1, 0, 1 },     { "hi + 1e-3", 1, 1e-3, 0 },
    { "hi + 1", 1, 1.0, 0 },
};
#define N_PAR (sizeof par_pos / sizeof par_pos[0])
#define N_LAYOUT 12u /* per parallel axis: 2 run axes x (+run, -run, diagonal) x (near, far) */

static void par_ray(int par, unsigned layout, double o[3], double d[3])
{
    int run = (par + 1 + (int)(layout % 2u)) % 3, third = 3 - par - run;
    unsigned kind = layout / 2u % 3u;
    double back = layout >= 6u ? 200.0 : 5.0;
    d[0] = d[1] = d[2] = 0;
    o[third] = 15.0;
    if (kind == 0) {
        d[run] = 1.0;
        o[run] = 10.0 - back;
    } else if (kind == 1) {
        d[run] = -1.0;
        o[run] = 20.0 + back;
    } else {
        /* diagonal (0.6, 0.8) in (run, third), through the box centre at (15, 15) */
        d[run] = 0.6;
        d[third] = 0.8;
        o[run] = 15.0 - 0.6 * (back + 10.0);
        o[third] = 15.0 - 0.8 * (back + 10.0);
    }
}

static void test_slab_parallel(void **state)
{
    static const double lo3[3] = { 10, 10, 10 }, hi3[3] = { 20, 20, 20 };
    unsigned long cases = 0, bad_q = 0, bad_f = 0;
    unsigned wrong_q[N_PAR], wrong_f[N_PAR], wrong_fn[N_PAR];
    unsigned par, layout, k;
    int want[N_PAR];
    (void)state;
    memset(wrong_q, 0, sizeof wrong_q);
    memset(wrong_f, 0, sizeof wrong_f);
    memset(wrong_fn, 0, sizeof wrong_fn);
    for (k = 0; k < N_PAR; k++)
        want[k] = par_pos[k].plane == 0 ? (par_pos[k].off + par_pos[k].ulps >= 0)
                                        : (par_pos[k].off + par_pos[k].ulps <= 0);
    for (par = 0; par < 3; par++) {
        for (layout = 0; layout < N_LAYOUT; layout++) {
            lt_ray16_q16_t p;
            lt_aabb_q16_t bq;
            dbox_t db;
            dray_t dr;
            lt_vq16_t tn = lt_vq16_set1(0);
            lt_mask16_t hq;
#if LT_CFG_FLOAT32
            lt_ray16_f32_t pf, pfn;
            lt_aabb_f32_t bf;
            lt_vf32_t tf = lt_vf32_set1(0.0f);
            lt_mask16_t hf, hfn;
#endif
            memset(&p, 0, sizeof p);
            q16_box(lo3, hi3, &bq, &db);
#if LT_CFG_FLOAT32
            memset(&pf, 0, sizeof pf);
            f32_box(lo3, hi3, &bf, &db);
#endif
            for (k = 0; k < N_PAR; k++) {
                double o[3], d[3], base = par_pos[k].plane ? hi3[par] : lo3[par];
                par_ray((int)par, layout, o, d);
                o[par] = base + par_pos[k].off;
                q16_lane(&p, (int)k, o, d, 1000.0, 0, &dr);
                q16_o(&p, (int)par)->l[k] += par_pos[k].ulps;
#if LT_CFG_FLOAT32
                f32_lane(&pf, (int)k, o, d, 1000.0, &dr);
                if (par_pos[k].ulps != 0)
                    f32_o(&pf, (int)par)->l[k] =
                        nextafterf((float)base, par_pos[k].ulps > 0 ? HUGE_VALF : -HUGE_VALF);
#endif
            }
            lt_ray16_q16_setup(&p);
            hq = lt_slab16_q16(&p, (lt_mask16_t)((1u << N_PAR) - 1u), &bq, &tn);
#if LT_CFG_FLOAT32
            /* float: the same rays with +0 direction components, then with -0 */
            pfn = pf;
            for (k = 0; k < N_PAR; k++)
                f32_d(&pfn, (int)par)->l[k] = -0.0f;
            lt_ray16_f32_setup(&pf);
            lt_ray16_f32_setup(&pfn);
            hf = lt_slab16_f32(&pf, (lt_mask16_t)((1u << N_PAR) - 1u), &bf, &tf);
            hfn = lt_slab16_f32(&pfn, (lt_mask16_t)((1u << N_PAR) - 1u), &bf, &tf);
#endif
            for (k = 0; k < N_PAR; k++) {
                cases++;
                if (LTT_ON(hq, k) != want[k]) {
                    bad_q++;
                    wrong_q[k]++;
                }
#if LT_CFG_FLOAT32
                if (LTT_ON(hf, k) != want[k]) {
                    bad_f++;
                    wrong_f[k]++;
                }
                if (LTT_ON(hfn, k) != want[k]) {
                    bad_f++;
                    wrong_fn[k]++;
                }
#endif
            }
        }
    }
    for (k = 0; k < N_PAR; k++) {
        if (wrong_q[k] != 0)
            ltt_report("  FAIL lt_slab16_q16 axis-parallel, origin %-9s: %2u/%u layouts say %s\n",
                       par_pos[k].name, wrong_q[k], 3u * N_LAYOUT, want[k] ? "miss" : "hit");
        if (wrong_f[k] != 0 || wrong_fn[k] != 0)
            ltt_report("  FAIL lt_slab16_f32 axis-parallel, origin %-9s: %2u/%u layouts (d = +0), "
                       "%2u/%u (d = -0) say %s\n", par_pos[k].name, wrong_f[k], 3u * N_LAYOUT,
                       wrong_fn[k], 3u * N_LAYOUT, want[k] ? "miss" : "hit");
    }
    ltt_report("lt_slab16_q16 axis-parallel: %lu cases (3 axes x %u layouts x %u origins: +-1, "
               "+-1e-3, +-1 ulp, on lo/hi, mid), %lu wrong (bound 0: closed slab)\n", cases,
               N_LAYOUT, (unsigned)N_PAR, bad_q);
#if LT_CFG_FLOAT32
    ltt_report("lt_slab16_f32 axis-parallel: %lu cases x (d = +0, d = -0), %lu wrong (bound 0)\n",
               cases, bad_f);
#endif
    assert_int_equal(bad_q + bad_f, 0);
}

/* Rays with a tiny nonzero direction component (|d| < 2^-15: the s15.16 reciprocal saturates).
 * The documented contract: "t saturates, which keeps the classification". */
/* Far origins: plane - origin beyond s15.16 (boxes up to 30,000 units out, origins up to 32,000
 * units out on any side), which the slab test clamps before the product. No double reference
 * applies there (the clamp is the documented behaviour); each lane of lt_slab16_q16 must equal
 * the single-ray test lt_slab1_q16 of the same ray bit for bit (hit and tnear), the arithmetic the
 * wide tree's node test and every backend share. */
static void test_slab_far_q16(void **state)
{
    ltt_rng_t r;
    unsigned pk, cases = 0, hits = 0, far = 0, bad = 0;
    int i, a;
    (void)state;
    ltt_rng_seed(&r, 1201);
    for (pk = 0; pk < 400; pk++) {
        lt_ray16_q16_t p;
        lt_aabb_q16_t box;
        lt_vq16_t tn;
        lt_mask16_t hit;
        double lo[3], hi[3];
        memset(&p, 0, sizeof p);
        for (a = 0; a < 3; a++) {
            double c = ltt_rng_uniform(&r, -30000.0, 30000.0), h = ltt_rng_uniform(&r, 1.0, 2000.0);
            lo[a] = c - h;
            hi[a] = c + h;
        }
        for (i = 0; i < LT_LANES; i++) {
            double o[3], d[3], tgt[3];
            dray_t dr;
            for (a = 0; a < 3; a++) {
                o[a] = ltt_rng_uniform(&r, -32000.0, 32000.0);
                /* aim at the box (a hit unless the clamp moves an end) or anywhere */
                tgt[a] = i % 4 != 3 ? ltt_rng_uniform(&r, lo[a], hi[a])
                                    : ltt_rng_uniform(&r, -32000.0, 32000.0);
                d[a] = tgt[a] - o[a];
            }
            normalize(d);
            for (a = 0; a < 3; a++)
                if (fabs(d[a]) < 1e-4)
                    d[a] = d[a] < 0 ? -1e-4 : 1e-4;
            normalize(d);
            q16_lane(&p, i, o, d, 30000.0, 0, &dr);
        }
        lt_ray16_q16_setup(&p);
        {
            dbox_t unused;
            q16_box(lo, hi, &box, &unused);
        }
        tn = lt_vq16_set1(0x5A5A5A5A);
        hit = lt_slab16_q16(&p, LT_MASK_ALL, &box, &tn);
        for (i = 0; i < LT_LANES; i++) {
            lt_ray1_q16_t r1;
            lt_q16_t t1 = 0x5A5A5A5A;
            int h1;
            memset(&r1, 0, sizeof r1);
            for (a = 0; a < 3; a++) {
                int64_t df;
                r1.o[a] = q16_o(&p, a)->l[i];
                r1.d[a] = q16_d(&p, a)->l[i];
                df = (int64_t)box.hi[a] - r1.o[a];
                far += df > INT32_MAX || (int64_t)box.lo[a] - r1.o[a] < INT32_MIN;
            }
            r1.tmin = p.tmin.l[i];
            r1.tmax = p.tmax.l[i];
            lt_ray1_q16_setup(&r1);
            h1 = lt_slab1_q16(&r1, &box, &t1);
            cases++;
            hits += (unsigned)h1;
            if (h1 != LTT_ON(hit, i) || (h1 && t1 != tn.l[i])) {
                if (bad++ < 5)
                    ltt_report("  FAIL far slab: packet %u lane %d: hit %d/%d tnear %d/%d\n", pk, i,
                               (int)LTT_ON(hit, i), h1, tn.l[i], t1);
            }
        }
    }
    ltt_report("lt_slab16_q16 far origins vs lt_slab1_q16 per lane: %u cases (%u axis ends with "
               "plane - origin beyond s15.16), %u hits, %u differ (bound 0)\n", cases, far, hits,
               bad);
    assert_true(far > cases / 4);
    assert_int_equal(bad, 0);
}

static void test_slab_near_parallel(void **state)
{
    static const double lo3[3] = { 10, 0, 0 }, hi3[3] = { 20, 1, 1 };
    static const double dy[] = { 1e-5, 2e-5, 3e-6, 9.5367431640625e-07 /* 2^-20 */, -1e-5 };
    static const double oy[] = { -1e-4, -1e-3, -0.01, 1.0001, 1.001, 0.5 };
    unsigned i, j, n = 0;
    unsigned long bad = 0, cases = 0;
    lt_ray16_q16_t p;
    lt_aabb_q16_t bq;
    dbox_t db;
    dray_t dr[LT_LANES];
    (void)state;
    q16_box(lo3, hi3, &bq, &db);
    memset(&p, 0, sizeof p);
    for (i = 0; i < sizeof dy / sizeof dy[0]; i++) {
        for (j = 0; j < sizeof oy / sizeof oy[0]; j++) {
            double o[3] = { 0, 0, 0.5 }, d[3];
            o[1] = oy[j];
            d[0] = 1.0;
            d[1] = dy[i];
            d[2] = 0;
            normalize(d);
            q16_lane(&p, (int)n, o, d, 100.0, 0, &dr[n]);
            n++;
            if (n == LT_LANES ||
                (i + 1 == sizeof dy / sizeof dy[0] && j + 1 == sizeof oy / sizeof oy[0])) {
                lt_vq16_t tn = lt_vq16_set1(0);
                lt_mask16_t hit;
                unsigned k;
                lt_ray16_q16_setup(&p);
                hit = lt_slab16_q16(&p, (lt_mask16_t)((1u << n) - 1u), &bq, &tn);
                for (k = 0; k < n; k++) {
                    verdict_t v = slab_ref(&dr[k], &db, FMT_Q16);
                    cases++;
                    if (LTT_ON(hit, k) != v.hit && bad++ < 8)
                        ltt_report("  FAIL lt_slab16_q16 near-parallel: o=(0,%.6g,0.5) "
                                   "d=(%.9g,%.9g,0) box [10,20]x[0,1]x[0,1] tmax 100: %s (tnear "
                                   "%.4g), reference %s (ref tnear %.4g)\n", dr[k].o[1], dr[k].d[0],
                                   dr[k].d[1], LTT_ON(hit, k) ? "hit" : "miss",
                                   lt_q16_to_double(tn.l[k]), v.hit ? "hit" : "miss", v.t);
                }
                n = 0;
                memset(&p, 0, sizeof p);
            }
        }
    }
    ltt_report("lt_slab16_q16 near-parallel (0 < |d| < 2^-15): %lu cases, %lu misclassified "
               "(bound 0: \"t saturates, which keeps the classification\")\n", cases, bad);
    assert_int_equal(bad, 0);
}

/* ---- triangles ---------------------------------------------------------------------------- */

#define TRI_PACKETS 1000

/* Random triangle: v0 in [-60, 60]^3, two edges of length 0.5..40 in random directions. */
static void tri_make(ltt_rng_t *r, double v[3][3])
{
    double u1[3], u2[3], s1 = ltt_rng_uniform(r, 0.5, 40), s2 = ltt_rng_uniform(r, 0.5, 40);
    int a;
    rng_unit(r, u1);
    rng_unit(r, u2);
    for (a = 0; a < 3; a++) {
        v[0][a] = ltt_rng_uniform(r, -60, 60);
        v[1][a] = v[0][a] + s1 * u1[a];
        v[2][a] = v[0][a] + s2 * u2[a];
    }
}

/* A ray toward a point of the triangle's plane with barycentrics in [-0.25, 1.25] (category 0),
 * within 1e-4 of an edge or vertex (1), or with the origin possibly past the plane (2). */
static void tri_aim(ltt_rng_t *r, const double v[3][3], unsigned c, double o[3], double d[3])
{
    double b1 = ltt_rng_uniform(r, -0.25, 1.25), b2 = ltt_rng_uniform(r, -0.25, 1.25), tgt[3];
    double back = ltt_rng_uniform(r, c == 2 ? -50 : 0.01, 150);
    int a;
    if (c == 1) {
        unsigned e = ltt_rng_below(r, 3);
        double eps = ltt_rng_uniform(r, -1e-4, 1e-4);
        b1 = ltt_rng_unit(r);
        if (e == 0) {
            b2 = eps;
        } else if (e == 1) {
            b2 = 1.0 - b1 + eps;
        } else {
            b2 = b1;
            b1 = eps;
        }
    }
    rng_unit(r, d);
    for (a = 0; a < 3; a++) {
        tgt[a] = v[0][a] + b1 * (v[1][a] - v[0][a]) + b2 * (v[2][a] - v[0][a]);
        o[a] = tgt[a] - back * d[a];
    }
}

static double rng_tmax(ltt_rng_t *r)
{
    return ltt_rng_below(r, 3) ? 1000.0 : ltt_rng_uniform(r, 0, 150);
}

static void test_tri_random_q16(void **state)
{
    ltt_rng_t r;
    tally_t ty;
    unsigned pk;
    int i;
    unsigned long id_bad = 0;
    (void)state;
    ltt_rng_seed(&r, 2002);
    tally_init(&ty, "lt_tri16_q16 random");
    for (pk = 0; pk < TRI_PACKETS; pk++) {
        lt_ray16_q16_t p;
        lt_tri_q16_t tq;
        dtri_t dt;
        dray_t dr[LT_LANES];
        lt_hit16_t h;
        lt_mask16_t got;
        double v[3][3], o[3], d[3];
        memset(&p, 0, sizeof p);
        /* one triangle per packet, 16 rays aimed at it */
        tri_make(&r, v);
        q16_tri((const double(*)[3])v, &tq, &dt);
        for (i = 0; i < LT_LANES; i++) {
            tri_aim(&r, (const double(*)[3])v, (pk + (unsigned)i) % 3u, o, d);
            q16_lane(&p, i, o, d, rng_tmax(&r), i & 1, &dr[i]);
        }
        lt_ray16_q16_setup(&p);
        h.id = lt_vi32_set1(-7);
        {
            lt_vq16_t tmax0 = p.tmax;
            got = lt_tri16_q16(&p, LT_MASK_ALL, &tq, 42, &h);
            for (i = 0; i < LT_LANES; i++) {
                verdict_t vr = tri_ref(&dr[i], &dt, FMT_Q16);
                int g = LTT_ON(got, i);
                tally_case(&ty, &vr, g, 1, lt_q16_to_double(p.tmax.l[i]), "ray", i);
                /* a hit shortens tmax and sets the id; a miss touches neither */
                if (g ? (h.id.l[i] != 42 || p.tmax.l[i] >= tmax0.l[i] || p.tmax.l[i] <= 0)
                      : (h.id.l[i] != -7 || p.tmax.l[i] != tmax0.l[i]))
                    id_bad++;
            }
        }
    }
    tally_print(&ty, "derived per case, see header");
    ltt_report("lt_tri16_q16 random: %lu lanes with a wrong id or tmax update\n", id_bad);
    assert_int_equal(ty.bad + ty.t_bad + id_bad, 0);
}


/* lt_tri.h: every 16-lane op of the triangle test computes lt_tri.h's per-lane function on each
 * lane (the documented equivalence of the lane form), on random operands over the whole int32
 * range (saturating lanes included) and on the kernel's own operands; and lt_tri16_q16 takes
 * exactly the hits and t of the per-lane body (lt__tri_q16_cand1, lt__tri_q16_tdiv1). */
static lt_vq16_t body_rnd16(ltt_rng_t *r, unsigned sh)
{
    lt_vq16_t v;
    int i;
    for (i = 0; i < LT_LANES; i++)
        v.l[i] = ltt_rng_i32(r) >> (ltt_rng_below(r, sh + 1u));
    return v;
}

static void test_tri_lane_body_q16(void **state)
{
    ltt_rng_t r;
    unsigned n, pk;
    unsigned long bad = 0, hits = 0;
    int i;
    (void)state;
    ltt_rng_seed(&r, 1616);
    for (n = 0; n < 4000; n++) {
        lt_vq16_t a = body_rnd16(&r, 31), b = body_rnd16(&r, 31), c = body_rnd16(&r, 31);
        lt_vq16_t d = body_rnd16(&r, 31), e = body_rnd16(&r, 31), f = body_rnd16(&r, 31);
        lt_vq30_t qa, qc, qd;
        lt_vq6_t q6a, q6b, q6c;
        lt_vq16_t pv;
        lt_vq6_t qv;
        lt_vql32_t dt, vv;
        lt_vql22_t tn, tnum;
        lt_vql32_t det;
        lt_vq16_t td, src = body_rnd16(&r, 0);
        lt_mask16_t k = (lt_mask16_t)ltt_rng_u32(&r);
        memcpy(&qa, &a, sizeof a);
        memcpy(&qc, &c, sizeof c);
        memcpy(&qd, &d, sizeof d);
        memcpy(&q6a, &d, sizeof d);
        memcpy(&q6b, &e, sizeof e);
        memcpy(&q6c, &f, sizeof f);
        pv = LT__TRI_V16_PVEC(qa, b, qc, d);
        qv = LT__TRI_V16_QVEC(a, b, c, d);
        dt = LT__TRI_V16_DOT(a, b, c, d, e, f);
        vv = LT__TRI_V16_V(qa, qc, qd, q6a, q6b, q6c);
        tn = LT__TRI_V16_TNUM(a, b, c, q6a, q6b, q6c);
        for (i = 0; i < LT_LANES; i++) {
            /* det > 0; operands for which the division's 2 n' + d' stays inside int64 (as the
             * geometry bound gives the kernel): any |tnum| < 2^60 with det < 2^27 (even lanes,
             * both shift branches), or |tnum| < 2^35 with det < 2^54 (odd lanes) */
            tnum.l[i] = ltt_rng_i64(&r) >> ((i & 1 ? 29u : 4u) + ltt_rng_below(&r, 30));
            det.l[i] = (int64_t)(ltt_rng_u64(&r) >> ((i & 1 ? 10u : 37u) + ltt_rng_below(&r, 27)));
            det.l[i] += det.l[i] == 0;
        }
        td = lt__tri_tdiv16_q16(src, k, tnum, det);
        for (i = 0; i < LT_LANES; i++) {
            bad += pv.l[i] != lt__tri_q16_pvec1(a.l[i], b.l[i], c.l[i], d.l[i]);
            bad += qv.l[i] != lt__tri_q16_qvec1(a.l[i], b.l[i], c.l[i], d.l[i]);
            bad += dt.l[i] != lt__tri_q16_dot1(a.l[i], b.l[i], c.l[i], d.l[i], e.l[i], f.l[i]);
            bad += vv.l[i] != lt__tri_q16_v1(a.l[i], c.l[i], d.l[i], d.l[i], e.l[i], f.l[i]);
            bad += tn.l[i] != lt__tri_q16_dot1(a.l[i], b.l[i], c.l[i], d.l[i], e.l[i], f.l[i]);
            bad += td.l[i] != (LTT_ON(k, i) ? lt__tri_q16_tdiv1(tnum.l[i], det.l[i]) : src.l[i]);
        }
    }
    /* the packet kernel against the per-lane body on aimed rays (as test_tri_random_q16) */
    for (pk = 0; pk < TRI_PACKETS; pk++) {
        lt_ray16_q16_t p;
        lt_tri_q16_t tq;
        dtri_t dtr;
        dray_t dr;
        lt_hit16_t h;
        lt_mask16_t got;
        lt_vq16_t tmax0;
        double v[3][3], o[3], dd[3];
        memset(&p, 0, sizeof p);
        tri_make(&r, v);
        q16_tri((const double(*)[3])v, &tq, &dtr);
        for (i = 0; i < LT_LANES; i++) {
            tri_aim(&r, (const double(*)[3])v, (pk + (unsigned)i) % 3u, o, dd);
            q16_lane(&p, i, o, dd, rng_tmax(&r), i & 1, &dr);
        }
        lt_ray16_q16_setup(&p);
        h.id = lt_vi32_set1(-1);
        tmax0 = p.tmax;
        got = lt_tri16_q16(&p, LT_MASK_ALL, &tq, 7, &h);
        for (i = 0; i < LT_LANES; i++) {
            lt_q16_t o1[3], t = 0;
            lt_q30_t d1[3];
            int64_t tnum1, det1;
            int hit;
            o1[0] = p.ox.l[i], o1[1] = p.oy.l[i], o1[2] = p.oz.l[i];
            d1[0] = p.dx.l[i], d1[1] = p.dy.l[i], d1[2] = p.dz.l[i];
            hit = lt__tri_q16_cand1(o1, d1, &tq, &tnum1, &det1);
            if (hit) {
                t = lt__tri_q16_tdiv1(tnum1, det1);
                hit = t > p.tmin.l[i] && t < tmax0.l[i];
            }
            hits += (unsigned long)hit;
            bad += hit != (int)LTT_ON(got, i);
            bad += hit ? p.tmax.l[i] != t : p.tmax.l[i] != tmax0.l[i];
        }
    }
    ltt_report("lt_tri.h per-lane body: %lu mismatches against the lane ops and lt_tri16_q16 "
               "(%lu body hits)\n", bad, hits);
    assert_int_equal(bad, 0);
    assert_true(hits > 0);
}

#if LT_CFG_FLOAT32
static void test_tri_random_f32(void **state)
{
    ltt_rng_t r;
    tally_t ty;
    unsigned pk;
    int i;
    unsigned long id_bad = 0;
    (void)state;
    ltt_rng_seed(&r, 2003);
    tally_init(&ty, "lt_tri16_f32 random");
    for (pk = 0; pk < TRI_PACKETS; pk++) {
        lt_ray16_f32_t p;
        lt_tri_f32_t tf;
        dtri_t dt;
        dray_t dr[LT_LANES];
        lt_hit16_t h;
        lt_mask16_t got;
        lt_vf32_t tmax0;
        double v[3][3], o[3], d[3];
        memset(&p, 0, sizeof p);
        tri_make(&r, v);
        f32_tri((const double(*)[3])v, &tf, &dt);
        for (i = 0; i < LT_LANES; i++) {
            tri_aim(&r, (const double(*)[3])v, (pk + (unsigned)i) % 3u, o, d);
            f32_lane(&p, i, o, d, rng_tmax(&r), &dr[i]);
        }
        lt_ray16_f32_setup(&p);
        h.id = lt_vi32_set1(-7);
        tmax0 = p.tmax;
        got = lt_tri16_f32(&p, LT_MASK_ALL, &tf, 42, &h);
        for (i = 0; i < LT_LANES; i++) {
            verdict_t vr = tri_ref(&dr[i], &dt, FMT_F32);
            int g = LTT_ON(got, i);
            tally_case(&ty, &vr, g, 1, (double)p.tmax.l[i], "ray", i);
            if (g ? (h.id.l[i] != 42 || !(p.tmax.l[i] < tmax0.l[i]) || !(p.tmax.l[i] > 0.0f))
                  : (h.id.l[i] != -7 || p.tmax.l[i] != tmax0.l[i]))
                id_bad++;
        }
    }
    tally_print(&ty, "relative 1e-5, see header");
    ltt_report("lt_tri16_f32 random: %lu lanes with a wrong id or tmax update\n", id_bad);
    assert_int_equal(ty.bad + ty.t_bad + id_bad, 0);
}
#endif

/* Degenerate triangles (zero area: a zero edge, equal edges, collinear edges, a point) must never
 * hit, whatever the ray; edge-on rays (in the triangle's plane) against an axis-aligned triangle
 * must miss (det is exactly 0 in both formats); tilted edge-on rays may go either way but must
 * leave a hit inside (tmin, tmax). */
static void test_tri_degenerate_edge_on(void **state)
{
    ltt_rng_t r;
    unsigned long cases = 0, deg_hits_q = 0, deg_hits_f = 0, edge_cases = 0, edge_hits_q = 0;
    unsigned long edge_hits_f = 0, tilt_cases = 0, tilt_hits_q = 0, tilt_bad = 0;
    unsigned n, kind;
    int i, a;
    (void)state;
    ltt_rng_seed(&r, 3003);
    for (n = 0; n < 200; n++) {
        lt_ray16_q16_t p;
        lt_tri_q16_t tq;
        lt_hit16_t h;
        dray_t dr;
        lt_mask16_t got;
        double w[3], v[3][3];
        int32_t wq[3], k1, k2;
#if LT_CFG_FLOAT32
        lt_ray16_f32_t pf;
        lt_tri_f32_t tf;
#endif
        kind = n % 5u;
        /* s15.16 edges that are exact integer multiples of one vector: exactly collinear */
        for (a = 0; a < 3; a++) {
            w[a] = ltt_rng_uniform(&r, -4, 4);
            wq[a] = lt_q16_from_double_sat(w[a]);
            v[0][a] = ltt_rng_uniform(&r, -20, 20);
        }
        k1 = ltt_rng_range(&r, -5, 5);
        k2 = ltt_rng_range(&r, -5, 5);
        for (a = 0; a < 3; a++) {
            tq.v0[a] = lt_q16_from_double_sat(v[0][a]);
            tq.e1[a] = kind == 0 ? 0 : (kind == 4 ? 0 : k1 * wq[a]);
            tq.e2[a] = kind == 1 ? 0 : (kind == 2 ? tq.e1[a] : (kind == 4 ? 0 : k2 * wq[a]));
        }
        memset(&p, 0, sizeof p);
        for (i = 0; i < LT_LANES; i++) {
            double o[3], d[3], tgt[3], s = ltt_rng_uniform(&r, -1, 2);
            rng_unit(&r, d);
            for (a = 0; a < 3; a++) {
                /* aim at a point of the degenerate segment */
                tgt[a] = lt_q16_to_double(tq.v0[a]) + s * lt_q16_to_double(tq.e1[a]);
                o[a] = tgt[a] - ltt_rng_uniform(&r, 1, 50) * d[a];
            }
            q16_lane(&p, i, o, d, 1000.0, i & 1, &dr);
        }
        lt_ray16_q16_setup(&p);
        h.id = lt_vi32_set1(-1);
        got = lt_tri16_q16(&p, LT_MASK_ALL, &tq, 5, &h);
        cases += LT_LANES;
        deg_hits_q += lt__popcount32(got);
#if LT_CFG_FLOAT32
        memset(&pf, 0, sizeof pf);
        for (a = 0; a < 3; a++) {
            tf.v0[a] = (float)lt_q16_to_double(tq.v0[a]);
            tf.e1[a] = (float)lt_q16_to_double(tq.e1[a]);
            tf.e2[a] = (float)lt_q16_to_double(tq.e2[a]);
        }
        for (i = 0; i < LT_LANES; i++)
            for (a = 0; a < 3; a++) {
                f32_o(&pf, a)->l[i] = (float)lt_q16_to_double(q16_o(&p, a)->l[i]);
                f32_d(&pf, a)->l[i] = (float)lt_q30_to_double(q16_d(&p, a)->l[i]);
            }
        pf.tmin = lt_vf32_set1(0.0f);
        pf.tmax = lt_vf32_set1(1000.0f);
        lt_ray16_f32_setup(&pf);
        got = lt_tri16_f32(&pf, LT_MASK_ALL, &tf, 5, &h);
        deg_hits_f += lt__popcount32(got);
#endif
    }
    /* edge-on: a triangle in the plane z = c (exact), rays with dz = 0 at z = c */
    for (n = 0; n < 200; n++) {
        lt_ray16_q16_t p;
        lt_tri_q16_t tq;
        dtri_t dt;
        lt_hit16_t h;
        dray_t dr;
        lt_mask16_t got;
        double v[3][3], c = ltt_rng_uniform(&r, -20, 20);
        int ax = (int)(n % 3u);
#if LT_CFG_FLOAT32
        lt_ray16_f32_t pf;
        lt_tri_f32_t tf;
#endif
        for (i = 0; i < 3; i++)
            for (a = 0; a < 3; a++)
                v[i][a] = a == ax ? c : ltt_rng_uniform(&r, -20, 20);
        q16_tri((const double(*)[3])v, &tq, &dt);
        memset(&p, 0, sizeof p);
        for (i = 0; i < LT_LANES; i++) {
            double o[3], d[3];
            rng_unit(&r, d);
            d[ax] = 0;
            normalize(d);
            for (a = 0; a < 3; a++)
                o[a] = (v[0][a] + v[1][a] + v[2][a]) / 3.0 - ltt_rng_uniform(&r, 1, 50) * d[a];
            o[ax] = c;
            q16_lane(&p, i, o, d, 1000.0, 0, &dr);
        }
        lt_ray16_q16_setup(&p);
        got = lt_tri16_q16(&p, LT_MASK_ALL, &tq, 5, &h);
        edge_cases += LT_LANES;
        edge_hits_q += lt__popcount32(got);
#if LT_CFG_FLOAT32
        memset(&pf, 0, sizeof pf);
        f32_tri((const double(*)[3])v, &tf, &dt);
        for (i = 0; i < LT_LANES; i++)
            for (a = 0; a < 3; a++) {
                f32_o(&pf, a)->l[i] = (float)lt_q16_to_double(q16_o(&p, a)->l[i]);
                f32_d(&pf, a)->l[i] = (float)lt_q30_to_double(q16_d(&p, a)->l[i]);
            }
        pf.tmin = lt_vf32_set1(0.0f);
        pf.tmax = lt_vf32_set1(1000.0f);
        lt_ray16_f32_setup(&pf);
        got = lt_tri16_f32(&pf, LT_MASK_ALL, &tf, 5, &h);
        edge_hits_f += lt__popcount32(got);
#endif
    }
    /* tilted edge-on: the ray lies in the plane of a general triangle (up to input rounding) */
    for (n = 0; n < 200; n++) {
        lt_ray16_q16_t p;
        lt_tri_q16_t tq;
        dtri_t dt;
        lt_hit16_t h;
        dray_t dr;
        lt_mask16_t got;
        double v[3][3], o[3], d[3];
        tri_make(&r, v);
        q16_tri((const double(*)[3])v, &tq, &dt);
        memset(&p, 0, sizeof p);
        for (i = 0; i < LT_LANES; i++) {
            double s = ltt_rng_uniform(&r, -0.5, 1.5), t2 = ltt_rng_uniform(&r, -0.5, 1.5);
            for (a = 0; a < 3; a++) {
                d[a] = s * dt.e1[a] + t2 * dt.e2[a];
                o[a] = dt.v0[a] + (1 - s) * dt.e1[a] * 0.3 - 3.0 * d[a];
            }
            normalize(d);
            q16_lane(&p, i, o, d, 1000.0, 0, &dr);
        }
        lt_ray16_q16_setup(&p);
        h.id = lt_vi32_set1(-1);
        got = lt_tri16_q16(&p, LT_MASK_ALL, &tq, 5, &h);
        tilt_cases += LT_LANES;
        tilt_hits_q += lt__popcount32(got);
        for (i = 0; i < LT_LANES; i++)
            if (LTT_ON(got, i) && (p.tmax.l[i] <= 0 || p.tmax.l[i] >= LT_Q16(1000.0)))
                tilt_bad++;
    }
    ltt_report("lt_tri16 degenerate (zero edge, e1 == e2, collinear, point): %lu rays aimed at "
               "them, %lu q16 hits, %lu f32 hits (bound 0)\n", cases, deg_hits_q, deg_hits_f);
    ltt_report("lt_tri16 edge-on, axis-aligned plane: %lu rays, %lu q16 hits, %lu f32 hits "
               "(bound 0: det == 0)\n", edge_cases, edge_hits_q, edge_hits_f);
    ltt_report("lt_tri16_q16 edge-on, tilted plane: %lu rays, %lu hits (either way allowed), %lu "
               "with t outside (tmin, tmax)\n", tilt_cases, tilt_hits_q, tilt_bad);
    assert_int_equal(deg_hits_q + deg_hits_f + edge_hits_q + edge_hits_f + tilt_bad, 0);
}

/* Two parallel triangles in front of a packet: the closer wins in either order; the farther one,
 * tested second, does not shorten. Then lane independence: every lane's result equals the result
 * of its ray alone in lane 0 of a packet of unrelated rays, and masked-off lanes keep tmax/id. */
static void test_tri_order_and_lanes(void **state)
{
    ltt_rng_t r;
    unsigned n, order;
    unsigned long order_bad = 0, order_cases = 0, lane_bad = 0, lane_cases = 0, mask_bad = 0;
    int i;
    uint16_t masks[LTT_MASK_COUNT];
    unsigned nm = ltt_masks(masks, 4004);
    (void)state;
    ltt_rng_seed(&r, 4004);
    for (n = 0; n < 100; n++) {
        double zn = ltt_rng_uniform(&r, 5, 40), zf = zn + ltt_rng_uniform(&r, 1e-3, 20);
        /* the triangles cover x, y >= -100, x + y <= 100; the rays stay within |x|, |y| < 30 */
        double vn[3][3] = { { -100, -100, 0 }, { 200, -100, 0 }, { -100, 200, 0 } };
        double vf[3][3];
        lt_tri_q16_t tn_, tf_;
        dtri_t dn, df;
        memcpy(vf, vn, sizeof vf);
        for (i = 0; i < 3; i++) {
            vn[i][2] = zn;
            vf[i][2] = zf;
        }
        q16_tri((const double(*)[3])vn, &tn_, &dn);
        q16_tri((const double(*)[3])vf, &tf_, &df);
        for (order = 0; order < 2; order++) {
            lt_ray16_q16_t p;
            lt_hit16_t h;
            dray_t dr[LT_LANES];
            lt_mask16_t m2;
            memset(&p, 0, sizeof p);
            for (i = 0; i < LT_LANES; i++) {
                double o[3], d[3];
                o[0] = ltt_rng_uniform(&r, -10, 10);
                o[1] = ltt_rng_uniform(&r, -10, 10);
                o[2] = 0;
                d[0] = ltt_rng_uniform(&r, -0.3, 0.3);
                d[1] = ltt_rng_uniform(&r, -0.3, 0.3);
                d[2] = 1;
                normalize(d);
                q16_lane(&p, i, o, d, 1000.0, i & 1, &dr[i]);
            }
            lt_ray16_q16_setup(&p);
            h.id = lt_vi32_set1(-1);
            if (order == 0) {
                (void)lt_tri16_q16(&p, LT_MASK_ALL, &tn_, 1, &h);
                m2 = lt_tri16_q16(&p, LT_MASK_ALL, &tf_, 2, &h);
            } else {
                (void)lt_tri16_q16(&p, LT_MASK_ALL, &tf_, 2, &h);
                m2 = lt_tri16_q16(&p, LT_MASK_ALL, &tn_, 1, &h);
            }
            for (i = 0; i < LT_LANES; i++) {
                verdict_t v = tri_ref(&dr[i], &dn, FMT_Q16);
                order_cases++;
                if (h.id.l[i] != 1 || fabs(lt_q16_to_double(p.tmax.l[i]) - v.t) > v.t_bound ||
                    LTT_ON(m2, i) != (order == 0 ? 0 : 1))
                    order_bad++;
            }
        }
    }
    /* lane independence against a random triangle */
    for (n = 0; n < 100; n++) {
        double v[3][3], o[3], d[3];
        lt_tri_q16_t tq;
        dtri_t dt;
        lt_ray16_q16_t full, p0;
        lt_hit16_t hf;
        lt_mask16_t mf;
        dray_t dr;
        tri_make(&r, v);
        q16_tri((const double(*)[3])v, &tq, &dt);
        memset(&full, 0, sizeof full);
        for (i = 0; i < LT_LANES; i++) {
            tri_aim(&r, (const double(*)[3])v, (unsigned)i % 3u, o, d);
            q16_lane(&full, i, o, d, rng_tmax(&r), i & 1, &dr);
        }
        lt_ray16_q16_setup(&full);
        {
            lt_ray16_q16_t before = full;
            hf.id = lt_vi32_set1(-3);
            mf = lt_tri16_q16(&full, LT_MASK_ALL, &tq, 9, &hf);
            for (i = 0; i < LT_LANES; i++) {
                lt_hit16_t h0;
                lt_mask16_t m0;
                int j;
                /* lane 0 = ray i, other lanes = the other rays rotated (unrelated results) */
                p0 = before;
                for (j = 0; j < LT_LANES; j++) {
                    int s = (i + j) % LT_LANES;
                    p0.ox.l[j] = before.ox.l[s];
                    p0.oy.l[j] = before.oy.l[s];
                    p0.oz.l[j] = before.oz.l[s];
                    p0.dx.l[j] = before.dx.l[s];
                    p0.dy.l[j] = before.dy.l[s];
                    p0.dz.l[j] = before.dz.l[s];
                    p0.tmin.l[j] = before.tmin.l[s];
                    p0.tmax.l[j] = before.tmax.l[s];
                }
                lt_ray16_q16_setup(&p0);
                h0.id = lt_vi32_set1(-3);
                m0 = lt_tri16_q16(&p0, 1u, &tq, 9, &h0);
                lane_cases++;
                if ((int)(m0 & 1u) != LTT_ON(mf, i) || p0.tmax.l[0] != full.tmax.l[i] ||
                    h0.id.l[0] != hf.id.l[i] || (m0 & 0xFFFEu) != 0)
                    lane_bad++;
            }
            /* masks: active lanes as in the full run, inactive lanes untouched */
            for (i = 0; i < (int)nm; i++) {
                lt_ray16_q16_t pm = before;
                lt_hit16_t hm;
                lt_mask16_t mm;
                int j;
                hm.id = lt_vi32_set1(-3);
                mm = lt_tri16_q16(&pm, masks[i], &tq, 9, &hm);
                if (mm != (mf & masks[i]))
                    mask_bad++;
                for (j = 0; j < LT_LANES; j++) {
                    int on = LTT_ON(masks[i], j);
                    if (pm.tmax.l[j] != (on ? full.tmax.l[j] : before.tmax.l[j]) ||
                        hm.id.l[j] != (on ? hf.id.l[j] : -3))
                        mask_bad++;
                }
            }
        }
    }
    ltt_report("lt_tri16_q16 closer wins: %lu lanes x 2 orders, %lu wrong id/t/return mask "
               "(bound 0 / t within bound)\n", order_cases, order_bad);
    ltt_report("lt_tri16_q16 lane independence: %lu lanes re-run alone in lane 0, %lu differ; "
               "%u masks: %lu inactive-lane or result mismatches (bound 0)\n", lane_cases, lane_bad,
               nm, mask_bad);
    assert_int_equal(order_bad + lane_bad + mask_bad, 0);
}

/* ---- chunk scene vs brute force ----------------------------------------------------------- */

/* Judge a closest-hit id against per-triangle reference verdicts: 0 agrees with the reference
 * closest hit, 1 differs only within the bounds (the kernel's triangle could hit, and every
 * triangle that surely hits is no closer than the kernel's by more than the two t bounds),
 * 2 unexplained. */
static int judge_closest(const verdict_t *v, unsigned n, int got, int *best_out)
{
    unsigned k;
    int best = -1;
    for (k = 0; k < n; k++)
        if (v[k].hit && (best < 0 || v[k].t < v[best].t))
            best = (int)k;
    *best_out = best;
    if (got == best)
        return 0;
    if (got < -1 || got >= (int)n)
        return 2;
    if (got >= 0 && !explainable(&v[got], 1))
        return 2;
    for (k = 0; k < n; k++)
        if (!explainable(&v[k], 0) &&
            (got < 0 || v[got].t - v[k].t > v[got].t_bound + v[k].t_bound))
            return 2;
    return 1;
}

#define MESH_TRIS 90
#define MESH_PACKETS 80

static void test_chunks_q16(void **state)
{
    ltt_rng_t r;
    lt_tri_q16_t tris[MESH_TRIS];
    dtri_t dt[MESH_TRIS];
    lt_aabb_q16_t boxes[LT_CHUNK_COUNT(MESH_TRIS) + 2];
    unsigned nbox = LT_CHUNK_COUNT(MESH_TRIS), k, pk, c;
    unsigned long cases = 0, hits = 0, allowed = 0, bad = 0, box_bad = 0;
    double max_terr = 0;
    int i, a;
    (void)state;
    ltt_rng_seed(&r, 5005);
    for (k = 0; k < MESH_TRIS; k++) {
        double v[3][3], u1[3], u2[3], s1 = ltt_rng_uniform(&r, 1, 12);
        double s2 = ltt_rng_uniform(&r, 1, 12);
        rng_unit(&r, u1);
        rng_unit(&r, u2);
        for (a = 0; a < 3; a++) {
            v[0][a] = ltt_rng_uniform(&r, -20, 20);
            v[1][a] = v[0][a] + s1 * u1[a];
            v[2][a] = v[0][a] + s2 * u2[a];
        }
        q16_tri((const double(*)[3])v, &tris[k], &dt[k]);
    }
    /* argument checks, then the build with a poisoned tail */
    assert_int_equal(lt_chunks_build_q16(NULL, MESH_TRIS, boxes), LT_E_ARG);
    assert_int_equal(lt_chunks_build_q16(tris, MESH_TRIS, NULL), LT_E_ARG);
    assert_int_equal(lt_chunks_build_q16(tris, 0, boxes), LT_E_ARG);
    ltt_poison(boxes, sizeof boxes);
    assert_int_equal(lt_chunks_build_q16(tris, MESH_TRIS, boxes), LT_OK);
    box_bad += ltt_touched(boxes, nbox * sizeof boxes[0], sizeof boxes) != 0;
    for (c = 0; c < nbox; c++) {
        /* each box is exactly the min/max of the vertices of its 16 triangles */
        for (a = 0; a < 3; a++) {
            int64_t lo = INT64_MAX, hi = INT64_MIN;
            for (k = c * LT_CHUNK_TRIS; k < MESH_TRIS && k < (c + 1) * LT_CHUNK_TRIS; k++) {
                int64_t p0 = tris[k].v0[a], p1 = p0 + tris[k].e1[a], p2 = p0 + tris[k].e2[a];
                lo = p0 < lo ? p0 : lo;
                lo = p1 < lo ? p1 : lo;
                lo = p2 < lo ? p2 : lo;
                hi = p0 > hi ? p0 : hi;
                hi = p1 > hi ? p1 : hi;
                hi = p2 > hi ? p2 : hi;
            }
            box_bad += boxes[c].lo[a] != lo || boxes[c].hi[a] != hi;
        }
    }
    for (pk = 0; pk < MESH_PACKETS; pk++) {
        lt_ray16_q16_t p;
        lt_hit16_t h;
        dray_t dr[LT_LANES];
        lt_mask16_t any;
        memset(&p, 0, sizeof p);
        for (i = 0; i < LT_LANES; i++) {
            double o[3], d[3], tgt[3];
            rng_unit(&r, o);
            for (a = 0; a < 3; a++) {
                o[a] *= 60.0;
                tgt[a] = ltt_rng_uniform(&r, -15, 15);
                d[a] = tgt[a] - o[a];
            }
            normalize(d);
            q16_lane(&p, i, o, d, 1000.0, i & 1, &dr[i]);
        }
        lt_ray16_q16_setup(&p);
        h.id = lt_vi32_set1(77);
        any = lt_chunks_trace16_q16(tris, MESH_TRIS, boxes, LT_ISECT_WT, &p, LT_MASK_ALL, &h);
        for (i = 0; i < LT_LANES; i++) {
            /* brute force: every triangle's reference verdict */
            verdict_t v[MESH_TRIS];
            int best, got = h.id.l[i], j;
            for (k = 0; k < MESH_TRIS; k++)
                v[k] = tri_ref(&dr[i], &dt[k], FMT_Q16);
            j = judge_closest(v, MESH_TRIS, got, &best);
            cases++;
            hits += got >= 0;
            if (LTT_ON(any, i) != (got >= 0))
                bad++;
            if (j == 0 && got >= 0) {
                double e = fabs(lt_q16_to_double(p.tmax.l[i]) - v[got].t);
                max_terr = e > max_terr ? e : max_terr;
                if (e > v[got].t_bound)
                    bad++;
            }
            if (j == 1) {
                allowed++;
            } else if (j == 2 && bad++ < 6) {
                ltt_report("  FAIL lt_chunks_trace16_q16: packet %u lane %d: id %d, brute force %d "
                           "(t %.6g)\n", pk, i, got, best, best >= 0 ? v[best].t : 0.0);
            }
        }
    }
    ltt_report("lt_chunks_build_q16: %u boxes of %u triangles equal the vertex min/max, %lu wrong; "
               "0xA5 tail untouched; NULL/n=0 -> LT_E_ARG\n", nbox, (unsigned)MESH_TRIS, box_bad);
    ltt_report("lt_chunks_trace16_q16 vs brute-force double: %lu rays, %lu hits, %lu id "
               "differences within bound, %lu unexplained, max |t err| %.3g\n", cases, hits,
               allowed, bad, max_terr);
    assert_int_equal(bad + box_bad, 0);
}

#if LT_CFG_FLOAT32
static void test_chunks_f32(void **state)
{
    ltt_rng_t r;
    lt_tri_f32_t tris[MESH_TRIS];
    dtri_t dt[MESH_TRIS];
    lt_aabb_f32_t boxes[LT_CHUNK_COUNT(MESH_TRIS) + 2];
    unsigned nbox = LT_CHUNK_COUNT(MESH_TRIS), k, pk;
    unsigned long cases = 0, hits = 0, allowed = 0, bad = 0;
    int i, a;
    (void)state;
    ltt_rng_seed(&r, 5006);
    for (k = 0; k < MESH_TRIS; k++) {
        double v[3][3], u1[3], u2[3], s1 = ltt_rng_uniform(&r, 1, 12);
        double s2 = ltt_rng_uniform(&r, 1, 12);
        rng_unit(&r, u1);
        rng_unit(&r, u2);
        for (a = 0; a < 3; a++) {
            v[0][a] = ltt_rng_uniform(&r, -20, 20);
            v[1][a] = v[0][a] + s1 * u1[a];
            v[2][a] = v[0][a] + s2 * u2[a];
        }
        f32_tri((const double(*)[3])v, &tris[k], &dt[k]);
    }
    assert_int_equal(lt_chunks_build_f32(tris, 0, boxes), LT_E_ARG);
    ltt_poison(boxes, sizeof boxes);
    assert_int_equal(lt_chunks_build_f32(tris, MESH_TRIS, boxes), LT_OK);
    assert_int_equal(ltt_touched(boxes, nbox * sizeof boxes[0], sizeof boxes), 0);
    for (pk = 0; pk < MESH_PACKETS; pk++) {
        lt_ray16_f32_t p;
        lt_hit16_t h;
        dray_t dr[LT_LANES];
        memset(&p, 0, sizeof p);
        for (i = 0; i < LT_LANES; i++) {
            double o[3], d[3];
            rng_unit(&r, o);
            for (a = 0; a < 3; a++) {
                o[a] *= 60.0;
                d[a] = ltt_rng_uniform(&r, -15, 15) - o[a];
            }
            normalize(d);
            f32_lane(&p, i, o, d, 1000.0, &dr[i]);
        }
        lt_ray16_f32_setup(&p);
        (void)lt_chunks_trace16_f32(tris, MESH_TRIS, boxes, LT_ISECT_WT, &p, LT_MASK_ALL, &h);
        for (i = 0; i < LT_LANES; i++) {
            verdict_t v[MESH_TRIS];
            int best, got = h.id.l[i], j;
            for (k = 0; k < MESH_TRIS; k++)
                v[k] = tri_ref(&dr[i], &dt[k], FMT_F32);
            j = judge_closest(v, MESH_TRIS, got, &best);
            cases++;
            hits += got >= 0;
            if (j == 1)
                allowed++;
            else if (j == 2 && bad++ < 6)
                ltt_report("  FAIL lt_chunks_trace16_f32: packet %u lane %d: id %d, brute force "
                           "%d\n", pk, i, got, best);
        }
    }
    ltt_report("lt_chunks_trace16_f32 vs brute-force double: %lu rays, %lu hits, %lu id "
               "differences within bound, %lu unexplained\n", cases, hits, allowed, bad);
    assert_int_equal(bad, 0);
}
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_slab_random_q16),
#if LT_CFG_FLOAT32
        cmocka_unit_test(test_slab_random_f32),
#endif
        cmocka_unit_test(test_slab_parallel),
        cmocka_unit_test(test_slab_near_parallel),
        cmocka_unit_test(test_slab_far_q16),
        cmocka_unit_test(test_tri_random_q16),
        cmocka_unit_test(test_tri_lane_body_q16),
#if LT_CFG_FLOAT32
        cmocka_unit_test(test_tri_random_f32),
#endif
        cmocka_unit_test(test_tri_degenerate_edge_on),
        cmocka_unit_test(test_tri_order_and_lanes),
        cmocka_unit_test(test_chunks_q16),
#if LT_CFG_FLOAT32
        cmocka_unit_test(test_chunks_f32),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
