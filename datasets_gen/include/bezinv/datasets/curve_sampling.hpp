#pragma once
// Dense sampling of a curve over its whole real parameter line: how the generators decide, by
// construction, which answer a point must get - whether another branch of the curve (on the
// segment or on its extension) comes near it, and where the nearest point of the segment is.
//
// The line t in R u {inf} is parametrized by an angle, [1-t : t] = [cos a : sin a], a in [0, pi):
// a in [0, pi/2] is the segment [0,1], (pi/2, 3pi/4) is t > 1, 3pi/4 is t = inf, (3pi/4, pi) is
// t < 0. Sampling a uniformly covers the far extension (which an engine's algebraic root can
// land on) with as few samples as the segment.
#include <optional>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/datasets/reference_evaluation.hpp"

namespace bezinv::datasets {

// t = sin a / (cos a + sin a); +-inf at a = 3pi/4.
Real parameter_of_angle(Real a);

// A local minimum of the distance from a point to the curve.
struct DistanceMinimum {
  Real t = 0;         // parameter (may be +-inf)
  Real distance = 0;  // |P(t) - p0|, or a lower bound on it (see CurveSampling)
  bool on_segment = false;
};

class CurveSampling {
 public:
  // samples_per_degree * max(degree, 1) samples over the segment, as many over the extension;
  // more on the segment where the curve moves fast (curve_sampling.cpp, kLongChord).
  explicit CurveSampling(Curve curve, int samples_per_degree = 256);

  const Curve& curve() const { return curve_; }
  double diagonal() const { return diagonal_; }

  // Local minima of |P - p0| over the whole parameter line. A minimum whose sampled value minus
  // the length of the adjacent chords exceeds `cutoff` is not refined and reports that lower bound
  // (no point of the curve near it is closer than `cutoff`); the others are refined by Brent's
  // method to what long double resolves.
  std::vector<DistanceMinimum> line_minima(RealPoint p0, Real cutoff) const;

  // Local minima of |P(t) - p0| over the segment alone: interior minima, and an end of the
  // segment where the distance decreases towards it (reported with t exactly 0 or 1).
  std::vector<DistanceMinimum> segment_minima(RealPoint p0, Real cutoff) const;

 private:
  struct Sample { RealPoint p; bool valid = false; };
  Real angle(int k) const;
  // Adds samples between (a0, s0) and (a1, p1), in order, while their chord exceeds long_chord.
  void densify(Real a0, Sample s0, Real a1, std::optional<RealPoint> p1, Real long_chord, int depth);
  std::optional<RealPoint> point_at_angle(Real a) const;
  DistanceMinimum refine(RealPoint p0, Real a_lo, Real a_hi, Real sampled_distance, Real sampled_angle) const;

  // Squared distances from p0 to every sample, in double (what finds the local minima; each is
  // then measured again in long double): +inf at a sample that is not a point.
  void squared_distances(RealPoint p0, std::vector<double>& d2) const;

  Curve curve_;
  double diagonal_ = 0;
  int count_ = 0;  // samples over [0, pi)
  int last_ = 0;   // the sample at a = pi/2 (t = 1)
  std::vector<Real> angles_;
  std::vector<Sample> samples_;
  // The samples again, as doubles relative to `origin_` (the first valid sample): near the curve
  // they keep their digits however far it is from (0, 0); and chord_[k], the longer of the chords
  // from sample k to its two neighbours on the closed line (inf next to a sample that is not a point).
  RealPoint origin_;
  std::vector<double> x_, y_;
  std::vector<Real> chord_;
};

}  // namespace bezinv::datasets
