/* lt_exr_testlib.h - multi-part and multi-view EXR files made with OpenEXR's C API (lt_exr_write
 * writes single-part files without attributes), shared by tests/unit/test_exr.c and
 * build/host/lt-exr-stereo (tests/exr/lt_exr_stereo.c, used by tests/run.d/cli.sh and
 * reproject.sh): parts with a name, a `view` attribute and scanline HALF/FLOAT channels, a
 * `multiView` attribute on every part; the synthetic stereo files (one eye per part, colour in
 * the depth's part or in a part of its own, no multiView, single-part multi-view) and the shared
 * single-part Beachball frame rewritten as a 2-part stereo file. Static functions, included once
 * per program. Host only; every function returns 0, or -1 with a message in diag.
 */
#ifndef LT_EXR_TESTLIB_H
#define LT_EXR_TESTLIB_H

#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"
#include <openexr.h>
#pragma GCC diagnostic pop

#include "io/lt_diag.h"
#include "io/lt_exr.h"

#define LTX_MAX_PARTS 4
#define LTX_MAX_CHANS 10

typedef struct ltx_chan {
    const char *name;
    exr_pixel_type_t type; /* HALF or FLOAT in the file */
    const float *data;     /* data-window raster, row-major */
} ltx_chan_t;

typedef struct ltx_part {
    const char *name; /* part name (a multi-part file needs one per part) */
    const char *view; /* `view` attribute, or NULL */
    int nch;
    ltx_chan_t ch[LTX_MAX_CHANS];
} ltx_part_t;

typedef struct ltx_file {
    exr_attr_box2i_t dw, disp; /* every part's windows */
    int nparts;
    ltx_part_t part[LTX_MAX_PARTS];
    int nviews;                /* multiView entries; 0: no multiView attribute */
    const char *views[4];
    exr_compression_t comp;
} ltx_file_t;

typedef struct ltx_io {
    int fd;
} ltx_io_t;

static int64_t ltx_write_fn(exr_const_context_t c, void *ud, const void *b, uint64_t sz,
                            uint64_t off, exr_stream_error_func_ptr_t e)
{
    (void)c;
    (void)e;
    return (int64_t)pwrite(((ltx_io_t *)ud)->fd, b, (size_t)sz, (off_t)off);
}

static void ltx_quiet(exr_const_context_t c, exr_result_t code, const char *msg)
{
    (void)c;
    (void)code;
    (void)msg;
}

/* The header of every part of f. */
static exr_result_t ltx_header(exr_context_t ctx, const ltx_file_t *f)
{
    exr_attr_v2f_t swc;
    exr_result_t rv = EXR_ERR_SUCCESS;
    int p, c, idx;
    swc.x = 0.0f;
    swc.y = 0.0f;
    for (p = 0; rv == EXR_ERR_SUCCESS && p < f->nparts; p++) {
        const ltx_part_t *pt = &f->part[p];
        rv = exr_add_part(ctx, pt->name, EXR_STORAGE_SCANLINE, &idx);
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_initialize_required_attr(ctx, idx, &f->disp, &f->dw, 1.0f, &swc, 1.0f,
                                              EXR_LINEORDER_INCREASING_Y, f->comp);
        for (c = 0; rv == EXR_ERR_SUCCESS && c < pt->nch; c++)
            rv = exr_add_channel(ctx, idx, pt->ch[c].name, pt->ch[c].type,
                                 EXR_PERCEPTUALLY_LINEAR, 1, 1);
        if (rv == EXR_ERR_SUCCESS && pt->view != NULL)
            rv = exr_attr_set_string(ctx, idx, "view", pt->view);
        if (rv == EXR_ERR_SUCCESS && f->nviews > 0) {
            const char *views[4];
            memcpy(views, f->views, sizeof views);
            rv = exr_attr_set_string_vector(ctx, idx, "multiView", f->nviews, views);
        }
    }
    return rv;
}

/* The pixels of part p; halfs[c] holds channel c as binary16 (NULL for FLOAT channels). */
static exr_result_t ltx_pixels(exr_context_t ctx, const ltx_file_t *f, int p,
                               uint16_t *const *halfs)
{
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    exr_chunk_info_t ci;
    exr_result_t rv;
    const ltx_part_t *pt = &f->part[p];
    int32_t lines = 1, y, w = f->dw.max.x - f->dw.min.x + 1;
    int inited = 0, c, i;
    rv = exr_get_scanlines_per_chunk(ctx, p, &lines);
    for (y = f->dw.min.y; rv == EXR_ERR_SUCCESS && y <= f->dw.max.y; y += lines) {
        size_t row;
        rv = exr_write_scanline_chunk_info(ctx, p, y, &ci);
        if (rv == EXR_ERR_SUCCESS)
            rv = inited ? exr_encoding_update(ctx, p, &ci, &enc)
                        : exr_encoding_initialize(ctx, p, &ci, &enc);
        if (rv != EXR_ERR_SUCCESS)
            break;
        inited = 1;
        row = (size_t)(ci.start_y - f->dw.min.y) * (size_t)w;
        for (c = 0; c < enc.channel_count; c++) {
            exr_coding_channel_info_t *ec = &enc.channels[c];
            for (i = 0; i < pt->nch && strcmp(pt->ch[i].name, ec->channel_name) != 0; i++)
                ;
            if (i == pt->nch)
                return EXR_ERR_INVALID_ARGUMENT;
            if (halfs[i] != NULL) {
                ec->encode_from_ptr = (const uint8_t *)(halfs[i] + row);
                ec->user_bytes_per_element = 2;
                ec->user_data_type = (uint16_t)EXR_PIXEL_HALF;
            } else {
                ec->encode_from_ptr = (const uint8_t *)(pt->ch[i].data + row);
                ec->user_bytes_per_element = 4;
                ec->user_data_type = (uint16_t)EXR_PIXEL_FLOAT;
            }
            ec->user_pixel_stride = ec->user_bytes_per_element;
            ec->user_line_stride = w * ec->user_bytes_per_element;
        }
        rv = exr_encoding_choose_default_routines(ctx, p, &enc);
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_run(ctx, p, &enc);
    }
    if (inited)
        (void)exr_encoding_destroy(ctx, &enc);
    return rv;
}

/* Write f to path (parts in order, each part's chunks in increasing y). */
static int ltx_write(const char *path, const ltx_file_t *f, lt_diag_t *diag)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctx = NULL;
    exr_result_t rv;
    ltx_io_t io;
    uint16_t *halfs[LTX_MAX_PARTS][LTX_MAX_CHANS];
    size_t n = (size_t)(f->dw.max.x - f->dw.min.x + 1) * (size_t)(f->dw.max.y - f->dw.min.y + 1);
    size_t k;
    int p, c, ok = 1;
    memset(halfs, 0, sizeof halfs);
    for (p = 0; p < f->nparts; p++)
        for (c = 0; c < f->part[p].nch; c++) {
            if (f->part[p].ch[c].type != EXR_PIXEL_HALF)
                continue;
            halfs[p][c] = (uint16_t *)malloc(n * sizeof(uint16_t));
            if (halfs[p][c] == NULL)
                ok = 0;
            for (k = 0; halfs[p][c] != NULL && k < n; k++)
                halfs[p][c][k] = lt_exr_half_from_float(f->part[p].ch[c].data[k]);
        }
    io.fd = ok ? open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644) : -1;
    init.user_data = &io;
    init.write_fn = ltx_write_fn;
    init.error_handler_fn = ltx_quiet;
    rv = io.fd < 0 ? EXR_ERR_FILE_ACCESS
                   : exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = ltx_header(ctx, f);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctx);
    for (p = 0; rv == EXR_ERR_SUCCESS && p < f->nparts; p++)
        rv = ltx_pixels(ctx, f, p, halfs[p]);
    if (ctx != NULL && exr_finish(&ctx) != EXR_ERR_SUCCESS && rv == EXR_ERR_SUCCESS)
        rv = EXR_ERR_FILE_ACCESS;
    if (io.fd >= 0 && close(io.fd) != 0 && rv == EXR_ERR_SUCCESS)
        rv = EXR_ERR_FILE_ACCESS;
    for (p = 0; p < f->nparts; p++)
        for (c = 0; c < f->part[p].nch; c++)
            free(halfs[p][c]);
    if (rv != EXR_ERR_SUCCESS || !ok)
        return lt_diag_fail(diag, "%s: writing the test file failed: %s", path,
                            ok ? exr_get_default_error_message(rv) : "out of memory");
    return 0;
}

/* ---- the synthetic stereo files ---------------------------------------------------------------- */

/* 24 x 16 pixels at (2, 3) in a 32 x 24 display window. Eye 0 is left, 1 right: Z (FLOAT) is a
 * tilted plane, 2 + x/16 + y/32 (left) and 4 + x/16 + y/32 (right), so every value tells the eye;
 * colour (HALF): R 0.25 (left) / 0.75 (right), G x/32, B y/32, A 1 (all exact in HALF). */
#define LTX_W 24
#define LTX_H 16
#define LTX_X0 2
#define LTX_Y0 3

static float ltx_value(int eye, int c, int x, int y)
{
    switch (c) {
    case 0:
        return (eye ? 0.75f : 0.25f);
    case 1:
        return (float)x / 32.0f;
    case 2:
        return (float)y / 32.0f;
    case 3:
        return 1.0f;
    default:
        return (eye ? 4.0f : 2.0f) + (float)x / 16.0f + (float)y / 32.0f;
    }
}

/* R G B A Z of both eyes, [eye][channel][pixel] */
static float ltx_data[2][5][LTX_W * LTX_H];

static void ltx_fill(void)
{
    int e, c, x, y;
    for (e = 0; e < 2; e++)
        for (c = 0; c < 5; c++)
            for (y = 0; y < LTX_H; y++)
                for (x = 0; x < LTX_W; x++)
                    ltx_data[e][c][y * LTX_W + x] = ltx_value(e, c, x, y);
}

/* Channels of eye e into pt: colour (RGBA, "<pfx>R" ...) and/or depth ("<pfx>Z"). */
static void ltx_eye(ltx_part_t *pt, int e, int color, int depth, const char *pfx, char names[][16])
{
    static const char *const base[5] = {"R", "G", "B", "A", "Z"};
    int c;
    for (c = 0; c < 5; c++) {
        if ((c < 4 && !color) || (c == 4 && !depth))
            continue;
        (void)snprintf(names[c], 16, "%s%s", pfx, base[c]);
        pt->ch[pt->nch].name = names[c];
        pt->ch[pt->nch].type = c == 4 ? EXR_PIXEL_FLOAT : EXR_PIXEL_HALF;
        pt->ch[pt->nch].data = ltx_data[e][c];
        pt->nch++;
    }
}

/* Kinds of synthetic file:
 *   "stereo"  part 0 "left" (view left), part 1 "right" (view right), each R G B A Z; multiView
 *             right left (the default view, right, is part 1)
 *   "split"   colour in parts of its own: 0 "left.depth" Z, 1 "right.depth" Z, 2 "left.color",
 *             3 "right.color" R G B A; views as named; multiView right left
 *   "nomv"    "stereo" without multiView (the default view is part 0's: left)
 *   "single"  one part, multiView right left: R G B A Z (right) and left.R ... left.Z
 *   "widedisp" one part, no views: R G B A Z (right) in a 20000 x 24 display window (wider than
 *             LT_EXR_MAX_DIM: the data window is readable, the display window is not)
 *   "fardisp" the same in the display window (-(2^29 - 1), -(2^29 - 1))-(2^29 - 1, 2^29 - 1),
 *             2^30 - 1 pixels square (OpenEXR refuses a window reaching past about +-2^30)
 *   "ctlview" "stereo" with the right view (the default; and its part) named "right\n\033[31m":
 *             a newline and an ANSI escape sequence in a name read from the file
 *   "farwin"  one part, no views: R G B A Z (right), the 24x16 data window at (10^6, 10^6), wholly
 *             outside the 32x24 display window */
static int ltx_write_kind(const char *path, const char *kind, lt_diag_t *diag)
{
    static char names[4][2][5][16];
    ltx_file_t f;
    memset(&f, 0, sizeof f);
    ltx_fill();
    f.dw.min.x = LTX_X0;
    f.dw.min.y = LTX_Y0;
    f.dw.max.x = LTX_X0 + LTX_W - 1;
    f.dw.max.y = LTX_Y0 + LTX_H - 1;
    f.disp.max.x = 31;
    f.disp.max.y = 23;
    f.comp = EXR_COMPRESSION_ZIP;
    f.nviews = 2;
    f.views[0] = "right";
    f.views[1] = "left";
    if (strcmp(kind, "stereo") == 0 || strcmp(kind, "nomv") == 0 || strcmp(kind, "ctlview") == 0) {
        f.nparts = 2;
        f.part[0].name = f.part[0].view = "left";
        f.part[1].name = f.part[1].view = "right";
        ltx_eye(&f.part[0], 0, 1, 1, "", names[0][0]);
        ltx_eye(&f.part[1], 1, 1, 1, "", names[1][0]);
        if (strcmp(kind, "nomv") == 0)
            f.nviews = 0;
        if (strcmp(kind, "ctlview") == 0)
            f.part[1].name = f.part[1].view = f.views[0] = "right\n\033[31m";
    } else if (strcmp(kind, "split") == 0) {
        f.nparts = 4;
        f.part[0].name = "left.depth";
        f.part[1].name = "right.depth";
        f.part[2].name = "left.color";
        f.part[3].name = "right.color";
        f.part[0].view = f.part[2].view = "left";
        f.part[1].view = f.part[3].view = "right";
        ltx_eye(&f.part[0], 0, 0, 1, "", names[0][0]);
        ltx_eye(&f.part[1], 1, 0, 1, "", names[1][0]);
        ltx_eye(&f.part[2], 0, 1, 0, "", names[2][0]);
        ltx_eye(&f.part[3], 1, 1, 0, "", names[3][0]);
    } else if (strcmp(kind, "single") == 0) {
        f.nparts = 1;
        ltx_eye(&f.part[0], 1, 1, 1, "", names[0][0]);
        ltx_eye(&f.part[0], 0, 1, 1, "left.", names[0][1]);
    } else if (strcmp(kind, "widedisp") == 0 || strcmp(kind, "fardisp") == 0) {
        f.nparts = 1;
        f.nviews = 0;
        ltx_eye(&f.part[0], 1, 1, 1, "", names[0][0]);
        f.disp.max.x = 19999;
        if (strcmp(kind, "fardisp") == 0) {
            f.disp.min.x = f.disp.min.y = -536870911; /* -(2^29 - 1) */
            f.disp.max.x = f.disp.max.y = 536870911;
        }
    } else if (strcmp(kind, "farwin") == 0) {
        f.nparts = 1;
        f.nviews = 0;
        ltx_eye(&f.part[0], 1, 1, 1, "", names[0][0]);
        f.dw.min.x = f.dw.min.y = 1000000;
        f.dw.max.x = 1000000 + LTX_W - 1;
        f.dw.max.y = 1000000 + LTX_H - 1;
    } else {
        return lt_diag_fail(diag, "unknown test file kind '%s' (stereo, split, nomv, single, "
                            "widedisp, fardisp, farwin, ctlview)", kind);
    }
    return ltx_write(path, &f, diag);
}

/* ---- the shared Beachball frame as a multi-part stereo file ------------------------------------ */

/* src: the single-part multi-view frame (R G B A Z of the default view "right", left.R ...
 * left.Z). dst: part 0 "left" (view left), part 1 "right" (view right), each R G B A Z (HALF,
 * the values read from src, exact), the same windows, ZIP, multiView as src's (right left). */
static int ltx_beachball_stereo(const char *src, const char *dst, lt_diag_t *diag)
{
    static const char *const base[5] = {"R", "G", "B", "A", "Z"};
    lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
    lt_exr_probe_t *pr = (lt_exr_probe_t *)malloc(sizeof *pr);
    lt_exr_depth_t d[2];
    ltx_file_t f;
    int e, c, rc = -1;
    memset(d, 0, sizeof d);
    memset(&f, 0, sizeof f);
    o.color = 1;
    if (pr == NULL)
        return lt_diag_fail(diag, "%s: out of memory", src);
    if (lt_exr_probe(src, pr, diag) != 0 || lt_exr_read_depth(src, "left", &o, &d[0], diag) != 0 ||
        lt_exr_read_depth(src, "Z", &o, &d[1], diag) != 0)
        goto done;
    if (pr->nviews < 2 || d[0].rgba[3] == NULL || d[1].rgba[3] == NULL) {
        lt_diag_fail(diag, "%s: not a stereo frame with R G B A Z per view", src);
        goto done;
    }
    f.dw.min.x = d[0].data_window.x0;
    f.dw.min.y = d[0].data_window.y0;
    f.dw.max.x = d[0].data_window.x1;
    f.dw.max.y = d[0].data_window.y1;
    f.disp.min.x = d[0].display_window.x0;
    f.disp.min.y = d[0].display_window.y0;
    f.disp.max.x = d[0].display_window.x1;
    f.disp.max.y = d[0].display_window.y1;
    f.comp = EXR_COMPRESSION_ZIP;
    f.nparts = 2;
    f.nviews = 2;
    f.views[0] = pr->views[0];
    f.views[1] = pr->views[1];
    f.part[0].name = f.part[0].view = "left";
    f.part[1].name = f.part[1].view = "right";
    for (e = 0; e < 2; e++)
        for (c = 0; c < 5; c++) {
            f.part[e].ch[c].name = base[c];
            f.part[e].ch[c].type = EXR_PIXEL_HALF;
            f.part[e].ch[c].data = c < 4 ? d[e].rgba[c] : d[e].z;
        }
    f.part[0].nch = f.part[1].nch = 5;
    rc = ltx_write(dst, &f, diag);
done:
    lt_exr_depth_free(&d[0]);
    lt_exr_depth_free(&d[1]);
    free(pr);
    return rc;
}

#endif /* LT_EXR_TESTLIB_H */
