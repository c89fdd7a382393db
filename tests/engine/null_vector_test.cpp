// Reading parameters back from null vectors (null_vector.hpp; paper Sect. 3):
//     z = alpha beta^{(N)}(t)  =>  t = i z_i / (i z_i + (N+1-i) z_{i-1}).
// The inputs are exact Bernstein basis vectors (support/exact) rounded once to double, so the
// expected parameter is known by construction.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/kernels/batch.hpp"
#include "bezinv/null_vector.hpp"
#include "null_vector_read_out.hpp"
#include "support/exact.hpp"
#include "support/measure.hpp"
#include "support/sanitizers.hpp"

namespace bezinv {
namespace {

using test_support::sci;

// alpha * beta^{(N)}(t), rounded once from the exact value.
std::vector<double> basis_vector(int N, double t, double alpha) {
  const std::vector<mpq_class> beta = exact::bernstein_basis(N, mpq_class(t));
  std::vector<double> z;
  for (const auto& b : beta) z.push_back(exact::nearest_double(b * mpq_class(alpha)));
  return z;
}

double norm(const std::vector<double>& z) {
  return std::sqrt(std::inner_product(z.begin(), z.end(), z.begin(), 0.0));
}

TEST(ParameterFromNullVector, RecoversParameterOfScaledBasisVectors) {
  std::mt19937_64 rng(53);
  std::vector<double> ts{1e-3, 0.01, 0.5, 0.99, 0.999, -0.5, 1.7, -2.0, 3.0};
  // A quarter of the random parameters under the sanitizers (support/sanitizers.hpp).
  for (int k = 0; k < 40 / test_support::kSanitizerThinning; ++k) ts.push_back(datasets::uniform(rng, 0.0, 1.0));
  double worst = 0.0;
  for (int N = 1; N <= 31; ++N)
    for (double t : ts)
      for (double alpha : {1.0, -1.0, 1e-200, -3.7e150, 0.37}) {
        std::vector<double> z = basis_vector(N, t, alpha);
        if (alpha == 0.37) {
          const double s = norm(z);
          for (double& v : z) v /= s;  // unit norm, like a column of V
        }
        const double got = parameter_from_null_vector(z);
        // The read-out uses two components of relative accuracy ~eps; for t = -2 or 3 the ratio
        // (N+1-i) t / (i (1-t)) is still O(1). Measured worst 8.9e-16 relative to max(|t|, 1).
        const double e = std::abs(got - t) / std::max(std::abs(t), 1.0);
        worst = std::max(worst, e);
        EXPECT_LE(e, 4e-15) << "N = " << N << " t = " << t << " alpha = " << alpha;
      }
  RecordProperty("worst_relative", sci(worst));
}

TEST(ParameterFromNullVector, EndpointsAndZeroVector) {
  // beta^{(N)}(0) = e_0 and beta^{(N)}(1) = e_N.
  EXPECT_EQ(parameter_from_null_vector(std::vector<double>{1.0, 0.0, 0.0, 0.0}), 0.0);
  EXPECT_EQ(parameter_from_null_vector(std::vector<double>{0.0, 0.0, 0.0, -2.0}), 1.0);
  EXPECT_TRUE(std::isnan(parameter_from_null_vector(std::vector<double>{0.0, 0.0, 0.0})));
}

// The pair is chosen as the paper describes (Sect. 5, Example 2): the largest component, and of
// its two neighbours the larger.
TEST(NullVectorPair, LargestComponentAndLargerNeighbour) {
  EXPECT_EQ(detail::null_vector_pair(std::vector<double>{0.1, 0.9, 0.5, 0.2}), 2);    // z1 max, z2 > z0
  EXPECT_EQ(detail::null_vector_pair(std::vector<double>{0.6, 0.9, 0.5, 0.2}), 1);    // z1 max, z0 > z2
  EXPECT_EQ(detail::null_vector_pair(std::vector<double>{-0.9, 0.1, 0.05}), 1);       // max at the first end
  EXPECT_EQ(detail::null_vector_pair(std::vector<double>{0.01, 0.3, -0.95}), 2);      // max at the last end
  EXPECT_EQ(detail::null_vector_pair(std::vector<double>{0.1, 0.2, -0.3, -0.8}), 3);  // signs do not matter
}

// Example 2 (Sect. 5): the paper prints V(:,15) and reads t0 = 2 z2 / (2 z2 + 13 z1)
// = 1.428606867264249e-01. The printed column has a duplicated line (z6 appears twice, so z7..z14
// are shifted), which is why only z0..z3 are taken from it: they hold the maximum |z2| and both
// of its neighbours. The tail z4..z14 is continued with the basis-vector ratio at t = 1/7,
// z_i = z_{i-1} (15-i) t / (i (1-t)), which keeps it far below |z2| and so out of the choice.
TEST(ParameterFromNullVector, PaperExample2PrintedVector) {
  std::vector<double> z{-2.473682899590338e-01, -5.771889609913881e-01, -6.253061379846553e-01,
                        -4.169368183026464e-01};
  const double t = 1.0 / 7.0;
  for (int i = 4; i <= 14; ++i) z.push_back(z.back() * (15 - i) * t / (i * (1 - t)));
  ASSERT_EQ(z.size(), 15u);
  EXPECT_EQ(detail::null_vector_pair(z), 2);
  EXPECT_NEAR(parameter_from_null_vector(z), 1.428606867264249e-01, 1e-12 * 1.428606867264249e-01);
}

// Example 3 (Sect. 5): V(:,4) printed in full, t0 = z1 / (z1 + 3 z0) = 3.333333267311144e-01.
TEST(ParameterFromNullVector, PaperExample3PrintedVector) {
  const std::vector<double> z{5.111012703997072e-01, 7.666518828223443e-01, 3.833259078513024e-01,
                              6.388763832491218e-02};
  EXPECT_EQ(detail::null_vector_pair(z), 1);
  EXPECT_NEAR(parameter_from_null_vector(z), 3.333333267311144e-01, 1e-12 * 3.333333267311144e-01);
}

TEST(BernsteinFormDefect, NearZeroOnBasisVectorsOrderOneOnMixes) {
  std::mt19937_64 rng(59);
  double worst_basis = 0.0, smallest_mix = 1.0;
  for (int N = 2; N <= 31; ++N) {
    for (int k = 0; k < 8; ++k) {
      const double t = k < 2 ? (k == 0 ? -0.5 : 1.7) : datasets::uniform(rng, 0.02, 0.98);
      const std::vector<double> z = basis_vector(N, t, k % 2 ? -2.5 : 1.0);
      // Measured worst 8.0e-16.
      const double d = detail::bernstein_form_defect(z, t);
      worst_basis = std::max(worst_basis, d);
      EXPECT_LE(d, 4e-15) << "N = " << N << " t = " << t;
    }
    // A mix of two well-separated basis vectors (a two-dimensional null space) is far from every
    // single basis vector: check a fine grid of t, including the read-out parameter.
    const double t1 = 0.2, t2 = 0.75;
    std::vector<double> a = basis_vector(N, t1, 1.0), b = basis_vector(N, t2, 1.0);
    const double na = norm(a), nb = norm(b);
    std::vector<double> mix(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) mix[i] = 0.6 * a[i] / na + 0.8 * b[i] / nb;
    double least = detail::bernstein_form_defect(mix, parameter_from_null_vector(mix));
    for (int g = 0; g <= 1000; ++g) least = std::min(least, detail::bernstein_form_defect(mix, -0.5 + 2.0 * g / 1000));
    smallest_mix = std::min(smallest_mix, least);
    // Measured: smallest 0.29 over N = 2..31 (smallest at low N, where a short vector has little
    // room to be far from the curve t -> beta(t)/|beta(t)|).
    EXPECT_GE(least, 0.05) << "N = " << N;
  }
  RecordProperty("worst_basis", sci(worst_basis));
  RecordProperty("smallest_mix", sci(smallest_mix));
}

TEST(BernsteinFormDefect, ScaleInvariant) {
  const std::vector<double> z = basis_vector(6, 0.3, 1.0);
  std::vector<double> w = z, y = z;
  w[2] += 0.05;
  for (std::size_t i = 0; i < z.size(); ++i) y[i] = -1e30 * w[i];
  EXPECT_NEAR(detail::bernstein_form_defect(w, 0.3), detail::bernstein_form_defect(y, 0.3), 1e-15);
  EXPECT_GT(detail::bernstein_form_defect(w, 0.3), 1e-3);
}

// Two-dimensional null space (double points, near degree drops): random orthonormal bases of
// span{beta(t1), beta(t2)} give back {t1, t2}.
TEST(ParametersFromNullSpace, RecoversBothParametersFromRotatedBases) {
  std::mt19937_64 rng(61);
  double worst = 0.0;
  for (int N = 2; N <= 29; ++N) {
    for (int draw = 0; draw < 6; ++draw) {
      double t1 = datasets::uniform(rng, 0.0, 1.0), t2 = datasets::uniform(rng, 0.0, 1.0);
      if (draw == 4) t1 = -0.3;  // one root off the segment
      if (draw == 5) t2 = 1.4;
      if (std::abs(t1 - t2) < 0.2) t2 = t1 < 0.5 ? t1 + 0.3 : t1 - 0.3;
      const std::vector<double> a = basis_vector(N, t1, 1.0), b = basis_vector(N, t2, 1.0);
      // Gram-Schmidt, then a random rotation of the orthonormal pair (like two columns of V).
      const double na = norm(a);
      std::vector<double> e1(a.size()), e2(b.size());
      for (std::size_t i = 0; i < a.size(); ++i) e1[i] = a[i] / na;
      const double proj = std::inner_product(b.begin(), b.end(), e1.begin(), 0.0);
      for (std::size_t i = 0; i < b.size(); ++i) e2[i] = b[i] - proj * e1[i];
      const double n2 = norm(e2);
      for (double& v : e2) v /= n2;
      const double th = datasets::uniform(rng, 0.0, 6.283185307179586), c = std::cos(th), s = std::sin(th);
      std::vector<double> uvec(a.size()), vvec(a.size());
      for (std::size_t i = 0; i < a.size(); ++i) {
        uvec[i] = c * e1[i] + s * e2[i];
        vvec[i] = -s * e1[i] + c * e2[i];
      }
      double t[2] = {std::nan(""), std::nan("")};
      const int count = parameters_from_null_space(uvec, vvec, t);
      ASSERT_EQ(count, 2) << "N = " << N << " t1 = " << t1 << " t2 = " << t2;
      std::array<double, 2> got{t[0], t[1]}, want{t1, t2};
      std::sort(got.begin(), got.end());
      std::sort(want.begin(), want.end());
      // Parameters at least 0.2 apart. Measured worst 1.1e-15 absolute (N <= 29).
      for (int k = 0; k < 2; ++k) {
        const double e = std::abs(got[k] - want[k]);
        worst = std::max(worst, e);
        EXPECT_LE(e, 5e-15) << "N = " << N << " t1 = " << t1 << " t2 = " << t2;
      }
    }
  }
  RecordProperty("worst_absolute", sci(worst));
}

}  // namespace
}  // namespace bezinv

namespace bezinv {
namespace {

// The kernels' lane-batched read-out (kernels::Implementation::bernstein_parameter) must give
// parameter_from_null_vector's bits: the fast path reads t with it and the SVD path's tests rely
// on both agreeing. Vectors with ties, zeros, NaN, and random signs and sizes.
TEST(ParameterFromNullVector, KernelGivesTheScalarBits) {
  for (const kernels::Implementation* implementation : kernels::available_implementations()) {
    std::mt19937_64 rng(17);
    for (int n = 2; n <= kernels::kMaxBatchSize; ++n) {
      const std::size_t count = 45, stride = kernels::batch_stride(count);
      std::vector<double> z(n * stride), t(count);
      for (std::size_t l = 0; l < count; ++l)
        for (int i = 0; i < n; ++i) {
          double value = datasets::uniform(rng, -1.0, 1.0) * std::pow(10.0, static_cast<double>(rng() % 7) - 3.0);
          if (l % 9 == 1) value = i % 3 == 0 ? 0.5 : -0.5;                       // ties
          if (l % 9 == 2 && i % 2) value = 0.0;                                  // zeros
          if (l % 9 == 3 && i == static_cast<int>(l) % n) value = std::nan("");  // NaN somewhere
          if (l % 9 == 4) value = 0.0;                                           // all zero: NaN
          z[i * stride + l] = value;
        }
      implementation->bernstein_parameter(n, count, stride, z.data(), t.data());
      for (std::size_t l = 0; l < count; ++l) {
        std::vector<double> lane(n);
        for (int i = 0; i < n; ++i) lane[i] = z[i * stride + l];
        const double expected = parameter_from_null_vector(lane);
        SCOPED_TRACE(std::string(implementation->name) + " n=" + std::to_string(n) + " lane " + std::to_string(l));
        if (std::isnan(expected))
          EXPECT_TRUE(std::isnan(t[l]));
        else
          EXPECT_EQ(std::bit_cast<std::uint64_t>(t[l]), std::bit_cast<std::uint64_t>(expected)) << t[l] << " vs " << expected;
      }
    }
  }
}

}  // namespace
}  // namespace bezinv
