#pragma once
// The eigenvalues of a small square pencil (M1, M2): the lambda with det(M1 - lambda M2) = 0,
// each as a pair alpha_j / beta_j so that a root at infinity (M2 singular) is a zero beta rather
// than an overflow. Eigen's QZ algorithm, in a file of its own: it is the costliest template the
// engine instantiates, and the sanitizer tree compiles it without instrumentation (it wraps Eigen
// only; engine/CMakeLists.txt).
#include <Eigen/Core>

namespace bezinv::detail {

// M1, M2: k x k. On success writes alphas and betas (k each) and returns true; false when the QZ
// iteration does not converge.
bool generalized_eigenvalues(const Eigen::MatrixXd& m1, const Eigen::MatrixXd& m2, Eigen::VectorXcd& alphas,
                             Eigen::VectorXd& betas);

}  // namespace bezinv::detail
