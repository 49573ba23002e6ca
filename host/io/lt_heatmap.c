/* lt_heatmap.c - false-colour heatmaps: Turbo colour map (colormap design A. Mikhailov, Google
 * 2019; polynomial approximation R. Du, Google, Apache-2.0 - the coefficients below are theirs),
 * a legend bar with ticks and %.4g min/max labels in a built-in 5x7 font, PNG and EXR output.
 * Host only; docs/io.md.
 */
#include "io/lt_heatmap.h"

#include "io/lt_exr.h"
#include "io/lt_png.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Minimum output height (in glyph pixels, times the font scale) so that both labels fit. */
#define HM_MIN_H 48

static uint8_t to_u8(double c)
{
    if (!(c > 0.0))
        return 0;
    if (c >= 1.0)
        return 255;
    return (uint8_t)(c * 255.0 + 0.5);
}

void lt_heatmap_color(float t, uint8_t rgb[3])
{
    /* Turbo polynomial: c(x) = sum_{i=0..5} k_i x^i per channel (R. Du's fit). */
    static const double k[3][6] = {
        {0.13572138, 4.61539260, -42.66032258, 132.13108234, -152.94239396, 59.28637943},
        {0.09140261, 2.19418839, 4.84296658, -14.18503333, 4.27729857, 2.82956604},
        {0.10667330, 12.64194608, -60.58204836, 110.36276771, -89.90310912, 27.34824973},
    };
    double x = (double)t, c;
    int ch, i;
    if (isnan(t)) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return;
    }
    if (x < 0.0)
        x = 0.0;
    if (x > 1.0)
        x = 1.0;
    for (ch = 0; ch < 3; ch++) {
        c = k[ch][5];
        for (i = 4; i >= 0; i--) /* Horner */
            c = c * x + k[ch][i];
        rgb[ch] = to_u8(c);
    }
}

/* ---- 5x7 font: rows top first, bit 4 = leftmost column --------------------------------------- */

static const char font_chars[] = "0123456789.-+e";
static const uint8_t font_rows[][7] = {
    {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}, /* 0 */
    {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}, /* 1 */
    {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}, /* 2 */
    {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}, /* 3 */
    {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}, /* 4 */
    {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}, /* 5 */
    {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}, /* 6 */
    {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}, /* 7 */
    {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}, /* 8 */
    {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}, /* 9 */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}, /* . */
    {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}, /* - */
    {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}, /* + */
    {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E}, /* e */
};

static void put(lt_heatmap_image_t *im, int32_t x, int32_t y, uint8_t r, uint8_t g, uint8_t b)
{
    uint8_t *p;
    if (x < 0 || y < 0 || x >= im->width || y >= im->height)
        return;
    p = im->rgb + ((size_t)y * (size_t)im->width + (size_t)x) * 3;
    p[0] = r;
    p[1] = g;
    p[2] = b;
}

/* Draw s with its top-left corner at (x, y), glyphs 6 * scale apart; unknown characters leave
 * a gap. */
static void draw_text(lt_heatmap_image_t *im, int32_t x, int32_t y, const char *s, int32_t scale)
{
    int32_t row, col, dx, dy;
    for (; *s != '\0'; s++, x += 6 * scale) {
        const char *f = strchr(font_chars, *s);
        if (f == NULL)
            continue;
        for (row = 0; row < 7; row++)
            for (col = 0; col < 5; col++) {
                if (!((font_rows[f - font_chars][row] >> (4 - col)) & 1u))
                    continue;
                for (dy = 0; dy < scale; dy++)
                    for (dx = 0; dx < scale; dx++)
                        put(im, x + col * scale + dx, y + row * scale + dy, LT_HEATMAP_TEXT_RGB);
            }
    }
}

void lt_heatmap_free(lt_heatmap_image_t *im)
{
    if (im == NULL)
        return;
    free(im->rgb);
    im->rgb = NULL;
}

int lt_heatmap_render(const float *v, int32_t w, int32_t h, const lt_heatmap_opts_t *opts,
                      lt_heatmap_image_t *out, lt_diag_t *diag)
{
    static const lt_heatmap_opts_t defaults = LT_HEATMAP_OPTS_DEFAULT;
    lt_heatmap_opts_t o = opts != NULL ? *opts : defaults;
    uint8_t lut[256][3];
    char lab_lo[32], lab_hi[32];
    size_t n, i;
    int32_t x, y, s, W, H, bx0 = 0, by0 = 0, by1 = 0, lx = 0, nch;
    float lo, hi;
    double scale;

    if (out == NULL || v == NULL) {
        lt_diag_fail(diag, "lt_heatmap_render: NULL %s", v == NULL ? "values" : "output");
        return -1;
    }
    memset(out, 0, sizeof *out);
    if (w < 1 || h < 1 || w > LT_PNG_MAX_DIM || h > LT_PNG_MAX_DIM) {
        lt_diag_fail(diag, "heatmap: image %dx%d outside 1..LT_PNG_MAX_DIM %d", (int)w, (int)h,
                     LT_PNG_MAX_DIM);
        return -1;
    }
    if (!isfinite(o.lo) || !isfinite(o.hi)) {
        lt_diag_fail(diag, "heatmap: range lo %g hi %g must be finite", (double)o.lo, (double)o.hi);
        return -1;
    }
    n = (size_t)w * (size_t)h;
    lo = o.lo;
    hi = o.hi;
    if (!(lo < hi)) { /* automatic range over the finite values */
        int any = 0;
        lo = hi = 0.0f;
        for (i = 0; i < n; i++) {
            if (!isfinite(v[i]))
                continue;
            if (!any || v[i] < lo)
                lo = v[i];
            if (!any || v[i] > hi)
                hi = v[i];
            any = 1;
        }
    }
    for (i = 0; i < 256; i++)
        lt_heatmap_color((float)i / 255.0f, lut[i]);

    /* layout: image | gap 4s | bar 10s | tick 3s | gap 5s | labels | margin 3s; the wide gap
     * keeps a tick from reading as a minus sign */
    s = 1 + h / 384;
    if (s > 4)
        s = 4;
    (void)snprintf(lab_lo, sizeof lab_lo, "%.4g", (double)lo);
    (void)snprintf(lab_hi, sizeof lab_hi, "%.4g", (double)hi);
    nch = (int32_t)(strlen(lab_lo) > strlen(lab_hi) ? strlen(lab_lo) : strlen(lab_hi));
    W = w;
    H = h;
    if (o.legend) {
        W = w + 4 * s + 10 * s + 3 * s + 5 * s + nch * 6 * s + 3 * s;
        if (H < HM_MIN_H * s)
            H = HM_MIN_H * s;
        bx0 = w + 4 * s;
        by0 = 3 * s;
        by1 = H - 1 - 3 * s;
        lx = bx0 + 10 * s + 3 * s + 5 * s;
    }
    out->rgb = (uint8_t *)malloc((size_t)W * (size_t)H * 3);
    if (out->rgb == NULL) {
        lt_diag_fail(diag, "heatmap: out of memory for %dx%d pixels", (int)W, (int)H);
        return -1;
    }
    out->width = W;
    out->height = H;
    out->lo = lo;
    out->hi = hi;
    out->font_scale = s;
    out->bar_x0 = out->bar_y0 = out->bar_x1 = out->bar_y1 = out->label_x0 = -1;
    for (i = 0; i < (size_t)W * (size_t)H; i++) {
        static const uint8_t bg[3] = {LT_HEATMAP_BACKGROUND_RGB};
        memcpy(out->rgb + i * 3, bg, 3);
    }
    scale = hi > lo ? 255.0 / ((double)hi - (double)lo) : 0.0;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            float f = v[(size_t)y * (size_t)w + (size_t)x];
            double t;
            int idx;
            if (!isfinite(f)) {
                put(out, x, y, LT_HEATMAP_INVALID_RGB);
                continue;
            }
            t = ((double)f - (double)lo) * scale;
            idx = t <= 0.0 ? 0 : t >= 255.0 ? 255 : (int)(t + 0.5);
            put(out, x, y, lut[idx][0], lut[idx][1], lut[idx][2]);
        }
    if (!o.legend)
        return 0;

    /* bar: top row = hi (LUT 255), bottom row = lo (LUT 0), linear in between */
    for (y = by0; y <= by1; y++) {
        int idx = (int)((double)(by1 - y) * 255.0 / (double)(by1 - by0) + 0.5);
        for (x = bx0; x < bx0 + 10 * s; x++)
            put(out, x, y, lut[idx][0], lut[idx][1], lut[idx][2]);
    }
    /* ticks at the two end rows, s rows thick, and the labels centred on them */
    for (y = 0; y < s; y++)
        for (x = bx0 + 10 * s; x < bx0 + 13 * s; x++) {
            put(out, x, by0 + y - s / 2, LT_HEATMAP_TEXT_RGB);
            put(out, x, by1 - y + s / 2, LT_HEATMAP_TEXT_RGB);
        }
    draw_text(out, lx, by0 - 3 * s, lab_hi, s);
    draw_text(out, lx, by1 - 3 * s, lab_lo, s);
    out->bar_x0 = bx0;
    out->bar_x1 = bx0 + 10 * s - 1;
    out->bar_y0 = by0;
    out->bar_y1 = by1;
    out->label_x0 = lx;
    return 0;
}

int lt_heatmap_write_png(const char *path, const float *v, int32_t w, int32_t h,
                         const lt_heatmap_opts_t *opts, lt_diag_t *diag)
{
    lt_heatmap_image_t im;
    int rc;
    if (lt_heatmap_render(v, w, h, opts, &im, diag) != 0)
        return lt_diag_prefix(diag, "%s: ", path != NULL ? path : "(null)");
    rc = lt_png_write(path, im.rgb, im.width, im.height, 3, 0, diag);
    lt_heatmap_free(&im);
    return rc;
}

int lt_heatmap_write_exr(const char *path, const float *v, int32_t w, int32_t h,
                         const char *channel, lt_diag_t *diag)
{
    lt_exr_channel_t ch;
    lt_exr_image_t img;
    ch.name = channel != NULL ? channel : "Y";
    ch.type = LT_EXR_FLOAT;
    ch.data = v;
    memset(&img, 0, sizeof img);
    img.width = w;
    img.height = h;
    img.nchannels = 1;
    img.channels = &ch;
    img.compression = LT_EXR_COMP_ZIP;
    return lt_exr_write(path, &img, diag);
}
