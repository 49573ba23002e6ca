# agree.mk - hit agreement with the double reference on real meshes (tests/agree/lt_agree.c), native
# build (speed); tests/run.d/agree.sh runs it on every shared scene. Usage: build/host/lt-agree MESH
# [--res N] [--min PCT] [--structures grid,kd,bvh,bvhq]
$(B)/host/lt-agree: $(B)/host/obj/tests/agree/lt_agree.o $(host_CORE_OBJS) $(host_HOST_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_host)
EXTRA_TEST_BINS += $(B)/host/lt-agree
