/* lt_recommend.c - see lt_recommend.h. */
#include "tune/lt_recommend.h"
#include "lt/lt_isect.h"
#include "render/lt_scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static lt_rec_pick_t *add(lt_rec_t *r, const char *knob, const char *pick)
{
    lt_rec_pick_t *k = &r->k[r->n++];
    k->knob = knob;
    snprintf(k->pick, sizeof k->pick, "%s", pick);
    k->reason[0] = '\0';
    return k;
}

static void numeric(const lt_rec_mesh_facts_t *f, lt_rec_t *r)
{
    lt_rec_pick_t *k;
    double pct = f->nonzero ? 100.0 * f->collapsed_q16 / (double)f->nonzero : 0.0;
    r->q16_ok = (uint64_t)f->collapsed_q16 * 1000000u <=
                (uint64_t)f->nonzero * LT_SCENE_MAX_COLLAPSED_PPM;
    if (!r->q16_ok) {
        k = add(r, "numeric", "f32");
        snprintf(k->reason, sizeof k->reason,
                 "not representable in s15.16: %u of %u triangles collapse (%.3f%%, limit %.1f%%), "
                 "dynamic range 2^%.1f (largest extent / shortest edge)",
                 f->collapsed_q16, f->nonzero, pct, LT_SCENE_MAX_COLLAPSED_PPM / 1e4,
                 r->range_log2);
    } else if (r->edge_steps < LT_REC_MIN_EDGE_STEPS) {
        k = add(r, "numeric", "f32");
        snprintf(k->reason, sizeof k->reason,
                 "representable in s15.16 (%u of %u triangles collapse) but the shortest edge spans "
                 "%.3g steps of 2^-16 (< %.0f): dynamic range 2^%.1f",
                 f->collapsed_q16, f->nonzero, r->edge_steps, LT_REC_MIN_EDGE_STEPS,
                 r->range_log2);
    } else {
        k = add(r, "numeric", "f32");
        snprintf(k->reason, sizeof k->reason,
                 "q16 holds it too (%u of %u triangles collapse, shortest edge %.3g steps of 2^-16, "
                 "dynamic range 2^%.1f); float32 measured cheaper and as accurate on lrb16 "
                 "(docs/tune.md)",
                 f->collapsed_q16, f->nonzero, r->edge_steps, r->range_log2);
    }
}

void lt_recommend_mesh(const lt_rec_mesh_facts_t *f, lt_rec_t *r)
{
    lt_rec_pick_t *k;
    memset(r, 0, sizeof *r);
    r->range_log2 = f->min_edge > 0.0 && f->extent > 0.0 ? log2(f->extent / f->min_edge) : 0.0;
    r->edge_steps = f->min_edge * f->scale * 65536.0;
    numeric(f, r);
    if (f->ntris > LT_REC_BVH_MIN_TRIS) {
        k = add(r, "structure", "bvh");
        snprintf(k->reason, sizeof k->reason,
                 "%u triangles (> %u): a hierarchy visits a few leaves where chunks test all %u "
                 "chunk boxes", f->ntris, LT_REC_BVH_MIN_TRIS, (unsigned)LT_CHUNK_COUNT(f->ntris));
        k = add(r, "leaf", "16");
        snprintf(k->reason, sizeof k->reason,
                 "about %u leaves of up to %u triangles; tune's cheapest BVH leaf on lrb16 "
                 "(16 lanes; 4 on the 1-lane mcu-m4)", (f->ntris + LT_REC_BVH_LEAF - 1u) /
                 LT_REC_BVH_LEAF, LT_REC_BVH_LEAF);
    } else {
        k = add(r, "structure", "chunks");
        snprintf(k->reason, sizeof k->reason,
                 "%u triangles (<= %u): %u chunk box(es) of 16, nothing to build or walk",
                 f->ntris, LT_REC_BVH_MIN_TRIS, (unsigned)LT_CHUNK_COUNT(f->ntris));
        k = add(r, "leaf", "-");
        snprintf(k->reason, sizeof k->reason, "chunks have no leaf size");
    }
}
