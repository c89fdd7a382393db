#pragma once
// The parameter of the curve point nearest to a double input point, to far more digits than a
// double holds: the truth the accuracy stress tool (`bezinv stress`) measures the engine against.
//
// Why not the generators' long double: a point made at a known t and rounded to doubles is no
// longer on the curve, and the engine is given that rounded point. Its true answer is the nearest
// curve point of the rounded input, whose parameter differs from the construction's t by up to
// ~ulp(P) / |P'|; to measure errors of an ulp of t and below, the truth needs tens of bits more
// than a double. So: Newton's method on f(t) = (P(t) - P0) . P'(t) in MPFR at kReferenceBits bits,
// from the construction's parameter, with the curve's coefficients and the point taken exactly
// (a double is a dyadic rational). P, P', P'' by de Casteljau's triangle, which is exact to the
// working precision on the extension too (no cancellation that matters at 128 bits for |t| <= 2).
#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"

namespace bezinv::datasets {

inline constexpr int kReferenceBits = 128;

struct HighPrecisionNearest {
  double t = 0;         // the parameter rounded to double
  double t_low = 0;     // the next 53 bits (t + t_low is the parameter to ~2^-106 relative)
  double distance = 0;  // |P(t) - P0| rounded to double
  double speed = 0;     // |P'(t)|
  bool converged = false;  // Newton's step fell below 2^-(kReferenceBits - 20); else t is the start
};

// Newton from t_start (a local minimum of |P(t) - point| is expected within ~1e-6 of it: the
// generators' long double answer). segment_only: the nearest point of the segment [0,1] (an off-curve
// point's answer), so a step that leaves the segment ends at that end; else of the whole curve (an
// on-curve point's, whose nearest parameter may lie a rounding beyond an end).
// A space curve's point has its third coordinate in z (read only for a curve of dimension 3).
HighPrecisionNearest high_precision_nearest(const Curve& curve, Point point, double t_start, bool segment_only,
                                            double z = 0.0);

// f(t) = (P(t) - point) . P'(t) at t = t_hi + t_lo, at kReferenceBits bits, rounded to double: its
// sign changes across a nearest parameter (for the tests of the reference itself).
double high_precision_stationarity(const Curve& curve, Point point, double t_hi, double t_lo, double z = 0.0);

}  // namespace bezinv::datasets
