/* lt_qt_ref.c - depth -> inverse-depth conversion and the double-precision pixel-marching
 * reference of the screen-space quadtree (see lt_qt_ref.h). Written independently of the core's
 * kernels: plain scalar double code, no hierarchy. Host only.
 */
#include "render/lt_qt_ref.h"

#include <math.h>
#include <stdlib.h>

#include "lt/lt_qt.h"

int lt_qt_zref_exp(const float *z, size_t n, int *e)
{
    double zmin = INFINITY;
    size_t i;
    *e = 0;
    for (i = 0; i < n; i++) {
        double v = (double)z[i];
        if (isfinite(v) && v > 0.0 && v < zmin)
            zmin = v;
    }
    if (!isfinite(zmin))
        return -1;
    *e = (int)floor(log2(zmin));
    /* log2 may round across an integer: make 2^e < zmin <= 2^(e+1) exact. Strictly below: with
       z_ref = zmin a surface there has w = 1 exactly, on the reprojection's default near plane
       (w <= 1), where the fixed-point paths lost it (a flat image at a power-of-two depth
       reprojected to 0% hits in n64 and n32). */
    while (ldexp(1.0, *e) >= zmin)
        (*e)--;
    while (ldexp(1.0, *e + 1) < zmin)
        (*e)++;
    return 0;
}

size_t lt_qt_w_from_depth_q30(const float *z, size_t n, int zexp, lt_q30_t *w)
{
    size_t i, holes = 0;
    for (i = 0; i < n; i++) {
        double v = (double)z[i];
        if (!isfinite(v) || v <= 0.0) {
            w[i] = 0;
            holes++;
        } else {
            double r = floor(ldexp(1.0, zexp + 30) / v + 0.5);
            w[i] = r >= 2147483647.0 ? INT32_MAX : (lt_q30_t)r;
        }
    }
    return holes;
}

size_t lt_qt_w_from_depth_f32(const float *z, size_t n, int zexp, float *w)
{
    size_t i, holes = 0;
    for (i = 0; i < n; i++) {
        double v = (double)z[i];
        if (!isfinite(v) || v <= 0.0) {
            w[i] = 0.0f;
            holes++;
        } else {
            w[i] = (float)(ldexp(1.0, zexp) / v);
        }
    }
    return holes;
}

/* ---- Alg. 1 in double ------------------------------------------------------------------------ */

static double at(const double *w, uint32_t W, int32_t x, int32_t y)
{
    return w[(size_t)y * W + (size_t)x];
}

/* One axis: value c, neighbours l (has_l) and r (has_r): derivative and second difference. */
static void axis(double c, double l, int has_l, double r, int has_r, double lh, double *d,
                 double *lap)
{
    double df = r - c, db = c - l;
    *lap = 0.0;
    if (has_l && has_r) {
        *d = fabs(db) < fabs(df) ? db : df;
        *lap = df - db;
    } else if (has_r) {
        *d = df;
    } else if (has_l) {
        *d = db;
    } else {
        *d = 0.0;
    }
    if (fabs(*d) > lh)
        *d = 0.0;
}

int lt_qt_ref_build(lt_qt_ref_t *ref, const double *w, uint32_t width, uint32_t height,
                    uint32_t layers, double lambda_h, double lambda_d)
{
    uint32_t k, x, y;
    size_t n = (size_t)width * height;
    ref->planes = NULL;
    if (width == 0 || height == 0 || layers == 0 || w == NULL)
        return -1;
    ref->planes = (lt_qt_ref_plane_t *)malloc(n * layers * sizeof *ref->planes);
    if (ref->planes == NULL)
        return -1;
    ref->width = width;
    ref->height = height;
    ref->layers = layers;
    for (k = 0; k < layers; k++) {
        const double *lw = w + n * k;
        for (y = 0; y < height; y++) {
            for (x = 0; x < width; x++) {
                lt_qt_ref_plane_t *p = &ref->planes[n * k + (size_t)y * width + x];
                double c = at(lw, width, (int32_t)x, (int32_t)y), lx, ly;
                int hl = x > 0, hr = x + 1 < width, hu = y > 0, hd = y + 1 < height;
                double l = hl ? at(lw, width, (int32_t)x - 1, (int32_t)y) : 0.0;
                double r = hr ? at(lw, width, (int32_t)x + 1, (int32_t)y) : 0.0;
                double u = hu ? at(lw, width, (int32_t)x, (int32_t)y - 1) : 0.0;
                double d = hd ? at(lw, width, (int32_t)x, (int32_t)y + 1) : 0.0;
                if (!(c >= 0.0))
                    c = 0.0;
                axis(c, l, hl, r, hr, lambda_h, &p->al, &lx);
                axis(c, u, hu, d, hd, lambda_h, &p->be, &ly);
                p->c = c;
                p->o = fabs(lx) + fabs(ly) >= lambda_d;
            }
        }
    }
    return 0;
}

void lt_qt_ref_free(lt_qt_ref_t *ref)
{
    free(ref->planes);
    ref->planes = NULL;
}

/* ---- the march --------------------------------------------------------------------------------- */

typedef struct layer_res {
    int hit, occ;
    double thit, tocc;
} layer_res_t;

static double f_at(const lt_qt_ref_plane_t *p, const lt_qt_ref_ray_t *r, double t, int32_t px,
                   int32_t py)
{
    double x = r->x + t * r->dx, y = r->y + t * r->dy;
    double wp = p->c + p->al * (x - (px + 0.5)) + p->be * (y - (py + 0.5));
    double wr = r->w + t * r->dw;
    /* the clip at w = 0 (the point at infinity) may round a hair below it */
    return (wr > 0.0 ? wr : 0.0) - wp;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Grid-line crossing parameters in (t0, t1) plus both ends, sorted (lt_qt_ref.h). */
size_t lt_qt_ref_crossings(const lt_qt_ref_ray_t *r, double t0, double t1, double *ts, size_t cap)
{
    size_t n = 0;
    int a;
    ts[n++] = t0;
    for (a = 0; a < 2; a++) {
        double o = a ? r->y : r->x, d = a ? r->dy : r->dx, lo, hi, g;
        if (d == 0.0)
            continue;
        lo = o + t0 * d;
        hi = o + t1 * d;
        if (lo > hi) {
            double s = lo;
            lo = hi;
            hi = s;
        }
        for (g = floor(lo) + 1.0; g < hi && n + 1 < cap; g += 1.0) {
            double t = (g - o) / d;
            if (t > t0 && t < t1)
                ts[n++] = t;
        }
    }
    ts[n++] = t1;
    qsort(ts, n, sizeof *ts, cmp_double);
    return n;
}

static void trace_layer(const lt_qt_ref_t *ref, uint32_t layer, const lt_qt_ref_ray_t *r,
                        double t0, double t1, int state, double *ts, size_t cap, long *pixels,
                        layer_res_t *res)
{
    /* state: 1 in front, -1 behind, 0 unknown (the start of a deeper layer) */
    const lt_qt_ref_plane_t *pl = ref->planes + (size_t)layer * ref->width * ref->height;
    size_t n = lt_qt_ref_crossings(r, t0, t1, ts, cap), i;
    res->hit = res->occ = 0;
    res->thit = res->tocc = t0;
    for (i = 0; i + 1 < n; i++) {
        double ta = ts[i], tb = ts[i + 1], tm = 0.5 * (ta + tb), fa, fb;
        int32_t px = (int32_t)floor(r->x + tm * r->dx), py = (int32_t)floor(r->y + tm * r->dy);
        const lt_qt_ref_plane_t *p;
        if (tb <= ta)
            continue;
        if (px < 0)
            px = 0;
        if (py < 0)
            py = 0;
        if (px >= (int32_t)ref->width)
            px = (int32_t)ref->width - 1;
        if (py >= (int32_t)ref->height)
            py = (int32_t)ref->height - 1;
        p = &pl[(size_t)py * ref->width + (size_t)px];
        (*pixels)++;
        fa = f_at(p, r, ta, px, py);
        fb = f_at(p, r, tb, px, py);
        if (fa >= 0.0 && fb < 0.0) {
            res->hit = 1;
            res->thit = ta + (tb - ta) * fa / (fa - fb);
            return;
        }
        if (fa < 0.0) {
            if (state == 1 && !p->o) {
                res->hit = 1;
                res->thit = ta;
                return;
            }
            if (state != -1 && !res->occ) {
                res->occ = 1;
                res->tocc = ta;
            }
        }
        state = fb < 0.0 ? -1 : 1;
    }
}

void lt_qt_ref_clip(uint32_t width, uint32_t height, const lt_qt_ref_ray_t *ray, double *t0,
                    double *t1)
{
    int a;
    *t0 = ray->tmin;
    *t1 = ray->tmax;
    for (a = 0; a < 2; a++) {
        double o = a ? ray->y : ray->x, d = a ? ray->dy : ray->dx;
        double ext = a ? (double)height : (double)width;
        if (d == 0.0) {
            if (!(o >= 0.0 && o < ext))
                *t1 = -1.0;
        } else {
            double ta = (0.0 - o) / d, tb = (ext - o) / d;
            if (ta > tb) {
                double s = ta;
                ta = tb;
                tb = s;
            }
            if (ta > *t0)
                *t0 = ta;
            if (tb < *t1)
                *t1 = tb;
        }
    }
    if (ray->dw < 0.0 && ray->w / -ray->dw < *t1)
        *t1 = ray->w / -ray->dw;
}

void lt_qt_ref_trace(const lt_qt_ref_t *ref, const lt_qt_ref_ray_t *ray, lt_qt_ref_hit_t *hit)
{
    double t0, t1, cand_t = 0.0;
    int cand = -1;
    uint32_t layer;
    size_t cap = 2u * (ref->width + ref->height) + 8u;
    double *ts;

    hit->status = LT_QT_MISS;
    hit->layer = -1;
    hit->pixels = 0;
    lt_qt_ref_clip(ref->width, ref->height, ray, &t0, &t1);
    hit->t = t1;
    if (!(t0 < t1)) {
        hit->t = ray->tmax;
        hit->w = ray->w + hit->t * ray->dw;
        return;
    }
    ts = (double *)malloc(cap * sizeof *ts);
    if (ts == NULL)
        return;
    for (layer = 0; layer < ref->layers; layer++) {
        layer_res_t r;
        trace_layer(ref, layer, ray, t0, t1, 0, ts, cap, &hit->pixels, &r);
        if (r.hit && !r.occ) {
            hit->status = LT_QT_HIT;
            hit->t = r.thit;
            hit->layer = (int)layer;
            break;
        }
        if (!r.hit && !r.occ) {
            if (cand >= 0) {
                hit->status = LT_QT_HIT;
                hit->t = cand_t;
                hit->layer = cand;
            }
            break;
        }
        if (r.hit) {
            cand = (int)layer;
            cand_t = r.thit;
            t1 = r.thit;
        }
        t0 = r.tocc;
        if (layer + 1u == ref->layers) {
            hit->status = LT_QT_OCCLUDED;
            hit->t = r.tocc;
            hit->layer = (int)layer;
        }
    }
    free(ts);
    hit->w = ray->w + hit->t * ray->dw;
}
