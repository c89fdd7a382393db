#include "bezinv/datasets/stress.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "bezinv/datasets/high_precision_nearest.hpp"
#include "bezinv/datasets/off_curve_points.hpp"
#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/random_numbers.hpp"

namespace bezinv::datasets {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Noisy points between these multiples of the tolerance may be answered ok or off_curve: the
// distance the engine measures carries its own rounding, and the contract does not say which side
// a point at the tolerance falls.
constexpr double kAmbiguousBelow = 0.5, kAmbiguousAbove = 2.0;

unsigned bit(Status status) { return 1u << static_cast<unsigned>(status); }

bool carries_t(Status status) {
  return status == Status::ok || status == Status::outside_segment || status == Status::off_curve ||
         status == Status::double_point;
}

// The truth of a generated point: the nearest parameter of the double input, at high precision,
// from the generator's answer.
StressRow truth(const Curve& curve, const KnownPoint& k, bool segment_only, double diagonal) {
  const HighPrecisionNearest h = high_precision_nearest(curve, k.point, k.t, segment_only);
  StressRow row;
  row.point = k.point;
  row.t_true = h.converged ? h.t : kNaN;
  row.distance = h.distance;
  row.bound = stress_bound(curve.degree(), k.point.x, k.point.y, diagonal, k.scale, h.speed);
  return row;
}

// t log-uniform within [1e-12, 1e-4] of 0 or 1 (as the nearest double).
std::vector<KnownPoint> near_end_points(const CurveSampling& sampling, int count, std::mt19937_64& rng) {
  std::vector<KnownPoint> points;
  for (int attempt = 0; attempt < 20 * count && static_cast<int>(points.size()) < count; ++attempt) {
    const double offset = std::pow(10.0, uniform(rng, -12.0, -4.0));
    const double t = uniform(rng, 0.0, 1.0) < 0.5 ? offset : 1.0 - offset;
    KnownPoint k = known_on_curve(sampling.curve(), t);
    if (isolated(sampling, k.point, {t})) points.push_back(k);
  }
  return points;
}

}  // namespace

const char* to_string(Family family) {
  switch (family) {
    case Family::on_curve: return "on_curve";
    case Family::near_ends: return "near_ends";
    case Family::extension: return "extension";
    case Family::noisy: return "noisy";
    case Family::far: return "far";
  }
  return "?";
}

std::optional<Family> family_from_string(std::string_view name) {
  for (Family f : kFamilies)
    if (name == to_string(f)) return f;
  return std::nullopt;
}

double stress_bound(int degree, double x, double y, double diagonal, double scale, double speed) {
  const double size = std::max({std::abs(x), std::abs(y), diagonal, std::isfinite(scale) ? scale : 0.0});
  return 2 * (8 + degree) * kEps * size / speed + 2 * kEps;
}

std::vector<StressRow> stress_rows(Family family, const CurveSampling& sampling, int count,
                                   double relative_tolerance, std::mt19937_64& rng) {
  const Curve& curve = sampling.curve();
  const double diagonal = sampling.diagonal(), tolerance = relative_tolerance * diagonal;
  std::vector<KnownPoint> known;
  switch (family) {
    case Family::on_curve: known = segment_points(sampling, count, rng); break;
    case Family::near_ends: known = near_end_points(sampling, count, rng); break;
    case Family::extension: known = extension_points(sampling, count, rng); break;
    case Family::noisy: known = normal_offset_points(sampling, count, 1e-12, 1e-3, rng); break;
    case Family::far: known = normal_offset_points(sampling, count, 10.0, 1000.0, rng); break;
  }
  const bool off = family == Family::noisy || family == Family::far;
  std::vector<StressRow> rows;
  rows.reserve(known.size());
  for (const KnownPoint& k : known) {
    StressRow row = truth(curve, k, /*segment_only=*/off, diagonal);
    if (!off) {
      row.expected = family == Family::extension ? Status::outside_segment : Status::ok;
      row.acceptable = bit(row.expected);
    } else if (row.distance <= kAmbiguousBelow * tolerance) {
      row.expected = Status::ok;
      row.acceptable = bit(Status::ok);
    } else {
      row.expected = Status::off_curve;
      row.acceptable = bit(Status::off_curve) | (row.distance < kAmbiguousAbove * tolerance ? bit(Status::ok) : 0u);
    }
    // The nearest point of the segment is an end and the point is within reach of the tolerance:
    // the curve's extension beyond that end is about as near.
    if (off && (row.t_true == 0.0 || row.t_true == 1.0) && row.distance < kAmbiguousAbove * tolerance)
      row.acceptable |= bit(Status::outside_segment) | bit(Status::ok);
    rows.push_back(row);
  }
  return rows;
}

void StressTally::add(const StressRow& row, const PointResult& got, double diagonal) {
  ++rows;
  const auto expected_index = static_cast<std::size_t>(row.expected), got_index = static_cast<std::size_t>(got.status);
  if (expected_index < kStatusCount && got_index < kStatusCount) ++confusion[expected_index][got_index];
  ambiguous += std::popcount(row.acceptable) > 1;
  if (!(row.acceptable & bit(got.status))) {
    ++wrong_status;
    if (expected_index < kStatusCount && got_index < kStatusCount) ++wrong[expected_index][got_index];
    return;
  }
  if (got.status == Status::double_point && std::isnan(got.t2)) ++missing_t2;
  if (!carries_t(got.status)) return;
  if (std::isnan(got.t)) {
    ++nan_t;
    return;
  }
  // Another right status of an ambiguous row answers another question (the extension's nearest
  // point, say): its t is not compared with this one's truth.
  if (got.status != row.expected) return;
  if (std::isnan(row.t_true)) {
    ++no_truth;
    return;
  }
  const double error = std::abs(got.t - row.t_true);
  dt.push_back(error);
  dt_over_bound.push_back(error / row.bound);
  residual_error.push_back(std::abs(got.residual - row.distance) / diagonal);
}

Quantiles quantiles(std::vector<double> values) {
  Quantiles q;
  if (values.empty()) {
    q.p50 = q.p99 = q.p999 = q.max = kNaN;
    return q;
  }
  std::sort(values.begin(), values.end());
  const auto at = [&](double fraction) {
    const std::size_t i = static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(values.size()))) - 1;
    return values[std::min(i, values.size() - 1)];
  };
  q.p50 = at(0.5);
  q.p99 = at(0.99);
  q.p999 = at(0.999);
  q.max = values.back();
  return q;
}

}  // namespace bezinv::datasets
