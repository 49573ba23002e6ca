/* lt_scene.h - a mesh made ready for the core: placed and scaled into the fixed-point range,
 * quantised to s15.16 and converted to float32, a pinhole camera that generates 16-ray packets over
 * 4x4 pixel tiles, and an independent double-precision reference tracer for error figures.
 * Host only.
 */
#ifndef LT_SCENE_H
#define LT_SCENE_H

#include "lt/lt.h"
#include "lt_mesh.h"

typedef struct lt_scene {
    uint32_t ntris;
    lt_tri_q16_t *tq;      /* s15.16 triangles (edges from quantised vertices) */
    lt_tri_f32_t *tf;      /* float32 triangles of the same scaled geometry */
    double *vd;            /* 9 doubles per triangle: scaled, unquantised (the reference) */
    double center[3];      /* file units: the origin of the scaled space */
    double scale;          /* scaled = (file - center) * scale; a power of two */
    double radius;         /* half the bounding-box diagonal, scaled units */
} lt_scene_t;

/* The scene radius is mapped to at most 2^(LT_CFG_GEOM_MAX_LOG2 - 2) units so that a camera at up
 * to 3x the radius from the centre stays within the core's geometry bound. */
#define LT_SCENE_RADIUS_LOG2 (LT_CFG_GEOM_MAX_LOG2 - 2)

/* Returns 0, or -1 with a message (degenerate bounds: all vertices equal; or a scale that would
 * push the scene's smallest feature below s15.16 resolution is reported as a warning only). */
int lt_scene_prepare(const lt_mesh_t *m, lt_scene_t *s, char *err, size_t errlen);
void lt_scene_free(lt_scene_t *s);

typedef struct lt_camera {
    double eye[3];           /* scaled units */
    double fwd[3], right[3], up[3];
    double tan_half_fov;
    uint32_t width, height;
} lt_camera_t;

/* The benchmark view of ../shared/docs/facts.md: looking at the bounding-box centre from direction
 * normalize(0.45, 0.35, 1.0) at distance radius / tan(20 deg), 40 deg vertical field of view, +y up. */
void lt_camera_default(const lt_scene_t *s, uint32_t width, uint32_t height, lt_camera_t *c);

/* An explicit pinhole camera given in mesh file units (converted to the scaled space).
 * Returns 0, or -1 with a message when the eye lies outside the core's geometry bound. */
int lt_camera_look(const lt_scene_t *s, const double eye[3], const double target[3],
                   const double up[3], double fov_y_deg, uint32_t width, uint32_t height,
                   lt_camera_t *c, char *err, size_t errlen);

/* Unit direction of the ray through the centre of pixel (x, y) (y down). */
void lt_camera_dir(const lt_camera_t *c, uint32_t x, uint32_t y, double d[3]);

/* Packets of the 4x4 tile whose top-left pixel is (tx, ty); pixels outside the image are masked
 * off. Returns the active mask. Lane i = pixel (tx + i % 4, ty + i / 4). */
lt_mask16_t lt_camera_packet_q16(const lt_camera_t *c, uint32_t tx, uint32_t ty, lt_ray16_q16_t *r);
lt_mask16_t lt_camera_packet_f32(const lt_camera_t *c, uint32_t tx, uint32_t ty, lt_ray16_f32_t *r);

/* Independent double-precision closest hit (brute force Moller-Trumbore over all triangles):
 * returns the triangle id or -1, and the distance in *t. */
int32_t lt_ref_trace(const lt_scene_t *s, const double o[3], const double d[3], double *t);

#endif /* LT_SCENE_H */
