#!/usr/bin/env bash
# merge.sh TARGET MAXLEN - minimise tests/fuzz/corpus/TARGET plus $B/fuzz/corpus-TARGET (what the
# fuzzer found) into tests/fuzz/corpus/TARGET with libFuzzer's -merge=1: the smallest set of inputs
# that keeps every feature, named by their SHA-1. Regression inputs (regress-*: each a bug found and
# fixed) are kept under their names whatever the merge says. Run by make fuzz-merge[-TARGET].
set -euo pipefail
B=${B:-build}
t=$1
maxlen=${2:-4096}
c=tests/fuzz/corpus/$t
m=$B/fuzz/merge-$t
mkdir -p "$B/fuzz/corpus-$t" "$c"
rm -rf "$m"
mkdir -p "$m"
"$B/fuzz/fuzz-$t" -merge=1 -close_fd_mask=3 -max_len="$maxlen" "$m" "$c" "$B/fuzz/corpus-$t" \
    >"$B/fuzz/merge-$t.log" 2>&1 || { tail -n 20 "$B/fuzz/merge-$t.log"; exit 1; }
for r in "$c"/regress-*; do
    [ -f "$r" ] && rm -f "$m/$(sha1sum "$r" | cut -d' ' -f1)"
done
find "$c" -type f ! -name 'regress-*' -delete
cp "$m"/* "$c"/ 2>/dev/null || true
echo "fuzz-merge-$t: $(find "$c" -type f | wc -l) inputs ($(find "$c" -name 'regress-*' | wc -l) regression), $(du -sk "$c" | cut -f1) KiB in $c"
