/* fuzz_exr.c - fuzz target of the OpenEXR depth reader (host/io/lt_exr.c): flat scanline, tiled,
 * multi-part, multi-view and deep scanline files, through lt_exr_probe and lt_exr_read_depth with
 * the options the CLI uses (info: deep front-most, colour; reproject: display window). Any bytes
 * must give a depth buffer within the documented limits or a one-line message naming the file,
 * never a crash, a hang or a read outside a buffer. The input is written to a file in /dev/shm
 * (the reader takes a path). Built with libFuzzer (make fuzz-exr) and replayed over
 * tests/fuzz/corpus/exr by tests/fuzz/fuzz_main.c in make test. Host only.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"
#include "io/lt_exr.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The reader's calls, in one place (their error convention may change). */
static int probe(const char *path, lt_exr_probe_t *pr, char *err, size_t cap)
{
    lt_diag_t dg;
    int r = lt_exr_probe(path, pr, &dg);
    fuzz_take_message(err, cap, r, &dg);
    return r;
}

static int read_depth(const char *path, const char *channel, const lt_exr_read_opts_t *o,
                      lt_exr_depth_t *d, char *err, size_t cap)
{
    lt_diag_t dg;
    int r = lt_exr_read_depth(path, channel, o, d, &dg);
    fuzz_take_message(err, cap, r, &dg);
    return r;
}

/* An accepted depth buffer is within the limits and every value can be read. */
static void check_depth(const lt_exr_depth_t *d)
{
    size_t n, i;
    volatile float sink = 0.0f;
    int c;
    if (d->width < 1 || d->height < 1 || d->width > LT_EXR_MAX_DIM ||
        d->height > LT_EXR_MAX_DIM || d->z == NULL ||
        memchr(d->channel, '\0', sizeof d->channel) == NULL)
        abort();
    n = (size_t)d->width * (size_t)d->height;
    for (i = 0; i < n; i++)
        sink += d->z[i];
    for (c = 0; c < 4; c++)
        if (d->rgba[c] != NULL)
            sink += d->rgba[c][0] + d->rgba[c][n - 1];
    (void)sink;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static lt_exr_probe_t pr; /* 8.6 KiB */
    static const char *const channels[2] = {NULL, "left"};
    const char *path = fuzz_file(data, size, "in.exr");
    char err[512];
    lt_exr_depth_t d;
    int k;

    if (probe(path, &pr, err, sizeof err) != 0)
        fuzz_check_message(err, sizeof err);
    else if (pr.parts < 1 || pr.nchannels < 0)
        abort();
    /* as `info` reads (deep front-most, colour, data window), then as `reproject --display`
       reads with a view name (display window, deep refused) */
    for (k = 0; k < 2; k++) {
        lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
        o.window = k == 0 ? LT_EXR_WINDOW_DATA : LT_EXR_WINDOW_DISPLAY;
        o.color = k == 0;
        o.deep = k == 0 ? LT_EXR_DEEP_FRONT : LT_EXR_DEEP_REJECT;
        o.fill = k == 0 ? 0.0f : INFINITY;
        memset(err, 'x', sizeof err);
        if (read_depth(path, channels[k], &o, &d, err, sizeof err) == 0) {
            check_depth(&d);
            lt_exr_depth_free(&d);
        } else {
            fuzz_check_message(err, sizeof err);
            if (d.z != NULL)
                abort(); /* a failed read leaves nothing allocated */
        }
    }
    return 0;
}
