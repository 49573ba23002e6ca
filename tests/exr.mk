# exr.mk - the multi-part / multi-view EXR test files for the CLI tests: build/host/lt-exr-stereo
# (tests/exr/lt_exr_stereo.c over tests/unit/lt_exr_testlib.h, which tests/unit/test_exr.c uses
# too); tests/run.d/cli.sh and reproject.sh run it. Test tool, not shipped.
$(B)/host/lt-exr-stereo: $(B)/host/obj/tests/exr/lt_exr_stereo.o $(B)/host/obj/host/io/lt_exr.o \
    $(B)/host/obj/host/io/lt_diag.o $(B)/host/obj/host/io/lt_tmpfiles.o
	@echo "LD $@"
	@$(CC) -o $@ $^ -lOpenEXRCore-3_1 -lm
EXTRA_TEST_BINS += $(B)/host/lt-exr-stereo
