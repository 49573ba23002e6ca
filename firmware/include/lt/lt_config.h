/* lt_config.h - every configuration knob of the core, each defined and documented once.
 * Override any of them with -D on the compiler command line; nothing else in the core tests them
 * before this header has given them a value. Builds: all.
 */
#ifndef LT_CONFIG_H
#define LT_CONFIG_H

/* LT_CFG_FLOAT32: 1 compiles the float32 numeric path (scalar and lane float ops, float kernels).
 * 0 gives a fixed-point-only core that links no float helper on soft-float targets (checked by
 * `make firmware` with nm on the rv32 image). Default 1. */
#ifndef LT_CFG_FLOAT32
#define LT_CFG_FLOAT32 1
#endif

/* LT_CFG_WT32: 1 lets a structure choose LT_ISECT_WT32 (lt_wt.h: the s15.16 watertight test on a
 * grid, 32-bit edge functions): the triangle-test dispatch of every walk (lt_isel.h) tests for it.
 * 0 leaves that test out (a walk then takes the exact test for LT_ISECT_WT32); the kernels
 * themselves are always compiled. Default 1; the firmware images whose instruction counts the
 * fitted MCU cycle models price are built with 0 (firmware/firmware.mk, docs/firmware.md). */
#ifndef LT_CFG_WT32
#define LT_CFG_WT32 1
#endif

/* LT_CFG_NO_STATUS_STRINGS: 1 drops the text table behind lt_status_str() (saves .rodata on MCUs);
 * lt_status_str() then returns "". Default 0. */
#ifndef LT_CFG_NO_STATUS_STRINGS
#define LT_CFG_NO_STATUS_STRINGS 0
#endif

/* LT_CFG_ASSERT: 1 makes LT_ASSERT trap (tests, ASan builds); 0 makes it vanish (release firmware).
 * Default 0. A user may instead define LT_ASSERT(x) themselves before including lt.h. */
#ifndef LT_CFG_ASSERT
#define LT_CFG_ASSERT 0
#endif

/* LT_CFG_GEOM_MAX_LOG2: world coordinates handed to the fixed-point triangle kernels must satisfy
 * |x| <= 2^LT_CFG_GEOM_MAX_LOG2 world units (s15.16). 12 (4096 units) keeps every product of the
 * Moller-Trumbore test inside int64 and leaves t headroom for the scene diagonal (see docs/numerics.md).
 * Host loaders scale each scene into this box. */
#ifndef LT_CFG_GEOM_MAX_LOG2
#define LT_CFG_GEOM_MAX_LOG2 12
#endif

/* LT_CFG_WT_F64_FALLBACK: 1 makes the float32 watertight test recompute, in double, the edge
 * functions of lanes where one of them came out exactly 0.0f (the paper's fallback; float x float
 * products are exact in double, so the recomputed signs are exact), and test zero area exactly in
 * double. 0 skips both for targets that must not link double (soft-float helpers): edge functions
 * that round to 0.0f are then taken as 0 (a ray through such a point hits both neighbours, never
 * neither, but vertices can leak in rare cases), and the zero-area test compares float products.
 * The s15.16 path never uses floating point. Default 1. (Knob kept here until the lead moves it to
 * lt_config.h.) */
#ifndef LT_CFG_WT_F64_FALLBACK
#define LT_CFG_WT_F64_FALLBACK 1
#endif

#if LT_CFG_ASSERT
#ifndef LT_ASSERT
#define LT_ASSERT(x) ((x) ? (void)0 : __builtin_trap())
#endif
#else
#ifndef LT_ASSERT
#define LT_ASSERT(x) ((void)0)
#endif
#endif

#endif /* LT_CONFIG_H */
