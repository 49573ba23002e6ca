/* lt_exr.c - OpenEXR writer (scanline, named HALF/FLOAT channels, atomic temp + rename) and depth
 * reader (scanline/tiled flat parts, multi-part and multi-view files read by part or view, deep
 * scanline front-most sample) over OpenEXR's C API, OpenEXRCore 3.1 (Debian). The library's file
 * I/O is replaced by pread/pwrite callbacks on our own descriptor, so open errors carry errno and
 * library messages are captured for our error text instead of going to stderr. Host only;
 * docs/io.md.
 */
#include "io/lt_exr.h"
#include "io/lt_tmpfiles.h"

/* openexr_attr.h uses anonymous structs and unions (C11); keep -Wpedantic for our own code. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"
#include <openexr.h>
#pragma GCC diagnostic pop

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- errors and I/O callbacks ---------------------------------------------------------------- */

/* Per-context I/O state, handed to the library as its user data. */
typedef struct exr_io {
    int fd;        /* file read or written */
    int64_t size;  /* size of the file read, bytes */
    int err_no;    /* errno of the first failed pread/pwrite, 0 if none */
    char msg[256]; /* first message the library reported for this context */
} exr_io_t;

static void on_lib_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    void *ud = NULL;
    exr_io_t *io;
    if (exr_get_user_data(ctxt, &ud) != EXR_ERR_SUCCESS || ud == NULL)
        return;
    io = (exr_io_t *)ud;
    if (io->msg[0] == '\0')
        (void)snprintf(io->msg, sizeof io->msg, "%s",
                       msg != NULL ? msg : exr_get_default_error_message(code));
}

/* Text for a failed library call: the captured message, else the library's text for rv. */
static const char *lib_text(const exr_io_t *io, exr_result_t rv)
{
    if (io->err_no != 0)
        return strerror(io->err_no);
    if (io->msg[0] != '\0')
        return io->msg;
    return exr_get_default_error_message(rv);
}

static int64_t io_read(exr_const_context_t ctxt, void *ud, void *buffer, uint64_t sz,
                       uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    exr_io_t *io = (exr_io_t *)ud;
    uint8_t *p = (uint8_t *)buffer;
    uint64_t got = 0;
    (void)ctxt;
    (void)error_cb;
    while (got < sz) {
        ssize_t r = pread(io->fd, p + got, (size_t)(sz - got), (off_t)(offset + got));
        if (r < 0) {
            if (errno == EINTR)
                continue;
            if (io->err_no == 0)
                io->err_no = errno;
            return -1;
        }
        if (r == 0)
            break; /* end of file: a short count, the library reports the truncation */
        got += (uint64_t)r;
    }
    return (int64_t)got;
}

static int64_t io_size(exr_const_context_t ctxt, void *ud)
{
    struct stat st;
    (void)ctxt;
    if (fstat(((exr_io_t *)ud)->fd, &st) != 0)
        return -1;
    return (int64_t)st.st_size;
}

static int64_t io_write(exr_const_context_t ctxt, void *ud, const void *buffer, uint64_t sz,
                        uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    exr_io_t *io = (exr_io_t *)ud;
    const uint8_t *p = (const uint8_t *)buffer;
    uint64_t put = 0;
    (void)ctxt;
    (void)error_cb;
    while (put < sz) {
        ssize_t r = pwrite(io->fd, p + put, (size_t)(sz - put), (off_t)(offset + put));
        if (r < 0) {
            if (errno == EINTR)
                continue;
            if (io->err_no == 0)
                io->err_no = errno;
            return -1;
        }
        put += (uint64_t)r;
    }
    return (int64_t)put;
}

static exr_context_initializer_t make_init(exr_io_t *io)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_lib_error;
    init.user_data = io;
    init.read_fn = io_read;
    init.size_fn = io_size;
    init.write_fn = io_write;
    /* The library's own limits sit above ours; ours are checked with a clearer message. */
    init.max_image_width = 0;
    init.max_image_height = 0;
    return init;
}

/* ---- half <-> float -------------------------------------------------------------------------- */

static uint32_t f32_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static float f32_from_bits(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

uint16_t lt_exr_half_from_float(float f)
{
    uint32_t u = f32_bits(f);
    uint32_t sign = (u >> 16) & 0x8000u;
    uint32_t exp = (u >> 23) & 0xFFu;
    uint32_t man = u & 0x7FFFFFu;
    uint32_t r;
    if (exp == 0xFFu) { /* inf, or NaN kept quiet with its top payload bits */
        if (man == 0)
            return (uint16_t)(sign | 0x7C00u);
        return (uint16_t)(sign | 0x7E00u | (man >> 13));
    }
    /* |f| >= 65520 rounds to inf (65504 is the largest half; 65520 is the half-way point). */
    if (exp > 142u || (exp == 142u && man >= 0x7FF000u))
        return (uint16_t)(sign | 0x7C00u);
    if (exp >= 113u) {
        /* normal half: keep 10 mantissa bits, round the 13 dropped bits to nearest even; a carry
         * out of the mantissa correctly bumps the exponent */
        r = ((exp - 112u) << 10) | (man >> 13);
        if ((man & 0x1FFFu) > 0x1000u || ((man & 0x1FFFu) == 0x1000u && (r & 1u)))
            r++;
        return (uint16_t)(sign | r);
    }
    if (exp < 102u) /* below half the smallest subnormal (2^-25): rounds to zero */
        return (uint16_t)sign;
    {
        /* subnormal half: value = m * 2^-24; shift the 24-bit significand right so that the
         * unit is 2^-24, rounding the dropped bits to nearest even */
        uint32_t sig = man | 0x800000u;
        uint32_t shift = 126u - exp; /* exp 113 -> 13 ... exp 102 -> 24 */
        uint32_t half = 1u << (shift - 1u);
        uint32_t rest = sig & ((1u << shift) - 1u);
        r = sig >> shift;
        if (rest > half || (rest == half && (r & 1u)))
            r++;
        return (uint16_t)(sign | r);
    }
}

float lt_exr_half_to_float(uint16_t h)
{
    uint32_t sign = ((uint32_t)h & 0x8000u) << 16;
    uint32_t exp = ((uint32_t)h >> 10) & 0x1Fu;
    uint32_t man = (uint32_t)h & 0x3FFu;
    if (exp == 0x1Fu)
        return f32_from_bits(sign | 0x7F800000u | (man << 13));
    if (exp != 0)
        return f32_from_bits(sign | ((exp + 112u) << 23) | (man << 13));
    if (man == 0)
        return f32_from_bits(sign);
    {
        /* subnormal: man * 2^-24, exact in float (ldexpf keeps -Wdouble-promotion quiet) */
        float v = ldexpf((float)man, -24);
        return sign != 0 ? -v : v;
    }
}

/* ---- writer ---------------------------------------------------------------------------------- */

static int check_image(const char *path, const lt_exr_image_t *img, lt_diag_t *diag)
{
    int i, j;
    int64_t dw, dh;
    if (img->width < 1 || img->height < 1 || img->width > LT_EXR_MAX_DIM ||
        img->height > LT_EXR_MAX_DIM) {
        lt_diag_fail(diag, "%s: image %dx%d outside 1..LT_EXR_MAX_DIM %d", path, (int)img->width,
                     (int)img->height, LT_EXR_MAX_DIM);
        return -1;
    }
    dw = img->display_w != 0 ? img->display_w : (int64_t)img->x0 + img->width;
    dh = img->display_h != 0 ? img->display_h : (int64_t)img->y0 + img->height;
    if (dw < 1 || dh < 1 || dw > INT32_MAX || dh > INT32_MAX ||
        (int64_t)img->x0 + img->width - 1 > INT32_MAX ||
        (int64_t)img->y0 + img->height - 1 > INT32_MAX) {
        lt_diag_fail(diag, "%s: display window %lldx%lld or data window origin (%d,%d) invalid",
                     path, (long long)dw, (long long)dh, (int)img->x0, (int)img->y0);
        return -1;
    }
    if (img->nchannels < 1 || img->nchannels > LT_EXR_MAX_CHANNELS || img->channels == NULL) {
        lt_diag_fail(diag, "%s: %d channels (need 1..LT_EXR_MAX_CHANNELS %d)", path,
                     img->nchannels, LT_EXR_MAX_CHANNELS);
        return -1;
    }
    if (img->compression != LT_EXR_COMP_ZIP && img->compression != LT_EXR_COMP_ZIPS &&
        img->compression != LT_EXR_COMP_NONE) {
        lt_diag_fail(diag, "%s: unknown compression %d", path, (int)img->compression);
        return -1;
    }
    for (i = 0; i < img->nchannels; i++) {
        const lt_exr_channel_t *c = &img->channels[i];
        size_t n = c->name != NULL ? strlen(c->name) : 0;
        if (n == 0 || n > LT_EXR_MAX_NAME) {
            lt_diag_fail(diag, "%s: channel %d: name length %zu (need 1..LT_EXR_MAX_NAME %d)",
                         path, i, n, LT_EXR_MAX_NAME);
            return -1;
        }
        if (c->type != LT_EXR_HALF && c->type != LT_EXR_FLOAT) {
            lt_diag_fail(diag, "%s: channel '%s': type %d (write HALF or FLOAT)", path, c->name,
                         (int)c->type);
            return -1;
        }
        if (c->data == NULL) {
            lt_diag_fail(diag, "%s: channel '%s' has no data", path, c->name);
            return -1;
        }
        for (j = 0; j < i; j++)
            if (strcmp(img->channels[j].name, c->name) == 0) {
                lt_diag_fail(diag, "%s: channel '%s' given twice", path, c->name);
                return -1;
            }
    }
    return 0;
}

/* Encode every chunk of the header-complete context. halfs[i] holds channel i as binary16 (or
 * NULL for FLOAT channels). */
/* The library's own compression step, wrapped by store_smaller. */
static exr_result_t (*lib_compress)(exr_encode_pipeline_t *enc);

/* A chunk is stored compressed only when that makes it smaller: a reader (OpenEXR's too) takes a
 * chunk whose stored size equals its raw size as uncompressed, and OpenEXRCore 3.1 stores the
 * zlib bytes when they are exactly as long as the raw ones. Then the raw bytes go to the file.
 * (The compressed buffer holds at least the raw size: exr_compress_max_buffer_size.) */
static exr_result_t store_smaller(exr_encode_pipeline_t *enc)
{
    exr_result_t rv = lib_compress(enc);
    if (rv != EXR_ERR_SUCCESS || enc->compressed_bytes < enc->packed_bytes)
        return rv;
    if (enc->compressed_alloc_size < enc->packed_bytes || enc->compressed_buffer == NULL)
        return EXR_ERR_OUT_OF_MEMORY;
    memcpy(enc->compressed_buffer, enc->packed_buffer, (size_t)enc->packed_bytes);
    enc->compressed_bytes = enc->packed_bytes;
    return EXR_ERR_SUCCESS;
}

static exr_result_t write_chunks(exr_context_t ctx, const lt_exr_image_t *img,
                                 uint16_t *const *halfs)
{
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    exr_chunk_info_t ci;
    exr_result_t rv = EXR_ERR_SUCCESS;
    int32_t lines = 1, y;
    int inited = 0, c, i;
    size_t w = (size_t)img->width;

    rv = exr_get_scanlines_per_chunk(ctx, 0, &lines);
    for (y = img->y0; rv == EXR_ERR_SUCCESS && y < img->y0 + img->height; y += lines) {
        rv = exr_write_scanline_chunk_info(ctx, 0, y, &ci);
        if (rv != EXR_ERR_SUCCESS)
            break;
        rv = inited ? exr_encoding_update(ctx, 0, &ci, &enc)
                    : exr_encoding_initialize(ctx, 0, &ci, &enc);
        if (rv != EXR_ERR_SUCCESS)
            break;
        inited = 1;
        for (c = 0; c < enc.channel_count; c++) {
            exr_coding_channel_info_t *ec = &enc.channels[c];
            size_t row = (size_t)(ci.start_y - img->y0);
            for (i = 0; i < img->nchannels; i++)
                if (strcmp(img->channels[i].name, ec->channel_name) == 0)
                    break;
            if (i == img->nchannels) /* cannot happen: the header was made from img */
                return EXR_ERR_INVALID_ARGUMENT;
            if (halfs[i] != NULL) {
                ec->encode_from_ptr = (const uint8_t *)(halfs[i] + row * w);
                ec->user_bytes_per_element = 2;
                ec->user_data_type = (uint16_t)EXR_PIXEL_HALF;
                ec->user_pixel_stride = 2;
                ec->user_line_stride = (int32_t)(w * 2);
            } else {
                ec->encode_from_ptr = (const uint8_t *)(img->channels[i].data + row * w);
                ec->user_bytes_per_element = 4;
                ec->user_data_type = (uint16_t)EXR_PIXEL_FLOAT;
                ec->user_pixel_stride = 4;
                ec->user_line_stride = (int32_t)(w * 4);
            }
        }
        rv = exr_encoding_choose_default_routines(ctx, 0, &enc);
        if (rv == EXR_ERR_SUCCESS && enc.compress_fn != NULL) {
            lib_compress = enc.compress_fn;
            enc.compress_fn = store_smaller;
        }
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_run(ctx, 0, &enc);
    }
    if (inited)
        (void)exr_encoding_destroy(ctx, &enc);
    return rv;
}

int lt_exr_write(const char *path, const lt_exr_image_t *img, lt_diag_t *diag)
{
    static const exr_compression_t comp_of[3] = {EXR_COMPRESSION_ZIP, EXR_COMPRESSION_ZIPS,
                                                 EXR_COMPRESSION_NONE};
    exr_io_t io;
    exr_context_initializer_t init;
    exr_context_t ctx = NULL;
    exr_attr_box2i_t disp, data;
    exr_attr_v2f_t swc;
    exr_result_t rv;
    uint16_t **halfs = NULL;
    char *tmp = NULL;
    const char *stage = "";
    const char *name; /* the output in messages (lt_tmp_target) */
    size_t n, k;
    int i, part = -1, longnames = 0, ok = 0;

    if (path == NULL || img == NULL) {
        lt_diag_fail(diag, "lt_exr_write: NULL %s", path == NULL ? "path" : "image");
        return -1;
    }
    name = lt_tmp_target(path);
    if (check_image(name, img, diag) != 0)
        return -1;

    /* HALF channels are rounded here (ties to even, documented) rather than by the library. */
    halfs = (uint16_t **)calloc((size_t)img->nchannels, sizeof *halfs);
    if (halfs == NULL) {
        lt_diag_fail(diag, "%s: out of memory", name);
        return -1;
    }
    n = (size_t)img->width * (size_t)img->height;
    for (i = 0; i < img->nchannels; i++) {
        if (img->channels[i].type != LT_EXR_HALF)
            continue;
        halfs[i] = (uint16_t *)malloc(n * sizeof(uint16_t));
        if (halfs[i] == NULL) {
            lt_diag_fail(diag, "%s: out of memory for channel '%s'", name, img->channels[i].name);
            goto done;
        }
        for (k = 0; k < n; k++)
            halfs[i][k] = lt_exr_half_from_float(img->channels[i].data[k]);
    }

    tmp = (char *)malloc(LT_TMP_PATH_MAX);
    if (tmp == NULL) {
        lt_diag_fail(diag, "%s: out of memory", name);
        goto done;
    }
    /* registered: a fatal signal removes it (io/lt_tmpfiles.h) */
    if (lt_tmp_begin(path, tmp, diag) != 0) {
        free(tmp);
        tmp = NULL;
        goto done;
    }
    memset(&io, 0, sizeof io);
    io.fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (io.fd < 0) {
        lt_diag_fail(diag, "%s: cannot create temporary file %s: %s", name, tmp, strerror(errno));
        goto done;
    }

    init = make_init(&io);
    stage = "start";
    rv = exr_start_write(&ctx, tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS) {
        stage = "add part";
        rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
    }
    data.min.x = img->x0;
    data.min.y = img->y0;
    data.max.x = img->x0 + img->width - 1;
    data.max.y = img->y0 + img->height - 1;
    disp.min.x = 0;
    disp.min.y = 0;
    disp.max.x = (img->display_w != 0 ? img->display_w : img->x0 + img->width) - 1;
    disp.max.y = (img->display_h != 0 ? img->display_h : img->y0 + img->height) - 1;
    swc.x = 0.0f;
    swc.y = 0.0f;
    if (rv == EXR_ERR_SUCCESS) {
        stage = "header";
        rv = exr_initialize_required_attr(ctx, part, &disp, &data, 1.0f, &swc, 1.0f,
                                          EXR_LINEORDER_INCREASING_Y,
                                          comp_of[img->compression]);
    }
    for (i = 0; rv == EXR_ERR_SUCCESS && i < img->nchannels; i++)
        longnames |= strlen(img->channels[i].name) > 31;
    if (rv == EXR_ERR_SUCCESS && longnames)
        rv = exr_set_longname_support(ctx, 1);
    for (i = 0; rv == EXR_ERR_SUCCESS && i < img->nchannels; i++) {
        stage = "channel list";
        rv = exr_add_channel(ctx, part, img->channels[i].name,
                             img->channels[i].type == LT_EXR_HALF ? EXR_PIXEL_HALF
                                                                  : EXR_PIXEL_FLOAT,
                             EXR_PERCEPTUALLY_LINEAR, 1, 1);
    }
    if (rv == EXR_ERR_SUCCESS) {
        stage = "writing the header";
        rv = exr_write_header(ctx);
    }
    if (rv == EXR_ERR_SUCCESS) {
        stage = "writing pixels";
        rv = write_chunks(ctx, img, halfs);
    }
    if (rv == EXR_ERR_SUCCESS) {
        stage = "finishing (chunk table)";
        rv = exr_finish(&ctx);
        ctx = NULL;
    }
    if (rv != EXR_ERR_SUCCESS) {
        lt_diag_fail(diag, "%s: OpenEXR %s failed: %s", name, stage, lib_text(&io, rv));
        goto done;
    }
    if (fsync(io.fd) != 0 || close(io.fd) != 0) {
        lt_diag_fail(diag, "%s: writing %s failed: %s", name, tmp, strerror(errno));
        io.fd = -1;
        goto done;
    }
    io.fd = -1;
    ok = lt_tmp_commit(tmp, path, diag) == 0; /* removes or forgets tmp */
    free(tmp);
    tmp = NULL;

done:
    if (ctx != NULL)
        (void)exr_finish(&ctx);
    if (tmp != NULL && io.fd >= 0)
        (void)close(io.fd);
    if (tmp != NULL)
        lt_tmp_discard(tmp);
    free(tmp);
    for (i = 0; i < img->nchannels; i++)
        free(halfs[i]);
    free(halfs);
    return ok ? 0 : -1;
}

/* ---- reader ---------------------------------------------------------------------------------- */

static int open_read(exr_context_t *ctx, exr_io_t *io, const char *path, lt_diag_t *diag)
{
    exr_context_initializer_t init;
    exr_result_t rv;
    struct stat st;
    *ctx = NULL;
    memset(io, 0, sizeof *io);
    io->fd = open(path, O_RDONLY);
    if (io->fd < 0) {
        lt_diag_fail(diag, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    if (fstat(io->fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        lt_diag_fail(diag, "%s: not a regular file", path);
        (void)close(io->fd);
        return -1;
    }
    io->size = (int64_t)st.st_size;
    init = make_init(io);
    rv = exr_start_read(ctx, path, &init);
    if (rv != EXR_ERR_SUCCESS) {
        lt_diag_fail(diag, "%s: not a readable OpenEXR file (%lld bytes): %s", path,
                     (long long)st.st_size, lib_text(io, rv));
        if (*ctx != NULL)
            (void)exr_finish(ctx);
        (void)close(io->fd);
        return -1;
    }
    return 0;
}

static void close_read(exr_context_t *ctx, exr_io_t *io)
{
    if (*ctx != NULL)
        (void)exr_finish(ctx);
    if (io->fd >= 0)
        (void)close(io->fd);
    io->fd = -1;
}

static int find_chan(const exr_attr_chlist_t *cl, const char *name)
{
    int i;
    for (i = 0; i < cl->num_channels; i++)
        if (strcmp(cl->entries[i].name.str, name) == 0)
            return i;
    return -1;
}

static int ends_with_dot_z(const char *s)
{
    size_t n = strlen(s);
    return n >= 2 && strcmp(s + n - 2, ".Z") == 0;
}

/* A string attribute of a part, or NULL. */
static const char *attr_str(exr_context_t ctx, int part, const char *name)
{
    const exr_attribute_t *a = NULL;
    if (exr_get_attribute_by_name(ctx, part, name, &a) != EXR_ERR_SUCCESS || a == NULL ||
        a->type != EXR_ATTR_STRING || a->string == NULL || a->string->str == NULL)
        return NULL;
    return a->string->str;
}

/* The `view` attribute of a part (multi-part multi-view files: the view the part holds), or NULL. */
static const char *part_view(exr_context_t ctx, int part)
{
    return attr_str(ctx, part, "view");
}

/* The multiView attribute of the first part that carries one, or NULL. */
static const exr_attr_string_vector_t *multiview(exr_context_t ctx, int nparts)
{
    int p;
    for (p = 0; p < nparts; p++) {
        const exr_attribute_t *a = NULL;
        if (exr_get_attribute_by_name(ctx, p, "multiView", &a) == EXR_ERR_SUCCESS && a != NULL &&
            a->type == EXR_ATTR_STRING_VECTOR && a->stringvector != NULL &&
            a->stringvector->n_strings > 0 && a->stringvector->strings != NULL)
            return a->stringvector;
    }
    return NULL;
}

/* The file's default view: the first entry of multiView, else the view of part 0, else NULL. */
static const char *file_default_view(exr_context_t ctx, int nparts)
{
    const exr_attr_string_vector_t *mv = multiview(ctx, nparts);
    if (mv != NULL && mv->strings[0].str != NULL)
        return mv->strings[0].str;
    return nparts > 0 ? part_view(ctx, 0) : NULL;
}

/* 1 when some part carries a `view` attribute. */
static int any_part_view(exr_context_t ctx, int nparts)
{
    int p;
    for (p = 0; p < nparts; p++)
        if (part_view(ctx, p) != NULL)
            return 1;
    return 0;
}

/* Views each_view walks at most (a file may name more; view_known sees them all). */
#define EXR_MAX_VIEWS 256

static int in_list(const char *const *l, int n, const char *s)
{
    int i;
    for (i = 0; i < n; i++)
        if (strcmp(l[i], s) == 0)
            return 1;
    return 0;
}

/* Call fn(s, arg) once per view of the file: multiView's entries, then the `view` attributes of
 * parts not among them, in part order, each name once, the first EXR_MAX_VIEWS names (so the
 * walk stays linear in the parts). Stops when fn returns nonzero; returns that value (0: all
 * seen). */
static int each_view(exr_context_t ctx, int nparts, int (*fn)(const char *, void *), void *arg)
{
    const exr_attr_string_vector_t *mv = multiview(ctx, nparts);
    const char *seen[EXR_MAX_VIEWS];
    int nmv = mv != NULL ? mv->n_strings : 0, nseen = 0, i, r;
    for (i = 0; i < nmv + nparts && nseen < EXR_MAX_VIEWS; i++) {
        const char *v = i < nmv ? mv->strings[i].str : part_view(ctx, i - nmv);
        if (v == NULL || in_list(seen, nseen, v))
            continue;
        seen[nseen++] = v;
        if ((r = fn(v, arg)) != 0)
            return r;
    }
    return 0;
}

/* 1 when the file names view v (multiView or a part's `view`). */
static int view_known(exr_context_t ctx, int nparts, const char *v)
{
    const exr_attr_string_vector_t *mv = multiview(ctx, nparts);
    int i;
    for (i = 0; mv != NULL && i < mv->n_strings; i++)
        if (mv->strings[i].str != NULL && strcmp(mv->strings[i].str, v) == 0)
            return 1;
    for (i = 0; i < nparts; i++)
        if (part_view(ctx, i) != NULL && strcmp(part_view(ctx, i), v) == 0)
            return 1;
    return 0;
}

/* Append s to the list in dst (size cap), "..." once it is full. */
static void list_add(char *dst, size_t cap, const char *s)
{
    size_t n = strlen(dst);
    if (n + 5 >= cap)
        return;
    if (n + strlen(s) + 6 >= cap) {
        (void)snprintf(dst + n, cap - n, "%s...", n > 0 ? " " : "");
        return;
    }
    (void)snprintf(dst + n, cap - n, "%s%s", n > 0 ? " " : "", s);
}

typedef struct strlist {
    char *dst;
    size_t cap;
} strlist_t;

static int view_add(const char *v, void *arg)
{
    strlist_t *l = (strlist_t *)arg;
    list_add(l->dst, l->cap, v);
    return 0;
}

/* The views of the file, space-separated ("" when it names none). */
static void list_views(exr_context_t ctx, int nparts, char *dst, size_t cap)
{
    strlist_t l;
    dst[0] = '\0';
    l.dst = dst;
    l.cap = cap;
    (void)each_view(ctx, nparts, view_add, &l);
}

/* 1 when a dot-separated component of name other than the last is v ("left.Z", "a.left.R"). */
static int names_view(const char *name, const char *v)
{
    size_t n = strlen(v);
    const char *s = name, *dot;
    while ((dot = strchr(s, '.')) != NULL) {
        if ((size_t)(dot - s) == n && strncmp(s, v, n) == 0)
            return 1;
        s = dot + 1;
    }
    return 0;
}

/* Resolve the depth channel of one part (rules in lt_exr.h); the index into cl, or -1. dv is the
 * file's default view (or NULL). *ambiguous is set when several "*.Z" channels exist and none is
 * preferred. */
static int pick_channel(const char *dv, const exr_attr_chlist_t *cl, const char *want,
                        int *ambiguous)
{
    char buf[LT_EXR_MAX_NAME + 8];
    int i, k, found = -1, nz = 0;
    *ambiguous = 0;
    if (want != NULL) {
        if ((k = find_chan(cl, want)) >= 0)
            return k;
        if (strlen(want) <= LT_EXR_MAX_NAME) {
            (void)snprintf(buf, sizeof buf, "%s.Z", want);
            if ((k = find_chan(cl, buf)) >= 0)
                return k;
        }
        if (dv != NULL && strcmp(dv, want) == 0)
            return find_chan(cl, "Z");
        return -1;
    }
    if ((k = find_chan(cl, "Z")) >= 0)
        return k;
    if ((k = find_chan(cl, "depth")) >= 0)
        return k;
    if (dv != NULL && strlen(dv) <= LT_EXR_MAX_NAME) {
        (void)snprintf(buf, sizeof buf, "%s.Z", dv);
        if ((k = find_chan(cl, buf)) >= 0)
            return k;
    }
    for (i = 0; i < cl->num_channels; i++)
        if (ends_with_dot_z(cl->entries[i].name.str)) {
            nz++;
            found = i;
        }
    if (nz > 1)
        *ambiguous = 1;
    return nz == 1 ? found : -1;
}

/* The depth channel of view v in a part that holds its views by channel name (a single-part
 * multi-view file): want (NULL: "Z", then "depth") as "<view>.<chan>" or "<layer>.<view>.<chan>"
 * for "<layer>.<chan>"; the default view's also unprefixed; a name that already names the view
 * as itself. The index into cl, or -1. */
static int pick_in_view(const exr_attr_chlist_t *cl, const char *want, const char *v,
                        int is_default)
{
    static const char *const picks[2] = {"Z", "depth"};
    char buf[2 * LT_EXR_MAX_NAME + 8];
    int i, k;
    for (i = 0; i < (want != NULL ? 1 : 2); i++) {
        const char *w = want != NULL ? want : picks[i];
        const char *dot = strrchr(w, '.');
        if (is_default && (k = find_chan(cl, w)) >= 0)
            return k;
        if (dot == NULL)
            (void)snprintf(buf, sizeof buf, "%s.%s", v, w);
        else
            (void)snprintf(buf, sizeof buf, "%.*s.%s.%s", (int)(dot - w), w, v, dot + 1);
        if ((k = find_chan(cl, buf)) >= 0)
            return k;
    }
    return want != NULL && names_view(want, v) ? find_chan(cl, want) : -1;
}

/* Error text for a channel that was not found (in scope, e.g. " in view 'left'"): the views, the
 * depth-like channels and the channels of every part (per part when there are several). */
static void describe_missing(exr_context_t ctx, int nparts, const char *path, const char *want,
                             int ambiguous, const char *scope, lt_diag_t *diag)
{
    char views[256] = "", depths[512] = "", all[640] = "", tag[48];
    int p, i, tagged;
    list_views(ctx, nparts, views, sizeof views);
    for (p = 0; p < nparts; p++) {
        const exr_attr_chlist_t *cl = NULL;
        const char *pv = part_view(ctx, p);
        if (exr_get_channels(ctx, p, &cl) != EXR_ERR_SUCCESS || cl == NULL)
            continue;
        (void)snprintf(tag, sizeof tag, "[part %d%s%.24s]", p, pv != NULL ? " " : "",
                       pv != NULL ? pv : "");
        if (nparts > 1)
            list_add(all, sizeof all, tag);
        for (i = 0, tagged = nparts < 2; i < cl->num_channels; i++) {
            const char *nm = cl->entries[i].name.str;
            list_add(all, sizeof all, nm);
            if (strcmp(nm, "Z") != 0 && strcmp(nm, "depth") != 0 && !ends_with_dot_z(nm))
                continue;
            if (!tagged)
                list_add(depths, sizeof depths, tag);
            tagged = 1;
            list_add(depths, sizeof depths, nm);
        }
    }
    if (want != NULL)
        lt_diag_fail(diag, "%s: no channel '%s' (nor '%s.Z')%s; views: %s; depth channels: %s; "
                     "channels: %s", path, want, want, scope, views[0] ? views : "(none)",
                     depths[0] ? depths : "(none)", all[0] ? all : "(none)");
    else
        lt_diag_fail(diag, "%s: %s%s; views: %s; depth channels: %s; channels: %s", path,
                     ambiguous ? "several depth channels, name one"
                               : "no depth channel (Z, depth, *.Z)",
                     scope, views[0] ? views : "(none)", depths[0] ? depths : "(none)",
                     all[0] ? all : "(none)");
}

/* What a read selected: the depth channel's part and index, the view, the colour's part. */
typedef struct exr_pick {
    int part;                    /* part of the depth channel */
    int chan;                    /* its index in cl */
    const exr_attr_chlist_t *cl; /* that part's channels */
    const char *view;            /* the view read, or NULL */
    int cpart;                   /* part of the colour channels, -1: none */
} exr_pick_t;

/* Whether part p (view pv) is searched in pass 0 or 1: --part: that part only; a view in a file
 * whose parts name views: its parts (pass 0), then the parts that name none (pass 1); else every
 * part (pass 0). */
static int searched(int p, const char *pv, int pass, int only, const char *v, int part_views)
{
    if (only >= 0)
        return pass == 0 && p == only;
    if (v == NULL || !part_views)
        return pass == 0;
    if (pass == 0)
        return pv != NULL && strcmp(pv, v) == 0;
    return pv == NULL;
}

/* The view the depth channel of a part without a `view` attribute belongs to: the view its name
 * carries ("left.Z"), else the default view, else NULL. */
typedef struct view_of {
    const char *name, *found;
} view_of_t;

static int view_in_name(const char *v, void *arg)
{
    view_of_t *w = (view_of_t *)arg;
    if (!names_view(w->name, v))
        return 0;
    w->found = v;
    return 1;
}

/* Choose the part and depth channel (rules in lt_exr.h). 0, or -1 with the message in diag. */
static int select_depth(exr_context_t ctx, int nparts, const char *channel,
                        const lt_exr_read_opts_t *o, exr_pick_t *pk, const char *path,
                        lt_diag_t *diag)
{
    const char *v = o->view, *dv = file_default_view(ctx, nparts), *pv;
    int part_views = any_part_view(ctx, nparts), named = v != NULL, pass, p, k = -1, amb = 0;
    int any_amb = 0;
    char scope[LT_EXR_MAX_NAME + 64] = "", views[256];
    memset(pk, 0, sizeof *pk);
    pk->part = pk->cpart = -1;
    if (o->part < -1 || o->part >= nparts)
        return lt_diag_fail(diag, "%s: part %d out of range: the file has %d part%s (0..%d)", path,
                            o->part, nparts, nparts == 1 ? "" : "s", nparts - 1);
    /* a channel that is no channel of the file but one of its views selects that view */
    if (v == NULL && channel != NULL && part_views && view_known(ctx, nparts, channel)) {
        for (p = 0; p < nparts && k < 0; p++) {
            const exr_attr_chlist_t *cl = NULL;
            if (exr_get_channels(ctx, p, &cl) == EXR_ERR_SUCCESS && cl != NULL)
                k = find_chan(cl, channel);
        }
        if (k < 0) {
            v = channel;
            channel = NULL;
            named = 1;
        }
        k = -1;
    }
    if (v != NULL && !view_known(ctx, nparts, v)) {
        list_views(ctx, nparts, views, sizeof views);
        return lt_diag_fail(diag, "%s: no view '%s'; views: %s%s%s", path, v,
                            views[0] ? views : "(none: the file names no views)",
                            dv != NULL ? "; default " : "", dv != NULL ? dv : "");
    }
    if (o->part >= 0 && v != NULL && (pv = part_view(ctx, o->part)) != NULL && strcmp(pv, v) != 0)
        return lt_diag_fail(diag, "%s: part %d holds view '%s', not '%s'", path, o->part, pv, v);
    if (v == NULL && o->part < 0 && part_views)
        v = dv; /* the default view: chooses parts, never renames channels */
    for (pass = 0; pass < 2 && k < 0; pass++)
        for (p = 0; p < nparts && k < 0; p++) {
            pv = part_view(ctx, p);
            if (!searched(p, pv, pass, o->part, v, part_views) ||
                exr_get_channels(ctx, p, &pk->cl) != EXR_ERR_SUCCESS || pk->cl == NULL)
                continue;
            if (named && pv == NULL)
                k = pick_in_view(pk->cl, channel, v, dv != NULL && strcmp(dv, v) == 0);
            else
                k = pick_channel(dv, pk->cl, channel, &amb);
            any_amb |= amb;
            pk->part = p;
        }
    if (k < 0) {
        if (o->part >= 0)
            (void)snprintf(scope, sizeof scope, " in part %d", o->part);
        else if (v != NULL && part_views)
            (void)snprintf(scope, sizeof scope, " in view '%s'%s", v,
                           named ? "" : " (the default view)");
        else if (v != NULL)
            (void)snprintf(scope, sizeof scope, " of view '%s'", v);
        describe_missing(ctx, nparts, path, channel, any_amb, scope, diag);
        return -1;
    }
    pk->chan = k;
    pk->view = part_view(ctx, pk->part);
    if (pk->view == NULL && named)
        pk->view = v;
    if (pk->view == NULL && dv != NULL) {
        view_of_t w;
        w.name = pk->cl->entries[k].name.str;
        w.found = dv;
        (void)each_view(ctx, nparts, view_in_name, &w);
        pk->view = w.found;
    }
    return 0;
}

/* Output targets of one read: up to 5 channel names (depth first) and their data-window rasters. */
typedef struct read_target {
    int n;                          /* channels to read, 1..5 */
    const char *name[5];            /* channel names; [0] = depth */
    float *dst[5];                  /* data-window rasters, W x H */
} read_target_t;

static int target_of(const read_target_t *t, const char *name)
{
    int i;
    for (i = 0; i < t->n; i++)
        if (strcmp(t->name[i], name) == 0)
            return i;
    return -1;
}

/* One value of channel bytes p (little endian in the file), as float32 (HALF converts exactly). */
static float raw_value(const uint8_t *p, uint16_t type)
{
    if (type == (uint16_t)EXR_PIXEL_HALF)
        return lt_exr_half_to_float((uint16_t)(p[0] | (p[1] << 8)));
    return f32_from_bits((uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
                         ((uint32_t)p[3] << 24));
}

/* Let the library read and decompress one chunk, without its unpack stage: OpenEXRCore 3.1.5
 * chooses its 3- and 4-channel HALF->FLOAT unpackers by the part's channel count rather than by
 * the channels asked for, and writes through NULL when only some are asked (seen on our own
 * 3-channel files). The decompressed bytes have the file's canonical layout, walked by callers. */
static exr_result_t decode_raw(exr_context_t ctx, int part, const exr_chunk_info_t *ci,
                               exr_decode_pipeline_t *dec, int *inited)
{
    exr_result_t rv;
    int c;
    rv = *inited ? exr_decoding_update(ctx, part, ci, dec)
                 : exr_decoding_initialize(ctx, part, ci, dec);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    *inited = 1;
    for (c = 0; c < dec->channel_count; c++)
        dec->channels[c].decode_to_ptr = NULL;
    rv = exr_decoding_choose_default_routines(ctx, part, dec);
    dec->unpack_and_convert_fn = NULL;
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_decoding_run(ctx, part, dec);
    return rv;
}

/* Read a flat (scanline or tiled) part into the data-window rasters of t. A decompressed chunk
 * holds, per line: per channel in file order: that line's values of the channel (subsampled
 * channels only on lines y with y % y_sampling == 0, with their own width). */
static int read_flat(exr_context_t ctx, int part, exr_storage_t st, const exr_attr_box2i_t *dw,
                     const read_target_t *t, exr_io_t *io, const char *path, lt_diag_t *diag)
{
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    exr_chunk_info_t ci;
    exr_result_t rv = EXR_ERR_SUCCESS;
    int32_t W = dw->max.x - dw->min.x + 1, H = dw->max.y - dw->min.y + 1;
    int32_t lines = 1, tw = 1, th = 1, ntx = 1, nty = 1, cx, cy, px = dw->min.x, py = dw->min.y;
    int32_t l, x;
    int inited = 0, c, ok = 0;
    long chunk = 0;
    const char *why = NULL;

    if (st == EXR_STORAGE_SCANLINE) {
        rv = exr_get_scanlines_per_chunk(ctx, part, &lines);
        if (rv == EXR_ERR_SUCCESS && lines < 1)
            rv = EXR_ERR_INVALID_ATTR;
        nty = rv == EXR_ERR_SUCCESS ? (H + lines - 1) / lines : 0;
    } else {
        rv = exr_get_tile_sizes(ctx, part, 0, 0, &tw, &th);
        if (rv == EXR_ERR_SUCCESS && (tw < 1 || th < 1))
            rv = EXR_ERR_INVALID_ATTR;
        ntx = rv == EXR_ERR_SUCCESS ? (W + tw - 1) / tw : 0;
        nty = rv == EXR_ERR_SUCCESS ? (H + th - 1) / th : 0;
    }
    if (rv != EXR_ERR_SUCCESS) {
        lt_diag_fail(diag, "%s: part %d: bad chunk layout: %s", path, part, lib_text(io, rv));
        return -1;
    }
    for (cy = 0; cy < nty && why == NULL; cy++) {
        for (cx = 0; cx < ntx && why == NULL; cx++, chunk++) {
            const uint8_t *buf;
            size_t off = 0, total;
            if (st == EXR_STORAGE_SCANLINE) {
                px = dw->min.x;
                py = dw->min.y + cy * lines;
                rv = exr_read_scanline_chunk_info(ctx, part, py, &ci);
            } else {
                px = dw->min.x + cx * tw;
                py = dw->min.y + cy * th;
                rv = exr_read_tile_chunk_info(ctx, part, cx, cy, 0, 0, &ci);
            }
            if (rv == EXR_ERR_SUCCESS &&
                (ci.width < 1 || ci.height < 1 || ci.width > W - (px - dw->min.x) ||
                 ci.height > H - (py - dw->min.y)))
                rv = EXR_ERR_CORRUPT_CHUNK;
            if (rv == EXR_ERR_SUCCESS)
                rv = decode_raw(ctx, part, &ci, &dec, &inited);
            if (rv != EXR_ERR_SUCCESS)
                goto bad;
            buf = (const uint8_t *)dec.unpacked_buffer;
            total = buf != NULL ? (size_t)ci.unpacked_size : 0;
            for (l = 0; l < ci.height && why == NULL; l++) {
                int32_t yabs = py + l;
                size_t row = (size_t)(py - dw->min.y + l) * (size_t)W + (size_t)(px - dw->min.x);
                for (c = 0; c < dec.channel_count; c++) {
                    const exr_coding_channel_info_t *dc = &dec.channels[c];
                    int32_t ys = dc->y_samples > 1 ? dc->y_samples : 1;
                    size_t bpe = (size_t)dc->bytes_per_element;
                    size_t bytes = (size_t)(dc->width > 0 ? dc->width : 0) * bpe;
                    int k;
                    if (dc->height == 0 || ((yabs % ys) + ys) % ys != 0)
                        continue;
                    if (bytes > total - off) {
                        why = "decompressed chunk shorter than its lines";
                        break;
                    }
                    k = target_of(t, dc->channel_name);
                    if (k >= 0) /* targets are 1x1 sampled: width == ci.width */
                        for (x = 0; x < dc->width; x++)
                            t->dst[k][row + (size_t)x] =
                                raw_value(buf + off + (size_t)x * bpe, dc->data_type);
                    off += bytes;
                }
            }
        }
    }
    if (why == NULL)
        ok = 1;
bad:
    if (why != NULL)
        lt_diag_fail(diag, "%s: part %d: pixel chunk %ld (at x %d, y %d) corrupt: %s", path, part,
                     chunk - 1, (int)px, (int)py, why);
    else if (!ok)
        lt_diag_fail(diag, "%s: part %d: pixel chunk %ld (at x %d, y %d) unreadable (truncated or "
                     "corrupt file?): %s", path, part, chunk, (int)px, (int)py, lib_text(io, rv));
    if (inited)
        (void)exr_decoding_destroy(ctx, &dec);
    return ok ? 0 : -1;
}

/* Read a deep scanline part: per pixel the sample with the least Z (NaN samples skipped; a pixel
 * whose samples are all NaN gets NaN), colour from that same sample. Pixels without samples keep
 * what the rasters were filled with. The library reads and decompresses each chunk; the sample
 * layout (per line: per channel in file order: per pixel: its samples) is walked here with every
 * offset checked against the decompressed size. */
static int read_deep(exr_context_t ctx, int part, const exr_attr_box2i_t *dw,
                     const read_target_t *t, exr_io_t *io, uint64_t *nsamples, const char *path,
                     lt_diag_t *diag)
{
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    exr_chunk_info_t ci;
    exr_result_t rv = EXR_ERR_SUCCESS;
    int32_t W = dw->max.x - dw->min.x + 1, H = dw->max.y - dw->min.y + 1;
    int32_t lines = 1, y = dw->min.y, l = 0, x;
    int inited = 0, c, ok = 0, zi = -1;
    const char *why = NULL;
    const exr_coding_channel_info_t *zc = NULL;
    size_t chan_off[64];
    int chan_tgt[64];

    *nsamples = 0;
    rv = exr_get_scanlines_per_chunk(ctx, part, &lines);
    if (rv == EXR_ERR_SUCCESS && lines < 1)
        rv = EXR_ERR_INVALID_ATTR;
    for (; rv == EXR_ERR_SUCCESS && y <= dw->max.y; y += lines) {
        const uint8_t *buf;
        const int32_t *counts;
        size_t off = 0, total;
        l = 0;
        rv = exr_read_scanline_chunk_info(ctx, part, y, &ci);
        if (rv == EXR_ERR_SUCCESS &&
            (ci.width != W || ci.height < 1 || ci.height > H - (y - dw->min.y)))
            rv = EXR_ERR_CORRUPT_CHUNK;
        if (rv == EXR_ERR_SUCCESS)
            rv = decode_raw(ctx, part, &ci, &dec, &inited);
        if (rv != EXR_ERR_SUCCESS)
            break;
        if (dec.channel_count > 64) {
            why = "more than 64 channels in a deep part";
            break;
        }
        buf = (const uint8_t *)dec.unpacked_buffer;
        counts = dec.sample_count_table;
        total = (size_t)ci.unpacked_size;
        if (counts == NULL) {
            why = "no sample count table";
            break;
        }
        zi = -1;
        for (c = 0; c < dec.channel_count; c++) {
            chan_tgt[c] = target_of(t, dec.channels[c].channel_name);
            if (chan_tgt[c] == 0)
                zi = c;
        }
        if (zi < 0) {
            why = "depth channel missing from the chunk";
            break;
        }
        zc = &dec.channels[zi];
        for (l = 0; l < ci.height && why == NULL; l++) {
            const int32_t *cnt = counts + (size_t)l * (size_t)W;
            size_t line_samples = (size_t)cnt[W - 1];
            size_t row = (size_t)(y - dw->min.y + l) * (size_t)W;
            /* Cumulative counts per line. OpenEXRCore 3.1 does not check that they never decrease
               (a raised count would walk past the line's samples): check every one here. */
            for (x = 0; x < W; x++) {
                int32_t prev = x == 0 ? 0 : cnt[x - 1];
                if (cnt[x] < prev) {
                    why = cnt[x] < 0 ? "negative sample count"
                                     : "sample counts decrease along the line";
                    break;
                }
            }
            if (why != NULL)
                break;
            for (c = 0; c < dec.channel_count; c++) {
                size_t bytes = line_samples * (size_t)dec.channels[c].bytes_per_element;
                if (bytes > total - off) {
                    why = "sample data shorter than its sample counts";
                    break;
                }
                chan_off[c] = off;
                off += bytes;
            }
            if (why != NULL)
                break;
            if (line_samples > 0 && buf == NULL) {
                why = "no sample data";
                break;
            }
            *nsamples += line_samples;
            for (x = 0; x < W; x++) {
                int32_t s0 = x == 0 ? 0 : cnt[x - 1], s1 = cnt[x], s, best = -1;
                float bz = 0.0f;
                if (s1 <= s0)
                    continue;
                for (s = s0; s < s1; s++) {
                    float v = raw_value(buf + chan_off[zi] +
                                             (size_t)s * (size_t)zc->bytes_per_element,
                                         zc->data_type);
                    if (isnan(v))
                        continue;
                    if (best < 0 || v < bz) {
                        best = s;
                        bz = v;
                    }
                }
                if (best < 0) { /* every sample NaN: a hole, kept as NaN */
                    t->dst[0][row + (size_t)x] = NAN;
                    continue;
                }
                for (c = 0; c < dec.channel_count; c++) {
                    const exr_coding_channel_info_t *dc = &dec.channels[c];
                    if (chan_tgt[c] < 0)
                        continue;
                    t->dst[chan_tgt[c]][row + (size_t)x] =
                        raw_value(buf + chan_off[c] + (size_t)best * (size_t)dc->bytes_per_element,
                                   dc->data_type);
                }
            }
        }
        if (why != NULL)
            break;
    }
    if (rv == EXR_ERR_SUCCESS && why == NULL)
        ok = 1;
    else if (why != NULL)
        lt_diag_fail(diag, "%s: part %d: deep chunk at y %d corrupt: %s", path, part,
                     (int)(y + l), why);
    else
        lt_diag_fail(diag, "%s: part %d: deep chunk at y %d unreadable (truncated or corrupt "
                     "file?): %s", path, part, (int)y, lib_text(io, rv));
    if (inited)
        (void)exr_decoding_destroy(ctx, &dec);
    return ok ? 0 : -1;
}

static const char *storage_name(exr_storage_t s)
{
    switch (s) {
    case EXR_STORAGE_SCANLINE:
        return "scanlineimage";
    case EXR_STORAGE_TILED:
        return "tiledimage";
    case EXR_STORAGE_DEEP_SCANLINE:
        return "deepscanline";
    case EXR_STORAGE_DEEP_TILED:
        return "deeptile";
    default:
        return "unknown";
    }
}

void lt_exr_depth_free(lt_exr_depth_t *d)
{
    int i;
    if (d == NULL)
        return;
    free(d->z);
    d->z = NULL;
    for (i = 0; i < 4; i++) {
        free(d->rgba[i]);
        d->rgba[i] = NULL;
    }
}

static void fill_f(float *p, size_t n, float v)
{
    size_t i;
    for (i = 0; i < n; i++)
        p[i] = v;
}

const char *lt_exr_compression_name(int c)
{
    static const char *const names[] = {"none", "rle", "zips", "zip", "piz", "pxr24",
                                        "b44",  "b44a", "dwaa", "dwab"};
    return c >= 0 && c < 10 ? names[c] : "unknown";
}

/* The most one byte of a chunk can unpack to, per compression (an upper bound, so that a header
 * cannot make the reader allocate and fill rasters that the file cannot hold): none 1; RLE 64
 * (a run of up to 128 bytes in 2); ZIP/ZIPS 1032 (deflate's own bound); PXR24 zlib over 24-bit
 * floats, 1376; PIZ 512 (Huffman codes of >= 1 bit for 16-bit values, runs up to 255 in a code
 * and 8 bits); B44/B44A 11 (a flat 4x4 block of halves in 3 bytes); DWAA/DWAB and anything else
 * 65536. */
static int64_t max_unpack_ratio(exr_compression_t c)
{
    switch (c) {
    case EXR_COMPRESSION_NONE:
        return 1;
    case EXR_COMPRESSION_RLE:
        return 64;
    case EXR_COMPRESSION_ZIPS:
    case EXR_COMPRESSION_ZIP:
        return 1032;
    case EXR_COMPRESSION_PXR24:
        return 1376;
    case EXR_COMPRESSION_PIZ:
        return 512;
    case EXR_COMPRESSION_B44:
    case EXR_COMPRESSION_B44A:
        return 11;
    default:
        return 65536;
    }
}

int lt_exr_display_check(const char *path, const lt_exr_box_t *disp, lt_diag_t *diag)
{
    /* in 64 bits: x1 - x0 + 1 of a stored window can exceed INT32_MAX */
    int64_t w = (int64_t)disp->x1 - disp->x0 + 1, h = (int64_t)disp->y1 - disp->y0 + 1;
    if (w < 1 || h < 1 || w > LT_EXR_MAX_DIM || h > LT_EXR_MAX_DIM)
        return lt_diag_fail(diag, "%s: display window %lldx%lld outside 1..LT_EXR_MAX_DIM %d",
                            path, (long long)w, (long long)h, LT_EXR_MAX_DIM);
    return 0;
}

int lt_exr_camera_check(const char *path, const lt_exr_box_t *data, const lt_exr_box_t *disp,
                        lt_diag_t *diag)
{
    if (lt_exr_display_check(path, disp, diag) != 0)
        return -1;
    if (data->x1 < disp->x0 || data->x0 > disp->x1 || data->y1 < disp->y0 || data->y0 > disp->y1)
        return lt_diag_fail(diag, "%s: data window (%ld,%ld)-(%ld,%ld) lies wholly outside the "
                            "display window (%ld,%ld)-(%ld,%ld)", path, (long)data->x0,
                            (long)data->y0, (long)data->x1, (long)data->y1, (long)disp->x0,
                            (long)disp->y0, (long)disp->x1, (long)disp->y1);
    return 0;
}

/* The depth part's storage and windows, checked against what is read (rules in lt_exr.h).
 * 0, or -1 with the message in diag. */
static int check_part(exr_context_t ctx, int part, const exr_attr_chlist_entry_t *ze,
                      const lt_exr_read_opts_t *o, exr_storage_t *st, exr_attr_box2i_t *dw,
                      exr_attr_box2i_t *disp, exr_io_t *io, const char *path, lt_diag_t *diag)
{
    int64_t W, H;
    if (exr_get_storage(ctx, part, st) != EXR_ERR_SUCCESS ||
        exr_get_data_window(ctx, part, dw) != EXR_ERR_SUCCESS ||
        exr_get_display_window(ctx, part, disp) != EXR_ERR_SUCCESS)
        return lt_diag_fail(diag, "%s: part %d: missing storage type or windows: %s", path, part,
                            lib_text(io, EXR_ERR_MISSING_REQ_ATTR));
    W = (int64_t)dw->max.x - dw->min.x + 1;
    H = (int64_t)dw->max.y - dw->min.y + 1;
    if (W < 1 || H < 1 || W > LT_EXR_MAX_DIM || H > LT_EXR_MAX_DIM)
        return lt_diag_fail(diag, "%s: data window %lldx%lld outside 1..LT_EXR_MAX_DIM %d", path,
                            (long long)W, (long long)H, LT_EXR_MAX_DIM);
    if (o->window == LT_EXR_WINDOW_DISPLAY) {
        lt_exr_box_t b;
        b.x0 = disp->min.x;
        b.y0 = disp->min.y;
        b.x1 = disp->max.x;
        b.y1 = disp->max.y;
        if (lt_exr_display_check(path, &b, diag) != 0)
            return -1;
    }
    if (ze->pixel_type != EXR_PIXEL_HALF && ze->pixel_type != EXR_PIXEL_FLOAT)
        return lt_diag_fail(diag, "%s: channel '%s' is UINT; a depth channel must be HALF or "
                            "FLOAT", path, ze->name.str);
    {
        /* the depth channel's bytes (a deep part's per-pixel sample counts: 4 bytes) must fit in
         * what the file's chunks can unpack to, before any raster is allocated */
        exr_compression_t comp = EXR_COMPRESSION_NONE;
        int64_t bpp = ze->pixel_type == EXR_PIXEL_HALF && *st != EXR_STORAGE_DEEP_SCANLINE ? 2 : 4;
        int64_t ratio;
        (void)exr_get_compression(ctx, part, &comp);
        ratio = max_unpack_ratio(comp);
        if (W * H * bpp > io->size * ratio)
            return lt_diag_fail(diag, "%s: part %d: the header's data window %lldx%lld asks for "
                                "%lld bytes of channel '%s', but the file's %lld bytes of %s "
                                "data can unpack to at most %lld: truncated, or a wrong header",
                                path, part, (long long)W, (long long)H, (long long)(W * H * bpp),
                                ze->name.str, (long long)io->size, lt_exr_compression_name((int)comp),
                                (long long)(io->size * ratio));
    }
    if (ze->x_sampling != 1 || ze->y_sampling != 1)
        return lt_diag_fail(diag, "%s: channel '%s' is subsampled %dx%d; only 1x1 sampling is "
                            "read", path, ze->name.str, (int)ze->x_sampling, (int)ze->y_sampling);
    if (*st == EXR_STORAGE_DEEP_TILED)
        return lt_diag_fail(diag, "%s: part %d is a deep tiled image (deeptile); only deep "
                            "scanline images are read (front-most sample)", path, part);
    if (*st == EXR_STORAGE_DEEP_SCANLINE && o->deep != LT_EXR_DEEP_FRONT)
        return lt_diag_fail(diag, "%s: part %d is a deep image (deepscanline: a variable number "
                            "of samples per pixel); read its front-most sample per pixel (least "
                            "Z): lanetrace reproject --deep-front, LT_EXR_DEEP_FRONT in the API",
                            path, part);
    if (*st != EXR_STORAGE_SCANLINE && *st != EXR_STORAGE_TILED &&
        *st != EXR_STORAGE_DEEP_SCANLINE)
        return lt_diag_fail(diag, "%s: part %d: unsupported storage %s", path, part,
                            storage_name(*st));
    return 0;
}

/* Index of colour channel name in cl when it can be read as float32 1x1 (else -1: counts as
 * absent, documented). */
static int color_chan(const exr_attr_chlist_t *cl, const char *name)
{
    int k = find_chan(cl, name);
    if (k < 0 || cl->entries[k].pixel_type == EXR_PIXEL_UINT || cl->entries[k].x_sampling != 1 ||
        cl->entries[k].y_sampling != 1)
        return -1;
    return k;
}

static int has_rgb(const exr_attr_chlist_t *cl, char cname[4][LT_EXR_MAX_NAME + 2])
{
    return color_chan(cl, cname[0]) >= 0 || color_chan(cl, cname[1]) >= 0 ||
           color_chan(cl, cname[2]) >= 0;
}

/* The part to read colour from: the depth's own part when it has <prefix>R, G or B; else (no
 * --part, a flat depth part) the first other flat part of the same view (or, like the depth's,
 * of none) with the same data window that has them. -1: none. */
static int color_part(exr_context_t ctx, int nparts, const exr_pick_t *pk, exr_storage_t st,
                      const exr_attr_box2i_t *dw, int only, char cname[4][LT_EXR_MAX_NAME + 2])
{
    const char *pv = part_view(ctx, pk->part);
    int p;
    if (has_rgb(pk->cl, cname))
        return pk->part;
    if (only >= 0 || st == EXR_STORAGE_DEEP_SCANLINE)
        return -1;
    for (p = 0; p < nparts; p++) {
        const char *qv = part_view(ctx, p);
        const exr_attr_chlist_t *cl = NULL;
        exr_storage_t qs;
        exr_attr_box2i_t qd;
        if (p == pk->part || (pv == NULL) != (qv == NULL) ||
            (pv != NULL && strcmp(pv, qv) != 0) ||
            exr_get_storage(ctx, p, &qs) != EXR_ERR_SUCCESS ||
            (qs != EXR_STORAGE_SCANLINE && qs != EXR_STORAGE_TILED) ||
            exr_get_data_window(ctx, p, &qd) != EXR_ERR_SUCCESS || qd.min.x != dw->min.x ||
            qd.min.y != dw->min.y || qd.max.x != dw->max.x || qd.max.y != dw->max.y ||
            exr_get_channels(ctx, p, &cl) != EXR_ERR_SUCCESS || cl == NULL || !has_rgb(cl, cname))
            continue;
        return p;
    }
    return -1;
}

/* Colour (opts->color): <prefix>R G B A of the depth's layer (prefix: the depth channel's name up
 * to its last dot) from color_part's part, as targets of t (the depth's part) or tc (another
 * part, its index in pk->cpart); slot[i] = raster index of R, G, B, A (t's first, then tc's) or
 * -1. */
static void color_targets(exr_context_t ctx, int nparts, exr_pick_t *pk, exr_storage_t st,
                          const exr_attr_box2i_t *dw, int only,
                          char cname[4][LT_EXR_MAX_NAME + 2], read_target_t *t,
                          read_target_t *tc, int slot[4])
{
    static const char *const rgba_base[4] = {"R", "G", "B", "A"};
    const char *zn = pk->cl->entries[pk->chan].name.str;
    const char *dot = strrchr(zn, '.');
    size_t prefix = dot != NULL ? (size_t)(dot - zn + 1) : 0;
    const exr_attr_chlist_t *cl = NULL;
    read_target_t *dst;
    int i;
    for (i = 0; i < 4; i++)
        slot[i] = -1;
    if (prefix > LT_EXR_MAX_NAME - 1)
        return;
    for (i = 0; i < 4; i++) {
        memcpy(cname[i], zn, prefix);
        (void)strcpy(cname[i] + prefix, rgba_base[i]);
    }
    pk->cpart = color_part(ctx, nparts, pk, st, dw, only, cname);
    if (pk->cpart < 0 || exr_get_channels(ctx, pk->cpart, &cl) != EXR_ERR_SUCCESS || cl == NULL) {
        pk->cpart = -1;
        return;
    }
    dst = pk->cpart == pk->part ? t : tc;
    for (i = 0; i < 4; i++) {
        if (color_chan(cl, cname[i]) < 0)
            continue;
        slot[i] = dst == t ? t->n : t->n + tc->n;
        dst->name[dst->n++] = cname[i];
    }
}

/* Copy the data-window rasters win[0..n-1] into display-window rasters (outside: fill for [0],
 * 0 for colour), in dd[0..n-1]. 0, or -1 when out of memory (nothing left allocated). */
static int to_display(float *const *win, int n, const exr_attr_box2i_t *dw,
                      const exr_attr_box2i_t *disp, float fill, float **dd)
{
    int64_t W = (int64_t)dw->max.x - dw->min.x + 1;
    int64_t dispW = (int64_t)disp->max.x - disp->min.x + 1;
    int64_t dispH = (int64_t)disp->max.y - disp->min.y + 1;
    int64_t ix0 = dw->min.x > disp->min.x ? dw->min.x : disp->min.x;
    int64_t iy0 = dw->min.y > disp->min.y ? dw->min.y : disp->min.y;
    int64_t ix1 = dw->max.x < disp->max.x ? dw->max.x : disp->max.x;
    int64_t iy1 = dw->max.y < disp->max.y ? dw->max.y : disp->max.y;
    int64_t yy;
    int i, j;
    for (i = 0; i < n; i++) {
        dd[i] = (float *)malloc((size_t)dispW * (size_t)dispH * sizeof(float));
        if (dd[i] == NULL) {
            for (j = 0; j < i; j++) {
                free(dd[j]);
                dd[j] = NULL;
            }
            return -1;
        }
        fill_f(dd[i], (size_t)dispW * (size_t)dispH, i == 0 ? fill : 0.0f);
        for (yy = iy0; ix0 <= ix1 && yy <= iy1; yy++)
            memcpy(dd[i] + (size_t)(yy - disp->min.y) * (size_t)dispW +
                       (size_t)(ix0 - disp->min.x),
                   win[i] + (size_t)(yy - dw->min.y) * (size_t)W + (size_t)(ix0 - dw->min.x),
                   (size_t)(ix1 - ix0 + 1) * sizeof(float));
    }
    return 0;
}

int lt_exr_read_depth(const char *path, const char *channel, const lt_exr_read_opts_t *opts,
                      lt_exr_depth_t *out, lt_diag_t *diag)
{
    static const lt_exr_read_opts_t defaults = LT_EXR_READ_OPTS_DEFAULT;
    lt_exr_read_opts_t o = opts != NULL ? *opts : defaults;
    exr_context_t ctx = NULL;
    exr_io_t io;
    exr_storage_t st = EXR_STORAGE_SCANLINE, cst = EXR_STORAGE_SCANLINE;
    exr_attr_box2i_t dw, disp;
    exr_pick_t pk;
    read_target_t t, tc;
    char cname[4][LT_EXR_MAX_NAME + 2];
    float *win[5] = {NULL, NULL, NULL, NULL, NULL}, *dd[5] = {NULL, NULL, NULL, NULL, NULL};
    float **ras = win;
    int nparts = 0, i, ok = 0, slot[4] = {-1, -1, -1, -1};
    int64_t W, H;
    uint64_t nsamples = 0;
    const exr_attr_chlist_entry_t *ze;

    if (out == NULL || path == NULL) {
        lt_diag_fail(diag, "lt_exr_read_depth: NULL %s", path == NULL ? "path" : "output");
        return -1;
    }
    memset(out, 0, sizeof *out);
    out->color_part = -1;
    if (open_read(&ctx, &io, path, diag) != 0)
        return -1;
    if (exr_get_count(ctx, &nparts) != EXR_ERR_SUCCESS || nparts < 1) {
        lt_diag_fail(diag, "%s: no parts", path);
        goto done;
    }
    if (select_depth(ctx, nparts, channel, &o, &pk, path, diag) != 0)
        goto done;
    ze = &pk.cl->entries[pk.chan];
    if (check_part(ctx, pk.part, ze, &o, &st, &dw, &disp, &io, path, diag) != 0)
        goto done;
    W = (int64_t)dw.max.x - dw.min.x + 1;
    H = (int64_t)dw.max.y - dw.min.y + 1;

    /* the depth channel and, when asked, R G B A of its layer (its part or one of its view) */
    memset(&t, 0, sizeof t);
    memset(&tc, 0, sizeof tc);
    t.n = 1;
    t.name[0] = ze->name.str;
    if (o.color)
        color_targets(ctx, nparts, &pk, st, &dw, o.part, cname, &t, &tc, slot);
    for (i = 0; i < t.n + tc.n; i++) {
        win[i] = (float *)malloc((size_t)W * (size_t)H * sizeof(float));
        if (win[i] == NULL) {
            lt_diag_fail(diag, "%s: out of memory for %lldx%lld pixels", path, (long long)W,
                         (long long)H);
            goto done;
        }
        fill_f(win[i], (size_t)W * (size_t)H, i == 0 ? o.fill : 0.0f);
        if (i < t.n)
            t.dst[i] = win[i];
        else
            tc.dst[i - t.n] = win[i];
    }
    if (st == EXR_STORAGE_DEEP_SCANLINE) {
        if (read_deep(ctx, pk.part, &dw, &t, &io, &nsamples, path, diag) != 0)
            goto done;
    } else if (read_flat(ctx, pk.part, st, &dw, &t, &io, path, diag) != 0) {
        goto done;
    }
    if (tc.n > 0) { /* colour from another part of the view (color_part checked its storage) */
        (void)exr_get_storage(ctx, pk.cpart, &cst);
        if (read_flat(ctx, pk.cpart, cst, &dw, &tc, &io, path, diag) != 0)
            goto done;
    }
    if (o.window == LT_EXR_WINDOW_DISPLAY) {
        if (to_display(win, t.n + tc.n, &dw, &disp, o.fill, dd) != 0) {
            lt_diag_fail(diag, "%s: out of memory for %lldx%lld pixels", path,
                         (long long)disp.max.x - disp.min.x + 1,
                         (long long)disp.max.y - disp.min.y + 1);
            goto done;
        }
        ras = dd;
        out->width = (int32_t)((int64_t)disp.max.x - disp.min.x + 1);
        out->height = (int32_t)((int64_t)disp.max.y - disp.min.y + 1);
        out->x0 = disp.min.x;
        out->y0 = disp.min.y;
    } else {
        out->width = (int32_t)W;
        out->height = (int32_t)H;
        out->x0 = dw.min.x;
        out->y0 = dw.min.y;
    }
    out->z = ras[0];
    ras[0] = NULL;
    for (i = 0; i < 4; i++)
        if (slot[i] >= 0) {
            out->rgba[i] = ras[slot[i]];
            ras[slot[i]] = NULL;
        }
    out->data_window.x0 = dw.min.x;
    out->data_window.y0 = dw.min.y;
    out->data_window.x1 = dw.max.x;
    out->data_window.y1 = dw.max.y;
    out->display_window.x0 = disp.min.x;
    out->display_window.y0 = disp.min.y;
    out->display_window.x1 = disp.max.x;
    out->display_window.y1 = disp.max.y;
    out->z_type = ze->pixel_type == EXR_PIXEL_HALF ? LT_EXR_HALF : LT_EXR_FLOAT;
    out->part = pk.part;
    out->color_part = pk.cpart;
    out->deep = st == EXR_STORAGE_DEEP_SCANLINE;
    out->deep_samples = nsamples;
    (void)snprintf(out->channel, sizeof out->channel, "%s", ze->name.str);
    (void)snprintf(out->view, sizeof out->view, "%s", pk.view != NULL ? pk.view : "");
    ok = 1;

done:
    for (i = 0; i < 5; i++) {
        free(win[i]);
        free(dd[i]);
    }
    close_read(&ctx, &io);
    if (!ok)
        lt_exr_depth_free(out);
    return ok ? 0 : -1;
}

static int probe_view(const char *v, void *arg)
{
    lt_exr_probe_t *info = (lt_exr_probe_t *)arg;
    if (info->nviews < LT_EXR_PROBE_VIEWS)
        (void)snprintf(info->views[info->nviews], sizeof info->views[0], "%s", v);
    info->nviews++;
    return 0;
}

int lt_exr_probe_part(const char *path, int part, lt_exr_probe_t *info, lt_diag_t *diag)
{
    exr_context_t ctx = NULL;
    exr_io_t io;
    exr_storage_t st;
    exr_compression_t comp;
    exr_attr_box2i_t dw, disp;
    const exr_attr_chlist_t *cl = NULL;
    const char *s;
    int i, ok = 0;

    if (info == NULL || path == NULL) {
        lt_diag_fail(diag, "lt_exr_probe: NULL argument");
        return -1;
    }
    memset(info, 0, sizeof *info);
    if (open_read(&ctx, &io, path, diag) != 0)
        return -1;
    if (exr_get_count(ctx, &info->parts) != EXR_ERR_SUCCESS || info->parts < 1) {
        lt_diag_fail(diag, "%s: no parts", path);
        goto done;
    }
    if (part < 0 || part >= info->parts) {
        lt_diag_fail(diag, "%s: part %d out of range: the file has %d part%s (0..%d)", path, part,
                     info->parts, info->parts == 1 ? "" : "s", info->parts - 1);
        goto done;
    }
    if (exr_get_storage(ctx, part, &st) != EXR_ERR_SUCCESS ||
        exr_get_compression(ctx, part, &comp) != EXR_ERR_SUCCESS ||
        exr_get_data_window(ctx, part, &dw) != EXR_ERR_SUCCESS ||
        exr_get_display_window(ctx, part, &disp) != EXR_ERR_SUCCESS ||
        exr_get_channels(ctx, part, &cl) != EXR_ERR_SUCCESS || cl == NULL) {
        lt_diag_fail(diag, "%s: part %d: header incomplete: %s", path, part,
                     lib_text(&io, EXR_ERR_MISSING_REQ_ATTR));
        goto done;
    }
    info->part = part;
    info->storage = (int)st;
    info->compression = (int)comp;
    info->data_window.x0 = dw.min.x;
    info->data_window.y0 = dw.min.y;
    info->data_window.x1 = dw.max.x;
    info->data_window.y1 = dw.max.y;
    info->display_window.x0 = disp.min.x;
    info->display_window.y0 = disp.min.y;
    info->display_window.x1 = disp.max.x;
    info->display_window.y1 = disp.max.y;
    if ((s = attr_str(ctx, part, "name")) != NULL)
        (void)snprintf(info->part_name, sizeof info->part_name, "%s", s);
    if ((s = part_view(ctx, part)) != NULL)
        (void)snprintf(info->view, sizeof info->view, "%s", s);
    if ((s = file_default_view(ctx, info->parts)) != NULL)
        (void)snprintf(info->default_view, sizeof info->default_view, "%s", s);
    (void)each_view(ctx, info->parts, probe_view, info);
    info->nchannels = cl->num_channels;
    for (i = 0; i < cl->num_channels && i < LT_EXR_PROBE_CHANNELS; i++) {
        const exr_attr_chlist_entry_t *e = &cl->entries[i];
        info->type[i] = e->pixel_type == EXR_PIXEL_HALF    ? LT_EXR_HALF
                        : e->pixel_type == EXR_PIXEL_FLOAT ? LT_EXR_FLOAT
                                                           : LT_EXR_UINT;
        (void)snprintf(info->name[i], sizeof info->name[i], "%s", e->name.str);
    }
    ok = 1;
done:
    close_read(&ctx, &io);
    return ok ? 0 : -1;
}

int lt_exr_probe(const char *path, lt_exr_probe_t *info, lt_diag_t *diag)
{
    return lt_exr_probe_part(path, 0, info, diag);
}
