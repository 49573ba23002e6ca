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
    assert_int_equal(lt_rec_machine_costs("z80", &c), -1);
    assert_int_equal(c.f32 + c.q16 + c.lanes, 0);
    print_message("recommend: mcu-m4 picks leaf 4 and prices the paths from its machine file\n");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_teapot),
        cmocka_unit_test(test_unrepresentable_small),
        cmocka_unit_test(test_limits),
        cmocka_unit_test(test_few_steps),
        cmocka_unit_test(test_machines),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
