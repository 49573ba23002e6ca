# meshin.sh - meshes assimp must not be trusted with, through the CLI (sourced by tests/run_tests.sh;
# $B, $tmp, check/ok/ko). Files made here: a PLY cut in its header (assimp spun forever), a binary
# PLY cut in its body (SIGSEGV inside assimp), ASCII PLY and OFF cut short (ai_assert in
# TriangulateProcess: SIGABRT), an OFF cut in its last face (fewer triangles, no word), a PLY header
# declaring 4e9 vertices (~48 GB asked for), a binary STL whose triangle count passes its end; an
# OpenGEX scene whose light has no node (ai_assert in PretransformVertices: SIGABRT, loads now), a
# crafted HL1 MDL header (SIGSEGV inside assimp: isolated in the importer process) and an LWS scene
# assimp never finishes (stopped by LT_IMPORT_TIMEOUT). Each must end in bounded time with exit 1
# and one line on stderr naming the file, or load; never a signal. docs/io.md.
echo "== mesh input checks and the importer process"
mi_dir="$tmp/meshin"
mkdir -p "$mi_dir"
python3 - "$mi_dir" <<'EOF'
import struct, sys
d = sys.argv[1]
def w(name, data):
    open(d + "/" + name, "wb").write(data if isinstance(data, bytes) else data.encode())
hdr = ("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
       "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n")
ply = hdr + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n"
w("ok.ply", ply)
w("cut_header.ply", ply[:60])
w("cut_ascii.ply", ply[:-4])
w("huge.ply", ply.replace("vertex 4\n", "vertex 4000000000\n"))
b = hdr.replace("ascii", "binary_little_endian").encode()
b += b"".join(struct.pack("<3f", *v) for v in [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)])
b += b"".join(struct.pack("<B3i", 3, *f) for f in [(0, 1, 2), (0, 2, 3)])
w("ok_le.ply", b)
w("cut_body.ply", b[:len(b) - 46])
off = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n3 0 2 3\n"
w("ok.off", off)
w("cut_header.off", off[:10])
w("cut_face.off", off[:-3])
tri = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0)
w("ok.stl", b"binary".ljust(80, b" ") + struct.pack("<I", 2) + tri * 2)
w("count.stl", b"binary".ljust(80, b" ") + struct.pack("<I", 1000) + tri * 2)
w("lamp.ogex",
  'GeometryNode $node1 {Name {string {"Tri"}} ObjectRef {ref {$geometry1}}}\n'
  'LightNode $node2 {Name {string {"Lamp"}} ObjectRef {ref {$light1}}}\n'
  'GeometryObject $geometry1 {Mesh (primitive = "triangles") {\n'
  '  VertexArray (attrib = "position") {float[3] {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}}}\n'
  '  IndexArray {unsigned_int32[3] {{0, 1, 2}}}}}\n'
  'LightObject $light1 (type = "point") {Color (attrib = "light") {float[3] {{1.0, 1.0, 1.0}}}}\n')
m = b"IDST" + struct.pack("<i", 10) + b"crash".ljust(64, b"\0") + struct.pack("<i", 244)
m += struct.pack("<15f", *([0.0] * 15)) + struct.pack("<i", 0)
m += struct.pack("<26i", *([1, 0x40000000] * 13))
w("crash.mdl", m)
w("hang.lws", "LWSC\n2\n\nLoadObject x.lwo\nObjectMotion (unnamed)\n  9\n  3\n  0 0 2 0 0 0\n")
EOF
mi_run() { # seconds limit, command... -> $mi_rc, $mi_s (elapsed), $tmp/mi.out, $tmp/mi.err
    local lim=$1 t0
    shift
    t0=$(date +%s%N)
    timeout "$lim" "$@" >"$tmp/mi.out" 2>"$tmp/mi.err"
    mi_rc=$?
    mi_s=$((($(date +%s%N) - t0) / 1000000))
}
mi_refused() { # file, pattern: exit 1, one stderr line naming the file with the pattern, < 10 s
    local f="$mi_dir/$1" pat=$2 how
    for how in "sim run" "native info" "native render"; do
        case $how in
        "sim run") mi_run 60 "$SIMBIN/lanetrace" run --mesh "$f" --res 8 -q ;;
        "native info") mi_run 60 "$HOSTBIN/lanetrace-native" info "$f" ;;
        "native render") mi_run 60 "$HOSTBIN/lanetrace-native" render --mesh "$f" --res 8 --out "$tmp/mi_r" ;;
        esac
        if [ "$mi_rc" -eq 1 ] && [ "$(wc -l <"$tmp/mi.err")" -eq 1 ] && [ "$mi_s" -lt 10000 ] &&
            grep -q "^$f: .*$pat" "$tmp/mi.err"; then
            ok "$how $1: exit 1 in ${mi_s} ms: $(cut -c1-160 "$tmp/mi.err" | sed "s|^$mi_dir/||")"
        else
            ko "$how $1 (rc $mi_rc, ${mi_s} ms, want 1 and '$pat'; stderr: $(head -c 300 "$tmp/mi.err"))"
        fi
    done
}
for mi_f in ok.ply ok_le.ply ok.off ok.stl lamp.ogex; do
    mi_run 60 "$HOSTBIN/lanetrace-native" info "$mi_dir/$mi_f"
    check "info $mi_f loads ($(head -1 "$tmp/mi.out" | sed "s|^$mi_dir/||"))" \
        bash -c "[ $mi_rc -eq 0 ] && grep -q ' triangles' '$tmp/mi.out'"
done
mi_refused cut_header.ply "without 'end_header' (truncated?)"
mi_refused cut_body.ply "header declares 4 vertices; the file's [0-9]* bytes hold at most 2"
mi_refused cut_ascii.ply "face 2 of 2 ends after 2 values"
mi_refused huge.ply "header declares 4000000000 vertices; the file's 203 bytes hold at most 6"
mi_refused cut_header.off "header declares 4 vertices"
mi_refused cut_face.off "face 2 of 2 lists 2 of its 3 vertex indices"
mi_refused count.stl "header declares 1000 triangles; the file's 184 bytes hold at most 2"
# the OpenGEX light without a node: every program that loads meshes
mi_run 60 "$SIMBIN/lanetrace" run --mesh "$mi_dir/lamp.ogex" --res 8 -q
check "run lamp.ogex (aborted in PretransformVertices before): exit 0 (rc $mi_rc)" test "$mi_rc" -eq 0
mi_run 60 "$HOSTBIN/lanetrace-native" render --mesh "$mi_dir/lamp.ogex" --res 8 --out "$tmp/mi_lamp"
check "render lamp.ogex: exit 0 (rc $mi_rc)" test "$mi_rc" -eq 0
if [ -x "$B/host/lt-agree" ]; then
    mi_run 120 "$B/host/lt-agree" "$mi_dir/lamp.ogex" --res 16
    check "lt-agree lamp.ogex: exit 0 (rc $mi_rc)" test "$mi_rc" -eq 0
fi
# inside assimp: a crash and a hang, each contained in the importer process
mi_refused crash.mdl "the importer (assimp) crashed (signal 11, SIGSEGV) on this file\|not a readable mesh"
mi_run 60 env LT_IMPORT_TIMEOUT=2 "$HOSTBIN/lanetrace-native" info "$mi_dir/hang.lws"
if [ "$mi_rc" -eq 1 ] && [ "$mi_s" -lt 5000 ] && [ "$(wc -l <"$tmp/mi.err")" -eq 1 ] &&
    grep -q "^$mi_dir/hang.lws: " "$tmp/mi.err"; then
    ok "info hang.lws with LT_IMPORT_TIMEOUT=2: exit 1 in ${mi_s} ms: $(sed "s|^$mi_dir/||" "$tmp/mi.err")"
else
    ko "info hang.lws with LT_IMPORT_TIMEOUT=2 (rc $mi_rc, ${mi_s} ms; stderr: $(head -c 300 "$tmp/mi.err"))"
fi
mi_run 60 env LT_IMPORT_TIMEOUT=soon "$HOSTBIN/lanetrace-native" info "$mi_dir/ok.ply"
check "a bad LT_IMPORT_TIMEOUT is an error naming it (rc $mi_rc)" \
    bash -c "[ $mi_rc -eq 1 ] && grep -q \"LT_IMPORT_TIMEOUT='soon'\" '$tmp/mi.err'"
