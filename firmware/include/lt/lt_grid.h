/* lt_grid.h - uniform grid over triangles (Stamminger & Grosso 2020 [Stamminger20], "Uniform Grid";
 * Amanatides & Woo 1987 [Amanatides87], as in Bikker 2016 [Bikker16]): resolution from the triangle
 * count, per-cell triangle lists built in two passes (count, fill) into caller memory sized exactly
 * by lt_grid_size, and 16-ray packet traversal by per-lane 3D-DDA with a per-packet mailbox. s15.16
 * and float32 from one kernel source (firmware/core/object/lt_grid.inc).
 * Builds: all; float32 entry points only with LT_CFG_FLOAT32. Layout and numbers: docs/kdtree-grid.md.
 */
#ifndef LT_GRID_H
#define LT_GRID_H

#include "lt_isect.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Limits: cells per axis; triangles (ids must stay below the mailbox's empty marker and the
 * reference counts inside uint32); mailbox slots per packet (LT_GRID_MAILBOX x 8 bytes on the C
 * stack of each trace call). */
#define LT_GRID_MAX_RES 1024u
#define LT_GRID_MAX_TRIS (1u << 24)
#define LT_GRID_MAILBOX 64u

/* Build parameters. */
typedef struct lt_grid_params {
    uint32_t cells_per_tri_q4; /* target cell count = n x this / 16 (lambda in 1/16 steps),
                                  1..1024; default 48 (lambda = 3) */
} lt_grid_params_t;

/* A built grid (caller-allocated; read-only after the build). Cell (x, y, z) has linear index
 * x + res[0] * (y + res[1] * z) and holds refs[cells[i] .. cells[i + 1]), sorted by triangle id. */
typedef struct lt_grid_q16 {
    const uint32_t *cells;     /* ncells + 1 offsets into refs (prefix sums), in the arena */
    const uint32_t *refs;      /* triangle indices, after cells in the arena */
    const lt_tri_q16_t *tris;  /* the caller's triangles: must outlive the grid, unchanged */
    uint32_t ntris, ncells, nrefs;
    uint32_t res[3];           /* cells per axis, 1..LT_GRID_MAX_RES */
    lt_q16_t cell[3];          /* cell size per axis, s15.16 raw >= 1 */
    lt_aabb_q16_t bounds;      /* lo = scene minimum; hi = lo + res x cell >= scene maximum */
    size_t bytes;              /* (ncells + 1 + nrefs) x 4: exactly what lt_grid_size reported */
    uint32_t isect;            /* intersector of its walks: LT_ISECT_WT (set by the build) or
                                  LT_ISECT_MT (set after the build; lt_isect.h) */
} lt_grid_q16_t;

/* The default parameters above. */
void lt_grid_params_default(lt_grid_params_t *p);

/* Exact arena bytes for the grid of these triangles: (cells + 1 + references) x 4, where a
 * triangle is referenced by every cell its bounding box touches (a box ending exactly on a cell
 * boundary touches both cells). One pass over the triangles, no memory. p may be NULL.
 * Cost: BUILD phase, GRID_BUILD_BOUNDS_TRI and GRID_TRANGE per triangle, GRID_RES_STEP per step of
 * the resolution's bisection (about log2 LT_GRID_MAX_RES). Returns: LT_OK, LT_E_ARG (NULL, bad
 * parameter),
 * LT_E_RANGE (a vertex outside the geometry range, n > LT_GRID_MAX_TRIS, references beyond
 * uint32 or bytes beyond size_t). */
lt_status_t lt_grid_size_q16(const lt_tri_q16_t *tris, uint32_t n, const lt_grid_params_t *p,
                             size_t *bytes);

/* Build the grid into mem (4-byte aligned, *bytes long): count pass, prefix sums, fill pass.
 * Resolution: per axis floor(m x extent / largest extent) (at least 1) for the largest m whose
 * cell count stays <= lambda x n; cell sizes are rounded up to whole s15.16 steps so all cells of
 * an axis are equal and cell boundaries are exact. Nothing past the reported size is written.
 * Format: s15.16. Rounding: cell size up (the grid box grows by < res s15.16 steps). Overflow: none.
 * Cost: BUILD phase, lt_grid_size_q16's and per triangle 2 GRID_TRANGE (count and fill passes), per
 * (triangle, cell) GRID_BUILD_COUNT_REF and GRID_BUILD_FILL_REF, per cell GRID_BUILD_PREFIX x2.
 * Returns: LT_OK, LT_E_ARG, LT_E_RANGE (as lt_grid_size_q16), LT_E_SPACE (*bytes
 * too small: the exact size is written back). On LT_OK *bytes = grid->bytes. */
lt_status_t lt_grid_build_q16(lt_grid_q16_t *g, const lt_tri_q16_t *tris, uint32_t n,
                              const lt_grid_params_t *p, void *mem, size_t *bytes);

/* Closest hit of the lanes in k by per-lane 3D-DDA. hit->id is reset to -1 on all lanes; lanes
 * that hit get the triangle index and r->tmax = its distance. Each lane walks its own cells; lanes
 * in the same cell test its triangles together; a lane stops once its closest hit lies inside the
 * current cell (t <= cell exit). Mailbox: per packet, LT_GRID_MAILBOX direct-mapped slots of
 * (triangle id, lanes that tested it); an evicted slot costs a repeated test, never a wrong result.
 * Format: boundary t = (boundary - o) x (1/d), s15.16 half up, recomputed from the exact boundary
 * at every step (no accumulated tDelta drift); saturated-reciprocal lanes divide exactly; parallel
 * lanes never step on that axis. Range: rays from lt_ray16_q16_setup, tmax < LT_Q16_MAX; any
 * origin, inside or outside the grid. Rounding: a hit within the plane rounding bound of a cell boundary
 * may be passed over for one equally close (docs/kdtree-grid.md). Overflow: none. Steps per lane
 * <= res[0] + res[1] + res[2] (a hard bound, also for degenerate rays). Cost: NODES per cell visited
 * by a lane group (TRAVERSE), the grid's intersector per tested reference (INTERSECT:
 * lt_tri16_wt_q16 with lt_ray16_wt_setup_q16 before the first, or lt_tri16_q16), LT_MEM per cell; the
 * GRID_WALK_* and GRID_MAILBOX_CLEAR recipes, GRID_LIN, GRID_OUTSIDE and the GRID_Q_* cell
 * routines with their lane ops (not checked by tests/unit/test_costs.c).
 * Returns: the mask of lanes that hit. */
lt_mask16_t lt_grid_trace16_q16(const lt_grid_q16_t *g, lt_ray16_q16_t *r, lt_mask16_t k,
                                lt_hit16_t *hit);

/* Any hit with tmin < t < tmax (shadow rays); r->tmax of occluded lanes is shortened to that hit.
 * Returns: the mask of occluded lanes. */
lt_mask16_t lt_grid_occluded16_q16(const lt_grid_q16_t *g, lt_ray16_q16_t *r, lt_mask16_t k);

#if LT_CFG_FLOAT32
typedef struct lt_grid_f32 {
    const uint32_t *cells;
    const uint32_t *refs;
    const lt_tri_f32_t *tris;
    uint32_t ntris, ncells, nrefs;
    uint32_t res[3];
    float cell[3];             /* cell size per axis (> 0); boundary j is lo + (float)j x cell */
    lt_aabb_f32_t bounds;
    size_t bytes;
    uint32_t isect; /* as lt_grid_q16_t */
} lt_grid_f32_t;

/* The float32 twins: same contracts; vertices must be finite with |x| <= 1e30 (else LT_E_RANGE). */
lt_status_t lt_grid_size_f32(const lt_tri_f32_t *tris, uint32_t n, const lt_grid_params_t *p,
                             size_t *bytes);
lt_status_t lt_grid_build_f32(lt_grid_f32_t *g, const lt_tri_f32_t *tris, uint32_t n,
                              const lt_grid_params_t *p, void *mem, size_t *bytes);
lt_mask16_t lt_grid_trace16_f32(const lt_grid_f32_t *g, lt_ray16_f32_t *r, lt_mask16_t k,
                                lt_hit16_t *hit);
lt_mask16_t lt_grid_occluded16_f32(const lt_grid_f32_t *g, lt_ray16_f32_t *r, lt_mask16_t k);
#endif

#ifdef __cplusplus
}
#endif
#endif /* LT_GRID_H */
