/* lt_stage.h - the stages the firmware apps tell their clock about, shared by the scene and frusta
 * blobs (lt_sblob.h) and the reprojection app (reproj_app.h). A firmware clock marks them for the
 * QEMU plugin's cycle model (lt_fw_stage, docs/qemu-plugin.md); the host's simulator build charges
 * the cycles between two calls to the stage begun by the first (lt-fwmodel, tools/fw_cycles.sh),
 * so both sides split a run at the same points. The values are the plugin's stage numbers.
 * Builds: all (freestanding C99). */
#ifndef LT_STAGE_H
#define LT_STAGE_H

#include <stdint.h>

enum {
    LT_STAGE_UNTIMED = 0,   /* anything else: set-up, hashing, output */
    LT_STAGE_PRIMARY = 1,   /* primary rays as 16-ray packets (BVH) */
    LT_STAGE_SHADOW = 2,    /* shadow rays as 16-ray packets (BVH, any hit) */
    LT_STAGE_PRIMARY1 = 3,  /* primary rays one by one */
    LT_STAGE_SHADOW1 = 4,   /* shadow rays one by one */
    LT_STAGE_FRUSTA = 5,    /* multi-frusta shadow samples (set-up and walk) */
    LT_STAGE_QT_BUILD = 6,  /* the screen-space quadtree build */
    LT_STAGE_REPROJ = 7,    /* reprojection rays (set-up and quadtree walk) */
    LT_STAGE__COUNT = 8
};

/* A tracer's clock: returns the ticks so far and notes that stage begins now. */
typedef uint64_t (*lt_sblob_clock_fn)(uint32_t stage);

#endif
