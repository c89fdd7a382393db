#pragma once
// The polynomials F of degree e that vanish on a homogeneous curve (U, V, W)(t) of degree D:
// F(U, V, W) is a polynomial of degree D e in t, zero when it vanishes at D e + 1 parameters, so
// F solves a linear system sampled at twice as many (detail::curve_samples).
#include <Eigen/Core>

#include "formula/homogeneous_curve.hpp"

namespace bezinv::detail {

Eigen::MatrixXd implicit_system(const HomogeneousCurve& curve, int e);

}  // namespace bezinv::detail
