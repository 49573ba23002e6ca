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

/* ---- depth images (the screen family: lanetrace reproject) ---- */

/* A neighbour pair whose depths differ by more than this fraction of the nearer is a jump */
#define LT_REC_JUMP_REL 0.05
/* A pixel is planar when the second differences of w = 1/z along x and y sum to at most this
 * fraction of its w (a plane in the camera is linear in w: second differences 0) */
#define LT_REC_PLANAR_REL 1e-3

typedef struct lt_rec_depth_facts {
    uint32_t width, height;
    uint64_t valid;          /* finite depths > 0 */
    uint64_t holes;          /* the others (0, negative, NaN, inf): background */
    double zmin, zmax;       /* over the valid depths */
    uint64_t pairs, jumps;   /* 4-neighbour pairs of valid pixels; of those, jumps */
    uint64_t inner, planar;  /* valid pixels with 4 valid neighbours; of those, planar */
    uint64_t target_px;      /* pixels of the reprojected view; 0: the source's size */
    const char *machine;     /* the machine model the picks are for; NULL: lrb16 */
} lt_rec_depth_facts_t;

/* The facts of a width x height depth image (row-major z, any units) into f; machine NULL. */
void lt_rec_depth_scan(const float *z, uint32_t width, uint32_t height, lt_rec_depth_facts_t *f);

/* Simulated cycles of a quadtree reprojection from src_px source to dst_px target pixels in node
 * format enc ("n64", "n32", "f32") on the machine, from its LT_MACHINE_QT rows (measured by
 * tests/bench/qtcal.sh); 0 for an unknown machine or format. */
double lt_rec_qt_cost(const char *machine, const char *enc, double src_px, double dst_px);

/* The recommendation for a depth image into r: knob "num", the quadtree node format: float32 when
 * s1.30's step at the farthest depth is coarser than float32's 2^-24, else the cheaper of n64
 * and f32 on the machine (lt_rec_qt_cost; n32 is never picked: it keeps 12-bit planes and loses
 * hits); r->range_log2 = log2(zmax / zmin). */
void lt_recommend_depth(const lt_rec_depth_facts_t *f, lt_rec_t *r);

#ifdef __cplusplus
}
#endif
#endif /* LT_RECOMMEND_H */
