#!/usr/bin/env bash
# qtcal.sh - the LT_MACHINE_QT rows of sim/machines/*.def: simulated cycles per source pixel of a
# quadtree reprojection (build + ray set-up + traversal) in each node format, on every machine.
# Calibration image: the shared Beachball EXR (911x876, 25% holes), reprojected to its own size
# after a move of 2% of the median depth to the right; the shared Trunks deep EXR (front-most
# samples) is measured the same way as an out-of-sample check of the formats' order. lanetrace
# info and reproject pick the cheaper of n64 and f32 (at equal accuracy) from these rows
# (host/tune/lt_recommend.c). Prints a table and the rows. Needs ../shared; make bench runs it.
# Usage: tests/bench/qtcal.sh [--write] [build/sim/lanetrace]; --write also puts the rows into
# the machine files (then `make` rebuilds what prices with them).
set -euo pipefail
cd "$(dirname "$0")/../.."
WRITE=0
if [ "${1:-}" = --write ]; then
    WRITE=1
    shift
fi
LT=${1:-build/sim/lanetrace}
SHARED=${LT_SHARED:-../shared}
BB=$SHARED/depth/beachball_singlepart.0001.exr
TR=$SHARED/depth/v2_LowResLeftView_Trunks_deep.exr
for f in "$BB" "$TR"; do
    if [ ! -f "$f" ]; then
        if [ "${CI:-}" = true ]; then echo "qtcal: FAIL: $f missing under CI" >&2; exit 1; fi
        echo "qtcal: SKIP: $f not found (the shared depth images live in ../shared)"
        exit 0
    fi
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
machines=$("$LT" machines | awk 'NR > 1 && /MHz/ { print $1 }')
# cost IMAGE MACHINE ENC [flags...]: cycles per source pixel, build and the rest
cost() {
    local img=$1 m=$2 e=$3
    shift 3
    "$LT" reproject --depth "$img" "$@" --move-rel 0.02,0,0 --machine "$m" --num "$e" --no-auto \
        --out "$tmp/o" -q --report "$tmp/r.json" >/dev/null
    python3 - "$tmp/r.json" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
px = d['pixels']
print('%.2f %.2f %.2f' % (d['total_cycles'] / px, d['build_cycles'] / px,
                          (d['total_cycles'] - d['build_cycles']) / px))
EOF
}
printf '%-8s %-4s %28s %28s\n' machine enc "beachball: total (build+rest)" "trunks: total (build+rest)"
for m in $machines; do
    for e in n64 n32 f32; do
        read -r bt bb br <<<"$(cost "$BB" "$m" "$e")"
        read -r tt tb trr <<<"$(cost "$TR" "$m" "$e" --deep-front)"
        printf '%-8s %-4s %12s (%s+%s) %12s (%s+%s)\n' "$m" "$e" "$bt" "$bb" "$br" "$tt" "$tb" "$trr"
        echo "$m $e $bb $br $bt $tt" >>"$tmp/rows"
    done
done
echo
echo "rows (the Beachball; paste into sim/machines/<machine>.def):"
awk '{ b[$1, $2] = $3; r[$1, $2] = $4; v[$1, $2] = $5; t[$1, $2] = $6
       if (!($1 in seen)) { seen[$1] = 1; order[++n] = $1 } }
     END {
         for (i = 1; i <= n; i++) {
             m = order[i]
             for (j = 1; j <= 3; j++) {
                 e = j == 1 ? "n64" : j == 2 ? "n32" : "f32"
                 printf "%-8s LT_MACHINE_QT(%s, %s, %s)\n", m, e, b[m, e], r[m, e]
             }
             same = (v[m, "n64"] < v[m, "f32"]) == (t[m, "n64"] < t[m, "f32"])
             printf "%-8s n64 vs f32 on the Trunks: %s\n", m, same ? "same order" : "ORDER DIFFERS"
         }
     }' "$tmp/rows"
if [ "$WRITE" = 1 ]; then
    while read -r m e b r _; do
        f=sim/machines/${m//-/_}.def
        grep -q "^LT_MACHINE_QT($e, " "$f" || { echo "qtcal: $f has no LT_MACHINE_QT($e, ...) row" >&2; exit 1; }
        sed -i "s/^LT_MACHINE_QT($e, .*/LT_MACHINE_QT($e, $b, $r)/" "$f"
    done <"$tmp/rows"
    echo "qtcal: wrote the rows into sim/machines/*.def"
fi
