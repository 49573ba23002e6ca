# threads.sh - every core (host/render/lt_par.h, docs/user-guide.md "Threads"), CLI level. Sourced
# by tests/run_tests.sh ($B, $tmp, check/ok/ko): the native build's render (primary, shadow and
# peel loops), run (every structure), reproject (quadtree, DDA, Hi-Z) and shadows (P-Packet,
# P-Frusta, S-Packet, S-Frusta, the 256-sample reference) write byte-identical outputs on 1, 2 and
# 7 threads, and equal the simulator build's (which traces its charged loops on one thread);
# --threads out of range is a usage error. On the bundled teapot: nothing from ../shared.
TH_NAT="$HOSTBIN/lanetrace-native"
TH_SIM="$SIMBIN/lanetrace"
th_same() { # name, file-or-text pattern: files $tmp/th.<tag>.1 .2 .7 (and .sim when present)
    local name=$1 base=$2 f ref="$2.1" bad=""
    for f in "$base.2" "$base.7" "$base.sim"; do
        [ -e "$f" ] || { [ "$f" = "$base.sim" ] && continue; bad="$bad missing:$f"; continue; }
        cmp -s "$ref" "$f" || bad="$bad $(basename "$f")"
    done
    check "$name: identical on 1, 2, 7 threads$([ -e "$base.sim" ] && echo ' and in the sim build')${bad:+ (differ:$bad)}" \
        test -s "$ref" -a -z "$bad"
}

# render: the EXR holds Z, id, normals, shaded RGB (hard shadows) and 2 depth layers
for t in 1 2 7; do
    "$TH_NAT" render scenes/teapot.json --res 90x70 --layers 2 --threads "$t" \
        --out "$tmp/thr$t" -q >/dev/null 2>&1
    cp "$tmp/thr$t.exr" "$tmp/th.render.$t" 2>/dev/null
done
"$TH_SIM" render scenes/teapot.json --res 90x70 --layers 2 --threads 2 --out "$tmp/thrs" -q \
    >/dev/null 2>&1 && cp "$tmp/thrs.exr" "$tmp/th.render.sim"
th_same "render 90x70 --layers 2 (EXR: primary, shadow, peel)" "$tmp/th.render"

# run: the result hash lines of every structure, both paths
for s in bvh bvhq kd grid chunks; do
    for t in 1 2 7; do
        num=both
        [ "$s" = bvhq ] && num=q16
        "$TH_NAT" run scenes/teapot.json --res 77x45 --structure "$s" --num "$num" --threads "$t" \
            --no-ref 2>&1 | grep '^result' >"$tmp/th.run$s.$t"
    done
    th_same "run --structure $s 77x45 (result hashes)" "$tmp/th.run$s"
done
# run --rays wide: the packets through the 8-wide tree, both paths (and the sim build's hashes)
for t in 1 2 7; do
    "$TH_NAT" run scenes/teapot.json --res 77x45 --num both --rays wide --threads "$t" --no-ref 2>&1 |
        grep '^result' >"$tmp/th.runwide.$t"
done
"$TH_SIM" run scenes/teapot.json --res 77x45 --num both --rays wide --no-ref 2>&1 | grep '^result' \
    >"$tmp/th.runwide.sim"
th_same "run --rays wide 77x45 (result hashes)" "$tmp/th.runwide"
grep -q "native, 7 threads" <("$TH_NAT" run scenes/teapot.json --res 16 --threads 7 --no-ref 2>&1)
check "run --threads 7 prints 'native, 7 threads' on its time line" test $? -eq 0

# reproject: the 2-layer depth render of the teapot into a moved view, every tracer
for tr in quadtree dda hiz; do
    for t in 1 2 7; do
        "$TH_NAT" reproject scenes/teapot.json --depth "$tmp/thr1.exr" --layers 2 --color \
            --tracer "$tr" --move-rel 0.08,0,0 --rot -3,0,0 --threads "$t" \
            --out "$tmp/th.rp$tr.$t.exr" -q >/dev/null 2>&1
        mv -f "$tmp/th.rp$tr.$t.exr" "$tmp/th.rp$tr.$t" 2>/dev/null
    done
    th_same "reproject --tracer $tr (EXR)" "$tmp/th.rp$tr"
done

# shadows: the Table-1 counts, the check and result lines, the filtered and reference images
for t in 1 2 7; do
    "$TH_NAT" shadows --mesh scenes/teapot.obj --res 72 --threads "$t" --png "$tmp/thsh$t.png" \
        --ref-png "$tmp/thshr$t.png" >"$tmp/thsh$t.txt" 2>&1
    grep -E '^(check|result|table|rays|quality)' "$tmp/thsh$t.txt" | sed 's/([0-9.]* s)//' \
        >"$tmp/th.shtxt.$t"
    cp "$tmp/thsh$t.png" "$tmp/th.shpng.$t" 2>/dev/null
    cp "$tmp/thshr$t.png" "$tmp/th.shref.$t" 2>/dev/null
done
th_same "shadows 72x72 (check, result, quality lines)" "$tmp/th.shtxt"
th_same "shadows 72x72 (filtered PNG)" "$tmp/th.shpng"
th_same "shadows 72x72 (256-sample reference PNG)" "$tmp/th.shref"

"$TH_NAT" run scenes/teapot.json --threads 257 >/dev/null 2>"$tmp/th.err"
rc=$?
check "run --threads 257: usage error naming the range (rc $rc)" \
    bash -c "[ $rc -eq 2 ] && grep -q -- '--threads' '$tmp/th.err' && grep -q '256' '$tmp/th.err'"

# the same loops under ThreadSanitizer (build/tsan: a data race exits 66), 7 threads, against the
# one-thread outputs above
TH_TSAN="$B/tsan/lanetrace-native"
# a kernel whose address-space layout ThreadSanitizer cannot use makes every TSan program die at
# start with "FATAL: ThreadSanitizer: unexpected memory mapping": that is the machine, not a race
th_tsan_env=""
if [ -x "$TH_TSAN" ] && "$TH_TSAN" machines >/dev/null 2>"$tmp/th.tsanprobe"; then :; else
    grep -q "FATAL: ThreadSanitizer" "$tmp/th.tsanprobe" 2>/dev/null && th_tsan_env=$(head -1 "$tmp/th.tsanprobe")
fi
if [ -n "$th_tsan_env" ]; then
    echo "SKIP tsan: ThreadSanitizer cannot run on this kernel ($th_tsan_env)"
elif [ -x "$TH_TSAN" ]; then
    export TSAN_OPTIONS="exitcode=66:halt_on_error=1:second_deadlock_stack=1"
    "$TH_TSAN" render scenes/teapot.json --res 90x70 --layers 2 --threads 7 --out "$tmp/thts" -q \
        >/dev/null 2>"$tmp/thts.err"
    rc=$?
    check "tsan: render --threads 7, no race (rc $rc), EXR = one thread's" \
        bash -c "[ $rc -eq 0 ] && cmp -s '$tmp/thts.exr' '$tmp/th.render.1'"
    "$TH_TSAN" run scenes/teapot.json --res 77x45 --structure kd --num both --threads 7 --no-ref \
        >"$tmp/thts.run" 2>&1
    rc=$?
    grep '^result' "$tmp/thts.run" >"$tmp/thts.runr"
    check "tsan: run --structure kd --threads 7, no race (rc $rc), hashes = one thread's" \
        bash -c "[ $rc -eq 0 ] && cmp -s '$tmp/thts.runr' '$tmp/th.runkd.1'"
    "$TH_TSAN" reproject scenes/teapot.json --depth "$tmp/thr1.exr" --layers 2 --color \
        --move-rel 0.08,0,0 --rot -3,0,0 --threads 7 --out "$tmp/thts.rp.exr" -q >/dev/null 2>&1
    rc=$?
    check "tsan: reproject --threads 7, no race (rc $rc), EXR = one thread's" \
        bash -c "[ $rc -eq 0 ] && cmp -s '$tmp/thts.rp.exr' '$tmp/th.rpquadtree.1'"
    "$TH_TSAN" shadows --mesh scenes/teapot.obj --res 72 --threads 7 --png "$tmp/thts.png" \
        --ref-png "$tmp/thtsr.png" >/dev/null 2>&1
    rc=$?
    check "tsan: shadows --threads 7, no race (rc $rc), images = one thread's" \
        bash -c "[ $rc -eq 0 ] && cmp -s '$tmp/thts.png' '$tmp/th.shpng.1' && cmp -s '$tmp/thtsr.png' '$tmp/th.shref.1'"
    "$B/tsan/test_par" >"$tmp/thts.unit" 2>&1
    rc=$?
    check "tsan: test_par (the queue, every structure's frames on 1-7 threads), no race (rc $rc)" \
        test "$rc" -eq 0
    unset TSAN_OPTIONS
else
    ko "tsan: $TH_TSAN not built (make test builds it)"
fi

# the progress bar: on a TTY (script(1) gives one) a run over a second draws it; piped, never (the
# 1280x1280 reference takes 2-3 s on one core here: at 768x768 it had come down to 1.0 s, the
# threshold)
if command -v script >/dev/null 2>&1; then
    script -qc "$TH_NAT shadows --mesh scenes/teapot.obj --res 1280 --threads 1 --only frusta" \
        /dev/null 2>&1 | tr '\r' '\n' | grep -c 'reference  \[' >"$tmp/th.bar"
    "$TH_NAT" shadows --mesh scenes/teapot.obj --res 96 --only frusta 2>&1 | grep -c 'ETA' \
        >"$tmp/th.nobar"
    check "progress bar: drawn on a TTY for the 1280x1280 shadow reference ($(cat "$tmp/th.bar") updates), none when piped ($(cat "$tmp/th.nobar"))" \
        bash -c "[ \"\$(cat '$tmp/th.bar')\" -gt 0 ] && [ \"\$(cat '$tmp/th.nobar')\" -eq 0 ]"
else
    echo "SKIP progress bar: no script(1) to give a TTY"
fi
