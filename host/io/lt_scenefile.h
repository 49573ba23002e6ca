/* lt_scenefile.h - the lanetrace scene description: a small JSON file (read with cJSON) naming the
 * mesh or depth file, camera, lights, resolution, structure, numeric configuration, machine model
 * and outputs. Validated with precise errors (unknown key, wrong type, out-of-range value, missing
 * file), each naming the file and the key path. docs/scene-format.md is the reference. Host only.
 */
#ifndef LT_SCENEFILE_H
#define LT_SCENEFILE_H

#include <stddef.h>
#include <stdint.h>

#include "io/lt_diag.h"

#define LT_SF_PATH_MAX 1024
#define LT_SF_MAX_LIGHTS 8
#define LT_SF_MAX_RES 8192

typedef enum lt_sf_num { LT_SF_NUM_Q16 = 1, LT_SF_NUM_F32 = 2, LT_SF_NUM_BOTH = 3 } lt_sf_num_t;

/* lt_scenefile_t.given: the knobs a file set (run --auto leaves those alone) */
#define LT_SF_GIVEN_STRUCTURE 1u
#define LT_SF_GIVEN_NUMERIC 2u
#define LT_SF_GIVEN_LEAF 4u

typedef struct lt_sf_light {
    double position[3]; /* mesh file units */
    double intensity;   /* >= 0 */
} lt_sf_light_t;

typedef struct lt_scenefile {
    char path[LT_SF_PATH_MAX];     /* the scene file itself ("" when built from flags only) */
    char mesh[LT_SF_PATH_MAX];     /* resolved path, "" if none */
    char depth[LT_SF_PATH_MAX];    /* resolved path of a depth EXR, "" if none */
    int has_camera;                /* 0: the default benchmark view */
    double eye[3], target[3], up[3];
    double fov_y_deg;              /* vertical field of view, (1, 179) */
    uint32_t width, height;        /* 1..LT_SF_MAX_RES */
    char structure[16];            /* "chunks" */
    char isect[8];                 /* ray/triangle intersector: "wt" (watertight, the default),
                                      "mt" (Moller-Trumbore) or "wt32" (s15.16: watertight on a
                                      grid, 32-bit edge functions) */
    lt_sf_num_t numeric;
    char machine[32];              /* one of lt_sf_machines ("lrb16") */
    char l1[32], l2[32];           /* cache overrides, "" = the machine's */
    int nlights;
    lt_sf_light_t lights[LT_SF_MAX_LIGHTS];
    char out_report[LT_SF_PATH_MAX]; /* JSON cycle report, "" = none */
    char out_csv[LT_SF_PATH_MAX];    /* one CSV row per numeric path, "" = none */
    /* "reproject": view synthesis from 'depth' (lanetrace reproject, docs/reproject.md) */
    int has_reproject;               /* 1 when the object is present */
    double rp_move[3];               /* target offset in source camera axes (x right, y down,
                                        z forward); world units, or median depths if rp_move_rel */
    int rp_move_rel;                 /* 1: rp_move is in units of the median source depth */
    double rp_rot[3];                /* yaw, pitch, roll of the target, degrees */
    char rp_encoding[8];             /* "n64", "n32", "f32" ("" = n64) */
    uint32_t rp_layers;              /* depth peels layer0.Z .. (0 = one layer, 'channel') */
    char rp_channel[64];             /* depth channel ("" = automatic) */
    int rp_color;                    /* 1: read R G B */
    int rp_distance;                 /* 1: depth values are distances along the pixel ray */
    char rp_tracer[16];              /* "quadtree", "dda", "hiz" ("" = quadtree) */
    double rp_gamma_norm, rp_gamma_dist; /* quadtree thresholds, fractions (< 0 = default) */
    /* object space */
    uint32_t leaf;                   /* "leaf": bvh/bvhq max_leaf or kd leaf_tris (0 = default) */
    unsigned given;                  /* LT_SF_GIVEN_* bits: object knobs the file set itself */
    /* "shadows": soft shadows (lanetrace shadows SCENE.json, docs/frusta.md) */
    int has_shadows;                 /* 1 when the object is present */
    char sh_primary[8];              /* "packet", "frusta", "both" ("" = both) */
    char sh_method[8];               /* "frusta", "packet", "both" ("" = both) */
    int sh_filter;                   /* 1: the filtered image is the result (default), 0: the
                                        16-spp image unfiltered */
    uint32_t sh_leaf;                /* frusta BVH leaf size (0 = 8) */
    char sh_cull[16];                /* shadow-ray culling letters b c r f l s p t or "none" ("" =
                                        the default, bcrflst) */
    uint32_t sh_spp;                 /* shadow samples per pixel: 4, 8, 16, 32 (0 = 16) */
} lt_scenefile_t;

/* Defaults: no mesh, default camera, 128x128, "chunks", both paths, lrb16, no lights, no outputs. */
void lt_sf_defaults(lt_scenefile_t *sf);

/* Parse and validate a scene file; relative paths inside it are resolved against its directory.
 * Returns 0, or -1 with a message in diag naming the file, the key path and the rule broken. */
int lt_sf_load(const char *path, lt_scenefile_t *sf, lt_diag_t *diag);

/* The same from a string (name is used in messages, base_dir resolves relative paths). */
int lt_sf_parse(const char *text, const char *name, const char *base_dir, lt_scenefile_t *sf,
                lt_diag_t *diag);

/* Structure names the tracer accepts (NULL-terminated). */
extern const char *const lt_sf_structures[];

/* Intersector names (NULL-terminated): "wt" (LT_ISECT_WT), "mt" (LT_ISECT_MT), in that order. */
extern const char *const lt_sf_isects[];

/* Machine model names (NULL-terminated, in file name order): one per sim/machines/<name>.def, known
 * in every build (the native one runs no cycle model). */
extern const char *const lt_sf_machines[];

/* The same as one string for messages: "lrb16, mcu-m4". */
const char *lt_sf_machine_list(void);

/* 1 when name is one of lt_sf_machines. */
int lt_sf_machine_known(const char *name);

#endif /* LT_SCENEFILE_H */
