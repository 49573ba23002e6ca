#!/usr/bin/env bash
# race_doc.sh - docs/results.md's race against Embree 3 regenerated on this machine (make race-doc):
# build/host/embree-race --kv on the bundled teapot and the shared scenes (RES 1024, RUNS 3), its
# "race: ..." lines turned into two tables with the machine they ran on in the caption (CPU, the
# ISA it supports and the one lanetrace was compiled for, Embree's version and native packet
# widths, one thread, date, git commit): Embree's modes, then lanetrace against Embree's best mode
# and each mode. Written to $B/race/race.md (each scene's full output beside it) and put between
# the <!-- race:begin --> / <!-- race:end --> markers of docs/results.md (tools/doc_insert.sh).
# Without ../shared (SHARED=...) it says so and leaves the page alone: exit 1 under CI=true, else 0.
# An Embree mode that disagrees with its single-ray mode (embree-race exits 1) stops it: no table.
# Usage: tests/bench/race_doc.sh   (from the repository root; B=build RES=1024 RUNS=3 DOC=docs/results.md;
#        RACE_ARGS: more embree-race options, e.g. "--embree-config isa=avx2", named in the caption;
#        VARIANT=avx2: build/avx2/embree-race into the race-avx2 markers, no profile: make
#        race-doc-avx2)
set -euo pipefail
B=${B:-build}
SHARED=${SHARED:-../shared}
RES=${RES:-1024}
RUNS=${RUNS:-3}
DOC=${DOC:-docs/results.md}
RACE_ARGS=${RACE_ARGS:-}
VARIANT=${VARIANT:-host}
RACE="$B/$VARIANT/embree-race"
OUT="$B/race"
MARK=race
if [ "$VARIANT" != host ]; then
    OUT="$B/race-$VARIANT"
    MARK="race-$VARIANT"
fi
scenes=(scenes/teapot.obj "$SHARED/scenes/bunny.obj" "$SHARED/scenes/dragon_res3.obj"
        "$SHARED/scenes/sponza.obj" "$SHARED/scenes/sibenik.obj" "$SHARED/scenes/conference.obj.gz"
        "$SHARED/scenes/CornellBox-Original.obj")

skip() {
    echo "race-doc: $1; $DOC is left as it was" >&2
    if [ "${CI:-}" = true ]; then
        echo "race-doc: CI=true: failing (clone the shared scenes beside this repository as $SHARED)" >&2
        exit 1
    fi
    echo "race-doc: skipped (clone the shared scenes beside this repository as $SHARED to run it)" >&2
    exit 0
}
[ -d "$SHARED/scenes" ] || skip "$SHARED/scenes is missing (the shared scenes)"
for s in "${scenes[@]}"; do
    [ -f "$s" ] || skip "$s is missing"
done
[ -x "$RACE" ] || { echo "race-doc: $RACE missing (make $RACE)" >&2; exit 1; }

mkdir -p "$OUT"
: >"$OUT/race.kv"
for s in "${scenes[@]}"; do
    name=$(basename "$s")
    echo "race-doc: $name (${RES}x${RES}, median of $RUNS)" >&2
    # shellcheck disable=SC2086 # RACE_ARGS is a list of options
    if ! "$RACE" --mesh "$s" --res "$RES" --runs "$RUNS" --structure bvh --kv $RACE_ARGS \
        >"$OUT/$name.txt" 2>&1; then
        cat "$OUT/$name.txt" >&2
        echo "race-doc: embree-race failed on $s (above); no table written" >&2
        exit 1
    fi
    grep '^race: ' "$OUT/$name.txt" >>"$OUT/race.kv"
done

commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
# the sources the race binary is built from: uncommitted changes there are named in the caption
if ! git diff --quiet HEAD -- firmware host tests/bench Makefile tests/bench.mk 2>/dev/null; then
    commit="$commit + uncommitted changes"
fi
when=$(date '+%Y-%m-%d %H:%M %Z')

target=race-doc
[ "$VARIANT" = host ] || target="race-doc-$VARIANT"
awk -v res="$RES" -v runs="$RUNS" -v commit="$commit" -v when="$when" -v target="$target" '
function rest(n,   s, i) { s = $n; for (i = n + 1; i <= NF; i++) s = s " " $i; return s }
function kv(   i) { delete v; for (i = 3; i < NF; i += 2) v[$i] = $(i + 1) }
function mr(x) { return x >= 100 ? sprintf("%.0f", x) : x >= 10 ? sprintf("%.1f", x) : sprintf("%.2f", x) }
function rt(x) { return x < 0.0995 ? sprintf("%.3fx", x) : sprintf("%.2fx", x) }
function yn(x) { return x ? "yes" : "no" }
function pretty(f) {
    if (f == "teapot.obj") return "teapot"
    if (f == "bunny.obj") return "bunny"
    if (f == "dragon_res3.obj") return "dragon"
    if (f == "sponza.obj") return "Sponza"
    if (f == "sibenik.obj") return "Sibenik"
    if (f == "conference.obj.gz") return "Conference"
    if (f == "CornellBox-Original.obj") return "Cornell box"
    return f
}
function commas(n,   s) { s = n ""; while (s ~ /[0-9][0-9][0-9][0-9]/) sub(/[0-9][0-9][0-9]($|,)/, ",&", s); return s }
function range(lo, hi) { return lo == hi ? rt(lo) : sprintf("%s-%s", substr(rt(lo), 1, length(rt(lo)) - 1), rt(hi)) }
function upd(key, x) {
    if (!(key in lo) || x < lo[key]) lo[key] = x
    if (!(key in hi) || x > hi[key]) hi[key] = x
}
$2 == "cpu" && cpu == "" { cpu = rest(3) }
$2 == "cpu-isa" && widest == "" { widest = $3; cisa = rest(5) }
$2 == "build-isa" && bisa == "" { bisa = rest(3) }
$2 == "embree" && ever == "" { kv(); ever = v["version"]; nat[4] = v["ray4"]; nat[8] = v["ray8"]; nat[16] = v["ray16"]
                               ecfg = v["config"] == "threads=1" ? "" : " (device " v["config"] ")" }
$2 == "scene" { kv(); ns++; sc = ns; sname[sc] = pretty(v["name"]); tris[sc] = v["tris"]
                build[sc] = v["build_ms"]; rebuild[sc] = v["rebuild_ms"] }
$2 == "mode" { kv(); m = v["name"]; rate[sc, m] = v["mrays"]; flag[sc, m] = substr(v["flag"], 1, 1)
               ok[sc, m] = v["ok"]
               if (m ~ /Intersect/ && (!((sc, "pmin") in agree) || v["ties"] < agree[sc, "pmin"])) agree[sc, "pmin"] = v["ties"]
               if (m ~ /Occluded/ && (!((sc, "smin") in agree) || v["ties"] < agree[sc, "smin"])) agree[sc, "smin"] = v["ties"] }
$2 == "best" { kv(); bestp[sc] = v["packet"]; bests[sc] = v["shadow"]; nbp[v["packet"]]++; nbs[v["shadow"]]++ }
$2 == "lanetrace" { kv(); p = v["path"]; ls[sc, p] = v["single"]; lp[sc, p] = v["packet"]
                    lsh[sc, p] = v["shadow"]; lsh1[sc, p] = v["shadow1"]; same[sc, p] = v["same"]
                    lpw[sc, p] = v["packet8"]; lshw[sc, p] = v["shadow8"]; upd("comp", v["packetcomp"] / v["packet"]) }
END {
    split("rtcIntersect1 rtcIntersect4 rtcIntersect8 rtcIntersect16 rtcOccluded1 rtcOccluded4 rtcOccluded8 rtcOccluded16", M, " ")
    split("single 2x2 4x2 4x4 single 2x2 4x2 4x4", T, " ")
    split("1 4 8 16 1 4 8 16", W, " ")
    printf "Measured on **%s**, ISA **%s** (the CPU supports %s; lanetrace built for %s), ", cpu, widest, cisa, bisa
    printf "**Embree %s%s native ray4/8/16: %s/%s/%s**, one thread, %dx%d rays, median of %d after one warm-up pass per mode, %s, git %s (`make %s`).\n\n", \
        ever, ecfg, yn(nat[4]), yn(nat[8]), yn(nat[16]), res, res, runs, when, commit, target
    printf "Embree 3, Mrays/s per mode (every mode timed with the incoherent and the coherent context flag, the faster kept: i / c; best packet and best shadow mode in bold; agreement: the lowest over the modes of the same triangle as rtcIntersect1 or a verified same-distance tie, and of the same occlusion as rtcOccluded1):\n\n"
    printf "| scene (tris) | build ms first / rebuilt |"
    for (k = 1; k <= 8; k++)
        printf " %s %s%s |", M[k], T[k], (W[k] > 1 ? (nat[W[k]] ? ", native" : ", **emulated**") : "")
    printf " agreement primary / shadow |\n|---|---|"
    for (k = 1; k <= 9; k++) printf "---|"
    printf "\n"
    for (s = 1; s <= ns; s++) {
        printf "| %s (%s) | %.2f / %.2f |", sname[s], commas(tris[s]), build[s], rebuild[s]
        for (k = 1; k <= 8; k++) {
            c = mr(rate[s, M[k]]) " " flag[s, M[k]]
            if (M[k] == bestp[s] || M[k] == bests[s]) c = "**" c "**"
            if (!ok[s, M[k]]) c = c " (DISAGREES)"
            printf " %s |", c
        }
        printf " %.3f%% / %.3f%% |\n", agree[s, "pmin"], agree[s, "smin"]
    }
    printf "\nlanetrace (its own code paths, one thread) against Embree in the same run: Mrays/s and lanetrace / Embree; single rays against rtcIntersect1, 16-ray packets against the best of rtcIntersect4/8/16, shadow packets and single shadow rays against the best of rtcOccluded1/4/8/16, then against each mode (both tracers take the camera'"'"'s directions computed before the timing, lanetrace'"'"'s with `lt_accel_set_view`; single rays and single shadow rays walk the 8-wide BVH, lt_bvh8.h; packets the binary one, the tree the machine models price; the wide-tree columns are the same packets through the 8-wide tree, `lanetrace run --rays wide`, against Embree'"'"'s best mode and against the binary walk):\n\n"
    printf "| scene | path | single rays (x rtcIntersect1) | 16-ray packets (x Embree best) | packets x rtcIntersect4 / 8 / 16 | wide-tree packets (x Embree best; x binary) | shadow packets (x Embree best) | shadows x rtcOccluded1 / 4 / 8 / 16 | wide-tree shadow packets (x Embree best; x binary) | single shadow rays (x Embree best) | same triangle as Embree |\n"
    printf "|---|---|---|---|---|---|---|---|---|---|---|\n"
    for (s = 1; s <= ns; s++)
        for (q = 1; q <= 2; q++) {
            p = q == 1 ? "q16" : "f32"
            x1 = ls[s, p] / rate[s, "rtcIntersect1"]; xp = lp[s, p] / rate[s, bestp[s]]; xs = lsh[s, p] / rate[s, bests[s]]
            xs1 = lsh1[s, p] / rate[s, bests[s]]
            xpw = lpw[s, p] / rate[s, bestp[s]]; xsw = lshw[s, p] / rate[s, bests[s]]
            bpw = lpw[s, p] / lp[s, p]; bsw = lshw[s, p] / lsh[s, p]
            upd(p "1", x1); upd(p "p", xp); upd(p "s", xs); upd(p "s1", xs1)
            upd(p "pw", xpw); upd(p "sw", xsw); upd(p "bpw", bpw); upd(p "bsw", bsw)
            printf "| %s | %s | %s (%s) | %s (%s %s) | %s / %s / %s | %s (%s; %s) | %s (%s %s) | %s / %s / %s / %s | %s (%s; %s) | %s (%s) | %.3f%% |\n", \
                q == 1 ? sname[s] : "", q == 1 ? "s15.16" : "float32", mr(ls[s, p]), rt(x1), \
                mr(lp[s, p]), rt(xp), bestp[s], \
                rt(lp[s, p] / rate[s, "rtcIntersect4"]), rt(lp[s, p] / rate[s, "rtcIntersect8"]), rt(lp[s, p] / rate[s, "rtcIntersect16"]), \
                mr(lpw[s, p]), rt(xpw), rt(bpw), \
                mr(lsh[s, p]), rt(xs), bests[s], \
                rt(lsh[s, p] / rate[s, "rtcOccluded1"]), rt(lsh[s, p] / rate[s, "rtcOccluded4"]), rt(lsh[s, p] / rate[s, "rtcOccluded8"]), rt(lsh[s, p] / rate[s, "rtcOccluded16"]), \
                mr(lshw[s, p]), rt(xsw), rt(bsw), \
                mr(lsh1[s, p]), rt(xs1), same[s, p]
        }
    bp = ""; for (m in nbp) bp = bp (bp == "" ? "" : ", ") m " on " nbp[m]
    bs = ""; for (m in nbs) bs = bs (bs == "" ? "" : ", ") m " on " nbs[m]
    printf "\nOn these %d scenes lanetrace'"'"'s float32 16-ray packets run at %s of Embree'"'"'s best packet mode and its s15.16 packets at %s; its float32 shadow packets at %s of Embree'"'"'s best shadow mode, s15.16 at %s; its single shadow rays through the wide BVH at %s (float32) and %s (s15.16); single rays at %s (float32) and %s (s15.16) of rtcIntersect1. Through the 8-wide tree the 16-ray packets run at %s (float32) and %s (s15.16) of Embree'"'"'s best packet mode (%s and %s of the binary walk), the shadow packets at %s and %s of its best shadow mode (%s and %s of the binary walk). Embree'"'"'s best packet mode: %s of the scenes; best shadow mode: %s. With the directions computed in the timed loop (`lanetrace run`'"'"'s way) lanetrace'"'"'s 16-ray packets run at %s of the speed above.\n", \
        ns, range(lo["f32p"], hi["f32p"]), range(lo["q16p"], hi["q16p"]), range(lo["f32s"], hi["f32s"]), range(lo["q16s"], hi["q16s"]), \
        range(lo["f32s1"], hi["f32s1"]), range(lo["q16s1"], hi["q16s1"]), \
        range(lo["f321"], hi["f321"]), range(lo["q161"], hi["q161"]), \
        range(lo["f32pw"], hi["f32pw"]), range(lo["q16pw"], hi["q16pw"]), range(lo["f32bpw"], hi["f32bpw"]), range(lo["q16bpw"], hi["q16bpw"]), \
        range(lo["f32sw"], hi["f32sw"]), range(lo["q16sw"], hi["q16sw"]), range(lo["f32bsw"], hi["f32bsw"]), range(lo["q16bsw"], hi["q16bsw"]), bp, bs, range(lo["comp"], hi["comp"])
}' "$OUT/race.kv" >"$OUT/race.md"

echo "race-doc: $OUT/race.md" >&2
tools/doc_insert.sh "$MARK" "$OUT/race.md" "$DOC"
[ "$VARIANT" = host ] || exit 0
# where lanetrace's time goes (perf; skipped with a line where perf cannot sample)
if B=$B tests/bench/profile.sh --md "$OUT/profile.md" && [ -s "$OUT/profile.md" ]; then
    tools/doc_insert.sh race-profile "$OUT/profile.md" "$DOC"
fi
