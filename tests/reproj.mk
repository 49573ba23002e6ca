# reproj.mk - reprojection ray generation and view synthesis (docs/reproject.md); included by the
# top-level Makefile. The core (firmware/core/lt_reproj.c), the host library
# (host/lt_reproject*.c) and the unit test (tests/unit/test_reproj.c) are auto-discovered; this
# fragment adds the firmware image of the shared 64 x 64 reprojection workload:
#   build/fw/<T>/reproj.elf   tests/fw/fw_reproj.c under QEMU (cm4, cm55, rv32); `make test` runs
#                             it and compares its hash with the host unit test (tests/run.d/reproject.sh)
define reproj_fw_rules
$(B)/fw/$(1)/obj/tests/fw/fw_reproj.o: tests/vectors/lt_reproj_tile.h
$(B)/fw/$(1)/reproj.elf: $(B)/fw/$(1)/obj/tests/fw/fw_reproj.o $$(fw_$(1)_CORE) $$(fw_$(1)_RT)
	@echo "LD $$@"
	@$(CC_$(1)) $(LDFLAGS_$(1)) -o $$@ $$^ $(LDLIBS_$(1))
endef
$(foreach t,$(FW_TARGETS),$(eval $(call reproj_fw_rules,$(t))))
REPROJ_FW_IMAGES := $(foreach t,$(FW_TARGETS),$(B)/fw/$(t)/reproj.elf)
$(B)/host/obj/tests/unit/test_reproj.o $(B)/sim/obj/tests/unit/test_reproj.o \
    $(B)/asan/obj/tests/unit/test_reproj.o: tests/vectors/lt_reproj_tile.h
EXTRA_TEST_BINS += $(REPROJ_FW_IMAGES)
reproj-fw: $(REPROJ_FW_IMAGES)
.PHONY: reproj-fw
