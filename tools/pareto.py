#!/usr/bin/env python3
"""pareto.py - docs/tradeoffs.md from lanetrace tune runs (tools/pareto.sh, make pareto).

usage: pareto.py OUT.md FRONT.json...

Reads each run's front.json (docs/tune.md) and writes, per scene: the run's counts, its plot, the
front of each family and machine, the picks for a tight, a medium and a loose budget (set from the
scene's own most accurate configuration, printed as --budget strings, picked by lanetrace tune's
rule: fewest cycles, then fewest bytes), what each knob buys, and whether float32 dominates s15.16;
then quadtree reprojection against BVH tracing in cycles per pixel over the scenes. Every number
comes from the runs.
"""
import json
import math
import os
import subprocess
import sys

FAMILIES = ("object", "screen", "shadows")
PRIMARY = {"object": ("rmse", "depth RMSE (scene units)", False),
           "screen": ("rel99", "rel99 (%)", False),
           "shadows": ("psnr", "PSNR (dB)", True)}
KNOBS = {"object": ("path", "structure", "leaf", "isect"),
         "screen": ("path", "tracer", "layers", "gamma"),
         "shadows": ("path", "leaf", "cull", "spp", "primary", "shadow", "filter")}


def fmt(v, digits=3):
    if v is None:
        return "-"
    if isinstance(v, float) and (math.isinf(v) or math.isnan(v)):
        return "-"
    if abs(v) >= 1e5:
        return "%.0f" % v
    return "%.*g" % (digits, v)


def objectives(p):
    m = p["full"]["metrics"]
    fam = p["knobs"]["family"]
    inf = math.inf
    def v(x):
        return inf if x is None else x
    if fam == "object":
        return (v(m["cycles"]), v(m["wrong"]), v(m["rmse"]))
    if fam == "screen":
        return (v(m["cycles"]), v(m["wrong"]), v(m["rel99"]))
    return (v(m["cycles"]), -m["psnr"] if m["psnr"] is not None else inf, v(m["off"]))


def dominates(a, b):
    return all(x <= y for x, y in zip(a, b)) and any(x < y for x, y in zip(a, b))


def err_cols(fam, m):
    if fam == "object":
        return [fmt(m["wrong"]), fmt(m["rmse"]), fmt(m["maxerr"])]
    if fam == "screen":
        return [fmt(m["wrong"]), fmt(m["rel50"]), fmt(m["rel99"]), fmt(m["within1"], 4)]
    return [fmt(m["psnr"], 4), fmt(m["off"])]


ERR_HEAD = {"object": ["wrong %", "depth RMSE", "max err"],
            "screen": ["wrong %", "rel. err median %", "rel99 %", "within 1 %"],
            "shadows": ["PSNR dB", "off > 1/255 %"]}


def triangles(path):
    try:
        out = subprocess.run(["build/sim/lanetrace", "info", path, "--json"], capture_output=True,
                             text=True, timeout=120, check=True).stdout
        return json.loads(out)["triangles"]
    except (OSError, subprocess.SubprocessError, ValueError, KeyError):
        return None


def pick(points, key, bound, higher):
    ok = [p for p in points if p["full"]["metrics"][key] is not None and
          (p["full"]["metrics"][key] >= bound if higher else p["full"]["metrics"][key] <= bound)]
    if not ok:
        return None
    return min(ok, key=lambda p: (p["full"]["metrics"]["cycles"],
                                  p["full"]["metrics"]["bytes"] if p["full"]["metrics"]["bytes"]
                                  is not None else 0))


def front_table(w, fam, pts, mach):
    fr = sorted([p for p in pts if p["front"] and p["knobs"]["machine"] == mach],
                key=lambda p: p["full"]["metrics"]["cycles"])
    w("\n%s on %s, %d point(s) on the front:\n\n" % (fam, mach, len(fr)))
    w("| configuration | cycles | cycles/px | bytes | %s |\n" % " | ".join(ERR_HEAD[fam]))
    w("|---|" + "---:|" * (3 + len(ERR_HEAD[fam])) + "\n")
    for p in fr:
        m = p["full"]["metrics"]
        res = p["full"]["res"]
        w("| %s | %.0f | %.1f | %s | %s |\n" % (p["text"], m["cycles"], m["cycles"] / (res * res),
                                                "-" if m["bytes"] is None else "%.0f" % m["bytes"],
                                                " | ".join(err_cols(fam, m))))


def budgets(w, fam, pts, machines):
    key, label, higher = PRIMARY[fam]
    vals = [p["full"]["metrics"][key] for p in pts if p["full"]["metrics"][key] is not None]
    if not vals:
        return
    best = max(vals) if higher else min(vals)
    if higher:
        levels = [("tight", best - 0.5), ("medium", best - 3.0), ("loose", best - 10.0)]
    else:
        levels = [("tight", best * 1.05), ("medium", best * 2.0), ("loose", best * 10.0)]
    w("\nPicks (the cheapest configuration meeting the budget, per machine; the most accurate has "
      "%s %s):\n\n| budget | %s |\n|---|%s\n" % (label, fmt(best, 4), " | ".join(machines),
                                                   "---|" * len(machines)))
    for name, bound in levels:
        cells = []
        for mach in machines:
            p = pick([q for q in pts if q["knobs"]["machine"] == mach], key, bound, higher)
            cells.append("%s, %.0f cycles, %s %s" % (p["text"], p["full"]["metrics"]["cycles"], key,
                                                   fmt(p["full"]["metrics"][key], 4))
                         if p else "none meets it")
        w("| %s `%s%s%s` | %s |\n" % (name, key, ">=" if higher else "<=", fmt(bound, 4),
                                      " | ".join(cells)))


def knob_value(p, knob):
    k = p["knobs"]
    if knob == "tracer":
        return k.get("tracer")
    if knob == "gamma":
        return k.get("gamma", "-")
    v = k.get(knob)
    if isinstance(v, bool):
        return "on" if v else "off"
    if knob == "leaf" and v == 0:
        return "none"
    return v


def knobs(w, fam, pts, machines):
    key, label, higher = PRIMARY[fam]
    w("\nWhat each knob buys (over every configuration measured at full size: the cheapest one "
      "with the value, and the best %s with it):\n\n" % label)
    for knob in KNOBS[fam]:
        values = sorted({str(knob_value(p, knob)) for p in pts},
                        key=lambda x: (0, int(x)) if x.isdigit() else (1, x))
        if len(values) < 2:
            continue
        parts = []
        for mach in machines:
            cells = []
            for v in values:
                sel = [p for p in pts if str(knob_value(p, knob)) == v and p["knobs"]["machine"] == mach]
                if not sel:
                    continue
                cyc = min(p["full"]["metrics"]["cycles"] for p in sel)
                errs = [p["full"]["metrics"][key] for p in sel if p["full"]["metrics"][key] is not None]
                be = (max(errs) if higher else min(errs)) if errs else None
                cells.append("%s %.3g cycles / %s" % (v, cyc, fmt(be, 4)))
            parts.append("%s: %s" % (mach, "; ".join(cells)))
        w("- **%s**: %s.\n" % (knob, " - ".join(parts)))


def dominance(w, fam, pts, machines):
    if fam == "screen":
        return
    for mach in machines:
        sel = [p for p in pts if p["knobs"]["machine"] == mach]
        q16 = [p for p in sel if p["knobs"]["path"] == "q16"]
        f32 = [p for p in sel if p["knobs"]["path"] == "f32"]
        if not q16 or not f32:
            continue
        dom = [p for p in q16 if any(dominates(objectives(f), objectives(p)) for f in f32)]
        if len(dom) == len(q16):
            w("\nOn %s float32 dominates s15.16 in %s space: each of the %d s15.16 configurations "
              "measured at full size is both dearer and no more accurate than some float32 one.\n"
              % (mach, fam, len(q16)))
        else:
            w("\nOn %s, %d of %d s15.16 configurations measured at full size are dominated by a "
              "float32 one; the others are on the trade.\n" % (mach, len(dom), len(q16)))


def scene(w, doc, fig):
    name = os.path.basename(doc["input"])
    c = doc["counts"]
    full = [p for p in doc["points"] if p["status"] == "full"]
    ntri = triangles(doc["input"])
    w("\n## %s%s\n\n" % (name, " (%d triangles)" % ntri if ntri else ""))
    w("`lanetrace tune %s --res %d --probe-res %d --jobs %d`: %d configurations, %d probed, %d "
      "pruned, %d measured at full size, %d on the fronts, %.1f s.\n\n![error vs cycles](%s)\n"
      % (doc["input"], doc["res"], doc["probe_res"], doc["jobs"], c["points"], c["probed"],
         c["pruned"], c["full"], c["front"], doc["seconds"], fig))
    if doc.get("q16_left_out"):
        w("\ns15.16 left out: %s\n" % doc["q16_left_out"])
    for fam in FAMILIES:
        pts = [p for p in full if p["knobs"]["family"] == fam]
        if not pts:
            continue
        w("\n### %s\n" % fam)
        for mach in doc["machines"]:
            front_table(w, fam, pts, mach)
        budgets(w, fam, pts, doc["machines"])
        knobs(w, fam, pts, doc["machines"])
        dominance(w, fam, pts, doc["machines"])
    return ntri


def cheapest(doc, fam, mach, cond):
    sel = [p for p in doc["points"] if p["status"] == "full" and p["knobs"]["family"] == fam and
           p["knobs"]["machine"] == mach and cond(p["knobs"])]
    if not sel:
        return None
    p = min(sel, key=lambda p: p["full"]["metrics"]["cycles"])
    return p["full"]["metrics"]["cycles"] / (p["full"]["res"] ** 2), p["text"]


def widmer(w, docs, ntris):
    w("\n## Reprojection through the quadtree against tracing the BVH\n\n"
      "Cycles per pixel on lrb16 of the cheapest quadtree reprojection (screen family, the view "
      "moved by 8% of the median depth and turned 3 degrees) against the cheapest BVH trace of "
      "the source view (object family, bvh or bvhq, the watertight test), both at the tune's size "
      "with their builds; "
      "scenes sorted by triangle count:\n\n| scene | triangles | quadtree cycles/px | BVH "
      "cycles/px | quadtree / BVH |\n|---|---:|---:|---:|---:|\n")
    rows = []
    for doc, n in zip(docs, ntris):
        q = cheapest(doc, "screen", "lrb16", lambda k: k.get("tracer") == "quadtree")
        b = cheapest(doc, "object", "lrb16",
                     lambda k: k.get("structure") in ("bvh", "bvhq") and k.get("isect", "wt") == "wt")
        if q and b:
            rows.append((n or 0, os.path.basename(doc["input"]), q, b))
    rows.sort()
    for n, name, q, b in rows:
        w("| %s | %d | %.1f (%s) | %.1f (%s) | %.2f |\n" % (name, n, q[0], q[1], b[0], b[1],
                                                         q[0] / b[0]))
    if len(rows) >= 2:
        cross = [i for i in range(1, len(rows))
                 if (rows[i - 1][2][0] > rows[i - 1][3][0]) != (rows[i][2][0] > rows[i][3][0])]
        if cross:
            i = cross[0]
            w("\nThe lines cross between %s (%d triangles) and %s (%d triangles).\n"
              % (rows[i - 1][1], rows[i - 1][0], rows[i][1], rows[i][0]))
        else:
            side = "cheaper" if rows[0][2][0] < rows[0][3][0] else "dearer"
            w("\nThe lines do not cross over these scenes: the quadtree is %s per pixel on all of "
              "them (add larger scenes with PARETO_SCENES to look further).\n" % side)


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    out = sys.argv[1]
    docs = [json.load(open(p)) for p in sys.argv[2:]]
    parts = []
    w = parts.append
    w("# Trade-offs: speed against accuracy, measured\n\n"
      "Generated by `make pareto` (tools/pareto.sh, tools/pareto.py) from `lanetrace tune` runs "
      "(docs/tune.md); do not edit by hand. Cycles are simulated per frame on each machine model "
      "(lrb16: 16 lanes at 1 GHz; the MCUs mcu-m4, a scalar Cortex-M4F, mcu-m55, a Cortex-M55 "
      "with Helium, and rv32imac, an integer-only RV32 core, their integer op costs fitted to "
      "the firmware's modelled cycles, docs/firmware.md); errors are against each "
      "family's reference: the double-precision frame (object), the ray-traced target view "
      "(screen), the 256-spp image (soft shadows). A front lists the configurations no other "
      "one beats in cycles and both errors at once. The MCU models are fitted on the firmware's "
      "BVH walks with the exact watertight test, frusta and quadtree; what else they price (kd, "
      "grid, chunks, bvhq, `isect mt`, `isect wt32`) they extrapolate by op class, and for "
      "`wt32` the models over-price its 16-ray packets by 19-71% against the targets "
      "(docs/firmware.md, \"Cycle models\"; docs/watertight.md, \"A narrower test\"). "
      "mcu-m4 and mcu-m55 price the exact test's packets lane by lane, as the Cortex-M4 and "
      "Cortex-M55 builds run them (docs/firmware.md, \"Lane by lane on Cortex-M4 and "
      "Cortex-M55\").\n")
    ntris = []
    for p, doc in zip(sys.argv[2:], docs):
        name = os.path.splitext(os.path.basename(doc["input"]))[0]
        ntris.append(scene(w, doc, "tradeoffs/%s.png" % name))
    widmer(w, docs, ntris)
    with open(out, "w") as f:
        f.write("".join(parts))
    return 0


if __name__ == "__main__":
    sys.exit(main())
