/* lt_render.h - trace one frame of primary rays through a structure in one numeric path, as
 * 16-ray packets over 4x4 tiles, and compare frames with the double reference. Used by the CLI,
 * benchmarks and tests; the same code runs in the host and sim builds (in sim builds it also
 * records simulated cycles per pixel). Host only.
 */
#ifndef LT_RENDER_H
#define LT_RENDER_H

#include "io/lt_diag.h"
#include "render/lt_paths.h"
#include "render/lt_scene.h"

/* Per-pixel results, width * height each, row-major, y down. */
typedef struct lt_frame {
    uint32_t width, height;
    int32_t *id;   /* hit triangle id, -1 = none */
    double *t;     /* hit distance in scaled scene units (meaningless where id < 0) */
    float *cost;   /* simulated cycles per pixel (the packet's cycles / its active lanes); 0 in
                      non-sim builds */
    float *steps;  /* traversal steps per pixel: nodes (or chunks) its packet visited; 0 in
                      non-sim builds */
    int heat;      /* 1: fill cost and steps (run --heatmap; each packet reads the simulator's
                      counters twice); 0 (lt_frame_alloc's default): they stay 0 */
} lt_frame_t;

/* Allocate (0) or fail (-1, message). */
int lt_frame_alloc(lt_frame_t *f, uint32_t w, uint32_t h, lt_diag_t *diag);
void lt_frame_free(lt_frame_t *f);

/* The prepared acceleration structure for one numeric path (an entry of lt_paths serving
 * LT_PATHS_OBJECT; every call goes through its render ops). Opaque to callers. */
typedef struct lt_accel lt_accel_t;

/* Names of the structures lt_accel_build knows (NULL-terminated): "chunks" (a box per 16
 * triangles), "bvh" (binned SAH, 32-byte nodes), "bvhq" (the same tree with 16-byte quantised
 * nodes, s15.16 only). */
extern const char *const lt_render_structures[];

/* Build `structure` over the scene for a path. Returns NULL with a message on error (also for a
 * path without object-space operations). */
lt_accel_t *lt_accel_build(const lt_scene_t *s, const char *structure,
                           const lt_path_info_t *path, lt_diag_t *diag);

/* Build knobs of lt_accel_build_ex (0 = the structure's default): leaf = the BVH's max_leaf
 * (bvh 1..LT_BVH_MAX_LEAF, bvhq 1..LT_BVHQ_MAX_LEAF; min_leaf = leaf / 2, as the frusta BVH)
 * or the kd-tree's leaf_tris (>= 1); chunks and grid have no leaf size (a non-zero leaf is refused). */
typedef struct lt_accel_params {
    uint32_t leaf;
} lt_accel_params_t;

/* lt_accel_build with knobs (p may be NULL: the defaults). */
lt_accel_t *lt_accel_build_ex(const lt_scene_t *s, const char *structure,
                              const lt_path_info_t *path, const lt_accel_params_t *p,
                              lt_diag_t *diag);
void lt_accel_free(lt_accel_t *a);

/* Bytes of the built structure (nodes, indices, boxes; not the triangles). */
size_t lt_accel_bytes(const lt_accel_t *a);

/* The ray/triangle intersector of every walk over the structure (lt_isect.h): LT_ISECT_WT,
 * watertight, what lt_accel_build sets, LT_ISECT_MT, Moller-Trumbore, or (s15.16)
 * LT_ISECT_WT32_G(g), the watertight test on the grid 2^g. */
void lt_accel_set_isect(lt_accel_t *a, uint32_t isect);

/* The same by name: "wt", "mt" or "wt32" (s15.16 only: the grid lt_wt32_shift_q16 picks for the
 * scene's triangles, written to *g when g != NULL). Returns 0, or -1 with the reason in diag (an
 * unknown name, wt32 on a float32 structure). */
int lt_accel_set_isect_name(lt_accel_t *a, const char *name, uint32_t *g, lt_diag_t *diag);

/* The walk of the 16-ray packets (primary, shadow and peel) over bvh: wide != 0, the 8-wide tree
 * of the single rays (lt_bvh8_trace16: one frustum test per node for the packet; collapsed here
 * if not yet, its memory outside lt_accel_bytes), 0 the binary tree (what lt_accel_build sets;
 * the walk the machine models' packets are measured on). Other structures: no effect. The
 * closest distances are the same either way; an exact tie between coplanar faces may name the
 * other face. Returns 0, or -1 with a message (no memory for the wide tree). */
int lt_accel_set_walk(lt_accel_t *a, int wide, lt_diag_t *diag);

/* The directions of camera c computed once (lt_camera_dirs_table, 24 bytes per pixel, outside
 * lt_accel_bytes): every later render call on a whose camera equals *c field by field reads its
 * tiles' directions from the table instead of computing them (the same values, so the same
 * results); other cameras compute as before. For benchmarks that trace one view many times
 * (embree-race, whose Embree side traces precomputed directions). c NULL drops the table.
 * Returns 0, or -1 with a message (out of memory). */
int lt_accel_set_view(lt_accel_t *a, const lt_camera_t *c, lt_diag_t *diag);

/* Trace all primary rays of the camera into f (allocated to the camera size). progress (may be
 * NULL) is called with the fraction done. */
void lt_render_primary(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                       lt_frame_t *f, void (*progress)(double done));

/* The same with one ray per pixel: the scalar single-ray traversal for bvh (through its wide
 * 8-child tree, lt_bvh8.h, collapsed on the first call; the closest distance is the packets', an
 * exact tie between coplanar faces may name the other face) and bvhq; the kd-tree,
 * grid and chunks have no scalar kernel and trace each ray alone through their packet kernel
 * with a one-lane mask. Returns 0, or -1 with a message (no memory for the wide tree). */
int lt_render_primary1(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                       lt_frame_t *f, lt_diag_t *diag);

/* Shadow rays (16-ray packets, any hit) from every primary hit of f to a point light given in
 * scaled units; *nrays rays, *noccluded of them blocked; occluded (may be NULL) gets 0/1 per pixel.
 * BVH structures only. Returns 0, or -1 with a message. */
int lt_render_shadows(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                      const lt_frame_t *f, const double light[3], uint32_t *nrays,
                      uint32_t *noccluded, uint8_t *occluded, lt_diag_t *diag);

/* The same shadow rays, each alone through the wide BVH (lt_bvh8.h; structure bvh only, collapsed
 * on first use), any hit with an early exit per ray: the same occlusion bits as the packets.
 * Returns 0, or -1 with a message. */
int lt_render_shadows1(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                       const lt_frame_t *f, const double light[3], uint32_t *nrays,
                       uint32_t *noccluded, uint8_t *occluded, lt_diag_t *diag);

/* The next depth layer: for every pixel that hit in prev, the first surface strictly beyond it
 * (tmin = the previous distance); pixels without a previous hit get id -1. Coplanar duplicates
 * at exactly the previous distance are skipped. BVH structures only. Returns 0 or -1. */
int lt_render_peel(const lt_scene_t *s, const lt_accel_t *a, const lt_camera_t *c,
                   const lt_frame_t *prev, lt_frame_t *next, lt_diag_t *diag);

/* The double-precision reference frame (brute force, independent code). */
void lt_render_reference(const lt_scene_t *s, const lt_camera_t *c, lt_frame_t *f,
                         void (*progress)(double done));

/* Accuracy of a frame against the reference. */
typedef struct lt_accuracy {
    uint32_t pixels, same_id, both_hit, within_tol;
    double rmse, max_err, tol;
} lt_accuracy_t;

void lt_frame_compare(const lt_frame_t *a, const lt_frame_t *ref, double tol, lt_accuracy_t *acc);

/* FNV-1a over ids and distance bits: equal across host and sim builds. */
uint32_t lt_frame_hash(const lt_frame_t *f);

#endif /* LT_RENDER_H */
