/* lt_tune_cli.c - `lanetrace tune` (lt_tune_cli.h, docs/tune.md): the Pareto fronts of a scene's
 * configurations per family and machine, measured in the simulator, a budget's pick verified at
 * full size, and the outputs (CSV, JSON, Markdown, PNG plot, HTML report, the chosen scene file).
 * Host only; cycles need the simulator build.
 */
#define _XOPEN_SOURCE 700 /* realpath, readlink */
#include "cli/lt_tune_cli.h"

#include "cli/lt_cliutil.h"
#include "cli/lt_opt.h"
#include "io/lt_scenefile.h"
#include "lt_meter.h"
#include "render/lt_paths.h"
#include "tune/lt_pareto.h"
#include "tune/lt_tune.h"

#include <errno.h>
#include <math.h>
#include <sys/personality.h>
#include <sys/stat.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define EXIT_INPUT 1
#define EXIT_USAGE 2
#define MAX_MACH 8

typedef struct tune {
    const char *input, *family, *budget_text, *out, *plan;
    const char *pos[16];
    int merge, job, seen_job;
    const char *mach_names[MAX_MACH];
    int nmach_names, npos, jobs, json, quiet, res, probe_res, seen_res, seen_probe;
    double slack;
    lt_budget_t budget;
    char who[64], outbuf[1100];
    lt_tune_input_t in;
    lt_tune_opts_t o;
    lt_tune_result_t r;
    lt_tune_pick_t picks[LT_TUNE_NFAM];
    lt_tune_server_t *srv;
    double t0;
} tune_t;

static tune_t *g_tune; /* for the progress callback */

/* --machine NAME[,NAME...], repeatable: the names are checked after parsing. */
static int parse_machine(const char *text, void *dest, const void *ctx)
{
    tune_t *t = dest;
    (void)ctx;
    if (t->nmach_names >= MAX_MACH)
        return -1;
    t->mach_names[t->nmach_names++] = text;
    return 0;
}

/* ---- progress (stderr, a TTY only) --------------------------------------------------------- */

static void progress(const char *stage, size_t done, size_t total)
{
    int i, w = 30, fill;
    double el;
    if (g_tune == NULL || g_tune->quiet || !isatty(2))
        return;
    el = lt_now_s() - g_tune->t0;
    fill = total ? (int)((double)w * (double)done / (double)total) : w;
    fprintf(stderr, "\rtune %-9s [", stage);
    for (i = 0; i < w; i++)
        fputc(i < fill ? '#' : ' ', stderr);
    fprintf(stderr, "] %zu/%zu runs, %.0f s ", done, total, el);
    if (done == total)
        fprintf(stderr, "\r%78s\r", "");
}

/* ---- options ------------------------------------------------------------------------------- */

/* t before the options: nothing given, the defaults of a tune. */
static void tune_defaults(tune_t *t)
{
    memset(t, 0, sizeof *t);
    t->jobs = 1;
    t->res = 128;
    t->slack = 0.2;
}

static int tune_parse(tune_t *t, int argc, char **argv, const char *prog)
{
    static char mhelp[256];
    const lt_opt_t opts[] = {
        LT_OPT_STR("--family", "F[,F]", &t->family,
                   "object, screen, shadows or all (default: all for a mesh)"),
        {.name = "--machine", .kind = LT_OPT_CUSTOM, .dest = t, .meta = "M[,M]", .help = mhelp,
         .parse = parse_machine, .expect = "at most 8 --machine options"},
        LT_OPT_STR("--budget", "SPEC", &t->budget_text,
                   "pick the cheapest configuration meeting every bound:\n"
                   "METRIC<=X or METRIC>=X, comma-separated; metrics wrong (%),\n"
                   "rmse, rel99 (%), psnr (dB), cycles, bytes"),
        LT_OPT_INT("--jobs", "N", &t->jobs, 1, 64, "worker processes, {range} (default 1)"),
        LT_OPT_STR("--out", "DIR", &t->out, "output folder (default tune-<input name>)"),
        {.name = "--res", .kind = LT_OPT_INT, .dest = &t->res, .seen = &t->seen_res, .meta = "N",
         .lo = 8, .hi = 1024, .help = "full size, N x N pixels, {range} (default: the scene "
                                      "file's width, else 128)"},
        {.name = "--probe-res", .kind = LT_OPT_INT, .dest = &t->probe_res, .seen = &t->seen_probe,
         .meta = "N", .lo = 0, .hi = 1024,
         .help = "probe size, {range} (default res/4, at least 16; 0: no probes)"},
        LT_OPT_DBL("--slack", "F", &t->slack, 0.0, 10.0,
                   "a probe prunes a configuration only when another one is no\n"
                   "worse in every error and bytes and cheaper by this fraction\n"
                   "of cycles (estimated at full size), {range} (default 0.2)"),
        LT_OPT_FLAG_("--json", &t->json, "the result (front.json's document) on stdout"),
        LT_OPT_SECTION_("beyond one machine (every configuration at full size, no probes):"),
        LT_OPT_STR("--plan", "DIR", &t->plan,
                   "write DIR/jobs.txt (one command per configuration and\n"
                   "machine, for GNU parallel), DIR/tune.slurm (a Slurm array\n"
                   "job of the same lines) and DIR/plan.json; measure nothing"),
        {.name = "--job", .kind = LT_OPT_INT, .dest = &t->job, .seen = &t->seen_job, .meta = "N",
         .lo = 0, .hi = 100000000,
         .help = "measure run N of the configurations into --out DIR/run-N.json\n"
                 "(what a line of jobs.txt does)"},
        LT_OPT_FLAG_("--merge", &t->merge,
                     "the arguments are plan folders: join their results\n"
                     "into the outputs (--out, default DIR/merged); the\n"
                     "front equals tune --probe-res 0's"),
        LT_OPT_FLAG_("-q", &t->quiet, "quiet: no progress, summary lines only"),
        LT_OPT_END_};
    lt_opt_cmd_t cmd = {t->who, "SCENE.json|MESH [options] | --merge DIR...",
                        "Measure every configuration of a scene's families in the simulator "
                        "(cycles per\nphase, structure bytes) with its error against the "
                        "family's reference, prune\ndominated ones with cheap probes, keep the "
                        "Pareto front per family and machine,\nand with --budget pick the "
                        "cheapest configuration that meets it (docs/tune.md).\n",
                        "Exit: 0 ok, 1 input or runtime error or an impossible budget, 2 usage "
                        "or a bad budget.\n",
                        opts, t->pos, 16, &t->npos};
    int rc;
    snprintf(t->who, sizeof t->who, "%s tune", prog);
    snprintf(mhelp, sizeof mhelp, "machine models to tune for, repeatable (default all: %s)",
             lt_meter_machine_names());
    rc = lt_opt_parse(&cmd, argc, argv, 2);
    if (rc == LT_OPT_OK && !t->merge && t->npos > 1) {
        fprintf(stderr, "%s: one input, not %d (%s ...; --merge takes several folders)\n",
                t->who, t->npos, t->pos[1]);
        return LT_OPT_USAGE;
    }
    t->input = t->npos > 0 ? t->pos[0] : NULL;
    return rc;
}

/* --family: comma-separated names or all. 0 or an exit code. */
static int settle_family(tune_t *t)
{
    const char *s = t->family;
    t->o.families = 0;
    if (s == NULL) {
        t->o.families = t->in.mesh[0] != '\0' ? LT_TUNE_ALL : LT_TUNE_SCREEN;
        return 0;
    }
    while (*s != '\0' || t->o.families == 0) {
        size_t n = strcspn(s, ",");
        int f, ok = 0;
        for (f = 0; f < LT_TUNE_NFAM; f++)
            if (n == strlen(lt_tune_family_names[f]) && strncmp(s, lt_tune_family_names[f], n) == 0) {
                t->o.families |= 1u << f;
                ok = 1;
            }
        if (n == 3 && strncmp(s, "all", 3) == 0) {
            t->o.families = LT_TUNE_ALL;
            ok = 1;
        }
        if (!ok) {
            fprintf(stderr, "%s: --family '%s': %s '%.*s' (expected object, screen, shadows or "
                            "all, comma-separated)\n", t->who, t->family,
                    n == 0 ? "empty family" : "unknown family", (int)n, s);
            return EXIT_USAGE;
        }
        s += n;
        if (*s == ',')
            s++;
    }
    return 0;
}

/* --machine: every name known; default all. 0 or an exit code. */
static int settle_machines(tune_t *t)
{
    int i, j;
    t->o.nmach = 0;
    if (t->nmach_names == 0) {
        for (i = 0; lt_meter_machine_name(i) != NULL && i < MAX_MACH; i++)
            t->o.machines[t->o.nmach++] = i;
        return 0;
    }
    for (i = 0; i < t->nmach_names; i++) {
        const char *s = t->mach_names[i];
        do { /* every comma-separated name, an empty one too ('' or 'a,,b') */
            size_t n = strcspn(s, ",");
            int m = -1, dup = 0;
            for (j = 0; lt_meter_machine_name(j) != NULL; j++)
                if (strlen(lt_meter_machine_name(j)) == n && strncmp(lt_meter_machine_name(j), s, n) == 0)
                    m = j;
            if (m < 0) {
                fprintf(stderr, "%s: --machine '%s': %s '%.*s' (known: %s)\n", t->who,
                        t->mach_names[i], n == 0 ? "empty machine name" : "unknown machine",
                        (int)n, s, lt_meter_machine_names());
                return EXIT_USAGE;
            }
            for (j = 0; j < t->o.nmach; j++)
                dup |= t->o.machines[j] == m;
            if (!dup && t->o.nmach < MAX_MACH)
                t->o.machines[t->o.nmach++] = m;
            s += n;
        } while (*s++ == ',');
    }
    return 0;
}

/* The budget metrics each family measures (bits of lt_metric_t). */
static unsigned family_metrics(int fam)
{
    unsigned all = 1u << LT_M_CYCLES;
    if (fam == 0)
        return all | 1u << LT_M_WRONG | 1u << LT_M_RMSE | 1u << LT_M_BYTES;
    if (fam == 1)
        return all | 1u << LT_M_WRONG | 1u << LT_M_RMSE | 1u << LT_M_REL99 | 1u << LT_M_BYTES;
    return all | 1u << LT_M_PSNR;
}

static void metric_names_of(unsigned bits, char *buf, size_t n)
{
    size_t len = 0;
    int m;
    buf[0] = '\0';
    for (m = 0; m < LT_M__COUNT && len < n; m++)
        if (bits & (1u << m))
            len += (size_t)snprintf(buf + len, n - len, "%s%s", len ? ", " : "", lt_metric_names[m]);
}

/* --budget: parsed, and measured by at least one selected family. 0 or an exit code. */
static int settle_budget(tune_t *t)
{
    lt_diag_t d;
    unsigned need = 0, have = 0;
    int i, f, any = 0;
    if (t->budget_text == NULL)
        return 0;
    if (lt_budget_parse(t->budget_text, &t->budget, &d) != 0) {
        fprintf(stderr, "%s: %s\n", t->who, d.msg);
        return EXIT_USAGE;
    }
    for (i = 0; i < t->budget.n; i++)
        need |= 1u << t->budget.t[i].metric;
    for (f = 0; f < LT_TUNE_NFAM; f++) {
        t->picks[f].family = f;
        t->picks[f].pick = t->picks[f].best = -1;
        t->picks[f].binding = -1;
        t->picks[f].applies = (t->o.families & (1u << f)) && (family_metrics(f) & need) == need;
        if (t->o.families & (1u << f))
            have |= family_metrics(f);
        any |= t->picks[f].applies;
    }
    if (any)
        return 0;
    {
        char a[128], b[128];
        metric_names_of(need & ~have, a, sizeof a);
        metric_names_of(have, b, sizeof b);
        fprintf(stderr, "%s: --budget '%s': no selected family measures all of it (%s missing; "
                        "the selected families measure %s)\n", t->who, t->budget_text, a, b);
    }
    return EXIT_USAGE;
}

static int ends_with(const char *s, const char *suf)
{
    size_t a = strlen(s), b = strlen(suf);
    return a >= b && strcmp(s + a - b, suf) == 0;
}

/* The input (scene file, mesh or depth EXR), the sizes and the output folder. 0 or an exit code. */
static int settle_input(tune_t *t)
{
    lt_tune_input_t *in = &t->in;
    const char *base, *dot;
    if (t->input == NULL) {
        fprintf(stderr, "%s: no input (SCENE.json, a mesh or a depth EXR; --help)\n", t->who);
        return EXIT_USAGE;
    }
    memset(in, 0, sizeof *in);
    if (ends_with(t->input, ".json")) {
        lt_scenefile_t sf;
        lt_diag_t d;
        if (lt_sf_load(t->input, &sf, &d) != 0) {
            fprintf(stderr, "%s: %s\n", t->who, d.msg);
            return EXIT_INPUT;
        }
        snprintf(in->scene, sizeof in->scene, "%s", t->input);
        snprintf(in->mesh, sizeof in->mesh, "%s", sf.mesh);
        snprintf(in->depth, sizeof in->depth, "%s", sf.depth);
        in->has_camera = sf.has_camera;
        memcpy(in->eye, sf.eye, sizeof in->eye);
        memcpy(in->target, sf.target, sizeof in->target);
        memcpy(in->up, sf.up, sizeof in->up);
        in->fov = sf.fov_y_deg;
        if (!t->seen_res)
            t->res = (int)(sf.width < 1024 ? sf.width : 1024);
    } else if (ends_with(t->input, ".exr") || ends_with(t->input, ".EXR")) {
        snprintf(in->depth, sizeof in->depth, "%s", t->input);
    } else {
        snprintf(in->mesh, sizeof in->mesh, "%s", t->input);
    }
    if (access(in->mesh[0] ? in->mesh : in->depth, R_OK) != 0) {
        fprintf(stderr, "%s: %s: cannot read the input\n", t->who, in->mesh[0] ? in->mesh : in->depth);
        return EXIT_INPUT;
    }
    if (!t->seen_probe)
        t->probe_res = t->res / 4 < 16 ? 16 : t->res / 4;
    if (t->out == NULL) {
        base = strrchr(t->input, '/');
        base = base != NULL ? base + 1 : t->input;
        dot = strchr(base, '.');
        snprintf(t->outbuf, sizeof t->outbuf, "tune-%.*s", dot ? (int)(dot - base) : (int)strlen(base),
                 base);
        t->out = t->outbuf;
    }
    return 0;
}

/* --out names a folder: a path that exists and is not one (a regular file, a FIFO) is refused
 * before anything is measured, not after the sweep (mkdir's EEXIST let it through, and the
 * first output file failed: "afile/front.csv: cannot create (Not a directory)"). */
static int out_not_folder(const tune_t *t, lt_diag_t *diag)
{
    struct stat st;
    if (stat(t->out, &st) == 0 && !S_ISDIR(st.st_mode))
        return lt_diag_fail(diag, "--out %s: exists and is not a folder (%s)", t->out,
                            S_ISREG(st.st_mode) ? "a regular file" : "a device, FIFO or socket");
    return 0;
}

static int mkdir_out(const tune_t *t, lt_diag_t *diag)
{
    if (mkdir(t->out, 0777) != 0 && errno != EEXIST)
        return lt_diag_fail(diag, "--out %s: cannot create the folder (%s)", t->out, strerror(errno));
    return out_not_folder(t, diag);
}

/* ---- the pick ---------------------------------------------------------------------------- */

/* Re-run point i (its whole run, on a copy: the results stay as measured) at full size, its image
 * to DIR/img-<i>.png. Returns 0 or -1. */
static int verify_point(tune_t *t, long i, lt_tune_meas_t *m, char *img, size_t imgn,
                        lt_diag_t *diag)
{
    lt_tune_point_t *cp = malloc(t->r.np * sizeof *cp);
    char prefix[1100];
    int run, rc;
    if (cp == NULL)
        return lt_diag_fail(diag, "out of memory");
    memcpy(cp, t->r.pts, t->r.np * sizeof *cp);
    snprintf(prefix, sizeof prefix, "%s/img", t->out);
    run = cp[i].run;
    rc = lt_tune_server_run(t->srv, cp, t->r.np, &run, 1, 1, 1, prefix, NULL, "verify", diag);
    *m = cp[i].full;
    snprintf(img, imgn, "%s-%ld.png", prefix, i);
    free(cp);
    return rc;
}

/* "wrong 0.12%, rmse 0.0031": the best value of every budget metric over a family's points. */
static void best_values(const tune_t *t, int fam, char *buf, size_t n)
{
    size_t len = 0, i;
    int j;
    buf[0] = '\0';
    for (j = 0; j < t->budget.n && len < n; j++) {
        int m = t->budget.t[j].metric, hb = lt_metric_higher_better(m);
        double best = NAN;
        for (i = 0; i < t->r.np; i++) {
            double v = t->r.pts[i].full.m[m];
            if (!t->r.pts[i].full.ok || t->r.pts[i].k.family != fam || isnan(v))
                continue;
            if (isnan(best) || (hb ? v > best : v < best))
                best = v;
        }
        len += (size_t)snprintf(buf + len, n - len, "%s%s %.6g%s", j ? ", " : "", lt_metric_names[m],
                                best, lt_metric_is_percent(m) ? "%" : "");
    }
}

/* The pick of family f, its verification, the most accurate point's image, the scene file. */
static int pick_family(tune_t *t, int f, lt_diag_t *diag)
{
    lt_tune_pick_t *k = &t->picks[f];
    unsigned char *inc = NULL;
    double *rows = lt_tune_metric_rows(t->r.pts, t->r.np, f, &inc);
    lt_tune_meas_t mb;
    if (rows == NULL)
        return lt_diag_fail(diag, "out of memory");
    k->pick = lt_budget_pick(&t->budget, rows, t->r.np, inc);
    k->binding = lt_budget_binding(&t->budget, rows, t->r.np, inc, k->pick);
    k->best = lt_tune_most_accurate(t->r.pts, t->r.np, f);
    free(rows);
    free(inc);
    if (k->pick < 0)
        return 0;
    if (verify_point(t, k->pick, &k->verify, k->img_pick, sizeof k->img_pick, diag) != 0 ||
        (k->best >= 0 && verify_point(t, k->best, &mb, k->img_best, sizeof k->img_best, diag) != 0))
        return -1;
    k->verified = k->verify.ok && lt_budget_meets(&t->budget, k->verify.m, NULL);
    snprintf(k->scene, sizeof k->scene, "%s/chosen-%s.json", t->out, lt_tune_family_names[f]);
    return lt_tune_write_scene(k->scene, &t->in, &t->r.pts[k->pick], (uint32_t)t->res, diag);
}

/* A metric's value as printed: "0.123%", "3019963", "41.2 dB". */
static void metric_text(int m, double v, char *buf, size_t n)
{
    if (isnan(v))
        snprintf(buf, n, "-");
    else if (m == LT_M_CYCLES || m == LT_M_BYTES)
        snprintf(buf, n, "%.0f", v);
    else if (m == LT_M_PSNR)
        snprintf(buf, n, "%.2f dB", v);
    else
        snprintf(buf, n, "%.4g%s", v, lt_metric_is_percent(m) ? "%" : "");
}

static void print_pick(const tune_t *t, int f)
{
    const lt_tune_pick_t *k = &t->picks[f];
    const lt_tune_point_t *pts = t->r.pts;
    char kt[160], v[160];
    int j;
    lt_tune_knobs_text(&pts[k->pick].k, kt, sizeof kt);
    printf("pick      %s: %s on %s\n", lt_tune_family_names[f], kt,
           lt_meter_machine_name(pts[k->pick].k.machine));
    printf("verified  %s: re-run at %u px:", lt_tune_family_names[f], k->verify.res);
    for (j = 0; j < t->budget.n; j++) {
        int m = t->budget.t[j].metric;
        metric_text(m, k->verify.m[m], v, sizeof v);
        printf("%s %s %s (%s %g)", j ? "," : "", lt_metric_names[m], v,
               t->budget.t[j].ge ? ">=" : "<=", t->budget.t[j].bound);
    }
    printf(": %s\n", k->verified ? "meets the budget" : "FAILS the budget");
    lt_budget_binding_text(&t->budget, k->binding, v, sizeof v);
    printf("binding   %s: %s\n", lt_tune_family_names[f],
           k->binding == -1 ? "none (the cheapest configuration measured meets the budget)" : v);
    if (k->best >= 0) {
        double cb = pts[k->best].full.m[LT_M_CYCLES], cp = k->verify.m[LT_M_CYCLES];
        lt_tune_knobs_text(&pts[k->best].k, kt, sizeof kt);
        printf("saved     %s: %.0f cycles (%.1f%%) against the most accurate, %s on %s (%.0f "
               "cycles)\n", lt_tune_family_names[f], cb - cp, cb > 0 ? 100.0 * (cb - cp) / cb : 0.0,
               kt, lt_meter_machine_name(pts[k->best].k.machine), cb);
    }
    printf("scene     %s\n", k->scene);
}

/* ---- the summary ----------------------------------------------------------------------------- */

static void print_fronts(const tune_t *t)
{
    const lt_tune_point_t *pts = t->r.pts;
    int f, mi;
    size_t i;
    for (f = 0; f < LT_TUNE_NFAM; f++)
        for (mi = 0; mi < t->o.nmach; mi++) {
            long lo = -1, n = 0;
            char kt[160];
            if (!(t->o.families & (1u << f)))
                continue;
            for (i = 0; i < t->r.np; i++)
                if (pts[i].front && pts[i].k.family == f && pts[i].k.machine == t->o.machines[mi]) {
                    n++;
                    if (lo < 0 || pts[i].full.m[LT_M_CYCLES] < pts[lo].full.m[LT_M_CYCLES])
                        lo = (long)i;
                }
            if (lo < 0)
                continue;
            lt_tune_knobs_text(&pts[lo].k, kt, sizeof kt);
            printf("front     %-7s %-7s %2ld points; cheapest %s: %.0f cycles (%.1f/px)\n",
                   lt_tune_family_names[f], lt_meter_machine_name(t->o.machines[mi]), n, kt,
                   pts[lo].full.m[LT_M_CYCLES],
                   pts[lo].full.m[LT_M_CYCLES] / ((double)t->res * t->res));
        }
}

static void print_summary(const tune_t *t, double secs)
{
    const lt_tune_result_t *r = &t->r;
    int f;
    printf("tune      %s: %zu configurations of", t->input, r->np);
    for (f = 0; f < LT_TUNE_NFAM; f++)
        if (t->o.families & (1u << f))
            printf(" %s", lt_tune_family_names[f]);
    printf(" on %d machine(s)\n", t->o.nmach);
    if (r->q16_note[0] != '\0')
        printf("note      s15.16 left out, the scene runs on float32: %s\n", r->q16_note);
    printf("search    %zu probed at %u px (%.1f s), %zu pruned as dominated, %zu measured at %d px "
           "(%.1f s), %zu failed; %.1f s in all, --jobs %d\n",
           r->probed, t->o.probe_res, r->secs_probe, r->pruned, r->measured, t->res, r->secs_full,
           r->failed, secs, t->o.jobs);
    for (f = 0; f < LT_TUNE_NFAM; f++)
        if (t->o.families & (1u << f))
            printf("family    %-7s %zu measurements, %.1f s of measuring\n", lt_tune_family_names[f],
                   r->fam_points[f], r->fam_secs[f]);
    print_fronts(t);
}

/* The picks of a budget: 0, EXIT_INPUT when it is impossible for a family, -1 on an error. */
static int do_budget(tune_t *t, lt_diag_t *diag)
{
    char bt[512], best[512];
    int f, impossible = 0;
    lt_budget_text(&t->budget, bt, sizeof bt);
    if (!t->json)
        printf("budget    %s\n", bt);
    for (f = 0; f < LT_TUNE_NFAM; f++) {
        if (!t->picks[f].applies)
            continue;
        if (pick_family(t, f, diag) != 0)
            return -1;
        if (t->picks[f].pick < 0) {
            best_values(t, f, best, sizeof best);
            fprintf(stderr, "%s: budget '%s' is impossible for %s: the best achievable values are "
                            "%s (each on its own)\n", t->who, bt, lt_tune_family_names[f], best);
            impossible = 1;
        } else if (!t->json) {
            print_pick(t, f);
        }
    }
    return impossible ? EXIT_INPUT : 0;
}

/* The same memory layout in every process: the cycle model charges memory it has no fixed
 * simulated address for (the soft-shadow renderer's per-pixel buffers) at its real address, and
 * address-space randomisation would move it by whole pages, so two processes (a --jobs worker
 * and a --job of a plan) could see different cache conflicts. Re-run this program once with
 * randomisation off (personality ADDR_NO_RANDOMIZE, what `setarch -R` does); where that is not
 * allowed, go on as it is. */
static void fixed_layout(char **argv)
{
    int p = personality(0xffffffffUL);
    if (p == -1 || (p & ADDR_NO_RANDOMIZE) != 0)
        return;
    if (personality((unsigned long)p | ADDR_NO_RANDOMIZE) == -1)
        return;
    execv("/proc/self/exe", argv);
    (void)personality((unsigned long)p); /* exec failed: carry on as we were */
}

/* The budget's picks (verified through the server, started here when the caller has none) and
 * the outputs. Returns the exit code. */
static int finish(tune_t *t)
{
    lt_diag_t d;
    lt_tune_report_t rep;
    int rc = 0;
    if (t->budget_text != NULL && t->srv == NULL) {
        char note[256];
        t->srv = lt_tune_server_start(&t->in, &t->o, note, sizeof note, &d);
        if (t->srv == NULL) {
            fprintf(stderr, "%s: %s\n", t->who, d.msg);
            return EXIT_INPUT;
        }
    }
    if (mkdir_out(t, &d) != 0 || (t->budget_text != NULL && (rc = do_budget(t, &d)) < 0)) {
        fprintf(stderr, "%s: %s\n", t->who, d.msg);
        return EXIT_INPUT;
    }
    memset(&rep, 0, sizeof rep);
    rep.title = t->input;
    rep.in = &t->in;
    rep.opts = &t->o;
    rep.res = &t->r;
    rep.budget = t->budget_text != NULL ? &t->budget : NULL;
    rep.picks = t->picks;
    rep.secs = lt_now_s() - t->t0;
    if (lt_tune_write_outputs(t->out, &rep, &d) != 0) {
        fprintf(stderr, "%s: %s\n", t->who, d.msg);
        return EXIT_INPUT;
    }
    if (t->json) {
        char *js = lt_tune_json(&rep);
        if (js != NULL)
            puts(js);
        free(js);
    } else {
        printf("outputs   %s/front.csv front.json front.md front.png report.html\n", t->out);
    }
    return rc;
}

/* The options into t->o; the timer. */
static void settle_opts(tune_t *t)
{
    if (!lt_meter_available())
        fprintf(stderr, "%s: the native build has no cycle model: every cycle count is 0 "
                        "(build/sim/lanetrace tune measures them)\n", t->who);
    t->o.res = (uint32_t)t->res;
    t->o.probe_res = (uint32_t)t->probe_res;
    t->o.slack = t->slack;
    t->o.jobs = t->jobs;
    t->o.progress = progress;
    g_tune = t;
    t->t0 = lt_now_s();
}

/* The plan's facts from the settled options (families as text, machine names, runs). */
static int plan_facts(tune_t *t, lt_tune_plan_t *p, lt_diag_t *d)
{
    lt_tune_point_t *pts = NULL;
    size_t np = 0;
    int f, m;
    memset(p, 0, sizeof *p);
    if (realpath(t->input, p->input) == NULL)
        snprintf(p->input, sizeof p->input, "%s", t->input);
    for (f = 0; f < LT_TUNE_NFAM; f++)
        if (t->o.families & (1u << f))
            snprintf(p->families + strlen(p->families), sizeof p->families - strlen(p->families),
                     "%s%s", p->families[0] ? "," : "", lt_tune_family_names[f]);
    for (m = 0; m < t->o.nmach; m++)
        snprintf(p->machines[p->nmach++], 32, "%s", lt_meter_machine_name(t->o.machines[m]));
    p->res = t->o.res;
    snprintf(p->q16_note, sizeof p->q16_note, "%s", t->r.q16_note);
    if (lt_tune_enumerate(t->o.families, t->o.machines, t->o.nmach, p->q16_note[0] != '\0', &pts,
                          &np, d) != 0)
        return -1;
    p->nruns = np > 0 ? (size_t)pts[np - 1].run + 1 : 0;
    free(pts);
    return 0;
}

/* --plan DIR: the job list, the Slurm script, plan.json. */
static int tune_plan(tune_t *t)
{
    lt_tune_plan_t p;
    lt_diag_t d;
    char exe[1024];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    exe[n > 0 ? n : 0] = '\0';
    if (plan_facts(t, &p, &d) != 0 || lt_tune_write_plan(t->plan, exe, &p, &d) != 0) {
        fprintf(stderr, "%s: %s\n", t->who, d.msg);
        return EXIT_INPUT;
    }
    printf("plan      %zu jobs (configurations x machines of %s at %u px): %s/jobs.txt\n", p.nruns,
           p.families, p.res, t->plan);
    printf("run       parallel --jobs 2 < %s/jobs.txt   (or: sbatch %s/tune.slurm)\n", t->plan,
           t->plan);
    printf("merge     %s --merge %s [--budget ...]\n", t->who, t->plan);
    return 0;
}

/* --job N: measure run N at full size into --out DIR/run-N.json. */
static int tune_job(tune_t *t)
{
    lt_diag_t d;
    char path[1200];
    int run = t->job, rc;
    if (t->seen_probe == 0)
        t->o.probe_res = 0;
    if (lt_tune_enumerate(t->o.families, t->o.machines, t->o.nmach, t->r.q16_note[0] != '\0',
                          &t->r.pts, &t->r.np, &d) != 0) {
        fprintf(stderr, "%s: %s\n", t->who, d.msg);
        return EXIT_INPUT;
    }
    if (t->r.np == 0 || run > t->r.pts[t->r.np - 1].run) {
        fprintf(stderr, "%s: --job %d is out of range [0, %d] (the runs of these families and "
                        "machines)\n", t->who, run, t->r.np ? t->r.pts[t->r.np - 1].run : -1);
        return EXIT_USAGE;
    }
    snprintf(path, sizeof path, "%s/run-%d.json", t->out, run);
    rc = mkdir_out(t, &d) != 0 ||
         lt_tune_server_run(t->srv, t->r.pts, t->r.np, &run, 1, 1, 1, NULL, NULL, "job", &d) != 0 ||
         lt_tune_write_job(path, t->r.pts, t->r.np, run, &d) != 0;
    if (rc != 0) {
        fprintf(stderr, "%s: %s\n", t->who, d.msg);
        return EXIT_INPUT;
    }
    if (!t->quiet)
        printf("job       %d: %s\n", run, path);
    return 0;
}

/* --merge DIR...: the plan of the first folder, the results of all, the fronts, the outputs. */
static int tune_merge(tune_t *t)
{
    lt_tune_plan_t p;
    lt_diag_t d;
    unsigned char *seen;
    size_t r, missing = 0, first = 0;
    int i, rc;
    if (t->npos < 1 || lt_tune_read_plan(t->pos[0], &p, &d) != 0) {
        fprintf(stderr, "%s: --merge %s\n", t->who, t->npos < 1 ? "needs plan folders" : d.msg);
        return t->npos < 1 ? EXIT_USAGE : EXIT_INPUT;
    }
    t->input = p.input;
    t->family = p.families;
    for (i = 0; i < p.nmach; i++)
        t->mach_names[i] = p.machines[i];
    t->nmach_names = p.nmach;
    t->res = (int)p.res;
    t->seen_res = t->seen_probe = 1;
    t->probe_res = 0;
    if (t->out == NULL) {
        snprintf(t->outbuf, sizeof t->outbuf, "%s/merged", t->pos[0]);
        t->out = t->outbuf;
    }
    if ((rc = settle_input(t)) != 0 || (rc = settle_family(t)) != 0 ||
        (rc = settle_machines(t)) != 0 || (rc = settle_budget(t)) != 0)
        return rc;
    settle_opts(t);
    snprintf(t->r.q16_note, sizeof t->r.q16_note, "%s", p.q16_note);
    seen = calloc(p.nruns ? p.nruns : 1, 1);
    if (seen == NULL || lt_tune_enumerate(t->o.families, t->o.machines, t->o.nmach,
                                          p.q16_note[0] != '\0', &t->r.pts, &t->r.np, &d) != 0) {
        free(seen);
        fprintf(stderr, "%s: %s\n", t->who, seen == NULL ? "out of memory" : d.msg);
        return EXIT_INPUT;
    }
    for (i = 0; i < t->npos; i++)
        if (lt_tune_read_results(t->pos[i], t->r.pts, t->r.np, seen, p.nruns, &d) < 0) {
            free(seen);
            fprintf(stderr, "%s: %s\n", t->who, d.msg);
            return EXIT_INPUT;
        }
    for (r = 0; r < p.nruns; r++)
        if (!seen[r] && missing++ == 0)
            first = r;
    free(seen);
    if (missing > 0) {
        fprintf(stderr, "%s: --merge: %zu of the plan's %zu runs have no result (the first: run "
                        "%zu, line %zu of %s/jobs.txt)\n", t->who, missing, p.nruns, first,
                first + 1, t->pos[0]);
        return EXIT_INPUT;
    }
    lt_tune_mark_fronts(t->r.pts, t->r.np);
    lt_tune_tally(&t->r);
    if (!t->json)
        print_summary(t, lt_now_s() - t->t0);
    return finish(t);
}

int lt_tune_cli(int argc, char **argv, const char *prog)
{
    tune_t t;
    lt_diag_t d;
    int rc;
    fixed_layout(argv);
    tune_defaults(&t);
    rc = tune_parse(&t, argc, argv, prog);
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    if (t.merge) {
        rc = tune_merge(&t);
    } else {
        if ((rc = settle_input(&t)) != 0 || (rc = settle_family(&t)) != 0 ||
            (rc = settle_machines(&t)) != 0 || (rc = settle_budget(&t)) != 0)
            return rc;
        settle_opts(&t);
        if (t.plan != NULL || t.seen_job)
            t.o.probe_res = 0; /* a plan measures every configuration at full size */
        if (t.plan == NULL && out_not_folder(&t, &d) != 0) {
            fprintf(stderr, "%s: %s\n", t.who, d.msg);
            return EXIT_INPUT;
        }
        t.srv = lt_tune_server_start(&t.in, &t.o, t.r.q16_note, sizeof t.r.q16_note, &d);
        if (t.srv == NULL) {
            fprintf(stderr, "%s: %s\n", t.who, d.msg);
            return EXIT_INPUT;
        }
        if (t.plan != NULL)
            rc = tune_plan(&t);
        else if (t.seen_job)
            rc = tune_job(&t);
        else if (lt_tune_search(t.srv, &t.o, &t.r, &d) != 0) {
            fprintf(stderr, "%s: %s\n", t.who, d.msg);
            rc = EXIT_INPUT;
        } else {
            if (!t.json)
                print_summary(&t, lt_now_s() - t.t0);
            rc = finish(&t);
        }
    }
    lt_tune_server_stop(t.srv);
    lt_tune_result_free(&t.r);
    return rc;
}
