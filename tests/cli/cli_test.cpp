// End to end: the real `bezinv` binary on small files. The points are made here from known
// parameters (de Casteljau on the control points, in the test itself), so the t the command
// writes is checked against the construction, not against another run of the engine.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "support/de_casteljau.hpp"
#include "support/run_bezinv.hpp"
#include "support/scratch_directory.hpp"
#include "support/split.hpp"

namespace {

namespace fs = std::filesystem;

using bezinv::test_support::read_file;
using bezinv::test_support::ScratchDirectory;
using bezinv::test_support::split;

using bezinv::test_support::Outcome;
using bezinv::test_support::quoted;
using bezinv::test_support::run_bezinv;

// ---- Independent truth: points from known parameters ----------------------------------------

using bezinv::test_support::de_casteljau;
using bezinv::test_support::rational_de_casteljau;
using bezinv::test_support::Vec2;

// The cubic's x(t) = 3t + 3t^2 - 2t^3 is increasing on [-0.36, 1.36], so each of the points below
// has exactly one parameter on the whole curve, not only on the segment.
const std::vector<Vec2> kArch{{0, 0}, {1, 2}, {3, 2}, {4, 0}};
// A quarter of the unit circle (weights 1, 1/sqrt(2), 1).
const std::vector<Vec2> kArc{{1, 0}, {1, 1}, {0, 1}};
const std::vector<double> kArcWeights{1, 0.70710678118654752, 1};

constexpr const char* kCubicAndArcJson = R"({"curves": [
  {"id": "cubic", "kind": "bezier", "points": [[0, 0], [1, 2], [3, 2], [4, 0]]},
  {"id": "arc", "kind": "rational_bezier", "points": [[1, 0], [1, 1], [0, 1]], "weights": [1, 0.70710678118654752, 1]}
]})";

using bezinv::test_support::csv_number;

std::string point_row(const std::string& curve, Vec2 p) { return curve + "," + csv_number(p[0]) + "," + csv_number(p[1]) + "\n"; }

class CliInvert : public ::testing::Test {
 protected:
  ScratchDirectory scratch{"bezinv-cli-test-"};
  std::string curves = scratch.write("curves.json", kCubicAndArcJson);
  std::string out = scratch.path("out.csv");

  std::string invert_arguments(const std::string& curves_path, const std::string& points_path) const {
    return "invert --curves " + quoted(curves_path) + " --points " + quoted(points_path) + " --out " + quoted(out);
  }

  // A run that must fail as a whole: non-zero exit, one stderr line naming `file`, no OUT.
  void expect_refused(const std::string& arguments, const std::string& file) {
    const Outcome run = run_bezinv(scratch, arguments);
    EXPECT_NE(run.exit_code, 0);
    EXPECT_EQ(run.exit_code, 2) << run.err;  // the input-error code, not a crash
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_TRUE(run.err.starts_with("bezinv: ")) << run.err;
    EXPECT_NE(run.err.find(file), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(out));
  }
};

TEST_F(CliInvert, KnownParametersComeBackInOrderWithPerRowStatuses) {
  std::string csv = "curve,x,y\n";
  csv += point_row("cubic", de_casteljau(kArch, 0.25));                    // 0 ok, t = 0.25
  csv += point_row("nope", {1, 1});                                         // 1 unknown id
  csv += point_row("1", rational_de_casteljau(kArc, kArcWeights, 0.6));     // 2 by index: ok, t = 0.6
  csv += "cubic,nan,1\n";                                                   // 3 non-finite x
  csv += point_row("cubic", de_casteljau(kArch, 1.3));                     // 4 on the extension
  csv += point_row("cubic", {100, 100});                                    // 5 far away
  csv += point_row("5", {0, 0});                                            // 6 index past the end
  csv += point_row("arc", rational_de_casteljau(kArc, kArcWeights, 0.0));  // 7 end point, t = 0
  const std::string points = scratch.write("points.csv", csv);

  const Outcome run = run_bezinv(scratch, invert_arguments(curves, points));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, "");  // invert talks through OUT only

  const std::vector<std::string> lines = split(read_file(out), '\n');
  ASSERT_EQ(lines.size(), 8u + 2u);  // header, 8 rows, "" after the final newline
  EXPECT_EQ(lines[0], "t,status,residual,t2,sigma_min,sigma_next,path,reason");
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 1; i <= 8; ++i) {
    rows.push_back(split(lines[i], ','));
    ASSERT_EQ(rows.back().size(), 8u) << lines[i];
  }
  const auto t_of = [&](std::size_t row) { return std::strtod(rows[row][0].c_str(), nullptr); };

  EXPECT_EQ(rows[0][1], "ok");
  EXPECT_NEAR(t_of(0), 0.25, 1e-9);
  EXPECT_EQ(rows[1][1], "invalid_input");
  EXPECT_EQ(rows[1][7], "unknown curve id");
  EXPECT_EQ(rows[2][1], "ok");
  EXPECT_NEAR(t_of(2), 0.6, 1e-9);
  EXPECT_EQ(rows[3][1], "invalid_input");
  EXPECT_EQ(rows[3][7], "x is not finite");
  EXPECT_EQ(rows[4][1], "outside_segment");
  EXPECT_NEAR(t_of(4), 1.3, 1e-9);
  EXPECT_EQ(rows[5][1], "off_curve");
  EXPECT_EQ(rows[6][1], "invalid_input");
  EXPECT_EQ(rows[6][7], "curve index past the end");
  EXPECT_EQ(rows[7][1], "ok");
  EXPECT_NEAR(t_of(7), 0.0, 1e-9);
}

TEST_F(CliInvert, MalformedCurvesFileIsRefusedWithoutOutput) {
  const std::string points = scratch.write("points.csv", "curve,x,y\ncubic,1,1\n");
  const std::string bad = scratch.write("broken.json", R"({"curves": [{"id": "a", "kind": "bezier",)");
  expect_refused(invert_arguments(bad, points), "broken.json");
}

TEST_F(CliInvert, EmptyCurveListIsRefusedWithoutOutput) {
  const std::string points = scratch.write("points.csv", "curve,x,y\ncubic,1,1\n");
  const std::string empty = scratch.write("empty.json", R"({"curves": []})");
  expect_refused(invert_arguments(empty, points), "empty.json");
}

TEST_F(CliInvert, MissingColumnIsRefusedWithoutOutput) {
  const std::string points = scratch.write("two-columns.csv", "curve,x\ncubic,1\n");
  expect_refused(invert_arguments(curves, points), "two-columns.csv:1:");
}

TEST_F(CliInvert, WrongFieldCountIsRefusedWithoutOutput) {
  const std::string points = scratch.write("ragged.csv", "curve,x,y\ncubic,1,1\ncubic,1,1,1\n");
  expect_refused(invert_arguments(curves, points), "ragged.csv:3:");
}

TEST_F(CliInvert, MissingPointsFileIsRefusedWithoutOutput) {
  expect_refused(invert_arguments(curves, scratch.path("absent.csv")), "absent.csv");
}

TEST_F(CliInvert, AFailedRunLeavesAStaleOutputAlone) {
  const std::string stale = "from an earlier run\n";
  scratch.write("out.csv", stale);
  const std::string points = scratch.write("ragged.csv", "curve,x,y\ncubic,1\n");
  const Outcome run = run_bezinv(scratch, invert_arguments(curves, points));
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_EQ(read_file(out), stale);
}

TEST_F(CliInvert, BadOptionValuesAreRefused) {
  const std::string points = scratch.write("points.csv", "curve,x,y\ncubic,1,1\n");
  const std::string base = invert_arguments(curves, points);
  for (const char* option : {"--tol 0", "--tol -1e-6", "--tol nan", "--tol inf", "--tol abc", "--threads -1",
                             "--threads x", "--bogus"}) {
    const Outcome run = run_bezinv(scratch, base + " " + option);
    EXPECT_NE(run.exit_code, 0) << option;
    EXPECT_FALSE(fs::exists(out)) << option;
  }
  // The same command with good values works (so the refusals above were about the values).
  const Outcome run = run_bezinv(scratch, base + " --tol 1e-8 --threads 1 --no-refine");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::exists(out));
}

TEST(CliCommand, NoSubcommandPrintsHelpAndFails) {
  ScratchDirectory scratch{"bezinv-cli-test-"};
  const Outcome run = run_bezinv(scratch, "");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE((run.out + run.err).find("invert"), std::string::npos);  // the help lists the subcommands
  EXPECT_NE((run.out + run.err).find("demo"), std::string::npos);
}

TEST(CliCommand, VersionPrintsTheName) {
  ScratchDirectory scratch{"bezinv-cli-test-"};
  const Outcome run = run_bezinv(scratch, "--version");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_NE(run.out.find("bezinv"), std::string::npos) << run.out;
}

}  // namespace
