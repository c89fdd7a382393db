# The Python module's tests run against the build tree: CMake's ctest entry sets PYTHONPATH to
# build/python and BEZINV_CLI to the command, so the module's answers can be held against it.
import json
import os
import subprocess

import numpy as np
import pytest

# Set by CMake in the sanitizer tree, where the engine runs 5-20x slower: the heaviest tests then
# invert fewer points along the same paths.
SANITIZER_TREE = os.environ.get("BEZINV_SANITIZER_TREE") == "1"


@pytest.fixture
def cli():
    path = os.environ.get("BEZINV_CLI")
    if not path:
        pytest.fail("BEZINV_CLI is not set (run these tests through ctest)")
    return path


def run_cli(cli, *arguments):
    done = subprocess.run([cli, *map(str, arguments)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done


def write_curves(directory, curves):
    path = os.path.join(directory, "curves.json")
    with open(path, "w") as f:
        json.dump({"curves": curves}, f)
    return path


def bernstein(n, t):
    """The degree-n Bernstein basis at t, (len(t), n+1), by the binomial formula (independent of the engine)."""
    from math import comb
    t = np.asarray(t, dtype=float)[:, None]
    i = np.arange(n + 1)[None, :]
    return np.array([comb(n, k) for k in range(n + 1)])[None, :] * t ** i * (1 - t) ** (n - i)


def bezier_points(control, t, weights=None):
    """P(t) of a (rational) Bezier curve given by its control points, for an array of t."""
    control = np.asarray(control, dtype=float)
    n = len(control) - 1
    b = bernstein(n, t)
    w = np.ones(n + 1) if weights is None else np.asarray(weights, dtype=float)
    return (b * w) @ control / (b @ w)[:, None]


def curve_points(curve, t):
    """P(t) of a CURVES.json curve dict of kind bezier, rational_bezier or rational."""
    if curve["kind"] in ("bezier", "rational_bezier"):
        return bezier_points(curve["points"], t, curve.get("weights"))
    n = len(curve["x_num"]) - 1
    b = bernstein(n, t)
    columns = [(b @ np.asarray(curve[c + "_num"], float)) / (b @ np.asarray(curve[c + "_den"], float))
               for c in ("x", "y", "z") if c + "_num" in curve]
    return np.stack(columns, 1)
