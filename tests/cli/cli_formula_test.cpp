// `bezinv formula` end to end: Wang & Joe's four worked examples as a user runs them (CURVES.json
// in, JSON out), compared with the paper's formulae, centres, implicit equation, double points and
// parameters; and the command's errors.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <map>
#include <string>

#include "support/run_bezinv.hpp"
#include "support/scratch_directory.hpp"

namespace {

using bezinv::test_support::quoted;
using bezinv::test_support::run_bezinv;
using bezinv::test_support::ScratchDirectory;
using nlohmann::json;

// The paper's four curves: Examples 1 and 2 (the semicircle and its reparametrization (14)) as
// written there, Example 3's cubic, and Example 4's quartic in s = t + 1 (so that its denominator
// has no root on the segment), its power form converted exactly to the Bernstein basis of s.
constexpr const char* kPaperCurves = R"({"curves": [
 {"id": "example 1", "kind": "rational", "x_num": [0, 1, 0], "x_den": [1, 0, 1], "y_num": [1, 0, -1], "y_den": [1, 0, 1]},
 {"id": "example 2", "kind": "rational", "x_num": [0, 0.5, 0], "x_den": [0.25, 0, 1], "y_num": [0.25, 0, -1], "y_den": [0.25, 0, 1]},
 {"id": "example 3", "kind": "rational_bezier", "points": [[0,0],[1,1],[0,1],[1,0]], "weights": [1,2,2,1]},
 {"id": "example 4", "kind": "rational", "x_num": [4, 3, 2, 1.5, 1], "x_den": [4, 2, 2, 2, 1], "y_num": [4, 1, 0, -0.5, -1], "y_den": [4, 2, 2, 2, 1]}
]})";

struct FormulaRun {
  ScratchDirectory scratch{"bezinv-cli-formula-"};
  json curves;  // the "curves" array of the command's output
  FormulaRun(const std::string& arguments) {
    const std::string path = scratch.write("curves.json", kPaperCurves);
    const auto run = run_bezinv(scratch, "formula --json --curves " + quoted(path) + " " + arguments);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    curves = json::parse(run.out)["curves"];
  }
};

// sum over the monomials a_ij x^i y^j of a polynomial in the output.
double evaluate(const json& polynomial, double x, double y) {
  double sum = 0.0;
  for (const auto& term : polynomial["monomials"])
    sum += term[2].get<double>() * std::pow(x, term[0].get<int>()) * std::pow(y, term[1].get<int>());
  return sum;
}

// The printed N / M equals the paper's formula at points spread over the plane (two formulae of
// one pencil agree everywhere: Theorem 4).
template <class Paper>
void expect_formula(const json& curve, Paper paper) {
  const json& f = curve["formula"];
  for (double x = -2.25; x <= 2.25; x += 0.5)
    for (double y = -2.25; y <= 2.25; y += 0.5) {
      const double expected = paper(x, y);
      if (!std::isfinite(expected) || std::abs(expected) > 1e6) continue;
      EXPECT_NEAR(evaluate(f["N"], x, y) / evaluate(f["M"], x, y), expected, 1e-10 * (1 + std::abs(expected)))
          << curve["id"] << " at (" << x << ", " << y << ")";
    }
}

void expect_centre(const json& curve, double x, double y) {
  const json& c = curve["formula"]["centre"];
  ASSERT_TRUE(c.is_array()) << curve["id"];
  EXPECT_NEAR(c[0].get<double>() / c[2].get<double>(), x, 1e-12) << curve["id"];
  EXPECT_NEAR(c[1].get<double>() / c[2].get<double>(), y, 1e-12) << curve["id"];
}

TEST(CliFormula, ReproducesThePapersFourExamples) {
  const FormulaRun run("");
  ASSERT_EQ(run.curves.size(), 4u);
  // (12): centre P(infinity) = (-1, 0).
  expect_formula(run.curves[0], [](double x, double y) { return (x - y + 1) / (2 * (x + 1)); });
  expect_centre(run.curves[0], -1, 0);
  // (15): centre (-4/5, -3/5).
  expect_formula(run.curves[1], [](double x, double y) { return (2 * x - y + 1) / (4 * x + 3 * y + 5); });
  expect_centre(run.curves[1], -0.8, -0.6);
  // Example 3: t = (5y - 6x) / (10y - 6), centred at the double point (1/2, 3/5), which has the
  // parameters (7 -+ sqrt 21) / 14; F = 1225y^3 - 756x^2y - 2520y^2 + 756xy + 1512x^2 + 1512y - 1512x.
  const json& cubic = run.curves[2];
  expect_formula(cubic, [](double x, double y) { return (5 * y - 6 * x) / (10 * y - 6); });
  expect_centre(cubic, 0.5, 0.6);
  auto paper_f = [](double x, double y) {
    return 1225 * y * y * y - 756 * x * x * y - 2520 * y * y + 756 * x * y + 1512 * x * x + 1512 * y - 1512 * x;
  };
  const double k = evaluate(cubic["implicit"]["F"], 3, 5) / paper_f(3, 5);
  for (double x = -2; x <= 2; x += 0.5)
    for (double y = -2; y <= 2; y += 0.5)
      EXPECT_NEAR(evaluate(cubic["implicit"]["F"], x, y) / k, paper_f(x, y), 1e-9 * (1 + std::abs(paper_f(x, y))));
  const json& base = cubic["base_points"]["real"];
  ASSERT_EQ(base.size(), 1u);
  EXPECT_EQ(base[0]["kind"], "double_point");
  EXPECT_NEAR(base[0]["point"][0].get<double>(), 0.5, 1e-12);
  EXPECT_NEAR(base[0]["point"][1].get<double>(), 0.6, 1e-12);
  EXPECT_NEAR(base[0]["parameters"][0][0].get<double>(), (7 - std::sqrt(21.0)) / 14, 1e-12);
  EXPECT_NEAR(base[0]["parameters"][1][0].get<double>(), (7 + std::sqrt(21.0)) / 14, 1e-12);
  // Example 4 (default choice): the three double points are base points, whichever the fourth.
  int doubles = 0, isolated = 0;
  for (const auto& p : run.curves[3]["base_points"]["real"]) {
    doubles += p["kind"] == "double_point";
    isolated += p["kind"] == "isolated_point";
  }
  EXPECT_EQ(doubles, 2);
  EXPECT_EQ(isolated, 1);
}

TEST(CliFormula, BasePointsChooseTheConicsCentreAndTheQuarticsFourthBasePoint) {
  const FormulaRun run("--base-points 0");
  // (13): centre P(0) = (0, 1).
  expect_formula(run.curves[0], [](double x, double y) { return (1 - y) / (x - y + 1); });
  expect_centre(run.curves[0], 0, 1);
  // Example 4 with its fourth base point at (1, 1) = P(s = 0): t = x(x-1) / (y(y-1)), s = t + 1.
  expect_formula(run.curves[3], [](double x, double y) { return (x * (x - 1) + y * (y - 1)) / (y * (y - 1)); });
  // The cubic has no free choice: a base point asked for is an error of that curve alone.
  EXPECT_TRUE(run.curves[2]["formula"].contains("error"));
}

TEST(CliFormula, AnUnknownCurveOrABadBasePointIsAnInputError) {
  ScratchDirectory scratch("bezinv-cli-formula-");
  const std::string path = scratch.write("curves.json", kPaperCurves);
  auto run = run_bezinv(scratch, "formula --curves " + quoted(path) + " --curve nope");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("no curve with id \"nope\""), std::string::npos) << run.err;
  run = run_bezinv(scratch, "formula --curves " + quoted(path) + " --base-points 0.5,x");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("'x'"), std::string::npos) << run.err;
}

// One CSV results file as rows of named fields.
std::vector<std::map<std::string, std::string>> formula_cli_rows(const std::string& text) {
  std::vector<std::vector<std::string>> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    std::vector<std::string> fields;
    std::size_t a = start;
    while (a <= end) {
      const std::size_t b = std::min(text.find(',', a), end);
      fields.push_back(text.substr(a, b - a));
      a = b + 1;
    }
    lines.push_back(fields);
    start = end + 1;
  }
  std::vector<std::map<std::string, std::string>> rows;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::map<std::string, std::string> row;
    for (std::size_t j = 0; j < lines[0].size() && j < lines[i].size(); ++j) row[lines[0][j]] = lines[i][j];
    rows.push_back(row);
  }
  return rows;
}

// `bezinv invert --algebraic formula`: the same statuses as the default on the paper's cubic, at
// points on it, near its double point and off it; rows the formula started say path formula.
TEST(CliFormula, InvertWithTheFormulaGivesTheDefaultsStatuses) {
  ScratchDirectory scratch("bezinv-cli-formula-");
  const std::string curves = scratch.write("curves.json", kPaperCurves);
  std::string csv = "curve,x,y\n";
  for (int k = 0; k <= 40; ++k) {
    const double t = k / 40.0;  // Example 3's cubic in power form (the paper's x(t), y(t))
    const double w = -3 * t * t + 3 * t + 1;
    const double x = (7 * t * t * t - 12 * t * t + 6 * t) / w, y = (-6 * t * t + 6 * t) / w;
    csv += "example 3," + std::to_string(x) + "," + std::to_string(y) + "\n";
    csv += "example 3," + std::to_string(x + 0.01) + "," + std::to_string(y) + "\n";
  }
  csv += "example 3,0.5,0.6\n";  // the double point, the formula's centre
  const std::string points = scratch.write("points.csv", csv);
  const auto bezout = run_bezinv(scratch, "invert --curves " + quoted(curves) + " --points " + quoted(points) +
                                              " --out " + quoted(scratch.path("bezout.csv")));
  const auto formula = run_bezinv(scratch, "invert --algebraic formula --curves " + quoted(curves) + " --points " +
                                               quoted(points) + " --out " + quoted(scratch.path("formula.csv")));
  ASSERT_EQ(bezout.exit_code, 0) << bezout.err;
  ASSERT_EQ(formula.exit_code, 0) << formula.err;
  const auto a = formula_cli_rows(bezinv::test_support::read_file(scratch.path("bezout.csv")));
  const auto b = formula_cli_rows(bezinv::test_support::read_file(scratch.path("formula.csv")));
  ASSERT_EQ(a.size(), b.size());
  int by_formula = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].at("status"), b[i].at("status")) << "row " << i;
    if (a[i].at("status") == "ok") {
      EXPECT_NEAR(std::stod(a[i].at("t")), std::stod(b[i].at("t")), 1e-12) << "row " << i;
    }
    by_formula += b[i].at("path") == "formula";
  }
  EXPECT_EQ(a.back().at("status"), "double_point");  // the centre: the Bezout path's answer
  EXPECT_GT(by_formula, 20);
}

// `--off-curve projection` on the paper's semicircles (Examples 1 and 2): the point (1, 1), off the
// unit circle, is projected from the centre P(inf) onto the circle. Example 1: from (-1, 0) onto
// (3/5, 4/5), t = 1/4 by formula (12), residual |(3/5, 4/5) - (1, 1)| = sqrt(1/5). Example 2: from
// (-4/5, -3/5) onto (20/29, 21/29), t^ = 1/6 by formula (15), residual sqrt(145)/29. The nearest
// point, (1/sqrt 2, 1/sqrt 2), is the default's answer. A point on the curve is answered as without
// the option. And `--no-refine --algebraic formula` reports N/M itself at (3/5, 4/5): t = 1/4 by
// (12), t^ = 1/7 by (15).
TEST(CliFormula, ProjectionAnswersFromTheCentreAndNoRefineReportsNOverM) {
  ScratchDirectory scratch("bezinv-cli-formula-");
  const std::string curves = scratch.write("curves.json", kPaperCurves);
  const std::string points = scratch.write("points.csv",
                                           "curve,x,y\nexample 1,1,1\nexample 1,0.6,0.8\n"
                                           "example 2,1,1\nexample 2,0.6,0.8\n");
  auto run = [&](const std::string& options, const std::string& out) {
    const auto r = run_bezinv(scratch, "invert " + options + " --curves " + quoted(curves) + " --points " +
                                           quoted(points) + " --out " + quoted(scratch.path(out)));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return formula_cli_rows(bezinv::test_support::read_file(scratch.path(out)));
  };
  const auto nearest = run("", "nearest.csv");
  const auto projection = run("--off-curve projection", "projection.csv");
  const auto unrefined = run("--no-refine --algebraic formula", "unrefined.csv");
  ASSERT_EQ(nearest.size(), 4u);
  ASSERT_EQ(projection.size(), 4u);
  ASSERT_EQ(unrefined.size(), 4u);
  const double projected_t[] = {0.25, 1.0 / 6.0}, projected_residual[] = {std::sqrt(0.2), std::sqrt(145.0) / 29},
               on_curve_t[] = {0.25, 1.0 / 7.0};
  for (int c = 0; c < 2; ++c) {
    const auto& off = projection[2 * c];
    EXPECT_EQ(off.at("status"), "off_curve");
    EXPECT_EQ(off.at("path"), "projection");
    EXPECT_NEAR(std::stod(off.at("t")), projected_t[c], 1e-12);
    EXPECT_NEAR(std::stod(off.at("residual")), projected_residual[c], 1e-12);
    EXPECT_EQ(nearest[2 * c].at("status"), "off_curve");
    EXPECT_EQ(nearest[2 * c].at("path"), "nearest");
    EXPECT_NEAR(std::stod(nearest[2 * c].at("residual")), std::sqrt(2.0) - 1, 1e-12);
    EXPECT_EQ(projection[2 * c + 1], nearest[2 * c + 1]);  // on the curve: unchanged
    EXPECT_EQ(unrefined[2 * c + 1].at("status"), "ok");
    EXPECT_EQ(unrefined[2 * c + 1].at("path"), "formula");
    EXPECT_NEAR(std::stod(unrefined[2 * c + 1].at("t")), on_curve_t[c], 1e-12);
  }
}

}  // namespace
