/* lt_png.c - 8-bit PNG writer over libpng's classic write API, with libpng errors captured
 * through setjmp/longjmp into our message (never printed, never an abort) and an atomic
 * temp + fsync + rename commit. Host only; docs/io.md.
 */
#include "io/lt_png.h"
#include "io/lt_tmpfiles.h"

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Error state shared with the libpng callbacks. */
typedef struct png_err {
    char msg[200]; /* first libpng error or warning text */
} png_err_t;

static void on_png_error(png_structp png, png_const_charp msg)
{
    png_err_t *pe = (png_err_t *)png_get_error_ptr(png);
    if (pe != NULL && pe->msg[0] == '\0')
        (void)snprintf(pe->msg, sizeof pe->msg, "%s", msg != NULL ? msg : "libpng error");
    png_longjmp(png, 1);
}

static void on_png_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg; /* warnings (e.g. about ancillary chunks) are not failures */
}

/* The libpng part: returns 0 or -1 with pe->msg set. Kept apart from file handling so that only
 * the locals here live across setjmp (none is modified after it). */
static int encode(FILE *fp, const uint8_t *pix, int32_t w, int32_t h, int channels, size_t stride,
                  png_err_t *pe)
{
    static const int color_of[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                    PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
    png_structp png;
    png_infop info = NULL;
    int32_t y;

    png = png_create_write_struct(PNG_LIBPNG_VER_STRING, pe, on_png_error, on_png_warning);
    if (png == NULL) {
        (void)snprintf(pe->msg, sizeof pe->msg, "libpng: cannot create the write struct");
        return -1;
    }
    info = png_create_info_struct(png);
    if (info == NULL) {
        png_destroy_write_struct(&png, NULL);
        (void)snprintf(pe->msg, sizeof pe->msg, "libpng: cannot create the info struct");
        return -1;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return -1;
    }
    png_init_io(png, fp);
    png_set_compression_level(png, 6);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, color_of[channels],
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (y = 0; y < h; y++)
        png_write_row(png, (png_const_bytep)(pix + (size_t)y * stride));
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return 0;
}

int lt_png_write(const char *path, const uint8_t *pix, int32_t w, int32_t h, int channels,
                 size_t stride, lt_diag_t *diag)
{
    png_err_t pe;
    FILE *fp;
    char *tmp;
    int rc;
    const char *name; /* the output in messages (lt_tmp_target) */

    if (path == NULL || pix == NULL) {
        lt_diag_fail(diag, "lt_png_write: NULL %s", path == NULL ? "path" : "pixels");
        return -1;
    }
    name = lt_tmp_target(path);
    if (w < 1 || h < 1 || w > LT_PNG_MAX_DIM || h > LT_PNG_MAX_DIM) {
        lt_diag_fail(diag, "%s: image %dx%d outside 1..LT_PNG_MAX_DIM %d", name, (int)w, (int)h,
                     LT_PNG_MAX_DIM);
        return -1;
    }
    if (channels < 1 || channels > 4) {
        lt_diag_fail(diag, "%s: %d channels per pixel (need 1 gray, 2 gray+alpha, 3 RGB, 4 RGBA)",
                     name, channels);
        return -1;
    }
    if (stride == 0)
        stride = (size_t)w * (size_t)channels;
    if (stride < (size_t)w * (size_t)channels) {
        lt_diag_fail(diag, "%s: row stride %zu < %d pixels x %d channels", name, stride, (int)w,
                     channels);
        return -1;
    }
    tmp = (char *)malloc(LT_TMP_PATH_MAX);
    if (tmp == NULL) {
        lt_diag_fail(diag, "%s: out of memory", name);
        return -1;
    }
    /* registered: a fatal signal removes it (io/lt_tmpfiles.h) */
    if (lt_tmp_begin(path, tmp, diag) != 0) {
        free(tmp);
        return -1;
    }
    fp = fopen(tmp, "wb");
    if (fp == NULL) {
        lt_diag_fail(diag, "%s: cannot create temporary file %s: %s", name, tmp, strerror(errno));
        lt_tmp_end(tmp);
        free(tmp);
        return -1;
    }
    memset(&pe, 0, sizeof pe);
    rc = encode(fp, pix, w, h, channels, stride, &pe);
    if (rc != 0) {
        lt_diag_fail(diag, "%s: PNG encoding failed: %s", name, pe.msg);
        (void)fclose(fp);
    } else if (fflush(fp) != 0 || fsync(fileno(fp)) != 0 || ferror(fp)) {
        lt_diag_fail(diag, "%s: writing %s failed: %s", name, tmp, strerror(errno));
        (void)fclose(fp);
        rc = -1;
    } else if (fclose(fp) != 0) {
        lt_diag_fail(diag, "%s: closing %s failed: %s", name, tmp, strerror(errno));
        rc = -1;
    } else {
        rc = lt_tmp_commit(tmp, path, diag); /* removes or forgets tmp */
        free(tmp);
        return rc;
    }
    lt_tmp_discard(tmp);
    free(tmp);
    return rc;
}
