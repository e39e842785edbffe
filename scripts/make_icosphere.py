#!/usr/bin/env python3
"""Writes an ASCII STL icosphere of radius 1 (outward normals) with a given subdivision level:
python3 scripts/make_icosphere.py LEVEL OUT.stl (level 4: 5120 triangles). Used for
cases/geometry/eye_sphere.stl, the vitreous cavity of the eye cases (scaled in the case)."""
import math
import sys


def icosphere(level):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
         (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        cache = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                p = [(v[a][k] + v[b][k]) / 2 for k in range(3)]
                n = math.sqrt(sum(x * x for x in p))
                v.append(tuple(x / n for x in p))
                cache[key] = len(v) - 1
            return cache[key]

        nf = []
        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    return v, f


def main():
    level, out = int(sys.argv[1]), sys.argv[2]
    v, f = icosphere(level)
    with open(out, "w") as fp:
        fp.write("solid icosphere\n")
        for a, b, c in f:
            p, q, r = v[a], v[b], v[c]
            u = [q[k] - p[k] for k in range(3)]
            w = [r[k] - p[k] for k in range(3)]
            n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
            ln = math.sqrt(sum(x * x for x in n))
            fp.write("  facet normal %.9g %.9g %.9g\n    outer loop\n" % tuple(x / ln for x in n))
            for P in (p, q, r):
                fp.write("      vertex %.9f %.9f %.9f\n" % P)
            fp.write("    endloop\n  endfacet\n")
        fp.write("endsolid icosphere\n")


if __name__ == "__main__":
    main()
