#!/usr/bin/env bash
# run_table.sh - the "Cycle report of the bundled scene" table of docs/results.md, measured now:
# runs build/sim/lanetrace run scenes/teapot.json (as `make run` does: the recommendation is the default) with a report per path
# and prints the Markdown table from the reports. Usage: tools/run_table.sh [extra run flags]
# (make run-doc writes it into docs/results.md between its run-table markers)
set -euo pipefail
B=${B:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$B/sim/lanetrace" run scenes/teapot.json --report "$tmp/r.json" -q "$@" >/dev/null
python3 - "$tmp" <<'PY'
import json, sys, os
d = sys.argv[1]
print("| path | structure | total cycles | cycles/ray | without the build | rays/s at %s | traverse | intersect | lane utilisation | L1 hits |" % "the clock")
print("|---|---|---|---|---|---|---|---|---|---|")
for p, name in (("q16", "s15.16"), ("f32", "float32")):
    f = os.path.join(d, "r.%s.json" % p)
    if not os.path.exists(f):
        continue
    j = json.load(open(f))
    tot = j["total_cycles"]
    ph = j["phases"]
    c = j["cache"]
    print("| %s | %s | %s | %.1f | %.1f | %.2f M (%s, %d MHz) | %.1f%% | %.1f%% | %.1f%% | %.2f%% |" % (
        name, j["structure"], format(tot, ","), j["cycles_per_ray"], j["trace_cycles_per_ray"],
        j["mrays_per_s"], j["machine"], j["clock_mhz"],
        100.0 * ph.get("TRAVERSE", {}).get("cycles", 0) / tot,
        100.0 * ph.get("INTERSECT", {}).get("cycles", 0) / tot,
        100.0 * j["lane_utilisation"], 100.0 * c["l1_hits"] / max(c["l1_accesses"], 1)))
PY
