/* lt_slab_loop.h - a deterministic loop of slab tests shared by the firmware image measured with
 * QEMU's instruction-count plugin (tests/fw/fw_slab.c) and the sim run that predicts the same
 * calls with a machine model (tests/bench/slab_model.c); the float32 twin (tests/fw/fw_slab_f32.c)
 * prices the soft-float kernel on rv32. Freestanding.
 */
#ifndef LT_SLAB_LOOP_H
#define LT_SLAB_LOOP_H

#include <stdint.h>

/* Run `calls` slab tests on pseudo-random packets and boxes; returns the total of hit lanes. Only
 * lt_slab16_q16 charges costs: the input generation is plain C. */
uint32_t lt_slab_loop(int calls);

/* The same calls of lt_slab16_f32 on the same rays and boxes, each value converted to the nearest
 * float with integer operations only (lt_f32_bits.h). Builds with LT_CFG_FLOAT32 only. */
uint32_t lt_slab_loop_f32(int calls);

#endif /* LT_SLAB_LOOP_H */
