/* test_recommend.c - cmocka tests of host/tune/lt_recommend (lanetrace info's recommendation):
 * the numeric pick follows lt_scene_check_q16's rule (collapsed triangles over 0.1%) and the
 * shortest edge in s15.16 steps; the structure switches to a BVH above LT_REC_BVH_MIN_TRIS; every
 * reason carries the scene's numbers. Builds: host, sim, asan.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "tune/lt_recommend.h"

static const lt_rec_pick_t *knob(const lt_rec_t *r, const char *name)
{
    int i;
    for (i = 0; i < r->n; i++)
        if (strcmp(r->k[i].knob, name) == 0)
            return &r->k[i];
    fail_msg("no knob %s", name);
    return NULL;
}

/* the teapot's facts (lanetrace info): 992 triangles, none collapse, a wide margin */
static void test_teapot(void **state)
{
    lt_rec_mesh_facts_t f = {992, 992, 0, 6.4, 0.0211, 0.16, "lrb16"};
    lt_rec_t r;
    (void)state;
    lt_recommend_mesh(&f, &r);
    assert_int_equal(r.n, 3);
    assert_true(r.q16_ok);
    assert_string_equal(knob(&r, "numeric")->pick, "f32");
    assert_non_null(strstr(knob(&r, "numeric")->reason, "q16 holds it too (0 of 992"));
    assert_non_null(strstr(knob(&r, "numeric")->reason, "cheaper on lrb16"));
    assert_string_equal(knob(&r, "structure")->pick, "bvh");
    assert_non_null(strstr(knob(&r, "structure")->reason, "992 triangles (> 256)"));
    assert_string_equal(knob(&r, "leaf")->pick, "16");
    assert_non_null(strstr(knob(&r, "leaf")->reason, "about 62 leaves"));
}

/* cli.sh's wide.obj: 10 of 11 collapse -> f32 with the counts; 11 triangles -> chunks */
static void test_unrepresentable_small(void **state)
{
    lt_rec_mesh_facts_t f = {11, 11, 10, 2e6, 1e-3, 0.000488281, NULL};
    lt_rec_t r;
    (void)state;
    lt_recommend_mesh(&f, &r);
    assert_false(r.q16_ok);
    assert_string_equal(knob(&r, "numeric")->pick, "f32");
    assert_non_null(strstr(knob(&r, "numeric")->reason, "not representable in s15.16: 10 of 11"));
    assert_non_null(strstr(knob(&r, "numeric")->reason, "dynamic range 2^30.9"));
    assert_string_equal(knob(&r, "structure")->pick, "chunks");
    assert_non_null(strstr(knob(&r, "structure")->reason, "11 triangles (<= 256): 1 chunk"));
    assert_string_equal(knob(&r, "leaf")->pick, "-");
}

/* the limit is lt_scene_check_q16's: 1 of 1000 collapsing is representable, 2 of 1000 is not;
 * the structure threshold is exclusive (256 chunks, 257 bvh) */
static void test_limits(void **state)
{
    lt_rec_mesh_facts_t f = {256, 1000, 1, 100.0, 1.0, 10.0, NULL};
    lt_rec_t r;
    (void)state;
    lt_recommend_mesh(&f, &r);
    assert_true(r.q16_ok);
    assert_string_equal(knob(&r, "structure")->pick, "chunks");
    f.collapsed_q16 = 2;
    f.ntris = 257;
    lt_recommend_mesh(&f, &r);
    assert_false(r.q16_ok);
    assert_string_equal(knob(&r, "structure")->pick, "bvh");
}

/* representable, but the shortest edge spans fewer than LT_REC_MIN_EDGE_STEPS steps */
static void test_few_steps(void **state)
{
    lt_rec_mesh_facts_t f = {500, 500, 0, 1000.0, 1e-4, 1.0, NULL}; /* 1e-4 * 65536 = 6.6 steps */
    lt_rec_t r;
    (void)state;
    lt_recommend_mesh(&f, &r);
    assert_true(r.q16_ok);
    assert_true(r.edge_steps < LT_REC_MIN_EDGE_STEPS);
    assert_string_equal(knob(&r, "numeric")->pick, "f32");
    assert_non_null(strstr(knob(&r, "numeric")->reason, "shortest edge spans 6.55 steps"));
}

/* The machine decides the leaf (16 lanes: 16, one lane: 4) and prices the paths: each path's cost
 * is its triangle test's op list at the machine's issue cycles (lt_rec_machine_costs), and the
 * numeric reason quotes both figures. An unknown machine has no costs. */
static void test_machines(void **state)
{
    lt_rec_mesh_facts_t f = {992, 992, 0, 6.4, 0.0211, 0.16, "mcu-m4"};
    lt_rec_costs_t c;
    uint32_t rq, rf;
    lt_rec_t r;
    char want[96];
    (void)state;
    assert_int_equal(lt_rec_machine_costs("mcu-m4", &c), 0);
    assert_int_equal(c.lanes, 1);
    assert_true(c.f32 > 0 && c.q16 > 0);
    lt_recommend_mesh(&f, &r);
    assert_string_equal(r.machine, "mcu-m4");
    assert_string_equal(knob(&r, "leaf")->pick, "4");
    assert_non_null(strstr(knob(&r, "leaf")->reason, "about 248 leaves"));
    snprintf(want, sizeof want, "%u", c.q16 < c.f32 ? c.q16 : c.f32);
    assert_non_null(strstr(knob(&r, "numeric")->reason, want));
    assert_string_equal(knob(&r, "numeric")->pick, c.q16 < c.f32 ? "q16" : "f32");
    assert_int_equal(lt_rec_machine_costs("lrb16", &c), 0);
    assert_int_equal(c.lanes, 16);
    /* the integer-only RV32IMAC: float32 in soft float, s15.16 is the cheap side */
    f.machine = "rv32imac";
    lt_recommend_mesh(&f, &r);
    assert_int_equal(lt_rec_machine_costs("rv32imac", &c), 0);
    assert_true(c.q16 < c.f32);
    assert_string_equal(knob(&r, "numeric")->pick, "q16");
    assert_non_null(strstr(knob(&r, "numeric")->reason, "cheaper on rv32imac"));
    rq = c.q16;
    rf = c.f32;
    assert_int_equal(lt_rec_machine_costs("z80", &c), -1);
    assert_int_equal(c.f32 + c.q16 + c.lanes, 0);
    print_message("recommend: mcu-m4 picks leaf 4 and prices the paths from its machine file; "
                  "rv32imac picks s15.16 (%u against %u cycles)\n", rq, rf);
}

/* Depth facts: a tilted plane (linear in 1/z) is planar everywhere with no jumps; a step of 2x is a
 * jump on its border; NaN, 0 and inf are holes and never neighbours. */
static void test_depth_scan(void **state)
{
    float z[8 * 8];
    lt_rec_depth_facts_t f;
    int x, y;
    (void)state;
    for (y = 0; y < 8; y++)
        for (x = 0; x < 8; x++)
            z[y * 8 + x] = (float)(1.0 / (0.5 + 0.01 * x + 0.02 * y));
    lt_rec_depth_scan(z, 8, 8, &f);
    assert_int_equal(f.valid, 64);
    assert_int_equal(f.holes, 0);
    assert_int_equal(f.pairs, 2 * 8 * 7);
    assert_int_equal(f.jumps, 0);
    assert_int_equal(f.inner, 36);
    assert_int_equal(f.planar, 36);
    for (y = 0; y < 8; y++)
        for (x = 0; x < 8; x++)
            z[y * 8 + x] = x < 4 ? 2.0f : 4.0f;
    z[0] = 0.0f / 0.0f;
    z[1] = 0.0f;
    z[2] = 1.0f / 0.0f;
    lt_rec_depth_scan(z, 8, 8, &f);
    assert_int_equal(f.holes, 3);
    assert_int_equal(f.valid, 61);
    assert_int_equal(f.jumps, 8);               /* the x = 3 | 4 border, one pair per row */
    assert_true(f.zmin == 2.0 && f.zmax == 4.0);
    assert_int_equal(f.pairs, 2 * 8 * 7 - 6);  /* pairs touching the 3 holes: 3 across, 3 down */
    print_message("depth scan: plane 36 of 36 inner pixels planar, step 8 jumps, 3 holes\n");
}

/* The node format: the range gate first (s1.30 coarser than float32 at the far end: f32 whatever
 * it costs), then the machine's quadtree rows weighed at the real source and target sizes. */
static void test_depth_pick(void **state)
{
    lt_rec_depth_facts_t f;
    lt_rec_t r;
    double b64, bf;
    (void)state;
    memset(&f, 0, sizeof f);
    f.width = 911;
    f.height = 876;
    f.valid = 600000;
    f.zmin = 9.0;
    f.zmax = 10.92;
    f.machine = "lrb16";
    /* a small target: the build dominates, n64's build is cheaper on lrb16 */
    f.target_px = 256 * 256;
    lt_recommend_depth(&f, &r);
    b64 = lt_rec_qt_cost("lrb16", "n64", 911.0 * 876, 65536.0);
    bf = lt_rec_qt_cost("lrb16", "f32", 911.0 * 876, 65536.0);
    assert_true(b64 > 0.0 && bf > 0.0);
    assert_string_equal(knob(&r, "num")->pick, b64 <= bf ? "n64" : "f32");
    assert_non_null(strstr(knob(&r, "num")->reason, "911x876 to 65536 target pixels"));
    /* mcu-m4 (float32 is cheaper per pixel in both parts there) */
    f.machine = "mcu-m4";
    lt_recommend_depth(&f, &r);
    assert_string_equal(knob(&r, "num")->pick,
                        lt_rec_qt_cost("mcu-m4", "n64", 911.0 * 876, 65536.0) <=
                                lt_rec_qt_cost("mcu-m4", "f32", 911.0 * 876, 65536.0) ? "n64" : "f32");
    assert_non_null(strstr(knob(&r, "num")->reason, "on mcu-m4"));
    /* depths 1e-3 .. 1e4: z_ref = 2^-10, the far step 2^-31 1e4 / 2^-10 = 4.8e-3 > 2^-24 */
    f.machine = "lrb16";
    f.zmin = 1e-3;
    f.zmax = 1e4;
    lt_recommend_depth(&f, &r);
    assert_string_equal(knob(&r, "num")->pick, "f32");
    assert_non_null(strstr(knob(&r, "num")->reason, "coarser than float32"));
    /* the gate's edge: z_ref = 8 for zmin 9, so zmax up to 8 2^7 = 1024 passes, 1100 does not */
    f.zmin = 9.0;
    f.zmax = 1000.0;
    lt_recommend_depth(&f, &r);
    assert_null(strstr(knob(&r, "num")->reason, "coarser"));
    f.zmax = 1100.0;
    lt_recommend_depth(&f, &r);
    assert_non_null(strstr(knob(&r, "num")->reason, "coarser than float32"));
    /* no valid depth: the default */
    f.valid = 0;
    lt_recommend_depth(&f, &r);
    assert_string_equal(knob(&r, "num")->pick, "n64");
    assert_true(lt_rec_qt_cost("z80", "n64", 1.0, 1.0) == 0.0);
    {
        /* every machine file has its quadtree rows (docs/cost-model.md, "Adding a machine") */
        static const char *const names[] = {
#define LT_MACHINE(id, name, desc, clock_mhz, lanes) name,
#include "lt_machines.h"
            NULL};
        int i;
        for (i = 0; names[i] != NULL; i++) {
            if (!(lt_rec_qt_cost(names[i], "n64", 1.0, 0.0) > 0.0 &&
                  lt_rec_qt_cost(names[i], "n32", 0.0, 1.0) > 0.0 &&
                  lt_rec_qt_cost(names[i], "f32", 1.0, 1.0) > 0.0))
                fail_msg("machine %s: no LT_MACHINE_QT rows (tests/bench/qtcal.sh prints them)",
                         names[i]);
        }
        print_message("every machine file (%d) has its quadtree rows\n", i);
    }
    assert_true(lt_rec_qt_cost("lrb16", "n16", 1.0, 1.0) == 0.0);
    print_message("depth pick: range gate at 2^-24, costs from the machine rows\n");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_teapot),
        cmocka_unit_test(test_unrepresentable_small),
        cmocka_unit_test(test_limits),
        cmocka_unit_test(test_few_steps),
        cmocka_unit_test(test_machines),
        cmocka_unit_test(test_depth_scan),
        cmocka_unit_test(test_depth_pick),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
