/* ssbench.c - the screen-space quadtree (lt_qt.h, Widmer et al.) against its two baselines in the
 * same harness on the same rays: the DDA of McGuire & Mara (lt_ssdda.h) and the Hi-Z tracer of
 * Uludag / FidelityFX SSSR (lt_hiz.h). Per depth scene (the shared beachball EXR when present, the
 * analytic steps and spheres scenes of test_qt.c) and ray set (novel views from lt_reproj.h, or
 * the double fallback of tests/unit/lt_ssb_testlib.h without it; reflection rays), every tracer and
 * numeric path (quadtree n64 / n32 / f32, DDA and Hi-Z q30 / f32) traces the same packets; printed:
 * build cycles, trace cycles per ray (lrb16, sim build), host time, nodes / AABB / plane tests per
 * ray (Hi-Z: cells visited = lookups; DDA: pixels), lane utilisation, memory per pixel, and the
 * depth error against the double reference of the quadtree's model (host/render/lt_qt_ref.h); then ratios
 * and an error-vs-cycles table over every numeric configuration and three thicknesses.
 * Built for sim (cycles) and host (native times). Usage: see usage(). docs/ss-baselines.md.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "lt/lt_hiz.h"
#include "cli/lt_cliutil.h"
#include "lt/lt_qt.h"
#include "lt/lt_ssdda.h"
#if SSBENCH_HAVE_REPROJ
#include "lt/lt_reproj.h"
#endif
#include "io/lt_exr.h"
#include "lt_ssb_testlib.h"
#if LT_COST_MODE == LT_COST_SIM
#include "lt_sim.h"
#endif

#define TOL_DZ 1e-3 /* "within tolerance": same status and relative depth error <= 0.1% */

/* ---- configurations -------------------------------------------------------------------------- */

enum { K_QT, K_DDA, K_HIZ };
typedef struct cfg {
    const char *name;
    int kind; /* K_* */
    int enc;  /* lt_qt_enc_t for the quadtree, lt_ssb_enc_t for the baselines */
    int f32;  /* takes the float32 packets */
} cfg_t;
#define NCFG 7
static const cfg_t cfgs[NCFG] = {
    {"qt n64", K_QT, LT_QT_N64, 0},    {"qt n32", K_QT, LT_QT_N32, 0},
    {"qt f32", K_QT, LT_QT_F32, 1},    {"dda q30", K_DDA, LT_SSB_Q30, 0},
    {"dda f32", K_DDA, LT_SSB_F32, 1}, {"hiz q30", K_HIZ, LT_SSB_Q30, 0},
    {"hiz f32", K_HIZ, LT_SSB_F32, 1},
};
/* thicknesses of the error-vs-cycles sweep (theta, relative depth); thetas[DEF_TH] is the
 * default of lt_ssb_params_default (checked at start-up) */
#define NTH 4
#define DEF_TH 2
static const double thetas[NTH] = {1.0 / 1024.0, 1.0 / 256.0, 1.0 / 64.0, 1.0 / 16.0};

/* ---- one scene with every structure built --------------------------------------------------- */

typedef struct sctx {
    ss_scene_t s;
    lt_qt_t qt[3];
    void *qa[3];
    size_t qbytes[3];
    double qbuild[3];    /* BUILD cycles (sim) */
    lt_ssdda_t dda[NTH][2];
    lt_hiz_t hiz[NTH][2];
    void *ha[NTH][2];
    size_t hbytes;
    double hbuild[2];    /* BUILD cycles of the pyramid (sim) */
    lt_qt_ref_t wref[2]; /* the double reference on the s1.30 / float inputs */
} sctx_t;

static uint64_t sim_cycles(int phase_mask)
{
#if LT_COST_MODE == LT_COST_SIM
    lt_sim_totals_t t;
    uint64_t c = 0;
    int ph;
    lt_sim_totals(&t);
    for (ph = 0; ph < LT_PH__COUNT; ph++)
        if ((phase_mask >> ph) & 1)
            c += t.cycles[ph];
    return c;
#else
    (void)phase_mask;
    return 0;
#endif
}

static void sim_reset(void)
{
#if LT_COST_MODE == LT_COST_SIM
    lt_sim_reset();
#endif
}

static void sim_region(const void *p, size_t bytes, uint64_t base)
{
#if LT_COST_MODE == LT_COST_SIM
    if (p != NULL && bytes != 0)
        (void)lt_sim_region(p, bytes, base);
#else
    (void)p;
    (void)bytes;
    (void)base;
#endif
}

#define PH(x) (1 << LT_PH_##x)

/* Build everything for c->s (sampled). Returns 0 or -1 with a message. */
static int sctx_build(sctx_t *c)
{
    ss_scene_t *s = &c->s;
    lt_qt_params_t qp;
    lt_ssb_desc_t d;
    int f, i;
    uint64_t base = 0x10000000u;
    lt_qt_params_default(&qp);
    sim_region(s->wq, (size_t)s->W * s->H * s->layers * sizeof *s->wq, base);
    sim_region(s->wf, (size_t)s->W * s->H * s->layers * sizeof *s->wf, base + 0x08000000u);
    for (f = 0; f < 3; f++) {
        lt_qt_desc_t qd;
        size_t need = 0;
        lt_status_t st;
        qd.width = s->W;
        qd.height = s->H;
        qd.layers = s->layers;
        qd.enc = (uint32_t)cfgs[f].enc;
        if (lt_qt_size(&qd, &need) != LT_OK || (c->qa[f] = malloc(need)) == NULL) {
            fprintf(stderr, "ssbench: %s: quadtree %s of %zu bytes: size query or allocation "
                    "failed\n", s->name, cfgs[f].name, need);
            return -1;
        }
        c->qbytes[f] = need;
        sim_region(c->qa[f], need, base + 0x10000000u * (uint64_t)(f + 1));
        sim_reset();
        if (f < 2)
            st = lt_qt_build_q30(&c->qt[f], &qd, &qp, s->wq, c->qa[f], &need);
        else
            st = lt_qt_build_f32(&c->qt[f], &qd, &qp, s->wf, c->qa[f], &need);
        c->qbuild[f] = (double)sim_cycles(PH(BUILD));
        if (st != LT_OK) {
            fprintf(stderr, "ssbench: %s: quadtree %s build failed (%s)\n", s->name,
                    cfgs[f].name, lt_status_str(st));
            return -1;
        }
    }
    d.width = s->W;
    d.height = s->H;
    d.layers = s->layers;
    d.enc = LT_SSB_Q30;
    if (lt_hiz_size(&d, &c->hbytes) != LT_OK)
        return -1;
    for (i = 0; i < NTH; i++) {
        lt_ssb_params_t p;
        lt_ssb_params_default(&p);
        p.thickness = lt_q30_from_double_sat(thetas[i]);
        for (f = 0; f < 2; f++) {
            size_t need = c->hbytes;
            lt_status_t st;
            d.enc = (uint32_t)f;
            c->ha[i][f] = malloc(need + 8);
            if (c->ha[i][f] == NULL)
                return -1;
            if (i == DEF_TH)
                sim_region(c->ha[i][f], need, base + 0x40000000u + 0x08000000u * (uint64_t)f);
            sim_reset();
            if (f == 0) {
                st = lt_ssdda_init_q30(&c->dda[i][0], &d, &p, s->wq);
                if (st == LT_OK)
                    st = lt_hiz_build_q30(&c->hiz[i][0], &d, &p, s->wq, c->ha[i][0], &need);
            } else {
                st = lt_ssdda_init_f32(&c->dda[i][1], &d, &p, s->wf);
                if (st == LT_OK)
                    st = lt_hiz_build_f32(&c->hiz[i][1], &d, &p, s->wf, c->ha[i][1], &need);
            }
            if (i == DEF_TH)
                c->hbuild[f] = (double)sim_cycles(PH(BUILD));
            if (st != LT_OK) {
                fprintf(stderr, "ssbench: %s: DDA / Hi-Z set-up failed (%s)\n", s->name,
                        lt_status_str(st));
                return -1;
            }
        }
    }
    if (lt_qt_ref_build(&c->wref[0], s->wqd, s->W, s->H, s->layers, qp.lambda_h / SS_Q30,
                        qp.lambda_d / SS_Q30) != 0 ||
        lt_qt_ref_build(&c->wref[1], s->wfd, s->W, s->H, s->layers,
                        (double)((float)qp.lambda_h * 9.31322574615478515625e-10f),
                        (double)((float)qp.lambda_d * 9.31322574615478515625e-10f)) != 0) {
        fprintf(stderr, "ssbench: %s: reference build failed (out of memory)\n", s->name);
        return -1;
    }
    return 0;
}

static void sctx_free(sctx_t *c)
{
    int f, i;
    for (f = 0; f < 3; f++)
        free(c->qa[f]);
    for (i = 0; i < NTH; i++)
        for (f = 0; f < 2; f++)
            free(c->ha[i][f]);
    lt_qt_ref_free(&c->wref[0]);
    lt_qt_ref_free(&c->wref[1]);
    ss_scene_free(&c->s);
}

/* ---- ray sets: packets in both formats plus the exact doubles and the reference's answers ---- */

typedef struct rayset {
    char name[32];
    size_t npk;
    lt_qray16_q30_t *pq;
    lt_qray16_f32_t *pf;
    lt_mask16_t *kq, *kf;
    lt_qt_ref_ray_t *exq, *exf; /* npk x 16 */
    ss_res_t *refq, *reff;       /* the double reference per lane */
    size_t nq, nf;               /* lanes traced */
    double ref_pixels;           /* mean pixels the reference marched per ray (q30 rays) */
} rayset_t;

static int rs_alloc(rayset_t *rs, size_t npk)
{
    memset(rs->name, 0, sizeof rs->name);
    rs->npk = npk;
    rs->pq = (lt_qray16_q30_t *)calloc(npk, sizeof *rs->pq);
    rs->pf = (lt_qray16_f32_t *)calloc(npk, sizeof *rs->pf);
    rs->kq = (lt_mask16_t *)calloc(npk, sizeof *rs->kq);
    rs->kf = (lt_mask16_t *)calloc(npk, sizeof *rs->kf);
    rs->exq = (lt_qt_ref_ray_t *)calloc(npk * 16, sizeof *rs->exq);
    rs->exf = (lt_qt_ref_ray_t *)calloc(npk * 16, sizeof *rs->exf);
    rs->refq = (ss_res_t *)calloc(npk * 16, sizeof *rs->refq);
    rs->reff = (ss_res_t *)calloc(npk * 16, sizeof *rs->reff);
    return (rs->pq && rs->pf && rs->kq && rs->kf && rs->exq && rs->exf && rs->refq && rs->reff)
               ? 0
               : -1;
}

static void rs_free(rayset_t *rs)
{
    free(rs->pq);
    free(rs->pf);
    free(rs->kq);
    free(rs->kf);
    free(rs->exq);
    free(rs->exf);
    free(rs->refq);
    free(rs->reff);
}

/* Packets from double segments (16 per packet). */
static int rs_from_doubles(rayset_t *rs, const lt_qt_ref_ray_t *d, size_t n)
{
    size_t p;
    if (rs_alloc(rs, (n + 15) / 16) != 0)
        return -1;
    for (p = 0; p < rs->npk; p++) {
        size_t cnt = n - 16 * p < 16 ? n - 16 * p : 16;
        rs->kq[p] = ss_pack_q30(d + 16 * p, cnt, &rs->pq[p], rs->exq + 16 * p);
        rs->kf[p] = ss_pack_f32(d + 16 * p, cnt, &rs->pf[p], rs->exf + 16 * p);
    }
    return 0;
}

/* The median valid depth of layer 0 (scene units), for camera baselines. */
static double median_depth(const ss_scene_t *s)
{
    size_t n = (size_t)s->W * s->H, i, m = 0;
    double *v = (double *)malloc(n * sizeof *v), med = 1.0;
    if (v == NULL)
        return 1.0;
    for (i = 0; i < n; i++)
        if (s->wqd[i] > 0.0)
            v[m++] = s->wqd[i];
    if (m > 0) {
        qsort(v, m, sizeof *v, ss_cmp_double);
        med = ldexp(1.0, s->zexp) / v[m / 2];
    }
    free(v);
    return med;
}

/* Novel views: three target cameras moved from the source (no rotation) by baselines of a few
 * percent of the median depth (sideways, diagonal, and forward); rays of 4x4 target tiles on a grid
 * of step tiles, about nrays in all. */
#define NVIEWS 3
static const double view_t[NVIEWS][3] = {{0.06, 0.0, 0.0}, {-0.04, 0.03, 0.0}, {0.02, -0.02, 0.15}};

static int rs_novel(const ss_scene_t *s, size_t nrays, rayset_t *rs, const char **src)
{
    double zmed = median_depth(s);
    uint32_t tiles_x = s->W / 4, tiles_y = s->H / 4, step = 1, v;
    size_t per_view = nrays / NVIEWS, npk = 0;
    while ((size_t)((tiles_x + step - 1) / step) * ((tiles_y + step - 1) / step) * 16u > per_view)
        step++;
    npk = NVIEWS * (size_t)((tiles_x + step - 1) / step) * ((tiles_y + step - 1) / step);
    if (rs_alloc(rs, npk) != 0)
        return -1;
    npk = 0;
#if SSBENCH_HAVE_REPROJ
    *src = "lt_reproj";
    for (v = 0; v < NVIEWS; v++) {
        lt_reproj_cam_t sc, dc;
        lt_reproj_opts_t o;
        lt_reproj_q30_t mq;
        lt_reproj_f32_t mf;
        uint32_t tx, ty;
        int a;
        memset(&sc, 0, sizeof sc);
        sc.fx = sc.fy = s->focal;
        sc.cx = 0.5 * s->W;
        sc.cy = 0.5 * s->H;
        for (a = 0; a < 3; a++)
            sc.r[a][a] = 1.0;
        sc.width = s->W;
        sc.height = s->H;
        dc = sc;
        for (a = 0; a < 3; a++)
            dc.c[a] = view_t[v][a] * zmed;
        memset(&o, 0, sizeof o);
        o.z_ref = ldexp(1.0, s->zexp);
        if (lt_reproj_setup(&sc, &dc, &o, &mq, &mf) != LT_OK) {
            fprintf(stderr, "ssbench: %s: lt_reproj_setup failed for view %u\n", s->name, v);
            return -1;
        }
        for (ty = 0; ty + 4 <= s->H; ty += 4 * step) {
            for (tx = 0; tx + 4 <= s->W; tx += 4 * step) {
                lt_mask16_t kq = 0xFFFF, kf = 0xFFFF;
                (void)lt_reproj_rays16_q30(&mq, tx, ty, &rs->pq[npk], &kq);
                (void)lt_reproj_rays16_f32(&mf, tx, ty, &rs->pf[npk], &kf);
                rs->kq[npk] = kq;
                rs->kf[npk] = kf;
                ss_exact_q30(&rs->pq[npk], kq, rs->exq + 16 * npk);
                ss_exact_f32(&rs->pf[npk], kf, rs->exf + 16 * npk);
                npk++;
            }
        }
    }
#else
    *src = "double fallback (no lt_reproj.h)";
    for (v = 0; v < NVIEWS; v++) {
        double T[3];
        size_t n = rs->npk * 16, made, p;
        lt_qt_ref_ray_t *d = (lt_qt_ref_ray_t *)malloc(n * sizeof *d);
        int a;
        if (d == NULL)
            return -1;
        for (a = 0; a < 3; a++)
            T[a] = view_t[v][a] * zmed;
        made = ss_gen_novel(s, T, 1e-3 * zmed, step, n, d);
        for (p = 0; p < made / 16 && npk < rs->npk; p++, npk++) {
            rs->kq[npk] = ss_pack_q30(d + 16 * p, 16, &rs->pq[npk], rs->exq + 16 * npk);
            rs->kf[npk] = ss_pack_f32(d + 16 * p, 16, &rs->pf[npk], rs->exf + 16 * npk);
        }
        free(d);
    }
#endif
    rs->npk = npk;
    return 0;
}

/* The reference's answers for every lane of both formats. */
static void rs_reference(const sctx_t *c, rayset_t *rs)
{
    size_t p, i;
    double pix = 0.0;
    rs->nq = rs->nf = 0;
    for (p = 0; p < rs->npk; p++) {
        for (i = 0; i < 16; i++) {
            lt_qt_ref_hit_t h;
            ss_res_t *o;
            if ((rs->kq[p] >> i) & 1u) {
                lt_qt_ref_trace(&c->wref[0], &rs->exq[16 * p + i], &h);
                o = &rs->refq[16 * p + i];
                o->status = h.status;
                o->layer = h.layer;
                o->t = h.t;
                o->w = h.w;
                pix += (double)h.pixels;
                rs->nq++;
            }
            if ((rs->kf[p] >> i) & 1u) {
                lt_qt_ref_trace(&c->wref[1], &rs->exf[16 * p + i], &h);
                o = &rs->reff[16 * p + i];
                o->status = h.status;
                o->layer = h.layer;
                o->t = h.t;
                o->w = h.w;
                rs->nf++;
            }
        }
    }
    rs->ref_pixels = rs->nq ? pix / (double)rs->nq : 0.0;
}

/* ---- measuring one configuration on one ray set --------------------------------------------- */

typedef struct row {
    size_t n;                          /* rays */
    double cyc_ray, host_ns_ray;       /* trace (SETUP + TRAVERSE) cycles and host ns per ray */
    double nodes, aabb, planes;        /* per ray means */
    int nodes_max, aabb_max, planes_max;
    double util_sim, util_pk;          /* masked-op lane utilisation (sim); lane-steps / slots */
    double same, rmse, within, wrong;  /* % same status, depth RMSE, % within TOL_DZ,
                                          % wrong hits */
    size_t hits_both;
    double build_px, bytes_px;         /* build cycles per pixel, trace-time bytes per pixel */
    size_t diff[5];                    /* differing status: ref hit / ours occluded, ref occluded /
                                          ours hit, ref hit / ours miss, ref miss / ours hit,
                                          other (incl. UNKNOWN) */
    size_t diff1_start;                /* of diff[1]: our hit within 2 px of the ray's start */
} row_t;

static void measure(const sctx_t *c, int ci, int th, const rayset_t *rs, row_t *row)
{
    const cfg_t *cf = &cfgs[ci];
    const ss_scene_t *s = &c->s;
    size_t p, i, n = 0, same = 0, within = 0, wrong = 0, hb = 0;
    double t0, sq = 0.0, sn = 0.0, sa = 0.0, sp = 0.0, used = 0.0, slots = 0.0, px;
    lt_qhit16_q30_t *hq = NULL;
    lt_qhit16_f32_t *hf = NULL;
    memset(row, 0, sizeof *row);
    px = (double)s->W * s->H;
    if (cf->f32)
        hf = (lt_qhit16_f32_t *)malloc(rs->npk * sizeof *hf);
    else
        hq = (lt_qhit16_q30_t *)malloc(rs->npk * sizeof *hq);
    if (hq == NULL && hf == NULL)
        return;
    /* pass 1: the timed (and counted) traces only */
    sim_reset();
    t0 = lt_now_s();
    for (p = 0; p < rs->npk; p++) {
        lt_mask16_t k = cf->f32 ? rs->kf[p] : rs->kq[p];
        if (k == 0)
            continue;
        switch (cf->kind) {
        case K_QT:
            if (cf->f32)
                (void)lt_qt_trace16_f32(&c->qt[ci], &rs->pf[p], k, 0, &hf[p]);
            else
                (void)lt_qt_trace16_q30(&c->qt[ci], &rs->pq[p], k, 0, &hq[p]);
            break;
        case K_DDA:
            if (cf->f32)
                (void)lt_ssdda_trace16_f32(&c->dda[th][1], &rs->pf[p], k, 0, &hf[p]);
            else
                (void)lt_ssdda_trace16_q30(&c->dda[th][0], &rs->pq[p], k, 0, &hq[p]);
            break;
        default:
            if (cf->f32)
                (void)lt_hiz_trace16_f32(&c->hiz[th][1], &rs->pf[p], k, 0, &hf[p]);
            else
                (void)lt_hiz_trace16_q30(&c->hiz[th][0], &rs->pq[p], k, 0, &hq[p]);
            break;
        }
    }
    row->host_ns_ray = lt_now_s() - t0;
#if LT_COST_MODE == LT_COST_SIM
    {
        lt_sim_totals_t t;
        double on = 0.0, ops = 0.0;
        lt_sim_totals(&t);
        on = (double)(t.ctr[LT_PH_SETUP][LT_OP__COUNT + LT_EV_LANES_ON] +
                      t.ctr[LT_PH_TRAVERSE][LT_OP__COUNT + LT_EV_LANES_ON]);
        ops = (double)(t.ctr[LT_PH_SETUP][LT_OP__COUNT + LT_EV_LANE_OPS] +
                       t.ctr[LT_PH_TRAVERSE][LT_OP__COUNT + LT_EV_LANE_OPS]);
        row->util_sim = ops > 0.0 ? 100.0 * on / (16.0 * ops) : 0.0;
        row->cyc_ray = (double)(t.cycles[LT_PH_SETUP] + t.cycles[LT_PH_TRAVERSE]);
    }
#endif
    /* pass 2: statistics against the reference */
    for (p = 0; p < rs->npk; p++) {
        lt_mask16_t k = cf->f32 ? rs->kf[p] : rs->kq[p];
        int maxn = 0;
        for (i = 0; i < 16; i++) {
            const ss_res_t *h;
            const lt_qt_ref_ray_t *ex;
            int st, ly, nd, ab, pl;
            double t, w, len;
            if (!((k >> i) & 1u))
                continue;
            if (cf->f32) {
                st = hf[p].status.l[i], ly = hf[p].layer.l[i], nd = hf[p].nodes.l[i];
                ab = hf[p].aabb.l[i], pl = hf[p].planes.l[i];
                t = (double)hf[p].t.l[i], w = (double)hf[p].w.l[i];
                h = &rs->reff[16 * p + i];
                ex = &rs->exf[16 * p + i];
            } else {
                st = hq[p].status.l[i], ly = hq[p].layer.l[i], nd = hq[p].nodes.l[i];
                ab = hq[p].aabb.l[i], pl = hq[p].planes.l[i];
                t = hq[p].t.l[i] / SS_Q30, w = hq[p].w.l[i] / SS_Q30;
                h = &rs->refq[16 * p + i];
                ex = &rs->exq[16 * p + i];
            }
            n++;
            sn += nd;
            sa += ab;
            sp += pl;
            if (nd > row->nodes_max)
                row->nodes_max = nd;
            if (ab > row->aabb_max)
                row->aabb_max = ab;
            if (pl > row->planes_max)
                row->planes_max = pl;
            if (nd > maxn)
                maxn = nd;
            used += nd;
            len = hypot(ex->dx, ex->dy);
            if (st == h->status) {
                same++;
                if (st == LT_QT_HIT) {
                    double dz = fabs(1.0 / w - 1.0 / h->w) * h->w;
                    hb++;
                    sq += dz * dz;
                    if (dz <= TOL_DZ && ly == h->layer)
                        within++;
                    if (ly != h->layer || fabs(t - h->t) * len > 0.5)
                        wrong++;
                } else {
                    within++;
                }
            } else {
                int kind = 4;
                if (h->status == LT_QT_HIT && st == LT_QT_OCCLUDED)
                    kind = 0;
                else if (h->status == LT_QT_OCCLUDED && st == LT_QT_HIT) {
                    kind = 1;
                    row->diff1_start += (t - ex->tmin) * len <= 2.0;
                }
                else if (h->status == LT_QT_HIT && st == LT_QT_MISS)
                    kind = 2;
                else if (h->status == LT_QT_MISS && st == LT_QT_HIT)
                    kind = 3;
                row->diff[kind]++;
                if (st == LT_QT_HIT)
                    wrong++;
            }
        }
        slots += 16.0 * maxn;
    }
    free(hq);
    free(hf);
    row->n = n;
    row->host_ns_ray = n ? 1e9 * row->host_ns_ray / (double)n : 0.0;
    row->cyc_ray = n ? row->cyc_ray / (double)n : 0.0;
    row->util_pk = slots > 0.0 ? 100.0 * used / slots : 0.0;
    row->nodes = n ? sn / (double)n : 0.0;
    row->aabb = n ? sa / (double)n : 0.0;
    row->planes = n ? sp / (double)n : 0.0;
    row->same = n ? 100.0 * (double)same / (double)n : 0.0;
    row->within = n ? 100.0 * (double)within / (double)n : 0.0;
    row->wrong = n ? 100.0 * (double)wrong / (double)n : 0.0;
    row->rmse = hb ? sqrt(sq / (double)hb) : 0.0;
    row->hits_both = hb;
    switch (cf->kind) {
    case K_QT:
        row->build_px = c->qbuild[ci] / px;
        row->bytes_px = (double)c->qbytes[ci] / px;
        break;
    case K_DDA:
        row->build_px = 0.0;
        row->bytes_px = 4.0 * s->layers; /* the w buffer itself */
        break;
    default:
        row->build_px = c->hbuild[cf->f32] / px;
        row->bytes_px = 4.0 * s->layers + (double)c->hbytes / px;
        break;
    }
}

static void print_header(void)
{
    printf("%-10s %-10s %-8s %8s %9s %8s %13s %13s %13s %6s %6s %6s %7s %9s %7s %7s\n", "scene",
           "rays", "tracer", "build/px", "trace/ray", "ns/ray", "nodes mn(max)", "aabb mn(max)",
           "plane mn(max)", "util%", "pkut%", "B/px", "same%", "dRMSE", "tol%", "wrong%");
}

static void print_row(const char *scene, const char *rs, const char *name, const row_t *r)
{
    char nb[32], ab[32], pb[32];
    snprintf(nb, sizeof nb, "%.2f(%d)", r->nodes, r->nodes_max);
    snprintf(ab, sizeof ab, "%.2f(%d)", r->aabb, r->aabb_max);
    snprintf(pb, sizeof pb, "%.2f(%d)", r->planes, r->planes_max);
    printf("%-10s %-10s %-8s %8.1f %9.1f %8.0f %13s %13s %13s %6.1f %6.1f %6.2f %7.2f %9.3g "
           "%7.2f %7.2f\n",
           scene, rs, name, r->build_px, r->cyc_ray, r->host_ns_ray, nb, ab, pb, r->util_sim,
           r->util_pk, r->bytes_px, r->same, r->rmse, r->within, r->wrong);
}

/* ---- the error-vs-cycles table: sums over scenes and ray sets ------------------------------- */

typedef struct agg {
    double n, cyc, ns, sq, hb, same, within, wrong, build, px;
} agg_t;

#define NAGG (NCFG + 4 * (NTH - 1))
static agg_t aggs[NAGG];
static char agg_name[NAGG][32];

static void agg_add(int a, const row_t *r, double pixels)
{
    agg_t *g = &aggs[a];
    double n = (double)r->n;
    g->n += n;
    g->cyc += r->cyc_ray * n;
    g->ns += r->host_ns_ray * n;
    g->sq += r->rmse * r->rmse * (double)r->hits_both;
    g->hb += (double)r->hits_both;
    g->same += r->same * n;
    g->within += r->within * n;
    g->wrong += r->wrong * n;
    g->build += r->build_px * pixels;
    g->px += pixels;
}

/* ---- main ----------------------------------------------------------------------------------- */

static void usage(FILE *f)
{
    fprintf(f, "usage: ssbench [--rays N] [--quick] [--exr PATH] [--no-exr]\n"
               "  quadtree (n64, n32, f32) vs screen-space DDA vs Hi-Z (q30, f32), same rays\n"
               "  --rays N    rays per ray set, 64..262144 (default 4096)\n"
               "  --quick     1024 rays per set\n"
               "  --exr PATH  depth EXR (default ../shared/depth/beachball_singlepart.0001.exr)\n"
               "  --no-exr    analytic scenes only\n");
}

static int run_scene(sctx_t *c, size_t nrays)
{
    ss_scene_t *s = &c->s;
    rayset_t sets[2];
    const char *src = "";
    int r, ci, th;
    lt_qt_ref_ray_t *d;
    ltt_rng_t g;
    size_t nr;
    row_t rows[NCFG];
#if LT_COST_MODE == LT_COST_SIM
    lt_diag_t diag;
    if (lt_sim_init(lt_sim_machine_find("lrb16"), NULL, NULL, &diag) != 0) {
        fprintf(stderr, "ssbench: %s\n", diag.msg);
        return -1;
    }
#endif
    if (sctx_build(c) != 0)
        return -1;
    memset(sets, 0, sizeof sets);
    if (rs_novel(s, nrays, &sets[0], &src) != 0)
        return -1;
    snprintf(sets[0].name, sizeof sets[0].name, "novel");
    d = (lt_qt_ref_ray_t *)malloc(nrays * sizeof *d);
    if (d == NULL)
        return -1;
    ltt_rng_seed(&g, 2024);
    nr = ss_gen_refl(s, &g, nrays, d);
    if (rs_from_doubles(&sets[1], d, nr) != 0)
        return -1;
    snprintf(sets[1].name, sizeof sets[1].name, "reflect");
    free(d);
    printf("\n== %s %ux%u, %u layer(s), z_ref = 2^%d, pinhole f = %.0f px; novel views: %d "
           "cameras moved by (0.06, 0, 0), (-0.04, 0.03, 0), (0.02, -0.02, 0.15) x median depth "
           "%.3g, rays from %s; reflection rays: %zu\n",
           s->name, s->W, s->H, s->layers, s->zexp, s->focal, NVIEWS, median_depth(s), src, nr);
    printf("   memory: quadtree n64 %zu B, n32 %zu B, f32 %zu B; Hi-Z pyramid %zu B (+ the w "
           "buffer %zu B); DDA the w buffer only\n",
           c->qbytes[0], c->qbytes[1], c->qbytes[2], c->hbytes,
           (size_t)s->W * s->H * s->layers * 4u);
    for (r = 0; r < 2; r++) {
        rayset_t *rs = &sets[r];
        rs_reference(c, rs);
        printf("-- %s / %s: %zu rays (q30), %zu (f32); the reference marches %.1f pixels per "
               "ray\n",
               s->name, rs->name, rs->nq, rs->nf, rs->ref_pixels);
        print_header();
        for (ci = 0; ci < NCFG; ci++) {
            measure(c, ci, DEF_TH, rs, &rows[ci]);
            print_row(s->name, rs->name, cfgs[ci].name, &rows[ci]);
            agg_add(ci, &rows[ci], (double)s->W * s->H);
        }
        /* the thickness sweep of the baselines (middle one = the default, above) */
        {
            int a = NCFG;
            for (ci = 3; ci < NCFG; ci++) {
                for (th = 0; th < NTH; th++) {
                    row_t tr;
                    char nm[32];
                    if (th == DEF_TH)
                        continue;
                    measure(c, ci, th, rs, &tr);
                    snprintf(nm, sizeof nm, "%s th=2^%d", cfgs[ci].name,
                             (int)lrint(log2(thetas[th])));
                    snprintf(agg_name[a], sizeof agg_name[a], "%s", nm);
                    agg_add(a++, &tr, (double)s->W * s->H);
                }
            }
        }
        printf("   differing status (rays) for dda q30 / hiz q30 / qt n32: ref hit & ours occluded "
               "%zu / %zu / %zu, ref occluded & ours hit %zu / %zu / %zu (%zu / %zu / %zu of "
               "them within 2 px of the start), ref hit & ours miss "
               "%zu / %zu / %zu, ref miss & ours hit %zu / %zu / %zu, other %zu / %zu / %zu\n",
               rows[3].diff[0], rows[5].diff[0], rows[1].diff[0], rows[3].diff[1],
               rows[5].diff[1], rows[1].diff[1], rows[3].diff1_start, rows[5].diff1_start,
               rows[1].diff1_start, rows[3].diff[2], rows[5].diff[2],
               rows[1].diff[2], rows[3].diff[3], rows[5].diff[3], rows[1].diff[3],
               rows[3].diff[4], rows[5].diff[4], rows[1].diff[4]);
        printf("   ratios (trace cycles per ray): DDA q30 / qt n64 %.2f, Hi-Z q30 / qt n64 %.2f, "
               "DDA f32 / qt f32 %.2f, Hi-Z f32 / qt f32 %.2f; qt n64 cycles against DDA q30 "
               "%+.0f%%, against Hi-Z q30 %+.0f%%; visits per ray qt %.1f, DDA %.1f, Hi-Z %.1f\n",
               rows[3].cyc_ray / (rows[0].cyc_ray + 1e-30),
               rows[5].cyc_ray / (rows[0].cyc_ray + 1e-30),
               rows[4].cyc_ray / (rows[2].cyc_ray + 1e-30),
               rows[6].cyc_ray / (rows[2].cyc_ray + 1e-30),
               100.0 * (rows[0].cyc_ray / (rows[3].cyc_ray + 1e-30) - 1.0),
               100.0 * (rows[0].cyc_ray / (rows[5].cyc_ray + 1e-30) - 1.0), rows[0].nodes,
               rows[3].nodes, rows[5].nodes);
        rs_free(rs);
    }
#if LT_COST_MODE == LT_COST_SIM
    lt_sim_shutdown();
#endif
    return 0;
}

int main(int argc, char **argv)
{
    const char *exr = "../shared/depth/beachball_singlepart.0001.exr";
    size_t nrays = 4096;
    int a, use_exr = 1, sc, ci;
    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--rays") == 0 && a + 1 < argc) {
            char *end;
            long v = strtol(argv[++a], &end, 10);
            if (*end != '\0' || v < 64 || v > 262144) {
                fprintf(stderr, "ssbench: --rays %s: must be an integer in 64..262144\n", argv[a]);
                return 2;
            }
            nrays = (size_t)v;
        } else if (strcmp(argv[a], "--quick") == 0) {
            nrays = 1024;
        } else if (strcmp(argv[a], "--exr") == 0 && a + 1 < argc) {
            exr = argv[++a];
        } else if (strcmp(argv[a], "--no-exr") == 0) {
            use_exr = 0;
        } else if (strcmp(argv[a], "--help") == 0 || strcmp(argv[a], "-h") == 0) {
            usage(stdout);
            return 0;
        } else {
            fprintf(stderr, "ssbench: unknown or incomplete option '%s'\n", argv[a]);
            usage(stderr);
            return 2;
        }
    }
    for (ci = 0; ci < NCFG; ci++)
        snprintf(agg_name[ci], sizeof agg_name[ci], "%s%s", cfgs[ci].name,
                 cfgs[ci].kind == K_QT ? "" : " th=default");
    printf("ssbench: quadtree vs screen-space DDA (McGuire & Mara) vs Hi-Z (Uludag / "
           "FidelityFX) on the same rays; %s build%s\n",
           LT_COST_MODE == LT_COST_SIM ? "sim" : "host",
           LT_COST_MODE == LT_COST_SIM ? ", cycles on lrb16" : " (no cycle counts)");
    printf("columns: build/px = BUILD cycles per pixel; trace/ray = SETUP + TRAVERSE cycles per "
           "ray; ns/ray = host time%s; nodes = nodes / cells / pixels visited (Hi-Z: texel "
           "lookups per layer); aabb = ray-box (cell) tests; plane = plane / pixel tests; util%% = "
           "masked-op lane utilisation (sim); pkut%% = lane-steps / (16 x longest lane) per "
           "packet; B/px = bytes per pixel needed at trace time; against the double reference of "
           "the quadtree's model (host/render/lt_qt_ref.h): same%% status, dRMSE relative depth on common "
           "hits, tol%% = same status and depth within %.0e, wrong%% = hits the reference does not "
           "have or > 0.5 px away\n",
           LT_COST_MODE == LT_COST_SIM ? " with counting" : "", TOL_DZ);
    for (sc = 0; sc < 3; sc++) {
        sctx_t *c = (sctx_t *)calloc(1, sizeof *c);
        if (c == NULL)
            return 1;
        if (sc == 0) {
            lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
            lt_exr_depth_t d;
            lt_diag_t diag;
            FILE *fp;
            if (!use_exr) {
                free(c);
                continue;
            }
            fp = fopen(exr, "rb");
            if (fp == NULL) {
                const char *civ = getenv("CI");
                printf("\n== %s missing: shared depth scene skipped\n", exr);
                free(c);
                if (civ != NULL && strcmp(civ, "true") == 0) {
                    fprintf(stderr, "ssbench: %s missing under CI=true\n", exr);
                    return 1;
                }
                continue;
            }
            fclose(fp);
            memset(&d, 0, sizeof d);
            if (lt_exr_read_depth(exr, NULL, &o, &d, &diag) != 0) {
                fprintf(stderr, "ssbench: %s\n", diag.msg);
                free(c);
                return 1;
            }
            c->s.name = "beachball";
            c->s.W = (uint32_t)d.width;
            c->s.H = (uint32_t)d.height;
            c->s.focal = (double)c->s.W; /* assumed: the file has no intrinsics */
            if (ss_scene_from_depth(&c->s, d.z, NULL) != 0) {
                fprintf(stderr, "ssbench: %s: no valid depth or out of memory\n", exr);
                lt_exr_depth_free(&d);
                free(c);
                return 1;
            }
            lt_exr_depth_free(&d);
        } else {
            if (sc == 1)
                ss_scene_steps(&c->s);
            else
                ss_scene_spheres(&c->s);
            if (ss_scene_sample(&c->s) != 0) {
                free(c);
                return 1;
            }
        }
        if (run_scene(c, nrays) != 0) {
            sctx_free(c);
            free(c);
            return 1;
        }
        sctx_free(c);
        free(c);
    }
    printf("\n== error vs cycles, every numeric configuration (and thickness theta for the "
           "baselines), over all scenes and ray sets\n");
    printf("%-22s %10s %9s %9s %11s %8s %8s %8s\n", "configuration", "build/px", "trace/ray",
           "ns/ray", "depth RMSE", "same%", "tol%", "wrong%");
    for (ci = 0; ci < NAGG; ci++) {
        const agg_t *g = &aggs[ci];
        if (g->n <= 0.0)
            continue;
        printf("%-22s %10.1f %9.1f %9.0f %11.3g %8.2f %8.2f %8.2f\n", agg_name[ci],
               g->px > 0.0 ? g->build / g->px : 0.0, g->cyc / g->n, g->ns / g->n,
               g->hb > 0.0 ? sqrt(g->sq / g->hb) : 0.0, g->same / g->n, g->within / g->n,
               g->wrong / g->n);
    }
    return 0;
}
