/* seeds_exr.c - writes the EXR fuzz target's seed files (small, one of each shape the reader
 * takes) into the directory given: flat scanline with every compression, HALF and FLOAT depth,
 * colour layers, data window off the display window, UINT and subsampled channels, tiled, two
 * parts, multi-view, deep scanline and deep tiled. Written with OpenEXRCore's C API so that the
 * shapes lt_exr_write does not make are there too. Used once to seed tests/fuzz/corpus/exr (make
 * fuzz-seeds); not part of make test. Host only.
 *     fuzz-seeds-exr DIR
 */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"
#include <openexr.h>
#pragma GCC diagnostic pop

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *dir;
static int failures;

typedef struct io {
    int fd;
} io_t;

static int64_t wr(exr_const_context_t c, void *ud, const void *b, uint64_t sz, uint64_t off,
                  exr_stream_error_func_ptr_t e)
{
    (void)c;
    (void)e;
    return (int64_t)pwrite(((io_t *)ud)->fd, b, (size_t)sz, (off_t)off);
}

static exr_attr_box2i_t box(int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
    exr_attr_box2i_t b;
    b.min.x = x0;
    b.min.y = y0;
    b.max.x = x1;
    b.max.y = y1;
    return b;
}

static exr_context_t start(const char *name, io_t *io)
{
    char path[1024];
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctx = NULL;
    (void)snprintf(path, sizeof path, "%s/%s", dir, name);
    io->fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (io->fd < 0) {
        perror(path);
        exit(1);
    }
    init.user_data = io;
    init.write_fn = wr;
    if (exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init) != EXR_ERR_SUCCESS) {
        fprintf(stderr, "%s: cannot start\n", path);
        exit(1);
    }
    return ctx;
}

static void finish(exr_context_t ctx, io_t *io, const char *name, exr_result_t rv)
{
    if (exr_finish(&ctx) != EXR_ERR_SUCCESS || rv != EXR_ERR_SUCCESS) {
        fprintf(stderr, "seeds_exr: %s: %s\n", name, exr_get_default_error_message(rv));
        failures++;
    }
    (void)close(io->fd);
}

typedef struct chan {
    const char *name;
    exr_pixel_type_t type;
    int xs, ys;
} chan_t;

/* One part's header; returns the part index or -1. */
static int add_part(exr_context_t ctx, const char *pname, exr_storage_t st, exr_attr_box2i_t disp,
                    exr_attr_box2i_t dw, exr_compression_t comp, const chan_t *ch, int nch,
                    int tw, int th)
{
    exr_attr_v2f_t swc;
    int part = -1, i;
    swc.x = 0.0f;
    swc.y = 0.0f;
    if (exr_add_part(ctx, pname, st, &part) != EXR_ERR_SUCCESS ||
        exr_initialize_required_attr(ctx, part, &disp, &dw, 1.0f, &swc, 1.0f,
                                     EXR_LINEORDER_INCREASING_Y, comp) != EXR_ERR_SUCCESS)
        return -1;
    if (tw > 0) {
        exr_attr_tiledesc_t td;
        td.x_size = (uint32_t)tw;
        td.y_size = (uint32_t)th;
        td.level_and_round = EXR_PACK_TILE_LEVEL_ROUND(EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN);
        if (exr_attr_set_tiledesc(ctx, part, "tiles", &td) != EXR_ERR_SUCCESS)
            return -1;
    }
    for (i = 0; i < nch; i++)
        if (exr_add_channel(ctx, part, ch[i].name, ch[i].type, EXR_PERCEPTUALLY_LINEAR, ch[i].xs,
                            ch[i].ys) != EXR_ERR_SUCCESS)
            return -1;
    return part;
}

/* Pixel data of every chunk of a flat part: channel c, pixel (x, y) = c + x * 0.5 + y * 0.25. */
static exr_result_t write_flat(exr_context_t ctx, int part, int tiled)
{
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    exr_attr_box2i_t dw;
    exr_result_t rv;
    int32_t lines = 1, tw = 1, th = 1, W, H, cx, cy, inited = 0;
    static uint8_t buf[8][64 * 64 * 4];
    rv = exr_get_data_window(ctx, part, &dw);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    W = dw.max.x - dw.min.x + 1;
    H = dw.max.y - dw.min.y + 1;
    if (tiled)
        rv = exr_get_tile_sizes(ctx, part, 0, 0, &tw, &th);
    else
        rv = exr_get_scanlines_per_chunk(ctx, part, &lines);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    for (cy = 0; cy < (tiled ? (H + th - 1) / th : (H + lines - 1) / lines); cy++)
        for (cx = 0; cx < (tiled ? (W + tw - 1) / tw : 1); cx++) {
            exr_chunk_info_t ci;
            int c, x, y;
            rv = tiled ? exr_write_tile_chunk_info(ctx, part, cx, cy, 0, 0, &ci)
                       : exr_write_scanline_chunk_info(ctx, part, dw.min.y + cy * lines, &ci);
            if (rv == EXR_ERR_SUCCESS)
                rv = inited ? exr_encoding_update(ctx, part, &ci, &enc)
                            : exr_encoding_initialize(ctx, part, &ci, &enc);
            if (rv != EXR_ERR_SUCCESS)
                break;
            inited = 1;
            for (c = 0; c < enc.channel_count && c < 8; c++) {
                exr_coding_channel_info_t *ec = &enc.channels[c];
                int bpe = ec->bytes_per_element;
                for (y = 0; y < ec->height; y++)
                    for (x = 0; x < ec->width; x++) {
                        float f = (float)c + (float)x * 0.5f + (float)y * 0.25f;
                        uint8_t *p = buf[c] + (y * ec->width + x) * bpe;
                        if (ec->data_type == EXR_PIXEL_FLOAT)
                            memcpy(p, &f, 4);
                        else if (ec->data_type == EXR_PIXEL_UINT) {
                            uint32_t u = (uint32_t)(x + y);
                            memcpy(p, &u, 4);
                        } else {
                            uint16_t h = (uint16_t)(0x3C00u + (unsigned)(x + y));
                            memcpy(p, &h, 2);
                        }
                    }
                ec->encode_from_ptr = buf[c];
                ec->user_pixel_stride = bpe;
                ec->user_line_stride = ec->width * bpe;
                ec->user_bytes_per_element = (int8_t)bpe;
                ec->user_data_type = ec->data_type;
            }
            rv = exr_encoding_choose_default_routines(ctx, part, &enc);
            if (rv == EXR_ERR_SUCCESS)
                rv = exr_encoding_run(ctx, part, &enc);
            if (rv != EXR_ERR_SUCCESS)
                break;
        }
    if (inited)
        (void)exr_encoding_destroy(ctx, &enc);
    return rv;
}

static void flat(const char *name, exr_compression_t comp, const chan_t *ch, int nch,
                 exr_attr_box2i_t disp, exr_attr_box2i_t dw, int tw, int th)
{
    io_t io;
    exr_context_t ctx = start(name, &io);
    int part = add_part(ctx, NULL, tw > 0 ? EXR_STORAGE_TILED : EXR_STORAGE_SCANLINE, disp, dw,
                        comp, ch, nch, tw, th);
    exr_result_t rv = part < 0 ? EXR_ERR_INVALID_ARGUMENT : exr_write_header(ctx);
    if (rv == EXR_ERR_SUCCESS)
        rv = write_flat(ctx, part, tw > 0);
    finish(ctx, &io, name, rv);
}

static void multipart(void)
{
    static const chan_t rgb[3] = {{"B", EXR_PIXEL_HALF, 1, 1}, {"G", EXR_PIXEL_HALF, 1, 1},
                                  {"R", EXR_PIXEL_HALF, 1, 1}};
    static const chan_t z[2] = {{"Z", EXR_PIXEL_FLOAT, 1, 1}, {"depth", EXR_PIXEL_HALF, 1, 1}};
    io_t io;
    exr_context_t ctx = start("multipart.exr", &io);
    int p0 = add_part(ctx, "beauty", EXR_STORAGE_SCANLINE, box(0, 0, 5, 3), box(0, 0, 5, 3),
                      EXR_COMPRESSION_ZIPS, rgb, 3, 0, 0);
    int p1 = add_part(ctx, "depth", EXR_STORAGE_TILED, box(0, 0, 5, 3), box(1, 1, 4, 3),
                      EXR_COMPRESSION_NONE, z, 2, 2, 2);
    exr_result_t rv = p0 < 0 || p1 < 0 ? EXR_ERR_INVALID_ARGUMENT : exr_write_header(ctx);
    if (rv == EXR_ERR_SUCCESS)
        rv = write_flat(ctx, p0, 0);
    if (rv == EXR_ERR_SUCCESS)
        rv = write_flat(ctx, p1, 1);
    finish(ctx, &io, "multipart.exr", rv);
}

static void multiview(void)
{
    static const chan_t ch[3] = {{"Z", EXR_PIXEL_FLOAT, 1, 1}, {"right.Z", EXR_PIXEL_HALF, 1, 1},
                                 {"right.R", EXR_PIXEL_HALF, 1, 1}};
    const char *views[2] = {"left", "right"};
    io_t io;
    exr_context_t ctx = start("multiview.exr", &io);
    int p = add_part(ctx, NULL, EXR_STORAGE_SCANLINE, box(0, 0, 3, 2), box(0, 0, 3, 2),
                     EXR_COMPRESSION_ZIP, ch, 3, 0, 0);
    exr_result_t rv = p < 0 ? EXR_ERR_INVALID_ARGUMENT
                            : exr_attr_set_string_vector(ctx, p, "multiView", 2, views);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctx);
    if (rv == EXR_ERR_SUCCESS)
        rv = write_flat(ctx, p, 0);
    finish(ctx, &io, "multiview.exr", rv);
}

/* Deep scanline W x 2 (R HALF, Z FLOAT), counts per pixel 0..3. */
static void deep(const char *name, exr_compression_t comp)
{
    static const chan_t ch[2] = {{"R", EXR_PIXEL_HALF, 1, 1}, {"Z", EXR_PIXEL_FLOAT, 1, 1}};
    static const int32_t counts[8] = {0, 1, 3, 2, 2, 1, 2, 1};
    io_t io;
    exr_context_t ctx = start(name, &io);
    int p = add_part(ctx, NULL, EXR_STORAGE_DEEP_SCANLINE, box(0, 0, 3, 1), box(0, 0, 3, 1), comp,
                     ch, 2, 0, 0);
    exr_result_t rv = p < 0 ? EXR_ERR_INVALID_ARGUMENT : exr_write_header(ctx);
    int y, x, s;
    for (y = 0; y < 2 && rv == EXR_ERR_SUCCESS; y++) {
        uint8_t table[16], data[256];
        int32_t cum = 0;
        size_t o = 0;
        for (x = 0; x < 4; x++) {
            cum += counts[y * 4 + x];
            memcpy(table + 4 * x, &cum, 4);
        }
        for (s = 0; s < cum; s++) {
            uint16_t h = (uint16_t)(0x3400u + (unsigned)s);
            memcpy(data + o, &h, 2);
            o += 2;
        }
        for (s = 0; s < cum; s++) {
            float z = (float)(7 - s) * 0.5f;
            memcpy(data + o, &z, 4);
            o += 4;
        }
        rv = exr_write_deep_scanline_chunk(ctx, p, y, data, o, o, table, sizeof table);
    }
    finish(ctx, &io, name, rv);
}

static void deep_tiled(void)
{
    static const chan_t ch[1] = {{"Z", EXR_PIXEL_FLOAT, 1, 1}};
    io_t io;
    exr_context_t ctx = start("deep_tiled_header.exr", &io);
    int p = add_part(ctx, NULL, EXR_STORAGE_DEEP_TILED, box(0, 0, 1, 1), box(0, 0, 1, 1),
                     EXR_COMPRESSION_NONE, ch, 1, 2, 2);
    /* the header alone: the reader refuses deep tiled parts before any chunk */
    exr_result_t rv = p < 0 ? EXR_ERR_INVALID_ARGUMENT : exr_write_header(ctx);
    finish(ctx, &io, "deep_tiled_header.exr", rv);
}

int main(int argc, char **argv)
{
    static const chan_t zf[1] = {{"Z", EXR_PIXEL_FLOAT, 1, 1}};
    static const chan_t zh[1] = {{"Z", EXR_PIXEL_HALF, 1, 1}};
    static const chan_t layer[5] = {{"layer0.A", EXR_PIXEL_HALF, 1, 1},
                                    {"layer0.B", EXR_PIXEL_HALF, 1, 1},
                                    {"layer0.G", EXR_PIXEL_HALF, 1, 1},
                                    {"layer0.R", EXR_PIXEL_FLOAT, 1, 1},
                                    {"layer0.Z", EXR_PIXEL_FLOAT, 1, 1}};
    static const chan_t odd[3] = {{"U", EXR_PIXEL_UINT, 1, 1}, {"Z", EXR_PIXEL_UINT, 1, 1},
                                  {"c", EXR_PIXEL_HALF, 2, 2}};
    static const chan_t sub[2] = {{"R", EXR_PIXEL_HALF, 2, 2}, {"Z", EXR_PIXEL_FLOAT, 1, 1}};
    static const struct {
        const char *name;
        exr_compression_t c;
    } comps[] = {{"scan_none.exr", EXR_COMPRESSION_NONE}, {"scan_rle.exr", EXR_COMPRESSION_RLE},
                 {"scan_zips.exr", EXR_COMPRESSION_ZIPS}, {"scan_zip.exr", EXR_COMPRESSION_ZIP},
                 {"scan_piz.exr", EXR_COMPRESSION_PIZ},   {"scan_pxr24.exr", EXR_COMPRESSION_PXR24},
                 {"scan_b44.exr", EXR_COMPRESSION_B44},   {"scan_b44a.exr", EXR_COMPRESSION_B44A}};
    /* DWAA/DWAB: OpenEXRCore 3.1 cannot write them (nor read them: "not implemented in C") */
    size_t i;
    if (argc != 2) {
        fprintf(stderr, "usage: %s DIR\n", argv[0]);
        return 2;
    }
    dir = argv[1];
    for (i = 0; i < sizeof comps / sizeof comps[0]; i++)
        flat(comps[i].name, comps[i].c, i % 2 ? zh : zf, 1, box(0, 0, 4, 3), box(0, 0, 4, 3), 0,
             0);
    flat("layers_zip.exr", EXR_COMPRESSION_ZIP, layer, 5, box(0, 0, 7, 5), box(0, 0, 7, 5), 0, 0);
    flat("window_off_display.exr", EXR_COMPRESSION_ZIPS, zf, 1, box(0, 0, 3, 3),
         box(-2, 2, 2, 5), 0, 0);
    flat("uint_subsampled.exr", EXR_COMPRESSION_NONE, odd, 3, box(0, 0, 3, 3), box(0, 0, 3, 3), 0,
         0);
    flat("subsampled_colour.exr", EXR_COMPRESSION_ZIPS, sub, 2, box(0, 0, 3, 3), box(0, 0, 3, 3),
         0, 0);
    flat("tiled_zip.exr", EXR_COMPRESSION_ZIP, zf, 1, box(0, 0, 9, 9), box(1, 2, 9, 8), 4, 3);
    flat("tiled_rle_half.exr", EXR_COMPRESSION_RLE, zh, 1, box(0, 0, 4, 4), box(0, 0, 4, 4), 2, 2);
    multipart();
    multiview();
    deep("deep_none.exr", EXR_COMPRESSION_NONE);
    deep("deep_zips.exr", EXR_COMPRESSION_ZIPS);
    deep("deep_rle.exr", EXR_COMPRESSION_RLE);
    deep_tiled();
    printf("seeds_exr: wrote %s (%d failed)\n", dir, failures);
    return failures != 0;
}
