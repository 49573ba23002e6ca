# auto.sh - the recommendation, on by default in `run` and `render` (`--no-auto` turns it off;
# docs/user-guide.md; docs/tune.md "Without a sweep"): lanetrace info's picks for the scene's
# machine applied to the knobs that neither a flag nor the scene file sets, each printed with its
# reason, the others kept and said so, all of it in the report JSON. Sourced by
# tests/run_tests.sh ($B, $tmp, check/ok/ko); the bundled teapot and a 2-triangle mesh written here.
AU_NAT="$HOSTBIN/lanetrace-native"
AU_SIM="$SIMBIN/lanetrace"
"$AU_NAT" run --mesh scenes/teapot.obj --res 32 --auto >"$tmp/au1.txt" 2>&1
rc=$?
check "run --mesh teapot --auto: numeric f32, structure bvh, leaf 16 applied with reasons (rc $rc)" \
    bash -c "[ $rc -eq 0 ] && grep -q '^auto      numeric   f32    q16 holds it too' '$tmp/au1.txt' &&
             grep -q '^auto      structure bvh    992 triangles' '$tmp/au1.txt' &&
             grep -q '^auto      leaf      16 ' '$tmp/au1.txt'"
check "run --auto on the teapot traces float32 only (the pick)" \
    bash -c "grep -q '^result    f32' '$tmp/au1.txt' && ! grep -q '^result    q16' '$tmp/au1.txt'"
"$AU_SIM" run scenes/teapot.json --res 32 --auto >"$tmp/au2.txt" 2>&1
check "run scenes/teapot.json --auto: numeric and structure kept (set by the scene file), leaf applied" \
    bash -c "grep -q '^auto      numeric   kept   set by the scene file' '$tmp/au2.txt' &&
             grep -q '^auto      structure kept   set by the scene file' '$tmp/au2.txt' &&
             grep -q '^auto      leaf      16 ' '$tmp/au2.txt' && grep -q '^result    q16' '$tmp/au2.txt'"
"$AU_NAT" run --mesh scenes/teapot.obj --res 32 --auto --num both --structure kd --json \
    >"$tmp/au3.json" 2>/dev/null
check "run --auto --num both --structure kd --json: flags win, the report says which knob was applied" \
    python3 -c "
import json, sys
d = json.load(open('$tmp/au3.json'))
a = d[0]['auto']
ok = len(d) == 2 and a['numeric'] == {'pick': 'f32', 'applied': False, 'set_by': '--num'} \
     and a['structure']['set_by'] == '--structure' and a['leaf']['applied'] is True \
     and d[0]['structure'] == 'kd' and d[0]['leaf'] == 16
sys.exit(0 if ok else 1)"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n' >"$tmp/au_quad.obj"
"$AU_NAT" run --mesh "$tmp/au_quad.obj" --res 16 --auto >"$tmp/au4.txt" 2>&1
rc=$?
check "run --auto on a 2-triangle mesh: chunks, no leaf (rc $rc)" \
    bash -c "[ $rc -eq 0 ] && grep -q '^auto      structure chunks' '$tmp/au4.txt' &&
             grep -q '^auto      leaf      -  ' '$tmp/au4.txt'"
"$AU_NAT" run --mesh scenes/teapot.obj --res 32 --no-auto >"$tmp/au5.txt" 2>&1
check "run --no-auto: no recommendation applied, both paths (the scene-file default)" \
    bash -c "! grep -q '^auto' '$tmp/au5.txt' && grep -q '^result    q16' '$tmp/au5.txt' &&
             grep -q '^result    f32' '$tmp/au5.txt'"
"$AU_NAT" run --mesh scenes/teapot.obj --res 32 >"$tmp/au6.txt" 2>&1
check "run with no flag: the recommendation is the default (same picks as --auto)" \
    bash -c "diff <(grep '^auto\|^result' '$tmp/au1.txt') <(grep '^auto\|^result' '$tmp/au6.txt')"
"$AU_SIM" run --mesh scenes/teapot.obj --res 16 --machine mcu-m4 --no-ref >"$tmp/au7.txt" 2>&1
check "run --machine mcu-m4: the picks are the machine's (leaf 4 for one lane, priced paths)" \
    bash -c "grep -q '^auto      leaf      4  *about 248 leaves of up to 4 triangles: mcu-m4 has 1 lane;' '$tmp/au7.txt' &&
             grep -q '^auto      numeric   f32 .*cheaper on mcu-m4: a 16-ray watertight triangle test costs [0-9]* cycles against [0-9]* in s15.16' '$tmp/au7.txt'"
"$AU_SIM" render --mesh "$tmp/au_quad.obj" --res 8 --out "$tmp/au_r" --json >"$tmp/au8.json" 2>&1
check "render on a 2-triangle mesh: chunks not applied (shadow rays need a hierarchy), path picked" \
    python3 -c "
import json, sys
d = json.load(open('$tmp/au8.json'))
a = d['auto']
ok = d['structure'] == 'bvh' and a['structure']['applied'] is False \
     and 'hierarchy' in a['structure']['set_by'] and a['numeric']['applied'] is True and d['path'] == 'f32'
sys.exit(0 if ok else 1)"
