"""The Python call against the C++ engine on the same points, in one process, turn by turn.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_speed.py [--points 10000000] [--rounds 5]

Each round times bezinv.invert(plans, points, out=results) (numpy in, OUT.npy records out into an
array reused from round to round) and bezinv::invert itself on the same points (C++ spans, no
records, its results allocated before the clock starts: _bezinv.engine_seconds), in alternating
order; prints each pair's ratio and their median. --fresh: the Python call allocates its output
each time (as bezinv.invert does without out=). Points on a cubic and on a degree-8 curve, made from known t (Bernstein formula).
"""
import argparse
import json
import statistics
import time
from math import comb

import numpy as np

import bezinv
from bezinv import _bezinv


def bezier(control, t):
    control = np.asarray(control, dtype=float)
    n = len(control) - 1
    out = np.zeros((len(t), 2))
    for k in range(n + 1):
        out += (comb(n, k) * t ** k * (1 - t) ** (n - k))[:, None] * control[k]
    return out


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--points", type=int, default=10_000_000)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--fresh", action="store_true")
    arguments = parser.parse_args()
    rng = np.random.default_rng(11)
    curves = {
        "cubic": [[0, 0], [1, 2], [3, 2], [4, 0]],
        "degree 8": [[k + 0.3 * np.sin(3 * k), np.sin(0.7 * k)] for k in range(9)],
    }
    rows = []
    for name, control in curves.items():
        plans = bezinv.plan([{"id": name, "kind": "bezier", "points": control}])
        points = bezier(control, rng.uniform(0, 1, arguments.points))
        ratios, python_s, engine_s = [], [], []
        out = None if arguments.fresh else np.empty(arguments.points, dtype=bezinv.RESULT_DTYPE)
        if out is not None:
            out[:] = 0  # touched once, as a reused array is
        for r in range(arguments.rounds):
            order = ("python", "engine") if r % 2 == 0 else ("engine", "python")
            for which in order:
                if which == "python":
                    start = time.perf_counter()
                    bezinv.invert(plans, points, threads=arguments.threads, out=out)
                    python_s.append(time.perf_counter() - start)
                else:
                    engine_s.append(_bezinv.engine_seconds(plans, points, 0, arguments.threads))
            ratios.append(python_s[-1] / engine_s[-1])
        row = {"curve": name, "points": arguments.points, "python_s": statistics.median(python_s),
               "engine_s": statistics.median(engine_s), "ratios": [round(x, 4) for x in ratios],
               "median_ratio": statistics.median(ratios)}
        rows.append(row)
        print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
