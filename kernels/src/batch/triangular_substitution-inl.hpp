// x <- A^{-1} x for a factored A (PivotedLu: PA = LU; Ldlt: A = L D L^T), one matrix per lane:
// the row interchanges, forward substitution with the unit lower triangle, backward substitution
// with the upper factor. One function for both factorizations, so that the solves of the
// null-vector kernels are written once. Re-included once per instruction set by
// hwy/foreach_target.h (see null_vector.cpp).
#if defined(BEZINV_KERNELS_BATCH_TRIANGULAR_SUBSTITUTION_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_TRIANGULAR_SUBSTITUTION_INL_H_
#undef BEZINV_KERNELS_BATCH_TRIANGULAR_SUBSTITUTION_INL_H_
#else
#define BEZINV_KERNELS_BATCH_TRIANGULAR_SUBSTITUTION_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>

#include "batch/wide-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
namespace hn = wide;

// Whether the substitutions are written out (every loop unrolled): only then does GCC keep x in
// registers instead of storing and reloading it at every update. On the SIMD targets up to n = 24;
// above, N vectors do not fit in the registers anyway, and writing them out costs compile time.
template <int N>
inline constexpr bool kUnrolledSolve = HWY_TARGET != HWY_SCALAR && HWY_TARGET != HWY_EMU128 && N <= 24;

// for (i = begin; i < end; ++i) f(i), every iteration written out when kUnroll. (The unroll
// pragma cannot take a template-dependent count: GCC 12 crashes.)
template <bool kUnroll, class F>
HWY_INLINE void each(int begin, int end, F&& f) {
  if constexpr (kUnroll) {
#pragma GCC unroll 32
    for (int i = begin; i < end; ++i) f(i);
  } else {
    for (int i = begin; i < end; ++i) f(i);
  }
}

// The substitutions for lanes g .. g + MaxLanes(d) - 1 of the factors' group, d one native vector
// (a wide group's G x N vectors would not fit in the registers; the G of them still overlap in
// the out-of-order window). Column-oriented: each x_k, once final, is subtracted from the
// components after it (forward) or before it (backward), so that the updates of one column are
// independent and the critical path is N steps, not the N^2 / 2 of row-by-row dot products.
//   PivotedLu (U with its diagonal):  x_k <- x_k / u_kk before column k updates the rest;
//   Ldlt (L^T, unit diagonal):        x <- D^{-1} x first, then the columns of L^T.
template <int N, class Factors>
HWY_INLINE void substitute(wide::Tag<1> d, const Factors& f, std::size_t g, double* HWY_RESTRICT x) {
  constexpr bool kUnroll = kUnrolledSolve<N>;
  constexpr std::size_t L = Factors::L;
  hn::Vec<wide::Tag<1>> v[N];
  each<kUnroll>(0, N, [&](int i) HWY_ATTR __attribute__((always_inline)) { v[i] = hn::Load(d, x + i * L + g); });
  if constexpr (Factors::kRowInterchanges) {  // x <- P x
    each<kUnroll>(0, N, [&](int k) HWY_ATTR __attribute__((always_inline)) {
      const auto row = hn::Load(d, f.pivot_row + k * L + g);
      each<kUnroll>(k + 1, N, [&](int i) HWY_ATTR __attribute__((always_inline)) {
        const auto swap = hn::Eq(row, hn::Set(d, static_cast<double>(i)));
        const auto a = v[k], b = v[i];
        v[k] = hn::IfThenElse(swap, b, a);
        v[i] = hn::IfThenElse(swap, a, b);
      });
    });
  }
  each<kUnroll>(0, N, [&](int k) HWY_ATTR __attribute__((always_inline)) {  // x <- L^{-1} x
    each<kUnroll>(k + 1, N, [&](int i) HWY_ATTR __attribute__((always_inline)) {
      v[i] = hn::NegMulAdd(hn::Load(d, f.lower(i, k) + g), v[k], v[i]);
    });
  });
  if constexpr (Factors::kSeparateDiagonal)  // x <- D^{-1} x
    each<kUnroll>(0, N, [&](int k) HWY_ATTR __attribute__((always_inline)) {
      v[k] = hn::Mul(v[k], hn::Load(d, f.inv_pivot + k * L + g));
    });
  each<kUnroll>(0, N, [&](int j) HWY_ATTR __attribute__((always_inline)) {  // x <- U^{-1} x, k = N-1 .. 0
    const int k = N - 1 - j;
    if constexpr (!Factors::kSeparateDiagonal) v[k] = hn::Mul(v[k], hn::Load(d, f.inv_pivot + k * L + g));
    each<kUnroll>(0, k, [&](int i) HWY_ATTR __attribute__((always_inline)) {
      v[i] = hn::NegMulAdd(hn::Load(d, f.upper(i, k) + g), v[k], v[i]);
    });
  });
  each<kUnroll>(0, N, [&](int i) HWY_ATTR __attribute__((always_inline)) { hn::Store(v[i], d, x + i * L + g); });
}

// x <- A^{-1} x for every lane of the factors' group D. Not inlined: one copy per size and group
// width instead of one per call site.
template <int N, class Factors, class D>
HWY_NOINLINE void solve(D, const Factors& factors, double* HWY_RESTRICT x) {
  constexpr std::size_t L1 = hn::MaxLanes(wide::Tag<1>());
  for (std::size_t g = 0; g < hn::MaxLanes(D()); g += L1) substitute<N>(wide::Tag<1>(), factors, g, x);
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_TRIANGULAR_SUBSTITUTION_INL_H_
