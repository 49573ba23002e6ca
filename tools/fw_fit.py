#!/usr/bin/env python3
"""fw_fit.py - fit a firmware target's machine model (the issue cycles per op class of
sim/machines/<name>.def) on calibration rows, and rewrite the file's fitted block.

Each row is one stage of one calibration run (tools/fw_cycles.sh writes them):
    row IMAGE STAGE CYCLES OP=COUNT ...
CYCLES: the QEMU plugin's modelled cycles of the stage on the target (its instruction classes
priced by sim/qemu/cycles/<target>.cyc); OP=COUNT: the ops the simulator charged the same stage
(lt-fwmodel, machine-independent). The fit finds integer costs w per op class minimising the
sum of squared relative errors sum_rows ((ops . w - CYCLES) / CYCLES)^2 plus LAMBDA times the
squared relative distance of each cost from its prior times a fitted scale (PRIOR: LT_OP_COST
lines, the costs the machine file had from per-op microbenchmarks before its first fit; the
scale lets the prior be in instructions when the rows are in cycles), each cost at least 1/16 of
its prior: bounded least squares (Lawson-Hanson NNLS), then rounded and improved one class at a
time in integer steps. The prior keeps a cost that the calibration rows cannot separate from
another (two classes always charged together) near what its own microbenchmark measured. A class
that no calibration row charges keeps the cost the file has.

Usage: tools/fw_fit.py ROWS PRIOR MACHINE.def [--write]
Prints the fitted costs and each row's residual; --write replaces the LT_OP_COST lines of the
classes the rows charge (latency = issue) in MACHINE.def, keeping every other line.
Pure Python 3 (no numpy: Debian's base python is enough)."""
import re
import sys


def solve(a, b):
    """Solve the square system a x = b (Gaussian elimination with partial pivoting)."""
    n = len(b)
    m = [row[:] + [b[i]] for i, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        if abs(m[p][c]) < 1e-300:
            raise ZeroDivisionError
        m[c], m[p] = m[p], m[c]
        for r in range(n):
            if r != c and m[r][c] != 0.0:
                f = m[r][c] / m[c][c]
                for k in range(c, n + 1):
                    m[r][k] -= f * m[c][k]
    return [m[i][n] / m[i][i] for i in range(n)]


def lstsq(a, b, cols):
    """Least squares on the columns cols of a (normal equations, a tiny ridge for rank loss)."""
    n = len(cols)
    ata = [[sum(r[i] * r[j] for r in a) for j in cols] for i in cols]
    atb = [sum(r[i] * bb for r, bb in zip(a, b)) for i in cols]
    scale = max([ata[i][i] for i in range(n)] + [1e-30])
    for i in range(n):
        ata[i][i] += 1e-12 * scale
    return solve(ata, atb)


def nnls(a, b, iters=500):
    """Lawson-Hanson non-negative least squares: min |a x - b|, x >= 0."""
    n = len(a[0])
    x = [0.0] * n
    passive = []
    for _ in range(iters):
        r = [bb - sum(ai * xi for ai, xi in zip(row, x)) for row, bb in zip(a, b)]
        grad = [sum(row[j] * rr for row, rr in zip(a, r)) for j in range(n)]
        cand = [j for j in range(n) if j not in passive and grad[j] > 1e-10]
        if not cand:
            break
        passive.append(max(cand, key=lambda j: grad[j]))
        while True:
            z = [0.0] * n
            for j, v in zip(passive, lstsq(a, b, passive)):
                z[j] = v
            if all(z[j] > 0 for j in passive):
                x = z
                break
            alpha = min(x[j] / (x[j] - z[j]) for j in passive if z[j] <= 0 and x[j] != z[j])
            x = [xi + alpha * (zi - xi) for xi, zi in zip(x, z)]
            passive = [j for j in passive if x[j] > 1e-12]
    return x


LAMBDAS = (0.0, 1e-5, 1e-4, 1e-3, 1e-2)


def read_costs(path):
    w = {}
    with open(path) as fh:
        for line in fh:
            m = re.match(r"\s*LT_OP_COST\((\w+),\s*(\d+),\s*(\d+)\)", line)
            if m:
                w[m.group(1)] = int(m.group(3))
    return w


def lower(prior, o):
    """The least cost a class may get: 1/16 of its prior (a 16-lane op costs at least one lane's
    share of the loop its prior prices), and at least 1 cycle when the prior is not 0."""
    p = prior.get(o, 1)
    return 0.0 if p == 0 else max(1.0, p / 16.0)


def fit(rows, classes, prior, lam):
    """Least squares on relative errors, plus lam * sum (w / prior - s)^2 over the classes with s
    a free scale (the prior gives the costs' proportions, not their unit: instructions or cycles),
    with w >= lower(prior): NNLS in (w - lower, s). Returns (w, s)."""
    n = len(classes)
    lb = [lower(prior, o) for o in classes] + [0.0]
    a = [[r[3].get(o, 0) / r[2] for o in classes] + [0.0] for r in rows]
    b = [1.0] * len(rows)
    if lam > 0:
        for j, o in enumerate(classes):
            p = max(prior.get(o, 1), 1)
            a.append([(lam ** 0.5) / p if k == j else 0.0 for k in range(n)] + [-(lam ** 0.5)])
            b.append(0.0)
    b = [bb - sum(x * l for x, l in zip(row, lb)) for row, bb in zip(a, b)]
    x = [v + l for v, l in zip(nnls(a, b), lb)]
    return x[:n], x[n]


def objective(rows, w, prior=None, lam=0.0, scale=1.0):
    v = sum(((sum(c * w[o] for o, c in ops.items()) - cyc) / cyc) ** 2 for _, _, cyc, ops in rows)
    if lam > 0:
        v += lam * sum((w[o] / max(prior.get(o, 1), 1) - scale) ** 2 for o in w)
    return v


def main():
    if len(sys.argv) not in (4, 5) or (len(sys.argv) == 5 and sys.argv[4] != "--write"):
        sys.stderr.write("usage: fw_fit.py ROWS PRIOR MACHINE.def [--write]\n")
        return 2
    rows = []
    with open(sys.argv[1]) as fh:
        for ln, line in enumerate(fh, 1):
            f = line.split()
            if not f or f[0] != "row":
                continue
            try:
                ops = {k: int(v) for k, v in (t.split("=") for t in f[4:])}
                rows.append((f[1], f[2], float(f[3]), ops))
            except ValueError:
                sys.stderr.write("fw_fit: %s:%d: malformed row\n" % (sys.argv[1], ln))
                return 1
    rows = [r for r in rows if r[2] > 0 and r[3]]
    if not rows:
        sys.stderr.write("fw_fit: %s: no rows\n" % sys.argv[1])
        return 1
    classes = sorted({o for r in rows for o in r[3]})
    prior = read_costs(sys.argv[2])
    # the prior's weight by two-fold cross-validation over the calibration scenes: fit on the
    # stages of the images of one scene (-a, -b), predict the other's; the weight with the least
    # rms error of the held-out predictions wins
    scenes = sorted({r[0].rsplit("-", 1)[-1] for r in rows})
    lam, cv = LAMBDAS[0], None
    if len(scenes) >= 2:
        for l in LAMBDAS:
            err, n = 0.0, 0
            for sc in scenes:
                train = [r for r in rows if not r[0].endswith("-" + sc)]
                test = [r for r in rows if r[0].endswith("-" + sc)]
                cl = sorted({o for r in train for o in r[3]})
                xs, _ = fit(train, cl, prior, l)
                wt = dict(zip(cl, xs))
                for _, _, cyc, ops in test:
                    p = sum(c * wt.get(o, prior.get(o, 0)) for o, c in ops.items())
                    err += ((p - cyc) / cyc) ** 2
                    n += 1
            rms = (err / n) ** 0.5
            print("cross-validation: prior weight %g: held-out rms error %.2f%%" % (l, 100 * rms))
            if cv is None or rms < cv:
                lam, cv = l, rms
    x, scale = fit(rows, classes, prior, lam)
    lo = {o: int(-(-lower(prior, o) // 1)) for o in classes}
    w = {o: max(lo[o], round(v)) for o, v in zip(classes, x)}
    # integer refinement: one class at a time, +-1 while the objective falls
    best = objective(rows, w, prior, lam, scale)
    improved = True
    while improved:
        improved = False
        for o in classes:
            for step in (1, -1):
                if w[o] + step < lo[o]:
                    continue
                w[o] += step
                v = objective(rows, w, prior, lam, scale)
                if v < best - 1e-15:
                    best = v
                    improved = True
                else:
                    w[o] -= step
    print("fit over %d rows, %d classes: rms relative error %.2f%%" %
          (len(rows), len(classes), 100.0 * (objective(rows, w) / len(rows)) ** 0.5))
    print("prior %s x %.3f (fitted scale), weight %g; costs at least 1/16 of the prior" %
          (sys.argv[2], scale, lam))
    print("costs: " + " ".join("%s=%d (%.2f)" % (o, w[o], v) for o, v in zip(classes, x)))
    for img, st, cyc, ops in rows:
        p = sum(c * w[o] for o, c in ops.items())
        print("  %-14s stage %-2s plugin %12.0f fitted %12d  %+6.1f%%" % (img, st, cyc, p, 100.0 * (p - cyc) / cyc))
    if len(sys.argv) == 5:
        path = sys.argv[3]
        with open(path) as fh:
            text = fh.read()
        for o in classes:
            pat = re.compile(r"^LT_OP_COST\(%s,\s*\d+,\s*\d+\)" % o, re.M)
            if not pat.search(text):
                sys.stderr.write("fw_fit: %s has no LT_OP_COST(%s, ...) line\n" % (path, o))
                return 1
            text = pat.sub("LT_OP_COST(%-8s %4d, %4d)" % (o + ",", w[o], w[o]), text)
        with open(path, "w") as fh:
            fh.write(text)
        print("wrote %s" % path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
