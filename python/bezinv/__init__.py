"""bezinv for Python: the parameters of points on rational Bezier curves, for numpy arrays.

    import bezinv
    curves = bezinv.load_curves("curves.json")          # or a dict / list of dicts, CURVES.json's schema
    plans = bezinv.plan(curves)                          # the per-curve precomputation, once
    r = bezinv.invert(plans, points, curve="a")          # points: float64 (N, 2) or (N, 3)
    r["t"], r["status"], r["residual"]                   # OUT.npy's fields, one row per point

The answers are `bezinv invert`'s, byte for byte: the same engine, reader and checks run here,
with the GIL released. README "Python" says more; docs/python.md says how it is built.
"""
import json
import numbers
import os

import numpy as np

from . import _bezinv

__all__ = [
    "Curve", "Curves", "load_curves", "plan", "invert", "status_name", "path_name",
    "RESULT_DTYPE", "RESULT_POINT_DTYPE", "STATUS_NAMES", "PATH_NAMES", "DEFAULT_TOLERANCE", "kernel",
    "stress", "OK", "OUTSIDE_SEGMENT", "DOUBLE_POINT", "OFF_CURVE", "INVALID_INPUT", "FAILED",
]

Curve = _bezinv.Curve
Curves = _bezinv.Curves

# OUT.npy's record: packed, as numpy makes a dtype from a list (42 bytes a row).
RESULT_DTYPE = np.dtype([("t", "<f8"), ("residual", "<f8"), ("t2", "<f8"), ("sigma_min", "<f8"),
                         ("sigma_next", "<f8"), ("status", "u1"), ("path", "u1")])
# With columns=("point",) (--columns point): x_t, y_t, z_t, the curve's point at t, after path (66 bytes).
RESULT_POINT_DTYPE = np.dtype(RESULT_DTYPE.descr + [("x_t", "<f8"), ("y_t", "<f8"), ("z_t", "<f8")])
for _dtype, _point in ((RESULT_DTYPE, False), (RESULT_POINT_DTYPE, True)):
    if str(_dtype.descr) != _bezinv.result_descr(_point):
        # The engine writes the records; a layout that differs from what numpy reads would be garbage.
        raise ImportError("bezinv: the engine's result record %s is not %s" % (_bezinv.result_descr(_point), _dtype.descr))
_COLUMNS = ("point",)

STATUS_NAMES = tuple(_bezinv.status_names())  # the codes of the `status` field
PATH_NAMES = tuple(_bezinv.path_names())      # the codes of the `path` field
OK, OUTSIDE_SEGMENT, DOUBLE_POINT, OFF_CURVE, INVALID_INPUT, FAILED = range(6)
DEFAULT_TOLERANCE = _bezinv.default_relative_tolerance

_ALGEBRAIC = ("auto", "bezout", "formula")
_OFF_CURVE = ("nearest", "projection")
_MAX_THREADS = 1024  # as `bezinv invert --threads`


def status_name(code):
    """The name of a `status` code ("ok", "off_curve", ...)."""
    return STATUS_NAMES[int(code)]


def path_name(code):
    """The name of a `path` code ("bezout_lu", "nearest", ...)."""
    return PATH_NAMES[int(code)]


def kernel():
    """The SVD kernel the engine uses in this process (BEZINV_KERNEL forces one)."""
    return _bezinv.kernel()


def _jsonable(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError("curves: %r (%s) is not a number, list or string" % (value, type(value).__name__))


def load_curves(source):
    """Curves from a CURVES.json path, a dict {"curves": [...]}, a list of curve dicts, or one curve
    dict, in CURVES.json's schema (numpy arrays may stand for lists). Checked as `bezinv invert`
    checks the file: ValueError naming the curve and the field."""
    if isinstance(source, Curves):
        return source
    if isinstance(source, (str, os.PathLike)):
        return _bezinv.read_curves(os.fspath(source))
    if isinstance(source, dict):
        document = source if "curves" in source else {"curves": [source]}
    elif isinstance(source, (list, tuple)):
        document = {"curves": list(source)}
    else:
        raise TypeError("curves: expected a path, a dict {'curves': [...]}, a list of curve dicts or "
                        "bezinv.Curves, got %s" % type(source).__name__)
    # NaN and infinities are written as JSON does not allow, so the engine's reader refuses them
    # with the place they are at, as it would in a file.
    text = json.dumps(document, default=_jsonable, allow_nan=True)
    return _bezinv.parse_curves(text, "curves")


def _check_threads(threads):
    if isinstance(threads, bool) or not isinstance(threads, numbers.Integral):
        raise TypeError("threads: expected an integer, got %s" % type(threads).__name__)
    if not 0 <= threads <= _MAX_THREADS:
        raise ValueError("threads: must be 0 (all cores) to %d, got %d" % (_MAX_THREADS, threads))
    return int(threads)


def plan(curves, threads=0):
    """The plans of every curve (the per-curve precomputation), built in parallel. Pass the result
    to invert() for as many point arrays as you like."""
    return _bezinv.plan(load_curves(curves), _check_threads(threads))


def _points_array(points):
    try:
        array = np.asarray(points)
    except Exception as error:  # a ragged list, an object numpy cannot take
        raise TypeError("points: %s" % error) from None
    if array.dtype.kind not in "fiu":
        raise TypeError("points: expected a float64 array (N, 2) or (N, 3), got dtype %s" % array.dtype)
    if array.ndim != 2 or array.shape[1] not in (2, 3):
        raise ValueError("points: shape %s is not (N, 2) or (N, 3)" % (array.shape,))
    # No copy when the array is already C-contiguous float64.
    return np.ascontiguousarray(array, dtype=np.float64)


def _index_array(curve_index, rows):
    array = np.asarray(curve_index)
    if array.dtype.kind not in "iu":
        raise TypeError("curve_index: expected an integer array (N,), got dtype %s" % array.dtype)
    if array.ndim != 1:
        raise ValueError("curve_index: shape %s is not (N,)" % (array.shape,))
    if array.shape[0] != rows:
        raise ValueError("curve_index: %d indices for %d points" % (array.shape[0], rows))
    if array.dtype.kind == "u" and array.size and array.max() > np.iinfo(np.int64).max:
        raise ValueError("curve_index: an index beyond int64")
    return np.ascontiguousarray(array, dtype=np.int64)


def _point_columns(columns):
    """Whether `columns` (a name or a list of names, as invert takes them) asks for the point columns."""
    if isinstance(columns, str):
        columns = (columns,)
    try:
        columns = tuple(columns)
    except TypeError:
        raise TypeError("columns: expected a list of names, got %s" % type(columns).__name__) from None
    for name in columns:
        if name not in _COLUMNS:
            raise ValueError("columns: %r is not one of %s" % (name, ", ".join(_COLUMNS)))
    return "point" in columns


def invert(plans, points, curve=None, curve_index=None, tol=DEFAULT_TOLERANCE, refine=True, fast_path=True,
           algebraic="auto", off_curve="nearest", threads=0, reasons=False, out=None, columns=()):
    """The parameter of every point, as `bezinv invert` gives it.

    plans       plan(curves), or curves as load_curves takes them (plans are then built for the
                curves the points name)
    points      (N, 2) or (N, 3) array: x, y (, z for a space curve's points); read in place when
                C-contiguous float64
    curve       the curve of every point: its id or its 0-based index (default: the only curve)
    curve_index an integer (N,) array, each point's 0-based curve index (instead of curve)
    tol         on-curve tolerance relative to the control-point bounding-box diagonal
    refine      False: the paper's algebraic t (--no-refine)
    fast_path   False: every point by the SVD (--svd-only)
    algebraic   "auto", "bezout" or "formula" (--algebraic)
    off_curve   "nearest" or "projection" (--off-curve)
    threads     0: all cores
    reasons     True: also return a list of each row's reason (why invalid_input or failed)
    out         an array of RESULT_DTYPE, shape (N,), C-contiguous, to write the results into
                (reused across calls, it saves allocating and first touching the memory)
    columns     optional fields after the others (--columns): ("point",) adds x_t, y_t, z_t, the
                curve's point at t (z_t 0 on a plane curve, nan where t is nan); the results
                (and out) are then of RESULT_POINT_DTYPE

    Returns a structured array of RESULT_DTYPE (OUT.npy's fields: t, residual, t2, sigma_min,
    sigma_next, status, path), one row per point in order; with reasons, (results, reasons).
    A bad row gets its status (invalid_input for a non-finite coordinate or an unknown curve
    index); a bad argument raises TypeError or ValueError naming it.
    """
    curves = plans if isinstance(plans, Curves) else load_curves(plans)
    array = _points_array(points)
    rows = array.shape[0]
    if curve is not None and curve_index is not None:
        raise ValueError("give curve or curve_index, not both")
    index = None
    if curve_index is not None:
        index = _index_array(curve_index, rows)
        selection = ""
    elif curve is None:
        if len(curves) != 1:
            raise ValueError("curve: %d curves: name the points' curve (curve=) or give curve_index" % len(curves))
        selection = "0"
    elif isinstance(curve, bool) or not isinstance(curve, (str, numbers.Integral)):
        raise TypeError("curve: expected an id or an index, got %s" % type(curve).__name__)
    else:
        selection = str(curve)
    if isinstance(tol, bool) or not isinstance(tol, numbers.Real):
        raise TypeError("tol: expected a number, got %s" % type(tol).__name__)
    if not (np.isfinite(tol) and tol > 0):
        raise ValueError("tol: must be finite and > 0, got %r" % (tol,))
    if algebraic not in _ALGEBRAIC:
        raise ValueError("algebraic: %r is not one of %s" % (algebraic, ", ".join(_ALGEBRAIC)))
    if off_curve not in _OFF_CURVE:
        raise ValueError("off_curve: %r is not one of %s" % (off_curve, ", ".join(_OFF_CURVE)))
    point = _point_columns(columns)
    dtype, dtype_name = (RESULT_POINT_DTYPE, "RESULT_POINT_DTYPE") if point else (RESULT_DTYPE, "RESULT_DTYPE")
    if out is None:
        out = np.empty(rows, dtype=dtype)
    elif not isinstance(out, np.ndarray) or out.dtype != dtype or out.shape != (rows,):
        raise ValueError("out: expected an array of bezinv.%s and shape (%d,)" % (dtype_name, rows))
    elif not (out.flags["C_CONTIGUOUS"] and out.flags["WRITEABLE"]):
        raise ValueError("out: must be C-contiguous and writeable")
    why = _bezinv.invert(curves, array, array.shape[1], selection, index, out, float(tol), bool(refine),
                         bool(fast_path), algebraic, off_curve, _check_threads(threads), bool(reasons), point)
    return (out, why) if reasons else out


def stress(families=None, kinds=("bezier", "rational_bezier", "rational"), degrees=(1, 24), points=100_000,
           curves=4, seed=20261203, paths=("default",), tol=DEFAULT_TOLERANCE, threads=0):
    """`bezinv stress --json` as a dict: curves of each family, kind and degree with points whose
    true parameters are known to 128 bits, inverted by each path, and how far each answer is from
    the truth (README "bezinv stress"; the families: datasets_gen/include/bezinv/datasets/stress.hpp).

    families, kinds, paths: lists of names (families=None: all); degrees: an int or (lo, hi).
    The result's "wrong_status", "nan_t" and "missing_t2" are 0 when every answer is right."""
    def names(value, what):
        if isinstance(value, str):
            return value
        try:
            return ",".join(str(v) for v in value)
        except TypeError:
            raise TypeError("%s: expected a list of names, got %s" % (what, type(value).__name__)) from None

    if isinstance(degrees, numbers.Integral):
        degrees = (degrees, degrees)
    low, high = degrees
    for name, value in (("points", points), ("curves", curves)):
        if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 1:
            raise ValueError("%s: must be an integer >= 1, got %r" % (name, value))
    if not (np.isfinite(tol) and tol > 0):
        raise ValueError("tol: must be finite and > 0, got %r" % (tol,))
    text = _bezinv.stress("" if families is None else names(families, "families"), names(kinds, "kinds"),
                          "%d-%d" % (low, high), int(points), int(curves), int(seed), names(paths, "paths"),
                          float(tol), _check_threads(threads))
    return json.loads(text)
