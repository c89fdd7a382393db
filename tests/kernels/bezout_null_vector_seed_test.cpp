// The seed kernel on Bezout matrices formed in registers (Implementation::bezout_null_vector_seed)
// against what it replaces on the engine's fast path: bezout_matrix (tested against GMP in
// bezout_matrix_test.cpp) followed by null_vector_seed (tested against Eigen in
// batch_kernels_test.cpp). Its contract is their composition bit for bit, so that the engine's
// answers do not depend on which of the two it runs; and bezout_matrix's poison.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "bezinv/kernels/batch.hpp"

namespace bezinv::kernels {
namespace {

struct Outputs {
  std::vector<double> z, defect, residual, poison;
};

// Lanes 0..count-1 of every output, bit for bit (the padding lanes are not part of the contract).
void expect_same_lanes(const Outputs& formed, const Outputs& stored, int n, std::size_t count, std::size_t stride) {
  for (std::size_t l = 0; l < count; ++l) {
    EXPECT_EQ(std::memcmp(&formed.defect[l], &stored.defect[l], sizeof(double)), 0) << "defect, lane " << l;
    EXPECT_EQ(std::memcmp(&formed.residual[l], &stored.residual[l], sizeof(double)), 0) << "residual, lane " << l;
    for (int r = 0; r < n; ++r)
      EXPECT_EQ(std::memcmp(&formed.z[r * stride + l], &stored.z[r * stride + l], sizeof(double)), 0)
          << "z[" << r << "], lane " << l;
  }
}

// Runs both ways on the points (u, v) of the coefficient matrices; Bxy empty: one denominator
// (the kernels get Bxy null, and B is affine in (u, v)).
void run_both(const Implementation& impl, int n, std::size_t count, const std::vector<double>& B0,
              const std::vector<double>& Bx, const std::vector<double>& By, const std::vector<double>& Bxy_or_none,
              const std::vector<double>& u, const std::vector<double>& v, Outputs& formed, Outputs& stored) {
  const double* Bxy = Bxy_or_none.empty() ? nullptr : Bxy_or_none.data();
  const std::size_t stride = batch_stride(count), nn = static_cast<std::size_t>(n) * n;
  for (Outputs* o : {&formed, &stored}) {
    o->z.assign(n * stride, -7.0);
    o->defect.assign(count, -7.0);
    o->residual.assign(count, -7.0);
    o->poison.assign(count, -7.0);
  }
  std::vector<double> B(nn * stride, 0.0);
  impl.bezout_matrix(n, count, stride, B0.data(), Bx.data(), By.data(), Bxy, u.data(), v.data(), B.data(),
                     stored.poison.data());
  impl.null_vector_seed(n, count, stride, B.data(), stored.z.data(), stored.defect.data(), stored.residual.data());
  impl.bezout_null_vector_seed(n, count, stride, B0.data(), Bx.data(), By.data(), Bxy, u.data(), v.data(),
                               formed.z.data(), formed.defect.data(), formed.residual.data(), formed.poison.data());
}

TEST(BezoutNullVectorSeed, BitForBitTheSeedOfBezoutMatrixInEveryImplementation) {
  std::mt19937_64 rng(33);
  std::uniform_real_distribution<double> coefficient(-3.0, 3.0), coordinate(-2.0, 2.0);
  for (const Implementation* impl : available_implementations()) {
    for (int n = 3; n <= kMaxBatchSize; ++n) {
      // 1 and 5: a partial SIMD vector; 19: whole and partial; 64: the engine's batch. 5 and 64
      // also with one denominator (Bxy null).
      for (const auto& [count, bilinear] : {std::pair{std::size_t{1}, true}, std::pair{std::size_t{5}, true},
                                           std::pair{std::size_t{19}, true}, std::pair{std::size_t{64}, true},
                                           std::pair{std::size_t{5}, false}, std::pair{std::size_t{64}, false}}) {
        SCOPED_TRACE(std::string(impl->name) + " n=" + std::to_string(n) + " count=" + std::to_string(count) +
                     (bilinear ? " bilinear" : " affine"));
        const std::size_t nn = static_cast<std::size_t>(n) * n;
        std::vector<double> B0(nn), Bx(nn), By(nn), Bxy(nn), u(count), v(count);
        for (int r = 0; r < n; ++r)  // symmetric, as Bezout matrices are
          for (int c = 0; c <= r; ++c) {
            const double b0 = coefficient(rng), bx = coefficient(rng), by = coefficient(rng);
            const double bxy = (r + c) % 3 ? coefficient(rng) : 0.0;  // 0: a common denominator's entries
            for (const std::size_t i : {static_cast<std::size_t>(r * n + c), static_cast<std::size_t>(c * n + r)})
              B0[i] = b0, Bx[i] = bx, By[i] = by, Bxy[i] = bxy;
          }
        for (std::size_t l = 0; l < count; ++l) u[l] = coordinate(rng), v[l] = coordinate(rng);
        if (!bilinear) Bxy.clear();
        Outputs formed, stored;
        run_both(*impl, n, count, B0, Bx, By, Bxy, u, v, formed, stored);
        for (std::size_t l = 0; l < count; ++l) {
          ASSERT_EQ(stored.poison[l], 0.0);
          EXPECT_EQ(formed.poison[l], 0.0) << "lane " << l;
          EXPECT_TRUE(std::isfinite(formed.residual[l])) << "lane " << l;
        }
        expect_same_lanes(formed, stored, n, count, batch_stride(count));
      }
    }
  }
}

TEST(BezoutNullVectorSeed, AnOverflowingMatrixPoisonsItsLaneOnly) {
  for (const Implementation* impl : available_implementations()) {
    for (const auto& [n, bilinear] : {std::pair{3, true}, std::pair{4, true}, std::pair{8, true}, std::pair{20, true},
                                     std::pair{3, false}, std::pair{8, false}}) {
      SCOPED_TRACE(std::string(impl->name) + " n=" + std::to_string(n) + (bilinear ? " bilinear" : " affine"));
      const std::size_t count = 21, nn = static_cast<std::size_t>(n) * n;
      std::vector<double> B0(nn), Bx(nn), By(nn), Bxy(bilinear ? nn : 0, 0.5);
      for (std::size_t i = 0; i < nn; ++i) B0[i] = 1.0 + 0.1 * i, Bx[i] = 2.0 - 0.05 * i, By[i] = -1.0;
      for (int r = 0; r < n; ++r)  // B0 diagonal-heavy, so the other lanes' matrices are regular
        B0[static_cast<std::size_t>(r * n + r)] += 10.0 * n;
      std::vector<double> u(count, 0.25), v(count, -0.5);
      u[13] = v[13] = bilinear ? 1e300 : 1e308;  // u v Bxy overflows (bilinear), and u Bx (1e308)
      u[20] = std::numeric_limits<double>::quiet_NaN();
      Outputs formed, stored;
      run_both(*impl, n, count, B0, Bx, By, Bxy, u, v, formed, stored);
      for (std::size_t l = 0; l < count; ++l) {
        if (l == 13 || l == 20) {
          EXPECT_TRUE(std::isnan(formed.poison[l])) << "lane " << l;
        } else {
          EXPECT_EQ(formed.poison[l], 0.0) << "lane " << l;
          EXPECT_EQ(formed.defect[l], stored.defect[l]) << "lane " << l;
          EXPECT_EQ(formed.residual[l], stored.residual[l]) << "lane " << l;
        }
      }
    }
  }
}

}  // namespace
}  // namespace bezinv::kernels
