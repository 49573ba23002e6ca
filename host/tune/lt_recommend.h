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
/* leaf size on a machine of fewer than 16 lanes: tune's cheapest BVH leaf on the 1-lane mcu-m4 */
#define LT_REC_BVH_LEAF_NARROW 4u

typedef struct lt_rec_mesh_facts {
    uint32_t ntris;         /* triangles of the file */
    uint32_t nonzero;       /* of non-zero area (double) */
    uint32_t collapsed_q16; /* of those, collapsed to zero area in s15.16 */
    double extent;          /* largest side of the bounding box, file units */
    double min_edge;        /* shortest non-zero edge of a non-degenerate triangle, file units */
    double scale;           /* file units -> s15.16 units (lt_scene_t.scale) */
    const char *machine;    /* the machine model the picks are for; NULL: lrb16 */
} lt_rec_mesh_facts_t;

/* The numeric pick weighs, on the machine, what one call of each path's watertight triangle test
 * costs for 16 rays that miss (most tests miss): lt_tri16_wt_q16 against lt_tri16_wt_f32, each
 * op class of the call (lt_rec_tri_q16/f32, terminated by n == 0) at the machine's issue cycles.
 * The lists are the ops the simulator charges for those calls; test_costs checks them. */
typedef struct lt_rec_op {
    int op;     /* LT_OP_* */
    unsigned n; /* times per call */
} lt_rec_op_t;
extern const lt_rec_op_t lt_rec_tri_q16[], lt_rec_tri_f32[];

typedef struct lt_rec_costs {
    uint32_t f32;   /* issue cycles of lt_tri16_wt_f32, 16 missing rays */
    uint32_t q16;   /* issue cycles of lt_tri16_wt_q16, 16 missing rays */
    uint32_t lanes; /* the machine's lanes */
} lt_rec_costs_t;

/* The costs of the machine called name (every build: the machine files are data); 0, or -1 for
 * an unknown name (then *c is zeroed). */
int lt_rec_machine_costs(const char *name, lt_rec_costs_t *c);

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
    const char *machine;  /* the machine the picks are for */
    lt_rec_costs_t costs; /* its costs (lt_rec_machine_costs) */
} lt_rec_t;

/* The recommendation for a mesh's facts into r (always succeeds). */
void lt_recommend_mesh(const lt_rec_mesh_facts_t *f, lt_rec_t *r);

#ifdef __cplusplus
}
#endif
#endif /* LT_RECOMMEND_H */
