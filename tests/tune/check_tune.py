#!/usr/bin/env python3
"""check_tune.py - checks of lanetrace tune's front.json for tests/run.d/tune.sh.

  check_tune.py front FRONT.json      every family/machine front is exactly the set of full-size
                                      points no other full-size point of the group dominates
                                      (objectives: cycles and the family's two errors)
  check_tune.py picks FRONT.json      every pick was verified at full size and its verification
                                      meets every bound of the budget
  check_tune.py get FRONT.json FAMILY KEY   a metric of FAMILY's pick verification (stdout)
  check_tune.py same A.json B.json    the points (knobs, status, measurements) of two runs are
                                      equal, front flags included (plan + merge vs in-process)
Exit 0 when the check holds, 1 with a one-line reason otherwise.
"""
import json
import math
import sys


def objectives(p):
    m = p["full"]["metrics"]
    fam = p["knobs"]["family"]
    def v(x):
        return math.inf if x is None else x
    if fam == "object":
        return (v(m["cycles"]), v(m["wrong"]), v(m["rmse"]))
    if fam == "screen":
        return (v(m["cycles"]), v(m["wrong"]), v(m["rel99"]))
    return (v(m["cycles"]), -m["psnr"] if m["psnr"] is not None else math.inf, v(m["off"]))


def dominates(a, b):
    return all(x <= y for x, y in zip(a, b)) and any(x < y for x, y in zip(a, b))


def check_front(doc):
    full = [p for p in doc["points"] if p["status"] == "full"]
    groups = {}
    for p in full:
        groups.setdefault((p["knobs"]["family"], p["knobs"]["machine"]), []).append(p)
    nfront = 0
    for key, pts in groups.items():
        obj = [objectives(p) for p in pts]
        for i, p in enumerate(pts):
            dom = any(dominates(obj[j], obj[i]) for j in range(len(pts)) if j != i)
            if p["front"] == dom:
                return "%s %s: point %d (%s) has front=%s but dominated=%s" % (
                    key[0], key[1], p["id"], p["text"], p["front"], dom)
            nfront += p["front"]
    for p in doc["points"]:
        if p["status"] != "full" and p["front"]:
            return "point %d (%s) is on a front without a full-size measurement" % (p["id"], p["text"])
    if nfront == 0:
        return "no front point at all"
    print("%d groups, %d full-size points, %d on the fronts: every front point non-dominated, "
          "every other point dominated" % (len(groups), len(full), nfront))
    return None


def check_picks(doc):
    picks = doc.get("picks", [])
    if not picks:
        return "no picks in the document"
    for k in picks:
        if k["id"] is None:
            return "%s: no pick" % k["family"]
        if not k["verified"]:
            return "%s: the verification does not meet the budget" % k["family"]
        m = k["verification"]["metrics"]
        for term in k["budget"].split(", "):
            op = "<=" if "<=" in term else ">="
            name, bound = term.split(op)
            bound = float(bound.rstrip("%"))
            val = m[name]
            if val is None or (val > bound if op == "<=" else val < bound):
                return "%s: %s = %s breaks %s" % (k["family"], name, val, term)
        print("%s: pick %d verified at %d px meets %s" % (k["family"], k["id"],
                                                         k["verification"]["res"], k["budget"]))
    return None


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    what, doc = sys.argv[1], json.load(open(sys.argv[2]))
    if what == "front":
        err = check_front(doc)
    elif what == "picks":
        err = check_picks(doc)
    elif what == "get":
        for k in doc.get("picks", []):
            if k["family"] == sys.argv[3]:
                print(k["verification"]["metrics"][sys.argv[4]])
                return 0
        err = "no pick for %s" % sys.argv[3]
    elif what == "same":
        other = json.load(open(sys.argv[3]))
        keep = ("text", "knobs", "status", "full", "probe", "front")
        a = [{k: p.get(k) for k in keep} for p in doc["points"]]
        b = [{k: p.get(k) for k in keep} for p in other["points"]]
        for p in a + b:
            for st in ("full", "probe"):
                if p.get(st):
                    p[st].pop("host_s", None)
        err = None if a == b else "the points differ (%d vs %d points)" % (len(a), len(b))
        if err is None:
            print("%d points equal, %d on the fronts" % (len(a), sum(p["front"] for p in a)))
    else:
        err = "unknown check %s" % what
    if err:
        print(err)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
