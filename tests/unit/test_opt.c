/* test_opt.c - cmocka tests of host/cli/lt_opt (the subcommands' table-driven option parser):
 * every kind reads a valid value and refuses trailing garbage, non-finite numbers, an exponent
 * where an integer is due, and values outside the range, with the uniform messages (the range and
 * the limit's name in them); unknown options, missing values, required options, positional
 * arguments, repeated options (last wins, seen = the argv index), deprecated spellings (note on
 * stderr), and the help printed from the table. Builds: host, sim, asan.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/lt_opt.h"

/* the state a test table writes into */
typedef struct st {
    int flag, quiet, n, e, seen_n, seen_e, seen_v, seen_a, seen_b;
    double d, dopen, v[3];
    uint32_t wh[2];
    const char *s, *req;
    int custom;
} st_t;

static const char *const colours[] = {"red", "green", "blue", NULL};

static int parse_even(const char *t, void *dest, const void *ctx)
{
    long x;
    (void)ctx;
    if (lt_opt_read_long(t, &x) != 0 || x % 2 != 0)
        return -1;
    *(int *)dest = (int)x;
    return 0;
}

static char g_err[4096]; /* what the last parse printed on stderr */
static char g_out[8192]; /* what it printed on stdout */

/* Redirect fd into a temporary file around the call and read it back into buf. */
static int capture_begin(int fd, FILE **tmp)
{
    int saved;
    fflush(NULL);
    *tmp = tmpfile();
    assert_non_null(*tmp);
    saved = dup(fd);
    assert_true(saved >= 0);
    assert_true(dup2(fileno(*tmp), fd) >= 0);
    return saved;
}

static void capture_end(int fd, int saved, FILE *tmp, char *buf, size_t n)
{
    size_t k;
    fflush(NULL);
    assert_true(dup2(saved, fd) >= 0);
    close(saved);
    rewind(tmp);
    k = fread(buf, 1, n - 1, tmp);
    buf[k] = '\0';
    fclose(tmp);
}

/* Parse a NULL-terminated argument list (after "prog sub") with the test table. */
static int parse(st_t *s, const char **pos, int *npos, ...)
{
    const lt_opt_t opts[] = {
        LT_OPT_FLAG_("--flag", &s->flag, "a flag"),
        LT_OPT_SET_("--loud", &s->quiet, 0, "quiet off"),
        {.name = "--int", .kind = LT_OPT_INT, .dest = &s->n, .seen = &s->seen_n, .meta = "N",
         .help = "an integer, {range}", .lo = 1, .hi = 64, .limit = "LT_TEST_MAX"},
        LT_OPT_DBL("--dbl", "X", &s->d, 0.0, 1.0, "a number in {range}"),
        {.name = "--open", .kind = LT_OPT_DOUBLE, .dest = &s->dopen, .meta = "X", .help = "open",
         .lo = 0.0, .hi = 2.0, .flags = LT_OPT_LO_OPEN | LT_OPT_HI_OPEN},
        LT_OPT_DBL("--pos", "X", &s->d, 0.0, HUGE_VAL, "non-negative"),
        {.name = "--vec", .kind = LT_OPT_VEC, .dest = s->v, .seen = &s->seen_v, .meta = "X,Y,Z",
         .help = "a vector", .lo = -HUGE_VAL, .hi = HUGE_VAL, .n = 3},
        {.name = "--rot", .kind = LT_OPT_VEC, .dest = s->v, .meta = "Y,P,R", .help = "angles",
         .lo = -180, .hi = 180, .n = 3},
        {.name = "--res", .kind = LT_OPT_SIZE, .dest = s->wh, .meta = "WxH|N", .help = "size",
         .lo = 1, .hi = 8192, .limit = "LT_TEST_DIM"},
        {.name = "--colour", .kind = LT_OPT_ENUM, .dest = &s->e, .seen = &s->seen_e,
         .help = "one of {choices}", .names = colours, .alias = "--col",
         .flags = LT_OPT_DEPRECATED},
        LT_OPT_SECTION_("outputs:"),
        {.name = "--even", .kind = LT_OPT_CUSTOM, .dest = &s->custom, .meta = "N",
         .help = "an even number", .expect = "an even integer", .parse = parse_even},
        LT_OPT_STR("--str", "TEXT", &s->s, "a string\nsecond line"),
        {.name = "--req", .kind = LT_OPT_STRING, .dest = &s->req, .meta = "PATH", .help = "needed",
         .flags = LT_OPT_REQUIRED},
        {.name = "--a", .kind = LT_OPT_FLAG, .dest = &s->flag, .seen = &s->seen_a, .value = 1,
         .help = "x", .flags = LT_OPT_HIDDEN},
        {.name = "--b", .kind = LT_OPT_FLAG, .dest = &s->flag, .seen = &s->seen_b, .value = 2,
         .help = "y", .flags = LT_OPT_HIDDEN},
        LT_OPT_END_};
    lt_opt_cmd_t cmd = {"prog sub", "[FILE] [options]", "Intro prose.\n", "Epilogue prose.\n",
                        opts, pos, 2, npos};
    char *argv[64];
    int argc = 0, rc, so, se;
    FILE *to, *te;
    va_list ap;
    const char *a;
    argv[argc++] = (char *)"prog";
    argv[argc++] = (char *)"sub";
    va_start(ap, npos);
    while ((a = va_arg(ap, const char *)) != NULL && argc < 63)
        argv[argc++] = (char *)a;
    va_end(ap);
    argv[argc] = NULL;
    so = capture_begin(1, &to);
    se = capture_begin(2, &te);
    rc = lt_opt_parse(&cmd, argc, argv, 2);
    capture_end(2, se, te, g_err, sizeof g_err);
    capture_end(1, so, to, g_out, sizeof g_out);
    return rc;
}

#define P(s, ...) parse(s, NULL, NULL, "--req", "r", __VA_ARGS__, (const char *)NULL)

static void expect_err(const char *want)
{
    if (strstr(g_err, want) == NULL)
        fail_msg("stderr '%s' lacks '%s'", g_err, want);
}

static void test_values_read(void **state)
{
    st_t s;
    (void)state;
    memset(&s, 0, sizeof s);
    s.quiet = 1;
    assert_int_equal(P(&s, "--flag", "--loud", "--int", "64", "--dbl", "0.25", "--open", "1.5",
                       "--vec", "1,-2.5,3e2", "--res", "640x480", "--colour", "blue", "--even",
                       "-4", "--str", "--looks-like-an-option"),
                     LT_OPT_OK);
    assert_int_equal(s.flag, 1);
    assert_int_equal(s.quiet, 0);
    assert_int_equal(s.n, 64);
    assert_true(s.d == 0.25 && s.dopen == 1.5);
    assert_true(s.v[0] == 1.0 && s.v[1] == -2.5 && s.v[2] == 300.0);
    assert_int_equal(s.wh[0], 640);
    assert_int_equal(s.wh[1], 480);
    assert_int_equal(s.e, 2);
    assert_int_equal(s.custom, -4);
    assert_string_equal(s.s, "--looks-like-an-option");
    assert_string_equal(g_err, "");
    memset(&s, 0, sizeof s);
    assert_int_equal(P(&s, "--res", "96", "--vec", "-1,0,0"), LT_OPT_OK);
    assert_int_equal(s.wh[0], 96);
    assert_int_equal(s.wh[1], 96);
    assert_true(s.v[0] == -1.0);
}

static void test_integers(void **state)
{
    st_t s;
    (void)state;
    memset(&s, 0, sizeof s);
    s.n = 7;
    /* "1e9" was read as 1 by atoi: now not an integer; the message names the range and limit */
    assert_int_equal(P(&s, "--int", "1e9"), LT_OPT_USAGE);
    expect_err("prog sub: --int 1e9: not an integer; expected 1..64 (LT_TEST_MAX)");
    assert_int_equal(s.n, 7);
    assert_int_equal(P(&s, "--int", "65"), LT_OPT_USAGE);
    expect_err("--int 65: out of range; expected 1..64 (LT_TEST_MAX)");
    assert_int_equal(P(&s, "--int", "0"), LT_OPT_USAGE);
    assert_int_equal(P(&s, "--int", "99999999999999999999999"), LT_OPT_USAGE);
    expect_err("out of range");
    assert_int_equal(P(&s, "--int", "12abc"), LT_OPT_USAGE);
    assert_int_equal(P(&s, "--int", ""), LT_OPT_USAGE);
    assert_int_equal(P(&s, "--int", " 5"), LT_OPT_USAGE);
    assert_int_equal(P(&s, "--int", "5 "), LT_OPT_USAGE);
    assert_int_equal(P(&s, "--int", "2.0"), LT_OPT_USAGE);
    assert_int_equal(s.n, 7);
    assert_int_equal(P(&s, "--int", "1"), LT_OPT_OK);
    assert_int_equal(s.n, 1);
}

static void test_doubles(void **state)
{
    st_t s;
    (void)state;
    memset(&s, 0, sizeof s);
    assert_int_equal(P(&s, "--dbl", "nan"), LT_OPT_USAGE);
    expect_err("--dbl nan: not a finite number; expected [0, 1]");
    assert_int_equal(P(&s, "--dbl", "inf"), LT_OPT_USAGE);
    assert_int_equal(P(&s, "--dbl", "1e999"), LT_OPT_USAGE);
    assert_int_equal(P(&s, "--dbl", "-1"), LT_OPT_USAGE);
    expect_err("--dbl -1: out of range; expected [0, 1]");
    assert_int_equal(P(&s, "--dbl", "0.5x"), LT_OPT_USAGE);
    assert_int_equal(P(&s, "--dbl", "1"), LT_OPT_OK);
    assert_int_equal(P(&s, "--open", "0"), LT_OPT_USAGE);
    expect_err("expected (0, 2)");
    assert_int_equal(P(&s, "--open", "2"), LT_OPT_USAGE);
    assert_int_equal(P(&s, "--pos", "-0.001"), LT_OPT_USAGE);
    expect_err("expected >= 0");
    assert_int_equal(P(&s, "--pos", "1e300"), LT_OPT_OK);
}

static void test_vectors(void **state)
{
    st_t s;
    (void)state;
    memset(&s, 0, sizeof s);
    assert_int_equal(P(&s, "--vec", "1,2,3xyz"), LT_OPT_USAGE);
    expect_err("--vec 1,2,3xyz: expected X,Y,Z (3 finite numbers)");
    assert_int_equal(P(&s, "--vec", "1,2"), LT_OPT_USAGE);
    assert_int_equal(P(&s, "--vec", "1,2,3,4"), LT_OPT_USAGE);
    assert_int_equal(P(&s, "--vec", "nan,0,0"), LT_OPT_USAGE);
    assert_int_equal(P(&s, "--vec", "0,inf,0"), LT_OPT_USAGE);
    assert_true(s.v[0] == 0.0 && s.v[1] == 0.0);
    assert_int_equal(P(&s, "--rot", "200,0,0"), LT_OPT_USAGE);
    expect_err("--rot 200,0,0: out of range; expected Y,P,R (3 finite numbers, each in [-180, 180])");
    assert_int_equal(P(&s, "--rot", "-180,180,0"), LT_OPT_OK);
}

static void test_sizes_enums_custom(void **state)
{
    st_t s;
    static const char *const bad[] = {"0", "8193", "64x", "x64", "64x0", "-64", "+64", "64x64x2",
                                       "64X64", " 64", "1e3"};
    size_t k;
    (void)state;
    memset(&s, 0, sizeof s);
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        assert_int_equal(P(&s, "--res", bad[k]), LT_OPT_USAGE);
        expect_err("expected WxH or N, 1..8192 per side (LT_TEST_DIM)");
    }
    assert_int_equal(P(&s, "--res", "8192x1"), LT_OPT_OK);
    assert_int_equal(P(&s, "--colour", "mauve"), LT_OPT_USAGE);
    expect_err("--colour mauve: expected red, green or blue");
    assert_int_equal(P(&s, "--even", "3"), LT_OPT_USAGE);
    expect_err("--even 3: expected an even integer");
}

static void test_structure(void **state)
{
    st_t s;
    const char *pos[2] = {NULL, NULL};
    int npos = -1;
    (void)state;
    memset(&s, 0, sizeof s);
    assert_int_equal(P(&s, "--frob"), LT_OPT_USAGE);
    expect_err("prog sub: unknown option '--frob'");
    assert_int_equal(P(&s, "--int"), LT_OPT_USAGE);
    expect_err("prog sub: --int: missing value (N)");
    assert_int_equal(parse(&s, NULL, NULL, "--flag", (const char *)NULL), LT_OPT_USAGE);
    expect_err("prog sub: --req PATH is required");
    expect_err("usage: prog sub [FILE] [options]");
    /* positional arguments: up to pos_max, between options */
    assert_int_equal(parse(&s, pos, &npos, "a.json", "--req", "r", "b.json", (const char *)NULL),
                     LT_OPT_OK);
    assert_int_equal(npos, 2);
    assert_string_equal(pos[0], "a.json");
    assert_string_equal(pos[1], "b.json");
    assert_int_equal(parse(&s, pos, &npos, "a", "b", "c", "--req", "r", (const char *)NULL),
                     LT_OPT_USAGE);
    expect_err("unexpected argument 'c'");
    assert_int_equal(P(&s, "stray"), LT_OPT_USAGE);
    /* repeats: the last wins; seen is the argv index of the last occurrence */
    assert_int_equal(P(&s, "--int", "3", "--colour", "red", "--int", "5"), LT_OPT_OK);
    assert_int_equal(s.n, 5);
    assert_int_equal(s.seen_n, 8);
    assert_int_equal(s.seen_e, 6);
    assert_int_equal(s.seen_v, 0);
    assert_int_equal(P(&s, "--b", "--a"), LT_OPT_OK);
    assert_int_equal(s.flag, 1);
    assert_true(s.seen_a > s.seen_b);
    /* a deprecated spelling works and says so on stderr */
    s.e = 0;
    assert_int_equal(P(&s, "--col", "green"), LT_OPT_OK);
    assert_int_equal(s.e, 1);
    expect_err("prog sub: note: --col is deprecated, use --colour");
}

static void test_help(void **state)
{
    st_t s;
    (void)state;
    memset(&s, 0, sizeof s);
    assert_int_equal(parse(&s, NULL, NULL, "--int", "3", "--help", "--frob", (const char *)NULL),
                     LT_OPT_HELP);
    assert_string_equal(g_err, "");
    assert_non_null(strstr(g_out, "usage: prog sub [FILE] [options]\nIntro prose.\n"));
    assert_non_null(strstr(g_out, "  --int N               an integer, 1..64\n"));
    assert_non_null(strstr(g_out, "  --dbl X               a number in [0, 1]\n"));
    assert_non_null(strstr(g_out, "  --colour red|green|blue  one of red, green or blue\n"));
    assert_non_null(strstr(g_out, "(--col: the deprecated spelling"));
    assert_non_null(strstr(g_out, "\noutputs:\n"));
    assert_non_null(strstr(g_out, "a string\n                        second line\n"));
    assert_non_null(strstr(g_out, "Epilogue prose.\n"));
    assert_null(strstr(g_out, "--a"));
    assert_int_equal(parse(&s, NULL, NULL, "-h", (const char *)NULL), LT_OPT_HELP);
}

static void test_range_text(void **state)
{
    lt_opt_t o;
    char b[64];
    (void)state;
    memset(&o, 0, sizeof o);
    o.kind = LT_OPT_DOUBLE;
    o.lo = 0.0;
    o.hi = 1.0;
    o.flags = LT_OPT_LO_OPEN;
    lt_opt_range_text(&o, b, sizeof b);
    assert_string_equal(b, "(0, 1]");
    o.lo = -HUGE_VAL;
    o.flags = LT_OPT_HI_OPEN;
    lt_opt_range_text(&o, b, sizeof b);
    assert_string_equal(b, "< 1");
    o.hi = HUGE_VAL;
    lt_opt_range_text(&o, b, sizeof b);
    assert_string_equal(b, "");
    o.kind = LT_OPT_INT;
    o.lo = 1;
    o.hi = 100000000;
    lt_opt_range_text(&o, b, sizeof b);
    assert_string_equal(b, "1..100000000");
    {
        static const char *const one[] = {"q16", NULL}, *const two[] = {"q16", "f32", NULL};
        lt_opt_choices_text(one, b, sizeof b);
        assert_string_equal(b, "q16");
        lt_opt_choices_text(two, b, sizeof b);
        assert_string_equal(b, "q16 or f32");
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_values_read),     cmocka_unit_test(test_integers),
        cmocka_unit_test(test_doubles),         cmocka_unit_test(test_vectors),
        cmocka_unit_test(test_sizes_enums_custom), cmocka_unit_test(test_structure),
        cmocka_unit_test(test_help),            cmocka_unit_test(test_range_text),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
