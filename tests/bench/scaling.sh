#!/usr/bin/env bash
# scaling.sh - all-core scaling of the native build (make bench; #14 target: >= 1.8x on 2 cores):
# the same work on --threads 1 and on every core (--threads 0), in one run: primary 16-ray packets
# (`run`, both numeric paths), the soft-shadow stages and the 256-sample reference (`shadows`), and
# the quadtree reprojection's trace (`reproject`). Prints the cores, each rate and the ratio; with
# --md FILE it also writes the table docs/results.md holds (make scaling-doc).
# Scene: the shared dragon (1024x1024) when ../shared is there, else the bundled teapot.
set -euo pipefail
B=${B:-build}
N="$B/host/lanetrace-native"
md=""
[ "${1:-}" = "--md" ] && md=$2
mesh=../shared/scenes/dragon_res3.obj
res=1024
if [ ! -f "$mesh" ]; then
    [ "${CI:-}" = "true" ] && { echo "scaling: $mesh missing under CI" >&2; exit 1; }
    echo "scaling: $mesh not found (no ../shared): the bundled teapot instead"
    mesh=scenes/teapot.obj
fi
cores=$(getconf _NPROCESSORS_ONLN)
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
median() { sort -g | sed -n 2p; }
rows=()
row() { # name, one-thread seconds, all-core seconds
    local r
    r=$(awk -v a="$2" -v b="$3" 'BEGIN{printf "%.2f", a / b}')
    printf '%-44s 1 thread %8.3f s   %u threads %8.3f s   scaling %sx (target >= 1.8x on 2 cores)\n' \
        "$1" "$2" "$cores" "$3" "$r"
    rows+=("| $1 | $(printf %.3f "$2") | $(printf %.3f "$3") | ${r}x |")
}

echo "scaling: $cpu, $cores online cores; $(basename "$mesh") ${res}x${res}, median of 3"
for p in f32 q16; do
    for t in 1 0; do
        for i in 1 2 3; do
            "$N" run --mesh "$mesh" --res $res --num $p --repeat 3 --no-ref -q --threads $t |
                awk '/^time/{print $3 / 1000}'
        done | median >"$tmp/run$p.$t"
    done
    row "run $p: primary 16-ray packets (3 frames)" "$(cat "$tmp/run$p.1")" "$(cat "$tmp/run$p.0")"
done

for t in 1 0; do
    for i in 1 2 3; do
        "$N" shadows --mesh "$mesh" --res $((res / 2)) --threads $t >"$tmp/sh.txt" 2>&1
        # stage seconds: P-Packet, P-Frusta, S-Packet, S-Frusta; the reference
        sed -n 's/^native    P-Packet \([0-9.]*\) s.*P-Frusta \([0-9.]*\) s.*S-Packet shadows \([0-9.]*\) s.*S-Frusta shadows \([0-9.]*\) s.*/\1 \2 \3 \4/p' \
            "$tmp/sh.txt" | awk '{print $1 + $2 + $3 + $4}' >>"$tmp/shs.$t"
        sed -n 's/^quality   vs 256 samples\/pixel (\([0-9.]*\) s).*/\1/p' "$tmp/sh.txt" >>"$tmp/shr.$t"
    done
done
row "shadows $((res / 2))x$((res / 2)): P/S packet + frusta stages" \
    "$(median <"$tmp/shs.1")" "$(median <"$tmp/shs.0")"
row "shadows $((res / 2))x$((res / 2)): 256-sample reference" \
    "$(median <"$tmp/shr.1")" "$(median <"$tmp/shr.0")"

# reprojection: a 2-layer depth render of the same view, into a moved camera
"$N" render --mesh "$mesh" --res $res --layers 2 --out "$tmp/d" -q
for t in 1 0; do
    for i in 1 2 3; do
        "$N" reproject --depth "$tmp/d.exr" --layers 2 --color --move-rel 0.08,0,0 --rot -3,0,0 \
            --threads $t --out "$tmp/rp.exr" 2>&1 | sed -n 's/^rays .*packets, \([0-9.]*\) s .*/\1/p'
    done | median >"$tmp/rp.$t"
done
row "reproject ${res}x${res}, 2 layers: quadtree trace" "$(cat "$tmp/rp.1")" "$(cat "$tmp/rp.0")"

if [ -n "$md" ]; then
    {
        echo "Measured by \`make speed-doc\` (tests/bench/scaling.sh) on $cpu, $cores online cores,"
        echo "$(date -u +%Y-%m-%d), lanetrace $(git rev-parse --short HEAD 2>/dev/null || echo '?');"
        echo "$(basename "$mesh") at ${res}x${res} (shadows at $((res / 2))x$((res / 2))), median of 3."
        echo
        echo "| work | 1 thread (s) | $cores threads (s) | scaling |"
        echo "|---|---|---|---|"
        printf '%s\n' "${rows[@]}"
    } >"$md"
    echo "scaling: wrote $md"
fi
