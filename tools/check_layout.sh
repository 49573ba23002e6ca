#!/usr/bin/env bash
# check_layout.sh - the rooms' rules (docs/architecture.md), checked on the tracked tree:
#   1. the core (firmware/core, firmware/include) includes only freestanding system headers and
#      its own files: every quoted include resolves inside firmware/include or firmware/core;
#   2. firmware applications (firmware/apps) include only the public API, their own files and the
#      target runtime headers;
#   3. host/ and sim/ never include a file from tests/; sim/ (the cycle model) includes nothing of
#      host/ but the one diagnostic type, host/io/lt_diag.h;
#   4. no shipped program is built from tests/: `make print-product-deps` lists each program's
#      link inputs and none may come from tests/; no tests/*.mk fragment defines a rule for a
#      shipped program or links a host/ program main.
# Prints one line per rule and every offending file; exit status 1 on any violation.
# Usage: tools/check_layout.sh   (from the repository root; `make layout`)
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
fail=0
GENERATED="lt_machines.inc"
bad() { echo "  $1"; fail=1; }

# resolve FILE's quoted include NAME against the including directory and ROOTS; print the path
resolve() {
    local dir=$1 name=$2 r
    shift 2
    if [ -f "$dir/$name" ]; then echo "$dir/$name"; return 0; fi
    for r in "$@"; do
        if [ -f "$r/$name" ]; then echo "$r/$name"; return 0; fi
    done
    return 1
}

# check_includes LABEL ALLOWED_PREFIX_REGEX SYSTEM_REGEX ROOTS... -- FILES...
check_includes() {
    local label=$1 allow=$2 sys=$3 n=0 v=0
    shift 3
    local roots=()
    while [ "$1" != "--" ]; do roots+=("$1"); shift; done
    shift
    local f line name path
    for f in "$@"; do
        n=$((n + 1))
        while IFS= read -r line; do
            if [[ $line =~ ^[[:space:]]*#[[:space:]]*include[[:space:]]*\"([^\"]+)\" ]]; then
                name=${BASH_REMATCH[1]}
                # files the Makefile generates into $(B)/gen (the machine list) exist only after
                # a build; they belong to sim/
                if [[ ($label == "host" || $label == "sim") && " $GENERATED " == *" $name "* ]]; then continue; fi
                if ! path=$(resolve "$(dirname "$f")" "$name" "${roots[@]}"); then
                    bad "$f: #include \"$name\" resolves nowhere in ${roots[*]}"; v=$((v + 1))
                elif ! [[ $(realpath --relative-to=. "$path") =~ $allow ]]; then
                    bad "$f: #include \"$name\" is $(realpath --relative-to=. "$path"), outside $label's rooms"
                    v=$((v + 1))
                fi
            elif [[ $line =~ ^[[:space:]]*#[[:space:]]*include[[:space:]]*\<([^\>]+)\> ]]; then
                name=${BASH_REMATCH[1]}
                if ! [[ $name =~ $sys ]]; then
                    bad "$f: #include <$name> is not allowed in $label"; v=$((v + 1))
                fi
            fi
        done <"$f"
    done
    echo "layout: $label: $n files, $v include violations"
}

mapfile -t core < <(git ls-files 'firmware/core/*' 'firmware/include/*' | grep -E '\.(c|h|inc|def)$')
check_includes "the core" '^firmware/(core|include)/' '^(stdint|stddef|stdbool|limits|arm_mve|arm_acle|immintrin)\.h$' \
    firmware/include firmware/core -- "${core[@]}"

mapfile -t apps < <(git ls-files 'firmware/apps/*' | grep -E '\.(c|h)$')
check_includes "firmware/apps" '^firmware/(include|apps|targets/common)/' '^(stdint|stddef|stdbool|limits)\.h$' \
    firmware/include firmware/apps firmware/targets/common -- "${apps[@]}"

mapfile -t hostfiles < <(git ls-files 'host/*' | grep -E '\.(c|h)$')
check_includes "host" '^(firmware/(include|apps)|host|sim)/' '.' \
    firmware/include firmware/apps host sim /usr/include/OpenEXR -- "${hostfiles[@]}"

mapfile -t simfiles < <(git ls-files 'sim/*' | grep -E '\.(c|h)$')
check_includes "sim" '^(firmware/include/|sim/|host/io/lt_diag\.h$)' '.' \
    firmware/include host sim -- "${simfiles[@]}"

# shipped programs and their link inputs
deps=$(make -s --no-print-directory print-product-deps 2>/dev/null)
if [ -z "$deps" ]; then
    bad "make print-product-deps printed nothing"
else
    np=$(wc -l <<<"$deps")
    from_tests=$(grep -oE '[^ ]*/obj/tests/[^ ]*' <<<"$deps" | sort -u)
    [ -n "$from_tests" ] && bad "shipped programs link objects built from tests/: $(echo $from_tests)"
    echo "layout: $np shipped programs, $(wc -w <<<"$deps") link inputs checked, none from tests/: $([ -z "$from_tests" ] && echo yes || echo NO)"
fi
products="lanetrace lanetrace-native lt-stream lt-faultinject lt-stream-dev"
nfrag=0
for mk in tests/*.mk; do
    [ -f "$mk" ] || continue
    nfrag=$((nfrag + 1))
    for p in $products; do
        if grep -qE "^\\\$\\(B\\)/[a-z]+/$p:" "$mk"; then bad "$mk defines the shipped program $p"; fi
    done
    if grep -qE 'obj/host/[a-z/]*_main\.o' "$mk"; then bad "$mk links a host/ program main"; fi
    if grep -qE '^\$\(B\)/fw/[^:]*stream\.elf:' "$mk"; then bad "$mk defines the streaming firmware image"; fi
done
echo "layout: $nfrag tests/*.mk fragments checked for shipped-program rules"

if [ "$fail" -ne 0 ]; then
    echo "layout: FAILED"
    exit 1
fi
echo "layout: ok"
