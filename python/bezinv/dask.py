"""bezinv over a dask array of points: each block of rows is inverted where it lives, by
bezinv.invert, so the result equals the single-process one row for row.

    import dask.array as da, bezinv, bezinv.dask
    points = da.from_npy_stack(...)  # or da.from_array(np.load(..., mmap_mode="r"), chunks=(1_000_000, 2))
    r = bezinv.dask.invert(bezinv.plan("curves.json"), points, curve="a")
    r.compute()  # or r.to_zarr(...) / da.to_npy_stack(...) for results larger than memory

The plans travel to the workers pickled (the curves' coefficients; each worker builds them again,
microseconds a curve). README "Past one machine" says when this pays and what it costs.
"""
import dask.array as da
import numpy as np

import bezinv


def _invert_block(points, curve_index=None, *, curves, curve, options):
    return bezinv.invert(curves, points, curve=curve, curve_index=curve_index, **options)


def invert(plans, points, curve=None, curve_index=None, **options):
    """bezinv.invert for a dask array `points` (N, 2) or (N, 3), chunked along rows (its columns
    are made one chunk), and optionally a dask or numpy (N,) `curve_index`. The other keywords are
    bezinv.invert's (not `reasons`). Returns a lazy (N,) dask array of bezinv.RESULT_DTYPE
    (RESULT_POINT_DTYPE with columns=("point",)).

    `threads` is per block: with several single-threaded workers per machine, pass threads=1;
    with one worker per machine, leave it 0 (all cores)."""
    if "reasons" in options:
        raise ValueError("reasons: not available with dask (call bezinv.invert on the rows of interest)")
    curves = plans if isinstance(plans, bezinv.Curves) else bezinv.load_curves(plans)
    points = da.asarray(points)
    if points.ndim != 2 or points.shape[1] not in (2, 3):
        raise ValueError("points: shape %s is not (N, 2) or (N, 3)" % (points.shape,))
    points = points.rechunk({1: -1})
    if curve is None and curve_index is None and len(curves) != 1:
        raise ValueError("curve: %d curves: name the points' curve (curve=) or give curve_index" % len(curves))
    arguments = [points, "ij"]
    if curve_index is not None:
        index = da.asarray(curve_index)
        if index.shape != (points.shape[0],):
            raise ValueError("curve_index: shape %s does not match the %d points" % (index.shape, points.shape[0]))
        arguments += [index.rechunk((points.chunks[0],)), "i"]
    if curve is None and curve_index is None:
        curve = 0
    dtype = bezinv.RESULT_POINT_DTYPE if bezinv._point_columns(options.get("columns", ())) else bezinv.RESULT_DTYPE
    # blockwise over the rows (i); the columns (j, one chunk) are taken whole by each block.
    return da.blockwise(_invert_block, "i", *arguments, curves=curves, curve=curve, options=options,
                        dtype=dtype, concatenate=True, meta=np.empty((0,), dtype=dtype))
