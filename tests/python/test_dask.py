# bezinv.dask: a dask array of points inverted block by block on a distributed.LocalCluster of
# worker processes (the plans reach them pickled) equals the single-process answer byte for byte.
import pickle

import numpy as np
import pytest

import bezinv
from conftest import curve_points

da = pytest.importorskip("dask.array")
distributed = pytest.importorskip("distributed")
import bezinv.dask  # noqa: E402

CURVES = [
    {"id": "cubic", "kind": "bezier", "points": [[0, 0], [1, 2], [3, 2], [4, 0]]},
    {"id": "arc", "kind": "rational_bezier", "points": [[1, 0], [1, 1], [0, 1]], "weights": [1, 0.7, 1]},
]


def points_and_index(count=40_000):
    rng = np.random.default_rng(3)
    index = rng.integers(0, 2, count)
    t = rng.uniform(-0.1, 1.1, count)
    points = np.empty((count, 2))
    for c, curve in enumerate(CURVES):
        points[index == c] = curve_points(curve, t[index == c])
    points += rng.normal(0, 1e-3, points.shape) * (rng.uniform(size=count) < 0.2)[:, None]
    return points, index


def test_plans_pickle_to_the_same_answers():
    plans = bezinv.plan(CURVES)
    again = pickle.loads(pickle.dumps(plans))
    assert again.planned and len(again) == 2 and again[1].id == "arc"
    points, index = points_and_index(2000)
    assert bezinv.invert(again, points, curve_index=index).tobytes() == bezinv.invert(plans, points, curve_index=index).tobytes()


def test_a_local_cluster_answers_as_one_process():
    plans = bezinv.plan(CURVES)
    points, index = points_and_index()
    expected = bezinv.invert(plans, points, curve_index=index)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster):
        lazy = bezinv.dask.invert(plans, da.from_array(points, chunks=(7_000, 2)),
                                  curve_index=da.from_array(index, chunks=(7_000,)), threads=1)
        assert lazy.dtype == bezinv.RESULT_DTYPE and lazy.numblocks == (6,)
        got = lazy.compute()
        one_curve = bezinv.dask.invert(plans, da.from_array(points, chunks=(9_000, 2)), curve="arc").compute()
        with_points = bezinv.dask.invert(plans, da.from_array(points, chunks=(9_000, 2)), curve="arc",
                                         columns=("point",))
        assert with_points.dtype == bezinv.RESULT_POINT_DTYPE
        with_points = with_points.compute()
    assert got.tobytes() == expected.tobytes()
    assert one_curve.tobytes() == bezinv.invert(plans, points, curve="arc").tobytes()
    assert with_points.tobytes() == bezinv.invert(plans, points, curve="arc", columns=("point",)).tobytes()


def test_dask_arguments_are_checked():
    plans = bezinv.plan(CURVES)
    with pytest.raises(ValueError, match="points: shape"):
        bezinv.dask.invert(plans, da.zeros((10, 4), chunks=5))
    with pytest.raises(ValueError, match="curve_index: shape"):
        bezinv.dask.invert(plans, da.zeros((10, 2), chunks=5), curve_index=np.zeros(9, dtype=int))
    with pytest.raises(ValueError, match="reasons"):
        bezinv.dask.invert(plans, da.zeros((10, 2), chunks=5), curve=0, reasons=True)
