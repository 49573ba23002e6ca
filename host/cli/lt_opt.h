/* lt_opt.h - table-driven option parsing for the lanetrace subcommands. A subcommand declares a
 * table of options (name, kind, destination, "seen" marker, one help line) and lt_opt_parse walks
 * argv with it: every subcommand gets the same messages (unknown option, missing value, value out
 * of range naming the limit, trailing garbage, non-finite numbers) and a --help printed from the
 * same table, so the help and the parser cannot drift apart. Host only.
 *
 *     int layers = 1, seen_layers = 0;
 *     const char *out = NULL;
 *     const lt_opt_t opts[] = {
 *         LT_OPT_STR("--out", "PREFIX", &out, "output prefix"),
 *         LT_OPT_INT("--layers", "K", &layers, 1, 16, "depth peels, {range} (default 1)"),
 *         LT_OPT_END_
 *     };
 *     lt_opt_cmd_t cmd = {"lanetrace render", "[SCENE.json] --out PREFIX [options]", NULL, NULL,
 *                         opts, NULL, 0, NULL};
 *     switch (lt_opt_parse(&cmd, argc, argv, 2)) { case LT_OPT_HELP: return 0; ... }
 *
 * Values: the next argument, whatever it looks like (`--move -1,0,0` works). Numbers are read
 * whole: "1e9" is not an integer, "1,2,3xyz" not a vector, "nan" and "inf" are refused, and a
 * value outside the option's range names the range (and its limit's name when the table gives
 * one). A deprecated spelling (`alias` with LT_OPT_DEPRECATED) still works and prints a one-line
 * note on stderr.
 */
#ifndef LT_OPT_H
#define LT_OPT_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum lt_opt_kind {
    LT_OPT_END = 0,  /* terminates a table (LT_OPT_END_) */
    LT_OPT_FLAG,     /* no value: *(int *)dest = value */
    LT_OPT_STRING,   /* *(const char **)dest = the argument */
    LT_OPT_INT,      /* *(int *)dest: a whole decimal integer in lo..hi */
    LT_OPT_DOUBLE,   /* *(double *)dest: a whole finite number in lo..hi (open ends: flags) */
    LT_OPT_VEC,      /* ((double *)dest)[0..n-1]: n finite numbers "X,Y,Z", each in lo..hi */
    LT_OPT_SIZE,     /* ((uint32_t *)dest)[0..1]: "WxH" or "N" (square), each side 1..hi */
    LT_OPT_ENUM,     /* *(int *)dest = the index of the argument in names[] */
    LT_OPT_CUSTOM,   /* parse(argument, dest, ctx) == 0, else "expected <expect>" */
    LT_OPT_SECTION   /* no option: a heading line in the help ("cameras:") */
} lt_opt_kind_t;

/* flags */
#define LT_OPT_LO_OPEN 1u    /* DOUBLE, VEC: lo itself is out of range */
#define LT_OPT_HI_OPEN 2u    /* DOUBLE, VEC: hi itself is out of range */
#define LT_OPT_DEPRECATED 4u /* alias is a deprecated spelling: a note on stderr when used */
#define LT_OPT_REQUIRED 8u   /* a usage error (with the help) when not given */
#define LT_OPT_HIDDEN 16u    /* not listed by the help */
#define LT_OPT_NONEMPTY 32u  /* STRING: an empty value is a usage error (an input path, a spec) */

/* Custom value parser: 0 when the text is valid (dest written), -1 when not (dest untouched is
 * not required). */
typedef int (*lt_opt_parse_fn)(const char *text, void *dest, const void *ctx);

typedef struct lt_opt {
    const char *name;         /* "--res" */
    lt_opt_kind_t kind;
    void *dest;               /* see lt_opt_kind_t; NULL for SECTION */
    int *seen;                /* NULL, or the argv index of the last occurrence (0: absent) */
    const char *meta;         /* the value in the help: "WxH|N", "X,Y,Z" (ENUM: NULL = "a|b|c") */
    const char *help;         /* one help line; '\n' continues it; "{range}" and "{choices}" are
                                 replaced by the range / the enum names as messages print them */
    double lo, hi;            /* INT, DOUBLE, VEC range (+-HUGE_VAL: open); SIZE: hi per side */
    unsigned flags;           /* LT_OPT_* flags */
    int value;                /* FLAG: the value stored */
    int n;                    /* VEC: components */
    const char *const *names; /* ENUM: NULL-terminated */
    const char *alias;        /* another spelling ("-h", "--colour", a deprecated "--enc") */
    const char *limit;        /* the range's limit by name, for messages ("LT_BVH_MAX_LEAF") */
    const char *expect;       /* CUSTOM, VEC: what a valid value is ("X,Y,Z,SIZE (SIZE >= 0)") */
    lt_opt_parse_fn parse;    /* CUSTOM */
    const void *ctx;          /* CUSTOM: passed to parse */
    const char *ext;          /* STRING naming an output file: its kind's extension ("exr");
                                 "" for a path prefix; a name ending in another output kind's
                                 extension (.png for an EXR, .exr for a prefix) is refused */
} lt_opt_t;

/* Table entries (C99 designated initializers; write a full initializer for the other fields). */
#define LT_OPT_FLAG_(nm, d, h)                                                                     \
    {.name = (nm), .kind = LT_OPT_FLAG, .dest = (d), .help = (h), .value = 1}
#define LT_OPT_SET_(nm, d, v, h)                                                                   \
    {.name = (nm), .kind = LT_OPT_FLAG, .dest = (d), .help = (h), .value = (v)}
#define LT_OPT_STR(nm, mt, d, h)                                                                   \
    {.name = (nm), .kind = LT_OPT_STRING, .dest = (d), .meta = (mt), .help = (h)}
#define LT_OPT_IN(nm, mt, d, h)                                                                    \
    {.name = (nm), .kind = LT_OPT_STRING, .dest = (d), .meta = (mt), .help = (h),                  \
     .flags = LT_OPT_NONEMPTY}
#define LT_OPT_OUT(nm, mt, d, x, h)                                                                \
    {.name = (nm), .kind = LT_OPT_STRING, .dest = (d), .meta = (mt), .help = (h), .ext = (x)}
#define LT_OPT_INT(nm, mt, d, l, u, h)                                                             \
    {.name = (nm), .kind = LT_OPT_INT, .dest = (d), .meta = (mt), .help = (h), .lo = (l), .hi = (u)}
#define LT_OPT_DBL(nm, mt, d, l, u, h)                                                             \
    {.name = (nm), .kind = LT_OPT_DOUBLE, .dest = (d), .meta = (mt), .help = (h), .lo = (l),       \
     .hi = (u)}
#define LT_OPT_VEC3(nm, mt, d, h)                                                                  \
    {.name = (nm), .kind = LT_OPT_VEC, .dest = (d), .meta = (mt), .help = (h), .lo = -HUGE_VAL,    \
     .hi = HUGE_VAL, .n = 3}
#define LT_OPT_SIZE_(nm, d, mx, h)                                                                 \
    {.name = (nm), .kind = LT_OPT_SIZE, .dest = (d), .meta = "WxH|N", .help = (h), .lo = 1,        \
     .hi = (mx)}
#define LT_OPT_ENUM_(nm, d, nms, h)                                                                \
    {.name = (nm), .kind = LT_OPT_ENUM, .dest = (d), .help = (h), .names = (nms)}
#define LT_OPT_SECTION_(h) {.kind = LT_OPT_SECTION, .help = (h)}
/* --threads N of the commands that trace on every core (lt_par.h), into an int (the command
 * passes it to lt_par_set_threads; 0 = every online core, the commands' default) */
#define LT_OPT_THREADS_(d)                                                                         \
    LT_OPT_INT("--threads", "N", (d), 0, 256,                                                      \
               "threads for the tile loops, {range} (default 0: every online core);\n"              \
               "results are bit-identical for any count; the simulator's charged\n"                 \
               "kernels run on one")
/* --no-auto and --auto (the default) of run, render and reproject: what lanetrace info recommends
 * (KNOBS, a phrase) is taken for every knob that neither a flag nor the scene file sets */
#define LT_OPT_AUTO_(d, knobs)                                                                     \
    LT_OPT_SET_("--no-auto", (d), 0,                                                               \
                "do not take lanetrace info's recommendation for the machine; by\n"                \
                "default it sets " knobs "\n"                                                      \
                "wherever neither a flag nor the scene file does, and each pick\n"                 \
                "and its reason is printed and written to the report"),                            \
        LT_OPT_SET_("--auto", (d), 1, "the default (kept for scripts): the recommendation")
#define LT_OPT_END_ {.kind = LT_OPT_END}

/* A subcommand: its options and where positional arguments go. */
typedef struct lt_opt_cmd {
    const char *who;      /* "lanetrace run": starts every message and the usage line */
    const char *synopsis; /* after who on the usage line: "[SCENE.json] [options]" */
    const char *intro;    /* prose between the usage line and the options, or NULL */
    const char *epilog;   /* prose after the options, or NULL */
    const lt_opt_t *opts; /* ends with LT_OPT_END_ */
    const char **pos;     /* positional arguments, in order (NULL: none accepted) */
    int pos_max;          /* how many fit in pos */
    int *npos;            /* NULL, or the count found */
} lt_opt_cmd_t;

#define LT_OPT_OK 0
#define LT_OPT_HELP 1  /* --help or -h: the help is on stdout; the command exits 0 */
#define LT_OPT_USAGE 2 /* a usage error, already printed on stderr; the command exits 2 */

/* The exit code of a program whose parse ended with rc (LT_OPT_HELP: 0, LT_OPT_USAGE: 2), for
 * `if ((rc = parse(...)) != LT_OPT_OK) return lt_opt_exit_code(rc);`. */
int lt_opt_exit_code(int rc);

/* Parse argv[first..argc-1] against cmd's table. Every option may repeat (the last wins; a FLAG
 * sets its value each time). Returns LT_OPT_OK, LT_OPT_HELP or LT_OPT_USAGE. */
int lt_opt_parse(const lt_opt_cmd_t *cmd, int argc, char **argv, int first);

/* The help: "usage: WHO SYNOPSIS", the intro, one line per option (name, value, help; sections as
 * headings), the epilog. */
void lt_opt_help(const lt_opt_cmd_t *cmd, FILE *f);

/* An option's range as the messages print it: "1..16", "[0, 1]", "(0, 1]", ">= 0", "" if none. */
void lt_opt_range_text(const lt_opt_t *o, char *buf, size_t n);

/* Enum names as messages print them: "q16, f32 or both". */
void lt_opt_choices_text(const char *const *names, char *buf, size_t n);

/* The number readers the kinds use, for custom parsers: 0 when text is a whole decimal integer /
 * a whole finite number / n comma-separated finite numbers, else -1; lt_opt_read_long returns -2
 * for an integer beyond long. */
/* The check LT_OPT_OUT applies to an output option's value, for outputs named elsewhere (a scene
 * file's "outputs"): 1 with the reason in why when path is empty, names a directory ("out/",
 * ".") or ends in the extension of another kind of file than ext ("json"; "" for a prefix that
 * takes none); else 0. */
int lt_opt_output_bad(const char *ext, const char *path, char *why, size_t n);

int lt_opt_read_long(const char *text, long *v);
int lt_opt_read_double(const char *text, double *v);
int lt_opt_read_vec(const char *text, double *v, int n);

#ifdef __cplusplus
}
#endif
#endif /* LT_OPT_H */
