/* fuzz_opt.c - fuzz target of the table-driven option parser (host/cli/lt_opt.c) that reads every
 * lanetrace subcommand's argv: the input, split at NUL and newline bytes, is the argument list
 * given to a table with one option of every kind (flag, string, int, double with open and closed
 * ends, vector, size, enum, custom, required, deprecated alias, section). Whatever the arguments,
 * the parser must return OK, HELP or USAGE; on OK every destination holds a value inside its
 * option's range (finite numbers, sizes 1..max, a valid enum index). The message helpers are run
 * with every buffer size up to their output. make fuzz-opt; replayed over tests/fuzz/corpus/opt in
 * make test. Host only.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/lt_opt.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define MAX_ARGS 32

static int parse_pair(const char *text, void *dest, const void *ctx)
{
    long a, b;
    const char *colon = strchr(text, ':');
    char left[32];
    (void)ctx;
    if (colon == NULL || (size_t)(colon - text) >= sizeof left)
        return -1;
    memcpy(left, text, (size_t)(colon - text));
    left[colon - text] = '\0';
    if (lt_opt_read_long(left, &a) != 0 || lt_opt_read_long(colon + 1, &b) != 0)
        return -1;
    ((long *)dest)[0] = a;
    ((long *)dest)[1] = b;
    return 0;
}

typedef struct vals {
    int flag, set, i, e, npos;
    const char *s, *req, *pos[2];
    double d, dopen, v[3], v4[4];
    uint32_t wh[2];
    long pair[2];
} vals_t;

/* The parser's call, in one place. */
static int parse(const lt_opt_cmd_t *cmd, int argc, char **argv)
{
    return lt_opt_parse(cmd, argc, argv, 0);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *const names[] = {"q16", "f32", "both", NULL};
    vals_t v;
    int seen_i = 0, seen_flag = 0, rc, argc = 0;
    const lt_opt_t opts[] = {
        LT_OPT_SECTION_("general:"),
        LT_OPT_FLAG_("--flag", &v.flag, "a flag"),
        LT_OPT_SET_("--no-set", &v.set, 0, "clears set"),
        LT_OPT_STR("--str", "TEXT", &v.s, "a string"),
        {.name = "--int", .kind = LT_OPT_INT, .dest = &v.i, .seen = &seen_i, .meta = "N",
         .help = "an integer, {range}", .lo = -5, .hi = 100000, .limit = "LT_FUZZ_MAX"},
        LT_OPT_DBL("--dbl", "X", &v.d, 0.0, 1.0, "a number in {range}"),
        {.name = "--open", .kind = LT_OPT_DOUBLE, .dest = &v.dopen, .meta = "X",
         .help = "(0, inf): {range}", .lo = 0.0, .hi = HUGE_VAL, .flags = LT_OPT_LO_OPEN},
        LT_OPT_VEC3("--vec", "X,Y,Z", v.v, "three numbers"),
        {.name = "--vec4", .kind = LT_OPT_VEC, .dest = v.v4, .meta = "X,Y,Z,S", .lo = -1e6,
         .hi = 1e6, .n = 4, .help = "four numbers in {range}", .alias = "--old-vec4",
         .flags = LT_OPT_DEPRECATED},
        LT_OPT_SIZE_("--res", v.wh, 16384, "size, {range} per side"),
        {.name = "--num", .kind = LT_OPT_ENUM, .dest = &v.e, .names = names,
         .help = "path: {choices}", .alias = "-n"},
        {.name = "--pair", .kind = LT_OPT_CUSTOM, .dest = v.pair, .meta = "A:B",
         .expect = "A:B (two integers)", .parse = parse_pair, .help = "custom"},
        {.name = "--req", .kind = LT_OPT_STRING, .dest = &v.req, .meta = "PATH",
         .flags = LT_OPT_REQUIRED, .help = "required"},
        {.name = "--hidden", .kind = LT_OPT_FLAG, .dest = &v.flag, .seen = &seen_flag,
         .value = 7, .flags = LT_OPT_HIDDEN, .help = "hidden"},
        LT_OPT_END_};
    lt_opt_cmd_t cmd = {"lanetrace fuzz", "[A [B]] --req PATH [options]", "intro\n", "epilog\n",
                        opts, v.pos, 2, &v.npos};
    char *copy = malloc(size + 1), *argv[MAX_ARGS + 1], buf[96];
    size_t i, start = 0, n;

    if (copy == NULL)
        return 0;
    memcpy(copy, data, size);
    copy[size] = '\0';
    for (i = 0; i <= size && argc < MAX_ARGS; i++)
        if (i == size || copy[i] == '\0' || copy[i] == '\n') {
            copy[i] = '\0';
            argv[argc++] = copy + start;
            start = i + 1;
        }
    argv[argc] = NULL;
    memset(&v, 0, sizeof v);
    v.i = 1;
    v.d = 0.5;
    v.dopen = 1.0;
    v.wh[0] = v.wh[1] = 1;
    rc = parse(&cmd, argc, argv);
    if (rc != LT_OPT_OK && rc != LT_OPT_HELP && rc != LT_OPT_USAGE)
        abort();
    if (rc == LT_OPT_OK) {
        if (v.req == NULL || v.i < -5 || v.i > 100000 || !(v.d >= 0.0 && v.d <= 1.0) ||
            !(v.dopen > 0.0) || !isfinite(v.dopen) || v.wh[0] < 1 || v.wh[1] < 1 ||
            v.wh[0] > 16384 || v.wh[1] > 16384 || v.e < 0 || v.e > 2 || v.npos < 0 ||
            v.npos > 2 || (seen_i != 0 && (seen_i < 1 || seen_i >= argc)))
            abort();
        for (i = 0; i < 3; i++)
            if (!isfinite(v.v[i]) || !(fabs(v.v4[i]) <= 1e6))
                abort();
    }
    /* the message helpers with every buffer size, on the table's options */
    n = size % sizeof buf;
    for (i = 0; opts[i].kind != LT_OPT_END; i++) {
        lt_opt_range_text(&opts[i], buf, n);
        if (n > 0 && memchr(buf, '\0', n) == NULL)
            abort();
    }
    lt_opt_choices_text(names, buf, n);
    if (n > 0 && memchr(buf, '\0', n) == NULL)
        abort();
    free(copy);
    return 0;
}
