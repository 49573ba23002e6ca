/* lt_fw_count.h - on-target counting (LT_COST_MODE = LT_COST_HANDLER): the firmware build of the
 * streaming device (build/fw/<T>/stream-count.elf) compiles the core with this header forced in
 * (-include), so every cost hook of the kernels calls the handlers below. They price each op at
 * the issue cycles of the target's machine model (sim/machines/<machine>.def, turned into
 * lt_fwc_issue[] by the build: mcu-m4 for cm4 and cm55, rv32imac for rv32) and count the events
 * the stream reports carry. Memory accesses add nothing: both models are single-cycle SRAM, where
 * the simulator's stall (access latency minus the L1 hit) is 0, so the counts equal what the
 * simulator acting as the device reports (tests/run.d/stream.sh). Phases are not kept.
 * Builds: firmware (freestanding).
 */
#ifndef LT_FW_COUNT_H
#define LT_FW_COUNT_H

#include <stdint.h>

/* The counters since boot. */
typedef struct lt_fwc {
    uint64_t cycles;              /* sum over ops of count x issue cycles */
    uint64_t aabb, aabb_rays;     /* events AABB, AABB_RAYS */
    uint64_t tris, tri_rays;      /* events TRIS, TRI_RAYS */
} lt_fwc_t;

extern lt_fwc_t lt_fwc;
extern const uint16_t lt_fwc_issue[]; /* [LT_OP__COUNT], generated from the machine file */
extern const char lt_fwc_machine[];   /* the machine's name */

void lt_fwc_cost(int op, uint64_t n);
void lt_fwc_event(int ev, uint64_t n);
int lt_fwc_phase(int ph);

#define LT_COST_HANDLER_FN(op, n) lt_fwc_cost((int)(op), (uint64_t)(n))
#define LT_EVENT_HANDLER_FN(ev, n) lt_fwc_event((int)(ev), (uint64_t)(n))
#define LT_MEM_HANDLER_FN(p, bytes, rw) ((void)(p), (void)(bytes), (void)(rw))
#define LT_PHASE_HANDLER_FN(ph) ((lt_phase_t)lt_fwc_phase((int)(ph)))

#endif /* LT_FW_COUNT_H */
