// engine/src/isolation.cpp: the certificate that lets the fast path skip its second-parameter walks.
// What it promises is checked directly, against the walks it replaces and against the curve:
//   - every piece of the curve lies in its box and its capsule;
//   - around each piece, the curve is as monotone as the stored bound says, and below the stored
//     distance the distance from a point to the curve has one minimum there;
//   - where a point is certified, no refinement of the distance (refine_parameter, the walk the
//     fast path would run from each root) started anywhere on [0, 1] ends within the tolerance at
//     a parameter distinct from t, for points on the curve and off it;
//   - at a double point, and next to one, nothing is certified.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "bezinv/datasets/on_curve_points.hpp"
#include "plan_data.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/datasets/self_intersection.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "isolation.hpp"
#include "refine.hpp"
#include "support/sanitizers.hpp"

namespace bezinv {
namespace {

// Both kinds the certificate covers: one denominator, and separate ones for x and y.
constexpr CurveKind kRationalKinds[] = {CurveKind::rational_bezier, CurveKind::rational};

// Random curves of degrees first..last, one per kind and kind of control polygon: f(n, plan).
template <class F>
void for_each_random_plan(std::mt19937_64& rng, int first, int last, F&& f) {
  for (int n = first; n <= last; ++n)
    for (CurveKind kind : kRationalKinds)
      for (auto polygon : {datasets::ControlPolygon::unit_square, datasets::ControlPolygon::perturbed_arc})
        f(n, detail::plan_data(make_plan(datasets::random_curve(kind, n, rng, polygon))));
}

// N, the parameters of pieces j-1..j+1 of K, where piece j's bounds hold.
std::pair<double, double> around_piece(int K, int j) {
  return {std::max(0, j - 1) / double(K), std::min(K, j + 2) / double(K)};
}

// For the random plans above, the pieces j whose bound (plan.*field)[j] applies (> 0; none may be
// negative): f(n, plan, j, bound) for 32 of a plan's pieces, every K/32-th from a random first
// (all of them at K = 32: the test's time does not grow with the degree's piece count, and over
// the plans every piece's position is drawn). Returns how many.
template <class F>
int for_each_bounded_piece(std::mt19937_64& rng, int first, int last, std::vector<double> detail::PlanData::*field,
                           F&& f) {
  int bounded = 0;
  for_each_random_plan(rng, first, last, [&](int n, const detail::PlanData& plan) {
    const int K = plan.isolation_pieces, stride = std::max(1, K / 32);
    for (int j = 0; j < K; ++j) EXPECT_GE((plan.*field)[j], 0.0) << "n " << n << " piece " << j;
    for (int j = static_cast<int>(rng() % stride); j < K; j += stride) {
      const double bound = (plan.*field)[j];
      if (!(bound > 0)) continue;
      ++bounded;
      f(n, plan, j, bound);
    }
  });
  return bounded;
}

// The signed curvature P' x P'' / |P'|^3 at a jet, and the point `off` along its left normal.
double curvature(const detail::CurveJet& jet) {
  const double speed = std::hypot(jet.dx, jet.dy);
  return (jet.dx * jet.ddy - jet.dy * jet.ddx) / (speed * speed * speed);
}
std::array<double, 2> along_normal(const detail::CurveJet& jet, double off) {
  const double speed = std::hypot(jet.dx, jet.dy);
  return {jet.x - off * jet.dy / speed, jet.y + off * jet.dx / speed};
}

// The distance from (x, y) to the chord of piece q's capsule, in long double from the stored
// doubles (NaN where the piece has no capsule).
long double capsule_chord_distance(const detail::PlanData& plan, int q, long double x, long double y) {
  const int K = plan.isolation_pieces;
  const double* c = plan.isolation_capsules.data();  // a x, a y, b x, b y, reach: K each
  if (std::isnan(c[4 * K + q])) return NAN;
  const long double dx = static_cast<long double>(c[2 * K + q]) - c[q], dy = static_cast<long double>(c[3 * K + q]) - c[K + q];
  const long double px = x - c[q], py = y - c[K + q], length2 = dx * dx + dy * dy;
  const long double s = length2 > 0 ? std::clamp((px * dx + py * dy) / length2, 0.0L, 1.0L) : 0.0L;
  return std::hypot(px - s * dx, py - s * dy);
}

TEST(Isolation, EveryPieceOfTheCurveLiesInItsBoxAndItsCapsule) {
  std::mt19937_64 rng(5);
  int boxes = 0, capsules = 0;
  for_each_random_plan(rng, 2, 24, [&](int n, const detail::PlanData& plan) {
      const int K = plan.isolation_pieces;
      ASSERT_EQ(K, detail::isolation_piece_count(n));
      ASSERT_EQ(plan.isolation_boxes.size(), 4u * K);
      ASSERT_EQ(plan.isolation_capsules.size(), 5u * K);
      for (int j = 0; j < K; ++j) {
        const double* b = plan.isolation_boxes.data();  // x centres, x half-widths, y centres, y half-widths
        const double box[4] = {b[j] - b[K + j], b[j] + b[K + j],  // x min, x max, y min, y max
                               b[2 * K + j] - b[3 * K + j], b[2 * K + j] + b[3 * K + j]};
        for (double side : box) ASSERT_TRUE(std::isfinite(side)) << "positive weights, piece " << j;  // in [0.5, 2]
        ++boxes;
        const double reach = plan.isolation_capsules[4 * K + j];
        EXPECT_EQ(std::isnan(reach), !plan.common_denominator || K < detail::kIsolationCapsuleMinPieces)
            << "n " << n << " piece " << j;
        capsules += !std::isnan(reach);
        for (int s = 0; s <= 20 && !std::isnan(reach); ++s) {
          const double t = (j + s / 20.0) / K;
          const auto p = plan.normalized_point(t);
          EXPECT_LE(capsule_chord_distance(plan, j, p[0], p[1]), reach) << "n " << n << " t " << t;
        }
        for (int s = 0; s <= 20; ++s) {
          const double t = (j + s / 20.0) / K;
          const auto p = plan.normalized_point(t);
          EXPECT_GE(p[0], box[0]) << "n " << n << " t " << t;
          EXPECT_LE(p[0], box[1]) << "n " << n << " t " << t;
          EXPECT_GE(p[1], box[2]) << "n " << n << " t " << t;
          EXPECT_LE(p[1], box[3]) << "n " << n << " t " << t;
        }
        // The group's box holds the piece's, so a point it clears is clear of the piece.
        const double* group = plan.isolation_groups.data() + 4 * (j / detail::kIsolationGroup);
        EXPECT_LE(group[0], box[0]) << "n " << n << " piece " << j;
        EXPECT_GE(group[1], box[1]) << "n " << n << " piece " << j;
        EXPECT_LE(group[2], box[2]) << "n " << n << " piece " << j;
        EXPECT_GE(group[3], box[3]) << "n " << n << " piece " << j;
      }
      ASSERT_EQ(plan.isolation_groups.size(), 4u * (K / detail::kIsolationGroup));
  });
  RecordProperty("boxes", boxes);
  RecordProperty("capsules", capsules);
  EXPECT_GT(capsules, boxes / 4);
}

// segment_far is a certificate: a point it calls far is farther than plan.segment_far_reach from
// every point of the segment. Checked against 6,000 points of each curve (their spacing, at most
// ~1e-3 of the diagonal, is far below the distances of the points it clears: a cell marked far by
// mistake within the reach would show), on points up to 1e-2 of the diagonal off the curve and on
// it (never far); and it must clear most of those beyond a few reaches, or the fast path gains
// nothing by it.
TEST(Isolation, ThePointsSegmentFarClearsAreFartherThanItsReachFromTheSegment) {
  std::mt19937_64 rng(77);
  int cleared = 0, beyond = 0, cleared_beyond = 0, checked = 0;
  for_each_random_plan(rng, detail::kSegmentFarMinDegree, 22, [&](int n, const detail::PlanData& plan) {
    ASSERT_FALSE(plan.segment_far_near.empty()) << "n " << n;  // positive weights: every piece has a box
    constexpr int kSamples = 6000;
    std::vector<std::array<double, 2>> samples;
    for (int k = 0; k <= kSamples; ++k) samples.push_back(plan.normalized_point(k / double(kSamples)));
    std::uniform_real_distribution<double> parameter(0.0, 1.0), angle(0.0, 6.283185307179586), radius(0.0, 1.0);
    const double reach = plan.segment_far_reach;
    EXPECT_EQ(reach, detail::kSegmentFarDistance * plan.normalized_diagonal);
    for (int k = 0; k < 300 / test_support::kSanitizerThinning; ++k) {
      const auto on = plan.normalized_point(parameter(rng));
      EXPECT_FALSE(detail::segment_far(plan, on[0], on[1])) << "n " << n;
      const double r = 1e-2 * plan.normalized_diagonal * radius(rng), a = angle(rng);
      const double u = on[0] + r * std::cos(a), v = on[1] + r * std::sin(a);
      double nearest2 = std::numeric_limits<double>::infinity();
      for (const auto& p : samples) nearest2 = std::min(nearest2, (p[0] - u) * (p[0] - u) + (p[1] - v) * (p[1] - v));
      const bool far = detail::segment_far(plan, u, v);
      ++checked;
      cleared += far;
      if (far) {
        EXPECT_GT(std::sqrt(nearest2), reach) << "n " << n << " at " << u << ", " << v;
      }
      beyond += std::sqrt(nearest2) > 8 * reach;
      cleared_beyond += far && std::sqrt(nearest2) > 8 * reach;
    }
  });
  RecordProperty("checked", checked);
  RecordProperty("cleared", cleared);
  RecordProperty("beyond", beyond);
  RecordProperty("cleared_beyond", cleared_beyond);
  EXPECT_GT(cleared_beyond, beyond * 3 / 4);  // most of those beyond 8 reaches
}

// isolated() looks at the pieces within kIsolationWide of t's only, or at those of the groups near
// the point: it certifies exactly what the definition does, every piece not next to t's farther
// than the tolerance by its box or its capsule (after the tests around
// t, which both share), on points near the curve, where groups are near, and far from it.
TEST(Isolation, TheGroupsChangeNothingIsolatedCertifies) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int certified = 0, refused = 0, by_wide = 0, by_capsule = 0;
  for_each_random_plan(rng, 2, 20, [&](int, const detail::PlanData& plan) {
    const int K = plan.isolation_pieces;
    const double* b = plan.isolation_boxes.data();
    for (int i = 0; i < 200; ++i) {
      const double t = unit(rng);
      const auto p = plan.normalized_point(t);
      const double angle = 6.283185307179586 * unit(rng), off = std::pow(10.0, -8 + 7 * unit(rng));
      const double u0 = p[0] + off * std::cos(angle), v0 = p[1] + off * std::sin(angle);
      const double distance = std::hypot(u0 - p[0], v0 - p[1]);
      const double tolerance = std::pow(10.0, -7 + 6 * unit(rng));
      const int j = std::min(K - 1, static_cast<int>(t * K));
      bool expected = distance < plan.isolation_monotone[j] * kDistinctParameterGap || distance < plan.isolation_unique[j];
      const double limit = tolerance * (1 + kIsolationMargin);
      for (int q = 0; q < K && expected; ++q) {
        if (q >= j - 1 && q <= j + 1) continue;
        const double dx = std::max(std::abs(u0 - b[q]) - b[K + q], 0.0);
        const double dy = std::max(std::abs(v0 - b[2 * K + q]) - b[3 * K + q], 0.0);
        // Or the capsule, where the box is not far enough (NaN: none; the slack isolated() keeps
        // for the rounding, far beyond the long double's).
        const long double chord = capsule_chord_distance(plan, q, u0, v0);
        const double reach = plan.isolation_capsules[4 * K + q];
        expected = dx * dx + dy * dy > limit * limit ||
                   chord > (reach + limit) * (1 + kIsolationMargin) + 4 * kIsolationMargin * (1 + std::abs(u0) + std::abs(v0));
        by_capsule += !(dx * dx + dy * dy > limit * limit) && expected;
      }
      const bool got = detail::isolated(plan, u0, v0, t, distance, tolerance);
      EXPECT_EQ(got, expected) << "t " << t << " off " << off << " tolerance " << tolerance;
      (got ? certified : refused) += 1;
      // The way isolated() took when the first comparison fails: the pieces within
      // kIsolationWide of t's alone.
      by_wide += !(plan.isolation_far[j] - distance > limit) && plan.isolation_far_wide[j] - distance > limit;
    }
  });
  EXPECT_GT(certified, 1000);
  EXPECT_GT(refused, 1000);
  EXPECT_GT(by_wide, 200);
  EXPECT_GT(by_capsule, 20);
  RecordProperty("by_wide", by_wide);
  RecordProperty("by_capsule", by_capsule);
  RecordProperty("certified", certified);
  RecordProperty("refused", refused);
}

// isolation_far and isolation_far_wide skip the groups that cannot hold a nearer box: the same
// minima, to the bit, as over every pair of boxes (degrees up to 24: K = 32 to 512).
TEST(Isolation, TheFarDistancesAreTheMinimaOverEveryPairOfBoxes) {
  std::mt19937_64 rng(43);
  int pieces = 0;
  for_each_random_plan(rng, 2, 24, [&](int n, const detail::PlanData& plan) {
    const int K = plan.isolation_pieces;
    const double* b = plan.isolation_boxes.data();
    for (int j = 0; j < K; ++j) {
      double nearest2 = std::numeric_limits<double>::infinity(), wide2 = nearest2;
      for (int q = 0; q < K; ++q) {
        if (q >= j - 1 && q <= j + 1) continue;
        const double dx = std::max(std::abs(b[j] - b[q]) - b[K + j] - b[K + q], 0.0);
        const double dy = std::max(std::abs(b[2 * K + j] - b[2 * K + q]) - b[3 * K + j] - b[3 * K + q], 0.0);
        nearest2 = std::min(nearest2, dx * dx + dy * dy);
        if (q < j - detail::kIsolationWide || q > j + detail::kIsolationWide) wide2 = std::min(wide2, dx * dx + dy * dy);
      }
      ASSERT_EQ(plan.isolation_far[j], std::sqrt(nearest2)) << "degree " << n << " piece " << j << " of " << K;
      ASSERT_EQ(plan.isolation_far_wide[j], std::sqrt(wide2)) << "degree " << n << " piece " << j << " of " << K;
      ++pieces;
    }
  });
  EXPECT_GT(pieces, 10000);
}

// The bound m of piece j says: for t, tau in pieces j-1..j+1,
//   sign(tau - t) (P(tau) - P(t)) . P'(tau) >= 2 m |tau - t| |P'(tau)|   (isolation.hpp).
TEST(Isolation, TheCurveIsAsMonotoneAroundEachPieceAsItsBoundSays) {
  std::mt19937_64 rng(6);
  int checked = 0;
  const int bounded = for_each_bounded_piece(
      rng, 2, 24, &detail::PlanData::isolation_monotone, [&](int n, const detail::PlanData& plan, int j, double m) {
        const auto [lo, hi] = around_piece(plan.isolation_pieces, j);
        for (int k = 0; k < 40; ++k) {
          const double t = datasets::uniform(rng, lo, hi), tau = datasets::uniform(rng, lo, hi);
          const auto a = plan.normalized_point(t);
          const detail::CurveJet b = detail::curve_jet(plan, tau);
          const double along = ((b.x - a[0]) * b.dx + (b.y - a[1]) * b.dy) * (tau > t ? 1 : -1);
          const double bound = 2 * m * std::abs(tau - t) * std::hypot(b.dx, b.dy);
          EXPECT_GE(along, bound * (1 - 1e-9) - 1e-15) << "n " << n << " piece " << j << " t " << t << " tau " << tau;
          ++checked;
        }
      });
  RecordProperty("pieces_with_a_bound", bounded);
  RecordProperty("pairs_checked", checked);
  EXPECT_GT(bounded, 100);
}

// Below isolation_unique, the squared distance to P0 has one local minimum on N (pieces j-1..j+1),
// checked on a fine grid. The points are placed on the inner side of the curve, as far as the bound
// allows or just past the centre of curvature, whichever is nearer: a bound too large (a bend
// underestimated) lets the second point through, and past the centre of a curvature maximum the
// distance has two minima.
TEST(Isolation, BelowTheUniquenessBoundTheDistanceHasOneMinimumAroundEachPiece) {
  std::mt19937_64 rng(12);
  int checked = 0;
  const int bounded = for_each_bounded_piece(
      rng, 2, 20, &detail::PlanData::isolation_unique, [&](int n, const detail::PlanData& plan, int j, double unique) {
        const auto [lo, hi] = around_piece(plan.isolation_pieces, j);
        for (int k = 0; k < 4; ++k) {
          const double t = datasets::uniform(rng, j / double(plan.isolation_pieces), (j + 1) / double(plan.isolation_pieces));
          if (test_support::thinned_out(static_cast<std::size_t>(j + k))) continue;  // the draws stay the same
          const detail::CurveJet jet = detail::curve_jet(plan, t);
          const double kappa = curvature(jet);
          const double radius = kappa != 0 ? 1 / std::abs(kappa) : std::numeric_limits<double>::infinity();
          const double off = std::min(0.99 * unique, 1.02 * radius) * (k % 3 == 0 ? 0.5 : 1.0);
          const auto [u0, v0] = along_normal(jet, kappa >= 0 ? off : -off);  // the inner side
          constexpr int kGrid = 400;
          std::vector<double> f(kGrid + 1);
          for (int g = 0; g <= kGrid; ++g) {
            const auto p = plan.normalized_point(lo + (hi - lo) * g / kGrid);
            f[g] = (p[0] - u0) * (p[0] - u0) + (p[1] - v0) * (p[1] - v0);
          }
          int minima = 0;
          for (int g = 1; g < kGrid; ++g) minima += f[g] < f[g - 1] && f[g] <= f[g + 1];
          EXPECT_LE(minima, 1) << "n " << n << " piece " << j << " t " << t << " off " << off << " radius " << radius;
          ++checked;
        }
      });
  RecordProperty("pieces_with_a_bound", bounded);
  RecordProperty("points_checked", checked);
  EXPECT_GT(bounded, 300);
}

// The promise itself, on curves that loop and cross (random control points in a square) and with a
// loose tolerance, so that other branches often come within it.
TEST(Isolation, NoWalkEndsWithinTheToleranceAwayFromACertifiedParameter) {
  std::mt19937_64 rng(8);
  int certified = 0, refused = 0;
  for (int n : {3, 4, 5, 6, 8, 10, 12, 15, 20})
    for (int c = 0; c < 6; ++c) {
      const detail::PlanData plan =
          detail::plan_data(make_plan(datasets::random_curve(kRationalKinds[c % 2], n, rng, datasets::ControlPolygon::unit_square)));
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

// isolated_by_far_boxes, the first test of isolated() for a batch: where it certifies a lane,
// isolated() does; on and off looping curves, with loose tolerances, NaN and t outside [0, 1] in
// the batch. Most on-curve points of arcs at the default tolerance must pass the first test alone
// (that is what the batched test is for), and the loops at loose tolerances must leave some to
// isolated()'s box-by-box test.
TEST(Isolation, TheBatchedFirstTestCertifiesOnlyWhatIsolatedCertifies) {
  std::mt19937_64 rng(13);
  int batched = 0, by_boxes = 0, refused = 0, arc_points = 0, arc_batched = 0;
  for (int n : {2, 3, 5, 8, 10, 15, 20})
    for (auto polygon : {datasets::ControlPolygon::unit_square, datasets::ControlPolygon::perturbed_arc})
      for (CurveKind kind : kRationalKinds) {
        const detail::PlanData plan = detail::plan_data(make_plan(datasets::random_curve(kind, n, rng, polygon)));
        for (double relative_tolerance : {1e-6, 1e-2}) {
          const double tolerance = relative_tolerance * plan.diagonal / plan.scale;
          constexpr std::size_t kLanes = 64;
          std::array<double, kLanes> u, v, t, distance;
          for (std::size_t l = 0; l < kLanes; ++l) {
            const auto p = plan.normalized_point(datasets::uniform(rng, 0.0, 1.0));
            const double off = l % 3 == 0 ? datasets::uniform(rng, 0.0, 2.0) * tolerance : 0.0;
            u[l] = p[0] + off;
            v[l] = p[1];
            const detail::Refined own = detail::refine_parameter(plan, u[l], v[l], datasets::uniform(rng, 0.0, 1.0), true);
            t[l] = own.t;
            distance[l] = own.distance;
          }
          t[5] = std::nan("");
          t[6] = 1.5;
          t[7] = -0.25;
          std::array<std::uint8_t, kLanes> certified;
          detail::isolated_by_far_boxes(plan, t.data(), distance.data(), tolerance, kLanes, certified.data());
          for (std::size_t l = 0; l < kLanes; ++l) {
            const bool isolated = detail::isolated(plan, u[l], v[l], t[l], distance[l], tolerance);
            if (certified[l]) {
              EXPECT_TRUE(isolated) << "n " << n << " lane " << l << " t " << t[l];
              ++batched;
            } else {
              ++(isolated ? by_boxes : refused);
            }
            if (polygon == datasets::ControlPolygon::perturbed_arc && relative_tolerance == 1e-6 && l % 3 != 0 &&
                l >= 8 && distance[l] <= tolerance) {
              ++arc_points;
              arc_batched += certified[l];
            }
          }
          for (std::size_t l : {5, 6, 7}) EXPECT_FALSE(certified[l]) << "t " << t[l];
        }
      }
  RecordProperty("batched", batched);
  RecordProperty("by_boxes", by_boxes);
  RecordProperty("refused", refused);
  EXPECT_GT(arc_points, 200);
  EXPECT_GE(arc_batched, 0.95 * arc_points);
  EXPECT_GT(refused, 100);
}

// The same promise for points off the curve (along the normal, either side, up to 0.9 of the
// tolerance): there the certificate rests on isolation_unique, the distance below which the
// distance function has one stationary point around t. Near a tight bend, on its inner side, a
// point past the centre of curvature has two nearest parameters; this is what the bound must refuse.
TEST(Isolation, NoWalkEndsWithinTheToleranceAwayFromACertifiedParameterOffTheCurve) {
  std::mt19937_64 rng(11);
  int certified = 0, certified_by_uniqueness = 0, refused = 0, past_centre = 0;
  for (int n : {2, 3, 4, 5, 6, 8, 10, 12, 15, 20})
    for (int c = 0; c < 6; ++c) {
      const detail::PlanData plan =
          detail::plan_data(make_plan(datasets::random_curve(kRationalKinds[c % 2], n, rng, datasets::ControlPolygon::unit_square)));
      for (double relative_tolerance : {1e-6, 1e-3, 3e-2}) {
        const double tolerance = relative_tolerance * plan.diagonal / plan.scale;
        for (int k = 0; k < 12; ++k) {
          const double t = datasets::uniform(rng, 0.0, 1.0);
          const detail::CurveJet jet = detail::curve_jet(plan, t);
          // Every other point: on the inner side, just past the centre of curvature, when that
          // is within the tolerance.
          double off = datasets::uniform(rng, -0.9, 0.9) * tolerance;
          const double kappa = curvature(jet);
          if (k % 2 == 1 && 1.05 / std::abs(kappa) < 0.9 * tolerance) {
            off = std::copysign(1.05 / std::abs(kappa), kappa);
            ++past_centre;
          }
          const auto [u0, v0] = along_normal(jet, off);
          const detail::Refined own = detail::refine_parameter(plan, u0, v0, t, true);
          if (!detail::isolated(plan, u0, v0, own.t, own.distance, tolerance)) {
            ++refused;
            continue;
          }
          ++certified;
          const int K = plan.isolation_pieces;
          const int j = std::min(K - 1, static_cast<int>(own.t * K));
          if (!(own.distance < plan.isolation_monotone[j] * kDistinctParameterGap)) ++certified_by_uniqueness;
          for (int s = 0; s <= 100; ++s) {
            const detail::Refined r = detail::refine_parameter(plan, u0, v0, s / 100.0, true);
            const bool second = r.distance <= tolerance && std::abs(r.t - own.t) > kDistinctParameterGap;
            EXPECT_FALSE(second) << "n " << n << " t " << own.t << " (distance " << own.distance << ") walk from "
                                 << s / 100.0 << " ends at " << r.t << ", distance " << r.distance << " <= " << tolerance;
          }
        }
      }
    }
  RecordProperty("certified", certified);
  RecordProperty("certified_by_uniqueness", certified_by_uniqueness);
  RecordProperty("refused", refused);
  RecordProperty("past_the_centre_of_curvature", past_centre);
  EXPECT_GT(certified_by_uniqueness, 100);
  EXPECT_GT(past_centre, 20);
  EXPECT_GT(refused, 50);
}

// The off-curve path's quick proof (engine/src/pipeline/off_curve_path.cpp): where
// nearest_on_segment says so, a stationary point of the distance is the nearest point of the
// whole segment. Checked against the distance on a grid of the segment, for points up to a tenth
// of the curve's size off random curves with loops, where another branch is often nearer.
TEST(Isolation, NearestOnSegmentIsTheNearestPointOfTheSegment) {
  std::mt19937_64 rng(13);
  int certified = 0, refused = 0;
  for (int n : {2, 3, 4, 5, 6, 8, 10, 12, 15, 20})
    for (int c = 0; c < 6; ++c) {
      const detail::PlanData plan =
          detail::plan_data(make_plan(datasets::random_curve(kRationalKinds[c % 2], n, rng, datasets::ControlPolygon::unit_square)));
      constexpr int kGrid = 4000;
      std::vector<std::array<double, 2>> grid(kGrid + 1);
      for (int g = 0; g <= kGrid; ++g) grid[g] = plan.normalized_point(g / double(kGrid));
      for (int k = 0; k < 40; ++k) {
        const double t = datasets::uniform(rng, 0.0, 1.0);
        const double off = std::copysign(std::pow(10.0, datasets::uniform(rng, -5.0, -1.0)), datasets::uniform(rng, -1.0, 1.0)) *
                           plan.diagonal / plan.scale;
        const auto [u0, v0] = along_normal(detail::curve_jet(plan, t), off);
        const detail::Refined own = detail::refine_parameter(plan, u0, v0, t, true);
        if (!(own.t > 0 && own.t < 1) || !detail::stationary_point(plan, u0, v0, own.t, own.distance) ||
            !detail::nearest_on_segment(plan, u0, v0, own.t, own.distance)) {
          ++refused;
          continue;
        }
        ++certified;
        double nearest = std::numeric_limits<double>::infinity();
        for (const auto& q : grid) nearest = std::min(nearest, std::hypot(q[0] - u0, q[1] - v0));
        EXPECT_GE(nearest, own.distance * (1 - 1e-12)) << "n " << n << " t " << own.t << " distance " << own.distance;
      }
    }
  RecordProperty("certified", certified);
  RecordProperty("refused", refused);
  EXPECT_GT(certified, 300);
  EXPECT_GT(refused, 300);
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
      const detail::PlanData plan = detail::plan_data(make_plan(curve));
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

TEST(Isolation, NotOffTheCurve) {
  std::mt19937_64 rng(10);
  const detail::PlanData plan = detail::plan_data(make_plan(
      datasets::random_curve(CurveKind::rational_bezier, 5, rng, datasets::ControlPolygon::perturbed_arc)));
  const int j = static_cast<int>(0.3 * plan.isolation_pieces);
  ASSERT_GT(plan.isolation_monotone[j], 0.0);
  const auto q = plan.normalized_point(0.3);
  EXPECT_TRUE(detail::isolated(plan, q[0], q[1], 0.3, 0.0, 1e-6));
  // A point off the curve by more than the bounds allow: not certified, however isolated.
  const double off = 2 * std::max(plan.isolation_monotone[j] * kDistinctParameterGap, plan.isolation_unique[j]);
  EXPECT_FALSE(detail::isolated(plan, q[0], q[1], 0.3, off, 1e-6));
  EXPECT_FALSE(detail::isolated(plan, q[0], q[1], std::nan(""), 0.0, 1e-6));
}

}  // namespace
}  // namespace bezinv
