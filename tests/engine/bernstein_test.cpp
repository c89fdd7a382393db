// Bernstein-basis primitives (bernstein.hpp) against exact rational references (support/exact).
// The references take the power-basis route (expanding (1-t)^{n-i} t^i), so they check the
// engine's difference formulas and de Casteljau rather than repeat them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bezinv/bernstein.hpp"
#include "support/exact.hpp"
#include "support/measure.hpp"
#include "support/random_polynomial.hpp"

namespace bezinv {
namespace {

using test_support::kEps;
using test_support::random_coefficients;
using test_support::sci;

// Parameters in and outside [0,1], all doubles (hence exact rationals).
const std::vector<double> kParameters{0.0, 1.0, 0.5, 1.0 / 3.0, 0.1, 0.9, 0.999, 1e-3, -0.5, -0.125, 1.25, 1.7};

// |computed - exact| / scale, as a double.
double relative(double computed, const mpq_class& exact_value, const mpq_class& scale) {
  return mpq_class(exact::abs(mpq_class(computed) - exact_value) / scale).get_d();
}

// sum_i |c_i| |beta_i^{(n)}(t)|: the condition scale of evaluating p at t (in and outside [0,1]).
mpq_class evaluation_scale(const exact::Poly& c, const mpq_class& t) {
  const std::vector<mpq_class> beta = exact::bernstein_basis(static_cast<int>(c.size()) - 1, t);
  mpq_class s = 0;
  for (std::size_t i = 0; i < c.size(); ++i) s += exact::abs(c[i]) * exact::abs(beta[i]);
  return s;
}

TEST(Binomial, ExactWhereverTheValueFitsIn53Bits) {
  // bernstein.hpp: "exact for n <= 64 as long as it fits in 53 bits". A multiplicative formula
  // r = r * (n-k+i) / i loses that once r * (n-k+i) passes 2^53 even though C(n,k) itself fits
  // (first at n = 55); exact integer arithmetic or Pascal's rule in double (sums of exact
  // integers below 2^53 are exact) keeps it.
  const mpz_class limit = mpz_class(1) << 53;
  int checked = 0;
  for (int n = 0; n <= 64; ++n)
    for (int k = 0; k <= n; ++k) {
      const mpz_class c = exact::binomial(n, k);
      if (c > limit) continue;
      EXPECT_EQ(mpq_class(binomial(n, k)), mpq_class(c)) << "C(" << n << "," << k << ")";
      ++checked;
    }
  // Every C(n,k) with n <= 56 fits; the degrees bezinv uses (<= 32) are all in.
  EXPECT_GT(checked, 57 * 58 / 2);
}

TEST(BernsteinBasis, ValuesMatchExactAndSumToOne) {
  double worst_entry = 0.0, worst_sum = 0.0;
  for (int n = 0; n <= 32; ++n)
    for (double t : kParameters) {
      std::vector<double> beta(static_cast<std::size_t>(n) + 1, std::nan(""));
      bernstein_basis(n, t, beta);
      const std::vector<mpq_class> ref = exact::bernstein_basis(n, mpq_class(t));
      mpq_class abs_sum = 0;
      for (const auto& v : ref) abs_sum += exact::abs(v);
      double sum = 0.0;
      for (int i = 0; i <= n; ++i) {
        // beta_i^{(j)} = (1-t) beta_i^{(j-1)} + t beta_{i-1}^{(j-1)} adds two terms of one sign,
        // also outside [0,1] (for t < 0 both have the sign (-1)^i), and the product form has no
        // sums at all: either way each entry is accurate to about n eps relative.
        // Measured worst 0.37 (n+1) eps over n <= 32 and all t.
        const double e = ref[i] == 0 ? std::abs(beta[i]) : relative(beta[i], ref[i], exact::abs(ref[i]));
        worst_entry = std::max(worst_entry, e / ((n + 1) * kEps));
        EXPECT_LE(e, 2.0 * (n + 1) * kEps) << "n = " << n << " t = " << t << " i = " << i;
        sum += beta[i];
      }
      // Partition of unity, judged against sum |beta_i| = (|1-t| + |t|)^n (1 on [0,1]).
      // Measured worst 0.33 (n+1) eps.
      const double se = std::abs(sum - 1.0) / abs_sum.get_d();
      worst_sum = std::max(worst_sum, se / ((n + 1) * kEps));
      EXPECT_LE(se, 2.0 * (n + 1) * kEps) << "n = " << n << " t = " << t;
    }
  RecordProperty("worst_entry_in_n_eps", sci(worst_entry));
  RecordProperty("worst_sum_in_n_eps", sci(worst_sum));
}

TEST(BernsteinValue, DeCasteljauMatchesExactInAndOutsideTheInterval) {
  std::mt19937_64 rng(17);
  double worst = 0.0;
  for (int n = 0; n <= 32; ++n) {
    const std::vector<double> c = random_coefficients(rng, n);
    const exact::Poly ce = exact::to_exact(c);
    for (double t : kParameters) {
      const mpq_class tq(t);
      // de Casteljau's rounding is bounded by ~2n eps sum_i |c_i||beta_i(t)| (also when
      // extrapolating, where the weights are |1-t| and |t|). Measured worst 0.29 (n+1) eps.
      const double e = relative(bernstein_value(c, t), exact::bernstein_value(ce, tq), evaluation_scale(ce, tq));
      worst = std::max(worst, e / ((n + 1) * kEps));
      EXPECT_LE(e, 2.0 * (n + 1) * kEps) << "n = " << n << " t = " << t;
    }
  }
  RecordProperty("worst_in_n_eps", sci(worst));
}

TEST(BernsteinValue, ReproducesKnownPolynomial) {
  // t^2 = sum_{i>=2} C(i,2)/C(3,2) beta_i^{(3)}(t): coefficients (0, 0, 1/3, 1) at degree 3.
  const std::vector<double> c{0.0, 0.0, 1.0 / 3.0, 1.0};
  for (double t : {0.0, 0.25, 0.5, 2.0, -1.0}) EXPECT_NEAR(bernstein_value(c, t), t * t, 1e-14 * (1 + t * t)) << t;
}

TEST(BernsteinJet, DerivativesMatchExactDerivatives) {
  std::mt19937_64 rng(23);
  double worst[3] = {0.0, 0.0, 0.0};
  for (int n = 0; n <= 32; ++n) {
    const std::vector<double> c = random_coefficients(rng, n);
    const exact::Poly c0 = exact::to_exact(c), c1 = exact::derivative(c0), c2 = exact::derivative(c1);
    for (double t : kParameters) {
      const mpq_class tq(t);
      const BernsteinJet jet = bernstein_jet(c, t);
      // Each derivative is judged against the evaluation scale of its own coefficients, which is
      // how the error of a difference-then-de-Casteljau computation scales; plus the rounding of
      // forming the differences (c_{i+1} - c_i, times n or n(n-1)), which the scale of the
      // original coefficients times n^k bounds. Measured worst 0.41, 0.15, 0.22 (n+1) eps.
      const double got[3] = {jet.value, jet.first, jet.second};
      const exact::Poly* refs[3] = {&c0, &c1, &c2};
      for (int k = 0; k < 3; ++k) {
        mpq_class scale = evaluation_scale(*refs[k], tq) + evaluation_scale(c0, tq) * (k == 0 ? 0 : (k == 1 ? n : n * n));
        if (scale == 0) scale = 1;
        const double e = relative(got[k], exact::bernstein_value(*refs[k], tq), scale);
        worst[k] = std::max(worst[k], e / ((n + 1) * kEps));
        EXPECT_LE(e, 2.0 * (n + 1) * kEps) << "derivative " << k << " n = " << n << " t = " << t;
      }
    }
  }
  RecordProperty("worst_value_in_n_eps", sci(worst[0]));
  RecordProperty("worst_first_in_n_eps", sci(worst[1]));
  RecordProperty("worst_second_in_n_eps", sci(worst[2]));
}

TEST(PowerLeadingCoefficient, MatchesExactExpansion) {
  std::mt19937_64 rng(29);
  double worst = 0.0;
  for (int n = 0; n <= 32; ++n) {
    const std::vector<double> c = random_coefficients(rng, n);
    const exact::Poly ce = exact::to_exact(c);
    mpq_class bound = 0;
    for (int i = 0; i <= n; ++i) bound += mpq_class(exact::binomial(n, i)) * exact::abs(ce[i]);
    // The bound itself (sum of positive terms) is accurate to ~n eps relative.
    EXPECT_LE(relative(power_leading_bound(c), bound, bound), 2.0 * (n + 1) * kEps) << "n = " << n;
    // The alternating sum cancels; its error is relative to the bound, which is what
    // kDegreeDropRatio (1e-9) compares against. Measured worst 0.07 (n+1) eps, so a leading
    // coefficient that is exactly zero reads as at most ~1e-14 of the bound: far below 1e-9.
    const double e = relative(power_leading_coefficient(c), exact::power_leading_coefficient(ce), bound);
    worst = std::max(worst, e / ((n + 1) * kEps));
    EXPECT_LE(e, 0.5 * (n + 1) * kEps) << "n = " << n;
  }
  RecordProperty("worst_relative_to_bound_in_n_eps", sci(worst));
}

TEST(PowerLeadingCoefficient, VanishesAfterElevation) {
  // Paper Example 1: p = x_num - x0 x_den has leading coefficient 1 - 2 x0 (Sect. 4), zero at 1/2.
  const std::vector<double> xn{4, 4, 3, 3, 7}, xd{1, 1, 1, 1, 3};
  for (double x0 : {0.5, 3.0, -1.25}) {
    std::vector<double> p(5);
    for (int i = 0; i < 5; ++i) p[i] = xn[i] - x0 * xd[i];
    EXPECT_EQ(power_leading_coefficient(p), 1.0 - 2.0 * x0) << "x0 = " << x0;
  }
}

TEST(DegreeElevation, MatchesExactAndReductionUndoesIt) {
  std::mt19937_64 rng(31);
  double worst_elevate = 0.0, worst_round_trip = 0.0;
  for (int n = 1; n <= 30; ++n) {
    for (int draw = 0; draw < 4; ++draw) {
      const std::vector<double> c = random_coefficients(rng, n);
      std::vector<double> up(static_cast<std::size_t>(n) + 2, std::nan("")), back(static_cast<std::size_t>(n) + 1, std::nan(""));
      elevate_degree(c, up);
      const exact::Poly ref = exact::elevate(exact::to_exact(c), n + 1);
      double max_c = 0.0;
      for (double v : c) max_c = std::max(max_c, std::abs(v));
      for (int i = 0; i <= n + 1; ++i) {
        // Convex combination of two coefficients: a couple of roundings. Measured worst 1.6e-16.
        const double e = relative(up[i], ref[i], mpq_class(max_c));
        worst_elevate = std::max(worst_elevate, e);
        EXPECT_LE(e, 4.0 * kEps) << "n = " << n << " i = " << i;
      }
      reduce_degree(up, back);
      for (int i = 0; i <= n; ++i) {
        // Measured worst 4.5e-16 relative to max |c| (n <= 30).
        const double e = std::abs(back[i] - c[i]) / max_c;
        worst_round_trip = std::max(worst_round_trip, e);
        EXPECT_LE(e, 2e-15) << "n = " << n << " i = " << i;
      }
    }
  }
  RecordProperty("worst_elevate", sci(worst_elevate));
  RecordProperty("worst_round_trip", sci(worst_round_trip));
}

// Reduction of an exactly elevated polynomial (coefficients rounded once) recovers the exact
// lower-degree coefficients, and reduction of a polynomial whose power-basis degree really is
// lower (built in the power basis, exactly) finds them too.
TEST(DegreeReduction, RecoversExactLowerDegreeForm) {
  std::mt19937_64 rng(37);
  double worst = 0.0;
  for (int n = 2; n <= 30; ++n) {
    const exact::Poly low = exact::to_exact(random_coefficients(rng, n - 1));
    const std::vector<double> high = exact::to_double(exact::elevate(low, n));
    std::vector<double> back(static_cast<std::size_t>(n), std::nan(""));
    reduce_degree(high, back);
    double max_c = 0.0;
    for (const auto& v : low) max_c = std::max(max_c, std::abs(v.get_d()));
    for (int i = 0; i < n; ++i) {
      // Measured worst 2.4e-16 relative to max |c|.
      const double e = relative(back[i], low[i], mpq_class(max_c));
      worst = std::max(worst, e);
      EXPECT_LE(e, 2e-15) << "n = " << n << " i = " << i;
    }
  }
  RecordProperty("worst_relative", sci(worst));
}

}  // namespace
}  // namespace bezinv
