#pragma once
// Inverting points: the answer for each point, with its evidence.
#include <cstdint>
#include <limits>
#include <span>
#include <string_view>

#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"

namespace bezinv {

enum class Status : std::uint8_t {
  ok,               // on the segment within the tolerance (ends included)
  outside_segment,  // on the curve's extension: t outside [0,1], within the tolerance
  double_point,     // on the segment at two parameters of separate branches: t < t2 (a self-intersection)
  off_curve,        // farther than the tolerance: t is the parameter of the nearest point of the segment
  invalid_input,    // non-finite coordinate, unknown curve, index past the end (set by the I/O layer)
  failed,           // no parameter can be given (a curve whose points all coincide, or no finite
                    // parameter found; reason says why)
};
const char* to_string(Status status);

// Which computation produced t.
enum class Path : std::uint8_t {
  none,
  bezout,       // null vector of the Bezout matrix by its SVD (paper Sect. 3)
  bezout_pair,  // k >= 2-dimensional null space of the Bezout matrix (double point, several parameters,
                // near degree drop), or the roots of p where B vanishes (a straight line)
  sylvester,    // Sylvester matrix at the true degrees of p and q (paper Sect. 4)
  nearest,      // nearest-point search on the segment (point off the curve)
  bezout_lu,    // null vector of the Bezout matrix by LU and inverse iteration (the fast path; sigma_min
                // and sigma_next are then the kernel's estimates relative to ||B||_F, see kernels/batch.hpp).
  formula,      // the curve's inversion formula N/M (bezinv/inversion_formula.hpp), refined and certified
                // as on the fast path (with --no-refine: N/M itself); no B was formed: sigma_min and
                // sigma_next are NaN.
  projection,   // off_curve with OffCurve::projection: t = N(P0)/M(P0), the paper's projection of the
                // point onto the curve (from the centre for degree <= 3), not the nearest point; residual
                // is |P(t) - P0|; sigma_min and sigma_next NaN.
                // New paths go last, so the codes of the .npy results file stay as they were.
};

// The algebraic step of the fast path: the null vector of B (the paper's), or the curve's inversion
// formula t = N(x, y) / M(x, y) where it is valid at the point (Wang & Joe; the Bezout path where
// it is not, near its base points). Either start is refined and certified the same way, so the
// statuses are the same; t agrees to the accuracy bound. With the fast path (and refine); with
// refine false, formula reports N/M itself where it can (InvertOptions::algebraic).
// automatic (the default): the formula on a conic or cubic with one denominator and weights within
// kFormulaPathMaxWeightRatio of each other (its linear formula, made with the plan: a few
// operations per point against B and its seed), and on a curve close to one of lower degree (a
// smooth function's graph: kNearLowerDegreeRatio) that has a linear one (a polynomial curve linear
// in t along a direction), where B is nearly singular twice over at every point and the null
// vector would send most points to the SVD path; at degrees 4-20 (one denominator, moderate
// weights), the curve's own formula for a call with enough points on the curve to repay making it
// (10,000 at degree 4 to 541,000 at 20, engine/src/pipeline/formula_path.hpp: making it costs up to
// ~55 ms, and each point then saves up to ~200 ns); bezout on every other curve and call, where
// its lane-batched kernel is the faster. The choice is per call, never per thread count. With
// refine false, automatic is bezout.
enum class Algebraic : std::uint8_t { bezout, formula, automatic };

// "bezout", "formula" or "auto" (the command's --algebraic, Python's algebraic=); false for any
// other name, `algebraic` then unchanged.
bool algebraic_named(std::string_view name, Algebraic& algebraic);

// What an off_curve row's t is: the nearest point of the segment (found and proved by a search), or
// the inversion formula's projection of the point, t = N(P0)/M(P0) (Wang & Joe, Sect. 4: for degree
// <= 3 the curve's point on the line from the formula's centre through P0; above, the curve's
// variable intersection with N - t M = 0). The projection costs a few operations where the search
// costs many; it may lie outside [0, 1] (the line meets the extension). Statuses are the same either
// way: a row is answered by projection only where the point is proved farther than the tolerance from
// the whole curve; where the formula is not valid at the point (near its base points, a curve with no
// formula or of formula degree above kFormulaPathMaxDegree), the nearest point as before.
enum class OffCurve : std::uint8_t { nearest, projection };
const char* to_string(OffCurve off_curve);
const char* to_string(Path path);

struct PointResult {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double t = nan;
  double t2 = nan;          // second parameter for double_point
  double residual = nan;    // |P(t) - P0| in input units (nan when t is nan)
  double sigma_min = nan;   // sigma_n / sigma_1 of B: how singular B is at this point
  double sigma_next = nan;  // sigma_{n-1} / sigma_1: the gap that separates nullity 1 from nullity 2
  Status status = Status::failed;
  Path path = Path::none;
  const char* reason = "";  // static text: why failed / invalid_input, empty otherwise
};

struct InvertOptions {
  double relative_tolerance = kDefaultRelativeTolerance;  // x the control-point bounding-box diagonal
  bool refine = true;  // Newton to the nearest point at full precision; false = the paper's algebraic t
  int threads = 0;     // 0: all cores
  // Answer the points it can by the fast path (LU null vector, path bezout_lu, sigma columns
  // estimated); false: every point by the SVD (exact singular values on every row, slower).
  // Used only with refine: the unrefined output is the paper's algebraic t, from the SVD.
  bool fast_path = true;
  // With refine false and formula: t = N/M itself where the formula is valid at the point and the
  // point is within the tolerance of the segment there, isolated from any other branch (else the
  // SVD path's algebraic t, as with bezout).
  Algebraic algebraic = Algebraic::automatic;
  OffCurve off_curve = OffCurve::nearest;
};

struct Point { double x, y; };
// A point in space. Constructed from three numbers only, so that {x, y} stays a plane Point.
struct Point3 {
  double x = 0, y = 0, z = 0;
  constexpr Point3() = default;
  constexpr Point3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
};

// Name of the SVD kernel the pipeline uses in this process (see kernels/).
std::string_view active_kernel_name();

// One point (the reference path: everything else must agree with it).
PointResult invert_point(const InversionPlan& plan, Point point, const InvertOptions& options = {});

// Many points of one curve, in parallel; results[i] answers points[i]. The answers do not depend
// on the thread count. (bezinv/profile.hpp has the same with the time of each stage.)
void invert(const InversionPlan& plan, std::span<const Point> points, std::span<PointResult> results,
            const InvertOptions& options = {});

// Many points of many curves: curve_of[i] indexes plans, or is negative for a point the I/O layer
// already rejected (then results[i] is left as the caller set it).
void invert(std::span<const InversionPlan> plans, std::span<const int> curve_of,
            std::span<const Point> points, std::span<PointResult> results,
            const InvertOptions& options = {});

// Space curves (plan.dimension() == 3; docs/space-curves.md): the same contract in space, the
// distances and the nearest point in 3D. The plane overloads above throw std::invalid_argument for
// a space curve's plan, and these for a plane curve's.
PointResult invert_point(const InversionPlan& plan, Point3 point, const InvertOptions& options = {});
void invert(const InversionPlan& plan, std::span<const Point3> points, std::span<PointResult> results,
            const InvertOptions& options = {});
// Many points of plane and space curves: z[i] is the third coordinate of points[i], read only
// where plans[curve_of[i]] is a space curve (z may be empty when no plan is).
void invert(std::span<const InversionPlan> plans, std::span<const int> curve_of,
            std::span<const Point> points, std::span<const double> z, std::span<PointResult> results,
            const InvertOptions& options = {});

}  // namespace bezinv
