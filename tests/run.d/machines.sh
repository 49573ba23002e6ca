# machines.sh - the machine models as data (docs/cost-model.md): one file sim/machines/<name>.def
# per machine. Sourced by tests/run_tests.sh ($B, $tmp, check/ok/ko). The names are read from the
# files here; `lanetrace machines` lists each of them (clock, lanes, caches; --ops every op of
# lt_ops.def; --json), the native build lists the names; every machine is accepted by
# `run --machine`; an unknown machine is refused (exit 2) with the names of the table by every CLI
# that takes --machine (run in both builds, reproject, lanetrace shadows, lt-stream-dev) and by the
# scene-file validator.
LT="$SIMBIN/lanetrace"
mc_expect() { # name, expected rc, fixed string in the output ("" = any), command...
    local name=$1 want=$2 pat=$3
    shift 3
    "$@" >"$tmp/mc.txt" 2>&1
    local rc=$?
    if [ "$rc" -eq "$want" ] && { [ -z "$pat" ] || grep -qF -- "$pat" "$tmp/mc.txt"; }; then
        ok "$name (rc $rc)"
    else
        ko "$name (rc $rc, want $want; output: $(head -c 300 "$tmp/mc.txt"))"
    fi
}
mc_names=$(cd sim/machines && LC_ALL=C ls -- *.def | while read -r f; do
    sed -n 's/^LT_MACHINE([A-Za-z0-9_]*, *"\([^"]*\)".*/\1/p' "$f"; done)
mc_n=$(printf '%s\n' "$mc_names" | grep -c .)
mc_list=$(printf '%s\n' "$mc_names" | paste -sd, - | sed 's/,/, /g')
mc_ops=$(sed -n 's/^LT_OP(\([A-Z0-9_]*\),.*/\1/p' firmware/include/lt/lt_ops.def)
echo "   machine files: $mc_n ($mc_list)"

"$LT" machines >"$tmp/mc_table.txt" 2>&1
check "lanetrace machines exits 0" test $? -eq 0
for m in $mc_names; do
    check "lanetrace machines lists $m with clock, lanes, caches" \
        grep -qE "^$m +[0-9]+ MHz +[0-9]+  [0-9]+:[0-9]+:[0-9]+ " "$tmp/mc_table.txt"
done
check "lanetrace machines: one row per file ($mc_n)" \
    test "$(grep -cE '^[^ ]+ +[0-9]+ MHz' "$tmp/mc_table.txt")" -eq "$mc_n"
"$LT" machines --ops >"$tmp/mc_ops.txt" 2>&1
mc_missing=0
for o in $mc_ops; do
    grep -qE "^$o +[A-Z]+( +[0-9]+/[0-9]+){$mc_n}\$" "$tmp/mc_ops.txt" || mc_missing=$((mc_missing + 1))
done
check "lanetrace machines --ops: a latency/issue row for each of the $(echo $mc_ops | wc -w) ops, one column per machine ($mc_missing missing)" \
    test "$mc_missing" -eq 0
"$LT" machines --json >"$tmp/mc.json" 2>&1
check "lanetrace machines --json: every machine with its clock and ops" \
    bash -c "[ \$(grep -c '\"clock_mhz\"' '$tmp/mc.json') -eq $mc_n ] && [ \$(grep -c '\"SALU\"' '$tmp/mc.json') -eq $mc_n ]"
"$HOSTBIN/lanetrace-native" machines >"$tmp/mc_native.txt" 2>/dev/null
check "lanetrace-native machines: the names, one per line, in file order" \
    test "$(cat "$tmp/mc_native.txt")" = "$mc_names"
mc_expect "lanetrace machines --frobnicate: usage error" 2 "unknown option" "$LT" machines --frobnicate

for m in $mc_names; do
    mc_expect "run --machine $m is accepted and reported" 0 "on $m" \
        "$LT" run --machine "$m" --res 4 --num q16 --no-ref -q
done
mc_expect "run --machine nosuch: refused, names the known machines" 2 "(known: $mc_list)" \
    "$LT" run --machine nosuch --res 4
mc_expect "native run --machine nosuch: refused the same way" 2 "(known: $mc_list)" \
    "$HOSTBIN/lanetrace-native" run --machine nosuch --res 4
mc_expect "run --help lists the machines" 0 "machine model: $mc_list" "$LT" run --help
mc_expect "reproject --machine nosuch: refused with the names" 2 "$mc_list" \
    "$LT" reproject --depth x.exr --machine nosuch
mc_expect "lanetrace shadows --machine nosuch: refused with the names" 2 "(known: $mc_list)" \
    "$SIMBIN/lanetrace" shadows --mesh scenes/teapot.obj --res 8 --machine nosuch
mc_expect "lt-stream-dev --machine nosuch: refused with the names" 2 "(known: $mc_list)" \
    "$SIMBIN/lt-stream-dev" --machine nosuch
printf '{"mesh": "%s/scenes/teapot.obj", "machine": "nosuch"}\n' "$PWD" >"$tmp/mc_scene.json"
mc_expect "scene file with machine nosuch: refused with the names" 1 "is not one of: $mc_list" \
    "$HOSTBIN/lanetrace-native" run "$tmp/mc_scene.json"
