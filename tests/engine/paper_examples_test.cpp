// The paper's numerical examples (Marco & Martinez, Sect. 4-5) through the public API.
// Expected numbers come from the paper itself or from exact rational arithmetic here (the exact
// curve points at t = 1/7, 1/3; the root of Example 1's x(t) = 1/2), never from bezinv's output.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

#include "bezinv/bezout.hpp"
#include "bezinv/curve.hpp"
#include "bezinv/datasets/paper_curves.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/kernels/symmetric_svd.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "support/exact.hpp"
#include "support/measure.hpp"

namespace bezinv {
namespace {

using test_support::sci;

// ---- the curves -------------------------------------------------------------------------------

// The curves come from datasets_gen (one transcription of the paper for the whole project);
// CurvesMatchThePaperText below checks that transcription against facts the paper prints
// independently of the control points (an exact curve point, power forms, an inversion formula).
Curve example1() { return datasets::paper_example1_curve(); }  // = Example 3's curve
Curve example2() { return datasets::paper_example2_curve(); }
Curve example4() { return datasets::paper_example4_curve(); }

// The curve in exact rationals (a double is a dyadic rational, so this adds no error).
exact::RationalCurve exact_curve(const Curve& c) {
  return {exact::to_exact(c.x_num), exact::to_exact(c.x_den), exact::to_exact(c.y_num), exact::to_exact(c.y_den)};
}

// Squared diagonal of the bounding box of the control points (x_num_i / x_den_i, y_num_i / y_den_i),
// the length tolerances are relative to (invert.hpp, plan.hpp), exactly.
mpq_class squared_diagonal(const exact::RationalCurve& c) {
  std::vector<mpq_class> xs, ys;
  for (std::size_t i = 0; i < c.x_num.size(); ++i) {
    xs.push_back(c.x_num[i] / c.x_den[i]);
    ys.push_back(c.y_num[i] / c.y_den[i]);
  }
  const auto [xmin, xmax] = std::minmax_element(xs.begin(), xs.end());
  const auto [ymin, ymax] = std::minmax_element(ys.begin(), ys.end());
  const mpq_class dx = *xmax - *xmin, dy = *ymax - *ymin;
  return dx * dx + dy * dy;
}

mpq_class squared_distance(const std::array<mpq_class, 2>& a, const std::array<mpq_class, 2>& b) {
  const mpq_class dx = a[0] - b[0], dy = a[1] - b[1];
  return dx * dx + dy * dy;
}

// A rational from "num/den" text, canonicalized (gmpxx leaves mpq_class(num, den) as given).
mpq_class q(const char* text) {
  mpq_class r(text);
  r.canonicalize();
  return r;
}

double relative_error(double got, double want) { return std::abs(got - want) / std::abs(want); }

constexpr InvertOptions kAlgebraic{.refine = false};

TEST(PaperExamples, CurvesMatchThePaperText) {
  // Example 1 (Sect. 4): in the power basis p-bar = 4 - x - 6t^2 + 8t^3 + (1 - 2x) t^4 and
  // q-bar = 2 - y + 4t - 6t^2 + 4t^3, i.e. x_num = 4 - 6t^2 + 8t^3 + t^4, x_den = 1 + 2t^4,
  // y_num = 2 + 4t - 6t^2 + 4t^3, y_den = 1.
  const Curve c1 = example1();
  EXPECT_EQ(c1.kind, CurveKind::rational);
  auto power = [](const std::vector<double>& b) { return exact::power_from_bernstein(exact::to_exact(b)); };
  auto ints = [](std::initializer_list<int> v) {
    exact::Poly p;
    for (int x : v) p.emplace_back(x);
    return p;
  };
  EXPECT_EQ(power(c1.x_num), ints({4, 0, -6, 8, 1}));
  EXPECT_EQ(power(c1.x_den), ints({1, 0, 0, 0, 2}));
  EXPECT_EQ(power(c1.y_num), ints({2, 4, -6, 4, 0}));
  EXPECT_EQ(power(c1.y_den), ints({1, 0, 0, 0, 0}));

  // Example 2 (Sect. 5): P(1/7) = (78193109744768, 131831466405881) / 9191995131007, which pins
  // down all 16 points and weights far beyond chance.
  const Curve c2 = example2();
  EXPECT_EQ(c2.kind, CurveKind::rational_bezier);
  EXPECT_EQ(c2.degree(), 15);
  const auto p17 = exact_curve(c2).point(q("1/7"));
  EXPECT_EQ(p17[0], q("78193109744768/9191995131007"));
  EXPECT_EQ(p17[1], q("131831466405881/9191995131007"));

  // Example 4 (Sect. 5): the printed inversion formula f(x, y) (Maple ffgausselim) satisfies
  // f(P(t)) = t identically; P(1/3) = (8/3, 109/45); f(2.66667, 2.42222) = 3.333319852915495e-01.
  const Curve c4 = example4();
  EXPECT_EQ(c4.kind, CurveKind::rational_bezier);
  EXPECT_EQ(c4.degree(), 3);
  const exact::RationalCurve e4 = exact_curve(c4);
  auto f = [](const mpq_class& x, const mpq_class& y) {
    return mpq_class((81408 * x + 13824 * y * x - 7680 * x * x - 276552 - 1008 * y + 1080 * y * y) /
                     (-216432 - 21024 * y + 67200 * x + 12672 * y * x - 6144 * x * x - 2160 * y * y));
  };
  for (const char* t : {"1/3", "1/5", "2/7", "3/4", "-1/2"}) {
    const auto p = e4.point(q(t));
    EXPECT_EQ(f(p[0], p[1]), q(t)) << t;
  }
  const auto p13 = e4.point(q("1/3"));
  EXPECT_EQ(p13[0], q("8/3"));
  EXPECT_EQ(p13[1], q("109/45"));
  EXPECT_NEAR(f(q("266667/100000"), q("242222/100000")).get_d(), 3.333319852915495e-01, 1e-15);
}

// ---- the algebraic parameter (paper Sect. 3, refine = false) -----------------------------------

// Example 2: t0 = 2 z2 / (2 z2 + 13 z1) = 1.428606867264249e-01 (Maple exact B, MATLAB SVD).
TEST(PaperExamples, Example2AlgebraicParameter) {
  const InversionPlan plan = make_plan(example2());
  ASSERT_TRUE(plan.usable()) << plan.reason();
  EXPECT_EQ(plan.degree(), 15);
  const PointResult r = invert_point(plan, {8.50665, 14.3420}, kAlgebraic);
  EXPECT_EQ(r.path, Path::bezout);
  // Measured 8.6e-14. The null vector is determined only to ~eps sigma_1 / sigma_14 by any
  // double-precision SVD, and here sigma_14 / sigma_1 = 6.7e-4 (r.sigma_next), i.e. ~3e-13: the
  // last digits of the paper's MATLAB value are not reproducible either (the lead's exact-B Python
  // run agreed with it to 4e-14).
  EXPECT_LE(relative_error(r.t, 1.428606867264249e-01), 1e-12) << r.t;
  RecordProperty("relative_error", sci(relative_error(r.t, 1.428606867264249e-01)));
  RecordProperty("sigma_min", sci(r.sigma_min));
  RecordProperty("sigma_next", sci(r.sigma_next));
}

// Example 3: t0 = z1 / (z1 + 3 z0) = 3.333333267311144e-01.
TEST(PaperExamples, Example3AlgebraicParameter) {
  const InversionPlan plan = make_plan(example1());
  ASSERT_TRUE(plan.usable()) << plan.reason();
  const PointResult r = invert_point(plan, {3.5542169, 2.8148148}, kAlgebraic);
  EXPECT_EQ(r.path, Path::bezout);
  // Measured 1.3e-15.
  EXPECT_LE(relative_error(r.t, 3.333333267311144e-01), 1e-12) << r.t;
  RecordProperty("relative_error", sci(relative_error(r.t, 3.333333267311144e-01)));
}

// Example 4: t0 = 3.333339104290224e-01.
TEST(PaperExamples, Example4AlgebraicParameter) {
  const InversionPlan plan = make_plan(example4());
  ASSERT_TRUE(plan.usable()) << plan.reason();
  const PointResult r = invert_point(plan, {2.66667, 2.42222}, kAlgebraic);
  EXPECT_EQ(r.path, Path::bezout);
  // Measured 1.7e-16.
  EXPECT_LE(relative_error(r.t, 3.333339104290224e-01), 1e-12) << r.t;
  RecordProperty("relative_error", sci(relative_error(r.t, 3.333339104290224e-01)));
}

// ---- singular values of B for Example 1's curve (Sect. 5, Example 3) ----------------------------

std::vector<double> example1_singular_values(double x0, double y0) {
  // The paper's B is built from the unnormalized p = x_num - x0 x_den, q = y_num - y0 y_den.
  const Curve c = example1();
  std::vector<double> p(5), q(5), b(16), sigma(4), v(16);
  for (int i = 0; i < 5; ++i) {
    p[i] = c.x_num[i] - x0 * c.x_den[i];
    q[i] = c.y_num[i] - y0 * c.y_den[i];
  }
  bezout_matrix(p, q, b);
  kernels::symmetric_svd(4, b, sigma, v);
  return sigma;
}

TEST(PaperExamples, Example3SingularValues) {
  const std::vector<double> sigma = example1_singular_values(3.5542169, 2.8148148);
  const double paper[4] = {4.212191730287018, 2.075444341475023, 5.981428444978487e-01, 3.357757839963324e-08};
  for (int k = 0; k < 3; ++k) EXPECT_LE(relative_error(sigma[k], paper[k]), 1e-12) << "sigma_" << k + 1;
  // sigma_4 ~ 8e-9 sigma_1: its absolute error ~ eps sigma_1 ~ 1e-15 makes ~3e-8 relative.
  // Measured 5.4e-8.
  EXPECT_LE(relative_error(sigma[3], paper[3]), 1e-6) << sigma[3];
  RecordProperty("sigma4_relative_error", sci(relative_error(sigma[3], paper[3])));
}

// At x0 = 1/2 the leading power coefficient 1 - 2 x0 of p vanishes (Sect. 4): nullity 2.
TEST(PaperExamples, DegreeDropSingularValues) {
  const std::vector<double> sigma = example1_singular_values(0.5, -3.0395517);
  EXPECT_LE(relative_error(sigma[0], 7.650996902942649e+01), 1e-12);
  EXPECT_LE(relative_error(sigma[1], 4.412324130498519e+01), 1e-12);
  // sigma_3 = 8.892019775556218e-09 in the paper, ~1e-10 sigma_1: absolute error ~ eps sigma_1.
  // Measured 1.1e-6 relative (= 1e-14 absolute, ~ eps sigma_1 / 2).
  EXPECT_LE(relative_error(sigma[2], 8.892019775556218e-09), 1e-5) << sigma[2];
  // sigma_4 is round-off (paper: 1.0e-15).
  EXPECT_LE(sigma[3], 1e-13 * sigma[0]);
  RecordProperty("sigma3_relative_error", sci(relative_error(sigma[2], 8.892019775556218e-09)));
}

// ---- the degree-drop point, end to end ------------------------------------------------------------

// Example 1 at P0 = (1/2, -3.0395517): x(t) = 1/2 <=> p-bar(t) = x_num(t) - x_den(t)/2 = 0
// (x_den = 1 + 2t^4 > 0), and Sect. 4's power form p-bar = 4 - x - 6t^2 + 8t^3 + (1 - 2x) t^4 at
// x = 1/2 is the cubic 8t^3 - 6t^2 + 3.5, with one real root, in (-1, 0). Found by exact
// bisection on dyadic rationals, to 2^-90.
mpq_class degree_drop_root() {
  auto f = [](const mpq_class& t) { return mpq_class(8 * t * t * t - 6 * t * t + q("7/2")); };
  mpq_class lo = -1, hi = 0;
  EXPECT_LT(f(lo), 0);
  EXPECT_GT(f(hi), 0);
  for (int i = 0; i < 90; ++i) {
    const mpq_class mid = (lo + hi) / 2;
    (f(mid) < 0 ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

TEST(PaperExamples, DegreeDropPointIsOnTheExtension) {
  const mpq_class root = degree_drop_root();
  const double t_true = exact::nearest_double(root);
  EXPECT_NEAR(t_true, -0.5746881074593174, 1e-15);  // the lead's independent (Python) value
  const exact::RationalCurve c = exact_curve(example1());
  // The exact curve point there is (1/2, y(t_true)); the paper's P0 has 8 digits of y.
  const auto exact_point = c.point(root);
  EXPECT_LT(exact::abs(exact_point[0] - q("1/2")), q("1/1000000000000"));
  const std::array<mpq_class, 2> p0{q("1/2"), q("-30395517/10000000")};
  const double dist = std::sqrt(squared_distance(exact_point, p0).get_d());
  const mpq_class diag2 = squared_diagonal(c);
  const double tolerance = kDefaultRelativeTolerance * std::sqrt(diag2.get_d());
  ASSERT_LT(dist, tolerance) << "the paper's point is on the curve within the default tolerance";

  const InversionPlan plan = make_plan(example1());
  EXPECT_NEAR(plan.diagonal(), std::sqrt(diag2.get_d()), 1e-15 * plan.diagonal());

  // Refined (default): the nearest point of the extension is within ~2 dist / |P'| of t_true
  // (measured error 3.1e-10, bound 9.9e-10).
  const auto tangent = c.tangent(root);
  const double speed = std::hypot(tangent[0].get_d(), tangent[1].get_d());
  const PointResult r = invert_point(plan, {0.5, -3.0395517});
  EXPECT_EQ(r.status, Status::outside_segment) << to_string(r.status) << " " << r.reason;
  EXPECT_LE(std::abs(r.t - t_true), 2.5 * dist / speed) << r.t;
  EXPECT_LE(r.residual, dist + 1e-14 * plan.diagonal());  // + the rounding of P(t)

  // Algebraic (the paper's Sect. 4 fallback: Sylvester at the true degrees). P0 is 7.6e-9 off
  // the curve, so the algebraic parameter is only as good as that allows: of the order of
  // dist / |P'| = 4.0e-10 like the geometric one (measured error 3.8e-10).
  const PointResult a = invert_point(plan, {0.5, -3.0395517}, kAlgebraic);
  EXPECT_TRUE(a.path == Path::sylvester || a.path == Path::bezout_pair) << to_string(a.path);
  EXPECT_EQ(a.status, Status::outside_segment) << to_string(a.status) << " " << a.reason;
  EXPECT_LE(std::abs(a.t - t_true), 5.0 * dist / speed) << a.t;
  RecordProperty("refined_t_error", sci(std::abs(r.t - t_true)));
  RecordProperty("algebraic_t_error", sci(std::abs(a.t - t_true)));
  RecordProperty("algebraic_path", to_string(a.path));
  RecordProperty("t_bound", sci(2.5 * dist / speed));
}

// ---- refined inversion of the printed points ------------------------------------------------------

struct RefinedCase {
  const char* name;
  Curve curve;
  exact::RationalCurve exact_curve;
  Point p0;                  // as printed
  std::array<mpq_class, 2> p0_exact;
  mpq_class t_exact;         // the parameter the printed point approximates
};

void check_refined(const RefinedCase& k) {
  SCOPED_TRACE(k.name);
  const auto exact_point = k.exact_curve.point(k.t_exact);
  const mpq_class d2 = squared_distance(exact_point, k.p0_exact);
  const mpq_class diag2 = squared_diagonal(k.exact_curve);
  // On the curve within the tolerance iff the nearest point is; the distance to P(t_exact) bounds
  // the nearest distance from above, so dist(P0, P(t_exact)) <= tol decides `ok` exactly.
  // (tol^2 = 1e-12 diag^2 compared in rationals.)
  const bool within = d2 <= q("1/1000000000000") * diag2;
  ASSERT_TRUE(within) << "every printed point is within 1e-6 diag; otherwise the test cannot decide";
  const double dist = std::sqrt(d2.get_d());

  const InversionPlan plan = make_plan(k.curve);
  ASSERT_TRUE(plan.usable()) << plan.reason();
  EXPECT_NEAR(plan.diagonal(), std::sqrt(diag2.get_d()), 1e-15 * plan.diagonal());
  const PointResult r = invert_point(plan, k.p0);
  EXPECT_EQ(r.status, Status::ok) << to_string(r.status) << " " << r.reason;
  // The nearest point P(t*) is at most dist from P0, hence at most 2 dist from P(t_exact):
  // |t* - t_exact| <~ 2 dist / |P'(t_exact)| (the curves are nearly straight at this scale).
  const auto tangent = k.exact_curve.tangent(k.t_exact);
  const double speed = std::hypot(tangent[0].get_d(), tangent[1].get_d());
  const double t_exact = k.t_exact.get_d();
  EXPECT_LE(std::abs(r.t - t_exact), 2.5 * dist / speed) << r.t;
  // Refinement finds the nearest point: no farther than P(t_exact), up to the rounding of P(t).
  EXPECT_LE(r.residual, dist + 1e-14 * plan.diagonal());
  // And it is a stationary point of the distance, (P(t) - P0) . P'(t) = 0, up to the rounding of
  // P(t) (~eps x the curve's size): Newton runs to full precision. Measured cos(angle) 1.7e-10,
  // 5.4e-8 (Example 3, residual ~3.6e-8, where the rounding of P(t) dominates), 3.0e-10.
  const mpq_class t(r.t);
  const auto pt = k.exact_curve.point(t), dp = k.exact_curve.tangent(t);
  const double dot = mpq_class((pt[0] - k.p0_exact[0]) * dp[0] + (pt[1] - k.p0_exact[1]) * dp[1]).get_d();
  const double dpn = std::hypot(dp[0].get_d(), dp[1].get_d());
  EXPECT_LE(std::abs(dot), (1e-8 * r.residual + 1e-14 * plan.diagonal()) * dpn) << "(P(t) - P0) . P'(t)";
  ::testing::Test::RecordProperty(std::string(k.name) + "_cos_angle", sci(std::abs(dot) / (r.residual * dpn)));
  ::testing::Test::RecordProperty(std::string(k.name) + "_t_error", sci(std::abs(r.t - t_exact)));
  ::testing::Test::RecordProperty(std::string(k.name) + "_t_bound", sci(2.5 * dist / speed));
}

TEST(PaperExamples, RefinedPrintedPointsAreOnTheCurve) {
  // Example 2: P0 approximates P(1/7) (five digits).
  check_refined({"example2", example2(), exact_curve(example2()), {8.50665, 14.3420},
                 {q("850665/100000"), q("143420/10000")}, q("1/7")});
  // Example 3: P0 approximates P(1/3) = (295/83, 76/27) (seven digits).
  check_refined({"example3", example1(), exact_curve(example1()), {3.5542169, 2.8148148},
                 {q("35542169/10000000"), q("28148148/10000000")}, q("1/3")});
  // Example 4: P0 approximates P(1/3) = (8/3, 109/45) (five digits).
  check_refined({"example4", example4(), exact_curve(example4()), {2.66667, 2.42222},
                 {q("266667/100000"), q("242222/100000")}, q("1/3")});
}

}  // namespace
}  // namespace bezinv
