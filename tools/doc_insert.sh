#!/usr/bin/env bash
# doc_insert.sh NAME TABLE DOC - put the file TABLE into DOC between the lines
# "<!-- NAME:begin -->" and "<!-- NAME:end -->", replacing what was there, so that the figures in
# the docs are the measured ones (make fuzz-doc, make frusta-doc).
set -euo pipefail
name=$1
table=$2
doc=$3
[ -s "$table" ] || { echo "doc_insert: no $table" >&2; exit 1; }
grep -q "^<!-- $name:begin -->\$" "$doc" && grep -q "^<!-- $name:end -->\$" "$doc" ||
    { echo "doc_insert: $doc has no $name markers" >&2; exit 1; }
awk -v t="$table" -v b="<!-- $name:begin -->" -v e="<!-- $name:end -->" '
    $0 == b { print; while ((getline l < t) > 0) print l; skip = 1; next }
    $0 == e { skip = 0 }
    !skip { print }' "$doc" >"$doc.tmp"
mv -f "$doc.tmp" "$doc"
echo "doc_insert: $doc now holds $table between its $name markers"
