#!/usr/bin/env python3
"""fuzz_summary.py DOC - the per-target totals of the fuzz campaign table in DOC (the block between
"<!-- fuzz-campaign:begin -->" and "<!-- fuzz-campaign:end -->" of docs/reliability.md: one row per
run of a target, its first column the target's name, optionally followed by a note in
parentheses), as a Markdown table on stdout: runs, executions, crashes and whether the target has
its 10 million executions (issue #12). `make fuzz-summary` puts it into docs/results.md."""
import re
import sys

GOAL = 10_000_000


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: fuzz_summary.py DOC")
    text = open(sys.argv[1], encoding="utf-8").read()
    m = re.search(r"^<!-- fuzz-campaign:begin -->$(.*?)^<!-- fuzz-campaign:end -->$", text,
                  re.S | re.M)
    if m is None:
        sys.exit(f"fuzz_summary: {sys.argv[1]} has no fuzz-campaign block")
    order, runs, execs, crashes = [], {}, {}, {}
    header = None
    for line in m.group(1).splitlines():
        if not line.startswith("|") or line.startswith("|---"):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if header is None:
            header = cells
            continue
        row = dict(zip(header, cells))
        target = row["target"].split()[0]
        if target not in runs:
            order.append(target)
            runs[target] = execs[target] = crashes[target] = 0
        runs[target] += 1
        execs[target] += int(row["executions"].replace(",", ""))
        crashes[target] += int(row["crashes"])
    if not order:
        sys.exit("fuzz_summary: the fuzz-campaign block has no rows")
    commits = list(dict.fromkeys(re.findall(r"commit ([0-9a-f]{7,})", m.group(1))))
    print("| target | runs | executions under ASan + UBSan | crashes, hangs, out-of-memory | "
          f"{GOAL:,} reached |")
    print("|---|---:|---:|---:|---|")
    for t in order:
        print(f"| {t} | {runs[t]} | {execs[t]:,} | {crashes[t]} | "
              f"{'yes' if execs[t] >= GOAL else 'no'} |")
    print()
    print(f"Summed by `make fuzz-summary` (tools/fuzz_summary.py) from the campaign table of "
          f"docs/reliability.md, {sum(runs.values())} runs at commits {', '.join(commits)}.")


main()
