#pragma once
// The degree limits of the engine and of the kernels it calls, tied together at compile time: a
// change to one that the others do not follow does not build. Past kMaxDegree a curve is refused
// by validate() (bezinv/curve.hpp) with its degree and the limit; a kernel called with a size it
// was not compiled for throws std::out_of_range naming itself and its sizes.
#include "bezinv/kernels/batch.hpp"
#include "bezinv/kernels/symmetric_svd.hpp"
#include "bezinv/tolerances.hpp"
#include "pipeline/fast_path.hpp"

namespace bezinv::detail {

// The SVD path: B's read-out and formation at every degree; the single-matrix SVD above the
// lane-batched one's degrees.
static_assert(kMaxDegree == kernels::kMaxBatchSize, "the batched kernels must take every degree bezinv accepts");
static_assert(kMaxDegree <= kernels::kMaxSize, "the single-matrix SVD must take every degree bezinv accepts");
// The lane-batched Jacobi kernel is compiled for exactly the degrees it is given.
static_assert(kLaneBatchedSvdMaxDegree == kernels::kSymmetricSvdMaxSize,
              "kernels::kSymmetricSvdMaxSize must be the largest n the engine gives the lane-batched SVD");
// The fast path's kernels.
static_assert(kFastPathMaxDegree <= kMaxDegree && kFastPathMaxDegree <= kernels::kMaxBatchSize,
              "the fast path's kernels must take every degree it is used at");
static_assert(kFormedBMinDegree >= 4 && kFormedBMinDegree <= kFastPathMaxDegree,
              "the seed on stored B covers 4 .. kFormedBMinDegree - 1 (3 is the adjugate)");

}  // namespace bezinv::detail
