#!/usr/bin/env bash
# opcal.sh - per-op microbenchmarks of a scalar machine from exact QEMU instruction counts: they
# gave the per-op costs the machine files had before their fit, now the fit's prior
# (sim/qemu/cycles/<target>.prior, tools/fw_fit.py), and the float rows, which no firmware stage
# fits (docs/firmware.md, "Cycle models"; docs/cost-model.md):
#   cm4  (default): mcu-m4, Cortex-M4F on mps2-an386 (hardware float);
#   rv32: rv32imac, RV32IMAC on virt (-mabi=ilp32: float32 in libgcc soft float).
#  1. builds, with the Makefile's own rules and flags (firmware/opcal.mk, `make opcal-<target>`):
#     build/fw/<target>/opcal.elf (tests/fw/fw_opcal.c), tri.elf, slab.elf (rv32 also tri_f32.elf,
#     slab_f32.elf), build/sim/{slab,tri}-model and the lt_icount plugin;
#  2. counts the instructions inside each op wrapper of fw_opcal.c (and inside every helper it
#     calls, e.g. memcpy for 128-byte struct copies, the 64-bit divide, on rv32 every soft-float routine
#     __addsf3, __mulsf3, __divsf3, __lesf2, ...; a wrapper that calls a helper is run alone in an
#     image built with -DOPCAL_ONLY so that the helper's count is its own), subtracts the empty
#     wrapper of the same signature and divides by the number of calls;
#  3. prints per-wrapper instructions per op, the per-class values (weighted by how the slab and
#     triangle kernels use each op), on rv32 the soft-float helpers' instructions per call (calls
#     counted at each helper's entry, the plugin's at=), and the kernels' predicted vs counted:
#     lt_slab16_q16, lt_tri16_q16, and on rv32 lt_slab16_f32, lt_tri16_f32.
# Unit: 1 executed guest instruction (QEMU TCG) = 1 cycle.
# Usage: tests/bench/opcal.sh [cm4|rv32] [machine]   (machine: the model that predicts the kernels;
# default mcu-m4 for cm4, rv32imac for rv32. A machine name alone, as before, means cm4.)
set -euo pipefail
cd "$(dirname "$0")/../.."
TARGET=${1:-cm4}
case $TARGET in
cm4 | rv32) MACHINE=${2:-} ;;
*) MACHINE=$TARGET TARGET=cm4 ;;
esac
case $TARGET in
cm4)
    MACHINE=${MACHINE:-mcu-m4}
    OBJDUMP=arm-none-eabi-objdump
    QEMU_BIN=qemu-system-arm
    # bl / b / b.w to another function
    CALLRE='\tb(l|[.]w)?\t[0-9a-f]+ <'
    ;;
rv32)
    MACHINE=${MACHINE:-rv32imac}
    OBJDUMP=riscv64-unknown-elf-objdump
    QEMU_BIN=qemu-system-riscv32
    # jal [ra,]ADDR <sym> (call), j ADDR <sym> (tail call), jalr ... # ADDR <sym> (far call)
    CALLRE='\t(jal|j)\t([a-z0-9]+,)?[0-9a-f]+ <|\tjalr\t.*# [0-9a-f]+ <'
    ;;
esac
export CALLRE
MK=(make -s --no-print-directory -f Makefile)
"${MK[@]}" "opcal-$TARGET" >/dev/null

# The firmware.mk compile and link commands for the target, as shell assignments.
eval "$("${MK[@]}" --eval "opcal-vars: ; @:\$(info CC_FW=\"\$(CC_$TARGET)\")\$(info CFLAGS_FW=\"\$(subst \",\\\",\$(FW_CFLAGS_COMMON) \$(FPFLAGS) \$(CFLAGS_$TARGET)) \$(FW_INC) -Itests/vectors -DLT_COST_MODE=LT_COST_OFF\")\$(info LDFLAGS_FW=\"\$(LDFLAGS_$TARGET)\")\$(info LDLIBS_FW=\"\$(LDLIBS_$TARGET)\")\$(info OBJS_FW=\"\$(fw_${TARGET}_CORE) \$(fw_${TARGET}_RT)\")\$(info QEMU_FW=\"\$(QEMU_$TARGET)\")\$(info PLUGIN=\"\$(PLUGIN_SO)\")" opcal-vars)"

OUT=build/opcal/$TARGET
mkdir -p "$OUT"
ELF=build/fw/$TARGET/opcal.elf

# qcount ELF OUTFILE ARG... : run under QEMU with the plugin; an ARG with '=' (at=ADDR) is passed
# as it is, any other is a symbol name (sym=ARG); appends UART output to OUTFILE.uart
qcount() {
    local elf=$1 out=$2 args="" s
    shift 2
    for s in "$@"; do
        case $s in *=*) args="$args,$s" ;; *) args="$args,sym=$s" ;; esac
    done
    timeout 30 $QEMU_FW "$elf" -plugin "$PLUGIN$args,out=$out" >"$out.uart"
}

# Direct callees (calls and tail calls to another function) of each function, from the disassembly.
$OBJDUMP -d "$ELF" >"$OUT/opcal.dis"
callees() { # DIS FN: transitive closure of the callees of FN in disassembly DIS
    local dis=$1 todo=("$2") seen=" $2 " f c
    while [ ${#todo[@]} -gt 0 ]; do
        f=${todo[0]}
        todo=("${todo[@]:1}")
        for c in $(awk -v fn="<$f>:" 'BEGIN { re = ENVIRON["CALLRE"] } \
                /^[0-9a-f]+ <.*>:$/ { cur = $2 } \
                $0 ~ re && cur == fn { g = $NF; gsub(/[<>]/, "", g); \
                if (g !~ /\+0x/) print g }' "$dis" | sort -u); do
            case "$seen" in *" $c "*) ;; *) seen="$seen$c "; todo+=("$c"); echo "$c" ;; esac
        done
    done
}
# Other names of the same code (libgcc's __ltsf2 = __lesf2, ...): QEMU may name an instruction by
# any of them, so each is counted. ELF FN...: the function symbols at the address of each FN that
# are not in the list.
aliases() {
    local elf=$1
    shift
    readelf -sW "$elf" | awk -v want=" $* " '
        $4 == "FUNC" && $3 > 0 { n[$2] = n[$2] " " $8; if (index(want, " " $8 " ")) a[$2] = 1 }
        END { for (v in a) { k = split(n[v], s, " "); for (i = 1; i <= k; i++) \
            if (!index(want, " " s[i] " ")) print s[i] } }' | sort -u
}
# entry address (hex, Thumb bit cleared) of function FN in ELF
entry() {
    local a
    a=$(readelf -sW "$1" | awk -v n="$2" '$4 == "FUNC" && $8 == n { print $2; exit }')
    printf '%x\n' $(((0x$a) & ~1))
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
# Soft float: every float op a libgcc call, so the FADD ops differ in price (add/sub a full
# __addsf3, min/max a compare, neg and blend integer only) and the masked divide pays per lane.
if [ "$TARGET" = rv32 ]; then
    WRAPPERS="$WRAPPERS
w_fadd_sub      FADD    w_base_p3    K
w_fadd_max      FADD    w_base_p3    K
w_fadd_blend    FADD    w_base_pk3   K
w_fadd_neg_m    FADD    w_base_pk3   K
w_fdiv_m        FDIV    w_base_pk3   K
"
fi
BASES="w_base_p3 w_base_pk3 w_base_p2 w_base_kp2 w_base_kp1 w_base_px w_base_pl w_base_k w_base_pkpp w_base_byval"

# Run 1: every wrapper without helpers, and the empty ones, in batches of <= 16 symbols.
: >"$OUT/counts.txt"
: >"$OUT/helpers.txt"
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
# Run 2: each wrapper that calls helpers, alone, with its helpers (and their other names); on rv32
# also the executions of each helper's entry, its calls.
for w in "${isolated[@]}"; do
    helpers=$(callees "$OUT/opcal.dis" "$w" | tr '\n' ' ')
    obj="$OUT/fw_opcal_$w.o"
    eval "$CC_FW $CFLAGS_FW '-DOPCAL_ONLY=\"$w\"' -c tests/fw/fw_opcal.c -o $obj"
    eval "$CC_FW $LDFLAGS_FW -o $OUT/$w.elf $obj $OBJS_FW $LDLIBS_FW"
    extra=$(aliases "$OUT/$w.elf" $helpers | tr '\n' ' ')
    ats=""
    if [ "$TARGET" = rv32 ]; then
        for h in $helpers; do ats="$ats at=$(entry "$OUT/$w.elf" "$h")"; done
    fi
    qcount "$OUT/$w.elf" "$OUT/run_$w.txt" "$w" $helpers $extra $ats
    # the printed helper list: the callees (as the disassembly names them)
    awk -v w="$w" -v hl=" $helpers " '/^icount sym/ { n += $4; \
            if ($3 != w && index(hl, " " $3 " ")) h = h " " $3 } \
        END { print w, n, h }' "$OUT/run_$w.txt" >>"$OUT/counts.txt"
    if [ "$TARGET" = rv32 ]; then
        # helper instructions calls: per helper, its count (with its other names) and its calls
        for h in $helpers; do
            a=$(entry "$OUT/$w.elf" "$h")
            names=" $h $(aliases "$OUT/$w.elf" "$h" | tr '\n' ' ') "
            awk -v w="$w" -v h="$h" -v a="0x$a" -v names="$names" '
                /^icount sym/ && index(names, " " $3 " ") { n += $4 }
                /^icount at/ && $3 == a { c = $4 }
                END { print w, h, n + 0, c + 0 }' "$OUT/run_$w.txt" >>"$OUT/helpers.txt"
        done
    fi
done

echo "opcal: $CC_FW $($CC_FW -dumpversion), $(echo "$CFLAGS_FW" | grep -o -- '-O[0-3s]' | head -1)," \
    "QEMU $($QEMU_BIN --version | head -1 | awk '{print $4}'); UART: $UART"
echo "instructions per op = (count in wrapper + helpers) / calls - empty wrapper of the same signature"
printf '%-8s %-16s %9s %7s  %s\n' class wrapper instr/op empty helpers
awk -v uart="$UART" -v wrappers="$WRAPPERS" -v perop="$OUT/perop.txt" '
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
            print w, per > perop
        }
    }' "$OUT/counts.txt" /dev/null

# The soft-float helpers (rv32): each one's own instructions per call, measured in the wrappers
# that call it (a helper that calls another, e.g. __clzsi2, does not include the callee's).
if [ "$TARGET" = rv32 ]; then
    echo
    echo "soft-float and other libgcc helpers: own instructions per call" \
        "(calls = executions of the entry)"
    printf '%-14s %-16s %10s %9s %10s\n' helper wrapper calls/op instr/op instr/call
    awk -v uart="$UART" '
        BEGIN {
            n = split(uart, u, " ")
            for (i = 1; i < n; i++) val[u[i]] = u[i + 1]
            K = val["K"]
        }
        $4 > 0 { printf "%-14s %-16s %10.2f %9.1f %10.1f\n", $2, $1, $4 / K, $3 / K, $3 / $4 }
    ' "$OUT/helpers.txt" | sort -k1,1 -k2,2
fi

# Per-class values. Weights: how often one lt_slab16_q16 call plus one lt_tri16_q16 call
# (firmware/core/object/lt_isect.inc, fixed-point traits in lt_isect.c) use each op, the triangle's tail
# (t = tnum / det and after) counted as taken: VALU sub 6+3, min 6, max 6, blend 1+2 (q16 and vi32
# blend); VMUL q16 mul_sat 6, vql_mul 24; VMULW add 9, sub 6, merge-masked sub (the two-sided flip) 4;
# VSHIFT round_sat 6, asr 1; VCMP q16 1+2, vql 5; MASK the two any-tests. VBCAST is lt_vq16_set1
# alone, as specified for this calibration: lt_tri16's eight lt_vql_set1(0) are real (a 32-word
# store loop plus a 128-byte copy each, not folded away by GCC 12) but their wrapper cost is shown
# for information only; weighting them in (q16/vi32 16, vql 8 -> 166) over-predicts both kernels
# (slab 1.20, tri 1.07 vs 1.12, 1.02). Classes the fixed-point kernels do not use: equal weights.
# rv32 (soft float), the float classes weighted by one lt_slab16_f32 + one lt_tri16_f32 call (tail
# taken): FADD add 8+1 (the dot products, u + v), sub 6+3+6 (slab, tvec, cross products), min 6,
# max 6 (slab), merge-masked neg 4 (the flip), blend 1+1; FDIV the candidate lanes' divide
# (w_fdiv_m, 8 of 16 lanes on, as VDIV); FCMP cmple_m (the compares with zero call the same
# routine).
FADD_SPEC="w_fadd_add 1 w_fadd_min 1"
FDIV_SPEC="w_fdiv 1"
CLASS_TITLE="class values (weights = uses in lt_slab16_q16 + lt_tri16_q16)"
if [ "$TARGET" = rv32 ]; then
    FADD_SPEC="w_fadd_add 9 w_fadd_sub 15 w_fadd_min 6 w_fadd_max 6 w_fadd_neg_m 4 w_fadd_blend 2"
    FDIV_SPEC="w_fdiv_m 1 w_fdiv 0"
    CLASS_TITLE="$CLASS_TITLE; float classes: lt_slab16_f32 + lt_tri16_f32"
fi
echo
echo "$CLASS_TITLE"
awk -v fadd="$FADD_SPEC" -v fdiv="$FDIV_SPEC" '
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
        cls("FADD",   fadd)
        cls("FMUL",   "w_fmul 1")
        cls("FDIV",   fdiv)
        cls("FCMP",   "w_fcmp 1")
        cls("VLOAD",  "w_vload 1")
        cls("VSTORE", "w_vstore 1")
        cls("MASK",   "w_mask_any 2 w_mask_popcount 0 w_mask_first 0")
        cls("VGATHER","w_vgather 1")
    }' "$OUT/perop.txt"

# Kernel checks: the model's prediction vs the count inside the kernel and every function it calls.
# The machines' integer rows are fitted in modelled cycles (tools/fw_cycles.sh), so pred/count of
# an s15.16 kernel includes the plugin's cycles per instruction (1.2-1.8 on these targets).
# A helper the loop around the kernel also called would be counted for the kernel: refused, except
# the start-up's copy of .data (lt__fw_reset calls lt__memcpy once, before main: on cm4 its few
# instructions are in the memcpy count).
echo
kernel() { # name elf model-binary [path]
    local name=$1 elf=$2 model=$3 path=${4:-} helpers extra pred cnt loopers
    $OBJDUMP -d "$elf" >"$OUT/k.dis"
    helpers=$(callees "$OUT/k.dis" "$name" | tr '\n' ' ')
    loopers=$(awk -v hl=" $helpers " -v kn="<$name>:" 'BEGIN { re = ENVIRON["CALLRE"] } \
        /^[0-9a-f]+ <.*>:$/ { cur = $2; \
            inside = (cur == kn) || index(hl, " " substr(cur, 2, length(cur) - 3) " ") } \
        $0 ~ re && !inside && cur != "<lt__fw_reset>:" { g = $NF; gsub(/[<>]/, "", g); \
            if (index(hl, " " g " ")) print cur, g }' "$OUT/k.dis")
    if [ -n "$loopers" ]; then
        echo "opcal.sh: $name: a helper is also called outside the kernel: $loopers" >&2
        return 1
    fi
    extra=$(aliases "$elf" $helpers | tr '\n' ' ')
    qcount "$elf" "$OUT/k.txt" "$name" $helpers $extra
    cnt=$(awk '/^icount sym/ { n += $4 } END { print n }' "$OUT/k.txt")
    pred=$("$model" "$MACHINE" 256 $path | awk '{ print $NF }')
    printf '%-14s 256 calls: predicted %9d counted %9d  pred/count %.3f  (counted: %s%s)\n' \
        "$name" "$pred" "$cnt" "$(echo "$pred $cnt" | awk '{ print $1 / $2 }')" "$name" \
        "$(awk -v hl=" $helpers " '/^icount sym/ && NR > 2 && (index(hl, " " $3 " ") || $4 > 0) \
            { printf " + %s %d", $3, $4 }' "$OUT/k.txt")"
}
kernel lt_slab16_q16 "build/fw/$TARGET/slab.elf" build/sim/slab-model
kernel lt_tri16_q16 "build/fw/$TARGET/tri.elf" build/sim/tri-model
if [ "$TARGET" = rv32 ]; then
    kernel lt_slab16_f32 build/fw/rv32/slab_f32.elf build/sim/slab-model f32
    kernel lt_tri16_f32 build/fw/rv32/tri_f32.elf build/sim/tri-model f32
fi
