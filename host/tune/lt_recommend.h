/* lt_recommend.h - lanetrace info's recommendation for a mesh without a sweep: for each knob of
 * the object family (numeric path, structure, leaf size) a pick and a one-line reason made of the
 * scene's measured facts (triangle counts, s15.16 collapses, extent, shortest edge). Pure: no I/O;
 * `lanetrace tune` measures what this only estimates (docs/tune.md). Host only.
 */
#ifndef LT_RECOMMEND_H
#define LT_RECOMMEND_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* structure: a BVH above this many triangles, chunks (a box per LT_CHUNK_TRIS = 16 triangles) at or below */
#define LT_REC_BVH_MIN_TRIS 256u
/* numeric: the shortest edge must span at least this many s15.16 steps (2^-16 scaled units) for
 * s15.16 to keep its shape within 1/128 of its length; fewer, and float32 is picked */
#define LT_REC_MIN_EDGE_STEPS 64.0
/* leaf size of the BVH: lanetrace tune's cheapest on lrb16 (16 lanes) for the teapot */
#define LT_REC_BVH_LEAF 16u

typedef struct lt_rec_mesh_facts {
    uint32_t ntris;         /* triangles of the file */
    uint32_t nonzero;       /* of non-zero area (double) */
    uint32_t collapsed_q16; /* of those, collapsed to zero area in s15.16 */
    double extent;          /* largest side of the bounding box, file units */
    double min_edge;        /* shortest non-zero edge of a non-degenerate triangle, file units */
    double scale;           /* file units -> s15.16 units (lt_scene_t.scale) */
} lt_rec_mesh_facts_t;

#define LT_REC_MAX_KNOBS 4

typedef struct lt_rec_pick {
    const char *knob;  /* "numeric", "structure", "leaf" */
    char pick[16];     /* the scene-file value ("f32", "bvh", "16"; "-" for none) */
    char reason[320];  /* one line, numbers from the facts */
} lt_rec_pick_t;

typedef struct lt_rec {
    int n;
    lt_rec_pick_t k[LT_REC_MAX_KNOBS];
    int q16_ok;        /* s15.16 represents the scene (lt_scene_check_q16's rule) */
    double range_log2; /* log2(extent / shortest edge); 0 when there is no edge */
    double edge_steps; /* the shortest edge in s15.16 steps */
} lt_rec_t;

/* The recommendation for a mesh's facts into r (always succeeds). */
void lt_recommend_mesh(const lt_rec_mesh_facts_t *f, lt_rec_t *r);

#ifdef __cplusplus
}
#endif
#endif /* LT_RECOMMEND_H */
