# wt.sh - the shared-data rule of test_wt (watertight triangle test, docs/watertight.md): without
# ../shared the bunny crack test prints a SKIP line and the binary passes; under CI=true it fails.
# Sourced by tests/run_tests.sh ($B, $tmp, check/ok/ko).
env -u CI LT_SHARED=/nonexistent-shared "$B/host/test_wt" >"$tmp/wt_noshared.txt" 2>&1
rc=$?
check "test_wt without shared data: passes, prints SKIP (rc $rc)" \
    bash -c "[ $rc -eq 0 ] && grep -q '^SKIP ../shared/scenes/bunny.obj' '$tmp/wt_noshared.txt'"
LT_SHARED=/nonexistent-shared CI=true "$B/host/test_wt" >"$tmp/wt_noshared_ci.txt" 2>&1
rc=$?
check "test_wt without shared data under CI=true: fails (rc $rc)" \
    bash -c "[ $rc -ne 0 ] && grep -q 'missing under CI=true' '$tmp/wt_noshared_ci.txt'"
