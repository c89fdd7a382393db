// BEZINV_KERNEL end to end: the real `bezinv` command, once per instruction set this CPU runs,
// forced through the environment. Each run must report the kernel it was given, answer points made
// from known parameters correctly, and agree with the other kernels row by row (same status and
// path; t within rounding, since FMA contraction differs between instruction sets).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bezinv/kernels/batch.hpp"
#include "support/de_casteljau.hpp"
#include "support/run_bezinv.hpp"
#include "support/sanitizers.hpp"
#include "support/scratch_directory.hpp"
#include "support/split.hpp"

namespace bezinv {
namespace {

using test_support::de_casteljau;
using test_support::Outcome;
using test_support::quoted;
using test_support::read_file;
using test_support::run_bezinv;
using test_support::ScratchDirectory;
using test_support::split;
using test_support::Vec2;

std::vector<std::string> kernel_names() {
  std::vector<std::string> names;
  for (const kernels::Implementation* impl : kernels::available_implementations()) names.emplace_back(impl->name);
  return names;
}

TEST(CliKernel, ProfileRunsOnTheForcedKernel) {
  ScratchDirectory scratch{"bezinv-kernel-test-"};
  // Fewer points under the sanitizers (support/sanitizers.hpp): the same stages on each kernel.
  const int points = bezinv::test_support::kSanitizerTree ? 500 : 2000;
  for (const std::string& name : kernel_names())
    for (int degree : {3, 8, 20}) {
      SCOPED_TRACE(name + " degree " + std::to_string(degree));
      const Outcome run = run_bezinv(scratch, "profile --degree " + std::to_string(degree) + " --points " +
                                                  std::to_string(points) + " --threads 1 --json",
                                     "BEZINV_KERNEL=" + name);
      ASSERT_EQ(run.exit_code, 0) << run.err;
      EXPECT_EQ(run.err, "");
      const auto report = nlohmann::json::parse(run.out);
      EXPECT_EQ(report.at("kernel").get<std::string>(), name);
      EXPECT_EQ(report.at("ok").get<int>(), points);
      EXPECT_LE(report.at("max_abs_dt_ok").get<double>(), 1e-10);
      // On-curve points of random curves: the fast path answers (nearly) all of them.
      EXPECT_GE(report.at("fast_path").get<int>(), points * 9 / 10);
      // ... and the isolation certificate settles most of those without the gap
      // (docs/fast-path.md#the-isolation-certificate).
      EXPECT_LE(report.at("certified").get<int>(), report.at("fast_path").get<int>());
      EXPECT_GE(report.at("certified").get<int>(), points * 8 / 10);
    }
}

TEST(CliKernel, AnUnknownKernelIsReportedAndTheBestIsUsed) {
  ScratchDirectory scratch{"bezinv-kernel-test-"};
  const Outcome run = run_bezinv(scratch, "profile --degree 3 --points 100 --json", "BEZINV_KERNEL=sse9");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("BEZINV_KERNEL=sse9"), std::string::npos) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out).at("kernel").get<std::string>(), kernel_names().back());
}

// A degree-7 Bezier curve (a wavy polygon, so B is 7 x 7 and both kernels of the engine work):
// points at known t on the segment, on the extension, and off the curve.
TEST(CliKernel, EveryKernelGivesTheSameRows) {
  ScratchDirectory scratch{"bezinv-kernel-test-"};
  const std::vector<Vec2> polygon{{0, 0}, {1, 2}, {2, -1}, {3, 2.5}, {4, -0.5}, {5, 1.5}, {6, 0.2}, {7, 1}};
  std::string json = R"({"curves": [{"id": "w", "kind": "bezier", "points": [)";
  for (std::size_t i = 0; i < polygon.size(); ++i) {  // piece by piece: GCC 12's false -Wrestrict on chained +
    char point[64];
    std::snprintf(point, sizeof point, "%s[%.17g,%.17g]", i ? "," : "", polygon[i][0], polygon[i][1]);
    json += point;
  }
  json += "]}]}";
  const std::string curves = scratch.write("curves.json", json);
  std::string csv = "curve,x,y\n";
  std::vector<double> known;
  auto add_point = [&](double t) {
    const Vec2 p = de_casteljau(polygon, t);
    char row[96];
    std::snprintf(row, sizeof row, "w,%.17g,%.17g\n", p[0], p[1]);
    csv += row;
    known.push_back(t);
  };
  for (int k = 0; k <= 200; ++k) add_point(k / 200.0);
  for (double t : {-0.05, 1.04}) add_point(t);  // the extension
  csv += "w,3.5,9\nw,-2,-2\n";  // off the curve
  known.push_back(std::nan(""));
  known.push_back(std::nan(""));
  const std::string points = scratch.write("points.csv", csv);

  std::vector<std::vector<std::vector<std::string>>> runs;
  for (const std::string& name : kernel_names()) {
    const std::string out = scratch.path("out-" + name + ".csv");
    const Outcome run = run_bezinv(
        scratch, "invert --curves " + quoted(curves) + " --points " + quoted(points) + " --out " + quoted(out),
        "BEZINV_KERNEL=" + name);
    ASSERT_EQ(run.exit_code, 0) << name << ": " << run.err;
    std::vector<std::string> lines = split(read_file(out), '\n');
    ASSERT_EQ(lines.size(), known.size() + 2) << name;
    std::vector<std::vector<std::string>> rows;
    for (std::size_t i = 1; i <= known.size(); ++i) rows.push_back(split(lines[i], ','));
    for (std::size_t i = 0; i < known.size(); ++i) {
      const double t = std::strtod(rows[i][0].c_str(), nullptr);
      if (std::isnan(known[i])) {
        EXPECT_EQ(rows[i][1], "off_curve") << name << " row " << i;
      } else {
        EXPECT_EQ(rows[i][1], known[i] < 0 || known[i] > 1 ? "outside_segment" : "ok") << name << " row " << i;
        EXPECT_NEAR(t, known[i], 1e-12) << name << " row " << i;
      }
    }
    runs.push_back(std::move(rows));
  }
  for (std::size_t k = 1; k < runs.size(); ++k)
    for (std::size_t i = 0; i < known.size(); ++i) {
      EXPECT_EQ(runs[k][i][1], runs[0][i][1]) << kernel_names()[k] << " row " << i;  // status
      EXPECT_EQ(runs[k][i][6], runs[0][i][6]) << kernel_names()[k] << " row " << i;  // path
      EXPECT_NEAR(std::strtod(runs[k][i][0].c_str(), nullptr), std::strtod(runs[0][i][0].c_str(), nullptr), 1e-15)
          << kernel_names()[k] << " row " << i;
    }
  EXPECT_EQ(runs.size(), kernel_names().size());
}

}  // namespace
}  // namespace bezinv
