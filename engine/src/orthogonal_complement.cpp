#include "orthogonal_complement.hpp"

#include <Eigen/QR>
#include <algorithm>

namespace bezinv::detail {

void orthogonal_complement(std::span<const double> r, std::span<double> basis) {
  const auto size = static_cast<Eigen::Index>(r.size());
  const Eigen::MatrixXd column = Eigen::Map<const Eigen::VectorXd>(r.data(), size);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(column);
  const Eigen::MatrixXd q = qr.householderQ();  // column-major: column 0 along r, then r^perp
  std::copy_n(q.data() + size, size * (size - 1), basis.begin());
}

}  // namespace bezinv::detail
