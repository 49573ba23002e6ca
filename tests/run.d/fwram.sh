# fwram.sh - the firmware programs' RAM (docs/firmware.md, "RAM"): every image paints its stack at
# boot and prints "ram: stack U of S bytes, static N bytes (.data + .bss)" at exit; under QEMU on
# cm4, cm55 and rv32 each program must print it, stay below its stack size, and need at most the
# budget of tests/fw/ram_budget.txt (U + N). A program whose line says needs=PATH is skipped when
# PATH is missing (../shared: a SKIP line; a FAIL under CI=true). Sourced by tests/run_tests.sh
# ($B, $tmp, check).
while read -r prog budget rest; do
    case $prog in '' | '#'*) continue ;; esac
    needs=$(sed -n 's/^needs=\([^ ]*\).*/\1/p' <<<"$rest")
    if [ -n "$needs" ] && [ ! -f "$needs" ]; then
        if [ "${CI:-}" = "true" ]; then
            ko "fw $prog.elf RAM: $needs missing under CI"
        else
            echo "SKIP fw $prog.elf RAM: $needs not found (a fresh clone has no ../shared)"
        fi
        continue
    fi
    for t in cm4 cm55 rv32; do
        qvar="QEMU_$t"
        line=$(timeout 300 ${!qvar} "$B/fw/$t/$prog.elf" </dev/null 2>/dev/null | grep '^ram: ')
        used=$(sed -n 's/^ram: stack \([0-9]*\) of.*/\1/p' <<<"$line")
        size=$(sed -n 's/^ram: stack [0-9]* of \([0-9]*\) bytes.*/\1/p' <<<"$line")
        stat=$(sed -n 's/.*static \([0-9]*\) bytes.*/\1/p' <<<"$line")
        check "fw/$t $prog.elf RAM: ${line#ram: } = $(( ${used:-0} + ${stat:-0} )) bytes, budget $budget" \
            test -n "$used" -a -n "$size" -a -n "$stat" -a "${used:-0}" -lt "${size:-0}" \
            -a $(( ${used:-0} + ${stat:-0} )) -le "$budget"
    done
done <tests/fw/ram_budget.txt
