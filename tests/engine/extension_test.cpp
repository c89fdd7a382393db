// extension_clear (engine/src/extension.hpp): the proof that no point of the curve beyond its
// segment comes within a radius of a point. Checked against the curve's extension evaluated
// independently: the homogeneous form sum c_i C(n,i) (1-t)^(n-i) t^i in long double at each t,
// scaled by 1/|t| far out so nothing overflows (not the engine's reparametrization in s).
#include "support/curve_kinds.hpp"
#include "support/sanitizers.hpp"
#include "extension.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "bezinv/bernstein.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "plan_data.hpp"

namespace bezinv {
namespace {

using test_support::kAllKinds;

using Real = long double;

// P(t) of the normalized curve, any real t: sum c_i C(n,i) a^(n-i) b^i at (a, b) = (1 - t, t),
// or at (a, b) / |t| for |t| > 2 (the ratios are the same). NaN at a pole.
std::array<Real, 2> extension_point(const detail::PlanData& plan, Real t) {
  const int n = plan.degree;
  Real a = 1 - t, b = t;
  if (std::abs(t) > 2) a /= std::abs(t), b /= std::abs(t);
  std::array<Real, kMaxDegree + 1> a_power, b_power;  // a^k, b^k
  a_power[0] = b_power[0] = 1;
  for (int k = 1; k <= n; ++k) a_power[k] = a_power[k - 1] * a, b_power[k] = b_power[k - 1] * b;
  const auto form = [&](const std::vector<double>& c) {
    Real sum = 0;
    for (int i = 0; i <= n; ++i) sum += c[i] * static_cast<Real>(binomial(n, i)) * a_power[n - i] * b_power[i];
    return sum;
  };
  const Real wx = form(plan.x_den), wy = form(plan.y_den);
  if (wx == 0 || wy == 0) return {NAN, NAN};
  return {form(plan.x_num) / wx, form(plan.y_num) / wy};
}

// Parameters of the extension, dense near both ends of the segment and out to |t| = 1e7 (the
// curve there is at its point at infinity, or beyond every radius tested).
std::vector<Real> extension_parameters() {
  std::vector<Real> ts;
  for (int k = 0; k <= 6000; ++k) {
    const Real e = -9 + 16.0L * k / 6000;  // 1e-9 .. 1e7
    ts.push_back(1 + std::pow(10.0L, e));
    ts.push_back(-std::pow(10.0L, e));
  }
  for (int k = 1; k < 4000; ++k) {  // and evenly over [1, 3] and [-2, 0]
    ts.push_back(1 + 2.0L * k / 4000);
    ts.push_back(-2.0L * k / 4000);
  }
  return ts;
}

Real nearest_on_grid(const std::vector<std::array<Real, 2>>& grid, double u0, double v0) {
  Real nearest = INFINITY;
  for (const auto& p : grid)
    if (std::isfinite(p[0]) && std::isfinite(p[1])) nearest = std::min(nearest, std::hypot(p[0] - u0, p[1] - v0));
  return nearest;
}


// Never clear where a point of the extension is within the radius: with the radius just above
// the nearest point of the grid, the answer must be no. Below it the proof is expected to succeed
// for points around the segment (counted: it is only worth having if it usually does there), at
// 0.99 of it (the grid's nearest is then beyond the radius; the true nearest may still be nearer
// between grid points) and at half. Points around the extension itself are harder (the proof
// needs pieces as fine as their distance): those it may leave to the SVD path.
TEST(Extension, NeverClearWhereThePointIsWithinTheRadiusOfTheExtension) {
  const std::vector<Real> ts = extension_parameters();
  int tried = 0, cleared_below = 0, cleared_half = 0, around_extension = 0, cleared_around_extension = 0;
  for (CurveKind kind : kAllKinds)
    for (int n : {2, 3, 5, 8, 12, 20, 32}) {
      std::mt19937_64 rng(911 + 31 * n + static_cast<int>(kind));
      for (auto polygon : {datasets::ControlPolygon::perturbed_arc, datasets::ControlPolygon::unit_square}) {
        const detail::PlanData plan = detail::plan_data(make_plan(datasets::random_curve(kind, n, rng, polygon)));
        std::vector<std::array<Real, 2>> grid;
        for (Real t : ts) grid.push_back(extension_point(plan, t));
        // Half the points under the sanitizers (support/sanitizers.hpp).
        for (int i = 0; i < (test_support::kSanitizerTree ? 5 : 10); ++i) {
          // Around the segment and around its extension, 1e-4 to 1 of the curve's size away.
          const Real t0 = datasets::uniform(rng, -0.6, 1.6);
          const auto base = extension_point(plan, t0);
          const double r = std::pow(10.0, datasets::uniform(rng, -4, 0)) * plan.normalized_diagonal;
          const double angle = datasets::uniform(rng, 0.0, 6.283185307179586);
          const double u0 = static_cast<double>(base[0]) + r * std::cos(angle), v0 = static_cast<double>(base[1]) + r * std::sin(angle);
          const double nearest = static_cast<double>(nearest_on_grid(grid, u0, v0));
          ASSERT_TRUE(std::isfinite(nearest));
          EXPECT_FALSE(detail::extension_clear(plan, u0, v0, nearest * (1 + 1e-6)))
              << to_string(kind) << " degree " << n << " t0 " << static_cast<double>(t0) << " nearest " << nearest;
          if (t0 < 0 || t0 > 1) {
            ++around_extension;
            cleared_around_extension += detail::extension_clear(plan, u0, v0, nearest * 0.5);
            continue;
          }
          ++tried;
          cleared_below += detail::extension_clear(plan, u0, v0, nearest * 0.99);
          cleared_half += detail::extension_clear(plan, u0, v0, nearest * 0.5);
        }
      }
    }
  RecordProperty("tried", tried);
  RecordProperty("cleared_at_0.99", cleared_below);
  RecordProperty("cleared_at_0.5", cleared_half);
  std::printf("[ measured ] around the segment, the extension cleared at 0.99 of the grid's nearest distance: %d of %d; "
              "at half: %d; around the extension at half: %d of %d\n",
              cleared_below, tried, cleared_half, cleared_around_extension, around_extension);
  EXPECT_GT(cleared_half, tried * 9 / 10);
  EXPECT_GT(cleared_below, tried * 3 / 4);
}

// The grid (extension_grid) on the same curves and points: its cell never clears a point with
// the radius just above the nearest point of the extension, nor do the pieces its cell lists;
// where it clears one, the pieces do too (it is only a quicker way to the pieces' own box and
// radius tests), and with its lists the answer is the full scan's; and it is worth having:
// points near the middle of the segment, off the curve by 1e-4 to 1e-1 of its size with that as
// the radius (as off_curve_path asks), are mostly cleared by their cell alone.
TEST(Extension, TheGridClearsOnlyWhatThePiecesClear) {
  const std::vector<Real> ts = extension_parameters();
  int tried = 0, by_grid = 0, middle = 0, middle_by_grid = 0;
  for (CurveKind kind : kAllKinds)
    for (int n : {2, 3, 5, 8, 12, 20, 32}) {
      std::mt19937_64 rng(4099 + 31 * n + static_cast<int>(kind));
      for (auto polygon : {datasets::ControlPolygon::perturbed_arc, datasets::ControlPolygon::unit_square}) {
        const detail::PlanData plan = detail::plan_data(make_plan(datasets::random_curve(kind, n, rng, polygon)));
        const detail::ExtensionGrid* grid = detail::extension_grid(plan, 0, true);
        ASSERT_NE(grid, nullptr);
        EXPECT_EQ(detail::extension_grid(plan, 0), grid);  // made once
        std::vector<std::array<Real, 2>> points;
        for (Real t : ts) points.push_back(extension_point(plan, t));
        for (int i = 0; i < (test_support::kSanitizerTree ? 15 : 30); ++i) {
          // Near the middle of the segment; anywhere around it; close to the extension, where the
          // cells' lists are used (a radius below kExtensionGridListed of the diagonal).
          const bool near_middle = i % 3 == 0, close = i % 3 == 2;
          const Real beyond = datasets::uniform(rng, 0.0, 0.3);
          const Real t0 = near_middle ? datasets::uniform(rng, 0.3, 0.7)
                          : close     ? (i % 2 ? 1 + beyond : -beyond)
                                      : datasets::uniform(rng, -0.6, 1.6);
          const auto base = extension_point(plan, t0);
          const double r = std::pow(10.0, close ? datasets::uniform(rng, -5, -2.5) : datasets::uniform(rng, -4, near_middle ? -1 : 0)) *
                           plan.normalized_diagonal;
          const double angle = datasets::uniform(rng, 0.0, 6.283185307179586);
          const double u0 = static_cast<double>(base[0]) + r * std::cos(angle), v0 = static_cast<double>(base[1]) + r * std::sin(angle);
          const double nearest = static_cast<double>(nearest_on_grid(points, u0, v0));
          ASSERT_TRUE(std::isfinite(nearest));
          EXPECT_FALSE(detail::grid_clears(*grid, u0, v0, nearest * (1 + 1e-6)))
              << to_string(kind) << " degree " << n << " t0 " << static_cast<double>(t0) << " nearest " << nearest;
          EXPECT_FALSE(detail::extension_clear(plan, u0, v0, nearest * (1 + 1e-6), grid))
              << to_string(kind) << " degree " << n << " t0 " << static_cast<double>(t0) << " nearest " << nearest;
          for (double radius : {nearest * 0.99, nearest * 0.5, r}) {
            const bool cleared = detail::grid_clears(*grid, u0, v0, radius);
            ++tried;
            by_grid += cleared;
            if (cleared) {
              EXPECT_TRUE(detail::extension_clear(plan, u0, v0, radius))
                  << to_string(kind) << " degree " << n << " t0 " << static_cast<double>(t0) << " radius " << radius;
            }
            EXPECT_EQ(detail::extension_clear(plan, u0, v0, radius, grid), cleared || detail::extension_clear(plan, u0, v0, radius));
          }
          if (near_middle) {
            ++middle;
            middle_by_grid += detail::grid_clears(*grid, u0, v0, r);
          }
        }
      }
    }
  std::printf("[ measured ] the grid cleared %d of %d tests; near the middle of the segment, %d of %d points\n", by_grid,
              tried, middle_by_grid, middle);
  EXPECT_GT(middle_by_grid, middle * 3 / 4);
}

// Points made on the extension from a known t (construction, rounded to doubles): within a
// radius of a millionth of the curve's size, never clear.
TEST(Extension, PointsOnTheExtensionAreNeverClear) {
  int tested = 0;
  for (CurveKind kind : kAllKinds)
    for (int n : {2, 3, 4, 7, 10, 16, 24, 32}) {
      std::mt19937_64 rng(77 + n + 5 * static_cast<int>(kind));
      const detail::PlanData plan =
          detail::plan_data(make_plan(datasets::random_curve(kind, n, rng, datasets::ControlPolygon::perturbed_arc)));
      for (Real t : {-2.0L, -0.5L, -0.1L, -1e-3L, -1e-6L, 1 + 1e-6L, 1 + 1e-3L, 1.1L, 1.5L, 3.0L}) {
        const auto p = extension_point(plan, t);
        if (!(std::max(std::abs(p[0]), std::abs(p[1])) < 1e6)) continue;  // near a pole
        ++tested;
        EXPECT_FALSE(detail::extension_clear(plan, static_cast<double>(p[0]), static_cast<double>(p[1]),
                                             1e-6 * plan.normalized_diagonal))
            << to_string(kind) << " degree " << n << " t " << static_cast<double>(t);
      }
    }
  EXPECT_GT(tested, 200);
}

// A conic with a pole on each side of the segment: W = (1-t)^2 + 6 t (1-t) + t^2 = 1 + 4t - 4t^2
// vanishes at t = 1/2 -+ 1/sqrt(2) (-0.207, 1.207): a hyperbola whose extension leaves through
// infinity and comes back as the other branch. Points on that other branch are never clear;
// points near the segment are, though every piece around a pole has weights of both signs.
TEST(Extension, AHyperbolaThroughItsPoles) {
  const detail::PlanData plan =
      detail::plan_data(make_plan(Curve::rational_bezier("hyperbola", {{0, 0}, {1, 2}, {2, 0}}, {1, 3, 1})));
  for (Real t : {-0.3L, -1.0L, -10.0L, 1.3L, 2.0L, 10.0L, -0.1L, 1.1L}) {
    const auto p = extension_point(plan, t);
    EXPECT_FALSE(detail::extension_clear(plan, static_cast<double>(p[0]), static_cast<double>(p[1]), 1e-9))
        << static_cast<double>(t);
  }
  const std::vector<Real> ts = extension_parameters();
  std::vector<std::array<Real, 2>> grid;
  for (Real t : ts) grid.push_back(extension_point(plan, t));
  int cleared = 0, tried = 0;
  std::mt19937_64 rng(5);
  for (int i = 0; i < 200; ++i) {
    const auto base = extension_point(plan, datasets::uniform(rng, 0.05, 0.95));
    const double angle = datasets::uniform(rng, 0.0, 6.283185307179586);
    const double u0 = static_cast<double>(base[0]) + 1e-3 * std::cos(angle), v0 = static_cast<double>(base[1]) + 1e-3 * std::sin(angle);
    const double nearest = static_cast<double>(nearest_on_grid(grid, u0, v0));
    ++tried;
    EXPECT_FALSE(detail::extension_clear(plan, u0, v0, nearest * (1 + 1e-6)));
    cleared += detail::extension_clear(plan, u0, v0, 0.5 * nearest);
  }
  EXPECT_GT(cleared, tried * 9 / 10);
}

// Every point of the extension lies in the box and the capsule of its piece (the one whose
// interval of s holds it), and, where that piece has parts, in the box and the capsule of one of
// them (to a part in 1e12 of the diagonal): they hold their piece, stay with it when the pieces
// are put in order, and a point outside all of them is clear of it. Every kind, degrees 2-20; the
// extension evaluated independently (extension_point). Some pieces must have parts and
// capsules, and most points a piece with a box, or the test would prove nothing.
TEST(Extension, EveryPointOfTheExtensionIsInThePartsAndCapsulesOfItsPiece) {
  std::mt19937_64 rng(47);
  const std::vector<Real> ts = extension_parameters();
  std::size_t with_parts = 0, with_capsules = 0, points = 0, boxed = 0;
  for (const CurveKind kind : kAllKinds)
    for (int n = 2; n <= 20; n += 3) {
      SCOPED_TRACE(std::string(to_string(kind)) + " degree " + std::to_string(n));
      const detail::PlanData plan = detail::plan_data(make_plan(datasets::random_curve(kind, n, rng)));
      const detail::OffCurveData& data = detail::off_curve_data(plan);
      const int pieces = static_cast<int>(data.extension_far2.size());
      ASSERT_EQ(data.extension_part_begin.size(), static_cast<std::size_t>(pieces) + 1);
      ASSERT_EQ(data.extension_capsules.size(), static_cast<std::size_t>(pieces) * detail::kCapsuleStride);
      ASSERT_EQ(data.extension_intervals.size(), static_cast<std::size_t>(pieces) * 3);
      ASSERT_EQ(data.extension_part_capsules.size() / detail::kCapsuleStride, data.extension_parts.size() / 4);
      for (int piece = 0; piece < pieces; ++piece) {
        with_parts += data.extension_part_begin[piece + 1] > data.extension_part_begin[piece];
        with_capsules += !std::isnan(data.extension_capsules[detail::kCapsuleStride * piece + 4]);
      }
      const double slack = 1e-12 * plan.normalized_diagonal;
      const auto in_box = [&](const double* box, const std::array<Real, 2>& q) {
        return !(box[0] == box[0]) || (q[0] >= box[0] - slack && q[0] <= box[1] + slack && q[1] >= box[2] - slack &&
                                       q[1] <= box[3] + slack);
      };
      // The distance from q to the chord, in long double from the stored doubles.
      const auto in_capsule = [&](const double* c, const std::array<Real, 2>& q) {
        if (std::isnan(c[4])) return true;
        const Real dx = Real{c[2]} - c[0], dy = Real{c[3]} - c[1], px = q[0] - c[0], py = q[1] - c[1];
        const Real length2 = dx * dx + dy * dy;
        const Real s = length2 > 0 ? std::clamp((px * dx + py * dy) / length2, Real{0}, Real{1}) : Real{0};
        return std::hypot(px - s * dx, py - s * dy) <= c[4] + slack;
      };
      for (std::size_t k = 0; k < ts.size(); k += 7) {
        const Real t = ts[k];
        const std::array<Real, 2> q = extension_point(plan, t);
        if (!std::isfinite(q[0]) || !std::isfinite(q[1]) || std::abs(q[0]) > 1e6 || std::abs(q[1]) > 1e6) continue;
        // The half and s of t (extension.hpp): t = 1 / (1 - s) for t >= 1, t = -s / (1 - s) for t <= 0.
        const int half = t >= 1 ? 0 : 1;
        const Real s = half == 0 ? 1 - 1 / t : t / (t - 1);
        int piece = 0;
        while (piece < pieces && !(data.extension_intervals[3 * piece] == half && data.extension_intervals[3 * piece + 1] <= s &&
                                   s <= data.extension_intervals[3 * piece + 2]))
          ++piece;
        ASSERT_LT(piece, pieces) << "no piece holds t = " << static_cast<double>(t);
        ++points;
        boxed += data.extension_boxes[4 * piece] == data.extension_boxes[4 * piece];
        const auto held = [&](const double* box, const double* capsule) { return in_box(box, q) && in_capsule(capsule, q); };
        bool covered = held(data.extension_boxes.data() + 4 * piece, data.extension_capsules.data() + detail::kCapsuleStride * piece);
        const std::uint32_t begin = data.extension_part_begin[piece], end = data.extension_part_begin[piece + 1];
        bool in_part = begin == end;
        for (std::uint32_t part = begin; part < end && !in_part; ++part)
          in_part = held(data.extension_parts.data() + 4 * static_cast<std::size_t>(part),
                         data.extension_part_capsules.data() + detail::kCapsuleStride * static_cast<std::size_t>(part));
        EXPECT_TRUE(covered && in_part) << "t = " << static_cast<double>(t) << ": (" << static_cast<double>(q[0]) << ", "
                                        << static_cast<double>(q[1]) << ")";
      }
    }
  RecordProperty("pieces_with_parts", static_cast<int>(with_parts));
  RecordProperty("pieces_with_capsules", static_cast<int>(with_capsules));
  EXPECT_GE(with_parts, 20u);
  EXPECT_GE(with_capsules, 100u);
  EXPECT_GE(points, 1000u);
  EXPECT_GE(boxed, points / 2);
}

// A polynomial curve's extension runs off to infinity as t grows: its pieces there are far from
// every point near the curve, and the far radius must say so, or every such point pays the h test
// on each of them (the Bezier kind's t >= 1 half has W = (1 - s)^n, about 0 beside its rounding
// bound far out). Points near the middle of the curve: cleared by the quick tests (far radius,
// box) alone on all but a few pieces, and the plan halves few pieces.
TEST(Extension, APolynomialCurvesFarExtensionIsClearedByItsFarRadius) {
  std::mt19937_64 rng(31);
  int points = 0, pieces_tested = 0, pieces_left = 0;
  for (int n = 3; n <= 20; ++n)
    for (auto polygon : {datasets::ControlPolygon::perturbed_arc, datasets::ControlPolygon::unit_square}) {
      const detail::PlanData plan = detail::plan_data(make_plan(datasets::random_curve(CurveKind::bezier, n, rng, polygon)));
      const detail::OffCurveData& data = detail::off_curve_data(plan);
      const int pieces = static_cast<int>(data.extension_far2.size());
      EXPECT_LE(pieces, 96) << "degree " << n;
      for (int k = 0; k < 8; ++k) {
        const auto p = plan.normalized_point(datasets::uniform(rng, 0.3, 0.7));
        const double off = 1e-3 * plan.normalized_diagonal, angle = datasets::uniform(rng, 0.0, 6.283185307179586);
        const double u0 = p[0] + off * std::cos(angle), v0 = p[1] + off * std::sin(angle);
        const double radius = 1e-9 * plan.normalized_diagonal, beyond = std::hypot(u0, v0) + radius;
        ++points;
        for (int piece = 0; piece < pieces; ++piece) {
          ++pieces_tested;
          const double* box = data.extension_boxes.data() + 4 * piece;
          const double dx = std::max({box[0] - u0, u0 - box[1], 0.0}), dy = std::max({box[2] - v0, v0 - box[3], 0.0});
          const bool box_clear = box[0] == box[0] && dx * dx + dy * dy > radius * radius;
          if (!(beyond * beyond < data.extension_far2[piece]) && !box_clear) ++pieces_left;
        }
      }
    }
  RecordProperty("pieces_left", pieces_left);
  EXPECT_LE(pieces_left, pieces_tested / 50) << "of " << pieces_tested << " (piece, point) pairs over " << points << " points";
}

}  // namespace
}  // namespace bezinv
