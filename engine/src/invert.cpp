#include "bezinv/invert.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>

#include "bezinv/bernstein.hpp"
#include "bezinv/kernels/symmetric_svd.hpp"
#include "bezinv/null_vector.hpp"
#include "bezinv/sylvester.hpp"
#include "refine.hpp"

namespace bezinv {

const char* to_string(Status status) {
  switch (status) {
    case Status::ok: return "ok";
    case Status::outside_segment: return "outside_segment";
    case Status::double_point: return "double_point";
    case Status::off_curve: return "off_curve";
    case Status::invalid_input: return "invalid_input";
    case Status::failed: return "failed";
  }
  return "?";
}

const char* to_string(Path path) {
  switch (path) {
    case Path::none: return "none";
    case Path::bezout: return "bezout";
    case Path::bezout_pair: return "bezout_pair";
    case Path::sylvester: return "sylvester";
    case Path::nearest: return "nearest";
  }
  return "?";
}

namespace {

using Coefficients = std::array<double, kMaxDegree + 1>;

// p = X_num - u0 X_den and q = Y_num - v0 Y_den at the plan's degree.
struct PointPolynomials {
  int n;
  Coefficients p, q;
  std::span<const double> p_span() const { return {p.data(), static_cast<std::size_t>(n + 1)}; }
  std::span<const double> q_span() const { return {q.data(), static_cast<std::size_t>(n + 1)}; }
};

PointPolynomials point_polynomials(const InversionPlan& plan, double u0, double v0) {
  PointPolynomials pq;
  pq.n = plan.degree;
  for (int i = 0; i <= pq.n; ++i) {
    pq.p[i] = plan.x_num[i] - u0 * plan.x_den[i];
    pq.q[i] = plan.y_num[i] - v0 * plan.y_den[i];
  }
  return pq;
}

// Paper Sect. 4: when the power-basis leading coefficients of p AND q both vanish, p and q share a
// root at infinity and the Bezout matrix of formal degree n gains a null direction that is not a
// point of the curve. The leading coefficient is affine in the point, from the plan's four.
bool degree_drops(const InversionPlan& plan, const PointPolynomials& pq, double u0, double v0) {
  const double lead_p = plan.lead_x_num - u0 * plan.lead_x_den;
  const double lead_q = plan.lead_y_num - v0 * plan.lead_y_den;
  return std::abs(lead_p) <= kDegreeDropRatio * power_leading_bound(pq.p_span()) &&
         std::abs(lead_q) <= kDegreeDropRatio * power_leading_bound(pq.q_span());
}

// p written at its true degree, in place: reduce while the leading power coefficient vanishes.
// Returns the degree.
int reduce_to_true_degree(Coefficients& p, int n) {
  Coefficients r;
  while (n >= 1) {
    const std::span<const double> current(p.data(), n + 1);
    if (std::abs(power_leading_coefficient(current)) > kDegreeDropRatio * power_leading_bound(current)) break;
    reduce_degree(current, std::span<double>(r.data(), n));
    --n;
    std::copy_n(r.begin(), n + 1, p.begin());
  }
  return n;
}

// The Sylvester path (paper Sect. 4, taken only at degree drops): the left null vector of S(p, q)
// at the true degrees is the Bernstein basis of degree m+k-1 at the common root. Fixed-size
// storage (m + k < 2 kMaxDegree), so no allocation here either.
double sylvester_parameter(const PointPolynomials& pq) {
  Coefficients p = pq.p, q = pq.q;
  const int m = reduce_to_true_degree(p, pq.n), k = reduce_to_true_degree(q, pq.n);
  if (m < 1 || k < 1) return std::nan("");
  constexpr int kMaxSize = 2 * kMaxDegree;
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor, kMaxSize, kMaxSize>;
  const int size = m + k;
  Matrix S(size, size);
  sylvester_matrix(std::span<const double>(p.data(), m + 1), std::span<const double>(q.data(), k + 1),
                   std::span<double>(S.data(), static_cast<std::size_t>(size) * size));
  Eigen::JacobiSVD<Matrix> svd(S, Eigen::ComputeFullU);
  const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxSize, 1> z = svd.matrixU().col(size - 1);  // v^T S = 0
  return parameter_from_null_vector(std::span<const double>(z.data(), size));
}

// Degree 1: B is 1 x 1 and has no null vector to read. p and q are linear; the least-squares
// root of both, t = -(p0 a + q0 b) / (a^2 + b^2) with a = p1 - p0, b = q1 - q0, is exact for a
// point on the line.
double linear_parameter(const PointPolynomials& pq) {
  const double a = pq.p[1] - pq.p[0], b = pq.q[1] - pq.q[0];
  return -(pq.p[0] * a + pq.q[0] * b) / (a * a + b * b);
}

struct Candidate {
  double t = PointResult::nan;
  double distance = PointResult::nan;  // normalized units
  Path path = Path::none;
  bool on_segment = false;  // t in [0,1] and within tolerance
  bool on_curve = false;    // within tolerance (segment or extension)
};

// From an algebraic parameter to a verified one: refine (or not), then measure.
Candidate settle(const InversionPlan& plan, double u0, double v0, double t_algebraic, Path path,
                 double tolerance, bool refine) {
  Candidate c;
  c.path = path;
  if (!std::isfinite(t_algebraic)) return c;
  const bool inside = t_algebraic >= 0.0 && t_algebraic <= 1.0;
  auto measure = [&](double t) { return detail::distance(plan, u0, v0, t); };
  if (!refine) {
    // The paper's algebraic t. A point within tolerance of an end of the segment whose algebraic t
    // fell just outside [0,1] is on the segment: its t is clamped onto it.
    const double clamped = std::clamp(t_algebraic, 0.0, 1.0);
    c.t = t_algebraic;
    c.distance = measure(t_algebraic);
    if (!inside && measure(clamped) <= tolerance) { c.t = clamped; c.distance = measure(clamped); }
  } else {
    c.t = detail::refine_parameter(plan, u0, v0, t_algebraic, /*stay_on_segment=*/inside);
    c.distance = measure(c.t);
    const bool at_end = c.t == 0.0 || c.t == 1.0;
    if (inside && at_end && !(c.distance <= tolerance)) {
      // Clamped at an end but not there: the point may be on the extension just past it.
      const double t = detail::refine_parameter(plan, u0, v0, t_algebraic, false);
      const double d = measure(t);
      if (d < c.distance) { c.t = t; c.distance = d; }
    } else if (!inside) {
      // Started on the extension: the nearest point of the segment wins if it is within tolerance.
      const double t = detail::refine_parameter(plan, u0, v0, std::clamp(t_algebraic, 0.0, 1.0), true);
      const double d = measure(t);
      if (d <= tolerance) { c.t = t; c.distance = d; }
    }
  }
  c.on_curve = c.distance <= tolerance;
  c.on_segment = c.on_curve && c.t >= 0.0 && c.t <= 1.0;
  return c;
}

}  // namespace

PointResult invert_point(const InversionPlan& plan, Point point, const InvertOptions& options) {
  PointResult r;
  if (!std::isfinite(point.x) || !std::isfinite(point.y)) {
    r.status = Status::invalid_input;
    r.reason = "non-finite coordinate";
    return r;
  }
  if (!plan.usable) {
    r.status = Status::failed;
    r.reason = plan.reason;
    return r;
  }
  const auto [u0, v0] = plan.normalize(point.x, point.y);
  if (!std::isfinite(u0) || !std::isfinite(v0)) {
    r.status = Status::invalid_input;
    r.reason = "coordinate overflows after normalization";
    return r;
  }
  const double tolerance = options.relative_tolerance * plan.diagonal / plan.scale;
  const int n = plan.degree;
  const PointPolynomials pq = point_polynomials(plan, u0, v0);

  std::array<Candidate, 6> candidates;
  int count = 0;
  auto add = [&](double t, Path path) {
    if (count < static_cast<int>(candidates.size()))
      candidates[count++] = settle(plan, u0, v0, t, path, tolerance, options.refine);
  };

  std::array<double, kMaxDegree * kMaxDegree> B, V;
  std::array<double, kMaxDegree> sigma;
  bool look_for_second = false;
  if (n == 1) {
    add(linear_parameter(pq), Path::bezout);
  } else {
    bezout_at(plan, u0, v0, B);
    bool finite = true;
    for (int i = 0; i < n * n; ++i) finite = finite && std::isfinite(B[i]);
    if (!finite) {
      r.status = Status::failed;
      r.reason = "point so far from the curve that the Bezout matrix overflows";
      return r;
    }
    kernels::symmetric_svd(n, std::span<const double>(B.data(), n * n), sigma, V);
    if (sigma[0] > 0 && std::isfinite(sigma[0])) {
      r.sigma_min = sigma[n - 1] / sigma[0];
      r.sigma_next = sigma[n - 2] / sigma[0];
      // Paper Sect. 3: the right singular vector of the smallest singular value.
      add(parameter_from_null_vector(std::span<const double>(V.data() + (n - 1) * n, n)), Path::bezout);
      look_for_second = n >= 3 && r.sigma_next <= kSecondNullDirectionRatio;
    }
  }
  const bool drop = n >= 2 && degree_drops(plan, pq, u0, v0);
  const bool settled = count > 0 && candidates[0].on_segment && !look_for_second && !drop;
  if (!settled) {
    if (drop) add(sylvester_parameter(pq), Path::sylvester);
    if (n >= 3 && sigma[0] > 0 && std::isfinite(sigma[0])) {
      // Nullity 2 (self-intersection, or a root driven towards infinity): both parameters from
      // the span of the two last singular vectors.
      double t[2];
      const int roots = parameters_from_null_space(std::span<const double>(V.data() + (n - 1) * n, n),
                                                   std::span<const double>(V.data() + (n - 2) * n, n), t);
      for (int i = 0; i < roots; ++i) add(t[i], Path::bezout_pair);
    }
  }

  // Decide. On the segment at two distinct parameters: a double point.
  const Candidate* first = nullptr;
  const Candidate* second = nullptr;
  for (int i = 0; i < count; ++i) {
    const Candidate& c = candidates[i];
    if (!c.on_segment) continue;
    if (!first) { first = &c; continue; }
    if (std::abs(c.t - first->t) > kDistinctParameterGap && (!second || c.distance < second->distance))
      second = &c;
  }
  auto report = [&](const Candidate& c, Status status) {
    r.t = c.t;
    r.residual = c.distance * plan.scale;
    r.path = c.path;
    r.status = status;
  };
  if (first && second) {
    const Candidate& lo = first->t < second->t ? *first : *second;
    const Candidate& hi = first->t < second->t ? *second : *first;
    report(lo, Status::double_point);
    r.t2 = hi.t;
    r.path = Path::bezout_pair;
    return r;
  }
  if (first) {
    report(*first, Status::ok);
    return r;
  }
  for (int i = 0; i < count; ++i)
    if (candidates[i].on_curve) {
      report(candidates[i], Status::outside_segment);
      return r;
    }

  // Off the curve (or every algebraic candidate failed): the nearest point of the segment.
  if (!options.refine && count > 0 && std::isfinite(candidates[0].t)) {
    report(candidates[0], Status::off_curve);  // --no-refine keeps the algebraic t
    return r;
  }
  double hint = -1.0;
  for (int i = 0; i < count; ++i)
    if (std::isfinite(candidates[i].t)) { hint = std::clamp(candidates[i].t, 0.0, 1.0); break; }
  Candidate nearest;
  nearest.t = detail::nearest_parameter_on_segment(plan, u0, v0, hint);
  nearest.distance = detail::distance(plan, u0, v0, nearest.t);
  nearest.path = Path::nearest;
  if (!std::isfinite(nearest.distance)) {
    r.status = Status::failed;
    r.reason = "no finite parameter found";
    return r;
  }
  // The algebra can miss a point that is on the segment (e.g. a coordinate constant along a
  // curve with separate denominators makes p vanish identically); the distance decides.
  report(nearest, nearest.distance <= tolerance ? Status::ok : Status::off_curve);
  return r;
}

namespace {

template <typename PlanOf>
void invert_range(std::size_t count, const InvertOptions& options, PlanOf&& body) {
  auto run = [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) body(i);
  };
  if (options.threads == 1 || count < 64) {
    run(tbb::blocked_range<std::size_t>(0, count));
    return;
  }
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] { tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 256), run); });
}

}  // namespace

void invert(const InversionPlan& plan, std::span<const Point> points, std::span<PointResult> results,
            const InvertOptions& options) {
  invert_range(points.size(), options,
               [&](std::size_t i) { results[i] = invert_point(plan, points[i], options); });
}

void invert(std::span<const InversionPlan> plans, std::span<const int> curve_of, std::span<const Point> points,
            std::span<PointResult> results, const InvertOptions& options) {
  invert_range(points.size(), options, [&](std::size_t i) {
    if (curve_of[i] >= 0) results[i] = invert_point(plans[curve_of[i]], points[i], options);
  });
}

}  // namespace bezinv
