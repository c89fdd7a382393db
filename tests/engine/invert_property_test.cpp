// Property tests of inversion through the public API (make_plan, invert_point, invert), on
// thousands of points whose answers are known by construction (datasets_gen): every kind, degrees
// 1..20, on the segment, at its ends, on its extension, off the curve along the normal, at
// constructed self-intersections, on degree-elevated, far-translated and improperly parametrized
// curves. Every failure message carries kind, degree, seed and t_true, so one run reproduces it.
//
// The accuracy model (the bounds every test uses, derived, not fitted):
//   A double point P0 = round(P(t_true)) is off the curve by <= u |P| (u = 2^-53), and evaluating
//   P(t) in double (de Casteljau, one division) errs by about n u scale, scale = KnownPoint::scale
//   (sum of the absolute terms; >= |P|, = (|1-t|+|t|)^n-amplified on the extension, ~|offset| for a
//   translated curve). Newton's method to full precision therefore lands within
//       e_P = kSlack (n + 1) u scale            of the curve (residual), and
//       e_t = e_P / |P'(t_true)| + 4 u max(1, |t|)   of t_true (the second term: its own stopping rule).
//   kSlack = 16 covers the normalization (centre, rotation, scale: a few more roundings per
//   coefficient); as the engine works relative to the centre of the control points, scale is at
//   least the diagonal (a point near the origin is not evaluated more accurately than one at the far
//   side of the curve). Where |P'| is tiny t is ill-conditioned and e_t grows with it, by
//   construction.
//   On top of the derived bounds, the fixed bounds hold wherever the data is of unit size:
//   residual <= 1e-12 diagonal and |t - t_true| <= 1e-8 whenever e_t <= 1e-9.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iomanip>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "support/bits.hpp"
#include "support/same_row.hpp"
#include "support/curve_kinds.hpp"
#include "bezinv/curve.hpp"
#include "plan_data.hpp"
#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/degree_elevation.hpp"
#include "bezinv/datasets/improper.hpp"
#include "bezinv/datasets/off_curve_points.hpp"
#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/paper_curves.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/datasets/self_intersection.hpp"
#include "bezinv/datasets/translation.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "isolation.hpp"
#include "pipeline/formula_path.hpp"
#include "support/sanitizers.hpp"

namespace bezinv {
namespace {

using test_support::same_bits;
using test_support::kAllKinds;

using datasets::ControlPolygon;
using datasets::CurveSampling;
using datasets::KnownPoint;

constexpr double kUnitRoundoff = 0x1p-53;
constexpr double kSlack = 16;
// The fixed bounds for data of unit size.
constexpr double kResidualRelative = 1e-12;
constexpr double kParameterError = 1e-8;
constexpr double kWellConditioned = 1e-9;  // e_t at most this: the fixed bound kParameterError applies

constexpr ControlPolygon kPolygons[] = {ControlPolygon::unit_square, ControlPolygon::perturbed_arc};

// ---- the cases -----------------------------------------------------------------------------------

struct Case {
  std::string name;  // kind, degree, polygon, seed (or the paper curve's id)
  int degree = 0;
  std::unique_ptr<CurveSampling> sampling;
  InversionPlan plan;
  std::uint64_t seed = 0;
};

std::uint64_t seed_of(CurveKind kind, int degree, ControlPolygon polygon, int salt) {
  return 1000003ULL * static_cast<std::uint64_t>(kind) + 1009ULL * static_cast<std::uint64_t>(degree) +
         101ULL * static_cast<std::uint64_t>(polygon) + static_cast<std::uint64_t>(salt);
}

std::string case_name(CurveKind kind, int degree, ControlPolygon polygon, std::uint64_t seed) {
  return std::string(to_string(kind)) + " degree " + std::to_string(degree) + " " + datasets::to_string(polygon) +
         " seed " + std::to_string(seed);
}

Case make_case(std::string name, Curve curve, std::uint64_t seed) {
  Case c;
  c.name = std::move(name);
  c.degree = curve.degree();
  c.seed = seed;
  c.plan = make_plan(curve);
  c.sampling = std::make_unique<CurveSampling>(std::move(curve));
  return c;
}

// Every kind x degree 1..20 x control polygon, plus the paper's curves and the default cubic.
// Built once (the dense sampling behind the point sets is the expensive part). Under the
// sanitizers one in kSanitizerThinning of the random ones (support/sanitizers.hpp), by kind +
// polygon + degree, so every degree is still met by some kind and polygon.
const std::vector<Case>& random_cases() {
  static const std::vector<Case> cases = [] {
    std::vector<Case> out;
    for (CurveKind kind : kAllKinds)
      for (int degree = 1; degree <= 20; ++degree)
        for (ControlPolygon polygon : kPolygons) {
          if (test_support::thinned_out(static_cast<std::size_t>(kind) + static_cast<std::size_t>(polygon) + degree))
            continue;
          const std::uint64_t seed = seed_of(kind, degree, polygon, 0);
          std::mt19937_64 rng(seed);
          out.push_back(make_case(case_name(kind, degree, polygon, seed),
                                  datasets::random_curve(kind, degree, rng, polygon), seed));
        }
    for (Curve c : {datasets::paper_example1_curve(), datasets::paper_example2_curve(),
                    datasets::paper_example4_curve(), datasets::default_cubic_curve()})
      out.push_back(make_case(c.id, c, 7));
    return out;
  }();
  return cases;
}

// ---- the accuracy model --------------------------------------------------------------------------

double residual_bound(const Case& c, const KnownPoint& k) {
  return kSlack * (c.degree + 1) * kUnitRoundoff * std::max(k.scale, c.plan.diagonal());
}

double parameter_bound(const Case& c, const KnownPoint& k) {
  return residual_bound(c, k) / k.speed + 4 * kUnitRoundoff * std::max(1.0, std::abs(k.t));
}

std::string describe(const Case& c, const KnownPoint& k, const PointResult& r) {
  std::ostringstream s;
  s.precision(17);
  s << c.name << ", t_true " << k.t;
  if (std::isfinite(k.t2)) s << ", t2_true " << k.t2;
  s << ", point (" << k.point.x << ", " << k.point.y << "), distance " << k.distance << ", speed " << k.speed
    << ", scale " << k.scale << " -> status " << to_string(r.status) << ", t " << r.t << ", t2 " << r.t2
    << ", residual " << r.residual << ", path " << to_string(r.path) << ", sigma_min " << r.sigma_min
    << ", sigma_next " << r.sigma_next << (r.reason[0] ? ", reason: " : "") << r.reason;
  return s.str();
}

// What a test measured, printed once at its end for the record (the bounds are asserted per point).
struct Measured {
  std::string what;
  int points = 0;
  double max_dt = 0;        // max |t - t_true|
  double max_dt_ratio = 0;  // max |t - t_true| / e_t
  double max_residual = 0;  // max |residual - distance| / diagonal
  void add(double dt, double ratio, double residual) {
    ++points;
    max_dt = std::max(max_dt, dt);
    max_dt_ratio = std::max(max_dt_ratio, ratio);
    max_residual = std::max(max_residual, residual);
  }
  ~Measured() {
    std::printf("[ measured ] %-34s %6d points  max|dt| %.2e  max|dt|/e_t %.3f  max|res-d|/diag %.2e\n",
                what.c_str(), points, max_dt, max_dt_ratio, max_residual);
  }
};

// A point on the curve (segment or extension): status, t and residual against the model.
void expect_on_curve(const Case& c, const KnownPoint& k, const PointResult& r, Status expected, Measured& m) {
  const double diagonal = c.plan.diagonal();
  ASSERT_EQ(r.status, expected) << describe(c, k, r);
  const double dt = std::abs(r.t - k.t);
  const double e_t = parameter_bound(c, k);
  EXPECT_LE(dt, e_t) << describe(c, k, r);
  if (e_t <= kWellConditioned) { EXPECT_LE(dt, kParameterError) << describe(c, k, r); }
  EXPECT_LE(r.residual, k.distance + residual_bound(c, k)) << describe(c, k, r);
  if (k.scale <= 4 * diagonal) { EXPECT_LE(r.residual, kResidualRelative * diagonal) << describe(c, k, r); }
  if (expected == Status::ok) { EXPECT_TRUE(r.t >= 0 && r.t <= 1) << describe(c, k, r); }
  if (expected == Status::outside_segment) { EXPECT_TRUE(r.t < 0 || r.t > 1) << describe(c, k, r); }
  m.add(dt, dt / e_t, std::abs(r.residual - k.distance) / diagonal);
}

// A point off the curve with a known nearest point of the segment.
void expect_nearest(const Case& c, const KnownPoint& k, const PointResult& r, Status expected, Measured& m) {
  const double diagonal = c.plan.diagonal();
  ASSERT_EQ(r.status, expected) << describe(c, k, r);
  const double dt = std::abs(r.t - k.t);
  // Near the nearest point the distance is flat to first order: the nearest-point condition
  // (P - P0) . P' = 0 has slope |P'|^2 (1 - kappa d) >= |P'|^2 / 2 (the generator keeps d below
  // half the radius of curvature), so t is found to 2 e_P / |P'| (plus its stopping rule), as on
  // the curve.
  const double e_t = 2 * parameter_bound(c, k);
  EXPECT_LE(dt, e_t) << describe(c, k, r);
  if (e_t <= kWellConditioned) { EXPECT_LE(dt, kParameterError) << describe(c, k, r); }
  // The residual is the distance to the nearest point: to 1e-9 relative, or to the rounding floor.
  const double floor = residual_bound(c, k);
  EXPECT_NEAR(r.residual, k.distance, 1e-9 * k.distance + floor) << describe(c, k, r);
  EXPECT_TRUE(r.t >= 0 && r.t <= 1) << describe(c, k, r);
  m.add(dt, dt / e_t, std::abs(r.residual - k.distance) / diagonal);
}

// ---- on the curve ----------------------------------------------------------------------------------

TEST(InvertProperty, OnTheSegment) {
  Measured m{"on the segment"};
  for (const Case& c : random_cases()) {
    std::mt19937_64 rng(c.seed + 1);
    const auto points = datasets::segment_points(*c.sampling, 16, rng);
    EXPECT_GE(points.size(), 12u) << c.name << ": the generator could not isolate enough points";
    for (const KnownPoint& k : points) expect_on_curve(c, k, invert_point(c.plan, k.point), Status::ok, m);
  }
  EXPECT_GT(m.points, 1500 / test_support::kSanitizerThinning);
}

TEST(InvertProperty, AtAndNearTheEnds) {
  Measured m{"ends (t = 0, 1e-12 .. 1)"};
  int exact_ends = 0, ends = 0;
  for (const Case& c : random_cases()) {
    for (const KnownPoint& k : datasets::end_points(*c.sampling)) {
      const PointResult r = invert_point(c.plan, k.point);
      expect_on_curve(c, k, r, Status::ok, m);
      if (k.t == 0.0 || k.t == 1.0) {
        ++ends;
        exact_ends += r.t == k.t;
      }
    }
  }
  std::printf("[ measured ] ends: t returned exactly 0 or 1 for %d of %d end points\n", exact_ends, ends);
  EXPECT_GT(m.points, 600 / test_support::kSanitizerThinning);
}

TEST(InvertProperty, OnTheExtension) {
  Measured m{"on the extension"};
  for (const Case& c : random_cases()) {
    std::mt19937_64 rng(c.seed + 2);
    for (const KnownPoint& k : datasets::extension_points(*c.sampling, 6, rng))
      expect_on_curve(c, k, invert_point(c.plan, k.point), Status::outside_segment, m);
  }
  EXPECT_GT(m.points, 400 / test_support::kSanitizerThinning);
}

// ---- off the curve ---------------------------------------------------------------------------------

TEST(InvertProperty, OffTheCurveAlongTheNormal) {
  Measured m{"off the curve (d >= 1e-5 diag)"};
  for (const Case& c : random_cases()) {
    std::mt19937_64 rng(c.seed + 3);
    // d from 10x the tolerance to 10% of the diagonal.
    const auto points = datasets::normal_offset_points(*c.sampling, 8, 10 * kDefaultRelativeTolerance, 0.1, rng);
    for (const KnownPoint& k : points) expect_nearest(c, k, invert_point(c.plan, k.point), Status::off_curve, m);
  }
  EXPECT_GT(m.points, 600 / test_support::kSanitizerThinning);
}

TEST(InvertProperty, WithinToleranceOfTheCurve) {
  Measured m{"within tolerance (d = 0.3 tol)"};
  for (const Case& c : random_cases()) {
    std::mt19937_64 rng(c.seed + 4);
    const double d = 0.3 * kDefaultRelativeTolerance;
    for (const KnownPoint& k : datasets::normal_offset_points(*c.sampling, 4, d, d, rng))
      expect_nearest(c, k, invert_point(c.plan, k.point), Status::ok, m);
  }
  EXPECT_GT(m.points, 300 / test_support::kSanitizerThinning);
}

// ---- self-intersections ----------------------------------------------------------------------------

TEST(InvertProperty, ConstructedSelfIntersections) {
  Measured m{"double points (t and t2)"};
  for (CurveKind kind : kAllKinds)
    for (int degree = 3; degree <= 20; ++degree) {
      const std::uint64_t seed = seed_of(kind, degree, ControlPolygon::unit_square, 5);
      std::mt19937_64 rng(seed);
      const double t1 = datasets::uniform(rng, 0.05, 0.45), t2 = datasets::uniform(rng, 0.55, 0.95);
      Case c = make_case(case_name(kind, degree, ControlPolygon::unit_square, seed) + " crossing at " +
                             std::to_string(t1) + ", " + std::to_string(t2),
                         datasets::with_self_intersection(kind, degree, t1, t2, rng), seed);
      // The crossing itself, then points 0.3 tol away from it: within tolerance of both branches.
      const auto points = datasets::crossing_points(*c.sampling, t1, t2, 4, 0.3 * kDefaultRelativeTolerance, rng);
      ASSERT_GE(points.size(), 3u) << c.name;
      for (const KnownPoint& k : points) {
        const PointResult r = invert_point(c.plan, k.point);
        ASSERT_EQ(r.status, Status::double_point) << describe(c, k, r);
        const double e_t = 2 * parameter_bound(c, k);
        const double dt = std::max(std::abs(r.t - k.t), std::abs(r.t2 - k.t2));
        EXPECT_LE(dt, e_t) << describe(c, k, r);
        if (e_t <= kWellConditioned) { EXPECT_LE(dt, kParameterError) << describe(c, k, r); }
        EXPECT_LT(r.t, r.t2) << describe(c, k, r);
        m.add(dt, dt / e_t, 0);
      }
    }
}

// ---- equivalent curves -----------------------------------------------------------------------------

TEST(InvertProperty, DegreeElevatedCurvesReduceAndInvertAsWell) {
  Measured m{"degree-elevated"};
  for (CurveKind kind : kAllKinds)
    for (int degree = 1; degree <= 15; ++degree)
      for (int times : {1, 2, 4}) {
        const std::uint64_t seed = seed_of(kind, degree, ControlPolygon::perturbed_arc, 10 + times);
        std::mt19937_64 rng(seed);
        const Curve original = datasets::random_curve(kind, degree, rng, ControlPolygon::perturbed_arc);
        Case c = make_case(case_name(kind, degree, ControlPolygon::perturbed_arc, seed) + " elevated " +
                               std::to_string(times) + "x",
                           datasets::degree_elevated(original, times), seed);
        ASSERT_EQ(c.plan.input_degree(), degree + times) << c.name;
        EXPECT_EQ(c.plan.degree(), degree) << c.name;
        // Accuracy as for the original: the model uses the original degree.
        c.degree = degree;
        for (const KnownPoint& k : datasets::segment_points(*c.sampling, 6, rng))
          expect_on_curve(c, k, invert_point(c.plan, k.point), Status::ok, m);
      }
}

TEST(InvertProperty, TranslatedFarFromTheOrigin) {
  Measured on{"translated ~(1e6,-1e6): on segment"}, off{"translated ~(1e6,-1e6): off curve"};
  for (CurveKind kind : kAllKinds)
    for (int degree = 1; degree <= 20; ++degree) {
      const std::uint64_t seed = seed_of(kind, degree, ControlPolygon::perturbed_arc, 20);
      std::mt19937_64 rng(seed);
      const Curve original = datasets::random_curve(kind, degree, rng, ControlPolygon::perturbed_arc);
      const double dx = 1e6 + datasets::uniform(rng, 0, 1), dy = -1e6 - datasets::uniform(rng, 0, 1);
      const Case c = make_case(case_name(kind, degree, ControlPolygon::perturbed_arc, seed) + " translated",
                               datasets::translated(original, dx, dy), seed);
      for (const KnownPoint& k : datasets::segment_points(*c.sampling, 8, rng))
        expect_on_curve(c, k, invert_point(c.plan, k.point), Status::ok, on);
      // Offsets from 1e-4 diagonal: the coordinates themselves are quantized at 1.2e-10 here.
      for (const KnownPoint& k : datasets::normal_offset_points(*c.sampling, 4, 1e-4, 0.1, rng))
        expect_nearest(c, k, invert_point(c.plan, k.point), Status::off_curve, off);
    }
}

// ---- improper parametrizations ---------------------------------------------------------------------

// Every point of Q(t^2) has the parameters t and -t: the Bezout matrix has nullity 2 on the whole
// curve, and both come from its two-dimensional null space. Only t is on the segment: ok there,
// at t. Points off the curve get the nearest point of the segment, as on any curve.
TEST(InvertProperty, ImproperCurvesAnswerEachPointAtItsParameterOnTheSegment) {
  Measured on{"improper Q(t^2): on segment"}, off{"improper Q(t^2): off curve"};
  int rows = 0;
  for (CurveKind kind : kAllKinds)
    for (int m = 1; m <= 10; ++m) {
      const std::uint64_t seed = seed_of(kind, m, ControlPolygon::perturbed_arc, 30);
      std::mt19937_64 rng(seed);
      const Curve q = datasets::random_curve(kind, m, rng, ControlPolygon::perturbed_arc);
      const Case c = make_case(case_name(kind, m, ControlPolygon::perturbed_arc, seed) + " as Q(t^2), degree " +
                                   std::to_string(2 * m),
                               datasets::improper(q), seed);
      ASSERT_TRUE(c.plan.usable()) << c.name << ": " << c.plan.reason();
      // Away from t = 0, where P'(0) = 0 and t is known only to the square root of the rounding.
      // (Not datasets::segment_points: its isolation check refuses every point here, since the
      // extension retraces the segment.)
      for (int i = 0; i < 8; ++i) {
        const KnownPoint k = datasets::known_on_curve(c.sampling->curve(), datasets::uniform(rng, 0.05, 1.0));
        expect_on_curve(c, k, invert_point(c.plan, k.point), Status::ok, on);
        ++rows;
      }
      for (const KnownPoint& k : datasets::normal_offset_points(*c.sampling, 4, 1e-3, 0.05, rng)) {
        if (k.t < 0.05) continue;
        expect_nearest(c, k, invert_point(c.plan, k.point), Status::off_curve, off);
        ++rows;
      }
    }
  EXPECT_GT(rows, 3 * 10 * 8);
}

// ---- the batched engine ----------------------------------------------------------------------------


TEST(InvertProperty, BatchedEqualsSinglePointBitForBit) {
  // Every fourth random case, with a mix of every kind of point (on, ends, extension, off, near).
  std::vector<const Case*> cases;
  std::vector<InversionPlan> plans;
  std::vector<int> curve_of;
  std::vector<Point> all_points;
  std::vector<double> all_t;
  int case_index = 0;
  for (const Case& c : random_cases()) {
    if (case_index++ % 4 != 0) continue;
    std::mt19937_64 rng(c.seed + 6);
    std::vector<KnownPoint> points = datasets::segment_points(*c.sampling, 40, rng);
    for (const auto& set : {datasets::end_points(*c.sampling), datasets::extension_points(*c.sampling, 10, rng),
                            datasets::normal_offset_points(*c.sampling, 10, 1e-7, 0.1, rng)})
      points.insert(points.end(), set.begin(), set.end());
    std::vector<Point> xy;
    for (const KnownPoint& k : points) xy.push_back(k.point);
    xy.push_back({PointResult::nan, 1.0});  // invalid_input
    std::vector<PointResult> single(xy.size());
    for (std::size_t i = 0; i < xy.size(); ++i) single[i] = invert_point(c.plan, xy[i]);
    for (int threads : {1, 2}) {
      std::vector<PointResult> batched(xy.size());
      invert(c.plan, xy, batched, {.threads = threads});
      for (std::size_t i = 0; i < xy.size(); ++i)
        EXPECT_TRUE(test_support::same_row(batched[i], single[i]))
            << c.name << ", threads " << threads << ", point " << i << " t_true "
            << (i < points.size() ? points[i].t : PointResult::nan);
    }
    cases.push_back(&c);
    plans.push_back(c.plan);
    for (std::size_t i = 0; i < xy.size(); ++i) {
      curve_of.push_back(static_cast<int>(plans.size()) - 1);
      all_points.push_back(xy[i]);
      all_t.push_back(i < points.size() ? points[i].t : PointResult::nan);
    }
  }
  // The many-curve overload: interleaved rows (runs of one or two, inverted in parallel with each
  // other), then the rows grouped by curve behind one run long enough for its batches to run in
  // parallel; rows the I/O layer rejected (curve_of < 0) are left exactly as the caller set them.
  std::mt19937_64 shuffle(99);
  std::vector<std::size_t> interleaved(all_points.size()), grouped;
  for (std::size_t i = 0; i < interleaved.size(); ++i) interleaved[i] = i;
  std::shuffle(interleaved.begin(), interleaved.end(), shuffle);
  for (int copy = 0; grouped.size() < 1000; ++copy)  // the first case's rows, again and again
    for (std::size_t i = 0; i < all_points.size() && curve_of[i] == 0; ++i) grouped.push_back(i);
  for (std::size_t i = 0; i < all_points.size(); ++i) grouped.push_back(i);
  PointResult untouched;
  untouched.status = Status::invalid_input;
  untouched.reason = "set by the caller";
  for (const std::vector<std::size_t>* order : {&interleaved, &grouped}) {
    std::vector<int> curves(order->size());
    std::vector<Point> points(order->size());
    for (std::size_t i = 0; i < order->size(); ++i) {
      const bool rejected = i % 97 == 0 && (order == &interleaved || i > grouped.size() / 2);  // not in the long run
      curves[i] = rejected ? -1 : curve_of[(*order)[i]];
      points[i] = all_points[(*order)[i]];
    }
    for (int threads : {1, 2}) {
      std::vector<PointResult> results(points.size(), untouched);
      invert(plans, curves, points, results, {.threads = threads});
      for (std::size_t i = 0; i < points.size(); ++i) {
        const PointResult expected = curves[i] < 0 ? untouched : invert_point(plans[curves[i]], points[i]);
        EXPECT_TRUE(test_support::same_row(results[i], expected))
            << (curves[i] < 0 ? std::string("rejected row") : cases[curves[i]]->name) << ", threads " << threads
            << ", row " << i << " t_true " << all_t[(*order)[i]];
      }
    }
    EXPECT_GT(points.size(), 1000u / test_support::kSanitizerThinning);
  }
}

// ---- the fast path (LU null vector) against the SVD path -------------------------------------------

// Every kind of point on every random case, and the constructed crossings: the fast path may answer
// a row only when the SVD path gives the same status, and then the same t up to Newton's own
// rounding. Both routes refine to the same root of f(t) = (P(t) - P0) . P'(t) from seeds that differ
// by ~1e-13, so the last iterates may differ by the rounding of f near the root: the accuracy
// model's parameter_bound, not bit equality.
// Many batches with a few SVD-path lanes each (points off the curve among points on it): those
// lanes wait in the engine's per-thread queue across batches (invert.cpp, SvdQueue) and are run
// with other batches' lanes, yet each answer is the one invert_point gives, for any thread count.
TEST(InvertProperty, QueuedSvdLanesAnswerAsAlone) {
  int ran = 0;
  constexpr int kCases = test_support::kSanitizerThinning > 1 ? 2 : 6;
  for (const Case& c : random_cases()) {
    if (c.plan.degree() < 3 || c.plan.degree() > 16) continue;
    if (ran++ == kCases) break;
    std::mt19937_64 rng(c.seed + 11);
    const std::vector<KnownPoint> on = datasets::segment_points(*c.sampling, 1500, rng);
    const std::vector<KnownPoint> off = datasets::normal_offset_points(*c.sampling, 60, 1e-3, 0.1, rng);
    std::vector<Point> xy;
    for (std::size_t i = 0; i < on.size(); ++i) {
      xy.push_back(on[i].point);
      if (i % 25 == 0 && i / 25 < off.size()) xy.push_back(off[i / 25].point);  // ~2.5 per batch
    }
    std::vector<PointResult> single(xy.size());
    std::size_t svd_lanes = 0;
    for (std::size_t i = 0; i < xy.size(); ++i) {
      single[i] = invert_point(c.plan, xy[i]);
      svd_lanes += single[i].path != Path::bezout_lu;
    }
    EXPECT_GE(svd_lanes, 40u) << c.name << ": the test needs lanes on the SVD path";
    for (int threads : {1, 2}) {
      std::vector<PointResult> batched(xy.size());
      invert(c.plan, xy, batched, {.threads = threads});
      for (std::size_t i = 0; i < xy.size(); ++i)
        EXPECT_TRUE(test_support::same_row(batched[i], single[i])) << c.name << ", threads " << threads << ", point " << i;
    }
  }
  EXPECT_EQ(ran, kCases + 1);  // kCases ran (the next one ended the loop)
}

// A row the off-curve path answered by distance alone (off_curve_path.hpp): path nearest, no
// singular values.
bool by_distance(const PointResult& r) {
  return r.status == Status::off_curve && r.path == Path::nearest && std::isnan(r.sigma_min) && std::isnan(r.sigma_next);
}

// The off-curve path's row against the SVD path's: a nearest point of the segment as near as the
// SVD path's, to the rounding of evaluating the curve (64 ulps of its size, `diagonal`, or of the
// distance if larger). Usually
// the same point (t equal but for Newton's last bits from different starts); where another
// parameter is as near (a point on an axis of symmetry) either is the answer.
::testing::AssertionResult same_nearest_point(const PointResult& distance_row, const PointResult& svd, double diagonal) {
  if (svd.status != Status::off_curve || svd.path != Path::nearest)
    return ::testing::AssertionFailure() << "the SVD path answered " << to_string(svd.status) << " by " << to_string(svd.path);
  const double rounding = 64 * std::numeric_limits<double>::epsilon() * std::max(diagonal, svd.residual);
  if (std::abs(distance_row.residual - svd.residual) <= rounding) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << std::setprecision(17) << "by distance t " << distance_row.t << " residual "
                                       << distance_row.residual << ", SVD path t " << svd.t << " residual " << svd.residual;
}

TEST(InvertProperty, FastPathAgreesWithTheSvdPath) {
  Measured m{"fast path vs SVD path (same rows)"};
  const InvertOptions svd_only{.fast_path = false};
  std::size_t fast_rows = 0, distance_rows = 0, rows = 0, certified_rows = 0, gap_rows = 0;
  std::size_t double_points = 0, near_crossing = 0, near_crossing_double = 0;
  double worst_over = 0;  // sigma_next estimate / the SVD's sigma_{n-1}/sigma_1 (>= the over-estimate)
  auto compare = [&](const Case& c, const KnownPoint& k, double tolerance = kDefaultRelativeTolerance) {
    // The Bezout fast path (the default takes the formula path on cubics: compared with this one below).
    const PointResult fast =
        invert_point(c.plan, k.point, {.relative_tolerance = tolerance, .algebraic = Algebraic::bezout});
    InvertOptions svd_options = svd_only;
    svd_options.relative_tolerance = tolerance;
    const PointResult svd = invert_point(c.plan, k.point, svd_options);
    ++rows;
    double_points += svd.status == Status::double_point;
    EXPECT_NE(svd.path, Path::bezout_lu) << describe(c, k, svd);
    ASSERT_EQ(fast.status, svd.status) << "fast: " << describe(c, k, fast) << "\nsvd: " << describe(c, k, svd);
    if (by_distance(fast)) {
      ++distance_rows;
      EXPECT_TRUE(same_nearest_point(fast, svd, c.plan.diagonal())) << describe(c, k, fast);
      return;
    }
    if (fast.path != Path::bezout_lu) {
      EXPECT_TRUE(test_support::same_row(fast, svd)) << c.name;  // not answered by the fast path: the SVD path's row
      return;
    }
    ++fast_rows;
    // On the curve, or off it where the isolation certificate says the SVD path's nearest-point
    // search can only find the fast path's own parameter: the same stationary point of the distance.
    EXPECT_EQ(fast.status, Status::ok) << describe(c, k, fast);
    EXPECT_EQ(svd.path, Path::bezout) << describe(c, k, svd);
    const double dt = std::abs(fast.t - svd.t);
    EXPECT_LE(dt, 2 * parameter_bound(c, k)) << "fast: " << describe(c, k, fast) << "\nsvd: " << describe(c, k, svd);
    EXPECT_LE(std::abs(fast.residual - svd.residual), residual_bound(c, k)) << describe(c, k, fast);
    // No gap estimate exactly where the isolation certificate decided (degree >= 3, on the segment):
    // no other parameter of the segment is within the tolerance, so the SVD path's search for one,
    // wherever its sigma_{n-1} sent it there, found none (the statuses agree above).
    const auto p0 = bezinv::detail::plan_data(c.plan).normalize(k.point.x, k.point.y);
    const bool certified = c.plan.degree() >= 3 && fast.status == Status::ok &&
                           detail::isolated(bezinv::detail::plan_data(c.plan), p0[0], p0[1], fast.t, fast.residual / bezinv::detail::plan_data(c.plan).scale,
                                            tolerance * c.plan.diagonal() / bezinv::detail::plan_data(c.plan).scale);
    EXPECT_EQ(std::isnan(fast.sigma_next), certified) << describe(c, k, fast);
    if (certified) {
      ++certified_rows;
      m.add(dt, dt / parameter_bound(c, k), std::abs(fast.residual - svd.residual) / c.plan.diagonal());
      return;
    }
    ++gap_rows;
    // The evidence: the sigma_{n-1} estimate is from above and relative to ||B||_F >= sigma_1; when
    // it cleared kFastPathGapRatio the SVD path did not look for a second parameter either.
    worst_over = std::max(worst_over, fast.sigma_next / svd.sigma_next);
    if (fast.sigma_next >= kFastPathGapRatio) {
      EXPECT_GT(svd.sigma_next, kSecondNullDirectionRatio) << describe(c, k, svd);
    }
    // Within the factor the gate allows for (tolerances.hpp, kFastPathGapRatio), with a margin.
    EXPECT_LE(fast.sigma_next, 1.8 * svd.sigma_next) << describe(c, k, fast);
    m.add(dt, dt / parameter_bound(c, k), std::abs(fast.residual - svd.residual) / c.plan.diagonal());
  };
  for (const Case& c : random_cases()) {
    std::mt19937_64 rng(c.seed + 8);
    std::vector<KnownPoint> points = datasets::segment_points(*c.sampling, 24, rng);
    for (const auto& set : {datasets::end_points(*c.sampling), datasets::extension_points(*c.sampling, 6, rng),
                            datasets::normal_offset_points(*c.sampling, 6, 1e-7, 0.1, rng)})
      points.insert(points.end(), set.begin(), set.end());
    for (const KnownPoint& k : points) compare(c, k);
  }
  for (CurveKind kind : kAllKinds)
    for (int degree = 3; degree <= 12; ++degree) {
      const std::uint64_t seed = seed_of(kind, degree, ControlPolygon::unit_square, 9);
      std::mt19937_64 rng(seed);
      const double t1 = datasets::uniform(rng, 0.05, 0.45), t2 = datasets::uniform(rng, 0.55, 0.95);
      Case c = make_case(case_name(kind, degree, ControlPolygon::unit_square, seed) + " crossing",
                         datasets::with_self_intersection(kind, degree, t1, t2, rng), seed);
      for (const KnownPoint& k : datasets::crossing_points(*c.sampling, t1, t2, 4, 0.3 * kDefaultRelativeTolerance, rng))
        compare(c, k);
      // On branch 1 near the crossing, with a tolerance loose enough to reach branch 2: B has a
      // clear gap there (sigma_{n-1} ~ the distance to the crossing), so the fast path, not the
      // SVD, must look for the second parameter, find it and leave the row to the SVD path.
      for (double tolerance : {1e-3, 1e-2})
        for (double dt : {-3e-4, -1e-4, 1e-4, 3e-4}) {
          const KnownPoint k = datasets::known_on_curve(c.sampling->curve(), t1 + dt);
          const std::size_t before = double_points;
          compare(c, k, tolerance);
          near_crossing += 1;
          near_crossing_double += double_points - before;
        }
    }
  RecordProperty("fast_rows", static_cast<int>(fast_rows));
  RecordProperty("distance_rows", static_cast<int>(distance_rows));
  RecordProperty("certified_rows", static_cast<int>(certified_rows));
  RecordProperty("gap_rows", static_cast<int>(gap_rows));
  RecordProperty("rows", static_cast<int>(rows));
  std::printf("[ measured ] fast path answered %zu of %zu rows (%zu certified, without a gap), the off-curve path %zu; "
              "sigma_next estimate / SVD's at most %.3g over %zu rows\n",
              fast_rows, rows, certified_rows, distance_rows, worst_over, gap_rows);
  EXPECT_GT(fast_rows, rows / 5);  // the comparison is not vacuous
  EXPECT_GT(certified_rows, rows / 10);
  EXPECT_GT(gap_rows, 200u / test_support::kSanitizerThinning);  // 298 in Release
  EXPECT_GT(distance_rows, 40u);
  // ... and most on-branch points near a crossing are double points under those tolerances.
  EXPECT_GT(near_crossing_double, near_crossing / 2) << near_crossing_double << " of " << near_crossing;
}

// The formula path (InvertOptions::algebraic = formula): the inversion formula's N/M in place of
// B's null vector as the start, refined and certified the same way. Batched, on the same rows as
// FastPathAgreesWithTheSvdPath: the same status as the Bezout path on every row, t (and t2) within
// the accuracy bound, and the formula answering most on-curve rows of the degrees it covers. The
// default (automatic) gives the formula path's rows, bit for bit, on the plans it takes it for
// (cubics with one denominator and moderate weights) and the Bezout path's on the others.
TEST(InvertProperty, TheFormulaPathAnswersAsTheBezoutPath) {
  const InvertOptions bezout_options{.algebraic = Algebraic::bezout};
  const InvertOptions formula_options{.algebraic = Algebraic::formula};
  std::size_t rows = 0, formula_rows = 0, automatic_formula_rows = 0, cubic_rows = 0;
  auto compare = [&](const Case& c, const std::vector<KnownPoint>& known) {
    std::vector<Point> points;
    for (const KnownPoint& k : known) points.push_back(k.point);
    std::vector<PointResult> bezout(points.size()), formula(points.size()), automatic(points.size());
    invert(c.plan, points, bezout, bezout_options);
    invert(c.plan, points, formula, formula_options);
    invert(c.plan, points, automatic, {});
    const bool takes_formula = detail::takes_formula_path(detail::plan_data(c.plan), InvertOptions{});
    const bool cubic = c.degree == 3 && c.plan.curve().kind != CurveKind::rational;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const KnownPoint& k = known[i];
      ++rows;
      formula_rows += formula[i].path == Path::formula;
      automatic_formula_rows += cubic && automatic[i].path == Path::formula;
      cubic_rows += cubic;
      EXPECT_TRUE(test_support::same_row(automatic[i], takes_formula ? formula[i] : bezout[i]))
          << "automatic: " << describe(c, k, automatic[i]) << "\nformula path taken: " << takes_formula;
      ASSERT_EQ(formula[i].status, bezout[i].status)
          << "formula: " << describe(c, k, formula[i]) << "\nbezout: " << describe(c, k, bezout[i]);
      if (formula[i].path != Path::formula && formula[i].path != Path::bezout_lu &&
          bezout[i].path != Path::bezout_lu && !(formula[i].path == Path::nearest))
        continue;  // both by the SVD path from the same start: compared below anyway
      if (std::isnan(bezout[i].t)) {
        EXPECT_TRUE(std::isnan(formula[i].t)) << describe(c, k, formula[i]);
        continue;
      }
      const double bound = formula[i].status == Status::off_curve ? 1e-6 : 2 * parameter_bound(c, k);
      EXPECT_LE(std::abs(formula[i].t - bezout[i].t), bound)
          << "formula: " << describe(c, k, formula[i]) << "\nbezout: " << describe(c, k, bezout[i]);
      if (formula[i].status == Status::double_point) {
        EXPECT_LE(std::abs(formula[i].t2 - bezout[i].t2), bound) << describe(c, k, formula[i]);
      }
      if (formula[i].path == Path::formula) {
        EXPECT_EQ(formula[i].status, Status::ok) << describe(c, k, formula[i]);
        EXPECT_TRUE(std::isnan(formula[i].sigma_min)) << describe(c, k, formula[i]);  // no B formed
      }
    }
  };
  // Making a formula costs ~1 ms at degree 8 and ~80 ms at 20 (its SVD; seconds unoptimized under
  // the sanitizers): degrees up to 12 here (separate denominators, of twice the degree, up to 6),
  // up to 8 (4) under the sanitizers.
  const int max_degree = test_support::kSanitizerThinning > 1 ? 8 : 12;
  auto covered = [&](CurveKind kind, int degree) {
    return degree <= (kind == CurveKind::rational ? max_degree / 2 : max_degree);
  };
  for (const Case& c : random_cases()) {
    if (!covered(c.plan.curve().kind, c.degree)) continue;
    std::mt19937_64 rng(c.seed + 8);
    std::vector<KnownPoint> points = datasets::segment_points(*c.sampling, 24, rng);
    for (const auto& set : {datasets::end_points(*c.sampling), datasets::extension_points(*c.sampling, 6, rng),
                            datasets::normal_offset_points(*c.sampling, 6, 1e-7, 0.1, rng)})
      points.insert(points.end(), set.begin(), set.end());
    compare(c, points);
  }
  for (CurveKind kind : kAllKinds)
    for (int degree = 3; degree <= 12; ++degree) {
      if (!covered(kind, degree)) continue;
      const std::uint64_t seed = seed_of(kind, degree, ControlPolygon::unit_square, 9);
      std::mt19937_64 rng(seed);
      const double t1 = datasets::uniform(rng, 0.05, 0.45), t2 = datasets::uniform(rng, 0.55, 0.95);
      Case c = make_case(case_name(kind, degree, ControlPolygon::unit_square, seed) + " crossing",
                         datasets::with_self_intersection(kind, degree, t1, t2, rng), seed);
      compare(c, datasets::crossing_points(*c.sampling, t1, t2, 4, 0.3 * kDefaultRelativeTolerance, rng));
    }
  std::printf("[ measured ] the formula path answered %zu of %zu rows; by default %zu of %zu rows of cubics\n",
              formula_rows, rows, automatic_formula_rows, cubic_rows);
  EXPECT_GT(formula_rows, rows / 5);  // not vacuous
  EXPECT_GT(automatic_formula_rows, cubic_rows / 3);
}

// --off-curve projection changes no status and no row but off_curve ones, whose t becomes the
// inversion formula's projection N(P0)/M(P0) where the formula is valid at the point (else the nearest
// point as before): its residual is |P(t) - P0|, no nearer than the segment's nearest point where t
// is on the segment. With either algebraic step, on points on, near and off every kind of curve,
// loose tolerances included (the extension then often passes within them).
TEST(InvertProperty, ProjectionChangesOnlyTheOffCurveRowsParameter) {
  std::size_t rows = 0, projected = 0;
  const int max_degree = test_support::kSanitizerThinning > 1 ? 8 : 12;
  for (const Case& c : random_cases()) {
    if (c.degree > (c.plan.curve().kind == CurveKind::rational ? max_degree / 2 : max_degree)) continue;
    std::mt19937_64 rng(c.seed + 31);
    std::vector<KnownPoint> known = datasets::segment_points(*c.sampling, 6, rng);
    for (const auto& set : {datasets::extension_points(*c.sampling, 4, rng),
                            datasets::normal_offset_points(*c.sampling, 24, 1e-7, 0.3, rng)})
      known.insert(known.end(), set.begin(), set.end());
    std::vector<Point> points;
    for (const KnownPoint& k : known) points.push_back(k.point);
    for (Algebraic algebraic : {Algebraic::bezout, Algebraic::formula})
      for (double tolerance : {kDefaultRelativeTolerance, 3e-2}) {
        const InvertOptions nearest_options{.relative_tolerance = tolerance, .algebraic = algebraic};
        InvertOptions projection_options = nearest_options;
        projection_options.off_curve = OffCurve::projection;
        std::vector<PointResult> nearest(points.size()), projection(points.size());
        invert(c.plan, points, nearest, nearest_options);
        invert(c.plan, points, projection, projection_options);
        for (std::size_t i = 0; i < points.size(); ++i) {
          const PointResult &a = nearest[i], &b = projection[i];
          ++rows;
          ASSERT_EQ(b.status, a.status) << describe(c, known[i], b) << "\nnearest: " << describe(c, known[i], a);
          if (b.path != Path::projection) {
            EXPECT_TRUE(same_bits(a.t, b.t) && same_bits(a.t2, b.t2) && same_bits(a.residual, b.residual) &&
                        a.path == b.path && same_bits(a.sigma_min, b.sigma_min))
                << describe(c, known[i], b) << "\nnearest: " << describe(c, known[i], a);
            continue;
          }
          ++projected;
          ASSERT_EQ(b.status, Status::off_curve) << describe(c, known[i], b);
          ASSERT_TRUE(std::isfinite(b.t)) << describe(c, known[i], b);
          EXPECT_TRUE(std::isnan(b.t2) && std::isnan(b.sigma_min) && std::isnan(b.sigma_next));
          const auto p = c.plan.curve().point(b.t);
          const double d = std::hypot(p[0] - points[i].x, p[1] - points[i].y);
          EXPECT_NEAR(b.residual, d, 1e-9 * (d + c.plan.diagonal())) << describe(c, known[i], b);
          if (b.t >= 0.0 && b.t <= 1.0) {
            EXPECT_GE(b.residual, a.residual * (1 - 1e-9) - 1e-12 * c.plan.diagonal())
                << describe(c, known[i], b) << "\nnearest: " << describe(c, known[i], a);
          }
        }
      }
  }
  std::printf("[ measured ] %zu rows, %zu answered by projection\n", rows, projected);
  EXPECT_GT(projected, rows / 10);  // not vacuous
}

// --no-refine with the formula: t = N/M itself where it is within the tolerance of the segment
// and certified alone there (status ok, path formula, t within the formula's accuracy of the point's
// parameter); every other row exactly as --no-refine with bezout gives it.
TEST(InvertProperty, UnrefinedFormulaRowsAreNOverMOnTheCurve) {
  std::size_t rows = 0, formula_rows = 0;
  const int max_degree = test_support::kSanitizerThinning > 1 ? 8 : 12;
  for (const Case& c : random_cases()) {
    if (c.degree > (c.plan.curve().kind == CurveKind::rational ? max_degree / 2 : max_degree)) continue;
    std::mt19937_64 rng(c.seed + 32);
    std::vector<KnownPoint> known = datasets::segment_points(*c.sampling, 12, rng);
    const std::size_t on_segment = known.size();  // made at t_true, rounded to the nearest double
    for (const auto& set : {datasets::end_points(*c.sampling), datasets::extension_points(*c.sampling, 4, rng),
                            datasets::normal_offset_points(*c.sampling, 8, 1e-7, 0.1, rng)})
      known.insert(known.end(), set.begin(), set.end());
    std::vector<Point> points;
    for (const KnownPoint& k : known) points.push_back(k.point);
    std::vector<PointResult> bezout(points.size()), formula(points.size());
    invert(c.plan, points, bezout, {.refine = false});
    invert(c.plan, points, formula, {.refine = false, .algebraic = Algebraic::formula});
    const double tolerance = kDefaultRelativeTolerance * c.plan.diagonal();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const PointResult &a = bezout[i], &b = formula[i];
      const KnownPoint& k = known[i];
      ++rows;
      if (b.path != Path::formula) {
        EXPECT_TRUE(b.status == a.status && same_bits(a.t, b.t) && same_bits(a.t2, b.t2) &&
                    same_bits(a.residual, b.residual) && a.path == b.path)
            << describe(c, k, b) << "\nbezout: " << describe(c, k, a);
        continue;
      }
      ++formula_rows;
      EXPECT_EQ(b.status, Status::ok) << describe(c, k, b);
      EXPECT_TRUE(b.t >= 0.0 && b.t <= 1.0) << describe(c, k, b);
      EXPECT_LE(b.residual, tolerance) << describe(c, k, b);
      const auto p = c.plan.curve().point(b.t);
      EXPECT_NEAR(b.residual, std::hypot(p[0] - k.point.x, p[1] - k.point.y), 1e-9 * c.plan.diagonal());
      // A point made at t_true on the segment: N/M is t_true to the formula's accuracy
      // (kFormulaPathMaxSegmentError, with the point's rounding over the curve's speed).
      if (i < on_segment) {
        EXPECT_LE(std::abs(b.t - k.t), 2 * kFormulaPathMaxSegmentError + 1e3 * parameter_bound(c, k))
            << describe(c, k, b);
      }
    }
  }
  std::printf("[ measured ] %zu rows, %zu answered by N/M unrefined\n", rows, formula_rows);
  EXPECT_GT(formula_rows, rows / 4);  // not vacuous
}

// Off the curve, anywhere around curves that loop: the off-curve path answers without the SVD only
// what the SVD path answers, off_curve at the same nearest point of the segment. Points off a
// random t along the normal, up to a tenth of the curve's size: on these loops many have another
// branch nearer, and under the loose tolerances the extension often passes within the tolerance
// (outside_segment: the off-curve path must leave those to the SVD path).
TEST(InvertProperty, OffTheCurveAnswersWithoutTheSvdAreTheSvdPathsAnswers) {
  const InvertOptions svd_only{.fast_path = false};
  int fast_off_curve = 0, rows = 0, outside_segment = 0;
  for (CurveKind kind : kAllKinds)
    for (int degree = 2; degree <= 12; ++degree) {
      const std::uint64_t seed = seed_of(kind, degree, ControlPolygon::unit_square, 21);
      std::mt19937_64 rng(seed);
      const Curve curve = datasets::random_curve(kind, degree, rng, ControlPolygon::unit_square);
      const InversionPlan plan = make_plan(curve);
      // A quarter of the points under the sanitizers (support/sanitizers.hpp).
      for (int k = 0; k < 80 / test_support::kSanitizerThinning; ++k) {
        // Along the normal at a random t, 1e-4 to 1e-1 of the curve's size (log-uniform), either side.
        const double t = datasets::uniform(rng, 0.0, 1.0);
        const Point on = datasets::on_curve(curve, t), ahead = datasets::on_curve(curve, t + 1e-6);
        const double tx = ahead.x - on.x, ty = ahead.y - on.y, length = std::hypot(tx, ty);
        const double off = std::copysign(std::pow(10.0, datasets::uniform(rng, -4.0, -1.0)), datasets::uniform(rng, -1.0, 1.0)) *
                           plan.diagonal();
        const Point p{on.x - off * ty / length, on.y + off * tx / length};
        // The default tolerance, and loose ones under which the curve's extension (the SVD path's
        // second-parameter candidates walk along it) often comes within the tolerance.
        for (double tolerance : {kDefaultRelativeTolerance, 3e-2, 1e-1}) {
          InvertOptions svd_options = svd_only;
          svd_options.relative_tolerance = tolerance;
          const PointResult fast = invert_point(plan, p, {.relative_tolerance = tolerance});
          const PointResult svd = invert_point(plan, p, svd_options);
          ++rows;
          outside_segment += svd.status == Status::outside_segment;
          ASSERT_EQ(fast.status, svd.status) << "degree " << degree << " point " << p.x << ", " << p.y << " tolerance "
                                             << tolerance;
          if (!by_distance(fast)) continue;
          ++fast_off_curve;
          EXPECT_TRUE(same_nearest_point(fast, svd, plan.diagonal())) << "degree " << degree << " tolerance " << tolerance;
        }
      }
    }
  RecordProperty("rows", rows);
  RecordProperty("fast_off_curve", fast_off_curve);
  RecordProperty("outside_segment", outside_segment);
  EXPECT_GT(fast_off_curve, 2000 / test_support::kSanitizerThinning);  // the comparison is not vacuous
  EXPECT_GT(outside_segment, 10 / test_support::kSanitizerThinning);  // nor is the extension's part
}

// ---- the paper's algebraic parameter ---------------------------------------------------------------

TEST(InvertProperty, AlgebraicParameterWithoutRefinementIsClose) {
  Measured m{"refine = false, degree <= 10"};
  for (const Case& c : random_cases()) {
    if (c.degree > 10) continue;
    std::mt19937_64 rng(c.seed + 7);
    for (const KnownPoint& k : datasets::segment_points(*c.sampling, 16, rng)) {
      const PointResult r = invert_point(c.plan, k.point, {.refine = false});
      ASSERT_EQ(r.status, Status::ok) << describe(c, k, r);
      const double dt = std::abs(r.t - k.t);
      EXPECT_LE(dt, kParameterError) << describe(c, k, r);
      m.add(dt, dt / parameter_bound(c, k), std::abs(r.residual - k.distance) / c.plan.diagonal());
    }
  }
  EXPECT_GT(m.points, 500 / test_support::kSanitizerThinning);
}

}  // namespace
}  // namespace bezinv
