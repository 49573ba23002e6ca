/* lt_tune_dist.c - lanetrace tune beyond one machine (lt_tune.h): the plan (a job list for GNU
 * parallel and the same as a Slurm array script), one job's result file, and reading the results
 * back for the merge. A job measures one run at full size in its own process through the same
 * measurement server as an in-process tune, so the merged points equal `tune --probe-res 0`'s.
 * Host only.
 */
#include "tune/lt_tune.h"

#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* path into buf, single-quoted for sh ('\'' for a quote). */
static void shq(char *buf, size_t n, const char *s)
{
    size_t len = 0;
    if (n < 3)
        return;
    buf[len++] = '\'';
    for (; *s != '\0' && len + 5 < n; s++) {
        if (*s == '\'') {
            memcpy(buf + len, "'\\''", 4);
            len += 4;
        } else {
            buf[len++] = *s;
        }
    }
    buf[len++] = '\'';
    buf[len] = '\0';
}

/* plan.json and run-K.json are a few KiB; anything past this is not one of them */
#define LT_TUNE_TEXT_MAX (64 << 20)

static char *read_text(const char *path, lt_diag_t *diag)
{
    const char *kind = lt_diag_not_regular(path);
    FILE *f;
    char *t;
    const char *nul;
    long n;
    /* refused before opening: a FIFO without a writer would block the open, a directory opens
     * but its "size" is LONG_MAX on some file systems (a malloc of 2^63 bytes) */
    if (kind != NULL) {
        lt_diag_fail(diag, "%s: %s, not a regular file", path, kind);
        return NULL;
    }
    f = fopen(path, "rb");
    if (f == NULL) {
        lt_diag_fail(diag, "%s: cannot open (%s)", path, strerror(errno));
        return NULL;
    }
    if (fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        lt_diag_fail(diag, "%s: cannot read", path);
        return NULL;
    }
    if (n > LT_TUNE_TEXT_MAX) {
        fclose(f);
        lt_diag_fail(diag, "%s: %ld bytes, larger than a plan or result file can be (at most %d)",
                     path, n, LT_TUNE_TEXT_MAX);
        return NULL;
    }
    if ((t = malloc((size_t)n + 1)) == NULL) {
        fclose(f);
        lt_diag_fail(diag, "%s: out of memory (%ld bytes)", path, n);
        return NULL;
    }
    if (fread(t, 1, (size_t)n, f) != (size_t)n) {
        free(t);
        fclose(f);
        lt_diag_fail(diag, "%s: cannot read", path);
        return NULL;
    }
    t[n] = '\0';
    fclose(f);
    if ((nul = memchr(t, '\0', (size_t)n)) != NULL) {
        lt_diag_fail(diag, "%s: a NUL byte at offset %ld: not a JSON text", path, (long)(nul - t));
        free(t);
        return NULL;
    }
    return t;
}

static int write_json(const char *path, cJSON *o, lt_diag_t *diag)
{
    char *s = cJSON_Print(o);
    FILE *f;
    int rc = 0;
    cJSON_Delete(o);
    if (s == NULL)
        return lt_diag_fail(diag, "%s: out of memory", path);
    f = fopen(path, "w");
    if (f == NULL || fputs(s, f) < 0)
        rc = lt_diag_fail(diag, "%s: cannot write (%s)", path, strerror(errno));
    if (f != NULL && fclose(f) != 0 && rc == 0)
        rc = lt_diag_fail(diag, "%s: write failed", path);
    free(s);
    return rc;
}

static int plan_files(const char *dir, const char *exe, const lt_tune_plan_t *p, lt_diag_t *diag)
{
    char path[1100], qexe[2200], qin[2200], qres[2400], mach[400] = "";
    FILE *j, *s;
    size_t r;
    int m;
    snprintf(path, sizeof path, "%s/results", dir);
    shq(qexe, sizeof qexe, exe);
    shq(qin, sizeof qin, p->input);
    shq(qres, sizeof qres, path);
    for (m = 0; m < p->nmach; m++)
        snprintf(mach + strlen(mach), sizeof mach - strlen(mach), " --machine %s", p->machines[m]);
    snprintf(path, sizeof path, "%s/jobs.txt", dir);
    j = fopen(path, "w");
    if (j == NULL)
        return lt_diag_fail(diag, "%s: cannot create (%s)", path, strerror(errno));
    for (r = 0; r < p->nruns; r++)
        fprintf(j, "%s tune %s --family %s%s --res %u --job %zu --out %s -q\n", qexe, qin,
                p->families, mach, p->res, r, qres);
    if (fclose(j) != 0)
        return lt_diag_fail(diag, "%s: write failed", path);
    snprintf(path, sizeof path, "%s/tune.slurm", dir);
    s = fopen(path, "w");
    if (s == NULL)
        return lt_diag_fail(diag, "%s: cannot create (%s)", path, strerror(errno));
    fprintf(s, "#!/bin/bash\n# lanetrace tune plan as a Slurm array job: task i runs line i + 1 of "
               "jobs.txt (the lines GNU parallel runs),\n# then: lanetrace tune --merge %s\n"
               "#SBATCH --job-name=lanetrace-tune\n#SBATCH --array=0-%zu\n#SBATCH --ntasks=1\n"
               "#SBATCH --cpus-per-task=1\n#SBATCH --output=%s/results/slurm-%%A_%%a.out\n"
               "set -euo pipefail\nline=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" %s/jobs.txt)\n"
               "eval \"$line\"\n",
            dir, p->nruns > 0 ? p->nruns - 1 : 0, dir, dir);
    if (fclose(s) != 0)
        return lt_diag_fail(diag, "%s: write failed", path);
    return 0;
}

int lt_tune_write_plan(const char *dir, const char *exe, const lt_tune_plan_t *p, lt_diag_t *diag)
{
    char path[1100];
    cJSON *o, *a;
    int m;
    if (mkdir(dir, 0777) != 0 && errno != EEXIST)
        return lt_diag_fail(diag, "--plan %s: cannot create the folder (%s)", dir, strerror(errno));
    snprintf(path, sizeof path, "%s/results", dir);
    if (mkdir(path, 0777) != 0 && errno != EEXIST)
        return lt_diag_fail(diag, "%s: cannot create the folder (%s)", path, strerror(errno));
    o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "tool", "lanetrace tune --plan");
    cJSON_AddStringToObject(o, "input", p->input);
    cJSON_AddStringToObject(o, "families", p->families);
    a = cJSON_AddArrayToObject(o, "machines");
    for (m = 0; m < p->nmach; m++)
        cJSON_AddItemToArray(a, cJSON_CreateString(p->machines[m]));
    cJSON_AddNumberToObject(o, "res", p->res);
    cJSON_AddStringToObject(o, "q16_left_out", p->q16_note);
    cJSON_AddNumberToObject(o, "runs", (double)p->nruns);
    snprintf(path, sizeof path, "%s/plan.json", dir);
    if (write_json(path, o, diag) != 0)
        return -1;
    return plan_files(dir, exe, p, diag);
}

static int get_str(const cJSON *o, const char *k, char *out, size_t n)
{
    const cJSON *x = cJSON_GetObjectItemCaseSensitive(o, k);
    if (!cJSON_IsString(x) || strlen(x->valuestring) >= n)
        return -1;
    snprintf(out, n, "%s", x->valuestring);
    return 0;
}

int lt_tune_read_plan(const char *dir, lt_tune_plan_t *p, lt_diag_t *diag)
{
    char path[1100], *t;
    cJSON *o;
    const cJSON *a, *x, *runs, *res;
    int bad;
    memset(p, 0, sizeof *p);
    snprintf(path, sizeof path, "%s/plan.json", dir);
    if ((t = read_text(path, diag)) == NULL)
        return -1;
    o = cJSON_Parse(t);
    free(t);
    a = cJSON_GetObjectItemCaseSensitive(o, "machines");
    runs = cJSON_GetObjectItemCaseSensitive(o, "runs");
    res = cJSON_GetObjectItemCaseSensitive(o, "res");
    bad = o == NULL || get_str(o, "input", p->input, sizeof p->input) != 0 ||
          get_str(o, "families", p->families, sizeof p->families) != 0 ||
          get_str(o, "q16_left_out", p->q16_note, sizeof p->q16_note) != 0 || !cJSON_IsArray(a) ||
          !cJSON_IsNumber(runs) || !cJSON_IsNumber(res);
    if (!bad) {
        cJSON_ArrayForEach(x, a) {
            if (!cJSON_IsString(x) || p->nmach == 8 || strlen(x->valuestring) >= 32) {
                bad = 1;
                break;
            }
            snprintf(p->machines[p->nmach++], 32, "%s", x->valuestring);
        }
        p->nruns = (size_t)runs->valuedouble;
        p->res = (uint32_t)res->valuedouble;
    }
    cJSON_Delete(o);
    if (bad)
        return lt_diag_fail(diag, "%s: not a plan of lanetrace tune --plan (input, families, "
                                  "machines, res, runs)", path);
    return 0;
}

int lt_tune_write_job(const char *path, const lt_tune_point_t *pts, size_t np, int run,
                      lt_diag_t *diag)
{
    cJSON *o = cJSON_CreateObject(), *a;
    size_t i;
    char kt[160];
    cJSON_AddStringToObject(o, "tool", "lanetrace tune --job");
    cJSON_AddNumberToObject(o, "run", run);
    a = cJSON_AddArrayToObject(o, "points");
    for (i = 0; i < np; i++) {
        cJSON *x;
        if (pts[i].run != run)
            continue;
        x = cJSON_CreateObject();
        lt_tune_knobs_text(&pts[i].k, kt, sizeof kt);
        cJSON_AddNumberToObject(x, "id", (double)i);
        cJSON_AddStringToObject(x, "text", kt);
        cJSON_AddNumberToObject(x, "machine", pts[i].k.machine);
        cJSON_AddItemToObject(x, "full", lt_tune_meas_json(&pts[i].full));
        cJSON_AddItemToArray(a, x);
    }
    return write_json(path, o, diag);
}

/* One result file into pts. */
static int read_one(const char *path, lt_tune_point_t *pts, size_t np, unsigned char *seen,
                    size_t nruns, lt_diag_t *diag)
{
    char *t = read_text(path, diag), kt[160];
    cJSON *o;
    const cJSON *a, *x, *run;
    int bad = 0;
    if (t == NULL)
        return -1;
    o = cJSON_Parse(t);
    free(t);
    a = cJSON_GetObjectItemCaseSensitive(o, "points");
    run = cJSON_GetObjectItemCaseSensitive(o, "run");
    if (o == NULL || !cJSON_IsArray(a) || !cJSON_IsNumber(run) || run->valuedouble < 0 ||
        (size_t)run->valuedouble >= nruns) {
        cJSON_Delete(o);
        return lt_diag_fail(diag, "%s: not a job result of this plan (its run is not one of the "
                                  "plan's 0..%zu)", path, nruns ? nruns - 1 : 0);
    }
    cJSON_ArrayForEach(x, a) {
        const cJSON *id = cJSON_GetObjectItemCaseSensitive(x, "id");
        const cJSON *tx = cJSON_GetObjectItemCaseSensitive(x, "text");
        size_t i;
        if (!cJSON_IsNumber(id) || id->valuedouble < 0 || (size_t)id->valuedouble >= np ||
            !cJSON_IsString(tx)) {
            bad = 1;
            break;
        }
        i = (size_t)id->valuedouble;
        lt_tune_knobs_text(&pts[i].k, kt, sizeof kt);
        if (strcmp(kt, tx->valuestring) != 0 || pts[i].run != (int)run->valuedouble ||
            lt_tune_meas_from_json(cJSON_GetObjectItemCaseSensitive(x, "full"), &pts[i].full) != 0) {
            bad = 1;
            break;
        }
    }
    if (!bad)
        seen[(size_t)run->valuedouble] = 1;
    cJSON_Delete(o);
    return bad ? lt_diag_fail(diag, "%s: its points do not match the plan's configurations", path)
               : 0;
}

long lt_tune_read_results(const char *dir, lt_tune_point_t *pts, size_t np, unsigned char *seen,
                          size_t nruns, lt_diag_t *diag)
{
    char sub[1100], path[1400];
    const char *d = dir;
    DIR *dh;
    struct dirent *e;
    long n = 0;
    snprintf(sub, sizeof sub, "%s/results", dir);
    dh = opendir(sub);
    if (dh != NULL)
        d = sub;
    else
        dh = opendir(dir);
    if (dh == NULL)
        return lt_diag_fail(diag, "--merge %s: cannot open the folder (%s)", dir, strerror(errno));
    while ((e = readdir(dh)) != NULL) {
        size_t len = strlen(e->d_name);
        if (strncmp(e->d_name, "run-", 4) != 0 || len < 9 || strcmp(e->d_name + len - 5, ".json") != 0)
            continue;
        snprintf(path, sizeof path, "%s/%s", d, e->d_name);
        if (read_one(path, pts, np, seen, nruns, diag) != 0) {
            closedir(dh);
            return -1;
        }
        n++;
    }
    closedir(dh);
    return n;
}
