# frusta.mk - multi-frusta soft shadows (docs/frusta.md); included by the top-level Makefile.
#   build/sim/lanetrace-shadows          the soft-shadow renderer with cycle counts per stage and
#                                        the Table-1-style report (every lane op charged)
#   build/host/lanetrace-shadows-native  the same program at native speed (timings, images)
#   build/host/frusta-race               S-Frusta and S-Packet shadow rays per second against
#                                        Embree 3 rtcOccluded16 on the same rays, single thread
#                                        (Embree linked only here)
$(B)/sim/lanetrace-shadows: $(B)/sim/obj/host/lt_shadows_main.o $(sim_CORE_OBJS) $(sim_HOST_OBJS) \
    $(sim_EXTRA_OBJS)
	$(CC) -o $@ $^ $(LIBS_sim)
$(B)/host/lanetrace-shadows-native: $(B)/host/obj/host/lt_shadows_main.o $(host_CORE_OBJS) \
    $(host_HOST_OBJS)
	$(CC) -o $@ $^ $(LIBS_host)
$(B)/host/frusta-race: $(B)/host/obj/tests/bench/frusta_race.o $(host_CORE_OBJS) $(host_HOST_OBJS)
	$(CC) -o $@ $^ $(LIBS_host) -lembree3
frusta: $(B)/sim/lanetrace-shadows $(B)/host/lanetrace-shadows-native $(B)/host/frusta-race
# `make bench` prints the frusta Table 1 (tests/bench/bench.sh step 6)
bench: $(B)/sim/lanetrace-shadows
EXTRA_TEST_BINS += $(B)/sim/lanetrace-shadows $(B)/host/lanetrace-shadows-native \
    $(B)/host/frusta-race
.PHONY: frusta
# firmware: the shared shadow-tile workload under QEMU (tests/fw/fw_frusta.c); `make test` runs it
# and compares its hash with the host unit test (tests/run.d/frusta.sh)
define frusta_fw_rules
$(B)/fw/$(1)/obj/tests/fw/fw_frusta.o: tests/vectors/lt_frusta_tile.h
$(B)/fw/$(1)/frusta.elf: $(B)/fw/$(1)/obj/tests/fw/fw_frusta.o $$(fw_$(1)_CORE) $$(fw_$(1)_RT)
	@echo "LD $$@"
	@$(CC_$(1)) $(LDFLAGS_$(1)) -o $$@ $$^ $(LDLIBS_$(1))
endef
$(foreach t,$(FW_TARGETS),$(eval $(call frusta_fw_rules,$(t))))
FRUSTA_FW_IMAGES := $(foreach t,$(FW_TARGETS),$(B)/fw/$(t)/frusta.elf)
$(B)/host/obj/tests/unit/test_frusta.o $(B)/sim/obj/tests/unit/test_frusta.o \
    $(B)/asan/obj/tests/unit/test_frusta.o: tests/vectors/lt_frusta_tile.h
EXTRA_TEST_BINS += $(FRUSTA_FW_IMAGES)
frusta-fw: $(FRUSTA_FW_IMAGES)
.PHONY: frusta-fw
