#include "formula/null_space.hpp"

#include <Eigen/SVD>
#include <algorithm>

namespace bezinv::detail {

NullSpace null_space(const Eigen::MatrixXd& a, int dimension) {
  // Divide and conquer: these systems reach ~2000 x 1000, where one-sided Jacobi takes seconds.
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
  const Eigen::VectorXd& sigma = svd.singularValues();  // min(rows, cols), descending
  const auto cols = a.cols(), count = sigma.size();
  const double largest = count > 0 ? sigma(0) : 0.0;
  auto ratio = [&](Eigen::Index k) { return k < count && largest > 0.0 ? sigma(k) / largest : 0.0; };
  NullSpace out;
  out.basis = svd.matrixV().rightCols(dimension);
  out.null_ratio = ratio(cols - dimension);
  out.next_ratio = cols - dimension - 1 >= 0 ? ratio(cols - dimension - 1) : 1.0;
  if (largest == 0.0) out.next_ratio = 0.0;  // a zero matrix: every direction is null
  return out;
}

Eigen::VectorXd largest_right_singular_vector(const Eigen::MatrixXd& a) {
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
  return svd.matrixV().col(0);
}

}  // namespace bezinv::detail
