#!/usr/bin/env bash
# opcal.sh - calibrate sim/machines/mcu_m4.def from exact QEMU instruction counts (cm4, mps2-an386).
#  1. builds, with the Makefile's own rules and flags (firmware/opcal.mk on top of the Makefile):
#     build/fw/cm4/opcal.elf (tests/fw/fw_opcal.c), tri.elf, slab.elf, build/sim/{slab,tri}-model
#     and the lt_icount plugin;
#  2. counts the instructions inside each op wrapper of fw_opcal.c (and inside every helper it calls,
#     e.g. memcpy for 128-byte struct copies, __aeabi_ldivmod; a wrapper that calls a helper is run
#     alone in an image built with -DOPCAL_ONLY so that the helper's count is its own), subtracts
#     the empty wrapper of the same signature and divides by the number of calls;
#  3. prints per-wrapper instructions per op, the per-class values (weighted by how lt_slab16 and
#     lt_tri16 use each op), and the slab and triangle kernels' predicted vs counted.
# Unit: 1 executed guest instruction (QEMU TCG) = 1 cycle. Usage: tests/bench/opcal.sh [machine]
set -euo pipefail
cd "$(dirname "$0")/../.."
MACHINE=${1:-mcu-m4}
MK=(make -s --no-print-directory -f Makefile -f firmware/opcal.mk)
"${MK[@]}" opcal >/dev/null

# The firmware.mk compile and link commands for cm4, as shell assignments.
eval "$("${MK[@]}" --eval 'opcal-vars: ; @:$(info CC_FW="$(CC_cm4)")$(info CFLAGS_FW="$(subst ",\",$(FW_CFLAGS_COMMON) $(FPFLAGS) $(CFLAGS_cm4)) -Itests/vectors -DLT_COST_MODE=LT_COST_OFF")$(info LDFLAGS_FW="$(LDFLAGS_cm4)")$(info LDLIBS_FW="$(LDLIBS_cm4)")$(info OBJS_FW="$(fw_cm4_CORE) $(fw_cm4_RT)")$(info QEMU_FW="$(QEMU_cm4)")$(info PLUGIN="$(PLUGIN_SO)")' opcal-vars)"

OUT=build/opcal
mkdir -p "$OUT"
ELF=build/fw/cm4/opcal.elf

# qcount ELF OUTFILE SYM... : run under QEMU with the plugin; appends UART output to OUTFILE.uart
qcount() {
    local elf=$1 out=$2 args="" s
    shift 2
    for s in "$@"; do args="$args,sym=$s"; done
    timeout 30 $QEMU_FW "$elf" -plugin "$PLUGIN$args,out=$out" >"$out.uart"
}

# Direct callees (bl/b.w to another function) of each function, from the disassembly.
arm-none-eabi-objdump -d "$ELF" >"$OUT/opcal.dis"
callees() { # DIS FN: transitive closure of the callees of FN in disassembly DIS
    local dis=$1 todo=("$2") seen=" $2 " f c
    while [ ${#todo[@]} -gt 0 ]; do
        f=${todo[0]}
        todo=("${todo[@]:1}")
        for c in $(awk -v fn="<$f>:" '/^[0-9a-f]+ <.*>:$/ { cur = $2 } \
                /\tb(l|\.w)?\t[0-9a-f]+ </ && cur == fn { g = $NF; gsub(/[<>]/, "", g); \
                if (g !~ /\+0x/) print g }' "$dis" | sort -u); do
            case "$seen" in *" $c "*) ;; *) seen="$seen$c "; todo+=("$c"); echo "$c" ;; esac
        done
    done
}

# wrapper  class  empty-wrapper  divide-by (K = per call; lanes name = per active lane)
WRAPPERS="
w_valu_add      VALU    w_base_p3    K
w_valu_sub      VALU    w_base_p3    K
w_valu_min      VALU    w_base_p3    K
w_valu_max      VALU    w_base_p3    K
w_valu_blend    VALU    w_base_pk3   K
w_vmul_q16      VMUL    w_base_p3    K
w_vmul_ql       VMUL    w_base_p3    K
w_vmulw_add     VMULW   w_base_p3    K
w_vmulw_sub     VMULW   w_base_p3    K
w_vmulw_sub_m   VMULW   w_base_pk3   K
w_vshift_round  VSHIFT  w_base_p2    K
w_vshift_asr    VSHIFT  w_base_p2    K
w_vdiv_m        VDIV    w_base_pk3   K
w_vcmp_q16      VCMP    w_base_kp2   K
w_vcmp_ql       VCMP    w_base_kp2   K
w_vcvt          VCVT    w_base_p2    K
w_vred          VRED    w_base_kp1   K
w_vbcast        VBCAST  w_base_px    K
w_vbcast_ql     VBCAST  w_base_pl    K
w_fadd_add      FADD    w_base_p3    K
w_fadd_min      FADD    w_base_p3    K
w_fmul          FMUL    w_base_p3    K
w_fdiv          FDIV    w_base_p3    K
w_fcmp          FCMP    w_base_kp2   K
w_vload         VLOAD   w_base_p2    K
w_vstore        VSTORE  w_base_p2    K
w_mask_any      MASK    w_base_k     K
w_mask_popcount MASK    w_base_k     K
w_mask_first    MASK    w_base_k     K
w_vgather       VGATHER w_base_pkpp  gather_lanes
w_byval_add     (VALU)  w_base_byval K
w_byval_mul     (VMUL)  w_base_byval K
"
BASES="w_base_p3 w_base_pk3 w_base_p2 w_base_kp2 w_base_kp1 w_base_px w_base_pl w_base_k w_base_pkpp w_base_byval"

# Run 1: every wrapper without helpers, and the empty ones, in batches of <= 16 symbols.
: >"$OUT/counts.txt"
plain=() isolated=()
while read -r w cls base div; do
    [ -n "$w" ] || continue
    if [ -n "$(callees "$OUT/opcal.dis" "$w")" ]; then isolated+=("$w"); else plain+=("$w"); fi
done <<<"$WRAPPERS"
all=($BASES "${plain[@]}")
for ((i = 0; i < ${#all[@]}; i += 16)); do
    qcount "$ELF" "$OUT/run.txt" "${all[@]:i:16}"
    awk '/^icount sym/ { print $3, $4 }' "$OUT/run.txt" >>"$OUT/counts.txt"
done
UART=$(cat "$OUT/run.txt.uart")
# Run 2: each wrapper that calls helpers, alone, with its helpers.
for w in "${isolated[@]}"; do
    helpers=$(callees "$OUT/opcal.dis" "$w" | tr '\n' ' ')
    obj="$OUT/fw_opcal_$w.o"
    eval "$CC_FW $CFLAGS_FW '-DOPCAL_ONLY=\"$w\"' -c tests/fw/fw_opcal.c -o $obj"
    eval "$CC_FW $LDFLAGS_FW -o $OUT/$w.elf $obj $OBJS_FW $LDLIBS_FW"
    qcount "$OUT/$w.elf" "$OUT/run_$w.txt" "$w" $helpers
    awk -v w="$w" '/^icount sym/ { n += $4; if ($3 != w) h = h " " $3 } \
        END { print w, n, h }' "$OUT/run_$w.txt" >>"$OUT/counts.txt"
done

echo "opcal: $CC_FW $($CC_FW -dumpversion), $(echo "$CFLAGS_FW" | grep -o -- '-O[0-3s]' | head -1)," \
    "QEMU $(qemu-system-arm --version | head -1 | awk '{print $4}'); UART: $UART"
echo "instructions per op = (count in wrapper + helpers) / calls - empty wrapper of the same signature"
printf '%-8s %-16s %9s %7s  %s\n' class wrapper instr/op empty helpers
awk -v uart="$UART" -v wrappers="$WRAPPERS" '
    BEGIN {
        n = split(uart, u, " ")
        for (i = 1; i < n; i++) val[u[i]] = u[i + 1]
    }
    FNR == NR { cnt[$1] = $2; h = ""; for (i = 3; i <= NF; i++) h = h " " $i; helpers[$1] = h; next }
    END {
        K = val["K"]
        m = split(wrappers, L, "\n")
        for (i = 1; i <= m; i++) {
            if (split(L[i], f, " ") < 4) continue
            w = f[1]; base = cnt[f[3]] / K
            d = f[4] == "K" ? 1 : val[f[4]] / K
            per = (cnt[w] / K - base) / d
            printf "%-8s %-16s %9.1f %7.1f %s%s\n", f[2], w, per, base, helpers[w], \
                f[4] == "K" ? "" : " (per active lane)"
            print w, per > "build/opcal/perop.txt"
        }
    }' "$OUT/counts.txt" /dev/null

# Per-class values. Weights: how often one lt_slab16_q16 call plus one lt_tri16_q16 call
# (firmware/core/object/lt_isect.inc, fixed-point traits in lt_isect.c) use each op, the triangle's tail
# (t = tnum / det and after) counted as taken: VALU sub 6+3, min 6, max 6, blend 1+2 (q16 and vi32
# blend); VMUL q16 mul_sat 6, vql_mul 24; VMULW add 9, sub 6, merge-masked sub (the two-sided flip) 4;
# VSHIFT round_sat 6, asr 1; VCMP q16 1+2, vql 5; MASK the two any-tests. VBCAST is lt_vq16_set1
# alone, as specified for this calibration: lt_tri16's eight lt_vql_set1(0) are real (a 32-word
# store loop plus a 128-byte copy each, not folded away by GCC 12) but their wrapper cost is shown
# for information only; weighting them in (q16/vi32 16, vql 8 -> 166) over-predicts both kernels
# (slab 1.20, tri 1.07 vs 1.12, 1.02). Classes the fixed-point kernels do not use: equal weights.
echo
echo "class values (weights = uses in lt_slab16_q16 + lt_tri16_q16)"
awk '
    { v[$1] = $2 }
    function cls(name, spec,   n, p, i, w, s, ws, txt) {
        n = split(spec, p, " ")
        s = 0; ws = 0; txt = ""
        for (i = 1; i <= n; i += 2) {
            w = p[i + 1]; s += v[p[i]] * w; ws += w
            txt = txt sprintf(" %s x%d", p[i], w)
        }
        printf "%-8s %7.1f  =%s\n", name, s / ws, txt
    }
    END {
        cls("VALU",   "w_valu_sub 9 w_valu_min 6 w_valu_max 6 w_valu_blend 3")
        cls("VMUL",   "w_vmul_q16 6 w_vmul_ql 24")
        cls("VMULW",  "w_vmulw_add 9 w_vmulw_sub 6 w_vmulw_sub_m 4")
        cls("VSHIFT", "w_vshift_round 6 w_vshift_asr 1")
        cls("VDIV",   "w_vdiv_m 1")
        cls("VCMP",   "w_vcmp_q16 3 w_vcmp_ql 5")
        cls("VCVT",   "w_vcvt 1")
        cls("VRED",   "w_vred 1")
        cls("VBCAST", "w_vbcast 1 w_vbcast_ql 0")
        cls("FADD",   "w_fadd_add 1 w_fadd_min 1")
        cls("FMUL",   "w_fmul 1")
        cls("FDIV",   "w_fdiv 1")
        cls("FCMP",   "w_fcmp 1")
        cls("VLOAD",  "w_vload 1")
        cls("VSTORE", "w_vstore 1")
        cls("MASK",   "w_mask_any 2 w_mask_popcount 0 w_mask_first 0")
        cls("VGATHER","w_vgather 1")
    }' "$OUT/perop.txt"

# Kernel checks: the model's prediction vs the count inside the kernel and every function it calls.
echo
kernel() { # name elf model-binary
    local name=$1 elf=$2 model=$3 helpers pred cnt
    arm-none-eabi-objdump -d "$elf" >"$OUT/k.dis"
    helpers=$(callees "$OUT/k.dis" "$name" | tr '\n' ' ')
    qcount "$elf" "$OUT/k.txt" "$name" $helpers
    cnt=$(awk '/^icount sym/ { n += $4 } END { print n }' "$OUT/k.txt")
    pred=$("$model" "$MACHINE" 256 | awk '{ print $NF }')
    printf '%-14s 256 calls: predicted %9d counted %9d  pred/count %.3f  (counted: %s%s)\n' \
        "$name" "$pred" "$cnt" "$(echo "$pred $cnt" | awk '{ print $1 / $2 }')" "$name" \
        "$(awk '/^icount sym/ && NR > 2 { printf " + %s %d", $3, $4 }' "$OUT/k.txt")"
}
kernel lt_slab16_q16 build/fw/cm4/slab.elf build/sim/slab-model
kernel lt_tri16_q16 build/fw/cm4/tri.elf build/sim/tri-model
