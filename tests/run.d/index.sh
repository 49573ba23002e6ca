# index.sh - the index of core functions (tools/gen_index.sh, `make index`): template-generated
# definitions are findable by name, with the template file and line, and every function a public
# header declares is defined. Sourced by tests/run_tests.sh ($B, $tmp, check/ok/ko).
tools/gen_index.sh --check "$B/host/obj/firmware/core" "$tmp/index" >"$tmp/index.txt" 2>&1
rc=$?
check "index: every public core function is defined ($(tail -1 "$tmp/index.txt"))" test "$rc" -eq 0
for fn in lt_bvh_build_q16 lt_bvh_build_f32 lt_kd_trace16_q16 lt_qt_trace16_q30; do
    loc=$(awk -v n="$fn" '$1 == n { print $2 }' "$tmp/index/symbols.txt")
    check "index: $fn found by name at ${loc:-nowhere}" test -n "$loc"
done
check "index: lt_bvh_build_q16 and _f32 come from one template (object/lt_bvh.inc)" \
    test "$(grep -cE '^lt_bvh_build_(q16|f32) +firmware/core/object/lt_bvh.inc:[0-9]+  template$' \
        "$tmp/index/symbols.txt")" -eq 2
check "index: the tags file lists lt_bvh_build_q16" \
    grep -q "^lt_bvh_build_q16	firmware/core/object/lt_bvh.inc	" "$tmp/index/tags"
