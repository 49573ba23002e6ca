# leak.mk - leaks through the whole pipeline on closed meshes (tests/leak/lt_leak.c), native build;
# tests/run.d/leak.sh runs it on the closed shared meshes and a 4x-subdivided dragon. Usage:
# build/host/lt-leak MESH [--res N] [--subdiv K] [--isect wt|mt|both] [--num q16|f32|both]
$(B)/host/lt-leak: $(B)/host/obj/tests/leak/lt_leak.o $(host_CORE_OBJS) $(host_HOST_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_host)
EXTRA_TEST_BINS += $(B)/host/lt-leak
