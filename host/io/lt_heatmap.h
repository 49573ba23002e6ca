/* lt_heatmap.h - false-colour maps of per-pixel float images (traversal steps, modelled cycles,
 * depth error) with the Turbo colour map (Mikhailov 2019, polynomial fit by R. Du), a legend bar
 * and min/max tick labels drawn with a built-in 5x7 digit font; written as PNG, and the same data
 * as a single-channel FLOAT EXR. Host only; see docs/io.md.
 */
#ifndef LT_HEATMAP_H
#define LT_HEATMAP_H

#include <stddef.h>
#include <stdint.h>

#include "io/lt_diag.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Rendering options; LT_HEATMAP_OPTS_DEFAULT (or a NULL pointer) gives the defaults. */
typedef struct lt_heatmap_opts {
    float lo, hi; /* value range mapped to the colour ends; lo >= hi: finite min..max of the data */
    int legend;   /* 1: legend bar, ticks and min/max labels right of the image */
} lt_heatmap_opts_t;

#define LT_HEATMAP_OPTS_DEFAULT {0.0f, 0.0f, 1}

/* Colours with a meaning of their own (not on the ramp, which runs from (35,23,27) at t = 0
 * through blue, cyan, green, yellow and red to (144,13,0) at t = 1). */
#define LT_HEATMAP_INVALID_RGB 0, 0, 0       /* NaN and +-inf pixels */
#define LT_HEATMAP_BACKGROUND_RGB 32, 32, 32 /* legend area and padding below a short image */
#define LT_HEATMAP_TEXT_RGB 255, 255, 255    /* labels and ticks */

/* A rendered map: the image at (0, 0), the legend to its right. */
typedef struct lt_heatmap_image {
    int32_t width, height;  /* pixels of rgb */
    uint8_t *rgb;           /* width * height * 3 bytes, rows top first */
    float lo, hi;           /* range used (labels print these with %.4g) */
    int32_t bar_x0, bar_y0; /* legend bar, inclusive box; the top row is hi, the bottom row lo */
    int32_t bar_x1, bar_y1; /* (all four -1 without a legend) */
    int32_t label_x0;       /* first column of the labels (-1 without a legend) */
    int32_t font_scale;     /* glyph pixel size: 1 below 384 rows, +1 per 384 rows, at most 4 */
} lt_heatmap_image_t;

/* Colour of t in [0, 1] (clamped; NaN -> the invalid colour) on the Turbo map.
 * Format: float -> 3 x uint8 (Du's degree-5 polynomial fit of the Turbo table, evaluated in
 * double). Range: [0, 1]. Rounding: channel * 255 to nearest. Overflow: channels clamp to
 * [0, 255]. Cost: host only. */
void lt_heatmap_color(float t, uint8_t rgb[3]);

/* Render v (w x h floats, rows top first) to an RGB image. Values map linearly from [lo, hi] to
 * [0, 1] (clamped; lo == hi maps every finite value to 0); NaN and +-inf get the invalid colour
 * and are left out of the automatic range.
 * Format: float -> RGB8. Range: any. Rounding: t * 255 to nearest LUT entry. Overflow: clamps.
 * Cost: host only.
 * Returns: 0, or -1 with a message naming the problem in diag (bad size, non-finite lo/hi,
 * out of memory). */
int lt_heatmap_render(const float *v, int32_t w, int32_t h, const lt_heatmap_opts_t *opts,
                      lt_heatmap_image_t *out, lt_diag_t *diag);

/* Free the rgb buffer (safe on a zeroed or already-freed image). Cost: host only. */
void lt_heatmap_free(lt_heatmap_image_t *im);

/* lt_heatmap_render, then lt_png_write (RGB, atomic). Format: float -> RGB8 PNG.
 * Cost: host only. Returns: 0, or -1 with a message naming path and the problem. */
int lt_heatmap_write_png(const char *path, const float *v, int32_t w, int32_t h,
                         const lt_heatmap_opts_t *opts, lt_diag_t *diag);

/* The raw values as a one-channel FLOAT EXR (channel NULL = "Y"), ZIP, atomic (lt_exr_write).
 * Format: float32 -> FLOAT, bit-exact. Cost: host only.
 * Returns: 0, or -1 with a message naming path and the problem. */
int lt_heatmap_write_exr(const char *path, const float *v, int32_t w, int32_t h,
                         const char *channel, lt_diag_t *diag);

#ifdef __cplusplus
}
#endif

#endif /* LT_HEATMAP_H */
