#!/usr/bin/env bash
# seeds.sh - gather the seed inputs of every fuzz target into $B/fuzz/corpus-<target>/ (the
# working corpora that `make fuzz-<target>` grows and `make fuzz-merge` minimises into
# tests/fuzz/corpus/<target>/): real files of the repository, of assimp-testmodels and of
# ../shared (small ones, or the first 16 KiB of large ones), files written by seeds_exr.c, and
# small crafted ones. Run by `make fuzz-seeds`; not part of make test. Needs $B/fuzz/seeds-exr.
set -euo pipefail
B=${B:-build}
A=/usr/share/assimp/models
S=../shared
d() { mkdir -p "$B/fuzz/corpus-$1"; echo "$B/fuzz/corpus-$1"; }
cp_small() { # target, max bytes, files...
    local t=$1 max=$2 f
    shift 2
    for f in "$@"; do
        [ -f "$f" ] || continue
        if [ "$(stat -c %s "$f")" -le "$max" ]; then
            cp "$f" "$(d "$t")/seed-$(basename "$(dirname "$f")")-$(basename "$f")"
        else
            head -c 16384 "$f" >"$(d "$t")/seed-head16k-$(basename "$f")"
        fi
    done
}

# EXR: every shape from seeds_exr.c; the shared depth files' first 16 KiB (header, chunk table)
"$B/fuzz/seeds-exr" "$(d exr)" >/dev/null
cp_small exr 16384 "$S"/depth/*.exr

# OBJ and gzip: the bundled teapot (and gzip'd), assimp's small OBJ files, crafted lines
shopt -s nullglob
cp_small mesh 8192 "$A"/OBJ/*.obj "$A"/invalid/*.obj
o=$(d mesh)
head -c 4096 scenes/teapot.obj >"$o/seed-teapot-head.obj"
gzip -9c scenes/teapot.obj | head -c 8192 >"$o/seed-teapot-trunc.obj.gz"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' | gzip -9c >"$o/seed-tri.obj.gz"
{ printf 'v 0 0 0\nv 1 0 0\n' | gzip -c; printf 'v 0 1 0\nf -3 -2 -1\n' | gzip -c; } >"$o/seed-two-members.obj.gz"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2//1 3/1\n  f -1 -2 -3\n' >"$o/seed-refs.obj"
printf 'v 1e200 0 0\nv 0 nan 0\nv 1 2\nf 1 2 3 # c\n' >"$o/seed-bad-values.obj"

# PLY, OFF, STL (lt_meshcheck): assimp's small files, crafted binary ones
cp_small meshcheck 8192 "$A"/PLY/*.ply "$A"/OFF/*.off "$A"/STL/*.stl "$A"/invalid/*.off \
    "$A"/invalid/*.ply
m=$(d meshcheck)
ply_bin() { # format, vertex bytes, face bytes
    printf 'ply\nformat %s 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n' "$1"
    printf "$2"
    printf "$3"
}
z4='\0\0\0\0'; o4='\0\0\200\77'; o4b='\77\200\0\0'
ply_bin binary_little_endian "$z4$z4$z4$o4$z4$z4$z4$o4$z4" '\3\0\0\0\0\1\0\0\0\2\0\0\0' >"$m/seed-le.ply"
ply_bin binary_big_endian "$z4$z4$z4$o4b$z4$z4$z4$o4b$z4" '\3\0\0\0\0\0\0\0\1\0\0\0\2' >"$m/seed-be.ply"
{ head -c 80 /dev/zero; printf '\1\0\0\0'; head -c 48 /dev/zero; printf '\0\0'; } >"$m/seed-bin.stl"
printf 'OFF\n# c\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n4 0 1 3 2 255 0 0\n' >"$m/seed-colour.off"
printf 'COFF\n3 1 3\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n3 0 1 2\n' >"$m/seed-coff.off"

# scene JSON: the committed corpus is the seed; the bundled scenes
cp_small scene 4096 scenes/*.json

# stream frames: the committed corpus is the seed

# cache specs: "L1\nL2\n<accesses>"
c=$(d cache)
printf '64:8:64\n512:8:64\n\0\0\0\0\100\0\0\0\20\0\10\1' >"$c/seed-l1-l2"
printf '1:1:4\n1:64:4096\nAAAAAABBBBBB' >"$c/seed-limits"
printf '63:8:64' >"$c/seed-not-pow2"
printf '64:8:64:1\n4294967296:1:4\n' >"$c/seed-extra-overflow"
printf '16384:64:64\n:8:64\n' >"$c/seed-max-empty"

# option lists: NUL/newline separated arguments
p=$(d opt)
printf -- '--req\nx\n--int\n42\n--dbl\n0.25\n--vec\n1,2,3\n--res\n64x32\n--num\nf32\n--pair\n1:2\nA\nB' >"$p/seed-all"
printf -- '--req\nx\n--old-vec4\n1,2,3,4\n--open\n1e-300\n--flag\n--no-set\n--hidden\n-n\nboth' >"$p/seed-alias"
printf -- '--int\n1e9\n' >"$p/seed-int-1e9"
printf -- '--vec\nnan,0,0\n' >"$p/seed-vec-nan"
printf -- '--res\n0\n' >"$p/seed-res-0"
printf -- '--help' >"$p/seed-help"
printf -- '--req' >"$p/seed-missing"
for t in exr mesh meshcheck scene cache opt; do
    echo "seeds: $t: $(ls "$B/fuzz/corpus-$t" | wc -l) files in $B/fuzz/corpus-$t"
done
