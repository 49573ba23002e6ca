# fwscene.sh - real meshes on the firmware targets (docs/firmware.md, "Scene blobs"). Sourced by
# tests/run_tests.sh ($B, $tmp, check/ok/ko). For the bundled bunny and teapot: `lanetrace pack`
# makes the same blob twice (byte for byte) and its trace agrees with the double-precision
# reference tracer; build/fw/<T>/scene-<S>.elf under QEMU on cm4, cm55 and rv32 prints every tile
# line and the image lines exactly as `lanetrace pack --in` does on the host, single rays equal
# packets; the instructions per ray each target counted are printed; on cm4 and cm55 the portable
# lane ops' bunny image gives the same lines and at least 2x the backend's instructions per packet
# ray. Bad blobs (truncated, damaged, not a blob) and bad flags get a message naming the file or
# limit. The shared dragon at 256x256
# when ../shared exists (SKIP otherwise, FAIL under CI=true).
FS_NAT="$HOSTBIN/lanetrace-native"
fs_expect() { # name, expected rc, pattern ("" = any), command...
    local name=$1 want=$2 pat=$3
    shift 3
    "$@" >"$tmp/fs.txt" 2>&1
    local rc=$?
    if [ "$rc" -eq "$want" ] && { [ -z "$pat" ] || grep -q -- "$pat" "$tmp/fs.txt"; }; then
        ok "$name (rc $rc)"
    else
        ko "$name (rc $rc, want $want; output: $(head -c 300 "$tmp/fs.txt"))"
    fi
}
# "same triangle P%" of a pack --trace output at least MIN percent
fs_acc_ok() { # file, min
    awk -v m="$2" '/^accuracy/ { for (i = 1; i < NF; i++) if ($i == "triangle") { p = $(i + 1); sub("%", "", p); ok = (p + 0 >= m) } } END { exit !ok }' "$1"
}
for s in bunny teapot; do
    blob="$B/gen/${s}64.ltsb"
    "$FS_NAT" pack --mesh "scenes/$s.obj" --res 64 --out "$tmp/fs-$s.ltsb" --trace >"$tmp/fs-$s.pack" 2>&1
    check "pack $s: the blob is made the same byte for byte as the firmware build's ($(stat -c %s "$blob" 2>/dev/null) bytes)" \
        cmp -s "$tmp/fs-$s.ltsb" "$blob"
    check "pack $s 64x64 s15.16: $(grep '^accuracy' "$tmp/fs-$s.pack" | sed 's/accuracy against the //') (bound >= 99.9%)" \
        fs_acc_ok "$tmp/fs-$s.pack" 99.9
    "$FS_NAT" pack --in "$blob" >"$tmp/fs-$s.host" 2>&1
    grep -E '^(tile|image)' "$tmp/fs-$s.host" >"$tmp/fs-$s.want"
    hp=$(sed -n 's/^image hash \(0x[0-9a-f]*\).*/\1/p' "$tmp/fs-$s.want")
    hs=$(sed -n 's/^image single rays hash \(0x[0-9a-f]*\).*/\1/p' "$tmp/fs-$s.want")
    check "pack --in $s (host): 16 tile lines, single rays = packets ($hp = $hs)" \
        bash -c "[ \$(grep -c '^tile' '$tmp/fs-$s.want') -eq 16 ] && [ -n '$hp' ] && [ '$hp' = '$hs' ]"
    for t in cm4 cm55 rv32; do
        qvar="QEMU_$t"
        timeout 300 ${!qvar} "$B/fw/$t/scene-$s.elf" </dev/null >"$tmp/fs-$s.$t" 2>&1
        rc=$?
        grep -E '^(tile|image)' "$tmp/fs-$s.$t" >"$tmp/fs-$s.$t.got"
        check "scene-$s.elf on $t under QEMU: exit 0, its 16 tile lines and 2 image lines = the host's (image $hp) (rc $rc)" \
            bash -c "[ $rc -eq 0 ] && [ -s '$tmp/fs-$s.want' ] && cmp -s '$tmp/fs-$s.want' '$tmp/fs-$s.$t.got'"
        grep -E '^instr' "$tmp/fs-$s.$t" | sed "s/^/     $s: /"
    done
done

# ---- the lane backends against the portable lane ops (LT_LANES_PORTABLE), the bunny ----
# cm4 and cm55 run the slab and watertight packet tests lane by lane (LT_LANEWISE(), lt_v16.h) and
# cm55 its other lane ops in Helium; the -portable images run the portable lane loops. The same
# lines, and (issue #13 item 3) the backends' 16-ray packets at least 2x fewer instructions per
# ray, counted on the target under -icount (deterministic).
fs_pk() { # file, primary|shadow: packets' instructions per ray
    awk -v w="$2" '/^instr .* packets primary/ { for (i = 1; i < NF; i++) if ($i == w) print $(i + 1) }' "$1"
}
for t in cm4 cm55; do
    qvar="QEMU_$t"
    timeout 300 ${!qvar} "$B/fw/$t/scene-bunny-portable.elf" </dev/null >"$tmp/fs-p.$t" 2>&1
    rc=$?
    grep -E '^(tile|image)' "$tmp/fs-p.$t" >"$tmp/fs-p.$t.got"
    bp=$(fs_pk "$tmp/fs-bunny.$t" primary) bs=$(fs_pk "$tmp/fs-bunny.$t" shadow)
    pp=$(fs_pk "$tmp/fs-p.$t" primary) ps=$(fs_pk "$tmp/fs-p.$t" shadow)
    check "scene-bunny-portable.elf on $t: its lines = the host's (rc $rc); packets $pp / $ps instructions per primary / shadow ray, the backend image's $bp / $bs: $(awk -v a="$pp" -v b="$bp" -v c="$ps" -v d="$bs" 'BEGIN { if (b > 0 && d > 0) printf "%.2fx / %.2fx", a / b, c / d }') fewer (want >= 2x)" \
        bash -c "[ $rc -eq 0 ] && cmp -s '$tmp/fs-bunny.want' '$tmp/fs-p.$t.got' && awk -v a='$pp' -v b='$bp' -v c='$ps' -v d='$bs' 'BEGIN { exit !(b > 0 && d > 0 && a >= 2 * b && c >= 2 * d) }'"
done

# ---- the bunny with the s15.16 grid test (LT_ISECT_WT32): the blob flag, objw images ----
blob="$B/gen/bunny64-wt32.ltsb"
"$FS_NAT" pack --mesh scenes/bunny.obj --res 64 --isect wt32 --out "$tmp/fs-w.ltsb" --trace >"$tmp/fs-w.pack" 2>&1
check "pack bunny --isect wt32: the blob is the firmware build's byte for byte; $(grep '^isect' "$tmp/fs-w.pack"); $(grep '^accuracy' "$tmp/fs-w.pack" | sed 's/accuracy against the //') (bound >= 99.9%)" \
    bash -c "cmp -s '$tmp/fs-w.ltsb' '$blob' && $(declare -f fs_acc_ok); fs_acc_ok '$tmp/fs-w.pack' 99.9"
"$FS_NAT" pack --in "$blob" >"$tmp/fs-w.host" 2>&1
grep -E '^(tile|image)' "$tmp/fs-w.host" >"$tmp/fs-w.want"
hp=$(sed -n 's/^image hash \(0x[0-9a-f]*\).*/\1/p' "$tmp/fs-w.want")
hs=$(sed -n 's/^image single rays hash \(0x[0-9a-f]*\).*/\1/p' "$tmp/fs-w.want")
hx=$(sed -n 's/^image hash \(0x[0-9a-f]*\).*/\1/p' "$tmp/fs-bunny.want")
check "pack --in bunny64-wt32 (host): single rays = packets ($hp = $hs), not the exact test's image ($hx): $(grep '^image hash' "$tmp/fs-w.want" | sed 's/.*rays/rays/') against $(grep '^image hash' "$tmp/fs-bunny.want" | sed 's/.*rays/rays/')" \
    bash -c "[ -n '$hp' ] && [ '$hp' = '$hs' ] && [ '$hp' != '$hx' ]"
for t in cm4 cm55 rv32; do
    qvar="QEMU_$t"
    timeout 300 ${!qvar} "$B/fw/$t/scene-bunny-wt32.elf" </dev/null >"$tmp/fs-w.$t" 2>&1
    rc=$?
    grep -E '^(tile|image)' "$tmp/fs-w.$t" >"$tmp/fs-w.$t.got"
    check "scene-bunny-wt32.elf on $t under QEMU: exit 0, its 16 tile lines and 2 image lines = the host's (image $hp) (rc $rc)" \
        bash -c "[ $rc -eq 0 ] && [ -s '$tmp/fs-w.want' ] && cmp -s '$tmp/fs-w.want' '$tmp/fs-w.$t.got'"
    # instructions per ray against the exact test's image on the same target
    awk -v t="$t" 'FNR == 1 { f++ } /^instr .* (packets|single) primary/ { for (i = 1; i <= NF; i++) { if ($i == "primary") p[f, $3] = $(i + 1); if ($i == "shadow") s[f, $3] = $(i + 1) } }
        END { for (m = 0; m < 2; m++) { k = m ? "single" : "packets"; if (p[1, k] > 0 && s[1, k] > 0) printf "     bunny %s %s: exact %s / %s, wt32 %s / %s instructions per primary / shadow ray (%.2fx / %.2fx)\n", t, k, p[1, k], s[1, k], p[2, k], s[2, k], p[2, k] / p[1, k], s[2, k] / s[1, k] } }' \
        "$tmp/fs-bunny.$t" "$tmp/fs-w.$t"
done

# ---- bad blobs and flags ----
head -c 1000 "$B/gen/teapot64.ltsb" >"$tmp/fs-short.ltsb"
cp "$B/gen/teapot64.ltsb" "$tmp/fs-dmg.ltsb"
printf '\x55' | dd of="$tmp/fs-dmg.ltsb" bs=1 seek=5000 conv=notrunc status=none
fs_expect "pack --in a truncated blob: refused, names the file" 1 "fs-short.ltsb: not a usable scene blob: shorter" \
    "$FS_NAT" pack --in "$tmp/fs-short.ltsb"
fs_expect "pack --in a damaged blob: checksum differs" 1 "checksum differs" "$FS_NAT" pack --in "$tmp/fs-dmg.ltsb"
fs_expect "pack --in an OBJ: not a scene blob" 1 "magic LTSB missing" "$FS_NAT" pack --in scenes/teapot.obj
fs_expect "pack --in a directory: not a regular file" 1 "not a regular file" "$FS_NAT" pack --in "$tmp"
fs_expect "pack --in a missing file" 1 "/nonexistent.ltsb: cannot read" "$FS_NAT" pack --in /nonexistent.ltsb
fs_expect "pack: --in and --out together is a usage error" 2 "give one of --out" \
    "$FS_NAT" pack --in a.ltsb --out b.ltsb
fs_expect "pack: --res above 4096 names the limit" 2 "1..4096" "$FS_NAT" pack --res 5000 --out "$tmp/x.ltsb"
fs_expect "pack: --leaf 0 names the range" 2 "1..64" "$FS_NAT" pack --leaf 0 --out "$tmp/x.ltsb"
fs_expect "pack: an unwritable --out is refused, naming the directory" 1 "/nonexistent/dir. does not exist" \
    "$FS_NAT" pack --out /nonexistent/dir/x.ltsb
fs_expect "lanetrace --help lists pack" 0 "pack SCENE|MESH" "$FS_NAT" --help

# ---- soft shadows: a multi-frusta block of the shared Sibenik on the targets ----
sib=../shared/scenes/sibenik.obj
if [ -f "$sib" ] && [ -f "$B/gen/sibenik-block.ltfb" ]; then
    "$FS_NAT" shadows --mesh "$sib" --res 128 --num q16 --only frusta --no-ref -q --pack-block auto \
        --blob "$tmp/fs-sib.ltfb" >"$tmp/fs-sib.host" 2>&1
    rc=$?
    grep -E '^(ftile|block)' "$tmp/fs-sib.host" >"$tmp/fs-sib.want"
    check "shadows --pack-block auto (Sibenik 128x128, 16 spp): $(grep '^fblob' "$tmp/fs-sib.host" | sed 's/ -> .*//'); the crop's block = the whole scene's ($(grep '^block' "$tmp/fs-sib.host")) (rc $rc)" \
        bash -c "[ $rc -eq 0 ] && grep -q 'whole scene 0x[0-9a-f]*: equal' '$tmp/fs-sib.want' && cmp -s '$tmp/fs-sib.ltfb' '$B/gen/sibenik-block.ltfb'"
    for t in cm4 cm55 rv32; do
        qvar="QEMU_$t"
        timeout 300 ${!qvar} "$B/fw/$t/scene-sibenik.elf" </dev/null >"$tmp/fs-sib.$t" 2>&1
        rc=$?
        grep -E '^(ftile|block)' "$tmp/fs-sib.$t" >"$tmp/fs-sib.$t.got"
        ram=$(sed -n 's/^ram: stack \([0-9]*\) of [0-9]* bytes, static \([0-9]*\) bytes.*/\1 \2/p' "$tmp/fs-sib.$t")
        used=$(( ${ram% *} + ${ram#* } ))
        check "scene-sibenik.elf on $t: exit 0, its 16 ftile lines and the block line = the host's, RAM $used bytes (budget 57344) (rc $rc)" \
            bash -c "[ $rc -eq 0 ] && [ -s '$tmp/fs-sib.want' ] && cmp -s '$tmp/fs-sib.want' '$tmp/fs-sib.$t.got' && [ $used -le 57344 ]"
        grep -E '^instr' "$tmp/fs-sib.$t" | sed "s/^/     sibenik: /"
    done
    for m in sponza conference; do
        mp=../shared/scenes/$m.obj
        [ -f "$mp" ] || mp=$(ls ../shared/scenes/$m.obj* 2>/dev/null | head -1)
        "$FS_NAT" shadows --mesh "$mp" --res 256 --num q16 --only frusta --no-ref -q --spp 8 \
            --pack-block auto --blob "$tmp/fs-$m.ltfb" >"$tmp/fs-$m.host" 2>&1
        rc=$?
        check "shadows --pack-block auto ($m 256x256, 8 spp): $(grep '^fblob' "$tmp/fs-$m.host" | sed 's/ -> .*//'); $(grep '^block' "$tmp/fs-$m.host") (rc $rc)" \
            bash -c "[ $rc -eq 0 ] && grep -q 'whole scene 0x[0-9a-f]*: equal' '$tmp/fs-$m.host'"
    done
    fs_expect "shadows --pack-block 3,5: not on the 4-pixel grid, named" 1 "must start on a multiple of 4" \
        "$FS_NAT" shadows --mesh "$sib" --res 64 --num q16 --only frusta --no-ref -q --pack-block 3,5 --blob "$tmp/x.ltfb"
    fs_expect "shadows --pack-block in float32: refused, names the path" 1 "needs the s15.16 path" \
        "$FS_NAT" shadows --mesh "$sib" --res 64 --num f32 --only frusta --no-ref -q --pack-block auto --blob "$tmp/x.ltfb"
elif [ "${CI:-}" = "true" ]; then
    ko "fwscene: shared Sibenik or its frusta blob missing under CI: $sib"
else
    echo "SKIP fwscene Sibenik frusta block: $sib not found (a fresh clone has no ../shared)"
fi
fs_expect "shadows --pack-block without --blob: usage error" 2 "go together" \
    "$FS_NAT" shadows --mesh scenes/teapot.obj --pack-block auto

# ---- a denser shared mesh at another size ----
dragon=../shared/scenes/dragon_res3.obj
if [ -f "$dragon" ]; then
    "$FS_NAT" pack --mesh "$dragon" --res 256 --out "$tmp/fs-dragon.ltsb" --trace >"$tmp/fs-dragon.pack" 2>&1
    hp=$(sed -n 's/^image hash \(0x[0-9a-f]*\).*/\1/p' "$tmp/fs-dragon.pack")
    hs=$(sed -n 's/^image single rays hash \(0x[0-9a-f]*\).*/\1/p' "$tmp/fs-dragon.pack")
    check "pack dragon_res3 256x256: single rays = packets ($hp), $(grep '^accuracy' "$tmp/fs-dragon.pack" | sed 's/accuracy against the //') (bound >= 99.8%)" \
        bash -c "[ -n '$hp' ] && [ '$hp' = '$hs' ] && $(declare -f fs_acc_ok); fs_acc_ok '$tmp/fs-dragon.pack' 99.8"
    rm -f "$tmp/fs-dragon.ltsb"
elif [ "${CI:-}" = "true" ]; then
    ko "fwscene: shared mesh missing under CI: $dragon"
else
    echo "SKIP fwscene dragon: $dragon not found (a fresh clone has no ../shared)"
fi
