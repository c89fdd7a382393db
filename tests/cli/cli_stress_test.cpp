// `bezinv stress` end to end: every family, kind and degree asked for gets its cell, the JSON
// object carries the documented fields, the engine's statuses are all right on these families
// (exit 0), and bad arguments are refused naming the item.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
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
                              "stress --families crossings,translated,elevated,improper,weights,papers,matrix_weighted,space,graphs "
                              "--degrees 3-4 "
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
  EXPECT_EQ(families, (std::set<std::string>{"crossings", "translated", "elevated", "improper", "weights", "papers",
                                             "matrix_weighted", "space", "graphs"}));
  EXPECT_GT(double_points, 0) << "the crossings must include points within the tolerance of both branches";
}

// Graphs of smooth functions at the degrees where they lie within rounding of a lower degree (the
// formula path's curves): every status right, every t within the accuracy model's bound.
TEST(CliStress, GraphsOfFunctionsAtHighDegreeAllRight) {
  ScratchDirectory scratch{"bezinv-stress-test-"};
  const auto run = run_bezinv(scratch, "stress --families graphs --degrees 8-20 --points 1300 --curves 2 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out.substr(0, 2000);
  const auto report = nlohmann::json::parse(run.out);
  int cells = 0;
  for (const auto& cell : report.at("cells")) {
    ++cells;
    EXPECT_EQ(cell.at("wrong_status").get<int>(), 0) << cell.dump();
    EXPECT_LE(cell.at("abs_dt_over_bound").at("max").get<double>(), 4.0) << cell.dump();
  }
  EXPECT_EQ(cells, 3 * 13);  // every kind and degree
}

// --report DIR: summary.json is the --json object; index.html is well-formed (an XML parser reads
// it: XHTML), has a histogram and a scatter plot with marks per family; every reproducer runs
// through `bezinv invert` as it is and gives what truth.json says the stress run got; a file
// already in DIR is left alone.
TEST(CliStress, ReportPageSummaryAndReproducers) {
  ScratchDirectory scratch{"bezinv-stress-test-"};
  const std::string dir = scratch.path("report");
  std::filesystem::create_directories(dir);
  scratch.write("report/mine.txt", "keep me");
  const auto run = run_bezinv(scratch, "stress --families on_curve,noisy,crossings --degrees 3-4 --points 600 --curves 2 "
                                       "--report " + bezinv::test_support::quoted(dir));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(bezinv::test_support::read_file(dir + "/mine.txt"), "keep me");
  const auto summary = nlohmann::json::parse(bezinv::test_support::read_file(dir + "/summary.json"));
  EXPECT_EQ(summary.at("wrong_status").get<int>(), 0);
  EXPECT_GT(summary.at("rows").get<int>(), 100);

  // Well-formed, and the plots have marks: Debian's Python reads the page as XML.
  const std::string check = scratch.write("check.py", R"(
import sys, xml.etree.ElementTree as E
svg = '{http://www.w3.org/2000/svg}'
root = E.parse(sys.argv[1]).getroot()
plots = root.findall('.//' + svg + 'svg')
marks = [len([e for e in p.iter() if e.get('class') == 'mark']) for p in plots]
print(len(plots), min(marks))
)");
  const std::string out = scratch.path("python.txt");
  ASSERT_EQ(std::system(("/usr/bin/python3 " + bezinv::test_support::quoted(check) + " " + bezinv::test_support::quoted(dir + "/index.html") +
                         " > " + bezinv::test_support::quoted(out) + " 2>&1").c_str()),
            0)
      << bezinv::test_support::read_file(out);
  int plots = 0, least_marks = 0;
  ASSERT_EQ(std::sscanf(bezinv::test_support::read_file(out).c_str(), "%d %d", &plots, &least_marks), 2);
  EXPECT_EQ(plots, 6);  // a histogram and a scatter plot per family
  EXPECT_GT(least_marks, 0);

  // The reproducers: each family's worst rows.
  int reproduced = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/repro")) {
    const std::string r = entry.path().string();
    const auto truth = nlohmann::json::parse(bezinv::test_support::read_file(r + "/truth.json"));
    const auto again = run_bezinv(scratch, "invert --curves " + bezinv::test_support::quoted(r + "/curves.json") +
                                               " --points " + bezinv::test_support::quoted(r + "/points.csv") +
                                               " --out " + bezinv::test_support::quoted(r + "/out.csv"));
    ASSERT_EQ(again.exit_code, 0) << r << ": " << again.err;
    const std::string rows = bezinv::test_support::read_file(r + "/out.csv");
    const std::string row = rows.substr(rows.find('\n') + 1);
    char status[32] = {};
    double t = 0;
    ASSERT_EQ(std::sscanf(row.c_str(), "%lf,%31[^,]", &t, status), 2) << rows;
    EXPECT_EQ(std::string(status), truth.at("got_status").get<std::string>()) << r;
    EXPECT_EQ(t, truth.at("got_t").get<double>()) << r;
    ++reproduced;
  }
  EXPECT_GE(reproduced, 3);
}

// The page in a real browser (Debian's headless chromium, which scripts/setup.sh installs): it
// loads, every plot in the rendered DOM has marks, and the screenshot is not blank: ink on a
// fiftieth of it or more (text, bars, tables), in more than a few colours (the plots' marks, bars and text).
TEST(CliStress, ReportRendersInAHeadlessBrowser) {
  std::string browser;
  for (const char* candidate : {"/usr/bin/chromium-headless-shell", "/usr/lib/chromium/chromium-headless-shell",
                                "/usr/bin/chromium"})
    if (std::filesystem::exists(candidate)) {
      browser = candidate;
      break;
    }
  if (browser.empty()) GTEST_SKIP() << "no headless chromium here (scripts/setup.sh installs chromium-headless-shell)";
  ScratchDirectory scratch{"bezinv-stress-browser-"};
  const std::string dir = scratch.path("report");
  const auto run = run_bezinv(scratch, "stress --families on_curve,crossings --degrees 3 --points 300 --curves 2 --report " +
                                           bezinv::test_support::quoted(dir));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string out = scratch.path("render.txt");
  const std::string command = "/usr/bin/python3 " + bezinv::test_support::quoted(BEZINV_TEST_SOURCE_DIR "/support/render_report.py") +
                              " " + bezinv::test_support::quoted(browser) + " " + bezinv::test_support::quoted(dir + "/index.html") +
                              " " + bezinv::test_support::quoted(scratch.path("")) + " > " + bezinv::test_support::quoted(out) + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << bezinv::test_support::read_file(out);
  int plots = 0, least_marks = 0, colours = 0;
  double inked = 0;
  ASSERT_EQ(std::sscanf(bezinv::test_support::read_file(out).c_str(), "%d %d %lf %d", &plots, &least_marks, &inked, &colours), 4)
      << bezinv::test_support::read_file(out);
  EXPECT_EQ(plots, 4);  // a histogram and a scatter plot per family
  EXPECT_GT(least_marks, 0);
  EXPECT_GT(inked, 0.02);
  EXPECT_GT(colours, 4);
}

// A report directory that cannot be made (a file is in the way): exit 2, the path named.
TEST(CliStress, AReportDirectoryThatCannotBeWrittenIsNamed) {
  ScratchDirectory scratch{"bezinv-stress-test-"};
  const std::string blocked = scratch.write("blocked", "a file, not a directory");
  const auto run = run_bezinv(scratch, "stress --families on_curve --degrees 2 --points 20 --report " +
                                           bezinv::test_support::quoted(blocked + "/report"));
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find(blocked), std::string::npos) << run.err;
  EXPECT_EQ(bezinv::test_support::read_file(blocked), "a file, not a directory");
}

TEST(CliStress, RefusesUnknownFamiliesKindsPathsAndDegrees) {
  ScratchDirectory scratch{"bezinv-stress-test-"};
  for (const auto& [arguments, named] :
       {std::pair{"--families on_curve,wobbly", "wobbly"}, std::pair{"--kinds nurbs", "nurbs"},
        std::pair{"--paths fast", "fast"}, std::pair{"--degrees 0-3", "0-3"}, std::pair{"--degrees 5-40", "5-40"},
        std::pair{"--baseline acis", "acis"}}) {
    const auto run = run_bezinv(scratch, std::string("stress --points 10 ") + arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments;
    EXPECT_NE(run.err.find(named), std::string::npos) << arguments << ": " << run.err;
  }
}

}  // namespace
