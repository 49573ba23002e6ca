# opcal.mk - images and host predictors for calibrating sim/machines/mcu_m4.def (included by the
# Makefile; `make opcal` builds them, `make bench` uses them):
#   build/fw/cm4/opcal.elf  op-class microbenchmarks (tests/fw/fw_opcal.c; firmware.mk's template)
#   build/fw/cm4/tri.elf    the ray-triangle loop of tests/vectors/lt_tri_loop.c under QEMU
#   build/sim/tri-model     the sim's prediction for the same loop (tests/bench/tri_model.c)
# tests/bench/opcal.sh builds these and prints the calibration tables.

$(B)/sim/tri-model: $(B)/sim/obj/tests/bench/tri_model.o $(B)/sim/obj/tests/vectors/lt_tri_loop.o \
    $(sim_CORE_OBJS) $(sim_EXTRA_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_sim)

opcal: $(B)/fw/cm4/opcal.elf $(B)/fw/cm4/tri.elf $(B)/sim/tri-model $(B)/fw/cm4/slab.elf \
    $(B)/sim/slab-model $(PLUGIN_SO)

.PHONY: opcal
