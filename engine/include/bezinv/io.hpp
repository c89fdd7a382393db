#pragma once
// The file formats of `bezinv invert` (README "File formats").
//   CURVES.json  {"curves": [CURVE, ...]}, CURVE one of
//                {"id": "a", "kind": "bezier", "points": [[x,y], ...]}
//                {"id": "b", "kind": "rational_bezier", "points": [[x,y], ...], "weights": [w0, ...]}
//                {"id": "c", "kind": "rational", "x_num": [...], "x_den": [...], "y_num": [...], "y_den": [...]}
//   POINTS.csv   header `curve,x,y`; curve is an id or a 0-based index into the list
//   OUT.csv      header, then one row per input point, in input order
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"

namespace bezinv {

// A whole input cannot be used. what() is one line naming the file and the line or field,
// e.g. "points.csv:1: header must be 'curve,x,y'" or "curves.json: curves[2] (id \"c\"): weights: ...".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses and validates every curve. Throws InputError (malformed JSON, missing field, empty list,
// duplicate id, a curve failing validate()).
std::vector<Curve> read_curves_json(const std::string& path);

// One data row of POINTS.csv. curve >= 0 indexes the curve list; a row that cannot be used
// (unknown id, index past the end, non-finite or unparsable coordinate) has curve = -1 and a
// static reason; it still gets its output row.
struct PointRow {
  int curve = -1;
  Point point{PointResult::nan, PointResult::nan};
  const char* reason = "";
};

// Throws InputError for a file that cannot be used as a whole (unreadable, missing or wrong
// header, a row with the wrong number of fields); per-row problems become rows with curve = -1.
std::vector<PointRow> read_points_csv(const std::string& path, const std::vector<Curve>& curves);

// Writes OUT.csv atomically (to a temporary file beside it, then renamed), so a failure leaves no
// partial file. Columns: t,status,residual,t2,sigma_min,sigma_next,path,reason. Numbers at
// round-trip precision (%.17g), `nan` when absent.
void write_results_csv(const std::string& path, std::span<const PointResult> results);

}  // namespace bezinv
