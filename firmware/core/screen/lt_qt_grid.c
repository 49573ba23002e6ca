/* lt_qt_grid.c - lane helpers of a screen-space level grid, shared by the quadtree (lt_qt.c) and
 * the Hi-Z pyramid (lt_hiz.c): both store level L of a layer as an nx[L] x ny[L] row-major grid
 * starting at off[L] (lt_qt.h, lt_hiz.h), so index and bounds test are one function each, defined
 * here once and declared in lt_qt_grid.h. Builds: all.
 */
#include "lt_qt_grid.h"

/* Index off[L] + qy nx[L] + qx per lane in k (0 elsewhere; for Hi-Z level 0 is the pixels,
 * y W + x). The level tables (<= 15 entries) fit one register: two permutes, a multiply and two
 * adds. Format: int32 lanes, in range by the walk (LT_ASSERT: L < levels, qx < nx[L], qy < ny[L]).
 * Overflow: none (the index is below the arena's cell count). Cost: VALU x4, VMUL x1. */
lt_vi32_t lt__qtgrid_index(const uint32_t *off, const uint32_t *nx, const uint32_t *ny,
                           uint32_t levels, lt_mask16_t k, lt_vi32_t lvl, lt_vi32_t qx,
                           lt_vi32_t qy)
{
    lt_vi32_t r;
    int i;
    LT_COST(VALU, 4);
    LT_COST(VMUL, 1);
    LT_UTIL(k);
    (void)ny;
    (void)levels;
    for (i = 0; i < LT_LANES; i++) {
        r.l[i] = 0;
        if (LT__ON(k, i)) {
            uint32_t L = (uint32_t)lvl.l[i];
            LT_ASSERT(L < levels && (uint32_t)qx.l[i] < nx[L] && (uint32_t)qy.l[i] < ny[L]);
            r.l[i] = (int32_t)(off[L] + (uint32_t)qy.l[i] * nx[L] + (uint32_t)qx.l[i]);
        }
    }
    return r;
}

/* Lanes in k whose node / cell (L, qx, qy) lies outside the level's grid (qx or qy negative, or
 * >= nx[L], ny[L]). Cost: VALU x2, VCMP x4. */
lt_mask16_t lt__qtgrid_outside(const uint32_t *nx, const uint32_t *ny, lt_mask16_t k,
                               lt_vi32_t lvl, lt_vi32_t qx, lt_vi32_t qy)
{
    unsigned m = 0;
    int i;
    LT_COST(VALU, 2);
    LT_COST(VCMP, 4);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        if (LT__ON(k, i)) {
            uint32_t L = (uint32_t)lvl.l[i];
            if (qx.l[i] < 0 || qy.l[i] < 0 || (uint32_t)qx.l[i] >= nx[L] ||
                (uint32_t)qy.l[i] >= ny[L])
                m |= 1u << i;
        }
    }
    return (lt_mask16_t)m;
}
