// The symmetric SVD kernel (kernels/symmetric_svd.hpp) for every size 1..kMaxSize.
// Two references: Eigen's JacobiSVD on random symmetric matrices, and matrices whose SVD is known
// exactly by construction, B = Q D Q^T with Q a product of rational Householder reflections
// I - (2/m) v v^T (v in {0, +-1}^n with m = 2^k nonzeros, so every entry is dyadic), formed in
// exact rationals and exactly representable in double. D may hold exact zeros: the singular
// values and null spaces of the rank-deficient matrices B of the paper (nullity 1, or 2 at a
// degree drop, Sect. 4 / Example 3) are then known without any rounding.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/kernels/symmetric_svd.hpp"
#include "support/exact.hpp"
#include "support/measure.hpp"
#include "support/reference_linear_algebra.hpp"

namespace bezinv::kernels {
namespace {

using test_support::sci;

using Dense = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic>;

struct Svd {
  std::vector<double> sigma, v;  // v column-major
  double vcol(int k, int i, int n) const { return v[static_cast<std::size_t>(k) * n + i]; }
};

Svd run_kernel(int n, const std::vector<double>& b) {
  Svd out{std::vector<double>(n, std::nan("")), std::vector<double>(static_cast<std::size_t>(n) * n, std::nan(""))};
  symmetric_svd(n, b, out.sigma, out.v);
  return out;
}

// The std:: distributions and std::shuffle are implementation-defined; these draw from the raw
// mt19937_64 stream (via datasets_gen), so the measured figures reproduce on any standard library.
double gaussian(std::mt19937_64& rng) {  // Box-Muller
  const double u1 = datasets::uniform(rng, 0x1p-53, 1.0), u2 = datasets::uniform(rng, 0.0, 1.0);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

template <class T>
void shuffle(std::vector<T>& v, std::mt19937_64& rng) {  // Fisher-Yates
  for (int i = static_cast<int>(v.size()) - 1; i > 0; --i) std::swap(v[i], v[datasets::uniform_int(rng, 0, i)]);
}

std::vector<double> random_symmetric(std::mt19937_64& rng, int n) {
  std::vector<double> b(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) b[i * n + j] = b[j * n + i] = gaussian(rng);
  return b;
}

Dense to_eigen(int n, const std::vector<double>& b) {
  Dense m(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m(i, j) = b[i * n + j];
  return m;
}

// |V^T V - I| (max entry).
double orthonormality_defect(int n, const Svd& s) {
  double worst = 0.0;
  for (int a = 0; a < n; ++a)
    for (int c = 0; c < n; ++c) {
      double d = 0.0;
      for (int i = 0; i < n; ++i) d += s.vcol(a, i, n) * s.vcol(c, i, n);
      worst = std::max(worst, std::abs(d - (a == c ? 1.0 : 0.0)));
    }
  return worst;
}

// |v_k - s w / |w||, s = sign(v_k . w): the angle between the lines of v_k and w, without the
// cancellation of sqrt(1 - cos^2) (which cannot resolve angles below ~1e-8).
double sine_of_angle(int n, const Svd& s, int k, const std::vector<double>& w) {
  double dot = 0.0, norm2 = 0.0;
  for (int i = 0; i < n; ++i) {
    dot += s.vcol(k, i, n) * w[i];
    norm2 += w[i] * w[i];
  }
  const double sign = dot < 0 ? -1.0 : 1.0, inv = 1.0 / std::sqrt(norm2);
  double d2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double d = s.vcol(k, i, n) - sign * w[i] * inv;
    d2 += d * d;
  }
  return std::sqrt(d2);
}

// max_k |B v_k - s_k sigma_k v_k| / sigma_1, s_k = sign of the eigenvalue (B symmetric).
double residual(int n, const std::vector<double>& b, const Svd& s) {
  double worst = 0.0;
  for (int k = 0; k < n; ++k) {
    std::vector<double> bv(n, 0.0);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) bv[i] += b[i * n + j] * s.vcol(k, j, n);
    double rayleigh = 0.0;
    for (int i = 0; i < n; ++i) rayleigh += bv[i] * s.vcol(k, i, n);
    const double lambda = rayleigh < 0 ? -s.sigma[k] : s.sigma[k];
    for (int i = 0; i < n; ++i) worst = std::max(worst, std::abs(bv[i] - lambda * s.vcol(k, i, n)));
  }
  return s.sigma[0] > 0 ? worst / s.sigma[0] : worst;
}

TEST(SymmetricSvd, MatchesEigenJacobiOnRandomSymmetricMatrices) {
  std::mt19937_64 rng(71);
  double worst_sigma = 0.0, worst_angle_times_gap = 0.0, worst_orth = 0.0, worst_res = 0.0;
  for (int n = 1; n <= kMaxSize; ++n)
    for (int draw = 0; draw < 8; ++draw) {
      std::vector<double> b = random_symmetric(rng, n);
      if (draw == 7) {  // graded: rows and columns scaled over 8 orders of magnitude
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j) b[i * n + j] *= std::pow(10.0, -4.0 * (i + j) / std::max(n - 1, 1));
      }
      const Svd s = run_kernel(n, b);
      const test_support::ReferenceSvd ref = test_support::reference_svd(to_eigen(n, b));
      const double s1 = ref.sigma(0);
      for (int k = 0; k < n; ++k) {
        if (k > 0) {
          EXPECT_GE(s.sigma[k - 1], s.sigma[k]) << "descending, n = " << n;
        }
        // Measured worst 9.4e-15 sigma_1 (the two solvers each err by a few eps sigma_1 sqrt(n)).
        const double e = std::abs(s.sigma[k] - ref.sigma(k)) / s1;
        worst_sigma = std::max(worst_sigma, e);
        EXPECT_LE(e, 1e-13) << "n = " << n << " k = " << k;
        // Singular vectors are defined up to sign, and only when sigma_k is isolated. With gap g
        // (relative to sigma_1) both solvers' vectors are within ~eps/g of the truth
        // (Davis-Kahan), so sin(angle) * g must be round-off small. Measured worst 2.7e-15.
        double gap = INFINITY;
        if (k > 0) gap = std::min(gap, (ref.sigma(k - 1) - ref.sigma(k)) / s1);
        if (k + 1 < n) gap = std::min(gap, (ref.sigma(k) - ref.sigma(k + 1)) / s1);
        if (gap < 1e-6) continue;
        std::vector<double> other(n);
        for (int i = 0; i < n; ++i) other[i] = ref.V(i, k);
        const double sine = sine_of_angle(n, s, k, other);
        const double scaled = sine * std::min(gap, 1.0);
        worst_angle_times_gap = std::max(worst_angle_times_gap, scaled);
        EXPECT_LE(scaled, 1e-13) << "n = " << n << " k = " << k << " gap " << gap;
      }
      // Measured worst 5.8e-15 and 2.2e-15.
      const double orth = orthonormality_defect(n, s), res = residual(n, b, s);
      worst_orth = std::max(worst_orth, orth);
      worst_res = std::max(worst_res, res);
      EXPECT_LE(orth, 2e-14) << "n = " << n;
      EXPECT_LE(res, 1e-14) << "n = " << n;
    }
  RecordProperty("worst_sigma", sci(worst_sigma));
  RecordProperty("worst_angle_times_gap", sci(worst_angle_times_gap));
  RecordProperty("worst_orthonormality", sci(worst_orth));
  RecordProperty("worst_residual", sci(worst_res));
}

// ---- exactly known decompositions ----------------------------------------------------------------

// Q = product of signed permutations and rational Householder reflections, exactly.
exact::Matrix exact_orthogonal(std::mt19937_64& rng, int n) {
  exact::Matrix q(n, n);
  std::vector<int> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  shuffle(perm, rng);
  for (int i = 0; i < n; ++i) q(i, perm[i]) = (rng() & 1) ? 1 : -1;
  int m = 1;
  while (2 * m <= n) m *= 2;
  for (int size : {m, m, std::max(m / 2, 1)}) {
    if (size < 2) continue;
    // H = I - (2/size) v v^T with `size` entries of v equal to +-1.
    std::vector<int> idx(n);
    std::iota(idx.begin(), idx.end(), 0);
    shuffle(idx, rng);
    std::vector<int> v(n, 0);
    for (int k = 0; k < size; ++k) v[idx[k]] = (rng() & 1) ? 1 : -1;
    exact::Matrix next(n, n);
    mpq_class f(2, size);
    f.canonicalize();
    for (int i = 0; i < n; ++i) {
      mpq_class qv = 0;  // (Q v)_i
      for (int j = 0; j < n; ++j) qv += q(i, j) * v[j];
      for (int j = 0; j < n; ++j) next(i, j) = q(i, j) - f * qv * v[j];  // Q H = Q - (2/size)(Q v) v^T
    }
    q = next;
  }
  return q;
}

struct KnownSvd {
  std::vector<double> b;  // exactly Q D Q^T
  exact::Matrix q;
  std::vector<int> d;     // eigenvalues (integers; zeros where rank-deficient)
};

KnownSvd known_matrix(std::mt19937_64& rng, int n, int nullity) {
  KnownSvd out{{}, exact_orthogonal(rng, n), {}};
  // Distinct |d| in 1..100, random signs, then `nullity` of them zeroed.
  std::vector<int> values(100);
  std::iota(values.begin(), values.end(), 1);
  shuffle(values, rng);
  for (int k = 0; k < n; ++k) out.d.push_back(k < nullity ? 0 : ((rng() & 1) ? values[k] : -values[k]));
  shuffle(out.d, rng);
  out.b.resize(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      mpq_class s = 0;
      for (int k = 0; k < n; ++k) s += out.q(i, k) * out.d[k] * out.q(j, k);
      out.b[i * n + j] = s.get_d();
      EXPECT_EQ(mpq_class(out.b[i * n + j]), s) << "construction must be exact in double";
    }
  return out;
}

TEST(SymmetricSvd, ExactlyKnownDecompositionsIncludingRankDeficient) {
  std::mt19937_64 rng(73);
  double worst_sigma = 0.0, worst_null = 0.0, worst_vec = 0.0;
  for (int n = 1; n <= kMaxSize; ++n)
    for (int nullity : {0, 1, 2}) {
      if (nullity >= n && n > 1) continue;
      const KnownSvd k = known_matrix(rng, n, nullity);
      const Svd s = run_kernel(n, k.b);
      std::vector<int> order(n);
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(), [&](int a, int c) { return std::abs(k.d[a]) > std::abs(k.d[c]); });
      const double s1 = std::abs(k.d[order[0]]);
      if (s1 == 0) continue;
      for (int r = 0; r < n; ++r) {
        const int idx = order[r];
        const double e = std::abs(s.sigma[r] - std::abs(k.d[idx])) / s1;
        worst_sigma = std::max(worst_sigma, e);
        // Measured worst 3.7e-15 sigma_1.
        EXPECT_LE(e, 1e-13) << "n = " << n << " r = " << r;
        if (k.d[idx] == 0) {
          // Exactly singular input: the computed sigma must be round-off small (the rank test of
          // tolerances.hpp depends on it). Measured worst 4.1e-16 sigma_1.
          worst_null = std::max(worst_null, s.sigma[r] / s1);
          EXPECT_LE(s.sigma[r], 1e-14 * s1) << "n = " << n << " nullity " << nullity;
          continue;
        }
        // Non-zero |d| are distinct integers: gap >= 1/100 relative. The vector matches Q's column
        // to ~eps / gap. Measured worst sine 1.7e-13.
        std::vector<double> column(n);
        for (int i = 0; i < n; ++i) column[i] = k.q(i, idx).get_d();
        const double sine = sine_of_angle(n, s, r, column);
        worst_vec = std::max(worst_vec, sine);
        EXPECT_LE(sine, 1e-12) << "n = " << n << " r = " << r;
      }
      // The null space: each exact null vector of B lies in the span of the last `nullity`
      // computed columns (for nullity 2 the pair is only defined up to rotation).
      for (int idx = 0; idx < n; ++idx) {
        if (k.d[idx] != 0) continue;
        double proj2 = 0.0, norm2 = 0.0;
        for (int i = 0; i < n; ++i) norm2 += k.q(i, idx).get_d() * k.q(i, idx).get_d();
        for (int r = n - nullity; r < n; ++r) {
          double dot = 0.0;
          for (int i = 0; i < n; ++i) dot += s.vcol(r, i, n) * k.q(i, idx).get_d();
          proj2 += dot * dot;
        }
        EXPECT_NEAR(proj2 / norm2, 1.0, 1e-13) << "n = " << n << " nullity " << nullity;
      }
      EXPECT_LE(orthonormality_defect(n, s), 2e-14) << "n = " << n;
    }
  RecordProperty("worst_sigma", sci(worst_sigma));
  RecordProperty("worst_null_sigma", sci(worst_null));
  RecordProperty("worst_vector_sine", sci(worst_vec));
}

TEST(SymmetricSvd, ReadsOnlyTheLowerTriangle) {
  std::mt19937_64 rng(79);
  for (int n : {2, 5, 16, 32}) {
    const std::vector<double> b = random_symmetric(rng, n);
    std::vector<double> lower = b;
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) lower[i * n + j] = std::nan("");
    const Svd full = run_kernel(n, b), half = run_kernel(n, lower);
    for (int k = 0; k < n; ++k) EXPECT_EQ(full.sigma[k], half.sigma[k]) << "n = " << n;
    for (std::size_t k = 0; k < full.v.size(); ++k) EXPECT_EQ(full.v[k], half.v[k]) << "n = " << n;
  }
}

TEST(SymmetricSvd, DiagonalAndZeroMatrices) {
  // diag(3, -7, 0.5): sigma = 7, 3, 0.5 with unit vectors e1, e0, e2.
  const std::vector<double> d{3.0, 0.0, 0.0, 0.0, -7.0, 0.0, 0.0, 0.0, 0.5};
  const Svd s = run_kernel(3, d);
  EXPECT_DOUBLE_EQ(s.sigma[0], 7.0);
  EXPECT_DOUBLE_EQ(s.sigma[1], 3.0);
  EXPECT_DOUBLE_EQ(s.sigma[2], 0.5);
  EXPECT_NEAR(std::abs(s.vcol(0, 1, 3)), 1.0, 1e-15);
  EXPECT_NEAR(std::abs(s.vcol(1, 0, 3)), 1.0, 1e-15);
  EXPECT_NEAR(std::abs(s.vcol(2, 2, 3)), 1.0, 1e-15);

  const Svd z = run_kernel(4, std::vector<double>(16, 0.0));
  for (double v : z.sigma) EXPECT_EQ(v, 0.0);
  EXPECT_LE(orthonormality_defect(4, z), 1e-15);

  const Svd one = run_kernel(1, std::vector<double>{-2.5});
  EXPECT_EQ(one.sigma[0], 2.5);
  EXPECT_EQ(std::abs(one.v[0]), 1.0);
}

}  // namespace
}  // namespace bezinv::kernels
