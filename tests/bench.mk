# bench.mk - benchmark programs (auto-included by the Makefile; `make bench` runs them).
#   build/host/embree-race  lanetrace native vs Embree 3 at its best on this machine (every packet
#                           width, both context flags, warm-up, median), single thread, same rays
#                           (linked to Embree only here)
#   make race-doc           the race on the bundled teapot and the shared scenes (1024x1024, median
#                           of 3; about a minute, needs ../shared) into docs/results.md between its
#                           race markers, the machine and ISA in the caption (tests/bench/race_doc.sh)
#   build/avx2/embree-race  the same race with lanetrace built for x86-64-v3 (the AVX2 lane backend)
#   make race-doc-avx2      the race as an AVX2-only host runs it: build/avx2/embree-race with Embree
#                           limited to AVX2 (--embree-config isa=avx2), into docs/results.md between
#                           its race-avx2 markers (needs a CPU with AVX2)
#   make frusta-race-doc    the native soft-shadow race (build/host/frusta-race: S-Frusta and
#                           S-Packet against Embree's best occlusion mode, both paths, 512x512, the
#                           shared interiors, bunny and dragon; a few minutes, needs ../shared) into
#                           docs/frusta.md between its frusta-race markers
#   make speed-doc          the cost of counting (tests/bench/counting.sh) and the all-core scaling
#                           (tests/bench/scaling.sh; the shared dragon, about a minute) into
#                           docs/results.md between their counting and scaling markers
$(B)/host/embree-race: $(B)/host/obj/tests/bench/embree_race.o $(host_CORE_OBJS) $(host_HOST_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_host) -lembree3
EXTRA_TEST_BINS += $(B)/host/embree-race
$(B)/avx2/embree-race: $(B)/avx2/obj/tests/bench/embree_race.o $(avx2_CORE_OBJS) $(avx2_HOST_OBJS)
	@echo "LD $@"
	@$(CC) -o $@ $^ $(LIBS_avx2) -lembree3

race-doc: deps
	@$(MAKE) --no-print-directory $(B)/host/embree-race
	@B=$(B) tests/bench/race_doc.sh
.PHONY: race-doc

race-doc-avx2: deps
	@$(MAKE) --no-print-directory $(B)/avx2/embree-race
	@B=$(B) VARIANT=avx2 RACE_ARGS="--embree-config isa=avx2" tests/bench/race_doc.sh
.PHONY: race-doc-avx2

frusta-race-doc: deps
	@$(MAKE) --no-print-directory $(B)/host/frusta-race $(B)/host/lt-vectors
	@B=$(B) tests/bench/frusta_race_doc.sh
.PHONY: frusta-race-doc

speed-doc: deps
	@$(MAKE) --no-print-directory all
	@B=$(B) tests/bench/counting.sh --md $(B)/counting.md
	@B=$(B) tests/bench/scaling.sh --md $(B)/scaling.md
	@tools/doc_insert.sh counting $(B)/counting.md docs/results.md
	@tools/doc_insert.sh scaling $(B)/scaling.md docs/results.md
.PHONY: speed-doc
