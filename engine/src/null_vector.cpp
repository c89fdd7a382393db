#include "bezinv/null_vector.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <complex>
#include <limits>

#include <Eigen/Core>

#include "bezinv/bernstein.hpp"
#include "bezinv/tolerances.hpp"
#include "generalized_eigenvalues.hpp"
#include "null_vector_read_out.hpp"

namespace bezinv {
namespace detail {

int null_vector_pair(std::span<const double> z) {
  const int size = static_cast<int>(z.size());
  assert(size >= 2);
  int k = 0;
  for (int i = 1; i < size; ++i)
    if (std::abs(z[i]) > std::abs(z[k])) k = i;
  if (k == 0) return 1;
  if (k == size - 1) return size - 1;
  return std::abs(z[k - 1]) >= std::abs(z[k + 1]) ? k : k + 1;
}

}  // namespace detail

double parameter_from_null_vector(std::span<const double> z) {
  const int size = static_cast<int>(z.size());
  const int i = detail::null_vector_pair(z);
  // z_i / z_{i-1} = (size - i) t / (i (1 - t))  =>  t = i z_i / (i z_i + (size - i) z_{i-1}).
  const double a = i * z[i];
  const double denom = a + (size - i) * z[i - 1];
  if (denom == 0.0) return std::numeric_limits<double>::quiet_NaN();
  return a / denom;
}

namespace detail {

double bernstein_form_defect(std::span<const double> z, double t) {
  const int size = static_cast<int>(z.size());
  std::array<double, 130> b;
  bernstein_basis(size - 1, t, std::span<double>(b.data(), size));
  double zz = 0, bb = 0, zb = 0;
  for (int i = 0; i < size; ++i) { zz += z[i] * z[i]; bb += b[i] * b[i]; zb += z[i] * b[i]; }
  if (zz == 0.0 || bb == 0.0 || !std::isfinite(bb)) return 1.0;
  // |z/|z| - (z^ . b^) b^| is the sine of the angle, computed without the cancellation of sqrt(1 - cos^2).
  const double zn = std::sqrt(zz), bn = std::sqrt(bb), c = zb / (zn * bn);
  double r2 = 0;
  for (int i = 0; i < size; ++i) {
    const double d = z[i] / zn - c * b[i] / bn;
    r2 += d * d;
  }
  return std::sqrt(r2);
}

}  // namespace detail

int parameters_from_null_space(std::span<const double> u, std::span<const double> v, double t[2]) {
  const int size = static_cast<int>(u.size());
  assert(size >= 3 && v.size() == u.size());
  // Normal equations of the pencil A c = t E c (E = A + D), see null_vector.hpp:
  //   M1 = E^T A,  M2 = E^T E,  det(M1 - t M2) = 0.
  double m1[2][2] = {{0, 0}, {0, 0}}, m2[2][2] = {{0, 0}, {0, 0}};
  for (int i = 1; i < size; ++i) {
    const double a[2] = {i * u[i], i * v[i]};
    const double e[2] = {a[0] + (size - i) * u[i - 1], a[1] + (size - i) * v[i - 1]};
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) { m1[r][c] += e[r] * a[c]; m2[r][c] += e[r] * e[c]; }
  }
  // det(M1 - t M2) = qa t^2 + qb t + qc.
  const double qa = m2[0][0] * m2[1][1] - m2[0][1] * m2[1][0];
  const double qb = -(m1[0][0] * m2[1][1] + m1[1][1] * m2[0][0] - m1[0][1] * m2[1][0] - m1[1][0] * m2[0][1]);
  const double qc = m1[0][0] * m1[1][1] - m1[0][1] * m1[1][0];
  const double scale = std::abs(qa) + std::abs(qb) + std::abs(qc);
  if (scale == 0.0 || !std::isfinite(scale)) return 0;
  // qa ~ 0: E is rank-deficient on the null space, i.e. beta(infinity) is in it (a degree drop);
  // the one finite root is then -qc/qb.
  if (std::abs(qa) <= kPencilInfinityRatio * scale) {
    if (qb == 0.0) return 0;
    t[0] = -qc / qb;
    return 1;
  }
  double disc = qb * qb - 4 * qa * qc;
  // A slightly negative discriminant is a double root blurred by rounding (t1 ~ t2).
  if (disc < 0) {
    if (disc < -kDoubleRootSlack * qb * qb) return 0;
    disc = 0;
  }
  // Stable quadratic formula: no cancellation in the larger-magnitude root.
  const double w = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
  const double r1 = w / qa;
  const double r2 = w != 0.0 ? qc / w : r1;
  t[0] = std::min(r1, r2);
  t[1] = std::max(r1, r2);
  return 2;
}

int parameters_from_null_space(std::span<const double> basis, int k, std::span<double> t) {
  const int size = static_cast<int>(basis.size()) / k;
  assert(k >= 2 && size >= k + 1 && t.size() >= static_cast<std::size_t>(k));
  // M1 = E^T A, M2 = E^T E as in the two-vector case, k x k.
  Eigen::MatrixXd a(size - 1, k), e(size - 1, k);
  for (int j = 0; j < k; ++j) {
    const double* c = basis.data() + static_cast<std::size_t>(j) * size;
    for (int i = 1; i < size; ++i) {
      a(i - 1, j) = i * c[i];
      e(i - 1, j) = a(i - 1, j) + (size - i) * c[i - 1];
    }
  }
  const Eigen::MatrixXd m1 = e.transpose() * a, m2 = e.transpose() * e;
  if (!m1.allFinite() || !m2.allFinite()) return 0;
  Eigen::VectorXcd alphas;
  Eigen::VectorXd betas;
  if (!detail::generalized_eigenvalues(m1, m2, alphas, betas)) return 0;
  const double scale = m1.norm() + m2.norm();
  int count = 0;
  for (int j = 0; j < k; ++j) {
    const std::complex<double> alpha = alphas(j);
    const double beta = betas(j);
    // A root at infinity (a degree drop), or too far out to be more than rounding.
    if (!(std::abs(beta) > kPencilInfinityRatio * scale)) continue;
    const double re = alpha.real() / beta, im = alpha.imag() / beta;
    if (!std::isfinite(re) || std::abs(im) > kComplexRootSlack * std::max(1.0, std::abs(re))) continue;
    t[count++] = re;
  }
  std::sort(t.begin(), t.begin() + count);
  return count;
}

}  // namespace bezinv
