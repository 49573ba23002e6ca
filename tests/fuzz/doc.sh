#!/usr/bin/env bash
# doc.sh TABLE DOC - put the campaign table (build/fuzz/campaign.md, written by campaign.sh) into DOC
# between the lines "<!-- fuzz-campaign:begin -->" and "<!-- fuzz-campaign:end -->", so that the
# figures in the docs are the measured ones. Run by make fuzz-doc after make fuzz-campaign.
set -euo pipefail
[ -s "$1" ] || { echo "fuzz-doc: no $1: run make fuzz-campaign SECONDS=N first" >&2; exit 1; }
exec "$(dirname "$0")/../../tools/doc_insert.sh" fuzz-campaign "$1" "$2"
