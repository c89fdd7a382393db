// The off-curve path's starts: per lane, the nearest of a curve's samples (bezinv/kernels/batch.hpp,
// Implementation::nearest_sample). Re-included once per instruction set by hwy/foreach_target.h
// (see nearest_newton.cpp, which compiles it with nearest_newton-inl.hpp).
//
// Sample by sample over a group of lanes held in registers: per sample two broadcasts, the squared
// distance of every lane and two selects. Without fused multiply-add (the file is compiled with
// -ffp-contract=off), so every implementation finds the same sample and the same start.
#if defined(BEZINV_KERNELS_BATCH_NEAREST_SAMPLE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_NEAREST_SAMPLE_INL_H_
#undef BEZINV_KERNELS_BATCH_NEAREST_SAMPLE_INL_H_
#else
#define BEZINV_KERNELS_BATCH_NEAREST_SAMPLE_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>
#include <limits>

#include "batch/wide-inl.hpp"
#include "bezinv/kernels/batch.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {

namespace nearest {

// One group of lanes, first..first+lanes, held in d's registers.
template <class D>
HWY_INLINE void sample_group(D d, const double* samples, int last, int stride, std::size_t first, std::size_t lanes,
                             const double* u, const double* v, double* t) {
  namespace hn = wide;
  using V = hn::Vec<D>;
  constexpr std::size_t L = hn::MaxLanes(D());
  HWY_ALIGN double best[L], at[L];
  const auto distance2 = [&](int k, std::size_t l) {
    const double dx = samples[2 * k] - u[first + l], dy = samples[2 * k + 1] - v[first + l];
    return dx * dx + dy * dy;
  };
  const V pu = hn::LoadGroup(d, u, first, lanes, 0.0), pv = hn::LoadGroup(d, v, first, lanes, 0.0);
  V nearest = hn::Set(d, std::numeric_limits<double>::infinity()), index = hn::Zero(d);
  for (int k = 0; k <= last; k += stride) {
    const V dx = hn::Sub(hn::Set(d, samples[2 * k]), pu), dy = hn::Sub(hn::Set(d, samples[2 * k + 1]), pv);
    const V d2 = hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy));
    const auto nearer = hn::Lt(d2, nearest);  // strict: the first of equally near samples stays
    nearest = hn::IfThenElse(nearer, d2, nearest);
    index = hn::IfThenElse(nearer, hn::Set(d, k), index);
  }
  hn::Store(nearest, d, best);
  hn::Store(index, d, at);
  for (std::size_t l = 0; l < lanes; ++l) {
    const int k = static_cast<int>(at[l]);
    double start = static_cast<double>(k) / last;
    if (k >= stride && k + stride <= last) {
      const double before = distance2(k - stride, l), after = distance2(k + stride, l);
      const double curvature = before - 2 * best[l] + after;
      if (curvature > 0) start += std::clamp(0.5 * (before - after) / curvature, -1.0, 1.0) * stride / last;
    }
    t[first + l] = start;
  }
}

}  // namespace nearest

// Two vectors a group, but a last group one vector holds runs as one (wide::ForEachGroup).
void nearest_sample_batch(const double* samples, int last, int stride, std::size_t count, const double* u,
                          const double* v, double* t) {
  constexpr int kWide = (HWY_TARGET == HWY_SCALAR || HWY_TARGET == HWY_EMU128) ? 1 : 2;
  wide::ForEachGroup<kWide>(count, [&](auto d, std::size_t first, std::size_t lanes) {
    nearest::sample_group(d, samples, last, stride, first, lanes, u, v, t);
  });
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_NEAREST_SAMPLE_INL_H_
