#!/usr/bin/env bash
# profile.sh - where lanetrace's native time goes (make race-doc; docs/results.md "What holds it
# back"): perf samples of one thread tracing the race's view of a mesh: the 16-ray primary packets
# (`run`) and a whole `render` (primary and shadow packets, shading, image files), both numeric
# paths; prints lanetrace's top functions in each with their share of all samples.
# Usage: profile.sh [--md FILE] [MESH] (default: the shared bunny, else the bundled teapot).
# Needs perf (linux-perf) and a kernel that lets it sample (perf_event_paranoid <= 2); says so
# and exits 0 otherwise (a profile is documentation, not a test).
set -euo pipefail
B=${B:-build}
md=""
if [ "${1:-}" = "--md" ]; then
    md=$2
    shift 2
fi
mesh=${1:-../shared/scenes/bunny.obj}
[ -f "$mesh" ] || mesh=scenes/teapot.obj
if ! command -v perf >/dev/null 2>&1 || ! perf stat -e task-clock true >/dev/null 2>&1; then
    echo "profile: perf is not available or not allowed here: no profile"
    exit 0
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
N="$B/host/lanetrace-native"
top() { # perf data -> "share symbol" lines: the top 6 of lanetrace's own code
    { perf report -i "$1" --no-children --stdio --sort sym --dsos lanetrace-native 2>/dev/null |
        awk '/^ +[0-9.]+%/ { s = $1; $1 = ""; $2 = ""; sub(/^ +/, ""); printf "%s %s\n", s, $0 }' |
        head -6; } || true
}
rows=()
for p in f32 q16; do
    perf record -q -o "$tmp/p.data" "$N" run --mesh "$mesh" --res 1024 --num $p --repeat 4 --no-ref -q \
        --threads 1 >/dev/null 2>&1
    t=$(top "$tmp/p.data" | paste -sd ';' | sed 's/;/; /g')
    echo "profile $p 16-ray packets (run): $t"
    rows+=("| $p | 16-ray primary packets | $t |")
    perf record -q -o "$tmp/s.data" "$N" render --mesh "$mesh" --res 1024 --num $p --threads 1 \
        --out "$tmp/r" -q >/dev/null 2>&1
    t=$(top "$tmp/s.data" | paste -sd ';' | sed 's/;/; /g')
    echo "profile $p render (packets, shadow packets, images): $t"
    rows+=("| $p | render: primary and shadow packets, shading, image files | $t |")
done
if [ -n "$md" ]; then
    {
        echo "Profiled by \`make race-doc\` (tests/bench/profile.sh: perf, one thread) on"
        echo "$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1), $(date -u +%Y-%m-%d), lanetrace $(git rev-parse --short HEAD 2>/dev/null || echo '?'): $(basename "$mesh") at 1024x1024; the six"
        echo "functions of lanetrace's own code with the most samples (self time, share of all samples"
        echo "of the process, libraries such as zlib and libpng included in the total)."
        echo
        echo "| path | work | top functions |"
        echo "|---|---|---|"
        printf '%s\n' "${rows[@]}"
    } >"$md"
    echo "profile: wrote $md"
fi
