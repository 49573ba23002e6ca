/* lt_slab_loop.h - a deterministic loop of slab tests shared by the firmware image measured with
 * QEMU's instruction-count plugin (tests/fw/fw_slab.c) and the sim run that predicts the same
 * calls with the mcu-m4 model (tests/bench/slab_model.c). Freestanding.
 */
#ifndef LT_SLAB_LOOP_H
#define LT_SLAB_LOOP_H

#include <stdint.h>

/* Run `calls` slab tests on pseudo-random packets and boxes; returns the total of hit lanes. Only
 * lt_slab16_q16 charges costs: the input generation is plain C. */
uint32_t lt_slab_loop(int calls);

#endif /* LT_SLAB_LOOP_H */
