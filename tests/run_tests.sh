#!/usr/bin/env bash
# run_tests.sh - everything `make test` checks, after `make test-build`: unit tests (host, sim,
# asan), cross-target vectors (host = sim = asan = cm4 = cm55 = rv32 = golden), firmware under
# QEMU, the QEMU plugin, the tracer CLIs (host = sim results, errors), shared scenes when present.
# Ends with "N passed, N failed". Run from the repository root.
set -uo pipefail
B=${B:-build}
# where the shipped programs are: the release builds, or (LT_SIMBIN=build/asan LT_HOSTBIN=build/asan)
# their ASan + UBSan builds; the CLI scripts are also run against those below
SIMBIN=${LT_SIMBIN:-$B/sim}
HOSTBIN=${LT_HOSTBIN:-$B/host}
UNIT_TESTS=${UNIT_TESTS:-port fx v16 isect}
pass=0
fail=0
failed=()
ok() { pass=$((pass + 1)); echo "PASS $1"; }
ko() { fail=$((fail + 1)); failed+=("$1"); echo "FAIL $1"; }
check() { # name, command...
    local name=$1
    shift
    if "$@"; then ok "$name"; else ko "$name"; fi
}

echo "== unit tests (cmocka) per variant"
for v in host sim asan; do
    for t in $UNIT_TESTS; do
        check "unit/$v/test_$t" "$B/$v/test_$t"
    done
done
check "unit/sim/test_cache" "$B/sim/test_cache"

echo "== cross-target vectors"
golden=tests/golden/vectors.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for v in host sim asan; do
    "$B/$v/lt-vectors" >"$tmp/$v.txt" 2>"$tmp/$v.err"
    check "vectors/$v = golden" diff -u "$golden" "$tmp/$v.txt"
done
# the lane backends (firmware/include/lt/lt_v16_x86.h): host and sim take the widest x86 backend
# their -march allows, asan the portable loops; build/avx2 the AVX2 one, run where the CPU has AVX2
echo "   lane backends: host $("$B/host/lt-vectors" --backend 2>/dev/null), asan $("$B/asan/lt-vectors" --backend 2>/dev/null)"
if grep -qw avx2 /proc/cpuinfo 2>/dev/null; then
    "$B/avx2/lt-vectors" >"$tmp/avx2.txt" 2>"$tmp/avx2.err"
    check "vectors/avx2 ($("$B/avx2/lt-vectors" --backend 2>/dev/null) lanes) = golden" diff -u "$golden" "$tmp/avx2.txt"
    check "unit/avx2/test_v16 (every lane op against its scalar reference, AVX2 backend)" "$B/avx2/test_v16"
    check "unit/avx2/test_isect (packet kernels, AVX2 backend)" "$B/avx2/test_isect"
    check "unit/avx2/test_bvh (binary and wide BVH walks, AVX2 backend)" "$B/avx2/test_bvh"
    check "unit/avx2/test_wt (watertight test: packet lanes vs the scalar test, AVX2 register forms)" "$B/avx2/test_wt"
else
    echo "SKIP lane backend avx2: this CPU has no AVX2"
fi
# the counted build on the backend charges what the portable loops charge: the cycle report of
# the sim build (backend) = the ASan sim build's (portable), saturation events included
for b in sim asan; do
    "$B/$b/lanetrace" run scenes/teapot.json --res 48 --num q16 --no-ref --json 2>/dev/null |
        python3 -c 'import json, sys; d = json.load(sys.stdin)[0]; print(d["total_cycles"], d["events"])' \
            >"$tmp/bk.$b" 2>&1
done
check "cycle report on the $("$B/host/lt-vectors" --backend 2>/dev/null) backend = portable (cycles, events: $(cut -c1-60 "$tmp/bk.sim"))" \
    bash -c "[ -s '$tmp/bk.sim' ] && cmp -s '$tmp/bk.sim' '$tmp/bk.asan'"
source <(make -s --no-print-directory -f tools/print_qemu.mk)
for t in cm4 cm55 rv32; do
    qvar="QEMU_$t"
    timeout 120 ${!qvar} "$B/fw/$t/vectors.elf" >"$tmp/$t.out" 2>"$tmp/$t.err"
    rc=$?
    grep -v '^ram: ' "$tmp/$t.out" >"$tmp/$t.txt" # the RAM line every image prints (fwram.sh)
    check "vectors/$t exit 0 under QEMU (rc=$rc)" test "$rc" -eq 0
    check "vectors/$t = golden (bit-exact)" diff -u "$golden" "$tmp/$t.txt"
done
# portable_vs T OBJDUMP_ARGS REGEX NAMES WHAT BACKEND: the default image of target T takes its
# backend, T's vectors-portable.elf (LT_LANES_PORTABLE) the portable code: both must give the
# golden lines, and the backend's instructions (REGEX) must be in the one and not in the other
portable_vs() {
    local t=$1 od=$2 re=$3 names=$4 what=$5 backend=$6 qvar="QEMU_$1" nb np
    timeout 120 ${!qvar} "$B/fw/$t/vectors-portable.elf" 2>/dev/null </dev/null |
        grep -v '^ram: ' >"$tmp/${t}p.txt"
    nb=$(arm-none-eabi-objdump -d $od "$B/fw/$t/vectors.elf" | grep -cE "$re")
    np=$(arm-none-eabi-objdump -d $od "$B/fw/$t/vectors-portable.elf" | grep -cE "$re")
    check "vectors/$t portable $what (LT_LANES_PORTABLE) = golden; the $backend image has $nb $names, the portable one $np" \
        bash -c "diff -u '$golden' '$tmp/${t}p.txt' && [ $nb -gt 0 ] && [ $np -eq 0 ]"
}
# cm55: the Helium lane backend (lt_v16_mve.h) against the portable loops (VPSEL also comes from
# GCC's own vectorising of the portable loops; these three do not)
portable_vs cm55 -marmv8.1-m.main '\s(vqadd|vqsub|vmulh)\.s32' VQADD/VQSUB/VMULH.S32 lanes Helium
# cm4: the DSP extension's QADD/QSUB for the saturating adds (lt_fx.h) against the 64-bit sums
portable_vs cm4 "" '\sq(add|sub)\s' QADD/QSUB "saturating adds" DSP
timeout 120 $QEMU_rv32 "$B/fw/rv32/vectors-fixed.elf" >"$tmp/rv32x.txt" 2>/dev/null
grep -v -e '_f32 ' -e '^groups' "$golden" >"$tmp/golden-fixed.txt"
grep -v -e '^groups' -e '^ram: ' "$tmp/rv32x.txt" >"$tmp/rv32x-body.txt"
check "vectors/rv32 LT_CFG_FLOAT32=0 = golden fixed-point groups" diff -u "$tmp/golden-fixed.txt" "$tmp/rv32x-body.txt"
n=$(grep -c cases "$golden")
echo "   $n vector groups compared across host, sim, asan, cm4, cm55, rv32"

echo "== firmware target smoke test (start-up, UART, exit codes, no libc)"
check "firmware/targets/smoke.sh" firmware/targets/smoke.sh

echo "== QEMU instruction-count plugin"
check "plugin/test_plugin.sh" sh sim/qemu/test_plugin.sh

echo "== lanetrace on the bundled scene (native and simulator builds)"
"$HOSTBIN/lanetrace-native" run scenes/teapot.json --res 32 >"$tmp/native.txt" 2>&1
check "lanetrace-native run exits 0" test $? -eq 0
"$SIMBIN/lanetrace" run scenes/teapot.json --res 32 --report "$tmp/r.json" >"$tmp/sim.txt" 2>&1
check "lanetrace run (sim) exits 0" test $? -eq 0
for p in q16 f32; do
    a=$(grep "result    $p" "$tmp/native.txt")
    b=$(grep "result    $p" "$tmp/sim.txt")
    check "result $p: host = sim ($a)" test -n "$a" -a "$a" = "$b"
    check "report $p JSON written (r.$p.json)" test -s "$tmp/r.$p.json"
done
check "cycle report has phases, ops, cache, lanes" grep -q "lanes     utilisation" "$tmp/sim.txt"
acc=$(grep "accuracy  q16" "$tmp/native.txt" | sed -E 's/.*same triangle ([0-9.]+)%.*/\1/')
check "q16 same triangle as double on >= 99% of pixels ($acc%)" awk -v a="$acc" 'BEGIN{exit !(a >= 99.0)}'

# feature test scripts: each tests/run.d/*.sh is sourced and uses check/ok/ko and $B, $tmp
for f in tests/run.d/*.sh; do
    [ -f "$f" ] || continue
    run_part=$(basename "$f" .sh) # the scripts may reuse f (and t0): keep the name apart
    echo "== $run_part"
    part_t0=$SECONDS
    # shellcheck disable=SC1090
    source "$f"
    echo "   ($run_part: $((SECONDS - part_t0)) s)"
done

# the CLI scripts again, against the ASan + UBSan builds of every shipped program (build/asan/,
# host/host.mk): a sanitizer report fails the run's own check (its exit code is 86, never an
# expected one); ASan and LeakSanitizer reports also go to files under $tmp/san/, which fail the
# closing check (GCC's UBSan prints on stderr whatever log_path says: its exit code 86 is the sign)
ASAN_CLI_SCRIPTS=${LT_ASAN_CLI_SCRIPTS-cli errpaths machines meshin stream reproject frusta assimp_models}
if [ -n "$ASAN_CLI_SCRIPTS" ] && [ "$SIMBIN" != "$B/asan" ]; then
    echo "== CLI scripts against the ASan + UBSan builds ($B/asan: LeakSanitizer on)"
    mkdir -p "$tmp/san"
    export ASAN_OPTIONS="detect_leaks=1:exitcode=86:log_path=$tmp/san/asan:abort_on_error=0"
    export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=86:log_path=$tmp/san/ubsan"
    SIMBIN=$B/asan
    HOSTBIN=$B/asan
    for s in $ASAN_CLI_SCRIPTS; do
        echo "== $s (ASan + UBSan)"
        part_t0=$SECONDS
        # shellcheck disable=SC1090
        source "tests/run.d/$s.sh"
        echo "   ($s under ASan: $((SECONDS - part_t0)) s)"
    done
    unset ASAN_OPTIONS UBSAN_OPTIONS
    SIMBIN=${LT_SIMBIN:-$B/sim}
    HOSTBIN=${LT_HOSTBIN:-$B/host}
    nsan=$(find "$tmp/san" -type f | wc -l)
    check "no ASan/UBSan/LeakSanitizer report from the CLI scripts ($ASAN_CLI_SCRIPTS) run against $B/asan ($nsan reports)" \
        test "$nsan" -eq 0
    if [ "$nsan" -ne 0 ]; then
        for f in $(find "$tmp/san" -type f | head -n 5); do
            echo "--- $f"
            grep -m 3 -E 'ERROR|SUMMARY|runtime error|#[0-9] ' "$f" | head -n 12
        done
    fi
fi

echo "== shared scenes"
shared=../shared/scenes
if [ -f "$shared/bunny.obj" ]; then
    "$HOSTBIN/lanetrace-native" run --mesh "$shared/bunny.obj" --res 32 --num q16 -q >"$tmp/bunny.txt" 2>&1
    acc=$(grep "accuracy  q16" "$tmp/bunny.txt" | sed -E 's/.*same triangle ([0-9.]+)%.*/\1/')
    check "bunny.obj q16 same triangle as double ($acc%)" awk -v a="$acc" 'BEGIN{exit !(a >= 99.0)}'
elif [ "${CI:-}" = "true" ]; then
    ko "shared scenes missing under CI: $shared/bunny.obj"
else
    echo "SKIP shared scenes: $shared not found (a fresh clone has no ../shared)"
fi

echo
if [ $fail -ne 0 ]; then
    printf 'failed: %s\n' "${failed[@]}"
fi
echo "$pass passed, $fail failed (in $SECONDS s)"
[ $fail -eq 0 ]
