/* lt_path_ops.h - the operations a renderer needs from one numeric path, one table type per family
 * of kernels, so the renderers call path->render->xxx(...) instead of branching on the path:
 *   lt_render_ops_t  object space (lt_render: lanetrace run, render): the scene's triangles in the
 *                    path, the build and the packet, any-hit and single-ray traces of each
 *                    structure, the camera's packets, lanes from doubles and tmax as a double
 *   lt_ss_ops_t      the multi-frusta soft shadows (lt_softshadow: lanetrace shadows)
 *   lt_rp_ops_t      the screen-space tracers (lt_reproject: lanetrace reproject)
 * Each table is written once per family as a template over the path's generic names
 * (lt_render_path.inc, lt_softshadow_path.inc, lt_reproject_path.inc, instantiated with
 * lt_path_<suffix>.h in lt_render_paths.c, lt_softshadow_paths.c and lt_reproject_paths.c), and
 * the registry entry of a path (lt_paths.h) points at its tables. Path-typed data (triangles,
 * boxes, packets, per-pixel buffers) cross these tables as void pointers to the path's own core
 * types; every table member is set (NULL only where a comment says a path may lack it).
 * Host only.
 */
#ifndef LT_PATH_OPS_H
#define LT_PATH_OPS_H

#include <stddef.h>
#include <stdint.h>

#include "lt/lt.h"
#include "lt/lt_hiz.h"
#include "lt/lt_reproj.h"
#include "lt/lt_ssdda.h"
#include "io/lt_diag.h"
#include "render/lt_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- object space ------------------------------------------------------------------------- */

/* "tris" is the scene's triangle array in the path (lt_tri_<p>_t), "r" one 16-ray packet
 * (lt_ray16_<p>_t, ray16_bytes), "boxes" the chunk boxes (lt_aabb_<p>_t), "kd" / "grid" the path's
 * kd-tree / grid header (lt_kd_<p>_t, lt_grid_<p>_t: kd_bytes, grid_bytes). Closest-hit traces
 * shorten the lanes' tmax and write hit->id; any-hit traces return the occluded lanes. */
typedef struct lt_render_ops {
    const void *(*tris)(const lt_scene_t *s);
    size_t tri_bytes;
    /* 0, or -1 with a message naming `name` when the path cannot represent the prepared scene;
       NULL: it represents every scene */
    int (*scene_check)(const lt_scene_t *s, const char *name, lt_diag_t *diag);

    /* chunks: a box per LT_CHUNK triangles */
    size_t box_bytes;
    lt_status_t (*chunks_build)(const void *tris, uint32_t n, void *boxes);
    void (*chunks_trace16)(const void *tris, uint32_t n, const void *boxes, uint32_t isect,
                           void *r, lt_mask16_t k, lt_hit16_t *hit);
    /* the BVH (lt_bvh_t is the same type in every path) */
    lt_status_t (*bvh_build)(lt_bvh_t *bvh, const lt_bvh_desc_t *desc, const void *tris,
                             uint32_t n, void *arena, size_t bytes);
    void (*bvh_trace16)(const lt_bvh_t *bvh, const void *tris, void *r, lt_mask16_t k,
                        lt_hit16_t *hit);
    lt_mask16_t (*bvh_occluded16)(const lt_bvh_t *bvh, const void *tris, void *r, lt_mask16_t k);
    /* one ray from o along the unit direction d (doubles, scaled units): the hit id (-1: none) and
       its distance in *t */
    int32_t (*bvh_trace1)(const lt_bvh_t *bvh, const void *tris, const double o[3],
                          const double d[3], double *t);
    /* the wide BVH for single rays (lt_bvh8.h), collapsed from the binary tree: one ray from o
       along d (doubles) closest hit (id, *t) or any hit within (tmin, tmax) (1 = occluded) */
    lt_status_t (*bvh8_build)(lt_bvh8_t *w, const lt_bvh_t *src, const void *tris, void *mem,
                              size_t bytes, uint32_t merge);
    int32_t (*bvh8_trace1)(const lt_bvh8_t *w, const void *tris, const double o[3],
                           const double d[3], double *t);
    int (*bvh8_occluded1)(const lt_bvh8_t *w, const void *tris, const double o[3],
                          const double d[3], double tmin, double tmax);
    /* a packet through the wide tree, as bvh_trace16 / bvh_occluded16 */
    void (*bvh8_trace16)(const lt_bvh8_t *w, const void *tris, void *r, lt_mask16_t k,
                         lt_hit16_t *hit);
    lt_mask16_t (*bvh8_occluded16)(const lt_bvh8_t *w, const void *tris, void *r, lt_mask16_t k);
    /* the BVH with 16-byte quantised nodes: all four NULL where the path has none */
    lt_status_t (*bvhq_build)(lt_bvhq_t *q, const lt_bvh_t *src, void *mem, size_t bytes);
    void (*bvhq_trace16)(const lt_bvhq_t *q, const void *tris, void *r, lt_mask16_t k,
                         lt_hit16_t *hit);
    lt_mask16_t (*bvhq_occluded16)(const lt_bvhq_t *q, const void *tris, void *r, lt_mask16_t k);
    int32_t (*bvhq_trace1)(const lt_bvhq_t *q, const void *tris, const double o[3],
                           const double d[3], double *t);
    /* kd-tree; *bytes: the arena's size in, the tree's bytes out */
    size_t kd_bytes;
    lt_status_t (*kd_build)(void *kd, const void *tris, uint32_t n, const lt_kd_params_t *p,
                            void *mem, size_t *bytes);
    void (*kd_trace16)(const void *kd, void *r, lt_mask16_t k, lt_hit16_t *hit);
    lt_mask16_t (*kd_occluded16)(const void *kd, void *r, lt_mask16_t k);
    void (*kd_set_isect)(void *kd, uint32_t isect); /* the intersector of its walks (lt_isect.h) */
    /* uniform grid */
    size_t grid_bytes;
    lt_status_t (*grid_size)(const void *tris, uint32_t n, const lt_grid_params_t *p,
                             size_t *bytes);
    lt_status_t (*grid_build)(void *grid, const void *tris, uint32_t n, const lt_grid_params_t *p,
                              void *mem, size_t *bytes);
    void (*grid_trace16)(const void *grid, void *r, lt_mask16_t k, lt_hit16_t *hit);
    lt_mask16_t (*grid_occluded16)(const void *grid, void *r, lt_mask16_t k);
    void (*grid_set_isect)(void *grid, uint32_t isect);

    /* packets */
    size_t ray16_bytes;
    /* the camera's packet of the 4x4 tile at (tx, ty), set up, its directions from tab
       (lt_camera_dirs_table of c) or computed (tab NULL); returns the lanes on the image */
    lt_mask16_t (*camera_packet)(const lt_camera_t *c, const double *tab, uint32_t tx,
                                 uint32_t ty, void *r);
    /* lane i from doubles (origin and tmin, tmax in scaled units, unit direction); not set up */
    void (*ray16_lane)(void *r, int i, const double o[3], const double d[3], double tmin,
                       double tmax);
    void (*ray16_tmin)(void *r, int i, double tmin);
    void (*ray16_setup)(void *r);
    /* lane i's tmax (the hit distance after a closest-hit trace) in scaled units */
    double (*ray16_t)(const void *r, int i);
} lt_render_ops_t;

extern const lt_render_ops_t lt_render_ops_q16, lt_render_ops_f32;

/* ---- multi-frusta soft shadows ------------------------------------------------------------ */

struct lt_softshadow;

/* The stages of lt_softshadow's renderer that work in the path's lanes; everything else
 * (loops over tiles, counts, audits in double, hashes, images) is written once in
 * lt_softshadow.c over its per-pixel buffers, whose elements are 4 bytes in every path (s15.16 /
 * s1.30 raw or binary32: lt_softshadow_int.h). A path serving the frusta family serves the object
 * family too: its BVHs are built and its triangles found through the path's render ops. "r1" is
 * a single ray (lt_ray1_<p>_t, ray1_bytes). */
typedef struct lt_ss_ops {
    size_t table_bytes, vtable_bytes; /* lt_frusta_table_<p>_t, lt_frusta_vtable_<p>_t */
    /* one worker's packets and frusta (scr below: the stages' scratch, 64-byte aligned; each
       worker of lt_par.h has its own, so the stages run on every core) */
    size_t scratch_bytes;
    /* the path's data from the scene's and the light's doubles: triangle normals, the light's
       centre m and emitting normal nl, its sample table, the primary view table; 0, or -1 with a
       message */
    int (*init)(struct lt_softshadow *ss, const double m[3], const double nl[3],
                lt_diag_t *diag);
    /* P-Packet of the 4x4 tile at (tx, ty) / P-Frusta of the 16x16 block at (bx, by), each with
       its shading and its answer kept per pixel (only the tile's / block's pixels are written);
       both return the primary rays traced */
    uint32_t (*primary_tile)(struct lt_softshadow *ss, void *scr, uint32_t tx, uint32_t ty);
    uint32_t (*primary_block)(struct lt_softshadow *ss, void *scr, uint32_t bx, uint32_t by);
    /* S-Frusta of the 4x4 tile at (tx, ty), pass 0 (pixel lane i: set i) or 1 (spp 32: set
       i ^ 8); S-Packet of pixel q's samples of set `set` that are in `samples` (bit j: sample j;
       returns the occluded ones) */
    void (*shadows_tile)(struct lt_softshadow *ss, void *scr, uint32_t tx, uint32_t ty,
                         unsigned pass);
    uint16_t (*packet)(const struct lt_softshadow *ss, void *scr, size_t q, unsigned set,
                       uint16_t samples);
    /* E = G x visible fraction of the tile's pixels from stage `which`'s occlusion (the lanes;
       the caller charges the loads and stores and enters SHADE) */
    void (*shade_tile)(struct lt_softshadow *ss, uint32_t tx, uint32_t ty, int which);
    /* the 4x4 discontinuity filter of E (ref 0) or of the reference's E (ref 1) */
    void (*filter)(struct lt_softshadow *ss, int ref);
    /* pixel q's normal as one word of lt_ss_primary_hash */
    uint32_t (*normal_word)(const struct lt_softshadow *ss, size_t q);
    /* the audits' single rays: sample j of set `set` from pixel q's origin / pixel (x, y)'s
       primary ray into r1, and in doubles (origin, direction, interval); 0, or -1 when the core
       refuses it */
    size_t ray1_bytes;
    int (*shadow_ray1)(const struct lt_softshadow *ss, size_t q, unsigned set, unsigned j,
                       void *r1, double o[3], double d[3], double *tmin, double *tmax);
    int (*primary_ray1)(const struct lt_softshadow *ss, uint32_t x, uint32_t y, void *r1,
                        double o[3], double d[3]);
    /* triangle i against r1 by the single-ray kernel (with cull: front faces only): 1 and the
       distance in *t for a hit, else 0; the triangle's vertices as the kernel sees them */
    int (*tri1)(const struct lt_softshadow *ss, const void *r1, uint32_t i, int cull, double *t);
    void (*tri_vertices)(const struct lt_softshadow *ss, uint32_t i, double v[9]);
} lt_ss_ops_t;

extern const lt_ss_ops_t lt_ss_ops_q16, lt_ss_ops_f32;

/* ---- screen space ------------------------------------------------------------------------- */

/* One traced lane of a reprojected packet, in doubles: its result and its segment. */
typedef struct lt_rp_lane {
    int status, layer;              /* LT_QT_*, the layer of the hit or occlusion */
    double t, w;                    /* hit parameter along the segment (0..1), inverse depth there */
    uint32_t nodes, aabb, planes;   /* nodes (pixels, cells) visited, box and plane tests */
    double x, y, w0, dx, dy, dw;    /* the segment: start (pixels, inverse depth) and extent */
} lt_rp_lane_t;

/* "w" is the w buffer in the path's format (w_bytes per sample; w_bytes 0: the path computes in
 * float32, its w buffer is the float copy itself), "map" the path's reprojection mapping
 * (lt_reproj_<p>_t, map_bytes), "r" / "h" a packet of segments and its results (lt_qray16_<p>_t,
 * lt_qhit16_<p>_t). The quadtree's node encoding and the DDA's and Hi-Z's w format come with the
 * descriptors (the registry's qt_enc and ssb_enc). */
typedef struct lt_rp_ops {
    size_t w_bytes;
    /* w = 2^e / z of n depths into w and its float value into wf (w may be wf when w_bytes is 0) */
    void (*w_from_depth)(const float *z, size_t n, int e, void *w, float *wf);
    lt_status_t (*qt_build)(lt_qt_t *qt, const lt_qt_desc_t *d, const lt_qt_params_t *p,
                            const void *w, void *arena, size_t *bytes);
    lt_status_t (*dda_init)(lt_ssdda_t *dda, const lt_ssb_desc_t *d, const lt_ssb_params_t *p,
                            const void *w);
    lt_status_t (*hiz_build)(lt_hiz_t *hz, const lt_ssb_desc_t *d, const lt_ssb_params_t *p,
                             const void *w, void *arena, size_t *bytes);
    /* the quadtree's plane nodes (not boxes) among its first `nodes` nodes, in this encoding */
    uint64_t (*qt_planes)(const void *arena, uint64_t nodes);
    size_t map_bytes, ray_bytes, hit_bytes;
    /* the mapping of a camera pair (lt_reproj_setup's result in this path) */
    lt_status_t (*setup)(const lt_reproj_cam_t *src, const lt_reproj_cam_t *dst,
                         const lt_reproj_opts_t *o, void *map);
    /* the segments of the target's 4x4 tile at (tx, ty); *k in: lanes on the image, out: lanes
       with a segment */
    void (*rays16)(const void *map, uint32_t tx, uint32_t ty, void *r, lt_mask16_t *k);
    void (*qt_trace16)(const lt_qt_t *qt, const void *r, lt_mask16_t k, uint32_t max_steps,
                       void *h);
    /* the same lanes traced one ray at a time (lt_qt_trace1_q30), the same results; NULL where
       the path has no single-ray walk (float32) */
    void (*qt_trace1)(const lt_qt_t *qt, const void *r, lt_mask16_t k, uint32_t max_steps,
                      void *h);
    void (*dda_trace16)(const lt_ssdda_t *dda, const void *r, lt_mask16_t k, uint32_t max_steps,
                        void *h);
    void (*hiz_trace16)(const lt_hiz_t *hz, const void *r, lt_mask16_t k, uint32_t max_steps,
                        void *h);
    void (*lane)(const void *r, const void *h, int l, lt_rp_lane_t *out);
} lt_rp_ops_t;

extern const lt_rp_ops_t lt_rp_ops_n64, lt_rp_ops_n32, lt_rp_ops_f32;

#ifdef __cplusplus
}
#endif
#endif /* LT_PATH_OPS_H */
