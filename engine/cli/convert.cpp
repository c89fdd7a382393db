#include "convert.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "bezinv/io.hpp"
#include "bezinv/matrix_weighted.hpp"

namespace bezinv::cli {
namespace {

using Json = nlohmann::ordered_json;

// The converted curve: kind rational_bezier (points of the curve's dimension, and the weights)
// where no weight is 0; with a zero weight (a control point at infinity, which eqs. (2) and (3)
// never give) a plane curve is written homogeneously as kind rational.
Json converted_json(const MatrixWeightedCurve& curve) {
  const ConvertedCurve c = convert(curve);
  bool zero_weight = false;
  for (double w : c.weights) zero_weight = zero_weight || w == 0.0;
  Json out{{"id", curve.id}};
  if (!zero_weight) {
    Json points = Json::array();
    for (const Vector3& q : c.points)
      points.push_back(curve.dimension == 3 ? Json::array({q[0], q[1], q[2]}) : Json::array({q[0], q[1]}));
    out["kind"] = "rational_bezier";
    out["points"] = points;
    out["weights"] = c.weights;
    return out;
  }
  if (curve.dimension == 3)
    throw InputError("curve \"" + curve.id + "\": a converted weight is 0 (a control point at infinity), which a "
                     "space rational_bezier cannot write");
  std::vector<double> x, y;
  for (const Vector3& q : c.numerators) x.push_back(q[0]), y.push_back(q[1]);
  out["kind"] = "rational";
  out["x_num"] = x;
  out["x_den"] = c.weights;
  out["y_num"] = y;
  out["y_den"] = c.weights;
  return out;
}

}  // namespace

int run_convert(const std::string& curves_path, const std::string& out_path) {
  // Checked as a whole first (every message names the file and the field), then converted.
  const std::vector<std::optional<MatrixWeightedCurve>> matrix_weighted = read_matrix_weighted_json(curves_path);
  std::ifstream in(curves_path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  const Json root = Json::parse(text.str());
  Json curves = Json::array();
  std::size_t converted = 0;
  for (std::size_t i = 0; i < root["curves"].size(); ++i) {
    if (matrix_weighted[i]) {
      curves.push_back(converted_json(*matrix_weighted[i]));
      ++converted;
    } else {
      curves.push_back(root["curves"][i]);  // as written
    }
  }
  // One curve a line.
  std::string out = "{\"curves\": [\n";
  for (std::size_t i = 0; i < curves.size(); ++i) {
    out += ' ';
    out += curves[i].dump();
    out += i + 1 < curves.size() ? ",\n" : "\n";
  }
  out += "]}\n";
  write_text_file(out_path, out);
  std::fprintf(stderr, "bezinv convert: %zu matrix-weighted curve(s) converted, %zu passed through -> %s\n", converted,
               curves.size() - converted, out_path.c_str());
  return 0;
}

}  // namespace bezinv::cli
