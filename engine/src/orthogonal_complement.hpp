#pragma once
// An orthonormal basis of r^perp, the hyperplane orthogonal to a vector r: the last n - 1 columns
// of Q in the Householder QR of r as one column (Q's first column is along r). Eigen's QR, in a
// file of its own: instantiating it took most of the compile time of the file that needs it, and
// the sanitizer tree compiles it without instrumentation (it wraps Eigen only; engine/CMakeLists.txt).
#include <span>

namespace bezinv::detail {

// r: n >= 2 entries, not all zero. Writes the n - 1 basis vectors, each n long and one after the
// other, into basis (room for n (n - 1)).
void orthogonal_complement(std::span<const double> r, std::span<double> basis);

}  // namespace bezinv::detail
