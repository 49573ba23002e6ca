# ssbench.sh - smoke test of the screen-space baselines benchmark (tests/bench/ssbench.c,
# docs/ss-baselines.md): the analytic scenes at 1024 rays per set in the sim and host builds; the
# visit counts and the agreement with the reference (columns nodes .. wrong%) must be identical
# (counting never changes a result), bad options exit 2. Sourced by tests/run_tests.sh ($B, $tmp,
# check/ok/ko).
"$B/sim/ssbench" --quick --no-exr >"$tmp/ssb_sim.txt" 2>&1
rc=$?
check "ssbench (sim) --quick --no-exr exits 0 (rc $rc)" test "$rc" -eq 0
"$B/host/ssbench" --quick --no-exr >"$tmp/ssb_host.txt" 2>&1
rc=$?
check "ssbench (host) --quick --no-exr exits 0 (rc $rc)" test "$rc" -eq 0
for v in sim host; do
    awk '$3 ~ /^(qt|dda|hiz)$/ && NF == 17 {print $1, $2, $3, $4, $8, $9, $10, $12, $13, $14,
        $15, $16, $17}' "$tmp/ssb_$v.txt" >"$tmp/ssb_$v.cols"
done
n=$(wc -l <"$tmp/ssb_sim.cols")
check "ssbench: $n rows (2 scenes x 2 ray sets x 7 tracers), host = sim in visits and errors" \
    bash -c "[ $n -eq 28 ] && cmp -s '$tmp/ssb_sim.cols' '$tmp/ssb_host.cols'"
"$B/host/ssbench" --rays 5 >/dev/null 2>&1
rc=$?
check "ssbench --rays 5: usage error, exit 2 (rc $rc)" test "$rc" -eq 2
