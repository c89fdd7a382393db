#pragma once
// Singular value decomposition of a small dense symmetric matrix, one at a time (Eigen): the
// engine's SVD above the sizes of the lane-batched one (bezinv/kernels/batch.hpp).
//
// For symmetric B = Q diag(lambda) Q^T, the SVD is B = Q diag(|lambda|) (Q diag(sign lambda))^T, so
// the singular values are |lambda| and the right singular vectors are the eigenvectors. The
// eigendecomposition is cheaper and, for symmetric input, as accurate.
#include <span>

namespace bezinv::kernels {

// Largest n the kernels take (the engine's kMaxDegree); sizes are fixed at compile time so a call
// allocates nothing.
inline constexpr int kMaxSize = 32;

// B: n x n row-major, symmetric (only the lower triangle is read). Writes sigma (n values,
// descending) and V (n x n, column-major: column k is the right singular vector of sigma[k]).
void symmetric_svd(int n, std::span<const double> B, std::span<double> sigma, std::span<double> V);

}  // namespace bezinv::kernels
