#pragma once
// A polynomial in the plane, f(x, y) of total degree d, as bezinv stores the inversion formula's
// N and M and the implicit equation F:
//     f = sum_{i + j <= d} c_ij T_i(u) T_j(v),     (u, v) = S R ((x, y) - centre),
// with T_k the Chebyshev polynomials and (u, v) the coordinates of a frame (PlaneFrame) that maps
// the curve's segment onto [-1, 1]^2: the plan's rotation, then a scale per axis. Why this basis:
// the monomials x^i y^j of a curve far from the origin cancel every digit (x = 1e6 + u), and the
// monomials u^i v^j on [-1, 1]^2 are as badly conditioned as the power basis on [-1, 1], while
// |T_i| <= 1 there, so the coefficients' size is the polynomial's size near the curve and none
// cancels (docs/inversion-formula.md).
#include <array>
#include <span>
#include <vector>

namespace bezinv {

// Where (u, v) comes from: a rotation and a scale per axis about a centre,
//     u = (cos (x - cx) - sin (y - cy)) / scale_u,   v = (sin (x - cx) + cos (y - cy)) / scale_v.
struct PlaneFrame {
  std::array<double, 2> centre{0.0, 0.0};
  double scale_u = 1.0, scale_v = 1.0;
  double cos_rotation = 1.0, sin_rotation = 0.0;

  std::array<double, 2> to_frame(double x, double y) const;
  std::array<double, 2> from_frame(double u, double v) const;
  // The homogeneous point (u, v, w) of the frame in input coordinates, (x, y, w) with w = 0 for a
  // point at infinity (then (x, y) is a direction).
  std::array<double, 3> from_frame_homogeneous(double u, double v, double w) const;
};

class PlanePolynomial {
 public:
  PlanePolynomial() = default;
  // coefficients.size() == size(degree), in the order of index().
  PlanePolynomial(int degree, PlaneFrame frame, std::vector<double> coefficients);

  // Number of terms of total degree <= d, and the position of c_ij: by total degree k = i + j,
  // then by j, so that the terms of degree <= d' < d come first.
  static int size(int degree) { return (degree + 1) * (degree + 2) / 2; }
  static int index(int i, int j) { return (i + j) * (i + j + 1) / 2 + j; }

  int degree() const { return degree_; }
  const PlaneFrame& frame() const { return frame_; }
  std::span<const double> coefficients() const { return coefficients_; }

  double operator()(double x, double y) const;   // at a point in input coordinates
  double at_frame(double u, double v) const;      // at a point in the frame's coordinates
  // W^d f(U / W, V / W): f at the frame's homogeneous point (U, V, W), finite at W = 0 (a point
  // at infinity). T_k homogenized satisfies T_{k+1} = 2 U T_k - W^2 T_{k-1}.
  double homogeneous(double u, double v, double w) const;

  // The same polynomial in the monomials of the input's x and y: a[index(i, j)] multiplies
  // x^i y^j. Exact in exact arithmetic; computed in long double, it keeps the digits a display
  // needs, not the frame's stability (for a curve far from the origin the monomials cancel).
  std::vector<double> monomials() const;

  // The Chebyshev terms T_i(u) T_j(v) (homogenized as homogeneous()) at one point, in index()
  // order: the row of the linear systems that determine N, M and F from points of the curve.
  static void homogeneous_terms(int degree, double u, double v, double w, std::span<double> out);

 private:
  int degree_ = 0;
  PlaneFrame frame_;
  std::vector<double> coefficients_{0.0};
};

}  // namespace bezinv
