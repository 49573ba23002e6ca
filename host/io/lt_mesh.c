/* lt_mesh.c - mesh loading through assimp's C API (Debian libassimp-dev): gzip'd files unpacked
 * in memory with zlib, OBJ text checked line by line (assimp silently accepts NaN vertices and
 * out-of-range texture indices, and reports no line numbers), then indices and finiteness checked
 * again after import for every format. Host only; docs/io.md.
 */
#include "io/lt_mesh.h"

#include "io/lt_import.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

#define IMPORT_FLAGS (aiProcess_Triangulate | aiProcess_PreTransformVertices)

/* Case-insensitive "s ends with suffix". */
static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix), i;
    if (k > n)
        return 0;
    for (i = 0; i < k; i++)
        if (tolower((unsigned char)s[n - k + i]) != tolower((unsigned char)suffix[i]))
            return 0;
    return 1;
}

/* ---- whole-file reading and gunzip ----------------------------------------------------------- */

int lt_mesh_read_file(const char *path, char **buf, size_t *len, lt_diag_t *diag)
{
    FILE *f;
    struct stat st;
    size_t got;
    *buf = NULL;
    *len = 0;
    if (lt_diag_not_regular(path) != NULL) { /* before opening it (io/lt_diag.h) */
        lt_diag_fail(diag, "%s: %s, not a regular file", path, lt_diag_not_regular(path));
        return -1;
    }
    f = fopen(path, "rb");
    if (f == NULL) {
        lt_diag_fail(diag, "%s: cannot open the mesh file: %s", path, strerror(errno));
        return -1;
    }
    if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
        lt_diag_fail(diag, "%s: not a regular file", path);
        (void)fclose(f);
        return -1;
    }
    if ((uint64_t)st.st_size > LT_MESH_MAX_BYTES) {
        lt_diag_fail(diag, "%s: %lld bytes exceed LT_MESH_MAX_BYTES %u", path,
                     (long long)st.st_size, LT_MESH_MAX_BYTES);
        (void)fclose(f);
        return -1;
    }
    *buf = (char *)malloc((size_t)st.st_size + 1);
    if (*buf == NULL) {
        lt_diag_fail(diag, "%s: out of memory for %lld bytes", path, (long long)st.st_size);
        (void)fclose(f);
        return -1;
    }
    got = fread(*buf, 1, (size_t)st.st_size, f);
    if (got != (size_t)st.st_size || ferror(f)) {
        lt_diag_fail(diag, "%s: read error after %zu of %lld bytes", path, got,
                     (long long)st.st_size);
        (void)fclose(f);
        free(*buf);
        *buf = NULL;
        return -1;
    }
    (void)fclose(f);
    (*buf)[got] = '\0';
    *len = got;
    return 0;
}

/* Unpack gzip data (one or more members) into a NUL-terminated buffer. */
static int gunzip(const char *path, const unsigned char *in, size_t inlen, char **out,
                  size_t *outlen, lt_diag_t *diag)
{
    z_stream zs;
    size_t cap, used = 0;
    char *buf;
    int zr = Z_OK;

    *out = NULL;
    *outlen = 0;
    if (inlen < 18 || in[0] != 0x1F || in[1] != 0x8B) {
        lt_diag_fail(diag, "%s: not a gzip file (%zu bytes; a gzip stream starts 1f 8b and has "
                     "at least 18 bytes)", path, inlen);
        return -1;
    }
    /* first guess: the last member's ISIZE (size mod 2^32), at least 64 KiB */
    cap = (size_t)in[inlen - 4] | ((size_t)in[inlen - 3] << 8) | ((size_t)in[inlen - 2] << 16) |
          ((size_t)in[inlen - 1] << 24);
    if (cap < 65536)
        cap = 65536;
    if (cap > LT_MESH_MAX_BYTES)
        cap = LT_MESH_MAX_BYTES;
    buf = (char *)malloc(cap + 1);
    if (buf == NULL) {
        lt_diag_fail(diag, "%s: out of memory", path);
        return -1;
    }
    memset(&zs, 0, sizeof zs);
    if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK) {
        lt_diag_fail(diag, "%s: zlib init failed", path);
        free(buf);
        return -1;
    }
    zs.next_in = (Bytef *)(uintptr_t)in; /* zlib's API is not const-correct */
    zs.avail_in = (uInt)inlen;           /* inlen <= LT_MESH_MAX_BYTES < 2^32 */
    for (;;) {
        if (used == cap) {
            char *nb;
            if (cap >= LT_MESH_MAX_BYTES) {
                lt_diag_fail(diag, "%s: unpacks to more than LT_MESH_MAX_BYTES %u bytes", path,
                             LT_MESH_MAX_BYTES);
                goto bad;
            }
            cap = cap * 2 > LT_MESH_MAX_BYTES ? LT_MESH_MAX_BYTES : cap * 2;
            nb = (char *)realloc(buf, cap + 1);
            if (nb == NULL) {
                lt_diag_fail(diag, "%s: out of memory for %zu unpacked bytes", path, cap);
                goto bad;
            }
            buf = nb;
        }
        zs.next_out = (Bytef *)(buf + used);
        zs.avail_out = (uInt)(cap - used);
        zr = inflate(&zs, Z_NO_FLUSH);
        used = cap - zs.avail_out;
        if (zr == Z_STREAM_END) {
            if (zs.avail_in == 0)
                break;
            /* another gzip member follows (as `cat a.gz b.gz` makes), or trailing garbage */
            if (zs.avail_in < 2 || zs.next_in[0] != 0x1F || zs.next_in[1] != 0x8B) {
                lt_diag_fail(diag, "%s: %u bytes of trailing data after the gzip stream "
                             "(at compressed byte %lu)", path, zs.avail_in, zs.total_in);
                goto bad;
            }
            if (inflateReset(&zs) != Z_OK) {
                lt_diag_fail(diag, "%s: zlib reset failed", path);
                goto bad;
            }
            continue;
        }
        if (zr == Z_OK)
            continue;
        if (zr == Z_BUF_ERROR && zs.avail_in == 0) {
            lt_diag_fail(diag, "%s: truncated gzip stream: input ends after %lu compressed bytes "
                         "(%zu bytes unpacked) before the end of the stream", path, zs.total_in,
                         used);
            goto bad;
        }
        if (zr == Z_BUF_ERROR)
            continue; /* output full: grow */
        lt_diag_fail(diag, "%s: corrupt gzip stream near compressed byte %lu: %s (zlib %d)", path,
                     zs.total_in, zs.msg != NULL ? zs.msg : "no message", zr);
        goto bad;
    }
    (void)inflateEnd(&zs);
    buf[used] = '\0';
    *out = buf;
    *outlen = used;
    return 0;
bad:
    (void)inflateEnd(&zs);
    free(buf);
    return -1;
}

/* ---- OBJ text check -------------------------------------------------------------------------- */

/* Blanks as assimp's OBJ reader has them (its IsSpace): a vertical tab is not one, so it stays
 * inside a word, where assimp read "2\v2" as a face index and threw inside its reader (mesh fuzz
 * target, LeakSanitizer; regress-vtab-leak); outside comments it is refused as a control byte. */
static int is_blank(char c) { return c == ' ' || c == '\t'; }

static int is_eol(char c) { return c == '\n' || c == '\r' || c == '\0'; }

/* The end of the word that starts at q on a line ending at p (for messages and keywords). */
static const char *word_end(const char *q, const char *p)
{
    while (q < p && !is_blank(*q) && !is_eol(*q))
        q++;
    return q;
}

/* One index of a face vertex: positive or negative (relative), it must reach one of the `have`
 * defined so far. */
static int check_index(long long idx, uint64_t have, unsigned long line, const char *what,
                       const char *defined, const char *where, lt_diag_t *diag)
{
    if (idx == 0) {
        lt_diag_fail(diag, "%s: line %lu: %s index 0 (OBJ indices start at 1, or -1 for the last)",
                     where, line, what);
        return -1;
    }
    if (idx < 0 && (uint64_t)(-(idx + 1)) >= have) {
        lt_diag_fail(diag, "%s: line %lu: relative %s index %lld but only %llu defined so far",
                     where, line, what, idx, (unsigned long long)have);
        return -1;
    }
    /* assimp takes an index to one defined before the face (a later one throws inside its OBJ
     * reader, which leaks what it had built) */
    if (idx > 0 && (uint64_t)idx > have) {
        lt_diag_fail(diag, "%s: line %lu: %s index %lld but the file defines %llu %s before "
                     "that line", where, line, what, idx, (unsigned long long)have, defined);
        return -1;
    }
    return 0;
}

/* 1 when [q, e) is a decimal number as assimp's OBJ reader counts and reads one: a digit or a
 * sign first (it counts only tokens that start so: ".5" would silently drop the whole vertex and
 * shift every later index), then digits with at most one '.', an optional exponent. strtod
 * accepts more (hex floats, "infinity"), which assimp would read as something else. */
static int obj_decimal(const char *q, const char *e)
{
    int digits = 0;
    if (q < e && (*q == '+' || *q == '-'))
        q++;
    else if (q >= e || *q < '0' || *q > '9')
        return 0;
    while (q < e && *q >= '0' && *q <= '9')
        q++, digits++;
    if (q < e && *q == '.') {
        q++;
        while (q < e && *q >= '0' && *q <= '9')
            q++, digits++;
    }
    if (digits == 0)
        return 0;
    if (q < e && (*q == 'e' || *q == 'E')) {
        q++;
        if (q < e && (*q == '+' || *q == '-'))
            q++;
        if (q >= e || *q < '0' || *q > '9')
            return 0;
        while (q < e && *q >= '0' && *q <= '9')
            q++;
    }
    return q == e;
}

/* The numbers of a v / vt / vn statement from q to the line's end p: each finite and within
 * float32 (the importer's format); their count into *n. what names the statement in messages. */
static int obj_numbers(const char *where, unsigned long line, const char *what, const char *q,
                       const char *p, int *n, double *last, lt_diag_t *diag)
{
    *n = 0;
    *last = 0.0;
    for (;;) {
        char *e;
        double d;
        while (q < p && is_blank(*q))
            q++;
        if (q >= p || is_eol(*q) || *q == '#')
            return 0;
        d = strtod(q, &e);
        if (e == q || (e < p && !is_blank(*e) && !is_eol(*e))) {
            lt_diag_fail(diag, "%s: line %lu: %s coordinate %d '%.*s' is not a number", where,
                         line, what, *n + 1, (int)(word_end(q, p) - q), q);
            return -1;
        }
        if (isfinite(d) && !obj_decimal(q, e)) {
            lt_diag_fail(diag, "%s: line %lu: %s coordinate %d '%.*s' is not a decimal number "
                         "the importer reads (a digit or sign first, e.g. 0.5 for .5)",
                         where, line, what, *n + 1, (int)(e - q), q);
            return -1;
        }
        if (!isfinite(d)) {
            lt_diag_fail(diag, "%s: line %lu: %s coordinate %d '%.*s' is not finite", where, line,
                         what, *n + 1, (int)(e - q), q);
            return -1;
        }
        if (fabs(d) > (double)FLT_MAX) {
            lt_diag_fail(diag, "%s: line %lu: %s coordinate %d '%.*s' overflows float32, the "
                         "importer's vertex format (|x| <= 3.4e38)",
                         where, line, what, *n + 1, (int)(e - q), q);
            return -1;
        }
        (*n)++;
        *last = d;
        q = e;
    }
}

/* Check OBJ text (NUL-terminated at len). where names the file in messages. Statements are told
 * apart as assimp 5.2.5's OBJ reader tells them: by their first letters, so that "vtx" is a
 * texture coordinate and "fo" or "lod" a face or a line to it; l and p statements are left out
 * before import (obj_for_assimp: lanetrace keeps triangles). */
static int check_obj(const char *where, const char *buf, size_t len, lt_diag_t *diag)
{
    /* a face vertex's three indices: v, vt, vn */
    static const char *const kind_name[3] = {"vertex", "texture", "normal"};
    static const char *const kind_defined[3] = {"vertices", "(vt lines)", "(vn lines)"};
    const char *nul = (const char *)memchr(buf, '\0', len);
    const char *p = buf, *end = buf + len;
    unsigned long line = 0;
    uint64_t nv = 0, nvt = 0, nvn = 0, nf = 0, poly2 = 0;

    if (nul != NULL) {
        unsigned long l = 1;
        const char *q;
        for (q = buf; q < nul; q++)
            l += *q == '\n';
        lt_diag_fail(diag, "%s: line %lu: NUL byte at offset %zu: binary data, not OBJ text", where,
                     l, (size_t)(nul - buf));
        return -1;
    }
    while (p < end) {
        const char *ls = p, *q;
        line++;
        while (p < end && *p != '\n')
            p++;
        /* [ls, p) is the line; p is at '\n' or the end; buffer is NUL-terminated at end */
        q = ls;
        while (q < p && is_blank(*q))
            q++;
        if (q < p && *q != '#') {
            const char *c;
            for (c = q; c < p; c++)
                if ((unsigned char)*c < 0x20 && !is_blank(*c) && *c != '\r') {
                    lt_diag_fail(diag, "%s: line %lu: control byte 0x%02x: binary data, not OBJ "
                                 "text", where, line, (unsigned)(unsigned char)*c);
                    return -1;
                }
        }
        if (q < p && q[0] == 'v' && (is_blank(q[1]) || is_eol(q[1]))) {
            int n;
            double w;
            if (obj_numbers(where, line, "vertex", q + 1, p, &n, &w, diag) != 0)
                return -1;
            if (n < 3) {
                lt_diag_fail(diag, "%s: line %lu: vertex has %d coordinate%s (need 3; truncated "
                             "file?)", where, line, n, n == 1 ? "" : "s");
                return -1;
            }
            /* x y z, x y z w (assimp divides by w) or x y z r g b; anything else assimp refuses
             * by throwing, and leaks what it had built */
            if (n != 3 && n != 4 && n != 6) {
                lt_diag_fail(diag, "%s: line %lu: vertex has %d numbers (OBJ: x y z, x y z w or x "
                             "y z r g b)", where, line, n);
                return -1;
            }
            if (n == 4 && w == 0.0) {
                lt_diag_fail(diag, "%s: line %lu: vertex has w = 0 (a point at infinity)", where,
                             line);
                return -1;
            }
            nv++;
        } else if (q < p && q[0] == 'v' && (q[1] == 't' || q[1] == 'n')) {
            /* assimp reads any "vt..." / "vn..." as a texture coordinate (2 or 3 numbers) / a
             * normal (3), and a failed read there throws and leaks what it had built */
            const char *w = word_end(q, p), *kind = q[1] == 't' ? "texture" : "normal";
            int n, lo = q[1] == 't' ? 2 : 3;
            double last;
            if (w - q != 2) {
                lt_diag_fail(diag, "%s: line %lu: '%.*s' is not an OBJ statement (assimp would "
                             "read it as '%.2s')", where, line, (int)(w - q), q, q);
                return -1;
            }
            if (obj_numbers(where, line, kind, w, p, &n, &last, diag) != 0)
                return -1;
            if (n < lo || n > 3) {
                lt_diag_fail(diag, "%s: line %lu: %s has %d coordinate%s (need %s)", where, line,
                             q[1] == 't' ? "texture coordinate" : "normal", n, n == 1 ? "" : "s",
                             q[1] == 't' ? "2 or 3" : "3");
                return -1;
            }
            if (q[1] == 't')
                nvt++;
            else
                nvn++;
        } else if (q < p && q[0] == 'f' && !is_blank(q[1]) && !is_eol(q[1])) {
            lt_diag_fail(diag, "%s: line %lu: '%.*s' is not an OBJ statement lanetrace reads "
                         "(assimp would read it as a face 'f')", where, line,
                         (int)(word_end(q, p) - q), q);
            return -1;
        } else if (q < p && q[0] == 'f') {
            int n = 0;
            q++;
            for (;;) {
                char *e;
                long long idx;
                int part;
                while (q < p && is_blank(*q))
                    q++;
                if (q >= p || is_eol(*q))
                    break;
                if (*q == '#') {
                    lt_diag_fail(diag, "%s: line %lu: comment after face vertices (assimp's OBJ "
                                 "reader rejects it)", where, line);
                    return -1;
                }
                /* v, v/t, v//n, v/t/n */
                for (part = 0; part < 3; part++) {
                    if (part > 0) {
                        if (*q != '/')
                            break;
                        q++;
                        if (*q == '/' || is_blank(*q) || is_eol(*q))
                            continue; /* empty texture (or trailing) index */
                    }
                    errno = 0;
                    idx = strtoll(q, &e, 10);
                    if (e == q || (e < p && *e != '/' && !is_blank(*e) && !is_eol(*e))) {
                        lt_diag_fail(diag, "%s: line %lu: face vertex %d: '%.*s' is not an index",
                                     where, line, n + 1, (int)(word_end(q, p) - q), q);
                        return -1;
                    }
                    if (check_index(idx, part == 0 ? nv : part == 1 ? nvt : nvn, line,
                                    kind_name[part], kind_defined[part], where, diag) != 0)
                        return -1;
                    q = e;
                }
                if (q < p && !is_blank(*q) && !is_eol(*q)) {
                    lt_diag_fail(diag, "%s: line %lu: face vertex %d: unexpected '%c'", where,
                                 line, n + 1, *q);
                    return -1;
                }
                n++;
            }
            if (n < 3) {
                lt_diag_fail(diag, "%s: line %lu: face has %d vert%s (need 3; truncated file?)",
                             where, line, n, n == 1 ? "ex" : "ices");
                return -1;
            }
            /* assimp triangulates a polygon in time quadratic in its vertices, in this process
             * (no time limit): 60,000 took 6 s here, so a small file could hang the tool */
            if (n > LT_MESH_MAX_FACE_VERTS) {
                lt_diag_fail(diag, "%s: line %lu: face has %d vertices, more than "
                             "LT_MESH_MAX_FACE_VERTS %d (split the polygon)", where, line, n,
                             LT_MESH_MAX_FACE_VERTS);
                return -1;
            }
            poly2 += (uint64_t)n * (uint64_t)n;
            if (poly2 > LT_MESH_MAX_POLY_WORK) {
                lt_diag_fail(diag, "%s: line %lu: the polygons up to here have a sum of squared "
                             "vertex counts above LT_MESH_MAX_POLY_WORK %llu (triangulating them "
                             "would take minutes; split the large polygons)", where, line,
                             (unsigned long long)LT_MESH_MAX_POLY_WORK);
                return -1;
            }
            nf++;
        }
        p++; /* past '\n' */
    }
    if (nf == 0) {
        lt_diag_fail(diag, "%s: no faces ('f' lines) in %lu lines, %llu vertices (empty or "
                     "truncated OBJ?)", where, line, (unsigned long long)nv);
        return -1;
    }
    return 0;
}

/* What ends a line for assimp (its IsLineEnd) that does not for the check: a CR not followed by
 * LF (classic Mac line ends, or a stray CR inside a line: "g a\rl 3 7 6" is a group and then a
 * line statement to it, which threw inside its reader and leaked; mesh fuzz target,
 * regress-bare-cr-leak), a form feed ("g a\f\ff 1 x" is a group and then a face that threw and
 * leaked; regress-formfeed-leak) and a NUL inside the text. Each becomes an LF, in place, so that
 * the check sees the lines assimp will read. CRLF stays as it is. */
static void obj_line_ends(char *buf, size_t len)
{
    size_t i;
    for (i = 0; i < len; i++)
        if ((buf[i] == '\r' && buf[i + 1] != '\n') || buf[i] == '\f' || buf[i] == '\0')
            buf[i] = '\n'; /* buf[len] is the NUL */
}

/* The checked OBJ text as assimp gets it, in place:
 * - The blanks that start lines are removed: assimp 5.2.5's OBJ reader silently skips a statement
 *   with leading blanks (" v 1 2 3" shifts every later index; "\tf 1 2 3" drops a face), although
 *   they are legal OBJ.
 * - Lines that start with 'l' or 'p' become comments: assimp reads every one as a line or point
 *   statement ("lod 1" too), throws on what it cannot read and leaks what it had built (found by
 *   the mesh fuzz target under LeakSanitizer); lanetrace keeps triangles only.
 * - `mtllib` statements become comments. lanetrace keeps geometry only, and from memory assimp
 *   does not find the named material file: it then parses its fallback, the OBJ's own name with
 *   .mtl, which the memory reader answers with the OBJ text itself. Its material reader, given
 *   OBJ lines, writes through a null current material on a texture statement before any
 *   `newmtl` ("map_Pm -1": SEGV; found by the mesh fuzz target, tests/fuzz/corpus/mesh/
 *   regress-mtllib-self).
 * Returns the new length (the buffer stays NUL-terminated). */
static size_t obj_for_assimp(char *buf, size_t len)
{
    size_t r = 0, w = 0;
    int line_start = 1;
    for (r = 0; r < len; r++) {
        char c = buf[r];
        if (line_start && is_blank(c))
            continue;
        if (line_start && len - r >= 6 && memcmp(buf + r, "mtllib", 6) == 0 &&
            (is_blank(buf[r + 6]) || is_eol(buf[r + 6]))) /* buf[len] is the NUL */
            c = '#';
        if (line_start && (c == 'l' || c == 'p'))
            c = '#';
        line_start = c == '\n';
        buf[w++] = c;
    }
    buf[w] = '\0';
    return w;
}

/* ---- assimp scene -> triangles --------------------------------------------------------------- */

static int scene_to_mesh(const struct aiScene *sc, const char *path, lt_mesh_t *m, lt_diag_t *diag)
{
    unsigned i, f, j, a;
    uint64_t n = 0;
    uint32_t t = 0;

    for (i = 0; i < sc->mNumMeshes; i++)
        for (f = 0; f < sc->mMeshes[i]->mNumFaces; f++)
            n += sc->mMeshes[i]->mFaces[f].mNumIndices == 3;
    if (n == 0 || n > LT_MESH_MAX_TRIS) {
        lt_diag_fail(diag, "%s: %llu triangles (need 1..%u)", path, (unsigned long long)n,
                     LT_MESH_MAX_TRIS);
        return -1;
    }
    m->v = (double *)malloc((size_t)n * 9 * sizeof(double));
    if (m->v == NULL) {
        lt_diag_fail(diag, "%s: out of memory for %llu triangles", path, (unsigned long long)n);
        return -1;
    }
    for (a = 0; a < 3; a++) {
        m->lo[a] = HUGE_VAL;
        m->hi[a] = -HUGE_VAL;
    }
    for (i = 0; i < sc->mNumMeshes; i++) {
        const struct aiMesh *me = sc->mMeshes[i];
        for (f = 0; f < me->mNumFaces; f++) {
            const struct aiFace *fa = &me->mFaces[f];
            if (fa->mNumIndices != 3)
                continue;
            for (j = 0; j < 3; j++) {
                const struct aiVector3D *p;
                if (fa->mIndices[j] >= me->mNumVertices) {
                    lt_diag_fail(diag, "%s: mesh %u face %u: vertex index %u >= %u vertices", path,
                                 i, f, fa->mIndices[j], me->mNumVertices);
                    lt_mesh_free(m);
                    return -1;
                }
                p = &me->mVertices[fa->mIndices[j]];
                if (!isfinite(p->x) || !isfinite(p->y) || !isfinite(p->z)) {
                    lt_diag_fail(diag, "%s: mesh %u face %u: vertex %u is not finite after "
                                 "import (NaN, or beyond float32's 3.4e38, the importer's vertex "
                                 "format)", path, i, f, fa->mIndices[j]);
                    lt_mesh_free(m);
                    return -1;
                }
                m->v[t * 9 + j * 3 + 0] = p->x;
                m->v[t * 9 + j * 3 + 1] = p->y;
                m->v[t * 9 + j * 3 + 2] = p->z;
                for (a = 0; a < 3; a++) {
                    double c = m->v[t * 9 + j * 3 + a];
                    if (c < m->lo[a])
                        m->lo[a] = c;
                    if (c > m->hi[a])
                        m->hi[a] = c;
                }
            }
            t++;
        }
    }
    m->ntris = t;
    return 0;
}

int lt_mesh_load(const char *path, lt_mesh_t *m, lt_diag_t *diag)
{
    const struct aiScene *sc = NULL;
    char *raw = NULL, *text = NULL;
    size_t rawlen = 0, textlen = 0;
    char hint[16] = "";
    int gz, obj, rc = -1;

    memset(m, 0, sizeof *m);
    gz = ends_with(path, ".gz");
    obj = ends_with(path, gz ? ".obj.gz" : ".obj");
    if (gz) {
        /* the format hint is the extension inside: "x.obj.gz" -> "obj" */
        size_t n = strlen(path) - 3, k = n;
        while (k > 0 && path[k - 1] != '.' && path[k - 1] != '/')
            k--;
        if (k == 0 || path[k - 1] != '.' || n - k < 1 || n - k >= sizeof hint) {
            lt_diag_fail(diag, "%s: cannot tell the format inside the gzip file: name it "
                         "<name>.<ext>.gz (e.g. scene.obj.gz)", path);
            return -1;
        }
        memcpy(hint, path + k, n - k);
        hint[n - k] = '\0';
    }
    if (gz || obj) {
        if (lt_mesh_read_file(path, &raw, &rawlen, diag) != 0)
            return -1;
        if (rawlen == 0) {
            lt_diag_fail(diag, "%s: empty file (0 bytes)", path);
            goto done;
        }
        if (gz) {
            if (gunzip(path, (const unsigned char *)raw, rawlen, &text, &textlen, diag) != 0)
                goto done;
            free(raw);
            raw = NULL;
            if (textlen == 0) {
                lt_diag_fail(diag, "%s: empty after gunzip", path);
                goto done;
            }
        } else {
            text = raw;
            textlen = rawlen;
            raw = NULL;
        }
        if (obj) {
            obj_line_ends(text, textlen);
            if (check_obj(path, text, textlen, diag) != 0)
                goto done;
            textlen = obj_for_assimp(text, textlen);
            (void)snprintf(hint, sizeof hint, "obj");
        }
    } else {
        FILE *probe;
        /* before opening it: a FIFO without a writer would block the open (and the importer's
         * child) for ever, and a device such as /dev/zero reads as "empty" through ftell */
        if (lt_diag_not_regular(path) != NULL) {
            lt_diag_fail(diag, "%s: %s, not a regular file", path, lt_diag_not_regular(path));
            return -1;
        }
        probe = fopen(path, "rb");
        if (probe == NULL) {
            lt_diag_fail(diag, "%s: cannot open the mesh file: %s", path, strerror(errno));
            return -1;
        }
        if (fseek(probe, 0, SEEK_END) == 0 && ftell(probe) == 0) {
            (void)fclose(probe);
            lt_diag_fail(diag, "%s: empty file (0 bytes)", path);
            return -1;
        }
        (void)fclose(probe);
    }
    if (!obj) {
        /* every other format in a child process (lt_import.c): PLY, OFF and STL checked first
         * (lt_meshcheck.c); the rest from the path, so that assimp finds the files they refer
         * to (.bin), or the unpacked .gz from memory */
        rc = lt_import_mesh(path, text, textlen, hint, IMPORT_FLAGS, scene_to_mesh, m, diag);
        goto done;
    }
    /* OBJ (checked, blanks stripped, no material library: obj_for_assimp; plain or unpacked
     * from .gz): in process, from memory. */
    sc = aiImportFileFromMemory(text, (unsigned)textlen, IMPORT_FLAGS, hint);
    if (sc == NULL || sc->mNumMeshes == 0) {
        lt_diag_fail(diag, "%s: not a readable mesh (assimp: %s)", path,
                     sc == NULL ? aiGetErrorString() : "no meshes in the scene");
        goto done;
    }
    rc = scene_to_mesh(sc, path, m, diag);
done:
    if (sc != NULL)
        aiReleaseImport(sc);
    free(raw);
    free(text);
    return rc;
}

void lt_mesh_free(lt_mesh_t *m)
{
    free(m->v);
    m->v = NULL;
    m->ntris = 0;
}
