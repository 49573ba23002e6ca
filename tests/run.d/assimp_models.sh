# assimp_models.sh - every model file of Debian's assimp-testmodels (assimp's own test models,
# /usr/share/assimp/models; tools/deps.sh installs the package) through `lanetrace-native info`:
# each loads (exit 0) or is refused with one line on stderr naming the file (exit 1); never a
# signal, never a hang (LT_IMPORT_TIMEOUT=30 per file, `timeout 60` around it), the whole walk
# under 180 s. "Model file": an extension assimp 5.2.5 lists (aiGetExtensionList), any case.
# Prints loaded / refused overall and per extension; docs/io.md has the totals. Without the
# package: SKIP (FAIL under CI=true). Sourced by tests/run_tests.sh ($B, $tmp, check/ok/ko).
echo "== assimp's test models (assimp-testmodels) through lanetrace info"
am_root=${LT_ASSIMP_MODELS:-/usr/share/assimp/models}
am_exts=" 3d 3ds 3mf ac ac3d acc amf ase ask assbin b3d blend bsp bvh cob csm dae dxf enff fbx glb
    gltf hmp ifc ifczip iqm irr irrmesh lwo lws lxo md2 md3 md5anim md5camera md5mesh mdc mdl mesh
    mot ms3d ndo nff obj off ogex pk3 ply pmx prj q3o q3s raw scn sib smd step stl stp ter uc vta x
    x3d x3db xgl xml zae zgl "
am_exts=" $(echo $am_exts) " # one blank between the names
if [ ! -d "$am_root" ]; then
    if [ "${CI:-}" = "true" ]; then
        ko "assimp-testmodels missing under CI ($am_root; tools/deps.sh installs it)"
    else
        echo "SKIP $am_root not found (apt-get install assimp-testmodels; tools/deps.sh does)"
    fi
else
    am_t0=$(date +%s)
    am_n=0 am_ok=0 am_ref=0 am_bad=0 am_crash=0 am_slow=0
    declare -A am_tot=() am_load=()
    while IFS= read -r -d '' am_f; do
        am_b=$(basename "$am_f" | tr 'A-Z' 'a-z')
        am_e=${am_b##*.}
        case "$am_exts" in *" $am_e "*) ;; *) continue ;; esac
        am_n=$((am_n + 1))
        am_tot[$am_e]=$((${am_tot[$am_e]:-0} + 1))
        LT_IMPORT_TIMEOUT=30 timeout 60 "$HOSTBIN/lanetrace-native" info "$am_f" \
            >"$tmp/am.out" 2>"$tmp/am.err" </dev/null
        am_rc=$?
        if [ $am_rc -eq 0 ] && grep -q ' triangles' "$tmp/am.out"; then
            am_ok=$((am_ok + 1))
            am_load[$am_e]=$((${am_load[$am_e]:-0} + 1))
        elif [ $am_rc -eq 1 ] && [ "$(wc -l <"$tmp/am.err")" -eq 1 ] &&
            [ "$(head -c ${#am_f} "$tmp/am.err")" = "$am_f" ]; then
            am_ref=$((am_ref + 1))
            grep -q 'the importer (assimp) crashed' "$tmp/am.err" && am_crash=$((am_crash + 1))
            grep -q 'did not finish within' "$tmp/am.err" && am_slow=$((am_slow + 1))
        else
            am_bad=$((am_bad + 1))
            echo "  BAD rc $am_rc ${am_f#"$am_root"/}: $(head -c 300 "$tmp/am.err" | tr '\n' '|')"
        fi
    done < <(find "$am_root" -type f -print0 | sort -z)
    am_s=$(($(date +%s) - am_t0))
    am_line=""
    for am_e in $(printf '%s\n' "${!am_tot[@]}" | sort); do
        am_line+=" $am_e ${am_load[$am_e]:-0}/${am_tot[$am_e]}"
    done
    echo "  loaded/files by extension:$am_line"
    echo "  $am_n model files: $am_ok loaded, $am_ref refused in one line naming the file" \
        "($am_crash of them assimp crashes caught in the importer process, $am_slow stopped at" \
        "the time limit), $am_bad otherwise (bound 0); ${am_s} s"
    check "assimp-testmodels: $am_n files, $am_ok loaded, $am_ref refused cleanly, 0 signals or hangs ($am_bad bad, ${am_s} s)" \
        test "$am_n" -gt 0 -a "$am_bad" -eq 0 -a "$am_s" -lt 180
fi
