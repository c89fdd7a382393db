#include "pipeline/pair_check.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "bezinv/kernels/batch.hpp"
#include "bezinv/null_vector.hpp"
#include "pipeline/decide.hpp"
#include "pipeline/form_b.hpp"
#include "pipeline/stage_clock.hpp"
#include "pipeline/svd_queue.hpp"
#include "refine.hpp"

namespace bezinv::detail {
namespace {

// A root this close to the lane's t goes to the front of the queue (near), the others to the back
// (far): roots of similar Newton work share a SIMD group. Speed only.
constexpr double kNearRoot = 1e-3;

}  // namespace

PairCheckQueue& pair_check_queue() {
  thread_local PairCheckQueue queue;
  return queue;
}

int null_space_roots(int n, const BatchWorkspace& w, std::size_t l, double roots[2]) {
  std::array<double, kMaxDegree> z, second;
  for (int r = 0; r < n; ++r) {
    z[r] = w.z[r * kBatchLanes + l];
    second[r] = w.second[r * kBatchLanes + l];
  }
  return parameters_from_null_space(std::span<const double>(z.data(), n), std::span<const double>(second.data(), n),
                                    roots);
}

bool queue_second_parameters(int n, const BatchWorkspace& w, std::size_t l, const Candidate& c, PointResult* target) {
  double roots[2];
  const int count = null_space_roots(n, w, l, roots);
  PairCheckQueue& q = pair_check_queue();
  const std::size_t lane = q.lanes;
  bool queued = false;
  // z's own root is the one nearer t; the other is the second parameter the plane announces.
  const int other = count == 2 ? (std::abs(roots[1] - c.t) > std::abs(roots[0] - c.t) ? 1 : 0) : -1;
  for (int i = 0; i < count; ++i) {
    const double start = std::clamp(roots[i], 0.0, 1.0);  // NaN stays NaN: not settled, refined to NaN
    const double from_t = std::abs(start - c.t);
    if (from_t <= kSameRoot) continue;  // z's own root (tolerances.hpp)
    const std::size_t k = from_t <= kNearRoot ? q.near++ : q.root_t.size() - 1 - q.far++;
    q.root_t[k] = start;
    q.root_u[k] = w.u[l];
    q.root_v[k] = w.v[l];
    q.root_lane[k] = static_cast<std::uint8_t>(lane);
    q.root_other[k] = i == other;
    queued = true;
  }
  if (!queued) return false;
  q.u[lane] = w.u[l];
  q.v[lane] = w.v[l];
  q.t[lane] = c.t;
  q.distance[lane] = c.distance;
  q.sigma_min[lane] = w.estimate[l];
  q.sigma_next[lane] = w.estimate[kBatchLanes + l];
  q.target[lane] = target;
  ++q.lanes;
  return true;
}

void flush_pair_check_queue(const PlanData& plan, const InvertOptions& options, StageSeconds* stages) {
  PairCheckQueue& q = pair_check_queue();
  if (q.lanes == 0) return;
  StageClock clock(stages);
  const double tolerance = normalized_tolerance(plan, options);
  const kernels::RationalCurve curve = detail::kernel_curve(plan);
  const std::size_t slots = q.root_t.size();
  for (const std::size_t first : {std::size_t{0}, slots - q.far}) {
    const std::size_t size = first == 0 ? q.near : q.far;
    kernels::active_implementation().rational_newton(curve, detail::kNewtonSettings, size, q.root_u.data() + first,
                                                     q.root_v.data() + first, q.root_t.data() + first,
                                                     q.root_distance.data() + first);
  }
  std::fill_n(q.second_found.begin(), q.lanes, std::uint8_t{0});
  for (std::size_t k = 0; k < slots; ++k) {
    if (k == q.near) k = slots - q.far;
    if (k == slots) break;
    const std::size_t lane = q.root_lane[k];
    detail::Refined r{q.root_t[k], q.root_distance[k]};
    if (std::isnan(r.distance)) r = detail::refine_parameter(plan, q.root_u[k], q.root_v[k], q.root_t[k], true);
    const bool distinct = std::abs(r.t - q.t[lane]) > kDistinctParameterGap;
    if ((r.distance <= tolerance && distinct) || (q.root_other[k] && !distinct)) q.second_found[lane] = 1;
  }
  clock.lap(&StageSeconds::refine);
  const std::size_t lanes = q.lanes;
  q.lanes = q.near = q.far = 0;
  // The lanes with a second parameter go to the SVD path through its queue, with their B formed
  // again as invert_batch_lanes forms it (the same kernel, so the same bits) in the batch
  // workspace, which is free between batches; kBatchLanes of them at a time.
  const int n = plan.degree, nn = n * n;
  SvdQueue& svd = svd_queue();
  std::array<double, kBatchLanes> u, v;
  std::array<PointResult*, kBatchLanes> target;
  for (std::size_t k = 0; k < lanes;) {
    std::size_t m = 0;
    for (; k < lanes && m < kBatchLanes; ++k) {
      if (!q.second_found[k]) {
        answer_fast(plan, q.t[k], q.distance[k], q.sigma_min[k], q.sigma_next[k], *q.target[k]);
        continue;
      }
      u[m] = q.u[k];
      v[m] = q.v[k];
      target[m++] = q.target[k];
    }
    if (m == 0) continue;
    BatchWorkspace& w = batch_workspace();
    form_compacted_b(plan, u.data(), v.data(), m, w.B.data());
    for (std::size_t j = 0; j < m; ++j) {
      if (svd.size == kBatchLanes) flush_svd_queue(plan, options, stages);  // uses w, but not w.B
      svd.push(nn, w.B.data(), j, u[j], v[j], target[j]);
    }
  }
  clock.lap(&StageSeconds::decide);
}

}  // namespace bezinv::detail
