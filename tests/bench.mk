# bench.mk - benchmark programs (auto-included by the Makefile; `make bench` runs them).
#   build/host/embree-race  lanetrace native vs Embree 3 at its best on this machine (every packet
#                           width, both context flags, warm-up, median), single thread, same rays
#                           (linked to Embree only here)
#   make race-doc           the race on the bundled teapot and the shared scenes (1024x1024, median
#                           of 3; about a minute, needs ../shared) into docs/results.md between its
#                           race markers, the machine and ISA in the caption (tests/bench/race_doc.sh)
$(B)/host/embree-race: $(B)/host/obj/tests/bench/embree_race.o $(host_CORE_OBJS) $(host_HOST_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_host) -lembree3
EXTRA_TEST_BINS += $(B)/host/embree-race

race-doc: deps
	@$(MAKE) --no-print-directory $(B)/host/embree-race
	@B=$(B) tests/bench/race_doc.sh
.PHONY: race-doc
