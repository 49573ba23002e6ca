/* lt_tune.c - configurations, the probe/prune/confirm search and its worker processes for
 * lanetrace tune (lt_tune.h). Host only.
 */
#include "tune/lt_tune.h"

#include "lt/lt_frusta.h"
#include "lt_meter.h"
#include "render/lt_paths.h"
#include "render/lt_render.h"
#include "render/lt_reproject.h"

#include <errno.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

const char *const lt_tune_family_names[] = {"object", "screen", "shadows", NULL};

const lt_tune_gamma_t lt_tune_gammas[LT_TUNE_NGAMMA] = {
    {"default", 1e-3, 1.0 / 131072.0}, /* lt_qt_params_default: 1e-3, 2^-17 */
    {"coarse", 1e-2, 1.0 / 8192.0},    /* 10x the normal angle, 16x the distance */
    {"coarser", 5e-2, 1.0 / 1024.0},   /* 50x, 128x: fewer, larger planes */
};

const char *const lt_tune_cull_names[LT_TUNE_NCULL] = {"bcr", "b", "cr"};
const unsigned lt_tune_cull_flags[LT_TUNE_NCULL] = {
    LT_FRUSTA_BACKFACE | LT_FRUSTA_CORNER | LT_FRUSTA_CR, LT_FRUSTA_BACKFACE,
    LT_FRUSTA_CORNER | LT_FRUSTA_CR};

static const char *const tracer_names[] = {"quadtree", "dda", "hiz"};

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- configurations ------------------------------------------------------------------------ */

typedef struct grow {
    lt_tune_point_t *p;
    size_t n, cap;
    int run;
} grow_t;

static int add(grow_t *g, const lt_tune_knobs_t *k)
{
    if (g->n == g->cap) {
        size_t cap = g->cap ? 2 * g->cap : 256;
        lt_tune_point_t *q = realloc(g->p, cap * sizeof *q);
        if (q == NULL)
            return -1;
        g->p = q;
        g->cap = cap;
    }
    memset(&g->p[g->n], 0, sizeof g->p[0]);
    g->p[g->n].k = *k;
    g->p[g->n].run = g->run;
    g->n++;
    return 0;
}

static int enum_object(grow_t *g, int mach, int skip_q16)
{
    static const int leaves_bvh[] = {2, 4, 8, 16}, leaves_bvhq[] = {2, 4, 8, 15},
                     leaves_kd[] = {1, 2, 4, 8};
    int pi, s, j;
    for (pi = 0; lt_paths[pi].name != NULL; pi++) {
        if (!(lt_paths[pi].families & LT_PATHS_OBJECT) ||
            (skip_q16 && lt_paths[pi].path == LT_PATH_Q16))
            continue;
        for (s = 0; lt_render_structures[s] != NULL; s++) {
            const char *sn = lt_render_structures[s];
            const int *lv = strcmp(sn, "bvh") == 0 ? leaves_bvh
                            : strcmp(sn, "bvhq") == 0 ? leaves_bvhq
                            : strcmp(sn, "kd") == 0 ? leaves_kd : NULL;
            if (strcmp(sn, "bvhq") == 0 && lt_paths[pi].path != LT_PATH_Q16)
                continue;
            for (j = 0; j < (lv != NULL ? 4 : 1); j++) {
                lt_tune_knobs_t k;
                memset(&k, 0, sizeof k);
                k.family = 0;
                k.machine = mach;
                k.path = pi;
                k.structure = s;
                k.leaf = lv != NULL ? lv[j] : 0;
                if (add(g, &k) != 0)
                    return -1;
                g->run++;
            }
        }
    }
    return 0;
}

static int enum_screen(grow_t *g, int mach)
{
    int pi, t, l, gm;
    for (t = 0; t < 3; t++)
        for (pi = 0; lt_paths[pi].name != NULL; pi++) {
            if (!(lt_paths[pi].families & LT_PATHS_SCREEN))
                continue;
            /* the DDA and Hi-Z trace n64 and n32 alike in s1.30: n64 stands for both */
            if (t != LT_RP_QUADTREE && lt_paths[pi].qt_enc == LT_QT_N32)
                continue;
            for (l = 1; l <= 4; l++)
                for (gm = 0; gm < (t == LT_RP_QUADTREE ? LT_TUNE_NGAMMA : 1); gm++) {
                    lt_tune_knobs_t k;
                    memset(&k, 0, sizeof k);
                    k.family = 1;
                    k.machine = mach;
                    k.path = pi;
                    k.structure = t;
                    k.layers = l;
                    k.gamma = gm;
                    if (add(g, &k) != 0)
                        return -1;
                    g->run++;
                }
        }
    return 0;
}

static int enum_shadows(grow_t *g, int mach, int skip_q16)
{
    static const int leaves[] = {4, 8, 16};
    int pi, j, cu, b;
    for (pi = 0; lt_paths[pi].name != NULL; pi++) {
        if (!(lt_paths[pi].families & LT_PATHS_FRUSTA) ||
            (skip_q16 && lt_paths[pi].path == LT_PATH_Q16))
            continue;
        for (j = 0; j < 3; j++)
            for (cu = 0; cu < LT_TUNE_NCULL; cu++) {
                for (b = 0; b < 8; b++) {
                    lt_tune_knobs_t k;
                    memset(&k, 0, sizeof k);
                    k.family = 2;
                    k.machine = mach;
                    k.path = pi;
                    k.leaf = leaves[j];
                    k.cull = cu;
                    k.prim = b & 1;
                    k.shadow = (b >> 1) & 1;
                    k.filter = (b >> 2) & 1;
                    if (add(g, &k) != 0)
                        return -1;
                }
                g->run++;
            }
    }
    return 0;
}

int lt_tune_enumerate(unsigned families, const int *machines, int nmach, int skip_q16,
                      lt_tune_point_t **pts, size_t *np, lt_diag_t *diag)
{
    grow_t g;
    int i, rc = 0;
    memset(&g, 0, sizeof g);
    for (i = 0; i < nmach && rc == 0; i++) {
        if (families & LT_TUNE_OBJECT)
            rc |= enum_object(&g, machines[i], skip_q16);
        if (families & LT_TUNE_SCREEN)
            rc |= enum_screen(&g, machines[i]);
        if (families & LT_TUNE_SHADOWS)
            rc |= enum_shadows(&g, machines[i], skip_q16);
    }
    if (rc != 0) {
        free(g.p);
        return lt_diag_fail(diag, "out of memory for the configurations");
    }
    *pts = g.p;
    *np = g.n;
    return 0;
}

void lt_tune_knobs_text(const lt_tune_knobs_t *k, char *buf, size_t n)
{
    const char *pn = lt_paths[k->path].name;
    if (k->family == 0) {
        if (k->leaf > 0)
            snprintf(buf, n, "%s %s leaf %d", pn, lt_render_structures[k->structure], k->leaf);
        else
            snprintf(buf, n, "%s %s", pn, lt_render_structures[k->structure]);
    } else if (k->family == 1) {
        if (k->structure == LT_RP_QUADTREE)
            snprintf(buf, n, "%s quadtree %d layer%s gamma %s", pn, k->layers,
                     k->layers > 1 ? "s" : "", lt_tune_gammas[k->gamma].name);
        else
            snprintf(buf, n, "%s %s %d layer%s", strcmp(pn, "f32") == 0 ? "f32" : "s1.30",
                     tracer_names[k->structure], k->layers, k->layers > 1 ? "s" : "");
    } else {
        snprintf(buf, n, "%s %s/%s leaf %d cull %s filter %s", pn, k->prim ? "P-Frusta" : "P-Packet",
                 k->shadow ? "S-Packet" : "S-Frusta", k->leaf, lt_tune_cull_names[k->cull],
                 k->filter ? "on" : "off");
    }
}

int lt_tune_objectives(int family, const lt_tune_meas_t *m, double *obj)
{
    obj[0] = m->m[LT_M_CYCLES];
    if (family == 0) {
        obj[1] = m->m[LT_M_WRONG];
        obj[2] = m->m[LT_M_RMSE];
    } else if (family == 1) {
        obj[1] = m->m[LT_M_WRONG];
        obj[2] = m->m[LT_M_REL99];
    } else {
        obj[1] = -m->m[LT_M_PSNR];
        obj[2] = m->off;
    }
    return 3;
}

/* ---- workers -------------------------------------------------------------------------------- */

typedef struct rec {
    long idx; /* point index, or -1 - run: the run is done */
    lt_tune_meas_t m;
} rec_t;

static int write_all(int fd, const void *buf, size_t n)
{
    const char *p = buf;
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return -1;
        p += w;
        n -= (size_t)w;
    }
    return 0;
}

/* 1: a whole record, 0: end of file, -1: error. */
static int read_all(int fd, void *buf, size_t n)
{
    char *p = buf;
    size_t got = 0;
    while (got < n) {
        ssize_t r = read(fd, p + got, n - got);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            return -1;
        if (r == 0)
            return got == 0 ? 0 : -1;
        got += (size_t)r;
    }
    return 1;
}

/* A worker: runs w, w + jobs, ... of runs[], each point's measurement to fd. */
static void worker(lt_tune_ctx_t *c, lt_tune_point_t *pts, size_t np, const int *runs,
                   size_t nruns, int full, int w, int jobs, int fd)
{
    size_t r, i;
    for (r = (size_t)w; r < nruns; r += (size_t)jobs) {
        rec_t rec;
        lt_tune_eval_run(c, pts, np, runs[r], full, NULL);
        for (i = 0; i < np; i++)
            if (pts[i].run == runs[r]) {
                rec.idx = (long)i;
                rec.m = full ? pts[i].full : pts[i].probe;
                if (write_all(fd, &rec, sizeof rec) != 0)
                    _exit(3);
            }
        memset(&rec, 0, sizeof rec);
        rec.idx = -1 - runs[r];
        if (write_all(fd, &rec, sizeof rec) != 0)
            _exit(3);
    }
}

/* Collect the workers' records until every pipe closes. */
static int collect(lt_tune_point_t *pts, size_t np, int full, struct pollfd *pf, int jobs,
                   size_t nruns, void (*progress)(const char *, size_t, size_t),
                   const char *stage)
{
    int open = jobs, j, bad = 0;
    size_t done = 0;
    rec_t rec;
    while (open > 0) {
        if (poll(pf, (nfds_t)jobs, -1) < 0) {
            if (errno == EINTR)
                continue;
            return -1;
        }
        for (j = 0; j < jobs; j++) {
            int rr;
            if (pf[j].fd < 0 || !(pf[j].revents & (POLLIN | POLLHUP | POLLERR)))
                continue;
            rr = read_all(pf[j].fd, &rec, sizeof rec);
            if (rr <= 0) {
                bad |= rr < 0;
                close(pf[j].fd);
                pf[j].fd = -1;
                open--;
                continue;
            }
            if (rec.idx >= 0 && (size_t)rec.idx < np) {
                if (full)
                    pts[rec.idx].full = rec.m;
                else
                    pts[rec.idx].probe = rec.m;
            } else if (rec.idx < 0 && progress != NULL) {
                progress(stage, ++done, nruns);
            }
        }
    }
    return bad ? -1 : 0;
}

int lt_tune_run_workers(lt_tune_ctx_t *c, lt_tune_point_t *pts, size_t np, const int *runs,
                        size_t nruns, int full, int jobs,
                        void (*progress)(const char *stage, size_t done, size_t total),
                        const char *stage, lt_diag_t *diag)
{
    struct pollfd pf[64];
    pid_t pid[64];
    int j, st, rc = 0;
    size_t r;
    if (jobs > (int)nruns)
        jobs = nruns > 0 ? (int)nruns : 1;
    if (jobs > 64)
        jobs = 64;
    if (jobs <= 1) {
        for (r = 0; r < nruns; r++) {
            lt_tune_eval_run(c, pts, np, runs[r], full, NULL);
            if (progress != NULL)
                progress(stage, r + 1, nruns);
        }
        return 0;
    }
    fflush(NULL);
    for (j = 0; j < jobs; j++) {
        int fds[2];
        if (pipe(fds) != 0 || (pid[j] = fork()) < 0) {
            lt_diag_fail(diag, "cannot start worker %d of --jobs %d: %s", j + 1, jobs,
                         strerror(errno));
            for (st = 0; st < j; st++) {
                kill(pid[st], SIGTERM);
                waitpid(pid[st], NULL, 0);
                close(pf[st].fd);
            }
            return -1;
        }
        if (pid[j] == 0) {
            close(fds[0]);
            for (st = 0; st < j; st++)
                close(pf[st].fd);
            worker(c, pts, np, runs, nruns, full, j, jobs, fds[1]);
            close(fds[1]);
            _exit(0);
        }
        close(fds[1]);
        pf[j].fd = fds[0];
        pf[j].events = POLLIN;
    }
    if (collect(pts, np, full, pf, jobs, nruns, progress, stage) != 0)
        rc = lt_diag_fail(diag, "reading the workers' results failed");
    for (j = 0; j < jobs; j++) {
        if (waitpid(pid[j], &st, 0) < 0 || !WIFEXITED(st) || WEXITSTATUS(st) != 0)
            rc = lt_diag_fail(diag, "worker %d of --jobs %d ended abnormally (status %d)", j + 1,
                              jobs, st);
    }
    return rc;
}

/* ---- the search ------------------------------------------------------------------------------ */

void lt_tune_mark_fronts(lt_tune_point_t *pts, size_t np)
{
    double *obj = malloc((np ? np : 1) * 3 * sizeof *obj);
    unsigned char *inc = malloc(np ? np : 1), *on = malloc(np ? np : 1);
    size_t i, j;
    if (obj == NULL || inc == NULL || on == NULL) {
        free(obj);
        free(inc);
        free(on);
        return;
    }
    for (i = 0; i < np; i++) {
        pts[i].front = 0;
        (void)lt_tune_objectives(pts[i].k.family, &pts[i].full, obj + 3 * i);
    }
    /* one front per family and machine */
    for (i = 0; i < np; i++) {
        int seen = 0;
        for (j = 0; j < i && !seen; j++)
            seen = pts[j].k.family == pts[i].k.family && pts[j].k.machine == pts[i].k.machine;
        if (seen)
            continue;
        for (j = 0; j < np; j++)
            inc[j] = pts[j].full.ok && pts[j].k.family == pts[i].k.family &&
                     pts[j].k.machine == pts[i].k.machine;
        lt_pareto_front(obj, np, 3, inc, on);
        for (j = 0; j < np; j++)
            if (on[j])
                pts[j].front = 1;
    }
    free(obj);
    free(inc);
    free(on);
}

/* NaN-equal-aware "a <= b". */
static int le(double a, double b)
{
    if (isnan(b))
        return 1;
    return !isnan(a) && a <= b;
}

/* Prune at the probe resolution: p goes when some q of its family and machine is no worse in both
 * errors and in bytes and cheaper by the slack in cycles. Returns the runs to measure at full
 * size (into runs, *nruns). */
static void prune(lt_tune_point_t *pts, size_t np, double slack, int *runs, size_t *nruns)
{
    size_t i, j;
    int last = -1;
    *nruns = 0;
    for (i = 0; i < np; i++) {
        double a[3], b[3];
        pts[i].pruned = !pts[i].probe.ok;
        if (!pts[i].probe.ok)
            continue;
        (void)lt_tune_objectives(pts[i].k.family, &pts[i].probe, a);
        for (j = 0; j < np && !pts[i].pruned; j++) {
            if (j == i || !pts[j].probe.ok || pts[j].k.family != pts[i].k.family ||
                pts[j].k.machine != pts[i].k.machine)
                continue;
            (void)lt_tune_objectives(pts[j].k.family, &pts[j].probe, b);
            if (b[0] * (1.0 + slack) <= a[0] && le(b[1], a[1]) && le(b[2], a[2]) &&
                le(pts[j].probe.m[LT_M_BYTES], pts[i].probe.m[LT_M_BYTES]))
                pts[i].pruned = 1;
        }
    }
    for (i = 0; i < np; i++)
        if (!pts[i].pruned && pts[i].run != last) {
            runs[(*nruns)++] = pts[i].run;
            last = pts[i].run;
        }
}

static void tally(lt_tune_result_t *r)
{
    size_t i;
    r->probed = r->measured = r->pruned = r->failed = r->front = 0;
    for (i = 0; i < r->np; i++) {
        const lt_tune_point_t *p = &r->pts[i];
        int f = p->k.family;
        r->probed += (size_t)(p->probe.res != 0);
        r->measured += (size_t)p->full.ok;
        r->failed += (size_t)((p->probe.res != 0 && !p->probe.ok) || (p->full.res != 0 && !p->full.ok));
        r->pruned += (size_t)(p->pruned && p->probe.ok && !p->full.ok);
        r->front += (size_t)p->front;
        if (p->probe.res != 0) {
            r->fam_points[(size_t)f]++;
            r->fam_secs[(size_t)f] += p->probe.secs;
        }
        if (p->full.res != 0) {
            r->fam_points[(size_t)f]++;
            r->fam_secs[(size_t)f] += p->full.secs;
        }
    }
}

int lt_tune_search(const lt_tune_input_t *in, const lt_tune_opts_t *o, lt_tune_result_t *r,
                   lt_diag_t *diag)
{
    lt_tune_ctx_t *full, *probe = NULL;
    int *runs = NULL, nrun = 0;
    size_t i, nr = 0;
    double t0;
    memset(r, 0, sizeof *r);
    full = lt_tune_ctx_new(in, o->families, o->res, diag);
    if (full == NULL)
        return -1;
    (void)lt_tune_ctx_q16_refused(full, r->q16_note, sizeof r->q16_note);
    if (lt_tune_enumerate(o->families, o->machines, o->nmach, r->q16_note[0] != '\0', &r->pts,
                          &r->np, diag) != 0)
        goto fail;
    for (i = 0; i < r->np; i++)
        nrun = r->pts[i].run + 1 > nrun ? r->pts[i].run + 1 : nrun;
    runs = malloc((size_t)(nrun ? nrun : 1) * sizeof *runs);
    if (runs == NULL) {
        lt_diag_fail(diag, "out of memory");
        goto fail;
    }
    for (i = 0; i < (size_t)nrun; i++)
        runs[i] = (int)i;
    nr = (size_t)nrun;
    if (o->probe_res > 0 && o->probe_res < o->res) {
        t0 = now_s();
        probe = lt_tune_ctx_new(in, o->families, o->probe_res, diag);
        if (probe == NULL ||
            lt_tune_run_workers(probe, r->pts, r->np, runs, nr, 0, o->jobs, o->progress, "probe",
                                diag) != 0)
            goto fail;
        prune(r->pts, r->np, o->slack, runs, &nr);
        r->secs_probe = now_s() - t0;
    }
    t0 = now_s();
    if (lt_tune_run_workers(full, r->pts, r->np, runs, nr, 1, o->jobs, o->progress, "full size",
                            diag) != 0)
        goto fail;
    r->secs_full = now_s() - t0;
    lt_tune_mark_fronts(r->pts, r->np);
    tally(r);
    free(runs);
    lt_tune_ctx_free(probe);
    lt_tune_ctx_free(full);
    return 0;
fail:
    free(runs);
    lt_tune_ctx_free(probe);
    lt_tune_ctx_free(full);
    lt_tune_result_free(r);
    return -1;
}

void lt_tune_result_free(lt_tune_result_t *r)
{
    free(r->pts);
    r->pts = NULL;
    r->np = 0;
}
