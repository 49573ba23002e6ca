/* lt_reproject.h - view synthesis by screen-space ray tracing (Widmer et al. 2015 [Widmer15],
 * section 5): a depth image (one or more layers, optional colour) seen by a source pinhole camera
 * is turned into the screen-space quadtree (lt_qt.h), every pixel of a target camera is traced
 * through it as a reprojected segment (lt_reproj.h), hits fetch the source colour, and holes
 * (disocclusions, views outside the source, step bound) are filled by a background-biased pull-push
 * inpainting.
 * Per-pixel traversal steps and (sim build) simulated cycles are recorded. Host only (malloc,
 * double); docs/reproject.md is the reference.
 */
#ifndef LT_REPROJECT_H
#define LT_REPROJECT_H

#include <stddef.h>
#include <stdint.h>
#include "lt/lt_hiz.h"
#include "lt/lt_reproj.h"
#include "io/lt_diag.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LT_RP_MAX_LAYERS 16

/* Per-pixel class of the result (the EXR "hole" channel holds these values). */
#define LT_RP_HIT 0        /* a surface of the source: colour fetched */
#define LT_RP_BACKGROUND 1 /* the ray reached infinity over source background (holes): the source's
                              background colour at the vanishing point, depth +inf; not a hole */
#define LT_RP_DISOCCLUDED 2 /* went behind the deepest layer (LT_QT_OCCLUDED): unknown, inpainted */
#define LT_RP_OUTSIDE 3    /* the ray leaves or never enters the source view: inpainted */
#define LT_RP_UNKNOWN 4    /* the traversal step bound was reached: inpainted */
#define LT_RP_CLASSES 5

/* The screen-space tracer that walks the reprojected segments (same rays, same result codes). */
typedef enum lt_rp_tracer {
    LT_RP_QUADTREE = 0, /* the adaptive quadtree (lt_qt.h), the node format of lt_rp_opts.enc */
    LT_RP_DDA = 1,      /* perspective-correct DDA (lt_ssdda.h), McGuire & Mara: s1.30 for n64 and
                           n32, float32 for f32 */
    LT_RP_HIZ = 2       /* min/max Hi-Z pyramid (lt_hiz.h), Uludag: the same numeric paths */
} lt_rp_tracer_t;

/* The source view. */
typedef struct lt_rp_source {
    uint32_t width, height, layers; /* pixels; 1..LT_RP_MAX_LAYERS layers, front to back */
    const float *z;                 /* layers x height x width z-depths (along the optical axis,
                                       world units); NaN, +-inf and <= 0 are background */
    const float *rgb[LT_RP_MAX_LAYERS]; /* per layer height x width x 3 linear colour, or NULL:
                                           such a layer is shown as grey = w (near bright) */
    lt_reproj_cam_t cam;            /* the source camera (cam.width/height = width/height) */
} lt_rp_source_t;

typedef struct lt_rp_opts {
    lt_qt_enc_t enc;      /* the quadtree node encoding: LT_QT_N64, LT_QT_N32 (s1.30 rays) or
                             LT_QT_F32 (float32 rays); its registry entry (lt_paths_of_qt_enc)
                             gives the numeric path's screen ops */
    int bilinear;         /* 1: depth-aware bilinear colour fetch (default), 0: nearest pixel */
    int inpaint;          /* 1: fill holes (default); 0: holes stay black with depth NaN */
    uint32_t max_steps;   /* nodes per lane per layer, 0 = lt_qt_default_steps */
    double z_near_dst;    /* target near plane (0 = rays start at the target camera centre) */
    lt_qt_params_t params; /* quadtree build thresholds (lt_qt_params_default; docs/quadtree.md) */
    lt_rp_tracer_t tracer; /* LT_RP_QUADTREE (default), LT_RP_DDA or LT_RP_HIZ */
    int single;           /* 1: the quadtree traced one ray at a time (lt_qt_trace1_q30, s1.30
                             paths only: the same results, scalar costs); 0: packets (default) */
    lt_ssb_params_t ssb;  /* the DDA's and Hi-Z's surface thickness (lt_ssb_params_default) */
    void (*progress)(double done); /* may be NULL */
} lt_rp_opts_t;

/* Fill o with the defaults above (n64, bilinear, inpaint, lt_qt_params_default, the quadtree,
 * lt_ssb_params_default). */
void lt_rp_opts_default(lt_rp_opts_t *o);

/* The walk of `--walk auto` (lanetrace reproject, lanetrace tune): 1, single rays, for the
 * quadtree of an s1.30 node format (n64, n32) on a machine model narrower than 16 lanes (the MCU
 * models: what their firmware runs, docs/firmware.md); else 0, packets (also in a build without
 * machine models). why (may be NULL) receives the reason in a few words. */
int lt_rp_auto_single(const char *machine, lt_qt_enc_t enc, lt_rp_tracer_t tracer, char *why,
                      size_t why_len);

/* Figures of one run; cycles are 0 outside the sim build. */
typedef struct lt_rp_stats {
    uint64_t pixels;                    /* target pixels */
    uint64_t cls[LT_RP_CLASSES];        /* pixels per class */
    uint64_t rays;                      /* traced lanes (segment not empty) */
    uint64_t nodes, aabb, planes;       /* sums over traced lanes */
    uint32_t nodes_max, aabb_max, planes_max;
    uint64_t packets;                   /* trace calls */
    double zref;                        /* z_ref = 2^e used for w */
    size_t qt_bytes;                    /* the tracer's arena: quadtree, Hi-Z levels 1.. (0: DDA) */
    uint64_t qt_planes, qt_nodes;       /* plane nodes / all nodes of the quadtree (0 otherwise) */
    /* simulated cycles (sim build): the cycle model's phase totals over the whole call, the
       figures of its report: BUILD, SETUP, TRAVERSE + INTERSECT, the rest (OTHER), their sum */
    uint64_t cyc_build, cyc_setup, cyc_trace, cyc_other, cyc_total;
    uint64_t lanes_on, lane_ops;        /* utilisation events over the whole call (sim build) */
    double t_build, t_trace, t_shade, t_inpaint; /* wall seconds */
} lt_rp_stats_t;

/* The synthesised view. Free with lt_rp_result_free. */
typedef struct lt_rp_result {
    uint32_t width, height;
    float *rgb;    /* width x height x 3, linear */
    float *z;      /* target z-depth; +inf background; inpainted pixels carry the filled depth */
    uint8_t *cls;  /* LT_RP_* per pixel (before inpainting) */
    float *steps;  /* nodes (quadtree), pixels (DDA) or cells (Hi-Z) visited per pixel (all
                      layers); 0 for untraced pixels */
    float *cycles; /* simulated cycles per pixel: its packet's setup + trace cycles over the
                      packet's lanes on the image (sim build; 0 otherwise) */
    float *sx, *sy; /* source position of each hit, pixels (NaN elsewhere) */
    int32_t *layer; /* layer of each hit, -1 elsewhere */
    lt_rp_stats_t st;
} lt_rp_result_t;

/* Synthesise the view of camera dst (dst->width x dst->height) from src. Returns 0, or -1 with a
 * message naming the input and the limit in diag (bad camera, image too large, no valid depth,
 * out of memory, layers not front to back is not checked: layer k+1 must lie behind layer k). */
int lt_rp_run(const lt_rp_source_t *src, const lt_reproj_cam_t *dst, const lt_rp_opts_t *o,
              lt_rp_result_t *res, lt_diag_t *diag);
void lt_rp_result_free(lt_rp_result_t *r);

/* Background-biased pull-push inpainting of rgb (w x h x 3) and z (w x h) where valid[i] == 0:
 * pull: each coarser pixel averages its valid children within 10% of their farthest depth
 * (+inf counts as farthest); push: each hole takes the bilinear mix of the four nearest coarser
 * pixels, again restricted to those within 10% of their farthest depth. Returns 0 or -1 (memory,
 * or no valid pixel: then nothing changes). */
int lt_rp_inpaint(float *rgb, float *z, const uint8_t *valid, uint32_t w, uint32_t h);

/* A default camera for a depth image without one: horizontal field of view hfov_deg over the
 * display window (disp_w x disp_h, 0 = the image itself), principal point at the display window's
 * centre expressed in the image's pixels (the image's top-left pixel sits at (ox, oy) of the
 * display window), at the origin looking down +z, y down. */
void lt_rp_cam_default(uint32_t w, uint32_t h, int32_t disp_w, int32_t disp_h, int32_t ox,
                       int32_t oy, double hfov_deg, lt_reproj_cam_t *c);

/* dst = src moved by move (in src camera coordinates: x right, y down, z forward) and then
 * rotated by yaw (about the camera y axis, + turns right), pitch (about x, + tilts up) and roll
 * (about z), degrees; width/height/intrinsics copied. */
void lt_rp_cam_move(const lt_reproj_cam_t *src, const double move[3], const double rot_deg[3],
                    lt_reproj_cam_t *dst);

/* Source position (x, y) in pixels and inverse depth w (= z_ref / z) -> depth of that point in
 * camera dst. */
double lt_rp_target_depth(const lt_reproj_cam_t *src, const lt_reproj_cam_t *dst, double zref,
                          double x, double y, double w);

/* Accuracy of a synthesised view against ground truth: the target view's z-depths as the
 * object-space tracer sees them (ztrue: width x height, +inf where the ray misses the scene).
 * A pixel the reprojection *knows* (LT_RP_HIT, LT_RP_BACKGROUND) is a wrong hit when it claims a
 * surface the truth does not have (spurious) or background where the truth hits (missed); where
 * both hit, the depth error e = z - z_true and its relative size |e| / z_true are measured and
 * the pixel is within tolerance when |e| <= tol * z_true. Inpainted pixels (disoccluded,
 * outside, step bound) are counted apart: their filled depth is a guess, not a trace. */
typedef struct lt_rp_truth {
    double tol;                 /* relative depth tolerance used */
    uint64_t pixels;            /* compared pixels (width x height) */
    uint64_t truth_hit;         /* pixels where the ground truth hits a surface */
    uint64_t known;             /* LT_RP_HIT + LT_RP_BACKGROUND pixels */
    uint64_t spurious, missed;  /* wrong hits among the known pixels */
    uint64_t both_hit, within;  /* LT_RP_HIT pixels whose truth hits; of those within tol */
    double rmse, rel_rmse, max_rel; /* over both_hit: absolute (world units) and relative */
    double rel_p50, rel_p99;    /* nearest-rank median and 99th percentile of the
                                   relative error over both_hit */
    uint64_t inpainted;         /* LT_RP_DISOCCLUDED + LT_RP_OUTSIDE + LT_RP_UNKNOWN pixels */
    uint64_t ip_unfilled;       /* of those without a filled depth (NaN: --no-inpaint) */
    uint64_t ip_wrong;          /* filled hit where the truth misses, or the reverse */
    uint64_t ip_both, ip_within; /* filled and true surface; of those within tol */
    double ip_rel_rmse;         /* over ip_both */
} lt_rp_truth_t;

/* Compare res against ztrue (res->width x res->height). relerr (may be NULL) receives
 * |e| / z_true per pixel where both the result (any class, after inpainting) and the truth have a
 * surface, NaN elsewhere. Returns 0, or -1 when tol is not a finite value in (0, 1] or memory
 * for the percentiles runs out. */
int lt_rp_truth_compare(const lt_rp_result_t *res, const float *ztrue, double tol,
                        lt_rp_truth_t *t, float *relerr);

/* The median (element m / 2 of the sorted values) of the valid (finite, > 0) depths z[0..n), or 0
 * when there is none or memory runs out (reproject's --move-rel unit, fwblob's). */
double lt_rp_median_depth(const float *z, size_t n);

#ifdef __cplusplus
}
#endif
#endif /* LT_REPROJECT_H */
