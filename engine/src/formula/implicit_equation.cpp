#include "bezinv/implicit_equation.hpp"

#include <string>

#include "bezinv/tolerances.hpp"
#include "formula/homogeneous_curve.hpp"
#include "formula/null_space.hpp"
#include "plan_data.hpp"
#include "quote.hpp"

namespace bezinv {
namespace {

// The polynomials F of degree e that vanish on a homogeneous curve (U, V, W)(t) of degree D:
// F(U, V, W) is a polynomial of degree D e in t, zero when it vanishes at D e + 1 parameters, so
// F solves a linear system sampled at twice as many (detail::curve_samples).
Eigen::MatrixXd implicit_system(const detail::HomogeneousCurve& curve, int e) {
  const int m = PlanePolynomial::size(e), rows = 2 * (curve.degree() * e + 1);
  const std::vector<detail::CurveSample> samples = detail::curve_samples(curve, rows);
  Eigen::MatrixXd system(rows, m);
  Eigen::RowVectorXd terms(m);
  for (int k = 0; k < rows; ++k) {
    const auto& h = samples[static_cast<std::size_t>(k)].point;
    PlanePolynomial::homogeneous_terms(e, h[0], h[1], h[2], {terms.data(), static_cast<std::size_t>(m)});
    system.row(k) = terms.normalized();
  }
  return system;
}

}  // namespace

ImplicitEquation implicit_equation(const InversionPlan& plan) {
  if (plan.dimension() != 2)
    throw FormulaError("curve " + detail::quoted_excerpt(plan.curve().id) + " is a space curve: no implicit equation");
  const detail::PlanData& data = detail::plan_data(plan);
  if (data.piecewise)
    throw FormulaError("curve " + detail::quoted_excerpt(plan.curve().id) + " is a " + to_string(plan.curve().kind) +
                       " curve: no implicit equation (one per span)");
  const detail::FrameCurve framed = detail::formula_curve(data);
  const detail::HomogeneousCurve& curve = framed.curve;
  const int n = curve.degree();
  if (n > kMaxFormulaCurveDegree)
    throw FormulaError("no implicit equation computed: degree " + std::to_string(n) + " (with separate denominators, "
                       "twice the curve's) is past " + std::to_string(kMaxFormulaCurveDegree));
  const detail::NullSpace space = detail::null_space(implicit_system(curve, n), 1);
  Eigen::VectorXd c = space.basis.col(0);
  Eigen::Index largest = 0;
  const double size = c.cwiseAbs().maxCoeff(&largest);
  c /= c(largest) < 0 ? -size : size;
  return {PlanePolynomial(n, framed.frame, {c.data(), c.data() + c.size()}), space.null_ratio,
          space.next_ratio};
}

}  // namespace bezinv
