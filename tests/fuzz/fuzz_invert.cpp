// libFuzzer target: invert and invert_point on arbitrary curves and points. The bytes are decoded
// into a curve (plane or space; bezier, rational_bezier or rational; degree 1..kFuzzMaxDegree;
// coefficients small, special - 0, denormal, 1e+-300, the largest double, inf, NaN - or any double,
// the whole curve scaled by a power of two) and a few points, on the curve (at a parameter of the
// segment or its extension, moved by a small offset) or anywhere. A curve that validate() or
// make_plan refuses (CurveError) is fine; every answer otherwise must keep the contract of
// invert.hpp, checked below: one status in range, an `ok` row on the segment within the tolerance
// with a finite t, no crash, no hang.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "plan_data.hpp"
#include "space/space_curve.hpp"

namespace {

using bezinv::Curve;
using bezinv::CurveKind;
using bezinv::PointResult;
using bezinv::Status;

// The per-input work grows as the degree cubed (a plan, B per point) or more (the plan's exact
// common factor): kept small so the target runs thousands of inputs a second. Every degree up
// to kMaxDegree is exercised by the unit tests.
constexpr int kFuzzMaxDegree = 6;
constexpr std::size_t kFuzzMaxPoints = 3;

class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool empty() const { return size_ == 0; }
  std::uint8_t byte() {
    if (size_ == 0) return 0;
    --size_;
    return *data_++;
  }
  // Most inputs spend one byte a number, so mutations move numbers one at a time; a few spend
  // nine and can be any double.
  double number() {
    static constexpr double kSpecial[16] = {0.0, -0.0, 1e-300, -1e-300, std::numeric_limits<double>::denorm_min(),
                                            1e300, -1e300, std::numeric_limits<double>::max(),
                                            -std::numeric_limits<double>::max(), std::numeric_limits<double>::infinity(),
                                            -std::numeric_limits<double>::infinity(),
                                            std::numeric_limits<double>::quiet_NaN(), 1e12, -1e12, 1e-12,
                                            1.0 + std::numeric_limits<double>::epsilon()};
    const std::uint8_t c = byte();
    if (c < 200) return (c - 100) / 8.0;
    if (c < 216) return kSpecial[c - 200];
    std::uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits |= std::uint64_t{byte()} << (8 * i);
    double value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
};

Curve decode_curve(Bytes& in, int dimension, int kind, int degree, double scale) {
  std::vector<std::array<double, 3>> points(static_cast<std::size_t>(degree + 1));
  auto coordinate = [&] { return in.number() * scale; };
  if (kind == 2) {  // separate denominators
    std::array<std::vector<double>, 6> lists;
    for (int k = 0; k < 2 * dimension; ++k)
      for (int i = 0; i <= degree; ++i) lists[k].push_back(k % 2 == 0 ? coordinate() : in.number());
    if (dimension == 2) return Curve::rational("f", lists[0], lists[1], lists[2], lists[3]);
    return Curve::space_rational("f", lists[0], lists[1], lists[2], lists[3], lists[4], lists[5]);
  }
  for (auto& p : points)
    for (int k = 0; k < dimension; ++k) p[k] = coordinate();
  std::vector<double> weights;
  if (kind == 1)
    for (int i = 0; i <= degree; ++i) weights.push_back(in.number());
  if (dimension == 3)
    return kind == 1 ? Curve::space_rational_bezier("f", points, weights) : Curve::space_bezier("f", points);
  std::vector<std::array<double, 2>> plane;
  for (const auto& p : points) plane.push_back({p[0], p[1]});
  return kind == 1 ? Curve::rational_bezier("f", plane, weights) : Curve::bezier("f", plane);
}

// The tolerance an `ok` row is held to, in input units: relative_tolerance x the diagonal of the
// control points' box, never below the resolution of the coordinates (tolerances.hpp,
// kResolutionUlps), as the engine's settle() measures it.
double tolerance_of(const bezinv::InversionPlan& plan, double relative_tolerance) {
  const bezinv::detail::PlanData& data = bezinv::detail::plan_data(plan);
  if (data.space)
    return std::max(relative_tolerance * data.space->diagonal, data.space->normalized_resolution * data.space->scale);
  return std::max(relative_tolerance * data.diagonal, data.normalized_resolution * data.scale);
}

// A broken contract: the row and the rule on stderr, for whoever replays the input, then the trap
// the fuzzer (or the mutation driver) catches.
[[noreturn]] void broken(const char* rule, const PointResult& r, double tolerance) {
  std::fprintf(stderr, "fuzz_invert: %s: status %d, path %d, t %.17g, t2 %.17g, residual %.17g, tolerance %.17g, reason \"%s\"\n",
               rule, static_cast<int>(r.status), static_cast<int>(r.path), r.t, r.t2, r.residual, tolerance,
               r.reason ? r.reason : "(null)");
  __builtin_trap();
}

// `tolerance` is NaN where the plan has no finite diagonal (a curve wider than the doubles): only
// what needs no tolerance is checked.
void check(const PointResult& r, bool finite_point, double tolerance) {
  // A bound computed in other units than the engine's comparison, by a product or two: a few ulps.
  const double bound = tolerance * (1 + 1e-12);
  auto beyond = [&](double residual) { return !std::isnan(tolerance) && !(residual <= bound); };
  if (r.status > Status::failed || r.path > bezinv::Path::projection || r.reason == nullptr)
    broken("status, path or reason out of range", r, tolerance);
  if (finite_point == (r.status == Status::invalid_input))
    broken("invalid_input for a finite point, or not for a non-finite one", r, tolerance);
  switch (r.status) {
    case Status::ok:
      if (!std::isfinite(r.t) || r.t < 0 || r.t > 1 || beyond(r.residual))
        broken("ok: t not in [0, 1] or residual beyond the tolerance", r, tolerance);
      break;
    case Status::outside_segment:
      if (!std::isfinite(r.t) || beyond(r.residual))
        broken("outside_segment: t not finite or residual beyond the tolerance", r, tolerance);
      break;
    case Status::double_point:
      if (!std::isfinite(r.t) || !std::isfinite(r.t2) || !(r.t < r.t2) || beyond(r.residual))
        broken("double_point: t, t2 not finite and ordered, or residual beyond the tolerance", r, tolerance);
      break;
    case Status::off_curve:
      if (r.residual <= tolerance * (1 - 1e-12)) broken("off_curve: residual within the tolerance", r, tolerance);
      break;
    case Status::invalid_input:
    case Status::failed:
      if (r.reason[0] == '\0') broken("invalid_input or failed without a reason", r, tolerance);
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  const std::uint8_t flags = in.byte();
  const int dimension = (flags & 1) ? 3 : 2;
  const int kind = ((flags >> 1) & 3) % 3;
  bezinv::InvertOptions options;
  options.threads = 1;
  options.refine = !(flags & 8);
  options.fast_path = !(flags & 16);
  if (flags & 32) options.algebraic = bezinv::Algebraic::formula;
  if (flags & 64) options.off_curve = bezinv::OffCurve::projection;
  if (flags & 128) options.relative_tolerance = 1e-2;
  const int degree = 1 + in.byte() % kFuzzMaxDegree;
  // The whole curve and its points scaled by 2^(8 s), s in -128..127: tiny and huge curves.
  const double scale = std::ldexp(1.0, 8 * static_cast<std::int8_t>(in.byte()));
  const Curve curve = decode_curve(in, dimension, kind, degree, scale);

  bezinv::InversionPlan plan;
  try {
    plan = bezinv::make_plan(curve);
  } catch (const bezinv::CurveError&) {
    return 0;
  }
  const double tolerance = tolerance_of(plan, options.relative_tolerance);
  // The tolerance checked against numbers the engine did not make: the box of a bezier curve's
  // control points (no weights, so no common factor changes it), halved so nothing overflows, and
  // a finite floor wherever the box is finite.
  if (kind == 0) {
    double lo[3], hi[3];
    for (int k = 0; k < dimension; ++k) {
      const std::vector<double>& c = k == 0 ? curve.x_num : k == 1 ? curve.y_num : curve.z_num;
      lo[k] = *std::min_element(c.begin(), c.end());
      hi[k] = *std::max_element(c.begin(), c.end());
    }
    const double half = dimension == 3 ? std::hypot(0.5 * hi[0] - 0.5 * lo[0], 0.5 * hi[1] - 0.5 * lo[1], 0.5 * hi[2] - 0.5 * lo[2])
                                       : std::hypot(0.5 * hi[0] - 0.5 * lo[0], 0.5 * hi[1] - 0.5 * lo[1]);
    // (inf for a box wider than the largest double, as plan.hpp says)
    const double diagonal = 2 * half;
    if (std::isfinite(half) && !(plan.diagonal() == diagonal || std::abs(plan.diagonal() - diagonal) <= 1e-14 * diagonal))
      __builtin_trap();
  }
  if (std::isfinite(plan.diagonal()) && !std::isfinite(tolerance)) __builtin_trap();
  const double checked_tolerance = std::isfinite(plan.diagonal()) ? tolerance : std::numeric_limits<double>::quiet_NaN();

  std::vector<bezinv::Point3> points;
  while (!in.empty() && points.size() < kFuzzMaxPoints) {
    const std::uint8_t tag = in.byte();
    if (tag & 1) {
      // On the curve at t in [-0.25, 1.25] (the extension too), moved by an offset of 2^-k times a number.
      const double t = -0.25 + 1.5 * (tag >> 1) / 127.0;
      const auto p = curve.point3(t);
      const double shrink = std::ldexp(scale, -static_cast<int>(in.byte() % 64));
      points.emplace_back(p[0] + in.number() * shrink, p[1] + in.number() * shrink,
                          dimension == 3 ? p[2] + in.number() * shrink : 0.0);
    } else {
      const double x = in.number() * scale, y = in.number() * scale;
      points.emplace_back(x, y, dimension == 3 ? in.number() * scale : 0.0);
    }
  }
  if (points.empty()) return 0;

  std::vector<PointResult> results(points.size());
  if (dimension == 3) {
    bezinv::invert(plan, points, results, options);
  } else {
    std::vector<bezinv::Point> plane;
    for (const auto& p : points) plane.push_back({p.x, p.y});
    bezinv::invert(plan, plane, results, options);
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    const bool finite = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    check(results[i], finite, checked_tolerance);
    const PointResult one = dimension == 3 ? bezinv::invert_point(plan, p, options)
                                           : bezinv::invert_point(plan, bezinv::Point{p.x, p.y}, options);
    check(one, finite, checked_tolerance);
  }
  return 0;
}
