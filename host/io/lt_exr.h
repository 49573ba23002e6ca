/* lt_exr.h - OpenEXR output of object-space renders (named FLOAT/HALF channels, multi-layer
 * "layer<k>.Z" depth peels, R G B A) and input of depth buffers (flat scanline or tiled, HALF or
 * FLOAT Z, multi-part and multi-view files read by part or view, optional colour, deep files read
 * front-most), through OpenEXR's C API (OpenEXRCore 3.1, Debian libopenexr-dev). Host only; see
 * docs/io.md for formats and limits.
 */
#ifndef LT_EXR_H
#define LT_EXR_H

#include <stddef.h>
#include <stdint.h>

#include "io/lt_diag.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest data-window (and, when it is read, display-window) width or height accepted (a build
 * may set a smaller one: the libFuzzer build does, tests/fuzz.mk). */
#ifndef LT_EXR_MAX_DIM
#define LT_EXR_MAX_DIM 16384
#endif
/* Most channels one lt_exr_write call writes. */
#define LT_EXR_MAX_CHANNELS 256
/* Longest channel name in bytes (names over 31 bytes switch the file to EXR "long names"). */
#define LT_EXR_MAX_NAME 255

/* Storage type of a channel in the file; in memory every channel is float32. */
typedef enum lt_exr_type {
    LT_EXR_HALF = 1,  /* IEEE 754 binary16 */
    LT_EXR_FLOAT = 2, /* IEEE 754 binary32 */
    LT_EXR_UINT = 3   /* uint32 (only reported by lt_exr_probe; neither written nor read) */
} lt_exr_type_t;

/* Compression of a written file (all lossless). */
typedef enum lt_exr_comp {
    LT_EXR_COMP_ZIP = 0,  /* zlib, 16 scanlines per chunk (the default) */
    LT_EXR_COMP_ZIPS = 1, /* zlib, 1 scanline per chunk */
    LT_EXR_COMP_NONE = 2  /* uncompressed */
} lt_exr_comp_t;

/* One channel to write: 16 bytes on LP64. */
typedef struct lt_exr_channel {
    const char *name;   /* e.g. "Z", "layer3.Z", "R"; 1..LT_EXR_MAX_NAME bytes, unique per image */
    lt_exr_type_t type; /* storage type in the file */
    const float *data;  /* width * height values, row-major, row 0 = top row of the data window */
} lt_exr_channel_t;

/* An image to write: a data window of width x height pixels whose top-left pixel sits at (x0, y0)
 * in the display window (0, 0)-(display_w - 1, display_h - 1). */
typedef struct lt_exr_image {
    int32_t width, height;            /* data window size, pixels, 1..LT_EXR_MAX_DIM */
    int32_t x0, y0;                   /* data window origin, pixels (may be negative) */
    int32_t display_w, display_h;     /* display window size; 0 = (x0 + width, y0 + height) */
    int nchannels;                    /* 1..LT_EXR_MAX_CHANNELS */
    const lt_exr_channel_t *channels; /* nchannels entries, any order (EXR sorts them) */
    lt_exr_comp_t compression;        /* LT_EXR_COMP_ZIP unless set */
} lt_exr_image_t;

/* Write img to path as a single-part scanline EXR, atomically: the data goes to
 * "<path>.tmp.<pid>" in the same directory, is fsync'ed, then renamed over path, so an interrupted
 * run leaves either the previous file or the complete new one (plus, at worst, the temp file).
 * A path that is an output set's registered temporary (lt_outset_add) is written directly, and
 * messages name the set's output instead (lt_tmp_target).
 * Format: float32 in memory -> HALF or FLOAT per channel in the file.
 * Range: any float, NaN and +-inf included. Rounding: HALF rounds to nearest, ties to even
 * (subnormal halves included). Overflow: HALF saturates to +-inf beyond +-65504 (+-65520 rounds
 * to inf as IEEE requires). Cost: host only, not charged.
 * Returns: 0, or -1 with a message naming the path and the problem in diag. */
int lt_exr_write(const char *path, const lt_exr_image_t *img, lt_diag_t *diag);

/* ---- reading --------------------------------------------------------------------------------- */

/* Inclusive pixel box, EXR convention: (x0, y0)-(x1, y1). */
typedef struct lt_exr_box {
    int32_t x0, y0, x1, y1; /* pixels */
} lt_exr_box_t;

typedef enum lt_exr_window {
    LT_EXR_WINDOW_DATA = 0,   /* return the data window (origin kept in x0, y0) */
    LT_EXR_WINDOW_DISPLAY = 1 /* return the display window; pixels outside the data window = fill */
} lt_exr_window_t;

typedef enum lt_exr_deep {
    LT_EXR_DEEP_REJECT = 0, /* a deep image is an error that says how to read it */
    LT_EXR_DEEP_FRONT = 1   /* read the front-most sample (least Z) of each deep pixel */
} lt_exr_deep_t;

/* Reading options; LT_EXR_READ_OPTS_DEFAULT (or a NULL pointer) gives the defaults. */
typedef struct lt_exr_read_opts {
    lt_exr_window_t window; /* data window (default) or display window */
    float fill;             /* depth outside the data window and of deep pixels with no sample */
    int color;              /* 1: also read <layer>.R/G/B/A (absent ones stay NULL) */
    lt_exr_deep_t deep;     /* what to do with deep images */
    int part;               /* -1: choose (by view, see lt_exr_read_depth); N: read part N only */
    const char *view;       /* NULL: the file's default view; else the view to read */
} lt_exr_read_opts_t;

#define LT_EXR_READ_OPTS_DEFAULT {LT_EXR_WINDOW_DATA, 0.0f, 0, LT_EXR_DEEP_REJECT, -1, NULL}

/* A depth buffer read from a file. Free with lt_exr_depth_free. */
typedef struct lt_exr_depth {
    int32_t width, height;        /* raster size, pixels */
    int32_t x0, y0;               /* EXR pixel coordinates of raster element (0, 0) */
    lt_exr_box_t data_window;     /* as stored in the file */
    lt_exr_box_t display_window;  /* as stored in the file */
    float *z;                     /* width * height depths, row-major, values as stored */
    float *rgba[4];               /* R, G, B, A of the same layer, or NULL (absent, not asked) */
    lt_exr_type_t z_type;         /* storage type of the depth channel in the file */
    int part;                     /* index of the part read */
    int color_part;               /* index of the part the colour came from, -1: no colour */
    int deep;                     /* 1: a deep part, front-most sample per pixel */
    uint64_t deep_samples;        /* deep parts: samples seen over the data window */
    char channel[LT_EXR_MAX_NAME + 1]; /* name of the depth channel read */
    char view[LT_EXR_MAX_NAME + 1];    /* view read ("" when the file names no views) */
} lt_exr_depth_t;

/* Read one depth channel.
 * Views and parts: the multiView attribute (of any part) lists the file's views, the first is
 * the default view. A multi-part file holds a view per part (each part's `view` attribute); a
 * part without one (every single-part file) holds its views by channel name: "<view>.<chan>" or
 * "<layer>.<view>.<chan>", the default view's channels unprefixed. Which part:
 *   opts->part N: part N only (out of range: an error naming N and the part count; with a view,
 *     part N must hold that view or none);
 *   opts->view NAME: the parts whose `view` is NAME, then the parts without a `view`, where
 *     NAME's channels are read ("Z" -> "NAME.Z", "layer1.Z" -> "layer1.NAME.Z"; the default
 *     view's also as named);
 *   neither: the default view's parts (multiView[0]; without multiView, part 0's view), then
 *     parts without a `view`; a file whose parts name no view: every part, the first match wins.
 * A view the file does not name is an error that lists the views (multiView's and the parts').
 * Which channel of a part: channel NULL picks, in this order: "Z"; "depth"; "<default view>.Z";
 * the only channel named "*.Z". A channel that is not in the file but names a view reads that
 * view: "<view>.Z" ("left" -> "left.Z"; the default view -> "Z"), or in a multi-part file the
 * view's part(s). Any other channel ("R", "layer2.Z") can be read the same way.
 * Colour (opts->color): R G B A next to the depth channel (its name's prefix up to the last dot)
 * in its part; when that part has none of R G B, in a multi-part file without opts->part: the
 * first other flat part of the same view (or, like the depth's, of none) with the same data
 * window (out->color_part). Background values (0 or +inf, whatever the renderer wrote) and NaN
 * are returned as stored: nothing is remapped.
 * Format: HALF or FLOAT in the file -> float32 (HALF converts exactly). Range: any.
 * Rounding: none. Overflow: none. Cost: host only, not charged.
 * Returns: 0, or -1 with a message naming the path and the problem in diag (a missing channel
 * lists the views and depth channels found, per part; an unknown view lists the views; a deep
 * image says how to read it; subsampled, UINT, oversized or corrupt inputs name the limit). */
int lt_exr_read_depth(const char *path, const char *channel, const lt_exr_read_opts_t *opts,
                      lt_exr_depth_t *out, lt_diag_t *diag);

/* Whether the display window disp (as stored in path) is one that may be read: 1..LT_EXR_MAX_DIM
 * per side, the limit lt_exr_read_depth applies to it with LT_EXR_WINDOW_DISPLAY. A command that
 * reads a data window and derives a camera from the display window around it (reproject's and
 * fwblob's default source camera, lt_rp_cam_default) checks it with this first, so that a window
 * of 20000 or 2^30 pixels is refused, not turned into a focal length. Cost: host only.
 * Returns: 0, or -1 with a message naming path, the window's size and the limit, e.g.
 * "d.exr: display window 20000x24 outside 1..LT_EXR_MAX_DIM 16384". */
int lt_exr_display_check(const char *path, const lt_exr_box_t *disp, lt_diag_t *diag);

/* lt_exr_display_check, and that the data window data overlaps the display window disp: the
 * check of a command that builds its camera over the display window (reproject's and fwblob's
 * default source camera). A data window wholly outside it (an offset of 10^6 pixels) would put
 * the principal point 10^6 pixels off the image, every ray nearly parallel to the image plane,
 * and give a view that looks valid but is not the file's. Cost: host only.
 * Returns: 0, or -1 with a message naming path and both windows, e.g. "d.exr: data window
 * (1000000,1000000)-(1000015,1000015) lies wholly outside the display window (0,0)-(15,15)". */
int lt_exr_camera_check(const char *path, const lt_exr_box_t *data, const lt_exr_box_t *disp,
                        lt_diag_t *diag);

/* Free what lt_exr_read_depth allocated (safe on a zeroed or already-freed struct).
 * Cost: host only. */
void lt_exr_depth_free(lt_exr_depth_t *d);

/* What a file holds, for listings and checks: the part count, the views and one part's header.
 * Channels past LT_EXR_PROBE_CHANNELS and views past LT_EXR_PROBE_VIEWS are counted but not
 * named. 13 KiB; not for the stack of small threads. */
#define LT_EXR_PROBE_CHANNELS 32
#define LT_EXR_PROBE_VIEWS 16
typedef struct lt_exr_probe {
    int parts;                    /* parts in the file */
    int part;                     /* the part described below */
    int storage;                  /* 0 scanline, 1 tiled, 2 deep scanline, 3 deep tiled */
    int compression;              /* EXR compression id (0 none, 2 ZIPS, 3 ZIP, ...) */
    lt_exr_box_t data_window;     /* of the part */
    lt_exr_box_t display_window;  /* of the part */
    char part_name[LT_EXR_MAX_NAME + 1]; /* the part's `name` attribute, "" if none */
    char view[LT_EXR_MAX_NAME + 1];      /* the part's `view` attribute, "" if none */
    int nviews;                   /* views of the file: multiView's, then parts' `view`s */
    char views[LT_EXR_PROBE_VIEWS][LT_EXR_MAX_NAME + 1];
    char default_view[LT_EXR_MAX_NAME + 1]; /* multiView[0], else part 0's view, else "" */
    int nchannels;                /* channels of the part */
    lt_exr_type_t type[LT_EXR_PROBE_CHANNELS];           /* storage type per channel */
    char name[LT_EXR_PROBE_CHANNELS][LT_EXR_MAX_NAME + 1]; /* names, sorted as in the file */
} lt_exr_probe_t;

/* Read the header of part 0 (and the part count and views); no pixels. Cost: host only.
 * Returns: 0, or -1 with a message naming the path and the problem in diag. */
int lt_exr_probe(const char *path, lt_exr_probe_t *info, lt_diag_t *diag);

/* The same for part `part` (0 .. parts - 1; out of range: an error naming the part count). */
int lt_exr_probe_part(const char *path, int part, lt_exr_probe_t *info, lt_diag_t *diag);

/* IEEE binary16 <-> binary32 as used by the writer (host helpers, exported for tests).
 * Format: float32 -> binary16 bits. Range: any. Rounding: to nearest, ties to even.
 * Overflow: to +-inf. NaN stays NaN (quiet, sign and top payload bits kept). Cost: none. */
uint16_t lt_exr_half_from_float(float f);
/* Format: binary16 bits -> float32. Range: any. Rounding: exact. Overflow: none. Cost: none. */
float lt_exr_half_to_float(uint16_t h);

/* The name of an OpenEXR compression value as `info` prints it ("none", "zip", "piz", ...;
 * "unknown" outside 0..9). */
const char *lt_exr_compression_name(int c);

#ifdef __cplusplus
}
#endif

#endif /* LT_EXR_H */
