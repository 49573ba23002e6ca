# kdgrid.mk - the kd-tree / grid parameter sweep (tests/bench/kdgrid_sweep.c), sim build only:
#   make build/sim/kdgrid-sweep && build/sim/kdgrid-sweep [scene.obj [resolution]]
# It prints the per-parameter numbers of docs/kdtree-grid.md; `make test` does not need it.
$(B)/sim/kdgrid-sweep: $(B)/sim/obj/tests/bench/kdgrid_sweep.o $(sim_CORE_OBJS) $(sim_HOST_OBJS) \
    $(sim_EXTRA_OBJS)
	$(CC) -o $@ $^ $(LIBS_sim)
