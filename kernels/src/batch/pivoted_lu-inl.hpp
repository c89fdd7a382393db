// PA = LU with partial pivoting, one matrix per lane, every lane with its own pivot rows: the
// factorization of null_vector (the fast path's kernel with the gap). Solved by
// triangular_substitution-inl.hpp. Re-included once per instruction set by hwy/foreach_target.h
// (see null_vector.cpp).
#if defined(BEZINV_KERNELS_BATCH_PIVOTED_LU_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_PIVOTED_LU_INL_H_
#undef BEZINV_KERNELS_BATCH_PIVOTED_LU_INL_H_
#else
#define BEZINV_KERNELS_BATCH_PIVOTED_LU_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>

#include "batch/constants.hpp"
#include "batch/wide-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
namespace hn = wide;

template <int N, class D>
struct PivotedLu {
  static constexpr std::size_t L = hn::MaxLanes(D());
  static constexpr bool kLowerOnly = false;        // factor() needs the whole matrix
  static constexpr bool kRowInterchanges = true;   // P, as pivot_row
  static constexpr bool kSeparateDiagonal = false; // U's diagonal is its own (1 / u_kk in inv_pivot)
  HWY_ALIGN double lu[N * N * L];     // unit L below the diagonal, U on and above
  HWY_ALIGN double inv_pivot[N * L];  // 1 / u_kk
  HWY_ALIGN double pivot_row[N * L];  // row swapped with row k at step k (as a double, for selects)

  double* at(int r, int c) { return lu + (r * N + c) * L; }
  const double* lower(int i, int k) const { return lu + (i * N + k) * L; }  // L(i, k), i > k
  const double* upper(int i, int k) const { return lu + (i * N + k) * L; }  // U(i, k), i < k

  void factor(D d) {
    // A pivot that is 0 (the matrix is singular by design) or below eps ||B|| (= eps here, B being
    // normalised) is rounding noise: replace it by +-eps so that the solves amplify the null
    // direction by ~1/eps instead of dividing by zero. This is exactly what inverse iteration wants.
    const auto tiny = hn::Set(d, batch::kEpsilon);
    for (int k = 0; k < N; ++k) {
      auto best = hn::Abs(hn::Load(d, at(k, k)));
      auto best_row = hn::Set(d, static_cast<double>(k));
      for (int i = k + 1; i < N; ++i) {
        const auto v = hn::Abs(hn::Load(d, at(i, k)));
        const auto larger = hn::Gt(v, best);
        best = hn::IfThenElse(larger, v, best);
        best_row = hn::IfThenElse(larger, hn::Set(d, static_cast<double>(i)), best_row);
      }
      hn::Store(best_row, d, pivot_row + k * L);
      // Swap rows k and best_row lane by lane (whole rows, so the multipliers move along, as in LAPACK).
      for (int i = k + 1; i < N; ++i) {
        const auto swap = hn::Eq(best_row, hn::Set(d, static_cast<double>(i)));
        if (hn::AllFalse(d, swap)) continue;
        for (int j = 0; j < N; ++j) {
          const auto a = hn::Load(d, at(k, j));
          const auto b = hn::Load(d, at(i, j));
          hn::Store(hn::IfThenElse(swap, b, a), d, at(k, j));
          hn::Store(hn::IfThenElse(swap, a, b), d, at(i, j));
        }
      }
      auto pivot = hn::Load(d, at(k, k));
      pivot = hn::IfThenElse(hn::Le(hn::Abs(pivot), tiny), hn::CopySign(tiny, pivot), pivot);
      hn::Store(pivot, d, at(k, k));
      const auto inv = hn::Div(hn::Set(d, 1.0), pivot);
      hn::Store(inv, d, inv_pivot + k * L);
      for (int i = k + 1; i < N; ++i) {
        const auto l = hn::Mul(hn::Load(d, at(i, k)), inv);
        hn::Store(l, d, at(i, k));
        for (int j = k + 1; j < N; ++j) hn::Store(hn::NegMulAdd(l, hn::Load(d, at(k, j)), hn::Load(d, at(i, j))), d, at(i, j));
      }
    }
  }
};

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_PIVOTED_LU_INL_H_
