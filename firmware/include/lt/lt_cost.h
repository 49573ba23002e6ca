/* lt_cost.h - the cost hook: the only seam between the kernels and the cycle model.
 * LT_COST_MODE selects what the hooks become: LT_COST_OFF (firmware, host: nothing; the arguments are
 * still type-checked through sizeof), LT_COST_SIM (sim/: inline counter increments plus a cache-model
 * call per memory access), LT_COST_HANDLER (user macros, Musashi style). A kernel never knows which.
 * Hook arguments must have no side effects: in OFF mode they are not evaluated.
 */
#ifndef LT_COST_H
#define LT_COST_H

#include <stdint.h>
#include "lt_port.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LT_COST_OFF 0
#define LT_COST_SIM 1
#define LT_COST_HANDLER 2
#ifndef LT_COST_MODE
#define LT_COST_MODE LT_COST_OFF
#endif

/* Op classes (priced by a machine model). */
typedef enum lt_op {
#define LT_OP(name, unit, doc) LT_OP_##name,
#define LT_EV(name, doc)
#define LT_PH(name, doc)
#include "lt_ops.def"
#undef LT_OP
#undef LT_EV
#undef LT_PH
    LT_OP__COUNT
} lt_op_t;

/* Events (counted, never priced). */
typedef enum lt_ev {
#define LT_OP(name, unit, doc)
#define LT_EV(name, doc) LT_EV_##name,
#define LT_PH(name, doc)
#include "lt_ops.def"
#undef LT_OP
#undef LT_EV
#undef LT_PH
    LT_EV__COUNT
} lt_ev_t;

/* Phases (every count goes to the current phase). */
typedef enum lt_phase {
#define LT_OP(name, unit, doc)
#define LT_EV(name, doc)
#define LT_PH(name, doc) LT_PH_##name,
#include "lt_ops.def"
#undef LT_OP
#undef LT_EV
#undef LT_PH
    LT_PH__COUNT
} lt_phase_t;

/* Recipes (lt_recipes.def): the named tallies a kernel charges in one call. */
typedef enum lt_recipe {
#define LT_RECIPE(name, doc, ops) LT_RC_##name,
#include "lt_recipes.def"
#undef LT_RECIPE
    LT_RC__COUNT
} lt_recipe_t;

/* Number of counters kept per phase: ops first, then events. */
#define LT_CTR__COUNT ((int)LT_OP__COUNT + (int)LT_EV__COUNT)

#define LT_MEM_READ 0
#define LT_MEM_WRITE 1

#if LT_COST_MODE == LT_COST_OFF
#define LT_COST(op, n) ((void)sizeof(LT_OP_##op), (void)sizeof(n))
#define LT_EVENT(ev, n) ((void)sizeof(LT_EV_##ev), (void)sizeof(n))
#define LT_MEM(p, bytes, rw) ((void)sizeof(p), (void)sizeof(bytes), (void)sizeof(rw))
#define LT_PHASE_ENTER(ph) ((void)sizeof(LT_PH_##ph), LT_PH_OTHER)
#define LT_PHASE_LEAVE(prev) ((void)(prev))
#elif LT_COST_MODE == LT_COST_SIM
/* Counters of the current phase; sim/ points this at the right row on every phase change. */
extern uint64_t *lt__sim_cur;
void lt_sim_mem(const void *p, uint32_t bytes, int rw);
lt_phase_t lt_sim_phase(lt_phase_t ph);
/* 1 while the machine modelled runs the lane-by-lane kernels (LT_MACHINE_LANEWISE() in its file;
 * LT_LANEWISE(), lt_v16.h); set with the machine. */
extern int lt__sim_lanewise;
#define LT_COST(op, n) ((void)(lt__sim_cur[LT_OP_##op] += (uint64_t)(n)))
#define LT_EVENT(ev, n) ((void)(lt__sim_cur[(int)LT_OP__COUNT + LT_EV_##ev] += (uint64_t)(n)))
#define LT_MEM(p, bytes, rw) lt_sim_mem((const void *)(p), (uint32_t)(bytes), (rw))
#define LT_PHASE_ENTER(ph) lt_sim_phase(LT_PH_##ph)
#define LT_PHASE_LEAVE(prev) ((void)lt_sim_phase(prev))
#elif LT_COST_MODE == LT_COST_HANDLER
/* The user supplies LT_COST_HANDLER_FN(op, n), LT_EVENT_HANDLER_FN(ev, n),
 * LT_MEM_HANDLER_FN(p, bytes, rw) and LT_PHASE_HANDLER_FN(ph) (returning the previous phase). */
#define LT_COST(op, n) LT_COST_HANDLER_FN(LT_OP_##op, (n))
#define LT_EVENT(ev, n) LT_EVENT_HANDLER_FN(LT_EV_##ev, (n))
#define LT_MEM(p, bytes, rw) LT_MEM_HANDLER_FN((p), (bytes), (rw))
#define LT_PHASE_ENTER(ph) LT_PHASE_HANDLER_FN(LT_PH_##ph)
#define LT_PHASE_LEAVE(prev) ((void)LT_PHASE_HANDLER_FN(prev))
#else
#error "LT_COST_MODE must be LT_COST_OFF, LT_COST_SIM or LT_COST_HANDLER"
#endif

/* LT_CHARGE(R) charges recipe R of lt_recipes.def once, LT_CHARGE_N(R, n) n times (every op count of
 * the recipe times n). A kernel charges its scalar control and its own routines' fused lane work
 * only through these: each tally is defined once, with its reason, in lt_recipes.def. In OFF mode
 * nothing is evaluated; otherwise each recipe is an inline function of LT_COST increments (so in
 * HANDLER mode the handler macros must be defined before this header is included). */
#if LT_COST_MODE == LT_COST_OFF
#define LT_CHARGE_N(r, n) ((void)sizeof(LT_RC_##r), (void)sizeof(n))
#else
#define LT_R(op, k) LT_COST(op, (uint64_t)(k) * n_);
#define LT_RECIPE(name, doc, ops) \
    LT_INLINE void lt__charge_##name(uint64_t n_) { ops }
#include "lt_recipes.def"
#undef LT_RECIPE
#undef LT_R
#define LT_CHARGE_N(r, n) lt__charge_##r((uint64_t)(n))
#endif
#define LT_CHARGE(r) LT_CHARGE_N(r, 1)

/* Lane utilisation of a masked lane op: active lanes and one masked op. */
#define LT_UTIL(k) (LT_EVENT(LANES_ON, lt__popcount32((uint32_t)(k))), LT_EVENT(LANE_OPS, 1))

#ifdef __cplusplus
}
#endif
#endif /* LT_COST_H */
