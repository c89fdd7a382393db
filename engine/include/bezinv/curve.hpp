#pragma once
// A plane rational curve in Bernstein form on [0,1]:
//     x(t) = x_num(t) / x_den(t),   y(t) = y_num(t) / y_den(t),
// all four of one common degree n. The three kinds users write are all stored this way:
//   bezier           x_num = a_i, y_num = b_i, x_den = y_den = 1
//   rational_bezier  x_num = w_i a_i, y_num = w_i b_i, x_den = y_den = w_i
//   rational         the four lists as given (paper Sect. 4: separate denominators)
// Two kinds are piecewise, inverted through their rational Bezier spans (bezinv/nurbs.hpp):
//   nurbs            x_num = w_i a_i, y_num = w_i b_i, x_den = y_den = w_i are the B-spline control
//                    points in homogeneous form (as rational_bezier's), `knots` the knot vector
//   composite        `curves`, joined end to end; the Bernstein lists are empty
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace bezinv {

enum class CurveKind { bezier, rational_bezier, rational, nurbs, composite };

const char* to_string(CurveKind kind);

struct Curve {
  std::string id;
  CurveKind kind = CurveKind::bezier;
  std::vector<double> x_num, x_den, y_num, y_den;  // n+1 Bernstein coefficients each
  // A space curve's third coordinate z = z_num / z_den, stored as x and y are (bezier: z_den = 1;
  // rational_bezier: w_i c_i over w_i). Empty for a plane curve.
  std::vector<double> z_num, z_den;
  // nurbs: the degree p of its B-splines, and the knot vector: (control points) + p + 1
  // non-decreasing numbers. 0 and empty otherwise.
  int spline_degree = 0;
  std::vector<double> knots{};
  // composite: the curves joined end to end (of the other kinds). Empty otherwise.
  std::vector<Curve> curves{};

  // The polynomial degree (nurbs: of its B-splines; composite: the highest of its curves').
  int degree() const;
  int dimension() const {
    if (kind == CurveKind::composite) return curves.empty() ? 2 : curves.front().dimension();
    return z_num.empty() && z_den.empty() ? 2 : 3;
  }
  // True when x_den == y_den (== z_den) coefficient by coefficient (then B(x0,y0) is affine in (x0,y0)).
  bool common_denominator() const { return x_den == y_den && (dimension() == 2 || z_den == x_den); }

  // P(t) of a plane curve (x and y of a space curve). Valid for t outside [0,1] too (the curve's
  // extension), NaN where a denominator is 0. For nurbs t is the knot parameter (de Boor; outside
  // the domain the end spans' extensions), for composite segment index + local parameter
  // (bezinv/nurbs.hpp, parameter_domain).
  std::array<double, 2> point(double t) const;
  // P(t) in space (z = 0 for a plane curve).
  std::array<double, 3> point3(double t) const;

  static Curve bezier(std::string id, const std::vector<std::array<double, 2>>& points);
  static Curve rational_bezier(std::string id, const std::vector<std::array<double, 2>>& points,
                               const std::vector<double>& weights);
  static Curve rational(std::string id, std::vector<double> x_num, std::vector<double> x_den,
                        std::vector<double> y_num, std::vector<double> y_den);
  // Space curves, the same kinds with control points [x, y, z] (kind rational: z_num, z_den too).
  static Curve space_bezier(std::string id, const std::vector<std::array<double, 3>>& points);
  static Curve space_rational_bezier(std::string id, const std::vector<std::array<double, 3>>& points,
                                     const std::vector<double>& weights);
  static Curve space_rational(std::string id, std::vector<double> x_num, std::vector<double> x_den,
                              std::vector<double> y_num, std::vector<double> y_den, std::vector<double> z_num,
                              std::vector<double> z_den);
  // A NURBS curve of the given degree: knots.size() == points.size() + degree + 1; weights empty
  // for a polynomial B-spline (every weight 1), else one positive weight per point.
  static Curve nurbs(std::string id, int degree, std::vector<double> knots,
                     const std::vector<std::array<double, 2>>& points, const std::vector<double>& weights = {});
  static Curve space_nurbs(std::string id, int degree, std::vector<double> knots,
                           const std::vector<std::array<double, 3>>& points, const std::vector<double>& weights = {});
  // Curves of the other kinds joined end to end: curve k covers parameters [k, k + 1].
  static Curve composite(std::string id, std::vector<Curve> curves);
};

// A curve that cannot be used at all. what() names the curve and the field.
class CurveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws CurveError unless: every number finite, degree 1..kMaxDegree, the four lists of one
// length, and no denominator with a root on [0,1] (a pole inside the segment). A nurbs curve: a
// knot vector of points + degree + 1 non-decreasing knots with a non-empty domain, no knot inside
// it repeated more than degree times, positive weights. A composite: at least one curve, none
// composite, all plane or all space, each valid, each starting where the one before ends (within
// kCompositeJointGap of the bounding-box diagonal). The message names the field (knots[3],
// curves[1]).
void validate(const Curve& curve);

}  // namespace bezinv
