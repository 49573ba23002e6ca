/* lt_opt.c - see lt_opt.h. */
#include "cli/lt_opt.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#define HELP_COL 24   /* the help text starts in this column */
#define MAX_OPTS 128  /* options per table (the required-option check keeps a flag each) */

int lt_opt_read_long(const char *text, long *v)
{
    char *end;
    long x;
    if (text == NULL || *text == '\0' || isspace((unsigned char)*text))
        return -1;
    errno = 0;
    x = strtol(text, &end, 10);
    if (end == text || *end != '\0')
        return -1;
    if (errno == ERANGE)
        return -2;
    *v = x;
    return 0;
}

int lt_opt_read_double(const char *text, double *v)
{
    char *end;
    double x;
    if (text == NULL || *text == '\0' || isspace((unsigned char)*text))
        return -1;
    x = strtod(text, &end);
    if (end == text || *end != '\0' || !isfinite(x))
        return -1;
    *v = x;
    return 0;
}

int lt_opt_read_vec(const char *text, double *v, int n)
{
    const char *p = text;
    int i;
    if (text == NULL)
        return -1;
    for (i = 0; i < n; i++) {
        char *end;
        v[i] = strtod(p, &end);
        if (end == p || !isfinite(v[i]))
            return -1;
        p = end;
        if (i + 1 < n) {
            if (*p != ',')
                return -1;
            p++;
        }
    }
    return *p == '\0' ? 0 : -1;
}

/* "WxH" or "N": digits only, each side 1..max */
static int read_size(const char *text, double max, uint32_t wh[2])
{
    unsigned long side[2] = {0, 0};
    const char *p = text;
    int k;
    for (k = 0; k < 2; k++) {
        const char *start = p;
        while (*p >= '0' && *p <= '9') {
            if (side[k] > 100000000ul)
                return -1;
            side[k] = 10 * side[k] + (unsigned long)(*p - '0');
            p++;
        }
        if (p == start || side[k] < 1 || (double)side[k] > max)
            return -1;
        if (k == 0 && *p == '\0') {
            side[1] = side[0];
            break;
        }
        if (k == 0 && *p++ != 'x')
            return -1;
    }
    if (*p != '\0')
        return -1;
    wh[0] = (uint32_t)side[0];
    wh[1] = (uint32_t)side[1];
    return 0;
}

void lt_opt_range_text(const lt_opt_t *o, char *buf, size_t n)
{
    int lo = isfinite(o->lo), hi = isfinite(o->hi);
    int lo_open = (o->flags & LT_OPT_LO_OPEN) != 0, hi_open = (o->flags & LT_OPT_HI_OPEN) != 0;
    if (o->kind == LT_OPT_INT || o->kind == LT_OPT_SIZE) {
        lo_open = hi_open = 0;
        if (lo && hi) {
            snprintf(buf, n, "%.0f..%.0f", o->lo, o->hi);
            return;
        }
    }
    if (lo && hi)
        snprintf(buf, n, "%c%g, %g%c", lo_open ? '(' : '[', o->lo, o->hi, hi_open ? ')' : ']');
    else if (lo)
        snprintf(buf, n, "%s %g", lo_open ? ">" : ">=", o->lo);
    else if (hi)
        snprintf(buf, n, "%s %g", hi_open ? "<" : "<=", o->hi);
    else if (n > 0)
        buf[0] = '\0';
}

void lt_opt_choices_text(const char *const *names, char *buf, size_t n)
{
    size_t len = 0;
    int i, count = 0;
    if (n == 0)
        return;
    buf[0] = '\0';
    while (names != NULL && names[count] != NULL)
        count++;
    for (i = 0; i < count && len < n; i++) {
        const char *sep = i == 0 ? "" : (i + 1 == count ? " or " : ", ");
        int w = snprintf(buf + len, n - len, "%s%s", sep, names[i]);
        if (w < 0)
            break;
        len += (size_t)w;
    }
}

static int in_range(const lt_opt_t *o, double x)
{
    int real = o->kind == LT_OPT_DOUBLE || o->kind == LT_OPT_VEC;
    int lo_open = real && (o->flags & LT_OPT_LO_OPEN) != 0;
    int hi_open = real && (o->flags & LT_OPT_HI_OPEN) != 0;
    if (lo_open ? !(x > o->lo) : !(x >= o->lo))
        return 0;
    if (hi_open ? !(x < o->hi) : !(x <= o->hi))
        return 0;
    return 1;
}

/* "expected <range>[ (<limit>)]" */
static void expected_range(const lt_opt_t *o, char *buf, size_t n)
{
    char r[96];
    lt_opt_range_text(o, r, sizeof r);
    if (o->limit != NULL)
        snprintf(buf, n, "expected %s (%s)", r, o->limit);
    else
        snprintf(buf, n, "expected %s", r);
}

/* The file kinds an output option can name, by extension (any case). */
static const char *const out_exts[] = {"exr", "png", "json", "csv", "jpg", "jpeg", "tif", "tiff",
                                       "ppm", "pgm", "bmp", "txt", "obj", "ply", NULL};

/* An output path whose extension names another kind than ext ("exr"; "" for a prefix, which
 * takes no extension of those kinds): the reason in why, 1; else 0. */
static int output_ext_bad(const char *ext, const char *v, char *why, size_t n)
{
    const char *base = strrchr(v, '/'), *dot;
    char e[8];
    size_t k;
    int i;
    base = base != NULL ? base + 1 : v;
    if (v[0] == '\0' || base[0] == '\0' || strcmp(base, ".") == 0 || strcmp(base, "..") == 0) {
        /* "", "out/", ".": no name to write (a prefix would make hidden ".exr", ".png", ...) */
        snprintf(why, n, "%s, not a %s", v[0] == '\0' ? "an empty name" : "a directory",
                 ext[0] == '\0' ? "path prefix (give DIR/NAME: NAME.exr, NAME.png, ...)"
                                : "file name");
        return 1;
    }
    dot = strrchr(base, '.');
    if (dot == NULL || dot == base || strlen(dot + 1) >= sizeof e)
        return 0;
    for (k = 0; dot[1 + k] != '\0'; k++)
        e[k] = (char)tolower((unsigned char)dot[1 + k]);
    e[k] = '\0';
    for (i = 0; out_exts[i] != NULL && strcmp(out_exts[i], e) != 0; i++)
        ;
    if (out_exts[i] == NULL || strcmp(e, ext) == 0)
        return 0;
    if (ext[0] == '\0')
        snprintf(why, n, "a path prefix, not a file: the outputs get their own extensions "
                         "(PREFIX.exr, PREFIX.png, ...); give it without '.%s'", e);
    else
        snprintf(why, n, "this output is a .%s file; its name ends in '.%s' (name it "
                         "<name>.%s)", ext, e, ext);
    return 1;
}

int lt_opt_output_bad(const char *ext, const char *path, char *why, size_t n)
{
    return output_ext_bad(ext, path, why, n);
}

/* Read one option's value into its destination; prints the message and returns -1 when bad. */
static int take_value(const lt_opt_cmd_t *cmd, const lt_opt_t *o, const char *spelt, const char *v)
{
    char why[384], exp[256];
    why[0] = '\0';
    switch (o->kind) {
    case LT_OPT_STRING:
        if (o->ext != NULL && output_ext_bad(o->ext, v, why, sizeof why))
            break;
        if ((o->flags & LT_OPT_NONEMPTY) && v[0] == '\0') {
            /* "--mesh ''" used to trace the default teapot, "--l1 ''" to take the machine's
             * cache: an empty value is never a path or a spec */
            snprintf(why, sizeof why, "an empty value; expected %s", o->meta != NULL ? o->meta
                                                                                    : "a value");
            break;
        }
        *(const char **)o->dest = v;
        return 0;
    case LT_OPT_INT: {
        long x = 0;
        int r = lt_opt_read_long(v, &x);
        expected_range(o, exp, sizeof exp);
        if (r == -1)
            snprintf(why, sizeof why, "not an integer; %s", exp);
        else if (r == -2 || !in_range(o, (double)x))
            snprintf(why, sizeof why, "out of range; %s", exp);
        else
            *(int *)o->dest = (int)x;
        break;
    }
    case LT_OPT_DOUBLE: {
        double x = 0.0;
        expected_range(o, exp, sizeof exp);
        if (lt_opt_read_double(v, &x) != 0 && !isfinite(o->lo) && !isfinite(o->hi))
            snprintf(why, sizeof why, "not a finite number");
        else if (lt_opt_read_double(v, &x) != 0)
            snprintf(why, sizeof why, "not a finite number; %s", exp);
        else if (!in_range(o, x))
            snprintf(why, sizeof why, "out of range; %s", exp);
        else
            *(double *)o->dest = x;
        break;
    }
    case LT_OPT_VEC: {
        double x[8];
        int i, n = o->n > 0 && o->n <= 8 ? o->n : 3;
        char r[96];
        lt_opt_range_text(o, r, sizeof r);
        if (o->expect != NULL)
            snprintf(exp, sizeof exp, "%s", o->expect);
        else if (r[0] != '\0')
            snprintf(exp, sizeof exp, "%s (%d finite numbers, each in %s)",
                     o->meta != NULL ? o->meta : "X,Y,Z", n, r);
        else
            snprintf(exp, sizeof exp, "%s (%d finite numbers)", o->meta != NULL ? o->meta : "X,Y,Z",
                     n);
        if (lt_opt_read_vec(v, x, n) != 0) {
            snprintf(why, sizeof why, "expected %s", exp);
            break;
        }
        for (i = 0; i < n; i++)
            if (!in_range(o, x[i]))
                break;
        if (i < n) {
            snprintf(why, sizeof why, "out of range; expected %s", exp);
            break;
        }
        memcpy(o->dest, x, (size_t)n * sizeof x[0]);
        break;
    }
    case LT_OPT_SIZE:
        if (read_size(v, o->hi, (uint32_t *)o->dest) != 0) {
            char r[96];
            lt_opt_range_text(o, r, sizeof r);
            snprintf(why, sizeof why, "expected WxH or N, %s per side%s%s%s", r,
                     o->limit != NULL ? " (" : "", o->limit != NULL ? o->limit : "",
                     o->limit != NULL ? ")" : "");
        }
        break;
    case LT_OPT_ENUM: {
        int i;
        for (i = 0; o->names[i] != NULL && strcmp(o->names[i], v) != 0; i++)
            ;
        if (o->names[i] != NULL) {
            *(int *)o->dest = i;
        } else {
            lt_opt_choices_text(o->names, exp, sizeof exp);
            snprintf(why, sizeof why, "expected %s", exp);
        }
        break;
    }
    case LT_OPT_CUSTOM:
        if (o->parse(v, o->dest, o->ctx) != 0)
            snprintf(why, sizeof why, "expected %s", o->expect != NULL ? o->expect : o->meta);
        break;
    default:
        snprintf(why, sizeof why, "option table error (kind %d)", (int)o->kind);
        break;
    }
    if (why[0] == '\0')
        return 0;
    fprintf(stderr, "%s: %s %s: %s\n", cmd->who, spelt, v, why);
    return -1;
}

static const lt_opt_t *find(const lt_opt_t *opts, const char *arg, int *deprecated)
{
    const lt_opt_t *o;
    *deprecated = 0;
    for (o = opts; o->kind != LT_OPT_END; o++) {
        if (o->kind == LT_OPT_SECTION)
            continue;
        if (strcmp(o->name, arg) == 0)
            return o;
        if (o->alias != NULL && strcmp(o->alias, arg) == 0) {
            *deprecated = (o->flags & LT_OPT_DEPRECATED) != 0;
            return o;
        }
    }
    return NULL;
}

static const char *meta_of(const lt_opt_t *o, char *buf, size_t n)
{
    size_t len = 0;
    int i;
    if (o->meta != NULL || o->kind != LT_OPT_ENUM)
        return o->meta;
    buf[0] = '\0';
    for (i = 0; o->names[i] != NULL && len < n; i++) {
        int w = snprintf(buf + len, n - len, "%s%s", i ? "|" : "", o->names[i]);
        if (w < 0)
            break;
        len += (size_t)w;
    }
    return buf;
}

int lt_opt_parse(const lt_opt_cmd_t *cmd, int argc, char **argv, int first)
{
    unsigned char given[MAX_OPTS];
    const lt_opt_t *o;
    int a, npos = 0, dep, i;
    memset(given, 0, sizeof given);
    if (cmd->npos != NULL)
        *cmd->npos = 0;
    for (a = first; a < argc; a++) {
        const char *arg = argv[a];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            lt_opt_help(cmd, stdout);
            return LT_OPT_HELP;
        }
        if (arg[0] == '\0') {
            /* an empty file name: "lanetrace run ''" said ": cannot open the scene file" */
            fprintf(stderr, "%s: an empty argument '' (usage: %s %s)\n", cmd->who, cmd->who,
                    cmd->synopsis);
            return LT_OPT_USAGE;
        }
        if (arg[0] != '-') {
            if (cmd->pos == NULL || npos >= cmd->pos_max) {
                fprintf(stderr, "%s: unexpected argument '%s' (usage: %s %s)\n", cmd->who, arg,
                        cmd->who, cmd->synopsis);
                return LT_OPT_USAGE;
            }
            cmd->pos[npos++] = arg;
            if (cmd->npos != NULL)
                *cmd->npos = npos;
            continue;
        }
        o = find(cmd->opts, arg, &dep);
        if (o == NULL) {
            fprintf(stderr, "%s: unknown option '%s' (see '%s --help')\n", cmd->who, arg, cmd->who);
            return LT_OPT_USAGE;
        }
        if (dep)
            fprintf(stderr, "%s: note: %s is deprecated, use %s (the old spelling is accepted "
                            "for one more release)\n", cmd->who, arg, o->name);
        if (o->kind == LT_OPT_FLAG) {
            *(int *)o->dest = o->value;
        } else {
            char mb[256];
            if (a + 1 >= argc) {
                const char *m = meta_of(o, mb, sizeof mb);
                fprintf(stderr, "%s: %s: missing value%s%s%s\n", cmd->who, arg,
                        m != NULL ? " (" : "", m != NULL ? m : "", m != NULL ? ")" : "");
                return LT_OPT_USAGE;
            }
            if (take_value(cmd, o, arg, argv[a + 1]) != 0)
                return LT_OPT_USAGE;
            a++;
        }
        i = (int)(o - cmd->opts);
        if (i < MAX_OPTS)
            given[i] = 1;
        if (o->seen != NULL)
            *o->seen = o->kind == LT_OPT_FLAG ? a : a - 1;
    }
    for (o = cmd->opts, i = 0; o->kind != LT_OPT_END; o++, i++) {
        if ((o->flags & LT_OPT_REQUIRED) && i < MAX_OPTS && !given[i]) {
            char mb[256];
            const char *m = meta_of(o, mb, sizeof mb);
            fprintf(stderr, "%s: %s%s%s is required\nusage: %s %s\n", cmd->who, o->name,
                    m != NULL ? " " : "", m != NULL ? m : "", cmd->who, cmd->synopsis);
            return LT_OPT_USAGE;
        }
    }
    return LT_OPT_OK;
}

/* Write one help text with {range} and {choices} replaced; lines after the first start at
 * HELP_COL. */
static void put_help(const lt_opt_t *o, const char *h, FILE *f)
{
    while (*h != '\0') {
        if (strncmp(h, "{range}", 7) == 0) {
            char r[96];
            lt_opt_range_text(o, r, sizeof r);
            fputs(r, f);
            h += 7;
        } else if (strncmp(h, "{choices}", 9) == 0) {
            char c[512];
            lt_opt_choices_text(o->names, c, sizeof c);
            fputs(c, f);
            h += 9;
        } else if (*h == '\n') {
            fprintf(f, "\n%*s", HELP_COL, "");
            h++;
        } else {
            fputc(*h++, f);
        }
    }
    fputc('\n', f);
}

void lt_opt_help(const lt_opt_cmd_t *cmd, FILE *f)
{
    const lt_opt_t *o;
    fprintf(f, "usage: %s %s\n", cmd->who, cmd->synopsis);
    if (cmd->intro != NULL)
        fputs(cmd->intro, f);
    for (o = cmd->opts; o->kind != LT_OPT_END; o++) {
        char left[320], mb[256];
        const char *m;
        int w;
        if (o->flags & LT_OPT_HIDDEN)
            continue;
        if (o->kind == LT_OPT_SECTION) {
            fprintf(f, "%s\n", o->help);
            continue;
        }
        m = meta_of(o, mb, sizeof mb);
        w = snprintf(left, sizeof left, "  %s%s%s", o->name, m != NULL ? " " : "",
                     m != NULL ? m : "");
        if (w < 0)
            continue;
        if (w <= HELP_COL - 2)
            fprintf(f, "%-*s", HELP_COL, left);
        else
            fprintf(f, "%s  ", left);
        put_help(o, o->help != NULL ? o->help : "", f);
        if (o->alias != NULL && (o->flags & LT_OPT_DEPRECATED))
            fprintf(f, "%*s(%s: the deprecated spelling, accepted for one more release)\n",
                    HELP_COL, "", o->alias);
    }
    if (cmd->epilog != NULL)
        fputs(cmd->epilog, f);
}

int lt_opt_exit_code(int rc)
{
    return rc == LT_OPT_HELP ? 0 : rc == LT_OPT_USAGE ? 2 : rc;
}
