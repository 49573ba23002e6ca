/* lt_qt_grid.h - internal header of the screen-space level grid (lt_qt_grid.c): the node / cell
 * index and the outside-the-grid test that the quadtree (lt_qt.c) and the Hi-Z pyramid (lt_hiz.c)
 * share, both storing level L of a layer as an nx[L] x ny[L] row-major grid at off[L]. Not part
 * of the public API. Builds: all.
 */
#ifndef LT_QT_GRID_H
#define LT_QT_GRID_H

#include "lt/lt_v16.h"

/* Index off[L] + qy nx[L] + qx per lane in k (0 elsewhere; for Hi-Z level 0 is the pixels,
 * y W + x). Cost: VALU x4, VMUL x1. */
lt_vi32_t lt__qtgrid_index(const uint32_t *off, const uint32_t *nx, const uint32_t *ny,
                           uint32_t levels, lt_mask16_t k, lt_vi32_t lvl, lt_vi32_t qx,
                           lt_vi32_t qy);

/* Lanes in k whose node / cell (L, qx, qy) lies outside the level's grid. Cost: VALU x2,
 * VCMP x4. */
lt_mask16_t lt__qtgrid_outside(const uint32_t *nx, const uint32_t *ny, lt_mask16_t k,
                               lt_vi32_t lvl, lt_vi32_t qx, lt_vi32_t qy);

#endif /* LT_QT_GRID_H */
