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
# the numeric pick is the path the machine file prices cheaper (which one moves with a refit of
# the MCU costs): the cycles it prints for the pick are below the other path's
au_num=$(grep '^auto      numeric' "$tmp/au7.txt")
au_cheaper=$(python3 - "$au_num" <<'EOF'
import re, sys
m = re.match(r'auto +numeric +(q16|f32) .*cheaper on mcu-m4: a 16-ray watertight triangle test '
             r'costs ([0-9]+) cycles (in s15\.16 )?against ([0-9]+) in (float32|s15\.16)$', sys.argv[1])
ok = m and int(m.group(2)) < int(m.group(4)) and (m.group(1) == 'q16') == (m.group(5) == 'float32')
print('yes' if ok else 'no')
EOF
)
check "run --machine mcu-m4: the picks are the machine's (leaf 4 for one lane; the path priced cheaper: ${au_num#auto      numeric   })" \
    bash -c "grep -q '^auto      leaf      4  *about 248 leaves of up to 4 triangles: mcu-m4 has 1 lane;' '$tmp/au7.txt' &&
             [ '$au_cheaper' = yes ]"
"$AU_SIM" render --mesh "$tmp/au_quad.obj" --res 8 --out "$tmp/au_r" --json >"$tmp/au8.json" 2>&1
check "render on a 2-triangle mesh: chunks not applied (shadow rays need a hierarchy), path picked" \
    python3 -c "
import json, sys
d = json.load(open('$tmp/au8.json'))
a = d['auto']
ok = d['structure'] == 'bvh' and a['structure']['applied'] is False \
     and 'hierarchy' in a['structure']['set_by'] and a['numeric']['applied'] is True and d['path'] == 'f32'
sys.exit(0 if ok else 1)"
# reproject: the node format from the depth image and the machine (lanetrace info's depth
# recommendation), on a depth image the quadtree rows were not measured on (the teapot, 96x96)
"$AU_SIM" render --mesh scenes/teapot.obj --res 96 --out "$tmp/au_d" -q >/dev/null 2>&1
au_rp() { "$AU_SIM" reproject --mesh scenes/teapot.obj --depth "$tmp/au_d.exr" --move-rel 0.05,0,0 \
    --out "$tmp/au_rp" "$@"; }
au_rp >"$tmp/au9.txt" 2>&1
rc=$?
check "reproject: the node format is picked with its reason by default (rc $rc)" \
    bash -c "[ $rc -eq 0 ] && grep -q '^auto      num       \(n64\|f32\)  *depths .* cheaper on lrb16: 96x96 to 9216 target pixels' '$tmp/au9.txt'"
au_rp --num n32 -q --json >"$tmp/au10.json" 2>&1
au_rp --tracer hiz -q --json >"$tmp/au11.json" 2>&1
au_rp --no-auto -q --json >"$tmp/au12.json" 2>&1
check "reproject: --num and --tracer keep their choice (said in the JSON); --no-auto keeps n64" \
    python3 -c "
import json, sys
a = json.load(open('$tmp/au10.json')); b = json.load(open('$tmp/au11.json')); c = json.load(open('$tmp/au12.json'))
ok = a['encoding'] == 'n32' and a['auto']['num'] == {'pick': a['auto']['num']['pick'], 'applied': False, 'set_by': '--num'} \
     and b['auto']['num']['applied'] is False and b['auto']['num']['set_by'].startswith('--tracer hiz') \
     and c['encoding'] == 'n64' and 'auto' not in c
sys.exit(0 if ok else 1)"
# out of sample: on every machine the pick costs at most 10% more than the cheaper of n64 and f32
for m in $("$AU_SIM" machines | awk 'NR > 1 && /MHz/ { print $1 }'); do
    for e in n64 f32 auto; do
        if [ $e = auto ]; then a=(); else a=(--num $e); fi
        au_rp --machine "$m" "${a[@]}" -q --report "$tmp/au_$m.$e.json" >/dev/null 2>&1
    done
    check "reproject on $m: the picked format costs at most 1.10x the cheaper of n64 and f32 here" \
        python3 -c "
import json, sys
c = {e: json.load(open('$tmp/au_$m.%s.json' % e)) for e in ('n64', 'f32', 'auto')}
best = min(c['n64']['total_cycles'], c['f32']['total_cycles'])
pick = c['auto']['total_cycles']
print('  $m: pick %s %d cycles, n64 %d, f32 %d (%.3fx the cheaper)' % (c['auto']['encoding'], pick,
      c['n64']['total_cycles'], c['f32']['total_cycles'], pick / best))
sys.exit(0 if c['auto']['auto']['num']['applied'] and pick <= 1.10 * best else 1)"
done
"$AU_NAT" info "$tmp/au_d.exr" --machine mcu-m4 >"$tmp/au13.txt" 2>&1
check "info DEPTH.exr --machine mcu-m4: shape facts and the node-format recommendation" \
    bash -c "grep -q '^shape     jumps [0-9.]*% of neighbour pairs' '$tmp/au13.txt' &&
             grep -q '^recommend for mcu-m4, reproject' '$tmp/au13.txt' &&
             grep -q '^  num  *\(n64\|f32\)  *depths' '$tmp/au13.txt'"
# the integer-only RV32IMAC (float32 in soft float): the recommendation is s15.16 there
"$AU_SIM" run --mesh scenes/teapot.obj --res 16 --machine rv32imac --no-ref >"$tmp/au14.txt" 2>&1
check "run --machine rv32imac: the recommendation traces s15.16 only (float32 is soft float there)" \
    bash -c "grep -q '^auto      numeric   q16 .*cheaper on rv32imac' '$tmp/au14.txt' &&
             grep -q '^result    q16' '$tmp/au14.txt' && ! grep -q '^result    f32' '$tmp/au14.txt'"
