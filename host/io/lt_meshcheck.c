/* lt_meshcheck.c - structural checks of PLY, OFF and STL bytes before assimp 5.2.5 sees them.
 * assimp trusts the counts and sizes these formats declare: a PLY header without end_header spins
 * forever, a truncated binary PLY body is read past its end (SIGSEGV), a truncated ASCII PLY or OFF
 * face trips an ai_assert in TriangulateProcess (SIGABRT), an OFF face cut short, split over two
 * lines, preceded by a comment line or with more than 9 vertices is silently dropped or read as
 * garbage, and a PLY header declaring 4e9 vertices asks for ~48 GB. Every check here is one pass
 * over the bytes, allocates only the fixed-size PLY header table, and ends in a one-line message
 * naming the file, the element and the limit. Host only; docs/io.md.
 */
#include "io/lt_meshcheck.h"

#include "io/lt_mesh.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int ieq(const char *a, const char *b)
{
    while (*a != '\0' && *b != '\0') {
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b))
            return 0;
        a++;
        b++;
    }
    return *a == *b;
}

lt_meshcheck_kind_t lt_meshcheck_kind(const char *ext, const unsigned char *head, size_t n)
{
    if (ext != NULL && ieq(ext, "ply"))
        return LT_MESHCHECK_PLY;
    if (ext != NULL && ieq(ext, "off"))
        return LT_MESHCHECK_OFF;
    if (ext != NULL && ieq(ext, "stl"))
        return LT_MESHCHECK_STL;
    if (head != NULL && n >= 4 && tolower(head[0]) == 'p' && tolower(head[1]) == 'l' &&
        tolower(head[2]) == 'y' && (head[3] == '\n' || head[3] == '\r'))
        return LT_MESHCHECK_PLY;
    return LT_MESHCHECK_NONE;
}

const char *lt_meshcheck_hint(lt_meshcheck_kind_t kind)
{
    return kind == LT_MESHCHECK_PLY ? "ply" : kind == LT_MESHCHECK_OFF ? "off"
                                          : kind == LT_MESHCHECK_STL ? "stl" : "";
}

/* ---- text helpers ---------------------------------------------------------------------------- */

static int is_blank(unsigned char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }

/* A line [s, e) of a text, e before its '\n' (a '\r' before it is dropped). */
typedef struct line {
    const unsigned char *s, *e;
} line_t;

/* The next line from *pos; 0 at the end of the buffer. *complete = the line ended in '\n'. */
static int next_line(const unsigned char *b, size_t len, size_t *pos, line_t *l, int *complete)
{
    const unsigned char *p, *nl;
    if (*pos >= len)
        return 0;
    p = b + *pos;
    nl = (const unsigned char *)memchr(p, '\n', len - *pos);
    l->s = p;
    l->e = nl != NULL ? nl : b + len;
    *pos = nl != NULL ? (size_t)(nl - b) + 1 : len;
    if (complete != NULL)
        *complete = nl != NULL;
    if (l->e > l->s && l->e[-1] == '\r')
        l->e--;
    return 1;
}

/* The next blank-separated token of *l (advances l->s); 0 when none is left. */
static int next_token(line_t *l, const unsigned char **ts, size_t *tn)
{
    while (l->s < l->e && (is_blank(*l->s) || *l->s == '\r'))
        l->s++;
    if (l->s >= l->e)
        return 0;
    *ts = l->s;
    while (l->s < l->e && !is_blank(*l->s) && *l->s != '\r')
        l->s++;
    *tn = (size_t)(l->s - *ts);
    return 1;
}

static int tok_is(const unsigned char *t, size_t n, const char *word)
{
    return strlen(word) == n && memcmp(t, word, n) == 0;
}

/* A decimal number: [sign] digits [. digits] [e [sign] digits], at least one digit before the
 * exponent; integer: [sign] digits only. No hex, no nan/inf (assimp's parsers read neither as
 * C does). */
static int is_number(const unsigned char *t, size_t n, int integer)
{
    size_t i = 0, digits = 0;
    if (i < n && (t[i] == '+' || t[i] == '-'))
        i++;
    while (i < n && isdigit(t[i])) {
        i++;
        digits++;
    }
    if (integer)
        return digits > 0 && i == n;
    if (i < n && t[i] == '.') {
        i++;
        while (i < n && isdigit(t[i])) {
            i++;
            digits++;
        }
    }
    if (digits == 0)
        return 0;
    if (i < n && (t[i] == 'e' || t[i] == 'E')) {
        size_t ed = 0;
        i++;
        if (i < n && (t[i] == '+' || t[i] == '-'))
            i++;
        while (i < n && isdigit(t[i])) {
            i++;
            ed++;
        }
        if (ed == 0)
            return 0;
    }
    return i == n;
}

/* Unsigned decimal digits only, saturating at UINT64_MAX; 0 if not all digits. */
static int parse_u64(const unsigned char *t, size_t n, uint64_t *v)
{
    size_t i;
    uint64_t x = 0;
    if (n == 0)
        return 0;
    for (i = 0; i < n; i++) {
        unsigned d;
        if (!isdigit(t[i]))
            return 0;
        d = (unsigned)(t[i] - '0');
        x = x > (UINT64_MAX - d) / 10 ? UINT64_MAX : x * 10 + d;
    }
    *v = x;
    return 1;
}

/* An integer token (optional sign) into *v, saturating; 0 if not an integer. */
static int parse_i64(const unsigned char *t, size_t n, int64_t *v)
{
    uint64_t u;
    int neg = 0;
    if (n > 0 && (t[0] == '+' || t[0] == '-')) {
        neg = t[0] == '-';
        t++;
        n--;
    }
    if (!parse_u64(t, n, &u))
        return 0;
    if (u > (uint64_t)INT64_MAX)
        u = (uint64_t)INT64_MAX;
    *v = neg ? -(int64_t)u : (int64_t)u;
    return 1;
}

/* A token quoted for a message: at most 24 bytes, non-printable bytes as '?'. */
static const char *quote(const unsigned char *t, size_t n, char out[32])
{
    size_t i, k = n > 24 ? 24 : n;
    for (i = 0; i < k; i++)
        out[i] = t[i] >= 0x20 && t[i] < 0x7F ? (char)t[i] : '?';
    if (n > k) {
        out[k - 3] = out[k - 2] = out[k - 1] = '.';
    }
    out[k] = '\0';
    return out;
}

/* ---- PLY ------------------------------------------------------------------------------------- */

#define PLY_MAX_ELEMS 16u
#define PLY_MAX_PROPS 128u
#define PLY_NAME 32u

enum { PT_NONE, PT_CHAR, PT_UCHAR, PT_SHORT, PT_USHORT, PT_INT, PT_UINT, PT_FLOAT, PT_DOUBLE };
/* assimp 5.2.5 PlyParser.cpp: Property::ParseDataType */
static const struct {
    const char *name;
    unsigned char type;
} ply_types[] = {{"char", PT_CHAR},     {"int8", PT_CHAR},    {"uchar", PT_UCHAR},
                 {"uint8", PT_UCHAR},   {"short", PT_SHORT},  {"int16", PT_SHORT},
                 {"ushort", PT_USHORT}, {"uint16", PT_USHORT}, {"int", PT_INT},
                 {"int32", PT_INT},     {"uint", PT_UINT},    {"uint32", PT_UINT},
                 {"float", PT_FLOAT},   {"float32", PT_FLOAT}, {"double", PT_DOUBLE},
                 {"float64", PT_DOUBLE}, {"double64", PT_DOUBLE}};

static size_t pt_size(unsigned t)
{
    static const unsigned char sz[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};
    return sz[t];
}

static int pt_integer(unsigned t) { return t >= PT_CHAR && t <= PT_UINT; }

static int pt_signed(unsigned t) { return t == PT_CHAR || t == PT_SHORT || t == PT_INT; }

enum { PE_OTHER, PE_VERTEX, PE_FACE, PE_TRISTRIPS };

typedef struct ply_prop {
    unsigned char type;       /* value type (list: item type) */
    unsigned char count_type; /* list count type, PT_NONE for a scalar */
    unsigned char index;      /* vertex_indices / vertex_index list of a face or tristrips */
    char name[PLY_NAME];
} ply_prop_t;

typedef struct ply_elem {
    char name[PLY_NAME];
    int kind;
    uint64_t count;
    unsigned long line;
    unsigned nprops;
    ply_prop_t props[PLY_MAX_PROPS];
} ply_elem_t;

typedef struct ply_hdr {
    int format; /* 0 none, 1 ascii, 2 binary little endian, 3 binary big endian */
    unsigned nelems;
    size_t body; /* offset of the first byte after end_header's line */
    unsigned long body_line;
    ply_elem_t elems[PLY_MAX_ELEMS];
} ply_hdr_t;

static void copy_name(char dst[PLY_NAME], const unsigned char *t, size_t n)
{
    char q[32];
    (void)quote(t, n, q);
    (void)snprintf(dst, PLY_NAME, "%s", q);
}

/* "vertices" / "vertex", "faces" / "face", else "'name' elements" / "'name' element". */
static const char *noun(const ply_elem_t *e, int plural, char out[64])
{
    if (e->kind == PE_VERTEX)
        return plural ? "vertices" : "vertex";
    if (e->kind == PE_FACE)
        return plural ? "faces" : "face";
    (void)snprintf(out, 64, "'%s' element%s", e->name, plural ? "s" : "");
    return out;
}

static int ply_header(const char *where, const unsigned char *b, size_t len, ply_hdr_t *h,
                      lt_diag_t *diag)
{
    size_t pos = 0;
    unsigned long ln = 0;
    line_t l;
    int complete;
    const unsigned char *t;
    size_t tn;
    char q[32];

    memset(h, 0, sizeof *h);
    for (;;) {
        line_t w;
        const unsigned char *c;
        if (!next_line(b, len, &pos, &l, &complete)) {
            lt_diag_fail(diag, "%s: the PLY header ends at byte %zu (line %lu) without "
                 "'end_header' (truncated?)", where, len, ln);
            return -1;
        }
        ln++;
        w = l;
        if (ln == 1) {
            if (!next_token(&w, &t, &tn) || tn != 3 || tolower(t[0]) != 'p' ||
                tolower(t[1]) != 'l' || tolower(t[2]) != 'y' || next_token(&w, &t, &tn)) {
                lt_diag_fail(diag, "%s: not a PLY file (its first line is not 'ply')", where);
                return -1;
            }
            continue;
        }
        for (c = l.s; c < l.e; c++)
            if ((*c < 0x20 && !is_blank(*c) && *c != '\r') || *c == 0x7F) {
                lt_diag_fail(diag, "%s: line %lu: byte 0x%02x in the PLY header (binary data "
                     "before 'end_header': truncated or not PLY?)", where, ln, (unsigned)*c);
                return -1;
            }
        if (!next_token(&w, &t, &tn))
            continue;
        if (tok_is(t, tn, "end_header")) {
            h->body = pos; /* == len when the file ends with this line */
            h->body_line = ln + 1;
            break;
        }
        if (!complete) {
            lt_diag_fail(diag, "%s: the PLY header ends at byte %zu (line %lu) without "
                 "'end_header' (truncated?)", where, len, ln);
            return -1;
        }
        if (tok_is(t, tn, "format")) {
            if (!next_token(&w, &t, &tn)) {
                lt_diag_fail(diag, "%s: line %lu: 'format' without a format", where, ln);
                return -1;
            }
            if (tok_is(t, tn, "ascii"))
                h->format = 1;
            else if (tok_is(t, tn, "binary_little_endian"))
                h->format = 2;
            else if (tok_is(t, tn, "binary_big_endian"))
                h->format = 3;
            else {
                lt_diag_fail(diag, "%s: line %lu: unknown PLY format '%s' (ascii, "
                     "binary_little_endian or binary_big_endian)", where, ln, quote(t, tn, q));
                return -1;
            }
        } else if (tok_is(t, tn, "element")) {
            ply_elem_t *e;
            if (h->nelems == PLY_MAX_ELEMS) {
                lt_diag_fail(diag, "%s: line %lu: more than %u elements in the PLY header", where,
                     ln, PLY_MAX_ELEMS);
                return -1;
            }
            e = &h->elems[h->nelems++];
            e->line = ln;
            if (!next_token(&w, &t, &tn)) {
                lt_diag_fail(diag, "%s: line %lu: 'element' without a name", where, ln);
                return -1;
            }
            copy_name(e->name, t, tn);
            e->kind = tok_is(t, tn, "vertex")      ? PE_VERTEX
                      : tok_is(t, tn, "face")      ? PE_FACE
                      : tok_is(t, tn, "tristrips") ? PE_TRISTRIPS
                                                   : PE_OTHER;
            if (!next_token(&w, &t, &tn) || !parse_u64(t, tn, &e->count)) {
                lt_diag_fail(diag, "%s: line %lu: element '%s' without a count (need a whole "
                     "number)", where, ln, e->name);
                return -1;
            }
            if (e->count > UINT32_MAX) {
                lt_diag_fail(diag, "%s: line %lu: element '%s' declares %llu instances (assimp "
                     "counts to %lu)", where, ln, e->name, (unsigned long long)e->count,
                     (unsigned long)UINT32_MAX);
                return -1;
            }
        } else if (tok_is(t, tn, "property")) {
            ply_elem_t *e;
            ply_prop_t *p;
            unsigned k, ty = PT_NONE, cty = PT_NONE;
            int list = 0;
            if (h->nelems == 0) {
                lt_diag_fail(diag, "%s: line %lu: 'property' before any 'element'", where, ln);
                return -1;
            }
            e = &h->elems[h->nelems - 1];
            if (e->nprops == PLY_MAX_PROPS) {
                lt_diag_fail(diag, "%s: line %lu: element '%s' has more than %u properties",
                     where, ln, e->name, PLY_MAX_PROPS);
                return -1;
            }
            if (!next_token(&w, &t, &tn)) {
                lt_diag_fail(diag, "%s: line %lu: 'property' without a type", where, ln);
                return -1;
            }
            if (tok_is(t, tn, "list")) {
                list = 1;
                if (!next_token(&w, &t, &tn)) {
                    lt_diag_fail(diag, "%s: line %lu: 'property list' without types", where, ln);
                    return -1;
                }
                for (k = 0; k < sizeof ply_types / sizeof ply_types[0]; k++)
                    if (tok_is(t, tn, ply_types[k].name))
                        cty = ply_types[k].type;
                if (cty == PT_NONE || !pt_integer(cty)) {
                    lt_diag_fail(diag, "%s: line %lu: list count type '%s' is not an integer "
                         "PLY type", where, ln, quote(t, tn, q));
                    return -1;
                }
                if (!next_token(&w, &t, &tn)) {
                    lt_diag_fail(diag, "%s: line %lu: 'property list' without an item type",
                         where, ln);
                    return -1;
                }
            }
            for (k = 0; k < sizeof ply_types / sizeof ply_types[0]; k++)
                if (tok_is(t, tn, ply_types[k].name))
                    ty = ply_types[k].type;
            if (ty == PT_NONE) {
                /* assimp ends the element's property list at an unknown type and drops the
                 * rest: the binary layout would no longer match */
                lt_diag_fail(diag, "%s: line %lu: property type '%s' is not a PLY type assimp "
                     "reads (char uchar short ushort int uint float double, int8 ... float64)",
                     where, ln, quote(t, tn, q));
                return -1;
            }
            if (!next_token(&w, &t, &tn)) {
                lt_diag_fail(diag, "%s: line %lu: property without a name", where, ln);
                return -1;
            }
            p = &e->props[e->nprops++];
            p->type = (unsigned char)ty;
            p->count_type = (unsigned char)(list ? cty : PT_NONE);
            p->index = (unsigned char)(list && (e->kind == PE_FACE || e->kind == PE_TRISTRIPS) &&
                                       (tok_is(t, tn, "vertex_indices") ||
                                        tok_is(t, tn, "vertex_index")));
            copy_name(p->name, t, tn);
            if (p->index && !pt_integer(ty)) {
                lt_diag_fail(diag, "%s: line %lu: %s list '%s' has a floating-point item type "
                     "(indices must be integers)", where, ln, e->name, p->name);
                return -1;
            }
        }
        /* comment, obj_info and anything else: skipped, as assimp does */
    }
    if (h->format == 0) {
        lt_diag_fail(diag, "%s: the PLY header has no 'format' line", where);
        return -1;
    }
    return 0;
}

/* Least bytes one instance of e takes: binary, the scalars and list counts; ascii, 2 per value
 * (a digit and a blank or line end), lists counted as their count alone. Values: the number of
 * values before any list item. */
static uint64_t ply_min_bytes(const ply_elem_t *e, int binary)
{
    uint64_t n = 0;
    unsigned k;
    for (k = 0; k < e->nprops; k++) {
        const ply_prop_t *p = &e->props[k];
        if (binary)
            n += pt_size(p->count_type != PT_NONE ? p->count_type : p->type);
        else
            n += 2;
    }
    return n;
}

static uint64_t rd_uint(const unsigned char *p, size_t n, int big)
{
    uint64_t v = 0;
    size_t i;
    for (i = 0; i < n; i++)
        v |= (uint64_t)p[big ? n - 1 - i : i] << (8 * i);
    return v;
}

/* An integer value of type t at p (binary); signed types sign-extended. */
static int64_t rd_int(const unsigned char *p, unsigned t, int big)
{
    size_t n = pt_size(t);
    uint64_t u = rd_uint(p, n, big);
    if (pt_signed(t) && n < 8 && (u >> (8 * n - 1)) != 0)
        return (int64_t)(u | ~((UINT64_C(1) << (8 * n)) - 1));
    return (int64_t)u;
}

/* One list index: >= 0 and < nverts (tristrips: -1 restarts a strip). */
static int ply_index_ok(int64_t idx, const ply_elem_t *e, uint64_t nverts)
{
    if (idx == -1 && e->kind == PE_TRISTRIPS)
        return 1;
    return idx >= 0 && (uint64_t)idx < nverts;
}

static int ply_body_binary(const char *where, const unsigned char *b, size_t len,
                           const ply_hdr_t *h, uint64_t nverts, lt_diag_t *diag)
{
    int big = h->format == 3;
    size_t pos = h->body;
    unsigned ei, k;
    char nb[64];
    for (ei = 0; ei < h->nelems; ei++) {
        const ply_elem_t *e = &h->elems[ei];
        uint64_t i;
        for (i = 0; i < e->count; i++) {
            size_t start = pos;
            for (k = 0; k < e->nprops; k++) {
                const ply_prop_t *p = &e->props[k];
                size_t isz = pt_size(p->type);
                if (p->count_type == PT_NONE) {
                    if (len - pos < isz)
                        goto truncated;
                    pos += isz;
                } else {
                    size_t csz = pt_size(p->count_type);
                    int64_t n;
                    if (len - pos < csz)
                        goto truncated;
                    n = rd_int(b + pos, p->count_type, big);
                    if (n < 0) {
                        lt_diag_fail(diag, "%s: %s %llu of %llu (byte %zu): list '%s' has %lld "
                             "items", where, noun(e, 0, nb), (unsigned long long)i + 1,
                             (unsigned long long)e->count, pos, p->name, (long long)n);
                        return -1;
                    }
                    pos += csz;
                    if ((uint64_t)n > (len - pos) / isz)
                        goto truncated;
                    if (p->index) {
                        int64_t j;
                        for (j = 0; j < n; j++) {
                            int64_t idx = rd_int(b + pos + (size_t)j * isz, p->type, big);
                            if (!ply_index_ok(idx, e, nverts)) {
                                lt_diag_fail(diag, "%s: %s %llu of %llu (byte %zu): vertex index "
                                     "%lld outside 0..%lld (%llu vertices)", where,
                                     noun(e, 0, nb), (unsigned long long)i + 1,
                                     (unsigned long long)e->count, start, (long long)idx,
                                     (long long)nverts - 1, (unsigned long long)nverts);
                                return -1;
                            }
                        }
                    }
                    pos += (size_t)n * isz;
                }
            }
            continue;
        truncated:
            lt_diag_fail(diag, "%s: truncated: the file's %zu bytes end inside %s %llu of %llu "
                 "(which starts at byte %zu; binary body from byte %zu)", where, len,
                 noun(e, 0, nb), (unsigned long long)i + 1, (unsigned long long)e->count, start,
                 h->body);
            return -1;
        }
    }
    return 0;
}

static int ply_body_ascii(const char *where, const unsigned char *b, size_t len,
                          const ply_hdr_t *h, uint64_t nverts, lt_diag_t *diag)
{
    size_t pos = h->body;
    unsigned long ln = h->body_line - 1;
    unsigned ei, k;
    char nb[64], q[32];
    for (ei = 0; ei < h->nelems; ei++) {
        const ply_elem_t *e = &h->elems[ei];
        uint64_t i;
        for (i = 0; i < e->count; i++) {
            line_t l;
            const unsigned char *t;
            size_t tn;
            unsigned vals = 0;
            /* one instance per line; assimp skips blank lines */
            for (;;) {
                line_t w;
                if (!next_line(b, len, &pos, &l, NULL)) {
                    lt_diag_fail(diag, "%s: truncated: the file ends after %llu of %llu %s (line "
                         "%lu)", where, (unsigned long long)i, (unsigned long long)e->count,
                         noun(e, 1, nb), ln);
                    return -1;
                }
                ln++;
                w = l;
                if (next_token(&w, &t, &tn))
                    break;
            }
            for (k = 0; k < e->nprops; k++) {
                const ply_prop_t *p = &e->props[k];
                uint64_t n = 1, j;
                if (p->count_type != PT_NONE) {
                    if (!next_token(&l, &t, &tn))
                        goto short_line;
                    vals++;
                    if (!parse_u64(t, tn, &n)) {
                        lt_diag_fail(diag, "%s: line %lu: %s %llu of %llu: list '%s' count '%s' "
                             "is not a whole number", where, ln, noun(e, 0, nb),
                             (unsigned long long)i + 1, (unsigned long long)e->count, p->name,
                             quote(t, tn, q));
                        return -1;
                    }
                }
                for (j = 0; j < n; j++) {
                    if (!next_token(&l, &t, &tn))
                        goto short_line;
                    vals++;
                    if (!is_number(t, tn, pt_integer(p->type))) {
                        lt_diag_fail(diag, "%s: line %lu: %s %llu of %llu: '%s' is not %s (property "
                             "'%s')", where, ln, noun(e, 0, nb), (unsigned long long)i + 1,
                             (unsigned long long)e->count, quote(t, tn, q),
                             pt_integer(p->type) ? "an integer" : "a number", p->name);
                        return -1;
                    }
                    if (p->index) {
                        int64_t idx = 0;
                        (void)parse_i64(t, tn, &idx);
                        if (!ply_index_ok(idx, e, nverts)) {
                            lt_diag_fail(diag, "%s: line %lu: %s %llu of %llu: vertex index %s "
                                 "outside 0..%lld (%llu vertices)", where, ln, noun(e, 0, nb),
                                 (unsigned long long)i + 1, (unsigned long long)e->count,
                                 quote(t, tn, q), (long long)nverts - 1,
                                 (unsigned long long)nverts);
                            return -1;
                        }
                    }
                }
                continue;
            short_line:
                lt_diag_fail(diag, "%s: line %lu: %s %llu of %llu ends after %u value%s, before "
                     "property '%s' is complete (truncated, or one %s split over lines?)", where,
                     ln, noun(e, 0, nb), (unsigned long long)i + 1, (unsigned long long)e->count,
                     vals, vals == 1 ? "" : "s", p->name, noun(e, 0, nb));
                return -1;
            }
            /* values after the properties are ignored by assimp (and here) */
        }
    }
    return 0;
}

static int check_ply(const char *where, const unsigned char *b, size_t len, lt_diag_t *diag)
{
    ply_hdr_t *h = (ply_hdr_t *)malloc(sizeof *h);
    uint64_t used = 0, nverts = 0, cap;
    size_t body;
    unsigned ei;
    int binary, rc = -1;
    char nb[64];

    if (h == NULL) {
        lt_diag_fail(diag, "%s: out of memory", where);
        return -1;
    }
    if (ply_header(where, b, len, h, diag) != 0)
        goto done;
    binary = h->format != 1;
    body = len - h->body;
    /* counts against the bytes there are, before walking anything; ascii: the last value of
     * the file needs no line end */
    cap = binary ? (uint64_t)body : (uint64_t)body + 1;
    for (ei = 0; ei < h->nelems; ei++) {
        const ply_elem_t *e = &h->elems[ei];
        uint64_t each = ply_min_bytes(e, binary);
        if (e->kind == PE_VERTEX && nverts == 0)
            nverts = e->count;
        if (e->count == 0)
            continue;
        if (e->nprops == 0) {
            lt_diag_fail(diag, "%s: line %lu: header declares %llu %s with no properties", where,
                 e->line, (unsigned long long)e->count, noun(e, 1, nb));
            goto done;
        }
        if (e->count > (cap - used) / each) {
            lt_diag_fail(diag, "%s: header declares %llu %s; the file's %zu bytes hold at most %llu "
                 "(%llu bytes each%s)", where, (unsigned long long)e->count, noun(e, 1, nb), len,
                 (unsigned long long)((cap - used) / each), (unsigned long long)each,
                 binary ? "" : " at least: a digit and a separator per value");
            goto done;
        }
        used += e->count * each;
        if (e->kind == PE_FACE && e->count > LT_MESH_MAX_TRIS) {
            lt_diag_fail(diag, "%s: header declares %llu faces (LT_MESH_MAX_TRIS is %u triangles)",
                 where, (unsigned long long)e->count, LT_MESH_MAX_TRIS);
            goto done;
        }
    }
    for (ei = 0; ei < h->nelems; ei++)
        if ((h->elems[ei].kind == PE_FACE || h->elems[ei].kind == PE_TRISTRIPS) &&
            h->elems[ei].count > 0)
            break;
    if (ei == h->nelems) {
        lt_diag_fail(diag, "%s: no faces: the header declares no 'face' or 'tristrips' element "
             "with instances (a point cloud?)", where);
        goto done;
    }
    rc = binary ? ply_body_binary(where, b, len, h, nverts, diag)
                : ply_body_ascii(where, b, len, h, nverts, diag);
done:
    free(h);
    return rc;
}

/* ---- OFF ------------------------------------------------------------------------------------- */

/* assimp's OFF reader copies each body line into a 4096-byte buffer */
#define OFF_MAX_LINE 4095u

/* Next token of the OFF header, skipping blanks, line ends and '#' comment lines (assimp's
 * NextToken). Returns 0 at the end. */
static int off_header_token(const unsigned char *b, size_t len, size_t *pos, unsigned long *ln,
                            const unsigned char **t, size_t *tn)
{
    size_t p = *pos;
    for (;;) {
        while (p < len && (is_blank(b[p]) || b[p] == '\r' || b[p] == '\n')) {
            *ln += b[p] == '\n';
            p++;
        }
        if (p < len && b[p] == '#') {
            while (p < len && b[p] != '\n')
                p++;
            continue;
        }
        break;
    }
    if (p >= len) {
        *pos = p;
        return 0;
    }
    *t = b + p;
    while (p < len && !is_blank(b[p]) && b[p] != '\r' && b[p] != '\n')
        p++;
    *tn = (size_t)(b + p - *t);
    *pos = p;
    return 1;
}

/* The next non-blank body line (assimp's GetNextLine skips empty lines). */
static int off_line(const unsigned char *b, size_t len, size_t *pos, unsigned long *ln,
                    line_t *l, int *toolong)
{
    for (;;) {
        line_t w;
        const unsigned char *t;
        size_t tn;
        if (!next_line(b, len, pos, l, NULL))
            return 0;
        (*ln)++;
        *toolong = (size_t)(l->e - l->s) > OFF_MAX_LINE;
        w = *l;
        if (next_token(&w, &t, &tn))
            return 1;
    }
}

/* OFF: the header line, the counts, and the counts against the file size. Leaves *pos and *ln at
 * the first vertex line; *need = values per vertex line. */
static int off_header(const char *where, const unsigned char *b, size_t len, size_t *pos_,
                      unsigned long *ln_, uint64_t *nv_, uint64_t *nf_, unsigned *need_,
                      lt_diag_t *diag)
{
    size_t pos = 0, i;
    unsigned long ln = 1;
    const unsigned char *t;
    size_t tn;
    int st = 0, col = 0, nrm = 0, hom = 0, ndim = 0;
    unsigned dims = 3, need;
    uint64_t nv, nf, ne, d64;
    char q[32];

    for (i = 0; i < len; i++)
        if (b[i] == 0 || b[i] == 0x7F) {
            lt_diag_fail(diag, "%s: byte 0x%02x at offset %zu: binary data (assimp reads only "
                 "ASCII OFF)", where, (unsigned)b[i], i);
            return -1;
        }
    if (!off_header_token(b, len, &pos, &ln, &t, &tn)) {
        lt_diag_fail(diag, "%s: no OFF header (empty or only comments)", where);
        return -1;
    }
    {
        size_t k = 0;
        if (k + 2 <= tn && t[k] == 'S' && t[k + 1] == 'T') {
            st = 1;
            k += 2;
        }
        if (k < tn && t[k] == 'C') {
            col = 1;
            k++;
        }
        if (k < tn && t[k] == 'N') {
            nrm = 1;
            k++;
        }
        if (k < tn && t[k] == '4') {
            hom = 1;
            k++;
        }
        if (k < tn && t[k] == 'n') {
            ndim = 1;
            k++;
        }
        if (!(tn - k == 3 && memcmp(t + k, "OFF", 3) == 0)) {
            lt_diag_fail(diag, "%s: line %lu: '%s' is not an OFF header ([ST][C][N][4][n]OFF; "
                 "assimp 5.2.5 does not read OFF files without one)", where, ln, quote(t, tn, q));
            return -1;
        }
    }
    if (ndim) {
        if (!off_header_token(b, len, &pos, &ln, &t, &tn) || !parse_u64(t, tn, &d64) ||
            d64 < 1 || d64 > 3) {
            lt_diag_fail(diag, "%s: line %lu: nOFF dimension must be 1..3 (assimp's limit)", where,
                 ln);
            return -1;
        }
        dims = (unsigned)d64;
    }
    {
        uint64_t *cnt[3];
        static const char *what[3] = {"vertex", "face", "edge"};
        unsigned c;
        cnt[0] = &nv;
        cnt[1] = &nf;
        cnt[2] = &ne;
        for (c = 0; c < 3; c++) {
            if (!off_header_token(b, len, &pos, &ln, &t, &tn)) {
                lt_diag_fail(diag, "%s: truncated: the OFF header ends before its %s count", where,
                     what[c]);
                return -1;
            }
            if (c == 0 && tok_is(t, tn, "BINARY")) {
                lt_diag_fail(diag, "%s: line %lu: binary OFF (assimp reads only ASCII OFF)", where,
                     ln);
                return -1;
            }
            if (!parse_u64(t, tn, cnt[c])) {
                lt_diag_fail(diag, "%s: line %lu: OFF %s count '%s' is not a whole number", where,
                     ln, what[c], quote(t, tn, q));
                return -1;
            }
        }
    }
    /* the rest of the counts line: blanks or a comment (assimp would read anything else as
     * the first vertex) */
    while (pos < len && (is_blank(b[pos]) || b[pos] == '\r'))
        pos++;
    if (pos < len && b[pos] != '\n' && b[pos] != '#') {
        line_t w;
        size_t p2 = pos;
        (void)next_line(b, len, &p2, &w, NULL);
        (void)next_token(&w, &t, &tn);
        lt_diag_fail(diag, "%s: line %lu: '%s' after the OFF counts (vertices faces edges)", where,
             ln, quote(t, tn, q));
        return -1;
    }
    while (pos < len && b[pos] != '\n')
        pos++; /* a comment */
    if (pos < len)
        pos++;
    ln++;
    if (nv == 0 || nf == 0) {
        lt_diag_fail(diag, "%s: header declares %llu vertices and %llu faces (need at least 1 "
             "each)", where, (unsigned long long)nv, (unsigned long long)nf);
        return -1;
    }
    need = dims + (unsigned)hom + 3u * (unsigned)nrm + (unsigned)col + 2u * (unsigned)st;
    {
        uint64_t body = (uint64_t)(len - pos) + 1, each = 2u * need;
        if (nv > body / each) {
            lt_diag_fail(diag, "%s: header declares %llu vertices; the file's %zu bytes hold at "
                 "most %llu (%llu bytes each at least: a digit and a separator per value)",
                 where, (unsigned long long)nv, len, (unsigned long long)(body / each),
                 (unsigned long long)each);
            return -1;
        }
        body -= nv * each;
        if (nf > body / 8) {
            lt_diag_fail(diag, "%s: header declares %llu faces; the file's %zu bytes hold at most "
                 "%llu after the vertices (8 bytes each at least: 'n i j k')", where,
                 (unsigned long long)nf, len, (unsigned long long)(body / 8));
            return -1;
        }
        if (nf > LT_MESH_MAX_TRIS) {
            lt_diag_fail(diag, "%s: header declares %llu faces (LT_MESH_MAX_TRIS is %u triangles)",
                 where, (unsigned long long)nf, LT_MESH_MAX_TRIS);
            return -1;
        }
    }
    *pos_ = pos;
    *ln_ = ln;
    *nv_ = nv;
    *nf_ = nf;
    *need_ = need;
    return 0;
}

/* OFF: nv vertex lines of need numbers each (comments after them allowed). */
static int off_vertices(const char *where, const unsigned char *b, size_t len, size_t *pos_,
                        unsigned long *ln_, uint64_t nv, unsigned need, lt_diag_t *diag)
{
    size_t pos = *pos_, tn;
    unsigned long ln = *ln_;
    const unsigned char *t;
    uint64_t v;
    char q[32];
    for (v = 0; v < nv; v++) {
        line_t l;
        int toolong;
        unsigned n = 0;
        if (!off_line(b, len, &pos, &ln, &l, &toolong)) {
            lt_diag_fail(diag, "%s: truncated: the file ends after %llu of %llu vertices (line %lu)",
                 where, (unsigned long long)v, (unsigned long long)nv, ln);
            return -1;
        }
        if (toolong) {
            lt_diag_fail(diag, "%s: line %lu is %zu bytes long (assimp's OFF reader reads lines of "
                 "up to %u)", where, ln, (size_t)(l.e - l.s), OFF_MAX_LINE);
            return -1;
        }
        {
            line_t w = l;
            if (next_token(&w, &t, &tn) && t[0] == '#') {
                lt_diag_fail(diag, "%s: line %lu: comment line among the vertices (assimp's OFF "
                     "reader would read it as vertex %llu of %llu)", where, ln,
                     (unsigned long long)v + 1, (unsigned long long)nv);
                return -1;
            }
        }
        while (n < need && next_token(&l, &t, &tn)) {
            if (t[0] == '#')
                break;
            if (!is_number(t, tn, 0)) {
                lt_diag_fail(diag, "%s: line %lu: vertex %llu of %llu: '%s' is not a number", where,
                     ln, (unsigned long long)v + 1, (unsigned long long)nv, quote(t, tn, q));
                return -1;
            }
            n++;
        }
        if (n < need) {
            lt_diag_fail(diag, "%s: line %lu: vertex %llu of %llu has %u of its %u values "
                 "(truncated?)", where, ln, (unsigned long long)v + 1, (unsigned long long)nv, n,
                 need);
            return -1;
        }
    }
    *pos_ = pos;
    *ln_ = ln;
    return 0;
}

/* OFF: nf face lines, 3..9 indices below nv each. */
static int off_faces(const char *where, const unsigned char *b, size_t len, size_t *pos_,
                     unsigned long *ln_, uint64_t nv, uint64_t nf, lt_diag_t *diag)
{
    size_t pos = *pos_, tn;
    unsigned long ln = *ln_;
    const unsigned char *t;
    uint64_t f;
    char q[32];
    for (f = 0; f < nf; f++) {
        line_t l;
        int toolong;
        uint64_t k, j;
        if (!off_line(b, len, &pos, &ln, &l, &toolong)) {
            lt_diag_fail(diag, "%s: truncated: the file ends after %llu of %llu faces (line %lu)",
                 where, (unsigned long long)f, (unsigned long long)nf, ln);
            return -1;
        }
        if (toolong) {
            lt_diag_fail(diag, "%s: line %lu is %zu bytes long (assimp's OFF reader reads lines of "
                 "up to %u)", where, ln, (size_t)(l.e - l.s), OFF_MAX_LINE);
            return -1;
        }
        (void)next_token(&l, &t, &tn);
        if (t[0] == '#') {
            lt_diag_fail(diag, "%s: line %lu: comment line among the faces (assimp would drop "
                 "face %llu of %llu)", where, ln, (unsigned long long)f + 1,
                 (unsigned long long)nf);
            return -1;
        }
        if (!parse_u64(t, tn, &k)) {
            lt_diag_fail(diag, "%s: line %lu: face %llu of %llu: vertex count '%s' is not a whole "
                 "number", where, ln, (unsigned long long)f + 1, (unsigned long long)nf,
                 quote(t, tn, q));
            return -1;
        }
        if (k < 3 || k > 9) {
            lt_diag_fail(diag, "%s: line %lu: face %llu of %llu has %llu vertices (assimp's OFF "
                 "reader drops faces of 0 or more than 9; a triangle needs 3)", where, ln,
                 (unsigned long long)f + 1, (unsigned long long)nf, (unsigned long long)k);
            return -1;
        }
        for (j = 0; j < k; j++) {
            uint64_t idx;
            if (!next_token(&l, &t, &tn) || t[0] == '#') {
                lt_diag_fail(diag, "%s: line %lu: face %llu of %llu lists %llu of its %llu vertex "
                     "indices (truncated?)", where, ln, (unsigned long long)f + 1,
                     (unsigned long long)nf, (unsigned long long)j, (unsigned long long)k);
                return -1;
            }
            if (!parse_u64(t, tn, &idx) || idx >= nv) {
                lt_diag_fail(diag, "%s: line %lu: face %llu of %llu: vertex index '%s' outside "
                     "0..%llu", where, ln, (unsigned long long)f + 1, (unsigned long long)nf,
                     quote(t, tn, q), (unsigned long long)nv - 1);
                return -1;
            }
        }
        /* colour values after the indices are allowed (and ignored) */
    }
    *pos_ = pos;
    *ln_ = ln;
    return 0;
}

static int check_off(const char *where, const unsigned char *b, size_t len, lt_diag_t *diag)
{
    size_t pos;
    unsigned long ln;
    uint64_t nv, nf;
    unsigned need;
    if (off_header(where, b, len, &pos, &ln, &nv, &nf, &need, diag) != 0 ||
        off_vertices(where, b, len, &pos, &ln, nv, need, diag) != 0 ||
        off_faces(where, b, len, &pos, &ln, nv, nf, diag) != 0)
        return -1;
    return 0;
}

/* ---- STL ------------------------------------------------------------------------------------- */

/* ASCII STL, checked token by token: solid NAME, then facets (facet normal x y z, outer loop,
 * three 'vertex x y z', endloop, endfacet), endsolid; several solids may follow each other.
 * assimp only warns about a facet with fewer than 3 vertices and then pairs the following
 * vertices into the wrong triangles. */
static int check_stl_ascii(const char *where, const unsigned char *b, size_t len, lt_diag_t *diag)
{
    size_t pos = 0;
    unsigned long ln = 0, facets = 0, fline = 0;
    int in_solid = 0, in_facet = 0, verts = 0, solids = 0;
    line_t l;
    const unsigned char *t;
    size_t tn;
    char q[32];

    while (next_line(b, len, &pos, &l, NULL)) {
        ln++;
        while (next_token(&l, &t, &tn)) {
            if (!in_solid) {
                if (!tok_is(t, tn, "solid")) {
                    lt_diag_fail(diag, "%s: line %lu: '%s' where 'solid' should start an ASCII STL "
                         "solid", where, ln, quote(t, tn, q));
                    return -1;
                }
                in_solid = 1;
                solids++;
                l.s = l.e; /* the name: the rest of the line */
                break;
            }
            if (tok_is(t, tn, "facet")) {
                int k;
                if (in_facet) {
                    lt_diag_fail(diag, "%s: line %lu: a facet starts before facet %lu (line %lu) "
                         "ended", where, ln, facets, fline);
                    return -1;
                }
                in_facet = 1;
                verts = 0;
                facets++;
                fline = ln;
                if (!next_token(&l, &t, &tn) || !tok_is(t, tn, "normal")) {
                    lt_diag_fail(diag, "%s: line %lu: facet %lu without 'normal x y z'", where, ln,
                         facets);
                    return -1;
                }
                for (k = 0; k < 3; k++)
                    if (!next_token(&l, &t, &tn) || !is_number(t, tn, 0)) {
                        lt_diag_fail(diag, "%s: line %lu: facet %lu: normal needs 3 numbers%s",
                             where, ln, facets, l.s >= l.e ? " (truncated?)" : "");
                        return -1;
                    }
            } else if (tok_is(t, tn, "vertex")) {
                int k;
                if (!in_facet) {
                    lt_diag_fail(diag, "%s: line %lu: 'vertex' outside a facet", where, ln);
                    return -1;
                }
                if (++verts > 3) {
                    lt_diag_fail(diag, "%s: line %lu: facet %lu has more than 3 vertices", where,
                         ln, facets);
                    return -1;
                }
                for (k = 0; k < 3; k++)
                    if (!next_token(&l, &t, &tn) || !is_number(t, tn, 0)) {
                        lt_diag_fail(diag, "%s: line %lu: facet %lu: vertex %d needs 3 numbers%s",
                             where, ln, facets, verts, l.s >= l.e ? " (truncated?)" : "");
                        return -1;
                    }
            } else if (tok_is(t, tn, "outer") || tok_is(t, tn, "loop") ||
                       tok_is(t, tn, "endloop")) {
                if (!in_facet) {
                    lt_diag_fail(diag, "%s: line %lu: '%s' outside a facet", where, ln,
                         quote(t, tn, q));
                    return -1;
                }
            } else if (tok_is(t, tn, "endfacet")) {
                if (!in_facet || verts != 3) {
                    lt_diag_fail(diag, "%s: line %lu: facet %lu ends with %d vertices (need 3)",
                         where, ln, facets, in_facet ? verts : 0);
                    return -1;
                }
                in_facet = 0;
                if (facets > LT_MESH_MAX_TRIS) {
                    lt_diag_fail(diag, "%s: line %lu: more than LT_MESH_MAX_TRIS %u facets", where,
                         ln, LT_MESH_MAX_TRIS);
                    return -1;
                }
            } else if (tok_is(t, tn, "endsolid")) {
                if (in_facet) {
                    lt_diag_fail(diag, "%s: line %lu: 'endsolid' inside facet %lu (line %lu)",
                         where, ln, facets, fline);
                    return -1;
                }
                in_solid = 0;
                l.s = l.e;
                break;
            } else {
                lt_diag_fail(diag, "%s: line %lu: unexpected '%s' in an ASCII STL solid", where,
                     ln, quote(t, tn, q));
                return -1;
            }
        }
    }
    if (in_facet) {
        lt_diag_fail(diag, "%s: truncated: the file ends inside facet %lu (line %lu) with %d of "
             "its 3 vertices", where, facets, fline, verts);
        return -1;
    }
    if (in_solid) {
        lt_diag_fail(diag, "%s: truncated: the file ends after facet %lu without 'endsolid'",
             where, facets);
        return -1;
    }
    if (solids == 0 || facets == 0) {
        lt_diag_fail(diag, "%s: no facets in the ASCII STL", where);
        return -1;
    }
    return 0;
}

static int check_stl(const char *where, const unsigned char *b, size_t len, lt_diag_t *diag)
{
    uint64_t n = 0, want;
    size_t i, k;
    int ascii;
    if (len >= 84) {
        n = rd_uint(b + 80, 4, 0);
        want = 84 + 50 * n;
        if (want == len) { /* assimp: binary whenever the sizes match, whatever the header says */
            if (n == 0) {
                lt_diag_fail(diag, "%s: binary STL with 0 triangles", where);
                return -1;
            }
            if (n > LT_MESH_MAX_TRIS) {
                lt_diag_fail(diag, "%s: header declares %llu triangles (LT_MESH_MAX_TRIS is %u)",
                     where, (unsigned long long)n, LT_MESH_MAX_TRIS);
                return -1;
            }
            return 0;
        }
    }
    /* assimp: ASCII when it starts with "solid" (after blanks) and its first 500 bytes are
     * ASCII */
    for (i = 0; i < len && isspace(b[i]); i++)
        ;
    ascii = len - i > 5 && memcmp(b + i, "solid", 5) == 0;
    for (k = 0; ascii && k < len && k < 500; k++)
        if (b[k] > 0x7F || b[k] == 0)
            ascii = 0;
    if (ascii)
        return check_stl_ascii(where, b, len, diag);
    if (len < 84) {
        lt_diag_fail(diag, "%s: %zu bytes: neither ASCII STL ('solid ...') nor binary STL (an "
             "84-byte header with the triangle count, then 50 bytes per triangle)", where, len);
        return -1;
    }
    if (84 + 50 * n > len) {
        lt_diag_fail(diag, "%s: header declares %llu triangles; the file's %zu bytes hold at most "
             "%zu (50 bytes each after the 84-byte header)", where, (unsigned long long)n, len,
             (len - 84) / 50);
        return -1;
    }
    lt_diag_fail(diag, "%s: header declares %llu triangles (%llu bytes) but the file has %zu bytes, "
         "%llu more (binary STL must match exactly; not ASCII either: no 'solid' at the start)",
         where, (unsigned long long)n, (unsigned long long)(84 + 50 * n), len,
         (unsigned long long)(len - 84 - 50 * n));
    return -1;
}

int lt_meshcheck(lt_meshcheck_kind_t kind, const char *where, const unsigned char *buf, size_t len,
                 lt_diag_t *diag)
{
    switch (kind) {
    case LT_MESHCHECK_PLY:
        return check_ply(where, buf, len, diag);
    case LT_MESHCHECK_OFF:
        return check_off(where, buf, len, diag);
    case LT_MESHCHECK_STL:
        return check_stl(where, buf, len, diag);
    case LT_MESHCHECK_NONE:
    default:
        return 0;
    }
}
