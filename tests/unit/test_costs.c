/* test_costs.c - the cost recipes (firmware/include/lt/lt_recipes.def) and the kernels' documented
 * costs. In the sim build: every recipe charges exactly its ops times n (LT_CHARGE_N), has a reason
 * and at least one op; and each covered public kernel, run on fixed inputs, charges exactly what the
 * Cost: line of its header says (op classes summed over phases): lt_ray16_q16_setup, lt_slab16_q16
 * (all lanes, no flagged axis), lt_ray1_q16_setup, lt_slab1_q16, lt_tri1_q16 (miss, hit),
 * lt_ray16_wt_setup_q16, lt_tri16_wt_q16 (coherent packet, miss), the float32 twins, and one
 * BVH packet traversal step (a one-leaf tree: the step's recipes plus the slab and triangle tests).
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
#include "lt_test_util.h"
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
    char err[128];
    assert_int_equal(lt_sim_init(lt_sim_machine_find("lrb16"), NULL, NULL, err, sizeof err), 0);
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
    CHECK("lt_ray16_wt_setup_q16", lt_ray16_wt_setup_q16(&r, &w), W(VALU, 16), W(VCMP, 5),
          W(VDIV, 3), W(VBCAST, 1), W(MASK, 23));
    CHECK("lt_tri16_wt_q16 (one permutation, miss)",
          lt_tri16_wt_q16(&r, &w, 0xFFFFu, &tm, 0, &hit), W(SLOAD, 9), W(SALU, 15), W(SMUL, 6),
          W(BRANCH, 1), W(MASK, 27), W(VBCAST, 10), W(VALU, 15), W(VMUL, 12), W(VMULW, 5),
          W(VCMP, 8));
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
    (void)tn;
    assert_int_equal(bad, 0);
}
#endif

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
#if LT_CFG_FLOAT32
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
#if LT_CFG_FLOAT32
        cmocka_unit_test(test_kernel_costs_f32),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
