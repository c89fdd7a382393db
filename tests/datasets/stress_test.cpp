// The accuracy stress tool's parts (datasets/high_precision_nearest.hpp, datasets/stress.hpp): the
// high-precision truth against exact rational arithmetic (GMP), and the tally against constructed
// answers of every kind it must tell apart.
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/datasets/high_precision_nearest.hpp"
#include "bezinv/datasets/off_curve_points.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/reference_evaluation.hpp"
#include "bezinv/datasets/self_intersection.hpp"
#include "bezinv/datasets/stress.hpp"
#include "bezinv/datasets/translation.hpp"

namespace bezinv::datasets {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// sum_i C(n,i) (1-t)^(n-i) t^i c_i, exactly.
mpq_class bernstein_exact(const std::vector<double>& c, const mpq_class& t) {
  const int n = static_cast<int>(c.size()) - 1;
  mpq_class sum = 0;
  for (int i = 0; i <= n; ++i) {
    mpz_class binomial;
    mpz_bin_uiui(binomial.get_mpz_t(), n, i);
    mpq_class term = mpq_class(binomial) * mpq_class(c[i]);
    for (int k = 0; k < n - i; ++k) term *= 1 - t;
    for (int k = 0; k < i; ++k) term *= t;
    sum += term;
  }
  return sum;
}

// The derivative's coefficients: n (c_{i+1} - c_i), in doubles exactly for the small integers used
// here, or as exact rationals in general (below).
mpq_class bernstein_derivative_exact(const std::vector<double>& c, const mpq_class& t) {
  const int n = static_cast<int>(c.size()) - 1;
  mpq_class sum = 0;
  for (int i = 0; i < n; ++i) {
    mpz_class binomial;
    mpz_bin_uiui(binomial.get_mpz_t(), n - 1, i);
    mpq_class term = mpq_class(binomial) * n * (mpq_class(c[i + 1]) - mpq_class(c[i]));
    for (int k = 0; k < n - 1 - i; ++k) term *= 1 - t;
    for (int k = 0; k < i; ++k) term *= t;
    sum += term;
  }
  return sum;
}

// f(t) = (P(t) - p) . P'(t), exactly: x = N / D, x' = (N' D - N D') / D^2.
mpq_class stationarity_exact(const Curve& curve, Point p, const mpq_class& t, double z = 0.0) {
  auto coordinate = [&](const std::vector<double>& num, const std::vector<double>& den, double p0) -> mpq_class {
    const mpq_class N = bernstein_exact(num, t), D = bernstein_exact(den, t);
    const mpq_class dN = bernstein_derivative_exact(num, t), dD = bernstein_derivative_exact(den, t);
    const mpq_class value = N / D, slope = (dN * D - N * dD) / (D * D);
    return (value - mpq_class(p0)) * slope;
  };
  mpq_class f = coordinate(curve.x_num, curve.x_den, p.x) + coordinate(curve.y_num, curve.y_den, p.y);
  if (curve.dimension() == 3) f += coordinate(curve.z_num, curve.z_den, z);
  return f;
}

// A polynomial curve with small integer control points at t = k / 64: P(t) has denominator
// 64^n and fits a double exactly (n <= 8), so the point is on the curve and its truth is t itself.
TEST(HighPrecisionNearest, APointExactlyOnTheCurveHasItsOwnParameter) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> coordinate(-7, 7);
  for (int n = 1; n <= 8; ++n) {
    std::vector<std::array<double, 2>> control(n + 1);
    for (auto& p : control) p = {double(coordinate(rng)), double(coordinate(rng))};
    control.back() = {8.0, 8.0};  // not all coincident
    const Curve curve = Curve::bezier("c", control);
    for (int k = 1; k < 64; k += 5) {
      mpq_class t(k, 64);
      t.canonicalize();
      mpq_class x = bernstein_exact(curve.x_num, t), y = bernstein_exact(curve.y_num, t);
      x.canonicalize();
      y.canonicalize();
      const Point p{x.get_d(), y.get_d()};
      ASSERT_EQ(mpq_class(p.x), x) << "the point must be exact for this test";
      ASSERT_EQ(mpq_class(p.y), y);
      if (bernstein_derivative_exact(curve.x_num, t) == 0 && bernstein_derivative_exact(curve.y_num, t) == 0)
        continue;  // a stationary point of the curve: no well-defined Newton
      const HighPrecisionNearest h = high_precision_nearest(curve, p, t.get_d() + 1e-7, false);
      ASSERT_TRUE(h.converged) << "n " << n << " t " << t.get_d();
      EXPECT_EQ(h.t, t.get_d()) << "n " << n;
      EXPECT_LE(std::abs(h.t_low), 1e-30) << "n " << n << " t " << t.get_d();
      EXPECT_LE(h.distance, 1e-28) << "n " << n << " t " << t.get_d();
    }
  }
}

// Off the curve (normal offsets on random curves of every kind): the exact f changes sign across
// t_hi + t_lo within 2^-90, far below a double's ulp of t, so the truth is good to ~30 bits more
// than the engine can be.
TEST(HighPrecisionNearest, TheExactStationarityChangesSignAcrossTheTruth) {
  std::mt19937_64 rng(17);
  int checked = 0;
  for (CurveKind kind : {CurveKind::bezier, CurveKind::rational_bezier, CurveKind::rational})
    for (int n : {2, 3, 5, 8}) {
      const Curve curve = random_curve(kind, n, rng, ControlPolygon::perturbed_arc);
      const CurveSampling sampling(curve);
      for (const KnownPoint& k : normal_offset_points(sampling, 6, 1e-8, 1e-2, rng)) {
        if (k.t == 0.0 || k.t == 1.0) continue;  // an end: not a stationary point
        const HighPrecisionNearest h = high_precision_nearest(curve, k.point, k.t, true);
        ASSERT_TRUE(h.converged);
        const mpq_class t = mpq_class(h.t) + mpq_class(h.t_low), delta = mpq_class(std::ldexp(1.0, -90));
        const int below = sgn(stationarity_exact(curve, k.point, t - delta));
        const int above = sgn(stationarity_exact(curve, k.point, t + delta));
        EXPECT_LT(below, 0) << to_string(kind) << " n " << n << " t " << h.t;
        EXPECT_GT(above, 0) << to_string(kind) << " n " << n << " t " << h.t;
        // And the generator's long double answer agrees to its own precision.
        EXPECT_NEAR(h.t, k.t, 1e-15);
        ++checked;
      }
    }
  EXPECT_GE(checked, 40);
}

// Every family's truths, on a sample of its rows, against a second computation: exact rational
// arithmetic says that the distance's derivative f = (P - p) . P' changes sign from - to + across
// each truth within an ulp (t_true is the 128-bit root rounded to double), so t_true is the
// parameter of a local minimum of the distance to the double input. (An end of the segment, the
// nearest point of an off-curve row there, is not a stationary point: skipped.)
TEST(StressRows, EveryFamilysTruthIsWhereTheExactDistanceHasAMinimum) {
  int checked = 0;
  for (Family family : kFamilies) {
    int family_checked = 0;
    for (CurveKind kind : {CurveKind::bezier, CurveKind::rational_bezier, CurveKind::rational})
      for (int degree : {3, 4}) {
        std::mt19937_64 rng(100 * static_cast<int>(family) + 10 * degree + static_cast<int>(kind));
        const auto curve = stress_curve(family, kind, degree, 0, rng);
        if (!curve) continue;
        const CurveSampling sampling(curve->curve);
        // The engine's curve: family space gives it the curve in space, and its rows a z.
        const Curve& given = curve->space ? *curve->space : curve->curve;
        for (const StressRow& r : stress_rows(family, *curve, sampling, 6, 1e-6, rng))
          for (double t : {r.t_true, r.t2_true}) {
            if (!std::isfinite(t) || t == 0.0 || t == 1.0) continue;
            const mpq_class below(std::nextafter(std::nextafter(t, -1e300), -1e300));
            const mpq_class above(std::nextafter(std::nextafter(t, 1e300), 1e300));
            const double z = std::isfinite(r.z) ? r.z : 0.0;
            EXPECT_LT(sgn(stationarity_exact(given, r.point, below, z)), 0) << to_string(family) << " t " << t;
            EXPECT_GT(sgn(stationarity_exact(given, r.point, above, z)), 0) << to_string(family) << " t " << t;
            ++family_checked;
          }
      }
    EXPECT_GE(family_checked, 3) << to_string(family);
    checked += family_checked;
  }
  EXPECT_GE(checked, 100);
}

// The space family's rows are the plane's on_curve and noisy rows lifted, and a noisy row's truth
// is the nearest point of the segment, as in the plane (an off_curve answer's t): at a tolerance
// loose enough that rows near an end are ambiguous (ok, outside_segment or off_curve right), the
// truth of an off_curve row stays on the segment, not on the extension beyond the end.
TEST(StressRows, ASpaceRowOffTheCurveHasTheNearestPointOfTheSegmentAsItsTruth) {
  int off_curve = 0, at_an_end = 0;
  for (int degree : {2, 3, 5})
    for (int index = 0; index < 4; ++index) {
      std::mt19937_64 rng(9090 + 10 * degree + index);
      const auto curve = stress_curve(Family::space, CurveKind::bezier, degree, index, rng);
      if (!curve) continue;
      const CurveSampling sampling(curve->curve);
      for (const StressRow& r : stress_rows(Family::space, *curve, sampling, 2000, 1e-4, rng)) {
        if (r.expected != Status::off_curve || !std::isfinite(r.t_true)) continue;
        ++off_curve;
        at_an_end += r.t_true == 0.0 || r.t_true == 1.0;
        EXPECT_GE(r.t_true, 0.0) << "degree " << degree << " curve " << index;
        EXPECT_LE(r.t_true, 1.0) << "degree " << degree << " curve " << index;
      }
    }
  EXPECT_GE(off_curve, 1000);
  EXPECT_GE(at_an_end, 5);  // rows whose nearest point of the segment is an end
}

StressRow row(Status expected, double t_true, unsigned also = 0) {
  StressRow r;
  r.point = {0.25, 0.5};
  r.expected = expected;
  r.acceptable = (1u << static_cast<unsigned>(expected)) | also;
  r.t_true = t_true;
  r.distance = 1e-3;
  r.bound = 1e-15;
  return r;
}

PointResult answer(Status status, double t, double residual = 1e-3) {
  PointResult r;
  r.status = status;
  r.t = t;
  r.residual = residual;
  return r;
}

// Every kind of answer the tally must tell apart, each counted where it belongs.
TEST(StressTally, CountsEachKindOfAnswerWhereItBelongs) {
  StressTally tally;
  tally.add(row(Status::ok, 0.5), answer(Status::ok, 0.5 + 1e-16), 1.0);            // right, within the bound
  tally.add(row(Status::ok, 0.5), answer(Status::ok, 0.5 + 1e-9), 1.0);             // right status, wrong t
  tally.add(row(Status::off_curve, 0.3), answer(Status::ok, 0.3), 1.0);             // wrong status
  tally.add(row(Status::off_curve, 0.3, 1u << static_cast<unsigned>(Status::ok)),  // ambiguous, answered ok
            answer(Status::ok, 0.7), 1.0);
  tally.add(row(Status::ok, 0.5), answer(Status::ok, kNaN), 1.0);                   // NaN t
  PointResult pair = answer(Status::double_point, 0.2);                              // no t2
  tally.add(row(Status::double_point, 0.2), pair, 1.0);
  tally.add(row(Status::ok, kNaN), answer(Status::ok, 0.5), 1.0);                   // no truth
  tally.add(row(Status::outside_segment, 1.2), answer(Status::failed, kNaN), 1.0);  // wrong status
  EXPECT_EQ(tally.rows, 8u);
  EXPECT_EQ(tally.wrong_status, 2u);
  EXPECT_EQ(tally.wrong[static_cast<int>(Status::off_curve)][static_cast<int>(Status::ok)], 1u);
  EXPECT_EQ(tally.wrong[static_cast<int>(Status::outside_segment)][static_cast<int>(Status::failed)], 1u);
  EXPECT_EQ(tally.ambiguous, 1u);
  EXPECT_EQ(tally.nan_t, 1u);
  EXPECT_EQ(tally.missing_t2, 1u);
  EXPECT_EQ(tally.no_truth, 1u);
  EXPECT_EQ(tally.confusion[static_cast<int>(Status::off_curve)][static_cast<int>(Status::ok)], 2u);
  // dt of the rows answered with their expected status: the two ok rows and the double point.
  ASSERT_EQ(tally.dt.size(), 3u);
  EXPECT_LE(tally.dt[0], 2e-16);  // 0.5 + 1e-16 is 0.5 + an ulp
  EXPECT_NEAR(tally.dt[1], 1e-9, 1e-16);
  EXPECT_NEAR(tally.dt_over_bound[1], 1e6, 1.0);
  EXPECT_EQ(tally.dt[2], 0.0);
}

TEST(StressQuantiles, NearestRankOfKnownValues) {
  std::vector<double> values;
  for (int i = 1000; i >= 1; --i) values.push_back(i);
  const Quantiles q = quantiles(values);
  EXPECT_EQ(q.p50, 500.0);
  EXPECT_EQ(q.p99, 990.0);
  EXPECT_EQ(q.p999, 999.0);
  EXPECT_EQ(q.max, 1000.0);
  EXPECT_TRUE(std::isnan(quantiles({}).max));
}

}  // namespace
}  // namespace bezinv::datasets

namespace bezinv::datasets {
namespace {

// Far from the origin the engine's tolerance has a floor of 4 ulps of the coordinates (4.9e-4 at
// 1e12, against the generators' isolation margin of 1e-4 diagonals): a point of one branch near a
// crossing may then be within the tolerance of the other branch too, and double_point is a right
// answer for it. The rows must say so, as measured here on a fine grid of the other branch.
TEST(StressRows, FarFromTheOriginAnotherBranchWithinTheToleranceMakesDoublePointRight) {
  std::mt19937_64 rng(23);
  const Curve crossing = with_self_intersection(CurveKind::bezier, 4, 0.3, 0.7, rng, ControlPolygon::perturbed_arc);
  StressCurve curve{translated(crossing, 1e12, 1e12), 0.3, 0.7, {}, {}, {}, {}};
  const CurveSampling sampling(curve.curve);
  const std::vector<StressRow> rows = stress_rows(Family::translated, curve, sampling, 1200, 1e-6, rng);
  const double ulp = std::nextafter(1e12, 2e12) - 1e12, tolerance = 4 * ulp;
  ASSERT_GT(tolerance, 1e-4 * sampling.diagonal());
  int near_other = 0;
  for (const StressRow& row : rows) {
    // The branches come near each other only around the crossing (a perturbed arc, one loop).
    const bool own_first = row.t_true < 0.5;  // branch 1 near t = 0.3, branch 2 near t = 0.7
    if (std::abs(row.t_true - (own_first ? 0.3 : 0.7)) > 0.02) continue;
    const double centre = own_first ? 0.7 : 0.3;
    Real nearest = std::numeric_limits<Real>::infinity();
    for (int k = -1000; k <= 1000; ++k) {
      const RealPoint p = reference_point(curve.curve, static_cast<Real>(centre + 0.03 * k / 1000.0));
      nearest = std::min(nearest, std::hypot(p.x - row.point.x, p.y - row.point.y));
    }
    if (nearest > 1.9 * tolerance) continue;  // (the grid's spacing is ~1e-5 of the diagonal)
    ++near_other;
    EXPECT_TRUE(row.acceptable & (1u << static_cast<unsigned>(Status::double_point)))
        << "t " << row.t_true << ": the other branch at " << static_cast<double>(nearest) << ", tolerance " << tolerance;
  }
  EXPECT_GT(near_other, 0) << "the test needs rows near the other branch";
}

}  // namespace
}  // namespace bezinv::datasets
