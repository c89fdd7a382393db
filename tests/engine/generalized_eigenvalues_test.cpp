// engine/src/generalized_eigenvalues.cpp: the eigenvalues alpha / beta of a pencil (M1, M2), against
// pencils made with known eigenvalues (a real spectrum and a complex pair, hidden by orthogonal
// transformations), and a pencil on which Eigen's QZ iteration does not converge.
#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>

#include "generalized_eigenvalues.hpp"

namespace bezinv::detail {
namespace {

// A random orthogonal matrix: Q of the QR factorization of a random matrix.
Eigen::MatrixXd random_orthogonal(int k, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd a(k, k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) a(i, j) = normal(rng);
  return Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ();
}

std::vector<std::complex<double>> sorted_eigenvalues(const Eigen::VectorXcd& alphas, const Eigen::VectorXd& betas) {
  std::vector<std::complex<double>> out;
  for (Eigen::Index i = 0; i < alphas.size(); ++i) out.push_back(alphas(i) / betas(i));
  std::sort(out.begin(), out.end(), [](auto a, auto b) { return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag(); });
  return out;
}

// (Q A Z, Q B Z) has the eigenvalues of (A, B) for orthogonal Q, Z: A upper triangular with the
// known real eigenvalues a_ii / b_ii, or with a 2 x 2 block [[c, -d], [d, c]] (c +- i d) over B = I.
TEST(GeneralizedEigenvalues, KnownSpectraUnderOrthogonalTransformations) {
  std::mt19937_64 rng(91);
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(4, 4), b = Eigen::MatrixXd::Identity(4, 4);
    a(0, 0) = 2.0, b(0, 0) = 4.0;  // 0.5
    a(1, 1) = -3.0;                // -3
    a(2, 2) = 1.5, a(2, 3) = -2.5, a(3, 2) = 2.5, a(3, 3) = 1.5;  // 1.5 -+ 2.5 i
    a(0, 1) = 0.7, a(0, 2) = -1.1, a(1, 3) = 0.4, b(0, 3) = 0.3, b(1, 2) = -0.2;
    const Eigen::MatrixXd q = random_orthogonal(4, rng), z = random_orthogonal(4, rng);
    Eigen::VectorXcd alphas;
    Eigen::VectorXd betas;
    ASSERT_TRUE(generalized_eigenvalues(q * a * z, q * b * z, alphas, betas));
    const std::vector<std::complex<double>> got = sorted_eigenvalues(alphas, betas);
    const std::vector<std::complex<double>> expected = {{-3.0, 0.0}, {0.5, 0.0}, {1.5, -2.5}, {1.5, 2.5}};
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t i = 0; i < got.size(); ++i)
      EXPECT_LT(std::abs(got[i] - expected[i]), 1e-12) << "trial " << trial << ", eigenvalue " << i;
  }
}

// A pencil from a fuzzed point's null space (tests/fuzz/corpus/fuzz_invert/qz_no_convergence.bin)
// on which Eigen's QZ iteration does not converge. Eigen's GeneralizedEigenSolver asserts when
// asked whether it did, so the engine stopped there in a build with assertions on (the sanitizer
// tree). It must return: false, or eigenvalues of the pencil.
TEST(GeneralizedEigenvalues, APencilWithoutConvergenceReturns) {
  Eigen::MatrixXd m1(3, 3), m2(3, 3);
  m1 << 0.99999999999999922, 4, -9.7220978903564073e-16, -1.3257406214122369e-15, 3.9999999999999996,
      -4.0927849978099396e-17, -3.0000000000000004, -1.7676541618829827e-15, 7.9544437284734292e-16;
  m2 << 4.9999999999999982, 3.9999999999999987, -3, 3.9999999999999987, 4.9999999999999991, 3.1260298239849781e-16,
      -3, 3.1260298239849781e-16, 9.0000000000000036;
  Eigen::VectorXcd alphas;
  Eigen::VectorXd betas;
  if (!generalized_eigenvalues(m1, m2, alphas, betas)) SUCCEED() << "no convergence, reported";
  else
    for (Eigen::Index i = 0; i < alphas.size(); ++i) {
      const Eigen::MatrixXcd pencil = betas(i) * m1.cast<std::complex<double>>() - alphas(i) * m2.cast<std::complex<double>>();
      EXPECT_LT(std::abs(pencil.determinant()), 1e-10 * (m1.norm() + m2.norm()));
    }
}

}  // namespace
}  // namespace bezinv::detail
