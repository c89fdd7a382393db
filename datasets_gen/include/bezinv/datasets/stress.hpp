#pragma once
// The accuracy stress tool's data (`bezinv stress`, engine/cli/stress.cpp): families of points
// whose answers are known, each row's truth computed on the double input the engine is given
// (high_precision_nearest.hpp), and the tally of the engine's answers against it.
//
// The families (what each stresses, how its truth is known):
//   on_curve   t uniform in [0,1]: the common case. P(t) made exactly and rounded; truth: the
//              nearest curve point of the rounded input, status ok.
//   near_ends  t within 1e-12..1e-4 of 0 or 1 (log-uniform): the ends, where the Bernstein basis is
//              most lopsided. Truth as on_curve; status ok.
//   extension  t in [-0.3,-0.01] u [1.01,1.3]: the curve beyond its segment. Truth as on_curve;
//              status outside_segment.
//   noisy      P(t0) + d N(t0), d log-uniform in 1e-12..1e-3 of the diagonal: measured points.
//              Truth: the nearest point of the segment (the generator checks it is unambiguous by
//              dense sampling), refined on the rounded input; status ok below half the tolerance,
//              off_curve above twice it, either between (ambiguous); near an end of the segment
//              whose nearest point is the end, outside_segment is right too.
//   far        the same with d in 10..1000 diagonals: far off the curve; status off_curve.
//   crossings  curves made to cross themselves at P(t1) = P(t2) (degree >= 3), points at the
//              crossing and at 1e-9..1e-4 diagonals from it: both branches within the tolerance
//              (double_point, t and t2), one (ok), none (off_curve), and between, more than one
//              status right. Truth: each branch's nearest parameter, high precision.
//   cusps      curves made to have a cusp at tc (P'(tc) = 0, degree >= 3; datasets/cusp.hpp), points
//              on them at tc +- s, s in 1e-4..1e-2: where the two branches meet, |P'| ~ s, and
//              for the smaller s the other branch is within the tolerance without the curve
//              leaving it between (one branch: ok, never double_point). Truth as on_curve (the
//              other branch is never within rounding of the point); status ok.
//   translated on_curve's points on the curve moved 1e6..1e12 away from the origin (map
//              coordinates): the digits the plan's centring must keep. Status ok.
//   tiny       on_curve's points on curves shrunk by 1e-12..1e-6 (about the origin; every other
//              curve then moved by (1, 1), where its coordinates' ulps reach 2e-4 of its diagonal):
//              nothing absolute may hide in the engine's scaling. Status ok.
//   elevated   on_curve's points on a curve of degree n - 2 written at degree n (in double, so its
//              top coefficients are round-off): the engine's degree reduction. Status ok.
//   improper   on_curve's points on P(t) = Q(t^2) (even degrees): every point has a second
//              parameter -t on the extension. Status ok.
//   weights    on_curve's points with weights (denominator coefficients) 10^-4..10^4: ratios up
//              to 1e8 (rational kinds only). Status ok.
//   matrix_weighted  Yang's matrix-weighted curves of degree n / 2 (even degrees, kind rational: what
//              the conversion gives), weights from point-normal or point-tangent pairs (eqs. (2),
//              (3)), omega 0.5..2, mu -0.9..10, converted to degree n; on_curve's points. Status ok.
//   space      plane curves (bezier, rational_bezier) placed in a random plane through the origin of
//              space: on_curve's and noisy's rows, the noisy ones off the curve moved off the plane
//              too, by up to twice their distance. A plane curve's nearest point to a point off its
//              plane is the nearest point to the point's foot in the plane, so the plane truth holds
//              (t the same, distance sqrt(d^2 + h^2)), computed again in space on the rounded
//              lifted point and curve, of the same kind (a noisy row's the nearest point of the
//              segment); statuses for the tolerance relative to the space curve's box. Status ok,
//              or off_curve.
//   graphs     graphs of smooth functions y = f(x) (sin 3x, e^x, the easing curve 1/(1 + 4x^2)),
//              control points (i/n, f(i/n)), every other one turned by a random angle; weights
//              0.5..2 (rational_bezier; rational: the weights on y alone, so x stays polynomial).
//              The curves people draw, which from degree ~7 lie within rounding of a lower degree
//              (the engine's formula path): on_curve's and noisy's rows. Status ok, or off_curve.
//   papers     the papers' curves where kind and degree match (Marco & Martinez's Examples 1, 2
//              and 4, and the demo's cubic), on_curve's points. Status ok.
// Every generated point is isolated from the curve's other branches (datasets/known_point.hpp).
// A family that does not apply to a kind or degree (crossings and cusps below 3, improper at odd degrees,
// weights for bezier, matrix_weighted but for rational at even degrees, space for rational, papers
// but for their own)
// makes no curve there.
#include <array>
#include <limits>
#include <cstddef>
#include <optional>
#include <random>
#include <string_view>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/invert.hpp"

namespace bezinv::datasets {

enum class Family {
  on_curve, near_ends, extension, noisy, far, crossings, cusps, translated, tiny, elevated, improper, weights,
  papers, matrix_weighted, space, graphs
};
inline constexpr std::array kFamilies = {Family::on_curve,   Family::near_ends, Family::extension, Family::noisy,
                                         Family::far,        Family::crossings, Family::cusps,     Family::translated,
                                         Family::tiny,       Family::elevated,  Family::improper,  Family::weights,
                                         Family::papers,     Family::matrix_weighted, Family::space,
                                         Family::graphs};
const char* to_string(Family family);
std::optional<Family> family_from_string(std::string_view name);

// One row: what the engine is given, and what it must answer.
struct StressRow {
  Point point;
  double z = std::numeric_limits<double>::quiet_NaN();  // the point's third coordinate (family space)
  Status expected = Status::ok;
  unsigned acceptable = 0;  // the statuses that are right (bit 1 << status; `expected` among them):
                            // more than one for a row within a margin of the tolerance (ambiguous)
  double t_true = 0;       // the nearest parameter of `point` (high precision, rounded)
  double t2_true = std::numeric_limits<double>::quiet_NaN();  // a double point's other parameter
  double distance = 0;     // |P(t_true) - point| (high precision, rounded)
  double bound = 0;        // the accuracy model's bound on |t - t_true| (stress_bound)
};

// The accuracy model's bound on |t - t_true| for a point (x, y) whose nearest curve point has speed
// |P'| = `speed` (docs/accuracy-model.md, "The stress tool's bound"): the parameter error that
// rounding the input and evaluating a degree-n curve in double cause, 2 (8 + n) eps S / |P'| + 4u,
// S = max(|x|, |y|, diagonal, `scale`), scale the evaluation's (KnownPoint::scale: the sum of the
// absolute terms, which grows as (|1 - t| + |t|)^n on the extension).
double stress_bound(int degree, double x, double y, double diagonal, double scale, double speed);

// A curve of the family, or none where the family does not apply. t1, t2: a crossing's parameters;
// t1: a cusp's.
struct StressCurve {
  Curve curve;  // the truth's curve (family space: the plane curve, in plane coordinates)
  double t1 = std::numeric_limits<double>::quiet_NaN(), t2 = std::numeric_limits<double>::quiet_NaN();
  // Family space: the curve given to the engine, (x, y) -> x e1 + y e2, and its plane's normal e3.
  std::optional<Curve> space;
  std::array<double, 3> e1{}, e2{}, e3{};
};
// index: the curve's number within its cell (even: a perturbed arc, odd: a wild control polygon).
std::optional<StressCurve> stress_curve(Family family, CurveKind kind, int degree, int index, std::mt19937_64& rng);

// `count` rows of `family` on the curve (fewer where too few isolated points exist), truths at
// high precision, statuses for the relative tolerance `relative_tolerance`. `sampling` is of
// curve.curve.
std::vector<StressRow> stress_rows(Family family, const StressCurve& curve, const CurveSampling& sampling, int count,
                                   double relative_tolerance, std::mt19937_64& rng);

inline constexpr std::size_t kStatusCount = 6;  // Status::ok .. Status::failed

// Whether `status` is one of the row's right ones.
inline bool accepts(const StressRow& row, Status status) {
  return (row.acceptable >> static_cast<unsigned>(status)) & 1u;
}

// |t - t_true| of an answer (for a double point the larger of both parameters' errors, where both
// are there); NaN where the answer has no t.
double parameter_error(const StressRow& row, const PointResult& got);

// The engine's answers against the truth, for one cell of the report (family x kind x degree x path).
struct StressTally {
  std::size_t rows = 0, ambiguous = 0;
  std::size_t no_truth = 0;      // the reference did not converge: the row's t is not compared
  std::size_t wrong_status = 0;  // a status not in the row's acceptable ones
  std::size_t nan_t = 0;         // a status that carries t (ok, outside_segment, off_curve) without one
  std::size_t missing_t2 = 0;    // double_point without t2
  std::array<std::array<std::size_t, kStatusCount>, kStatusCount> confusion{};  // [expected][got]
  std::array<std::array<std::size_t, kStatusCount>, kStatusCount> wrong{};      // the wrong rows alone
  std::vector<double> dt, dt_over_bound;  // rows answered with the expected status, which carries t
  std::vector<double> residual_error;     // |residual - true distance| / diagonal, the same rows
  void add(const StressRow& row, const PointResult& got, double diagonal);
};

struct Quantiles {
  double p50 = 0, p99 = 0, p999 = 0, max = 0;  // NaN when there are no values
};
Quantiles quantiles(std::vector<double> values);

}  // namespace bezinv::datasets
