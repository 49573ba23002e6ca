# fwcycles.sh - the firmware cycle models (docs/firmware.md, "Cycle models"). Sourced by
# tests/run_tests.sh ($B, $tmp, check/ok/ko). Checks:
#  - out of sample: every kernel family of the whole-scene images (bunny and teapot blobs; the
#    Sibenik frusta block and the Beachball reprojection where ../shared has them) predicted by
#    the target's machine file (lt-fwmodel) within 10% of the cycles the QEMU plugin models on
#    cm4, cm55 and rv32 (tools/fw_cycles.sh --check 10; the table is printed);
#  - the committed machine files are what the fit gives: `tools/fw_cycles.sh --fit` on copies
#    writes the same LT_OP_COST lines (so a kernel change that moves the costs fails here until
#    the models are refitted);
#  - tools/fw_fit.py recovers known costs from synthetic rows and refuses malformed rows.
if [ -n "${CI:-}" ] && [ ! -f "$B/fw/cm4/reproj-bb.elf" ]; then
    ko "fwcycles: the shared images (reproj-bb, scene-sibenik) are missing under CI"
fi
[ -f "$B/fw/cm4/reproj-bb.elf" ] || echo "SKIP fwcycles: the Sibenik and Beachball images need ../shared (the bunny and teapot are checked)"
B=$B tools/fw_cycles.sh --check 10 >"$tmp/fwc.md" 2>"$tmp/fwc.err"
rc=$?
sed -n '3,$p' "$tmp/fwc.md" | sed 's/^/     /'
check "fw cycle models: $(grep -E ' per (ray|sample|pixel) \|' "$tmp/fwc.md" | grep -cv 'bunny-wt32') family x scene x target predictions within 10% of the plugin's cycles (and $(grep -E ' per (ray|sample|pixel) \|' "$tmp/fwc.md" | grep -c 'bunny-wt32') of the grid test printed, not calibrated) ($(grep '^Largest' "$tmp/fwc.md" | sed 's/ (units.*//')) (rc $rc$( [ -s "$tmp/fwc.err" ] && echo ": $(head -c 300 "$tmp/fwc.err")"))" \
    test "$rc" -eq 0

mkdir -p "$tmp/fwc-mach"
cp sim/machines/*.def "$tmp/fwc-mach/"
MACHDIR="$tmp/fwc-mach" B=$B tools/fw_cycles.sh --fit >"$tmp/fwc-fit.txt" 2>&1
rc=$?
same=1
for m in mcu_m4 mcu_m55 rv32imac; do
    cmp -s <(grep '^LT_OP_COST' "sim/machines/$m.def") <(grep '^LT_OP_COST' "$tmp/fwc-mach/$m.def") || same=0
done
grep '^fit over\|^## ' "$tmp/fwc-fit.txt" | paste - - | sed 's/^/     /'
check "fw cycle models: a refit on the calibration images (tools/fw_cycles.sh --fit) gives the committed op costs of mcu-m4, mcu-m55 and rv32imac (rc $rc)" \
    test "$rc" -eq 0 -a "$same" -eq 1

# synthetic rows: known integer costs, ops drawn per stage; the fit must reproduce the cycles
python3 - "$tmp/fwc-syn" <<'PY'
import random, sys
random.seed(7)
true = {"SALU": 3, "SMUL": 11, "BRANCH": 5, "VALU": 180, "VMUL": 420, "VLOAD": 90}
with open(sys.argv[1] + ".rows", "w") as f:
    for sc in "ab":
        for k in range(6):
            ops = {o: random.randint(1000, 90000) for o in true}
            cyc = sum(n * true[o] for o, n in ops.items())
            f.write("row syn%d-%s %d %d %s\n" % (k, sc, k, cyc, " ".join("%s=%d" % x for x in ops.items())))
with open(sys.argv[1] + ".def", "w") as f:
    for o in true:
        f.write("LT_OP_COST(%s, 1, 1)\n" % o)
PY
python3 tools/fw_fit.py "$tmp/fwc-syn.rows" "$tmp/fwc-syn.def" "$tmp/fwc-syn.def" --write >"$tmp/fwc-syn.txt" 2>&1
check "fw_fit.py: six known costs recovered from 12 synthetic stages ($(grep '^fit over' "$tmp/fwc-syn.txt"))" \
    bash -c "grep -q 'rms relative error 0.00%' '$tmp/fwc-syn.txt' && grep -q 'LT_OP_COST(VMUL, *420, *420)' '$tmp/fwc-syn.def' && grep -q 'LT_OP_COST(SALU, *3, *3)' '$tmp/fwc-syn.def'"
echo "row x 1 12 SALU=zz" >"$tmp/fwc-bad.rows"
python3 tools/fw_fit.py "$tmp/fwc-bad.rows" "$tmp/fwc-syn.def" "$tmp/fwc-syn.def" >"$tmp/fwc-bad.txt" 2>&1
rc=$?
check "fw_fit.py: a malformed row is refused with its file and line (rc $rc: $(head -c 120 "$tmp/fwc-bad.txt"))" \
    bash -c "[ $rc -eq 1 ] && grep -q 'fwc-bad.rows:1: malformed row' '$tmp/fwc-bad.txt'"
