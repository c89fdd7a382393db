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
static_assert(kernels::kSymmetricSvdMinSize <= 2, "the SVD path runs from degree 2");
static_assert(kernels::kBezoutMatrixMinSize <= 2 && kernels::kBezoutMatrixMaxSize >= kMaxDegree,
              "B is formed by the kernel at every degree from 2");
static_assert(kernels::kBernsteinParameterMinSize <= 2 && kernels::kBernsteinParameterMaxSize >= kMaxDegree,
              "t is read out by the kernel at every degree from 2");
// The fast path's kernels: degree 2 the pivoted kernel alone, 3 .. kFormedBMinDegree - 1 the seed
// on stored B, from kFormedBMinDegree the seed forming B; the gap pass and the refinement at all.
static_assert(kFastPathMaxDegree <= kMaxDegree, "the fast path runs at degrees bezinv accepts");
static_assert(kernels::kNullVectorMinSize <= 2 && kernels::kNullVectorMaxSize >= kFastPathMaxDegree,
              "the pivoted kernel (degree 2, the gap pass) must take every fast-path degree");
static_assert(kernels::kNullVectorSeedMinSize <= 3 && kernels::kNullVectorSeedMaxSize >= kFormedBMinDegree - 1,
              "the seed on stored B must take 3 .. kFormedBMinDegree - 1");
static_assert(kernels::kBezoutNullVectorSeedMinSize <= kFormedBMinDegree &&
                  kernels::kBezoutNullVectorSeedMaxSize >= kFastPathMaxDegree,
              "the seed forming B must take kFormedBMinDegree .. kFastPathMaxDegree");
static_assert(kernels::kRationalNewtonMinDegree <= 2 && kernels::kRationalNewtonMaxDegree >= kFastPathMaxDegree,
              "the lane-batched refinement must take every fast-path degree");

}  // namespace bezinv::detail
