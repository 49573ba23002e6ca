# stream.mk - tests of the stream protocol (docs/stream.md); included by the top-level Makefile.
# The programs (lt-stream, lt-faultinject, lt-stream-dev) are shipped ones: host/host.mk builds
# them; the streaming firmware build/fw/<T>/stream.elf comes from firmware.mk's image template.
#   build/asan/fuzz-frame         the frame fuzz target's replay driver (ASan + UBSan)
#   make fuzz-frame / make fuzz   libFuzzer run of tests/fuzz/fuzz_frame.c for FUZZ_SECONDS (60)
#                                 when clang has -fsanitize=fuzzer; else the corpus replay
STREAM_FW_IMAGES := $(foreach t,$(FW_TARGETS),$(B)/fw/$(t)/stream.elf)

# ---- fuzzing ----------------------------------------------------------------------------------
$(B)/asan/fuzz-frame: $(B)/asan/obj/tests/fuzz/fuzz_frame.o $(B)/asan/obj/tests/fuzz/fuzz_main.o \
    $(asan_CORE_OBJS) $(asan_HOST_OBJS)
	$(CC) $(LDFLAGS_asan) -o $@ $^ $(LIBS_asan)

FUZZ_SECONDS ?= 60
FUZZ_CLANG ?= clang
FUZZ_FRAME_SRCS := tests/fuzz/fuzz_frame.c firmware/core/stream/lt_stream.c \
    firmware/core/numerics/lt_mem.c host/stream/lt_rx.c host/stream/lt_faults.c host/io/lt_diag.c
$(B)/fuzz/fuzz-frame-libfuzzer: $(FUZZ_FRAME_SRCS)
	@mkdir -p $(@D)
	$(FUZZ_CLANG) -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
	    -D_POSIX_C_SOURCE=200809L -Ifirmware/include -Ifirmware/core -Ihost $(FUZZ_FRAME_SRCS) -o $@

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

EXTRA_TEST_BINS += $(B)/asan/fuzz-frame $(STREAM_FW_IMAGES)

.PHONY: fuzz fuzz-frame
