# fwmodel.mk - lt-fwmodel (tests/fw/fw_model.c), simulator build only: a machine model's
# prediction of a firmware blob's run, stage by stage, set against the QEMU plugin's modelled
# cycles of the images by tools/fw_cycles.sh (docs/firmware.md, "Cycle models").
$(B)/sim/lt-fwmodel: $(B)/sim/obj/tests/fw/fw_model.o $(B)/sim/obj/firmware/apps/reproj_app.o \
    $(sim_CORE_OBJS) $(sim_HOST_OBJS) $(sim_EXTRA_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_sim)
EXTRA_TEST_BINS += $(B)/sim/lt-fwmodel
