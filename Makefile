# lanetrace - one non-recursive Makefile for the three builds of one source:
#   build/host  native (LT_COST_OFF, -O2 -march=native): the golden reference and the speed race
#   build/sim   the same kernels with LT_COST_SIM, linked to sim/: cycle reports
#   build/asan  host build with ASan + UBSan, used by the tests
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
FPFLAGS := -ffp-contract=off -fno-fast-math
# Header dependencies come from the compiler (-MMD -MP): every object has a .d file beside it.
DEPFLAGS := -MMD -MP
# -Wno-format-truncation: host messages are built with snprintf, whose truncation is the intent
HOST_CFLAGS := $(WARN) -Wdouble-promotion -Wno-format-truncation $(FPFLAGS) -O2 -g \
    -fno-var-tracking-assignments -D_POSIX_C_SOURCE=200809L $(DEPFLAGS)
NATIVE_ARCH ?= -march=native

# ---- rooms and their include paths (docs/architecture.md) ----------------------------------------
#   firmware/core/<room>/   the freestanding core: sees only the public API and its own rooms
#   firmware/apps/          firmware applications (the stream device), shared with the host sim
#   sim/                    the cycle model (host only)
#   host/<room>/            the programs: cli, io, render, stream
#   tests/                  tests and benchmarks only: no shipped program is built from here
CORE_INC := -Ifirmware/include -Ifirmware/core
APP_INC := $(CORE_INC) -Ifirmware/apps
SIM_INC := -Ifirmware/include -Isim
HOST_INC := -Ifirmware/include -Ifirmware/apps -Ihost -Isim -isystem /usr/include/OpenEXR
TEST_INC := $(HOST_INC) -Itests/unit -Itests/vectors

CORE_SRCS := $(wildcard firmware/core/*/*.c)
# host library: every host/<room>/*.c except program mains (*_main.c) and the USB backend
# (host/stream/usb, compiled with hidapi's flags in host/host.mk)
HOSTLIB_SRCS := $(filter-out %_main.c,$(wildcard host/*/*.c))
SIM_SRCS := sim/lt_sim.c sim/lt_cache.c
# unit tests: tests/unit/test_<name>.c, built for every variant (test_cache is sim-only)
UNIT_TESTS := $(filter-out cache,$(patsubst tests/unit/test_%.c,%,$(wildcard tests/unit/test_*.c)))
VEC_SRCS := tests/vectors/lt_vec.c

# ---- variants: CFLAGS per variant ------------------------------------------------------------
CFLAGS_host := $(HOST_CFLAGS) $(NATIVE_ARCH) -DLT_COST_MODE=LT_COST_OFF
CFLAGS_sim := $(HOST_CFLAGS) $(NATIVE_ARCH) -DLT_COST_MODE=LT_COST_SIM
CFLAGS_asan := $(HOST_CFLAGS) -O1 -fsanitize=address,undefined -fno-sanitize-recover=all \
    -fno-omit-frame-pointer -DLT_COST_MODE=LT_COST_OFF -DLT_CFG_ASSERT=1
LDFLAGS_asan := -fsanitize=address,undefined
# host-side libraries (Debian): assimp, cJSON, OpenEXR's C API (OpenEXRCore), libpng, zlib
HOST_LIBS = -lassimp -lcjson -lOpenEXRCore-3_1 -lpng16 -lz -lm
LIBS_host = $(HOST_LIBS)
LIBS_sim = $(HOST_LIBS)
LIBS_asan = $(HOST_LIBS)
VARIANTS := host sim asan

all: $(B)/sim/lanetrace $(B)/host/lanetrace-native

# One object rule per variant; the include path follows the room the source lives in
# (pattern-specific SRC_INC), so the core never sees host, sim or test headers.
define variant_rules
$(B)/$(1)/obj/firmware/core/%.o: SRC_INC := $(CORE_INC)
$(B)/$(1)/obj/firmware/apps/%.o: SRC_INC := $(APP_INC)
$(B)/$(1)/obj/sim/%.o: SRC_INC := $(SIM_INC)
$(B)/$(1)/obj/host/%.o: SRC_INC := $(HOST_INC)
$(B)/$(1)/obj/tests/%.o: SRC_INC := $(TEST_INC)
$(B)/$(1)/obj/%.o: %.c Makefile
	@mkdir -p $$(@D)
	@echo "CC [$(1)] $$<"
	@$(CC) $(CFLAGS_$(1)) $$(SRC_INC) -c $$< -o $$@
$(1)_CORE_OBJS := $(CORE_SRCS:%.c=$(B)/$(1)/obj/%.o)
$(1)_HOST_OBJS := $(HOSTLIB_SRCS:%.c=$(B)/$(1)/obj/%.o)
$(1)_EXTRA_OBJS := $(if $(filter sim,$(1)),$(SIM_SRCS:%.c=$(B)/$(1)/obj/%.o))
$(B)/$(1)/test_%: $(B)/$(1)/obj/tests/unit/test_%.o $$($(1)_CORE_OBJS) $$($(1)_HOST_OBJS) \
    $$($(1)_EXTRA_OBJS)
	@echo "LD $$@"
	@$(CC) $(LDFLAGS_$(1)) -o $$@ $$^ -lcmocka $(LIBS_$(1))
$(B)/$(1)/lt-vectors: $(B)/$(1)/obj/tests/vectors/vec_host.o $(B)/$(1)/obj/$(VEC_SRCS:.c=.o) \
    $$($(1)_CORE_OBJS) $$($(1)_EXTRA_OBJS)
	@echo "LD $$@"
	@$(CC) $(LDFLAGS_$(1)) -o $$@ $$^ $(LIBS_$(1))
endef
$(foreach v,$(VARIANTS),$(eval $(call variant_rules,$(v))))

$(B)/sim/test_cache: $(B)/sim/obj/tests/unit/test_cache.o $(B)/sim/obj/sim/lt_cache.o
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
	$(B)/sim/lanetrace run scenes/teapot.json --report $(B)/run/report.json $(RUN_ARGS)
	@# view synthesis (docs/reproject.md): a 2-layer depth render of the teapot, reprojected
	$(B)/host/lanetrace-native render scenes/teapot.json --res 96 --layers 2 --out $(B)/run/teapot -q
	$(B)/sim/lanetrace reproject scenes/teapot.json --depth $(B)/run/teapot.exr --layers 2 --color \
	    --move-rel 0.08,0,0 --rot -3,0,0 --out $(B)/run/teapot-reproj.exr --png $(B)/run/teapot-reproj.png \
	    --heat-cycles $(B)/run/teapot-reproj-cycles.png --report $(B)/run/reproj-report.json --truth

TEST_BINS := $(foreach v,$(VARIANTS),$(UNIT_TESTS:%=$(B)/$(v)/test_%) $(B)/$(v)/lt-vectors) \
    $(B)/sim/test_cache $(B)/host/lanetrace-native $(B)/sim/lanetrace $(EXTRA_TEST_BINS)

test: deps
	@$(MAKE) --no-print-directory test-build
	@B=$(B) UNIT_TESTS="$(UNIT_TESTS)" tests/run_tests.sh

test-build: $(TEST_BINS) firmware $(PLUGIN_SO)

bench: deps
	@$(MAKE) --no-print-directory all firmware opcal $(B)/host/embree-race $(B)/sim/ssbench
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

clean:
	rm -rf $(B)

.PHONY: all sim deps run test test-build bench clean firmware plots layout index
