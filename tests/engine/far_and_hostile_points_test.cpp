// Curves far from the origin (translated by up to 1e12, map coordinates), curves of huge and tiny
// size (control points near 1e154 and 1e-154), and finite points up to the largest double. The
// answers must not depend on where the curve sits, and a finite point must never be refused: far
// points are off_curve at the nearest point of the segment, with its distance. Points on the curve
// are made from a known t by exact evaluation of the curve as given; distances to the segment come
// from dense sampling in long double (tests/support/known_parameter.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "support/curve_kinds.hpp"
#include "bezinv/bernstein.hpp"
#include "bezinv/curve.hpp"
#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/datasets/translation.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "support/exact.hpp"
#include "support/known_parameter.hpp"
#include "support/sanitizers.hpp"

namespace bezinv {
namespace {

using test_support::kAllKinds;

using test_support::ExactCurve;
using test_support::expect_known;
using test_support::Findings;
using test_support::kEps;
using test_support::known_at;
using test_support::KnownParameter;

constexpr double kLargest = std::numeric_limits<double>::max();

// The curve scaled by s (every coordinate; rounded once per coefficient).
Curve scaled(Curve c, double s) {
  for (double& v : c.x_num) v *= s;
  for (double& v : c.y_num) v *= s;
  return c;
}

// ---- 7. far from the origin ----------------------------------------------------------------------

// For a curve at distance D of size L: the point's own rounding is half an ulp of D, the curve's
// coefficients were rounded at D too (translated in double), and the engine evaluates relative to
// the centre: residual <= 8 eps D + (8 + n) eps L, and t within that over |P'|.
double far_residual_bound(const ExactCurve& curve, Point p) {
  return 8 * kEps * std::max(std::abs(p.x), std::abs(p.y)) + (8 + curve.degree()) * kEps * curve.diagonal();
}

// The distance from p to the curve near P(t) across it: the component of p - P(t) normal to P'(t)
// (to second order the distance to the curve; p is within an ulp of P(t)).
double normal_distance(const ExactCurve& curve, const KnownParameter& k) {
  const auto q = curve.point(k.t);
  const long double dx = test_support::to_long_double(mpq_class(k.point.x) - q[0]);
  const long double dy = test_support::to_long_double(mpq_class(k.point.y) - q[1]);
  const auto d = curve.approximate_tangent(k.t);
  return static_cast<double>(std::abs(dx * d[1] - dy * d[0]) / std::hypot(d[0], d[1]));
}

// Random curves of every kind, degree 2..10, of size ~1 and ~1000, translated by (d, d) and
// (d, -5d), d = 1e3 .. 1e12; each point P(t) of the translated curve (as given, exactly) is
// answered at t, and its t agrees with the t of P(t) on the curve at the origin.
//
// The status. Rounded to double, P(t) lies up to half an ulp of the offset off the curve, and the
// engine's residual is itself good only to the bound rb (8 eps |P|: the coefficients as given are
// rounded at the offset's ulp). Against the default tolerance (1e-6 of the diagonal) the status is
// therefore decided only where the point's distance is clear of the tolerance by rb: ok where its
// distance plus rb is within it, off_curve where its normal distance minus rb exceeds it. In between
// (a unit curve beyond ~1e8, where an ulp of the coordinates is near the tolerance) ok, off_curve,
// or at an end outside_segment (the rounding may put the point beyond the end, along the
// extension) are all right, with t and the residual still within their bounds. Then again with a
// tolerance above the coordinates' rounding and rb (`--tol`), where every point must be ok.
TEST(OrdinaryFarAndHostile, TranslatedCurvesInvertAsAtTheOrigin) {
  Findings findings("translated by up to 1e12 (d,d), (d,-5d)"), agreement("translated: t as at the origin");
  Findings loose("translated, tolerance above the coordinates' rounding");
  int skipped_offsets = 0, curves = 0, must_be_ok = 0, must_be_off = 0, undecided = 0;
  for (CurveKind kind : kAllKinds)
    for (int n = 2; n <= 10; n += 2)
      for (double size : {1.0, 1000.0}) {
        const std::uint64_t seed = 100ULL * static_cast<int>(kind) + n + (size > 1 ? 50 : 0);
        std::mt19937_64 rng(seed);
        const Curve origin =
            scaled(datasets::random_curve(kind, n, rng, datasets::ControlPolygon::perturbed_arc), size);
        const ExactCurve exact_origin(origin);
        const InversionPlan origin_plan = make_plan(origin);
        std::vector<double> parameters{0.0, 1.0, 0.5};
        for (int i = 0; i < 4; ++i) parameters.push_back(datasets::uniform(rng, 0.0, 1.0));
        for (int e = 3; e <= 12; ++e)
          for (double y_factor : {1.0, -5.0}) {
            // Under the sanitizers a quarter of the offsets, a different quarter for each curve, so
            // that every offset is still tried (support/sanitizers.hpp).
            if (test_support::thinned_out(static_cast<std::size_t>(e + n + static_cast<int>(kind)))) continue;
            const double d = std::pow(10.0, e);
            // Below ~1e4 ulps of the offset the curve's shape is no longer resolved by its own
            // coordinates (a unit curve at 5e12 is 1000 ulps wide): left out.
            if (exact_origin.diagonal() < 1e4 * kEps * std::max(1.0, std::abs(y_factor)) * d) {
              ++skipped_offsets;
              continue;
            }
            const Curve curve = datasets::translated(origin, d, y_factor * d);
            const ExactCurve exact(curve);
            const InversionPlan plan = make_plan(curve);
            std::ostringstream name;
            name << to_string(kind) << " degree " << n << " size " << size << " at (" << d << ", " << y_factor * d
                 << "), seed " << seed;
            const double tolerance = kDefaultRelativeTolerance * exact.diagonal();
            for (double t : parameters) {
              const KnownParameter k = known_at(exact, t);
              const double rb = far_residual_bound(exact, k.point);
              const double tb = 2 * rb / k.speed + 4 * test_support::kUnit;
              const double off = exact.distance(t, k.point), normal = normal_distance(exact, k);
              const PointResult r = invert_point(plan, k.point);
              if (off + rb <= tolerance) {
                ++must_be_ok;
                expect_known(findings, name.str(), exact, k, r, {.dt_bound = tb, .residual_bound = rb});
              } else {
                const bool off_curve = normal - rb > tolerance;
                (off_curve ? must_be_off : undecided) += 1;
                findings.count();
                const auto what = [&] {
                  std::ostringstream s;
                  s << name.str() << ": point " << off << " off the curve (" << normal << " across it), tolerance "
                    << tolerance << ", bound " << rb << ": " << test_support::describe(k, r);
                  return s.str();
                };
                const bool at_end = t == 0 || t == 1;
                findings.check(off_curve ? r.status == Status::off_curve
                                         : r.status == Status::ok || r.status == Status::off_curve ||
                                               (at_end && r.status == Status::outside_segment),
                               what);
                findings.check(std::abs(r.t - t) <= tb && r.t >= -tb && r.t <= 1 + tb, what);
                findings.check(r.residual <= off + rb && exact.distance(r.t, k.point) <= off + rb, what);
              }
              // With the tolerance over twice the accuracy bound, every point is on the curve.
              const double relative = kDefaultRelativeTolerance + 2 * rb / exact.diagonal();
              expect_known(loose, name.str() + " tolerance " + std::to_string(relative), exact, k,
                           invert_point(plan, k.point, {.relative_tolerance = relative}),
                           {.dt_bound = tb, .residual_bound = rb});
              const KnownParameter k0 = known_at(exact_origin, t);
              const PointResult r0 = invert_point(origin_plan, k0.point);
              agreement.count();
              const double bound = tb + test_support::parameter_bound(exact_origin, k0);
              agreement.measure(std::abs(r.t - r0.t) / bound, 0);
              agreement.check(std::abs(r.t - r0.t) <= bound, [&] {
                std::ostringstream s;
                s.precision(17);
                s << name.str() << ": t " << r.t << " far, " << r0.t << " at the origin (bound " << bound << ")";
                return s.str();
              });
            }
            ++curves;
          }
      }
  std::printf(
      "[ measured ] %d translated curves, %d offsets left out (curve below 1e4 ulps of the offset); at the "
      "default tolerance %d points must be ok, %d off_curve, %d undecided by the rounding\n",
      curves, skipped_offsets, must_be_ok, must_be_off, undecided);
  EXPECT_GT(must_be_ok, 1500 / test_support::kSanitizerThinning);
}

// Cubics of about one unit in map coordinates (easting ~5e5, northing ~5e6, metres), with a top
// power coefficient of 1e-4 (a gentle S-bend): the top term is 1e5 ulps of the coordinates, a real
// part of the shape that the engine must keep.
TEST(OrdinaryFarAndHostile, MapCoordinates) {
  Findings findings("map coordinates (5e5, 5e6), 1-unit cubics"), agreement("map coordinates: t as at the origin");
  for (int copy = 0; copy < 40; ++copy) {
    const std::uint64_t seed = 500 + copy;
    std::mt19937_64 rng(seed);
    const double easting = 5e5 + datasets::uniform(rng, -1e3, 1e3), northing = 5e6 + datasets::uniform(rng, -1e3, 1e3);
    exact::Poly x(4), y(4);  // power basis, local: x = a1 t + a2 t^2 + 1e-4 t^3
    x[0] = y[0] = 0;
    for (int k = 1; k <= 2; ++k) {
      x[k] = datasets::uniform(rng, -1.0, 1.0);
      y[k] = datasets::uniform(rng, -1.0, 1.0);
    }
    x[3] = copy % 2 ? 1e-4 : -1e-4;
    y[3] = copy % 3 ? 1e-4 : -1e-4;
    const exact::Poly bx = exact::bernstein_from_power(x, 3), by = exact::bernstein_from_power(y, 3);
    std::vector<std::array<double, 2>> far, local;
    for (int i = 0; i <= 3; ++i) {
      far.push_back(
          {exact::nearest_double(bx[i] + mpq_class(easting)), exact::nearest_double(by[i] + mpq_class(northing))});
      local.push_back({exact::nearest_double(bx[i]), exact::nearest_double(by[i])});
    }
    const Curve curve = Curve::bezier("map", far), origin = Curve::bezier("local", local);
    const ExactCurve exact(curve), exact_origin(origin);
    const InversionPlan plan = make_plan(curve), origin_plan = make_plan(origin);
    EXPECT_EQ(plan.degree(), 3) << "seed " << seed << ": the 1e-4 top term was dropped";
    const std::string name = "map cubic seed " + std::to_string(seed);
    std::vector<double> parameters{0.0, 1.0, 0.5};
    for (int i = 0; i < 8; ++i) parameters.push_back(datasets::uniform(rng, 0.0, 1.0));
    for (double t : parameters) {
      const KnownParameter k = known_at(exact, t);
      const PointResult r = invert_point(plan, k.point);
      const double rb = far_residual_bound(exact, k.point);
      const double tb = 2 * rb / k.speed + 4 * test_support::kUnit;
      expect_known(findings, name, exact, k, r, {.dt_bound = tb, .residual_bound = rb});
      const KnownParameter k0 = known_at(exact_origin, t);
      const PointResult r0 = invert_point(origin_plan, k0.point);
      agreement.count();
      const double bound = tb + test_support::parameter_bound(exact_origin, k0);
      agreement.measure(std::abs(r.t - r0.t) / bound, 0);
      agreement.check(std::abs(r.t - r0.t) <= bound, [&] {
        return name + ": t " + std::to_string(r.t) + " far, " + std::to_string(r0.t) + " at the origin";
      });
    }
  }
  EXPECT_GT(findings.points(), 400);
}

// ---- 8. huge and tiny curves, far points ---------------------------------------------------------

// Random curves of every kind, degree 2..12, scaled to control points near 1e154 and 1e-154 (whose
// squares are near the ends of the doubles' range): points at known t are ok, as at unit size.
// Found by tests/fuzz/fuzz_invert (corpus: largest_double_control_point.bin): a control point at
// the largest double made the tolerance's floor (4 ulps of the curve's largest coordinate) inf,
// the step above that double being inf, so every point was on the curve. The floor is 4 ulps of
// that binade, and the tolerance 1e-6 of the diagonal, as for any other curve.
TEST(OrdinaryFarAndHostile, AControlPointAtTheLargestDoubleKeepsAFiniteTolerance) {
  const double big = std::numeric_limits<double>::max();
  const InversionPlan plan = make_plan(Curve::bezier("edge", {{0, 0}, {big, 0}}));
  const PointResult on = invert_point(plan, {big / 2, big * 1e-9});
  EXPECT_EQ(on.status, Status::ok);
  EXPECT_NEAR(on.t, 0.5, 1e-12);
  // 1e-5 of the diagonal away: off the curve, at its foot.
  const PointResult off = invert_point(plan, {big / 4, big * 1e-5});
  EXPECT_EQ(off.status, Status::off_curve);
  EXPECT_NEAR(off.t, 0.25, 1e-12);
  EXPECT_NEAR(off.residual / big, 1e-5, 1e-12);
  const InversionPlan space = make_plan(Curve::space_bezier("edge", {{0, 0, 0}, {big, 0, 0}}));
  EXPECT_EQ(invert_point(space, Point3(big / 2, 0, big * 1e-9)).status, Status::ok);
  EXPECT_EQ(invert_point(space, Point3(big / 4, 0, big * 1e-5)).status, Status::off_curve);
}

// A curve far narrower than its coordinates resolve: 1e-300 wide (in y, or in z) at x = -DBL_MAX,
// where the doubles are 2e292 apart. Normalizing it by its own width made the coordinates'
// resolution overflow, so the tolerance was inf and every finite point on the curve (found by
// tests/fuzz/fuzz_invert). The curve is a point to within the resolution, 4 ulps of DBL_MAX: a
// point there is ok, one 8 ulps off is off_curve at that distance.
TEST(OrdinaryFarAndHostile, ACurveNarrowerThanItsCoordinatesResolveKeepsAFiniteTolerance) {
  const double big = std::numeric_limits<double>::max(), ulp = big - std::nextafter(big, 0.0);
  const InversionPlan plane = make_plan(Curve::bezier("sliver", {{-big, 0}, {-big, 1e-300}}));
  const InversionPlan space = make_plan(Curve::space_bezier("sliver", {{-big, 0, 0}, {-big, 0, 1e-300}}));
  for (const bool refine : {true, false}) {
    const InvertOptions options{.refine = refine};
    const PointResult on = invert_point(plane, {-big, 5e-301}, options);
    EXPECT_EQ(on.status, Status::ok) << on.reason;
    EXPECT_LE(on.residual, 4 * ulp);
    const PointResult off = invert_point(plane, {-big + 8 * ulp, 0}, options);
    EXPECT_EQ(off.status, Status::off_curve) << off.reason;
    EXPECT_EQ(off.residual, 8 * ulp);
    const PointResult on3 = invert_point(space, Point3(-big, 0, 5e-301), options);
    EXPECT_EQ(on3.status, Status::ok) << on3.reason;
    EXPECT_LE(on3.residual, 4 * ulp);
    const PointResult off3 = invert_point(space, Point3(-big + 8 * ulp, 0, 0), options);
    EXPECT_EQ(off3.status, Status::off_curve) << off3.reason;
    EXPECT_EQ(off3.residual, 8 * ulp);
  }
}

// A negative middle weight: the curve is sized by its segment (1e-300 long), its middle control
// point (1, 1) lies 1e300 of those units away, and the squares of that offset overflowed in the
// plan's rotation, which made every normalized coefficient NaN: every point, P(0) itself, was
// off_curve with residual 0 (found by tests/fuzz/fuzz_invert). Points made at known t are ok.
TEST(OrdinaryFarAndHostile, AControlPointFarOutsideATinySegmentKeepsThePlanFinite) {
  const double big = std::numeric_limits<double>::max();
  const Curve curve = Curve::rational_bezier("tiny", {{0, 0}, {1, 1}, {0, 1e-300}}, {big, -12.5, big});
  const InversionPlan plan = make_plan(curve);
  const double tolerance = 1e-6 * plan.diagonal();
  ASSERT_GT(plan.diagonal(), 0.0);
  for (const double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    const auto p = curve.point(t);
    const PointResult r = invert_point(plan, {p[0], p[1]});
    EXPECT_EQ(r.status, Status::ok) << "t " << t << ": " << r.reason;
    EXPECT_LE(r.residual, tolerance) << "t " << t;
  }
  const PointResult far = invert_point(plan, {1, 1});
  EXPECT_EQ(far.status, Status::off_curve);
  EXPECT_NEAR(far.residual, std::sqrt(2.0), 1e-12);
}

TEST(OrdinaryFarAndHostile, HugeAndTinyCurves) {
  Findings findings("control points near 1e154 and 1e-154");
  int skipped = 0;
  for (CurveKind kind : kAllKinds)
    for (int n = 2; n <= 12; n += 2)
      for (double s : {1e154, 3e153, 1e-154, 3e-155}) {
        const std::uint64_t seed = 300ULL + 100ULL * static_cast<int>(kind) + n;
        std::mt19937_64 rng(seed);
        const Curve curve = scaled(datasets::random_curve(kind, n, rng, datasets::ControlPolygon::perturbed_arc), s);
        const ExactCurve exact(curve);
        const datasets::CurveSampling sampling(curve, 32);
        const InversionPlan plan = make_plan(curve);
        std::ostringstream name;
        name << to_string(kind) << " degree " << n << " scaled by " << s << ", seed " << seed;
        std::vector<double> parameters{0.0, 1.0, 0.5};
        for (int i = 0; i < 5; ++i) parameters.push_back(datasets::uniform(rng, 0.0, 1.0));
        for (double t : parameters) {
          const KnownParameter k = known_at(exact, t);
          if (!test_support::isolated_on_segment(sampling, k.point, t, 1e-4 * exact.diagonal())) {
            ++skipped;  // another part of the segment is near: a double point would be right
            continue;
          }
          expect_known(findings, name.str(), exact, k, invert_point(plan, k.point));
        }
      }
  std::printf("[ measured ] %d points skipped (near another branch)\n", skipped);
  EXPECT_GT(findings.points(), 500);
}

// The distance from p to the segment: the smallest of the local minima of |P(t) - p| over a dense
// sample (long double), each refined by golden section within its neighbouring samples (the ends
// too: a minimum just inside an end is not a sampled one); long double's exponent range holds the
// squares of any doubles.
long double distance_to_segment(const ExactCurve& curve, Point p) {
  const int samples = 32 * curve.degree();
  auto distance = [&](long double t) {
    const auto q = curve.approximate_point(t);
    const long double dx = q[0] - p.x, dy = q[1] - p.y;
    return std::sqrt(dx * dx + dy * dy);
  };
  std::vector<long double> d(samples + 1);
  for (int k = 0; k <= samples; ++k) d[k] = distance(static_cast<long double>(k) / samples);
  long double best = std::min(d.front(), d.back());
  for (int k = 0; k <= samples; ++k) {
    // A strict decrease into k (flat runs, where the distance does not resolve the curve, are no minima).
    const bool left = k == 0 || d[k] < d[k - 1], right = k == samples || d[k] <= d[k + 1];
    if (!left || !right) continue;
    long double lo = static_cast<long double>(std::max(k - 1, 0)) / samples;
    long double hi = static_cast<long double>(std::min(k + 1, samples)) / samples;
    const long double g = (std::sqrt(5.0L) - 1) / 2;
    long double a = hi - g * (hi - lo), b = lo + g * (hi - lo), da = distance(a), db = distance(b);
    for (int i = 0; i < 80; ++i) {
      if (da < db) {
        hi = b;
        b = a;
        db = da;
        a = hi - g * (hi - lo);
        da = distance(a);
      } else {
        lo = a;
        a = b;
        da = db;
        b = lo + g * (hi - lo);
        db = distance(b);
      }
    }
    best = std::min({best, da, db});
  }
  return best;
}

// A point off the curve: off_curve, t on the segment, the residual the distance to the nearest
// point of the segment to 1e-12 relative (inf only when that distance is beyond the largest
// double), and the reported residual the exact distance at the reported t.
PointResult expect_far(Findings& findings, const std::string& name, const ExactCurve& exact, const InversionPlan& plan,
                       Point p) {
  findings.count();
  const PointResult r = invert_point(plan, p);
  const long double truth = distance_to_segment(exact, p);
  const auto what = [&] {
    std::ostringstream s;
    s.precision(17);
    s << name << ": point (" << p.x << ", " << p.y << "), distance " << static_cast<double>(truth) << " -> "
      << to_string(r.status) << ", t " << r.t << ", residual " << r.residual << ", path " << to_string(r.path)
      << (r.reason[0] ? ", reason: " : "") << r.reason;
    return s.str();
  };
  if (!findings.check(r.status == Status::off_curve, what)) return r;
  findings.check(r.t >= 0 && r.t <= 1, what);
  if (truth > kLargest) {
    findings.check(std::isinf(r.residual), what);
    return r;
  }
  findings.check(std::isfinite(r.residual), what);
  const long double relative = std::abs(r.residual - truth) / truth;
  findings.check(relative <= 1e-12L,
                 [&] { return what() + " (relative error " + std::to_string(static_cast<double>(relative)) + ")"; });
  const double at_t = exact.distance(r.t, p);
  findings.check(std::abs(at_t - r.residual) <= 1e-12 * at_t,
                 [&] { return what() + " (the distance at the reported t is " + std::to_string(at_t) + ")"; });
  findings.measure(0, static_cast<double>(relative / 1e-12L));
  return r;
}

// Finite points up to the largest double around unit, huge and tiny curves, and points at 1e2 ..
// 1e10 times the curve's size in random directions (there the nearest point still matters to
// 1e-12 of the distance).
TEST(OrdinaryFarAndHostile, FarPointsAreOffCurveAtTheNearestDistance) {
  Findings findings("far points (to 1.7e308)");
  const std::vector<Point> extreme{{1e200, 1e200},        {1e200, -1e200}, {1.7e308, 0},       {-1.7e308, 0},
                                   {0, 1.7e308},          {0, -1.7e308},   {1.7e308, 1.7e308}, {-1.7e308, 1.7e308},
                                   {kLargest, -kLargest}, {-kLargest, 0},  {1e300, 1e-300},    {-1e250, 1e308}};
  for (CurveKind kind : kAllKinds)
    for (int n : {2, 3, 5, 8, 13})
      for (double s : {1.0, 1e154, 1e-154, 1e300}) {
        const std::uint64_t seed = 600ULL + 100ULL * static_cast<int>(kind) + n;
        std::mt19937_64 rng(seed);
        const Curve curve = scaled(datasets::random_curve(kind, n, rng, datasets::ControlPolygon::perturbed_arc), s);
        const ExactCurve exact(curve);
        const InversionPlan plan = make_plan(curve);
        std::ostringstream name;
        name << to_string(kind) << " degree " << n << " scaled by " << s << ", seed " << seed;
        std::vector<Point> points;
        std::vector<PointResult> results;
        for (const Point& p : extreme) {
          points.push_back(p);
          results.push_back(expect_far(findings, name.str(), exact, plan, p));
        }
        const auto centre = exact.approximate_point(0.5L);
        for (int e = 2; e <= 10; e += 2) {
          const double angle = datasets::uniform(rng, 0.0, 6.283185307179586);
          const double radius = std::pow(10.0, e) * exact.diagonal();
          const Point p{static_cast<double>(centre[0]) + radius * std::cos(angle),
                        static_cast<double>(centre[1]) + radius * std::sin(angle)};
          if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
          points.push_back(p);
          results.push_back(expect_far(findings, name.str(), exact, plan, p));
        }
        test_support::expect_batched_as_single(findings, name.str(), plan, points, results);
      }
  EXPECT_GT(findings.points(), 900);
}

// A degree-13 Bezier curve 1.3 wide at x = -6.5e11, y = 1.1e8 (map coordinates in metres; found by
// `bezinv stress`, family `translated`): its x coordinates are resolved to 1.2e-4, a ten-thousandth
// of its size, and its top power coefficients (5 and 9 in the plan's units) are its own, but below
// the bound on what rounding leaves in an elevated curve's (~19 here). Reduced a degree on that
// test alone, the curve moved by 46-84 ulps of its coordinates, beyond the tolerance's floor of 4,
// and points on it were answered off_curve with a residual of 1.9e-3 where they are within 1e-4.
// Each point P(t), exact and rounded to doubles (so within half an ulp of the curve), must be ok at
// t, its residual the exact distance from the point to the curve at the answer's t (to the rounding
// of a curve of size 1: the engine works relative to its centre). Beside it a cubic at the same
// place, elevated in double to degree 13 as a CAD system would, must still be reduced to degree 3
// and invert the same way, its residual then to the reduction's change, within the 4 ulps of the
// coordinates that the tolerance's floor takes in (kResolutionUlps).
TEST(OrdinaryFarAndHostile, AHighDegreeCurveAtMapCoordinatesKeepsItsDegree) {
  using Polygon = std::vector<std::array<double, 2>>;
  const Polygon map_polygon = {
      {-648941687922.5154, 107826478.32723422},
      {-648941687922.5609, 107826478.38990588},
      {-648941687922.4658, 107826478.46142513},
      {-648941687922.5425, 107826478.73565365},
      {-648941687922.5577, 107826478.84681545},
      {-648941687922.6968, 107826478.82972407},
      {-648941687922.7762, 107826478.8709658},
      {-648941687922.9124, 107826479.03192131},
      {-648941687923.1357, 107826479.05661553},
      {-648941687923.2463, 107826478.93593836},
      {-648941687923.3499, 107826478.91143468},
      {-648941687923.3828, 107826478.76433915},
      {-648941687923.5088, 107826478.68955927},
      {-648941687923.5414, 107826478.47975317}};
  const Polygon cubic = {{-648941687922.5, 107826478.3},
                        {-648941687922.1, 107826479.3},
                        {-648941687921.6, 107826479.5},
                        {-648941687921.2, 107826478.4}};
  std::vector<double> x, y;
  for (const auto& p : cubic) x.push_back(p[0]), y.push_back(p[1]);
  while (x.size() < map_polygon.size()) {  // elevated in double, rounded at the coordinates' ulp
    std::vector<double> ex(x.size() + 1), ey(y.size() + 1);
    elevate_degree(x, ex);
    elevate_degree(y, ey);
    x = ex, y = ey;
  }
  Polygon elevated_polygon;
  for (std::size_t i = 0; i < x.size(); ++i) elevated_polygon.push_back({x[i], y[i]});
  const double ulp_x = 0x1p-13;  // of 6.5e11
  struct Case {
    Curve curve;
    int degree;
    double residual_bound;
  };
  for (const auto& [curve, degree, residual_bound] :
       {Case{Curve::bezier("map", map_polygon), 13, 1e-12},
        Case{Curve::bezier("elevated cubic", elevated_polygon), 3, kResolutionUlps * ulp_x}}) {
    const InversionPlan plan = make_plan(curve);
    EXPECT_EQ(plan.degree(), degree) << curve.id;
    const ExactCurve exact(curve);
    Findings findings(curve.id + " at x = -6.5e11");
    for (int i = 1; i < 100; ++i) {
      const double t = i / 100.0;
      const KnownParameter k = known_at(exact, t);
      const PointResult r = invert_point(plan, k.point);
      // The point is within half an ulp of P(t) in each coordinate: its nearest point within that
      // over the speed, twice over (and the plan's curve within residual_bound of the given one).
      const auto ulp = [](double v) {
        return std::nextafter(std::abs(v), std::numeric_limits<double>::infinity()) - std::abs(v);
      };
      const double rounding = std::hypot(0.5 * ulp(k.point.x), 0.5 * ulp(k.point.y));
      const double t_bound = (2 * rounding + residual_bound) / k.speed + 1e-12;
      findings.count();
      findings.check(r.status == Status::ok && std::abs(r.t - t) <= t_bound &&
                         std::abs(r.residual - exact.distance(r.t, k.point)) <= residual_bound,
                     [&] { return curve.id + ": " + test_support::describe(k, r); });
    }
  }
}

}  // namespace
}  // namespace bezinv
