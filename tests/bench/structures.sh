#!/usr/bin/env bash
# structures.sh - the lectures' comparison (Stamminger & Grosso 2020 [Stamminger20], Bikker 2016
# [Bikker16]; docs/bibliography.md) measured: uniform grid vs kd-tree vs BVH (and the chunk scene
# and quantised BVH) on real scenes, in the simulator (lrb16), both numeric paths: build cycles,
# structure memory, trace cycles per ray, nodes / AABB tests / triangle tests per ray (the columns
# of Table 1 of Benthin & Wald 2009 [Benthin09]), L1 hit rate, lane utilisation, accuracy.
set -euo pipefail
B=${B:-build}
RES=${STRUCT_RES:-128}
scenes=(scenes/teapot.obj)
for s in bunny.obj CornellBox-Original.obj dragon_res3.obj; do
    [ -f "../shared/scenes/$s" ] && scenes+=("../shared/scenes/$s")
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '%-22s %-6s %-4s %12s %10s %9s %8s %8s %8s %7s %6s %8s\n' scene struct path build_cyc bytes \
    cyc/ray nodes/r aabb/r tris/r L1hit% util% same_id%
for s in "${scenes[@]}"; do
    for st in grid kd bvh bvhq chunks; do
        # the chunk scene is linear in the triangles: skip it on big meshes
        [ "$st" = chunks ] && [ "$(basename "$s")" = dragon_res3.obj ] && continue
        nm=both
        [ "$st" = bvhq ] && nm=q16
        "$B/sim/lanetrace" run --mesh "$s" --structure $st --num $nm --res "$RES" --csv "$tmp/c.csv" -q \
            >/dev/null
        tail -n +2 "$tmp/c.csv" | awk -F, -v sc="$(basename "$s" .obj)" -v st=$st '{
            printf "%-22s %-6s %-4s %12d %10d %9.1f %8.2f %8.2f %8.2f %7.2f %6.1f %8.3f\n",
                sc, st, $3, $16, $25, ($8 - $16) / $7, $22, $23, $24, $21, 100 * $11, $13 }'
    done
done
