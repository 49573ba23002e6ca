#!/usr/bin/env python3
"""cal_scene.py - the synthetic calibration scenes of the firmware cycle models (docs/firmware.md,
"Cycle models"): small procedural meshes, disjoint from every scene the models are checked on.
  a: a bumpy wall (a height field, 2 x 18 x 18 triangles) behind three icospheres (320 each) and a
     slab: occluders in front of a receiver, depth edges for the reprojection;
  b: a ring of eight icospheres of different sizes (80 or 320 triangles) over a flat floor.
Usage: tools/cal_scene.py a|b OUT.obj   (deterministic: the same bytes every run)"""
import math
import sys


def icosphere(cx, cy, cz, r, subdiv):
    t = (1.0 + 5.0 ** 0.5) / 2.0
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
         (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdiv):
        mid = {}

        def m(a, b):
            k = (min(a, b), max(a, b))
            if k not in mid:
                p = [(v[a][i] + v[b][i]) / 2 for i in range(3)]
                n = math.sqrt(sum(x * x for x in p))
                v.append(tuple(x / n for x in p))
                mid[k] = len(v) - 1
            return mid[k]
        nf = []
        for a, b, c in f:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    return [(cx + r * p[0], cy + r * p[1], cz + r * p[2]) for p in v], f


def heightfield(n, size, amp):
    v, f = [], []
    for j in range(n + 1):
        for i in range(n + 1):
            x = (i / n - 0.5) * size
            z = (j / n - 0.5) * size
            h = amp * (math.sin(3.1 * x / size * math.pi) * math.cos(2.3 * z / size * math.pi))
            v.append((x, z, h - 1.5))  # a wall facing +z, the default camera's side
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            f += [(a, a + n + 1, a + 1), (a + 1, a + n + 1, a + n + 2)]
    return v, f


def box(x0, y0, z0, x1, y1, z1):
    v = [(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]
    f = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7), (2, 7, 6),
         (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    return v, f


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("a", "b"):
        sys.stderr.write("usage: cal_scene.py a|b OUT.obj\n")
        return 2
    parts = []
    if sys.argv[1] == "a":
        parts.append(heightfield(18, 10.0, 0.6))
        parts.append(icosphere(-2.0, 1.2, 0.5, 1.1, 2))
        parts.append(icosphere(1.8, -1.6, 0.2, 0.8, 2))
        parts.append(icosphere(0.4, 2.0, 1.5, 0.6, 2))
        parts.append(box(-3.0, -3.0, 0.0, 1.0, -2.5, 1.0))
    else:
        parts.append(box(-6.0, -0.1, -6.0, 6.0, 0.0, 6.0))
        for k in range(8):
            a = 2 * math.pi * k / 8
            parts.append(icosphere(3.5 * math.cos(a), 0.9 + 0.3 * (k % 3), 3.5 * math.sin(a),
                                   0.5 + 0.15 * (k % 4), 2 if k % 2 == 0 else 1))
    out, base, ntri = [], 1, 0
    out.append("# lanetrace calibration scene %s (tools/cal_scene.py)\n" % sys.argv[1])
    for v, f in parts:
        for p in v:
            out.append("v %.6f %.6f %.6f\n" % p)
        for a, b, c in f:
            out.append("f %d %d %d\n" % (a + base, b + base, c + base))
        base += len(v)
        ntri += len(f)
    with open(sys.argv[2], "w") as fh:
        fh.write("".join(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
