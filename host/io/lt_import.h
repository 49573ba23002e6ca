/* lt_import.h - mesh imports through assimp in a forked child process, so that no input can take
 * the program down: PLY, OFF and STL bytes are checked first (lt_meshcheck), the child imports,
 * checks and repairs the scene graph, post-processes and streams the triangles (or an error
 * message) back through a pipe; the parent reads with a bound and a time limit and reports a
 * child killed by a signal as a one-line error. Host only (POSIX fork, pipe, poll); docs/io.md.
 */
#ifndef LT_IMPORT_H
#define LT_IMPORT_H

#include <stddef.h>

#include "io/lt_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

struct aiScene;

/* Time limit of one import, in whole seconds; the environment variable overrides it (0 = none). */
#define LT_IMPORT_TIMEOUT_DEFAULT 120u
#define LT_IMPORT_TIMEOUT_ENV "LT_IMPORT_TIMEOUT"

/* Turns an imported, post-processed scene into triangles (lt_mesh.c's scene_to_mesh). Runs in the
 * child. Returns 0, or -1 with a message. */
typedef int (*lt_import_convert_fn)(const struct aiScene *sc, const char *path, lt_mesh_t *m,
                                    lt_diag_t *diag);

/* Import the mesh at path (data == NULL) or the len bytes at data (already read, e.g. unpacked
 * from a .gz; hint = the format's extension) through assimp with the post-processing `flags`, in
 * a child process. PLY, OFF and STL (by extension or hint; PLY also by its first bytes) are read
 * whole (at most LT_MESH_MAX_BYTES) and checked by lt_meshcheck first, then imported from those
 * bytes. Returns 0 with *m filled, or -1 with a one-line message naming the file: the check's,
 * assimp's own error text, a crash ("the importer (assimp) crashed (signal 6, SIGABRT) on this
 * file: <its last words>"), or the time limit. */
int lt_import_mesh(const char *path, const char *data, size_t len, const char *hint,
                   unsigned flags, lt_import_convert_fn conv, lt_mesh_t *m, lt_diag_t *diag);

/* The isolation alone: run fn(ctx, ...) in a forked child and bring back its mesh or its message.
 * path names the file in messages. Used by lt_import_mesh; the tests call it with functions that
 * crash, hang or lie. */
typedef int (*lt_import_child_fn)(void *ctx, lt_mesh_t *m, lt_diag_t *diag);
int lt_import_isolated(const char *path, lt_import_child_fn fn, void *ctx, lt_mesh_t *m, lt_diag_t *diag);

#ifdef __cplusplus
}
#endif

#endif /* LT_IMPORT_H */
