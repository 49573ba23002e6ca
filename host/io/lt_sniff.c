/* lt_sniff.c - a file's kind from its first bytes. Host only. */
#include "io/lt_sniff.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#define HEAD_MAX 512u

static int starts(const unsigned char *h, size_t n, const char *w)
{
    size_t k = strlen(w);
    return n >= k && memcmp(h, w, k) == 0;
}

static int ext_is(const char *name, const char *ext)
{
    size_t n = name != NULL ? strlen(name) : 0, k = strlen(ext), i;
    if (n <= k || name[n - k - 1] != '.')
        return 0;
    for (i = 0; i < k; i++)
        if (tolower((unsigned char)name[n - k + i]) != ext[i])
            return 0;
    return 1;
}

/* Text that looks like OBJ: its first non-blank, non-comment line starts with a known keyword. */
static int obj_like(const unsigned char *h, size_t n)
{
    static const char *const kw[] = {"v ", "vn ", "vt ", "f ", "o ", "g ", "s ", "usemtl ",
                                     "mtllib ", "v\t", "f\t", NULL};
    size_t i = 0;
    while (i < n) {
        int k;
        while (i < n && (h[i] == ' ' || h[i] == '\t' || h[i] == '\r' || h[i] == '\n'))
            i++;
        if (i < n && h[i] == '#') {
            while (i < n && h[i] != '\n')
                i++;
            continue;
        }
        for (k = 0; kw[k] != NULL; k++)
            if (starts(h + i, n - i, kw[k]))
                return 1;
        return 0;
    }
    return 0;
}

void lt_sniff_bytes(const unsigned char *h, size_t n, const char *name, lt_sniff_t *s)
{
    const char *w = NULL;
    memset(s, 0, sizeof *s);
    s->kind = LT_SNIFF_MESH;
    if (n >= 4 && h[0] == 0x76 && h[1] == 0x2f && h[2] == 0x31 && h[3] == 0x01) {
        s->kind = LT_SNIFF_EXR;
        w = "OpenEXR (magic bytes 76 2f 31 01)";
    } else if (n >= 2 && h[0] == 0x1f && h[1] == 0x8b) {
        w = "gzip-compressed (magic bytes 1f 8b; the format inside from the name)";
    } else if (starts(h, n, "ply\n") || starts(h, n, "ply\r\n")) {
        w = "PLY";
    } else if (starts(h, n, "OFF") || starts(h, n, "COFF") || starts(h, n, "NOFF")) {
        w = "OFF";
    } else if (starts(h, n, "glTF")) {
        w = "glTF binary (magic glTF)";
    } else if (starts(h, n, "solid") && !(n >= 84 && memchr(h, 0, n) != NULL)) {
        w = "STL (ascii)";
    } else if (n >= 84 && !obj_like(h, n) && (ext_is(name, "stl") || memchr(h, 0, n) != NULL)) {
        w = ext_is(name, "stl") ? "STL (binary)" : "binary data (no known magic bytes)";
    } else if (obj_like(h, n)) {
        w = "OBJ text";
    } else if (n >= 5 && (starts(h, n, "<?xml") || starts(h, n, "<COLLADA"))) {
        w = "XML (COLLADA or another XML format)";
    } else if (n >= 1 && (h[0] == '{' || h[0] == '[')) {
        w = "JSON-like text (glTF or another text format)";
    } else {
        w = "no known magic bytes (left to the mesh importer)";
    }
    snprintf(s->what, sizeof s->what, "%s", w);
    s->name_agrees = s->kind == LT_SNIFF_EXR ? ext_is(name, "exr") : !ext_is(name, "exr");
}

int lt_sniff_file(const char *path, lt_sniff_t *s, lt_diag_t *diag)
{
    unsigned char head[HEAD_MAX];
    struct stat st;
    size_t n;
    FILE *f;
    memset(s, 0, sizeof *s);
    if (stat(path, &st) != 0)
        return lt_diag_fail(diag, "%s: cannot open: %s", path, strerror(errno));
    if (S_ISDIR(st.st_mode))
        return lt_diag_fail(diag, "%s: is a directory, not a file", path);
    if (!S_ISREG(st.st_mode)) /* a FIFO without a writer would block the open */
        return lt_diag_fail(diag, "%s: %s, not a regular file", path, lt_diag_not_regular(path));
    f = fopen(path, "rb");
    if (f == NULL)
        return lt_diag_fail(diag, "%s: cannot open: %s", path, strerror(errno));
    n = fread(head, 1, sizeof head, f);
    if (ferror(f)) {
        (void)fclose(f);
        return lt_diag_fail(diag, "%s: cannot read", path);
    }
    (void)fclose(f);
    if (n == 0)
        return lt_diag_fail(diag, "%s: empty file (0 bytes)", path);
    lt_sniff_bytes(head, n, path, s);
    return 0;
}
