#pragma once
// Scheduling: the batches of a curve's points over TBB worker threads. Answers do not depend on
// the thread count (no lane's answer depends on another's).
#include <cstddef>
#include <functional>
#include <span>

#include "bezinv/profile.hpp"
#include "plan_data.hpp"

namespace bezinv::detail {

// All points of one curve: batches in parallel (options.threads; 1 = on the calling thread).
// `stages`, when given, accumulates the seconds of work of each stage over the threads.
void invert_curve(const PlanData& plan, std::span<const Point> points, std::span<PointResult> results,
                  const InvertOptions& options, StageSeconds* stages);

// Points of many curves: curve_of[i] indexes plans (negative: left as the caller set it); z[i]
// the third coordinate where the plan is a space curve's (space/invert_space.hpp).
void invert_curves(std::span<const InversionPlan> plans, std::span<const int> curve_of, std::span<const Point> points,
                   std::span<const double> z, std::span<PointResult> results, const InvertOptions& options);

// body(begin, end) over [0, count) in ranges of about `grain`, in parallel on options.threads
// threads (one, or a single range: here).
void for_each_range(std::size_t count, const InvertOptions& options,
                    const std::function<void(std::size_t, std::size_t)>& body, std::size_t grain = 256);

}  // namespace bezinv::detail
