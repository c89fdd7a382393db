// Compiles batch/null_vector-inl.hpp once per instruction set for the seed kernel on Bezout
// matrices formed from a plan's coefficients (Implementation::bezout_null_vector_seed,
// batch/matrix_source-inl.hpp), in its own translation unit: compiled without contraction, as
// bezout_matrix.cpp is, so that the entries it forms are that kernel's bits; and beside
// null_vector_seed.cpp, so that the two compile in parallel.
#include "batch/targets.hpp"
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/bezout_null_vector_seed.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
// clang-format on
#include <hwy/highway.h>

#include "batch/adjugate_null_vector-inl.hpp"
#include "batch/matrix_source-inl.hpp"
#include "batch/null_vector-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {

void bezout_null_vector_seed_batch(int n, std::size_t count, std::size_t stride, const double* B0, const double* Bx,
                                   const double* By, const double* Bxy, const double* u, const double* v, double* z,
                                   double* defect, double* residual, double* poison) {
  const BezoutMatrices source{B0, Bx, By, Bxy, u, v, poison};
  if (n == 3) return adjugate::seed<kWideVectors<3>>(count, stride, source, z, defect, residual);
  dispatch_size(n, [&](auto size) {
    null_vector_fixed<decltype(size)::value, false>(count, stride, source, z, defect, residual, nullptr);
  });
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "batch/kernels.hpp"
#include "batch/per_target.hpp"

namespace bezinv::kernels::batch {

BezoutNullVectorSeedKernel bezout_null_vector_seed_kernel(std::int64_t target) {
  return for_target<BezoutNullVectorSeedKernel>(target, BEZINV_PER_TARGET(bezout_null_vector_seed_batch));
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
