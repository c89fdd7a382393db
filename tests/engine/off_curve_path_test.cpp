// The off-curve path (engine/src/pipeline/off_curve_path.hpp) against the SVD path it stands in
// for: on many thousands of points off curves of every kind and degree 1-32, in the places where
// the nearest point is hard to tell (near the evolute, where two basins are nearly equally near;
// near and beyond the ends; far away; around self-intersections) and under plain noise, every
// row has the status the SVD path gives it, and a row answered by distance alone (path nearest,
// no singular values) has the SVD path's nearest point of the segment (the same, or one as near).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "support/curve_kinds.hpp"
#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/datasets/self_intersection.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "plan_data.hpp"
#include "refine.hpp"
#include "support/sanitizers.hpp"

namespace bezinv {
namespace {

using test_support::kAllKinds;

// Normalized coordinates back to the input's (the inverse of PlanData::normalize).
Point to_input(const detail::PlanData& plan, double u, double v) {
  const double dx = plan.cos_rotation * u + plan.sin_rotation * v, dy = -plan.sin_rotation * u + plan.cos_rotation * v;
  return {plan.centre[0] + dx * plan.scale, plan.centre[1] + dy * plan.scale};
}

// The places to look, for one curve (normalized units, then in input coordinates).
std::vector<Point> hard_points(const detail::PlanData& plan, std::mt19937_64& rng) {
  std::vector<Point> points;
  const double size = plan.normalized_diagonal;
  const auto around = [&](double u, double v, double r) {
    const double angle = datasets::uniform(rng, 0.0, 6.283185307179586);
    points.push_back(to_input(plan, u + r * std::cos(angle), v + r * std::sin(angle)));
  };
  // Plain noise: Gaussian offsets of 1e-6, 1e-4 and 1e-2 of the diagonal per coordinate.
  std::normal_distribution<double> normal;
  for (double noise : {1e-6, 1e-4, 1e-2})
    for (int i = 0; i < 16; ++i) {
      const auto p = detail::curve_point(plan, datasets::uniform(rng, 0.0, 1.0));
      points.push_back(to_input(plan, p[0] + noise * size * normal(rng), p[1] + noise * size * normal(rng)));
    }
  // Near the evolute: the centre of curvature of P(t), moved along the normal by a little.
  for (int i = 0; i < 12; ++i) {
    const detail::CurveJet j = detail::curve_jet(plan, datasets::uniform(rng, 0.02, 0.98));
    const double speed = std::hypot(j.dx, j.dy), cross = j.dx * j.ddy - j.dy * j.ddx;
    if (!(std::abs(cross) > 0) || !(speed > 0)) continue;
    const double radius = speed * speed * speed / cross;  // signed: along the left normal
    if (!(std::abs(radius) < 10 * size)) continue;
    const double nx = -j.dy / speed, ny = j.dx / speed;
    const double along = radius * (1 + std::copysign(std::pow(10.0, datasets::uniform(rng, -6, -1)), datasets::uniform(rng, -1, 1)));
    points.push_back(to_input(plan, j.x + along * nx, j.y + along * ny));
  }
  // Near and beyond the ends, all around them.
  for (double t : {0.0, 1.0})
    for (double r : {1e-6, 1e-4, 1e-2, 1e-1}) {
      const auto p = detail::curve_point(plan, t);
      around(p[0], p[1], r * size);
      around(p[0], p[1], r * size);
    }
  // Far: 10 to 1000 times the diagonal, every direction.
  for (double r : {10.0, 100.0, 1000.0})
    for (int i = 0; i < 3; ++i) around(0.0, 0.0, r * size);
  return points;
}

struct Tally {
  std::size_t rows = 0, by_distance = 0, off_curve = 0, outside_segment = 0, other = 0;
};

// Every row against the SVD path's; the batch goes through invert() as a user's would.
void compare(const InversionPlan& plan, const std::vector<Point>& points, const std::string& name, Tally& tally) {
  std::vector<PointResult> results(points.size());
  invert(plan, points, results);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (test_support::thinned_out(i)) continue;  // under the sanitizers: every row inverted, some compared
    const PointResult svd = invert_point(plan, points[i], {.fast_path = false});
    const PointResult& r = results[i];
    // The rounding of a distance: 64 ulps of the curve's size or of the distance, the larger.
    const double rounding = 64 * std::numeric_limits<double>::epsilon() * std::max(plan.diagonal(), svd.residual);
    ++tally.rows;
    ASSERT_EQ(r.status, svd.status) << name << " point " << i << " (" << points[i].x << ", " << points[i].y << "): "
                                    << to_string(r.status) << " by " << to_string(r.path) << ", the SVD path "
                                    << to_string(svd.status) << " by " << to_string(svd.path);
    tally.off_curve += r.status == Status::off_curve;
    tally.outside_segment += r.status == Status::outside_segment;
    tally.other += r.status != Status::off_curve && r.status != Status::ok;
    if (!(r.status == Status::off_curve && r.path == Path::nearest && std::isnan(r.sigma_min))) continue;
    ++tally.by_distance;
    EXPECT_EQ(svd.path, Path::nearest) << name << " point " << i;
    // The same nearest point of the segment, or one as near (a tie), to the rounding of the curve.
    EXPECT_LE(std::abs(r.residual - svd.residual), rounding)
        << name << " point " << i << ": by distance t " << r.t << " residual " << r.residual << ", the SVD path t "
        << svd.t << " residual " << svd.residual;
    if (std::abs(r.residual - svd.residual) <= rounding / 8) continue;  // equally near: either t
    EXPECT_NEAR(r.t, svd.t, 1e-9) << name << " point " << i;
  }
}

TEST(OffCurvePath, AnswersAsTheSvdPathAroundCurvesOfEveryKindAndDegree) {
  Tally tally;
  // Perturbed arcs and the unit square's loopier curves, in turn by degree (both at every degree
  // would double the time, mostly the SVD path's, for little more).
  for (CurveKind kind : kAllKinds)
    for (int n = 1; n <= kMaxDegree; ++n) {
      const auto polygon = n % 2 ? datasets::ControlPolygon::perturbed_arc : datasets::ControlPolygon::unit_square;
      std::mt19937_64 rng(6151 + 97 * n + 13 * static_cast<int>(kind) + static_cast<int>(polygon));
      const InversionPlan plan = make_plan(datasets::random_curve(kind, n, rng, polygon));
      const std::vector<Point> points = hard_points(detail::plan_data(plan), rng);
      compare(plan, points, std::string(to_string(kind)) + " degree " + std::to_string(n), tally);
      if (HasFatalFailure()) return;
    }
  std::printf("[ measured ] %zu rows: %zu off_curve (%zu by distance alone), %zu outside_segment, %zu other\n",
              tally.rows, tally.off_curve, tally.by_distance, tally.outside_segment, tally.other);
  RecordProperty("rows", static_cast<int>(tally.rows));
  RecordProperty("by_distance", static_cast<int>(tally.by_distance));
  EXPECT_GT(tally.rows, 7000u / test_support::kSanitizerThinning);
  EXPECT_GT(tally.by_distance, tally.off_curve * 3 / 4);  // the comparison is about the new path
}

// Around a self-intersection P(t1) = P(t2): two branches nearly equally near, the crossing itself
// a double point.
TEST(OffCurvePath, AnswersAsTheSvdPathAroundSelfIntersections) {
  Tally tally;
  for (CurveKind kind : kAllKinds)
    for (int n = 3; n <= 16; ++n) {
      std::mt19937_64 rng(3301 + 7 * n + static_cast<int>(kind));
      const double t1 = datasets::uniform(rng, 0.1, 0.45), t2 = datasets::uniform(rng, 0.55, 0.9);
      const Curve curve = datasets::with_self_intersection(kind, n, t1, t2, rng);
      const InversionPlan plan = make_plan(curve);
      const detail::PlanData& data = detail::plan_data(plan);
      const auto crossing = detail::curve_point(data, t1);
      std::vector<Point> points;
      for (double r : {1e-7, 1e-5, 1e-3, 1e-2, 5e-2})
        for (int i = 0; i < 8; ++i) {
          const double angle = datasets::uniform(rng, 0.0, 6.283185307179586);
          const double d = r * data.normalized_diagonal;
          points.push_back(to_input(data, crossing[0] + d * std::cos(angle), crossing[1] + d * std::sin(angle)));
        }
      compare(plan, points, std::string(to_string(kind)) + " degree " + std::to_string(n) + " crossing", tally);
      if (HasFatalFailure()) return;
    }
  std::printf("[ measured ] %zu rows around crossings: %zu off_curve (%zu by distance alone), %zu other\n", tally.rows,
              tally.off_curve, tally.by_distance, tally.other);
  EXPECT_GT(tally.by_distance, 300u);
  EXPECT_GT(tally.other, 50u);  // double points among them
}

}  // namespace
}  // namespace bezinv
