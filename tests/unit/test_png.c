/* test_png.c - cmocka tests of host/io/lt_png (8-bit PNG writer) and host/io/lt_heatmap (Turbo false
 * colour, legend bar, min/max labels, PNG and EXR output). Every PNG is read back with libpng's
 * own simplified reader (png_image), independent of the writer's code path; heatmap pixels are
 * checked against lt_heatmap_color and the 5x7 glyph pixel counts. Builds: host, sim, asan.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <dirent.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/lt_exr.h"
#include "io/lt_heatmap.h"
#include "io/lt_png.h"
#include "lt_test_util.h"

static char g_dir[64];

static const char *tpath(const char *name)
{
    static char buf[8][400];
    static int k;
    k = (k + 1) & 7;
    (void)snprintf(buf[k], sizeof buf[k], "%s/%s", g_dir, name);
    return buf[k];
}

static int setup_dir(void **state)
{
    (void)state;
    (void)snprintf(g_dir, sizeof g_dir, "/tmp/lt_test_png.XXXXXX");
    return mkdtemp(g_dir) != NULL ? 0 : -1;
}

static int teardown_dir(void **state)
{
    DIR *d = opendir(g_dir);
    struct dirent *e;
    (void)state;
    if (d != NULL) {
        while ((e = readdir(d)) != NULL)
            if (e->d_name[0] != '.')
                (void)unlink(tpath(e->d_name));
        (void)closedir(d);
    }
    return rmdir(g_dir);
}

static int temps_left(void)
{
    DIR *d = opendir(g_dir);
    struct dirent *e;
    int n = 0;
    if (d == NULL)
        return -1;
    while ((e = readdir(d)) != NULL)
        n += strstr(e->d_name, ".tmp.") != NULL;
    (void)closedir(d);
    return n;
}

/* Read a PNG with libpng's simplified API as 8-bit samples of the file's own format; returns a
 * malloc'd buffer (w * h * channels) or NULL. */
static uint8_t *read_png(const char *path, int32_t *w, int32_t *h, int *channels)
{
    png_image im;
    uint8_t *buf;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&im, path))
        return NULL;
    /* keep the stored layout: gray, gray+alpha, RGB or RGBA, 8 bits */
    im.format &= PNG_FORMAT_FLAG_ALPHA | PNG_FORMAT_FLAG_COLOR;
    buf = malloc(PNG_IMAGE_SIZE(im));
    if (buf == NULL || !png_image_finish_read(&im, NULL, buf, 0, NULL)) {
        free(buf);
        png_image_free(&im);
        return NULL;
    }
    *w = (int32_t)im.width;
    *h = (int32_t)im.height;
    *channels = (int)PNG_IMAGE_PIXEL_CHANNELS(im.format);
    return buf;
}

static void test_png_roundtrip(void **state)
{
    static const char *kind[5] = {"", "gray", "gray+alpha", "RGB", "RGBA"};
    const int32_t W = 37, H = 19;
    ltt_rng_t r;
    int ch, bad = 0, cases = 0;
    size_t i;
    lt_diag_t diag;
    (void)state;
    ltt_rng_seed(&r, 7);
    for (ch = 1; ch <= 4; ch++) {
        /* rows 3 bytes longer than the pixels: the stride argument must be honoured */
        size_t stride = (size_t)W * (size_t)ch + 3;
        uint8_t *src = malloc(stride * (size_t)H), *back;
        int32_t w, h, y;
        int c;
        for (i = 0; i < stride * (size_t)H; i++)
            src[i] = (uint8_t)ltt_rng_u32(&r);
        src[0] = 0;
        src[1] = 255;
        assert_int_equal(lt_png_write(tpath("rt.png"), src, W, H, ch, stride, &diag),
                         0);
        back = read_png(tpath("rt.png"), &w, &h, &c);
        assert_non_null(back);
        assert_int_equal(w, W);
        assert_int_equal(h, H);
        assert_int_equal(c, ch);
        for (y = 0; y < H; y++)
            bad += memcmp(back + (size_t)y * (size_t)W * (size_t)ch, src + (size_t)y * stride,
                          (size_t)W * (size_t)ch) != 0;
        cases += H;
        ltt_report("  %s %dx%d, stride %zu: read back by png_image as %d channels\n", kind[ch],
                   W, H, stride, c);
        free(back);
        free(src);
    }
    ltt_report("PNG round trip (gray, gray+alpha, RGB, RGBA, padded rows): %d rows compared "
               "with libpng's reader, %d differ (bound 0)\n", cases, bad);
    assert_int_equal(bad, 0);
    assert_int_equal(temps_left(), 0);
}

static void test_png_errors(void **state)
{
    uint8_t px[16] = {0};
    lt_diag_t diag;
    int n = 0;
    (void)state;
    assert_int_equal(lt_png_write(tpath("e.png"), px, 0, 4, 1, 0, &diag), -1);
    assert_non_null(strstr(diag.msg, "LT_PNG_MAX_DIM 16384"));
    n++;
    assert_int_equal(lt_png_write(tpath("e.png"), px, 16385, 1, 1, 0, &diag), -1);
    ltt_report("  %s\n", diag.msg);
    assert_non_null(strstr(diag.msg, "16385x1"));
    n++;
    assert_int_equal(lt_png_write(tpath("e.png"), px, 2, 2, 5, 0, &diag), -1);
    ltt_report("  %s\n", diag.msg);
    assert_non_null(strstr(diag.msg, "5 channels"));
    n++;
    assert_int_equal(lt_png_write(tpath("e.png"), px, 4, 2, 2, 7, &diag), -1);
    assert_non_null(strstr(diag.msg, "stride 7"));
    n++;
    assert_int_equal(lt_png_write("/nonexistent-dir/e.png", px, 2, 2, 1, 0, &diag), -1);
    ltt_report("  %s\n", diag.msg);
    assert_non_null(strstr(diag.msg, "/nonexistent-dir/e.png"));
    n++;
    assert_int_equal(access(tpath("e.png"), F_OK), -1);
    assert_int_equal(temps_left(), 0);
    ltt_report("PNG errors (0 and 16385 wide, 5 channels, short stride, no such directory): "
               "%d refused naming the path or limit, nothing written\n", n);
}

/* Pixels of the text colour inside a box of im. */
static int count_text(const lt_heatmap_image_t *im, int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
    static const uint8_t t[3] = {LT_HEATMAP_TEXT_RGB};
    int32_t x, y;
    int n = 0;
    for (y = y0; y <= y1; y++)
        for (x = x0; x <= x1; x++)
            n += memcmp(im->rgb + ((size_t)y * (size_t)im->width + (size_t)x) * 3, t, 3) == 0;
    return n;
}

static int same_rgb(const uint8_t *p, const uint8_t c[3]) { return memcmp(p, c, 3) == 0; }

static void test_heatmap(void **state)
{
    enum { W = 64, H = 40 };
    float *v = malloc(sizeof(float) * W * H);
    lt_heatmap_image_t im;
    lt_heatmap_opts_t o = LT_HEATMAP_OPTS_DEFAULT;
    uint8_t c[3], *back;
    static const uint8_t invalid[3] = {LT_HEATMAP_INVALID_RGB};
    static const uint8_t bg[3] = {LT_HEATMAP_BACKGROUND_RGB};
    lt_diag_t diag;
    int32_t x, y, w2, h2, mid;
    int bad = 0, cases = 0, nc, hi_px, lo_px, gap_px;
    size_t i;
    (void)state;
    /* 0 .. 99 steps per pixel, one NaN and one +inf pixel */
    for (i = 0; i < (size_t)(W * H); i++)
        v[i] = (float)((i * 37u) % 100u);
    v[5] = NAN;
    v[6] = INFINITY;
    assert_int_equal(lt_heatmap_render(v, W, H, &o, &im, &diag), 0);
    assert_true(im.lo == 0.0f && im.hi == 99.0f); /* automatic range skips NaN and inf */
    assert_int_equal(im.font_scale, 1);
    assert_int_equal(im.height, 48); /* short image padded to the legend's minimum */
    assert_true(im.width > W + 20);
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            float f = v[y * W + x];
            const uint8_t *p = im.rgb + ((size_t)y * (size_t)im.width + (size_t)x) * 3;
            if (!isfinite(f)) {
                bad += !same_rgb(p, invalid);
            } else {
                lt_heatmap_color((float)(int)((double)f * 255.0 / 99.0 + 0.5) / 255.0f, c);
                bad += !same_rgb(p, c);
            }
            cases++;
        }
    /* padding rows under the image are background */
    for (x = 0; x < W; x++)
        for (y = H; y < im.height; y++, cases++)
            bad += !same_rgb(im.rgb + ((size_t)y * (size_t)im.width + (size_t)x) * 3, bg);
    /* legend bar: top row = colour(1), bottom row = colour(0), middle ~ colour(0.5) */
    lt_heatmap_color(1.0f, c);
    for (x = im.bar_x0; x <= im.bar_x1; x++, cases++)
        bad += !same_rgb(im.rgb + ((size_t)im.bar_y0 * (size_t)im.width + (size_t)x) * 3, c);
    lt_heatmap_color(0.0f, c);
    for (x = im.bar_x0; x <= im.bar_x1; x++, cases++)
        bad += !same_rgb(im.rgb + ((size_t)im.bar_y1 * (size_t)im.width + (size_t)x) * 3, c);
    mid = (im.bar_y0 + im.bar_y1) / 2;
    lt_heatmap_color((float)(int)((double)(im.bar_y1 - mid) * 255.0 /
                                  (double)(im.bar_y1 - im.bar_y0) + 0.5) / 255.0f,
                     c); /* the bar walks the same 256-entry table */
    cases++;
    bad += !same_rgb(im.rgb + ((size_t)mid * (size_t)im.width + (size_t)im.bar_x0) * 3, c);
    /* ticks right of the bar at both ends */
    cases += 2;
    bad += count_text(&im, im.bar_x1 + 1, im.bar_y0, im.bar_x1 + 3, im.bar_y0) != 3;
    bad += count_text(&im, im.bar_x1 + 1, im.bar_y1, im.bar_x1 + 3, im.bar_y1) != 3;
    /* labels: "99" at the top (the 5x7 '9' lights 15 pixels), "0" at the bottom (19 pixels),
     * nothing in between */
    hi_px = count_text(&im, im.label_x0, 0, im.width - 1, 6);
    lo_px = count_text(&im, im.label_x0, im.height - 7, im.width - 1, im.height - 1);
    gap_px = count_text(&im, im.label_x0, 8, im.width - 1, im.height - 9);
    ltt_report("  legend: bar x %d..%d y %d..%d, labels at x %d: top '99' %d px (want 30), "
               "bottom '0' %d px (want 19), between %d px (want 0)\n", im.bar_x0, im.bar_x1,
               im.bar_y0, im.bar_y1, im.label_x0, hi_px, lo_px, gap_px);
    cases += 3;
    bad += (hi_px != 30) + (lo_px != 19) + (gap_px != 0);

    /* the PNG holds exactly the rendered pixels */
    assert_int_equal(lt_heatmap_write_png(tpath("heat.png"), v, W, H, &o, &diag), 0);
    back = read_png(tpath("heat.png"), &w2, &h2, &nc);
    assert_non_null(back);
    assert_int_equal(w2, im.width);
    assert_int_equal(h2, im.height);
    assert_int_equal(nc, 3);
    cases++;
    bad += memcmp(back, im.rgb, (size_t)w2 * (size_t)h2 * 3) != 0;
    free(back);
    lt_heatmap_free(&im);

    /* and the EXR holds exactly the values */
    {
        lt_exr_depth_t d;
        assert_int_equal(lt_heatmap_write_exr(tpath("heat.exr"), v, W, H, "steps", &diag),
                         0);
        assert_int_equal(lt_exr_read_depth(tpath("heat.exr"), "steps", NULL, &d, &diag),
                         0);
        for (i = 0; i < (size_t)(W * H); i++, cases++)
            bad += !(d.z[i] == v[i] || (isnan(d.z[i]) && isnan(v[i])));
        lt_exr_depth_free(&d);
    }
    ltt_report("heatmap 64x40 (0..99, NaN, +inf): image pixels = colour map, invalid = black, "
               "padding, bar ends and middle, ticks, label glyphs, PNG = render, EXR = values: "
               "%d checks, %d wrong (bound 0)\n", cases, bad);
    assert_int_equal(bad, 0);
    free(v);
}

static void test_heatmap_options(void **state)
{
    enum { W = 100, H = 400 };
    float *v = malloc(sizeof(float) * W * H);
    lt_heatmap_image_t im;
    lt_heatmap_opts_t o = LT_HEATMAP_OPTS_DEFAULT;
    uint8_t c0[3], c1[3], c[3];
    lt_diag_t diag;
    int i, bad = 0;
    (void)state;
    for (i = 0; i < W * H; i++)
        v[i] = -2.5f + (float)i * 1e-3f;
    /* fixed range: values below lo / above hi clamp to the ends; labels scale with the height */
    o.lo = 0.0f;
    o.hi = 10.0f;
    assert_int_equal(lt_heatmap_render(v, W, H, &o, &im, &diag), 0);
    assert_int_equal(im.font_scale, 2);
    assert_int_equal(im.height, H);
    lt_heatmap_color(0.0f, c0);
    lt_heatmap_color(1.0f, c1);
    bad += memcmp(im.rgb, c0, 3) != 0;                                   /* -2.5 -> lo */
    bad += memcmp(im.rgb + ((size_t)(H - 1) * (size_t)im.width + (W - 1)) * 3, c1, 3) != 0;
    assert_true(count_text(&im, im.label_x0, 0, im.width - 1, 14) > 0);  /* "10" */
    lt_heatmap_free(&im);
    /* no legend: the image alone */
    o.legend = 0;
    assert_int_equal(lt_heatmap_render(v, W, H, &o, &im, &diag), 0);
    assert_int_equal(im.width, W);
    assert_int_equal(im.bar_x0, -1);
    lt_heatmap_free(&im);
    /* a constant image: everything maps to t = 0 */
    for (i = 0; i < W * H; i++)
        v[i] = 3.0f;
    o = (lt_heatmap_opts_t)LT_HEATMAP_OPTS_DEFAULT;
    assert_int_equal(lt_heatmap_render(v, 4, 2, &o, &im, &diag), 0);
    bad += memcmp(im.rgb, c0, 3) != 0;
    lt_heatmap_free(&im);
    /* Turbo's hue order: blue at 0.15, green at 0.45, red at 0.85 */
    lt_heatmap_color(0.15f, c);
    bad += !(c[2] > c[0] && c[2] > c[1]);
    lt_heatmap_color(0.45f, c);
    bad += !(c[1] > c[0] && c[1] > c[2]);
    lt_heatmap_color(0.85f, c);
    bad += !(c[0] > c[1] && c[0] > c[2]);
    /* errors */
    o.lo = NAN;
    assert_int_equal(lt_heatmap_render(v, 4, 2, &o, &im, &diag), -1);
    assert_non_null(strstr(diag.msg, "finite"));
    assert_int_equal(lt_heatmap_write_png(tpath("h.png"), v, 0, 2, NULL, &diag), -1);
    ltt_report("  %s\n", diag.msg);
    assert_non_null(strstr(diag.msg, "h.png"));
    ltt_report("heatmap options (fixed range clamps, font scale 2 at 400 rows, no legend, "
               "constant image, hue order, NaN range, empty image): 8 checks, %d wrong\n", bad);
    assert_int_equal(bad, 0);
    free(v);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_png_roundtrip),
        cmocka_unit_test(test_png_errors),
        cmocka_unit_test(test_heatmap),
        cmocka_unit_test(test_heatmap_options),
    };
    return cmocka_run_group_tests(tests, setup_dir, teardown_dir);
}
