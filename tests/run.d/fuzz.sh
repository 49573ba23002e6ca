# fuzz.sh - replay every fuzz target's committed corpus (tests/fuzz/corpus/<target>/) through its
# ASan + UBSan replay driver $B/asan/fuzz-<target> (tests/fuzz.mk; no libFuzzer needed): each input
# once, in seconds. A crash, a sanitizer report or a broken invariant fails the line; each line
# says how many inputs it checked. Sourced by tests/run_tests.sh (check, $B, $tmp).
for d in tests/fuzz/corpus/*/; do
    t=$(basename "$d")
    "$B/asan/fuzz-$t" "$d" >"$tmp/fuzz_$t.txt" 2>&1
    rc=$?
    n=$(grep -a '^fuzz replay' "$tmp/fuzz_$t.txt" | tail -n 1 | sed 's/^fuzz replay [^:]*: //')
    check "fuzz-$t corpus replay (ASan+UBSan): ${n:-no summary: $(tail -n 3 "$tmp/fuzz_$t.txt" | tr '\n' ' ' | cut -c1-300)}" \
        test $rc -eq 0
done
