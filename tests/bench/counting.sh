#!/usr/bin/env bash
# counting.sh - the cost of counting (make bench section 1; #14 target: counted <= 3x native): the
# same kernels on the same frames, one thread each, native (LT_COST_OFF, build/host) vs counted
# (LT_COST_SIM on lrb16 with its caches, build/sim), median of 3 runs. With --md FILE it also
# writes the table docs/results.md holds (make speed-doc).
# Env: BENCH_SCENE (default the bundled teapot), BENCH_RES (128), BENCH_REPEAT (10 frames).
set -euo pipefail
B=${B:-build}
SCENE=${BENCH_SCENE:-scenes/teapot.obj}
RES=${BENCH_RES:-128}
REP=${BENCH_REPEAT:-10}
md=""
[ "${1:-}" = "--md" ] && md=$2
median() { sort -g | sed -n 2p; }
rows=()
echo "cost of counting: $SCENE ${RES}x${RES}, $REP frames, one thread, median of 3 runs"
for p in q16 f32; do
    nat=$(for i in 1 2 3; do "$B/host/lanetrace-native" run --mesh "$SCENE" --res "$RES" \
        --repeat "$REP" --num $p --no-ref -q --threads 1 | awk '/^time/{print $3}'; done | median)
    cnt=$(for i in 1 2 3; do "$B/sim/lanetrace" run --mesh "$SCENE" --res "$RES" \
        --repeat "$REP" --num $p --no-ref -q | awk '/^time/{print $3}'; done | median)
    line=$(awk -v p=$p -v n="$nat" -v c="$cnt" 'BEGIN{r = c / n; printf "%s|%.2f|%.2f|%.2f|%s", p, n, c, r, (r <= 3) ? "met" : "NOT met"}')
    IFS='|' read -r pp n c r v <<<"$line"
    printf '%-4s native %8.2f ms  counted %8.2f ms  ratio %sx (target <= 3x: %s)\n' "$pp" "$n" "$c" "$r" "$v"
    name=$([ "$p" = q16 ] && echo s15.16 || echo float32)
    rows+=("| $name | $n ms | $c ms | ${r}x | $v |")
done
if [ -n "$md" ]; then
    {
        echo "Measured by \`make speed-doc\` (tests/bench/counting.sh) on $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1),"
        echo "$(date -u +%Y-%m-%d), lanetrace $(git rev-parse --short HEAD 2>/dev/null || echo '?'): $(basename "$SCENE") ${RES}x${RES}, $REP frames, one thread each,"
        echo "median of 3 runs; counted = the simulator build on lrb16 with its caches."
        echo
        echo "| path | native | counted | ratio | target <= 3x |"
        echo "|---|---|---|---|---|"
        printf '%s\n' "${rows[@]}"
    } >"$md"
    echo "counting: wrote $md"
fi
