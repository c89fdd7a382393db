#include "generalized_eigenvalues.hpp"

#include <Eigen/Eigenvalues>

namespace bezinv::detail {

bool generalized_eigenvalues(const Eigen::MatrixXd& m1, const Eigen::MatrixXd& m2, Eigen::VectorXcd& alphas,
                             Eigen::VectorXd& betas) {
  const Eigen::GeneralizedEigenSolver<Eigen::MatrixXd> qz(m1, m2, /*computeEigenvectors=*/false);
  if (qz.info() != Eigen::Success) return false;
  alphas = qz.alphas();
  betas = qz.betas();
  return true;
}

}  // namespace bezinv::detail
