/* embree_race.c - lanetrace's native build against Embree 3 (Debian libembree-dev) at its best on
 * the machine it runs on, single thread, the same rays in the same run: 1024x1024 (by default)
 * primary rays of the benchmark view (docs/results.md, "The benchmark view") and shadow rays from
 * each primary hit to a point light.
 *
 * Embree runs every mode: primary rays with rtcIntersect1 (row by row), rtcIntersect4 (2x2 tiles),
 * rtcIntersect8 (4x2 tiles, two per 4x4 tile) and rtcIntersect16 (4x4 tiles); shadow rays with
 * rtcOccluded1/4/8/16 in the same tilings (single rays in 4x4-tile order), all from
 * rtcIntersect1's hits. Every mode is timed with the incoherent and the coherent context flag and
 * keeps the faster; each timing is one warm-up pass, then the median of --runs passes. A mode
 * counts only if it agrees with the single-ray mode (the same triangle, or one at the same
 * distance, on >= 99.9% of pixels; the same occlusion on >= 99.9% of shadow rays and an occluded
 * count within 0.01%): a broken
 * packet setup cannot make a fast wrong figure (it is printed as DISAGREES, left out of the best
 * mode, and the program exits 1). The build is rtcCommitScene alone (the device is created before),
 * the first commit and the median of RACE_REBUILDS rebuilds into fresh scenes.
 *
 * lanetrace runs its own single-ray, 16-ray packet and shadow packet paths in s15.16 and float32
 * (one warm-up pass each, then the median of --runs), and is reported against Embree's best mode
 * and against each mode: single rays against rtcIntersect1, packets against the fastest of
 * rtcIntersect4/8/16, shadow packets against the fastest of rtcOccluded1/4/8/16.
 *
 * The machine is printed first: the CPU model (/proc/cpuinfo), the ISA the CPU supports, the ISA
 * this build was compiled for, Embree's version and its native packet widths
 * (RTC_DEVICE_PROPERTY_NATIVE_RAY4/8/16_SUPPORTED; a width that is not native is emulated).
 * --kv adds "race: ..." lines (key value pairs) that tests/bench/race_doc.sh turns into
 * docs/results.md's race table (make race-doc). Embree is linked only into this benchmark. Host
 * only; `make bench` runs it, `make test` runs it small (tests/run.d/race.sh).
 * --embree-config CFG is appended to Embree's device configuration "threads=1" (e.g. isa=avx2: the
 * kernels of an AVX2-only machine, where ray16 is emulated).
 * Usage: embree-race [--mesh PATH] [--res N] [--runs N] [--structure NAME] [--kv]
 *                    [--embree-config CFG]
 */
#include "io/lt_mesh.h"
#include "cli/lt_cliutil.h"
#include "render/lt_par.h"
#include "render/lt_render.h"
#include "render/lt_scene.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#define RACE_X86 1
#else
#define RACE_X86 0
#endif

#define RACE_MAX_RUNS 15
#define RACE_REBUILDS 5
/* agreement with the single-ray mode a mode needs to count (percent of pixels / shadow rays); a
 * primary ray agrees if it hits the same triangle, or reports another triangle that the ray
 * really hits at the same distance (within 1e-6 relative, checked in double: the coplanar
 * duplicate faces of the Cornell box, Conference and the dragon, where Embree's coherent packets
 * keep another face of the tie than its single rays) */
#define RACE_AGREE_MIN 99.9
/* largest difference of occluded counts against rtcOccluded1, as a fraction of the shadow rays */
#define RACE_OCC_TOL 1e-4

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return v[n / 2];
}

typedef struct race {
    const lt_scene_t *sc;
    lt_camera_t cam;
    RTCScene scene;
    float *dirs;       /* 3 floats per pixel */
    unsigned *id1;     /* rtcIntersect1's hit triangle per pixel (the reference, shadow origins) */
    float *t1;         /* rtcIntersect1's hit distance per pixel */
    unsigned *idm;     /* a packet mode's hit triangle per pixel */
    float *tm;         /* a packet mode's hit distance per pixel */
    uint8_t *occ1;     /* rtcOccluded1's result per pixel (1 = occluded) */
    uint8_t *occm;     /* a shadow mode's result per pixel */
    const float *vb;   /* Embree's vertices, 9 floats per triangle */
    float eps;         /* shadow ray tnear */
    float light[3];
} race_t;

/* ---- primary rays ---- */

static unsigned hit_id(unsigned geom, unsigned prim)
{
    return geom == RTC_INVALID_GEOMETRY_ID ? RTC_INVALID_GEOMETRY_ID : prim;
}

/* rtcIntersect1, row by row (as lanetrace's single rays) */
static void embree_primary1(race_t *r, struct RTCIntersectContext *ctx, unsigned *id, float *t)
{
    uint32_t i, n = r->cam.width * r->cam.height;
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = (float)r->cam.eye[0];
    rh.ray.org_y = (float)r->cam.eye[1];
    rh.ray.org_z = (float)r->cam.eye[2];
    rh.ray.mask = 0xFFFFFFFFu;
    for (i = 0; i < n; i++) {
        rh.ray.dir_x = r->dirs[3 * i];
        rh.ray.dir_y = r->dirs[3 * i + 1];
        rh.ray.dir_z = r->dirs[3 * i + 2];
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = INFINITY;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(r->scene, ctx, &rh);
        id[i] = hit_id(rh.hit.geomID, rh.hit.primID);
        t[i] = rh.ray.tfar;
    }
}

/* rtcIntersectN over TWxTH sub-tiles of each 4x4 tile: lane l = pixel (x0 + l % TW, y0 + l / TW).
 * The fields Embree does not write (origin, tnear, mask, time, id, flags) are set once; per packet
 * only the directions, tfar and the hit ids. valid[] must be aligned to the packet size (Embree
 * loads it as a vector): the union takes the alignment of Embree's RTCRayN block. */
#define RACE_PRIMARY_N(N, TW, TH)                                                                 \
    static void embree_primary##N(race_t *r, struct RTCIntersectContext *ctx, unsigned *id,       \
                                  float *t)                                                       \
    {                                                                                             \
        uint32_t tx, ty, sx, sy, W = r->cam.width, H = r->cam.height;                             \
        struct RTCRayHit##N rh;                                                                   \
        union {                                                                                   \
            struct RTCRay##N align;                                                               \
            int v[N];                                                                             \
        } vu;                                                                                     \
        int *valid = vu.v, l;                                                                     \
        memset(&rh, 0, sizeof rh);                                                                \
        for (l = 0; l < N; l++) {                                                                 \
            rh.ray.org_x[l] = (float)r->cam.eye[0];                                               \
            rh.ray.org_y[l] = (float)r->cam.eye[1];                                               \
            rh.ray.org_z[l] = (float)r->cam.eye[2];                                               \
            rh.ray.mask[l] = 0xFFFFFFFFu;                                                         \
        }                                                                                         \
        for (ty = 0; ty < H; ty += 4)                                                             \
            for (tx = 0; tx < W; tx += 4)                                                         \
                for (sy = 0; sy < 4; sy += TH)                                                    \
                    for (sx = 0; sx < 4; sx += TW) {                                              \
                        for (l = 0; l < N; l++) {                                                 \
                            uint32_t x = tx + sx + (uint32_t)(l % TW);                            \
                            uint32_t y = ty + sy + (uint32_t)(l / TW), p = y * W + x;             \
                            valid[l] = (x < W && y < H) ? -1 : 0;                                 \
                            if (!valid[l])                                                        \
                                continue;                                                         \
                            rh.ray.dir_x[l] = r->dirs[3 * p];                                     \
                            rh.ray.dir_y[l] = r->dirs[3 * p + 1];                                 \
                            rh.ray.dir_z[l] = r->dirs[3 * p + 2];                                 \
                            rh.ray.tfar[l] = INFINITY;                                            \
                            rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;                           \
                            rh.hit.instID[0][l] = RTC_INVALID_GEOMETRY_ID;                        \
                        }                                                                         \
                        rtcIntersect##N(valid, r->scene, ctx, &rh);                               \
                        for (l = 0; l < N; l++) {                                                 \
                            uint32_t x = tx + sx + (uint32_t)(l % TW);                            \
                            uint32_t y = ty + sy + (uint32_t)(l / TW);                            \
                            if (!valid[l])                                                        \
                                continue;                                                         \
                            id[y * W + x] = hit_id(rh.hit.geomID[l], rh.hit.primID[l]);           \
                            t[y * W + x] = rh.ray.tfar[l];                                        \
                        }                                                                         \
                    }                                                                             \
    }

RACE_PRIMARY_N(4, 2, 2)
RACE_PRIMARY_N(8, 4, 2)
RACE_PRIMARY_N(16, 4, 4)

/* ---- shadow rays, from rtcIntersect1's hits towards the light ---- */

/* The shadow ray of pixel p (which must have a hit): origin o, unit direction d, length *len. */
static void shadow_ray(const race_t *r, uint32_t p, float o[3], float d[3], float *len)
{
    uint32_t a;
    float l;
    for (a = 0; a < 3; a++) {
        o[a] = (float)r->cam.eye[a] + r->t1[p] * r->dirs[3 * p + a];
        d[a] = r->light[a] - o[a];
    }
    l = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (a = 0; a < 3; a++)
        d[a] /= l;
    *len = l;
}

/* rtcOccluded1 in 4x4-tile order (the packets' order); returns the occluded count. */
static uint32_t embree_shadow1(race_t *r, struct RTCIntersectContext *ctx, uint8_t *occ,
                               uint32_t *nrays)
{
    uint32_t tx, ty, W = r->cam.width, H = r->cam.height, n = 0, no = 0;
    struct RTCRay ray;
    memset(&ray, 0, sizeof ray);
    ray.mask = 0xFFFFFFFFu;
    for (ty = 0; ty < H; ty += 4)
        for (tx = 0; tx < W; tx += 4) {
            int l;
            for (l = 0; l < 16; l++) {
                uint32_t x = tx + (uint32_t)(l % 4), y = ty + (uint32_t)(l / 4), p = y * W + x;
                float o[3], d[3], len;
                if (x >= W || y >= H || r->id1[p] == RTC_INVALID_GEOMETRY_ID)
                    continue;
                shadow_ray(r, p, o, d, &len);
                ray.org_x = o[0];
                ray.org_y = o[1];
                ray.org_z = o[2];
                ray.dir_x = d[0];
                ray.dir_y = d[1];
                ray.dir_z = d[2];
                ray.tnear = r->eps;
                ray.tfar = len;
                rtcOccluded1(r->scene, ctx, &ray);
                occ[p] = ray.tfar < 0.0f;
                no += occ[p];
                n++;
            }
        }
    *nrays = n;
    return no;
}

/* rtcOccludedN over TWxTH sub-tiles of each 4x4 tile, lanes as the primary packets. */
#define RACE_SHADOW_N(N, TW, TH)                                                                  \
    static uint32_t embree_shadow##N(race_t *r, struct RTCIntersectContext *ctx, uint8_t *occ,    \
                                     uint32_t *nrays)                                             \
    {                                                                                             \
        uint32_t tx, ty, sx, sy, W = r->cam.width, H = r->cam.height, n = 0, no = 0;              \
        struct RTCRay##N ray;                                                                     \
        union {                                                                                   \
            struct RTCRay##N align;                                                               \
            int v[N];                                                                             \
        } vu;                                                                                     \
        int *valid = vu.v, l;                                                                     \
        memset(&ray, 0, sizeof ray);                                                              \
        for (l = 0; l < N; l++)                                                                   \
            ray.mask[l] = 0xFFFFFFFFu;                                                            \
        for (ty = 0; ty < H; ty += 4)                                                             \
            for (tx = 0; tx < W; tx += 4)                                                         \
                for (sy = 0; sy < 4; sy += TH)                                                    \
                    for (sx = 0; sx < 4; sx += TW) {                                              \
                        int any = 0;                                                              \
                        for (l = 0; l < N; l++) {                                                 \
                            uint32_t x = tx + sx + (uint32_t)(l % TW);                            \
                            uint32_t y = ty + sy + (uint32_t)(l / TW), p = y * W + x;             \
                            float o[3], d[3], len;                                                \
                            valid[l] = (x < W && y < H && r->id1[p] != RTC_INVALID_GEOMETRY_ID)   \
                                           ? -1 : 0;                                              \
                            if (!valid[l])                                                        \
                                continue;                                                         \
                            shadow_ray(r, p, o, d, &len);                                         \
                            ray.org_x[l] = o[0];                                                  \
                            ray.org_y[l] = o[1];                                                  \
                            ray.org_z[l] = o[2];                                                  \
                            ray.dir_x[l] = d[0];                                                  \
                            ray.dir_y[l] = d[1];                                                  \
                            ray.dir_z[l] = d[2];                                                  \
                            ray.tnear[l] = r->eps;                                                \
                            ray.tfar[l] = len;                                                    \
                            any = 1;                                                              \
                            n++;                                                                  \
                        }                                                                         \
                        if (!any)                                                                 \
                            continue;                                                             \
                        rtcOccluded##N(valid, r->scene, ctx, &ray);                               \
                        for (l = 0; l < N; l++) {                                                 \
                            uint32_t x = tx + sx + (uint32_t)(l % TW);                            \
                            uint32_t y = ty + sy + (uint32_t)(l / TW);                            \
                            if (!valid[l])                                                        \
                                continue;                                                         \
                            occ[y * W + x] = ray.tfar[l] < 0.0f;                                  \
                            no += occ[y * W + x];                                                 \
                        }                                                                         \
                    }                                                                             \
        *nrays = n;                                                                               \
        return no;                                                                                \
    }

RACE_SHADOW_N(4, 2, 2)
RACE_SHADOW_N(8, 4, 2)
RACE_SHADOW_N(16, 4, 4)

/* ---- the modes ---- */

typedef void (*race_primary_fn)(race_t *, struct RTCIntersectContext *, unsigned *, float *);
typedef uint32_t (*race_shadow_fn)(race_t *, struct RTCIntersectContext *, uint8_t *, uint32_t *);

typedef struct race_mode {
    const char *name;         /* Embree's function */
    const char *tile;         /* "single", "2x2", ... */
    int width;                /* rays per call */
    race_primary_fn primary;  /* one of primary / shadow */
    race_shadow_fn shadow;
    int native;               /* Embree's native packet width (single rays: 1) */
    double rate[2];           /* Mrays/s with the incoherent [0] and the coherent [1] flag */
    int flag;                 /* the faster: 0 incoherent, 1 coherent */
    double same;              /* % same triangle as rtcIntersect1 / occlusion as rtcOccluded1 */
    double ties;              /* primary: % same triangle or a hit at the same distance (a tie) */
    uint32_t nrays, noccluded;
    int ok;                   /* agrees with the single-ray mode */
} race_mode_t;

#define RACE_NMODES 8
static race_mode_t modes[RACE_NMODES] = {
    {"rtcIntersect1", "single", 1, embree_primary1, NULL, 1, {0, 0}, 0, 0, 0, 0, 0, 0},
    {"rtcIntersect4", "2x2", 4, embree_primary4, NULL, 0, {0, 0}, 0, 0, 0, 0, 0, 0},
    {"rtcIntersect8", "4x2", 8, embree_primary8, NULL, 0, {0, 0}, 0, 0, 0, 0, 0, 0},
    {"rtcIntersect16", "4x4", 16, embree_primary16, NULL, 0, {0, 0}, 0, 0, 0, 0, 0, 0},
    {"rtcOccluded1", "single", 1, NULL, embree_shadow1, 1, {0, 0}, 0, 0, 0, 0, 0, 0},
    {"rtcOccluded4", "2x2", 4, NULL, embree_shadow4, 0, {0, 0}, 0, 0, 0, 0, 0, 0},
    {"rtcOccluded8", "4x2", 8, NULL, embree_shadow8, 0, {0, 0}, 0, 0, 0, 0, 0, 0},
    {"rtcOccluded16", "4x4", 16, NULL, embree_shadow16, 0, {0, 0}, 0, 0, 0, 0, 0, 0},
};

static const char *const flag_name[2] = {"incoherent", "coherent"};

/* One pass of mode m; the single-ray modes write the reference arrays. */
static void run_mode(race_t *r, race_mode_t *m, struct RTCIntersectContext *ctx)
{
    if (m->primary != NULL) {
        if (m->width == 1)
            m->primary(r, ctx, r->id1, r->t1);
        else
            m->primary(r, ctx, r->idm, r->tm);
        m->nrays = r->cam.width * r->cam.height;
    } else {
        m->noccluded = m->shadow(r, ctx, m->width == 1 ? r->occ1 : r->occm, &m->nrays);
    }
}

/* Mrays/s of mode m with a context flag: one warm-up pass, then the median of runs passes. */
static double time_mode(race_t *r, race_mode_t *m, int coherent, int runs)
{
    struct RTCIntersectContext ctx;
    double times[RACE_MAX_RUNS], t0;
    int k;
    rtcInitIntersectContext(&ctx);
    ctx.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                         : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    run_mode(r, m, &ctx);
    for (k = 0; k < runs; k++) {
        t0 = lt_now_s();
        run_mode(r, m, &ctx);
        times[k] = lt_now_s() - t0;
    }
    return (double)m->nrays / median(times, runs) / 1e6;
}

/* Whether the ray of pixel p hits triangle tri at distance t (relative 1e-6; barycentrics within
 * 1e-6 of the triangle), in double: a tie with the reference's triangle at the same distance. */
static int hits_at(const race_t *r, uint32_t p, unsigned tri, float t)
{
    const float *v = r->vb + 9 * (size_t)tri;
    double e1[3], e2[3], s[3], pv[3], q[3], d[3], det, u, w, tt;
    uint32_t a;
    for (a = 0; a < 3; a++) {
        e1[a] = (double)v[3 + a] - (double)v[a];
        e2[a] = (double)v[6 + a] - (double)v[a];
        s[a] = (double)(float)r->cam.eye[a] - (double)v[a]; /* Embree's origin: the float eye */
        d[a] = (double)r->dirs[3 * p + a];
    }
    pv[0] = d[1] * e2[2] - d[2] * e2[1];
    pv[1] = d[2] * e2[0] - d[0] * e2[2];
    pv[2] = d[0] * e2[1] - d[1] * e2[0];
    det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    if (det == 0.0)
        return 0;
    u = (s[0] * pv[0] + s[1] * pv[1] + s[2] * pv[2]) / det;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    w = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
    tt = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
    return u >= -1e-6 && w >= -1e-6 && u + w <= 1.0 + 1e-6 &&
           fabs(tt - (double)t) <= 1e-6 * (double)t;
}

/* Agreement of mode m's last pass with the single-ray mode (single-ray modes: the reference). */
static void check_mode(const race_t *r, race_mode_t *m, uint32_t occ1)
{
    uint32_t i, n = r->cam.width * r->cam.height, same = 0, ties = 0, rays = 0;
    if (m->width == 1) {
        m->same = m->ties = 100.0;
        m->ok = 1;
        return;
    }
    for (i = 0; i < n; i++) {
        if (m->primary != NULL) {
            uint32_t s = r->idm[i] == r->id1[i];
            same += s;
            ties += s || (r->idm[i] != RTC_INVALID_GEOMETRY_ID &&
                          r->id1[i] != RTC_INVALID_GEOMETRY_ID &&
                          fabsf(r->tm[i] - r->t1[i]) <= 1e-6f * r->t1[i] &&
                          hits_at(r, i, r->idm[i], r->t1[i]));
        } else if (r->id1[i] != RTC_INVALID_GEOMETRY_ID) {
            same += r->occm[i] == r->occ1[i];
            rays++;
        }
    }
    if (m->primary != NULL) {
        m->same = 100.0 * same / n;
        m->ties = 100.0 * ties / n;
        m->ok = m->ties >= RACE_AGREE_MIN;
    } else {
        double d = fabs((double)m->noccluded - (double)occ1);
        m->same = m->ties = rays ? 100.0 * same / rays : 100.0;
        m->ok = m->same >= RACE_AGREE_MIN && d <= RACE_OCC_TOL * rays;
    }
}

/* ---- the machine ---- */

/* The CPU model from /proc/cpuinfo ("model name", vendor, family, model) into buf. */
static void cpu_model(char *buf, size_t n)
{
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512], name[256] = "", vendor[64] = "";
    int family = -1, model = -1;
    if (f != NULL) {
        while (fgets(line, sizeof line, f) != NULL) {
            char *c = strchr(line, ':'), *v;
            size_t len;
            if (c == NULL)
                continue;
            v = c + 1 + strspn(c + 1, " \t");
            len = strcspn(v, "\n");
            v[len] = '\0';
            if (strncmp(line, "model name", 10) == 0 && name[0] == '\0')
                snprintf(name, sizeof name, "%s", v);
            else if (strncmp(line, "vendor_id", 9) == 0 && vendor[0] == '\0')
                snprintf(vendor, sizeof vendor, "%s", v);
            else if (strncmp(line, "cpu family", 10) == 0 && family < 0)
                family = atoi(v);
            else if (strncmp(line, "model", 5) == 0 && (line[5] == '\t' || line[5] == ' ') &&
                     model < 0)
                model = atoi(v);
            else if (line[0] == '\n' && name[0] != '\0')
                break;
        }
        fclose(f);
    }
    if (name[0] == '\0')
        snprintf(name, sizeof name, "unknown CPU (no /proc/cpuinfo model name)");
    if (vendor[0] != '\0' && family >= 0 && model >= 0)
        snprintf(buf, n, "%s (%s family %d model %d)", name, vendor, family, model);
    else
        snprintf(buf, n, "%s", name);
}

static void add_word(char *buf, size_t n, const char *w)
{
    size_t len = strlen(buf);
    snprintf(buf + len, n - len, "%s%s", len ? " " : "", w);
}

/* What the CPU running this supports (x86: __builtin_cpu_supports); *widest gets the widest
 * vector extension. */
static void cpu_isa(char *buf, size_t n, const char **widest)
{
    buf[0] = '\0';
    *widest = "unknown";
#if RACE_X86 && defined(__GNUC__)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("sse4.2"))
        add_word(buf, n, "SSE4.2"), *widest = "SSE4.2";
    if (__builtin_cpu_supports("avx"))
        add_word(buf, n, "AVX"), *widest = "AVX";
    if (__builtin_cpu_supports("avx2"))
        add_word(buf, n, "AVX2"), *widest = "AVX2";
    if (__builtin_cpu_supports("fma"))
        add_word(buf, n, "FMA");
    if (__builtin_cpu_supports("avx512f"))
        add_word(buf, n, "AVX-512F"), *widest = "AVX-512";
    if (__builtin_cpu_supports("avx512bw"))
        add_word(buf, n, "AVX-512BW");
    if (__builtin_cpu_supports("avx512dq"))
        add_word(buf, n, "AVX-512DQ");
    if (__builtin_cpu_supports("avx512vl"))
        add_word(buf, n, "AVX-512VL");
#endif
    if (buf[0] == '\0')
        snprintf(buf, n, "(not detected on this architecture)");
}

/* The ISA this file (and lanetrace's host build, same flags) was compiled for. */
static void build_isa(char *buf, size_t n)
{
    buf[0] = '\0';
#if defined(__AVX512F__)
    add_word(buf, n, "AVX-512F");
#endif
#if defined(__AVX512BW__)
    add_word(buf, n, "AVX-512BW");
#endif
#if defined(__AVX512DQ__)
    add_word(buf, n, "AVX-512DQ");
#endif
#if defined(__AVX512VL__)
    add_word(buf, n, "AVX-512VL");
#endif
#if defined(__AVX2__)
    add_word(buf, n, "AVX2");
#endif
#if defined(__FMA__)
    add_word(buf, n, "FMA");
#endif
#if defined(__AVX__)
    add_word(buf, n, "AVX");
#endif
#if defined(__SSE4_2__)
    add_word(buf, n, "SSE4.2");
#endif
#if defined(__SSE2__)
    add_word(buf, n, "SSE2");
#endif
#if defined(__ARM_NEON)
    add_word(buf, n, "NEON");
#endif
    if (buf[0] == '\0')
        snprintf(buf, n, "(no vector extension macros)");
    /* the tuning (-mtune, GCC's __tune_*__ macro): on an AVX-512 Zen 4 the Makefile's choice
       of it moves the float32 packets by 1.8-1.9x (docs/results.md) */
    {
        static const char *const tunes[] = {
#if defined(__tune_znver1__)
            "znver1",
#endif
#if defined(__tune_znver2__)
            "znver2",
#endif
#if defined(__tune_znver3__)
            "znver3",
#endif
#if defined(__tune_znver4__)
            "znver4",
#endif
#if defined(__tune_znver5__)
            "znver5",
#endif
#if defined(__tune_haswell__)
            "haswell",
#endif
#if defined(__tune_skylake__)
            "skylake",
#endif
#if defined(__tune_skylake_avx512__)
            "skylake-avx512",
#endif
#if defined(__tune_cascadelake__)
            "cascadelake",
#endif
#if defined(__tune_icelake_client__)
            "icelake-client",
#endif
#if defined(__tune_icelake_server__)
            "icelake-server",
#endif
#if defined(__tune_tigerlake__)
            "tigerlake",
#endif
#if defined(__tune_rocketlake__)
            "rocketlake",
#endif
#if defined(__tune_alderlake__)
            "alderlake",
#endif
#if defined(__tune_sapphirerapids__)
            "sapphirerapids",
#endif
            NULL};
        size_t len = strlen(buf);
        snprintf(buf + len, n - len, "; tuned for %s", tunes[0] != NULL ? tunes[0] : "generic");
    }
}

/* ---- the race ---- */

/* Build a fresh scene over the shared buffers and time rtcCommitScene alone (ms). */
static RTCScene embree_build(RTCDevice dev, float *vb, unsigned *ib, uint32_t ntris, double *ms)
{
    RTCScene s = rtcNewScene(dev);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    double t0;
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vb, 0,
                               3 * sizeof(float), (size_t)ntris * 3);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, ib, 0,
                               3 * sizeof(unsigned), ntris);
    rtcCommitGeometry(g);
    rtcAttachGeometry(s, g);
    rtcReleaseGeometry(g);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_MEDIUM);
    t0 = lt_now_s();
    rtcCommitScene(s);
    *ms = 1e3 * (lt_now_s() - t0);
    return s;
}

static const char *yes_no(int v)
{
    return v ? "yes" : "no";
}

/* "rtcIntersect8 (4x2, native, coherent)" */
static const char *mode_label(const race_mode_t *m, char *buf, size_t n)
{
    snprintf(buf, n, "%s (%s, %s, %s)", m->name, m->tile, m->native ? "native" : "emulated",
             flag_name[m->flag]);
    return buf;
}

/* The fastest agreeing mode in modes[lo..hi]; NULL if none agrees. */
static const race_mode_t *best_mode(int lo, int hi)
{
    const race_mode_t *b = NULL;
    int i;
    for (i = lo; i <= hi; i++)
        if (modes[i].ok && (b == NULL || modes[i].rate[modes[i].flag] > b->rate[b->flag]))
            b = &modes[i];
    return b;
}

static double mode_rate(const race_mode_t *m)
{
    return m->rate[m->flag];
}

/* "= a x Embree best <kind> mode (...); b x mode1, c x mode2, ..." for modes[lo..hi] */
static void print_ratios(double rate, const race_mode_t *best, const char *kind, int lo, int hi)
{
    char lab[96];
    int i;
    if (best == NULL)
        printf(" = (no agreeing Embree %s mode)", kind);
    else if (lo == hi)
        printf(" = %.3fx Embree %s (%s)", rate / mode_rate(best), best->name,
               flag_name[best->flag]);
    else
        printf(" = %.3fx Embree best %s mode %s", rate / mode_rate(best), kind,
               mode_label(best, lab, sizeof lab));
    if (lo == hi)
        return;
    for (i = lo; i <= hi; i++)
        printf("%s %.3fx %s%s%s", i == lo ? ";" : ",", rate / mode_rate(&modes[i]), modes[i].name,
               modes[i].native ? "" : " (emulated)", modes[i].ok ? "" : " (DISAGREES)");
}

int main(int argc, char **argv)
{
    const char *mesh_path = "scenes/teapot.obj", *structure = "bvh", *widest, *base, *ecfg = NULL;
    uint32_t res = 1024, i;
    int runs = 5, a, k, kv = 0, status = 0;
    lt_mesh_t m;
    lt_scene_t sc;
    race_t r;
    lt_diag_t diag;
    RTCDevice dev;
    float *vb;
    unsigned *ib;
    double t0, build_ms, rebuild_ms[RACE_REBUILDS], rebuild_med, times[RACE_MAX_RUNS];
    lt_frame_t fr;
    char cpu[400], cisa[200], bisa[200], lab[96], devcfg[256];
    int native[3];
    const race_mode_t *bestp, *bests;

    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--mesh") == 0 && a + 1 < argc)
            mesh_path = argv[++a];
        else if (strcmp(argv[a], "--res") == 0 && a + 1 < argc)
            res = (uint32_t)atoi(argv[++a]);
        else if (strcmp(argv[a], "--runs") == 0 && a + 1 < argc)
            runs = atoi(argv[++a]);
        else if (strcmp(argv[a], "--structure") == 0 && a + 1 < argc)
            structure = argv[++a];
        else if (strcmp(argv[a], "--kv") == 0)
            kv = 1;
        else if (strcmp(argv[a], "--embree-config") == 0 && a + 1 < argc)
            ecfg = argv[++a];
        else {
            fprintf(stderr, "usage: embree-race [--mesh PATH] [--res N] [--runs 1..%d] "
                            "[--structure NAME] [--kv] [--embree-config CFG]\n", RACE_MAX_RUNS);
            return 2;
        }
    }
    if (res < 4 || res > 8192 || runs < 1 || runs > RACE_MAX_RUNS) {
        fprintf(stderr, "embree-race: --res 4..8192, --runs 1..%d\n", RACE_MAX_RUNS);
        return 2;
    }
#if RACE_X86
    /* flush denormals on both sides (docs/results.md, "The benchmark view") */
    /* MXCSR bits 15 (FTZ) and 6 (DAZ), set directly: the header macros trip -Wsign-conversion */
    _mm_setcsr(_mm_getcsr() | 0x8040u);
#endif
    /* one thread on both sides: lanetrace's tile loops (lt_par.h) and Embree's device */
    lt_par_set_threads(1u);
    if (lt_mesh_load(mesh_path, &m, &diag) != 0 ||
        lt_scene_prepare(&m, &sc, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return 1;
    }
    memset(&r, 0, sizeof r);
    r.sc = &sc;
    lt_camera_default(&sc, res, res, &r.cam);
    r.dirs = malloc((size_t)res * res * 3 * sizeof(float));
    r.id1 = malloc((size_t)res * res * sizeof(unsigned));
    r.t1 = malloc((size_t)res * res * sizeof(float));
    r.idm = malloc((size_t)res * res * sizeof(unsigned));
    r.tm = malloc((size_t)res * res * sizeof(float));
    r.occ1 = calloc((size_t)res * res, 1);
    r.occm = calloc((size_t)res * res, 1);
    /* Embree reads the last vertex with a 16-byte load: one float of padding */
    vb = malloc(((size_t)sc.ntris * 9 + 1) * sizeof(float));
    ib = malloc((size_t)sc.ntris * 3 * sizeof(unsigned));
    if (r.dirs == NULL || r.id1 == NULL || r.t1 == NULL || r.idm == NULL || r.tm == NULL ||
        r.occ1 == NULL || r.occm == NULL || vb == NULL || ib == NULL ||
        lt_frame_alloc(&fr, res, res, &diag) != 0) {
        fprintf(stderr, "embree-race: out of memory\n");
        return 1;
    }
    for (i = 0; i < res * res; i++) {
        double d[3];
        lt_camera_dir(&r.cam, i % res, i / res, d);
        r.dirs[3 * i] = (float)d[0];
        r.dirs[3 * i + 1] = (float)d[1];
        r.dirs[3 * i + 2] = (float)d[2];
    }
    {
        /* light at centre + 2 radius normalize(-0.5, 1.5, 0.8): the benchmark view's light */
        double l[3] = {-0.5, 1.5, 0.8}, n = sqrt(0.25 + 2.25 + 0.64);
        for (a = 0; a < 3; a++)
            r.light[a] = (float)(2.0 * sc.radius * l[a] / n);
        r.eps = (float)(1e-4 * sc.radius);
    }
    for (i = 0; i < sc.ntris * 9; i++)
        vb[i] = (float)sc.vd[i];
    vb[sc.ntris * 9] = 0.0f;
    for (i = 0; i < sc.ntris * 3; i++)
        ib[i] = i;
    r.vb = vb;

    /* the machine */
    snprintf(devcfg, sizeof devcfg, "threads=1%s%s", ecfg ? "," : "", ecfg ? ecfg : "");
    dev = rtcNewDevice(devcfg);
    if (dev == NULL) {
        fprintf(stderr, "embree-race: rtcNewDevice(\"%s\") failed (error %d)\n", devcfg,
                (int)rtcGetDeviceError(NULL));
        return 1;
    }
    native[0] = (int)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED);
    native[1] = (int)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED);
    native[2] = (int)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED);
    for (k = 0; k < RACE_NMODES; k++)
        if (modes[k].width > 1)
            modes[k].native = native[modes[k].width == 4 ? 0 : modes[k].width == 8 ? 1 : 2];
    cpu_model(cpu, sizeof cpu);
    cpu_isa(cisa, sizeof cisa, &widest);
    build_isa(bisa, sizeof bisa);
    printf("machine: %s\n", cpu);
    printf("CPU ISA: %s (widest: %s)\n", cisa, widest);
    printf("lanetrace host build compiled for: %s\n", bisa);
    printf("Embree %d.%d.%d: native ray4 %s, ray8 %s, ray16 %s (a width not native is emulated); "
           "device \"%s\"\n",
           (int)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_VERSION_MAJOR),
           (int)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_VERSION_MINOR),
           (int)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_VERSION_PATCH), yes_no(native[0]),
           yes_no(native[1]), yes_no(native[2]), devcfg);
    base = strrchr(mesh_path, '/');
    base = base != NULL ? base + 1 : mesh_path;
    if (kv) {
        printf("race: cpu %s\n", cpu);
        printf("race: cpu-isa %s : %s\n", widest, cisa);
        printf("race: build-isa %s\n", bisa);
        printf("race: embree version %d.%d.%d ray4 %d ray8 %d ray16 %d config %s\n",
               (int)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_VERSION_MAJOR),
               (int)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_VERSION_MINOR),
               (int)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_VERSION_PATCH), native[0],
               native[1], native[2], devcfg);
    }

    /* the build: rtcCommitScene alone, the device already made */
    r.scene = embree_build(dev, vb, ib, sc.ntris, &build_ms);
    for (k = 0; k < RACE_REBUILDS; k++)
        rtcReleaseScene(embree_build(dev, vb, ib, sc.ntris, &rebuild_ms[k]));
    rebuild_med = median(rebuild_ms, RACE_REBUILDS);

    printf("scene %s: %u triangles, %ux%u rays, single thread, median of %d after one warm-up "
           "pass per mode\n",
           mesh_path, sc.ntris, res, res, runs);
    printf("Embree 3 build (rtcCommitScene, quality medium): first %.2f ms, median of %d rebuilds "
           "%.2f ms\n",
           build_ms, RACE_REBUILDS, rebuild_med);
    if (kv)
        printf("race: scene name %s tris %u res %u runs %d build_ms %.2f rebuild_ms %.2f\n", base,
               sc.ntris, res, runs, build_ms, rebuild_med);

    /* every mode, both flags; the single-ray modes first (the references) */
    for (k = 0; k < RACE_NMODES; k++) {
        race_mode_t *md = &modes[k];
        double same[2], ties[2];
        int f, ok[2];
        uint32_t nocc[2];
        if (k == 0)
            printf("Embree primary rays (a mode counts if it hits the same triangle as "
                   "rtcIntersect1, or one at the same distance, on >= %.1f%% of pixels):\n",
                   RACE_AGREE_MIN);
        if (k == 4)
            printf("Embree shadow rays from rtcIntersect1's hits (a mode counts if it agrees with "
                   "rtcOccluded1 on >= %.1f%% of rays, occluded count within %.2f%%):\n",
                   RACE_AGREE_MIN, 100.0 * RACE_OCC_TOL);
        /* each flag's results are checked; the faster of the agreeing flags is kept */
        for (f = 0; f < 2; f++) {
            md->rate[f] = time_mode(&r, md, f, runs);
            check_mode(&r, md, modes[4].noccluded);
            same[f] = md->same;
            ties[f] = md->ties;
            ok[f] = md->ok;
            nocc[f] = md->noccluded;
        }
        md->flag = ok[0] == ok[1] ? md->rate[1] > md->rate[0] : ok[1];
        md->same = same[md->flag];
        md->ties = ties[md->flag];
        md->ok = ok[md->flag];
        md->noccluded = nocc[md->flag];
        if (!md->ok)
            status = 1;
        printf("  %-14s %-6s %-8s %8.2f Mrays/s (%s kept; incoherent %.2f, coherent %.2f)",
               md->name, md->tile, md->native ? "native" : "emulated", mode_rate(md),
               flag_name[md->flag], md->rate[0], md->rate[1]);
        if (md->width == 1)
            printf(" reference");
        else if (md->primary != NULL)
            printf(" same triangle as rtcIntersect1 on %.3f%% of pixels (%.3f%% with same-distance "
                   "ties): %s",
                   md->same, md->ties, md->ok ? "ok" : "DISAGREES");
        else
            printf(" same occlusion as rtcOccluded1 on %.3f%% of rays: %s", md->same,
                   md->ok ? "ok" : "DISAGREES");
        if (md->shadow != NULL)
            printf(" (%u rays, %u occluded)", md->nrays, md->noccluded);
        printf("\n");
        if (kv)
            printf("race: mode name %s tile %s native %d mrays %.3f flag %s incoherent %.3f "
                   "coherent %.3f same %.3f ties %.3f ok %d rays %u occluded %u\n",
                   md->name, md->tile, md->native, mode_rate(md), flag_name[md->flag], md->rate[0],
                   md->rate[1], md->same, md->ties, md->ok, md->nrays, md->noccluded);
    }
    bestp = best_mode(1, 3);
    bests = best_mode(4, 7);
    if (bestp != NULL)
        printf("Embree best packet mode: %s %.2f Mrays/s\n", mode_label(bestp, lab, sizeof lab),
               mode_rate(bestp));
    if (bests != NULL)
        printf("Embree best shadow mode: %s %.2f Mrays/s\n", mode_label(bests, lab, sizeof lab),
               mode_rate(bests));
    if (kv)
        printf("race: best packet %s shadow %s\n", bestp ? bestp->name : "none",
               bests ? bests->name : "none");

    for (a = 0; a < 2; a++) {
        lt_accel_t *acc;
        uint32_t same = 0, sn = 0, so = 0;
        double lp, lpc, l1 = 0.0, ls = 0.0, ls1 = 0.0, lb, lpw = 0.0, lsw = 0.0;
        uint32_t wso = 0;
        double light[3] = {r.light[0], r.light[1], r.light[2]};
        const char *name = a == 0 ? "s15.16 " : "float32";
        int chunks = strcmp(structure, "chunks") == 0;
        t0 = lt_now_s();
        acc = lt_accel_build(&sc, structure, lt_paths_find(a ? "f32" : "q16", LT_PATHS_OBJECT),
                             &diag);
        lb = 1e3 * (lt_now_s() - t0);
        if (acc == NULL) {
            fprintf(stderr, "%s\n", diag.msg);
            return 1;
        }
        printf("lanetrace %s %s: build %.1f ms, %zu bytes\n", name, structure, lb,
               lt_accel_bytes(acc));
        /* the camera's directions computed once, as Embree's rays are (r.dirs): both sides
           trace given directions; lpc below is the packets with them computed in the loop */
        if (lt_accel_set_view(acc, &r.cam, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            return 1;
        }
        /* each path: one warm-up pass, then the median of runs */
        if (!chunks) {
            for (k = -1; k < runs; k++) {
                t0 = lt_now_s();
                lt_render_primary1(&sc, acc, &r.cam, &fr, &diag);
                if (k >= 0)
                    times[k] = lt_now_s() - t0;
            }
            l1 = (double)res * res / median(times, runs) / 1e6;
        }
        for (k = -1; k < runs; k++) {
            t0 = lt_now_s();
            lt_render_primary(&sc, acc, &r.cam, &fr, NULL);
            if (k >= 0)
                times[k] = lt_now_s() - t0;
        }
        lp = (double)res * res / median(times, runs) / 1e6;
        (void)lt_accel_set_view(acc, NULL, &diag);
        for (k = -1; k < runs; k++) {
            t0 = lt_now_s();
            lt_render_primary(&sc, acc, &r.cam, &fr, NULL);
            if (k >= 0)
                times[k] = lt_now_s() - t0;
        }
        lpc = (double)res * res / median(times, runs) / 1e6;
        if (lt_accel_set_view(acc, &r.cam, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            return 1;
        }
        if (strcmp(structure, "bvh") == 0) {
            /* the same packets through the 8-wide tree (lt_accel_set_walk), then its shadow
               packets; the closest distances must be the binary walk's, the occlusion the same */
            uint32_t sw = 0, sn2 = 0, so2 = 0;
            lt_frame_t fw;
            if (lt_frame_alloc(&fw, res, res, &diag) != 0 || lt_accel_set_walk(acc, 1, &diag) != 0) {
                fprintf(stderr, "%s\n", diag.msg);
                return 1;
            }
            for (k = -1; k < runs; k++) {
                t0 = lt_now_s();
                lt_render_primary(&sc, acc, &r.cam, &fw, NULL);
                if (k >= 0)
                    times[k] = lt_now_s() - t0;
            }
            lpw = (double)res * res / median(times, runs) / 1e6;
            for (i = 0; i < res * res; i++)
                sw += fw.t[i] == fr.t[i];
            if (sw != (uint32_t)(res * res)) {
                fprintf(stderr, "embree-race: lanetrace wide-tree packets: %u of %u distances "
                                "differ from the binary walk's\n", res * res - sw, res * res);
                status = 1;
            }
            lt_frame_free(&fw);
            if (!chunks) {
                for (k = -1; k < runs; k++) {
                    t0 = lt_now_s();
                    lt_render_shadows(&sc, acc, &r.cam, &fr, light, &sn2, &so2, NULL, &diag);
                    if (k >= 0)
                        times[k] = lt_now_s() - t0;
                }
                lsw = (double)sn2 / median(times, runs) / 1e6;
                wso = so2;
            }
            (void)lt_accel_set_walk(acc, 0, &diag);
        }
        for (i = 0; i < res * res; i++) {
            int eh = r.id1[i] != RTC_INVALID_GEOMETRY_ID;
            same += eh ? (fr.id[i] == (int32_t)r.id1[i]) : (fr.id[i] < 0);
        }
        if (!chunks) {
            for (k = -1; k < runs; k++) {
                t0 = lt_now_s();
                lt_render_shadows(&sc, acc, &r.cam, &fr, light, &sn, &so, NULL, &diag);
                if (k >= 0)
                    times[k] = lt_now_s() - t0;
            }
            ls = (double)sn / median(times, runs) / 1e6;
            if (strcmp(structure, "bvh") == 0) {
                /* the same shadow rays one at a time through the wide tree (lt_bvh8.h) */
                uint32_t sn1 = 0, so1 = 0;
                for (k = -1; k < runs; k++) {
                    t0 = lt_now_s();
                    lt_render_shadows1(&sc, acc, &r.cam, &fr, light, &sn1, &so1, NULL, &diag);
                    if (k >= 0)
                        times[k] = lt_now_s() - t0;
                }
                ls1 = (double)sn1 / median(times, runs) / 1e6;
                if (sn1 != sn || so1 != so) {
                    fprintf(stderr, "embree-race: lanetrace single shadow rays %u/%u occluded, "
                                    "packets %u/%u\n", so1, sn1, so, sn);
                    status = 1;
                }
            }
            printf("lanetrace %s single rays     %8.2f Mrays/s", name, l1);
            print_ratios(l1, &modes[0], "single-ray", 0, 0);
            printf("\n");
        }
        printf("lanetrace %s 16-ray packets  %8.2f Mrays/s", name, lp);
        print_ratios(lp, bestp, "packet", 1, 3);
        printf("; same triangle as Embree on %.3f%% of pixels\n", 100.0 * same / (res * res));
        printf("lanetrace %s 16-ray packets, directions computed in the loop %8.2f Mrays/s "
               "(%.2fx of the packets above)\n", name, lpc, lpc / lp);
        if (lpw > 0.0) {
            printf("lanetrace %s 16-ray packets (wide BVH) %8.2f Mrays/s = %.2fx the binary walk",
                   name, lpw, lpw / lp);
            print_ratios(lpw, bestp, "packet", 1, 3);
            printf("\n");
        }
        if (!chunks) {
            printf("lanetrace %s shadow packets  %8.2f Mrays/s", name, ls);
            print_ratios(ls, bests, "shadow", 4, 7);
            printf(" (%u rays, %u occluded)\n", sn, so);
            if (ls1 > 0.0) {
                printf("lanetrace %s single shadow rays (wide BVH) %8.2f Mrays/s", name, ls1);
                print_ratios(ls1, bests, "shadow", 4, 7);
                printf(" (the same %u occluded)\n", so);
            }
            if (lsw > 0.0) {
                printf("lanetrace %s shadow packets (wide BVH) %8.2f Mrays/s = %.2fx the binary "
                       "walk", name, lsw, lsw / ls);
                print_ratios(lsw, bests, "shadow", 4, 7);
                printf(" (%u occluded)\n", wso);
                if (wso != so) {
                    fprintf(stderr, "embree-race: lanetrace wide-tree shadow packets %u occluded, "
                                    "binary %u\n", wso, so);
                    status = 1;
                }
            }
        }
        if (kv)
            printf("race: lanetrace path %s single %.3f packet %.3f shadow %.3f shadow1 %.3f "
                   "same %.3f packet8 %.3f shadow8 %.3f packetcomp %.3f\n",
                   a ? "f32" : "q16", l1, lp, ls, ls1, 100.0 * same / (res * res), lpw, lsw, lpc);
        lt_accel_free(acc);
    }
    if (status != 0)
        fprintf(stderr, "embree-race: an Embree mode DISAGREES with its single-ray mode (above): "
                        "its figure is left out\n");
    rtcReleaseScene(r.scene);
    rtcReleaseDevice(dev);
    lt_frame_free(&fr);
    free(r.dirs);
    free(r.id1);
    free(r.t1);
    free(r.idm);
    free(r.tm);
    free(r.occ1);
    free(r.occm);
    free(vb);
    free(ib);
    lt_scene_free(&sc);
    lt_mesh_free(&m);
    return status;
}
