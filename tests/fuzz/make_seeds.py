#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets (tests/fuzz/corpus/<target>/): small valid inputs of
every kind each reader takes, and a few nearly valid ones, for the fuzzer to mutate. Run from
anywhere; it rewrites the seeds it makes and leaves other files (inputs that found bugs) alone."""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def write(target, name, data):
    directory = os.path.join(HERE, "corpus", target)
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


# ---- CURVES.json -------------------------------------------------------------------------------
curves = {
    "bezier": '{"id": "a", "kind": "bezier", "points": [[0,0],[1,2],[3,1]]}',
    "rational_bezier": '{"id": "b", "kind": "rational_bezier", "points": [[0,0],[1,1],[2,0]], "weights": [1,2,1]}',
    "rational": '{"id": "c", "kind": "rational", "x_num": [0,1,2], "x_den": [1,1,1], "y_num": [0,2,0], "y_den": [1,2,1]}',
    "space_bezier": '{"id": "d", "kind": "bezier", "points": [[0,0,0],[1,2,3],[2,-1,1]]}',
    "space_rational_bezier": '{"id": "e", "kind": "rational_bezier", "points": [[0,0,0],[1,1,1],[2,0,1]], "weights": [1,0.5,1]}',
    "space_rational": '{"id": "f", "kind": "rational", "x_num": [0,1], "x_den": [1,1], "y_num": [0,1], "y_den": [1,2], "z_num": [1,0], "z_den": [1,1]}',
    "matrices": '{"id": "k", "kind": "matrix_weighted_bezier", "points": [[0,0],[1,1]], "matrices": [[[1,0],[0,2]], [[2,0.5],[0.5,1]]]}',
    "normals": '{"id": "m", "kind": "matrix_weighted_bezier", "points": [[0,0],[1,2],[2,0]], "normals": [[-1,0],[0,3],[1,0]], "omegas": [1,1,1], "mus": [2,10,2]}',
    "tangents": '{"id": "s", "kind": "matrix_weighted_bezier", "points": [[0,0,0],[1,2,0],[2,0,1]], "tangents": [[0,1,0],[1,0,0],[0,-1,1]], "omegas": [1,2,1], "mus": [1,2,4]}',
}
for name, curve in curves.items():
    write("fuzz_curves_json", name + ".json", '{"curves": [%s]}\n' % curve)
write("fuzz_curves_json", "all.json", '{"curves": [\n  %s\n]}\n' % ",\n  ".join(curves.values()))
write("fuzz_curves_json", "duplicate_id.json", '{"curves": [%s, %s]}' % (curves["bezier"], curves["bezier"]))
write("fuzz_curves_json", "pole.json",
      '{"curves": [{"id": "p", "kind": "rational_bezier", "points": [[0,0],[1,1]], "weights": [1,-1]}]}')
write("fuzz_curves_json", "escapes.json",
      '{"curves": [{"id": "\\u00e9\\n\\"x", "kind": "bezier", "points": [[1e-300,-0.0],[1.7976931348623157e308,2E+3]]}]}')

# ---- POINTS.csv (curves of fuzz_points_csv.cpp: "a" plane, "s" space, "1" plane, "x,y" plane) ----
write("fuzz_points_csv", "plane.csv", "curve,x,y\na,0.5,1\n0,1,2\n1,0.25,0.5\n")
write("fuzz_points_csv", "space.csv", "curve,x,y,z\na,0.5,1,\ns,1,2,3\n1,0,0,\n")
write("fuzz_points_csv", "quoted.csv", 'curve,x,y\r\n"x,y",0.5,"1"\r\n"a",1e3,-2.5\r\n')
write("fuzz_points_csv", "bom_blanks.csv", "\ufeffcurve , x , y \n a , 1 , 2 \n\n")
write("fuzz_points_csv", "bad_rows.csv", "curve,x,y,z\n7,nan,1,\n-1,1,inf,\nq,1,2,\ns,1,2,\na,1,2,3\n,1,2,\n")
write("fuzz_points_csv", "wrong_fields.csv", "curve,x,y\na,1\n")


# ---- .npy ------------------------------------------------------------------------------------------
def npy(descr, shape, data, fortran="False", major=1):
    header = "{'descr': %s, 'fortran_order': %s, 'shape': %s, }" % (descr, fortran, shape)
    length_bytes = 2 if major == 1 else 4
    while (6 + 2 + length_bytes + len(header) + 1) % 64:
        header += " "
    header += "\n"
    length = struct.pack("<H" if major == 1 else "<I", len(header))
    return b"\x93NUMPY" + bytes([major, 0]) + length + header.encode("latin-1") + data


def doubles(*values):
    return struct.pack("<%dd" % len(values), *values)


write("fuzz_points_npy", "plane.npy", npy("'<f8'", "(3, 2)", doubles(0, 0, 1, 1, 2, 0.5)))
write("fuzz_points_npy", "space.npy", npy("'<f8'", "(2, 3)", doubles(0, 0, 0, 1, 2, 3)))
write("fuzz_points_npy", "version2.npy", npy("'<f8'", "(1, 2)", doubles(0.5, 0.25), major=2))
write("fuzz_points_npy", "non_finite.npy",
      npy("'<f8'", "(3, 2)", doubles(float("nan"), 0, 1, float("inf"), 1e308, -1e-308)))
write("fuzz_points_npy", "index_i4.npy", npy("'<i4'", "(3,)", struct.pack("<3i", 0, 2, -1)))
write("fuzz_points_npy", "index_i8.npy", npy("'<i8'", "(3,)", struct.pack("<3q", 1, 0, 5)))
write("fuzz_points_npy", "truncated.npy", npy("'<f8'", "(4, 2)", doubles(1, 2, 3)))
write("fuzz_points_npy", "fortran.npy", npy("'<f8'", "(2, 2)", doubles(1, 2, 3, 4), fortran="True"))
write("fuzz_points_npy", "huge_shape.npy", npy("'<f8'", "(18446744073709551615, 2)", b""))
# OUT.npy: t, residual, t2, sigma_min, sigma_next '<f8', status, path 'u1' (engine/io/result_record.hpp).
result_descr = ("[('t', '<f8'), ('residual', '<f8'), ('t2', '<f8'), ('sigma_min', '<f8'), "
                "('sigma_next', '<f8'), ('status', '|u1'), ('path', '|u1')]")
record = doubles(0.5, 1e-17, float("nan"), 1e-16, 0.3) + bytes([0, 5])
write("fuzz_points_npy", "results.npy", npy(result_descr, "(2,)", record + doubles(1, 2, 0, 0, 0) + bytes([3, 4])))


# ---- invert: flags, degree - 1, scale exponent / 8, coefficients, points (fuzz_invert.cpp) ---------
def small(value):  # one byte: (c - 100) / 8
    c = int(round(value * 8 + 100))
    assert 0 <= c < 200
    return c


def on_curve(t, offset=0.0, dimension=2):  # a point at t in [-0.25, 1.25], moved by offset
    tag = (int(round((t + 0.25) / 1.5 * 127)) << 1) | 1
    return bytes([tag, 0] + [small(offset)] * dimension)


def anywhere(*coordinates):
    return bytes([0] + [small(c) for c in coordinates])


cubic = [small(v) for v in (0, 0, 1, 2, 2, -1, 3, 1)]
write("fuzz_invert", "plane_cubic.bin",
      bytes([0, 2, 0] + cubic) + on_curve(0.3) + on_curve(0.8, 0.125) + anywhere(5, 5) + on_curve(1.2))
write("fuzz_invert", "rational_quadratic.bin",
      bytes([2, 1, 0] + [small(v) for v in (0, 0, 1, 1, 2, 0, 1, 2, 1)]) + on_curve(0.5) + anywhere(1, 3))
# x = (1 - t)^2 + ..., separate denominators: x_num, x_den, y_num, y_den.
write("fuzz_invert", "separate_denominators.bin",
      bytes([4, 1, 0] + [small(v) for v in (0, 1, 2, 1, 1, 1, 0, 2, 0, 1, 2, 1)]) + on_curve(0.25) + anywhere(0, 4))
# A loop: a cubic whose ends cross.
write("fuzz_invert", "loop.bin",
      bytes([0, 2, 0] + [small(v) for v in (0, 0, 4, 4, -2, 4, 2, 0)]) + on_curve(0.2) + on_curve(0.7) + anywhere(1, 1.5))
write("fuzz_invert", "space_cubic.bin",
      bytes([1, 2, 0] + [small(v) for v in (0, 0, 0, 1, 2, 1, 2, -1, 3, 3, 1, 0)]) + on_curve(0.4, 0, 3) +
      anywhere(1, 1, 1) + on_curve(0.9, 0.25, 3))
write("fuzz_invert", "space_rational.bin",
      bytes([3, 1, 0] + [small(v) for v in (0, 0, 0, 1, 1, 1, 2, 0, 1, 1, 0.5, 1)]) + on_curve(0.6, 0, 3))
# Huge (2^800) and tiny (2^-800) curves, options flipped (no refine, SVD only, formula, projection, loose).
write("fuzz_invert", "huge_no_refine.bin", bytes([8 | 16, 2, 100] + cubic) + on_curve(0.3) + anywhere(3, 3))
write("fuzz_invert", "tiny_formula_projection.bin",
      bytes([32 | 64 | 128, 2, 156] + cubic) + on_curve(0.6) + anywhere(-4, 2))
write("fuzz_invert", "degree_six.bin",
      bytes([0, 5, 0] + [small(v) for v in (0, 0, 1, 3, 2, -2, 3, 4, 4, -1, 5, 2, 6, 0)]) +
      on_curve(0.1) + on_curve(0.55) + anywhere(4, 1))
# Special values: the largest double and 1e-300 among the control points.
write("fuzz_invert", "specials.bin", bytes([0, 1, 0, 207, 200, 202, 207]) + anywhere(1, 1))
write("fuzz_invert", "straight_line_at_degree_three.bin",
      bytes([0, 2, 0] + [small(v) for v in (0, 0, 1, 1, 2, 2, 3, 3)]) + on_curve(0.5) + anywhere(1, 2))
