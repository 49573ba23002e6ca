/* lt_reproject.c - view synthesis by screen-space ray tracing (Widmer et al. 2015 [Widmer15],
 * section 5): quadtree over the source depth layers (lt_qt.h), reprojected segments per 4x4 target
 * tile (lt_reproj.h), colour fetch (nearest or depth-aware bilinear), target depth,
 * background-biased pull-push inpainting of the holes, per-pixel steps and simulated cycles. Host
 * only (malloc, double); the same code runs in the host, asan and sim builds. docs/reproject.md.
 */
#include "render/lt_reproject.h"
#include "cli/lt_cliutil.h"
#include "lt_meter.h"
#include "render/lt_par.h"
#include "render/lt_paths.h"
#include "render/lt_qt_ref.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* A segment start within this many pixels of the source's border was clipped by the screen (the
 * clip puts it on the border up to rounding in s15.16 or float32). */
#define RP_EDGE_EPS (1.0 / 256.0)

static uint64_t cycles_now(void) { return lt_meter_cycles(); }

void lt_rp_opts_default(lt_rp_opts_t *o)
{
    memset(o, 0, sizeof *o);
    o->enc = LT_QT_N64;
    o->bilinear = 1;
    o->inpaint = 1;
    lt_qt_params_default(&o->params);
    o->tracer = LT_RP_QUADTREE;
    o->single = 0;
    lt_ssb_params_default(&o->ssb);
}

int lt_rp_auto_single(const char *machine, lt_qt_enc_t enc, lt_rp_tracer_t tracer, char *why,
                      size_t why_len)
{
    const lt_path_info_t *p = lt_paths_of_qt_enc(enc);
    lt_meter_machine_t m;
    char tmp[8];
    if (why == NULL) {
        why = tmp;
        why_len = sizeof tmp;
    }
    if (tracer != LT_RP_QUADTREE || p == NULL || p->screen == NULL || p->screen->qt_trace1 == NULL) {
        snprintf(why, why_len, "the single-ray walk is the s1.30 quadtree's");
        return 0;
    }
    if (machine == NULL || lt_meter_machine_info(machine, &m) != 0) {
        snprintf(why, why_len, "no machine model in this build");
        return 0;
    }
    if (m.lanes >= 16) {
        snprintf(why, why_len, "machine %s has %u lanes", m.name, m.lanes);
        return 0;
    }
    snprintf(why, why_len, "machine %s has %u lane%s, where a packet step costs all 16 lanes",
             m.name, m.lanes, m.lanes == 1 ? "" : "s");
    return 1;
}

/* The structure one run traces: the quadtree, the DDA over the w buffer or the Hi-Z pyramid. */
typedef struct rp_tracer {
    lt_rp_tracer_t kind;
    lt_qt_t qt;
    lt_ssdda_t dda;
    lt_hiz_t hiz;
} rp_tracer_t;

/* One packet of segments r through the tracer in the path's format, results into h. */
static void trace16(const rp_tracer_t *t, const lt_rp_ops_t *ops, int single, const void *r,
                    lt_mask16_t k, uint32_t max_steps, void *h)
{
    if (t->kind == LT_RP_DDA)
        ops->dda_trace16(&t->dda, r, k, max_steps, h);
    else if (t->kind == LT_RP_HIZ)
        ops->hiz_trace16(&t->hiz, r, k, max_steps, h);
    else if (single)
        ops->qt_trace1(&t->qt, r, k, max_steps, h);
    else
        ops->qt_trace16(&t->qt, r, k, max_steps, h);
}

/* Build (quadtree, Hi-Z) or set up (DDA) the tracer over the w buffer of path p; *arena gets the
 * memory (NULL for the DDA), *bytes its size. Returns 0 or -1 with a message. */
static int tracer_build(rp_tracer_t *t, const lt_rp_opts_t *o, const lt_path_info_t *p,
                        uint32_t W, uint32_t H, uint32_t layers, const void *w, void **arena,
                        size_t *bytes, lt_diag_t *diag)
{
    const lt_rp_ops_t *ops = p->screen;
    lt_status_t s;
    lt_ssb_desc_t sd;
    static const char *const name[3] = {"quadtree", "DDA", "Hi-Z"};
    t->kind = o->tracer;
    *arena = NULL;
    *bytes = 0;
    sd.width = W;
    sd.height = H;
    sd.layers = layers;
    sd.enc = (lt_ssb_enc_t)p->ssb_enc;
    if (o->tracer == LT_RP_DDA) {
        s = ops->dda_init(&t->dda, &sd, &o->ssb, w);
    } else {
        lt_qt_desc_t qd;
        qd.width = W;
        qd.height = H;
        qd.layers = layers;
        qd.enc = (uint32_t)p->qt_enc;
        s = o->tracer == LT_RP_HIZ ? lt_hiz_size(&sd, bytes) : lt_qt_size(&qd, bytes);
        if (s != LT_OK) {
            lt_diag_fail(diag, "reproject: %s size query failed for %ux%u x %u layers (%s)",
                         name[o->tracer], W, H, layers, lt_status_str(s));
            return -1;
        }
        *arena = malloc(*bytes > 0 ? *bytes : 1);
        if (*arena == NULL) {
            lt_diag_fail(diag, "reproject: out of memory for the %zu-byte %s", *bytes,
                         name[o->tracer]);
            return -1;
        }
        lt_meter_region(*arena, *bytes, 0x40000000u);
        if (o->tracer == LT_RP_HIZ)
            s = ops->hiz_build(&t->hiz, &sd, &o->ssb, w, *arena, bytes);
        else
            s = ops->qt_build(&t->qt, &qd, &o->params, w, *arena, bytes);
    }
    if (s != LT_OK) {
        lt_diag_fail(diag, "reproject: %s build failed (%s)", name[o->tracer],
                     lt_status_str(s));
        return -1;
    }
    return 0;
}

void lt_rp_result_free(lt_rp_result_t *r)
{
    free(r->rgb);
    free(r->z);
    free(r->cls);
    free(r->steps);
    free(r->cycles);
    free(r->sx);
    free(r->sy);
    free(r->layer);
    memset(r, 0, sizeof *r);
}

/* ---- cameras ------------------------------------------------------------------------------- */

void lt_rp_cam_default(uint32_t w, uint32_t h, int32_t disp_w, int32_t disp_h, int32_t ox,
                       int32_t oy, double hfov_deg, lt_reproj_cam_t *c)
{
    double dw = disp_w > 0 ? (double)disp_w : (double)w, dh = disp_h > 0 ? (double)disp_h : (double)h;
    int i, j;
    memset(c, 0, sizeof *c);
    c->fx = c->fy = 0.5 * dw / tan(0.5 * hfov_deg * 3.14159265358979323846 / 180.0);
    c->cx = 0.5 * dw - (double)ox;
    c->cy = 0.5 * dh - (double)oy;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            c->r[i][j] = i == j ? 1.0 : 0.0;
    c->width = w;
    c->height = h;
}

void lt_rp_cam_move(const lt_reproj_cam_t *src, const double move[3], const double rot_deg[3],
                    lt_reproj_cam_t *dst)
{
    const double k = 3.14159265358979323846 / 180.0;
    double cy = cos(rot_deg[0] * k), sy = sin(rot_deg[0] * k);
    double cp = cos(rot_deg[1] * k), sp = sin(rot_deg[1] * k);
    double cr = cos(rot_deg[2] * k), sr = sin(rot_deg[2] * k);
    /* rows: the new camera axes in the old camera's coordinates. Yaw: z turns toward +x (right);
     * pitch: z turns toward -y (up, y points down); roll: x turns toward +y. Applied yaw, pitch,
     * roll: Q = Qroll Qpitch Qyaw. */
    double qy[3][3] = {{cy, 0, -sy}, {0, 1, 0}, {sy, 0, cy}};
    double qp[3][3] = {{1, 0, 0}, {0, cp, sp}, {0, -sp, cp}};
    double qr[3][3] = {{cr, sr, 0}, {-sr, cr, 0}, {0, 0, 1}};
    double t[3][3], q[3][3];
    lt_reproj_cam_t d = *src;
    int i, j, l;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            t[i][j] = 0.0;
            for (l = 0; l < 3; l++)
                t[i][j] += qp[i][l] * qy[l][j];
        }
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            q[i][j] = 0.0;
            for (l = 0; l < 3; l++)
                q[i][j] += qr[i][l] * t[l][j];
        }
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            d.r[i][j] = 0.0;
            for (l = 0; l < 3; l++)
                d.r[i][j] += q[i][l] * src->r[l][j];
        }
        d.c[i] = src->c[i];
        for (l = 0; l < 3; l++)
            d.c[i] += src->r[l][i] * move[l]; /* R^T move: camera offset in world units */
    }
    *dst = d;
}

double lt_rp_target_depth(const lt_reproj_cam_t *src, const lt_reproj_cam_t *dst, double zref,
                          double x, double y, double w)
{
    double zs = zref / w, pc[3], pw[3], z = 0.0;
    int i;
    pc[0] = zs * (x - src->cx) / src->fx;
    pc[1] = zs * (y - src->cy) / src->fy;
    pc[2] = zs;
    for (i = 0; i < 3; i++)
        pw[i] = src->c[i] + src->r[0][i] * pc[0] + src->r[1][i] * pc[1] + src->r[2][i] * pc[2];
    for (i = 0; i < 3; i++)
        z += dst->r[2][i] * (pw[i] - dst->c[i]);
    return z;
}

/* ---- inpainting --------------------------------------------------------------------------- */

#define BG_KEEP 0.9f /* children / neighbours within 10% of the farthest depth take part */

typedef struct lvl {
    uint32_t w, h;
    float *c; /* w x h x 3 */
    float *z;
    uint8_t *v;
} lvl_t;

/* Background-biased weighted mean of up to 4 samples; returns 0 when none is valid. */
static int bg_mix(const float *c[4], const float z[4], const float wt[4], int n, float out_c[3],
                  float *out_z)
{
    float zmax = -1.0f, sw = 0.0f, acc[3] = {0, 0, 0}, az = 0.0f;
    int i, inf = 0;
    for (i = 0; i < n; i++) {
        if (wt[i] <= 0.0f)
            continue;
        if (isinf(z[i]))
            inf = 1;
        else if (z[i] > zmax)
            zmax = z[i];
    }
    if (!inf && zmax < 0.0f)
        return 0;
    for (i = 0; i < n; i++) {
        int keep;
        if (wt[i] <= 0.0f)
            continue;
        keep = inf ? isinf(z[i]) : (z[i] >= BG_KEEP * zmax);
        if (!keep)
            continue;
        sw += wt[i];
        acc[0] += wt[i] * c[i][0];
        acc[1] += wt[i] * c[i][1];
        acc[2] += wt[i] * c[i][2];
        if (!inf)
            az += wt[i] * z[i];
    }
    if (sw <= 0.0f)
        return 0;
    out_c[0] = acc[0] / sw;
    out_c[1] = acc[1] / sw;
    out_c[2] = acc[2] / sw;
    *out_z = inf ? INFINITY : az / sw;
    return 1;
}

int lt_rp_inpaint(float *rgb, float *z, const uint8_t *valid, uint32_t w, uint32_t h)
{
    lvl_t L[32];
    int n = 0, l, ok = -1;
    size_t i, cnt = 0;
    for (i = 0; i < (size_t)w * h; i++)
        cnt += valid[i] != 0;
    if (cnt == 0)
        return -1;
    memset(L, 0, sizeof L);
    L[0].w = w;
    L[0].h = h;
    L[0].c = rgb;
    L[0].z = z;
    L[0].v = malloc((size_t)w * h);
    if (L[0].v == NULL)
        return -1;
    memcpy(L[0].v, valid, (size_t)w * h);
    n = 1;
    /* pull */
    while ((L[n - 1].w > 1 || L[n - 1].h > 1) && n < 32) {
        lvl_t *f = &L[n - 1], *c = &L[n];
        uint32_t x, y;
        c->w = (f->w + 1) / 2;
        c->h = (f->h + 1) / 2;
        c->c = malloc((size_t)c->w * c->h * 3 * sizeof(float));
        c->z = malloc((size_t)c->w * c->h * sizeof(float));
        c->v = malloc((size_t)c->w * c->h);
        n++;
        if (c->c == NULL || c->z == NULL || c->v == NULL)
            goto out;
        for (y = 0; y < c->h; y++)
            for (x = 0; x < c->w; x++) {
                const float *cc[4];
                float zz[4], wt[4];
                size_t o = (size_t)y * c->w + x;
                int k;
                for (k = 0; k < 4; k++) {
                    uint32_t fx = 2 * x + (uint32_t)(k & 1), fy = 2 * y + (uint32_t)(k >> 1);
                    size_t fo = (size_t)fy * f->w + fx;
                    if (fx < f->w && fy < f->h && f->v[fo]) {
                        cc[k] = &f->c[3 * fo];
                        zz[k] = f->z[fo];
                        wt[k] = 1.0f;
                    } else {
                        cc[k] = NULL;
                        zz[k] = 0.0f;
                        wt[k] = 0.0f;
                    }
                }
                c->v[o] = (uint8_t)bg_mix(cc, zz, wt, 4, &c->c[3 * o], &c->z[o]);
                if (!c->v[o]) {
                    c->c[3 * o] = c->c[3 * o + 1] = c->c[3 * o + 2] = 0.0f;
                    c->z[o] = 0.0f;
                }
            }
    }
    /* push: the top is valid (at least one valid pixel); fill each level's holes from the level
     * above, which is complete by then */
    for (l = n - 2; l >= 0; l--) {
        lvl_t *f = &L[l], *c = &L[l + 1];
        uint32_t x, y;
        for (y = 0; y < f->h; y++)
            for (x = 0; x < f->w; x++) {
                size_t o = (size_t)y * f->w + x;
                const float *cc[4];
                float zz[4], wt[4], gx, gy, ax, ay;
                int k, x0, y0;
                if (f->v[o])
                    continue;
                /* the fine pixel centre in coarse pixel coordinates */
                gx = ((float)x + 0.5f) * 0.5f - 0.5f;
                gy = ((float)y + 0.5f) * 0.5f - 0.5f;
                x0 = (int)floorf(gx);
                y0 = (int)floorf(gy);
                ax = gx - (float)x0;
                ay = gy - (float)y0;
                for (k = 0; k < 4; k++) {
                    int cx = x0 + (k & 1), cy = y0 + (k >> 1);
                    size_t co;
                    if (cx < 0)
                        cx = 0;
                    if (cy < 0)
                        cy = 0;
                    if (cx >= (int)c->w)
                        cx = (int)c->w - 1;
                    if (cy >= (int)c->h)
                        cy = (int)c->h - 1;
                    co = (size_t)cy * c->w + (size_t)cx;
                    cc[k] = &c->c[3 * co];
                    zz[k] = c->z[co];
                    wt[k] = ((k & 1) ? ax : 1.0f - ax) * ((k >> 1) ? ay : 1.0f - ay);
                    if (!c->v[co])
                        wt[k] = 0.0f;
                }
                if (!bg_mix(cc, zz, wt, 4, &f->c[3 * o], &f->z[o])) {
                    /* all four weights zero (exactly on a coarse centre whose value is used) */
                    float one[4] = {1, 1, 1, 1};
                    if (!bg_mix(cc, zz, one, 4, &f->c[3 * o], &f->z[o]))
                        continue;
                }
                f->v[o] = 1;
            }
    }
    ok = 0;
out:
    free(L[0].v);
    for (l = 1; l < n; l++) {
        free(L[l].c);
        free(L[l].z);
        free(L[l].v);
    }
    return ok;
}

/* ---- colour fetch -------------------------------------------------------------------------- */

typedef struct fetch_ctx {
    const lt_rp_source_t *src;
    const float *wl; /* layers x H x W w (double-precision values of what the core saw) */
    double zref;
    int bilinear;
} fetch_ctx_t;

static void layer_colour(const fetch_ctx_t *f, uint32_t layer, size_t p, float out[3])
{
    const float *c = f->src->rgb[layer];
    if (c != NULL) {
        out[0] = c[3 * p];
        out[1] = c[3 * p + 1];
        out[2] = c[3 * p + 2];
    } else {
        float g = f->wl[(size_t)layer * f->src->width * f->src->height + p];
        out[0] = out[1] = out[2] = g;
    }
}

/* Colour at source position (x, y) of layer `layer`, hit inverse depth w. Depth-aware bilinear:
 * the four pixel centres around (x, y) weighted bilinearly, keeping only those whose own w lies
 * within 5% of the hit's (a neighbour across a depth edge belongs to another surface); none left
 * (or nearest mode): the pixel containing (x, y). */
static void fetch(const fetch_ctx_t *f, uint32_t layer, double x, double y, double w, float out[3])
{
    uint32_t W = f->src->width, H = f->src->height;
    size_t base = (size_t)layer * W * H;
    int px = (int)floor(x), py = (int)floor(y);
    if (px < 0)
        px = 0;
    if (py < 0)
        py = 0;
    if (px >= (int)W)
        px = (int)W - 1;
    if (py >= (int)H)
        py = (int)H - 1;
    if (f->bilinear) {
        double gx = x - 0.5, gy = y - 0.5, ax, ay, sw = 0.0, acc[3] = {0, 0, 0};
        int x0 = (int)floor(gx), y0 = (int)floor(gy), k;
        ax = gx - x0;
        ay = gy - y0;
        for (k = 0; k < 4; k++) {
            int cx = x0 + (k & 1), cy = y0 + (k >> 1);
            double wt = ((k & 1) ? ax : 1.0 - ax) * ((k >> 1) ? ay : 1.0 - ay), wn;
            float c[3];
            size_t p;
            if (cx < 0 || cy < 0 || cx >= (int)W || cy >= (int)H || wt <= 0.0)
                continue;
            p = (size_t)cy * W + (size_t)cx;
            wn = (double)f->wl[base + p];
            if (!(fabs(wn - w) <= 0.05 * w))
                continue;
            layer_colour(f, layer, p, c);
            sw += wt;
            acc[0] += wt * (double)c[0];
            acc[1] += wt * (double)c[1];
            acc[2] += wt * (double)c[2];
        }
        if (sw > 0.0) {
            out[0] = (float)(acc[0] / sw);
            out[1] = (float)(acc[1] / sw);
            out[2] = (float)(acc[2] / sw);
            return;
        }
    }
    layer_colour(f, layer, (size_t)py * W + (size_t)px, out);
}

/* ---- the run ------------------------------------------------------------------------------- */

/* The class, colour, depth and source position of target pixel p from its traced lane. */
static void classify(lt_rp_result_t *res, lt_rp_stats_t *st, const fetch_ctx_t *fc,
                     const lt_reproj_cam_t *dst, size_t p, const lt_rp_lane_t *ln)
{
    const lt_rp_source_t *src = fc->src;
    uint32_t W = src->width, H = src->height;
    double t = ln->t, w = ln->w, rx = ln->x, ry = ln->y, rdx = ln->dx, rdy = ln->dy;
    st->rays++;
    st->nodes += ln->nodes;
    st->aabb += ln->aabb;
    st->planes += ln->planes;
    if (ln->nodes > st->nodes_max)
        st->nodes_max = ln->nodes;
    if (ln->aabb > st->aabb_max)
        st->aabb_max = ln->aabb;
    if (ln->planes > st->planes_max)
        st->planes_max = ln->planes;
    res->steps[p] = (float)ln->nodes;
    if (ln->status == LT_QT_HIT && w > 0.0) {
        double sx = rx + t * rdx, sy = ry + t * rdy;
        res->cls[p] = LT_RP_HIT;
        res->sx[p] = (float)sx;
        res->sy[p] = (float)sy;
        res->layer[p] = ln->layer;
        fetch(fc, (uint32_t)ln->layer, sx, sy, w, &res->rgb[3 * p]);
        res->z[p] = (float)lt_rp_target_depth(&src->cam, dst, res->st.zref, sx, sy, w);
    } else if (ln->status == LT_QT_MISS && ln->w0 + ln->dw <= 0.0 && t >= 1.0 &&
               rx > RP_EDGE_EPS && rx < (double)W - RP_EDGE_EPS &&
               ry > RP_EDGE_EPS && ry < (double)H - RP_EDGE_EPS) {
        /* reached the vanishing point on screen, the whole segment seen by the source: the
           source's background there. A segment whose start the screen clipped entered the view
           from outside: what lies on its unseen part is unknown, so it stays LT_RP_OUTSIDE. */
        double ex = rx + rdx, ey = ry + rdy;
        int bx = (int)floor(ex), by = (int)floor(ey);
        if (bx >= (int)W)
            bx = (int)W - 1;
        if (by >= (int)H)
            by = (int)H - 1;
        if (bx < 0)
            bx = 0;
        if (by < 0)
            by = 0;
        res->cls[p] = LT_RP_BACKGROUND;
        layer_colour(fc, 0, (size_t)by * W + (size_t)bx, &res->rgb[3 * p]);
        if (src->rgb[0] == NULL)
            res->rgb[3 * p] = res->rgb[3 * p + 1] = res->rgb[3 * p + 2] = 0.0f;
        res->z[p] = INFINITY;
    } else if (ln->status == LT_QT_OCCLUDED) {
        res->cls[p] = LT_RP_DISOCCLUDED;
    } else if (ln->status == LT_QT_UNKNOWN) {
        res->cls[p] = LT_RP_UNKNOWN;
    } else {
        res->cls[p] = LT_RP_OUTSIDE;
    }
}

/* Zeroed memory aligned to a cache line (a packet's lane vectors start on line boundaries, as in
 * the core's buffers); NULL on failure. */
static void *alloc64z(size_t bytes)
{
    void *p = NULL;
    if (posix_memalign(&p, 64, bytes > 0 ? bytes : 64) != 0)
        return NULL;
    memset(p, 0, bytes > 0 ? bytes : 64);
    return p;
}

/* What one run keeps between its steps: the path, the mapping, a packet and its results (the
 * path's types, from its screen ops), the tracer. */
typedef struct rp_run {
    const lt_path_info_t *p;
    const lt_rp_ops_t *ops;
    void *map, *ray, *hit;
    rp_tracer_t *tr;
} rp_run_t;

/* The tile loop on every core (lt_par.h): a task is a row of 4x4 tiles, each worker has its own
 * packet, results and counts (summed after; worker 0 has the run's own packet). The charged
 * trace runs on one thread in the sim build. */
typedef struct rp_job {
    const rp_run_t *rr;
    const fetch_ctx_t *fc;
    const lt_reproj_cam_t *dst;
    const lt_rp_opts_t *o;
    lt_rp_result_t *res;
    void *ray[LT_PAR_MAX_THREADS], *hit[LT_PAR_MAX_THREADS];
    lt_rp_stats_t *st; /* one per worker */
} rp_job_t;

static void trace_row(void *ctx, unsigned wk, uint32_t row)
{
    const rp_job_t *j = ctx;
    const rp_run_t *rr = j->rr;
    const lt_reproj_cam_t *dst = j->dst;
    lt_rp_result_t *res = j->res;
    lt_rp_stats_t *st = &j->st[wk];
    void *ray = j->ray[wk], *hit = j->hit[wk];
    uint32_t tx, ty = 4u * row;
    for (tx = 0; tx < dst->width; tx += 4) {
        lt_mask16_t k = 0xFFFF, kon = 0;
        uint64_t p0 = cycles_now();
        float per;
        int l;
        for (l = 0; l < LT_LANES; l++)
            if (tx + (uint32_t)(l & 3) < dst->width && ty + (uint32_t)(l >> 2) < dst->height)
                kon = (lt_mask16_t)(kon | (1u << l));
        k = kon;
        rr->ops->rays16(rr->map, tx, ty, ray, &k);
        if (k != 0)
            trace16(rr->tr, rr->ops, j->o->single, ray, k, j->o->max_steps, hit);
        st->packets += k != 0;
        per = (float)(cycles_now() - p0) / (float)lt__popcount32(kon);
        for (l = 0; l < LT_LANES; l++) {
            uint32_t x = tx + (uint32_t)(l & 3), y = ty + (uint32_t)(l >> 2);
            size_t p = (size_t)y * dst->width + x;
            lt_rp_lane_t ln;
            if (!LT__ON(kon, l))
                continue;
            res->cycles[p] = per;
            if (!LT__ON(k, l))
                continue; /* empty segment: outside the source view */
            rr->ops->lane(ray, hit, l, &ln);
            classify(res, st, j->fc, dst, p, &ln);
        }
    }
}

/* Every 4x4 target tile: its segments, the trace, each lane's class; cycles per stage. 0, or -1
 * when out of memory (nothing traced). */
static int trace_tiles(const rp_run_t *rr, const fetch_ctx_t *fc, const lt_reproj_cam_t *dst,
                       const lt_rp_opts_t *o, lt_rp_result_t *res)
{
    rp_job_t j;
    uint32_t rows = (dst->height + 3u) / 4u;
    unsigned w = lt_par_workers(rows, 1), i;
    memset(&j, 0, sizeof j);
    j.rr = rr;
    j.fc = fc;
    j.dst = dst;
    j.o = o;
    j.res = res;
    j.ray[0] = rr->ray;
    j.hit[0] = rr->hit;
    if ((j.st = calloc(w, sizeof *j.st)) == NULL)
        return -1;
    for (i = 1; i < w; i++)
        if ((j.ray[i] = alloc64z(rr->ops->ray_bytes)) == NULL ||
            (j.hit[i] = alloc64z(rr->ops->hit_bytes)) == NULL)
            break;
    w = i;
    (void)lt_par_run(rows, w, trace_row, &j, o->progress);
    for (i = 0; i < w; i++) {
        const lt_rp_stats_t *t = &j.st[i];
        res->st.rays += t->rays;
        res->st.nodes += t->nodes;
        res->st.aabb += t->aabb;
        res->st.planes += t->planes;
        res->st.packets += t->packets;
        if (t->nodes_max > res->st.nodes_max)
            res->st.nodes_max = t->nodes_max;
        if (t->aabb_max > res->st.aabb_max)
            res->st.aabb_max = t->aabb_max;
        if (t->planes_max > res->st.planes_max)
            res->st.planes_max = t->planes_max;
    }
    for (i = 1; i < LT_PAR_MAX_THREADS; i++) {
        free(j.ray[i]);
        free(j.hit[i]);
    }
    free(j.st);
    return 0;
}

/* The result's buffers for a w x h target, every pixel outside with no depth; 0 or -1. */
static int result_alloc(lt_rp_result_t *res, uint32_t w, uint32_t h)
{
    size_t i, np = (size_t)w * h;
    res->width = w;
    res->height = h;
    res->rgb = calloc(np * 3, sizeof(float));
    res->z = malloc(np * sizeof(float));
    res->cls = malloc(np);
    res->steps = calloc(np, sizeof(float));
    res->cycles = calloc(np, sizeof(float));
    res->sx = malloc(np * sizeof(float));
    res->sy = malloc(np * sizeof(float));
    res->layer = malloc(np * sizeof(int32_t));
    if (res->rgb == NULL || res->z == NULL || res->cls == NULL || res->steps == NULL ||
        res->cycles == NULL || res->sx == NULL || res->sy == NULL || res->layer == NULL)
        return -1;
    for (i = 0; i < np; i++) {
        res->z[i] = NAN;
        res->sx[i] = res->sy[i] = NAN;
        res->layer[i] = -1;
        res->cls[i] = LT_RP_OUTSIDE;
    }
    res->st.pixels = np;
    return 0;
}

/* The checks of lt_rp_run's inputs; the numeric path of o->enc, or NULL with a message. */
static const lt_path_info_t *run_check(const lt_rp_source_t *src, const lt_reproj_cam_t *dst,
                                       const lt_rp_opts_t *o, lt_diag_t *diag)
{
    const lt_path_info_t *p = lt_paths_of_qt_enc(o->enc);
    if (src == NULL || dst == NULL || src->z == NULL || src->layers < 1 ||
        src->layers > LT_RP_MAX_LAYERS) {
        lt_diag_fail(diag, "reproject: bad source (layers must be 1..%d)", LT_RP_MAX_LAYERS);
        return NULL;
    }
    if (src->width < 1 || src->height < 1 || src->width > LT_QT_MAX_DIM ||
        src->height > LT_QT_MAX_DIM || dst->width < 1 || dst->height < 1 ||
        dst->width > LT_QT_MAX_DIM || dst->height > LT_QT_MAX_DIM) {
        lt_diag_fail(diag, "reproject: source %ux%u or target %ux%u outside 1..%u (LT_QT_MAX_DIM) "
                     "per side", src->width, src->height, dst->width, dst->height, LT_QT_MAX_DIM);
        return NULL;
    }
    if (p == NULL || p->screen == NULL || (unsigned)o->tracer > (unsigned)LT_RP_HIZ) {
        lt_diag_fail(diag, "reproject: unknown node encoding %d or tracer %d (0..2 each)",
                     (int)o->enc, (int)o->tracer);
        return NULL;
    }
    if (o->single && (o->tracer != LT_RP_QUADTREE || p->screen->qt_trace1 == NULL)) {
        lt_diag_fail(diag, "reproject: the single-ray walk is the quadtree's on an s1.30 path (n64, "
                     "n32), not %s", o->tracer != LT_RP_QUADTREE ? "the DDA or Hi-Z tracer"
                                                                : "float32 (f32)");
        return NULL;
    }
    return p;
}

int lt_rp_run(const lt_rp_source_t *src, const lt_reproj_cam_t *dst, const lt_rp_opts_t *o,
              lt_rp_result_t *res, lt_diag_t *diag)
{
    lt_rp_opts_t od;
    static rp_tracer_t tr;
    lt_reproj_opts_t ro;
    rp_run_t rr;
    fetch_ctx_t fc;
    void *arena = NULL, *w = NULL;
    float *wf = NULL;
    uint8_t *valid = NULL;
    size_t n, np, bytes, i;
    int e, status = -1;
    lt_status_t s;
    double t0;
    lt_meter_totals_t m0, m1;

    memset(res, 0, sizeof *res);
    memset(&rr, 0, sizeof rr);
    if (o == NULL) {
        lt_rp_opts_default(&od);
        o = &od;
    }
    if ((rr.p = run_check(src, dst, o, diag)) == NULL)
        return -1;
    rr.ops = rr.p->screen;
    rr.tr = &tr;
    n = (size_t)src->width * src->height * src->layers;
    if (lt_qt_zref_exp(src->z, n, &e) != 0) {
        lt_diag_fail(diag, "reproject: the depth image has no valid depth (all NaN, inf or <= 0)");
        return -1;
    }
    res->st.zref = ldexp(1.0, e);

    /* w per layer in the path's format (and as float: the fetch compares with the same values
       the core saw), the mapping, a packet and its results */
    wf = malloc(n * sizeof *wf);
    if (rr.ops->w_bytes > 0)
        w = malloc(n * rr.ops->w_bytes);
    rr.map = alloc64z(rr.ops->map_bytes);
    rr.ray = alloc64z(rr.ops->ray_bytes);
    rr.hit = alloc64z(rr.ops->hit_bytes);
    if (wf == NULL || (rr.ops->w_bytes > 0 && w == NULL) || rr.map == NULL || rr.ray == NULL ||
        rr.hit == NULL) {
        lt_diag_fail(diag, "reproject: out of memory for %zu depth samples", n);
        goto done;
    }
    rr.ops->w_from_depth(src->z, n, e, w != NULL ? w : wf, wf);

    /* mapping */
    memset(&ro, 0, sizeof ro);
    ro.z_ref = res->st.zref;
    ro.z_near_dst = o->z_near_dst;
    s = rr.ops->setup(&src->cam, dst, &ro, rr.map);
    if (s != LT_OK) {
        lt_diag_fail(diag,
                     "reproject: camera setup failed (%s): focal lengths must be > 0 and finite, "
                     "rotations orthonormal, sizes 1..%u, z_ref / near < 2",
                     lt_status_str(s), LT_QT_MAX_DIM);
        goto done;
    }

    /* the tracer: quadtree (built), DDA (no structure) or Hi-Z (built) */
    t0 = lt_now_s();
    lt_meter_region(w != NULL ? w : (void *)wf, n * (w != NULL ? rr.ops->w_bytes : sizeof *wf),
                    0x50000000u);
    lt_meter_totals(&m0);
    if (tracer_build(&tr, o, rr.p, src->width, src->height, src->layers, w != NULL ? w : wf,
                     &arena, &bytes, diag) != 0)
        goto done;
    res->st.t_build = lt_now_s() - t0;
    res->st.qt_bytes = bytes;
    if (o->tracer == LT_RP_QUADTREE) {
        res->st.qt_nodes = (uint64_t)tr.qt.layer_nodes * tr.qt.layers;
        res->st.qt_planes = rr.ops->qt_planes(arena, res->st.qt_nodes);
    }

    /* outputs */
    np = (size_t)dst->width * dst->height;
    valid = malloc(np);
    if (result_alloc(res, dst->width, dst->height) != 0 || valid == NULL) {
        lt_diag_fail(diag, "reproject: out of memory for a %ux%u target", dst->width,
                     dst->height);
        goto done;
    }
    fc.src = src;
    fc.wl = wf;
    fc.zref = res->st.zref;
    fc.bilinear = o->bilinear;

    t0 = lt_now_s();
    if (trace_tiles(&rr, &fc, dst, o, res) != 0) {
        lt_diag_fail(diag, "reproject: out of memory for the tile loop's counts");
        goto done;
    }
    res->st.t_trace = lt_now_s() - t0;
    /* one source of truth with the cycle report: the model's phase totals over the call */
    lt_meter_totals(&m1);
    res->st.cyc_build = m1.cycles[LT_PH_BUILD] - m0.cycles[LT_PH_BUILD];
    res->st.cyc_setup = m1.cycles[LT_PH_SETUP] - m0.cycles[LT_PH_SETUP];
    res->st.cyc_trace = m1.cycles[LT_PH_TRAVERSE] - m0.cycles[LT_PH_TRAVERSE] +
                        m1.cycles[LT_PH_INTERSECT] - m0.cycles[LT_PH_INTERSECT];
    res->st.cyc_total = m1.total_cycles - m0.total_cycles;
    res->st.cyc_other = res->st.cyc_total - res->st.cyc_build - res->st.cyc_setup -
                        res->st.cyc_trace;
    res->st.lanes_on += m1.events[LT_EV_LANES_ON] - m0.events[LT_EV_LANES_ON];
    res->st.lane_ops += m1.events[LT_EV_LANE_OPS] - m0.events[LT_EV_LANE_OPS];
    for (i = 0; i < np; i++) {
        res->st.cls[res->cls[i]]++;
        valid[i] = res->cls[i] == LT_RP_HIT || res->cls[i] == LT_RP_BACKGROUND;
    }
    t0 = lt_now_s();
    if (o->inpaint)
        (void)lt_rp_inpaint(res->rgb, res->z, valid, dst->width, dst->height);
    res->st.t_inpaint = lt_now_s() - t0;
    status = 0;
done:
    free(arena);
    free(w);
    free(wf);
    free(valid);
    free(rr.map);
    free(rr.ray);
    free(rr.hit);
    if (status != 0)
        lt_rp_result_free(res);
    return status;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

int lt_rp_truth_compare(const lt_rp_result_t *res, const float *ztrue, double tol,
                        lt_rp_truth_t *t, float *relerr)
{
    size_t i, n = (size_t)res->width * res->height;
    double se = 0.0, sre = 0.0, ip_sre = 0.0;
    double *rels;
    memset(t, 0, sizeof *t);
    if (!(tol > 0.0 && tol <= 1.0))
        return -1;
    rels = malloc((n > 0 ? n : 1) * sizeof *rels);
    if (rels == NULL)
        return -1;
    t->tol = tol;
    t->pixels = n;
    for (i = 0; i < n; i++) {
        double zt = (double)ztrue[i], z = (double)res->z[i], e, rel;
        int thit = isfinite(zt) && zt > 0.0, rhit = isfinite(z) && z > 0.0;
        int known = res->cls[i] == LT_RP_HIT || res->cls[i] == LT_RP_BACKGROUND;
        t->truth_hit += (uint64_t)thit;
        if (relerr != NULL)
            relerr[i] = NAN;
        if (known) {
            t->known++;
            if (res->cls[i] == LT_RP_HIT && !thit)
                t->spurious++;
            else if (res->cls[i] == LT_RP_BACKGROUND && thit)
                t->missed++;
        } else {
            t->inpainted++;
            if (z != z)
                t->ip_unfilled++;
            else if (rhit != thit)
                t->ip_wrong++;
        }
        if (!rhit || !thit)
            continue;
        e = z - zt;
        rel = fabs(e) / zt;
        if (relerr != NULL)
            relerr[i] = (float)rel;
        if (res->cls[i] == LT_RP_HIT) {
            rels[t->both_hit] = rel;
            t->both_hit++;
            se += e * e;
            sre += rel * rel;
            if (rel > t->max_rel)
                t->max_rel = rel;
            t->within += rel <= tol;
        } else if (!known) {
            t->ip_both++;
            ip_sre += rel * rel;
            t->ip_within += rel <= tol;
        }
    }
    if (t->both_hit > 0) {
        t->rmse = sqrt(se / (double)t->both_hit);
        t->rel_rmse = sqrt(sre / (double)t->both_hit);
    }
    if (t->ip_both > 0)
        t->ip_rel_rmse = sqrt(ip_sre / (double)t->ip_both);
    if (t->both_hit > 0) {
        qsort(rels, (size_t)t->both_hit, sizeof *rels, cmp_double);
        /* nearest rank: the smallest value with at least q of the samples at or below it */
        t->rel_p50 = rels[(size_t)ceil(0.50 * (double)t->both_hit) - 1];
        t->rel_p99 = rels[(size_t)ceil(0.99 * (double)t->both_hit) - 1];
    }
    free(rels);
    return 0;
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

double lt_rp_median_depth(const float *z, size_t n)
{
    float *v = malloc((n > 0 ? n : 1) * sizeof *v);
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
