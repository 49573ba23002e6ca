#!/usr/bin/env bash
# campaign.sh - run each libFuzzer target for FUZZ_TIME seconds (or, with FUZZ_RUNS=N, for N
# executions, FUZZ_TIME then being a cap: 0 = none), one after the other, and print one
# table (target, seconds, executions, exec/s, corpus, new inputs, peak RSS, crashes), also written
# to $B/fuzz/campaign.md for docs/reliability.md. Called by `make fuzz-campaign SECONDS=N`, which
# builds $B/fuzz/fuzz-<target> first. Exit 1 when any target crashed, hung, ran out of memory or
# did not report its statistics. Logs: $B/fuzz/<target>.log; artifacts: $B/fuzz/artifacts/<target>/.
set -uo pipefail
B=${B:-build}
T=${FUZZ_TIME:-60}
R=${FUZZ_RUNS:-}
FLAGS=${FUZZ_RUN_FLAGS:--timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -close_fd_mask=3}
[ $# -gt 0 ] || { echo "usage: $0 TARGET..." >&2; exit 2; }
case $T in '' | *[!0-9]*) echo "fuzz-campaign: SECONDS=$T is not a whole number" >&2; exit 2 ;; esac
case $R in *[!0-9]*) echo "fuzz-campaign: RUNS=$R is not a whole number" >&2; exit 2 ;; esac
runs=()
per="${T} s per target"
if [ -n "$R" ]; then
    runs=(-runs="$R")
    per="$R executions per target$([ "$T" -gt 0 ] && echo " (at most $T s)")"
fi
out=$B/fuzz/campaign.md
started=$(date -u +%Y-%m-%dT%H:%MZ)
load0=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo '?')
commit=$(git rev-parse --short HEAD 2>/dev/null || echo '?')
[ -n "$(git status --porcelain --untracked-files=no 2>/dev/null)" ] && commit="$commit + local changes"
bad=0
rows=()
final_stat() { sed -n "s/^stat::$1: *\([0-9]*\).*/\1/p" "$2" | tail -n 1; }
for t in "$@"; do
    bin=$B/fuzz/fuzz-$t
    log=$B/fuzz/$t.log
    art=$B/fuzz/artifacts/$t
    maxlen_var=FUZZ_MAXLEN_$t
    mkdir -p "$B/fuzz/corpus-$t" "$art"
    before=$(find "$art" -maxdepth 1 -type f | wc -l)
    dict=()
    [ -f "tests/fuzz/$t.dict" ] && dict=(-dict="tests/fuzz/$t.dict")
    echo "fuzz-campaign: $t, $per" >&2
    # shellcheck disable=SC2086
    t0=$(date +%s)
    "$bin" $FLAGS -max_total_time="$T" "${runs[@]}" -max_len="${!maxlen_var:-4096}" \
        -artifact_prefix="$art/" "${dict[@]}" "$B/fuzz/corpus-$t" "tests/fuzz/corpus/$t" >"$log" 2>&1
    rc=$?
    secs=$(($(date +%s) - t0))
    after=$(find "$art" -maxdepth 1 -type f | wc -l)
    execs=$(final_stat number_of_executed_units "$log")
    eps=$(final_stat average_exec_per_sec "$log")
    news=$(final_stat new_units_added "$log")
    rss=$(final_stat peak_rss_mb "$log")
    corpus=$(( $(find "$B/fuzz/corpus-$t" "tests/fuzz/corpus/$t" -type f | wc -l) ))
    crashes=$((after - before))
    if [ $rc -ne 0 ] && [ $crashes -eq 0 ]; then crashes=1; fi
    note=""
    if [ $crashes -ne 0 ]; then
        note=" (rc $rc; $(grep -m1 -E 'ERROR: |SUMMARY: |deadly signal|timeout|out-of-memory' "$log" | cut -c1-80))"
        bad=1
    elif [ -z "$execs" ]; then
        note=" (no final statistics: see $log)"
        bad=1
    fi
    rows+=("| $t | $secs | ${execs:-?} | ${eps:-?} | $corpus | ${news:-?} | ${rss:-?} | $crashes$note |")
done
{
    echo "Fuzz campaign: started $started, commit $commit, $(clang --version 2>/dev/null | head -n 1), ASan + UBSan, $per, one process each on $(nproc) cores (load average $load0 at the start, $(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo '?') at the end: other work on the machine lowers exec/s)"
    echo
    echo "| target | seconds | executions | exec/s | corpus | new inputs | peak RSS MB | crashes |"
    echo "|---|---:|---:|---:|---:|---:|---:|---:|"
    printf '%s\n' "${rows[@]}"
} >"$out.tmp" && mv -f "$out.tmp" "$out"
cat "$out"
echo
if [ $bad -ne 0 ]; then
    echo "fuzz-campaign: FAILED (crash, hang, out-of-memory or no statistics; logs in $B/fuzz/, inputs in $B/fuzz/artifacts/)"
    exit 1
fi
echo "fuzz-campaign: no crash in $# targets (table in $out)"
