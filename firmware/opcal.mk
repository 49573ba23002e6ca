# opcal.mk - images and host predictors for calibrating the scalar machine models from QEMU
# instruction counts (included by the Makefile; `make opcal` builds them, `make bench` uses them):
#   cm4 (sim/machines/mcu_m4.def) and rv32 (sim/machines/rv32imac.def), each with
#   build/fw/<T>/opcal.elf  op-class microbenchmarks (tests/fw/fw_opcal.c; firmware.mk's template)
#   build/fw/<T>/tri.elf    the ray-triangle loop of tests/vectors/lt_tri_loop.c under QEMU
#   build/fw/<T>/slab.elf   the slab-test loop (firmware.mk builds it for every target)
#   build/fw/rv32/tri_f32.elf, slab_f32.elf  their float32 twins (soft float on rv32)
#   build/sim/tri-model     the sim's prediction for the same loops (tests/bench/tri_model.c)
#   build/sim/slab-model    idem for the slab loops (tests/bench/slab_model.c; rule in the Makefile)
# tests/bench/opcal.sh [cm4|rv32] builds these and prints the calibration tables.

FW_IMG_tri_f32 := tests/fw/fw_tri_f32.c tests/vectors/lt_tri_loop.c
FW_IMG_slab_f32 := tests/fw/fw_slab_f32.c tests/vectors/lt_slab_loop.c
$(foreach i,opcal tri tri_f32 slab_f32,$(eval $(call fw_image,rv32,$(i),obj,)))

$(B)/sim/tri-model: $(B)/sim/obj/tests/bench/tri_model.o $(B)/sim/obj/tests/vectors/lt_tri_loop.o \
    $(sim_CORE_OBJS) $(sim_EXTRA_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_sim)

OPCAL_cm4 := $(B)/fw/cm4/opcal.elf $(B)/fw/cm4/tri.elf $(B)/fw/cm4/slab.elf
OPCAL_rv32 := $(B)/fw/rv32/opcal.elf $(B)/fw/rv32/tri.elf $(B)/fw/rv32/slab.elf \
    $(B)/fw/rv32/tri_f32.elf $(B)/fw/rv32/slab_f32.elf
OPCAL_HOST := $(B)/sim/tri-model $(B)/sim/slab-model $(PLUGIN_SO)

opcal: $(OPCAL_cm4) $(OPCAL_rv32) $(OPCAL_HOST)
opcal-cm4: $(OPCAL_cm4) $(OPCAL_HOST)
opcal-rv32: $(OPCAL_rv32) $(OPCAL_HOST)

.PHONY: opcal opcal-cm4 opcal-rv32
