// Lane-batched null vector by LU with partial pivoting and inverse iteration, one matrix per lane.
// Re-included once per instruction set by hwy/foreach_target.h (see null_vector.cpp).
#if defined(BEZINV_KERNELS_BATCH_NULL_VECTOR_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_NULL_VECTOR_INL_H_
#undef BEZINV_KERNELS_BATCH_NULL_VECTOR_INL_H_
#else
#define BEZINV_KERNELS_BATCH_NULL_VECTOR_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <type_traits>

#include "batch/constants.hpp"
#include "batch/matrix_source-inl.hpp"
#include "batch/sizes-inl.hpp"
#include "batch/wide-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
// Highway's operations on wide vectors (batch/wide-inl.hpp): D is a wide::Tag<G>, G vectors of
// lanes processed side by side.
namespace hn = wide;

// PA = LU of the (Frobenius-normalised) matrix, every lane with its own pivot rows.
// The solve is written out (LaneLu::solve_unrolled) on the SIMD targets for n <= 24. Beyond, and
// for the scalar target, its loops stay rolled: writing out n = 25..32 too took this file from 1 to
// 4 min to compile (CI's budget), for sizes whose N vectors do not fit in the registers anyway.
template <int N>
inline constexpr bool kUnrolledSolve = HWY_TARGET != HWY_SCALAR && HWY_TARGET != HWY_EMU128 && N <= 24;

// f(DN(), g) for each native vector DN of the wide group D, lanes g .. g + MaxLanes(DN()) - 1 (the
// written-out solves work one native vector at a time, see LaneLu::solve_unrolled).
template <class D, class F>
HWY_INLINE void for_each_native_vector(D, F&& f) {
  using DN = typename D::D;
  constexpr std::size_t L = hn::MaxLanes(D()), L1 = hwy::HWY_NAMESPACE::MaxLanes(DN());
  for (std::size_t g = 0; g < L; g += L1) f(DN(), g);
}

// v <- L^{-1} v for the unit lower triangle L of a factorization (entries at(i, k), i > k),
// column-oriented: each v_k, once final, is subtracted from the components after it.
template <int N, class D, class At>
HWY_INLINE void forward_substitution(D d, At at, hn::Vec<D>* v) {
  for (int k = 0; k < N; ++k)
    for (int i = k + 1; i < N; ++i) v[i] = hn::NegMulAdd(hn::Load(d, at(i, k)), v[k], v[i]);
}

template <int N, class D>
struct LaneLu {
  static constexpr std::size_t L = hn::MaxLanes(D());
  static constexpr bool kLowerOnly = false;
  HWY_ALIGN double lu[N * N * L];        // unit L below the diagonal, U on and above
  HWY_ALIGN double inv_pivot[N * L];     // 1 / u_kk
  HWY_ALIGN double pivot_row[N * L];     // row swapped with row k at step k (as a double, for selects)

  double* at(int r, int c) { return lu + (r * N + c) * L; }

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

  // x <- U^{-1} L^{-1} P x. Column-oriented (each x_k, once final, is subtracted from all the
  // components after or before it) with x held in registers: the updates of one column are
  // independent, so the critical path is N steps instead of the N^2 / 2 of row-by-row dot products
  // (measured: the kernel 1.3-1.5x faster at n = 8..15).
  // Not inlined: one copy per size and group width instead of one per call site (compile time 2.5
  // -> 1.1 min for this file, speed unchanged).
  HWY_NOINLINE void solve(D d, double* HWY_RESTRICT x) {
    if constexpr (kUnrolledSolve<N>) {
      for_each_native_vector(d, [&](auto dn, std::size_t g) { solve_unrolled(dn, g, x); });
    } else {
      hn::Vec<D> v[N];
      for (int i = 0; i < N; ++i) v[i] = hn::Load(d, x + i * L);
      for (int k = 0; k < N; ++k) {
        const auto row = hn::Load(d, pivot_row + k * L);
        for (int i = k + 1; i < N; ++i) {
          const auto swap = hn::Eq(row, hn::Set(d, static_cast<double>(i)));
          const auto a = v[k], b = v[i];
          v[k] = hn::IfThenElse(swap, b, a);
          v[i] = hn::IfThenElse(swap, a, b);
        }
      }
      forward_substitution<N>(d, [&](int i, int k) { return at(i, k); }, v);
      for (int k = N - 1; k >= 0; --k) {
        v[k] = hn::Mul(v[k], hn::Load(d, inv_pivot + k * L));
        for (int i = 0; i < k; ++i) v[i] = hn::NegMulAdd(hn::Load(d, at(i, k)), v[k], v[i]);
      }
      for (int i = 0; i < N; ++i) hn::Store(v[i], d, x + i * L);
    }
  }

  // The same solve written out (every loop unrolled), one native vector (lanes g..g+L1-1) at a
  // time: only then does GCC keep v in registers. Rolled, v lives on the stack and every update is
  // a store and a reload (perf: the solve was bound by those stores); written out, the kernel is
  // 1.3-1.55x faster at n = 5..24 on AVX-512 and on AVX2 (1.07x at n = 3), with the same bits. A
  // wide group's G x N vectors would not fit in the registers, hence one native vector at a time
  // (the G of them still overlap in the out-of-order window). The pragma cannot take a
  // template-dependent count (GCC 12 crashes), hence two copies of the loops.
  template <class DN>
  HWY_INLINE void solve_unrolled(DN d, std::size_t g, double* HWY_RESTRICT x) {
    namespace hw = hwy::HWY_NAMESPACE;
    hw::Vec<DN> v[N];
#pragma GCC unroll 32
    for (int i = 0; i < N; ++i) v[i] = hw::Load(d, x + i * L + g);
#pragma GCC unroll 32
    for (int k = 0; k < N; ++k) {
      const auto row = hw::Load(d, pivot_row + k * L + g);
#pragma GCC unroll 32
      for (int i = k + 1; i < N; ++i) {
        const auto swap = hw::Eq(row, hw::Set(d, static_cast<double>(i)));
        const auto a = v[k], b = v[i];
        v[k] = hw::IfThenElse(swap, b, a);
        v[i] = hw::IfThenElse(swap, a, b);
      }
    }
#pragma GCC unroll 32
    for (int k = 0; k < N; ++k) {
#pragma GCC unroll 32
      for (int i = k + 1; i < N; ++i) v[i] = hw::NegMulAdd(hw::Load(d, at(i, k) + g), v[k], v[i]);
    }
#pragma GCC unroll 32
    for (int k = N - 1; k >= 0; --k) {
      v[k] = hw::Mul(v[k], hw::Load(d, inv_pivot + k * L + g));
#pragma GCC unroll 32
      for (int i = 0; i < k; ++i) v[i] = hw::NegMulAdd(hw::Load(d, at(i, k) + g), v[k], v[i]);
    }
#pragma GCC unroll 32
    for (int i = 0; i < N; ++i) hw::Store(v[i], d, x + i * L + g);
  }
};

// B = L D L^T without pivoting, every lane alike (the seed kernel, null_vector_seed): unit L below
// the diagonal, D as 1 / d_k in inv_pivot, from B's lower triangle (B's upper is never read; the factorization keeps
// its undivided multipliers there). n^3 / 6 multiply-adds
// against LU's n^3 / 3, and no per-lane row swaps, which took half of the LU's time (the
// factorization alone, measured: 2.4x faster at n = 8, 3x at n = 15).
// Why no pivoting is good enough here. Without pivoting L D L^T = B + E with ||E|| ~ eps times the
// growth of the entries, which a small pivot d_k makes large (1 / d_k); the null vector of B is
// then a null vector of L D L^T up to ||E|| / sigma_{n-1}, and inverse iteration converges to it as
// with pivoting while that stays small. On Bezout matrices of on-curve points of random curves
// (degrees 3-20, both kinds, perturbed arcs and unit squares, 4,096 points each, B normalised) the
// least pivot before the last was 5e-12 and the 1st percentile 5e-7 to 2e-5, and Newton from every
// one of the 81,920 seeds refined to the point's true parameter. Where the seed is poor anyway, it
// costs time, not answers: the engine checks what it makes of the seed on its own (the isolation
// certificate), and every lane it cannot settle that way goes on to null_vector, pivoted, or to
// the SVD.
template <int N, class D>
struct LaneLdl {
  static constexpr std::size_t L = hn::MaxLanes(D());
  static constexpr bool kLowerOnly = true;  // reads B's lower triangle only
  HWY_ALIGN double lu[N * N * L];           // unit L below the diagonal; above it, L D undivided
                                            // (c_jk at (k, j)); the diagonal is not rewritten
  HWY_ALIGN double inv_pivot[N * L];        // 1 / d_k

  double* at(int r, int c) { return lu + (r * N + c) * L; }

  // Crout order: column j of L D is b_ij - sum_{k<j} l_ik c_jk (i >= j), c_jk = l_jk d_k the
  // undivided multiplier, kept in the upper triangle at (k, j) where the solves never look. Each
  // entry takes the updates of the steps k in ascending order, as in the right-looking order
  // (a_ij <- a_ij - l_ik c_jk at step k) this replaced: the same operations, so the same bits
  // (checked on every size and implementation against the earlier kernel's output).
  // Why Crout: the right-looking update loaded and stored every entry of the trailing triangle
  // at every step (3 loads and a store per 2 multiply-adds, two steps at a time); here a tile of
  // kTileRows rows x 2 columns stays in registers for all its k (6 loads per 8 multiply-adds at
  // 4 rows, one store per entry), and the wide group's G vectors interleave their dependency
  // chains (the pivots' divisions, each diagonal entry's sum). BM_KernelBezoutSeed_formed,
  // AVX-512, medians of 4-5 alternating runs: 1.0x at n = 5, 1.17x at 8, 1.15x at 12, 1.05x at
  // 15, 1.02-1.11x at 20, 1.19x at 24 (BENCHMARKS.md, ninth session).
  static constexpr int kTileRows = D::kVectors >= 4 ? 2 : 4;  // 4 vectors: 2 rows, or spills

  // B = L D L^T for B = scale times the lower triangle stored in lu (each entry is loaded once,
  // at the start of its tile, and scaled there).
  void factor(D d, hn::Vec<D> scale) {
    int j = 0;
    for (; j + 1 < N; j += 2) column_pair<true>(d, j, scale);
    if (j < N) column_pair<false>(d, j, scale);  // odd N: the last column alone
  }

  // Columns j and j + 1 (kPair; else column j alone): the diagonal rows first (row j gives d_j;
  // row j + 1 gives c_{j+1,j}, then, after step j, d_{j+1}), then the rows below in tiles.
  template <bool kPair>
  HWY_INLINE void column_pair(D d, int j, hn::Vec<D> scale) {
    constexpr int kHead = kPair ? 2 : 1;
    hn::Vec<D> a[kHead][2];
    tile_sums<kHead, kPair, true>(d, j, j, scale, a);
    const auto inv = pivot_inverse(d, j, a[0][0]);
    hn::Vec<D> c_next = hn::Zero(d), inv_next = hn::Zero(d);
    if constexpr (kPair) {
      c_next = a[1][0];
      hn::Store(c_next, d, at(j, j + 1));
      const auto l = hn::Mul(c_next, inv);
      hn::Store(l, d, at(j + 1, j));
      inv_next = pivot_inverse(d, j + 1, hn::NegMulAdd(l, c_next, a[1][1]));
    }
    int i0 = j + kHead;
    for (; i0 + kTileRows <= N; i0 += kTileRows) tile<kTileRows, kPair>(d, i0, j, scale, inv, c_next, inv_next);
    // The last rows one at a time: tiles of every height in between cost compile time (CI's
    // budget) for no measured speed.
    for (; i0 < N; ++i0) tile<1, kPair>(d, i0, j, scale, inv, c_next, inv_next);
  }

  // Rows i0 .. i0 + R - 1 of columns j (and j + 1): the stored entries times scale, every step
  // k < j applied. kHead: the rows j and j + 1, whose (j, j + 1) is not in the lower triangle (0
  // here, and unused).
  template <int R, bool kPair, bool kHead = false>
  HWY_INLINE void tile_sums(D d, int i0, int j, hn::Vec<D> scale, hn::Vec<D> (&a)[R][2]) {
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      a[r][0] = hn::Mul(hn::Load(d, at(i0 + r, j)), scale);
      if constexpr (kPair)
        a[r][1] = kHead && r == 0 ? hn::Zero(d) : hn::Mul(hn::Load(d, at(i0 + r, j + 1)), scale);
    }
    for (int k = 0; k < j; ++k) {
      const auto c = hn::Load(d, at(k, j));
      hn::Vec<D> c2;
      if constexpr (kPair) c2 = hn::Load(d, at(k, j + 1));
#pragma GCC unroll 8
      for (int r = 0; r < R; ++r) {
        const auto l = hn::Load(d, at(i0 + r, k));
        a[r][0] = hn::NegMulAdd(l, c, a[r][0]);
        if constexpr (kPair) a[r][1] = hn::NegMulAdd(l, c2, a[r][1]);
      }
    }
  }

  // Rows i0 .. i0 + R - 1, all below the pair's diagonal rows: their sums, then column j's c and
  // l, step j on column j + 1, and its c and l.
  template <int R, bool kPair>
  HWY_INLINE void tile(D d, int i0, int j, hn::Vec<D> scale, hn::Vec<D> inv, hn::Vec<D> c_next,
                       hn::Vec<D> inv_next) {
    hn::Vec<D> a[R][2];
    tile_sums<R, kPair>(d, i0, j, scale, a);
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      const int i = i0 + r;
      hn::Store(a[r][0], d, at(j, i));
      const auto l = hn::Mul(a[r][0], inv);
      hn::Store(l, d, at(i, j));
      if constexpr (kPair) {
        const auto c = hn::NegMulAdd(l, c_next, a[r][1]);
        hn::Store(c, d, at(j + 1, i));
        hn::Store(hn::Mul(c, inv_next), d, at(i, j + 1));
      }
    }
  }

  // 1 / d_k for the pivot d_k, guarded as LaneLu's pivots are (below eps ||B|| -> +-eps); also
  // stored in inv_pivot.
  HWY_INLINE hn::Vec<D> pivot_inverse(D d, int k, hn::Vec<D> pivot) {
    const auto tiny = hn::Set(d, batch::kEpsilon);
    pivot = hn::IfThenElse(hn::Le(hn::Abs(pivot), tiny), hn::CopySign(tiny, pivot), pivot);
    const auto inv = hn::Div(hn::Set(d, 1.0), pivot);
    hn::Store(inv, d, inv_pivot + k * L);
    return inv;
  }

  // x <- L^{-T} D^{-1} L^{-1} x, column-oriented as LaneLu::solve (and written out the same way
  // on the SIMD targets, see there).
  HWY_NOINLINE void solve(D d, double* HWY_RESTRICT x) {
    if constexpr (kUnrolledSolve<N>) {
      for_each_native_vector(d, [&](auto dn, std::size_t g) { solve_unrolled(dn, g, x); });
    } else {
      hn::Vec<D> v[N];
      for (int i = 0; i < N; ++i) v[i] = hn::Load(d, x + i * L);
      forward_substitution<N>(d, [&](int i, int k) { return at(i, k); }, v);
      for (int k = 0; k < N; ++k) v[k] = hn::Mul(v[k], hn::Load(d, inv_pivot + k * L));
      for (int k = N - 1; k >= 0; --k)
        for (int i = 0; i < k; ++i) v[i] = hn::NegMulAdd(hn::Load(d, at(k, i)), v[k], v[i]);
      for (int i = 0; i < N; ++i) hn::Store(v[i], d, x + i * L);
    }
  }

  // Written out as LaneLu::solve_unrolled, and for the same reason (v stays in registers only
  // when the loops are literal and unrolled in place, so they are not shared): no swaps, then D.
  template <class DN>
  HWY_INLINE void solve_unrolled(DN d, std::size_t g, double* HWY_RESTRICT x) {
    namespace hw = hwy::HWY_NAMESPACE;
    hw::Vec<DN> v[N];
#pragma GCC unroll 32
    for (int i = 0; i < N; ++i) v[i] = hw::Load(d, x + i * L + g);
#pragma GCC unroll 32
    for (int k = 0; k < N; ++k) {
#pragma GCC unroll 32
      for (int i = k + 1; i < N; ++i) v[i] = hw::NegMulAdd(hw::Load(d, at(i, k) + g), v[k], v[i]);
    }
    // D^{-1} on every component before L^T: its diagonal is 1, unlike U's in LaneLu::solve.
#pragma GCC unroll 32
    for (int k = 0; k < N; ++k) v[k] = hw::Mul(v[k], hw::Load(d, inv_pivot + k * L + g));
#pragma GCC unroll 32
    for (int k = N - 1; k >= 0; --k) {
#pragma GCC unroll 32
      for (int i = 0; i < k; ++i) v[i] = hw::NegMulAdd(hw::Load(d, at(k, i) + g), v[k], v[i]);
    }
#pragma GCC unroll 32
    for (int i = 0; i < N; ++i) hw::Store(v[i], d, x + i * L + g);
  }
};

template <int N, class D>
HWY_INLINE hn::Vec<D> dot(D d, const double* HWY_RESTRICT x, const double* HWY_RESTRICT y) {
  constexpr std::size_t L = hn::MaxLanes(D());
  auto sum = hn::Zero(d);
  for (int i = 0; i < N; ++i) sum = hn::MulAdd(hn::Load(d, x + i * L), hn::Load(d, y + i * L), sum);
  return sum;
}

// to <- from, vector by vector (std::copy became `rep movsq`, slow to start for these few hundred
// bytes: the kernel is 6% faster at n = 3 without it, within the noise at n >= 8).
template <int N, class D>
HWY_INLINE void copy(D d, const double* HWY_RESTRICT from, double* HWY_RESTRICT to) {
  constexpr std::size_t L = hn::MaxLanes(D());
  for (int i = 0; i < N; ++i) hn::Store(hn::Load(d, from + i * L), d, to + i * L);
}

// x <- x / ||x||_2, returning ||x||_2.
template <int N, class D>
HWY_INLINE hn::Vec<D> normalize(D d, double* HWY_RESTRICT x) {
  constexpr std::size_t L = hn::MaxLanes(D());
  const auto norm = hn::Sqrt(dot<N>(d, x, x));
  const auto inv = hn::Div(hn::Set(d, 1.0), norm);
  for (int i = 0; i < N; ++i) hn::Store(hn::Mul(hn::Load(d, x + i * L), inv), d, x + i * L);
  return norm;
}

// Sign-insensitive chordal distance min ||x -+ y|| = 2 sin(angle / 2) between unit vectors. Unlike
// sqrt(1 - (x.y)^2) it keeps its relative accuracy for tiny angles (1e-10 is not lost in 1 - c^2).
template <int N, class D>
HWY_INLINE hn::Vec<D> chord(D d, const double* HWY_RESTRICT x, const double* HWY_RESTRICT y) {
  constexpr std::size_t L = hn::MaxLanes(D());
  auto minus = hn::Zero(d), plus = hn::Zero(d);
  for (int i = 0; i < N; ++i) {
    const auto a = hn::Load(d, x + i * L), b = hn::Load(d, y + i * L);
    const auto dm = hn::Sub(a, b), dp = hn::Add(a, b);
    minus = hn::MulAdd(dm, dm, minus);
    plus = hn::MulAdd(dp, dp, plus);
  }
  return hn::Sqrt(hn::Min(minus, plus));
}

// The largest |Ritz value| of A (B's inverse deflated against z, symmetric like B) on the plane of
// the last two deflated iterates u = w_{K-2}, v = w_{K-1}, given w = w_K, A u = g1 v and
// A v = g2 w. The power iteration's growth g2 converges at the rate sigma_{n-1}/sigma_{n-2}, slowly
// when those two are close (the estimate of sigma_{n-1} was then up to 1.6x high); the plane holds
// both directions and its Ritz value resolves them (Rayleigh-Ritz on the Krylov space
// span{u, A u}; Golub & Van Loan, Sect. 10.1). A Ritz value of a symmetric operator never exceeds
// its norm 1 / sigma_{n-1}, so sigma_{n-1} is still estimated from above.
// With q = (u - c v) / s the unit vector of the plane orthogonal to v (c = u.v, s^2 = 1 - c^2), the
// 2 x 2 matrix [v q]^T A [v q] needs only the dot products c, d = u.w and e = v.w:
//   T11 = g2 e,  T22 = c g2 (c e - d) / s^2,  T12 = (g1 - c g2 e) / s,  T21 = g2 (d - c e) / s,
// symmetrised (A is symmetric up to the rounding of the LU). When the iterates are nearly parallel
// (s^2 < 1e-6) the iteration has converged and the cancellation in c e - d would dominate: 0 then,
// so that the caller keeps g2.
template <int N, class D>
HWY_INLINE hn::Vec<D> ritz_growth(D d, const double* HWY_RESTRICT u, const double* HWY_RESTRICT v,
                                  const double* HWY_RESTRICT w, hn::Vec<D> g1, hn::Vec<D> g2) {
  const auto c = dot<N>(d, u, v), dd = dot<N>(d, u, w), e = dot<N>(d, v, w);
  const auto s2 = hn::NegMulAdd(c, c, hn::Set(d, 1.0));
  const auto planar = hn::Ge(s2, hn::Set(d, 1e-6));
  const auto safe_s2 = hn::IfThenElse(planar, s2, hn::Set(d, 1.0));
  const auto inv_s = hn::Div(hn::Set(d, 1.0), hn::Sqrt(safe_s2));
  const auto ce_minus_d = hn::MulSub(c, e, dd);
  const auto t11 = hn::Mul(g2, e);
  const auto t22 = hn::Div(hn::Mul(hn::Mul(c, g2), ce_minus_d), safe_s2);
  const auto t12 = hn::Mul(hn::NegMulAdd(hn::Mul(c, g2), e, g1), inv_s);
  const auto t21 = hn::Mul(hn::Neg(hn::Mul(g2, ce_minus_d)), inv_s);
  const auto off = hn::Mul(hn::Set(d, 0.5), hn::Add(t12, t21));
  const auto mean = hn::Mul(hn::Set(d, 0.5), hn::Add(t11, t22));
  const auto half_gap = hn::Mul(hn::Set(d, 0.5), hn::Sub(t11, t22));
  const auto radius = hn::Sqrt(hn::MulAdd(half_gap, half_gap, hn::Mul(off, off)));
  const auto largest = hn::Add(hn::Abs(mean), radius);
  // Not finite (NaN input, overflow): 0, so that the caller keeps g2 (NaN or not).
  return hn::IfThenElse(hn::And(planar, hn::IsFinite(largest)), largest, hn::Zero(d));
}

// The defect says how far z may be from the singular vector of sigma_n: the larger of
//   1. chord(x_{k-1}, x_k) over the last two iterations: the iteration has not settled (no gap);
//   2. eps ||B||_F / sigma_{n-1}, with 1/sigma_{n-1} estimated by inverse iteration orthogonal to z:
//      the first-order forward error of a computed null vector (backward error eps ||B|| over the
//      gap, Wedin / Davis-Kahan). For nullity 2 it is ~1 however the rounding happened to split
//      the two tiny singular values, which measure 1 alone cannot promise: with two tiny singular
//      values of ratio r, the iterates converge at rate 1/r in the 2-D null space, and r may be
//      large by chance.
// Rank n-1 with sigma_{n-1} >= 1e-4 ||B||: both ~1e-12 or less. Capped at 1. Whether B is singular
// at all is the residual's to say (||B z|| / ||B||_F, reported apart): a point near the curve but
// off it has a slightly regular B whose z is as good a seed as a null vector.
// kGap false (null_vector_seed): z from L D L^T without pivoting (LaneLdl), measure 1 alone, and
// no deflated iterations, no sigma_{n-1} estimate, no second vector.
template <int N, bool kGap, class Source, class D>
HWY_NOINLINE void null_vector_group(D d, std::size_t stride, std::size_t first, std::size_t lanes,
                                    const Source& source, double* HWY_RESTRICT z,
                                    double* HWY_RESTRICT defect, double* HWY_RESTRICT estimate,
                                    double* HWY_RESTRICT second) {
  constexpr std::size_t L = hn::MaxLanes(D());
  const auto one = hn::Set(d, 1.0);
  const GroupMatrix<Source, D> matrix(d, source, stride, first, lanes);
  constexpr bool kFormed = GroupMatrix<Source, D>::kFormed;
  auto entry = [&](int r, int c) {  // B(r, c) from the lower triangle
    return matrix.entry(static_cast<std::size_t>(r >= c ? r * N + c : c * N + r));
  };
  // One pass over B's lower triangle (stored: at high degree in L2 only; formed: from the
  // coefficients, matrix_source-inl.hpp) copies it into the factorization's storage and sums
  // ||B||_F^2: the diagonal, and twice the entries below it, one partial sum per row (a single
  // running sum was a chain of n^2 / 2 dependent multiply-adds). Then the copy, in L1, is scaled
  // (by the factorization as it loads each entry, for the seed's L D L^T).
  using Factorization = std::conditional_t<kGap, LaneLu<N, D>, LaneLdl<N, D>>;
  Factorization lu;
  auto diagonal2 = hn::Zero(d), below2 = hn::Zero(d), poison = hn::Zero(d);
  for (int r = 0; r < N; ++r) {
    auto row2 = hn::Zero(d), row_poison = hn::Zero(d);
    for (int c = 0; c < r; ++c) {
      const auto e = entry(r, c);
      row2 = hn::MulAdd(e, e, row2);
      if constexpr (kFormed) row_poison = hn::Add(row_poison, hn::Mul(e, hn::Zero(d)));
      hn::Store(e, d, lu.at(r, c));
    }
    const auto e = entry(r, r);
    diagonal2 = hn::MulAdd(e, e, diagonal2);
    if constexpr (kFormed) poison = hn::Add(poison, hn::Add(row_poison, hn::Mul(e, hn::Zero(d))));
    hn::Store(e, d, lu.at(r, r));
    below2 = hn::Add(below2, row2);
  }
  matrix.write_poison(poison);  // formed B: NaN where an entry is not finite, +0 otherwise
  const auto norm = hn::Sqrt(hn::MulAdd(hn::Set(d, 2.0), below2, diagonal2));
  const auto zero_matrix = hn::Eq(norm, hn::Zero(d));
  const auto scale = hn::IfThenElse(zero_matrix, one, hn::Div(one, norm));
  // The seed (kGap false) factors without pivoting (LaneLdl), reading the lower triangle only and
  // scaling each entry as it first loads it (the same product as a pass of its own, one pass
  // over the triangle fewer); null_vector with it (LaneLu), which needs the upper too: scaled and
  // mirrored from the lower here.
  if constexpr (Factorization::kLowerOnly) {
    lu.factor(d, scale);
  } else {
    for (int r = 0; r < N; ++r)
      for (int c = 0; c <= r; ++c) {
        const auto e = hn::Mul(hn::Load(d, lu.at(r, c)), scale);
        hn::Store(e, d, lu.at(r, c));
        if (c < r) hn::Store(e, d, lu.at(c, r));
      }
    lu.factor(d);
  }

  // Inverse iteration from (1, ..., 1) / sqrt(n).
  HWY_ALIGN double x[N * L];
  HWY_ALIGN double previous[N * L];
  for (int i = 0; i < N; ++i) hn::Store(one, d, x + i * L);
  normalize<N>(d, x);
  auto unsettled = hn::Zero(d);
  // The settling measure: the chord between the last two iterates (the larger of the last two
  // chords where there are three solves).
  constexpr int kIterations = kGap ? batch::kInverseIterations : batch::kSeedInverseIterations;
  constexpr int kMeasured = kIterations >= 3 ? 2 : 1;
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    if (iteration + kMeasured >= kIterations) copy<N>(d, x, previous);  // for the chord below
    lu.solve(d, x);
    normalize<N>(d, x);
    if (iteration + kMeasured >= kIterations) unsettled = hn::Max(unsettled, chord<N>(d, previous, x));
  }

  // ||B z|| / ||B||_F with the original entries (scaled once at the end: the same to rounding as
  // with the normalised entries, at n^2 fewer multiplications), B z from the lower triangle in
  // one pass over it: entry (r, c), c < r, adds to row r (in a register) and to row c (in y).
  HWY_ALIGN double y[N * L];
  for (int r = 0; r < N; ++r) {
    const auto xr = hn::Load(d, x + r * L);
    auto row = hn::Mul(entry(r, r), xr);
    for (int c = 0; c < r; ++c) {
      const auto e = entry(r, c);
      row = hn::MulAdd(e, hn::Load(d, x + c * L), row);
      hn::Store(hn::MulAdd(e, xr, hn::Load(d, y + c * L)), d, y + c * L);
    }
    hn::Store(row, d, y + r * L);
  }
  auto residual2 = hn::Zero(d);
  for (int r = 0; r < N; ++r) residual2 = hn::MulAdd(hn::Load(d, y + r * L), hn::Load(d, y + r * L), residual2);
  const auto residual = hn::Mul(hn::Sqrt(residual2), scale);
  auto result = unsettled;
  auto next = hn::Set(d, std::numeric_limits<double>::infinity());  // n = 1: no sigma_{n-1}

  HWY_ALIGN double w_lanes[kGap ? N * L : 1];  // the deflated iterate: ~ the singular vector of sigma_{n-1}
  if constexpr (N > 1 && kGap) {
    double* HWY_RESTRICT w = w_lanes;
    // w: a fixed vector of mixed signs and sizes, then kept orthogonal to z after every solve (the
    // solve re-amplifies the rounding-level z component by 1/eps).
    auto project = [&] {
      const auto along = dot<N>(d, w, x);
      for (int i = 0; i < N; ++i)
        hn::Store(hn::NegMulAdd(along, hn::Load(d, x + i * L), hn::Load(d, w + i * L)), d, w + i * L);
    };
    for (int i = 0; i < N; ++i) hn::Store(hn::Set(d, (i % 2 ? -1.0 : 1.0) * (1.0 + 0.37 * i)), d, w + i * L);
    project();
    normalize<N>(d, w);
    // The last three iterates w_{K-2}, w_{K-1}, w_K and the last two growths g_{K-1}, g_K, with
    // A w_{k-1} = g_k w_k for A the inverse deflated against z.
    // (Zeroed only because GCC cannot see that the loop below always sets them before the Ritz
    // step reads them: -Wmaybe-uninitialized.)
    HWY_ALIGN double older[N * L] = {}, old[N * L] = {};
    auto growth = hn::Zero(d), old_growth = hn::Zero(d);
    constexpr int kIterations = batch::deflated_iterations(N);
    for (int iteration = 0; iteration < kIterations; ++iteration) {
      if (iteration + 2 == kIterations) copy<N>(d, w, older);  // w_{K-2}
      if (iteration + 1 == kIterations) copy<N>(d, w, old);    // w_{K-1}
      lu.solve(d, w);
      // Twice: the solve makes the z component ~1/eps times larger than the rest, and one
      // projection leaves rounding of that size (measured: w.z up to 2e-4 after one, with the
      // sigma_{n-1} estimate 0.14% low); the second removes it to rounding of the rest.
      project();
      project();
      old_growth = growth;
      growth = normalize<N>(d, w);  // ~ 1 / sigma_{n-1} of the normalised matrix
    }
    // Not Max: x86's max returns its second operand when either is NaN, and a NaN growth (an
    // overflow) must stay NaN so that the defect sends the lane to the SVD.
    const auto ritz = ritz_growth<N>(d, older, old, w, old_growth, growth);
    growth = hn::IfThenElse(hn::Gt(ritz, growth), ritz, growth);
    result = hn::Max(result, hn::Mul(hn::Set(d, batch::kEpsilon), growth));
    next = hn::Div(one, growth);
  }
  // A zero matrix has nullity n: flagged unless n = 1 (then z = (1) is its null vector). NaN (from
  // an overflow) compares false and is mapped to 1, so that such a lane is redone.
  result = hn::IfThenElse(zero_matrix, hn::Set(d, N == 1 ? 0.0 : 1.0), result);
  result = hn::IfThenElse(hn::Le(result, one), result, one);

  const auto residual_out = hn::IfThenElse(zero_matrix, hn::Zero(d), residual);
  // A zero matrix has every direction null: no gap, unless n = 1 (nothing else to separate from).
  if constexpr (N > 1) next = hn::IfThenElse(zero_matrix, hn::Zero(d), next);
  if (lanes == L) {  // a whole group: vector stores (lane by lane, the kernel was 5% slower at n = 3)
    hn::StoreU(result, d, defect + first);
    if (estimate) {
      hn::StoreU(residual_out, d, estimate + first);
      if constexpr (kGap) hn::StoreU(next, d, estimate + stride + first);
    }
    for (int r = 0; r < N; ++r) {
      if constexpr (N > 1 && kGap)
        if (second) hn::StoreU(hn::Load(d, w_lanes + r * L), d, second + r * stride + first);
      hn::StoreU(hn::Load(d, x + r * L), d, z + r * stride + first);
    }
    return;
  }
  HWY_ALIGN double defect_lanes[L], residual_lanes[L], next_lanes[L];
  hn::Store(result, d, defect_lanes);
  hn::Store(residual_out, d, residual_lanes);
  hn::Store(next, d, next_lanes);
  for (std::size_t l = 0; l < lanes; ++l) {
    defect[first + l] = defect_lanes[l];
    if (estimate) {
      estimate[first + l] = residual_lanes[l];
      if constexpr (kGap) estimate[stride + first + l] = next_lanes[l];
    }
    if constexpr (N > 1 && kGap)
      if (second)
        for (int r = 0; r < N; ++r) second[static_cast<std::size_t>(r) * stride + first + l] = w_lanes[r * L + l];
    for (int r = 0; r < N; ++r) z[static_cast<std::size_t>(r) * stride + first + l] = x[r * L + l];
  }
}

// Lanes per group: kWideVectors<N> SIMD vectors side by side where the batch has them, whose
// dependency chains overlap, one vector for the rest; each lane computes the same numbers either
// way. Measured with bench/kernels_bench.cpp on AVX-512 (null_vector, matrices/s), 1 -> 2 -> 4
// vectors: n = 3 21M -> 32M -> 47M, n = 8 3.8M -> 5.4M -> 6.9M, n = 15 1.27M -> 1.77M -> 1.60M,
// n = 24 0.41M -> 0.48M -> 0.38M (register pressure).
// Wide only where it pays and is measured: SIMD targets, n <= 24 (each wide size is one more
// instantiation per target, and compile time is CI's budget).
template <int N>
inline constexpr int kWideVectors = (HWY_TARGET == HWY_SCALAR || HWY_TARGET == HWY_EMU128 || N > 24) ? 1
                                    : N <= 8                                                        ? 4
                                                                                                    : 2;

template <int N, bool kGap, class Source>
void null_vector_fixed(std::size_t count, std::size_t stride, const Source& B, double* z, double* defect,
                       double* estimate, double* second) {
  using Wide = wide::Tag<kWideVectors<N>>;
  constexpr std::size_t LW = wide::MaxLanes(Wide()), L1 = wide::MaxLanes(wide::Tag<1>());
  std::size_t first = 0;
  for (; first < count && first + LW <= stride; first += LW)  // whole wide groups inside the rows
    null_vector_group<N, kGap>(Wide(), stride, first, std::min(LW, count - first), B, z, defect, estimate, second);
  for (; first < count; first += L1)
    null_vector_group<N, kGap>(wide::Tag<1>(), stride, first, std::min(L1, count - first), B, z, defect, estimate,
                               second);
}

// The entry points, null_vector_batch and null_vector_seed_batch (dispatch_size over
// null_vector_fixed<N, true / false>), are each in their own translation unit, null_vector.cpp and
// null_vector_seed.cpp, so that the two compile in parallel (1 min 41 s together, CI's budget).

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_NULL_VECTOR_INL_H_
