// Lanes by kind before the seed (engine/src/pipeline/by_kind.hpp): far from a high-degree curve, a
// batch's lanes far from the segment leave for a per-thread far queue and its near ones for a seed
// queue, each decided in batches gathered from several. None of it may change an answer: every row
// of a mixed file must be the row its point gets alone (invert_point, a batch of one, never
// queued), bit for bit, on one thread and two, whatever the arrangement of the kinds (at every
// degree, those that sort and those that do not); and the sorting itself must put each lane where
// segment_far says.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "isolation.hpp"
#include "pipeline/by_kind.hpp"
#include "plan_data.hpp"
#include "pipeline/fast_path.hpp"
#include "pipeline/workspace.hpp"
#include "support/bits.hpp"
#include "support/same_row.hpp"
#include "support/sanitizers.hpp"

namespace bezinv {
namespace {

// How the kinds follow each other in the file.
enum class Arrangement { alternating, random, blocks_of_40, few_off };

// Points of the curve at known t, and points moved off it by `noise` x the diagonal in a random
// direction, arranged as asked; every 97th point is NaN (a lane no longer active from the start).
std::vector<Point> mixed_points(const Curve& curve, double diagonal, double noise, Arrangement arrangement,
                                std::size_t count, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Point> points(count);
  for (std::size_t i = 0; i < count; ++i) {
    bool off = false;
    switch (arrangement) {
      case Arrangement::alternating: off = i % 2 == 1; break;
      case Arrangement::random: off = unit(rng) < 0.5; break;
      case Arrangement::blocks_of_40: off = (i / 40) % 2 == 1; break;
      case Arrangement::few_off: off = i % 16 == 5; break;
    }
    const Point p = datasets::on_curve(curve, unit(rng));
    const double angle = 2 * M_PI * unit(rng), d = off ? noise * diagonal * (0.5 + unit(rng)) : 0.0;
    points[i] = {p.x + d * std::cos(angle), p.y + d * std::sin(angle)};
    if (i % 97 == 96) points[i] = {std::numeric_limits<double>::quiet_NaN(), 0.0};
  }
  return points;
}

TEST(LanesByKind, EveryRowOfAMixedFileIsThePointsRowAlone) {
  constexpr std::size_t kPoints = test_support::kSanitizerThinning > 1 ? 600 : 2000;
  std::size_t rows = 0;
  for (int n : {3, 4, 5, 8, 12, 15, 16, 20}) {
    std::mt19937_64 rng(5200 + n);
    const Curve curve =
        datasets::random_curve(CurveKind::rational_bezier, n, rng, datasets::ControlPolygon::perturbed_arc);
    const InversionPlan plan = make_plan(curve);
    for (double noise : {1e-6, 1e-4, 1e-2, 10.0}) {
      for (Arrangement arrangement :
           {Arrangement::alternating, Arrangement::random, Arrangement::blocks_of_40, Arrangement::few_off}) {
        const std::vector<Point> points = mixed_points(curve, plan.diagonal(), noise, arrangement, kPoints, rng);
        std::vector<PointResult> alone(points.size());
        for (std::size_t i = 0; i < points.size(); ++i) alone[i] = invert_point(plan, points[i]);
        for (int threads : {1, 2}) {
          std::vector<PointResult> batched(points.size());
          invert(plan, points, batched, {.threads = threads});
          for (std::size_t i = 0; i < points.size(); ++i)
            ASSERT_TRUE(test_support::same_row(batched[i], alone[i]))
                << "degree " << n << ", noise " << noise << ", arrangement " << static_cast<int>(arrangement)
                << ", threads " << threads << ", point " << i;
          rows += points.size();
        }
      }
    }
  }
  EXPECT_GT(rows, 0u);
}

// A LaneSet holds any of a batch's lanes, in either of its words, and visits them in order.
TEST(LanesByKind, ALaneSetHoldsEveryLaneOfABatchInOrder) {
  using detail::kBatchLanes;
  detail::LaneSet odd, low, none;
  for (std::size_t l = 0; l < kBatchLanes; ++l) {
    odd.add(l, l % 2 == 1);
    low.add(l, l < 70);  // across the first word's end
    none.add(l, false);
  }
  EXPECT_TRUE(none.empty());
  EXPECT_FALSE(odd.empty());
  std::vector<std::size_t> seen;
  odd.both(low).for_each([&](std::size_t l) { seen.push_back(l); });
  std::vector<std::size_t> expected;
  for (std::size_t l = 1; l < 70; l += 2) expected.push_back(l);
  EXPECT_EQ(seen, expected);
  seen.clear();
  odd.without(low).for_each([&](std::size_t l) { seen.push_back(l); });
  expected.clear();
  for (std::size_t l = 71; l < kBatchLanes; l += 2) expected.push_back(l);
  EXPECT_EQ(seen, expected);
  for (std::size_t l = 0; l < kBatchLanes; ++l) {
    EXPECT_EQ(odd.has(l), l % 2 == 1) << l;
    EXPECT_EQ(low.has(l), l < 70) << l;
  }
  EXPECT_TRUE(odd.without(odd).empty());
}

// LaneSet::first and LaneSet::of_flags against add(), lane by lane: every count from 0 to a whole
// batch (within a word, at its end, across it, an eight-lane step and its tail), random flags.
TEST(LanesByKind, ALaneSetOfFlagsHoldsTheFlaggedLanesBelowTheCount) {
  using detail::kBatchLanes;
  std::mt19937_64 rng(5301);
  std::array<std::uint8_t, kBatchLanes> flags;
  for (std::size_t count = 0; count <= kBatchLanes; ++count) {
    for (std::uint8_t& f : flags) f = static_cast<std::uint8_t>(rng() % 2);
    detail::LaneSet expected, below;
    for (std::size_t l = 0; l < count; ++l) {
      expected.add(l, flags[l] != 0);
      below.add(l, true);
    }
    const detail::LaneSet got = detail::LaneSet::of_flags(count, flags.data());
    const detail::LaneSet first = detail::LaneSet::first(count);
    for (std::size_t l = 0; l < kBatchLanes; ++l) {
      EXPECT_EQ(got.has(l), expected.has(l)) << "count " << count << " lane " << l;
      EXPECT_EQ(first.has(l), below.has(l)) << "count " << count << " lane " << l;
    }
  }
}

// set_aside_far on a batch of a degree-16 curve: points on it (near) and 1e-2 of the diagonal off
// it (far from the segment, as segment_far tells), which lanes go to which queue, in order.
TEST(LanesByKind, SetAsideSendsFarLanesToTheFarQueueAndNearOnesToTheSeedQueue) {
  using detail::kBatchLanes;
  std::mt19937_64 rng(5300);
  const Curve curve =
      datasets::random_curve(CurveKind::rational_bezier, 16, rng, datasets::ControlPolygon::perturbed_arc);
  const InversionPlan plan = make_plan(curve);
  const detail::PlanData& data = detail::plan_data(plan);
  const double tolerance = kDefaultRelativeTolerance * plan.diagonal() / data.scale;
  ASSERT_TRUE(detail::skips_far_seeds(data, tolerance)) << "the test needs a plan whose seed skips far lanes";
  const std::vector<Point> points = mixed_points(curve, plan.diagonal(), 1e-2, Arrangement::random, kBatchLanes, rng);
  detail::BatchWorkspace& w = detail::batch_workspace();
  for (std::size_t l = 0; l < kBatchLanes; ++l) {
    const auto uv = data.normalize(points[l].x, points[l].y);
    w.u[l] = uv[0], w.v[l] = uv[1];
    w.active[l] = l != 7;  // one lane answered already
  }
  const detail::FarLanes far = detail::far_lanes(data, tolerance, kBatchLanes, w);
  ASSERT_TRUE(far.known);
  std::vector<std::size_t> far_of, near_of;
  for (std::size_t l = 0; l < kBatchLanes; ++l) {
    ASSERT_EQ(far.lanes.has(l), detail::segment_far(data, w.u[l], w.v[l])) << l;
    if (l == 7) continue;
    (far.lanes.has(l) ? far_of : near_of).push_back(l);
  }
  ASSERT_GT(far_of.size(), 8u);
  ASSERT_GT(near_of.size(), 8u);

  std::array<PointResult, kBatchLanes> results{};
  detail::SeedQueue& seeds = detail::seed_queue();
  detail::FarQueue& far_lanes = detail::far_queue();
  seeds.size = far_lanes.size = 3;  // lanes already waiting stay first
  ASSERT_TRUE(detail::set_aside_far(far, points.data(), detail::LaneRows(results.data()), kBatchLanes, w));
  ASSERT_EQ(far_lanes.size, 3 + far_of.size());
  ASSERT_EQ(seeds.size, 3 + near_of.size());
  for (std::size_t k = 0; k < far_of.size(); ++k) {
    EXPECT_TRUE(test_support::same_bits(far_lanes.u[3 + k], w.u[far_of[k]]));
    EXPECT_TRUE(test_support::same_bits(far_lanes.v[3 + k], w.v[far_of[k]]));
    EXPECT_EQ(far_lanes.target[3 + k], &results[far_of[k]]);
  }
  for (std::size_t k = 0; k < near_of.size(); ++k) {
    EXPECT_TRUE(test_support::same_bits(seeds.u[3 + k], w.u[near_of[k]]));
    EXPECT_TRUE(test_support::same_bits(seeds.point[3 + k].x, points[near_of[k]].x));
    EXPECT_EQ(seeds.target[3 + k], &results[near_of[k]]);
  }

  // A far queue's lanes come back as unseeded lanes, the rest of the queue moved to its front.
  std::array<PointResult*, kBatchLanes> rows;
  detail::take_from_far_queue(5, w, rows);
  ASSERT_EQ(far_lanes.size, far_of.size() - 2);
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(w.active[k], 1);
    EXPECT_TRUE(std::isnan(w.t_algebraic[k]));
    EXPECT_EQ(w.estimate[k], std::numeric_limits<double>::infinity());
  }
  EXPECT_EQ(rows[3], &results[far_of[0]]);
  EXPECT_EQ(far_lanes.target[0], &results[far_of[2]]);

  // A batch all near, or all far, stays as it is.
  seeds.size = far_lanes.size = 0;
  for (const bool far_only : {false, true}) {
    for (std::size_t l = 0; l < kBatchLanes; ++l) w.active[l] = far.lanes.has(l) == far_only;
    EXPECT_FALSE(detail::set_aside_far(far, points.data(), detail::LaneRows(results.data()), kBatchLanes, w));
    EXPECT_EQ(seeds.size + far_lanes.size, 0u);
  }
}

}  // namespace
}  // namespace bezinv
