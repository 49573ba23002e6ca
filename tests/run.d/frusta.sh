# frusta.sh - multi-frusta soft shadows and primary frusta (docs/frusta.md), CLI level. Sourced by
# tests/run_tests.sh ($B, $tmp, check/ok/ko): the unit test's tile hashes are equal in the host,
# sim and asan builds; lanetrace shadows gives the same result hash natively and in the simulator
# (s15.16 and float32), P-Frusta = P-Packet closest hit on every pixel with equal primary-image
# hashes, frusta = packet visibility on every pixel, a PNG is written, the Table-1 report (P and S
# rows) is printed, and bad input exits with the right code and names the input; the shared tile
# workload (shadow and primary frusta) hashes the same in the firmware images under QEMU (cm4,
# cm55, rv32) as on the host; the bunny runs when ../shared exists (SKIP otherwise, FAIL under
# CI=true).
SH_SIM="$SIMBIN/lanetrace"
SH_NAT="$HOSTBIN/lanetrace-native"
fr_expect() { # name, expected rc, pattern ("" = any), command...
    local name=$1 want=$2 pat=$3
    shift 3
    "$@" >"$tmp/fr.txt" 2>&1
    local rc=$?
    if [ "$rc" -eq "$want" ] && { [ -z "$pat" ] || grep -q -- "$pat" "$tmp/fr.txt"; }; then
        ok "$name (rc $rc)"
    else
        ko "$name (rc $rc, want $want; output: $(head -c 300 "$tmp/fr.txt"))"
    fi
}
for v in host sim asan; do
    "$B/$v/test_frusta" 2>/dev/null | grep -E "frusta (fw )?tile hash" >"$tmp/frhash.$v"
done
h=$(tr '\n' ' ' <"$tmp/frhash.host")
check "test_frusta tile hashes (shadow and primary frusta) host = sim = asan ($h)" \
    bash -c "[ -n \"$h\" ] && cmp -s '$tmp/frhash.host' '$tmp/frhash.sim' && cmp -s '$tmp/frhash.host' '$tmp/frhash.asan'"
fwh=$("$B/host/test_frusta" 2>/dev/null | grep "frusta fw tile hash")
for t in cm4 cm55 rv32; do
    qvar="QEMU_$t"
    timeout 300 ${!qvar} "$B/fw/$t/frusta.elf" >"$tmp/frfw.$t" 2>"$tmp/frfw.$t.err"
    rc=$?
    check "frusta tile on $t under QEMU: exit 0, hash = host unit test ($fwh) (rc $rc)" \
        bash -c "[ $rc -eq 0 ] && [ -n \"$fwh\" ] && grep -qF \"$fwh\" '$tmp/frfw.$t'"
done
for p in q16 f32; do
    "$SH_NAT" shadows --mesh scenes/teapot.obj --res 32 --num $p --png "$tmp/tp_$p.png" >"$tmp/frn.$p" 2>&1
    rcn=$?
    "$SH_SIM" shadows --mesh scenes/teapot.obj --res 32 --num $p >"$tmp/frs.$p" 2>&1
    rcs=$?
    a=$(grep "^result" "$tmp/frn.$p")
    b=$(grep "^result" "$tmp/frs.$p")
    check "lanetrace shadows teapot $p: native and sim exit 0 (rc $rcn, $rcs)" test "$rcn$rcs" = 00
    check "lanetrace shadows teapot $p: result native = sim ($a)" test -n "$a" -a "$a" = "$b"
    check "lanetrace shadows teapot $p: frusta = packet visibility" grep -q "visibility on .*(0 differ)" "$tmp/frs.$p"
    for f in "$tmp/frn.$p" "$tmp/frs.$p"; do
        ph=$(grep "^check     P-Frusta = P-Packet" "$f")
        check "lanetrace shadows teapot $p ($(basename "$f")): P-Frusta = P-Packet closest hit on every pixel, primary hashes equal ($ph)" \
            bash -c "grep -q 'P-Frusta = P-Packet closest hit on .*(0 differ)' '$f' && grep '^check     P-Frusta = P-Packet' '$f' | awk '{a = \$(NF-2); sub(\",\", \"\", a); if (\$NF != a) exit 1}'"
    done
    check "lanetrace shadows teapot $p: PNG written" test -s "$tmp/tp_$p.png"
done
check "lanetrace shadows sim prints the Table-1 rows (P and S)" \
    bash -c "grep -q '^P-Packet (+shad)' '$tmp/frs.q16' && grep -q '^P-Frusta (+shad)' '$tmp/frs.q16' && grep -q '^P Reduction' '$tmp/frs.q16' && grep -q '^S-Frusta ' '$tmp/frs.q16' && grep -q '^S Reduction' '$tmp/frs.q16' && grep -q '[kMG]*rays/s per simulated' '$tmp/frs.q16'"
# the "why" lines carry this run's figures (a fixed sentence was printed before): per-phase cycles
# of both methods whose sum is the stage total, and the deciding phase
check "lanetrace shadows sim: the why lines give this run's phase cycles and name the deciding phase ($(grep -c '^why ' "$tmp/frs.q16") lines)" \
    python3 -c "
import re, sys
ok = 0
for l in open(sys.argv[1]):
    m = re.match(r'why +([PS])-Frusta / [PS]-Packet ([0-9.]+)M / ([0-9.]+)M cycles .*: setup ([0-9.]+)M / ([0-9.]+)M, traversal ([0-9.]+)M / ([0-9.]+)M, intersection ([0-9.]+)M / ([0-9.]+)M, other ([0-9.]+)M / ([0-9.]+)M;.* the .* decides it', l)
    if not m: continue
    v = [float(x) for x in m.groups()[1:]]
    if abs(v[0] - (v[2] + v[4] + v[6] + v[8])) <= 0.03 and abs(v[1] - (v[3] + v[5] + v[7] + v[9])) <= 0.03:
        ok += 1
sys.exit(0 if ok == 2 else 1)" "$tmp/frs.q16"
# the old combination (S-Frusta on P-Packet primaries) and two-sided primaries stay available
"$SH_SIM" shadows --mesh scenes/teapot.obj --res 16 --prim packet --pcull cr --no-ref >"$tmp/frs.old" 2>&1
rco=$?
check "lanetrace shadows --prim packet --pcull cr: exit 0, S rows without P-Frusta (rc $rco)" \
    bash -c "[ $rco -eq 0 ] && grep -q '^S-Frusta ' '$tmp/frs.old' && ! grep -q '^P-Frusta' '$tmp/frs.old'"
check "lanetrace shadows prints the quality line" grep -q "^quality .*PSNR filtered" "$tmp/frn.q16"
fr_expect "shadows: usage without --mesh" 2 "usage:" "$SH_NAT" shadows
fr_expect "shadows: unknown option" 2 "unknown option" "$SH_NAT" shadows --mesh scenes/teapot.obj --frob
fr_expect "shadows: --leaf 0 names the limit" 2 "LT_BVH_MAX_LEAF" "$SH_NAT" shadows --mesh scenes/teapot.obj --leaf 0
fr_expect "shadows: --leaf 65 names the limit" 2 "1..64" "$SH_NAT" shadows --mesh scenes/teapot.obj --leaf 65
fr_expect "shadows: --res 8193 names the range (1..8192; 3 is taken since N x N from 1)" 2 "out of range; expected 1..8192" "$SH_NAT" shadows --mesh scenes/teapot.obj --res 8193
fr_expect "shadows: --cull letters" 2 "letters b, c, r, f, l, s, p" "$SH_NAT" shadows --mesh scenes/teapot.obj --cull x
fr_expect "shadows: --pcull letters" 2 "pcull x: expected letters b, c, r, l, s" "$SH_NAT" shadows --mesh scenes/teapot.obj --pcull x
fr_expect "shadows: --prim values" 2 "expected packet, frusta or both" "$SH_NAT" shadows --mesh scenes/teapot.obj --prim rays
fr_expect "shadows: --light needs 4 numbers" 2 "X,Y,Z,SIZE" "$SH_NAT" shadows --mesh scenes/teapot.obj --light 1,2
fr_expect "shadows: missing mesh names the file" 1 "/nonexistent.obj" "$SH_NAT" shadows --mesh /nonexistent.obj
fr_expect "shadows: light outside the fixed-point range" 1 "LT_CFG_GEOM_MAX_LOG2" \
    "$SH_NAT" shadows --mesh scenes/teapot.obj --res 8 --light 0,90000,0,1
fr_expect "shadows: unwritable PNG names the path" 1 "/nonexistent-dir/x.png" \
    "$SH_NAT" shadows --mesh scenes/teapot.obj --res 8 --no-ref --png /nonexistent-dir/x.png
fr_expect "shadows: unknown machine (sim)" 2 "z80" "$SH_SIM" shadows --mesh scenes/teapot.obj --res 8 --machine z80
shared_bunny=../shared/scenes/bunny.obj
if [ -f "$shared_bunny" ]; then
    fr_expect "shadows: bunny 64x64 in the sim, frusta = packet" 0 "visibility on .*(0 differ)" \
        "$SH_SIM" shadows --mesh "$shared_bunny" --res 64 --no-ref
    fr_expect "shadows: bunny 64x64 in the sim, P-Frusta = P-Packet" 0 "closest hit on .*(0 differ)" \
        "$SH_SIM" shadows --mesh "$shared_bunny" --res 64 --no-ref
elif [ "${CI:-}" = "true" ]; then
    ko "frusta: shared scene missing under CI: $shared_bunny"
else
    echo "SKIP frusta bunny: $shared_bunny not found (a fresh clone has no ../shared)"
fi
# FS (the shadow frusta's intervals shrink with CR; the default): the scene line says bcrfls, the
# primary frusta refuse f, and with it or without it the frusta equal the packets on every pixel
"$SH_SIM" shadows --mesh scenes/teapot.obj --res 48 --no-ref >"$tmp/fs1.txt" 2>&1
"$SH_SIM" shadows --mesh scenes/teapot.obj --res 48 --no-ref --cull bcrls >"$tmp/fs2.txt" 2>&1
check "shadows: FS and t are on by default (culling bcrflst), frusta = packets with and without it" \
    bash -c "grep -q 'culling bcrflst, primary culling bcrlst' '$tmp/fs1.txt' &&
             grep -q 'culling bcrls, primary' '$tmp/fs2.txt' &&
             grep -q 'frusta = packet visibility on 2304 of 2304 pixels (0 differ)' '$tmp/fs1.txt' &&
             grep -q 'frusta = packet visibility on 2304 of 2304 pixels (0 differ)' '$tmp/fs2.txt'"
fr_expect "shadows: --pcull f is refused (FS is the shadow frusta's)" 2 "pcull f: expected letters b, c, r, l, s" "$SH_NAT" shadows --mesh scenes/teapot.obj --pcull f
# the paper's 256-ray packet comparison (--cull p, shadow frusta only): same image as the packets
"$SH_SIM" shadows --mesh scenes/teapot.obj --res 48 --no-ref --cull bcp >"$tmp/p256.txt" 2>&1
check "shadows --cull bcp (256-ray packets): frusta = packets on every pixel" \
    grep -q 'frusta = packet visibility on 2304 of 2304 pixels (0 differ)' "$tmp/p256.txt"
fr_expect "shadows: --pcull p is refused (the 256-ray walk is the shadow frusta's)" 2 "pcull p: expected letters b, c, r, l, s" "$SH_NAT" shadows --mesh scenes/teapot.obj --pcull p
# samples per pixel (--spp 4, 8, 16, 32; scene key shadows.spp): frusta = packets, the quality line
# names the count, and fewer samples cost more PSNR against the 256-sample reference
for n in 4 8 32; do
    "$SH_SIM" shadows --mesh scenes/teapot.obj --res 48 --spp $n >"$tmp/spp$n.txt" 2>&1
    check "shadows --spp $n: frusta = packets on every pixel, $n spp traced" \
        bash -c "grep -q 'frusta = packet visibility on 2304 of 2304 pixels (0 differ)' '$tmp/spp$n.txt' &&
                 grep -q '$n shadow samples per pixel' '$tmp/spp$n.txt' && grep -q 'unfiltered $n spp' '$tmp/spp$n.txt'"
done
"$SH_SIM" shadows --mesh scenes/teapot.obj --res 48 >"$tmp/spp16.txt" 2>&1
check "shadows: unfiltered PSNR grows with the samples (4 < 8 < 16 < 32 spp)" python3 -c "
import re, sys
p = [float(re.search(r'unfiltered %d spp ([0-9.]+) dB' % n, open('$tmp/spp%d.txt' % n).read()).group(1)) for n in (4, 8, 16, 32)]
print('  PSNR unfiltered 4/8/16/32 spp: %s dB' % ' / '.join('%.2f' % v for v in p))
sys.exit(0 if p[0] < p[1] < p[2] < p[3] else 1)"
fr_expect "shadows --spp 12: refused naming the counts" 2 "spp 12: expected 4, 8, 16 or 32" "$SH_NAT" shadows --mesh scenes/teapot.obj --spp 12
printf '{"mesh": "%s/scenes/teapot.obj", "shadows": {"spp": 12}}\n' "$PWD" >"$tmp/spp.json"
fr_expect "scene: shadows.spp 12 refused naming the key" 1 "'shadows.spp' = 12: expected 4, 8, 16 or 32" "$SH_NAT" shadows "$tmp/spp.json"
