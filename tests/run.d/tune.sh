# tune.sh - lanetrace tune (docs/tune.md) on the bundled teapot at a small size with --jobs 2:
# the outputs exist; every reported front is non-dominated and complete (tests/tune/
# check_tune.py); each pick meets its budget on the verification run; the chosen scene files
# round-trip (run: the verification's cycles within 0.1%; reproject and shadows accept theirs and
# measure the same error); --jobs 1 and --jobs 2 measure the same points; bad budgets exit 2
# naming the input; an impossible budget exits 1 naming the best achievable values; the HTML
# report loads in headless Chromium with every image decoded and no console error (SKIP without
# chromium unless CI=true). Sourced by tests/run_tests.sh ($B, $tmp, check/ok/ko).
LT="$B/sim/lanetrace"
TU="$tmp/tune"
mkdir -p "$TU"
tu_py() { python3 tests/tune/check_tune.py "$@"; }
tu_expect() { # name, expected rc, fixed string in stderr+stdout, command...
    local name=$1 want=$2 pat=$3
    shift 3
    "$@" >"$TU/x.txt" 2>&1
    local rc=$?
    if [ "$rc" -eq "$want" ] && grep -qF -- "$pat" "$TU/x.txt"; then
        ok "$name (rc $rc: $(head -c 160 "$TU/x.txt" | tr '\n' ' '))"
    else
        ko "$name (rc $rc, want $want and '$pat'; output: $(head -c 300 "$TU/x.txt"))"
    fi
}

# a real tune: every family, both machines, probes at 16 px, full size 48 px
tu_t0=$(date +%s)
"$LT" tune scenes/teapot.obj --res 48 --probe-res 16 --jobs 2 --out "$TU/all" \
    --budget 'wrong<=1%,cycles<=2e7' >"$TU/all.txt" 2>&1
tu_rc=$?
check "tune teapot (all families, --jobs 2) exits 0 in $(($(date +%s) - tu_t0)) s" test "$tu_rc" -eq 0
grep -E '^(search|front|pick|binding|saved)' "$TU/all.txt" | sed 's/^/   /'
for f in front.csv front.json front.md front.png report.html chosen-object.json chosen-screen.json; do
    check "tune output $f written" test -s "$TU/all/$f"
done
check "tune: every front is non-dominated and complete ($(tu_py front "$TU/all/front.json" 2>&1 | tail -1))" \
    tu_py front "$TU/all/front.json"
check "tune: each pick meets its budget on the verification run" tu_py picks "$TU/all/front.json"
check "tune: the summary names budget, pick, binding constraint and cycles saved" \
    grep -qE '^saved     object: -?[0-9]+ cycles' "$TU/all.txt"

# the chosen scene files as they are
"$LT" run "$TU/all/chosen-object.json" --json >"$TU/run.json" 2>"$TU/run.err"
check "chosen-object.json runs through lanetrace run" test $? -eq 0
tu_vc=$(tu_py get "$TU/all/front.json" object cycles)
tu_rc_cyc=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))[0]["total_cycles"])' "$TU/run.json" 2>/dev/null)
# the CLI's kernels run on the process stack, charged at its real addresses: equal within 0.1%
check "lanetrace run of the chosen object scene: $tu_rc_cyc cycles, the verification's $tu_vc" \
    python3 -c 'import sys; a,b=map(float,sys.argv[1:3]); sys.exit(abs(a-b)>1e-3*b)' "${tu_rc_cyc:-nan}" "${tu_vc:-nan}"
"$B/host/lanetrace-native" render "$TU/all/chosen-screen.json" --layers 4 --out "$TU/src" -q \
    >"$TU/render.txt" 2>&1 &&
    "$LT" reproject "$TU/all/chosen-screen.json" --depth "$TU/src.exr" --truth -q --json \
        >"$TU/rp.json" 2>"$TU/rp.err"
check "chosen-screen.json runs through lanetrace render and reproject --truth" test $? -eq 0
tu_vw=$(tu_py get "$TU/all/front.json" screen wrong)
tu_rw=$(python3 -c 'import json,sys; t=json.load(open(sys.argv[1]))["truth"]; print(100.0*(t["spurious_hits"]+t["missed_hits"])/t["known_pixels"])' "$TU/rp.json" 2>/dev/null)
check "reproject of the chosen screen scene: wrong $tu_rw% = the verification's $tu_vw%" \
    python3 -c 'import sys; a,b=map(float,sys.argv[1:3]); sys.exit(abs(a-b)>1e-9)' "${tu_rw:-nan}" "${tu_vw:-nan}"

# shadows alone, a PSNR budget
"$LT" tune scenes/teapot.obj --family shadows --machine lrb16 --res 32 --jobs 2 --out "$TU/sh" \
    --budget 'psnr>=30' >"$TU/sh.txt" 2>&1
check "tune --family shadows --budget psnr>=30 exits 0" test $? -eq 0
check "tune shadows: the pick meets its budget on verification" tu_py picks "$TU/sh/front.json"
"$LT" shadows "$TU/sh/chosen-shadows.json" -q >"$TU/shq.txt" 2>&1
check "chosen-shadows.json runs through lanetrace shadows" test $? -eq 0
tu_vp=$(tu_py get "$TU/sh/front.json" shadows psnr)
tu_sp=$(sed -nE 's/.*PSNR filtered ([0-9.]+) dB, unfiltered 16 spp ([0-9.]+) dB.*/\1 \2/p' "$TU/shq.txt")
check "shadows of the chosen scene: PSNR ($tu_sp) includes the verification's $tu_vp dB" \
    python3 -c 'import sys; v=float(sys.argv[1]); sys.exit(not any(abs(float(x)-v)<0.006 for x in sys.argv[2:]))' \
    "${tu_vp:-nan}" $tu_sp

# --jobs does not change a measurement (the measurement server, docs/tune.md)
"$LT" tune scenes/teapot.obj --family object,screen --res 32 --probe-res 0 --jobs 1 --out "$TU/j1" -q \
    >/dev/null 2>&1
"$LT" tune scenes/teapot.obj --family object,screen --res 32 --probe-res 0 --jobs 2 --out "$TU/j2" -q \
    >/dev/null 2>&1
check "tune --jobs 1 and --jobs 2 measure the same points ($(tu_py same "$TU/j1/front.json" "$TU/j2/front.json" 2>&1))" \
    tu_py same "$TU/j1/front.json" "$TU/j2/front.json"

# bad input: exit 2 naming it; an impossible budget: exit 1 with the best achievable values
tu_expect "tune --budget with an unknown metric" 2 "unknown metric 'speed'" \
    "$LT" tune scenes/teapot.obj --budget 'speed<=3' --out "$TU/bad"
tu_expect "tune --budget with a negative bound" 2 "'wrong<=-1%': the bound of wrong is negative" \
    "$LT" tune scenes/teapot.obj --budget 'wrong<=-1%' --out "$TU/bad"
tu_expect "tune --budget with a non-numeric bound" 2 "'cycles<=abc': the bound of cycles is not a number" \
    "$LT" tune scenes/teapot.obj --budget 'cycles<=abc' --out "$TU/bad"
tu_expect "tune --budget with an empty term" 2 "empty term" \
    "$LT" tune scenes/teapot.obj --budget 'wrong<=1,' --out "$TU/bad"
tu_expect "tune --family with an empty family" 2 "--family '': empty family" \
    "$LT" tune scenes/teapot.obj --family '' --out "$TU/bad"
tu_expect "tune --family with an unknown family" 2 "unknown family 'volume'" \
    "$LT" tune scenes/teapot.obj --family object,volume --out "$TU/bad"
tu_expect "tune --budget no selected family measures" 2 "no selected family measures all of it (psnr missing" \
    "$LT" tune scenes/teapot.obj --family object --budget 'psnr>=30' --out "$TU/bad"
tu_expect "tune --machine unknown" 2 "--machine 'pdp11': unknown machine" \
    "$LT" tune scenes/teapot.obj --machine pdp11 --out "$TU/bad"
# found by the cli fuzz target: --machine '' planned and measured no machine, exit 0
tu_expect "tune --machine with an empty name" 2 "--machine '': empty machine name" \
    "$LT" tune scenes/teapot.obj --machine '' --plan "$TU/bad-plan"
tu_expect "tune --machine with an empty name in a list" 2 "--machine 'lrb16,,mcu-m4': empty machine name" \
    "$LT" tune scenes/teapot.obj --machine lrb16,,mcu-m4 --out "$TU/bad"
tu_expect "tune of a missing input" 1 "nothing.obj: cannot read the input" \
    "$LT" tune nothing.obj --out "$TU/bad"
tu_expect "tune with an impossible budget" 1 "is impossible for object: the best achievable values are wrong 0%, cycles" \
    "$LT" tune scenes/teapot.obj --family object --machine lrb16 --res 32 --budget 'wrong<=0%,cycles<=10' --out "$TU/imp"

# the HTML report in headless Chromium
tu_chr=$(command -v chromium || command -v chromium-browser || true)
if [ -n "$tu_chr" ]; then
    timeout 120 "$tu_chr" --headless --no-sandbox --disable-gpu --virtual-time-budget=5000 \
        --enable-logging=stderr --v=0 --dump-dom "file://$(realpath "$TU/all/report.html")" \
        >"$TU/dom.html" 2>"$TU/chromium.err"
    check "report.html loads in headless Chromium (exit $?)" grep -q '<h1>lanetrace tune' "$TU/dom.html"
    check "report.html: every image decodes ($(grep -o 'data-images="[0-9]*"' "$TU/dom.html"))" \
        grep -q 'data-broken-images="0"' "$TU/dom.html"
    check "report.html: no console error or uncaught exception" \
        bash -c "! grep -E 'CONSOLE|Uncaught|Failed to load' '$TU/chromium.err'"
elif [ "${CI:-}" = "true" ]; then
    ko "chromium missing under CI (tools/deps.sh installs it)"
else
    echo "SKIP tune report in headless Chromium: chromium not installed (make deps installs it)"
fi

# beyond one machine: --plan, GNU parallel on local jobs, --merge == the in-process tune
if command -v parallel >/dev/null 2>&1; then
    "$LT" tune scenes/teapot.obj --family object,screen --machine lrb16 --res 32 --plan "$TU/plan" \
        >"$TU/plan.txt" 2>&1
    check "tune --plan writes jobs.txt ($(wc -l <"$TU/plan/jobs.txt" 2>/dev/null) lines), tune.slurm, plan.json" \
        test -s "$TU/plan/jobs.txt" -a -s "$TU/plan/tune.slurm" -a -s "$TU/plan/plan.json"
    check "tune.slurm is an array job over the lines of jobs.txt" \
        grep -q "^#SBATCH --array=0-$(($(wc -l <"$TU/plan/jobs.txt") - 1))\$" "$TU/plan/tune.slurm"
    parallel --will-cite --jobs 2 <"$TU/plan/jobs.txt" >"$TU/parallel.txt" 2>&1
    check "GNU parallel runs every job of the plan (exit $?)" \
        test "$(ls "$TU/plan/results" | grep -c '^run-')" -eq "$(wc -l <"$TU/plan/jobs.txt")"
    "$LT" tune --merge "$TU/plan" --out "$TU/merged" -q >"$TU/merge.txt" 2>&1
    check "tune --merge exits 0" test $? -eq 0
    "$LT" tune scenes/teapot.obj --family object,screen --machine lrb16 --res 32 --probe-res 0 \
        --jobs 2 --out "$TU/inproc" -q >/dev/null 2>&1
    check "plan + GNU parallel + merge == the in-process tune, every point and front ($(tu_py same "$TU/inproc/front.json" "$TU/merged/front.json" 2>&1))" \
        tu_py same "$TU/inproc/front.json" "$TU/merged/front.json"
    rm -f "$TU/plan/results/run-3.json"
    tu_expect "tune --merge with a missing result names the run" 1 "1 of the plan's" \
        "$LT" tune --merge "$TU/plan" --out "$TU/merged2"
elif [ "${CI:-}" = "true" ]; then
    ko "GNU parallel missing under CI (tools/deps.sh installs it)"
else
    echo "SKIP tune --plan/--merge with GNU parallel: parallel not installed (make deps installs it)"
fi
