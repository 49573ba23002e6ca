/* lt_meshcheck.h - structural checks of PLY (ascii, binary little and big endian), OFF and STL
 * (ascii, binary) file bytes before assimp sees them: element counts against the file size, every
 * element and face complete, indices in range, counts assimp can hold. Host only; docs/io.md.
 */
#ifndef LT_MESHCHECK_H
#define LT_MESHCHECK_H

#include <stddef.h>

#include "io/lt_diag.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum lt_meshcheck_kind {
    LT_MESHCHECK_NONE = 0, /* not a format checked here */
    LT_MESHCHECK_PLY,
    LT_MESHCHECK_OFF,
    LT_MESHCHECK_STL
} lt_meshcheck_kind_t;

/* Which check applies: by the extension (ext without the dot, any case: "ply", "off", "stl"), or,
 * for any extension, by the first bytes ("ply" and a line end: assimp finds PLY by content too).
 * head may be NULL (n = 0). */
lt_meshcheck_kind_t lt_meshcheck_kind(const char *ext, const unsigned char *head, size_t n);

/* The format's name as assimp's import hint ("ply", "off", "stl"), "" for NONE. */
const char *lt_meshcheck_hint(lt_meshcheck_kind_t kind);

/* Check the whole file's bytes (buf, len) as `kind`; `where` names the file in messages.
 * Returns 0, or -1 with a one-line message naming the file, the element and the limit, e.g.
 * "x.ply: header declares 4000000000 vertices; the file's 1234 bytes hold at most 102 (12 bytes
 * each)". Time and memory are bounded by len (one pass, a fixed-size table of the PLY header). */
int lt_meshcheck(lt_meshcheck_kind_t kind, const char *where, const unsigned char *buf, size_t len,
                 lt_diag_t *diag);

#ifdef __cplusplus
}
#endif

#endif /* LT_MESHCHECK_H */
