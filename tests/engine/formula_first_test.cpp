// formula_first (engine/src/pipeline/formula_first.cpp): the formula path's common case in one
// pass must give every lane it answers the row the stages give it (invert_batch_by_stages), bit
// for bit, and leave every other lane to them. Points of every kind a file holds: on the curve
// (made at a known t, whose t the answers must also find), within 1e-13 to 1e-6 of the diagonal of
// it, near and past the ends, near the curve's other branches, far away, and not finite; on
// conics and cubics (the fused kernel, formula_newton), graphs of functions, and, asked for, the
// curve's own formula from degree 4 (the kernels one after the other).
#include "pipeline/formula_first.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "pipeline/batch.hpp"
#include "pipeline/by_kind.hpp"
#include "pipeline/formula_path.hpp"
#include "pipeline/stage_clock.hpp"
#include "pipeline/workspace.hpp"
#include "plan_data.hpp"
#include "support/bits.hpp"
#include "support/same_row.hpp"
#include "support/sanitizers.hpp"

namespace bezinv {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A batch's worth of points of every kind, the on-curve ones (from t in `known`, NaN for the
// others) a little over half.
std::vector<Point> every_kind_of_point(const Curve& curve, double diagonal, std::mt19937_64& rng,
                                       std::vector<double>& known) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), exponent(-13.0, -6.0);
  std::vector<Point> points;
  known.clear();
  auto add = [&](Point p, double t) {
    points.push_back(p);
    known.push_back(t);
  };
  for (int k = 0; k < 72; ++k) {
    const double t = k < 8 ? std::pow(10.0, -1.0 - k) : unit(rng);  // some within 1e-9 of the start
    add(datasets::on_curve(curve, k % 2 ? t : 1.0 - t), k % 2 ? t : 1.0 - t);
  }
  for (int k = 0; k < 40; ++k) {  // near the curve: 1e-13 to 1e-6 of the diagonal, any direction
    const Point p = datasets::on_curve(curve, unit(rng));
    const double angle = 2 * M_PI * unit(rng), d = std::pow(10.0, exponent(rng)) * diagonal;
    add({p.x + d * std::cos(angle), p.y + d * std::sin(angle)}, kNaN);
  }
  for (int k = 0; k < 8; ++k) {  // off it: 1e-3 to 10 diagonals
    const Point p = datasets::on_curve(curve, unit(rng));
    const double d = std::pow(10.0, -3.0 + k / 2.0) * diagonal;
    add({p.x + d, p.y - d}, kNaN);
  }
  // Past the ends along the chord from the other end; not finite; far beyond any formula's reach.
  const Point a = datasets::on_curve(curve, 0.0), b = datasets::on_curve(curve, 1.0);
  add({a.x + 1e-3 * (a.x - b.x), a.y + 1e-3 * (a.y - b.y)}, kNaN);
  add({b.x + 1e-9 * (b.x - a.x), b.y + 1e-9 * (b.y - a.y)}, kNaN);
  add({kNaN, a.y}, kNaN);
  add({a.x, kInf}, kNaN);
  add({-kInf, kNaN}, kNaN);
  add({1e300, -1e300}, kNaN);
  add({a.x * 1e12, b.y}, kNaN);
  add(a, 0.0);
  return points;
}

struct Tally {
  std::size_t rows = 0, answered_first = 0, on_curve = 0, on_curve_first = 0;
};

// Every batch of the curve's points: rows with formula_first against rows by the stages alone,
// every one bit for bit; the on-curve points' t against their known t.
void check_curve(const Curve& curve, const InvertOptions& options, std::mt19937_64& rng, Tally& tally,
                 const std::string& what) {
  const InversionPlan plan = make_plan(curve);
  const detail::PlanData& data = detail::plan_data(plan);
  ASSERT_TRUE(detail::takes_formula_first(data, options)) << what;
  std::vector<double> known;
  std::vector<Point> points = every_kind_of_point(curve, plan.diagonal(), rng, known);
  // Shuffled (the kinds mixed in each batch), known alongside.
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<Point> shuffled(points.size());
  std::vector<double> shuffled_known(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) shuffled[i] = points[order[i]], shuffled_known[i] = known[order[i]];

  std::vector<PointResult> first(points.size()), staged(points.size());
  {
    const detail::QueueScope scope;
    for (std::size_t s = 0; s < points.size(); s += detail::kBatchLanes) {
      const std::size_t count = std::min(detail::kBatchLanes, points.size() - s);
      detail::invert_batch(data, &shuffled[s], &first[s], count, options, nullptr);
      // Which lanes formula_first answers itself, for the tally.
      std::array<PointResult, detail::kBatchLanes> scratch;
      detail::StageClock clock(nullptr);
      const detail::FormulaLeft left =
          detail::formula_first(data, &shuffled[s], scratch.data(), count, options, detail::batch_workspace(), clock);
      std::vector<bool> leaves(count, false);
      for (std::size_t k = 0; k < left.count; ++k) leaves[left.lane_of[k]] = true;
      for (std::size_t l = 0; l < count; ++l) {
        tally.answered_first += !leaves[l];
        if (!leaves[l]) {
          EXPECT_TRUE(test_support::same_row(scratch[l], first[s + l])) << what << " point " << s + l;
        }
        if (!std::isnan(shuffled_known[s + l])) ++tally.on_curve, tally.on_curve_first += !leaves[l];
      }
    }
    detail::flush_queues(data, options, nullptr);
  }
  {
    const detail::QueueScope scope;
    for (std::size_t s = 0; s < points.size(); s += detail::kBatchLanes)
      detail::invert_batch_by_stages(data, &shuffled[s], &staged[s], std::min(detail::kBatchLanes, points.size() - s),
                                     options);
    detail::flush_queues(data, options, nullptr);
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    ASSERT_TRUE(test_support::same_row(first[i], staged[i]))
        << what << " point " << i << " (" << shuffled[i].x << ", " << shuffled[i].y << ")";
    if (!std::isnan(shuffled_known[i]) && first[i].status == Status::ok) {
      EXPECT_NEAR(first[i].t, shuffled_known[i], 1e-9) << what << " point " << i;
    }
  }
  tally.rows += points.size();
}

TEST(FormulaFirst, EveryRowItWritesIsTheStagesRow) {
  const int curves = test_support::kSanitizerTree ? 6 : 30;
  Tally tally;
  std::mt19937_64 rng(20261206);
  for (int n : {2, 3})
    for (CurveKind kind : {CurveKind::bezier, CurveKind::rational_bezier})
      for (datasets::ControlPolygon polygon :
           {datasets::ControlPolygon::perturbed_arc, datasets::ControlPolygon::unit_square})
        for (int c = 0; c < curves; ++c) {
          const Curve curve = datasets::random_curve(kind, n, rng, polygon);
          const InversionPlan plan = make_plan(curve);
          if (!detail::takes_formula_first(detail::plan_data(plan), {})) continue;  // wide weights: the Bezout path
          check_curve(curve, {}, rng, tally,
                      std::string(to_string(kind)) + " degree " + std::to_string(n) + " curve " + std::to_string(c));
        }
  // The test means something: most rows, and nearly every on-curve one, answered by formula_first.
  EXPECT_GT(tally.rows, 100u * static_cast<std::size_t>(curves));
  EXPECT_GT(tally.answered_first, tally.rows / 2);
  EXPECT_GT(tally.on_curve_first, tally.on_curve * 9 / 10);
  std::printf("%zu rows, %zu answered by formula_first; on the curve %zu of %zu\n", tally.rows, tally.answered_first,
              tally.on_curve_first, tally.on_curve);
}

// Graphs of functions, y = f(x) with x(t) linear (map coordinates, easing curves): the plan's
// linear formula t = (x - x0) / (x1 - x0), at any degree (fused for conics and cubics).
TEST(FormulaFirst, GraphsOfFunctionsAtEveryDegree) {
  Tally tally;
  std::mt19937_64 rng(20261208);
  std::uniform_real_distribution<double> ordinate(-1.0, 1.0), origin(-1e3, 1e3);
  for (int n : {2, 3, 5, 9}) {
    for (int c = 0; c < (test_support::kSanitizerTree ? 2 : 6); ++c) {
      const double x0 = origin(rng), y0 = origin(rng), width = 1 + 10 * (ordinate(rng) + 1);
      std::vector<std::array<double, 2>> polygon;
      for (int i = 0; i <= n; ++i) polygon.push_back({x0 + width * i / n, y0 + width * ordinate(rng)});
      const Curve curve = Curve::bezier("graph", polygon);
      const InversionPlan plan = make_plan(curve);
      if (!detail::takes_formula_first(detail::plan_data(plan), {})) continue;
      check_curve(curve, {}, rng, tally, "graph of degree " + std::to_string(n) + " curve " + std::to_string(c));
    }
  }
  EXPECT_GT(tally.rows, 0u);
  EXPECT_GT(tally.on_curve_first, tally.on_curve * 9 / 10);
}

// The curve's own formula, asked for (degree 4 and up: the kernels one after the other, not fused).
TEST(FormulaFirst, TheCurvesOwnFormulaFromDegreeFourToo) {
  Tally tally;
  std::mt19937_64 rng(20261207);
  const InvertOptions options{.algebraic = Algebraic::formula};
  for (int n : {4, 6})
    for (int c = 0; c < (test_support::kSanitizerTree ? 2 : 6); ++c) {
      const Curve curve =
          datasets::random_curve(CurveKind::rational_bezier, n, rng, datasets::ControlPolygon::perturbed_arc);
      const InversionPlan plan = make_plan(curve);
      if (!detail::takes_formula_first(detail::plan_data(plan), options)) continue;
      check_curve(curve, options, rng, tally, "degree " + std::to_string(n) + " curve " + std::to_string(c));
    }
  EXPECT_GT(tally.on_curve_first, tally.on_curve * 9 / 10);
}

// A batch formula_first leaves whole (every point off the curve) goes on in place, from what it
// computed for its lanes; a batch it leaves in part sends its lanes to the stages queue, run once
// it holds a batch's worth. Here: a batch on the curve (after which formula_first is not skipped),
// then one off it at noise 1e-8 to 1e-2 of the diagonal, then batches of both kinds; every row
// against the stages' row, and formula_first seen to leave the off-curve batch whole, most of its
// lanes left by the first Newton iteration (the lanes that path takes up).
TEST(FormulaFirst, LanesItLeavesGoOnFromWhereItLeftThem) {
  std::mt19937_64 rng(20261209);
  std::uniform_real_distribution<double> unit(0.0, 1.0), exponent(-8.0, -2.0);
  std::size_t whole = 0, newton_left = 0;
  for (const InvertOptions options : {InvertOptions{}, InvertOptions{.algebraic = Algebraic::formula}})
    for (int n : {2, 3, 6})
      for (int c = 0; c < (test_support::kSanitizerTree ? 2 : 8); ++c) {
        const Curve curve =
            datasets::random_curve(CurveKind::rational_bezier, n, rng, datasets::ControlPolygon::perturbed_arc);
        const InversionPlan plan = make_plan(curve);
        const detail::PlanData& data = detail::plan_data(plan);
        if (!detail::takes_formula_first(data, options)) continue;
        const std::size_t lanes = detail::kBatchLanes;
        std::vector<Point> points;
        auto off_curve = [&] {
          const Point p = datasets::on_curve(curve, unit(rng));
          const double angle = 2 * M_PI * unit(rng), d = std::pow(10.0, exponent(rng)) * plan.diagonal();
          return Point{p.x + d * std::cos(angle), p.y + d * std::sin(angle)};
        };
        for (std::size_t k = 0; k < lanes; ++k) points.push_back(datasets::on_curve(curve, unit(rng)));
        for (std::size_t k = 0; k < lanes; ++k) points.push_back(off_curve());
        for (std::size_t k = 0; k < 5 * lanes; ++k)
          points.push_back(k % 2 ? off_curve() : datasets::on_curve(curve, unit(rng)));
        {  // formula_first on the off-curve batch alone: it leaves it whole
          std::array<PointResult, detail::kBatchLanes> scratch;
          detail::StageClock clock(nullptr);
          const detail::FormulaLeft left = detail::formula_first(data, &points[lanes], scratch.data(), lanes, options,
                                                                 detail::batch_workspace(), clock);
          whole += left.count == lanes;
          for (std::size_t l = 0; l < lanes; ++l) newton_left += left.first_iteration_leaves.has(l);
        }
        std::vector<PointResult> first(points.size()), staged(points.size());
        {
          const detail::QueueScope scope;
          for (std::size_t s = 0; s < points.size(); s += lanes)
            detail::invert_batch(data, &points[s], &first[s], std::min(lanes, points.size() - s), options, nullptr);
          detail::flush_queues(data, options, nullptr);
        }
        {
          const detail::QueueScope scope;
          for (std::size_t s = 0; s < points.size(); s += lanes)
            detail::invert_batch_by_stages(data, &points[s], &staged[s], std::min(lanes, points.size() - s), options);
          detail::flush_queues(data, options, nullptr);
        }
        for (std::size_t i = 0; i < points.size(); ++i)
          ASSERT_TRUE(test_support::same_row(first[i], staged[i])) << "degree " << n << " curve " << c << " point " << i
                                                                   << " (" << points[i].x << ", " << points[i].y << ")";
      }
  EXPECT_GT(whole, 0u);
  EXPECT_GT(newton_left, whole * detail::kBatchLanes / 2);
}

// Where formula_first does not keep each lane's point normalized and N / M (after a batch it
// settled whole), the lanes it leaves reach the stages queue with the same values, computed there,
// bit for bit: against the values it keeps, for batches of both kinds on conics and cubics.
TEST(FormulaFirst, NotKeptTheStartsAreComputedTheSame) {
  std::mt19937_64 rng(20261210);
  std::uniform_real_distribution<double> unit(0.0, 1.0), exponent(-8.0, -2.0);
  std::size_t compared = 0;
  for (int n : {2, 3})
    for (int c = 0; c < 6; ++c) {
      const Curve curve =
          datasets::random_curve(CurveKind::rational_bezier, n, rng, datasets::ControlPolygon::perturbed_arc);
      const InversionPlan plan = make_plan(curve);
      const detail::PlanData& data = detail::plan_data(plan);
      if (!detail::takes_formula_first(data, {})) continue;
      std::vector<Point> points;
      for (std::size_t k = 0; k < detail::kBatchLanes; ++k) {
        Point p = datasets::on_curve(curve, unit(rng));
        const double d = k % 3 ? 0.0 : std::pow(10.0, exponent(rng)) * plan.diagonal();
        points.push_back({p.x + d, p.y - d});
      }
      points[5] = {kNaN, 0.0};
      std::array<PointResult, detail::kBatchLanes> scratch;
      detail::StageClock clock(nullptr);
      detail::BatchWorkspace& w = detail::batch_workspace();
      const detail::QueueScope scope;
      const detail::FormulaLeft kept =
          detail::formula_first(data, points.data(), scratch.data(), points.size(), {}, w, clock, /*keep=*/true);
      ASSERT_TRUE(kept.given);
      std::vector<double> u, v, t;
      for (std::size_t k = 0; k < kept.count; ++k) {
        const std::size_t l = kept.lane_of[k];
        u.push_back(w.u[l]), v.push_back(w.v[l]), t.push_back(w.t_algebraic[l]);
      }
      const detail::FormulaLeft not_kept =
          detail::formula_first(data, points.data(), scratch.data(), points.size(), {}, w, clock, /*keep=*/false);
      ASSERT_FALSE(not_kept.given);
      ASSERT_EQ(not_kept.count, kept.count);
      detail::StagesQueue& queue = detail::stages_queue();
      queue.size = 0;
      detail::queue_for_stages(data, points.data(), scratch.data(), not_kept, w);
      ASSERT_EQ(queue.size, kept.count);
      for (std::size_t k = 0; k < kept.count; ++k) {
        EXPECT_TRUE(test_support::same_bits(queue.u[k], u[k]) && test_support::same_bits(queue.v[k], v[k]) &&
                    test_support::same_bits(queue.t[k], t[k]))
            << "degree " << n << " curve " << c << " lane " << int(kept.lane_of[k]);
        EXPECT_EQ(queue.first_iteration_leaves[k] != 0, kept.first_iteration_leaves.has(kept.lane_of[k]));
        ++compared;
      }
      queue.size = 0;
    }
  EXPECT_GT(compared, 100u);
}

}  // namespace
}  // namespace bezinv
