/* lt_reproject_cli.c - `lanetrace reproject`: view synthesis from a depth EXR through the
 * screen-space quadtree (docs/reproject.md). Options, EXR depth layers and colour, source camera
 * (flags, a scene file with 'depth' + 'camera', lanetrace render's camera for a mesh scene, or the
 * documented default), target camera (move / rotate / intrinsics / size), lt_rp_run, outputs:
 * EXR (R G B Z hole steps [cycles]), PNG, heatmap PNGs with legends, the cycle report (sim build)
 * as text and JSON. Exit codes: 0 ok, 1 input or runtime error, 2 usage. Host only.
 */
#include "lt_reproject_cli.h"
#include "lt_exr.h"
#include "lt_heatmap.h"
#include "lt_mesh.h"
#include "lt_png.h"
#include "lt_reproject.h"
#include "lt_scene.h"
#include "lt_scenefile.h"
#if LT_COST_MODE == LT_COST_SIM
#include "lt_sim.h"
#endif

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define EXIT_INPUT 1
#define EXIT_USAGE 2
#define RP_DEFAULT_FOV 60.0

void lt_rp_cli_usage(const char *prog, FILE *f)
{
    fprintf(f,
            "usage: %s reproject [SCENE.json] --depth FILE.exr [options]\n"
            "Synthesise a new view of a depth image by screen-space ray tracing through the\n"
            "adaptive quadtree (Widmer et al.): every target pixel's ray is reprojected into the\n"
            "source view and traced over all depth layers; holes are inpainted.\n"
            "input:\n"
            "  --depth FILE.exr     source depth (z along the optical axis unless --dist)\n"
            "  --channel NAME       depth channel (default: Z, depth, the default view's Z)\n"
            "  --layers K           use the depth peels layer0.Z .. layer<K-1>.Z (lanetrace\n"
            "                       render --layers K), 1..%d\n"
            "  --color              fetch colour from R G B of the depth's layer (else grey = w)\n"
            "  --dist               depth values are distances along the pixel ray (lanetrace\n"
            "                       render's Z; the default with a mesh scene)\n"
            "cameras (pinhole, x right, y down, z forward; pixels, world units of the depth):\n"
            "  --src-cam FX,FY,CX,CY  source intrinsics (default: a scene's camera, else a %g-degree\n"
            "                       horizontal field of view over the EXR display window, centred)\n"
            "  --fov DEG            the default camera's horizontal field of view (1..179)\n"
            "  --move X,Y,Z         target = source moved along its own axes (world units)\n"
            "  --move-rel X,Y,Z     the same in units of the median source depth\n"
            "  --rot YAW,PITCH,ROLL target rotation, degrees (yaw + turns right, pitch + up)\n"
            "  --dst-cam FX,FY,CX,CY  target intrinsics (default: the source's, scaled with --res)\n"
            "  --res WxH|N          target size (default: the source's), 1..%u\n"
            "tracing:\n"
            "  --enc n64|n32|f32    quadtree node format / numeric path (default n64)\n"
            "  --sample bilinear|nearest  colour fetch (default: depth-aware bilinear)\n"
            "  --no-inpaint         leave holes black (depth NaN)\n"
            "  --max-steps N        quadtree nodes per ray per layer (default 8(w+h)+4 levels+16)\n"
            "  --machine NAME       (simulator build) machine model: lrb16, mcu-m4\n"
            "outputs:\n"
            "  --out FILE.exr       R G B (linear), Z (target depth, inf = background), hole (0 hit,\n"
            "                       1 background, 2 disoccluded, 3 outside, 4 step bound), steps,\n"
            "                       cycles (simulator build)\n"
            "  --png FILE.png       the view (gamma 2.2)\n"
            "  --heat-steps FILE.png  quadtree nodes per pixel, with legend\n"
            "  --heat-cycles FILE.png (simulator build) simulated cycles per pixel, with legend\n"
            "  --report FILE.json   (simulator build) the cycle report as JSON\n"
            "  --json               the summary as JSON on stdout\n"
            "  -q                   quiet: no summary, no report text\n"
            "A scene file may give 'depth', 'camera' (the source) and a 'reproject' object\n"
            "(docs/scene-format.md); flags override it.\n",
            prog, LT_RP_MAX_LAYERS, RP_DEFAULT_FOV, LT_QT_MAX_DIM);
}

/* ---- small parsers ------------------------------------------------------------------------- */

static int parse_vec(const char *s, double *v, int n)
{
    int i;
    const char *p = s;
    for (i = 0; i < n; i++) {
        char *end;
        v[i] = strtod(p, &end);
        if (end == p || !isfinite(v[i]))
            return -1;
        p = end;
        if (i + 1 < n) {
            if (*p != ',')
                return -1;
            p++;
        }
    }
    return *p == '\0' ? 0 : -1;
}

static int parse_wh(const char *s, uint32_t *w, uint32_t *h)
{
    unsigned long a, b;
    char *end;
    a = strtoul(s, &end, 10);
    b = a;
    if (end == s)
        return -1;
    if (*end == 'x')
        b = strtoul(end + 1, &end, 10);
    if (*end != '\0' || a == 0 || b == 0 || a > LT_QT_MAX_DIM || b > LT_QT_MAX_DIM)
        return -1;
    *w = (uint32_t)a;
    *h = (uint32_t)b;
    return 0;
}

static uint8_t to8(float v)
{
    double d = (double)v;
    d = d < 0.0 || d != d ? 0.0 : (d > 1.0 ? 1.0 : d);
    return (uint8_t)(255.0 * pow(d, 1.0 / 2.2) + 0.5);
}

#if LT_COST_MODE == LT_COST_SIM
static int write_text_atomic(const char *path, const char *text, char *err, size_t errlen)
{
    char tmp[1200];
    FILE *f;
    snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)getpid());
    f = fopen(tmp, "w");
    if (f == NULL) {
        snprintf(err, errlen, "%s: cannot create the output (directory missing or not writable)",
                 path);
        return -1;
    }
    if (fputs(text, f) < 0 || fclose(f) != 0) {
        unlink(tmp);
        snprintf(err, errlen, "%s: write failed (disk full?)", path);
        return -1;
    }
    if (rename(tmp, path) != 0) {
        unlink(tmp);
        snprintf(err, errlen, "%s: cannot rename the output into place", path);
        return -1;
    }
    return 0;
}
#endif

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

/* Median of the valid (finite, > 0) depths of layer 0, or 0 when none. */
static double median_depth(const float *z, size_t n)
{
    float *v = malloc(n * sizeof *v);
    size_t i, m = 0;
    double r = 0.0;
    if (v == NULL)
        return 0.0;
    for (i = 0; i < n; i++)
        if (isfinite(z[i]) && z[i] > 0.0f)
            v[m++] = z[i];
    if (m > 0) {
        qsort(v, m, sizeof *v, cmp_float);
        r = (double)v[m / 2];
    }
    free(v);
    return r;
}

/* A look-at camera as lanetrace render builds it (lt_camera_look): fwd = target - eye, right =
 * fwd x up, up' = right x fwd; fov_y over the image height. Rows: right, -up', fwd. */
static void cam_from_basis(const double eye[3], const double fwd[3], const double right[3],
                           const double up[3], double tan_half_fov, uint32_t w, uint32_t h,
                           lt_reproj_cam_t *c)
{
    int i;
    memset(c, 0, sizeof *c);
    c->fy = c->fx = 0.5 * (double)h / tan_half_fov;
    c->cx = 0.5 * (double)w;
    c->cy = 0.5 * (double)h;
    for (i = 0; i < 3; i++) {
        c->r[0][i] = right[i];
        c->r[1][i] = -up[i];
        c->r[2][i] = fwd[i];
        c->c[i] = eye[i];
    }
    c->width = w;
    c->height = h;
}

static void normalize3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0.0) {
        v[0] /= l;
        v[1] /= l;
        v[2] /= l;
    }
}

static void cross3(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

/* ---- the command --------------------------------------------------------------------------- */

int lt_rp_cli(int argc, char **argv, const char *prog, const lt_rp_cli_hooks_t *hk)
{
    lt_scenefile_t sf;
    lt_rp_source_t src;
    lt_reproj_cam_t dcam;
    lt_rp_opts_t ro;
    lt_rp_result_t res;
    lt_exr_depth_t dl[LT_RP_MAX_LAYERS], dc;
    lt_exr_read_opts_t xo = LT_EXR_READ_OPTS_DEFAULT;
    char err[1024];
    const char *scene_path = NULL, *depth = NULL, *channel = NULL, *out = NULL, *png = NULL;
    const char *heat_steps = NULL, *heat_cycles = NULL, *report = NULL, *machine = NULL;
    double move[3] = {0, 0, 0}, rot[3] = {0, 0, 0}, srck[4], dstk[4], fov = RP_DEFAULT_FOV;
    int have_srck = 0, have_dstk = 0, have_move = 0, move_rel = 0, have_rot = 0, color = 0;
    int dist = -1, json = 0, layers = 0, status = 0, a, l, enc = -1, bilinear = 1, inpaint = 1;
    uint32_t dw = 0, dh = 0, W, H, max_steps = 0;
    float *zall = NULL, *rgb[LT_RP_MAX_LAYERS];
    size_t i, n;
    const char *cam_desc = "default";
    static const char *const enc_name[3] = {"n64", "n32", "f32"};
    double median = 0.0;

    memset(dl, 0, sizeof dl);
    memset(&dc, 0, sizeof dc);
    memset(&res, 0, sizeof res);
    memset(rgb, 0, sizeof rgb);
    lt_sf_defaults(&sf);
    for (a = 2; a < argc; a++) {
        const char *o = argv[a], *v = a + 1 < argc ? argv[a + 1] : NULL;
        if (strcmp(o, "--help") == 0 || strcmp(o, "-h") == 0) {
            lt_rp_cli_usage(prog, stdout);
            return 0;
        }
        if (strcmp(o, "-q") == 0) {
            *hk->quiet = 1;
            continue;
        }
        if (strcmp(o, "--json") == 0) {
            json = *hk->quiet = 1;
            continue;
        }
        if (strcmp(o, "--color") == 0 || strcmp(o, "--colour") == 0) {
            color = 1;
            continue;
        }
        if (strcmp(o, "--dist") == 0) {
            dist = 1;
            continue;
        }
        if (strcmp(o, "--no-inpaint") == 0) {
            inpaint = 0;
            continue;
        }
        if (o[0] != '-') {
            if (scene_path != NULL) {
                fprintf(stderr, "%s reproject: more than one scene file ('%s', '%s')\n", prog,
                        scene_path, o);
                return EXIT_USAGE;
            }
            scene_path = o;
            continue;
        }
        if (v == NULL) {
            fprintf(stderr, "%s reproject: unknown option '%s' or missing value\n", prog, o);
            return EXIT_USAGE;
        }
        a++;
        if (strcmp(o, "--depth") == 0) {
            depth = v;
        } else if (strcmp(o, "--channel") == 0) {
            channel = v;
        } else if (strcmp(o, "--out") == 0) {
            out = v;
        } else if (strcmp(o, "--png") == 0) {
            png = v;
        } else if (strcmp(o, "--heat-steps") == 0) {
            heat_steps = v;
        } else if (strcmp(o, "--heat-cycles") == 0) {
            heat_cycles = v;
        } else if (strcmp(o, "--report") == 0) {
            report = v;
        } else if (strcmp(o, "--machine") == 0) {
            machine = v;
        } else if (strcmp(o, "--layers") == 0) {
            char *end;
            long k = strtol(v, &end, 10);
            if (*end != '\0' || k < 1 || k > LT_RP_MAX_LAYERS) {
                fprintf(stderr, "%s reproject: --layers %s: expected 1..%d\n", prog, v,
                        LT_RP_MAX_LAYERS);
                return EXIT_USAGE;
            }
            layers = (int)k;
        } else if (strcmp(o, "--src-cam") == 0 || strcmp(o, "--dst-cam") == 0) {
            double *k = o[2] == 's' ? srck : dstk;
            if (parse_vec(v, k, 4) != 0 || !(k[0] > 0.0) || !(k[1] > 0.0)) {
                fprintf(stderr, "%s reproject: %s %s: expected FX,FY,CX,CY in pixels, FX and FY "
                                "> 0 and finite\n", prog, o, v);
                return EXIT_USAGE;
            }
            if (o[2] == 's')
                have_srck = 1;
            else
                have_dstk = 1;
        } else if (strcmp(o, "--fov") == 0) {
            if (parse_vec(v, &fov, 1) != 0 || fov < 1.0 || fov > 179.0) {
                fprintf(stderr, "%s reproject: --fov %s: expected degrees in 1..179\n", prog, v);
                return EXIT_USAGE;
            }
        } else if (strcmp(o, "--move") == 0 || strcmp(o, "--move-rel") == 0) {
            if (parse_vec(v, move, 3) != 0) {
                fprintf(stderr, "%s reproject: %s %s: expected X,Y,Z (3 finite numbers)\n", prog,
                        o, v);
                return EXIT_USAGE;
            }
            have_move = 1;
            move_rel = strcmp(o, "--move-rel") == 0;
        } else if (strcmp(o, "--rot") == 0) {
            if (parse_vec(v, rot, 3) != 0 || fabs(rot[0]) > 180.0 || fabs(rot[1]) > 180.0 ||
                fabs(rot[2]) > 180.0) {
                fprintf(stderr, "%s reproject: --rot %s: expected YAW,PITCH,ROLL in degrees, "
                                "each in -180..180\n", prog, v);
                return EXIT_USAGE;
            }
            have_rot = 1;
        } else if (strcmp(o, "--res") == 0) {
            if (parse_wh(v, &dw, &dh) != 0) {
                fprintf(stderr, "%s reproject: --res %s: expected WxH or N, 1..%u (LT_QT_MAX_DIM)\n",
                        prog, v, LT_QT_MAX_DIM);
                return EXIT_USAGE;
            }
        } else if (strcmp(o, "--enc") == 0) {
            for (enc = 0; enc < 3 && strcmp(v, enc_name[enc]) != 0; enc++)
                ;
            if (enc == 3) {
                fprintf(stderr, "%s reproject: --enc %s: expected n64, n32 or f32\n", prog, v);
                return EXIT_USAGE;
            }
        } else if (strcmp(o, "--sample") == 0) {
            if (strcmp(v, "bilinear") != 0 && strcmp(v, "nearest") != 0) {
                fprintf(stderr, "%s reproject: --sample %s: expected bilinear or nearest\n", prog,
                        v);
                return EXIT_USAGE;
            }
            bilinear = strcmp(v, "bilinear") == 0;
        } else if (strcmp(o, "--max-steps") == 0) {
            char *end;
            unsigned long k = strtoul(v, &end, 10);
            if (*end != '\0' || k < 1 || k > 100000000ul || v[0] == '-') {
                fprintf(stderr, "%s reproject: --max-steps %s: expected 1..100000000\n", prog, v);
                return EXIT_USAGE;
            }
            max_steps = (uint32_t)k;
        } else {
            fprintf(stderr, "%s reproject: unknown option '%s'\n", prog, o);
            lt_rp_cli_usage(prog, stderr);
            return EXIT_USAGE;
        }
    }
#if LT_COST_MODE != LT_COST_SIM
    if (heat_cycles != NULL || report != NULL || machine != NULL) {
        fprintf(stderr, "%s reproject: %s needs the simulator build (build/sim/lanetrace); this is "
                        "the native build\n", prog,
                heat_cycles != NULL ? "--heat-cycles" : report != NULL ? "--report" : "--machine");
        return EXIT_USAGE;
    }
#endif
    if (scene_path != NULL && lt_sf_load(scene_path, &sf, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return EXIT_INPUT;
    }
    if (depth == NULL && sf.depth[0] != '\0')
        depth = sf.depth;
    if (depth == NULL) {
        fprintf(stderr, "%s reproject: --depth FILE.exr is required (or a scene file with "
                        "'depth')\n", prog);
        return EXIT_USAGE;
    }
    /* scene defaults under the flags */
    if (sf.has_reproject) {
        if (!have_move) {
            memcpy(move, sf.rp_move, sizeof move);
            move_rel = sf.rp_move_rel;
        }
        if (!have_rot)
            memcpy(rot, sf.rp_rot, sizeof rot);
        if (enc < 0 && sf.rp_encoding[0] != '\0')
            for (enc = 0; enc < 3 && strcmp(sf.rp_encoding, enc_name[enc]) != 0; enc++)
                ;
        if (layers == 0 && sf.rp_layers > 0)
            layers = (int)sf.rp_layers;
        if (channel == NULL && sf.rp_channel[0] != '\0')
            channel = sf.rp_channel;
        color |= sf.rp_color;
        if (dist < 0 && sf.rp_distance)
            dist = 1;
    }
    if (enc < 0)
        enc = 0;
    if (machine == NULL)
        machine = sf.machine;
#if LT_COST_MODE == LT_COST_SIM
    {
        const lt_machine_t *m = lt_sim_machine_find(machine);
        if (m == NULL) {
            fprintf(stderr, "%s reproject: --machine %s: unknown (lrb16, mcu-m4)\n", prog, machine);
            return EXIT_USAGE;
        }
        if (lt_sim_init(m, NULL, NULL, err, sizeof err) != 0) {
            fprintf(stderr, "%s\n", err);
            return EXIT_USAGE;
        }
    }
#endif

    /* ---- depth layers and colour ---- */
    if (layers == 0)
        layers = 1;
    for (l = 0; l < layers; l++) {
        char name[64];
        const char *ch = channel;
        if (layers > 1) {
            snprintf(name, sizeof name, "layer%d.Z", l);
            ch = name;
        }
        xo.color = color && layers > 1 && l > 0;
        if (lt_exr_read_depth(depth, ch, &xo, &dl[l], err, sizeof err) != 0) {
            fprintf(stderr, "%s\n", err);
            status = EXIT_INPUT;
            goto done;
        }
        if (l > 0 && (dl[l].width != dl[0].width || dl[l].height != dl[0].height)) {
            fprintf(stderr, "%s: channel %s is %dx%d, layer 0 is %dx%d\n", depth, dl[l].channel,
                    dl[l].width, dl[l].height, dl[0].width, dl[0].height);
            status = EXIT_INPUT;
            goto done;
        }
    }
    W = (uint32_t)dl[0].width;
    H = (uint32_t)dl[0].height;
    n = (size_t)W * H;
    if (W > LT_QT_MAX_DIM || H > LT_QT_MAX_DIM) {
        fprintf(stderr, "%s: %ux%u exceeds LT_QT_MAX_DIM %u per side\n", depth, W, H,
                LT_QT_MAX_DIM);
        status = EXIT_INPUT;
        goto done;
    }
    if (color) {
        /* layer 0's colour: R G B next to the base depth channel (the render's primary hit) */
        xo.color = 1;
        if (lt_exr_read_depth(depth, layers > 1 ? channel : dl[0].channel, &xo, &dc, err,
                              sizeof err) == 0 &&
            dc.width == (int32_t)W && dc.height == (int32_t)H && dc.rgba[0] != NULL &&
            dc.rgba[1] != NULL && dc.rgba[2] != NULL) {
            dl[0].rgba[0] = dc.rgba[0];
            dl[0].rgba[1] = dc.rgba[1];
            dl[0].rgba[2] = dc.rgba[2];
        } else if (!*hk->quiet) {
            fprintf(stderr, "%s: no R G B channels next to %s: layer 0 shown as grey = w\n", depth,
                    dl[0].channel);
        }
    }
    zall = malloc(n * (size_t)layers * sizeof *zall);
    if (zall == NULL) {
        fprintf(stderr, "%s reproject: out of memory for %d layers of %ux%u\n", prog, layers, W, H);
        status = EXIT_INPUT;
        goto done;
    }
    for (l = 0; l < layers; l++) {
        memcpy(zall + (size_t)l * n, dl[l].z, n * sizeof *zall);
        if (color && dl[l].rgba[0] != NULL && dl[l].rgba[1] != NULL && dl[l].rgba[2] != NULL) {
            rgb[l] = malloc(n * 3 * sizeof(float));
            if (rgb[l] == NULL) {
                fprintf(stderr, "%s reproject: out of memory for colour\n", prog);
                status = EXIT_INPUT;
                goto done;
            }
            for (i = 0; i < n; i++) {
                rgb[l][3 * i] = dl[l].rgba[0][i];
                rgb[l][3 * i + 1] = dl[l].rgba[1][i];
                rgb[l][3 * i + 2] = dl[l].rgba[2][i];
            }
        }
    }

    /* ---- source camera ---- */
    memset(&src, 0, sizeof src);
    if (have_srck) {
        int r;
        src.cam.fx = srck[0];
        src.cam.fy = srck[1];
        src.cam.cx = srck[2];
        src.cam.cy = srck[3];
        for (r = 0; r < 3; r++)
            src.cam.r[r][r] = 1.0;
        src.cam.width = W;
        src.cam.height = H;
        cam_desc = "--src-cam";
    } else if (sf.mesh[0] != '\0') {
        /* lanetrace render's camera for this scene, in its scaled units */
        lt_mesh_t mesh;
        lt_scene_t sc;
        lt_camera_t cam;
        if (lt_mesh_load(sf.mesh, &mesh, err, sizeof err) != 0) {
            fprintf(stderr, "%s\n", err);
            status = EXIT_INPUT;
            goto done;
        }
        if (lt_scene_prepare(&mesh, &sc, err, sizeof err) != 0) {
            fprintf(stderr, "%s: %s\n", sf.mesh, err);
            lt_mesh_free(&mesh);
            status = EXIT_INPUT;
            goto done;
        }
        if (sf.has_camera) {
            if (lt_camera_look(&sc, sf.eye, sf.target, sf.up, sf.fov_y_deg, W, H, &cam, err,
                               sizeof err) != 0) {
                fprintf(stderr, "%s: %s\n", sf.path, err);
                lt_scene_free(&sc);
                lt_mesh_free(&mesh);
                status = EXIT_INPUT;
                goto done;
            }
        } else {
            lt_camera_default(&sc, W, H, &cam);
        }
        cam_from_basis(cam.eye, cam.fwd, cam.right, cam.up, cam.tan_half_fov, W, H, &src.cam);
        lt_scene_free(&sc);
        lt_mesh_free(&mesh);
        if (dist < 0)
            dist = 1;
        cam_desc = "the scene's render camera";
    } else if (sf.has_camera) {
        double f[3], r[3], u[3];
        int k;
        for (k = 0; k < 3; k++)
            f[k] = sf.target[k] - sf.eye[k];
        normalize3(f);
        cross3(f, sf.up, r);
        normalize3(r);
        cross3(r, f, u);
        cam_from_basis(sf.eye, f, r, u, tan(0.5 * sf.fov_y_deg * 3.14159265358979323846 / 180.0),
                       W, H, &src.cam);
        cam_desc = "the scene's camera";
    } else {
        int32_t disp_w = dl[0].display_window.x1 - dl[0].display_window.x0 + 1;
        int32_t disp_h = dl[0].display_window.y1 - dl[0].display_window.y0 + 1;
        lt_rp_cam_default(W, H, disp_w, disp_h, dl[0].x0 - dl[0].display_window.x0,
                          dl[0].y0 - dl[0].display_window.y0, fov, &src.cam);
        cam_desc = "default";
    }
    if (dist == 1) {
        /* distance along the unit pixel ray -> z along the optical axis */
        for (l = 0; l < layers; l++)
            for (i = 0; i < n; i++) {
                double x = ((double)(i % W) + 0.5 - src.cam.cx) / src.cam.fx;
                double y = ((double)(i / W) + 0.5 - src.cam.cy) / src.cam.fy;
                float *z = &zall[(size_t)l * n + i];
                *z = (float)((double)*z / sqrt(x * x + y * y + 1.0));
            }
    }
    src.width = W;
    src.height = H;
    src.layers = (uint32_t)layers;
    src.z = zall;
    for (l = 0; l < layers; l++)
        src.rgb[l] = rgb[l];
    median = median_depth(zall, n);

    /* ---- target camera ---- */
    if (move_rel) {
        for (a = 0; a < 3; a++)
            move[a] *= median;
    }
    lt_rp_cam_move(&src.cam, move, rot, &dcam);
    if (dw != 0 && !have_dstk) {
        double sx = (double)dw / (double)W, sy = (double)dh / (double)H;
        dcam.fx *= sx;
        dcam.cx *= sx;
        dcam.fy *= sy;
        dcam.cy *= sy;
    }
    if (dw != 0) {
        dcam.width = dw;
        dcam.height = dh;
    }
    if (have_dstk) {
        dcam.fx = dstk[0];
        dcam.fy = dstk[1];
        dcam.cx = dstk[2];
        dcam.cy = dstk[3];
    }

    /* ---- run ---- */
    lt_rp_opts_default(&ro);
    ro.enc = (lt_qt_enc_t)enc;
    ro.bilinear = bilinear;
    ro.inpaint = inpaint;
    ro.max_steps = max_steps;
    ro.progress = hk->progress;
    hk->begin("reproject");
    if (lt_rp_run(&src, &dcam, &ro, &res, err, sizeof err) != 0) {
        hk->end();
        fprintf(stderr, "%s: %s\n", depth, err);
        status = EXIT_INPUT;
        goto done;
    }
    hk->end();

    /* ---- outputs ---- */
    {
        size_t np = (size_t)res.width * res.height;
        float *ch[5];
        int k;
        memset(ch, 0, sizeof ch);
        for (k = 0; k < 5; k++)
            ch[k] = malloc(np * sizeof(float));
        if (ch[0] == NULL || ch[1] == NULL || ch[2] == NULL || ch[3] == NULL || ch[4] == NULL) {
            fprintf(stderr, "%s reproject: out of memory for the outputs\n", prog);
            status = EXIT_INPUT;
        } else {
            for (i = 0; i < np; i++) {
                ch[0][i] = res.rgb[3 * i];
                ch[1][i] = res.rgb[3 * i + 1];
                ch[2][i] = res.rgb[3 * i + 2];
                ch[3][i] = (float)res.cls[i];
            }
        }
        if (status == 0 && out != NULL) {
            lt_exr_channel_t ec[7];
            lt_exr_image_t im;
            int nc = 0;
            ec[nc].name = "R";
            ec[nc].type = LT_EXR_FLOAT;
            ec[nc++].data = ch[0];
            ec[nc].name = "G";
            ec[nc].type = LT_EXR_FLOAT;
            ec[nc++].data = ch[1];
            ec[nc].name = "B";
            ec[nc].type = LT_EXR_FLOAT;
            ec[nc++].data = ch[2];
            ec[nc].name = "Z";
            ec[nc].type = LT_EXR_FLOAT;
            ec[nc++].data = res.z;
            ec[nc].name = "hole";
            ec[nc].type = LT_EXR_HALF;
            ec[nc++].data = ch[3];
            ec[nc].name = "steps";
            ec[nc].type = LT_EXR_FLOAT;
            ec[nc++].data = res.steps;
#if LT_COST_MODE == LT_COST_SIM
            ec[nc].name = "cycles";
            ec[nc].type = LT_EXR_FLOAT;
            ec[nc++].data = res.cycles;
#endif
            memset(&im, 0, sizeof im);
            im.width = (int32_t)res.width;
            im.height = (int32_t)res.height;
            im.nchannels = nc;
            im.channels = ec;
            if (lt_exr_write(out, &im, err, sizeof err) != 0) {
                fprintf(stderr, "%s\n", err);
                status = EXIT_INPUT;
            }
        }
        if (status == 0 && png != NULL) {
            uint8_t *px = malloc(np * 3);
            if (px == NULL) {
                fprintf(stderr, "%s reproject: out of memory for the PNG\n", prog);
                status = EXIT_INPUT;
            } else {
                for (i = 0; i < np * 3; i++)
                    px[i] = to8(res.rgb[i]);
                if (lt_png_write(png, px, (int32_t)res.width, (int32_t)res.height, 3, 0, err,
                                 sizeof err) != 0) {
                    fprintf(stderr, "%s\n", err);
                    status = EXIT_INPUT;
                }
                free(px);
            }
        }
        if (status == 0 && heat_steps != NULL &&
            lt_heatmap_write_png(heat_steps, res.steps, (int32_t)res.width, (int32_t)res.height,
                                 NULL, err, sizeof err) != 0) {
            fprintf(stderr, "%s\n", err);
            status = EXIT_INPUT;
        }
        if (status == 0 && heat_cycles != NULL &&
            lt_heatmap_write_png(heat_cycles, res.cycles, (int32_t)res.width, (int32_t)res.height,
                                 NULL, err, sizeof err) != 0) {
            fprintf(stderr, "%s\n", err);
            status = EXIT_INPUT;
        }
        for (k = 0; k < 5; k++)
            free(ch[k]);
        if (status != 0)
            goto done;
    }

    /* ---- summary, report ---- */
    {
        const lt_rp_stats_t *st = &res.st;
        double rays = st->rays > 0 ? (double)st->rays : 1.0, px = (double)st->pixels;
        double holes = (double)(st->cls[LT_RP_DISOCCLUDED] + st->cls[LT_RP_OUTSIDE] +
                                st->cls[LT_RP_UNKNOWN]);
        double util = st->lane_ops > 0 ? (double)st->lanes_on / (16.0 * (double)st->lane_ops) : 0.0;
        char title[1400];
        (void)util;
        snprintf(title, sizeof title, "reproject %s %ux%u x %d layer(s) -> %ux%u, %s", depth, W, H,
                 layers, res.width, res.height, enc_name[enc]);
        if (!*hk->quiet) {
            printf("source    %s: %ux%u, %d layer(s), channel %s%s, z_ref %g, median depth %.4g\n",
                   depth, W, H, layers, dl[0].channel, dist == 1 ? " (distances)" : "", st->zref,
                   median);
            printf("cameras   source %s: f %.2f,%.2f c %.2f,%.2f; target moved %.4g,%.4g,%.4g "
                   "rotated %.3g,%.3g,%.3g deg, %ux%u\n",
                   cam_desc, src.cam.fx, src.cam.fy, src.cam.cx, src.cam.cy, dcam.c[0] - src.cam.c[0],
                   dcam.c[1] - src.cam.c[1], dcam.c[2] - src.cam.c[2], rot[0], rot[1], rot[2],
                   res.width, res.height);
            printf("quadtree  %s: %llu nodes (%llu planes), %zu bytes, build %.3f s\n",
                   enc_name[enc], (unsigned long long)st->qt_nodes,
                   (unsigned long long)st->qt_planes, st->qt_bytes, st->t_build);
            printf("rays      %llu of %llu pixels traced in %llu packets, %.3f s (%.2f Mrays/s)\n",
                   (unsigned long long)st->rays, (unsigned long long)st->pixels,
                   (unsigned long long)st->packets, st->t_trace,
                   st->t_trace > 0 ? (double)st->rays / st->t_trace * 1e-6 : 0.0);
            printf("per ray   nodes %.2f (max %u), AABB tests %.2f (max %u), plane tests %.2f "
                   "(max %u)\n",
                   (double)st->nodes / rays, st->nodes_max, (double)st->aabb / rays, st->aabb_max,
                   (double)st->planes / rays, st->planes_max);
            printf("pixels    hit %.2f%%, background %.2f%%, disoccluded %.2f%%, outside %.2f%%, "
                   "step bound %.2f%%; holes %.2f%% %s\n",
                   100.0 * (double)st->cls[LT_RP_HIT] / px,
                   100.0 * (double)st->cls[LT_RP_BACKGROUND] / px,
                   100.0 * (double)st->cls[LT_RP_DISOCCLUDED] / px,
                   100.0 * (double)st->cls[LT_RP_OUTSIDE] / px,
                   100.0 * (double)st->cls[LT_RP_UNKNOWN] / px, 100.0 * holes / px,
                   inpaint ? "(inpainted)" : "(left black)");
#if LT_COST_MODE == LT_COST_SIM
            printf("cycles    build %llu, setup %llu (%.1f per ray), traverse %llu (%.1f per ray); "
                   "lane utilisation %.1f%%\n",
                   (unsigned long long)st->cyc_build, (unsigned long long)st->cyc_setup,
                   (double)st->cyc_setup / px, (unsigned long long)st->cyc_trace,
                   (double)st->cyc_trace / rays, 100.0 * util);
#endif
        }
#if LT_COST_MODE == LT_COST_SIM
        {
            char extra[1024], *js;
            snprintf(extra, sizeof extra,
                     "{\"encoding\": \"%s\", \"pixels\": %llu, \"traced_rays\": %llu, "
                     "\"nodes_per_ray\": %.4f, \"aabb_per_ray\": %.4f, \"planes_per_ray\": %.4f, "
                     "\"nodes_max\": %u, \"hole_fraction\": %.6f, \"build_cycles\": %llu, "
                     "\"setup_cycles\": %llu, \"traverse_cycles\": %llu, "
                     "\"lane_utilisation\": %.4f}",
                     enc_name[enc], (unsigned long long)st->pixels, (unsigned long long)st->rays,
                     (double)st->nodes / rays, (double)st->aabb / rays, (double)st->planes / rays,
                     st->nodes_max, holes / px, (unsigned long long)st->cyc_build,
                     (unsigned long long)st->cyc_setup, (unsigned long long)st->cyc_trace, util);
            if (!*hk->quiet)
                lt_sim_report_text(stdout, title, st->pixels);
            if (report != NULL) {
                js = lt_sim_report_json_string(title, st->pixels, extra);
                if (js == NULL || write_text_atomic(report, js, err, sizeof err) != 0) {
                    fprintf(stderr, "%s\n", js == NULL ? "reproject: out of memory for the report"
                                                       : err);
                    free(js);
                    status = EXIT_INPUT;
                    goto done;
                }
                free(js);
            }
        }
#endif
        if (!*hk->quiet) {
            if (out != NULL)
                printf("exr       %s (R G B Z hole steps%s)\n", out,
                       LT_COST_MODE == LT_COST_SIM ? " cycles" : "");
            if (png != NULL)
                printf("png       %s\n", png);
            if (heat_steps != NULL)
                printf("heatmap   %s (quadtree nodes per pixel)\n", heat_steps);
            if (heat_cycles != NULL)
                printf("heatmap   %s (simulated cycles per pixel)\n", heat_cycles);
            if (report != NULL)
                printf("report    %s\n", report);
        }
        if (json) {
            cJSON *o = cJSON_CreateObject(), *files = cJSON_AddArrayToObject(o, "files");
            cJSON *cls = cJSON_AddObjectToObject(o, "pixels_by_class");
            const char *fl[5] = {out, png, heat_steps, heat_cycles, report};
            char *js;
            int k;
            for (k = 0; k < 5; k++)
                if (fl[k] != NULL)
                    cJSON_AddItemToArray(files, cJSON_CreateString(fl[k]));
            cJSON_AddStringToObject(o, "depth", depth);
            cJSON_AddStringToObject(o, "channel", dl[0].channel);
            cJSON_AddNumberToObject(o, "layers", layers);
            cJSON_AddStringToObject(o, "encoding", enc_name[enc]);
            cJSON_AddNumberToObject(o, "source_width", W);
            cJSON_AddNumberToObject(o, "source_height", H);
            cJSON_AddNumberToObject(o, "width", res.width);
            cJSON_AddNumberToObject(o, "height", res.height);
            cJSON_AddNumberToObject(o, "z_ref", st->zref);
            cJSON_AddNumberToObject(o, "pixels", (double)st->pixels);
            cJSON_AddNumberToObject(o, "traced_rays", (double)st->rays);
            cJSON_AddNumberToObject(cls, "hit", (double)st->cls[LT_RP_HIT]);
            cJSON_AddNumberToObject(cls, "background", (double)st->cls[LT_RP_BACKGROUND]);
            cJSON_AddNumberToObject(cls, "disoccluded", (double)st->cls[LT_RP_DISOCCLUDED]);
            cJSON_AddNumberToObject(cls, "outside", (double)st->cls[LT_RP_OUTSIDE]);
            cJSON_AddNumberToObject(cls, "step_bound", (double)st->cls[LT_RP_UNKNOWN]);
            cJSON_AddNumberToObject(o, "hole_fraction", holes / px);
            cJSON_AddNumberToObject(o, "nodes_per_ray", (double)st->nodes / rays);
            cJSON_AddNumberToObject(o, "nodes_max", st->nodes_max);
            cJSON_AddNumberToObject(o, "aabb_per_ray", (double)st->aabb / rays);
            cJSON_AddNumberToObject(o, "aabb_max", st->aabb_max);
            cJSON_AddNumberToObject(o, "planes_per_ray", (double)st->planes / rays);
            cJSON_AddNumberToObject(o, "planes_max", st->planes_max);
            cJSON_AddNumberToObject(o, "quadtree_bytes", (double)st->qt_bytes);
            cJSON_AddNumberToObject(o, "build_seconds", st->t_build);
            cJSON_AddNumberToObject(o, "trace_seconds", st->t_trace);
#if LT_COST_MODE == LT_COST_SIM
            cJSON_AddNumberToObject(o, "build_cycles", (double)st->cyc_build);
            cJSON_AddNumberToObject(o, "setup_cycles", (double)st->cyc_setup);
            cJSON_AddNumberToObject(o, "traverse_cycles", (double)st->cyc_trace);
            cJSON_AddNumberToObject(o, "cycles_per_ray",
                                    (double)(st->cyc_setup + st->cyc_trace) / px);
            cJSON_AddNumberToObject(o, "lane_utilisation", util);
#endif
            js = cJSON_Print(o);
            if (js != NULL)
                puts(js);
            free(js);
            cJSON_Delete(o);
        }
    }
done:
    for (l = 0; l < LT_RP_MAX_LAYERS; l++) {
        if (l == 0 && dc.z != NULL) {
            /* layer 0's colour pointers belong to dc */
            dl[0].rgba[0] = dl[0].rgba[1] = dl[0].rgba[2] = NULL;
        }
        lt_exr_depth_free(&dl[l]);
        free(rgb[l]);
    }
    lt_exr_depth_free(&dc);
    free(zall);
    lt_rp_result_free(&res);
#if LT_COST_MODE == LT_COST_SIM
    lt_sim_shutdown();
#endif
    return status;
}
