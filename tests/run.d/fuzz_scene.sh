# fuzz_scene.sh - replay the scene-parser fuzz corpus under ASan + UBSan (no libFuzzer needed).
"$B/asan/fuzz-scene" tests/fuzz/corpus/scene >"$tmp/fuzz_scene.txt" 2>&1
check "fuzz-scene corpus replay: $(tail -1 "$tmp/fuzz_scene.txt")" test $? -eq 0
