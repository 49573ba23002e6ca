/* lt_sim.h - the C-only cycle model behind LT_COST_MODE == LT_COST_SIM: per-phase counters of the
 * op classes and events in lt_ops.def, a cache hierarchy fed by LT_MEM addresses, machine tables
 * (sim/machines/<name>.def) and the cycle report (text table and JSON).
 * Host only. The sim is single-threaded per process: it charges one global active core.
 */
#ifndef LT_SIM_H
#define LT_SIM_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "io/lt_diag.h"
#include "lt/lt_cost.h"

typedef struct lt_machine {
    const char *name;             /* e.g. "lrb16" */
    const char *desc;             /* one line for reports */
    uint32_t clock_mhz;           /* modelled clock */
    uint32_t lanes;               /* SIMD lanes */
    int lanewise;                 /* LT_MACHINE_LANEWISE(): charge the lane-by-lane forms */
    uint16_t latency[LT_OP__COUNT]; /* cycles until a result is usable (informational) */
    uint16_t issue[LT_OP__COUNT];   /* cycles the op occupies its unit: what is charged */
    const char *l1;               /* "sets:ways:line" */
    const char *l2;               /* "sets:ways:line" or NULL for no L2 */
    uint32_t l1_hit, l2_hit, mem; /* load-to-use cycles of an L1 hit, L2 hit, memory access */
} lt_machine_t;

/* NULL-terminated list of the machines: one per file sim/machines/<name>.def, in file name order
 * (the Makefile lists the files; see lt_machines.h). */
extern const lt_machine_t *const lt_sim_machines[];

/* The machine called name, or NULL. */
const lt_machine_t *lt_sim_machine_find(const char *name);

/* Select the machine and build its caches (l1/l2 override the machine's specs when non-NULL).
 * Resets all counters. Returns 0, or -1 with a message naming the bad spec in diag. */
int lt_sim_init(const lt_machine_t *m, const char *l1, const char *l2, lt_diag_t *diag);

/* Zero counters and invalidate caches (machine kept). */
void lt_sim_reset(void);

/* Release the caches. */
void lt_sim_shutdown(void);

/* Memory regions: LT_MEM addresses inside [base, base + bytes) are charged at
 * (sim_base + offset), so cache behaviour does not depend on where the host allocator or ASLR put
 * the data. sim_base should be line-aligned. At most 16 regions; returns -1 when full. */
int lt_sim_region(const void *base, size_t bytes, uint64_t sim_base);

/* Totals after a run. */
typedef struct lt_sim_totals {
    uint64_t ctr[LT_PH__COUNT][LT_CTR__COUNT]; /* op and event counts per phase */
    uint64_t memstall[LT_PH__COUNT];          /* cycles waiting on L2/memory per phase */
    uint64_t cycles[LT_PH__COUNT];            /* issue cycles + memory stalls per phase */
    uint64_t total_cycles;
    uint64_t l1_acc, l1_hit, l2_acc, l2_hit;
} lt_sim_totals_t;

void lt_sim_totals(lt_sim_totals_t *t);

/* Names from lt_ops.def. */
const char *lt_sim_op_name(int op);
const char *lt_sim_ev_name(int ev);
const char *lt_sim_phase_name(int ph);

/* Print the cycle report as a readable table; rays = rays traced (for rays/s). */
void lt_sim_report_text(FILE *f, const char *title, uint64_t rays);

/* Write the same report as JSON (cJSON). Returns 0 or -1 (message in diag). */
int lt_sim_report_json(const char *path, const char *title, uint64_t rays, const char *extra_json,
                       lt_diag_t *diag);

/* The report as a cJSON-printed string (caller frees with free()); extra_json (may be NULL) is an
 * object string whose members are merged in. */
char *lt_sim_report_json_string(const char *title, uint64_t rays, const char *extra_json);

/* Total cycles charged so far (all phases): cheap enough to sample per packet for per-pixel cost
 * images. */
uint64_t lt_sim_cycles_total(void);

/* Total of one event (LT_EV_*) over all phases so far. */
uint64_t lt_sim_event_total(int ev);

/* The selected machine (NULL before lt_sim_init). */
const lt_machine_t *lt_sim_machine(void);

#endif /* LT_SIM_H */
