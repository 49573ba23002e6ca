# fuzz.mk - the fuzz targets, one template for all (auto-included by the Makefile; docs/reliability.md).
# A target <t> is tests/fuzz/fuzz_<t>.c (LLVMFuzzerTestOneInput) plus the sources it exercises,
# FUZZ_SRCS_<t>, linked with FUZZ_LIBS_<t>; its seed corpus is tests/fuzz/corpus/<t>/ and its
# dictionary, when there is one, tests/fuzz/<t>.dict. For every target:
#   build/asan/fuzz-<t>     replay driver (tests/fuzz/fuzz_main.c) under ASan + UBSan (gcc): runs
#                           the committed corpus in make test (tests/run.d/fuzz.sh)
#   build/fuzz/fuzz-<t>     libFuzzer build (clang -fsanitize=fuzzer,address,undefined)
#   make fuzz-<t>           libFuzzer for FUZZ_SECONDS (60) on the corpus; new inputs go to
#                           build/fuzz/corpus-<t>/, crashes to build/fuzz/artifacts/<t>/; without
#                           libFuzzer in clang, the corpus replay instead
#   make fuzz               every target for FUZZ_SECONDS, one after the other
#   make fuzz-campaign SECONDS=N   every target for N s under ASan + UBSan: one table of executions,
#                           (RUNS=N: N executions per target, SECONDS then a cap, 0 = none;
#                           FUZZ_TARGETS="a b" for a subset)
#                           exec/s, new inputs and crashes (also build/fuzz/campaign.md); exit 1 on
#                           any crash, hang or out-of-memory
#   make fuzz-doc           copy that table into docs/reliability.md (between its markers), then
#                           make fuzz-summary: the per-target totals into docs/results.md
#   make fuzz-merge         minimise build/fuzz/corpus-<t> + tests/fuzz/corpus/<t> into the latter
#                           (libFuzzer -merge=1, tests/fuzz/merge.sh; regress-* inputs kept by
#                           name): the step before committing a corpus
FUZZ_TARGETS := scene frame exr mesh meshcheck cache opt blob cli

FUZZ_SRCS_scene := host/io/lt_scenefile.c sim/lt_cache.c host/io/lt_diag.c tests/fuzz/fuzz_util.c
FUZZ_LIBS_scene := -lcjson -lm
FUZZ_SRCS_frame := firmware/core/stream/lt_stream.c firmware/core/numerics/lt_mem.c \
    host/stream/lt_rx.c host/stream/lt_faults.c host/io/lt_diag.c
FUZZ_SRCS_exr := host/io/lt_exr.c host/io/lt_tmpfiles.c host/io/lt_diag.c tests/fuzz/fuzz_util.c
FUZZ_LIBS_exr := -lOpenEXRCore-3_1 -lm
FUZZ_SRCS_mesh := host/io/lt_mesh.c host/io/lt_import.c host/io/lt_meshcheck.c \
    host/io/lt_diag.c tests/fuzz/fuzz_util.c
FUZZ_LIBS_mesh := -lassimp -lz -lm
FUZZ_SRCS_meshcheck := host/io/lt_meshcheck.c host/io/lt_diag.c tests/fuzz/fuzz_util.c
FUZZ_SRCS_cache := sim/lt_cache.c host/io/lt_diag.c tests/fuzz/fuzz_util.c
FUZZ_SRCS_opt := host/cli/lt_opt.c host/io/lt_diag.c
FUZZ_SRCS_blob := firmware/apps/lt_sblob.c $(CORE_SRCS)
FUZZ_LIBS_opt := -lm
# cli: the subcommands' argument handling (tests/fuzz/fuzz_cli.h); each fuzz_cli_<command>.c
# includes its command's source, so those leave the host library's list
FUZZ_CLI_CMDS := main reproject shadows tune pack
FUZZ_SRCS_cli := $(FUZZ_CLI_CMDS:%=tests/fuzz/fuzz_cli_%.c) $(CORE_SRCS) \
    $(filter-out $(FUZZ_CLI_CMDS:%=host/cli/lt_%_cli.c),$(HOSTLIB_SRCS)) $(CACHE_SRCS) \
    $(HOSTAPP_SRCS)
FUZZ_LIBS_cli = $(HOST_LIBS)
FUZZ_CLI_INCLUDED := host/cli/lanetrace_main.c \
    $(patsubst %,host/cli/lt_%_cli.c,$(filter-out main,$(FUZZ_CLI_CMDS)))
# largest input libFuzzer makes, per target (default 4096)
FUZZ_MAXLEN_exr := 16384
FUZZ_MAXLEN_mesh := 8192
FUZZ_MAXLEN_meshcheck := 8192
FUZZ_MAXLEN_blob := 8192
# the libFuzzer build of the EXR reader caps windows at 512 pixels a side (instead of 16384), so
# that a header asking for the largest window costs 5 MB, not 5 GB, per execution
FUZZ_CFLAGS_exr := -DLT_EXR_MAX_DIM=512

FUZZ_CLANG ?= clang
FUZZ_SECONDS ?= 60
SECONDS ?= $(FUZZ_SECONDS)
FUZZ_CFLAGS := -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
    -std=c99 -D_POSIX_C_SOURCE=200809L -DLT_COST_MODE=LT_COST_OFF -DLT_CFG_ASSERT=1 \
    -Ifirmware/include -Ifirmware/core -Ifirmware/apps -Ihost -Isim -I$(B)/gen \
    -isystem /usr/include/OpenEXR -Itests/fuzz
# the libFuzzer options of every run (docs/reliability.md): a hang is an input over 10 s, memory
# is capped at 2 GiB, the targets' own messages are not printed (crash reports still are)
FUZZ_RUN_FLAGS := -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -close_fd_mask=3
FUZZ_HAVE := $(B)/fuzz/.have-libfuzzer-$(notdir $(FUZZ_CLANG))

$(FUZZ_HAVE): tests/fuzz.mk
	@mkdir -p $(@D)
	@if echo 'int LLVMFuzzerTestOneInput(const char *d, unsigned long n) { return d[0] & n; }' \
	    | $(FUZZ_CLANG) -fsanitize=fuzzer -x c - -o $(B)/fuzz/probe >/dev/null 2>&1; \
	then echo yes >$@; else echo no >$@; fi; rm -f $(B)/fuzz/probe

define fuzz_target
$(B)/asan/fuzz-$(1): $(B)/asan/obj/tests/fuzz/fuzz_$(1).o $(B)/asan/obj/tests/fuzz/fuzz_main.o \
    $(FUZZ_SRCS_$(1):%.c=$(B)/asan/obj/%.o)
	@echo "LD $$@"
	@$(CC) $(LDFLAGS_asan) -o $$@ $$^ $(FUZZ_LIBS_$(1))
$(B)/fuzz/fuzz-$(1): tests/fuzz/fuzz_$(1).c $(FUZZ_SRCS_$(1)) tests/fuzz.mk | $(B)/gen/lt_machines.inc
	@mkdir -p $$(@D)
	@echo "CLANG [libFuzzer] $$@"
	@$(FUZZ_CLANG) $(FUZZ_CFLAGS) $(FUZZ_CFLAGS_$(1)) -MMD -MP -MF $$@.d tests/fuzz/fuzz_$(1).c \
	    $(FUZZ_SRCS_$(1)) -o $$@ $(FUZZ_LIBS_$(1))
fuzz-$(1): $(B)/asan/fuzz-$(1) $(FUZZ_HAVE)
	@if [ "$$$$(cat $(FUZZ_HAVE))" = yes ]; then \
	    $(MAKE) --no-print-directory $(B)/fuzz/fuzz-$(1) && \
	    mkdir -p $(B)/fuzz/corpus-$(1) $(B)/fuzz/artifacts/$(1) && \
	    $(B)/fuzz/fuzz-$(1) $(FUZZ_RUN_FLAGS) -max_total_time=$(FUZZ_SECONDS) \
	        -max_len=$(or $(FUZZ_MAXLEN_$(1)),4096) -artifact_prefix=$(B)/fuzz/artifacts/$(1)/ \
	        $(if $(wildcard tests/fuzz/$(1).dict),-dict=tests/fuzz/$(1).dict) \
	        $(B)/fuzz/corpus-$(1) tests/fuzz/corpus/$(1); \
	else \
	    echo "fuzz-$(1): $(FUZZ_CLANG) has no -fsanitize=fuzzer (make deps): replaying the corpus"; \
	    $(B)/asan/fuzz-$(1) tests/fuzz/corpus/$(1); \
	fi
fuzz-merge-$(1): $(B)/fuzz/fuzz-$(1)
	@B=$(B) tests/fuzz/merge.sh $(1) $(or $(FUZZ_MAXLEN_$(1)),4096)
.PHONY: fuzz-$(1) fuzz-merge-$(1)
endef
$(foreach t,$(FUZZ_TARGETS),$(eval $(call fuzz_target,$(t))))
# the command sources fuzz_cli_<command>.c include
$(B)/fuzz/fuzz-cli: $(FUZZ_CLI_INCLUDED)

FUZZ_REPLAYS := $(FUZZ_TARGETS:%=$(B)/asan/fuzz-%)
EXTRA_TEST_BINS += $(FUZZ_REPLAYS)

fuzz: $(FUZZ_TARGETS:%=fuzz-%)
fuzz-merge: $(FUZZ_TARGETS:%=fuzz-merge-%)
fuzz-campaign: $(FUZZ_HAVE)
	@if [ "$$(cat $(FUZZ_HAVE))" != yes ]; then \
	    echo "fuzz-campaign: $(FUZZ_CLANG) has no -fsanitize=fuzzer (make deps installs clang and libclang-rt)"; \
	    exit 1; fi
	@$(MAKE) --no-print-directory $(FUZZ_TARGETS:%=$(B)/fuzz/fuzz-%)
	@B=$(B) FUZZ_TIME=$(SECONDS) FUZZ_RUNS=$(RUNS) FUZZ_RUN_FLAGS="$(FUZZ_RUN_FLAGS)" \
	    $(foreach t,$(FUZZ_TARGETS),FUZZ_MAXLEN_$(t)=$(or $(FUZZ_MAXLEN_$(t)),4096)) \
	    tests/fuzz/campaign.sh $(FUZZ_TARGETS)
.PHONY: fuzz fuzz-merge fuzz-campaign

# seeds: $(B)/fuzz/corpus-<t>/ from real and crafted files (tests/fuzz/seeds.sh), EXR shapes from
# tests/fuzz/seeds_exr.c; then `make fuzz` grows them and `make fuzz-merge` commits the minimum
$(B)/fuzz/seeds-exr: tests/fuzz/seeds_exr.c tests/fuzz.mk
	@mkdir -p $(@D)
	@echo "LD $@"
	@$(CC) $(WARN) -D_POSIX_C_SOURCE=200809L -isystem /usr/include/OpenEXR $< -o $@ -lOpenEXRCore-3_1
fuzz-seeds: $(B)/fuzz/seeds-exr
	@B=$(B) tests/fuzz/seeds.sh
# the last campaign's table (build/fuzz/campaign.md) into docs/reliability.md, between its markers
fuzz-doc:
	@tests/fuzz/doc.sh $(B)/fuzz/campaign.md docs/reliability.md
	@$(MAKE) --no-print-directory fuzz-summary
# the per-target totals of that table (runs, executions, crashes, 10 million reached) into
# docs/results.md, between its fuzz-summary markers
fuzz-summary:
	@mkdir -p $(B)/fuzz
	@python3 tools/fuzz_summary.py docs/reliability.md >$(B)/fuzz/summary.md
	@tools/doc_insert.sh fuzz-summary $(B)/fuzz/summary.md docs/results.md
.PHONY: fuzz-seeds fuzz-doc fuzz-summary
