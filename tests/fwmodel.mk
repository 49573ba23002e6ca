# fwmodel.mk - the firmware cycle models (docs/firmware.md, "Cycle models"): lt-fwmodel
# (tests/fw/fw_model.c, simulator build only), a machine model's prediction of a firmware blob's
# run, stage by stage, set against the QEMU plugin's modelled cycles of the images by
# tools/fw_cycles.sh; the calibration images (firmware.mk, make fw-cal) are built for make test
# (tests/run.d/fwcycles.sh) and `make fw-cycles` writes the residual table into the docs.
$(B)/sim/lt-fwmodel: $(B)/sim/obj/tests/fw/fw_model.o $(B)/sim/obj/firmware/apps/reproj_app.o \
    $(sim_CORE_OBJS) $(sim_HOST_OBJS) $(sim_EXTRA_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_sim)
EXTRA_TEST_BINS += $(B)/sim/lt-fwmodel $(FW_CAL_IMAGES)

fw-cycles: $(B)/sim/lt-fwmodel $(PLUGIN_SO) firmware fw-cal $(FW_SHARED_IMAGES)
	@B=$(B) tools/fw_cycles.sh >$(B)/fw-cycles.md
	@cat $(B)/fw-cycles.md
	@tools/doc_insert.sh fw-cycles $(B)/fw-cycles.md docs/firmware.md
.PHONY: fw-cycles
