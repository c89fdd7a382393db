// `bezinv profile` end to end: it generates points at known parameters on random curves, so on
// exact (noise-free) points every row must come back ok with t at rounding level of t_true; the
// JSON object must carry the fields the README documents.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "support/run_bezinv.hpp"
#include "support/sanitizers.hpp"
#include "support/scratch_directory.hpp"

namespace {

using bezinv::test_support::run_bezinv;
using bezinv::test_support::ScratchDirectory;

TEST(CliProfile, JsonReportsThroughputAndEveryOnCurvePointOk) {
  ScratchDirectory scratch{"bezinv-profile-test-"};
  // Fewer points under the sanitizers (support/sanitizers.hpp): the same stages and paths.
  const int points = bezinv::test_support::kSanitizerTree ? 600 : 3000;
  for (const char* kind : {"bezier", "rational_bezier", "rational"}) {
    for (int degree : {1, 3, 8, 20}) {
      const auto run = run_bezinv(scratch, std::string("profile --kind ") + kind + " --degree " +
                                               std::to_string(degree) + " --points " + std::to_string(points) +
                                               " --threads 2 --json");
      ASSERT_EQ(run.exit_code, 0) << kind << " " << degree << ": " << run.err;
      const auto report = nlohmann::json::parse(run.out);
      EXPECT_GT(report.at("points_per_second").get<double>(), 0.0);
      EXPECT_EQ(report.at("degree").get<int>(), degree);
      EXPECT_EQ(report.at("threads").get<int>(), 2);
      EXPECT_FALSE(report.at("kernel").get<std::string>().empty());
      EXPECT_EQ(report.at("points").get<int>(), points);
      // Exact points (P(t) in double): all ok. The t error bound is generous (rounding of P(t) is
      // ~1e-16 of the curve size; a parameter is off by that over the speed |P'|, which on these
      // arcs stays above 1e-3 of the size) and still fails on any wrong branch or stalled Newton.
      EXPECT_EQ(report.at("ok").get<int>(), points) << kind << " degree " << degree;
      EXPECT_LE(report.at("max_abs_dt_ok").get<double>(), 1e-10) << kind << " degree " << degree;
      // A conic's or cubic's points on the formula path, all of them here, go through one kernel
      // (formula_newton: normalizing, N / M, Newton, the certificate), timed as the kernel stage,
      // then the rows (decide); every other path has all five stages.
      const bool fused = degree <= 3 && report.at("formula").get<int>() == points;
      for (const char* stage : {"kernel", "decide"})
        EXPECT_GT(report.at("stages_points_per_second").at(stage).get<double>(), 0.0) << kind << " " << stage;
      for (const char* stage : {"form_b", "read_out", "refine"}) {
        const double rate = report.at("stages_points_per_second").at(stage).get<double>();
        if (fused)
          EXPECT_EQ(rate, 0.0) << kind << " " << stage;
        else
          EXPECT_GT(rate, 0.0) << kind << " " << stage;
      }
    }
  }
}

// --mixed leaves every other point on the curve: at noise up to 1e-2 of the diagonal (ten
// thousand times the tolerance) those are the ok rows, nearly all the others off the curve,
// answered by distance.
TEST(CliProfile, MixedLeavesEveryOtherPointOnTheCurve) {
  ScratchDirectory scratch{"bezinv-profile-test-"};
  // A multiple of twice the 16 curves: every curve gets an even count, half of it on the curve.
  const int points = bezinv::test_support::kSanitizerTree ? 640 : 3200;
  const auto run = run_bezinv(scratch, "profile --degree 5 --noise 1e-2 --mixed --threads 1 --json --points " +
                                           std::to_string(points));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto report = nlohmann::json::parse(run.out);
  EXPECT_TRUE(report.at("mixed").get<bool>());
  // The half on the curve ok; of the other half, moved by up to 1e-2 of the diagonal (uniformly),
  // about one in 10^4 lands within the tolerance and is ok too, the rest off the curve.
  const int ok = report.at("ok").get<int>(), off = report.at("off_curve_path").get<int>();
  EXPECT_GE(ok, points / 2);
  EXPECT_LE(ok, points / 2 + points / 200);
  EXPECT_EQ(ok + off, points);
  const auto plain = nlohmann::json::parse(run_bezinv(scratch, "profile --degree 5 --noise 1e-2 --threads 1 --json "
                                                               "--points " + std::to_string(points)).out);
  EXPECT_FALSE(plain.at("mixed").get<bool>());
  EXPECT_LT(plain.at("ok").get<int>(), points / 100);
}

TEST(CliProfile, RefusesADegreeOutOfRange) {
  ScratchDirectory scratch{"bezinv-profile-test-"};
  EXPECT_NE(run_bezinv(scratch, "profile --degree 0").exit_code, 0);
  EXPECT_NE(run_bezinv(scratch, "profile --degree 99").exit_code, 0);
  EXPECT_NE(run_bezinv(scratch, "profile --kind spline").exit_code, 0);
}

}  // namespace
