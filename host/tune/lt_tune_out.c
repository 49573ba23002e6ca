/* lt_tune_out.c - what lanetrace tune writes (lt_tune.h): the points as CSV, JSON and a Markdown
 * table, the error-vs-cycles plot (gnuplot), one self-contained HTML report, and the chosen
 * configuration as a scene file. Host only.
 */
#define _XOPEN_SOURCE 700 /* realpath */
#include "tune/lt_tune.h"
#include "io/lt_scenefile.h"

#include "lt_meter.h"
#include "render/lt_paths.h"
#include "render/lt_render.h"
#include "render/lt_reproject.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static const char *const phase_names[] = {
#define LT_OP(name, unit, doc)
#define LT_EV(name, doc)
#define LT_PH(name, doc) #name,
#include "lt/lt_ops.def"
#undef LT_OP
#undef LT_EV
#undef LT_PH
};

static const char *const tracer_names[] = {"quadtree", "dda", "hiz"};

/* 1 when a's errors are better than b's (lexicographic on the family's error objectives, then
 * fewer cycles). */
static int more_accurate(const lt_tune_point_t *a, const lt_tune_point_t *b)
{
    double x[3], y[3];
    int i;
    (void)lt_tune_objectives(a->k.family, &a->full, x);
    (void)lt_tune_objectives(b->k.family, &b->full, y);
    for (i = 1; i < 3; i++)
        if (x[i] != y[i] && !(isnan(x[i]) && isnan(y[i])))
            return isnan(y[i]) || (!isnan(x[i]) && x[i] < y[i]);
    return x[0] < y[0];
}

long lt_tune_most_accurate(const lt_tune_point_t *pts, size_t np, int family)
{
    long best = -1;
    size_t i;
    for (i = 0; i < np; i++)
        if (pts[i].full.ok && pts[i].k.family == family &&
            (best < 0 || more_accurate(&pts[i], &pts[best])))
            best = (long)i;
    return best;
}

double *lt_tune_metric_rows(const lt_tune_point_t *pts, size_t np, int family,
                            unsigned char **include)
{
    double *v = malloc((np ? np : 1) * LT_M__COUNT * sizeof *v);
    size_t i;
    int m;
    *include = malloc(np ? np : 1);
    if (v == NULL || *include == NULL) {
        free(v);
        free(*include);
        *include = NULL;
        return NULL;
    }
    for (i = 0; i < np; i++) {
        for (m = 0; m < LT_M__COUNT; m++)
            v[i * LT_M__COUNT + (size_t)m] = pts[i].full.ok ? pts[i].full.m[m] : (double)NAN;
        (*include)[i] = pts[i].full.ok && pts[i].k.family == family;
    }
    return v;
}

/* ---- CSV ------------------------------------------------------------------------------------- */

static void num(FILE *f, double v, const char *sep)
{
    if (isnan(v))
        fprintf(f, "%s", sep);
    else
        fprintf(f, "%.9g%s", v, sep);
}

static int is_pick(const lt_tune_report_t *rep, size_t i)
{
    int f;
    if (rep->picks == NULL)
        return 0;
    for (f = 0; f < LT_TUNE_NFAM; f++)
        if (rep->picks[f].pick == (long)i)
            return 1;
    return 0;
}

static int write_csv(const char *path, const lt_tune_report_t *rep, lt_diag_t *diag)
{
    const lt_tune_result_t *r = rep->res;
    FILE *f = fopen(path, "w");
    size_t i;
    int m, ph;
    if (f == NULL)
        return lt_diag_fail(diag, "%s: cannot create (%s)", path, strerror(errno));
    fprintf(f, "id,family,machine,path,structure,leaf,layers,gamma,primary,shadow,filter,cull,spp,"
               "isect,knobs,status,res,");
    for (m = 0; m < LT_M__COUNT; m++)
        fprintf(f, "%s,", lt_metric_names[m]);
    fprintf(f, "maxerr,rel50,within1,off,");
    for (ph = 0; ph < LT_PH__COUNT; ph++)
        fprintf(f, "cycles_%s,", phase_names[ph]);
    fprintf(f, "probe_res,probe_cycles,probe_err1,probe_err2,front,pick\n");
    for (i = 0; i < r->np; i++) {
        const lt_tune_point_t *p = &r->pts[i];
        const lt_tune_meas_t *x = p->full.ok ? &p->full : &p->probe;
        double po[3];
        char kt[160];
        lt_tune_knobs_text(&p->k, kt, sizeof kt);
        (void)lt_tune_objectives(p->k.family, &p->probe, po);
        fprintf(f, "%zu,%s,%s,%s,%s,%d,%d,%s,%s,%s,%s,%s,%s,%s,\"%s\",%s,%u,", i,
                lt_tune_family_names[p->k.family], lt_meter_machine_name(p->k.machine),
                lt_paths[p->k.path].name,
                p->k.family == 0   ? lt_render_structures[p->k.structure]
                : p->k.family == 1 ? tracer_names[p->k.structure] : "frusta-bvh",
                p->k.leaf, p->k.layers, p->k.family == 1 ? lt_tune_gammas[p->k.gamma].name : "",
                p->k.family == 2 ? (p->k.prim ? "frusta" : "packet") : "",
                p->k.family == 2 ? (p->k.shadow ? "packet" : "frusta") : "",
                p->k.family == 2 ? (p->k.filter ? "on" : "off") : "",
                p->k.family == 2 ? lt_tune_cull_names[p->k.cull] : "",
                p->k.family == 2 ? (p->k.spp == 4 ? "4" : p->k.spp == 8 ? "8" : p->k.spp == 32 ? "32" : "16") : "",
                p->k.family == 0 ? lt_sf_isects[p->k.isect] : "", kt,
                p->full.ok ? "full" : (p->pruned && p->probe.ok ? "pruned" : "failed"), x->res);
        for (m = 0; m < LT_M__COUNT; m++)
            num(f, x->m[m], ",");
        num(f, x->maxerr, ",");
        num(f, x->rel50, ",");
        num(f, x->within, ",");
        num(f, x->off, ",");
        for (ph = 0; ph < LT_PH__COUNT; ph++)
            num(f, x->ok ? x->phase[ph] : (double)NAN, ",");
        fprintf(f, "%u,", p->probe.res);
        num(f, p->probe.ok ? po[0] : (double)NAN, ",");
        num(f, p->probe.ok ? po[1] : (double)NAN, ",");
        num(f, p->probe.ok ? po[2] : (double)NAN, ",");
        fprintf(f, "%d,%d\n", p->front, is_pick(rep, i));
    }
    if (fclose(f) != 0)
        return lt_diag_fail(diag, "%s: write failed", path);
    return 0;
}

/* ---- JSON ------------------------------------------------------------------------------------ */

static void jnum(cJSON *o, const char *k, double v)
{
    if (isnan(v) || isinf(v))
        cJSON_AddNullToObject(o, k);
    else
        cJSON_AddNumberToObject(o, k, v);
}

cJSON *lt_tune_meas_json(const lt_tune_meas_t *x)
{
    cJSON *o = cJSON_CreateObject(), *mm, *ph;
    int m, i;
    cJSON_AddNumberToObject(o, "res", x->res);
    cJSON_AddBoolToObject(o, "ok", x->ok);
    if (!x->ok) {
        cJSON_AddStringToObject(o, "error", x->msg);
        return o;
    }
    mm = cJSON_AddObjectToObject(o, "metrics");
    for (m = 0; m < LT_M__COUNT; m++)
        jnum(mm, lt_metric_names[m], x->m[m]);
    jnum(mm, "maxerr", x->maxerr);
    jnum(mm, "rel50", x->rel50);
    jnum(mm, "within1", x->within);
    jnum(mm, "off", x->off);
    ph = cJSON_AddObjectToObject(o, "phases");
    for (i = 0; i < LT_PH__COUNT; i++)
        jnum(ph, phase_names[i], x->phase[i]);
    jnum(o, "host_s", x->secs);
    return o;
}

/* A number member (null: NaN); missing: NaN. */
static double jget(const cJSON *o, const char *k)
{
    const cJSON *x = cJSON_GetObjectItemCaseSensitive(o, k);
    return cJSON_IsNumber(x) ? x->valuedouble : (double)NAN;
}

int lt_tune_meas_from_json(const cJSON *o, lt_tune_meas_t *x)
{
    const cJSON *mm, *ph, *ok, *err;
    int m, i;
    memset(x, 0, sizeof *x);
    if (!cJSON_IsObject(o) || !cJSON_IsNumber(cJSON_GetObjectItemCaseSensitive(o, "res")))
        return -1;
    x->res = (uint32_t)jget(o, "res");
    ok = cJSON_GetObjectItemCaseSensitive(o, "ok");
    x->ok = cJSON_IsTrue(ok);
    if (!x->ok) {
        err = cJSON_GetObjectItemCaseSensitive(o, "error");
        snprintf(x->msg, sizeof x->msg, "%s", cJSON_IsString(err) ? err->valuestring : "failed");
        return 0;
    }
    mm = cJSON_GetObjectItemCaseSensitive(o, "metrics");
    ph = cJSON_GetObjectItemCaseSensitive(o, "phases");
    if (!cJSON_IsObject(mm) || !cJSON_IsObject(ph))
        return -1;
    for (m = 0; m < LT_M__COUNT; m++)
        x->m[m] = jget(mm, lt_metric_names[m]);
    x->maxerr = jget(mm, "maxerr");
    x->rel50 = jget(mm, "rel50");
    x->within = jget(mm, "within1");
    x->off = jget(mm, "off");
    for (i = 0; i < LT_PH__COUNT; i++)
        x->phase[i] = jget(ph, phase_names[i]);
    x->secs = jget(o, "host_s");
    return 0;
}

static cJSON *knobs_json(const lt_tune_knobs_t *k)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "family", lt_tune_family_names[k->family]);
    cJSON_AddStringToObject(o, "machine", lt_meter_machine_name(k->machine));
    cJSON_AddStringToObject(o, "path", lt_paths[k->path].name);
    if (k->family == 0) {
        cJSON_AddStringToObject(o, "structure", lt_render_structures[k->structure]);
        cJSON_AddNumberToObject(o, "leaf", k->leaf);
        cJSON_AddStringToObject(o, "isect", lt_sf_isects[k->isect]);
    } else if (k->family == 1) {
        cJSON_AddStringToObject(o, "tracer", tracer_names[k->structure]);
        cJSON_AddNumberToObject(o, "layers", k->layers);
        if (k->structure == LT_RP_QUADTREE) {
            cJSON_AddStringToObject(o, "gamma", lt_tune_gammas[k->gamma].name);
            cJSON_AddNumberToObject(o, "gamma_norm", lt_tune_gammas[k->gamma].gamma_norm);
            cJSON_AddNumberToObject(o, "gamma_dist", lt_tune_gammas[k->gamma].gamma_dist);
        }
    } else {
        cJSON_AddNumberToObject(o, "leaf", k->leaf);
        cJSON_AddStringToObject(o, "primary", k->prim ? "frusta" : "packet");
        cJSON_AddStringToObject(o, "shadow", k->shadow ? "packet" : "frusta");
        cJSON_AddBoolToObject(o, "filter", k->filter);
        cJSON_AddStringToObject(o, "cull", lt_tune_cull_names[k->cull]);
        cJSON_AddNumberToObject(o, "spp", k->spp ? k->spp : 16);
    }
    return o;
}

static cJSON *point_json(const lt_tune_report_t *rep, size_t i)
{
    const lt_tune_point_t *p = &rep->res->pts[i];
    cJSON *o = cJSON_CreateObject();
    char kt[160];
    lt_tune_knobs_text(&p->k, kt, sizeof kt);
    cJSON_AddNumberToObject(o, "id", (double)i);
    cJSON_AddStringToObject(o, "text", kt);
    cJSON_AddItemToObject(o, "knobs", knobs_json(&p->k));
    cJSON_AddStringToObject(o, "status", p->full.ok ? "full"
                                         : (p->pruned && p->probe.ok ? "pruned" : "failed"));
    if (p->probe.res != 0)
        cJSON_AddItemToObject(o, "probe", lt_tune_meas_json(&p->probe));
    if (p->full.res != 0)
        cJSON_AddItemToObject(o, "full", lt_tune_meas_json(&p->full));
    cJSON_AddBoolToObject(o, "front", p->front);
    cJSON_AddBoolToObject(o, "pick", is_pick(rep, i));
    return o;
}

static cJSON *picks_json(const lt_tune_report_t *rep)
{
    cJSON *a = cJSON_CreateArray();
    char bt[512];
    int f;
    for (f = 0; f < LT_TUNE_NFAM; f++) {
        const lt_tune_pick_t *k = &rep->picks[f];
        const lt_tune_point_t *pts = rep->res->pts;
        cJSON *o;
        if (!(rep->opts->families & (1u << f)) || !k->applies)
            continue;
        o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "family", lt_tune_family_names[f]);
        lt_budget_text(rep->budget, bt, sizeof bt);
        cJSON_AddStringToObject(o, "budget", bt);
        if (k->pick >= 0) {
            cJSON_AddNumberToObject(o, "id", (double)k->pick);
            cJSON_AddItemToObject(o, "knobs", knobs_json(&pts[k->pick].k));
            cJSON_AddItemToObject(o, "verification", lt_tune_meas_json(&k->verify));
            cJSON_AddBoolToObject(o, "verified", k->verified);
            if (k->binding != -1) {
                char bt2[160];
                lt_budget_binding_text(rep->budget, k->binding, bt2, sizeof bt2);
                cJSON_AddStringToObject(o, "binding", bt2);
            } else {
                cJSON_AddNullToObject(o, "binding");
            }
            cJSON_AddStringToObject(o, "scene", k->scene);
        } else {
            cJSON_AddNullToObject(o, "id");
        }
        if (k->best >= 0) {
            cJSON_AddNumberToObject(o, "most_accurate_id", (double)k->best);
            if (k->pick >= 0)
                cJSON_AddNumberToObject(o, "cycles_saved",
                                        pts[k->best].full.m[LT_M_CYCLES] - k->verify.m[LT_M_CYCLES]);
        }
        cJSON_AddItemToArray(a, o);
    }
    return a;
}

char *lt_tune_json(const lt_tune_report_t *rep)
{
    const lt_tune_result_t *r = rep->res;
    cJSON *o = cJSON_CreateObject(), *a, *c;
    char *s;
    size_t i;
    int f;
    cJSON_AddStringToObject(o, "tool", "lanetrace tune");
    cJSON_AddStringToObject(o, "input", rep->title);
    a = cJSON_AddArrayToObject(o, "families");
    for (f = 0; f < LT_TUNE_NFAM; f++)
        if (rep->opts->families & (1u << f))
            cJSON_AddItemToArray(a, cJSON_CreateString(lt_tune_family_names[f]));
    a = cJSON_AddArrayToObject(o, "machines");
    for (f = 0; f < rep->opts->nmach; f++)
        cJSON_AddItemToArray(a, cJSON_CreateString(lt_meter_machine_name(rep->opts->machines[f])));
    cJSON_AddNumberToObject(o, "res", rep->opts->res);
    cJSON_AddNumberToObject(o, "probe_res", rep->opts->probe_res);
    cJSON_AddNumberToObject(o, "jobs", rep->opts->jobs);
    jnum(o, "seconds", rep->secs);
    c = cJSON_AddObjectToObject(o, "counts");
    cJSON_AddNumberToObject(c, "points", (double)r->np);
    cJSON_AddNumberToObject(c, "probed", (double)r->probed);
    cJSON_AddNumberToObject(c, "pruned", (double)r->pruned);
    cJSON_AddNumberToObject(c, "full", (double)r->measured);
    cJSON_AddNumberToObject(c, "failed", (double)r->failed);
    cJSON_AddNumberToObject(c, "front", (double)r->front);
    c = cJSON_AddObjectToObject(o, "family_seconds");
    for (f = 0; f < LT_TUNE_NFAM; f++)
        if (rep->opts->families & (1u << f))
            jnum(c, lt_tune_family_names[f], r->fam_secs[f]);
    c = cJSON_AddObjectToObject(o, "family_measurements");
    for (f = 0; f < LT_TUNE_NFAM; f++)
        if (rep->opts->families & (1u << f))
            cJSON_AddNumberToObject(c, lt_tune_family_names[f], (double)r->fam_points[f]);
    if (r->q16_note[0] != '\0')
        cJSON_AddStringToObject(o, "q16_left_out", r->q16_note);
    if (rep->budget != NULL && rep->picks != NULL)
        cJSON_AddItemToObject(o, "picks", picks_json(rep));
    a = cJSON_AddArrayToObject(o, "points");
    for (i = 0; i < r->np; i++)
        cJSON_AddItemToArray(a, point_json(rep, i));
    s = cJSON_Print(o);
    cJSON_Delete(o);
    return s;
}

static int write_text(const char *path, const char *text, lt_diag_t *diag)
{
    FILE *f = fopen(path, "w");
    if (f == NULL)
        return lt_diag_fail(diag, "%s: cannot create (%s)", path, strerror(errno));
    if (fputs(text, f) < 0) {
        fclose(f);
        return lt_diag_fail(diag, "%s: write failed", path);
    }
    return fclose(f) == 0 ? 0 : lt_diag_fail(diag, "%s: write failed", path);
}

/* ---- Markdown ------------------------------------------------------------------------------- */

/* Indices of the front points of (family, machine) sorted by cycles into idx; returns how many. */
static size_t front_sorted(const lt_tune_result_t *r, int fam, int mach, size_t *idx)
{
    size_t i, j, n = 0;
    for (i = 0; i < r->np; i++)
        if (r->pts[i].front && r->pts[i].k.family == fam && r->pts[i].k.machine == mach)
            idx[n++] = i;
    for (i = 1; i < n; i++)
        for (j = i; j > 0 && r->pts[idx[j]].full.m[LT_M_CYCLES] < r->pts[idx[j - 1]].full.m[LT_M_CYCLES]; j--) {
            size_t t = idx[j];
            idx[j] = idx[j - 1];
            idx[j - 1] = t;
        }
    return n;
}

static const char *const err_head[LT_TUNE_NFAM] = {
    "wrong % | depth RMSE | max err", "wrong % | rel. err median % | rel99 % | within 1 %",
    "PSNR dB | off > 1/255 %"};

/* The error cells of a point, separated by sep (" | " in Markdown, "</td><td>" in HTML). */
static void err_cells(FILE *f, const lt_tune_point_t *p, const char *sep)
{
    const lt_tune_meas_t *x = &p->full;
    if (p->k.family == 0)
        fprintf(f, "%.3f%s%.3g%s%.3g", x->m[LT_M_WRONG], sep, x->m[LT_M_RMSE], sep, x->maxerr);
    else if (p->k.family == 1)
        fprintf(f, "%.3f%s%.3g%s%.3g%s%.2f", x->m[LT_M_WRONG], sep, x->rel50, sep,
                x->m[LT_M_REL99], sep, x->within);
    else
        fprintf(f, "%.2f%s%.2f", x->m[LT_M_PSNR], sep, x->off);
}

/* err_head[fam] with its " | " separators replaced by sep. */
static void err_header(FILE *f, int fam, const char *sep)
{
    const char *s = err_head[fam], *bar;
    while ((bar = strstr(s, " | ")) != NULL) {
        fprintf(f, "%.*s%s", (int)(bar - s), s, sep);
        s = bar + 3;
    }
    fputs(s, f);
}

static void md_picks(FILE *f, const lt_tune_report_t *rep)
{
    const lt_tune_point_t *pts = rep->res->pts;
    char bt[512], kt[160], bind[160];
    int fam;
    lt_budget_text(rep->budget, bt, sizeof bt);
    fprintf(f, "\n## Picks for the budget `%s`\n\n", bt);
    for (fam = 0; fam < LT_TUNE_NFAM; fam++) {
        const lt_tune_pick_t *k = &rep->picks[fam];
        if (!(rep->opts->families & (1u << fam)) || !k->applies)
            continue;
        if (k->pick < 0) {
            fprintf(f, "- %s: no configuration meets the budget\n", lt_tune_family_names[fam]);
            continue;
        }
        lt_tune_knobs_text(&pts[k->pick].k, kt, sizeof kt);
        fprintf(f, "- %s: **%s on %s**, %.0f cycles verified at %u px (%s); binding: %s; ",
                lt_tune_family_names[fam], kt, lt_meter_machine_name(pts[k->pick].k.machine),
                k->verify.m[LT_M_CYCLES], k->verify.res, k->verified ? "meets the budget" : "FAILS",
                (lt_budget_binding_text(rep->budget, k->binding, bind, sizeof bind), bind));
        if (k->best >= 0)
            fprintf(f, "%.0f cycles saved against the most accurate configuration (%.0f)",
                    pts[k->best].full.m[LT_M_CYCLES] - k->verify.m[LT_M_CYCLES],
                    pts[k->best].full.m[LT_M_CYCLES]);
        fprintf(f, "; scene file `%s`\n", k->scene);
    }
}

static int write_md(const char *path, const lt_tune_report_t *rep, lt_diag_t *diag)
{
    const lt_tune_result_t *r = rep->res;
    FILE *f = fopen(path, "w");
    size_t *idx = malloc((r->np ? r->np : 1) * sizeof *idx), n, i;
    int fam, mi;
    if (f == NULL || idx == NULL) {
        if (f != NULL)
            fclose(f);
        free(idx);
        return lt_diag_fail(diag, "%s: cannot create (%s)", path, strerror(errno));
    }
    fprintf(f, "# lanetrace tune: %s\n\n%zu configurations, %zu probed at %u px, %zu pruned, %zu "
               "measured at %u px, %zu on the fronts, %zu failed; %.1f s with %d job(s).\n",
            rep->title, r->np, r->probed, rep->opts->probe_res, r->pruned, r->measured,
            rep->opts->res, r->front, r->failed, rep->secs, rep->opts->jobs);
    if (r->q16_note[0] != '\0')
        fprintf(f, "\ns15.16 left out: %s\n", r->q16_note);
    for (fam = 0; fam < LT_TUNE_NFAM; fam++)
        for (mi = 0; mi < rep->opts->nmach; mi++) {
            int mach = rep->opts->machines[mi];
            if (!(rep->opts->families & (1u << fam)))
                continue;
            n = front_sorted(r, fam, mach, idx);
            fprintf(f, "\n## %s on %s: the front (%zu points)\n\n| configuration | cycles | "
                       "cycles/px | bytes | %s |\n|---|---:|---:|---:|%s\n",
                    lt_tune_family_names[fam], lt_meter_machine_name(mach), n, err_head[fam],
                    fam == 0 ? "---:|---:|---:|" : fam == 1 ? "---:|---:|---:|---:|" : "---:|---:|");
            for (i = 0; i < n; i++) {
                const lt_tune_point_t *p = &r->pts[idx[i]];
                char kt[160];
                lt_tune_knobs_text(&p->k, kt, sizeof kt);
                fprintf(f, "| %s%s | %.0f | %.1f | ", kt, is_pick(rep, idx[i]) ? " (pick)" : "",
                        p->full.m[LT_M_CYCLES],
                        p->full.m[LT_M_CYCLES] / ((double)p->full.res * p->full.res));
                if (isnan(p->full.m[LT_M_BYTES]))
                    fprintf(f, "- | ");
                else
                    fprintf(f, "%.0f | ", p->full.m[LT_M_BYTES]);
                err_cells(f, p, " | ");
                fprintf(f, " |\n");
            }
        }
    if (rep->budget != NULL && rep->picks != NULL)
        md_picks(f, rep);
    free(idx);
    return fclose(f) == 0 ? 0 : lt_diag_fail(diag, "%s: write failed", path);
}

/* ---- the plot (gnuplot) ---------------------------------------------------------------------- */

static const char *const y_label[LT_TUNE_NFAM] = {
    "object: depth RMSE vs the double reference (scene units)",
    "screen: 99th pct relative depth error vs ray traced (%)",
    "shadows: PSNR vs 256 spp (dB, higher is better)"};

static double plot_y(const lt_tune_point_t *p)
{
    const lt_tune_meas_t *x = &p->full;
    double v = p->k.family == 0 ? x->m[LT_M_RMSE]
               : p->k.family == 1 ? x->m[LT_M_REL99] : x->m[LT_M_PSNR];
    if (p->k.family != 2 && !(v > 1e-6))
        v = 1e-6; /* zero on a log axis: drawn at the floor */
    if (p->k.family == 2 && isinf(v))
        v = 99.0;
    return v;
}

static int run_gnuplot(const char *dir, lt_diag_t *diag)
{
    pid_t pid;
    int st;
    fflush(NULL);
    pid = fork();
    if (pid < 0)
        return lt_diag_fail(diag, "cannot start gnuplot: %s", strerror(errno));
    if (pid == 0) {
        if (chdir(dir) != 0)
            _exit(126);
        if (freopen("front.gnuplot.log", "w", stderr) == NULL)
            _exit(126);
        execlp("gnuplot", "gnuplot", "front.gp", (char *)NULL);
        _exit(127);
    }
    if (waitpid(pid, &st, 0) < 0 || !WIFEXITED(st))
        return lt_diag_fail(diag, "%s/front.gp: gnuplot did not finish", dir);
    if (WEXITSTATUS(st) == 127)
        return lt_diag_fail(diag, "%s/front.png: gnuplot not found (Debian gnuplot-nox; make deps)",
                            dir);
    if (WEXITSTATUS(st) != 0)
        return lt_diag_fail(diag, "%s/front.gp: gnuplot failed (exit %d, see %s/front.gnuplot.log)",
                            dir, WEXITSTATUS(st), dir);
    return 0;
}

static int write_plot(const char *dir, const lt_tune_report_t *rep, lt_diag_t *diag)
{
    const lt_tune_result_t *r = rep->res;
    char path[1100];
    FILE *d, *g;
    size_t *idx = malloc((r->np ? r->np : 1) * sizeof *idx), n, i;
    int fam, mi, nf = 0, block = 0;
    for (fam = 0; fam < LT_TUNE_NFAM; fam++)
        nf += (int)((rep->opts->families >> fam) & 1u);
    snprintf(path, sizeof path, "%s/front.dat", dir);
    d = fopen(path, "w");
    snprintf(path, sizeof path, "%s/front.gp", dir);
    g = d != NULL ? fopen(path, "w") : NULL;
    if (idx == NULL || d == NULL || g == NULL) {
        if (d != NULL)
            fclose(d);
        free(idx);
        return lt_diag_fail(diag, "%s: cannot create (%s)", path, strerror(errno));
    }
    fprintf(g, "set terminal pngcairo size %d,420 font ',9'\nset output 'front.png'\n"
               "set multiplot layout 1,%d title '%s: error vs simulated cycles (dots: all "
               "measured at full size; lines: the Pareto fronts)'\nset logscale x\nset grid\n"
               "set key top right\nset xlabel 'cycles per frame'\n",
            480 * nf, nf, "lanetrace tune");
    for (fam = 0; fam < LT_TUNE_NFAM; fam++) {
        int first = 1;
        if (!(rep->opts->families & (1u << fam)))
            continue;
        fprintf(g, "%s\nset ylabel '%s'\nplot ", fam == 2 ? "unset logscale y" : "set logscale y",
                y_label[fam]);
        for (mi = 0; mi < rep->opts->nmach; mi++) {
            int mach = rep->opts->machines[mi], any = 0;
            for (i = 0; i < r->np; i++)
                if (r->pts[i].full.ok && r->pts[i].k.family == fam && r->pts[i].k.machine == mach) {
                    fprintf(d, "%.9g %.9g\n", r->pts[i].full.m[LT_M_CYCLES], plot_y(&r->pts[i]));
                    any = 1;
                }
            fprintf(d, "%s\n\n", any ? "" : "1 1\n");
            n = front_sorted(r, fam, mach, idx);
            for (i = 0; i < n; i++)
                fprintf(d, "%.9g %.9g\n", r->pts[idx[i]].full.m[LT_M_CYCLES], plot_y(&r->pts[idx[i]]));
            fprintf(d, "%s\n\n", n == 0 ? "1 1\n" : "");
            fprintf(g, "%s'front.dat' index %d using 1:2 with points pt 7 ps 0.5 lc %d notitle, "
                       "'front.dat' index %d using 1:2 with linespoints pt 5 lw 2 lc %d title "
                       "'%s front'",
                    first ? "" : ", ", block, mi + 1, block + 1, mi + 1,
                    lt_meter_machine_name(mach));
            block += 2;
            first = 0;
        }
        fprintf(g, "\n");
    }
    fprintf(g, "unset multiplot\n");
    free(idx);
    if (fclose(d) != 0 || fclose(g) != 0)
        return lt_diag_fail(diag, "%s: write failed", path);
    return run_gnuplot(dir, diag);
}

/* ---- HTML ---------------------------------------------------------------------------------- */

/* The file at path as <img src="data:image/png;base64,...">, or a note when it is missing. */
static void html_img(FILE *f, const char *path, const char *alt)
{
    static const char b64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    FILE *in = fopen(path, "rb");
    unsigned char b[3];
    size_t n;
    if (in == NULL) {
        fprintf(f, "<p>(%s: no image)</p>", alt);
        return;
    }
    fprintf(f, "<img alt=\"%s\" src=\"data:image/png;base64,", alt);
    while ((n = fread(b, 1, 3, in)) > 0) {
        unsigned v = (unsigned)b[0] << 16 | (n > 1 ? (unsigned)b[1] << 8 : 0u) | (n > 2 ? b[2] : 0u);
        fputc(b64[(v >> 18) & 63], f);
        fputc(b64[(v >> 12) & 63], f);
        fputc(n > 1 ? b64[(v >> 6) & 63] : '=', f);
        fputc(n > 2 ? b64[v & 63] : '=', f);
        if (n < 3)
            break;
    }
    fclose(in);
    fprintf(f, "\">");
}

/* Text with &, <, > escaped. */
static void html_text(FILE *f, const char *s)
{
    for (; *s; s++) {
        if (*s == '&')
            fputs("&amp;", f);
        else if (*s == '<')
            fputs("&lt;", f);
        else if (*s == '>')
            fputs("&gt;", f);
        else
            fputc(*s, f);
    }
}

static void html_fronts(FILE *f, const lt_tune_report_t *rep, size_t *idx)
{
    const lt_tune_result_t *r = rep->res;
    int fam, mi;
    size_t n, i;
    for (fam = 0; fam < LT_TUNE_NFAM; fam++)
        for (mi = 0; mi < rep->opts->nmach; mi++) {
            int mach = rep->opts->machines[mi];
            if (!(rep->opts->families & (1u << fam)))
                continue;
            n = front_sorted(r, fam, mach, idx);
            fprintf(f, "<h3>%s on %s: %zu points on the front</h3>\n<table><tr><th>configuration"
                       "</th><th>cycles</th><th>cycles/px</th><th>bytes</th><th>",
                    lt_tune_family_names[fam], lt_meter_machine_name(mach), n);
            err_header(f, fam, "</th><th>");
            fprintf(f, "</th></tr>\n");
            for (i = 0; i < n; i++) {
                const lt_tune_point_t *p = &r->pts[idx[i]];
                char kt[160];
                lt_tune_knobs_text(&p->k, kt, sizeof kt);
                fprintf(f, "<tr%s><td>", is_pick(rep, idx[i]) ? " class=\"pick\"" : "");
                html_text(f, kt);
                fprintf(f, "</td><td>%.0f</td><td>%.1f</td><td>", p->full.m[LT_M_CYCLES],
                        p->full.m[LT_M_CYCLES] / ((double)p->full.res * p->full.res));
                if (isnan(p->full.m[LT_M_BYTES]))
                    fprintf(f, "-");
                else
                    fprintf(f, "%.0f", p->full.m[LT_M_BYTES]);
                fprintf(f, "</td><td>");
                err_cells(f, p, "</td><td>");
                fprintf(f, "</td></tr>\n");
            }
            fprintf(f, "</table>\n");
        }
}

static void html_picks(FILE *f, const lt_tune_report_t *rep)
{
    const lt_tune_point_t *pts = rep->res->pts;
    char bt[512], kt[160], bind[160];
    int fam;
    lt_budget_text(rep->budget, bt, sizeof bt);
    fprintf(f, "<h2>The pick for the budget <code>");
    html_text(f, bt);
    fprintf(f, "</code></h2>\n");
    for (fam = 0; fam < LT_TUNE_NFAM; fam++) {
        const lt_tune_pick_t *k = &rep->picks[fam];
        if (!(rep->opts->families & (1u << fam)) || !k->applies)
            continue;
        fprintf(f, "<h3>%s</h3>\n", lt_tune_family_names[fam]);
        if (k->pick < 0) {
            fprintf(f, "<p>No configuration meets the budget.</p>\n");
            continue;
        }
        lt_tune_knobs_text(&pts[k->pick].k, kt, sizeof kt);
        fprintf(f, "<p>Pick: <b>");
        html_text(f, kt);
        fprintf(f, "</b> on %s. Verification at %u px: %.0f cycles, ",
                lt_meter_machine_name(pts[k->pick].k.machine), k->verify.res,
                k->verify.m[LT_M_CYCLES]);
        err_header(f, fam, ", ");
        fprintf(f, ": ");
        err_cells(f, &pts[k->pick], ", ");
        fprintf(f, " (%s). Binding constraint: %s.", k->verified ? "meets the budget" : "FAILS the budget",
                (lt_budget_binding_text(rep->budget, k->binding, bind, sizeof bind), bind));
        if (k->best >= 0) {
            lt_tune_knobs_text(&pts[k->best].k, kt, sizeof kt);
            fprintf(f, " Most accurate: ");
            html_text(f, kt);
            fprintf(f, " on %s, %.0f cycles: %.0f cycles saved.",
                    lt_meter_machine_name(pts[k->best].k.machine), pts[k->best].full.m[LT_M_CYCLES],
                    pts[k->best].full.m[LT_M_CYCLES] - k->verify.m[LT_M_CYCLES]);
        }
        fprintf(f, " Scene file: <code>");
        html_text(f, k->scene);
        fprintf(f, "</code></p>\n<div class=\"pair\"><figure>");
        html_img(f, k->img_best, "most accurate");
        fprintf(f, "<figcaption>most accurate</figcaption></figure><figure>");
        html_img(f, k->img_pick, "chosen");
        fprintf(f, "<figcaption>chosen</figcaption></figure></div>\n");
    }
}

static int write_html(const char *dir, const lt_tune_report_t *rep, lt_diag_t *diag)
{
    const lt_tune_result_t *r = rep->res;
    char path[1100];
    size_t *idx = malloc((r->np ? r->np : 1) * sizeof *idx);
    FILE *f;
    snprintf(path, sizeof path, "%s/report.html", dir);
    f = fopen(path, "w");
    if (f == NULL || idx == NULL) {
        if (f != NULL)
            fclose(f);
        free(idx);
        return lt_diag_fail(diag, "%s: cannot create (%s)", path, strerror(errno));
    }
    fprintf(f, "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>lanetrace "
               "tune: ");
    html_text(f, rep->title);
    fprintf(f, "</title>\n<style>body{font-family:sans-serif;margin:1.5em;max-width:1500px}"
               "table{border-collapse:collapse;margin-bottom:1em}td,th{border:1px solid #bbb;"
               "padding:2px 6px;text-align:right}td:first-child{text-align:left}"
               "tr.pick{background:#ffe9a8}img{max-width:100%%;image-rendering:pixelated}"
               ".pair{display:flex;gap:1em}.pair img{width:320px}figure{margin:0}</style>\n"
               "</head><body>\n<h1>lanetrace tune: ");
    html_text(f, rep->title);
    fprintf(f, "</h1>\n<p>%zu configurations; %zu probed at %u px, %zu pruned as dominated, %zu "
               "measured at %u px in the simulator, %zu on the fronts, %zu failed; %.1f s with %d "
               "job(s).</p>\n",
            r->np, r->probed, rep->opts->probe_res, r->pruned, r->measured, rep->opts->res,
            r->front, r->failed, rep->secs, rep->opts->jobs);
    if (r->q16_note[0] != '\0') {
        fprintf(f, "<p>s15.16 left out: ");
        html_text(f, r->q16_note);
        fprintf(f, "</p>\n");
    }
    snprintf(path, sizeof path, "%s/front.png", dir);
    html_img(f, path, "error vs cycles");
    if (rep->budget != NULL && rep->picks != NULL)
        html_picks(f, rep);
    fprintf(f, "<h2>The fronts</h2>\n");
    html_fronts(f, rep, idx);
    fprintf(f, "<p>Every point (knobs, cycles per phase, bytes, errors, probe figures): "
               "front.csv, front.json.</p>\n<script>window.addEventListener('load', function () {"
               "var n = 0, i; for (i = 0; i < document.images.length; i++) if "
               "(!document.images[i].complete || document.images[i].naturalWidth === 0) n++; "
               "document.body.setAttribute('data-broken-images', String(n)); "
               "document.body.setAttribute('data-images', String(document.images.length));});"
               "</script>\n</body></html>\n");
    free(idx);
    return fclose(f) == 0 ? 0 : lt_diag_fail(diag, "%s/report.html: write failed", dir);
}

/* ---- the chosen configuration as a scene file ---------------------------------------------- */

int lt_tune_write_scene(const char *path, const lt_tune_input_t *in, const lt_tune_point_t *p,
                        uint32_t res, lt_diag_t *diag)
{
    const lt_tune_knobs_t *k = &p->k;
    cJSON *o = cJSON_CreateObject(), *x;
    char mesh[4096], kt[160], *s;
    int rc;
    if (realpath(in->mesh, mesh) == NULL)
        snprintf(mesh, sizeof mesh, "%s", in->mesh);
    lt_tune_knobs_text(k, kt, sizeof kt);
    cJSON_AddNumberToObject(o, "lanetrace", 1);
    cJSON_AddStringToObject(o, "mesh", mesh);
    cJSON_AddNumberToObject(o, "resolution", res);
    cJSON_AddStringToObject(o, "machine", lt_meter_machine_name(k->machine));
    if (in->has_camera && k->family == 0) {
        x = cJSON_AddObjectToObject(o, "camera");
        cJSON_AddItemToObject(x, "eye", cJSON_CreateDoubleArray(in->eye, 3));
        cJSON_AddItemToObject(x, "target", cJSON_CreateDoubleArray(in->target, 3));
        cJSON_AddItemToObject(x, "up", cJSON_CreateDoubleArray(in->up, 3));
        cJSON_AddNumberToObject(x, "fov_y_deg", in->fov);
    }
    if (k->family == 0) {
        cJSON_AddStringToObject(o, "structure", lt_render_structures[k->structure]);
        cJSON_AddStringToObject(o, "numeric", lt_paths[k->path].name);
        if (k->leaf > 0)
            cJSON_AddNumberToObject(o, "leaf", k->leaf);
        if (k->isect != 0)
            cJSON_AddStringToObject(o, "isect", lt_sf_isects[k->isect]);
    } else if (k->family == 1) {
        static const double move[3] = {0.08, 0, 0}, rot[3] = {-3, 0, 0};
        x = cJSON_AddObjectToObject(o, "reproject");
        cJSON_AddItemToObject(x, "move", cJSON_CreateDoubleArray(move, 3));
        cJSON_AddBoolToObject(x, "move_relative", 1);
        cJSON_AddItemToObject(x, "rot", cJSON_CreateDoubleArray(rot, 3));
        cJSON_AddStringToObject(x, "encoding", lt_paths[k->path].name);
        cJSON_AddNumberToObject(x, "layers", k->layers);
        cJSON_AddStringToObject(x, "tracer", tracer_names[k->structure]);
        if (k->structure == LT_RP_QUADTREE) {
            cJSON_AddNumberToObject(x, "gamma_norm", lt_tune_gammas[k->gamma].gamma_norm);
            cJSON_AddNumberToObject(x, "gamma_dist", lt_tune_gammas[k->gamma].gamma_dist);
        }
    } else {
        cJSON_AddStringToObject(o, "numeric", lt_paths[k->path].name);
        x = cJSON_AddObjectToObject(o, "shadows");
        cJSON_AddStringToObject(x, "primary", k->prim ? "frusta" : "packet");
        cJSON_AddStringToObject(x, "method", k->shadow ? "packet" : "frusta");
        cJSON_AddBoolToObject(x, "filter", k->filter);
        cJSON_AddNumberToObject(x, "leaf", k->leaf);
        cJSON_AddStringToObject(x, "cull", lt_tune_cull_names[k->cull]);
        cJSON_AddNumberToObject(x, "spp", k->spp ? k->spp : 16);
    }
    s = cJSON_Print(o);
    cJSON_Delete(o);
    if (s == NULL)
        return lt_diag_fail(diag, "%s: out of memory", path);
    rc = write_text(path, s, diag);
    free(s);
    return rc;
}

int lt_tune_write_outputs(const char *dir, const lt_tune_report_t *rep, lt_diag_t *diag)
{
    char path[1100], *js;
    int rc;
    if (mkdir(dir, 0777) != 0 && errno != EEXIST)
        return lt_diag_fail(diag, "--out %s: cannot create the folder (%s)", dir, strerror(errno));
    snprintf(path, sizeof path, "%s/front.csv", dir);
    if (write_csv(path, rep, diag) != 0)
        return -1;
    js = lt_tune_json(rep);
    if (js == NULL)
        return lt_diag_fail(diag, "%s/front.json: out of memory", dir);
    snprintf(path, sizeof path, "%s/front.json", dir);
    rc = write_text(path, js, diag);
    free(js);
    if (rc != 0)
        return -1;
    snprintf(path, sizeof path, "%s/front.md", dir);
    if (write_md(path, rep, diag) != 0 || write_plot(dir, rep, diag) != 0)
        return -1;
    return write_html(dir, rep, diag);
}
