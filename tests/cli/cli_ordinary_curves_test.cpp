// End to end: the real `bezinv` command on ordinary curves that a plain Bezout inversion refuses or
// gets wrong (a graph of a function as bezier and as rational, an arch 1e12 from the origin, a line
// traced at degree 3, a curve with a common factor), and on finite points far beyond the curves.
// The points are made here from known parameters by exact evaluation
// (tests/support/known_parameter.hpp), written with 17 significant digits, which read back as the
// same doubles.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "bezinv/curve.hpp"
#include "support/exact.hpp"
#include "support/known_parameter.hpp"
#include "support/run_bezinv.hpp"
#include "support/scratch_directory.hpp"
#include "support/split.hpp"

namespace bezinv {
namespace {

using test_support::ExactCurve;
using test_support::known_at;
using test_support::KnownParameter;
using test_support::Outcome;
using test_support::quoted;
using test_support::read_file;
using test_support::run_bezinv;
using test_support::ScratchDirectory;
using test_support::split;

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string list(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + number(v[i]);
  return s + "]";
}

// The curve as a CURVES.json entry, exactly the doubles the in-process Curve holds.
std::string json(const Curve& c) {
  std::string s = R"({"id": ")" + c.id + R"(", )";
  if (c.kind == CurveKind::bezier) {
    s += R"("kind": "bezier", "points": [)";
    for (std::size_t i = 0; i < c.x_num.size(); ++i)
      s += (i ? ", [" : "[") + number(c.x_num[i]) + ", " + number(c.y_num[i]) + "]";
    return s + "]}";
  }
  return s + R"("kind": "rational", "x_num": )" + list(c.x_num) + R"(, "x_den": )" + list(c.x_den) + R"(, "y_num": )" +
         list(c.y_num) + R"(, "y_den": )" + list(c.y_den) + "}";
}

// The arch [[0,0],[1,2],[3,2],[4,0]] times (1 + t) (x_den = y_den = 1 + t): integer coefficients,
// exact in double.
Curve factored_arch() {
  const exact::Poly g{mpq_class(1), mpq_class(2)};  // 1 + t
  exact::Poly x{0, 1, 3, 4}, y{0, 2, 2, 0}, w{1, 1, 1, 1};
  std::vector<exact::Poly> polys{exact::product(x, g), exact::product(w, g), exact::product(y, g)};
  mpz_class l = 1;
  for (const auto& p : polys)
    for (const mpq_class& c : p) mpz_lcm(l.get_mpz_t(), l.get_mpz_t(), c.get_den().get_mpz_t());
  std::vector<std::vector<double>> c;
  for (auto& p : polys) {
    for (mpq_class& v : p) v *= l;
    c.push_back(exact::to_double(p));
  }
  return Curve::rational("factored", c[0], c[1], c[2], c[1]);
}

struct Row {
  std::string curve;
  Point point;
  double t_true = NAN;  // NAN: a far point (off_curve)
};

TEST(CliOrdinaryCurves, OrdinaryCurvesEndToEnd) {
  std::vector<std::array<double, 2>> graph_points;
  for (int i = 0; i <= 8; ++i) graph_points.push_back({i / 8.0, std::sin(3 * (i / 8.0))});
  std::vector<double> x, ones(6, 1.0), y;
  for (int i = 0; i <= 5; ++i) {
    x.push_back(i / 5.0);
    y.push_back(std::exp(i / 5.0));
  }
  const std::vector<Curve> curves{
      Curve::bezier("graph", graph_points),
      Curve::rational("graph-rational", x, ones, y, ones),
      Curve::bezier("far-arch", {{1e12, 0}, {1e12 + 1, 2}, {1e12 + 3, 2}, {1e12 + 4, 0}}),
      Curve::bezier("line", {{0, 0}, {2, 2}, {1, 1}, {3, 3}}),
      factored_arch(),
  };
  std::string curves_json = R"({"curves": [)";
  for (std::size_t i = 0; i < curves.size(); ++i) curves_json += (i ? ",\n  " : "\n  ") + json(curves[i]);
  curves_json += "\n]}\n";

  std::vector<Row> rows;
  std::vector<const ExactCurve*> exact_of;
  std::vector<ExactCurve> exact;
  for (const Curve& c : curves) exact.emplace_back(c);
  for (std::size_t i = 0; i < curves.size(); ++i) {
    if (curves[i].id == "far-arch" || curves[i].id == "line") continue;  // their points are given below
    for (double t : {0.0, 0.25, 0.5, 0.61803398874989485, 1.0}) {
      const KnownParameter k = known_at(exact[i], t);
      rows.push_back({curves[i].id, k.point, t});
      exact_of.push_back(&exact[i]);
    }
  }
  // P(1/2) of the arch and of the line, exactly: (1e12 + 2, 1.5) and (1.5, 1.5).
  rows.push_back({"far-arch", {1e12 + 2, 1.5}, 0.5});
  exact_of.push_back(&exact[2]);
  rows.push_back({"line", {1.5, 1.5}, 0.5});
  exact_of.push_back(&exact[3]);
  // Finite points far away: off_curve, the residual finite, or inf beyond the largest double.
  for (const Point& p : {Point{1e200, 0}, Point{1.7e308, -1.7e308}, Point{-1.7e308, 1.7e308}}) {
    rows.push_back({"far-arch", p, NAN});
    exact_of.push_back(&exact[2]);
    rows.push_back({"graph", p, NAN});
    exact_of.push_back(&exact[0]);
  }

  ScratchDirectory scratch{"bezinv-cli-ordinary-"};
  std::string csv = "curve,x,y\n";
  for (const Row& r : rows) csv += r.curve + "," + number(r.point.x) + "," + number(r.point.y) + "\n";
  const std::string curves_path = scratch.write("curves.json", curves_json),
                    points_path = scratch.write("points.csv", csv);
  const std::string out = scratch.path("out.csv");
  const Outcome run = run_bezinv(
      scratch, "invert --curves " + quoted(curves_path) + " --points " + quoted(points_path) + " --out " + quoted(out));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::vector<std::string> lines = split(read_file(out), '\n');
  ASSERT_EQ(lines.size(), rows.size() + 2);  // header, the rows, "" after the final newline
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::vector<std::string> f = split(lines[i + 1], ',');
    ASSERT_EQ(f.size(), 8u) << lines[i + 1];
    const double t = std::strtod(f[0].c_str(), nullptr), residual = std::strtod(f[2].c_str(), nullptr);
    const Row& r = rows[i];
    const ExactCurve& e = *exact_of[i];
    std::ostringstream what;
    what.precision(17);
    what << r.curve << " point (" << r.point.x << ", " << r.point.y << "), t_true " << r.t_true << ": " << lines[i + 1];
    if (std::isnan(r.t_true)) {
      EXPECT_EQ(f[1], "off_curve") << what.str();
      EXPECT_TRUE(t >= 0 && t <= 1) << what.str();
      // The distance from the point to P(t) at the reported t, exactly: the residual, to 1e-12.
      const double at_t = e.distance(t, r.point);
      if (std::isinf(at_t)) {
        EXPECT_EQ(f[2], "inf") << what.str();
      } else {
        EXPECT_NEAR(residual, at_t, 1e-12 * at_t) << what.str();
      }
      continue;
    }
    const KnownParameter k = known_at(e, r.t_true);
    EXPECT_EQ(f[1], "ok") << what.str();
    EXPECT_LE(std::abs(t - r.t_true), test_support::parameter_bound(e, k)) << what.str();
    EXPECT_LE(residual, test_support::residual_bound(e, r.point)) << what.str();
    EXPECT_LE(e.distance(t, r.point), test_support::residual_bound(e, r.point)) << what.str();
    if (r.curve == "far-arch") std::printf("[ measured ] far arch P(1/2): %s\n", lines[i + 1].c_str());
  }
}

}  // namespace
}  // namespace bezinv
