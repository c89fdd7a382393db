// `bezinv invert` on NURBS and composite curves: CURVES.json with a rational NURBS circle, a
// composite of a Bezier curve, a NURBS curve and a rational Bezier arc, and a space NURBS curve;
// POINTS.csv and POINTS.npy made at known parameters (the circle from the angle, the others by the
// test's own Cox-de Boor and de Casteljau); OUT rows checked; a composite with a gap refused.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "support/de_boor.hpp"
#include "support/npy_bytes.hpp"
#include "support/run_bezinv.hpp"
#include "support/scratch_directory.hpp"
#include "support/split.hpp"

namespace {

using bezinv::test_support::csv_number;
using bezinv::test_support::quoted;
using bezinv::test_support::read_file;
using bezinv::test_support::run_bezinv;
using bezinv::test_support::ScratchDirectory;
using bezinv::test_support::split;

constexpr const char* kPiecewiseCurves = R"({"curves": [
 {"id": "circle", "kind": "nurbs", "degree": 2, "knots": [0,0,0,0.25,0.25,0.5,0.5,0.75,0.75,1,1,1],
  "points": [[1,0],[1,1],[0,1],[-1,1],[-1,0],[-1,-1],[0,-1],[1,-1],[1,0]],
  "weights": [1,0.70710678118654757,1,0.70710678118654757,1,0.70710678118654757,1,0.70710678118654757,1]},
 {"id": "path", "kind": "composite", "curves": [
   {"kind": "bezier", "points": [[0,0],[1,1],[2,1],[3,0]]},
   {"kind": "nurbs", "degree": 2, "knots": [2,2,2,3,3.5,5,5,5], "points": [[3,0],[4,-1],[5,0],[6,-1],[7,0]]},
   {"id": "arc", "kind": "rational_bezier", "points": [[7,0],[8,0],[8,1]], "weights": [1,0.70710678118654757,1]}]},
 {"id": "twist", "kind": "nurbs", "degree": 3, "knots": [0,0,0,0,0.4,1,1,1,1],
  "points": [[0,0,0],[1,2,1],[2,-1,2],[3,1,0],[4,0,1]], "weights": [1,2,0.5,1,1.5]}
]})";

const bezinv::test_support::Nurbs kTwist{
    3, {0, 0, 0, 0, 0.4, 1, 1, 1, 1}, {{0, 0, 0}, {1, 2, 1}, {2, -1, 2}, {3, 1, 0}, {4, 0, 1}}, {1, 2, 0.5, 1, 1.5}};

struct ExpectedNurbsRow {
  const char* status;
  double t, residual;  // residual NaN: not checked (on the curve: rounding)
};

TEST(CliNurbs, CsvPointsOnNurbsAndCompositeCurves) {
  ScratchDirectory scratch("bezinv-cli-nurbs-");
  const std::string curves = scratch.write("curves.json", kPiecewiseCurves);
  const double nan = std::nan("");
  std::string csv = "curve,x,y,z\n";
  std::vector<ExpectedNurbsRow> expected;
  auto row = [&](const std::string& line, ExpectedNurbsRow e) {
    csv += line + "\n";
    expected.push_back(e);
  };
  row("circle,1,0,", {"ok", 0, nan});                    // the start (= the end): one point
  row("circle,0,1,", {"ok", 0.25, nan});                 // a knot of multiplicity 2
  row("circle,-1,0,", {"ok", 0.5, nan});
  row("circle," + csv_number(std::cos(0.3)) + "," + csv_number(std::sin(0.3)) + ",",
      {"ok", (std::numbers::sqrt2 * std::tan(0.15) / (1 + std::tan(0.15) * (std::numbers::sqrt2 - 1))) / 4, nan});
  row("circle,2,0,", {"off_curve", 0, 1});
  row("path,1.5,0.75,", {"ok", 0.5, nan});               // the Bezier curve at 1/2
  row("path,3,0,", {"ok", 1, nan});                      // a joint
  const bezinv::test_support::Nurbs middle{
      2, {2, 2, 2, 3, 3.5, 5, 5, 5}, {{3, 0, 0}, {4, -1, 0}, {5, 0, 0}, {6, -1, 0}, {7, 0, 0}}, {}};
  for (const double u : {2.5, 3.0, 4.2}) {  // the NURBS part: t = 1 + (u - 2) / 3
    const auto p = bezinv::test_support::nurbs_point(middle, u);
    row("path," + csv_number(p[0]) + "," + csv_number(p[1]) + ",", {"ok", 1 + (u - 2) / 3, nan});
  }
  row("path,7,0,", {"ok", 2, nan});                      // a joint
  row("path,8,1,", {"ok", 3, nan});                      // the end
  for (const double u : {0.0, 0.25, 0.4, 0.7, 1.0}) {
    const auto p = bezinv::test_support::nurbs_point(kTwist, u);
    row("twist," + csv_number(p[0]) + "," + csv_number(p[1]) + "," + csv_number(p[2]), {"ok", u, nan});
  }
  row("twist,1,1,", {"invalid_input", nan, nan});        // no z for a space curve
  const std::string points = scratch.write("points.csv", csv);
  const auto run = run_bezinv(scratch, "invert --curves " + quoted(curves) + " --points " + quoted(points) +
                                           " --out " + quoted(scratch.path("out.csv")));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto lines = split(read_file(scratch.path("out.csv")), '\n');
  ASSERT_EQ(lines[0], "t,status,residual,t2,sigma_min,sigma_next,path,reason");
  ASSERT_GE(lines.size(), expected.size() + 1);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const auto fields = split(lines[i + 1], ',');
    EXPECT_EQ(fields[1], expected[i].status) << lines[i + 1];
    if (!std::isnan(expected[i].t)) {
      EXPECT_NEAR(std::stod(fields[0]), expected[i].t, 1e-10) << lines[i + 1];
    }
    if (!std::isnan(expected[i].residual)) {
      EXPECT_NEAR(std::stod(fields[2]), expected[i].residual, 1e-12) << lines[i + 1];
    }
    EXPECT_EQ(fields[3], "nan") << lines[i + 1];  // no double point among them
  }
}

TEST(CliNurbs, NpyPointsOnACompositeCurve) {
  ScratchDirectory scratch("bezinv-cli-nurbs-");
  const std::string curves = scratch.write("curves.json", kPiecewiseCurves);
  // On the arc (part 2) at angles from its start: t = 2 + s.
  std::string data;
  std::vector<double> expected_t;
  for (int k = 0; k <= 4; ++k) {
    const double a = k * std::numbers::pi / 8, tau = std::tan(a / 2);
    bezinv::test_support::append_le(data, 7 + std::sin(a));
    bezinv::test_support::append_le(data, 1 - std::cos(a));
    expected_t.push_back(2 + tau * std::numbers::sqrt2 / (1 + tau * (std::numbers::sqrt2 - 1)));
  }
  const std::string points = scratch.write("points.npy", bezinv::test_support::npy_file("<f8", "(5, 2)", data));
  const auto run = run_bezinv(scratch, "invert --curves " + quoted(curves) + " --points " + quoted(points) +
                                           " --curve path --threads 2 --out " + quoted(scratch.path("out.csv")));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto lines = split(read_file(scratch.path("out.csv")), '\n');
  for (int k = 0; k <= 4; ++k) {
    const auto fields = split(lines[k + 1], ',');
    EXPECT_EQ(fields[1], "ok") << lines[k + 1];
    EXPECT_NEAR(std::stod(fields[0]), expected_t[k], 1e-10) << lines[k + 1];
  }
}

TEST(CliNurbs, CompositeWithAGapIsRefused) {
  ScratchDirectory scratch("bezinv-cli-nurbs-");
  const std::string curves = scratch.write("curves.json", R"({"curves": [{"id": "broken", "kind": "composite", "curves": [
    {"kind": "bezier", "points": [[0,0],[1,0]]}, {"kind": "nurbs", "degree": 1, "knots": [0,0,1,1], "points": [[1.5,0],[2,0]]}]}]})");
  const std::string points = scratch.write("points.csv", "curve,x,y\nbroken,0.5,0\n");
  const auto run = run_bezinv(scratch, "invert --curves " + quoted(curves) + " --points " + quoted(points) +
                                           " --out " + quoted(scratch.path("out.csv")));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("curves[0] (id \"broken\"): curves[1]: starts at (1.5, 0) but curves[0] ends at (1, 0)"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(std::filesystem::exists(scratch.path("out.csv")));
}

}  // namespace
