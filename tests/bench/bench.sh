#!/usr/bin/env bash
# bench.sh - benchmarks printed as ratios against a peer measured in the same run (make bench):
#  1. the cost of counting: the same kernels on the same frames, native (LT_COST_OFF) vs counted
#     (LT_COST_SIM, lrb16 with caches), one thread each; target: counted <= 3x native
#     (tests/bench/counting.sh);
#  2. the scalar MCU model vs measured instructions: mcu-m4's predicted cycles for the slab-test loop
#     vs the instructions QEMU's lt_icount plugin counts inside lt_slab16_q16 on Cortex-M4;
# 2b. the integer-only rv32imac model vs measured instructions: the s15.16 and soft-float float32
#     slab and triangle kernels on RV32IMAC (tests/bench/opcal.sh rv32, its kernel lines);
#  3. the race against Embree 3 at its best on this machine (native, single thread, same rays; all
#     shared scenes): rtcIntersect1/4/8/16 and rtcOccluded1/4/8/16, both context flags, a warm-up,
#     the median; the CPU, its ISA and Embree's native packet widths printed first (make race-doc
#     writes the table of docs/results.md);
# 3b. every core: render/run, shadows and reproject on one thread vs every online core
#     (tests/bench/scaling.sh; target >= 1.8x on 2 cores);
#  4. structures: grid vs kd-tree vs BVH in the simulator (tests/bench/structures.sh);
#  5. the cycle report of the bundled scene on lrb16;
#  6. screen-space baselines: quadtree vs DDA vs Hi-Z on the same rays (build/sim/ssbench);
#  7. the multi-frusta Table 1 (docs/frusta.md): P-Packet vs P-Frusta and S-Packet vs S-Frusta in
#     the simulator on Sibenik at 1024x1024 (~20 s), the bundled teapot at 256x256 without ../shared;
#     7b. the same shadow rays natively against Embree's best occlusion mode (build/host/frusta-race,
#     Sibenik 512x512, both paths; make frusta-race-doc for every scene);
#  8. view synthesis against ray-traced ground truth (tests/bench/rptruth.sh): depth error of the
#     quadtree reprojection per numeric configuration on the teapot and the shared meshes (~15 s);
#  9. lanetrace tune: how long each family's sweep takes and how many points it measures
#     (tests/bench/tune_bench.sh; teapot and bunny, 128 px, --jobs 2, ~1 min);
# 10. the machine files' quadtree rows (LT_MACHINE_QT): cycles per pixel of a reprojection in each
#     node format on every machine, Beachball and Trunks (tests/bench/qtcal.sh, ~10 s).
# Run from the repository root after make all firmware build/sim/slab-model build/plugin/lt_icount.so.
set -euo pipefail
B=build
SCENE=${BENCH_SCENE:-scenes/teapot.obj}
RES=${BENCH_RES:-128}
REP=${BENCH_REPEAT:-10}

echo "== 1. cost of counting: native vs counted, one thread each (tests/bench/counting.sh)"
B=$B BENCH_SCENE="$SCENE" BENCH_RES="$RES" BENCH_REPEAT="$REP" tests/bench/counting.sh

echo "== 2. mcu-m4 model vs QEMU instruction counts (Cortex-M4, mps2-an386, lt_icount plugin)"
source <(make -s --no-print-directory -f tools/print_qemu.mk)
pred=$("$B/sim/slab-model" mcu-m4 256 | awk '{print $NF}')
out=$(mktemp)
timeout 60 $QEMU_cm4 "$B/fw/cm4/slab.elf" -plugin "$B/plugin/lt_icount.so,sym=lt_slab16_q16,out=$out" >/dev/null
cnt=$(awk '/^icount sym lt_slab16_q16/{print $4}' "$out")
rm -f "$out"
awk -v p="$pred" -v c="$cnt" 'BEGIN{printf "lt_slab16_q16 x256: predicted %d cycles, counted %d instructions, predicted/counted %.3f\n", p, c, p/c}'
pred=$("$B/sim/tri-model" mcu-m4 | awk '{print $NF}')
out=$(mktemp)
# the triangle kernel's own instructions plus the helpers it calls (struct copies, 64-bit divides)
syms="lt_tri16_q16 lt__tri_tdiv16_q16 lt__memcpy memcpy __aeabi_ldivmod __udivmoddi4"
timeout 60 $QEMU_cm4 "$B/fw/cm4/tri.elf" -plugin "$B/plugin/lt_icount.so,$(printf 'sym=%s,' $syms)out=$out" >/dev/null
cnt=$(awk '/^icount sym/{s += $4} END{print s}' "$out")
awk '/^icount sym/{printf "   %-16s %d\n", $3, $4}' "$out"
rm -f "$out"
awk -v p="$pred" -v c="$cnt" 'BEGIN{printf "lt_tri16_q16 (+helpers): predicted %d cycles, counted %d instructions, predicted/counted %.3f\n", p, c, p/c}'

echo "== 2b. rv32imac model vs QEMU instruction counts (RV32IMAC, virt, soft float; tests/bench/opcal.sh rv32)"
tests/bench/opcal.sh rv32 | grep -E '^lt_(slab|tri)16_(q16|f32) '

echo "== 3. race against Embree 3 at its best on this machine (native build, single thread, same rays, 1024x1024; every packet width and context flag, warm-up, median)"
STRUCT=${BENCH_STRUCTURE:-bvh}
"$B/host/embree-race" --mesh "$SCENE" --res 1024 --runs 5 --structure "$STRUCT"
for m in bunny.obj dragon_res3.obj sponza.obj sibenik.obj conference.obj.gz CornellBox-Original.obj; do
    if [ -f "../shared/scenes/$m" ]; then
        "$B/host/embree-race" --mesh "../shared/scenes/$m" --res 1024 --runs 3 --structure "$STRUCT"
    fi
done

echo "== 3b. every core: the native build on --threads 1 vs every online core (tests/bench/scaling.sh; target >= 1.8x on 2 cores)"
B=$B tests/bench/scaling.sh

echo "== 4. structures: grid vs kd-tree vs BVH (lrb16, simulator, ${STRUCT_RES:-128}x${STRUCT_RES:-128})"
B=$B tests/bench/structures.sh

echo "== 4b. intersector: watertight (default) vs Moller-Trumbore vs the s15.16 grid test (wt32), BVH trace cycles per ray (lrb16, simulator, 128x128; docs/watertight.md)"
for m in scenes/teapot.obj ../shared/scenes/bunny.obj ../shared/scenes/dragon_res3.obj; do
    [ -f "$m" ] || continue
    for is in wt mt wt32; do
        nums=both
        [ "$is" = wt32 ] && nums=q16
        "$B/sim/lanetrace" run --mesh "$m" --res 128 --isect "$is" --num "$nums" --no-ref 2>&1 |
            awk -v m="$(basename "$m")" -v is="$is" '/^result/ {p = $2} /^rays/ {for (i = 1; i <= NF; i++) if ($i == "build:") c = $(i + 1); printf "  %-16s %-4s %s  %s cycles/ray (trace only)\n", m, p, is, c}'
    done
done
echo "   larger sweeps: build/host/lt-leak MESH --res 1024 --isect all [--subdiv 1] (leak counts per structure)"
echo "   on the targets (instructions per ray, wt against wt32): make test, tests/run.d/fwscene.sh (scene-bunny-wt32.elf)"

echo "== 5. cycle report: bundled scene on lrb16"
"$B/sim/lanetrace" run --mesh "$SCENE" --res "$RES" --structure "$STRUCT" --num both --report "$B/bench-report.json"
echo "== 6. screen-space baselines: quadtree vs DDA vs Hi-Z, same rays (lrb16, simulator; docs/ss-baselines.md)"; "$B/sim/ssbench"

echo "== 7. multi-frusta Table 1: primary and soft-shadow frusta vs 16-ray packets (lrb16 simulator)"
if [ -f ../shared/scenes/sibenik.obj ]; then
    "$B/sim/lanetrace" shadows --mesh ../shared/scenes/sibenik.obj --res "${FRUSTA_RES:-1024}" --no-ref
else
    echo "(../shared missing: the bundled teapot instead of Sibenik)"
    "$B/sim/lanetrace" shadows --mesh "$SCENE" --res "${FRUSTA_RES:-256}" --no-ref
fi

echo "== 7b. native soft shadows: S-Frusta and S-Packet against Embree's best occlusion mode (one thread, same rays; docs/frusta.md)"
if [ -f ../shared/scenes/sibenik.obj ]; then
    for p in q16 f32; do
        "$B/host/frusta-race" --mesh ../shared/scenes/sibenik.obj --res 512 --runs 3 --num "$p"
    done
else
    echo "(../shared missing: skipped, it races the shared interiors)"
fi

echo "== 8. view synthesis vs ray-traced ground truth: depth error per numeric configuration (lrb16 simulator; docs/reproject.md)"
B=$B tests/bench/rptruth.sh

echo "== 9. lanetrace tune: each family's sweep, its points and wall time (--jobs 2, docs/tune.md)"
B=$B tests/bench/tune_bench.sh

echo "== 10. the machines' quadtree rows: reprojection cycles per pixel per node format (tests/bench/qtcal.sh)"
tests/bench/qtcal.sh "$B/sim/lanetrace"

echo "== 11. firmware: instructions per ray of real meshes on cm4, cm55 and rv32 (scene blobs under QEMU, lt_icount plugin; tools/fw_rays.sh, docs/firmware.md)"
B=$B tools/fw_rays.sh

echo "== 12. firmware cycle models: the plugin's modelled cycles per kernel family against the fitted machine files' prediction, out of sample (tools/fw_cycles.sh, docs/firmware.md, \"Cycle models\")"
B=$B tools/fw_cycles.sh
