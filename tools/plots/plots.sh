#!/usr/bin/env bash
# plots.sh SWEEP.csv OUTDIR - the PNG plots of `make plots` from a sweep CSV (tools/plots/sweep.sh):
# cycles per ray by phase, the error-vs-cycles trade, lane utilisation (all on lrb16), and the
# mcu-m4 vs lrb16 cycles per ray.
set -euo pipefail
csv=$1
out=$2
# label, path, cycles/ray, build, setup, traverse, intersect (per ray), rmse, utilisation %, machine
awk -F, 'NR > 1 { n = split($1, p, "/"); sub(/\.obj(\.gz)?$/, "", p[n]);
    printf "%s-%s,%s,%s,%g,%g,%g,%g,%s,%g,%s\n", p[n], $3, $3, $9, $16/$7, $17/$7, $18/$7, $19/$7,
        $14, 100*$11, $4 }' "$csv" >"$out/plotdata.csv"
grep ',lrb16$' "$out/plotdata.csv" >"$out/lrb16.csv"
grep ',mcu-m4$' "$out/plotdata.csv" >"$out/mcu.csv" || true
gnuplot -e "lrb='$out/lrb16.csv'; mcu='$out/mcu.csv'; out='$out'" tools/plots/plots.gp
ls "$out"/*.png
