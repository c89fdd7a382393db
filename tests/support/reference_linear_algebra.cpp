#include "support/reference_linear_algebra.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>

namespace bezinv::test_support {

ReferenceSvd reference_svd(const Eigen::MatrixXd& a) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
  return {svd.singularValues(), svd.matrixV()};
}

Eigen::MatrixXd orthogonal_factor(const Eigen::MatrixXd& a) {
  return Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ() * Eigen::MatrixXd::Identity(a.rows(), a.rows());
}

Eigen::MatrixXd random_orthogonal(int n, std::mt19937_64& rng) {
  std::normal_distribution<double> gaussian;
  Eigen::MatrixXd a(n, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) a(r, c) = gaussian(rng);
  return orthogonal_factor(a);
}

}  // namespace bezinv::test_support
