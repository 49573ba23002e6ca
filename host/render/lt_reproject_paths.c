/* lt_reproject_paths.c - the screen-space operations of each numeric path (lt_rp_ops_t,
 * lt_path_ops.h): lt_reproject_path.inc instantiated once per ray format (s1.30, float32), one
 * table per quadtree node encoding (n64 and n32 share the s1.30 rays). Adding a path: its
 * lt_path_<suffix>.h, the lines here, its entry in lt_paths.c. Host only.
 */
#include "render/lt_path_ops.h"
#include "render/lt_qt_ref.h"

/* The plane nodes of a built quadtree, per node encoding. */
static uint64_t planes_n64(const void *arena, uint64_t nodes)
{
    const lt_qt_n64_t *n = arena;
    uint64_t i, k = 0;
    for (i = 0; i < nodes; i++)
        k += !LT_QT_N64_IS_AABB(n[i]);
    return k;
}

static uint64_t planes_n32(const void *arena, uint64_t nodes)
{
    const lt_qt_n32_t *n = arena;
    uint64_t i, k = 0;
    for (i = 0; i < nodes; i++)
        k += !LT_QT_N32_IS_AABB(n[i]);
    return k;
}

static uint64_t planes_nf32(const void *arena, uint64_t nodes)
{
    const lt_qt_nf32_t *n = arena;
    uint64_t i, k = 0;
    for (i = 0; i < nodes; i++)
        k += !LT_QT_NF32_IS_AABB(n[i]);
    return k;
}

/* s1.30: the 64- and 32-bit node encodings */
#include "render/lt_path_q30.h"
#include "render/lt_reproject_path.inc"
const lt_rp_ops_t lt_rp_ops_n64 = LT_RP_OPS(planes_n64);
const lt_rp_ops_t lt_rp_ops_n32 = LT_RP_OPS(planes_n32);
#include "render/lt_path_undef.h"

/* float32 */
#include "render/lt_path_f32.h"
#include "render/lt_reproject_path.inc"
const lt_rp_ops_t lt_rp_ops_f32 = LT_RP_OPS(planes_nf32);
#include "render/lt_path_undef.h"
