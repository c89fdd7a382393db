#include "piecewise/piecewise_validation.hpp"

#include <charconv>
#include <cmath>
#include <string_view>
#include <utility>

#include "bezinv/nurbs.hpp"
#include "bezinv/tolerances.hpp"
#include "piecewise/control_box.hpp"
#include "quote.hpp"

namespace bezinv::detail {
namespace {

// The shortest text that reads back as the same double.
std::string number_text(double x) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, x).ptr;
  return std::string(text, end);
}

std::string field(const char* name, std::size_t i) { return std::string(name) + "[" + std::to_string(i) + "]"; }

std::string point_text(const std::array<double, 3>& p, int dimension) {
  std::string s = "(" + number_text(p[0]) + ", " + number_text(p[1]);
  if (dimension == 3) s += ", " + number_text(p[2]);
  return s + ")";
}

}  // namespace

void validate_nurbs(const Curve& c, const std::string& who) {
  const int p = c.spline_degree;
  const std::size_t count = c.x_num.size();
  if (p < 1) throw CurveError(who + "degree: must be at least 1 (got " + std::to_string(p) + ")");
  if (p > kMaxDegree)
    throw CurveError(who + "degree: " + std::to_string(p) + " exceeds the maximum " + std::to_string(kMaxDegree));
  if (count < static_cast<std::size_t>(p) + 1)
    throw CurveError(who + "points: " + std::to_string(count) + " for degree " + std::to_string(p) +
                     " (need at least degree + 1 = " + std::to_string(p + 1) + ")");
  const std::pair<const char*, const std::vector<double>*> lists[] = {
      {"x_num", &c.x_num}, {"y_num", &c.y_num}, {"weights", &c.x_den}, {"y_den", &c.y_den},
      {"z_num", &c.z_num}, {"z_den", &c.z_den}};
  for (const auto& [name, values] : lists) {
    if (values == &c.z_num && c.dimension() == 2) break;
    if (values->size() != count)
      throw CurveError(who + name + ": " + std::to_string(values->size()) + " values for " + std::to_string(count) +
                       " control points");
    for (std::size_t i = 0; i < count; ++i)
      if (!std::isfinite((*values)[i])) throw CurveError(who + field(name, i) + " is not a finite number");
  }
  for (std::size_t i = 0; i < count; ++i)
    if (!(c.x_den[i] > 0) || c.y_den[i] != c.x_den[i] || (c.dimension() == 3 && c.z_den[i] != c.x_den[i]))
      throw CurveError(who + field("weights", i) + ": " + number_text(c.x_den[i]) +
                       " is not positive (a NURBS curve's weights are)");
  const std::vector<double>& U = c.knots;
  if (U.size() != count + p + 1)
    throw CurveError(who + "knots: " + std::to_string(U.size()) + " knots for " + std::to_string(count) +
                     " points of degree " + std::to_string(p) + " (need points + degree + 1 = " +
                     std::to_string(count + p + 1) + ")");
  for (std::size_t i = 0; i < U.size(); ++i) {
    if (!std::isfinite(U[i])) throw CurveError(who + field("knots", i) + " is not a finite number");
    if (i > 0 && U[i] < U[i - 1])
      throw CurveError(who + field("knots", i) + ": " + number_text(U[i]) + " is less than " + field("knots", i - 1) +
                       " = " + number_text(U[i - 1]) + " (knots must not decrease)");
  }
  const std::size_t last = U.size() - 1 - static_cast<std::size_t>(p);
  if (!(U[p] < U[last]))
    throw CurveError(who + "knots: the domain [" + field("knots", static_cast<std::size_t>(p)) + ", " +
                     field("knots", last) + "] = [" + number_text(U[p]) + ", " + number_text(U[last]) + "] is empty");
  // A knot inside the domain repeated more than p times breaks the curve there (its spans need not
  // meet); more than p + 1 anywhere leaves a basis function that is zero everywhere.
  for (std::size_t i = 0; i < U.size();) {
    std::size_t j = i;
    while (j < U.size() && U[j] == U[i]) ++j;
    const std::size_t multiplicity = j - i;
    const bool inside = U[i] > U[p] && U[i] < U[last];
    if (multiplicity > static_cast<std::size_t>(p) + 1 || (inside && multiplicity > static_cast<std::size_t>(p)))
      throw CurveError(who + field("knots", i) + ": " + number_text(U[i]) + " repeated " + std::to_string(multiplicity) +
                       " times, more than " + (inside ? "the degree inside the domain (the curve would break there)"
                                                      : "degree + 1"));
    i = j;
  }
}

void validate_composite(const Curve& c, const std::string& who) {
  if (c.curves.empty()) throw CurveError(who + "curves: empty list (need at least one curve)");
  for (std::size_t i = 0; i < c.curves.size(); ++i) {
    const Curve& part = c.curves[i];
    const std::string name = field("curves", i);
    if (part.kind == CurveKind::composite)
      throw CurveError(who + name + ": kind composite inside a composite (list its curves in this one instead)");
    if (part.dimension() != c.curves.front().dimension())
      throw CurveError(who + name + ": a " + (part.dimension() == 3 ? "space" : "plane") + " curve, but curves[0] is a " +
                       (part.dimension() == 3 ? "plane" : "space") + " curve (a composite is plane or space throughout)");
    try {
      validate(part);
    } catch (const CurveError& e) {
      // validate() names the part by its own id; the composite's field names it here.
      std::string_view message(e.what());
      const std::string own = "curve " + quoted_excerpt(part.id) + ": ";
      if (message.starts_with(own)) message.remove_prefix(own.size());
      throw CurveError(who + name + ": " + std::string(message));
    }
  }
  const ControlBox box = control_box(c);
  const double allowed = kCompositeJointGap * box.diagonal();
  for (std::size_t i = 1; i < c.curves.size(); ++i) {
    const Curve& before = c.curves[i - 1];
    const Curve& part = c.curves[i];
    const auto end = before.point3(parameter_domain(before)[1]), start = part.point3(parameter_domain(part)[0]);
    const double gap = std::hypot(start[0] - end[0], start[1] - end[1], start[2] - end[2]);
    if (!(gap <= allowed))
      throw CurveError(who + field("curves", i) + ": starts at " + point_text(start, c.dimension()) + " but " +
                       field("curves", i - 1) + " ends at " + point_text(end, c.dimension()) + ", a gap of " +
                       number_text(gap) + " (more than " + number_text(kCompositeJointGap) +
                       " of the bounding box diagonal " + number_text(box.diagonal()) + ")");
  }
}

}  // namespace bezinv::detail
