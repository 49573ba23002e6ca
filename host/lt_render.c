/* lt_render.c - frame tracing over the core's structures, reference frames, comparison.
 * Host only; in sim builds (LT_COST_SIM) it samples the simulator's cycle total per packet.
 */
#include "lt_render.h"
#if LT_COST_MODE == LT_COST_SIM
#include "lt_sim.h"
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct lt_accel {
    lt_path_t path;
    uint32_t n;
    lt_aabb_q16_t *boxes_q;
    lt_aabb_f32_t *boxes_f;
};

int lt_frame_alloc(lt_frame_t *f, uint32_t w, uint32_t h, char *err, size_t errlen)
{
    size_t n = (size_t)w * h;
    memset(f, 0, sizeof *f);
    f->width = w;
    f->height = h;
    f->id = malloc(n * sizeof *f->id);
    f->t = malloc(n * sizeof *f->t);
    f->cost = calloc(n, sizeof *f->cost);
    if (f->id == NULL || f->t == NULL || f->cost == NULL) {
        lt_frame_free(f);
        snprintf(err, errlen, "out of memory for a %ux%u frame", w, h);
        return -1;
    }
    return 0;
}

void lt_frame_free(lt_frame_t *f)
{
    free(f->id);
    free(f->t);
    free(f->cost);
    memset(f, 0, sizeof *f);
}

lt_accel_t *lt_accel_build(const lt_scene_t *s, const char *structure, lt_path_t path, char *err,
                           size_t errlen)
{
    lt_accel_t *a;
    size_t nb = LT_CHUNK_COUNT(s->ntris);
    lt_status_t st;
    if (strcmp(structure, "chunks") != 0) {
        snprintf(err, errlen, "structure '%s' is not available (available: chunks)", structure);
        return NULL;
    }
    a = calloc(1, sizeof *a);
    if (a == NULL) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    a->path = path;
    a->n = s->ntris;
    if (path == LT_PATH_Q16) {
        a->boxes_q = malloc(nb * sizeof *a->boxes_q);
#if LT_COST_MODE == LT_COST_SIM
        lt_sim_region(s->tq, s->ntris * sizeof *s->tq, 0x10000000u);
        if (a->boxes_q != NULL)
            lt_sim_region(a->boxes_q, nb * sizeof *a->boxes_q, 0x20000000u);
#endif
        st = a->boxes_q ? lt_chunks_build_q16(s->tq, s->ntris, a->boxes_q) : LT_E_SPACE;
    } else {
        a->boxes_f = malloc(nb * sizeof *a->boxes_f);
#if LT_COST_MODE == LT_COST_SIM
        lt_sim_region(s->tf, s->ntris * sizeof *s->tf, 0x10000000u);
        if (a->boxes_f != NULL)
            lt_sim_region(a->boxes_f, nb * sizeof *a->boxes_f, 0x20000000u);
#endif
        st = a->boxes_f ? lt_chunks_build_f32(s->tf, s->ntris, a->boxes_f) : LT_E_SPACE;
    }
    if (st != LT_OK) {
        snprintf(err, errlen, "building '%s': %s", structure, lt_status_str(st));
        lt_accel_free(a);
        return NULL;
    }
    return a;
}

void lt_accel_free(lt_accel_t *a)
{
    if (a == NULL)
        return;
    free(a->boxes_q);
    free(a->boxes_f);
    free(a);
}

static uint64_t cycles_now(void)
{
#if LT_COST_MODE == LT_COST_SIM
    return lt_sim_cycles_total();
#else
    return 0;
#endif
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
            uint64_t c0 = cycles_now();
            float per;
            int i;
            lt_phase_t prev = LT_PHASE_ENTER(SETUP);
            k = a->path == LT_PATH_Q16 ? lt_camera_packet_q16(c, tx, ty, &rq)
                                       : lt_camera_packet_f32(c, tx, ty, &rf);
            LT_EVENT(RAYS, lt__popcount32(k));
            LT_PHASE_LEAVE(prev);
            if (a->path == LT_PATH_Q16)
                lt_chunks_trace16_q16(s->tq, a->n, a->boxes_q, &rq, k, &hit);
            else
                lt_chunks_trace16_f32(s->tf, a->n, a->boxes_f, &rf, k, &hit);
            per = (float)(cycles_now() - c0) / (float)lt__popcount32(k);
            for (i = 0; i < LT_LANES; i++) {
                uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
                size_t p = (size_t)y * c->width + x;
                if ((((unsigned)k >> i) & 1u) == 0)
                    continue;
                f->id[p] = hit.id.l[i];
                f->t[p] = a->path == LT_PATH_Q16 ? (double)rq.tmax.l[i] / 65536.0
                                                 : (double)rf.tmax.l[i];
                f->cost[p] = per;
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
