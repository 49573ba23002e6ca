/* lanetrace_main.c - the lanetrace command line: subcommands run, render, reproject, info, diff,
 * machines, stream (docs/user-guide.md).
 * Built twice from this source: build/sim/lanetrace (the kernels charged to a machine model: cycle
 * reports) and build/host/lanetrace-native (LT_COST_OFF: native speed); `lanetrace run --native`
 * hands over to the native build. Exit codes: 0 ok, 1 input or runtime error, 2 usage. Host only.
 */
#include "lt/lt.h"
#include "cli/lt_cliutil.h"
#include "lt_rate.h"
#include "cli/lt_opt.h"
#include "io/lt_exr.h"
#include "io/lt_heatmap.h"
#include "io/lt_mesh.h"
#include "lt_meter.h"
#include "io/lt_png.h"
#include "render/lt_par.h"
#include "render/lt_paths.h"
#include "tune/lt_recommend.h"
#include "render/lt_render.h"
#include "cli/lt_reproject_cli.h"
#include "cli/lt_pack_cli.h"
#include "cli/lt_fwblob_cli.h"
#include "cli/lt_shadows_cli.h"
#include "cli/lt_tune_cli.h"
#include "render/lt_scene.h"
#include "io/lt_scenefile.h"
#include "io/lt_sniff.h"
#include "io/lt_tmpfiles.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define EXIT_INPUT 1
#define EXIT_USAGE 2

static int quiet;
static int threads_opt; /* --threads (0: every core) */
static const char *prog = "lanetrace";

/* ---- progress bar (lt_cliutil.h: stderr, a TTY only, after the first second) ----------------- */

static void progress(double done) { lt_progress(done); }

static void progress_begin(const char *label) { lt_progress_begin(label, quiet); }

static void progress_end(void) { lt_progress_end(); }

/* ---- scene files: the mesh and the outputs they name ---------------------------------------- */

/* The mesh to trace: the scene file's (or --mesh), the bundled teapot when neither names one; a
 * scene file without "mesh" (a depth image's scene, for `reproject`) is refused, not replaced. */
static int scene_mesh_or_default(const char *scene, lt_scenefile_t *sf, const char *cmd)
{
    if (sf->mesh[0] != '\0')
        return 0;
    if (scene != NULL) {
        fprintf(stderr, "%s %s: %s names no \"mesh\"%s; give --mesh PATH\n", prog, cmd, scene,
                sf->depth[0] != '\0' ? " (it names a depth image: `lanetrace reproject` "
                                       "traces it)" : "");
        return -1;
    }
    snprintf(sf->mesh, sizeof sf->mesh, "scenes/teapot.obj");
    return 0;
}

/* Whether a and b name the same existing file. */
static int same_file(const char *a, const char *b)
{
    struct stat x, y;
    return stat(a, &x) == 0 && stat(b, &y) == 0 && x.st_dev == y.st_dev && x.st_ino == y.st_ino;
}

/* A scene file's output (key "outputs.report" ...) under the checks its command-line option
 * gets (lt_opt_output_bad), and not one of the scene's inputs. */
static int scene_output_bad(const char *scene, const char *key, const char *path, const char *ext,
                            const lt_scenefile_t *sf)
{
    char why[384];
    if (lt_opt_output_bad(ext, path, why, sizeof why)) {
        fprintf(stderr, "%s: '%s' = \"%s\": %s\n", scene, key, path, why);
        return -1;
    }
    if (same_file(path, scene) || (sf->mesh[0] != '\0' && same_file(path, sf->mesh)) ||
        (sf->depth[0] != '\0' && same_file(path, sf->depth))) {
        fprintf(stderr, "%s: '%s' = \"%s\" is one of the scene's inputs; it would be "
                "overwritten\n", scene, key, path);
        return -1;
    }
    return 0;
}

/* ---- atomic outputs: a temporary name renamed into place; Ctrl-C removes the temporary ---------- */


/* text into path through a registered temporary (a fatal signal removes it) */
static int write_atomic(const char *path, const char *text, lt_diag_t *diag)
{
    char tmp[LT_TMP_PATH_MAX];
    FILE *f;
    if (lt_tmp_begin(path, tmp, diag) != 0)
        return -1;
    f = fopen(tmp, "w");
    if (f == NULL) {
        lt_diag_fail(diag, "%s: cannot create the output (directory missing or not writable)", path);
        lt_tmp_end(tmp);
        return -1;
    }
    if (fputs(text, f) < 0 || fclose(f) != 0) {
        lt_diag_fail(diag, "%s: write failed (disk full?)", path);
        lt_tmp_discard(tmp);
        return -1;
    }
    return lt_tmp_commit(tmp, path, diag);
}

/* run --rays */
static const char *const run_rays_names[] = {"packet", "single", "wide", NULL};
/* render --rays */
static const char *const render_rays_names[] = {"packet", "wide", NULL};

/* ---- run --native ------------------------------------------------------------------------- */

/* The simulator build's kernels charge every op (LT_COST_SIM is a compile-time mode): native
 * speed is the other binary, build/host/lanetrace-native, which this hands over to. */
static int exec_native(int argc, char **argv)
{
    char path[1200];
    const char *slash = strrchr(argv[0], '/');
    char **nargv = calloc((size_t)argc + 2, sizeof *nargv);
    int i, n = 0;
    if (nargv == NULL)
        return EXIT_INPUT;
    if (slash != NULL)
        snprintf(path, sizeof path, "%.*s/../host/lanetrace-native", (int)(slash - argv[0]), argv[0]);
    else
        snprintf(path, sizeof path, "lanetrace-native");
    nargv[n++] = path;
    for (i = 1; i < argc; i++)
        if (strcmp(argv[i], "--native") != 0)
            nargv[n++] = argv[i];
    nargv[n] = NULL;
    execv(path, nargv);
    fprintf(stderr, "%s: --native: cannot run %s (build it with `make all`)\n", prog, path);
    free(nargv);
    return EXIT_INPUT;
}

/* ---- --num: the names of the numeric-path registry (host/render/lt_paths.c) ------------------- */

/* The --num choices for a family: the registry's names (and "both" for run, every path in turn),
 * each with the scene file's lt_sf_num_t bits; the help line names each path's format. Returns
 * the number of names (names[] ends with NULL). */
static int num_choices(unsigned families, int with_both, const char **names, unsigned *sets,
                       char *help, size_t helplen)
{
    const lt_path_info_t *p;
    unsigned all = 0;
    size_t len;
    int n = 0;
    len = (size_t)snprintf(help, helplen, "numeric path:");
    for (p = lt_paths; p->name != NULL && n < 6; p++) {
        if ((p->families & families) == 0)
            continue;
        names[n] = p->name;
        sets[n++] = (unsigned)p->sf_num;
        all |= (unsigned)p->sf_num;
        if (len < helplen)
            len += (size_t)snprintf(help + len, helplen - len, "%s %s (%s)", n > 1 ? "," : "",
                                    p->name, p->format);
    }
    if (with_both) {
        names[n] = "both";
        sets[n++] = all;
        if (len < helplen)
            snprintf(help + len, helplen - len, ", both (each in turn)");
    }
    names[n] = NULL;
    return n;
}

/* lt_recommend_mesh's facts of a loaded mesh and its prepared scene, and its picks into r. */
static void mesh_recommend(const lt_mesh_t *m, const lt_scene_t *sc, const char *machine,
                           lt_rec_t *r)
{
    lt_rec_mesh_facts_t f;
    int a;
    memset(&f, 0, sizeof f);
    f.ntris = m->ntris;
    f.nonzero = sc->nonzero;
    f.collapsed_q16 = sc->collapsed_q16;
    for (a = 0; a < 3; a++)
        if (m->hi[a] - m->lo[a] > f.extent)
            f.extent = m->hi[a] - m->lo[a];
    f.scale = sc->scale;
    f.min_edge = sc->scale > 0.0 ? sc->min_edge / sc->scale : 0.0;
    f.machine = machine;
    lt_recommend_mesh(&f, r);
}

/* 1 for the structures with a leaf size (the scene file's "leaf": bvh, bvhq, kd). */
static int structure_has_leaf(const char *structure)
{
    return strcmp(structure, "bvh") == 0 || strcmp(structure, "bvhq") == 0 ||
           strcmp(structure, "kd") == 0;
}

/* ---- run ------------------------------------------------------------------------------------ */

/* lanetrace run: the options (the flags override the scene file), the inputs, then per numeric
 * path a trace and its outputs. */
typedef struct run {
    /* options */
    lt_scenefile_t sf;
    const char *scene_path;
    int npos;
    const char *mesh_over, *report, *csv, *depth_out, *heat_out, *machine, *l1, *l2;
    uint32_t wh[2];
    int num, structure, isect, json, repeat, do_ref, native;
    int rays; /* --rays: 0 16-ray packets (default), 1 single rays (bvh: the wide tree), 2 16-ray
                 packets through the wide tree (bvh) */
    int seen_res, seen_num, seen_structure, seen_isect, seen_machine, seen_l1, seen_l2;
    int autop;              /* --auto: info's recommendation for the knobs nobody set */
    char auto_json[2048];   /* what --auto did, a JSON object for the report ("" = nothing) */
    const char *num_names[8];
    unsigned num_sets[8];
    /* inputs */
    lt_mesh_t mesh;
    lt_scene_t sc;
    lt_camera_t cam;
    lt_frame_t ref, fr;
    /* outputs */
    float *zbuf[LT_PATHS_MAX], *idbuf[LT_PATHS_MAX]; /* per lt_paths_index */
    char zname[LT_PATHS_MAX][16], idname[LT_PATHS_MAX][16];
    cJSON *jout;
    FILE *csvf;
    int status, heat_warned;
    lt_outset_t *set; /* every output file, renamed into place together at the end */
    /* a selected path dropped because it cannot represent the scene, and the reason */
    const lt_path_info_t *dropped;
    char drop_reason[LT_DIAG_MAX];
} run_t;

/* Whether the scene file's path bits select p (an object-space path). */
static int run_selects(const lt_scenefile_t *sf, const lt_path_info_t *p)
{
    return (p->families & LT_PATHS_OBJECT) && ((unsigned)sf->numeric & (unsigned)p->sf_num);
}

/* How many paths the run traces. */
static int run_npaths(const lt_scenefile_t *sf)
{
    const lt_path_info_t *p;
    int n = 0;
    for (p = lt_paths; p->name != NULL; p++)
        n += run_selects(sf, p);
    return n;
}

/* The selected paths' names, "q16 and f32" (a static buffer). */
static const char *run_selected_names(const lt_scenefile_t *sf)
{
    static char buf[128];
    const lt_path_info_t *p;
    size_t len = 0;
    buf[0] = '\0';
    for (p = lt_paths; p->name != NULL && len < sizeof buf; p++)
        if (run_selects(sf, p)) {
            int w = snprintf(buf + len, sizeof buf - len, "%s%s", len ? " and " : "", p->name);
            if (w < 0)
                break;
            len += (size_t)w;
        }
    return buf;
}

/* r before the options: nothing given, the defaults of a run. */
static void run_defaults(run_t *r)
{
    memset(r, 0, sizeof *r);
    lt_sf_defaults(&r->sf);
    r->repeat = 1;
    r->do_ref = 1;
    r->autop = 1;
}

/* path as a member of the run's output set: *dst is where its writer writes. Returns 0, or -1
 * after the message (r->status set). */
static int run_out(run_t *r, const char *path, const char **dst)
{
    lt_diag_t diag;
    if (lt_outset_add(r->set, path, dst, &diag) != 0) {
        fprintf(stderr, "%s run: %s\n", prog, diag.msg);
        r->status = EXIT_INPUT;
        return -1;
    }
    return 0;
}

/* The options into r; LT_OPT_OK, LT_OPT_HELP or LT_OPT_USAGE. */
static int run_parse(run_t *r, int argc, char **argv)
{
    char who[64], num_help[256], machine_help[256];
    const lt_opt_t opts[] = {
        LT_OPT_IN("--mesh", "PATH", &r->mesh_over,
                  "mesh file (overrides the scene's \"mesh\"; default scenes/teapot.obj)"),
        {.name = "--res", .kind = LT_OPT_SIZE, .dest = r->wh, .seen = &r->seen_res,
         .meta = "WxH|N", .help = "image size ({range} per side)", .lo = 1, .hi = LT_SF_MAX_RES},
        {.name = "--num", .kind = LT_OPT_ENUM, .dest = &r->num, .seen = &r->seen_num,
         .names = r->num_names, .help = num_help},
        {.name = "--structure", .kind = LT_OPT_ENUM, .dest = &r->structure,
         .seen = &r->seen_structure, .meta = "NAME", .names = lt_render_structures,
         .help = "acceleration structure: {choices} (default bvh)"},
        {.name = "--isect", .kind = LT_OPT_ENUM, .dest = &r->isect, .seen = &r->seen_isect,
         .meta = "NAME", .names = lt_sf_isects,
         .help = "ray/triangle test: {choices} (default wt: watertight; mt: Moller-Trumbore,\n"
                 "cheaper, leaks at shared edges; wt32: s15.16 only, watertight on a grid\n"
                 "with 32-bit edge functions, t of the snapped triangle)"},
        {.name = "--machine", .kind = LT_OPT_STRING, .dest = &r->machine,
         .seen = &r->seen_machine, .meta = "NAME", .help = machine_help},
        {.name = "--l1", .kind = LT_OPT_STRING, .dest = &r->l1, .seen = &r->seen_l1,
         .meta = "S:W:B", .help = "L1 cache geometry override (sets:ways:line)",
         .flags = LT_OPT_NONEMPTY},
        {.name = "--l2", .kind = LT_OPT_STRING, .dest = &r->l2, .seen = &r->seen_l2,
         .meta = "S:W:B", .help = "L2 cache geometry override (sets:ways:line)",
         .flags = LT_OPT_NONEMPTY},
        LT_OPT_OUT("--report", "PATH.json", &r->report, "json",
                   "write the report JSON (PATH.q16.json / PATH.f32.json with both paths)"),
        LT_OPT_OUT("--csv", "PATH.csv", &r->csv, "csv", "write one CSV row per path"),
        LT_OPT_OUT("--depth", "PATH.exr", &r->depth_out, "exr",
                   "write distance and triangle id per pixel (EXR, FLOAT channels\n"
                   "<path>.Z and <path>.id)"),
        LT_OPT_OUT("--heatmap", "PREFIX", &r->heat_out, "",
                   "(sim build) per-pixel simulated cycles: PREFIX.<path>.png with a\n"
                   "legend and PREFIX.<path>.exr with the values; traversal steps:\n"
                   "PREFIX.<path>.steps.png / .steps.exr"),
        LT_OPT_INT("--repeat", "N", &r->repeat, 1, 100000, "trace the frame N times (timing), {range}"),
        LT_OPT_SET_("--no-ref", &r->do_ref, 0, "skip the reference and the accuracy figures"),
        LT_OPT_AUTO_(&r->autop, "the numeric path, structure and leaf size"),
        LT_OPT_ENUM_("--rays", &r->rays, run_rays_names,
                     "packet: 16-ray packets over 4x4 tiles (default); single: each ray\n"
                     "alone (bvh: through the 8-wide tree with 4-triangle leaf blocks,\n"
                     "docs/bvh.md; bvhq: its single-ray walk; kd, grid, chunks: a one-lane\n"
                     "packet); wide: 16-ray packets through that 8-wide tree (bvh; one\n"
                     "frustum test per node; other structures: as packet)"),
        LT_OPT_FLAG_("--native", &r->native, "run the native build (no cycle model; wall-clock speed)"),
        LT_OPT_FLAG_("--json", &r->json, "machine-readable JSON on stdout"),
        LT_OPT_THREADS_(&threads_opt),
        LT_OPT_FLAG_("-q", &quiet, "quiet: summary lines only"),
        LT_OPT_END_};
    lt_opt_cmd_t cmd = {who, "[SCENE.json] [options]",
                        "Trace primary rays of a scene in s15.16 and/or float32, print accuracy "
                        "against a\ndouble-precision reference and (simulator build) the cycle "
                        "report.\n",
                        NULL, opts, &r->scene_path, 1, &r->npos};
    int rc;
    snprintf(who, sizeof who, "%s run", prog);
    num_choices(LT_PATHS_OBJECT, 1, r->num_names, r->num_sets, num_help, sizeof num_help);
    snprintf(machine_help, sizeof machine_help, "machine model: %s (lanetrace machines)",
             lt_meter_machine_names());
    rc = lt_opt_parse(&cmd, argc, argv, 2);
    lt_par_set_threads((unsigned)threads_opt);
    if (r->json)
        quiet = 1;
    return rc;
}

/* The scene file, then the flags given on the command line over it; the machine model.
 * Returns 0 or an exit code. */
static int run_settle(run_t *r)
{
    lt_scenefile_t *sf = &r->sf;
    lt_diag_t diag;
    if (r->scene_path != NULL) {
        if (lt_sf_load(r->scene_path, sf, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            return EXIT_INPUT;
        }
    }
    if (r->seen_res) {
        sf->width = r->wh[0];
        sf->height = r->wh[1];
    }
    if (r->seen_num)
        sf->numeric = (lt_sf_num_t)r->num_sets[r->num];
    if (r->seen_structure)
        snprintf(sf->structure, sizeof sf->structure, "%s", lt_render_structures[r->structure]);
    if (r->seen_isect)
        snprintf(sf->isect, sizeof sf->isect, "%s", lt_sf_isects[r->isect]);
    if (r->seen_machine)
        snprintf(sf->machine, sizeof sf->machine, "%s", r->machine);
    if (r->seen_l1)
        snprintf(sf->l1, sizeof sf->l1, "%s", r->l1);
    if (r->seen_l2)
        snprintf(sf->l2, sizeof sf->l2, "%s", r->l2);
    if (r->mesh_over != NULL)
        snprintf(sf->mesh, sizeof sf->mesh, "%s", r->mesh_over);
    if (scene_mesh_or_default(r->scene_path, sf, "run") != 0)
        return EXIT_INPUT;
    if (r->report == NULL && sf->out_report[0] != '\0') {
        if (scene_output_bad(r->scene_path, "outputs.report", sf->out_report, "json", sf) != 0)
            return EXIT_INPUT;
        r->report = sf->out_report;
    }
    if (r->csv == NULL && sf->out_csv[0] != '\0') {
        if (scene_output_bad(r->scene_path, "outputs.csv", sf->out_csv, "csv", sf) != 0)
            return EXIT_INPUT;
        r->csv = sf->out_csv;
    }
    if (!lt_meter_machine_known(sf->machine)) {
        fprintf(stderr, "%s run: machine '%s' unknown (known: %s)\n", prog, sf->machine,
                lt_meter_machine_names());
        return EXIT_USAGE;
    }
    if (lt_meter_init(sf->machine, sf->l1[0] ? sf->l1 : NULL, sf->l2[0] ? sf->l2 : NULL, &diag) != 0) {
        fprintf(stderr, "%s run: %s\n", prog, diag.msg);
        return EXIT_USAGE;
    }
    return 0;
}

/* Who set each object knob before the recommendation: a flag's name, "the scene file", or NULL. */
typedef struct auto_by {
    const char *numeric, *structure, *leaf;
} auto_by_t;

/* lanetrace info's picks (lt_recommend_mesh, for sf's machine) applied to the knobs nobody set
 * (by); each printed with its reason, or with what set the knob instead, unless silent, and kept
 * as a JSON object in json. hierarchy: the command needs a structure with a hierarchy (render:
 * shadow rays and peels), so a "chunks" pick (and its leaf) is not applied. */
static void auto_apply(lt_scenefile_t *sf, const lt_mesh_t *m, const lt_scene_t *sc,
                       const auto_by_t *by0, int hierarchy, int silent, char *json, size_t len)
{
    lt_rec_t rec;
    auto_by_t by = *by0;
    cJSON *o = cJSON_CreateObject();
    char *txt;
    int i;
    mesh_recommend(m, sc, sf->machine, &rec);
    for (i = 0; i < rec.n; i++)
        if (hierarchy && strcmp(rec.k[i].knob, "structure") == 0 &&
            strcmp(rec.k[i].pick, "chunks") == 0 && by.structure == NULL)
            by.structure = by.leaf = "render (shadow rays and peels need a hierarchy)";
    for (i = 0; i < rec.n; i++) {
        const lt_rec_pick_t *k = &rec.k[i];
        const char *who;
        cJSON *x = cJSON_AddObjectToObject(o, k->knob);
        if (strcmp(k->knob, "numeric") == 0) {
            who = by.numeric;
            if (who == NULL && strcmp(sf->structure, "bvhq") == 0) {
                who = "the structure bvhq (quantised s15.16 nodes)";
                sf->numeric = LT_SF_NUM_Q16;
            }
            if (who == NULL)
                sf->numeric = strcmp(k->pick, "q16") == 0 ? LT_SF_NUM_Q16
                              : strcmp(k->pick, "f32") == 0 ? LT_SF_NUM_F32 : LT_SF_NUM_BOTH;
        } else if (strcmp(k->knob, "structure") == 0) {
            who = by.structure;
            if (who == NULL)
                snprintf(sf->structure, sizeof sf->structure, "%s", k->pick);
        } else if (strcmp(k->knob, "leaf") == 0) {
            who = by.leaf;
            if (who == NULL && strcmp(sf->structure, "bvhq") == 0 &&
                strtoul(k->pick, NULL, 10) > LT_BVHQ_MAX_LEAF)
                who = "the structure bvhq (leaves of at most 15 triangles)";
            if (who == NULL)
                sf->leaf = strcmp(k->pick, "-") == 0 ? 0u : (uint32_t)strtoul(k->pick, NULL, 10);
        } else {
            continue;
        }
        cJSON_AddStringToObject(x, "pick", k->pick);
        cJSON_AddBoolToObject(x, "applied", who == NULL);
        cJSON_AddStringToObject(x, who == NULL ? "reason" : "set_by", who == NULL ? k->reason : who);
        if (!silent && who == NULL)
            printf("auto      %-9s %-6s %s\n", k->knob, k->pick, k->reason);
        else if (!silent)
            printf("auto      %-9s kept   set by %s (the recommendation: %s)\n", k->knob, who,
                   k->pick);
    }
    cJSON_AddStringToObject(o, "machine", rec.machine);
    txt = cJSON_PrintUnformatted(o);
    snprintf(json, len, "%s", txt != NULL ? txt : "");
    cJSON_free(txt);
    cJSON_Delete(o);
}

/* Who set the object knobs: --num / --structure when seen, else the scene file when it has them. */
static auto_by_t auto_by(const lt_scenefile_t *sf, int seen_num, int seen_structure)
{
    const char *file = "the scene file";
    auto_by_t by;
    by.numeric = seen_num ? "--num" : (sf->given & LT_SF_GIVEN_NUMERIC) ? file : NULL;
    by.structure = seen_structure ? "--structure" : (sf->given & LT_SF_GIVEN_STRUCTURE) ? file : NULL;
    by.leaf = (sf->given & LT_SF_GIVEN_LEAF) ? file : NULL;
    return by;
}

/* run: the recommendation for the knobs that neither a flag nor the scene file set; its lines
 * are not summary lines, so -q (and --json, which sets it) keeps them off stdout. */
static void run_auto(run_t *r)
{
    auto_by_t by = auto_by(&r->sf, r->seen_num, r->seen_structure);
    auto_apply(&r->sf, &r->mesh, &r->sc, &by, 0, quiet, r->auto_json, sizeof r->auto_json);
}

/* The mesh, the prepared scene and the camera. Returns 0 or an exit code. */
static int run_load(run_t *r)
{
    lt_scenefile_t *sf = &r->sf;
    const lt_path_info_t *p;
    lt_diag_t diag;
    if (lt_mesh_load(sf->mesh, &r->mesh, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    if (lt_scene_prepare(&r->mesh, &r->sc, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", sf->mesh, diag.msg);
        return EXIT_INPUT;
    }
    if (r->autop)
        run_auto(r);
    if (strcmp(sf->structure, "bvhq") == 0 && sf->numeric == LT_SF_NUM_BOTH) {
        /* both paths (the default): bvhq has s15.16 nodes only, so the float32 pass is left out
           (asked for alone, --num f32, the structure's error says why) */
        sf->numeric = LT_SF_NUM_Q16;
        if (!quiet)
            printf("numeric   q16 only: the structure bvhq has quantised s15.16 nodes\n");
    }
    /* a selected path that cannot represent the scene is dropped while another selected path
       remains (--num both, the default); asked for alone (--num q16), it is refused */
    for (p = lt_paths; p->name != NULL; p++)
        if (run_selects(sf, p) && p->render->scene_check != NULL &&
            p->render->scene_check(&r->sc, sf->mesh, &diag) != 0) {
            if (run_npaths(sf) < 2) {
                fprintf(stderr, "%s\n", diag.msg);
                return EXIT_INPUT;
            }
            sf->numeric = (lt_sf_num_t)((unsigned)sf->numeric & ~(unsigned)p->sf_num);
            r->dropped = p;
            snprintf(r->drop_reason, sizeof r->drop_reason, "%s", diag.msg);
            fprintf(stderr, "%s run: numeric path %s (%s) dropped, running %s: %s\n", prog,
                    p->name, p->format, run_selected_names(sf), diag.msg);
        }
    if (sf->has_camera) {
        if (lt_camera_look(&r->sc, sf->eye, sf->target, sf->up, sf->fov_y_deg, sf->width,
                           sf->height, &r->cam, &diag) != 0) {
            fprintf(stderr, "%s: %s\n", sf->path[0] ? sf->path : sf->mesh, diag.msg);
            return EXIT_INPUT;
        }
    } else {
        lt_camera_default(&r->sc, sf->width, sf->height, &r->cam);
    }
    return 0;
}

/* The CSV output, written under a temporary name row by row. */
static int run_csv_open(run_t *r)
{
    const char *dst;
    if (run_out(r, r->csv, &dst) != 0)
        return -1;
    r->csvf = fopen(dst, "w");
    if (r->csvf == NULL) {
        fprintf(stderr, "%s: cannot create the CSV output (%s)\n", r->csv, strerror(errno));
        r->status = EXIT_INPUT;
        return -1;
    }
    fprintf(r->csvf, "scene,structure,path,machine,width,height,rays,total_cycles,cycles_per_ray,"
                     "mrays_per_s_modelled,lane_utilisation,host_ms,same_triangle_pct,depth_rmse,"
                     "depth_max_err,cycles_build,cycles_setup,cycles_traverse,cycles_intersect,"
                     "cycles_shade,l1_hit_pct,nodes_per_ray,aabb_tests_per_ray,tri_tests_per_ray,"
                     "structure_bytes\n");
    return 0;
}

/* Keep one path's distances and ids for --depth; -1 when out of memory. */
static int run_keep_depth(run_t *r, const lt_path_info_t *p)
{
    size_t i, np = (size_t)r->sf.width * r->sf.height;
    int path = lt_paths_index(p);
    r->zbuf[path] = malloc(np * sizeof(float));
    r->idbuf[path] = malloc(np * sizeof(float));
    if (r->zbuf[path] == NULL || r->idbuf[path] == NULL) {
        fprintf(stderr, "%s: out of memory for the depth output\n", r->depth_out);
        return -1;
    }
    /* misses: distance +inf, id -1 (ids up to 2^24 are exact in float) */
    for (i = 0; i < np; i++) {
        r->zbuf[path][i] = r->fr.id[i] >= 0 ? (float)r->fr.t[i] : (float)INFINITY;
        r->idbuf[path][i] = (float)r->fr.id[i];
    }
    snprintf(r->zname[path], sizeof r->zname[path], "%s.Z", p->name);
    snprintf(r->idname[path], sizeof r->idname[path], "%s.id", p->name);
    return 0;
}

/* --heatmap: the simulated cycles and traversal steps per pixel of one path (PNG and EXR). */
static void run_heatmaps(run_t *r, const lt_path_info_t *p)
{
    const lt_scenefile_t *sf = &r->sf;
    const char *pname = p->name, *heat_out = r->heat_out;
    lt_diag_t diag;
    char hp[1100];
    lt_heatmap_opts_t ho = LT_HEATMAP_OPTS_DEFAULT;
    if (!lt_meter_available()) {
        if (!r->heat_warned)
            fprintf(stderr, "%s run: --heatmap needs the simulator build (build/sim/lanetrace); "
                            "ignored\n", prog);
        r->heat_warned = 1;
        return;
    }
    {
        /* four files per path, each a member of the run's output set */
        static const char *const sfx[4] = {"png", "exr", "steps.png", "steps.exr"};
        int i;
        for (i = 0; i < 4; i++) {
            const char *dst;
            const float *v = i < 2 ? r->fr.cost : r->fr.steps;
            int e;
            snprintf(hp, sizeof hp, "%s.%s.%s", heat_out, pname, sfx[i]);
            if (run_out(r, hp, &dst) != 0)
                return;
            e = i % 2 == 0 ? lt_heatmap_write_png(dst, v, (int32_t)sf->width, (int32_t)sf->height,
                                                  &ho, &diag)
                           : lt_heatmap_write_exr(dst, v, (int32_t)sf->width,
                                                  (int32_t)sf->height,
                                                  i < 2 ? "cycles" : "steps", &diag);
            if (e != 0) {
                fprintf(stderr, "%s\n", diag.msg);
                r->status = EXIT_INPUT;
                return;
            }
        }
    }
    if (!quiet) {
        printf("heatmap   %s.%s.png (simulated cycles per pixel)\n", heat_out, pname);
        printf("heatmap   %s.%s.steps.png (traversal steps per pixel's packet)\n", heat_out,
               pname);
    }
}

/* The run facts merged into the report (cJSON escapes the path) into extra. */
static void run_facts(const run_t *r, const char *pname, double ms, size_t acc_bytes,
                      const lt_accuracy_t *ac, char *extra, size_t extralen)
{
    const lt_scenefile_t *sf = &r->sf;
    cJSON *x = cJSON_CreateObject();
    char *xs;
    cJSON_AddStringToObject(x, "path", pname);
    cJSON_AddStringToObject(x, "structure", sf->structure);
    cJSON_AddStringToObject(x, "isect", sf->isect);
    cJSON_AddStringToObject(x, "scene", sf->mesh);
    cJSON_AddNumberToObject(x, "width", sf->width);
    cJSON_AddNumberToObject(x, "height", sf->height);
    cJSON_AddNumberToObject(x, "host_ms", ms);
    cJSON_AddNumberToObject(x, "host_threads", lt_par_workers(UINT32_MAX, 1));
    cJSON_AddNumberToObject(x, "leaf", sf->leaf);
    if (r->auto_json[0] != '\0')
        cJSON_AddItemToObject(x, "auto", cJSON_Parse(r->auto_json));
    cJSON_AddNumberToObject(x, "frame_hash", lt_frame_hash(&r->fr));
    cJSON_AddNumberToObject(x, "structure_bytes", (double)acc_bytes);
    if (r->dropped != NULL) {
        cJSON *y = cJSON_AddObjectToObject(x, "numeric_pick");
        cJSON_AddStringToObject(y, "path", pname);
        cJSON_AddStringToObject(y, "dropped", r->dropped->name);
        cJSON_AddStringToObject(y, "reason", r->drop_reason);
    }
    if (r->do_ref) {
        cJSON *y = cJSON_AddObjectToObject(x, "accuracy");
        cJSON_AddNumberToObject(y, "same_triangle_pct", 100.0 * ac->same_id / ac->pixels);
        cJSON_AddNumberToObject(y, "depth_rmse", ac->rmse);
        cJSON_AddNumberToObject(y, "depth_max_err", ac->max_err);
        cJSON_AddNumberToObject(y, "scene_radius", r->sc.radius);
    }
    xs = cJSON_PrintUnformatted(x);
    snprintf(extra, extralen, "%s", xs != NULL ? xs : "{}");
    free(xs);
    cJSON_Delete(x);
}

/* --report: PATH, or PATH with .<path> before its extension when both paths run
 * (report.json -> report.q16.json, report.f32.json). */
static void run_write_report(run_t *r, const char *pname, const char *text)
{
    lt_diag_t diag;
    const char *dst;
    char p[4096];
    int both = run_npaths(&r->sf) > 1;
    if (both ? lt_path_tagged(p, sizeof p, r->report, pname) != 0
             : snprintf(p, sizeof p, "%s", r->report) >= (int)sizeof p) {
        fprintf(stderr, "%s run: --report %.60s...: the path is longer than %zu bytes\n", prog,
                r->report, sizeof p - 1);
        r->status = EXIT_INPUT;
        return;
    }
    if (run_out(r, p, &dst) != 0)
        return;
    if (write_atomic(dst, text, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        r->status = EXIT_INPUT;
    } else if (!quiet) {
        printf("report    %s\n", p);
    }
}

/* The report of one path: the cycle report (sim build: text, and JSON with the run facts) or the
 * run facts alone (native build). Returns the JSON for --json, or NULL. */
static cJSON *run_report(run_t *r, const char *pname, uint64_t rays, const char *extra)
{
    const lt_scenefile_t *sf = &r->sf;
    cJSON *jr;
    if (lt_meter_available()) {
        char title[512], *js;
        snprintf(title, sizeof title, "%s %ux%u %s, %s, %d frame(s)", sf->mesh, sf->width,
                 sf->height, pname, sf->structure, r->repeat);
        if (!quiet) {
            lt_meter_report_text(stdout, title, rays);
        } else if (!r->json) {
            lt_meter_totals_t tt;
            lt_meter_totals(&tt);
            printf("cycles    %-4s %llu total, %.1f cycles/ray on %s\n", pname,
                   (unsigned long long)tt.total_cycles, (double)tt.total_cycles / (double)rays,
                   sf->machine);
        }
        js = lt_meter_report_json(title, rays, extra);
        jr = js != NULL ? cJSON_Parse(js) : NULL;
        if (r->report != NULL && js != NULL)
            run_write_report(r, pname, js);
        free(js);
    } else {
        /* native build: the report holds the run facts and accuracy, no cycle counts */
        jr = cJSON_Parse(extra);
        if (r->report != NULL)
            run_write_report(r, pname, extra);
    }
    return jr;
}

/* One CSV row of a path. */
static void run_csv_row(run_t *r, const char *pname, uint64_t rays, double ms,
                        const lt_accuracy_t *ac, size_t acc_bytes, const cJSON *jr)
{
    const lt_scenefile_t *sf = &r->sf;
    if (lt_meter_available()) {
        lt_meter_machine_t mi;
        lt_meter_totals_t tt;
        double util = 0.0;
        (void)lt_meter_machine_info(sf->machine, &mi);
        lt_meter_totals(&tt);
        if (jr != NULL && cJSON_GetObjectItem(jr, "lane_utilisation") != NULL)
            util = cJSON_GetObjectItem(jr, "lane_utilisation")->valuedouble;
        fprintf(r->csvf,
                "%s,%s,%s,%s,%u,%u,%llu,%llu,%.3f,%.4f,%.4f,%.3f,%.4f,%.6g,%.6g,%llu,%llu,"
                "%llu,%llu,%llu,%.3f,%.3f,%.3f,%.3f,%zu\n",
                sf->mesh, sf->structure, pname, sf->machine, sf->width, sf->height,
                (unsigned long long)rays, (unsigned long long)tt.total_cycles,
                (double)tt.total_cycles / (double)rays,
                (double)rays / ((double)tt.total_cycles / (mi.clock_mhz * 1e6)) / 1e6,
                util, ms, r->do_ref ? 100.0 * ac->same_id / ac->pixels : 0.0, ac->rmse,
                ac->max_err,
                (unsigned long long)tt.cycles[LT_PH_BUILD],
                (unsigned long long)tt.cycles[LT_PH_SETUP],
                (unsigned long long)tt.cycles[LT_PH_TRAVERSE],
                (unsigned long long)tt.cycles[LT_PH_INTERSECT],
                (unsigned long long)tt.cycles[LT_PH_SHADE],
                tt.l1_acc ? 100.0 * (double)tt.l1_hit / (double)tt.l1_acc : 0.0,
                (double)tt.events[LT_EV_NODES] / (double)rays,
                (double)tt.events[LT_EV_AABB_RAYS] / (double)rays,
                (double)tt.events[LT_EV_TRI_RAYS] / (double)rays, acc_bytes);
    } else {
        fprintf(r->csvf, "%s,%s,%s,native,%u,%u,%llu,,,,,%.3f,%.4f,%.6g,%.6g,,,,,,,,,,%zu\n",
                sf->mesh, sf->structure, pname, sf->width, sf->height, (unsigned long long)rays,
                ms, r->do_ref ? 100.0 * ac->same_id / ac->pixels : 0.0, ac->rmse, ac->max_err,
                acc_bytes);
    }
}

/* One numeric path: build, trace (--repeat times), depth and heatmaps, accuracy, the report, the
 * CSV row. Returns -1 when the other paths should not run (r->status says why). */
/* The intersector of path p's pass: the scene's, except that with both paths (--num both) the
 * float32 pass takes wt for wt32 (an s15.16 test; said once in the report's scene line). */
static const char *run_isect(const lt_scenefile_t *sf, const lt_path_info_t *p)
{
    if (strcmp(sf->isect, "wt32") == 0 && p->bvh_num != LT_BVH_NUM_Q16 &&
        sf->numeric == LT_SF_NUM_BOTH)
        return "wt";
    return sf->isect;
}

static int run_path(run_t *r, const lt_path_info_t *p)
{
    const lt_scenefile_t *sf = &r->sf;
    const char *pname = p->name;
    lt_diag_t diag;
    lt_accel_t *acc;
    lt_accuracy_t ac;
    double t0, ms;
    int rep;
    cJSON *jr;
    char extra[4096];
    size_t acc_bytes;
    uint64_t rays = (uint64_t)sf->width * sf->height * (uint64_t)r->repeat;
    lt_meter_reset();
    {
        /* the scene file's "leaf", for the structures that have a leaf size */
        lt_accel_params_t prm = {structure_has_leaf(sf->structure) ? sf->leaf : 0};
        acc = lt_accel_build_ex(&r->sc, sf->structure, p, &prm, &diag);
    }
    if (acc == NULL) {
        fprintf(stderr, "%s: %s\n", sf->path[0] ? sf->path : prog, diag.msg);
        r->status = EXIT_INPUT;
        return -1;
    }
    {
        const char *is = run_isect(sf, p);
        uint32_t g = 0;
        if (lt_accel_set_isect_name(acc, is, &g, &diag) != 0) {
            fprintf(stderr, "%s: %s\n", sf->path[0] ? sf->path : prog, diag.msg);
            lt_accel_free(acc);
            r->status = EXIT_USAGE;
            return -1;
        }
        if (!quiet && strcmp(is, "wt32") == 0)
            printf("isect     wt32: s15.16 watertight test on a grid of 2^%u raw = %.3g s15.16 "
                   "units (%.3g file units; lt_wt32_shift_q16: 99%% of the triangles' edges fit "
                   "2^13 steps)\n",
                   g, ldexp(1.0, (int)g - 16), ldexp(1.0, (int)g - 16) / r->sc.scale);
        else if (!quiet && strcmp(is, sf->isect) != 0)
            printf("isect     %s: wt (wt32 is an s15.16 test: the float32 pass takes wt)\n", p->name);
    }
    if (r->rays == 2 && lt_accel_set_walk(acc, 1, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", sf->path[0] ? sf->path : prog, diag.msg);
        lt_accel_free(acc);
        r->status = EXIT_INPUT;
        return -1;
    }
    progress_begin(pname);
    t0 = lt_now_s();
    for (rep = 0; rep < r->repeat; rep++) {
        if (r->rays != 1) {
            lt_render_primary(&r->sc, acc, &r->cam, &r->fr, progress);
        } else if (lt_render_primary1(&r->sc, acc, &r->cam, &r->fr, &diag) != 0) {
            progress_end();
            fprintf(stderr, "%s: %s\n", sf->path[0] ? sf->path : prog, diag.msg);
            lt_accel_free(acc);
            r->status = EXIT_INPUT;
            return -1;
        }
    }
    ms = 1e3 * (lt_now_s() - t0);
    progress_end();
    acc_bytes = lt_accel_bytes(acc);
    lt_accel_free(acc);
    if (r->depth_out != NULL && run_keep_depth(r, p) != 0) {
        r->status = EXIT_INPUT;
        return -1;
    }
    if (r->heat_out != NULL)
        run_heatmaps(r, p);
    memset(&ac, 0, sizeof ac);
    if (r->do_ref)
        lt_frame_compare(&r->fr, &r->ref, 1e-4 * r->sc.radius, &ac);
    if (!r->json) {
        char rt[LT_RATE_TEXT];
        unsigned nth = lt_par_workers(UINT32_MAX, 1);
        printf("time      %-4s %.3f ms for %d frame(s) of %u %s (%s, %u thread%s, %s host)\n",
               pname, ms, r->repeat, sf->width * sf->height,
               r->rays == 1 ? "single rays" : r->rays == 2 ? "rays (wide-tree packets)" : "rays",
               lt_meter_available() ? "counted" : "native", nth, nth == 1 ? "" : "s",
               lt_rate_text(ms > 0.0 ? (double)rays / (ms * 1e-3) : -1.0, rt));
        printf("result    %-4s hash 0x%08x\n", pname, lt_frame_hash(&r->fr));
        if (r->do_ref)
            printf("accuracy  %-4s vs double: same triangle %.3f%% (%u of %u pixels, %u differ), "
                   "depth RMSE %.3g, max %.3g (scene radius %.1f), %.2f%% of common hits within "
                   "1e-4 radius (%u of %u)\n",
                   pname, 100.0 * ac.same_id / ac.pixels, ac.same_id, ac.pixels,
                   ac.pixels - ac.same_id, ac.rmse, ac.max_err, r->sc.radius,
                   ac.both_hit ? 100.0 * ac.within_tol / ac.both_hit : 100.0, ac.within_tol,
                   ac.both_hit);
    }
    run_facts(r, pname, ms, acc_bytes, &ac, extra, sizeof extra);
    jr = run_report(r, pname, rays, extra);
    if (r->csvf != NULL)
        run_csv_row(r, pname, rays, ms, &ac, acc_bytes, jr);
    if (jr != NULL)
        cJSON_AddItemToArray(r->jout, jr);
    return 0;
}

/* --depth: every traced path's distance and id channels in one EXR. */
static void run_write_depth(run_t *r)
{
    lt_diag_t diag;
    const char *dst;
    lt_exr_channel_t ch[2 * LT_PATHS_MAX];
    lt_exr_image_t im;
    int nch = 0, path;
    for (path = 0; path < LT_PATHS_MAX; path++) {
        if (r->zbuf[path] == NULL)
            continue;
        ch[nch].name = r->zname[path];
        ch[nch].type = LT_EXR_FLOAT;
        ch[nch++].data = r->zbuf[path];
        ch[nch].name = r->idname[path];
        ch[nch].type = LT_EXR_FLOAT;
        ch[nch++].data = r->idbuf[path];
    }
    memset(&im, 0, sizeof im);
    im.width = (int32_t)r->sf.width;
    im.height = (int32_t)r->sf.height;
    im.nchannels = nch;
    im.channels = ch;
    im.compression = LT_EXR_COMP_ZIP;
    if (run_out(r, r->depth_out, &dst) != 0)
        return;
    if (lt_exr_write(dst, &im, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        r->status = EXIT_INPUT;
    } else if (!quiet) {
        printf("depth     %s (%d channels)\n", r->depth_out, nch);
    }
}

/* The CSV finished (the output set renames it into place). */
static void run_csv_close(run_t *r)
{
    if (fclose(r->csvf) != 0) {
        fprintf(stderr, "%s: cannot write the CSV output: %s\n", r->csv, strerror(errno));
        r->status = EXIT_INPUT;
    } else if (!quiet) {
        printf("csv       %s\n", r->csv);
    }
    r->csvf = NULL;
}

/* The traces: the scene line, the reference, each selected path, then the outputs of all. */
static int run_trace(run_t *r)
{
    const lt_scenefile_t *sf = &r->sf;
    const lt_path_info_t *p;
    lt_diag_t diag;
    if (!quiet)
        printf("scene     %s: %u triangles, scale %g (file units -> s15.16 units), radius %.1f, "
               "%ux%u pixels, %u packets, structure %s, isect %s\n",
               sf->mesh, r->sc.ntris, r->sc.scale, r->sc.radius, sf->width, sf->height,
               ((sf->width + 3) / 4) * ((sf->height + 3) / 4), sf->structure, sf->isect);
    if (lt_frame_alloc(&r->ref, sf->width, sf->height, &diag) != 0 ||
        lt_frame_alloc(&r->fr, sf->width, sf->height, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    r->fr.heat = r->heat_out != NULL; /* the per-pixel cycles and steps only for --heatmap */
    if (r->do_ref) {
        progress_begin("reference");
        lt_render_reference(&r->sc, &r->cam, &r->ref, progress);
        progress_end();
    }
    if (r->csv != NULL && run_csv_open(r) != 0) {
        lt_outset_abort(r->set);
        return EXIT_INPUT;
    }
    for (p = lt_paths; p->name != NULL; p++)
        if (run_selects(sf, p) && run_path(r, p) != 0)
            break;
    if (r->depth_out != NULL && r->status == 0)
        run_write_depth(r);
    if (r->csvf != NULL)
        run_csv_close(r);
    /* all outputs or none: the new files replace the old ones only when every one was written */
    if (r->status == 0) {
        if (lt_outset_commit(r->set, &diag) != 0) {
            fprintf(stderr, "%s run: %s\n", prog, diag.msg);
            r->status = EXIT_INPUT;
        }
    } else if (r->set->n > 0) {
        fprintf(stderr, "%s run: none of the outputs written (%d prepared were removed; previous "
                        "files are unchanged)\n", prog, r->set->n);
        lt_outset_abort(r->set);
    }
    if (r->json) {
        char *s = cJSON_Print(r->jout);
        if (s != NULL)
            puts(s);
        free(s);
    }
    return r->status;
}

static int cmd_run(int argc, char **argv)
{
    run_t r;
    int rc, path;
    run_defaults(&r);
    rc = run_parse(&r, argc, argv);
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    if (r.native && lt_meter_available())
        return exec_native(argc, argv);
    r.jout = cJSON_CreateArray();
    r.set = calloc(1, sizeof *r.set);
    if (r.set == NULL) {
        fprintf(stderr, "%s run: out of memory\n", prog);
        cJSON_Delete(r.jout);
        return EXIT_INPUT;
    }
    rc = run_settle(&r);
    if (rc == 0)
        rc = run_load(&r);
    if (rc == 0)
        rc = run_trace(&r);
    for (path = 0; path < LT_PATHS_MAX; path++) {
        free(r.zbuf[path]);
        free(r.idbuf[path]);
    }
    cJSON_Delete(r.jout);
    free(r.set);
    lt_frame_free(&r.fr);
    lt_frame_free(&r.ref);
    lt_scene_free(&r.sc);
    lt_mesh_free(&r.mesh);
    lt_meter_shutdown();
    return rc;
}

/* ---- info ----------------------------------------------------------------------------------- */

/* j as one line on stdout, then freed */
static void print_json_line(cJSON *j)
{
    char *txt = cJSON_PrintUnformatted(j);
    if (txt != NULL)
        printf("%s\n", txt);
    cJSON_free(txt);
    cJSON_Delete(j);
}

/* EXR: every part's header (name, view, storage, compression, windows, channels), the views and
 * the depth statistics of one view or part (--view, --part; default: the file's default view). */
#define INFO_EXR_PARTS 64 /* parts listed (the rest are counted) */
static const char *const exr_storage_name[] = {"scanline", "tiled", "deep scanline", "deep tiled"};
static const char *const exr_type_name[] = {"?", "HALF", "FLOAT", "UINT"};

/* Depth statistics over the pixels with a positive finite depth. */
typedef struct exr_stats {
    size_t n, holes;
    double mn, mx, sum;
} exr_stats_t;

static void exr_depth_stats(const lt_exr_depth_t *d, exr_stats_t *s)
{
    size_t k;
    memset(s, 0, sizeof *s);
    s->mn = INFINITY;
    s->mx = -INFINITY;
    for (k = 0; k < (size_t)d->width * (size_t)d->height; k++) {
        double z = d->z[k];
        if (!isfinite(z) || z <= 0.0) {
            s->holes++;
            continue;
        }
        s->n++;
        s->sum += z;
        s->mn = z < s->mn ? z : s->mn;
        s->mx = z > s->mx ? z : s->mx;
    }
    if (s->n == 0)
        s->mn = s->mx = 0.0;
}

/* One part as a JSON object. */
static cJSON *exr_part_json(const lt_exr_probe_t *pr)
{
    cJSON *o = cJSON_CreateObject(), *ch = cJSON_CreateArray();
    const int dw[4] = {pr->data_window.x0, pr->data_window.y0, pr->data_window.x1,
                       pr->data_window.y1},
              vw[4] = {pr->display_window.x0, pr->display_window.y0, pr->display_window.x1,
                       pr->display_window.y1};
    int c;
    cJSON_AddNumberToObject(o, "index", pr->part);
    cJSON_AddStringToObject(o, "name", pr->part_name);
    if (pr->view[0] != '\0')
        cJSON_AddStringToObject(o, "view", pr->view);
    else
        cJSON_AddNullToObject(o, "view");
    cJSON_AddStringToObject(o, "storage", exr_storage_name[pr->storage & 3]);
    cJSON_AddStringToObject(o, "compression", lt_exr_compression_name(pr->compression));
    cJSON_AddItemToObject(o, "data_window", cJSON_CreateIntArray(dw, 4));
    cJSON_AddItemToObject(o, "display_window", cJSON_CreateIntArray(vw, 4));
    cJSON_AddNumberToObject(o, "nchannels", pr->nchannels);
    for (c = 0; c < pr->nchannels && c < LT_EXR_PROBE_CHANNELS; c++) {
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "name", pr->name[c]);
        cJSON_AddStringToObject(e, "type", exr_type_name[pr->type[c] & 3]);
        cJSON_AddItemToArray(ch, e);
    }
    cJSON_AddItemToObject(o, "channels", ch);
    return o;
}

/* One part as text: "part N    name ..., view ..., storage, compression, windows" and its
 * channels. */
static void exr_part_text(const lt_exr_probe_t *pr)
{
    int c;
    char t[256];
    printf("part %-5d", pr->part);
    if (pr->part_name[0] != '\0')
        printf("name '%s', ", lt_shown(pr->part_name, t, sizeof t));
    if (pr->view[0] != '\0')
        printf("view %s%s, ", lt_shown(pr->view, t, sizeof t),
               strcmp(pr->view, pr->default_view) == 0 ? " (default)" : "");
    printf("%s, %s, data window (%d,%d)-(%d,%d), display window (%d,%d)-(%d,%d)\n",
           exr_storage_name[pr->storage & 3], lt_exr_compression_name(pr->compression),
           pr->data_window.x0, pr->data_window.y0, pr->data_window.x1, pr->data_window.y1,
           pr->display_window.x0, pr->display_window.y0, pr->display_window.x1,
           pr->display_window.y1);
    printf("channels  %d:", pr->nchannels);
    for (c = 0; c < pr->nchannels && c < LT_EXR_PROBE_CHANNELS; c++)
        printf(" %s(%s)", lt_shown(pr->name[c], t, sizeof t), exr_type_name[pr->type[c] & 3]);
    printf("%s\n", pr->nchannels > LT_EXR_PROBE_CHANNELS ? " ..." : "");
}

/* The views line: "views right left (default right)" or "no views". */
static void exr_views_text(const lt_exr_probe_t *pr, char *buf, size_t cap)
{
    size_t n = 0;
    int v;
    char t[256];
    if (pr->nviews == 0) {
        snprintf(buf, cap, "no views");
        return;
    }
    n += (size_t)snprintf(buf, cap, "views");
    for (v = 0; v < pr->nviews && v < LT_EXR_PROBE_VIEWS && n < cap; v++)
        n += (size_t)snprintf(buf + n, cap - n, " %s", lt_shown(pr->views[v], t, sizeof t));
    if (pr->nviews > LT_EXR_PROBE_VIEWS && n < cap)
        n += (size_t)snprintf(buf + n, cap - n, " ... (%d)", pr->nviews);
    if (n < cap)
        snprintf(buf + n, cap - n, " (default %s)", lt_shown(pr->default_view, t, sizeof t));
}

/* Probe part p into pr (part 0 is there already). 0, or -1 after a message on stderr. */
static int exr_probe_next(const char *path, int p, lt_exr_probe_t *pr)
{
    lt_diag_t diag;
    if (p == 0 || lt_exr_probe_part(path, p, pr, &diag) == 0)
        return 0;
    fprintf(stderr, "%s\n", diag.msg);
    return -1;
}

/* info --json: the file, its views, part 0's header at the top level (as before parts were
 * listed), "part_list" with every part, "depth" (d NULL: "depth_error", why none),
 * "limit_error" when reproject and fwblob refuse the depth image (limit). */
static int info_exr_json(const char *path, const lt_sniff_t *sn, lt_exr_probe_t *pr,
                         const lt_exr_depth_t *d, const exr_stats_t *s, const char *why,
                         const char *limit, const lt_rec_depth_facts_t *df, const lt_rec_t *rec)
{
    cJSON *j = cJSON_CreateObject(), *a;
    const int dw[4] = {pr->data_window.x0, pr->data_window.y0, pr->data_window.x1,
                       pr->data_window.y1},
              vw[4] = {pr->display_window.x0, pr->display_window.y0, pr->display_window.x1,
                       pr->display_window.y1};
    char *txt;
    int p, rc = 0;
    cJSON_AddStringToObject(j, "file", path);
    cJSON_AddStringToObject(j, "detected", sn->what);
    cJSON_AddBoolToObject(j, "name_agrees", sn->name_agrees);
    cJSON_AddNumberToObject(j, "parts", pr->parts);
    a = cJSON_AddArrayToObject(j, "views");
    for (p = 0; p < pr->nviews && p < LT_EXR_PROBE_VIEWS; p++)
        cJSON_AddItemToArray(a, cJSON_CreateString(pr->views[p]));
    if (pr->default_view[0] != '\0')
        cJSON_AddStringToObject(j, "default_view", pr->default_view);
    else
        cJSON_AddNullToObject(j, "default_view");
    cJSON_AddStringToObject(j, "storage", exr_storage_name[pr->storage & 3]);
    cJSON_AddItemToObject(j, "data_window", cJSON_CreateIntArray(dw, 4));
    cJSON_AddItemToObject(j, "display_window", cJSON_CreateIntArray(vw, 4));
    cJSON_AddNumberToObject(j, "channels", pr->nchannels);
    a = cJSON_AddArrayToObject(j, "part_list");
    for (p = 0; p < pr->parts && p < INFO_EXR_PARTS && rc == 0; p++)
        if ((rc = exr_probe_next(path, p, pr)) == 0)
            cJSON_AddItemToArray(a, exr_part_json(pr));
    if (d != NULL) {
        a = cJSON_AddObjectToObject(j, "depth");
        cJSON_AddNumberToObject(a, "part", d->part);
        if (d->view[0] != '\0')
            cJSON_AddStringToObject(a, "view", d->view);
        else
            cJSON_AddNullToObject(a, "view");
        cJSON_AddStringToObject(a, "channel", d->channel);
        cJSON_AddBoolToObject(a, "deep", d->deep);
        cJSON_AddNumberToObject(a, "pixels", (double)s->n);
        cJSON_AddNumberToObject(a, "holes", (double)s->holes);
        cJSON_AddNumberToObject(a, "min", s->mn);
        cJSON_AddNumberToObject(a, "max", s->mx);
        cJSON_AddNumberToObject(a, "mean", s->n ? s->sum / (double)s->n : 0.0);
        cJSON_AddNumberToObject(a, "jump_share", df->pairs ? (double)df->jumps / (double)df->pairs : 0.0);
        cJSON_AddNumberToObject(a, "planar_share",
                                df->inner ? (double)df->planar / (double)df->inner : 0.0);
        if (limit != NULL)
            cJSON_AddStringToObject(j, "limit_error", limit);
        a = cJSON_AddObjectToObject(j, "recommend");
        cJSON_AddStringToObject(a, "machine", rec->machine);
        cJSON_AddNumberToObject(a, "depth_range_log2", rec->range_log2);
        for (p = 0; p < rec->n; p++) {
            cJSON *k = cJSON_AddObjectToObject(a, rec->k[p].knob);
            cJSON_AddStringToObject(k, "pick", rec->k[p].pick);
            cJSON_AddStringToObject(k, "reason", rec->k[p].reason);
        }
    } else {
        cJSON_AddStringToObject(j, "depth_error", why);
    }
    txt = cJSON_PrintUnformatted(j);
    if (txt != NULL && rc == 0)
        printf("%s\n", txt);
    cJSON_free(txt);
    cJSON_Delete(j);
    return rc == 0 ? 0 : EXIT_INPUT;
}

/* info: the file and its views, every part, the depth statistics (d NULL: why none). */
static int info_exr_text(const char *path, const lt_sniff_t *sn, lt_exr_probe_t *pr,
                         const lt_exr_depth_t *d, const exr_stats_t *s, const char *why,
                         const char *limit, const lt_rec_depth_facts_t *df, const lt_rec_t *rec)
{
    char views[1024], tv[256], tc[256];
    int p;
    exr_views_text(pr, views, sizeof views);
    printf("detected  %s by its content%s\n", sn->what,
           sn->name_agrees ? "" : " (its name says otherwise)");
    printf("%s: OpenEXR, %d part%s, %s\n", path, pr->parts, pr->parts == 1 ? "" : "s", views);
    for (p = 0; p < pr->parts && p < INFO_EXR_PARTS; p++) {
        if (exr_probe_next(path, p, pr) != 0)
            return EXIT_INPUT;
        exr_part_text(pr);
    }
    if (pr->parts > INFO_EXR_PARTS)
        printf("...       %d more parts not listed\n", pr->parts - INFO_EXR_PARTS);
    if (d != NULL)
        printf("depth     part %d%s%s, channel %s%s: %zu pixels with depth, %zu holes (0, "
               "negative, NaN or inf), min %g max %g mean %g\n",
               d->part, d->view[0] != '\0' ? ", view " : "", lt_shown(d->view, tv, sizeof tv),
               lt_shown(d->channel, tc, sizeof tc),
               d->deep ? " (deep: front-most sample)" : "", s->n, s->holes, s->mn, s->mx,
               s->n ? s->sum / (double)s->n : 0.0);
    if (d != NULL) {
        printf("shape     jumps %.2f%% of neighbour pairs (depths > %g%% apart), planar %.2f%% of "
               "inner pixels (second differences of 1/z <= %g of it)\n",
               df->pairs ? 100.0 * (double)df->jumps / (double)df->pairs : 0.0,
               100.0 * LT_REC_JUMP_REL,
               df->inner ? 100.0 * (double)df->planar / (double)df->inner : 0.0, LT_REC_PLANAR_REL);
        if (limit != NULL)
            printf("limits    %s\n", limit);
        printf("recommend for %s, reproject (no sweep; lanetrace tune measures it)\n", rec->machine);
        for (p = 0; p < rec->n; p++)
            printf("  %-10s %-7s %s\n", rec->k[p].knob, rec->k[p].pick, rec->k[p].reason);
    } else
        printf("depth     none readable: %s\n", why);
    return 0;
}

static int info_exr(const char *path, const lt_sniff_t *sn, int json, int part, const char *view,
                    const char *machine)
{
    lt_rec_depth_facts_t df;
    lt_rec_t rec;
    lt_exr_probe_t *pr = malloc(sizeof *pr);
    lt_exr_depth_t d;
    lt_exr_read_opts_t ro = LT_EXR_READ_OPTS_DEFAULT;
    lt_diag_t diag, ldiag;
    exr_stats_t s;
    char lim[LT_DIAG_MAX + 80];
    const char *limit = NULL; /* why reproject and fwblob refuse the depth image, or NULL */
    int have_depth, rc;
    if (pr == NULL || lt_exr_probe(path, pr, &diag) != 0) {
        fprintf(stderr, "%s\n", pr == NULL ? "lanetrace info: out of memory" : diag.msg);
        free(pr);
        return EXIT_INPUT;
    }
    ro.deep = LT_EXR_DEEP_FRONT;
    ro.part = part;
    ro.view = view;
    have_depth = lt_exr_read_depth(path, NULL, &ro, &d, &diag) == 0;
    if (!have_depth && (part >= 0 || view != NULL)) {
        fprintf(stderr, "%s\n", diag.msg); /* no such view or part, or no depth there */
        free(pr);
        return EXIT_INPUT;
    }
    memset(&df, 0, sizeof df);
    memset(&rec, 0, sizeof rec);
    if (have_depth) {
        exr_depth_stats(&d, &s);
        lt_rec_depth_scan(d.z, (uint32_t)d.width, (uint32_t)d.height, &df);
        df.machine = machine;
        lt_recommend_depth(&df, &rec);
        /* the header is described either way; the commands that take it are told here */
        if (lt_exr_camera_check(path, &d.data_window, &d.display_window, &ldiag) != 0) {
            snprintf(lim, sizeof lim, "%s; reproject (without --src-cam or a scene camera) and "
                     "fwblob refuse it", ldiag.msg);
            limit = lim;
        }
    }
    if (json)
        rc = info_exr_json(path, sn, pr, have_depth ? &d : NULL, &s, diag.msg, limit, &df, &rec);
    else
        rc = info_exr_text(path, sn, pr, have_depth ? &d : NULL, &s, diag.msg, limit, &df, &rec);
    if (have_depth)
        lt_exr_depth_free(&d);
    free(pr);
    return rc;
}

/* The recommendation block of `info MESH` (lt_recommend_mesh): text lines, or the "recommend"
 * object of j. */
static void info_recommend(const lt_mesh_t *m, const lt_scene_t *sc, const char *machine,
                           cJSON *j)
{
    lt_rec_t r;
    int i;
    mesh_recommend(m, sc, machine, &r);
    if (j != NULL) {
        cJSON *o = cJSON_AddObjectToObject(j, "recommend");
        cJSON_AddStringToObject(o, "machine", r.machine);
        cJSON_AddBoolToObject(o, "q16_representable", r.q16_ok);
        cJSON_AddNumberToObject(o, "dynamic_range_log2", r.range_log2);
        cJSON_AddNumberToObject(o, "shortest_edge_q16_steps", r.edge_steps);
        for (i = 0; i < r.n; i++) {
            cJSON *k = cJSON_AddObjectToObject(o, r.k[i].knob);
            cJSON_AddStringToObject(k, "pick", r.k[i].pick);
            cJSON_AddStringToObject(k, "reason", r.k[i].reason);
        }
        return;
    }
    printf("recommend for %s (no sweep; lanetrace tune measures it)\n", r.machine);
    for (i = 0; i < r.n; i++)
        printf("  %-10s %-7s %s\n", r.k[i].knob, r.k[i].pick, r.k[i].reason);
}

static int cmd_info(int argc, char **argv)
{
    lt_mesh_t m;
    lt_scene_t sc;
    char who[64];
    lt_diag_t diag;
    lt_sniff_t sn;
    uint32_t i, zero = 0;
    int json = 0, rc, part = -1;
    const char *path = NULL, *view = NULL, *machine = "lrb16";
    char machine_help[256];
    const lt_opt_t opts[] = {
        LT_OPT_FLAG_("--json", &json, "one JSON object on stdout"),
        LT_OPT_STR("--machine", "NAME", &machine, machine_help),
        LT_OPT_STR("--view", "NAME", &view,
                   "EXR: the depth statistics of view NAME (default: the file's\n"
                   "default view, multiView's first)"),
        LT_OPT_INT("--part", "N", &part, 0, 1e9,
                   "EXR: the depth statistics of part N (0 = the first)"),
        LT_OPT_END_};
    lt_opt_cmd_t cmd = {who, "FILE [--json] [--view NAME] [--part N]",
                        "Describe a mesh (triangles, zero-area triangles, bounds, the fixed-point "
                        "scale lanetrace\npicks) or an EXR file (every part: name, view, storage, "
                        "windows, channels; the\nviews; depth statistics of one view or part).\n",
                        NULL, opts, &path, 1, NULL};
    snprintf(who, sizeof who, "%s info", prog);
    snprintf(machine_help, sizeof machine_help,
             "the machine model the recommendation is for: %s (default lrb16)",
             lt_meter_machine_names());
    rc = lt_opt_parse(&cmd, argc, argv, 2);
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    if (!lt_meter_machine_known(machine)) {
        fprintf(stderr, "%s info: --machine '%s': unknown machine (known: %s)\n", prog, machine,
                lt_meter_machine_names());
        return EXIT_USAGE;
    }
    if (path == NULL) {
        fprintf(stderr, "%s info: a FILE is required\n", prog);
        return EXIT_USAGE;
    }
    if (lt_sniff_file(path, &sn, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    if (sn.kind == LT_SNIFF_EXR)
        return info_exr(path, &sn, json, part, view, machine);
    if (part >= 0 || view != NULL) {
        fprintf(stderr, "%s info: %s: --view and --part select in an EXR file, this is %s\n", prog,
                path, sn.what);
        return EXIT_USAGE;
    }
    if (lt_mesh_load(path, &m, &diag) != 0) {
        fprintf(stderr, "%s (detected by content: %s)\n", diag.msg, sn.what);
        return EXIT_INPUT;
    }
    for (i = 0; i < m.ntris; i++) {
        const double *v = &m.v[i * 9];
        double e1[3], e2[3], c[3];
        int k;
        for (k = 0; k < 3; k++) {
            e1[k] = v[3 + k] - v[k];
            e2[k] = v[6 + k] - v[k];
        }
        c[0] = e1[1] * e2[2] - e1[2] * e2[1];
        c[1] = e1[2] * e2[0] - e1[0] * e2[2];
        c[2] = e1[0] * e2[1] - e1[1] * e2[0];
        zero += c[0] == 0.0 && c[1] == 0.0 && c[2] == 0.0;
    }
    if (lt_scene_prepare(&m, &sc, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", path, diag.msg);
        lt_mesh_free(&m);
        return EXIT_INPUT;
    }
    if (json) {
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "file", path);
        cJSON_AddStringToObject(j, "detected", sn.what);
        cJSON_AddBoolToObject(j, "name_agrees", sn.name_agrees);
        cJSON_AddNumberToObject(j, "triangles", m.ntris);
        cJSON_AddNumberToObject(j, "zero_area", zero);
        cJSON_AddItemToObject(j, "lo", cJSON_CreateDoubleArray(m.lo, 3));
        cJSON_AddItemToObject(j, "hi", cJSON_CreateDoubleArray(m.hi, 3));
        cJSON_AddNumberToObject(j, "scale", sc.scale);
        cJSON_AddNumberToObject(j, "radius_scaled", sc.radius);
        cJSON_AddNumberToObject(j, "collapsed_q16", sc.collapsed_q16);
        cJSON_AddNumberToObject(j, "nonzero", sc.nonzero);
        cJSON_AddBoolToObject(j, "q16_representable", lt_scene_check_q16(&sc, path, &diag) == 0);
        info_recommend(&m, &sc, machine, j);
        print_json_line(j);
    } else {
        printf("detected  %s by its content%s\n", sn.what,
               sn.name_agrees ? "" : " (its name says otherwise)");
        printf("%s: mesh, %u triangles (%u zero-area), bounds [%g %g %g] .. [%g %g %g]\n"
               "fixed point: scale %g (a power of two), scene radius %.2f units of s15.16, "
               "resolution %.3g file units\n"
               "s15.16: %u of %u non-degenerate triangles collapse to zero area (limit %.1f%%: %s), "
               "shortest edge %.3g units\n",
               path, m.ntris, zero, m.lo[0], m.lo[1], m.lo[2], m.hi[0], m.hi[1], m.hi[2], sc.scale,
               sc.radius, lt_path_to_double(lt_paths_find("q16", LT_PATHS_OBJECT), 1) / sc.scale,
               sc.collapsed_q16, sc.nonzero,
               LT_SCENE_MAX_COLLAPSED_PPM / 1e4,
               lt_scene_check_q16(&sc, path, &diag) == 0 ? "representable"
                                                                 : "NOT representable, float32 only",
               sc.min_edge);
        info_recommend(&m, &sc, machine, NULL);
    }
    lt_scene_free(&sc);
    lt_mesh_free(&m);
    return 0;
}

/* ---- diff ----------------------------------------------------------------------------------- */

static cJSON *load_json(const char *path, lt_diag_t *diag)
{
    FILE *f;
    char *buf;
    long n;
    cJSON *j;
    if (lt_diag_not_regular(path) != NULL) {
        lt_diag_fail(diag, "%s: %s, not a report file", path, lt_diag_not_regular(path));
        return NULL;
    }
    f = fopen(path, "rb");
    if (f == NULL) {
        lt_diag_fail(diag, "%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    if (n < 0 || n > (64L << 20)) {
        fclose(f);
        lt_diag_fail(diag, "%s: not a report (size %ld, limit 64 MiB)", path, n);
        return NULL;
    }
    buf = malloc((size_t)n + 1);
    if (buf == NULL || fread(buf, 1, (size_t)n, f) != (size_t)n) {
        fclose(f);
        free(buf);
        lt_diag_fail(diag, "%s: cannot read", path);
        return NULL;
    }
    fclose(f);
    buf[n] = '\0';
    j = cJSON_Parse(buf);
    free(buf);
    if (j == NULL || !cJSON_IsObject(j)) {
        cJSON_Delete(j);
        lt_diag_fail(diag, "%s: not a JSON report object", path);
        return NULL;
    }
    return j;
}

/* Walk both reports' numeric members (nested objects flattened as a.b.c) and print changes. */
static void diff_walk(const cJSON *a, const cJSON *b, const char *prefix, double threshold,
                      cJSON *out, int *changed, int *total)
{
    const cJSON *x;
    cJSON_ArrayForEach(x, a) {
        char key[256];
        const cJSON *y = cJSON_GetObjectItemCaseSensitive(b, x->string);
        snprintf(key, sizeof key, "%s%s%s", prefix, *prefix ? "." : "", x->string);
        if (cJSON_IsObject(x) && cJSON_IsObject(y)) {
            diff_walk(x, y, key, threshold, out, changed, total);
        } else if (cJSON_IsNumber(x)) {
            double va = x->valuedouble, vb = cJSON_IsNumber(y) ? y->valuedouble : 0.0;
            double rel = va != 0.0 ? 100.0 * (vb - va) / fabs(va) : (vb != 0.0 ? (double)INFINITY : 0.0);
            (*total)++;
            if (y == NULL || fabs(rel) > threshold) {
                cJSON *row = cJSON_CreateObject();
                (*changed)++;
                cJSON_AddStringToObject(row, "counter", key);
                cJSON_AddNumberToObject(row, "a", va);
                if (y != NULL)
                    cJSON_AddNumberToObject(row, "b", vb);
                cJSON_AddNumberToObject(row, "delta", vb - va);
                if (isfinite(rel))
                    cJSON_AddNumberToObject(row, "pct", rel);
                cJSON_AddItemToArray(out, row);
            }
        }
    }
    cJSON_ArrayForEach(x, b) {
        char key[256];
        snprintf(key, sizeof key, "%s%s%s", prefix, *prefix ? "." : "", x->string);
        if (cJSON_IsNumber(x) && cJSON_GetObjectItemCaseSensitive(a, x->string) == NULL) {
            cJSON *row = cJSON_CreateObject();
            (*changed)++;
            (*total)++;
            cJSON_AddStringToObject(row, "counter", key);
            cJSON_AddNumberToObject(row, "b", x->valuedouble);
            cJSON_AddNumberToObject(row, "delta", x->valuedouble);
            cJSON_AddItemToArray(out, row);
        }
    }
}

static int cmd_diff(int argc, char **argv)
{
    const char *pos[2] = {NULL, NULL}, *pa, *pb;
    double threshold = 0.0;
    int json = 0, changed = 0, total = 0, npos = 0, rc;
    char who[64];
    lt_diag_t diag;
    cJSON *ja, *jb, *rows;
    const cJSON *r;
    const lt_opt_t opts[] = {
        LT_OPT_DBL("--threshold", "PCT", &threshold, 0.0, HUGE_VAL,
                   "only counters that moved by more than PCT% ({range}, default 0)"),
        LT_OPT_FLAG_("--json", &json, "the counters and rows as JSON"),
        LT_OPT_END_};
    lt_opt_cmd_t cmd = {who, "A.json B.json [--threshold PCT] [--json]",
                        "Compare two JSON reports: every numeric counter that moved by more than "
                        "PCT% (default 0).\n",
                        NULL, opts, pos, 2, &npos};
    snprintf(who, sizeof who, "%s diff", prog);
    rc = lt_opt_parse(&cmd, argc, argv, 2);
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    if (npos < 2) {
        fprintf(stderr, "%s diff: two reports are required\n", prog);
        return EXIT_USAGE;
    }
    pa = pos[0];
    pb = pos[1];
    if ((ja = load_json(pa, &diag)) == NULL ||
        (jb = load_json(pb, &diag)) == NULL) {
        fprintf(stderr, "%s\n", diag.msg);
        cJSON_Delete(ja); /* the first report when the second one fails (NULL-safe) */
        return EXIT_INPUT;
    }
    rows = cJSON_CreateArray();
    diff_walk(ja, jb, "", threshold, rows, &changed, &total);
    if (json) {
        char *s;
        cJSON *o = cJSON_CreateObject();
        cJSON_AddNumberToObject(o, "counters", total);
        cJSON_AddNumberToObject(o, "changed", changed);
        cJSON_AddItemToObject(o, "rows", rows);
        s = cJSON_Print(o);
        puts(s);
        free(s);
        cJSON_Delete(o);
    } else {
        printf("%-40s %16s %16s %14s %9s\n", "counter", "a", "b", "delta", "change");
        cJSON_ArrayForEach(r, rows) {
            const cJSON *va = cJSON_GetObjectItem(r, "a"), *vb = cJSON_GetObjectItem(r, "b");
            const cJSON *p = cJSON_GetObjectItem(r, "pct");
            char sa[32] = "-", sb[32] = "-", sp[32] = "new";
            if (va)
                snprintf(sa, sizeof sa, "%.6g", va->valuedouble);
            if (vb)
                snprintf(sb, sizeof sb, "%.6g", vb->valuedouble);
            if (p)
                snprintf(sp, sizeof sp, "%+.2f%%", p->valuedouble);
            else if (va && !vb)
                snprintf(sp, sizeof sp, "gone");
            printf("%-40s %16s %16s %14.6g %9s\n", cJSON_GetObjectItem(r, "counter")->valuestring,
                   sa, sb, cJSON_GetObjectItem(r, "delta")->valuedouble, sp);
        }
        printf("%d of %d counters changed (threshold %g%%)\n", changed, total, threshold);
        cJSON_Delete(rows);
    }
    cJSON_Delete(ja);
    cJSON_Delete(jb);
    return 0;
}


/* ---- render --------------------------------------------------------------------------------- */

static uint64_t count_hits(const lt_frame_t *f)
{
    size_t i, n = (size_t)f->width * f->height;
    uint64_t c = 0;
    for (i = 0; i < n; i++)
        c += f->id[i] >= 0;
    return c;
}

/* lanetrace render: options, inputs, the trace (primary, shadow and peel rays), the images. */
typedef struct render {
    /* options */
    lt_scenefile_t sf;
    const char *scene_path;
    int npos;
    const char *mesh_over, *out, *report;
    uint32_t wh[2];
    double lf[3];
    int seen_res, seen_light, seen_num, num, structure, isect, seen_isect, layers, json;
    int seen_structure, autop;
    int rays; /* --rays: 0 packets through the binary BVH, 1 through the 8-wide one */
    char auto_json[2048]; /* what the recommendation did, a JSON object ("" = nothing) */
    const char *num_names[8];
    unsigned num_sets[8];
    const lt_path_info_t *path;
    /* the path asked for when it cannot represent the scene and another runs, and the reason */
    const lt_path_info_t *dropped;
    char drop_reason[LT_DIAG_MAX];
    /* inputs */
    lt_mesh_t mesh;
    lt_scene_t sc;
    lt_camera_t cam;
    double light[3]; /* scaled units */
    /* the trace and the images */
    lt_accel_t *acc;
    lt_frame_t fr, lay[16];
    size_t n;
    float *ch[10];
    uint8_t *occ, *rgb;
    uint64_t nrays;
    uint32_t nshadow, nocc;
    lt_outset_t *set; /* every output, renamed into place together at the end */
} render_t;

/* PREFIX + suffix as a member of the render's output set: *dst is where to write it. Returns 0,
 * or an exit code after the message (a name too long is refused, never cut). */
static int render_out(render_t *r, const char *suffix, char path[LT_TMP_PATH_MAX],
                      const char **dst)
{
    lt_diag_t diag;
    int k = snprintf(path, LT_TMP_PATH_MAX, "%s%s", r->out, suffix);
    if (k < 0 || k >= LT_TMP_PATH_MAX - 24) {
        fprintf(stderr, "%s render: --out %.60s...: the output names would be longer than %d "
                        "bytes\n", prog, r->out, LT_TMP_PATH_MAX - 25);
        return EXIT_USAGE;
    }
    if (lt_outset_add(r->set, path, dst, &diag) != 0) {
        fprintf(stderr, "%s render: %s\n", prog, diag.msg);
        return EXIT_INPUT;
    }
    return 0;
}

/* r before the options: nothing given, the defaults of a render. */
static void render_defaults(render_t *r)
{
    memset(r, 0, sizeof *r);
    lt_sf_defaults(&r->sf);
    r->layers = 1;
    r->autop = 1;
    for (r->structure = 0; strcmp(lt_render_structures[r->structure], "bvh") != 0; r->structure++)
        ;
}

/* The options into r; LT_OPT_OK, LT_OPT_HELP or LT_OPT_USAGE. */
static int render_parse(render_t *r, int argc, char **argv)
{
    char who[64], num_help[256];
    const lt_opt_t opts[] = {
        {.name = "--out", .kind = LT_OPT_STRING, .dest = &r->out, .meta = "PREFIX",
         .help = "the images' path prefix (PREFIX.exr, PREFIX.png, PREFIX.<kind>.png)",
         .flags = LT_OPT_REQUIRED, .ext = ""},
        LT_OPT_IN("--mesh", "PATH", &r->mesh_over,
                  "mesh file (overrides the scene's \"mesh\"; default scenes/teapot.obj)"),
        {.name = "--res", .kind = LT_OPT_SIZE, .dest = r->wh, .seen = &r->seen_res,
         .meta = "WxH|N", .help = "image size ({range} per side)", .lo = 1, .hi = LT_SF_MAX_RES},
        {.name = "--num", .kind = LT_OPT_ENUM, .dest = &r->num, .seen = &r->seen_num,
         .names = r->num_names, .help = num_help},
        {.name = "--structure", .kind = LT_OPT_ENUM, .dest = &r->structure, .meta = "NAME",
         .seen = &r->seen_structure, .names = lt_render_structures,
         .help = "acceleration structure: {choices}\n(default: the scene's, else the "
                 "recommendation; chunks: no shadows, no peels)"},
        {.name = "--isect", .kind = LT_OPT_ENUM, .dest = &r->isect, .seen = &r->seen_isect,
         .meta = "NAME", .names = lt_sf_isects,
         .help = "ray/triangle test: {choices} (default: the scene's, else wt:\n"
                 "watertight; mt: Moller-Trumbore, cheaper, leaks at shared edges;\n"
                 "wt32: s15.16 only, watertight on a grid with 32-bit edge functions)"},
        LT_OPT_INT("--layers", "K", &r->layers, 1, 16, "depth peels, {range} (default 1)"),
        LT_OPT_ENUM_("--rays", &r->rays, render_rays_names,
                     "packet: 16-ray packets through the binary BVH (default, the walk the\n"
                     "machine models price); wide: the same packets through the 8-wide BVH\n"
                     "(bvh; one frustum test per node: the same distances, faster natively;\n"
                     "docs/bvh.md)"),
        LT_OPT_OUT("--report", "PATH.json",
                   &r->report, "json", "(simulator build) write the cycle report of the whole render as\n"
                               "JSON; the text report is printed unless -q or --json"),
        {.name = "--light", .kind = LT_OPT_VEC, .dest = r->lf, .seen = &r->seen_light,
         .meta = "X,Y,Z", .lo = -HUGE_VAL, .hi = HUGE_VAL, .n = 3,
         .help = "point light in mesh file units (default: the scene's first light,\n"
                 "else centre + 2 radius normalize(-0.5, 1.5, 0.8))"},
        LT_OPT_AUTO_(&r->autop, "the numeric path, structure and leaf size"),
        LT_OPT_FLAG_("--json", &r->json, "print what was written as JSON on stdout"),
        LT_OPT_THREADS_(&threads_opt),
        LT_OPT_FLAG_("-q", &quiet, "quiet"),
        LT_OPT_END_};
    lt_opt_cmd_t cmd = {
        who, "[SCENE.json] --out PREFIX [options]",
        "Render a mesh through a structure in one numeric path and write images:\n"
        "  PREFIX.exr  FLOAT channels Z (distance), id, N.x N.y N.z (normal), R G B (shaded:\n"
        "              one point light, hard shadows) and, with --layers K, layer0.Z ..\n"
        "              layer<K-1>.Z (the first K surfaces along each primary ray)\n"
        "  PREFIX.png  the shaded image; PREFIX.depth.png, PREFIX.normals.png, PREFIX.ids.png\n"
        "options:\n",
        NULL, opts, &r->scene_path, 1, &r->npos};
    int rc;
    snprintf(who, sizeof who, "%s render", prog);
    num_choices(LT_PATHS_OBJECT, 0, r->num_names, r->num_sets, num_help, sizeof num_help);
    strncat(num_help, "; default the scene file's \"numeric\" when it names one path, else\n"
                      "the recommendation (--no-auto: q16; f32 when s15.16 cannot represent\n"
                      "the scene and q16 was not asked for)",
            sizeof num_help - strlen(num_help) - 1);
    rc = lt_opt_parse(&cmd, argc, argv, 2);
    lt_par_set_threads((unsigned)threads_opt);
    if (r->json)
        quiet = 1;
    r->path = lt_paths_find(r->num_names[r->num], LT_PATHS_OBJECT);
    return rc;
}

/* The path: --num, else the scene file's "numeric" when it names one path, else q16; one that
 * cannot represent the scene is refused when asked for (--num, the scene file), else replaced by
 * the first path that can, with a line saying why. Returns 0 or -1 after the message. */
static int render_pick_path(render_t *r)
{
    const lt_scenefile_t *sf = &r->sf;
    const lt_path_info_t *p, *alt;
    lt_diag_t diag;
    int asked = r->seen_num;
    for (p = lt_paths; !asked && sf->numeric != LT_SF_NUM_BOTH && p->name != NULL; p++)
        if ((p->families & LT_PATHS_OBJECT) && (unsigned)p->sf_num == (unsigned)sf->numeric) {
            r->path = p;
            asked = 1;
        }
    if (r->path->render->scene_check == NULL ||
        r->path->render->scene_check(&r->sc, sf->mesh, &diag) == 0)
        return 0;
    alt = asked ? NULL : lt_paths_fallback(&r->sc, LT_PATHS_OBJECT, r->path);
    if (alt == NULL) {
        fprintf(stderr, "%s\n", diag.msg);
        return -1;
    }
    fprintf(stderr, "%s render: numeric path %s (%s) dropped, running %s (%s): %s\n", prog,
            r->path->name, r->path->format, alt->name, alt->format, diag.msg);
    r->dropped = r->path;
    snprintf(r->drop_reason, sizeof r->drop_reason, "%s", diag.msg);
    r->path = alt;
    return 0;
}

/* The scene file under the flags, the mesh, the prepared scene, the camera and the light.
 * Returns 0 or an exit code. */
static int render_load(render_t *r)
{
    lt_scenefile_t *sf = &r->sf;
    lt_diag_t diag;
    int a;
    if (!lt_meter_available() && r->report != NULL) {
        fprintf(stderr, "%s render: --report needs the simulator build (build/sim/lanetrace); "
                        "this is the native build\n", prog);
        return EXIT_USAGE;
    }
    if (r->scene_path != NULL && lt_sf_load(r->scene_path, sf, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    if (r->seen_res) {
        sf->width = r->wh[0];
        sf->height = r->wh[1];
    }
    if (r->mesh_over != NULL)
        snprintf(sf->mesh, sizeof sf->mesh, "%s", r->mesh_over);
    if (scene_mesh_or_default(r->scene_path, sf, "render") != 0)
        return EXIT_INPUT;
    if (!r->seen_light && sf->nlights > 0) {
        memcpy(r->lf, sf->lights[0].position, sizeof r->lf);
        r->seen_light = 1;
    }
    if (lt_meter_init(sf->machine, NULL, NULL, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_USAGE;
    }
    if (lt_mesh_load(sf->mesh, &r->mesh, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    if (lt_scene_prepare(&r->mesh, &r->sc, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", sf->mesh, diag.msg);
        return EXIT_INPUT;
    }
    if (r->seen_structure) /* the picks must see it (bvhq: s15.16, leaves of at most 15) */
        snprintf(sf->structure, sizeof sf->structure, "%s", lt_render_structures[r->structure]);
    if (r->autop) {
        auto_by_t by = auto_by(sf, r->seen_num, r->seen_structure);
        auto_apply(sf, &r->mesh, &r->sc, &by, 1, quiet, r->auto_json, sizeof r->auto_json);
    }
    if (!r->seen_structure) {
        for (a = 0; lt_render_structures[a] != NULL; a++)
            if (strcmp(lt_render_structures[a], sf->structure) == 0)
                r->structure = a;
    }
    if (render_pick_path(r) != 0)
        return EXIT_INPUT;
    if (sf->has_camera) {
        if (lt_camera_look(&r->sc, sf->eye, sf->target, sf->up, sf->fov_y_deg, sf->width,
                           sf->height, &r->cam, &diag) != 0) {
            fprintf(stderr, "%s: %s\n", sf->path, diag.msg);
            return EXIT_INPUT;
        }
    } else {
        lt_camera_default(&r->sc, sf->width, sf->height, &r->cam);
    }
    lt_scene_light(&r->sc, r->seen_light ? r->lf : NULL, r->light);
    for (a = 0; a < 3; a++) {
        if (fabs(r->light[a]) > ldexp(1.0, LT_CFG_GEOM_MAX_LOG2)) {
            fprintf(stderr, "%s render: the light lies outside the fixed-point range (|x| <= %g "
                            "scaled units, %.3g scene radii)\n",
                    prog, ldexp(1.0, LT_CFG_GEOM_MAX_LOG2),
                    ldexp(1.0, LT_CFG_GEOM_MAX_LOG2) / r->sc.radius);
            return EXIT_INPUT;
        }
    }
    return 0;
}

/* The structure, the primary rays, the image buffers and the shadow rays. Returns 0 or an exit
 * code. */
/* Bytes of memory available to this process: MemAvailable of /proc/meminfo, or the address-space
 * limit (ulimit -v) when that is lower; 0 if neither is known. *what names the one used. */
static double mem_available(const char **what)
{
    char line[256];
    double kb = 0.0, avail = 0.0;
    struct rlimit rl;
    FILE *f = fopen("/proc/meminfo", "r");
    *what = "MemAvailable";
    if (f != NULL) {
        while (fgets(line, sizeof line, f) != NULL)
            if (sscanf(line, "MemAvailable: %lf kB", &kb) == 1)
                break;
        fclose(f);
        avail = kb * 1024.0;
    }
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY &&
        (avail == 0.0 || (double)rl.rlim_cur < avail)) {
        avail = (double)rl.rlim_cur;
        *what = "the address-space limit, ulimit -v";
    }
    return avail;
}

/* The images of the whole render, measured and allocated before any tracing: a render too large
 * for this machine fails at once, naming the size, instead of after the trace. Returns 0 or an
 * exit code. */
static int render_memory(render_t *r)
{
    const lt_scenefile_t *sf = &r->sf;
    lt_diag_t diag;
    double n = (double)sf->width * sf->height, L = r->layers > 1 ? r->layers : 0;
    /* frames (id 4 + t 8 + cost 4 + steps 4) for the render and each peel, 10 float channels,
       RGB8 + occlusion bytes, one float depth per peel for the EXR */
    const char *what;
    double need = n * (20.0 * (1.0 + L) + 40.0 + 4.0 + 4.0 * L), avail = mem_available(&what);
    int l;
    if (avail > 0.0 && need > avail) {
        fprintf(stderr, "%s render: %ux%u with %d layer(s) needs %.2f GiB for its images; %.2f GiB "
                        "are available (%s); lower --res or --layers\n", prog, sf->width,
                sf->height, r->layers, need / 1073741824.0, avail / 1073741824.0, what);
        return EXIT_INPUT;
    }
    if (lt_frame_alloc(&r->fr, sf->width, sf->height, &diag) != 0) {
        fprintf(stderr, "%s render: %s (%.2f GiB needed in all)\n", prog, diag.msg,
                need / 1073741824.0);
        return EXIT_INPUT;
    }
    for (l = 0; l < r->layers && r->layers > 1; l++)
        if (lt_frame_alloc(&r->lay[l], sf->width, sf->height, &diag) != 0) {
            fprintf(stderr, "%s render: %s (layer %d; %.2f GiB needed in all)\n", prog,
                    diag.msg, l, need / 1073741824.0);
            return EXIT_INPUT;
        }
    return 0;
}

static int render_trace(render_t *r)
{
    const lt_scenefile_t *sf = &r->sf;
    const char *structure = lt_render_structures[r->structure];
    lt_diag_t diag;
    int a;
    if ((a = render_memory(r)) != 0)
        return a;
    {
        lt_accel_params_t prm = {structure_has_leaf(structure) ? sf->leaf : 0};
        r->acc = lt_accel_build_ex(&r->sc, structure, r->path, &prm, &diag);
    }
    if (r->acc == NULL) {
        fprintf(stderr, "%s render: %s\n", prog, diag.msg);
        return EXIT_USAGE;
    }
    if (r->seen_isect)
        snprintf(r->sf.isect, sizeof r->sf.isect, "%s", lt_sf_isects[r->isect]);
    if (lt_accel_set_isect_name(r->acc, sf->isect, NULL, &diag) != 0) {
        fprintf(stderr, "%s render: %s\n", prog, diag.msg);
        return EXIT_USAGE;
    }
    if (r->rays == 1 && lt_accel_set_walk(r->acc, 1, &diag) != 0) {
        fprintf(stderr, "%s render: %s\n", prog, diag.msg);
        return EXIT_INPUT;
    }
    progress_begin("render");
    lt_render_primary(&r->sc, r->acc, &r->cam, &r->fr, progress);
    progress_end();
    r->n = (size_t)sf->width * sf->height;
    r->occ = calloc(r->n, 1);
    r->rgb = malloc(r->n * 3);
    for (a = 0; a < 10; a++)
        r->ch[a] = malloc(r->n * sizeof(float));
    for (a = 0; a < 10; a++)
        if (r->ch[a] == NULL || r->occ == NULL || r->rgb == NULL) {
            fprintf(stderr, "%s render: out of memory for %ux%u images\n", prog, sf->width,
                    sf->height);
            return EXIT_INPUT;
        }
    if (strcmp(structure, "chunks") != 0 &&
        lt_render_shadows(&r->sc, r->acc, &r->cam, &r->fr, r->light, &r->nshadow, &r->nocc,
                          r->occ, &diag) != 0) {
        fprintf(stderr, "%s render: %s\n", prog, diag.msg);
        return EXIT_INPUT;
    }
    return 0;
}

/* The channels Z id N.x N.y N.z R G B (shaded: one point light, hard shadows, two-sided normals
 * facing the camera) and the 8-bit shaded image. */
static void render_shade(render_t *r)
{
    const lt_frame_t *fr = &r->fr;
    size_t i;
    for (i = 0; i < r->n; i++) {
        uint32_t x = (uint32_t)(i % r->sf.width), y = (uint32_t)(i / r->sf.width);
        int32_t id = fr->id[i];
        double nrm[3] = {0, 0, 0}, d[3], shade = 0.0;
        if (id >= 0) {
            const double *v = &r->sc.vd[(size_t)id * 9];
            double e1[3], e2[3], ln, p[3], L[3], ll;
            int k;
            for (k = 0; k < 3; k++) {
                e1[k] = v[3 + k] - v[k];
                e2[k] = v[6 + k] - v[k];
            }
            nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
            nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
            nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
            ln = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
            lt_camera_dir(&r->cam, x, y, d);
            if (ln > 0.0) {
                /* two-sided: the normal faces the camera */
                double s1 = (nrm[0] * d[0] + nrm[1] * d[1] + nrm[2] * d[2]) > 0.0 ? -1.0 : 1.0;
                for (k = 0; k < 3; k++)
                    nrm[k] *= s1 / ln;
            }
            for (k = 0; k < 3; k++) {
                p[k] = r->cam.eye[k] + fr->t[i] * d[k];
                L[k] = r->light[k] - p[k];
            }
            ll = sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
            shade = 0.08 + (r->occ[i] ? 0.0
                                      : 0.92 * fmax(0.0, (nrm[0] * L[0] + nrm[1] * L[1] +
                                                          nrm[2] * L[2]) / ll));
        }
        r->ch[0][i] = id >= 0 ? (float)fr->t[i] : (float)INFINITY;
        r->ch[1][i] = (float)id;
        r->ch[2][i] = (float)nrm[0];
        r->ch[3][i] = (float)nrm[1];
        r->ch[4][i] = (float)nrm[2];
        r->ch[5][i] = r->ch[6][i] = r->ch[7][i] = (float)shade;
        r->rgb[3 * i] = r->rgb[3 * i + 1] = r->rgb[3 * i + 2] = id >= 0 ? lt_gamma8(shade) : 24;
    }
}

/* PREFIX.exr: the channels and, with --layers K > 1, the depth peels layer0.Z .. (layer 0 is the
 * primary hit; each further layer traces peel rays from the hits of the one before). Returns 0
 * or an exit code. */
static int render_write_exr(render_t *r)
{
    const lt_scenefile_t *sf = &r->sf;
    size_t n = r->n, i;
    char path[LT_TMP_PATH_MAX];
    lt_diag_t diag;
    lt_exr_channel_t ec[8 + 16];
    lt_exr_image_t im;
    static const char *const names[8] = {"Z", "id", "N.x", "N.y", "N.z", "R", "G", "B"};
    static char lname[16][16];
    int nc = 0, a, l, status = 0;
    for (a = 0; a < 8; a++) {
        ec[nc].name = names[a];
        ec[nc].type = LT_EXR_FLOAT;
        ec[nc++].data = r->ch[a];
    }
    for (l = 0; l < r->layers && r->layers > 1; l++) {
        float *z = malloc(n * sizeof(float));
        if (z == NULL || (r->lay[l].id == NULL &&
                          lt_frame_alloc(&r->lay[l], sf->width, sf->height, &diag) != 0)) {
            free(z);
            fprintf(stderr, "%s render: out of memory for layer %d\n", prog, l);
            status = EXIT_INPUT;
            break;
        }
        if (l == 0) {
            memcpy(r->lay[0].id, r->fr.id, n * sizeof *r->fr.id);
            memcpy(r->lay[0].t, r->fr.t, n * sizeof *r->fr.t);
        } else if ((r->nrays += count_hits(&r->lay[l - 1]), 0) ||
                   lt_render_peel(&r->sc, r->acc, &r->cam, &r->lay[l - 1], &r->lay[l], &diag) != 0) {
            free(z);
            fprintf(stderr, "%s render: %s\n", prog, diag.msg);
            status = EXIT_USAGE;
            break;
        }
        for (i = 0; i < n; i++)
            z[i] = r->lay[l].id[i] >= 0 ? (float)r->lay[l].t[i] : (float)INFINITY;
        snprintf(lname[l], sizeof lname[l], "layer%d.Z", l);
        ec[nc].name = lname[l];
        ec[nc].type = LT_EXR_FLOAT;
        ec[nc++].data = z;
    }
    if (status == 0) {
        memset(&im, 0, sizeof im);
        im.width = (int32_t)sf->width;
        im.height = (int32_t)sf->height;
        im.nchannels = nc;
        im.channels = ec;
        const char *dst = NULL;
        status = render_out(r, ".exr", path, &dst);
        if (status != 0) {
            /* the message is out */
        } else if (lt_exr_write(dst, &im, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            status = EXIT_INPUT;
        } else if (!quiet) {
            printf("exr       %s (%d channels%s)\n", path, nc,
                   r->layers > 1 ? ", depth peels" : "");
        }
    }
    for (a = 8; a < nc; a++)
        free((void *)ec[a].data);
    return status;
}

/* The numeric pick into o when the path asked for was dropped: {"path", "dropped", "reason"}. */
static void render_pick_json(const render_t *r, cJSON *o)
{
    cJSON *y;
    if (r->auto_json[0] != '\0')
        cJSON_AddItemToObject(o, "auto", cJSON_Parse(r->auto_json));
    if (r->dropped == NULL)
        return;
    y = cJSON_AddObjectToObject(o, "numeric_pick");
    cJSON_AddStringToObject(y, "path", r->path->name);
    cJSON_AddStringToObject(y, "dropped", r->dropped->name);
    cJSON_AddStringToObject(y, "reason", r->drop_reason);
}

/* (sim build) the cycle report of every ray of the render: primary packets, shadow packets,
 * peels (and the build); --report writes it as JSON. Returns 0 or an exit code. */
static int render_report(render_t *r)
{
    const lt_scenefile_t *sf = &r->sf;
    lt_diag_t diag;
    char title[1400], extra[2048], *js;
    if (!lt_meter_available())
        return 0;
    snprintf(title, sizeof title, "render %s %ux%u %s, %s, %d layer(s), shadows", sf->mesh,
             sf->width, sf->height, r->path->name, lt_render_structures[r->structure], r->layers);
    if (!quiet)
        lt_meter_report_text(stdout, title, r->nrays);
    {
        cJSON *x = cJSON_CreateObject();
        char *xs;
        cJSON_AddNumberToObject(x, "primary_rays", (double)r->n);
        cJSON_AddNumberToObject(x, "shadow_rays", r->nshadow);
        cJSON_AddNumberToObject(x, "peel_rays", (double)(r->nrays - r->n - r->nshadow));
        render_pick_json(r, x);
        xs = cJSON_PrintUnformatted(x);
        snprintf(extra, sizeof extra, "%s", xs != NULL ? xs : "{}");
        free(xs);
        cJSON_Delete(x);
    }
    js = lt_meter_report_json(title, r->nrays, extra);
    if (r->report != NULL) {
        const char *dst = NULL;
        FILE *f = NULL;
        if (lt_outset_add(r->set, r->report, &dst, &diag) != 0 || js == NULL ||
            (f = fopen(dst, "w")) == NULL || fputs(js, f) < 0 || fclose(f) != 0) {
            if (f == NULL && js != NULL && dst != NULL)
                lt_diag_fail(&diag, "%s: cannot create the output: %s", r->report,
                             strerror(errno));
            else if (f != NULL)
                lt_diag_fail(&diag, "%s: write failed (disk full?)", r->report);
            fprintf(stderr, "%s\n", js == NULL ? "render: out of memory for the report" : diag.msg);
            free(js);
            return EXIT_INPUT;
        }
        if (!quiet)
            printf("report    %s\n", r->report);
    }
    free(js);
    return 0;
}

/* PREFIX.png (shaded) and the quick looks: depth (near bright), normals (0.5 + 0.5 n), ids
 * (hashed colours). Returns 0 or an exit code. */
static int render_write_pngs(render_t *r)
{
    const lt_scenefile_t *sf = &r->sf;
    const lt_frame_t *fr = &r->fr;
    char path[LT_TMP_PATH_MAX];
    lt_diag_t diag;
    double zmin = INFINITY, zmax = 0.0;
    static const char *const kinds[3] = {".depth.png", ".normals.png", ".ids.png"};
    const char *dst = NULL;
    size_t i;
    int kk, rc;
    if ((rc = render_out(r, ".png", path, &dst)) != 0)
        return rc;
    if (lt_png_write(dst, r->rgb, (int32_t)sf->width, (int32_t)sf->height, 3, 3 * sf->width,
                     &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    for (i = 0; i < r->n; i++)
        if (fr->id[i] >= 0) {
            zmin = fmin(zmin, fr->t[i]);
            zmax = fmax(zmax, fr->t[i]);
        }
    for (kk = 0; kk < 3; kk++) {
        for (i = 0; i < r->n; i++) {
            uint8_t *px = &r->rgb[3 * i];
            if (fr->id[i] < 0) {
                px[0] = px[1] = px[2] = 0;
            } else if (kk == 0) {
                double v = zmax > zmin ? 1.0 - (fr->t[i] - zmin) / (zmax - zmin) : 1.0;
                px[0] = px[1] = px[2] = (uint8_t)(40.0 + 215.0 * v);
            } else if (kk == 1) {
                px[0] = (uint8_t)(127.5 + 127.0 * (double)r->ch[2][i]);
                px[1] = (uint8_t)(127.5 + 127.0 * (double)r->ch[3][i]);
                px[2] = (uint8_t)(127.5 + 127.0 * (double)r->ch[4][i]);
            } else {
                uint32_t hsh = (uint32_t)fr->id[i] * 2654435761u;
                px[0] = (uint8_t)(64 + (hsh >> 24) % 192);
                px[1] = (uint8_t)(64 + (hsh >> 16) % 192);
                px[2] = (uint8_t)(64 + (hsh >> 8) % 192);
            }
        }
        if ((rc = render_out(r, kinds[kk], path, &dst)) != 0)
            return rc;
        if (lt_png_write(dst, r->rgb, (int32_t)sf->width, (int32_t)sf->height, 3, 3 * sf->width,
                         &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            return EXIT_INPUT;
        }
    }
    return 0;
}

/* The summary line, and with --json what was written. */
static void render_summary(const render_t *r)
{
    const char *out = r->out;
    char path[1200];
    if (!quiet)
        printf("png       %s.png (shaded), %s.depth.png, %s.normals.png, %s.ids.png; %u shadow "
               "rays, %u occluded\n",
               out, out, out, out, r->nshadow, r->nocc);
    if (r->json) {
        cJSON *o = cJSON_CreateObject(), *files = cJSON_AddArrayToObject(o, "files");
        static const char *const sfx[5] = {".exr", ".png", ".depth.png", ".normals.png", ".ids.png"};
        char *js;
        int a;
        for (a = 0; a < 5; a++) {
            snprintf(path, sizeof path, "%s%s", out, sfx[a]);
            cJSON_AddItemToArray(files, cJSON_CreateString(path));
        }
        cJSON_AddStringToObject(o, "mesh", r->sf.mesh);
        cJSON_AddStringToObject(o, "structure", lt_render_structures[r->structure]);
        cJSON_AddStringToObject(o, "isect", r->sf.isect);
        cJSON_AddStringToObject(o, "path", r->path->name);
        render_pick_json(r, o);
        cJSON_AddNumberToObject(o, "width", r->sf.width);
        cJSON_AddNumberToObject(o, "height", r->sf.height);
        cJSON_AddNumberToObject(o, "layers", r->layers);
        cJSON_AddNumberToObject(o, "shadow_rays", r->nshadow);
        cJSON_AddNumberToObject(o, "occluded", r->nocc);
        cJSON_AddNumberToObject(o, "rays", (double)r->nrays);
        if (lt_meter_available()) {
            lt_meter_totals_t tt;
            lt_meter_totals(&tt);
            cJSON_AddNumberToObject(o, "cycles", (double)tt.total_cycles);
            if (r->report != NULL)
                cJSON_AddStringToObject(o, "report", r->report);
        }
        js = cJSON_Print(o);
        if (js != NULL)
            puts(js);
        free(js);
        cJSON_Delete(o);
    }
}

static int cmd_render(int argc, char **argv)
{
    render_t r;
    int rc, a;
    render_defaults(&r);
    rc = render_parse(&r, argc, argv);
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    r.set = calloc(1, sizeof *r.set);
    if (r.set == NULL) {
        fprintf(stderr, "%s render: out of memory\n", prog);
        return EXIT_INPUT;
    }
    rc = render_load(&r);
    if (rc == 0)
        rc = render_trace(&r);
    if (rc == 0) {
        render_shade(&r);
        rc = render_write_exr(&r);
    }
    if (rc == 0) {
        r.nrays += r.n + r.nshadow;
        rc = render_report(&r);
    }
    if (rc == 0)
        rc = render_write_pngs(&r);
    /* all outputs or none: the new files replace the old ones only when every one was written */
    if (rc == 0) {
        lt_diag_t diag;
        if (lt_outset_commit(r.set, &diag) != 0) {
            fprintf(stderr, "%s render: %s\n", prog, diag.msg);
            rc = EXIT_INPUT;
        }
    } else if (r.set->n > 0) {
        fprintf(stderr, "%s render: none of the outputs written (%d prepared were removed; "
                        "previous files are unchanged)\n", prog, r.set->n);
        lt_outset_abort(r.set);
    }
    if (rc == 0)
        render_summary(&r);
    free(r.set);
    for (a = 0; a < 10; a++)
        free(r.ch[a]);
    for (a = 0; a < 16; a++)
        lt_frame_free(&r.lay[a]);
    free(r.occ);
    free(r.rgb);
    lt_accel_free(r.acc);
    lt_frame_free(&r.fr);
    lt_scene_free(&r.sc);
    lt_mesh_free(&r.mesh);
    lt_meter_shutdown();
    return rc;
}

/* ---- stream: the receiver is its own program (host/stream/lt_stream_main.c); hand over to it ---------- */

static int cmd_stream(int argc, char **argv)
{
    char path[1200];
    const char *slash = strrchr(argv[0], '/');
    char **nargv = calloc((size_t)argc + 1, sizeof *nargv);
    int i;
    if (nargv == NULL)
        return EXIT_INPUT;
    /* the CLI lives in build/sim or build/host; lt-stream in build/host */
    if (slash != NULL)
        snprintf(path, sizeof path, "%.*s/../host/lt-stream", (int)(slash - argv[0]), argv[0]);
    else
        snprintf(path, sizeof path, "lt-stream");
    nargv[0] = path;
    for (i = 2; i < argc; i++)
        nargv[i - 1] = argv[i];
    nargv[argc - 1] = NULL;
    execv(path, nargv);
    if (slash == NULL)
        execvp("lt-stream", nargv);
    fprintf(stderr, "%s stream: cannot run %s (build it with `make test-build`)\n", prog, path);
    free(nargv);
    return EXIT_INPUT;
}

/* ---- reproject: view synthesis from a depth EXR (host/cli/lt_reproject_cli.c) -------------------- */

static int cmd_reproject(int argc, char **argv)
{
    lt_rp_cli_hooks_t h;
    h.begin = progress_begin;
    h.progress = progress;
    h.end = progress_end;
    h.quiet = &quiet;
    h.write_text = write_atomic;
    return lt_rp_cli(argc, argv, prog, &h);
}

/* ---- machines: the machine models (sim/machines/<name>.def) ------------------------------- */

static const char *const op_names[] = {
#define LT_OP(name, unit, doc) #name,
#define LT_EV(name, doc)
#define LT_PH(name, doc)
#include "lt/lt_ops.def"
#undef LT_OP
#undef LT_EV
#undef LT_PH
};

static const char *const op_units[] = {
#define LT_OP(name, unit, doc) #unit,
#define LT_EV(name, doc)
#define LT_PH(name, doc)
#include "lt/lt_ops.def"
#undef LT_OP
#undef LT_EV
#undef LT_PH
};

/* "64:8:64 32 KiB, 3 cy" or "none" */
static void cache_text(char *buf, size_t n, const char *spec, uint32_t hit)
{
    unsigned sets, ways, line;
    char c;
    if (spec == NULL) {
        snprintf(buf, n, "none");
    } else if (sscanf(spec, "%u:%u:%u%c", &sets, &ways, &line, &c) == 3) {
        unsigned long long b = (unsigned long long)sets * ways * line;
        if (b >= 1024 && b % 1024 == 0)
            snprintf(buf, n, "%s %llu KiB, %u cy", spec, b / 1024, hit);
        else
            snprintf(buf, n, "%s %llu B, %u cy", spec, b, hit);
    } else {
        snprintf(buf, n, "%s, %u cy", spec, hit);
    }
}

/* --json: everything about every machine (the native build: the names). */
static int machines_json(int nm)
{
    cJSON *root = cJSON_CreateObject(), *arr;
    lt_meter_machine_t m;
    char *js;
    int i, o;
    cJSON_AddStringToObject(root, "build", lt_meter_available() ? "simulator" : "native");
    arr = cJSON_AddArrayToObject(root, "machines");
    for (i = 0; i < nm; i++) {
        cJSON *x = cJSON_CreateObject(), *y;
        const char *name = lt_meter_machine_name(i);
        cJSON_AddStringToObject(x, "name", name);
        if (lt_meter_machine_info(name, &m) == 0) {
            cJSON_AddStringToObject(x, "description", m.desc);
            cJSON_AddNumberToObject(x, "clock_mhz", m.clock_mhz);
            cJSON_AddNumberToObject(x, "lanes", m.lanes);
            y = cJSON_AddObjectToObject(x, "l1");
            cJSON_AddStringToObject(y, "spec", m.l1);
            cJSON_AddNumberToObject(y, "hit_cycles", m.l1_hit);
            if (m.l2 != NULL) {
                y = cJSON_AddObjectToObject(x, "l2");
                cJSON_AddStringToObject(y, "spec", m.l2);
                cJSON_AddNumberToObject(y, "hit_cycles", m.l2_hit);
            } else {
                cJSON_AddNullToObject(x, "l2");
            }
            cJSON_AddNumberToObject(x, "memory_cycles", m.mem);
            y = cJSON_AddObjectToObject(x, "ops");
            for (o = 0; o < LT_OP__COUNT; o++) {
                cJSON *z = cJSON_AddObjectToObject(y, op_names[o]);
                cJSON_AddNumberToObject(z, "latency", m.latency[o]);
                cJSON_AddNumberToObject(z, "issue", m.issue[o]);
            }
        }
        cJSON_AddItemToArray(arr, x);
    }
    js = cJSON_Print(root);
    if (js != NULL)
        puts(js);
    free(js);
    cJSON_Delete(root);
    return js != NULL ? 0 : EXIT_INPUT;
}

/* The table (simulator build): one row per machine, then with --ops the op prices. */
static void machines_table(int nm, int ops)
{
    size_t wn = strlen("machine"), w1 = strlen("L1"), w2 = strlen("L2");
    const char *name;
    char c1[96], c2[96];
    lt_meter_machine_t m;
    int i, o;
    for (i = 0; i < nm; i++) {
        name = lt_meter_machine_name(i);
        (void)lt_meter_machine_info(name, &m);
        cache_text(c1, sizeof c1, m.l1, m.l1_hit);
        cache_text(c2, sizeof c2, m.l2, m.l2_hit);
        wn = strlen(name) > wn ? strlen(name) : wn;
        w1 = strlen(c1) > w1 ? strlen(c1) : w1;
        w2 = strlen(c2) > w2 ? strlen(c2) : w2;
    }
    printf("%-*s %9s %5s  %-*s  %-*s %7s  %s\n", (int)wn, "machine", "clock", "lanes", (int)w1,
           "L1", (int)w2, "L2", "memory", "description");
    for (i = 0; i < nm; i++) {
        char clk[32], mem[32];
        name = lt_meter_machine_name(i);
        (void)lt_meter_machine_info(name, &m);
        cache_text(c1, sizeof c1, m.l1, m.l1_hit);
        cache_text(c2, sizeof c2, m.l2, m.l2_hit);
        snprintf(clk, sizeof clk, "%u MHz", m.clock_mhz);
        snprintf(mem, sizeof mem, "%u cy", m.mem);
        printf("%-*s %9s %5u  %-*s  %-*s %7s  %s\n", (int)wn, name, clk, m.lanes, (int)w1, c1,
               (int)w2, c2, mem, m.desc);
    }
    if (!ops) {
        printf("(caches: sets:ways:line, size, load-to-use cycles of a hit; op prices: %s "
               "machines --ops)\n", prog);
        return;
    }
    printf("\nop prices, latency/issue cycles (a phase's cycles = sum of count x issue + memory "
           "stalls)\n");
    printf("%-10s %-7s", "op class", "unit");
    for (i = 0; i < nm; i++)
        printf(" %12s", lt_meter_machine_name(i));
    printf("\n");
    for (o = 0; o < LT_OP__COUNT; o++) {
        printf("%-10s %-7s", op_names[o], op_units[o]);
        for (i = 0; i < nm; i++) {
            char cell[32];
            (void)lt_meter_machine_info(lt_meter_machine_name(i), &m);
            snprintf(cell, sizeof cell, "%u/%u", m.latency[o], m.issue[o]);
            printf(" %12s", cell);
        }
        printf("\n");
    }
}

static int cmd_machines(int argc, char **argv)
{
    int i, json = 0, ops = 0, nm, rc;
    char who[64];
    const lt_opt_t opts[] = {
        LT_OPT_FLAG_("--ops", &ops, "the price of every op class (latency/issue cycles;\n"
                                    "issue is what is charged)"),
        LT_OPT_FLAG_("--json", &json, "all of it as JSON"),
        LT_OPT_END_};
    lt_opt_cmd_t cmd = {who, "[--ops] [--json]",
                        "The machine models of the cycle model, one per file "
                        "sim/machines/<name>.def:\nname, clock, lanes, caches (sets:ways:line, "
                        "size, hit latency), memory\nlatency, description. The native build "
                        "knows the names only.\n",
                        NULL, opts, NULL, 0, NULL};
    snprintf(who, sizeof who, "%s machines", prog);
    rc = lt_opt_parse(&cmd, argc, argv, 2);
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    for (nm = 0; lt_meter_machine_name(nm) != NULL; nm++)
        ;
    if (json)
        return machines_json(nm);
    if (!lt_meter_available()) {
        /* names only, one per line; where the rest is on stderr */
        for (i = 0; i < nm; i++)
            printf("%s\n", lt_meter_machine_name(i));
        fprintf(stderr, "%s machines: the native build has no cycle model; build/sim/lanetrace "
                        "machines prints clocks, caches and op prices\n", prog);
        return 0;
    }
    machines_table(nm, ops);
    return 0;
}

/* ---- main ----------------------------------------------------------------------------------- */

static void usage(FILE *f)
{
    fprintf(f,
            "usage: %s COMMAND [options]   (%s build)\n"
            "commands:\n"
            "  run [SCENE.json]   trace a scene; accuracy and (sim build) the cycle report\n"
            "  render [SCENE.json] --out PREFIX  images: depth, normals, ids, shaded (hard\n"
            "                     shadows), k-layer depth peels (EXR + PNG)\n"
            "  reproject --depth FILE.exr  a new view of a depth image (screen-space quadtree,\n"
            "                     inpainting; EXR + PNG + heatmaps; sim build: cycle report)\n"
            "  shadows --mesh FILE  soft shadows by multi-frusta and 16-ray packets, Table-1\n"
            "                     report (sim build: cycles per stage), images, reference\n"
            "  tune SCENE|MESH    Pareto fronts of cycles vs error per family and machine;\n"
            "                     --budget picks the cheapest configuration (docs/tune.md)\n"
            "  fwblob --depth FILE.exr --out FILE  the firmware reprojection blob of a depth\n"
            "                     EXR crop (firmware/apps/reproj_app.h, docs/firmware.md)\n"
            "  info FILE          describe a mesh or EXR file\n"
            "  pack SCENE|MESH    a scene blob for a firmware target, and its trace here\n"
            "  stream [SOURCE]    receive a device's report frames (see lt-stream --help)\n"
            "  diff A.json B.json compare two JSON reports\n"
            "  machines [--ops]   the machine models: clock, lanes, caches, op prices (--json)\n"
            "  help               this text\n"
            "Every command takes --help. Exit codes: 0 ok, 1 input or runtime error, 2 usage.\n",
            prog, lt_meter_available() ? "simulator" : "native");
}

int main(int argc, char **argv)
{
    lt_tmp_handle_signals(); /* no temporary output survives SIGINT, SIGTERM, SIGXFSZ, ... */
    if (argc < 2 || strcmp(argv[1], "help") == 0 || strcmp(argv[1], "--help") == 0 ||
        strcmp(argv[1], "-h") == 0) {
        usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? EXIT_USAGE : 0;
    }
    if (strcmp(argv[1], "run") == 0)
        return cmd_run(argc, argv);
    if (strcmp(argv[1], "stream") == 0)
        return cmd_stream(argc, argv);
    if (strcmp(argv[1], "render") == 0)
        return cmd_render(argc, argv);
    if (strcmp(argv[1], "info") == 0)
        return cmd_info(argc, argv);
    if (strcmp(argv[1], "reproject") == 0)
        return cmd_reproject(argc, argv);
    if (strcmp(argv[1], "diff") == 0)
        return cmd_diff(argc, argv);
    if (strcmp(argv[1], "shadows") == 0)
        return lt_shadows_cli(argc, argv, prog);
    if (strcmp(argv[1], "machines") == 0)
        return cmd_machines(argc, argv);
    if (strcmp(argv[1], "tune") == 0)
        return lt_tune_cli(argc, argv, prog);
    if (strcmp(argv[1], "pack") == 0)
        return lt_pack_cli(argc, argv, prog);
    if (strcmp(argv[1], "fwblob") == 0)
        return lt_fwblob_cli(argc, argv, prog);
    fprintf(stderr, "%s: unknown command '%s'\n", prog, argv[1]);
    usage(stderr);
    return EXIT_USAGE;
}
