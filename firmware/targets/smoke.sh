#!/bin/sh
# smoke.sh - build firmware/targets/hello.c for every firmware target and run it under QEMU.
# Checks per target: expected UART text, exit code 7, identical output on a second run (-icount
# determinism), exit codes 0/42/255 passing through, no libc symbols, and that the memory
# functions (common/lt_rt.c, core/lt_mem.c) do not call themselves. Prints one line per target; exit status 1 on failure.
# Usage: firmware/targets/smoke.sh   (from anywhere; builds into build/smoke/)
set -u
cd "$(dirname "$0")/../.." || exit 1

MK="make -s -f firmware/targets/smoke.mk"
if ! $MK; then
    echo "smoke: build FAILED"
    exit 1
fi

TARGETS=$($MK print-FW_TARGETS)
fail=0
for t in $TARGETS; do
    qemu=$($MK print-QEMU_$t)
    cc=$($MK print-CC_$t)
    tool=${cc%gcc}
    dir=build/smoke/$t
    why=""

    out=$(timeout 10 $qemu $dir/hello.elf </dev/null 2>$dir/hello.stderr)
    rc=$?
    out2=$(timeout 10 $qemu $dir/hello.elf </dev/null 2>/dev/null)
    [ "$rc" -eq 7 ] || why="$why rc=$rc(want 7)"
    for want in "hello from $t" "u32: 0 1234567890 4294967295" "hex: 0x00000000 0xdeadbeef" \
                "data/bss: ok" "rt: ok" "fpu: 375" "exit: 7"; do
        printf '%s\n' "$out" | grep -qxF "$want" || why="$why missing[$want]"
    done
    if [ "$t" = cm55 ]; then
        printf '%s\n' "$out" | grep -qxF "mve: 20" || why="$why missing[mve: 20]"
    fi
    ticks=$(printf '%s\n' "$out" | sed -n 's/^ticks: \([0-9]*\) at [0-9]*$/\1/p')
    [ -n "$ticks" ] && [ "$ticks" -gt 0 ] || why="$why bad-ticks"
    [ "$out" = "$out2" ] || why="$why nondeterministic"

    for code in 0 42 255; do
        timeout 10 $qemu $dir/exit$code.elf </dev/null >/dev/null 2>&1
        r=$?
        [ "$r" -eq "$code" ] || why="$why exit$code->$r"
    done

    if [ -n "$(${tool}nm -u $dir/hello.elf)" ]; then why="$why undefined-symbols"; fi
    libc=$(${tool}nm $dir/hello.elf | awk '{print $NF}' |
           grep -xE 'printf|puts|putchar|malloc|free|calloc|abort|exit|_exit|_sbrk|_write|strlen')
    if [ -n "$libc" ]; then why="$why libc[$libc]"; fi
    # GCC may turn the byte loops back into memset/memcpy calls (infinite recursion): the
    # memory functions may reference no libc-named one (memcpy calling lt__memcpy is fine).
    for o in lt_rt lt_mem; do
        if ${tool}objdump -dr $dir/$o.o |
           grep -qE 'R_[A-Z0-9_]+[[:space:]]+mem(cpy|set|move|cmp)$'; then
            why="$why $o-calls-mem*"
        fi
    done

    if [ -z "$why" ]; then
        echo "$t: ok (rc 7; exit 0/42/255 pass through; ticks $ticks; deterministic)"
    else
        echo "$t: FAIL$why"
        printf '%s\n' "$out" | sed 's/^/    | /'
        fail=1
    fi
done
exit $fail
