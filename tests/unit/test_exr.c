/* test_exr.c - cmocka tests of host/io/lt_exr (OpenEXR writer and depth reader): half conversion
 * against a double-precision reference, FLOAT/HALF round trips over three compressions, data
 * windows inside and outside the display window, multi-layer names, NaN/inf/0 kept, tiled and
 * deep files made here with the raw C API (front-most sample checked by hand), size limits,
 * corrupt and truncated files, atomic writes, multi-part stereo and multi-view files made with
 * the C API (lt_exr_testlib.h: part and view selection, colour of the view, errors that list the
 * views or the part count), and the shared production files ../shared/depth, the Beachball frame
 * also rewritten as a 2-part stereo file (skipped when absent, failed under CI=true). Builds:
 * host, sim, asan.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"
#include <openexr.h>
#pragma GCC diagnostic pop

#include "io/lt_exr.h"
#include "lt_exr_testlib.h"
#include "lt_test_util.h"

static char g_dir[64]; /* per-run temp directory */

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
    (void)snprintf(g_dir, sizeof g_dir, "/tmp/lt_test_exr.XXXXXX");
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

/* Shared data root (../shared from the repository root, or $LT_SHARED). NULL when missing: the
 * caller prints a SKIP line, or fails under CI=true. */
static const char *shared_file(const char *rel)
{
    static char buf[512];
    const char *root = getenv("LT_SHARED");
    (void)snprintf(buf, sizeof buf, "%s/%s", root != NULL ? root : "../shared", rel);
    return access(buf, R_OK) == 0 ? buf : NULL;
}

static int shared_missing(const char *rel)
{
    const char *ci = getenv("CI");
    if (ci != NULL && strcmp(ci, "true") == 0) {
        ltt_report("FAIL shared file ../shared/%s missing under CI=true\n", rel);
        return -1;
    }
    ltt_report("SKIP ../shared/%s not found (a fresh clone has no ../shared)\n", rel);
    return 0;
}

static int file_exists(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0;
}

/* Number of "<base>.tmp.*" files left in the temp dir. */
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

static long file_size(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0 ? (long)st.st_size : -1;
}

static int copy_prefix(const char *src, const char *dst, long n)
{
    FILE *a = fopen(src, "rb"), *b = fopen(dst, "wb");
    int c, ok = a != NULL && b != NULL;
    long i;
    for (i = 0; ok && i < n && (c = fgetc(a)) != EOF; i++)
        ok = fputc(c, b) != EOF;
    if (a != NULL)
        (void)fclose(a);
    if (b != NULL)
        ok &= fclose(b) == 0;
    return ok ? 0 : -1;
}

static uint32_t fbits(float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    return u;
}

/* ---- half conversion against an independent double reference ------------------------------- */

/* Nearest binary16 value of f, ties to even, computed in double: the unit in the last place is
 * 2^(e - 10) for |f| in [2^e, 2^(e+1)), e >= -14, and 2^-24 below (subnormals); rint rounds to
 * nearest even in the default rounding mode. |f| >= 65520 gives inf. */
static double half_ref(float f)
{
    double a = fabs((double)f), ulp, r;
    int e;
    if (a >= 65520.0)
        return f < 0 ? -HUGE_VAL : HUGE_VAL;
    if (a == 0.0)
        return (double)f;
    (void)frexp(a, &e); /* a = m 2^e, m in [0.5, 1): a in [2^(e-1), 2^e) */
    e -= 1;
    if (e < -14)
        e = -14;
    ulp = ldexp(1.0, e - 10);
    r = rint(a / ulp) * ulp;
    return f < 0 ? -r : r;
}

static void test_half_conversion(void **state)
{
    ltt_rng_t rng;
    unsigned long cases = 0, bad = 0, roundtrip = 0, ties = 0;
    double max_rel = 0.0, max_abs_sub = 0.0;
    uint32_t h;
    int i;
    static const float edge[] = {0.0f, -0.0f, 1.0f, -1.0f, 65504.0f, 65519.99f, 65520.0f, 1e6f,
                                 -1e6f, 6.103515625e-05f, 5.9604645e-08f, 2.9802322e-08f,
                                 2.9802326e-08f, 1.0f + 0x1p-11f, 1.0f + 3 * 0x1p-11f,
                                 2048.0f + 1.0f, 0.1f, 10.92f};
    (void)state;
    /* every half converts to float and back to itself (NaNs: stay NaN) */
    for (h = 0; h < 65536u; h++) {
        float f = lt_exr_half_to_float((uint16_t)h);
        uint16_t back = lt_exr_half_from_float(f);
        if (((h >> 10) & 0x1Fu) == 0x1Fu && (h & 0x3FFu) != 0)
            roundtrip += !(isnan(f) && ((back >> 10) & 0x1Fu) == 0x1Fu && (back & 0x3FFu) != 0);
        else
            roundtrip += back != h || (double)f != half_ref(f);
    }
    ltt_report("half->float->half: 65536 halves, %lu not identical (bound 0)\n", roundtrip);
    assert_int_equal(roundtrip, 0);

    ltt_rng_seed(&rng, 11);
    for (i = 0; i < 400000 + (int)(sizeof edge / sizeof edge[0]); i++) {
        float f;
        double want, got, err;
        if (i < (int)(sizeof edge / sizeof edge[0])) {
            f = edge[i];
        } else {
            /* magnitudes spread over 2^-30 .. 2^17: subnormal, normal and overflow ranges */
            f = (float)ldexp(ltt_rng_uniform(&rng, 1.0, 2.0), (int)ltt_rng_below(&rng, 48) - 30);
            if (ltt_rng_u32(&rng) & 1u)
                f = -f;
        }
        want = half_ref(f);
        got = (double)lt_exr_half_to_float(lt_exr_half_from_float(f));
        cases++;
        if (got != want) {
            bad++;
            if (bad < 5)
                ltt_report("  FAIL half(%a) = %a, want %a\n", (double)f, got, want);
        }
        if (!isfinite(want))
            continue;
        err = fabs(got - (double)f);
        if (fabs((double)f) >= 0x1p-14) {
            if (err / fabs((double)f) > max_rel)
                max_rel = err / fabs((double)f);
        } else if (err > max_abs_sub) {
            max_abs_sub = err;
        }
        ties += fmod(fabs((double)f) / ldexp(1.0, -25), 2.0) == 1.0;
    }
    ltt_report("float->half (round to nearest even): %lu cases, %lu differ from the double "
               "reference (bound 0); max rel err %.3g (bound 2^-11 = %.3g) for normals, max abs "
               "err %.3g (bound 2^-25 = %.3g) for subnormals\n",
               cases, bad, max_rel, ldexp(1.0, -11), max_abs_sub, ldexp(1.0, -25));
    (void)ties;
    assert_int_equal(bad, 0);
    assert_true(max_rel <= ldexp(1.0, -11));
    assert_true(max_abs_sub <= ldexp(1.0, -25));
    assert_int_equal(lt_exr_half_from_float(65504.0f), 0x7BFF);
    assert_int_equal(lt_exr_half_from_float(65519.99f), 0x7BFF);
    assert_int_equal(lt_exr_half_from_float(65520.0f), 0x7C00);
    assert_int_equal(lt_exr_half_from_float(-INFINITY), 0xFC00);
    assert_int_equal(lt_exr_half_from_float(1.0f + 0x1p-11f), 0x3C00);     /* tie -> even */
    assert_int_equal(lt_exr_half_from_float(1.0f + 3 * 0x1p-11f), 0x3C02); /* tie -> even */
    assert_true(isnan(lt_exr_half_to_float(lt_exr_half_from_float(NAN))));
}

/* ---- round trips ----------------------------------------------------------------------------- */

/* Fill a w x h test pattern: kind 0 = values exactly representable in HALF (m 2^e, 11-bit m),
 * 1 = arbitrary floats over 1e-3 .. 1e4 and both signs. */
static void pattern(float *p, int32_t w, int32_t h, int kind, uint64_t seed)
{
    ltt_rng_t r;
    int32_t i;
    ltt_rng_seed(&r, seed);
    for (i = 0; i < w * h; i++) {
        if (kind == 0)
            p[i] = (float)ldexp((double)(1024 + ltt_rng_below(&r, 1024)),
                                (int)ltt_rng_below(&r, 20) - 24);
        else
            p[i] = (float)(ltt_rng_uniform(&r, -1.0, 1.0) * pow(10.0, ltt_rng_uniform(&r, -3, 4)));
    }
}

static void test_roundtrip(void **state)
{
    static const char *comp_name[3] = {"ZIP", "ZIPS", "NONE"};
    const int32_t W = 53, H = 37;
    float *a = malloc((size_t)(W * H) * 4), *b = malloc((size_t)(W * H) * 4);
    float *c = malloc((size_t)(W * H) * 4);
    lt_exr_channel_t ch[3];
    lt_exr_image_t img;
    lt_exr_probe_t *pr = malloc(sizeof *pr);
    lt_diag_t diag;
    int comp, i, exact_bad = 0, bound_bad = 0;
    unsigned long cases = 0;
    double max_rel = 0.0;
    (void)state;
    assert_non_null(a);
    assert_non_null(pr);
    pattern(a, W, H, 1, 1); /* FLOAT: any value, must come back bit-exact */
    pattern(b, W, H, 0, 2); /* HALF, representable: exact */
    pattern(c, W, H, 1, 3); /* HALF, arbitrary: within 2^-11 relative */
    ch[0].name = "Z";
    ch[0].type = LT_EXR_FLOAT;
    ch[0].data = a;
    ch[1].name = "exact.Z";
    ch[1].type = LT_EXR_HALF;
    ch[1].data = b;
    ch[2].name = "R";
    ch[2].type = LT_EXR_HALF;
    ch[2].data = c;
    memset(&img, 0, sizeof img);
    img.width = W;
    img.height = H;
    img.nchannels = 3;
    img.channels = ch;
    for (comp = 0; comp < 3; comp++) {
        lt_exr_depth_t d;
        const char *p = tpath(comp == 0 ? "rt0.exr" : comp == 1 ? "rt1.exr" : "rt2.exr");
        img.compression = (lt_exr_comp_t)comp;
        assert_int_equal(lt_exr_write(p, &img, &diag), 0);
        assert_int_equal(lt_exr_probe(p, pr, &diag), 0);
        assert_int_equal(pr->nchannels, 3);
        assert_int_equal(pr->compression, comp == 0 ? 3 : comp == 1 ? 2 : 0);
        assert_string_equal(pr->name[0], "R"); /* EXR sorts channel names */
        assert_string_equal(pr->name[1], "Z");
        assert_string_equal(pr->name[2], "exact.Z");
        assert_int_equal(pr->type[0], LT_EXR_HALF);
        assert_int_equal(pr->type[1], LT_EXR_FLOAT);

        assert_int_equal(lt_exr_read_depth(p, NULL, NULL, &d, &diag), 0);
        assert_string_equal(d.channel, "Z");
        assert_int_equal(d.z_type, LT_EXR_FLOAT);
        assert_int_equal(d.width, W);
        assert_int_equal(d.height, H);
        for (i = 0; i < W * H; i++)
            exact_bad += fbits(d.z[i]) != fbits(a[i]);
        lt_exr_depth_free(&d);

        assert_int_equal(lt_exr_read_depth(p, "exact.Z", NULL, &d, &diag), 0);
        assert_int_equal(d.z_type, LT_EXR_HALF);
        for (i = 0; i < W * H; i++)
            exact_bad += fbits(d.z[i]) != fbits(b[i]);
        lt_exr_depth_free(&d);

        assert_int_equal(lt_exr_read_depth(p, "R", NULL, &d, &diag), 0);
        for (i = 0; i < W * H; i++) {
            double rel = fabs((double)d.z[i] - (double)c[i]) / fabs((double)c[i]);
            cases++;
            /* relative bound for normal halves, absolute 2^-25 in the subnormal range */
            if (fabs((double)c[i]) >= 0x1p-14) {
                if (rel > max_rel)
                    max_rel = rel;
                bound_bad += rel > ldexp(1.0, -11);
            } else {
                bound_bad += fabs((double)d.z[i] - (double)c[i]) > ldexp(1.0, -25);
            }
            bound_bad += d.z[i] != (float)half_ref(c[i]);
        }
        lt_exr_depth_free(&d);
    }
    ltt_report("EXR round trip (%s, %s, %s): FLOAT %d px + HALF-representable %d px per file, "
               "%d not bit-exact (bound 0); HALF arbitrary %lu px, max rel err %.3g (bound 2^-11 "
               "= %.3g; subnormals: abs 2^-25), %d over bound or not nearest-even\n",
               comp_name[0], comp_name[1], comp_name[2], W * H, W * H, exact_bad, cases, max_rel,
               ldexp(1.0, -11), bound_bad);
    assert_int_equal(exact_bad, 0);
    assert_int_equal(bound_bad, 0);
    assert_int_equal(temps_left(), 0);
    free(a);
    free(b);
    free(c);
    free(pr);
}

static void test_data_window(void **state)
{
    const int32_t W = 20, H = 10, X0 = 7, Y0 = 5, DW = 40, DH = 30;
    float z[200];
    lt_exr_channel_t ch = {"Z", LT_EXR_FLOAT, z};
    lt_exr_image_t img;
    lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
    lt_exr_depth_t d;
    lt_exr_probe_t *pr = malloc(sizeof *pr);
    lt_diag_t diag;
    int32_t x, y, i, bad = 0, checked = 0;
    (void)state;
    for (i = 0; i < W * H; i++)
        z[i] = 1.0f + (float)i;
    memset(&img, 0, sizeof img);
    img.width = W;
    img.height = H;
    img.x0 = X0;
    img.y0 = Y0;
    img.display_w = DW;
    img.display_h = DH;
    img.nchannels = 1;
    img.channels = &ch;
    assert_int_equal(lt_exr_write(tpath("dw.exr"), &img, &diag), 0);
    assert_int_equal(lt_exr_probe(tpath("dw.exr"), pr, &diag), 0);
    assert_int_equal(pr->data_window.x0, X0);
    assert_int_equal(pr->data_window.y1, Y0 + H - 1);
    assert_int_equal(pr->display_window.x1, DW - 1);
    assert_int_equal(pr->display_window.y1, DH - 1);

    /* data window: origin kept */
    assert_int_equal(lt_exr_read_depth(tpath("dw.exr"), NULL, &o, &d, &diag), 0);
    assert_int_equal(d.width, W);
    assert_int_equal(d.x0, X0);
    assert_int_equal(d.y0, Y0);
    assert_int_equal(d.display_window.x1, DW - 1);
    lt_exr_depth_free(&d);

    /* display window, background +inf and then 0 */
    for (i = 0; i < 2; i++) {
        o.window = LT_EXR_WINDOW_DISPLAY;
        o.fill = i == 0 ? INFINITY : 0.0f;
        assert_int_equal(lt_exr_read_depth(tpath("dw.exr"), NULL, &o, &d, &diag), 0);
        assert_int_equal(d.width, DW);
        assert_int_equal(d.height, DH);
        assert_int_equal(d.x0, 0);
        for (y = 0; y < DH; y++)
            for (x = 0; x < DW; x++) {
                int inside = x >= X0 && x < X0 + W && y >= Y0 && y < Y0 + H;
                float want = inside ? z[(y - Y0) * W + (x - X0)] : o.fill;
                bad += fbits(d.z[y * DW + x]) != fbits(want);
                checked++;
            }
        lt_exr_depth_free(&d);
    }

    /* a data window reaching outside the display window (negative origin): clipped */
    img.x0 = -4;
    img.y0 = -3;
    img.display_w = 10;
    img.display_h = 5;
    assert_int_equal(lt_exr_write(tpath("dw2.exr"), &img, &diag), 0);
    o.fill = -1.0f;
    assert_int_equal(lt_exr_read_depth(tpath("dw2.exr"), NULL, &o, &d, &diag), 0);
    assert_int_equal(d.width, 10);
    assert_int_equal(d.height, 5);
    for (y = 0; y < 5; y++)
        for (x = 0; x < 10; x++) {
            bad += d.z[y * 10 + x] != z[(y + 3) * W + (x + 4)];
            checked++;
        }
    lt_exr_depth_free(&d);
    o.window = LT_EXR_WINDOW_DATA;
    assert_int_equal(lt_exr_read_depth(tpath("dw2.exr"), NULL, &o, &d, &diag), 0);
    assert_int_equal(d.x0, -4);
    assert_int_equal(d.y0, -3);
    lt_exr_depth_free(&d);
    ltt_report("data window (%dx%d at %d,%d in %dx%d; and -4,-3 in 10x5): %d display-window "
               "pixels checked (inside = data, outside = fill +inf / 0), %d wrong (bound 0)\n",
               W, H, X0, Y0, DW, DH, checked, bad);
    assert_int_equal(bad, 0);
    free(pr);
}

static void test_multilayer(void **state)
{
    enum { W = 16, H = 8, K = 4 };
    static const char *names[K + 4] = {"layer0.Z", "layer1.Z", "layer2.Z", "layer3.Z",
                                       "R",        "G",        "B",        "A"};
    float *buf = malloc(sizeof(float) * W * H * (K + 4));
    lt_exr_channel_t ch[K + 5];
    lt_exr_image_t img;
    lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
    lt_exr_depth_t d;
    lt_diag_t diag;
    int i, j, bad = 0;
    (void)state;
    for (i = 0; i < K + 4; i++) {
        for (j = 0; j < W * H; j++)
            buf[i * W * H + j] = (float)(i * 128 + j); /* < 1024: exact in HALF */
        ch[i].name = names[i];
        ch[i].type = i < K ? LT_EXR_FLOAT : LT_EXR_HALF;
        ch[i].data = buf + i * W * H;
    }
    memset(&img, 0, sizeof img);
    img.width = W;
    img.height = H;
    img.nchannels = K + 4;
    img.channels = ch;
    assert_int_equal(lt_exr_write(tpath("peel.exr"), &img, &diag), 0);

    /* by full name and by layer ("view") name */
    for (i = 0; i < K; i++) {
        char v[24];
        assert_int_equal(lt_exr_read_depth(tpath("peel.exr"), names[i], NULL, &d, &diag),
                         0);
        for (j = 0; j < W * H; j++)
            bad += d.z[j] != (float)(i * 128 + j);
        lt_exr_depth_free(&d);
        (void)snprintf(v, sizeof v, "layer%d", i);
        assert_int_equal(lt_exr_read_depth(tpath("peel.exr"), v, NULL, &d, &diag), 0);
        assert_string_equal(d.channel, names[i]);
        lt_exr_depth_free(&d);
    }
    /* no "Z": several "*.Z" -> an error that names them */
    assert_int_equal(lt_exr_read_depth(tpath("peel.exr"), NULL, NULL, &d, &diag), -1);
    ltt_report("  auto pick among layers: %s\n", diag.msg);
    assert_non_null(strstr(diag.msg, "several depth channels"));
    assert_non_null(strstr(diag.msg, "layer3.Z"));
    assert_non_null(strstr(diag.msg, "peel.exr"));
    assert_null(d.z);
    /* missing channel lists what exists */
    assert_int_equal(lt_exr_read_depth(tpath("peel.exr"), "layer9", NULL, &d, &diag),
                     -1);
    assert_non_null(strstr(diag.msg, "no channel 'layer9'"));
    assert_non_null(strstr(diag.msg, "layer0.Z"));

    /* colour travels with "Z" (R G B A at the top level); a layer without colour gets NULLs */
    ch[K + 4].name = "Z";
    ch[K + 4].type = LT_EXR_FLOAT;
    ch[K + 4].data = buf;
    img.nchannels = K + 5;
    assert_int_equal(lt_exr_write(tpath("peelz.exr"), &img, &diag), 0);
    o.color = 1;
    assert_int_equal(lt_exr_read_depth(tpath("peelz.exr"), NULL, &o, &d, &diag), 0);
    assert_string_equal(d.channel, "Z");
    for (i = 0; i < 4; i++) {
        assert_non_null(d.rgba[i]);
        for (j = 0; j < W * H; j++)
            bad += d.rgba[i][j] != (float)((K + i) * 128 + j);
    }
    lt_exr_depth_free(&d);
    assert_int_equal(lt_exr_read_depth(tpath("peelz.exr"), "layer1.Z", &o, &d, &diag),
                     0);
    assert_null(d.rgba[0]);
    assert_null(d.rgba[3]);
    lt_exr_depth_free(&d);
    ltt_report("multi-layer (layer0..3.Z FLOAT + R G B A HALF + Z): %d channels read by name "
               "and by layer, colour with Z, %d wrong values (bound 0)\n", 2 * K + 5, bad);
    assert_int_equal(bad, 0);
    free(buf);
}

static void test_special_values(void **state)
{
    static const float v[8] = {0.0f, -0.0f, INFINITY, -INFINITY, NAN, 1e6f, 65504.0f, 5.96e-8f};
    lt_exr_channel_t ch[2] = {{"Z", LT_EXR_FLOAT, v}, {"h.Z", LT_EXR_HALF, v}};
    lt_exr_image_t img;
    lt_exr_depth_t d;
    lt_diag_t diag;
    int i;
    (void)state;
    memset(&img, 0, sizeof img);
    img.width = 8;
    img.height = 1;
    img.nchannels = 2;
    img.channels = ch;
    assert_int_equal(lt_exr_write(tpath("special.exr"), &img, &diag), 0);
    assert_int_equal(lt_exr_read_depth(tpath("special.exr"), "Z", NULL, &d, &diag), 0);
    for (i = 0; i < 8; i++)
        assert_true(fbits(d.z[i]) == fbits(v[i]) || (isnan(v[i]) && isnan(d.z[i])));
    lt_exr_depth_free(&d);
    assert_int_equal(lt_exr_read_depth(tpath("special.exr"), "h", NULL, &d, &diag), 0);
    assert_true(d.z[0] == 0.0f && !signbit(d.z[0]));
    assert_true(d.z[1] == 0.0f && signbit(d.z[1]));
    assert_true(isinf(d.z[2]) && d.z[2] > 0);
    assert_true(isinf(d.z[3]) && d.z[3] < 0);
    assert_true(isnan(d.z[4]));
    assert_true(isinf(d.z[5]));           /* 1e6 overflows HALF: +inf, documented */
    assert_true(d.z[6] == 65504.0f);      /* largest half */
    assert_true(d.z[7] == 0x1p-24f);      /* smallest subnormal */
    lt_exr_depth_free(&d);
    ltt_report("special values (0, -0, +-inf, NaN, 1e6, 65504, 2^-24) FLOAT bit-exact, HALF: "
               "signs kept, NaN kept, 1e6 -> +inf, 65504 and 2^-24 exact: 16 cases, 0 wrong\n");
}

/* ---- files made with the raw C API: tiled, deep, oversized ----------------------------------- */

/* An EXR box (the library's structs use anonymous unions, so no brace initialisers). */
static exr_attr_box2i_t mkbox(int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
    exr_attr_box2i_t b;
    b.min.x = x0;
    b.min.y = y0;
    b.max.x = x1;
    b.max.y = y1;
    return b;
}

static exr_attr_v2f_t swc0(void)
{
    exr_attr_v2f_t v;
    v.x = 0.0f;
    v.y = 0.0f;
    return v;
}

typedef struct raw_io {
    int fd;
} raw_io_t;

static int64_t raw_write(exr_const_context_t c, void *ud, const void *b, uint64_t sz, uint64_t off,
                         exr_stream_error_func_ptr_t e)
{
    (void)c;
    (void)e;
    return (int64_t)pwrite(((raw_io_t *)ud)->fd, b, (size_t)sz, (off_t)off);
}

static void raw_quiet(exr_const_context_t c, exr_result_t code, const char *msg)
{
    (void)c;
    (void)code;
    (void)msg;
}

static exr_context_t raw_start(const char *path, raw_io_t *io)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctx = NULL;
    io->fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    assert_true(io->fd >= 0);
    init.user_data = io;
    init.write_fn = raw_write;
    init.error_handler_fn = raw_quiet;
    assert_int_equal(exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init), 0);
    return ctx;
}

static void raw_finish(exr_context_t ctx, raw_io_t *io)
{
    assert_int_equal(exr_finish(&ctx), 0);
    assert_int_equal(close(io->fd), 0);
}

/* A tiled ONE_LEVEL file, tiles tw x th, one FLOAT channel "Z" = f(x, y) over a data window. */
static float tile_value(int32_t x, int32_t y) { return (float)(x * 1000 + y) + 0.5f; }

static void write_tiled(const char *path, exr_attr_box2i_t dw, int32_t tw, int32_t th)
{
    raw_io_t io;
    exr_context_t ctx = raw_start(path, &io);
    exr_attr_box2i_t disp = mkbox(0, 0, 63, 63);
    exr_attr_v2f_t swc = swc0();
    exr_attr_tiledesc_t td;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    int part = -1, inited = 0;
    int32_t W = dw.max.x - dw.min.x + 1, H = dw.max.y - dw.min.y + 1, tx, ty, x, y;
    float *tile = malloc(sizeof(float) * (size_t)(tw * th));
    assert_int_equal(exr_add_part(ctx, NULL, EXR_STORAGE_TILED, &part), 0);
    assert_int_equal(exr_initialize_required_attr(ctx, part, &disp, &dw, 1.0f, &swc, 1.0f,
                                                  EXR_LINEORDER_INCREASING_Y,
                                                  EXR_COMPRESSION_ZIP),
                     0);
    td.x_size = (uint32_t)tw;
    td.y_size = (uint32_t)th;
    td.level_and_round = EXR_PACK_TILE_LEVEL_ROUND(EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN);
    assert_int_equal(exr_attr_set_tiledesc(ctx, part, "tiles", &td), 0);
    assert_int_equal(exr_add_channel(ctx, part, "Z", EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1,
                                     1),
                     0);
    assert_int_equal(exr_write_header(ctx), 0);
    for (ty = 0; ty * th < H; ty++)
        for (tx = 0; tx * tw < W; tx++) {
            exr_chunk_info_t ci;
            assert_int_equal(exr_write_tile_chunk_info(ctx, part, tx, ty, 0, 0, &ci), 0);
            for (y = 0; y < ci.height; y++)
                for (x = 0; x < ci.width; x++)
                    tile[y * ci.width + x] =
                        tile_value(dw.min.x + tx * tw + x, dw.min.y + ty * th + y);
            if (inited)
                assert_int_equal(exr_encoding_update(ctx, part, &ci, &enc), 0);
            else
                assert_int_equal(exr_encoding_initialize(ctx, part, &ci, &enc), 0);
            inited = 1;
            enc.channels[0].encode_from_ptr = (const uint8_t *)tile;
            enc.channels[0].user_pixel_stride = 4;
            enc.channels[0].user_line_stride = ci.width * 4;
            enc.channels[0].user_bytes_per_element = 4;
            enc.channels[0].user_data_type = EXR_PIXEL_FLOAT;
            assert_int_equal(exr_encoding_choose_default_routines(ctx, part, &enc), 0);
            assert_int_equal(exr_encoding_run(ctx, part, &enc), 0);
        }
    (void)exr_encoding_destroy(ctx, &enc);
    raw_finish(ctx, &io);
    free(tile);
}

static void test_tiled(void **state)
{
    exr_attr_box2i_t dw = mkbox(3, 2, 3 + 40 - 1, 2 + 27 - 1);
    lt_exr_depth_t d;
    lt_diag_t diag;
    int32_t x, y, bad = 0;
    (void)state;
    write_tiled(tpath("tiled.exr"), dw, 16, 8);
    assert_int_equal(lt_exr_read_depth(tpath("tiled.exr"), NULL, NULL, &d, &diag), 0);
    assert_int_equal(d.width, 40);
    assert_int_equal(d.height, 27);
    for (y = 0; y < 27; y++)
        for (x = 0; x < 40; x++)
            bad += d.z[y * 40 + x] != tile_value(x + 3, y + 2);
    lt_exr_depth_free(&d);
    ltt_report("tiled EXR (16x8 tiles, ZIP, 40x27 data window at 3,2; edge tiles partial): "
               "1080 px, %d wrong (bound 0)\n", bad);
    assert_int_equal(bad, 0);
}

/* A deep scanline file, NONE compression, W x 2 pixels, channels R (HALF) and Z (FLOAT);
 * samples per pixel from counts[], Z values from zs[] in pixel order, R = 0.25 * sample index. */
/* A deep 2-line file; table, when not NULL, replaces the cumulative sample-count table written
 * per line (W entries per line; the sample data stays what counts says). */
static void write_deep_table(const char *path, int32_t W, const int32_t *counts, const float *zs,
                             const int32_t *table_override)
{
    raw_io_t io;
    exr_context_t ctx = raw_start(path, &io);
    exr_attr_box2i_t box = mkbox(0, 0, W - 1, 1);
    exr_attr_v2f_t swc = swc0();
    int part = -1, y, x, s, base = 0;
    assert_int_equal(exr_add_part(ctx, NULL, EXR_STORAGE_DEEP_SCANLINE, &part), 0);
    assert_int_equal(exr_initialize_required_attr(ctx, part, &box, &box, 1.0f, &swc, 1.0f,
                                                  EXR_LINEORDER_INCREASING_Y,
                                                  EXR_COMPRESSION_NONE),
                     0);
    assert_int_equal(exr_add_channel(ctx, part, "R", EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LINEAR, 1,
                                     1),
                     0);
    assert_int_equal(exr_add_channel(ctx, part, "Z", EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1,
                                     1),
                     0);
    assert_int_equal(exr_write_header(ctx), 0);
    for (y = 0; y < 2; y++) {
        uint8_t table[64 * 4], data[1024];
        int32_t cum = 0, n;
        size_t o = 0;
        for (x = 0; x < W; x++) {
            cum += counts[y * W + x];
            memcpy(table + 4 * x, &cum, 4); /* little-endian host */
        }
        n = cum;
        if (table_override != NULL)
            memcpy(table, table_override + y * W, (size_t)W * 4);
        for (s = 0; s < n; s++) { /* R: all samples of the line, then Z */
            uint16_t hv = lt_exr_half_from_float(0.25f * (float)(base + s));
            memcpy(data + o, &hv, 2);
            o += 2;
        }
        for (s = 0; s < n; s++) {
            memcpy(data + o, &zs[base + s], 4);
            o += 4;
        }
        assert_int_equal(exr_write_deep_scanline_chunk(ctx, part, y, data, o, o, table,
                                                       (uint64_t)W * 4),
                         0);
        base += n;
    }
    raw_finish(ctx, &io);
}

static void write_deep(const char *path, int32_t W, const int32_t *counts, const float *zs)
{
    write_deep_table(path, W, counts, zs, NULL);
}

static void test_deep_synthetic(void **state)
{
    /* pixel: samples (Z)            front-most
     * 0: none                        fill
     * 1: 5                           5
     * 2: 7, 3, 9                     3 (sample 2 of the file)
     * 3: NaN, 4                      4
     * 4..: line 1: 2, 2 (tie: first) | NaN only | +inf, 8 | 1 */
    static const int32_t counts[8] = {0, 1, 3, 2, 2, 1, 2, 1};
    static const float zs[12] = {5, 7, 3, 9, NAN, 4, 2, 2, NAN, INFINITY, 8, 1};
    static const float want_z[8] = {-1, 5, 3, 4, 2, NAN, 8, 1};
    static const int want_s[8] = {-1, 0, 2, 5, 6, -1, 10, 11}; /* sample index of the colour */
    lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
    lt_exr_depth_t d;
    lt_diag_t diag;
    int i, bad = 0;
    (void)state;
    write_deep(tpath("deep.exr"), 4, counts, zs);
    assert_int_equal(lt_exr_read_depth(tpath("deep.exr"), NULL, &o, &d, &diag), -1);
    assert_non_null(strstr(diag.msg, "deepscanline"));
    assert_non_null(strstr(diag.msg, "deep.exr"));
    o.deep = LT_EXR_DEEP_FRONT;
    o.fill = -1.0f;
    o.color = 1;
    assert_int_equal(lt_exr_read_depth(tpath("deep.exr"), NULL, &o, &d, &diag), 0);
    assert_int_equal(d.deep, 1);
    assert_int_equal((int)d.deep_samples, 12);
    assert_non_null(d.rgba[0]);
    assert_null(d.rgba[1]);
    for (i = 0; i < 8; i++) {
        float r = want_s[i] < 0 ? 0.0f : 0.25f * (float)want_s[i];
        if (isnan(want_z[i]))
            bad += !isnan(d.z[i]) || d.rgba[0][i] != 0.0f;
        else
            bad += d.z[i] != want_z[i] || d.rgba[0][i] != r;
    }
    lt_exr_depth_free(&d);
    ltt_report("deep front-most (hand-made 4x2 file: empty pixel, 1-3 samples, NaN samples, tie, "
               "+inf): 8 pixels, Z and colour of the least-Z sample, %d wrong (bound 0)\n", bad);
    assert_int_equal(bad, 0);
}

/* Data window w x 1 written with the raw API (to get past lt_exr_write's own limit). */
static void write_wide(const char *path, int32_t w, int32_t disp_w)
{
    raw_io_t io;
    exr_context_t ctx = raw_start(path, &io);
    exr_attr_box2i_t dw = mkbox(0, 0, w - 1, 0), disp = mkbox(0, 0, disp_w - 1, 0);
    exr_attr_v2f_t swc = swc0();
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    exr_chunk_info_t ci;
    float *row = calloc((size_t)w, sizeof(float));
    int part = -1;
    assert_int_equal(exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part), 0);
    assert_int_equal(exr_initialize_required_attr(ctx, part, &disp, &dw, 1.0f, &swc, 1.0f,
                                                  EXR_LINEORDER_INCREASING_Y,
                                                  EXR_COMPRESSION_ZIPS),
                     0);
    assert_int_equal(exr_add_channel(ctx, part, "Z", EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1,
                                     1),
                     0);
    assert_int_equal(exr_write_header(ctx), 0);
    assert_int_equal(exr_write_scanline_chunk_info(ctx, part, 0, &ci), 0);
    assert_int_equal(exr_encoding_initialize(ctx, part, &ci, &enc), 0);
    enc.channels[0].encode_from_ptr = (const uint8_t *)row;
    enc.channels[0].user_pixel_stride = 4;
    enc.channels[0].user_line_stride = w * 4;
    enc.channels[0].user_bytes_per_element = 4;
    enc.channels[0].user_data_type = EXR_PIXEL_FLOAT;
    assert_int_equal(exr_encoding_choose_default_routines(ctx, part, &enc), 0);
    assert_int_equal(exr_encoding_run(ctx, part, &enc), 0);
    (void)exr_encoding_destroy(ctx, &enc);
    raw_finish(ctx, &io);
    free(row);
}

/* A deep file whose cumulative sample counts decrease (one raised far past the line's samples,
 * the file otherwise valid) or go negative: an error naming the file and the line, never a read
 * past the decompressed samples (ASan build). Every pixel of both lines, several bad values. */
static void test_deep_bad_counts(void **state)
{
    static const int32_t counts[8] = {0, 1, 3, 2, 2, 1, 2, 1};
    static const float zs[12] = {5, 7, 3, 9, NAN, 4, 2, 2, NAN, INFINITY, 8, 1};
    static const int32_t good[8] = {0, 1, 4, 6, 2, 3, 5, 6};
    static const int32_t bad_values[4] = {100000, 2147483647, -1, -100000};
    lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
    int i, v, cases = 0, refused = 0, named = 0;
    lt_diag_t diag;
    (void)state;
    o.deep = LT_EXR_DEEP_FRONT;
    o.color = 1;
    for (i = 0; i < 8; i++) {
        for (v = 0; v < 4; v++) {
            int32_t t[8];
            lt_exr_depth_t d;
            memcpy(t, good, sizeof t);
            t[i] = bad_values[v];
            write_deep_table(tpath("deepbad.exr"), 4, counts, zs, t);
            cases++;
            if (lt_exr_read_depth(tpath("deepbad.exr"), NULL, &o, &d, &diag) != 0) {
                refused++;
                named += strstr(diag.msg, "deepbad.exr") != NULL &&
                         strstr(diag.msg, "at y ") != NULL;
            } else {
                lt_exr_depth_free(&d);
            }
        }
    }
    ltt_report("deep sample-count table corrupt (4x2 file, each of 8 entries set to 1e5, INT_MAX, "
               "-1, -1e5): %d files, %d refused with the file and line named (bound: all)\n",
               cases, named);
    assert_int_equal(refused, cases);
    assert_int_equal(named, cases);
}

/* Small, highly compressible images through ZIP and ZIPS: chunks whose zlib stream is as long as
 * the raw bytes must be stored raw (a reader takes an equal-size chunk as uncompressed), so every
 * image reads back bit for bit. Sizes 1x1..7x5, HALF and FLOAT, constant, two-valued and random
 * pixels (all exactly representable in HALF). */
static void test_zip_small_roundtrip(void **state)
{
    ltt_rng_t r;
    float *z = malloc(64 * sizeof(float));
    lt_exr_channel_t ch[1];
    lt_exr_image_t img;
    lt_diag_t diag;
    int w, h, comp, ty, kind, rep, cases = 0, bad = 0, i;
    (void)state;
    assert_non_null(z);
    ltt_rng_seed(&r, 7);
    for (w = 1; w <= 7; w++)
        for (h = 1; h <= 5; h++)
            for (comp = 0; comp < 2; comp++)
                for (ty = 0; ty < 2; ty++)
                    for (kind = 0; kind < 3; kind++)
                        for (rep = 0; rep < 6; rep++) {
                            lt_exr_depth_t d;
                            float a = (float)ltt_rng_below(&r, 2048) * 0.5f;
                            float b = (float)ltt_rng_below(&r, 2048) * 0.25f;
                            for (i = 0; i < w * h; i++)
                                z[i] = kind == 0 ? a
                                       : kind == 1 ? ((ltt_rng_u32(&r) & 1u) ? a : b)
                                                   : (float)ltt_rng_below(&r, 2048) * 0.125f;
                            ch[0].name = "Z";
                            ch[0].type = ty == 0 ? LT_EXR_HALF : LT_EXR_FLOAT;
                            ch[0].data = z;
                            memset(&img, 0, sizeof img);
                            img.width = w;
                            img.height = h;
                            img.nchannels = 1;
                            img.channels = ch;
                            img.compression = comp == 0 ? LT_EXR_COMP_ZIP : LT_EXR_COMP_ZIPS;
                            assert_int_equal(lt_exr_write(tpath("zs.exr"), &img, &diag),
                                             0);
                            cases++;
                            if (lt_exr_read_depth(tpath("zs.exr"), NULL, NULL, &d, &diag) != 0) {
                                bad++;
                                continue;
                            }
                            for (i = 0; i < w * h; i++)
                                if (fbits(d.z[i]) != fbits(z[i])) {
                                    bad++;
                                    break;
                                }
                            lt_exr_depth_free(&d);
                        }
    ltt_report("ZIP/ZIPS small-image round trips (1x1..7x5, HALF/FLOAT, constant, two-valued, "
               "random): %d images, %d not read back bit for bit (bound 0)\n", cases, bad);
    assert_int_equal(bad, 0);
    assert_int_equal(temps_left(), 0);
    free(z);
}

static void test_limits(void **state)
{
    float z[4] = {0};
    lt_exr_channel_t ch = {"Z", LT_EXR_FLOAT, z};
    lt_exr_image_t img;
    lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
    lt_exr_depth_t d;
    lt_diag_t diag;
    (void)state;
    memset(&img, 0, sizeof img);
    img.width = LT_EXR_MAX_DIM + 1;
    img.height = 1;
    img.nchannels = 1;
    img.channels = &ch;
    assert_int_equal(lt_exr_write(tpath("big.exr"), &img, &diag), -1);
    ltt_report("  write limit: %s\n", diag.msg);
    assert_non_null(strstr(diag.msg, "16384"));
    assert_false(file_exists(tpath("big.exr")));

    write_wide(tpath("wide.exr"), LT_EXR_MAX_DIM + 1, 4);
    assert_int_equal(lt_exr_read_depth(tpath("wide.exr"), NULL, NULL, &d, &diag), -1);
    ltt_report("  read limit: %s\n", diag.msg);
    assert_non_null(strstr(diag.msg, "LT_EXR_MAX_DIM 16384"));
    assert_non_null(strstr(diag.msg, "wide.exr"));

    write_wide(tpath("widedisp.exr"), 2, 20000);
    assert_int_equal(lt_exr_read_depth(tpath("widedisp.exr"), NULL, &o, &d, &diag), 0);
    /* read by its data window: a command building a camera over the display window asks */
    assert_int_equal(lt_exr_display_check(tpath("widedisp.exr"), &d.display_window, &diag), -1);
    assert_non_null(strstr(diag.msg, "widedisp.exr: display window 20000x1 outside "
                                     "1..LT_EXR_MAX_DIM 16384"));
    {
        /* the extremes: 2^32 wide (x1 - x0 + 1 past int32), 1x1 and 16384 accepted */
        lt_exr_box_t b = {INT32_MIN, 0, INT32_MAX, 0};
        assert_int_equal(lt_exr_display_check("x.exr", &b, &diag), -1);
        assert_non_null(strstr(diag.msg, "display window 4294967296x1"));
        b.x0 = b.x1 = 7;
        assert_int_equal(lt_exr_display_check("x.exr", &b, &diag), 0);
        b.x0 = -5;
        b.x1 = -5 + LT_EXR_MAX_DIM - 1;
        b.y1 = LT_EXR_MAX_DIM - 1;
        assert_int_equal(lt_exr_display_check("x.exr", &b, &diag), 0);
    }
    lt_exr_depth_free(&d);
    o.window = LT_EXR_WINDOW_DISPLAY;
    assert_int_equal(lt_exr_read_depth(tpath("widedisp.exr"), NULL, &o, &d, &diag), -1);
    assert_non_null(strstr(diag.msg, "display window 20000x1"));
    ltt_report("limits: width 16385 refused on write and read (data window), display window "
               "20000 refused when the display window is asked for or checked "
               "(lt_exr_display_check: 2^32 refused, 1x1 and 16384 taken): 8 cases, 0 wrong\n");
}

/* ---- bad input ------------------------------------------------------------------------------- */

static void expect_read_error(const char *path, const char *opt_channel, int deep,
                              const char *must, unsigned *cases)
{
    lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
    lt_exr_depth_t d;
    lt_diag_t diag;
    const char *base = strrchr(path, '/') != NULL ? strrchr(path, '/') + 1 : path;
    o.deep = deep ? LT_EXR_DEEP_FRONT : LT_EXR_DEEP_REJECT;
    assert_int_equal(lt_exr_read_depth(path, opt_channel, &o, &d, &diag), -1);
    ltt_report("  %s\n", diag.msg);
    assert_non_null(strstr(diag.msg, base));
    if (must != NULL)
        assert_non_null(strstr(diag.msg, must));
    assert_null(d.z);
    (*cases)++;
}

static void test_corrupt(void **state)
{
    enum { W = 64, H = 64 };
    float *z = malloc(sizeof(float) * W * H);
    lt_exr_channel_t ch = {"Z", LT_EXR_FLOAT, z};
    lt_exr_image_t img;
    lt_exr_depth_t d;
    lt_diag_t diag;
    unsigned cases = 0, survived = 0, i;
    long n;
    FILE *f;
    (void)state;
    pattern(z, W, H, 1, 5);
    memset(&img, 0, sizeof img);
    img.width = W;
    img.height = H;
    img.nchannels = 1;
    img.channels = &ch;
    assert_int_equal(lt_exr_write(tpath("good.exr"), &img, &diag), 0);
    n = file_size(tpath("good.exr"));
    assert_true(n > 1000);

    assert_int_equal(copy_prefix(tpath("good.exr"), tpath("half.exr"), n / 2), 0);
    expect_read_error(tpath("half.exr"), NULL, 0, "truncated or corrupt", &cases);
    assert_int_equal(copy_prefix(tpath("good.exr"), tpath("head.exr"), 40), 0);
    expect_read_error(tpath("head.exr"), NULL, 0, "not a readable OpenEXR", &cases);
    assert_int_equal(copy_prefix(tpath("good.exr"), tpath("empty.exr"), 0), 0);
    expect_read_error(tpath("empty.exr"), NULL, 0, "0 bytes", &cases);
    f = fopen(tpath("garbage.exr"), "wb");
    for (i = 0; i < 5000; i++)
        (void)fputc((int)((i * 2654435761u) >> 24), f);
    (void)fclose(f);
    expect_read_error(tpath("garbage.exr"), NULL, 0, "not a readable OpenEXR", &cases);
    expect_read_error(tpath("nonexistent.exr"), NULL, 0, "No such file", &cases);
    expect_read_error(g_dir, NULL, 0, "not a regular file", &cases);
    expect_read_error(tpath("good.exr"), "nope", 0, "no channel 'nope'", &cases);

    /* every cut length of the first 400 bytes and bytes flipped all over: errors, never a crash */
    for (i = 0; i < 400; i += 7) {
        (void)copy_prefix(tpath("good.exr"), tpath("cut.exr"), (long)i);
        if (lt_exr_read_depth(tpath("cut.exr"), NULL, NULL, &d, &diag) == 0) {
            survived++;
            lt_exr_depth_free(&d);
        }
        cases++;
    }
    for (i = 0; i < 64; i++) {
        FILE *g;
        long at = (long)((i * 7919u) % (unsigned long)n);
        (void)copy_prefix(tpath("good.exr"), tpath("flip.exr"), n);
        g = fopen(tpath("flip.exr"), "r+b");
        (void)fseek(g, at, SEEK_SET);
        (void)fputc(0xFF ^ (int)(i & 0x7F), g);
        (void)fclose(g);
        if (lt_exr_read_depth(tpath("flip.exr"), NULL, NULL, &d, &diag) == 0) {
            survived++; /* damage inside pixel data may still decode (ZIP checks no CRC) */
            lt_exr_depth_free(&d);
        }
        cases++;
    }
    ltt_report("corrupt EXR: half file, 40-byte header, empty, garbage, missing, directory, "
               "missing channel, 58 cut lengths, 64 flipped bytes: %u cases, no crash, every "
               "error names the file; %u damaged files still decoded (allowed: pixel bytes)\n",
               cases, survived);
    free(z);
}

/* A header that asks for more than the file can hold: a valid 64x64 file (ZIP and uncompressed)
 * whose dataWindow is patched to 16384 x 16384 (1 GiB of FLOAT depth) must fail before any raster
 * is allocated, naming the window, the bytes asked and the file's bound (it used to allocate and
 * fill 1 GiB per channel read before the first chunk proved the file wrong). */
static void test_header_bomb(void **state)
{
    enum { W = 64, H = 64 };
    static const char key[] = "dataWindow\0box2i";
    float *z = malloc(sizeof(float) * W * H);
    lt_exr_channel_t ch = {"Z", LT_EXR_FLOAT, z};
    lt_exr_image_t img;
    unsigned cases = 0, c;
    (void)state;
    pattern(z, W, H, 1, 5);
    for (c = 0; c < 2; c++) {
        const char *p = tpath(c ? "bomb-none.exr" : "bomb-zip.exr");
        unsigned char buf[4096];
        size_t n, i;
        FILE *f;
        memset(&img, 0, sizeof img);
        img.width = W;
        img.height = H;
        img.nchannels = 1;
        img.channels = &ch;
        img.compression = c ? LT_EXR_COMP_NONE : LT_EXR_COMP_ZIP;
        assert_int_equal(lt_exr_write(p, &img, NULL), 0);
        f = fopen(p, "r+b");
        assert_non_null(f);
        n = fread(buf, 1, sizeof buf, f);
        for (i = 0; i + sizeof key + 4 + 16 <= n; i++)
            if (memcmp(buf + i, key, sizeof key) == 0)
                break;
        assert_true(i + sizeof key + 4 + 16 <= n);
        i += sizeof key + 4; /* past the name, the type and the 4-byte size: xmin ymin xmax ymax */
        buf[i + 8] = buf[i + 12] = 0xFF;
        buf[i + 9] = buf[i + 13] = 0x3F;
        buf[i + 10] = buf[i + 14] = buf[i + 11] = buf[i + 15] = 0;
        (void)fseek(f, (long)(i + 8), SEEK_SET);
        assert_int_equal(fwrite(buf + i + 8, 1, 8, f), 8);
        (void)fclose(f);
        expect_read_error(p, NULL, 0, "16384x16384 asks for 1073741824 bytes", &cases);
    }
    ltt_report("header bomb: a 64x64 file (ZIP, none) claiming a 16384x16384 FLOAT depth window: "
               "%u refused before allocating, naming the window and the file's bound\n", cases);
    free(z);
}

static void test_write_errors(void **state)
{
    float z[4] = {1, 2, 3, 4};
    lt_exr_channel_t ch[2] = {{"Z", LT_EXR_FLOAT, z}, {"Z", LT_EXR_HALF, z}};
    lt_exr_image_t img;
    lt_exr_depth_t d;
    lt_diag_t diag;
    const char *p = tpath("keep.exr");
    (void)state;
    memset(&img, 0, sizeof img);
    img.width = 2;
    img.height = 2;
    img.nchannels = 1;
    img.channels = ch;
    assert_int_equal(lt_exr_write(p, &img, &diag), 0);

    assert_int_equal(lt_exr_write("/nonexistent-dir/x.exr", &img, &diag), -1);
    ltt_report("  %s\n", diag.msg);
    assert_non_null(strstr(diag.msg, "/nonexistent-dir/x.exr"));
    img.nchannels = 2; /* duplicate name: refused, the existing file stays */
    assert_int_equal(lt_exr_write(p, &img, &diag), -1);
    ltt_report("  %s\n", diag.msg);
    assert_non_null(strstr(diag.msg, "given twice"));
    ch[1].name = "Y";
    ch[1].data = NULL;
    assert_int_equal(lt_exr_write(p, &img, &diag), -1);
    assert_non_null(strstr(diag.msg, "'Y' has no data"));
    ch[1].data = z;
    ch[1].type = (lt_exr_type_t)7;
    assert_int_equal(lt_exr_write(p, &img, &diag), -1);
    assert_non_null(strstr(diag.msg, "type 7"));
    img.nchannels = 0;
    assert_int_equal(lt_exr_write(p, &img, &diag), -1);
    assert_non_null(strstr(diag.msg, "0 channels"));
    assert_int_equal(lt_exr_read_depth(p, NULL, NULL, &d, &diag), 0);
    assert_true(d.z[3] == 4.0f);
    lt_exr_depth_free(&d);
    assert_int_equal(temps_left(), 0);
    ltt_report("write errors (no such directory, duplicate name, NULL data, bad type, 0 "
               "channels): 5 refused with the path in the message, previous file intact, no "
               "temp file left\n");
}

/* Kill a writer mid-file: the destination is then absent or complete, never partial. */
static void test_atomic_kill(void **state)
{
    enum { W = 1024, H = 1024 };
    char p[400];
    int round, absent = 0, complete = 0, bad = 0;
    (void)state;
    (void)snprintf(p, sizeof p, "%s", tpath("killed.exr")); /* tpath() recycles its buffers */
    for (round = 0; round < 3; round++) {
        pid_t pid;
        int st, reaped = 0;
        (void)unlink(p);
        pid = fork();
        assert_true(pid >= 0);
        if (pid == 0) {
            float *z = calloc((size_t)W * H * 4, sizeof(float));
            lt_exr_channel_t ch[4] = {{"A", LT_EXR_FLOAT, z},
                                      {"B", LT_EXR_FLOAT, z + W * H},
                                      {"G", LT_EXR_FLOAT, z + 2 * W * H},
                                      {"R", LT_EXR_FLOAT, z + 3 * W * H}};
            lt_exr_image_t img;
            lt_diag_t diag;
            memset(&img, 0, sizeof img);
            img.width = W;
            img.height = H;
            img.nchannels = 4;
            img.channels = ch;
            img.compression = LT_EXR_COMP_NONE;
            _exit(z != NULL && lt_exr_write(p, &img, &diag) == 0 ? 0 : 1);
        }
        /* wait until the temp file has grown (or the child finished), then kill it */
        {
            struct timespec ts = {0, 200000};
            int k;
            for (k = 0; k < 20000; k++) {
                DIR *dd = opendir(g_dir);
                struct dirent *e;
                long sz = 0;
                while (dd != NULL && (e = readdir(dd)) != NULL)
                    if (strstr(e->d_name, "killed.exr.tmp.") != NULL)
                        sz = file_size(tpath(e->d_name));
                if (dd != NULL)
                    (void)closedir(dd);
                if (waitpid(pid, &st, WNOHANG) == pid) {
                    reaped = 1;
                    break;
                }
                if (sz > (long)(round + 1) * 2000000)
                    break;
                (void)nanosleep(&ts, NULL);
            }
        }
        if (!reaped) { /* only our own child, never a reused pid */
            (void)kill(pid, SIGKILL);
            (void)waitpid(pid, &st, 0);
        }
        if (!file_exists(p)) {
            absent++;
        } else {
            lt_exr_depth_t d;
            lt_diag_t diag;
            if (lt_exr_read_depth(p, "R", NULL, &d, &diag) == 0 && d.width == W) {
                complete++;
            } else {
                bad++;
                ltt_report("  partial: %s\n", diag.msg);
            }
            lt_exr_depth_free(&d);
        }
    }
    {
        /* remove the killed writers' temp files */
        DIR *dd = opendir(g_dir);
        struct dirent *e;
        while (dd != NULL && (e = readdir(dd)) != NULL)
            if (strstr(e->d_name, ".tmp.") != NULL)
                (void)unlink(tpath(e->d_name));
        if (dd != NULL)
            (void)closedir(dd);
    }
    ltt_report("atomic write under SIGKILL (16 MiB EXR, 3 kills at growing temp sizes): "
               "destination absent %d, complete %d, partial %d (bound 0)\n", absent, complete,
               bad);
    assert_int_equal(bad, 0);
}

/* ---- multi-part and multi-view files (tests/unit/lt_exr_testlib.h, OpenEXR's C API) ----------- */

/* Read path with part / view / colour; 0 or -1 (diag). */
static int read_sel(const char *path, const char *channel, int part, const char *view, int color,
                    lt_exr_depth_t *d, lt_diag_t *diag)
{
    lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
    o.part = part;
    o.view = view;
    o.color = color;
    return lt_exr_read_depth(path, channel, &o, d, diag);
}

/* Pixels of d (data window of the synthetic files) that differ from eye e's Z and, when d has
 * colour, from its R G B A. */
static long eye_mismatch(const lt_exr_depth_t *d, int e)
{
    long bad = 0;
    int x, y, c;
    if (d->width != LTX_W || d->height != LTX_H || d->x0 != LTX_X0 || d->y0 != LTX_Y0)
        return -1;
    for (y = 0; y < LTX_H; y++)
        for (x = 0; x < LTX_W; x++) {
            bad += d->z[y * LTX_W + x] != ltx_value(e, 4, x, y);
            for (c = 0; c < 4; c++)
                bad += d->rgba[c] != NULL && d->rgba[c][y * LTX_W + x] != ltx_value(e, c, x, y);
        }
    return bad;
}

/* One read that must succeed: part, view and channel read, eye e's values. */
static void expect_eye(const char *path, const char *channel, int part, const char *view,
                       int color, int want_part, const char *want_view, const char *want_chan,
                       int e, unsigned *cases)
{
    lt_exr_depth_t d;
    lt_diag_t diag;
    if (read_sel(path, channel, part, view, color, &d, &diag) != 0) {
        ltt_report("FAIL %s: %s\n", path, diag.msg);
        fail();
    }
    if (d.part != want_part || strcmp(d.view, want_view) != 0 || strcmp(d.channel, want_chan) != 0)
        ltt_report("FAIL %s channel %s part %d view %s: read part %d view '%s' channel %s\n", path,
                   channel != NULL ? channel : "(default)", part, view != NULL ? view : "(default)",
                   d.part, d.view, d.channel);
    assert_int_equal(d.part, want_part);
    assert_string_equal(d.view, want_view);
    assert_string_equal(d.channel, want_chan);
    assert_int_equal(eye_mismatch(&d, e), 0);
    if (color) {
        assert_non_null(d.rgba[0]);
        assert_non_null(d.rgba[3]);
    }
    lt_exr_depth_free(&d);
    (*cases)++;
}

/* One read that must fail with a message naming the file and containing must (and not "(none)"
 * when views exist). */
static void expect_sel_error(const char *path, const char *channel, int part, const char *view,
                             const char *must, unsigned *cases)
{
    lt_exr_depth_t d;
    lt_diag_t diag;
    assert_int_equal(read_sel(path, channel, part, view, 0, &d, &diag), -1);
    ltt_report("  %s\n", diag.msg);
    assert_non_null(strstr(diag.msg, path));
    assert_non_null(strstr(diag.msg, must));
    assert_null(strstr(diag.msg, "views: (none)"));
    assert_null(d.z);
    (*cases)++;
}

static void test_multipart_stereo(void **state)
{
    const char *p = tpath("stereo.exr");
    lt_exr_probe_t *pr = malloc(sizeof *pr);
    lt_exr_depth_t d;
    lt_diag_t diag;
    unsigned cases = 0;
    long outside = 0;
    int x, y;
    (void)state;
    assert_int_equal(ltx_write_kind(p, "stereo", &diag), 0);
    /* the default view is multiView[0] = right, part 1 (it used to read part 0, the left eye) */
    expect_eye(p, NULL, -1, NULL, 1, 1, "right", "Z", 1, &cases);
    expect_eye(p, NULL, -1, "left", 1, 0, "left", "Z", 0, &cases);
    expect_eye(p, NULL, -1, "right", 1, 1, "right", "Z", 1, &cases);
    expect_eye(p, NULL, 0, NULL, 1, 0, "left", "Z", 0, &cases);
    expect_eye(p, NULL, 1, NULL, 0, 1, "right", "Z", 1, &cases);
    expect_eye(p, NULL, 0, "left", 0, 0, "left", "Z", 0, &cases);
    expect_eye(p, "Z", -1, "left", 1, 0, "left", "Z", 0, &cases);
    /* a view named as the channel (lt_exr.h: a channel that names a view reads it) */
    expect_eye(p, "left", -1, NULL, 1, 0, "left", "Z", 0, &cases);
    expect_eye(p, "right", -1, NULL, 0, 1, "right", "Z", 1, &cases);
    expect_sel_error(p, NULL, -1, "center", "no view 'center'; views: right left; default right",
                     &cases);
    expect_sel_error(p, "center", -1, NULL, "views: right left", &cases);
    expect_sel_error(p, NULL, 2, NULL, "part 2 out of range: the file has 2 parts (0..1)", &cases);
    expect_sel_error(p, NULL, -5, NULL, "part -5 out of range", &cases);
    expect_sel_error(p, NULL, 0, "right", "part 0 holds view 'left', not 'right'", &cases);
    expect_sel_error(p, "N.x", -1, "left", "no channel 'N.x' (nor 'N.x.Z') in view 'left'",
                     &cases);
    /* colour of the view, in the display window */
    {
        lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
        o.view = "left";
        o.color = 1;
        o.window = LT_EXR_WINDOW_DISPLAY;
        o.fill = INFINITY;
        assert_int_equal(lt_exr_read_depth(p, NULL, &o, &d, &diag), 0);
        assert_int_equal(d.width, 32);
        assert_int_equal(d.height, 24);
        assert_int_equal(d.color_part, 0);
        for (y = 0; y < 24; y++)
            for (x = 0; x < 32; x++) {
                int in = x >= LTX_X0 && x < LTX_X0 + LTX_W && y >= LTX_Y0 && y < LTX_Y0 + LTX_H;
                float z = d.z[y * 32 + x], r = d.rgba[0][y * 32 + x];
                outside += in ? z != ltx_value(0, 4, x - LTX_X0, y - LTX_Y0) || r != 0.25f
                              : !isinf(z) || r != 0.0f;
            }
        lt_exr_depth_free(&d);
        assert_int_equal(outside, 0);
    }
    /* the header of every part */
    assert_int_equal(lt_exr_probe_part(p, 1, pr, &diag), 0);
    assert_int_equal(pr->parts, 2);
    assert_int_equal(pr->part, 1);
    assert_string_equal(pr->part_name, "right");
    assert_string_equal(pr->view, "right");
    assert_string_equal(pr->default_view, "right");
    assert_int_equal(pr->nviews, 2);
    assert_string_equal(pr->views[0], "right");
    assert_string_equal(pr->views[1], "left");
    assert_int_equal(pr->nchannels, 5);
    assert_string_equal(pr->name[4], "Z");
    assert_int_equal(lt_exr_probe_part(p, 0, pr, &diag), 0);
    assert_string_equal(pr->view, "left");
    assert_int_equal(lt_exr_probe_part(p, 2, pr, &diag), -1);
    assert_non_null(strstr(diag.msg, "part 2 out of range: the file has 2 parts"));
    free(pr);
    ltt_report("multi-part stereo (part 0 left, part 1 right, multiView right left): default, "
               "--view, --part, view as channel, colour, display window: %u cases, 0 wrong eyes "
               "or values; bad view / part / view of part refused with the views or the count\n",
               cases);
}

static void test_multipart_variants(void **state)
{
    const char *sp = tpath("split.exr"), *nm = tpath("nomv.exr"), *sg = tpath("single.exr");
    lt_exr_depth_t d;
    lt_diag_t diag;
    unsigned cases = 0;
    (void)state;
    assert_int_equal(ltx_write_kind(sp, "split", &diag), 0);
    assert_int_equal(ltx_write_kind(nm, "nomv", &diag), 0);
    assert_int_equal(ltx_write_kind(sg, "single", &diag), 0);

    /* colour in a part of its own: from the part of the same view and data window */
    expect_eye(sp, NULL, -1, NULL, 1, 1, "right", "Z", 1, &cases);
    expect_eye(sp, NULL, -1, "left", 1, 0, "left", "Z", 0, &cases);
    assert_int_equal(read_sel(sp, NULL, -1, NULL, 1, &d, &diag), 0);
    assert_int_equal(d.color_part, 3);
    lt_exr_depth_free(&d);
    assert_int_equal(read_sel(sp, NULL, -1, "left", 1, &d, &diag), 0);
    assert_int_equal(d.color_part, 2);
    lt_exr_depth_free(&d);
    /* --part N reads part N only: no colour there */
    assert_int_equal(read_sel(sp, NULL, 1, NULL, 1, &d, &diag), 0);
    assert_int_equal(d.color_part, -1);
    assert_null(d.rgba[0]);
    lt_exr_depth_free(&d);
    expect_sel_error(sp, NULL, 2, NULL, "no depth channel (Z, depth, *.Z) in part 2", &cases);
    cases++;

    /* no multiView: the default view is part 0's */
    expect_eye(nm, NULL, -1, NULL, 1, 0, "left", "Z", 0, &cases);
    expect_eye(nm, NULL, -1, "right", 1, 1, "right", "Z", 1, &cases);
    expect_eye(nm, "right", -1, NULL, 1, 1, "right", "Z", 1, &cases);
    expect_sel_error(nm, NULL, -1, "center", "views: left right; default left", &cases);

    /* single-part multi-view: views by channel name, the default view's unprefixed */
    expect_eye(sg, NULL, -1, NULL, 1, 0, "right", "Z", 1, &cases);
    expect_eye(sg, NULL, -1, "right", 1, 0, "right", "Z", 1, &cases);
    expect_eye(sg, NULL, -1, "left", 1, 0, "left", "left.Z", 0, &cases);
    expect_eye(sg, "Z", -1, "left", 1, 0, "left", "left.Z", 0, &cases);
    expect_eye(sg, "left.Z", -1, "left", 1, 0, "left", "left.Z", 0, &cases);
    expect_eye(sg, "left", -1, NULL, 1, 0, "left", "left.Z", 0, &cases);
    expect_eye(sg, NULL, 0, "left", 1, 0, "left", "left.Z", 0, &cases);
    expect_sel_error(sg, NULL, -1, "center", "no view 'center'; views: right left", &cases);
    expect_sel_error(sg, NULL, 1, NULL, "part 1 out of range: the file has 1 part (0..0)", &cases);
    /* a plain file names no views */
    {
        float z[4] = {1.0f, 2.0f, 3.0f, 4.0f};
        lt_exr_channel_t ch = {"Z", LT_EXR_FLOAT, z};
        lt_exr_image_t img;
        memset(&img, 0, sizeof img);
        img.width = 2;
        img.height = 2;
        img.nchannels = 1;
        img.channels = &ch;
        assert_int_equal(lt_exr_write(tpath("plain.exr"), &img, &diag), 0);
        assert_int_equal(read_sel(tpath("plain.exr"), NULL, -1, "left", 0, &d, &diag), -1);
        ltt_report("  %s\n", diag.msg);
        assert_non_null(strstr(diag.msg, "no view 'left'; views: (none: the file names no views)"));
        cases++;
    }
    ltt_report("multi-part variants (colour in parts of its own, no multiView, single-part "
               "multi-view, plain): %u cases, 0 wrong eyes, colour from the view's part (3 right, "
               "2 left), none with --part\n", cases);
}

/* ---- shared production files ----------------------------------------------------------------- */

static void stats(const lt_exr_depth_t *d, double *mn, double *mx, double *mean, long *n)
{
    long i, k = 0;
    double s = 0.0;
    *mn = HUGE_VAL;
    *mx = -HUGE_VAL;
    for (i = 0; i < (long)d->width * d->height; i++) {
        double v = (double)d->z[i];
        if (!isfinite(v))
            continue;
        *mn = v < *mn ? v : *mn;
        *mx = v > *mx ? v : *mx;
        s += v;
        k++;
    }
    *mean = k > 0 ? s / (double)k : 0.0;
    *n = k;
}

static void test_shared_beachball(void **state)
{
    const char *rel = "depth/beachball_singlepart.0001.exr";
    const char *p = shared_file(rel);
    lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
    lt_exr_depth_t d;
    lt_diag_t diag;
    double mn, mx, mean, lmn, lmx, lmean;
    long n, ln, outside_bad = 0, x, y;
    (void)state;
    if (p == NULL) {
        assert_int_equal(shared_missing(rel), 0);
        return;
    }
    o.color = 1;
    assert_int_equal(lt_exr_read_depth(p, NULL, &o, &d, &diag), 0);
    assert_string_equal(d.channel, "Z");
    assert_int_equal(d.z_type, LT_EXR_HALF);
    assert_int_equal(d.width, 911);
    assert_int_equal(d.height, 876);
    assert_int_equal(d.x0, 654);
    assert_int_equal(d.y0, 245);
    assert_int_equal(d.display_window.x1, 2047);
    assert_int_equal(d.display_window.y1, 1555);
    assert_non_null(d.rgba[0]);
    assert_non_null(d.rgba[3]);
    stats(&d, &mn, &mx, &mean, &n);
    lt_exr_depth_free(&d);
    assert_int_equal(lt_exr_read_depth(p, "left", NULL, &d, &diag), 0);
    assert_string_equal(d.channel, "left.Z");
    stats(&d, &lmn, &lmx, &lmean, &ln);
    lt_exr_depth_free(&d);
    ltt_report("beachball Z (HALF): %ld px, min %.4g max %.4g mean %.4f (SOURCES.md: 798,036 px, "
               "0..10.92, mean 7.02); left.Z: min %.4g max %.4g\n", n, mn, mx, mean, lmn, lmx);
    assert_int_equal(n, 798036);
    assert_true(mn == 0.0);
    assert_true(fabs(mx - 10.92) < 0.005);
    assert_true(fabs(mean - 7.02) < 0.005);
    assert_true(lmn == 0.0);
    assert_true(fabs(lmx - 10.26) < 0.005);

    /* the display window read keeps the data in place and fills the rest */
    o.color = 0;
    o.window = LT_EXR_WINDOW_DISPLAY;
    o.fill = INFINITY;
    assert_int_equal(lt_exr_read_depth(p, "right", &o, &d, &diag), 0);
    assert_string_equal(d.channel, "Z"); /* "right" is the default view */
    assert_int_equal(d.width, 2048);
    assert_int_equal(d.height, 1556);
    for (y = 0; y < 1556; y += 5)
        for (x = 0; x < 2048; x += 5) {
            int inside = x >= 654 && x <= 1564 && y >= 245 && y <= 1120;
            outside_bad += !inside && !isinf(d.z[y * 2048 + x]);
            outside_bad += inside && !isfinite(d.z[y * 2048 + x]);
        }
    lt_exr_depth_free(&d);
    assert_int_equal(outside_bad, 0);
    assert_int_equal(lt_exr_read_depth(p, "center", NULL, &d, &diag), -1);
    ltt_report("  %s\n", diag.msg);
    assert_non_null(strstr(diag.msg, "views: right left"));
    assert_non_null(strstr(diag.msg, "depth channels: Z left.Z"));
}

static void test_shared_deep(void **state)
{
    const char *rel = "depth/v2_LowResLeftView_Trunks_deep.exr";
    const char *p = shared_file(rel);
    lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
    lt_exr_depth_t d;
    lt_diag_t diag;
    double mn = HUGE_VAL, mx = -HUGE_VAL, s = 0.0;
    long covered = 0, i;
    (void)state;
    if (p == NULL) {
        assert_int_equal(shared_missing(rel), 0);
        return;
    }
    assert_int_equal(lt_exr_read_depth(p, NULL, &o, &d, &diag), -1);
    ltt_report("  default: %s\n", diag.msg);
    assert_non_null(strstr(diag.msg, "deepscanline"));
    o.deep = LT_EXR_DEEP_FRONT;
    o.fill = -1.0f;
    o.color = 1;
    assert_int_equal(lt_exr_read_depth(p, NULL, &o, &d, &diag), 0);
    assert_int_equal(d.width, 1024);
    assert_int_equal(d.height, 435);
    assert_int_equal(d.y0, 141);
    assert_int_equal(d.z_type, LT_EXR_FLOAT);
    for (i = 0; i < (long)d.width * d.height; i++) {
        double v = (double)d.z[i];
        if (v == -1.0)
            continue;
        covered++;
        mn = v < mn ? v : mn;
        mx = v > mx ? v : mx;
        s += v;
    }
    /* reference: OpenEXR's C++ DeepScanLineInputFile, least Z per pixel (docs/io.md) */
    ltt_report("deep front-most: %llu samples, %ld covered px, front Z min %.6f max %.6f mean "
               "%.4f (C++ reference: 49152, 44329, 94.300232, 991.630127, 360.8085)\n",
               (unsigned long long)d.deep_samples, covered, mn, mx, s / (double)covered);
    assert_int_equal((long)d.deep_samples, 49152);
    assert_int_equal(covered, 44329);
    assert_true(fabs(mn - 94.300232) < 1e-5);
    assert_true(fabs(mx - 991.630127) < 1e-4);
    assert_true(fabs(s / (double)covered - 360.8085) < 1e-3);
    assert_non_null(d.rgba[0]);
    lt_exr_depth_free(&d);

    /* the deep file cut in half */
    assert_int_equal(copy_prefix(p, tpath("deep_half.exr"), 587334 / 2), 0);
    {
        unsigned cases = 0;
        expect_read_error(tpath("deep_half.exr"), NULL, 1, "deep chunk", &cases);
    }
}

static void test_shared_cut(void **state)
{
    const char *rel = "depth/beachball_singlepart.0001.exr";
    const char *p = shared_file(rel);
    unsigned cases = 0;
    (void)state;
    if (p == NULL) {
        assert_int_equal(shared_missing(rel), 0);
        return;
    }
    assert_int_equal(copy_prefix(p, tpath("beach_half.exr"), 2347698 / 2), 0);
    expect_read_error(tpath("beach_half.exr"), NULL, 0, "truncated or corrupt", &cases);
    ltt_report("beachball cut in half: clear error, no crash\n");
}

/* The shared single-part frame rewritten as a 2-part stereo file (part 0 left, part 1 right,
 * multiView right left, made here with the OpenEXR C API): each eye reads the same values as the
 * single-part file's view, colour included. */
static void test_shared_beachball_multipart(void **state)
{
    const char *rel = "depth/beachball_singlepart.0001.exr";
    const char *p = shared_file(rel), *mp = tpath("beach_stereo.exr");
    static const char *const eyes[2] = {"left", "right"};
    lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
    lt_exr_depth_t s, m;
    lt_diag_t diag;
    double mn[2], mx[2], mean[2], mmn, mmx, mmean;
    long n[2], mn_n, bad = 0, i;
    int e, c;
    (void)state;
    if (p == NULL) {
        assert_int_equal(shared_missing(rel), 0);
        return;
    }
    assert_int_equal(ltx_beachball_stereo(p, mp, &diag), 0);
    o.color = 1;
    for (e = 0; e < 2; e++) {
        /* the single-part file: "left" reads left.Z, "right" (the default view) Z */
        o.view = eyes[e];
        assert_int_equal(lt_exr_read_depth(p, NULL, &o, &s, &diag), 0);
        assert_string_equal(s.channel, e == 0 ? "left.Z" : "Z");
        stats(&s, &mn[e], &mx[e], &mean[e], &n[e]);
        /* the multi-part file: --view NAME, and the default view for right */
        assert_int_equal(lt_exr_read_depth(mp, NULL, &o, &m, &diag), 0);
        assert_int_equal(m.part, e);
        assert_string_equal(m.view, eyes[e]);
        assert_int_equal(m.color_part, e);
        stats(&m, &mmn, &mmx, &mmean, &mn_n);
        assert_int_equal(mn_n, n[e]);
        assert_true(mmn == mn[e] && mmx == mx[e] && mmean == mean[e]);
        for (i = 0; i < (long)s.width * s.height; i++) {
            bad += fbits(s.z[i]) != fbits(m.z[i]);
            for (c = 0; c < 4; c++)
                bad += fbits(s.rgba[c][i]) != fbits(m.rgba[c][i]);
        }
        lt_exr_depth_free(&s);
        lt_exr_depth_free(&m);
    }
    o.view = NULL;
    assert_int_equal(lt_exr_read_depth(mp, NULL, &o, &m, &diag), 0);
    assert_int_equal(m.part, 1);
    assert_string_equal(m.view, "right");
    lt_exr_depth_free(&m);
    ltt_report("beachball as a 2-part stereo file: default view right = part 1; left: %ld px, "
               "min %.4g max %.4g mean %.4f; right: %ld px, min %.4g max %.4g mean %.4f; both "
               "= the single-part file's views (Z and R G B A bit for bit: %ld differ, bound 0)\n",
               n[0], mn[0], mx[0], mean[0], n[1], mn[1], mx[1], mean[1], bad);
    assert_int_equal(bad, 0);
    assert_true(fabs(mx[0] - 10.26) < 0.005);
    assert_true(fabs(mx[1] - 10.92) < 0.005);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_half_conversion),  cmocka_unit_test(test_roundtrip),
        cmocka_unit_test(test_data_window),      cmocka_unit_test(test_multilayer),
        cmocka_unit_test(test_special_values),   cmocka_unit_test(test_tiled),
        cmocka_unit_test(test_deep_synthetic),   cmocka_unit_test(test_deep_bad_counts),
        cmocka_unit_test(test_zip_small_roundtrip), cmocka_unit_test(test_limits),
        cmocka_unit_test(test_corrupt),          cmocka_unit_test(test_header_bomb),
        cmocka_unit_test(test_write_errors),
        cmocka_unit_test(test_atomic_kill),      cmocka_unit_test(test_shared_beachball),
        cmocka_unit_test(test_shared_deep),      cmocka_unit_test(test_shared_cut),
        cmocka_unit_test(test_multipart_stereo), cmocka_unit_test(test_multipart_variants),
        cmocka_unit_test(test_shared_beachball_multipart),
    };
    return cmocka_run_group_tests(tests, setup_dir, teardown_dir);
}
