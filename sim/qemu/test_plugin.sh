#!/bin/sh
# sim/qemu/test_plugin.sh: tests the lt_icount QEMU plugin (docs/qemu-plugin.md) on Cortex-M4
# (mps2-an386) and RV32IMAC (virt). Expected counts come from the disassembly: count_me is
# prologue + loop body x COUNT_ME_N + epilogue, main is straight-line; every executed instruction
# must land in a named function, except QEMU's RISC-V reset ROM, counted from -d in_asm.
# Run from the repo root. Exit 0 if all checks pass. Ends with "N passed, N failed".
# Word splitting of $CFLAGS, $QARM, $QRV and command output is intended.
# shellcheck disable=SC2086,SC2046
set -u

N=1000                              # count_me loop trips
B=build/plugin-test
T=sim/qemu/testdata
SO=build/plugin/lt_icount.so
pass=0
fail=0

ok()   { pass=$((pass + 1)); echo "ok   $*"; }
bad()  { fail=$((fail + 1)); echo "FAIL $*"; }
need() { command -v "$1" >/dev/null 2>&1; }

mkdir -p "$B" || exit 1
if ! timeout 120 make -s -f sim/qemu/plugin.mk "$SO"; then
    echo "FAIL plugin build"; echo "0 passed, 1 failed"; exit 1
fi

# fn_count OBJDUMP ELF NAME MODE: expected executions of function NAME, from its disassembly.
# MODE loop: exactly one branch, backward; prints "total pre body post" with
# total = pre + body * N + post. MODE line: no branch other than calls and a final return;
# prints the instruction count. Prints "?: reason" when the code has another shape.
fn_count()
{
    od=$1; elf=$2; name=$3; mode=$4
    # FUNC symbols give start and size, so alignment padding after the function is excluded.
    set -- $(readelf -sW "$elf" | awk -v n="$name" '$4 == "FUNC" && $8 == n { print $2, $3 }')
    [ $# -eq 2 ] || { echo "?: no FUNC symbol $name"; return; }
    start=$(( (0x$1) & ~1 ))        # clear the Thumb bit
    stop=$(( start + $2 ))
    "$od" -d --start-address="$start" --stop-address="$stop" "$elf" |
    awk -v mode="$mode" -v N="$N" '
        function hex(s,   i, v) {
            v = 0; s = tolower(s)
            for (i = 1; i <= length(s); i++)
                v = v * 16 + index("0123456789abcdef", substr(s, i, 1)) - 1
            return v
        }
        /^ *[0-9a-f]+:\t/ {
            split($0, f, "\t"); m = f[3]; ops = f[4]
            if (m ~ /^\./ || m == "") next          # literal pool (.word), not an instruction
            a = $1; sub(/:$/, "", a)
            addr[n] = hex(a); kind[n] = "op"
            if (m ~ /^(bx|ret)$/ && (ops ~ /^lr/ || m == "ret") || (m == "pop" && ops ~ /pc/) || \
                (m == "jr" && ops == "ra"))
                kind[n] = "ret"
            else if (m ~ /^blx?(\.[nw])?$/ || m == "call" || (m ~ /^jalr?$/ && ops !~ /^zero,/))
                kind[n] = "call"
            else if (m ~ /^(b|bx|cbz|cbnz|tbb|tbh|j|jr)(\.[nw])?$/ || \
                     m ~ /^b(eq|ne|cs|hs|cc|lo|mi|pl|vs|vc|hi|ls|ge|lt|gt|le)(\.[nw])?$/ || \
                     m ~ /^b(eq|ne|lt|ge|ltu|geu|gt|le|gtu|leu)z?$/) {
                kind[n] = "br"; t = ops; sub(/ <.*/, "", t); sub(/.*[, ]/, "", t); tgt[n] = hex(t)
            }
            n++
        }
        END {
            if (n == 0) { print "?: empty disassembly"; exit }
            if (kind[n - 1] != "ret") { print "?: does not end in a return"; exit }
            nb = 0
            for (i = 0; i < n; i++) if (kind[i] == "br") { nb++; bi = i }
            if (mode == "line") {
                if (nb) { print "?: main has branches"; exit }
                print n; exit
            }
            if (nb != 1 || tgt[bi] >= addr[bi]) { print "?: not a single backward loop"; exit }
            for (ti = 0; ti < n && addr[ti] != tgt[bi]; ti++) ;
            if (ti == n) { print "?: loop target outside the function"; exit }
            body = bi - ti + 1; post = n - bi - 1
            printf "%d %d %d %d\n", ti + body * N + post, ti, body, post
        }'
}

# get FILE KEY: the count on line "icount KEY N" (KEY "total" or "sym NAME").
get() { sed -n "s/^icount $2 \([0-9][0-9]*\)\$/\1/p" "$1"; }

# check_target TAG OBJDUMP ELF UNNAMED QEMU-COMMAND...: runs the plugin three ways and checks.
check_target()
{
    tag=$1; od=$2; elf=$3; unnamed=$4; shift 4

    syms=$(readelf -sW "$elf" | awk '$4 == "FUNC" && $3 > 0 { print $8 }' | sort -u)
    args=""
    for s in $syms; do args="$args,sym=$s"; done
    # at=: executions of the entry instructions of count_me (called once) and lt_test_putc
    # (three times); the Thumb bit cleared
    for s in count_me lt_test_putc; do
        a=$(readelf -sW "$elf" | awk -v n="$s" '$4 == "FUNC" && $8 == n { print $2 }')
        args="$args,at=$(printf '%x' $(( (0x$a) & ~1 )))"
    done
    set -- "$@" -kernel "$elf"

    # run 1: out= file, -icount; run 2: same, through qemu_plugin_outs into a -D log;
    # run 3: without -icount (a different TB layout must give the same numbers).
    rm -f "$B/$tag.run1" "$B/$tag.run2" "$B/$tag.run3"
    timeout 20 "$@" -icount shift=0 -plugin "$SO$args,out=$B/$tag.run1" >/dev/null 2>&1 ||
        bad "$tag: qemu run 1 failed"
    timeout 20 "$@" -icount shift=0 -plugin "$SO$args" -d plugin -D "$B/$tag.run2" \
        >/dev/null 2>&1 || bad "$tag: qemu run 2 failed"
    timeout 20 "$@" -plugin "$SO$args,out=$B/$tag.run3" >/dev/null 2>&1 ||
        bad "$tag: qemu run 3 failed"
    [ -s "$B/$tag.run1" ] || { bad "$tag: no plugin output"; return; }

    exp=$(fn_count "$od" "$elf" count_me loop)
    got=$(get "$B/$tag.run1" "sym count_me")
    set -- $exp
    if [ "$got" = "$1" ]; then
        ok "$tag: count_me $got = $2 + $3 x $N + $4 (disassembly: prologue + loop x N + epilogue)"
    else
        bad "$tag: count_me $got, expected $exp"
    fi
    exp=$(fn_count "$od" "$elf" main line)
    got=$(get "$B/$tag.run1" "sym main")
    if [ "$got" = "$exp" ]; then ok "$tag: main $got (straight-line)"
    else bad "$tag: main $got, expected $exp"; fi

    calls=$(awk '/^icount at / { printf "%s%s", sep, $4; sep = " " }' "$B/$tag.run1")
    if [ "$calls" = "1 3" ]; then ok "$tag: at= entry counts: count_me 1 call, lt_test_putc 3"
    else bad "$tag: at= entry counts '$calls', expected '1 3'"; fi

    sum=0
    for s in $syms; do sum=$((sum + $(get "$B/$tag.run1" "sym $s"))); done
    got=$(get "$B/$tag.run1" total)
    if [ "$got" = "$((sum + unnamed))" ]; then
        ok "$tag: total $got = sum over $(echo $syms | wc -w) functions $sum + unnamed $unnamed"
    else
        bad "$tag: total $got, functions $sum + unnamed $unnamed"
    fi
    if cmp -s "$B/$tag.run1" "$B/$tag.run2"; then ok "$tag: out= and qemu_plugin_outs agree"
    else bad "$tag: runs 1 and 2 differ"; fi
    if cmp -s "$B/$tag.run1" "$B/$tag.run3"; then ok "$tag: same counts without -icount"
    else bad "$tag: runs 1 and 3 (no -icount) differ"; fi
}

CFLAGS="-O2 -ffreestanding -nostdlib -Wall -Wextra -Werror -DCOUNT_ME_N=${N}u"

if need arm-none-eabi-gcc && need qemu-system-arm; then
    QARM="qemu-system-arm -M mps2-an386 -nographic -monitor none -serial stdio
          -semihosting-config enable=on,target=native"
    if arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb $CFLAGS -T $T/cm4.ld -o $B/cm4.elf \
            $T/start_cm4.c $T/icount_test.c; then
        check_target cm4 arm-none-eabi-objdump $B/cm4.elf 0 $QARM
        # A bad argument must stop QEMU, not be ignored.
        if timeout 20 $QARM -plugin "$SO,bogus=1" -kernel $B/cm4.elf >/dev/null 2>&1; then
            bad "cm4: unknown plugin argument accepted"
        else ok "cm4: unknown argument rejected"; fi
        if timeout 20 $QARM -plugin "$SO,at=12zz" -kernel $B/cm4.elf >/dev/null 2>&1; then
            bad "cm4: at= with a non-hexadecimal address accepted"
        else ok "cm4: at= with a non-hexadecimal address rejected"; fi
    else
        bad "cm4: build"
    fi
else
    echo "skip cm4: arm-none-eabi-gcc or qemu-system-arm missing"
fi

if need riscv64-unknown-elf-gcc && need qemu-system-riscv32; then
    QRV="qemu-system-riscv32 -M virt -bios none -nographic -monitor none -serial stdio"
    if riscv64-unknown-elf-gcc -march=rv32imac -mabi=ilp32 -mcmodel=medany $CFLAGS \
            -Wl,--no-warn-rwx-segments -T $T/rv32.ld -o $B/rv32.elf \
            $T/start_rv32.c $T/icount_test.c; then
        # The virt reset ROM (below 0x80000000, no symbol) runs once before _start: count its
        # distinct instructions in the translation log.
        rm -f $B/rv32.inasm
        timeout 20 $QRV -d in_asm -D $B/rv32.inasm -kernel $B/rv32.elf >/dev/null 2>&1
        rom=$(grep -E '^0x0000[0-9a-f]{4}:' $B/rv32.inasm | cut -d: -f1 | sort -u | wc -l)
        check_target rv32 riscv64-unknown-elf-objdump $B/rv32.elf "$rom" $QRV
    else
        bad "rv32: build"
    fi
else
    echo "skip rv32: riscv64-unknown-elf-gcc or qemu-system-riscv32 missing"
fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
