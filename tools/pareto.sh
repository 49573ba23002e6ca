#!/usr/bin/env bash
# pareto.sh - make pareto: runs lanetrace tune (docs/tune.md) on the bundled teapot and the shared
# meshes, then regenerates docs/tradeoffs.md and its plots (docs/tradeoffs/<scene>.png) from the
# runs' front.json with tools/pareto.py: the fronts, the picks for a tight, a medium and a loose
# budget, what each knob buys, and quadtree reprojection against BVH tracing per pixel. Every
# figure in the document comes from these runs; nothing is typed.
#   PARETO_SCENES  meshes to tune (default: the teapot, then every mesh of ../shared: the Cornell
#                  boxes, bunny, dragon, Sibenik, Sponza and the Conference room; about 10 minutes
#                  on 2 cores at 128 px)
#   PARETO_RES     image side (default 128); PARETO_JOBS worker processes (default 2)
#   PARETO_PROBE_RES  probe size (default 0: every configuration at full size, exact fronts)
# Run from the repository root after make all.
set -euo pipefail
B=${B:-build}
RES=${PARETO_RES:-128}
JOBS=${PARETO_JOBS:-2}
PROBE=${PARETO_PROBE_RES:-0}
OUT=$B/pareto
shared=../shared/scenes
if [ -z "${PARETO_SCENES:-}" ]; then
    PARETO_SCENES="scenes/teapot.obj"
    for s in cornell_box.obj CornellBox-Original.obj bunny.obj dragon_res3.obj sibenik.obj \
        sponza.obj conference.obj.gz; do
        [ -f "$shared/$s" ] && PARETO_SCENES="$PARETO_SCENES $shared/$s"
    done
fi
mkdir -p "$OUT" docs/tradeoffs
runs=()
for s in $PARETO_SCENES; do
    name=$(basename "$s" .gz)
    name=${name%.obj}
    echo "pareto: tune $s (${RES} px, --jobs $JOBS)"
    t0=$(date +%s)
    "$B/sim/lanetrace" tune "$s" --res "$RES" --probe-res "$PROBE" --jobs "$JOBS" --out "$OUT/$name" -q >"$OUT/$name.txt" 2>&1 || {
        echo "pareto: tune $s failed: $(tail -1 "$OUT/$name.txt")"
        exit 1
    }
    echo "pareto:   $(grep '^search' "$OUT/$name.txt" | sed 's/^search *//') (wall $(($(date +%s) - t0)) s)"
    cp "$OUT/$name/front.png" "docs/tradeoffs/$name.png"
    runs+=("$OUT/$name/front.json")
done
python3 tools/pareto.py docs/tradeoffs.md "${runs[@]}"
echo "pareto: docs/tradeoffs.md and docs/tradeoffs/*.png written from ${#runs[@]} tune runs"
