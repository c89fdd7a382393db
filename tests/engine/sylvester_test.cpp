// The Bernstein Sylvester matrix (sylvester.hpp; Winkler & Goldman 2003), the paper's fallback
// when p and q have lower true degree than the formal one (Sect. 4, Example 1 at x0 = 1/2).
// Reference: support/exact forms each column beta_j^{(k-1)} p and beta_j^{(m-1)} q through the
// power basis, not through the product formula C(a,i) C(b,j) / C(a+b,i+j).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/sylvester.hpp"
#include "support/exact.hpp"
#include "support/measure.hpp"
#include "support/random_polynomial.hpp"
#include "support/sanitizers.hpp"

namespace bezinv {
namespace {

using test_support::kEps;
using test_support::random_coefficients;
using test_support::sci;

std::vector<double> engine_sylvester(const std::vector<double>& p, const std::vector<double>& q) {
  const std::size_t size = p.size() + q.size() - 2;
  std::vector<double> s(size * size, std::nan(""));
  sylvester_matrix(p, q, s);
  return s;
}

TEST(SylvesterMatrix, MatchesExactDefinitionForAllDegreePairs) {
  std::mt19937_64 rng(41);
  double worst = 0.0;
  // Every pair up to 16, and the largest the engine can meet (m, k <= kMaxDegree = 32, so the
  // product basis reaches degree 63, where the binomials no longer fit in 53 bits).
  std::vector<std::pair<int, int>> sizes;
  for (int m = 1; m <= 16; ++m)
    for (int k = 1; k <= 16; ++k) sizes.emplace_back(m, k);
  for (auto mk : {std::pair{32, 32}, std::pair{32, 31}, std::pair{29, 32}, std::pair{32, 1}}) sizes.push_back(mk);
  for (auto [m, k] : sizes) {
    const std::vector<double> p = random_coefficients(rng, m), q = random_coefficients(rng, k);
    // Under the sanitizers the pairs with m + k a multiple of 4 (every m and every k) and the large.
    if (m <= 16 && k <= 16 && test_support::thinned_out(static_cast<std::size_t>(m + k))) continue;
    const exact::Matrix ref = exact::sylvester(exact::to_exact(p), exact::to_exact(q));
    const std::vector<double> s = engine_sylvester(p, q);
    const int size = m + k;
    ASSERT_EQ(ref.rows, size);
    double max_p = 0.0, max_q = 0.0;
    for (double v : p) max_p = std::max(max_p, std::abs(v));
    for (double v : q) max_q = std::max(max_q, std::abs(v));
    for (int r = 0; r < size; ++r)
      for (int c = 0; c < size; ++c) {
        // Column c < k carries p, the rest q. Each entry is a coefficient times a ratio of
        // binomials: a few roundings relative to the coefficients' size. Measured worst 1.6e-16.
        const double scale = c < k ? max_p : max_q;
        const double e = exact::abs(mpq_class(s[r * size + c]) - ref(r, c)).get_d() / scale;
        worst = std::max(worst, e);
        EXPECT_LE(e, 4.0 * kEps) << "m = " << m << " k = " << k << " (" << r << "," << c << ")";
      }
  }
  RecordProperty("worst_relative", sci(worst));
}

// Structure the definition implies, on a hand-checkable case: p of degree 2 and q of degree 1
// give a 3 x 3 matrix whose column 0 is p (beta_0^{(0)} = 1) and whose columns 1, 2 are
// beta_0^{(1)} q = (q0, q1/2, 0) and beta_1^{(1)} q = (0, q0/2, q1).
TEST(SylvesterMatrix, SmallCaseByHand) {
  const std::vector<double> p{3.0, -1.0, 2.0}, q{4.0, 6.0};
  const std::vector<double> s = engine_sylvester(p, q);
  const std::vector<double> expected{3.0, 4.0, 0.0,   //
                                     -1.0, 3.0, 2.0,  //
                                     2.0, 0.0, 6.0};
  for (int i = 0; i < 9; ++i) EXPECT_DOUBLE_EQ(s[i], expected[i]) << i;
}

// Left null vector: with p(t0) = q(t0) = 0 every column vanishes at t0, so
// beta^{(m+k-1)}(t0)^T S = 0. Built exactly as p = (t - t0) r1, q = (t - t0) r2 with integer r and
// dyadic t0 (Bernstein coefficients exact in double), for m != k included.
TEST(SylvesterMatrix, CommonRootGivesLeftNullVector) {
  std::mt19937_64 rng(43);
  double worst = 0.0;
  const std::vector<std::pair<int, int>> sizes{{1, 1}, {2, 1}, {1, 3}, {4, 3}, {4, 2}, {3, 7}, {9, 5}, {12, 12}, {15, 14}, {6, 16}};
  for (auto [m, k] : sizes)
    for (double t0 : {0.25, 0.5625, 0.0, 1.0, -0.75, 1.5}) {
      exact::Poly r1(m), r2(k);
      for (auto& v : r1) v = datasets::uniform_int(rng, -20, 20);
      for (auto& v : r2) v = datasets::uniform_int(rng, -20, 20);
      const exact::Poly linear{mpq_class(-t0), mpq_class(1.0 - t0)};  // t - t0 at degree 1
      const exact::Poly p = exact::product(linear, r1), q = exact::product(linear, r2);
      // Scale to integers (by m, k) so the double copies are exact.
      std::vector<double> pd, qd;
      for (const auto& v : p) pd.push_back(mpq_class(v * m).get_d());
      for (const auto& v : q) qd.push_back(mpq_class(v * k).get_d());
      for (int i = 0; i <= m; ++i) ASSERT_EQ(mpq_class(pd[i]), p[i] * m);
      for (int i = 0; i <= k; ++i) ASSERT_EQ(mpq_class(qd[i]), q[i] * k);
      const int size = m + k;
      const std::vector<double> s = engine_sylvester(pd, qd);
      const std::vector<double> v = exact::to_double(exact::bernstein_basis(size - 1, mpq_class(t0)));
      double max_s = 0.0, max_v = 0.0, max_r = 0.0;
      for (double x : s) max_s = std::max(max_s, std::abs(x));
      for (double x : v) max_v = std::max(max_v, std::abs(x));
      for (int c = 0; c < size; ++c) {
        long double r = 0.0L;
        for (int i = 0; i < size; ++i) r += static_cast<long double>(v[i]) * s[i * size + c];
        max_r = std::max(max_r, static_cast<double>(std::fabs(r)));
      }
      // Measured worst 4.4e-17 relative to |S| |v|.
      const double rel = max_r / (max_s * max_v);
      worst = std::max(worst, rel);
      EXPECT_LE(rel, 5e-16) << "m = " << m << " k = " << k << " t0 = " << t0;
    }
  RecordProperty("worst_relative_residual", sci(worst));
}

// Without a common root the exact Sylvester matrix is regular (its determinant is the resultant);
// a sanity check of the reference itself, so the null-vector test above is not vacuous.
TEST(SylvesterMatrix, ExactReferenceIsRegularWithoutCommonRoot) {
  const exact::Poly p{mpq_class(1), mpq_class(-2), mpq_class(3)}, q{mpq_class(2), mpq_class(5)};
  exact::Matrix rhs(3, 1);
  rhs(0, 0) = 1;
  EXPECT_NO_THROW(exact::solve(exact::sylvester(p, q), rhs));
}

}  // namespace
}  // namespace bezinv
