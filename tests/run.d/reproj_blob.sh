# reproj_blob.sh - reprojection of a real depth image on every target (issue #13 item 1,
# docs/firmware.md "Reprojection of a real depth image"): the blob `lanetrace fwblob` makes from
# the shared Beachball EXR now equals the one linked into build/fw/<T>/reproj-bb.elf; the host
# runner of the app (build/host/reproj-blob-host, the same source as the images) prints its lines
# tracing packets, the ASan build the same with packets and with single rays; under QEMU each
# target exits 0 and prints the host's lines exactly (header with the blob's checksum, one line per
# 16x16 tile, the total) from reproj-bb.elf (single rays) and reproj-bb-packets.elf (packets of
# 16), within the RAM budget of tests/fw/ram_budget.txt; no float or double helper is linked; damaged blobs and short memory
# give their error codes without a crash (ASan); lanetrace fwblob's usage and input errors.
# Without ../shared: SKIP (FAIL under CI=true).
# Sourced by tests/run_tests.sh ($B, $tmp, check/ok/ko, QEMU_<T>).
rb_exr=../shared/depth/beachball_singlepart.0001.exr
rb_blob=$B/gen/reproj_bb.blob
rb_expect() { # name, expected rc, pattern, command...
    local name=$1 want=$2 pat=$3
    shift 3
    "$@" >"$tmp/rbx.txt" 2>&1
    local rc=$?
    if [ "$rc" -eq "$want" ] && grep -q -- "$pat" "$tmp/rbx.txt"; then
        ok "$name (rc $rc)"
    else
        ko "$name (rc $rc, want $want; output: $(head -c 300 "$tmp/rbx.txt"))"
    fi
}
rb_lt=$HOSTBIN/lanetrace-native
rb_expect "fwblob: no --depth / --out is a usage error" 2 "are required" "$rb_lt" fwblob --out "$tmp/x.blob"
rb_expect "fwblob: missing EXR names the file" 1 "/nonexistent.exr" "$rb_lt" fwblob --depth /nonexistent.exr --out "$tmp/x.blob"
rb_expect "fwblob: --tile 6 is not a multiple of 4" 2 "a multiple of 4" "$rb_lt" fwblob --depth x.exr --out "$tmp/x.blob" --tile 6
rb_expect "fwblob: --crop in fractions of a pixel refused" 2 "whole pixels" "$rb_lt" fwblob --depth x.exr --out "$tmp/x.blob" --crop 1.5,0,8,8
if [ ! -f "$rb_exr" ]; then
    if [ "${CI:-}" = "true" ]; then
        ko "reproj-blob: shared depth file missing under CI: $rb_exr"
    else
        echo "SKIP reproj-blob: $rb_exr not found (a fresh clone has no ../shared; reproj-bb.elf is not built)"
    fi
else
    # the blob, made again in this run with firmware.mk's arguments, is the one the images link
    rb_args=$(sed -n 's/^FW_RPBB_ARGS := //p' firmware/firmware.mk)
    # shellcheck disable=SC2086
    "$HOSTBIN/lanetrace-native" fwblob --depth "$rb_exr" $rb_args --out "$tmp/rb.blob" >"$tmp/rb.gen" 2>&1
    check "reproj-blob: lanetrace fwblob $rb_args: $(sed -n 's/^  //p' "$tmp/rb.gen" | tail -n 1), = $rb_blob" \
        cmp -s "$tmp/rb.blob" "$rb_blob"
    "$B/host/reproj-blob-host" "$rb_blob" >"$tmp/rb.host" 2>&1
    rc=$?
    rb_total=$(grep '^total: ' "$tmp/rb.host")
    rb_tiles=$(grep -c '^tile ' "$tmp/rb.host")
    check "reproj-blob host: exit 0 (rc $rc), $rb_tiles tile lines; $(head -n 1 "$tmp/rb.host")" \
        test "$rc" -eq 0 -a "$rb_tiles" -eq 64
    echo "   host $rb_total"
    "$B/asan/reproj-blob-host" "$rb_blob" >"$tmp/rb.asan" 2>&1
    check "reproj-blob asan (ASan + UBSan, poisoned memory, guard after it) = host" cmp -s "$tmp/rb.host" "$tmp/rb.asan"
    "$B/asan/reproj-blob-host" "$rb_blob" --single >"$tmp/rb.asan1" 2>&1
    check "reproj-blob asan --single (lt_qt_trace1_q30, one ray at a time) = host's packets, all $(wc -l <"$tmp/rb.asan1") lines" \
        cmp -s "$tmp/rb.host" "$tmp/rb.asan1"
    rb_expect "fwblob: a crop outside the data window names the window" 1 "outside the 911x876 data window" \
        "$rb_lt" fwblob --depth "$rb_exr" --crop 900,0,128,128 --out "$tmp/x.blob"
    rb_expect "fwblob: a crop without valid depth is refused" 1 "has no valid depth" \
        "$rb_lt" fwblob --depth "$rb_exr" --crop 0,0,8,8 --out "$tmp/x.blob"
    rb_expect "fwblob: unwritable --out names the path" 1 "/nonexistent-dir" \
        "$rb_lt" fwblob --depth "$rb_exr" --out /nonexistent-dir/x.blob
    rb_budget=$(awk '$1 == "reproj-bb" {print $2}' tests/fw/ram_budget.txt)
    for t in cm4 cm55 rv32 cm4:packets cm55:packets rv32:packets; do
        qvar="QEMU_${t%:*}"
        img=reproj-bb
        walk=single
        if [ "${t#*:}" = packets ]; then
            img=reproj-bb-packets
            walk=packets
        fi
        t=${t%:*}
        timeout 300 ${!qvar} "$B/fw/$t/$img.elf" </dev/null >"$tmp/rb.$t" 2>"$tmp/rb.$t.err"
        rc=$?
        grep -v -e '^ram: ' -e '^ticks ' "$tmp/rb.$t" >"$tmp/rb.$t.lines"
        h=$(sed -n 's/^total: .* hash \(0x[0-9a-f]*\)$/\1/p' "$tmp/rb.$t")
        check "reproj-blob $t $img.elf under QEMU: exit 0 (rc $rc), walk $walk, all $(wc -l <"$tmp/rb.$t.lines") lines = host's packets (64 tile hashes, total hash ${h:-none})" \
            bash -c "[ $rc -eq 0 ] && [ -s '$tmp/rb.host' ] && cmp -s '$tmp/rb.host' '$tmp/rb.$t.lines' && grep -q '^ticks .*, walk $walk\$' '$tmp/rb.$t'"
        line=$(grep '^ram: ' "$tmp/rb.$t")
        used=$(sed -n 's/^ram: stack \([0-9]*\) of.*/\1/p' <<<"$line")
        stat=$(sed -n 's/.*static \([0-9]*\) bytes.*/\1/p' <<<"$line")
        check "reproj-blob $t $img.elf RAM: stack ${used:-?} + static ${stat:-?} = $(( ${used:-0} + ${stat:-0} )) bytes, budget ${rb_budget:-?} (limit 524288)" \
            test -n "$used" -a -n "$stat" -a -n "$rb_budget" -a $(( ${used:-0} + ${stat:-0} )) -le "${rb_budget:-0}" \
            -a "${rb_budget:-524289}" -le 524288
        echo "   $t $(grep '^ticks ' "$tmp/rb.$t")"
    done
    # the targets run the integer path only: the mapping came from the host, no soft-float helper
    for t in cm4 cm55 rv32; do
        nm=arm-none-eabi-nm
        [ "$t" = rv32 ] && nm=riscv64-unknown-elf-nm
        fl=$($nm "$B/fw/$t/reproj-bb.elf" 2>/dev/null | awk '{print $NF}' |
            grep -E '^(__aeabi_[fd]|__(add|sub|mul|div)[sd]f3|__float|__fix|__extend|__trunc|__(eq|ne|lt|le|gt|ge|unord)[sd]f2)' | tr '\n' ' ')
        check "reproj-blob $t: no float or double helper linked${fl:+ [$fl]}" \
            bash -c "[ -s '$B/fw/$t/reproj-bb.elf' ] && [ -z '$fl' ]"
    done

    # damaged blobs and short memory: an error line and the code, never a crash (ASan build)
    python3 - "$rb_blob" "$tmp" <<'EOF'
import struct, sys
src, d = sys.argv[1], sys.argv[2]
b = bytearray(open(src, 'rb').read())
def fnv(p):
    h = 2166136261
    for c in p:
        h = ((h ^ c) * 16777619) & 0xFFFFFFFF
    return h
def put(name, blob, fix=False):
    blob = bytearray(blob)
    if fix:
        struct.pack_into('<I', blob, 16, fnv(blob[20:]))
    open('%s/rbbad.%s' % (d, name), 'wb').write(blob)
def field(off, v, fix=False):
    c = bytearray(b)
    struct.pack_into('<I', c, off, v & 0xFFFFFFFF)
    return c
put('empty', b'')
put('short', b[:100])
put('cut', b[:-4])
put('magic', field(0, 0x12345678))
put('endian', field(0, 0x4C505242))
put('version', field(4, 2))
put('width', field(20, 70000))
put('layers', field(28, 0))
put('offset', field(40, 250))
put('past', field(44, 4 * 128 * 128 * 2 + 64))
c = bytearray(b); c[len(c) // 2] ^= 0x40
put('flip', c)
put('map', field(96 + 96, 127), fix=True)
put('wnear', field(96 + 120, 0), fix=True)
EOF
    rb_bad="empty:10 short:10 cut:15 magic:12 endian:13 version:14 width:16 layers:16 offset:17 past:17 flip:18 map:19 wnear:19"
    rb_ok=0
    rb_n=0
    for c in $rb_bad; do
        n=${c%%:*}
        want=${c##*:}
        "$B/asan/reproj-blob-host" "$tmp/rbbad.$n" >"$tmp/rbbad.$n.out" 2>&1
        rc=$?
        rb_n=$((rb_n + 1))
        if [ "$rc" -eq "$want" ] && grep -q "^error $want: " "$tmp/rbbad.$n.out"; then
            rb_ok=$((rb_ok + 1))
        else
            echo "   blob '$n': rc $rc, want $want: $(head -c 200 "$tmp/rbbad.$n.out")"
        fi
    done
    check "reproj-blob: $rb_ok of $rb_n damaged blobs refused with their code and an error line, no crash (ASan)" \
        test "$rb_ok" -eq "$rb_n"
    rb_need=$(sed -n 's/.*quadtree \([0-9]*\) bytes.*/\1/p' "$tmp/rb.host")
    "$B/asan/reproj-blob-host" "$rb_blob" --mem 100000 >"$tmp/rbmem.out" 2>&1
    rc=$?
    check "reproj-blob: 100000 bytes of memory refused (rc $rc): $(head -n 1 "$tmp/rbmem.out")" \
        bash -c "[ $rc -eq 20 ] && grep -q '^error 20: memory too small: 100000 bytes given, $((rb_need + 1024)) needed' '$tmp/rbmem.out'"
fi
