/* lt_kdgrid_testlib.h - test code shared by test_kd.c and test_grid.c: meshes (random soups,
 * terrains), packets of every lane kind, the kd-tree, chunk-scene and double-precision references,
 * and the verdict rules that decide whether a differing hit is explained by the numeric bounds.
 * Static functions, included once by each test program. Host only.
 */
#ifndef LT_KDGRID_TESTLIB_H
#define LT_KDGRID_TESTLIB_H

#if LT_COST_MODE == LT_COST_SIM
#include "lt_sim.h"
#endif
#include "lt_isect_oracle.h"

#define ULP16 (1.0 / 65536.0)

/* Sanitizer builds run the same cases on fewer packets and smaller camera views (ASan + UBSan make
 * the lane loops ~50x slower). */
#if defined(__SANITIZE_ADDRESS__)
#define NPACKETS 16
#define CAM_SCALE 8
#else
#define NPACKETS 150
#define CAM_SCALE 1
#endif

/* ---- meshes ------------------------------------------------------------------------------- */

/* A triangle set in both paths plus its chunk boxes (the reference) and double bounds. */
typedef struct mesh {
    uint32_t n;
    lt_tri_q16_t *tq;
    lt_aabb_q16_t *bq;
    double lo[3], hi[3]; /* bounds of the double vertices */
    double bmax;         /* largest |coordinate| */
#if LT_CFG_FLOAT32
    lt_tri_f32_t *tf;
    lt_aabb_f32_t *bf;
#endif
} mesh_t;

/* Quantise as lt_scene_prepare does: s15.16 vertices, edges as differences; float32 v0 and edges
 * from the float vertices. */
static void mesh_init(mesh_t *m, const double *v, uint32_t n)
{
    uint32_t i, j, a, nb = LT_CHUNK_COUNT(n) + 1u;
    memset(m, 0, sizeof *m);
    m->n = n;
    m->tq = calloc(n + 1u, sizeof *m->tq);
    m->bq = calloc(nb, sizeof *m->bq);
#if LT_CFG_FLOAT32
    m->tf = calloc(n + 1u, sizeof *m->tf);
    m->bf = calloc(nb, sizeof *m->bf);
    assert_non_null(m->tf);
    assert_non_null(m->bf);
#endif
    assert_non_null(m->tq);
    assert_non_null(m->bq);
    for (a = 0; a < 3; a++) {
        m->lo[a] = n > 0 ? v[a] : 0.0;
        m->hi[a] = m->lo[a];
    }
    for (i = 0; i < n; i++) {
        lt_q16_t q[3][3];
        for (j = 0; j < 3; j++)
            for (a = 0; a < 3; a++) {
                double c = v[i * 9 + j * 3 + a];
                q[j][a] = lt_q16_from_double_sat(c);
                m->lo[a] = c < m->lo[a] ? c : m->lo[a];
                m->hi[a] = c > m->hi[a] ? c : m->hi[a];
                m->bmax = fabs(c) > m->bmax ? fabs(c) : m->bmax;
            }
        for (a = 0; a < 3; a++) {
            m->tq[i].v0[a] = q[0][a];
            m->tq[i].e1[a] = q[1][a] - q[0][a];
            m->tq[i].e2[a] = q[2][a] - q[0][a];
#if LT_CFG_FLOAT32
            {
                float v0 = (float)v[i * 9 + a];
                m->tf[i].v0[a] = v0;
                m->tf[i].e1[a] = (float)v[i * 9 + 3 + a] - v0;
                m->tf[i].e2[a] = (float)v[i * 9 + 6 + a] - v0;
            }
#endif
        }
    }
    if (n > 0) {
        assert_int_equal(lt_chunks_build_q16(m->tq, n, m->bq), LT_OK);
#if LT_CFG_FLOAT32
        assert_int_equal(lt_chunks_build_f32(m->tf, n, m->bf), LT_OK);
#endif
    }
}

static void mesh_free(mesh_t *m)
{
    free(m->tq);
    free(m->bq);
#if LT_CFG_FLOAT32
    free(m->tf);
    free(m->bf);
#endif
    memset(m, 0, sizeof *m);
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void normalize(double d[3])
{
    double l = sqrt(dot3(d, d));
    d[0] /= l;
    d[1] /= l;
    d[2] /= l;
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

/* A triangle soup in [-s, s]^3 with edges of 0.05 s .. 0.4 s; every 13th triangle is collinear
 * (zero area), every 29th is a single point, every 7th lies in an axis plane at a whole
 * coordinate (a likely split position). Returns 9 doubles per triangle (malloc). */
static double *gen_soup(ltt_rng_t *r, uint32_t n, double s)
{
    double *v = malloc((size_t)n * 9 * sizeof *v);
    uint32_t i;
    int a, j;
    assert_non_null(v);
    for (i = 0; i < n; i++) {
        double *t = &v[i * 9], u1[3], u2[3], l1 = ltt_rng_uniform(r, 0.05, 0.4) * s;
        double l2 = ltt_rng_uniform(r, 0.05, 0.4) * s;
        rng_unit(r, u1);
        rng_unit(r, u2);
        for (a = 0; a < 3; a++) {
            t[a] = ltt_rng_uniform(r, -s, s);
            t[3 + a] = t[a] + l1 * u1[a];
            t[6 + a] = t[a] + l2 * u2[a];
        }
        if (i % 13 == 5)
            for (a = 0; a < 3; a++)
                t[6 + a] = t[a] + 0.5 * (t[3 + a] - t[a]);
        if (i % 29 == 3)
            for (a = 0; a < 3; a++)
                t[3 + a] = t[6 + a] = t[a];
        if (i % 7 == 2) {
            int ax = (int)ltt_rng_below(r, 3);
            double c = floor(ltt_rng_uniform(r, -s, s));
            for (j = 0; j < 3; j++)
                t[j * 3 + ax] = c;
        }
    }
    return v;
}

/* A height field of nx x nx quads over [-s, s]^2 (shared edges and vertices, so two triangles
 * often hit at the same t) plus its four vertical walls. 2 nx^2 + 8 triangles. */
static double *gen_terrain(ltt_rng_t *r, uint32_t nx, double s, uint32_t *n)
{
    double *h = malloc((size_t)(nx + 1) * (nx + 1) * sizeof *h), *v;
    uint32_t i, j, k = 0, w;
    assert_non_null(h);
    *n = 2 * nx * nx + 8;
    v = malloc((size_t)*n * 9 * sizeof *v);
    assert_non_null(v);
    for (i = 0; i <= nx; i++)
        for (j = 0; j <= nx; j++)
            h[i * (nx + 1) + j] = floor(ltt_rng_uniform(r, -0.2, 0.2) * s * 8) / 8;
#define TV(ii, jj, o)                                                                               \
    do {                                                                                           \
        v[k * 9 + (o) * 3 + 0] = -s + 2 * s * (double)(ii) / nx;                                   \
        v[k * 9 + (o) * 3 + 1] = -s + 2 * s * (double)(jj) / nx;                                   \
        v[k * 9 + (o) * 3 + 2] = h[(ii) * (nx + 1) + (jj)];                                        \
    } while (0)
    for (i = 0; i < nx; i++)
        for (j = 0; j < nx; j++) {
            TV(i, j, 0);
            TV(i + 1, j, 1);
            TV(i + 1, j + 1, 2);
            k++;
            TV(i, j, 0);
            TV(i + 1, j + 1, 1);
            TV(i, j + 1, 2);
            k++;
        }
#undef TV
    for (w = 0; w < 4; w++) {
        /* walls x = +-s and y = +-s from z = -s/2 to s/2 */
        double c = (w & 1) ? s : -s, p[4][3];
        int q, ax = (int)(w >> 1), o = 1 - ax;
        for (q = 0; q < 4; q++) {
            p[q][ax] = c;
            p[q][o] = (q == 1 || q == 2) ? s : -s;
            p[q][2] = q >= 2 ? s / 2 : -s / 2;
        }
        memcpy(&v[k * 9], p[0], sizeof p[0]);
        memcpy(&v[k * 9 + 3], p[1], sizeof p[1]);
        memcpy(&v[k * 9 + 6], p[2], sizeof p[2]);
        k++;
        memcpy(&v[k * 9], p[0], sizeof p[0]);
        memcpy(&v[k * 9 + 3], p[2], sizeof p[2]);
        memcpy(&v[k * 9 + 6], p[3], sizeof p[3]);
        k++;
    }
    free(h);
    return v;
}

/* ---- packets ------------------------------------------------------------------------------ */

/* The same 16 rays in both paths, with their double origins (for the bound). */
typedef struct pk {
    lt_ray16_q16_t q;
#if LT_CFG_FLOAT32
    lt_ray16_f32_t f;
#endif
    double o[LT_LANES][3];
    lt_mask16_t k;
} pk_t;

/* tmax <= 0 means "unbounded" (LT_Q16_MAX - 1, 3e38 as the camera uses). */
static void pk_lane(pk_t *p, int i, const double o[3], const double d[3], double tmax)
{
    p->q.ox.l[i] = lt_q16_from_double_sat(o[0]);
    p->q.oy.l[i] = lt_q16_from_double_sat(o[1]);
    p->q.oz.l[i] = lt_q16_from_double_sat(o[2]);
    p->q.dx.l[i] = lt_q30_from_double_sat(d[0]);
    p->q.dy.l[i] = lt_q30_from_double_sat(d[1]);
    p->q.dz.l[i] = lt_q30_from_double_sat(d[2]);
    p->q.tmin.l[i] = 0;
    p->q.tmax.l[i] = tmax > 0 ? lt_q16_from_double_sat(tmax) : LT_Q16_MAX - 1;
#if LT_CFG_FLOAT32
    p->f.ox.l[i] = (float)o[0];
    p->f.oy.l[i] = (float)o[1];
    p->f.oz.l[i] = (float)o[2];
    p->f.dx.l[i] = (float)d[0];
    p->f.dy.l[i] = (float)d[1];
    p->f.dz.l[i] = (float)d[2];
    p->f.tmin.l[i] = 0.0f;
    p->f.tmax.l[i] = tmax > 0 ? (float)tmax : 3.0e38f;
#endif
    memcpy(p->o[i], o, sizeof p->o[i]);
}

static void pk_setup(pk_t *p)
{
    lt_ray16_q16_setup(&p->q);
#if LT_CFG_FLOAT32
    lt_ray16_f32_setup(&p->f);
#endif
}

/* Split planes rays may start on: axis and position (double, exact for s15.16 positions). */
typedef struct planes {
    unsigned n;
    int axis[64];
    double pos[64];
} planes_t;

static const char *const lane_kind_names[] = {
    "outside->scene", "inside", "axis-parallel", "missing the bounds", "parallel to a plane",
    "on a split plane",
};
#define LANE_KINDS 6

/* One packet. Coherent packets (1 in 3) share an origin outside and aim at a small region;
 * mixed ones draw each lane's kind: from outside toward the scene, from inside in a random
 * direction, exactly along an axis, away from the scene (missing its bounds), inside with one
 * direction component exactly 0, or from a point exactly on one of the given split planes (in
 * the plane, perpendicular to it, or random). 1 lane in 8 gets a finite tmax. kinds[] counts. */
static void gen_packet(ltt_rng_t *r, const mesh_t *m, const planes_t *pl, pk_t *p,
                       unsigned long kinds[LANE_KINDS])
{
    double c[3], ext = 0, o[3], d[3], tg[3];
    int i, a, coherent = ltt_rng_below(r, 3) == 0;
    for (a = 0; a < 3; a++) {
        c[a] = 0.5 * (m->lo[a] + m->hi[a]);
        ext = fmax(ext, m->hi[a] - m->lo[a]);
    }
    ext = fmax(ext, 1.0);
    memset(p, 0, sizeof *p);
    if (coherent) {
        rng_unit(r, o);
        for (a = 0; a < 3; a++) {
            o[a] = c[a] + o[a] * 1.5 * ext;
            tg[a] = c[a] + ltt_rng_uniform(r, -0.4, 0.4) * ext;
        }
    }
    for (i = 0; i < LT_LANES; i++) {
        unsigned kind = coherent ? 0u : ltt_rng_below(r, LANE_KINDS);
        double tmax = ltt_rng_below(r, 8) == 0 ? ltt_rng_uniform(r, 0.1, 2.0) * ext : -1.0;
        if (kind == 5 && (pl == NULL || pl->n == 0))
            kind = 1;
        kinds[kind]++;
        if (coherent) {
            for (a = 0; a < 3; a++)
                d[a] = tg[a] + ltt_rng_uniform(r, -0.05, 0.05) * ext - o[a];
            normalize(d);
        } else {
            for (a = 0; a < 3; a++)
                o[a] = c[a] + ltt_rng_uniform(r, -0.5, 0.5) * (m->hi[a] - m->lo[a]);
            rng_unit(r, d);
            switch (kind) {
            case 0:
                rng_unit(r, o);
                for (a = 0; a < 3; a++) {
                    o[a] = c[a] + o[a] * 1.5 * ext;
                    d[a] = c[a] + ltt_rng_uniform(r, -0.5, 0.5) * ext - o[a];
                }
                normalize(d);
                break;
            case 2:
                d[0] = d[1] = d[2] = 0;
                d[ltt_rng_below(r, 3)] = ltt_rng_below(r, 2) ? 1.0 : -1.0;
                break;
            case 3:
                rng_unit(r, d);
                for (a = 0; a < 3; a++)
                    o[a] = c[a] + d[a] * 1.5 * ext;
                break;
            case 4:
                d[ltt_rng_below(r, 3)] = 0;
                normalize(d);
                break;
            case 5: {
                unsigned j = ltt_rng_below(r, pl->n), w = ltt_rng_below(r, 3);
                int ax = pl->axis[j];
                o[ax] = pl->pos[j];
                if (w == 0) {
                    d[ax] = 0; /* in the plane */
                    normalize(d);
                } else if (w == 1) {
                    d[0] = d[1] = d[2] = 0; /* perpendicular */
                    d[ax] = ltt_rng_below(r, 2) ? 1.0 : -1.0;
                }
                break;
            }
            default:
                break;
            }
        }
        pk_lane(p, i, o, d, tmax);
    }
    p->k = (lt_mask16_t)(ltt_rng_below(r, 6) == 0 ? ltt_rng_u32(r) : 0xFFFFu);
    pk_setup(p);
}

/* ---- structures under test and the reference ---------------------------------------------- */

typedef struct acc {
    const char *name;
    const void *q, *f;
    lt_mask16_t (*tq)(const void *, lt_ray16_q16_t *, lt_mask16_t, lt_hit16_t *);
    lt_mask16_t (*oq)(const void *, lt_ray16_q16_t *, lt_mask16_t);
#if LT_CFG_FLOAT32
    lt_mask16_t (*tf)(const void *, lt_ray16_f32_t *, lt_mask16_t, lt_hit16_t *);
    lt_mask16_t (*of)(const void *, lt_ray16_f32_t *, lt_mask16_t);
#endif
} acc_t;

static lt_mask16_t kd_tq(const void *a, lt_ray16_q16_t *r, lt_mask16_t k, lt_hit16_t *h)
{
    return lt_kd_trace16_q16((const lt_kd_q16_t *)a, r, k, h);
}
static lt_mask16_t kd_oq(const void *a, lt_ray16_q16_t *r, lt_mask16_t k)
{
    return lt_kd_occluded16_q16((const lt_kd_q16_t *)a, r, k);
}
static lt_mask16_t ch_tq(const void *a, lt_ray16_q16_t *r, lt_mask16_t k, lt_hit16_t *h)
{
    const mesh_t *m = (const mesh_t *)a;
    if (m->n == 0) {
        h->id = lt_vi32_set1(-1);
        return 0;
    }
    return lt_chunks_trace16_q16(m->tq, m->n, m->bq, LT_ISECT_WT, r, k, h);
}

#if LT_CFG_FLOAT32
static lt_mask16_t kd_tf(const void *a, lt_ray16_f32_t *r, lt_mask16_t k, lt_hit16_t *h)
{
    return lt_kd_trace16_f32((const lt_kd_f32_t *)a, r, k, h);
}
static lt_mask16_t kd_of(const void *a, lt_ray16_f32_t *r, lt_mask16_t k)
{
    return lt_kd_occluded16_f32((const lt_kd_f32_t *)a, r, k);
}
static lt_mask16_t ch_tf(const void *a, lt_ray16_f32_t *r, lt_mask16_t k, lt_hit16_t *h)
{
    const mesh_t *m = (const mesh_t *)a;
    if (m->n == 0) {
        h->id = lt_vi32_set1(-1);
        return 0;
    }
    return lt_chunks_trace16_f32(m->tf, m->n, m->bf, LT_ISECT_WT, r, k, h);
}

#endif

static void acc_chunks(acc_t *a, const mesh_t *m)
{
    memset(a, 0, sizeof *a);
    a->name = "chunks";
    a->q = a->f = m;
    a->tq = ch_tq;
#if LT_CFG_FLOAT32
    a->tf = ch_tf;
#endif
}

/* Per-lane results of one packet. */
typedef struct res16 {
    int32_t id[LT_LANES];
    double t[LT_LANES];
    lt_mask16_t hit, occ;
} res16_t;

/* Trace and occlusion-test packet p with structure a in path f32 (0/1); a structure without an
 * occlusion query (the chunks) reports its hit mask. Counts contract violations: returned mask !=
 * lanes with an id, inactive or missing lanes whose tmax changed or whose id is not -1. */
static unsigned long run(const acc_t *a, int f32, const pk_t *p, res16_t *o)
{
    unsigned long bad = 0;
    lt_hit16_t h;
    int i;
    if (!f32) {
        lt_ray16_q16_t r = p->q;
        o->hit = a->tq(a->q, &r, p->k, &h);
        for (i = 0; i < LT_LANES; i++) {
            o->id[i] = h.id.l[i];
            o->t[i] = lt_q16_to_double(r.tmax.l[i]);
            if (o->id[i] < 0 && r.tmax.l[i] != p->q.tmax.l[i])
                bad++;
        }
        r = p->q;
        o->occ = a->oq != NULL ? a->oq(a->q, &r, p->k) : o->hit;
    } else {
#if LT_CFG_FLOAT32
        lt_ray16_f32_t r = p->f;
        o->hit = a->tf(a->f, &r, p->k, &h);
        for (i = 0; i < LT_LANES; i++) {
            o->id[i] = h.id.l[i];
            o->t[i] = (double)r.tmax.l[i];
            if (o->id[i] < 0 && r.tmax.l[i] != p->f.tmax.l[i])
                bad++;
        }
        r = p->f;
        o->occ = a->of != NULL ? a->of(a->f, &r, p->k) : o->hit;
#endif
    }
    for (i = 0; i < LT_LANES; i++) {
        if (LTT_ON(o->hit, i) != (o->id[i] >= 0))
            bad++;
        if (!LTT_ON(p->k, i) && o->id[i] != -1)
            bad++;
    }
    return bad;
}

/* ---- double verdicts (test_isect.c's triangle bound) ---------------------------------------- */

#define SQRT3 1.7320508075688772
#define REL_F32 1e-5
#define QV_FRAC 6 /* qvec fractional bits documented by lt_tri16_q16 (s25.6) */

static void cross3(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

static double norm3(const double a[3])
{
    return sqrt(dot3(a, a));
}

/* Moller-Trumbore in double on the kernel's own inputs, with each condition's margin and error
 * bound (test_isect.c, file header): could the kernel hit (`hit` = 1) or miss (0) this triangle? */
typedef struct verdict {
    int sure_hit, sure_miss; /* the double answer holds beyond every error bound */
    double t, tb;            /* double t and its bound */
} verdict_t;

static verdict_t verdict(const mesh_t *m, int f32, const pk_t *p, int i, int32_t id)
{
    double o[3], d[3], e1[3], e2[3], v0[3], pv[3], tv[3], q[3], det, u, w, tn, ddet, du, dv, dtn;
    double tmin, tmax, dd, bb, ub, vb, mg[5], eb[5];
    int a, k, ok = 1, fail = 0;
    verdict_t v;
    if (!f32) {
        o[0] = lt_q16_to_double(p->q.ox.l[i]);
        o[1] = lt_q16_to_double(p->q.oy.l[i]);
        o[2] = lt_q16_to_double(p->q.oz.l[i]);
        d[0] = lt_q30_to_double(p->q.dx.l[i]);
        d[1] = lt_q30_to_double(p->q.dy.l[i]);
        d[2] = lt_q30_to_double(p->q.dz.l[i]);
        tmin = lt_q16_to_double(p->q.tmin.l[i]);
        tmax = lt_q16_to_double(p->q.tmax.l[i]);
        for (a = 0; a < 3; a++) {
            v0[a] = lt_q16_to_double(m->tq[id].v0[a]);
            e1[a] = lt_q16_to_double(m->tq[id].e1[a]);
            e2[a] = lt_q16_to_double(m->tq[id].e2[a]);
        }
    } else {
#if LT_CFG_FLOAT32
        o[0] = (double)p->f.ox.l[i];
        o[1] = (double)p->f.oy.l[i];
        o[2] = (double)p->f.oz.l[i];
        d[0] = (double)p->f.dx.l[i];
        d[1] = (double)p->f.dy.l[i];
        d[2] = (double)p->f.dz.l[i];
        tmin = (double)p->f.tmin.l[i];
        tmax = (double)p->f.tmax.l[i];
        for (a = 0; a < 3; a++) {
            v0[a] = (double)m->tf[id].v0[a];
            e1[a] = (double)m->tf[id].e1[a];
            e2[a] = (double)m->tf[id].e2[a];
        }
#else
        memset(&v, 0, sizeof v);
        return v;
#endif
    }
    memset(&v, 0, sizeof v);
    cross3(d, e2, pv);
    det = dot3(e1, pv);
    for (a = 0; a < 3; a++)
        tv[a] = o[a] - v0[a];
    u = dot3(tv, pv);
    cross3(tv, e1, q);
    w = dot3(d, q);
    tn = dot3(e2, q);
    if (!f32) {
        ddet = norm3(e1) * SQRT3 * ldexp(1.0, -17);
        du = norm3(tv) * SQRT3 * ldexp(1.0, -17);
        dv = SQRT3 * ldexp(1.0, -(QV_FRAC + 1)) + ldexp(1.0, -32);
        dtn = norm3(e2) * SQRT3 * ldexp(1.0, -(QV_FRAC + 1));
    } else {
        ddet = REL_F32 * norm3(e1) * norm3(e2);
        du = REL_F32 * norm3(tv) * norm3(e2);
        dv = REL_F32 * norm3(tv) * norm3(e1);
        dtn = REL_F32 * norm3(tv) * norm3(e1) * norm3(e2);
    }
    if (fabs(det) <= 2.0 * ddet) {
        v.t = HUGE_VAL;
        v.tb = HUGE_VAL; /* the side is undecidable in this format: anything goes */
        return v;
    }
    dd = fabs(det) - ddet;
    ub = u / det;
    vb = w / det;
    v.t = tn / det;
    bb = (du + dv + ddet * (1.0 + fabs(ub) + fabs(vb))) / dd;
    v.tb = (dtn + fabs(v.t) * ddet) / dd +
           (!f32 ? 0.5 * ULP16 + fabs(v.t) * ldexp(1.0, -30) : REL_F32 * fabs(v.t));
    mg[0] = ub;
    mg[1] = vb;
    mg[2] = 1.0 - ub - vb;
    mg[3] = v.t - tmin;
    mg[4] = tmax - v.t;
    eb[0] = eb[1] = eb[2] = bb;
    eb[3] = eb[4] = v.tb;
    for (k = 0; k < 5; k++) {
        ok &= mg[k] > eb[k];     /* every condition holds with room to spare */
        fail |= -mg[k] > eb[k];  /* some condition fails beyond its bound */
    }
    v.sure_hit = ok;
    v.sure_miss = fail;
    return v;
}

/* Comparison statistics of a structure against a reference. */
typedef struct cmp {
    unsigned long rays, hits, same, within, edge, bad, occ_bad, contract;
    double max_dt, max_bound;
} cmp_t;

/* Plane rounding part of the bound: 2^-16 (4 + L) in s15.16, 2^-20 (4 + L) in float32. */
static double lane_bound(int f32, const double o[3], double bmax)
{
    double l = fmax(fabs(o[0]), fmax(fabs(o[1]), fabs(o[2]))) + bmax;
    return f32 ? ldexp(4.0 + l, -20) : ldexp(4.0 + l, -16);
}

/* Is triangle id hit by lane i of the packet at exactly t (re-tested alone)? */
static int real_hit(const mesh_t *m, int f32, const pk_t *p, int i, int32_t id, double t)
{
    lt_hit16_t h;
    h.id = lt_vi32_set1(-1);
    if (!f32) {
        lt_ray16_q16_t r = p->q;
        if (ltt_tri16_q16(&r, (lt_mask16_t)(1u << i), &m->tq[id], id, &h) == 0)
            return 0;
        return lt_q16_to_double(r.tmax.l[i]) == t;
    }
#if LT_CFG_FLOAT32
    {
        lt_ray16_f32_t r = p->f;
        if (ltt_tri16_f32(&r, (lt_mask16_t)(1u << i), &m->tf[id], id, &h) == 0)
            return 0;
        return (double)r.tmax.l[i] == t;
    }
#else
    return 0;
#endif
}

/* A lane's result against the reference's. Same id: t must be bit-identical (same kernel). A
 * different id is explained in two ways only:
 *  - "within": both hit, the structure's hit is real, and the two distances differ by at most the
 *    plane bound plus both triangles' t bounds (which of two so close hits is first is numeric);
 *  - "edge": one side has no hit, and the triangle the other side hit is one the double verdict
 *    cannot call (neither a sure hit nor a sure miss within the kernel's bounds): a kernel hit
 *    that pokes past an edge by less than its error may lie outside every node or cell holding
 *    the triangle, or outside the reference's chunk box.
 * Everything else is unexplained. */
static void judge(cmp_t *c, const char *what, const mesh_t *m, int f32, const pk_t *p,
                  const res16_t *s, const res16_t *ref)
{
    int i;
    for (i = 0; i < LT_LANES; i++) {
        double b = lane_bound(f32, p->o[i], m->bmax);
        int32_t is = s->id[i], ir = ref->id[i];
        if (!LTT_ON(p->k, i))
            continue;
        c->rays++;
        c->hits += ir >= 0;
        c->max_bound = fmax(c->max_bound, b);
        if (LTT_ON(s->occ, i) != (ir >= 0) && LTT_ON(s->occ, i) != (is >= 0) &&
            c->occ_bad++ < 4)
            ltt_report("  FAIL %s occluded16: lane %d occluded %d, ids %d / reference %d\n", what,
                       i, LTT_ON(s->occ, i), is, ir);
        if (is == ir) {
            c->same++;
            if (is >= 0 && s->t[i] != ref->t[i] && c->bad++ < 6)
                ltt_report("  FAIL %s: lane %d same id %d but t %.9g != %.9g\n", what, i, is,
                           s->t[i], ref->t[i]);
            continue;
        }
        if (is >= 0 && !real_hit(m, f32, p, i, is, s->t[i])) {
            if (c->bad++ < 6)
                ltt_report("  FAIL %s: lane %d id %d t %.9g is not what lt_tri16 gives alone\n",
                           what, i, is, s->t[i]);
            continue;
        }
        if (is >= 0 && ir >= 0) {
            verdict_t vs = verdict(m, f32, p, i, is), vr = verdict(m, f32, p, i, ir);
            double lim = b + vs.tb + vr.tb, dt = fabs(s->t[i] - ref->t[i]);
            if (dt <= lim) {
                c->within++;
                c->max_dt = fmax(c->max_dt, dt);
                continue;
            }
        } else {
            verdict_t v = verdict(m, f32, p, i, is >= 0 ? is : ir);
            if (!v.sure_hit && !v.sure_miss) {
                c->edge++;
                continue;
            }
        }
        if (c->bad++ < 6)
            ltt_report("  FAIL %s: lane %d o (%.6g %.6g %.6g) id %d t %.9g, reference id %d t "
                       "%.9g (plane bound %.3g)\n",
                       what, i, p->o[i][0], p->o[i][1], p->o[i][2], is, s->t[i], ir, ref->t[i],
                       b);
    }
}

static void cmp_print(const cmp_t *c, const char *what)
{
    ltt_report("%s: %lu rays (%lu hit), same id %lu (%.4f%%); differences: %lu with both hits "
               "within the bound (plane <= %.3g + both triangles' t bounds; max |dt| %.3g), %lu "
               "at an edge the kernel cannot call, %lu unexplained; %lu contract violations; "
               "occluded16: %lu mismatches\n",
               what, c->rays, c->hits, c->same,
               c->rays ? 100.0 * (double)c->same / (double)c->rays : 100.0, c->within,
               c->max_bound, c->max_dt, c->edge, c->bad, c->contract, c->occ_bad);
}

/* No unexplained difference, no contract violation; at least min_same of the rays with the same
 * id (0.9999 for the scenes; the synthetic sets are built to be ambiguous: coplanar overlapping
 * triangles, shared edges, rays lying in cell and node boundary planes). */
static void cmp_assert(const cmp_t *c, double min_same)
{
    assert_int_equal(c->bad, 0);
    assert_int_equal(c->occ_bad, 0);
    assert_int_equal(c->contract, 0);
    assert_true((double)c->same >= min_same * (double)c->rays);
}

/* ---- kd-tree specifics --------------------------------------------------------------------- */

/* Build both paths into poisoned arenas of exactly lt_kd_size bytes plus a guard, checking the
 * guard and the compaction. Returns the arenas (caller frees). */
typedef struct kdpair {
    lt_kd_q16_t q;
    void *mq;
    size_t bound;
#if LT_CFG_FLOAT32
    lt_kd_f32_t f;
    void *mf;
#endif
} kdpair_t;

#define GUARD 256

static void kd_build_pair(kdpair_t *k, const mesh_t *m, const lt_kd_params_t *p)
{
    size_t sz, got;
    assert_int_equal(lt_kd_size(m->n, p, &sz), LT_OK);
    k->bound = sz;
    k->mq = malloc(sz + GUARD);
    assert_non_null(k->mq);
    ltt_poison(k->mq, sz + GUARD);
    got = sz;
    assert_int_equal(lt_kd_build_q16(&k->q, m->tq, m->n, p, k->mq, &got), LT_OK);
    assert_int_equal(ltt_touched(k->mq, sz, sz + GUARD), 0);
    assert_true(got == k->q.bytes && got <= sz);
    assert_true((const void *)k->q.nodes == k->mq);
    assert_true((const char *)k->q.refs == (const char *)k->mq + (size_t)k->q.nnodes * 8u);
#if LT_CFG_FLOAT32
    k->mf = malloc(sz + GUARD);
    assert_non_null(k->mf);
    ltt_poison(k->mf, sz + GUARD);
    got = sz;
    assert_int_equal(lt_kd_build_f32(&k->f, m->tf, m->n, p, k->mf, &got), LT_OK);
    assert_int_equal(ltt_touched(k->mf, sz, sz + GUARD), 0);
    assert_true(got == k->f.bytes && got <= sz);
#endif
}

static void kd_free_pair(kdpair_t *k)
{
    free(k->mq);
#if LT_CFG_FLOAT32
    free(k->mf);
#endif
}

static void acc_kd(acc_t *a, const kdpair_t *k)
{
    memset(a, 0, sizeof *a);
    a->name = "kd";
    a->q = &k->q;
    a->tq = kd_tq;
    a->oq = kd_oq;
#if LT_CFG_FLOAT32
    a->f = &k->f;
    a->tf = kd_tf;
    a->of = kd_of;
#endif
}


#endif /* LT_KDGRID_TESTLIB_H */
