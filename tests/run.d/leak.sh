# leak.sh - leaks through the whole pipeline (tests/leak/lt_leak.c, issue 11), sourced by
# tests/run_tests.sh: at 512x512, both numeric paths, every structure (chunks, bvh, bvhq, kd, grid;
# packets, single rays, any-hit shadow rays), the watertight default must let no ray through a
# closed mesh. The bundled scenes have no closed mesh; the shared bunny is closed (checked by the
# program), the shared dragon is not (non-manifold and inconsistently oriented edges: traced with
# --allow-open, only reference-confirmed front-face leaks count), and its 4x subdivision (~190K
# triangles, made in the program) runs without the chunks (a box per 16 triangles: minutes).
# Moller-Trumbore runs alongside on the bunny for the before/after figures (not asserted); the
# s15.16 grid test (--isect wt32, LT_ISECT_WT32) must be leak-free like the default.
echo "== leaks through closed meshes (lt-leak, 512x512)"
leak_one() { # name, args...
    local name=$1
    shift
    if "$B/host/lt-leak" "$@" >"$tmp/leak.txt" 2>&1; then
        grep -E "^leak .* wt(32)? " "$tmp/leak.txt" | awk '{n += 1; l += $(NF-1)} END {printf "  %d watertight runs (wt, wt32), %d leaks\n", n, l}'
        grep "^leak .* mt .* [1-9][0-9]* leaks" "$tmp/leak.txt" | sed 's/^/  (mt) /'
        ok "leak $name: 0 leaks (watertight)"
    else
        grep -v " 0 leaks" "$tmp/leak.txt" | sed 's/^/  /'
        ko "leak $name"
    fi
}
leak_shared=../shared/scenes
if [ -f "$leak_shared/bunny.obj" ]; then
    leak_one "bunny 512 all structures (wt, wt32; mt for comparison)" "$leak_shared/bunny.obj" --res 512 --isect all
    leak_one "dragon_res3 512 all structures" "$leak_shared/dragon_res3.obj" --res 512 --allow-open
    leak_one "dragon_res3 x4 subdivided 512 (wt, wt32; mt for comparison)" "$leak_shared/dragon_res3.obj" \
        --res 512 --allow-open --subdiv 1 --structures bvh,bvhq,kd,grid --isect all
elif [ "${CI:-}" = "true" ]; then
    ko "leak: shared scenes missing under CI: $leak_shared"
else
    echo "SKIP leak: $leak_shared not found"
fi
"$B/host/lt-leak" scenes/teapot.obj --res 16 >"$tmp/leak.txt" 2>&1
check "lt-leak refuses an open mesh (teapot: 64 boundary edges)" grep -q "NOT CLOSED" "$tmp/leak.txt"
