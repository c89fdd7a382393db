#include "bezinv/curve.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "bezinv/bernstein.hpp"
#include "bezinv/nurbs.hpp"
#include "bezinv/tolerances.hpp"
#include "piecewise/homogeneous_spline.hpp"
#include "piecewise/piecewise_validation.hpp"
#include "quote.hpp"

namespace bezinv {

const char* to_string(CurveKind kind) {
  switch (kind) {
    case CurveKind::bezier: return "bezier";
    case CurveKind::rational_bezier: return "rational_bezier";
    case CurveKind::rational: return "rational";
    case CurveKind::nurbs: return "nurbs";
    case CurveKind::composite: return "composite";
  }
  return "?";
}

int Curve::degree() const {
  if (kind == CurveKind::nurbs) return spline_degree;
  if (kind == CurveKind::composite) {
    int highest = 0;
    for (const Curve& c : curves) highest = std::max(highest, c.degree());
    return highest;
  }
  return static_cast<int>(x_num.size()) - 1;
}

std::array<double, 2> Curve::point(double t) const {
  if (piecewise(*this)) {
    const auto p = point3(t);
    return {p[0], p[1]};
  }
  return {bernstein_value(x_num, t) / bernstein_value(x_den, t),
          bernstein_value(y_num, t) / bernstein_value(y_den, t)};
}

std::array<double, 3> Curve::point3(double t) const {
  if (kind == CurveKind::nurbs) {
    const auto q = detail::de_boor(detail::homogeneous_spline(*this), t);
    return {q[0] / q[3], q[1] / q[3], dimension() == 3 ? q[2] / q[3] : 0.0};
  }
  if (kind == CurveKind::composite) {
    // Curve k covers [k, k + 1] (a nurbs curve's domain normalized to it); beyond the ends, the end
    // curves' extensions.
    const double last = static_cast<double>(curves.size() - 1);
    const double k = std::clamp(std::floor(t), 0.0, last);
    const Curve& part = curves[static_cast<std::size_t>(k)];
    const auto [a, b] = parameter_domain(part);
    return part.point3(a + (t - k) * (b - a));
  }
  return {bernstein_value(x_num, t) / bernstein_value(x_den, t), bernstein_value(y_num, t) / bernstein_value(y_den, t),
          dimension() == 3 ? bernstein_value(z_num, t) / bernstein_value(z_den, t) : 0.0};
}

Curve Curve::space_bezier(std::string id, const std::vector<std::array<double, 3>>& points) {
  std::vector<std::array<double, 2>> xy;
  for (const auto& p : points) xy.push_back({p[0], p[1]});
  Curve c = bezier(std::move(id), xy);
  for (const auto& p : points) c.z_num.push_back(p[2]);
  c.z_den = c.x_den;
  return c;
}

Curve Curve::space_rational_bezier(std::string id, const std::vector<std::array<double, 3>>& points,
                                   const std::vector<double>& weights) {
  std::vector<std::array<double, 2>> xy;
  for (const auto& p : points) xy.push_back({p[0], p[1]});
  Curve c = rational_bezier(std::move(id), xy, weights);
  for (std::size_t i = 0; i < points.size(); ++i) c.z_num.push_back(weights[i] * points[i][2]);
  c.z_den = weights;
  return c;
}

Curve Curve::space_rational(std::string id, std::vector<double> x_num, std::vector<double> x_den,
                            std::vector<double> y_num, std::vector<double> y_den, std::vector<double> z_num,
                            std::vector<double> z_den) {
  Curve c = rational(std::move(id), std::move(x_num), std::move(x_den), std::move(y_num), std::move(y_den));
  c.z_num = std::move(z_num);
  c.z_den = std::move(z_den);
  return c;
}

Curve Curve::nurbs(std::string id, int degree, std::vector<double> knots,
                   const std::vector<std::array<double, 2>>& points, const std::vector<double>& weights) {
  std::vector<std::array<double, 3>> xyz;
  for (const auto& p : points) xyz.push_back({p[0], p[1], 0.0});
  Curve c = space_nurbs(std::move(id), degree, std::move(knots), xyz, weights);
  c.z_num.clear();
  c.z_den.clear();
  return c;
}

Curve Curve::space_nurbs(std::string id, int degree, std::vector<double> knots,
                         const std::vector<std::array<double, 3>>& points, const std::vector<double>& weights) {
  Curve c;
  c.id = std::move(id);
  c.kind = CurveKind::nurbs;
  c.spline_degree = degree;
  c.knots = std::move(knots);
  if (!weights.empty() && weights.size() != points.size())
    throw CurveError("curve " + detail::quoted_excerpt(c.id) + ": weights: " + std::to_string(weights.size()) +
                     " weights for " + std::to_string(points.size()) + " points");
  for (std::size_t i = 0; i < points.size(); ++i) {
    // Homogeneous form, as rational_bezier's: the numerators carry w_i P_i.
    const double w = weights.empty() ? 1.0 : weights[i];
    c.x_num.push_back(w * points[i][0]);
    c.y_num.push_back(w * points[i][1]);
    c.z_num.push_back(w * points[i][2]);
    c.x_den.push_back(w);
  }
  c.y_den = c.x_den;
  c.z_den = c.x_den;
  return c;
}

Curve Curve::composite(std::string id, std::vector<Curve> curves) {
  Curve c;
  c.id = std::move(id);
  c.kind = CurveKind::composite;
  c.curves = std::move(curves);
  return c;
}

Curve Curve::bezier(std::string id, const std::vector<std::array<double, 2>>& points) {
  Curve c;
  c.id = std::move(id);
  c.kind = CurveKind::bezier;
  for (const auto& p : points) {
    c.x_num.push_back(p[0]);
    c.y_num.push_back(p[1]);
  }
  c.x_den.assign(points.size(), 1.0);
  c.y_den = c.x_den;
  return c;
}

Curve Curve::rational_bezier(std::string id, const std::vector<std::array<double, 2>>& points,
                             const std::vector<double>& weights) {
  Curve c;
  c.id = std::move(id);
  c.kind = CurveKind::rational_bezier;
  if (weights.size() != points.size())
    throw CurveError("curve " + detail::quoted_excerpt(c.id) + ": weights: " + std::to_string(weights.size()) +
                     " weights for " + std::to_string(points.size()) + " points");
  for (std::size_t i = 0; i < points.size(); ++i) {
    // Homogeneous form: the numerators carry w_i a_i, so P = X/W with one denominator W.
    c.x_num.push_back(weights[i] * points[i][0]);
    c.y_num.push_back(weights[i] * points[i][1]);
  }
  c.x_den = weights;
  c.y_den = weights;
  return c;
}

Curve Curve::rational(std::string id, std::vector<double> x_num, std::vector<double> x_den,
                      std::vector<double> y_num, std::vector<double> y_den) {
  Curve c;
  c.id = std::move(id);
  c.kind = CurveKind::rational;
  c.x_num = std::move(x_num);
  c.x_den = std::move(x_den);
  c.y_num = std::move(y_num);
  c.y_den = std::move(y_den);
  return c;
}

namespace {

// True when the Bernstein polynomial has a root on [0,1] (or comes within round-off of one).
// Bernstein coefficients of one strict sign bound the polynomial away from zero (convex hull
// property); otherwise subdivide at 1/2 (de Casteljau) and look at each half. A sign change of
// the values at the ends of a piece is a root; a piece still undecided after 40 halvings
// (width 1e-12) is a double root or a root within round-off: reported as a root too.
bool has_root_on_unit_interval(const std::vector<double>& coefficients) {
  struct Piece { std::vector<double> c; int depth; };
  std::vector<Piece> stack{{coefficients, 0}};
  while (!stack.empty()) {
    Piece piece = std::move(stack.back());
    stack.pop_back();
    const auto& c = piece.c;
    bool all_positive = true, all_negative = true;
    for (double v : c) {
      all_positive = all_positive && v > 0;
      all_negative = all_negative && v < 0;
    }
    if (all_positive || all_negative) continue;
    if (c.front() == 0.0 || c.back() == 0.0) return true;
    if ((c.front() > 0) != (c.back() > 0)) return true;
    if (piece.depth >= kDenominatorRootHalvings) return true;
    // Split at 1/2: the left half's coefficients are the first points of each de Casteljau
    // level, the right half's the last ones.
    const int n = static_cast<int>(c.size()) - 1;
    std::vector<double> left(n + 1), right(n + 1), work = c;
    left[0] = work[0];
    right[n] = work[n];
    for (int r = 1; r <= n; ++r) {
      for (int i = 0; i <= n - r; ++i) work[i] = 0.5 * (work[i] + work[i + 1]);
      left[r] = work[0];
      right[n - r] = work[n - r];
    }
    stack.push_back({std::move(left), piece.depth + 1});
    stack.push_back({std::move(right), piece.depth + 1});
  }
  return false;
}

}  // namespace

void validate(const Curve& curve) {
  // The id may come from a file: escaped and cut short like any file content in a message.
  const std::string who = "curve " + detail::quoted_excerpt(curve.id) + ": ";
  if (curve.kind == CurveKind::nurbs) return detail::validate_nurbs(curve, who);
  if (curve.kind == CurveKind::composite) return detail::validate_composite(curve, who);
  const std::size_t size = curve.x_num.size();
  if (size < 2)
    throw CurveError(who + "degree must be at least 1 (" + std::to_string(size) + " coefficients given)");
  if (static_cast<int>(size) - 1 > kMaxDegree)
    throw CurveError(who + "degree " + std::to_string(size - 1) + " exceeds the maximum " +
                     std::to_string(kMaxDegree));
  const std::pair<const char*, const std::vector<double>*> fields[] = {
      {"x_num", &curve.x_num}, {"x_den", &curve.x_den}, {"y_num", &curve.y_num},
      {"y_den", &curve.y_den}, {"z_num", &curve.z_num}, {"z_den", &curve.z_den}};
  for (const auto& [name, values] : fields) {
    if (values == &curve.z_num && curve.dimension() == 2) break;  // a plane curve has no z
    if (values->size() != size)
      throw CurveError(who + name + ": " + std::to_string(values->size()) + " coefficients, expected " +
                       std::to_string(size) + " (one common degree)");
    for (std::size_t i = 0; i < size; ++i)
      if (!std::isfinite((*values)[i]))
        throw CurveError(who + name + "[" + std::to_string(i) + "] is not a finite number");
  }
  const char* den_field = curve.kind == CurveKind::rational ? "x_den" : "weights";
  if (has_root_on_unit_interval(curve.x_den))
    throw CurveError(who + den_field + ": the denominator has a root on [0,1] (the curve has a pole on its segment)");
  if (curve.kind == CurveKind::rational && has_root_on_unit_interval(curve.y_den))
    throw CurveError(who + "y_den: the denominator has a root on [0,1] (the curve has a pole on its segment)");
  if (curve.kind == CurveKind::rational && curve.dimension() == 3 && has_root_on_unit_interval(curve.z_den))
    throw CurveError(who + "z_den: the denominator has a root on [0,1] (the curve has a pole on its segment)");
}

}  // namespace bezinv
