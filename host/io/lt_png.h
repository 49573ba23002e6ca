/* lt_png.h - 8-bit PNG output (gray, gray+alpha, RGB, RGBA) through libpng (Debian libpng16),
 * written atomically (temp name + fsync + rename). Host only; see docs/io.md.
 */
#ifndef LT_PNG_H
#define LT_PNG_H

#include <stddef.h>
#include <stdint.h>

#include "io/lt_diag.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest width or height written. */
#define LT_PNG_MAX_DIM 16384

/* Write a w x h image of `channels` interleaved 8-bit samples per pixel (1 gray, 2 gray+alpha,
 * 3 RGB, 4 RGBA; alpha not premultiplied), rows top first, `stride` bytes apart (0 = w *
 * channels). The data goes to "<path>.tmp.<pid>", is fsync'ed and renamed over path, so an
 * interrupted run leaves the previous file or the complete new one. An output set's registered
 * temporary (lt_outset_add) is written directly, and messages name the set's output.
 * Format: uint8 samples -> 8-bit PNG (zlib level 6, no filter heuristics beyond libpng's).
 * Range: 0..255. Rounding: none. Overflow: none. Cost: host only, not charged.
 * Returns: 0, or -1 with a message naming the path and the problem in diag. */
int lt_png_write(const char *path, const uint8_t *pix, int32_t w, int32_t h, int channels,
                 size_t stride, lt_diag_t *diag);

#ifdef __cplusplus
}
#endif

#endif /* LT_PNG_H */
