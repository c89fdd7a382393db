#include "pipeline/decide.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "bezinv/bernstein.hpp"
#include "bezinv/null_vector.hpp"
#include "degree_drop.hpp"
#include "isolation.hpp"
#include "orthogonal_complement.hpp"
#include "pipeline/far_point.hpp"
#include "pipeline/point_polynomials.hpp"
#include "pipeline/projection.hpp"
#include "pipeline/sylvester_path.hpp"
#include "refine.hpp"

namespace bezinv::detail {
namespace {

// The tolerance relative to the normalized curve's diagonal, floor included.
double relative_tolerance(const PlanData& plan, double tolerance) { return tolerance / plan.normalized_diagonal; }

// How many singular values, from the smallest, are at most kSecondNullDirectionRatio sigma_1
// (sigma in decreasing order, n of them), whatever the tolerance: the directions between that and
// a larger tolerance's ratio are not near-null, and a pencil with them lost the second parameter
// that the plane gives (stress, --tol 1e-4, degree 15; docs/accuracy-model.md).
int numerical_nullity(const double* sigma, int n) {
  int k = 0;
  while (k < n && sigma[n - 1 - k] <= kSecondNullDirectionRatio * sigma[0]) ++k;
  return k;
}

// max_ij |B0| + |u0 Bx| + |v0 By| + |u0 v0 Bxy|: the size of B's terms before they cancel.
double bezout_term_size(const PlanData& plan, double u0, double v0) {
  double size = 0.0;
  const int nn = plan.degree * plan.degree;
  for (int i = 0; i < nn; ++i)
    size = std::max(size, std::abs(plan.B0[i]) + std::abs(u0 * plan.Bx[i]) + std::abs(v0 * plan.By[i]) +
                              (plan.common_denominator ? 0.0 : std::abs(u0 * v0 * plan.Bxy[i])));
  return size;
}

// Whether B(u0, v0), whose largest singular value is sigma_1, vanishes (kVanishingBezoutRatio):
// decided first against a bound of the terms' size from the plan's largest entries, which settles
// every point of a curve that is not a line without a pass over B.
bool bezout_vanishes(const PlanData& plan, double u0, double v0, double sigma_1) {
  const auto& m = plan.bezout_max_entries;
  const double bound = m[0] + std::abs(u0) * m[1] + std::abs(v0) * m[2] + std::abs(u0 * v0) * m[3];
  if (sigma_1 > kVanishingBezoutRatio * bound) return false;
  return !(sigma_1 > kVanishingBezoutRatio * bezout_term_size(plan, u0, v0));
}

// The real roots of a Bernstein polynomial r of degree n >= 1 (into t, room for n): the t with
// beta(t) orthogonal to r's coefficients, i.e. in the n-dimensional space r^perp, found as from
// any null space (parameters_from_null_space).
int bernstein_roots(std::span<const double> r, std::span<double> t) {
  const int size = static_cast<int>(r.size());
  if (size == 2) {  // linear: r0 (1 - t) + r1 t
    if (r[0] == r[1]) return 0;
    t[0] = r[0] / (r[0] - r[1]);
    return 1;
  }
  if (!(Eigen::Map<const Eigen::VectorXd>(r.data(), size).norm() > 0.0)) return 0;
  std::array<double, (kMaxDegree + 1) * kMaxDegree> perp;
  const auto perp_size = static_cast<std::size_t>(size) * (size - 1);
  orthogonal_complement(r, std::span<double>(perp.data(), perp_size));
  return parameters_from_null_space(std::span<const double>(perp.data(), perp_size), size - 1, t);
}

// Whether P0 is reached at t1 and t2 by separate branches of the curve: somewhere between them
// the curve leaves the tolerance of P0 (sampled at kBranchSamples interior parameters; a branch
// that passes slowly, or a cusp within the tolerance, stays inside).
bool separate_branches(const PlanData& plan, double u0, double v0, double t1, double t2, double tolerance) {
  for (int k = 1; k <= kBranchSamples; ++k) {
    const double t = t1 + (t2 - t1) * k / (kBranchSamples + 1);
    if (!(detail::distance(plan, u0, v0, t) <= tolerance)) return true;
  }
  return false;
}

}  // namespace

bool admit(const PlanData& plan, const Point& point, double u, double v, PointResult& r) {
  r = PointResult{};
  if (!std::isfinite(point.x) || !std::isfinite(point.y)) {
    r.status = Status::invalid_input;
    r.reason = "non-finite coordinate";
    return false;
  }
  if (!plan.usable) {
    r.status = Status::failed;
    r.reason = plan.reason;
    return false;
  }
  if (!std::isfinite(u) || !std::isfinite(v)) {
    answer_far_point(plan, point, r);
    return false;
  }
  return true;
}

void decide_with_gap(const PlanData& plan, BatchWorkspace& w, std::size_t l, const Candidate& c,
                     double tolerance, bool asked, PointResult& result) {
  const int n = plan.degree;
  const std::size_t stride = kBatchLanes;
  if (!c.on_segment) return;  // the off-curve path (off_curve_path.hpp), then the SVD path
  // Below the gap the SVD path looks for a second parameter in its near-null space, of dimension
  // 2 or more, from its exact singular vectors. The fast path's second vector is good only to
  // sigma_{n-1} / sigma_{n-2}: where a third singular value is small too (near a cusp at high
  // degree) the plane of z and it holds neither the second parameter nor a root near it, and a
  // double point was answered ok. So such a lane stays active, for the SVD path.
  const double gate = scaled_to_tolerance(kFastPathGapRatio, relative_tolerance(plan, tolerance));
  if (w.estimate[stride + l] >= gate || n < 3 ||
      (!asked && detail::isolated(plan, w.u[l], w.v[l], c.t, c.distance, tolerance))) {
    w.active[l] = 0;
    answer_fast(plan, c.t, c.distance, w.estimate[l], w.estimate[stride + l], result);
  }
}

void decide(const PlanData& plan, double u0, double v0, const Candidate& main, const double* sigma,
            const double* V, const InvertOptions& options, PointResult& r) {
  const int n = plan.degree;
  const double tolerance = normalized_tolerance(plan, options);
  std::array<Candidate, kMaxDegree + 4> candidates;
  int count = 0;
  if (std::isfinite(main.t) || main.path != Path::none) candidates[count++] = main;
  auto add = [&](double t, Path path) {
    if (count < static_cast<int>(candidates.size()))
      candidates[count++] = settle(plan, u0, v0, t, path, tolerance, options.refine);
  };

  const bool have_svd = n >= 2 && sigma[0] > 0 && std::isfinite(sigma[0]);
  if (have_svd) {
    r.sigma_min = sigma[n - 1] / sigma[0];
    r.sigma_next = sigma[n - 2] / sigma[0];
  }
  const double second_ratio = scaled_to_tolerance(kSecondNullDirectionRatio, relative_tolerance(plan, tolerance));
  const bool look_for_second = have_svd && n >= 3 && r.sigma_next <= second_ratio;
  const PointPolynomials pq = point_polynomials(plan, u0, v0);
  const bool drop = n >= 2 && detail::degree_drops(plan, u0, v0);
  // B vanishes (a straight line through the point): its singular values are rounding, and say
  // nothing of how many parameters there are.
  const bool vanishes = n >= 2 && bezout_vanishes(plan, u0, v0, sigma[0]);
  const bool settled = count > 0 && candidates[0].on_segment && !look_for_second && !drop && !vanishes;
  if (!settled) {
    if (drop) add(sylvester_parameter(pq), Path::sylvester);
    if (vanishes) {
      // B vanishes: p and q are proportional, the curve is a straight line through the point
      // (traced at degree n), and each real root of p (or q) is a parameter.
      std::array<double, kMaxDegree> t;
      const double p_size = power_leading_bound(pq.p_span()), q_size = power_leading_bound(pq.q_span());
      const int roots = bernstein_roots(p_size >= q_size ? pq.p_span() : pq.q_span(), t);
      for (int i = 0; i < roots; ++i) add(t[i], Path::bezout_pair);
    } else if (have_svd && n >= 3) {
      // Nullity 2 (self-intersection, or a root driven towards infinity): both parameters from
      // the span of the two last singular vectors. Nullity k > 2 (several parameters over C, or
      // an ill-conditioned B): every real one from the span of the k last.
      const int k = std::min(numerical_nullity(sigma, n), std::min(kMaxNullSpaceDimension, n - 1));
      std::array<double, kMaxDegree> t;
      auto add_roots = [&](int roots) {
        for (int i = 0; i < roots; ++i) add(t[i], Path::bezout_pair);
      };
      // The parameters whose Bernstein vector lies in the plane of the two last singular vectors.
      auto plane_roots = [&] {
        return parameters_from_null_space(std::span<const double>(V + (n - 1) * n, n),
                                          std::span<const double>(V + (n - 2) * n, n), t.data());
      };
      const int roots =
          k <= 2 ? plane_roots()
                 : parameters_from_null_space(std::span<const double>(V + (n - k) * n, static_cast<std::size_t>(k) * n),
                                              k, t);
      add_roots(roots);
      // Near a cusp with a small loop (two parameters of a double point close together) a third
      // singular value can fall below the threshold too, and the roots of the k-dimensional space
      // miss the second parameter that the plane of the two last singular vectors gives (stress:
      // 20 such points of one degree-8 curve answered ok). Its roots are candidates as well.
      if (k > 2 && roots < 2) add_roots(plane_roots());
    }
  }

  // On the segment at two distinct parameters of separate branches: a double point. Two
  // parameters of one branch (the curve between them stays within the tolerance: it passes
  // slowly, or turns at a cusp near the point) are one answer, the nearer.
  const Candidate* first = nullptr;
  const Candidate* second = nullptr;
  for (int i = 0; i < count; ++i) {
    const Candidate& c = candidates[i];
    if (!c.on_segment) continue;
    if (!first) { first = &c; continue; }
    if (std::abs(c.t - first->t) <= kDistinctParameterGap) continue;
    if (!separate_branches(plan, u0, v0, first->t, c.t, tolerance)) {
      if (c.distance < first->distance) first = &c;
      continue;
    }
    if (!second || c.distance < second->distance) second = &c;
  }
  if (second && !separate_branches(plan, u0, v0, first->t, second->t, tolerance)) second = nullptr;
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
    return;
  }
  if (first) return report(*first, Status::ok);
  for (int i = 0; i < count; ++i)
    if (candidates[i].on_curve) {
      // The extension passes within the tolerance; the segment may too, at a parameter no
      // candidate led to (a huge end weight holds the segment near P(0) over a range of t that
      // B's null vector does not single out). On the segment wins.
      if (options.refine) {
        Candidate nearest;
        nearest.t = detail::nearest_parameter_on_segment(plan, u0, v0, std::clamp(candidates[i].t, 0.0, 1.0));
        nearest.distance = detail::distance(plan, u0, v0, nearest.t);
        nearest.path = Path::nearest;
        if (nearest.distance <= tolerance) return report(nearest, Status::ok);
      }
      return report(candidates[i], Status::outside_segment);
    }

  // Off the curve (or every algebraic candidate failed): the nearest point of the segment.
  // Off the curve by projection where asked for and the formula is valid at the point.
  auto report_off_curve = [&](const Candidate& c) {
    report(c, Status::off_curve);
    if (projects_off_curve(plan, options)) project_off_curve(plan, u0, v0, tolerance, r);
  };
  if (!options.refine && count > 0 && std::isfinite(candidates[0].t))
    return report_off_curve(candidates[0]);  // --no-refine keeps the algebraic t
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
    return;
  }
  // The algebra can miss a point that is on the segment (e.g. a coordinate constant along a
  // curve with separate denominators makes p vanish identically); the distance decides.
  if (nearest.distance <= tolerance) return report(nearest, Status::ok);
  report_off_curve(nearest);
}

}  // namespace bezinv::detail
