/* lt_tune.c - configurations, the probe/prune/confirm search and its worker processes for
 * lanetrace tune (lt_tune.h). Host only.
 */
#include "tune/lt_tune.h"

#include "lt/lt_frusta.h"
#include "lt_meter.h"
#include "render/lt_paths.h"
#include "render/lt_path_ops.h"
#include "render/lt_render.h"
#include "render/lt_reproject.h"
#include "render/lt_softshadow.h"
#include "io/lt_scenefile.h"

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

const char *const lt_tune_cull_names[LT_TUNE_NCULL] = {"bcrflst", "bcr", "b"};
const unsigned lt_tune_cull_flags[LT_TUNE_NCULL] = {
    LT_SS_FLAGS_DEFAULT, LT_FRUSTA_BACKFACE | LT_FRUSTA_CORNER | LT_FRUSTA_CR, LT_FRUSTA_BACKFACE};

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

/* A path whose scene must pass the s15.16 representability check (skipped, with the reason
 * printed, for a scene that fails it). */
static int needs_q16_check(const lt_path_info_t *p)
{
    return p->render != NULL && p->render->scene_check != NULL;
}

static int enum_object(grow_t *g, int mach, int skip_q16)
{
    static const int leaves_bvh[] = {2, 4, 8, 16}, leaves_bvhq[] = {2, 4, 8, 15},
                     leaves_kd[] = {1, 2, 4, 8};
    int pi, s, j;
    for (pi = 0; lt_paths[pi].name != NULL; pi++) {
        if (!(lt_paths[pi].families & LT_PATHS_OBJECT) ||
            (skip_q16 && needs_q16_check(&lt_paths[pi])))
            continue;
        for (s = 0; lt_render_structures[s] != NULL; s++) {
            const char *sn = lt_render_structures[s];
            const int *lv = strcmp(sn, "bvh") == 0 ? leaves_bvh
                            : strcmp(sn, "bvhq") == 0 ? leaves_bvhq
                            : strcmp(sn, "kd") == 0 ? leaves_kd : NULL;
            if (strcmp(sn, "bvhq") == 0 && lt_paths[pi].render->bvhq_build == NULL)
                continue;
            /* the ray/triangle test on the BVH (the other structures take the default, wt):
               wt, mt, and on the s15.16 path wt32 */
            int ni = strcmp(sn, "bvh") != 0 ? 1 : lt_paths[pi].bvh_num == LT_BVH_NUM_Q16 ? 3 : 2;
            for (j = 0; j < (lv != NULL ? 4 : 1); j++) {
                int is;
                for (is = 0; is < ni; is++) {
                    lt_tune_knobs_t k;
                    memset(&k, 0, sizeof k);
                    k.family = 0;
                    k.machine = mach;
                    k.path = pi;
                    k.structure = s;
                    k.leaf = lv != NULL ? lv[j] : 0;
                    k.isect = is;
                    if (add(g, &k) != 0)
                        return -1;
                    g->run++;
                }
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
    static const int leaves[] = {4, 8, 16}, spps[] = {16, 4, 8, 32};
    int pi, j, cu, b, sp;
    for (pi = 0; lt_paths[pi].name != NULL; pi++) {
        if (!(lt_paths[pi].families & LT_PATHS_FRUSTA) ||
            (skip_q16 && needs_q16_check(&lt_paths[pi])))
            continue;
        /* every leaf and culling set at 16 samples per pixel; the other sample counts at the
           default leaf (8) and culling set */
        for (j = 0; j < 3; j++)
            for (cu = 0; cu < LT_TUNE_NCULL; cu++)
                for (sp = 0; sp < 4; sp++) {
                    if (sp > 0 && (leaves[j] != 8 || cu != 0))
                        continue;
                    for (b = 0; b < 8; b++) {
                        lt_tune_knobs_t k;
                        memset(&k, 0, sizeof k);
                        k.family = 2;
                        k.machine = mach;
                        k.path = pi;
                        k.leaf = leaves[j];
                        k.cull = cu;
                        k.spp = sp > 0 ? spps[sp] : 0;
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
        char is[16] = "";
        if (k->isect != 0)
            snprintf(is, sizeof is, " isect %s", lt_sf_isects[k->isect]);
        if (k->leaf > 0)
            snprintf(buf, n, "%s %s leaf %d%s", pn, lt_render_structures[k->structure], k->leaf,
                     is);
        else
            snprintf(buf, n, "%s %s%s", pn, lt_render_structures[k->structure], is);
    } else if (k->family == 1) {
        if (k->structure == LT_RP_QUADTREE)
            snprintf(buf, n, "%s quadtree %d layer%s gamma %s", pn, k->layers,
                     k->layers > 1 ? "s" : "", lt_tune_gammas[k->gamma].name);
        else
            snprintf(buf, n, "%s %s %d layer%s", strcmp(pn, "f32") == 0 ? "f32" : "s1.30",
                     tracer_names[k->structure], k->layers, k->layers > 1 ? "s" : "");
    } else {
        snprintf(buf, n, "%s %s/%s leaf %d cull %s filter %s spp %d", pn,
                 k->prim ? "P-Frusta" : "P-Packet", k->shadow ? "S-Packet" : "S-Frusta", k->leaf,
                 lt_tune_cull_names[k->cull], k->filter ? "on" : "off", k->spp ? k->spp : 16);
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

/* ---- the measurement server ------------------------------------------------------------------
 * One process, forked before the search allocates anything, loads the contexts (full and probe
 * size) and forks a child per requested run: every measurement starts from the same memory
 * state, so buffers the cycle model does not place at fixed simulated addresses (the soft-shadow
 * renderer's per-pixel buffers) land at the same addresses, and a run gives the same cycles with
 * any --jobs, in the verification and in a --job of a plan. Children write their records to one
 * pipe (a record is smaller than PIPE_BUF: writes do not interleave). */

#define REC_HELLO (-2000000000L)

typedef struct rec {
    long idx; /* point index; -1 - run: the run is done; REC_HELLO: the server's first word */
    lt_tune_meas_t m;
} rec_t;

typedef struct req {
    int run, full;
    char img[1024]; /* image prefix, "" for none */
} req_t;

/* One server process per size (probe, full), each forked from the caller's state before any
 * context exists, so the full-size measurements do not depend on whether probes run. */
typedef struct one_server {
    pid_t pid;
    int req_fd, res_fd;
} one_server_t;

struct lt_tune_server {
    one_server_t s[2]; /* [0] probe size (pid 0: none), [1] full size */
};

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

/* Records of every point of run (its measurements, or `why` as a failure), then "done". */
static void send_run(int fd, lt_tune_point_t *pts, size_t np, int run, int full, uint32_t res,
                     const char *why)
{
    rec_t rec;
    size_t i;
    for (i = 0; i < np; i++)
        if (pts[i].run == run) {
            memset(&rec, 0, sizeof rec);
            rec.idx = (long)i;
            rec.m = full ? pts[i].full : pts[i].probe;
            if (why != NULL) {
                memset(&rec.m, 0, sizeof rec.m);
                rec.m.res = res;
                snprintf(rec.m.msg, sizeof rec.m.msg, "%s", why);
            }
            (void)write_all(fd, &rec, sizeof rec);
        }
    memset(&rec, 0, sizeof rec);
    rec.idx = -1 - run;
    (void)write_all(fd, &rec, sizeof rec);
}

typedef struct child {
    pid_t pid;
    int run, full;
} child_t;

/* Reap finished children; a child that did not exit 0 gets its run reported as failed. */
static void reap(child_t *ch, int *nch, lt_tune_point_t *pts, size_t np, int fd, uint32_t res[2],
                 int block)
{
    int st, i;
    pid_t pid;
    while (*nch > 0 && (pid = waitpid(-1, &st, block ? 0 : WNOHANG)) > 0) {
        for (i = 0; i < *nch; i++)
            if (ch[i].pid == pid)
                break;
        if (i == *nch)
            continue;
        if (!WIFEXITED(st) || WEXITSTATUS(st) != 0) {
            char why[96];
            snprintf(why, sizeof why, "the measurement process died (%s %d)",
                     WIFSIGNALED(st) ? "signal" : "exit", WIFSIGNALED(st) ? WTERMSIG(st) : WEXITSTATUS(st));
            send_run(fd, pts, np, ch[i].run, ch[i].full, res[ch[i].full], why);
        }
        ch[i] = ch[--*nch];
        block = 0;
    }
}

/* The server's loop: one child per request; at most 64 at once (the caller keeps --jobs). */
static void server_loop(lt_tune_ctx_t *c, int full, lt_tune_point_t *pts, size_t np, int rq,
                        int fd, uint32_t res[2])
{
    child_t ch[64];
    int nch = 0;
    req_t q;
    while (read_all(rq, &q, sizeof q) == 1) {
        pid_t pid;
        reap(ch, &nch, pts, np, fd, res, 0);
        if (nch == 64)
            reap(ch, &nch, pts, np, fd, res, 1);
        if (q.full != full) {
            send_run(fd, pts, np, q.run, q.full, res[q.full], "no context for this size");
            continue;
        }
        pid = fork();
        if (pid == 0) {
            close(rq);
            lt_tune_eval_run(c, pts, np, q.run, q.full, q.img[0] ? q.img : NULL);
            send_run(fd, pts, np, q.run, q.full, res[q.full], NULL);
            _exit(0);
        }
        if (pid < 0) {
            send_run(fd, pts, np, q.run, q.full, res[q.full], "fork failed");
            continue;
        }
        ch[nch].pid = pid;
        ch[nch].run = q.run;
        ch[nch++].full = q.full;
    }
    while (nch > 0)
        reap(ch, &nch, pts, np, fd, res, 1);
}

/* A server process: its context (full or probe size), the enumeration, hello (the q16 note or the
 * load error), the loop. */
static void server_main(const lt_tune_input_t *in, const lt_tune_opts_t *o, int full, int rq,
                        int fd)
{
    lt_tune_ctx_t *c;
    lt_tune_point_t *pts = NULL;
    size_t np = 0;
    uint32_t res[2];
    lt_diag_t d;
    rec_t hello;
    memset(&hello, 0, sizeof hello);
    hello.idx = REC_HELLO;
    res[0] = o->probe_res;
    res[1] = o->res;
    c = lt_tune_ctx_new(in, o->families, res[full], &d);
    if (c == NULL) {
        snprintf(hello.m.msg, sizeof hello.m.msg, "%s", d.msg);
        (void)write_all(fd, &hello, sizeof hello);
        _exit(1);
    }
    (void)lt_tune_ctx_q16_refused(c, hello.m.msg, sizeof hello.m.msg);
    if (lt_tune_enumerate(o->families, o->machines, o->nmach, hello.m.msg[0] != '\0', &pts, &np,
                          &d) != 0) {
        snprintf(hello.m.msg, sizeof hello.m.msg, "%s", d.msg);
        (void)write_all(fd, &hello, sizeof hello);
        _exit(1);
    }
    hello.m.ok = 1;
    (void)write_all(fd, &hello, sizeof hello);
    server_loop(c, full, pts, np, rq, fd, res);
    _exit(0);
}

static void one_stop(one_server_t *s)
{
    if (s->pid <= 0)
        return;
    close(s->req_fd);
    close(s->res_fd);
    waitpid(s->pid, NULL, 0);
    s->pid = 0;
}

/* Fork one server; its hello into *hello. Returns 0 or -1 with a message. */
static int one_start(one_server_t *s, const lt_tune_input_t *in, const lt_tune_opts_t *o,
                     int full, rec_t *hello, lt_diag_t *diag)
{
    int rq[2], rs[2];
    if (pipe(rq) != 0 || pipe(rs) != 0)
        return lt_diag_fail(diag, "cannot start the measurement server: %s", strerror(errno));
    fflush(NULL);
    s->pid = fork();
    if (s->pid < 0)
        return lt_diag_fail(diag, "cannot start the measurement server: %s", strerror(errno));
    if (s->pid == 0) {
        close(rq[1]);
        close(rs[0]);
        server_main(in, o, full, rq[0], rs[1]);
    }
    close(rq[0]);
    close(rs[1]);
    s->req_fd = rq[1];
    s->res_fd = rs[0];
    if (read_all(s->res_fd, hello, sizeof *hello) != 1 || hello->idx != REC_HELLO || !hello->m.ok) {
        lt_diag_fail(diag, "%s", hello->idx == REC_HELLO && hello->m.msg[0] ? hello->m.msg
                                  : "the measurement server did not start");
        one_stop(s);
        return -1;
    }
    return 0;
}

lt_tune_server_t *lt_tune_server_start(const lt_tune_input_t *in, const lt_tune_opts_t *o,
                                       char *q16_note, size_t n, lt_diag_t *diag)
{
    lt_tune_server_t *s = calloc(1, sizeof *s);
    rec_t hello;
    if (s == NULL) {
        lt_diag_fail(diag, "out of memory");
        return NULL;
    }
    memset(&hello, 0, sizeof hello);
    /* the full-size server first: forked from the same state whether probes run or not */
    if (one_start(&s->s[1], in, o, 1, &hello, diag) != 0) {
        free(s);
        return NULL;
    }
    snprintf(q16_note, n, "%s", hello.m.msg);
    if (o->probe_res > 0 && o->probe_res < o->res &&
        one_start(&s->s[0], in, o, 0, &hello, diag) != 0) {
        lt_tune_server_stop(s);
        return NULL;
    }
    return s;
}

void lt_tune_server_stop(lt_tune_server_t *s)
{
    if (s == NULL)
        return;
    one_stop(&s->s[0]);
    one_stop(&s->s[1]);
    free(s);
}

int lt_tune_server_run(lt_tune_server_t *s, lt_tune_point_t *pts, size_t np, const int *runs,
                       size_t nruns, int full, int jobs, const char *img_prefix,
                       void (*progress)(const char *stage, size_t done, size_t total),
                       const char *stage, lt_diag_t *diag)
{
    size_t sent = 0, done = 0;
    one_server_t *os = &s->s[full ? 1 : 0];
    req_t q;
    rec_t rec;
    if (os->pid <= 0)
        return lt_diag_fail(diag, "no measurement server for the %s size", full ? "full" : "probe");
    memset(&q, 0, sizeof q);
    q.full = full;
    if (img_prefix != NULL)
        snprintf(q.img, sizeof q.img, "%s", img_prefix);
    if (jobs < 1)
        jobs = 1;
    while (done < nruns) {
        while (sent < nruns && sent - done < (size_t)jobs) {
            q.run = runs[sent++];
            if (write_all(os->req_fd, &q, sizeof q) != 0)
                return lt_diag_fail(diag, "the measurement server stopped");
        }
        if (read_all(os->res_fd, &rec, sizeof rec) != 1)
            return lt_diag_fail(diag, "the measurement server stopped");
        if (rec.idx >= 0 && (size_t)rec.idx < np) {
            if (full)
                pts[rec.idx].full = rec.m;
            else
                pts[rec.idx].probe = rec.m;
        } else if (rec.idx < 0 && rec.idx != REC_HELLO) {
            done++;
            if (progress != NULL)
                progress(stage, done, nruns);
        }
    }
    return 0;
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

/* A probe's cycles scaled to full size: the per-pixel phases times the pixel ratio; the object and
 * shadows structures' BUILD phase does not depend on the image size (the screen family builds
 * over the image: it scales too). */
static double est_cycles(const lt_tune_point_t *p, double ratio)
{
    double build = p->probe.phase[LT_PH_BUILD];
    if (p->k.family == 1)
        return p->probe.m[LT_M_CYCLES] * ratio;
    return build + (p->probe.m[LT_M_CYCLES] - build) * ratio;
}

/* Prune at the probe resolution: p goes when some q of its family and machine is no worse in both
 * errors and in bytes and cheaper by the slack in cycles (estimated at full size, est_cycles).
 * Returns the runs to measure at full size (into runs, *nruns). */
static void prune(lt_tune_point_t *pts, size_t np, double slack, double ratio, int *runs,
                  size_t *nruns)
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
        a[0] = est_cycles(&pts[i], ratio);
        for (j = 0; j < np && !pts[i].pruned; j++) {
            if (j == i || !pts[j].probe.ok || pts[j].k.family != pts[i].k.family ||
                pts[j].k.machine != pts[i].k.machine)
                continue;
            (void)lt_tune_objectives(pts[j].k.family, &pts[j].probe, b);
            b[0] = est_cycles(&pts[j], ratio);
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

void lt_tune_tally(lt_tune_result_t *r)
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

int lt_tune_search(lt_tune_server_t *srv, const lt_tune_opts_t *o, lt_tune_result_t *r,
                   lt_diag_t *diag)
{
    int *runs = NULL, nrun = 0;
    size_t i, nr = 0;
    double t0;
    char note[sizeof r->q16_note];
    snprintf(note, sizeof note, "%s", r->q16_note);
    memset(r, 0, sizeof *r);
    snprintf(r->q16_note, sizeof r->q16_note, "%s", note);
    if (lt_tune_enumerate(o->families, o->machines, o->nmach, r->q16_note[0] != '\0', &r->pts,
                          &r->np, diag) != 0)
        return -1;
    for (i = 0; i < r->np; i++)
        nrun = r->pts[i].run + 1 > nrun ? r->pts[i].run + 1 : nrun;
    runs = malloc((size_t)(nrun ? nrun : 1) * sizeof *runs);
    if (runs == NULL) {
        lt_tune_result_free(r);
        return lt_diag_fail(diag, "out of memory");
    }
    for (i = 0; i < (size_t)nrun; i++)
        runs[i] = (int)i;
    nr = (size_t)nrun;
    if (o->probe_res > 0 && o->probe_res < o->res) {
        t0 = now_s();
        if (lt_tune_server_run(srv, r->pts, r->np, runs, nr, 0, o->jobs, NULL, o->progress,
                               "probe", diag) != 0)
            goto fail;
        prune(r->pts, r->np, o->slack,
              ((double)o->res * o->res) / ((double)o->probe_res * o->probe_res), runs, &nr);
        r->secs_probe = now_s() - t0;
    }
    t0 = now_s();
    if (lt_tune_server_run(srv, r->pts, r->np, runs, nr, 1, o->jobs, NULL, o->progress,
                           "full size", diag) != 0)
        goto fail;
    r->secs_full = now_s() - t0;
    lt_tune_mark_fronts(r->pts, r->np);
    lt_tune_tally(r);
    free(runs);
    return 0;
fail:
    free(runs);
    lt_tune_result_free(r);
    return -1;
}

void lt_tune_result_free(lt_tune_result_t *r)
{
    free(r->pts);
    r->pts = NULL;
    r->np = 0;
}
