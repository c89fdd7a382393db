#include "formula/linear_inversion_formula.hpp"

#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>

#include "bezinv/tolerances.hpp"
#include "pipeline/formula_path.hpp"

namespace bezinv::detail {
namespace {

// The system's smallest pivot against its largest below this: the null space is not one line (the
// plan refuses curves this would leave: points, lines; kept as the guard of what follows).
constexpr double kRankRatio = 1e-10;

}  // namespace

FormulaPathData linear_inversion_formula(const PlanData& plan) {
  FormulaPathData formula;
  const int n = plan.degree;
  if (!plan.usable || !plan.common_denominator || plan.straight_line || (n != 2 && n != 3)) return formula;
  // Homogeneous coordinates (W, X, Y): the unknowns (n0, n1, n2, m0, m1, m2) multiply them.
  const double* h[3] = {plan.x_den.data(), plan.x_num.data(), plan.y_num.data()};
  Eigen::Matrix<double, 5, 6> a = Eigen::Matrix<double, 5, 6>::Zero();
  for (int k = 0; k <= n + 1; ++k)
    for (int c = 0; c < 3; ++c) {
      const double f_k = (k <= n ? (n + 1 - k) * h[c][k] : 0.0) + (k >= 1 ? k * h[c][k - 1] : 0.0);
      a(k, c) = f_k;
      a(k, 3 + c) = k >= 1 ? -k * h[c][k - 1] : 0.0;
    }
  if (n == 2)
    for (int c = 0; c < 3; ++c) a(4, c) = h[c][0] - 2 * h[c][1] + h[c][2];  // N(P(inf)) = 0
  // Rows of one size, so that the pivots compare conditions, not their scales.
  for (int k = 0; k < 5; ++k) {
    const double size = a.row(k).norm();
    if (!(size > 0.0) || !std::isfinite(size)) return formula;
    a.row(k) /= size;
  }
  const Eigen::ColPivHouseholderQR<Eigen::Matrix<double, 6, 5>> qr(a.transpose());
  const auto& r = qr.matrixQR();
  if (!(std::abs(r(4, 4)) > kRankRatio * std::abs(r(0, 0)))) return formula;
  // The last column of Q is orthogonal to every row of a: the null vector.
  const Eigen::Matrix<double, 6, 6> q = qr.householderQ();
  Eigen::Matrix<double, 6, 1> z = q.col(5);
  z /= z.cwiseAbs().maxCoeff();
  // N = n0 W + n1 X + n2 Y over W: n0 + n1 u + n2 v (PlanePolynomial's order for degree 1).
  formula.degree = 1;
  formula.n = {z(0), z(1), z(2)};
  formula.m = {z(3), z(4), z(5)};
  formula.usable = true;
  // The formula against the parameters of the plan's samples P(k / S), where it would be used.
  const int samples = static_cast<int>(plan.nearest_samples.size() / 2) - 1;
  double error = 0.0;
  int used = 0;
  for (int k = 0; k <= samples; ++k) {
    const double t = formula_parameter(formula, plan.nearest_samples[2 * k], plan.nearest_samples[2 * k + 1]);
    if (std::isnan(t)) continue;
    error = std::max(error, std::abs(t - static_cast<double>(k) / samples));
    ++used;
  }
  if (!(error <= kFormulaPathMaxSegmentError) || used < 2) formula.usable = false;
  return formula;
}

}  // namespace bezinv::detail
