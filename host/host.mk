# host.mk - the shipped programs, built from host/ and firmware/apps/ only (included by the
# Makefile; `make layout` checks that no file under tests/ goes into one of them):
#   build/sim/lanetrace          the CLI, simulator build: every lane op charged, cycle reports
#   build/host/lanetrace-native  the same CLI at native speed (LT_COST_OFF)
#   build/host/lt-stream         the report-stream receiver: file/pipe/stdin, serial, TCP, USB HID
#   build/host/lt-faultinject    the stream fault injector with ground truth
#   build/sim/lt-stream-dev      the simulator acting as a streaming device (the firmware's device
#                                code, firmware/apps/stream_dev.c)
# STREAM_HID selects the hidapi backend by pkg-config name (hidapi-hidraw; hidapi-libusb works
# too); when pkg-config does not know it, lt-stream is built without HID support and says so.

# Each program's link inputs are a variable, PROD_<name>, so `make print-product-deps` can list them.
PROD_lanetrace_native := $(B)/host/obj/host/cli/lanetrace_main.o $(host_CORE_OBJS) $(host_HOST_OBJS)
PROD_lanetrace := $(B)/sim/obj/host/cli/lanetrace_main.o $(sim_CORE_OBJS) $(sim_HOST_OBJS) \
    $(sim_EXTRA_OBJS)
PROD_lt_stream := $(B)/host/obj/host/stream/lt_stream_main.o \
    $(B)/host/obj/host/stream/usb/lt_rx_hid.o $(host_CORE_OBJS) $(host_HOST_OBJS)
PROD_lt_faultinject := $(B)/host/obj/host/stream/lt_faultinject_main.o $(host_CORE_OBJS) \
    $(host_HOST_OBJS)
PROD_lt_stream_dev := $(B)/sim/obj/host/stream/lt_stream_dev_main.o \
    $(B)/sim/obj/firmware/apps/stream_dev.o $(sim_CORE_OBJS) $(sim_HOST_OBJS) $(sim_EXTRA_OBJS)
PRODUCTS := $(B)/sim/lanetrace $(B)/host/lanetrace-native $(B)/host/lt-stream \
    $(B)/host/lt-faultinject $(B)/sim/lt-stream-dev
PRODUCT_VARS := lanetrace lanetrace_native lt_stream lt_faultinject lt_stream_dev

$(B)/host/lanetrace-native: $(PROD_lanetrace_native)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_host)
$(B)/sim/lanetrace: $(PROD_lanetrace)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_sim)

STREAM_HID ?= hidapi-hidraw
STREAM_HID_CFLAGS := $(shell pkg-config --cflags $(STREAM_HID) 2>/dev/null)
STREAM_HID_LIBS := $(shell pkg-config --libs $(STREAM_HID) 2>/dev/null)
ifeq ($(strip $(STREAM_HID_LIBS)),)
STREAM_HID_CFLAGS := -DLT_RX_NO_HIDAPI
endif

$(B)/host/obj/host/stream/usb/lt_rx_hid.o: host/stream/usb/lt_rx_hid.c host/host.mk | $(B)/gen/lt_machines.inc
	@mkdir -p $(@D)
	@echo "CC [host] $<"
	@$(CC) $(CFLAGS_host) $(HOST_INC) $(STREAM_HID_CFLAGS) -c $< -o $@

$(B)/host/lt-stream: $(PROD_lt_stream)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_host) $(STREAM_HID_LIBS)
$(B)/host/lt-faultinject: $(PROD_lt_faultinject)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_host)
$(B)/sim/lt-stream-dev: $(PROD_lt_stream_dev)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_sim)

# Sanitizer builds (ASan + UBSan) of every shipped program: build/asan/<program>, linked from the
# same inputs as the program with build/host -> build/asan and build/sim -> build/asansim objects
# (the USB backend: its own rule below). The CLI tests run against them in make test
# (tests/run_tests.sh, LT_HOSTBIN / LT_SIMBIN).
ASAN_PRODUCTS := $(foreach v,$(PRODUCT_VARS),$(B)/asan/$(subst _,-,$(v)))
define asan_product
$(B)/asan/$(subst _,-,$(1)): $$(subst $(B)/sim/,$(B)/asansim/,$$(subst $(B)/host/,$(B)/asan/,$$(PROD_$(1))))
	@mkdir -p $$(@D)
	@echo "LD $$@"
	@$$(CC) $$(LDFLAGS_asan) -o $$@ $$^ $$(LIBS_asan) $(if $(filter lt_stream,$(1)),$$(STREAM_HID_LIBS))
endef
$(foreach v,$(PRODUCT_VARS),$(eval $(call asan_product,$(v))))
$(B)/asan/obj/host/stream/usb/lt_rx_hid.o: host/stream/usb/lt_rx_hid.c host/host.mk | $(B)/gen/lt_machines.inc
	@mkdir -p $(@D)
	@echo "CC [asan] $<"
	@$(CC) $(CFLAGS_asan) $(HOST_INC) $(STREAM_HID_CFLAGS) -c $< -o $@
asan-products: $(ASAN_PRODUCTS)

# ThreadSanitizer build of the native CLI (the threaded tile loops; tests/run.d/threads.sh)
$(B)/tsan/lanetrace-native: $(subst $(B)/host/,$(B)/tsan/,$(PROD_lanetrace_native))
	@echo "LD $@"
	@$(CC) $(LDFLAGS_tsan) -o $@ $^ $(LIBS_tsan)

products: $(PRODUCTS)
# the link inputs of every shipped program, one program per line (`make layout` reads them)
print-product-deps:
	@$(foreach v,$(PRODUCT_VARS),echo "$(v): $(PROD_$(v))";)
EXTRA_TEST_BINS += $(PRODUCTS) $(ASAN_PRODUCTS)
.PHONY: products asan-products print-product-deps
