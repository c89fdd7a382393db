# import bezinv; invert numpy arrays: answers against known parameters (points made from a known
# t by the Bernstein formula here, not by the engine) and against `bezinv invert` byte for byte.
import os
import threading

import numpy as np
import pytest

import bezinv
from conftest import SANITIZER_TREE, bezier_points, curve_points, run_cli, write_curves

CUBIC = {"id": "cubic", "kind": "bezier", "points": [[0, 0], [1, 2], [3, 2], [4, 0]]}
ARC = {"id": "arc", "kind": "rational_bezier", "points": [[1, 0], [1, 1], [0, 1]], "weights": [1, 0.7071067811865476, 1]}
GRAPH = {"id": "graph", "kind": "rational", "x_num": [0, 1, 2, 3], "x_den": [1, 1, 1, 1],
         "y_num": [1, -2, 5, 0.5], "y_den": [1, 1.5, 0.8, 1]}
SPACE = {"id": "helix", "kind": "bezier", "points": [[1, 0, 0], [1, 1, 0.5], [-1, 1, 1], [-1, 0, 1.5]]}
CURVES = [CUBIC, ARC, GRAPH, SPACE]


def test_points_made_from_known_parameters_come_back_with_their_t():
    curves = bezinv.load_curves(CURVES)
    plans = bezinv.plan(curves)
    t = np.linspace(0, 1, 101)
    for name, control, weights in (("cubic", CUBIC["points"], None), ("arc", ARC["points"], ARC["weights"]),
                                   ("helix", SPACE["points"], None)):
        points = bezier_points(control, t, weights)
        r = bezinv.invert(plans, points, curve=name)
        assert r.dtype == bezinv.RESULT_DTYPE and r.shape == (101,)
        assert np.all(r["status"] == bezinv.OK), name
        np.testing.assert_allclose(r["t"], t, atol=1e-12, err_msg=name)
        assert np.all(r["residual"] < 1e-12)


def test_the_answers_are_the_commands_byte_for_byte(tmp_path, cli):
    rng = np.random.default_rng(7)
    curves_path = write_curves(str(tmp_path), CURVES[:3])
    count = 3000
    index = rng.integers(0, 3, count)
    t = rng.uniform(-0.2, 1.2, count)
    points = np.empty((count, 2))
    for c, curve in enumerate(CURVES[:3]):
        points[index == c] = curve_points(curve, t[index == c])
    points += rng.normal(0, 1e-3, points.shape) * (rng.uniform(size=count) < 0.3)[:, None]  # some off the curve
    points[5] = [np.nan, 1.0]
    points[6] = [np.inf, 0.0]
    index[7] = 3   # past the end
    index[8] = -1  # negative
    np.save(tmp_path / "points.npy", points)
    np.save(tmp_path / "index.npy", index.astype(np.int64))
    plans = bezinv.plan(curves_path)
    variants = [[], ["--no-refine"], ["--svd-only"], ["--algebraic", "formula"], ["--algebraic", "bezout"],
                ["--off-curve", "projection"], ["--tol", "1e-6"]]
    keywords = [{}, {"refine": False}, {"fast_path": False}, {"algebraic": "formula"}, {"algebraic": "bezout"},
                {"off_curve": "projection"}, {"tol": 1e-6}]
    for flags, options in zip(variants, keywords):
        out = tmp_path / "out.npy"
        run_cli(cli, "invert", "--curves", curves_path, "--points", tmp_path / "points.npy",
                "--curve-index", tmp_path / "index.npy", "--out", out, *flags)
        expected = np.load(out)
        got = bezinv.invert(plans, points, curve_index=index, **options)
        assert got.tobytes() == expected.tobytes(), flags
        # The curves unplanned (plans built for the curves the points name) answer the same.
        assert bezinv.invert(curves_path, points, curve_index=index, **options).tobytes() == expected.tobytes()
    # One curve for every point, by id: with bad rows (the reader's checks), and every row finite
    # (the module then hands the array to the engine in place).
    run_cli(cli, "invert", "--curves", curves_path, "--points", tmp_path / "points.npy", "--curve", "arc",
            "--out", tmp_path / "arc.npy")
    assert bezinv.invert(plans, points, curve="arc").tobytes() == np.load(tmp_path / "arc.npy").tobytes()
    finite = np.ascontiguousarray(points[np.isfinite(points).all(axis=1)])
    np.save(tmp_path / "finite.npy", finite)
    for flags, options in zip(variants, keywords):
        run_cli(cli, "invert", "--curves", curves_path, "--points", tmp_path / "finite.npy", "--curve", "1",
                "--out", tmp_path / "finite-out.npy", *flags)
        expected = np.load(tmp_path / "finite-out.npy")
        assert bezinv.invert(plans, finite, curve=1, **options).tobytes() == expected.tobytes(), flags
        assert bezinv.invert(plans, finite, curve="arc", reasons=True, **options)[0].tobytes() == expected.tobytes()


def test_arrays_of_many_chunks_match_the_command_on_any_thread_count(tmp_path, cli):
    # Past the in-place path's chunk of 16,384 rows (the chunks are inverted and packed in parallel),
    # and with a non-finite coordinate in the third chunk (the call then goes the reader's way).
    rng = np.random.default_rng(11)
    curves_path = write_curves(str(tmp_path), [CUBIC])
    points = curve_points(CUBIC, rng.uniform(-0.1, 1.1, 36000))
    points += rng.normal(0, 1e-3, points.shape) * (rng.uniform(size=len(points)) < 0.3)[:, None]
    plans = bezinv.plan(curves_path)
    for bad in (None, [np.nan, 0.0], [1.0, -np.inf]):
        if bad is not None:
            points[34000] = bad
        np.save(tmp_path / "many.npy", points)
        run_cli(cli, "invert", "--curves", curves_path, "--points", tmp_path / "many.npy", "--curve", "cubic",
                "--out", tmp_path / "many-out.npy")
        expected = np.load(tmp_path / "many-out.npy")
        for threads in (1, 0) if SANITIZER_TREE else (1, 2, 0):
            got = bezinv.invert(plans, points, curve="cubic", threads=threads)
            assert got.tobytes() == expected.tobytes(), (bad, threads)
        if bad is not None:
            assert expected["status"][34000] == bezinv.INVALID_INPUT


def test_point_columns_match_the_command(tmp_path, cli):
    # columns=("point",) is --columns point: the same records, byte for byte, plane and space curves,
    # bad rows included; x_t, y_t of a point made from a known t are that point.
    curves_path = write_curves(str(tmp_path), CURVES)
    rng = np.random.default_rng(3)
    t = rng.uniform(0, 1, 200)
    points = curve_points(CUBIC, t)
    points[7] = [np.nan, 0.0]
    np.save(tmp_path / "p.npy", points)
    run_cli(cli, "invert", "--curves", curves_path, "--points", tmp_path / "p.npy", "--curve", "cubic",
            "--columns", "point", "--out", tmp_path / "o.npy")
    expected = np.load(tmp_path / "o.npy")
    got = bezinv.invert(curves_path, points, curve="cubic", columns=("point",))
    assert got.dtype == bezinv.RESULT_POINT_DTYPE == expected.dtype
    assert got.tobytes() == expected.tobytes()
    finite = np.isfinite(points).all(axis=1)
    np.testing.assert_allclose(np.stack([got["x_t"], got["y_t"]], axis=1)[finite], points[finite], atol=1e-12)
    assert np.all(got["z_t"][finite] == 0) and np.isnan(got["x_t"][7])
    space = curve_points(SPACE, t)
    np.save(tmp_path / "s.npy", space)
    run_cli(cli, "invert", "--curves", curves_path, "--points", tmp_path / "s.npy", "--curve", "helix",
            "--columns", "point", "--out", tmp_path / "so.npy")
    got = bezinv.invert(curves_path, space, curve="helix", columns="point")
    assert got.tobytes() == np.load(tmp_path / "so.npy").tobytes()
    np.testing.assert_allclose(np.stack([got["x_t"], got["y_t"], got["z_t"]], axis=1), space, atol=1e-12)
    with pytest.raises(ValueError, match="columns: 'normal'"):
        bezinv.invert(curves_path, points, curve="cubic", columns=("normal",))
    with pytest.raises(ValueError, match="RESULT_POINT_DTYPE"):
        bezinv.invert(curves_path, points, curve="cubic", columns=("point",), out=np.empty(200, bezinv.RESULT_DTYPE))


def test_space_points_match_the_command(tmp_path, cli):
    curves_path = write_curves(str(tmp_path), [SPACE])
    t = np.linspace(-0.1, 1.1, 257)
    points = bezier_points(SPACE["points"], t) + np.array([0, 0, 1e-4]) * (t > 0.5)[:, None]
    np.save(tmp_path / "p.npy", points)
    run_cli(cli, "invert", "--curves", curves_path, "--points", tmp_path / "p.npy", "--curve", "0", "--out", tmp_path / "o.npy")
    r = bezinv.invert(curves_path, points)
    assert r.tobytes() == np.load(tmp_path / "o.npy").tobytes()
    assert set(r["status"]) <= {bezinv.OK, bezinv.OUTSIDE_SEGMENT, bezinv.OFF_CURVE}


def test_a_contiguous_float64_array_is_read_in_place_and_others_are_converted():
    points = np.zeros((10, 2))
    assert bezinv._points_array(points) is points
    strided = np.zeros((10, 4))[:, ::2]
    assert bezinv._points_array(strided).flags["C_CONTIGUOUS"]
    plans = bezinv.plan([CUBIC])
    t = np.linspace(0, 1, 11)
    exact = bezier_points(CUBIC["points"], t)
    reused = np.zeros(11, dtype=bezinv.RESULT_DTYPE)
    assert bezinv.invert(plans, exact, out=reused) is reused
    assert reused.tobytes() == bezinv.invert(plans, exact).tobytes()
    as_list = bezinv.invert(plans, exact.tolist())
    as_fortran = bezinv.invert(plans, np.asfortranarray(exact))
    assert as_list.tobytes() == as_fortran.tobytes() == bezinv.invert(plans, exact).tobytes()


def test_bad_rows_get_their_status_and_reason():
    plans = bezinv.plan([CUBIC, SPACE])
    points = np.array([[0.0, 0.0], [np.nan, 0.0], [0.0, -np.inf], [4.0, 0.0], [1.0, 1.0]])
    r, reasons = bezinv.invert(plans, points, curve_index=np.array([0, 0, 0, 5, 1], dtype=np.int32), reasons=True)
    assert [bezinv.status_name(s) for s in r["status"]] == ["ok", "invalid_input", "invalid_input", "invalid_input",
                                                            "invalid_input"]
    assert reasons == ["", "x is not finite", "y is not finite", "curve index past the end",
                       "no z for a point of a space curve"]


def test_errors_name_the_argument_or_the_field():
    with pytest.raises(ValueError, match=r"curves\[1\].*weights"):
        bezinv.load_curves([CUBIC, {"id": "w", "kind": "rational_bezier", "points": [[0, 0], [1, 1]], "weights": [1]}])
    with pytest.raises(ValueError, match=r"curves\[0\].*points"):
        bezinv.load_curves({"id": "nan", "kind": "bezier", "points": [[0, float("nan")], [1, 1]]})
    with pytest.raises(ValueError, match="no such file|cannot read"):
        bezinv.load_curves("/nonexistent/curves.json")
    with pytest.raises(TypeError, match="curves"):
        bezinv.load_curves(42)
    plans = bezinv.plan([CUBIC, ARC])
    with pytest.raises(ValueError, match=r"points: shape \(4, 5\)"):
        bezinv.invert(plans, np.zeros((4, 5)), curve=0)
    with pytest.raises(TypeError, match="points"):
        bezinv.invert(plans, np.array([["a", "b"]]), curve=0)
    with pytest.raises(ValueError, match="curve.*name the points' curve"):
        bezinv.invert(plans, np.zeros((4, 2)))
    with pytest.raises(ValueError, match="curve 'nope'"):
        bezinv.invert(plans, np.zeros((4, 2)), curve="nope")
    with pytest.raises(ValueError, match="plane curve, whose points are"):
        bezinv.invert(plans, np.zeros((4, 3)), curve="cubic")
    with pytest.raises(ValueError, match="curve_index: 3 indices for 4 points"):
        bezinv.invert(plans, np.zeros((4, 2)), curve_index=[0, 1, 0])
    with pytest.raises(TypeError, match="curve_index"):
        bezinv.invert(plans, np.zeros((2, 2)), curve_index=[0.0, 1.0])
    with pytest.raises(ValueError, match="tol"):
        bezinv.invert(plans, np.zeros((2, 2)), curve=0, tol=float("nan"))
    with pytest.raises(ValueError, match="algebraic"):
        bezinv.invert(plans, np.zeros((2, 2)), curve=0, algebraic="svd")
    with pytest.raises(ValueError, match="off_curve"):
        bezinv.invert(plans, np.zeros((2, 2)), curve=0, off_curve="far")
    with pytest.raises(ValueError, match="out"):
        bezinv.invert(plans, np.zeros((2, 2)), curve=0, out=np.empty(3, dtype=bezinv.RESULT_DTYPE))
    with pytest.raises(ValueError, match="out"):
        bezinv.invert(plans, np.zeros((2, 2)), curve=0, out=np.empty(2))
    with pytest.raises(ValueError, match="threads"):
        bezinv.invert(plans, np.zeros((2, 2)), curve=0, threads=-1)


def test_curves_from_dicts_with_numpy_arrays_are_the_files_curves(tmp_path):
    as_arrays = dict(CUBIC, points=np.array(CUBIC["points"], dtype=float))
    from_dict = bezinv.load_curves({"curves": [as_arrays]})
    from_file = bezinv.load_curves(write_curves(str(tmp_path), [CUBIC]))
    assert len(from_dict) == len(from_file) == 1
    c = from_dict[0]
    assert (c.id, c.kind, c.degree, c.dimension) == ("cubic", "bezier", 3, 2)
    assert c.point(0.5) == from_file[0].point(0.5) == (2.0, 1.5)


def test_the_engine_runs_without_the_gil():
    # While one thread inverts a million points (200,000 in the slower sanitizer tree), another
    # runs Python: it could not if the engine held the interpreter lock.
    plans = bezinv.plan([CUBIC])
    count = 200_000 if SANITIZER_TREE else 1_000_000
    points = bezier_points(CUBIC["points"], np.random.default_rng(1).uniform(0, 1, count))
    started, done = threading.Event(), threading.Event()

    def work():
        started.set()
        bezinv.invert(plans, points, threads=1)
        done.set()

    worker = threading.Thread(target=work)
    worker.start()
    started.wait()
    spins, spins_while_inverting = 0, 0
    while not done.is_set():
        spins += 1
        if spins == 200_000:
            spins_while_inverting = 0 if done.is_set() else spins
    worker.join()
    assert spins_while_inverting == 200_000, "the main thread could not run while the engine worked"


def test_stress_reports_as_the_command_does(cli):
    import json
    import subprocess
    options = dict(families=["on_curve", "noisy"], kinds=["bezier"], degrees=(2, 3), points=400, curves=2, seed=5)
    got = bezinv.stress(**options)
    command = subprocess.run([cli, "stress", "--families", "on_curve,noisy", "--kinds", "bezier", "--degrees", "2-3",
                              "--points", "400", "--curves", "2", "--seed", "5", "--json"], capture_output=True, text=True)
    expected = json.loads(command.stdout)
    assert got["rows"] == expected["rows"] > 0
    assert got["wrong_status"] == expected["wrong_status"] == 0
    for a, b in zip(got["cells"], expected["cells"]):
        assert (a["family"], a["degree"], a["rows"], a["confusion"], a["abs_dt"]) == \
               (b["family"], b["degree"], b["rows"], b["confusion"], b["abs_dt"])
    with pytest.raises(ValueError, match="nosuchfamily"):
        bezinv.stress(families=["nosuchfamily"])


def test_nurbs_and_composite_curves_answer_as_the_command(tmp_path, cli):
    import pickle
    # A quarter circle as a clamped rational B-spline of two eighth-circle spans (a double knot at 1),
    # and a composite of a segment
    # and a cubic: points made from the known parameter (the circle's angle in closed form).
    nurbs = {"id": "n", "kind": "nurbs", "degree": 2, "knots": [0, 0, 0, 1, 1, 2, 2, 2],
             "points": [[1, 0], [1, 0.4142135623730951], [0.7071067811865476, 0.7071067811865476],
                        [0.4142135623730951, 1], [0, 1]],
             "weights": [1, 0.9238795325112867, 1, 0.9238795325112867, 1]}
    composite = {"id": "c", "kind": "composite", "curves": [
        {"kind": "bezier", "points": [[0, 0], [1, 0]]},
        {"kind": "bezier", "points": [[1, 0], [2, 1], [3, 1], [4, 0]]}]}
    curves_path = write_curves(str(tmp_path), [nurbs, composite])
    plans = bezinv.plan(curves_path)
    assert plans[0].kind == "nurbs" and len(plans[1].parts) == 2
    angle = np.linspace(0, np.pi / 2, 9)
    points = np.stack([np.cos(angle), np.sin(angle)], 1)
    r = bezinv.invert(plans, points, curve="n")
    assert np.all(r["status"] == bezinv.OK)
    # On this circle the knot parameter u in [0, 2] meets the angle at u = 0, 1, 2 (0, 45, 90 degrees).
    np.testing.assert_allclose(r["t"][[0, 4, 8]], [0, 1, 2], atol=1e-12)
    assert np.all(np.diff(r["t"]) > 0)
    np.save(tmp_path / "p.npy", points)
    run_cli(cli, "invert", "--curves", curves_path, "--points", tmp_path / "p.npy", "--curve", "n", "--out", tmp_path / "o.npy")
    assert r.tobytes() == np.load(tmp_path / "o.npy").tobytes()
    on_composite = np.array([[0.5, 0.0], [1.0, 0.0], [4.0, 0.0], [2.5, 0.75], [5.0, -4.0 / 3.0]])  # the last on the extension, s = 4/3
    rc = bezinv.invert(plans, on_composite, curve="c")
    np.testing.assert_allclose(rc["t"][:4], [0.5, 1.0, 2.0, 1.5], atol=1e-12)
    assert [bezinv.status_name(s) for s in rc["status"]] == ["ok"] * 4 + ["outside_segment"]
    again = pickle.loads(pickle.dumps(plans))
    assert bezinv.invert(again, on_composite, curve="c").tobytes() == rc.tobytes()
