# errpaths.sh - error paths of the CLIs that the other scripts do not take: outputs that cannot be
# written after the work is done, inputs of the wrong kind (a directory, a missing layer), cut or
# hostile inputs from the fuzz corpora. Each must exit 1 with one line naming the file; run a
# second time against the ASan + UBSan builds by tests/run_tests.sh, where LeakSanitizer makes a
# leak on any of these paths a failure. Sourced by tests/run_tests.sh (check/ok/ko, $B, $tmp,
# $SIMBIN, $HOSTBIN).
ep_expect() { # name, expected rc, pattern in output, command...
    local name=$1 want=$2 pat=$3
    shift 3
    "$@" >"$tmp/ep.txt" 2>&1
    local rc=$?
    if [ "$rc" -eq "$want" ] && grep -q -- "$pat" "$tmp/ep.txt"; then
        ok "$name (rc $rc)"
    else
        ko "$name (rc $rc, want $want; output: $(tail -c 300 "$tmp/ep.txt"))"
    fi
}
E=$tmp/ep
mkdir -p "$E"
"$HOSTBIN/lanetrace-native" render --res 16 --layers 2 --out "$E/d" -q >/dev/null 2>&1
check "errpaths: a 2-layer depth EXR to reproject" test -s "$E/d.exr"
ep_expect "render: unwritable output set" 1 "/nonexistent-ep/r.exr: cannot create" \
    "$HOSTBIN/lanetrace-native" render --res 8 --out /nonexistent-ep/r
ep_expect "run: unwritable reports of both paths" 1 "/nonexistent-ep/r.f32.json: cannot create" \
    "$SIMBIN/lanetrace" run --res 8 --num both --report /nonexistent-ep/r.json -q
ep_expect "run: unwritable depth EXR" 1 "/nonexistent-ep/x.exr: cannot create" \
    "$HOSTBIN/lanetrace-native" run --res 8 --depth /nonexistent-ep/x.exr -q
ep_expect "reproject: unwritable output after the work" 1 "/nonexistent-ep/x.exr: cannot create" \
    "$SIMBIN/lanetrace" reproject scenes/teapot.json --depth "$E/d.exr" --layers 2 --out /nonexistent-ep/x.exr
ep_expect "reproject: a layer the EXR does not have" 1 "no channel 'layer2.Z'" \
    "$SIMBIN/lanetrace" reproject scenes/teapot.json --depth "$E/d.exr" --layers 3
ep_expect "reproject: unwritable report" 1 "/nonexistent-ep/r.json" \
    "$SIMBIN/lanetrace" reproject scenes/teapot.json --depth "$E/d.exr" --report /nonexistent-ep/r.json
ep_expect "info: a directory" 1 "$E" "$SIMBIN/lanetrace" info "$E"
ep_expect "run: a directory as the scene" 1 "$E" "$SIMBIN/lanetrace" run "$E"
ep_expect "diff: directories" 1 "$E" "$SIMBIN/lanetrace" diff "$E" "$E"
ep_expect "info: the EXR whose attribute holds a newline (fuzz regression): no depth, in one line" 0 \
    "depth     none readable: .*Invalid size" \
    "$SIMBIN/lanetrace" info tests/fuzz/corpus/exr/regress-libmsg-newline.exr
ep_expect "reproject: the same EXR" 1 "regress-libmsg-newline.exr" \
    "$SIMBIN/lanetrace" reproject scenes/teapot.json --depth tests/fuzz/corpus/exr/regress-libmsg-newline.exr
head -c 300 "$E/d.exr" >"$E/cut.exr"
ep_expect "reproject: an EXR cut after 300 bytes" 1 "cut.exr" \
    "$SIMBIN/lanetrace" reproject scenes/teapot.json --depth "$E/cut.exr"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' | gzip -c | head -c 30 >"$E/cut.obj.gz"
ep_expect "render: a cut .obj.gz" 1 "cut.obj.gz: truncated gzip stream" \
    "$SIMBIN/lanetrace" render --mesh "$E/cut.obj.gz" --res 8 --out "$E/g"
check "render: nothing written for the cut .obj.gz" test ! -e "$E/g.exr"
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\0\0' >"$E/cut.ply"
ep_expect "shadows: a PLY cut in its body" 1 "cut.ply" \
    "$SIMBIN/lanetrace" shadows --mesh "$E/cut.ply" --res 8 --no-ref
ep_expect "run: a scene key holding a newline and an escape sequence: one line, shown as '?'" 1 \
    "unknown key 'co?lour?\[31m'" "$SIMBIN/lanetrace" run tests/fuzz/corpus/scene/regress-key-newline-escape.json
