/* lt_softshadow.c - soft shadows from a quad light by multi-frusta tracing or 16-ray packets, after
 * primary visibility by 16-ray packets or primary frusta from one linear camera, the shading and
 * filtering of Benthin & Wald 2009 [Benthin09], section 4.5, the 256-sample reference, quality
 * metrics and brute-force audits, on the core's kernels (lt_frusta.h, lt_bvh.h). Every per-pixel
 * stage runs lane ops, so the sim build charges it to its phase (SETUP, TRAVERSE, INTERSECT, SHADE,
 * FILTER). Host only.
 */
#include "render/lt_softshadow.h"
#include "io/lt_fx_float.h"
#include "lt_meter.h"
#include "io/lt_png.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct lt_softshadow {
    const lt_scene_t *s;
    lt_camera_t cam;
    lt_ss_light_t light;
    lt_ss_opts_t o;
    uint32_t w, h;
    size_t n;
    void *adeep, *ashal;
    lt_bvh_t deep, shal;
    lt_qmc_sets_t sets;
    lt_frusta_table_q16_t *tbq;
    lt_frusta_table_f32_t *tbf;
    lt_q16_t mq[3];             /* light centre, s15.16 */
    lt_q30_t nlq[3];            /* light normal (emitting side), s1.30 */
    float mf[3], nlf[3];
    lt_q30_t *tnq;              /* per triangle unit normal, s1.30 (3 per triangle) */
    float *tnf;
    /* per pixel (row-major) */
    int32_t *id;
    lt_q16_t *oq[3], *zq, *gq, *eq, *efq, *erq, *efrq, *vq, *vrq;
    lt_q30_t *nq[3];
    float *nf[3];
    float *of[3], *zf, *gf, *ef, *eff, *erf, *efrf, *vf, *vrf;
    uint8_t *valid, *lit;
    uint16_t *occ[2];
    int have[2], last;
    lt_frusta_vtable_q16_t *vtq; /* the linear camera of both primary methods */
    lt_frusta_vtable_f32_t *vtf;
    int32_t *pid[2];             /* per pixel: closest-hit id of P-Packet (0) / P-Frusta (1) */
    uint32_t *pt[2];             /* ... and the bits of its t */
    int have_prim[2];
    double *vref;
    lt_ss_counts_t cnt;
};

typedef struct named_view {
    const char *name;
    lt_ss_view_t v;
} named_view_t;

static const named_view_t views[] = {
    {"bunny", {0, {0, 0, 0}, {0, 0, 0}, 40, {4, 22, 8}, 6, 1}},
    {"dragon_res3", {0, {0, 0, 0}, {0, 0, 0}, 40, {0.03, 0.42, 0.1}, 0.08, 1}},
    {"teapot", {0, {0, 0, 0}, {0, 0, 0}, 40, {8, 40, 14}, 10, 1}},
    {"sibenik", {1, {-18, -12, 0}, {0, -10, 0}, 65, {5, 0, 0}, 2.5, 0}},
    {"sponza", {1, {-14, 2.5, 1}, {0, 4.5, -1}, 65, {2, 19, 0}, 3, 0}},
    {"conference", {1, {1500, 380, 500}, {0, 150, -300}, 60, {300, 600, -150}, 150, 0}},
};

int lt_ss_view_for(const char *mesh_path, lt_ss_view_t *v)
{
    const char *base = strrchr(mesh_path, '/');
    size_t i;
    base = base != NULL ? base + 1 : mesh_path;
    for (i = 0; i < sizeof views / sizeof views[0]; i++) {
        size_t n = strlen(views[i].name);
        if (strncmp(base, views[i].name, n) == 0 && (base[n] == '.' || base[n] == '\0')) {
            *v = views[i].v;
            return 1;
        }
    }
    return 0;
}

void lt_ss_opts_default(const lt_scene_t *s, lt_ss_opts_t *o)
{
    int e;
    memset(o, 0, sizeof *o);
    o->path = LT_PATH_Q16;
    o->leaf = 8;
    o->flags = LT_FRUSTA_BACKFACE | LT_FRUSTA_CORNER | LT_FRUSTA_CR;
    o->pflags = LT_FRUSTA_BACKFACE | LT_FRUSTA_CORNER | LT_FRUSTA_CR;
    o->qmc = LT_QMC_LP;
    o->depth_rel = 0.05;
    o->cos_min = 0.9;
    frexp(s->radius, &e);
    o->eps = ldexp(1.0, e - 12);
}

int lt_ss_light_square(const lt_scene_t *s, const double centre[3], double size, lt_ss_light_t *l,
                       lt_diag_t *diag)
{
    double half, side, lim = ldexp(1.0, LT_CFG_GEOM_MAX_LOG2);
    int a;
    /* the side on the 2^-7 grid of scaled units, at least one step */
    side = floor(size * s->scale * 128.0 + 0.5) / 128.0;
    if (side < 1.0 / 128.0)
        side = 0.0;
    half = 0.5 * side;
    for (a = 0; a < 3; a++) {
        double c = (centre[a] - s->center[a]) * s->scale;
        l->c[a] = floor((c - (a != 1 ? half : 0.0)) * 65536.0 + 0.5) / 65536.0;
        l->eu[a] = a == 0 ? side : 0.0;
        l->ev[a] = a == 2 ? side : 0.0;
        if (!(fabs(l->c[a]) + side <= lim)) {
            /* name the part that does not fit: the centre, or the size around it */
            if (!(fabs(c) <= lim))
                lt_diag_fail(diag, "light centre %.4g (axis %c) lies %.3g scene radii from the "
                             "scene's centre; the fixed-point range allows %.3g "
                             "(LT_CFG_GEOM_MAX_LOG2 = %d)", centre[a], "xyz"[a],
                             fabs(c) / s->radius, lim / s->radius, LT_CFG_GEOM_MAX_LOG2);
            else
                lt_diag_fail(diag, "light size %.4g (%.3g scene radii) around a centre %.3g "
                             "scene radii from the scene's centre (axis %c) reaches beyond the "
                             "fixed-point range of %.3g scene radii (LT_CFG_GEOM_MAX_LOG2 = %d); "
                             "the light may be at most %.4g wide there", size,
                             side / s->radius, fabs(c) / s->radius, "xyz"[a], lim / s->radius,
                             LT_CFG_GEOM_MAX_LOG2,
                             fmax(0.0, 2.0 * (lim - fabs(c)) / s->scale));
            return -1;
        }
    }
    return 0;
}

int lt_ss_add_ground(lt_mesh_t *m, double grow, lt_diag_t *diag)
{
    double *v = realloc(m->v, ((size_t)m->ntris + 2) * 9 * sizeof(double));
    double x0, x1, z0, z1, y;
    double q[4][3];
    static const int tri[2][3] = {{0, 2, 1}, {0, 3, 2}};
    int t, j, a;
    if (v == NULL) {
        lt_diag_fail(diag, "out of memory adding a ground plane");
        return -1;
    }
    m->v = v;
    x0 = m->lo[0] - grow * (m->hi[0] - m->lo[0]);
    x1 = m->hi[0] + grow * (m->hi[0] - m->lo[0]);
    z0 = m->lo[2] - grow * (m->hi[2] - m->lo[2]);
    z1 = m->hi[2] + grow * (m->hi[2] - m->lo[2]);
    y = m->lo[1];
    q[0][0] = x0, q[0][1] = y, q[0][2] = z0;
    q[1][0] = x1, q[1][1] = y, q[1][2] = z0;
    q[2][0] = x1, q[2][1] = y, q[2][2] = z1;
    q[3][0] = x0, q[3][1] = y, q[3][2] = z1;
    /* (0, 2, 1) and (0, 3, 2): e1 x e2 points +y (the front faces up) */
    for (t = 0; t < 2; t++)
        for (j = 0; j < 3; j++)
            for (a = 0; a < 3; a++)
                v[((size_t)m->ntris + (size_t)t) * 9 + (size_t)j * 3 + (size_t)a] = q[tri[t][j]][a];
    m->ntris += 2;
    m->lo[0] = x0, m->hi[0] = x1, m->lo[2] = z0, m->hi[2] = z1;
    return 0;
}

int lt_ss_pview(const lt_camera_t *c, uint32_t flags, lt_frusta_view_q16_t *vq,
                lt_frusta_view_f32_t *vf, lt_diag_t *diag)
{
    double aspect = (double)c->width / (double)c->height, th = c->tan_half_fov;
    double u0 = (1.0 / (double)c->width - 1.0) * th * aspect, du = 2.0 * th * aspect / c->width;
    double v0 = (1.0 - 1.0 / (double)c->height) * th, dv = -2.0 * th / c->height;
    double d0[3], dx[3], dy[3], m = 0.0, s, lim = ldexp(1.0, LT_CFG_GEOM_MAX_LOG2);
    uint32_t w4 = (c->width + 3u) & ~3u, h4 = (c->height + 3u) & ~3u;
    int a, j, e;
    for (a = 0; a < 3; a++) {
        d0[a] = c->fwd[a] + u0 * c->right[a] + v0 * c->up[a];
        dx[a] = du * c->right[a];
        dy[a] = dv * c->up[a];
        if (fabs(c->eye[a]) > lim) {
            lt_diag_fail(diag, "camera eye %.4g (axis %d) lies outside the fixed-point range "
                         "+-%.4g (LT_CFG_GEOM_MAX_LOG2 = %d)", c->eye[a], a, lim,
                         LT_CFG_GEOM_MAX_LOG2);
            return -1;
        }
    }
    /* the directions are affine in (x, y): their largest component is at a corner pixel */
    for (j = 0; j < 4; j++)
        for (a = 0; a < 3; a++) {
            double v = d0[a] + ((j & 1) ? (double)(w4 - 1u) : 0.0) * dx[a] +
                       ((j & 2) ? (double)(h4 - 1u) : 0.0) * dy[a];
            m = fabs(v) > m ? fabs(v) : m;
        }
    if (!(m > 0.0) || !(m < 1e30)) {
        lt_diag_fail(diag, "degenerate camera (largest direction component %g)", m);
        return -1;
    }
    frexp(m / 0.75, &e); /* m / 0.75 < 2^e */
    s = ldexp(1.0, -e);
    for (a = 0; a < 3; a++) {
        if (vq != NULL) {
            vq->o[a] = lt_q16_from_double_sat(c->eye[a]);
            vq->d0[a] = (lt_q30_t)floor(d0[a] * s * 1073741824.0 + 0.5);
            vq->dx[a] = (lt_q30_t)floor(dx[a] * s * 1073741824.0 + 0.5);
            vq->dy[a] = (lt_q30_t)floor(dy[a] * s * 1073741824.0 + 0.5);
        }
        if (vf != NULL) {
            vf->o[a] = (float)c->eye[a];
            vf->d0[a] = (float)(floor(d0[a] * s * 8388608.0 + 0.5) / 8388608.0);
            vf->dx[a] = (float)(floor(dx[a] * s * 8388608.0 + 0.5) / 8388608.0);
            vf->dy[a] = (float)(floor(dy[a] * s * 8388608.0 + 0.5) / 8388608.0);
        }
    }
    if (vq != NULL) {
        vq->width = c->width;
        vq->height = c->height;
        vq->flags = flags;
    }
    if (vf != NULL) {
        vf->width = c->width;
        vf->height = c->height;
        vf->flags = flags;
    }
    return 0;
}

static void *alloc64(size_t bytes)
{
    void *p = NULL;
    if (posix_memalign(&p, 64, bytes == 0 ? 64 : bytes) != 0)
        return NULL;
    memset(p, 0, bytes == 0 ? 64 : bytes);
    return p;
}

static int build_tree(const lt_softshadow_t *ss, uint32_t max_leaf, uint32_t min_leaf, void **arena,
                      lt_bvh_t *bvh, lt_diag_t *diag)
{
    lt_bvh_desc_t d;
    size_t bytes = 0;
    lt_status_t st;
    memset(&d, 0, sizeof d);
    d.max_leaf = max_leaf;
    d.min_leaf = min_leaf;
    st = lt_bvh_size(ss->s->ntris, &d, &bytes);
    if (st == LT_OK && (*arena = alloc64(bytes)) == NULL)
        st = LT_E_SPACE;
    if (st == LT_OK)
        st = ss->o.path == LT_PATH_Q16
                 ? lt_bvh_build_q16(bvh, &d, ss->s->tq, ss->s->ntris, *arena, bytes)
                 : lt_bvh_build_f32(bvh, &d, ss->s->tf, ss->s->ntris, *arena, bytes);
    if (st != LT_OK) {
        lt_diag_fail(diag, "building a BVH (leaf %u) over %u triangles: %s", max_leaf,
                     ss->s->ntris, lt_status_str(st));
        return -1;
    }
    bvh->isect = ss->o.isect; /* the intersector of every walk over it, frusta included */
    return 0;
}

void lt_ss_free(lt_softshadow_t *ss)
{
    int a;
    if (ss == NULL)
        return;
    free(ss->adeep);
    free(ss->ashal);
    free(ss->tbq);
    free(ss->tbf);
    free(ss->tnq);
    free(ss->tnf);
    free(ss->id);
    for (a = 0; a < 3; a++) {
        free(ss->oq[a]);
        free(ss->nq[a]);
        free(ss->of[a]);
        free(ss->nf[a]);
    }
    free(ss->zq), free(ss->gq), free(ss->eq), free(ss->efq), free(ss->erq), free(ss->efrq);
    free(ss->zf), free(ss->gf), free(ss->ef), free(ss->eff), free(ss->erf), free(ss->efrf);
    free(ss->vq), free(ss->vrq), free(ss->vf), free(ss->vrf);
    free(ss->valid);
    free(ss->lit);
    free(ss->occ[0]);
    free(ss->occ[1]);
    free(ss->vref);
    free(ss->vtq);
    free(ss->vtf);
    for (a = 0; a < 2; a++) {
        free(ss->pid[a]);
        free(ss->pt[a]);
    }
    free(ss);
}

/* Fixed simulated addresses for every array the kernels touch (cache results independent of the
 * host allocator), 16 MiB apart; no-ops without a cycle model. */
static void region(const void *p, size_t bytes, unsigned slot)
{
    lt_meter_region(p, bytes, 0x10000000u + (uint64_t)slot * 0x01000000u);
}

lt_softshadow_t *lt_ss_create(const lt_scene_t *s, const lt_camera_t *cam, const lt_ss_light_t *l,
                              const lt_ss_opts_t *o, lt_diag_t *diag)
{
    lt_softshadow_t *ss = calloc(1, sizeof *ss);
    size_t n = (size_t)cam->width * cam->height, bq = n * sizeof(lt_q16_t), bf = n * sizeof(float);
    double m[3], nl[3], len;
    uint32_t i;
    int a, fail = 0;
    lt_status_t st;

    if (ss == NULL) {
        lt_diag_fail(diag, "out of memory");
        return NULL;
    }
    if (o->leaf < 1 || o->leaf > LT_BVH_MAX_LEAF) {
        lt_diag_fail(diag, "frusta leaf size %u outside 1..%d (LT_BVH_MAX_LEAF)", o->leaf,
                     LT_BVH_MAX_LEAF);
        free(ss);
        return NULL;
    }
    ss->s = s;
    ss->cam = *cam;
    ss->light = *l;
    ss->o = *o;
    ss->w = cam->width;
    ss->h = cam->height;
    ss->n = n;
    ss->last = -1;
    if (build_tree(ss, 4, 1, &ss->adeep, &ss->deep, diag) != 0 ||
        build_tree(ss, o->leaf, o->leaf > 1 ? o->leaf / 2 : 1, &ss->ashal, &ss->shal, diag) != 0) {
        lt_ss_free(ss);
        return NULL;
    }
    (void)lt_qmc_interleave4x4(o->qmc, o->scramble, &ss->sets);
    /* light centre and its emitting normal (eu x ev, flipped toward the scene centre) */
    for (a = 0; a < 3; a++)
        m[a] = l->c[a] + 0.5 * (l->eu[a] + l->ev[a]);
    nl[0] = l->eu[1] * l->ev[2] - l->eu[2] * l->ev[1];
    nl[1] = l->eu[2] * l->ev[0] - l->eu[0] * l->ev[2];
    nl[2] = l->eu[0] * l->ev[1] - l->eu[1] * l->ev[0];
    len = sqrt(nl[0] * nl[0] + nl[1] * nl[1] + nl[2] * nl[2]);
    if (len == 0.0) { /* a point or line light: face the scene centre */
        len = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]) + 1e-300;
        for (a = 0; a < 3; a++)
            nl[a] = -m[a];
    }
    if (nl[0] * -m[0] + nl[1] * -m[1] + nl[2] * -m[2] < 0.0)
        len = -len;
    for (a = 0; a < 3; a++) {
        nl[a] /= len;
        ss->mq[a] = lt_q16_from_double_sat(m[a]);
        ss->nlq[a] = lt_q30_from_double_sat(nl[a]);
        ss->mf[a] = (float)m[a];
        ss->nlf[a] = (float)nl[a];
    }
    ss->tbq = alloc64(sizeof *ss->tbq);
    ss->tbf = alloc64(sizeof *ss->tbf);
    ss->tnq = malloc((size_t)s->ntris * 3 * sizeof(lt_q30_t) + 4);
    ss->tnf = malloc((size_t)s->ntris * 3 * sizeof(float) + 4);
    ss->id = malloc(n * sizeof *ss->id);
    for (a = 0; a < 3; a++) {
        ss->oq[a] = alloc64(bq), ss->nq[a] = alloc64(bq), ss->of[a] = alloc64(bf);
        ss->nf[a] = alloc64(bf);
        fail |= ss->oq[a] == NULL || ss->nq[a] == NULL || ss->of[a] == NULL || ss->nf[a] == NULL;
    }
    ss->zq = alloc64(bq), ss->gq = alloc64(bq), ss->eq = alloc64(bq), ss->efq = alloc64(bq);
    ss->erq = alloc64(bq), ss->efrq = alloc64(bq);
    ss->zf = alloc64(bf), ss->gf = alloc64(bf), ss->ef = alloc64(bf), ss->eff = alloc64(bf);
    ss->erf = alloc64(bf), ss->efrf = alloc64(bf);
    ss->vq = alloc64(bq), ss->vrq = alloc64(bq), ss->vf = alloc64(bf), ss->vrf = alloc64(bf);
    ss->valid = alloc64(n), ss->lit = alloc64(n);
    ss->occ[0] = alloc64(n * 2), ss->occ[1] = alloc64(n * 2);
    ss->vref = calloc(n + 1, sizeof(double));
    ss->vtq = alloc64(sizeof *ss->vtq);
    ss->vtf = alloc64(sizeof *ss->vtf);
    for (a = 0; a < 2; a++) {
        ss->pid[a] = calloc(n + 1, sizeof(int32_t));
        ss->pt[a] = calloc(n + 1, sizeof(uint32_t));
        fail |= ss->pid[a] == NULL || ss->pt[a] == NULL;
    }
    fail |= ss->vtq == NULL || ss->vtf == NULL;
    fail |= ss->tbq == NULL || ss->tbf == NULL || ss->tnq == NULL || ss->tnf == NULL ||
            ss->id == NULL || ss->zq == NULL || ss->gq == NULL || ss->eq == NULL ||
            ss->efq == NULL || ss->erq == NULL || ss->efrq == NULL || ss->zf == NULL ||
            ss->gf == NULL || ss->ef == NULL || ss->eff == NULL || ss->erf == NULL ||
            ss->efrf == NULL || ss->vq == NULL || ss->vrq == NULL || ss->vf == NULL ||
            ss->vrf == NULL || ss->valid == NULL || ss->lit == NULL || ss->occ[0] == NULL ||
            ss->occ[1] == NULL || ss->vref == NULL;
    if (fail) {
        lt_diag_fail(diag, "out of memory for a %ux%u soft-shadow frame", ss->w, ss->h);
        lt_ss_free(ss);
        return NULL;
    }
    /* per-triangle geometric normals (scene data, like a stored vertex attribute) */
    for (i = 0; i < s->ntris; i++) {
        const double *v = &s->vd[(size_t)i * 9];
        double e1[3], e2[3], nn[3], ln;
        for (a = 0; a < 3; a++) {
            e1[a] = v[3 + a] - v[a];
            e2[a] = v[6 + a] - v[a];
        }
        nn[0] = e1[1] * e2[2] - e1[2] * e2[1];
        nn[1] = e1[2] * e2[0] - e1[0] * e2[2];
        nn[2] = e1[0] * e2[1] - e1[1] * e2[0];
        ln = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
        for (a = 0; a < 3; a++) {
            double c = ln > 0.0 ? nn[a] / ln : (a == 1 ? 1.0 : 0.0);
            ss->tnq[(size_t)i * 3 + (size_t)a] = lt_q30_from_double_sat(c);
            ss->tnf[(size_t)i * 3 + (size_t)a] = (float)c;
        }
    }
    /* the sample table of the light */
    if (o->path == LT_PATH_Q16) {
        lt_frusta_light_q16_t fl;
        for (a = 0; a < 3; a++) {
            fl.c[a] = lt_q16_from_double_sat(l->c[a]);
            fl.eu[a] = lt_q16_from_double_sat(l->eu[a]);
            fl.ev[a] = lt_q16_from_double_sat(l->ev[a]);
        }
        fl.flags = o->flags;
        fl.end_shift = 0;
        st = lt_frusta_table_q16(&fl, &ss->sets, ss->tbq);
    } else {
        lt_frusta_light_f32_t fl;
        for (a = 0; a < 3; a++) {
            fl.c[a] = (float)l->c[a];
            fl.eu[a] = (float)l->eu[a];
            fl.ev[a] = (float)l->ev[a];
        }
        fl.flags = o->flags;
        fl.end_shift = 0;
        st = lt_frusta_table_f32(&fl, &ss->sets, ss->tbf);
    }
    if (st != LT_OK) {
        lt_diag_fail(diag, "light table: %s (edges must be multiples of 2^-7 units, corners "
                     "within the geometry bound)", lt_status_str(st));
        lt_ss_free(ss);
        return NULL;
    }
    /* the linear camera shared by P-Packet and P-Frusta */
    {
        lt_frusta_view_q16_t vq;
        lt_frusta_view_f32_t vf;
        if (lt_ss_pview(cam, o->pflags, &vq, &vf, diag) != 0) {
            lt_ss_free(ss);
            return NULL;
        }
        st = lt_frusta_vtable_q16(&vq, ss->vtq);
        if (st == LT_OK)
            st = lt_frusta_vtable_f32(&vf, ss->vtf);
        if (st != LT_OK) {
            lt_diag_fail(diag, "primary view table (%ux%u, flags %u): %s (the directions must "
                         "stay below 1 per axis, the eye within the geometry bound, the size "
                         "within LT_FRUSTA_PMAX_DIM %u)", cam->width, cam->height, o->pflags,
                         lt_status_str(st), LT_FRUSTA_PMAX_DIM);
            lt_ss_free(ss);
            return NULL;
        }
    }
    if (o->path == LT_PATH_Q16) {
        region(s->tq, s->ntris * sizeof *s->tq, 0);
        region(ss->tnq, s->ntris * 3 * sizeof *ss->tnq, 3);
        region(ss->tbq, sizeof *ss->tbq, 4);
        region(ss->zq, bq, 5), region(ss->nq[0], bq, 6), region(ss->nq[1], bq, 7);
        region(ss->nq[2], bq, 8), region(ss->eq, bq, 9), region(ss->efq, bq, 10);
    } else {
        region(s->tf, s->ntris * sizeof *s->tf, 0);
        region(ss->tnf, s->ntris * 3 * sizeof *ss->tnf, 3);
        region(ss->tbf, sizeof *ss->tbf, 4);
        region(ss->zf, bf, 5), region(ss->nf[0], bf, 6), region(ss->nf[1], bf, 7);
        region(ss->nf[2], bf, 8), region(ss->ef, bf, 9), region(ss->eff, bf, 10);
    }
    region(ss->adeep, ss->deep.bytes, 1);
    region(ss->ashal, ss->shal.bytes, 2);
    region(ss->valid, n, 11);
    if (o->path == LT_PATH_Q16)
        region(ss->vtq, sizeof *ss->vtq, 12);
    else
        region(ss->vtf, sizeof *ss->vtf, 12);
    return ss;
}

/* Pixel of lane i of the 4x4 tile at (tx, ty), or SIZE_MAX outside the image. */
static size_t pix(const lt_softshadow_t *ss, uint32_t tx, uint32_t ty, int i)
{
    uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
    return x < ss->w && y < ss->h ? (size_t)y * ss->w + x : (size_t)-1;
}

/* Reinterpret s1.30 lanes as s15.16 lanes for the sign-agnostic int32 ops (a register rename). */
static lt_vq16_t as16(lt_vq30_t a)
{
    lt_vq16_t r;
    memcpy(&r, &a, sizeof r);
    return r;
}

static lt_vq30_t as30(lt_vq16_t a)
{
    lt_vq30_t r;
    memcpy(&r, &a, sizeof r);
    return r;
}

/* Shading of one 4x4 tile from its primary rays and closest hits (SHADE): hit point o + t d, the
 * triangle's normal (a gather) turned toward the eye, the shadow origin lifted by eps along it,
 * and the direct term; the same code after P-Packet and P-Frusta. */
static void shade_tile_q16(lt_softshadow_t *ss, uint32_t tx, uint32_t ty, const lt_ray16_q16_t *r,
                           const lt_hit16_t *hit, lt_mask16_t k)
{
    lt_mask16_t hm, lm;
    lt_vq30_t n[3];
    lt_vq16_t p[3], g, eps = lt_vq16_set1(lt_q16_from_double_sat(ss->o.eps));
    lt_vi32_t idx;
    lt_vql_t dn;
    lt_phase_t prev = LT_PHASE_ENTER(SHADE);
    int i, a;
    hm = (lt_mask16_t)(k & ~lt_vi32_cmpeq(hit->id, lt_vi32_set1(-1)));
    /* hit point, the triangle's normal turned toward the eye, the origin lifted by eps */
    p[0] = lt_vq16_add_sat(r->ox, lt_vq16_mul_q30_sat(r->tmax, r->dx));
    p[1] = lt_vq16_add_sat(r->oy, lt_vq16_mul_q30_sat(r->tmax, r->dy));
    p[2] = lt_vq16_add_sat(r->oz, lt_vq16_mul_q30_sat(r->tmax, r->dz));
    idx = lt_vi32_add_wrap(lt_vi32_add_wrap(hit->id, hit->id), hit->id);
    for (a = 0; a < 3; a++) {
        n[a] = lt_vq30_gather_m(lt_vq30_set1(0), hm, ss->tnq + a, idx);
    }
    dn = lt_vql_add_wrap(
        lt_vql_add_wrap(lt_vql_mul(lt_vi32_from_q30(n[0]), lt_vi32_from_q30(r->dx)),
                        lt_vql_mul(lt_vi32_from_q30(n[1]), lt_vi32_from_q30(r->dy))),
        lt_vql_mul(lt_vi32_from_q30(n[2]), lt_vi32_from_q30(r->dz)));
    {
        lt_mask16_t back = lt_vql_cmpgt_m(hm, dn, lt_vql_set1(0));
        for (a = 0; a < 3; a++) {
            n[a] = as30(lt_vq16_neg_sat_m(as16(n[a]), back, as16(n[a])));
            p[a] = lt_vq16_add_sat(p[a], lt_vq16_mul_q30_sat(eps, n[a]));
        }
    }
    lm = lt_frusta_direct16_q16(p, n, ss->mq, ss->nlq, hm, &g);
    LT_COST(VSTORE, 9);
    for (i = 0; i < LT_LANES; i++) {
        size_t q = pix(ss, tx, ty, i);
        if (q == (size_t)-1)
            continue;
        ss->id[q] = hit->id.l[i];
        ss->valid[q] = (uint8_t)(((unsigned)hm >> i) & 1u);
        ss->lit[q] = (uint8_t)(((unsigned)lm >> i) & 1u);
        ss->zq[q] = r->tmax.l[i];
        ss->gq[q] = (((unsigned)lm >> i) & 1u) ? g.l[i] : 0;
        for (a = 0; a < 3; a++) {
            ss->oq[a][q] = p[a].l[i];
            ss->nq[a][q] = n[a].l[i];
        }
    }
    LT_PHASE_LEAVE(prev);
}

static void shade_tile_f32(lt_softshadow_t *ss, uint32_t tx, uint32_t ty, const lt_ray16_f32_t *r,
                           const lt_hit16_t *hit, lt_mask16_t k)
{
    lt_mask16_t hm, lm, back;
    lt_vf32_t n[3], p[3], g, dn, eps = lt_vf32_set1((float)ss->o.eps);
    lt_vi32_t idx;
    lt_phase_t prev = LT_PHASE_ENTER(SHADE);
    int i, a;
    hm = (lt_mask16_t)(k & ~lt_vi32_cmpeq(hit->id, lt_vi32_set1(-1)));
    p[0] = lt_vf32_add(r->ox, lt_vf32_mul(r->tmax, r->dx));
    p[1] = lt_vf32_add(r->oy, lt_vf32_mul(r->tmax, r->dy));
    p[2] = lt_vf32_add(r->oz, lt_vf32_mul(r->tmax, r->dz));
    idx = lt_vi32_add_wrap(lt_vi32_add_wrap(hit->id, hit->id), hit->id);
    for (a = 0; a < 3; a++)
        n[a] = lt_vf32_gather_m(lt_vf32_set1(0.0f), hm, ss->tnf + a, idx);
    dn = lt_vf32_add(lt_vf32_add(lt_vf32_mul(n[0], r->dx), lt_vf32_mul(n[1], r->dy)),
                     lt_vf32_mul(n[2], r->dz));
    back = lt_vf32_cmpgt_m(hm, dn, lt_vf32_set1(0.0f));
    for (a = 0; a < 3; a++) {
        n[a] = lt_vf32_neg_m(n[a], back, n[a]);
        p[a] = lt_vf32_add(p[a], lt_vf32_mul(eps, n[a]));
    }
    lm = lt_frusta_direct16_f32(p, n, ss->mf, ss->nlf, hm, &g);
    LT_COST(VSTORE, 9);
    for (i = 0; i < LT_LANES; i++) {
        size_t q = pix(ss, tx, ty, i);
        if (q == (size_t)-1)
            continue;
        ss->id[q] = hit->id.l[i];
        ss->valid[q] = (uint8_t)(((unsigned)hm >> i) & 1u);
        ss->lit[q] = (uint8_t)(((unsigned)lm >> i) & 1u);
        ss->zf[q] = r->tmax.l[i];
        ss->gf[q] = (((unsigned)lm >> i) & 1u) ? g.l[i] : 0.0f;
        for (a = 0; a < 3; a++) {
            ss->of[a][q] = p[a].l[i];
            ss->nf[a][q] = n[a].l[i];
        }
    }
    LT_PHASE_LEAVE(prev);
}

/* Keep one primary method's answer per pixel (id and t bits) for the P-Packet / P-Frusta check;
 * host bookkeeping, not charged. */
static void keep_prim(lt_softshadow_t *ss, int which, uint32_t tx, uint32_t ty,
                      const lt_hit16_t *hit, const void *tmax)
{
    int i;
    for (i = 0; i < LT_LANES; i++) {
        size_t q = pix(ss, tx, ty, i);
        if (q == (size_t)-1)
            continue;
        ss->pid[which][q] = hit->id.l[i];
        memcpy(&ss->pt[which][q], (const char *)tmax + 4 * (size_t)i, 4);
    }
}

/* P-Packet: the tile's 16 camera rays (the linear camera shared with the frusta) as one packet,
 * closest hit through the deep tree, then shading. */
static void primary_q16(lt_softshadow_t *ss, uint32_t tx, uint32_t ty)
{
    static lt_ray16_q16_t r;
    lt_hit16_t hit;
    lt_mask16_t k = 0;
    lt_phase_t prev = LT_PHASE_ENTER(SETUP);
    (void)lt_frusta_prays16_q16(ss->vtq, tx, ty, &r, &k);
    LT_EVENT(RAYS, lt__popcount32(k));
    LT_PHASE_LEAVE(prev);
    (void)lt_frusta_packet_trace16_q16(&ss->deep, ss->s->tq, ss->o.pflags, ss->vtq->o, &r, k,
                                       &hit);
    ss->cnt.primary_rays += lt__popcount32(k);
    keep_prim(ss, 0, tx, ty, &hit, r.tmax.l);
    shade_tile_q16(ss, tx, ty, &r, &hit, k);
}

static void primary_f32(lt_softshadow_t *ss, uint32_t tx, uint32_t ty)
{
    static lt_ray16_f32_t r;
    lt_hit16_t hit;
    lt_mask16_t k = 0;
    lt_phase_t prev = LT_PHASE_ENTER(SETUP);
    (void)lt_frusta_prays16_f32(ss->vtf, tx, ty, &r, &k);
    LT_EVENT(RAYS, lt__popcount32(k));
    LT_PHASE_LEAVE(prev);
    (void)lt_frusta_packet_trace16_f32(&ss->deep, ss->s->tf, ss->o.pflags, ss->vtf->o, &r, k,
                                       &hit);
    ss->cnt.primary_rays += lt__popcount32(k);
    keep_prim(ss, 0, tx, ty, &hit, r.tmax.l);
    shade_tile_f32(ss, tx, ty, &r, &hit, k);
}

static void primary_counts(lt_softshadow_t *ss, int which)
{
    size_t i;
    ss->cnt.pixels = ss->n;
    ss->cnt.hits = ss->cnt.lit = 0;
    for (i = 0; i < ss->n; i++) {
        ss->cnt.hits += ss->valid[i];
        ss->cnt.lit += ss->lit[i];
    }
    ss->cnt.shadow_rays = 16u * ss->cnt.lit;
    ss->have_prim[which] = 1;
    if (ss->have_prim[0] && ss->have_prim[1]) {
        ss->cnt.prim_mismatch = 0;
        for (i = 0; i < ss->n; i++)
            ss->cnt.prim_mismatch += ss->pid[0][i] != ss->pid[1][i] || ss->pt[0][i] != ss->pt[1][i];
    }
}

void lt_ss_primary(lt_softshadow_t *ss)
{
    uint32_t tx, ty;
    ss->cnt.primary_rays = 0;
    for (ty = 0; ty < ss->h; ty += 4)
        for (tx = 0; tx < ss->w; tx += 4) {
            if (ss->o.path == LT_PATH_Q16)
                primary_q16(ss, tx, ty);
            else
                primary_f32(ss, tx, ty);
        }
    primary_counts(ss, 0);
}

/* P-Frusta: 16 frusta (the 4x4 tiles of a 16x16 block) through the shallow tree, then each tile
 * shaded from its frustum's hits (its rays regenerated from ray 0 and the deltas: 3 broadcasts
 * and 3 adds, charged to SHADE). */
void lt_ss_primary_frusta(lt_softshadow_t *ss)
{
    static lt_frusta_prim16_q16_t Pq;
    static lt_frusta_prim16_f32_t Pf;
    uint32_t bx, by, f;
    ss->cnt.primary_rays = 0;
    for (by = 0; by < ss->h; by += 16)
        for (bx = 0; bx < ss->w; bx += 16) {
            lt_mask16_t act;
            if (ss->o.path == LT_PATH_Q16) {
                (void)lt_frusta_psetup16_q16(ss->vtq, bx, by, &Pq);
                (void)lt_frusta_trace16_q16(&ss->shal, ss->s->tq, ss->vtq, &Pq);
                act = Pq.active;
            } else {
                (void)lt_frusta_psetup16_f32(ss->vtf, bx, by, &Pf);
                (void)lt_frusta_trace16_f32(&ss->shal, ss->s->tf, ss->vtf, &Pf);
                act = Pf.active;
            }
            for (f = 0; f < LT_LANES; f++) {
                uint32_t tx = bx + 4u * (f & 3u), ty = by + 4u * (f >> 2);
                lt_hit16_t hit;
                if (((unsigned)act >> f & 1u) == 0)
                    continue;
                if (ss->o.path == LT_PATH_Q16) {
                    static lt_ray16_q16_t r;
                    lt_vq16_t d[3];
                    lt_phase_t prev = LT_PHASE_ENTER(SHADE);
                    const lt_vq30_t *g[3];
                    int a;
                    g[0] = &ss->vtq->gx, g[1] = &ss->vtq->gy, g[2] = &ss->vtq->gz;
                    for (a = 0; a < 3; a++) {
                        const lt_vq30_t *c = a == 0 ? &Pq.cx : (a == 1 ? &Pq.cy : &Pq.cz);
                        d[a] = lt_vq16_add_wrap(lt_vq16_set1(c->l[f]), as16(*g[a]));
                    }
                    r.ox = lt_vq16_set1(ss->vtq->o[0]);
                    r.oy = lt_vq16_set1(ss->vtq->o[1]);
                    r.oz = lt_vq16_set1(ss->vtq->o[2]);
                    r.dx = as30(d[0]), r.dy = as30(d[1]), r.dz = as30(d[2]);
                    r.tmax = Pq.t[f];
                    hit.id = Pq.id[f];
                    LT_PHASE_LEAVE(prev);
                    keep_prim(ss, 1, tx, ty, &hit, r.tmax.l);
                    shade_tile_q16(ss, tx, ty, &r, &hit, Pq.live[f]);
                    ss->cnt.primary_rays += lt__popcount32(Pq.live[f]);
                } else {
                    static lt_ray16_f32_t r;
                    lt_phase_t prev = LT_PHASE_ENTER(SHADE);
                    r.ox = lt_vf32_set1(ss->vtf->o[0]);
                    r.oy = lt_vf32_set1(ss->vtf->o[1]);
                    r.oz = lt_vf32_set1(ss->vtf->o[2]);
                    r.dx = lt_vf32_add(lt_vf32_set1(Pf.cx.l[f]), ss->vtf->gx);
                    r.dy = lt_vf32_add(lt_vf32_set1(Pf.cy.l[f]), ss->vtf->gy);
                    r.dz = lt_vf32_add(lt_vf32_set1(Pf.cz.l[f]), ss->vtf->gz);
                    r.tmax = Pf.t[f];
                    hit.id = Pf.id[f];
                    LT_PHASE_LEAVE(prev);
                    keep_prim(ss, 1, tx, ty, &hit, r.tmax.l);
                    shade_tile_f32(ss, tx, ty, &r, &hit, Pf.live[f]);
                    ss->cnt.primary_rays += lt__popcount32(Pf.live[f]);
                }
            }
            /* tiles of the block with no frustum (off the image) have no pixels to shade */
        }
    primary_counts(ss, 1);
}

uint32_t lt_ss_primary_hash(const lt_softshadow_t *ss)
{
    uint32_t h = 2166136261u;
    size_t q;
    for (q = 0; q < ss->n; q++) {
        uint32_t v[9];
        unsigned char b[36];
        int j, a;
        v[0] = (uint32_t)ss->id[q];
        v[1] = ss->valid[q] | (uint32_t)ss->lit[q] << 1;
        if (ss->o.path == LT_PATH_Q16) {
            v[2] = (uint32_t)ss->zq[q];
            v[3] = (uint32_t)ss->gq[q];
            for (a = 0; a < 3; a++) {
                v[4 + a] = (uint32_t)ss->oq[a][q];
            }
            v[7] = (uint32_t)ss->nq[0][q] ^ ((uint32_t)ss->nq[1][q] << 1) ^
                   ((uint32_t)ss->nq[2][q] << 2);
        } else {
            memcpy(&v[2], &ss->zf[q], 4);
            memcpy(&v[3], &ss->gf[q], 4);
            for (a = 0; a < 3; a++)
                memcpy(&v[4 + a], &ss->of[a][q], 4);
            memcpy(&v[7], &ss->nf[0][q], 4);
        }
        v[8] = (uint32_t)q;
        memcpy(b, v, 36);
        for (j = 0; j < 36; j++) {
            h ^= b[j];
            h *= 16777619u;
        }
    }
    return h;
}

/* Pixel q's primary hit differs between P-Packet and P-Frusta (both ran): its two shadow results
 * start from different points and are not compared. */
static int prim_differs(const lt_softshadow_t *ss, size_t q)
{
    return ss->have_prim[0] && ss->have_prim[1] &&
           (ss->pid[0][q] != ss->pid[1][q] || ss->pt[0][q] != ss->pt[1][q]);
}

static void count_occ(lt_softshadow_t *ss, int which)
{
    size_t i;
    ss->cnt.occluded = ss->cnt.partial = 0;
    for (i = 0; i < ss->n; i++) {
        unsigned c = lt__popcount32(ss->occ[which][i]);
        ss->cnt.occluded += c;
        ss->cnt.partial += ss->lit[i] && c != 0 && c != 16;
    }
    ss->have[which] = 1;
    ss->last = which;
    if (ss->have[0] && ss->have[1]) {
        ss->cnt.mismatch = ss->cnt.shadow_skipped = 0;
        for (i = 0; i < ss->n; i++) {
            if (prim_differs(ss, i))
                ss->cnt.shadow_skipped++;
            else
                ss->cnt.mismatch += ss->occ[0][i] != ss->occ[1][i];
        }
    }
}

void lt_ss_shadows_frusta(lt_softshadow_t *ss)
{
    static lt_frusta16_q16_t Fq;
    static lt_frusta16_f32_t Ff;
    uint32_t tx, ty;
    for (ty = 0; ty < ss->h; ty += 4)
        for (tx = 0; tx < ss->w; tx += 4) {
            lt_mask16_t k = 0;
            int i;
            lt_phase_t prev = LT_PHASE_ENTER(SETUP);
            /* the tile's origins: three vector loads in a tile-major layout */
            LT_COST(VLOAD, 4);
            for (i = 0; i < LT_LANES; i++) {
                size_t q = pix(ss, tx, ty, i);
                int a = q != (size_t)-1 && ss->lit[q];
                if (a)
                    k = (lt_mask16_t)(k | (1u << i));
                if (ss->o.path == LT_PATH_Q16) {
                    Fq.ox.l[i] = a ? ss->oq[0][q] : 0;
                    Fq.oy.l[i] = a ? ss->oq[1][q] : 0;
                    Fq.oz.l[i] = a ? ss->oq[2][q] : 0;
                } else {
                    Ff.ox.l[i] = a ? ss->of[0][q] : 0.0f;
                    Ff.oy.l[i] = a ? ss->of[1][q] : 0.0f;
                    Ff.oz.l[i] = a ? ss->of[2][q] : 0.0f;
                }
            }
            LT_PHASE_LEAVE(prev);
            if (ss->o.path == LT_PATH_Q16) {
                (void)lt_frusta_setup16_q16(ss->tbq, k, &Fq);
                (void)lt_frusta_occluded16_q16(&ss->shal, ss->s->tq, ss->tbq, &Fq);
            } else {
                (void)lt_frusta_setup16_f32(ss->tbf, k, &Ff);
                (void)lt_frusta_occluded16_f32(&ss->shal, ss->s->tf, ss->tbf, &Ff);
            }
            LT_COST(VSTORE, 1);
            for (i = 0; i < LT_LANES; i++) {
                size_t q = pix(ss, tx, ty, i);
                if (q != (size_t)-1)
                    ss->occ[0][q] = ss->o.path == LT_PATH_Q16 ? Fq.occl[i] : Ff.occl[i];
            }
        }
    count_occ(ss, 0);
}

/* One pixel's 16 samples of set `set` as a packet, any hit; returns the occluded mask. */
static uint16_t packet1(lt_softshadow_t *ss, size_t q, unsigned set)
{
    lt_mask16_t pk = 0, occ = 0;
    if (ss->o.path == LT_PATH_Q16) {
        static lt_ray16_q16_t r;
        lt_q16_t o[3];
        o[0] = ss->oq[0][q], o[1] = ss->oq[1][q], o[2] = ss->oq[2][q];
        lt_phase_t prev = LT_PHASE_ENTER(SETUP);
        (void)lt_frusta_rays16_q16(ss->tbq, o, set, &r, &pk);
        LT_PHASE_LEAVE(prev);
        (void)lt_frusta_packet_occluded16_q16(&ss->deep, ss->s->tq, ss->o.flags, o, &r, pk, &occ);
    } else {
        static lt_ray16_f32_t r;
        float o[3];
        o[0] = ss->of[0][q], o[1] = ss->of[1][q], o[2] = ss->of[2][q];
        lt_phase_t prev = LT_PHASE_ENTER(SETUP);
        (void)lt_frusta_rays16_f32(ss->tbf, o, set, &r, &pk);
        LT_PHASE_LEAVE(prev);
        (void)lt_frusta_packet_occluded16_f32(&ss->deep, ss->s->tf, ss->o.flags, o, &r, pk, &occ);
    }
    return occ;
}

void lt_ss_shadows_packet(lt_softshadow_t *ss)
{
    uint32_t x, y;
    for (y = 0; y < ss->h; y++)
        for (x = 0; x < ss->w; x++) {
            size_t q = (size_t)y * ss->w + x;
            ss->occ[1][q] = ss->lit[q] ? packet1(ss, q, (x & 3u) + 4u * (y & 3u)) : 0;
        }
    count_occ(ss, 1);
}

void lt_ss_shade(lt_softshadow_t *ss, int which)
{
    uint32_t tx, ty;
    for (ty = 0; ty < ss->h; ty += 4)
        for (tx = 0; tx < ss->w; tx += 4) {
            lt_phase_t prev = LT_PHASE_ENTER(SHADE);
            int i;
            /* E = G x (16 - occluded) / 16: a popcount per lane, a shift and one multiply */
            LT_COST(VLOAD, 2);
            LT_COST(VALU, 3);
            LT_COST(VSTORE, 1);
            if (ss->o.path == LT_PATH_Q16) {
                lt_vq16_t g, v, e;
                for (i = 0; i < LT_LANES; i++) {
                    size_t q = pix(ss, tx, ty, i);
                    g.l[i] = q != (size_t)-1 ? ss->gq[q] : 0;
                    v.l[i] = q != (size_t)-1
                                 ? (lt_q16_t)((16u - lt__popcount32(ss->occ[which][q])) << 12)
                                 : 0;
                }
                e = lt_vq16_mul_sat(g, v);
                for (i = 0; i < LT_LANES; i++) {
                    size_t q = pix(ss, tx, ty, i);
                    if (q != (size_t)-1) {
                        ss->eq[q] = e.l[i];
                        ss->vq[q] = v.l[i];
                    }
                }
            } else {
                lt_vf32_t g, v, e;
                for (i = 0; i < LT_LANES; i++) {
                    size_t q = pix(ss, tx, ty, i);
                    g.l[i] = q != (size_t)-1 ? ss->gf[q] : 0.0f;
                    v.l[i] = q != (size_t)-1
                                 ? (float)(16u - lt__popcount32(ss->occ[which][q])) * 0.0625f
                                 : 0.0f;
                }
                e = lt_vf32_mul(g, v);
                for (i = 0; i < LT_LANES; i++) {
                    size_t q = pix(ss, tx, ty, i);
                    if (q != (size_t)-1) {
                        ss->ef[q] = e.l[i];
                        ss->vf[q] = v.l[i];
                    }
                }
            }
            LT_PHASE_LEAVE(prev);
        }
}

static void filter_into(lt_softshadow_t *ss, int ref)
{
    uint32_t x, y;
    int vis = ss->o.filter_vis;
    if (ss->o.path == LT_PATH_Q16) {
        lt_frusta_filter_q16_t par;
        const lt_q16_t *in = vis ? (ref ? ss->vrq : ss->vq) : (ref ? ss->erq : ss->eq);
        lt_q16_t *out = ref ? ss->efrq : ss->efq;
        par.depth_rel = lt_q16_from_double_sat(ss->o.depth_rel);
        par.cos_min = lt_q30_from_double_sat(ss->o.cos_min);
        for (y = 0; y < ss->h; y++)
            for (x = 0; x < ss->w; x += 16) {
                lt_frusta_filter16_q16(in, ss->zq, ss->nq[0], ss->nq[1], ss->nq[2], ss->valid,
                                       ss->w, ss->h, x, y, &par, out);
                if (vis) {
                    /* E = G x filtered V, one multiply per 16 pixels */
                    lt_phase_t prev = LT_PHASE_ENTER(SHADE);
                    lt_vq16_t g, v;
                    int i;
                    LT_COST(VLOAD, 2);
                    LT_COST(VSTORE, 1);
                    for (i = 0; i < LT_LANES; i++) {
                        size_t q = (size_t)y * ss->w + x + (size_t)i;
                        g.l[i] = x + (uint32_t)i < ss->w ? ss->gq[q] : 0;
                        v.l[i] = x + (uint32_t)i < ss->w ? out[q] : 0;
                    }
                    v = lt_vq16_mul_sat(g, v);
                    for (i = 0; i < LT_LANES && x + (uint32_t)i < ss->w; i++)
                        out[(size_t)y * ss->w + x + (size_t)i] = v.l[i];
                    LT_PHASE_LEAVE(prev);
                }
            }
    } else {
        lt_frusta_filter_f32_t par;
        const float *in = vis ? (ref ? ss->vrf : ss->vf) : (ref ? ss->erf : ss->ef);
        float *out = ref ? ss->efrf : ss->eff;
        par.depth_rel = (float)ss->o.depth_rel;
        par.cos_min = (float)ss->o.cos_min;
        for (y = 0; y < ss->h; y++)
            for (x = 0; x < ss->w; x += 16) {
                lt_frusta_filter16_f32(in, ss->zf, ss->nf[0], ss->nf[1], ss->nf[2], ss->valid,
                                       ss->w, ss->h, x, y, &par, out);
                if (vis) {
                    lt_phase_t prev = LT_PHASE_ENTER(SHADE);
                    lt_vf32_t g, v;
                    int i;
                    LT_COST(VLOAD, 2);
                    LT_COST(VSTORE, 1);
                    for (i = 0; i < LT_LANES; i++) {
                        size_t q = (size_t)y * ss->w + x + (size_t)i;
                        g.l[i] = x + (uint32_t)i < ss->w ? ss->gf[q] : 0.0f;
                        v.l[i] = x + (uint32_t)i < ss->w ? out[q] : 0.0f;
                    }
                    v = lt_vf32_mul(g, v);
                    for (i = 0; i < LT_LANES && x + (uint32_t)i < ss->w; i++)
                        out[(size_t)y * ss->w + x + (size_t)i] = v.l[i];
                    LT_PHASE_LEAVE(prev);
                }
            }
    }
}

void lt_ss_filter(lt_softshadow_t *ss) { filter_into(ss, 0); }

static double gval(const lt_softshadow_t *ss, size_t q)
{
    return ss->o.path == LT_PATH_Q16 ? (double)ss->gq[q] / 65536.0 : (double)ss->gf[q];
}

void lt_ss_reference(lt_softshadow_t *ss, void (*progress)(double done))
{
    uint32_t x, y;
    for (y = 0; y < ss->h; y++) {
        for (x = 0; x < ss->w; x++) {
            size_t q = (size_t)y * ss->w + x;
            unsigned s, occ = 0;
            double e;
            if (ss->lit[q])
                for (s = 0; s < LT_FRUSTA_SETS; s++)
                    occ += lt__popcount32(packet1(ss, q, s));
            ss->vref[q] = ss->lit[q] ? 1.0 - (double)occ / 256.0 : 0.0;
            e = gval(ss, q) * ss->vref[q];
            ss->erq[q] = lt_q16_from_double_sat(e);
            ss->erf[q] = (float)e;
            ss->vrq[q] = lt_q16_from_double_sat(ss->vref[q]);
            ss->vrf[q] = (float)ss->vref[q];
        }
        if (progress != NULL && (y & 15u) == 15u)
            progress((double)(y + 1) / (double)ss->h);
    }
    filter_into(ss, 1);
}

void lt_ss_counts(const lt_softshadow_t *ss, lt_ss_counts_t *c) { *c = ss->cnt; }

static double eval(const lt_softshadow_t *ss, size_t q, int which)
{
    if (ss->o.path == LT_PATH_Q16) {
        const lt_q16_t *a = which == 0 ? ss->efq : (which == 1 ? ss->eq : (which == 2 ? ss->erq
                                                                                      : ss->efrq));
        return (double)a[q] / 65536.0;
    } else {
        const float *a = which == 0 ? ss->eff : (which == 1 ? ss->ef : (which == 2 ? ss->erf
                                                                                   : ss->efrf));
        return (double)a[q];
    }
}

static double psnr(double se, uint64_t n)
{
    return se > 0.0 && n > 0 ? 10.0 * log10((double)n / se) : 99.0;
}

void lt_ss_quality(const lt_softshadow_t *ss, double tol, lt_ss_quality_t *qq)
{
    size_t q;
    double sf = 0.0, sr = 0.0, sfr = 0.0, sff = 0.0;
    uint64_t nh = 0;
    memset(qq, 0, sizeof *qq);
    qq->tol = tol;
    for (q = 0; q < ss->n; q++) {
        double ef, er, eraw, efr;
        if (!ss->valid[q])
            continue;
        ef = eval(ss, q, 0);
        eraw = eval(ss, q, 1);
        er = eval(ss, q, 2);
        efr = eval(ss, q, 3);
        sf += (ef - er) * (ef - er);
        sr += (eraw - er) * (eraw - er);
        sfr += (efr - er) * (efr - er);
        sff += (ef - efr) * (ef - efr);
        nh++;
        if (ss->lit[q] && ss->vref[q] > 0.0 && ss->vref[q] < 1.0) {
            qq->penumbra++;
            qq->penumbra_ok += fabs(ef - er) <= tol;
            qq->penumbra_raw_ok += fabs(eraw - er) <= tol;
        }
    }
    qq->psnr_filtered = psnr(sf, nh);
    qq->psnr_raw = psnr(sr, nh);
    qq->psnr_filtered_ref = psnr(sfr, nh);
    qq->psnr_vs_filtered_ref = psnr(sff, nh);
}

int lt_ss_write_png(const lt_softshadow_t *ss, const char *path, int which, lt_diag_t *diag)
{
    uint8_t *rgb = malloc(ss->n * 3);
    size_t q;
    int rc;
    static const double albedo[3] = {0.78, 0.74, 0.68};
    if (rgb == NULL) {
        lt_diag_fail(diag, "%s: out of memory", path);
        return -1;
    }
    for (q = 0; q < ss->n; q++) {
        int c;
        double e = ss->valid[q] ? eval(ss, q, which == 0 ? 0 : (which == 1 ? 1 : 2)) : 0.0;
        for (c = 0; c < 3; c++) {
            double v = ss->valid[q] ? albedo[c] * (0.08 + 0.92 * e)
                                    : (c == 2 ? 0.25 : 0.08);
            v = pow(v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v), 1.0 / 2.2);
            rgb[q * 3 + (size_t)c] = (uint8_t)(v * 255.0 + 0.5);
        }
    }
    rc = lt_png_write(path, rgb, (int32_t)ss->w, (int32_t)ss->h, 3, 0, diag);
    free(rgb);
    return rc;
}

uint32_t lt_ss_hash(const lt_softshadow_t *ss)
{
    uint32_t h = 2166136261u;
    size_t q;
    for (q = 0; q < ss->n; q++) {
        uint32_t v[2];
        unsigned char b[8];
        int j;
        v[0] = ss->last >= 0 ? ss->occ[ss->last][q] : 0u;
        if (ss->o.path == LT_PATH_Q16)
            v[1] = (uint32_t)ss->efq[q];
        else
            memcpy(&v[1], &ss->eff[q], 4);
        memcpy(b, v, 8);
        for (j = 0; j < 8; j++) {
            h ^= b[j];
            h *= 16777619u;
        }
    }
    return h;
}

const uint16_t *lt_ss_occlusion(const lt_softshadow_t *ss, int which)
{
    return which >= 0 && which < 2 && ss->have[which] ? ss->occ[which] : NULL;
}

void lt_ss_origins(const lt_softshadow_t *ss, double *o, uint8_t *lit)
{
    size_t q;
    int a;
    for (q = 0; q < ss->n; q++) {
        for (a = 0; a < 3; a++)
            o[q * 3 + (size_t)a] = ss->o.path == LT_PATH_Q16 ? (double)ss->oq[a][q] / 65536.0
                                                             : (double)ss->of[a][q];
        lit[q] = ss->lit[q];
    }
}

void lt_ss_sample_point(const lt_softshadow_t *ss, unsigned set, unsigned j, double p[3])
{
    double u = (2.0 * ss->sets.u[set][j] + 1.0) / 512.0, v = (2.0 * ss->sets.v[set][j] + 1.0) / 512.0;
    int a;
    for (a = 0; a < 3; a++)
        p[a] = ss->light.c[a] + u * ss->light.eu[a] + v * ss->light.ev[a];
}

/* One triangle against one ray in double: the exact ray's plane crossing and whether it lies
 * inside the triangle's box padded by the BVH pad, within the ray's interval. */
static int genuine(const double o[3], const double d[3], double tmin, double tmax, const double v[9])
{
    double e1[3], e2[3], n[3], den, t, pad = (double)LT_BVH_PAD_Q16 / 65536.0;
    int a;
    for (a = 0; a < 3; a++) {
        e1[a] = v[3 + a] - v[a];
        e2[a] = v[6 + a] - v[a];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    den = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    if (den == 0.0)
        return 0;
    t = ((v[0] - o[0]) * n[0] + (v[1] - o[1]) * n[1] + (v[2] - o[2]) * n[2]) / den;
    if (!(t > tmin && t < tmax))
        return 0;
    for (a = 0; a < 3; a++) {
        double x = o[a] + t * d[a], lo = v[a], hi = v[a];
        int j;
        for (j = 1; j < 3; j++) {
            lo = v[3 * j + a] < lo ? v[3 * j + a] : lo;
            hi = v[3 * j + a] > hi ? v[3 * j + a] : hi;
        }
        if (x < lo - pad || x > hi + pad)
            return 0;
    }
    return 1;
}

/* Brute force for one sample: *any = some kernel hit (det > 0 under back-face culling), *gen =
 * some such hit that is genuine. */
static void brute1(const lt_softshadow_t *ss, size_t q, unsigned set, unsigned j, int *any, int *gen)
{
    uint32_t i;
    double o[3], d[3], tmin, tmax;
    int a, cull = (ss->o.flags & LT_FRUSTA_BACKFACE) != 0;
    *any = *gen = 0;
    if (ss->o.path == LT_PATH_Q16) {
        lt_ray1_q16_t r;
        lt_q16_t oq[3];
        for (a = 0; a < 3; a++)
            oq[a] = ss->oq[a][q];
        if (lt_frusta_ray1_q16(ss->tbq, oq, set, j, &r) != LT_OK)
            return;
        for (a = 0; a < 3; a++) {
            o[a] = (double)r.o[a] / 65536.0;
            d[a] = (double)r.d[a] / 1073741824.0;
        }
        tmin = (double)r.tmin / 65536.0;
        tmax = (double)r.tmax / 65536.0;
        for (i = 0; i < ss->s->ntris; i++) {
            lt_ray1_q16_t rr = r;
            const lt_tri_q16_t *t = &ss->s->tq[i];
            if (!lt_tri1_q16(&rr, t))
                continue;
            if (cull) {
                int64_t p0 = lt__round_sat32((int64_t)r.d[1] * t->e2[2] - (int64_t)r.d[2] * t->e2[1], 30);
                int64_t p1 = lt__round_sat32((int64_t)r.d[2] * t->e2[0] - (int64_t)r.d[0] * t->e2[2], 30);
                int64_t p2 = lt__round_sat32((int64_t)r.d[0] * t->e2[1] - (int64_t)r.d[1] * t->e2[0], 30);
                if (t->e1[0] * p0 + t->e1[1] * p1 + t->e1[2] * p2 <= 0)
                    continue;
            }
            {
                double v[9];
                for (a = 0; a < 3; a++) {
                    v[a] = (double)t->v0[a] / 65536.0;
                    v[3 + a] = (double)((int64_t)t->v0[a] + t->e1[a]) / 65536.0;
                    v[6 + a] = (double)((int64_t)t->v0[a] + t->e2[a]) / 65536.0;
                }
                *any = 1;
                if (genuine(o, d, tmin, tmax, v)) {
                    *gen = 1;
                    return;
                }
            }
        }
    } else {
        lt_ray1_f32_t r;
        float of[3];
        for (a = 0; a < 3; a++)
            of[a] = ss->of[a][q];
        if (lt_frusta_ray1_f32(ss->tbf, of, set, j, &r) != LT_OK)
            return;
        for (a = 0; a < 3; a++) {
            o[a] = (double)r.o[a];
            d[a] = (double)r.d[a];
        }
        tmin = (double)r.tmin;
        tmax = (double)r.tmax;
        for (i = 0; i < ss->s->ntris; i++) {
            lt_ray1_f32_t rr = r;
            const lt_tri_f32_t *t = &ss->s->tf[i];
            if (!lt_tri1_f32(&rr, t))
                continue;
            if (cull) {
                float px = r.d[1] * t->e2[2] - r.d[2] * t->e2[1];
                float py = r.d[2] * t->e2[0] - r.d[0] * t->e2[2];
                float pz = r.d[0] * t->e2[1] - r.d[1] * t->e2[0];
                if ((t->e1[0] * px + t->e1[1] * py) + t->e1[2] * pz <= 0.0f)
                    continue;
            }
            {
                double v[9];
                for (a = 0; a < 3; a++) {
                    v[a] = (double)t->v0[a];
                    v[3 + a] = (double)t->v0[a] + (double)t->e1[a];
                    v[6 + a] = (double)t->v0[a] + (double)t->e2[a];
                }
                *any = 1;
                if (genuine(o, d, tmin, tmax, v)) {
                    *gen = 1;
                    return;
                }
            }
        }
    }
}

int lt_ss_hit_genuine(const double o[3], const double d[3], const double v[9], double pad,
                      double tk)
{
    double e1[3], e2[3], n[3], den, t;
    int a, j;
    for (a = 0; a < 3; a++) {
        e1[a] = v[3 + a] - v[a];
        e2[a] = v[6 + a] - v[a];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    den = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    if (den == 0.0)
        return 0;
    t = ((v[0] - o[0]) * n[0] + (v[1] - o[1]) * n[1] + (v[2] - o[2]) * n[2]) / den;
    if (!(t > 0.0) || fabs(t - tk) > pad)
        return 0;
    for (a = 0; a < 3; a++) {
        double x = o[a] + t * d[a], lo = v[a], hi = v[a];
        for (j = 1; j < 3; j++) {
            lo = v[3 * j + a] < lo ? v[3 * j + a] : lo;
            hi = v[3 * j + a] > hi ? v[3 * j + a] : hi;
        }
        if (x < lo - pad || x > hi + pad)
            return 0;
    }
    return 1;
}

/* A primary answer (id, t) is right for pixel (x, y) when it is a kernel hit of the pixel's ray (or
 * a miss) and no kernel hit before it in (t, id) order is genuine. With ref != NULL also the
 * brute-force closest hit's id (the first smallest kernel t). */
static int prim_right(const lt_softshadow_t *ss, uint32_t x, uint32_t y, int32_t id, uint32_t tbits,
                      int32_t *ref)
{
    double o[3], d[3], v[9];
    uint32_t i;
    int a, cull = (ss->o.pflags & LT_FRUSTA_BACKFACE) != 0;
    if (ss->o.path == LT_PATH_Q16) {
        lt_ray1_q16_t r;
        lt_q16_t t, rt = 0;
        memcpy(&t, &tbits, 4);
        if (lt_frusta_pray1_q16(ss->vtq, x, y, &r) != LT_OK)
            return 0;
        for (a = 0; a < 3; a++) {
            o[a] = (double)r.o[a] / 65536.0;
            d[a] = (double)r.d[a] / 1073741824.0;
        }
        for (i = 0; i < ss->s->ntris; i++) {
            lt_ray1_q16_t rr = r;
            const lt_tri_q16_t *tr = &ss->s->tq[i];
            int hit = lt_tri1_q16(&rr, tr);
            if (hit && cull) {
                int64_t p0 = lt__round_sat32((int64_t)r.d[1] * tr->e2[2] -
                                                 (int64_t)r.d[2] * tr->e2[1], 30);
                int64_t p1 = lt__round_sat32((int64_t)r.d[2] * tr->e2[0] -
                                                 (int64_t)r.d[0] * tr->e2[2], 30);
                int64_t p2 = lt__round_sat32((int64_t)r.d[0] * tr->e2[1] -
                                                 (int64_t)r.d[1] * tr->e2[0], 30);
                hit = tr->e1[0] * p0 + tr->e1[1] * p1 + tr->e1[2] * p2 > 0;
            }
            if (hit && ref != NULL && (*ref < 0 || rr.tmax < rt)) {
                *ref = (int32_t)i;
                rt = rr.tmax;
            }
            if ((int32_t)i == id && (!hit || rr.tmax != t))
                return 0; /* the answer is not a kernel hit of this ray */
            if (!hit || (id >= 0 && (rr.tmax > t || (rr.tmax == t && (int32_t)i >= id))))
                continue;
            for (a = 0; a < 3; a++) {
                v[a] = (double)tr->v0[a] / 65536.0;
                v[3 + a] = (double)((int64_t)tr->v0[a] + tr->e1[a]) / 65536.0;
                v[6 + a] = (double)((int64_t)tr->v0[a] + tr->e2[a]) / 65536.0;
            }
            if (lt_ss_hit_genuine(o, d, v, LT_SS_GENUINE_PAD, (double)rr.tmax / 65536.0))
                return 0; /* a genuine hit before the answer was missed */
        }
    } else {
        lt_ray1_f32_t r;
        float t, rt = 0.0f;
        memcpy(&t, &tbits, 4);
        if (lt_frusta_pray1_f32(ss->vtf, x, y, &r) != LT_OK)
            return 0;
        for (a = 0; a < 3; a++) {
            o[a] = (double)r.o[a];
            d[a] = (double)r.d[a];
        }
        for (i = 0; i < ss->s->ntris; i++) {
            lt_ray1_f32_t rr = r;
            const lt_tri_f32_t *tr = &ss->s->tf[i];
            int hit = lt_tri1_f32(&rr, tr);
            if (hit && cull) {
                float px = r.d[1] * tr->e2[2] - r.d[2] * tr->e2[1];
                float py = r.d[2] * tr->e2[0] - r.d[0] * tr->e2[2];
                float pz = r.d[0] * tr->e2[1] - r.d[1] * tr->e2[0];
                hit = (tr->e1[0] * px + tr->e1[1] * py) + tr->e1[2] * pz > 0.0f;
            }
            if (hit && ref != NULL && (*ref < 0 || rr.tmax < rt)) {
                *ref = (int32_t)i;
                rt = rr.tmax;
            }
            if ((int32_t)i == id && (!hit || rr.tmax != t))
                return 0;
            if (!hit || (id >= 0 && (rr.tmax > t || (rr.tmax == t && (int32_t)i >= id))))
                continue;
            for (a = 0; a < 3; a++) {
                v[a] = (double)tr->v0[a];
                v[3 + a] = (double)tr->v0[a] + (double)tr->e1[a];
                v[6 + a] = (double)tr->v0[a] + (double)tr->e2[a];
            }
            if (lt_ss_hit_genuine(o, d, v, LT_SS_GENUINE_PAD, (double)rr.tmax))
                return 0;
        }
    }
    return 1;
}

void lt_ss_primary_audit(const lt_softshadow_t *ss, lt_ss_audit_t *au)
{
    uint32_t x, y;
    memset(au, 0, sizeof *au);
    if (!ss->have_prim[0] || !ss->have_prim[1])
        return;
    for (y = 0; y < ss->h; y++)
        for (x = 0; x < ss->w; x++) {
            size_t q = (size_t)y * ss->w + x;
            int m, ok = 1;
            if (ss->pid[0][q] == ss->pid[1][q] && ss->pt[0][q] == ss->pt[1][q])
                continue;
            au->samples++;
            for (m = 0; m < 2; m++) {
                int32_t ref = -1;
                ok &= prim_right(ss, x, y, ss->pid[m][q], ss->pt[m][q], &ref);
                au->ref[m] += ref == ss->pid[m][q];
            }
            if (ok)
                au->spurious++;
            else
                au->errors++;
        }
}

void lt_ss_audit(const lt_softshadow_t *ss, lt_ss_audit_t *au)
{
    uint32_t x, y;
    memset(au, 0, sizeof *au);
    if (!ss->have[0] || !ss->have[1])
        return;
    for (y = 0; y < ss->h; y++)
        for (x = 0; x < ss->w; x++) {
            size_t q = (size_t)y * ss->w + x;
            unsigned diff = (unsigned)(ss->occ[0][q] ^ ss->occ[1][q]), j;
            if (prim_differs(ss, q))
                continue; /* different shadow origins: not comparable */
            for (j = 0; j < 16; j++) {
                int any, gen, m, ok = 1;
                if (((diff >> j) & 1u) == 0)
                    continue;
                au->samples++;
                brute1(ss, q, (x & 3u) + 4u * (y & 3u), j, &any, &gen);
                for (m = 0; m < 2; m++) {
                    int occ = (int)(((unsigned)ss->occ[m][q] >> j) & 1u);
                    ok &= (!gen || occ) && (!occ || any);
                }
                if (ok)
                    au->spurious++;
                else
                    au->errors++;
            }
        }
}
