/* stream_dev.h - the streaming device of issue 6: traces a small fixed scene (an 18-triangle
 * embedded mesh, integer camera) tile by tile with lt_chunks_trace16_q16 and streams a TILE report
 * per tile, a SUMMARY per image frame and optional IMAGE tiles through the lt_stream batcher.
 * One source for every device: the firmware images (firmware/apps/stream_fw.c, counters it can count
 * itself) and the simulator acting as a device (host/stream/lt_stream_dev_main.c, sim counters).
 * Builds: firmware (freestanding), host, sim.
 */
#ifndef LT_STREAM_DEV_H
#define LT_STREAM_DEV_H

#include <stddef.h>
#include <stdint.h>
#include "lt/lt_stream.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LT_SDEV_W 64       /* image width, pixels */
#define LT_SDEV_H 64       /* image height */
#define LT_SDEV_TILE 16    /* tile side, pixels (16 packets of 4x4 rays) */
#define LT_SDEV_TILES ((LT_SDEV_W / LT_SDEV_TILE) * (LT_SDEV_H / LT_SDEV_TILE))
#define LT_SDEV_MAX_FRAMES 64

/* Cumulative counters a device may know besides its tick clock. */
typedef struct lt_sdev_ctr {
    uint64_t cycles;            /* modelled cycles */
    uint64_t aabb, aabb_rays;   /* packet-box, ray-box tests */
    uint64_t tris, tri_rays;    /* packet-triangle, ray-triangle tests */
} lt_sdev_ctr_t;

/* What the device runs on. */
typedef struct lt_sdev_port {
    uint64_t (*ticks)(void *ctx);                   /* device clock, ticks */
    void (*idle_until)(void *ctx, uint64_t t);      /* wait until ticks() >= t */
    void (*counters)(void *ctx, lt_sdev_ctr_t *c);  /* NULL when the device cannot count */
    void (*region)(void *ctx, const void *p, size_t bytes, uint64_t sim_base); /* may be NULL */
    lt_stream_sink_fn sink;                         /* where frames go */
    void *ctx;
    uint32_t tick_hz;           /* ticks per device second */
    uint32_t valid;             /* LT_STREAM_F_* the device fills */
    uint8_t source;             /* LT_STREAM_SRC_* */
    const char *name;           /* "cm4", "sim:mcu-m4" (at most 16 bytes are sent) */
} lt_sdev_port_t;

/* What to run. */
typedef struct lt_sdev_cfg {
    uint32_t frames; /* image frames, 1..LT_SDEV_MAX_FRAMES (the camera moves per frame) */
    uint32_t image_from;        /* frames >= this also stream IMAGE tiles (>= frames: none) */
    int direct;                 /* 1: trace only, no stream (the reference run) */
    lt_stream_link_t link;      /* batcher parameters (tick_hz is overwritten from the port) */
} lt_sdev_cfg_t;

/* Per-frame results (what SUMMARY carries), filled for every frame in both modes. */
typedef struct lt_sdev_result {
    lt_stream_summary_t sum[LT_SDEV_MAX_FRAMES];
    uint32_t frames;
    lt_stream_tx_t tx;          /* batcher statistics (stream mode) */
    uint64_t ticks_end;         /* device tick when tracing ended */
    uint64_t link_done;         /* tick when the last frame left the link */
} lt_sdev_result_t;

/* The default configuration: 4 frames, IMAGE tiles from frame 2, lt_stream_link_default. */
void lt_sdev_cfg_default(lt_sdev_cfg_t *c);

/* Trace and (unless direct) stream. Returns 0, or a nonzero device error code (also sent as the
 * END status): 1 bad configuration, 2 scene build failed, 3 camera failed. */
int lt_sdev_run(const lt_sdev_port_t *p, const lt_sdev_cfg_t *c, lt_sdev_result_t *r);

#ifdef __cplusplus
}
#endif
#endif /* LT_STREAM_DEV_H */
