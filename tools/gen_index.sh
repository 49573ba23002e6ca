#!/usr/bin/env bash
# gen_index.sh - the index of every function the core defines, including the ones a kernel
# template generates per numeric path (lt_bvh_build_q16 and lt_bvh_build_f32 are both written
# once, in object/lt_bvh.inc, and spelled there through a token-pasting macro that grep and
# ctags cannot see). The names and places come from the compiler's own debug information
# (`nm -l` on the objects of the host build), so the index is exactly what was compiled.
# Writes, under OUT (default build/index):
#   tags         a ctags file (vim: `:set tags+=build/index/tags`; most editors read it)
#   symbols.txt  one line per function: name, file:line, and "template" when the definition
#                sits in a kernel template (.inc) shared by several numeric paths
# and prints a summary. With --check it also fails if a function declared in a public header
# (firmware/include/lt/*.h) is neither defined by the core, nor an inline body in the header,
# nor (for the cost hook's simulator entry points) defined by sim/.
# Usage: tools/gen_index.sh [--check] [OBJDIR [OUT]]   (`make index`; the objects must exist)
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
check=0
if [ "${1:-}" = "--check" ]; then check=1; shift; fi
objdir=${1:-build/host/obj/firmware/core}
out=${2:-build/index}
top=$(pwd)
mapfile -t objs < <(find "$objdir" -name '*.o' 2>/dev/null | sort)
if [ ${#objs[@]} -eq 0 ]; then
    echo "index: no objects under $objdir (build them first: make all)"
    exit 1
fi
mkdir -p "$out"
# "<addr> T name<TAB>/abs/path/file:line" -> "name<TAB>rel/file<TAB>line"
nm -l --defined-only "${objs[@]}" 2>/dev/null |
    awk -v top="$top/" '$2 == "T" && NF >= 3 {
        split($0, f, "\t"); n = split(f[1], a, " "); name = a[n];
        loc = f[2]; sub(top, "", loc); i = match(loc, /:[0-9]+$/);
        if (i == 0) next;
        print name "\t" substr(loc, 1, i - 1) "\t" substr(loc, i + 1) }' |
    sort -u >"$out/defs.tsv"
{
    printf '!_TAG_FILE_FORMAT\t2\t/extended format/\n'
    printf '!_TAG_FILE_SORTED\t1\t/0=unsorted, 1=sorted/\n'
    awk -F'\t' '{ printf "%s\t%s\t%s;\"\tf\n", $1, $2, $3 }' "$out/defs.tsv" | LC_ALL=C sort
} >"$out/tags"
awk -F'\t' '{ printf "%-40s %s:%s%s\n", $1, $2, $3, ($2 ~ /\.inc$/ ? "  template" : "") }' \
    "$out/defs.tsv" >"$out/symbols.txt"
n=$(wc -l <"$out/defs.tsv")
nt=$(awk -F'\t' '$2 ~ /\.inc$/' "$out/defs.tsv" | wc -l)
echo "index: $n core functions ($nt generated from kernel templates) -> $out/tags, $out/symbols.txt"
[ "$check" -eq 1 ] || exit 0

# public declarations: "lt_name(" at the start of a declaration in firmware/include/lt/*.h
missing=()
declared=0
while IFS= read -r name; do
    declared=$((declared + 1))
    if grep -q "^$name	" "$out/defs.tsv"; then continue; fi
    # an inline body in the header itself (LT_INLINE ... name(...) { ... })
    if grep -qE "LT_INLINE[^;]*\\b$name\\(" firmware/include/lt/*.h; then continue; fi
    # the cost hook's simulator entry points (lt_cost.h, LT_COST_SIM) are defined by sim/
    if grep -qE "^[a-z_0-9 ]+\\b$name\\(" sim/*.c; then continue; fi
    missing+=("$name")
done < <(grep -hoE '^(const )?[a-z_0-9]+( \*| )+(lt_[a-z0-9_]+)\(' firmware/include/lt/*.h |
    grep -oE 'lt_[a-z0-9_]+\($' | tr -d '(' | sort -u)
echo "index: $declared functions declared in firmware/include/lt/*.h; undefined: ${#missing[@]}"
if [ ${#missing[@]} -gt 0 ]; then
    echo "index: declared but not defined: ${missing[*]}"
    exit 1
fi
exit 0
