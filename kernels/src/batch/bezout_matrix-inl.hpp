// Lane-batched Bezout matrices B(u, v) = B0 - u Bx - v By + (u v) Bxy, one point per lane
// (bezinv/kernels/batch.hpp, Implementation::bezout_matrix). Re-included once per instruction set
// by hwy/foreach_target.h (see bezout_matrix.cpp).
//
// Each entry is computed as the engine writes it (bezout_at), ((B0 - u Bx) - v By) + (u v) Bxy, or
// without the last term for one denominator (Bxy null), without fused multiply-add (the file is
// compiled with -ffp-contract=off): the same bits on every instruction set.
#if defined(BEZINV_KERNELS_BATCH_BEZOUT_MATRIX_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_BEZOUT_MATRIX_INL_H_
#undef BEZINV_KERNELS_BATCH_BEZOUT_MATRIX_INL_H_
#else
#define BEZINV_KERNELS_BATCH_BEZOUT_MATRIX_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>

#include "batch/matrix_source-inl.hpp"
#include "batch/sizes-inl.hpp"
#include "batch/wide-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {

// B for one group of lanes (G SIMD vectors) from `source`, the entries formed by GroupMatrix, the
// one place that writes their expression (the seed kernel forms them there too). Whole vectors are
// stored: rows are `stride` long, a multiple of kBatchAlignment >= the vector's lanes. poison: the
// sum of entry * 0 (NaN once an entry is not finite, +0 otherwise, in any order of the sum), one
// partial sum per row added to the total at the row's end: a single running sum was one
// dependent add per entry, the kernel's critical path (BM_KernelBezoutMatrix).
template <int G, class Source>
HWY_INLINE void bezout_matrix_group(int n, std::size_t stride, std::size_t first, std::size_t lanes,
                                    const Source& source, double* B) {
  const wide::Tag<G> d;
  const GroupMatrix<Source, wide::Tag<G>> matrix(d, source, stride, first, lanes);
  const auto zero = wide::Zero(d);
  auto sum = zero;
  for (int r = 0; r < n; ++r) {
    auto row = zero;
    for (int c = 0; c <= r; ++c) {  // the lower triangle: the kernels read nothing else
      const std::size_t i = static_cast<std::size_t>(r * n + c);
      const auto e = matrix.entry(i);
      wide::StoreU(e, d, B + i * stride + first);  // B need not be vector-aligned
      row = wide::Add(row, wide::Mul(e, zero));
    }
    sum = wide::Add(sum, row);
  }
  matrix.write_poison(sum);
}

template <class Source>
void bezout_matrix_groups(int n, std::size_t count, std::size_t stride, const Source& source, double* B) {
  constexpr std::size_t L2 = wide::MaxLanes(wide::Tag<2>()), L1 = wide::MaxLanes(wide::Tag<1>());
  std::size_t first = 0;
  // Two vectors at a time where the batch has them whole: each coefficient is broadcast once for
  // both (the broadcasts are loads, and were two thirds of the loads); then one at a time.
  for (; first + L2 <= count; first += L2) bezout_matrix_group<2>(n, stride, first, L2, source, B);
  for (; first < count; first += L1) bezout_matrix_group<1>(n, stride, first, std::min(L1, count - first), source, B);
}

void bezout_matrix_batch(int n, std::size_t count, std::size_t stride, const double* B0, const double* Bx,
                         const double* By, const double* Bxy, const double* u, const double* v, double* B,
                         double* poison) {
  check_size<kBezoutMatrixMinSize, kBezoutMatrixMaxSize>("bezout_matrix", n);
  if (Bxy == nullptr) return bezout_matrix_groups(n, count, stride, BezoutMatrices<false>{B0, Bx, By, Bxy, u, v, poison}, B);
  bezout_matrix_groups(n, count, stride, BezoutMatrices<true>{B0, Bx, By, Bxy, u, v, poison}, B);
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_BEZOUT_MATRIX_INL_H_
