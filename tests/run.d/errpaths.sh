# errpaths.sh - error paths of the CLIs that the other scripts do not take: outputs that cannot be
# written after the work is done, inputs of the wrong kind (a directory, a missing layer), cut or
# hostile inputs from the fuzz corpora. Each must exit 1 with one line naming the file; run a
# second time against the ASan + UBSan builds by tests/run_tests.sh, where LeakSanitizer makes a
# leak on any of these paths a failure. Sourced by tests/run_tests.sh (check/ok/ko, $B, $tmp,
# $SIMBIN, $HOSTBIN).
ep_expect() { # name, expected rc, pattern in output ("" for any), command...
    local name=$1 want=$2 pat=$3
    shift 3
    "$@" >"$tmp/ep.txt" 2>&1
    local rc=$?
    if [ "$rc" -eq "$want" ] && { [ -z "$pat" ] || grep -q -- "$pat" "$tmp/ep.txt"; }; then
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
# A member of an output set that its writer cannot create (the directory passes the set's check,
# the file cannot be made there: /proc as root, "not writable" otherwise): the message names the
# output, and its temporary once; it used to name "x.exr.tmp.<pid>" and "x.exr.tmp.<pid>.tmp.<pid>".
ep_once() { # name: the last ep_expect output names no temporary of a temporary
    local name=$1
    check "$name" sh -c "! grep -q '\\.tmp\\.[0-9]*\\.tmp\\.' '$tmp/ep.txt'"
}
ep_expect "render: an output its writer cannot create names the output once" 1 "/proc/lt-ep.exr: " \
    "$HOSTBIN/lanetrace-native" render --res 8 --out /proc/lt-ep -q
ep_once "render: no doubled temporary suffix in the message"
ep_expect "reproject: the same" 1 "/proc/lt-ep.exr: " \
    "$SIMBIN/lanetrace" reproject scenes/teapot.json --depth "$E/d.exr" --layers 2 --out /proc/lt-ep.exr -q
ep_once "reproject: no doubled temporary suffix in the message"
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

# Outputs that are not regular files are written through and stay what they are (a symbolic link
# to a file, a FIFO, a link to /dev/null); before, the temporary was renamed over them, which as
# root replaced /dev/null itself with a regular file.
echo keep >"$E/target.json"
ln -sf target.json "$E/link.json"
ep_expect "run: --report through a symbolic link" 0 "" \
    "$SIMBIN/lanetrace" run --res 8 --num f32 --no-ref --report "$E/link.json" -q
check "run: the link is still a link, its target the report" \
    sh -c "test -L '$E/link.json' && grep -q '\"machine\"' '$E/target.json'"
rm -f "$E/p.json" "$E/p.out"
mkfifo "$E/p.json"
(timeout 60 cat "$E/p.json" >"$E/p.out") &
ep_expect "run: --report into a FIFO" 0 "" \
    timeout 60 "$SIMBIN/lanetrace" run --res 8 --num f32 --no-ref --report "$E/p.json" -q
wait
check "run: the FIFO is still a FIFO and its reader got the report" \
    sh -c "test -p '$E/p.json' && grep -q '\"machine\"' '$E/p.out'"
ln -sf /dev/null "$E/null.exr"
ep_expect "reproject: --out a link to /dev/null" 0 "" \
    "$SIMBIN/lanetrace" reproject scenes/teapot.json --depth "$E/d.exr" --layers 2 --out "$E/null.exr" -q
check "reproject: the link and /dev/null are unchanged, no temporary left in $E" \
    sh -c "test -L '$E/null.exr' && test -c /dev/null && ! ls '$E' | grep -q '\\.tmp'"

# Output names that name no file: an empty prefix or a directory would write hidden ".exr" ...
ep_expect "render: an empty --out prefix" 2 "an empty name" \
    "$HOSTBIN/lanetrace-native" render --res 8 --out "" -q
ep_expect "render: --out a directory" 2 "a directory, not a path prefix" \
    "$HOSTBIN/lanetrace-native" render --res 8 --out "$E/" -q

# Scene files: a depth image's scene is not traced as the default teapot; a scene's outputs get
# the command line's name checks and may not overwrite an input; a \u0000 escape is refused.
printf '{"depth": "d.exr", "resolution": 16}\n' >"$E/depthonly.json"
ep_expect "run: a scene file with a depth image and no mesh" 1 'names no "mesh"' \
    "$HOSTBIN/lanetrace-native" run "$E/depthonly.json" --no-ref -q
ep_expect "render: the same" 1 'names no "mesh"' \
    "$HOSTBIN/lanetrace-native" render "$E/depthonly.json" --out "$E/do" -q
cp scenes/teapot.obj "$E/tp.obj"
printf '{"mesh": "tp.obj", "resolution": 16, "outputs": {"report": "tp.obj"}}\n' >"$E/outsame.json"
ep_expect "run: a scene whose report would overwrite its mesh" 1 "outputs.report" \
    "$SIMBIN/lanetrace" run "$E/outsame.json" --num f32 --no-ref -q
check "run: the mesh is intact" cmp -s scenes/teapot.obj "$E/tp.obj"
printf '{"mesh": "tp.obj", "resolution": 16, "outputs": {"csv": "x.png"}}\n' >"$E/outpng.json"
ep_expect "run: a scene's CSV named .png" 1 "this output is a .csv file" \
    "$SIMBIN/lanetrace" run "$E/outpng.json" --num f32 --no-ref -q
printf '{"mesh": "tp\\u0000x.obj", "resolution": 16}\n' >"$E/nul.json"
ep_expect "run: a scene string with \\u0000" 1 'u0000 (NUL)' \
    "$HOSTBIN/lanetrace-native" run "$E/nul.json" -q
printf '{"mesh": ".", "resolution": 16}\n' >"$E/dot.json"
ep_expect "run: a scene whose mesh is a directory" 1 "is a directory, not a regular file" \
    "$HOSTBIN/lanetrace-native" run "$E/dot.json" -q

# Inputs that are not regular files are refused before they are opened (a FIFO without a writer
# used to block info forever).
rm -f "$E/fifo.obj"
mkfifo "$E/fifo.obj"
ep_expect "info: a FIFO" 1 "FIFO" timeout 20 "$HOSTBIN/lanetrace-native" info "$E/fifo.obj"
ep_expect "run: a FIFO as the mesh" 1 "FIFO" \
    timeout 20 "$HOSTBIN/lanetrace-native" run --mesh "$E/fifo.obj" -q
ep_expect "diff: a directory" 1 "a directory, not a report file" \
    "$SIMBIN/lanetrace" diff "$E" "$E/target.json"
# The same for a mesh whose name is not .obj/.obj.gz (the importer's formats): lt_mesh_load opened
# it to measure its size, so a FIFO blocked run, render, shadows, pack and tune for ever and
# /dev/zero was called "empty file (0 bytes)".
rm -f "$E/fifo.ply" "$E/fifo-noext"
mkfifo "$E/fifo.ply" "$E/fifo-noext"
ep_expect "run: a FIFO named .ply as the mesh" 1 "fifo.ply: a device, FIFO or socket" \
    timeout 20 "$HOSTBIN/lanetrace-native" run --mesh "$E/fifo.ply" --res 8 --no-ref -q
ep_expect "shadows: a FIFO without an extension as the mesh" 1 "fifo-noext: a device, FIFO or socket" \
    timeout 20 "$SIMBIN/lanetrace" shadows --mesh "$E/fifo-noext" --res 8 --no-ref -q
ep_expect "tune: a FIFO as the input" 1 "fifo-noext: a device, FIFO or socket" \
    timeout 20 "$SIMBIN/lanetrace" tune "$E/fifo-noext" --plan "$E/fifo-plan"
# tune --merge reads DIR/plan.json and DIR/results/run-K.json: a plan.json that was a directory
# was a malloc of its "size" (2^63: AddressSanitizer allocation-size-too-big), a FIFO blocked the
# merge for ever, and a NUL byte was only "not a plan"
"$SIMBIN/lanetrace" tune scenes/teapot.obj --family object --machine lrb16 --res 16 \
    --plan "$E/tplan" -q >/dev/null 2>&1
check "errpaths: tune --plan for the merge checks" test -s "$E/tplan/plan.json"
for k in dir fifo nul; do rm -rf "$E/tplan-$k"; cp -r "$E/tplan" "$E/tplan-$k"; done
rm "$E/tplan-dir/plan.json" "$E/tplan-fifo/plan.json"
mkdir "$E/tplan-dir/plan.json"
mkfifo "$E/tplan-fifo/plan.json"
printf '{"tool":\0}' >"$E/tplan-nul/plan.json"
ep_expect "tune --merge: plan.json a directory" 1 "tplan-dir/plan.json: a directory, not a regular file" \
    timeout 20 "$SIMBIN/lanetrace" tune --merge "$E/tplan-dir"
ep_expect "tune --merge: plan.json a FIFO" 1 "tplan-fifo/plan.json: a device, FIFO or socket" \
    timeout 20 "$SIMBIN/lanetrace" tune --merge "$E/tplan-fifo"
ep_expect "tune --merge: plan.json with a NUL byte" 1 "tplan-nul/plan.json: a NUL byte at offset 8" \
    timeout 20 "$SIMBIN/lanetrace" tune --merge "$E/tplan-nul"
mkdir -p "$E/tplan/results/run-0.json"
ep_expect "tune --merge: a result that is a directory" 1 "run-0.json: a directory, not a regular file" \
    timeout 20 "$SIMBIN/lanetrace" tune --merge "$E/tplan"
# tune --out naming a regular file: the whole sweep ran, then the first output failed
# ("afile/front.csv: cannot create (Not a directory)"); now refused before anything is measured
: >"$E/tout-file"
ep_expect "tune --out a regular file: refused before measuring" 1 \
    "tout-file: exists and is not a folder (a regular file)" \
    timeout 60 "$SIMBIN/lanetrace" tune scenes/teapot.obj --family object --machine lrb16 --res 16 \
    --probe-res 0 --out "$E/tout-file"
check "tune --out a regular file: nothing measured (no search line)" \
    bash -c '! grep -q "^search" "$1"' _ "$tmp/ep.txt"
ep_expect "render: /dev/zero as the mesh is a device, not an empty file" 1 \
    "/dev/zero: a device, FIFO or socket" \
    timeout 20 "$HOSTBIN/lanetrace-native" render --mesh /dev/zero --res 8 --out "$E/z" -q

# run's outputs are one set (lt_outset), as render's and reproject's: a failing member leaves
# every previous output as it was. The report used to be replaced before the CSV (an existing
# directory) or a heatmap (a missing directory) failed.
rm -rf "$E/rs" # make test sources this part twice (release and ASan builds) into one $tmp
mkdir -p "$E/rs" "$E/rs/d.csv"
echo OLDREPORT >"$E/rs/r.json"
echo OLDCSV >"$E/rs/c.csv"
ep_expect "run: --csv onto a directory, the report kept as it was" 1 "d.csv: is a directory" \
    "$SIMBIN/lanetrace" run --res 8 --num f32 --no-ref --report "$E/rs/r.json" --csv "$E/rs/d.csv" -q
check "run: after the failed --csv the previous report is unchanged ($(head -c 20 "$E/rs/r.json"))" \
    grep -qx OLDREPORT "$E/rs/r.json"
ep_expect "run: --heatmap into a missing directory, the report and CSV kept" 1 \
    "none of the outputs written" \
    "$SIMBIN/lanetrace" run --res 8 --num f32 --no-ref --report "$E/rs/r.json" --csv "$E/rs/c.csv" \
    --heatmap /nonexistent-ep/h -q
check "run: after the failed --heatmap the report and the CSV are unchanged, no temporary left ($(ls "$E/rs" | tr '\n' ' '))" \
    bash -c "grep -qx OLDREPORT '$E/rs/r.json' && grep -qx OLDCSV '$E/rs/c.csv' && [ \$(ls -A '$E/rs' | wc -l) -eq 3 ]"
"$SIMBIN/lanetrace" run --res 8 --num both --no-ref --report "$E/rs/r.json" --csv "$E/rs/c.csv" \
    --depth "$E/rs/z.exr" --heatmap "$E/rs/h" -q >/dev/null 2>&1
rc=$?
check "run: every output written together when all succeed (rc $rc: two reports, CSV, depth, 8 heatmaps)" \
    bash -c "[ $rc -eq 0 ] && [ -s '$E/rs/r.q16.json' ] && [ -s '$E/rs/r.f32.json' ] && [ \$(wc -l <'$E/rs/c.csv') -eq 3 ] &&
        [ -s '$E/rs/z.exr' ] && [ \$(ls '$E/rs'/h.*.png '$E/rs'/h.*.exr | wc -l) -eq 8 ] && ! ls '$E/rs' | grep -q tmp"

# OBJ polygons: assimp triangulates them in time quadratic in their size, in this process.
awk 'BEGIN { print "v 0 0 0"; print "v 1 0 0"; print "v 0 1 0"; printf "f"; for (i = 0; i < 5000; i++) printf " 1 2 3"; print "" }' >"$E/longface.obj"
ep_expect "info: a face of 15,000 vertices" 1 "LT_MESH_MAX_FACE_VERTS 4096" \
    timeout 60 "$HOSTBIN/lanetrace-native" info "$E/longface.obj"
awk 'BEGIN { print "v 0 0 0"; print "v 1 0 0"; print "v 0 1 0"; for (f = 0; f < 70; f++) { printf "f"; for (i = 0; i < 1360; i++) printf " 1 2 3"; print "" } }' >"$E/manyfaces.obj"
ep_expect "info: 70 faces of 4,080 vertices" 1 "LT_MESH_MAX_POLY_WORK" \
    timeout 60 "$HOSTBIN/lanetrace-native" info "$E/manyfaces.obj"

# The quantised BVH with the automatic picks: s15.16 only, leaves of at most 15.
ep_expect "run: --structure bvhq with the defaults" 0 "numeric   kept   set by the structure bvhq" \
    "$SIMBIN/lanetrace" run --res 16 --structure bvhq --no-ref
ep_expect "run: --structure bvhq without the automatic picks" 0 "numeric   q16 only" \
    "$SIMBIN/lanetrace" run --res 16 --structure bvhq --no-ref --no-auto
ep_expect "render: --structure bvhq with the defaults" 0 "" \
    "$HOSTBIN/lanetrace-native" render --res 16 --structure bvhq --out "$E/bq" -q

# Flags: the eye and target of shadows, the TCP port of lt-stream.
ep_expect "shadows: the eye equals the target" 1 "equals the eye" \
    "$SIMBIN/lanetrace" shadows --mesh scenes/teapot.obj --eye 0,0,0 --target 0,0,0 --res 8 --no-ref
ep_expect "shadows: looking straight down the up vector" 1 "parallel to the up vector" \
    "$SIMBIN/lanetrace" shadows --mesh scenes/teapot.obj --eye 0,100,0 --target 0,0,0 --res 8 --no-ref
ep_expect "lt-stream: a TCP port above 65535" 1 "1..65535" \
    "$HOSTBIN/lt-stream" --tcp 127.0.0.1:70000 -q

# lt-stream on a source that is not a lanetrace stream: noise stops it (it is not silence, so
# --timeout never fired), and SIGINT ends it with the summary of what arrived.
ep_expect "lt-stream: /dev/zero stops after 64 MiB without a valid frame" 1 "no valid frame in the last" \
    timeout 120 "$HOSTBIN/lt-stream" --file /dev/zero -q
rm -f "$E/idle.fifo"
mkfifo "$E/idle.fifo"
(sleep 20 >"$E/idle.fifo") &
idle_writer=$!
"$HOSTBIN/lt-stream" --file "$E/idle.fifo" -q >"$E/int.out" 2>&1 &
lt_pid=$!
sleep 1
kill -INT "$lt_pid"
wait "$lt_pid"
int_rc=$?
kill "$idle_writer" 2>/dev/null
wait "$idle_writer" 2>/dev/null
check "lt-stream: SIGINT on an idle FIFO ends it with exit 1 and the summary (rc $int_rc)" \
    sh -c "test $int_rc -eq 1 && grep -q 'interrupted' '$E/int.out' && grep -q '^bytes' '$E/int.out'"
printf 'this is not a blob, just text long enough to pass the size check of its header words: %0200d\n' 0 >"$E/text.ltsb"
ep_expect "pack --in: a text file names its first word, not a bogus offset" 1 "its first word is 0x73696874" \
    "$HOSTBIN/lanetrace-native" pack --in "$E/text.ltsb"
# Wide views (corner directions 90 degrees or more apart, none of them zero): lt_sblob_open's
# zero-direction check measured the corners along the top-left direction and refused them, after
# pack had written the blob (exit 0); it measures along the centre direction now, and pack runs
# the check before writing. Each is written and traced on the host, as the targets trace it.
for wr in 13x4 64x16; do
    rm -f "$E/wide.ltsb"
    ep_expect "pack --res $wr (a view over 90 degrees corner to corner): written and traced" 0 "^image" \
        "$HOSTBIN/lanetrace-native" pack --res $wr --out "$E/wide.ltsb" --trace
    check "pack --res $wr: the blob is there and pack --in takes it" \
        bash -c "[ -s '$E/wide.ltsb' ] && '$HOSTBIN/lanetrace-native' pack --in '$E/wide.ltsb' >/dev/null 2>&1"
done
# 4096x1: 180 degrees corner to corner less 0.03; the integer camera words' rounding puts the
# corners behind the centre direction: refused before writing, the check and its reason named
rm -f "$E/wide.ltsb"
ep_expect "pack --res 4096x1 (a 180-degree view): refused, the target's check named" 1 \
    "4096x1 blob .* fails the target's check (item 0): .* 90 degrees or more from the centre" \
    "$HOSTBIN/lanetrace-native" pack --res 4096x1 --out "$E/wide.ltsb"
check "pack --res 4096x1: no blob written" test ! -e "$E/wide.ltsb"

# Depth EXRs whose display window is over LT_EXR_MAX_DIM (16384) per side (build/host/lt-exr-stereo:
# 24x16 of depth in a 20000x24 and a (2^30 - 1)-square display window). The reader reads the data
# window; reproject's and fwblob's default source camera spans the display window, and made a
# focal length of 9.3e8 pixels of it, silently. Now refused, naming the file, the size and the
# limit; info still describes the header and says so; --src-cam needs no display window.
"$B/host/lt-exr-stereo" widedisp "$E/widedisp.exr" && "$B/host/lt-exr-stereo" fardisp "$E/fardisp.exr"
check "errpaths: lt-exr-stereo writes the display-window test files" \
    test -s "$E/widedisp.exr" -a -s "$E/fardisp.exr"
ep_expect "reproject: a 20000-wide display window for the default camera" 1 \
    "widedisp.exr: display window 20000x24 outside 1..LT_EXR_MAX_DIM 16384; reproject's default source camera" \
    "$SIMBIN/lanetrace" reproject --depth "$E/widedisp.exr" --out "$E/wd.exr" -q
check "reproject: nothing written for it" test ! -e "$E/wd.exr"
ep_expect "reproject: a (2^30 - 1)-square display window" 1 \
    "fardisp.exr: display window 1073741823x1073741823 outside 1..LT_EXR_MAX_DIM 16384" \
    "$HOSTBIN/lanetrace-native" reproject --depth "$E/fardisp.exr" --out "$E/fd.exr" -q
ep_expect "reproject: the same with --src-cam (the display window is not used)" 0 "" \
    "$SIMBIN/lanetrace" reproject --depth "$E/fardisp.exr" --src-cam 20,20,12,8 --out "$E/fd.exr" -q
ep_expect "fwblob: the 20000-wide display window" 1 \
    "widedisp.exr: display window 20000x24 outside 1..LT_EXR_MAX_DIM 16384; fwblob" \
    "$HOSTBIN/lanetrace-native" fwblob --depth "$E/widedisp.exr" --crop 0,0,8,8 --out "$E/wd.blob"
ep_expect "info: the header described, the limit said (exit 0)" 0 \
    "^limits    .*widedisp.exr: display window 20000x24 outside 1..LT_EXR_MAX_DIM 16384; reproject" \
    "$HOSTBIN/lanetrace-native" info "$E/widedisp.exr"
check "info: the display window listed" grep -q "display window (0,0)-(19999,23)" "$tmp/ep.txt"
ep_expect "info --json: limit_error" 0 '"limit_error":".*fardisp.exr: display window 1073741823x' \
    "$HOSTBIN/lanetrace-native" info --json "$E/fardisp.exr"
# A data window wholly outside the display window (10^6 pixels off, lt-exr-stereo farwin): the
# default source camera spans the display window, so its principal point sat 10^6 pixels off the
# image and reproject (exit 0) and fwblob made a view of rays nearly parallel to the image plane,
# silently. Now refused, naming both windows; --src-cam needs no display window.
rm -f "$E/fw.exr" "$E/fw.blob" # the part runs twice into one $tmp (release and ASan builds)
"$B/host/lt-exr-stereo" farwin "$E/farwin.exr"
check "errpaths: lt-exr-stereo writes farwin.exr" test -s "$E/farwin.exr"
ep_expect "reproject: a data window outside the display window" 1 \
    "farwin.exr: data window (1000000,1000000)-(1000023,1000015) lies wholly outside the display window (0,0)-(31,23); reproject's default source camera" \
    "$SIMBIN/lanetrace" reproject --depth "$E/farwin.exr" --out "$E/fw.exr" -q
check "reproject: nothing written for it" test ! -e "$E/fw.exr"
ep_expect "reproject: the same with --src-cam" 0 "" \
    "$SIMBIN/lanetrace" reproject --depth "$E/farwin.exr" --src-cam 20,20,12,8 --out "$E/fw.exr" -q
ep_expect "fwblob: a data window outside the display window" 1 \
    "farwin.exr: data window (1000000,1000000)-(1000023,1000015) lies wholly outside the display window (0,0)-(31,23); fwblob" \
    "$HOSTBIN/lanetrace-native" fwblob --depth "$E/farwin.exr" --crop 0,0,8,8 --out "$E/fw.blob"
check "fwblob: nothing written for it" test ! -e "$E/fw.blob"
ep_expect "info: the limit said for it (exit 0)" 0 \
    "^limits    .*farwin.exr: data window (1000000,1000000)-(1000023,1000015) lies wholly outside" \
    "$HOSTBIN/lanetrace-native" info "$E/farwin.exr"
# Names read from an EXR (part, view, channel) printed as text: a view named "right\n\033[31m"
# (lt-exr-stereo ctlview) broke info's lines and sent the escape sequence to the terminal (info,
# reproject's source line, fwblob's summary); now shown with '?' for each control byte, as
# messages are (info --json escapes them).
"$B/host/lt-exr-stereo" ctlview "$E/ctlview.exr"
check "errpaths: lt-exr-stereo writes ctlview.exr" test -s "$E/ctlview.exr"
ep_expect "info: a view name with a newline and an escape sequence shown as '?'" 0 \
    "^part 1    name 'right??\[31m', view right??\[31m (default), " \
    "$HOSTBIN/lanetrace-native" info "$E/ctlview.exr"
check "info: no escape byte and no line broken by the name" \
    bash -c '! grep -q "$(printf "\033")" "$1" && ! grep -q "^\[31m" "$1"' _ "$tmp/ep.txt"
ep_expect "reproject: the view's name in the source line shown as '?'" 0 \
    "^source    .*(part 1, view right??\[31m)" \
    "$SIMBIN/lanetrace" reproject --depth "$E/ctlview.exr" --out "$E/ctl.exr"
ep_expect "fwblob: the view's name shown as '?'" 0 "view right??\[31m)" \
    "$HOSTBIN/lanetrace-native" fwblob --depth "$E/ctlview.exr" --crop 0,0,8,8 --out "$E/ctl.blob"
# The smallest image the quadtree takes is 1x1 (LT_QT_MAX_DIM's range is 1..16384: lt_qt.h,
# lt_reproject.c): a 1x1 render is reprojected, not refused.
"$HOSTBIN/lanetrace-native" render --res 1 --out "$E/one" -q >/dev/null 2>&1
ep_expect "reproject: a 1x1 depth image (the quadtree's minimum)" 0 "" \
    "$SIMBIN/lanetrace" reproject scenes/teapot.json --depth "$E/one.exr" --out "$E/one_rp.exr" -q
check "reproject: its 1x1 output written" test -s "$E/one_rp.exr"

# -q: "summary lines only". run -q printed the recommendation's three "auto" lines (render -q,
# reproject -q and shadows -q did not); the picks still apply and go to --report.
ep_expect "run -q: no auto lines, the result line" 0 "^result    f32" \
    "$SIMBIN/lanetrace" run --res 8 --no-ref -q
check "run -q (sim): no auto line" sh -c "! grep -q '^auto' '$tmp/ep.txt'"
ep_expect "run -q (native): the same" 0 "^result    f32" \
    "$HOSTBIN/lanetrace-native" run --res 8 --no-ref -q --report "$E/q.json"
check "run -q (native): no auto line; the picks in the report" \
    sh -c "! grep -q '^auto' '$tmp/ep.txt' && grep -q '\"auto\"' '$E/q.json'"
ep_expect "render -q: silent" 0 "" "$HOSTBIN/lanetrace-native" render --res 8 --out "$E/rq" -q
check "render -q: no auto line" sh -c "! grep -q '^auto' '$tmp/ep.txt'"
ep_expect "shadows -q: the result line" 0 "^result" \
    "$SIMBIN/lanetrace" shadows --mesh scenes/teapot.obj --res 8 --no-ref -q
check "shadows -q: no auto line" sh -c "! grep -q '^auto' '$tmp/ep.txt'"
ep_expect "run without -q: the auto lines (unchanged)" 0 "^auto      numeric" \
    "$HOSTBIN/lanetrace-native" run --res 8 --no-ref
