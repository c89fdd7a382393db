// Compiles batch/null_vector-inl.hpp once per instruction set and exports the seed kernels (L D L^T
// without pivoting, batch/ldlt-inl.hpp, no gap; at n = 3 the adjugate, adjugate_null_vector-inl.hpp):
// null_vector_seed on stored matrices, and bezout_null_vector_seed on Bezout matrices it forms
// itself (batch/matrix_source-inl.hpp). Both in this one translation unit, so that the
// factorizations and solves of the sizes they share are compiled once; the file is compiled
// without contraction, as bezout_matrix.cpp is, so that the entries the second
// forms are that kernel's bits (the seed's own arithmetic is written with explicit fused
// multiply-adds, so contraction changes nothing else). null_vector.cpp exports the pivoted kernel.
#include "batch/targets.hpp"
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/null_vector_seed.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
// clang-format on
#include <hwy/highway.h>

#include "batch/adjugate_null_vector-inl.hpp"
#include "batch/matrix_source-inl.hpp"
#include "batch/null_vector-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {

// The seed of every lane's matrix from `source` (matrix_source-inl.hpp): the adjugate at n = 3,
// L D L^T without pivoting above.
template <int N, class Source>
void seed(std::size_t count, std::size_t stride, const Source& source, double* z, double* defect, double* residual) {
  if constexpr (N == 3)
    adjugate::seed<kWideVectors<3>>(count, stride, source, z, defect, residual);
  else
    null_vector_fixed<N, false>(count, stride, source, z, defect, residual, nullptr);
}

void null_vector_seed_batch(int n, std::size_t count, std::size_t stride, const double* B, double* z,
                            double* defect, double* residual) {
  dispatch_size<kNullVectorSeedMinSize, kNullVectorSeedMaxSize>("null_vector_seed", n, [&](auto size) {
    seed<decltype(size)::value>(count, stride, StoredMatrices{B}, z, defect, residual);
  });
}

void bezout_null_vector_seed_batch(int n, std::size_t count, std::size_t stride, const double* B0, const double* Bx,
                                   const double* By, const double* Bxy, const double* u, const double* v, double* z,
                                   double* defect, double* residual, double* poison) {
  dispatch_size<kBezoutNullVectorSeedMinSize, kBezoutNullVectorSeedMaxSize>(
      "bezout_null_vector_seed", n, [&](auto size) {
        constexpr int N = decltype(size)::value;
        // One denominator (Bxy null): B is affine in (u, v), see matrix_source-inl.hpp.
        if (Bxy == nullptr)
          seed<N>(count, stride, BezoutMatrices<false>{B0, Bx, By, Bxy, u, v, poison}, z, defect, residual);
        else
          seed<N>(count, stride, BezoutMatrices<true>{B0, Bx, By, Bxy, u, v, poison}, z, defect, residual);
      });
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "batch/kernels.hpp"
#include "batch/per_target.hpp"

namespace bezinv::kernels::batch {

NullVectorSeedKernel null_vector_seed_kernel(std::int64_t target) {
  return for_target<NullVectorSeedKernel>(target, BEZINV_PER_TARGET(null_vector_seed_batch));
}

BezoutNullVectorSeedKernel bezout_null_vector_seed_kernel(std::int64_t target) {
  return for_target<BezoutNullVectorSeedKernel>(target, BEZINV_PER_TARGET(bezout_null_vector_seed_batch));
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
