// The lane-batched Bezout matrices (Implementation::bezout_matrix), every available implementation:
// each entry against the exact value of B0 - u Bx - v By + u v Bxy (GMP) within the rounding of its
// four products and three sums, and bit for bit against the others and the engine's expression
// (the order of the operations is the contract that keeps the engine's answers the same on every
// instruction set). With Bxy null (one denominator) the last term is absent, as in bezout_at.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "bezinv/kernels/batch.hpp"
#include "support/exact.hpp"
#include "support/sanitizers.hpp"
#include "support/measure.hpp"

namespace bezinv::kernels {
namespace {

using test_support::kEps;
constexpr double kUnset = -7.0;  // what the upper triangle and lanes past the last vector keep

// bilinear: separate denominators (Bxy given, some of its entries 0); else one denominator (Bxy
// null: B is affine in (u, v), the term absent).
void expect_entries_in_every_implementation(bool bilinear) {
  std::mt19937_64 rng(bilinear ? 21 : 22);
  std::uniform_real_distribution<double> coefficient(-3.0, 3.0), coordinate(-2.0, 2.0);
  std::vector<double> reference;  // the first implementation's entries, for the others
  for (int n = kBezoutMatrixMinSize; n <= kBezoutMatrixMaxSize; ++n) {
    constexpr std::size_t kCounts[] = {1, 5, 8, 19};
    for (std::size_t k = 0; k < std::size(kCounts); ++k) {
      const std::size_t count = kCounts[k];
      const std::size_t nn = static_cast<std::size_t>(n) * n, stride = batch_stride(count);
      std::vector<double> B0(nn), Bx(nn), By(nn), Bxy(nn), u(count), v(count);
      for (std::size_t i = 0; i < nn; ++i) {
        B0[i] = coefficient(rng);
        Bx[i] = coefficient(rng);
        By[i] = coefficient(rng);
        Bxy[i] = bilinear && i % 3 ? coefficient(rng) : 0.0;  // 0 as a common denominator's entries
      }
      for (std::size_t l = 0; l < count; ++l) u[l] = coordinate(rng), v[l] = coordinate(rng);
      // Under the sanitizers one count per size, a different one from size to size.
      if (test_support::thinned_out(static_cast<std::size_t>(n) + k)) continue;
      bool first = true;
      for (const Implementation* implementation : available_implementations()) {
        SCOPED_TRACE(std::string(implementation->name) + " n=" + std::to_string(n) + " count=" + std::to_string(count));
        std::vector<double> B(nn * stride, kUnset), poison(count, kUnset);
        implementation->bezout_matrix(n, count, stride, B0.data(), Bx.data(), By.data(),
                                      bilinear ? Bxy.data() : nullptr, u.data(), v.data(), B.data(), poison.data());
        for (std::size_t l = 0; l < count; ++l) {
          EXPECT_EQ(poison[l], 0.0) << "lane " << l;
          for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c) {
              const std::size_t i = static_cast<std::size_t>(r * n + c);
              const double got = B[i * stride + l];
              if (c > r) {
                EXPECT_EQ(got, kUnset) << "upper triangle written at (" << r << ", " << c << ")";
                continue;
              }
              const mpq_class exact = mpq_class(B0[i]) - mpq_class(u[l]) * mpq_class(Bx[i]) -
                                      mpq_class(v[l]) * mpq_class(By[i]) +
                                      mpq_class(u[l]) * mpq_class(v[l]) * mpq_class(Bxy[i]);
              const double size = std::abs(B0[i]) + std::abs(u[l] * Bx[i]) + std::abs(v[l] * By[i]) +
                                  std::abs(u[l] * v[l] * Bxy[i]);
              EXPECT_LE(std::abs(got - exact.get_d()), 4 * kEps * size) << "(" << r << ", " << c << ") lane " << l;
              // The engine's expression (bezout_at), evaluated here in the same order (no FMA on
              // this build's baseline target). Compared as bits: the affine form must not add the
              // zero term, which would turn an entry -0 into +0.
              const double affine = B0[i] - u[l] * Bx[i] - v[l] * By[i];
              const double engine = bilinear ? affine + (u[l] * v[l]) * Bxy[i] : affine;
              EXPECT_EQ(std::memcmp(&got, &engine, sizeof got), 0)
                  << "(" << r << ", " << c << ") lane " << l << ": " << got << " vs " << engine;
            }
        }
        // Padding lanes of the last vector hold finite values (B0 here); none past the stride.
        for (std::size_t l = count; l < stride; ++l)
          EXPECT_TRUE(B[l] == kUnset || B[l] == B0[0]) << "padding lane " << l;
        // The lanes' entries, bit for bit, in every implementation (padding lanes may differ).
        std::vector<double> lanes;
        for (std::size_t i = 0; i < nn; ++i) lanes.insert(lanes.end(), &B[i * stride], &B[i * stride] + count);
        if (first) reference = lanes;
        EXPECT_EQ(lanes, reference) << "differs from " << available_implementations()[0]->name;
        first = false;
      }
    }
  }
}

TEST(BatchBezoutMatrix, EntriesAreTheBilinearCombinationInEveryImplementation) {
  expect_entries_in_every_implementation(true);
}

TEST(BatchBezoutMatrix, WithOneDenominatorEntriesAreTheAffineCombinationInEveryImplementation) {
  expect_entries_in_every_implementation(false);
}

// -0 entries: B0 = -0 and u Bx = v By = +0 give (-0 - 0) - 0 = -0, which adding (u v) Bxy = +0
// would make +0; bezout_at leaves it -0 with one denominator, and so must the kernels (a pivot's
// sign decides which way the seed's guard moves it).
TEST(BatchBezoutMatrix, WithOneDenominatorANegativeZeroStaysNegative) {
  for (const Implementation* implementation : available_implementations()) {
    SCOPED_TRACE(implementation->name);
    const int n = 2;
    const std::size_t count = 9, stride = batch_stride(count);
    const std::vector<double> B0(4, -0.0), Bx(4, 1.0), By(4, 1.0);
    const std::vector<double> u(count, 0.0), v(count, 0.0);
    std::vector<double> B(4 * stride, kUnset), poison(count);
    implementation->bezout_matrix(n, count, stride, B0.data(), Bx.data(), By.data(), nullptr, u.data(), v.data(),
                                  B.data(), poison.data());
    for (std::size_t l = 0; l < count; ++l) {
      EXPECT_EQ(B[l], 0.0);
      EXPECT_TRUE(std::signbit(B[l])) << "lane " << l;
    }
  }
}

TEST(BatchBezoutMatrix, AnOverflowingEntryPoisonsItsLaneOnly) {
  for (const Implementation* implementation : available_implementations()) {
    SCOPED_TRACE(implementation->name);
    const int n = 3;
    const std::size_t count = 10, stride = batch_stride(count);
    const std::vector<double> B0(9, 1.0), Bx(9, 2.0), By(9, -1.0), Bxy(9, 0.5);
    std::vector<double> u(count, 0.25), v(count, -0.5), B(9 * stride), poison(count, kUnset);
    u[3] = 1e300;  // u v Bxy and u Bx overflow: inf - inf somewhere, or inf
    v[3] = 1e300;
    implementation->bezout_matrix(n, count, stride, B0.data(), Bx.data(), By.data(), Bxy.data(), u.data(), v.data(),
                                  B.data(), poison.data());
    for (std::size_t l = 0; l < count; ++l) {
      if (l == 3)
        EXPECT_TRUE(std::isnan(poison[l]));
      else
        EXPECT_EQ(poison[l], 0.0) << "lane " << l;
    }
  }
}

}  // namespace
}  // namespace bezinv::kernels
