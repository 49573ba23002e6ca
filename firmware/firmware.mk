# firmware.mk - freestanding images of the core for each QEMU target (included by the Makefile).
#   build/fw/<T>/vectors.elf   the cross-target test vectors (tests/fw/fw_vectors.c)
#   build/fw/<T>/slab.elf      the slab-test kernel loop measured by the QEMU plugin (tests/fw/fw_slab.c)
#   build/fw/rv32/vectors-fixed.elf  LT_CFG_FLOAT32=0: must link no soft-float helper
# `make firmware` builds them, then tools/check_fw.sh fails on any libc or lt_sim_ symbol, and
# prints .text/.data/.bss per target.

FW_CORE_SRCS := $(CORE_SRCS)
FW_APP_SRCS := $(VEC_SRCS)

define fw_rules
$(B)/fw/$(1)/obj/%.o: %.c $(CORE_HDRS) $(FW_RT_DEPS) tests/vectors/lt_vec.h tests/vectors/lt_slab_loop.h
	@mkdir -p $$(@D)
	@echo "CC [$(1)] $$<"
	@$(CC_$(1)) $(FW_CFLAGS_COMMON) $(FPFLAGS) $(CFLAGS_$(1)) -Itests/vectors -DLT_COST_MODE=LT_COST_OFF -c $$< -o $$@
$(B)/fw/$(1)/obj/%.o: %.S $(FW_RT_DEPS)
	@mkdir -p $$(@D)
	@echo "AS [$(1)] $$<"
	@$(CC_$(1)) $(CFLAGS_$(1)) -c $$< -o $$@
$(B)/fw/$(1)/objx/%.o: %.c $(CORE_HDRS) $(FW_RT_DEPS) tests/vectors/lt_vec.h tests/vectors/lt_slab_loop.h
	@mkdir -p $$(@D)
	@echo "CC [$(1)] $$<"
	@$(CC_$(1)) $(FW_CFLAGS_COMMON) $(FPFLAGS) $(CFLAGS_$(1)) -Itests/vectors -DLT_COST_MODE=LT_COST_OFF -DLT_CFG_FLOAT32=0 -c $$< -o $$@
fw_$(1)_RT := $(patsubst %.S,$(B)/fw/$(1)/obj/%.o,$(FW_RT_SRCS_$(1):%.c=$(B)/fw/$(1)/obj/%.o))
fw_$(1)_CORE := $(FW_CORE_SRCS:%.c=$(B)/fw/$(1)/obj/%.o)
$(B)/fw/$(1)/vectors.elf: $(B)/fw/$(1)/obj/tests/fw/fw_vectors.o $(B)/fw/$(1)/obj/tests/vectors/lt_vec.o \
    $$(fw_$(1)_CORE) $$(fw_$(1)_RT)
	@echo "LD $$@"
	@$(CC_$(1)) $(LDFLAGS_$(1)) -Wl,-Map=$$@.map -o $$@ $$^ $(LDLIBS_$(1))
$(B)/fw/$(1)/vectors-fixed.elf: $(B)/fw/$(1)/objx/tests/fw/fw_vectors.o $(B)/fw/$(1)/objx/tests/vectors/lt_vec.o \
    $(FW_CORE_SRCS:%.c=$(B)/fw/$(1)/objx/%.o) $$(fw_$(1)_RT)
	@echo "LD $$@"
	@$(CC_$(1)) $(LDFLAGS_$(1)) -o $$@ $$^ $(LDLIBS_$(1))
$(B)/fw/$(1)/slab.elf: $(B)/fw/$(1)/obj/tests/fw/fw_slab.o $(B)/fw/$(1)/obj/tests/vectors/lt_slab_loop.o \
    $$(fw_$(1)_CORE) $$(fw_$(1)_RT)
	@echo "LD $$@"
	@$(CC_$(1)) $(LDFLAGS_$(1)) -o $$@ $$^ $(LDLIBS_$(1))
endef
$(foreach t,$(FW_TARGETS),$(eval $(call fw_rules,$(t))))

FW_IMAGES := $(foreach t,$(FW_TARGETS),$(B)/fw/$(t)/vectors.elf $(B)/fw/$(t)/slab.elf) \
    $(B)/fw/rv32/vectors-fixed.elf

firmware: $(FW_IMAGES)
	@tools/check_fw.sh $(FW_IMAGES)
