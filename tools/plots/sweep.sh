#!/usr/bin/env bash
# sweep.sh OUT.csv - run lanetrace over scenes x numeric paths x machines and collect one CSV
# (the input of `make plots`). Scenes: the bundled teapot, plus ../shared scenes when present.
set -euo pipefail
B=${B:-build}
out=$1
res=${SWEEP_RES:-64}
scenes=(scenes/teapot.obj)
for s in ../shared/scenes/bunny.obj ../shared/scenes/CornellBox-Original.obj; do
    [ -f "$s" ] && scenes+=("$s")
done
tmpd=$(mktemp -d)
trap 'rm -rf "$tmpd"' EXIT
first=1
for s in "${scenes[@]}"; do
    for m in lrb16 mcu-m4; do
        "$B/sim/lanetrace" run --mesh "$s" --res "$res" --machine "$m" --csv "$tmpd/one.csv" -q >/dev/null
        if [ $first -eq 1 ]; then head -1 "$tmpd/one.csv" >"$out.tmp"; first=0; fi
        tail -n +2 "$tmpd/one.csv" >>"$out.tmp"
    done
done
mv "$out.tmp" "$out"
echo "sweep: $(($(wc -l <"$out") - 1)) rows -> $out"
