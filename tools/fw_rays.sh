#!/usr/bin/env bash
# fw_rays.sh - instructions per ray on the firmware targets (issue #13 item 3; docs/firmware.md,
# "Scene blobs"): runs build/fw/<T>/scene-<S>.elf under QEMU (-icount shift=0) on cm4, cm55 (its
# portable lane loops, and its Helium backend with the DSP lane-by-lane packet tests) and rv32
# with the lt_icount plugin and prints a Markdown table: the image's own per-ray counts of
# each stage (lt_fw_ticks: exact on rv32, SysTick-scaled on Arm) and the plugin's exact total of
# the whole run against the sum of the stages the image timed. Needs `make firmware plugin`.
# With the frusta block image (build/fw/<T>/scene-sibenik.elf, made where ../shared is) a second
# table gives its instructions per shadow sample.
# Usage: tools/fw_rays.sh [scene...] (default: bunny, bunny-wt32 (the s15.16 grid test), teapot). `make fw-doc` puts the table into
# docs/firmware.md; `make bench` prints it.
set -euo pipefail
cd "$(dirname "$0")/.."
B=${B:-build}
eval "$(make -s --no-print-directory -f tools/print_qemu.mk)"
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(bunny bunny-wt32 teapot)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# elf_of IMAGE TARGET: the image's file; a target with a p (cm4p, cm55p) is that target's portable
# build (IMAGE-portable.elf: no DSP, no Helium), which only a few images have: fails, printing
# nothing, when there is none
elf_of() {
    local t=${2%p}
    if [ "$t" = "$2" ]; then
        echo "$B/fw/$t/$1.elf"
    else
        [ -f "$B/fw/$t/$1-portable.elf" ] && echo "$B/fw/$t/$1-portable.elf"
    fi
}
# run ELF TARGET: the image under QEMU with the plugin into $tmp/out and $tmp/cnt
run() {
    local q="QEMU_${2%p}"
    rm -f "$tmp/cnt"
    timeout 300 ${!q} "$1" -plugin "$B/plugin/lt_icount.so,out=$tmp/cnt" </dev/null >"$tmp/out"
}
label() { case $1 in cm55p) echo "cm55 portable" ;; cm55) echo "cm55 Helium+DSP" ;; cm4p) echo "cm4 portable" ;; cm4) echo "cm4 DSP" ;; *) echo "$1" ;; esac; }
TARGETS="cm4p cm4 cm55p cm55 rv32"
echo "| scene | target | packets: primary | packets: shadow | single rays: primary | single rays: shadow | blob checks | whole run (plugin) | timed stages / plugin |"
echo "|---|---|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
    for t in $TARGETS; do
        elf=$(elf_of "scene-$s" "$t") || continue
        run "$elf" "$t"
        awk -v s="$s" -v t="$(label "$t")" -v cnt="$tmp/cnt" '
            /^sblob/ { ntri = $2 }
            /^image hash/ { rays = $5; srays = $9 }
            /^instr .* open/ { open = $4 }
            /^instr .* packets/ { pp = $5; ps = $7 }
            /^instr .* single/ { sp = $5; ss = $7 }
            END {
                while ((getline l < cnt) > 0) if (l ~ /^icount total/) { split(l, f, " "); tot = f[3] }
                timed = open + (pp + sp) * rays + (ps + ss) * srays
                printf "| %s (%d triangles, 64x64) | %s | %s | %s | %s | %s | %s | %s | %.3f |\n",
                    s, ntri, t, pp, ps, sp, ss, open, tot, timed / tot
            }' "$tmp/out"
    done
done

# the multi-frusta block (a frusta blob of the shared Sibenik; only where ../shared is)
if [ -f "$B/fw/cm4/scene-sibenik.elf" ]; then
    echo
    echo "| frusta block | target | per shadow sample | per lit pixel | blob checks and sample table | whole run (plugin) | timed stages / plugin |"
    echo "|---|---|---|---|---|---|---|"
    for t in $TARGETS; do
        elf=$(elf_of scene-sibenik "$t") || continue
        run "$elf" "$t"
        awk -v t="$(label "$t")" -v cnt="$tmp/cnt" '
            /^fblob/ { d = $0; sub(/^fblob /, "", d); sub(/, [0-9]+ bytes$/, "", d) }
            /^block hash/ { lit = $5 }
            /^instr .* open/ { open = $4 }
            /^instr .* per shadow sample/ { ps = $7; sub(/,$/, "", ps); pp = $11 }
            END {
                while ((getline l < cnt) > 0) if (l ~ /^icount total/) { split(l, f, " "); tot = f[3] }
                printf "| Sibenik, %s | %s | %s | %s | %s | %s | %.3f |\n", d, t, ps, pp, open, tot,
                    (open + pp * lit) / tot
            }' "$tmp/out"
    done
fi

# the reprojection of the Beachball crop, single rays (reproj-bb.elf) and packets
# (reproj-bb-packets.elf); only where ../shared is
if [ -f "$B/fw/cm4/reproj-bb.elf" ]; then
    echo
    echo "| reprojection | target | walk | per traced ray | quadtree build | whole run (plugin) | timed stages / plugin |"
    echo "|---|---|---|---|---|---|---|"
    for img in reproj-bb reproj-bb-packets; do
        for t in $TARGETS; do
            elf=$(elf_of "$img" "$t") || continue
            [ -f "$elf" ] || continue
            run "$elf" "$t"
            awk -v t="$(label "$t")" -v cnt="$tmp/cnt" '
                /^reproj-blob:/ { d = "Beachball crop 128x128 x 2 layers, n64" }
                /^ticks/ { b = $4; sub(/,$/, "", b); r = $6; sub(/,$/, "", r); pr = $10; sub(/,$/, "", pr)
                    w = $NF == "single" ? "single rays" : "packets of 16" }
                END {
                    while ((getline l < cnt) > 0) if (l ~ /^icount total/) { split(l, f, " "); tot = f[3] }
                    printf "| %s | %s | %s | %s | %s | %s | %.3f |\n", d, t, w, pr, b, tot, (b + r) / tot
                }' "$tmp/out"
        done
    done
fi
