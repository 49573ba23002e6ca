# reproj.mk - reprojection ray generation and view synthesis (docs/reproject.md); included by the
# top-level Makefile. The core (firmware/core/screen/lt_reproj.c), the host library
# (host/render/lt_reproject.c, host/cli/lt_reproject_cli.c) and the unit test
# (tests/unit/test_reproj.c) are auto-discovered; the firmware image of the shared 64 x 64
# reprojection workload, build/fw/<T>/reproj.elf (tests/fw/fw_reproj.c), comes from firmware.mk's
# image template. `make test` runs it and compares its hash with the host unit test
# (tests/run.d/reproject.sh).
REPROJ_FW_IMAGES := $(foreach t,$(FW_TARGETS),$(B)/fw/$(t)/reproj.elf)
EXTRA_TEST_BINS += $(REPROJ_FW_IMAGES)
reproj-fw: $(REPROJ_FW_IMAGES)
.PHONY: reproj-fw

# The reprojection app over a real depth image (firmware/apps/reproj_app.[ch], docs/firmware.md,
# "Reprojection of a real depth image"): its host runner, in the host and ASan builds, over the
# blob firmware.mk makes from the Beachball EXR with `lanetrace fwblob`; tests/run.d/reproj_blob.sh
# compares its lines with build/fw/<T>/reproj-bb.elf's (built when ../shared has the EXR).
define rpblob_host
$(B)/$(1)/reproj-blob-host: $(B)/$(1)/obj/tests/fw/reproj_blob_host.o \
    $(B)/$(1)/obj/firmware/apps/reproj_app.o $$($(1)_CORE_OBJS)
	@echo "LD $$@"
	@$$(CC) $$(LDFLAGS_$(1)) -o $$@ $$^
endef
$(foreach v,host asan,$(eval $(call rpblob_host,$(v))))
EXTRA_TEST_BINS += $(B)/host/reproj-blob-host $(B)/asan/reproj-blob-host
