// The seed kernel on Bezout matrices formed in registers (Implementation::bezout_null_vector_seed):
// on matrices B0 - u Bx of known null vectors, against Eigen; for the sizes null_vector_seed also
// takes, against bezout_matrix (tested against GMP in bezout_matrix_test.cpp) followed by
// null_vector_seed (tested against Eigen in batch_kernels_test.cpp), bit for bit, as its contract
// says; and bezout_matrix's poison.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "bezinv/kernels/batch.hpp"
#include "support/reference_linear_algebra.hpp"

namespace bezinv::kernels {
namespace {

constexpr double kUnsetOutput = -7.0;

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

// The sizes both seeds take.
constexpr int kFirstShared = std::max(kNullVectorSeedMinSize, kBezoutNullVectorSeedMinSize);
constexpr int kLastShared = std::min(kNullVectorSeedMaxSize, kBezoutNullVectorSeedMaxSize);
bool stored_seed_takes(int n) { return n >= kNullVectorSeedMinSize && n <= kNullVectorSeedMaxSize; }

// Runs both ways on the points (u, v) of the coefficient matrices (the stored seed only where it
// takes n); Bxy empty: one denominator (the kernels get Bxy null, and B is affine in (u, v)).
void run_both(const Implementation& impl, int n, std::size_t count, const std::vector<double>& B0,
              const std::vector<double>& Bx, const std::vector<double>& By, const std::vector<double>& Bxy_or_none,
              const std::vector<double>& u, const std::vector<double>& v, Outputs& formed, Outputs& stored) {
  const double* Bxy = Bxy_or_none.empty() ? nullptr : Bxy_or_none.data();
  const std::size_t stride = batch_stride(count), nn = static_cast<std::size_t>(n) * n;
  for (Outputs* o : {&formed, &stored}) {
    o->z.assign(n * stride, kUnsetOutput);
    o->defect.assign(count, kUnsetOutput);
    o->residual.assign(count, kUnsetOutput);
    o->poison.assign(count, kUnsetOutput);
  }
  std::vector<double> B(nn * stride, 0.0);
  impl.bezout_matrix(n, count, stride, B0.data(), Bx.data(), By.data(), Bxy, u.data(), v.data(), B.data(),
                     stored.poison.data());
  if (stored_seed_takes(n))
    impl.null_vector_seed(n, count, stride, B.data(), stored.z.data(), stored.defect.data(), stored.residual.data(), 1.0);
  impl.bezout_null_vector_seed(n, count, stride, B0.data(), Bx.data(), By.data(), Bxy, u.data(), v.data(),
                               formed.z.data(), formed.defect.data(), formed.residual.data(), formed.poison.data(), 1.0);
}

TEST(BezoutNullVectorSeed, BitForBitTheSeedOfBezoutMatrixInEveryImplementation) {
  if (kFirstShared > kLastShared) GTEST_SKIP() << "no size is taken by both seeds";
  std::mt19937_64 rng(33);
  std::uniform_real_distribution<double> coefficient(-3.0, 3.0), coordinate(-2.0, 2.0);
  for (const Implementation* impl : available_implementations()) {
    for (int n = kFirstShared; n <= kLastShared; ++n) {
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
    for (const auto& [n, bilinear] :
         {std::pair{kBezoutNullVectorSeedMinSize, true}, std::pair{20, true}, std::pair{kBezoutNullVectorSeedMaxSize, true},
          std::pair{kBezoutNullVectorSeedMinSize, false}, std::pair{20, false}}) {
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
          EXPECT_TRUE(std::isfinite(formed.defect[l]) && std::isfinite(formed.residual[l])) << "lane " << l;
          if (!stored_seed_takes(n)) continue;
          EXPECT_EQ(formed.defect[l], stored.defect[l]) << "lane " << l;
          EXPECT_EQ(formed.residual[l], stored.residual[l]) << "lane " << l;
        }
      }
    }
  }
}

// B(u, v) = B0 - u Bx with B0 = Q diag(s) Q^T and Bx = q q^T for q = Q's last column: the lanes
// with u = s_n are singular with null vector q (up to the rounding of B0 and of u Bx), the others
// regular with sigma_n = |s_n - u|. Q from a Gaussian matrix, s uniform in +-[0.1, 1].
struct ConstructedPencil {
  std::vector<double> B0, Bx, By;  // n x n, row-major, symmetric to the last bit (By = 0)
  Eigen::VectorXd null;            // q
  double singular_u = 0;           // s_n
};

ConstructedPencil constructed_pencil(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> spectrum(0.1, 1.0);
  std::normal_distribution<double> gaussian;
  Eigen::MatrixXd a(n, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) a(r, c) = gaussian(rng);
  const Eigen::MatrixXd q = test_support::orthogonal_factor(a);
  Eigen::VectorXd s(n);
  for (int k = 0; k < n; ++k) s(k) = spectrum(rng) * (rng() % 2 ? 1.0 : -1.0);
  const Eigen::MatrixXd b0 = q * s.asDiagonal() * q.transpose();
  ConstructedPencil pencil;
  pencil.null = q.col(n - 1);
  pencil.singular_u = s(n - 1);
  const Eigen::MatrixXd bx = pencil.null * pencil.null.transpose();
  const std::size_t nn = static_cast<std::size_t>(n) * n;
  pencil.B0.resize(nn), pencil.Bx.resize(nn), pencil.By.assign(nn, 0.0);
  for (int r = 0; r < n; ++r)  // symmetric to the last bit, as Bezout matrices are
    for (int c = 0; c <= r; ++c) {
      pencil.B0[r * n + c] = pencil.B0[c * n + r] = b0(r, c);
      pencil.Bx[r * n + c] = pencil.Bx[c * n + r] = bx(r, c);
    }
  return pencil;
}

// Every size the kernel takes, one denominator (Bxy null).
TEST(BezoutNullVectorSeed, NullVectorsOfConstructedMatrices) {
  std::mt19937_64 rng(44);
  double worst_cos = 0;
  for (int n = kBezoutNullVectorSeedMinSize; n <= kBezoutNullVectorSeedMaxSize; ++n) {
    const ConstructedPencil pencil = constructed_pencil(n, rng);
    const std::vector<double>&B0 = pencil.B0, &Bx = pencil.Bx, &By = pencil.By;
    const Eigen::VectorXd& null = pencil.null;
    for (const std::size_t count : {std::size_t{5}, std::size_t{64}}) {
      std::vector<double> u(count), v(count, 0.0);
      for (std::size_t l = 0; l < count; ++l)  // singular, regular
        u[l] = l % 2 ? pencil.singular_u : pencil.singular_u - 0.5;
      const std::size_t stride = batch_stride(count);
      for (const Implementation* impl : available_implementations()) {
        SCOPED_TRACE(std::string(impl->name) + " n=" + std::to_string(n) + " count=" + std::to_string(count));
        std::vector<double> z(n * stride, kUnsetOutput), defect(count), residual(count), poison(count);
        impl->bezout_null_vector_seed(n, count, stride, B0.data(), Bx.data(), By.data(), nullptr, u.data(), v.data(),
                                      z.data(), defect.data(), residual.data(), poison.data(), 1.0);
        for (std::size_t l = 0; l < count; ++l) {
          EXPECT_EQ(poison[l], 0.0) << "lane " << l;
          Eigen::VectorXd lane(n);
          for (int r = 0; r < n; ++r) lane(r) = z[r * stride + l];
          EXPECT_NEAR(lane.norm(), 1.0, 1e-14) << "lane " << l;
          Eigen::MatrixXd b(n, n);
          for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c) b(r, c) = (B0[r * n + c] - u[l] * Bx[r * n + c]) - v[l] * By[r * n + c];
          const double expected_residual = (b * lane).norm() / b.norm();
          EXPECT_NEAR(residual[l], expected_residual, 1e-14 + 1e-12 * expected_residual) << "lane " << l;
          if (l % 2) {
            const double cos = std::abs(lane.dot(null));
            EXPECT_GE(cos, 1 - 1e-10) << "lane " << l;
            EXPECT_LE(defect[l], 1e-10) << "lane " << l;
            worst_cos = std::max(worst_cos, 1 - cos);
          } else {
            EXPECT_GE(residual[l], 1e-3) << "non-singular must show in the residual, lane " << l;
          }
        }
        for (std::size_t l = count; l < stride; ++l) EXPECT_EQ(z[l], kUnsetOutput) << "padding lane " << l;
      }
    }
  }
  RecordProperty("worst_one_minus_cos", std::to_string(worst_cos));
}

// The residual only where the seed settled (settled_defect; the engine's kFastPathMaxDefect):
// against the same kernel asked for every lane's residual (settled_defect 1), bit for bit, both
// seeds, every implementation. The matrices are NullVectorsOfConstructedMatrices': singular lanes
// settle, regular ones (sigma_n = 0.5 among singular values 0.1-1) do not. Lanes 0-63 are
// singular one in seven (every SIMD group mixed, fewer than a quarter settled: the formed seed's
// residual of those lanes comes from its compacted second pass), 64-95 all singular (computed in
// their groups), 96-119 one in seven again, 120-135 every other one (groups with a quarter of
// their lanes settled or more, which compute it in place for every lane), 136-149 all regular
// (skipped): three chunks of 64, the last one partial.
TEST(BezoutNullVectorSeed, TheResidualOnlyWhereTheSeedSettledIsTheSameBitForBit) {
  constexpr double kSettled = 1e-3;
  constexpr std::size_t count = 150;
  auto singular_lane = [](std::size_t l) {
    return (l < 120 && l % 7 == 0) || (l >= 64 && l < 96) || (l >= 120 && l < 136 && l % 2 == 0);
  };
  std::mt19937_64 rng(55);
  for (const int n : {3, 5, 8, 9, 15, 20, 24, kBezoutNullVectorSeedMaxSize}) {
    const ConstructedPencil pencil = constructed_pencil(n, rng);
    const std::vector<double>&B0 = pencil.B0, &Bx = pencil.Bx, &By = pencil.By;
    const std::size_t nn = static_cast<std::size_t>(n) * n, stride = batch_stride(count);
    std::vector<double> u(count), v(count, 0.0);
    for (std::size_t l = 0; l < count; ++l) u[l] = singular_lane(l) ? pencil.singular_u : pencil.singular_u - 0.5;
    for (const Implementation* impl : available_implementations()) {
      SCOPED_TRACE(std::string(impl->name) + " n=" + std::to_string(n));
      // seed(settled_defect, outputs): the formed seed where it takes n, else the stored one on
      // bezout_matrix's B.
      auto seed = [&](double settled_defect, Outputs& o) {
        o.z.assign(n * stride, kUnsetOutput);
        o.defect.assign(count, kUnsetOutput);
        o.residual.assign(count, kUnsetOutput);
        o.poison.assign(count, kUnsetOutput);
        if (n >= kBezoutNullVectorSeedMinSize) {
          impl->bezout_null_vector_seed(n, count, stride, B0.data(), Bx.data(), By.data(), nullptr, u.data(), v.data(),
                                        o.z.data(), o.defect.data(), o.residual.data(), o.poison.data(), settled_defect);
        } else {
          std::vector<double> B(nn * stride, 0.0);
          impl->bezout_matrix(n, count, stride, B0.data(), Bx.data(), By.data(), nullptr, u.data(), v.data(), B.data(),
                              o.poison.data());
          impl->null_vector_seed(n, count, stride, B.data(), o.z.data(), o.defect.data(), o.residual.data(),
                                 settled_defect);
        }
      };
      Outputs every, settled_only;
      seed(1.0, every);
      seed(kSettled, settled_only);
      std::size_t settled = 0, mixed_groups_settled = 0, half_settled_groups_settled = 0;
      for (std::size_t l = 0; l < count; ++l) {
        ASSERT_TRUE(std::isfinite(every.residual[l])) << "lane " << l;
        EXPECT_EQ(std::memcmp(&every.defect[l], &settled_only.defect[l], sizeof(double)), 0) << "defect, lane " << l;
        for (int r = 0; r < n; ++r)
          EXPECT_EQ(std::memcmp(&every.z[r * stride + l], &settled_only.z[r * stride + l], sizeof(double)), 0)
              << "z[" << r << "], lane " << l;
        if (every.defect[l] <= kSettled) {
          ++settled;
          mixed_groups_settled += l < 64;
          half_settled_groups_settled += l >= 120 && l < 136;
          EXPECT_EQ(std::memcmp(&every.residual[l], &settled_only.residual[l], sizeof(double)), 0)
              << "residual, lane " << l << ": " << every.residual[l] << " and " << settled_only.residual[l];
        } else {
          EXPECT_EQ(settled_only.residual[l], std::numeric_limits<double>::infinity()) << "lane " << l;
        }
      }
      // The batch has what the test is for: settled lanes among unsettled ones, and the other way.
      EXPECT_GE(mixed_groups_settled, 8u);
      EXPECT_GE(half_settled_groups_settled, 6u);
      EXPECT_GE(settled, 40u);
      EXPECT_LE(settled, 80u);
    }
  }
}

}  // namespace
}  // namespace bezinv::kernels
