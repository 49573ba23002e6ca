# firmware.mk - freestanding images of the core for each QEMU target (included by the Makefile).
# Every image comes from one template, fw_image: its own sources + the core + the target runtime.
#   build/fw/<T>/vectors.elf   the cross-target test vectors (tests/fw/fw_vectors.c)
#   build/fw/<T>/slab.elf      the slab-test kernel loop measured by the QEMU plugin (tests/fw/fw_slab.c)
#   build/fw/<T>/frusta.elf    the shared shadow-tile workload (tests/fw/fw_frusta.c)
#   build/fw/<T>/reproj.elf    the shared 64 x 64 reprojection workload (tests/fw/fw_reproj.c)
#   build/fw/<T>/stream.elf    the streaming firmware (firmware/apps/stream_fw.c; docs/stream.md)
#   build/fw/rv32/vectors-fixed.elf  LT_CFG_FLOAT32=0: must link no soft-float helper
# `make firmware` builds them, then tools/check_fw.sh fails on any libc or lt_sim_ symbol, and
# prints .text/.data/.bss per image.

FW_CORE_SRCS := $(CORE_SRCS)

# image name -> its own sources (besides the core and the target runtime)
FW_IMG_vectors := tests/fw/fw_vectors.c $(VEC_SRCS)
FW_IMG_slab := tests/fw/fw_slab.c tests/vectors/lt_slab_loop.c
FW_IMG_frusta := tests/fw/fw_frusta.c
FW_IMG_reproj := tests/fw/fw_reproj.c
FW_IMG_stream := firmware/apps/stream_fw.c firmware/apps/stream_dev.c
FW_IMG_opcal := tests/fw/fw_opcal.c
FW_IMG_tri := tests/fw/fw_tri.c tests/vectors/lt_tri_loop.c

# Object rules per target and object directory ($(2): obj, or objx for LT_CFG_FLOAT32=0 builds,
# whose extra flags are $(3)). The include path follows the room of the source.
define fw_obj_rules
$(B)/fw/$(1)/$(2)/firmware/core/%.o: FW_SRC_INC := -Ifirmware/include -Ifirmware/core
$(B)/fw/$(1)/$(2)/firmware/apps/%.o: FW_SRC_INC := -Ifirmware/include -Ifirmware/apps \
    -I$(FW_TGT_DIR)/common
$(B)/fw/$(1)/$(2)/tests/%.o: FW_SRC_INC := -Ifirmware/include -I$(FW_TGT_DIR)/common -Itests/vectors
$(B)/fw/$(1)/$(2)/firmware/targets/%.o: FW_SRC_INC := -Ifirmware/include -I$(FW_TGT_DIR)/common
$(B)/fw/$(1)/$(2)/%.o: %.c Makefile
	@mkdir -p $$(@D)
	@echo "CC [$(1)] $$<"
	@$(CC_$(1)) $(FW_CFLAGS_COMMON) $(DEPFLAGS) $(FPFLAGS) $(CFLAGS_$(1)) $$(FW_SRC_INC) \
	    -DLT_COST_MODE=LT_COST_OFF $(3) -c $$< -o $$@
$(B)/fw/$(1)/$(2)/%.o: %.S $(FW_RT_DEPS)
	@mkdir -p $$(@D)
	@echo "AS [$(1)] $$<"
	@$(CC_$(1)) $(CFLAGS_$(1)) $(FW_INC) -c $$< -o $$@
endef

fw_objs = $(patsubst %.S,$(B)/fw/$(1)/$(2)/%.o,$(3:%.c=$(B)/fw/$(1)/$(2)/%.o))

# The one image template: $(1) target, $(2) image name, $(3) object directory, $(4) file suffix.
define fw_image
$(B)/fw/$(1)/$(2)$(4).elf: $(call fw_objs,$(1),$(3),$(FW_IMG_$(2)) $(FW_CORE_SRCS) $(FW_RT_SRCS_$(1)))
	@echo "LD $$@"
	@$(CC_$(1)) $(LDFLAGS_$(1)) -Wl,-Map=$$@.map -o $$@ $$^ $(LDLIBS_$(1))
endef

$(foreach t,$(FW_TARGETS),$(eval $(call fw_obj_rules,$(t),obj,)) \
    $(eval $(call fw_obj_rules,$(t),objx,-DLT_CFG_FLOAT32=0)))
FW_ALL_IMAGES := vectors slab frusta reproj stream
$(foreach t,$(FW_TARGETS),$(foreach i,$(FW_ALL_IMAGES),$(eval $(call fw_image,$(t),$(i),obj,))))
$(eval $(call fw_image,rv32,vectors,objx,-fixed))
$(foreach i,opcal tri,$(eval $(call fw_image,cm4,$(i),obj,)))
# kept for the fragments that link their own images against the core and runtime objects
$(foreach t,$(FW_TARGETS),$(eval fw_$(t)_CORE := $(call fw_objs,$(t),obj,$(FW_CORE_SRCS))) \
    $(eval fw_$(t)_RT := $(call fw_objs,$(t),obj,$(FW_RT_SRCS_$(t)))))

FW_IMAGES := $(foreach t,$(FW_TARGETS),$(foreach i,$(FW_ALL_IMAGES),$(B)/fw/$(t)/$(i).elf)) \
    $(B)/fw/rv32/vectors-fixed.elf

firmware: $(FW_IMAGES)
	@tools/check_fw.sh $(FW_IMAGES)
