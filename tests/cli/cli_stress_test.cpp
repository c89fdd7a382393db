// `bezinv stress` end to end: every family, kind and degree asked for gets its cell, the JSON
// object carries the documented fields, the engine's statuses are all right on these families
// (exit 0), and bad arguments are refused naming the item.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "support/run_bezinv.hpp"
#include "support/scratch_directory.hpp"

namespace {

using bezinv::test_support::run_bezinv;
using bezinv::test_support::ScratchDirectory;

TEST(CliStress, EveryCellReportedAndEveryStatusRight) {
  ScratchDirectory scratch{"bezinv-stress-test-"};
  const auto run = run_bezinv(scratch,
                              "stress --families on_curve,near_ends,extension,noisy,far --degrees 2-3 --points 1200 "
                              "--curves 2 --paths default,svd-only --json");
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out.substr(0, 2000);
  const auto report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report.at("wrong_status").get<int>(), 0);
  EXPECT_EQ(report.at("nan_t").get<int>(), 0);
  const auto& cells = report.at("cells");
  ASSERT_EQ(cells.size(), 5u * 3u * 2u * 2u);  // families x kinds x degrees x paths
  std::set<std::string> families;
  int rows = 0;
  for (const auto& cell : cells) {
    families.insert(cell.at("family").get<std::string>());
    rows += cell.at("rows").get<int>();
    EXPECT_GT(cell.at("rows").get<int>(), 0) << cell.dump();
    // Every answer within a small multiple of the accuracy model's bound.
    EXPECT_LE(cell.at("abs_dt_over_bound").at("max").get<double>(), 4.0) << cell.dump();
    for (const char* field : {"p50", "p99", "p999", "max"}) EXPECT_TRUE(cell.at("abs_dt").contains(field));
    EXPECT_GT(cell.at("points_per_second").get<double>(), 0.0);
  }
  EXPECT_EQ(families, (std::set<std::string>{"on_curve", "near_ends", "extension", "noisy", "far"}));
  EXPECT_EQ(report.at("rows").get<int>(), rows);
}

// The families made of special curves, where each applies at degrees 3 and 4: crossings, curves
// far from the origin, degree-elevated, improper (even degrees), extreme weights (rational kinds),
// the papers' curves (Example 4 and the demo's cubic at degree 3).
TEST(CliStress, SpecialCurvesFamiliesAllRight) {
  ScratchDirectory scratch{"bezinv-stress-test-"};
  const auto run = run_bezinv(scratch,
                              "stress --families crossings,translated,elevated,improper,weights,papers --degrees 3-4 "
                              "--points 2400 --curves 2 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out.substr(0, 2000);
  const auto report = nlohmann::json::parse(run.out);
  std::set<std::string> families;
  int double_points = 0;
  for (const auto& cell : report.at("cells")) {
    families.insert(cell.at("family").get<std::string>());
    EXPECT_LE(cell.at("abs_dt_over_bound").at("max").get<double>(), 4.0) << cell.dump();
    if (cell.at("confusion").contains("double_point"))
      double_points += cell.at("confusion").at("double_point").value("double_point", 0);
  }
  EXPECT_EQ(families, (std::set<std::string>{"crossings", "translated", "elevated", "improper", "weights", "papers"}));
  EXPECT_GT(double_points, 0) << "the crossings must include points within the tolerance of both branches";
}

TEST(CliStress, RefusesUnknownFamiliesKindsPathsAndDegrees) {
  ScratchDirectory scratch{"bezinv-stress-test-"};
  for (const auto& [arguments, named] :
       {std::pair{"--families on_curve,wobbly", "wobbly"}, std::pair{"--kinds nurbs", "nurbs"},
        std::pair{"--paths fast", "fast"}, std::pair{"--degrees 0-3", "0-3"}, std::pair{"--degrees 5-40", "5-40"}}) {
    const auto run = run_bezinv(scratch, std::string("stress --points 10 ") + arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments;
    EXPECT_NE(run.err.find(named), std::string::npos) << arguments << ": " << run.err;
  }
}

}  // namespace
