/* lt_mesh.h - triangle meshes loaded on the host through assimp's C API, in double precision;
 * gzip'd files (<name>.<ext>.gz) are unpacked in memory with zlib first, and OBJ text is checked
 * line by line before assimp sees it; other formats go through io/lt_import (checks, a child
 * process). Host only; see docs/io.md.
 */
#ifndef LT_MESH_H
#define LT_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "io/lt_diag.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Upper bound of triangles a mesh may have (the core indexes triangles with int32). */
#define LT_MESH_MAX_TRIS 16000000u
/* Largest mesh file read into memory (OBJ text, a .gz file, or what a .gz unpacks to): 1 GiB. */
#define LT_MESH_MAX_BYTES (1024u * 1024u * 1024u)
/* OBJ polygons: assimp's triangulation takes time quadratic in a polygon's vertices (measured
 * here: 60,000 vertices of one repeated triangle 6 s, a convex disc of 40,000 12 s). At most this
 * many per face, and a sum of squared counts over all faces at most LT_MESH_MAX_POLY_WORK (at
 * most ~8 s of triangulation at the disc's rate; ordinary meshes add 9 or 16 per face). */
#define LT_MESH_MAX_FACE_VERTS 4096
#define LT_MESH_MAX_POLY_WORK 1000000000ull

typedef struct lt_mesh {
    double *v;       /* 9 doubles per triangle: v0 v1 v2, file units */
    uint32_t ntris;  /* triangles (faces with 3 indices after triangulation) */
    double lo[3];    /* bounds, file units */
    double hi[3];
} lt_mesh_t;

/* Load every triangle of every mesh in the file (OBJ with quads and negative indices, PLY, OFF,
 * glTF...) via assimp, triangulated, with node transforms applied. Zero-area triangles are kept.
 * "<name>.<ext>.gz" is gunzipped in memory (zlib; several gzip members allowed) and imported with
 * <ext> as the format hint. OBJ text (plain or gzip'd) is checked first: NUL or control bytes
 * (binary data), a "v" line with fewer than 3 numbers or a non-finite one, a face with fewer
 * than 3 vertices, index 0, or a v/vt/vn index outside the vertices defined (negative indices:
 * relative to those defined so far), a face of more than LT_MESH_MAX_FACE_VERTS vertices or
 * polygons past LT_MESH_MAX_POLY_WORK are errors naming the line.
 * Every other format is imported in a child process (io/lt_import.h): PLY, OFF and STL are
 * checked first (io/lt_meshcheck.h: counts against the file size, complete elements and faces),
 * and a crash or hang inside assimp becomes an error (time limit LT_IMPORT_TIMEOUT, 120 s).
 * Returns 0, or -1 with a message naming the file and the problem (unreadable, empty, corrupt or
 * truncated gzip stream, an OBJ line as above, a PLY/OFF/STL element or count, assimp's own
 * error text, an importer crash or time-out, no triangles, a non-finite vertex, an out-of-range
 * index, more than LT_MESH_MAX_TRIS triangles or more than LT_MESH_MAX_BYTES bytes). */
int lt_mesh_load(const char *path, lt_mesh_t *m, lt_diag_t *diag);

void lt_mesh_free(lt_mesh_t *m);

/* The whole file (a regular file of at most LT_MESH_MAX_BYTES) into a malloc'ed buffer with a NUL
 * after its *len bytes. Returns 0, or -1 with a message naming the file (cannot open, not a
 * regular file, too large, out of memory, read error). */
int lt_mesh_read_file(const char *path, char **buf, size_t *len, lt_diag_t *diag);

#ifdef __cplusplus
}
#endif

#endif /* LT_MESH_H */
