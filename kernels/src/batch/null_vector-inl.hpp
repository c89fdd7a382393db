// The null vector of every lane's (nearly) singular symmetric matrix by inverse iteration from
// (1, ..., 1), one matrix per lane: null_vector (pivoted LU, with the gap) and the seeds
// (L D L^T without pivoting, no gap). Re-included once per instruction set by
// hwy/foreach_target.h (see null_vector.cpp, null_vector_seed.cpp).
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
#include <vector>

#include "batch/constants.hpp"
#include "batch/gap_estimate-inl.hpp"
#include "batch/lane_vectors-inl.hpp"
#include "batch/ldlt-inl.hpp"
#include "batch/matrix_source-inl.hpp"
#include "batch/pivoted_lu-inl.hpp"
#include "batch/sizes-inl.hpp"
#include "batch/triangular_substitution-inl.hpp"
#include "batch/wide-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
// Highway's operations on wide vectors (batch/wide-inl.hpp): D is a wide::Tag<G>, G vectors of
// lanes processed side by side.
namespace hn = wide;

// Entry (r, c) of a symmetric n x n matrix from its lower triangle, the only one the kernels read.
template <int N, class Matrix>
HWY_INLINE auto lower_entry(const Matrix& matrix, int r, int c) {
  return matrix.entry(static_cast<std::size_t>(r >= c ? r * N + c : c * N + r));
}

// ||B x|| for every lane of a group, B a GroupMatrix (matrix_source-inl.hpp) and x as
// x[r L + lane]: B x from the lower triangle in one pass over it, entry (r, c), c < r, adding to
// row r (in a register) and to row c (in y).
template <int N, class D, class Matrix>
HWY_INLINE wide::Vec<D> residual_norm(D d, const Matrix& matrix, const double* HWY_RESTRICT x) {
  constexpr std::size_t L = hn::MaxLanes(D());
  auto entry = [&](int r, int c) { return lower_entry<N>(matrix, r, c); };
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
  return hn::Sqrt(residual2);
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
// `iterations` (kGap only): the solves from (1, ..., 1), batch::kInverseIterations unless a caller
// asks for more (null_vector_iterations: where sigma_n / sigma_{n-1} is ~0.1, three leave z
// unsettled).
// kGap false (the seeds): z from L D L^T without pivoting (Ldlt), measure 1 alone, and no
// deflated iterations, no sigma_{n-1} estimate, no second vector.
// The seeds (kGap false) compute the residual only for the lanes whose defect is at most
// `settled_defect`, and write +inf for the others: a seed that has not settled is not used, and
// its residual, which forms B a second time, is a fifth of the seed's work at n = 15. A group
// whose lanes all settled computes it at once, one with none skips it, and one with both either
// computes it for all (deferred_scale null, or a quarter of its lanes settled or more) or leaves it
// to the caller for the settled lanes, writing their 1 / ||B||_F to deferred_scale[l] (NaN for the
// other lanes, l < lanes) and returning true: a group of mostly unsettled lanes (points off the
// curve) then does not run for the few settled ones. The caller's pass forms B and gathers z
// again, about twice a lane's share of the group's own pass at n = 8. So a group half settled (a
// batch half on the curve, whose seed groups nearly all hold both kinds) computes in place at
// every size: deferring such groups cost 4% of the pipeline at degrees 8 and 12, noise 1e-4, and
// at degree 16, noise 1e-2, the caller's pass took 21 ns a point of a mixed batch, the seed in
// all 74-90 ns a point against 59-81 in place (perf; docs/fast-path.md, "Mixed batches").

template <int N, bool kGap, class Source, class D>
HWY_NOINLINE bool null_vector_group(D d, std::size_t stride, std::size_t first, std::size_t lanes,
                                    const Source& source, double* HWY_RESTRICT z,
                                    double* HWY_RESTRICT defect, double* HWY_RESTRICT estimate,
                                    double* HWY_RESTRICT second, double settled_defect = 1.0,
                                    double* HWY_RESTRICT deferred_scale = nullptr,
                                    int iterations = batch::kInverseIterations) {
  static_assert(N >= 2, "n = 1 has no sigma_{n-1}, and no seed needs it");
  constexpr std::size_t L = hn::MaxLanes(D());
  const auto one = hn::Set(d, 1.0);
  const GroupMatrix<Source, D> matrix(d, source, stride, first, lanes);
  constexpr bool kFormed = GroupMatrix<Source, D>::kFormed;
  auto entry = [&](int r, int c) { return lower_entry<N>(matrix, r, c); };
  // One pass over B's lower triangle (stored: at high degree in L2 only; formed: from the
  // coefficients, matrix_source-inl.hpp) copies it into the factorization's storage and sums
  // ||B||_F^2: the diagonal, and twice the entries below it, one partial sum per row (a single
  // running sum was a chain of n^2 / 2 dependent multiply-adds). Then the copy, in L1, is scaled
  // (by the factorization as it loads each entry, for the seed's L D L^T).
  using Factorization = std::conditional_t<kGap, PivotedLu<N, D>, Ldlt<N, D>>;
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
  // The seed's Ldlt reads the lower triangle only and scales each entry as it first loads it (the
  // same product as a pass of its own, one pass over the triangle fewer); PivotedLu needs the
  // upper too: scaled and mirrored from the lower here.
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
  HWY_ALIGN double previous[N * L] = {};  // written before it is read; {} for the compiler's sake
  for (int i = 0; i < N; ++i) hn::Store(one, d, x + i * L);
  normalize<N>(d, x);
  auto unsettled = hn::Zero(d);
  // The settling measure: the chord between the last two iterates (the larger of the last two
  // chords where there are three solves).
  // The usual count as a constant, so that the loop unrolls at small n (a run-time count there cost
  // the conics 2%); more solves only where asked for.
  auto iterate = [&](int solves) HWY_ATTR __attribute__((always_inline)) {
    const int measured = solves >= 3 ? 2 : 1;
    for (int iteration = 0; iteration < solves; ++iteration) {
      if (iteration + measured >= solves) copy<N>(d, x, previous);  // for the chord below
      solve<N>(d, lu, x);
      normalize<N>(d, x);
      if (iteration + measured >= solves) unsettled = hn::Max(unsettled, chord<N>(d, previous, x));
    }
  };
  constexpr int kSolves = kGap ? batch::kInverseIterations : batch::kSeedInverseIterations;
  if (kGap && iterations != kSolves) iterate(iterations);
  else iterate(kSolves);

  auto result = unsettled;
  auto next = hn::Zero(d);  // 1 / growth (kGap)

  HWY_ALIGN double w_lanes[kGap ? N * L : 1];  // the deflated iterate: ~ the singular vector of sigma_{n-1}
  if constexpr (kGap) {
    const auto growth = inverse_sigma_next<N>(d, lu, x, w_lanes);  // NaN stays NaN: the lane is redone
    result = hn::Max(result, hn::Mul(hn::Set(d, batch::kEpsilon), growth));
    next = hn::Div(one, growth);
  }
  // A zero matrix has nullity n: flagged. NaN (from an overflow) compares false and is mapped to
  // 1, so that such a lane is redone.
  result = hn::IfThenElse(zero_matrix, one, result);
  result = hn::IfThenElse(hn::Le(result, one), result, one);

  // ||B z|| / ||B||_F with the original entries (scaled once at the end: the same to rounding as
  // with the normalised entries, at n^2 fewer multiplications). The seeds: where settled only
  // (above).
  auto residual_out = hn::Set(d, std::numeric_limits<double>::infinity());
  bool deferred = false;
  if constexpr (kGap) {
    residual_out = hn::IfThenElse(zero_matrix, hn::Zero(d), hn::Mul(residual_norm<N>(d, matrix, x), scale));
  } else {
    const auto settled = hn::Le(result, hn::Set(d, settled_defect));
    if (!hn::AllFalse(d, settled)) {
      // Some lanes settled: are they all (padding aside), or few enough to leave to the caller?
      const auto not_settled = lanes == L ? hn::Not(settled) : hn::AndNot(settled, hn::FirstN(d, lanes));
      deferred = deferred_scale != nullptr && 4 * hn::CountTrue(d, not_settled) > 3 * lanes;  // (some unsettled)
      if (deferred) {
        HWY_ALIGN double scale_lanes[L];
        hn::Store(hn::IfThenElse(settled, scale, hn::Set(d, std::numeric_limits<double>::quiet_NaN())), d,
                  scale_lanes);
        for (std::size_t l = 0; l < lanes; ++l) deferred_scale[l] = scale_lanes[l];
      } else {
        const auto residual = hn::IfThenElse(zero_matrix, hn::Zero(d), hn::Mul(residual_norm<N>(d, matrix, x), scale));
        residual_out = hn::IfThenElse(settled, residual, residual_out);
      }
    }
  }
  // A zero matrix has every direction null: no gap.
  next = hn::IfThenElse(zero_matrix, hn::Zero(d), next);
  if (lanes == L) {  // a whole group: vector stores (lane by lane is measurably slower at small n)
    hn::StoreU(result, d, defect + first);
    if (estimate) {
      hn::StoreU(residual_out, d, estimate + first);
      if constexpr (kGap) hn::StoreU(next, d, estimate + stride + first);
    }
    for (int r = 0; r < N; ++r) {
      if constexpr (kGap)
        if (second) hn::StoreU(hn::Load(d, w_lanes + r * L), d, second + r * stride + first);
      hn::StoreU(hn::Load(d, x + r * L), d, z + r * stride + first);
    }
    return deferred;
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
    if constexpr (kGap)
      if (second)
        for (int r = 0; r < N; ++r) second[static_cast<std::size_t>(r) * stride + first + l] = w_lanes[r * L + l];
    for (int r = 0; r < N; ++r) z[static_cast<std::size_t>(r) * stride + first + l] = x[r * L + l];
  }
  return deferred;
}

// Lanes per group: kWideVectors<N> SIMD vectors side by side, whose dependency chains overlap; each
// lane computes the same numbers whatever the group. Wide on the SIMD targets up to n = 24 only:
// beyond, the registers run out and a wide group is slower (docs/kernels.md, "Wide groups").
template <int N>
inline constexpr int kWideVectors = (HWY_TARGET == HWY_SCALAR || HWY_TARGET == HWY_EMU128 || N > 24) ? 1
                                    : N <= 8                                                        ? 4
                                                                                                    : 2;

// Every group has the same width, the last one too: one instantiation of the kernel per size and
// instruction set. A stored batch's last group may reach past the rows (a stride that is not a
// multiple of the group's lanes; never the engine's batches): its lanes are then copied into a
// batch of their own, zeros after them, and its outputs copied back. (Formed matrices pad
// themselves, matrix_source-inl.hpp.)
template <int N, bool kGap, class Source>
void null_vector_fixed(std::size_t count, std::size_t stride, const Source& B, double* z, double* defect,
                       double* estimate, double* second, double settled_defect = 1.0,
                       int iterations = batch::kInverseIterations) {
  using Wide = wide::Tag<kWideVectors<N>>;
  constexpr std::size_t LW = wide::MaxLanes(Wide());
  constexpr bool kPastTheRows = !GroupMatrix<Source, Wide>::kFormed;
  std::size_t first = 0;
  for (; first < count && (!kPastTheRows || first + LW <= stride); first += LW)
    null_vector_group<N, kGap>(Wide(), stride, first, std::min(LW, count - first), B, z, defect, estimate, second,
                               settled_defect, nullptr, iterations);
  if constexpr (kPastTheRows) {
    if (first >= count) return;
    const std::size_t lanes = count - first;
    std::vector<double> padded(N * N * LW, 0.0), z_lanes(N * LW), defect_lanes(LW), estimate_lanes(2 * LW),
        second_lanes(N * LW);
    for (std::size_t i = 0; i < N * N; ++i) std::copy_n(B.B + i * stride + first, lanes, padded.data() + i * LW);
    null_vector_group<N, kGap>(Wide(), LW, 0, lanes, StoredMatrices{padded.data()}, z_lanes.data(),
                               defect_lanes.data(), estimate ? estimate_lanes.data() : nullptr,
                               second ? second_lanes.data() : nullptr, settled_defect, nullptr, iterations);
    for (std::size_t l = 0; l < lanes; ++l) {
      defect[first + l] = defect_lanes[l];
      if (estimate) {
        estimate[first + l] = estimate_lanes[l];
        if constexpr (kGap) estimate[stride + first + l] = estimate_lanes[LW + l];
      }
      for (std::size_t r = 0; r < N; ++r) {
        z[r * stride + first + l] = z_lanes[r * LW + l];
        if (second) second[r * stride + first + l] = second_lanes[r * LW + l];
      }
    }
  }
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_NULL_VECTOR_INL_H_
