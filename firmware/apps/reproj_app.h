/* reproj_app.h - screen-space reprojection of a prepared depth blob (issue #13 item 1): the blob
 * (written on the host by `lanetrace fwblob` from a real depth EXR) holds layers of s1.30 inverse
 * depth and the s1.30 mapping of a moved target camera; the app validates it, builds the quadtree
 * in caller-provided memory and reprojects the target view tile by tile, printing a line per tile
 * as it finishes (no output image is held). One source for every build: the firmware image
 * (firmware/apps/reproj_fw.c, the blob linked as read-only data) and the host runner
 * (tests/fw/reproj_blob_host.c); their lines must be equal. docs/firmware.md, "Reprojection of a
 * real depth image". Builds: firmware (freestanding), host.
 */
#ifndef LT_REPROJ_APP_H
#define LT_REPROJ_APP_H

#include <stddef.h>
#include <stdint.h>
#include "lt/lt_reproj.h"
#include "lt_stage.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the blob -------------------------------------------------------------------------------- */
/* Little-endian, position independent: every offset counts from the blob's first byte, which
 * must be 64-byte aligned in memory (lt_fw_blob.S aligns it). The header is followed (at
 * depth_off) by layers x height x width int32 inverse depths, layer-major, row-major. */
#define LT_RPB_MAGIC 0x4252504Cu   /* the bytes "LPRB" */
#define LT_RPB_MAGIC_SWAPPED 0x4C505242u /* the magic read with the other byte order */
#define LT_RPB_VERSION 1u
#define LT_RPB_DEPTH_W_Q30 1u      /* depth format: w = z_ref / z, s1.30, 0 = hole */
#define LT_RPB_HDR_BYTES 224u
#define LT_RPB_ALIGN 64u           /* blob start and depth_off alignment */
#define LT_RPB_SUM_FROM 20u        /* the checksum covers bytes [20, blob_bytes) */

/* 224 bytes, 4-byte fields only (no padding on any ABI). */
typedef struct lt_rpb_hdr {
    uint32_t magic;        /*   0: LT_RPB_MAGIC */
    uint32_t version;      /*   4: LT_RPB_VERSION */
    uint32_t hdr_bytes;    /*   8: LT_RPB_HDR_BYTES */
    uint32_t blob_bytes;   /*  12: the whole blob, bytes; must equal the length the app is given */
    uint32_t checksum;     /*  16: FNV-1a 32 of bytes [LT_RPB_SUM_FROM, blob_bytes) */
    uint32_t width;        /*  20: source depth image, pixels, 1..LT_QT_MAX_DIM */
    uint32_t height;       /*  24: pixels, 1..LT_QT_MAX_DIM */
    uint32_t layers;       /*  28: depth layers, front to back, 1..LT_QT_MAX_LAYERS */
    uint32_t enc;          /*  32: node format to build: LT_QT_N64 or LT_QT_N32 */
    uint32_t depth_format; /*  36: LT_RPB_DEPTH_W_Q30 */
    uint32_t depth_off;    /*  40: offset of the depth array, a multiple of LT_RPB_ALIGN */
    uint32_t depth_bytes;  /*  44: layers x height x width x 4 */
    int32_t zref_exp;      /*  48: z_ref = 2^zref_exp world units (w = z_ref / z); informative */
    uint32_t tile;         /*  52: side of an output tile, pixels, a multiple of 4 in 4..256 */
    uint32_t max_steps;    /*  56: traversal step bound per lane and layer, 0 = the default */
    uint32_t crop_x;       /*  60: crop origin in the EXR's data window, pixels; informative */
    uint32_t crop_y;       /*  64: informative */
    uint32_t src_exr_w;    /*  68: the EXR's data window size, pixels; informative */
    uint32_t src_exr_h;    /*  72: informative */
    uint32_t reserved;     /*  76: 0 */
    lt_qt_params_t params; /*  80: quadtree build thresholds, s1.30 (16 bytes) */
    lt_reproj_q30_t map;   /*  96: the s1.30 mapping source <- target (128 bytes): map.src_w, src_h
                                   equal width, height; map.dst_w x dst_h is the target view */
} lt_rpb_hdr_t;
LT_STATIC_ASSERT(sizeof(lt_rpb_hdr_t) == LT_RPB_HDR_BYTES, "reprojection blob header is 224 bytes");

/* FNV-1a 32 of n bytes, continuing from h (2166136261 to start): the blob's checksum, shared by
 * the writer (lanetrace fwblob) and the app. Cost: none. */
static inline uint32_t lt_rpb_fnv(uint32_t h, const uint8_t *p, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        h ^= p[i];
        h *= 16777619u;
    }
    return h;
}

/* ---- the app --------------------------------------------------------------------------------- */

/* Error codes (the firmware image's exit status; each also printed as "error N: ..."). */
#define LT_RPAPP_OK 0
#define LT_RPAPP_E_SHORT 10     /* shorter than the header, or NULL */
#define LT_RPAPP_E_ALIGN 11     /* blob or memory not 64-byte aligned */
#define LT_RPAPP_E_MAGIC 12     /* not a blob */
#define LT_RPAPP_E_ENDIAN 13    /* a blob of the other byte order */
#define LT_RPAPP_E_VERSION 14   /* another version */
#define LT_RPAPP_E_LENGTH 15    /* hdr_bytes or blob_bytes do not match */
#define LT_RPAPP_E_SIZES 16     /* width, height, layers, enc, depth format, tile out of range */
#define LT_RPAPP_E_OFFSETS 17   /* the depth array is misaligned, overlaps the header or the end */
#define LT_RPAPP_E_CHECKSUM 18  /* the bytes do not match the checksum */
#define LT_RPAPP_E_MAP 19       /* the mapping does not fit the depth image or is rejected */
#define LT_RPAPP_E_MEMORY 20    /* the caller's memory is too small (the need is printed) */
#define LT_RPAPP_E_BUILD 21     /* the quadtree build failed */
#define LT_RPAPP_E_TRACE 22     /* the trace failed */

/* What the app runs on. */
typedef struct lt_rpapp_port {
    void (*puts)(void *ctx, const char *s); /* one output line (with its '\n') */
    /* instruction clock, or NULL (no "ticks:" line): the ticks so far; stage (LT_STAGE_QT_BUILD,
       LT_STAGE_REPROJ or LT_STAGE_UNTIMED, lt_stage.h) begins now */
    uint64_t (*ticks)(void *ctx, uint32_t stage);
    void *ctx;
    const char *name;                       /* printed in the first line ("cm4", "host") */
    int single; /* 1: trace each ray alone (lt_qt_trace1_q30: cores without wide SIMD); 0: packets
                   of 16 (lt_qt_trace16_q30). The lines are the same but the ticks line's walk */
} lt_rpapp_port_t;

/* Validate the blob (blob_len bytes at blob) and say how much memory lt_rpapp_run needs.
 * Returns: LT_RPAPP_OK, or one of the LT_RPAPP_E_* codes above (never reads past blob_len). */
int lt_rpapp_mem_bytes(const void *blob, size_t blob_len, size_t *bytes);

/* Validate, build the quadtree in mem (64-byte aligned, mem_bytes bytes; lt_rpapp_mem_bytes says
 * how much), reproject every target pixel in tiles of hdr.tile pixels (4x4 packets row by row
 * within a tile, tiles row by row), and print:
 *   reproj-blob <name>: source WxH x L layers nNN, target WxH, tiles TxT, quadtree B bytes,
 *       blob B bytes checksum 0x........
 *   tile TX TY: rays N kept N hit N miss N disoccluded N unknown N nodes N hash 0x........
 *   total: rays N kept N hit N (behind layer 0: N) miss N disoccluded N unknown N outside N
 *       nodes N hash 0x........
 *   ticks (NAME): build T, reproject T, per traced ray T.TT, per pixel T.TT, walk single|packets
 *       (only with port->ticks)
 * (a "badray N" field follows unknown when a lane was LT_QT_BADRAY, never for a valid blob)
 * kept = lanes with a non-empty segment; outside = rays - kept (the ray never enters the source
 * view); hit / miss / disoccluded / unknown = the kept lanes' LT_QT_HIT / MISS / OCCLUDED /
 * UNKNOWN. A tile's hash is FNV-1a over its packets' masks and each kept lane's segment and trace
 * result (as tests/vectors/lt_reproj_tile.h hashes them); the total hash chains the tile hashes.
 * Integer only: no float, no double, no allocation.
 * Returns: LT_RPAPP_OK or an LT_RPAPP_E_* code (after an "error N: ..." line). */
int lt_rpapp_run(const lt_rpapp_port_t *port, const void *blob, size_t blob_len, void *mem,
                 size_t mem_bytes);

#ifdef __cplusplus
}
#endif
#endif /* LT_REPROJ_APP_H */
