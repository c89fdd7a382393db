#pragma once
// The null space of a (numerically) rank-deficient matrix, of a dimension known in advance, from
// its singular value decomposition: the right singular vectors of the smallest singular values.
// Every SVD of the formulae is here, one instantiation of Eigen's (it is the slowest part of
// the engine to compile).
#include <Eigen/Core>

namespace bezinv::detail {

struct NullSpace {
  Eigen::MatrixXd basis;    // cols x dimension, orthonormal columns
  double null_ratio = 0.0;  // largest singular value of the null space / the largest (0 past the rows)
  double next_ratio = 1.0;  // the next one up / the largest: the gap that makes the dimension clear
};

// a: rows x cols, any shape; 1 <= dimension <= cols.
NullSpace null_space(const Eigen::MatrixXd& a, int dimension);

// The unit vector x maximizing |a x| (the right singular vector of the largest singular value).
Eigen::VectorXd largest_right_singular_vector(const Eigen::MatrixXd& a);

}  // namespace bezinv::detail
