/* lt_tune.h - `lanetrace tune` (docs/tune.md): the knobs of each family of kernels, one measured
 * configuration ("point": knobs, simulated cycles total and per phase, structure bytes, the
 * family's error against its reference), the in-process evaluators, the search (cheap probes at a
 * lower resolution prune dominated configurations, the survivors are measured at full size) over
 * worker processes, and the outputs. Host only; the cycles need the simulator build.
 *
 * Families and their references:
 *   object   primary rays through a structure (lt_render): numeric path q16/f32, structure
 *            chunks/bvh/bvhq/kd/grid, leaf size (bvh, bvhq, kd); against the double-precision
 *            brute-force reference (wrong triangle %, depth RMSE, max error).
 *   screen   view synthesis of a moved camera from depth layers of the mesh (lt_reproject):
 *            encoding n64/n32/f32, tracer quadtree/DDA/Hi-Z, layers 1..4, quadtree thresholds;
 *            against the target view ray traced (wrong hit/miss %, relative depth error median and
 *            99th percentile, % within 1%).
 *   shadows  soft shadows of a quad light, 16 samples per pixel (lt_softshadow): numeric path,
 *            frusta leaf size, culling set, P-Packet/P-Frusta primaries, S-Frusta/S-Packet
 *            shadows, discontinuity filter on/off; against the 256-spp reference (PSNR, % of
 *            pixels whose 8-bit shaded value differs by more than 1/255).
 */
#ifndef LT_TUNE_H
#define LT_TUNE_H

#include <stddef.h>
#include <stdint.h>

#include "io/lt_diag.h"
#include "lt/lt_cost.h"
#include "tune/lt_pareto.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LT_TUNE_OBJECT 1u
#define LT_TUNE_SCREEN 2u
#define LT_TUNE_SHADOWS 4u
#define LT_TUNE_ALL 7u
#define LT_TUNE_NFAM 3

/* "object", "screen", "shadows" by bit index (0, 1, 2). */
extern const char *const lt_tune_family_names[];

/* Quadtree threshold presets of the screen family (index = knobs.gamma). */
#define LT_TUNE_NGAMMA 3
typedef struct lt_tune_gamma {
    const char *name;              /* "fine", "default"... */
    double gamma_norm, gamma_dist; /* as fractions (s1.30 in the core) */
} lt_tune_gamma_t;
extern const lt_tune_gamma_t lt_tune_gammas[LT_TUNE_NGAMMA];

/* Culling sets of the shadows family (index = knobs.cull): the LT_FRUSTA_* flags of shadow rays. */
#define LT_TUNE_NCULL 3
extern const char *const lt_tune_cull_names[LT_TUNE_NCULL]; /* "bcrls", "bcr", "b" */
extern const unsigned lt_tune_cull_flags[LT_TUNE_NCULL];

/* One configuration. Unused knobs are 0 (-1 for leaf: the default). */
typedef struct lt_tune_knobs {
    int family;    /* 0 object, 1 screen, 2 shadows (bit index of LT_TUNE_*) */
    int machine;   /* index of lt_meter_machine_name */
    int path;      /* index into lt_paths[] */
    int structure; /* object: index of lt_render_structures; screen: lt_rp_tracer_t */
    int leaf;      /* object (bvh, bvhq, kd), shadows (frusta BVH): leaf size; 0 = default */
    int layers;    /* screen: depth layers 1..4 */
    int gamma;     /* screen (quadtree): lt_tune_gammas index */
    int prim;      /* shadows: 0 P-Packet, 1 P-Frusta */
    int shadow;    /* shadows: 0 S-Frusta, 1 S-Packet */
    int filter;    /* shadows: 1 the 4x4 discontinuity filter */
    int cull;      /* shadows: lt_tune_cull_names index */
    int spp;       /* shadows: shadow samples per pixel (4, 8, 32); 0 = 16, the default */
    int isect;     /* object: lt_sf_isects index (0 wt, the default; 1 mt; 2 wt32, s15.16) */
} lt_tune_knobs_t;

/* What one measurement gives. */
typedef struct lt_tune_meas {
    int ok;                        /* 0: the configuration failed (msg says why) */
    uint32_t res;                  /* image side measured at, pixels */
    double m[LT_M__COUNT];         /* the budget metrics (NaN: not measured by the family) */
    double maxerr;                 /* object: max depth error, scene units */
    double rel50;                  /* screen: median relative depth error, % */
    double within;                 /* screen: % of common hits within 1% */
    double off;                    /* shadows: % of pixels off by more than 1/255 */
    double phase[LT_PH__COUNT];    /* cycles per phase */
    double secs;                   /* host seconds of the measurement */
    char msg[160];
} lt_tune_meas_t;

/* A point: the knobs, its probe and its full-size measurement, and the search's verdicts. */
typedef struct lt_tune_point {
    lt_tune_knobs_t k;
    int run;              /* the measurement run it comes from (shadows: 8 points per run) */
    lt_tune_meas_t probe; /* at the probe resolution (ok = 0 when not probed) */
    lt_tune_meas_t full;  /* at full size (ok = 0 when pruned or failed) */
    int pruned;           /* dominated at the probe resolution: not measured at full size */
    int front;            /* on its family's front at full size (per machine) */
} lt_tune_point_t;

/* The input: a mesh (or a scene file naming one) or a depth EXR. */
typedef struct lt_tune_input {
    char mesh[1024];      /* mesh path ("" for a depth EXR) */
    char depth[1024];     /* depth EXR ("" for a mesh) */
    char scene[1024];     /* the scene file given ("" when a mesh or EXR was given) */
    int has_camera;       /* the scene file's camera (object family) */
    double eye[3], target[3], up[3], fov;
} lt_tune_input_t;

/* ---- configurations ------------------------------------------------------------------------ */

/* Every configuration of the families (LT_TUNE_* bits) on the machines (indices, n of them),
 * one run per object/screen point and per shadows group (8 points); *np points into *pts
 * (malloc'ed). skip_q16: leave out the s15.16 object and shadows paths (a scene it cannot
 * represent). Returns 0 or -1 (memory). */
int lt_tune_enumerate(unsigned families, const int *machines, int nmach, int skip_q16,
                      lt_tune_point_t **pts, size_t *np, lt_diag_t *diag);

/* Human text of a point's knobs: "q16 bvh leaf 4" (no family, no machine). */
void lt_tune_knobs_text(const lt_tune_knobs_t *k, char *buf, size_t n);

/* The family's objectives (minimised) of a measurement, for fronts: cycles and two errors
 * (object: wrong, rmse; screen: wrong, rel99; shadows: -psnr, off). Returns how many (3). */
int lt_tune_objectives(int family, const lt_tune_meas_t *m, double *obj);

/* ---- evaluation ---------------------------------------------------------------------------- */

typedef struct lt_tune_ctx lt_tune_ctx_t;

/* Load the input for the families at image side res: the scene, the references (object: the
 * double-precision frame; screen: the source depth layers and the ray-traced target view;
 * shadows: view, light). Returns NULL with a message. */
lt_tune_ctx_t *lt_tune_ctx_new(const lt_tune_input_t *in, unsigned families, uint32_t res,
                               lt_diag_t *diag);
void lt_tune_ctx_free(lt_tune_ctx_t *c);

/* 1 when the s15.16 path cannot represent the scene (its reason in why). */
int lt_tune_ctx_q16_refused(const lt_tune_ctx_t *c, char *why, size_t n);

/* Measure run `run` (all points of pts with .run == run) at the context's size into their probe
 * (full = 0) or full measurement. img_prefix (may be NULL): write the image of each point to
 * "<img_prefix>-<i>.png" (i = index into pts). */
void lt_tune_eval_run(lt_tune_ctx_t *c, lt_tune_point_t *pts, size_t np, int run, int full,
                      const char *img_prefix);

/* ---- the search ---------------------------------------------------------------------------- */

typedef struct lt_tune_opts {
    unsigned families;
    int machines[8], nmach;
    uint32_t res, probe_res;   /* full size and probe size (0: no probes, every point full) */
    double slack;              /* a probe prunes p only if the dominating point is this much
                                  cheaper in cycles too (0.05) */
    int jobs;                  /* worker processes */
    void (*progress)(const char *stage, size_t done, size_t total); /* may be NULL */
} lt_tune_opts_t;

typedef struct lt_tune_result {
    lt_tune_point_t *pts;
    size_t np;
    size_t probed, measured, pruned, failed, front;
    double secs_probe, secs_full;    /* wall seconds of the two stages */
    double fam_secs[LT_TUNE_NFAM];   /* measurement seconds summed per family */
    size_t fam_points[LT_TUNE_NFAM]; /* measurements per family (probes + full) */
    char q16_note[256];              /* why s15.16 was left out ("" if it was not) */
} lt_tune_result_t;

/* The measurement server (lt_tune.c): a process forked before the search that loads the contexts
 * at full and probe size (the probe one only when 0 < probe_res < res) and measures each
 * requested run in a child forked from that fixed state, so a run's cycles do not depend on which
 * worker, stage or process measures it. q16_note receives why s15.16 is left out ("" if it is
 * not). Returns NULL with a message (the input could not be loaded). */
typedef struct lt_tune_server lt_tune_server_t;
lt_tune_server_t *lt_tune_server_start(const lt_tune_input_t *in, const lt_tune_opts_t *o,
                                       char *q16_note, size_t n, lt_diag_t *diag);
void lt_tune_server_stop(lt_tune_server_t *s);

/* Measure runs[0..nruns) at full (1) or probe (0) size, at most jobs at once, into the probe or
 * full measurements of pts (which must be lt_tune_enumerate's list for the server's options);
 * img_prefix (may be NULL): each point's image to "<prefix>-<index>.png". Returns 0 or -1. */
int lt_tune_server_run(lt_tune_server_t *s, lt_tune_point_t *pts, size_t np, const int *runs,
                       size_t nruns, int full, int jobs, const char *img_prefix,
                       void (*progress)(const char *stage, size_t done, size_t total),
                       const char *stage, lt_diag_t *diag);

/* Enumerate, probe, prune, measure at full size, mark the fronts, count (r->q16_note is kept).
 * Returns 0, or -1 with a message. */
int lt_tune_search(lt_tune_server_t *srv, const lt_tune_opts_t *o, lt_tune_result_t *r,
                   lt_diag_t *diag);
void lt_tune_result_free(lt_tune_result_t *r);

/* Mark pts[i].front: non-dominated among the full measurements of its family and machine. */
void lt_tune_mark_fronts(lt_tune_point_t *pts, size_t np);

/* The counts and per-family times of r from its points. */
void lt_tune_tally(lt_tune_result_t *r);

/* ---- picks and outputs (lt_tune_out.c) ----------------------------------------------------- */

/* A family's pick under a budget, its verification and the most accurate configuration. */
typedef struct lt_tune_pick {
    int family;              /* 0 object, 1 screen, 2 shadows */
    int applies;             /* 1 when the family measures every metric of the budget */
    long pick;               /* index into pts, -1: the budget is impossible */
    long best;               /* the most accurate point (its full measurement), -1: none */
    int binding;             /* index of the binding term, -1: none binds */
    lt_tune_meas_t verify;   /* the pick re-run at full size */
    int verified;            /* 1 when the verification meets the budget */
    char scene[1100];        /* the chosen configuration as a scene file */
    char img_pick[1100], img_best[1100]; /* their images */
} lt_tune_pick_t;

/* The most accurate full measurement of a family (errors first, then cycles), or -1. */
long lt_tune_most_accurate(const lt_tune_point_t *pts, size_t np, int family);

/* Budget metrics of the full measurement of every point, rows of LT_M__COUNT, for lt_budget_*
 * (NaN rows for points without one); include[i] = full.ok && family matches. malloc'ed. */
double *lt_tune_metric_rows(const lt_tune_point_t *pts, size_t np, int family,
                            unsigned char **include);

/* The outputs in dir (created if missing): front.csv, front.json, front.md, front.png (gnuplot),
 * report.html; the picks' scene files are written by lt_tune_write_scene. title names the input.
 * Returns 0 or -1 with a message naming the file. */
typedef struct lt_tune_report {
    const char *title;        /* the input */
    const lt_tune_input_t *in;
    const lt_tune_opts_t *opts;
    const lt_tune_result_t *res;
    const lt_budget_t *budget; /* NULL: none */
    const lt_tune_pick_t *picks; /* LT_TUNE_NFAM, or NULL */
    double secs;              /* wall seconds of the whole tune */
} lt_tune_report_t;

int lt_tune_write_outputs(const char *dir, const lt_tune_report_t *rep, lt_diag_t *diag);

/* The JSON document of front.json (cJSON *, caller deletes) as a string (free()). */
char *lt_tune_json(const lt_tune_report_t *rep);

/* The chosen configuration of point p as a scene file that run/render/reproject/shadows accept
 * (docs/scene-format.md). Returns 0 or -1 with a message naming path. */
int lt_tune_write_scene(const char *path, const lt_tune_input_t *in, const lt_tune_point_t *p,
                        uint32_t res, lt_diag_t *diag);

/* A measurement as JSON (front.json's "full"/"probe" objects) and back: numbers print so that
 * they read back bit for bit (cJSON prints %.17g when %.15g does not round-trip). */
struct cJSON;
struct cJSON *lt_tune_meas_json(const lt_tune_meas_t *x);
int lt_tune_meas_from_json(const struct cJSON *o, lt_tune_meas_t *x);

/* ---- beyond one machine: plans, jobs, merges (lt_tune_dist.c) -------------------------------- */

/* What a plan fixes: the input, the families and machines (by name) and the size. Every job and
 * the merge enumerate the same configurations from it. */
typedef struct lt_tune_plan {
    char input[1024];       /* absolute path of the input as given to tune */
    char families[64];      /* --family text ("object,screen,shadows") */
    char machines[8][32];
    int nmach;
    uint32_t res;
    char q16_note[256];     /* why s15.16 was left out ("" if not) */
    size_t nruns;
} lt_tune_plan_t;

/* DIR/plan.json, DIR/jobs.txt (one command per run: a configuration - for shadows its group of
 * eight points - on one machine, for GNU parallel), DIR/tune.slurm (the same as a Slurm array job)
 * and DIR/results/. exe: the lanetrace binary (absolute). Returns 0 or -1 with a message. */
int lt_tune_write_plan(const char *dir, const char *exe, const lt_tune_plan_t *p, lt_diag_t *diag);

/* Read DIR/plan.json. Returns 0 or -1 with a message naming the file. */
int lt_tune_read_plan(const char *dir, lt_tune_plan_t *p, lt_diag_t *diag);

/* One job's result: the full measurements of run's points to path (JSON). Returns 0 or -1. */
int lt_tune_write_job(const char *path, const lt_tune_point_t *pts, size_t np, int run,
                      lt_diag_t *diag);

/* Every run-*.json of DIR/results (or of DIR itself) into the full measurements of pts (each
 * point checked against its knobs' text); seen[run] = 1 for each run read. Returns the number of
 * files read, or -1 with a message naming the file. */
long lt_tune_read_results(const char *dir, lt_tune_point_t *pts, size_t np, unsigned char *seen,
                          size_t nruns, lt_diag_t *diag);

#ifdef __cplusplus
}
#endif
#endif /* LT_TUNE_H */
