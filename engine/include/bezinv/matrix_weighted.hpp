#pragma once
// Matrix-weighted rational Bezier curves (Yang), in the plane (d = 2) or in space (d = 3):
//     Q(t) = [sum_i M_i B_{i,n}(t)]^{-1} sum_i M_i P_i B_{i,n}(t),     M_i d x d,
// and their conversion to ordinary rational Bezier curves of degree d n (Sect. 2, eqs. (4)-(6);
// Sect. 3, eqs. (7)-(8)): with M(t) = sum_i M_i B_i(t) and M*(t) its adjugate,
//     Q(t) = M*(t) sum_j M_j P_j B_j(t) / det M(t),
// the numerator and the denominator multiplied out in the Bernstein basis (products of Bernstein
// polynomials, Farouki & Rajan): the weights are det M(t)'s coefficients of degree d n, the control
// points the numerator's over them. Weight matrices from point-normal pairs (eq. (2)) and
// point-tangent pairs (eq. (3)) are positive definite, and then every converted weight is positive
// (docs/matrix-weighted.md: the weights are positive combinations of mixed discriminants of
// positive definite matrices; Yang's Conjecture 4.1).
#include <array>
#include <string>
#include <vector>

#include "bezinv/curve.hpp"

namespace bezinv {

using Vector3 = std::array<double, 3>;
using Matrix3 = std::array<double, 9>;  // row-major; in the plane, the top-left 2 x 2 block

struct MatrixWeightedCurve {
  std::string id;
  int dimension = 2;              // 2 or 3
  std::vector<Vector3> points;    // P_i (z unused in the plane)
  std::vector<Matrix3> matrices;  // M_i
};

// Eq. (2): omega (I + mu n n^T), and eq. (3): omega (I + mu (I - t t^T)), with n, t normalized here
// (in the plane their z is ignored). Throws CurveError unless omega > 0, mu > -1 and the vector is
// not zero (`what` names the control point).
Matrix3 normal_weight(int dimension, Vector3 normal, double omega, double mu, const std::string& what);
Matrix3 tangent_weight(int dimension, Vector3 tangent, double omega, double mu, const std::string& what);

// The converted curve: degree d n, weights[k] = omega_k, points[k] = Q_k (points[k] is the
// numerator's coefficient itself where omega_k = 0: a control point at infinity, its direction).
struct ConvertedCurve {
  int dimension = 2;
  std::vector<double> weights;
  std::vector<Vector3> points;
  std::vector<Vector3> numerators;  // omega_k Q_k: the homogeneous form, exact where omega_k = 0
};

// Throws CurveError naming the curve and the parameter where M(t) is singular on [0, 1].
ConvertedCurve convert(const MatrixWeightedCurve& curve);

// Q(t) by the definition: M(t) Q(t) = sum_i B_i(t) M_i P_i solved at t (the reference the
// conversion is tested against).
Vector3 matrix_weighted_point(const MatrixWeightedCurve& curve, double t);

// A plane curve's conversion as the engine takes it: kind rational, the numerators omega_k Q_k over
// the weights as one common denominator (the homogeneous form keeps the digits Q_k loses where a
// weight is tiny against its terms).
Curve plane_curve(const ConvertedCurve& converted, std::string id);
// The same in the converted curve's dimension (a space curve: z_num, z_den too).
Curve rational_curve(const ConvertedCurve& converted, std::string id);

// The curve the engine inverts, in lowest terms where that is known exactly: when every M_i is
// s_i I (s_i > 0), Q(t) = sum B_i s_i P_i / sum B_i s_i is the rational Bezier curve of weights s_i at
// degree n -- the conversion's degree 2n (or 3n) carries the factor sum s_i B_i in every polynomial,
// to rounding, which no exact gcd finds. Otherwise rational_curve(convert(curve)). Throws CurveError
// as convert does.
Curve lowest_terms_curve(const MatrixWeightedCurve& curve, std::string id);

}  // namespace bezinv
