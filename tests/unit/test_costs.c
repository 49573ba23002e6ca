/* test_costs.c - the cost recipes (firmware/include/lt/lt_recipes.def) and the kernels' documented
 * costs. In the sim build: every recipe charges exactly its ops times n (LT_CHARGE_N), has a reason
 * and at least one op; and every public kernel of screen/, frusta/ and object/ (but the kd-tree
 * and grid walks), run on fixed inputs, charges exactly what the Cost: line of its header says:
 *   - straight-line kernels (ray set-ups, slab and triangle tests, the reprojected-ray program,
 *     the frusta set-ups, ray generators, direct light and filter): their op lists, summed over
 *     phases or per phase;
 *   - walks and builds: the charge per phase composed from the pieces their Cost: lines name
 *     (recipes times their count, plain lane ops by class, the kernels they call as those charge
 *     alone) for the walk the fixed input takes, which the test knows by construction and checks
 *     through the hit records: the quadtree, DDA and Hi-Z on 1x1 and 2x1 images (bad rays, one
 *     hit; box, descend, pass, advance, crack or occlusion), their builds on 1x1, 2x2 and 2x1
 *     images, the shadow and primary frusta and their packet baselines on a one-leaf tree, the
 *     BVH, quantised BVH and chunk walks on a one-triangle scene, the one-triangle builds;
 *   - entry points documented "Cost: none" charge nothing.
 * A piece function here (qt_visit, fr_tri, ...) mirrors one clause of a Cost: line; when a kernel's
 * charges change, its Cost: line, its recipes and the piece change together.
 * In other builds the cost checks are skipped with a printed line.
 * Builds: host, sim, asan.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lt/lt.h"
#include "lt/lt_bvh.h"
#include "lt/lt_isect.h"
#include "lt/lt_wt.h"
#include "lt/lt_qt.h"
#include "lt/lt_hiz.h"
#include "lt/lt_ssdda.h"
#include "lt/lt_reproj.h"
#include "lt/lt_frusta.h"
#include "lt/lt_kd.h"
#include "lt/lt_grid.h"
#include "lt_test_util.h"
#include "tune/lt_recommend.h"
#if LT_COST_MODE == LT_COST_SIM
#include "lt_sim.h"
#endif

/* ---- the recipe table, as data --------------------------------------------------------------- */

typedef struct want {
    int op;
    uint64_t n;
} want_t;
#define W(op, n) { LT_OP_##op, (n) }

typedef struct recipe_row {
    const char *name;
    const char *doc;
    uint32_t n[LT_OP__COUNT]; /* count per op class */
} recipe_row_t;

#define LT_R(op, k) r.n[LT_OP_##op] += (uint32_t)(k);
#define LT_RECIPE(nm_, doc_, ops)                                                                  \
    static recipe_row_t row_##nm_(void)                                                            \
    {                                                                                              \
        recipe_row_t r;                                                                            \
        memset(&r, 0, sizeof r);                                                                   \
        r.name = #nm_;                                                                             \
        r.doc = doc_;                                                                              \
        ops return r;                                                                              \
    }
#include "lt/lt_recipes.def"
#undef LT_RECIPE

typedef recipe_row_t (*row_fn)(void);
static const row_fn rows[] = {
#define LT_RECIPE(name, doc, ops) row_##name,
#include "lt/lt_recipes.def"
#undef LT_RECIPE
};
#undef LT_R

static void test_recipe_table(void **state)
{
    size_t i;
    (void)state;
    assert_int_equal(sizeof rows / sizeof rows[0], LT_RC__COUNT);
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        recipe_row_t r = rows[i]();
        uint32_t sum = 0;
        int op;
        for (op = 0; op < (int)LT_OP__COUNT; op++)
            sum += r.n[op];
        if (sum == 0 || strlen(r.doc) < 10)
            ltt_report("  FAIL recipe %s: no ops or no reason\n", r.name);
        assert_true(sum > 0);
        assert_true(strlen(r.doc) >= 10);
    }
    ltt_report("recipes: %d in lt_recipes.def, each with a reason and its ops\n", (int)LT_RC__COUNT);
}

#if LT_COST_MODE == LT_COST_SIM

static void snap(uint64_t c[LT_OP__COUNT])
{
    lt_sim_totals_t t;
    int ph, op;
    lt_sim_totals(&t);
    for (op = 0; op < (int)LT_OP__COUNT; op++) {
        c[op] = 0;
        for (ph = 0; ph < (int)LT_PH__COUNT; ph++)
            c[op] += t.ctr[ph][op];
    }
}

/* Compare the ops charged since b with the documented list (ops not listed: 0). */
static int verify(const char *name, const uint64_t b[LT_OP__COUNT], const want_t *w, size_t nw)
{
    uint64_t now[LT_OP__COUNT];
    int op, bad = 0;
    size_t j;
    snap(now);
    for (op = 0; op < (int)LT_OP__COUNT; op++) {
        uint64_t want = 0, got = now[op] - b[op];
        for (j = 0; j < nw; j++)
            if (w[j].op == op)
                want += w[j].n;
        if (got != want) {
            ltt_report("  FAIL %s: %s x%llu charged, documented x%llu\n", name, lt_sim_op_name(op),
                       (unsigned long long)got, (unsigned long long)want);
            bad++;
        }
    }
    if (bad == 0)
        ltt_report("%s: charges as documented\n", name);
    return bad;
}

#define CHECK(name, expr, ...)                                                                     \
    do {                                                                                           \
        uint64_t b_[LT_OP__COUNT];                                                                 \
        static const want_t w_[] = { __VA_ARGS__ };                                                \
        snap(b_);                                                                                  \
        (void)(expr);                                                                              \
        bad += verify(name, b_, w_, sizeof w_ / sizeof w_[0]);                                     \
    } while (0)

static void sim_start(void)
{
    lt_diag_t diag;
    assert_int_equal(lt_sim_init(lt_sim_machine_find("lrb16"), NULL, NULL, &diag), 0);
    lt_sim_reset();
}

static void test_recipe_charges(void **state)
{
    int bad = 0;
    (void)state;
    sim_start();
    /* every recipe: LT_CHARGE_N(R, 3) charges 3 x its ops, nothing else */
#define LT_R(op, k)
#define LT_RECIPE(name, doc, ops)                                                                  \
    do {                                                                                           \
        uint64_t b_[LT_OP__COUNT], a_[LT_OP__COUNT];                                               \
        recipe_row_t r_ = row_##name();                                                            \
        int op_;                                                                                   \
        snap(b_);                                                                                  \
        LT_CHARGE_N(name, 3);                                                                      \
        snap(a_);                                                                                  \
        for (op_ = 0; op_ < (int)LT_OP__COUNT; op_++)                                              \
            if (a_[op_] - b_[op_] != 3u * r_.n[op_]) {                                             \
                ltt_report("  FAIL LT_CHARGE_N(%s, 3): %s\n", #name, lt_sim_op_name(op_));         \
                bad++;                                                                             \
            }                                                                                      \
    } while (0);
#include "lt/lt_recipes.def"
#undef LT_RECIPE
#undef LT_R
    ltt_report("recipe charges: LT_CHARGE_N of each of %d recipes, %d mismatches\n",
               (int)LT_RC__COUNT, bad);
    assert_int_equal(bad, 0);
}

/* ---- fixed inputs: 16 rays from (0, 0, -8) towards +z, spread a little in x and y ----------- */

static void make_q16(lt_ray16_q16_t *r, lt_ray1_q16_t r1[LT_LANES])
{
    int i;
    memset(r, 0, sizeof *r);
    for (i = 0; i < LT_LANES; i++) {
        double dx = 0.01 * (i % 4) - 0.015, dy = 0.01 * (i / 4) - 0.015;
        double n = 1.0 / sqrt(dx * dx + dy * dy + 1.0);
        r->ox.l[i] = LT_Q16(dx * 0.25);
        r->oy.l[i] = LT_Q16(dy * 0.25);
        r->oz.l[i] = LT_Q16(-8.0);
        r->dx.l[i] = (lt_q30_t)(dx * n * 1073741824.0);
        r->dy.l[i] = (lt_q30_t)(dy * n * 1073741824.0);
        r->dz.l[i] = (lt_q30_t)(n * 1073741823.0);
        r->tmin.l[i] = 0;
        r->tmax.l[i] = LT_Q16(100.0);
        memset(&r1[i], 0, sizeof r1[i]);
        r1[i].o[0] = r->ox.l[i];
        r1[i].o[1] = r->oy.l[i];
        r1[i].o[2] = r->oz.l[i];
        r1[i].d[0] = r->dx.l[i];
        r1[i].d[1] = r->dy.l[i];
        r1[i].d[2] = r->dz.l[i];
        r1[i].tmin = 0;
        r1[i].tmax = LT_Q16(100.0);
    }
}

/* A triangle across the rays at z = 0 (hit), and one far off to the side (miss). */
static void make_tris(lt_tri_q16_t *hit, lt_tri_q16_t *miss)
{
    memset(hit, 0, sizeof *hit);
    hit->v0[0] = LT_Q16(-2.0);
    hit->v0[1] = LT_Q16(-2.0);
    hit->e1[0] = LT_Q16(6.0);
    hit->e2[1] = LT_Q16(6.0);
    *miss = *hit;
    miss->v0[0] = LT_Q16(50.0);
}

static void test_kernel_costs_q16(void **state)
{
    lt_ray16_q16_t r;
    lt_ray1_q16_t r1[LT_LANES];
    lt_aabb_q16_t box = { { LT_Q16(-1.0), LT_Q16(-1.0), LT_Q16(-1.0) },
                          { LT_Q16(1.0), LT_Q16(1.0), LT_Q16(1.0) } };
    lt_tri_q16_t th, tm;
    lt_vq16_t tn;
    lt_q16_t t1;
    lt_hit16_t hit;
    lt_wt16_q16_t w;
    int bad = 0;
    (void)state;
    sim_start();
    make_q16(&r, r1);
    make_tris(&th, &tm);
    hit.id = lt_vi32_set1(-1);
    /* lt_isect.h */
    CHECK("lt_ray16_q16_setup", (lt_ray16_q16_setup(&r), 0), W(VDIV, 3), W(VCMP, 9), W(VBCAST, 9));
    CHECK("lt_slab16_q16 (16 lanes, no flagged axis)", lt_slab16_q16(&r, 0xFFFFu, &box, &tn),
          W(VALU, 19), W(VMUL, 6), W(VCMP, 1), W(SLOAD, 6), W(VBCAST, 6), W(MASK, 3));
    /* lt_bvh.h: the single-ray kernels */
    CHECK("lt_ray1_q16_setup", (lt_ray1_q16_setup(&r1[0]), 0), W(SDIV, 3), W(SALU, 9));
    CHECK("lt_slab1_q16", lt_slab1_q16(&r1[0], &box, &t1), W(SLOAD, 6), W(SALU, 14), W(SMUL, 6),
          W(BRANCH, 4));
    CHECK("lt_tri1_q16 (miss)", lt_tri1_q16(&r1[0], &tm), W(SLOAD, 9), W(SMUL, 24), W(SALU, 24),
          W(BRANCH, 2));
    CHECK("lt_tri1_q16 (hit)", lt_tri1_q16(&r1[0], &th), W(SLOAD, 9), W(SMUL, 24), W(SALU, 24),
          W(BRANCH, 2), W(SDIV, 1));
    /* lt_wt.h */
    CHECK("lt_ray16_wt_setup_q16", lt_ray16_wt_setup_q16(&r, &w), W(VALU, 18), W(VSHIFT, 1), W(VCMP, 5),
          W(VDIV, 3), W(VBCAST, 1), W(MASK, 23));
    CHECK("lt_tri16_wt_q16 (one permutation, miss)",
          lt_tri16_wt_q16(&r, &w, 0xFFFFu, &tm, 0, &hit), W(SLOAD, 9), W(SALU, 15), W(SMUL, 6),
          W(BRANCH, 1), W(MASK, 27), W(VBCAST, 10), W(VALU, 15), W(VMUL, 12), W(VMULW, 5),
          W(VCMP, 8));
    {
        lt_wt1_q16_t w1;
        lt_q16_t tmx = r1[0].tmax;
        CHECK("lt_ray1_wt_setup_q16", lt_ray1_wt_setup_q16(r1[0].o, r1[0].d, &w1), W(SALU, 12),
              W(SDIV, 3), W(BRANCH, 2));
        CHECK("lt_tri1_wt_q16 (hit)", lt_tri1_wt_q16(&w1, &th, r1[0].tmin, &tmx), W(SLOAD, 9),
              W(SALU, 27 + 9 + 12), W(SMUL, 12 + 6 + 9), W(BRANCH, 2 + 1), W(SDIV, 2));
    }
    assert_int_equal(bad, 0);
}

/* One packet traversal step: a one-triangle tree is a root leaf; trace16 = the root's slab test,
 * one node step (BVH_TRAV_NODE), one leaf triangle (BVH_TRAV_LEAF_TRI, the triangle test) and the
 * leaf's exit test (BVH_TRAV_ANY_EXIT), plus the call's VBCAST x2. Checked against the same kernels run alone. */
static void test_bvh_step_q16(void **state)
{
    static uint64_t arena[1024];
    size_t need = 0;
    lt_ray16_q16_t r, r2;
    lt_ray1_q16_t r1[LT_LANES];
    lt_tri_q16_t th, tm;
    lt_bvh_t bvh;
    lt_hit16_t hit;
    lt_vq16_t tn;
    uint64_t b[LT_OP__COUNT], a[LT_OP__COUNT], k[LT_OP__COUNT];
    int op, bad = 0;
    (void)state;
    sim_start();
    make_q16(&r, r1);
    make_tris(&th, &tm);
    lt_ray16_q16_setup(&r);
    r2 = r;
    assert_int_equal(lt_bvh_size(1, NULL, &need), LT_OK);
    assert_true(need <= sizeof arena);
    assert_int_equal(lt_bvh_build_q16(&bvh, NULL, &th, 1, arena, sizeof arena), LT_OK);
    bvh.isect = LT_ISECT_MT; /* the walks' Cost lines are composed with lt_tri16 (the MT option) */
    assert_int_equal(bvh.nnodes, 1);
    /* the kernels alone, on a copy of the packet */
    snap(b);
    (void)lt_slab16_q16(&r2, 0xFFFFu, &((const lt_bvh_node_q16_t *)bvh.nodes)[0].b, &tn);
    hit.id = lt_vi32_set1(-1);
    (void)lt_tri16_q16(&r2, 0xFFFFu, &th, 0, &hit);
    LT_CHARGE(BVH_TRAV_NODE);
    LT_CHARGE(BVH_TRAV_LEAF_TRI);
    LT_CHARGE(BVH_TRAV_ANY_EXIT);
    snap(a);
    for (op = 0; op < (int)LT_OP__COUNT; op++)
        k[op] = a[op] - b[op];
    k[LT_OP_VBCAST] += 2; /* the call's tnear vectors of the two children, set to 0 */
    /* the traversal */
    snap(b);
    assert_int_equal(lt_bvh_trace16_q16(&bvh, &th, &r, 0xFFFFu, &hit), LT_OK);
    snap(a);
    for (op = 0; op < (int)LT_OP__COUNT; op++)
        if (a[op] - b[op] != k[op]) {
            ltt_report("  FAIL lt_bvh_trace16_q16 step: %s x%llu, slab + node + tri + exit x%llu\n",
                       lt_sim_op_name(op), (unsigned long long)(a[op] - b[op]),
                       (unsigned long long)k[op]);
            bad++;
        }
    if (bad == 0)
        ltt_report("lt_bvh_trace16_q16 (one leaf): slab + BVH_TRAV_NODE + BVH_TRAV_LEAF_TRI + "
                   "lt_tri16_q16 + BVH_TRAV_ANY_EXIT\n");
    assert_int_equal(bad, 0);
}

#if LT_CFG_FLOAT32
static void test_kernel_costs_f32(void **state)
{
    lt_ray16_f32_t r;
    lt_ray1_f32_t r1;
    lt_aabb_f32_t box = { { -1.0f, -1.0f, -1.0f }, { 1.0f, 1.0f, 1.0f } };
    lt_vf32_t tn;
    float t1;
    lt_wt16_f32_t w;
    int i, bad = 0;
    (void)state;
    sim_start();
    memset(&r, 0, sizeof r);
    memset(&r1, 0, sizeof r1);
    for (i = 0; i < LT_LANES; i++) {
        r.ox.l[i] = 0.0f;
        r.oy.l[i] = 0.0f;
        r.oz.l[i] = -8.0f;
        r.dx.l[i] = 0.01f * (float)(i % 4) - 0.015f;
        r.dy.l[i] = 0.01f * (float)(i / 4) - 0.015f;
        r.dz.l[i] = 1.0f;
        r.tmax.l[i] = 100.0f;
    }
    r1.o[2] = -8.0f;
    r1.d[0] = 0.005f;
    r1.d[1] = 0.005f;
    r1.d[2] = 1.0f;
    r1.tmax = 100.0f;
    CHECK("lt_ray16_f32_setup", (lt_ray16_f32_setup(&r), 0), W(FDIV, 3), W(FCMP, 6), W(VALU, 3),
          W(VBCAST, 3));
    CHECK("lt_ray1_f32_setup", (lt_ray1_f32_setup(&r1), 0), W(SDIV, 3), W(SALU, 9));
    CHECK("lt_slab1_f32", lt_slab1_f32(&r1, &box, &t1), W(SLOAD, 6), W(SALU, 14), W(SMUL, 6),
          W(BRANCH, 4));
    CHECK("lt_ray16_wt_setup_f32", lt_ray16_wt_setup_f32(&r, &w), W(FADD, 16), W(FCMP, 5),
          W(FDIV, 3), W(VBCAST, 2), W(MASK, 23));
    {
        /* one permutation, candidate lanes: a triangle across every ray at z = 0 */
        lt_tri_f32_t t;
        lt_hit16_t h;
        memset(&t, 0, sizeof t);
        t.v0[0] = t.v0[1] = -2.0f;
        t.e1[0] = 6.0f;
        t.e2[1] = 6.0f;
        h.id = lt_vi32_set1(-1);
        CHECK("lt_tri16_wt_f32 (one permutation, candidate lanes)",
              lt_tri16_wt_f32(&r, &w, 0xFFFFu, &t, 0, &h), W(SLOAD, 9), W(SALU, 15), W(SMUL, 6),
              W(BRANCH, 1), W(MASK, 30), W(VBCAST, 11), W(VALU, 1), W(FADD, 23), W(FMUL, 18),
              W(FDIV, 1), W(FCMP, 13));
        bad += h.id.l[0] != 0;
    }
    (void)tn;
    assert_int_equal(bad, 0);
}

/* lanetrace info's numeric pick (host/tune/lt_recommend) prices each path by the ops one call of
 * its watertight triangle test charges for 16 missing rays: those lists are what the kernels charge. */
static int verify_mix(const char *name, const uint64_t b[LT_OP__COUNT], const lt_rec_op_t *mix)
{
    want_t w[LT_OP__COUNT];
    size_t n = 0;
    for (; mix->n != 0 && n < LT_OP__COUNT; mix++, n++) {
        w[n].op = mix->op;
        w[n].n = mix->n;
    }
    return verify(name, b, w, n);
}

static void test_recommend_mix(void **state)
{
    lt_ray16_q16_t rq;
    lt_ray1_q16_t r1[LT_LANES];
    lt_tri_q16_t th, tm;
    lt_wt16_q16_t wq;
    lt_ray16_f32_t rf;
    lt_wt16_f32_t wf;
    lt_tri_f32_t tf;
    lt_hit16_t h;
    uint64_t b[LT_OP__COUNT];
    int i, bad = 0;
    lt_mask16_t k;
    (void)state;
    sim_start();
    make_q16(&rq, r1);
    make_tris(&th, &tm);
    memset(&rf, 0, sizeof rf);
    for (i = 0; i < LT_LANES; i++) {
        rf.ox.l[i] = (float)rq.ox.l[i] / 65536.0f;
        rf.oy.l[i] = (float)rq.oy.l[i] / 65536.0f;
        rf.oz.l[i] = -8.0f;
        rf.dx.l[i] = (float)rq.dx.l[i] / 1073741824.0f;
        rf.dy.l[i] = (float)rq.dy.l[i] / 1073741824.0f;
        rf.dz.l[i] = (float)rq.dz.l[i] / 1073741824.0f;
        rf.tmax.l[i] = 100.0f;
    }
    memset(&tf, 0, sizeof tf);
    tf.v0[0] = 50.0f;
    tf.v0[1] = -2.0f;
    tf.e1[0] = 6.0f;
    tf.e2[1] = 6.0f;
    (void)lt_ray16_wt_setup_q16(&rq, &wq);
    (void)lt_ray16_wt_setup_f32(&rf, &wf);
    h.id = lt_vi32_set1(-1);
    snap(b);
    k = lt_tri16_wt_q16(&rq, &wq, 0xFFFFu, &tm, 0, &h);
    bad += verify_mix("lt_rec_tri_q16 = lt_tri16_wt_q16 on 16 missing rays", b, lt_rec_tri_q16);
    bad += k != 0;
    snap(b);
    k = lt_tri16_wt_f32(&rf, &wf, 0xFFFFu, &tf, 0, &h);
    bad += verify_mix("lt_rec_tri_f32 = lt_tri16_wt_f32 on 16 missing rays", b, lt_rec_tri_f32);
    bad += k != 0;
    assert_int_equal(bad, 0);
}
#endif

/* ==== kernels with data-dependent walks: expected charges composed from the Cost: lines ======= */

/* Counters per phase and op class. The expected charge of a call is built from the pieces its
 * Cost: line names (recipes of lt_recipes.def times their count, plain lane ops by class) for the
 * walk the fixed inputs take (known by construction and checked through the hit records). */
typedef struct cost {
    uint64_t n[LT_PH__COUNT][LT_OP__COUNT];
} cost_t;

static void csnap(cost_t *c)
{
    lt_sim_totals_t t;
    int ph, op;
    lt_sim_totals(&t);
    for (ph = 0; ph < (int)LT_PH__COUNT; ph++)
        for (op = 0; op < (int)LT_OP__COUNT; op++)
            c->n[ph][op] = t.ctr[ph][op];
}

static void crow(cost_t *c, int ph, recipe_row_t r, uint64_t k)
{
    int op;
    for (op = 0; op < (int)LT_OP__COUNT; op++)
        c->n[ph][op] += (uint64_t)r.n[op] * k;
}

/* In a piece function with `cost_t *c` and a phase `ph`: a recipe, a lane op by class name, a lane
 * op by id. */
#define CR(name, k) crow(c, ph, row_##name(), (uint64_t)(k))
#define CL(op, k) (c->n[ph][LT_OP_##op] += (uint64_t)(k))
#define CO(opid, k) (c->n[ph][(opid)] += (uint64_t)(k))

static int cverify(const char *name, const cost_t *b, const cost_t *want)
{
    cost_t a;
    int ph, op, bad = 0;
    csnap(&a);
    for (ph = 0; ph < (int)LT_PH__COUNT; ph++)
        for (op = 0; op < (int)LT_OP__COUNT; op++) {
            uint64_t got = a.n[ph][op] - b->n[ph][op];
            if (got != want->n[ph][op]) {
                ltt_report("  FAIL %s: %s %s x%llu charged, documented x%llu\n", name,
                           lt_sim_phase_name(ph), lt_sim_op_name(op), (unsigned long long)got,
                           (unsigned long long)want->n[ph][op]);
                bad++;
            }
        }
    if (bad == 0)
        ltt_report("%s: charges as documented\n", name);
    return bad;
}

#define CHECKC(name, expr, want)                                                                   \
    do {                                                                                           \
        cost_t b_;                                                                                 \
        csnap(&b_);                                                                                \
        (void)(expr);                                                                              \
        bad += cverify(name, &b_, want);                                                           \
    } while (0)

/* The classes of the generic lane ops of the two numeric paths of a screen-space tracer (q30:
 * f = 0, float32: f = 1): V (t, w narrow) blend / min / max / add, V compares, W (wide values
 * along the ray) arithmetic, W compares. */
#define VB (f ? LT_OP_FADD : LT_OP_VALU)
#define VC (f ? LT_OP_FCMP : LT_OP_VCMP)
#define WA (f ? LT_OP_FADD : LT_OP_VMULW)
#define WC (f ? LT_OP_FCMP : LT_OP_VCMP)

/* ---- lt_ssb.h's routines, as their Cost: lines say ---- */

static void ssb_tcross(cost_t *c, int ph, int f)
{
    if (f)
        CR(SSB_F_TCROSS, 1);
    else
        CR(SSB_Q_TCROSS, 1);
}

static void ssb_wray(cost_t *c, int ph, int f, unsigned n)
{
    if (f)
        CR(SSB_F_WRAY, n);
    else
        CR(SSB_Q_WRAY, n);
}

static void ssb_hit_t(cost_t *c, int ph, int f)
{
    if (f)
        CR(SSB_F_HIT_T, 1);
    else
        CR(SSB_Q_HIT_T, 1);
}

/* the clip: SSB_*_CLIP, four crossings, per axis two int blends, four set1, a max, a min and two
 * V blends, the final compare */
static void ssb_clip(cost_t *c, int ph, int f)
{
    if (f)
        CR(SSB_F_CLIP, 1);
    else
        CR(SSB_Q_CLIP, 1);
    ssb_tcross(c, ph, f);
    ssb_tcross(c, ph, f);
    ssb_tcross(c, ph, f);
    ssb_tcross(c, ph, f);
    CL(VALU, 4);
    CL(VBCAST, 8);
    CO(VB, 8);
    CO(VC, 1);
}

/* lt__ssb_setup_*: the clip and the major axis */
static void ssb_setup(cost_t *c, int ph, int f)
{
    ssb_clip(c, ph, f);
    if (f)
        CR(SSB_F_MAJOR, 1);
    else
        CR(SSB_Q_MAJOR, 1);
}

/* lt__ssb_child_side_*: a crossing and two compares for moving lanes, SSB_*_SIDE_PAR for the
 * parallel ones */
static void ssb_side(cost_t *c, int ph, int f, int moving, int parallel)
{
    if (moving) {
        ssb_tcross(c, ph, f);
        CO(VC, 2);
    }
    if (parallel) {
        if (f)
            CR(SSB_F_SIDE_PAR, 1);
        else
            CR(SSB_Q_SIDE_PAR, 1);
    }
}

static void ssb_gather_pix(cost_t *c, int ph, int f, unsigned lanes)
{
    CR(LANE_GATHER, lanes);
    if (f)
        CR(SSB_F_PIX_HOLES, 1);
    else
        CR(SSB_Q_PIX_HOLES, 1);
}

static void ssb_shell(cost_t *c, int ph, int f)
{
    if (f) {
        CR(SSB_F_SHELL_LO, 1);
    } else {
        CR(SSB_Q_SHELL_LO, 1);
        CR(SSB_Q_SHELL_HI, 1);
    }
}

/* ---- lt_qt_trace16_*: the pieces of its Cost: line (lt_qt.h) ---- */

static void qt_call(cost_t *c, int f)
{
    int ph = LT_PH_OTHER; /* the caller's phase: the layer counter's set1 */
    CL(VBCAST, 1);
    ph = LT_PH_SETUP;
    ssb_clip(c, ph, f);
    ph = LT_PH_TRAVERSE;
    if (f)
        CR(SSB_F_WRAY, 1);
    else
        CR(SSB_Q_W_AT, 1);
    CL(VALU, 11);
    CO(VB, 3);
    CL(VBCAST, 6);
}

static void qt_layer(cost_t *c, int f, int last)
{
    int ph = LT_PH_TRAVERSE;
    CR(QT_TRACE_LAYER, 1);
    CL(VALU, 10 + (last ? 2 : 0));
    CO(VB, 5 + (last ? 1 : 0));
    CL(VBCAST, 13 + (last ? 1 : 0));
}

/* one node visit by `lanes` lanes of node format enc (0 n64, 1 n32, 2 f32) */
static void qt_visit(cost_t *c, int enc, unsigned lanes)
{
    int ph = LT_PH_TRAVERSE, f = enc == 2;
    CR(QT_WALK_STEP, 1);
    CR(QT_WALK_NODE, 1);
    CR(QTGRID_INDEX, 1);
    CR(LANE_GATHER, f ? 2u * lanes : lanes);
    if (enc == 0)
        CR(QT_N64_DECODE, 1);
    else if (enc == 1)
        CR(QT_N32_DECODE, 1);
    else
        CR(QT_F_DECODE, 1);
    ssb_tcross(c, ph, f);
    ssb_tcross(c, ph, f);
    CL(VALU, 4);
    CL(VSHIFT, 2);
    CL(VCMP, 2);
    CL(VBCAST, 1);
    CO(VB, 5);
    CO(VC, 1);
}

static void qt_planes(cost_t *c, int f)
{
    int ph = LT_PH_TRAVERSE;
    if (f)
        CR(QT_F_PLANE_F, 2);
    else
        CR(QT_Q_PLANE_F, 2);
    CR(QT_WALK_PLANES, 1);
    CO(WC, 2);
    CL(VBCAST, 2);
    CL(VALU, 1);
    CO(VB, 2);
}

static void qt_cross(cost_t *c, int f)
{
    int ph = LT_PH_TRAVERSE;
    if (f)
        CR(QT_F_HIT_T, 1);
    else
        CR(SSB_Q_HIT_T, 1);
    CO(VB, 1);
}

static void qt_boxes(cost_t *c, int f)
{
    int ph = LT_PH_TRAVERSE;
    ssb_wray(c, ph, f, 2);
    CR(QT_WALK_BOXES, 1);
    CO(WA, 2);
    if (!f)
        CL(VCVT, 2);
    CO(WC, 6);
    CL(VALU, 1);
}

/* lt_qt_trace1_q30, one lane of the fixed inputs below: s 0 a bad ray (set-up only), 1 the
 * crossed plane, 2 the box, descent, passed plane, advance and crack */
static void qt1_lane(cost_t *c, int s)
{
    int ph = LT_PH_SETUP;
    CR(QT1_SETUP, 1);
    if (s == 1) /* dw < 0, no axis */
        CR(QT1_WLIM, 1);
    if (s == 2) { /* along x: its reciprocal and its two image edges */
        CR(QT1_RCP, 1);
        CR(QT1_CROSS, 2);
    }
    ph = LT_PH_TRAVERSE;
    CR(QT1_FINISH, 1);
    if (s == 1) {
        CR(QT1_LAYER, 1);
        CR(QT1_STEP, 1);
        /* a ray along w only (dx = dy = 0): no crossing on either axis */
        CR(QT1_PLANE, 1);
        CR(QT1_HIT_T, 1);
    } else if (s == 2) {
        CR(QT1_LAYER, 1);
        CR(QT1_STEP, 3);
        /* x's edges: the root's far edge 2, the midline 1 at the descent (the child's exit),
           then the far edge again, cached */
        CR(QT1_CROSS, 2);
        CR(QT1_BOX, 1);
        CR(QT1_DESCEND, 1);
        CR(QT1_PLANE, 2);
        CR(QT1_ADVANCE, 1);
    }
}

static void qt_descend(cost_t *c, int f, int xmove, int xpar, int ymove, int ypar)
{
    int ph = LT_PH_TRAVERSE;
    CL(VALU, 14);
    CL(VSHIFT, 2);
    ssb_side(c, ph, f, xmove, xpar);
    ssb_side(c, ph, f, ymove, ypar);
}

static void qt_advance(cost_t *c, int f)
{
    int ph = LT_PH_TRAVERSE;
    CR(QTGRID_OUTSIDE, 1);
    CR(QT_WALK_ADVANCE, 1);
    CO(VC, 2);
    CL(VALU, 12);
    CO(VB, 2);
    CL(VSHIFT, 2);
    CL(VBCAST, 1);
}

/* ---- lt_ssdda_trace16_* (lt_ssdda.h) ---- */

static void dda_call(cost_t *c, int f)
{
    int ph = LT_PH_OTHER;
    CL(VBCAST, 6);
    ph = LT_PH_SETUP;
    ssb_setup(c, ph, f);
    CR(DDA_POINT_LANES, 1);
    ph = LT_PH_TRAVERSE;
    if (f)
        CR(SSB_F_WRAY, 1);
    else
        CR(SSB_Q_W_AT, 1);
    CL(VALU, 9);
    CO(VB, 4);
    CL(VBCAST, 8);
}

static void dda_step(cost_t *c, int f)
{
    int ph = LT_PH_TRAVERSE;
    CR(DDA_WALK_STEP, 1);
    CR(DDA_WALK_END, 1);
    CR(DDA_INDEX, 1);
    if (f) {
        CR(SSB_F_TSPAN, 2);
        CR(SSB_F_PIXEL, 2);
    } else {
        CR(SSB_Q_TSPAN, 2);
        CR(SSB_Q_PIXEL, 2);
    }
    ssb_wray(c, ph, f, 2);
    CL(VALU, 8);
    CL(VCMP, 1);
    CL(VBCAST, 5);
    CO(VB, 7);
    CO(VC, 1);
    CO(WA, 2);
}

static void dda_layer(cost_t *c, int f, unsigned lanes, int last)
{
    int ph = LT_PH_TRAVERSE;
    ssb_gather_pix(c, ph, f, lanes);
    ssb_shell(c, ph, f);
    CR(DDA_WALK_LAYER, 1);
    CO(VC, 1);
    CL(VBCAST, 1);
    CO(WC, 2 + (last ? 1 : 0));
}

/* a layer whose shell the step meets; `entry`: the ray enters it inside the step (a crossing) */
static void dda_layer_hit(cost_t *c, int f, int entry)
{
    int ph = LT_PH_TRAVERSE;
    CR(DDA_WALK_LAYER_HIT, 1);
    CO(WC, 2);
    CO(VC, 1);
    CO(VB, 1);
    CL(VALU, 1);
    CL(VBCAST, 1);
    if (entry) {
        CO(WA, 6);
        ssb_hit_t(c, ph, f);
    }
}

/* the end of a step for hit lanes (hit) or lanes behind the deepest shell (occluded) */
static void dda_end(cost_t *c, int f, int hit, int occluded)
{
    int ph = LT_PH_TRAVERSE;
    if (hit) {
        CO(VB, 1);
        CL(VALU, 1);
    }
    if (occluded) {
        CO(VB, 1);
        CL(VALU, 1);
        CL(VBCAST, 1);
    }
}

/* ---- lt_hiz_trace16_* (lt_hiz.h) ---- */

/* hiz_start on one axis; `moving`: some lane moves on it */
static void hiz_start(cost_t *c, int f, int moving)
{
    int ph = LT_PH_SETUP;
    if (f)
        CR(SSB_F_PIXEL, 1);
    else
        CR(SSB_Q_PIXEL, 1);
    CL(VALU, 2);
    CL(VBCAST, 2);
    if (moving) {
        ssb_tcross(c, ph, f);
        ssb_tcross(c, ph, f);
        CL(VALU, 5);
        CL(VBCAST, 3);
        CO(VC, 4);
    }
}

static void hiz_call(cost_t *c, int f, int xmove, int ymove)
{
    int ph = LT_PH_OTHER;
    CL(VBCAST, 5);
    ph = LT_PH_SETUP;
    ssb_setup(c, ph, f);
    hiz_start(c, f, xmove);
    hiz_start(c, f, ymove);
    CL(VALU, 4);
    CL(VBCAST, 2);
    ph = LT_PH_TRAVERSE;
    if (f)
        CR(SSB_F_WRAY, 1);
    else
        CR(SSB_Q_W_AT, 1);
    CL(VALU, 9);
    CO(VB, 4);
    CL(VBCAST, 7);
}

static void hiz_visit(cost_t *c, int f)
{
    int ph = LT_PH_TRAVERSE;
    CR(HIZ_WALK_STEP, 1);
    CR(HIZ_WALK_CELL, 1);
    CR(QTGRID_INDEX, 1);
    ssb_tcross(c, ph, f);
    ssb_tcross(c, ph, f);
    ssb_wray(c, ph, f, 2);
    CL(VALU, 4);
    CL(VSHIFT, 2);
    CL(VCMP, 2);
    CL(VBCAST, 3);
    CO(VB, 4);
    CO(VC, 1);
    CO(WA, 2);
}

/* one layer of a cell visit: lanes at a pixel (k0) and at a cell (k1) */
static void hiz_layer(cost_t *c, int f, unsigned k0, unsigned k1, int last, int stop)
{
    int ph = LT_PH_TRAVERSE;
    CR(HIZ_WALK_LAYER, 1);
    CL(VBCAST, 2);
    if (k0 != 0) {
        ssb_gather_pix(c, ph, f, k0);
        CO(VC, 1);
        CL(VBCAST, 1);
    }
    if (k1 != 0) {
        CR(LANE_GATHER, k1);
        CR(HIZ_GATHER_SPLIT, 1);
        CO(VB, 2);
        CO(VC, 1);
    }
    ssb_shell(c, ph, f);
    CO(WC, 2);
    if (last) {
        CO(WC, 1);
        if (stop && k1 != 0) {
            if (f)
                CR(SSB_F_SHELL_LO, 1);
            else
                CR(SSB_Q_SHELL_LO, 1);
            CO(WC, 1);
            CO(WA, 4);
            CL(VBCAST, 1);
        }
    }
}

static void hiz_pixel_hit(cost_t *c, int f, int entry)
{
    int ph = LT_PH_TRAVERSE;
    CR(HIZ_WALK_PIXEL_HIT, 1);
    CO(WC, 2);
    CO(VC, 1);
    CO(VB, 1);
    CL(VALU, 1);
    CL(VBCAST, 1);
    if (entry) {
        CO(WA, 6);
        ssb_hit_t(c, ph, f);
    }
}

static void hiz_cell_hull(cost_t *c, int f)
{
    int ph = LT_PH_TRAVERSE;
    CO(WA, 4);
}

static void hiz_visit_end(cost_t *c, int f, int hit, int occluded)
{
    int ph = LT_PH_TRAVERSE;
    CL(VALU, 2);
    dda_end(c, f, hit, occluded);
}

static void hiz_descend(cost_t *c, int f, int entry, int xmove, int xpar, int ymove, int ypar)
{
    int ph = LT_PH_TRAVERSE;
    CR(HIZ_WALK_DESCEND, 1);
    CO(WC, 2);
    if (entry) {
        CO(WA, 6);
        ssb_hit_t(c, ph, f);
        CO(VB, 3);
        CL(VBCAST, 1);
    }
    CL(VALU, 14);
    CL(VSHIFT, 2);
    ssb_side(c, ph, f, xmove, xpar);
    ssb_side(c, ph, f, ymove, ypar);
}

static void hiz_advance(cost_t *c, int f)
{
    int ph = LT_PH_TRAVERSE;
    CR(QTGRID_OUTSIDE, 1);
    CR(HIZ_WALK_ADVANCE, 1);
    CO(VC, 2);
    CL(VCMP, 1);
    CL(VALU, 7);
    CL(VSHIFT, 2);
    CO(VB, 1);
}

/* ---- fixed inputs of the screen-space tracers ---- */

#define W_HALF (LT_Q30_ONE / 2)
static uint64_t g_arena[8192];

/* 16 equal lanes: a point ray at the centre of pixel (0, 0) from w = 1 to w = 0 (bad: w < 0), or
 * (move) a ray along row 0 from x = 0 to x = 2 at constant w = 0.3 */
static void sray_q30(lt_qray16_q30_t *r, int bad, int move)
{
    int i;
    memset(r, 0, sizeof *r);
    for (i = 0; i < LT_LANES; i++) {
        r->x.l[i] = move ? 0 : 32768;
        r->y.l[i] = 32768;
        r->w.l[i] = bad ? -1 : (move ? 322122547 : LT_Q30_ONE);
        r->dx.l[i] = move ? 2 * 65536 : 0;
        r->dw.l[i] = move ? 0 : -LT_Q30_ONE;
        r->tmax.l[i] = LT_Q30_ONE;
    }
}

static void sray_f32(lt_qray16_f32_t *r, int bad, int move)
{
    int i;
    memset(r, 0, sizeof *r);
    for (i = 0; i < LT_LANES; i++) {
        r->x.l[i] = move ? 0.0f : 0.5f;
        r->y.l[i] = 0.5f;
        r->w.l[i] = bad ? -1.0f : (move ? 0.3f : 1.0f);
        r->dx.l[i] = move ? 2.0f : 0.0f;
        r->dw.l[i] = move ? 0.0f : -1.0f;
        r->tmax.l[i] = 1.0f;
    }
}

typedef struct shit {
    int32_t status, nodes, aabb, planes;
} shit_t;

/* the walk the lanes took (all 16 lanes are equal) */
static int swalk(const char *name, const lt_qhit16_q30_t *hq, const lt_qhit16_f32_t *hf, int f,
                 int status, int nodes, int aabb, int planes)
{
    shit_t h;
    int i;
    for (i = 0; i < LT_LANES; i++) {
        h.status = f ? hf->status.l[i] : hq->status.l[i];
        h.nodes = f ? hf->nodes.l[i] : hq->nodes.l[i];
        h.aabb = f ? hf->aabb.l[i] : hq->aabb.l[i];
        h.planes = f ? hf->planes.l[i] : hq->planes.l[i];
        if (h.status != status || h.nodes != nodes || h.aabb != aabb || h.planes != planes) {
            ltt_report("  FAIL %s: lane %d walked status %d nodes %d aabb %d planes %d, the fixed "
                       "input's walk is %d %d %d %d\n",
                       name, i, h.status, h.nodes, h.aabb, h.planes, status, nodes, aabb, planes);
            return 1;
        }
    }
    return 0;
}

static void test_screen_walk_costs(void **state)
{
    static const char *const encn[3] = {"n64", "n32", "f32"};
    lt_q30_t w1q[2] = {W_HALF, W_HALF}, w2q[2] = {1 << 28, 1 << 29};
    float w1f[2] = {0.5f, 0.5f}, w2f[2] = {0.25f, 0.5f};
    lt_qray16_q30_t rq;
    lt_qray16_f32_t rf;
    lt_qhit16_q30_t hq;
    lt_qhit16_f32_t hf;
    char nm[160];
    int bad = 0, e, f, s;
    (void)state;
    sim_start();
    memset(&hq, 0, sizeof hq);
    memset(&hf, 0, sizeof hf);
    /* the quadtree: 1x1 (one plane node) and 2x1 (an AABB root over two planes) */
    for (e = 0; e < 3; e++) {
        f = e == 2;
        for (s = 0; s < 3; s++) {
            lt_qt_desc_t d;
            lt_qt_t qt;
            size_t bytes = sizeof g_arena;
            cost_t want;
            cost_t *c = &want;
            d.width = s == 2 ? 2u : 1u;
            d.height = 1;
            d.layers = 1;
            d.enc = e == 0 ? LT_QT_N64 : (e == 1 ? LT_QT_N32 : LT_QT_F32);
            if (f)
                assert_int_equal(
                    lt_qt_build_f32(&qt, &d, NULL, s == 2 ? w2f : w1f, g_arena, &bytes), LT_OK);
            else
                assert_int_equal(
                    lt_qt_build_q30(&qt, &d, NULL, s == 2 ? w2q : w1q, g_arena, &bytes), LT_OK);
            sray_q30(&rq, s == 0, s == 2);
            sray_f32(&rf, s == 0, s == 2);
            memset(&want, 0, sizeof want);
            qt_call(c, f);
            if (s == 1) { /* one node: a plane, crossed */
                qt_layer(c, f, 1);
                qt_visit(c, e, 16);
                qt_planes(c, f);
                qt_cross(c, f);
            } else if (s == 2) { /* root box, descend; pixel 0 passed, advance; pixel 1 a crack */
                qt_layer(c, f, 1);
                qt_visit(c, e, 16);
                qt_boxes(c, f);
                qt_descend(c, f, 1, 0, 0, 1);
                qt_visit(c, e, 16);
                qt_planes(c, f);
                qt_advance(c, f);
                qt_visit(c, e, 16);
                qt_planes(c, f);
            }
            snprintf(nm, sizeof nm, "lt_qt_trace16_%s (%s, %s)", f ? "f32" : "q30", encn[e],
                     s == 0 ? "bad rays" : (s == 1 ? "1x1, one plane crossed" :
                                                     "2x1: box, descend, pass, advance, crack"));
            if (f)
                CHECKC(nm, lt_qt_trace16_f32(&qt, &rf, LT_MASK_ALL, 0, &hf), &want);
            else
                CHECKC(nm, lt_qt_trace16_q30(&qt, &rq, LT_MASK_ALL, 0, &hq), &want);
            if (s == 1)
                bad += swalk(nm, &hq, &hf, f, LT_QT_HIT, 1, 0, 1);
            else if (s == 2)
                bad += swalk(nm, &hq, &hf, f, LT_QT_HIT, 3, 1, 2);
            if (!f) { /* the single-ray walk over the same input: per lane, scalar recipes */
                int i;
                memset(&want, 0, sizeof want);
                for (i = 0; i < 16; i++)
                    qt1_lane(c, s);
                snprintf(nm, sizeof nm, "lt_qt_trace1_q30 (%s, %s)", encn[e],
                         s == 0 ? "bad rays" : (s == 1 ? "1x1, one plane crossed" :
                                                         "2x1: box, descend, pass, advance, crack"));
                CHECKC(nm, lt_qt_trace1_q30(&qt, &rq, LT_MASK_ALL, 0, &hq), &want);
                if (s == 1)
                    bad += swalk(nm, &hq, &hf, 0, LT_QT_HIT, 1, 0, 1);
                else if (s == 2)
                    bad += swalk(nm, &hq, &hf, 0, LT_QT_HIT, 3, 1, 2);
            }
        }
    }
    /* the DDA: bad rays; 1x1, one step into the shell; 2x1, a step in front then behind */
    for (f = 0; f < 2; f++) {
        for (s = 0; s < 3; s++) {
            lt_ssb_desc_t d;
            lt_ssdda_t dda;
            cost_t want;
            cost_t *c = &want;
            d.width = s == 2 ? 2u : 1u;
            d.height = 1;
            d.layers = 1;
            d.enc = f ? LT_SSB_F32 : LT_SSB_Q30;
            if (f)
                assert_int_equal(lt_ssdda_init_f32(&dda, &d, NULL, s == 2 ? w2f : w1f), LT_OK);
            else
                assert_int_equal(lt_ssdda_init_q30(&dda, &d, NULL, s == 2 ? w2q : w1q), LT_OK);
            sray_q30(&rq, s == 0, s == 2);
            sray_f32(&rf, s == 0, s == 2);
            memset(&want, 0, sizeof want);
            dda_call(c, f);
            if (s == 1) {
                dda_step(c, f);
                dda_layer(c, f, 16, 1);
                dda_layer_hit(c, f, 1);
                dda_end(c, f, 1, 0);
            } else if (s == 2) {
                dda_step(c, f);
                dda_layer(c, f, 16, 1);
                dda_step(c, f);
                dda_layer(c, f, 16, 1);
                dda_end(c, f, 0, 1);
            }
            snprintf(nm, sizeof nm, "lt_ssdda_trace16_%s (%s)", f ? "f32" : "q30",
                     s == 0 ? "bad rays" : (s == 1 ? "1x1, one step, hit" :
                                                     "2x1: a step in front, one behind"));
            if (f)
                CHECKC(nm, lt_ssdda_trace16_f32(&dda, &rf, LT_MASK_ALL, 0, &hf), &want);
            else
                CHECKC(nm, lt_ssdda_trace16_q30(&dda, &rq, LT_MASK_ALL, 0, &hq), &want);
            if (s == 1)
                bad += swalk(nm, &hq, &hf, f, LT_QT_HIT, 1, 0, 1);
            else if (s == 2)
                bad += swalk(nm, &hq, &hf, f, LT_QT_OCCLUDED, 2, 0, 2);
        }
    }
    /* Hi-Z: bad rays; 1x1, the pixel hit; 2x1: pixel 0 passed, up to the cell, descend, pixel 1
     * behind */
    for (f = 0; f < 2; f++) {
        for (s = 0; s < 3; s++) {
            lt_ssb_desc_t d;
            lt_hiz_t hz;
            size_t bytes = sizeof g_arena;
            cost_t want;
            cost_t *c = &want;
            d.width = s == 2 ? 2u : 1u;
            d.height = 1;
            d.layers = 1;
            d.enc = f ? LT_SSB_F32 : LT_SSB_Q30;
            if (f)
                assert_int_equal(lt_hiz_build_f32(&hz, &d, NULL, s == 2 ? w2f : w1f, g_arena,
                                                  &bytes), LT_OK);
            else
                assert_int_equal(lt_hiz_build_q30(&hz, &d, NULL, s == 2 ? w2q : w1q, g_arena,
                                                  &bytes), LT_OK);
            sray_q30(&rq, s == 0, s == 2);
            sray_f32(&rf, s == 0, s == 2);
            memset(&want, 0, sizeof want);
            hiz_call(c, f, s == 2, 0);
            if (s == 1) {
                hiz_visit(c, f);
                hiz_layer(c, f, 16, 0, 1, 1);
                hiz_pixel_hit(c, f, 1);
                hiz_visit_end(c, f, 1, 0);
            } else if (s == 2) {
                hiz_visit(c, f);
                hiz_layer(c, f, 16, 0, 1, 1);
                hiz_visit_end(c, f, 0, 0);
                hiz_advance(c, f);
                hiz_visit(c, f);
                hiz_layer(c, f, 0, 16, 1, 1);
                hiz_cell_hull(c, f);
                hiz_visit_end(c, f, 0, 0);
                hiz_descend(c, f, 0, 1, 0, 0, 1);
                hiz_visit(c, f);
                hiz_layer(c, f, 16, 0, 1, 1);
                hiz_visit_end(c, f, 0, 1);
            }
            snprintf(nm, sizeof nm, "lt_hiz_trace16_%s (%s)", f ? "f32" : "q30",
                     s == 0 ? "bad rays" : (s == 1 ? "1x1, the pixel hit" :
                                                     "2x1: pass, up, descend, behind"));
            if (f)
                CHECKC(nm, lt_hiz_trace16_f32(&hz, &rf, LT_MASK_ALL, 0, &hf), &want);
            else
                CHECKC(nm, lt_hiz_trace16_q30(&hz, &rq, LT_MASK_ALL, 0, &hq), &want);
            if (s == 1)
                bad += swalk(nm, &hq, &hf, f, LT_QT_HIT, 1, 0, 1);
            else if (s == 2)
                bad += swalk(nm, &hq, &hf, f, LT_QT_OCCLUDED, 3, 1, 2);
        }
    }
    assert_int_equal(bad, 0);
}

/* ---- lt_qt_build_*: leaves (per 16-pixel pass of a row) and merges (per 16-parent pass) ---- */

/* wide build values (W) of the two paths: arithmetic (add/sub/blend/abs), shift, *3, from V */
static void qt_w(cost_t *c, int f, unsigned arith, unsigned shift, unsigned mul3, unsigned fromv)
{
    int ph = LT_PH_BUILD;
    if (f) {
        CL(FADD, arith);
        CL(VBCAST, shift);
        CL(FMUL, shift + mul3);
    } else {
        CL(VMULW, arith + 2u * mul3);
        CL(VSHIFT, shift);
        CL(VCVT, fromv);
    }
}

static void qt_enc_plane(cost_t *c, int enc, unsigned tries)
{
    int ph = LT_PH_BUILD;
    if (enc == 0) {
        CR(QT_N64_ENC_PLANE, 1);
        CR(QT_N64_ENC_TRY, tries);
    } else if (enc == 1) {
        CR(QT_N32_ENC_PLANE, 1);
        CR(QT_N32_ENC_TRY, tries);
    } else {
        CR(QT_F_STORE_ROW, 1);
    }
}

static void qt_decode(cost_t *c, int enc, unsigned lanes, int bounds)
{
    int ph = LT_PH_BUILD;
    CR(LANE_GATHER, enc == 2 ? 2u * lanes : lanes);
    if (enc == 0) {
        CR(QT_N64_DECODE, 1);
        CR(QT_N64_DECODE_BOUNDS, bounds);
    } else if (enc == 1) {
        CR(QT_N32_DECODE, 1);
        CR(QT_N32_DECODE_BOUNDS, bounds);
    } else {
        CR(QT_F_DECODE, 1);
        CR(QT_F_DECODE_BOUNDS, bounds);
    }
}

/* per layer: the leaves' three parameters (set1) */
static void qt_leaves_call(cost_t *c)
{
    int ph = LT_PH_BUILD;
    CL(VBCAST, 3);
}

/* one leaf pass: `loads` pixel-vector loads (3, + 1 with a row above, + 1 with a row below) */
static void qt_leaf_pass(cost_t *c, int enc, unsigned loads, unsigned tries)
{
    int ph = LT_PH_BUILD, f = enc == 2;
    CR(QT_LEAVES_PASS, 1);
    if (f)
        CR(QT_F_LOADPIX, loads);
    else
        CR(QT_Q_LOADPIX, loads);
    CO(VB, 23);
    CO(VC, 5);
    qt_w(c, f, 0, 0, 0, 3);
    qt_enc_plane(c, enc, tries);
}

/* one merge pass over the children masks kp[4] (lane counts) */
static void qt_merge_pass(cost_t *c, int enc, const unsigned kp[4])
{
    int ph = LT_PH_BUILD, j;
    CR(QT_MERGE_PASS, 1);
    CL(VBCAST, 8);
    for (j = 0; j < 4; j++)
        qt_decode(c, enc, kp[j], 1);
}

/* the proxy of parents whose children are all planes: sums, means, slopes, encode and decode */
static void qt_merge_proxy(cost_t *c, int enc, int tworows, unsigned tries, unsigned kept)
{
    int ph = LT_PH_BUILD, f = enc == 2;
    CR(QT_MERGE_PROXY, 1);
    qt_w(c, f, 20, 0, 0, 12);     /* sums over the 4 children */
    qt_w(c, f, 8, 10, 1, 0);      /* means, x slope, offset */
    if (tworows)
        qt_w(c, f, 3, 2, 1, 0);   /* y slope from two rows */
    else
        qt_w(c, f, 1, 2, 0, 0);   /* y slope of one row, offset moved */
    qt_enc_plane(c, enc, tries);
    qt_decode(c, enc, kept, 0);
    qt_w(c, f, 0, 0, 0, 4);
}

/* the distance and angle tests of one present child */
static void qt_merge_child(cost_t *c, int enc)
{
    int ph = LT_PH_BUILD, f = enc == 2;
    CR(QT_MERGE_CHILD_TESTS, 1);
    qt_w(c, f, 12, 7, 0, 4);
    if (f) {
        CL(FMUL, 3);
        CL(FADD, 2);
        CL(FCMP, 2);
        CL(VBCAST, 2);
    } else {
        CR(QT_Q_RELTOL, 1);
        CR(QT_Q_ANGLE_OK, 1);
        CL(VCMP, 1);
    }
}

static void qt_merge_copy(cost_t *c, int enc)
{
    int ph = LT_PH_BUILD;
    CR(QT_COPY_LINE, enc == 0 ? 2 : (enc == 1 ? 1 : 4));
}

static void qt_merge_aabb(cost_t *c, int enc)
{
    int ph = LT_PH_BUILD, f = enc == 2;
    CO(VB, 12);
    if (enc == 0)
        CR(QT_N64_ENC_AABB, 1);
    else if (enc == 1)
        CR(QT_N32_ENC_AABB, 1);
    else
        CR(QT_F_STORE_ROW, 1);
}

/* ---- lt_hiz_build_*: per 16-parent pass of a level ---- */

static void hiz_level_pass(cost_t *c, int f, unsigned pixrows, unsigned cellrows)
{
    int ph = LT_PH_BUILD;
    CR(HIZ_LEVEL_PASS, 1);
    CL(VBCAST, 2);
    CR(HIZ_LOAD_PIX2, pixrows);
    if (f)
        CR(HIZ_F_PIX_TEST, pixrows);
    else
        CR(HIZ_Q_PIX_TEST, pixrows);
    CR(HIZ_LOAD_CELL2, cellrows);
    CO(VB, 4u * (pixrows + cellrows));
    CR(HIZ_STORE_CELL, 1);
}

static void test_screen_build_costs(void **state)
{
    static const char *const encn[3] = {"n64", "n32", "f32"};
    lt_q30_t wq[4] = {W_HALF, W_HALF, W_HALF, W_HALF}, w2q[2] = {1 << 28, 1 << 29};
    float wf[4] = {0.5f, 0.5f, 0.5f, 0.5f}, w2f[2] = {0.25f, 0.5f};
    char nm[160];
    int bad = 0, e, f, s;
    (void)state;
    sim_start();
    /* the quadtree: 1x1 (one leaf pass), 2x2 of one depth (two leaf passes, one merge kept), 2x1
     * of depths 4 and 2 (w 0.25, 0.5: a jump; the proxy fails, an AABB) */
    for (e = 0; e < 3; e++) {
        f = e == 2;
        for (s = 0; s < 3; s++) {
            lt_qt_desc_t d;
            lt_qt_t qt;
            size_t bytes = sizeof g_arena;
            cost_t want;
            cost_t *c = &want;
            /* plane encodes of constant w: the n32 format fits at the first exponent, n64
             * retries no slope shift */
            unsigned tries = e == 1 ? 1u : 0u;
            memset(&want, 0, sizeof want);
            d.width = s == 0 ? 1u : 2u;
            d.height = s == 1 ? 2u : 1u;
            d.layers = 1;
            d.enc = e == 0 ? LT_QT_N64 : (e == 1 ? LT_QT_N32 : LT_QT_F32);
            qt_leaves_call(c);
            if (s == 0) {
                qt_leaf_pass(c, e, 3, tries);
            } else if (s == 2) {
                /* the proxy C = 0.375, Al = 0.375 (s1.30, 2^-6 fraction): n32 fits C in 12 bits
                 * and the slope in 6 only at the fifth exponent (E = 21, K = 1); n64 at once */
                static const unsigned kp[4] = {1, 1, 0, 0};
                qt_leaf_pass(c, e, 3, tries);
                qt_merge_pass(c, e, kp);
                qt_merge_proxy(c, e, 0, e == 1 ? 5u : 0u, 1);
                qt_merge_child(c, e);
                qt_merge_child(c, e);
                {
                    int ph = LT_PH_BUILD;
                    CR(QT_MERGE_CHILD, 4);
                }
                qt_merge_aabb(c, e);
            } else {
                static const unsigned kp[4] = {1, 1, 1, 1};
                qt_leaf_pass(c, e, 4, tries);
                qt_leaf_pass(c, e, 4, tries);
                qt_merge_pass(c, e, kp);
                qt_merge_proxy(c, e, 1, tries, 1);
                qt_merge_child(c, e);
                qt_merge_child(c, e);
                qt_merge_child(c, e);
                qt_merge_child(c, e);
                {
                    int ph = LT_PH_BUILD;
                    CR(QT_MERGE_CHILD, 4);
                }
                qt_merge_copy(c, e);
            }
            snprintf(nm, sizeof nm, "lt_qt_build_%s (%s, %s)", f ? "f32" : "q30", encn[e],
                     s == 0 ? "1x1" : (s == 1 ? "2x2 of one depth: a plane kept" :
                                                "2x1 with a jump: the proxy fails, an AABB"));
            if (f)
                CHECKC(nm, lt_qt_build_f32(&qt, &d, NULL, s == 2 ? w2f : wf, g_arena, &bytes),
                       &want);
            else
                CHECKC(nm, lt_qt_build_q30(&qt, &d, NULL, s == 2 ? w2q : wq, g_arena, &bytes),
                       &want);
        }
    }
    /* Hi-Z: 1x1 (level 0 only: nothing), 2x2 (one pass over two pixel rows) */
    for (f = 0; f < 2; f++) {
        for (s = 0; s < 2; s++) {
            lt_ssb_desc_t d;
            lt_hiz_t hz;
            size_t bytes = sizeof g_arena;
            cost_t want;
            cost_t *c = &want;
            memset(&want, 0, sizeof want);
            d.width = d.height = s == 0 ? 1u : 2u;
            d.layers = 1;
            d.enc = f ? LT_SSB_F32 : LT_SSB_Q30;
            if (s == 1)
                hiz_level_pass(c, f, 2, 0);
            snprintf(nm, sizeof nm, "lt_hiz_build_%s (%s)", f ? "f32" : "q30",
                     s == 0 ? "1x1: no level to build" : "2x2: one pass over two pixel rows");
            if (f)
                CHECKC(nm, lt_hiz_build_f32(&hz, &d, NULL, wf, g_arena, &bytes), &want);
            else
                CHECKC(nm, lt_hiz_build_q30(&hz, &d, NULL, wq, g_arena, &bytes), &want);
        }
    }
    assert_int_equal(bad, 0);
}

/* ---- screen space: the straight-line and the uncharged entry points ---- */

static void test_screen_fixed_costs(void **state)
{
    lt_reproj_cam_t src, dst;
    lt_reproj_opts_t o = {4.0, 0.0, 0.0, 0.0};
    lt_reproj_q30_t mq;
    lt_reproj_f32_t mf;
    lt_qray16_q30_t rq;
    lt_qray16_f32_t rf;
    lt_mask16_t k;
    lt_qt_params_t qp;
    lt_qt_desc_t qd = {8, 8, 1, LT_QT_N64};
    lt_ssb_params_t sp;
    lt_ssb_desc_t sd = {8, 8, 1, LT_SSB_Q30};
    lt_ssdda_t dda;
    lt_hiz_t hz;
    lt_qt_t qt;
    lt_q30_t wq[64];
    float wf[64];
    size_t bytes;
    cost_t none, want;
    cost_t *c = &want;
    int ph, i, j, bad = 0;
    (void)state;
    sim_start();
    memset(&none, 0, sizeof none);
    for (i = 0; i < 64; i++) {
        wq[i] = W_HALF;
        wf[i] = 0.5f;
    }
    /* Cost: none */
    CHECKC("lt_qt_params_default", (lt_qt_params_default(&qp), 0), &none);
    CHECKC("lt_qt_size", lt_qt_size(&qd, &bytes), &none);
    bytes = sizeof g_arena;
    assert_int_equal(lt_qt_build_q30(&qt, &qd, NULL, wq, g_arena, &bytes), LT_OK);
    CHECKC("lt_qt_default_steps", lt_qt_default_steps(&qt), &none);
    CHECKC("lt_ssb_params_default", (lt_ssb_params_default(&sp), 0), &none);
    CHECKC("lt_ssdda_init_q30", lt_ssdda_init_q30(&dda, &sd, NULL, wq), &none);
    CHECKC("lt_ssdda_default_steps", lt_ssdda_default_steps(&dda), &none);
    CHECKC("lt_hiz_size", lt_hiz_size(&sd, &bytes), &none);
    bytes = sizeof g_arena;
    assert_int_equal(lt_hiz_build_q30(&hz, &sd, NULL, wq, g_arena, &bytes), LT_OK);
    CHECKC("lt_hiz_default_steps", lt_hiz_default_steps(&hz), &none);
    sd.enc = LT_SSB_F32;
    CHECKC("lt_ssdda_init_f32", lt_ssdda_init_f32(&dda, &sd, NULL, wf), &none);
    /* a target camera 0.3 units right of the source, both 8x8 pinholes (f = 8) */
    memset(&src, 0, sizeof src);
    src.fx = src.fy = 8.0;
    src.cx = src.cy = 4.0;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            src.r[i][j] = i == j ? 1.0 : 0.0;
    src.width = src.height = 8;
    dst = src;
    dst.c[0] = 0.3;
    CHECKC("lt_reproj_setup", lt_reproj_setup(&src, &dst, &o, &mq, &mf), &none);
    assert_int_equal(lt_reproj_setup(&src, &dst, &o, &mq, &mf), LT_OK);
    /* the packet program: SETUP, one recipe and the stores, whatever the lanes */
    memset(&want, 0, sizeof want);
    ph = LT_PH_SETUP;
    CR(RPJ_Q30_PACKET, 1);
    CR(RPJ_STORE_RAYS, 1);
    k = LT_MASK_ALL;
    CHECKC("lt_reproj_rays16_q30 (a 4x4 tile)", lt_reproj_rays16_q30(&mq, 0, 0, &rq, &k), &want);
    k = 0x00FF;
    CHECKC("lt_reproj_rays16_q30 (8 lanes)", lt_reproj_rays16_q30(&mq, 4, 4, &rq, &k), &want);
    memset(&want, 0, sizeof want);
    CR(RPJ_F32_PACKET, 1);
    CR(RPJ_STORE_RAYS, 1);
    k = LT_MASK_ALL;
    CHECKC("lt_reproj_rays16_f32 (a 4x4 tile)", lt_reproj_rays16_f32(&mf, 0, 0, &rf, &k), &want);
    assert_int_equal(bad, 0);
}

/* ==== multi-frusta (lt_frusta.h) ============================================================== */

/* classes of the frusta kernels' generic ops, s15.16 (f = 0) and float32 (f = 1): V arithmetic
 * (add, sub, min, max, abs, blend), V multiply, V compare */
#define FA (f ? LT_OP_FADD : LT_OP_VALU)
#define FM (f ? LT_OP_FMUL : LT_OP_VMUL)
#define FC (f ? LT_OP_FCMP : LT_OP_VCMP)

/* the products of the triangle test: a cross product (s15.16: rounded), a dot product, d . qvec */
static void fr_cross(cost_t *c, int ph, int f, unsigned n)
{
    if (f) {
        CL(FMUL, 2 * n);
        CL(FADD, n);
    } else {
        CL(VMUL, 2 * n);
        CL(VMULW, n);
        CL(VSHIFT, n);
    }
}

static void fr_dot(cost_t *c, int ph, int f, unsigned n, int rounded)
{
    if (f) {
        CL(FMUL, 3 * n);
        CL(FADD, 2 * n);
    } else {
        CL(VMUL, 3 * n);
        CL(VMULW, 2 * n);
        CL(VSHIFT, rounded ? n : 0);
    }
}

/* the wide lanes det, u, v, tnum: n add / sub (s15.16 int64 lanes, float32 adds) */
static void fr_w(cost_t *c, int ph, int f, unsigned n)
{
    if (f)
        CL(FADD, n);
    else
        CL(VMULW, n);
}

/* fr_box / pr_box: the interval slab test of 16 frusta against one box */
static void fr_box(cost_t *c, int f, int primary)
{
    int ph = LT_PH_TRAVERSE;
    if (primary)
        CR(FR_PBOX_LOAD, 1);
    else
        CR(FR_BOX_LOAD, 1);
    CL(VBCAST, 10);
    CO(FA, primary ? 16 : 22);
    CO(FM, 6);
    CO(FC, 1);
    if (f) { /* the relative margins: abs, multiply, add */
        CL(FADD, 2);
        CL(FMUL, 2);
    }
}

/* the bit-scan over n frusta */
static void fr_scan(cost_t *c, int ph, unsigned n)
{
    CL(MASK, 3 * n + 1);
}

/* fr_cull without corner-ray culling (CORNER unset): tvec, qvec, tnum, the sign test */
static void fr_cull(cost_t *c, int f, int backface)
{
    int ph = LT_PH_INTERSECT;
    CR(FR_CULL_BACK, 1);
    CL(VBCAST, 9 + (backface ? 1 : 2));
    CO(FA, 3);
    fr_cross(c, ph, f, 3);
    fr_dot(c, ph, f, 1, 0);
    CO(FC, backface ? 1 : 2);
}

/* fr_gen: frustum f's 16 rays */
static void fr_gen(cost_t *c, int f)
{
    int ph = LT_PH_INTERSECT;
    CR(FR_GEN, 1);
    CL(VBCAST, f ? 6 : 3);
    CO(FA, 3);
    if (f)
        CL(FMUL, 3);
    else
        CR(FR_Q_TOD, 3);
}

/* fr_tri / pr_tri's common part: the broadcasts (fr_tri only), pvec, det, u, v, the flip, the
 * barycentric tests and the division of the candidates */
static void fr_tri_common(cost_t *c, int f, int flip, unsigned negs, int cand)
{
    int ph = LT_PH_INTERSECT;
    fr_cross(c, ph, f, 3);
    fr_dot(c, ph, f, 2, 0);
    fr_dot(c, ph, f, 1, 1);
    if (flip) {
        fr_w(c, ph, f, negs);
        if (!f)
            CL(VBCAST, negs);
    }
    CO(FC, 4);
    CL(VBCAST, 3);
    fr_w(c, ph, f, 1);
    if (cand) {
        if (f)
            CL(FDIV, 1);
        else
            CR(TRI_Q_TDIV16, 1);
    }
}

static void fr_tri(cost_t *c, int f, int flip, int cand)
{
    int ph = LT_PH_INTERSECT;
    CR(FR_TRI, 1);
    CL(VBCAST, 13);
    fr_tri_common(c, f, flip, 4, cand);
    if (cand) {
        CL(VBCAST, 3);
        CO(FC, 2);
    }
}

/* What lt_slab16_* / lt_tri16_* charge on a copy of the packet (the root box of a one-node tree,
 * one triangle), added to phase ph: the walks charge the kernels they call. */
static void cadd_since(cost_t *c, int ph, const cost_t *b)
{
    cost_t a;
    int p, op;
    csnap(&a);
    for (p = 0; p < (int)LT_PH__COUNT; p++)
        for (op = 0; op < (int)LT_OP__COUNT; op++)
            c->n[ph][op] += a.n[p][op] - b->n[p][op];
}

static void slab_alone(cost_t *c, int ph, int f, const lt_ray16_q16_t *rq, const lt_ray16_f32_t *rf,
                       const void *nodes)
{
    lt_ray16_q16_t q = *rq;
    lt_ray16_f32_t r = *rf;
    lt_vq16_t tq;
    lt_vf32_t tf;
    cost_t b;
    csnap(&b);
    if (f)
        (void)lt_slab16_f32(&r, LT_MASK_ALL, &((const lt_bvh_node_f32_t *)nodes)[0].b, &tf);
    else
        (void)lt_slab16_q16(&q, LT_MASK_ALL, &((const lt_bvh_node_q16_t *)nodes)[0].b, &tq);
    cadd_since(c, ph, &b);
}

static void tri_alone(cost_t *c, int ph, int f, const lt_ray16_q16_t *rq, const lt_ray16_f32_t *rf,
                      const lt_tri_q16_t *tq, const lt_tri_f32_t *tf)
{
    lt_ray16_q16_t q = *rq;
    lt_ray16_f32_t r = *rf;
    lt_hit16_t h;
    cost_t b;
    h.id = lt_vi32_set1(-1);
    csnap(&b);
    if (f)
        (void)lt_tri16_f32(&r, LT_MASK_ALL, tf, 0, &h);
    else
        (void)lt_tri16_q16(&q, LT_MASK_ALL, tq, 0, &h);
    cadd_since(c, ph, &b);
}

static void test_frusta_costs(void **state)
{
    static uint64_t arena[2][2048];
    static lt_frusta_table_q16_t tbq;
    static lt_frusta_table_f32_t tbf;
    static lt_frusta16_q16_t Fq;
    static lt_frusta16_f32_t Ff;
    static lt_frusta_prim16_q16_t Pq;
    static lt_frusta_prim16_f32_t Pf;
    lt_tri_q16_t tq[1];
    lt_tri_f32_t tf[1];
    lt_bvh_t bq, bf;
    lt_qmc_sets_t sets;
    lt_frusta_light_q16_t lq;
    lt_frusta_light_f32_t lf;
    lt_frusta_view_q16_t vq;
    lt_frusta_view_f32_t vf;
    lt_frusta_vtable_q16_t vtq;
    lt_frusta_vtable_f32_t vtf;
    lt_q16_t oq[3] = {0, 0, -4 * 65536};
    float of[3] = {0.0f, 0.0f, -4.0f};
    lt_ray16_q16_t rq, rq2;
    lt_ray16_f32_t rf, rf2;
    lt_ray1_q16_t r1q;
    lt_ray1_f32_t r1f;
    lt_hit16_t hit2;
    lt_mask16_t k, occ;
    cost_t none, want;
    cost_t *c = &want;
    /* one triangle z = 0 over (-64, -64) .. (128, -64) .. (-64, 128): every ray of the scene
     * crosses it */
    static const int32_t v0[3] = {-64 * 65536, -64 * 65536, 0},
                         v1[3] = {128 * 65536, -64 * 65536, 0},
                         v2[3] = {-64 * 65536, 128 * 65536, 0};
    int i, a, f, ph, bad = 0;
    (void)state;
    sim_start();
    memset(&none, 0, sizeof none);
    for (a = 0; a < 3; a++) {
        tq[0].v0[a] = v0[a];
        tq[0].e1[a] = v1[a] - v0[a];
        tq[0].e2[a] = v2[a] - v0[a];
        tf[0].v0[a] = (float)v0[a] / 65536.0f;
        tf[0].e1[a] = (float)tq[0].e1[a] / 65536.0f;
        tf[0].e2[a] = (float)tq[0].e2[a] / 65536.0f;
    }
    assert_int_equal(lt_bvh_build_q16(&bq, NULL, tq, 1, arena[0], sizeof arena[0]), LT_OK);
    assert_int_equal(lt_bvh_build_f32(&bf, NULL, tf, 1, arena[1], sizeof arena[1]), LT_OK);
    bq.isect = bf.isect = LT_ISECT_MT; /* walks composed with lt_tri16 (the MT option) */
    CHECKC("lt_qmc_interleave4x4", lt_qmc_interleave4x4(LT_QMC_LP, 0, &sets), &none);
    /* a 1 x 1 light at z = 4 over the origins at z = -4 */
    memset(&lq, 0, sizeof lq);
    lq.c[0] = lq.c[1] = -32768;
    lq.c[2] = 4 * 65536;
    lq.eu[0] = 65536;
    lq.ev[1] = 65536;
    memset(&lf, 0, sizeof lf);
    lf.c[0] = lf.c[1] = -0.5f;
    lf.c[2] = 4.0f;
    lf.eu[0] = 1.0f;
    lf.ev[1] = 1.0f;
    CHECKC("lt_frusta_table_q16", lt_frusta_table_q16(&lq, &sets, &tbq), &none);
    CHECKC("lt_frusta_table_f32", lt_frusta_table_f32(&lf, &sets, &tbf), &none);
    for (i = 0; i < LT_LANES; i++) {
        Fq.ox.l[i] = (i % 4) * 4096;
        Fq.oy.l[i] = (i / 4) * 4096;
        Fq.oz.l[i] = -4 * 65536;
        Ff.ox.l[i] = (float)Fq.ox.l[i] / 65536.0f;
        Ff.oy.l[i] = (float)Fq.oy.l[i] / 65536.0f;
        Ff.oz.l[i] = -4.0f;
    }
    for (f = 0; f < 2; f++) {
        char nm[160];
        /* setup: straight-line */
        memset(&want, 0, sizeof want);
        ph = LT_PH_SETUP;
        CR(FR_SETUP, 1);
        if (f) {
            CR(FR_F_SCALE, 1);
            CR(FR_F_TEND, 1);
            CR(FR_F_TMAX, 1);
            CL(FMUL, 18);
            CL(FADD, 57);
            CL(FDIV, 6);
            CL(FCMP, 24);
        } else {
            CR(FR_Q_SCALE, 1);
            CR(FR_Q_TEND, 1);
            CR(FR_Q_TMAX, 1);
            CR(FR_Q_TOD, 18);
            CL(VALU, 57);
            CL(VDIV, 6);
            CL(VCMP, 24);
        }
        CL(VBCAST, 32);
        snprintf(nm, sizeof nm, "lt_frusta_setup16_%s", f ? "f32" : "q16");
        if (f)
            CHECKC(nm, lt_frusta_setup16_f32(&tbf, LT_MASK_ALL, &Ff), &want);
        else
            CHECKC(nm, lt_frusta_setup16_q16(&tbq, LT_MASK_ALL, &Fq), &want);
        /* the walk: a one-leaf tree, the root box entered, the triangle kept by all 16 frusta,
         * every frustum's rays generated and all occluded (the sign flip: tnum < 0) */
        memset(&want, 0, sizeof want);
        ph = LT_PH_TRAVERSE;
        CL(VBCAST, 2);
        fr_box(c, f, 0);
        CR(BVH_TRAV_NODE, 1);
        CR(FR_ACTIVE_EXIT, 1);
        ph = LT_PH_INTERSECT;
        CR(FR_LEAF_TRI, 1);
        fr_cull(c, f, 0);
        fr_scan(c, ph, 16);
        for (i = 0; i < LT_LANES; i++) {
            CR(FR_LEAF_FRUSTUM, 1);
            fr_gen(c, f);
            fr_tri(c, f, 1, 1);
            CR(FR_LEAF_OCCLUDED, 1);
        }
        snprintf(nm, sizeof nm, "lt_frusta_occluded16_%s (one leaf, all occluded)",
                 f ? "f32" : "q16");
        if (f) {
            CHECKC(nm, lt_frusta_occluded16_f32(&bf, tf, &tbf, &Ff), &want);
            bad += Ff.active != 0 || Ff.occl[0] != 0xFFFF;
        } else {
            CHECKC(nm, lt_frusta_occluded16_q16(&bq, tq, &tbq, &Fq), &want);
            bad += Fq.active != 0 || Fq.occl[0] != 0xFFFF;
        }
        /* nothing active: no charge */
        snprintf(nm, sizeof nm, "lt_frusta_occluded16_%s (no active frustum)", f ? "f32" : "q16");
        if (f)
            CHECKC(nm, lt_frusta_occluded16_f32(&bf, tf, &tbf, &Ff), &none);
        else
            CHECKC(nm, lt_frusta_occluded16_q16(&bq, tq, &tbq, &Fq), &none);
        /* one frustum's rays as a packet, one as a single ray: in the caller's phase */
        memset(&want, 0, sizeof want);
        ph = LT_PH_OTHER;
        CR(FR_RAYS, 1);
        CO(FA, 3);
        CL(VBCAST, f ? 11 : 8);
        if (f) {
            CL(FMUL, 3);
            CL(FDIV, 3); /* lt_ray16_f32_setup */
            CL(FCMP, 6);
            CL(VALU, 3);
            CL(VBCAST, 3);
        } else {
            CR(FR_Q_TOD, 3);
            CL(VDIV, 3); /* lt_ray16_q16_setup */
            CL(VCMP, 9);
            CL(VBCAST, 9);
        }
        snprintf(nm, sizeof nm, "lt_frusta_rays16_%s", f ? "f32" : "q16");
        if (f)
            CHECKC(nm, lt_frusta_rays16_f32(&tbf, of, 3, &rf, &k), &want);
        else
            CHECKC(nm, lt_frusta_rays16_q16(&tbq, oq, 3, &rq, &k), &want);
        memset(&want, 0, sizeof want);
        CR(BVH_RAY1_SETUP, 1);
        snprintf(nm, sizeof nm, "lt_frusta_ray1_%s", f ? "f32" : "q16");
        if (f)
            CHECKC(nm, lt_frusta_ray1_f32(&tbf, of, 3, 5, &r1f), &want);
        else
            CHECKC(nm, lt_frusta_ray1_q16(&tbq, oq, 3, 5, &r1q), &want);
        /* the packet baseline on those rays: the root slab test and the leaf's triangle test,
         * charged as lt_slab16 / lt_tri16 charge alone (measured here on copies of the packet), one
         * node; the triangle occludes every lane */
        memset(&want, 0, sizeof want);
        ph = LT_PH_TRAVERSE;
        CL(VBCAST, 2);
        CR(BVH_TRAV_NODE, 1);
        CR(BVH_TRAV_ANY_EXIT, 1);
        slab_alone(c, ph, f, &rq, &rf, f ? bf.nodes : bq.nodes);
        ph = LT_PH_INTERSECT;
        CR(BVH_TRAV_LEAF_TRI, 1);
        CR(BVH_TRAV_ANY_RETIRE, 1);
        tri_alone(c, ph, f, &rq, &rf, &tq[0], &tf[0]);
        snprintf(nm, sizeof nm, "lt_frusta_packet_occluded16_%s (one leaf, all occluded)",
                 f ? "f32" : "q16");
        rq2 = rq;
        rf2 = rf;
        if (f)
            CHECKC(nm, lt_frusta_packet_occluded16_f32(&bf, tf, 0, of, &rf2, LT_MASK_ALL, &occ),
                   &want);
        else
            CHECKC(nm, lt_frusta_packet_occluded16_q16(&bq, tq, 0, oq, &rq2, LT_MASK_ALL, &occ),
                   &want);
        bad += occ != LT_MASK_ALL;
        /* with BACKFACE the triangle faces away from the origin: culled by the scalar sign */
        memset(&want, 0, sizeof want);
        ph = LT_PH_TRAVERSE;
        CL(VBCAST, 2);
        CR(BVH_TRAV_NODE, 1);
        CR(BVH_TRAV_ANY_EXIT, 1);
        slab_alone(c, ph, f, &rq, &rf, f ? bf.nodes : bq.nodes);
        ph = LT_PH_INTERSECT;
        CR(BVH_TRAV_LEAF_TRI, 1);
        CR(FR_PACKET_TRI_LOAD, 1);
        CR(FR_TNUM_SIGN, 1);
        snprintf(nm, sizeof nm, "lt_frusta_packet_occluded16_%s (BACKFACE: culled)",
                 f ? "f32" : "q16");
        rq2 = rq;
        rf2 = rf;
        if (f)
            CHECKC(nm, lt_frusta_packet_occluded16_f32(&bf, tf, LT_FRUSTA_BACKFACE, of, &rf2,
                                                       LT_MASK_ALL, &occ), &want);
        else
            CHECKC(nm, lt_frusta_packet_occluded16_q16(&bq, tq, LT_FRUSTA_BACKFACE, oq, &rq2,
                                                       LT_MASK_ALL, &occ), &want);
        bad += occ != 0;
    }
    /* primary frusta: a 16 x 16 view from (0, 0, -8) looking down +z, every ray hits */
    memset(&vq, 0, sizeof vq);
    vq.o[2] = -8 * 65536;
    vq.d0[0] = vq.d0[1] = -8 * (1 << 20);
    vq.d0[2] = 1 << 29;
    vq.dx[0] = 1 << 20;
    vq.dy[1] = 1 << 20;
    vq.width = vq.height = 16;
    memset(&vf, 0, sizeof vf);
    for (a = 0; a < 3; a++) {
        vf.o[a] = (float)vq.o[a] / 65536.0f;
        vf.d0[a] = (float)vq.d0[a] / 1073741824.0f;
        vf.dx[a] = (float)vq.dx[a] / 1073741824.0f;
        vf.dy[a] = (float)vq.dy[a] / 1073741824.0f;
    }
    vf.width = vf.height = 16;
    CHECKC("lt_frusta_vtable_q16", lt_frusta_vtable_q16(&vq, &vtq), &none);
    CHECKC("lt_frusta_vtable_f32", lt_frusta_vtable_f32(&vf, &vtf), &none);
    for (f = 0; f < 2; f++) {
        char nm[160];
        memset(&want, 0, sizeof want);
        ph = LT_PH_SETUP;
        CR(FR_PSETUP_TILE, LT_LANES);
        CR(FR_PSETUP_CR, LT_LANES);
        CR(FR_PSETUP_CORNERS, 1);
        if (f) {
            CR(FR_F_PBASEV, 3);
            CL(FADD, 18);
            CL(FDIV, 6);
            CL(FCMP, 24);
            CL(VBCAST, 58);
        } else {
            CR(FR_Q_PBASEV, 3);
            CL(VALU, 18);
            CL(VDIV, 6);
            CL(VCMP, 24);
            CL(VBCAST, 46);
        }
        snprintf(nm, sizeof nm, "lt_frusta_psetup16_%s", f ? "f32" : "q16");
        if (f)
            CHECKC(nm, lt_frusta_psetup16_f32(&vtf, 0, 0, &Pf), &want);
        else
            CHECKC(nm, lt_frusta_psetup16_q16(&vtq, 0, 0, &Pq), &want);
        /* the walk: the root box, one node, the leaf's triangle (tnum < 0: sigma = -1) kept by
         * all 16 frusta, every frustum's rays generated and all hit; their tmax updated */
        memset(&want, 0, sizeof want);
        ph = LT_PH_TRAVERSE;
        CL(VBCAST, 2);
        fr_box(c, f, 1);
        CR(BVH_TRAV_NODE, 1);
        ph = LT_PH_INTERSECT;
        CR(FR_PLEAF_TRI, 1);
        CR(FR_PTQ, 1);
        CR(FR_PLEAF_KEPT, 1);
        CL(VBCAST, 13);
        fr_scan(c, ph, 16);
        for (i = 0; i < LT_LANES; i++) {
            CR(FR_PLEAF_FRUSTUM, 1);
            CR(FR_PGEN, 1); /* pr_gen */
            CL(VBCAST, 3);
            CO(FA, 3);
            CR(FR_PTRI, 1); /* pr_tri */
            fr_tri_common(c, f, 1, 3, 1);
            CO(FC, 3);
            CL(VBCAST, 2);
            CR(FR_PTRI_HITS, 1);
            CO(FA, 1);
            CL(VALU, 1);
            CR(FR_PLEAF_TMAX, 1);
            CL(VRED, 1);
        }
        fr_scan(c, ph, 16);
        snprintf(nm, sizeof nm, "lt_frusta_trace16_%s (one leaf, all hit)", f ? "f32" : "q16");
        if (f) {
            CHECKC(nm, lt_frusta_trace16_f32(&bf, tf, &vtf, &Pf), &want);
            bad += Pf.id[0].l[0] != 0 || Pf.id[15].l[15] != 0;
        } else {
            CHECKC(nm, lt_frusta_trace16_q16(&bq, tq, &vtq, &Pq), &want);
            bad += Pq.id[0].l[0] != 0 || Pq.id[15].l[15] != 0;
        }
        /* a tile's rays as a packet and one as a single ray: in the caller's phase */
        memset(&want, 0, sizeof want);
        ph = LT_PH_OTHER;
        CR(FR_PRAYS, 1);
        CL(VBCAST, 8);
        CO(FA, 3);
        if (f) {
            CL(FDIV, 3); /* lt_ray16_f32_setup */
            CL(FCMP, 6);
            CL(VALU, 3);
            CL(VBCAST, 3);
        } else {
            CL(VDIV, 3); /* lt_ray16_q16_setup */
            CL(VCMP, 9);
            CL(VBCAST, 9);
        }
        snprintf(nm, sizeof nm, "lt_frusta_prays16_%s", f ? "f32" : "q16");
        if (f)
            CHECKC(nm, lt_frusta_prays16_f32(&vtf, 0, 0, &rf, &k), &want);
        else
            CHECKC(nm, lt_frusta_prays16_q16(&vtq, 0, 0, &rq, &k), &want);
        memset(&want, 0, sizeof want);
        CR(BVH_RAY1_SETUP, 1);
        snprintf(nm, sizeof nm, "lt_frusta_pray1_%s", f ? "f32" : "q16");
        if (f)
            CHECKC(nm, lt_frusta_pray1_f32(&vtf, 1, 2, &r1f), &want);
        else
            CHECKC(nm, lt_frusta_pray1_q16(&vtq, 1, 2, &r1q), &want);
        /* P-Packet on that tile: root slab, one node, the triangle (no tie) */
        memset(&want, 0, sizeof want);
        ph = LT_PH_OTHER;
        CL(VBCAST, 1);
        ph = LT_PH_TRAVERSE;
        CL(VBCAST, 2);
        CR(BVH_TRAV_NODE, 1);
        slab_alone(c, ph, f, &rq, &rf, f ? bf.nodes : bq.nodes);
        ph = LT_PH_INTERSECT;
        CR(BVH_TRAV_LEAF_TRI, 1);
        CR(FR_IDGT, 1);
        CR(FR_PACKET_TIE, 1);
        tri_alone(c, ph, f, &rq, &rf, &tq[0], &tf[0]);
        snprintf(nm, sizeof nm, "lt_frusta_packet_trace16_%s (one leaf, all hit)",
                 f ? "f32" : "q16");
        rq2 = rq;
        rf2 = rf;
        if (f)
            CHECKC(nm, lt_frusta_packet_trace16_f32(&bf, tf, 0, vf.o, &rf2, LT_MASK_ALL, &hit2),
                   &want);
        else
            CHECKC(nm, lt_frusta_packet_trace16_q16(&bq, tq, 0, vq.o, &rq2, LT_MASK_ALL, &hit2),
                   &want);
        bad += hit2.id.l[0] != 0;
    }
    /* shading and filtering */
    {
        lt_vq16_t p[3], g;
        lt_vq30_t n[3];
        lt_vf32_t pf[3], nf[3], gf;
        lt_q16_t m[3] = {0, 0, 4 * 65536};
        lt_q30_t nl[3] = {0, 0, -LT_Q30_ONE};
        float mf[3] = {0.0f, 0.0f, 4.0f}, nlf[3] = {0.0f, 0.0f, -1.0f};
        static lt_q16_t e[64], z[64], out[64];
        static lt_q30_t nx[64], ny[64], nz[64];
        static float ef[64], zf[64], nxf[64], nyf[64], nzf[64], outf[64];
        static uint8_t valid[64];
        lt_frusta_filter_q16_t par = {3277, 966367642};
        lt_frusta_filter_f32_t parf = {0.05f, 0.9f};
        for (a = 0; a < 3; a++)
            for (i = 0; i < LT_LANES; i++) {
                p[a].l[i] = a == 2 ? 0 : i * 4096;
                n[a].l[i] = a == 2 ? LT_Q30_ONE : 0;
                pf[a].l[i] = (float)p[a].l[i] / 65536.0f;
                nf[a].l[i] = a == 2 ? 1.0f : 0.0f;
            }
        for (i = 0; i < 64; i++) {
            e[i] = 32768;
            z[i] = 65536;
            nz[i] = LT_Q30_ONE;
            ef[i] = 0.5f;
            zf[i] = 1.0f;
            nzf[i] = 1.0f;
            valid[i] = 1;
        }
        for (f = 0; f < 2; f++) {
            char nm[160];
            int y;
            memset(&want, 0, sizeof want);
            ph = LT_PH_OTHER;
            CO(FA, 4);
            CO(FC, 3);
            CL(VBCAST, 7);
            if (f) {
                CL(FADD, 6);
                CL(FMUL, 10);
                CL(FDIV, 1);
            } else {
                CL(VMUL, 10);
                CL(VMULW, 6);
                CL(VSHIFT, 2);
                CR(FR_Q_GTERM_DIV, 1);
            }
            snprintf(nm, sizeof nm, "lt_frusta_direct16_%s", f ? "f32" : "q16");
            if (f)
                CHECKC(nm, lt_frusta_direct16_f32(pf, nf, mf, nlf, LT_MASK_ALL, &gf), &want);
            else
                CHECKC(nm, lt_frusta_direct16_q16(p, n, m, nl, LT_MASK_ALL, &g), &want);
            /* 16 x 4, all valid: row 1 has all 16 window offsets, row 0 the 12 inside */
            for (y = 0; y < 2; y++) {
                unsigned offs = y == 1 ? 16u : 12u;
                memset(&want, 0, sizeof want);
                ph = LT_PH_OTHER;
                CL(VBCAST, 1);
                ph = LT_PH_FILTER;
                CR(FR_VMASK, 1 + offs);
                CR(FR_LOADX, 4 + 5 * offs);
                CR(FR_FILTER_OFFSET, offs);
                CO(FM, 1);
                CL(VBCAST, 2 + 2 * offs);
                CL(VSTORE, 1);
                CO(FA, 3 * offs);
                CO(FC, 2 * offs);
                CL(VALU, offs);
                if (f) {
                    CL(FDIV, 1);
                    CL(FMUL, 3 * offs);
                    CL(FADD, 2 * offs);
                } else {
                    CL(VDIV, 1);
                    CL(VMUL, 3 * offs);
                    CL(VMULW, 2 * offs);
                }
                snprintf(nm, sizeof nm, "lt_frusta_filter16_%s (row %d of 16 x 4)",
                         f ? "f32" : "q16", y);
                if (f)
                    CHECKC(nm, (lt_frusta_filter16_f32(ef, zf, nxf, nyf, nzf, valid, 16, 4, 0,
                                                       (uint32_t)y, &parf, outf), 0), &want);
                else
                    CHECKC(nm, (lt_frusta_filter16_q16(e, z, nx, ny, nz, valid, 16, 4, 0,
                                                       (uint32_t)y, &par, out), 0), &want);
            }
        }
    }
    {
        uint32_t u, v;
        CHECKC("lt_qmc_vdc", lt_qmc_vdc(5), &none);
        CHECKC("lt_qmc_lp", lt_qmc_lp(5), &none);
        CHECKC("lt_qmc_point", lt_qmc_point(LT_QMC_LP, 5, 4, &u, &v), &none);
    }
    assert_int_equal(bad, 0);
}

/* ==== object space: the kernels not covered above, on a one-triangle scene ==================== */

static void test_object_costs(void **state)
{
    static uint64_t arena[3][2048];
    lt_tri_q16_t tq[1];
    lt_tri_f32_t tf[1];
    lt_bvh_t bq, bf;
    lt_bvhq_t qq;
    lt_aabb_q16_t boxq;
    lt_aabb_f32_t boxf;
    lt_ray16_q16_t rq, rq2;
    lt_ray16_f32_t rf, rf2;
    lt_ray1_q16_t r1q, r1q2;
    lt_ray1_f32_t r1f, r1f2;
    lt_hit16_t hit;
    lt_mask16_t m;
    lt_vq16_t tnq;
    lt_vf32_t tnf;
    lt_bvh_desc_t bd;
    lt_kd_params_t kp;
    lt_grid_params_t gp;
    size_t bytes;
    int32_t id;
    int occ;
    cost_t none, want;
    cost_t *c = &want;
    static const int32_t v0[3] = {-2 * 65536, -2 * 65536, 0}, v1[3] = {4 * 65536, -2 * 65536, 0},
                         v2[3] = {-2 * 65536, 4 * 65536, 0};
    int i, a, f, ph, bad = 0;
    (void)state;
    sim_start();
    memset(&none, 0, sizeof none);
    for (a = 0; a < 3; a++) {
        tq[0].v0[a] = v0[a];
        tq[0].e1[a] = v1[a] - v0[a];
        tq[0].e2[a] = v2[a] - v0[a];
        tf[0].v0[a] = (float)v0[a] / 65536.0f;
        tf[0].e1[a] = (float)tq[0].e1[a] / 65536.0f;
        tf[0].e2[a] = (float)tq[0].e2[a] / 65536.0f;
    }
    /* 16 rays down +z from z = -8 near the origin: x and y are parallel axes (d == 0) */
    memset(&rq, 0, sizeof rq);
    memset(&rf, 0, sizeof rf);
    for (i = 0; i < LT_LANES; i++) {
        rq.ox.l[i] = (i % 4) * 4096;
        rq.oy.l[i] = (i / 4) * 4096;
        rq.oz.l[i] = -8 * 65536;
        rq.dz.l[i] = LT_Q30_ONE - 1;
        rq.tmax.l[i] = 100 * 65536;
        rf.ox.l[i] = (float)rq.ox.l[i] / 65536.0f;
        rf.oy.l[i] = (float)rq.oy.l[i] / 65536.0f;
        rf.oz.l[i] = -8.0f;
        rf.dz.l[i] = 1.0f;
        rf.tmax.l[i] = 100.0f;
    }
    lt_ray16_q16_setup(&rq);
    lt_ray16_f32_setup(&rf);
    memset(&r1q, 0, sizeof r1q);
    r1q.o[2] = -8 * 65536;
    r1q.d[2] = LT_Q30_ONE - 1;
    r1q.tmax = 100 * 65536;
    lt_ray1_q16_setup(&r1q);
    memset(&r1f, 0, sizeof r1f);
    r1f.o[2] = -8.0f;
    r1f.d[2] = 1.0f;
    r1f.tmax = 100.0f;
    lt_ray1_f32_setup(&r1f);
    /* Cost: none */
    memset(&bd, 0, sizeof bd);
    CHECKC("lt_bvh_size", lt_bvh_size(1, NULL, &bytes), &none);
    CHECKC("lt_kd_params_default", (lt_kd_params_default(&kp), 0), &none);
    CHECKC("lt_kd_size", lt_kd_size(1, &kp, &bytes), &none);
    CHECKC("lt_grid_params_default", (lt_grid_params_default(&gp), 0), &none);
    /* builds of one triangle: the box, one leaf, its fix-up, the index moved */
    memset(&want, 0, sizeof want);
    ph = LT_PH_BUILD;
    CR(BVH_BUILD_TRI_BOX, 1);
    CR(BVH_BUILD_NODE_POP, 1);
    CR(BVH_BUILD_RANGE_BOX, 1);
    CR(BVH_BUILD_NODE_FIX, 1);
    CR(BVH_BUILD_IDX_MOVE, 1);
    CHECKC("lt_bvh_build_q16 (one triangle)",
           lt_bvh_build_q16(&bq, NULL, tq, 1, arena[0], sizeof arena[0]), &want);
    CHECKC("lt_bvh_build_f32 (one triangle)",
           lt_bvh_build_f32(&bf, NULL, tf, 1, arena[1], sizeof arena[1]), &want);
    bq.isect = bf.isect = LT_ISECT_MT; /* walks composed with lt_tri16 (the MT option) */
    CHECKC("lt_bvhq_size", lt_bvhq_size(&bq, &bytes), &none);
    memset(&want, 0, sizeof want);
    CR(BVHQ_BUILD_NODE, 1);
    CHECKC("lt_bvhq_build_q16 (one leaf)", lt_bvhq_build_q16(&qq, &bq, arena[2], sizeof arena[2]),
           &want);
    /* the kd-tree of one triangle: its bounds, one job (a leaf), the reference moved in place; the
     * grid: the scene bounds, the resolution's bisection (10 steps for this scene), each
     * triangle's cell range (once for the size, twice more in the build: count and fill), the
     * count and fill of its one reference, the prefix sums of the one cell */
    {
        lt_kd_q16_t kd;
        lt_grid_q16_t g;
        memset(&want, 0, sizeof want);
        ph = LT_PH_BUILD;
        CR(KD_BUILD_BOUNDS_TRI, 1);
        CR(KD_BUILD_JOB, 1);
        CR(KD_MOVE_REF, 2);
        bytes = sizeof arena[2];
        CHECKC("lt_kd_build_q16 (one triangle)", lt_kd_build_q16(&kd, tq, 1, &kp, arena[2], &bytes),
               &want);
        memset(&want, 0, sizeof want);
        CR(GRID_BUILD_BOUNDS_TRI, 1);
        CR(GRID_RES_STEP, 10);
        CR(GRID_TRANGE, 1);
        CHECKC("lt_grid_size_q16 (one triangle)", lt_grid_size_q16(tq, 1, &gp, &bytes), &want);
        CR(GRID_TRANGE, 2);
        CR(GRID_BUILD_COUNT_REF, 1);
        CR(GRID_BUILD_FILL_REF, 1);
        CR(GRID_BUILD_PREFIX, 2);
        bytes = sizeof arena[2];
        CHECKC("lt_grid_build_q16 (one triangle)",
               lt_grid_build_q16(&g, tq, 1, &gp, arena[2], &bytes), &want);
        bad += g.ncells != 1;
    }
    memset(&want, 0, sizeof want);
    CR(ISECT_CHUNK_BOX_TRI, 1);
    CHECKC("lt_chunks_build_q16 (one triangle)", lt_chunks_build_q16(tq, 1, &boxq), &want);
    CHECKC("lt_chunks_build_f32 (one triangle)", lt_chunks_build_f32(tf, 1, &boxf), &want);
    for (f = 0; f < 2; f++) {
        char nm[160];
        /* the triangle test: every lane a candidate and a hit; then none a candidate (the same
         * triangle behind the rays' new tmax is still a candidate: use a ray pointing away) */
        memset(&want, 0, sizeof want);
        ph = LT_PH_OTHER;
        CR(ISECT_TRI_LOAD, 1);
        CR(ISECT_TRI_EARLY_OUT, 1);
        if (f) {
            CL(VBCAST, 14);
            CL(FADD, 23);
            CL(FMUL, 24);
            CL(FCMP, 7);
            CL(FDIV, 1);
            CL(VALU, 1);
        } else {
            CL(VBCAST, 18);
            CL(VALU, 5);
            CL(VSHIFT, 7);
            CL(VMUL, 24);
            CL(VMULW, 19);
            CL(VCMP, 7);
            CR(TRI_Q_TDIV16, 1);
        }
        snprintf(nm, sizeof nm, "lt_tri16_%s (16 candidates, hit)", f ? "f32" : "q16");
        rq2 = rq;
        rf2 = rf;
        hit.id = lt_vi32_set1(-1);
        if (f)
            CHECKC(nm, lt_tri16_f32(&rf2, LT_MASK_ALL, &tf[0], 0, &hit), &want);
        else
            CHECKC(nm, lt_tri16_q16(&rq2, LT_MASK_ALL, &tq[0], 0, &hit), &want);
        bad += hit.id.l[0] != 0;
        memset(&want, 0, sizeof want);
        CR(ISECT_TRI_LOAD, 1);
        CR(ISECT_TRI_EARLY_OUT, 1);
        if (f) {
            CL(VBCAST, 13);
            CL(FADD, 22);
            CL(FMUL, 24);
            CL(FCMP, 5);
        } else {
            CL(VBCAST, 17);
            CL(VALU, 3);
            CL(VSHIFT, 7);
            CL(VMUL, 24);
            CL(VMULW, 19);
            CL(VCMP, 5);
        }
        snprintf(nm, sizeof nm, "lt_tri16_%s (no candidate)", f ? "f32" : "q16");
        rq2 = rq;
        rf2 = rf;
        for (i = 0; i < LT_LANES; i++) {
            rq2.ox.l[i] += 50 * 65536;
            rf2.ox.l[i] += 50.0f;
        }
        if (f)
            CHECKC(nm, lt_tri16_f32(&rf2, LT_MASK_ALL, &tf[0], 0, &hit), &want);
        else
            CHECKC(nm, lt_tri16_q16(&rq2, LT_MASK_ALL, &tq[0], 0, &hit), &want);
        /* the slab test with two parallel axes */
        memset(&want, 0, sizeof want);
        CR(ISECT_SLAB_LOAD, 1);
        CR(ISECT_SLAB_AXIS_FLAG, 3);
        CL(VBCAST, 6);
        if (f) {
            CR(ISECT_F_SLAB_PAR, 2);
            CL(FADD, 19);
            CL(FMUL, 6);
            CL(FCMP, 1);
        } else {
            CR(ISECT_Q_SLAB_PAR, 2);
            CL(VALU, 19);
            CL(VMUL, 6);
            CL(VCMP, 1);
        }
        snprintf(nm, sizeof nm, "lt_slab16_%s (x, y parallel)", f ? "f32" : "q16");
        if (f)
            CHECKC(nm, lt_slab16_f32(&rf, LT_MASK_ALL, &((const lt_bvh_node_f32_t *)bf.nodes)[0].b,
                                     &tnf), &want);
        else
            CHECKC(nm, lt_slab16_q16(&rq, LT_MASK_ALL, &((const lt_bvh_node_q16_t *)bq.nodes)[0].b,
                                     &tnq), &want);
        /* one ray: the slab test (two parallel axes), the triangle test (a hit) */
        memset(&want, 0, sizeof want);
        CR(BVH_SLAB1, 1);
        CR(BVH_SLAB1_FIX, 2);
        snprintf(nm, sizeof nm, "lt_slab1_%s (x, y parallel)", f ? "f32" : "q16");
        {
            lt_q16_t t1q;
            float t1f;
            if (f)
                CHECKC(nm, lt_slab1_f32(&r1f, &((const lt_bvh_node_f32_t *)bf.nodes)[0].b, &t1f),
                       &want);
            else
                CHECKC(nm, lt_slab1_q16(&r1q, &((const lt_bvh_node_q16_t *)bq.nodes)[0].b, &t1q),
                       &want);
        }
        memset(&want, 0, sizeof want);
        CR(BVH_TRI1, 1);
        if (!f)
            CR(BVH_TRI1_TDIV, 1);
        snprintf(nm, sizeof nm, "lt_tri1_%s (hit)", f ? "f32" : "q16");
        r1q2 = r1q;
        r1f2 = r1f;
        if (f)
            CHECKC(nm, lt_tri1_f32(&r1f2, &tf[0]), &want);
        else
            CHECKC(nm, lt_tri1_q16(&r1q2, &tq[0]), &want);
        /* chunks: one chunk entered, its triangle */
        memset(&want, 0, sizeof want);
        ph = LT_PH_TRAVERSE;
        CL(VBCAST, 2);
        CR(ISECT_CHUNK_STEP, 1);
        CL(MASK, 1);
        slab_alone(c, ph, f, &rq, &rf, f ? bf.nodes : bq.nodes);
        ph = LT_PH_INTERSECT;
        CR(ISECT_CHUNK_TRI, 1);
        tri_alone(c, ph, f, &rq, &rf, &tq[0], &tf[0]);
        snprintf(nm, sizeof nm, "lt_chunks_trace16_%s (one chunk, hit)", f ? "f32" : "q16");
        rq2 = rq;
        rf2 = rf;
        if (f)
            CHECKC(nm, lt_chunks_trace16_f32(tf, 1, &boxf, LT_ISECT_MT, &rf2, LT_MASK_ALL, &hit), &want);
        else
            CHECKC(nm, lt_chunks_trace16_q16(tq, 1, &boxq, LT_ISECT_MT, &rq2, LT_MASK_ALL, &hit), &want);
        /* BVH walks over the one-leaf tree */
        memset(&want, 0, sizeof want);
        ph = LT_PH_OTHER;
        CL(VBCAST, 1);
        ph = LT_PH_TRAVERSE;
        CL(VBCAST, 2);
        CR(BVH_TRAV_NODE, 1);
        CR(BVH_TRAV_ANY_EXIT, 1);
        slab_alone(c, ph, f, &rq, &rf, f ? bf.nodes : bq.nodes);
        ph = LT_PH_INTERSECT;
        CR(BVH_TRAV_LEAF_TRI, 1);
        tri_alone(c, ph, f, &rq, &rf, &tq[0], &tf[0]);
        if (f) {
            snprintf(nm, sizeof nm, "lt_bvh_trace16_f32 (one leaf)");
            rf2 = rf;
            CHECKC(nm, lt_bvh_trace16_f32(&bf, tf, &rf2, LT_MASK_ALL, &hit), &want);
        }
        ph = LT_PH_INTERSECT;
        CR(BVH_TRAV_ANY_RETIRE, 1);
        snprintf(nm, sizeof nm, "lt_bvh_occluded16_%s (one leaf)", f ? "f32" : "q16");
        rq2 = rq;
        rf2 = rf;
        if (f)
            CHECKC(nm, lt_bvh_occluded16_f32(&bf, tf, &rf2, LT_MASK_ALL, &m), &want);
        else
            CHECKC(nm, lt_bvh_occluded16_q16(&bq, tq, &rq2, LT_MASK_ALL, &m), &want);
        bad += m != LT_MASK_ALL;
        if (!f) {
            /* the quantised tree: the root box is stored whole, the node step loads one word */
            memset(&want, 0, sizeof want);
            ph = LT_PH_OTHER;
            CL(VBCAST, 1);
            ph = LT_PH_TRAVERSE;
            CL(VBCAST, 2);
            CR(BVH_TRAV_NODE1, 1);
            CR(BVH_TRAV_ANY_EXIT, 1);
            slab_alone(c, ph, f, &rq, &rf, bq.nodes);
            ph = LT_PH_INTERSECT;
            CR(BVH_TRAV_LEAF_TRI, 1);
            tri_alone(c, ph, f, &rq, &rf, &tq[0], &tf[0]);
            rq2 = rq;
            CHECKC("lt_bvhq_trace16_q16 (one leaf)",
                   lt_bvhq_trace16_q16(&qq, tq, &rq2, LT_MASK_ALL, &hit), &want);
            CR(BVH_TRAV_ANY_RETIRE, 1);
            rq2 = rq;
            CHECKC("lt_bvhq_occluded16_q16 (one leaf)",
                   lt_bvhq_occluded16_q16(&qq, tq, &rq2, LT_MASK_ALL, &m), &want);
        }
        /* one ray: the root slab test (two parallel axes), one node, the leaf's triangle */
        memset(&want, 0, sizeof want);
        ph = LT_PH_TRAVERSE;
        CR(BVH_SLAB1, 1);
        CR(BVH_SLAB1_FIX, 2);
        CR(BVH_TRAV_NODE, 1);
        ph = LT_PH_INTERSECT;
        CR(BVH_TRAV_LEAF_TRI, 1);
        CR(BVH_TRI1, 1);
        if (!f)
            CR(BVH_TRI1_TDIV, 1);
        snprintf(nm, sizeof nm, "lt_bvh_trace1_%s (one leaf)", f ? "f32" : "q16");
        r1q2 = r1q;
        r1f2 = r1f;
        if (f)
            CHECKC(nm, lt_bvh_trace1_f32(&bf, tf, &r1f2, &id), &want);
        else
            CHECKC(nm, lt_bvh_trace1_q16(&bq, tq, &r1q2, &id), &want);
        bad += id != 0;
        snprintf(nm, sizeof nm, "lt_bvh_occluded1_%s (one leaf)", f ? "f32" : "q16");
        r1q2 = r1q;
        r1f2 = r1f;
        if (f)
            CHECKC(nm, lt_bvh_occluded1_f32(&bf, tf, &r1f2, &occ), &want);
        else
            CHECKC(nm, lt_bvh_occluded1_q16(&bq, tq, &r1q2, &occ), &want);
        bad += occ != 1;
        if (!f) {
            memset(&want, 0, sizeof want);
            ph = LT_PH_TRAVERSE;
            CR(BVH_SLAB1, 1);
            CR(BVH_SLAB1_FIX, 2);
            CR(BVH_TRAV_NODE1, 1);
            ph = LT_PH_INTERSECT;
            CR(BVH_TRAV_LEAF_TRI, 1);
            CR(BVH_TRI1, 1);
            CR(BVH_TRI1_TDIV, 1);
            r1q2 = r1q;
            CHECKC("lt_bvhq_trace1_q16 (one leaf)", lt_bvhq_trace1_q16(&qq, tq, &r1q2, &id), &want);
        }
    }
    (void)bd;
    assert_int_equal(bad, 0);
}

#else /* not the sim build */

static void skip_costs(const char *what)
{
    ltt_report("%s: not counted in this build (LT_COST_OFF); the sim build of test_costs checks "
               "it\n",
               what);
}
static void test_recipe_charges(void **state)
{
    (void)state;
    skip_costs("recipe charges");
}
static void test_kernel_costs_q16(void **state)
{
    (void)state;
    skip_costs("kernel costs (s15.16)");
}
static void test_bvh_step_q16(void **state)
{
    (void)state;
    skip_costs("BVH traversal step");
}
static void test_screen_walk_costs(void **state)
{
    (void)state;
    skip_costs("screen-space walks (quadtree, DDA, Hi-Z)");
}
static void test_screen_build_costs(void **state)
{
    (void)state;
    skip_costs("screen-space builds (quadtree, Hi-Z)");
}
static void test_screen_fixed_costs(void **state)
{
    (void)state;
    skip_costs("screen-space set-up and reprojection");
}
static void test_frusta_costs(void **state)
{
    (void)state;
    skip_costs("multi-frusta");
}
static void test_object_costs(void **state)
{
    (void)state;
    skip_costs("object-space kernels (one-triangle scene)");
}
#if LT_CFG_FLOAT32
static void test_recommend_mix(void **state)
{
    (void)state;
    skip_costs("lanetrace info's triangle-test op lists");
}
static void test_kernel_costs_f32(void **state)
{
    (void)state;
    skip_costs("kernel costs (float32)");
}
#endif
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_recipe_table),
        cmocka_unit_test(test_recipe_charges),
        cmocka_unit_test(test_kernel_costs_q16),
        cmocka_unit_test(test_bvh_step_q16),
        cmocka_unit_test(test_screen_walk_costs),
        cmocka_unit_test(test_screen_build_costs),
        cmocka_unit_test(test_screen_fixed_costs),
        cmocka_unit_test(test_frusta_costs),
        cmocka_unit_test(test_object_costs),
#if LT_CFG_FLOAT32
        cmocka_unit_test(test_kernel_costs_f32),
        cmocka_unit_test(test_recommend_mix),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
