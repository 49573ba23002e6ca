#!/usr/bin/env bash
# check_fw.sh ELF... - fail if a firmware image links a libc or simulator symbol; for images named
# *-fixed.elf (LT_CFG_FLOAT32=0) also fail on any soft-float helper. Prints .text/.data/.bss and
# the RAM the image measured when run once under QEMU (its stack high-water mark plus .data +
# .bss, from the "ram:" line every image prints at exit; the streaming images keep their UART
# binary and print none). A run takes well under a second; all images about 10 s.
set -uo pipefail
status=0
eval "$(make -s --no-print-directory -f tools/print_qemu.mk 2>/dev/null)" || true
LIBC_RE='^(printf|fprintf|sprintf|snprintf|puts|putchar|malloc|calloc|realloc|free|abort|exit|_exit|atexit|fopen|fwrite|fputs|strlen|strcmp|_sbrk|sbrk|__errno|_impure_ptr|_reent|raise|signal|time|clock)$'
FLOAT_RE='^(__aeabi_f|__aeabi_d|__addsf3|__subsf3|__mulsf3|__divsf3|__adddf3|__muldf3|__divdf3|__float|__fix|__eqsf2|__nesf2|__ltsf2|__lesf2|__gtsf2|__gesf2|__unordsf2|__extendsfdf2|__truncdfsf2)'
for elf in "$@"; do
    case "$elf" in */rv32/*) nm=riscv64-unknown-elf-nm; size=riscv64-unknown-elf-size ;;
                   *) nm=arm-none-eabi-nm; size=arm-none-eabi-size ;; esac
    syms=$($nm "$elf" | awk '{print $NF}')
    bad=$(grep -E "$LIBC_RE" <<<"$syms" | tr '\n' ' ')
    sim=$(grep -E '^lt_sim_|^lt__sim_' <<<"$syms" | tr '\n' ' ')
    undef=$($nm -u "$elf" | awk '{print $NF}' | tr '\n' ' ')
    if [ -n "$bad" ] || [ -n "$sim" ] || [ -n "$undef" ]; then
        echo "FAIL $elf: libc symbols [$bad] sim symbols [$sim] undefined [$undef]"
        status=1
    fi
    case "$elf" in *-fixed.elf)
        fl=$(grep -E "$FLOAT_RE" <<<"$syms" | tr '\n' ' ')
        if [ -n "$fl" ]; then
            echo "FAIL $elf: fixed-point-only image links float helpers [$fl]"
            status=1
        else
            echo "ok   $elf: no float helpers (LT_CFG_FLOAT32=0)"
        fi ;;
    esac
    read -r text data bss _ < <($size "$elf" | tail -1)
    t=$(basename "$(dirname "$elf")")
    q="QEMU_$t"
    ram="RAM not measured (no QEMU command for $t)"
    if [ -n "${!q:-}" ]; then
        line=$(timeout 60 ${!q} "$elf" </dev/null 2>/dev/null | grep -a '^ram: ')
        u=$(sed -n 's/^ram: stack \([0-9]*\) of.*/\1/p' <<<"$line")
        n=$(sed -n 's/.*static \([0-9]*\) bytes.*/\1/p' <<<"$line")
        if [ -n "$u" ] && [ -n "$n" ]; then
            ram=$(printf 'RAM %7s (stack %s + static %s)' $((u + n)) "$u" "$n")
        else
            ram="RAM not reported (binary UART)"
        fi
    fi
    printf 'size %-36s .text %7s  .data %5s  .bss %7s  %s\n' "$elf" "$text" "$data" "$bss" "$ram"
done
[ $status -eq 0 ] && echo "firmware: ${#@} images, no libc or sim symbols"
exit $status
