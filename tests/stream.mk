# stream.mk - tests of the stream protocol (docs/stream.md); included by the top-level Makefile.
# The programs (lt-stream, lt-faultinject, lt-stream-dev) are shipped ones: host/host.mk builds
# them; the streaming firmware build/fw/<T>/stream.elf comes from firmware.mk's image template.
# The frame fuzz target (tests/fuzz/fuzz_frame.c, make fuzz-frame) is built by tests/fuzz.mk.
STREAM_FW_IMAGES := $(foreach t,$(FW_TARGETS),$(B)/fw/$(t)/stream.elf)
EXTRA_TEST_BINS += $(STREAM_FW_IMAGES)

