# frusta.mk - multi-frusta soft shadows tests and benchmarks (docs/frusta.md); included by the
# top-level Makefile. The program itself is `lanetrace shadows` (host/cli/lt_shadows_cli.c).
#   build/host/frusta-race   S-Frusta and S-Packet shadow rays per second against Embree 3
#                            rtcOccluded16 on the same rays, single thread (Embree linked only here)
# The firmware shadow tile (tests/fw/fw_frusta.c, build/fw/<T>/frusta.elf) comes from
# firmware.mk's image template; `make test` compares its hash with the host unit test
# (tests/run.d/frusta.sh).
$(B)/host/frusta-race: $(B)/host/obj/tests/bench/frusta_race.o $(host_CORE_OBJS) $(host_HOST_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_host) -lembree3
frusta: $(B)/sim/lanetrace $(B)/host/lanetrace-native $(B)/host/frusta-race
FRUSTA_FW_IMAGES := $(foreach t,$(FW_TARGETS),$(B)/fw/$(t)/frusta.elf)
EXTRA_TEST_BINS += $(B)/host/frusta-race $(FRUSTA_FW_IMAGES)
frusta-fw: $(FRUSTA_FW_IMAGES)
.PHONY: frusta frusta-fw
