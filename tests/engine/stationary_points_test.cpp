// The certified nearest point of the segment (engine/src/stationary_points.hpp): where it says it
// proved its answer, no point of the segment is nearer. Checked against a dense grid of the curve
// evaluated here (de Casteljau on the plan's normalized polynomials, not the engine's evaluation),
// against the sampling search it stands in front of, and on curves whose nearest points are known
// in closed form.
#include "stationary_points.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/plan.hpp"
#include "plan_data.hpp"
#include "refine.hpp"
#include "support/sanitizers.hpp"

namespace bezinv {
namespace {

double bernstein_by_de_casteljau(std::vector<double> c, double t) {
  for (std::size_t level = 1; level < c.size(); ++level)
    for (std::size_t i = 0; i + level < c.size(); ++i) c[i] = (1 - t) * c[i] + t * c[i + 1];
  return c[0];
}

std::array<double, 2> normalized_point(const detail::PlanData& plan, double t) {
  return {bernstein_by_de_casteljau(plan.x_num, t) / bernstein_by_de_casteljau(plan.x_den, t),
          bernstein_by_de_casteljau(plan.y_num, t) / bernstein_by_de_casteljau(plan.y_den, t)};
}

double distance_to(const std::array<double, 2>& p, double u0, double v0) { return std::hypot(p[0] - u0, p[1] - v0); }

TEST(CertifiedNearest, NoPointOfTheSegmentIsNearerThanACertifiedAnswer) {
  constexpr int kGrid = 3000;
  constexpr double kSlack = 1e-12;  // normalized units: the curve's size is about 1
  const std::vector<double> noises = {1e-6, 1e-4, 1e-2, 0.3, 3.0};
  for (CurveKind kind : {CurveKind::bezier, CurveKind::rational_bezier, CurveKind::rational})
    for (int n : {1, 2, 3, 5, 8, 12, 15, 20, 24, 32}) {
      std::vector<int> tried(noises.size(), 0), proved(noises.size(), 0);
      for (auto polygon : {datasets::ControlPolygon::perturbed_arc, datasets::ControlPolygon::unit_square}) {
        std::mt19937_64 rng(4049 + 17 * n + static_cast<int>(kind));
        // Two curves each; one under the sanitizers (support/sanitizers.hpp).
        for (int curve_index = 0; curve_index < (test_support::kSanitizerThinning > 1 ? 1 : 2); ++curve_index) {
          const detail::PlanData plan = detail::plan_data(make_plan(datasets::random_curve(kind, n, rng, polygon)));
          std::vector<std::array<double, 2>> grid(kGrid + 1);
          for (int k = 0; k <= kGrid; ++k) grid[k] = normalized_point(plan, static_cast<double>(k) / kGrid);
          for (std::size_t level = 0; level < noises.size(); ++level)
            for (int i = 0; i < 12; ++i) {
              const double t0 = datasets::uniform(rng, -0.05, 1.05), angle = datasets::uniform(rng, 0.0, 6.283185307179586);
              const auto base = normalized_point(plan, t0);
              const double r = noises[level] * plan.normalized_diagonal;
              const double u0 = base[0] + r * std::cos(angle), v0 = base[1] + r * std::sin(angle);
              const detail::NearestOnSegment found = detail::certified_nearest_on_segment(plan, u0, v0, -1.0);
              ++tried[level];
              if (!found.certified) continue;
              ++proved[level];
              SCOPED_TRACE(std::string(to_string(kind)) + " n=" + std::to_string(n) + " noise=" +
                           std::to_string(noises[level]) + " t=" + std::to_string(found.t));
              ASSERT_GE(found.t, 0.0);
              ASSERT_LE(found.t, 1.0);
              EXPECT_NEAR(found.distance, distance_to(normalized_point(plan, found.t), u0, v0), kSlack);
              double grid_best = std::numeric_limits<double>::infinity();
              for (const auto& p : grid) grid_best = std::min(grid_best, distance_to(p, u0, v0));
              EXPECT_LE(found.distance, grid_best + kSlack);
              // Never worse than the sampling search either.
              const double sampled = detail::nearest_parameter_by_sampling(plan, u0, v0, -1.0);
              EXPECT_LE(found.distance, distance_to(normalized_point(plan, sampled), u0, v0) + kSlack);
            }
        }
      }
      // The proof must hold for nearly every point, or the search it stands in front of does the work.
      for (std::size_t level = 0; level < noises.size(); ++level)
        EXPECT_GE(proved[level], 0.9 * tried[level])
            << to_string(kind) << " n=" << n << " noise=" << noises[level] << ": " << proved[level] << " of "
            << tried[level];
    }
}

// y = x^2 on x in [-1, 1] (a quadratic Bezier curve): from (0, h), h > 1/2, the nearest points are
// x = +-sqrt(h - 1/2) at distance sqrt(h - 1/4); below h = 1/2 the vertex, at distance h.
TEST(CertifiedNearest, ParabolaFromItsAxisIsAtTheKnownDistance) {
  Curve curve;
  curve.kind = CurveKind::bezier;
  curve.x_num = {-1.0, 0.0, 1.0};
  curve.y_num = {1.0, -1.0, 1.0};
  curve.x_den = curve.y_den = {1.0, 1.0, 1.0};
  const detail::PlanData plan = detail::plan_data(make_plan(curve));
  for (double h : {0.1, 0.3, 0.6, 0.75, 1.0, 1.2}) {
    const auto p0 = plan.normalize(0.0, h);
    const detail::NearestOnSegment found = detail::certified_nearest_on_segment(plan, p0[0], p0[1], -1.0);
    ASSERT_TRUE(found.certified) << "h = " << h;
    const double expected = h > 0.5 ? std::sqrt(h - 0.25) : h;
    EXPECT_NEAR(found.distance * plan.scale, expected, 1e-14) << "h = " << h;
    const double x = 2 * found.t - 1;
    EXPECT_NEAR(std::abs(x), h > 0.5 ? std::sqrt(h - 0.5) : 0.0, 1e-7) << "h = " << h;
  }
}

// A quarter circle (rational quadratic, weights 1, 1/sqrt2, 1): from its centre every point is
// equally near, the derivative of the distance vanishes identically, and no sign can be trusted:
// the answer must not claim a proof. Off the centre, it does, and the nearest point is on the ray.
TEST(CertifiedNearest, QuarterCircleFromItsCentreIsNotCertifiedAndElsewhereIsOnTheRay) {
  const double w = std::sqrt(0.5);
  Curve curve;
  curve.kind = CurveKind::rational_bezier;
  curve.x_num = {1.0, w, 0.0};
  curve.y_num = {0.0, w, 1.0};
  curve.x_den = curve.y_den = {1.0, w, 1.0};
  const detail::PlanData plan = detail::plan_data(make_plan(curve));
  const auto centre = plan.normalize(0.0, 0.0);
  EXPECT_FALSE(detail::certified_nearest_on_segment(plan, centre[0], centre[1], -1.0).certified);
  for (double angle : {0.2, 0.7, 1.3})
    for (double radius : {0.25, 0.9, 1.1, 3.0}) {
      const auto p0 = plan.normalize(radius * std::cos(angle), radius * std::sin(angle));
      const detail::NearestOnSegment found = detail::certified_nearest_on_segment(plan, p0[0], p0[1], -1.0);
      ASSERT_TRUE(found.certified) << angle << " " << radius;
      EXPECT_NEAR(found.distance * plan.scale, std::abs(radius - 1.0), 1e-14) << angle << " " << radius;
    }
}

// A point so far (1e20 times the curve's size) that its distances to every point of the curve
// round to one double: the nearest point in exact arithmetic is the point of the segment farthest
// along the point's direction, and that is what the search must give (not whichever point it
// happened to look at first). Checked on a dense grid: no point of it lies farther along.
// An improper parametrization (the curve traced there and back, P(t) = P(1 - t)) stops at t = 1/2:
// P'(1/2) = 0, so t = 1/2 is a stationary point of the distance for every point, here a maximum.
// A point on the curve near the turn lies at two parameters either side of it, one in each of the
// pieces that meet at 1/2; the search must find one of them, not the turning point, whatever it
// starts from. The points are made from known t (construction).
TEST(CertifiedNearest, AnImproperCurvesTurningPointIsNotTakenForTheNearest) {
  const detail::PlanData plan = detail::plan_data(
      make_plan(Curve::bezier("improper", {{1, 1}, {0, -1}, {-1.0 / 3, 1}, {0, -1}, {1, 1}})));
  for (double t_true : {0.49, 0.498, 0.4999, 0.45, 0.3}) {
    const auto p0 = normalized_point(plan, t_true);
    for (double hint : {-1.0, 0.5, t_true, 1 - t_true}) {
      const detail::NearestOnSegment found = detail::certified_nearest_on_segment(plan, p0[0], p0[1], hint);
      ASSERT_TRUE(found.certified) << t_true << " hint " << hint;
      EXPECT_LE(found.distance, 1e-15) << t_true << " hint " << hint << " t " << found.t;
      EXPECT_NEAR(std::min(std::abs(found.t - t_true), std::abs(found.t - (1 - t_true))), 0.0, 1e-9)
          << t_true << " hint " << hint;
    }
  }
}

TEST(CertifiedNearest, AFarPointGetsThePointOfTheSegmentFarthestAlongItsDirection) {
  constexpr int kGrid = 4000;
  for (CurveKind kind : {CurveKind::bezier, CurveKind::rational_bezier, CurveKind::rational})
    for (int n : {1, 2, 3, 7, 12, 20}) {
      std::mt19937_64 rng(733 + n + 100 * static_cast<int>(kind));
      const detail::PlanData plan = detail::plan_data(
          make_plan(datasets::random_curve(kind, n, rng, datasets::ControlPolygon::perturbed_arc)));
      for (int i = 0; i < 8; ++i) {
        const double angle = datasets::uniform(rng, 0.0, 6.283185307179586);
        const double cx = std::cos(angle), cy = std::sin(angle);
        const double t = detail::nearest_parameter_on_segment(plan, 1e20 * cx, 1e20 * cy, -1.0);
        ASSERT_GE(t, 0.0);
        ASSERT_LE(t, 1.0);
        const auto p = normalized_point(plan, t);
        double farthest = -std::numeric_limits<double>::infinity();
        for (int k = 0; k <= kGrid; ++k) {
          const auto q = normalized_point(plan, static_cast<double>(k) / kGrid);
          farthest = std::max(farthest, q[0] * cx + q[1] * cy);
        }
        // The stand-in at kFarStandIn moves the answer by O(1 / kFarStandIn) of the curve's size.
        EXPECT_GE(p[0] * cx + p[1] * cy, farthest - 1e-7)
            << to_string(kind) << " n=" << n << " angle " << angle << " t " << t;
      }
    }
}

}  // namespace
}  // namespace bezinv
