# bench.mk - benchmark programs (auto-included by the Makefile; `make bench` runs them).
#   build/host/embree-race  lanetrace native vs Embree 3, single thread, same rays (linked to Embree only here)
$(B)/host/embree-race: $(B)/host/obj/tests/bench/embree_race.o $(host_CORE_OBJS) $(host_HOST_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_host) -lembree3
EXTRA_TEST_BINS += $(B)/host/embree-race
