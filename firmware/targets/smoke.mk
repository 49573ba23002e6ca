# smoke.mk - builds firmware/targets/hello.c for every firmware target into build/smoke/<T>/.
# Run from the repository root: make -f firmware/targets/smoke.mk  (used by smoke.sh).
# hello.elf returns 7; exit<N>.elf is the same program returning N (exit-code pass-through).

include firmware/targets/targets.mk

SMOKE_DIR := build/smoke
SMOKE_CODES := 0 42 255
# lt__memcpy/lt__memset live in the core (firmware/core/numerics/lt_mem.c); hello links that one file.
SMOKE_SRC := $(FW_TGT_DIR)/hello.c firmware/core/numerics/lt_mem.c

.PHONY: all
all: $(foreach T,$(FW_TARGETS),$(SMOKE_DIR)/$(T)/hello.elf \
    $(SMOKE_DIR)/$(T)/lt_rt.o $(SMOKE_DIR)/$(T)/lt_mem.o \
    $(foreach N,$(SMOKE_CODES),$(SMOKE_DIR)/$(T)/exit$(N).elf))

# $(1) = target, $(2) = image name, $(3) = extra flags
define SMOKE_IMAGE
$(SMOKE_DIR)/$(1)/$(2).elf: $(SMOKE_SRC) $(FW_RT_SRCS_$(1)) $(FW_RT_DEPS) firmware/targets/smoke.mk
	@mkdir -p $$(@D)
	$(CC_$(1)) $(FW_CFLAGS_COMMON) $(CFLAGS_$(1)) $(FW_INC) $(3) $(LDFLAGS_$(1)) \
	    -Wl,-Map,$$(@:.elf=.map) -o $$@ $(SMOKE_SRC) $(FW_RT_SRCS_$(1)) $(LDLIBS_$(1))
endef

# The memory functions alone, so smoke.sh can check their relocations (the images drop unused
# functions). $(1) = target, $(2) = source.
define SMOKE_OBJ
$(SMOKE_DIR)/$(1)/$(basename $(notdir $(2))).o: $(2) $(FW_RT_DEPS) firmware/targets/smoke.mk
	@mkdir -p $$(@D)
	$(CC_$(1)) $(FW_CFLAGS_COMMON) $(CFLAGS_$(1)) $(FW_INC) -c -o $$@ $$<
endef

$(foreach T,$(FW_TARGETS),$(eval $(call SMOKE_OBJ,$(T),$(FW_TGT_DIR)/common/lt_rt.c)) \
    $(eval $(call SMOKE_OBJ,$(T),firmware/core/numerics/lt_mem.c)))
$(foreach T,$(FW_TARGETS),$(eval $(call SMOKE_IMAGE,$(T),hello,)) \
    $(foreach N,$(SMOKE_CODES),$(eval $(call SMOKE_IMAGE,$(T),exit$(N),-DLT_FW_HELLO_RC=$(N)))))

# make -f firmware/targets/smoke.mk -s print-QEMU_cm4 prints a variable (used by smoke.sh).
print-%:
	@echo '$($*)'
