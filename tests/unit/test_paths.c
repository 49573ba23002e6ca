/* test_paths.c - cmocka tests of host/render/lt_paths (the host's registry of numeric paths): the
 * names are unique; each family's enumeration value maps back to its entry (lt_path_t, lt_qt_enc_t,
 * LT_BVH_NUM_*, lt_sf_num_t, lt_ssb_enc_t) and every value of those enumerations has an entry; the
 * scene file accepts exactly the registry's names for "numeric" (plus "both") and
 * "reproject.encoding"; the name lists for options and messages; the fixed-point conversions round
 * trip, and the float path's is the binary32 bit pattern. Run from the repository root (the scene
 * file names scenes/teapot.obj). Builds: host, sim, asan.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io/lt_scenefile.h"
#include "lt/lt_bvh.h"
#include "render/lt_paths.h"

static void test_names_unique_and_found(void **state)
{
    const lt_path_info_t *p, *q;
    int n = 0;
    (void)state;
    for (p = lt_paths; p->name != NULL; p++, n++) {
        assert_non_null(p->format);
        assert_non_null(p->desc);
        assert_true(p->families != 0);
        for (q = p + 1; q->name != NULL; q++)
            assert_string_not_equal(p->name, q->name);
        assert_ptr_equal(lt_paths_find(p->name, 0), p);
        assert_ptr_equal(lt_paths_find(p->name, p->families), p);
        /* a family serves: its enumeration value exists */
        assert_int_equal((p->families & LT_PATHS_OBJECT) != 0, p->render != NULL);
        assert_int_equal((p->families & LT_PATHS_SCREEN) != 0, p->screen != NULL);
        assert_int_equal((p->families & LT_PATHS_OBJECT) != 0, p->bvh_num != 0);
        assert_int_equal((p->families & LT_PATHS_OBJECT) != 0, p->sf_num != 0);
        assert_int_equal((p->families & LT_PATHS_SCREEN) != 0, p->qt_enc >= 0);
        assert_int_equal((p->families & LT_PATHS_SCREEN) != 0, p->ssb_enc >= 0);
        assert_int_equal(p->frac_bits == 0, strcmp(p->format, "float32") == 0);
        assert_true(p->qt_enc < LT_PATHS_MAX);
        assert_int_equal(lt_paths_index(p), n);
    }
    assert_int_equal(n, 4);
    assert_true(n < LT_PATHS_MAX);
    assert_null(lt_paths_find("n64", LT_PATHS_OBJECT));
    assert_null(lt_paths_find("q16", LT_PATHS_SCREEN));
    assert_null(lt_paths_find("both", 0));
    assert_null(lt_paths_find(NULL, 0));
}

static void test_enumerations_map_back(void **state)
{
    const lt_path_info_t *q16 = lt_paths_find("q16", 0), *f32 = lt_paths_find("f32", 0);
    const lt_path_info_t *n64 = lt_paths_find("n64", 0), *n32 = lt_paths_find("n32", 0);
    (void)state;
    assert_ptr_equal(lt_paths_of_qt_enc(LT_QT_N64), n64);
    assert_ptr_equal(lt_paths_of_qt_enc(LT_QT_N32), n32);
    assert_ptr_equal(lt_paths_of_qt_enc(LT_QT_F32), f32);
    assert_int_equal(q16->bvh_num, LT_BVH_NUM_Q16);
    assert_int_equal(f32->bvh_num, LT_BVH_NUM_F32);
    assert_int_equal(q16->sf_num | f32->sf_num, LT_SF_NUM_BOTH);
    assert_int_equal(q16->sf_num, LT_SF_NUM_Q16);
    assert_int_equal(n64->ssb_enc, LT_SSB_Q30);
    assert_int_equal(n32->ssb_enc, LT_SSB_Q30);
    assert_int_equal(f32->ssb_enc, LT_SSB_F32);
    assert_string_equal(q16->format, "s15.16");
    assert_string_equal(n64->format, "s1.30");
    assert_string_equal(f32->format, "float32");
}

static void test_lists(void **state)
{
    const char *names[8];
    char buf[128];
    (void)state;
    assert_int_equal(lt_paths_names(LT_PATHS_OBJECT, names, 8), 2);
    assert_string_equal(names[0], "q16");
    assert_string_equal(names[1], "f32");
    assert_null(names[2]);
    assert_int_equal(lt_paths_names(LT_PATHS_SCREEN, names, 8), 3);
    assert_string_equal(names[0], "n64");
    assert_string_equal(names[2], "f32");
    assert_int_equal(lt_paths_names(LT_PATHS_SCREEN, names, 2), 1);
    assert_null(names[1]);
    lt_paths_list(LT_PATHS_SCREEN, buf, sizeof buf);
    assert_string_equal(buf, "n64, n32 or f32");
    lt_paths_list(LT_PATHS_FRUSTA, buf, sizeof buf);
    assert_string_equal(buf, "q16 or f32");
}

/* the scene file's validator keeps its own lists (it links without the renderer): they must be
 * the registry's */
static void test_scene_file_agrees(void **state)
{
    const lt_path_info_t *p;
    lt_scenefile_t sf;
    char text[256];
    lt_diag_t diag;
    (void)state;
    for (p = lt_paths; p->name != NULL; p++) {
        snprintf(text, sizeof text, "{\"mesh\": \"scenes/teapot.obj\", \"numeric\": \"%s\"}",
                 p->name);
        lt_sf_defaults(&sf);
        assert_int_equal(lt_sf_parse(text, "t.json", ".", &sf, &diag) == 0,
                         (p->families & LT_PATHS_OBJECT) != 0);
        if (p->families & LT_PATHS_OBJECT)
            assert_int_equal((int)sf.numeric, p->sf_num);
        snprintf(text, sizeof text,
                 "{\"mesh\": \"scenes/teapot.obj\", \"reproject\": {\"encoding\": \"%s\"}}",
                 p->name);
        lt_sf_defaults(&sf);
        assert_int_equal(lt_sf_parse(text, "t.json", ".", &sf, &diag) == 0,
                         (p->families & LT_PATHS_SCREEN) != 0);
        if (p->families & LT_PATHS_SCREEN)
            assert_ptr_equal(lt_paths_find(sf.rp_encoding, LT_PATHS_SCREEN), p);
    }
    lt_sf_defaults(&sf);
    assert_int_equal(lt_sf_parse("{\"mesh\": \"scenes/teapot.obj\", \"numeric\": \"both\"}",
                                 "t.json", ".", &sf, &diag),
                     0);
    assert_int_equal((int)sf.numeric, LT_SF_NUM_BOTH);
}

static void test_conversions(void **state)
{
    const lt_path_info_t *q16 = lt_paths_find("q16", 0), *n64 = lt_paths_find("n64", 0);
    const lt_path_info_t *f32 = lt_paths_find("f32", 0);
    (void)state;
    assert_true(lt_path_to_double(q16, 65536) == 1.0);
    assert_true(lt_path_to_double(q16, -1) == -ldexp(1.0, -16));
    assert_true(lt_path_to_double(n64, 1 << 30) == 1.0);
    assert_int_equal(lt_path_from_double(q16, 1.5), 98304);
    assert_int_equal(lt_path_from_double(n64, 1e-3), 1073742);
    assert_int_equal(lt_path_from_double(n64, 5.0), INT32_MAX); /* saturates like the core */
    assert_int_equal(lt_path_from_double(q16, -0.5 / 65536.0), 0); /* half up */
    assert_int_equal(lt_path_from_double(f32, 1.0), 0x3f800000);
    assert_true(lt_path_to_double(f32, 0x3f800000) == 1.0);
    assert_true(lt_path_to_double(f32, lt_path_from_double(f32, 0.1)) == (double)0.1f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_names_unique_and_found), cmocka_unit_test(test_enumerations_map_back),
        cmocka_unit_test(test_lists),                  cmocka_unit_test(test_scene_file_agrees),
        cmocka_unit_test(test_conversions),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
