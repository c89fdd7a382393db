// `bezinv invert` on space curves: CURVES.json with 3D control points of every kind (and a plane
// curve beside them), POINTS.csv with a z column, POINTS.npy of shape (N, 3); a point of the other
// dimension is an invalid_input row (a whole-file error for a .npy whose width is not its --curve's
// dimension). Points are made at known parameters by the curve's own definition (rational de
// Casteljau of the control points, in the test).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "support/npy_bytes.hpp"
#include "support/run_bezinv.hpp"
#include "support/scratch_directory.hpp"
#include "support/split.hpp"

namespace {

using bezinv::test_support::quoted;
using bezinv::test_support::read_file;
using bezinv::test_support::run_bezinv;
using bezinv::test_support::ScratchDirectory;
using bezinv::test_support::split;

using Vec3 = std::array<double, 3>;

// P(t) of the rational Bezier curve with control points p and weights w, by de Casteljau on the
// homogeneous points (w x, w y, w z, w).
Vec3 space_de_casteljau(std::vector<Vec3> p, std::vector<double> w, double t) {
  std::vector<std::array<double, 4>> h;
  for (std::size_t i = 0; i < p.size(); ++i) h.push_back({w[i] * p[i][0], w[i] * p[i][1], w[i] * p[i][2], w[i]});
  for (std::size_t r = 1; r < h.size(); ++r)
    for (std::size_t i = 0; i + r < h.size(); ++i)
      for (int k = 0; k < 4; ++k) h[i][k] = (1 - t) * h[i][k] + t * h[i + 1][k];
  return {h[0][0] / h[0][3], h[0][1] / h[0][3], h[0][2] / h[0][3]};
}

const std::vector<Vec3> kSpacePoints{{0, 0, 0}, {1, 2, 0.5}, {2, -1, 1.5}, {3, 1, 2}};
const std::vector<double> kSpaceWeights{1, 2, 0.5, 1};

constexpr const char* kSpaceCurves = R"({"curves": [
 {"id": "poly", "kind": "bezier", "points": [[0,0,0],[1,2,0.5],[2,-1,1.5],[3,1,2]]},
 {"id": "weighted", "kind": "rational_bezier", "points": [[0,0,0],[1,2,0.5],[2,-1,1.5],[3,1,2]], "weights": [1,2,0.5,1]},
 {"id": "flat", "kind": "bezier", "points": [[0,0],[1,2],[2,0]]}
]})";

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

TEST(CliSpaceCurves, CsvPointsWithZInvertOnSpaceAndPlaneCurves) {
  ScratchDirectory scratch("bezinv-cli-space-");
  const std::string curves = scratch.write("curves.json", kSpaceCurves);
  std::string csv = "curve,x,y,z\n";
  std::vector<double> expected_t;
  for (int k = 0; k <= 10; ++k) {
    const double t = k / 10.0;
    const Vec3 a = space_de_casteljau(kSpacePoints, {1, 1, 1, 1}, t), b = space_de_casteljau(kSpacePoints, kSpaceWeights, t);
    csv += "poly," + number(a[0]) + "," + number(a[1]) + "," + number(a[2]) + "\n";
    csv += "weighted," + number(b[0]) + "," + number(b[1]) + "," + number(b[2]) + "\n";
    expected_t.push_back(t);
    expected_t.push_back(t);
  }
  csv += "flat,1,1,\n";       // a plane curve's point: z empty
  csv += "poly,1.5,0.5,9\n";  // far above the curve
  csv += "flat,1,1,0\n";      // z for a plane curve
  csv += "poly,1,1,\n";       // no z for a space curve
  csv += "poly,1,1,x\n";      // z not a number
  const std::string points = scratch.write("points.csv", csv);
  const auto run = run_bezinv(scratch, "invert --curves " + quoted(curves) + " --points " + quoted(points) +
                                           " --out " + quoted(scratch.path("out.csv")));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto lines = split(read_file(scratch.path("out.csv")), '\n');
  ASSERT_GE(lines.size(), expected_t.size() + 6);
  for (std::size_t i = 0; i < expected_t.size(); ++i) {
    const auto fields = split(lines[i + 1], ',');
    EXPECT_EQ(fields[1], "ok") << lines[i + 1];
    EXPECT_NEAR(std::stod(fields[0]), expected_t[i], 1e-12) << lines[i + 1];
  }
  const std::size_t tail = expected_t.size() + 1;
  EXPECT_EQ(split(lines[tail], ',')[1], "ok");
  EXPECT_NEAR(std::stod(split(lines[tail], ',')[0]), 0.5, 1e-14);
  EXPECT_EQ(split(lines[tail + 1], ',')[1], "off_curve");
  EXPECT_GT(std::stod(split(lines[tail + 1], ',')[2]), 6.0);  // residual: the point is 7 above z <= 2
  EXPECT_EQ(lines[tail + 2], "nan,invalid_input,nan,nan,nan,nan,none,z given for a point of a plane curve");
  EXPECT_EQ(lines[tail + 3], "nan,invalid_input,nan,nan,nan,nan,none,no z for a point of a space curve");
  EXPECT_EQ(lines[tail + 4], "nan,invalid_input,nan,nan,nan,nan,none,z is not a number");
}

TEST(CliSpaceCurves, NpyPointsOfThreeColumns) {
  ScratchDirectory scratch("bezinv-cli-space-");
  const std::string curves = scratch.write("curves.json", kSpaceCurves);
  std::string data;
  for (int k = 0; k <= 4; ++k) {
    const Vec3 p = space_de_casteljau(kSpacePoints, kSpaceWeights, k / 4.0);
    for (double c : p) bezinv::test_support::append_le(data, c);
  }
  using bezinv::test_support::npy_bytes;
  using bezinv::test_support::npy_dict;
  const std::string points = scratch.write("points.npy", npy_bytes(npy_dict("'<f8'", "(5, 3)"), data));
  auto run = run_bezinv(scratch, "invert --curves " + quoted(curves) + " --points " + quoted(points) +
                                     " --curve weighted --out " + quoted(scratch.path("out.csv")));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto lines = split(read_file(scratch.path("out.csv")), '\n');
  for (int k = 0; k <= 4; ++k) {
    const auto fields = split(lines[k + 1], ',');
    EXPECT_EQ(fields[1], "ok") << lines[k + 1];
    EXPECT_NEAR(std::stod(fields[0]), k / 4.0, 1e-12) << lines[k + 1];
  }
  // The same file for the plane curve: the whole file is refused, nothing written.
  run = run_bezinv(scratch, "invert --curves " + quoted(curves) + " --points " + quoted(points) +
                                " --curve flat --out " + quoted(scratch.path("flat.csv")));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("shape (5, 3): curve \"flat\" is a plane curve"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(scratch.path("flat.csv")));
  // --curve-index over both kinds: the plane curve's rows are invalid_input, the space curve's ok.
  std::string index;
  for (std::int64_t i : {1, 2, 1, 2, 0}) bezinv::test_support::append_le(index, i);
  const std::string indices = scratch.write("index.npy", npy_bytes(npy_dict("'<i8'", "(5,)"), index));
  run = run_bezinv(scratch, "invert --curves " + quoted(curves) + " --points " + quoted(points) + " --curve-index " +
                                quoted(indices) + " --out " + quoted(scratch.path("mixed.csv")));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto mixed = split(read_file(scratch.path("mixed.csv")), '\n');
  EXPECT_EQ(split(mixed[1], ',')[1], "ok");
  EXPECT_EQ(mixed[2], "nan,invalid_input,nan,nan,nan,nan,none,z given for a point of a plane curve");
  EXPECT_EQ(split(mixed[3], ',')[1], "ok");
  EXPECT_EQ(split(mixed[4], ',')[1], "invalid_input");
  // P(1) of "weighted" is P(1) of "poly" too: both end at (3, 1, 2).
  EXPECT_EQ(split(mixed[5], ',')[1], "ok");
  EXPECT_EQ(split(mixed[5], ',')[0], "1");
}

}  // namespace
