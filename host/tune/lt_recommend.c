/* lt_recommend.c - see lt_recommend.h. */
#include "tune/lt_recommend.h"
#include "lt/lt_cost.h"
#include "lt/lt_isect.h"
#include "render/lt_scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Every machine file's issue costs (sim/lt_machines.h: data, no simulator needed). */
typedef struct rec_machine {
    const char *name;
    uint32_t lanes;
    uint16_t issue[LT_OP__COUNT];
} rec_machine_t;

static const rec_machine_t rec_machines[] = {
#define LT_MACHINE(id, name, desc, clock_mhz, lanes) {name, lanes, {
#define LT_OP_COST(op, latency, issue) [LT_OP_##op] = issue,
#define LT_MACHINE_END }},
#include "lt_machines.h"
    {NULL, 0, {0}}};

#define OP(name, n) {LT_OP_##name, n}
const lt_rec_op_t lt_rec_tri_q16[] = {OP(SLOAD, 9), OP(SALU, 15), OP(SMUL, 6), OP(BRANCH, 1),
                                      OP(MASK, 27), OP(VBCAST, 10), OP(VALU, 15), OP(VMUL, 12),
                                      OP(VMULW, 5), OP(VCMP, 8), {0, 0}};
const lt_rec_op_t lt_rec_tri_f32[] = {OP(SLOAD, 9), OP(SALU, 15), OP(SMUL, 6), OP(BRANCH, 1),
                                      OP(MASK, 30), OP(VBCAST, 10), OP(FADD, 20), OP(FMUL, 12),
                                      OP(FCMP, 11), {0, 0}};
#undef OP

static uint32_t mix_cost(const lt_rec_op_t *mix, const uint16_t *issue)
{
    uint32_t c = 0;
    for (; mix->n != 0; mix++)
        c += mix->n * (uint32_t)issue[mix->op];
    return c;
}

int lt_rec_machine_costs(const char *name, lt_rec_costs_t *c)
{
    const rec_machine_t *m;
    memset(c, 0, sizeof *c);
    for (m = rec_machines; m->name != NULL; m++)
        if (name != NULL && strcmp(m->name, name) == 0) {
            c->f32 = mix_cost(lt_rec_tri_f32, m->issue);
            c->q16 = mix_cost(lt_rec_tri_q16, m->issue);
            c->lanes = m->lanes;
            return 0;
        }
    return -1;
}

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
    } else if (r->costs.q16 < r->costs.f32) {
        k = add(r, "numeric", "q16");
        snprintf(k->reason, sizeof k->reason,
                 "representable (%u of %u triangles collapse, shortest edge %.3g steps of 2^-16, "
                 "dynamic range 2^%.1f) and cheaper on %s: a 16-ray watertight triangle test costs "
                 "%u cycles in s15.16 against %u in float32",
                 f->collapsed_q16, f->nonzero, r->edge_steps, r->range_log2, r->machine,
                 r->costs.q16, r->costs.f32);
    } else {
        k = add(r, "numeric", "f32");
        snprintf(k->reason, sizeof k->reason,
                 "q16 holds it too (%u of %u triangles collapse, shortest edge %.3g steps of 2^-16, "
                 "dynamic range 2^%.1f) but float32 is as accurate and cheaper on %s: a 16-ray "
                 "watertight triangle test costs %u cycles against %u in s15.16",
                 f->collapsed_q16, f->nonzero, r->edge_steps, r->range_log2, r->machine,
                 r->costs.f32, r->costs.q16);
    }
}

void lt_recommend_mesh(const lt_rec_mesh_facts_t *f, lt_rec_t *r)
{
    lt_rec_pick_t *k;
    unsigned leaf;
    memset(r, 0, sizeof *r);
    r->machine = f->machine != NULL ? f->machine : "lrb16";
    if (lt_rec_machine_costs(r->machine, &r->costs) != 0) /* validated by the callers */
        (void)lt_rec_machine_costs("lrb16", &r->costs);
    leaf = r->costs.lanes >= 16u ? LT_REC_BVH_LEAF : LT_REC_BVH_LEAF_NARROW;
    r->range_log2 = f->min_edge > 0.0 && f->extent > 0.0 ? log2(f->extent / f->min_edge) : 0.0;
    r->edge_steps = f->min_edge * f->scale * 65536.0;
    numeric(f, r);
    if (f->ntris > LT_REC_BVH_MIN_TRIS) {
        k = add(r, "structure", "bvh");
        snprintf(k->reason, sizeof k->reason,
                 "%u triangles (> %u): a hierarchy visits a few leaves where chunks test all %u "
                 "chunk boxes", f->ntris, LT_REC_BVH_MIN_TRIS, (unsigned)LT_CHUNK_COUNT(f->ntris));
        k = add(r, "leaf", leaf == LT_REC_BVH_LEAF ? "16" : "4");
        snprintf(k->reason, sizeof k->reason,
                 "about %u leaves of up to %u triangles: %s has %u lane%s; tune's cheapest BVH "
                 "leaf is %u on 16 lanes (lrb16), %u on one (mcu-m4)",
                 (f->ntris + leaf - 1u) / leaf, leaf, r->machine, (unsigned)r->costs.lanes,
                 r->costs.lanes == 1u ? "" : "s",
                 LT_REC_BVH_LEAF, LT_REC_BVH_LEAF_NARROW);
    } else {
        k = add(r, "structure", "chunks");
        snprintf(k->reason, sizeof k->reason,
                 "%u triangles (<= %u): %u chunk box(es) of 16, nothing to build or walk",
                 f->ntris, LT_REC_BVH_MIN_TRIS, (unsigned)LT_CHUNK_COUNT(f->ntris));
        k = add(r, "leaf", "-");
        snprintf(k->reason, sizeof k->reason, "chunks have no leaf size");
    }
}
