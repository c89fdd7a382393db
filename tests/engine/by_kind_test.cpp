// Lanes by kind (engine/src/pipeline/by_kind.hpp): where a batch holds points on the curve and
// points off it, the lanes leave for per-thread queues of their kind and are decided in batches
// gathered from several; far from a high-degree curve, the far lanes leave before the seed and the
// near ones are seeded in a batch of their own. None of it may change an answer: every row of a
// mixed file must be the row its point gets alone (invert_point, a batch of one, never queued), bit
// for bit, on one thread and two, whatever the arrangement of the kinds; and the sorting itself
// must put each lane where its kind says.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "pipeline/by_kind.hpp"
#include "pipeline/fast_path.hpp"
#include "pipeline/workspace.hpp"
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

// sort_by_kind on a batch made by hand: which lanes stay, which leave for which queue, in order.
TEST(LanesByKind, SortPutsEachLaneWhereItsKindSays) {
  using detail::kBatchLanes;
  detail::BatchWorkspace& w = detail::batch_workspace();
  detail::KindQueue& on_queue = detail::kind_queue(detail::LaneKind::on_curve);
  detail::KindQueue& off_queue = detail::kind_queue(detail::LaneKind::off_curve);
  std::array<PointResult, kBatchLanes> results{};
  const double inf = std::numeric_limits<double>::infinity();
  // Lane l: u = l; off the curve where `off(l)`; lane 7 no longer active.
  auto fill = [&](auto off) {
    for (std::size_t l = 0; l < kBatchLanes; ++l) {
      w.u[l] = static_cast<double>(l), w.v[l] = -static_cast<double>(l);
      w.t_algebraic[l] = 0.5, w.defect[l] = 1e-9;
      w.estimate[l] = off(l) ? (l % 3 == 0 ? inf : 1e-6) : (l % 5 == 0 ? 0.0 : 1e-15);
      w.active[l] = l != 7;
    }
  };
  std::array<PointResult*, kBatchLanes> gathered;
  
  // Half and half: every active lane leaves for its kind's queue, in order.
  on_queue.size = off_queue.size = 0;
  fill([](std::size_t l) { return l % 2 == 1; });
  const detail::KindSort all_leave = detail::sort_by_kind(kBatchLanes, detail::LaneRows(results.data()), w, gathered);
  EXPECT_TRUE(all_leave.moved);
  EXPECT_EQ(all_leave.kept, 0u);
  ASSERT_EQ(on_queue.size, kBatchLanes / 2);
  ASSERT_EQ(off_queue.size, kBatchLanes / 2 - 1);  // lane 7 stays behind, answered already
  for (std::size_t k = 0; k < on_queue.size; ++k) {
    EXPECT_EQ(on_queue.u[k], 2.0 * k);
    EXPECT_EQ(on_queue.target[k], &results[2 * k]);
  }
  for (std::size_t k = 0; k < off_queue.size; ++k) {
    const std::size_t l = k < 3 ? 2 * k + 1 : 2 * k + 3;  // 1, 3, 5, then 9, 11, ...
    EXPECT_EQ(off_queue.u[k], static_cast<double>(l));
    EXPECT_EQ(off_queue.v[k], -static_cast<double>(l));
    EXPECT_EQ(off_queue.estimate[k], w.estimate[l] == inf ? inf : 1e-6);
    EXPECT_EQ(off_queue.target[k], &results[l]);
  }

  // Half and half again, with 40 lanes waiting on the curve: the batch's 32 stay, and the queue's
  // first 32 join them; the off-curve lanes leave.
  for (std::size_t k = 0; k < 40; ++k) on_queue.u[k] = 1000.0 + static_cast<double>(k);
  on_queue.size = 40;
  off_queue.size = 0;
  fill([](std::size_t l) { return l % 2 == 1; });
  std::array<PointResult*, 40> waiting;
  std::copy_n(on_queue.target.begin(), 40, waiting.begin());
  const detail::KindSort joined = detail::sort_by_kind(kBatchLanes, detail::LaneRows(results.data()), w, gathered);
  EXPECT_TRUE(joined.moved);
  ASSERT_EQ(joined.kept, kBatchLanes);
  EXPECT_TRUE(joined.on_curve);
  EXPECT_EQ(off_queue.size, kBatchLanes / 2 - 1);
  ASSERT_EQ(on_queue.size, 8u);
  for (std::size_t k = 0; k < 8; ++k) EXPECT_EQ(on_queue.u[k], 1032.0 + static_cast<double>(k));
  for (std::size_t k = 0; k < kBatchLanes; ++k) {
    EXPECT_EQ(w.u[k], k < 32 ? 2.0 * k : 1000.0 + static_cast<double>(k - 32)) << k;
    EXPECT_EQ(gathered[k], k < 32 ? &results[2 * k] : waiting[k - 32]) << k;
    EXPECT_EQ(w.active[k], 1);
  }

  // Few off the curve (kKindStaysAbove): they leave; the others stay, compacted, in order.
  on_queue.size = off_queue.size = 0;
  fill([](std::size_t l) { return l == 10 || l == 40; });
  const detail::KindSort few = detail::sort_by_kind(kBatchLanes, detail::LaneRows(results.data()), w, gathered);
  const std::size_t kept = few.kept;
  EXPECT_TRUE(few.moved);
  EXPECT_TRUE(few.on_curve);
  ASSERT_EQ(kept, kBatchLanes - 3);  // less lane 7, 10 and 40
  EXPECT_EQ(on_queue.size, 0u);
  ASSERT_EQ(off_queue.size, 2u);
  EXPECT_EQ(off_queue.target[0], &results[10]);
  EXPECT_EQ(off_queue.target[1], &results[40]);
  for (std::size_t k = 0, l = 0; k < kept; ++k, ++l) {
    while (l == 7 || l == 10 || l == 40) ++l;
    EXPECT_EQ(w.u[k], static_cast<double>(l));
    EXPECT_EQ(gathered[k], &results[l]);
    EXPECT_EQ(w.active[k], 1);
  }

  // One kind only (lane 7 apart): the batch is left as it is.
  on_queue.size = off_queue.size = 0;
  fill([](std::size_t) { return true; });
  const detail::KindSort off_only = detail::sort_by_kind(kBatchLanes, detail::LaneRows(results.data()), w, gathered);
  EXPECT_FALSE(off_only.moved);
  EXPECT_EQ(off_only.kept, kBatchLanes);
  EXPECT_FALSE(off_only.on_curve);
  EXPECT_EQ(on_queue.size + off_queue.size, 0u);
  fill([](std::size_t) { return false; });
  const detail::KindSort on_only = detail::sort_by_kind(kBatchLanes, detail::LaneRows(results.data()), w, gathered);
  EXPECT_FALSE(on_only.moved);
  EXPECT_EQ(on_only.kept, kBatchLanes);
  EXPECT_TRUE(on_only.on_curve);
  EXPECT_EQ(on_queue.size + off_queue.size, 0u);
  on_queue.size = off_queue.size = 0;
}

}  // namespace
}  // namespace bezinv
