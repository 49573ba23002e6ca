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

# ---- the s15.16 grid test from the command line (--isect wt32, docs/watertight.md) ----
WN="$HOSTBIN/lanetrace-native"
WS="$SIMBIN/lanetrace"
"$WN" run --mesh scenes/teapot.obj --res 48 --num both --isect wt32 --no-ref >"$tmp/w32.nat" 2>&1
rc=$?
"$WS" run --mesh scenes/teapot.obj --res 48 --num both --isect wt32 --no-ref >"$tmp/w32.sim" 2>&1
rc2=$?
"$WN" run --mesh scenes/teapot.obj --res 48 --num both --no-ref >"$tmp/wt.nat" 2>&1
hq=$(sed -n 's/^result    q16  hash \(0x[0-9a-f]*\)/\1/p' "$tmp/w32.nat")
hs=$(sed -n 's/^result    q16  hash \(0x[0-9a-f]*\)/\1/p' "$tmp/w32.sim")
hw=$(sed -n 's/^result    q16  hash \(0x[0-9a-f]*\)/\1/p' "$tmp/wt.nat")
hf=$(sed -n 's/^result    f32  hash \(0x[0-9a-f]*\)/\1/p' "$tmp/w32.nat")
hfw=$(sed -n 's/^result    f32  hash \(0x[0-9a-f]*\)/\1/p' "$tmp/wt.nat")
check "run --isect wt32 --num both: the grid named ($(grep '^isect' "$tmp/w32.nat" | cut -c11-70)...), s15.16 hash native $hq = sim $hs, not the exact test's $hw; the float32 pass takes wt ($hf = $hfw) (rc $rc, $rc2)" \
    bash -c "[ $rc -eq 0 ] && [ $rc2 -eq 0 ] && grep -q 'the float32 pass takes wt' '$tmp/w32.nat' && [ -n '$hq' ] && [ '$hq' = '$hs' ] && [ '$hq' != '$hw' ] && [ -n '$hf' ] && [ '$hf' = '$hfw' ]"
"$WN" run --mesh scenes/teapot.obj --res 16 --num f32 --isect wt32 --no-ref >/dev/null 2>"$tmp/w32.err"
rc=$?
check "run --num f32 --isect wt32: refused, exit 2, names the path ($(head -c 120 "$tmp/w32.err"))" \
    bash -c "[ $rc -eq 2 ] && grep -q 'the f32 path takes wt or mt' '$tmp/w32.err'"
"$WN" render --mesh scenes/teapot.obj --res 16 --num f32 --isect wt32 --out "$tmp/w32r" >/dev/null 2>"$tmp/w32.err"
rc=$?
check "render --num f32 --isect wt32: refused, exit 2 (rc $rc)" \
    bash -c "[ $rc -eq 2 ] && grep -q 'takes wt or mt' '$tmp/w32.err' && [ ! -e '$tmp/w32r.exr' ]"
"$WN" render --mesh scenes/teapot.obj --res 16 --num q16 --isect wt32 --out "$tmp/w32r" >/dev/null 2>&1
rc=$?
check "render --num q16 --isect wt32: exit 0, the EXR written (rc $rc)" \
    bash -c "[ $rc -eq 0 ] && [ -s '$tmp/w32r.exr' ]"
"$WN" shadows --mesh scenes/teapot.obj --res 16 --isect wt32 --no-ref >/dev/null 2>"$tmp/w32.err"
rc=$?
check "shadows --isect wt32: a usage error, exit 2, the frusta take wt or mt (rc $rc)" \
    bash -c "[ $rc -eq 2 ] && grep -q 'multi-frusta kernels take wt or mt' '$tmp/w32.err'"
printf '{"mesh": "%s/scenes/teapot.obj", "resolution": 16, "numeric": "q16", "isect": "wt32"}\n' "$PWD" >"$tmp/w32.json"
"$WN" run "$tmp/w32.json" --no-ref >"$tmp/w32f.txt" 2>&1
rc=$?
check "scene file \"isect\": \"wt32\": run takes it (rc $rc)" \
    bash -c "[ $rc -eq 0 ] && grep -q '^isect     wt32' '$tmp/w32f.txt'"
printf '{"mesh": "%s/scenes/teapot.obj", "isect": "wt64"}\n' "$PWD" >"$tmp/w32b.json"
"$WN" run "$tmp/w32b.json" --no-ref >/dev/null 2>"$tmp/w32.err"
rc=$?
check "scene file \"isect\": \"wt64\": refused, names the choices ($(head -c 150 "$tmp/w32.err")) (rc $rc)" \
    bash -c "[ $rc -ne 0 ] && grep -q 'wt32' '$tmp/w32.err'"
