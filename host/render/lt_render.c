/* lt_render.c - frame tracing over the core's structures, reference frames, comparison.
 * Host only; in sim builds it samples the cycle model's total per packet (lt_meter.h; zeros
 * natively).
 */
#include "render/lt_render.h"
#include "io/lt_fx_float.h"
#include "lt_meter.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Structure kinds behind the names of lt_accel_build. */
enum { ACC_CHUNKS, ACC_BVH, ACC_BVHQ, ACC_KD, ACC_GRID };

struct lt_accel {
    lt_path_t path;
    int kind;
    uint32_t n;
    lt_aabb_q16_t *boxes_q;  /* chunks */
    lt_aabb_f32_t *boxes_f;
    void *arena;             /* bvh: the tree's arena (64-byte aligned) */
    lt_bvh_t bvh;
    void *qmem;              /* bvhq: quantised nodes */
    lt_bvhq_t bvhq;
    void *mem;               /* kd, grid: their arena */
    lt_kd_q16_t kdq;
    lt_kd_f32_t kdf;
    lt_grid_q16_t gq;
    lt_grid_f32_t gf;
    size_t bytes;            /* structure memory */
    uint32_t isect;          /* the intersector of every walk (LT_ISECT_WT unless set) */
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

static lt_accel_t *build_bvh(const lt_scene_t *s, lt_accel_t *a, int quantised, lt_diag_t *diag)
{
    lt_bvh_desc_t desc;
    size_t bytes = 0;
    lt_status_t st;
    memset(&desc, 0, sizeof desc);
    if (quantised && a->path != LT_PATH_Q16) {
        lt_diag_fail(diag, "structure 'bvhq' (quantised nodes) exists in s15.16 only");
        return NULL;
    }
    st = lt_bvh_size(s->ntris, &desc, &bytes);
    if (st == LT_OK) {
        a->arena = alloc64(bytes);
        if (a->arena == NULL)
            st = LT_E_SPACE;
    }
    if (st == LT_OK)
        st = a->path == LT_PATH_Q16 ? lt_bvh_build_q16(&a->bvh, &desc, s->tq, s->ntris, a->arena, bytes)
                                    : lt_bvh_build_f32(&a->bvh, &desc, s->tf, s->ntris, a->arena, bytes);
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
        if (st == LT_OK)
            st = lt_bvhq_build_q16(&a->bvhq, &a->bvh, a->qmem, qb);
        if (st != LT_OK) {
            lt_diag_fail(diag, "quantising the BVH: %s", lt_status_str(st));
            return NULL;
        }
        /* the quantised tree keeps its nodes plus the source tree's index array */
        a->bytes = a->bvhq.bytes + (size_t)s->ntris * sizeof(uint32_t);
    }
    lt_meter_region(a->arena, a->bvh.bytes, 0x20000000u);
    if (quantised)
        lt_meter_region(a->qmem, a->bvhq.bytes, 0x30000000u);
    return a;
}

/* kd-tree or uniform grid: size query, arena, build (docs/kdtree-grid.md). */
static lt_accel_t *build_kdgrid(const lt_scene_t *s, lt_accel_t *a, lt_diag_t *diag)
{
    size_t bytes = 0;
    lt_status_t st;
    if (a->kind == ACC_KD) {
        lt_kd_params_t p;
        lt_kd_params_default(&p);
        st = lt_kd_size(s->ntris, &p, &bytes);
        if (st == LT_OK && (a->mem = alloc64(bytes)) == NULL)
            st = LT_E_SPACE;
        if (st == LT_OK)
            st = a->path == LT_PATH_Q16 ? lt_kd_build_q16(&a->kdq, s->tq, s->ntris, &p, a->mem, &bytes)
                                        : lt_kd_build_f32(&a->kdf, s->tf, s->ntris, &p, a->mem, &bytes);
        a->bytes = a->path == LT_PATH_Q16 ? a->kdq.bytes : a->kdf.bytes;
    } else {
        lt_grid_params_t p;
        lt_grid_params_default(&p);
        st = a->path == LT_PATH_Q16 ? lt_grid_size_q16(s->tq, s->ntris, &p, &bytes)
                                    : lt_grid_size_f32(s->tf, s->ntris, &p, &bytes);
        if (st == LT_OK && (a->mem = alloc64(bytes)) == NULL)
            st = LT_E_SPACE;
        if (st == LT_OK)
            st = a->path == LT_PATH_Q16 ? lt_grid_build_q16(&a->gq, s->tq, s->ntris, &p, a->mem, &bytes)
                                        : lt_grid_build_f32(&a->gf, s->tf, s->ntris, &p, a->mem, &bytes);
        a->bytes = bytes;
    }
    if (st != LT_OK) {
        lt_diag_fail(diag, "building the %s over %u triangles: %s",
                     a->kind == ACC_KD ? "kd-tree" : "grid", s->ntris, lt_status_str(st));
        return NULL;
    }
    lt_meter_region(a->mem, a->bytes, 0x20000000u);
    return a;
}

lt_accel_t *lt_accel_build(const lt_scene_t *s, const char *structure, lt_path_t path,
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
    a = calloc(1, sizeof *a);
    if (a == NULL) {
        lt_diag_fail(diag, "out of memory");
        return NULL;
    }
    a->path = path;
    a->kind = kind;
    a->n = s->ntris;
    if (path == LT_PATH_Q16)
        lt_meter_region(s->tq, s->ntris * sizeof *s->tq, 0x10000000u);
    else
        lt_meter_region(s->tf, s->ntris * sizeof *s->tf, 0x10000000u);
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
    if (path == LT_PATH_Q16) {
        a->boxes_q = malloc(nb * sizeof *a->boxes_q);
        if (a->boxes_q != NULL)
            lt_meter_region(a->boxes_q, nb * sizeof *a->boxes_q, 0x20000000u);
        st = a->boxes_q ? lt_chunks_build_q16(s->tq, s->ntris, a->boxes_q) : LT_E_SPACE;
        a->bytes = nb * sizeof *a->boxes_q;
    } else {
        a->boxes_f = malloc(nb * sizeof *a->boxes_f);
        if (a->boxes_f != NULL)
            lt_meter_region(a->boxes_f, nb * sizeof *a->boxes_f, 0x20000000u);
        st = a->boxes_f ? lt_chunks_build_f32(s->tf, s->ntris, a->boxes_f) : LT_E_SPACE;
        a->bytes = nb * sizeof *a->boxes_f;
    }
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
    a->kdq.isect = isect;
    a->kdf.isect = isect;
    a->gq.isect = isect;
    a->gf.isect = isect;
}

void lt_accel_free(lt_accel_t *a)
{
    if (a == NULL)
        return;
    free(a->boxes_q);
    free(a->boxes_f);
    free(a->arena);
    free(a->qmem);
    free(a->mem);
    free(a);
}

static uint64_t cycles_now(void) { return lt_meter_cycles(); }

static uint64_t nodes_now(void) { return lt_meter_event(LT_EV_NODES); }

/* Closest hit of one packet through the structure. */
static void trace16(const lt_scene_t *s, const lt_accel_t *a, lt_ray16_q16_t *rq,
                    lt_ray16_f32_t *rf, lt_mask16_t k, lt_hit16_t *hit)
{
    if (a->kind == ACC_CHUNKS) {
        if (a->path == LT_PATH_Q16)
            lt_chunks_trace16_q16(s->tq, a->n, a->boxes_q, a->isect, rq, k, hit);
        else
            lt_chunks_trace16_f32(s->tf, a->n, a->boxes_f, a->isect, rf, k, hit);
    } else if (a->kind == ACC_KD) {
        if (a->path == LT_PATH_Q16)
            (void)lt_kd_trace16_q16(&a->kdq, rq, k, hit);
        else
            (void)lt_kd_trace16_f32(&a->kdf, rf, k, hit);
    } else if (a->kind == ACC_GRID) {
        if (a->path == LT_PATH_Q16)
            (void)lt_grid_trace16_q16(&a->gq, rq, k, hit);
        else
            (void)lt_grid_trace16_f32(&a->gf, rf, k, hit);
    } else if (a->kind == ACC_BVHQ) {
        (void)lt_bvhq_trace16_q16(&a->bvhq, s->tq, rq, k, hit);
    } else if (a->path == LT_PATH_Q16) {
        (void)lt_bvh_trace16_q16(&a->bvh, s->tq, rq, k, hit);
    } else {
        (void)lt_bvh_trace16_f32(&a->bvh, s->tf, rf, k, hit);
    }
}

void lt_render_primary(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                       lt_frame_t *f, void (*progress)(double done))
{
    uint32_t tx, ty;
    static lt_ray16_q16_t rq;
    static lt_ray16_f32_t rf;
    for (ty = 0; ty < c->height; ty += 4) {
        for (tx = 0; tx < c->width; tx += 4) {
            lt_hit16_t hit;
            lt_mask16_t k;
            uint64_t c0 = cycles_now(), n0 = nodes_now();
            float per, steps;
            int i;
            lt_phase_t prev = LT_PHASE_ENTER(SETUP);
            k = a->path == LT_PATH_Q16 ? lt_camera_packet_q16(c, tx, ty, &rq)
                                       : lt_camera_packet_f32(c, tx, ty, &rf);
            LT_EVENT(RAYS, lt__popcount32(k));
            LT_PHASE_LEAVE(prev);
            trace16(s, a, &rq, &rf, k, &hit);
            per = (float)(cycles_now() - c0) / (float)lt__popcount32(k);
            steps = (float)(nodes_now() - n0);
            for (i = 0; i < LT_LANES; i++) {
                uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
                size_t p = (size_t)y * c->width + x;
                if ((((unsigned)k >> i) & 1u) == 0)
                    continue;
                f->id[p] = hit.id.l[i];
                f->t[p] = a->path == LT_PATH_Q16 ? (double)rq.tmax.l[i] / 65536.0
                                                 : (double)rf.tmax.l[i];
                f->cost[p] = per;
                f->steps[p] = steps;
            }
        }
        if (progress != NULL)
            progress((double)(ty + 4) / (double)c->height);
    }
}

void lt_render_reference(const lt_scene_t *s, const lt_camera_t *c, lt_frame_t *f,
                         void (*progress)(double done))
{
    uint32_t x, y;
    for (y = 0; y < c->height; y++) {
        for (x = 0; x < c->width; x++) {
            double d[3];
            size_t p = (size_t)y * c->width + x;
            lt_camera_dir(c, x, y, d);
            f->id[p] = lt_ref_trace(s, c->eye, d, &f->t[p]);
            f->cost[p] = 0.0f;
        }
        if (progress != NULL && (y & 7) == 7)
            progress((double)(y + 1) / (double)c->height);
    }
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

/* One primary ray per pixel (single-ray traversal, BVH structures only). */
int lt_render_primary1(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                       lt_frame_t *f, lt_diag_t *diag)
{
    uint32_t x, y;
    (void)diag;
    if (a->kind != ACC_BVH && a->kind != ACC_BVHQ) {
        /* kd-tree, grid, chunks: no scalar traversal; each ray runs alone through the packet
           kernel with a one-lane mask (what a 16-lane machine does with an incoherent ray:
           1/16 lane utilisation). The tile's packet is set up once, its lanes traced one by one. */
        static lt_ray16_q16_t rq;
        static lt_ray16_f32_t rf;
        uint32_t tx, ty;
        for (ty = 0; ty < c->height; ty += 4)
            for (tx = 0; tx < c->width; tx += 4) {
                lt_mask16_t k = a->path == LT_PATH_Q16 ? lt_camera_packet_q16(c, tx, ty, &rq)
                                                       : lt_camera_packet_f32(c, tx, ty, &rf);
                int i;
                LT_EVENT(RAYS, lt__popcount32(k));
                for (i = 0; i < LT_LANES; i++) {
                    lt_hit16_t hit;
                    size_t p = (size_t)(ty + (uint32_t)(i / 4)) * c->width + tx + (uint32_t)(i % 4);
                    if ((((unsigned)k >> i) & 1u) == 0)
                        continue;
                    trace16(s, a, &rq, &rf, (lt_mask16_t)(1u << i), &hit);
                    f->id[p] = hit.id.l[i];
                    f->t[p] = a->path == LT_PATH_Q16 ? (double)rq.tmax.l[i] / 65536.0
                                                     : (double)rf.tmax.l[i];
                }
            }
        return 0;
    }
    for (y = 0; y < c->height; y++)
        for (x = 0; x < c->width; x++) {
            double d[3];
            size_t p = (size_t)y * c->width + x;
            int32_t id = -1;
            int i;
            lt_camera_dir(c, x, y, d);
            if (a->path == LT_PATH_Q16) {
                lt_ray1_q16_t r;
                memset(&r, 0, sizeof r);
                for (i = 0; i < 3; i++) {
                    r.o[i] = lt_q16_from_double_sat(c->eye[i]);
                    r.d[i] = lt_q30_from_double_sat(d[i]);
                }
                r.tmin = 0;
                r.tmax = LT_Q16_MAX - 1;
                lt_ray1_q16_setup(&r);
                if (a->kind == ACC_BVHQ)
                    (void)lt_bvhq_trace1_q16(&a->bvhq, s->tq, &r, &id);
                else
                    (void)lt_bvh_trace1_q16(&a->bvh, s->tq, &r, &id);
                f->t[p] = (double)r.tmax / 65536.0;
            } else {
                lt_ray1_f32_t r;
                memset(&r, 0, sizeof r);
                for (i = 0; i < 3; i++) {
                    r.o[i] = (float)c->eye[i];
                    r.d[i] = (float)d[i];
                }
                r.tmin = 0.0f;
                r.tmax = 3.0e38f;
                lt_ray1_f32_setup(&r);
                (void)lt_bvh_trace1_f32(&a->bvh, s->tf, &r, &id);
                f->t[p] = (double)r.tmax;
            }
            f->id[p] = id;
        }
    return 0;
}

/* Shadow rays from each primary hit of f towards the light (scaled units), 16-ray packets over
 * the same 4x4 tiles; origins offset by eps along the way to the light. */
int lt_render_shadows(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                      const lt_frame_t *f, const double light[3], uint32_t *nrays,
                      uint32_t *noccluded, uint8_t *occluded, lt_diag_t *diag)
{
    uint32_t tx, ty, n = 0, occ = 0;
    double eps = 1e-4 * s->radius;
    static lt_ray16_q16_t rq;
    static lt_ray16_f32_t rf;
    if (a->kind == ACC_CHUNKS) {
        lt_diag_fail(diag, "shadow rays need a hierarchy (bvh, bvhq, kd, grid)");
        return -1;
    }
    for (ty = 0; ty < c->height; ty += 4)
        for (tx = 0; tx < c->width; tx += 4) {
            unsigned k = 0;
            lt_mask16_t o = 0;
            int i;
            for (i = 0; i < LT_LANES; i++) {
                uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
                double d[3], p[3], l2 = 0.0, len;
                size_t q = (size_t)y * c->width + x;
                int j;
                if (x < c->width && y < c->height && f->id[q] >= 0) {
                    lt_camera_dir(c, x, y, d);
                    for (j = 0; j < 3; j++) {
                        p[j] = c->eye[j] + f->t[q] * d[j];
                        d[j] = light[j] - p[j];
                        l2 += d[j] * d[j];
                    }
                    len = sqrt(l2);
                    for (j = 0; j < 3; j++)
                        d[j] /= len;
                    k |= 1u << i;
                } else {
                    p[0] = p[1] = p[2] = 0.0;
                    d[0] = 1.0;
                    d[1] = d[2] = 0.0;
                    len = 1.0;
                }
                if (a->path == LT_PATH_Q16) {
                    rq.ox.l[i] = lt_q16_from_double_sat(p[0]);
                    rq.oy.l[i] = lt_q16_from_double_sat(p[1]);
                    rq.oz.l[i] = lt_q16_from_double_sat(p[2]);
                    rq.dx.l[i] = lt_q30_from_double_sat(d[0]);
                    rq.dy.l[i] = lt_q30_from_double_sat(d[1]);
                    rq.dz.l[i] = lt_q30_from_double_sat(d[2]);
                    rq.tmin.l[i] = lt_q16_from_double_sat(eps);
                    rq.tmax.l[i] = lt_q16_from_double_sat(len - eps);
                } else {
                    rf.ox.l[i] = (float)p[0];
                    rf.oy.l[i] = (float)p[1];
                    rf.oz.l[i] = (float)p[2];
                    rf.dx.l[i] = (float)d[0];
                    rf.dy.l[i] = (float)d[1];
                    rf.dz.l[i] = (float)d[2];
                    rf.tmin.l[i] = (float)eps;
                    rf.tmax.l[i] = (float)(len - eps);
                }
            }
            if (k == 0)
                continue;
            if (a->kind == ACC_KD || a->kind == ACC_GRID) {
                if (a->path == LT_PATH_Q16) {
                    lt_ray16_q16_setup(&rq);
                    o = a->kind == ACC_KD ? lt_kd_occluded16_q16(&a->kdq, &rq, (lt_mask16_t)k)
                                          : lt_grid_occluded16_q16(&a->gq, &rq, (lt_mask16_t)k);
                } else {
                    lt_ray16_f32_setup(&rf);
                    o = a->kind == ACC_KD ? lt_kd_occluded16_f32(&a->kdf, &rf, (lt_mask16_t)k)
                                          : lt_grid_occluded16_f32(&a->gf, &rf, (lt_mask16_t)k);
                }
            } else if (a->path == LT_PATH_Q16) {
                lt_ray16_q16_setup(&rq);
                if (a->kind == ACC_BVHQ)
                    (void)lt_bvhq_occluded16_q16(&a->bvhq, s->tq, &rq, (lt_mask16_t)k, &o);
                else
                    (void)lt_bvh_occluded16_q16(&a->bvh, s->tq, &rq, (lt_mask16_t)k, &o);
            } else {
                lt_ray16_f32_setup(&rf);
                (void)lt_bvh_occluded16_f32(&a->bvh, s->tf, &rf, (lt_mask16_t)k, &o);
            }
            n += lt__popcount32(k);
            occ += lt__popcount32(o);
            if (occluded != NULL)
                for (i = 0; i < LT_LANES; i++) {
                    uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
                    if (x < c->width && y < c->height)
                        occluded[(size_t)y * c->width + x] = (uint8_t)(((unsigned)o >> i) & 1u);
                }
        }
    *nrays = n;
    *noccluded = occ;
    return 0;
}

int lt_render_peel(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                   const lt_frame_t *prev, lt_frame_t *next, lt_diag_t *diag)
{
    uint32_t tx, ty;
    static lt_ray16_q16_t rq;
    static lt_ray16_f32_t rf;
    if (a->kind == ACC_CHUNKS) {
        lt_diag_fail(diag, "depth peeling needs a hierarchy (bvh, bvhq, kd, grid)");
        return -1;
    }
    for (ty = 0; ty < c->height; ty += 4)
        for (tx = 0; tx < c->width; tx += 4) {
            lt_hit16_t hit;
            lt_mask16_t k, live = 0;
            int i;
            k = a->path == LT_PATH_Q16 ? lt_camera_packet_q16(c, tx, ty, &rq)
                                       : lt_camera_packet_f32(c, tx, ty, &rf);
            /* the next surface lies strictly beyond the previous hit: tmin = previous t */
            for (i = 0; i < LT_LANES; i++) {
                uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
                size_t p = (size_t)y * c->width + x;
                if (((unsigned)k >> i & 1u) == 0 || prev->id[p] < 0)
                    continue;
                live = (lt_mask16_t)(live | (1u << i));
                if (a->path == LT_PATH_Q16)
                    rq.tmin.l[i] = lt_q16_from_double_sat(prev->t[p]);
                else
                    rf.tmin.l[i] = (float)prev->t[p];
            }
            hit.id = lt_vi32_set1(-1);
            if (live != 0)
                trace16(s, a, &rq, &rf, live, &hit);
            for (i = 0; i < LT_LANES; i++) {
                uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
                size_t p = (size_t)y * c->width + x;
                if (((unsigned)k >> i & 1u) == 0)
                    continue;
                next->id[p] = ((unsigned)live >> i & 1u) ? hit.id.l[i] : -1;
                next->t[p] = a->path == LT_PATH_Q16 ? (double)rq.tmax.l[i] / 65536.0
                                                    : (double)rf.tmax.l[i];
            }
        }
    return 0;
}
