/* lt_tune_eval.c - the in-process evaluators of lanetrace tune (lt_tune.h): each configuration is
 * built and traced by the renderers' own APIs (lt_render, lt_reproject, lt_softshadow) with the
 * cycle model charging every op (lt_meter), and compared with its family's reference, which is
 * computed once per context. Host only.
 */
#define _XOPEN_SOURCE 600 /* makecontext, swapcontext */
#include "tune/lt_tune.h"
#include "io/lt_scenefile.h"

#include "cli/lt_reproject_cli.h"
#include "io/lt_mesh.h"
#include "io/lt_png.h"
#include "lt_meter.h"
#include "render/lt_paths.h"
#include "render/lt_render.h"
#include "render/lt_reproject.h"
#include "render/lt_scene.h"
#include "render/lt_softshadow.h"

#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <ucontext.h>
#include <unistd.h>

#define MAX_LAYERS 4

struct lt_tune_ctx {
    lt_tune_input_t in;
    unsigned families;
    uint32_t res;
    char q16_why[256];
    /* object and screen: the mesh as given */
    lt_mesh_t mesh;
    lt_scene_t sc;
    int have_sc;
    lt_camera_t cam;
    lt_frame_t ref;          /* object: the double-precision frame */
    /* screen */
    float *zsrc;             /* MAX_LAYERS x res x res source z-depths */
    lt_reproj_cam_t scam, dcam;
    float *ztrue;            /* the target view ray traced */
    /* shadows: the mesh with its ground quad, view and light */
    lt_mesh_t smesh;
    lt_scene_t ssc;
    int have_ssc;
    lt_camera_t scam_ss;
    lt_ss_light_t light;
};

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void meas_clear(lt_tune_meas_t *m, uint32_t res)
{
    int i;
    memset(m, 0, sizeof *m);
    m->res = res;
    for (i = 0; i < LT_M__COUNT; i++)
        m->m[i] = NAN;
    m->maxerr = m->rel50 = m->within = m->off = NAN;
}

static void meas_phases(lt_tune_meas_t *m)
{
    lt_meter_totals_t t;
    int i;
    lt_meter_totals(&t);
    for (i = 0; i < LT_PH__COUNT; i++)
        m->phase[i] = (double)t.cycles[i];
    m->m[LT_M_CYCLES] = (double)t.total_cycles;
}

/* ---- images -------------------------------------------------------------------------------- */

/* Grey depth image (near bright), misses dark blue; values <= 0 or non-finite are misses. */
static int write_depth_png(const char *path, const float *z, uint32_t w, uint32_t h)
{
    size_t i, n = (size_t)w * h;
    float lo = INFINITY, hi = -INFINITY;
    uint8_t *pix = malloc(n * 3);
    lt_diag_t d;
    int rc;
    if (pix == NULL)
        return -1;
    for (i = 0; i < n; i++)
        if (isfinite(z[i]) && z[i] > 0.0f) {
            lo = z[i] < lo ? z[i] : lo;
            hi = z[i] > hi ? z[i] : hi;
        }
    for (i = 0; i < n; i++) {
        if (isfinite(z[i]) && z[i] > 0.0f) {
            double v = hi > lo ? (double)(hi - z[i]) / (double)(hi - lo) : 1.0;
            uint8_t g = (uint8_t)(40.0 + 215.0 * v + 0.5);
            pix[3 * i] = pix[3 * i + 1] = pix[3 * i + 2] = g;
        } else {
            pix[3 * i] = 20;
            pix[3 * i + 1] = 20;
            pix[3 * i + 2] = 64;
        }
    }
    rc = lt_png_write(path, pix, (int32_t)w, (int32_t)h, 3, 0, &d);
    free(pix);
    return rc;
}

/* An 8-bit RGB PNG into *pix (malloc'ed). Returns 0 or -1. */
static int read_png_rgb(const char *path, uint8_t **pix, uint32_t *w, uint32_t *h)
{
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&im, path))
        return -1;
    im.format = PNG_FORMAT_RGB;
    *pix = malloc(PNG_IMAGE_SIZE(im));
    if (*pix == NULL || !png_image_finish_read(&im, NULL, *pix, 0, NULL)) {
        free(*pix);
        *pix = NULL;
        png_image_free(&im);
        return -1;
    }
    *w = im.width;
    *h = im.height;
    return 0;
}

/* % of pixels of a whose shaded 8-bit value differs from b's by more than 1 in any channel. */
static double png_off_pct(const char *a, const char *b)
{
    uint8_t *pa = NULL, *pb = NULL;
    uint32_t wa, ha, wb, hb;
    size_t i, n, off = 0;
    double r = NAN;
    if (read_png_rgb(a, &pa, &wa, &ha) == 0 && read_png_rgb(b, &pb, &wb, &hb) == 0 && wa == wb &&
        ha == hb) {
        n = (size_t)wa * ha;
        for (i = 0; i < n; i++) {
            int c, bad = 0;
            for (c = 0; c < 3; c++)
                bad |= abs((int)pa[3 * i + (size_t)c] - (int)pb[3 * i + (size_t)c]) > 1;
            off += (size_t)bad;
        }
        r = n ? 100.0 * (double)off / (double)n : 0.0;
    }
    free(pa);
    free(pb);
    return r;
}

/* ---- contexts ------------------------------------------------------------------------------ */

/* Object and screen: the mesh, its camera (the scene file's or the benchmark view) and the
 * references of the families asked for. */
static int ctx_mesh(lt_tune_ctx_t *c, lt_diag_t *diag)
{
    if (lt_mesh_load(c->in.mesh, &c->mesh, diag) != 0)
        return -1;
    if (lt_scene_prepare(&c->mesh, &c->sc, diag) != 0)
        return lt_diag_prefix(diag, "%s: ", c->in.mesh);
    c->have_sc = 1;
    if (lt_scene_check_q16(&c->sc, c->in.mesh, diag) != 0)
        snprintf(c->q16_why, sizeof c->q16_why, "%s", diag->msg);
    if (c->in.has_camera) {
        if (lt_camera_look(&c->sc, c->in.eye, c->in.target, c->in.up, c->in.fov, c->res, c->res,
                           &c->cam, diag) != 0)
            return lt_diag_prefix(diag, "%s: ", c->in.scene);
    } else {
        lt_camera_default(&c->sc, c->res, c->res, &c->cam);
    }
    if (c->families & LT_TUNE_OBJECT) {
        if (lt_frame_alloc(&c->ref, c->res, c->res, diag) != 0)
            return -1;
        lt_render_reference(&c->sc, &c->cam, &c->ref, NULL);
    }
    return 0;
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

/* Screen: MAX_LAYERS depth peels of the mesh from its camera (float32 BVH, as lanetrace render),
 * the target camera moved by 8% of the median depth to the right and turned 3 degrees (the
 * README's make run), and the target view ray traced. */
static int ctx_screen(lt_tune_ctx_t *c, lt_diag_t *diag)
{
    size_t n = (size_t)c->res * c->res, i, m = 0;
    lt_frame_t fr[2];
    lt_accel_t *acc;
    float *v;
    double move[3] = {0, 0, 0}, rot[3] = {-3.0, 0, 0};
    int l;
    c->zsrc = malloc(MAX_LAYERS * n * sizeof *c->zsrc);
    c->ztrue = malloc(n * sizeof *c->ztrue);
    v = malloc(n * sizeof *v);
    if (c->zsrc == NULL || c->ztrue == NULL || v == NULL) {
        free(v);
        return lt_diag_fail(diag, "out of memory for %u x %u depth layers", c->res, c->res);
    }
    if (lt_frame_alloc(&fr[0], c->res, c->res, diag) != 0 ||
        lt_frame_alloc(&fr[1], c->res, c->res, diag) != 0) {
        free(v);
        return -1;
    }
    acc = lt_accel_build(&c->sc, "bvh", lt_paths_find("f32", LT_PATHS_OBJECT), diag);
    if (acc == NULL) {
        free(v);
        return -1;
    }
    lt_render_primary(&c->sc, acc, &c->cam, &fr[0], NULL);
    for (l = 0; l < MAX_LAYERS; l++) {
        lt_frame_t *cur = &fr[l & 1];
        if (l > 0 && lt_render_peel(&c->sc, acc, &c->cam, &fr[(l - 1) & 1], cur, diag) != 0)
            break;
        for (i = 0; i < n; i++) {
            double d[3];
            lt_camera_dir(&c->cam, (uint32_t)(i % c->res), (uint32_t)(i / c->res), d);
            c->zsrc[(size_t)l * n + i] =
                cur->id[i] >= 0 ? (float)(cur->t[i] * (d[0] * c->cam.fwd[0] + d[1] * c->cam.fwd[1] +
                                                       d[2] * c->cam.fwd[2]))
                                : (float)INFINITY;
        }
    }
    lt_accel_free(acc);
    lt_frame_free(&fr[0]);
    lt_frame_free(&fr[1]);
    if (l < MAX_LAYERS) {
        free(v);
        return -1;
    }
    for (i = 0; i < n; i++)
        if (isfinite(c->zsrc[i]))
            v[m++] = c->zsrc[i];
    if (m == 0) {
        free(v);
        return lt_diag_fail(diag, "%s: the mesh covers no pixel of the view", c->in.mesh);
    }
    qsort(v, m, sizeof *v, cmp_float);
    move[0] = 0.08 * (double)v[m / 2];
    free(v);
    lt_rp_cam_from_camera(&c->cam, c->res, c->res, &c->scam);
    lt_rp_cam_move(&c->scam, move, rot, &c->dcam);
    return lt_rp_render_truth(&c->sc, &c->dcam, c->ztrue, diag);
}

/* Shadows: the mesh with the ground quad, camera and light of lanetrace shadows for it. */
static int ctx_shadows(lt_tune_ctx_t *c, lt_diag_t *diag)
{
    lt_ss_view_t view, *pre = NULL;
    double lc[4], up[3] = {0, 1, 0};
    int ground;
    if (lt_ss_view_for(c->in.mesh, &view))
        pre = &view;
    if (lt_mesh_load(c->in.mesh, &c->smesh, diag) != 0)
        return -1;
    ground = pre != NULL ? pre->ground : 1;
    if (pre != NULL) {
        memcpy(lc, pre->light, 3 * sizeof lc[0]);
        lc[3] = pre->size;
    } else {
        lc[0] = 0.5 * (c->smesh.lo[0] + c->smesh.hi[0]);
        lc[1] = c->smesh.hi[1] + (c->smesh.hi[1] - c->smesh.lo[1]);
        lc[2] = 0.5 * (c->smesh.lo[2] + c->smesh.hi[2]);
        lc[3] = 0.2 * (c->smesh.hi[0] - c->smesh.lo[0]);
    }
    if (ground && lt_ss_add_ground(&c->smesh, 0.6, diag) != 0)
        return -1;
    if (lt_scene_prepare(&c->smesh, &c->ssc, diag) != 0)
        return lt_diag_prefix(diag, "%s: ", c->in.mesh);
    c->have_ssc = 1;
    if (pre != NULL && pre->has_camera) {
        if (lt_camera_look(&c->ssc, pre->eye, pre->target, up, pre->fov, c->res, c->res,
                           &c->scam_ss, diag) != 0)
            return -1;
    } else {
        lt_camera_default(&c->ssc, c->res, c->res, &c->scam_ss);
    }
    return lt_ss_light_square(&c->ssc, lc, lc[3], &c->light, diag);
}

lt_tune_ctx_t *lt_tune_ctx_new(const lt_tune_input_t *in, unsigned families, uint32_t res,
                               lt_diag_t *diag)
{
    lt_tune_ctx_t *c = calloc(1, sizeof *c);
    if (c == NULL) {
        lt_diag_fail(diag, "out of memory");
        return NULL;
    }
    c->in = *in;
    c->families = families;
    c->res = res;
    if (in->mesh[0] == '\0') {
        lt_diag_fail(diag, "%s: a depth image has no mesh to ray trace the target view from, "
                           "so the screen family has no reference; give the mesh (or a scene "
                           "file naming it)", in->depth);
        lt_tune_ctx_free(c);
        return NULL;
    }
    if (((families & (LT_TUNE_OBJECT | LT_TUNE_SCREEN)) && ctx_mesh(c, diag) != 0) ||
        ((families & LT_TUNE_SCREEN) && ctx_screen(c, diag) != 0) ||
        ((families & LT_TUNE_SHADOWS) && ctx_shadows(c, diag) != 0)) {
        lt_tune_ctx_free(c);
        return NULL;
    }
    return c;
}

void lt_tune_ctx_free(lt_tune_ctx_t *c)
{
    if (c == NULL)
        return;
    lt_frame_free(&c->ref);
    free(c->zsrc);
    free(c->ztrue);
    if (c->have_sc)
        lt_scene_free(&c->sc);
    if (c->have_ssc)
        lt_scene_free(&c->ssc);
    lt_mesh_free(&c->mesh);
    lt_mesh_free(&c->smesh);
    free(c);
}

int lt_tune_ctx_q16_refused(const lt_tune_ctx_t *c, char *why, size_t n)
{
    snprintf(why, n, "%s", c->q16_why);
    return c->q16_why[0] != '\0';
}

/* ---- evaluation ---------------------------------------------------------------------------- */

/* Measurements run on a stack of their own (eval_stack, switched to with swapcontext), registered
 * with the cycle model at a fixed simulated address: the kernels' packets, hits and traversal
 * stacks live there, and memory the model has no region for is charged at its real address, so on
 * the process stack the cycles would depend on the caller's depth and on the size of the
 * environment (frames realigned to 64 bytes move with it): a worker, the verification and a
 * --job under GNU parallel would disagree by a few cycles. */
#define EVAL_STACK (8u << 20)
static union {
    double align;
    unsigned char b[EVAL_STACK + 64];
} eval_stack_mem;
static unsigned char *eval_stack; /* 64-byte aligned start inside eval_stack_mem */

/* The machine and the measurement stack as a region. */
static int machine_init(const lt_tune_knobs_t *k, lt_tune_meas_t *m)
{
    lt_diag_t d;
    if (lt_meter_init(lt_meter_machine_name(k->machine), NULL, NULL, &d) != 0) {
        snprintf(m->msg, sizeof m->msg, "%s", d.msg);
        return -1;
    }
    lt_meter_region(eval_stack, EVAL_STACK, 0x70000000u);
    return 0;
}

static void eval_object(lt_tune_ctx_t *c, lt_tune_point_t *p, lt_tune_meas_t *m, const char *img)
{
    const lt_tune_knobs_t *k = &p->k;
    lt_accel_params_t prm;
    lt_accel_t *acc;
    lt_frame_t fr;
    lt_accuracy_t ac;
    lt_diag_t d;
    if (lt_frame_alloc(&fr, c->res, c->res, &d) != 0 || machine_init(k, m) != 0) {
        snprintf(m->msg, sizeof m->msg, "%s", d.msg);
        return;
    }
    prm.leaf = (uint32_t)k->leaf;
    acc = lt_accel_build_ex(&c->sc, lt_render_structures[k->structure],
                            &lt_paths[k->path], &prm, &d);
    if (acc == NULL) {
        snprintf(m->msg, sizeof m->msg, "%s", d.msg);
        lt_frame_free(&fr);
        return;
    }
    if (lt_accel_set_isect_name(acc, lt_sf_isects[k->isect], NULL, &d) != 0) {
        snprintf(m->msg, sizeof m->msg, "%s", d.msg);
        lt_accel_free(acc);
        lt_frame_free(&fr);
        return;
    }
    lt_render_primary(&c->sc, acc, &c->cam, &fr, NULL);
    meas_phases(m);
    m->m[LT_M_BYTES] = (double)lt_accel_bytes(acc);
    lt_accel_free(acc);
    lt_frame_compare(&fr, &c->ref, 1e-4 * c->sc.radius, &ac);
    m->m[LT_M_WRONG] = 100.0 * (double)(ac.pixels - ac.same_id) / (double)ac.pixels;
    m->m[LT_M_RMSE] = ac.rmse / c->sc.scale; /* scaled units -> scene (file) units */
    m->maxerr = ac.max_err / c->sc.scale;
    if (img != NULL) {
        size_t i, n = (size_t)c->res * c->res;
        float *z = malloc(n * sizeof *z);
        if (z != NULL) {
            for (i = 0; i < n; i++)
                z[i] = fr.id[i] >= 0 ? (float)fr.t[i] : (float)INFINITY;
            (void)write_depth_png(img, z, c->res, c->res);
        }
        free(z);
    }
    lt_frame_free(&fr);
    m->ok = 1;
}

static void eval_screen(lt_tune_ctx_t *c, lt_tune_point_t *p, lt_tune_meas_t *m, const char *img)
{
    const lt_tune_knobs_t *k = &p->k;
    lt_rp_source_t src;
    lt_rp_opts_t o;
    lt_rp_result_t res;
    lt_rp_truth_t tr;
    lt_diag_t d;
    memset(&src, 0, sizeof src);
    src.width = src.height = c->res;
    src.layers = (uint32_t)k->layers;
    src.z = c->zsrc;
    src.cam = c->scam;
    lt_rp_opts_default(&o);
    o.enc = (lt_qt_enc_t)lt_paths[k->path].qt_enc;
    o.tracer = (lt_rp_tracer_t)k->structure;
    o.params.gamma_norm = (lt_q30_t)floor(lt_tune_gammas[k->gamma].gamma_norm * 1073741824.0 + 0.5);
    o.params.gamma_dist = (lt_q30_t)floor(lt_tune_gammas[k->gamma].gamma_dist * 1073741824.0 + 0.5);
    /* the walk the machine's firmware runs (single rays on the MCU models) */
    o.single = lt_rp_auto_single(lt_meter_machine_name(k->machine), o.enc, o.tracer, NULL, 0);
    if (machine_init(k, m) != 0)
        return;
    memset(&res, 0, sizeof res);
    if (lt_rp_run(&src, &c->dcam, &o, &res, &d) != 0) {
        snprintf(m->msg, sizeof m->msg, "%s", d.msg);
        return;
    }
    meas_phases(m);
    m->m[LT_M_BYTES] = (double)res.st.qt_bytes;
    if (lt_rp_truth_compare(&res, c->ztrue, 0.01, &tr, NULL) != 0) {
        snprintf(m->msg, sizeof m->msg, "out of memory comparing with the ground truth");
        lt_rp_result_free(&res);
        return;
    }
    m->m[LT_M_WRONG] = tr.known ? 100.0 * (double)(tr.spurious + tr.missed) / (double)tr.known : 0.0;
    m->m[LT_M_RMSE] = tr.rmse / c->sc.scale;
    m->m[LT_M_REL99] = 100.0 * tr.rel_p99;
    m->rel50 = 100.0 * tr.rel_p50;
    m->within = tr.both_hit ? 100.0 * (double)tr.within / (double)tr.both_hit : 100.0;
    if (img != NULL)
        (void)write_depth_png(img, res.z, res.width, res.height);
    lt_rp_result_free(&res);
    m->ok = 1;
}

/* Shadows: one renderer per (machine, path, leaf, culling) gives 8 points: both primaries, both
 * shadow methods, filter on and off. Stage cycles and phases are read between stages; the 256-spp
 * reference is not charged to any point. Errors use the P-Packet primaries (P-Frusta traces the
 * same rays; docs/frusta.md audits the rare differences). */
typedef struct ss_stage {
    double cyc, ph[LT_PH__COUNT];
} ss_stage_t;

static void stage_mark(ss_stage_t *s, lt_meter_totals_t *last)
{
    lt_meter_totals_t t;
    int i;
    lt_meter_totals(&t);
    s->cyc = (double)(t.total_cycles - last->total_cycles);
    for (i = 0; i < LT_PH__COUNT; i++)
        s->ph[i] = (double)(t.cycles[i] - last->cycles[i]);
    *last = t;
}

enum { ST_BUILD, ST_PF, ST_PP, ST_SF, ST_SP, ST_SHADE, ST_FILTER, ST__N };

/* PSNR and off-% of one shadow method, filtered and not, into q[2] (0 raw, 1 filtered). */
static void ss_quality(lt_softshadow_t *ss, int which, const char *dir, double psnr[2],
                       double off[2], char img[2][1100])
{
    lt_ss_quality_t q;
    lt_diag_t d;
    char ref[1100];
    int f;
    lt_ss_shade(ss, which);
    lt_ss_filter(ss);
    lt_ss_quality(ss, 1.0 / 255.0, &q);
    psnr[0] = q.psnr_raw;
    psnr[1] = q.psnr_filtered;
    snprintf(ref, sizeof ref, "%s/ref.png", dir);
    for (f = 0; f < 2; f++) {
        snprintf(img[f], sizeof img[f], "%s/m%d-f%d.png", dir, which, f);
        off[f] = NAN;
        if (lt_ss_write_png(ss, img[f], f ? 0 : 1, &d) == 0)
            off[f] = png_off_pct(img[f], ref);
    }
}

static int copy_file(const char *from, const char *to)
{
    FILE *a = fopen(from, "rb"), *b = a != NULL ? fopen(to, "wb") : NULL;
    char buf[8192];
    size_t n;
    int rc = 0;
    if (a == NULL || b == NULL) {
        if (a != NULL)
            fclose(a);
        return -1;
    }
    while ((n = fread(buf, 1, sizeof buf, a)) > 0)
        if (fwrite(buf, 1, n, b) != n)
            rc = -1;
    fclose(a);
    return fclose(b) != 0 ? -1 : rc;
}

static void rm_dir_pngs(const char *dir)
{
    char p[1100];
    int w, f;
    snprintf(p, sizeof p, "%s/ref.png", dir);
    unlink(p);
    for (w = 0; w < 2; w++)
        for (f = 0; f < 2; f++) {
            snprintf(p, sizeof p, "%s/m%d-f%d.png", dir, w, f);
            unlink(p);
        }
    rmdir(dir);
}

/* The 8 points of run `run` from the stage figures (st), quality (psnr/off per method and filter)
 * and images. */
static void ss_points(lt_tune_point_t *pts, size_t np, int run, int full, const ss_stage_t *st,
                      double psnr[2][2], double off[2][2], char img[2][2][1100], double bytes,
                      double secs, const char *img_prefix)
{
    size_t i;
    for (i = 0; i < np; i++) {
        lt_tune_point_t *p = &pts[i];
        lt_tune_meas_t *m = full ? &p->full : &p->probe;
        int w = p->k.shadow == 0 ? LT_SS_FRUSTA : LT_SS_PACKET, f = p->k.filter, s, ph;
        int use[ST__N] = {1, 0, 0, 0, 0, 1, 0};
        if (p->run != run)
            continue;
        use[p->k.prim ? ST_PF : ST_PP] = 1;
        use[w == LT_SS_FRUSTA ? ST_SF : ST_SP] = 1;
        use[ST_FILTER] = f;
        m->m[LT_M_CYCLES] = 0.0;
        for (s = 0; s < ST__N; s++) {
            if (!use[s])
                continue;
            m->m[LT_M_CYCLES] += st[s].cyc;
            for (ph = 0; ph < LT_PH__COUNT; ph++)
                m->phase[ph] += st[s].ph[ph];
        }
        m->m[LT_M_PSNR] = psnr[w][f];
        m->off = off[w][f];
        m->m[LT_M_BYTES] = bytes;
        m->secs = secs / 8.0;
        m->ok = 1;
        if (img_prefix != NULL) {
            char to[1100];
            snprintf(to, sizeof to, "%s-%zu.png", img_prefix, i);
            (void)copy_file(img[w][f], to);
        }
    }
}

static void eval_shadows(lt_tune_ctx_t *c, lt_tune_point_t *pts, size_t np, int run, int full,
                         const lt_tune_point_t *p0, const char *img_prefix)
{
    const lt_tune_knobs_t *k = &p0->k;
    lt_tune_meas_t *m0 = full ? (lt_tune_meas_t *)&pts[p0 - pts].full : (lt_tune_meas_t *)&pts[p0 - pts].probe;
    lt_ss_opts_t o;
    lt_softshadow_t *ss;
    lt_meter_totals_t last;
    ss_stage_t st[ST__N];
    double psnr[2][2], off[2][2], t0 = now_s();
    char dir[64], img[2][2][1100];
    lt_diag_t d;
    memset(st, 0, sizeof st);
    if (machine_init(k, m0) != 0)
        return;
    lt_ss_opts_default(&c->ssc, &o);
    o.path = &lt_paths[k->path];
    if (k->leaf > 0)
        o.leaf = (uint32_t)k->leaf;
    o.flags = lt_tune_cull_flags[k->cull];
    if (k->spp > 0)
        o.spp = (uint32_t)k->spp;
    snprintf(dir, sizeof dir, "/tmp/lt-tune-XXXXXX");
    if (mkdtemp(dir) == NULL) {
        snprintf(m0->msg, sizeof m0->msg, "cannot create a temporary folder under /tmp");
        return;
    }
    lt_meter_totals(&last);
    ss = lt_ss_create(&c->ssc, &c->scam_ss, &c->light, &o, &d);
    if (ss == NULL) {
        snprintf(m0->msg, sizeof m0->msg, "%s", d.msg);
        rmdir(dir);
        return;
    }
    stage_mark(&st[ST_BUILD], &last);
    lt_ss_primary_frusta(ss);
    stage_mark(&st[ST_PF], &last);
    lt_ss_primary(ss);
    stage_mark(&st[ST_PP], &last);
    lt_ss_reference(ss, NULL);
    {
        char ref[1100];
        snprintf(ref, sizeof ref, "%s/ref.png", dir);
        (void)lt_ss_write_png(ss, ref, 2, &d);
    }
    lt_meter_totals(&last); /* the reference is not charged */
    lt_ss_shadows_frusta(ss);
    stage_mark(&st[ST_SF], &last);
    lt_ss_shade(ss, LT_SS_FRUSTA);
    stage_mark(&st[ST_SHADE], &last);
    lt_ss_filter(ss);
    stage_mark(&st[ST_FILTER], &last);
    ss_quality(ss, LT_SS_FRUSTA, dir, psnr[LT_SS_FRUSTA], off[LT_SS_FRUSTA], img[LT_SS_FRUSTA]);
    lt_meter_totals(&last);
    lt_ss_shadows_packet(ss);
    stage_mark(&st[ST_SP], &last);
    ss_quality(ss, LT_SS_PACKET, dir, psnr[LT_SS_PACKET], off[LT_SS_PACKET], img[LT_SS_PACKET]);
    lt_ss_free(ss);
    ss_points(pts, np, run, full, st, psnr, off, img, NAN, now_s() - t0, img_prefix);
    rm_dir_pngs(dir);
}

static void eval_run(lt_tune_ctx_t *c, lt_tune_point_t *pts, size_t np, int run, int full,
                     const char *img_prefix)
{
    lt_tune_point_t *first = NULL;
    size_t i;
    for (i = 0; i < np; i++)
        if (pts[i].run == run) {
            meas_clear(full ? &pts[i].full : &pts[i].probe, c->res);
            if (first == NULL)
                first = &pts[i];
        }
    if (first == NULL)
        return;
    if (first->k.family == 2) {
        lt_tune_meas_t *m0 = full ? &first->full : &first->probe;
        eval_shadows(c, pts, np, run, full, first, img_prefix);
        for (i = 0; i < np; i++)
            if (pts[i].run == run && !m0->ok)
                snprintf((full ? &pts[i].full : &pts[i].probe)->msg, sizeof m0->msg, "%s", m0->msg);
    } else {
        lt_tune_meas_t *m = full ? &first->full : &first->probe;
        char img[1100];
        double t0 = now_s();
        if (img_prefix != NULL)
            snprintf(img, sizeof img, "%s-%zu.png", img_prefix, (size_t)(first - pts));
        if (first->k.family == 0)
            eval_object(c, first, m, img_prefix != NULL ? img : NULL);
        else
            eval_screen(c, first, m, img_prefix != NULL ? img : NULL);
        m->secs = now_s() - t0;
    }
}

static struct {
    lt_tune_ctx_t *c;
    lt_tune_point_t *pts;
    size_t np;
    int run, full;
    const char *img_prefix;
} eval_args;
static ucontext_t uc_caller, uc_eval;

static void eval_trampoline(void)
{
    eval_run(eval_args.c, eval_args.pts, eval_args.np, eval_args.run, eval_args.full,
             eval_args.img_prefix);
}

void lt_tune_eval_run(lt_tune_ctx_t *c, lt_tune_point_t *pts, size_t np, int run, int full,
                      const char *img_prefix)
{
    eval_stack = eval_stack_mem.b + ((64u - (uintptr_t)eval_stack_mem.b % 64u) % 64u);
    eval_args.c = c;
    eval_args.pts = pts;
    eval_args.np = np;
    eval_args.run = run;
    eval_args.full = full;
    eval_args.img_prefix = img_prefix;
    if (getcontext(&uc_eval) != 0) {
        eval_trampoline(); /* no context switching: on this stack */
        return;
    }
    uc_eval.uc_stack.ss_sp = eval_stack;
    uc_eval.uc_stack.ss_size = EVAL_STACK;
    uc_eval.uc_link = &uc_caller;
    makecontext(&uc_eval, eval_trampoline, 0);
    if (swapcontext(&uc_caller, &uc_eval) != 0)
        eval_trampoline();
}
