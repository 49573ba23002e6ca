/* lt_scene.c - scene placement, quantisation, camera rays and the double reference. Host only. */
#include "render/lt_scene.h"
#include "io/lt_fx_float.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int lt_scene_prepare(const lt_mesh_t *m, lt_scene_t *s, lt_diag_t *diag)
{
    double ext = 0.0, diag2 = 0.0;
    uint32_t i, a, j;
    int e;

    memset(s, 0, sizeof *s);
    for (a = 0; a < 3; a++) {
        double w = m->hi[a] - m->lo[a];
        s->center[a] = 0.5 * (m->lo[a] + m->hi[a]);
        diag2 += w * w;
        if (w > ext)
            ext = w;
    }
    if (!(ext > 0.0) || !isfinite(diag2)) {
        lt_diag_fail(diag, "scene has empty or non-finite bounds (extent %g)", ext);
        return -1;
    }
    /* largest power of two with radius * scale <= 2^LT_SCENE_RADIUS_LOG2 */
    frexp(0.5 * sqrt(diag2) / ldexp(1.0, LT_SCENE_RADIUS_LOG2), &e);
    s->scale = ldexp(1.0, -e);
    s->radius = 0.5 * sqrt(diag2) * s->scale;
    s->ntris = m->ntris;
    s->tq = malloc((size_t)m->ntris * sizeof *s->tq);
    s->tf = malloc((size_t)m->ntris * sizeof *s->tf);
    s->vd = malloc((size_t)m->ntris * 9 * sizeof(double));
    if (s->tq == NULL || s->tf == NULL || s->vd == NULL) {
        lt_scene_free(s);
        lt_diag_fail(diag, "out of memory for %u triangles", m->ntris);
        return -1;
    }
    /* float32 vertices on one grid, 2^(e - 23) for |coordinate| <= 2^e (here e <= 10: every
       coordinate lies within the radius): each is then exact in float, and so is every
       difference of two (|v1 - v0| <= 2^(e+1) in steps of 2^(e-23): 24 bits), so the kernels'
       rebuild fl(v0 + e1) gives back v1 bit for bit in every triangle that shares it - what the
       watertight test needs (docs/watertight.md). The grid step is at most twice the float
       spacing at the largest coordinate. */
    {
        double mx = 0.0;
        for (i = 0; i < m->ntris * 9u; i++) {
            double c = fabs((m->v[i] - s->center[i % 3u]) * s->scale);
            mx = c > mx ? c : mx;
        }
        frexp(mx, &e);
        s->fgrid = ldexp(1.0, e - 23);
    }
    for (i = 0; i < m->ntris; i++) {
        lt_q16_t q[3][3];
        float fv[3][3];
        for (j = 0; j < 3; j++)
            for (a = 0; a < 3; a++) {
                double c = (m->v[i * 9 + j * 3 + a] - s->center[a]) * s->scale;
                s->vd[i * 9 + j * 3 + a] = c;
                q[j][a] = lt_q16_from_double_sat(c);
                fv[j][a] = (float)(nearbyint(c / s->fgrid) * s->fgrid);
            }
        {
            /* area in double of the file's own coordinates (before centring: a unit triangle
               beside a 1e30 one keeps its area there, and loses it to the centring and to the
               quantisation alike) and of the quantised vertices (exact) */
            const double *v = &m->v[(size_t)i * 9];
            double e1[3], e2[3], nx, ny, nz;
            int64_t q1[3], q2[3];
            for (a = 0; a < 3; a++) {
                e1[a] = v[3 + a] - v[a];
                e2[a] = v[6 + a] - v[a];
                q1[a] = (int64_t)q[1][a] - q[0][a];
                q2[a] = (int64_t)q[2][a] - q[0][a];
            }
            nx = e1[1] * e2[2] - e1[2] * e2[1];
            ny = e1[2] * e2[0] - e1[0] * e2[2];
            nz = e1[0] * e2[1] - e1[1] * e2[0];
            if (nx != 0.0 || ny != 0.0 || nz != 0.0) {
                double l[3];
                s->nonzero++;
                for (a = 0; a < 3; a++) {
                    const double *p0 = &v[3 * a], *p1 = &v[3 * ((a + 1) % 3)];
                    l[a] = s->scale * sqrt((p1[0] - p0[0]) * (p1[0] - p0[0]) +
                                           (p1[1] - p0[1]) * (p1[1] - p0[1]) +
                                           (p1[2] - p0[2]) * (p1[2] - p0[2]));
                    if (l[a] > 0.0 && (s->min_edge == 0.0 || l[a] < s->min_edge))
                        s->min_edge = l[a];
                }
                /* every vertex lies within the radius, 2^LT_SCENE_RADIUS_LOG2 units = 2^26 raw:
                   edges < 2^27 raw, products < 2^54, exact in int64 */
                if (q1[1] * q2[2] == q1[2] * q2[1] && q1[2] * q2[0] == q1[0] * q2[2] &&
                    q1[0] * q2[1] == q1[1] * q2[0])
                    s->collapsed_q16++;
            }
        }
        for (a = 0; a < 3; a++) {
            s->tq[i].v0[a] = q[0][a];
            s->tq[i].e1[a] = q[1][a] - q[0][a];
            s->tq[i].e2[a] = q[2][a] - q[0][a];
            s->tf[i].v0[a] = fv[0][a];
            s->tf[i].e1[a] = fv[1][a] - fv[0][a]; /* exact: both on the grid */
            s->tf[i].e2[a] = fv[2][a] - fv[0][a];
        }
    }
    return 0;
}

int lt_scene_check_q16(const lt_scene_t *s, const char *name, lt_diag_t *diag)
{
    if ((uint64_t)s->collapsed_q16 * 1000000u <= (uint64_t)s->nonzero * LT_SCENE_MAX_COLLAPSED_PPM)
        return 0;
    lt_diag_fail(diag,
                 "%s: cannot be represented in s15.16: %u of %u triangles with non-zero area "
                 "(%.3f%%) collapse to zero area (limit %.1f%%); the scene is scaled by %g to a "
                 "radius of %.0f units, its shortest edge is %.3g units against a resolution of "
                 "2^-16 = 1.5e-05; use the float32 path (run, render, shadows: --num f32) or split the scene",
                 name, s->collapsed_q16, s->nonzero, 100.0 * s->collapsed_q16 / (double)s->nonzero,
                 LT_SCENE_MAX_COLLAPSED_PPM / 1e4, s->scale, s->radius, s->min_edge);
    return -1;
}

void lt_scene_free(lt_scene_t *s)
{
    free(s->tq);
    free(s->tf);
    free(s->vd);
    memset(s, 0, sizeof *s);
}

static void normalize(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
}

static void cross(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

void lt_camera_default(const lt_scene_t *s, uint32_t width, uint32_t height, lt_camera_t *c)
{
    double dir[3] = {0.45, 0.35, 1.0}, wup[3] = {0.0, 1.0, 0.0};
    double dist;
    int a;
    (void)s;
    normalize(dir);
    c->tan_half_fov = tan(20.0 * 3.14159265358979323846 / 180.0);
    dist = s->radius / c->tan_half_fov;
    for (a = 0; a < 3; a++) {
        c->eye[a] = dir[a] * dist; /* the scaled space is centred on the bounding box */
        c->fwd[a] = -dir[a];
    }
    cross(c->fwd, wup, c->right);
    normalize(c->right);
    cross(c->right, c->fwd, c->up);
    c->width = width;
    c->height = height;
}

void lt_camera_basis(lt_camera_t *c, const double dir[3], const double up[3])
{
    int a;
    for (a = 0; a < 3; a++)
        c->fwd[a] = dir[a];
    normalize(c->fwd);
    cross(c->fwd, up, c->right);
    normalize(c->right);
    cross(c->right, c->fwd, c->up);
}

int lt_camera_look(const lt_scene_t *s, const double eye[3], const double target[3],
                   const double up[3], double fov_y_deg, uint32_t width, uint32_t height,
                   lt_camera_t *c, lt_diag_t *diag)
{
    double lim = ldexp(1.0, LT_CFG_GEOM_MAX_LOG2), dir[3];
    int a;
    for (a = 0; a < 3; a++) {
        c->eye[a] = (eye[a] - s->center[a]) * s->scale;
        dir[a] = target[a] - eye[a];
        if (fabs(c->eye[a]) > lim) {
            lt_diag_fail(diag,
                         "camera eye is %.4g scene radii from the centre; the fixed-point range "
                         "allows at most %.4g (LT_CFG_GEOM_MAX_LOG2 = %d)",
                         fabs(c->eye[a]) / s->radius, lim / s->radius, LT_CFG_GEOM_MAX_LOG2);
            return -1;
        }
    }
    {
        /* the scene file's rules (lt_scenefile.c), for eyes and targets given as flags: a view
           direction, and an up vector not parallel to it (sine of their angle above 1e-6) */
        double fm = fmax(fabs(dir[0]), fmax(fabs(dir[1]), fabs(dir[2])));
        double um = fmax(fabs(up[0]), fmax(fabs(up[1]), fabs(up[2])));
        double g[3], u[3], x[3], s2;
        if (!(fm > 0.0) || !isfinite(fm)) {
            lt_diag_fail(diag, "camera target [%g, %g, %g] %s the eye [%g, %g, %g]: no view "
                         "direction", target[0], target[1], target[2],
                         fm > 0.0 ? "is too far from" : "equals", eye[0], eye[1], eye[2]);
            return -1;
        }
        for (a = 0; a < 3; a++) {
            g[a] = dir[a] / fm;
            u[a] = up[a] / um;
        }
        x[0] = g[1] * u[2] - g[2] * u[1];
        x[1] = g[2] * u[0] - g[0] * u[2];
        x[2] = g[0] * u[1] - g[1] * u[0];
        s2 = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) /
             ((g[0] * g[0] + g[1] * g[1] + g[2] * g[2]) * (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]));
        if (!(s2 > 1e-12)) {
            lt_diag_fail(diag, "camera view direction (target - eye = [%g, %g, %g]) is parallel "
                         "to the up vector [%g, %g, %g] (the angle between them must be above "
                         "1e-6 rad): move the eye or the target sideways",
                         dir[0], dir[1], dir[2], up[0], up[1], up[2]);
            return -1;
        }
    }
    lt_camera_basis(c, dir, up);
    c->tan_half_fov = tan(0.5 * fov_y_deg * 3.14159265358979323846 / 180.0);
    c->width = width;
    c->height = height;
    return 0;
}

void lt_scene_light(const lt_scene_t *s, const double *pos, double out[3])
{
    const double d[3] = {-0.5, 1.5, 0.8};
    double ln = sqrt(0.25 + 2.25 + 0.64);
    int a;
    for (a = 0; a < 3; a++)
        out[a] = pos != NULL ? (pos[a] - s->center[a]) * s->scale : 2.0 * s->radius * d[a] / ln;
}

void lt_camera_dir(const lt_camera_t *c, uint32_t x, uint32_t y, double d[3])
{
    double aspect = (double)c->width / (double)c->height;
    double u = (2.0 * ((double)x + 0.5) / (double)c->width - 1.0) * c->tan_half_fov * aspect;
    double v = (1.0 - 2.0 * ((double)y + 0.5) / (double)c->height) * c->tan_half_fov;
    int a;
    for (a = 0; a < 3; a++)
        d[a] = c->fwd[a] + u * c->right[a] + v * c->up[a];
    normalize(d);
}

/* The lanes of the 4x4 tile at (tx, ty) whose pixel is on the image. */
static unsigned tile_lanes(const lt_camera_t *c, uint32_t tx, uint32_t ty)
{
    unsigned k = 0;
    int i;
    for (i = 0; i < LT_LANES; i++)
        k |= (unsigned)(tx + (uint32_t)(i % 4) < c->width && ty + (uint32_t)(i / 4) < c->height)
             << i;
    return k;
}

/* Written as lane loops over doubles that the compiler vectorises (IEEE +, x, / and sqrt are
 * correctly rounded in any width; the build keeps contraction off), so bit-identical to
 * lt_camera_dir. */
unsigned lt_camera_tile_dirs(const lt_camera_t *c, uint32_t tx, uint32_t ty, double dx[LT_LANES],
                             double dy[LT_LANES], double dz[LT_LANES])
{
    double aspect = (double)c->width / (double)c->height;
    double w = (double)c->width, h = (double)c->height, t = c->tan_half_fov;
    /* local arrays: the compiler cannot prove that the callers' dx, dy and dz do not overlap,
     * so loops over them stay scalar (48 divides a tile, measured as most of the function) */
    double u[LT_LANES], v[LT_LANES], l[LT_LANES], ex[LT_LANES], ey[LT_LANES], ez[LT_LANES];
    double uc[4], vr[4];
    unsigned k;
    int i;
    /* u depends on the column only and v on the row: 4 + 4 divides, not 16 + 16 */
    for (i = 0; i < 4; i++) {
        double x = (double)(tx + (uint32_t)i), y = (double)(ty + (uint32_t)i);
        uc[i] = (2.0 * (x + 0.5) / w - 1.0) * t * aspect;
        vr[i] = (1.0 - 2.0 * (y + 0.5) / h) * t;
    }
    for (i = 0; i < LT_LANES; i++) {
        u[i] = uc[i % 4];
        v[i] = vr[i / 4];
    }
    for (i = 0; i < LT_LANES; i++) {
        ex[i] = c->fwd[0] + u[i] * c->right[0] + v[i] * c->up[0];
        ey[i] = c->fwd[1] + u[i] * c->right[1] + v[i] * c->up[1];
        ez[i] = c->fwd[2] + u[i] * c->right[2] + v[i] * c->up[2];
    }
    for (i = 0; i < LT_LANES; i++)
        l[i] = sqrt(ex[i] * ex[i] + ey[i] * ey[i] + ez[i] * ez[i]);
    for (i = 0; i < LT_LANES; i++) {
        ex[i] /= l[i];
        ey[i] /= l[i];
        ez[i] /= l[i];
    }
    k = tile_lanes(c, tx, ty);
    for (i = 0; i < LT_LANES; i++)
        if (((k >> i) & 1u) == 0) {
            ex[i] = ey[i] = 0.0;
            ez[i] = 1.0;
        }
    memcpy(dx, ex, sizeof ex);
    memcpy(dy, ey, sizeof ey);
    memcpy(dz, ez, sizeof ez);
    return k;
}

double *lt_camera_dirs_table(const lt_camera_t *c)
{
    size_t tw = (c->width + 3u) / 4u, th = (c->height + 3u) / 4u, x, y;
    double *tab;
    if (tw == 0 || th == 0 || tw * th > SIZE_MAX / (3 * LT_LANES * sizeof *tab))
        return NULL;
    if ((tab = malloc(tw * th * 3 * LT_LANES * sizeof *tab)) == NULL)
        return NULL;
    for (y = 0; y < th; y++)
        for (x = 0; x < tw; x++) {
            double *p = &tab[(y * tw + x) * 3 * LT_LANES];
            (void)lt_camera_tile_dirs(c, (uint32_t)(4 * x), (uint32_t)(4 * y), p, p + LT_LANES,
                                      p + 2 * LT_LANES);
        }
    return tab;
}

unsigned lt_camera_tile_dirs_tab(const lt_camera_t *c, const double *tab, uint32_t tx,
                                 uint32_t ty, double dx[LT_LANES], double dy[LT_LANES],
                                 double dz[LT_LANES])
{
    const double *p;
    if (tab == NULL)
        return lt_camera_tile_dirs(c, tx, ty, dx, dy, dz);
    p = &tab[((size_t)(ty / 4u) * ((c->width + 3u) / 4u) + tx / 4u) * 3 * LT_LANES];
    memcpy(dx, p, LT_LANES * sizeof *dx);
    memcpy(dy, p + LT_LANES, LT_LANES * sizeof *dy);
    memcpy(dz, p + 2 * LT_LANES, LT_LANES * sizeof *dz);
    return tile_lanes(c, tx, ty);
}

lt_mask16_t lt_camera_packet_q16(const lt_camera_t *c, uint32_t tx, uint32_t ty, lt_ray16_q16_t *r)
{
    return lt_camera_packet_tab_q16(c, NULL, tx, ty, r);
}

lt_mask16_t lt_camera_packet_f32(const lt_camera_t *c, uint32_t tx, uint32_t ty, lt_ray16_f32_t *r)
{
    return lt_camera_packet_tab_f32(c, NULL, tx, ty, r);
}

lt_mask16_t lt_camera_packet_tab_q16(const lt_camera_t *c, const double *tab, uint32_t tx,
                                     uint32_t ty, lt_ray16_q16_t *r)
{
    double dx[LT_LANES], dy[LT_LANES], dz[LT_LANES];
    unsigned k = lt_camera_tile_dirs_tab(c, tab, tx, ty, dx, dy, dz);
    lt_q16_t o[3];
    int i;
    for (i = 0; i < 3; i++)
        o[i] = lt_q16_from_double_sat(c->eye[i]);
    for (i = 0; i < LT_LANES; i++) {
        r->ox.l[i] = o[0];
        r->oy.l[i] = o[1];
        r->oz.l[i] = o[2];
        r->dx.l[i] = lt_q30_from_double_sat(dx[i]);
        r->dy.l[i] = lt_q30_from_double_sat(dy[i]);
        r->dz.l[i] = lt_q30_from_double_sat(dz[i]);
        r->tmin.l[i] = 0;
        r->tmax.l[i] = LT_Q16_MAX - 1;
    }
    lt_ray16_q16_setup(r);
    return (lt_mask16_t)k;
}

lt_mask16_t lt_camera_packet_tab_f32(const lt_camera_t *c, const double *tab, uint32_t tx,
                                     uint32_t ty, lt_ray16_f32_t *r)
{
    double dx[LT_LANES], dy[LT_LANES], dz[LT_LANES];
    unsigned k = lt_camera_tile_dirs_tab(c, tab, tx, ty, dx, dy, dz);
    int i;
    for (i = 0; i < LT_LANES; i++) {
        r->ox.l[i] = (float)c->eye[0];
        r->oy.l[i] = (float)c->eye[1];
        r->oz.l[i] = (float)c->eye[2];
        r->dx.l[i] = (float)dx[i];
        r->dy.l[i] = (float)dy[i];
        r->dz.l[i] = (float)dz[i];
        r->tmin.l[i] = 0.0f;
        r->tmax.l[i] = 3.0e38f;
    }
    lt_ray16_f32_setup(r);
    return (lt_mask16_t)k;
}

int32_t lt_ref_trace(const lt_scene_t *s, const double o[3], const double d[3], double *t)
{
    uint32_t i;
    int32_t best = -1;
    double tb = HUGE_VAL;
    for (i = 0; i < s->ntris; i++) {
        const double *v = &s->vd[i * 9];
        double e1[3], e2[3], p[3], q[3], tv[3], det, u, w, tt;
        int a;
        for (a = 0; a < 3; a++) {
            e1[a] = v[3 + a] - v[a];
            e2[a] = v[6 + a] - v[a];
            tv[a] = o[a] - v[a];
        }
        cross(d, e2, p);
        det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
        if (det == 0.0)
            continue;
        u = (tv[0] * p[0] + tv[1] * p[1] + tv[2] * p[2]) / det;
        if (u < 0.0 || u > 1.0)
            continue;
        cross(tv, e1, q);
        w = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
        if (w < 0.0 || u + w > 1.0)
            continue;
        tt = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
        if (tt > 0.0 && tt < tb) {
            tb = tt;
            best = (int32_t)i;
        }
    }
    *t = tb;
    return best;
}
