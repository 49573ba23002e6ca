# ssbench.mk - the screen-space baselines benchmark (docs/ss-baselines.md); included by the
# Makefile.
#   build/sim/ssbench    quadtree (n64, n32, f32) vs DDA vs Hi-Z (q30, f32) on the same rays, every
#                        lane op charged to the cycle model (lrb16): the table `make bench` prints
#   build/host/ssbench   the same program natively (LT_COST_OFF): host times without counting
# Usage: ssbench [--rays N] [--quick] (see --help). Rays come from lt_reproj.h when that module
# exists (firmware/include/lt/lt_reproj.h), else from the double-precision fallback in
# tests/unit/lt_ssb_testlib.h.
SSBENCH_REPROJ := $(if $(wildcard firmware/include/lt/lt_reproj.h firmware/core/screen/lt_reproj.c),\
    -DSSBENCH_HAVE_REPROJ=1,)
define ssbench_rules
$(B)/$(1)/obj/tests/bench/ssbench.o: tests/bench/ssbench.c Makefile tests/ssbench.mk | $(B)/gen/lt_machines.inc
	@mkdir -p $$(@D)
	@echo "CC [$(1)] $$<"
	@$(CC) $(CFLAGS_$(1)) $(TEST_INC) $(SSBENCH_REPROJ) -c $$< -o $$@
$(B)/$(1)/ssbench: $(B)/$(1)/obj/tests/bench/ssbench.o $$($(1)_CORE_OBJS) $$($(1)_HOST_OBJS) \
    $$($(1)_EXTRA_OBJS)
	@echo "LD $$@"
	@$(CC) $(LDFLAGS_$(1)) -o $$@ $$^ $(LIBS_$(1))
endef
$(foreach v,host sim,$(eval $(call ssbench_rules,$(v))))
ssbench: $(B)/sim/ssbench $(B)/host/ssbench
EXTRA_TEST_BINS += $(B)/sim/ssbench $(B)/host/ssbench
# `make bench` runs build/sim/ssbench (tests/bench/bench.sh): build it first
bench: $(B)/sim/ssbench
.PHONY: ssbench
