#!/usr/bin/env bash
# doc.sh TABLE DOC - put the campaign table (build/fuzz/campaign.md, written by campaign.sh) into DOC
# between the lines "<!-- fuzz-campaign:begin -->" and "<!-- fuzz-campaign:end -->", so that the
# figures in the docs are the measured ones. Run by make fuzz-doc after make fuzz-campaign.
set -euo pipefail
table=$1
doc=$2
[ -s "$table" ] || { echo "fuzz-doc: no $table: run make fuzz-campaign SECONDS=N first" >&2; exit 1; }
grep -q '^<!-- fuzz-campaign:begin -->$' "$doc" && grep -q '^<!-- fuzz-campaign:end -->$' "$doc" ||
    { echo "fuzz-doc: $doc has no fuzz-campaign markers" >&2; exit 1; }
awk -v t="$table" '
    /^<!-- fuzz-campaign:begin -->$/ { print; while ((getline l < t) > 0) print l; skip = 1; next }
    /^<!-- fuzz-campaign:end -->$/ { skip = 0 }
    !skip { print }' "$doc" >"$doc.tmp"
mv -f "$doc.tmp" "$doc"
echo "fuzz-doc: $doc now holds the table of $table"
