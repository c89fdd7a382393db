#include "bezinv/datasets/stress.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>

#include "bezinv/datasets/branches.hpp"
#include "bezinv/datasets/cusp.hpp"
#include "bezinv/datasets/degree_elevation.hpp"
#include "bezinv/datasets/high_precision_nearest.hpp"
#include "bezinv/datasets/improper.hpp"
#include "bezinv/datasets/off_curve_points.hpp"
#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/paper_curves.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/datasets/self_intersection.hpp"
#include "bezinv/datasets/translation.hpp"
#include "bezinv/matrix_weighted.hpp"

namespace bezinv::datasets {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Noisy points between these multiples of the tolerance may be answered ok or off_curve: the
// distance the engine measures carries its own rounding, and the contract does not say which side
// a point at the tolerance falls.
constexpr double kAmbiguousBelow = 0.5, kAmbiguousAbove = 2.0;

// Below this speed (|P'(t)| per diagonal) the point's branch is slow enough that another minimum of
// the distance may sit a few samples away, unseen: the rows there get branches_within's proof.
constexpr double kSlowSpeed = 1e-2;

unsigned bit(Status status) { return 1u << static_cast<unsigned>(status); }

bool carries_t(Status status) {
  return status == Status::ok || status == Status::outside_segment || status == Status::off_curve ||
         status == Status::double_point;
}

// The truth of a generated point: the nearest parameter of the double input, at high precision,
// from the generator's answer.
StressRow truth(const Curve& curve, const KnownPoint& k, bool segment_only, double diagonal, double* speed = nullptr) {
  const HighPrecisionNearest h = high_precision_nearest(curve, k.point, k.t, segment_only);
  if (speed) *speed = h.speed;
  StressRow row;
  row.point = k.point;
  row.t_true = h.converged ? h.t : kNaN;
  row.distance = h.distance;
  row.bound = stress_bound(curve.degree(), k.point.x, k.point.y, diagonal, k.scale, h.speed);
  return row;
}

// t log-uniform within [1e-12, 1e-4] of 0 or 1 (as the nearest double).
std::vector<KnownPoint> near_end_points(const CurveSampling& sampling, int count, std::mt19937_64& rng) {
  std::vector<KnownPoint> points;
  for (int attempt = 0; attempt < 20 * count && static_cast<int>(points.size()) < count; ++attempt) {
    const double offset = std::pow(10.0, uniform(rng, -12.0, -4.0));
    const double t = uniform(rng, 0.0, 1.0) < 0.5 ? offset : 1.0 - offset;
    KnownPoint k = known_on_curve(sampling.curve(), t);
    if (isolated(sampling, k.point, {t})) points.push_back(k);
  }
  return points;
}

// On an improper curve P(t) = Q(t^2) every point is also P(-t): isolated from the rest of the curve
// but that second parameter.
std::vector<KnownPoint> improper_points(const CurveSampling& sampling, int count, std::mt19937_64& rng) {
  std::vector<KnownPoint> points;
  for (int attempt = 0; attempt < 20 * count && static_cast<int>(points.size()) < count; ++attempt) {
    const double t = uniform(rng, 0.05, 1.0);  // away from t = 0, where t and -t meet
    KnownPoint k = known_on_curve(sampling.curve(), t);
    if (isolated(sampling, k.point, {t, -t})) points.push_back(k);
  }
  return points;
}

// Points around a crossing P(t1) = P(t2): the crossing itself, then points at 1e-9..1e-4
// diagonals from it (log-uniform), each with both branches' nearest parameters.
std::vector<KnownPoint> around_crossing(const CurveSampling& sampling, double t1, double t2, int count,
                                        std::mt19937_64& rng) {
  std::vector<KnownPoint> points = crossing_points(sampling, t1, t2, 0, 0.0, rng);  // the crossing
  for (int i = 0; static_cast<int>(points.size()) < count && i < 4 * count; ++i) {
    const double radius = std::pow(10.0, uniform(rng, -9.0, -4.0));
    const std::vector<KnownPoint> one = crossing_points(sampling, t1, t2, 1, radius, rng);
    if (one.size() == 2) points.push_back(one[1]);
  }
  return points;
}

// The row of a point near a crossing: each branch's distance decides (within the tolerance: near;
// beyond twice it: far; else either).
StressRow crossing_row(const Curve& curve, const KnownPoint& k, double diagonal, double tolerance) {
  const HighPrecisionNearest a = high_precision_nearest(curve, k.point, k.t, false);
  const HighPrecisionNearest b = high_precision_nearest(curve, k.point, k.t2, false);
  StressRow row;
  row.point = k.point;
  const double slower = std::min(a.speed, b.speed);
  row.bound = stress_bound(curve.degree(), k.point.x, k.point.y, diagonal, k.scale, slower);
  const bool near_a = a.distance <= kAmbiguousBelow * tolerance, near_b = b.distance <= kAmbiguousBelow * tolerance;
  const bool far_a = a.distance >= kAmbiguousAbove * tolerance, far_b = b.distance >= kAmbiguousAbove * tolerance;
  const bool converged = a.converged && b.converged;
  const HighPrecisionNearest& nearer = a.distance <= b.distance ? a : b;
  row.distance = nearer.distance;
  row.t_true = converged ? nearer.t : kNaN;
  if (near_a && near_b) {
    row.expected = Status::double_point;
    row.t_true = converged ? a.t : kNaN;
    row.t2_true = b.t;
    row.distance = a.distance;  // the residual is |P(t) - P0| at the first parameter
  } else if ((near_a && far_b) || (near_b && far_a)) {
    row.expected = Status::ok;
  } else if (far_a && far_b) {
    row.expected = Status::off_curve;
    // Both branches about as near: either is the nearest point, t is not compared.
    if (std::abs(a.distance - b.distance) <= 1e-2 * row.distance) row.t_true = kNaN;
  } else {
    row.expected = near_a || near_b ? Status::ok : Status::off_curve;
  }
  row.acceptable = bit(row.expected);
  if (!(near_a && near_b) && !((near_a && far_b) || (near_b && far_a)) && !(far_a && far_b))
    row.acceptable |= bit(Status::double_point) | bit(Status::ok) | bit(Status::off_curve);
  return row;
}

// The row of a point on the curve near its cusp at tc, at t = tc + s: its own branch holds it, and
// the other branch (parameters on the other side of tc) decides. Beyond twice the tolerance, or
// within it while the curve stays within it in between (by the tip): one branch, ok. Within half
// the tolerance while the curve goes farther than twice it in between (to the tip and back): the
// point is where two branches pass (README's double_point), t and t2 the two parameters. Between
// those margins, both are right.
StressRow cusp_row(const Curve& curve, const KnownPoint& k, double tc, double diagonal, double tolerance) {
  StressRow row = truth(curve, k, /*segment_only=*/false, diagonal);
  row.expected = Status::ok;
  row.acceptable = bit(Status::ok);
  if (std::isnan(row.t_true)) return row;
  // The other branch's nearest point: the least of 400 samples over 5 |s| beyond the tip, then
  // high-precision Newton from it.
  const RealPoint p{k.point.x, k.point.y};
  const Real s = static_cast<Real>(k.t) - tc;
  // The power-form evaluation, O(n) (the compensated de Casteljau is O(n^2)): near the cusp, on
  // [0, 1], both agree far below the tolerance, which is all these samples decide.
  auto distance_at = [&](Real t) {
    const auto q = reference_point(curve, 1 - t, t);
    return q ? distance(*q, p) : std::numeric_limits<Real>::infinity();
  };
  Real best_t = tc, best = distance_at(tc);
  for (int i = 1; i <= 400; ++i) {
    const Real t = tc - s * 5 * i / 400;
    if (const Real d = distance_at(t); d < best) { best = d; best_t = t; }
  }
  const HighPrecisionNearest other = high_precision_nearest(curve, k.point, static_cast<double>(best_t), false);
  if (!other.converged || !((other.t - tc) * (k.t - tc) < 0) || other.distance >= kAmbiguousAbove * tolerance) return row;
  // How far the curve gets from the point between the two parameters (it passes the tip).
  Real farthest = 0;
  for (int i = 1; i < 256; ++i)
    farthest = std::max(farthest, distance_at(other.t + (static_cast<Real>(row.t_true) - other.t) * i / 256));
  if (farthest <= kAmbiguousBelow * tolerance) return row;  // one branch: the curve never leaves
  if (other.distance <= kAmbiguousBelow * tolerance && farthest >= kAmbiguousAbove * tolerance) {
    const bool own_first = row.t_true < other.t;
    row.expected = Status::double_point;
    row.acceptable = bit(Status::double_point);
    row.t2_true = own_first ? other.t : row.t_true;
    row.t_true = own_first ? row.t_true : other.t;
    row.distance = own_first ? row.distance : other.distance;  // the residual is at the first parameter
    row.bound = std::max(row.bound, stress_bound(curve.degree(), k.point.x, k.point.y, diagonal, k.scale, other.speed));
    return row;
  }
  row.acceptable |= bit(Status::double_point);
  return row;
}

// The engine's tolerance (docs/accuracy-model.md): REL x diagonal, but at least 4 ulps of the
// control points' largest coordinate (a curve 1e12 from the origin has ulps of 1.2e-4).
double effective_tolerance(const Curve& curve, double diagonal, double relative_tolerance) {
  double magnitude = 0;
  for (std::size_t i = 0; i < curve.x_num.size(); ++i) {
    if (curve.x_den[i] != 0) magnitude = std::max(magnitude, std::abs(curve.x_num[i] / curve.x_den[i]));
    if (curve.y_den[i] != 0) magnitude = std::max(magnitude, std::abs(curve.y_num[i] / curve.y_den[i]));
  }
  const double ulp = std::nextafter(magnitude, std::numeric_limits<double>::infinity()) - magnitude;
  return std::max(relative_tolerance * diagonal, 4 * ulp);
}

// Where the tolerance is that large (far from the origin) the generators' isolation margin
// (kIsolation x diagonal) no longer keeps other branches out of it: a branch of the segment other
// than the point's own within twice the tolerance makes double_point right too.
void allow_other_branches(const CurveSampling& sampling, double tolerance, StressRow& row) {
  if (tolerance < kIsolation * sampling.diagonal() / 4 || std::isnan(row.t_true)) return;
  for (const DistanceMinimum& m : sampling.line_minima({row.point.x, row.point.y}, 2 * tolerance))
    if (m.on_segment && m.distance <= 2 * tolerance && std::abs(static_cast<double>(m.t) - row.t_true) > 1e-6)
      row.acceptable |= bit(Status::double_point);
}

}  // namespace

std::optional<StressCurve> stress_curve(Family family, CurveKind kind, int degree, int index, std::mt19937_64& rng) {
  const auto polygon = index % 2 ? ControlPolygon::unit_square : ControlPolygon::perturbed_arc;
  StressCurve c;
  switch (family) {
    case Family::crossings: {
      if (degree < 3) return std::nullopt;
      c.t1 = uniform(rng, 0.15, 0.45);
      c.t2 = uniform(rng, 0.55, 0.85);
      try {
        c.curve = with_self_intersection(kind, degree, c.t1, c.t2, rng, polygon);
      } catch (const std::runtime_error&) {
        return std::nullopt;  // no curve of this degree crossed itself as asked
      }
      return c;
    }
    case Family::cusps: {
      if (degree < 3) return std::nullopt;
      c.t1 = uniform(rng, 0.3, 0.7);
      try {
        c.curve = with_cusp(kind, degree, c.t1, rng, polygon);
      } catch (const std::runtime_error&) {
        return std::nullopt;  // no curve of this degree had a verified cusp
      }
      return c;
    }
    case Family::translated: {
      const double dx = std::copysign(std::pow(10.0, uniform(rng, 6.0, 12.0)), uniform(rng, -1.0, 1.0));
      const double dy = std::copysign(std::pow(10.0, uniform(rng, 6.0, 12.0)), uniform(rng, -1.0, 1.0));
      c.curve = translated(random_curve(kind, degree, rng, polygon), dx, dy);
      return c;
    }
    case Family::tiny: {
      const Curve small = scaled(random_curve(kind, degree, rng, polygon), std::pow(10.0, uniform(rng, -12.0, -6.0)));
      c.curve = index % 2 ? translated(small, 1.0, 1.0) : small;
      return c;
    }
    case Family::elevated:
      if (degree < 3) return std::nullopt;
      c.curve = degree_elevated(random_curve(kind, degree - 2, rng, polygon), 2);
      return c;
    case Family::improper:
      if (degree % 2) return std::nullopt;
      c.curve = improper(random_curve(kind, degree / 2, rng, polygon));
      return c;
    case Family::weights: {
      if (kind == CurveKind::bezier) return std::nullopt;
      Curve base = random_curve(kind, degree, rng, polygon);
      auto weight = [&] { return std::pow(10.0, uniform(rng, -4.0, 4.0)); };
      for (int i = 0; i <= degree; ++i) {
        // num_i / den_i is the control point (x), so both scale together.
        const double wx = weight(), wy = kind == CurveKind::rational_bezier ? wx : weight();
        base.x_num[i] *= wx / base.x_den[i];
        base.x_den[i] = wx;
        base.y_num[i] *= wy / base.y_den[i];
        base.y_den[i] = wy;
      }
      c.curve = base;
      return c;
    }
    case Family::matrix_weighted: {
      if (kind != CurveKind::rational || degree % 2) return std::nullopt;
      const Curve base = random_curve(CurveKind::bezier, degree / 2, rng, polygon);
      MatrixWeightedCurve m;
      m.id = "matrix_weighted";
      for (int i = 0; i <= degree / 2; ++i) {
        m.points.push_back({base.x_num[i], base.y_num[i], 0.0});
        const double angle = uniform(rng, 0.0, 2 * std::numbers::pi);
        const Vector3 direction{std::cos(angle), std::sin(angle), 0.0};
        const double omega = uniform(rng, 0.5, 2.0), mu = uniform(rng, -0.9, 10.0);
        m.matrices.push_back(index % 2 ? normal_weight(2, direction, omega, mu, "P")
                                       : tangent_weight(2, direction, omega, mu, "P"));
      }
      try {
        c.curve = plane_curve(convert(m), "matrix_weighted");
      } catch (const CurveError&) {
        return std::nullopt;  // M(t) singular on [0, 1] (eqs. (2), (3) make it positive definite: never)
      }
      return c;
    }
    case Family::space: {
      if (kind == CurveKind::rational) return std::nullopt;  // a rotation would mix separate denominators
      c.curve = random_curve(kind, degree, rng, polygon);
      // e1, e2: an orthonormal pair from random directions (Gram-Schmidt), e3 their cross product.
      auto unit = [](std::array<double, 3> v) {
        const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (double& x : v) x /= l;
        return v;
      };
      c.e1 = unit({uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)});
      std::array<double, 3> v{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
      const double along = v[0] * c.e1[0] + v[1] * c.e1[1] + v[2] * c.e1[2];
      for (int k = 0; k < 3; ++k) v[k] -= along * c.e1[k];
      c.e2 = unit(v);
      c.e3 = {c.e1[1] * c.e2[2] - c.e1[2] * c.e2[1], c.e1[2] * c.e2[0] - c.e1[0] * c.e2[2],
              c.e1[0] * c.e2[1] - c.e1[1] * c.e2[0]};
      Curve lifted = c.curve;  // one denominator: the homogeneous numerators map linearly
      lifted.z_num.resize(c.curve.x_num.size());
      for (std::size_t i = 0; i < c.curve.x_num.size(); ++i) {
        const double x = c.curve.x_num[i], y = c.curve.y_num[i];
        lifted.x_num[i] = c.e1[0] * x + c.e2[0] * y;
        lifted.y_num[i] = c.e1[1] * x + c.e2[1] * y;
        lifted.z_num[i] = c.e1[2] * x + c.e2[2] * y;
      }
      lifted.z_den = lifted.x_den;
      c.space = lifted;
      return c;
    }
    case Family::graphs: {
      const int f = index % 3;
      auto ordinate = [f](double x) { return f == 0 ? std::sin(3 * x) : f == 1 ? std::exp(x) : 1 / (1 + 4 * x * x); };
      // Turned by a random angle on every other curve (not kind rational: a turn mixes separate
      // denominators), so that no coordinate is the linear one.
      const double angle = index % 2 && kind != CurveKind::rational ? uniform(rng, 0.0, 2 * std::numbers::pi) : 0.0;
      const double cos_a = std::cos(angle), sin_a = std::sin(angle);
      std::vector<std::array<double, 2>> points(degree + 1);
      std::vector<double> w(degree + 1);
      for (int i = 0; i <= degree; ++i) {
        const double u = static_cast<double>(i) / degree, v = ordinate(u);
        points[i] = {cos_a * u - sin_a * v, sin_a * u + cos_a * v};
        w[i] = uniform(rng, 0.5, 2.0);
      }
      if (kind == CurveKind::bezier) {
        c.curve = Curve::bezier("graphs", points);
      } else if (kind == CurveKind::rational_bezier) {
        c.curve = Curve::rational_bezier("graphs", points, w);
      } else {
        std::vector<double> x(degree + 1), x_den(degree + 1, 1.0), yw(degree + 1);
        for (int i = 0; i <= degree; ++i) x[i] = points[i][0], yw[i] = points[i][1] * w[i];
        c.curve = Curve::rational("graphs", x, x_den, yw, w);
      }
      return c;
    }
    case Family::papers: {
      if (index != 0) return std::nullopt;  // one curve: they are fixed
      if (kind == CurveKind::rational && degree == 4) c.curve = paper_example1_curve();
      else if (kind == CurveKind::rational_bezier && degree == 15) c.curve = paper_example2_curve();
      else if (kind == CurveKind::rational_bezier && degree == 3) c.curve = paper_example4_curve();
      else if (kind == CurveKind::bezier && degree == 3) c.curve = default_cubic_curve();
      else return std::nullopt;
      return c;
    }
    default:
      c.curve = random_curve(kind, degree, rng, polygon);
      return c;
  }
}

const char* to_string(Family family) {
  switch (family) {
    case Family::on_curve: return "on_curve";
    case Family::near_ends: return "near_ends";
    case Family::extension: return "extension";
    case Family::noisy: return "noisy";
    case Family::far: return "far";
    case Family::crossings: return "crossings";
    case Family::cusps: return "cusps";
    case Family::translated: return "translated";
    case Family::tiny: return "tiny";
    case Family::elevated: return "elevated";
    case Family::improper: return "improper";
    case Family::weights: return "weights";
    case Family::papers: return "papers";
    case Family::matrix_weighted: return "matrix_weighted";
    case Family::space: return "space";
    case Family::graphs: return "graphs";
  }
  return "?";
}

std::optional<Family> family_from_string(std::string_view name) {
  for (Family f : kFamilies)
    if (name == to_string(f)) return f;
  return std::nullopt;
}

double stress_bound(int degree, double x, double y, double diagonal, double scale, double speed) {
  const double size = std::max({std::abs(x), std::abs(y), diagonal, std::isfinite(scale) ? scale : 0.0});
  return 2 * (8 + degree) * kEps * size / speed + 2 * kEps;
}

std::vector<StressRow> stress_rows(Family family, const StressCurve& stress_curve, const CurveSampling& sampling,
                                   int count, double relative_tolerance, std::mt19937_64& rng) {
  const Curve& curve = sampling.curve();
  const double diagonal = sampling.diagonal(), tolerance = effective_tolerance(curve, diagonal, relative_tolerance);
  if (family == Family::crossings) {
    std::vector<StressRow> rows;
    for (const KnownPoint& k : around_crossing(sampling, stress_curve.t1, stress_curve.t2, count, rng))
      rows.push_back(crossing_row(curve, k, diagonal, tolerance));
    return rows;
  }
  if (family == Family::cusps) {
    std::vector<StressRow> rows;
    for (const KnownPoint& k : near_cusp_points(sampling, stress_curve.t1, count, rng))
      rows.push_back(cusp_row(curve, k, stress_curve.t1, diagonal, tolerance));
    return rows;
  }
  // Half on_curve's rows, half noisy's, at the relative tolerance `relative` (how many on_curve's:
  // *on_curve_rows).
  const auto on_and_noisy_rows = [&](double relative, std::size_t* on_curve_rows = nullptr) {
    std::vector<StressRow> rows = stress_rows(Family::on_curve, stress_curve, sampling, count / 2, relative, rng);
    if (on_curve_rows != nullptr) *on_curve_rows = rows.size();
    std::vector<StressRow> off = stress_rows(Family::noisy, stress_curve, sampling, count - count / 2, relative, rng);
    rows.insert(rows.end(), off.begin(), off.end());
    return rows;
  };
  if (family == Family::graphs) return on_and_noisy_rows(relative_tolerance);
  if (family == Family::space) {
    // The plane rows at the space curve's tolerance, lifted (see stress.hpp).
    const Curve& lifted = *stress_curve.space;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (std::size_t i = 0; i < lifted.x_num.size(); ++i) {
      const double p[3] = {lifted.x_num[i] / lifted.x_den[i], lifted.y_num[i] / lifted.x_den[i],
                           lifted.z_num[i] / lifted.x_den[i]};
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    }
    const double diagonal3 = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    const double relative = relative_tolerance * diagonal3 / diagonal;
    std::size_t on_curve_rows = 0;
    std::vector<StressRow> rows = on_and_noisy_rows(relative, &on_curve_rows);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      StressRow& row = rows[i];
      const double x = row.point.x, y = row.point.y;
      // Off the plane only where the status cannot change: rows off the curve beyond doubt.
      const bool off = row.acceptable == bit(Status::off_curve);
      const double h = off ? uniform(rng, -2.0, 2.0) * row.distance : 0.0;
      const std::array<double, 3>& a = stress_curve.e1;
      const std::array<double, 3>& b = stress_curve.e2;
      const std::array<double, 3>& n = stress_curve.e3;
      row.point = {a[0] * x + b[0] * y + h * n[0], a[1] * x + b[1] * y + h * n[1]};
      row.z = a[2] * x + b[2] * y + h * n[2];
      // The lifted point and curve are rounded: the truth again, in space, from the plane's, and of
      // the same kind: for a noisy row the nearest point of the segment (an off_curve row's t, and
      // an ok row's near an end), as the plane's noisy family has it, whatever statuses are right.
      const bool from_noisy = i >= on_curve_rows;
      const HighPrecisionNearest truth3 =
          high_precision_nearest(lifted, row.point, row.t_true, /*segment_only=*/from_noisy, row.z);
      if (truth3.converged) {
        row.t_true = truth3.t;
        row.distance = truth3.distance;
        const double size = std::max({std::abs(row.point.x), std::abs(row.point.y), std::abs(row.z)});
        row.bound = std::max(row.bound, stress_bound(lifted.degree(), size, 0.0, diagonal3, 0.0, truth3.speed));
      } else {
        row.t_true = std::numeric_limits<double>::quiet_NaN();  // counted as no truth
        row.distance = std::hypot(row.distance, h);
      }
    }
    return rows;
  }
  std::vector<KnownPoint> known;
  switch (family) {
    case Family::on_curve:
    case Family::translated:
    case Family::tiny:
    case Family::elevated:
    case Family::weights:
    case Family::matrix_weighted:
    case Family::papers: known = segment_points(sampling, count, rng); break;
    case Family::space: break;
    case Family::graphs: break;
    case Family::improper: known = improper_points(sampling, count, rng); break;
    case Family::cusps: break;
    case Family::crossings: break;
    case Family::near_ends: known = near_end_points(sampling, count, rng); break;
    case Family::extension: known = extension_points(sampling, count, rng); break;
    case Family::noisy: known = normal_offset_points(sampling, count, 1e-12, 1e-3, rng); break;
    case Family::far: known = normal_offset_points(sampling, count, 10.0, 1000.0, rng); break;
  }
  const bool off = family == Family::noisy || family == Family::far;
  std::vector<StressRow> rows;
  rows.reserve(known.size());
  for (const KnownPoint& k : known) {
    double speed = 0;
    StressRow row = truth(curve, k, /*segment_only=*/off, diagonal, &speed);
    if (!off) {
      row.expected = family == Family::extension ? Status::outside_segment : Status::ok;
      row.acceptable = bit(row.expected);
    } else if (row.distance <= kAmbiguousBelow * tolerance) {
      row.expected = Status::ok;
      row.acceptable = bit(Status::ok);
    } else {
      row.expected = Status::off_curve;
      row.acceptable = bit(Status::off_curve) | (row.distance < kAmbiguousAbove * tolerance ? bit(Status::ok) : 0u);
    }
    // The nearest point of the segment is an end and the point is within reach of the tolerance:
    // the curve's extension beyond that end is about as near.
    if (off && (row.t_true == 0.0 || row.t_true == 1.0) && row.distance < kAmbiguousAbove * tolerance)
      row.acceptable |= bit(Status::outside_segment) | bit(Status::ok);
    allow_other_branches(sampling, tolerance, row);
    // Where a sampling can miss a second branch within the tolerance, the subdivision's proof
    // decides: extreme weights (a loop inside a sliver of parameter) and a curve that nearly stops
    // (two minima of the distance a few samples apart). Two runs within the tolerance, the curve
    // farther between: double_point is right too.
    if (row.distance <= kAmbiguousAbove * tolerance && (family == Family::weights || speed < kSlowSpeed * diagonal) &&
        branches_within(curve, {k.point.x, k.point.y}, tolerance) >= 2)
      row.acceptable |= bit(Status::double_point);
    rows.push_back(row);
  }
  return rows;
}

void StressTally::add(const StressRow& row, const PointResult& got, double diagonal) {
  ++rows;
  const auto expected_index = static_cast<std::size_t>(row.expected), got_index = static_cast<std::size_t>(got.status);
  if (expected_index < kStatusCount && got_index < kStatusCount) ++confusion[expected_index][got_index];
  ambiguous += std::popcount(row.acceptable) > 1;
  if (!accepts(row, got.status)) {
    ++wrong_status;
    if (expected_index < kStatusCount && got_index < kStatusCount) ++wrong[expected_index][got_index];
    return;
  }
  if (got.status == Status::double_point && std::isnan(got.t2)) ++missing_t2;
  if (!carries_t(got.status)) return;
  if (std::isnan(got.t)) {
    ++nan_t;
    return;
  }
  // Another right status of an ambiguous row answers another question (the extension's nearest
  // point, say): its t is not compared with this one's truth.
  if (got.status != row.expected) return;
  // An off_curve row answered by projection (--off-curve projection) carries the formula's
  // projection, not the nearest point: its status is what is checked.
  if (got.path == Path::projection) return;
  if (std::isnan(row.t_true)) {
    ++no_truth;
    return;
  }
  const double error = parameter_error(row, got);
  dt.push_back(error);
  dt_over_bound.push_back(error / row.bound);
  if (std::isfinite(got.residual)) residual_error.push_back(std::abs(got.residual - row.distance) / diagonal);
}

double parameter_error(const StressRow& row, const PointResult& got) {
  double error = std::abs(got.t - row.t_true);
  if (got.status == Status::double_point && std::isfinite(row.t2_true) && std::isfinite(got.t2))
    error = std::max(error, std::abs(got.t2 - row.t2_true));
  return error;
}

Quantiles quantiles(std::vector<double> values) {
  Quantiles q;
  if (values.empty()) {
    q.p50 = q.p99 = q.p999 = q.max = kNaN;
    return q;
  }
  std::sort(values.begin(), values.end());
  const auto at = [&](double fraction) {
    const std::size_t i = static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(values.size()))) - 1;
    return values[std::min(i, values.size() - 1)];
  };
  q.p50 = at(0.5);
  q.p99 = at(0.99);
  q.p999 = at(0.999);
  q.max = values.back();
  return q;
}

}  // namespace bezinv::datasets
