#include "generalized_eigenvalues.hpp"

#include <cmath>
#include <complex>

#include <Eigen/Eigenvalues>

namespace bezinv::detail {

// Eigen's RealQZ, and the eigenvalues read from its generalized real Schur form (S, T) as
// Eigen's GeneralizedEigenSolver reads them, operation for operation: its info() asserts where the
// QZ iteration did not converge (a pencil of extreme entries), so a build with assertions on
// stopped there instead of returning false.
bool generalized_eigenvalues(const Eigen::MatrixXd& m1, const Eigen::MatrixXd& m2, Eigen::VectorXcd& alphas,
                             Eigen::VectorXd& betas) {
  const Eigen::RealQZ<Eigen::MatrixXd> qz(m1, m2, /*computeQZ=*/false);
  if (qz.info() != Eigen::Success) return false;
  const Eigen::MatrixXd& s = qz.matrixS();
  const Eigen::MatrixXd& t = qz.matrixT();
  const Eigen::Index size = m1.cols();
  alphas.resize(size);
  betas.resize(size);
  for (Eigen::Index i = 0; i < size;) {
    if (i == size - 1 || s(i + 1, i) == 0.0) {  // a real eigenvalue: a 1 x 1 block
      alphas(i) = s(i, i);
      betas(i) = t(i, i);
      ++i;
      continue;
    }
    // A complex pair: a 2 x 2 block of S over a diagonal block diag(a, b) of T. With beta = a b no
    // division is needed: alpha are the eigenvalues of S diag(b, a).
    const double a = t(i, i), b = t(i + 1, i + 1);
    const double beta = a * b;
    betas(i) = betas(i + 1) = beta;
    const double s00 = s(i, i) * b, s01 = s(i, i + 1) * a, s10 = s(i + 1, i) * b, s11 = s(i + 1, i + 1) * a;
    const double p = 0.5 * (s00 - s11);
    const double z = std::sqrt(std::abs(p * p + s10 * s01));
    const std::complex<double> alpha(s11 + p, beta > 0 ? z : -z);
    alphas(i) = std::conj(alpha);
    alphas(i + 1) = alpha;
    i += 2;
  }
  return true;
}

}  // namespace bezinv::detail
