#pragma once
// The value of a NURBS curve at a knot parameter, by de Boor's algorithm in homogeneous
// coordinates (Piegl & Tiller, The NURBS Book, A3.1 and A4.1).
#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace bezinv::detail {

// A B-spline in homogeneous form: P_i = (w x, w y, w z, w) (z = 0 for a plane curve).
struct HomogeneousSpline {
  int degree = 0;
  std::vector<double> knots;                  // points + degree + 1
  std::vector<std::array<double, 4>> points;
};

// The index k of the knot interval [u_k, u_{k+1}) that holds u, among the non-empty ones of the
// domain [u_p, u_{m-p}]: the first for u before the domain, the last for u at or past its end (so
// a parameter outside the domain gets the end span's polynomial: the curve's extension).
std::size_t knot_span(const HomogeneousSpline& spline, double u);

// (w x, w y, w z, w) at u.
std::array<double, 4> de_boor(const HomogeneousSpline& spline, double u);

}  // namespace bezinv::detail
