/* lt_paths.h - the host's one registry of numeric paths. The core names a path several ways, one
 * per family of kernels: lt_path_t (object-space rendering, host/render/lt_render.h; also the
 * frusta soft shadows), LT_BVH_NUM_* (a built BVH's node format), lt_sf_num_t (the scene file's
 * "numeric" bits), lt_qt_enc_t (the screen-space quadtree's node encodings) and lt_ssb_enc_t (the
 * DDA and Hi-Z baselines' w buffer). This table gives each path one name - the one the CLI's
 * `--num` and the scene file take - with its compute format, a description, the families it
 * serves and its value in each of those enumerations, so no program keeps its own list of names.
 *
 *   name format  families               lt_path_t    BVH_NUM sf_num lt_qt_enc  lt_ssb_enc
 *   q16  s15.16  object, frusta         LT_PATH_Q16  _Q16    _Q16   -          -
 *   n64  s1.30   screen                 -            -       -      LT_QT_N64  LT_SSB_Q30
 *   n32  s1.30   screen                 -            -       -      LT_QT_N32  LT_SSB_Q30
 *   f32  float32 object, frusta, screen LT_PATH_F32  _F32    _F32   LT_QT_F32  LT_SSB_F32
 *
 * (n64 and n32 are the quadtree's 64- and 32-bit node encodings of the s1.30 screen-space path;
 * the DDA and Hi-Z baselines trace both in s1.30; fixed point comes first, so lists read "q16 or
 * f32" and "n64, n32 or f32".) Adding a path: a line in lt_paths.c, then the families'
 * enumerations and kernels (docs/architecture.md, "a numeric path"). Host only.
 */
#ifndef LT_PATHS_H
#define LT_PATHS_H

#include <stddef.h>
#include <stdint.h>

#include "lt/lt_qt.h"
#include "lt/lt_ssdda.h"
#include "render/lt_path_ops.h"

#ifdef __cplusplus
extern "C" {
#endif

/* More than the number of entries and than any path's value in a family's enumeration (arrays
 * indexed by lt_paths_index use it). */
#define LT_PATHS_MAX 8

/* The families of kernels a path can serve (bits). */
#define LT_PATHS_OBJECT 1u /* object space: lanetrace run, render (lt_accel_build, lt_render_*) */
#define LT_PATHS_FRUSTA 2u /* multi-frusta soft shadows: lanetrace shadows (lt_softshadow) */
#define LT_PATHS_SCREEN 4u /* screen space: lanetrace reproject (quadtree, DDA, Hi-Z) */

typedef struct lt_path_info {
    const char *name;   /* "q16": --num, the scene file's "numeric" / "reproject.encoding" */
    const char *format; /* the compute format: "s15.16", "s1.30", "float32" */
    const char *desc;   /* one line for help texts and docs */
    const char *note;   /* a few words beside the format in option help ("32-bit nodes"), or NULL */
    unsigned families;  /* LT_PATHS_* */
    int frac_bits;      /* fixed point: fraction bits of the format (raw / 2^frac_bits); 0: float */
    /* the operations of each family it serves (lt_path_ops.h), NULL for the others */
    const lt_render_ops_t *render; /* LT_PATHS_OBJECT */
    const lt_ss_ops_t *frusta;     /* LT_PATHS_FRUSTA (such a path serves LT_PATHS_OBJECT too) */
    const lt_rp_ops_t *screen;     /* LT_PATHS_SCREEN */
    /* the path in the core's and the scene file's enumerations, -1 / 0 where it has no value */
    int bvh_num;        /* LT_BVH_NUM_* (0: none) */
    int sf_num;         /* lt_sf_num_t bit (0: none) */
    int qt_enc;         /* lt_qt_enc_t */
    int ssb_enc;        /* lt_ssb_enc_t */
} lt_path_info_t;

/* Every path, ending with a NULL name. */
extern const lt_path_info_t lt_paths[];

/* The path called name that serves one of the families (0: any), or NULL. */
const lt_path_info_t *lt_paths_find(const char *name, unsigned families);

/* The entry of an lt_qt_enc_t (NULL when out of range). */
const lt_path_info_t *lt_paths_of_qt_enc(lt_qt_enc_t e);

/* The position of p in lt_paths (0 ..), for arrays of LT_PATHS_MAX per path. */
int lt_paths_index(const lt_path_info_t *p);

/* The names of the paths serving any of families, in table order, into names[0..max-2] and a
 * NULL after them (an ENUM option's list). Returns how many. */
int lt_paths_names(unsigned families, const char **names, int max);

/* Those names joined for messages and help: "n64, n32 or f32". */
void lt_paths_list(unsigned families, char *buf, size_t n);

/* Fixed-point paths: a raw value of the format as a double (exact) and a double as the nearest raw
 * value (half up, saturating to int32 like the core). Float paths: raw is the binary32 bit pattern
 * (to_double) / the binary32 bit pattern of the value rounded to float (from_double). */
double lt_path_to_double(const lt_path_info_t *p, int64_t raw);
int64_t lt_path_from_double(const lt_path_info_t *p, double v);

#ifdef __cplusplus
}
#endif
#endif /* LT_PATHS_H */
