/* lt_sblob.h - the scene blob: a prepared, position-independent object-space scene (s15.16
 * triangles, their BVH, an integer pinhole camera and a point light) that a firmware target
 * traces where it finds it (read-only memory: nothing is copied to RAM), and the tracer that
 * renders it tile by tile: primary rays and hard shadows in s15.16, 16-ray packets of 4x4 pixels
 * (lt_bvh_trace16_q16, lt_bvh_occluded16_q16) or single rays, with the watertight test.
 * `lanetrace pack` writes blobs from any mesh or scene file and runs this same tracer over them,
 * so a target's lines can be compared with the host's bit for bit (docs/firmware.md, "Scene
 * blobs"). Builds: firmware (freestanding), host, sim.
 */
#ifndef LT_SBLOB_H
#define LT_SBLOB_H

#include <stddef.h>
#include <stdint.h>
#include "lt_stage.h"
#include "lt/lt.h"
#include "lt/lt_frusta.h"
#include "lt/lt_qmc.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LT_SBLOB_MAGIC 0x4253544Cu /* "LTSB" as a little-endian word */
#define LT_SBLOB_VERSION 1u
#define LT_SBLOB_HEADER_BYTES 128u /* 32 words */
#define LT_SBLOB_TILE 16u          /* tile side, pixels: 16 packets of 4x4 rays */
#define LT_SBLOB_MAX_RES 4096u     /* largest width and height */

/* The header: 32 little-endian 32-bit words at the blob's start (the blob is 4-byte aligned;
 * 64-byte aligned keeps node pairs in one cache line). Offsets are bytes from the blob's start. */
enum lt_sblob_word {
    LT_SB_MAGIC = 0,     /* LT_SBLOB_MAGIC */
    LT_SB_VERSION = 1,   /* LT_SBLOB_VERSION */
    LT_SB_HEADER = 2,    /* LT_SBLOB_HEADER_BYTES */
    LT_SB_BYTES = 3,     /* the whole blob, header included */
    LT_SB_NTRIS = 4,     /* triangles, 1..LT_BVH_MAX_TRIS */
    LT_SB_NNODES = 5,    /* BVH node slots (node 0 the root, slot 1 unused) */
    LT_SB_OFF_TRIS = 6,  /* lt_tri_q16_t[ntris], 36 bytes each */
    LT_SB_OFF_NODES = 7, /* lt_bvh_node_q16_t[nnodes], 32 bytes each */
    LT_SB_OFF_IDX = 8,   /* uint32_t[ntris]: leaf slot -> triangle */
    LT_SB_WIDTH = 9,     /* image width, 1..LT_SBLOB_MAX_RES */
    LT_SB_HEIGHT = 10,   /* image height */
    LT_SB_FLAGS = 11,    /* LT_SBLOB_F_* */
    LT_SB_EPS = 12,      /* shadow rays' offset at both ends, s15.16, > 0 */
    LT_SB_EYE = 13,      /* 3 words: the eye, s15.16 */
    LT_SB_D00 = 16,      /* 3 words: direction through pixel (0, 0)'s centre, any scale (int32) */
    LT_SB_DX = 19,       /* 3 words: its change per pixel to the right */
    LT_SB_DY = 22,       /* 3 words: its change per pixel down */
    LT_SB_LIGHT = 25,    /* 3 words: the point light, s15.16 */
    LT_SB_DEPTH = 28,    /* deepest leaf of the BVH (root 0), <= LT_BVH_MAX_DEPTH */
    LT_SB_LEAF = 29,     /* the build's largest leaf, 1..LT_BVH_MAX_LEAF */
    LT_SB_SUM = 30,      /* FNV-1a of the blob's bytes with this word taken as 0 (lt_sblob_sum) */
    LT_SB_SCALE = 31     /* informational: s15.16 units per mesh unit x 2^16 (saturates) */
};

#define LT_SBLOB_F_SHADOWS 1u /* trace a shadow ray from every primary hit to the light */
#define LT_SBLOB_F_WT32 2u    /* trace with LT_ISECT_WT32 (lt_wt.h) on the grid lt_wt32_shift_q16
                                 picks for the blob's triangles; a build with LT_CFG_WT32 0
                                 refuses such a blob (flags out of range) */

/* Why a blob was refused (lt_sblob_open). */
typedef enum lt_sblob_err {
    LT_SBLOB_OK = 0,
    LT_SBLOB_E_SHORT,     /* fewer bytes than the header, or than its byte count */
    LT_SBLOB_E_MAGIC,     /* not a scene blob (or another byte order) */
    LT_SBLOB_E_VERSION,   /* another format version */
    LT_SBLOB_E_LAYOUT,    /* a section outside the blob, misaligned or overlapping the header */
    LT_SBLOB_E_SUM,       /* the checksum differs: the bytes were damaged */
    LT_SBLOB_E_IMAGE,     /* width, height, eps or flags out of range */
    LT_SBLOB_E_CAMERA,    /* a pixel direction overflows, or a corner's is 90 degrees or more
                             from the centre pixel's (so one may be zero) */
    LT_SBLOB_E_GEOMETRY,  /* a vertex or the eye or light outside the core's geometry bound */
    LT_SBLOB_E_TREE       /* a node or index out of range, a cycle, or a tree deeper than allowed */
} lt_sblob_err_t;

/* An opened blob: pointers into it (nothing copied). */
typedef struct lt_sblob {
    lt_bvh_t bvh;
    const lt_tri_q16_t *tris;
    uint32_t width, height, flags, tiles_x, tiles_y;
    lt_q16_t eps, eye[3], light[3];
    int32_t d00[3], dx[3], dy[3];
    uint32_t bad; /* after an error: the word, node or triangle it concerns (else 0) */
} lt_sblob_t;

/* One tile's results. */
typedef struct lt_sblob_tile {
    uint32_t hash;      /* FNV-1a over the tile's pixels in raster order: id, distance, shadowed */
    uint32_t rays;      /* primary rays (pixels inside the image) */
    uint32_t hits;      /* primary hits */
    uint32_t srays;     /* shadow rays traced (hits farther than 2 eps from the light) */
    uint32_t occluded;  /* of those, the blocked ones */
    uint64_t t_primary; /* ticks spent in primary rays, t_shadow in shadow rays (0 without clock) */
    uint64_t t_shadow;
    int32_t *ids;       /* set by the caller: NULL, or [16 x 16] to receive the tile's triangle ids
                           (-1: miss) in raster order, for pixels inside the image */
} lt_sblob_tile_t;

/* What a blob shows besides its geometry: image, camera, light (the header words of the same
 * names). */
typedef struct lt_sblob_view {
    uint32_t width, height, flags;
    lt_q16_t eps, eye[3], light[3];
    int32_t d00[3], dx[3], dy[3];
    uint32_t scale; /* LT_SB_SCALE, informational */
} lt_sblob_view_t;

/* Bytes of the blob of ntris triangles and a tree of nnodes node slots (the sections 64-byte
 * aligned). Cost: none. */
size_t lt_sblob_size(uint32_t ntris, uint32_t nnodes);

/* Write the blob of tris[0 .. bvh->ntris) and their built s15.16 tree (lt_bvh_build_q16 with
 * max_leaf) seen as v into out (4-byte aligned, bytes >= lt_sblob_size), little-endian whatever
 * the host's byte order, the checksum last. It is not checked here: lt_sblob_open does that.
 * Returns LT_OK, LT_E_ARG (NULL, a float32 or empty tree), LT_E_SPACE (bytes too small). */
lt_status_t lt_sblob_write(const lt_tri_q16_t *tris, const lt_bvh_t *bvh, uint32_t max_leaf,
                           const lt_sblob_view_t *v, void *out, size_t bytes);

/* The checksum of a blob of `bytes` bytes (>= LT_SBLOB_HEADER_BYTES): FNV-1a over them with the
 * LT_SB_SUM word taken as zero. Cost: one pass. */
uint32_t lt_sblob_sum(const void *p, size_t bytes);

/* Check the blob at p (4-byte aligned, `bytes` long) and fill s. Every field, section, node and
 * index is checked (a damaged or foreign blob is refused, never traced). Cost: a pass over the
 * blob (checksum, triangles, nodes, indices). Returns LT_SBLOB_OK or why not (s->bad says where). */
lt_sblob_err_t lt_sblob_open(const void *p, size_t bytes, lt_sblob_t *s);

/* One line of text per error code ("checksum differs: the blob was damaged"). */
const char *lt_sblob_err_str(lt_sblob_err_t e);

/* Trace tile t (0 .. tiles_x * tiles_y - 1, raster order of 16x16 tiles): primary rays, and with
 * LT_SBLOB_F_SHADOWS a shadow ray per hit; single = 0: 16-ray packets of 4x4 pixels
 * (lt_bvh_trace16_q16, lt_bvh_occluded16_q16), 1: one ray at a time (lt_bvh_trace1_q16,
 * lt_bvh_occluded1_q16), which gives the same results bit for bit. ticks (may be NULL) times the
 * two stages (LT_STAGE_PRIMARY and _SHADOW, or _PRIMARY1 and _SHADOW1 ray by ray). Returns LT_OK or the traversal's error (LT_E_ARG for t out of range). */
lt_status_t lt_sblob_trace_tile(const lt_sblob_t *s, uint32_t t, int single,
                                lt_sblob_clock_fn ticks, lt_sblob_tile_t *out);

/* ---- frusta blobs: one 16x16 block of multi-frusta soft shadows ----------------------------- */

/* A frusta blob carries the soft-shadow work of one 16x16 pixel block: the block's shadow origins
 * (the primary hits, offset along the normal, as the host's renderer made them) and which pixels
 * are lit, the quad light and its sample sets, and the triangles that can stand between them and
 * the light (a crop of the scene the host proved conservative) with their shallow BVH. The target
 * runs the block's 16 4x4 tiles as S-Frusta (lt_frusta_setup16_q16, lt_frusta_occluded16_q16; one
 * frustum per pixel, spp samples each). `lanetrace shadows --pack-block` writes them. */
#define LT_FBLOB_MAGIC 0x4246544Cu /* "LTFB" */
#define LT_FBLOB_VERSION 1u
#define LT_FBLOB_HEADER_BYTES 256u /* 64 words */
#define LT_FBLOB_BLOCK 16u         /* block side, pixels: 16 tiles of 4x4 frusta */

enum lt_fblob_word {
    LT_FB_MAGIC = 0, LT_FB_VERSION = 1, LT_FB_HEADER = 2, LT_FB_BYTES = 3,
    LT_FB_NTRIS = 4,      /* triangles of the crop, 1..LT_BVH_MAX_TRIS */
    LT_FB_NNODES = 5,     /* its BVH's node slots */
    LT_FB_OFF_TRIS = 6, LT_FB_OFF_NODES = 7, LT_FB_OFF_IDX = 8,
    LT_FB_OFF_ORG = 9,    /* lt_q16_t[256][3]: pixel p = y * 16 + x of the block, its origin */
    LT_FB_LIT = 10,       /* 8 words: bit p % 32 of word p / 32 = pixel p gets shadow frusta */
    LT_FB_LIGHT = 18,     /* 9 words: the light's c, eu, ev (lt_frusta_light_q16_t) */
    LT_FB_LFLAGS = 27,    /* its flags (LT_FRUSTA_*) */
    LT_FB_END_SHIFT = 28, /* its end_shift */
    LT_FB_QMC = 29,       /* lt_qmc_kind_t of the sample sets */
    LT_FB_SCRAMBLE = 30,  /* their digital shift */
    LT_FB_SPP = 31,       /* samples per pixel: 4, 8 or 16 */
    LT_FB_DEPTH = 32, LT_FB_LEAF = 33,
    LT_FB_SUM = 34,       /* FNV-1a of the blob with this word taken as 0 */
    LT_FB_BX = 35, LT_FB_BY = 36, /* informational: the block's top-left pixel in its image */
    LT_FB_REF = 37,       /* informational: the block's hash over the whole scene (host) */
    LT_FB_SCENE_TRIS = 38 /* informational: triangles of the whole scene */
};

typedef struct lt_fblob {
    lt_bvh_t bvh;
    const lt_tri_q16_t *tris;
    const lt_q16_t *org;         /* [256][3] */
    uint32_t lit[8];
    uint32_t spp, ref, scene_tris, bx, by;
    lt_frusta_table_q16_t tb;    /* built by lt_fblob_open (6388 bytes) */
    uint32_t bad;
} lt_fblob_t;

/* One 4x4 tile's S-Frusta result. */
typedef struct lt_fblob_tile {
    uint32_t hash;     /* FNV-1a over the tile's pixels in raster order: lit, occluded samples */
    uint32_t lit;      /* lit pixels (frusta traced) */
    uint32_t occluded; /* occluded samples */
    uint64_t ticks;    /* spent in setup and walk (0 without clock) */
} lt_fblob_tile_t;

/* Check a frusta blob (as lt_sblob_open: every word, the checksum, the scene, the light, the
 * origins against the geometry bound) and build its sample table. Returns LT_SBLOB_OK or why not. */
lt_sblob_err_t lt_fblob_open(const void *p, size_t bytes, lt_fblob_t *f);

/* S-Frusta of 4x4 tile t (0..15, raster order in the block). ticks may be NULL. Returns LT_OK or
 * the walk's error (LT_E_ARG for t > 15). */
lt_status_t lt_fblob_trace_tile(const lt_fblob_t *f, uint32_t t, lt_sblob_clock_fn ticks,
                                lt_fblob_tile_t *out);

/* The block hash: FNV-1a over the 16 tile hashes in order (also how the host hashes the whole
 * scene's answer for LT_FB_REF). */
uint32_t lt_fblob_block_hash(const uint32_t tile_hash[16]);

/* The tile hash of 16 pixels (lit flag, occluded samples), lane order i = y * 4 + x. */
uint32_t lt_fblob_tile_hash(const uint8_t lit[16], const uint16_t occl[16]);

/* Blob writer for the host: sections 64-byte aligned after the 256-byte header. h[64] holds every
 * header word but the layout and checksum words, which this fills. Returns LT_OK, LT_E_ARG,
 * LT_E_SPACE (bytes < lt_fblob_size). */
size_t lt_fblob_size(uint32_t ntris, uint32_t nnodes);
lt_status_t lt_fblob_write(const lt_tri_q16_t *tris, const lt_bvh_t *bvh, const lt_q16_t org[768],
                           uint32_t h[64], void *out, size_t bytes);

/* FNV-1a over bytes, continuing from h (start with LT_SBLOB_FNV0). */
#define LT_SBLOB_FNV0 2166136261u
uint32_t lt_sblob_fnv(uint32_t h, const void *p, size_t n);

#ifdef __cplusplus
}
#endif
#endif /* LT_SBLOB_H */
