/* test_diag.c - cmocka tests of host/io/lt_diag (the one diagnostic type): printf formatting and
 * the -1 return, a NULL diag, messages that exactly fit, messages cut with the "..." marker,
 * context put in front (lt_diag_prefix) with and without cutting, a wrapper over lt_diag_vfail,
 * and a message whose arguments cannot be formatted. Builds: host, sim, asan.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>
#include <wchar.h>

#include "io/lt_diag.h"

/* a string of n copies of c (n < sizeof buf) */
static const char *run_of(char c, size_t n)
{
    static char buf[4 * LT_DIAG_MAX];
    assert_true(n < sizeof buf);
    memset(buf, c, n);
    buf[n] = '\0';
    return buf;
}

/* 1 when s ends with the cut marker and has the longest length a message can have */
static int is_cut(const char *s)
{
    size_t n = strlen(s), k = strlen(LT_DIAG_CUT);
    return n == LT_DIAG_MAX - 1 && strcmp(s + n - k, LT_DIAG_CUT) == 0;
}

static void test_diag_format(void **state)
{
    lt_diag_t d;
    (void)state;
    assert_int_equal(lt_diag_fail(&d, "%s: %d triangles (need 1..%u)", "a.obj", 0, 5u), -1);
    assert_string_equal(d.msg, "a.obj: 0 triangles (need 1..5)");
    assert_int_equal(lt_diag_fail(&d, "%s", ""), -1);
    assert_string_equal(d.msg, "");
    /* a second failure replaces the first message */
    assert_int_equal(lt_diag_fail(&d, "first"), -1);
    assert_int_equal(lt_diag_fail(&d, "second %.2f", 0.5), -1);
    assert_string_equal(d.msg, "second 0.50");
    printf("diag: formats printf-style, returns -1, a new failure replaces the old message\n");
}

static void test_diag_null(void **state)
{
    (void)state;
    assert_int_equal(lt_diag_fail(NULL, "x %d", 1), -1);
    assert_int_equal(lt_diag_prefix(NULL, "%s: ", "p"), -1);
    printf("diag: a NULL diag is accepted by lt_diag_fail and lt_diag_prefix (still -1)\n");
}

static void test_diag_truncation(void **state)
{
    lt_diag_t d;
    const size_t max = LT_DIAG_MAX - 1;
    (void)state;
    /* exactly the longest message: kept whole, no marker */
    (void)lt_diag_fail(&d, "%s", run_of('a', max));
    assert_int_equal(strlen(d.msg), max);
    assert_int_equal(strspn(d.msg, "a"), max);
    /* one byte more: cut, ends with the marker, the rest is the message's beginning */
    (void)lt_diag_fail(&d, "%s", run_of('b', max + 1));
    assert_true(is_cut(d.msg));
    assert_int_equal(strspn(d.msg, "b"), max - strlen(LT_DIAG_CUT));
    /* far longer, with a path at the front: the path survives */
    (void)lt_diag_fail(&d, "%s: %s", "/x/y.exr", run_of('c', 3 * LT_DIAG_MAX));
    assert_true(is_cut(d.msg));
    assert_memory_equal(d.msg, "/x/y.exr: ccc", 13);
    printf("diag: %zu bytes kept whole, %zu and %d cut to %zu ending in \"%s\"\n", max, max + 1,
           3 * LT_DIAG_MAX + 10, max, LT_DIAG_CUT);
}

static void test_diag_prefix(void **state)
{
    lt_diag_t d;
    const size_t max = LT_DIAG_MAX - 1;
    (void)state;
    (void)lt_diag_fail(&d, "image %dx%d outside 1..%d", 0, 4, 16384);
    assert_int_equal(lt_diag_prefix(&d, "%s: ", "out.png"), -1);
    assert_string_equal(d.msg, "out.png: image 0x4 outside 1..16384");
    (void)lt_diag_fail(&d, "x");
    (void)lt_diag_prefix(&d, "%s", "");
    assert_string_equal(d.msg, "x");
    /* prefix + message exactly fit */
    (void)lt_diag_fail(&d, "%s", run_of('m', max - 3));
    (void)lt_diag_prefix(&d, "%s", "p: ");
    assert_int_equal(strlen(d.msg), max);
    assert_memory_equal(d.msg, "p: mmm", 6);
    assert_int_equal(d.msg[max - 1], 'm');
    /* one byte too many: cut, the prefix first */
    (void)lt_diag_fail(&d, "%s", run_of('m', max - 2));
    (void)lt_diag_prefix(&d, "%s", "p: ");
    assert_true(is_cut(d.msg));
    assert_memory_equal(d.msg, "p: mmm", 6);
    /* a message already cut stays cut under a prefix */
    (void)lt_diag_fail(&d, "%s", run_of('n', 2 * LT_DIAG_MAX));
    (void)lt_diag_prefix(&d, "%s: ", "scene.json");
    assert_true(is_cut(d.msg));
    assert_memory_equal(d.msg, "scene.json: nnn", 15);
    /* a prefix longer than the buffer: cut, the old message gone */
    (void)lt_diag_fail(&d, "old");
    (void)lt_diag_prefix(&d, "%s", run_of('q', 2 * LT_DIAG_MAX));
    assert_true(is_cut(d.msg));
    assert_null(strstr(d.msg, "old"));
    printf("diag: lt_diag_prefix puts context first; exact fit kept, overflow cut with \"%s\"\n",
           LT_DIAG_CUT);
}

/* a module's own wrapper, as host/io/lt_scenefile.c has: the message, then the file in front */
static int ctx_fail(lt_diag_t *d, const char *name, const char *fmt, ...) LT_DIAG_PRINTF(3, 4);
static int ctx_fail(lt_diag_t *d, const char *name, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    (void)lt_diag_vfail(d, fmt, ap);
    va_end(ap);
    return lt_diag_prefix(d, "%s: ", name);
}

static void test_diag_vfail(void **state)
{
    lt_diag_t d;
    (void)state;
    assert_int_equal(ctx_fail(&d, "s.json", "'%s' must be a number", "fov_y_deg"), -1);
    assert_string_equal(d.msg, "s.json: 'fov_y_deg' must be a number");
    assert_int_equal(ctx_fail(NULL, "s.json", "'%s' must be a number", "fov_y_deg"), -1);
    printf("diag: lt_diag_vfail serves a wrapper that adds its context\n");
}

static void test_diag_unformattable(void **state)
{
    lt_diag_t d;
    static const wchar_t smile[] = {0x263a, 0};
    (void)state;
    /* in the C locale a wide character outside ASCII has no multibyte form: vsnprintf fails */
    (void)lt_diag_fail(&d, "hid: %ls", smile);
    assert_true(strncmp(d.msg, "hid: ", 5) == 0);
    assert_true(strlen(d.msg) < LT_DIAG_MAX);
    printf("diag: an unformattable argument still leaves a message: \"%s\"\n", d.msg);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_diag_format),     cmocka_unit_test(test_diag_null),
        cmocka_unit_test(test_diag_truncation), cmocka_unit_test(test_diag_prefix),
        cmocka_unit_test(test_diag_vfail),      cmocka_unit_test(test_diag_unformattable),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
