/* lt_machines.h - one pass over the machine models: every file sim/machines/<name>.def, in file
 * name order. The list is not written by hand: the Makefile generates lt_machines.inc (in
 * $(B)/gen, on the include path) from the .def files found in sim/machines/ and rewrites it when
 * the set of files changes, so adding a machine is adding its file (docs/cost-model.md).
 *
 * A machine file holds, in this order:
 *   LT_MACHINE(id, "name", "description", clock_mhz, lanes)   id: a C identifier, unique
 *   LT_MACHINE_CACHE(L1, "sets:ways:line", hit_cycles)         L1 required
 *   LT_MACHINE_CACHE(L2, "sets:ways:line" or NULL, hit_cycles) optional; NULL: no L2
 *   LT_MACHINE_MEM(cycles)                                     a memory access
 *   LT_MACHINE_LANEWISE()                                      optional: the target's firmware
 *       runs the packet kernels that have a lane-by-lane form that way (LT_LANEWISE(), lt_v16.h:
 *       the Arm DSP builds, Cortex-M4 and Cortex-M55), so the simulator charges that form when
 *       modelling it
 *   LT_OP_COST(op, latency, issue)                             every LT_OP of lt/lt_ops.def
 *   LT_MACHINE_QT(enc, build, rest)                            n64, n32 and f32: simulated cycles
 *       per pixel of a quadtree reprojection, build per source pixel and the rest (ray set-up,
 *       traversal) per target pixel, measured by tests/bench/qtcal.sh; lanetrace info and
 *       reproject weigh the node formats with them (host/tune/lt_recommend.c)
 * and the generated list closes each file with LT_MACHINE_END.
 *
 * Use: define the macros a pass needs (the others expand to nothing), include this file; it
 * undefines all six afterwards, so it can be included once per pass (no include guard).
 * Builds: host, sim, asan (data only; the names need no simulator).
 */
#ifndef LT_MACHINE
#define LT_MACHINE(id, name, desc, clock_mhz, lanes)
#endif
#ifndef LT_MACHINE_CACHE
#define LT_MACHINE_CACHE(level, spec, hit)
#endif
#ifndef LT_MACHINE_MEM
#define LT_MACHINE_MEM(cycles)
#endif
#ifndef LT_MACHINE_LANEWISE
#define LT_MACHINE_LANEWISE()
#endif
#ifndef LT_OP_COST
#define LT_OP_COST(op, latency, issue)
#endif
#ifndef LT_MACHINE_QT
#define LT_MACHINE_QT(enc, build, rest)
#endif
#ifndef LT_MACHINE_END
#define LT_MACHINE_END
#endif

#include "lt_machines.inc"

#undef LT_MACHINE
#undef LT_MACHINE_CACHE
#undef LT_MACHINE_MEM
#undef LT_MACHINE_LANEWISE
#undef LT_OP_COST
#undef LT_MACHINE_QT
#undef LT_MACHINE_END
