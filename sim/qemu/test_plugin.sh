#!/bin/sh
# sim/qemu/test_plugin.sh: tests the lt_icount QEMU plugin (docs/qemu-plugin.md) on Cortex-M4
# (mps2-an386), Cortex-M55 (mps3-an547, with a Helium loop) and RV32IMAC (virt). Expected counts
# come from the disassembly: count_me is prologue + loop body x COUNT_ME_N + epilogue, main is
# straight-line; every executed instruction must land in a named function, except QEMU's RISC-V
# reset ROM, counted from -d in_asm. The cycle model: class counts sum to the total, count_me's
# loop branch is taken N - 1 times and not taken once, cycles = sum of count x cost for a test
# cost file, stage 1 (marked with lt_fw_stage around count_me's call) has the instructions the
# disassembly gives, the stages sum to the total, one instruction per block (-singlestep) changes
# nothing, the Helium loop's classes are right, bad cost files are refused. Run from the repo
# root. Exit 0 if all checks pass. Ends with "N passed, N failed".
# Word splitting of $CFLAGS, $QARM, $QARM55, $QRV and command output is intended.
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
eq()   { if [ "$1" = "$2" ]; then ok "$3"; else bad "$4"; fi; }   # GOT WANT PASS-TEXT FAIL-TEXT

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
            if (m == "nop" && n > 0 && kind[n - 1] == "ret") next   # padding after the return
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

# get FILE KEY: the count on line "icount KEY N ..." (KEY "total", "sym NAME", "class NAME").
get() { sed -n "s/^icount $2 \([0-9][0-9]*\)\( .*\)\{0,1\}\$/\1/p" "$1"; }

# call_gap OBJDUMP ELF FUNC CALLEE: instructions of FUNC after its first call to CALLEE, up to and
# including the second (FUNC straight-line between them).
call_gap()
{
    od=$1; elf=$2; name=$3; callee=$4
    set -- $(readelf -sW "$elf" | awk -v n="$name" '$4 == "FUNC" && $8 == n { print $2, $3 }')
    start=$(( (0x$1) & ~1 )); stop=$(( start + $2 ))
    "$od" -d --start-address="$start" --stop-address="$stop" "$elf" |
    awk -F'\t' -v c="<$callee>" '
        /^ *[0-9a-f]+:\t/ { if ($3 ~ /^\./ || $3 == "") next
                            if (calls == 1) n++
                            if (index($4, c) > 0) calls++ }
        END { print (calls >= 2 ? n : "?") }'
}

# cond_branches OBJDUMP ELF FUNC: conditional branches in FUNC's disassembly (Thumb b<cc>, cbz,
# cbnz, an IT-predicated bx/pop; RISC-V b*).
cond_branches()
{
    od=$1; elf=$2; name=$3
    set -- $(readelf -sW "$elf" | awk -v n="$name" '$4 == "FUNC" && $8 == n { print $2, $3 }')
    start=$(( (0x$1) & ~1 )); stop=$(( start + $2 ))
    "$od" -d --start-address="$start" --stop-address="$stop" "$elf" |
    awk -F'\t' '/^ *[0-9a-f]+:\t/ { m = $3; sub(/\.[nw]$/, "", m)
        if (m ~ /^b(eq|ne|cs|hs|cc|lo|mi|pl|vs|vc|hi|ls|ge|lt|gt|le)$/ || m ~ /^cbn?z$/ ||
            m ~ /^(bx|pop)(eq|ne|cs|hs|cc|lo|mi|pl|vs|vc|hi|ls|ge|lt|gt|le)$/ ||
            m ~ /^b(eq|ne|lt|ge|ltu|geu|gt|le|gtu|leu)z?$/) n++ }
        END { print n + 0 }'
}

# The test cost file: every class the test programs run, distinct prices, some fractional.
cat >"$B/test.cyc" <<'EOF'
# lt_icount test costs (test_plugin.sh)
alu 1
mul 3
mla 4
mull 5
div 7
load 2
load_after_load 1.5
store 1.5
ldm 1
ldm_reg 0.5
stm 2
stm_reg 1
branch_taken 3
branch_not_taken 1
jump 2.5     # a comment after a price
it 1
system 9
mve_alu 2
mve_mul 2.5
mve_load 3
mve_store 3.5
mve_ctl 0.5
lob 0
EOF

# check_target TAG OBJDUMP ELF UNNAMED QEMU-COMMAND...: runs the plugin three ways and checks.
check_target()
{
    tag=$1; od=$2; elf=$3; unnamed=$4; shift 4

    syms=$(readelf -sW "$elf" | awk '$4 == "FUNC" && $3 > 0 { print $8 }' | sort -u)
    slots=$(readelf -sW "$elf" | awk '$4 == "OBJECT" && $8 == "lt_fw_stage_slots" { print $2 }')
    args=",cyc=$B/test.cyc,stage=0x$slots"
    for s in $syms; do args="$args,sym=$s"; done
    # at=: executions of the entry instructions of count_me (called once) and lt_test_putc
    # (three times); the Thumb bit cleared
    for s in count_me lt_test_putc; do
        a=$(readelf -sW "$elf" | awk -v n="$s" '$4 == "FUNC" && $8 == n { print $2 }')
        args="$args,at=$(printf '%x' $(( (0x$a) & ~1 )))"
    done
    set -- "$@" -kernel "$elf"

    # run 1: out= file, -icount; run 2: same, through qemu_plugin_outs into a -D log;
    # run 3: without -icount (a different TB layout must give the same numbers). All with the
    # test cost file and stage marks.
    rm -f "$B/$tag.run1" "$B/$tag.run2" "$B/$tag.run3" "$B/$tag.run4"
    timeout 20 "$@" -icount shift=0 -plugin "$SO$args,out=$B/$tag.run1" >/dev/null 2>&1 ||
        bad "$tag: qemu run 1 failed"
    timeout 20 "$@" -icount shift=0 -plugin "$SO$args" -d plugin -D "$B/$tag.run2" \
        >/dev/null 2>&1 || bad "$tag: qemu run 2 failed"
    timeout 20 "$@" -plugin "$SO$args,out=$B/$tag.run3" >/dev/null 2>&1 ||
        bad "$tag: qemu run 3 failed"
    # run 4: one instruction per block; classes, taken branches, load pairs and stages must not
    # depend on how QEMU splits the code into blocks
    timeout 20 "$@" -singlestep -plugin "$SO$args,out=$B/$tag.run4" >/dev/null 2>&1 ||
        bad "$tag: qemu run 4 failed"
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
    eq "$got" "$exp" "$tag: main $got (straight-line)" "$tag: main $got, expected $exp"

    calls=$(awk '/^icount at / { printf "%s%s", sep, $4; sep = " " }' "$B/$tag.run1")
    eq "$calls" "1 3" "$tag: at= entry counts: count_me 1 call, lt_test_putc 3" \
        "$tag: at= entry counts '$calls', expected '1 3'"

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
    if cmp -s "$B/$tag.run1" "$B/$tag.run4"; then ok "$tag: same counts with -singlestep"
    else bad "$tag: runs 1 and 4 (-singlestep) differ"; fi

    r=$B/$tag.run1
    got=$(awk '$1 == "icount" && $2 == "class" { s += $4 } END { print s + 0 }' "$r")
    tot=$(get "$r" total)
    eq "$got" "$tot" "$tag: class counts sum to the total $tot" "$tag: class counts sum to $got, total $tot"
    got=$(awk '$1 == "icount" && $2 == "stage" { s += $5 } END { print s + 0 }' "$r")
    eq "$got" "$tot" "$tag: stage counts sum to the total" "$tag: stage counts sum to $got, total $tot"

    # count_me's bottom-tested loop is the program's only conditional branch (checked in the
    # other functions' disassembly): N - 1 taken, 1 not taken
    others=0
    for s in $syms; do
        [ "$s" = count_me ] || others=$((others + $(cond_branches "$od" "$elf" "$s")))
    done
    set -- $(fn_count "$od" "$elf" count_me loop)
    tk=$(get "$r" "class branch_taken"); nt=$(get "$r" "class branch_not_taken")
    if [ "$others" != 0 ]; then
        bad "$tag: $others conditional branches outside count_me; the branch check needs none"
    elif [ "$tk" = "$((N - 1))" ] && [ "$nt" = 1 ]; then
        ok "$tag: loop branch taken $tk, not taken $nt (the only conditional branch)"
    else bad "$tag: loop branch taken '$tk', not taken '$nt', expected $((N - 1)) and 1"; fi

    # stage 1: lt_fw_stage(1) .. lt_fw_stage(2) = the rest of lt_fw_stage after its store, main
    # from the first call to the second, count_me, lt_fw_stage up to its store: main's gap +
    # count_me + lt_fw_stage (straight-line, one store)
    fs=$(fn_count "$od" "$elf" lt_fw_stage line)
    gap=$(call_gap "$od" "$elf" main lt_fw_stage)
    exp=$(( $1 + fs + gap ))
    got=$(awk '$1 == "icount" && $2 == "stage" && $3 == 1 { print $5 }' "$r")
    if [ "$got" = "$exp" ]; then
        ok "$tag: stage 1 $got = main's gap $gap + count_me $1 + lt_fw_stage $fs"
    else bad "$tag: stage 1 '$got', expected $exp (gap $gap, count_me $1, lt_fw_stage $fs)"; fi

    # cycles: every line's count x its price from test.cyc, the total their sum, stages too
    # (in tenths of a cycle, exact)
    if awk 'NR == FNR { sub(/#.*/, ""); if (NF == 2) c[$1] = $2 * 10; next }
            $1 != "icount" { next }
            $2 == "cycles" { tot = $3 * 10; have = 1 }
            $2 == "class" || $2 == "regs" {
                if (!($3 in c) || $4 * c[$3] != $5 * 10) { print "line: " $0; bad = 1 }
                sum += $4 * c[$3] }
            $2 == "stage" { st += $7 * 10 }
            END { if (!have || sum != tot || st != tot) {
                      print "sum " sum " total " tot " stages " st; bad = 1 }
                  exit bad }' "$B/test.cyc" "$r" >"$B/$tag.cyc.err"; then
        ok "$tag: cycles $(awk '$2 == "cycles" { print $3 }' "$r") = sum of count x cost" \
           "= sum of the stages"
    else bad "$tag: cycles do not add up: $(cat "$B/$tag.cyc.err")"; fi
}

# refused WHAT PATTERN QEMU-COMMAND...: the command must fail and print PATTERN on stderr.
refused()
{
    what=$1; pat=$2; shift 2
    if timeout 20 "$@" >/dev/null 2>"$B/refused.err"; then bad "$what accepted"
    elif grep -qF -- "$pat" "$B/refused.err"; then
        ok "$what refused: $(grep -m1 -F -- "$pat" "$B/refused.err")"
    else bad "$what refused without '$pat': $(head -3 "$B/refused.err")"; fi
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
        # bad cost files: refused at load, with FILE:LINE and the reason
        printf 'alu 1\nbogus 2\n' >"$B/bad1.cyc"
        printf 'alu 1\nload 1.25\n' >"$B/bad2.cyc"
        printf 'alu 1\nstore\n' >"$B/bad3.cyc"
        printf 'alu 1\nalu 2\n' >"$B/bad4.cyc"
        refused "cm4: missing cost file" "nonexistent.cyc: cannot open" \
            $QARM -plugin "$SO,cyc=$B/nonexistent.cyc" -kernel $B/cm4.elf
        refused "cm4: unknown class" "bad1.cyc:2: unknown class 'bogus'" \
            $QARM -plugin "$SO,cyc=$B/bad1.cyc" -kernel $B/cm4.elf
        refused "cm4: price with two decimals" "bad2.cyc:2: '1.25' is not a number of cycles" \
            $QARM -plugin "$SO,cyc=$B/bad2.cyc" -kernel $B/cm4.elf
        refused "cm4: class without a price" "bad3.cyc:2: want 'CLASS CYCLES'" \
            $QARM -plugin "$SO,cyc=$B/bad3.cyc" -kernel $B/cm4.elf
        refused "cm4: class priced twice" "bad4.cyc:2: class 'alu' priced twice" \
            $QARM -plugin "$SO,cyc=$B/bad4.cyc" -kernel $B/cm4.elf
        # an executed class without a price: an error line instead of the cycles line
        grep -v '^jump' "$B/test.cyc" >"$B/nojump.cyc"
        rm -f "$B/nojump.out"
        timeout 20 $QARM -plugin "$SO,cyc=$B/nojump.cyc,out=$B/nojump.out" -kernel $B/cm4.elf \
            >/dev/null 2>&1
        if grep -qx 'icount error unpriced class jump' "$B/nojump.out" 2>/dev/null &&
                ! grep -q '^icount cycles' "$B/nojump.out"; then
            ok "cm4: executed class without a price: 'icount error unpriced class jump', no cycles"
        else bad "cm4: unpriced class not reported: $(head -3 "$B/nojump.out" 2>/dev/null)"; fi
    else
        bad "cm4: build"
    fi
else
    echo "skip cm4: arm-none-eabi-gcc or qemu-system-arm missing"
fi

# Cortex-M55 (mps3-an547): the same program, plus mve_me's Helium loop (LT_TEST_MVE; most of it
# is what QEMU's disassembler, capstone 4, prints as .byte). -fno-branch-count-reg keeps
# count_me a compare-and-branch loop (not DLS/LE).
if need arm-none-eabi-gcc && need qemu-system-arm; then
    QARM55="qemu-system-arm -M mps3-an547 -nographic -monitor none -serial stdio
            -semihosting-config enable=on,target=native"
    if arm-none-eabi-gcc -mcpu=cortex-m55 -mthumb -mfloat-abi=hard $CFLAGS -fno-branch-count-reg \
            -DLT_TEST_MVE -DLT_TEST_UART0=0x49303000u -T $T/cm4.ld -o $B/cm55.elf \
            $T/start_cm4.c $T/icount_test.c; then
        check_target cm55 arm-none-eabi-objdump $B/cm55.elf 0 $QARM55
        # mve_me: 10 trips of VLDRW, VADD, VMULH, VCMP, VPST, VADDT, VPSEL, VSTRW, LE after a DLS
        r=$B/cm55.run1
        got=$(for c in mve_load mve_alu mve_mul mve_ctl mve_store lob other; do
                  printf '%s=%s ' $c "$(get "$r" "class $c")"; done)
        if [ "$got" = "mve_load=10 mve_alu=40 mve_mul=10 mve_ctl=10 mve_store=10 lob=11 other= " ]
        then ok "cm55: Helium loop classes: $got"
        else bad "cm55: Helium loop classes '$got', expected mve_load=10 mve_alu=40 mve_mul=10" \
                 "mve_ctl=10 mve_store=10 lob=11, no other"; fi
    else
        bad "cm55: build"
    fi
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
