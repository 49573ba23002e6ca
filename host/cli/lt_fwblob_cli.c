/* lt_fwblob_cli.c - `lanetrace fwblob`: the reprojection blob of firmware/apps/reproj_app.h from a
 * real depth EXR. A crop of the EXR's depth (layer 0) and, with --layers 2, a second layer behind
 * it (the mirror of the visible surface about the plane of its deepest sample, below); z_ref and
 * w = z_ref / z in s1.30 (lt_qt_zref_exp, lt_qt_w_from_depth_q30, as lanetrace reproject does);
 * the source camera is lanetrace reproject's default camera of the whole EXR, cropped (principal
 * point shifted); the target is it moved and rotated (lt_rp_cam_move); lt_reproj_setup makes the
 * s1.30 mapping here, in double, so the targets only run the integer path. Host only.
 */
#include "cli/lt_fwblob_cli.h"
#include "cli/lt_cliutil.h"
#include "cli/lt_opt.h"
#include "io/lt_exr.h"
#include "io/lt_tmpfiles.h"
#include "render/lt_qt_ref.h"
#include "render/lt_reproject.h"
#include "reproj_app.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EXIT_INPUT 1
#define EXIT_USAGE 2

int lt_fwblob_cli(int argc, char **argv, const char *prog)
{
    static const char *const nums[] = {"n64", "n32", NULL};
    char who[256];
    const char *depth = NULL, *out = NULL;
    double crop[4] = {40, 120, 128, 128}, move[3] = {0.05, 0, 0}, rot[3] = {-2, 0, 0}, fov = 60.0;
    int layers = 2, num = 0, tile = 16, quiet = 0, seen_crop = 0;
    lt_exr_read_opts_t xo = LT_EXR_READ_OPTS_DEFAULT;
    lt_exr_depth_t d;
    lt_diag_t diag;
    lt_reproj_cam_t src, dst;
    lt_reproj_opts_t ro;
    lt_rpb_hdr_t h;
    uint32_t cx, cy, cw, ch, x, y, doff;
    size_t n, i, total;
    float *z = NULL, zmax = 0.0f;
    uint8_t *blob = NULL;
    double med, mv[3];
    int e, rc = EXIT_INPUT, a;
    lt_status_t s;
    const lt_opt_t opts[] = {
        LT_OPT_IN("--depth", "FILE.exr", &depth, "the depth EXR (its default view's Z)"),
        LT_OPT_OUT("--out", "FILE", &out, "", "the blob to write"),
        {.name = "--crop", .kind = LT_OPT_VEC, .dest = crop, .seen = &seen_crop,
         .meta = "X,Y,W,H", .lo = 0, .hi = LT_QT_MAX_DIM, .n = 4,
         .expect = "X,Y,W,H (whole pixels, the window inside the EXR's data window)",
         .help = "the window of the data window to take (default 40,120,128,128)"},
        LT_OPT_INT("--layers", "K", &layers, 1, 2,
                   "depth layers, {range} (default 2: the second is the mirror of the\n"
                   "first about the plane of the deepest depth sample)"),
        LT_OPT_VEC3("--move-rel", "X,Y,Z", move,
                    "target camera offset in median depths of the crop, source axes\n"
                    "(default 0.05,0,0)"),
        LT_OPT_VEC3("--rot", "YAW,PITCH,ROLL", rot, "target rotation, degrees (default -2,0,0)"),
        LT_OPT_DBL("--fov", "DEG", &fov, 1, 179,
                   "horizontal field of view over the EXR's display window (default 60)"),
        LT_OPT_ENUM_("--num", &num, nums, "quadtree node format, {choices} (default n64)"),
        LT_OPT_INT("--tile", "N", &tile, 4, 256,
                   "output tile side, pixels, a multiple of 4 in {range} (default 16)"),
        LT_OPT_FLAG_("-q", &quiet, "print nothing"),
        LT_OPT_END_};
    lt_opt_cmd_t cmd = {who, "--depth FILE.exr --out FILE [options]",
                        "Writes the reprojection blob of the firmware app (firmware/apps/\n"
                        "reproj_app.h; docs/firmware.md): a crop of the depth EXR, its layers as\n"
                        "s1.30 w = z_ref / z, and the s1.30 mapping to the moved camera.\n",
                        NULL, opts, NULL, 0, NULL};
    snprintf(who, sizeof who, "%s fwblob", prog);
    if ((a = lt_opt_parse(&cmd, argc, argv, 2)) != LT_OPT_OK)
        return lt_opt_exit_code(a);
    if (depth == NULL || out == NULL) {
        fprintf(stderr, "%s: --depth FILE.exr and --out FILE are required\n", who);
        return EXIT_USAGE;
    }
    for (a = 0; a < 4; a++)
        if (crop[a] != floor(crop[a]) || (a >= 2 && crop[a] < 1)) {
            fprintf(stderr, "%s: --crop X,Y,W,H: whole pixels, W and H >= 1\n", who);
            return EXIT_USAGE;
        }
    if ((tile & 3) != 0) {
        fprintf(stderr, "%s: --tile %d: a multiple of 4\n", who, tile);
        return EXIT_USAGE;
    }
    memset(&d, 0, sizeof d);
    if (lt_exr_read_depth(depth, NULL, &xo, &d, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    /* the source camera spans the display window (lt_rp_cam_default below) */
    if (lt_exr_camera_check(depth, &d.data_window, &d.display_window, &diag) != 0) {
        fprintf(stderr, "%s; fwblob's source camera spans it\n", diag.msg);
        goto done;
    }
    cx = (uint32_t)crop[0];
    cy = (uint32_t)crop[1];
    cw = (uint32_t)crop[2];
    ch = (uint32_t)crop[3];
    if ((uint64_t)cx + cw > (uint64_t)d.width || (uint64_t)cy + ch > (uint64_t)d.height) {
        fprintf(stderr, "%s: --crop %u,%u,%u,%u: outside the %dx%d data window\n", depth, cx, cy,
                cw, ch, d.width, d.height);
        goto done;
    }
    /* the deepest valid sample of the whole image: the plane the second layer mirrors about */
    for (i = 0; i < (size_t)d.width * (size_t)d.height; i++)
        if (isfinite(d.z[i]) && d.z[i] > zmax)
            zmax = d.z[i];
    n = (size_t)cw * ch;
    z = malloc(n * (size_t)layers * sizeof *z);
    /* the depth array starts at the first multiple of LT_RPB_ALIGN after the header */
    doff = (LT_RPB_HDR_BYTES + LT_RPB_ALIGN - 1u) / LT_RPB_ALIGN * LT_RPB_ALIGN;
    total = doff + n * (size_t)layers * sizeof(lt_q30_t);
    blob = calloc(1, total);
    if (z == NULL || blob == NULL) {
        fprintf(stderr, "%s: out of memory for a %ux%u crop\n", who, cw, ch);
        goto done;
    }
    for (y = 0; y < ch; y++)
        for (x = 0; x < cw; x++) {
            float z0 = d.z[(size_t)(cy + y) * (size_t)d.width + cx + x];
            z[(size_t)y * cw + x] = z0;
            /* layer 1: a depth peel of a convex object seen against the background, estimated:
               the visible surface mirrored about the plane z = zmax through its deepest (rim)
               samples (the back of the ball); holes stay holes. Behind layer 0 by construction. */
            if (layers == 2)
                z[n + (size_t)y * cw + x] =
                    isfinite(z0) && z0 > 0.0f ? 2.0f * zmax - z0 : z0;
        }
    if (lt_qt_zref_exp(z, n * (size_t)layers, &e) != 0) {
        fprintf(stderr, "%s: the crop %u,%u,%u,%u has no valid depth\n", depth, cx, cy, cw, ch);
        goto done;
    }
    memset(&h, 0, sizeof h);
    h.depth_off = doff;
    (void)lt_qt_w_from_depth_q30(z, n * (size_t)layers, e, (lt_q30_t *)(void *)(blob + doff));

    /* the cameras: the whole EXR's default camera, cropped; the target moved and rotated */
    lt_rp_cam_default((uint32_t)d.width, (uint32_t)d.height,
                      d.display_window.x1 - d.display_window.x0 + 1,
                      d.display_window.y1 - d.display_window.y0 + 1, d.x0 - d.display_window.x0,
                      d.y0 - d.display_window.y0, fov, &src);
    src.cx -= (double)cx;
    src.cy -= (double)cy;
    src.width = cw;
    src.height = ch;
    med = lt_rp_median_depth(z, n);
    for (a = 0; a < 3; a++)
        mv[a] = move[a] * med;
    lt_rp_cam_move(&src, mv, rot, &dst);
    memset(&ro, 0, sizeof ro);
    ro.z_ref = ldexp(1.0, e);
    if ((s = lt_reproj_setup(&src, &dst, &ro, &h.map, NULL)) != LT_OK) {
        fprintf(stderr, "%s: camera setup failed (%s)\n", who, lt_status_str(s));
        goto done;
    }

    h.magic = LT_RPB_MAGIC;
    h.version = LT_RPB_VERSION;
    h.hdr_bytes = LT_RPB_HDR_BYTES;
    h.blob_bytes = (uint32_t)total;
    h.width = cw;
    h.height = ch;
    h.layers = (uint32_t)layers;
    h.enc = num == 0 ? (uint32_t)LT_QT_N64 : (uint32_t)LT_QT_N32;
    h.depth_format = LT_RPB_DEPTH_W_Q30;
    h.depth_bytes = (uint32_t)(n * (size_t)layers * sizeof(lt_q30_t));
    h.zref_exp = e;
    h.tile = (uint32_t)tile;
    h.max_steps = 0;
    h.crop_x = cx;
    h.crop_y = cy;
    h.src_exr_w = (uint32_t)d.width;
    h.src_exr_h = (uint32_t)d.height;
    lt_qt_params_default(&h.params);
    memcpy(blob, &h, sizeof h);
    h.checksum = lt_rpb_fnv(2166136261u, blob + LT_RPB_SUM_FROM, total - LT_RPB_SUM_FROM);
    memcpy(blob, &h, sizeof h);
    if (lt_write_file_atomic(out, blob, total, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        goto done;
    }
    if (!quiet) {
        char tc[256], tv[256];
        printf("%s: crop %u,%u %ux%u of %s (%dx%d, channel %s%s%s), %u layer%s", out, cx, cy, cw,
               ch, depth, d.width, d.height, lt_shown(d.channel, tc, sizeof tc),
               d.view[0] != '\0' ? ", view " : "", lt_shown(d.view, tv, sizeof tv),
               (unsigned)layers, layers > 1 ? "s" : "");
        if (layers == 2)
            printf(" (layer 1 = layer 0 mirrored about z = %.6g)", (double)zmax);
        printf("\n  z_ref 2^%d, median depth %.6g; target moved %.6g,%.6g,%.6g, turned %g,%g,%g "
               "deg; %s nodes, tiles %dx%d\n  %zu bytes, checksum 0x%08x\n",
               e, med, mv[0], mv[1], mv[2], rot[0], rot[1], rot[2], nums[num], tile, tile, total,
               h.checksum);
    }
    rc = 0;
done:
    free(z);
    free(blob);
    lt_exr_depth_free(&d);
    return rc;
}
