// The lane-batched inversion formula t = N / M (Implementation::formula_parameter), every available
// implementation, formula degrees 1..32, batch sizes around the vector widths and the kernel's
// groups of four vectors. Expected values are exact: N and M summed in rational arithmetic (GMP)
// at the point's frame coordinates, and t's error bounded by the sums' sizes. The NaNs come from
// construction: points beyond the formula's reach, NaN and infinite points, and points where M
// vanishes (its constant term chosen so). tests/engine/formula_path_test.cpp checks the
// kernel against the engine's scalar formula_parameter bit for bit.
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "bezinv/kernels/batch.hpp"
#include "support/bits.hpp"

namespace bezinv::kernels {
namespace {

using test_support::kNaN;
using test_support::same_bits;

constexpr double kFormulaEps = std::numeric_limits<double>::epsilon();
constexpr double kFormulaMaxCoordinate = 1e6, kFormulaMinDenominator = 1e-6;

int formula_terms(int d) { return (d + 1) * (d + 2) / 2; }

// A random formula of degree d in a random frame.
struct KernelTestFormula {
  int d = 0;
  double centre_u = 0, centre_v = 0, inverse_half_u = 1, inverse_half_v = 1;
  std::vector<double> n, m;
  PlaneFormula view() const {
    return {d, centre_u, centre_v, inverse_half_u, inverse_half_v, kFormulaMaxCoordinate, kFormulaMinDenominator, n.data(), m.data()};
  }
  // The frame coordinates the kernel defines, (u - centre_u) * inverse_half_u rounded twice.
  double a(double u) const { return (u - centre_u) * inverse_half_u; }
  double b(double v) const { return (v - centre_v) * inverse_half_v; }
};

KernelTestFormula random_kernel_formula(int d, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), half(0.25, 4.0);
  KernelTestFormula f;
  f.d = d;
  f.centre_u = unit(rng);
  f.centre_v = unit(rng);
  f.inverse_half_u = half(rng);
  f.inverse_half_v = half(rng);
  for (int e = 0; e < formula_terms(d); ++e) {
    f.n.push_back(unit(rng));
    f.m.push_back(unit(rng));
  }
  return f;
}

// T_0..T_d at x, exactly, and a bound on their values' and their rounding's growth for the error
// bound: |T_k| <= A_k with A_{k+1} = 2 |x| A_k + A_{k-1}.
void exact_chebyshev(int d, double x, std::vector<mpq_class>& t, std::vector<double>& size) {
  t.assign(d + 1, 0);
  size.assign(d + 1, 1.0);
  t[0] = 1;
  t[1] = x;
  size[1] = std::abs(x);
  for (int k = 1; k < d; ++k) {
    t[k + 1] = 2 * mpq_class(x) * t[k] - t[k - 1];
    size[k + 1] = 2 * std::abs(x) * size[k] + size[k - 1];
  }
}

// N, M, sum |m_ij T_i T_j| exactly, and the sizes sum |n_ij| A_i B_j and sum |m_ij| A_i B_j.
struct ExactFormulaValue {
  mpq_class numerator, denominator, size;
  double numerator_bound = 0, denominator_bound = 0;
};

ExactFormulaValue exact_formula_value(const KernelTestFormula& f, double u, double v) {
  std::vector<mpq_class> ta, tb;
  std::vector<double> sa, sb;
  exact_chebyshev(f.d, f.a(u), ta, sa);
  exact_chebyshev(f.d, f.b(v), tb, sb);
  ExactFormulaValue r;
  std::size_t e = 0;
  for (int k = 0; k <= f.d; ++k)
    for (int j = 0; j <= k; ++j, ++e) {
      const mpq_class term = ta[k - j] * tb[j];
      r.numerator += mpq_class(f.n[e]) * term;
      const mpq_class weighted = mpq_class(f.m[e]) * term;
      r.denominator += weighted;
      r.size += abs(weighted);
      r.numerator_bound += std::abs(f.n[e]) * sa[k - j] * sb[j];
      r.denominator_bound += std::abs(f.m[e]) * sa[k - j] * sb[j];
    }
  return r;
}

// The kernel's t at the points of one batch, every implementation alike to the first (scalar).
std::vector<double> formula_on_every_kernel(const KernelTestFormula& f, const std::vector<double>& u, const std::vector<double>& v) {
  std::vector<double> first;
  for (const Implementation* implementation : available_implementations()) {
    std::vector<double> t(u.size(), -7.0);
    implementation->formula_parameter(f.view(), u.size(), u.data(), v.data(), t.data());
    if (first.empty())
      first = t;
    else
      for (std::size_t l = 0; l < u.size(); ++l)
        EXPECT_TRUE(same_bits(t[l], first[l]))
            << implementation->name << " d " << f.d << " lane " << l << ": " << t[l] << " against " << first[l];
  }
  return first;
}

TEST(FormulaParameter, IsNOverMWithinItsRoundingAtEveryDegreeAndBatchSize) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> near(-1.5, 1.5);
  int checked = 0;
  for (const int d : {1, 2, 3, 4, 5, 7, 8, 12, 13, 18, 20, 32})
    for (const std::size_t count : {1, 3, 4, 7, 8, 9, 31, 32, 33, 40, 71}) {
      const KernelTestFormula f = random_kernel_formula(d, rng);
      std::vector<double> u(count), v(count);
      for (std::size_t l = 0; l < count; ++l) {
        // Within the frame's box, where |T_k| <= 1 and the sums keep their digits, mostly.
        u[l] = f.centre_u + near(rng) / f.inverse_half_u;
        v[l] = f.centre_v + near(rng) / f.inverse_half_v;
      }
      const std::vector<double> t = formula_on_every_kernel(f, u, v);
      for (std::size_t l = 0; l < count; ++l) {
        const ExactFormulaValue x = exact_formula_value(f, u[l], v[l]);
        const double m = x.denominator.get_d();
        const bool clear = std::abs(m) >= 2 * kFormulaMinDenominator * x.size.get_d();
        const bool absent = std::abs(m) <= 0.5 * kFormulaMinDenominator * x.size.get_d();
        if (absent) {
          EXPECT_TRUE(std::isnan(t[l])) << "d " << d << " lane " << l;
          continue;
        }
        if (!clear) continue;  // at the threshold either answer is right
        ASSERT_TRUE(std::isfinite(t[l])) << "d " << d << " lane " << l;
        const mpq_class want = x.numerator / x.denominator;
        // Each sum's error: the recurrence's (2 k eps A_k for T_k), the products', and the
        // summation's of formula_terms(d) terms one after the other (Higham's gamma_N), times the sizes,
        // divided through M.
        const double gamma = (2 * d + 4 + formula_terms(d)) * kFormulaEps;
        const double bound =
            gamma * (x.numerator_bound + std::abs(want.get_d()) * x.denominator_bound) / std::abs(m) * 1.01 +
            kFormulaEps * std::abs(want.get_d());
        EXPECT_LE(std::abs(t[l] - want.get_d()), bound) << "d " << d << " lane " << l;
        ++checked;
      }
    }
  EXPECT_GT(checked, 2500);
}

TEST(FormulaParameter, IsNaNBeyondItsReachAtNaNPointsAndWhereMVanishes) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> near(-1.0, 1.0);
  const double inf = std::numeric_limits<double>::infinity();
  for (const int d : {1, 2, 6, 18}) {
    KernelTestFormula f = random_kernel_formula(d, rng);
    // M(a0, b0) = 0 to rounding at one point: its constant term cancels the others there.
    const double u0 = f.centre_u + 0.3 / f.inverse_half_u, v0 = f.centre_v - 0.6 / f.inverse_half_v;
    f.m[0] = 0.0;
    f.m[0] = -exact_formula_value(f, u0, v0).denominator.get_d();
    std::vector<double> u{u0, 2 * kFormulaMaxCoordinate, 0.0, kNaN, 0.0, inf, -inf}, v{v0, 0.0, -2 * kFormulaMaxCoordinate, 0.0, kNaN,
                                                                              0.0, inf};
    const std::size_t odd = u.size();
    // Ordinary points around them, so that the odd ones sit in every position of a group.
    for (int k = 0; k < 40; ++k) {
      u.insert(u.begin() + (k * 7) % static_cast<int>(u.size()), f.centre_u + near(rng) / f.inverse_half_u);
      v.insert(v.begin() + (k * 7) % static_cast<int>(v.size()), f.centre_v + near(rng) / f.inverse_half_v);
    }
    const std::vector<double> t = formula_on_every_kernel(f, u, v);
    std::size_t nans = 0;
    for (std::size_t l = 0; l < u.size(); ++l) {
      const bool odd_point = !(std::abs(u[l]) <= kFormulaMaxCoordinate && std::abs(v[l]) <= kFormulaMaxCoordinate) ||
                             (u[l] == u0 && v[l] == v0);
      if (odd_point) {
        EXPECT_TRUE(std::isnan(t[l])) << "d " << d << " lane " << l << " at (" << u[l] << ", " << v[l] << ")";
        ++nans;
      }
    }
    EXPECT_EQ(nans, odd);
  }
}

TEST(FormulaParameter, RefusesADegreeOutsideItsRange) {
  std::mt19937_64 rng(2);
  KernelTestFormula f = random_kernel_formula(2, rng);
  for (const int d : {0, kFormulaParameterMaxDegree + 1}) {
    PlaneFormula view = f.view();
    view.degree = d;
    double u = 0, v = 0, t = 0;
    for (const Implementation* implementation : available_implementations())
      EXPECT_THROW(implementation->formula_parameter(view, 1, &u, &v, &t), std::out_of_range) << implementation->name;
  }
}

}  // namespace
}  // namespace bezinv::kernels
