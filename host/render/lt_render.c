/* lt_render.c - frame tracing over the core's structures, reference frames, comparison.
 * Written once for every numeric path: path-typed work (builds, packets, traces, conversions)
 * goes through the path's render ops (a->ops, lt_path_ops.h). Host only; in sim builds it samples
 * the cycle model's total per packet (lt_meter.h; zeros natively).
 */
#include "render/lt_render.h"
#include "lt/lt_wt.h"
#include "lt_meter.h"
#include "render/lt_par.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Structure kinds behind the names of lt_accel_build. */
enum { ACC_CHUNKS, ACC_BVH, ACC_BVHQ, ACC_KD, ACC_GRID };

struct lt_accel {
    const lt_path_info_t *path;
    const lt_render_ops_t *ops; /* path->render */
    int kind;
    uint32_t n;
    const void *tris;        /* the scene's triangles in the path */
    void *boxes;             /* chunks: the path's boxes */
    void *arena;             /* bvh: the tree's arena (64-byte aligned) */
    lt_bvh_t bvh;
    void *qmem;              /* bvhq: quantised nodes */
    lt_bvhq_t bvhq;
    void *mem;               /* kd, grid: their arena */
    void *hdr;               /* kd, grid: the path's tree or grid header */
    void *ray;               /* one packet in the path's format, the traces' scratch */
    void *wmem;              /* bvh: the wide tree's nodes for single rays (built on first use) */
    lt_bvh8_t wide;
    const lt_bvh8_t *walk16; /* bvh: the wide tree the packets walk (lt_accel_set_walk: wide or,
                                in float32, pwide), NULL for the binary tree */
    void *pmem;              /* bvh, float32: pwide's memory */
    lt_bvh8_t pwide;         /* bvh, float32: the packets' wide tree, no merged leaves */
    size_t bytes;            /* structure memory */
    uint32_t leaf;           /* lt_accel_params_t.leaf (0: default) */
    uint32_t isect;          /* the intersector of every walk (LT_ISECT_WT unless set) */
    double *view;            /* lt_accel_set_view: view_cam's directions, or NULL */
    lt_camera_t view_cam;
};

const char *const lt_render_structures[] = {"chunks", "bvh", "bvhq", "kd", "grid", NULL};

int lt_frame_alloc(lt_frame_t *f, uint32_t w, uint32_t h, lt_diag_t *diag)
{
    size_t n = (size_t)w * h;
    memset(f, 0, sizeof *f);
    f->width = w;
    f->height = h;
    f->id = malloc(n * sizeof *f->id);
    f->t = malloc(n * sizeof *f->t);
    f->cost = calloc(n, sizeof *f->cost);
    f->steps = calloc(n, sizeof *f->steps);
    if (f->id == NULL || f->t == NULL || f->cost == NULL || f->steps == NULL) {
        lt_frame_free(f);
        lt_diag_fail(diag, "out of memory for a %ux%u frame", w, h);
        return -1;
    }
    return 0;
}

void lt_frame_free(lt_frame_t *f)
{
    free(f->id);
    free(f->t);
    free(f->cost);
    free(f->steps);
    memset(f, 0, sizeof *f);
}

/* 64-byte aligned memory (a cache line: BVH sibling pairs share one); NULL on failure. */
static void *alloc64(size_t bytes)
{
    void *p = NULL;
    if (posix_memalign(&p, 64, bytes == 0 ? 64 : bytes) != 0)
        return NULL;
    return p;
}

/* The formats of the paths with quantised BVH nodes, for messages: "s15.16". */
static const char *bvhq_formats(void)
{
    static char buf[64];
    const lt_path_info_t *p;
    size_t len = 0;
    buf[0] = '\0';
    for (p = lt_paths; p->name != NULL; p++)
        if (p->render != NULL && p->render->bvhq_build != NULL && len < sizeof buf)
            len += (size_t)snprintf(buf + len, sizeof buf - len, "%s%s", len ? ", " : "",
                                    p->format);
    return buf;
}

static lt_accel_t *build_bvh(const lt_scene_t *s, lt_accel_t *a, int quantised, lt_diag_t *diag)
{
    lt_bvh_desc_t desc;
    size_t bytes = 0;
    lt_status_t st;
    memset(&desc, 0, sizeof desc);
    desc.max_leaf = a->leaf;
    desc.min_leaf = a->leaf / 2u; /* 0 (the default, 1) for leaf 0 and 1 */
    if (quantised && a->ops->bvhq_build == NULL) {
        lt_diag_fail(diag, "structure 'bvhq' (quantised nodes) exists in %s only", bvhq_formats());
        return NULL;
    }
    st = lt_bvh_size(s->ntris, &desc, &bytes);
    if (st == LT_OK) {
        a->arena = alloc64(bytes);
        if (a->arena == NULL)
            st = LT_E_SPACE;
        else /* before the build: its writes are charged at the same simulated addresses */
            lt_meter_region(a->arena, bytes, 0x20000000u);
    }
    if (st == LT_OK)
        st = a->ops->bvh_build(&a->bvh, &desc, a->tris, s->ntris, a->arena, bytes);
    if (st != LT_OK) {
        lt_diag_fail(diag, "building the BVH over %u triangles: %s", s->ntris, lt_status_str(st));
        return NULL;
    }
    a->bytes = a->bvh.bytes;
    if (quantised) {
        size_t qb = 0;
        st = lt_bvhq_size(&a->bvh, &qb);
        if (st == LT_OK && (a->qmem = alloc64(qb)) == NULL)
            st = LT_E_SPACE;
        if (st == LT_OK) {
            lt_meter_region(a->qmem, qb, 0x30000000u);
            st = a->ops->bvhq_build(&a->bvhq, &a->bvh, a->qmem, qb);
        }
        if (st != LT_OK) {
            lt_diag_fail(diag, "quantising the BVH: %s", lt_status_str(st));
            return NULL;
        }
        /* the quantised tree keeps its nodes plus the source tree's index array */
        a->bytes = a->bvhq.bytes + (size_t)s->ntris * sizeof(uint32_t);
    }
    return a;
}

/* kd-tree or uniform grid: size query, arena, build (docs/kdtree-grid.md). */
static lt_accel_t *build_kdgrid(const lt_scene_t *s, lt_accel_t *a, lt_diag_t *diag)
{
    size_t bytes = 0;
    lt_status_t st;
    a->hdr = calloc(1, a->kind == ACC_KD ? a->ops->kd_bytes : a->ops->grid_bytes);
    if (a->hdr == NULL) {
        st = LT_E_SPACE;
    } else if (a->kind == ACC_KD) {
        lt_kd_params_t p;
        lt_kd_params_default(&p);
        if (a->leaf != 0)
            p.leaf_tris = a->leaf;
        st = lt_kd_size(s->ntris, &p, &bytes);
        if (st == LT_OK && (a->mem = alloc64(bytes)) == NULL)
            st = LT_E_SPACE;
        if (st == LT_OK)
            lt_meter_region(a->mem, bytes, 0x20000000u);
        if (st == LT_OK)
            st = a->ops->kd_build(a->hdr, a->tris, s->ntris, &p, a->mem, &bytes);
        a->bytes = bytes;
    } else {
        lt_grid_params_t p;
        lt_grid_params_default(&p);
        st = a->ops->grid_size(a->tris, s->ntris, &p, &bytes);
        if (st == LT_OK && (a->mem = alloc64(bytes)) == NULL)
            st = LT_E_SPACE;
        if (st == LT_OK)
            lt_meter_region(a->mem, bytes, 0x20000000u);
        if (st == LT_OK)
            st = a->ops->grid_build(a->hdr, a->tris, s->ntris, &p, a->mem, &bytes);
        a->bytes = bytes;
    }
    if (st != LT_OK) {
        lt_diag_fail(diag, "building the %s over %u triangles: %s",
                     a->kind == ACC_KD ? "kd-tree" : "grid", s->ntris, lt_status_str(st));
        return NULL;
    }
    return a;
}

lt_accel_t *lt_accel_build(const lt_scene_t *s, const char *structure,
                           const lt_path_info_t *path, lt_diag_t *diag)
{
    return lt_accel_build_ex(s, structure, path, NULL, diag);
}

lt_accel_t *lt_accel_build_ex(const lt_scene_t *s, const char *structure,
                              const lt_path_info_t *path, const lt_accel_params_t *prm,
                              lt_diag_t *diag)
{
    lt_accel_t *a;
    size_t nb = LT_CHUNK_COUNT(s->ntris);
    lt_status_t st;
    int kind;
    if (strcmp(structure, "chunks") == 0)
        kind = ACC_CHUNKS;
    else if (strcmp(structure, "bvh") == 0)
        kind = ACC_BVH;
    else if (strcmp(structure, "bvhq") == 0)
        kind = ACC_BVHQ;
    else if (strcmp(structure, "kd") == 0)
        kind = ACC_KD;
    else if (strcmp(structure, "grid") == 0)
        kind = ACC_GRID;
    else {
        lt_diag_fail(diag,
                     "structure '%s' is not available (available: chunks, bvh, bvhq, kd, grid)",
                     structure);
        return NULL;
    }
    if (path == NULL || path->render == NULL) {
        lt_diag_fail(diag, "numeric path '%s' has no object-space operations",
                     path != NULL ? path->name : "(none)");
        return NULL;
    }
    if (prm != NULL && prm->leaf != 0 &&
        (kind == ACC_CHUNKS || kind == ACC_GRID ||
         prm->leaf > (kind == ACC_BVHQ ? LT_BVHQ_MAX_LEAF : (kind == ACC_BVH ? LT_BVH_MAX_LEAF
                                                                             : UINT32_MAX)))) {
        lt_diag_fail(diag, "structure '%s': leaf size %u is not available (%s)", structure,
                     prm->leaf, kind == ACC_CHUNKS || kind == ACC_GRID ? "it has no leaf size"
                     : kind == ACC_BVHQ ? "1..LT_BVHQ_MAX_LEAF = 15" : "1..LT_BVH_MAX_LEAF = 64");
        return NULL;
    }
    a = calloc(1, sizeof *a);
    if (a != NULL && (a->ray = alloc64(path->render->ray16_bytes)) != NULL)
        memset(a->ray, 0, path->render->ray16_bytes);
    if (a == NULL || a->ray == NULL) {
        free(a);
        lt_diag_fail(diag, "out of memory");
        return NULL;
    }
    /* the descriptor (the kernels read its root box and pointers) at a fixed simulated address */
    lt_meter_region(a, sizeof *a, 0x40000000u);
    lt_meter_region(a->ray, path->render->ray16_bytes, 0x48000000u); /* the packet's lanes */
    a->leaf = prm != NULL ? prm->leaf : 0;
    a->path = path;
    a->ops = path->render;
    a->kind = kind;
    a->n = s->ntris;
    a->tris = a->ops->tris(s);
    lt_meter_region(a->tris, s->ntris * a->ops->tri_bytes, 0x10000000u);
    if (kind == ACC_KD || kind == ACC_GRID) {
        if (build_kdgrid(s, a, diag) == NULL) {
            lt_accel_free(a);
            return NULL;
        }
        return a;
    }
    if (kind != ACC_CHUNKS) {
        if (build_bvh(s, a, kind == ACC_BVHQ, diag) == NULL) {
            lt_accel_free(a);
            return NULL;
        }
        return a;
    }
    a->boxes = malloc(nb * a->ops->box_bytes);
    if (a->boxes != NULL)
        lt_meter_region(a->boxes, nb * a->ops->box_bytes, 0x20000000u);
    st = a->boxes ? a->ops->chunks_build(a->tris, s->ntris, a->boxes) : LT_E_SPACE;
    a->bytes = nb * a->ops->box_bytes;
    if (st != LT_OK) {
        lt_diag_fail(diag, "building '%s': %s", structure, lt_status_str(st));
        lt_accel_free(a);
        return NULL;
    }
    return a;
}

size_t lt_accel_bytes(const lt_accel_t *a) { return a->bytes; }

void lt_accel_set_isect(lt_accel_t *a, uint32_t isect)
{
    a->isect = isect;
    a->bvh.isect = isect;
    a->bvhq.isect = isect;
    a->wide.isect = isect;
    a->pwide.isect = isect;
    if (a->hdr != NULL && a->kind == ACC_KD)
        a->ops->kd_set_isect(a->hdr, isect);
    if (a->hdr != NULL && a->kind == ACC_GRID)
        a->ops->grid_set_isect(a->hdr, isect);
}

int lt_accel_set_isect_name(lt_accel_t *a, const char *name, uint32_t *g, lt_diag_t *diag)
{
    uint32_t v;
    if (strcmp(name, "wt") == 0) {
        v = LT_ISECT_WT;
    } else if (strcmp(name, "mt") == 0) {
        v = LT_ISECT_MT;
    } else if (strcmp(name, "wt32") == 0) {
        unsigned sh;
        if (a->path->bvh_num != LT_BVH_NUM_Q16) {
            lt_diag_fail(diag, "--isect wt32 is the s15.16 test on a grid (32-bit edge "
                               "functions); the %s path takes wt or mt", a->path->name);
            return -1;
        }
        sh = lt_wt32_shift_q16((const lt_tri_q16_t *)a->tris, a->n);
        v = LT_ISECT_WT32_G(sh);
        if (g != NULL)
            *g = sh;
    } else {
        lt_diag_fail(diag, "unknown intersector '%s' (wt, mt, wt32)", name);
        return -1;
    }
    lt_accel_set_isect(a, v);
    return 0;
}

void lt_accel_free(lt_accel_t *a)
{
    if (a == NULL)
        return;
    free(a->boxes);
    free(a->arena);
    free(a->qmem);
    free(a->mem);
    free(a->hdr);
    free(a->ray);
    free(a->wmem);
    free(a->pmem);
    free(a->view);
    free(a);
}

static int same_camera(const lt_camera_t *a, const lt_camera_t *b)
{
    int i;
    for (i = 0; i < 3; i++)
        if (a->eye[i] != b->eye[i] || a->fwd[i] != b->fwd[i] || a->right[i] != b->right[i] ||
            a->up[i] != b->up[i])
            return 0;
    return a->tan_half_fov == b->tan_half_fov && a->width == b->width && a->height == b->height;
}

int lt_accel_set_view(lt_accel_t *a, const lt_camera_t *c, lt_diag_t *diag)
{
    free(a->view);
    a->view = NULL;
    if (c == NULL)
        return 0;
    if ((a->view = lt_camera_dirs_table(c)) == NULL) {
        lt_diag_fail(diag, "out of memory for the directions of a %ux%u view", c->width,
                     c->height);
        return -1;
    }
    a->view_cam = *c;
    return 0;
}

/* The accel's direction table when it was made for camera c, else NULL (computed). */
static const double *view_tab(const lt_accel_t *a, const lt_camera_t *c)
{
    return a->view != NULL && same_camera(&a->view_cam, c) ? a->view : NULL;
}

static uint64_t cycles_now(void) { return lt_meter_cycles(); }

static uint64_t nodes_now(void) { return lt_meter_event(LT_EV_NODES); }

/* Closest hit of one packet (ray: the accel's scratch packet or a worker's) through the
 * structure. */
static void trace16(const lt_accel_t *a, void *ray, lt_mask16_t k, lt_hit16_t *hit)
{
    const lt_render_ops_t *ops = a->ops;
    if (a->kind == ACC_CHUNKS)
        ops->chunks_trace16(a->tris, a->n, a->boxes, a->isect, ray, k, hit);
    else if (a->kind == ACC_KD)
        ops->kd_trace16(a->hdr, ray, k, hit);
    else if (a->kind == ACC_GRID)
        ops->grid_trace16(a->hdr, ray, k, hit);
    else if (a->kind == ACC_BVHQ)
        ops->bvhq_trace16(&a->bvhq, a->tris, ray, k, hit);
    else if (a->walk16 != NULL)
        ops->bvh8_trace16(a->walk16, a->tris, ray, k, hit);
    else
        ops->bvh_trace16(&a->bvh, a->tris, ray, k, hit);
}

/* Any hit of a packet: the occluded lanes of k (hierarchies only). */
static lt_mask16_t occluded16(const lt_accel_t *a, void *ray, lt_mask16_t k)
{
    const lt_render_ops_t *ops = a->ops;
    if (a->kind == ACC_KD)
        return ops->kd_occluded16(a->hdr, ray, k);
    if (a->kind == ACC_GRID)
        return ops->grid_occluded16(a->hdr, ray, k);
    if (a->kind == ACC_BVHQ)
        return ops->bvhq_occluded16(&a->bvhq, a->tris, ray, k);
    if (a->walk16 != NULL)
        return ops->bvh8_occluded16(a->walk16, a->tris, ray, k);
    return ops->bvh_occluded16(&a->bvh, a->tris, ray, k);
}

/* ---- the loops on every core (lt_par.h) ------------------------------------------------------
 * A task is one row of 4x4 tiles (or of pixels); each writes only its own pixels. Worker 0 uses
 * the accel's scratch packet (the one the cycle model knows), the others their own. */

typedef struct rd_job {
    const lt_accel_t *a;
    const lt_camera_t *c;
    lt_frame_t *f;             /* primary, primary1: the frame written; peel: the next layer */
    const lt_frame_t *prev;    /* shadows: the primary hits; peel: the previous layer */
    const double *light;       /* shadows */
    double eps;                /* shadows */
    uint8_t *occluded;         /* shadows (may be NULL) */
    int single;                /* shadows: single rays through the wide tree, not packets */
    const double *tab;         /* the camera's directions (lt_accel_set_view) or NULL */
    void *ray[LT_PAR_MAX_THREADS];
    uint32_t n[LT_PAR_MAX_THREADS], occ[LT_PAR_MAX_THREADS]; /* shadows: per-worker counts */
} rd_job_t;

/* The job over camera c (its directions from the accel's table when made for c) and its scratch
 * packets for up to lt_par_workers(ntasks, 1) workers; returns how many are ready (at least 1:
 * worker 0 has the accel's). */
static unsigned rd_open(rd_job_t *j, const lt_accel_t *a, const lt_camera_t *c, uint32_t ntasks)
{
    unsigned w = lt_par_workers(ntasks, 1), i;
    memset(j, 0, sizeof *j);
    j->a = a;
    j->c = c;
    j->tab = view_tab(a, c);
    j->ray[0] = a->ray;
    for (i = 1; i < w; i++) {
        if ((j->ray[i] = alloc64(a->ops->ray16_bytes)) == NULL)
            break;
        memset(j->ray[i], 0, a->ops->ray16_bytes);
    }
    return i;
}

static void rd_close(rd_job_t *j)
{
    unsigned i;
    for (i = 1; i < LT_PAR_MAX_THREADS; i++)
        free(j->ray[i]);
}

static uint32_t tile_rows(const lt_camera_t *c) { return (c->height + 3u) / 4u; }

static void primary_row(void *ctx, unsigned w, uint32_t row)
{
    const rd_job_t *j = ctx;
    const lt_accel_t *a = j->a;
    const lt_camera_t *c = j->c;
    lt_frame_t *f = j->f;
    void *ray = j->ray[w];
    uint32_t tx, ty = 4u * row;
    for (tx = 0; tx < c->width; tx += 4) {
        lt_hit16_t hit;
        lt_mask16_t k;
        uint64_t c0 = 0, n0 = 0;
        float per = 0.0f, steps = 0.0f;
        int i;
        lt_phase_t prev;
        if (f->heat) {
            c0 = cycles_now();
            n0 = nodes_now();
        }
        prev = LT_PHASE_ENTER(SETUP);
        k = a->ops->camera_packet(c, j->tab, tx, ty, ray);
        LT_EVENT(RAYS, lt__popcount32(k));
        LT_PHASE_LEAVE(prev);
        trace16(a, ray, k, &hit);
        if (f->heat) {
            per = (float)(cycles_now() - c0) / (float)lt__popcount32(k);
            steps = (float)(nodes_now() - n0);
        }
        for (i = 0; i < LT_LANES; i++) {
            uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
            size_t p = (size_t)y * c->width + x;
            if ((((unsigned)k >> i) & 1u) == 0)
                continue;
            f->id[p] = hit.id.l[i];
            f->t[p] = a->ops->ray16_t(ray, i);
            f->cost[p] = per;
            f->steps[p] = steps;
        }
    }
}

void lt_render_primary(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                       lt_frame_t *f, void (*progress)(double done))
{
    rd_job_t j;
    unsigned w = rd_open(&j, a, c, tile_rows(c));
    (void)s;
    j.f = f;
    (void)lt_par_run(tile_rows(c), w, primary_row, &j, progress);
    rd_close(&j);
}

typedef struct ref_job {
    const lt_scene_t *s;
    const lt_camera_t *c;
    lt_frame_t *f;
} ref_job_t;

static void reference_row(void *ctx, unsigned w, uint32_t y)
{
    const ref_job_t *j = ctx;
    uint32_t x;
    (void)w;
    for (x = 0; x < j->c->width; x++) {
        double d[3];
        size_t p = (size_t)y * j->c->width + x;
        lt_camera_dir(j->c, x, y, d);
        j->f->id[p] = lt_ref_trace(j->s, j->c->eye, d, &j->f->t[p]);
        j->f->cost[p] = 0.0f;
    }
}

/* The reference charges nothing (double-precision host code): every core, in every build. */
void lt_render_reference(const lt_scene_t *s, const lt_camera_t *c, lt_frame_t *f,
                         void (*progress)(double done))
{
    ref_job_t j;
    j.s = s;
    j.c = c;
    j.f = f;
    (void)lt_par_run(c->height, lt_par_workers(c->height, 0), reference_row, &j, progress);
}

void lt_frame_compare(const lt_frame_t *a, const lt_frame_t *ref, double tol, lt_accuracy_t *acc)
{
    size_t i, n = (size_t)a->width * a->height;
    double se = 0.0;
    memset(acc, 0, sizeof *acc);
    acc->tol = tol;
    acc->pixels = (uint32_t)n;
    for (i = 0; i < n; i++) {
        acc->same_id += a->id[i] == ref->id[i];
        if (a->id[i] >= 0 && ref->id[i] >= 0) {
            double e = fabs(a->t[i] - ref->t[i]);
            acc->both_hit++;
            se += e * e;
            if (e > acc->max_err)
                acc->max_err = e;
            acc->within_tol += e <= tol;
        }
    }
    acc->rmse = acc->both_hit ? sqrt(se / acc->both_hit) : 0.0;
}

uint32_t lt_frame_hash(const lt_frame_t *f)
{
    uint32_t h = 2166136261u;
    size_t i, n = (size_t)f->width * f->height;
    for (i = 0; i < n; i++) {
        unsigned char b[12];
        int j;
        uint64_t tb;
        memcpy(&tb, &f->t[i], sizeof tb);
        memcpy(b, &f->id[i], 4);
        memcpy(b + 4, &tb, 8);
        for (j = 0; j < 12; j++) {
            h ^= b[j];
            h *= 16777619u;
        }
    }
    return h;
}

/* kd-tree, grid, chunks: no scalar traversal; each ray runs alone through the packet kernel with
   a one-lane mask (what a 16-lane machine does with an incoherent ray: 1/16 lane utilisation).
   The tile's packet is set up once, its lanes traced one by one. */
static void primary1_lanes_row(void *ctx, unsigned w, uint32_t row)
{
    const rd_job_t *j = ctx;
    const lt_accel_t *a = j->a;
    const lt_camera_t *c = j->c;
    void *ray = j->ray[w];
    uint32_t tx, ty = 4u * row;
    for (tx = 0; tx < c->width; tx += 4) {
        lt_mask16_t k = a->ops->camera_packet(c, j->tab, tx, ty, ray);
        int i;
        LT_EVENT(RAYS, lt__popcount32(k));
        for (i = 0; i < LT_LANES; i++) {
            lt_hit16_t hit;
            size_t p = (size_t)(ty + (uint32_t)(i / 4)) * c->width + tx + (uint32_t)(i % 4);
            if ((((unsigned)k >> i) & 1u) == 0)
                continue;
            trace16(a, ray, (lt_mask16_t)(1u << i), &hit);
            j->f->id[p] = hit.id.l[i];
            j->f->t[p] = a->ops->ray16_t(ray, i);
        }
    }
}

/* bvh: a wide tree (lt_bvh8.h) collapsed from the binary tree into *w (memory *mem, modelled at
 * address base) with merge bound merge, once (the packets and lt_accel_bytes keep to the binary
 * tree unless lt_accel_set_walk says otherwise); 0, or -1 with a message. */
static int wide_build(lt_accel_t *a, lt_bvh8_t *w, void **mem, uint32_t merge, uint32_t base,
                      lt_diag_t *diag)
{
    size_t bytes = 0;
    lt_status_t st;
    if (a->kind != ACC_BVH || w->num != 0)
        return 0;
    st = lt_bvh8_size_merge(&a->bvh, merge, &bytes);
    if (st == LT_OK && bytes > 0 && (*mem = alloc64(bytes)) == NULL)
        st = LT_E_SPACE;
    if (st == LT_OK) {
        lt_meter_region(*mem, bytes, base);
        st = a->ops->bvh8_build(w, &a->bvh, a->tris, *mem, bytes, merge);
    }
    if (st != LT_OK) {
        lt_diag_fail(diag, "collapsing the BVH into 8-wide nodes (%zu bytes): %s", bytes,
                     lt_status_str(st));
        return -1;
    }
    return 0;
}

/* The single rays' wide tree (the path's merge bound), built on the first single-ray call. */
static int wide_tree(const lt_accel_t *ac, lt_diag_t *diag)
{
    lt_accel_t *a = (lt_accel_t *)(uintptr_t)ac; /* a cache of the accel's own tree */
    return wide_build(a, &a->wide, &a->wmem, lt_bvh8_merge_default(a->bvh.num), 0x38000000u,
                      diag);
}

int lt_accel_set_walk(lt_accel_t *a, int wide, lt_diag_t *diag)
{
    a->walk16 = NULL;
    if (!wide || a->kind != ACC_BVH)
        return 0;
    /* the packets' tree keeps every binary leaf (merge 0): the single rays' tree where that is
       the path's own (s15.16), else its own */
    if (lt_bvh8_merge_default(a->bvh.num) == 0) {
        if (wide_tree(a, diag) != 0)
            return -1;
        a->walk16 = &a->wide;
    } else {
        if (wide_build(a, &a->pwide, &a->pmem, 0, 0x3C000000u, diag) != 0)
            return -1;
        a->walk16 = &a->pwide;
    }
    return 0;
}

/* bvh, bvhq: each ray of a row of 4x4 tiles alone through the single-ray traversal (the wide tree
 * for bvh; tile order: the directions come 16 at a time, lt_camera_tile_dirs). */
static void primary1_row(void *ctx, unsigned w, uint32_t row)
{
    const rd_job_t *j = ctx;
    const lt_accel_t *a = j->a;
    const lt_camera_t *c = j->c;
    uint32_t tx, ty = 4u * row;
    (void)w;
    for (tx = 0; tx < c->width; tx += 4) {
        double dx[LT_LANES], dy[LT_LANES], dz[LT_LANES];
        unsigned k = lt_camera_tile_dirs_tab(c, j->tab, tx, ty, dx, dy, dz);
        int i;
        for (i = 0; i < LT_LANES; i++) {
            double d[3];
            size_t p = (size_t)(ty + (uint32_t)(i / 4)) * c->width + tx + (uint32_t)(i % 4);
            if (((k >> i) & 1u) == 0)
                continue;
            d[0] = dx[i];
            d[1] = dy[i];
            d[2] = dz[i];
            j->f->id[p] = a->kind == ACC_BVHQ
                              ? a->ops->bvhq_trace1(&a->bvhq, a->tris, c->eye, d, &j->f->t[p])
                              : a->ops->bvh8_trace1(&a->wide, a->tris, c->eye, d, &j->f->t[p]);
        }
    }
}

/* One primary ray per pixel (single-ray traversal, BVH structures only). */
int lt_render_primary1(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                       lt_frame_t *f, lt_diag_t *diag)
{
    rd_job_t j;
    int lanes = a->kind != ACC_BVH && a->kind != ACC_BVHQ;
    uint32_t nt = tile_rows(c);
    unsigned w;
    (void)s;
    if (wide_tree(a, diag) != 0)
        return -1;
    w = rd_open(&j, a, c, nt);
    j.f = f;
    (void)lt_par_run(nt, w, lanes ? primary1_lanes_row : primary1_row, &j, NULL);
    rd_close(&j);
    return 0;
}

static void shadows_row(void *ctx, unsigned w, uint32_t row)
{
    rd_job_t *j = ctx;
    const lt_accel_t *a = j->a;
    const lt_camera_t *c = j->c;
    const lt_frame_t *f = j->prev;
    void *ray = j->ray[w];
    uint32_t tx, ty = 4u * row;
    for (tx = 0; tx < c->width; tx += 4) {
        unsigned k = 0;
        lt_mask16_t o = 0;
        double cx[LT_LANES], cy[LT_LANES], cz[LT_LANES], t[LT_LANES], len[LT_LANES];
        double px[LT_LANES], py[LT_LANES], pz[LT_LANES], l2[LT_LANES];
        int i;
        (void)lt_camera_tile_dirs_tab(c, j->tab, tx, ty, cx, cy, cz);
        for (i = 0; i < LT_LANES; i++) {
            uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
            size_t q = (size_t)y * c->width + x;
            int on = x < c->width && y < c->height && f->id[q] >= 0;
            k |= (unsigned)on << i;
            t[i] = on ? f->t[q] : 0.0;
        }
        /* hit points and unit directions to the light, as lane loops over doubles (the same
           operations per lane as one at a time: bit-identical, and vectorised) */
        for (i = 0; i < LT_LANES; i++) {
            px[i] = c->eye[0] + t[i] * cx[i];
            py[i] = c->eye[1] + t[i] * cy[i];
            pz[i] = c->eye[2] + t[i] * cz[i];
            cx[i] = j->light[0] - px[i];
            cy[i] = j->light[1] - py[i];
            cz[i] = j->light[2] - pz[i];
            l2[i] = cx[i] * cx[i] + cy[i] * cy[i] + cz[i] * cz[i];
        }
        for (i = 0; i < LT_LANES; i++)
            len[i] = sqrt(l2[i]);
        for (i = 0; i < LT_LANES; i++) {
            cx[i] /= len[i];
            cy[i] /= len[i];
            cz[i] /= len[i];
        }
        for (i = 0; i < LT_LANES; i++) {
            double d[3], p[3], ln;
            if ((k >> i) & 1u) {
                p[0] = px[i];
                p[1] = py[i];
                p[2] = pz[i];
                d[0] = cx[i];
                d[1] = cy[i];
                d[2] = cz[i];
                ln = len[i];
            } else {
                p[0] = p[1] = p[2] = 0.0;
                d[0] = 1.0;
                d[1] = d[2] = 0.0;
                ln = 1.0;
            }
            if (j->single) {
                /* one ray alone through the wide tree: the packet lane's conversions and setup */
                if ((k >> i) & 1u)
                    o = (lt_mask16_t)(o | (unsigned)a->ops->bvh8_occluded1(&a->wide, a->tris, p, d,
                                                                          j->eps, ln - j->eps)
                                              << i);
                continue;
            }
            a->ops->ray16_lane(ray, i, p, d, j->eps, ln - j->eps);
        }
        if (k == 0)
            continue;
        if (!j->single) {
            a->ops->ray16_setup(ray);
            o = occluded16(a, ray, (lt_mask16_t)k);
        }
        j->n[w] += lt__popcount32(k);
        j->occ[w] += lt__popcount32(o);
        if (j->occluded != NULL)
            for (i = 0; i < LT_LANES; i++) {
                uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
                if (x < c->width && y < c->height)
                    j->occluded[(size_t)y * c->width + x] =
                        (uint8_t)(((unsigned)o >> i) & 1u);
            }
    }
}

/* Shadow rays from each primary hit of f towards the light (scaled units), 16-ray packets over
 * the same 4x4 tiles (single: each ray alone through the wide tree); origins offset by eps along
 * the way to the light. */
static int shadows(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                   const lt_frame_t *f, const double light[3], uint32_t *nrays,
                   uint32_t *noccluded, uint8_t *occluded, int single, lt_diag_t *diag)
{
    rd_job_t j;
    unsigned w, i;
    uint32_t n = 0, occ = 0;
    if (a->kind == ACC_CHUNKS) {
        lt_diag_fail(diag, "shadow rays need a hierarchy (bvh, bvhq, kd, grid)");
        return -1;
    }
    if (single && a->kind != ACC_BVH) {
        lt_diag_fail(diag, "single shadow rays walk the wide BVH: structure bvh only");
        return -1;
    }
    if (single && wide_tree(a, diag) != 0)
        return -1;
    w = rd_open(&j, a, c, tile_rows(c));
    j.single = single;
    j.prev = f;
    j.light = light;
    j.eps = 1e-4 * s->radius;
    j.occluded = occluded;
    (void)lt_par_run(tile_rows(c), w, shadows_row, &j, NULL);
    for (i = 0; i < w; i++) {
        n += j.n[i];
        occ += j.occ[i];
    }
    rd_close(&j);
    *nrays = n;
    *noccluded = occ;
    return 0;
}

int lt_render_shadows(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                      const lt_frame_t *f, const double light[3], uint32_t *nrays,
                      uint32_t *noccluded, uint8_t *occluded, lt_diag_t *diag)
{
    return shadows(s, a, c, f, light, nrays, noccluded, occluded, 0, diag);
}

int lt_render_shadows1(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                       const lt_frame_t *f, const double light[3], uint32_t *nrays,
                       uint32_t *noccluded, uint8_t *occluded, lt_diag_t *diag)
{
    return shadows(s, a, c, f, light, nrays, noccluded, occluded, 1, diag);
}

static void peel_row(void *ctx, unsigned w, uint32_t row)
{
    const rd_job_t *j = ctx;
    const lt_accel_t *a = j->a;
    const lt_camera_t *c = j->c;
    void *ray = j->ray[w];
    uint32_t tx, ty = 4u * row;
    for (tx = 0; tx < c->width; tx += 4) {
        lt_hit16_t hit;
        lt_mask16_t k, live = 0;
        int i;
        k = a->ops->camera_packet(c, j->tab, tx, ty, ray);
        /* the next surface lies strictly beyond the previous hit: tmin = previous t */
        for (i = 0; i < LT_LANES; i++) {
            uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
            size_t p = (size_t)y * c->width + x;
            if (((unsigned)k >> i & 1u) == 0 || j->prev->id[p] < 0)
                continue;
            live = (lt_mask16_t)(live | (1u << i));
            a->ops->ray16_tmin(ray, i, j->prev->t[p]);
        }
        hit.id = lt_vi32_set1(-1);
        if (live != 0)
            trace16(a, ray, live, &hit);
        for (i = 0; i < LT_LANES; i++) {
            uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
            size_t p = (size_t)y * c->width + x;
            if (((unsigned)k >> i & 1u) == 0)
                continue;
            j->f->id[p] = ((unsigned)live >> i & 1u) ? hit.id.l[i] : -1;
            j->f->t[p] = a->ops->ray16_t(ray, i);
        }
    }
}

int lt_render_peel(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                   const lt_frame_t *prev, lt_frame_t *next, lt_diag_t *diag)
{
    rd_job_t j;
    unsigned w;
    (void)s;
    if (a->kind == ACC_CHUNKS) {
        lt_diag_fail(diag, "depth peeling needs a hierarchy (bvh, bvhq, kd, grid)");
        return -1;
    }
    w = rd_open(&j, a, c, tile_rows(c));
    j.prev = prev;
    j.f = next;
    (void)lt_par_run(tile_rows(c), w, peel_row, &j, NULL);
    rd_close(&j);
    return 0;
}
