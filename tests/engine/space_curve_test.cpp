// Space curves (engine/src/space/), by construction: random space curves of every kind and degree,
// points on them at known parameters (the segment, its ends, the extension), off them along a
// normal (the nearest point checked by a dense search of the test's own), constructed
// self-intersections in space, curves whose projection crosses itself where the curve does not,
// plane curves in a tilted plane (against the plane engine on the same curve in plane
// coordinates), lines, degree-elevated curves and curves far from the origin.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "bezinv/bernstein.hpp"
#include "bezinv/kernels/batch.hpp"
#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "space/space_curve.hpp"
#include "support/bits.hpp"
#include "support/sanitizers.hpp"

namespace bezinv {
namespace {

using Vec3 = std::array<double, 3>;

double space_uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// A random space curve of the kind and degree: control points in the unit cube, weights in
// [0.5, 2] (kind rational: each coordinate its own weights).
Curve random_space_curve(CurveKind kind, int degree, std::mt19937_64& rng) {
  std::vector<Vec3> points(degree + 1);
  for (Vec3& p : points)
    for (double& c : p) c = space_uniform(rng, 0.0, 1.0);
  std::vector<double> w(degree + 1);
  for (double& v : w) v = space_uniform(rng, 0.5, 2.0);
  if (kind == CurveKind::bezier) return Curve::space_bezier("s", points);
  if (kind == CurveKind::rational_bezier) return Curve::space_rational_bezier("s", points, w);
  std::array<std::vector<double>, 3> num, den;
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i <= degree; ++i) {
      den[k].push_back(space_uniform(rng, 0.5, 2.0));
      num[k].push_back(den[k][i] * points[i][k]);
    }
  return Curve::space_rational("s", num[0], den[0], num[1], den[1], num[2], den[2]);
}

Vec3 space_point(const Curve& c, double t) { return c.point3(t); }

Vec3 space_tangent(const Curve& c, double t) {
  const double h = 1e-6;
  const Vec3 a = c.point3(t - h), b = c.point3(t + h);
  return {(b[0] - a[0]) / (2 * h), (b[1] - a[1]) / (2 * h), (b[2] - a[2]) / (2 * h)};
}

double space_length(const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// The nearest point of the segment by the test's own search: 4,000 samples, then golden-section
// search around the best three.
double nearest_distance_by_search(const Curve& c, const Vec3& p) {
  auto d = [&](double t) {
    const Vec3 q = c.point3(t);
    return std::hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
  };
  constexpr int kSamples = 4000;
  std::vector<std::pair<double, int>> best;
  for (int j = 0; j <= kSamples; ++j) best.push_back({d(static_cast<double>(j) / kSamples), j});
  std::partial_sort(best.begin(), best.begin() + 3, best.end());
  double nearest = best[0].first;
  for (int k = 0; k < 3; ++k) {
    double lo = std::max(0.0, (best[k].second - 1.0) / kSamples), hi = std::min(1.0, (best[k].second + 1.0) / kSamples);
    for (int it = 0; it < 100; ++it) {
      const double m1 = lo + (hi - lo) * 0.381966, m2 = hi - (hi - lo) * 0.381966;
      if (d(m1) < d(m2)) hi = m2; else lo = m1;
    }
    nearest = std::min(nearest, d(0.5 * (lo + hi)));
  }
  return nearest;
}

std::string space_describe(const Curve& c, double t, const Vec3& p, const PointResult& r) {
  char text[400];
  std::snprintf(text, sizeof text, "%s degree %d, t_true %.17g, point (%.17g, %.17g, %.17g): status %s t %.17g t2 %.17g residual %.3g path %s",
                to_string(c.kind), c.degree(), t, p[0], p[1], p[2], to_string(r.status), r.t, r.t2, r.residual,
                to_string(r.path));
  return text;
}

constexpr CurveKind kSpaceKinds[] = {CurveKind::bezier, CurveKind::rational_bezier, CurveKind::rational};

// Every kind to degree 20: with separate denominators the curve is projected on a coordinate plane,
// at its own degree (a principal projection would be of degree 3n, at most 32: n <= 10).
int space_max_degree(CurveKind) { return 20; }

TEST(SpaceCurves, PointsOnTheSegmentAtTheirEndsAndOnTheExtension) {
  int rows = 0;
  for (CurveKind kind : kSpaceKinds)
    for (int degree = 1; degree <= space_max_degree(kind); ++degree) {
      std::mt19937_64 rng(1000 * degree + static_cast<int>(kind));
      const Curve curve = random_space_curve(kind, degree, rng);
      const InversionPlan plan = make_plan(curve);
      ASSERT_EQ(plan.dimension(), 3);
      std::vector<double> ts{0.0, 1.0};
      for (int k = 0; k < 12; ++k) ts.push_back(space_uniform(rng, 0.0, 1.0));
      for (int k = 0; k < 3; ++k) ts.push_back(space_uniform(rng, 1.02, 1.2)), ts.push_back(space_uniform(rng, -0.2, -0.02));
      std::vector<Point3> points;
      for (double t : ts) {
        const Vec3 p = space_point(curve, t);
        points.emplace_back(p[0], p[1], p[2]);
      }
      std::vector<PointResult> results(points.size());
      invert(plan, points, results);
      for (std::size_t i = 0; i < ts.size(); ++i) {
        const double t = ts[i];
        const Vec3 p{points[i].x, points[i].y, points[i].z};
        const PointResult& r = results[i];
        // Far along the extension of a rational curve a denominator may vanish: only where the
        // curve is well-conditioned there (finite, not racing away).
        if (!(t >= 0 && t <= 1) && !(space_length(space_tangent(curve, t)) < 100)) continue;
        ++rows;
        const Status expected = t >= 0 && t <= 1 ? Status::ok : Status::outside_segment;
        ASSERT_EQ(r.status, expected) << space_describe(curve, t, p, r);
        const double speed = space_length(space_tangent(curve, t));
        EXPECT_LE(std::abs(r.t - t), 1e-8 + 1e-11 / speed) << space_describe(curve, t, p, r);
        EXPECT_LE(r.residual, 1e-12 * plan.diagonal() + 1e-9 * std::abs(r.t - t) * speed) << space_describe(curve, t, p, r);
      }
    }
  EXPECT_GT(rows, 800);
}

// Off the curve along a normal at t, by 1e-4 to 1e-1 of the diagonal: off_curve, the nearest point
// of the segment (no point of it nearer than the residual, by the test's own search; and the
// residual no more than the offset).
TEST(SpaceCurves, PointsOffTheCurveGetTheNearestPointOfTheSegment) {
  int rows = 0;
  for (CurveKind kind : kSpaceKinds)
    for (int degree = 1; degree <= space_max_degree(kind); degree += 1 + (test_support::kSanitizerThinning > 1)) {
      std::mt19937_64 rng(2000 * degree + static_cast<int>(kind));
      const Curve curve = random_space_curve(kind, degree, rng);
      const InversionPlan plan = make_plan(curve);
      for (int k = 0; k < 6; ++k) {
        const double t = space_uniform(rng, 0.05, 0.95);
        const Vec3 on = space_point(curve, t), tangent = space_tangent(curve, t);
        Vec3 random{space_uniform(rng, -1, 1), space_uniform(rng, -1, 1), space_uniform(rng, -1, 1)};
        const double along = (random[0] * tangent[0] + random[1] * tangent[1] + random[2] * tangent[2]) /
                             (tangent[0] * tangent[0] + tangent[1] * tangent[1] + tangent[2] * tangent[2]);
        Vec3 normal;
        for (int c = 0; c < 3; ++c) normal[c] = random[c] - along * tangent[c];
        const double offset = std::pow(10.0, space_uniform(rng, -4, -1)) * plan.diagonal() / space_length(normal);
        const Vec3 p{on[0] + offset * normal[0], on[1] + offset * normal[1], on[2] + offset * normal[2]};
        const PointResult r = invert_point(plan, Point3(p[0], p[1], p[2]));
        ++rows;
        ASSERT_EQ(r.status, Status::off_curve) << space_describe(curve, t, p, r);
        ASSERT_TRUE(r.t >= 0 && r.t <= 1) << space_describe(curve, t, p, r);
        const Vec3 q = space_point(curve, r.t);
        EXPECT_NEAR(r.residual, std::hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]), 1e-12 * plan.diagonal());
        EXPECT_LE(r.residual, offset * space_length(normal) * (1 + 1e-9)) << space_describe(curve, t, p, r);
        EXPECT_LE(r.residual, nearest_distance_by_search(curve, p) + 1e-10 * plan.diagonal())
            << space_describe(curve, t, p, r);
      }
    }
  EXPECT_GT(rows, 150 / test_support::kSanitizerThinning);
}

// A polynomial space curve through one point at two parameters t1 < t2: the last control point
// solves P(t1) = P(t2), sum_i (B_i(t1) - B_i(t2)) P_i = 0.
Curve crossing_space_curve(int degree, double t1, double t2, std::mt19937_64& rng) {
  std::vector<Vec3> p(degree + 1);
  for (Vec3& q : p)
    for (double& c : q) c = space_uniform(rng, 0.0, 1.0);
  std::vector<double> b1(degree + 1), b2(degree + 1);
  bernstein_basis(degree, t1, b1);
  bernstein_basis(degree, t2, b2);
  for (int c = 0; c < 3; ++c) {
    double s = 0;
    for (int i = 0; i < degree; ++i) s += (b1[i] - b2[i]) * p[i][c];
    p[degree][c] = -s / (b1[degree] - b2[degree]);
  }
  return Curve::space_bezier("crossing", p);
}

TEST(SpaceCurves, ASelfIntersectionInSpaceIsADoublePointWithBothParameters) {
  int rows = 0;
  for (int degree = 3; degree <= 12; ++degree)
    for (int k = 0; k < 3; ++k) {
      std::mt19937_64 rng(3000 * degree + k);
      const double t1 = space_uniform(rng, 0.1, 0.4), t2 = space_uniform(rng, 0.6, 0.9);
      const Curve curve = crossing_space_curve(degree, t1, t2, rng);
      const InversionPlan plan = make_plan(curve);
      const Vec3 a = space_point(curve, t1), b = space_point(curve, t2);
      ASSERT_LT(std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]), 1e-12 * plan.diagonal());
      const PointResult r = invert_point(plan, Point3(a[0], a[1], a[2]));
      ++rows;
      ASSERT_EQ(r.status, Status::double_point) << space_describe(curve, t1, a, r);
      EXPECT_NEAR(r.t, t1, 1e-8) << space_describe(curve, t1, a, r);
      EXPECT_NEAR(r.t2, t2, 1e-8) << space_describe(curve, t1, a, r);
    }
  EXPECT_EQ(rows, 30);
}

// A plane crossing lifted off its plane: x, y cross at t1, t2 (as above, in 2D) and z = 1e-4 t, so
// P(t2) - P(t1) = (0, 0, 1e-4 (t2 - t1)): 30 times the tolerance and more, along the plane's normal.
// The curve's principal plane is then the (x, y) plane to within ~1e-4 rad, so its projection
// crosses itself within the tolerance, the curve does not: a point at P(t1) is ok at t1 alone.
TEST(SpaceCurves, AProjectionThatCrossesItselfIsNotADoublePoint) {
  int rows = 0;
  for (int degree = 3; degree <= 10; ++degree)
    for (int k = 0; k < 3; ++k) {
      std::mt19937_64 rng(4000 * degree + k);
      const double t1 = space_uniform(rng, 0.1, 0.4), t2 = space_uniform(rng, 0.6, 0.9);
      const Curve plane = crossing_space_curve(degree, t1, t2, rng);
      std::vector<Vec3> p(degree + 1);
      for (int i = 0; i <= degree; ++i) p[i] = {plane.x_num[i], plane.y_num[i], 1e-4 * i / degree};
      const Curve curve = Curve::space_bezier("lifted", p);
      const InversionPlan plan = make_plan(curve);
      for (double t : {t1, t2}) {
        const Vec3 a = space_point(curve, t);
        const PointResult r = invert_point(plan, Point3(a[0], a[1], a[2]));
        ++rows;
        ASSERT_EQ(r.status, Status::ok) << space_describe(curve, t, a, r);
        EXPECT_NEAR(r.t, t, 1e-8) << space_describe(curve, t, a, r);
      }
    }
  EXPECT_EQ(rows, 48);
}

// A plane curve placed in a tilted plane far from the origin (a rotation and a translation): every
// point of the plane, on, near and off the curve, gets the plane engine's status and t.
TEST(SpaceCurves, APlaneCurveInATiltedPlaneAnswersAsInItsPlane) {
  int rows = 0, off = 0;
  for (CurveKind kind : {CurveKind::bezier, CurveKind::rational_bezier})
    for (int degree = 1; degree <= 12; ++degree) {
      std::mt19937_64 rng(5000 * degree + static_cast<int>(kind));
      std::vector<std::array<double, 2>> q(degree + 1);
      std::vector<double> w(degree + 1);
      for (auto& c : q) c = {space_uniform(rng, 0, 1), space_uniform(rng, 0, 1)};
      for (double& v : w) v = space_uniform(rng, 0.5, 2);
      const Curve flat = kind == CurveKind::bezier ? Curve::bezier("f", q) : Curve::rational_bezier("f", q, w);
      // An orthonormal frame e1, e2 of the plane (Gram-Schmidt from random vectors), and an origin.
      Vec3 e1{space_uniform(rng, -1, 1), space_uniform(rng, -1, 1), space_uniform(rng, -1, 1)};
      const double l1 = space_length(e1);
      for (double& c : e1) c /= l1;
      Vec3 e2{space_uniform(rng, -1, 1), space_uniform(rng, -1, 1), space_uniform(rng, -1, 1)};
      const double d = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2];
      for (int c = 0; c < 3; ++c) e2[c] -= d * e1[c];
      const double l2 = space_length(e2);
      for (double& c : e2) c /= l2;
      const Vec3 origin{123.0, -45.0, 67.0};
      auto lift = [&](double x, double y) {
        return Vec3{origin[0] + x * e1[0] + y * e2[0], origin[1] + x * e1[1] + y * e2[1], origin[2] + x * e1[2] + y * e2[2]};
      };
      std::vector<Vec3> p(degree + 1);
      for (int i = 0; i <= degree; ++i) p[i] = lift(q[i][0], q[i][1]);
      const Curve lifted = kind == CurveKind::bezier ? Curve::space_bezier("l", p) : Curve::space_rational_bezier("l", p, w);
      const InversionPlan plan2 = make_plan(flat), plan3 = make_plan(lifted);
      std::vector<Point> points2;
      std::vector<Point3> points3;
      for (int k = 0; k < 20; ++k) {
        const double t = space_uniform(rng, 0, 1);
        const auto on = flat.point(t);
        const double spread = k < 8 ? 0.0 : std::pow(10.0, space_uniform(rng, -5, -1));
        const double x = on[0] + spread * space_uniform(rng, -1, 1), y = on[1] + spread * space_uniform(rng, -1, 1);
        points2.push_back({x, y});
        const Vec3 l = lift(x, y);
        points3.emplace_back(l[0], l[1], l[2]);
      }
      std::vector<PointResult> r2(points2.size()), r3(points3.size());
      invert(plan2, points2, r2);
      invert(plan3, points3, r3);
      for (std::size_t i = 0; i < points2.size(); ++i) {
        ++rows;
        off += r2[i].status == Status::off_curve;
        const Vec3 l{points3[i].x, points3[i].y, points3[i].z};
        ASSERT_EQ(r3[i].status, r2[i].status) << space_describe(lifted, r2[i].t, l, r3[i]);
        EXPECT_NEAR(r3[i].t, r2[i].t, 1e-7) << space_describe(lifted, r2[i].t, l, r3[i]);
        EXPECT_NEAR(r3[i].residual, r2[i].residual, 1e-9 + 1e-6 * r2[i].residual);
      }
    }
  EXPECT_EQ(rows, 480);
  EXPECT_GT(off, 100);
}

// Lines, degree-elevated curves and a curve far from the origin.
// Found by tests/fuzz/fuzz_invert (corpus: space_point_beyond_the_largest_double.bin): a finite
// point more than the largest double from a curve's centre overflowed the projection to the plane
// and came back invalid_input. It is off the curve, at the nearest point of the segment, as in the
// plane; and a huge curve's point whose projection overflows but whose normalized point does not
// is answered by the search in space.
TEST(SpaceCurves, AFinitePointBeyondTheLargestDoubleFromTheCurveIsOffTheCurve) {
  const double big = std::numeric_limits<double>::max();
  for (const bool refine : {true, false}) {
    const InvertOptions options{.refine = refine};
    // A unit segment at x = -big, the point at x = +big: 2 big away, in input and normalized units.
    // From there every point of the segment is as near, to within its size over the distance.
    const InversionPlan small = make_plan(Curve::space_bezier("far", {{-big, 0, 0}, {-big, 1, 0}}));
    for (const double y : {0.0, -5.0, 0.25, 7.0}) {
      const PointResult r = invert_point(small, Point3(big, y, 0), options);
      EXPECT_EQ(r.status, Status::off_curve) << r.reason;
      EXPECT_EQ(r.path, Path::nearest);
      EXPECT_GE(r.t, 0.0) << y;
      EXPECT_LE(r.t, 1.0) << y;
      EXPECT_EQ(r.residual, std::numeric_limits<double>::infinity());  // the distance exceeds the largest double
    }
    // A curve as wide as half the doubles, far on one side: the point's projection overflows, its
    // normalized coordinates do not.
    const InversionPlan huge = make_plan(Curve::space_bezier("huge", {{-big, 0, 0}, {-big / 2, 0, 0}}));
    const PointResult r = invert_point(huge, Point3(0.3 * big, 0, 0.25 * big), options);
    EXPECT_EQ(r.status, Status::off_curve) << r.reason;
    EXPECT_NEAR(r.t, 1.0, 1e-12);
    EXPECT_NEAR(r.residual / big, std::hypot(0.8, 0.25), 1e-12);
  }
}

// A unit segment at x = -DBL_MAX: its tolerance is the resolution of its coordinates, 4 ulps of
// DBL_MAX, and its extent in the plan's normalized units a few ulps, so the plane (in the
// projection's units) and space (in its own) can disagree by rounding on a point an ulp or two off
// the line. Whatever either says, the space answer keeps the contract: an off_curve row's residual
// beyond the tolerance, every other row's within it; with every option (found by fuzz_invert:
// without refinement, a row the plane put off the curve stayed off_curve within the tolerance).
TEST(SpaceCurves, AStatusAgreesWithTheResidualOnACurveAFewUlpsWide) {
  const double big = std::numeric_limits<double>::max(), ulp = big - std::nextafter(big, 0.0);
  const double tolerance = kResolutionUlps * ulp;
  const InversionPlan plan = make_plan(Curve::space_bezier("edge", {{-big, 0.0, 0.0}, {-big, 1.0, 0.0}}));
  const std::vector<Point3> points = {{-big + ulp, 0.34, 0.0}, {-big + ulp, 0.5, 0.0}, {-big, 0.25, 0.0},
                                      {-big + 2 * ulp, 0.75, 0.0}, {-big + ulp, 1.5, 0.0}, {-big + 8 * ulp, 0.5, 0.0}};
  int off_curve = 0;
  for (int flags = 0; flags < 16; ++flags) {
    InvertOptions options;
    options.threads = 1;
    options.refine = !(flags & 1);
    options.fast_path = !(flags & 2);
    options.relative_tolerance = (flags & 4) ? 1e-2 : kDefaultRelativeTolerance;
    if (flags & 8) options.off_curve = OffCurve::projection;
    std::vector<PointResult> results(points.size());
    invert(plan, points, results, options);
    for (std::size_t k = 0; k < points.size(); ++k) {
      const PointResult& r = results[k];
      if (r.status == Status::off_curve) {
        ++off_curve;
        EXPECT_GT(r.residual, tolerance * (1 - 1e-12)) << "flags " << flags << ", point " << k;
      } else {
        EXPECT_LE(r.residual, tolerance * (1 + 1e-12)) << "flags " << flags << ", point " << k << ": status "
                                                        << static_cast<int>(r.status);
      }
      EXPECT_EQ(r.status == Status::ok, r.t >= 0.0 && r.t <= 1.0 && r.residual <= tolerance * (1 + 1e-12))
          << "flags " << flags << ", point " << k;
    }
  }
  EXPECT_GE(off_curve, 16);  // the point 8 ulps off the line, at least
}

TEST(SpaceCurves, LinesElevatedAndFarCurves) {
  const Curve line = Curve::space_bezier("line", {{0, 0, 0}, {1, 2, 3}});
  const PointResult on_line = invert_point(make_plan(line), Point3(0.25, 0.5, 0.75));
  EXPECT_EQ(on_line.status, Status::ok);
  EXPECT_NEAR(on_line.t, 0.25, 1e-14);
  const PointResult off_line = invert_point(make_plan(line), Point3(1.0, 0.5, 0.75));
  EXPECT_EQ(off_line.status, Status::off_curve);
  // Nearest point of the line to (1, 0.5, 0.75): t = (1 + 1 + 2.25) / 14.
  EXPECT_NEAR(off_line.t, 4.25 / 14, 1e-12);

  // A cubic and the same cubic elevated to degree 5 (the same points at the same t).
  const std::vector<Vec3> cubic{{0, 0, 0}, {1, 2, 0}, {2, -1, 1}, {3, 1, 2}};
  std::vector<Vec3> elevated = cubic;
  for (int step = 0; step < 2; ++step) {
    const int n = static_cast<int>(elevated.size()) - 1;
    std::vector<Vec3> next(n + 2);
    next[0] = elevated[0];
    next[n + 1] = elevated[n];
    for (int i = 1; i <= n; ++i)
      for (int c = 0; c < 3; ++c)
        next[i][c] = (static_cast<double>(i) / (n + 1)) * elevated[i - 1][c] + (1 - static_cast<double>(i) / (n + 1)) * elevated[i][c];
    elevated = next;
  }
  const Curve a = Curve::space_bezier("cubic", cubic), b = Curve::space_bezier("elevated", elevated);
  const InversionPlan plan_b = make_plan(b);
  EXPECT_EQ(plan_b.degree(), 3);
  for (double t : {0.0, 0.3, 0.7, 1.0}) {
    const Vec3 p = a.point3(t);
    const PointResult r = invert_point(plan_b, Point3(p[0], p[1], p[2]));
    EXPECT_EQ(r.status, Status::ok) << t;
    EXPECT_NEAR(r.t, t, 1e-12) << t;
  }
  // Far from the origin: the same cubic moved by 1e6 in every coordinate.
  std::vector<Vec3> moved = cubic;
  for (Vec3& p : moved)
    for (double& c : p) c += 1e6;
  const Curve far = Curve::space_bezier("far", moved);
  const InversionPlan plan_far = make_plan(far);
  for (double t : {0.1, 0.5, 0.9}) {
    const Vec3 p = far.point3(t);
    const PointResult r = invert_point(plan_far, Point3(p[0], p[1], p[2]));
    EXPECT_EQ(r.status, Status::ok) << t;
    EXPECT_NEAR(r.t, t, 1e-9) << t;
  }
}

// The plane and space entry points refuse each other's plans; the many-curve overload takes both
// kinds of curve in one call, z read for the space ones only; a non-finite z is invalid_input.
TEST(SpaceCurves, PlaneAndSpaceCurvesInOneCall) {
  const Curve plane = Curve::bezier("p", {{0, 0}, {1, 1}, {2, 0}});
  const Curve space = Curve::space_bezier("s", {{0, 0, 0}, {1, 1, 1}, {2, 0, 2}});
  const std::vector<InversionPlan> plans{make_plan(plane), make_plan(space)};
  EXPECT_THROW(invert_point(plans[1], Point{1, 0.5}), std::invalid_argument);
  EXPECT_THROW(invert_point(plans[0], Point3(1, 0.5, 0)), std::invalid_argument);
  const std::vector<int> curve_of{0, 1, 1, 0};
  const std::vector<Point> points{{1, 0.5}, {1, 0.5}, {1, 0.5}, {0, 0}};
  const std::vector<double> z{99, 1, std::nan(""), 99};
  std::vector<PointResult> results(4);
  invert(plans, curve_of, points, z, results);
  EXPECT_EQ(results[0].status, Status::ok);
  EXPECT_NEAR(results[0].t, 0.5, 1e-14);
  EXPECT_EQ(results[1].status, Status::ok);
  EXPECT_NEAR(results[1].t, 0.5, 1e-14);
  EXPECT_EQ(results[2].status, Status::invalid_input);
  EXPECT_EQ(results[3].status, Status::ok);
  EXPECT_EQ(results[3].t, 0.0);
}

}  // namespace
}  // namespace bezinv

namespace bezinv {
namespace {

// A curve with separate denominators is projected on the coordinate plane where it spreads most,
// at its own degree, each coordinate over its own denominator; the plane's two coordinates are the
// curve's own, less the centre.
TEST(SpaceCurves, SeparateDenominatorsProjectOnACoordinatePlaneAtTheirDegree) {
  std::mt19937_64 rng(8);
  for (int n = 1; n <= 20; ++n) {
    const Curve c = random_space_curve(CurveKind::rational, n, rng);
    const detail::SpaceData space = detail::make_space_data(c);
    ASSERT_GE(space.axes[0], 0) << n;
    const Curve flat = detail::projected_curve(space);
    EXPECT_EQ(flat.degree(), n);
    const std::array<const std::vector<double>*, 3> dens{&c.x_den, &c.y_den, &c.z_den};
    EXPECT_EQ(flat.x_den, *dens[space.axes[0]]);
    EXPECT_EQ(flat.y_den, *dens[space.axes[1]]);
    for (double t : {0.0, 0.3, 1.0}) {
      const Vec3 p = c.point3(t);
      const auto q = flat.point(t);
      EXPECT_NEAR(q[0], p[space.axes[0]] - space.centre[space.axes[0]], 1e-13) << n;
      EXPECT_NEAR(q[1], p[space.axes[1]] - space.centre[space.axes[1]], 1e-13) << n;
    }
  }
  // Flattened along z (the curve 50 times thinner in z than in x and y): the xy plane, where it
  // spreads as on its principal plane.
  std::vector<std::vector<double>> num(3), den(3);
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i <= 4; ++i) {
      den[k].push_back(space_uniform(rng, 0.5, 2.0));
      num[k].push_back(den[k][i] * space_uniform(rng, 0.0, k == 2 ? 0.02 : 1.0));
    }
  const Curve thin = Curve::space_rational("z", num[0], den[0], num[1], den[1], num[2], den[2]);
  const detail::SpaceData space = detail::make_space_data(thin);
  EXPECT_EQ(space.axes[0], 0);
  EXPECT_EQ(space.axes[1], 1);
  // A line along z: its projection on xy would be a point; on xz or yz it is the line.
  const Curve line = Curve::space_rational("l", {0.5, 1.0}, {1, 2}, {0.25, 0.75}, {1, 3}, {0, 2}, {1, 1.5});
  const detail::SpaceData along_z = detail::make_space_data(line);
  EXPECT_EQ(along_z.axes[1], 2);
  EXPECT_EQ(detail::projected_curve(along_z).degree(), 1);
  // The line x = y = z = t (its denominators 1, 2, 3 times one another): any coordinate plane keeps
  // it a line, and its points invert at their t.
  const Curve diagonal = Curve::space_rational("d", {0, 1}, {1, 1}, {0, 2}, {2, 2}, {0, 3}, {3, 3});
  EXPECT_GE(detail::make_space_data(diagonal).axes[0], 0);
  const InversionPlan plan = make_plan(diagonal);
  for (double t : {0.0, 0.25, 0.6, 1.0}) {
    const PointResult r = invert_point(plan, Point3(t, t, t));
    EXPECT_EQ(r.status, Status::ok) << t;
    EXPECT_NEAR(r.t, t, 1e-14) << t;
  }
}

// P and P' from the one Horner loop of every polynomial and its derivative side by side
// (SpaceData::first_order_forward, width 8 with one denominator, 16 with three) are the doubles of
// the general evaluation, which evaluates the values and the derivatives in loops of their own.
TEST(SpaceCurves, TheOneLoopJetIsTheGeneralJetBitForBit) {
  std::mt19937_64 rng(77);
  int compared = 0;
  for (CurveKind kind : kSpaceKinds)
    for (int n = 1; n <= 20; ++n) {
      const Curve c = random_space_curve(kind, n, rng);
      const detail::SpaceData space = detail::make_space_data(c);
      EXPECT_EQ(space.first_order_width, kind == CurveKind::rational ? 16 : 8);
      for (int k = 0; k < 50; ++k) {
        const double t = k == 0 ? 0.0 : k == 1 ? 1.0 : k == 2 ? 0.5 : space_uniform(rng, 0.0, 1.0);
        const detail::SpaceJet one_loop = detail::space_jet(space, t, 2), general = detail::space_jet(space, t, 3);
        for (int j = 0; j < 3; ++j) {
          EXPECT_TRUE(test_support::same_bits(one_loop.p[j], general.p[j])) << to_string(kind) << " n=" << n << " t=" << t;
          EXPECT_TRUE(test_support::same_bits(one_loop.dp[j], general.dp[j])) << to_string(kind) << " n=" << n << " t=" << t;
        }
        ++compared;
      }
    }
  EXPECT_EQ(compared, 3 * 20 * 50);
}

// The lane-batched check in space (Implementation::space_check) against the scalar code it stands
// for: every lane it settles has space_refine's distance bit for bit, and space_refine keeps the
// lane's t (so the answer is the same); on points on the curve and moved 1e-2..1e-6 along a normal
// (settled: t is the foot to rounding), moved 1e-9 along z or
// given a t 1e-12 past theirs (where the first-order test says t is not the foot: not settled, and
// space_refine answers them); degrees 1..20, every kind (one denominator and three), every
// implementation.
TEST(SpaceCurves, TheBatchedCheckGivesTheScalarChecksBits) {
  for (const kernels::Implementation* implementation : kernels::available_implementations()) {
    std::mt19937_64 rng(20261204);
    std::size_t lanes_total = 0, settled = 0;
    for (CurveKind kind : kSpaceKinds)
      for (int n = 1; n <= 20; ++n) {
        const Curve c = random_space_curve(kind, n, rng);
        const detail::SpaceData space = detail::make_space_data(c);
        std::vector<double> t, x, y, z;
        for (int k = 0; k < 24; ++k) {
          const double t0 = k == 0 ? 0.0 : k == 1 ? 1.0 : space_uniform(rng, 0.0, 1.0);
          Vec3 p = c.point3(t0);
          if (k % 4 == 1) p[2] += 1e-9;
          const double start = k % 4 == 3 ? std::min(1.0, t0 + 1e-12) : t0;
          auto q = detail::space_normalize(space, p[0], p[1], p[2]);
          if (k % 4 == 2) {  // moved along a normal N = P' x a in normalized units: t stays the foot
            const detail::SpaceJet jet = detail::space_jet(space, t0, 2);
            const Vec3 a{space_uniform(rng, -1, 1), space_uniform(rng, -1, 1), space_uniform(rng, -1, 1)};
            const Vec3 normal{jet.dp[1] * a[2] - jet.dp[2] * a[1], jet.dp[2] * a[0] - jet.dp[0] * a[2],
                              jet.dp[0] * a[1] - jet.dp[1] * a[0]};
            const double delta = std::pow(10.0, -2.0 - k % 5) / space_length(normal);
            for (int j = 0; j < 3; ++j) q[j] += delta * normal[j];
          }
          t.push_back(start), x.push_back(q[0]), y.push_back(q[1]), z.push_back(q[2]);
        }
        std::vector<double> distance(t.size());
        implementation->space_check({space.degree, space.first_order_width == 8 ? 1 : 3,
                                     space.first_order_forward.data(), space.first_order_backward.data()},
                                    t.size(), t.data(), x.data(), y.data(), z.data(), distance.data());
        for (std::size_t l = 0; l < t.size(); ++l) {
          SCOPED_TRACE(std::string(implementation->name) + " " + to_string(kind) + " n=" + std::to_string(n) +
                       " lane " + std::to_string(l));
          ++lanes_total;
          if (std::isnan(distance[l])) continue;
          ++settled;
          const detail::SpaceRefined scalar = detail::space_refine(space, {x[l], y[l], z[l]}, t[l], true);
          EXPECT_TRUE(test_support::same_bits(scalar.distance, distance[l])) << scalar.distance << " " << distance[l];
          EXPECT_TRUE(test_support::same_bits(scalar.t, t[l]));
        }
      }
    std::printf("%s: %zu of %zu lanes settled by the batched check\n", std::string(implementation->name).c_str(),
                settled, lanes_total);
    EXPECT_GE(settled, lanes_total * 2 / 5) << implementation->name;
  }
}

}  // namespace
}  // namespace bezinv
