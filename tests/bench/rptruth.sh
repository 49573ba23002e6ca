#!/usr/bin/env bash
# rptruth.sh - view synthesis against ray-traced ground truth (docs/reproject.md section 5): for
# each mesh scene, `lanetrace render` writes a 2-layer depth image from the scene's camera (source
# numeric path s15.16 or float32); `lanetrace reproject --truth` synthesises moved views in the
# simulator (lrb16) and compares their depth with the target view rendered by the object-space
# tracer. Three tables: every numeric configuration (s15.16 source with each node encoding n64,
# n32, f32, and float32 throughout) x two views; the build threshold lambda_h; the quadtree vs
# the DDA and Hi-Z baselines on the same rays. Columns: cycles per pixel, traced pixels with the
# wrong hit/miss, relative depth error (median, RMSE, within RP_TOL, max), inpainted share.
# Run from the repository root after make all.
# Environment: B (build dir), RP_RES (default 256), RP_TOL (default 0.01), RP_SCENES (mesh paths).
set -euo pipefail
B=${B:-build}
RES=${RP_RES:-256}
TOL=${RP_TOL:-0.01}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

scenes=${RP_SCENES:-"$PWD/scenes/teapot.obj"}
if [ -z "${RP_SCENES:-}" ]; then
    for m in bunny.obj CornellBox-Original.obj sponza.obj; do
        if [ -f "../shared/scenes/$m" ]; then
            scenes="$scenes $(cd ../shared/scenes && pwd)/$m"
        else
            echo "(../shared/scenes/$m missing: skipped)"
        fi
    done
fi
# views: target = source moved (units of the median depth) and turned (yaw, pitch, roll degrees)
views=("0.05,0,0 -2,0,0" "0.15,0.05,0 -6,2,0")

# jget KEY FILE: a number from lanetrace's pretty-printed --json output (keys are unique)
jget() { awk -F':' -v k="\"$1\"" '{g = $1; gsub(/[ \t]/, "", g)} g == k {v = $2; gsub(/[ \t,]/, "", v); print v; exit}' "$2"; }

hdr() { printf '%-20s %-3s %-3s %-18s %-8s %6s %7s %6s %7s %8s %9s %8s %7s %7s\n' scene src enc "view" "$1" \
    "bld/px" "cyc/px" "hit%" "wrong%" "median%" "relRMSE%" "within%" "maxrel%" "inpnt%"; }
# row NAME SRC ENC MOVE ROT LABEL [extra reproject flags]: one synthesised view against the truth
row() {
    local n=$1 s=$2 e=$3 mv=$4 rt=$5 lab=$6
    shift 6
    "$B/sim/lanetrace" reproject "$tmp/s.json" --depth "$tmp/d.exr" --layers 2 --move-rel "$mv" \
        --rot "$rt" --num $e --truth --truth-tol "$TOL" --json "$@" >"$tmp/o.json"
    awk -v n="$n" -v s=$s -v e=$e -v vw="$mv/$rt" -v lab="$lab" -v px="$(jget pixels "$tmp/o.json")" \
        -v cyc="$(jget cycles_per_ray "$tmp/o.json")" -v hit="$(jget hit "$tmp/o.json")" \
        -v kn="$(jget known_pixels "$tmp/o.json")" -v sp="$(jget spurious_hits "$tmp/o.json")" \
        -v mi="$(jget missed_hits "$tmp/o.json")" -v ch="$(jget common_hits "$tmp/o.json")" \
        -v wi="$(jget within_tolerance "$tmp/o.json")" -v rr="$(jget relative_rmse "$tmp/o.json")" \
        -v md="$(jget relative_p50 "$tmp/o.json")" -v mr="$(jget max_relative "$tmp/o.json")" \
        -v ip="$(jget inpainted "$tmp/o.json")" -v bc="$(jget build_cycles "$tmp/o.json")" \
        -v sw="$(jget source_width "$tmp/o.json")" -v sh="$(jget source_height "$tmp/o.json")" \
        'BEGIN{printf "%-20s %-3s %-3s %-18s %-8s %6.1f %7.1f %6.2f %7.3f %8.4f %9.3f %8.2f %7.1f %7.2f\n",
            n, s, e, vw, lab, bc/(sw*sh), cyc, 100*hit/px, 100*(sp+mi)/(kn>0?kn:1), 100*md, 100*rr,
            100*wi/(ch>0?ch:1), 100*mr, 100*ip/px}'
}

# scene_json MESH: $tmp/s.json names the mesh; $name = its base name
scene_json() {
    name=$(basename "$1")
    name=${name%%.*}
    printf '{"mesh": "%s"}\n' "$1" >"$tmp/s.json"
}

echo "-- numeric configurations (source render path x node encoding), default build thresholds"
hdr "-"
for mesh in $scenes; do
    scene_json "$mesh"
    for src in q16 f32; do
        "$B/host/lanetrace-native" render "$tmp/s.json" --res "$RES" --layers 2 --num $src \
            --out "$tmp/d" -q
        encs="n64 n32 f32"
        [ $src = f32 ] && encs=f32 # the all-float32 configuration
        for v in "${views[@]}"; do
            set -- $v
            for enc in $encs; do
                row "$name" $src $enc "$1" "$2" -
            done
        done
    done
done
# the threshold and tracer tables share one s15.16 render per scene and the first view
for mesh in $scenes; do
    scene_json "$mesh"
    "$B/host/lanetrace-native" render "$tmp/s.json" --res "$RES" --layers 2 --out "$tmp/d" -q
    set -- ${views[0]}
    for lh in 1e-3 1e-2 1e-1 1; do
        row "$name" q16 n64 "$1" "$2" $lh --lambda-h $lh >>"$tmp/lambda.txt"
    done
    for t in quadtree dda hiz; do
        for enc in n64 f32; do
            row "$name" q16 $enc "$1" "$2" $t --tracer $t >>"$tmp/tracers.txt"
        done
    done
    row "$name" q16 n64 "$1" "$2" "qt,l.1" --lambda-h 0.1 >>"$tmp/tracers.txt"
done
echo "-- the slope threshold lambda_h (docs/quadtree.md section 6; the supplement's 1e-3 is the"
echo "   default): s15.16 source, n64, the first view"
hdr "lam_h"
cat "$tmp/lambda.txt"
echo "-- the screen-space tracers on the same rays: quadtree vs DDA (McGuire & Mara) vs Hi-Z"
echo "   (Uludag), thickness 1/64 for the baselines; s15.16 source, the first view; n64 = s1.30 rays"
hdr "tracer"
cat "$tmp/tracers.txt"
echo "bld/px: build cycles per source pixel (quadtree, Hi-Z pyramid; the DDA has none); cyc/px:"
echo "setup + traversal cycles per target pixel; hit%: pixels the tracer traced to a surface;"
echo "wrong%: traced pixels (hit or background) whose hit/miss differs from the ground truth;"
echo "median/relRMSE/within/maxrel: relative depth error over the pixels both hit (within:"
echo "|z - z_true| <= $TOL z_true); inpnt%: disoccluded or entered from outside the source view"
echo "(inpainted, not counted as traced). Views: --move-rel / --rot. qt,l.1: the quadtree with"
echo "--lambda-h 0.1."
