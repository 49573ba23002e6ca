/* fuzz_mesh.c - fuzz target of the in-process mesh readers (host/io/lt_mesh.c): gzip unpacking
 * (several members, truncation, trailing data, bombs up to the size limit), the OBJ text check and
 * assimp's OBJ importer on what passes it. Input starting 1f 8b is read as "in.obj.gz", anything
 * else as "in.obj" (never another format: those are imported in a child process, lt_import.c,
 * after the checks fuzzed by fuzz_meshcheck.c). Any bytes must give triangles within the limits
 * (finite vertices, bounds that hold them) or a one-line message naming the file. The input is
 * written to a file in /dev/shm (the loader takes a path). make fuzz-mesh; replayed over
 * tests/fuzz/corpus/mesh in make test. Host only.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"
#include "io/lt_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The loader's call, in one place (its error convention may change). */
static int load(const char *path, lt_mesh_t *m, char *err, size_t cap)
{
    lt_diag_t dg;
    int r = lt_mesh_load(path, m, &dg);
    fuzz_take_message(err, cap, r, &dg);
    return r;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    int gz = size >= 2 && data[0] == 0x1F && data[1] == 0x8B;
    const char *path = fuzz_file(data, size, gz ? "in.obj.gz" : "in.obj");
    char err[1024];
    lt_mesh_t m;
    uint32_t t;
    int a;

    memset(err, 'x', sizeof err);
    if (load(path, &m, err, sizeof err) != 0) {
        fuzz_check_message(err, sizeof err);
        if (m.v != NULL || m.ntris != 0)
            abort(); /* a failed load leaves nothing allocated */
        return 0;
    }
    if (m.ntris < 1 || m.ntris > LT_MESH_MAX_TRIS || m.v == NULL)
        abort();
    for (t = 0; t < m.ntris * 9u; t++) {
        a = (int)(t % 3u);
        if (!isfinite(m.v[t]) || m.v[t] < m.lo[a] || m.v[t] > m.hi[a])
            abort();
    }
    lt_mesh_free(&m);
    return 0;
}
