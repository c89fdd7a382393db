#include "bezinv/inversion_formula.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "bezinv/tolerances.hpp"
#include "formula/homogeneous_curve.hpp"
#include "formula/null_space.hpp"
#include "plan_data.hpp"
#include "quote.hpp"

namespace bezinv {
namespace {

using detail::HomogeneousCurve;

// The terms of a degree-d polynomial at a homogeneous point, as a row of length size(d).
Eigen::RowVectorXd terms_at(int d, const std::array<double, 3>& h) {
  Eigen::RowVectorXd row(PlanePolynomial::size(d));
  PlanePolynomial::homogeneous_terms(d, h[0], h[1], h[2], {row.data(), static_cast<std::size_t>(row.size())});
  return row;
}

// The formula's degree for a curve of degree n.
int formula_degree(int n) { return std::max(1, n - 2); }

// The dimension of the space of (N, M) for a faithful curve of degree n: 2 (d + 1)(d + 2) / 2
// unknowns, n d + 2 independent conditions.
int solution_dimension(int n) {
  const int d = formula_degree(n);
  return (d + 1) * (d + 2) - (n * d + 2);
}

}  // namespace

namespace {

// The formulae are Wang & Joe's, for plane curves. A space curve's plan holds its projection's
// plane plan (engine/src/space/), whose formula would say nothing about the curve itself.
const detail::PlanData& plane_plan_data(const InversionPlan& plan) {
  if (plan.dimension() != 2)
    throw FormulaError("curve " + detail::quoted_excerpt(plan.curve().id) +
                       " is a space curve: inversion formulae, implicit equations and singular points are for plane curves");
  if (detail::plan_data(plan).piecewise)
    throw FormulaError("curve " + detail::quoted_excerpt(plan.curve().id) + " is a " + to_string(plan.curve().kind) +
                       " curve: inversion formulae, implicit equations and singular points are for one rational Bezier curve");
  return detail::plan_data(plan);
}

}  // namespace

InversionFormula::InversionFormula(const InversionPlan& plan, const FormulaChoice& choice)
    : InversionFormula(plane_plan_data(plan), choice) {}

InversionFormula::InversionFormula(const detail::PlanData& data, const FormulaChoice& choice) {
  if (!data.usable) throw FormulaError(std::string("no inversion formula: ") + data.reason);
  const detail::FrameCurve framed = detail::formula_curve(data);
  const HomogeneousCurve& curve = framed.curve;
  const int parametrization_degree = curve.degree();

  // With t = b / (a + b) and the homogeneous point Q(a, b) = (a + b)^D P(t), the condition times
  // (a + b) is (a + b) N(Q) - b M(Q) = 0, finite at t = infinity too. For N and M of degree d it
  // is a polynomial of degree D d + 1 in t: sampled at twice the D d + 2 points that fix it.
  auto sampled_system = [&](int d, std::vector<detail::CurveSample>& samples) {
    const int m = PlanePolynomial::size(d), rows = 2 * (parametrization_degree * d + 2);
    samples = detail::curve_samples(curve, rows);
    Eigen::MatrixXd system(rows, 2 * m);
    for (int k = 0; k < rows; ++k) {
      const auto& sample = samples[static_cast<std::size_t>(k)];
      const Eigen::RowVectorXd phi = terms_at(d, sample.point);
      system.row(k) << (sample.a + sample.b) * phi, -sample.b * phi;
      system.row(k).normalize();
    }
    return system;
  };
  // The curve's degree is the parametrization's: the plan has taken out what it can (an exact
  // common factor, a degree elevation). A curve traced more than once has no formula: no
  // solution, or (where N and M may be multiples of its implicit equation) only solutions with
  // M = 0 all along the curve, which the check below refuses.
  const int n = parametrization_degree;
  if (n > kMaxFormulaCurveDegree)
    throw FormulaError("no inversion formula computed: degree " + std::to_string(n) + " (with separate denominators, "
                       "twice the curve's) is past " + std::to_string(kMaxFormulaCurveDegree));
  std::vector<detail::CurveSample> samples;
  const detail::NullSpace space = detail::null_space(sampled_system(formula_degree(n), samples), solution_dimension(n));
  const int d = formula_degree(n), m = PlanePolynomial::size(d), rows = static_cast<int>(samples.size());
  const int dimension = solution_dimension(n);
  curve_degree_ = n;
  null_ratio_ = space.null_ratio;
  next_ratio_ = space.next_ratio;
  // Rounding leaves ~1e-16 .. 1e-12 here; a curve traced more than once (no formula) leaves the
  // smallest singular values of a full rank system, ~1e-4 or more.
  if (!(space.null_ratio <= kFormulaNullRatio))
    throw FormulaError("no inversion formula: the curve is not faithfully parametrized (its points have more than "
                       "one parameter; smallest singular value ratio " + std::to_string(space.null_ratio) + ")");

  // The choice within the space: linear conditions C c = 0 on the coefficients c = (N, M).
  std::vector<Eigen::RowVectorXd> conditions;
  auto base_point = [&](double s) {
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(2 * m);
    if (std::isinf(s))
      row.head(m) = terms_at(d, curve.at_infinity());  // N(P(inf)) = 0 (M(P(inf)) = 0 always)
    else
      row.tail(m) = terms_at(d, curve.at(s));  // M(P(s)) = 0, and so N(P(s)) = 0
    conditions.push_back(row);
  };
  if (n == 1) {
    // The centre at infinity normal to the line: both N and M vanish there, so every line of the
    // pencil is perpendicular to the curve and N / M is the orthogonal projection.
    const auto a = curve.at(0.0), b = curve.at(1.0);
    const double du = b[0] / b[2] - a[0] / a[2], dv = b[1] / b[2] - a[1] / a[2];
    const std::array<double, 3> normal{-dv, du, 0.0};
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(2 * m);
    row.head(m) = terms_at(d, normal);
    conditions.push_back(row);
    row.setZero();
    row.tail(m) = terms_at(d, normal);
    conditions.push_back(row);
  } else if (n == 2) {
    if (choice.base_parameters.size() > 1)
      throw FormulaError("a conic's formula has one free choice, its centre: give one parameter");
    base_point(choice.base_parameters.empty() ? std::numeric_limits<double>::infinity() : choice.base_parameters[0]);
  } else {
    if (static_cast<int>(choice.base_parameters.size()) > dimension - 1)
      throw FormulaError("the formula of a curve of degree " + std::to_string(n) + " has " +
                         std::to_string(dimension - 1) + " free base point(s); " +
                         std::to_string(choice.base_parameters.size()) + " given");
    for (double s : choice.base_parameters) base_point(s);
  }

  // a: the combination of the space's basis Z with C Z a = 0; where the conditions leave more
  // than one, the one maximizing sum_k M(P(t_k))^2 over the samples (|a| = 1).
  const Eigen::MatrixXd& basis = space.basis;  // 2m x dimension
  Eigen::MatrixXd free = Eigen::MatrixXd::Identity(dimension, dimension);
  if (!conditions.empty()) {
    Eigen::MatrixXd c(static_cast<Eigen::Index>(conditions.size()), 2 * m);
    for (std::size_t i = 0; i < conditions.size(); ++i) c.row(static_cast<Eigen::Index>(i)) = conditions[i].normalized();
    const int left = dimension - static_cast<int>(conditions.size());
    const detail::NullSpace within = detail::null_space(c * basis, left);
    if (!(within.next_ratio > kFormulaChoiceRatio))
      throw FormulaError("the base points asked for do not fix the formula (two of them coincide, or one is the "
                         "curve's singular point)");
    free = within.basis;
  }
  Eigen::VectorXd a;
  if (free.cols() == 1) {
    a = free.col(0);
  } else {
    // M on the segment's samples only (the first half): where the engine evaluates N / M.
    const int on_segment = (rows + 1) / 2;
    Eigen::MatrixXd g(on_segment, free.cols());
    for (int k = 0; k < on_segment; ++k)
      g.row(k) = terms_at(d, samples[static_cast<std::size_t>(k)].point) * basis.bottomRows(m) * free;
    a = free * detail::largest_right_singular_vector(g);
  }
  Eigen::VectorXd c = basis * a;
  // A line traced more than once has solutions with N and M multiples of the line's equation:
  // M then vanishes all along the curve, and N / M gives no parameter.
  {
    // Against the size of the terms with the coefficients' scale (c is scaled just below to
    // largest 1; here its largest is |c|_inf).
    double largest_m = 0.0, size = 0.0;
    const double scale = c.cwiseAbs().maxCoeff();
    for (int k = 0; k < rows; ++k) {
      const Eigen::RowVectorXd phi = terms_at(d, samples[static_cast<std::size_t>(k)].point);
      largest_m = std::max(largest_m, std::abs(phi.dot(c.tail(m))));
      size = std::max(size, phi.cwiseAbs().sum() * scale);
    }
    if (!(largest_m > kFormulaNullRatio * size))
      throw FormulaError("no inversion formula: the curve is not faithfully parametrized (a line traced more than once)");
  }
  // Scale: the largest coefficient 1 and, of M's, the largest positive (one formula, one print).
  const Eigen::Index largest = [&] {
    Eigen::Index i = 0;
    c.tail(m).cwiseAbs().maxCoeff(&i);
    return i;
  }();
  c /= c.cwiseAbs().maxCoeff() * (c(m + largest) < 0 ? -1.0 : 1.0);
  const PlaneFrame& frame = framed.frame;
  numerator_ = PlanePolynomial(d, frame, {c.data(), c.data() + m});
  denominator_ = PlanePolynomial(d, frame, {c.data() + m, c.data() + 2 * m});
  constexpr int kCheckedParameters = 64;
  for (int k = 0; k < kCheckedParameters; ++k) {
    const double t = 0.5 - 0.5 * std::cos(std::numbers::pi * (k + 0.5) / kCheckedParameters);
    const auto p = data.curve.point(t);
    segment_error_ = std::max(segment_error_, std::abs((*this)(p[0], p[1]) - t));
  }
}

double InversionFormula::operator()(double x, double y) const { return numerator_(x, y) / denominator_(x, y); }

std::optional<std::array<double, 3>> InversionFormula::centre() const {
  if (degree() != 1) return std::nullopt;
  // N = c0 + c1 u + c2 v (T_1(u) = u): the line (c1, c2, c0) in homogeneous (u, v, w); the
  // centre is the cross product of the two lines.
  const auto cn = numerator_.coefficients(), cm = denominator_.coefficients();
  const std::array<double, 3> ln{cn[1], cn[2], cn[0]}, lm{cm[1], cm[2], cm[0]};
  const double u = ln[1] * lm[2] - ln[2] * lm[1], v = ln[2] * lm[0] - ln[0] * lm[2], w = ln[0] * lm[1] - ln[1] * lm[0];
  const double size = std::max({std::abs(u), std::abs(v), std::abs(w)});
  if (!(size > 0.0)) return std::nullopt;
  if (std::abs(w) <= 0x1p-40 * size) {  // parallel lines: a centre at infinity, their direction
    const auto h = numerator_.frame().from_frame_homogeneous(u / size, v / size, 0.0);
    const double length = std::hypot(h[0], h[1]);
    return std::array<double, 3>{h[0] / length, h[1] / length, 0.0};
  }
  const auto p = numerator_.frame().from_frame(u / w, v / w);
  return std::array<double, 3>{p[0], p[1], 1.0};
}

}  // namespace bezinv
