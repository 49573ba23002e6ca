/* test_wt.c - cmocka tests of the watertight ray/triangle test (lt_wt.h, Woop, Benthin, Wald,
 * JCGT 2013 [Woop13]) in s15.16 and float32: crack tests on closed meshes, agreement with a double
 * reference, zero-area and degenerate triangles, rays parallel to the triangle's plane,
 * axis-parallel rays and the kz tie rule, lane independence, and (sim build) the cost per test
 * against lt_tri16_q16 (Moller-Trumbore). Every test prints what it checked.
 * Builds: host, sim, asan (any LT_COST_MODE); float32 parts only with LT_CFG_FLOAT32.
 *
 * Crack criterion. A ray aimed at a point p of a shared edge (or at a shared vertex) is judged on
 * D = the two triangles of the edge (the fan of the vertex), a disk around p. Project D with the
 * EXACT shear of the ray (double, from the kernel's own quantised inputs) to the 2D plane where
 * the ray is the origin. If the boundary polygon of D winds around the origin (|winding| >= 1:
 * the ray crosses the surface at p, it does not graze a silhouette) and stays farther than the
 * kernel's worst per-vertex displacement delta from it, then the kernel's own (rounded) 2D
 * triangles of D still wind around the origin, and an exact, consistent inside test must find
 * the origin in one of them (docs/watertight.md, proof sketch). So every such ray must hit a
 * triangle of D: a miss is a leak. delta: s15.16 moves each sheared coordinate by at most
 * |A_z| 2^-31 + 2^-17 < 2^-16 (|A| <= 2^13), and the test uses a margin of 2^-14; float32 moves
 * it by about 4 ulp of the largest |A| component, and the margin is 2^-18 max|A| + 2^-14.
 * Rays failing the criterion (silhouette, grazing) are counted and not judged.
 *
 * Reference bound (random rays). Per vertex the kernel's sheared x', y' differ from the exact
 * ones by eps <= |A_z| 2^-31 + 2^-17 (s15.16: rounded Sx, rounded product) and z' by the same;
 * the edge functions are then exact, so |dE| <= eps_b (|x_c| + |y_c|) + eps_c (|x_b| + |y_b|)
 * + 2 eps_b eps_c. A classification may differ only when some |E| <= dE (or |det| <= sum dE).
 * t = sum E_i z_i / det moves by at most sum dE_i |z_i - t| / (|det| - sum dE) + max dz + 2^-17
 * (final rounding): the E_i of a hit share det's sign, so the z error enters as a convex
 * combination. Float32 uses eps = 2^-21 (|A_x| + |A_y| + |A_z|), product and sum rounding
 * 2^-22 of the magnitudes involved, and 2^-21 relative on t.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lt/lt_wt.h"
#include "io/lt_fx_float.h"
#include "io/lt_mesh.h"
#include "render/lt_scene.h"
#include "lt_test_util.h"
#if LT_COST_MODE == LT_COST_SIM
#include "lt_sim.h"
#endif
/* internal: the triangle-parallel layout (lt__wt16_meet_tris) against the packet test */
#include "../../firmware/core/object/lt_isel.h"

#define FMT_Q16 0
#define FMT_F32 1
#define FMT_W32 2 /* s15.16 on the grid 2^w32_g (lt_tri16_wt32_q16, LT_ISECT_WT32) */
static unsigned w32_g;
#define ULP16 (1.0 / 65536.0)
#define TWO_PI 6.283185307179586

/* ---- small double geometry ------------------------------------------------------------------- */

typedef struct dray {
    double o[3], d[3], tmin, tmax; /* exact images of the kernel's inputs */
} dray_t;

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void normalize(double d[3])
{
    double n = sqrt(dot3(d, d));
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

/* The kernel's frame on exact direction values: kz = largest |d| (ties: z, then y), (kx, ky) the
 * next axes cyclically, swapped when d[kz] < 0; exact shear constants. */
typedef struct frame {
    int kx, ky, kz;
    double sx, sy, sz;
    double o[3];
} frame_t;

static void frame_axes(const double d[3], int *kx, int *ky, int *kz)
{
    double ax = fabs(d[0]), ay = fabs(d[1]), az = fabs(d[2]);
    int z = (az >= ax && az >= ay) ? 2 : (ay >= ax ? 1 : 0);
    *kz = z;
    *kx = (z + 1) % 3;
    *ky = (z + 2) % 3;
    if (d[z] < 0) {
        int s = *kx;
        *kx = *ky;
        *ky = s;
    }
}

static void frame_make(const dray_t *r, frame_t *f)
{
    frame_axes(r->d, &f->kx, &f->ky, &f->kz);
    f->sx = r->d[f->kx] / r->d[f->kz];
    f->sy = r->d[f->ky] / r->d[f->kz];
    f->sz = 1.0 / r->d[f->kz];
    memcpy(f->o, r->o, sizeof f->o);
}

/* Exact sheared image (x', y', z') of v, and |A| = the translated vertex's components. */
static void frame_proj(const frame_t *f, const double v[3], double out[3], double absa[3])
{
    double a[3];
    int i;
    for (i = 0; i < 3; i++)
        a[i] = v[i] - f->o[i];
    out[0] = a[f->kx] - f->sx * a[f->kz];
    out[1] = a[f->ky] - f->sy * a[f->kz];
    out[2] = f->sz * a[f->kz];
    absa[0] = fabs(a[f->kx]);
    absa[1] = fabs(a[f->ky]);
    absa[2] = fabs(a[f->kz]);
}

/* Winding number of a closed 2D polygon around the origin, and its distance to the origin. */
static int winding(const double (*p)[2], int n, double *mind)
{
    double sum = 0.0, md = HUGE_VAL;
    int i;
    for (i = 0; i < n; i++) {
        const double *a = p[i], *b = p[(i + 1) % n];
        double ex = b[0] - a[0], ey = b[1] - a[1], l2 = ex * ex + ey * ey, t = 0.0, dx, dy;
        if (l2 > 0.0) {
            t = -(a[0] * ex + a[1] * ey) / l2;
            t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
        }
        dx = a[0] + t * ex;
        dy = a[1] + t * ey;
        if (sqrt(dx * dx + dy * dy) < md)
            md = sqrt(dx * dx + dy * dy);
        sum += atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1]);
    }
    *mind = md;
    return (int)lround(sum / TWO_PI);
}

/* ---- packet lanes ---------------------------------------------------------------------------- */

static lt_vq16_t *q_o(lt_ray16_q16_t *p, int a)
{
    return a == 0 ? &p->ox : (a == 1 ? &p->oy : &p->oz);
}

static lt_vq30_t *q_d(lt_ray16_q16_t *p, int a)
{
    return a == 0 ? &p->dx : (a == 1 ? &p->dy : &p->dz);
}

/* Lane i from a double ray (d unit): origin rounded to s15.16, direction to s1.30; ex = exact. */
static void q_lane(lt_ray16_q16_t *p, int i, const double o[3], const double d[3], double tmin,
                   double tmax, dray_t *ex)
{
    int a;
    for (a = 0; a < 3; a++) {
        q_o(p, a)->l[i] = lt_q16_from_double_sat(o[a]);
        q_d(p, a)->l[i] = lt_q30_from_double_sat(d[a]);
        ex->o[a] = lt_q16_to_double(q_o(p, a)->l[i]);
        ex->d[a] = lt_q30_to_double(q_d(p, a)->l[i]);
    }
    p->tmin.l[i] = lt_q16_from_double_sat(tmin);
    p->tmax.l[i] = lt_q16_from_double_sat(tmax);
    ex->tmin = lt_q16_to_double(p->tmin.l[i]);
    ex->tmax = lt_q16_to_double(p->tmax.l[i]);
}

#if LT_CFG_FLOAT32
static lt_vf32_t *f_o(lt_ray16_f32_t *p, int a)
{
    return a == 0 ? &p->ox : (a == 1 ? &p->oy : &p->oz);
}

static lt_vf32_t *f_d(lt_ray16_f32_t *p, int a)
{
    return a == 0 ? &p->dx : (a == 1 ? &p->dy : &p->dz);
}

static void f_lane(lt_ray16_f32_t *p, int i, const double o[3], const double d[3], double tmin,
                   double tmax, dray_t *ex)
{
    int a;
    for (a = 0; a < 3; a++) {
        f_o(p, a)->l[i] = (float)o[a];
        f_d(p, a)->l[i] = (float)d[a];
        ex->o[a] = (double)f_o(p, a)->l[i];
        ex->d[a] = (double)f_d(p, a)->l[i];
    }
    p->tmin.l[i] = (float)tmin;
    p->tmax.l[i] = (float)tmax;
    ex->tmin = (double)p->tmin.l[i];
    ex->tmax = (double)p->tmax.l[i];
}
#endif

#if LT_CFG_FLOAT32
/* Replays the float32 kernel's edge functions for lane i of w against t with the same IEEE
 * operations (builds use -ffp-contract=off): 0 when none is exactly 0.0f; 1 when one is (the
 * kernel takes its double fallback) and the exact value is 0 too; 2 when a 0.0f hides a nonzero
 * exact value (the fallback recovers its sign). */
static int f32_zero_edge(const lt_wt16_f32_t *w, int i, const lt_tri_f32_t *t)
{
    float p[3][3], x[3], y[3], e[3];
    int v, a, kx = LTT_ON(w->kx[0], i) ? 0 : (LTT_ON(w->kx[1], i) ? 1 : 2);
    int ky = LTT_ON(w->ky[0], i) ? 0 : (LTT_ON(w->ky[1], i) ? 1 : 2);
    int kz = LTT_ON(w->kz[0], i) ? 0 : (LTT_ON(w->kz[1], i) ? 1 : 2);
    for (a = 0; a < 3; a++) {
        p[0][a] = t->v0[a];
        p[1][a] = t->v0[a] + t->e1[a];
        p[2][a] = t->v0[a] + t->e2[a];
    }
    for (v = 0; v < 3; v++) {
        float ax = p[v][kx] - w->ox.l[i], ay = p[v][ky] - w->oy.l[i], az = p[v][kz] - w->oz.l[i];
        x[v] = ax - w->sx.l[i] * az;
        y[v] = ay - w->sy.l[i] * az;
    }
    e[0] = x[2] * y[1] - y[2] * x[1];
    e[1] = x[0] * y[2] - y[0] * x[2];
    e[2] = x[1] * y[0] - y[1] * x[0];
    for (v = 0; v < 3; v++) {
        int c = (v + 2) % 3, b = (v + 1) % 3; /* e[v] = cross(x[c], x[b]) as in the kernel */
        double ex = (double)x[c] * (double)y[b] - (double)y[c] * (double)x[b];
        if (e[v] == 0.0f && ex != 0.0)
            return 2;
    }
    return e[0] == 0.0f || e[1] == 0.0f || e[2] == 0.0f;
}
#endif

/* ---- meshes with shared vertices ------------------------------------------------------------- */

typedef struct wmesh {
    const char *name;
    uint32_t nv, nt;
    lt_q16_t (*vq)[3];   /* vertices, s15.16 */
    double (*vd)[3];     /* their exact double images */
    uint32_t (*tv)[3];   /* triangle vertex indices, in stored winding */
    lt_tri_q16_t *tq;    /* v0 = vertex 0, e1/e2 exact differences */
    uint8_t *zq;         /* triangle has exactly zero area (s15.16) */
#if LT_CFG_FLOAT32
    float (*vf)[3];      /* vertices rounded to the 2^-8 grid: every difference exact in float */
    double (*vfd)[3];
    lt_tri_f32_t *tf;
    uint8_t *zf;
    unsigned long f_recon_bad; /* vertices that fl(v0 + e) did not rebuild bit-exactly */
#endif
    /* topology */
    uint32_t ne;         /* manifold, consistently oriented edges */
    uint32_t (*edge)[4]; /* P, Q, T1 (runs P->Q), T2 (runs Q->P) */
    uint32_t nbound, nnonman, nincons;
    uint32_t *fan_off;   /* CSR over vertices */
    uint32_t *fan;       /* incident triangles, in link order for interior vertices */
    uint32_t *link;      /* link cycle (the opposite vertices), same CSR */
    uint8_t *interior;   /* vertex has one closed, consistently oriented fan */
    uint32_t ninterior;
    double center[3], radius;
} wmesh_t;

static void *xcalloc(size_t n, size_t sz)
{
    void *p = calloc(n == 0 ? 1 : n, sz);
    assert_non_null(p);
    return p;
}

static void mesh_free(wmesh_t *m)
{
    free(m->vq);
    free(m->vd);
    free(m->tv);
    free(m->tq);
    free(m->zq);
#if LT_CFG_FLOAT32
    free(m->vf);
    free(m->vfd);
    free(m->tf);
    free(m->zf);
#endif
    free(m->edge);
    free(m->fan_off);
    free(m->fan);
    free(m->link);
    free(m->interior);
    memset(m, 0, sizeof *m);
}

typedef struct hedge {
    uint32_t lo, hi, a, b, t;
} hedge_t;

static int hedge_cmp(const void *x, const void *y)
{
    const hedge_t *p = (const hedge_t *)x, *q = (const hedge_t *)y;
    if (p->lo != q->lo)
        return p->lo < q->lo ? -1 : 1;
    if (p->hi != q->hi)
        return p->hi < q->hi ? -1 : 1;
    return p->t < q->t ? -1 : (p->t > q->t);
}

static uint32_t third(const uint32_t t[3], uint32_t a, uint32_t b)
{
    int i;
    for (i = 0; i < 3; i++)
        if (t[i] != a && t[i] != b)
            return t[i];
    return t[0];
}

/* From vq/tv: triangles in both formats, zero-area flags, manifold edges, vertex fans. */
static void mesh_finish(wmesh_t *m)
{
    hedge_t *h = (hedge_t *)xcalloc((size_t)m->nt * 3, sizeof *h);
    uint32_t i, j, n = m->nt * 3, *cnt;
    double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
    int a;

    m->vd = (double(*)[3])xcalloc(m->nv, sizeof *m->vd);
    for (i = 0; i < m->nv; i++)
        for (a = 0; a < 3; a++) {
            m->vd[i][a] = lt_q16_to_double(m->vq[i][a]);
            lo[a] = fmin(lo[a], m->vd[i][a]);
            hi[a] = fmax(hi[a], m->vd[i][a]);
        }
    m->radius = 0.0;
    for (a = 0; a < 3; a++) {
        m->center[a] = 0.5 * (lo[a] + hi[a]);
        m->radius += 0.25 * (hi[a] - lo[a]) * (hi[a] - lo[a]);
    }
    m->radius = sqrt(m->radius);
    m->tq = (lt_tri_q16_t *)xcalloc(m->nt, sizeof *m->tq);
    m->zq = (uint8_t *)xcalloc(m->nt, 1);
    for (i = 0; i < m->nt; i++) {
        const lt_q16_t *p0 = m->vq[m->tv[i][0]], *p1 = m->vq[m->tv[i][1]], *p2 = m->vq[m->tv[i][2]];
        int64_t c[3];
        for (a = 0; a < 3; a++) {
            m->tq[i].v0[a] = p0[a];
            m->tq[i].e1[a] = p1[a] - p0[a];
            m->tq[i].e2[a] = p2[a] - p0[a];
        }
        c[0] = (int64_t)m->tq[i].e1[1] * m->tq[i].e2[2] - (int64_t)m->tq[i].e1[2] * m->tq[i].e2[1];
        c[1] = (int64_t)m->tq[i].e1[2] * m->tq[i].e2[0] - (int64_t)m->tq[i].e1[0] * m->tq[i].e2[2];
        c[2] = (int64_t)m->tq[i].e1[0] * m->tq[i].e2[1] - (int64_t)m->tq[i].e1[1] * m->tq[i].e2[0];
        m->zq[i] = c[0] == 0 && c[1] == 0 && c[2] == 0;
    }
#if LT_CFG_FLOAT32
    m->vf = (float(*)[3])xcalloc(m->nv, sizeof *m->vf);
    m->vfd = (double(*)[3])xcalloc(m->nv, sizeof *m->vfd);
    m->tf = (lt_tri_f32_t *)xcalloc(m->nt, sizeof *m->tf);
    m->zf = (uint8_t *)xcalloc(m->nt, 1);
    m->f_recon_bad = 0;
    for (i = 0; i < m->nv; i++)
        for (a = 0; a < 3; a++) {
            m->vf[i][a] = (float)ldexp(floor(ldexp(m->vd[i][a], 8) + 0.5), -8);
            m->vfd[i][a] = (double)m->vf[i][a];
        }
    for (i = 0; i < m->nt; i++) {
        const float *p0 = m->vf[m->tv[i][0]], *p1 = m->vf[m->tv[i][1]], *p2 = m->vf[m->tv[i][2]];
        double e1[3], e2[3];
        for (a = 0; a < 3; a++) {
            m->tf[i].v0[a] = p0[a];
            m->tf[i].e1[a] = p1[a] - p0[a];
            m->tf[i].e2[a] = p2[a] - p0[a];
            m->f_recon_bad += (unsigned long)((p0[a] + m->tf[i].e1[a] != p1[a]) +
                                              (p0[a] + m->tf[i].e2[a] != p2[a]));
            e1[a] = (double)m->tf[i].e1[a];
            e2[a] = (double)m->tf[i].e2[a];
        }
        m->zf[i] = e1[1] * e2[2] == e1[2] * e2[1] && e1[2] * e2[0] == e1[0] * e2[2] &&
                   e1[0] * e2[1] == e1[1] * e2[0];
    }
#endif
    /* edges: half-edges sorted by their vertex pair */
    for (i = 0; i < m->nt; i++)
        for (j = 0; j < 3; j++) {
            uint32_t va = m->tv[i][j], vb = m->tv[i][(j + 1) % 3];
            hedge_t *e = &h[i * 3 + j];
            e->a = va;
            e->b = vb;
            e->lo = va < vb ? va : vb;
            e->hi = va < vb ? vb : va;
            e->t = i;
        }
    qsort(h, n, sizeof *h, hedge_cmp);
    m->edge = (uint32_t(*)[4])xcalloc(n, sizeof *m->edge);
    m->ne = m->nbound = m->nnonman = m->nincons = 0;
    for (i = 0; i < n;) {
        for (j = i + 1; j < n && h[j].lo == h[i].lo && h[j].hi == h[i].hi; j++)
            ;
        if (j - i == 1) {
            m->nbound++;
        } else if (j - i > 2) {
            m->nnonman++;
        } else if (h[i].a == h[i + 1].a) {
            m->nincons++;
        } else {
            m->edge[m->ne][0] = h[i].a;
            m->edge[m->ne][1] = h[i].b;
            m->edge[m->ne][2] = h[i].t;
            m->edge[m->ne][3] = h[i + 1].t;
            m->ne++;
        }
        i = j;
    }
    free(h);
    /* vertex fans (CSR), then the link cycle of each vertex */
    cnt = (uint32_t *)xcalloc(m->nv + 1, sizeof *cnt);
    m->fan_off = (uint32_t *)xcalloc(m->nv + 1, sizeof *m->fan_off);
    for (i = 0; i < m->nt; i++)
        for (j = 0; j < 3; j++)
            m->fan_off[m->tv[i][j] + 1]++;
    for (i = 0; i < m->nv; i++)
        m->fan_off[i + 1] += m->fan_off[i];
    m->fan = (uint32_t *)xcalloc(n, sizeof *m->fan);
    m->link = (uint32_t *)xcalloc(n, sizeof *m->link);
    for (i = 0; i < m->nt; i++)
        for (j = 0; j < 3; j++) {
            uint32_t v = m->tv[i][j];
            m->fan[m->fan_off[v] + cnt[v]++] = i;
        }
    m->interior = (uint8_t *)xcalloc(m->nv, 1);
    m->ninterior = 0;
    for (i = 0; i < m->nv; i++) {
        uint32_t b = m->fan_off[i], k = m->fan_off[i + 1] - b, s, step, cur;
        int ok = k >= 3 && k <= 64;
        uint32_t *fa = &m->fan[b], *qa, *qb, *ord, *lk;
        if (!ok)
            continue;
        qa = (uint32_t *)xcalloc(k, sizeof *qa);
        qb = (uint32_t *)xcalloc(k, sizeof *qb);
        ord = (uint32_t *)xcalloc(k, sizeof *ord);
        lk = (uint32_t *)xcalloc(k, sizeof *lk);
        /* rotate each fan triangle to (i, qa, qb) in its winding; the link edges qa -> qb must
         * chain into one cycle through all k triangles */
        for (s = 0; s < k; s++) {
            const uint32_t *t = m->tv[fa[s]];
            int c = t[0] == i ? 0 : (t[1] == i ? 1 : 2);
            qa[s] = t[(c + 1) % 3];
            qb[s] = t[(c + 2) % 3];
            ok &= !m->zq[fa[s]];
        }
        cur = 0;
        for (step = 0; step < k && ok; step++) {
            uint32_t nx = k, c2;
            ord[step] = cur;
            lk[step] = qa[cur];
            for (c2 = 0; c2 < k; c2++)
                if (qa[c2] == qb[cur]) {
                    if (nx != k)
                        ok = 0; /* two successors: not a disk */
                    nx = c2;
                }
            if (nx == k || (nx == 0) != (step + 1 == k))
                ok = 0;
            cur = nx;
        }
        if (ok) {
            uint32_t tmp[64];
            m->interior[i] = 1;
            m->ninterior++;
            for (s = 0; s < k; s++)
                tmp[s] = fa[ord[s]];
            for (s = 0; s < k; s++) {
                fa[s] = tmp[s];
                m->link[b + s] = lk[s];
            }
        }
        free(qa);
        free(qb);
        free(ord);
        free(lk);
    }
    free(cnt);
}

/* Orient every triangle of a convex mesh outward (normal away from the centroid). */
static void mesh_orient_convex(wmesh_t *m)
{
    double c[3] = { 0, 0, 0 };
    uint32_t i;
    int a;
    for (i = 0; i < m->nv; i++)
        for (a = 0; a < 3; a++)
            c[a] += lt_q16_to_double(m->vq[i][a]) / m->nv;
    for (i = 0; i < m->nt; i++) {
        double p[3][3], e1[3], e2[3], n[3], w[3];
        int j;
        for (j = 0; j < 3; j++)
            for (a = 0; a < 3; a++)
                p[j][a] = lt_q16_to_double(m->vq[m->tv[i][j]][a]);
        for (a = 0; a < 3; a++) {
            e1[a] = p[1][a] - p[0][a];
            e2[a] = p[2][a] - p[0][a];
            w[a] = p[0][a] - c[a];
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        if (dot3(n, w) < 0) {
            uint32_t s = m->tv[i][1];
            m->tv[i][1] = m->tv[i][2];
            m->tv[i][2] = s;
        }
    }
}

static void mesh_tetra(wmesh_t *m)
{
    static const double v[4][3] = { { 173.3, 180.1, 165.7 },
                                    { 170.2, -181.9, -166.4 },
                                    { -171.8, 179.4, -168.8 },
                                    { -169.5, -178.6, 170.9 } };
    static const uint32_t t[4][3] = { { 0, 1, 2 }, { 0, 3, 1 }, { 0, 2, 3 }, { 1, 3, 2 } };
    uint32_t i;
    int a;
    memset(m, 0, sizeof *m);
    m->name = "tetrahedron";
    m->nv = 4;
    m->nt = 4;
    m->vq = (lt_q16_t(*)[3])xcalloc(4, sizeof *m->vq);
    m->tv = (uint32_t(*)[3])xcalloc(4, sizeof *m->tv);
    for (i = 0; i < 4; i++)
        for (a = 0; a < 3; a++) {
            m->vq[i][a] = lt_q16_from_double_sat(v[i][a]);
            m->tv[i][a] = t[i][a];
        }
    mesh_orient_convex(m);
    mesh_finish(m);
}

/* Octahedron subdivided `levels` times (each triangle into 4, midpoints shared), vertices pushed
 * to a sphere of radius 300 and rounded to s15.16: 8 * 4^levels triangles. */
static void mesh_octasphere(wmesh_t *m, int levels)
{
    static const double ov[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 },
                                     { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
    static const uint32_t ot[8][3] = { { 0, 2, 4 }, { 2, 1, 4 }, { 1, 3, 4 }, { 3, 0, 4 },
                                       { 2, 0, 5 }, { 1, 2, 5 }, { 3, 1, 5 }, { 0, 3, 5 } };
    uint32_t maxv = 6, maxt = 8, nv = 6, nt = 8, i, l;
    double(*p)[3];
    uint32_t(*t)[3];
    int a;
    for (l = 0; l < (uint32_t)levels; l++) {
        maxv += maxt * 3 / 2;
        maxt *= 4;
    }
    p = (double(*)[3])xcalloc(maxv, sizeof *p);
    t = (uint32_t(*)[3])xcalloc(maxt, sizeof *t);
    memcpy(p, ov, sizeof ov);
    memcpy(t, ot, sizeof ot);
    for (l = 0; l < (uint32_t)levels; l++) {
        uint32_t nv0 = nv, *mid = (uint32_t *)xcalloc((size_t)nv * nv, sizeof *mid);
        uint32_t(*t2)[3] = (uint32_t(*)[3])xcalloc((size_t)nt * 4, sizeof *t2);
        for (i = 0; i < nt; i++) {
            uint32_t c[3], j;
            for (j = 0; j < 3; j++) {
                uint32_t x = t[i][j], y = t[i][(j + 1) % 3], lo = x < y ? x : y, hi = x < y ? y : x;
                if (mid[lo * nv0 + hi] == 0) {
                    for (a = 0; a < 3; a++)
                        p[nv][a] = 0.5 * (p[x][a] + p[y][a]);
                    normalize(p[nv]);
                    mid[lo * nv0 + hi] = nv++;
                }
                c[j] = mid[lo * nv0 + hi];
            }
            /* c[j] is the midpoint of edge (t[j], t[j+1]) */
            t2[i * 4][0] = t[i][0], t2[i * 4][1] = c[0], t2[i * 4][2] = c[2];
            t2[i * 4 + 1][0] = c[0], t2[i * 4 + 1][1] = t[i][1], t2[i * 4 + 1][2] = c[1];
            t2[i * 4 + 2][0] = c[2], t2[i * 4 + 2][1] = c[1], t2[i * 4 + 2][2] = t[i][2];
            t2[i * 4 + 3][0] = c[0], t2[i * 4 + 3][1] = c[1], t2[i * 4 + 3][2] = c[2];
        }
        memcpy(t, t2, (size_t)nt * 4 * sizeof *t);
        nt *= 4;
        free(t2);
        free(mid);
    }
    memset(m, 0, sizeof *m);
    m->name = "octasphere";
    m->nv = nv;
    m->nt = nt;
    m->vq = (lt_q16_t(*)[3])xcalloc(nv, sizeof *m->vq);
    m->tv = (uint32_t(*)[3])xcalloc(nt, sizeof *m->tv);
    for (i = 0; i < nv; i++)
        for (a = 0; a < 3; a++)
            m->vq[i][a] = lt_q16_from_double_sat(300.0 * p[i][a] + 0.37 * (a + 1));
    memcpy(m->tv, t, (size_t)nt * sizeof *t);
    free(p);
    free(t);
    mesh_orient_convex(m);
    mesh_finish(m);
}

typedef struct corner {
    lt_q16_t x[3];
    uint32_t idx;
} corner_t;

static int corner_cmp(const void *a, const void *b)
{
    const corner_t *p = (const corner_t *)a, *q = (const corner_t *)b;
    int i;
    for (i = 0; i < 3; i++)
        if (p->x[i] != q->x[i])
            return p->x[i] < q->x[i] ? -1 : 1;
    return 0;
}

/* A scene file through lt_mesh_load + lt_scene_prepare, its s15.16 vertices welded by value.
 * Returns 0, or -1 when the file cannot be loaded (message printed). */
static int mesh_file(wmesh_t *m, const char *name, const char *path)
{
    lt_mesh_t mesh;
    lt_scene_t sc;
    lt_diag_t diag;
    corner_t *c;
    uint32_t i, n;
    memset(m, 0, sizeof *m);
    if (lt_mesh_load(path, &mesh, &diag) != 0) {
        ltt_report("  %s: %s\n", name, diag.msg);
        return -1;
    }
    if (lt_scene_prepare(&mesh, &sc, &diag) != 0) {
        ltt_report("  %s: %s\n", name, diag.msg);
        lt_mesh_free(&mesh);
        return -1;
    }
    n = sc.ntris * 3;
    c = (corner_t *)xcalloc(n, sizeof *c);
    for (i = 0; i < sc.ntris; i++) {
        int a;
        for (a = 0; a < 3; a++) {
            c[i * 3].x[a] = sc.tq[i].v0[a];
            c[i * 3 + 1].x[a] = sc.tq[i].v0[a] + sc.tq[i].e1[a];
            c[i * 3 + 2].x[a] = sc.tq[i].v0[a] + sc.tq[i].e2[a];
        }
        c[i * 3].idx = i * 3;
        c[i * 3 + 1].idx = i * 3 + 1;
        c[i * 3 + 2].idx = i * 3 + 2;
    }
    qsort(c, n, sizeof *c, corner_cmp);
    m->name = name;
    m->nt = sc.ntris;
    m->vq = (lt_q16_t(*)[3])xcalloc(n, sizeof *m->vq);
    m->tv = (uint32_t(*)[3])xcalloc(m->nt, sizeof *m->tv);
    m->nv = 0;
    for (i = 0; i < n; i++) {
        if (i == 0 || corner_cmp(&c[i], &c[i - 1]) != 0) {
            memcpy(m->vq[m->nv], c[i].x, sizeof c[i].x);
            m->nv++;
        }
        m->tv[c[i].idx / 3][c[i].idx % 3] = m->nv - 1;
    }
    free(c);
    lt_scene_free(&sc);
    lt_mesh_free(&mesh);
    mesh_finish(m);
    return 0;
}

/* ---- crack test ------------------------------------------------------------------------------ */

typedef struct crack {
    unsigned long rays[2];     /* [0] aimed at edges, [1] at vertices */
    unsigned long judged[2];   /* crossing with margin: must hit */
    unsigned long leak_wt[2];  /* judged rays the watertight test let through */
    unsigned long leak_mt[2];  /* the same rays through lt_tri16 (Moller-Trumbore) */
    unsigned long multi[2];    /* judged rays accepted by 2+ triangles of D (shared edge ties) */
    unsigned long fallback[2]; /* float32 lane-triangle tests with a 0.0f edge function; of
                                  them, with a nonzero exact value (sign recovered in double) */
    double max_dt;             /* max |t - distance to the target| of judged hits */
} crack_t;

#define MAX_D 64

/* One packet of 16 rays at one feature. D = triangles around the target; poly = D's boundary
 * (vertex indices, cyclic); targets: edge (P, Q) when q_is_edge, else vertex P. */
typedef struct feature {
    int is_edge;
    uint32_t P, Q;
    uint32_t d[MAX_D], nd;
    uint32_t poly[MAX_D], np;
} feature_t;

static int feature_edge(const wmesh_t *m, uint32_t e, feature_t *f, int fmt)
{
    uint32_t P = m->edge[e][0], Q = m->edge[e][1], T1 = m->edge[e][2], T2 = m->edge[e][3];
    const uint8_t *z = m->zq;
#if LT_CFG_FLOAT32
    if (fmt == FMT_F32)
        z = m->zf;
#else
    (void)fmt;
#endif
    if (z[T1] || z[T2])
        return 0;
    f->is_edge = 1;
    f->P = P;
    f->Q = Q;
    f->nd = 2;
    f->d[0] = T1;
    f->d[1] = T2;
    /* T1 = (P, Q, R), T2 = (Q, P, S): boundary P -> S -> Q -> R */
    f->np = 4;
    f->poly[0] = P;
    f->poly[1] = third(m->tv[T2], P, Q);
    f->poly[2] = Q;
    f->poly[3] = third(m->tv[T1], P, Q);
    return 1;
}

static int feature_vertex(const wmesh_t *m, uint32_t v, feature_t *f, int fmt)
{
    uint32_t b = m->fan_off[v], k = m->fan_off[v + 1] - b, i;
    if (!m->interior[v] || k > MAX_D)
        return 0;
    for (i = 0; i < k; i++) {
#if LT_CFG_FLOAT32
        if (fmt == FMT_F32 && m->zf[m->fan[b + i]])
            return 0;
#else
        (void)fmt;
#endif
        f->d[i] = m->fan[b + i];
        f->poly[i] = m->link[b + i];
    }
    f->is_edge = 0;
    f->P = f->Q = v;
    f->nd = f->np = k;
    return 1;
}

/* Judge lane ray r against feature f of mesh m in format fmt: 1 when the ray crosses the
 * surface at the target with the margin of the file header. */
static int crossing(const wmesh_t *m, const feature_t *f, const dray_t *r, int fmt)
{
    frame_t fr;
    double poly[MAX_D][2], maxa = 0.0, dist;
    uint32_t i;
    int w, a;
    frame_make(r, &fr);
    for (i = 0; i < f->np; i++) {
        double s[3], aa[3];
        const double *v = m->vd[f->poly[i]];
#if LT_CFG_FLOAT32
        if (fmt == FMT_F32)
            v = m->vfd[f->poly[i]];
#endif
        frame_proj(&fr, v, s, aa);
        poly[i][0] = s[0];
        poly[i][1] = s[1];
        for (a = 0; a < 3; a++)
            maxa = fmax(maxa, aa[a]);
    }
    w = winding((const double(*)[2])poly, (int)f->np, &dist);
    /* the grid moves each snapped coordinate by at most half a step, 2^(g-17) units */
    return w != 0 && dist > (fmt == FMT_Q16   ? ldexp(1.0, -14)
                             : fmt == FMT_W32 ? ldexp(1.0, -14) + ldexp(3.0, (int)w32_g - 17)
                                              : ldexp(maxa, -18) + ldexp(1.0, -14));
}

/* Rays of packet `pk` at feature f: a random origin per lane (or one for all lanes when
 * `coherent`) at 2.5 radii from the centre; target = the vertex, or the edge midpoint (lane 0)
 * and points at random fractions of the edge. Runs the watertight test and Moller-Trumbore of
 * format fmt over D and tallies into c. */
static void crack_packet(const wmesh_t *m, const feature_t *f, ltt_rng_t *rng, int coherent,
                         int fmt, crack_t *c)
{
    dray_t dr[LT_LANES];
    double tp[LT_LANES];
    lt_mask16_t judge = 0, wt = 0, mt = 0, multi = 0;
    double oc[3];
    int i, a, kind = f->is_edge ? 0 : 1;
    uint32_t j;
    lt_ray16_q16_t pq, pq2;
    lt_wt16_q16_t wq;
#if LT_CFG_FLOAT32
    lt_ray16_f32_t pf, pf2;
    lt_wt16_f32_t wf;
    memset(&pf, 0, sizeof pf);
#endif
    memset(&pq, 0, sizeof pq);
    rng_unit(rng, oc);
    for (i = 0; i < LT_LANES; i++) {
        double o[3], p[3], d[3], s, fr = i == 0 ? 0.5 : ltt_rng_unit(rng);
        const double *vp = m->vd[f->P], *vq = m->vd[f->Q];
#if LT_CFG_FLOAT32
        if (fmt == FMT_F32) {
            vp = m->vfd[f->P];
            vq = m->vfd[f->Q];
        }
#endif
        if (!coherent)
            rng_unit(rng, oc);
        for (a = 0; a < 3; a++) {
            o[a] = m->center[a] + 2.5 * m->radius * oc[a];
            p[a] = f->is_edge ? vp[a] + fr * (vq[a] - vp[a]) : vp[a];
            d[a] = p[a] - o[a];
        }
        s = sqrt(dot3(d, d));
        normalize(d);
        if (fmt != FMT_F32)
            q_lane(&pq, i, o, d, 0.0, 2.0 * s + 10.0, &dr[i]);
#if LT_CFG_FLOAT32
        else
            f_lane(&pf, i, o, d, 0.0, 2.0 * s + 10.0, &dr[i]);
#endif
        for (a = 0; a < 3; a++)
            d[a] = p[a] - dr[i].o[a];
        tp[i] = sqrt(dot3(d, d));
        if (crossing(m, f, &dr[i], fmt))
            judge = (lt_mask16_t)(judge | (1u << i));
    }
    /* each triangle of D from the same tmax, so that every triangle that accepts a ray is
     * counted (ties on a shared edge accept both) */
    if (fmt != FMT_F32) {
        lt_hit16_t h1, h2;
        lt_vq16_t tmax0;
        lt_ray16_q16_setup(&pq);
        (void)lt_ray16_wt_setup_q16(&pq, &wq);
        pq2 = pq;
        tmax0 = pq.tmax;
        h1.id = h2.id = lt_vi32_set1(-1);
        for (j = 0; j < f->nd; j++) {
            lt_mask16_t hm = fmt == FMT_W32
                                 ? lt_tri16_wt32_q16(&pq, &wq, w32_g, LT_MASK_ALL,
                                                     &m->tq[f->d[j]], (int32_t)f->d[j], &h1)
                                 : lt_tri16_wt_q16(&pq, &wq, LT_MASK_ALL, &m->tq[f->d[j]],
                                                   (int32_t)f->d[j], &h1);
            multi = (lt_mask16_t)(multi | (wt & hm));
            wt = (lt_mask16_t)(wt | hm);
            for (i = 0; i < LT_LANES; i++)
                if (LTT_ON(hm, i) && LTT_ON(judge, i))
                    c->max_dt = fmax(c->max_dt, fabs(lt_q16_to_double(pq.tmax.l[i]) - tp[i]));
            pq.tmax = tmax0;
            mt = (lt_mask16_t)(mt | lt_tri16_q16(&pq2, LT_MASK_ALL, &m->tq[f->d[j]],
                                                 (int32_t)f->d[j], &h2));
            pq2.tmax = tmax0;
        }
    }
#if LT_CFG_FLOAT32
    else {
        lt_hit16_t h1, h2;
        lt_vf32_t tmax0;
        lt_ray16_f32_setup(&pf);
        (void)lt_ray16_wt_setup_f32(&pf, &wf);
        pf2 = pf;
        tmax0 = pf.tmax;
        h1.id = h2.id = lt_vi32_set1(-1);
        for (j = 0; j < f->nd; j++) {
            lt_mask16_t hm = lt_tri16_wt_f32(&pf, &wf, LT_MASK_ALL, &m->tf[f->d[j]],
                                             (int32_t)f->d[j], &h1);
            for (i = 0; i < LT_LANES; i++) {
                int zr = f32_zero_edge(&wf, i, &m->tf[f->d[j]]);
                c->fallback[0] += zr != 0;
                c->fallback[1] += zr == 2;
            }
            multi = (lt_mask16_t)(multi | (wt & hm));
            wt = (lt_mask16_t)(wt | hm);
            for (i = 0; i < LT_LANES; i++)
                if (LTT_ON(hm, i) && LTT_ON(judge, i))
                    c->max_dt = fmax(c->max_dt, fabs((double)pf.tmax.l[i] - tp[i]));
            pf.tmax = tmax0;
            mt = (lt_mask16_t)(mt | lt_tri16_f32(&pf2, LT_MASK_ALL, &m->tf[f->d[j]],
                                                 (int32_t)f->d[j], &h2));
            pf2.tmax = tmax0;
        }
    }
#endif
    c->rays[kind] += LT_LANES;
    c->judged[kind] += lt__popcount32(judge);
    c->leak_wt[kind] += lt__popcount32((uint32_t)judge & ~(uint32_t)wt);
    c->leak_mt[kind] += lt__popcount32((uint32_t)judge & ~(uint32_t)mt);
    c->multi[kind] += lt__popcount32((uint32_t)judge & multi);
    if ((judge & ~wt) != 0) {
        for (i = 0; i < LT_LANES; i++)
            if (LTT_ON(judge, i) && !LTT_ON(wt, i) && c->leak_wt[kind] < 6)
                ltt_report("  FAIL %s %s leak: %s %u-%u lane %d o=(%.9g %.9g %.9g) d=(%.12g %.12g "
                           "%.12g)\n", fmt == FMT_Q16 ? "q16" : fmt == FMT_W32 ? "wt32" : "f32",
                           m->name,
                           f->is_edge ? "edge" : "vertex", f->P, f->Q, i, dr[i].o[0], dr[i].o[1],
                           dr[i].o[2], dr[i].d[0], dr[i].d[1], dr[i].d[2]);
    }
}

/* Every manifold edge (edge_packets packets) and every interior vertex (vertex_packets) of m. */
static void crack_mesh(const wmesh_t *m, int fmt, unsigned edge_packets, unsigned vertex_packets,
                       uint64_t seed, crack_t *c)
{
    ltt_rng_t r;
    uint32_t e, v;
    unsigned k;
    feature_t f;
    ltt_rng_seed(&r, seed);
    memset(c, 0, sizeof *c);
    for (e = 0; e < m->ne; e++)
        if (feature_edge(m, e, &f, fmt))
            for (k = 0; k < edge_packets; k++)
                crack_packet(m, &f, &r, (int)((e + k) & 1u), fmt, c);
    for (v = 0; v < m->nv; v++)
        if (feature_vertex(m, v, &f, fmt))
            for (k = 0; k < vertex_packets; k++)
                crack_packet(m, &f, &r, (int)((v + k) & 1u), fmt, c);
}

static unsigned long crack_report(const wmesh_t *m, int fmt, const crack_t *c)
{
    const char *wt = fmt == FMT_Q16   ? "lt_tri16_wt_q16"
                     : fmt == FMT_W32 ? "lt_tri16_wt32_q16"
                                      : "lt_tri16_wt_f32";
    const char *mt = fmt == FMT_F32 ? "lt_tri16_f32" : "lt_tri16_q16";
    ltt_report("%s%s crack, %s (%u tris, %u manifold edges, %u boundary, %u non-manifold, %u "
               "inconsistent; %u/%u interior vertices): %lu rays at edges, %lu at vertices; "
               "crossing with margin: %lu + %lu; leaked %lu + %lu (bound 0); %lu + %lu hit 2+ "
               "triangles; max |t - target| %.3g\n",
               wt, fmt == FMT_W32 ? " (on the grid)" : "",
               m->name, m->nt, m->ne, m->nbound, m->nnonman, m->nincons, m->ninterior, m->nv,
               c->rays[0], c->rays[1], c->judged[0], c->judged[1], c->leak_wt[0], c->leak_wt[1],
               c->multi[0], c->multi[1], c->max_dt);
    if (fmt == FMT_F32)
        ltt_report("  %s: %lu lane-triangle tests had a 0.0f edge function (double fallback), "
                   "%lu of them nonzero in double (sign recovered)\n", wt, c->fallback[0],
                   c->fallback[1]);
    ltt_report("%s (Moller-Trumbore) on the same rays, %s: leaked %lu at edges, %lu at vertices\n",
               mt, m->name, c->leak_mt[0], c->leak_mt[1]);
    return c->leak_wt[0] + c->leak_wt[1];
}

static void crack_all_formats(wmesh_t *m, unsigned ep, unsigned vp, uint64_t seed)
{
    crack_t c;
    unsigned long bad;
    unsigned k;
    crack_mesh(m, FMT_Q16, ep, vp, seed, &c);
    bad = crack_report(m, FMT_Q16, &c);
    assert_true(c.judged[0] > 0);
    /* the grid test at the mesh's own grid (lt_wt32_shift_q16) and at 4 steps coarser */
    for (k = 0; k < 2; k++) {
        w32_g = lt_wt32_shift_q16(m->tq, m->nt) + 4u * k;
        w32_g = w32_g > LT_WT32_SHIFT_MAX ? LT_WT32_SHIFT_MAX : w32_g;
        ltt_report("  %s: LT_ISECT_WT32 grid 2^%u raw (%.3g units)%s\n", m->name, w32_g,
                   ldexp(1.0, (int)w32_g - 16),
                   k ? ", coarser than lt_wt32_shift_q16's (+4, at most 15)" : "");
        crack_mesh(m, FMT_W32, ep, vp, seed + 2 + k, &c);
        bad += crack_report(m, FMT_W32, &c);
        assert_true(c.judged[0] > 0);
    }
#if LT_CFG_FLOAT32
    ltt_report("  %s float32 copy on the 2^-8 grid: %lu vertex rebuilds fl(v0 + e) inexact "
               "(bound 0)\n", m->name, m->f_recon_bad);
    bad += m->f_recon_bad;
    crack_mesh(m, FMT_F32, ep, vp, seed + 1, &c);
    bad += crack_report(m, FMT_F32, &c);
#endif
    assert_int_equal(bad, 0);
}

static void test_crack_tetra(void **state)
{
    wmesh_t m;
    (void)state;
    mesh_tetra(&m);
    assert_int_equal(m.ne, 6);
    assert_int_equal(m.ninterior, 4);
    crack_all_formats(&m, 64, 64, 7001);
    mesh_free(&m);
}

static void test_crack_octasphere(void **state)
{
    wmesh_t m;
    (void)state;
    mesh_octasphere(&m, 3);
    assert_int_equal(m.nt, 512);
    assert_int_equal(m.ne, 768);
    assert_int_equal(m.ninterior, m.nv);
    crack_all_formats(&m, 3, 3, 7002);
    mesh_free(&m);
}

static void test_crack_teapot(void **state)
{
    wmesh_t m;
    (void)state;
    if (mesh_file(&m, "teapot", "scenes/teapot.obj") != 0)
        fail_msg("scenes/teapot.obj (bundled) could not be loaded; run from the repository root");
    crack_all_formats(&m, 1, 2, 7003);
    mesh_free(&m);
}

/* ../shared/scenes/bunny.obj (LT_SHARED overrides ../shared): skipped with a SKIP line when
 * missing, a failure under CI=true. */
static void test_crack_bunny(void **state)
{
    const char *root = getenv("LT_SHARED"), *ci = getenv("CI");
    char path[512];
    wmesh_t m;
    FILE *f;
    (void)state;
    (void)snprintf(path, sizeof path, "%s/scenes/bunny.obj", root != NULL ? root : "../shared");
    f = fopen(path, "rb");
    if (f == NULL) {
        int strict = ci != NULL && strcmp(ci, "true") == 0;
        if (strict)
            fail_msg("FAIL ../shared/scenes/bunny.obj (looked for %s) missing under CI=true",
                     path);
        ltt_report("SKIP ../shared/scenes/bunny.obj (looked for %s): not present\n", path);
        return;
    }
    fclose(f);
    assert_int_equal(mesh_file(&m, "bunny", path), 0);
    crack_all_formats(&m, 1, 1, 7004);
    mesh_free(&m);
}

/* ---- axis-parallel rays on a flat grid, and the kz tie rule ---------------------------------- */

/* kz, kx, ky and the shear constants for exact axis directions and exact ties. */
static void test_axes_ties(void **state)
{
    static const int dirs[][3] = {
        { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 },
        { 1, 1, 0 }, { -1, 1, 0 }, { 1, -1, 0 }, { 1, 0, 1 }, { 1, 0, -1 }, { 0, 1, 1 },
        { 0, -1, -1 }, { 1, 1, 1 }, { -1, -1, -1 }, { 1, -1, 1 },
    };
    lt_ray16_q16_t p;
    lt_wt16_q16_t w;
    unsigned long bad = 0;
    int i, a;
    (void)state;
    memset(&p, 0, sizeof p);
    for (i = 0; i < LT_LANES; i++) {
        double n = sqrt((double)(dirs[i][0] * dirs[i][0] + dirs[i][1] * dirs[i][1] +
                                 dirs[i][2] * dirs[i][2]));
        for (a = 0; a < 3; a++)
            q_d(&p, a)->l[i] = lt_q30_from_double_sat(dirs[i][a] / n);
    }
    assert_int_equal(lt_ray16_wt_setup_q16(&p, &w), 0);
    for (i = 0; i < LT_LANES; i++) {
        double d[3];
        int kx, ky, kz;
        int32_t dz;
        for (a = 0; a < 3; a++)
            d[a] = lt_q30_to_double(q_d(&p, a)->l[i]);
        frame_axes(d, &kx, &ky, &kz);
        dz = q_d(&p, kz)->l[i];
        /* the rule: largest |d|, ties to z then y; exact ties give Sx/Sy = +-1 or 0 exactly */
        if (!LTT_ON(w.kz[kz], i) || !LTT_ON(w.kx[kx], i) || !LTT_ON(w.ky[ky], i))
            bad++;
        if (w.sx.l[i] != (int32_t)lt__div_round64((int64_t)q_d(&p, kx)->l[i] * 1073741824, dz) ||
            w.sy.l[i] != (int32_t)lt__div_round64((int64_t)q_d(&p, ky)->l[i] * 1073741824, dz) ||
            w.sz.l[i] != (int32_t)lt__div_round64((int64_t)1 << 60, dz))
            bad++;
        if (dirs[i][kx] == 0 ? w.sx.l[i] != 0
                             : (w.sx.l[i] != LT_Q30_ONE && w.sx.l[i] != -LT_Q30_ONE))
            bad++;
    }
    ltt_report("lt_ray16_wt_setup_q16 axes: 16 directions (6 axis, 10 exact ties), %lu wrong "
               "(rule: kz = largest |d|, ties to z then y; kx, ky swapped for d[kz] < 0)\n", bad);
    assert_int_equal(bad, 0);
}

/* A flat 8 x 8 grid of unit-4 squares (alternating diagonals) in the plane z = 3.25, rays along
 * +-z (exactly axis-parallel: Sx = Sy = 0, so the ray passes exactly through the target) and
 * along exact ties, aimed at interior edges (midpoints and fractions) and interior vertices. */
static void test_axis_grid(void **state)
{
    wmesh_t m;
    ltt_rng_t r;
    unsigned long rays = 0, judged = 0, leak_wt = 0, leak_mt = 0, leak_wtf = 0, leak_mtf = 0;
    unsigned long fallback = 0, recovered = 0, leak_32 = 0;
    uint32_t i, j, e, v;
    unsigned g32;
    static const double dirs[4][3] = { { 0, 0, -1 }, { 0, 0, 1 }, { 1, 1, -1 }, { -1, 1, 1 } };
    (void)state;
    memset(&m, 0, sizeof m);
    m.name = "grid";
    m.nv = 81;
    m.nt = 128;
    m.vq = (lt_q16_t(*)[3])xcalloc(m.nv, sizeof *m.vq);
    m.tv = (uint32_t(*)[3])xcalloc(m.nt, sizeof *m.tv);
    for (j = 0; j < 9; j++)
        for (i = 0; i < 9; i++) {
            m.vq[j * 9 + i][0] = (lt_q16_t)((int32_t)i * 4 - 16) * LT_Q16_ONE;
            m.vq[j * 9 + i][1] = (lt_q16_t)((int32_t)j * 4 - 16) * LT_Q16_ONE;
            m.vq[j * 9 + i][2] = LT_Q16(3.25);
        }
    for (j = 0; j < 8; j++)
        for (i = 0; i < 8; i++) {
            uint32_t a0 = j * 9 + i, a1 = a0 + 1, a2 = a0 + 10, a3 = a0 + 9, t = (j * 8 + i) * 2;
            if ((i + j) & 1u) {
                m.tv[t][0] = a0, m.tv[t][1] = a1, m.tv[t][2] = a2;
                m.tv[t + 1][0] = a0, m.tv[t + 1][1] = a2, m.tv[t + 1][2] = a3;
            } else {
                m.tv[t][0] = a0, m.tv[t][1] = a1, m.tv[t][2] = a3;
                m.tv[t + 1][0] = a1, m.tv[t + 1][1] = a2, m.tv[t + 1][2] = a3;
            }
        }
    mesh_finish(&m);
    g32 = lt_wt32_shift_q16(m.tq, m.nt);
    ltt_rng_seed(&r, 7100);
    for (e = 0; e < m.ne + m.nv; e++) {
        feature_t f;
        int ok = e < m.ne ? feature_edge(&m, e, &f, FMT_Q16)
                          : feature_vertex(&m, e - m.ne, &f, FMT_Q16);
        unsigned dk;
        if (!ok)
            continue;
        for (dk = 0; dk < 4; dk++) {
            lt_ray16_q16_t p, p2, p3;
            lt_wt16_q16_t w;
            lt_hit16_t h;
            dray_t dr[LT_LANES];
            lt_mask16_t judge = 0, hw = 0, hm = 0, h32 = 0;
#if LT_CFG_FLOAT32
            lt_ray16_f32_t pf, pf2;
            lt_wt16_f32_t wf;
            dray_t drf[LT_LANES];
            lt_mask16_t hwf = 0, hmf = 0;
            memset(&pf, 0, sizeof pf);
#endif
            memset(&p, 0, sizeof p);
            for (i = 0; i < LT_LANES; i++) {
                double d[3], o[3], pt[3];
                double fr = i == 0 ? 0.5 : (double)(1u + ltt_rng_below(&r, 63)) / 64.0;
                int a;
                memcpy(d, dirs[dk], sizeof d);
                normalize(d);
                for (a = 0; a < 3; a++) {
                    pt[a] = m.vd[f.P][a] + (f.is_edge ? fr * (m.vd[f.Q][a] - m.vd[f.P][a]) : 0.0);
                    o[a] = pt[a] - 20.0 * d[a];
                }
                q_lane(&p, (int)i, o, d, 0.0, 100.0, &dr[i]);
                if (crossing(&m, &f, &dr[i], FMT_Q16))
                    judge = (lt_mask16_t)(judge | (1u << i));
#if LT_CFG_FLOAT32
                f_lane(&pf, (int)i, o, d, 0.0, 100.0, &drf[i]);
#endif
            }
            lt_ray16_q16_setup(&p);
            (void)lt_ray16_wt_setup_q16(&p, &w);
            p2 = p;
            p3 = p;
#if LT_CFG_FLOAT32
            lt_ray16_f32_setup(&pf);
            (void)lt_ray16_wt_setup_f32(&pf, &wf);
            pf2 = pf;
#endif
            for (v = 0; v < f.nd; v++) {
                hw |= lt_tri16_wt_q16(&p, &w, LT_MASK_ALL, &m.tq[f.d[v]], 1, &h);
                hm |= lt_tri16_q16(&p2, LT_MASK_ALL, &m.tq[f.d[v]], 1, &h);
                h32 |= lt_tri16_wt32_q16(&p3, &w, g32, LT_MASK_ALL, &m.tq[f.d[v]], 1, &h);
#if LT_CFG_FLOAT32
                hwf |= lt_tri16_wt_f32(&pf, &wf, LT_MASK_ALL, &m.tf[f.d[v]], 1, &h);
                for (i = 0; i < LT_LANES; i++) {
                    int zr = f32_zero_edge(&wf, (int)i, &m.tf[f.d[v]]);
                    fallback += zr != 0;
                    recovered += zr == 2;
                }
                hmf |= lt_tri16_f32(&pf2, LT_MASK_ALL, &m.tf[f.d[v]], 1, &h);
#endif
            }
            rays += LT_LANES;
            judged += lt__popcount32(judge);
            leak_wt += lt__popcount32((uint32_t)judge & ~(uint32_t)hw);
            leak_mt += lt__popcount32((uint32_t)judge & ~(uint32_t)hm);
            leak_32 += lt__popcount32((uint32_t)judge & ~(uint32_t)h32);
#if LT_CFG_FLOAT32
            leak_wtf += lt__popcount32((uint32_t)judge & ~(uint32_t)hwf);
            leak_mtf += lt__popcount32((uint32_t)judge & ~(uint32_t)hmf);
#endif
        }
    }
    ltt_report("lt_tri16_wt axis-parallel and exact-tie rays on a flat 8x8 grid (%u edges, %u "
               "interior vertices): %lu rays, %lu crossing; leaked q16 %lu, f32 %lu (bound 0; "
               "%lu f32 lane-triangle tests took the double fallback, %lu recovered a sign); "
               "Moller-Trumbore leaked q16 %lu, f32 %lu\n", m.ne, m.ninterior, rays, judged,
               leak_wt, leak_wtf, fallback, recovered, leak_mt, leak_mtf);
    ltt_report("lt_tri16_wt32_q16 (grid 2^%u) on the same rays: leaked %lu (bound 0)\n", g32,
               leak_32);
    assert_int_equal(judged, rays);
    assert_int_equal(leak_wt + leak_wtf + leak_32, 0);
    mesh_free(&m);
}

/* ---- agreement with a double reference ------------------------------------------------------- */

typedef struct wref {
    int hit;      /* reference result */
    int close;    /* a margin within its bound: either answer allowed */
    double t, tb; /* reference t and its bound (valid when hit or inside) */
} wref_t;

/* The watertight test in double on the kernel's exact inputs, with the bounds of the header. */
static wref_t wt_ref(const dray_t *r, const double v[3][3], int zero_area, int fmt)
{
    frame_t fr;
    double s[3][3], aa[3][3], eps[3], epz[3], e[3], de[3], det, sde = 0.0, mz = 0.0;
    int i, all_ge, all_le;
    wref_t w;
    memset(&w, 0, sizeof w);
    if (zero_area)
        return w; /* must miss */
    frame_make(r, &fr);
    for (i = 0; i < 3; i++) {
        frame_proj(&fr, v[i], s[i], aa[i]);
        if (fmt != FMT_F32) {
            eps[i] = aa[i][2] * ldexp(1.0, -31) + ldexp(1.0, -17);
            epz[i] = eps[i];
            if (fmt == FMT_W32) /* snapped: half a grid step more per coordinate */
                eps[i] += ldexp(1.0, (int)w32_g - 17);
        } else {
            eps[i] = ldexp(aa[i][0] + aa[i][1] + aa[i][2], -21);
            epz[i] = ldexp(fabs(s[i][2]), -21);
        }
        mz = fmax(mz, epz[i]);
    }
    /* U: (v2, v1), V: (v0, v2), W: (v1, v0) as in the kernel */
    {
        static const int ia[3] = { 2, 0, 1 }, ib[3] = { 1, 2, 0 };
        for (i = 0; i < 3; i++) {
            const double *c = s[ia[i]], *b = s[ib[i]];
            double ec = eps[ia[i]], eb = eps[ib[i]];
            e[i] = c[0] * b[1] - c[1] * b[0];
            de[i] = eb * (fabs(c[0]) + fabs(c[1])) + ec * (fabs(b[0]) + fabs(b[1])) + 2 * eb * ec;
            if (fmt == FMT_F32)
                de[i] += ldexp(fabs(c[0] * b[1]) + fabs(c[1] * b[0]), -22);
            sde += de[i];
        }
    }
    det = e[0] + e[1] + e[2];
    all_ge = e[0] >= 0 && e[1] >= 0 && e[2] >= 0;
    all_le = e[0] <= 0 && e[1] <= 0 && e[2] <= 0;
    for (i = 0; i < 3; i++)
        if (fabs(e[i]) <= de[i])
            w.close = 1;
    if (fabs(det) <= sde) {
        w.close = 1;
        return w;
    }
    if (!(all_ge || all_le))
        return w;
    w.t = (e[0] * s[0][2] + e[1] * s[1][2] + e[2] * s[2][2]) / det;
    w.tb = 0.0;
    for (i = 0; i < 3; i++)
        w.tb += de[i] * fabs(s[i][2] - w.t);
    w.tb = w.tb / (fabs(det) - sde) + mz;
    if (fmt != FMT_F32)
        w.tb += 0.5 * ULP16;
    else
        w.tb += ldexp(fabs(e[0] * s[0][2]) + fabs(e[1] * s[1][2]) + fabs(e[2] * s[2][2]), -21) /
                    fabs(det) + ldexp(fabs(w.t), -21);
    w.hit = w.t > r->tmin && w.t < r->tmax;
    if (fabs(w.t - r->tmin) <= w.tb || fabs(w.t - r->tmax) <= w.tb)
        w.close = 1;
    return w;
}

/* Bit-exact replica of lt_tri16_wt_q16 for lane i: the same scalar shear rounding (lt_fx.h
 * helpers), then the edge functions, T and t = round half up (T / det) in the compiler's 128-bit
 * integers, independent of the kernel's two-word emulation and restoring division. Returns 1 for
 * a hit (tmin < t < tmax) and its t. */
__extension__ typedef __int128 ltt_i128_t;

static int q16_replica(const lt_ray16_q16_t *p, const lt_wt16_q16_t *w, int i,
                       const lt_tri_q16_t *tr, int g, int32_t *t_out)
{
    lt_q16_t v[3][3], x[3], y[3], z[3], o[3];
    int64_t e[3], det, c[3];
    ltt_i128_t tn, num, den, q;
    int a, k, ax[3], ge, le;
    for (a = 0; a < 3; a++) {
        v[0][a] = tr->v0[a];
        v[1][a] = lt__q16_add_sat(tr->v0[a], tr->e1[a]);
        v[2][a] = lt__q16_add_sat(tr->v0[a], tr->e2[a]);
    }
    for (a = 0; a < 3; a++) {
        int32_t d1[3], d2[3];
        for (k = 0; k < 3; k++) {
            d1[k] = lt__ssat32((int64_t)v[1][k] - v[0][k]);
            d2[k] = lt__ssat32((int64_t)v[2][k] - v[0][k]);
        }
        c[a] = (int64_t)d1[(a + 1) % 3] * d2[(a + 2) % 3] -
               (int64_t)d1[(a + 2) % 3] * d2[(a + 1) % 3];
    }
    if (c[0] == 0 && c[1] == 0 && c[2] == 0)
        return 0;
    ax[0] = LTT_ON(w->kx[0], i) ? 0 : (LTT_ON(w->kx[1], i) ? 1 : 2);
    ax[1] = LTT_ON(w->ky[0], i) ? 0 : (LTT_ON(w->ky[1], i) ? 1 : 2);
    ax[2] = LTT_ON(w->kz[0], i) ? 0 : (LTT_ON(w->kz[1], i) ? 1 : 2);
    o[0] = (ax[0] == 0 ? p->ox : (ax[0] == 1 ? p->oy : p->oz)).l[i];
    o[1] = (ax[1] == 0 ? p->ox : (ax[1] == 1 ? p->oy : p->oz)).l[i];
    o[2] = (ax[2] == 0 ? p->ox : (ax[2] == 1 ? p->oy : p->oz)).l[i];
    for (k = 0; k < 3; k++) {
        lt_q16_t az = lt__q16_sub_sat(v[k][ax[2]], o[2]);
        x[k] = lt__q16_sub_sat(lt__q16_sub_sat(v[k][ax[0]], o[0]),
                               lt__q16_mul_q30_sat(az, w->sx.l[i]));
        y[k] = lt__q16_sub_sat(lt__q16_sub_sat(v[k][ax[1]], o[1]),
                               lt__q16_mul_q30_sat(az, w->sy.l[i]));
        z[k] = lt__q16_mul_q30_sat(az, w->sz.l[i]);
    }
    /* LT_ISECT_WT32's definition (g >= 0): a vertex whose coordinates round (half up) to at most
     * 16383 steps of 2^g is moved to that grid point; then the exact test on the points */
    for (k = 0; g >= 0 && k < 3; k++) {
        int64_t sx = (int64_t)floor(((double)x[k] + (g > 0 ? ldexp(1.0, g - 1) : 0.0)) / ldexp(1.0, g));
        int64_t sy = (int64_t)floor(((double)y[k] + (g > 0 ? ldexp(1.0, g - 1) : 0.0)) / ldexp(1.0, g));
        if (llabs(sx) <= 16383 && llabs(sy) <= 16383) {
            x[k] = (lt_q16_t)(sx * ((int64_t)1 << g));
            y[k] = (lt_q16_t)(sy * ((int64_t)1 << g));
        }
    }
    e[0] = (int64_t)x[2] * y[1] - (int64_t)y[2] * x[1];
    e[1] = (int64_t)x[0] * y[2] - (int64_t)y[0] * x[2];
    e[2] = (int64_t)x[1] * y[0] - (int64_t)y[1] * x[0];
    ge = e[0] >= 0 && e[1] >= 0 && e[2] >= 0;
    le = e[0] <= 0 && e[1] <= 0 && e[2] <= 0;
    det = e[0] + e[1] + e[2];
    if (!(ge || le) || det == 0)
        return 0;
    tn = (ltt_i128_t)e[0] * z[0] + (ltt_i128_t)e[1] * z[1] + (ltt_i128_t)e[2] * z[2];
    den = det;
    if (den < 0) {
        den = -den;
        tn = -tn;
    }
    /* floor((2 tn + den) / (2 den)): C division truncates, so correct negative quotients */
    num = 2 * tn + den;
    den = 2 * den;
    q = num / den;
    if (num % den != 0 && num < 0)
        q -= 1;
    *t_out = (int32_t)q;
    return *t_out > p->tmin.l[i] && *t_out < p->tmax.l[i];
}

typedef struct rtally {
    unsigned long cases, hits, close, allowed, bad, t_bad, upd_bad, replica_bad;
    double max_terr, max_frac;
} rtally_t;

static void rtally_case(rtally_t *ty, const char *name, const wref_t *w, int got, double t_got)
{
    ty->cases++;
    ty->hits += got != 0;
    ty->close += w->close != 0;
    if (got != w->hit) {
        if (w->close)
            ty->allowed++;
        else if (ty->bad++ < 6)
            ltt_report("  FAIL %s: got %s, reference %s (t_ref %.9g)\n", name, got ? "hit" : "miss",
                       w->hit ? "hit" : "miss", w->t);
        return;
    }
    if (got) {
        double er = fabs(t_got - w->t);
        ty->max_terr = fmax(ty->max_terr, er);
        if (w->tb > 0)
            ty->max_frac = fmax(ty->max_frac, er / w->tb);
        if (er > w->tb && ty->t_bad++ < 6)
            ltt_report("  FAIL %s: t %.9g vs reference %.9g (bound %.3g)\n", name, t_got, w->t,
                       w->tb);
    }
}

/* Random triangle at scale sc: v0 in [-sc, sc]^3, edges 0.02 sc .. sc (every 8th a needle with one
 * edge 1e-4 sc .. 1e-2 sc). */
static void tri_make(ltt_rng_t *r, double sc, unsigned n, double v[3][3])
{
    double u1[3], u2[3], s1, s2;
    int a;
    s1 = ltt_rng_uniform(r, 0.02, 1.0) * sc;
    s2 = (n % 8u == 7u) ? ltt_rng_uniform(r, 1e-4, 1e-2) * sc : ltt_rng_uniform(r, 0.02, 1.0) * sc;
    rng_unit(r, u1);
    rng_unit(r, u2);
    for (a = 0; a < 3; a++) {
        v[0][a] = ltt_rng_uniform(r, -sc, sc);
        v[1][a] = v[0][a] + s1 * u1[a];
        v[2][a] = v[0][a] + s2 * u2[a];
    }
}

/* A ray aimed at barycentrics in [-0.25, 1.25] (c = 0), within 1e-4 of an edge (1), or with the
 * origin possibly past the plane (2), from a distance up to sc. */
static void tri_aim(ltt_rng_t *r, const double v[3][3], double sc, unsigned c, double o[3],
                    double d[3])
{
    double b1 = ltt_rng_uniform(r, -0.25, 1.25), b2 = ltt_rng_uniform(r, -0.25, 1.25), tgt[3];
    double back = ltt_rng_uniform(r, c == 2 ? -0.5 * sc : 0.01 * sc, sc);
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

#define REF_PACKETS 1500

static void test_reference(void **state)
{
    static const double scales[5] = { 2.0, 40.0, 400.0, 1000.0, 0.0 /* range corners */ };
    ltt_rng_t r;
    rtally_t tq, tf, tw;
    unsigned pk;
    int i, a, j;
    (void)state;
    ltt_rng_seed(&r, 7200);
    memset(&tq, 0, sizeof tq);
    memset(&tf, 0, sizeof tf);
    memset(&tw, 0, sizeof tw);
    for (pk = 0; pk < REF_PACKETS; pk++) {
        double sc = scales[pk % 5u], v[3][3], vq[3][3], sg[3];
        lt_ray16_q16_t p;
        lt_wt16_q16_t w;
        lt_tri_q16_t tri;
        lt_hit16_t h;
        lt_vq16_t tmax0;
        lt_mask16_t got;
        dray_t dr[LT_LANES];
        double oo[LT_LANES][3], dd[LT_LANES][3], tm[LT_LANES];
#if LT_CFG_FLOAT32
        lt_ray16_f32_t pf;
        lt_wt16_f32_t wf;
        lt_tri_f32_t trf;
        lt_vf32_t tmaxf;
        double vf[3][3];
        memset(&pf, 0, sizeof pf);
#endif
        memset(&p, 0, sizeof p);
        if (sc > 0.0) {
            tri_make(&r, sc, pk, v);
        } else {
            /* a triangle in one corner of the +-4096 box, rays from the opposite corner: every
             * translated coordinate near 2^13, sheared ones near 2^14 (the format limits) */
            tri_make(&r, 90.0, pk, v);
            for (a = 0; a < 3; a++) {
                sg[a] = ltt_rng_below(&r, 2) ? 1.0 : -1.0;
                v[1][a] += sg[a] * 4000.0;
                v[2][a] += sg[a] * 4000.0;
                v[0][a] += sg[a] * 4000.0;
            }
        }
        for (a = 0; a < 3; a++) {
            tri.v0[a] = lt_q16_from_double_sat(v[0][a]);
            tri.e1[a] = lt_q16_from_double_sat(v[1][a]) - tri.v0[a];
            tri.e2[a] = lt_q16_from_double_sat(v[2][a]) - tri.v0[a];
            vq[0][a] = lt_q16_to_double(tri.v0[a]);
            vq[1][a] = lt_q16_to_double(tri.v0[a] + tri.e1[a]);
            vq[2][a] = lt_q16_to_double(tri.v0[a] + tri.e2[a]);
        }
        for (i = 0; i < LT_LANES; i++) {
            tri_aim(&r, (const double(*)[3])v, sc > 0.0 ? sc : 90.0, (pk + (unsigned)i) % 3u, oo[i],
                    dd[i]);
            if (sc == 0.0) {
                double b1 = ltt_rng_uniform(&r, -0.25, 1.25), b2 = ltt_rng_uniform(&r, -0.25, 1.25);
                for (a = 0; a < 3; a++) {
                    double tgt = v[0][a] + b1 * (v[1][a] - v[0][a]) + b2 * (v[2][a] - v[0][a]);
                    oo[i][a] = -sg[a] * ltt_rng_uniform(&r, 3500.0, 4090.0);
                    dd[i][a] = tgt - oo[i][a];
                }
                normalize(dd[i]);
            }
            /* the documented range: |origin| <= 4096 per axis (vertices are inside it) */
            for (a = 0; a < 3; a++)
                oo[i][a] = fmax(-4090.0, fmin(4090.0, oo[i][a]));
            tm[i] = ltt_rng_below(&r, 3) ? (sc > 0.0 ? 3.0 * sc : 16000.0)
                                          : ltt_rng_uniform(&r, 0, sc > 0.0 ? 1.5 * sc : 14000.0);
            q_lane(&p, i, oo[i], dd[i], 0.0, tm[i], &dr[i]);
        }
        (void)lt_ray16_wt_setup_q16(&p, &w);
        h.id = lt_vi32_set1(-7);
        tmax0 = p.tmax;
        {
            /* LT_ISECT_WT32 on the same lanes: the triangle's own grid, up to 16x coarser (at most 2^13), or g = 0
             * (most vertices off the grid's range: the exact points) */
            lt_ray16_q16_t pw = p;
            unsigned gs = lt_wt32_shift_q16(&tri, 1);
            w32_g = gs + 4u > LT_WT32_SHIFT_MAX ? LT_WT32_SHIFT_MAX : gs + 4u;
            w32_g = pk % 3u == 0 ? gs : (pk % 3u == 1 ? w32_g : 0u);
            got = lt_tri16_wt32_q16(&pw, &w, w32_g, LT_MASK_ALL, &tri, 42, &h);
            for (i = 0; i < LT_LANES; i++) {
                int32_t tr = 0;
                int rh = q16_replica(&p, &w, i, &tri, (int)w32_g, &tr);
                wref_t ref = wt_ref(&dr[i], (const double(*)[3])vq, 0, FMT_W32);
                int g = LTT_ON(got, i);
                if (rh != g || (rh && tr != pw.tmax.l[i]))
                    if (tw.replica_bad++ < 6)
                        ltt_report("  FAIL lt_tri16_wt32_q16 (g %u) vs 128-bit replica: lane %d "
                                   "hit %d/%d t %d/%d\n", w32_g, i, g, rh, pw.tmax.l[i], tr);
                rtally_case(&tw, "lt_tri16_wt32_q16 random", &ref, g,
                            lt_q16_to_double(pw.tmax.l[i]));
                if (g ? (h.id.l[i] != 42 || pw.tmax.l[i] >= tmax0.l[i])
                      : (h.id.l[i] != -7 || pw.tmax.l[i] != tmax0.l[i]))
                    tw.upd_bad++;
            }
            h.id = lt_vi32_set1(-7);
        }
        {
            lt_ray16_q16_t p0 = p;
            got = lt_tri16_wt_q16(&p, &w, LT_MASK_ALL, &tri, 42, &h);
            for (i = 0; i < LT_LANES; i++) {
                int32_t tr = 0;
                int rh = q16_replica(&p0, &w, i, &tri, -1, &tr);
                if (rh != LTT_ON(got, i) || (rh && tr != p.tmax.l[i]))
                    if (tq.replica_bad++ < 6)
                        ltt_report("  FAIL lt_tri16_wt_q16 vs 128-bit replica: lane %d hit %d/%d "
                                   "t %d/%d\n", i, LTT_ON(got, i), rh, p.tmax.l[i], tr);
            }
        }
        for (i = 0; i < LT_LANES; i++) {
            wref_t ref = wt_ref(&dr[i], (const double(*)[3])vq, 0, FMT_Q16);
            int g = LTT_ON(got, i);
            rtally_case(&tq, "lt_tri16_wt_q16 random", &ref, g, lt_q16_to_double(p.tmax.l[i]));
            if (g ? (h.id.l[i] != 42 || p.tmax.l[i] >= tmax0.l[i] || p.tmax.l[i] <= p.tmin.l[i])
                  : (h.id.l[i] != -7 || p.tmax.l[i] != tmax0.l[i]))
                tq.upd_bad++;
        }
#if LT_CFG_FLOAT32
        for (a = 0; a < 3; a++) {
            trf.v0[a] = (float)v[0][a];
            trf.e1[a] = (float)(v[1][a] - v[0][a]);
            trf.e2[a] = (float)(v[2][a] - v[0][a]);
            vf[0][a] = (double)trf.v0[a];
            vf[1][a] = (double)(trf.v0[a] + trf.e1[a]);
            vf[2][a] = (double)(trf.v0[a] + trf.e2[a]);
        }
        for (i = 0; i < LT_LANES; i++)
            f_lane(&pf, i, oo[i], dd[i], 0.0, tm[i], &dr[i]);
        (void)lt_ray16_wt_setup_f32(&pf, &wf);
        h.id = lt_vi32_set1(-7);
        tmaxf = pf.tmax;
        got = lt_tri16_wt_f32(&pf, &wf, LT_MASK_ALL, &trf, 42, &h);
        for (i = 0; i < LT_LANES; i++) {
            wref_t ref = wt_ref(&dr[i], (const double(*)[3])vf, 0, FMT_F32);
            int g = LTT_ON(got, i);
            rtally_case(&tf, "lt_tri16_wt_f32 random", &ref, g, (double)pf.tmax.l[i]);
            if (g ? (h.id.l[i] != 42 || !(pf.tmax.l[i] < tmaxf.l[i]))
                  : (h.id.l[i] != -7 || pf.tmax.l[i] != tmaxf.l[i]))
                tf.upd_bad++;
        }
#endif
        (void)j;
    }
    ltt_report("lt_tri16_wt_q16 vs double reference: %lu cases (scales 2..1000 units, needles, "
               "triangles and origins in opposite corners of the +-4096 range), "
               "%lu hits, %lu within the bound of a boundary, %lu disagreements (all such), %lu "
               "unexplained; max |t err| %.3g (%.3g of its bound: sum dE |z - t| / (|det| - sum "
               "dE) + dz + 2^-17), %lu t over bound; %lu wrong id/tmax updates; %lu lanes differ "
               "from the bit-exact __int128 replica (bound 0)\n",
               tq.cases, tq.hits, tq.close, tq.allowed, tq.bad, tq.max_terr, tq.max_frac, tq.t_bad,
               tq.upd_bad, tq.replica_bad);
#if LT_CFG_FLOAT32
    ltt_report("lt_tri16_wt_f32 vs double reference: %lu cases, %lu hits, %lu close, %lu "
               "disagreements (all such), %lu unexplained; max |t err| %.3g (%.3g of its bound); "
               "%lu t over bound; %lu wrong id/tmax updates\n", tf.cases, tf.hits, tf.close,
               tf.allowed, tf.bad, tf.max_terr, tf.max_frac, tf.t_bad, tf.upd_bad);
#endif
    ltt_report("lt_tri16_wt32_q16 (LT_ISECT_WT32) vs the same double reference: %lu cases (grid: "
               "the triangle's own lt_wt32_shift_q16, up to 16x coarser, or 2^0), %lu hits, %lu "
               "within the bound of a boundary (each snapped coordinate adds 2^(g-17) units to "
               "the per-vertex error), %lu disagreements (all such), %lu unexplained; max |t "
               "err| %.3g (%.3g of its bound), %lu t over bound; %lu wrong id/tmax updates; %lu "
               "lanes differ from the __int128 replica of the grid's definition (bound 0)\n",
               tw.cases, tw.hits, tw.close, tw.allowed, tw.bad, tw.max_terr, tw.max_frac,
               tw.t_bad, tw.upd_bad, tw.replica_bad);
    assert_int_equal(tq.bad + tq.t_bad + tq.upd_bad + tq.replica_bad + tf.bad + tf.t_bad +
                         tf.upd_bad + tw.bad + tw.t_bad + tw.upd_bad + tw.replica_bad, 0);
}

/* ---- zero-area and degenerate triangles ------------------------------------------------------ */

/* Zero area in every form (a zero edge, equal edges, collinear edges that are integer multiples
 * of one vector, a point) never hits, for rays aimed at points of the degenerate segment from
 * every direction. */
static void test_degenerate(void **state)
{
    ltt_rng_t r;
    unsigned long cases = 0, hits_q = 0, hits_f = 0;
    unsigned n;
    int i, a;
    (void)state;
    ltt_rng_seed(&r, 7300);
    for (n = 0; n < 400; n++) {
        unsigned kind = n % 5u;
        lt_ray16_q16_t p;
        lt_wt16_q16_t w;
        lt_tri_q16_t tq;
        lt_hit16_t h;
        dray_t dr;
        int32_t wq[3], k1 = ltt_rng_range(&r, -5, 5), k2 = ltt_rng_range(&r, -5, 5);
        double v0[3], scale = n < 200 ? 4.0 : 600.0;
#if LT_CFG_FLOAT32
        lt_ray16_f32_t pf;
        lt_wt16_f32_t wf;
        lt_tri_f32_t tf;
        memset(&pf, 0, sizeof pf);
#endif
        for (a = 0; a < 3; a++) {
            wq[a] = lt_q16_from_double_sat(ltt_rng_uniform(&r, -scale, scale) / 6.0);
            v0[a] = ltt_rng_uniform(&r, -20, 20);
            tq.v0[a] = lt_q16_from_double_sat(v0[a]);
            tq.e1[a] = kind == 0 || kind == 4 ? 0 : k1 * wq[a];
            tq.e2[a] = kind == 1 ? 0 : (kind == 2 ? tq.e1[a] : (kind == 4 ? 0 : k2 * wq[a]));
#if LT_CFG_FLOAT32
            {
                /* the same shapes in float on the 2^-8 grid, where multiples are exact */
                int32_t g = lt__asr32(wq[a], 8), e1 = kind == 0 || kind == 4 ? 0 : k1 * g;
                int32_t e2 = kind == 1 || kind == 4 ? 0 : (kind == 2 ? e1 : k2 * g);
                tf.v0[a] = (float)ldexp(floor(ldexp(v0[a], 8)), -8);
                tf.e1[a] = (float)ldexp((double)e1, -8);
                tf.e2[a] = (float)ldexp((double)e2, -8);
            }
#endif
        }
        memset(&p, 0, sizeof p);
        for (i = 0; i < LT_LANES; i++) {
            double o[3], d[3], tgt[3], s = ltt_rng_uniform(&r, -1, 2);
            rng_unit(&r, d);
            if (i < 3) { /* axis-parallel rays too */
                d[0] = d[1] = d[2] = 0.0;
                d[i] = 1.0;
            }
            for (a = 0; a < 3; a++) {
                tgt[a] = lt_q16_to_double(tq.v0[a]) + s * lt_q16_to_double(tq.e1[a]);
                o[a] = tgt[a] - ltt_rng_uniform(&r, 1, 50) * d[a];
            }
            q_lane(&p, i, o, d, 0.0, 1000.0, &dr);
#if LT_CFG_FLOAT32
            for (a = 0; a < 3; a++) {
                tgt[a] = (double)tf.v0[a] + s * (double)tf.e1[a];
                o[a] = tgt[a] - 20.0 * d[a];
            }
            f_lane(&pf, i, o, d, 0.0, 1000.0, &dr);
#endif
        }
        (void)lt_ray16_wt_setup_q16(&p, &w);
        h.id = lt_vi32_set1(-1);
        hits_q += lt__popcount32(lt_tri16_wt_q16(&p, &w, LT_MASK_ALL, &tq, 5, &h));
#if LT_CFG_FLOAT32
        (void)lt_ray16_wt_setup_f32(&pf, &wf);
        hits_f += lt__popcount32(lt_tri16_wt_f32(&pf, &wf, LT_MASK_ALL, &tf, 5, &h));
#endif
        cases += LT_LANES;
    }
    ltt_report("lt_tri16_wt zero-area (zero edge, equal edges, collinear multiples, point; rays "
               "aimed at the segment, 3 per packet axis-parallel): %lu cases, q16 %lu hits, "
               "f32 %lu hits (bound 0)\n", cases, hits_q, hits_f);
    assert_int_equal(hits_q + hits_f, 0);
}

/* ---- rays parallel to the triangle's plane --------------------------------------------------- */

/* Triangles in planes with exact normals n in {(0,0,1), (1,1,0), (1,1,1), (1,-2,3)}; ray directions
 * with d . n == 0 EXACTLY in s1.30 (built from integer raws), origins at offsets h along n from the
 * plane. h = 0: in the plane; the test may hit or miss, but a hit's t must lie between the
 * vertices' depths along the ray (t is a convex combination of them), and for the axis-aligned
 * plane (exact shear along one axis) det is exactly 0: never a hit. |h| >= 1e-3: never a hit. */
static void test_parallel(void **state)
{
    static const int normals[4][3] = { { 0, 0, 1 }, { 1, 1, 0 }, { 1, 1, 1 }, { 1, -2, 3 } };
    static const double offs[6] = { 0.0, 0.0, 1e-3, -1e-3, 1.0, -25.0 };
    ltt_rng_t r;
    unsigned long cases = 0, inplane = 0, inplane_hits = 0, axis_hits = 0, off_hits = 0, t_bad = 0;
    unsigned n;
    int i, a;
    (void)state;
    ltt_rng_seed(&r, 7400);
    for (n = 0; n < 400; n++) {
        const int *nm = normals[n % 4u];
        double nn[3], b1[3], b2[3], c[3], v[3][3], vv[3][3];
        lt_ray16_q16_t p;
        lt_wt16_q16_t w;
        lt_tri_q16_t tq;
        lt_hit16_t h;
        lt_mask16_t got;
        dray_t dr[LT_LANES];
        double zlo[LT_LANES], zhi[LT_LANES];
        for (a = 0; a < 3; a++)
            nn[a] = nm[a];
        normalize(nn);
        /* an in-plane basis of integer vectors: b1 = n x e, b2 = n x b1 (exact integers) */
        {
            double e[3] = { 0, 0, 0 }, ni[3] = { nm[0], nm[1], nm[2] };
            e[nm[0] == 0 ? 0 : 2] = 1.0;
            b1[0] = ni[1] * e[2] - ni[2] * e[1];
            b1[1] = ni[2] * e[0] - ni[0] * e[2];
            b1[2] = ni[0] * e[1] - ni[1] * e[0];
            b2[0] = ni[1] * b1[2] - ni[2] * b1[1];
            b2[1] = ni[2] * b1[0] - ni[0] * b1[2];
            b2[2] = ni[0] * b1[1] - ni[1] * b1[0];
        }
        /* vertices: integer-combination points of the plane through an integer point c, so
         * every vertex lies exactly on the plane n . x = n . c in s15.16 */
        for (a = 0; a < 3; a++)
            c[a] = (double)ltt_rng_range(&r, -30, 30);
        for (i = 0; i < 3; i++) {
            double s1 = (double)ltt_rng_range(&r, -8, 8) * 0.5;
            double s2 = (double)ltt_rng_range(&r, -8, 8) * 0.5;
            if (i == 0)
                s1 = s2 = 0.0;
            for (a = 0; a < 3; a++)
                v[i][a] = c[a] + s1 * b1[a] + s2 * b2[a];
        }
        for (a = 0; a < 3; a++) {
            tq.v0[a] = lt_q16_from_double_sat(v[0][a]);
            tq.e1[a] = lt_q16_from_double_sat(v[1][a]) - tq.v0[a];
            tq.e2[a] = lt_q16_from_double_sat(v[2][a]) - tq.v0[a];
            for (i = 0; i < 3; i++)
                vv[i][a] = v[i][a];
        }
        memset(&p, 0, sizeof p);
        for (i = 0; i < LT_LANES; i++) {
            double al = ltt_rng_uniform(&r, 0, TWO_PI), dd[3], o[3], tgt[3], h_off;
            double u = ltt_rng_uniform(&r, -0.2, 1.2), vb = ltt_rng_uniform(&r, -0.2, 1.2);
            int32_t raw[3];
            int k;
            /* direction in the plane, rounded to s1.30 such that raw . n == 0 exactly */
            for (a = 0; a < 3; a++)
                dd[a] = cos(al) * b1[a] / sqrt(dot3(b1, b1)) + sin(al) * b2[a] / sqrt(dot3(b2, b2));
            k = nm[2] != 0 ? 2 : 1; /* the component solved from the others */
            for (a = 0; a < 3; a++)
                raw[a] = lt_q30_from_double_sat(dd[a]);
            raw[k] = 0;
            {
                int64_t s = 0;
                int j = nm[0] == 1 ? 0 : 1; /* a component with |n| = 1 (every normal has one) */
                for (a = 0; a < 3; a++)
                    s += (int64_t)raw[a] * nm[a];
                /* make the rest divisible by n[k] (1 or 3), then solve raw . n == 0 exactly */
                while (s % nm[k] != 0) {
                    raw[j] += 1;
                    s += nm[j];
                }
                raw[k] = (int32_t)(-s / nm[k]);
            }
            h_off = offs[i % 6];
            for (a = 0; a < 3; a++) {
                dd[a] = lt_q30_to_double(raw[a]);
                tgt[a] = v[0][a] + u * (v[1][a] - v[0][a]) + vb * (v[2][a] - v[0][a]);
                o[a] = tgt[a] - 40.0 * dd[a] + h_off * nn[a];
            }
            q_lane(&p, i, o, dd, 0.0, 1000.0, &dr[i]);
            p.dx.l[i] = raw[0];
            p.dy.l[i] = raw[1];
            p.dz.l[i] = raw[2];
            /* the vertices' depths along the ray: a hit's t must lie between them */
            zlo[i] = HUGE_VAL;
            zhi[i] = -HUGE_VAL;
            for (k = 0; k < 3; k++) {
                double q[3], z;
                for (a = 0; a < 3; a++)
                    q[a] = vv[k][a] - dr[i].o[a];
                z = dot3(q, dr[i].d) / dot3(dr[i].d, dr[i].d);
                zlo[i] = fmin(zlo[i], z);
                zhi[i] = fmax(zhi[i], z);
            }
        }
        (void)lt_ray16_wt_setup_q16(&p, &w);
        h.id = lt_vi32_set1(-1);
        got = lt_tri16_wt_q16(&p, &w, LT_MASK_ALL, &tq, 1, &h);
        for (i = 0; i < LT_LANES; i++) {
            int g = LTT_ON(got, i);
            cases++;
            if (offs[i % 6] == 0.0) {
                inplane++;
                inplane_hits += (unsigned long)g;
                if (n % 4u == 0u)
                    axis_hits += (unsigned long)g;
                if (g) {
                    double t = lt_q16_to_double(p.tmax.l[i]);
                    if (t < zlo[i] - 1e-3 || t > zhi[i] + 1e-3)
                        t_bad++;
                }
            } else {
                off_hits += (unsigned long)g;
            }
        }
    }
    ltt_report("lt_tri16_wt_q16 parallel rays (d . n == 0 exactly): %lu cases; %lu in the plane, "
               "%lu of them hit (allowed, t within the vertices' depth range: %lu outside), %lu "
               "hits for the axis-aligned plane (bound 0: det == 0 exactly); %lu hits off the "
               "plane at |h| >= 1e-3 (bound 0)\n", cases, inplane, inplane_hits, t_bad, axis_hits,
               off_hits);
    assert_int_equal(t_bad + axis_hits + off_hits, 0);
}

/* ---- lane independence ----------------------------------------------------------------------- */

/* Every mask class: a lane's result is the same whatever the other lanes hold or whether they are
 * active; inactive lanes keep tmax and id bit for bit. Packets mix permutations. */
static void test_lanes(void **state)
{
    uint16_t masks[LTT_MASK_COUNT];
    unsigned nm = ltt_masks(masks, 7500), mi, pk;
    unsigned long cases = 0, bad = 0;
    ltt_rng_t r;
    int i, a;
    (void)state;
    ltt_rng_seed(&r, 7501);
    for (pk = 0; pk < 40; pk++) {
        double v[3][3];
        lt_ray16_q16_t p, solo[LT_LANES];
        lt_wt16_q16_t w;
        lt_tri_q16_t tq;
        lt_hit16_t hs[LT_LANES];
        lt_mask16_t gs[LT_LANES];
        dray_t dr;
#if LT_CFG_FLOAT32
        lt_ray16_f32_t pf, solof[LT_LANES];
        lt_wt16_f32_t wf;
        lt_tri_f32_t tf;
        lt_hit16_t hsf[LT_LANES];
        lt_mask16_t gsf[LT_LANES];
        memset(&pf, 0, sizeof pf);
#endif
        memset(&p, 0, sizeof p);
        tri_make(&r, 40.0, pk, v);
        for (a = 0; a < 3; a++) {
            tq.v0[a] = lt_q16_from_double_sat(v[0][a]);
            tq.e1[a] = lt_q16_from_double_sat(v[1][a]) - tq.v0[a];
            tq.e2[a] = lt_q16_from_double_sat(v[2][a]) - tq.v0[a];
#if LT_CFG_FLOAT32
            tf.v0[a] = (float)v[0][a];
            tf.e1[a] = (float)(v[1][a] - v[0][a]);
            tf.e2[a] = (float)(v[2][a] - v[0][a]);
#endif
        }
        for (i = 0; i < LT_LANES; i++) {
            double o[3], d[3];
            tri_aim(&r, (const double(*)[3])v, 40.0, (unsigned)i % 3u, o, d);
            q_lane(&p, i, o, d, 0.0, 80.0, &dr);
#if LT_CFG_FLOAT32
            f_lane(&pf, i, o, d, 0.0, 80.0, &dr);
#endif
        }
        /* each lane alone, the other lanes poisoned */
        for (i = 0; i < LT_LANES; i++) {
            lt_wt16_q16_t ws;
            solo[i] = p;
            (void)lt_ray16_wt_setup_q16(&solo[i], &ws);
            hs[i].id = lt_vi32_set1(-3);
            gs[i] = lt_tri16_wt_q16(&solo[i], &ws, (lt_mask16_t)(1u << i), &tq, 9, &hs[i]);
#if LT_CFG_FLOAT32
            {
                lt_wt16_f32_t wsf;
                solof[i] = pf;
                (void)lt_ray16_wt_setup_f32(&solof[i], &wsf);
                hsf[i].id = lt_vi32_set1(-3);
                gsf[i] = lt_tri16_wt_f32(&solof[i], &wsf, (lt_mask16_t)(1u << i), &tf, 9, &hsf[i]);
            }
#endif
        }
        (void)lt_ray16_wt_setup_q16(&p, &w);
#if LT_CFG_FLOAT32
        (void)lt_ray16_wt_setup_f32(&pf, &wf);
#endif
        for (mi = 0; mi < nm; mi++) {
            lt_ray16_q16_t pp = p;
            lt_hit16_t h;
            lt_mask16_t k = masks[mi], g;
#if LT_CFG_FLOAT32
            lt_ray16_f32_t ppf = pf;
            lt_hit16_t hf;
            lt_mask16_t gf;
            hf.id = lt_vi32_set1(-3);
            gf = lt_tri16_wt_f32(&ppf, &wf, k, &tf, 9, &hf);
#endif
            h.id = lt_vi32_set1(-3);
            g = lt_tri16_wt_q16(&pp, &w, k, &tq, 9, &h);
            for (i = 0; i < LT_LANES; i++) {
                int on = LTT_ON(k, i), e = 0;
                cases++;
                if (on)
                    e |= LTT_ON(g, i) != LTT_ON(gs[i], i) || pp.tmax.l[i] != solo[i].tmax.l[i] ||
                         h.id.l[i] != hs[i].id.l[i];
                else
                    e |= LTT_ON(g, i) || pp.tmax.l[i] != p.tmax.l[i] || h.id.l[i] != -3;
#if LT_CFG_FLOAT32
                if (on)
                    e |= LTT_ON(gf, i) != LTT_ON(gsf[i], i) ||
                         memcmp(&ppf.tmax.l[i], &solof[i].tmax.l[i], sizeof(float)) != 0 ||
                         hf.id.l[i] != hsf[i].id.l[i];
                else
                    e |= LTT_ON(gf, i) ||
                         memcmp(&ppf.tmax.l[i], &pf.tmax.l[i], sizeof(float)) != 0 ||
                         hf.id.l[i] != -3;
#endif
                if (e && bad++ < 6)
                    ltt_report("  FAIL lanes: packet %u mask %s 0x%04x lane %d\n", pk,
                               ltt_mask_class(mi), (unsigned)k, i);
            }
        }
    }
    ltt_report("lt_tri16_wt lane independence: %lu lane cases (%u mask patterns: none, all, "
               "alternating, single, random; q16 and f32), %lu differ from the lane run alone or "
               "touched an inactive lane (bound 0)\n", cases, nm, bad);
    assert_int_equal(bad, 0);
}

/* ---- the triangle-parallel layout --------------------------------------------------------------- */

/* lt__wt16_meet_tris (one ray, a triangle per lane) against lt__wt16_meet (16 rays, one triangle):
 * every (ray, triangle) pair must give the same meet bit and the same t bits, in both paths, for
 * any n and lane order. The triangles: random ones (every 8th a sliver), two sharing an edge, a
 * zero-area one, one far off; the rays: aimed inside, within 1e-4 of an edge, from behind the
 * plane, through a shared vertex, axis-parallel, and a zero direction (bad lane). */
static void test_tris_layout(void **state)
{
    unsigned long pairs = 0, meets = 0, bad = 0;
    unsigned round, i, j;
    ltt_rng_t r;
    int a;
    (void)state;
    ltt_rng_seed(&r, 7701);
    for (round = 0; round < 300; round++) {
        double v[LT_LANES][3][3];
        lt_tri_q16_t tq[LT_LANES];
        lt_ray16_q16_t p;
        lt_wt16_q16_t w;
        lt_vq16_t tp[LT_LANES], tt;
        lt_mask16_t mp[LT_LANES], mt;
        uint32_t idx[LT_LANES];
        unsigned n = 1u + ltt_rng_below(&r, LT_LANES);
        dray_t dr;
#if LT_CFG_FLOAT32
        lt_tri_f32_t tf[LT_LANES];
        lt_ray16_f32_t pf;
        lt_wt16_f32_t wf;
        lt_vf32_t tpf[LT_LANES], ttf;
        lt_mask16_t mpf[LT_LANES], mtf;
        memset(&pf, 0, sizeof pf);
#endif
        memset(&p, 0, sizeof p);
        for (i = 0; i < LT_LANES; i++)
            tri_make(&r, 40.0, round * LT_LANES + i, v[i]);
        for (a = 0; a < 3; a++) {
            v[1][0][a] = v[0][1][a]; /* triangles 0 and 1 share the edge (v1, v2) of 0 */
            v[1][1][a] = v[0][2][a];
            v[2][2][a] = v[2][1][a]; /* triangle 2 has zero area */
            v[3][0][a] += 1000.0;    /* triangle 3 is far off */
        }
        for (i = 0; i < LT_LANES; i++)
            for (a = 0; a < 3; a++) {
                tq[i].v0[a] = lt_q16_from_double_sat(v[i][0][a]);
                tq[i].e1[a] = lt_q16_from_double_sat(v[i][1][a]) - tq[i].v0[a];
                tq[i].e2[a] = lt_q16_from_double_sat(v[i][2][a]) - tq[i].v0[a];
#if LT_CFG_FLOAT32
                tf[i].v0[a] = (float)v[i][0][a];
                tf[i].e1[a] = (float)(v[i][1][a] - v[i][0][a]);
                tf[i].e2[a] = (float)(v[i][2][a] - v[i][0][a]);
#endif
            }
        /* n of the 16 triangles in a random order */
        for (i = 0; i < LT_LANES; i++)
            idx[i] = i;
        for (i = LT_LANES - 1u; i > 0; i--) {
            unsigned k = ltt_rng_below(&r, i + 1u);
            uint32_t x = idx[i];
            idx[i] = idx[k];
            idx[k] = x;
        }
        for (j = 0; j < LT_LANES; j++) {
            double o[3], d[3];
            /* each ray aimed at one of the n triangles tested */
            tri_aim(&r, (const double(*)[3])v[idx[j % n]], 40.0, j % 3u, o, d);
            if (j == 13)
                for (a = 0; a < 3; a++) /* through the shared vertex v0[1] */
                    d[a] = v[0][1][a] - o[a];
            if (j == 14)
                for (a = 0; a < 3; a++) /* axis-parallel */
                    d[a] = a == (int)(round % 3u) ? (round & 4u ? -1.0 : 1.0) : 0.0;
            if (j % 4u == 3u) { /* short directions, as the frusta's (t scale sh > 0) */
                double sc = ltt_rng_uniform(&r, 0.01, 0.6);
                for (a = 0; a < 3; a++)
                    d[a] *= sc;
            }
            if (j == 15)
                d[0] = d[1] = d[2] = 0.0; /* no direction: a bad lane */
            if (j == 13) {
                double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                for (a = 0; a < 3; a++)
                    d[a] /= l;
            }
            q_lane(&p, (int)j, o, d, 0.0, 80.0, &dr);
#if LT_CFG_FLOAT32
            f_lane(&pf, (int)j, o, d, 0.0, 80.0, &dr);
#endif
        }
        (void)lt_ray16_wt_setup_q16(&p, &w);
#if LT_CFG_FLOAT32
        (void)lt_ray16_wt_setup_f32(&pf, &wf);
#endif
        for (i = 0; i < LT_LANES; i++) {
            tp[i] = lt_vq16_set1(-7);
            mp[i] = lt__wt16_meet_q16(&w, 0xFFFFu, &tq[i], &tp[i]);
#if LT_CFG_FLOAT32
            tpf[i] = lt_vf32_set1(-7.0f);
            mpf[i] = lt__wt16_meet_f32(&wf, 0xFFFFu, &tf[i], &tpf[i]);
#endif
        }
        for (j = 0; j < LT_LANES; j++) {
            tt = lt_vq16_set1(-7);
            mt = lt__wt16_meet_tris_q16(&w, j, tq, idx, n, &tt);
#if LT_CFG_FLOAT32
            ttf = lt_vf32_set1(-7.0f);
            mtf = lt__wt16_meet_tris_f32(&wf, j, tf, idx, n, &ttf);
#endif
            for (i = 0; i < LT_LANES; i++) {
                unsigned x = idx[i];
                int e = 0, on = (int)((unsigned)mt >> i & 1u);
                if (i >= n) {
                    e = on;
#if LT_CFG_FLOAT32
                    e |= (int)((unsigned)mtf >> i & 1u);
#endif
                } else {
                    pairs++;
                    meets += (unsigned long)on;
                    e = on != (int)((unsigned)mp[x] >> j & 1u) || (on && tt.l[i] != tp[x].l[j]);
#if LT_CFG_FLOAT32
                    on = (int)((unsigned)mtf >> i & 1u);
                    e |= on != (int)((unsigned)mpf[x] >> j & 1u) ||
                         (on && memcmp(&ttf.l[i], &tpf[x].l[j], sizeof(float)) != 0);
#endif
                }
                if (e && bad++ < 6)
                    ltt_report("  FAIL tris layout: round %u ray %u lane %u (triangle %u, n %u)\n",
                               round, j, i, x, n);
            }
        }
    }
    ltt_report("lt__wt16_meet_tris (one ray, a triangle per lane) against lt__wt16_meet (16 rays, one "
               "triangle): %lu ray-triangle pairs (shared edge and vertex, zero area, axis-parallel, "
               "short and zero directions, n 1-16 in random lane order; q16 and f32), %lu meet, %lu differ "
               "in the meet bit or t bits or set a lane past n (bound 0)\n", pairs, meets, bad);
    assert_int_equal(bad, 0);
    assert_true(meets * 8 > (unsigned long)300 * LT_LANES); /* most rays meet their target */
}

/* ---- bad directions and the f32 fallback ----------------------------------------------------- */

/* Lanes with a zero or too short direction are flagged and never hit; the float32 double fallback
 * is exercised (edge functions exactly 0.0f on rays through vertices of a grid). */
static void test_bad_dir(void **state)
{
    lt_ray16_q16_t p;
    lt_wt16_q16_t w;
    lt_tri_q16_t tq;
    lt_hit16_t h;
    lt_mask16_t bad, got;
    int i, a;
    (void)state;
    memset(&p, 0, sizeof p);
    for (a = 0; a < 3; a++) {
        tq.v0[a] = LT_Q16(-5.0);
        tq.e1[a] = a == 0 ? LT_Q16(10.0) : 0;
        tq.e2[a] = a == 1 ? LT_Q16(10.0) : 0;
    }
    tq.v0[2] = 0;
    for (i = 0; i < LT_LANES; i++) {
        p.oz.l[i] = LT_Q16(-10.0);
        p.dz.l[i] = i < 4 ? (int32_t)(i * 0x08000000) : LT_Q30_ONE; /* 0, 1/8, 1/4, 3/8 */
        p.tmax.l[i] = LT_Q16(100.0);
    }
    bad = lt_ray16_wt_setup_q16(&p, &w);
    h.id = lt_vi32_set1(-1);
    got = lt_tri16_wt_q16(&p, &w, LT_MASK_ALL, &tq, 1, &h);
    /* only d == 0 is bad; short directions are scaled by 2^sh for Sz and t = T 2^sh / det comes
     * back in units of |d| (10 / (1/8) = 80, 40, 80/3) */
    ltt_report("lt_ray16_wt_setup_q16: d == 0 flagged: mask 0x%04x (expected 0x0001), hits 0x%04x "
               "(expected 0xfffe), t = %.6f %.6f %.6f (80, 40, 26.666667), shifts %u %u %u\n",
               (unsigned)bad, (unsigned)got, p.tmax.l[1] / 65536.0, p.tmax.l[2] / 65536.0,
               p.tmax.l[3] / 65536.0, w.sh[1], w.sh[2], w.sh[3]);
    assert_int_equal(bad, 0x0001);
    assert_int_equal(got, 0xFFFE);
    assert_int_equal(p.tmax.l[1], LT_Q16(80.0));
    assert_int_equal(p.tmax.l[2], LT_Q16(40.0));
    /* z is rounded in units of d 2^sh, so t carries up to 2^(sh - 17) + 2^-17 of rounding */
    assert_true(fabs(p.tmax.l[3] / 65536.0 - 10.0 / 0.375) <= ldexp(1.0, w.sh[3] - 17) + ldexp(1.0, -17));
    assert_int_equal(p.tmax.l[4], LT_Q16(10.0));
}

/* The single-ray test (lt_ray1_wt_setup_*, lt_tri1_wt_*) equals its packet lane bit for bit:
 * random triangles (some sharing vertices, some zero-area) and rays, unit and short directions
 * (components down to 2^-20), aimed at vertices, edges and random points. */
/* The single-ray setup of lane i of a packet (lt_ray1_wt_setup_q16 on its origin and direction). */
static void q_lane_setup1(const lt_ray16_q16_t *p, int i, lt_wt1_q16_t *w1)
{
    lt_q16_t o[3];
    lt_q30_t d[3];
    o[0] = p->ox.l[i], o[1] = p->oy.l[i], o[2] = p->oz.l[i];
    d[0] = p->dx.l[i], d[1] = p->dy.l[i], d[2] = p->dz.l[i];
    (void)lt_ray1_wt_setup_q16(o, d, w1);
}

static void test_single_ray(void **state)
{
    ltt_rng_t rng;
    unsigned long cases = 0, hits = 0, bad = 0, cases32 = 0, hits32 = 0;
    int it;
    (void)state;
    ltt_rng_seed(&rng, 91);
    for (it = 0; it < 4000; it++) {
        lt_ray16_q16_t p;
        lt_wt16_q16_t w;
        lt_tri_q16_t tq;
        lt_hit16_t h;
        double v[3][3];
        int i, a;
        lt_mask16_t got;
        memset(&p, 0, sizeof p);
        /* every 7th case far out: the triangle around a centre up to 30,000 units out and the
           origins up to 32,000 units out on any side, so vertex - origin can leave s15.16 and
           saturate (in the packet and the scalar test alike) */
        double c[3] = {0.0, 0.0, 0.0}, orr = it % 7 == 6 ? 32000.0 : 200.0;
        if (it % 7 == 6)
            for (a = 0; a < 3; a++)
                c[a] = ltt_rng_uniform(&rng, -30000.0, 30000.0);
        for (i = 0; i < 3; i++)
            for (a = 0; a < 3; a++)
                v[i][a] = c[a] + ltt_rng_uniform(&rng, -50.0, 50.0);
        if (it % 17 == 0)
            for (a = 0; a < 3; a++)
                v[2][a] = v[1][a]; /* zero area */
        for (a = 0; a < 3; a++) {
            tq.v0[a] = LT_Q16(v[0][a]);
            tq.e1[a] = LT_Q16(v[1][a]) - tq.v0[a];
            tq.e2[a] = LT_Q16(v[2][a]) - tq.v0[a];
        }
        for (i = 0; i < LT_LANES; i++) {
            double o[3], tg[3], d[3], l = 0.0, sc;
            int k = (int)(ltt_rng_u32(&rng) % 3u);
            for (a = 0; a < 3; a++) {
                double b0 = ltt_rng_uniform(&rng, 0.0, 1.0), b1 = ltt_rng_uniform(&rng, 0.0, 1.0);
                o[a] = ltt_rng_uniform(&rng, -orr, orr);
                (void)b1;
                tg[a] = i % 3 == 0 ? v[k][a] : (i % 3 == 1 ? v[k][a] + b0 * (v[(k + 1) % 3][a] - v[k][a])
                                                           : v[0][a]);
            }
            for (a = 0; a < 3; a++) {
                d[a] = tg[a] - o[a];
                l += d[a] * d[a];
            }
            l = sqrt(l);
            /* unit, or short: scaled by 2^-e, e up to 20 */
            sc = i < 8 ? 1.0 : ldexp(1.0, -(int)(ltt_rng_u32(&rng) % 21u));
            for (a = 0; a < 3; a++) {
                lt_q16_t *oo = a == 0 ? &p.ox.l[i] : (a == 1 ? &p.oy.l[i] : &p.oz.l[i]);
                lt_q30_t *dd = a == 0 ? &p.dx.l[i] : (a == 1 ? &p.dy.l[i] : &p.dz.l[i]);
                *oo = LT_Q16(o[a]);
                *dd = (lt_q30_t)(d[a] / l * sc * 1073741824.0);
            }
            p.tmin.l[i] = 0;
            p.tmax.l[i] = LT_Q16_MAX - 1;
        }
        (void)lt_ray16_wt_setup_q16(&p, &w);
        {
            lt_ray16_q16_t p0 = p;
            h.id = lt_vi32_set1(-1);
            got = lt_tri16_wt_q16(&p, &w, LT_MASK_ALL, &tq, 3, &h);
            for (i = 0; i < LT_LANES; i++) {
                lt_q16_t tmax = p0.tmax.l[i];
                lt_wt1_q16_t w1;
                int hit1;
                q_lane_setup1(&p0, i, &w1);
                hit1 = lt_tri1_wt_q16(&w1, &tq, p0.tmin.l[i], &tmax);
                cases++;
                hits += (unsigned long)hit1;
                if (hit1 != (int)(((unsigned)got >> (unsigned)i) & 1u) || tmax != p.tmax.l[i] || w1.sh != w.sh[i]) {
                    if (bad < 5)
                        ltt_report("  FAIL q16 single ray: case %d lane %d: hit %d/%d t %d/%d\n", it,
                                   i, hit1, (int)(((unsigned)got >> (unsigned)i) & 1u), tmax, p.tmax.l[i]);
                    bad++;
                }
            }
        }
        {
            /* LT_ISECT_WT32: the same lanes (unit and short directions: sh > 0 takes the wide
             * arithmetic) on the triangle's grid, up to 16x coarser, or 2^0 */
            lt_ray16_q16_t p0 = p;
            unsigned g = lt_wt32_shift_q16(&tq, 1);
            unsigned gc = g + 4u > LT_WT32_SHIFT_MAX ? LT_WT32_SHIFT_MAX : g + 4u;
            g = it % 3 == 0 ? g : (it % 3 == 1 ? gc : 0u);
            h.id = lt_vi32_set1(-1);
            p = p0;
            got = lt_tri16_wt32_q16(&p, &w, g, LT_MASK_ALL, &tq, 3, &h);
            for (i = 0; i < LT_LANES; i++) {
                lt_q16_t tmax = p0.tmax.l[i];
                lt_wt1_q16_t w1;
                int hit1;
                q_lane_setup1(&p0, i, &w1);
                hit1 = lt_tri1_wt32_q16(&w1, g, &tq, p0.tmin.l[i], &tmax);
                cases32++;
                hits32 += (unsigned long)hit1;
                if (hit1 != (int)(((unsigned)got >> (unsigned)i) & 1u) || tmax != p.tmax.l[i]) {
                    if (bad < 5)
                        ltt_report("  FAIL wt32 single ray: case %d lane %d g %u: hit %d/%d t "
                                   "%d/%d\n", it, i, g, hit1,
                                   (int)(((unsigned)got >> (unsigned)i) & 1u), tmax, p.tmax.l[i]);
                    bad++;
                }
            }
            p = p0;
        }
#if LT_CFG_FLOAT32
        {
            lt_ray16_f32_t pf;
            lt_wt16_f32_t wf;
            lt_tri_f32_t tf;
            memset(&pf, 0, sizeof pf);
            for (a = 0; a < 3; a++) {
                tf.v0[a] = (float)tq.v0[a] / 65536.0f;
                tf.e1[a] = (float)tq.e1[a] / 65536.0f;
                tf.e2[a] = (float)tq.e2[a] / 65536.0f;
            }
            for (i = 0; i < LT_LANES; i++) {
                pf.ox.l[i] = (float)p.ox.l[i] / 65536.0f;
                pf.oy.l[i] = (float)p.oy.l[i] / 65536.0f;
                pf.oz.l[i] = (float)p.oz.l[i] / 65536.0f;
                pf.dx.l[i] = (float)p.dx.l[i] / 1073741824.0f;
                pf.dy.l[i] = (float)p.dy.l[i] / 1073741824.0f;
                pf.dz.l[i] = (float)p.dz.l[i] / 1073741824.0f;
                pf.tmax.l[i] = 3.0e38f;
            }
            (void)lt_ray16_wt_setup_f32(&pf, &wf);
            {
                lt_ray16_f32_t p0 = pf;
                h.id = lt_vi32_set1(-1);
                got = lt_tri16_wt_f32(&pf, &wf, LT_MASK_ALL, &tf, 3, &h);
                for (i = 0; i < LT_LANES; i++) {
                    float o[3], d[3], tmax = p0.tmax.l[i];
                    lt_wt1_f32_t w1;
                    int hit1;
                    o[0] = p0.ox.l[i], o[1] = p0.oy.l[i], o[2] = p0.oz.l[i];
                    d[0] = p0.dx.l[i], d[1] = p0.dy.l[i], d[2] = p0.dz.l[i];
                    (void)lt_ray1_wt_setup_f32(o, d, &w1);
                    hit1 = lt_tri1_wt_f32(&w1, &tf, p0.tmin.l[i], &tmax);
                    cases++;
                    hits += (unsigned long)hit1;
                    if (hit1 != (int)(((unsigned)got >> (unsigned)i) & 1u) || memcmp(&tmax, &pf.tmax.l[i], 4) != 0) {
                        if (bad < 5)
                            ltt_report("  FAIL f32 single ray: case %d lane %d: hit %d/%d\n", it, i,
                                       hit1, (int)(((unsigned)got >> (unsigned)i) & 1u));
                        bad++;
                    }
                }
            }
        }
#endif
    }
    ltt_report("lt_tri1_wt_q16/_f32 vs their packet lane (1 case in 7 with vertex - origin "
               "saturating s15.16): %lu cases, %lu hits; lt_tri1_wt32_q16 vs its packet lane "
               "(grids 2^0 .. 2^13, unit and short directions): %lu cases, %lu hits; %lu differ "
               "(bound 0)\n", cases, hits, cases32, hits32, bad);
    assert_int_equal(bad, 0);
}

/* ---- cost (sim build) ------------------------------------------------------------------------ */

#if LT_COST_MODE == LT_COST_SIM
static void cost_run(const char *machine, int coherent, double out[6][2])
{
    const lt_machine_t *mach = lt_sim_machine_find(machine);
    lt_diag_t diag;
    ltt_rng_t r;
    int kern, pk, i, a;
    assert_non_null(mach);
    assert_int_equal(lt_sim_init(mach, NULL, NULL, &diag), 0);
    for (kern = 0; kern < 6; kern++) {
        lt_sim_totals_t t, t0;
        uint64_t ops = 0;
        int ph, op;
        ltt_rng_seed(&r, 7600);
        lt_sim_reset();
        for (pk = 0; pk < 200; pk++) {
            double v[3][3], oc[3];
            lt_ray16_q16_t p;
            lt_wt16_q16_t w;
            lt_tri_q16_t tq;
            lt_hit16_t h;
            dray_t dr;
#if LT_CFG_FLOAT32
            lt_ray16_f32_t pf;
            lt_wt16_f32_t wf;
            lt_tri_f32_t tf;
            memset(&pf, 0, sizeof pf);
#endif
            memset(&p, 0, sizeof p);
            tri_make(&r, 40.0, (unsigned)pk, v);
            rng_unit(&r, oc);
            for (a = 0; a < 3; a++) {
                tq.v0[a] = lt_q16_from_double_sat(v[0][a]);
                tq.e1[a] = lt_q16_from_double_sat(v[1][a]) - tq.v0[a];
                tq.e2[a] = lt_q16_from_double_sat(v[2][a]) - tq.v0[a];
#if LT_CFG_FLOAT32
                tf.v0[a] = (float)v[0][a];
                tf.e1[a] = (float)(v[1][a] - v[0][a]);
                tf.e2[a] = (float)(v[2][a] - v[0][a]);
#endif
            }
            for (i = 0; i < LT_LANES; i++) {
                double o[3], d[3], tgt[3];
                /* half the lanes aimed inside the triangle; coherent packets share the origin */
                if (coherent) {
                    double b1 = ltt_rng_uniform(&r, -0.3, 1.0), b2 = ltt_rng_uniform(&r, -0.3, 1.0);
                    for (a = 0; a < 3; a++) {
                        tgt[a] = v[0][a] + b1 * (v[1][a] - v[0][a]) + b2 * (v[2][a] - v[0][a]);
                        o[a] = v[0][a] + 100.0 * oc[a];
                        d[a] = tgt[a] - o[a];
                    }
                    normalize(d);
                } else {
                    tri_aim(&r, (const double(*)[3])v, 40.0, (unsigned)i % 3u, o, d);
                }
                q_lane(&p, i, o, d, 0.0, 500.0, &dr);
#if LT_CFG_FLOAT32
                f_lane(&pf, i, o, d, 0.0, 500.0, &dr);
#endif
            }
            /* the setups (kernels 4, 5) are per packet, measured apart from the per-triangle
             * tests, which run on packets set up outside the counted window */
            if (kern < 4) {
                lt_ray16_q16_setup(&p);
                (void)lt_ray16_wt_setup_q16(&p, &w);
#if LT_CFG_FLOAT32
                lt_ray16_f32_setup(&pf);
                (void)lt_ray16_wt_setup_f32(&pf, &wf);
#endif
            }
            lt_sim_totals(&t0);
            h.id = lt_vi32_set1(-1);
            switch (kern) {
            case 0:
                (void)lt_tri16_wt_q16(&p, &w, LT_MASK_ALL, &tq, 1, &h);
                break;
            case 1:
                (void)lt_tri16_q16(&p, LT_MASK_ALL, &tq, 1, &h);
                break;
#if LT_CFG_FLOAT32
            case 2:
                (void)lt_tri16_wt_f32(&pf, &wf, LT_MASK_ALL, &tf, 1, &h);
                break;
            case 3:
                (void)lt_tri16_f32(&pf, LT_MASK_ALL, &tf, 1, &h);
                break;
#endif
            case 4:
                (void)lt_ray16_wt_setup_q16(&p, &w);
                break;
            default:
                lt_ray16_q16_setup(&p);
                break;
            }
            lt_sim_totals(&t);
            for (ph = 0; ph < LT_PH__COUNT; ph++)
                for (op = 0; op < LT_OP__COUNT; op++)
                    ops += t.ctr[ph][op] - t0.ctr[ph][op];
            out[kern][1] += (double)(t.total_cycles - t0.total_cycles) / 200.0;
        }
        out[kern][0] = (double)ops / 200.0;
    }
    lt_sim_shutdown();
}

static void test_cost(void **state)
{
    static const char *names[6] = { "lt_tri16_wt_q16", "lt_tri16_q16", "lt_tri16_wt_f32",
                                    "lt_tri16_f32", "lt_ray16_wt_setup_q16", "lt_ray16_q16_setup" };
    static const char *machines[3] = { "lrb16", "mcu-m4", "rv32imac" };
    int mi, co, k;
    (void)state;
    for (mi = 0; mi < 3; mi++)
        for (co = 0; co < 2; co++) {
            double out[6][2];
            memset(out, 0, sizeof out);
            cost_run(machines[mi], co, out);
            for (k = 0; k < 6; k++)
                if (LT_CFG_FLOAT32 || (k != 2 && k != 3))
                    ltt_report("cost %-8s %-9s %-21s %6.1f ops/call %8.1f cycles/call (%.2fx "
                               "%s)\n", machines[mi], co ? "coherent" : "mixed", names[k],
                               out[k][0], out[k][1], out[k][1] / out[k | 1][1], names[k | 1]);
            assert_true(out[0][1] > 0);
        }
}
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_axes_ties),
        cmocka_unit_test(test_bad_dir),
        cmocka_unit_test(test_single_ray),
        cmocka_unit_test(test_crack_tetra),
        cmocka_unit_test(test_crack_octasphere),
        cmocka_unit_test(test_crack_teapot),
        cmocka_unit_test(test_crack_bunny),
        cmocka_unit_test(test_axis_grid),
        cmocka_unit_test(test_reference),
        cmocka_unit_test(test_degenerate),
        cmocka_unit_test(test_parallel),
        cmocka_unit_test(test_lanes),
        cmocka_unit_test(test_tris_layout),
#if LT_COST_MODE == LT_COST_SIM
        cmocka_unit_test(test_cost),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
