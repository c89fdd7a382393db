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

// for (i = begin; i < end; ++i) f(i, args...), every iteration written out when kUnroll. (The
// unroll pragma cannot take a template-dependent count: GCC 12 crashes.) f captures nothing: what
// it works on comes as arguments, which become plain values once inlined, where a capture would
// be a field of the closure that the optimizer must trace through every store of the loop.
template <bool kUnroll, class F, class... Args>
HWY_INLINE void each(int begin, int end, F f, Args... args) {
  if constexpr (kUnroll) {
#pragma GCC unroll 32
    for (int i = begin; i < end; ++i) f(i, args...);
  } else {
    for (int i = begin; i < end; ++i) f(i, args...);
  }
}

// The loop bodies given to each(): inlined into the loop, so that the unroller sees the literal
// loops.
#ifndef BEZINV_LOOP_BODY
#define BEZINV_LOOP_BODY HWY_ATTR __attribute__((always_inline))
#endif

// The substitutions for lanes g .. g + MaxLanes(DN()) - 1 of the factors' group, DN one native
// vector (a wide group's G x N vectors would not fit in the registers; the G of them still
// overlap in the out-of-order window). Column-oriented: each x_k, once final, is subtracted from
// the components after it (forward) or before it (backward), so that the updates of one column
// are independent and the critical path is N steps, not the N^2 / 2 of row-by-row dot products.
//   PivotedLu (U with its diagonal):  x_k <- x_k / u_kk before column k updates the rest;
//   Ldlt (L^T, unit diagonal):        x <- D^{-1} x first, then the columns of L^T.
template <int N, class Factors, class DN>
HWY_INLINE void substitute(DN, const Factors& f, std::size_t g, double* HWY_RESTRICT x) {
  namespace hw = hwy::HWY_NAMESPACE;
  using V = hw::Vec<DN>;
  constexpr bool kUnroll = kUnrolledSolve<N>;
  constexpr std::size_t L = Factors::L;
  V v[N];
  each<kUnroll>(0, N, [](int i, V* v, const double* x) BEZINV_LOOP_BODY { v[i] = hw::Load(DN(), x + i * L); }, v,
                x + g);
  if constexpr (Factors::kRowInterchanges) {  // x <- P x
    each<kUnroll>(0, N, [](int k, V* v, const double* pivot_row) BEZINV_LOOP_BODY {
      const V row = hw::Load(DN(), pivot_row + k * L);
      each<kUnroll>(k + 1, N, [](int i, V* v, int k, V row) BEZINV_LOOP_BODY {
        const auto swap = hw::Eq(row, hw::Set(DN(), static_cast<double>(i)));
        const V a = v[k], b = v[i];
        v[k] = hw::IfThenElse(swap, b, a);
        v[i] = hw::IfThenElse(swap, a, b);
      }, v, k, row);
    }, v, f.pivot_row + g);
  }
  each<kUnroll>(0, N, [](int k, V* v, const Factors* f, std::size_t g) BEZINV_LOOP_BODY {  // x <- L^{-1} x
    each<kUnroll>(k + 1, N, [](int i, V* v, const Factors* f, std::size_t g, int k) BEZINV_LOOP_BODY {
      v[i] = hw::NegMulAdd(hw::Load(DN(), f->lower(i, k) + g), v[k], v[i]);
    }, v, f, g, k);
  }, v, &f, g);
  if constexpr (Factors::kSeparateDiagonal) {  // x <- D^{-1} x
    each<kUnroll>(0, N, [](int k, V* v, const double* inv_pivot) BEZINV_LOOP_BODY {
      v[k] = hw::Mul(v[k], hw::Load(DN(), inv_pivot + k * L));
    }, v, f.inv_pivot + g);
  }
  each<kUnroll>(0, N, [](int j, V* v, const Factors* f, std::size_t g) BEZINV_LOOP_BODY {  // x <- U^{-1} x
    const int k = N - 1 - j;  // columns k = N-1 .. 0
    if constexpr (!Factors::kSeparateDiagonal) v[k] = hw::Mul(v[k], hw::Load(DN(), f->inv_pivot + k * L + g));
    each<kUnroll>(0, k, [](int i, V* v, const Factors* f, std::size_t g, int k) BEZINV_LOOP_BODY {
      v[i] = hw::NegMulAdd(hw::Load(DN(), f->upper(i, k) + g), v[k], v[i]);
    }, v, f, g, k);
  }, v, &f, g);
  each<kUnroll>(0, N, [](int i, const V* v, double* x) BEZINV_LOOP_BODY { hw::Store(v[i], DN(), x + i * L); }, v,
                x + g);
}

// x <- A^{-1} x for every lane of the factors' group D. Not inlined: one copy per size and group
// width instead of one per call site.
template <int N, class Factors, class D>
HWY_NOINLINE void solve(D, const Factors& factors, double* HWY_RESTRICT x) {
  using DN = typename D::D;  // the native vector of the wide group
  constexpr std::size_t L1 = hwy::HWY_NAMESPACE::MaxLanes(DN());
  for (std::size_t g = 0; g < hn::MaxLanes(D()); g += L1) substitute<N>(DN(), factors, g, x);
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_TRIANGULAR_SUBSTITUTION_INL_H_
