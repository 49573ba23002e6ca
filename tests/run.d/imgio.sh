# imgio.sh - the shared-data rule of the I/O unit tests (test_exr, test_mesh): without ../shared
# they pass with SKIP lines, under CI=true they fail. Sourced by tests/run_tests.sh ($B, $tmp,
# check/ok/ko).
for t in exr mesh; do
    env -u CI LT_SHARED=/nonexistent-shared "$B/host/test_$t" >"$tmp/imgio_$t.txt" 2>&1
    rc=$?
    check "test_$t without shared data: passes, prints SKIP (rc $rc)" \
        bash -c "[ $rc -eq 0 ] && grep -q '^SKIP ../shared/' '$tmp/imgio_$t.txt'"
    LT_SHARED=/nonexistent-shared CI=true "$B/host/test_$t" >"$tmp/imgio_ci_$t.txt" 2>&1
    rc=$?
    check "test_$t without shared data under CI=true: fails (rc $rc)" \
        bash -c "[ $rc -ne 0 ] && grep -q 'missing under CI=true' '$tmp/imgio_ci_$t.txt'"
done
