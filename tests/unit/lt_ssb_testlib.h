/* lt_ssb_testlib.h - code shared by the screen-space tests and benchmark: tests/unit/test_qt.c
 * (the quadtree lt_qt.h), tests/unit/test_ssbase.c and tests/bench/ssbench.c (the baselines
 * lt_ssdda.h / lt_hiz.h against the quadtree): analytic inverse-depth scenes, scenes from depth
 * buffers, segment rays (coherent and random sets, rays over a depth buffer), reflection rays and
 * novel-view rays from pinhole cameras, conversion of double segments to the s1.30 and float32
 * packets with the exact values each path sees and of hit packets back to doubles, and two
 * double-precision references of the baselines' own surface model (pixel shells of relative
 * thickness): a supercover pixel march (what the Hi-Z tracer must reproduce) and McGuire & Mara's
 * major-axis march (the DDA's), built on host/render/lt_qt_ref.h's clip and grid crossings. Static
 * functions, included once by each program. Host only (C99 + libm, malloc).
 */
#ifndef LT_SSB_TESTLIB_H
#define LT_SSB_TESTLIB_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "lt/lt_hiz.h"
#include "lt/lt_qt.h"
#include "lt/lt_ssdda.h"
#include "io/lt_fx_float.h"
#include "render/lt_qt_ref.h"
#include "lt_test_util.h"

#define SS_Q30 1073741824.0

/* ---- scenes: analytic w(x, y) per layer, sampled at pixel centres ---------------------------- */

typedef struct ss_scene ss_scene_t;
typedef double (*ss_wfn_t)(const ss_scene_t *s, int layer, double x, double y);

struct ss_scene {
    const char *name;
    uint32_t W, H, layers;
    ss_wfn_t fn;       /* NULL for a buffer loaded from a file */
    double p[24];      /* scene parameters */
    double focal;      /* pinhole focal length in pixels (centre W/2, H/2) for camera rays */
    int zexp;          /* w = 2^zexp / z */
    double *w;         /* layers x H x W true samples (w units, 0 = hole) */
    lt_q30_t *wq;      /* s1.30 input */
    float *wf;         /* float input */
    double *wqd, *wfd; /* exact doubles of wq and wf (what each path sees; holes 0) */
};

/* s cleared, then its name, size, layers and w function (parameters and buffers left to the
 * caller: p[], then ss_scene_sample). */
static LT_UNUSED void ss_scene_set(ss_scene_t *s, const char *name, uint32_t W, uint32_t H,
                                   uint32_t layers, ss_wfn_t fn)
{
    memset(s, 0, sizeof *s);
    s->name = name;
    s->W = W;
    s->H = H;
    s->layers = layers;
    s->fn = fn;
}

static LT_UNUSED double ss_w_plane(const ss_scene_t *s, int layer, double x, double y)
{
    (void)layer;
    return s->p[0] + s->p[1] * x + s->p[2] * y;
}

/* pinhole camera: focal p[0] px, centre (W/2, H/2); background plane w = p1 + p2 x + p3 y (a
 * world plane is linear in w); p[4] spheres (x, y, z, r) from p[5] */
static double ss_sphere_w(const ss_scene_t *s, const double *sp, double x, double y)
{
    double f = s->p[0], dx = (x - 0.5 * s->W) / f, dy = (y - 0.5 * s->H) / f, dz = 1.0;
    double a = dx * dx + dy * dy + dz * dz, b = -2.0 * (dx * sp[0] + dy * sp[1] + dz * sp[2]);
    double c = sp[0] * sp[0] + sp[1] * sp[1] + sp[2] * sp[2] - sp[3] * sp[3];
    double disc = b * b - 4.0 * a * c;
    if (disc < 0.0)
        return -1.0;
    return 1.0 / ((-b - sqrt(disc)) / (2.0 * a));
}

static LT_UNUSED double ss_w_spheres(const ss_scene_t *s, int layer, double x, double y)
{
    double best = s->p[1] + s->p[2] * x + s->p[3] * y, wz;
    int i, n = (int)s->p[4];
    if (layer != 0)
        return 0.0;
    for (i = 0; i < n; i++) {
        wz = ss_sphere_w(s, &s->p[5 + 4 * i], x, y);
        if (wz > best)
            best = wz;
    }
    return best;
}

/* steps: a tilted floor with raised fronto-parallel blocks of three heights */
static LT_UNUSED double ss_w_steps(const ss_scene_t *s, int layer, double x, double y)
{
    double base = 0.25 + 0.0004 * x + 0.0008 * y;
    int bx = (int)floor(x / 16.0), by = (int)floor(y / 12.0);
    (void)s;
    (void)layer;
    switch ((bx * 7 + by * 3) % 5) {
    case 0:
        return 0.55;
    case 1:
        return 0.7;
    case 2:
        return base + 0.1;
    default:
        return base;
    }
}

/* checkerboard of two depths; layer 1 (if any) all holes */
static LT_UNUSED double ss_w_checker(const ss_scene_t *s, int layer, double x, double y)
{
    (void)s;
    if (layer != 0)
        return 0.0;
    return (((int)floor(x) + (int)floor(y)) & 1) ? 0.5 : 0.25;
}

/* two layers: a card (w 0.8) in front of a tilted background; layer 1 holds the background behind
 * the card, holes elsewhere. Single-layer scenes (layers = 1) see only layer 0. */
static LT_UNUSED double ss_w_card(const ss_scene_t *s, int layer, double x, double y)
{
    int in = x >= s->p[0] && x < s->p[1] && y >= s->p[2] && y < s->p[3];
    double bg = 0.3 + 0.0005 * x + 0.0002 * y;
    if (layer == 0)
        return in ? 0.8 : bg;
    return in ? bg : 0.0;
}

/* smooth field for small images */
static LT_UNUSED double ss_w_wave(const ss_scene_t *s, int layer, double x, double y)
{
    (void)layer;
    return 0.5 + s->p[0] * sin(0.3 * x + s->p[1]) + s->p[0] * cos(0.23 * y + s->p[2]);
}

/* Allocate the buffers of s (layers x H x W). Returns 0 or -1. */
static int ss_scene_alloc(ss_scene_t *s)
{
    size_t n = (size_t)s->W * s->H * s->layers;
    s->w = (double *)malloc(n * sizeof *s->w);
    s->wq = (lt_q30_t *)malloc(n * sizeof *s->wq);
    s->wf = (float *)malloc(n * sizeof *s->wf);
    s->wqd = (double *)malloc(n * sizeof *s->wqd);
    s->wfd = (double *)malloc(n * sizeof *s->wfd);
    return (s->w && s->wq && s->wf && s->wqd && s->wfd) ? 0 : -1;
}

/* Sample s->fn at pixel centres into all buffers. Returns 0 or -1. */
static LT_UNUSED int ss_scene_sample(ss_scene_t *s)
{
    size_t n = (size_t)s->W * s->H * s->layers, i;
    uint32_t k, x, y;
    if (ss_scene_alloc(s) != 0)
        return -1;
    for (k = 0; k < s->layers; k++)
        for (y = 0; y < s->H; y++)
            for (x = 0; x < s->W; x++)
                s->w[((size_t)k * s->H + y) * s->W + x] = s->fn(s, (int)k, x + 0.5, y + 0.5);
    for (i = 0; i < n; i++) {
        double v = s->w[i] > 0.0 ? s->w[i] : 0.0;
        volatile float f = (float)v; /* through a volatile: see f32_of in test_qt.c */
        s->w[i] = v;
        s->wq[i] = lt_q30_from_double_sat(v);
        s->wf[i] = f;
        s->wqd[i] = s->wq[i] / SS_Q30;
        s->wfd[i] = (double)s->wf[i];
    }
    return 0;
}

/* Fill s from depths z (H x W, one layer) through the host conversion (NaN, inf, <= 0: holes;
 * z_ref = 2^s->zexp). holes, if not NULL, receives the hole counts of the s1.30 and the float
 * conversion. Returns 0, or -1 (no valid depth, or no memory). */
static LT_UNUSED int ss_scene_from_depth(ss_scene_t *s, const float *z, size_t holes[2])
{
    size_t n = (size_t)s->W * s->H, i, hq, hf;
    s->layers = 1;
    if (lt_qt_zref_exp(z, n, &s->zexp) != 0 || ss_scene_alloc(s) != 0)
        return -1;
    hq = lt_qt_w_from_depth_q30(z, n, s->zexp, s->wq);
    hf = lt_qt_w_from_depth_f32(z, n, s->zexp, s->wf);
    if (holes != NULL) {
        holes[0] = hq;
        holes[1] = hf;
    }
    for (i = 0; i < n; i++) {
        s->wqd[i] = s->wq[i] / SS_Q30;
        s->wfd[i] = (double)s->wf[i];
        s->w[i] = s->wqd[i];
    }
    return 0;
}

static LT_UNUSED void ss_scene_free(ss_scene_t *s)
{
    free(s->w);
    free(s->wq);
    free(s->wf);
    free(s->wqd);
    free(s->wfd);
    s->w = s->wqd = s->wfd = NULL;
    s->wq = NULL;
    s->wf = NULL;
}

/* The steps and spheres scenes (test_qt.c's test_steps / test_spheres). */
static LT_UNUSED void ss_scene_steps(ss_scene_t *s)
{
    memset(s, 0, sizeof *s);
    s->name = "steps";
    s->W = 160;
    s->H = 96;
    s->layers = 1;
    s->fn = ss_w_steps;
    s->focal = 140.0;
}

static LT_UNUSED void ss_scene_spheres(ss_scene_t *s)
{
    memset(s, 0, sizeof *s);
    s->name = "spheres";
    s->W = 160;
    s->H = 120;
    s->layers = 1;
    s->fn = ss_w_spheres;
    s->p[0] = 140.0;
    s->p[1] = 0.12;
    s->p[2] = 0.0002;
    s->p[3] = 0.0006;
    s->p[4] = 3;
    s->p[5] = -0.8, s->p[6] = -0.3, s->p[7] = 3.0, s->p[8] = 0.9;
    s->p[9] = 0.9, s->p[10] = 0.2, s->p[11] = 4.0, s->p[12] = 1.2;
    s->p[13] = 0.1, s->p[14] = 0.9, s->p[15] = 2.2, s->p[16] = 0.35;
    s->focal = 140.0;
}

static LT_UNUSED void ss_scene_card(ss_scene_t *s, uint32_t layers)
{
    memset(s, 0, sizeof *s);
    s->name = layers > 1 ? "card 2 layers" : "card";
    s->W = 96;
    s->H = 64;
    s->layers = layers;
    s->fn = ss_w_card;
    s->p[0] = 30, s->p[1] = 60, s->p[2] = 16, s->p[3] = 48;
    s->focal = 96.0;
}

/* ---- rays ------------------------------------------------------------------------------------ */

/* A random unit direction without trigonometry: sin and cos of one angle may be fused into sincos
 * (rounded differently) depending on the compiler flags, which would give each build variant a
 * different ray set; rejection sampling and sqrt are exact IEEE. */
static void ss_rng_dir(ltt_rng_t *g, double *ux, double *uy)
{
    double x, y, n;
    do {
        x = ltt_rng_uniform(g, -1, 1);
        y = ltt_rng_uniform(g, -1, 1);
        n = x * x + y * y;
    } while (n > 1.0 || n < 1e-6);
    n = sqrt(n);
    *ux = x / n;
    *uy = y / n;
}

/* Segment rays: a 4x4 tile of start pixels, one direction and w rate per packet (coherent) or per
 * lane (random); each starts in front of its pixel's surface (w0 = w_true (1 + a), a in
 * [5e-4, 0.2]) and ends at w0 q (q in [0.2, 1.1]), 4 to 1.2 W pixels long, so the set holds hits,
 * occlusions behind objects and misses. Tiles start at x in [0, xr), y in [0, yr); starts past
 * the image clamp to W - 0.5, H - 0.5. s->fn gives w_true, else layer 0 of the buffer (file
 * scenes). */
static LT_UNUSED void ss_gen_rays_in(const ss_scene_t *s, ltt_rng_t *g, size_t n, int coherent,
                                     double xr, double yr, lt_qt_ref_ray_t *r)
{
    size_t p, i;
    for (p = 0; p < n; p += 16) {
        double tx = ltt_rng_uniform(g, 0, xr);
        double ty = ltt_rng_uniform(g, 0, yr);
        double ux, uy, len, a, q;
        ss_rng_dir(g, &ux, &uy);
        len = ltt_rng_uniform(g, 4, 1.2 * s->W);
        a = ltt_rng_uniform(g, 0.0005, 0.2);
        q = ltt_rng_uniform(g, 0.2, 1.1);
        for (i = 0; i < 16 && p + i < n; i++) {
            lt_qt_ref_ray_t *d = &r[p + i];
            double x, y, w0;
            uint32_t ix, iy;
            if (!coherent) {
                tx = ltt_rng_uniform(g, 0, xr);
                ty = ltt_rng_uniform(g, 0, yr);
                ss_rng_dir(g, &ux, &uy);
                len = ltt_rng_uniform(g, 4, 1.2 * s->W);
                a = ltt_rng_uniform(g, 0.0005, 0.2);
                q = ltt_rng_uniform(g, 0.2, 1.1);
            }
            x = tx + (double)(i % 4) + ltt_rng_uniform(g, 0.05, 0.95);
            y = ty + (double)(i / 4) + ltt_rng_uniform(g, 0.05, 0.95);
            if (x >= s->W)
                x = s->W - 0.5;
            if (y >= s->H)
                y = s->H - 0.5;
            if (s->fn != NULL) {
                w0 = s->fn(s, 0, x, y);
            } else {
                ix = (uint32_t)x;
                iy = (uint32_t)y;
                w0 = s->w[(size_t)iy * s->W + ix];
            }
            if (w0 <= 0.0)
                w0 = 0.3;
            w0 *= 1.0 + a;
            if (w0 > 1.9)
                w0 = 1.9;
            d->x = x;
            d->y = y;
            d->w = w0;
            d->dx = len * ux;
            d->dy = len * uy;
            d->dw = w0 * q - w0;
            d->tmin = 0.0;
            d->tmax = 1.0;
        }
    }
}

/* ss_gen_rays_in with tiles inside the image: [0, W - 4) x [0, H - 4) (1 when W or H <= 4). */
static LT_UNUSED void ss_gen_rays(const ss_scene_t *s, ltt_rng_t *g, size_t n, int coherent,
                                  lt_qt_ref_ray_t *r)
{
    ss_gen_rays_in(s, g, n, coherent, s->W > 4 ? s->W - 4 : 1, s->H > 4 ? s->H - 4 : 1, r);
}

/* Rays over a depth buffer (the beachball tests): from the centre of a random pixel, 1% in front
 * of its w (0.5 for a hole), 4 to W / 2 pixels long in a random direction, w falling by up to 80%
 * of the pixel's w. */
static LT_UNUSED void ss_gen_buffer_rays(const ss_scene_t *s, ltt_rng_t *g, size_t n,
                                         lt_qt_ref_ray_t *r)
{
    size_t i;
    for (i = 0; i < n; i++) {
        uint32_t x = ltt_rng_below(g, s->W), y = ltt_rng_below(g, s->H);
        double w0 = s->wqd[(size_t)y * s->W + x], ux, uy, len;
        ss_rng_dir(g, &ux, &uy);
        len = ltt_rng_uniform(g, 4, 0.5 * s->W);
        if (w0 <= 0.0)
            w0 = 0.5;
        r[i].x = x + 0.5;
        r[i].y = y + 0.5;
        r[i].w = w0 * 1.01;
        r[i].dx = len * ux;
        r[i].dy = len * uy;
        r[i].dw = -w0 * ltt_rng_uniform(g, 0.0, 0.8);
        r[i].tmin = 0.0;
        r[i].tmax = 1.0;
    }
}

/* The holes scene's depths (H x W): a disc of depth 2..3 (radius 18 px around (32, 24)) over a
 * background of holes of every kind (NaN, +inf, 0), and -inf, -1 at pixels 5 and 6. */
static LT_UNUSED void ss_holes_depth(float *z, uint32_t W, uint32_t H)
{
    uint32_t x, y;
    for (y = 0; y < H; y++) {
        for (x = 0; x < W; x++) {
            double dx = x + 0.5 - 32.0, dy = y + 0.5 - 24.0;
            float v;
            if (dx * dx + dy * dy < 18.0 * 18.0)
                v = (float)(2.0 + 0.01 * dx + 0.02 * dy);
            else
                v = (x + y) % 3 == 0 ? NAN : ((x + y) % 3 == 1 ? INFINITY : 0.0f);
            z[y * W + x] = v;
        }
    }
    z[5] = -INFINITY;
    z[6] = -1.0f;
}

/* The holes scene's rays: random starts inside the image, up to 30 px per axis, w in [0.3, 0.6]
 * falling by up to 1.2 (some reach w = 0 on the screen). */
static LT_UNUSED void ss_gen_holes_rays(ltt_rng_t *g, uint32_t W, uint32_t H, size_t n,
                                        lt_qt_ref_ray_t *r)
{
    size_t i;
    for (i = 0; i < n; i++) {
        r[i].x = ltt_rng_uniform(g, 0.5, W - 0.5);
        r[i].y = ltt_rng_uniform(g, 0.5, H - 0.5);
        r[i].dx = ltt_rng_uniform(g, -30, 30);
        r[i].dy = ltt_rng_uniform(g, -30, 30);
        r[i].w = ltt_rng_uniform(g, 0.3, 0.6);
        r[i].dw = -ltt_rng_uniform(g, 0.0, 1.2);
        r[i].tmin = 0.0;
        r[i].tmax = 1.0;
    }
}

/* The edge-ray set of test_qt.c / test_ssbase.c on a plane scene (ss_w_plane, s->p[0..2]):
 * SS_EDGE_N rays, 16 per class: grazing (along the plane's gradient, w rate matching it to 1e-3),
 * parallel to x, parallel to y, a point on the screen (only w changes), leaving the screen in
 * front of the plane, entering from outside then hitting, reaching w = 0 on the screen, on pixel
 * edges and corners (diagonal), starting behind the surface, a t sub-range, outside the image
 * entirely, long rays across the screen. */
#define SS_EDGE_N (16 * 12)
static LT_UNUSED void ss_gen_edge_rays(const ss_scene_t *s, ltt_rng_t *g, lt_qt_ref_ray_t *rays)
{
    size_t i;
    enum { N = SS_EDGE_N };
    for (i = 0; i < N; i++) {
        lt_qt_ref_ray_t *r = &rays[i];
        double x = ltt_rng_uniform(g, 0.5, s->W - 0.5), y = ltt_rng_uniform(g, 0.5, s->H - 0.5);
        double wsurf = ss_w_plane(s, 0, x, y);
        r->tmin = 0.0;
        r->tmax = 1.0;
        r->x = x;
        r->y = y;
        switch (i / 16) {
        case 0: /* grazing: along the plane's gradient, w rate matching it to 1e-3 */
            r->dx = ltt_rng_uniform(g, -40, 40);
            r->dy = ltt_rng_uniform(g, -40, 40);
            r->w = wsurf + 1e-6;
            r->dw = (s->p[1] * r->dx + s->p[2] * r->dy) * (1.0 - ltt_rng_uniform(g, 1e-4, 1e-2));
            break;
        case 1: /* parallel to x */
            r->dx = ltt_rng_uniform(g, -60, 60);
            r->dy = 0.0;
            r->w = wsurf + 0.01;
            r->dw = -0.03;
            break;
        case 2: /* parallel to y */
            r->dx = 0.0;
            r->dy = ltt_rng_uniform(g, -60, 60);
            r->w = wsurf + 0.01;
            r->dw = -0.03;
            break;
        case 3: /* a point on the screen: only w changes */
            r->dx = r->dy = 0.0;
            r->w = wsurf + 0.05;
            r->dw = -0.1;
            break;
        case 4: /* leaving the screen in front of the plane */
            r->dx = s->W * 3.0;
            r->dy = ltt_rng_uniform(g, -5, 5);
            r->w = 0.9;
            r->dw = -0.1;
            break;
        case 5: /* entering from outside, then hitting */
            r->x = -30.0;
            r->dx = s->W + 60.0;
            r->dy = ltt_rng_uniform(g, -10, 10);
            r->w = 0.6;
            r->dw = -0.4;
            break;
        case 6: /* reaching w = 0 on the screen */
            r->dx = ltt_rng_uniform(g, -10, 10);
            r->dy = ltt_rng_uniform(g, -10, 10);
            r->w = wsurf + 0.3;
            r->dw = -3.0 * r->w;
            break;
        case 7: /* on pixel edges and corners, diagonal */
            r->x = floor(x);
            r->y = floor(y);
            r->dx = 16.0;
            r->dy = (i & 1) ? 16.0 : -16.0;
            r->w = wsurf + 0.01;
            r->dw = -0.05;
            break;
        case 8: /* starting 2.5% behind the surface (theta 1.6%): occluded from the start */
            r->dx = ltt_rng_uniform(g, -10, 10);
            r->dy = ltt_rng_uniform(g, -10, 10);
            r->w = wsurf - 0.01;
            r->dw = -0.01;
            break;
        case 9: /* t sub-range */
            r->dx = ltt_rng_uniform(g, -30, 30);
            r->dy = ltt_rng_uniform(g, -30, 30);
            r->w = wsurf + 0.02;
            r->dw = -0.06;
            r->tmin = 0.1;
            r->tmax = 0.3;
            break;
        case 10: /* outside the image entirely */
            r->x = -20.0;
            r->y = -20.0;
            r->dx = -10.0;
            r->dy = 3.0;
            r->w = 0.5;
            r->dw = -0.2;
            break;
        default: /* long rays across the screen */
            r->x = -0.0;
            r->dx = s->W;
            r->dy = ltt_rng_uniform(g, -(double)s->H, (double)s->H);
            r->w = 0.8;
            r->dw = -0.6;
            break;
        }
    }
}

/* The checkerboard's adversarial rays (ss_w_checker, 64 x 64): from within a pixel of the centre,
 * 64 px long in a random direction (every 8th axis-parallel), at w 0.375 between the two depths,
 * so they overlap every cell above level 0 and never cross a surface. */
static LT_UNUSED void ss_gen_checker_rays(ltt_rng_t *g, size_t n, lt_qt_ref_ray_t *rays)
{
    size_t i;
    for (i = 0; i < n; i++) {
        double ux, uy;
        ss_rng_dir(g, &ux, &uy);
        rays[i].x = 32.5 + ltt_rng_uniform(g, -1, 1);
        rays[i].y = 32.5 + ltt_rng_uniform(g, -1, 1);
        rays[i].dx = 64.0 * ux;
        rays[i].dy = 64.0 * uy;
        if (i % 8 == 0)
            rays[i].dy = 0.0; /* axis-parallel */
        rays[i].w = 0.375;
        rays[i].dw = 0.0;
        rays[i].tmin = 0.0;
        rays[i].tmax = 1.0;
    }
}

/* Screen point of camera-space P (z > 0) for a pinhole (focal f, centre W/2, H/2): pixels and
 * w = 2^zexp / z. */
static void ss_project(const ss_scene_t *s, const double P[3], double out[3])
{
    out[0] = 0.5 * s->W + s->focal * P[0] / P[2];
    out[1] = 0.5 * s->H + s->focal * P[1] / P[2];
    out[2] = ldexp(1.0, s->zexp) / P[2];
}

/* Camera-space point of screen (x, y) at inverse depth w > 0. */
static void ss_unproject(const ss_scene_t *s, double x, double y, double w, double P[3])
{
    double z = ldexp(1.0, s->zexp) / w;
    P[0] = (x - 0.5 * s->W) * z / s->focal;
    P[1] = (y - 0.5 * s->H) * z / s->focal;
    P[2] = z;
}

/* The screen segment of the camera-space ray C + u D, u >= u0 (C + u0 D in front of the camera):
 * from its projection to the vanishing point (w = 0) when D goes away from the camera, else to
 * where z falls to zmin; then clipped to the box [-2W, 3W] x [-2H, 3H] (the segment is a straight
 * line in (x, y, w), so clipping is linear). Returns 0, or -1 when nothing is left. */
static int ss_segment(const ss_scene_t *s, const double C[3], const double D[3], double u0,
                      double zmin, lt_qt_ref_ray_t *r)
{
    double P0[3], a[3], b[3], lo = 0.0, hi = 1.0;
    int k;
    for (k = 0; k < 3; k++)
        P0[k] = C[k] + u0 * D[k];
    if (P0[2] <= zmin)
        return -1;
    ss_project(s, P0, a);
    if (D[2] > 1e-12 * sqrt(D[0] * D[0] + D[1] * D[1] + D[2] * D[2])) {
        b[0] = 0.5 * s->W + s->focal * D[0] / D[2];
        b[1] = 0.5 * s->H + s->focal * D[1] / D[2];
        b[2] = 0.0;
    } else {
        double u1 = u0 + (P0[2] - zmin) / -D[2], P1[3];
        if (D[2] == 0.0)
            u1 = u0 + 1e3 * P0[2];
        for (k = 0; k < 3; k++)
            P1[k] = C[k] + u1 * D[k];
        if (P1[2] < zmin)
            P1[2] = zmin;
        ss_project(s, P1, b);
    }
    for (k = 0; k < 2; k++) {
        double ext = k ? s->H : s->W, bl = -2.0 * ext, bh = 3.0 * ext, d = b[k] - a[k];
        if (a[k] < bl || a[k] > bh)
            return -1;
        if (d > 0.0 && a[k] + d > bh)
            hi = fmin(hi, (bh - a[k]) / d);
        if (d < 0.0 && a[k] + d < bl)
            hi = fmin(hi, (bl - a[k]) / d);
    }
    (void)lo;
    r->x = a[0];
    r->y = a[1];
    r->w = a[2];
    r->dx = (b[0] - a[0]) * hi;
    r->dy = (b[1] - a[1]) * hi;
    r->dw = (b[2] - a[2]) * hi;
    r->tmin = 0.0;
    r->tmax = 1.0;
    return r->w < 1.99 ? 0 : -1;
}

/* Reflection rays (screen-space reflections, the use of both baselines): from the centre of a
 * random valid pixel of layer 0, camera-space normal from central differences of the unprojected
 * neighbours, the view direction reflected about it, to the vanishing point (or the near plane at
 * z / 4); the first 1.25 pixels are skipped (tmin) so no tracer meets its own start pixel. The
 * scene needs focal and zexp. Returns the number of rays made (n unless valid pixels are rare). */
static LT_UNUSED size_t ss_gen_refl(const ss_scene_t *s, ltt_rng_t *g, size_t n,
                                    lt_qt_ref_ray_t *r)
{
    size_t made = 0, tries = 0;
    while (made < n && tries < 50 * n + 1000) {
        uint32_t x = ltt_rng_below(g, s->W), y = ltt_rng_below(g, s->H);
        const double *w = s->wqd;
        double P[3], Pl[3], Pr[3], Pu[3], Pd[3], ex[3], ey[3], N[3], V[3], R[3], nn, vn, len;
        uint32_t xl = x > 0 ? x - 1 : x, xr = x + 1 < s->W ? x + 1 : x;
        uint32_t yu = y > 0 ? y - 1 : y, yd = y + 1 < s->H ? y + 1 : y;
        int k;
        tries++;
        if (xl == xr || yu == yd)
            continue;
        if (w[(size_t)y * s->W + x] <= 0.0 || w[(size_t)y * s->W + xl] <= 0.0 ||
            w[(size_t)y * s->W + xr] <= 0.0 || w[(size_t)yu * s->W + x] <= 0.0 ||
            w[(size_t)yd * s->W + x] <= 0.0)
            continue;
        ss_unproject(s, x + 0.5, y + 0.5, w[(size_t)y * s->W + x], P);
        ss_unproject(s, xl + 0.5, y + 0.5, w[(size_t)y * s->W + xl], Pl);
        ss_unproject(s, xr + 0.5, y + 0.5, w[(size_t)y * s->W + xr], Pr);
        ss_unproject(s, x + 0.5, yu + 0.5, w[(size_t)yu * s->W + x], Pu);
        ss_unproject(s, x + 0.5, yd + 0.5, w[(size_t)yd * s->W + x], Pd);
        for (k = 0; k < 3; k++) {
            ex[k] = Pr[k] - Pl[k];
            ey[k] = Pd[k] - Pu[k];
        }
        N[0] = ex[1] * ey[2] - ex[2] * ey[1];
        N[1] = ex[2] * ey[0] - ex[0] * ey[2];
        N[2] = ex[0] * ey[1] - ex[1] * ey[0];
        nn = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
        len = sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]);
        if (nn <= 0.0)
            continue;
        vn = 0.0;
        for (k = 0; k < 3; k++) {
            N[k] /= nn;
            V[k] = P[k] / len;
            vn += V[k] * N[k];
        }
        if (vn > 0.0) {
            for (k = 0; k < 3; k++)
                N[k] = -N[k];
            vn = -vn;
        }
        if (vn > -0.02)
            continue; /* grazing view: the normal of a silhouette pixel */
        for (k = 0; k < 3; k++)
            R[k] = V[k] - 2.0 * vn * N[k];
        if (ss_segment(s, P, R, 0.0, 0.25 * P[2], &r[made]) != 0)
            continue;
        len = hypot(r[made].dx, r[made].dy);
        if (len < 3.0)
            continue;
        r[made].tmin = 1.25 / len;
        made++;
    }
    return made;
}

/* Novel-view rays: the target camera is the source camera moved by T (camera-space units, no
 * rotation); the ray of target pixel (u, v) starts at depth zn in front of it and runs to infinity;
 * its screen segment in the source view is what lt_reproj produces (host fallback in double).
 * Pixels of the 4x4 tiles (tx, ty) = (i step, j step) of the target image. Returns the count. */
static LT_UNUSED size_t ss_gen_novel(const ss_scene_t *s, const double T[3], double zn,
                                     uint32_t step, size_t n, lt_qt_ref_ray_t *r)
{
    size_t made = 0;
    uint32_t tx, ty, i;
    for (ty = 0; ty + 4 <= s->H && made < n; ty += 4 * step) {
        for (tx = 0; tx + 4 <= s->W && made < n; tx += 4 * step) {
            for (i = 0; i < 16 && made < n; i++) {
                double D[3], C[3];
                uint32_t u = tx + i % 4, v = ty + i / 4;
                D[0] = (u + 0.5 - 0.5 * s->W) / s->focal;
                D[1] = (v + 0.5 - 0.5 * s->H) / s->focal;
                D[2] = 1.0;
                C[0] = T[0];
                C[1] = T[1];
                C[2] = T[2];
                if (ss_segment(s, C, D, zn, 0.05 * zn, &r[made]) != 0) {
                    /* keep the packet's lane layout: a zero-length ray off the screen misses */
                    r[made].x = r[made].y = -1.0;
                    r[made].w = 0.5;
                    r[made].dx = r[made].dy = r[made].dw = 0.0;
                    r[made].tmin = 0.0;
                    r[made].tmax = 1.0;
                }
                made++;
            }
        }
    }
    return made;
}

/* ---- packets --------------------------------------------------------------------------------- */

/* double -> float through a volatile (GCC's SLP vectoriser otherwise drops the float rounding at
 * -O2 -march=native; see test_qt.c). */
static float ss_f32(double v)
{
    volatile float f = (float)v;
    return f;
}

/* Exact doubles of the lanes in k of a packet (what each path sees) into ex[lane]. */
static void ss_exact_q30(const lt_qray16_q30_t *r, lt_mask16_t k, lt_qt_ref_ray_t *ex)
{
    int i;
    for (i = 0; i < 16; i++) {
        if (!LTT_ON(k, i))
            continue;
        ex[i].x = r->x.l[i] / 65536.0;
        ex[i].y = r->y.l[i] / 65536.0;
        ex[i].w = r->w.l[i] / SS_Q30;
        ex[i].dx = r->dx.l[i] / 65536.0;
        ex[i].dy = r->dy.l[i] / 65536.0;
        ex[i].dw = r->dw.l[i] / SS_Q30;
        ex[i].tmin = r->tmin.l[i] / SS_Q30;
        ex[i].tmax = r->tmax.l[i] / SS_Q30;
    }
}

static void ss_exact_f32(const lt_qray16_f32_t *r, lt_mask16_t k, lt_qt_ref_ray_t *ex)
{
    int i;
    for (i = 0; i < 16; i++) {
        if (!LTT_ON(k, i))
            continue;
        ex[i].x = (double)r->x.l[i];
        ex[i].y = (double)r->y.l[i];
        ex[i].w = (double)r->w.l[i];
        ex[i].dx = (double)r->dx.l[i];
        ex[i].dy = (double)r->dy.l[i];
        ex[i].dw = (double)r->dw.l[i];
        ex[i].tmin = (double)r->tmin.l[i];
        ex[i].tmax = (double)r->tmax.l[i];
    }
}

/* Lanes [0, cnt) of an s1.30 packet from d[0 .. cnt): end points to s15.16 / s1.30 half up, the
 * differences of the rounded ends; ex[] receives the exact doubles of what the core sees.
 * Returns the lane mask. */
static LT_UNUSED lt_mask16_t ss_pack_q30(const lt_qt_ref_ray_t *d, size_t cnt, lt_qray16_q30_t *r,
                                         lt_qt_ref_ray_t *ex)
{
    size_t i;
    lt_mask16_t k = 0;
    memset(r, 0, sizeof *r);
    for (i = 0; i < cnt && i < 16; i++) {
        int32_t x0 = lt_q16_from_double_sat(d[i].x), y0 = lt_q16_from_double_sat(d[i].y);
        int32_t x1 = lt_q16_from_double_sat(d[i].x + d[i].dx);
        int32_t y1 = lt_q16_from_double_sat(d[i].y + d[i].dy);
        int32_t w0 = lt_q30_from_double_sat(d[i].w);
        int32_t w1 = lt_q30_from_double_sat(d[i].w + d[i].dw);
        r->x.l[i] = x0;
        r->y.l[i] = y0;
        r->w.l[i] = w0;
        r->dx.l[i] = lt__ssat32((int64_t)x1 - x0);
        r->dy.l[i] = lt__ssat32((int64_t)y1 - y0);
        r->dw.l[i] = lt__ssat32((int64_t)w1 - w0);
        r->tmin.l[i] = lt_q30_from_double_sat(d[i].tmin);
        r->tmax.l[i] = lt_q30_from_double_sat(d[i].tmax);
        k = (lt_mask16_t)(k | (1u << i));
    }
    ss_exact_q30(r, k, ex);
    return k;
}

static LT_UNUSED lt_mask16_t ss_pack_f32(const lt_qt_ref_ray_t *d, size_t cnt, lt_qray16_f32_t *r,
                                         lt_qt_ref_ray_t *ex)
{
    size_t i;
    lt_mask16_t k = 0;
    memset(r, 0, sizeof *r);
    for (i = 0; i < cnt && i < 16; i++) {
        r->x.l[i] = ss_f32(d[i].x);
        r->y.l[i] = ss_f32(d[i].y);
        r->w.l[i] = ss_f32(d[i].w);
        r->dx.l[i] = ss_f32(d[i].dx);
        r->dy.l[i] = ss_f32(d[i].dy);
        r->dw.l[i] = ss_f32(d[i].dw);
        r->tmin.l[i] = ss_f32(d[i].tmin);
        r->tmax.l[i] = ss_f32(d[i].tmax);
        k = (lt_mask16_t)(k | (1u << i));
    }
    ss_exact_f32(r, k, ex);
    return k;
}

/* The invalid-lane packet of the bad-ray tests: 16 lanes at (10, 10) px, w 1/2, 5 px along x,
 * t in [0, 1]; then lane 0 |x| > 2^14 px, lane 1 w < 0, lane 2 tmin > tmax, lane 3 tmax > 1, lane
 * 4 an end beyond 2^14 px. Lanes 0-4 must come back BADRAY, the others traced. */
static LT_UNUSED void ss_bad_rays_q30(lt_qray16_q30_t *r)
{
    int i;
    memset(r, 0, sizeof *r);
    for (i = 0; i < 16; i++) {
        r->x.l[i] = 10 << 16;
        r->y.l[i] = 10 << 16;
        r->w.l[i] = 1 << 29;
        r->dx.l[i] = 5 << 16;
        r->tmax.l[i] = 1 << 30;
    }
    r->x.l[0] = (int32_t)((1 << 14) + 1) << 16;   /* |x| > 2^14 */
    r->w.l[1] = -1;                               /* w < 0 */
    r->tmin.l[2] = 1 << 29, r->tmax.l[2] = 1 << 28; /* tmin > tmax */
    r->tmax.l[3] = (1 << 30) + 1;                  /* tmax > 1 */
    r->dx.l[4] = (int32_t)0x7FFF0000;              /* end beyond 2^14 */
}

/* The size-query tests' input: n s1.30 samples in [0.25, 0.254) (a fixed pseudo-random walk)
 * and their float copies. */
static LT_UNUSED void ss_size_test_w(lt_q30_t *w, float *wf, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        w[i] = (lt_q30_t)(0x10000000 + (int32_t)((i * 7919u) % 65536u) * 64);
        wf[i] = (float)(w[i] / SS_Q30);
    }
}

/* One traced ray, any tracer. */
typedef struct ss_res {
    int status, layer, nodes, aabb, planes;
    double t, w;
} ss_res_t;

/* Lanes [0, cnt) of a hit packet as ss_res_t (t and w as exact doubles). */
static LT_UNUSED void ss_res_q30(const lt_qhit16_q30_t *h, size_t cnt, ss_res_t *out)
{
    size_t i;
    for (i = 0; i < cnt && i < 16; i++) {
        ss_res_t *o = &out[i];
        o->status = h->status.l[i];
        o->layer = h->layer.l[i];
        o->nodes = h->nodes.l[i];
        o->aabb = h->aabb.l[i];
        o->planes = h->planes.l[i];
        o->t = h->t.l[i] / SS_Q30;
        o->w = h->w.l[i] / SS_Q30;
    }
}

static LT_UNUSED void ss_res_f32(const lt_qhit16_f32_t *h, size_t cnt, ss_res_t *out)
{
    size_t i;
    for (i = 0; i < cnt && i < 16; i++) {
        ss_res_t *o = &out[i];
        o->status = h->status.l[i];
        o->layer = h->layer.l[i];
        o->nodes = h->nodes.l[i];
        o->aabb = h->aabb.l[i];
        o->planes = h->planes.l[i];
        o->t = (double)h->t.l[i];
        o->w = (double)h->w.l[i];
    }
}

/* ---- double references of the baselines' surface model --------------------------------------- */

static LT_UNUSED int ss_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* One step of both references: the ray over [ta, tb] against the shells of every layer at pixel
 * (px, py) (clamped into the image). Returns 1 (hit: *th, *lh), 2 (entirely behind the deepest
 * layer's shell) or 0. */
static int ss_ref_pixel(const double *w, uint32_t W, uint32_t H, uint32_t layers, double k,
                        const lt_qt_ref_ray_t *r, double ta, double tb, int32_t px, int32_t py,
                        double *th, int *lh)
{
    double wa = r->w + ta * r->dw, wb = r->w + tb * r->dw, lo = fmin(wa, wb), hi = fmax(wa, wb);
    uint32_t l;
    int hit = 0, behind = 0;
    if (px < 0)
        px = 0;
    if (py < 0)
        py = 0;
    if (px >= (int32_t)W)
        px = (int32_t)W - 1;
    if (py >= (int32_t)H)
        py = (int32_t)H - 1;
    for (l = 0; l < layers; l++) {
        double ws = w[((size_t)l * H + (size_t)py) * W + (size_t)px], A = ws * k, B = ws, te;
        if (!(ws > 0.0))
            continue;
        if (hi >= A && lo <= B) {
            if (wa > B)
                te = ta + (tb - ta) * (wa - B) / (wa - wb);
            else if (wa < A)
                te = ta + (tb - ta) * (A - wa) / (wb - wa);
            else
                te = ta;
            if (!hit || te < *th) {
                *th = te;
                *lh = (int)l;
            }
            hit = 1;
        } else if (l + 1 == layers && hi < A) {
            behind = 1;
        }
    }
    return hit ? 1 : (behind ? 2 : 0);
}

/* The reference of lt_hiz: every pixel the segment crosses, in order of t (sorted grid-line
 * crossings; the pixel of an interval is the one at its midpoint), each tested on its own [ta, tb].
 * dda != 0 gives the reference of lt_ssdda instead: McGuire & Mara's steps of one pixel along the
 * major axis, step i on [t0 + (2i - 1) h, t0 + (2i + 1) h] sampling the pixel at t0 + 2 i h.
 * w: layers x H x W (w units, holes 0); k = 1 / (1 + theta) as the tracer holds it. */
static LT_UNUSED void ss_ref_trace(const double *w, uint32_t W, uint32_t H, uint32_t layers,
                                   double k, int stop, int dda, const lt_qt_ref_ray_t *r,
                                   ss_res_t *o)
{
    double t0, t1;
    memset(o, 0, sizeof *o);
    o->status = LT_QT_MISS;
    o->layer = -1;
    lt_qt_ref_clip(W, H, r, &t0, &t1);
    o->t = t1;
    if (!(t0 < t1)) {
        o->w = r->w + o->t * r->dw;
        return;
    }
    if (!dda) {
        size_t cap = 2u * (W + H) + 8u, n, i;
        double *ts = (double *)malloc(cap * sizeof *ts);
        if (ts == NULL)
            return;
        n = lt_qt_ref_crossings(r, t0, t1, ts, cap);
        for (i = 0; i + 1 < n; i++) {
            double ta = ts[i], tb = ts[i + 1], tm = 0.5 * (ta + tb), th = 0.0;
            int lh = 0, v;
            if (tb <= ta)
                continue;
            o->nodes++;
            v = ss_ref_pixel(w, W, H, layers, k, r, ta, tb, (int32_t)floor(r->x + tm * r->dx),
                             (int32_t)floor(r->y + tm * r->dy), &th, &lh);
            if (v == 1 || (v == 2 && stop)) {
                o->status = v == 1 ? LT_QT_HIT : LT_QT_OCCLUDED;
                o->t = v == 1 ? th : ta;
                o->layer = v == 1 ? lh : (int)layers - 1;
                break;
            }
        }
        free(ts);
    } else {
        int ymaj = fabs(r->dy) > fabs(r->dx), pt = r->dx == 0.0 && r->dy == 0.0;
        double h = pt ? 0.0 : 0.5 / fabs(ymaj ? r->dy : r->dx), ta = t0;
        long i;
        for (i = 0;; i++) {
            double tb = pt ? t1 : fmin(t0 + (2.0 * (double)i + 1.0) * h, t1);
            double ts = fmax(ta, fmin(t0 + 2.0 * (double)i * h, tb)), th = 0.0;
            int lh = 0, v;
            o->nodes++;
            v = ss_ref_pixel(w, W, H, layers, k, r, ta, tb, (int32_t)floor(r->x + ts * r->dx),
                             (int32_t)floor(r->y + ts * r->dy), &th, &lh);
            if (v == 1 || (v == 2 && stop)) {
                o->status = v == 1 ? LT_QT_HIT : LT_QT_OCCLUDED;
                o->t = v == 1 ? th : ta;
                o->layer = v == 1 ? lh : (int)layers - 1;
                break;
            }
            if (tb >= t1)
                break;
            ta = tb;
        }
    }
    o->w = r->w + o->t * r->dw;
}

/* ---- cmocka helpers: only in programs that include <cmocka.h> first (not ssbench.c) --------- */
#ifdef fail_msg
#include <stdio.h>

#include "io/lt_exr.h"

/* The shared depth buffer at path (../shared/...) into *d: 1 when read (a read error fails the
 * test), 0 when the file is missing -- reported as skipped, and a failure when CI=true. */
static LT_UNUSED int ss_shared_depth(const char *path, lt_exr_depth_t *d)
{
    lt_exr_read_opts_t o = LT_EXR_READ_OPTS_DEFAULT;
    lt_diag_t diag;
    FILE *fp = fopen(path, "rb");
    if (fp == NULL) {
        const char *ci = getenv("CI");
        ltt_report("beachball: %s missing, skipped\n", path);
        if (ci != NULL && strcmp(ci, "true") == 0)
            fail_msg("CI=true and %s is missing", path);
        return 0;
    }
    fclose(fp);
    memset(d, 0, sizeof *d);
    if (lt_exr_read_depth(path, NULL, &o, d, &diag) != 0)
        fail_msg("%s", diag.msg);
    return 1;
}

/* Lane i of a poisoned s1.30 hit packet was not written (every field). */
static LT_UNUSED void ss_assert_untouched_q30(const lt_qhit16_q30_t *h, unsigned i)
{
    assert_int_equal(ltt_touched(&h->status.l[i], 0, 4), 0);
    assert_int_equal(ltt_touched(&h->t.l[i], 0, 4), 0);
    assert_int_equal(ltt_touched(&h->w.l[i], 0, 4), 0);
    assert_int_equal(ltt_touched(&h->layer.l[i], 0, 4), 0);
    assert_int_equal(ltt_touched(&h->nodes.l[i], 0, 4), 0);
    assert_int_equal(ltt_touched(&h->aabb.l[i], 0, 4), 0);
    assert_int_equal(ltt_touched(&h->planes.l[i], 0, 4), 0);
}
#endif /* fail_msg */

#endif /* LT_SSB_TESTLIB_H */
