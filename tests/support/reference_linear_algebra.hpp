#pragma once
// Eigen's dense decompositions as the kernels' tests use them: the reference SVD and random
// orthogonal matrices. Compiled once, in the test-support library, not in every test file that
// needs them: Eigen's SVD is the costliest template the tests instantiate, and the sanitizer
// tree compiles the test files themselves without optimization (tests/CMakeLists.txt) but keeps
// this library optimized, so a reference stays quick to run.
#include <Eigen/Core>
#include <random>

namespace bezinv::test_support {

// Singular values (descending) and right singular vectors of a dense matrix (Eigen::JacobiSVD,
// one-sided Jacobi: accurate to a few ulps of sigma_1 on every matrix, the reference for the
// kernels' symmetric SVD and null vectors).
struct ReferenceSvd {
  Eigen::VectorXd sigma;
  Eigen::MatrixXd V;
};
ReferenceSvd reference_svd(const Eigen::MatrixXd& a);

// The orthogonal factor Q (n x n) of a's Householder QR: for a Gaussian a, a random orthogonal
// matrix (Haar up to the signs of its columns).
Eigen::MatrixXd orthogonal_factor(const Eigen::MatrixXd& a);

// An n x n random orthogonal matrix: orthogonal_factor of a matrix of standard normal entries.
Eigen::MatrixXd random_orthogonal(int n, std::mt19937_64& rng);

}  // namespace bezinv::test_support
