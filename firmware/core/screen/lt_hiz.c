/* lt_hiz.c - the hierarchical-Z screen-space tracer (Uludag, "Hi-Z Screen-Space Cone-Traced
 * Reflections", GPU Pro 5; AMD FidelityFX SSSR), a baseline for the screen-space quadtree
 * (lt_qt.c): pyramid layout and size query, the set-up checks, and the s1.30 and float32
 * instantiations of lt_hiz.inc (traits lt_ssb_q30.inc / lt_ssb_f32.inc plus the cell type and hole
 * test), which holds the cell codecs, build, walk and entry points. The ray helpers are
 * lt_ssb.c's (lt_ssb.h), shared with the DDA (lt_ssdda.c); the level-grid index and bounds test
 * are lt_qt_grid.c's (lt_qt_grid.h), shared with lt_qt.c. Formats and rules: lt_hiz.h, docs/ss-baselines.md.
 * Builds: all; float32 only with LT_CFG_FLOAT32.
 */
#include "lt/lt_hiz.h"
#include "lt_qt_grid.h"
#include "lt_ssb.h"

/* ---- layout ---------------------------------------------------------------------------------- */

/* Fill the level tables of hz from d and compute the arena size. */
static lt_status_t hiz_layout(const lt_ssb_desc_t *d, lt_hiz_t *hz, size_t *bytes)
{
    uint32_t n = 1, L, dim;
    uint64_t cells = 0, total;

    if (d == NULL || bytes == NULL)
        return LT_E_ARG;
    if (d->width == 0 || d->height == 0 || d->width > LT_SSB_MAX_DIM ||
        d->height > LT_SSB_MAX_DIM || d->layers == 0 || d->layers > LT_SSB_MAX_LAYERS)
        return LT_E_ARG;
    if (d->enc != LT_SSB_Q30 && !(LT_CFG_FLOAT32 && d->enc == LT_SSB_F32))
        return LT_E_ARG;
    dim = d->width > d->height ? d->width : d->height;
    while ((1u << (n - 1u)) < dim)
        n++;
    hz->width = d->width;
    hz->height = d->height;
    hz->layers = d->layers;
    hz->enc = d->enc;
    hz->levels = n;
    for (L = 0; L < LT_HIZ_MAX_LEVELS; L++) {
        hz->nx[L] = L < n ? (d->width + (1u << L) - 1u) >> L : 0u;
        hz->ny[L] = L < n ? (d->height + (1u << L) - 1u) >> L : 0u;
        hz->off[L] = (uint32_t)cells;
        if (L >= 1u && L < n)
            cells += (uint64_t)hz->nx[L] * hz->ny[L];
    }
    hz->layer_cells = (uint32_t)cells;
    /* both cell types are 8 bytes */
    total = cells * d->layers * sizeof(lt_hiz_cell_q30_t);
    if (total > (uint64_t)SIZE_MAX)
        return LT_E_RANGE;
    *bytes = (size_t)total;
    return LT_OK;
}

lt_status_t lt_hiz_size(const lt_ssb_desc_t *d, size_t *bytes)
{
    lt_hiz_t hz;
    return hiz_layout(d, &hz, bytes);
}

uint32_t lt_hiz_default_steps(const lt_hiz_t *hz)
{
    return 8u * (hz->width + hz->height) + 4u * hz->levels + 16u;
}

/* Common checks of the build entry points: layout, parameters, space, arena. */
static lt_status_t hiz_prepare(lt_hiz_t *hz, const lt_ssb_desc_t *d, const lt_ssb_params_t *p,
                               const void *w, void *arena, size_t *arena_bytes, uint32_t enc)
{
    size_t need;
    lt_status_t s;
    lt_ssb_params_t dp;
    if (hz == NULL || w == NULL || arena_bytes == NULL || d == NULL || d->enc != enc)
        return LT_E_ARG;
    s = hiz_layout(d, hz, &need);
    if (s != LT_OK)
        return s;
    if (p == NULL) {
        lt_ssb_params_default(&dp);
        p = &dp;
    }
    if (p->thickness < 0 || (p->flags & ~LT_SSB_CONTINUE_BEHIND) != 0u)
        return LT_E_ARG;
    if (*arena_bytes < need) {
        *arena_bytes = need;
        return LT_E_SPACE;
    }
    if ((need != 0 && arena == NULL) || ((uintptr_t)arena & 3u) != 0)
        return LT_E_ARG;
    hz->params = *p;
    hz->kq = lt__ssb_kthick_q30(p->thickness);
#if LT_CFG_FLOAT32
    hz->kf = 1.0f / (1.0f + (float)p->thickness * 9.31322574615478515625e-10f);
#endif
    hz->w = w;
    hz->cells = arena;
    return LT_OK;
}

/* ---- format-free lane helpers ---------------------------------------------------------------- */

/* Cell index (level 0: a pixel, y W + x) and the outside-the-grid test: lt__qtgrid_index /
 * lt__qtgrid_outside (lt_qt_grid.h), shared with lt_qt.c's nodes (the same row-major level
 * layout). */

/* ==== s1.30 cells ============================================================================= */

/* The cell codecs (pixel pair loads, cell pair loads, stores, gathers) are lt_hiz.inc's, written
 * once over the SS_* traits; the two paths differ only in what a hole is (SS_PIX_OK) and in the
 * compare class that tests it (SS_PIX_TEST_COST). */
#include "lt_ssb_q30.inc"
#define SS_CELL lt_hiz_cell_q30_t
#define SS_ENC LT_SSB_Q30
/* raw <= 0 is a hole (w > 0 is the valid range of the s1.30 input); one VCMP per pixel vector */
#define SS_PIX_OK(v) ((v) > 0)
#define SS_PIX_TEST_COST() LT_COST(VCMP, 2)
#include "lt_hiz.inc"
#include "lt_ssb_undef.inc"

/* ==== float32 cells =========================================================================== */
#if LT_CFG_FLOAT32

#include "lt_ssb_f32.inc"
#define SS_CELL lt_hiz_cell_f32_t
#define SS_ENC LT_SSB_F32
/* NaN, +-inf and w <= 0 are holes: two FCMP per pixel vector (the test is false for NaN) */
#define SS_PIX_OK(v) ((v) > 0.0f && (v) <= LT__SSB_F32_MAX)
#define SS_PIX_TEST_COST() LT_COST(FCMP, 4)
#include "lt_hiz.inc"
#include "lt_ssb_undef.inc"

#endif /* LT_CFG_FLOAT32 */
