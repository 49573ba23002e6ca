#!/usr/bin/env bash
# frusta_race_doc.sh - docs/frusta.md's native soft-shadow race against Embree 3 regenerated on
# this machine (make frusta-race-doc): build/host/frusta-race --kv on the shared interiors and the
# bunny and dragon (RES 512, RUNS 3), both numeric paths, lanetrace at its shipped defaults and
# Embree at its best mode (rtcOccluded1/4/8/16, both context flags, warm-up, median). Written to
# $B/frusta-race/race.md (each run's output beside it) and put between the
# <!-- frusta-race:begin --> / <!-- frusta-race:end --> markers of docs/frusta.md. Without
# ../shared (SHARED=...) it says so and leaves the page alone: exit 1 under CI=true, else 0.
# Usage: tests/bench/frusta_race_doc.sh   (from the repository root; B=build RES=512 RUNS=3
#        DOC=docs/frusta.md)
set -euo pipefail
B=${B:-build}
SHARED=${SHARED:-../shared}
RES=${RES:-512}
RUNS=${RUNS:-3}
DOC=${DOC:-docs/frusta.md}
RACE="$B/host/frusta-race"
OUT="$B/frusta-race"
scenes=(sibenik.obj sponza.obj conference.obj.gz bunny.obj dragon_res3.obj)

skip() {
    echo "frusta-race-doc: $1; $DOC is left as it was" >&2
    if [ "${CI:-}" = true ]; then
        echo "frusta-race-doc: CI=true: failing (clone the shared scenes beside this repository as $SHARED)" >&2
        exit 1
    fi
    exit 0
}
for s in "${scenes[@]}"; do
    [ -f "$SHARED/scenes/$s" ] || skip "$SHARED/scenes/$s is missing"
done
[ -x "$RACE" ] || { echo "frusta-race-doc: $RACE missing (make $RACE)" >&2; exit 1; }
mkdir -p "$OUT"
: >"$OUT/race.kv"
for s in "${scenes[@]}"; do
    for p in q16 f32; do
        echo "frusta-race-doc: $s $p (${RES}x${RES}, median of $RUNS)" >&2
        if ! "$RACE" --mesh "$SHARED/scenes/$s" --res "$RES" --runs "$RUNS" --num "$p" --kv \
            >"$OUT/$s.$p.txt" 2>&1; then
            cat "$OUT/$s.$p.txt" >&2
            echo "frusta-race-doc: frusta-race failed on $s ($p); no table written" >&2
            exit 1
        fi
        grep '^frusta-race: ' "$OUT/$s.$p.txt" >>"$OUT/race.kv"
    done
done
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
if ! git diff --quiet HEAD -- firmware host tests/bench Makefile 2>/dev/null; then
    commit="$commit + uncommitted changes"
fi
cpu=$(awk -F': ' '/^model name/ {print $2; exit}' /proc/cpuinfo 2>/dev/null || echo unknown)
backend=$("$B/host/lt-vectors" --backend 2>/dev/null || echo unknown)
python3 - "$OUT/race.kv" "$RES" "$RUNS" "$commit" "$(date '+%Y-%m-%d %H:%M %Z')" "$cpu" "$backend" \
    >"$OUT/race.md" <<'PY'
import sys
kvf, res, runs, commit, when, cpu, backend = sys.argv[1:8]
rows = []
for line in open(kvf):
    t = line.split()[1:]
    rows.append(dict(zip(t[0::2], t[1::2])))
names = {"sibenik.obj": "Sibenik", "sponza.obj": "Sponza", "conference.obj.gz": "Conference",
         "bunny.obj": "bunny + ground", "dragon_res3.obj": "dragon + ground"}
def mr(x):
    x = float(x)
    return "%.1f" % x if x >= 10 else "%.2f" % x
print("Measured on **%s** (lanetrace's lane backend: %s), one thread, %sx%s, median of %s after a "
      "warm-up pass, %s, git %s (`make frusta-race-doc`). Embree: the fastest of `rtcOccluded1/4/8/16` "
      "(a lit pixel's 16 samples as 16, 4, 2 or 1 calls) with the incoherent and the coherent context "
      "flag; lanetrace: `lanetrace shadows`' defaults (frusta leaf size and culling set as printed)."
      % (cpu, backend, res, res, runs, when, commit))
print()
print("| scene | path | shadow rays | Embree best (Mrays/s) | rtcOccluded1 / 4 / 8 / 16 | S-Packet (x Embree best) | "
      "S-Frusta (x Embree best) | S-Frusta / S-Packet | leaf, culling | agreement with Embree |")
print("|---|---|---|---|---|---|---|---|---|---|")
for r in rows:
    base = r["scene"].split("/")[-1]
    e = float(r["embree"])
    p, f = float(r["packet"]), float(r["frusta"])
    print("| %s | %s | %.2fM | %s (%s) | %s / %s / %s / %s | %s (%.2fx) | %s (%.2fx) | %.2fx | %s, %s | %.4f%% |" % (
        names.get(base, base), "s15.16" if r["path"] == "q16" else "float32",
        int(r["rays"]) / 1e6, mr(e), r["embree_best"].replace("_", ", "),
        mr(r["e1"]), mr(r["e4"]), mr(r["e8"]), mr(r["e16"]), mr(p), p / e, mr(f), f / e, f / p,
        r["leaf"], r["cull"], float(r["agree"])))
fr = [float(r["frusta"]) / float(r["packet"]) for r in rows]
fe = [float(r["frusta"]) / float(r["embree"]) for r in rows]
print()
print("On these %d runs S-Frusta runs at %.2f-%.2fx of S-Packet and at %.2f-%.2fx of Embree's best "
      "mode, natively, one thread." % (len(rows), min(fr), max(fr), min(fe), max(fe)))
PY
tools/doc_insert.sh frusta-race "$OUT/race.md" "$DOC"
