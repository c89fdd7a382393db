#!/usr/bin/python3
"""Compares two `bezinv invert` outputs (CSV or .npy) row by row, within the accuracy bound.

    compare_results.py BASE THIS

Same number of rows, and per row: the same status, path and reason; t, t2, the residual and the
singular values equal, or both NaN, or within 1e-9 (t, t2: absolute, in the parameter; the others:
relative, plus 1e-13 for the residual). That is the accuracy bezinv promises for a parameter (ACCURACY.md): a change of method
that keeps it gives "the same answers" even where the last bits move.

An off_curve row answers with the nearest point of the segment; where two points of it are equally
near (a curve traced twice, a point on an axis of symmetry, a point so far that every distance
rounds alike), either is the answer. Such a row, everything else the same and the residual within
the bound but t elsewhere, is counted as "equally near", not as a difference.

An off_curve row whose evidence changed with the route it took (answered now by distance alone,
path nearest without singular values: the off-curve path, engine/src/pipeline/off_curve_path.hpp;
or now by the SVD path where the base answered it from the fast path's estimates, path bezout_lu)
is the same answer when its residual is within the bound (t is then the same point, or an equally
near one, as above): counted as "other evidence". So is an ok row whose second parameter another
certificate ruled out: the isolation certificate on the fast path (path bezout_lu, no
sigma_next, sigma_min the seed's estimate; engine/src/isolation.hpp) where the base ran the gap
pass (path bezout_lu, sigma_next from the full kernel) or the SVD path (path bezout, the exact
singular values; bezout_pair, its search for a second parameter finding none other), or the
other way, with the same status and reason and t, t2 and the residual
within the bound.

An ok row decided by the fast path's gap (path bezout_lu, sigma_min and sigma_next the full kernel's
estimates: the gap pass, or the seed retry for a lane whose seed fell just short,
engine/src/pipeline/seed_retry.hpp) where the base took the SVD path (path bezout, the exact
singular values), or the other way, is the same answer when its status, reason, t, t2 and the
residual are within the bound and the estimate of sigma_next is at most twice the SVD's (the
engine's gate, kFastPathGapRatio) and at least an eighth of it (the estimate is relative to
||B||_F, up to sqrt(n) sigma_1, n <= 32): counted as "other evidence".

An ok row now answered from the inversion formula's start (path formula: no B was formed, so no
singular values) where the base answered from B's null vector (path bezout_lu, or bezout where the
seed left the row to the SVD path: a point off the curve within a loose tolerance), or the other
way, is the same answer when its status, reason, t and residual are within the bound: counted as
"another start" (the default's algebraic step on cubics, engine/src/pipeline/formula_path.hpp).

Prints a summary line and every row beyond the bound; exit 1 if there is one.
"""
import ast
import csv
import math
import struct
import sys

NUMERIC = ("t", "residual", "t2", "sigma_min", "sigma_next")
TEXT = ("status", "path", "reason")
BOUND = 1e-9
RESIDUAL_FLOOR = 1e-13


def rows(path):
    if path.endswith(".npy"):
        # bezinv's result records (engine/io/results.cpp): five little-endian doubles, two bytes.
        with open(path, "rb") as f:
            data = f.read()
        if data[:6] != b"\x93NUMPY":
            raise SystemExit(f"{path}: not a .npy file")
        header_length, start = (struct.unpack_from("<H", data, 8)[0], 10) if data[6] == 1 else \
            (struct.unpack_from("<I", data, 8)[0], 12)
        header = ast.literal_eval(data[start:start + header_length].decode("latin1"))
        names = [name for name, _ in header["descr"]]
        if names != list(NUMERIC) + ["status", "path"]:
            raise SystemExit(f"{path}: unexpected record {header['descr']}")
        for offset in range(start + header_length, len(data), 42):
            *numbers, status, way = struct.unpack_from("<5dBB", data, offset)
            yield {**dict(zip(NUMERIC, numbers)), "status": status, "path": way}
    else:
        with open(path, newline="") as f:
            for r in csv.DictReader(f):
                out = {k: float(r[k]) for k in NUMERIC if k in r}
                out.update({k: r[k] for k in TEXT if k in r})
                yield out


def close(name, a, b):
    if a == b or (math.isnan(a) and math.isnan(b)):
        return True
    if math.isnan(a) or math.isnan(b):
        return False
    if name in ("t", "t2"):
        return abs(a - b) <= BOUND
    # A residual is |P(t) - P0|, rounded at the scale of the coordinates: a tiny one (a point
    # 1e-10 from a curve of size 1) moves by a relative 1e-7 when its last bits do.
    floor = RESIDUAL_FLOOR if name == "residual" else 0.0
    return abs(a - b) <= BOUND * max(abs(a), abs(b)) + floor


def off_curve_nearest(r):
    """An off_curve row at a nearest point of the segment, by any route (paths nearest, bezout_lu)."""
    return r.get("status") in ("off_curve", 3) and r.get("path") in ("nearest", "bezout_lu", 4, 5) and \
        r.get("reason", "") == "" and math.isnan(r.get("t2", math.nan))


def certified_other_way(x, y):
    """An ok row whose second parameter the isolation certificate ruled out in one (path bezout_lu,
    no sigma_next) and the gap pass or the SVD path in the other, the answer within the bound."""
    def by_b(r):  # the SVD path's pair search (bezout_pair) may have found the same parameter
        return r.get("status") in ("ok", 0) and r.get("path") in ("bezout", "bezout_lu", "bezout_pair", 1, 2, 5)

    def isolated(r):
        return r.get("path") in ("bezout_lu", 5) and math.isnan(r["sigma_next"])
    return by_b(x) and by_b(y) and isolated(x) != isolated(y) and \
        x.get("reason", "") == y.get("reason", "") and close("t", x["t"], y["t"]) and \
        close("t2", x["t2"], y["t2"]) and close("residual", x["residual"], y["residual"])


def gap_other_way(x, y):
    """An ok row decided by the full kernel's gap in one (path bezout_lu, sigma_next an estimate)
    and by the SVD path in the other (path bezout), the answer within the bound."""
    def by_gap(r):
        return r.get("path") in ("bezout_lu", 5) and not math.isnan(r["sigma_next"])

    def by_svd(r):
        return r.get("path") in ("bezout", 1)
    if not (x.get("status") in ("ok", 0) and y.get("status") == x.get("status")):
        return False
    if not ((by_gap(x) and by_svd(y)) or (by_svd(x) and by_gap(y))):
        return False
    gap, svd = (x, y) if by_gap(x) else (y, x)
    ratio = gap["sigma_next"] / svd["sigma_next"] if svd["sigma_next"] > 0 else math.inf
    return x.get("reason", "") == y.get("reason", "") and 1 / 8 <= ratio <= 2 and close("t", x["t"], y["t"]) and \
        close("t2", x["t2"], y["t2"]) and close("residual", x["residual"], y["residual"])


def started(r):
    """An ok row from an algebraic start: B's null vector (paths bezout, bezout_lu) or the formula."""
    return r.get("status") in ("ok", 0) and r.get("path") in ("bezout", "bezout_lu", "formula", 1, 5, 6)


def another_start(x, y):
    formula = ("formula", 6)
    return started(x) and started(y) and (x["path"] in formula) != (y["path"] in formula) and \
        x.get("reason", "") == y.get("reason", "") and close("t", x["t"], y["t"]) and \
        close("t2", x["t2"], y["t2"]) and close("residual", x["residual"], y["residual"])


def main(base, this):
    a, b = list(rows(base)), list(rows(this))
    if len(a) != len(b):
        print(f"{this}: {len(b)} rows, {base}: {len(a)}")
        return 1
    identical = within = tied = other_evidence = other_start = beyond = 0
    for i, (x, y) in enumerate(zip(a, b)):
        if x == y or all(close(k, x[k], y[k]) if k in NUMERIC else x[k] == y[k] for k in x):
            if all(x[k] == y[k] or (k in NUMERIC and math.isnan(x[k]) and math.isnan(y[k])) for k in x):
                identical += 1
            else:
                within += 1
            continue
        if x.get("status") in ("off_curve", 3) and all(
                close(k, x[k], y[k]) if k in NUMERIC else x[k] == y[k] for k in x if k != "t"):
            tied += 1
            continue
        if off_curve_nearest(x) and off_curve_nearest(y) and close("residual", x["residual"], y["residual"]):
            other_evidence += 1
            continue
        if certified_other_way(x, y) or gap_other_way(x, y):
            other_evidence += 1
            continue
        if another_start(x, y):
            other_start += 1
            continue
        beyond += 1
        print(f"row {i + 1}: {x}\n    now: {y}")
    print(f"{this}: {identical} rows identical, {within} within the accuracy bound, {tied} equally near, "
          f"{other_evidence} with other evidence, {other_start} from another start, {beyond} beyond the bound")
    return 1 if beyond else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
