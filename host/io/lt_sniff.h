/* lt_sniff.h - what a file is, from its first bytes (not its name): an OpenEXR image or a mesh
 * format lanetrace reads. `lanetrace info` decides EXR vs mesh with it and says what it found.
 * Host only.
 */
#ifndef LT_SNIFF_H
#define LT_SNIFF_H

#include <stddef.h>

#include "io/lt_diag.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum lt_sniff_kind {
    LT_SNIFF_EXR = 1, /* OpenEXR: magic 76 2f 31 01 */
    LT_SNIFF_MESH     /* anything else: a mesh for lt_mesh_load (which checks it) */
} lt_sniff_kind_t;

typedef struct lt_sniff {
    lt_sniff_kind_t kind;
    char what[96]; /* "OpenEXR (magic bytes 76 2f 31 01)", "PLY (ascii)", "gzip (1f 8b)", ... */
    int name_agrees; /* the extension names the same kind (.exr for EXR, anything else a mesh) */
} lt_sniff_t;

/* Read up to the first 512 bytes of path and classify them. Returns 0, or -1 with a message
 * naming the file (cannot open, a directory, empty). */
int lt_sniff_file(const char *path, lt_sniff_t *s, lt_diag_t *diag);

/* The same for bytes in memory (head, n); never fails. name may be NULL (no extension check). */
void lt_sniff_bytes(const unsigned char *head, size_t n, const char *name, lt_sniff_t *s);

#ifdef __cplusplus
}
#endif
#endif /* LT_SNIFF_H */
