#!/usr/bin/env python3
"""Writes the answer corpus: a large, varied, deterministic set of `bezinv invert` inputs whose
outputs must not change when the code is reshaped (scripts/same_answers.sh runs two builds on it
and compares every output byte for byte).

    python3 tests/corpus/make_corpus.py DIR

DIR gets curves.json, points.csv, points.npy + curve-index.npy (the same points), and a few
hostile files (bad-*.csv, bad-*.json) whose error messages and exit codes must not change either.

What it covers: every curve kind (bezier, rational_bezier, rational with separate denominators),
degrees 1-32, the curves people have (graphs of functions, easing and font curves, map
coordinates, wide weights, curves far from the origin), and the hard ones (degree elevation, a
common factor, improper Q(t^2), a loop with its double point, a cusp, a straight line traced at
degree n, a curve whose points all coincide); points on the segment, near it, off it, on the
extension, at the double point, far away, and bad rows (NaN, infinities, unknown curves).
Standard library only; the same DIR contents on every run and every machine.
"""
import array
import json
import math
import os
import random
import sys


def de_casteljau(coefficients, t):
    values = list(coefficients)
    for r in range(1, len(values)):
        for i in range(len(values) - r):
            values[i] = (1.0 - t) * values[i] + t * values[i + 1]
    return values[0]


class Curve:
    """One curve in the three forms bezinv reads; evaluates in floating point (inputs, not answers)."""

    def __init__(self, cid, kind, entry, x_num, x_den, y_num, y_den):
        self.id, self.kind, self.entry = cid, kind, entry
        self.x_num, self.x_den, self.y_num, self.y_den = x_num, x_den, y_num, y_den

    def point(self, t):
        return (de_casteljau(self.x_num, t) / de_casteljau(self.x_den, t),
                de_casteljau(self.y_num, t) / de_casteljau(self.y_den, t))

    def diagonal(self):
        xs = [a / w for a, w in zip(self.x_num, self.x_den)]
        ys = [a / w for a, w in zip(self.y_num, self.y_den)]
        return math.hypot(max(xs) - min(xs), max(ys) - min(ys)) or 1.0


def bezier(cid, points):
    n = len(points)
    return Curve(cid, "bezier", {"id": cid, "kind": "bezier", "points": [list(p) for p in points]},
                 [p[0] for p in points], [1.0] * n, [p[1] for p in points], [1.0] * n)


def rational_bezier(cid, points, weights):
    return Curve(cid, "rational_bezier",
                 {"id": cid, "kind": "rational_bezier", "points": [list(p) for p in points], "weights": list(weights)},
                 [p[0] * w for p, w in zip(points, weights)], list(weights),
                 [p[1] * w for p, w in zip(points, weights)], list(weights))


def rational(cid, x_num, x_den, y_num, y_den):
    return Curve(cid, "rational", {"id": cid, "kind": "rational", "x_num": x_num, "x_den": x_den,
                                   "y_num": y_num, "y_den": y_den}, x_num, x_den, y_num, y_den)


def elevate(coefficients, times=1):
    for _ in range(times):
        n = len(coefficients) - 1
        coefficients = [coefficients[0]] + [
            (i / (n + 1)) * coefficients[i - 1] + (1 - i / (n + 1)) * coefficients[i] for i in range(1, n + 1)
        ] + [coefficients[-1]]
    return coefficients


def power_to_bernstein(power):
    """Bernstein coefficients of sum_k a_k t^k at degree len(power)-1."""
    n = len(power) - 1
    return [sum(math.comb(i, k) / math.comb(n, k) * power[k] for k in range(i + 1)) for i in range(n + 1)]


def bernstein_product(a, b):
    m, n = len(a) - 1, len(b) - 1
    return [sum(math.comb(m, i) * math.comb(n, k - i) * a[i] * b[k - i]
                for i in range(max(0, k - n), min(m, k) + 1)) / math.comb(m + n, k) for k in range(m + n + 1)]


def double_point(curve):
    """Parameters a < b with P(a) = P(b): the closest sampled pair far apart, then Newton in (a, b)."""
    samples = [(i / 400, curve.point(i / 400)) for i in range(401)]
    best = min(((math.dist(p, q), s, t) for s, p in samples for t, q in samples if t - s > 0.2))
    a, b = best[1], best[2]
    for _ in range(50):
        pa, pb, h = curve.point(a), curve.point(b), 1e-7
        f = (pa[0] - pb[0], pa[1] - pb[1])
        da = [(u - v) / h for u, v in zip(curve.point(a + h), pa)]
        db = [(v - u) / h for u, v in zip(curve.point(b + h), pb)]
        det = da[0] * db[1] - db[0] * da[1]
        a, b = a - (f[0] * db[1] - db[0] * f[1]) / det, b - (da[0] * f[1] - f[0] * da[1]) / det
    return a, b


def make_curves(rng):
    curves = []
    # Random curves of every kind and degree 1-32 (two each), some far from the origin.
    for degree in range(1, 33):
        for copy in range(2):
            offset = (0.0, 0.0) if copy == 0 else (rng.uniform(-1e5, 1e5), rng.uniform(-1e5, 1e5))
            points = [(offset[0] + rng.uniform(-1, 1), offset[1] + rng.uniform(-1, 1)) for _ in range(degree + 1)]
            curves.append(bezier(f"bezier-{degree}-{copy}", points))
            weights = [rng.uniform(0.2, 5.0) for _ in range(degree + 1)]
            curves.append(rational_bezier(f"rational-bezier-{degree}-{copy}", points, weights))
        if degree <= 12:
            den = [rng.uniform(0.5, 2.0) for _ in range(degree + 1)]
            curves.append(rational(f"rational-{degree}", [rng.uniform(-1, 1) for _ in range(degree + 1)],
                                   den, [rng.uniform(-1, 1) for _ in range(degree + 1)],
                                   [rng.uniform(0.5, 2.0) for _ in range(degree + 1)]))
    # The curves people have.
    for degree in (2, 3, 5, 9):  # graphs of functions: x = t
        curves.append(bezier(f"graph-{degree}", [(i / degree, rng.uniform(-1, 1)) for i in range(degree + 1)]))
    curves.append(bezier("near-parabola", [(0.0, 0.0), (0.5, 1.0 + 1e-9), (1.0, 0.0)]))
    curves.append(bezier("easing-ease", [(0, 0), (0.25, 0.1), (0.25, 1.0), (1, 1)]))
    curves.append(bezier("easing-ease-in-out", [(0, 0), (0.42, 0), (0.58, 1.0), (1, 1)]))
    curves.append(bezier("font-quadratic", [(120, 0), (260, 700), (420, 0)]))
    curves.append(bezier("map-coordinates", [(2.3522, 48.8566), (2.3530, 48.8571), (2.3541, 48.8569), (2.3550, 48.8575)]))
    curves.append(bezier("map-metres", [(651234.5, 6862345.25), (651240.0, 6862350.5), (651251.75, 6862349.0)]))
    curves.append(bezier("far-1e12", [(1e12, 1e12), (1e12 + 1, 1e12 + 3), (1e12 + 4, 1e12 + 1)]))
    curves.append(rational_bezier("wide-weights", [(0, 0), (1, 2), (3, 2), (4, 0)], [1.0, 1e-3, 1e3, 1.0]))
    curves.append(rational_bezier("circle-quarter", [(1, 0), (1, 1), (0, 1)], [1.0, math.sqrt(0.5), 1.0]))
    # The hard ones.
    cubic = [(0.0, 0.0), (1.0, 2.0), (3.0, 2.0), (4.0, 0.0)]
    xs, ys = elevate([p[0] for p in cubic], 3), elevate([p[1] for p in cubic], 3)
    curves.append(bezier("elevated-3-to-6", list(zip(xs, ys))))
    xs, ys = elevate([0.0, 1.0], 7), elevate([0.0, 3.0], 7)
    curves.append(bezier("line-at-degree-8", list(zip(xs, ys))))
    curves.append(bezier("loop", [(0, 0), (2, 2), (-1, 2), (1, 0)]))
    curves.append(bezier("cusp", [(0, 0), (1, 1), (0, 1), (1, 0)]))
    # Improper: (s, s^2) with s = (2t - 1)^2, a parabola arc traced twice.
    curves.append(bezier("improper-square", list(zip(power_to_bernstein([1.0, -4.0, 4.0, 0.0, 0.0]),
                                                     power_to_bernstein([1.0, -8.0, 24.0, -32.0, 16.0])))))
    # Common factor: (X, Y, W) * (1 + t), Bernstein coefficients (1, 2).
    base_x, base_y, base_w = [0.0, 1.0, 2.0], [0.0, 2.0, 0.0], [1.0, 2.0, 1.0]
    factor = lambda c: bernstein_product(c, [1.0, 2.0])
    curves.append(rational("common-factor", factor(base_x), factor(base_w), factor(base_y), factor(base_w)))
    curves.append(bezier("all-points-coincide", [(1.0, 2.0)] * 4))
    paper1 = rational_bezier("paper-example-1", [(0, 0), (1, 2), (2, 0)], [1.0, 1.0, 1.0])
    curves.append(paper1)
    return curves


def make_points(rng, curves):
    rows = []  # (curve id, x, y)
    for curve in curves:
        diagonal = curve.diagonal()
        for k in range(40):
            t = rng.random() if k else 0.0
            if k == 1:
                t = 1.0
            x, y = curve.point(t)
            rows.append((curve.id, x, y))  # on
            angle = rng.uniform(0, 2 * math.pi)
            for scale in (1e-9, 1e-4, 0.1):  # near, just off, off
                rows.append((curve.id, x + scale * diagonal * math.cos(angle), y + scale * diagonal * math.sin(angle)))
        for t in (-0.5, -0.05, 1.05, 1.5):  # the extension
            try:
                rows.append((curve.id,) + curve.point(t))
            except ZeroDivisionError:
                pass
        x, y = curve.point(0.5)
        for far in (1e10, 1e200):
            rows.append((curve.id, x + far * diagonal, y - far * diagonal))
    loop = next(c for c in curves if c.id == "loop")
    a, b = double_point(loop)
    rows.append(("loop",) + loop.point(a))
    rows.append(("loop",) + loop.point(b))
    rows.append(("paper-example-1", 1.0, 1.0))
    bad = [("bezier-3-0", float("nan"), 0.0), ("bezier-3-0", 0.0, float("inf")), ("bezier-3-0", float("-inf"), 1.0),
           ("no-such-curve", 0.5, 0.5)]
    for i, row in enumerate(bad):
        rows.insert(97 * (i + 1), row)
    return rows


def write_npy(path, descr, shape, values, typecode):
    header = "{'descr': '%s', 'fortran_order': False, 'shape': %s, }" % (descr, shape)
    header += " " * ((64 - (10 + len(header) + 1) % 64) % 64) + "\n"
    with open(path, "wb") as f:
        f.write(b"\x93NUMPY\x01\x00" + len(header).to_bytes(2, "little") + header.encode("latin1"))
        array.array(typecode, values).tofile(f)


def main():
    directory = sys.argv[1]
    os.makedirs(directory, exist_ok=True)
    rng = random.Random(20261202)
    curves = make_curves(rng)
    rows = make_points(rng, curves)
    with open(os.path.join(directory, "curves.json"), "w") as f:
        json.dump({"curves": [c.entry for c in curves]}, f)
    with open(os.path.join(directory, "points.csv"), "w") as f:
        f.write("curve,x,y\n")
        for cid, x, y in rows:
            f.write(f"{cid},{x!r},{y!r}\n")
    index = {c.id: i for i, c in enumerate(curves)}
    write_npy(os.path.join(directory, "points.npy"), "<f8", "(%d, 2)" % len(rows),
              [v for _, x, y in rows for v in (x, y)], "d")
    write_npy(os.path.join(directory, "curve-index.npy"), "<i8", "(%d,)" % len(rows),
              [index.get(cid, len(curves)) for cid, _, _ in rows], "q")
    # Whole-file failures: the message and the exit code are answers too.
    with open(os.path.join(directory, "bad-row.csv"), "w") as f:
        f.write("curve,x,y\nbezier-3-0,0.5,0.5\nbezier-3-0,0.5\n")
    with open(os.path.join(directory, "bad-number.csv"), "w") as f:
        f.write("curve,x,y\nbezier-3-0,0.5,abc\n")
    with open(os.path.join(directory, "bad-curves.json"), "w") as f:
        f.write('{"curves": [{"id": "a", "kind": "bezier", "points": [[0, 0], [1]]}]}')
    with open(os.path.join(directory, "bad-kind.json"), "w") as f:
        f.write('{"curves": [{"id": "a", "kind": "spline", "points": [[0, 0], [1, 1]]}]}')


if __name__ == "__main__":
    main()
