/* lt_tri_loop.h - a deterministic loop of ray-triangle tests shared by the firmware image measured
 * with QEMU's instruction-count plugin (tests/fw/fw_tri.c) and the sim run that predicts the same
 * calls with a machine model (tests/bench/tri_model.c); the triangle twin of lt_slab_loop.h. The
 * float32 twin (tests/fw/fw_tri_f32.c) prices the soft-float kernel on rv32.
 * Freestanding.
 */
#ifndef LT_TRI_LOOP_H
#define LT_TRI_LOOP_H

#include <stdint.h>

/* Run `calls` calls of lt_tri16_q16 on pseudo-random ray packets (a new packet every 4 calls) and
 * triangles (front- and back-facing, hit by some, all or none of the lanes). Returns the total of
 * lanes whose ray was shortened. Only lt_tri16_q16 charges costs: the input generation is plain C
 * (the rays' reciprocals, unused by the triangle test, are not computed). */
uint32_t lt_tri_loop(int calls);

/* The same calls of lt_tri16_f32 on the same rays and triangles, each value converted to the
 * nearest float with integer operations only (lt_f32_bits.h). Builds with LT_CFG_FLOAT32 only. */
uint32_t lt_tri_loop_f32(int calls);

#endif /* LT_TRI_LOOP_H */
