#pragma once
// Scheduling: the batches of a curve's points over TBB worker threads. Answers do not depend on
// the thread count (no lane's answer depends on another's).
#include <span>

#include "bezinv/profile.hpp"
#include "plan_data.hpp"

namespace bezinv::detail {

// All points of one curve: batches in parallel (options.threads; 1 = on the calling thread).
// `stages`, when given, accumulates the seconds of work of each stage over the threads.
void invert_curve(const PlanData& plan, std::span<const Point> points, std::span<PointResult> results,
                  const InvertOptions& options, StageSeconds* stages);

// Points of many curves: curve_of[i] indexes plans (negative: left as the caller set it).
void invert_curves(std::span<const InversionPlan> plans, std::span<const int> curve_of, std::span<const Point> points,
                   std::span<PointResult> results, const InvertOptions& options);

}  // namespace bezinv::detail
