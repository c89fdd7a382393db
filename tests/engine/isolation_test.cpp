// engine/src/isolation.cpp: the certificate that lets the fast path skip its second-parameter walks.
// What it promises is checked directly, against the walks it replaces and against the curve:
//   - every piece of the curve lies in its box;
//   - around each piece, the curve is as monotone as the stored bound says;
//   - where a point is certified, no refinement of the distance (refine_parameter, the walk the
//     fast path would run from each root) started anywhere on [0, 1] ends within the tolerance at
//     a parameter distinct from t;
//   - at a double point, and next to one, nothing is certified.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/datasets/self_intersection.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "isolation.hpp"
#include "refine.hpp"

namespace bezinv {
namespace {

constexpr int K = detail::kIsolationPieces;

TEST(Isolation, EveryPieceOfTheCurveLiesInItsBox) {
  std::mt19937_64 rng(5);
  int boxes = 0;
  for (int n = 2; n <= 24; ++n)
    for (auto polygon : {datasets::ControlPolygon::unit_square, datasets::ControlPolygon::perturbed_arc}) {
      const InversionPlan plan = make_plan(datasets::random_curve(CurveKind::rational_bezier, n, rng, polygon));
      ASSERT_EQ(plan.isolation_boxes.size(), 4u * K);
      for (int j = 0; j < K; ++j) {
        const double* b = plan.isolation_boxes.data();  // x centres, x half-widths, y centres, y half-widths
        const double box[4] = {b[j] - b[K + j], b[j] + b[K + j],  // x min, x max, y min, y max
                               b[2 * K + j] - b[3 * K + j], b[2 * K + j] + b[3 * K + j]};
        for (double side : box) ASSERT_TRUE(std::isfinite(side)) << "positive weights, piece " << j;  // in [0.5, 2]
        ++boxes;
        for (int s = 0; s <= 20; ++s) {
          const double t = (j + s / 20.0) / K;
          const auto p = plan.normalized_point(t);
          EXPECT_GE(p[0], box[0]) << "n " << n << " t " << t;
          EXPECT_LE(p[0], box[1]) << "n " << n << " t " << t;
          EXPECT_GE(p[1], box[2]) << "n " << n << " t " << t;
          EXPECT_LE(p[1], box[3]) << "n " << n << " t " << t;
        }
      }
    }
  RecordProperty("boxes", boxes);
}

// The bound m of piece j says: for t, tau in pieces j-1..j+1,
//   sign(tau - t) (P(tau) - P(t)) . P'(tau) >= 2 m |tau - t| |P'(tau)|   (isolation.hpp).
TEST(Isolation, TheCurveIsAsMonotoneAroundEachPieceAsItsBoundSays) {
  std::mt19937_64 rng(6);
  int bounded = 0, checked = 0;
  for (int n = 2; n <= 24; ++n)
    for (auto polygon : {datasets::ControlPolygon::unit_square, datasets::ControlPolygon::perturbed_arc}) {
      const InversionPlan plan = make_plan(datasets::random_curve(CurveKind::rational_bezier, n, rng, polygon));
      for (int j = 0; j < K; ++j) {
        const double m = plan.isolation_monotone[j];
        ASSERT_GE(m, 0.0);
        if (m == 0) continue;
        ++bounded;
        const double lo = std::max(0, j - 1) / double(K), hi = std::min(K, j + 2) / double(K);
        for (int k = 0; k < 40; ++k) {
          const double t = datasets::uniform(rng, lo, hi), tau = datasets::uniform(rng, lo, hi);
          const auto a = plan.normalized_point(t);
          const detail::CurveJet b = detail::curve_jet(plan, tau);
          const double along = ((b.x - a[0]) * b.dx + (b.y - a[1]) * b.dy) * (tau > t ? 1 : -1);
          const double bound = 2 * m * std::abs(tau - t) * std::hypot(b.dx, b.dy);
          EXPECT_GE(along, bound * (1 - 1e-9) - 1e-15) << "n " << n << " piece " << j << " t " << t << " tau " << tau;
          ++checked;
        }
      }
    }
  RecordProperty("pieces_with_a_bound", bounded);
  RecordProperty("pairs_checked", checked);
  EXPECT_GT(bounded, 100);
}

// The promise itself, on curves that loop and cross (random control points in a square) and with a
// loose tolerance, so that other branches often come within it.
TEST(Isolation, NoWalkEndsWithinTheToleranceAwayFromACertifiedParameter) {
  std::mt19937_64 rng(8);
  int certified = 0, refused = 0;
  for (int n : {3, 4, 5, 6, 8, 10, 12, 15, 20})
    for (int c = 0; c < 6; ++c) {
      const InversionPlan plan =
          make_plan(datasets::random_curve(CurveKind::rational_bezier, n, rng, datasets::ControlPolygon::unit_square));
      for (double relative_tolerance : {1e-6, 1e-3, 3e-2}) {
        const double tolerance = relative_tolerance * plan.diagonal / plan.scale;
        for (int k = 0; k < 12; ++k) {
          const double t = datasets::uniform(rng, 0.0, 1.0);
          const auto p = plan.normalized_point(t);
          const detail::Refined own = detail::refine_parameter(plan, p[0], p[1], t, true);
          if (!detail::isolated(plan, p[0], p[1], own.t, own.distance, tolerance)) {
            ++refused;
            continue;
          }
          ++certified;
          for (int s = 0; s <= 100; ++s) {
            const detail::Refined r = detail::refine_parameter(plan, p[0], p[1], s / 100.0, true);
            const bool second = r.distance <= tolerance && std::abs(r.t - own.t) > kDistinctParameterGap;
            EXPECT_FALSE(second) << "n " << n << " t " << own.t << " walk from " << s / 100.0 << " ends at " << r.t
                                 << ", distance " << r.distance << " <= " << tolerance;
          }
        }
      }
    }
  RecordProperty("certified", certified);
  RecordProperty("refused", refused);
  EXPECT_GT(certified, 100);
  EXPECT_GT(refused, 50);  // the loose tolerances and the loops must refuse some
}

// At a double point (the two branches through one point) and next to it nothing is certified,
// whether the two parameters are far apart (the boxes refuse) or close (the bound around t does).
TEST(Isolation, NothingIsCertifiedAtADoublePoint) {
  std::mt19937_64 rng(9);
  int near_pairs = 0, far_pairs = 0;
  for (int n : {3, 4, 5, 6, 8, 10, 12, 15})
    for (auto [t1, t2] : {std::pair{0.2, 0.75}, std::pair{0.1, 0.9}, std::pair{0.40, 0.47}, std::pair{0.5, 0.58}}) {
      Curve curve;
      try {  // a loop as short as 0.07 is not always to be had
        curve = datasets::with_self_intersection(CurveKind::rational_bezier, n, t1, t2, rng);
      } catch (const std::runtime_error&) {
        continue;
      }
      (t2 - t1 < 0.1 ? near_pairs : far_pairs)++;
      const InversionPlan plan = make_plan(curve);
      const double tolerance = kDefaultRelativeTolerance * plan.diagonal / plan.scale;
      for (double t : {t1, t2}) {
        const auto p = plan.normalized_point(t);
        EXPECT_FALSE(detail::isolated(plan, p[0], p[1], t, 0.0, tolerance)) << "n " << n << " t " << t;
        // A point of this branch a little away from the crossing, the other branch within the tolerance.
        for (double dt : {-1e-7, 1e-7}) {
          const auto q = plan.normalized_point(t + dt);
          EXPECT_FALSE(detail::isolated(plan, q[0], q[1], t + dt, 0.0, tolerance)) << "n " << n << " t " << t + dt;
        }
      }
    }
  RecordProperty("near_pairs", near_pairs);
  RecordProperty("far_pairs", far_pairs);
  EXPECT_GE(near_pairs, 4);  // the parameters in the same or the next piece: the bound around t refuses
  EXPECT_GE(far_pairs, 8);
}

TEST(Isolation, NotForSeparateDenominatorsOrOffTheCurve) {
  std::mt19937_64 rng(10);
  const InversionPlan separate = make_plan(datasets::random_curve(CurveKind::rational, 5, rng));
  EXPECT_TRUE(separate.isolation_monotone.empty());
  const auto p = separate.normalized_point(0.3);
  EXPECT_FALSE(detail::isolated(separate, p[0], p[1], 0.3, 0.0, 1e-6));

  const InversionPlan plan = make_plan(
      datasets::random_curve(CurveKind::rational_bezier, 5, rng, datasets::ControlPolygon::perturbed_arc));
  const int j = static_cast<int>(0.3 * K);
  ASSERT_GT(plan.isolation_monotone[j], 0.0);
  const auto q = plan.normalized_point(0.3);
  EXPECT_TRUE(detail::isolated(plan, q[0], q[1], 0.3, 0.0, 1e-6));
  // A point off the curve by more than the bound allows: not certified, however isolated.
  const double off = 2 * plan.isolation_monotone[j] * kDistinctParameterGap;
  EXPECT_FALSE(detail::isolated(plan, q[0], q[1], 0.3, off, 1e-6));
  EXPECT_FALSE(detail::isolated(plan, q[0], q[1], std::nan(""), 0.0, 1e-6));
}

}  // namespace
}  // namespace bezinv
