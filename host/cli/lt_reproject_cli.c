/* lt_reproject_cli.c - `lanetrace reproject`: view synthesis from a depth EXR through the
 * screen-space quadtree (docs/reproject.md). Options, EXR depth layers and colour, source camera
 * (flags, a scene file with 'depth' + 'camera', lanetrace render's camera for a mesh scene, or the
 * documented default), target camera (move / rotate / intrinsics / size), lt_rp_run, outputs:
 * EXR (R G B Z hole steps [cycles]), PNG, heatmap PNGs with legends, the cycle report (sim build)
 * as text and JSON. Exit codes: 0 ok, 1 input or runtime error, 2 usage. Host only.
 */
#include "cli/lt_reproject_cli.h"
#include "cli/lt_cliutil.h"
#include "lt_rate.h"
#include "cli/lt_opt.h"
#include "io/lt_exr.h"
#include "io/lt_heatmap.h"
#include "io/lt_mesh.h"
#include "io/lt_tmpfiles.h"
#include "lt_meter.h"
#include "io/lt_png.h"
#include "render/lt_par.h"
#include "render/lt_paths.h"
#include "render/lt_render.h"
#include "render/lt_reproject.h"
#include "render/lt_scene.h"
#include "io/lt_scenefile.h"
#include "tune/lt_recommend.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EXIT_INPUT 1
#define EXIT_USAGE 2
#define RP_DEFAULT_FOV 60.0
#define RP_DEFAULT_TRUTH_TOL 0.01

/* lanetrace reproject: options, the scene file and the depth layers, the two cameras, the ground
 * truth, the run and the outputs. */
typedef struct rp {
    /* options */
    lt_scenefile_t sf;
    const char *scene_path, *depth, *channel, *out, *png, *heat_steps, *heat_cycles, *heat_error;
    const char *mesh_over; /* --mesh: the scene's mesh without a scene file */
    int deep_front;        /* --deep-front: a deep EXR is read front-most sample per pixel */
    lt_outset_t *set;      /* the outputs, renamed into place together at the end */
    const char *view;      /* --view: the EXR view (NULL: the file's default view) */
    int part;              /* --part: the EXR part, -1: chosen by the view */
    const char *report, *machine;
    int npos, truth, color, dist, json, layers, enc, tracer, sample, inpaint, max_steps;
    int walk;             /* --walk: 0 auto, 1 packets, 2 single */
    char walk_why[160];   /* why the walk was chosen (printed with it) */
    int seen_move, seen_move_rel, seen_rot, seen_enc, seen_srck, seen_dstk, seen_res, seen_tracer;
    double truth_tol, move[3], rot[3], srck[4], dstk[4], fov, thickness;
    double qtp[4]; /* lambda_h, lambda_d, gamma_norm, gamma_dist; -1: the default */
    uint32_t dwh[2];
    const char *enc_names[8];
    const lt_path_info_t *path; /* the screen-space numeric path (--num) */
    int move_rel;
    int autop;            /* the recommendation for the knobs nobody set (default on) */
    int enc_given;        /* the scene file names the encoding */
    char auto_json[1024]; /* what it did, a JSON object ("" = nothing) */
    /* the source: depth layers, colour, camera */
    lt_exr_depth_t dl[LT_RP_MAX_LAYERS], dc;
    lt_mesh_t mesh;
    lt_scene_t sc;
    int have_scene;
    uint32_t W, H;
    size_t n;
    float *zall, *rgb[LT_RP_MAX_LAYERS];
    double median;
    const char *cam_desc;
    lt_rp_source_t src;
    /* the target, the run, the ground truth */
    lt_reproj_cam_t dcam;
    lt_rp_opts_t ro;
    lt_rp_result_t res;
    float *ztrue, *relerr;
    lt_rp_truth_t tr;
} rp_t;

static const char *const tracer_name[] = {"quadtree", "dda", "hiz", NULL};
static const char *const walk_name[] = {"auto", "packets", "single", NULL};
static const char *const sample_name[] = {"bilinear", "nearest", NULL};

static int rp_threads; /* --threads (0: every core) */

/* --src-cam, --dst-cam: FX,FY,CX,CY in pixels, FX and FY > 0 */
static int parse_cam(const char *text, void *dest, const void *ctx)
{
    double k[4];
    (void)ctx;
    if (lt_opt_read_vec(text, k, 4) != 0 || !(k[0] > 0.0) || !(k[1] > 0.0))
        return -1;
    memcpy(dest, k, sizeof k);
    return 0;
}

/* r before the options: nothing given, the defaults of a reprojection. */
static void rp_defaults(rp_t *r)
{
    memset(r, 0, sizeof *r);
    lt_sf_defaults(&r->sf);
    r->dist = -1;
    r->inpaint = 1;
    r->thickness = -1.0;
    r->qtp[0] = r->qtp[1] = r->qtp[2] = r->qtp[3] = -1.0;
    r->truth_tol = RP_DEFAULT_TRUTH_TOL;
    r->fov = RP_DEFAULT_FOV;
    r->cam_desc = "default";
    r->part = -1;
    r->autop = 1;
}

/* The options of r: parse argv (help == NULL) or print the help on help. LT_OPT_OK, LT_OPT_HELP
 * or LT_OPT_USAGE. */
static int rp_options(rp_t *r, int *quiet, const char *prog, int argc, char **argv, FILE *help)
{
    char who[64], src_help[256], num_help[256], machine_help[256], tol_help[256];
    const lt_opt_t opts[] = {
        LT_OPT_SECTION_("input:"),
        LT_OPT_IN("--depth", "FILE.exr", &r->depth,
                  "source depth (z along the optical axis unless --dist)"),
        LT_OPT_IN("--mesh", "PATH", &r->mesh_over,
                  "the mesh the depth was rendered from (lanetrace render --mesh PATH):\n"
                  "its render camera is the source camera and --truth renders it\n"
                  "(overrides the scene file's \"mesh\")"),
        LT_OPT_FLAG_("--deep-front", &r->deep_front,
                     "a deep EXR (several samples per pixel): read the front-most\n"
                     "(least Z) sample of each pixel"),
        LT_OPT_STR("--channel", "NAME", &r->channel,
                   "depth channel (default: Z, depth, the default view's Z)"),
        LT_OPT_STR("--view", "NAME", &r->view,
                   "the view to read, depth and colour (a stereo EXR: left, right;\n"
                   "default: the file's default view, multiView's first)"),
        LT_OPT_INT("--part", "N", &r->part, 0, 1e9,
                   "read depth and colour from part N of a multi-part EXR only\n"
                   "(0 = the first; default: the parts of the view)"),
        LT_OPT_INT("--layers", "K", &r->layers, 1, LT_RP_MAX_LAYERS,
                   "use the depth peels layer0.Z .. layer<K-1>.Z (lanetrace\n"
                   "render --layers K), {range}"),
        {.name = "--color", .kind = LT_OPT_FLAG, .dest = &r->color, .value = 1,
         .alias = "--colour",
         .help = "fetch colour from R G B of the depth's layer and view (its part,\n"
                 "else a part of the view with the same data window; else grey = w)"},
        LT_OPT_FLAG_("--dist", &r->dist,
                     "depth values are distances along the pixel ray (lanetrace\n"
                     "render's Z; the default with a mesh scene)"),
        LT_OPT_SECTION_("cameras (pinhole, x right, y down, z forward; pixels, world units of the "
                        "depth):"),
        {.name = "--src-cam", .kind = LT_OPT_CUSTOM, .dest = r->srck, .seen = &r->seen_srck,
         .meta = "FX,FY,CX,CY", .parse = parse_cam,
         .expect = "FX,FY,CX,CY in pixels, FX and FY > 0 and finite",
         .help = src_help},
        LT_OPT_DBL("--fov", "DEG", &r->fov, 1.0, 179.0,
                   "the default camera's horizontal field of view, {range}"),
        {.name = "--move", .kind = LT_OPT_VEC, .dest = r->move, .seen = &r->seen_move,
         .meta = "X,Y,Z", .lo = -HUGE_VAL, .hi = HUGE_VAL, .n = 3,
         .help = "target = source moved along its own axes (world units)"},
        {.name = "--move-rel", .kind = LT_OPT_VEC, .dest = r->move, .seen = &r->seen_move_rel,
         .meta = "X,Y,Z", .lo = -HUGE_VAL, .hi = HUGE_VAL, .n = 3,
         .help = "the same in units of the median source depth"},
        {.name = "--rot", .kind = LT_OPT_VEC, .dest = r->rot, .seen = &r->seen_rot,
         .meta = "YAW,PITCH,ROLL", .lo = -180.0, .hi = 180.0, .n = 3,
         .help = "target rotation, degrees, each in {range} (yaw + turns right,\npitch + up)"},
        {.name = "--dst-cam", .kind = LT_OPT_CUSTOM, .dest = r->dstk, .seen = &r->seen_dstk,
         .meta = "FX,FY,CX,CY", .parse = parse_cam,
         .expect = "FX,FY,CX,CY in pixels, FX and FY > 0 and finite",
         .help = "target intrinsics (default: the source's, scaled with --res)"},
        {.name = "--res", .kind = LT_OPT_SIZE, .dest = r->dwh, .seen = &r->seen_res,
         .meta = "WxH|N", .lo = 1, .hi = LT_QT_MAX_DIM, .limit = "LT_QT_MAX_DIM",
         .help = "target size (default: the source's), {range} per side"},
        LT_OPT_SECTION_("tracing:"),
        {.name = "--num", .kind = LT_OPT_ENUM, .dest = &r->enc, .seen = &r->seen_enc,
         .names = r->enc_names, .alias = "--enc", .flags = LT_OPT_DEPRECATED, .help = num_help},
        {.name = "--tracer", .kind = LT_OPT_ENUM, .dest = &r->tracer, .seen = &r->seen_tracer,
         .names = tracer_name,
         .help = "the screen-space tracer (default quadtree); the DDA\n"
                 "(McGuire & Mara) and Hi-Z (Uludag) baselines run on the\n"
                 "same rays, s1.30 for n64/n32, float32 for f32"},
        {.name = "--walk", .kind = LT_OPT_ENUM, .dest = &r->walk, .names = walk_name,
         .help = "the quadtree on s1.30 (n64, n32): packets of 16 lanes or\n"
                 "single rays, one at a time (same results); auto (default):\n"
                 "single on a machine model narrower than 16 lanes (the MCUs)"},
        {.name = "--thickness", .kind = LT_OPT_DOUBLE, .dest = &r->thickness, .meta = "REL",
         .lo = 0.0, .hi = 2.0, .flags = LT_OPT_HI_OPEN,
         .help = "DDA and Hi-Z: relative depth thickness of a pixel, {range} (1/64)"},
        LT_OPT_ENUM_("--sample", &r->sample, sample_name,
                     "colour fetch (default: depth-aware bilinear)"),
        LT_OPT_SET_("--no-inpaint", &r->inpaint, 0, "leave holes black (depth NaN)"),
        LT_OPT_INT("--max-steps", "N", &r->max_steps, 1, 100000000,
                   "quadtree nodes per ray per layer, {range}\n(default 8(w+h)+4 levels+16)"),
        LT_OPT_DBL("--lambda-h", "V", &r->qtp[0], 0.0, 1.0,
                   "build: |dw/dpixel| above V is a jump, its slope zeroed (1e-3)"),
        LT_OPT_DBL("--lambda-d", "V", &r->qtp[1], 0.0, 1.0,
                   "build: Laplacian |Lx|+|Ly| >= V flags a discontinuity (1e-3)"),
        LT_OPT_DBL("--gamma-norm", "V", &r->qtp[2], 0.0, 1.0,
                   "build: merge planes whose normals differ by < V (1e-3)"),
        LT_OPT_DBL("--gamma-dist", "V", &r->qtp[3], 0.0, 1.0,
                   "build: merge when the proxy plane stays within V relative\n"
                   "depth of its children (2^-17); w units, each in {range}\n"
                   "(docs/quadtree.md section 6)"),
        LT_OPT_STR("--machine", "NAME", &r->machine, machine_help),
        LT_OPT_AUTO_(&r->autop, "the node format for the depth image"),
        LT_OPT_SECTION_("ground truth (a mesh scene only; the target camera must keep the source's "
                        "centred\nsquare-pixel intrinsics):"),
        LT_OPT_FLAG_("--truth", &r->truth,
                     "also render the target view with the object-space tracer (BVH,\n"
                     "float32; not counted in the cycle report) and print the\n"
                     "synthesised depth's error: wrong hit/miss, RMSE, within tolerance"),
        {.name = "--truth-tol", .kind = LT_OPT_DOUBLE, .dest = &r->truth_tol, .meta = "REL",
         .lo = 0.0, .hi = 1.0, .flags = LT_OPT_LO_OPEN, .help = tol_help},
        LT_OPT_OUT("--heat-error", "FILE.png", &r->heat_error, "png",
                   "|z - z_true| / z_true per pixel, colours 0..5x the tolerance\n"
                   "(black: no surface in one of the two)"),
        LT_OPT_SECTION_("outputs:"),
        LT_OPT_OUT("--out", "FILE.exr", &r->out, "exr",
                   "R G B (linear), Z (target depth, inf = background), hole (0 hit,\n"
                   "1 background, 2 disoccluded, 3 outside, 4 step bound), steps,\n"
                   "cycles (simulator build), Ztrue (with --truth)"),
        LT_OPT_OUT("--png", "FILE.png", &r->png, "png", "the view (gamma 2.2)"),
        LT_OPT_OUT("--heat-steps", "FILE.png", &r->heat_steps, "png", "quadtree nodes per pixel, with legend"),
        LT_OPT_OUT("--heat-cycles", "FILE.png", &r->heat_cycles, "png",
                   "(simulator build) simulated cycles per pixel, with legend"),
        LT_OPT_OUT("--report", "FILE.json", &r->report, "json",
                   "(simulator build) the cycle report as JSON"),
        LT_OPT_FLAG_("--json", &r->json, "the summary as JSON on stdout"),
        LT_OPT_THREADS_(&rp_threads),
        LT_OPT_FLAG_("-q", quiet, "quiet: no summary, no report text"),
        LT_OPT_END_};
    lt_opt_cmd_t cmd = {who, "[SCENE.json] --depth FILE.exr [options]",
                        "Synthesise a new view of a depth image by screen-space ray tracing "
                        "through the\nadaptive quadtree (Widmer et al.): every target pixel's ray "
                        "is reprojected into the\nsource view and traced over all depth layers; "
                        "holes are inpainted.\n",
                        "A scene file may give 'depth', 'camera' (the source) and a 'reproject' "
                        "object\n(docs/scene-format.md); flags override it.\n",
                        opts, &r->scene_path, 1, &r->npos};
    const lt_path_info_t *p;
    size_t len;
    int k = 0;
    snprintf(who, sizeof who, "%s reproject", prog);
    snprintf(src_help, sizeof src_help,
             "source intrinsics (default: a scene's camera, else a %g-degree\n"
             "horizontal field of view over the EXR display window, centred)", RP_DEFAULT_FOV);
    lt_paths_names(LT_PATHS_SCREEN, r->enc_names, 8);
    len = (size_t)snprintf(num_help, sizeof num_help, "numeric path and quadtree node format:\n");
    for (p = lt_paths; p->name != NULL; p++)
        if ((p->families & LT_PATHS_SCREEN) && len < sizeof num_help)
            len += (size_t)snprintf(num_help + len, sizeof num_help - len, "%s%s (%s%s%s)",
                                    k++ ? ", " : "", p->name, p->format,
                                    p->note != NULL ? ", " : "", p->note != NULL ? p->note : "");
    if (len < sizeof num_help)
        snprintf(num_help + len, sizeof num_help - len, "; default %s", r->enc_names[0]);
    snprintf(machine_help, sizeof machine_help, "(simulator build) machine model: %s",
             lt_meter_machine_names());
    snprintf(tol_help, sizeof tol_help, "relative depth tolerance, {range} (default %g)",
             RP_DEFAULT_TRUTH_TOL);
    if (help != NULL) {
        lt_opt_help(&cmd, help);
        return LT_OPT_HELP;
    }
    k = lt_opt_parse(&cmd, argc, argv, 2);
    lt_par_set_threads((unsigned)rp_threads);
    return k;
}

void lt_rp_cli_usage(const char *prog, FILE *f)
{
    rp_t r;
    int quiet = 0;
    memset(&r, 0, sizeof r);
    (void)rp_options(&r, &quiet, prog, 0, NULL, f);
}

/* ---- small helpers ------------------------------------------------------------------------- */

/* lanetrace render's camera (lt_camera_t: eye, fwd, right, up, fov_y over the image height) as
 * the reprojection's pinhole: rows right, -up, fwd; fx = fy = H / (2 tan(fov_y / 2)), centred. */
void lt_rp_cam_from_camera(const lt_camera_t *cam, uint32_t w, uint32_t h, lt_reproj_cam_t *c)
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
int lt_rp_render_truth(const lt_scene_t *sc, const lt_reproj_cam_t *d, float *ztrue, lt_diag_t *diag)
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
    acc = lt_accel_build(sc, "bvh", lt_paths_find("f32", LT_PATHS_OBJECT), diag);
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

/* The scene file and its 'reproject' defaults under the flags; the checks that need both; the
 * machine model. Returns 0 or an exit code. */
static int rp_settle(rp_t *r, const char *prog)
{
    lt_scenefile_t *sf = &r->sf;
    const lt_path_info_t *scene_enc;
    int k;
    lt_diag_t diag;
    if (!lt_meter_available() &&
        (r->heat_cycles != NULL || r->report != NULL || r->machine != NULL)) {
        fprintf(stderr, "%s reproject: %s needs the simulator build (build/sim/lanetrace); this is "
                        "the native build\n", prog,
                r->heat_cycles != NULL ? "--heat-cycles" : r->report != NULL ? "--report" : "--machine");
        return EXIT_USAGE;
    }
    if (r->scene_path != NULL && lt_sf_load(r->scene_path, sf, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    if (r->mesh_over != NULL &&
        snprintf(sf->mesh, sizeof sf->mesh, "%s", r->mesh_over) >= (int)sizeof sf->mesh) {
        fprintf(stderr, "%s reproject: --mesh %.60s...: the path is longer than %zu bytes\n", prog,
                r->mesh_over, sizeof sf->mesh - 1);
        return EXIT_USAGE;
    }
    if (r->depth == NULL && sf->depth[0] != '\0')
        r->depth = sf->depth;
    if (r->heat_error != NULL)
        r->truth = 1;
    if (r->truth && sf->mesh[0] == '\0') {
        fprintf(stderr, "%s reproject: --truth%s needs the mesh (--mesh PATH or a scene file "
                        "with 'mesh'): the ground truth is the mesh rendered from the target "
                        "camera\n",
                prog, r->heat_error != NULL ? " (and --heat-error)" : "");
        return EXIT_USAGE;
    }
    if (r->depth == NULL) {
        fprintf(stderr, "%s reproject: --depth FILE.exr is required (or a scene file with "
                        "'depth')\n", prog);
        return EXIT_USAGE;
    }
    /* the move: the last of --move and --move-rel given */
    r->move_rel = r->seen_move_rel > r->seen_move;
    /* scene defaults under the flags */
    if (sf->has_reproject) {
        if (!r->seen_move && !r->seen_move_rel) {
            memcpy(r->move, sf->rp_move, sizeof r->move);
            r->move_rel = sf->rp_move_rel;
        }
        if (!r->seen_rot)
            memcpy(r->rot, sf->rp_rot, sizeof r->rot);
        scene_enc = lt_paths_find(sf->rp_encoding, LT_PATHS_SCREEN);
        if (!r->seen_enc && scene_enc != NULL)
            r->path = scene_enc;
        r->enc_given = scene_enc != NULL;
        if (r->layers == 0 && sf->rp_layers > 0)
            r->layers = (int)sf->rp_layers;
        if (r->channel == NULL && sf->rp_channel[0] != '\0')
            r->channel = sf->rp_channel;
        r->color |= sf->rp_color;
        if (r->dist < 0 && sf->rp_distance)
            r->dist = 1;
        for (k = 0; !r->seen_tracer && sf->rp_tracer[0] != '\0' && tracer_name[k] != NULL; k++)
            if (strcmp(tracer_name[k], sf->rp_tracer) == 0)
                r->tracer = k;
        if (r->qtp[2] < 0.0 && sf->rp_gamma_norm >= 0.0)
            r->qtp[2] = sf->rp_gamma_norm;
        if (r->qtp[3] < 0.0 && sf->rp_gamma_dist >= 0.0)
            r->qtp[3] = sf->rp_gamma_dist;
    }
    if (r->machine == NULL)
        r->machine = sf->machine;
    if (!lt_meter_machine_known(r->machine)) {
        fprintf(stderr, "%s reproject: --machine %s: unknown (%s)\n", prog, r->machine,
                lt_meter_machine_names());
        return EXIT_USAGE;
    }
    if (lt_meter_init(r->machine, NULL, NULL, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_USAGE;
    }
    return 0;
}

/* The depth layers (and layer 0's colour), all layers' z in one buffer, each layer's colour.
 * Returns 0 or an exit code. */
static int rp_load_depth(rp_t *r, const char *prog, int quiet)
{
    lt_exr_read_opts_t xo = LT_EXR_READ_OPTS_DEFAULT;
    lt_diag_t diag;
    size_t i, n;
    int l;
    xo.deep = r->deep_front ? LT_EXR_DEEP_FRONT : LT_EXR_DEEP_REJECT;
    if (r->layers == 0)
        r->layers = 1;
    xo.part = r->part;
    xo.view = r->view;
    for (l = 0; l < r->layers; l++) {
        char name[64];
        const char *ch = r->channel;
        if (r->layers > 1) {
            snprintf(name, sizeof name, "layer%d.Z", l);
            ch = name;
        }
        xo.color = r->color && r->layers > 1 && l > 0;
        if (lt_exr_read_depth(r->depth, ch, &xo, &r->dl[l], &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            return EXIT_INPUT;
        }
        if (l > 0 && (r->dl[l].width != r->dl[0].width || r->dl[l].height != r->dl[0].height)) {
            fprintf(stderr, "%s: channel %s is %dx%d, layer 0 is %dx%d\n", r->depth,
                    r->dl[l].channel, r->dl[l].width, r->dl[l].height, r->dl[0].width,
                    r->dl[0].height);
            return EXIT_INPUT;
        }
    }
    r->W = (uint32_t)r->dl[0].width;
    r->H = (uint32_t)r->dl[0].height;
    r->n = n = (size_t)r->W * r->H;
    if (r->W > LT_QT_MAX_DIM || r->H > LT_QT_MAX_DIM) {
        fprintf(stderr, "%s: %ux%u exceeds LT_QT_MAX_DIM %u per side\n", r->depth, r->W, r->H,
                LT_QT_MAX_DIM);
        return EXIT_INPUT;
    }
    if (r->color) {
        /* layer 0's colour: R G B next to the base depth channel (the render's primary hit) */
        lt_exr_depth_t *dc = &r->dc;
        xo.color = 1;
        if (lt_exr_read_depth(r->depth, r->layers > 1 ? r->channel : r->dl[0].channel, &xo, dc,
                              &diag) == 0 &&
            dc->width == (int32_t)r->W && dc->height == (int32_t)r->H && dc->rgba[0] != NULL &&
            dc->rgba[1] != NULL && dc->rgba[2] != NULL) {
            r->dl[0].rgba[0] = dc->rgba[0];
            r->dl[0].rgba[1] = dc->rgba[1];
            r->dl[0].rgba[2] = dc->rgba[2];
        } else if (!quiet) {
            char tc[256], tv[256];
            fprintf(stderr, "%s: no R G B channels next to %s (part %d%s%s): layer 0 shown as "
                    "grey = w\n", r->depth, lt_shown(r->dl[0].channel, tc, sizeof tc),
                    r->dl[0].part, r->dl[0].view[0] != '\0' ? ", view " : "",
                    lt_shown(r->dl[0].view, tv, sizeof tv));
        }
    }
    r->zall = malloc(n * (size_t)r->layers * sizeof *r->zall);
    if (r->zall == NULL) {
        fprintf(stderr, "%s reproject: out of memory for %d layers of %ux%u\n", prog, r->layers,
                r->W, r->H);
        return EXIT_INPUT;
    }
    for (l = 0; l < r->layers; l++) {
        const lt_exr_depth_t *d = &r->dl[l];
        memcpy(r->zall + (size_t)l * n, d->z, n * sizeof *r->zall);
        if (r->color && d->rgba[0] != NULL && d->rgba[1] != NULL && d->rgba[2] != NULL) {
            r->rgb[l] = malloc(n * 3 * sizeof(float));
            if (r->rgb[l] == NULL) {
                fprintf(stderr, "%s reproject: out of memory for colour\n", prog);
                return EXIT_INPUT;
            }
            for (i = 0; i < n; i++) {
                r->rgb[l][3 * i] = d->rgba[0][i];
                r->rgb[l][3 * i + 1] = d->rgba[1][i];
                r->rgb[l][3 * i + 2] = d->rgba[2][i];
            }
        }
    }
    return 0;
}

/* The source camera: --src-cam, lanetrace render's camera of a mesh scene (the scene stays loaded
 * for --truth), the scene file's look-at camera, or the default; distances to z; the source
 * description and its median depth. Returns 0 or an exit code. */
static int rp_source_camera(rp_t *r)
{
    lt_scenefile_t *sf = &r->sf;
    lt_rp_source_t *src = &r->src;
    uint32_t W = r->W, H = r->H;
    size_t i, n = r->n;
    lt_diag_t diag;
    int l;
    memset(src, 0, sizeof *src);
    if (r->seen_srck) {
        int k;
        src->cam.fx = r->srck[0];
        src->cam.fy = r->srck[1];
        src->cam.cx = r->srck[2];
        src->cam.cy = r->srck[3];
        for (k = 0; k < 3; k++)
            src->cam.r[k][k] = 1.0;
        src->cam.width = W;
        src->cam.height = H;
        r->cam_desc = "--src-cam";
    } else if (sf->mesh[0] != '\0') {
        /* lanetrace render's camera for this scene, in its scaled units; the scene stays loaded
           for --truth */
        lt_camera_t cam;
        if (lt_mesh_load(sf->mesh, &r->mesh, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            return EXIT_INPUT;
        }
        if (lt_scene_prepare(&r->mesh, &r->sc, &diag) != 0) {
            fprintf(stderr, "%s: %s\n", sf->mesh, diag.msg);
            return EXIT_INPUT;
        }
        r->have_scene = 1;
        if (sf->has_camera) {
            if (lt_camera_look(&r->sc, sf->eye, sf->target, sf->up, sf->fov_y_deg, W, H, &cam, &diag) != 0) {
                fprintf(stderr, "%s: %s\n", sf->path, diag.msg);
                return EXIT_INPUT;
            }
        } else {
            lt_camera_default(&r->sc, W, H, &cam);
        }
        lt_rp_cam_from_camera(&cam, W, H, &src->cam);
        if (r->dist < 0)
            r->dist = 1;
        r->cam_desc = "the scene's render camera";
    } else if (sf->has_camera) {
        /* the look-at camera of the scene file, in the depth image's own units */
        lt_camera_t cam;
        double dir[3];
        int k;
        memset(&cam, 0, sizeof cam);
        for (k = 0; k < 3; k++) {
            cam.eye[k] = sf->eye[k];
            dir[k] = sf->target[k] - sf->eye[k];
        }
        lt_camera_basis(&cam, dir, sf->up);
        cam.tan_half_fov = tan(0.5 * sf->fov_y_deg * 3.14159265358979323846 / 180.0);
        lt_rp_cam_from_camera(&cam, W, H, &src->cam);
        r->cam_desc = "the scene's camera";
    } else {
        /* the field of view spans the display window: one over LT_EXR_MAX_DIM (which the reader
           does not check for a data-window read) would give a focal length of 2^30 pixels */
        const lt_exr_depth_t *d = &r->dl[0];
        int32_t disp_w, disp_h;
        if (lt_exr_camera_check(r->depth, &d->data_window, &d->display_window, &diag) != 0) {
            fprintf(stderr, "%s; reproject's default source camera spans it (give --src-cam, or "
                    "a scene file with a camera)\n", diag.msg);
            return EXIT_INPUT;
        }
        disp_w = d->display_window.x1 - d->display_window.x0 + 1;
        disp_h = d->display_window.y1 - d->display_window.y0 + 1;
        lt_rp_cam_default(W, H, disp_w, disp_h, d->x0 - d->display_window.x0,
                          d->y0 - d->display_window.y0, r->fov, &src->cam);
        r->cam_desc = "default";
    }
    if (r->dist == 1) {
        /* distance along the unit pixel ray -> z along the optical axis */
        for (l = 0; l < r->layers; l++)
            for (i = 0; i < n; i++) {
                double x = ((double)(i % W) + 0.5 - src->cam.cx) / src->cam.fx;
                double y = ((double)(i / W) + 0.5 - src->cam.cy) / src->cam.fy;
                float *z = &r->zall[(size_t)l * n + i];
                *z = (float)((double)*z / sqrt(x * x + y * y + 1.0));
            }
    }
    src->width = W;
    src->height = H;
    src->layers = (uint32_t)r->layers;
    src->z = r->zall;
    for (l = 0; l < r->layers; l++)
        src->rgb[l] = r->rgb[l];
    r->median = lt_rp_median_depth(r->zall, n);
    return 0;
}

/* The target camera: the source moved (--move-rel in median depths) and rotated, resized
 * (--res), with --dst-cam intrinsics. */
/* The recommendation (lt_recommend_depth) for the node format, from layer 0's depths along the
 * axis and the machine, applied unless --num or the scene file set it or the tracer is not the
 * quadtree (the pick prices quadtree node visits); printed unless quiet. */
static void rp_auto(rp_t *r, int quiet)
{
    lt_rec_depth_facts_t df;
    lt_rec_t rec;
    const char *by = NULL;
    cJSON *o, *x;
    char *txt;
    if (!r->autop)
        return;
    lt_rec_depth_scan(r->zall, r->W, r->H, &df);
    df.machine = r->machine;
    df.target_px = (uint64_t)r->dcam.width * r->dcam.height;
    lt_recommend_depth(&df, &rec);
    if (rec.n < 1)
        return;
    if (r->seen_enc)
        by = "--num";
    else if (r->enc_given)
        by = "the scene file";
    else if (r->tracer != LT_RP_QUADTREE)
        by = r->tracer == LT_RP_DDA ? "--tracer dda (the pick prices quadtree nodes)"
                                    : "--tracer hiz (the pick prices quadtree nodes)";
    if (by == NULL)
        r->path = lt_paths_find(rec.k[0].pick, LT_PATHS_SCREEN);
    if (!quiet && by == NULL)
        printf("auto      %-9s %-6s %s\n", rec.k[0].knob, rec.k[0].pick, rec.k[0].reason);
    else if (!quiet)
        printf("auto      %-9s kept   set by %s (the recommendation: %s)\n", rec.k[0].knob, by,
               rec.k[0].pick);
    o = cJSON_CreateObject();
    x = cJSON_AddObjectToObject(o, rec.k[0].knob);
    cJSON_AddStringToObject(x, "pick", rec.k[0].pick);
    cJSON_AddBoolToObject(x, "applied", by == NULL);
    cJSON_AddStringToObject(x, by == NULL ? "reason" : "set_by", by == NULL ? rec.k[0].reason : by);
    cJSON_AddStringToObject(o, "machine", rec.machine);
    txt = cJSON_PrintUnformatted(o);
    snprintf(r->auto_json, sizeof r->auto_json, "%s", txt != NULL ? txt : "");
    cJSON_free(txt);
    cJSON_Delete(o);
}

static void rp_target_camera(rp_t *r)
{
    lt_reproj_cam_t *dcam = &r->dcam;
    int a;
    if (r->move_rel) {
        for (a = 0; a < 3; a++)
            r->move[a] *= r->median;
    }
    lt_rp_cam_move(&r->src.cam, r->move, r->rot, dcam);
    if (r->seen_res && !r->seen_dstk) {
        double sx = (double)r->dwh[0] / (double)r->W, sy = (double)r->dwh[1] / (double)r->H;
        dcam->fx *= sx;
        dcam->cx *= sx;
        dcam->fy *= sy;
        dcam->cy *= sy;
    }
    if (r->seen_res) {
        dcam->width = r->dwh[0];
        dcam->height = r->dwh[1];
    }
    if (r->seen_dstk) {
        dcam->fx = r->dstk[0];
        dcam->fy = r->dstk[1];
        dcam->cx = r->dstk[2];
        dcam->cy = r->dstk[3];
    }
}

/* --truth: the target view by the object-space tracer, before the run (the simulator is reset
 * afterwards, so the report holds the reprojection alone). Returns 0 or an exit code. */
static int rp_ground_truth(rp_t *r, const char *prog, const lt_rp_cli_hooks_t *hk)
{
    size_t nt = (size_t)r->dcam.width * r->dcam.height;
    lt_diag_t diag;
    if (!r->have_scene) {
        fprintf(stderr, "%s reproject: --truth needs the source camera of the mesh scene "
                        "(lanetrace render's camera), not --src-cam\n", prog);
        return EXIT_USAGE;
    }
    r->ztrue = malloc(nt * sizeof *r->ztrue);
    r->relerr = malloc(nt * sizeof *r->relerr);
    if (r->ztrue == NULL || r->relerr == NULL) {
        fprintf(stderr, "%s reproject: out of memory for the ground truth (%ux%u)\n", prog,
                r->dcam.width, r->dcam.height);
        return EXIT_INPUT;
    }
    hk->begin("ground truth");
    if (lt_rp_render_truth(&r->sc, &r->dcam, r->ztrue, &diag) != 0) {
        hk->end();
        fprintf(stderr, "%s reproject: %s\n", prog, diag.msg);
        return EXIT_USAGE;
    }
    hk->end();
    if (lt_meter_init(r->machine, NULL, NULL, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    return 0;
}

/* The walk: --walk packets / single as given (lt_rp_run refuses single off the s1.30 quadtree);
 * auto: single rays where the machine model is narrower than 16 lanes (a packet step there costs
 * all 16 lanes' work however few are active, as on the firmware targets), on the quadtree of an
 * s1.30 path; packets otherwise. */
static void rp_walk(rp_t *r)
{
    char why[sizeof r->walk_why - 8];
    if (r->walk != 0) {
        r->ro.single = r->walk == 2;
        snprintf(r->walk_why, sizeof r->walk_why, "set by --walk");
        return;
    }
    r->ro.single = lt_rp_auto_single(r->machine, r->ro.enc, r->ro.tracer, why, sizeof why);
    snprintf(r->walk_why, sizeof r->walk_why, "auto: %s", why);
}

/* The reprojection (and the comparison with the ground truth). Returns 0 or an exit code. */
static int rp_run(rp_t *r, const char *prog, const lt_rp_cli_hooks_t *hk)
{
    lt_rp_opts_t *ro = &r->ro;
    lt_q30_t *pp[4];
    lt_diag_t diag;
    int k;
    lt_rp_opts_default(ro);
    ro->enc = (lt_qt_enc_t)r->path->qt_enc;
    ro->bilinear = r->sample == 0;
    ro->inpaint = r->inpaint;
    ro->max_steps = (uint32_t)r->max_steps;
    ro->tracer = (lt_rp_tracer_t)r->tracer;
    rp_walk(r);
    if (r->thickness >= 0.0)
        ro->ssb.thickness = (lt_q30_t)floor(r->thickness * 1073741824.0 + 0.5);
    pp[0] = &ro->params.lambda_h;
    pp[1] = &ro->params.lambda_d;
    pp[2] = &ro->params.gamma_norm;
    pp[3] = &ro->params.gamma_dist;
    for (k = 0; k < 4; k++)
        if (r->qtp[k] >= 0.0)
            *pp[k] = (lt_q30_t)floor(r->qtp[k] * 1073741824.0 + 0.5);
    ro->progress = hk->progress;
    hk->begin("reproject");
    if (lt_rp_run(&r->src, &r->dcam, ro, &r->res, &diag) != 0) {
        hk->end();
        fprintf(stderr, "%s: %s\n", r->depth, diag.msg);
        return EXIT_INPUT;
    }
    hk->end();
    if (r->truth && lt_rp_truth_compare(&r->res, r->ztrue, r->truth_tol, &r->tr, r->relerr) != 0) {
        fprintf(stderr, "%s reproject: out of memory comparing with the ground truth\n", prog);
        return EXIT_INPUT;
    }
    return 0;
}

/* path as a member of the output set: where to write it, or NULL after the message. */
static const char *rp_out(const rp_t *r, const char *path)
{
    lt_diag_t diag;
    const char *dst = NULL;
    if (lt_outset_add(r->set, path, &dst, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return NULL;
    }
    return dst;
}

/* --out: R G B Z hole steps (+ cycles in the sim build, Ztrue with --truth). Returns 0 or an exit
 * code. */
static int rp_write_exr(const rp_t *r, float *const ch[4])
{
    const lt_rp_result_t *res = &r->res;
    lt_diag_t diag;
    lt_exr_channel_t ec[8];
    lt_exr_image_t im;
    static const char *const names[4] = {"R", "G", "B", "Z"};
    const char *dst;
    int nc = 0, k;
    for (k = 0; k < 4; k++) {
        ec[nc].name = names[k];
        ec[nc].type = LT_EXR_FLOAT;
        ec[nc++].data = k < 3 ? ch[k] : res->z;
    }
    ec[nc].name = "hole";
    ec[nc].type = LT_EXR_HALF;
    ec[nc++].data = ch[3];
    ec[nc].name = "steps";
    ec[nc].type = LT_EXR_FLOAT;
    ec[nc++].data = res->steps;
    if (lt_meter_available()) {
        ec[nc].name = "cycles";
        ec[nc].type = LT_EXR_FLOAT;
        ec[nc++].data = res->cycles;
    }
    if (r->truth) {
        ec[nc].name = "Ztrue";
        ec[nc].type = LT_EXR_FLOAT;
        ec[nc++].data = r->ztrue;
    }
    memset(&im, 0, sizeof im);
    im.width = (int32_t)res->width;
    im.height = (int32_t)res->height;
    im.nchannels = nc;
    im.channels = ec;
    if ((dst = rp_out(r, r->out)) == NULL)
        return EXIT_INPUT;
    if (lt_exr_write(dst, &im, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    return 0;
}

/* The files: --out, --png, and the heatmaps (steps, error against the ground truth, cycles).
 * Returns 0 or an exit code. */
static int rp_write_outputs(const rp_t *r, const char *prog)
{
    const lt_rp_result_t *res = &r->res;
    /* the error map's colours run from 0 to 5x the tolerance (larger errors saturate) */
    lt_heatmap_opts_t eo = LT_HEATMAP_OPTS_DEFAULT;
    size_t np = (size_t)res->width * res->height, i;
    lt_diag_t diag;
    float *ch[4];
    int k, status = 0;
    eo.lo = 0.0f;
    eo.hi = (float)(5.0 * r->truth_tol);
    for (k = 0; k < 4; k++)
        ch[k] = malloc(np * sizeof(float));
    if (ch[0] == NULL || ch[1] == NULL || ch[2] == NULL || ch[3] == NULL) {
        fprintf(stderr, "%s reproject: out of memory for the outputs\n", prog);
        status = EXIT_INPUT;
    } else {
        for (i = 0; i < np; i++) {
            ch[0][i] = res->rgb[3 * i];
            ch[1][i] = res->rgb[3 * i + 1];
            ch[2][i] = res->rgb[3 * i + 2];
            ch[3][i] = (float)res->cls[i];
        }
    }
    if (status == 0 && r->out != NULL)
        status = rp_write_exr(r, ch);
    if (status == 0 && r->png != NULL) {
        uint8_t *px = malloc(np * 3);
        if (px == NULL) {
            fprintf(stderr, "%s reproject: out of memory for the PNG\n", prog);
            status = EXIT_INPUT;
        } else {
            for (i = 0; i < np * 3; i++)
                px[i] = lt_gamma8((double)res->rgb[i]);
            const char *dst = rp_out(r, r->png);
            if (dst == NULL) {
                status = EXIT_INPUT;
            } else if (lt_png_write(dst, px, (int32_t)res->width, (int32_t)res->height, 3, 0,
                                    &diag) != 0) {
                fprintf(stderr, "%s\n", diag.msg);
                status = EXIT_INPUT;
            }
            free(px);
        }
    }
    if (status == 0 && r->heat_steps != NULL) {
        const char *dst = rp_out(r, r->heat_steps);
        if (dst == NULL || lt_heatmap_write_png(dst, res->steps, (int32_t)res->width, (int32_t)res->height,
                             NULL, &diag) != 0) {
            if (dst != NULL)
                fprintf(stderr, "%s\n", diag.msg);
            status = EXIT_INPUT;
        }
    }
    if (status == 0 && r->heat_error != NULL) {
        const char *dst = rp_out(r, r->heat_error);
        if (dst == NULL || lt_heatmap_write_png(dst, r->relerr, (int32_t)res->width, (int32_t)res->height,
                             &eo, &diag) != 0) {
            if (dst != NULL)
                fprintf(stderr, "%s\n", diag.msg);
            status = EXIT_INPUT;
        }
    }
    if (status == 0 && r->heat_cycles != NULL) {
        const char *dst = rp_out(r, r->heat_cycles);
        if (dst == NULL || lt_heatmap_write_png(dst, res->cycles, (int32_t)res->width,
                             (int32_t)res->height, NULL, &diag) != 0) {
            if (dst != NULL)
                fprintf(stderr, "%s\n", diag.msg);
            status = EXIT_INPUT;
        }
    }
    for (k = 0; k < 4; k++)
        free(ch[k]);
    return status;
}

/* Figures the summary, the report and the JSON share. */
typedef struct rp_figs {
    double rays, px, holes, util;
} rp_figs_t;

static void rp_figures(const rp_t *r, rp_figs_t *f)
{
    const lt_rp_stats_t *st = &r->res.st;
    f->rays = st->rays > 0 ? (double)st->rays : 1.0;
    f->px = (double)st->pixels;
    f->holes = (double)(st->cls[LT_RP_DISOCCLUDED] + st->cls[LT_RP_OUTSIDE] +
                        st->cls[LT_RP_UNKNOWN]);
    f->util = st->lane_ops > 0 ? (double)st->lanes_on / (16.0 * (double)st->lane_ops) : 0.0;
}

/* The truth block of the summary. */
static void rp_print_truth(const rp_t *r, double px)
{
    const lt_rp_truth_t *tr = &r->tr;
    double kn = tr->known > 0 ? (double)tr->known : 1.0;
    double bh = tr->both_hit > 0 ? (double)tr->both_hit : 1.0;
    double ip = tr->inpainted > 0 ? (double)tr->inpainted : 1.0;
    double ipb = tr->ip_both > 0 ? (double)tr->ip_both : 1.0;
    printf("truth     the target view by the object-space tracer (BVH, float32): a "
           "surface on %.2f%% of the pixels\n", 100.0 * (double)tr->truth_hit / px);
    printf("          traced (hit or background) %.2f%% of the pixels: wrong hit/miss "
           "%.3f%% of them (%llu spurious hits, %llu missed surfaces)\n",
           100.0 * (double)tr->known / px, 100.0 * (double)(tr->spurious + tr->missed) / kn,
           (unsigned long long)tr->spurious, (unsigned long long)tr->missed);
    printf("          depth of the %llu common hits: RMSE %.4g (%.3f%% relative), "
           "relative error median %.2g%%, 99th percentile %.2g%%, max %.2f%%; within "
           "%.3g%%: %.2f%%\n",
           (unsigned long long)tr->both_hit, tr->rmse, 100.0 * tr->rel_rmse,
           100.0 * tr->rel_p50, 100.0 * tr->rel_p99, 100.0 * tr->max_rel, 100.0 * tr->tol,
           100.0 * (double)tr->within / bh);
    if (tr->inpainted == 0)
        printf("          no holes\n");
    else if (tr->inpainted > tr->ip_unfilled)
        printf("          inpainted %.2f%% of the pixels: wrong hit/miss %.2f%% of "
               "them; depth within %.3g%% on %.2f%% of %llu filled surfaces "
               "(relative RMSE %.2f%%)\n",
               100.0 * (double)tr->inpainted / px, 100.0 * (double)tr->ip_wrong / ip,
               100.0 * tr->tol, 100.0 * (double)tr->ip_within / ipb,
               (unsigned long long)tr->ip_both, 100.0 * tr->ip_rel_rmse);
    else
        printf("          holes %.2f%% of the pixels, not inpainted\n",
               100.0 * (double)tr->inpainted / px);
}

/* The summary: source, cameras, the structure, rays, per-ray work, pixel classes, the truth
 * block and (sim build) the cycles. */
static void rp_print_summary(const rp_t *r, const rp_figs_t *f)
{
    const lt_rp_stats_t *st = &r->res.st;
    const lt_reproj_cam_t *sc = &r->src.cam, *dc = &r->dcam;
    const char *enc = r->path->name;
    double rays = f->rays, px = f->px;
    char rt[LT_RATE_TEXT], tc[256], tv[256];
    printf("source    %s: %ux%u, %d layer(s), channel %s%s (part %d%s%s), z_ref %g, median depth "
           "%.4g\n", r->depth, r->W, r->H, r->layers, lt_shown(r->dl[0].channel, tc, sizeof tc),
           r->dist == 1 ? " (distances)" : "", r->dl[0].part,
           r->dl[0].view[0] != '\0' ? ", view " : "", lt_shown(r->dl[0].view, tv, sizeof tv),
           st->zref, r->median);
    printf("cameras   source %s: f %.2f,%.2f c %.2f,%.2f; target moved %.4g,%.4g,%.4g "
           "rotated %.3g,%.3g,%.3g deg, %ux%u\n",
           r->cam_desc, sc->fx, sc->fy, sc->cx, sc->cy, dc->c[0] - sc->c[0], dc->c[1] - sc->c[1],
           dc->c[2] - sc->c[2], r->rot[0], r->rot[1], r->rot[2], r->res.width, r->res.height);
    if (r->tracer == LT_RP_QUADTREE)
        printf("quadtree  %s: %llu nodes (%llu planes), %zu bytes, build %.3f s\n", enc,
               (unsigned long long)st->qt_nodes, (unsigned long long)st->qt_planes, st->qt_bytes,
               st->t_build);
    else
        printf("tracer    %s, %s: %zu bytes besides the w buffer, build %.3f s; "
               "thickness %.4g\n", r->tracer == LT_RP_DDA ? "DDA" : "Hi-Z", r->path->format,
               st->qt_bytes, st->t_build, (double)r->ro.ssb.thickness / 1073741824.0);
    printf("rays      %llu of %llu pixels traced in %llu packets, %.3f s (%s); walk %s (%s)\n",
           (unsigned long long)st->rays, (unsigned long long)st->pixels,
           (unsigned long long)st->packets, st->t_trace,
           lt_rate_text(st->t_trace > 0 ? (double)st->rays / st->t_trace : -1.0, rt),
           r->ro.single ? "single rays" : "packets", r->walk_why);
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
           100.0 * (double)st->cls[LT_RP_UNKNOWN] / px, 100.0 * f->holes / px,
           r->inpaint ? "(inpainted)" : "(left black)");
    if (r->truth)
        rp_print_truth(r, px);
    if (lt_meter_available())
        printf("cycles    build %llu, setup %llu (%.1f per pixel), traverse %llu (%.1f per "
               "ray), other %llu; total %llu; lane utilisation %.1f%% (the report's phases)\n",
               (unsigned long long)st->cyc_build, (unsigned long long)st->cyc_setup,
               (double)st->cyc_setup / px, (unsigned long long)st->cyc_trace,
               (double)st->cyc_trace / rays, (unsigned long long)st->cyc_other,
               (unsigned long long)st->cyc_total, 100.0 * f->util);
}

/* (sim build) the cycle report: the text unless quiet, --report as JSON with the reprojection's
 * figures. Returns 0 or an exit code. */
static int rp_report(const rp_t *r, const rp_figs_t *f, const lt_rp_cli_hooks_t *hk)
{
    const lt_rp_stats_t *st = &r->res.st;
    lt_diag_t diag;
    char title[1400], extra[2048], *js;
    int len;
    if (!lt_meter_available())
        return 0;
    snprintf(title, sizeof title, "reproject %s %ux%u x %d layer(s) -> %ux%u, %s%s%s", r->depth,
             r->W, r->H, r->layers, r->res.width, r->res.height, r->path->name,
             r->tracer ? " " : "", r->tracer ? tracer_name[r->tracer] : "");
    len = snprintf(extra, sizeof extra,
                   "{\"encoding\": \"%s\", \"tracer\": \"%s\", \"walk\": \"%s\", \"pixels\": %llu, "
                   "\"traced_rays\": "
                   "%llu, \"nodes_per_ray\": %.4f, \"aabb_per_ray\": %.4f, \"planes_per_ray\": "
                   "%.4f, \"nodes_max\": %u, \"hole_fraction\": %.6f, \"build_cycles\": %llu, "
                   "\"setup_cycles\": %llu, \"traverse_cycles\": %llu, "
                   "\"lane_utilisation\": %.4f}",
                   r->path->name, tracer_name[r->tracer], r->ro.single ? "single" : "packets",
                   (unsigned long long)st->pixels, (unsigned long long)st->rays,
                   (double)st->nodes / f->rays,
                   (double)st->aabb / f->rays, (double)st->planes / f->rays, st->nodes_max,
                   f->holes / f->px, (unsigned long long)st->cyc_build,
                   (unsigned long long)st->cyc_setup, (unsigned long long)st->cyc_trace, f->util);
    if (r->truth && len > 0 && (size_t)len < sizeof extra) {
        cJSON *tj = truth_json(&r->tr);
        char *ts = tj != NULL ? cJSON_PrintUnformatted(tj) : NULL;
        if (ts != NULL)
            snprintf(extra + len - 1, sizeof extra - (size_t)len + 1, ", \"truth\": %s}", ts);
        free(ts);
        cJSON_Delete(tj);
        len = (int)strlen(extra);
    }
    if (r->auto_json[0] != '\0' && len > 0 && (size_t)len + strlen(r->auto_json) + 12 < sizeof extra)
        snprintf(extra + len - 1, sizeof extra - (size_t)len + 1, ", \"auto\": %s}", r->auto_json);
    if (!*hk->quiet)
        lt_meter_report_text(stdout, title, st->pixels);
    if (r->report != NULL) {
        js = lt_meter_report_json(title, st->pixels, extra);
        const char *dst = js != NULL ? rp_out(r, r->report) : NULL;
        if (js != NULL && dst == NULL) {
            free(js);
            return EXIT_INPUT;
        }
        if (js == NULL || hk->write_text(dst, js, &diag) != 0) {
            fprintf(stderr, "%s\n", js == NULL ? "reproject: out of memory for the report" : diag.msg);
            free(js);
            return EXIT_INPUT;
        }
        free(js);
    }
    return 0;
}

/* The files written, one line each. */
static void rp_print_files(const rp_t *r)
{
    if (r->out != NULL)
        printf("exr       %s (R G B Z hole steps%s%s)\n", r->out,
               lt_meter_available() ? " cycles" : "", r->truth ? " Ztrue" : "");
    if (r->png != NULL)
        printf("png       %s\n", r->png);
    if (r->heat_steps != NULL)
        printf("heatmap   %s (quadtree nodes per pixel)\n", r->heat_steps);
    if (r->heat_cycles != NULL)
        printf("heatmap   %s (simulated cycles per pixel)\n", r->heat_cycles);
    if (r->heat_error != NULL)
        printf("heatmap   %s (relative depth error against the ground truth)\n", r->heat_error);
    if (r->report != NULL)
        printf("report    %s\n", r->report);
}

/* --json: the summary as one JSON object. */
static void rp_print_json(const rp_t *r, const rp_figs_t *f)
{
    const lt_rp_stats_t *st = &r->res.st;
    cJSON *o = cJSON_CreateObject(), *files = cJSON_AddArrayToObject(o, "files");
    cJSON *cls = cJSON_AddObjectToObject(o, "pixels_by_class");
    const char *fl[6] = {r->out, r->png, r->heat_steps, r->heat_cycles, r->report, r->heat_error};
    char *js;
    int k;
    for (k = 0; k < 6; k++)
        if (fl[k] != NULL)
            cJSON_AddItemToArray(files, cJSON_CreateString(fl[k]));
    cJSON_AddStringToObject(o, "depth", r->depth);
    cJSON_AddStringToObject(o, "channel", r->dl[0].channel);
    cJSON_AddNumberToObject(o, "part", r->dl[0].part);
    if (r->dl[0].view[0] != '\0')
        cJSON_AddStringToObject(o, "view", r->dl[0].view);
    else
        cJSON_AddNullToObject(o, "view");
    cJSON_AddNumberToObject(o, "layers", r->layers);
    cJSON_AddStringToObject(o, "encoding", r->path->name);
    cJSON_AddStringToObject(o, "tracer", tracer_name[r->tracer]);
    cJSON_AddStringToObject(o, "walk", r->ro.single ? "single" : "packets");
    if (r->auto_json[0] != '\0')
        cJSON_AddItemToObject(o, "auto", cJSON_Parse(r->auto_json));
    cJSON_AddNumberToObject(o, "source_width", r->W);
    cJSON_AddNumberToObject(o, "source_height", r->H);
    cJSON_AddNumberToObject(o, "width", r->res.width);
    cJSON_AddNumberToObject(o, "height", r->res.height);
    cJSON_AddNumberToObject(o, "z_ref", st->zref);
    cJSON_AddNumberToObject(o, "pixels", (double)st->pixels);
    cJSON_AddNumberToObject(o, "traced_rays", (double)st->rays);
    cJSON_AddNumberToObject(cls, "hit", (double)st->cls[LT_RP_HIT]);
    cJSON_AddNumberToObject(cls, "background", (double)st->cls[LT_RP_BACKGROUND]);
    cJSON_AddNumberToObject(cls, "disoccluded", (double)st->cls[LT_RP_DISOCCLUDED]);
    cJSON_AddNumberToObject(cls, "outside", (double)st->cls[LT_RP_OUTSIDE]);
    cJSON_AddNumberToObject(cls, "step_bound", (double)st->cls[LT_RP_UNKNOWN]);
    cJSON_AddNumberToObject(o, "hole_fraction", f->holes / f->px);
    cJSON_AddNumberToObject(o, "nodes_per_ray", (double)st->nodes / f->rays);
    cJSON_AddNumberToObject(o, "nodes_max", st->nodes_max);
    cJSON_AddNumberToObject(o, "aabb_per_ray", (double)st->aabb / f->rays);
    cJSON_AddNumberToObject(o, "aabb_max", st->aabb_max);
    cJSON_AddNumberToObject(o, "planes_per_ray", (double)st->planes / f->rays);
    cJSON_AddNumberToObject(o, "planes_max", st->planes_max);
    cJSON_AddNumberToObject(o, "quadtree_bytes", (double)st->qt_bytes);
    cJSON_AddNumberToObject(o, "build_seconds", st->t_build);
    cJSON_AddNumberToObject(o, "trace_seconds", st->t_trace);
    if (r->truth)
        cJSON_AddItemToObject(o, "truth", truth_json(&r->tr));
    if (lt_meter_available()) {
        cJSON_AddNumberToObject(o, "build_cycles", (double)st->cyc_build);
        cJSON_AddNumberToObject(o, "setup_cycles", (double)st->cyc_setup);
        cJSON_AddNumberToObject(o, "traverse_cycles", (double)st->cyc_trace);
        cJSON_AddNumberToObject(o, "cycles_per_ray", (double)(st->cyc_setup + st->cyc_trace) / f->px);
        cJSON_AddNumberToObject(o, "lane_utilisation", f->util);
    }
    js = cJSON_Print(o);
    if (js != NULL)
        puts(js);
    free(js);
    cJSON_Delete(o);
}

/* Everything r holds. */
static void rp_free(rp_t *r)
{
    int l;
    for (l = 0; l < LT_RP_MAX_LAYERS; l++) {
        if (l == 0 && r->dc.z != NULL) {
            /* layer 0's colour pointers belong to dc */
            r->dl[0].rgba[0] = r->dl[0].rgba[1] = r->dl[0].rgba[2] = NULL;
        }
        lt_exr_depth_free(&r->dl[l]);
        free(r->rgb[l]);
    }
    lt_exr_depth_free(&r->dc);
    free(r->zall);
    free(r->ztrue);
    free(r->relerr);
    if (r->have_scene)
        lt_scene_free(&r->sc);
    lt_mesh_free(&r->mesh);
    lt_rp_result_free(&r->res);
    lt_meter_shutdown();
}

int lt_rp_cli(int argc, char **argv, const char *prog, const lt_rp_cli_hooks_t *hk)
{
    rp_t r;
    rp_figs_t f;
    int rc;
    memset(&f, 0, sizeof f);
    rp_defaults(&r);
    rc = rp_options(&r, hk->quiet, prog, argc, argv, NULL);
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    if (r.json)
        *hk->quiet = 1;
    r.path = lt_paths_find(r.enc_names[r.enc], LT_PATHS_SCREEN);
    r.set = calloc(1, sizeof *r.set);
    if (r.set == NULL) {
        fprintf(stderr, "%s reproject: out of memory\n", prog);
        return EXIT_INPUT;
    }
    rc = rp_settle(&r, prog);
    if (rc == 0)
        rc = rp_load_depth(&r, prog, *hk->quiet);
    if (rc == 0)
        rc = rp_source_camera(&r);
    if (rc == 0) {
        rp_target_camera(&r);
        rp_auto(&r, *hk->quiet);
        if (r.truth)
            rc = rp_ground_truth(&r, prog, hk);
    }
    if (rc == 0)
        rc = rp_run(&r, prog, hk);
    if (rc == 0)
        rc = rp_write_outputs(&r, prog);
    if (rc == 0) {
        rp_figures(&r, &f);
        if (!*hk->quiet)
            rp_print_summary(&r, &f);
        rc = rp_report(&r, &f, hk);
    }
    /* all outputs or none: the new files replace the old ones only when every one was written */
    if (rc == 0) {
        lt_diag_t diag;
        if (lt_outset_commit(r.set, &diag) != 0) {
            fprintf(stderr, "%s reproject: %s\n", prog, diag.msg);
            rc = EXIT_INPUT;
        }
    } else if (r.set != NULL && r.set->n > 0) {
        fprintf(stderr, "%s reproject: none of the outputs written (%d prepared were removed; "
                        "previous files are unchanged)\n", prog, r.set->n);
        lt_outset_abort(r.set);
    }
    if (rc == 0) {
        if (!*hk->quiet)
            rp_print_files(&r);
        if (r.json)
            rp_print_json(&r, &f);
    }
    free(r.set);
    rp_free(&r);
    return rc;
}
