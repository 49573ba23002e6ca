/* lt_shadows_cli.c - `lanetrace shadows`: soft shadows of a quad area light with 16 samples per
 * pixel, by multi-frusta tracing (S-Frusta) and by 16-ray packets (S-Packet), after primary
 * visibility by 16-ray packets (P-Packet) and by primary frusta (P-Frusta; S-Frusta uses them as
 * the paper does, S-Packet the packets); shading, 4x4 discontinuity filter, 256-sample reference
 * and quality, PNGs, and the Table-1-style comparison of Benthin & Wald 2009 [Benthin09]. A
 * subcommand of both CLIs: build/sim/lanetrace shadows (every lane op charged to a machine model:
 * counts and cycles per stage) and build/host/lanetrace-native shadows (native timing). Exit codes:
 * 0 ok, 1 input or runtime error (including frusta != packet visibility), 2 usage. Host only;
 * docs/frusta.md.
 */
#include "render/lt_softshadow.h"
#include "io/lt_scenefile.h"
#include "cli/lt_cliutil.h"
#include "lt_rate.h"
#include "cli/lt_opt.h"
#include "cli/lt_shadows_cli.h"
#include "lt_sblob.h"
#include "io/lt_tmpfiles.h"
#include "lt_meter.h"
#include "render/lt_par.h"
#include "render/lt_paths.h"
#include "io/lt_scenefile.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define EXIT_INPUT 1
#define EXIT_USAGE 2

/* "PROG shadows", the name messages start with */
static char who[256];
static int ss_threads; /* --threads (0: every core) */

/* Counters of one stage (sim builds; zeros natively). */
typedef struct stage {
    const char *name;
    double seconds;
    uint64_t ev[LT_EV__COUNT];
    uint64_t cyc[LT_PH__COUNT];
    uint64_t cycles;
} stage_t;

static void stage_begin(void) { lt_meter_reset(); }

static void stage_end(stage_t *st, const char *name, double t0)
{
    memset(st, 0, sizeof *st);
    st->name = name;
    st->seconds = lt_now_s() - t0;
    if (lt_meter_available()) {
        lt_meter_totals_t t;
        lt_meter_totals(&t);
        memcpy(st->ev, t.events, sizeof st->ev);
        memcpy(st->cyc, t.cycles, sizeof st->cyc);
        st->cycles = t.total_cycles;
    }
}

static void stage_add(stage_t *d, const stage_t *a)
{
    int e, p;
    d->seconds += a->seconds;
    for (e = 0; e < LT_EV__COUNT; e++)
        d->ev[e] += a->ev[e];
    for (p = 0; p < LT_PH__COUNT; p++)
        d->cyc[p] += a->cyc[p];
    d->cycles += a->cycles;
}

static double ratio(uint64_t a, uint64_t b) { return b != 0 ? (double)a / (double)b : 0.0; }

/* rays per second; -1 (printed "n/a") when no time was measured */
static double rate(uint64_t rays, double seconds) { return seconds > 0.0 ? (double)rays / seconds : -1.0; }

static double k_(uint64_t v) { return (double)v / 1000.0; }

/* lanetrace shadows: the options, the scene and light, the stages, the report and the images. */
typedef struct shadows {
    /* options */
    const char *mesh_path, *png, *raw_png, *ref_png, *machine, *scene_path, *pack_block, *blob;
    int res, leaf, num, prim, only, qmc, filter, report, no_ref, ground, quiet, isect, spp, seen_spp;
    int npos, seen_res, seen_num, seen_leaf, seen_cull, seen_prim, seen_only, png_which;
    lt_scenefile_t sf;
    int seen_light, seen_eye, seen_target, seen_fov;
    uint32_t flags, pflags;
    double light_c[4]; /* X, Y, Z, SIZE */
    double eye[3], target[3], fov, tol, depth_rel, cos_min;
    const char *num_names[8];
    const lt_path_info_t *path;
    int run_pp, run_pf, run_fr, run_pk;
    /* inputs */
    lt_ss_view_t view;
    const lt_ss_view_t *pre;
    lt_mesh_t m;
    lt_scene_t sc;
    lt_camera_t cam;
    lt_ss_light_t light;
    lt_softshadow_t *ss;
    /* stages and results */
    stage_t sp, spf, sshp, sshf, sshade, sfilt, tot_p, tot_f, tot_fo;
    uint32_t hash_pp, hash_pf;
    lt_ss_counts_t cnt;
    int rc;
} shadows_t;

static const char *const prim_names[] = {"packet", "frusta", "both", NULL};
static const char *const only_names[] = {"frusta", "packet", NULL};
static const char *const qmc_names[] = {"lp", "hammersley", NULL};
static const lt_qmc_kind_t qmc_kinds[] = {LT_QMC_LP, LT_QMC_HAMMERSLEY};
static const char *const filter_names[] = {"irradiance", "visibility", NULL};

/* --cull, --pcull: any of the letters b (back-face), c (corner rays), r (CR), l (ray-AABB leaf
 * culling), s (wide frusta split into packets), or "none"; --cull (ctx non-NULL) also f (FS:
 * shrink the shadow frusta's direction intervals with their corner rays; implies r) and p (the
 * paper's 256-ray packet walk); both also t (LT_FRUSTA_TRIPAR: triangle-parallel leaves) */
static int parse_cull(const char *text, void *dest, const void *ctx)
{
    return lt_ss_parse_cull(text, ctx != NULL, (uint32_t *)dest, NULL);
}

/* --pcull: as --cull without p (the 256-ray packet walk is for shadow frusta) */
static int parse_pcull(const char *text, void *dest, const void *ctx)
{
    return strchr(text, 'p') != NULL ? -1 : parse_cull(text, dest, ctx);
}

/* --light X,Y,Z,SIZE: four finite numbers, SIZE >= 0 */
static int parse_light(const char *text, void *dest, const void *ctx)
{
    double v[4];
    (void)ctx;
    if (lt_opt_read_vec(text, v, 4) != 0 || !(v[3] >= 0.0))
        return -1;
    memcpy(dest, v, sizeof v);
    return 0;
}

/* s before the options: nothing given, the defaults of a shadows run; who names the command. */
static void shadows_defaults(shadows_t *s, const char *prog)
{
    memset(s, 0, sizeof *s);
    s->res = 128;
    s->leaf = 8;
    s->spp = 16;
    s->ground = -1;
    s->prim = 2;  /* both */
    s->only = -1; /* both */
    s->fov = 60;
    s->tol = 0.05;
    s->depth_rel = 0.05;
    s->cos_min = 0.9;
    s->pflags = LT_SS_PFLAGS_DEFAULT;
    s->flags = LT_SS_FLAGS_DEFAULT;
    snprintf(who, sizeof who, "%s shadows", prog);
}

/* The options into s; LT_OPT_OK, LT_OPT_HELP or LT_OPT_USAGE. */
static int shadows_parse(shadows_t *s, int argc, char **argv)
{
    char num_help[256], machine_help[256], paths[64];
    const lt_opt_t opts[] = {
        {.name = "--mesh", .kind = LT_OPT_STRING, .dest = &s->mesh_path, .meta = "PATH",
         .flags = LT_OPT_NONEMPTY,
         .help = "the mesh (required unless SCENE.json names one)"},
        {.name = "--res", .kind = LT_OPT_INT, .dest = &s->res, .seen = &s->seen_res, .meta = "N",
         .lo = 1, .hi = LT_SF_MAX_RES,
         .help = "image N x N, {range} (default 128; multiples of 4 keep tiles full)"},
        {.name = "--num", .kind = LT_OPT_ENUM, .dest = &s->num, .seen = &s->seen_num,
         .names = s->num_names, .help = num_help},
        {.name = "--spp", .kind = LT_OPT_INT, .dest = &s->spp, .seen = &s->seen_spp, .meta = "N",
         .lo = 4, .hi = 32,
         .help = "shadow samples per pixel: 4, 8, 16 (default) or 32 (the first N of\n"
                 "each pixel's interleaved set; 32: a second set per pixel)"},
        {.name = "--leaf", .kind = LT_OPT_INT, .dest = &s->leaf, .seen = &s->seen_leaf, .meta = "N",
         .lo = 1,
         .hi = LT_BVH_MAX_LEAF, .limit = "LT_BVH_MAX_LEAF",
         .help = "frusta BVH leaf size, {range} (max_leaf N, min_leaf N/2; default 8)"},
        {.name = "--cull", .kind = LT_OPT_CUSTOM, .dest = &s->flags, .seen = &s->seen_cull,
         .meta = "LIST",
         .parse = parse_cull, .ctx = "shadow", .expect = "letters b, c, r, f, l, s, p, t or none",
         .help = "shadow culling: any of b (back-face), c (corner rays), r (CR),\n"
                 "f (FS: CR that also shrinks the traversal's direction intervals),\n"
                 "l (ray-AABB leaf culling), s (wide frusta go on as packets),\n"
                 "p (walk as 16 packets of 16 rays: the paper's 256-ray packet\n"
                 "comparison), t (a packet leaf with fewer live rays than\n"
                 "triangles: ray by ray, its triangles in the lanes; S-Packet and\n"
                 "the frusta's packet walks), or none (default bcrflst)"},
        {.name = "--prim", .kind = LT_OPT_ENUM, .dest = &s->prim, .seen = &s->seen_prim,
         .names = prim_names,
         .help = "primary method(s) (default both: P-Packet feeds S-Packet and\n"
                 "P-Frusta S-Frusta; with one, both S rows use it)"},
        {.name = "--pcull", .kind = LT_OPT_CUSTOM, .dest = &s->pflags, .meta = "LIST",
         .parse = parse_pcull, .expect = "letters b, c, r, l, s, t or none",
         .help = "primary culling: b (back faces, both methods), c (corner rays),\n"
                 "r (corner rays through the on-image pixels), l (ray-AABB leaf\n"
                 "culling), s (wide frusta go on as packets), t (a leaf with fewer\n"
                 "rays in its box than triangles: ray by ray, its triangles in the\n"
                 "lanes; both methods), or none (default bcrlst)"},
        LT_OPT_ENUM_("--qmc", &s->qmc, qmc_names, "sample set (default lp)"),
        LT_OPT_ENUM_("--isect", &s->isect, lt_sf_isects,
                     "ray/triangle test of every stage: wt (watertight, default) or mt\n"
                     "(Moller-Trumbore: cheaper, leaks at shared edges); not wt32"),
        {.name = "--light", .kind = LT_OPT_CUSTOM, .dest = s->light_c, .seen = &s->seen_light,
         .meta = "X,Y,Z,S", .parse = parse_light,
         .expect = "X,Y,Z,SIZE (4 finite numbers, SIZE >= 0)",
         .help = "square light (normal -y) centred at X,Y,Z of side S, file units"},
        {.name = "--eye", .kind = LT_OPT_VEC, .dest = s->eye, .seen = &s->seen_eye,
         .meta = "X,Y,Z", .lo = -HUGE_VAL, .hi = HUGE_VAL, .n = 3, .help = "camera eye (file units)"},
        {.name = "--target", .kind = LT_OPT_VEC, .dest = s->target, .seen = &s->seen_target,
         .meta = "X,Y,Z", .lo = -HUGE_VAL, .hi = HUGE_VAL, .n = 3,
         .help = "camera target (file units)"},
        {.name = "--fov", .kind = LT_OPT_DOUBLE, .dest = &s->fov, .seen = &s->seen_fov,
         .meta = "DEG", .lo = 1.0, .hi = 179.0, .flags = LT_OPT_LO_OPEN | LT_OPT_HI_OPEN,
         .help = "vertical field of view, {range} (default 60, or the scene's)"},
        LT_OPT_SET_("--ground", &s->ground, 1, "add a ground quad below the mesh (default: per scene)"),
        LT_OPT_SET_("--no-ground", &s->ground, 0, "no ground quad"),
        {.name = "--depth-rel", .kind = LT_OPT_DOUBLE, .dest = &s->depth_rel, .meta = "R",
         .lo = 0.0, .hi = 1000.0, .flags = LT_OPT_HI_OPEN,
         .help = "filter: relative depth threshold, {range} (default 0.05)"},
        LT_OPT_DBL("--cos-min", "C", &s->cos_min, -1.0, 1.0,
                   "filter: normal cosine threshold, {range} (default 0.9)"),
        LT_OPT_ENUM_("--filter", &s->filter, filter_names,
                     "filter E = G V (default, as Benthin & Wald 2009 do) or V alone"),
        LT_OPT_DBL("--tol", "T", &s->tol, 0.0, 1.0,
                   "penumbra tolerance on irradiance, {range} (default 0.05)"),
        LT_OPT_FLAG_("--no-ref", &s->no_ref, "skip the 256-sample reference and the quality metrics"),
        LT_OPT_OUT("--png", "PATH.png", &s->png, "png", "filtered image"),
        LT_OPT_STR("--raw-png", "PATH", &s->raw_png, "unfiltered image"),
        LT_OPT_OUT("--ref-png", "PATH.png", &s->ref_png, "png", "the reference"),
        {.name = "--only", .kind = LT_OPT_ENUM, .dest = &s->only, .seen = &s->seen_only,
         .names = only_names, .help = "run one shadow method (default both, compared)"},
        LT_OPT_STR("--machine", "NAME", &s->machine, machine_help),
        LT_OPT_STR("--pack-block", "X,Y|auto", &s->pack_block,
                   "with --blob: the S-Frusta work of the 16x16 block at pixel X,Y\n"
                   "(multiples of 4; auto: the one with the most penumbra pixels) as a\n"
                   "frusta blob for a firmware target, traced here too (docs/firmware.md)"),
        LT_OPT_OUT("--blob", "PATH.ltfb", &s->blob, "ltfb", "where --pack-block writes the blob"),
        LT_OPT_FLAG_("--report", &s->report,
                     "sim builds: the full cycle report of each shadow stage and the filter"),
        LT_OPT_THREADS_(&ss_threads),
        LT_OPT_FLAG_("-q", &s->quiet, "only the result lines"),
        LT_OPT_END_};
    lt_opt_cmd_t cmd = {who, "[SCENE.json] [--mesh PATH] [options]",
                        "Soft shadows of a square area light by multi-frusta and by 16-ray "
                        "packets (Benthin &\nWald 2009): the Table-1 report (sim build: cycles "
                        "per stage), images, the reference.\nA scene file gives the mesh, "
                        "resolution, numeric path, machine and its \"shadows\"\nobject "
                        "(docs/scene-format.md); flags override it.\n",
                        NULL, opts, &s->scene_path, 1, &s->npos};
    lt_paths_names(LT_PATHS_FRUSTA, s->num_names, 8);
    lt_paths_list(LT_PATHS_FRUSTA, paths, sizeof paths);
    snprintf(num_help, sizeof num_help, "numeric path, %s (default q16)", paths);
    snprintf(machine_help, sizeof machine_help, "sim builds: machine model (%s; default lrb16)",
             lt_meter_machine_names());
    int rc = lt_opt_parse(&cmd, argc, argv, 2);
    lt_par_set_threads((unsigned)ss_threads);
    if (rc == LT_OPT_OK && lt_ss_spp_log2((uint32_t)s->spp) < 0) {
        fprintf(stderr, "lanetrace shadows: --spp %d: expected %s samples per pixel\n", s->spp,
                LT_SS_SPP_LIST);
        return LT_OPT_USAGE;
    }
    if (rc == LT_OPT_OK && (s->pack_block == NULL) != (s->blob == NULL)) {
        fprintf(stderr, "%s: --pack-block and --blob go together\n", who);
        return LT_OPT_USAGE;
    }
    return rc;
}

/* SCENE.json under the flags: mesh, resolution, numeric path, machine and the "shadows" object.
 * Returns 0 or an exit code. */
static int shadows_scene(shadows_t *s)
{
    lt_scenefile_t *sf = &s->sf;
    lt_diag_t diag;
    int i;
    if (s->scene_path != NULL) {
        if (lt_sf_load(s->scene_path, sf, &diag) != 0) {
            fprintf(stderr, "%s: %s\n", who, diag.msg);
            return EXIT_INPUT;
        }
        if (s->mesh_path == NULL && sf->mesh[0] != '\0')
            s->mesh_path = sf->mesh;
        if (!s->seen_res)
            s->res = (int)sf->width;
        for (i = 0; !s->seen_num && sf->numeric != LT_SF_NUM_BOTH && s->num_names[i] != NULL; i++)
            if ((unsigned)lt_paths_find(s->num_names[i], LT_PATHS_FRUSTA)->sf_num == (unsigned)sf->numeric)
                s->num = i;
        if (s->machine == NULL)
            s->machine = sf->machine;
        if (!s->seen_leaf && sf->sh_leaf > 0)
            s->leaf = (int)sf->sh_leaf;
        if (!s->seen_spp && sf->sh_spp > 0)
            s->spp = (int)sf->sh_spp;
        if (!s->seen_cull && sf->sh_cull[0] != '\0')
            (void)parse_cull(sf->sh_cull, &s->flags, "shadow");
        for (i = 0; !s->seen_prim && sf->sh_primary[0] != '\0' && prim_names[i] != NULL; i++)
            if (strcmp(prim_names[i], sf->sh_primary) == 0)
                s->prim = i;
        if (!s->seen_only && sf->sh_method[0] != '\0')
            s->only = strcmp(sf->sh_method, "frusta") == 0 ? 0
                      : strcmp(sf->sh_method, "packet") == 0 ? 1 : -1;
        s->png_which = sf->sh_filter ? 0 : 1;
    }
    if (s->mesh_path == NULL) {
        fprintf(stderr, "%s: no mesh: give --mesh PATH or a scene file with \"mesh\"\n"
                        "usage: %s [SCENE.json] [--mesh PATH] [options]  (--help lists them)\n",
                who, who);
        return EXIT_USAGE;
    }
    if (s->machine == NULL)
        s->machine = "lrb16";
    return 0;
}

/* The mesh (and ground), the light, the scene, the camera, the machine and the renderer.
 * Returns 0 or an exit code. */
static int shadows_load(shadows_t *s)
{
    lt_diag_t diag;
    lt_ss_opts_t o;
    double up[3] = {0, 1, 0};
    if (lt_ss_view_for(s->mesh_path, &s->view))
        s->pre = &s->view;
    if (lt_mesh_load(s->mesh_path, &s->m, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        return EXIT_INPUT;
    }
    if (s->ground < 0)
        s->ground = s->pre != NULL ? s->pre->ground : 1;
    if (!s->seen_light) {
        if (s->pre != NULL) {
            memcpy(s->light_c, s->pre->light, 3 * sizeof s->light_c[0]);
            s->light_c[3] = s->pre->size;
        } else {
            /* above the bounding box, a tenth of its x extent wide */
            s->light_c[0] = 0.5 * (s->m.lo[0] + s->m.hi[0]);
            s->light_c[1] = s->m.hi[1] + (s->m.hi[1] - s->m.lo[1]);
            s->light_c[2] = 0.5 * (s->m.lo[2] + s->m.hi[2]);
            s->light_c[3] = 0.2 * (s->m.hi[0] - s->m.lo[0]);
        }
    }
    if (s->ground && lt_ss_add_ground(&s->m, 0.6, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        return EXIT_INPUT;
    }
    if (lt_scene_prepare(&s->m, &s->sc, &diag) != 0) {
        fprintf(stderr, "%s: %s: %s\n", who, s->mesh_path, diag.msg);
        return EXIT_INPUT;
    }
    /* the same representability rule as run and render (the ground plane included): a path
       that cannot represent the scene is refused when asked for (--num, the scene file's
       "numeric"), else the first frusta path that can runs, with a line saying why */
    if (s->path->render->scene_check != NULL &&
        s->path->render->scene_check(&s->sc, s->mesh_path, &diag) != 0) {
        int asked = s->seen_num || (s->scene_path != NULL && s->sf.numeric != LT_SF_NUM_BOTH);
        const lt_path_info_t *alt = asked ? NULL
                                          : lt_paths_fallback(&s->sc, LT_PATHS_FRUSTA, s->path);
        if (alt == NULL) {
            fprintf(stderr, "%s: %s\n", who, diag.msg);
            return EXIT_INPUT;
        }
        fprintf(stderr, "%s: numeric path %s (%s) dropped, running %s (%s): %s\n", who,
                s->path->name, s->path->format, alt->name, alt->format, diag.msg);
        s->path = alt;
    }
    if (s->seen_eye || (s->pre != NULL && s->pre->has_camera)) {
        if (!s->seen_eye)
            memcpy(s->eye, s->pre->eye, sizeof s->eye);
        if (!s->seen_target)
            memcpy(s->target, s->pre != NULL && s->pre->has_camera ? s->pre->target : s->sc.center,
                   sizeof s->target);
        if (s->pre != NULL && s->pre->has_camera && !s->seen_fov)
            s->fov = s->pre->fov;
        if (lt_camera_look(&s->sc, s->eye, s->target, up, s->fov, (uint32_t)s->res,
                           (uint32_t)s->res, &s->cam, &diag) != 0) {
            fprintf(stderr, "%s: %s\n", who, diag.msg);
            return EXIT_INPUT;
        }
    } else {
        lt_camera_default(&s->sc, (uint32_t)s->res, (uint32_t)s->res, &s->cam);
    }
    if (lt_ss_light_square(&s->sc, s->light_c, s->light_c[3], &s->light, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        return EXIT_INPUT;
    }
    if (!lt_meter_machine_known(s->machine)) {
        fprintf(stderr, "%s: --machine %s: unknown machine (known: %s)\n", who, s->machine,
                lt_meter_machine_names());
        return EXIT_USAGE;
    }
    if (lt_meter_init(s->machine, NULL, NULL, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        return EXIT_INPUT;
    }
    lt_ss_opts_default(&s->sc, &o);
    o.path = s->path;
    o.leaf = (uint32_t)s->leaf;
    o.flags = s->flags;
    o.qmc = qmc_kinds[s->qmc];
    o.depth_rel = s->depth_rel;
    o.cos_min = s->cos_min;
    o.filter_vis = s->filter == 1;
    o.pflags = s->pflags;
    if (s->isect == 2) {
        fprintf(stderr, "%s: --isect wt32: the multi-frusta kernels take wt or mt (wt32, the "
                        "s15.16 grid test, is for run and render)\n", who);
        return EXIT_USAGE;
    }
    o.isect = s->isect == 1 ? LT_ISECT_MT : LT_ISECT_WT;
    o.spp = (uint32_t)s->spp;
    s->ss = lt_ss_create(&s->sc, &s->cam, &s->light, &o, &diag);
    if (s->ss == NULL) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        return EXIT_INPUT;
    }
    return 0;
}

/* The scene line. */
static void shadows_print_scene(const shadows_t *s)
{
    const lt_ss_light_t *light = &s->light;
    uint32_t flags = s->flags, pflags = s->pflags;
    printf("scene     %s: %u triangles%s, radius %.1f units (scale %g), %ux%u, %s, light "
           "%.3g x %.3g units at (%.1f, %.1f, %.1f), frusta leaf %u, culling %s%s%s%s%s%s%s%s%s, "
           "primary culling %s%s%s%s%s%s%s, %d shadow samples per pixel (%s), isect %s\n",
           s->mesh_path, s->sc.ntris, s->ground ? " (with ground quad)" : "", s->sc.radius,
           s->sc.scale, s->res, s->res, s->path->format, light->eu[0], light->ev[2],
           light->c[0] + 0.5 * light->eu[0], light->c[1], light->c[2] + 0.5 * light->ev[2],
           s->leaf, flags == 0 ? "none" : "", flags & LT_FRUSTA_BACKFACE ? "b" : "",
           flags & LT_FRUSTA_CORNER ? "c" : "", flags & LT_FRUSTA_CR ? "r" : "",
           flags & LT_FRUSTA_FS ? "f" : "",
           flags & LT_FRUSTA_LEAFRAY ? "l" : "", flags & LT_FRUSTA_SPLIT ? "s" : "",
           flags & LT_FRUSTA_P256 ? "p" : "", flags & LT_FRUSTA_TRIPAR ? "t" : "",
           pflags == 0 ? "none" : "", pflags & LT_FRUSTA_BACKFACE ? "b" : "",
           pflags & LT_FRUSTA_CORNER ? "c" : "", pflags & LT_FRUSTA_CR ? "r" : "",
           pflags & LT_FRUSTA_LEAFRAY ? "l" : "", pflags & LT_FRUSTA_SPLIT ? "s" : "",
           pflags & LT_FRUSTA_TRIPAR ? "t" : "", s->spp,
           qmc_kinds[s->qmc] == LT_QMC_LP ? "Larcher-Pillichshammer" : "Hammersley",
           lt_sf_isects[s->isect]);
}

/* The stages, each measured alone: P-Packet then S-Packet on its hit points, P-Frusta then
 * S-Frusta on its hit points (the same points when the two primary methods agree), shading and
 * the filter. */
static void shadows_stages(shadows_t *s)
{
    lt_softshadow_t *ss = s->ss;
    double t0;
    int i;
    if (s->run_pp) {
        stage_begin();
        t0 = lt_now_s();
        lt_ss_primary(ss);
        stage_end(&s->sp, "P-Packet (+shad)", t0);
        s->hash_pp = lt_ss_primary_hash(ss);
        if (s->report)
            lt_meter_report_text(stdout, "P-Packet primary stage", 0);
    }
    for (i = 0; i < 2; i++) {
        /* S-Packet right after P-Packet (or, without P-Packet, after P-Frusta) */
        if (s->run_pk && (i == 0) == (s->run_pp != 0)) {
            stage_begin();
            t0 = lt_now_s();
            lt_ss_shadows_packet(ss);
            stage_end(&s->sshp, "S-Packet shadows", t0);
            if (s->report)
                lt_meter_report_text(stdout, "S-Packet shadow stage", 0);
        }
        if (i == 0 && s->run_pf) {
            stage_begin();
            t0 = lt_now_s();
            lt_ss_primary_frusta(ss);
            stage_end(&s->spf, "P-Frusta (+shad)", t0);
            s->hash_pf = lt_ss_primary_hash(ss);
            if (s->report)
                lt_meter_report_text(stdout, "P-Frusta primary stage", 0);
        }
    }
    if (s->run_fr) {
        stage_begin();
        t0 = lt_now_s();
        lt_ss_shadows_frusta(ss);
        stage_end(&s->sshf, "S-Frusta shadows", t0);
        if (s->report)
            lt_meter_report_text(stdout, "S-Frusta shadow stage", 0);
    }
    stage_begin();
    t0 = lt_now_s();
    lt_ss_shade(ss, s->run_fr ? LT_SS_FRUSTA : LT_SS_PACKET);
    stage_end(&s->sshade, "shade", t0);
    stage_begin();
    t0 = lt_now_s();
    lt_ss_filter(ss);
    stage_end(&s->sfilt, "filter", t0);
    if (s->report)
        lt_meter_report_text(stdout, "filter stage", 0);
    lt_ss_counts(ss, &s->cnt);
}

/* The ray counts, the agreement checks (an audit where they differ) and the result hash. */
static void shadows_checks(shadows_t *s)
{
    const lt_ss_counts_t *cnt = &s->cnt;
    printf("rays      %llu primary (%llu hits), %llu lit pixels x 16 = %llu shadow rays, %llu "
           "occluded, %llu penumbra pixels\n",
           (unsigned long long)cnt->primary_rays, (unsigned long long)cnt->hits,
           (unsigned long long)cnt->lit, (unsigned long long)cnt->shadow_rays,
           (unsigned long long)cnt->occluded, (unsigned long long)cnt->partial);
    if (s->run_pp && s->run_pf) {
        printf("check     P-Frusta = P-Packet closest hit on %llu of %llu pixels (%llu differ); "
               "primary hash P-Packet %08x, P-Frusta %08x\n",
               (unsigned long long)(cnt->pixels - cnt->prim_mismatch),
               (unsigned long long)cnt->pixels, (unsigned long long)cnt->prim_mismatch,
               s->hash_pp, s->hash_pf);
        if (cnt->prim_mismatch != 0) {
            lt_ss_audit_t au;
            lt_ss_primary_audit(s->ss, &au);
            printf("audit     %llu differing primary rays re-traced by brute force: %llu explained "
                   "by spurious kernel hits (not genuine: off the triangle's padded box or t), %llu "
                   "errors; brute force = P-Packet on %llu, = P-Frusta on %llu\n",
                   (unsigned long long)au.samples, (unsigned long long)au.spurious,
                   (unsigned long long)au.errors, (unsigned long long)au.ref[0],
                   (unsigned long long)au.ref[1]);
            if (au.errors != 0)
                s->rc = EXIT_INPUT;
        }
    }
    if (s->run_fr && s->run_pk) {
        printf("check     frusta = packet visibility on %llu of %llu pixels (%llu differ)",
               (unsigned long long)(cnt->pixels - cnt->shadow_skipped - cnt->mismatch),
               (unsigned long long)(cnt->pixels - cnt->shadow_skipped),
               (unsigned long long)cnt->mismatch);
        if (cnt->shadow_skipped != 0)
            printf("; %llu pixels whose primary hits differ left out",
                   (unsigned long long)cnt->shadow_skipped);
        printf("\n");
        if (cnt->mismatch != 0) {
            lt_ss_audit_t au;
            lt_ss_audit(s->ss, &au);
            printf("audit     %llu differing samples re-traced by brute force: %llu explained by "
                   "spurious kernel hits of grazing rays (off the triangle's padded box), %llu "
                   "errors\n", (unsigned long long)au.samples, (unsigned long long)au.spurious,
                   (unsigned long long)au.errors);
            if (au.errors != 0)
                s->rc = EXIT_INPUT;
        }
    }
    printf("result    %s hash %08x\n", s->path->name, lt_ss_hash(s->ss));
}

/* The totals: the paper's S rows include primary rays, shading and filtering; S-Packet on
 * P-Packet primaries, S-Frusta on P-Frusta primaries (each on the other when only one ran), and
 * S-Frusta on P-Packet primaries (the previous table's combination). */
static void shadows_totals(shadows_t *s)
{
    s->tot_p = s->run_pp ? s->sp : s->spf;
    stage_add(&s->tot_p, &s->sshp);
    stage_add(&s->tot_p, &s->sshade);
    stage_add(&s->tot_p, &s->sfilt);
    s->tot_f = s->run_pf ? s->spf : s->sp;
    stage_add(&s->tot_f, &s->sshf);
    stage_add(&s->tot_f, &s->sshade);
    stage_add(&s->tot_f, &s->sfilt);
    s->tot_fo = s->sp;
    stage_add(&s->tot_fo, &s->sshf);
    stage_add(&s->tot_fo, &s->sshade);
    stage_add(&s->tot_fo, &s->sfilt);
}

/* (sim build) Table 1: one row per method with triangle, box and intersection counts, cycles
 * and lane utilisation, and the reductions against the paper's. */
static void shadows_table(const shadows_t *s, const char *machine_name, double mhz)
{
    const stage_t *sp = &s->sp, *spf = &s->spf, *sshp = &s->sshp, *sshf = &s->sshf;
    const stage_t *tot_p = &s->tot_p;
    const stage_t *rows[5];
    const char *names[5] = {"P-Packet (+shad)", "P-Frusta (+shad)", "S-Packet", "S-Frusta",
                            "S-Frusta/P-Packet"};
    int r, show[5];
    rows[0] = sp;
    rows[1] = spf;
    rows[2] = tot_p;
    rows[3] = &s->tot_f;
    rows[4] = &s->tot_fo;
    show[0] = s->run_pp;
    show[1] = s->run_pf;
    show[2] = s->run_pk;
    show[3] = s->run_fr;
    show[4] = s->run_fr && s->run_pp && s->run_pf;
    printf("\nTable 1 (simulated, %s at %.0f MHz, one core; P rows: cycles without shading "
           "(with it), as the paper's; S rows include primary rays, shading and filtering as "
           "in the paper)\n", machine_name, mhz);
    printf("%-18s %21s %10s %10s %22s %8s  %s\n", "", "#tris (+culling)", "#AABB", "#isec",
           "cycles", "lanes", "cycles: setup/traverse/intersect/shade/filter");
    for (r = 0; r < 5; r++) {
        const stage_t *st = rows[r];
        char cyc[64];
        if (!show[r])
            continue;
        if (r < 2)
            snprintf(cyc, sizeof cyc, "%.2fM (%.2fM)",
                     (double)(st->cycles - st->cyc[LT_PH_SHADE]) / 1e6,
                     (double)st->cycles / 1e6);
        else
            snprintf(cyc, sizeof cyc, "%.2fM", (double)st->cycles / 1e6);
        printf("%-18s %9.0fK / %8.0fK %9.0fK %9.0fK %22s %7.1f%%  %.1fM/%.1fM/%.1fM/%.1fM/"
               "%.1fM\n",
               names[r], k_(st->ev[LT_EV_TRI_FETCH]), k_(st->ev[LT_EV_TRI_KEPT]),
               k_(st->ev[LT_EV_AABB]), k_(st->ev[LT_EV_TRIS]), cyc,
               100.0 * ratio(st->ev[LT_EV_LANES_ON], 16u * st->ev[LT_EV_LANE_OPS]),
               (double)st->cyc[LT_PH_SETUP] / 1e6, (double)st->cyc[LT_PH_TRAVERSE] / 1e6,
               (double)st->cyc[LT_PH_INTERSECT] / 1e6, (double)st->cyc[LT_PH_SHADE] / 1e6,
               (double)st->cyc[LT_PH_FILTER] / 1e6);
        if (r == 1 && s->run_pp) {
            char red[64];
            snprintf(red, sizeof red, "%.2fx (%.2fx)",
                     ratio(sp->cycles - sp->cyc[LT_PH_SHADE], spf->cycles - spf->cyc[LT_PH_SHADE]),
                     ratio(sp->cycles, spf->cycles));
            printf("%-18s %8.2fx / %7.2fx %9.2fx %9.2fx %22s            (paper: 1.45-2.3x / "
                   "2.98-9.5x, 11.8-21x, 1.67-3.1x, 3.42-7.83x (2.98-6.09x))\n",
                   "P Reduction", ratio(sp->ev[LT_EV_TRI_FETCH], spf->ev[LT_EV_TRI_FETCH]),
                   ratio(sp->ev[LT_EV_TRI_KEPT], spf->ev[LT_EV_TRI_KEPT]),
                   ratio(sp->ev[LT_EV_AABB], spf->ev[LT_EV_AABB]),
                   ratio(sp->ev[LT_EV_TRIS], spf->ev[LT_EV_TRIS]), red);
        }
        if ((r == 3 && s->run_pk) || (r == 4 && s->run_pk)) {
            const stage_t *fr = rows[r];
            printf("%-18s %8.2fx / %7.2fx %9.2fx %9.2fx %21.2fx            %s\n",
                   r == 3 ? "S Reduction" : "  reduction", ratio(tot_p->ev[LT_EV_TRI_FETCH],
                                                                 fr->ev[LT_EV_TRI_FETCH]),
                   ratio(tot_p->ev[LT_EV_TRI_KEPT], fr->ev[LT_EV_TRI_KEPT]),
                   ratio(tot_p->ev[LT_EV_AABB], fr->ev[LT_EV_AABB]),
                   ratio(tot_p->ev[LT_EV_TRIS], fr->ev[LT_EV_TRIS]),
                   ratio(tot_p->cycles, fr->cycles),
                   r == 3 ? "(paper: 1.89-3.67x / 4.96-10.06x, 14.1-23.8x, 1.01-1.44x, "
                            "3.94-6.11x)"
                          : "(S-Frusta on P-Packet primaries, the previous combination)");
        }
    }
    if (s->run_pk && s->run_fr)
        printf("%-18s %8.2fx / %7.2fx %9.2fx %9.2fx %21.2fx            (shadow stage alone: "
               "S-Packet %.2fM vs S-Frusta %.2fM cycles)\n",
               "S shadows only:", ratio(sshp->ev[LT_EV_TRI_FETCH], sshf->ev[LT_EV_TRI_FETCH]),
               ratio(sshp->ev[LT_EV_TRI_KEPT], sshf->ev[LT_EV_TRI_KEPT]),
               ratio(sshp->ev[LT_EV_AABB], sshf->ev[LT_EV_AABB]),
               ratio(sshp->ev[LT_EV_TRIS], sshf->ev[LT_EV_TRIS]), ratio(sshp->cycles, sshf->cycles),
               (double)sshp->cycles / 1e6, (double)sshf->cycles / 1e6);
}

/* The frusta stage against the packet stage of the same rays, from this run's counters: the
 * cycles of each phase (setup, traversal, intersection, the rest), box and triangle tests, and
 * the phase that decides the ratio (the largest difference). */
static void why_line(const char *which, const stage_t *fr, const stage_t *pk)
{
    static const struct { int ph; const char *name; } phs[] = {
        {LT_PH_SETUP, "setup"}, {LT_PH_TRAVERSE, "traversal"}, {LT_PH_INTERSECT, "intersection"}};
    double d[4], worst = 0.0;
    int i, w = 3;
    uint64_t rest_f = fr->cycles, rest_p = pk->cycles;
    printf("why       %s-Frusta / %s-Packet %.2fM / %.2fM cycles (%.2fx):", which, which,
           (double)fr->cycles / 1e6, (double)pk->cycles / 1e6, ratio(pk->cycles, fr->cycles));
    for (i = 0; i < 3; i++) {
        uint64_t a = fr->cyc[phs[i].ph], b = pk->cyc[phs[i].ph];
        printf(" %s %.2fM / %.2fM,", phs[i].name, (double)a / 1e6, (double)b / 1e6);
        d[i] = (double)a - (double)b;
        rest_f -= a;
        rest_p -= b;
    }
    d[3] = (double)rest_f - (double)rest_p;
    for (i = 0; i < 4; i++)
        if (fabs(d[i]) > fabs(worst)) {
            worst = d[i];
            w = i;
        }
    printf(" other %.2fM / %.2fM; box tests %.0fK / %.0fK (ray-box pairs %.0fK / %.0fK), "
           "triangle tests %.0fK / %.0fK (ray-triangle pairs %.0fK / %.0fK); the %s decides it "
           "(%+.2fM cycles)\n",
           (double)rest_f / 1e6, (double)rest_p / 1e6, k_(fr->ev[LT_EV_AABB]),
           k_(pk->ev[LT_EV_AABB]), k_(fr->ev[LT_EV_AABB_RAYS]), k_(pk->ev[LT_EV_AABB_RAYS]),
           k_(fr->ev[LT_EV_TRIS]), k_(pk->ev[LT_EV_TRIS]), k_(fr->ev[LT_EV_TRI_RAYS]),
           k_(pk->ev[LT_EV_TRI_RAYS]), w < 3 ? phs[w].name : "rest (shading, culling, other)",
           worst / 1e6);
}

/* (sim build) Table 1, why from the run's counters, the stage cycles and the simulated speeds. */
static void shadows_simulated(const shadows_t *s)
{
    const stage_t *sp = &s->sp, *spf = &s->spf, *sshp = &s->sshp, *sshf = &s->sshf;
    const lt_ss_counts_t *cnt = &s->cnt;
    lt_meter_machine_t mm;
    char r1[LT_RATE_TEXT], r2[LT_RATE_TEXT], r3[LT_RATE_TEXT], r4[LT_RATE_TEXT];
    double mhz, hz;
    (void)lt_meter_machine_info(s->machine, &mm);
    mhz = (double)mm.clock_mhz;
    hz = mhz * 1e6; /* rays per cycle x cycles per second */
    shadows_table(s, mm.name, mhz);
    if (s->run_pk && s->run_fr)
        why_line("S", sshf, sshp);
    if (s->run_pp && s->run_pf)
        why_line("P", spf, sp);
    printf("stages    P-Packet %.2fM, P-Frusta %.2fM, shade %.2fM, filter %.2fM cycles (%.1f "
           "cycles/pixel); culled pairs: P-Packet back-face %.0fK; P-Frusta back-face %.0fK, "
           "corner %.0fK, leaf %.0fK, split %.0fK; S-Packet back-face %.0fK; S-Frusta back-face "
           "%.0fK, corner %.0fK, leaf %.0fK, split %.0fK\n",
           (double)sp->cycles / 1e6, (double)spf->cycles / 1e6, (double)s->sshade.cycles / 1e6,
           (double)s->sfilt.cycles / 1e6, ratio(s->sfilt.cycles, cnt->pixels),
           k_(sp->ev[LT_EV_CULL_BACK]), k_(spf->ev[LT_EV_CULL_BACK]),
           k_(spf->ev[LT_EV_CULL_CORNER]), k_(spf->ev[LT_EV_LEAF_CULL]), k_(spf->ev[LT_EV_SPLIT]),
           k_(sshp->ev[LT_EV_CULL_BACK]), k_(sshf->ev[LT_EV_CULL_BACK]),
           k_(sshf->ev[LT_EV_CULL_CORNER]), k_(sshf->ev[LT_EV_LEAF_CULL]),
           k_(sshf->ev[LT_EV_SPLIT]));
    if (s->run_pp || s->run_pf)
        printf("speed     primary rays per simulated %.0f MHz core: P-Packet %s "
               "(%s with shading), P-Frusta %s (%s with shading)\n", mhz,
               lt_rate_text(ratio(cnt->primary_rays, sp->cycles - sp->cyc[LT_PH_SHADE]) * hz, r1),
               lt_rate_text(ratio(cnt->primary_rays, sp->cycles) * hz, r2),
               lt_rate_text(ratio(cnt->primary_rays, spf->cycles - spf->cyc[LT_PH_SHADE]) * hz, r3),
               lt_rate_text(ratio(cnt->primary_rays, spf->cycles) * hz, r4));
    if (s->run_fr)
        printf("speed     S-Frusta: %s per simulated %.0f MHz core (primary + shadow "
               "rays over all stages); shadow stage alone %s\n",
               lt_rate_text(ratio(cnt->primary_rays + cnt->shadow_rays, s->tot_f.cycles) * hz, r1),
               mhz, lt_rate_text(ratio(cnt->shadow_rays, sshf->cycles) * hz, r2));
    if (s->run_pk)
        printf("speed     S-Packet: %s per simulated core; shadow stage alone %s\n",
               lt_rate_text(ratio(cnt->primary_rays + cnt->shadow_rays, s->tot_p.cycles) * hz, r1),
               lt_rate_text(ratio(cnt->shadow_rays, sshp->cycles) * hz, r2));
}

/* (native build) the stage times and speed-ups. */
static void shadows_native(const shadows_t *s)
{
    const stage_t *sp = &s->sp, *spf = &s->spf, *sshp = &s->sshp, *sshf = &s->sshf;
    const lt_ss_counts_t *cnt = &s->cnt;
    char r1[LT_RATE_TEXT];
    if (s->run_pp)
        printf("native    P-Packet %.3f s (%s with shading)", sp->seconds,
               lt_rate_text(rate(cnt->primary_rays, sp->seconds), r1));
    if (s->run_pf)
        printf("%s P-Frusta %.3f s (%s with shading)", s->run_pp ? "," : "native   ",
               spf->seconds, lt_rate_text(rate(cnt->primary_rays, spf->seconds), r1));
    if (s->run_pk)
        printf(", S-Packet shadows %.3f s (%s)", sshp->seconds,
               lt_rate_text(rate(cnt->shadow_rays, sshp->seconds), r1));
    if (s->run_fr)
        printf(", S-Frusta shadows %.3f s (%s)", sshf->seconds,
               lt_rate_text(rate(cnt->shadow_rays, sshf->seconds), r1));
    printf(", shade %.3f s, filter %.3f s (one thread); traces on %u thread%s\n",
           s->sshade.seconds, s->sfilt.seconds, lt_par_threads(), lt_par_threads() == 1 ? "" : "s");
    if (s->run_pk && s->run_fr)
        printf("native    S-Frusta / S-Packet shadow speed-up %.2fx\n",
               sshp->seconds / sshf->seconds);
    if (s->run_pp && s->run_pf)
        printf("native    P-Frusta / P-Packet primary speed-up %.2fx (with shading)\n",
               sp->seconds / spf->seconds);
}

/* The 256-sample reference and the quality figures (unless --no-ref), the PNGs. */
static void shadows_outputs(shadows_t *s)
{
    lt_diag_t diag;
    if (!s->no_ref) {
        lt_ss_quality_t q;
        double t0 = lt_now_s();
        lt_progress_begin("reference", s->quiet);
        lt_ss_reference(s->ss, lt_progress);
        lt_progress_end();
        lt_ss_quality(s->ss, s->tol, &q);
        printf("quality   vs 256 samples/pixel (%.1f s): PSNR filtered %.2f dB, unfiltered %d spp "
               "%.2f dB, reference through the same filter %.2f dB, filtered vs filtered reference "
               "%.2f dB; penumbra pixels %llu, within %.3g: %.1f%% filtered (%llu), %.1f%% "
               "unfiltered (%llu)\n",
               lt_now_s() - t0, q.psnr_filtered, s->spp, q.psnr_raw, q.psnr_filtered_ref,
               q.psnr_vs_filtered_ref,
               (unsigned long long)q.penumbra, q.tol, 100.0 * ratio(q.penumbra_ok, q.penumbra),
               (unsigned long long)q.penumbra_ok, 100.0 * ratio(q.penumbra_raw_ok, q.penumbra),
               (unsigned long long)q.penumbra_raw_ok);
        if (s->ref_png != NULL && lt_ss_write_png(s->ss, s->ref_png, 2, &diag) != 0) {
            fprintf(stderr, "%s: %s\n", who, diag.msg);
            s->rc = EXIT_INPUT;
        }
    }
    if (s->png != NULL && lt_ss_write_png(s->ss, s->png, s->png_which, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        s->rc = EXIT_INPUT;
    }
    if (s->raw_png != NULL && lt_ss_write_png(s->ss, s->raw_png, 1, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        s->rc = EXIT_INPUT;
    }
}

/* --pack-block: the block's frusta blob, written all or nothing, then traced here as a target
 * would (firmware/apps/scene_fw.c prints the same lines); the crop must give the whole scene's
 * answer. Returns 0 or an exit code. */
static int shadows_pack(shadows_t *s)
{
    uint32_t bx = UINT32_MAX, by = UINT32_MAX, th[16], t, lit = 0, occ = 0;
    uint8_t *blob = NULL;
    size_t bytes = 0;
    lt_fblob_t *f;
    lt_diag_t diag;
    lt_sblob_err_t e;
    int rc = EXIT_INPUT;
    if (strcmp(s->pack_block, "auto") != 0) {
        char end;
        if (sscanf(s->pack_block, "%u,%u%c", &bx, &by, &end) != 2) {
            fprintf(stderr, "%s: --pack-block %s: expected X,Y or auto\n", who, s->pack_block);
            return EXIT_USAGE;
        }
    }
    if (lt_ss_pack_block(s->ss, bx, by, &blob, &bytes, &diag) != 0) {
        fprintf(stderr, "%s: --pack-block: %s\n", who, diag.msg);
        return EXIT_INPUT;
    }
    f = malloc(sizeof *f);
    if (f == NULL) {
        fprintf(stderr, "%s: --blob: out of memory\n", who);
        goto done;
    }
    if (lt_write_file_atomic(s->blob, blob, bytes, &diag) != 0) {
        fprintf(stderr, "%s: --blob: %s\n", who, diag.msg);
        goto done;
    }
    e = lt_fblob_open(blob, bytes, f);
    if (e != LT_SBLOB_OK) {
        fprintf(stderr, "%s: %s: %s\n", who, s->blob, lt_sblob_err_str(e));
        goto done;
    }
    printf("fblob %u triangles (of %u), block %u,%u, spp %u, %zu bytes -> %s\n", f->bvh.ntris,
           f->scene_tris, f->bx, f->by, f->spp, bytes, s->blob);
    for (t = 0; t < 16u; t++) {
        lt_fblob_tile_t r;
        if (lt_fblob_trace_tile(f, t, NULL, &r) != LT_OK) {
            fprintf(stderr, "%s: %s: tile %u failed\n", who, s->blob, t);
            goto done;
        }
        printf("ftile %u hash 0x%08x lit %u occluded %u\n", t, r.hash, r.lit, r.occluded);
        th[t] = r.hash;
        lit += r.lit;
        occ += r.occluded;
    }
    t = lt_fblob_block_hash(th);
    printf("block hash 0x%08x lit %u occluded %u (whole scene 0x%08x: %s)\n", t, lit, occ, f->ref,
           t == f->ref ? "equal" : "differs");
    rc = t == f->ref ? 0 : EXIT_INPUT;
done:
    free(f);
    free(blob);
    return rc;
}

int lt_shadows_cli(int argc, char **argv, const char *prog)
{
    shadows_t s;
    int rc;
    shadows_defaults(&s, prog);
    rc = shadows_parse(&s, argc, argv);
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    rc = shadows_scene(&s);
    if (rc != 0)
        return rc;
    s.path = lt_paths_find(s.num_names[s.num], LT_PATHS_FRUSTA);
    s.run_pp = s.prim != 1; /* not frusta only */
    s.run_pf = s.prim != 0; /* not packets only */
    s.run_fr = s.only != 1;
    s.run_pk = s.only != 0;
    rc = shadows_load(&s);
    if (rc == 0) {
        if (!s.quiet)
            shadows_print_scene(&s);
        shadows_stages(&s);
        shadows_checks(&s);
        shadows_totals(&s);
        if (lt_meter_available())
            shadows_simulated(&s);
        else
            shadows_native(&s);
        shadows_outputs(&s);
        rc = s.rc;
        if (rc == 0 && s.pack_block != NULL)
            rc = shadows_pack(&s);
    }
    lt_ss_free(s.ss);
    lt_scene_free(&s.sc);
    lt_mesh_free(&s.m);
    return rc;
}
