#pragma once
// "The paper's way" (Marco & Martinez Sect. 3 and 5), as a straightforward implementation would do
// it per point: form p and q, build the Bernstein-Bezout matrix with the printed Bini-Gemignani
// recurrence over the whole matrix, take a general SVD (Eigen::JacobiSVD, as the paper's MATLAB
// svd), read t from the last right singular vector. A baseline for bench/invert_bench.cpp and
// bench/baselines_bench.cpp; it gives only the algebraic t (no refinement, no status).
#include <Eigen/SVD>

#include <cmath>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"

namespace bezinv::bench {

// The Bini-Gemignani recurrence exactly as printed in the paper (Maple, 1-based B[1..n, 1..n],
// p[0..n], q[0..n]), over the whole matrix.
inline void printed_bezout_recurrence(const double* p, const double* q, int n, Eigen::MatrixXd& B) {
  auto b = [&](int i, int j) -> double& { return B(i - 1, j - 1); };
  for (int i = 1; i <= n; ++i) b(i, 1) = (static_cast<double>(n) / i) * (p[i] * q[0] - p[0] * q[i]);
  for (int j = 1; j <= n - 1; ++j) b(n, j + 1) = (static_cast<double>(n) / (n - j)) * (p[n] * q[j] - p[j] * q[n]);
  for (int j = 1; j <= n - 1; ++j)
    for (int i = 1; i <= n - 1; ++i)
      b(i, j + 1) = (static_cast<double>(n) * n / (static_cast<double>(i) * (n - j))) * (p[i] * q[j] - p[j] * q[i]) +
                    (static_cast<double>(j) * (n - i) / (static_cast<double>(i) * (n - j))) * b(i + 1, j);
}

// The paper's read-out: the largest component of z, the larger of its two neighbours, and
// t = i z_i / (i z_i + (N+1-i) z_{i-1}) with N + 1 = z.size().
inline double paper_read_out(const Eigen::VectorXd& z) {
  const int size = static_cast<int>(z.size());
  int k = 0;
  for (int i = 1; i < size; ++i)
    if (std::abs(z[i]) > std::abs(z[k])) k = i;
  int i = k;  // the pair (z_{i-1}, z_i)
  if (k == 0 || (k + 1 < size && std::abs(z[k + 1]) > std::abs(z[k - 1]))) i = k + 1;
  return i * z[i] / (i * z[i] + (size - i) * z[i - 1]);
}

// Per-point workspace, allocated once per benchmark.
struct PaperWay {
  explicit PaperWay(int n) : n(n), B(n, n), svd(n, n, Eigen::ComputeFullV), p(n + 1), q(n + 1) {}
  double parameter(const Curve& curve, Point P0) {
    // Paper Sect. 3: p = sum w_i a_i beta_i - x0 sum w_i beta_i, q likewise with b_i, y0.
    for (int i = 0; i <= n; ++i) {
      p[i] = curve.x_num[i] - P0.x * curve.x_den[i];
      q[i] = curve.y_num[i] - P0.y * curve.y_den[i];
    }
    printed_bezout_recurrence(p.data(), q.data(), n, B);
    svd.compute(B, Eigen::ComputeFullV);
    return paper_read_out(svd.matrixV().col(n - 1));
  }
  int n;
  Eigen::MatrixXd B;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd;
  std::vector<double> p, q;
};

}  // namespace bezinv::bench
