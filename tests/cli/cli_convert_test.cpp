// `bezinv convert` end to end: matrix-weighted curves (plane and space, from matrices, normals or
// tangents) written as rational Bezier curves that are the curves of the definition; the other
// curves passed through as written; the converted plane curve's points invert at their parameter;
// errors name the file, the curve and the field, and OUT is never an input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "bezinv/bernstein.hpp"
#include "bezinv/matrix_weighted.hpp"
#include "support/run_bezinv.hpp"
#include "support/scratch_directory.hpp"

namespace {

using bezinv::test_support::quoted;
using bezinv::test_support::read_file;
using bezinv::test_support::run_bezinv;
using bezinv::test_support::ScratchDirectory;

constexpr const char* kMatrixWeighted = R"({"curves": [
 {"id": "m", "kind": "matrix_weighted_bezier", "points": [[0,0],[1,2],[2,0]], "normals": [[-1,0],[0,3],[1,0]], "omegas": [1,1,1], "mus": [2,10,2]},
 {"id": "s", "kind": "matrix_weighted_bezier", "points": [[0,0,0],[1,2,0],[2,0,1]], "tangents": [[0,1,0],[1,0,0],[0,-1,1]], "omegas": [1,2,1], "mus": [1,2,4]},
 {"id": "k", "kind": "matrix_weighted_bezier", "points": [[0,0],[1,1]], "matrices": [[[1,0],[0,2]], [[2,0.5],[0.5,1]]]},
 {"id": "b", "kind": "bezier", "points": [[0,0],[1,1],[2,0.1]]}
]})";

// The same curves, built through the library (the definition the conversion is checked against).
bezinv::MatrixWeightedCurve curve_m() {
  bezinv::MatrixWeightedCurve c;
  c.id = "m";
  c.points = {{0, 0, 0}, {1, 2, 0}, {2, 0, 0}};
  const double n[3][2] = {{-1, 0}, {0, 3}, {1, 0}}, mu[3] = {2, 10, 2};
  for (int i = 0; i < 3; ++i) c.matrices.push_back(bezinv::normal_weight(2, {n[i][0], n[i][1], 0}, 1.0, mu[i], "m"));
  return c;
}

bezinv::MatrixWeightedCurve curve_s() {
  bezinv::MatrixWeightedCurve c;
  c.id = "s";
  c.dimension = 3;
  c.points = {{0, 0, 0}, {1, 2, 0}, {2, 0, 1}};
  const double t[3][3] = {{0, 1, 0}, {1, 0, 0}, {0, -1, 1}}, omega[3] = {1, 2, 1}, mu[3] = {1, 2, 4};
  for (int i = 0; i < 3; ++i)
    c.matrices.push_back(bezinv::tangent_weight(3, {t[i][0], t[i][1], t[i][2]}, omega[i], mu[i], "s"));
  return c;
}

// A rational Bezier curve from the output, at t.
std::array<double, 3> written_point(const nlohmann::json& curve, double t) {
  std::vector<double> w = curve["weights"].get<std::vector<double>>(), x, y, z;
  for (std::size_t k = 0; k < w.size(); ++k) {
    const auto& p = curve["points"][k];
    x.push_back(w[k] * p[0].get<double>());
    y.push_back(w[k] * p[1].get<double>());
    z.push_back(p.size() == 3 ? w[k] * p[2].get<double>() : 0.0);
  }
  const double den = bezinv::bernstein_value(w, t);
  return {bezinv::bernstein_value(x, t) / den, bezinv::bernstein_value(y, t) / den, bezinv::bernstein_value(z, t) / den};
}

TEST(CliConvert, WritesEachMatrixWeightedCurveAsTheRationalBezierCurveOfTheDefinition) {
  ScratchDirectory scratch("bezinv-cli-convert-");
  const std::string in = scratch.write("curves.json", kMatrixWeighted), out = scratch.path("converted.json");
  const auto run = run_bezinv(scratch, "convert --curves " + quoted(in) + " --out " + quoted(out));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto curves = nlohmann::json::parse(read_file(out))["curves"];
  ASSERT_EQ(curves.size(), 4u);
  EXPECT_EQ(curves[0]["kind"], "rational_bezier");
  EXPECT_EQ(curves[0]["weights"].size(), 5u);  // degree 2 n
  EXPECT_EQ(curves[1]["weights"].size(), 7u);  // degree 3 n, space
  EXPECT_EQ(curves[1]["points"][0].size(), 3u);
  EXPECT_EQ(curves[3], nlohmann::json::parse(kMatrixWeighted)["curves"][3]);  // passed through
  for (const auto& [index, curve] : {std::pair{0, curve_m()}, std::pair{1, curve_s()}})
    for (int k = 0; k <= 20; ++k) {
      const double t = k / 20.0;
      const auto a = bezinv::matrix_weighted_point(curve, t), b = written_point(curves[index], t);
      for (int e = 0; e < 3; ++e) EXPECT_NEAR(a[e], b[e], 1e-13 * (1 + std::abs(a[e]))) << curve.id << " t " << t;
    }
}

TEST(CliConvert, APlaneMatrixWeightedCurveInvertsAtItsParameter) {
  ScratchDirectory scratch("bezinv-cli-convert-");
  // The plane curves alone (a space curve is not inverted).
  const std::string curves = scratch.write(
      "curves.json",
      R"({"curves": [{"id": "m", "kind": "matrix_weighted_bezier", "points": [[0,0],[1,2],[2,0]], "normals": [[-1,0],[0,3],[1,0]], "omegas": [1,1,1], "mus": [2,10,2]}]})");
  std::string csv = "curve,x,y\n";
  for (int k = 0; k <= 10; ++k) {
    const auto p = bezinv::matrix_weighted_point(curve_m(), k / 10.0);
    char row[128];
    std::snprintf(row, sizeof row, "m,%.17g,%.17g\n", p[0], p[1]);
    csv += row;
  }
  const std::string points = scratch.write("points.csv", csv), out = scratch.path("out.csv");
  const auto run = run_bezinv(scratch, "invert --curves " + quoted(curves) + " --points " + quoted(points) + " --out " + quoted(out));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string text = read_file(out);
  std::size_t line = text.find('\n') + 1;
  for (int k = 0; k <= 10; ++k) {
    const std::size_t end = text.find('\n', line);
    const std::string row = text.substr(line, end - line);
    EXPECT_NEAR(std::stod(row.substr(0, row.find(','))), k / 10.0, 1e-12) << row;
    EXPECT_NE(row.find(",ok,"), std::string::npos) << row;
    line = end + 1;
  }
}

TEST(CliConvert, ErrorsNameTheCurveAndTheFieldAndOutIsNeverAnInput) {
  ScratchDirectory scratch("bezinv-cli-convert-");
  auto convert_error = [&](const std::string& curve) {
    const std::string in = scratch.write("bad.json", "{\"curves\": [" + curve + "]}");
    const auto run = run_bezinv(scratch, "convert --curves " + quoted(in) + " --out " + quoted(scratch.path("o.json")));
    EXPECT_EQ(run.exit_code, 2) << curve;
    return run.err;
  };
  EXPECT_NE(convert_error(R"({"id": "z", "kind": "matrix_weighted_bezier", "points": [[0,0],[1,0]], "normals": [[0,1],[0,1]], "omegas": [1,0], "mus": [1,1]})")
                .find("curves[0] (id \"z\"): normals[1], omegas[1], mus[1]: omega must be > 0"),
            std::string::npos);
  EXPECT_NE(convert_error(R"({"id": "f", "kind": "matrix_weighted_bezier", "points": [[0,0],[1,0]], "matrices": [[[1,0],[0,1]], [[-1,0],[0,-1]]]})")
                .find("singular at t = 0.5"),
            std::string::npos);
  EXPECT_NE(convert_error(R"({"id": "d", "kind": "matrix_weighted_bezier", "points": [[0,0],[1,0,0]], "matrices": [[[1,0],[0,1]], [[1,0],[0,1]]]})")
                .find("points[1]: 3 coordinates, but the curve is 2D"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(scratch.path("o.json")));  // nothing written
  const std::string in = scratch.write("curves.json", kMatrixWeighted);
  const auto same = run_bezinv(scratch, "convert --curves " + quoted(in) + " --out " + quoted(in));
  EXPECT_EQ(same.exit_code, 2);
  EXPECT_EQ(read_file(in), kMatrixWeighted);  // untouched
}

}  // namespace
