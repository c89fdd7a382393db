// The Bernstein-Bezout matrix (paper Sect. 2.1) against two exact references that share no code:
// the paper's own recurrence run in rationals, and the matrix solved from its defining identity.
// Also: why the engine does not run that recurrence in double over the whole matrix, Theorem 2,
// and the plan's affine combination B(u0, v0) = B0 - u0 Bx - v0 By + u0 v0 Bxy (plan.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bezinv/bernstein.hpp"
#include "plan_data.hpp"
#include "bezinv/bezout.hpp"
#include "bezinv/curve.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/plan.hpp"
#include "support/exact.hpp"
#include "support/measure.hpp"
#include "support/random_polynomial.hpp"

namespace bezinv {
namespace {

using test_support::kEps;
using test_support::random_coefficients;
using test_support::sci;

std::vector<double> engine_bezout(const std::vector<double>& p, const std::vector<double>& q) {
  const std::size_t n = p.size() - 1;
  std::vector<double> b(n * n, std::nan(""));
  bezout_matrix(p, q, b);
  return b;
}

// max_ij |b_ij - e_ij| / max_ij |e_ij|, the error measure of bezout.hpp's accuracy claim.
double relative_error(const std::vector<double>& b, const exact::Matrix& e) {
  mpq_class worst = 0;
  for (std::size_t k = 0; k < b.size(); ++k) worst = std::max(worst, exact::abs(mpq_class(b[k]) - e.a[k]));
  const mpq_class scale = exact::max_abs(e);
  return scale == 0 ? worst.get_d() : mpq_class(worst / scale).get_d();
}

// The recurrence exactly as printed (Sect. 2.1, Bini & Gemignani's algorithm in Maple), in
// double, over the whole matrix. Kept here, not in the engine, to document why the engine
// computes only the lower triangle.
std::vector<double> printed_recurrence_in_double(const std::vector<double>& p, const std::vector<double>& q) {
  const int n = static_cast<int>(p.size()) - 1;
  std::vector<double> b(static_cast<std::size_t>(n) * n);
  auto B = [&](int i, int j) -> double& { return b[static_cast<std::size_t>(i - 1) * n + (j - 1)]; };
  const double dn = n;
  for (int i = 1; i <= n; ++i) B(i, 1) = (dn / i) * (p[i] * q[0] - p[0] * q[i]);
  for (int j = 1; j <= n - 1; ++j) B(n, j + 1) = (dn / (n - j)) * (p[n] * q[j] - p[j] * q[n]);
  for (int j = 1; j <= n - 1; ++j)
    for (int i = 1; i <= n - 1; ++i)
      B(i, j + 1) = (dn * dn / (i * (dn - j))) * (p[i] * q[j] - p[j] * q[i]) +
                    ((j * (dn - i)) / (i * (dn - j))) * B(i + 1, j);
  return b;
}

// Largest error over the matrix, relative to max |B|, measured on all 30 degrees x 4 draws below:
// worst 3.3e-16. The bound keeps a factor ~4 (bezout.hpp promises ~4e-16).
constexpr double kBezoutRelativeError = 1.2e-15;

TEST(BezoutMatrix, AgreesWithExactRecurrenceForEveryDegree) {
  std::mt19937_64 rng(20240611);
  double worst = 0.0;
  for (int n = 1; n <= 30; ++n) {
    for (int draw = 0; draw < 4; ++draw) {
      // Draw 3 mixes magnitudes (coefficients spanning 1e-3..1e3), like p = X - x0 W far from 0.
      std::vector<double> p = random_coefficients(rng, n), q = random_coefficients(rng, n);
      if (draw == 3) {
        for (double& v : p) v *= std::pow(10.0, datasets::uniform(rng, -3.0, 3.0));
        for (double& v : q) v *= std::pow(10.0, datasets::uniform(rng, -3.0, 3.0));
      }
      const exact::Matrix reference = exact::bezout_recurrence(exact::to_exact(p), exact::to_exact(q));
      const double err = relative_error(engine_bezout(p, q), reference);
      worst = std::max(worst, err);
      EXPECT_LE(err, kBezoutRelativeError) << "n = " << n << ", draw " << draw;
    }
  }
  RecordProperty("worst_relative_error", sci(worst));
}

TEST(BezoutMatrix, IsSymmetricBitForBit) {
  std::mt19937_64 rng(7);
  for (int n = 1; n <= 32; ++n) {
    const std::vector<double> b = engine_bezout(random_coefficients(rng, n), random_coefficients(rng, n));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < i; ++j) ASSERT_EQ(b[i * n + j], b[j * n + i]) << "n = " << n << " (" << i << "," << j << ")";
  }
}

// The two exact references are independent: one is the paper's recurrence, the other solves the
// identity (p(t)q(s) - p(s)q(t))/(t-s) = sum b_ij beta_i(t) beta_j(s) at n x n node pairs.
// Their exact equality confirms both the printed recurrence and the sign/scale convention.
TEST(BezoutMatrix, PrintedRecurrenceSatisfiesTheDefinitionExactly) {
  std::mt19937_64 rng(11);
  for (int n = 1; n <= 30; ++n) {
    const exact::Poly p = exact::to_exact(random_coefficients(rng, n)), q = exact::to_exact(random_coefficients(rng, n));
    const exact::Matrix a = exact::bezout_recurrence(p, q), b = exact::bezout_from_definition(p, q);
    EXPECT_TRUE(a == b) << "n = " << n;
    // And the engine is close to the definition too (not only to the recurrence).
    const double err = relative_error(engine_bezout(exact::to_double(p), exact::to_double(q)), b);
    EXPECT_LE(err, kBezoutRelativeError) << "n = " << n;
  }
}

// Hand-derived small case: n = 1 gives (p(t)q(s) - p(s)q(t))/(t - s) = p1 q0 - p0 q1.
TEST(BezoutMatrix, DegreeOneByHand) {
  const std::vector<double> p{2.0, 5.0}, q{-1.0, 3.0};
  EXPECT_EQ(engine_bezout(p, q)[0], 5.0 * -1.0 - 2.0 * 3.0);
}

// The multiplier j(n-i)/(i(n-j)) of the upper triangle reaches (n-1)^2, so rounding grows
// geometrically: at n = 20 the printed recurrence in double is off by 2.9e-8 .. 2.5e-7 relative to
// max|B| over these five draws (measured; other seeds gave 4e-9 .. 5e-7), while the engine stays
// at round-off on the same input.
TEST(BezoutMatrix, PrintedRecurrenceInDoubleIsInaccurateAtDegree20) {
  std::mt19937_64 rng(2004);
  const int n = 20;
  for (int draw = 0; draw < 5; ++draw) {
    const std::vector<double> p = random_coefficients(rng, n), q = random_coefficients(rng, n);
    const exact::Matrix reference = exact::bezout_recurrence(exact::to_exact(p), exact::to_exact(q));
    const double printed = relative_error(printed_recurrence_in_double(p, q), reference);
    const double engine = relative_error(engine_bezout(p, q), reference);
    EXPECT_GT(printed, 1e-9) << "draw " << draw;
    EXPECT_GT(printed, 1e4 * std::max(engine, 1e-17)) << "draw " << draw;
    EXPECT_LE(engine, kBezoutRelativeError) << "draw " << draw;
    RecordProperty("printed_error_draw_" + std::to_string(draw), sci(printed));
  }
}

// Theorem 2: a common root t0 of p and q puts beta^{(n-1)}(t0) in the null space of B.
// p = n (t - t0) r1 and q = n (t - t0) r2 with integer r1, r2 and a dyadic t0: the Bernstein
// coefficients n p_i = i (1 - t0) r1_{i-1} - (n - i) t0 r1_i are then exact in double, so the
// engine's input has the common root exactly and any residual is the engine's rounding.
TEST(BezoutMatrix, CommonRootGivesNullVector) {
  std::mt19937_64 rng(3);
  const std::array<double, 7> roots{0.0, 0.125, 0.5, 0.6875, 1.0, -0.5, 1.75};
  double worst = 0.0;
  for (int n = 2; n <= 30; ++n) {
    for (double t0 : roots) {
      exact::Poly r1(n), r2(n);
      for (auto& v : r1) v = datasets::uniform_int(rng, -40, 40);
      for (auto& v : r2) v = datasets::uniform_int(rng, -40, 40);
      const exact::Poly linear{mpq_class(-t0) * n, mpq_class(1 - t0) * n};
      const exact::Poly p = exact::product(linear, r1), q = exact::product(linear, r2);
      ASSERT_EQ(exact::bernstein_value(p, mpq_class(t0)), 0);
      const std::vector<double> pd = exact::to_double(p), qd = exact::to_double(q);
      ASSERT_TRUE(exact::to_exact(pd) == p) << "construction must be exact in double";
      const std::vector<double> b = engine_bezout(pd, qd);
      const std::vector<double> beta = exact::to_double(exact::bernstein_basis(n - 1, mpq_class(t0)));
      double max_b = 0.0, max_beta = 0.0, max_residual = 0.0;
      for (double v : b) max_b = std::max(max_b, std::abs(v));
      if (max_b == 0.0) continue;  // r1 and r2 proportional (happens at n = 2): B = 0 exactly
      for (double v : beta) max_beta = std::max(max_beta, std::abs(v));
      for (int i = 0; i < n; ++i) {
        long double s = 0.0L;  // long double so the check adds little error of its own
        for (int j = 0; j < n; ++j) s += static_cast<long double>(b[i * n + j]) * beta[j];
        max_residual = std::max(max_residual, static_cast<double>(std::fabs(s)));
      }
      // |B beta(t0)| relative to |B| |beta(t0)| (infinity norms): with B correct to ~eps|B|,
      // the residual is ~n eps. Measured worst 1.0e-16 (n <= 30, t0 in and outside [0,1]).
      const double rel = max_residual / (max_b * max_beta);
      worst = std::max(worst, rel);
      EXPECT_LE(rel, 5e-16) << "n = " << n << ", t0 = " << t0;
    }
  }
  RecordProperty("worst_relative_residual", sci(worst));
}

// ---- the plan's affine combination ------------------------------------------------------------

// A datasets_gen random curve of the kind, scaled by 10 and moved to (120, -45): far from the
// origin on purpose, since the plan normalizes and B(u0, v0) must not depend on where the curve is.
// (x_num + c x_den) / x_den = x + c for every kind, each denominator its own.
Curve random_curve(std::mt19937_64& rng, CurveKind kind, int n) {
  Curve c = datasets::random_curve(kind, n, rng);
  for (std::size_t i = 0; i < c.x_num.size(); ++i) {
    c.x_num[i] = 10.0 * c.x_num[i] + 120.0 * c.x_den[i];
    c.y_num[i] = 10.0 * c.y_num[i] - 45.0 * c.y_den[i];
  }
  return c;
}

// B(u0, v0) assembled from the plan's four matrices equals the Bezout matrix of
// p = x_num - u0 x_den, q = y_num - v0 y_den formed directly (bilinearity + antisymmetry, plan.hpp).
TEST(BezoutAt, MatchesDirectBezoutMatrixForEveryKind) {
  std::mt19937_64 rng(99);
  double worst_direct = 0.0, worst_exact = 0.0;
  for (CurveKind kind : {CurveKind::bezier, CurveKind::rational_bezier, CurveKind::rational}) {
    for (int n = 1; n <= 20; ++n) {
      const Curve curve = random_curve(rng, kind, n);
      const InversionPlan plan = make_plan(curve);
      ASSERT_TRUE(plan.usable()) << to_string(kind) << " n = " << n << ": " << plan.reason();
      const int m = plan.degree();
      ASSERT_EQ(static_cast<int>(bezinv::detail::plan_data(plan).x_num.size()), m + 1);
      for (int trial = 0; trial < 3; ++trial) {
        // Near the curve (in and slightly outside the segment), where B is nearly singular.
        const auto xy = curve.point(datasets::uniform(rng, -0.1, 1.1));
        const auto uv = bezinv::detail::plan_data(plan).normalize(xy[0] + datasets::uniform(rng, -1e-3, 1e-3),
                                       xy[1] + datasets::uniform(rng, -1e-3, 1e-3));
        std::vector<double> at(static_cast<std::size_t>(m) * m, std::nan(""));
        bezinv::detail::bezout_at(bezinv::detail::plan_data(plan), uv[0], uv[1], at);

        std::vector<double> p(m + 1), q(m + 1);
        exact::Poly pe(m + 1), qe(m + 1);
        for (int i = 0; i <= m; ++i) {
          p[i] = bezinv::detail::plan_data(plan).x_num[i] - uv[0] * bezinv::detail::plan_data(plan).x_den[i];
          q[i] = bezinv::detail::plan_data(plan).y_num[i] - uv[1] * bezinv::detail::plan_data(plan).y_den[i];
          pe[i] = mpq_class(bezinv::detail::plan_data(plan).x_num[i]) - mpq_class(uv[0]) * mpq_class(bezinv::detail::plan_data(plan).x_den[i]);
          qe[i] = mpq_class(bezinv::detail::plan_data(plan).y_num[i]) - mpq_class(uv[1]) * mpq_class(bezinv::detail::plan_data(plan).y_den[i]);
        }
        const std::vector<double> direct = engine_bezout(p, q);
        const exact::Matrix reference = exact::bezout_recurrence(pe, qe);
        // Scale: the size of the terms of the affine combination, max_ij (|B0| + |u0||Bx| +
        // |v0||By| + |u0 v0||Bxy|). Not max|B(u0,v0)|: the points lie near the curve, where B is
        // nearly singular, and for n = 1 the 1 x 1 matrix B itself is ~0 (relative error of a
        // vanishing quantity means nothing). Both computations round at this scale.
        double scale = 0.0, diff = 0.0, diff_exact = 0.0;
        for (std::size_t k = 0; k < direct.size(); ++k) {
          const double bxy = bezinv::detail::plan_data(plan).Bxy.empty() ? 0.0 : std::abs(bezinv::detail::plan_data(plan).Bxy[k]);
          scale = std::max(scale, std::abs(bezinv::detail::plan_data(plan).B0[k]) + std::abs(uv[0] * bezinv::detail::plan_data(plan).Bx[k]) +
                                      std::abs(uv[1] * bezinv::detail::plan_data(plan).By[k]) + std::abs(uv[0] * uv[1]) * bxy);
          diff = std::max(diff, std::abs(direct[k] - at[k]));
          diff_exact = std::max(diff_exact, exact::abs(mpq_class(at[k]) - reference.a[k]).get_d());
        }
        const double rel = diff / scale, rel_exact = diff_exact / scale;
        worst_direct = std::max(worst_direct, rel);
        worst_exact = std::max(worst_exact, rel_exact);
        // Measured worst: 1.4e-15 against the direct matrix, 2.3e-16 against the exact one
        // (the direct matrix rounds p and q first, so it is the less accurate of the two).
        EXPECT_LE(rel, 5e-15) << to_string(kind) << " n = " << n;
        EXPECT_LE(rel_exact, 1e-15) << to_string(kind) << " n = " << n;
      }
    }
  }
  RecordProperty("worst_vs_direct", sci(worst_direct));
  RecordProperty("worst_vs_exact", sci(worst_exact));
}

// plan.hpp: translation and rotation leave B unchanged (Bez is alternating, det R = 1) and the
// scale multiplies it by 1/scale^2; plan.cpp also divides each numerator/denominator pair by its
// largest denominator coefficient (P unchanged, B divided by max|x_den| max|y_den|). What the
// method needs is that B(u0, v0) is proportional to the Bezout matrix of the curve as given,
// p = x_num - x0 x_den, q = y_num - y0 y_den (same null vectors, same sigma ratios), with the
// constant scale^2 max|x_den| max|y_den|. Checked here against that matrix computed exactly.
TEST(BezoutAt, NormalizationOnlyScalesB) {
  std::mt19937_64 rng(101);
  double worst = 0.0;
  for (CurveKind kind : {CurveKind::bezier, CurveKind::rational_bezier, CurveKind::rational}) {
    for (int n = 1; n <= 20; ++n) {
      const Curve curve = random_curve(rng, kind, n);
      const InversionPlan plan = make_plan(curve);
      ASSERT_EQ(plan.degree(), n) << "a random curve is not degree-elevated";
      double xs = 0.0, ys = 0.0;
      for (int i = 0; i <= n; ++i) {
        xs = std::max(xs, std::abs(curve.x_den[i]));
        ys = std::max(ys, std::abs(curve.y_den[i]));
      }
      const mpq_class factor = mpq_class(bezinv::detail::plan_data(plan).scale) * mpq_class(bezinv::detail::plan_data(plan).scale) * mpq_class(xs) * mpq_class(ys);
      for (int trial = 0; trial < 3; ++trial) {
        const auto xy = curve.point(datasets::uniform(rng, -0.1, 1.1));
        const double x0 = xy[0] + datasets::uniform(rng, -1e-3, 1e-3), y0 = xy[1] + datasets::uniform(rng, -1e-3, 1e-3);
        const auto uv = bezinv::detail::plan_data(plan).normalize(x0, y0);
        std::vector<double> at(static_cast<std::size_t>(n) * n);
        bezinv::detail::bezout_at(bezinv::detail::plan_data(plan), uv[0], uv[1], at);
        exact::Poly p(n + 1), q(n + 1);
        for (int i = 0; i <= n; ++i) {
          p[i] = mpq_class(curve.x_num[i]) - mpq_class(x0) * mpq_class(curve.x_den[i]);
          q[i] = mpq_class(curve.y_num[i]) - mpq_class(y0) * mpq_class(curve.y_den[i]);
        }
        const exact::Matrix reference = exact::bezout_recurrence(p, q);
        // Scale: translating and rotating the input rounds at the size of the untranslated terms,
        // M_x = max_i |x_num_i| + |x0| |x_den_i| (likewise M_y), which the centring cannot undo;
        // an entry of B is a sum of ~n products p_i q_j, so its rounding is ~n eps M_x M_y.
        double mx = 0.0, my = 0.0;
        for (int i = 0; i <= n; ++i) {
          mx = std::max(mx, std::abs(curve.x_num[i]) + std::abs(x0 * curve.x_den[i]));
          my = std::max(my, std::abs(curve.y_num[i]) + std::abs(y0 * curve.y_den[i]));
        }
        double diff = 0.0;
        for (std::size_t k = 0; k < at.size(); ++k)
          diff = std::max(diff, exact::abs(mpq_class(at[k]) * factor - reference.a[k]).get_d());
        const double rel = diff / (n * mx * my * kEps);
        worst = std::max(worst, rel);
        // Measured worst 0.20 (in units of n eps M_x M_y).
        EXPECT_LE(rel, 1.0) << to_string(kind) << " n = " << n;
      }
    }
  }
  RecordProperty("worst_in_n_eps_MxMy", sci(worst));
}

// For a rational Bezier curve the denominators coincide, Bez(W, W) = 0, and B is affine.
TEST(BezoutAt, CommonDenominatorMakesBxyVanish) {
  std::mt19937_64 rng(5);
  for (int n = 1; n <= 12; ++n) {
    const InversionPlan plan = make_plan(random_curve(rng, CurveKind::rational_bezier, n));
    EXPECT_TRUE(bezinv::detail::plan_data(plan).common_denominator);
    for (double v : bezinv::detail::plan_data(plan).Bxy) EXPECT_EQ(v, 0.0) << "n = " << n;
  }
}

}  // namespace
}  // namespace bezinv
