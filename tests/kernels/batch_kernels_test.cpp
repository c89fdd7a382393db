// The lane-batched kernels (kernels/batch.hpp), every available implementation, every size each is
// compiled for, batch sizes around the vector widths (2, 4, 8 lanes). References are never the kernels' own output:
// Eigen::JacobiSVD per lane, or matrices built as B = Q diag(sigma) Q^T with known sigma and Q.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "support/bits.hpp"
#include "bezinv/kernels/batch.hpp"
#include "bezinv/kernels/detail/batch_selection.hpp"
#include "support/measure.hpp"
#include "support/reference_linear_algebra.hpp"
#include "support/sanitizers.hpp"

namespace bezinv::kernels {
namespace {

using test_support::kEps;
using test_support::sci;
using Dense = Eigen::MatrixXd;

constexpr std::size_t kCounts[] = {1, 2, 3, 4, 5, 7, 8, 9, 15, 16, 17, 33};
// Both sides are Jacobi methods with errors ~ n eps sigma_1; measured worst ~1.1e-14 at n = 22.
constexpr double kSigmaTolerance = 2e-14;
using test_support::kNaN;

Dense random_symmetric(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Dense b(n, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c <= r; ++c) b(r, c) = b(c, r) = u(rng);
  return b;
}

// Q diag(sigma) Q^T with sigma_k = 0 for the last `nullity` k and the others in [0.1, 1]. The
// null space is spanned by the last `nullity` columns of Q (up to rounding of the product).
struct Constructed {
  Dense b, q;
};
Constructed with_nullity(int n, int nullity, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.1, 1.0);
  Dense q = test_support::random_orthogonal(n, rng);
  Eigen::VectorXd sigma(n);
  for (int k = 0; k < n; ++k) sigma(k) = k < n - nullity ? u(rng) * (rng() % 2 ? 1.0 : -1.0) : 0.0;
  Dense b = q * sigma.asDiagonal() * q.transpose();
  b = (0.5 * (b + b.transpose())).eval();
  return {b, q};
}

// The SoA batch of the header; padding lanes get finite junk that must not matter.
struct Batch {
  int n;
  std::size_t count, stride;
  std::vector<Dense> matrices;
  std::vector<double> B, sigma, V, z, defect, estimate, second;

  Batch(const std::vector<Dense>& matrices, std::mt19937_64& rng)
      : n(static_cast<int>(matrices.front().rows())), count(matrices.size()), stride(batch_stride(count)),
        matrices(matrices) {
    const std::size_t nn = static_cast<std::size_t>(n) * n;
    B.assign(nn * stride, 0.0);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (std::size_t l = 0; l < stride; ++l)
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) B[(r * n + c) * stride + l] = l < count ? matrices[l](r, c) : u(rng);
    sigma.assign(n * stride, kNaN);
    V.assign(nn * stride, kNaN);
    z.assign(n * stride, kNaN);
    defect.assign(stride, kNaN);
    estimate.assign(2 * stride, kNaN);
    second.assign(n * stride, kNaN);
  }
  // Outside the sizes symmetric_svd is compiled for (the engine uses Eigen above), sigma and V
  // come from Eigen::JacobiSVD: the null-vector checks still have their reference.
  void run(const Implementation& impl) {
    if (n >= kSymmetricSvdMinSize && n <= kSymmetricSvdMaxSize) {
      impl.symmetric_svd(n, count, stride, B.data(), sigma.data(), V.data());
    } else {
      for (std::size_t l = 0; l < count; ++l) {
        const test_support::ReferenceSvd svd = test_support::reference_svd(matrices[l]);
        for (int k = 0; k < n; ++k) {
          sigma[k * stride + l] = svd.sigma(k);
          for (int r = 0; r < n; ++r) V[(k * n + r) * stride + l] = svd.V(r, k);
        }
      }
    }
    impl.null_vector(n, count, stride, B.data(), z.data(), defect.data(), estimate.data(), second.data());
  }
  double s(std::size_t l, int k) const { return sigma[k * stride + l]; }
  Eigen::VectorXd v(std::size_t l, int k) const {
    Eigen::VectorXd out(n);
    for (int r = 0; r < n; ++r) out(r) = V[(k * n + r) * stride + l];
    return out;
  }
  Eigen::VectorXd null(std::size_t l) const {
    Eigen::VectorXd out(n);
    for (int r = 0; r < n; ++r) out(r) = z[r * stride + l];
    return out;
  }
  Eigen::VectorXd next(std::size_t l) const {  // the fast path's second vector
    Eigen::VectorXd out(n);
    for (int r = 0; r < n; ++r) out(r) = second[r * stride + l];
    return out;
  }
  // The results contract covers lanes < count only: nothing is written to the padding lanes.
  void expect_padding_untouched() const {
    for (std::size_t l = count; l < stride; ++l) {
      EXPECT_TRUE(std::isnan(defect[l]) && std::isnan(estimate[l]) && std::isnan(estimate[stride + l])) << "lane " << l;
      for (int k = 0; k < n; ++k) {
        EXPECT_TRUE(std::isnan(s(l, k)) && std::isnan(z[k * stride + l])) << "lane " << l;
        for (int r = 0; r < n; ++r) EXPECT_TRUE(std::isnan(V[(k * n + r) * stride + l])) << "lane " << l;
      }
    }
  }
};

double abs_cos(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return std::abs(a.dot(b)) / (a.norm() * b.norm()); }

std::string label(const Implementation& impl, int n, std::size_t count) {
  return std::string(impl.name) + " n=" + std::to_string(n) + " count=" + std::to_string(count);
}

TEST(BatchImplementations, ScalarFirstAndAvx512OnThisCpu) {
  const auto all = available_implementations();
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all.front()->name, "scalar");
  for (const Implementation* impl : all) {
    ASSERT_NE(impl->symmetric_svd, nullptr);
    ASSERT_NE(impl->null_vector, nullptr);
  }
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512bw")) {
    EXPECT_EQ(all.back()->name, "avx512");
  } else if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    EXPECT_EQ(all.back()->name, "avx2");
  }
}

// Every instruction set this CPU runs is available, where this build compiled it; the tests that
// compare implementations then compare all of them. A tree built with BEZINV_KERNEL_TARGETS=native
// (the trees of scripts/test.sh) has scalar and this CPU's only: the others are reported skipped here.
TEST(BatchImplementations, EveryInstructionSetOfThisCpu) {
  const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw");
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  EXPECT_TRUE(detail::implementation_compiled("scalar"));
  EXPECT_NE(detail::implementation_named("scalar"), nullptr);
  std::string missing;
  for (const auto& [name, runs] : {std::pair{"avx2", avx2}, std::pair{"avx512", avx512}}) {
    if (!runs) continue;
    if (detail::implementation_compiled(name))
      EXPECT_NE(detail::implementation_named(name), nullptr) << name;
    else
      missing += std::string(missing.empty() ? "" : ", ") + name;
  }
  if (!missing.empty())
    GTEST_SKIP() << "this build did not compile the kernels for " << missing
                 << " (BEZINV_KERNEL_TARGETS=native); the tests that compare implementations compare the others";
}

TEST(BatchImplementations, SelectionByName) {
  for (const Implementation* impl : available_implementations()) {
    ASSERT_EQ(detail::implementation_named(impl->name), impl);
    std::string warning;
    EXPECT_EQ(&detail::select_implementation(std::string(impl->name).c_str(), warning), impl);
    EXPECT_TRUE(warning.empty());
  }
  EXPECT_EQ(detail::implementation_named("neon"), nullptr);
  EXPECT_EQ(detail::implementation_named(""), nullptr);
  std::string warning;
  EXPECT_EQ(&detail::select_implementation(nullptr, warning), &detail::best_implementation());
  EXPECT_TRUE(warning.empty());
  EXPECT_EQ(&detail::select_implementation("sse9", warning), &detail::best_implementation());
  EXPECT_NE(warning.find("BEZINV_KERNEL=sse9"), std::string::npos) << warning;
  EXPECT_EQ(warning.find('\n'), std::string::npos);
  // Without BEZINV_KERNEL in the environment of this test run, the active one is the best.
  if (std::getenv("BEZINV_KERNEL") == nullptr) {
    EXPECT_EQ(&active_implementation(), &detail::best_implementation());
  }
}

// Random symmetric matrices against Eigen::JacobiSVD, lane by lane, and the implementations
// against each other.
TEST(BatchSymmetricSvd, MatchesEigenJacobiSvdAndEachOther) {
  std::mt19937_64 rng(20240611);
  double worst_sigma = 0, worst_vector = 0, worst_between = 0;
  // Every size it is compiled for (n = 2..16: around both vector widths, 4 and 8 doubles).
  for (int n = kSymmetricSvdMinSize; n <= kSymmetricSvdMaxSize; ++n) {
    for (std::size_t count : kCounts) {
      std::vector<Dense> matrices;
      for (std::size_t l = 0; l < count; ++l) matrices.push_back(random_symmetric(n, rng));
      std::vector<Batch> results;
      for (const Implementation* impl : available_implementations()) {
        SCOPED_TRACE(label(*impl, n, count));
        std::mt19937_64 junk(n * 1000 + count);
        Batch batch(matrices, junk);
        batch.run(*impl);
        batch.expect_padding_untouched();
        for (std::size_t l = 0; l < count; ++l) {
          const test_support::ReferenceSvd svd = test_support::reference_svd(matrices[l]);
          const auto& s = svd.sigma;
          for (int k = 0; k < n; ++k) {
            const double err = std::abs(batch.s(l, k) - s(k)) / s(0);
            worst_sigma = std::max(worst_sigma, err);
            ASSERT_LE(err, kSigmaTolerance) << "lane " << l << " k " << k;
            // Vectors are only determined up to sign, and only when separated from their neighbours.
            const double gap = std::min(k > 0 ? s(k - 1) - s(k) : s(0), k + 1 < n ? s(k) - s(k + 1) : s(0));
            if (gap < 1e-3 * s(0)) continue;
            const double angle = 1 - abs_cos(batch.v(l, k), svd.V.col(k));
            worst_vector = std::max(worst_vector, angle);
            ASSERT_LE(angle, 1e-12) << "lane " << l << " k " << k;
            ASSERT_NEAR(batch.v(l, k).norm(), 1.0, 1e-14);
          }
        }
        results.push_back(std::move(batch));
      }
      for (std::size_t i = 1; i < results.size(); ++i)
        for (std::size_t l = 0; l < count; ++l)
          for (int k = 0; k < n; ++k) {
            const double err = std::abs(results[i].s(l, k) - results[0].s(l, k)) / results[0].s(l, 0);
            worst_between = std::max(worst_between, err);
            ASSERT_LE(err, kSigmaTolerance) << available_implementations()[i]->name << " n " << n << " lane " << l;
          }
    }
  }
  RecordProperty("worst_sigma_vs_eigen_rel", sci(worst_sigma));
  RecordProperty("worst_vector_1_minus_cos", sci(worst_vector));
  RecordProperty("worst_sigma_between_implementations", sci(worst_between));
}

// A size a kernel was not compiled for is an error naming the kernel and its range, not a silent
// no-op (which would leave the outputs as they were).
void expect_out_of_range(const std::function<void()>& call, const std::string& kernel, int min, int max) {
  try {
    call();
    ADD_FAILURE() << kernel << ": no exception";
  } catch (const std::out_of_range& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(kernel), std::string::npos) << message;
    EXPECT_NE(message.find(std::to_string(min) + ".." + std::to_string(max)), std::string::npos) << message;
  }
}

TEST(BatchImplementations, SizesOutsideTheCompiledRangesThrow) {
  constexpr std::size_t count = 3, stride = batch_stride(count);
  constexpr int kLargest = kMaxBatchSize + 1;
  std::vector<double> B(static_cast<std::size_t>(kLargest) * kLargest * stride, 1.0);
  std::vector<double> sigma(kLargest * stride), V(B.size()), z(sigma.size()), defect(stride), estimate(2 * stride),
      t(stride, 0.5), u(stride, 0.0), v(stride, 0.0), distance(stride), poison(stride);
  std::vector<double> coefficients(kLargest + 1, 1.0);
  for (const Implementation* impl : available_implementations()) {
    SCOPED_TRACE(impl->name);
    for (int n : {kSymmetricSvdMinSize - 1, kSymmetricSvdMaxSize + 1})
      expect_out_of_range([&] { impl->symmetric_svd(n, count, stride, B.data(), sigma.data(), V.data()); },
                          "symmetric_svd", kSymmetricSvdMinSize, kSymmetricSvdMaxSize);
    for (int n : {kNullVectorMinSize - 1, kNullVectorMaxSize + 1})
      expect_out_of_range(
          [&] { impl->null_vector(n, count, stride, B.data(), z.data(), defect.data(), estimate.data(), nullptr); },
          "null_vector", kNullVectorMinSize, kNullVectorMaxSize);
    for (int n : {kNullVectorSeedMinSize - 1, kNullVectorSeedMaxSize + 1})
      expect_out_of_range(
          [&] { impl->null_vector_seed(n, count, stride, B.data(), z.data(), defect.data(), estimate.data(), 1.0); },
          "null_vector_seed", kNullVectorSeedMinSize, kNullVectorSeedMaxSize);
    for (int n : {kBezoutNullVectorSeedMinSize - 1, kBezoutNullVectorSeedMaxSize + 1})
      expect_out_of_range(
          [&] {
            impl->bezout_null_vector_seed(n, count, stride, B.data(), B.data(), B.data(), nullptr, u.data(), v.data(),
                                          z.data(), defect.data(), estimate.data(), poison.data(), 1.0);
          },
          "bezout_null_vector_seed", kBezoutNullVectorSeedMinSize, kBezoutNullVectorSeedMaxSize);
    for (int n : {kBezoutMatrixMinSize - 1, kBezoutMatrixMaxSize + 1})
      expect_out_of_range(
          [&] {
            impl->bezout_matrix(n, count, stride, B.data(), B.data(), B.data(), nullptr, u.data(), v.data(),
                                V.data(), poison.data());
          },
          "bezout_matrix", kBezoutMatrixMinSize, kBezoutMatrixMaxSize);
    for (int n : {kBernsteinParameterMinSize - 1, kBernsteinParameterMaxSize + 1})
      expect_out_of_range([&] { impl->bernstein_parameter(n, count, stride, z.data(), t.data()); },
                          "bernstein_parameter", kBernsteinParameterMinSize, kBernsteinParameterMaxSize);
    for (int degree : {kRationalNewtonMinDegree - 1, kRationalNewtonMaxDegree + 1}) {
      const RationalCurve curve{degree, coefficients.data(), coefficients.data(), coefficients.data(),
                                coefficients.data()};
      const NewtonSettings settings{10, 0.125, 1e-6, 10, 1e-12};
      expect_out_of_range(
          [&] { impl->rational_newton(curve, settings, count, u.data(), v.data(), t.data(), distance.data()); },
          "rational_newton", kRationalNewtonMinDegree, kRationalNewtonMaxDegree);
    }
    for (int degree : {kSpaceCheckMinDegree - 1, kSpaceCheckMaxDegree + 1}) {
      const SpaceCurve curve{degree, 1, coefficients.data(), coefficients.data()};
      expect_out_of_range(
          [&] { impl->space_check(curve, count, t.data(), u.data(), v.data(), u.data(), distance.data()); },
          "space_check", kSpaceCheckMinDegree, kSpaceCheckMaxDegree);
    }
  }
}

// How far above the true sigma_{n-1} the fast path's estimate may lie on these matrices (singular
// values in [0.1, 1], so sigma_{n-2} / sigma_{n-1} can be close to 1 and the deflated iterations
// converge slowly). Measured 1.44 with the Ritz value on the last two iterates, 1.61 from the
// power iteration alone. The engine gates on it with a factor of 2 (tolerances.hpp,
// kFastPathGapRatio).
constexpr double kNextEstimateMaxOver = 1.5;

// Rank n-1 and nullity 2 by construction; plus rank n-1 with a small gap sigma_{n-1} = 1e-6.
TEST(BatchNullVector, RankDeficientByConstruction) {
  std::mt19937_64 rng(7);
  double worst_rank1_defect = 0, least_nullity2_defect = 1, least_regular_residual = 1, worst_next_over = 1,
         least_next_over = 1, least_second_in_null_space = 1;
  constexpr std::size_t kCountsHere[] = {1, 5, 8, 17};
  // The matrices of n = 1, which null_vector no longer takes, are still drawn: the bounds below were
  // measured on the matrices the generator gives every later size after them.
  for (std::size_t count : kCountsHere)
    for (std::size_t l = 0; l < count; ++l) {
      with_nullity(1, 1, rng);
      with_nullity(1, 0, rng);
    }
  static_assert(kNullVectorMinSize == 2);
  for (int n = kNullVectorMinSize; n <= kNullVectorMaxSize; ++n) {
    for (std::size_t i = 0; i < std::size(kCountsHere); ++i) {
      const std::size_t count = kCountsHere[i];
      std::vector<Constructed> rank1, nullity2, regular;
      for (std::size_t l = 0; l < count; ++l) {
        rank1.push_back(with_nullity(n, 1, rng));
        nullity2.push_back(with_nullity(n, 2, rng));
        regular.push_back(with_nullity(n, 0, rng));
      }
      // Under the sanitizers one count per size, a different one from size to size.
      if (test_support::thinned_out(static_cast<std::size_t>(n) + i)) continue;
      auto matrices = [](const std::vector<Constructed>& c) {
        std::vector<Dense> out;
        for (const auto& m : c) out.push_back(m.b);
        return out;
      };
      for (const Implementation* impl : available_implementations()) {
        SCOPED_TRACE(label(*impl, n, count));
        std::mt19937_64 junk(n);
        Batch a(matrices(rank1), junk);
        a.run(*impl);
        a.expect_padding_untouched();
        for (std::size_t l = 0; l < count; ++l) {
          const Eigen::VectorXd expected = rank1[l].q.col(n - 1);
          EXPECT_GE(abs_cos(a.null(l), expected), 1 - 1e-12) << "null_vector lane " << l;
          EXPECT_NEAR(a.null(l).norm(), 1.0, 1e-14);
          EXPECT_GE(abs_cos(a.v(l, n - 1), expected), 1 - 1e-12) << "svd lane " << l;
          EXPECT_LE(a.s(l, n - 1), 64 * kEps * a.s(l, 0));
          EXPECT_LE(a.defect[l], 1e-10) << "lane " << l;
          worst_rank1_defect = std::max(worst_rank1_defect, a.defect[l]);
          // The evidence without an SVD, against the constructed singular values (Eigen's here).
          const double frobenius = rank1[l].b.norm();
          EXPECT_LE(a.estimate[l], 64 * kEps) << "||Bz|| / ||B||_F, lane " << l;
          EXPECT_NEAR(a.next(l).norm(), 1.0, 1e-14) << "lane " << l;
          EXPECT_LE(std::abs(a.next(l).dot(a.null(l))), 1e-12) << "second is orthogonal to z, lane " << l;
          const double next = a.s(l, n - 2) / frobenius;
          const double ratio = a.estimate[a.stride + l] / next;
          // From above in exact arithmetic; the deflated solves round (measured down to 0.9986).
          EXPECT_GE(ratio, 0.99) << "sigma_{n-1} is estimated from above, lane " << l;
          least_next_over = std::min(least_next_over, ratio);
          EXPECT_LE(ratio, kNextEstimateMaxOver) << "lane " << l;
          worst_next_over = std::max(worst_next_over, ratio);
          // n <= 3: the deflated space is at most a plane, on which the Ritz value is exact.
          if (n <= 3) {
            EXPECT_NEAR(ratio, 1.0, 1e-9) << "exact at n <= 3, lane " << l;
          }
        }
        Batch b(matrices(nullity2), junk);
        b.run(*impl);
        for (std::size_t l = 0; l < count; ++l) {
          EXPECT_GE(b.defect[l], 1e-3) << "nullity 2 must be flagged, lane " << l;
          least_nullity2_defect = std::min(least_nullity2_defect, b.defect[l]);
          // Whatever it is, z lies in the 2-D null space, and so do the SVD's last two vectors.
          const Dense null_space = nullity2[l].q.rightCols(2);
          EXPECT_GE((null_space.transpose() * b.null(l)).norm(), 1 - 1e-10) << "lane " << l;
          // The deflated iterate heads for the other null direction (both are amplified ~1/eps by
          // the solves, and z is projected out). Not to rounding level: at nullity 2 the rounding
          // of the two tiny pivots decides the mix (measured down to 0.9855); a random unit vector
          // would give ~sqrt(2/n). The engine never answers a nullity-2 lane on the fast path.
          const double in_span = (null_space.transpose() * b.next(l)).norm();
          EXPECT_GE(in_span, 0.95) << "second, lane " << l;
          least_second_in_null_space = std::min(least_second_in_null_space, in_span);
          for (int k : {n - 2, n - 1}) EXPECT_GE((null_space.transpose() * b.v(l, k)).norm(), 1 - 1e-12);
        }
        Batch c(matrices(regular), junk);
        c.run(*impl);
        for (std::size_t l = 0; l < count; ++l) {
          // A regular matrix is told by its residual ||B z|| / ||B||_F >= sigma_n / ||B||_F, not
          // by the defect (z may well have converged to the singular vector of sigma_n).
          EXPECT_GE(c.estimate[l], 1e-3) << "non-singular must show in the residual, lane " << l;
          least_regular_residual = std::min(least_regular_residual, c.estimate[l]);
        }
      }
    }
  }
  RecordProperty("worst_rank1_defect", sci(worst_rank1_defect));
  RecordProperty("least_nullity2_defect", sci(least_nullity2_defect));
  RecordProperty("least_nonsingular_residual", sci(least_regular_residual));
  RecordProperty("worst_sigma_next_estimate_over_true", sci(worst_next_over));
  RecordProperty("least_sigma_next_estimate_over_true", sci(least_next_over));
  RecordProperty("least_second_in_null_space", sci(least_second_in_null_space));
}

// null_vector_seed: LDL^T without pivoting, no gap. On matrices of nullity 1 its z is the null
// vector (against the constructed one) and its residual is ||B z|| / ||B||_F (against Eigen's
// product); on regular matrices the residual shows it; it reads only the lower triangle and writes
// nothing it does not own.
TEST(BatchNullVector, SeedWithoutPivoting) {
  std::mt19937_64 rng(11);
  std::size_t lanes = 0;
  double worst_cos = 0, worst_residual_error = 0, least_regular_residual = 1;
  for (int n = kNullVectorSeedMinSize; n <= kNullVectorSeedMaxSize; ++n) {
    for (std::size_t count : {std::size_t{3}, std::size_t{17}, std::size_t{64}}) {
      std::vector<Constructed> constructed;
      std::vector<Dense> matrices;
      for (std::size_t l = 0; l < count; ++l) {
        constructed.push_back(with_nullity(n, l % 2 ? 1 : 0, rng));  // regular and singular in turn
        matrices.push_back(constructed.back().b);
      }
      for (const Implementation* impl : available_implementations()) {
        SCOPED_TRACE(label(*impl, n, count));
        std::mt19937_64 junk(n);
        Batch a(matrices, junk);
        // The upper triangle is never read: NaN there must change nothing.
        for (int r = 0; r < n; ++r)
          for (int c = r + 1; c < n; ++c)
            for (std::size_t l = 0; l < a.stride; ++l) a.B[(r * n + c) * a.stride + l] = kNaN;
        impl->null_vector_seed(n, count, a.stride, a.B.data(), a.z.data(), a.defect.data(), a.estimate.data(), 1.0);
        for (std::size_t l = count; l < a.stride; ++l) {
          EXPECT_TRUE(std::isnan(a.defect[l]) && std::isnan(a.estimate[l]) && std::isnan(a.z[l])) << "lane " << l;
        }
        for (std::size_t l = a.stride; l < 2 * a.stride; ++l) {
          EXPECT_TRUE(std::isnan(a.estimate[l])) << "no sigma_{n-1} row: " << l;
        }
        for (std::size_t l = 0; l < count; ++l) {
          ++lanes;
          const Dense& b = constructed[l].b;
          const Eigen::VectorXd z = a.null(l);
          EXPECT_NEAR(z.norm(), 1.0, 1e-14) << "lane " << l;
          const double residual = (b * z).norm() / b.norm();
          EXPECT_NEAR(a.estimate[l], residual, 1e-14 + 1e-12 * residual) << "lane " << l;
          worst_residual_error = std::max(worst_residual_error, std::abs(a.estimate[l] - residual));
          if (l % 2) {
            const double cos = abs_cos(z, constructed[l].q.col(n - 1));
            EXPECT_GE(cos, 1 - 1e-10) << "lane " << l;
            EXPECT_LE(a.defect[l], 1e-10) << "lane " << l;
            worst_cos = std::max(worst_cos, 1 - cos);
          } else {
            EXPECT_GE(a.estimate[l], 1e-3) << "non-singular must show in the residual, lane " << l;
            least_regular_residual = std::min(least_regular_residual, a.estimate[l]);
          }
        }
      }
    }
  }
  RecordProperty("lanes", static_cast<int>(lanes));
  RecordProperty("worst_one_minus_cos", sci(worst_cos));
  RecordProperty("worst_residual_error", sci(worst_residual_error));
  RecordProperty("least_regular_residual", sci(least_regular_residual));
  std::printf("[ measured ] seed: worst 1 - |cos(z, null vector)| %.3g, worst residual error %.3g, least regular "
              "residual %.3g over %zu lanes\n", worst_cos, worst_residual_error, least_regular_residual, lanes);
}

// null_vector_iterations: three solves give null_vector's bits; where sigma_n / sigma_{n-1} = 0.1
// (B = Q diag(sigma) Q^T, sigma_{n-1} = 1e-3, sigma_n = 1e-4, the others in [0.1, 1]) three
// leave z unsettled (defect above the engine's 1e-3) in most lanes and six settle it onto the
// constructed singular vector in every lane; fewer than three are refused. The singular vector of sigma_n has positive
// components, as a Bernstein basis vector has: the start (1, ..., 1) is then well inside its
// basin (a random one may be nearly orthogonal to it, and take more solves).
TEST(BatchNullVector, MoreIterationsSettleASlowlyConvergingLane) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(0.1, 1.0);
  std::size_t lanes = 0, unsettled_by_three = 0;
  double worst_defect_of_six = 0, worst_cos = 0;
  for (int n : {3, 5, 8, 12, 16, 20, 24, 32}) {
    constexpr std::size_t kCount = 17;
    std::vector<Dense> matrices, q;
    for (std::size_t l = 0; l < kCount; ++l) {
      // Q's last column along a positive vector: Householder QR of a matrix whose first column it is.
      Dense a(n, n);
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) a(r, c) = c == 0 ? u(rng) : 2 * u(rng) - 1.1;
      const Dense h = Eigen::HouseholderQR<Dense>(a).householderQ();
      q.emplace_back(n, n);
      q.back() << h.rightCols(n - 1), h.col(0);
      Eigen::VectorXd sigma(n);
      for (int k = 0; k < n; ++k) sigma(k) = (k < n - 2 ? u(rng) : k == n - 2 ? 1e-3 : 1e-4) * (rng() % 2 ? 1.0 : -1.0);
      const Dense b = q.back() * sigma.asDiagonal() * q.back().transpose();
      matrices.push_back((0.5 * (b + b.transpose())).eval());
    }
    for (const Implementation* impl : available_implementations()) {
      SCOPED_TRACE(label(*impl, n, kCount));
      std::mt19937_64 junk(n);
      Batch three(matrices, junk), plain(matrices, junk), six(matrices, junk);
      impl->null_vector(n, kCount, plain.stride, plain.B.data(), plain.z.data(), plain.defect.data(),
                        plain.estimate.data(), plain.second.data());
      impl->null_vector_iterations(n, 3, kCount, three.stride, three.B.data(), three.z.data(), three.defect.data(),
                                   three.estimate.data(), three.second.data());
      EXPECT_TRUE(test_support::same_bits(three.z, plain.z) && test_support::same_bits(three.defect, plain.defect) &&
                  test_support::same_bits(three.estimate, plain.estimate) &&
                  test_support::same_bits(three.second, plain.second));
      impl->null_vector_iterations(n, 6, kCount, six.stride, six.B.data(), six.z.data(), six.defect.data(),
                                   six.estimate.data(), six.second.data());
      for (std::size_t l = 0; l < kCount; ++l) {
        ++lanes;
        unsettled_by_three += three.defect[l] > 1e-3;
        EXPECT_LE(six.defect[l], 1e-3) << "lane " << l;
        const double cos = abs_cos(six.null(l), q[l].col(n - 1));
        EXPECT_GE(cos, 1 - 1e-8) << "lane " << l;
        worst_defect_of_six = std::max(worst_defect_of_six, six.defect[l]);
        worst_cos = std::max(worst_cos, 1 - cos);
      }
      EXPECT_THROW(impl->null_vector_iterations(n, 2, kCount, six.stride, six.B.data(), six.z.data(),
                                                six.defect.data(), six.estimate.data(), six.second.data()),
                   std::invalid_argument);
    }
  }
  std::printf("[ measured ] sigma_n / sigma_{n-1} = 0.1: %zu of %zu lanes unsettled by three solves; after six the "
              "defect at most %.3g, 1 - |cos(z, singular vector)| at most %.3g\n",
              unsettled_by_three, lanes, worst_defect_of_six, worst_cos);
  EXPECT_GT(unsettled_by_three, lanes / 2);  // the case more solves are for
}

// The smallest singular vector of a nearly singular matrix with sigma_{n-1} / sigma_1 = 1e-6,
// against Eigen::JacobiSVD (the accuracy target of the contract).
TEST(BatchSymmetricSvd, SmallestVectorWithSmallGap) {
  std::mt19937_64 rng(99);
  for (int n = 2; n <= kMaxBatchSize; ++n) {
    std::vector<Dense> matrices;
    for (std::size_t l = 0; l < 9; ++l) {
      std::uniform_real_distribution<double> u(0.1, 1.0);
      const Dense q = test_support::random_orthogonal(n, rng);
      Eigen::VectorXd sigma(n);
      for (int k = 0; k < n; ++k) sigma(k) = u(rng);
      sigma(0) = 1.0;
      sigma(n - 2) = 1e-6;
      sigma(n - 1) = 1e-17;
      const Dense b = q * sigma.asDiagonal() * q.transpose();
      matrices.push_back(0.5 * (b + b.transpose()));
    }
    for (const Implementation* impl : available_implementations()) {
      SCOPED_TRACE(label(*impl, n, matrices.size()));
      std::mt19937_64 junk(n);
      Batch batch(matrices, junk);
      batch.run(*impl);
      for (std::size_t l = 0; l < matrices.size(); ++l) {
        const test_support::ReferenceSvd svd = test_support::reference_svd(matrices[l]);
        EXPECT_GE(abs_cos(batch.v(l, n - 1), svd.V.col(n - 1)), 1 - 1e-12) << "lane " << l;
        EXPECT_GE(abs_cos(batch.null(l), svd.V.col(n - 1)), 1 - 1e-12) << "lane " << l;
      }
    }
  }
}

}  // namespace
}  // namespace bezinv::kernels
