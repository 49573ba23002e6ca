# lanetrace - one non-recursive Makefile for the three builds of one source:
#   build/host  native (LT_COST_OFF, -O2 -march=native): the golden reference and the speed race
#   build/sim   the same kernels with LT_COST_SIM, linked to sim/: cycle reports
#   build/asan  host build with ASan + UBSan, used by the tests; also the sanitizer builds of every
#               shipped program (host/host.mk), the simulator ones from build/asansim objects
#   build/fw/<target>  freestanding firmware images for cm4, cm55, rv32 (QEMU)
# Main targets: deps all run test firmware sim bench clean (see README.md).

.SUFFIXES:
.DELETE_ON_ERROR:
# keep intermediate objects (test mains), so a second build does not recompile them
.SECONDARY:
SHELL := /bin/bash

B ?= build
CC ?= gcc
# One warning list for every build of every room (host, sim, asan and the firmware targets).
WARN := -std=c99 -Wall -Wextra -Wpedantic -Werror -Wshadow -Wundef -Wstrict-prototypes \
    -Wmissing-prototypes -Wcast-align -Wconversion
# Float32 results are bit-identical across builds only without FMA contraction or fast-math.
# (-fno-math-errno on the host: sqrt without the errno branch, so lane loops over doubles vectorise;
# IEEE results unchanged)
FPFLAGS := -ffp-contract=off -fno-fast-math
# Header dependencies come from the compiler (-MMD -MP): every object has a .d file beside it.
DEPFLAGS := -MMD -MP
# -Wno-format-truncation: host messages are built with snprintf, whose truncation is the intent
HOST_CFLAGS := $(WARN) -Wdouble-promotion -Wno-format-truncation $(FPFLAGS) -fno-math-errno -O2 -g \
    -fno-var-tracking-assignments -D_POSIX_C_SOURCE=200809L -pthread $(DEPFLAGS)
# -mmove-max=256 -mstore-max=256 (GCC 12+, x86) for AVX2 targets without AVX-512: struct copies
# and stores of the 64-byte lane vectors in whole 256-bit moves. Without them GCC's x86-64-v3
# tuning (generic or znver3) copies a lane vector in 128-bit pieces that the kernels' next 256-bit
# load cannot forward from: the AVX2 build's float32 16-ray packets ran at 4.6 Mrays/s instead of
# 29.9 (bunny 1024, one thread; docs/results.md, "AVX2 hosts"). On AVX-512 targets the lane
# backend writes whole registers itself and the flags cost 3% (float32 packets 33.5 -> 32.4).
# Left out where the compiler does not take them.
X86_MOVE := $(shell $(CC) -mmove-max=256 -mstore-max=256 -E -x c /dev/null -o /dev/null \
    2>/dev/null && echo -mmove-max=256 -mstore-max=256)
NATIVE_DEFS := $(shell $(CC) -march=native -dM -E -x c /dev/null 2>/dev/null)
# -mtune=icelake-server on AVX-512 hosts that GCC tunes as an AMD Zen (GCC 12 takes an AVX-512
# Zen 4 for znver3 with AVX-512 added): with znver3's tuning GCC moves the 64-byte lane vectors
# as 256-bit halves that the next 512-bit load cannot forward from, and the float32 16-ray packets
# ran at half speed. Measured on an AMD EPYC (family 25 model 17), one thread, 1024x1024,
# build/host/embree-race, znver3 -> icelake-server tuning: float32 packets bunny 20.2 -> 38.4
# Mrays/s, dragon 14.9 -> 26.9, shadow packets 5.6 -> 9.6 and 3.9 -> 6.6, single rays +3-5%;
# s15.16 packets 4-7% slower (bunny 18.1 -> 17.4), single rays 4% faster. Tuning only: the same
# instructions sets, -ffp-contract=off, the same bits (golden vectors, hashes).
NATIVE_TUNE := $(shell $(CC) -march=native -Q --help=target 2>/dev/null | awk '$$1 == "-mtune=" {print $$2}')
NATIVE_ARCH ?= -march=native $(if $(findstring __AVX2__,$(NATIVE_DEFS)),$(if $(findstring \
    __AVX512F__,$(NATIVE_DEFS)),$(if $(filter znver%,$(NATIVE_TUNE)),-mtune=icelake-server),$(X86_MOVE)))

# ---- rooms and their include paths (docs/architecture.md) ----------------------------------------
#   firmware/core/<room>/   the freestanding core: sees only the public API and its own rooms
#   firmware/apps/          firmware applications (the stream device), shared with the host sim
#   sim/                    the cycle model (host only)
#   host/<room>/            the programs: cli, io, render, stream
#   tests/                  tests and benchmarks only: no shipped program is built from here
CORE_INC := -Ifirmware/include -Ifirmware/core
APP_INC := $(CORE_INC) -Ifirmware/apps
# sim/ and host/ also see the generated machine list ($(B)/gen/lt_machines.inc); sim/ sees host/
# for the one diagnostic type only (io/lt_diag.h; `make layout` checks that)
SIM_INC := -Ifirmware/include -Isim -Ihost -I$(B)/gen
HOST_INC := -Ifirmware/include -Ifirmware/apps -Ihost -Isim -I$(B)/gen -isystem /usr/include/OpenEXR
TEST_INC := $(HOST_INC) -Itests/unit -Itests/vectors

CORE_SRCS := $(wildcard firmware/core/*/*.c)
# host library: every host/<room>/*.c except program mains (*_main.c) and the USB backend
# (host/stream/usb, compiled with hidapi's flags in host/host.mk)
HOSTLIB_SRCS := $(filter-out %_main.c,$(wildcard host/*/*.c))
# firmware applications the host programs also run (lanetrace pack traces scene blobs)
HOSTAPP_SRCS := firmware/apps/lt_sblob.c
SIM_SRCS := sim/lt_sim.c sim/lt_meter_sim.c
# the cache geometry parser and model: in every variant (scene files and --l1/--l2 are checked the
# same way in the native build, which has no cycle model to use them)
CACHE_SRCS := sim/lt_cache.c
# what the cycle model needs from host/: its diagnostics (lt_diag_t)
SIM_HOST_DEPS := host/io/lt_diag.c
# unit tests: tests/unit/test_<name>.c, built for every variant (test_cache is sim-only)
UNIT_TESTS := $(filter-out cache,$(patsubst tests/unit/test_%.c,%,$(wildcard tests/unit/test_*.c)))
VEC_SRCS := tests/vectors/lt_vec.c

# ---- machines: one file sim/machines/<name>.def each (docs/cost-model.md) -----------------------
# $(B)/gen/lt_machines.inc lists them for sim/lt_machines.h; it is rewritten only when the set of
# files changes, so adding (or removing) a machine needs no other edit.
MACHINE_DEFS := $(sort $(wildcard sim/machines/*.def))
$(B)/gen/lt_machines.inc: FORCE
	@mkdir -p $(@D)
	@{ echo '/* generated by the Makefile from sim/machines/<name>.def (do not edit) */'; \
	  $(foreach f,$(MACHINE_DEFS),echo '#include "$(f:sim/%=%)"'; echo 'LT_MACHINE_END';) } >$@.tmp
	@if cmp -s $@.tmp $@; then rm -f $@.tmp; else mv -f $@.tmp $@; echo "GEN $@"; fi
FORCE:
.PHONY: FORCE

# ---- variants: CFLAGS per variant ------------------------------------------------------------
CFLAGS_host := $(HOST_CFLAGS) $(NATIVE_ARCH) -DLT_COST_MODE=LT_COST_OFF
CFLAGS_sim := $(HOST_CFLAGS) $(NATIVE_ARCH) -DLT_COST_MODE=LT_COST_SIM
CFLAGS_asan := $(HOST_CFLAGS) -O1 -fsanitize=address,undefined -fno-sanitize-recover=all \
    -fno-omit-frame-pointer -DLT_COST_MODE=LT_COST_OFF -DLT_CFG_ASSERT=1
LDFLAGS_asan := -fsanitize=address,undefined
# the simulator build (LT_COST_SIM) under ASan + UBSan: objects of the sanitizer builds of the
# simulator programs (build/asan/lanetrace, build/asan/lt-stream-dev; host/host.mk)
CFLAGS_asansim := $(subst LT_COST_OFF,LT_COST_SIM,$(CFLAGS_asan))
LDFLAGS_asansim := $(LDFLAGS_asan)
# ThreadSanitizer (native, LT_COST_OFF): the threaded tile loops (host/render/lt_par.h) raced by
# build/tsan/test_par and build/tsan/lanetrace-native (tests/run.d/threads.sh)
CFLAGS_tsan := $(HOST_CFLAGS) -O1 -fsanitize=thread -fno-omit-frame-pointer \
    -DLT_COST_MODE=LT_COST_OFF
LDFLAGS_tsan := -fsanitize=thread
# The AVX2 lane backend (firmware/include/lt/lt_v16_x86.h) on any x86 host that runs AVX2: the
# kernels for x86-64-v3 (AVX2, FMA, no AVX-512), native LT_COST_OFF; make test compares its
# vectors with the golden file and runs test_v16, test_isect and test_bvh on it (the native
# build takes the widest backend its -march allows, asan the portable loops)
CFLAGS_avx2 := $(HOST_CFLAGS) -march=x86-64-v3 $(X86_MOVE) -DLT_COST_MODE=LT_COST_OFF
# host-side libraries (Debian): assimp, cJSON, OpenEXR's C API (OpenEXRCore), libpng, zlib
HOST_LIBS = -pthread -lassimp -lcjson -lOpenEXRCore-3_1 -lpng16 -lz -lm
LIBS_host = $(HOST_LIBS)
LIBS_sim = $(HOST_LIBS)
LIBS_asan = $(HOST_LIBS)
LIBS_asansim = $(HOST_LIBS)
LIBS_tsan = $(HOST_LIBS)
LIBS_avx2 = $(HOST_LIBS)
VARIANTS := host sim asan
SIM_VARIANTS := sim asansim

all: $(B)/sim/lanetrace $(B)/host/lanetrace-native

# One object rule per variant; the include path follows the room the source lives in
# (pattern-specific SRC_INC), so the core never sees host, sim or test headers.
define variant_rules
$(B)/$(1)/obj/firmware/core/%.o: SRC_INC := $(CORE_INC)
$(B)/$(1)/obj/firmware/apps/%.o: SRC_INC := $(APP_INC)
$(B)/$(1)/obj/sim/%.o: SRC_INC := $(SIM_INC)
$(B)/$(1)/obj/host/%.o: SRC_INC := $(HOST_INC)
$(B)/$(1)/obj/tests/%.o: SRC_INC := $(TEST_INC)
$(B)/$(1)/obj/%.o: %.c Makefile | $(B)/gen/lt_machines.inc
	@mkdir -p $$(@D)
	@echo "CC [$(1)] $$<"
	@$(CC) $(CFLAGS_$(1)) $$(SRC_INC) -c $$< -o $$@
$(1)_CORE_OBJS := $(CORE_SRCS:%.c=$(B)/$(1)/obj/%.o)
# the sim build meters through sim/lt_meter_sim.c (SIM_SRCS), the others through lt_meter_null.c
$(1)_HOST_OBJS := $(filter-out $(if $(filter $(SIM_VARIANTS),$(1)),%/lt_meter_null.o),$(HOSTLIB_SRCS:%.c=$(B)/$(1)/obj/%.o)) \
    $(CACHE_SRCS:%.c=$(B)/$(1)/obj/%.o) $(HOSTAPP_SRCS:%.c=$(B)/$(1)/obj/%.o)
$(1)_EXTRA_OBJS := $(if $(filter $(SIM_VARIANTS),$(1)),$(SIM_SRCS:%.c=$(B)/$(1)/obj/%.o) \
    $(CACHE_SRCS:%.c=$(B)/$(1)/obj/%.o) $(SIM_HOST_DEPS:%.c=$(B)/$(1)/obj/%.o))
$(B)/$(1)/test_%: $(B)/$(1)/obj/tests/unit/test_%.o $$($(1)_CORE_OBJS) $$($(1)_HOST_OBJS) \
    $$($(1)_EXTRA_OBJS)
	@echo "LD $$@"
	@$(CC) $(LDFLAGS_$(1)) -o $$@ $$^ -lcmocka $(LIBS_$(1))
$(B)/$(1)/lt-vectors: $(B)/$(1)/obj/tests/vectors/vec_host.o $(B)/$(1)/obj/$(VEC_SRCS:.c=.o) \
    $$($(1)_CORE_OBJS) $$($(1)_EXTRA_OBJS)
	@echo "LD $$@"
	@$(CC) $(LDFLAGS_$(1)) -o $$@ $$^ $(LIBS_$(1))
endef
$(foreach v,$(VARIANTS) asansim tsan avx2,$(eval $(call variant_rules,$(v))))

$(B)/sim/test_cache: $(B)/sim/obj/tests/unit/test_cache.o $(B)/sim/obj/sim/lt_cache.o \
    $(SIM_HOST_DEPS:%.c=$(B)/sim/obj/%.o)
	@echo "LD $@"
	@$(CC) -o $@ $^ -lcmocka

$(B)/sim/slab-model: $(B)/sim/obj/tests/bench/slab_model.o $(B)/sim/obj/tests/vectors/lt_slab_loop.o \
    $(sim_CORE_OBJS) $(sim_EXTRA_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_sim)

sim: $(B)/sim/lanetrace

# ---- rooms' own rules --------------------------------------------------------------------------
include firmware/targets/targets.mk
include sim/qemu/plugin.mk
include firmware/firmware.mk
include firmware/opcal.mk
# the shipped programs (host/host.mk), then tests' and benchmarks' own programs and images
include host/host.mk
include $(sort $(wildcard tests/*.mk))
# compiler-generated header dependencies of every object built so far
-include $(shell find $(B) -name '*.d' 2>/dev/null)

# ---- deps, run, test, bench ----------------------------------------------------------------------
deps:
	@tools/deps.sh

RUN_ARGS ?=
run: deps
	@$(MAKE) --no-print-directory all
	@mkdir -p $(B)/run
	@# lanetrace info's recommendation is taken for what the scene file leaves open (its leaf size)
	$(B)/sim/lanetrace run scenes/teapot.json --report $(B)/run/report.json $(RUN_ARGS)
	@# view synthesis (docs/reproject.md): a 2-layer depth render of the teapot, reprojected
	$(B)/host/lanetrace-native render scenes/teapot.json --res 96 --layers 2 --out $(B)/run/teapot -q
	$(B)/sim/lanetrace reproject scenes/teapot.json --depth $(B)/run/teapot.exr --layers 2 --color \
	    --move-rel 0.08,0,0 --rot -3,0,0 --out $(B)/run/teapot-reproj.exr --png $(B)/run/teapot-reproj.png \
	    --heat-cycles $(B)/run/teapot-reproj-cycles.png --report $(B)/run/reproj-report.json --truth

# the "Cycle report of the bundled scene" table of docs/results.md, measured now
run-doc: deps
	@$(MAKE) --no-print-directory all
	@B=$(B) tools/run_table.sh >$(B)/run-table.md
	@tools/doc_insert.sh run-table $(B)/run-table.md docs/results.md
.PHONY: run-doc

TEST_BINS := $(foreach v,$(VARIANTS),$(UNIT_TESTS:%=$(B)/$(v)/test_%) $(B)/$(v)/lt-vectors) \
    $(B)/sim/test_cache $(B)/host/lanetrace-native $(B)/sim/lanetrace $(EXTRA_TEST_BINS) \
    $(B)/tsan/test_par $(B)/tsan/lanetrace-native $(B)/avx2/test_v16 $(B)/avx2/test_isect \
    $(B)/avx2/test_bvh $(B)/avx2/test_wt $(B)/avx2/lt-vectors

test: deps
	@$(MAKE) --no-print-directory test-build
	@B=$(B) UNIT_TESTS="$(UNIT_TESTS)" tests/run_tests.sh

test-build: $(TEST_BINS) firmware $(PLUGIN_SO) $(FW_SHARED_IMAGES)

bench: deps
	@$(MAKE) --no-print-directory all firmware opcal fw-cal $(PLUGIN_SO) $(B)/sim/lt-fwmodel \
	    $(B)/host/embree-race $(B)/host/frusta-race $(B)/sim/ssbench
	@tests/bench/bench.sh

# the rooms' rules: the core includes nothing of host, sim or tests; no shipped program from tests/
layout:
	@tools/check_layout.sh

# the index of every core function, template-generated ones included (build/index/tags)
index: $(host_CORE_OBJS)
	@tools/gen_index.sh --check $(B)/host/obj/firmware/core $(B)/index

# CSV sweep -> PNG plots (gnuplot): cycles per phase, error vs cycles, lane utilisation
plots: deps
	@$(MAKE) --no-print-directory all
	@mkdir -p $(B)/plots
	@B=$(B) tools/plots/sweep.sh $(B)/plots/sweep.csv
	@tools/plots/plots.sh $(B)/plots/sweep.csv $(B)/plots

# lanetrace tune on the teapot and the shared meshes -> docs/tradeoffs.md and docs/tradeoffs/*.png
pareto: deps
	@$(MAKE) --no-print-directory all
	@B=$(B) tools/pareto.sh

# the multi-frusta reduction sweep and Table 2 -> docs/frusta.md, docs/results.md (tools/frusta_sweep.sh,
# tools/frusta_table2.sh; about 20 minutes on one core, needs ../shared)
frusta-doc: deps
	@$(MAKE) --no-print-directory all
	@mkdir -p $(B)/sweep
	@B=$(B) tools/frusta_sweep.sh >$(B)/sweep/sweep.md
	@B=$(B) tools/frusta_table2.sh 512 >$(B)/sweep/table2.md
	@tools/doc_insert.sh frusta-sweep $(B)/sweep/sweep.md docs/frusta.md
	@tools/doc_insert.sh frusta-table2 $(B)/sweep/table2.md docs/frusta.md
	@tools/doc_insert.sh frusta-sweep $(B)/sweep/sweep.md docs/results.md

# instructions per ray of the scene-blob images on cm4, cm55 and rv32 -> docs/firmware.md
# (tools/fw_rays.sh, QEMU with the lt_icount plugin; seconds), and every image's sizes and
# measured RAM -> docs/results.md
fw-doc: deps
	@$(MAKE) --no-print-directory firmware $(PLUGIN_SO)
	@mkdir -p $(B)/fwdoc
	@B=$(B) tools/fw_rays.sh >$(B)/fwdoc/rays.md
	@tools/doc_insert.sh fw-rays $(B)/fwdoc/rays.md docs/firmware.md
	@{ echo "| image | .text | .data | .bss (incl. stack) | RAM measured (stack + static) |"; \
	  echo "|---|---:|---:|---:|---:|"; \
	  tools/check_fw.sh $(FW_IMAGES) | awk '/^size / { r = $$10 ~ /^[0-9]+$$/ ? $$10 : "not reported"; \
	    sub(/^$(B)\/fw\//, "", $$2); printf "| %s | %s | %s | %s | %s |\n", $$2, $$4, $$6, $$8, r }'; } \
	    >$(B)/fwdoc/sizes.md
	@tools/doc_insert.sh fw-sizes $(B)/fwdoc/sizes.md docs/results.md

clean:
	rm -rf $(B)

.PHONY: all sim deps run test test-build bench clean firmware plots layout index pareto \
    frusta-doc fw-doc
