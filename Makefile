# lanetrace - one non-recursive Makefile for the three builds of one source:
#   build/host  native (LT_COST_OFF, -O2 -march=native): the golden reference and the speed race
#   build/sim   the same kernels with LT_COST_SIM, linked to sim/: cycle reports
#   build/asan  host build with ASan + UBSan, used by the tests
#   build/fw/<target>  freestanding firmware images for cm4, cm55, rv32 (QEMU)
# Main targets: deps all run test firmware sim bench clean (see README.md).

.SUFFIXES:
.DELETE_ON_ERROR:
SHELL := /bin/bash

B ?= build
CC ?= gcc
WARN := -std=c99 -Wall -Wextra -Wpedantic -Werror -Wshadow -Wundef -Wstrict-prototypes \
    -Wmissing-prototypes -Wcast-align -Wconversion
# Float32 results are bit-identical across builds only without FMA contraction or fast-math.
FPFLAGS := -ffp-contract=off -fno-fast-math
INC := -Ifirmware/include -Isim -Ihost -Itests/unit -Itests/vectors -isystem /usr/include/OpenEXR
# -Wno-format-truncation: host messages are built with snprintf, whose truncation is the intent
HOST_CFLAGS := $(WARN) -Wdouble-promotion -Wno-format-truncation $(FPFLAGS) -O2 -g -fno-var-tracking-assignments $(INC) -D_POSIX_C_SOURCE=200809L
NATIVE_ARCH ?= -march=native

CORE_SRCS := $(wildcard firmware/core/*.c)
CORE_HDRS := $(wildcard firmware/include/lt/*.h firmware/include/lt/*.def firmware/core/*.inc)
# host library: every host/*.c except program mains (*_main.c)
HOSTLIB_SRCS := $(filter-out %_main.c,$(wildcard host/*.c))
HOSTLIB_HDRS := $(wildcard host/*.h)
SIM_SRCS := sim/lt_sim.c sim/lt_cache.c
SIM_HDRS := $(wildcard sim/*.h sim/machines/*.def)
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

define variant_rules
$(B)/$(1)/obj/%.o: %.c $(CORE_HDRS) $(HOSTLIB_HDRS) $(SIM_HDRS) Makefile
	@mkdir -p $$(@D)
	@echo "CC [$(1)] $$<"
	@$(CC) $(CFLAGS_$(1)) -c $$< -o $$@
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

# the CLI: the simulator build (cycle reports) and the native build, from one source
$(B)/host/lanetrace-native: $(B)/host/obj/host/lanetrace_main.o $(host_CORE_OBJS) $(host_HOST_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_host)
$(B)/sim/lanetrace: $(B)/sim/obj/host/lanetrace_main.o $(sim_CORE_OBJS) $(sim_HOST_OBJS) \
    $(sim_EXTRA_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_sim)
$(B)/sim/test_cache: $(B)/sim/obj/tests/unit/test_cache.o $(B)/sim/obj/sim/lt_cache.o
	@echo "LD $@"
	@$(CC) -o $@ $^ -lcmocka

$(B)/sim/slab-model: $(B)/sim/obj/tests/bench/slab_model.o $(B)/sim/obj/tests/vectors/lt_slab_loop.o \
    $(sim_CORE_OBJS) $(sim_EXTRA_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_sim)

sim: $(B)/sim/lanetrace

# ---- firmware ----------------------------------------------------------------------------------
include firmware/targets/targets.mk
include sim/qemu/plugin.mk
include firmware/firmware.mk
include firmware/opcal.mk
# feature fragments add their own programs and images (each documents what it builds)
include $(sort $(wildcard host/*.mk tests/*.mk))

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
	@$(MAKE) --no-print-directory all firmware opcal $(B)/host/embree-race $(B)/sim/ssbench \
	    $(B)/sim/lanetrace-shadows
	@tests/bench/bench.sh

# CSV sweep -> PNG plots (gnuplot): cycles per phase, error vs cycles, lane utilisation
plots: deps
	@$(MAKE) --no-print-directory all
	@mkdir -p $(B)/plots
	@B=$(B) tools/plots/sweep.sh $(B)/plots/sweep.csv
	@tools/plots/plots.sh $(B)/plots/sweep.csv $(B)/plots

clean:
	rm -rf $(B)

.PHONY: all sim deps run test test-build bench clean firmware plots
