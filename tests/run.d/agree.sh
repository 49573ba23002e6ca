# agree.sh - hit agreement with the double-precision reference on every shared scene (sourced by
# tests/run_tests.sh). build/host/lt-agree traces the benchmark view with the grid, kd-tree, BVH and
# quantised BVH in s15.16 and float32 and requires, per structure and path, >= 99.99% of pixels on
# the reference's triangle or at a depth tie, and every other difference explained as a ray within
# the path's error bound of a triangle border (tests/agree/lt_agree.c says how). The structures are
# compared with each other too. The bundled teapot always runs; the shared scenes run when
# ../shared exists (SKIP otherwise, FAIL under CI=true).
echo "== hit agreement with the double reference (lt-agree)"
agree_one() { # mesh, resolution
    if "$B/host/lt-agree" "$1" --res "$2" >"$tmp/agree.txt" 2>&1; then
        grep "^agree .* q16 \|^agree .* f32 " "$tmp/agree.txt" | grep -v " vs " | sed 's/^/  /'
        ok "agree $(basename "$1") ${2}x$2: $(grep -c ' pixels, + ' "$tmp/agree.txt") structure/path runs, 0 unexplained, >= 99.99% same or tie"
    else
        sed 's/^/  /' "$tmp/agree.txt"
        ko "agree $(basename "$1") ${2}x$2"
    fi
}
agree_one scenes/teapot.obj 128
shared_scenes=../shared/scenes
if [ -d "$shared_scenes" ]; then
    for s in bunny.obj:128 CornellBox-Original.obj:128 cornell_box.obj:128 dragon_res3.obj:128 \
        sibenik.obj:64 sponza.obj:64 conference.obj.gz:64 teapot.obj:128; do
        f="$shared_scenes/${s%%:*}"
        if [ -f "$f" ]; then
            agree_one "$f" "${s##*:}"
        elif [ "${CI:-}" = "true" ]; then
            ko "agree: shared scene missing under CI: $f"
        else
            echo "SKIP agree $f: not found"
        fi
    done
elif [ "${CI:-}" = "true" ]; then
    ko "agree: ../shared/scenes missing under CI"
else
    echo "SKIP agree on the shared scenes: ../shared/scenes not found (a fresh clone has no ../shared)"
fi
