/* lt_paths.h - the host's one registry of numeric paths: each path's name (the one `--num` and
 * the scene file take), compute format, description, the families of kernels it serves, its ops
 * table for each of them (lt_path_ops.h: the renderers call path->render->..., ->frusta->...,
 * ->screen->... and never branch on the path), its raw <-> double conversion, and its value in the
 * core's enumerations where the core's API takes one (LT_BVH_NUM_*, lt_qt_enc_t, lt_ssb_enc_t) and
 * in the scene file's "numeric" bits (lt_sf_num_t). No program keeps its own list of paths.
 *
 *   name format  families               ops tables              BVH_NUM sf_num qt_enc    ssb_enc
 *   q16  s15.16  object, frusta         lt_{render,ss}_ops_q16  _Q16    _Q16   -         -
 *   n64  s1.30   screen                 lt_rp_ops_n64           -       -      LT_QT_N64 LT_SSB_Q30
 *   n32  s1.30   screen                 lt_rp_ops_n32           -       -      LT_QT_N32 LT_SSB_Q30
 *   f32  float32 object, frusta, screen lt_{render,ss,rp}_ops_f32 _F32  _F32   LT_QT_F32 LT_SSB_F32
 *
 * (n64 and n32 are the quadtree's 64- and 32-bit node encodings of the s1.30 screen-space rays:
 * one instantiation of the screen template, two tables; the DDA and Hi-Z baselines trace both in
 * s1.30; fixed point comes first, so lists read "q16 or f32" and "n64, n32 or f32".) Each table
 * is a family's template written once (lt_render_path.inc, lt_softshadow_path.inc,
 * lt_reproject_path.inc) instantiated with the path's header of generic names (lt_path_q16.h,
 * lt_path_q30.h, lt_path_f32.h) in lt_render_paths.c, lt_softshadow_paths.c and
 * lt_reproject_paths.c. Adding a path: its kernels in the core, its lt_path_<suffix>.h, three lines
 * per family in those files, one entry in lt_paths.c (docs/architecture.md, "a numeric path");
 * the renderers' bodies do not change. Host only.
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

/* The first path in table order serving any of families (with object-space ops) other than
 * `except` that represents the prepared scene s (no scene_check, or the check passes): where a
 * scene one path cannot represent runs when the user did not ask for that path. NULL: none. */
const lt_path_info_t *lt_paths_fallback(const lt_scene_t *s, unsigned families,
                                        const lt_path_info_t *except);

/* Fixed-point paths: a raw value of the format as a double (exact) and a double as the nearest raw
 * value (half up, saturating to int32 like the core). Float paths: raw is the binary32 bit pattern
 * (to_double) / the binary32 bit pattern of the value rounded to float (from_double). */
double lt_path_to_double(const lt_path_info_t *p, int64_t raw);
int64_t lt_path_from_double(const lt_path_info_t *p, double v);

#ifdef __cplusplus
}
#endif
#endif /* LT_PATHS_H */
