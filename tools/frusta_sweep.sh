#!/usr/bin/env bash
# frusta_sweep.sh - the multi-frusta reduction sweep of docs/frusta.md ("Reduction sweep"): for
# every shared scene (and a 4x-subdivided copy of the shared dragon, written to build/sweep/), at
# each resolution, `lanetrace shadows --no-ref` in the simulator (lrb16), s15.16 and float32 with
# the default culling and s15.16 with the paper's set (bcr: no leaf culling, no split); one
# Markdown row per run: P reduction without (with) shading, S reduction (all stages), the shadow
# stage alone, and whether frusta = packets on every pixel (primary hits and shadow bits). The
# culling column is the set the run used (the scene line of its output).
# Usage: tools/frusta_sweep.sh [RES ...]   (default 256 512 1024; SHARED=../shared, B=build)
# Needs build/sim/lanetrace (make) and ../shared/scenes; takes about 15 minutes at the defaults.
set -euo pipefail
B=${B:-build}
SHARED=${SHARED:-../shared}
LT="$B/sim/lanetrace"
res=("$@")
[ ${#res[@]} -gt 0 ] || res=(256 512 1024)
[ -x "$LT" ] || { echo "frusta_sweep: $LT missing (run make)" >&2; exit 1; }
[ -d "$SHARED/scenes" ] || { echo "frusta_sweep: $SHARED/scenes missing" >&2; exit 1; }
mkdir -p "$B/sweep"
d4="$B/sweep/dragon_res3_subdiv4.obj"
if [ ! -s "$d4" ]; then
    # 4-to-1 midpoint subdivision of every triangle (shared midpoints are the same point)
    python3 - "$SHARED/scenes/dragon_res3.obj" "$d4" <<'PY'
import sys
V, F, mid = [], [], {}
for line in open(sys.argv[1]):
    p = line.split()
    if p and p[0] == 'v':
        V.append(tuple(map(float, p[1:4])))
    elif p and p[0] == 'f':
        ix = [int(x.split('/')[0]) for x in p[1:]]
        ix = [i - 1 if i > 0 else len(V) + i for i in ix]
        F += [(ix[0], ix[k], ix[k + 1]) for k in range(1, len(ix) - 1)]
def m(a, b):
    k = (min(a, b), max(a, b))
    if k not in mid:
        mid[k] = len(V)
        V.append(tuple(0.5 * (V[a][i] + V[b][i]) for i in range(3)))
    return mid[k]
with open(sys.argv[2], 'w') as out:
    G = []
    for a, b, c in F:
        ab, bc, ca = m(a, b), m(b, c), m(c, a)
        G += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    for v in V:
        out.write("v %.9g %.9g %.9g\n" % v)
    for t in G:
        out.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))
PY
fi
meshes=("$SHARED/scenes/bunny.obj" "$SHARED/scenes/dragon_res3.obj" "$d4" "$SHARED/scenes/sibenik.obj"
        "$SHARED/scenes/sponza.obj" "$SHARED/scenes/conference.obj.gz")
echo "| scene | res | path | culling (shadow / primary) | P reduction (with shading) | S reduction | shadow stage alone | frusta = packets |"
echo "|---|---:|---|---|---|---|---|---|"
for r in "${res[@]}"; do
    for m in "${meshes[@]}"; do
        for v in "q16 default" "f32 default" "q16 bcr"; do
            set -- $v
            cull=()
            [ "$2" = default ] || cull=(--cull "$2" --pcull "$2")
            out=$("$LT" shadows --mesh "$m" --res "$r" --no-ref --num "$1" "${cull[@]}" 2>&1) ||
                { echo "frusta_sweep: $m $r $v failed" >&2; exit 1; }
            used=$(grep -oE 'culling [a-z]+, primary culling [a-z]+' <<<"$out" | awk '{sub(",", "", $2); print $2 " / " $5}')
            p=$(grep '^P Reduction' <<<"$out" | grep -oE '[0-9.]+x \([0-9.]+x\)' | head -1)
            s=$(grep '^S Reduction' <<<"$out" | grep -oE '[0-9.]+x +\(paper' | grep -oE '^[0-9.]+x')
            a=$(grep '^S shadows only' <<<"$out" | grep -oE '[0-9.]+x +\(shadow' | grep -oE '^[0-9.]+x')
            eq=$(grep -c ' (0 differ)' <<<"$out" || true)
            echo "| $(basename "$m") | $r | $1 | $used | $p | $s | $a | $([ "$eq" = 2 ] && echo yes || echo NO) |"
        done
    done
done
echo
echo "lanetrace $(git rev-parse --short HEAD 2>/dev/null || echo '?'), $("$LT" shadows --help >/dev/null 2>&1; echo lrb16 at 1000 MHz, one core), $(date -u +%Y-%m-%d)"
