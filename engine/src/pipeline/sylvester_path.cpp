#include "pipeline/sylvester_path.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "bezinv/bernstein.hpp"
#include "bezinv/null_vector.hpp"
#include "bezinv/sylvester.hpp"

namespace bezinv::detail {
namespace {

// p written at its true degree, in place: reduce while the leading power coefficient vanishes.
// Returns the degree.
int reduce_to_true_degree(Coefficients& p, int n) {
  Coefficients r;
  while (n >= 1) {
    const std::span<const double> current(p.data(), n + 1);
    if (std::abs(power_leading_coefficient(current)) > kDegreeDropRatio * power_leading_bound(current)) break;
    reduce_degree(current, std::span<double>(r.data(), n));
    --n;
    std::copy_n(r.begin(), n + 1, p.begin());
  }
  return n;
}

}  // namespace

// Fixed-size storage (m + k < 2 kMaxDegree): no allocation here either.
double sylvester_parameter(const PointPolynomials& pq) {
  Coefficients p = pq.p, q = pq.q;
  const int m = reduce_to_true_degree(p, pq.n), k = reduce_to_true_degree(q, pq.n);
  if (m < 1 || k < 1) return std::nan("");
  constexpr int kMaxSize = 2 * kMaxDegree;
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor, kMaxSize, kMaxSize>;
  const int size = m + k;
  Matrix S(size, size);
  sylvester_matrix(std::span<const double>(p.data(), m + 1), std::span<const double>(q.data(), k + 1),
                   std::span<double>(S.data(), static_cast<std::size_t>(size) * size));
  // S is square, so no QR preconditioning would run: none is compiled.
  Eigen::JacobiSVD<Matrix, Eigen::NoQRPreconditioner> svd(S, Eigen::ComputeFullU);
  const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxSize, 1> z = svd.matrixU().col(size - 1);  // v^T S = 0
  return parameter_from_null_vector(std::span<const double>(z.data(), size));
}

}  // namespace bezinv::detail
