/* lt_meter.h - what host programs need from the cycle model, without depending on it. The
 * simulator build links sim/lt_meter_sim.c (sim/lt_sim.c behind it); the native and ASan builds
 * link host/render/lt_meter_null.c: lt_meter_available() is 0, nothing is counted (totals are zeros),
 * reports print nothing. The kernels themselves charge through lt/lt_cost.h, not through here.
 * Machine names (sim/machines/<name>.def) are known in every build; their clocks, caches and op
 * prices only where the cycle model is linked. Host only.
 */
#ifndef LT_METER_H
#define LT_METER_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "io/lt_diag.h"
#include "lt/lt_cost.h"

/* 1 in the simulator build (cycles are counted), 0 in the native and ASan builds. */
int lt_meter_available(void);

/* ---- machines ------------------------------------------------------------------------------ */

/* Machine i's name (i from 0, file name order), NULL past the last. Every build. */
const char *lt_meter_machine_name(int i);

/* 1 when name is a machine's name. Every build. */
int lt_meter_machine_known(const char *name);

/* The names as one string for messages and usage texts: "lrb16, mcu-m4". Every build. */
const char *lt_meter_machine_names(void);

typedef struct lt_meter_machine {
    const char *name;
    const char *desc;               /* one line */
    uint32_t clock_mhz;
    uint32_t lanes;
    const char *l1, *l2;            /* "sets:ways:line"; l2 NULL: no L2 */
    uint32_t l1_hit, l2_hit, mem;   /* load-to-use cycles: L1 hit, L2 hit, memory */
    const uint16_t *latency;        /* [LT_OP__COUNT]: cycles until the result is usable */
    const uint16_t *issue;          /* [LT_OP__COUNT]: cycles charged per op */
} lt_meter_machine_t;

/* The machine called name in full. Returns 0, or -1 when the name is unknown or the build has no
 * cycle model (then *m is zeroed). */
int lt_meter_machine_info(const char *name, lt_meter_machine_t *m);

/* ---- a metered run ------------------------------------------------------------------------- */

/* Select the machine and build its caches (l1/l2 "sets:ways:line" override the machine's when
 * non-NULL); counters reset. Returns 0, or -1 with a message in diag (an unknown machine, a bad
 * cache spec). Without a cycle model only the name is checked and the cache specs are ignored. */
int lt_meter_init(const char *machine, const char *l1, const char *l2, lt_diag_t *diag);

/* Zero the counters, invalidate the caches (machine kept). */
void lt_meter_reset(void);

/* Release the caches and forget the regions. */
void lt_meter_shutdown(void);

/* Charge the memory accesses inside [base, base + bytes) at sim_base + offset, so cache results
 * do not depend on where the allocator put the data (lt_sim_region). No-op without a model. */
void lt_meter_region(const void *base, size_t bytes, uint64_t sim_base);

/* Cycles charged so far, all phases (0 without a model). Cheap enough per packet. */
uint64_t lt_meter_cycles(void);

/* Total of one event (LT_EV_*) over all phases so far (0 without a model). */
uint64_t lt_meter_event(int ev);

typedef struct lt_meter_totals {
    uint64_t cycles[LT_PH__COUNT];  /* per phase: issue cycles + memory stalls */
    uint64_t total_cycles;
    uint64_t events[LT_EV__COUNT];  /* over all phases */
    uint64_t l1_acc, l1_hit, l2_acc, l2_hit;
} lt_meter_totals_t;

/* The counters so far (zeros without a model). */
void lt_meter_totals(lt_meter_totals_t *t);

/* The cycle report as a table on f; rays = rays traced (for rays/s). Prints nothing without a
 * model. */
void lt_meter_report_text(FILE *f, const char *title, uint64_t rays);

/* The same report as a JSON string (free() it), extra_json's members merged in; NULL without a
 * model or out of memory. */
char *lt_meter_report_json(const char *title, uint64_t rays, const char *extra_json);

#endif /* LT_METER_H */
