/* lt_reproject_cli.c - `lanetrace reproject`: view synthesis from a depth EXR through the
 * screen-space quadtree (docs/reproject.md). Options, EXR depth layers and colour, source camera
 * (flags, a scene file with 'depth' + 'camera', lanetrace render's camera for a mesh scene, or the
 * documented default), target camera (move / rotate / intrinsics / size), lt_rp_run, outputs:
 * EXR (R G B Z hole steps [cycles]), PNG, heatmap PNGs with legends, the cycle report (sim build)
 * as text and JSON. Exit codes: 0 ok, 1 input or runtime error, 2 usage. Host only.
 */
#include "cli/lt_reproject_cli.h"
#include "cli/lt_cliutil.h"
#include "io/lt_exr.h"
#include "io/lt_heatmap.h"
#include "io/lt_mesh.h"
#include "lt_meter.h"
#include "io/lt_png.h"
#include "render/lt_render.h"
#include "render/lt_reproject.h"
#include "render/lt_scene.h"
#include "io/lt_scenefile.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EXIT_INPUT 1
#define EXIT_USAGE 2
#define RP_DEFAULT_FOV 60.0
#define RP_DEFAULT_TRUTH_TOL 0.01

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
            "  --tracer quadtree|dda|hiz  the screen-space tracer (default quadtree); the DDA\n"
            "                       (McGuire & Mara) and Hi-Z (Uludag) baselines run on the\n"
            "                       same rays, s1.30 for n64/n32, float32 for f32\n"
            "  --thickness REL      DDA and Hi-Z: relative depth thickness of a pixel (1/64)\n"
            "  --sample bilinear|nearest  colour fetch (default: depth-aware bilinear)\n"
            "  --no-inpaint         leave holes black (depth NaN)\n"
            "  --max-steps N        quadtree nodes per ray per layer (default 8(w+h)+4 levels+16)\n"
            "  --lambda-h V         build: |dw/dpixel| above V is a jump, its slope zeroed (1e-3)\n"
            "  --lambda-d V         build: Laplacian |Lx|+|Ly| >= V flags a discontinuity (1e-3)\n"
            "  --gamma-norm V       build: merge planes whose normals differ by < V (1e-3)\n"
            "  --gamma-dist V       build: merge when the proxy plane stays within V relative\n"
            "                       depth of its children (2^-17); w units, each in [0, 1]\n"
            "  --machine NAME       (simulator build) machine model: %s\n"
            "ground truth (a mesh scene only; the target camera must keep the source's centred\n"
            "square-pixel intrinsics):\n"
            "  --truth              also render the target view with the object-space tracer (BVH,\n"
            "                       float32; not counted in the cycle report) and print the\n"
            "                       synthesised depth's error: wrong hit/miss, RMSE, within tolerance\n"
            "  --truth-tol REL      relative depth tolerance, (0, 1] (default %g)\n"
            "  --heat-error FILE.png  |z - z_true| / z_true per pixel, colours 0..5x the tolerance\n"
            "                       (black: no surface in one of the two)\n"
            "outputs:\n"
            "  --out FILE.exr       R G B (linear), Z (target depth, inf = background), hole (0 hit,\n"
            "                       1 background, 2 disoccluded, 3 outside, 4 step bound), steps,\n"
            "                       cycles (simulator build), Ztrue (with --truth)\n"
            "  --png FILE.png       the view (gamma 2.2)\n"
            "  --heat-steps FILE.png  quadtree nodes per pixel, with legend\n"
            "  --heat-cycles FILE.png (simulator build) simulated cycles per pixel, with legend\n"
            "  --report FILE.json   (simulator build) the cycle report as JSON\n"
            "  --json               the summary as JSON on stdout\n"
            "  -q                   quiet: no summary, no report text\n"
            "A scene file may give 'depth', 'camera' (the source) and a 'reproject' object\n"
            "(docs/scene-format.md); flags override it.\n",
            prog, LT_RP_MAX_LAYERS, RP_DEFAULT_FOV, LT_QT_MAX_DIM, lt_meter_machine_names(),
            RP_DEFAULT_TRUTH_TOL);
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

/* lanetrace render's camera (lt_camera_t: eye, fwd, right, up, fov_y over the image height) as
 * the reprojection's pinhole: rows right, -up, fwd; fx = fy = H / (2 tan(fov_y / 2)), centred. */
static void cam_from_camera(const lt_camera_t *cam, uint32_t w, uint32_t h, lt_reproj_cam_t *c)
{
    int i;
    memset(c, 0, sizeof *c);
    c->fy = c->fx = 0.5 * (double)h / cam->tan_half_fov;
    c->cx = 0.5 * (double)w;
    c->cy = 0.5 * (double)h;
    for (i = 0; i < 3; i++) {
        c->r[0][i] = cam->right[i];
        c->r[1][i] = -cam->up[i];
        c->r[2][i] = cam->fwd[i];
        c->c[i] = cam->eye[i];
    }
    c->width = w;
    c->height = h;
}

/* Ground truth: the target view rendered by the object-space tracer (float32 BVH packets, the
 * path lanetrace render uses) as z-depths along the target's optical axis, +inf on a miss. The
 * tracer's camera is centred with square pixels, so the target's intrinsics must be too. */
static int render_truth(const lt_scene_t *sc, const lt_reproj_cam_t *d, float *ztrue,
                        lt_diag_t *diag)
{
    lt_camera_t cam;
    lt_frame_t fr;
    lt_accel_t *acc;
    double w = (double)d->width, h = (double)d->height;
    uint32_t x, y;
    int k;
    if (fabs(d->fx - d->fy) > 1e-9 * d->fy || fabs(d->cx - 0.5 * w) > 1e-9 * w ||
        fabs(d->cy - 0.5 * h) > 1e-9 * h) {
        lt_diag_fail(diag, "--truth: the target camera (f %.6g,%.6g c %.6g,%.6g, %ux%u) is not "
                              "centred with square pixels, which the object-space tracer's camera "
                              "needs (drop --dst-cam, keep the aspect in --res)",
                     d->fx, d->fy, d->cx, d->cy, d->width, d->height);
        return -1;
    }
    memset(&cam, 0, sizeof cam);
    for (k = 0; k < 3; k++) {
        cam.eye[k] = d->c[k];
        cam.right[k] = d->r[0][k];
        cam.up[k] = -d->r[1][k];
        cam.fwd[k] = d->r[2][k];
    }
    cam.tan_half_fov = 0.5 * h / d->fy;
    cam.width = d->width;
    cam.height = d->height;
    if (lt_frame_alloc(&fr, d->width, d->height, diag) != 0)
        return -1;
    acc = lt_accel_build(sc, "bvh", LT_PATH_F32, diag);
    if (acc == NULL) {
        lt_frame_free(&fr);
        return -1;
    }
    lt_render_primary(sc, acc, &cam, &fr, NULL);
    for (y = 0; y < d->height; y++)
        for (x = 0; x < d->width; x++) {
            size_t p = (size_t)y * d->width + x;
            double dir[3];
            lt_camera_dir(&cam, x, y, dir);
            ztrue[p] = fr.id[p] >= 0 ? (float)(fr.t[p] * (dir[0] * cam.fwd[0] +
                                                          dir[1] * cam.fwd[1] +
                                                          dir[2] * cam.fwd[2]))
                                     : (float)INFINITY;
        }
    lt_accel_free(acc);
    lt_frame_free(&fr);
    return 0;
}

/* The ground-truth comparison as a JSON object (--json, --report). */
static cJSON *truth_json(const lt_rp_truth_t *tr)
{
    const struct {
        const char *key;
        double v;
    } f[] = {
        {"tolerance", tr->tol},
        {"truth_hits", (double)tr->truth_hit},
        {"known_pixels", (double)tr->known},
        {"spurious_hits", (double)tr->spurious},
        {"missed_hits", (double)tr->missed},
        {"common_hits", (double)tr->both_hit},
        {"within_tolerance", (double)tr->within},
        {"rmse", tr->rmse},
        {"relative_rmse", tr->rel_rmse},
        {"max_relative", tr->max_rel},
        {"relative_p50", tr->rel_p50},
        {"relative_p99", tr->rel_p99},
        {"inpainted", (double)tr->inpainted},
        {"inpainted_unfilled", (double)tr->ip_unfilled},
        {"inpainted_wrong", (double)tr->ip_wrong},
        {"inpainted_common", (double)tr->ip_both},
        {"inpainted_within", (double)tr->ip_within},
        {"inpainted_relative_rmse", tr->ip_rel_rmse},
    };
    cJSON *t = cJSON_CreateObject();
    size_t k;
    if (t == NULL)
        return NULL;
    cJSON_AddStringToObject(t, "tracer", "bvh f32");
    for (k = 0; k < sizeof f / sizeof f[0]; k++)
        cJSON_AddNumberToObject(t, f[k].key, f[k].v);
    return t;
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
    lt_diag_t diag;
    const char *scene_path = NULL, *depth = NULL, *channel = NULL, *out = NULL, *png = NULL;
    const char *heat_steps = NULL, *heat_cycles = NULL, *report = NULL, *machine = NULL;
    const char *heat_error = NULL;
    lt_mesh_t mesh;
    lt_scene_t sc;
    int have_scene = 0, truth = 0;
    double truth_tol = RP_DEFAULT_TRUTH_TOL;
    float *ztrue = NULL, *relerr = NULL;
    lt_rp_truth_t tr;
    double move[3] = {0, 0, 0}, rot[3] = {0, 0, 0}, srck[4], dstk[4], fov = RP_DEFAULT_FOV;
    int have_srck = 0, have_dstk = 0, have_move = 0, move_rel = 0, have_rot = 0, color = 0;
    int dist = -1, json = 0, layers = 0, status = 0, a, l, enc = -1, bilinear = 1, inpaint = 1;
    uint32_t dw = 0, dh = 0, W, H, max_steps = 0;
    float *zall = NULL, *rgb[LT_RP_MAX_LAYERS];
    size_t i, n;
    const char *cam_desc = "default";
    static const char *const enc_name[3] = {"n64", "n32", "f32"};
    static const char *const tracer_name[3] = {"quadtree", "dda", "hiz"};
    int tracer = 0;
    double thickness = -1.0;
    double median = 0.0;
    double qtp[4] = {-1.0, -1.0, -1.0, -1.0}; /* lambda_h, lambda_d, gamma_norm, gamma_dist */
    static const char *const qtp_flag[4] = {"--lambda-h", "--lambda-d", "--gamma-norm",
                                            "--gamma-dist"};

    memset(dl, 0, sizeof dl);
    memset(&dc, 0, sizeof dc);
    memset(&res, 0, sizeof res);
    memset(rgb, 0, sizeof rgb);
    memset(&mesh, 0, sizeof mesh);
    memset(&sc, 0, sizeof sc);
    memset(&tr, 0, sizeof tr);
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
        if (strcmp(o, "--truth") == 0) {
            truth = 1;
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
        } else if (strcmp(o, "--heat-error") == 0) {
            heat_error = v;
        } else if (strcmp(o, "--truth-tol") == 0) {
            if (parse_vec(v, &truth_tol, 1) != 0 || !(truth_tol > 0.0) || truth_tol > 1.0) {
                fprintf(stderr, "%s reproject: --truth-tol %s: expected a relative tolerance in "
                                "(0, 1]\n", prog, v);
                return EXIT_USAGE;
            }
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
            if (lt_parse_wh(v, LT_QT_MAX_DIM, &dw, &dh) != 0) {
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
        } else if (strcmp(o, "--tracer") == 0) {
            for (tracer = 0; tracer < 3 && strcmp(v, tracer_name[tracer]) != 0; tracer++)
                ;
            if (tracer == 3) {
                fprintf(stderr, "%s reproject: --tracer %s: expected quadtree, dda or hiz\n", prog,
                        v);
                return EXIT_USAGE;
            }
        } else if (strcmp(o, "--thickness") == 0) {
            if (parse_vec(v, &thickness, 1) != 0 || thickness < 0.0 || thickness >= 2.0) {
                fprintf(stderr, "%s reproject: --thickness %s: expected a relative depth in "
                                "[0, 2)\n", prog, v);
                return EXIT_USAGE;
            }
        } else if (strcmp(o, "--sample") == 0) {
            if (strcmp(v, "bilinear") != 0 && strcmp(v, "nearest") != 0) {
                fprintf(stderr, "%s reproject: --sample %s: expected bilinear or nearest\n", prog,
                        v);
                return EXIT_USAGE;
            }
            bilinear = strcmp(v, "bilinear") == 0;
        } else if (strcmp(o, "--lambda-h") == 0 || strcmp(o, "--lambda-d") == 0 ||
                   strcmp(o, "--gamma-norm") == 0 || strcmp(o, "--gamma-dist") == 0) {
            int k;
            for (k = 0; strcmp(o, qtp_flag[k]) != 0; k++)
                ;
            if (parse_vec(v, &qtp[k], 1) != 0 || qtp[k] < 0.0 || qtp[k] > 1.0) {
                fprintf(stderr, "%s reproject: %s %s: expected a value in [0, 1] (w units, "
                                "docs/quadtree.md section 6)\n", prog, o, v);
                return EXIT_USAGE;
            }
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
    if (!lt_meter_available() && (heat_cycles != NULL || report != NULL || machine != NULL)) {
        fprintf(stderr, "%s reproject: %s needs the simulator build (build/sim/lanetrace); this is "
                        "the native build\n", prog,
                heat_cycles != NULL ? "--heat-cycles" : report != NULL ? "--report" : "--machine");
        return EXIT_USAGE;
    }
    if (scene_path != NULL && lt_sf_load(scene_path, &sf, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    if (depth == NULL && sf.depth[0] != '\0')
        depth = sf.depth;
    if (heat_error != NULL)
        truth = 1;
    if (truth && sf.mesh[0] == '\0') {
        fprintf(stderr, "%s reproject: --truth%s needs a mesh scene file (SCENE.json with "
                        "'mesh'): the ground truth is the mesh rendered from the target camera\n",
                prog, heat_error != NULL ? " (and --heat-error)" : "");
        return EXIT_USAGE;
    }
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
    if (!lt_meter_machine_known(machine)) {
        fprintf(stderr, "%s reproject: --machine %s: unknown (%s)\n", prog, machine,
                lt_meter_machine_names());
        return EXIT_USAGE;
    }
    if (lt_meter_init(machine, NULL, NULL, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_USAGE;
    }

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
        if (lt_exr_read_depth(depth, ch, &xo, &dl[l], &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
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
        if (lt_exr_read_depth(depth, layers > 1 ? channel : dl[0].channel, &xo, &dc, &diag) == 0 &&
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
        /* lanetrace render's camera for this scene, in its scaled units; the scene stays loaded
           for --truth */
        lt_camera_t cam;
        if (lt_mesh_load(sf.mesh, &mesh, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            status = EXIT_INPUT;
            goto done;
        }
        if (lt_scene_prepare(&mesh, &sc, &diag) != 0) {
            fprintf(stderr, "%s: %s\n", sf.mesh, diag.msg);
            lt_mesh_free(&mesh);
            memset(&mesh, 0, sizeof mesh);
            status = EXIT_INPUT;
            goto done;
        }
        have_scene = 1;
        if (sf.has_camera) {
            if (lt_camera_look(&sc, sf.eye, sf.target, sf.up, sf.fov_y_deg, W, H, &cam,
                               &diag) != 0) {
                fprintf(stderr, "%s: %s\n", sf.path, diag.msg);
                status = EXIT_INPUT;
                goto done;
            }
        } else {
            lt_camera_default(&sc, W, H, &cam);
        }
        cam_from_camera(&cam, W, H, &src.cam);
        if (dist < 0)
            dist = 1;
        cam_desc = "the scene's render camera";
    } else if (sf.has_camera) {
        /* the look-at camera of the scene file, in the depth image's own units */
        lt_camera_t cam;
        double dir[3];
        int k;
        memset(&cam, 0, sizeof cam);
        for (k = 0; k < 3; k++) {
            cam.eye[k] = sf.eye[k];
            dir[k] = sf.target[k] - sf.eye[k];
        }
        lt_camera_basis(&cam, dir, sf.up);
        cam.tan_half_fov = tan(0.5 * sf.fov_y_deg * 3.14159265358979323846 / 180.0);
        cam_from_camera(&cam, W, H, &src.cam);
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

    /* ---- ground truth (before the run: the sim is reset afterwards, so the report holds the
       reprojection alone) ---- */
    if (truth) {
        size_t nt = (size_t)dcam.width * dcam.height;
        if (!have_scene) {
            fprintf(stderr, "%s reproject: --truth needs the source camera of the mesh scene "
                            "(lanetrace render's camera), not --src-cam\n", prog);
            status = EXIT_USAGE;
            goto done;
        }
        ztrue = malloc(nt * sizeof *ztrue);
        relerr = malloc(nt * sizeof *relerr);
        if (ztrue == NULL || relerr == NULL) {
            fprintf(stderr, "%s reproject: out of memory for the ground truth (%ux%u)\n", prog,
                    dcam.width, dcam.height);
            status = EXIT_INPUT;
            goto done;
        }
        hk->begin("ground truth");
        if (render_truth(&sc, &dcam, ztrue, &diag) != 0) {
            hk->end();
            fprintf(stderr, "%s reproject: %s\n", prog, diag.msg);
            status = EXIT_USAGE;
            goto done;
        }
        hk->end();
        if (lt_meter_init(machine, NULL, NULL, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            status = EXIT_INPUT;
            goto done;
        }
    }

    /* ---- run ---- */
    lt_rp_opts_default(&ro);
    ro.enc = (lt_qt_enc_t)enc;
    ro.bilinear = bilinear;
    ro.inpaint = inpaint;
    ro.max_steps = max_steps;
    ro.tracer = (lt_rp_tracer_t)tracer;
    if (thickness >= 0.0)
        ro.ssb.thickness = (lt_q30_t)floor(thickness * 1073741824.0 + 0.5);
    {
        lt_q30_t *pp[4];
        int k;
        pp[0] = &ro.params.lambda_h;
        pp[1] = &ro.params.lambda_d;
        pp[2] = &ro.params.gamma_norm;
        pp[3] = &ro.params.gamma_dist;
        for (k = 0; k < 4; k++)
            if (qtp[k] >= 0.0)
                *pp[k] = (lt_q30_t)floor(qtp[k] * 1073741824.0 + 0.5);
    }
    ro.progress = hk->progress;
    hk->begin("reproject");
    if (lt_rp_run(&src, &dcam, &ro, &res, &diag) != 0) {
        hk->end();
        fprintf(stderr, "%s: %s\n", depth, diag.msg);
        status = EXIT_INPUT;
        goto done;
    }
    hk->end();
    if (truth && lt_rp_truth_compare(&res, ztrue, truth_tol, &tr, relerr) != 0) {
        fprintf(stderr, "%s reproject: out of memory comparing with the ground truth\n", prog);
        status = EXIT_INPUT;
        goto done;
    }

    /* ---- outputs ---- */
    {
        /* the error map's colours run from 0 to 5x the tolerance (larger errors saturate) */
        lt_heatmap_opts_t eo = LT_HEATMAP_OPTS_DEFAULT;
        size_t np = (size_t)res.width * res.height;
        float *ch[5];
        eo.lo = 0.0f;
        eo.hi = (float)(5.0 * truth_tol);
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
            lt_exr_channel_t ec[8];
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
            if (lt_meter_available()) {
                ec[nc].name = "cycles";
                ec[nc].type = LT_EXR_FLOAT;
                ec[nc++].data = res.cycles;
            }
            if (truth) {
                ec[nc].name = "Ztrue";
                ec[nc].type = LT_EXR_FLOAT;
                ec[nc++].data = ztrue;
            }
            memset(&im, 0, sizeof im);
            im.width = (int32_t)res.width;
            im.height = (int32_t)res.height;
            im.nchannels = nc;
            im.channels = ec;
            if (lt_exr_write(out, &im, &diag) != 0) {
                fprintf(stderr, "%s\n", diag.msg);
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
                    px[i] = lt_gamma8((double)res.rgb[i]);
                if (lt_png_write(png, px, (int32_t)res.width, (int32_t)res.height, 3, 0,
                                 &diag) != 0) {
                    fprintf(stderr, "%s\n", diag.msg);
                    status = EXIT_INPUT;
                }
                free(px);
            }
        }
        if (status == 0 && heat_steps != NULL &&
            lt_heatmap_write_png(heat_steps, res.steps, (int32_t)res.width, (int32_t)res.height,
                                 NULL, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            status = EXIT_INPUT;
        }
        if (status == 0 && heat_error != NULL &&
            lt_heatmap_write_png(heat_error, relerr, (int32_t)res.width, (int32_t)res.height,
                                 &eo, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            status = EXIT_INPUT;
        }
        if (status == 0 && heat_cycles != NULL &&
            lt_heatmap_write_png(heat_cycles, res.cycles, (int32_t)res.width, (int32_t)res.height,
                                 NULL, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
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
        snprintf(title, sizeof title, "reproject %s %ux%u x %d layer(s) -> %ux%u, %s%s%s", depth,
                 W, H, layers, res.width, res.height, enc_name[enc], tracer ? " " : "",
                 tracer ? tracer_name[tracer] : "");
        if (!*hk->quiet) {
            printf("source    %s: %ux%u, %d layer(s), channel %s%s, z_ref %g, median depth %.4g\n",
                   depth, W, H, layers, dl[0].channel, dist == 1 ? " (distances)" : "", st->zref,
                   median);
            printf("cameras   source %s: f %.2f,%.2f c %.2f,%.2f; target moved %.4g,%.4g,%.4g "
                   "rotated %.3g,%.3g,%.3g deg, %ux%u\n",
                   cam_desc, src.cam.fx, src.cam.fy, src.cam.cx, src.cam.cy, dcam.c[0] - src.cam.c[0],
                   dcam.c[1] - src.cam.c[1], dcam.c[2] - src.cam.c[2], rot[0], rot[1], rot[2],
                   res.width, res.height);
            if (tracer == LT_RP_QUADTREE)
                printf("quadtree  %s: %llu nodes (%llu planes), %zu bytes, build %.3f s\n",
                       enc_name[enc], (unsigned long long)st->qt_nodes,
                       (unsigned long long)st->qt_planes, st->qt_bytes, st->t_build);
            else
                printf("tracer    %s, %s: %zu bytes besides the w buffer, build %.3f s; "
                       "thickness %.4g\n", tracer == LT_RP_DDA ? "DDA" : "Hi-Z",
                       enc == LT_QT_F32 ? "float32" : "s1.30", st->qt_bytes, st->t_build,
                       (double)ro.ssb.thickness / 1073741824.0);
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
            if (truth) {
                double kn = tr.known > 0 ? (double)tr.known : 1.0;
                double bh = tr.both_hit > 0 ? (double)tr.both_hit : 1.0;
                double ip = tr.inpainted > 0 ? (double)tr.inpainted : 1.0;
                double ipb = tr.ip_both > 0 ? (double)tr.ip_both : 1.0;
                printf("truth     the target view by the object-space tracer (BVH, float32): a "
                       "surface on %.2f%% of the pixels\n", 100.0 * (double)tr.truth_hit / px);
                printf("          traced (hit or background) %.2f%% of the pixels: wrong hit/miss "
                       "%.3f%% of them (%llu spurious hits, %llu missed surfaces)\n",
                       100.0 * (double)tr.known / px,
                       100.0 * (double)(tr.spurious + tr.missed) / kn,
                       (unsigned long long)tr.spurious, (unsigned long long)tr.missed);
                printf("          depth of the %llu common hits: RMSE %.4g (%.3f%% relative), "
                       "relative error median %.2g%%, 99th percentile %.2g%%, max %.2f%%; within "
                       "%.3g%%: %.2f%%\n",
                       (unsigned long long)tr.both_hit, tr.rmse, 100.0 * tr.rel_rmse,
                       100.0 * tr.rel_p50, 100.0 * tr.rel_p99, 100.0 * tr.max_rel, 100.0 * tr.tol,
                       100.0 * (double)tr.within / bh);
                if (tr.inpainted == 0)
                    printf("          no holes\n");
                else if (tr.inpainted > tr.ip_unfilled)
                    printf("          inpainted %.2f%% of the pixels: wrong hit/miss %.2f%% of "
                           "them; depth within %.3g%% on %.2f%% of %llu filled surfaces "
                           "(relative RMSE %.2f%%)\n",
                           100.0 * (double)tr.inpainted / px, 100.0 * (double)tr.ip_wrong / ip,
                           100.0 * tr.tol, 100.0 * (double)tr.ip_within / ipb,
                           (unsigned long long)tr.ip_both, 100.0 * tr.ip_rel_rmse);
                else
                    printf("          holes %.2f%% of the pixels, not inpainted\n",
                           100.0 * (double)tr.inpainted / px);
            }
            if (lt_meter_available())
                printf("cycles    build %llu, setup %llu (%.1f per ray), traverse %llu (%.1f per "
                       "ray); lane utilisation %.1f%%\n",
                       (unsigned long long)st->cyc_build, (unsigned long long)st->cyc_setup,
                       (double)st->cyc_setup / px, (unsigned long long)st->cyc_trace,
                       (double)st->cyc_trace / rays, 100.0 * util);
        }
        if (lt_meter_available()) {
            char extra[2048], *js;
            int len = snprintf(extra, sizeof extra,
                     "{\"encoding\": \"%s\", \"tracer\": \"%s\", \"pixels\": %llu, \"traced_rays\": %llu, "
                     "\"nodes_per_ray\": %.4f, \"aabb_per_ray\": %.4f, \"planes_per_ray\": %.4f, "
                     "\"nodes_max\": %u, \"hole_fraction\": %.6f, \"build_cycles\": %llu, "
                     "\"setup_cycles\": %llu, \"traverse_cycles\": %llu, "
                     "\"lane_utilisation\": %.4f}",
                     enc_name[enc], tracer_name[tracer], (unsigned long long)st->pixels,
                     (unsigned long long)st->rays, (double)st->nodes / rays, (double)st->aabb / rays, (double)st->planes / rays,
                     st->nodes_max, holes / px, (unsigned long long)st->cyc_build,
                     (unsigned long long)st->cyc_setup, (unsigned long long)st->cyc_trace, util);
            if (truth && len > 0 && (size_t)len < sizeof extra) {
                cJSON *tj = truth_json(&tr);
                char *ts = tj != NULL ? cJSON_PrintUnformatted(tj) : NULL;
                if (ts != NULL)
                    snprintf(extra + len - 1, sizeof extra - (size_t)len + 1, ", \"truth\": %s}",
                             ts);
                free(ts);
                cJSON_Delete(tj);
            }
            if (!*hk->quiet)
                lt_meter_report_text(stdout, title, st->pixels);
            if (report != NULL) {
                js = lt_meter_report_json(title, st->pixels, extra);
                if (js == NULL || hk->write_text(report, js, &diag) != 0) {
                    fprintf(stderr, "%s\n", js == NULL ? "reproject: out of memory for the report"
                                                       : diag.msg);
                    free(js);
                    status = EXIT_INPUT;
                    goto done;
                }
                free(js);
            }
        }
        if (!*hk->quiet) {
            if (out != NULL)
                printf("exr       %s (R G B Z hole steps%s%s)\n", out,
                       lt_meter_available() ? " cycles" : "", truth ? " Ztrue" : "");
            if (png != NULL)
                printf("png       %s\n", png);
            if (heat_steps != NULL)
                printf("heatmap   %s (quadtree nodes per pixel)\n", heat_steps);
            if (heat_cycles != NULL)
                printf("heatmap   %s (simulated cycles per pixel)\n", heat_cycles);
            if (heat_error != NULL)
                printf("heatmap   %s (relative depth error against the ground truth)\n",
                       heat_error);
            if (report != NULL)
                printf("report    %s\n", report);
        }
        if (json) {
            cJSON *o = cJSON_CreateObject(), *files = cJSON_AddArrayToObject(o, "files");
            cJSON *cls = cJSON_AddObjectToObject(o, "pixels_by_class");
            const char *fl[6] = {out, png, heat_steps, heat_cycles, report, heat_error};
            char *js;
            int k;
            for (k = 0; k < 6; k++)
                if (fl[k] != NULL)
                    cJSON_AddItemToArray(files, cJSON_CreateString(fl[k]));
            cJSON_AddStringToObject(o, "depth", depth);
            cJSON_AddStringToObject(o, "channel", dl[0].channel);
            cJSON_AddNumberToObject(o, "layers", layers);
            cJSON_AddStringToObject(o, "encoding", enc_name[enc]);
            cJSON_AddStringToObject(o, "tracer", tracer_name[tracer]);
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
            if (truth)
                cJSON_AddItemToObject(o, "truth", truth_json(&tr));
            if (lt_meter_available()) {
                cJSON_AddNumberToObject(o, "build_cycles", (double)st->cyc_build);
                cJSON_AddNumberToObject(o, "setup_cycles", (double)st->cyc_setup);
                cJSON_AddNumberToObject(o, "traverse_cycles", (double)st->cyc_trace);
                cJSON_AddNumberToObject(o, "cycles_per_ray",
                                        (double)(st->cyc_setup + st->cyc_trace) / px);
                cJSON_AddNumberToObject(o, "lane_utilisation", util);
            }
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
    free(ztrue);
    free(relerr);
    if (have_scene)
        lt_scene_free(&sc);
    lt_mesh_free(&mesh);
    lt_rp_result_free(&res);
    lt_meter_shutdown();
    return status;
}
