/* lt_recommend.c - see lt_recommend.h. */
#include "tune/lt_recommend.h"
#include "lt/lt_cost.h"
#include "lt/lt_isect.h"
#include "render/lt_scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Every machine file's issue costs and quadtree rows (sim/lt_machines.h: data, no simulator). */
enum { QT_n64, QT_n32, QT_f32, QT__COUNT };
typedef struct rec_machine {
    const char *name;
    uint32_t lanes;
    uint16_t issue[LT_OP__COUNT];
    double qt[QT__COUNT][2]; /* LT_MACHINE_QT: build cycles per source pixel, rest per target */
} rec_machine_t;

static const rec_machine_t rec_machines[] = {
#define LT_MACHINE(id, nm, desc, clock_mhz, nlanes) {.name = nm, .lanes = nlanes,
#define LT_OP_COST(op, latency, cost) .issue[LT_OP_##op] = cost,
#define LT_MACHINE_QT(enc, build, rest) .qt[QT_##enc] = {build, rest},
#define LT_MACHINE_END },
#include "lt_machines.h"
    {.name = NULL}};

static const rec_machine_t *rec_machine(const char *name)
{
    const rec_machine_t *m;
    for (m = rec_machines; m->name != NULL; m++)
        if (name != NULL && strcmp(m->name, name) == 0)
            return m;
    return NULL;
}

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
    const rec_machine_t *m = rec_machine(name);
    memset(c, 0, sizeof *c);
    if (m == NULL)
        return -1;
    c->f32 = mix_cost(lt_rec_tri_f32, m->issue);
    c->q16 = mix_cost(lt_rec_tri_q16, m->issue);
    c->lanes = m->lanes;
    return 0;
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

/* ---- depth images ---- */

/* A depth that is a surface: finite and > 0 (NaN compares false). */
static int depth_ok(double v) { return v > 0.0 && v <= 3.5e38; }

/* 1 when the depths a and b (both valid) differ by more than LT_REC_JUMP_REL of the nearer. */
static int depth_jump(double a, double b) { return fabs(a - b) > LT_REC_JUMP_REL * (a < b ? a : b); }

void lt_rec_depth_scan(const float *z, uint32_t width, uint32_t height, lt_rec_depth_facts_t *f)
{
    uint32_t x, y;
    memset(f, 0, sizeof *f);
    f->width = width;
    f->height = height;
    for (y = 0; y < height; y++)
        for (x = 0; x < width; x++) {
            size_t i = (size_t)y * width + x;
            double v = (double)z[i], l = 0.0, rt = 0.0, u = 0.0, d = 0.0;
            if (!depth_ok(v)) {
                f->holes++;
                continue;
            }
            if (f->valid == 0 || v < f->zmin)
                f->zmin = v;
            if (f->valid == 0 || v > f->zmax)
                f->zmax = v;
            f->valid++;
            if (x > 0)
                l = (double)z[i - 1];
            if (x + 1 < width)
                rt = (double)z[i + 1];
            if (y > 0)
                u = (double)z[i - width];
            if (y + 1 < height)
                d = (double)z[i + width];
            if (depth_ok(rt)) {
                f->pairs++;
                f->jumps += (uint64_t)depth_jump(v, rt);
            }
            if (depth_ok(d)) {
                f->pairs++;
                f->jumps += (uint64_t)depth_jump(v, d);
            }
            if (depth_ok(l) && depth_ok(rt) && depth_ok(u) && depth_ok(d)) {
                double w = 1.0 / v, lx = 1.0 / l - 2.0 * w + 1.0 / rt, ly = 1.0 / u - 2.0 * w + 1.0 / d;
                f->inner++;
                f->planar += (uint64_t)(fabs(lx) + fabs(ly) <= LT_REC_PLANAR_REL * w);
            }
        }
}

double lt_rec_qt_cost(const char *machine, const char *enc, double src_px, double dst_px)
{
    const rec_machine_t *m = rec_machine(machine);
    int e = enc == NULL ? -1 : strcmp(enc, "n64") == 0 ? QT_n64 : strcmp(enc, "n32") == 0 ? QT_n32
                             : strcmp(enc, "f32") == 0 ? QT_f32 : -1;
    if (m == NULL || e < 0)
        return 0.0;
    return m->qt[e][0] * src_px + m->qt[e][1] * dst_px;
}

void lt_recommend_depth(const lt_rec_depth_facts_t *f, lt_rec_t *r)
{
    lt_rec_pick_t *k;
    double zref, step, src = (double)f->width * f->height;
    double dst = f->target_px ? (double)f->target_px : src, c64, cf;
    char size[96];
    memset(r, 0, sizeof *r);
    r->machine = f->machine != NULL && rec_machine(f->machine) != NULL ? f->machine : "lrb16";
    (void)lt_rec_machine_costs(r->machine, &r->costs);
    if (f->valid == 0) {
        k = add(r, "num", "n64");
        snprintf(k->reason, sizeof k->reason, "no valid depth (%llu holes): nothing to weigh, "
                 "the default kept", (unsigned long long)f->holes);
        return;
    }
    r->range_log2 = log2(f->zmax / f->zmin);
    /* z_ref: the largest power of two strictly below the nearest depth (docs/quadtree.md 1);
       s1.30's relative step at the farthest depth is 2^-31 / (z_ref / zmax) */
    zref = ldexp(1.0, (int)ceil(log2(f->zmin)) - 1);
    step = ldexp(1.0, -31) * f->zmax / zref;
    c64 = lt_rec_qt_cost(r->machine, "n64", src, dst);
    cf = lt_rec_qt_cost(r->machine, "f32", src, dst);
    if (f->target_px)
        snprintf(size, sizeof size, "%ux%u to %llu target pixels", f->width, f->height,
                 (unsigned long long)f->target_px);
    else
        snprintf(size, sizeof size, "%ux%u to the same size", f->width, f->height);
    if (c64 <= 0.0 || cf <= 0.0) {
        k = add(r, "num", "n64");
        snprintf(k->reason, sizeof k->reason, "the machine file of %s has no quadtree rows "
                 "(LT_MACHINE_QT, tests/bench/qtcal.sh): the default kept", r->machine);
    } else if (step > ldexp(1.0, -24)) {
        k = add(r, "num", "f32");
        snprintf(k->reason, sizeof k->reason,
                 "depths %.4g..%.4g (range 2^%.1f): s1.30 w = z_ref / z steps %.2g of the depth at "
                 "the far end, coarser than float32's 6e-08 everywhere",
                 f->zmin, f->zmax, r->range_log2, step);
    } else if (c64 <= cf) {
        k = add(r, "num", "n64");
        snprintf(k->reason, sizeof k->reason,
                 "depths %.4g..%.4g (range 2^%.1f): s1.30 steps %.2g of the depth at the far end, "
                 "as fine as float32, and cheaper on %s: %s, %.3g cycles against %.3g in float32 "
                 "nodes (the machine's quadtree rows, tests/bench/qtcal.sh)",
                 f->zmin, f->zmax, r->range_log2, step, r->machine, size, c64, cf);
    } else {
        k = add(r, "num", "f32");
        snprintf(k->reason, sizeof k->reason,
                 "depths %.4g..%.4g (range 2^%.1f): s1.30 (n64) would be as fine (steps %.2g at the "
                 "far end) but float32 nodes are cheaper on %s: %s, %.3g cycles against %.3g in "
                 "n64 (the machine's quadtree rows, tests/bench/qtcal.sh)",
                 f->zmin, f->zmax, r->range_log2, step, r->machine, size, cf, c64);
    }
}
