#pragma once
// Knot insertion (Boehm, 1980; Piegl & Tiller A5.1 with r = 1) and the decomposition of a NURBS
// curve into rational Bezier spans by inserting every knot of its domain to full multiplicity.
// Inserting a knot changes the basis, not the curve; in homogeneous coordinates the new control
// points are convex combinations of the old, so positive weights stay positive.
#include <vector>

#include "piecewise/de_boor.hpp"

namespace bezinv::detail {

// Inserts u (in the domain) once: u_k <= u < u_{k+1} (k the last index with u_k <= u), s the
// multiplicity of u already there; Q_i = a_i P_i + (1 - a_i) P_{i-1}, a_i = (u - u_i) / (u_{i+p} - u_i)
// for k - p + 1 <= i <= k - s. Requires s < p (or s <= p away from the domain's ends).
void insert_knot(HomogeneousSpline& spline, double u);

// The homogeneous Bezier control points (degree + 1 each) of the spans of the non-empty knot
// intervals of the domain, in order, and the interval of each: every distinct knot of the domain
// inserted until it has multiplicity p (then span [u_j, u_{j+1}] has the control points P_{j-p..j}).
struct HomogeneousSpan {
  std::vector<std::array<double, 4>> points;
  double start, end;
};
std::vector<HomogeneousSpan> bezier_decomposition(HomogeneousSpline spline);

}  // namespace bezinv::detail
