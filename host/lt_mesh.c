/* lt_mesh.c - mesh loading through assimp's C API (Debian libassimp-dev). Host only. */
#include "lt_mesh.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int lt_mesh_load(const char *path, lt_mesh_t *m, char *err, size_t errlen)
{
    const struct aiScene *sc;
    unsigned i, f, j, a;
    uint64_t n = 0;
    uint32_t t = 0;
    FILE *probe;

    memset(m, 0, sizeof *m);
    probe = fopen(path, "rb");
    if (probe == NULL) {
        snprintf(err, errlen, "%s: cannot open the mesh file", path);
        return -1;
    }
    fclose(probe);
    sc = aiImportFile(path, aiProcess_Triangulate | aiProcess_PreTransformVertices);
    if (sc == NULL || sc->mNumMeshes == 0) {
        snprintf(err, errlen, "%s: not a readable mesh (assimp: %s)", path, aiGetErrorString());
        if (sc != NULL)
            aiReleaseImport(sc);
        return -1;
    }
    for (i = 0; i < sc->mNumMeshes; i++)
        for (f = 0; f < sc->mMeshes[i]->mNumFaces; f++)
            n += sc->mMeshes[i]->mFaces[f].mNumIndices == 3;
    if (n == 0 || n > LT_MESH_MAX_TRIS) {
        snprintf(err, errlen, "%s: %llu triangles (need 1..%u)", path, (unsigned long long)n,
                 LT_MESH_MAX_TRIS);
        aiReleaseImport(sc);
        return -1;
    }
    m->v = malloc((size_t)n * 9 * sizeof(double));
    if (m->v == NULL) {
        snprintf(err, errlen, "%s: out of memory for %llu triangles", path, (unsigned long long)n);
        aiReleaseImport(sc);
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
                    snprintf(err, errlen, "%s: mesh %u face %u: vertex index %u >= %u vertices", path,
                             i, f, fa->mIndices[j], me->mNumVertices);
                    aiReleaseImport(sc);
                    lt_mesh_free(m);
                    return -1;
                }
                p = &me->mVertices[fa->mIndices[j]];
                if (!isfinite(p->x) || !isfinite(p->y) || !isfinite(p->z)) {
                    snprintf(err, errlen, "%s: mesh %u face %u: vertex %u is not finite", path, i, f,
                             fa->mIndices[j]);
                    aiReleaseImport(sc);
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
    aiReleaseImport(sc);
    return 0;
}

void lt_mesh_free(lt_mesh_t *m)
{
    free(m->v);
    m->v = NULL;
    m->ntris = 0;
}
