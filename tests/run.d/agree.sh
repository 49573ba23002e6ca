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
    # the dragon at 256x256 had one pixel no bound explained (s15.16, pixel (60,72): two genuine
    # hits 0.0025 apart in depth, inside the path's depth error; the tie tolerance did not use the
    # path's depth bound) and, with Moller-Trumbore, edge cases (rays through cracks: 99.99x% same
    # triangle or tie). With the watertight default every structure and path is at 100%: the
    # verdict passes even with --min 100, with 0 edge and 0 unexplained pixels.
    f="$shared_scenes/dragon_res3.obj"
    if [ -f "$f" ]; then
        "$B/host/lt-agree" "$f" --res 256 --min 100 >"$tmp/agree256.txt" 2>&1
        rc=$?
        grep "^agree .* q16 \|^agree .* f32 " "$tmp/agree256.txt" | grep -v " vs \|single" | sed 's/^/  /'
        grep '^agree verdict' "$tmp/agree256.txt" | cut -c 1-200 | sed 's/^/  /'
        check "agree dragon_res3.obj 256x256 --min 100: 100% same triangle or tie, 0 edge, 0 unexplained in every structure and path" \
            bash -c "[ $rc -eq 0 ] && [ \$(grep -c '; 0 edge, 0 unexplained' '$tmp/agree256.txt') -eq 7 ] && ! grep -q 'unexplained pixel' '$tmp/agree256.txt'"
    fi
elif [ "${CI:-}" = "true" ]; then
    ko "agree: ../shared/scenes missing under CI"
else
    echo "SKIP agree on the shared scenes: ../shared/scenes not found (a fresh clone has no ../shared)"
fi
