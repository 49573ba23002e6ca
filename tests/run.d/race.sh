# race.sh - smoke test of the race against Embree 3 (tests/bench/embree_race.c, docs/results.md):
# a short run (64x64, one timed pass) on the bundled teapot and, when ../shared is there, the
# Cornell box (coplanar duplicate faces: Embree's coherent packets keep other faces of the ties
# than its single rays). The machine lines are printed (CPU, its ISA, the build's ISA, Embree's
# version and native widths); every Embree mode prints its agreement line with its single-ray
# mode, at or above the 99.9% the race requires, and "ok"; the best modes and lanetrace's ratios
# are printed; --kv gives the machine-readable lines; a bad option exits 2. Timing is not checked.
# Sourced by tests/run_tests.sh ($B, $tmp, check/ok/ko).
race_meshes=(scenes/teapot.obj)
[ -f ../shared/scenes/CornellBox-Original.obj ] && race_meshes+=(../shared/scenes/CornellBox-Original.obj)
for m in "${race_meshes[@]}"; do
    n=$(basename "$m" .obj)
    "$B/host/embree-race" --mesh "$m" --res 64 --runs 1 --kv >"$tmp/race.txt" 2>&1
    rc=$?
    check "embree-race $n --res 64 exits 0 (rc $rc)" test "$rc" -eq 0
    check "embree-race $n: machine, CPU ISA, build ISA and tuning, Embree native widths printed" \
        bash -c "grep -q '^machine: ' '$tmp/race.txt' && grep -q '^CPU ISA: .*(widest: ' '$tmp/race.txt' &&
            grep -q '^lanetrace host build compiled for: .*; tuned for [a-z0-9-]*$' '$tmp/race.txt' &&
            grep -qE '^Embree [0-9]+\.[0-9]+\.[0-9]+: native ray4 (yes|no), ray8 (yes|no), ray16 (yes|no)' '$tmp/race.txt'"
    for md in rtcIntersect1 rtcIntersect4 rtcIntersect8 rtcIntersect16 rtcOccluded1 rtcOccluded4 \
        rtcOccluded8 rtcOccluded16; do
        line=$(grep -E "^  $md +(single|2x2|4x2|4x4) +(native|emulated) +[0-9.]+ Mrays/s \((incoherent|coherent) kept" "$tmp/race.txt")
        case $md in
        *1) check "embree-race $n: $md is the reference" bash -c "[[ '$line' == *' reference'* ]]" ;;
        rtcIntersect*)
            a=$(sed -nE 's/.* \(([0-9.]+)% with same-distance ties\): ok.*/\1/p' <<<"$line")
            check "embree-race $n: $md agrees with rtcIntersect1 on ${a:-?}% of pixels (>= 99.9)" \
                awk -v a="${a:-0}" 'BEGIN { exit !(a >= 99.9) }' ;;
        *)
            a=$(sed -nE 's/.* same occlusion as rtcOccluded1 on ([0-9.]+)% of rays: ok.*/\1/p' <<<"$line")
            check "embree-race $n: $md agrees with rtcOccluded1 on ${a:-?}% of rays (>= 99.9)" \
                awk -v a="${a:-0}" 'BEGIN { exit !(a >= 99.9) }' ;;
        esac
    done
    check "embree-race $n: best packet and shadow modes, lanetrace against each mode (binary and wide-tree packets)" \
        bash -c "grep -q '^Embree best packet mode: rtcIntersect' '$tmp/race.txt' &&
            grep -q '^Embree best shadow mode: rtcOccluded' '$tmp/race.txt' &&
            [ \$(grep -cE '^lanetrace (s15.16 |float32) 16-ray packets  .*[0-9]x Embree best packet mode rtcIntersect.*x rtcIntersect4, .*x rtcIntersect8.*, .*x rtcIntersect16' '$tmp/race.txt') -eq 2 ] &&
            [ \$(grep -cE '^lanetrace (s15.16 |float32) 16-ray packets \(wide BVH\) .*[0-9]x the binary walk = .*x Embree best packet mode' '$tmp/race.txt') -eq 2 ] &&
            [ \$(grep -cE '^lanetrace (s15.16 |float32) shadow packets  .*[0-9]x Embree best shadow mode rtcOccluded.*x rtcOccluded1, .*x rtcOccluded16' '$tmp/race.txt') -eq 2 ] &&
            [ \$(grep -cE '^lanetrace (s15.16 |float32) shadow packets \(wide BVH\) .*[0-9]x the binary walk = .*x Embree best shadow mode' '$tmp/race.txt') -eq 2 ] &&
            [ \$(grep -cE '^lanetrace (s15.16 |float32) single rays .*[0-9]x Embree rtcIntersect1' '$tmp/race.txt') -eq 2 ]"
    check "embree-race $n --kv: 8 mode lines, both paths, the machine" \
        bash -c "[ \$(grep -c '^race: mode name ' '$tmp/race.txt') -eq 8 ] &&
            [ \$(grep -c '^race: lanetrace path ' '$tmp/race.txt') -eq 2 ] &&
            grep -q '^race: cpu ' '$tmp/race.txt' && grep -q '^race: embree version ' '$tmp/race.txt'"
done
"$B/host/embree-race" --runs 99 >/dev/null 2>&1
rc=$?
check "embree-race --runs 99: usage error, exit 2 (rc $rc)" test "$rc" -eq 2

# the native soft-shadow race (tests/bench/frusta_race.c, docs/frusta.md, make frusta-race-doc):
# a short run on the bundled teapot in both paths; every Embree mode (4 widths x 2 flags) printed
# with the same occluded count, the best marked, lanetrace at the shipped defaults (leaf and
# culling set as `lanetrace shadows` prints them), S-Frusta's occluded count within 0.1% of
# Embree's (float vs s15.16 edge cases, back faces), the --kv line; a bad --cull letter exits 2
for p in q16 f32; do
    "$B/host/frusta-race" --mesh scenes/teapot.obj --res 32 --runs 1 --num "$p" --kv >"$tmp/frace.txt" 2>&1
    rc=$?
    def=$("$B/host/lanetrace-native" shadows --mesh scenes/teapot.obj --res 8 --no-ref 2>/dev/null |
        sed -nE 's/.*frusta leaf ([0-9]+), culling ([a-z]+),.*/\1 \2/p' | head -1)
    got=$(sed -nE 's/.*frusta leaf ([0-9]+), culling ([a-z]+),.*/\1 \2/p' "$tmp/frace.txt" | head -1)
    eo=$(sed -nE 's/^Embree rtcOccluded16 incoherent .*\(([0-9]+) occluded\).*/\1/p' "$tmp/frace.txt")
    lo=$(sed -nE 's/^lanetrace S-Frusta .*\(([0-9]+) occluded\).*/\1/p' "$tmp/frace.txt")
    check "frusta-race teapot --res 32 --num $p: exit 0 (rc $rc), 8 Embree modes with one occluded count, the best marked, leaf and culling = lanetrace shadows' defaults ($got = $def), S-Frusta occluded $lo vs Embree $eo (within 0.1%), --kv line" \
        bash -c "[ $rc -eq 0 ] && [ \$(grep -cE '^Embree rtcOccluded(1|4|8|16) +(incoherent|coherent) +[0-9.]+ Mrays/s \($eo occluded\)' '$tmp/frace.txt') -eq 8 ] &&
            [ \$(grep -c '<- best' '$tmp/frace.txt') -eq 1 ] && [ -n '$def' ] && [ '$got' = '$def' ] &&
            [ -n '$lo' ] && awk -v a='$lo' -v b='$eo' 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(b > 0 && d <= 0.001 * b) }' &&
            grep -qE '^frusta-race: scene scenes/teapot.obj path $p res 32 .* embree_best rtcOccluded[0-9]+_(in)?coherent ' '$tmp/frace.txt'"
done
"$B/host/frusta-race" --mesh scenes/teapot.obj --cull bx >"$tmp/frace.txt" 2>&1
rc=$?
check "frusta-race --cull bx: exit 2 naming the letter (rc $rc: $(head -c 90 "$tmp/frace.txt"))" \
    bash -c "[ $rc -eq 2 ] && grep -q \"not 'x'\" '$tmp/frace.txt'"
