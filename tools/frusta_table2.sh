#!/usr/bin/env bash
# frusta_table2.sh - the paper's Table 2 ([Benthin09] section 5.3: techniques that shrink frusta)
# reproduced in the simulator (lrb16), plus this project's two additions, for the S-Frusta shadow
# stage alone: `lanetrace shadows --only frusta --prim frusta --report` per culling set, reading
# the stage's events (TRI_FETCH = #tris accessed, TRI_KEPT = after culling, AABB = #AABB tests,
# TRIS = #isec tests) and cycles. Rows: the paper's "No Shrink." (b c: back-face and corner-ray
# culling), "Ray-AABB" (+ l: each frustum's own rays against the leaf's box), "CR" (+ r: corner
# rays recomputed after a leaf that occluded rays), "FS" (+ f: CR that also shrinks the direction
# intervals the traversal tests boxes with), and "+ split" (+ s: wide frusta go on as packets),
# "256-ray packets" (+ p: the walk's box tests done by the 16 frusta's rays as 16 packets, the
# paper's section 5.3 comparison), the defaults without FS (b c r l s), without the packet walks'
# triangle-parallel leaves (b c r f l s) and the default (b c r f l s t);
# percentages against No Shrink., as the paper prints them.
# Usage: tools/frusta_table2.sh [RES] [MESH ...]   (default 512; the shared Sibenik, Sponza,
# Conference and dragon; SHARED=../shared, B=build)
set -euo pipefail
B=${B:-build}
SHARED=${SHARED:-../shared}
LT="$B/sim/lanetrace"
res=${1:-512}
[ $# -gt 0 ] && shift
meshes=("$@")
[ ${#meshes[@]} -gt 0 ] || meshes=("$SHARED/scenes/sibenik.obj" "$SHARED/scenes/sponza.obj"
                                   "$SHARED/scenes/conference.obj.gz" "$SHARED/scenes/dragon_res3.obj")
[ -x "$LT" ] || { echo "frusta_table2: $LT missing (run make)" >&2; exit 1; }
variants=("bc:No Shrink. (b c)" "bcl:Ray-AABB (b c l)" "bcr:CR (b c r)" "bcrf:FS (b c r f)"
          "bcs:split (b c s)" "bcp:256-ray packets (b c p)"
          "bcrls:without FS (b c r l s)" "bcrfls:without t (b c r f l s)"
          "bcrflst:default (b c r f l s t)")
pct() { awk -v a="$1" -v b="$2" 'BEGIN { if (b == 0) print "-"; else printf "%+.1f%%", 100 * (a - b) / b }'; }
echo "| scene | variant | #tris accessed / +culling | #AABB tests | #isec tests | cycles | vs No Shrink. (#tris / +culling, #AABB, #isec, cycles) |"
echo "|---|---|---|---|---|---|---|"
for m in "${meshes[@]}"; do
    base=()
    for v in "${variants[@]}"; do
        c=${v%%:*}
        out=$("$LT" shadows --mesh "$m" --res "$res" --no-ref --only frusta --prim frusta \
            --cull "$c" --report 2>&1) || { echo "frusta_table2: $m $c failed" >&2; exit 1; }
        blk=$(awk '/^== cycle report: S-Frusta shadow stage/{f=1} f&&/^events/{print; exit}' <<<"$out")
        cyc=$(awk '/^== cycle report: S-Frusta shadow stage/{f=1} f&&/^total/{print $2; exit}' <<<"$out")
        ev() { grep -oE " $1=[0-9]+" <<<"$blk" | cut -d= -f2; }
        tf=$(ev TRI_FETCH) tk=$(ev TRI_KEPT) ab=$(ev AABB) is=$(ev TRIS)
        [ ${#base[@]} -gt 0 ] || base=("$tf" "$tk" "$ab" "$is" "$cyc")
        echo "| $(basename "$m") | ${v#*:} | $tf / $tk | $ab | $is | $cyc | $(pct "$tf" "${base[0]}") / $(pct "$tk" "${base[1]}"), $(pct "$ab" "${base[2]}"), $(pct "$is" "${base[3]}"), $(pct "$cyc" "${base[4]}") |"
    done
done
echo
echo "lanetrace $(git rev-parse --short HEAD 2>/dev/null || echo '?'), ${res}x${res}, s15.16, lrb16 at 1000 MHz, one core, $(date -u +%Y-%m-%d)"
