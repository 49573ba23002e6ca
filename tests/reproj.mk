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
