/* lt_mesh.h - triangle meshes loaded on the host through assimp's C API, in double precision.
 * Host only.
 */
#ifndef LT_MESH_H
#define LT_MESH_H

#include <stddef.h>
#include <stdint.h>

/* Upper bound of triangles a mesh may have (the core indexes triangles with int32). */
#define LT_MESH_MAX_TRIS 16000000u

typedef struct lt_mesh {
    double *v;       /* 9 doubles per triangle: v0 v1 v2, file units */
    uint32_t ntris;  /* triangles (faces with 3 indices after triangulation) */
    double lo[3];    /* bounds, file units */
    double hi[3];
} lt_mesh_t;

/* Load every triangle of every mesh in the file (OBJ with quads and negative indices, PLY, OFF,
 * glTF...) via assimp, triangulated, with node transforms applied. Zero-area triangles are kept.
 * Returns 0, or -1 with a message naming the file and the problem (unreadable, no triangles,
 * a non-finite vertex, more than LT_MESH_MAX_TRIS triangles). */
int lt_mesh_load(const char *path, lt_mesh_t *m, char *err, size_t errlen);

void lt_mesh_free(lt_mesh_t *m);

#endif /* LT_MESH_H */
