# citations.sh - sources are cited by authors, title, venue and year with a key defined in
# docs/bibliography.md, never by paths that a user's clone does not have: no tracked file may
# mention the private copies of the papers (a seeds/ folder) or the shared notes folder, and no
# file may point at a style, facts or architecture page that is not in the repository. Every
# [Key99] used in a tracked file must be defined in the bibliography. Sourced by
# tests/run_tests.sh ($tmp, check/ok/ko).
cit_self=tests/run.d/citations.sh
cit_bib=docs/bibliography.md
# tracked files (a git checkout), else every file outside build/ and .git/ (an unpacked archive)
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git ls-files >"$tmp/cit_all.txt"
else
    find . -type f -not -path './build/*' -not -path './.git/*' | sed 's|^\./||' >"$tmp/cit_all.txt"
fi
grep -v -x -F "$cit_self" "$tmp/cit_all.txt" | while IFS= read -r f; do
    [ -f "$f" ] && printf '%s\0' "$f"
done >"$tmp/cit_files.z"
cit_n=$(tr -cd '\0' <"$tmp/cit_files.z" | wc -c)
echo "   $cit_n files scanned (tracked files except this script)"

# cit_grep NAME ERE HINT: FAIL with file:line of the first matches of ERE, PASS if there is none
cit_grep() {
    xargs -0 grep -I -n -E -- "$2" <"$tmp/cit_files.z" >"$tmp/cit_hits.txt" 2>/dev/null
    local n
    n=$(wc -l <"$tmp/cit_hits.txt")
    if [ "$n" -eq 0 ]; then
        ok "$1: none"
    else
        ko "$1: $n line(s), $3: $(head -5 "$tmp/cit_hits.txt" |
            cut -c1-120 | tr '\n' ';')"
    fi
}
# the bracketed characters keep these patterns from matching their own text
cit_grep "mentions of the private paper copies (seeds/0..)" 'seeds/[0]' \
    "cite the work as in docs/bibliography.md"
cit_grep "mentions of the shared notes folder (shared/docs/)" 'shared/[d]ocs/' \
    "point at the docs/ page that holds the fact"
for cit_page in style facts architecture; do
    if grep -q -E "(^|/)$cit_page\.md\$" "$tmp/cit_all.txt"; then
        ok "$cit_page.md is in the repository: mentions allowed"
    else
        cit_grep "mentions of $cit_page.md (not in the repository)" \
            "(^|[^A-Za-z0-9_.-])$cit_page\\.md" "point at the docs/ page that holds the fact"
    fi
done

# every citation key used is defined as **[Key]** in the bibliography
check "$cit_bib exists" test -s "$cit_bib"
xargs -0 grep -I -h -o -E '\[[A-Z][A-Za-z]+[0-9]{2}\]' <"$tmp/cit_files.z" 2>/dev/null |
    sort -u >"$tmp/cit_keys.txt"
cit_undef=""
while IFS= read -r k; do
    grep -q -F "**$k**" "$cit_bib" 2>/dev/null || cit_undef="$cit_undef $k"
done <"$tmp/cit_keys.txt"
cit_nk=$(wc -l <"$tmp/cit_keys.txt")
check "all $cit_nk citation keys used are defined in $cit_bib${cit_undef:+ (undefined:$cit_undef)}" \
    test -z "$cit_undef"
