# stream.sh - the stream protocol of issue 6 (docs/stream.md), sourced by tests/run_tests.sh (uses
# check/ok/ko, $B, $tmp). Fuzz corpus replay; the simulator as a device against a direct run of the
# same scene (every counter, per frame); the firmware images under QEMU (cm4, cm55, rv32) through
# a file, a pipe and QEMU's TCP serial, compared tile by tile with the simulator; determinism of
# the device's drops; receiver errors; and the fault-injection matrix, where the receiver must
# report exactly what the injector did.

S=$tmp/stream
mkdir -p "$S"
# value of "key" in the one-key-per-line JSON that lt-stream and lt-faultinject write
jget() { sed -n "s/^ *\"$1\": *\"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}\$/\1/p" "$2" | head -n 1; }

echo "-- firmware symbols (the frame fuzz corpus is replayed by fuzz.sh)"
check "stream.elf images link no libc or simulator symbol" \
    tools/check_fw.sh "$B/fw/cm4/stream.elf" "$B/fw/cm55/stream.elf" "$B/fw/rv32/stream.elf"

echo "-- the simulator as a device vs a direct run"
"$SIMBIN/lt-stream-dev" --out "$S/sim.bin" 2>"$S/sim.err"
check "lt-stream-dev (mcu-m4) exits 0" test $? -eq 0
"$SIMBIN/lt-stream-dev" --direct >"$S/direct.txt"
"$HOSTBIN/lt-stream" --file "$S/sim.bin" --tiles "$S/sim.tiles" --json >"$S/sim.json"
check "lt-stream on the sim stream: exit 0 (END, nothing lost, damaged, duplicated, reordered)" \
    test $? -eq 0
grep '^summary' "$S/sim.tiles" | sed 's/ dropped [0-9]*$//' >"$S/sim.sum"
check "sim stream summaries = direct run, field by field (rays hits hash ticks cycles aabb aabb_rays tris tri_rays, $(wc -l <"$S/direct.txt") frames)" \
    diff -u "$S/direct.txt" "$S/sim.sum"
# the per-tile reports of each frame add up to its summary (no tile report was dropped here)
awk '$1 == "tile" { k = $2; r[k] += $5; h[k] += $7; c[k] += $13; a[k] += $15; ar[k] += $17; t[k] += $19; tr[k] += $21; n[k]++ }
     $1 == "summary" { k = $2; if (n[k] != $4 || r[k] != $6 || h[k] != $8 || c[k] != $14 || a[k] != $16 || ar[k] != $18 || t[k] != $20 || tr[k] != $22) bad++; m++ }
     END { exit !(m > 0 && bad == 0) }' "$S/sim.tiles"
check "sim tile reports add up to their frame summaries (rays, hits, cycles, box and triangle tests)" \
    test $? -eq 0
"$SIMBIN/lt-stream-dev" --machine lrb16 --out "$S/lrb.bin" 2>/dev/null
"$HOSTBIN/lt-stream" --file "$S/lrb.bin" --json >"$S/lrb.json"
rc=$?
t=$(jget tiles "$S/lrb.json"); d=$(jget dev_dropped_tile "$S/lrb.json"); n=$(jget tiles_traced "$S/lrb.json")
check "lrb16 device (faster than the link): drops $d of $n tile reports and says so; received $t + dropped $d = traced $n, link clean" \
    test "$rc" -eq 0 -a "$d" -gt 0 -a $((t + d)) -eq "$n"

echo "-- firmware under QEMU: file, pipe, TCP"
source <(make -s --no-print-directory -f tools/print_qemu.mk)
# tile and summary keys with the fields both devices know: rays, hits, hash
fields() { awk '$1 == "tile" { print "tile", $2, $3, $5, $7, $9 } $1 == "summary" { print "summary", $2, $4, $6, $8, $10 }' "$1" | sort; }
fields "$S/sim.tiles" >"$S/sim.keys"
for t in cm4 cm55 rv32; do
    qvar="QEMU_$t"
    timeout 60 ${!qvar} "$B/fw/$t/stream.elf" >"$S/$t.bin" 2>"$S/$t.err" </dev/null
    rc=$?
    check "stream.elf/$t exits 0 under QEMU (rc=$rc)" test "$rc" -eq 0
    "$HOSTBIN/lt-stream" --file "$S/$t.bin" --tiles "$S/$t.tiles" --json >"$S/$t.json"
    rc=$?
    check "lt-stream on the $t UART stream: exit 0 ($(jget valid "$S/$t.json") frames, clean)" \
        test "$rc" -eq 0
    fields "$S/$t.tiles" >"$S/$t.keys"
    nt=$(grep -c '^tile' "$S/$t.keys")
    nb=$(comm -12 "$S/$t.keys" "$S/sim.keys" | grep -c '^tile')
    check "fw/$t: all $nt tile reports received equal the sim's (frame, tile, rays, hits, hash)" \
        test "$nt" -gt 0 -a "$nt" -eq "$nb"
    check "fw/$t: frame summaries equal the sim's (tiles, rays, hits, image hash)" \
        diff <(grep '^summary' "$S/$t.keys") <(grep '^summary' "$S/sim.keys")
    tr=$(jget tiles "$S/$t.json"); dr=$(jget dev_dropped_tile "$S/$t.json"); tt=$(jget tiles_traced "$S/$t.json")
    check "fw/$t: tiles received $tr + reported dropped $dr = traced $tt; image frames dropped $(jget dev_dropped_image "$S/$t.json") and reported" \
        test $((tr + dr)) -eq "$tt"
    check "fw/$t: scene hash = sim's" test "$(jget scene_hash "$S/$t.json")" = "$(jget scene_hash "$S/sim.json")"
done
timeout 60 $QEMU_rv32 "$B/fw/rv32/stream.elf" </dev/null 2>/dev/null |
    "$HOSTBIN/lt-stream" -q --json >"$S/pipe.json"
st=("${PIPESTATUS[@]}")
check "fw/rv32 piped into lt-stream: QEMU exit ${st[0]}, lt-stream exit ${st[1]}" \
    test "${st[0]}" -eq 0 -a "${st[1]}" -eq 0
printf '   measured (pipe, rv32): %s frames, %s bytes in %s s wall: %s frames/s, %s B/s; device link %s B/s budget\n' \
    "$(jget valid "$S/pipe.json")" "$(jget bytes "$S/pipe.json")" "$(jget wall_s "$S/pipe.json")" \
    "$(jget frames_per_s "$S/pipe.json")" "$(jget bytes_per_s "$S/pipe.json")" \
    "$(jget link_bytes_per_s "$S/pipe.json")"
port=$((20000 + RANDOM % 30000))
while (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null; do port=$((port + 1)); done
${QEMU_cm4/-serial stdio/-serial tcp:127.0.0.1:$port,server=on,wait=on} "$B/fw/cm4/stream.elf" \
    </dev/null >/dev/null 2>"$S/tcp.err" &
qpid=$!
timeout 60 "$HOSTBIN/lt-stream" --tcp "127.0.0.1:$port" -q --tiles "$S/tcp.tiles" >"$S/tcp.txt"
rc=$?
wait $qpid
qrc=$?
# a second run of the same image: every record, ticks and drop points included, must be the same
check "fw/cm4 over QEMU -serial tcp (port $port) into lt-stream --tcp: exit $rc, QEMU exit $qrc; records (ticks, drops) identical to the file run: deterministic under -icount" \
    bash -c "[ $rc -eq 0 ] && [ $qrc -eq 0 ] && cmp -s '$S/tcp.tiles' '$S/cm4.tiles'"

echo "-- on-target counting (stream-count.elf: LT_COST_HANDLER, the target's machine model)"
"$SIMBIN/lt-stream-dev" --machine rv32imac --out "$S/simrv.bin" 2>/dev/null
"$HOSTBIN/lt-stream" --file "$S/simrv.bin" --tiles "$S/simrv.tiles" >/dev/null
"$SIMBIN/lt-stream-dev" --machine mcu-m55 --out "$S/sim55.bin" 2>/dev/null
"$HOSTBIN/lt-stream" --file "$S/sim55.bin" --tiles "$S/sim55.tiles" >/dev/null
# frame, tile, cycles, aabb, aabb_rays, tris, tri_rays of every tile report
cnt() { awk '$1 == "tile" { print $2, $3, $13, $15, $17, $19, $21 }' "$1" | sort; }
for t in cm4 cm55 rv32; do
    qvar="QEMU_$t"
    ref="$S/sim.tiles"; m=mcu-m4
    [ $t = rv32 ] && ref="$S/simrv.tiles" && m=rv32imac
    [ $t = cm55 ] && ref="$S/sim55.tiles" && m=mcu-m55
    timeout 120 ${!qvar} "$B/fw/$t/stream-count.elf" >"$S/$t.cnt.bin" 2>/dev/null </dev/null
    rc=$?
    "$HOSTBIN/lt-stream" --file "$S/$t.cnt.bin" --tiles "$S/$t.cnt.tiles" --json >"$S/$t.cnt.json"
    rc2=$?
    n=$(cnt "$S/$t.cnt.tiles" | wc -l)
    same=$(comm -12 <(cnt "$S/$t.cnt.tiles") <(cnt "$ref") | wc -l)
    check "fw/$t stream-count.elf (QEMU rc $rc, lt-stream rc $rc2): $same of $n tile reports carry the cycles and box/triangle tests the simulator reports as $m, exactly" \
        test "$rc" -eq 0 -a "$rc2" -eq 0 -a "$n" -gt 0 -a "$same" -eq "$n"
    # the model against the instructions QEMU executed for the same tiles (stream.elf's ticks:
    # 1 ns = 1 instruction under -icount shift=0); reported, not a pass criterion
    join <(awk '$1 == "tile" { print $2 "-" $3, $11 }' "$S/$t.tiles" | sort) \
         <(awk '$1 == "tile" { print $2 "-" $3, $13 }' "$ref" | sort) |
        awk -v t="$t" -v m="$m" '{ r = $3 / $2; s += r; n++; if (n == 1 || r < mn) mn = r; if (r > mx) mx = r; si += $2; sc += $3 }
             END { if (n) printf "   %s: %s model cycles / executed instructions per tile: all %d tiles %.3f (per tile %.3f..%.3f)\n", t, m, n, sc / si, mn, mx }'
done

echo "-- receiver and tool errors"
"$HOSTBIN/lt-stream" --hid 1209:0001 -q >"$S/e.txt" 2>&1
rc=$?
check "lt-stream --hid 1209:0001 with no device: exit 1, names it ($(head -n 1 "$S/e.txt" | cut -c 1-110))" \
    bash -c "[ $rc -eq 1 ] && grep -q 1209:0001 '$S/e.txt'"
"$HOSTBIN/lt-stream" --hid-path /dev/hidraw99 -q >"$S/e.txt" 2>&1
rc=$?
check "lt-stream --hid-path /dev/hidraw99: exit 1, names it" \
    bash -c "[ $rc -eq 1 ] && grep -q /dev/hidraw99 '$S/e.txt'"
"$HOSTBIN/lt-stream" --hid-path "$S/sim.bin" -q >"$S/e.txt" 2>&1
rc=$?
check "lt-stream --hid-path on a regular file: exit 1, says it is not a device node (not 'hidapi: Success')" \
    bash -c "[ $rc -eq 1 ] && grep -q 'not a HID device node (a regular file)' '$S/e.txt' && ! grep -q Success '$S/e.txt'"
"$HOSTBIN/lt-stream" --serial /dev/null -q >"$S/e.txt" 2>&1
rc=$?
check "lt-stream --serial /dev/null: exit 1, not a serial device" \
    bash -c "[ $rc -eq 1 ] && grep -q 'not a serial device' '$S/e.txt'"
"$HOSTBIN/lt-stream" --file /nonexistent.bin >"$S/e.txt" 2>&1
rc=$?
check "lt-stream --file /nonexistent.bin: exit 1, names it" \
    bash -c "[ $rc -eq 1 ] && grep -q /nonexistent.bin '$S/e.txt'"
"$HOSTBIN/lt-stream" --tcp >"$S/e.txt" 2>&1
check "lt-stream --tcp without a value: exit 2" test $? -eq 2
"$HOSTBIN/lt-faultinject" --rate 0.3 <"$S/sim.bin" >/dev/null 2>"$S/e.txt"
rc=$?
check "lt-faultinject --rate 0.3 (sum 1.5): exit 2 with the reason" \
    bash -c "[ $rc -eq 2 ] && grep -q 'sum' '$S/e.txt'"
"$SIMBIN/lt-stream-dev" --frames 0 >/dev/null 2>"$S/e.txt"
check "lt-stream-dev --frames 0: exit 2" test $? -eq 2
# the three programs parse options with the CLI's table parser (host/cli/lt_opt): the same
# messages (value, range, option named) and --help from the table
for p in "$HOSTBIN/lt-stream" "$HOSTBIN/lt-faultinject" "$SIMBIN/lt-stream-dev"; do
    "$p" --help >"$S/h.txt" 2>&1
    rc=$?
    check "$(basename $p) --help: exit 0, usage and options from the table" \
        bash -c "[ $rc -eq 0 ] && grep -q '^usage: $(basename $p)' '$S/h.txt' && grep -q 'exit status' '$S/h.txt'"
    "$p" --frobnicate >/dev/null 2>"$S/e.txt"
    rc=$?
    check "$(basename $p) --frobnicate: exit 2, names the option" \
        bash -c "[ $rc -eq 2 ] && grep -q -- \"unknown option '--frobnicate'\" '$S/e.txt'"
done
for c in "$HOSTBIN/lt-stream --baud 9600x:--baud 9600x" "$HOSTBIN/lt-stream --timeout nan:--timeout nan" \
    "$HOSTBIN/lt-faultinject --flips 9:1..8" "$HOSTBIN/lt-faultinject --seed -1:--seed -1" \
    "$HOSTBIN/lt-faultinject --drop 1e300:[0, 1]" "$SIMBIN/lt-stream-dev --cap 3:4..64" \
    "$SIMBIN/lt-stream-dev --link 1e6:--link 1e6"; do
    cmdline=${c%%:*} want=${c#*:}
    # shellcheck disable=SC2086
    $cmdline </dev/null >/dev/null 2>"$S/e.txt"
    rc=$?
    check "$(basename "${cmdline%% *}") ${cmdline#* }: exit 2 ($(head -n 1 "$S/e.txt" | cut -c 1-90))" \
        bash -c "[ $rc -eq 2 ] && grep -qF -- '$want' '$S/e.txt'"
done
"$HOSTBIN/lt-faultinject" --rate 0.1 --drop 0.5 --json "$S/rates.json" <"$S/sim.bin" >/dev/null 2>&1
check "lt-faultinject --rate 0.1 --drop 0.5: the later --drop wins ($(grep rates "$S/rates.json" | tr -d ' '))" \
    grep -q '"rates": \[0.5, 0.1, 0.1, 0.1, 0.1\]' "$S/rates.json"
"$HOSTBIN/lt-faultinject" --drop 0.5 --rate 0.1 --json "$S/rates.json" <"$S/sim.bin" >/dev/null 2>&1
check "lt-faultinject --drop 0.5 --rate 0.1: the later --rate wins ($(grep rates "$S/rates.json" | tr -d ' '))" \
    grep -q '"rates": \[0.1, 0.1, 0.1, 0.1, 0.1\]' "$S/rates.json"
# a replayed session (the same stream twice: HELLO after END) is a fault unless --sessions allows it
cat "$S/sim.bin" "$S/sim.bin" >"$S/twice.bin"
"$HOSTBIN/lt-stream" --file "$S/twice.bin" -q --json >"$S/twice.json" 2>&1
rc=$?
check "lt-stream on a session sent twice (HELLO after END): exit 1, 2 sessions, not clean (rc $rc)" \
    bash -c "[ $rc -eq 1 ] && [ \"$(jget sessions "$S/twice.json")\" = 2 ] && [ \"$(jget clean "$S/twice.json")\" = 0 ]"
"$HOSTBIN/lt-stream" --file "$S/twice.bin" -q --sessions 2 >/dev/null 2>&1
check "lt-stream --sessions 2 accepts the two sessions: exit 0" test $? -eq 0
head -c 5000 /dev/urandom | "$HOSTBIN/lt-stream" -q --json >"$S/rand.json"
rc=$?
check "random bytes: lt-stream exit 1, all $(jget garbage_bytes "$S/rand.json") bytes reported as garbage, no HELLO" \
    bash -c "[ $rc -eq 1 ] && [ \"$(jget garbage_bytes "$S/rand.json")\" = 5000 ] && [ \"$(jget have_hello "$S/rand.json")\" = 0 ]"
# CRC-valid records that contradict the HELLO or themselves (tests/stream/forge_frame.py): a
# tile index outside the image (TILE, IMAGE), a (frame, tile) reported twice, more rays than a
# tile's pixels, a summary of 65535 tiles, a 0x0 tile size. lt-stream took each as a clean stream
# (exit 0, "16 of 65535 tile reports received ... ok"); now exit 1, one line naming the frame's
# sequence number, the record and the limit, and the --tiles lines of every record received are
# still written. A TILE with a 0-byte payload and an input that ends inside a frame were exit 1
# with the summary only; now they have the same one line on stderr.
for k in "tile_out:tile index 999 outside the image: 16 tiles (64x64 in 16x16 tiles)" \
    "tile_twice:tile 0 of frame 0 reported a second time" \
    "rays:tile 0 of frame 0: 65535 rays, over the 256 pixels of a 16x16 tile" \
    "sum_tiles:frame 0: 65535 tiles traced, over the image's 16" \
    "hello_zero:image 64x64 in 0x0 tiles: sizes must be at least 1" \
    "image_out:tile index 999 outside the image: 16 tiles" \
    "tile_len0:a payload of 0 bytes that does not fit the type" \
    "cut:the input ends 30 bytes into a 64-byte frame, after frame seq"; do
    kind=${k%%:*}
    want=${k#*:}
    seq=$(python3 tests/stream/forge_frame.py "$S/sim.bin" "$S/forged-$kind.bin" "$kind")
    timeout 20 "$HOSTBIN/lt-stream" --file "$S/forged-$kind.bin" -q --tiles "$S/forged-$kind.tiles" \
        >"$S/forged-$kind.txt" 2>"$S/forged-$kind.err"
    rc=$?
    check "lt-stream on a forged record ($kind, seq $seq): exit 1, one line: $(head -n 1 "$S/forged-$kind.err")" \
        bash -c '[ "$1" -eq 1 ] && [ "$(wc -l <"$2")" -eq 1 ] && grep -qF "frame seq $3" "$2" && grep -qF -- "$4" "$2"' \
        _ "$rc" "$S/forged-$kind.err" "$seq" "$want"
    [ "$kind" = cut ] || [ "$kind" = tile_len0 ] ||
        check "lt-stream on a forged record ($kind): the --tiles lines of every record kept ($(wc -l <"$S/forged-$kind.tiles") of $(wc -l <"$S/sim.tiles"))" \
            test "$(wc -l <"$S/forged-$kind.tiles")" -eq "$(wc -l <"$S/sim.tiles")"
done
script -qec "'$HOSTBIN/lt-stream' --file '$S/sim.bin'" /dev/null >"$S/tty.txt" 2>&1
check "live line on a terminal (frames/s, bytes/s, rays/s, cycles/s)" \
    grep -q 'fr/s.*kB/s.*rays/s.*cycles/s' "$S/tty.txt"

echo "-- fault injection matrix (sim device, 16 frames; one fault at most per frame)"
"$SIMBIN/lt-stream-dev" --frames 16 --image-from 8 --out "$S/long.bin" 2>/dev/null
"$HOSTBIN/lt-faultinject" <"$S/long.bin" >"$S/f0.bin" 2>/dev/null
check "rates 0: output identical to input" cmp -s "$S/long.bin" "$S/f0.bin"
printf '   %-28s %4s | %5s %5s %5s %5s %5s | %5s %7s %5s %5s %7s %3s\n' "drop/corrupt/dup/reorder/trunc" \
    seed drop corr dup reord trunc lost damaged dup reord garbage end
for rates in "0.01 0 0 0 0" "0 0.01 0 0 0" "0 0 0.01 0 0" "0 0 0 0.01 0" "0 0 0 0 0.01" \
    "0.01 0.01 0.01 0.01 0.01" "0.05 0.05 0.05 0.05 0.05" "0.1 0.1 0.1 0.1 0.1"; do
    read -r r1 r2 r3 r4 r5 <<<"$rates"
    for seed in 1 2 3; do
        "$HOSTBIN/lt-faultinject" --drop "$r1" --corrupt "$r2" --dup "$r3" --reorder "$r4" \
            --trunc "$r5" --seed "$seed" --json "$S/truth.json" -q <"$S/long.bin" >"$S/f.bin"
        "$HOSTBIN/lt-stream" --file "$S/f.bin" -q --json >"$S/rx.json"
        rc=$?
        d=$(jget dropped "$S/truth.json"); c=$(jget corrupted "$S/truth.json")
        u=$(jget duplicated "$S/truth.json"); o=$(jget reordered "$S/truth.json")
        tr=$(jget truncated "$S/truth.json"); tail=$(jget tail_destroyed "$S/truth.json")
        db=$(jget damaged_bytes "$S/truth.json")
        lost=$(jget lost "$S/rx.json"); dmg=$(jget damaged "$S/rx.json")
        rdup=$(jget duplicates "$S/rx.json"); rreo=$(jget reordered "$S/rx.json")
        gb=$(jget garbage_bytes "$S/rx.json"); end=$(jget have_end "$S/rx.json")
        sent=$(jget sent "$S/rx.json"); recv=$(jget received "$S/rx.json")
        printf '   %-28s %4s | %5s %5s %5s %5s %5s | %5s %7s %5s %5s %7s %3s\n' "$rates" "$seed" \
            "$d" "$c" "$u" "$o" "$tr" "$lost" "$dmg" "$rdup" "$rreo" "$gb" "$end"
        faults=$((d + c + u + o + tr))
        want_rc=$([ "$faults" -gt 0 ] && echo 1 || echo 0)
        check "faults $rates seed $seed: lost $lost = $d+$c+$tr-$tail, dup $rdup = $u, reord $rreo = $o, garbage $gb = $db B, received+lost = sent, exit $rc" \
            test "$lost" -eq $((d + c + tr - tail)) -a "$rdup" -eq "$u" -a "$rreo" -eq "$o" \
            -a "$gb" -eq "$db" -a $((recv + lost)) -eq "$sent" -a "$dmg" -le $((c + tr)) \
            -a "$end" -eq $([ "$tail" -eq 0 ] && echo 1 || echo 0) -a "$rc" -eq "$want_rc"
    done
done
