/* lt_softshadow.c - soft shadows from a quad light by multi-frusta tracing or 16-ray packets, after
 * primary visibility by 16-ray packets or primary frusta from one linear camera, the shading and
 * filtering of Benthin & Wald 2009 [Benthin09], section 4.5, the 256-sample reference, quality
 * metrics and brute-force audits, on the core's kernels (lt_frusta.h, lt_bvh.h). Every per-pixel
 * stage runs lane ops, so the sim build charges it to its phase (SETUP, TRAVERSE, INTERSECT, SHADE,
 * FILTER). Written once for every numeric path: the stages' lane work is the path's frusta ops
 * (ss->ops, lt_softshadow_path.inc), the rest works on the path's 4-byte buffers through the
 * registry's conversions (lt_softshadow_int.h). Host only.
 */
#include "render/lt_softshadow_int.h"
#include "lt_sblob.h"
#include "io/lt_fx_float.h"
#include "lt_meter.h"
#include "render/lt_par.h"
#include "io/lt_png.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

int lt_ss_spp_log2(uint32_t spp)
{
    return spp == 4u ? 2 : spp == 8u ? 3 : spp == 16u ? 4 : spp == 32u ? 5 : -1;
}

int lt_ss_parse_cull(const char *text, int shadow, uint32_t *flags, char *bad)
{
    uint32_t f = 0;
    const char *c;
    if (strcmp(text, "none") != 0)
        for (c = text; *c != '\0'; c++) {
            if (*c == 'b')
                f |= LT_FRUSTA_BACKFACE;
            else if (*c == 'c')
                f |= LT_FRUSTA_CORNER;
            else if (*c == 'r')
                f |= LT_FRUSTA_CR;
            else if (*c == 'l')
                f |= LT_FRUSTA_LEAFRAY;
            else if (*c == 's')
                f |= LT_FRUSTA_SPLIT;
            else if (*c == 'f' && shadow)
                f |= LT_FRUSTA_FS | LT_FRUSTA_CR;
            else if (*c == 'p' && shadow)
                f |= LT_FRUSTA_P256;
            else if (*c == 't')
                f |= LT_FRUSTA_TRIPAR;
            else {
                if (bad != NULL)
                    *bad = *c;
                return -1;
            }
        }
    *flags = f;
    return 0;
}

void lt_ss_opts_default(const lt_scene_t *s, lt_ss_opts_t *o)
{
    int e;
    memset(o, 0, sizeof *o);
    o->path = lt_paths_find("q16", LT_PATHS_FRUSTA);
    o->leaf = 8;
    o->flags = LT_SS_FLAGS_DEFAULT;
    o->pflags = LT_SS_PFLAGS_DEFAULT;
    o->qmc = LT_QMC_LP;
    o->spp = 16;
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

/* Element q of one of the path's 4-byte buffers: its bits, and its value in scaled units (a
 * position-format buffer: s15.16 raw or binary32, lt_path_to_double). */
static uint32_t bits_at(const void *buf, size_t q)
{
    uint32_t u;
    memcpy(&u, (const char *)buf + q * LT_SS_ELEM, sizeof u);
    return u;
}

static double value_at(const lt_softshadow_t *ss, const void *buf, size_t q)
{
    return lt_path_to_double(ss->p, (int64_t)(int32_t)bits_at(buf, q));
}

/* ... and a double stored there (half up and saturating, or rounded to float). */
static void store_at(const lt_softshadow_t *ss, void *buf, size_t q, double v)
{
    uint32_t u = (uint32_t)lt_path_from_double(ss->p, v);
    memcpy((char *)buf + q * LT_SS_ELEM, &u, sizeof u);
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
        st = ss->p->render->bvh_build(bvh, &d, ss->tris, ss->s->ntris, *arena, bytes);
    if (st != LT_OK) {
        lt_diag_fail(diag, "building a BVH (leaf %u) over %u triangles: %s", max_leaf,
                     ss->s->ntris, lt_status_str(st));
        return -1;
    }
    bvh->isect = ss->o.isect; /* the intersector of every walk over it, frusta included */
    return 0;
}

/* The per-pixel buffers in the path's formats (4 bytes each). */
#define SS_NBUF 12
static void **pixel_bufs(lt_softshadow_t *ss, void **b[SS_NBUF])
{
    b[0] = &ss->org[0], b[1] = &ss->org[1], b[2] = &ss->org[2], b[3] = &ss->nrm[0];
    b[4] = &ss->nrm[1], b[5] = &ss->nrm[2], b[6] = &ss->z, b[7] = &ss->g, b[8] = &ss->e;
    b[9] = &ss->ef, b[10] = &ss->er, b[11] = &ss->efr;
    return b[0];
}

void lt_ss_free(lt_softshadow_t *ss)
{
    void **b[SS_NBUF];
    int a;
    if (ss == NULL)
        return;
    (void)pixel_bufs(ss, b);
    for (a = 0; a < SS_NBUF; a++)
        free(*b[a]);
    free(ss->adeep);
    free(ss->ashal);
    free(ss->tb);
    free(ss->vt);
    free(ss->lm);
    free(ss->ln);
    free(ss->tn);
    free(ss->v);
    free(ss->vr);
    free(ss->ray1);
    free(ss->scr0);
    free(ss->id);
    free(ss->valid);
    free(ss->lit);
    free(ss->occ[0]);
    free(ss->occ[1]);
    free(ss->occ2[0]);
    free(ss->occ2[1]);
    free(ss->vref);
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

/* Every buffer of a w x h frame and of the path's data; 0 or -1. */
static int alloc_buffers(lt_softshadow_t *ss)
{
    const lt_ss_ops_t *ops = ss->ops;
    size_t n = ss->n, bq = n * LT_SS_ELEM;
    void **b[SS_NBUF];
    int a, fail = 0;
    (void)pixel_bufs(ss, b);
    for (a = 0; a < SS_NBUF; a++)
        fail |= (*b[a] = alloc64(bq)) == NULL;
    ss->v = alloc64(bq), ss->vr = alloc64(bq);
    ss->tb = alloc64(ops->table_bytes);
    ss->vt = alloc64(ops->vtable_bytes);
    ss->lm = alloc64(3 * LT_SS_ELEM), ss->ln = alloc64(3 * LT_SS_ELEM);
    ss->tn = malloc((size_t)ss->s->ntris * 3 * LT_SS_ELEM + 4);
    ss->ray1 = alloc64(ops->ray1_bytes);
    ss->scr0 = alloc64(ops->scratch_bytes);
    ss->id = malloc(n * sizeof *ss->id);
    ss->valid = alloc64(n), ss->lit = alloc64(n);
    ss->occ[0] = alloc64(n * 2), ss->occ[1] = alloc64(n * 2);
    if (ss->o.spp == 32u) {
        ss->occ2[0] = alloc64(n * 2), ss->occ2[1] = alloc64(n * 2);
        fail |= ss->occ2[0] == NULL || ss->occ2[1] == NULL;
    }
    ss->vref = calloc(n + 1, sizeof(double));
    for (a = 0; a < 2; a++) {
        ss->pid[a] = calloc(n + 1, sizeof(int32_t));
        ss->pt[a] = calloc(n + 1, sizeof(uint32_t));
        fail |= ss->pid[a] == NULL || ss->pt[a] == NULL;
    }
    fail |= ss->v == NULL || ss->vr == NULL || ss->tb == NULL || ss->vt == NULL ||
            ss->lm == NULL || ss->ln == NULL || ss->tn == NULL || ss->ray1 == NULL ||
            ss->scr0 == NULL || ss->id == NULL || ss->valid == NULL || ss->lit == NULL || ss->occ[0] == NULL ||
            ss->occ[1] == NULL || ss->vref == NULL;
    return fail ? -1 : 0;
}

/* The light's centre and its emitting normal (eu x ev, flipped toward the scene centre). */
static void light_frame(const lt_ss_light_t *l, double m[3], double nl[3])
{
    double len;
    int a;
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
    for (a = 0; a < 3; a++)
        nl[a] /= len;
}

lt_softshadow_t *lt_ss_create(const lt_scene_t *s, const lt_camera_t *cam, const lt_ss_light_t *l,
                              const lt_ss_opts_t *o, lt_diag_t *diag)
{
    lt_softshadow_t *ss = calloc(1, sizeof *ss);
    size_t n = (size_t)cam->width * cam->height, bq = n * LT_SS_ELEM;
    double m[3], nl[3];

    if (ss == NULL) {
        lt_diag_fail(diag, "out of memory");
        return NULL;
    }
    if (o->path == NULL || o->path->frusta == NULL || o->path->render == NULL) {
        lt_diag_fail(diag, "numeric path '%s' has no soft-shadow operations",
                     o->path != NULL ? o->path->name : "(none)");
        free(ss);
        return NULL;
    }
    if (lt_ss_spp_log2(o->spp) < 0) {
        lt_diag_fail(diag, "%u shadow samples per pixel: expected %s", o->spp, LT_SS_SPP_LIST);
        free(ss);
        return NULL;
    }
    if (o->leaf < 1 || o->leaf > LT_BVH_MAX_LEAF) {
        lt_diag_fail(diag, "frusta leaf size %u outside 1..%d (LT_BVH_MAX_LEAF)", o->leaf,
                     LT_BVH_MAX_LEAF);
        free(ss);
        return NULL;
    }
    ss->s = s;
    ss->p = o->path;
    ss->ops = o->path->frusta;
    ss->tris = o->path->render->tris(s);
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
    if (alloc_buffers(ss) != 0) {
        lt_diag_fail(diag, "out of memory for a %ux%u soft-shadow frame", ss->w, ss->h);
        lt_ss_free(ss);
        return NULL;
    }
    light_frame(l, m, nl);
    if (ss->ops->init(ss, m, nl, diag) != 0) {
        lt_ss_free(ss);
        return NULL;
    }
    region(ss->tris, s->ntris * ss->p->render->tri_bytes, 0);
    region(ss->tn, s->ntris * 3 * LT_SS_ELEM, 3);
    region(ss->tb, ss->ops->table_bytes, 4);
    region(ss->z, bq, 5), region(ss->nrm[0], bq, 6), region(ss->nrm[1], bq, 7);
    region(ss->nrm[2], bq, 8), region(ss->e, bq, 9), region(ss->ef, bq, 10);
    region(ss->adeep, ss->deep.bytes, 1);
    region(ss->ashal, ss->shal.bytes, 2);
    region(ss->valid, n, 11);
    region(ss->vt, ss->ops->vtable_bytes, 12);
    region(ss->scr0, ss->ops->scratch_bytes, 13);
    return ss;
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
    ss->cnt.shadow_rays = (uint64_t)ss->o.spp * ss->cnt.lit;
    ss->have_prim[which] = 1;
    if (ss->have_prim[0] && ss->have_prim[1]) {
        ss->cnt.prim_mismatch = 0;
        for (i = 0; i < ss->n; i++)
            ss->cnt.prim_mismatch += ss->pid[0][i] != ss->pid[1][i] || ss->pt[0][i] != ss->pt[1][i];
    }
}

/* ---- the stages on every core (lt_par.h) ------------------------------------------------------
 * A task is a row of tiles, of 16x16 blocks or of pixels; each writes only its own pixels, and
 * counts go per worker, summed after. Worker 0 uses ss->scr0 (at a fixed simulated address); the
 * others their own scratch. The charged stages run on one thread in the sim build. */

typedef struct ss_job {
    lt_softshadow_t *ss;
    void *scr[LT_PAR_MAX_THREADS];
    uint32_t rays[LT_PAR_MAX_THREADS];
    void (*progress)(double done);
} ss_job_t;

/* Scratch for the workers of ntasks tasks: returns how many are ready (at least 1). */
static unsigned ss_open(ss_job_t *j, lt_softshadow_t *ss, uint32_t ntasks, int counted)
{
    unsigned w = lt_par_workers(ntasks, counted), i;
    memset(j, 0, sizeof *j);
    j->ss = ss;
    j->scr[0] = ss->scr0;
    for (i = 1; i < w; i++)
        if ((j->scr[i] = alloc64(ss->ops->scratch_bytes)) == NULL)
            break;
    return i;
}

static uint32_t ss_close(ss_job_t *j)
{
    uint32_t i, rays = 0;
    for (i = 1; i < LT_PAR_MAX_THREADS; i++)
        free(j->scr[i]);
    for (i = 0; i < LT_PAR_MAX_THREADS; i++)
        rays += j->rays[i];
    return rays;
}

static void ss_primary_row(void *ctx, unsigned w, uint32_t row)
{
    ss_job_t *j = ctx;
    uint32_t tx;
    for (tx = 0; tx < j->ss->w; tx += 4)
        j->rays[w] += j->ss->ops->primary_tile(j->ss, j->scr[w], tx, 4u * row);
}

void lt_ss_primary(lt_softshadow_t *ss)
{
    ss_job_t j;
    uint32_t rows = (ss->h + 3u) / 4u;
    unsigned w = ss_open(&j, ss, rows, 1);
    (void)lt_par_run(rows, w, ss_primary_row, &j, NULL);
    ss->cnt.primary_rays = ss_close(&j);
    primary_counts(ss, 0);
}

static void ss_block_row(void *ctx, unsigned w, uint32_t row)
{
    ss_job_t *j = ctx;
    uint32_t bx;
    for (bx = 0; bx < j->ss->w; bx += 16)
        j->rays[w] += j->ss->ops->primary_block(j->ss, j->scr[w], bx, 16u * row);
}

/* P-Frusta: 16 frusta (the 4x4 tiles of a 16x16 block) through the shallow tree, then each tile
 * shaded from its frustum's hits. */
void lt_ss_primary_frusta(lt_softshadow_t *ss)
{
    ss_job_t j;
    uint32_t rows = (ss->h + 15u) / 16u;
    unsigned w = ss_open(&j, ss, rows, 1);
    (void)lt_par_run(rows, w, ss_block_row, &j, NULL);
    ss->cnt.primary_rays = ss_close(&j);
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
        v[2] = bits_at(ss->z, q);
        v[3] = bits_at(ss->g, q);
        for (a = 0; a < 3; a++)
            v[4 + a] = bits_at(ss->org[a], q);
        v[7] = ss->ops->normal_word(ss, q);
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

/* Occluded samples of pixel q in stage `which`, both passes. */
static unsigned occ_count(const lt_softshadow_t *ss, int which, size_t q)
{
    unsigned c = (unsigned)lt__popcount32(ss->occ[which][q]);
    return ss->occ2[which] != NULL ? c + (unsigned)lt__popcount32(ss->occ2[which][q]) : c;
}

static void count_occ(lt_softshadow_t *ss, int which)
{
    size_t i;
    ss->cnt.occluded = ss->cnt.partial = 0;
    for (i = 0; i < ss->n; i++) {
        unsigned c = occ_count(ss, which, i);
        ss->cnt.occluded += c;
        ss->cnt.partial += ss->lit[i] && c != 0 && c != ss->o.spp;
    }
    ss->have[which] = 1;
    ss->last = which;
    if (ss->have[0] && ss->have[1]) {
        ss->cnt.mismatch = ss->cnt.shadow_skipped = 0;
        for (i = 0; i < ss->n; i++) {
            if (prim_differs(ss, i))
                ss->cnt.shadow_skipped++;
            else
                ss->cnt.mismatch += ss->occ[0][i] != ss->occ[1][i] ||
                                    (ss->occ2[0] != NULL && ss->occ2[0][i] != ss->occ2[1][i]);
        }
    }
}

static void ss_shadows_row(void *ctx, unsigned w, uint32_t row)
{
    ss_job_t *j = ctx;
    uint32_t tx;
    for (tx = 0; tx < j->ss->w; tx += 4) {
        j->ss->ops->shadows_tile(j->ss, j->scr[w], tx, 4u * row, 0);
        if (j->ss->occ2[0] != NULL)
            j->ss->ops->shadows_tile(j->ss, j->scr[w], tx, 4u * row, 1);
    }
}

void lt_ss_shadows_frusta(lt_softshadow_t *ss)
{
    ss_job_t j;
    uint32_t rows = (ss->h + 3u) / 4u;
    unsigned w = ss_open(&j, ss, rows, 1);
    (void)lt_par_run(rows, w, ss_shadows_row, &j, NULL);
    (void)ss_close(&j);
    count_occ(ss, 0);
}

static void ss_packet_row(void *ctx, unsigned w, uint32_t y)
{
    ss_job_t *j = ctx;
    lt_softshadow_t *ss = j->ss;
    uint32_t x;
    for (x = 0; x < ss->w; x++) {
        size_t q = (size_t)y * ss->w + x;
        unsigned set = (x & 3u) + 4u * (y & 3u);
        uint16_t sm = (uint16_t)(ss->o.spp < 16u ? (1u << ss->o.spp) - 1u : 0xFFFFu);
        ss->occ[1][q] = ss->lit[q] ? ss->ops->packet(ss, j->scr[w], q, set, sm) : 0;
        if (ss->occ2[1] != NULL)
            ss->occ2[1][q] = ss->lit[q] ? ss->ops->packet(ss, j->scr[w], q, set ^ 8u, sm) : 0;
    }
}

void lt_ss_shadows_packet(lt_softshadow_t *ss)
{
    ss_job_t j;
    unsigned w = ss_open(&j, ss, ss->h, 1);
    (void)lt_par_run(ss->h, w, ss_packet_row, &j, NULL);
    (void)ss_close(&j);
    count_occ(ss, 1);
}

void lt_ss_shade(lt_softshadow_t *ss, int which)
{
    uint32_t tx, ty;
    for (ty = 0; ty < ss->h; ty += 4)
        for (tx = 0; tx < ss->w; tx += 4) {
            lt_phase_t prev = LT_PHASE_ENTER(SHADE);
            /* E = G x (16 - occluded) / 16: a popcount per lane, a shift and one multiply */
            LT_COST(VLOAD, 2);
            LT_COST(VALU, 3);
            LT_COST(VSTORE, 1);
            ss->ops->shade_tile(ss, tx, ty, which);
            LT_PHASE_LEAVE(prev);
        }
}

void lt_ss_filter(lt_softshadow_t *ss) { ss->ops->filter(ss, 0); }

static void ss_reference_row(void *ctx, unsigned w, uint32_t y)
{
    ss_job_t *j = ctx;
    lt_softshadow_t *ss = j->ss;
    uint32_t x;
    for (x = 0; x < ss->w; x++) {
        size_t q = (size_t)y * ss->w + x;
        unsigned s, occ = 0;
        if (ss->lit[q])
            for (s = 0; s < LT_FRUSTA_SETS; s++)
                occ += lt__popcount32(ss->ops->packet(ss, j->scr[w], q, s, 0xFFFFu));
        ss->vref[q] = ss->lit[q] ? 1.0 - (double)occ / 256.0 : 0.0;
        store_at(ss, ss->er, q, value_at(ss, ss->g, q) * ss->vref[q]);
        store_at(ss, ss->vr, q, ss->vref[q]);
    }
}

void lt_ss_reference(lt_softshadow_t *ss, void (*progress)(double done))
{
    ss_job_t j;
    unsigned w = ss_open(&j, ss, ss->h, 1);
    (void)lt_par_run(ss->h, w, ss_reference_row, &j, progress);
    (void)ss_close(&j);
    ss->ops->filter(ss, 1);
}

void lt_ss_counts(const lt_softshadow_t *ss, lt_ss_counts_t *c) { *c = ss->cnt; }

/* E per pixel: filtered (which 0), unfiltered (1), reference (2), filtered reference (3). */
static double eval(const lt_softshadow_t *ss, size_t q, int which)
{
    const void *a = which == 0 ? ss->ef : (which == 1 ? ss->e : (which == 2 ? ss->er : ss->efr));
    return value_at(ss, a, q);
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

/* Penumbra pixels (lit, some but not all samples occluded) of the block at (bx, by). */
static uint32_t block_penumbra(const lt_softshadow_t *ss, uint32_t bx, uint32_t by)
{
    uint32_t x, y, n = 0;
    for (y = by; y < by + LT_FBLOB_BLOCK; y++)
        for (x = bx; x < bx + LT_FBLOB_BLOCK; x++) {
            size_t q = (size_t)y * ss->w + x;
            unsigned c = lt__popcount32(ss->occ[LT_SS_FRUSTA][q]);
            n += ss->lit[q] && c > 0u && c < ss->o.spp;
        }
    return n;
}

int lt_ss_pack_block(const lt_softshadow_t *ss, uint32_t bx, uint32_t by, uint8_t **blob,
                     size_t *bytes, lt_diag_t *diag)
{
    const lt_frusta_table_q16_t *tb = ss->tb;
    const lt_tri_q16_t *tq = ss->tris;
    static const double dir13[13][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, -1, 0},
                                        {1, 0, 1}, {1, 0, -1}, {0, 1, 1}, {0, 1, -1}, {1, 1, 1},
                                        {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
    double dir[22][3], lo[22], hi[22], cen[3] = {0, 0, 0}, m[3], u[3], w[3], ln;
    lt_q16_t org[768];
    uint32_t h[64], th[16], x, y, t, i, nlit = 0, nk = 0, *keep = NULL;
    lt_tri_q16_t *ct = NULL;
    lt_bvh_desc_t d;
    lt_bvh_t bvh;
    void *arena = NULL;
    size_t ab = 0;
    int a, k, rc = -1;
    *blob = NULL;
    *bytes = 0;
    if (strcmp(ss->p->name, "q16") != 0 || !ss->have[LT_SS_FRUSTA] || ss->o.spp > 16u) {
        lt_diag_fail(diag, "a frusta blob needs the s15.16 path (--num q16), at most 16 samples "
                           "per pixel and the frusta shadow stage");
        return -1;
    }
    if (ss->w < LT_FBLOB_BLOCK || ss->h < LT_FBLOB_BLOCK) {
        lt_diag_fail(diag, "the image (%ux%u) is smaller than a %u x %u block", ss->w, ss->h,
                     LT_FBLOB_BLOCK, LT_FBLOB_BLOCK);
        return -1;
    }
    if (bx == UINT32_MAX) {
        uint32_t best = 0;
        bx = by = 0;
        for (y = 0; y + LT_FBLOB_BLOCK <= ss->h; y += LT_FBLOB_BLOCK)
            for (x = 0; x + LT_FBLOB_BLOCK <= ss->w; x += LT_FBLOB_BLOCK) {
                uint32_t n = block_penumbra(ss, x, y);
                if (n > best)
                    best = n, bx = x, by = y;
            }
    }
    if (bx % 4u || by % 4u || bx + LT_FBLOB_BLOCK > ss->w || by + LT_FBLOB_BLOCK > ss->h) {
        lt_diag_fail(diag, "block %u,%u: it must start on a multiple of 4 and lie inside the "
                           "%ux%u image", bx, by, ss->w, ss->h);
        return -1;
    }
    memset(h, 0, sizeof h);
    for (t = 0; t < 16u; t++) {
        uint8_t lit[16];
        uint16_t occl[16];
        for (i = 0; i < 16u; i++) {
            uint32_t px = 4u * (t % 4u) + i % 4u, py = 4u * (t / 4u) + i / 4u, p = py * 16u + px;
            size_t q = (size_t)(by + py) * ss->w + bx + px;
            lit[i] = ss->lit[q] ? 1u : 0u;
            occl[i] = lit[i] ? ss->occ[LT_SS_FRUSTA][q] : 0u;
            for (a = 0; a < 3; a++)
                org[3u * p + (unsigned)a] = lit[i] ? (lt_q16_t)bits_at(ss->org[a], q) : 0;
            if (lit[i]) {
                h[LT_FB_LIT + p / 32u] |= 1u << (p % 32u);
                nlit++;
                for (a = 0; a < 3; a++)
                    cen[a] += org[3u * p + (unsigned)a] / 65536.0;
            }
        }
        th[t] = lt_fblob_tile_hash(lit, occl);
    }
    if (nlit == 0) {
        lt_diag_fail(diag, "block %u,%u has no lit pixel: nothing to trace", bx, by);
        return -1;
    }
    /* the crop: 13 fixed directions and 9 around the axis from the origins to the light */
    for (a = 0; a < 3; a++) {
        cen[a] /= nlit;
        m[a] = (tb->c[a] + 0.5 * (tb->eu[a] + tb->ev[a])) / 65536.0 - cen[a];
    }
    ln = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    for (a = 0; a < 3; a++)
        m[a] = ln > 0 ? m[a] / ln : (a == 1);
    u[0] = fabs(m[0]) < 0.9 ? 0.0 : -m[1];
    u[1] = fabs(m[0]) < 0.9 ? -m[2] : m[0];
    u[2] = fabs(m[0]) < 0.9 ? m[1] : 0.0;
    ln = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (a = 0; a < 3; a++)
        u[a] /= ln;
    w[0] = m[1] * u[2] - m[2] * u[1];
    w[1] = m[2] * u[0] - m[0] * u[2];
    w[2] = m[0] * u[1] - m[1] * u[0];
    for (k = 0; k < 13; k++)
        memcpy(dir[k], dir13[k], sizeof dir[k]);
    for (k = 0; k < 8; k++) {
        double c = cos(k * 3.14159265358979323846 / 8.0), sn = sin(k * 3.14159265358979323846 / 8.0);
        for (a = 0; a < 3; a++)
            dir[13 + k][a] = c * u[a] + sn * w[a];
    }
    memcpy(dir[21], m, sizeof dir[21]);
    for (k = 0; k < 22; k++) {
        lo[k] = HUGE_VAL;
        hi[k] = -HUGE_VAL;
        for (i = 0; i < 256u + 4u; i++) {
            double pt[3], v;
            if (i < 256u) {
                if (!((h[LT_FB_LIT + i / 32u] >> (i % 32u)) & 1u))
                    continue;
                for (a = 0; a < 3; a++)
                    pt[a] = org[3u * i + (unsigned)a] / 65536.0;
            } else {
                for (a = 0; a < 3; a++)
                    pt[a] = (tb->c[a] + ((i - 256u) & 1u ? tb->eu[a] : 0) +
                             ((i - 256u) & 2u ? tb->ev[a] : 0)) / 65536.0;
            }
            v = dir[k][0] * pt[0] + dir[k][1] * pt[1] + dir[k][2] * pt[2];
            lo[k] = fmin(lo[k], v);
            hi[k] = fmax(hi[k], v);
        }
    }
    keep = malloc(ss->s->ntris * sizeof *keep);
    if (keep == NULL)
        goto oom;
    for (i = 0; i < ss->s->ntris; i++) {
        double v[3][3];
        int out = 0;
        for (a = 0; a < 3; a++) {
            v[0][a] = tq[i].v0[a] / 65536.0;
            v[1][a] = (tq[i].v0[a] + tq[i].e1[a]) / 65536.0;
            v[2][a] = (tq[i].v0[a] + tq[i].e2[a]) / 65536.0;
        }
        for (k = 0; k < 22 && !out; k++) {
            double p0 = dir[k][0] * v[0][0] + dir[k][1] * v[0][1] + dir[k][2] * v[0][2];
            double p1 = dir[k][0] * v[1][0] + dir[k][1] * v[1][1] + dir[k][2] * v[1][2];
            double p2 = dir[k][0] * v[2][0] + dir[k][1] * v[2][1] + dir[k][2] * v[2][2];
            /* a margin of 2^-8 units over rounding (the kernels' hits lie on the triangle within
               far less) */
            double margin = 1.0 / 256.0;
            out = fmin(p0, fmin(p1, p2)) > hi[k] + margin || fmax(p0, fmax(p1, p2)) < lo[k] - margin;
        }
        if (!out)
            keep[nk++] = i;
    }
    if (nk == 0) {
        /* nothing can occlude: one far-away degenerate triangle keeps the tree non-empty */
        keep[nk++] = 0;
    }
    ct = malloc(nk * sizeof *ct);
    if (ct == NULL)
        goto oom;
    for (i = 0; i < nk; i++)
        ct[i] = tq[keep[i]];
    memset(&d, 0, sizeof d);
    d.max_leaf = ss->o.leaf;
    d.min_leaf = ss->o.leaf > 1 ? ss->o.leaf / 2 : 1;
    if (lt_bvh_size(nk, &d, &ab) != LT_OK || (arena = alloc64(ab)) == NULL)
        goto oom;
    if (lt_bvh_build_q16(&bvh, &d, ct, nk, arena, ab) != LT_OK) {
        lt_diag_fail(diag, "building the crop's BVH over %u triangles failed", nk);
        goto done;
    }
    for (a = 0; a < 3; a++) {
        h[LT_FB_LIGHT + a] = (uint32_t)tb->c[a];
        h[LT_FB_LIGHT + 3 + a] = (uint32_t)tb->eu[a];
        h[LT_FB_LIGHT + 6 + a] = (uint32_t)tb->ev[a];
    }
    h[LT_FB_LFLAGS] = tb->flags;
    h[LT_FB_END_SHIFT] = tb->end_shift;
    h[LT_FB_QMC] = (uint32_t)ss->o.qmc;
    h[LT_FB_SCRAMBLE] = ss->o.scramble;
    h[LT_FB_SPP] = ss->o.spp;
    h[LT_FB_LEAF] = d.max_leaf;
    h[LT_FB_BX] = bx;
    h[LT_FB_BY] = by;
    h[LT_FB_REF] = lt_fblob_block_hash(th);
    h[LT_FB_SCENE_TRIS] = ss->s->ntris;
    *bytes = lt_fblob_size(nk, bvh.nnodes);
    *blob = malloc(*bytes);
    if (*blob == NULL)
        goto oom;
    if (lt_fblob_write(ct, &bvh, org, h, *blob, *bytes) != LT_OK) {
        lt_diag_fail(diag, "writing the frusta blob failed");
        free(*blob);
        *blob = NULL;
        goto done;
    }
    rc = 0;
    goto done;
oom:
    lt_diag_fail(diag, "out of memory for the frusta blob (%u triangles kept)", nk);
done:
    free(keep);
    free(ct);
    free(arena);
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
        if (ss->last >= 0 && ss->occ2[ss->last] != NULL)
            v[0] |= (uint32_t)ss->occ2[ss->last][q] << 16;
        v[1] = bits_at(ss->ef, q);
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
            o[q * 3 + (size_t)a] = value_at(ss, ss->org[a], q);
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
    const lt_ss_ops_t *ops = ss->ops;
    uint32_t i;
    double o[3], d[3], tmin, tmax, t, v[9];
    int cull = (ss->o.flags & LT_FRUSTA_BACKFACE) != 0;
    *any = *gen = 0;
    if (ops->shadow_ray1(ss, q, set, j, ss->ray1, o, d, &tmin, &tmax) != 0)
        return;
    for (i = 0; i < ss->s->ntris; i++) {
        if (!ops->tri1(ss, ss->ray1, i, cull, &t))
            continue;
        ops->tri_vertices(ss, i, v);
        *any = 1;
        if (genuine(o, d, tmin, tmax, v)) {
            *gen = 1;
            return;
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
 * brute-force closest hit's id (the first smallest kernel t). Distances compare as doubles: the
 * path's values convert exactly. */
static int prim_right(const lt_softshadow_t *ss, uint32_t x, uint32_t y, int32_t id, uint32_t tbits,
                      int32_t *ref)
{
    const lt_ss_ops_t *ops = ss->ops;
    double o[3], d[3], v[9], t = lt_path_to_double(ss->p, (int64_t)(int32_t)tbits), rt = 0.0;
    uint32_t i;
    int cull = (ss->o.pflags & LT_FRUSTA_BACKFACE) != 0;
    if (ops->primary_ray1(ss, x, y, ss->ray1, o, d) != 0)
        return 0;
    for (i = 0; i < ss->s->ntris; i++) {
        double ti;
        int hit = ops->tri1(ss, ss->ray1, i, cull, &ti);
        if (hit && ref != NULL && (*ref < 0 || ti < rt)) {
            *ref = (int32_t)i;
            rt = ti;
        }
        if ((int32_t)i == id && (!hit || ti != t))
            return 0; /* the answer is not a kernel hit of this ray */
        if (!hit || (id >= 0 && (ti > t || (ti == t && (int32_t)i >= id))))
            continue;
        ops->tri_vertices(ss, i, v);
        if (lt_ss_hit_genuine(o, d, v, LT_SS_GENUINE_PAD, ti))
            return 0; /* a genuine hit before the answer was missed */
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
            unsigned pass, j;
            if (prim_differs(ss, q))
                continue; /* different shadow origins: not comparable */
            for (pass = 0; pass < (ss->occ2[0] != NULL ? 2u : 1u); pass++) {
                uint16_t *const *oc = pass ? ss->occ2 : ss->occ;
                unsigned diff = (unsigned)(oc[0][q] ^ oc[1][q]);
                for (j = 0; j < 16; j++) {
                    int any, gen, m, ok = 1;
                    if (((diff >> j) & 1u) == 0)
                        continue;
                    au->samples++;
                    brute1(ss, q, ((x & 3u) + 4u * (y & 3u)) ^ (pass ? 8u : 0u), j, &any, &gen);
                    for (m = 0; m < 2; m++) {
                        int occ = (int)(((unsigned)oc[m][q] >> j) & 1u);
                        ok &= (!gen || occ) && (!occ || any);
                    }
                    if (ok)
                        au->spurious++;
                    else
                        au->errors++;
                }
            }
        }
}
