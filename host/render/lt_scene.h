/* lt_scene.h - a mesh made ready for the core: placed and scaled into the fixed-point range,
 * quantised to s15.16 and converted to float32, a pinhole camera that generates 16-ray packets over
 * 4x4 pixel tiles, and an independent double-precision reference tracer for error figures.
 * Host only.
 */
#ifndef LT_SCENE_H
#define LT_SCENE_H

#include "lt/lt.h"
#include "io/lt_diag.h"
#include "io/lt_mesh.h"

typedef struct lt_scene {
    uint32_t ntris;
    lt_tri_q16_t *tq;      /* s15.16 triangles (edges from quantised vertices) */
    lt_tri_f32_t *tf;      /* float32 triangles of the same scaled geometry, vertices on the grid
                              fgrid (exact edges: watertight) */
    double *vd;            /* 9 doubles per triangle: scaled, unquantised (the reference) */
    double center[3];      /* file units: the origin of the scaled space */
    double scale;          /* scaled = (file - center) * scale; a power of two */
    double radius;         /* half the bounding-box diagonal, scaled units */
    double fgrid;          /* the float32 vertices' grid (a power of two, scaled units): their
                              edges are exact, so fl(v0 + e1) rebuilds v1 bit for bit */
    uint32_t collapsed_q16; /* triangles of non-zero area whose s15.16 vertices span zero area */
    uint32_t nonzero;       /* triangles of non-zero area (double, file geometry) */
    double min_edge;        /* shortest non-zero edge of a non-degenerate triangle, scaled units */
} lt_scene_t;

/* The s15.16 path cannot represent a scene when more than this many parts per million of its
 * non-degenerate triangles collapse to zero area on quantisation (they would vanish: holes in
 * the image, silently). 1000 ppm = 0.1%. */
#define LT_SCENE_MAX_COLLAPSED_PPM 1000u

/* The scene radius is mapped to at most 2^(LT_CFG_GEOM_MAX_LOG2 - 2) units so that a camera at up
 * to 3x the radius from the centre stays within the core's geometry bound. */
#define LT_SCENE_RADIUS_LOG2 (LT_CFG_GEOM_MAX_LOG2 - 2)

/* Returns 0, or -1 with a message (empty or non-finite bounds, out of memory). Also counts the
 * triangles that s15.16 quantisation collapses (collapsed_q16) for lt_scene_check_q16. */
int lt_scene_prepare(const lt_mesh_t *m, lt_scene_t *s, lt_diag_t *diag);

/* Whether the s15.16 path can represent the prepared scene: 0, or -1 with a message naming
 * `name`, the collapsed count and LT_SCENE_MAX_COLLAPSED_PPM (the scene's dynamic range exceeds
 * s15.16: its extent is mapped to 2^LT_SCENE_RADIUS_LOG2 units and its smallest features fall
 * below 2^-16 units). The float32 path has no such limit. */
int lt_scene_check_q16(const lt_scene_t *s, const char *name, lt_diag_t *diag);
void lt_scene_free(lt_scene_t *s);

typedef struct lt_camera {
    double eye[3];           /* scaled units */
    double fwd[3], right[3], up[3];
    double tan_half_fov;
    uint32_t width, height;
} lt_camera_t;

/* The benchmark view (docs/results.md, "The benchmark view"): looking at the bounding-box centre
 * from direction normalize(0.45, 0.35, 1.0) at distance radius / tan(20 deg), 40 deg vertical field
 * of view, +y up. */
void lt_camera_default(const lt_scene_t *s, uint32_t width, uint32_t height, lt_camera_t *c);

/* An explicit pinhole camera given in mesh file units (converted to the scaled space).
 * Returns 0, or -1 with a message when the eye lies outside the core's geometry bound, the
 * target equals the eye, or the view direction is parallel to up (the scene file's rules). */
int lt_camera_look(const lt_scene_t *s, const double eye[3], const double target[3],
                   const double up[3], double fov_y_deg, uint32_t width, uint32_t height,
                   lt_camera_t *c, lt_diag_t *diag);

/* The look-at basis: fwd = normalize(dir), right = normalize(fwd x up), up' = right x fwd into
 * c->fwd, c->right, c->up (the rest of c untouched). dir and up must not be parallel. */
void lt_camera_basis(lt_camera_t *c, const double dir[3], const double up[3]);

/* The point light in scaled units: pos (mesh file units) placed like the mesh, or with pos NULL
 * the default, centre + 2 radius normalize(-0.5, 1.5, 0.8) (render, pack). */
void lt_scene_light(const lt_scene_t *s, const double *pos, double out[3]);

/* Unit direction of the ray through the centre of pixel (x, y) (y down). */
void lt_camera_dir(const lt_camera_t *c, uint32_t x, uint32_t y, double d[3]);

/* The directions of the 16 pixels of the 4x4 tile at (tx, ty) (lane i = pixel (tx + i % 4,
 * ty + i / 4)), each bit-identical to lt_camera_dir's, computed 16 at a time; lanes off the image
 * get (0, 0, 1). Returns the on-image lanes. */
unsigned lt_camera_tile_dirs(const lt_camera_t *c, uint32_t tx, uint32_t ty, double dx[16],
                             double dy[16], double dz[16]);

/* Every 4x4 tile's lt_camera_tile_dirs computed once, for tracing one view many times
 * (benchmarks): tile-major (tile (tx, ty) at ((ty / 4) * ((width + 3) / 4) + tx / 4) * 48), dx[16],
 * dy[16], dz[16] per tile. Returns NULL when out of memory; free() it. */
double *lt_camera_dirs_table(const lt_camera_t *c);

/* lt_camera_tile_dirs from such a table of c (tab NULL: computed): the same values. */
unsigned lt_camera_tile_dirs_tab(const lt_camera_t *c, const double *tab, uint32_t tx,
                                 uint32_t ty, double dx[16], double dy[16], double dz[16]);

/* Packets of the 4x4 tile whose top-left pixel is (tx, ty); pixels outside the image are masked
 * off. Returns the active mask. Lane i = pixel (tx + i % 4, ty + i / 4). The _tab forms take the
 * directions from lt_camera_dirs_table's tab (NULL: computed). */
lt_mask16_t lt_camera_packet_q16(const lt_camera_t *c, uint32_t tx, uint32_t ty, lt_ray16_q16_t *r);
lt_mask16_t lt_camera_packet_f32(const lt_camera_t *c, uint32_t tx, uint32_t ty, lt_ray16_f32_t *r);
lt_mask16_t lt_camera_packet_tab_q16(const lt_camera_t *c, const double *tab, uint32_t tx,
                                     uint32_t ty, lt_ray16_q16_t *r);
lt_mask16_t lt_camera_packet_tab_f32(const lt_camera_t *c, const double *tab, uint32_t tx,
                                     uint32_t ty, lt_ray16_f32_t *r);

/* Independent double-precision closest hit (brute force Moller-Trumbore over all triangles):
 * returns the triangle id or -1, and the distance in *t. */
int32_t lt_ref_trace(const lt_scene_t *s, const double o[3], const double d[3], double *t);

#endif /* LT_SCENE_H */
