#pragma once
// The libraries bezinv is measured against, one point at a time as their users call them:
//   occt  OpenCASCADE's Geom2dAPI_ProjectPointOnCurve on a Geom2d_BezierCurve (poles and weights),
//         the parameter of the nearest extremum (LowerDistanceParameter);
//   sisl  SISL's s1953 (every closest point between a curve and a point) on the curve as a rational
//         B-spline with Bezier knots, the candidate nearest to the point (by s1221).
// Compiled in when CMake finds them with -DBEZINV_BUILD_BASELINES=ON (scripts/bench.sh installs
// them); otherwise `available` says so and nothing links against them. Used by `bezinv stress
// --baseline` and bench/baselines_bench.cpp.
#include <memory>
#include <string_view>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"

namespace bezinv::baselines {

enum class Library { occt, sisl };
const char* to_string(Library library);

// Whether this build has the library.
bool available(Library library);

// One curve in the library's form.
class Projector {
 public:
  virtual ~Projector() = default;
  // The parameter of the point of the segment [0,1] nearest to `point`, as the library finds it;
  // NaN when it returns none.
  virtual double parameter(Point point) const = 0;
};

// Null when the library is not in this build or cannot take the curve: both take one denominator
// (bezier, rational_bezier), not the separate denominators of `rational`.
std::unique_ptr<Projector> projector(Library library, const Curve& curve);

// SISL's s1953 recurses deeply (17,000 frames on some degree-20 points): past an 8 MiB stack it
// crashes instead of failing. True when the stack limit is at least 4 GiB or unlimited
// (`ulimit -s unlimited`).
bool stack_is_large();

}  // namespace bezinv::baselines
