#include "bezinv/kernels/symmetric_svd.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

namespace bezinv::kernels {
namespace {
// Dynamic size with a compile-time maximum: Eigen keeps the storage (and the solver's
// workspace) inline, so a call allocates nothing.
using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxSize, kMaxSize>;
}  // namespace

void symmetric_svd(int n, std::span<const double> B, std::span<double> sigma, std::span<double> V) {
  assert(n >= 1 && n <= kMaxSize);
  Matrix m(n, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c <= r; ++c) m(r, c) = B[r * n + c];
  // GCC 12 reports -Wmaybe-uninitialized inside Eigen's tridiagonal QR for max-size matrices: the
  // solver writes its n x n eigenvector block before reading it, but the analysis cannot see that
  // the inline 32 x 32 storage is only used up to n. A false positive, silenced here only (clang
  // has no such warning, and would warn about the unknown option).
#pragma GCC diagnostic push
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
  Eigen::SelfAdjointEigenSolver<Matrix> solver;
  solver.compute(m, Eigen::ComputeEigenvectors);  // reads the lower triangle only
  const auto& lambda = solver.eigenvalues();
  const auto& Q = solver.eigenvectors();
  // Singular values are |lambda|; order them descending, carrying the eigenvectors along.
  // NaN (from a non-finite input) sorts first, so the order is a strict weak ordering whatever
  // the input: std::sort with an inconsistent comparator is undefined behaviour.
  auto key = [&](int i) {
    const double s = std::abs(lambda[i]);
    return std::isnan(s) ? std::numeric_limits<double>::infinity() : s;
  };
  std::array<int, kMaxSize> order;
  for (int i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.begin() + n, [&](int a, int b) { return key(a) > key(b); });
  for (int k = 0; k < n; ++k) {
    sigma[k] = std::abs(lambda[order[k]]);
    for (int r = 0; r < n; ++r) V[k * n + r] = Q(r, order[k]);
  }
#pragma GCC diagnostic pop
}

}  // namespace bezinv::kernels
