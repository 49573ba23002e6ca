# cli.sh - lanetrace command-line behaviour: help, exit codes, bad flags, missing and malformed
# files, scene validation, unwritable outputs, diff and info (meshes, EXR files, multi-part stereo
# EXR files: parts, views, --view, --part). Sourced by tests/run_tests.sh.
LT="$SIMBIN/lanetrace"
expect() { # name, expected rc, pattern in output ("" = any), command...
    local name=$1 want=$2 pat=$3
    shift 3
    "$@" >"$tmp/o.txt" 2>&1
    local rc=$?
    if [ "$rc" -eq "$want" ] && { [ -z "$pat" ] || grep -q -- "$pat" "$tmp/o.txt"; }; then
        ok "$name (rc $rc)"
    else
        ko "$name (rc $rc, want $want; output: $(head -c 300 "$tmp/o.txt"))"
    fi
}
expect "lanetrace --help" 0 "commands:" "$LT" --help
expect "lanetrace without a command: usage" 2 "usage:" "$LT"
expect "unknown command" 2 "unknown command" "$LT" frobnicate
for c in run info diff; do
    expect "lanetrace $c --help" 0 "usage: lanetrace $c" "$LT" $c --help
done
expect "run: unknown flag" 2 "unknown option" "$LT" run --frobnicate 1
expect "run: bad --num" 2 "expected q16" "$LT" run --num q8
expect "run: bad --res" 2 "expected WxH" "$LT" run --res 0
expect "run: unknown machine" 2 "z80" "$LT" run --machine z80 --res 4
expect "run: bad cache spec names it" 2 "63:8:64" "$LT" run --l1 63:8:64 --res 4
expect "run: missing mesh names the file" 1 "/nonexistent.obj" "$LT" run --mesh /nonexistent.obj
# Empty values: "--mesh ''" traced the default teapot (run, render, pack, reproject: exit 0),
# "--l1 ''" took the machine's cache over the scene file's, and an empty positional name said
# ": cannot open ..." naming nothing. Each is a usage error now.
expect "run: --mesh '' is refused, not the teapot" 2 "run: --mesh : an empty value; expected PATH" \
    "$LT" run --mesh '' --res 4 --no-ref
expect "render: --mesh ''" 2 "render: --mesh : an empty value" \
    "$HOSTBIN/lanetrace-native" render --mesh '' --res 4 --out "$tmp/em" -q
check "render: nothing written for --mesh ''" test ! -e "$tmp/em.exr"
expect "pack: --mesh ''" 2 "pack: --mesh : an empty value" \
    "$HOSTBIN/lanetrace-native" pack --mesh '' --out "$tmp/em.ltsb"
expect "shadows: --mesh ''" 2 "shadows: --mesh : an empty value" "$LT" shadows --mesh '' --res 4
expect "reproject: --depth ''" 2 "reproject: --depth : an empty value; expected FILE.exr" \
    "$LT" reproject --depth ''
expect "run: --l1 ''" 2 "run: --l1 : an empty value; expected S:W:B" "$LT" run --l1 '' --res 4
expect "run: --l2 ''" 2 "run: --l2 : an empty value" "$LT" run --l2 '' --res 4
expect "run: an empty scene file name" 2 "run: an empty argument ''" "$LT" run ''
expect "info: an empty file name" 2 "info: an empty argument ''" "$LT" info ''
expect "tune: an empty input name" 2 "tune: an empty argument ''" "$LT" tune ''
printf 'v 0 0 0\nv 1 0 0\nf 1 2 9\n' >"$tmp/bad.obj"
expect "run: malformed OBJ names the file" 1 "bad.obj" "$LT" run --mesh "$tmp/bad.obj"
expect "run: missing scene file" 1 "nope.json" "$LT" run "$tmp/nope.json"
sc() { printf '%s\n' "$1" >"$tmp/s.json"; }
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "colour": 1}'
expect "scene: unknown key named" 1 "unknown key 'colour'" "$LT" run "$tmp/s.json"
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "camera": {"eye": [0,0,5], "target": [0,0,0], "fov": 30}}'
expect "scene: unknown nested key named with its path" 1 "camera.fov" "$LT" run "$tmp/s.json"
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "resolution": [8, 8], "resolution": [16, 16]}'
expect "scene: a duplicate key is an error (cJSON took the first silently)" 1 "s.json: key 'resolution' appears more than once" "$LT" run "$tmp/s.json"
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "camera": {"eye": [0,0,5], "target": [0,0,0], "eye": [1,1,1]}}'
expect "scene: a duplicate nested key named with its path" 1 "key 'camera.eye' appears more than once" "$LT" run "$tmp/s.json"
# A NUL byte ended the scene file for the parser: '{"mesh": ...}\0{"junk"' traced, exit 0.
printf '{"mesh": "%s/scenes/teapot.obj", "resolution": 4}\0{"bogus": 1}' "$PWD" >"$tmp/nul.json"
expect "scene: a raw NUL byte is refused with its place" 1 "nul.json: a NUL byte at line 1, column" \
    "$LT" run "$tmp/nul.json" --no-ref
# Nesting beyond cJSON's limit was called "not valid JSON"; it is valid, just deeper than 1000.
awk 'BEGIN { printf "{\"x\": "; for (i = 0; i < 1100; i++) printf "["; for (i = 0; i < 1100; i++) printf "]"; print "}" }' >"$tmp/deep.json"
expect "scene: nesting past CJSON_NESTING_LIMIT says so" 1 \
    "deep.json: arrays and objects nested deeper than 1000 levels at line 1, column .*CJSON_NESTING_LIMIT" \
    "$LT" run "$tmp/deep.json"
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "caches": {"l1": "63:8:64"}}'
expect "scene: a bad cache geometry names the file and key (sim)" 1 "s.json: 'caches.l1': cache spec \"63:8:64\": sets 63 is not a power of two" "$LT" run "$tmp/s.json" --res 8 -q
expect "scene: ... and the native build refuses it too (it ignored caches)" 1 "s.json: 'caches.l1'" "$HOSTBIN/lanetrace-native" run "$tmp/s.json" --res 8 -q
expect "native build: a bad --l1 is refused like in the simulator" 2 "63:8:64" "$HOSTBIN/lanetrace-native" run --l1 63:8:64 --res 8 -q
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "resolution": "big"}'
expect "scene: wrong type" 1 "'resolution' must be" "$LT" run "$tmp/s.json"
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "resolution": [64, 9000]}'
expect "scene: out of range" 1 "out of range" "$LT" run "$tmp/s.json"
sc '{"mesh": "missing.obj"}'
expect "scene: missing file resolved against the scene's folder" 1 "missing.obj' not found" "$LT" run "$tmp/s.json"
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "numeric": "q8"}'
expect "scene: bad choice lists the choices" 1 "q16, f32, both" "$LT" run "$tmp/s.json"
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj",'
expect "scene: broken JSON gives line and column" 1 "at line [0-9]*, column [0-9]*" "$LT" run "$tmp/s.json"
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "camera": {"eye": [0,0,5], "target": [0,0,5]}}'
expect "scene: degenerate camera" 1 "no view direction" "$LT" run "$tmp/s.json"
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "camera": {"eye": [0,1,40], "target": [0,1,0], "fov_y_deg": 30}, "resolution": 16, "numeric": "q16"}'
expect "scene: explicit camera traces" 0 "same triangle" "$LT" run "$tmp/s.json" -q
expect "flags override the scene (--res)" 0 "of 64 rays" "$LT" run "$tmp/s.json" --res 8 -q
expect "unwritable report: exit 1, names it" 1 "/nonexistent-dir/r.json" \
    "$LT" run --res 4 --num q16 --report /nonexistent-dir/r.json -q
check "no temporary left behind" bash -c "! ls /nonexistent-dir 2>/dev/null"
"$LT" run --res 16 --num q16 --report "$tmp/a.json" --csv "$tmp/a.csv" -q >/dev/null 2>&1
"$LT" run --res 16 --num q16 --machine mcu-m4 --report "$tmp/b.json" -q >/dev/null 2>&1
check "csv written with header and one row" bash -c "[ \$(wc -l <'$tmp/a.csv') -eq 2 ] && head -1 '$tmp/a.csv' | grep -q total_cycles"
expect "diff names moved counters" 0 "total_cycles" "$LT" diff "$tmp/a.json" "$tmp/b.json"
expect "diff of a report with itself: nothing moved" 0 "^0 of" "$LT" diff "$tmp/a.json" "$tmp/a.json" --threshold 0
expect "diff: missing report" 1 "nope.json" "$LT" diff "$tmp/a.json" "$tmp/nope.json"
expect "diff --json" 0 '"changed"' "$LT" diff "$tmp/a.json" "$tmp/b.json" --json
expect "info on a mesh" 0 "992 triangles" "$LT" info scenes/teapot.obj
expect "info --json" 0 '"triangles":992' "$LT" info scenes/teapot.obj --json
expect "run --native hands over to the native build" 0 "native" "$LT" run --native --res 8 --num f32
# --rays single: each ray alone (bvh: the 8-wide tree's walk and leaf blocks), the same image hashes
# as the packets in both paths, simulated (its own cycle report) and native, and on a structure
# without a single-ray walk (kd: one-lane packets)
for rs in "" "--native"; do
    for st in bvh kd; do
        hp=$("$LT" run scenes/teapot.json --res 48 --num both --structure $st --no-ref $rs 2>/dev/null | grep '^result' | paste -sd ' ')
        hs=$("$LT" run scenes/teapot.json --res 48 --num both --structure $st --no-ref $rs --rays single 2>/dev/null | grep '^result' | paste -sd ' ')
        check "run ${rs:+$rs }--structure $st --rays single: both paths' hashes equal the packets' ($hs)" \
            test -n "$hp" -a "$hp" = "$hs"
        # --rays wide: the packets through the 8-wide tree (bvh; kd: as packet)
        hw=$("$LT" run scenes/teapot.json --res 48 --num both --structure $st --no-ref $rs --rays wide 2>/dev/null | grep '^result' | paste -sd ' ')
        check "run ${rs:+$rs }--structure $st --rays wide: both paths' hashes equal the packets' ($hw)" \
            test -n "$hp" -a "$hp" = "$hw"
    done
done
expect "run --rays wide prints the wide-packet cycle report" 0 "wide-tree packets" "$LT" run scenes/teapot.json --res 16 --num q16 --rays wide --no-ref
# render --rays wide: primary, shadow and peel packets through the 8-wide tree, the same images
for rw in packet wide; do
    "$HOSTBIN/lanetrace-native" render scenes/teapot.json --res 90x70 --layers 2 --rays $rw \
        --out "$tmp/rw_$rw" -q >/dev/null 2>&1
done
check "render --rays wide (native): the same EXR and PNG as --rays packet (primary, shadows, 2 layers)" \
    bash -c "cmp -s '$tmp/rw_packet.exr' '$tmp/rw_wide.exr' && cmp -s '$tmp/rw_packet.png' '$tmp/rw_wide.png'"
expect "run --rays single prints the single-ray cycle report" 0 "single rays (counted" "$LT" run scenes/teapot.json --res 16 --num q16 --rays single --no-ref
expect "run --rays bogus: usage error" 2 "expected packet, single or wide" "$LT" run --res 8 --rays bogus
mkdir -p "$tmp/plots"
B=$B SWEEP_RES=8 tools/plots/sweep.sh "$tmp/plots/sweep.csv" >/dev/null 2>&1 &&
    tools/plots/plots.sh "$tmp/plots/sweep.csv" "$tmp/plots" >/dev/null 2>&1
check "make plots pipeline: sweep CSV -> 4 PNG plots" bash -c "[ \$(ls '$tmp'/plots/*.png | wc -l) -eq 4 ]"
expect "run --depth writes an EXR with Z and id per path" 0 "" "$LT" run --res 16 --num both --depth "$tmp/d.exr" -q
expect "info on the depth EXR lists its channels" 0 "q16.Z(FLOAT)" "$LT" info "$tmp/d.exr"
expect "run --heatmap writes PNG and EXR per path" 0 "" "$LT" run --res 16 --num q16 --heatmap "$tmp/h" -q
check "heatmap files exist (cycles and steps)" test -s "$tmp/h.q16.png" -a -s "$tmp/h.q16.exr" -a -s "$tmp/h.q16.steps.png"
# the per-pixel cycles and steps are read only when --heatmap asks (lt_frame_t.heat): the maps
# must still vary over the image (a map of zeros has one colour besides the legend's ~44)
"$LT" run --res 32 --num q16 --no-ref --heatmap "$tmp/h32" -q >/dev/null 2>&1
hc=$(python3 tools/png_colours.py "$tmp/h32.q16.png" 2>/dev/null)
hs=$(python3 tools/png_colours.py "$tmp/h32.q16.steps.png" 2>/dev/null)
check "run --heatmap at 32x32: the cycle and step maps vary ($hc and $hs distinct colours, legend included; >= 55)" \
    bash -c "[ '${hc:-0}' -ge 55 ] && [ '${hs:-0}' -ge 55 ]"
expect "info on the heatmap EXR" 0 "cycles(FLOAT)" "$LT" info "$tmp/h.q16.exr"
# info decides EXR vs mesh by the first bytes, not the name, and says what it found
cp "$tmp/d.exr" "$tmp/depth.bin"
expect "info: an EXR named .bin is read as OpenEXR (magic bytes)" 0 "detected  OpenEXR (magic bytes 76 2f 31 01) by its content (its name says otherwise)" "$LT" info "$tmp/depth.bin"
cp scenes/teapot.obj "$tmp/teapot.exr"
expect "info: OBJ text named .exr is read as a mesh" 0 "detected  OBJ text by its content (its name says otherwise)" "$LT" info "$tmp/teapot.exr"
expect "info on a directory: one line, not a size overflow" 1 "is a directory, not a file" "$LT" info "$tmp"
cp "$tmp/d.exr" "$tmp/a \"q\" \\ b.exr"
"$LT" info "$tmp/a \"q\" \\ b.exr" --json >"$tmp/infoj.json" 2>&1
check "info --json escapes the path (a quote and a backslash in the name): valid JSON" \
    python3 -c "import json,sys; j=json.load(open(sys.argv[1])); sys.exit(0 if j['file'].endswith('a \"q\" \\\\ b.exr') and j['detected'].startswith('OpenEXR') else 1)" "$tmp/infoj.json"
if [ -f ../shared/depth/beachball_singlepart.0001.exr ]; then
    expect "info on the shared beachball EXR: 20 channels, Z stats" 0 "mean 9.385" \
        "$LT" info ../shared/depth/beachball_singlepart.0001.exr
    expect "info on the shared deep EXR: front-most sample" 0 "front-most" \
        "$LT" info ../shared/depth/v2_LowResLeftView_Trunks_deep.exr
elif [ "${CI:-}" = "true" ]; then
    ko "shared depth files missing under CI"
else
    echo "SKIP info on shared EXR files: ../shared/depth not found"
fi
# a multi-part stereo EXR (build/host/lt-exr-stereo: part 0 left, part 1 right, multiView right
# left, so the default view is part 1; Z 2.. for the left eye, 4.. for the right)
"$B/host/lt-exr-stereo" stereo "$tmp/stereo.exr" && "$B/host/lt-exr-stereo" split "$tmp/split.exr"
check "lt-exr-stereo writes the multi-part test files" test -s "$tmp/stereo.exr" -a -s "$tmp/split.exr"
expect "info on a stereo EXR names the views and the default" 0 "stereo.exr: OpenEXR, 2 parts, views right left (default right)" \
    "$LT" info "$tmp/stereo.exr"
expect "info lists part 0 with its name, view, storage and windows" 0 \
    "^part 0    name 'left', view left, scanline, zip, data window (2,3)-(25,18), display window (0,0)-(31,23)" \
    "$LT" info "$tmp/stereo.exr"
expect "info lists part 1, the default view" 0 "^part 1    name 'right', view right (default), scanline" \
    "$LT" info "$tmp/stereo.exr"
expect "info lists each part's channels" 0 "^channels  4: A(HALF) B(HALF) G(HALF) R(HALF)$" "$LT" info "$tmp/split.exr"
expect "info: depth statistics of the default view say their part (right eye)" 0 \
    "^depth     part 1, view right, channel Z: 384 pixels with depth, 0 holes .* min 4 max 5.90625" \
    "$LT" info "$tmp/stereo.exr"
expect "info --view left: the left eye" 0 "^depth     part 0, view left, channel Z: .* min 2 max 3.90625" \
    "$LT" info "$tmp/stereo.exr" --view left
expect "info --part 1: the right eye" 0 "^depth     part 1, view right, channel Z: .* min 4 max" \
    "$LT" info "$tmp/stereo.exr" --part 1
expect "info --view center: exit 1, the views listed" 1 "no view 'center'; views: right left; default right" \
    "$LT" info "$tmp/stereo.exr" --view center
expect "info --part 2: exit 1, the part count named" 1 "part 2 out of range: the file has 2 parts (0..1)" \
    "$LT" info "$tmp/stereo.exr" --part 2
expect "info --part of a colour-only part: exit 1, no depth channel there" 1 "no depth channel (Z, depth, \*.Z) in part 2;" \
    "$LT" info "$tmp/split.exr" --part 2
expect "info --view on a mesh: usage error" 2 "select in an EXR file" "$LT" info scenes/teapot.obj --view left
"$LT" info "$tmp/stereo.exr" --json >"$tmp/infost.json" 2>&1
check "info --json lists the parts with views and channels, the views, and the depth's part" \
    python3 -c "
import json, sys
j = json.load(open(sys.argv[1])); pl = j['part_list']; d = j['depth']
sys.exit(0 if j['parts'] == 2 and j['views'] == ['right', 'left'] and j['default_view'] == 'right'
         and [p['view'] for p in pl] == ['left', 'right'] and [p['name'] for p in pl] == ['left', 'right']
         and [c['name'] for c in pl[1]['channels']] == ['A', 'B', 'G', 'R', 'Z']
         and d['part'] == 1 and d['view'] == 'right' and d['min'] == 4 else 1)" "$tmp/infost.json"
# every structure traces the same image: compared with the chunks (brute force over boxes)
"$HOSTBIN/lanetrace-native" run --structure chunks --num both --res 32 -q >"$tmp/chunks.txt" 2>&1
for st in bvh bvhq; do
    nm=both; [ $st = bvhq ] && nm=q16
    "$HOSTBIN/lanetrace-native" run --structure $st --num $nm --res 32 -q >"$tmp/n_$st.txt" 2>&1
    "$LT" run --structure $st --num $nm --res 32 -q >"$tmp/s_$st.txt" 2>&1
    a=$(grep "result    q16" "$tmp/n_$st.txt"); b=$(grep "result    q16" "$tmp/s_$st.txt")
    c=$(grep "result    q16" "$tmp/chunks.txt")
    check "structure $st: host = sim = chunks result ($a)" test -n "$a" -a "$a" = "$b" -a "$a" = "$c"
done
expect "render writes EXR + PNGs with depth peels" 0 "depth peels" "$LT" render --res 32 --layers 3 --out "$tmp/rd"
check "render PNGs exist (shaded, depth, normals, ids)" bash -c "ls '$tmp'/rd.png '$tmp'/rd.depth.png '$tmp'/rd.normals.png '$tmp'/rd.ids.png >/dev/null"
expect "render EXR has Z, normals, shaded and 3 layers" 0 "layer2.Z(FLOAT)" "$LT" info "$tmp/rd.exr"
expect "render --layers with chunks: usage error" 2 "hierarchy" "$LT" render --res 8 --layers 2 --structure chunks --out "$tmp/rc"
expect "render without --out: usage" 2 "--out" "$LT" render --res 8
expect "render --help" 0 "usage: lanetrace render" "$LT" render --help
for st in kd grid; do
    "$LT" run --structure $st --num both --res 32 -q >"$tmp/s_$st.txt" 2>&1
    a=$(grep "result    q16" "$tmp/s_$st.txt"); c=$(grep "result    q16" "$tmp/chunks.txt")
    check "structure $st (sim) = chunks result ($a)" test -n "$a" -a "$a" = "$c"
done
expect "render with the kd-tree and depth peels" 0 "depth peels" "$LT" render --structure kd --layers 2 --res 16 --out "$tmp/kdr"
expect "render --json lists the files" 0 "\"shadow_rays\"" "$LT" render --res 8 --json --out "$tmp/rj"
expect "render (sim) prints the cycle report of primary, shadow and peel rays" 0 "cycles/ray" "$LT" render --structure grid --layers 2 --res 16 --out "$tmp/gr" --report "$tmp/gr.json"
check "render --report JSON counts primary + shadow + peel rays" python3 -c "
import json,sys; r=json.load(open('$tmp/gr.json')); x=r.get('extra', r)
print('render report rays', r['rays'], 'primary', x['primary_rays'], 'shadow', x['shadow_rays'], 'peel', x['peel_rays'])
sys.exit(0 if x['primary_rays']==256 and x['peel_rays']>0 and x['shadow_rays']>0 else 1)"
expect "render --report in the native build: usage error" 2 "simulator build" "$HOSTBIN/lanetrace-native" render --res 8 --out "$tmp/rn" --report "$tmp/rn.json"
# a scene whose dynamic range exceeds s15.16: one 2e6-unit triangle and ten 1e-3-unit ones
{
    echo "v -1000000 0 0"; echo "v 1000000 0 0"; echo "v 0 1000000 0"
    for i in 0 1 2 3 4 5 6 7 8 9; do echo "v $i 0 1"; echo "v $i.001 0 1"; echo "v $i 0.001 1"; done
    echo "f 1 2 3"
    for i in 0 1 2 3 4 5 6 7 8 9; do b=$((4 + 3 * i)); echo "f $b $((b + 1)) $((b + 2))"; done
} >"$tmp/wide.obj"
# by default the recommendation picks float32 with the reason (s15.16 cannot represent it);
# not asked for s15.16 otherwise (--num both, --no-auto: render's and shadows' q16): s15.16 is
# dropped with the reason on one line and float32 runs; asked for (--num q16, the scene file's
# "numeric": "q16"): refused naming the file and the limit
expect "run: a scene s15.16 cannot represent: the recommendation runs f32 and says why" 0 "auto      numeric   f32    not representable in s15.16: 10 of 11 triangles collapse .*limit 0.1%" "$LT" run --mesh "$tmp/wide.obj" --res 8
check "run: the pick traced f32 only" bash -c "grep -q 'result    f32' '$tmp/o.txt' && ! grep -q 'result    q16' '$tmp/o.txt'"
expect "run --num both: a scene s15.16 cannot represent runs on f32, the reason on one line" 0 "run: numeric path q16 (s15.16) dropped, running f32: .*wide.obj: cannot be represented in s15.16: 10 of 11 triangles.*limit 0.1%" "$LT" run --mesh "$tmp/wide.obj" --res 8 -q --num both
check "run --num both: the fallback traced f32 only" grep -q "result    f32" "$tmp/o.txt"
check "run --num both: ... and not q16" test "$(grep -c 'result    q16' "$tmp/o.txt")" -eq 0
expect "render: a scene s15.16 cannot represent: the recommendation renders f32 and says why" 0 "auto      numeric   f32    not representable in s15.16" "$LT" render --mesh "$tmp/wide.obj" --res 8 --out "$tmp/widea"
"$LT" run --mesh "$tmp/wide.obj" --res 8 --no-ref --num both --json >"$tmp/wide.json" 2>/dev/null
check "run --json records the pick and the reason (numeric_pick)" python3 -c "
import json,sys; r=json.load(open('$tmp/wide.json')); x=r[0].get('extra', r[0]); p=x['numeric_pick']
sys.exit(0 if len(r)==1 and p['path']=='f32' and p['dropped']=='q16' and 'cannot be represented in s15.16' in p['reason'] else 1)"
expect "run --num q16: a scene s15.16 cannot represent is refused naming the file and the limit" 1 "wide.obj: cannot be represented in s15.16: 10 of 11 triangles.*limit 0.1%" "$LT" run --mesh "$tmp/wide.obj" --res 8 -q --num q16
printf '{"mesh": "%s", "numeric": "q16", "resolution": [8, 8]}\n' "$tmp/wide.obj" >"$tmp/wideq.json"
expect "run: the scene file's \"numeric\": \"q16\" is asked for too: refused" 1 "cannot be represented in s15.16" "$LT" run "$tmp/wideq.json" -q
expect "render --no-auto: the same fallback to f32" 0 "render: numeric path q16 (s15.16) dropped, running f32 (float32): .*cannot be represented in s15.16" "$LT" render --mesh "$tmp/wide.obj" --res 8 --out "$tmp/wide" --json --no-auto
check "render --json records the pick" grep -q '"dropped":.*"q16"' "$tmp/o.txt"
check "render: the fallback wrote its images" test -s "$tmp/wide.exr"
expect "render --num q16: refused" 1 "cannot be represented in s15.16" "$LT" render --mesh "$tmp/wide.obj" --res 8 --out "$tmp/wideq" --num q16
check "render --num q16: nothing written for the unrepresentable scene" test ! -e "$tmp/wideq.exr"
expect "render: the scene file's \"numeric\": \"q16\": refused" 1 "cannot be represented in s15.16" "$LT" render "$tmp/wideq.json" --out "$tmp/wideq"
expect "run --num f32 traces the same scene" 0 "result    f32" "$LT" run --mesh "$tmp/wide.obj" --res 8 -q --num f32 --no-ref
expect "info says which paths can represent a mesh" 0 "10 of 11 non-degenerate triangles collapse.*NOT representable" "$HOSTBIN/lanetrace-native" info "$tmp/wide.obj"
check "info recommends f32 for it with the collapse counts" grep -q "numeric    f32     not representable in s15.16: 10 of 11 triangles collapse" "$tmp/o.txt"
check "info recommends chunks for its 11 triangles" grep -q "structure  chunks  11 triangles (<= 256)" "$tmp/o.txt"
expect "info on the teapot recommends a bvh from its triangle count" 0 "structure  bvh     992 triangles (> 256)" "$HOSTBIN/lanetrace-native" info scenes/teapot.obj
"$HOSTBIN/lanetrace-native" info scenes/teapot.obj --json >"$tmp/infor.json" 2>&1
check "info --json has a recommend object (numeric, structure, leaf: pick and reason)" python3 -c "
import json,sys; r=json.load(open('$tmp/infor.json'))['recommend']
sys.exit(0 if r['q16_representable'] and r['structure']['pick']=='bvh' and r['leaf']['pick']=='16' and r['numeric']['pick']=='f32' and '992' in r['structure']['reason'] else 1)"
expect "shadows: the same fallback to f32" 0 "shadows: numeric path q16 (s15.16) dropped, running f32 (float32): .*wide.obj: cannot be represented in s15.16" "$LT" shadows --mesh "$tmp/wide.obj" --res 8 --no-ref -q
check "shadows: the fallback's result is f32" grep -q "result    f32" "$tmp/o.txt"
expect "shadows --num q16: refused" 1 "wide.obj: cannot be represented in s15.16" "$LT" shadows --mesh "$tmp/wide.obj" --res 8 --no-ref --num q16
expect "lt-agree: the same error (it traces s15.16)" 1 "wide.obj: cannot be represented in s15.16" "$B/host/lt-agree" "$tmp/wide.obj" --res 8
# a unit triangle beside a 1e30 one: centring in double alone erases it (range above 2^53); the
# check measures area on the file's coordinates, so it counts as collapsed (it was "representable")
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1e30 0 0\nv 0 1e30 0\nv 0 0 1e30\nf 1 2 3\nf 4 5 6\n' >"$tmp/huge.obj"
expect "info: a unit triangle beside a 1e30 one is not representable in s15.16" 0 "1 of 2 non-degenerate triangles collapse.*NOT representable" "$HOSTBIN/lanetrace-native" info "$tmp/huge.obj"
expect "run: ... and refused for s15.16" 1 "huge.obj: cannot be represented in s15.16: 1 of 2" "$LT" run --mesh "$tmp/huge.obj" --res 8 -q --num q16
expect "lt-agree --help exits 0 with the options" 0 "usage: lt-agree MESH" "$B/host/lt-agree" --help
expect "lt-agree without a mesh: usage error" 2 "no mesh given" "$B/host/lt-agree"
expect "lt-agree --res 2: the range named" 2 "--res 2: out of range; expected 4..4096" "$B/host/lt-agree" scenes/teapot.obj --res 2
# a slow run prints a rate in a unit that fits (it printed "0.00 Mrays/s")
expect "run on mcu-m4 (grid, s15.16): the report's rate in krays/s" 0 "cycles/ray, [0-9.]* krays/s at 168 MHz" "$LT" run scenes/teapot.json --res 16 --machine mcu-m4 --num q16 --structure grid --no-ref
check "... and no '0.00 Mrays/s' anywhere" bash -c "! grep -q '0\.00 Mrays/s' '$tmp/o.txt'"
# output names follow their kind (render --out a.png wrote a.png.exr, reproject --out x.png an EXR
# named x.png); run --report with both paths puts the path before the extension
expect "render --out a.png: a prefix takes no image extension" 2 "render: --out $tmp/a.png: a path prefix" "$LT" render --res 8 --out "$tmp/a.png"
check "... and nothing is written" test ! -e "$tmp/a.png.exr" -a ! -e "$tmp/a.png"
expect "reproject --out x.png: the EXR output refuses a .png name" 2 "this output is a .exr file; its name ends in '.png'" "$LT" reproject scenes/teapot.json --depth "$tmp/d.exr" --out "$tmp/x.png"
expect "run --depth d.png: refused" 2 "--depth $tmp/d.png: this output is a .exr file" "$LT" run --res 8 --depth "$tmp/d.png"
expect "shadows --png s.exr: refused" 2 "--png $tmp/s.exr: this output is a .png file" "$LT" shadows --mesh scenes/teapot.obj --res 8 --png "$tmp/s.exr"
expect "run --report r.json with both paths" 0 "report    $tmp/rb.q16.json" "$LT" run scenes/teapot.json --res 8 --report "$tmp/rb.json"
check "... writes r.q16.json and r.f32.json" test -s "$tmp/rb.q16.json" -a -s "$tmp/rb.f32.json"
# messages that name the real problem (each misled before: a size overflow for a directory,
# "camera.up is parallel" for a far eye or a tiny up, "not finite" for a float32 overflow, the
# light centre blamed for its size, an API constant for a flag)
mkdir -p "$tmp/adir"
expect "a directory as the scene file" 1 "adir: not a regular file (a directory)" "$LT" run "$tmp/adir"
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "camera": {"eye": [1e300, 0, 0], "target": [0, 0, 0]}}'
expect "scene: an eye 1e300 away is named as out of range, not 'up is parallel'" 1 "camera eye is .* scene radii from the centre" "$LT" run "$tmp/s.json" --res 8 -q
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "camera": {"eye": [0, 0, 50], "target": [0, 0, 0], "up": [0, 1e-300, 0]}}'
expect "scene: a tiny but valid up vector works" 0 "result    f32" "$LT" run "$tmp/s.json" --res 8 -q --no-ref
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "camera": {"eye": [1e308, 0, 0], "target": [-1e308, 0, 0]}}'
expect "scene: an eye-target distance that overflows is named" 1 "overflows a double" "$LT" run "$tmp/s.json" --res 8 -q
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "camera": {"eye": [0, 0, 50], "target": [0, 0, 0], "up": [0, 0, 3]}}'
expect "scene: an up along the view is parallel, with both vectors" 1 "'camera.up' \[0, 0, 3\] is parallel to the view direction" "$LT" run "$tmp/s.json" --res 8 -q
printf 'v 0 0 0\nv 1e200 0 0\nv 0 1 0\nf 1 2 3\n' >"$tmp/big.obj"
expect "OBJ: 1e200 overflows float32 (not 'not finite')" 1 "big.obj: line 2: vertex coordinate 1 '1e200' overflows float32" "$LT" run --mesh "$tmp/big.obj" --res 8 -q
expect "shadows: a 1e9-wide light blames its size, not its centre" 1 "light size 1e+09" "$LT" shadows --mesh scenes/teapot.obj --res 8 --light 0,20,0,1e9 --no-ref
expect "run: counts next to percentages on the accuracy line" 0 "same triangle 100.000% (64 of 64 pixels, 0 differ)" "$LT" run scenes/teapot.json --res 8 --num q16
if [ -f ../shared/depth/v2_LowResLeftView_Trunks_deep.exr ]; then
    expect "reproject on a deep EXR names the flag" 1 "lanetrace reproject --deep-front" "$LT" reproject --depth ../shared/depth/v2_LowResLeftView_Trunks_deep.exr
    expect "reproject --deep-front reads it (front-most sample)" 0 "source    ../shared/depth/v2_LowResLeftView_Trunks_deep.exr: 1024x435" "$HOSTBIN/lanetrace-native" reproject --depth ../shared/depth/v2_LowResLeftView_Trunks_deep.exr --deep-front --move 0.01,0,0
fi
# render's outputs are one set: all new or all old (a failure part-way left a mix); names too
# long are refused (a fixed buffer cut them, so all five outputs overwrote one file)
"$LT" render --res 16 --out "$tmp/set" -q >/dev/null 2>&1
sum0=$(cat "$tmp"/set.exr "$tmp"/set*.png | md5sum)
expect "render: a failing --report leaves the previous outputs as they were" 1 "none of the outputs written" \
    "$LT" render --res 24 --out "$tmp/set" -q --report /nonexistent-dir/r.json
check "... the EXR and PNGs unchanged, no temporary left" \
    bash -c "[ \"\$(cat '$tmp'/set.exr '$tmp'/set*.png | md5sum)\" = '$sum0' ] && ! ls '$tmp' | grep -q '\.tmp\.'"
long=$(printf 'x%.0s' $(seq 1 4100))
expect "render: an --out over the path limit is refused, not cut" 2 "the output names would be longer than" \
    "$LT" render --res 8 --out "$tmp/$long" -q
# a render too large for the memory fails at once, naming the size (it allocated the peels after
# tracing); the address-space limit stands in for a small machine
t0=$(date +%s)
# (not in the sanitizer pass: ASan reserves more address space than the limit allows)
[ "$SIMBIN" != "$B/asan" ] &&
expect "render 8192^2 x 16 layers under a 2 GiB limit: fails before tracing, names the need" 1 \
    "needs 28.00 GiB for its images; 2.00 GiB are available (the address-space limit" \
    bash -c "ulimit -v 2097152 && exec '$LT' render --res 8192 --layers 16 --out '$tmp/huge' -q"
[ "$SIMBIN" != "$B/asan" ] && check "... within 10 s, nothing written" bash -c "[ \$((\$(date +%s) - $t0)) -lt 10 ] && [ ! -e '$tmp/huge.exr' ]"
# ---- option parsing (host/cli/lt_opt): values are read whole, numbers must be finite, ranges are
# named; each of these was accepted before (atoi read "1e9" as 1, sscanf ignored trailing text,
# NaN passed the range checks, --tol had none)
expect "render --layers 1e9 is refused, not read as 1" 2 "render: --layers 1e9: not an integer; expected 1..16" \
    "$LT" render --res 8 --layers 1e9 --out "$tmp/opt_l"
check "render --layers 1e9: nothing written" test ! -e "$tmp/opt_l.exr"
expect "render --light 1,2,3xyz: trailing text refused" 2 "render: --light 1,2,3xyz: expected X,Y,Z" \
    "$LT" render --res 8 --light 1,2,3xyz --out "$tmp/opt_g"
expect "run --repeat 1e9 is refused, not read as 1" 2 "run: --repeat 1e9: not an integer; expected 1..100000" \
    "$LT" run --res 4 --num q16 --no-ref --repeat 1e9
expect "shadows --tol -1: out of range" 2 "shadows: --tol -1: out of range; expected \[0, 1\]" \
    "$LT" shadows --mesh scenes/teapot.obj --res 8 --no-ref --tol -1
expect "shadows --light nan,...: not a finite light" 2 "shadows: --light nan,0,0,1: expected X,Y,Z,SIZE" \
    "$LT" shadows --mesh scenes/teapot.obj --res 8 --no-ref --light nan,0,0,1
expect "shadows --light with trailing text refused" 2 "shadows: --light 0,5,0,1xyz: expected X,Y,Z,SIZE" \
    "$LT" shadows --mesh scenes/teapot.obj --res 8 --no-ref --light 0,5,0,1xyz
expect "shadows --fov 60abc: trailing text refused" 2 "shadows: --fov 60abc: not a finite number" \
    "$LT" shadows --mesh scenes/teapot.obj --res 8 --no-ref --fov 60abc
# shadows at N x N under 4 (1..LT_SF_MAX_RES like run and render): --res 3 was refused (4..8192),
# and a scene file's "resolution" under 4 was raised to 4 without a word (a 4x4 image for 2)
png_wh() { # a PNG's WxH from its IHDR
    od -An -tu1 -j16 -N8 "$1" | awk '{ printf "%dx%d", $1 * 16777216 + $2 * 65536 + $3 * 256 + $4, $5 * 16777216 + $6 * 65536 + $7 * 256 + $8 }'
}
expect "shadows --res 3: a 3x3 image" 0 "^result" \
    "$LT" shadows --mesh scenes/teapot.obj --res 3 --no-ref -q --png "$tmp/sh3.png"
check "shadows --res 3: the PNG is 3x3 ($(png_wh "$tmp/sh3.png"))" test "$(png_wh "$tmp/sh3.png")" = 3x3
sc '{"mesh": "'"$PWD"'/scenes/teapot.obj", "resolution": 2}'
expect "shadows: a scene's resolution 2 gives 2x2, not 4x4" 0 "2x2, s15.16" \
    "$HOSTBIN/lanetrace-native" shadows "$tmp/s.json" --no-ref --png "$tmp/sh2.png"
check "shadows: its PNG is 2x2 ($(png_wh "$tmp/sh2.png"))" test "$(png_wh "$tmp/sh2.png")" = 2x2
expect "shadows --res 0: out of range, names the limits" 2 "shadows: --res 0: out of range; expected 1..8192" \
    "$LT" shadows --mesh scenes/teapot.obj --res 0 --no-ref
# the same messages from every subcommand
for c in run render reproject shadows info diff machines fwblob pack; do
    expect "$c --help is printed from the option table" 0 "usage: lanetrace $c" "$LT" $c --help
    expect "$c: unknown option, uniform message" 2 "lanetrace $c: unknown option '--frobnicate' (see 'lanetrace $c --help')" \
        "$LT" $c --frobnicate
done
for co in "run --res" "render --out" "reproject --depth" "shadows --mesh" "diff --threshold"; do
    set -- $co
    expect "$1 $2 without its value: missing value" 2 "lanetrace $1: $2: missing value" "$LT" $1 $2
done
# --num takes the names of the numeric-path registry (host/render/lt_paths.c) in every subcommand
expect "run --num lists the object paths" 2 "run: --num n64: expected q16, f32 or both" "$LT" run --num n64
expect "render --num lists the object paths" 2 "render: --num both: expected q16 or f32" "$LT" render --num both --out "$tmp/x"
expect "shadows --num lists the frusta paths" 2 "shadows: --num n32: expected q16 or f32" "$LT" shadows --mesh scenes/teapot.obj --num n32
expect "reproject --num lists the screen paths" 2 "reproject: --num q16: expected n64, n32 or f32" "$LT" reproject --depth x.exr --num q16
expect "reproject --enc (deprecated) still parses, with a note on stderr" 1 "reproject: note: --enc is deprecated, use --num" \
    "$LT" reproject --depth /nonexistent.exr --enc n32
