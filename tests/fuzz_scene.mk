# fuzz_scene.mk - the scene-parser fuzz target (auto-included by the Makefile).
#   build/asan/fuzz-scene     replay driver over tests/fuzz/corpus/scene (ASan + UBSan), in make test
#   make fuzz-scene           libFuzzer for FUZZ_SECONDS when clang has -fsanitize=fuzzer
$(B)/asan/fuzz-scene: $(B)/asan/obj/tests/fuzz/fuzz_scene.o $(B)/asan/obj/tests/fuzz/fuzz_main.o \
    $(B)/asan/obj/host/io/lt_scenefile.o $(B)/asan/obj/host/io/lt_diag.o $(B)/asan/obj/sim/lt_cache.o
	@echo "LD $@"
	@$(CC) $(LDFLAGS_asan) -o $@ $^ -lcjson -lm
EXTRA_TEST_BINS += $(B)/asan/fuzz-scene
FUZZ_CLANG ?= clang
FUZZ_SECONDS ?= 60
$(B)/fuzz/fuzz-scene-libfuzzer: tests/fuzz/fuzz_scene.c host/io/lt_scenefile.c host/io/lt_diag.c sim/lt_cache.c \
    $(B)/gen/lt_machines.inc
	@mkdir -p $(@D)
	$(FUZZ_CLANG) -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all -Ihost \
	    -Isim -I$(B)/gen tests/fuzz/fuzz_scene.c host/io/lt_scenefile.c host/io/lt_diag.c sim/lt_cache.c \
	    -lcjson -lm \
	    -o $@
fuzz-scene: $(B)/asan/fuzz-scene
	@mkdir -p $(B)/fuzz/corpus-scene
	@if echo 'int LLVMFuzzerTestOneInput(const char *d, long n){(void)d;(void)n;return 0;}' \
	    | $(FUZZ_CLANG) -fsanitize=fuzzer -x c - -o $(B)/fuzz/probe-scene >/dev/null 2>&1; then \
	    rm -f $(B)/fuzz/probe-scene; \
	    $(MAKE) --no-print-directory $(B)/fuzz/fuzz-scene-libfuzzer && \
	    $(B)/fuzz/fuzz-scene-libfuzzer -max_total_time=$(FUZZ_SECONDS) -max_len=4096 \
	        -artifact_prefix=$(B)/fuzz/ -print_final_stats=1 $(B)/fuzz/corpus-scene \
	        tests/fuzz/corpus/scene; \
	else \
	    echo "fuzz-scene: $(FUZZ_CLANG) has no -fsanitize=fuzzer: replaying the corpus instead"; \
	    $(B)/asan/fuzz-scene tests/fuzz/corpus/scene; \
	fi
fuzz: fuzz-scene
.PHONY: fuzz-scene
