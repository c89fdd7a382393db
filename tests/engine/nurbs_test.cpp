// NURBS and composite curves (engine/src/piecewise/): points made from known global parameters by
// the test's own Cox-de Boor evaluation (tests/support/de_boor.hpp), or by construction (a circle
// from its angle, a point along a normal, a crossing of a symmetric curve), inverted on the whole
// curve; the parameter, the status and the residual checked against those.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/io.hpp"
#include "bezinv/nurbs.hpp"
#include "bezinv/plan.hpp"
#include "support/de_boor.hpp"
#include "support/de_casteljau.hpp"
#include "support/expect_input_error.hpp"
#include "support/sanitizers.hpp"
#include "support/scratch_directory.hpp"

namespace bezinv {
namespace nurbs_tests {

using test_support::Nurbs;
using test_support::nurbs_point;
using Vec3 = std::array<double, 3>;

Curve engine_nurbs(const Nurbs& n, bool space = false) {
  if (space) return Curve::space_nurbs("n", n.degree, n.knots, n.points, n.weights);
  std::vector<std::array<double, 2>> xy;
  for (const Vec3& p : n.points) xy.push_back({p[0], p[1]});
  return Curve::nurbs("n", n.degree, n.knots, xy, n.weights);
}

PointResult invert_at(const InversionPlan& plan, const Vec3& p) {
  if (plan.dimension() == 3) return invert_point(plan, Point3{p[0], p[1], p[2]});
  return invert_point(plan, Point{p[0], p[1]});
}

// A cubic whose control points go right throughout: a graph of x, so no point has two parameters.
Nurbs wavy_cubic(std::vector<double> knots) {
  return {3, std::move(knots), {{0, 0, 0}, {1, 2, 0}, {2, -1, 0}, {3, 2, 0}, {4, 0, 0}, {5, 1, 0}, {6, -1, 0}}, {}};
}

// Every knot of the domain, the ends, points between them, and points just beside the knots
// (within the tolerance of the span ending there too: one point, not two).
std::vector<double> parameters_of(const Nurbs& n, int between = 7) {
  std::vector<double> u;
  const double a = n.domain_start(), b = n.domain_end();
  for (int i = 0; i <= 8 * between; ++i) u.push_back(a + (b - a) * i / (8 * between));
  for (double k : n.knots)
    if (k >= a && k <= b) {
      u.push_back(k);
      if (k - 1e-9 * (b - a) > a) u.push_back(k - 1e-9 * (b - a));
      if (k + 1e-9 * (b - a) < b) u.push_back(k + 1e-9 * (b - a));
    }
  return u;
}

// Each parameter's point, inverted: ok at that parameter (a closed curve's end: at its start).
void expect_parameters_recovered(const Nurbs& n, bool space = false, bool closed = false) {
  const InversionPlan plan = make_plan(engine_nurbs(n, space));
  const double length = n.domain_end() - n.domain_start();
  for (const double u : parameters_of(n)) {
    const PointResult r = invert_at(plan, nurbs_point(n, u));
    EXPECT_EQ(r.status, Status::ok) << "u = " << u;
    EXPECT_NEAR(r.t, closed && u == n.domain_end() ? n.domain_start() : u, 1e-9 * length) << "u = " << u;
    EXPECT_LE(r.residual, 1e-12 * plan.diagonal()) << "u = " << u;
    EXPECT_TRUE(std::isnan(r.t2)) << "u = " << u;
  }
}

TEST(NurbsCurve, ClampedKnotVectorRecoversKnownParameters) {
  expect_parameters_recovered(wavy_cubic({0, 0, 0, 0, 0.5, 1.5, 3, 4, 4, 4, 4}));
}

TEST(NurbsCurve, UnclampedKnotVectorRecoversKnownParameters) {
  const Nurbs n = wavy_cubic({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10});
  EXPECT_EQ(parameter_domain(engine_nurbs(n)), (std::array<double, 2>{3, 7}));
  expect_parameters_recovered(n);
}

TEST(NurbsCurve, SpansCoverTheDomainInOrder) {
  const std::vector<BezierSpan> spans = bezier_spans(engine_nurbs(wavy_cubic({0, 0, 0, 0, 0.5, 1.5, 3, 4, 4, 4, 4})));
  ASSERT_EQ(spans.size(), 4u);
  const double ends[] = {0, 0.5, 1.5, 3, 4};
  for (std::size_t k = 0; k < spans.size(); ++k) {
    EXPECT_EQ(spans[k].start, ends[k]);
    EXPECT_EQ(spans[k].end, ends[k + 1]);
    EXPECT_EQ(spans[k].curve.degree(), 3);
  }
}

TEST(NurbsCurve, CornerAtARepeatedKnotIsOnePoint) {
  // Knot 1 twice at degree 2: the curve passes through (2, 0), the control point there, with a corner.
  const Nurbs n{2, {0, 0, 0, 1, 1, 2, 2, 2}, {{0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {3, 1, 0}, {4, 0, 0}}, {}};
  const InversionPlan plan = make_plan(engine_nurbs(n));
  const PointResult corner = invert_at(plan, {2, 0, 0});
  EXPECT_EQ(corner.status, Status::ok);
  EXPECT_EQ(corner.t, 1.0);
  EXPECT_TRUE(std::isnan(corner.t2));
  expect_parameters_recovered(n);
}

TEST(NurbsCurve, DegreeOnePolyline) {
  const Nurbs n{1, {0, 0, 1, 2, 3, 3}, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 1, 0}}, {}};
  expect_parameters_recovered(n);
  const InversionPlan plan = make_plan(engine_nurbs(n));
  const PointResult r = invert_at(plan, {1.25, 1, 0});
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_NEAR(r.t, 2.25, 1e-12);
}

TEST(NurbsCurve, ClosedCurveStartIsOnePoint) {
  // Clamped, first control point = last.
  const Nurbs clamped{3, {0, 0, 0, 0, 1, 2, 3, 3, 3, 3},
                      {{0, 0, 0}, {2, -1, 0}, {3, 1, 0}, {1, 3, 0}, {-1, 2, 0}, {0, 0, 0}}, {}};
  const InversionPlan plan = make_plan(engine_nurbs(clamped));
  const PointResult r = invert_at(plan, {0, 0, 0});
  EXPECT_EQ(r.status, Status::ok);
  EXPECT_EQ(r.t, 0.0);
  EXPECT_TRUE(std::isnan(r.t2));
  expect_parameters_recovered(clamped, /*space=*/false, /*closed=*/true);

  // Unclamped and periodic: the first three control points repeated at the end, uniform knots.
  const Nurbs periodic{3, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11},
                       {{0, 0, 0}, {2, -1, 0}, {3, 1, 0}, {1, 3, 0}, {-1, 2, 0}, {0, 0, 0}, {2, -1, 0}, {3, 1, 0}},
                       {}};
  const InversionPlan closed = make_plan(engine_nurbs(periodic));
  const PointResult start = invert_at(closed, nurbs_point(periodic, 3.0));
  EXPECT_EQ(start.status, Status::ok);
  EXPECT_NEAR(start.t, 3.0, 1e-9);
  EXPECT_TRUE(std::isnan(start.t2));
  const PointResult end = invert_at(closed, nurbs_point(periodic, 8.0));
  EXPECT_EQ(end.status, Status::ok);
  EXPECT_NEAR(end.t, 3.0, 1e-9);
}

// The circle of radius 1 as 9 control points of degree 2, weights 1 and sqrt(2)/2, knots at the
// quarters. On the quarter q, the point at angle q pi/2 + a has s = tan(a/2) sqrt2 / (1 + tan(a/2)
// (sqrt2 - 1)) (the stereographic parameter tan(a/2) = s / (s + sqrt2 (1 - s))), so u = (q + s) / 4.
Nurbs unit_circle() {
  const double w = std::numbers::sqrt2 / 2;
  return {2,
          {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1},
          {{1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}, {0, -1, 0}, {1, -1, 0}, {1, 0, 0}},
          {1, w, 1, w, 1, w, 1, w, 1}};
}

double circle_parameter(double angle) {
  const double quarter = std::numbers::pi / 2;
  const double q = std::min(std::floor(angle / quarter), 3.0);
  const double tau = std::tan((angle - q * quarter) / 2);
  const double s = tau * std::numbers::sqrt2 / (1 + tau * (std::numbers::sqrt2 - 1));
  return (q + s) / 4;
}

TEST(NurbsCurve, CircleFromItsAngle) {
  const InversionPlan plan = make_plan(engine_nurbs(unit_circle()));
  for (int i = 0; i < 64; ++i) {
    const double angle = 2 * std::numbers::pi * i / 64 + (i % 3) * 0.01;
    const double u = circle_parameter(angle);
    const PointResult r = invert_at(plan, {std::cos(angle), std::sin(angle), 0});
    EXPECT_EQ(r.status, Status::ok) << "angle " << angle;
    EXPECT_NEAR(r.t, u, 1e-12) << "angle " << angle;
    EXPECT_TRUE(std::isnan(r.t2)) << "angle " << angle;
    // Off the circle along its radius: off_curve, the distance exactly |radius - 1|.
    for (const double radius : {1.01, 0.5}) {
      const PointResult off = invert_at(plan, {radius * std::cos(angle), radius * std::sin(angle), 0});
      EXPECT_EQ(off.status, Status::off_curve) << "angle " << angle << " radius " << radius;
      EXPECT_NEAR(off.residual, std::abs(radius - 1), 1e-12) << "angle " << angle << " radius " << radius;
      if (i > 0) {
        EXPECT_NEAR(off.t, u, 1e-7) << "angle " << angle << " radius " << radius;
      }
    }
  }
  // The start (= the end): one point, at the start of the domain.
  const PointResult start = invert_at(plan, {1, 0, 0});
  EXPECT_EQ(start.status, Status::ok);
  EXPECT_EQ(start.t, 0.0);
}

TEST(NurbsCurve, SelfIntersectingPolylineIsADoublePoint) {
  const Nurbs n{1, {0, 0, 1, 2, 3, 3}, {{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 2, 0}}, {}};
  const PointResult r = invert_at(make_plan(engine_nurbs(n)), {1, 1, 0});
  EXPECT_EQ(r.status, Status::double_point);
  EXPECT_NEAR(r.t, 0.5, 1e-12);
  EXPECT_NEAR(r.t2, 2.5, 1e-12);
}

TEST(NurbsCurve, SelfIntersectionAcrossCubicSpans) {
  // Symmetric about x = 0 (control points and knots mirrored): P(3 - u) is P(u) mirrored, so where
  // x(u) = 0 away from the middle, P(u) = P(3 - u): a crossing of two different spans.
  const Nurbs n{3, {0, 0, 0, 0, 1, 2, 3, 3, 3, 3},
                {{-3, 0, 0}, {3, 2, 0}, {1, 4, 0}, {-1, 4, 0}, {-3, 2, 0}, {3, 0, 0}}, {}};
  double lo = 0, hi = 1;  // x(0) = -3 < 0 < x(1)
  ASSERT_GT(nurbs_point(n, 1.0)[0], 0);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (nurbs_point(n, mid)[0] < 0 ? lo : hi) = mid;
  }
  const double u = 0.5 * (lo + hi);
  const PointResult r = invert_at(make_plan(engine_nurbs(n)), nurbs_point(n, u));
  EXPECT_EQ(r.status, Status::double_point);
  EXPECT_NEAR(r.t, u, 1e-9);
  EXPECT_NEAR(r.t2, 3 - u, 1e-9);
}

TEST(NurbsCurve, BeyondTheEndsIsOutsideSegment) {
  const Nurbs n = wavy_cubic({0, 0, 0, 0, 0.5, 1.5, 3, 4, 4, 4, 4});
  const InversionPlan plan = make_plan(engine_nurbs(n));
  for (const double u : {-0.1, -0.02, 4.02, 4.1}) {
    const PointResult r = invert_at(plan, nurbs_point(n, u));  // the end spans' polynomials
    EXPECT_EQ(r.status, Status::outside_segment) << "u = " << u;
    EXPECT_NEAR(r.t, u, 1e-9) << "u = " << u;
  }
}

TEST(NurbsCurve, AnInnerSpanExtensionIsOffTheCurve) {
  // (1, -0.5) is on the line of the middle segment, below the curve: off_curve, nearest (1, 0).
  const Nurbs n{1, {0, 0, 1, 2, 3, 3}, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 1, 0}}, {}};
  const PointResult r = invert_at(make_plan(engine_nurbs(n)), {1, -0.5, 0});
  EXPECT_EQ(r.status, Status::off_curve);
  EXPECT_NEAR(r.t, 1.0, 1e-12);
  EXPECT_NEAR(r.residual, 0.5, 1e-12);
}

// min over u of |P(u) - p|: dense samples, the best refined by golden sections.
double nearest_distance(const Nurbs& n, const Vec3& p, int samples = 20000) {
  const auto distance = [&](double u) {
    const Vec3 q = nurbs_point(n, u);
    return std::hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
  };
  const double a = n.domain_start(), b = n.domain_end();
  int best = 0;
  for (int i = 1; i <= samples; ++i)
    if (distance(a + (b - a) * i / samples) < distance(a + (b - a) * best / samples)) best = i;
  double lo = a + (b - a) * std::max(best - 1, 0) / samples, hi = a + (b - a) * std::min(best + 1, samples) / samples;
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 100; ++i) {
    const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    (distance(x1) < distance(x2) ? hi : lo) = distance(x1) < distance(x2) ? x2 : x1;
  }
  return distance(0.5 * (lo + hi));
}

TEST(NurbsCurve, OffCurveResidualIsTheDistance) {
  // A convex arc; points outside it along the normal, nearest point P(u) at distance d.
  const Nurbs n{3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1}, {{0, 0, 0}, {1, 2, 0}, {3, 3, 0}, {5, 2, 0}, {6, 0, 0}}, {1, 2, 1, 1, 1}};
  const InversionPlan plan = make_plan(engine_nurbs(n));
  for (const double u : {0.1, 0.3, 0.5, 0.62, 0.9}) {
    const Vec3 p = nurbs_point(n, u), d = test_support::nurbs_tangent(n, u);
    const double length = std::hypot(d[0], d[1]);
    for (const double distance : {1e-3, 0.05}) {
      const Vec3 q{p[0] - distance * d[1] / length, p[1] + distance * d[0] / length, 0};  // to the left: outside
      const PointResult r = invert_at(plan, q);
      EXPECT_EQ(r.status, Status::off_curve) << "u = " << u;
      EXPECT_NEAR(r.t, u, 1e-6) << "u = " << u;
      EXPECT_NEAR(r.residual, distance, 1e-7 * distance) << "u = " << u;
      EXPECT_NEAR(r.residual, nearest_distance(n, q), 1e-9) << "u = " << u;
    }
  }
}

TEST(NurbsCurve, RationalSpaceCurve) {
  const Nurbs n{3, {0, 0, 0, 0, 0.4, 1, 1, 1, 1}, {{0, 0, 0}, {1, 2, 1}, {2, -1, 2}, {3, 1, 0}, {4, 0, 1}}, {1, 2, 0.5, 1, 1.5}};
  expect_parameters_recovered(n, /*space=*/true);
  const InversionPlan plan = make_plan(engine_nurbs(n, true));
  EXPECT_EQ(plan.dimension(), 3);
  // Off the curve in space: the residual is the distance of the test's own search.
  const Vec3 q{2, 1, 2};
  const PointResult r = invert_at(plan, q);
  EXPECT_EQ(r.status, Status::off_curve);
  EXPECT_NEAR(r.residual, nearest_distance(n, q), 1e-9);
}

// Points on, near and off a curve, with their bits compared across thread counts and against the
// many-curve overload.
TEST(NurbsCurve, AnswersDoNotDependOnThreadsOrOverload) {
  const Nurbs plane = unit_circle();
  const Nurbs space{3, {0, 0, 0, 0, 0.4, 1, 1, 1, 1}, {{0, 0, 0}, {1, 2, 1}, {2, -1, 2}, {3, 1, 0}, {4, 0, 1}}, {}};
  const std::vector<InversionPlan> plans{make_plan(Curve::bezier("b", {{0, 0}, {1, 2}, {2, 0}})),
                                         make_plan(engine_nurbs(plane)), make_plan(engine_nurbs(space, true))};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0, 1), noise(-1e-3, 1e-3);
  std::vector<int> curve_of;
  std::vector<Point> points;
  std::vector<double> z;
  for (int i = 0; i < 3000; ++i) {
    const int c = static_cast<int>(rng() % 3);
    Vec3 p = c == 0 ? Vec3{2 * unit(rng), unit(rng), 0} : nurbs_point(c == 1 ? plane : space, unit(rng));
    if (i % 2) p = {p[0] + noise(rng), p[1] + noise(rng), c == 2 ? p[2] + noise(rng) : 0};
    curve_of.push_back(c);
    points.push_back({p[0], p[1]});
    z.push_back(c == 2 ? p[2] : 0);
  }
  auto run = [&](int threads) {
    std::vector<PointResult> results(points.size());
    InvertOptions options;
    options.threads = threads;
    invert(plans, curve_of, points, z, results, options);
    return results;
  };
  const auto one = run(1), two = run(2), all = run(0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const PointResult alone = curve_of[i] == 2 ? invert_point(plans[2], Point3{points[i].x, points[i].y, z[i]})
                                               : invert_point(plans[curve_of[i]], points[i]);
    for (const auto* r : {&two[i], &all[i], &alone}) {
      EXPECT_EQ(r->status, one[i].status) << i;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(r->t), std::bit_cast<std::uint64_t>(one[i].t)) << i;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(r->residual), std::bit_cast<std::uint64_t>(one[i].residual)) << i;
    }
    if (curve_of[i] > 0 && i % 2 == 0) {
      EXPECT_EQ(one[i].status, Status::ok) << i;
    }
  }
}

// A curve of many spans, where each point is put only to the spans near it: points on it are found
// at their parameter, points near and far from it answered at their nearest point (the test's own
// search over the whole curve: no span that holds a nearer point was passed over).
TEST(NurbsCurve, ManySpansNearAndFarPoints) {
  Nurbs n{3, {0, 0, 0, 0}, {}, {}};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < 23; ++i) {
    n.points.push_back({static_cast<double>(i), 2 * std::sin(0.7 * i) + 0.5 * unit(rng), 0});
    n.weights.push_back(0.5 + unit(rng));
  }
  for (int k = 1; k <= 19; ++k) n.knots.push_back(k);
  for (int k = 0; k < 4; ++k) n.knots.push_back(20);
  const InversionPlan plan = make_plan(engine_nurbs(n));
  for (int i = 0; i < 60; ++i) {
    const double u = 20 * unit(rng);
    const PointResult r = invert_at(plan, nurbs_point(n, u));
    EXPECT_EQ(r.status, Status::ok) << "u = " << u;
    EXPECT_NEAR(r.t, u, 1e-9 * 20) << "u = " << u;
  }
  std::uniform_real_distribution<double> x(-10, 32), y(-8, 8), near(-0.05, 0.05);
  for (int i = 0; i < 30; ++i) {
    const Vec3 on = nurbs_point(n, 20 * unit(rng));
    const Vec3 far{x(rng), y(rng), 0}, beside{on[0] + near(rng), on[1] + near(rng), 0};
    if (test_support::thinned_out(static_cast<std::size_t>(i))) continue;
    for (const Vec3& q : {far, beside}) {
      const PointResult r = invert_at(plan, q);
      // 200 samples a span, then golden sections: the spans' wiggles are a span long.
      const double expected = nearest_distance(n, q, 4000);
      if (expected > 1e-6 * plan.diagonal() * 1.01) {
        EXPECT_EQ(r.status, Status::off_curve) << q[0] << ", " << q[1];
        EXPECT_NEAR(r.residual, expected, 1e-9 * (1 + expected)) << q[0] << ", " << q[1];
      }
    }
  }
}

// A cubic Bezier from (0, 0) to (3, 0), a quadratic NURBS on [2, 5] from (3, 0) to (7, 0), a
// quarter circle about (7, 1) to (8, 1): t = 0..1, 1..2, 2..3.
Curve three_part_composite() {
  const double w = std::numbers::sqrt2 / 2;
  return Curve::composite(
      "c", {Curve::bezier("", {{0, 0}, {1, 1}, {2, 1}, {3, 0}}),
            Curve::nurbs("", 2, {2, 2, 2, 3, 3.5, 5, 5, 5}, {{3, 0}, {4, -1}, {5, 0}, {6, -1}, {7, 0}}),
            Curve::rational_bezier("", {{7, 0}, {8, 0}, {8, 1}}, {1, w, 1})});
}

TEST(CompositeCurve, BezierNurbsAndRationalBezier) {
  const InversionPlan plan = make_plan(three_part_composite());
  EXPECT_EQ(parameter_domain(plan.curve()), (std::array<double, 2>{0, 3}));
  const Nurbs middle{2, {2, 2, 2, 3, 3.5, 5, 5, 5}, {{3, 0, 0}, {4, -1, 0}, {5, 0, 0}, {6, -1, 0}, {7, 0, 0}}, {}};
  for (int i = 0; i <= 20; ++i) {
    const double s = i / 20.0;
    const auto b = test_support::de_casteljau({{0, 0}, {1, 1}, {2, 1}, {3, 0}}, s);
    const Vec3 in_middle = nurbs_point(middle, 2 + 3 * s);
    const double angle = -std::numbers::pi / 2 + s * std::numbers::pi / 2;
    const Vec3 on_arc{7 + std::cos(angle), 1 + std::sin(angle), 0};
    const double expected[] = {s, 1 + s, 2 + circle_parameter(angle + std::numbers::pi / 2) * 4};
    const Vec3 points[] = {{b[0], b[1], 0}, in_middle, on_arc};
    for (int k = 0; k < 3; ++k) {
      const PointResult r = invert_at(plan, points[k]);
      EXPECT_EQ(r.status, Status::ok) << "part " << k << " s " << s;
      EXPECT_NEAR(r.t, expected[k], 1e-9) << "part " << k << " s " << s;
      EXPECT_TRUE(std::isnan(r.t2)) << "part " << k << " s " << s;
    }
  }
  // Off the composite, above the joint (3, 0) of the first two parts: the distance of a dense
  // search over the three parts.
  const Vec3 q{3, 0.2, 0};
  double nearest = HUGE_VAL;
  for (int i = 0; i <= 300000; ++i) {
    const double s = i / 300000.0;
    const auto b = test_support::de_casteljau({{0, 0}, {1, 1}, {2, 1}, {3, 0}}, s);
    const Vec3 m = nurbs_point(middle, 2 + 3 * s);
    nearest = std::min({nearest, std::hypot(b[0] - q[0], b[1] - q[1]), std::hypot(m[0] - q[0], m[1] - q[1])});
  }
  const PointResult off = invert_at(plan, q);
  EXPECT_EQ(off.status, Status::off_curve);
  EXPECT_LE(off.residual, nearest);
  EXPECT_NEAR(off.residual, nearest, 1e-9);
  // Beyond the end of the arc (its extension past (8, 1)): outside_segment, t past 3.
  const double w = std::numbers::sqrt2 / 2;
  const auto beyond = test_support::rational_de_casteljau({{7, 0}, {8, 0}, {8, 1}}, {1, w, 1}, 1.05);
  const PointResult r = invert_at(plan, {beyond[0], beyond[1], 0});
  EXPECT_EQ(r.status, Status::outside_segment);
  EXPECT_NEAR(r.t, 3.05, 1e-9);
}

TEST(PiecewiseInput, RefusedCurvesNameTheField) {
  const auto refused = [](const Curve& c, const std::string& fragment) {
    try {
      validate(c);
      ADD_FAILURE() << "no CurveError, expected one naming " << fragment;
    } catch (const CurveError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  const std::vector<std::array<double, 2>> p{{0, 0}, {1, 1}, {2, 0}, {3, 1}};
  refused(Curve::nurbs("a", 2, {0, 0, 0, 1, 1, 1}, p), "knots: 6 knots for 4 points of degree 2");
  refused(Curve::nurbs("a", 2, {0, 0, 0, 2, 1, 1, 1}, p), "knots[4]");
  refused(Curve::nurbs("a", 2, {0, 0, 0, 1, 2, 2, 2}, p, {1, 1, 0, 1}), "weights[2]");
  refused(Curve::nurbs("a", 0, {0, 0, 1, 1}, p), "degree");
  refused(Curve::nurbs("a", 1, {0, 0, 1, 1, 1, 1}, p), "knots[2]");  // 1 four times: more than degree + 1
  refused(Curve::composite("c", {Curve::bezier("", {{0, 0}, {1, 0}}), Curve::bezier("", {{1, 0.1}, {2, 0}})}),
          "curves[1]: starts at (1, 0.1) but curves[0] ends at (1, 0)");
  refused(Curve::composite("c", {}), "curves: empty");
}

TEST(PiecewiseInput, CurvesFileErrorsNameTheCurveAndTheField) {
  const test_support::ScratchDirectory scratch("bezinv_nurbs_input_");
  const auto file_error = [&](const std::string& curve, std::initializer_list<std::string> fragments) {
    const std::string path = scratch.write("curves.json", "{\"curves\": [" + curve + "]}");
    test_support::expect_input_error([&] { read_curves_json(path); }, fragments);
  };
  const std::string points = R"("points": [[0,0],[1,1],[2,0],[3,1]])";
  file_error(R"({"id": "n", "kind": "nurbs", "degree": 2, "knots": [0,0,0,1,1,1], )" + points + "}",
             {"curves[0] (id \"n\")", "knots: 6 knots for 4 points of degree 2"});
  file_error(R"({"id": "n", "kind": "nurbs", "degree": 2, "knots": [0,0,0,2,1,1,1], )" + points + "}",
             {"curves[0] (id \"n\")", "knots[4]", "must not decrease"});
  file_error(R"({"id": "n", "kind": "nurbs", "degree": 2, "knots": [0,0,0,1,2,2,2], "weights": [1,1,0,1], )" + points + "}",
             {"curves[0] (id \"n\")", "weights[2]", "not positive"});
  file_error(R"({"id": "n", "kind": "nurbs", "degree": 2.5, "knots": [0,0,0,1,2,2,2], )" + points + "}",
             {"curves[0] (id \"n\")", "degree: expected an integer"});
  file_error(R"({"id": "c", "kind": "composite", "curves": [
                  {"kind": "bezier", "points": [[0,0],[1,0]]}, {"kind": "bezier", "points": [[1,0.5],[2,0]]}]})",
             {"curves[0] (id \"c\")", "curves[1]: starts at (1, 0.5) but curves[0] ends at (1, 0)"});
  file_error(R"({"id": "c", "kind": "composite", "curves": [{"kind": "composite", "curves": []}]})",
             {"curves[0] (id \"c\")", "curves[0]", "composite inside a composite"});
  file_error(R"({"id": "c", "kind": "composite", "curves": [{"kind": "bezier", "points": [[0,0],[1,0]], "knots": [1]}]})",
             {"curves[0] (id \"c\")", "curves[0]", "knots: not a field of kind \"bezier\""});
  file_error(R"({"id": "c", "kind": "composite", "curves": [
                  {"kind": "bezier", "points": [[0,0],[1,0]]}, {"kind": "bezier", "points": [[1,0,0],[2,0,0]]}]})",
             {"curves[0] (id \"c\")", "curves[1]: a space curve, but curves[0] is a plane curve"});
}

}  // namespace nurbs_tests
}  // namespace bezinv
