#pragma once
// The numbers that decide, for the lane-batched kernels (bezinv/kernels/batch.hpp), in one place.
#include <limits>

#include "bezinv/kernels/batch.hpp"

namespace bezinv::kernels::batch {

// Unit roundoff scale used by every tolerance below (2^-52).
inline constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// Cyclic Jacobi stops when, in every lane, off(A) <= kJacobiTolerance * ||A||_F (off = Frobenius
// norm of the strict off-diagonal part). Convergence is quadratic once off(A) is small
// (Golub & Van Loan, Sect. 8.5.3), so one more sweep after off ~ 1e-8 reaches the rounding level;
// rounding in a rotation only produces errors proportional to the (already tiny) off-diagonal
// entries, so this level is attainable. kJacobiMaxSweeps caps pathological lanes; in practice
// 6..9 sweeps are enough for n <= 32.
inline constexpr double kJacobiTolerance = kEpsilon;
inline constexpr int kJacobiMaxSweeps = 15;

// Inverse iteration for the null vector: iterations from (1, ..., 1). With a pivot of order
// eps ||B||, one iteration already damps the other directions by sigma_n / sigma_{n-1}; the next
// two are there to *measure* convergence (the defect).
inline constexpr int kInverseIterations = kNullVectorIterations;
// The seed (null_vector_seed) measures its settling over its last step alone, so two solves do:
// nothing trusts the seed (its caller checks what it refines to by other means), and the settling
// measure only spares the refinement lanes whose z has not converged.
inline constexpr int kSeedInverseIterations = 2;
// Inverse iterations orthogonal to the null vector, estimating 1 / sigma_{n-1} (the defect, and the
// engine's gate for answering without an SVD). They converge at the rate sigma_{n-1}/sigma_{n-2},
// so 2 can leave the estimate far too high; 8, with the Ritz value of the last two iterates
// (gap_estimate-inl.hpp), keep it within the engine's factor of 2 (docs/kernels.md). Each costs
// n^2, against n^3/3 for the factorization.
inline constexpr int kDeflatedIterations = 8;
// Except for n <= 3: the deflated space (orthogonal to z) then has dimension n - 1 <= 2, so the
// plane of the last two iterates is all of it (or they are parallel, at n = 2) and the Ritz value
// is exact after two iterations.
constexpr int deflated_iterations(int n) { return n <= 3 ? 2 : kDeflatedIterations; }
static_assert(deflated_iterations(1) >= 2 && kDeflatedIterations >= 2, "the Ritz value needs the last two iterates");

}  // namespace bezinv::kernels::batch
