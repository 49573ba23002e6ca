#!/usr/bin/env bash
# tune_bench.sh - how long lanetrace tune's sweep of each family takes and how many points it
# measures (make bench, section 9; docs/tune.md): the bundled teapot and, when ../shared is
# there, the bunny, at the default size (TUNE_RES, 128) with --jobs 2, one family at a time, both
# machine models. Prints one line per scene and family: configurations, probes, pruned, measured
# at full size, front size, wall seconds. Run from the repository root after make all.
set -uo pipefail
B=${B:-build}
RES=${TUNE_RES:-128}
OUT=$B/bench-tune
mkdir -p "$OUT"
scenes=(scenes/teapot.obj)
[ -f ../shared/scenes/bunny.obj ] && scenes+=(../shared/scenes/bunny.obj)
printf '%-10s %-8s %8s %7s %7s %9s %6s %8s\n' scene family configs probed pruned full-size front wall_s
for s in "${scenes[@]}"; do
    name=$(basename "$s" .obj)
    for fam in object screen shadows; do
        t0=$(date +%s.%N)
        if ! "$B/sim/lanetrace" tune "$s" --family "$fam" --res "$RES" --jobs 2 \
            --out "$OUT/$name-$fam" -q >"$OUT/$name-$fam.txt" 2>&1; then
            echo "$name $fam: tune failed: $(tail -1 "$OUT/$name-$fam.txt")"
            continue
        fi
        t1=$(date +%s.%N)
        python3 - "$OUT/$name-$fam/front.json" "$name" "$fam" "$t0" "$t1" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
c = d["counts"]
print("%-10s %-8s %8d %7d %7d %9d %6d %8.1f" % (sys.argv[2], sys.argv[3], c["points"], c["probed"],
      c["pruned"], c["full"], c["front"], float(sys.argv[5]) - float(sys.argv[4])))
PY
    done
done
