# stream.mk - the stream protocol of issue 6 (docs/stream.md); included by the top-level Makefile.
#   build/host/lt-stream          receiver: file/pipe/stdin, serial, TCP, USB HID (hidapi)
#   build/host/lt-faultinject     fault injector with ground truth
#   build/sim/lt-stream-dev       the simulator acting as a streaming device (same device code as
#                                 the firmware: tests/fw/stream_dev.c)
#   build/fw/<T>/stream.elf       the streaming firmware for cm4, cm55, rv32 (tests/fw/fw_stream.c)
#   build/asan/fuzz-frame         the frame fuzz target's replay driver (ASan + UBSan)
#   make fuzz-frame / make fuzz   libFuzzer run of tests/fuzz/fuzz_frame.c for FUZZ_SECONDS (60)
#                                 when clang has -fsanitize=fuzzer; else the corpus replay
# STREAM_HID selects the hidapi backend by pkg-config name (hidapi-hidraw; hidapi-libusb works
# too); when pkg-config does not know it, lt-stream is built without HID support and says so.

STREAM_HID ?= hidapi-hidraw
STREAM_HID_CFLAGS := $(shell pkg-config --cflags $(STREAM_HID) 2>/dev/null)
STREAM_HID_LIBS := $(shell pkg-config --libs $(STREAM_HID) 2>/dev/null)
ifeq ($(strip $(STREAM_HID_LIBS)),)
STREAM_HID_CFLAGS := -DLT_RX_NO_HIDAPI
endif

STREAM_DEV_HDRS := tests/fw/stream_dev.h firmware/include/lt/lt_stream.h
STREAM_HOST_HDRS := host/lt_rx.h host/lt_faults.h host/usb/lt_rx_hid.h

# ---- host programs ---------------------------------------------------------------------------
$(B)/host/obj/host/usb/lt_rx_hid.o: host/usb/lt_rx_hid.c $(STREAM_HOST_HDRS) $(CORE_HDRS) \
    tests/stream.mk
	@mkdir -p $(@D)
	@echo "CC [host] $<"
	@$(CC) $(CFLAGS_host) $(STREAM_HID_CFLAGS) -c $< -o $@

$(B)/host/obj/host/lt_stream_main.o $(B)/host/obj/host/lt_faultinject_main.o: $(STREAM_HOST_HDRS)

$(B)/host/lt-stream: $(B)/host/obj/host/lt_stream_main.o $(B)/host/obj/host/usb/lt_rx_hid.o \
    $(host_CORE_OBJS) $(host_HOST_OBJS)
	$(CC) -o $@ $^ $(LIBS_host) $(STREAM_HID_LIBS)

$(B)/host/lt-faultinject: $(B)/host/obj/host/lt_faultinject_main.o $(host_CORE_OBJS) \
    $(host_HOST_OBJS)
	$(CC) -o $@ $^ $(LIBS_host)

$(B)/sim/obj/host/lt_stream_dev_main.o $(B)/sim/obj/tests/fw/stream_dev.o: $(STREAM_DEV_HDRS)

$(B)/sim/lt-stream-dev: $(B)/sim/obj/host/lt_stream_dev_main.o $(B)/sim/obj/tests/fw/stream_dev.o \
    $(sim_CORE_OBJS) $(sim_HOST_OBJS) $(sim_EXTRA_OBJS)
	$(CC) -o $@ $^ $(LIBS_sim)

# ---- firmware images ---------------------------------------------------------------------------
define stream_fw_rules
$(B)/fw/$(1)/obj/tests/fw/fw_stream.o $(B)/fw/$(1)/obj/tests/fw/stream_dev.o: $(STREAM_DEV_HDRS) \
    firmware/targets/common/lt_uart_tx.h
$(B)/fw/$(1)/stream.elf: $(B)/fw/$(1)/obj/tests/fw/fw_stream.o \
    $(B)/fw/$(1)/obj/tests/fw/stream_dev.o $$(fw_$(1)_CORE) $$(fw_$(1)_RT)
	$(CC_$(1)) $(LDFLAGS_$(1)) -o $$@ $$^ $(LDLIBS_$(1))
endef
$(foreach t,$(FW_TARGETS),$(eval $(call stream_fw_rules,$(t))))
STREAM_FW_IMAGES := $(foreach t,$(FW_TARGETS),$(B)/fw/$(t)/stream.elf)

# ---- fuzzing ----------------------------------------------------------------------------------
$(B)/asan/obj/tests/fuzz/fuzz_frame.o: $(STREAM_HOST_HDRS)
$(B)/asan/fuzz-frame: $(B)/asan/obj/tests/fuzz/fuzz_frame.o $(B)/asan/obj/tests/fuzz/fuzz_main.o \
    $(asan_CORE_OBJS) $(asan_HOST_OBJS)
	$(CC) $(LDFLAGS_asan) -o $@ $^ $(LIBS_asan)

FUZZ_SECONDS ?= 60
FUZZ_CLANG ?= clang
FUZZ_FRAME_SRCS := tests/fuzz/fuzz_frame.c firmware/core/lt_stream.c firmware/core/lt_mem.c \
    host/lt_rx.c host/lt_faults.c
$(B)/fuzz/fuzz-frame-libfuzzer: $(FUZZ_FRAME_SRCS) $(STREAM_HOST_HDRS) $(CORE_HDRS)
	@mkdir -p $(@D)
	$(FUZZ_CLANG) -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
	    -D_POSIX_C_SOURCE=200809L -Ifirmware/include -Ihost $(FUZZ_FRAME_SRCS) -o $@

fuzz-frame: $(B)/asan/fuzz-frame
	@mkdir -p $(B)/fuzz
	@if echo 'int LLVMFuzzerTestOneInput(const char *d, unsigned long n) { return d[0] & n; }' \
	    | $(FUZZ_CLANG) -fsanitize=fuzzer -x c - -o $(B)/fuzz/probe >/dev/null 2>&1; then \
	    rm -f $(B)/fuzz/probe; \
	    $(MAKE) --no-print-directory $(B)/fuzz/fuzz-frame-libfuzzer && \
	    mkdir -p $(B)/fuzz/corpus-frame && \
	    $(B)/fuzz/fuzz-frame-libfuzzer -max_total_time=$(FUZZ_SECONDS) -max_len=4096 \
	        -artifact_prefix=$(B)/fuzz/ \
	        -print_final_stats=1 $(B)/fuzz/corpus-frame tests/fuzz/corpus/frame; \
	else \
	    echo "fuzz-frame: $(FUZZ_CLANG) has no -fsanitize=fuzzer: replaying the corpus instead"; \
	    $(B)/asan/fuzz-frame tests/fuzz/corpus/frame; \
	fi

fuzz: fuzz-frame

EXTRA_TEST_BINS += $(B)/host/lt-stream $(B)/host/lt-faultinject $(B)/sim/lt-stream-dev \
    $(B)/asan/fuzz-frame $(STREAM_FW_IMAGES)

.PHONY: fuzz fuzz-frame
