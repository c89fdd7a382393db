// invert_stream: reader -> invert -> writer, one chunk at a time (bezinv/io.hpp). Memory is the
// chunk's rows, points and results, whatever the size of the input, and never more than the
// input needs.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "bezinv/io.hpp"

namespace bezinv {
namespace {

constexpr std::size_t kProgressSlice = std::size_t{1} << 16;

// A chunk's buffers start this small and double while the input keeps filling them, so a large
// chunk_points costs memory only when the input has that many points.
constexpr std::size_t kFirstChunkPoints = std::size_t{1} << 16;

// Reads up to `limit` rows into the front of `rows`, growing it as needed; returns how many.
std::size_t read_chunk(PointReader& reader, std::vector<PointRow>& rows, std::size_t limit) {
  std::size_t count = 0;
  while (true) {
    if (count == rows.size()) {
      if (rows.size() >= limit) return count;
      std::size_t wanted = std::min(limit, std::max(kFirstChunkPoints, 2 * rows.size()));
      // A reader that knows its total (.npy) tells how much is left: no more than that is allocated.
      const ReadProgress progress = reader.progress();
      if (progress.points_total > 0) {
        const std::uint64_t left = progress.points_total > progress.points ? progress.points_total - progress.points : 0;
        if (left == 0) return count;
        wanted = static_cast<std::size_t>(std::min<std::uint64_t>(wanted, count + left));
      }
      rows.resize(wanted);
    }
    const std::size_t asked = rows.size() - count;
    const std::size_t got = reader.read(std::span(rows).subspan(count));
    count += got;
    if (got < asked) return count;  // fewer than asked: the end of the input
  }
}

// P(t) on the row's curve (ResultColumns::point): nan for a rejected row or a nan t.
Point3 point_at(std::span<const InversionPlan> plans, int curve, double t) {
  constexpr double nan = PointResult::nan;
  if (curve < 0 || !std::isfinite(t)) return {nan, nan, nan};
  const auto p = plans[static_cast<std::size_t>(curve)].curve().point3(t);
  return {p[0], p[1], p[2]};
}

// The loop of both invert_stream overloads; prepare(curve_of) is called for each chunk before it
// is inverted, with the chunk's curve indices.
template <class Prepare>
StreamSummary stream(PointReader& reader, ResultWriter& writer, std::span<const InversionPlan> plans,
                     const InvertOptions& options, std::size_t chunk_points,
                     const std::function<void(const ReadProgress&)>& on_progress, Prepare&& prepare) {
  chunk_points = std::max<std::size_t>(chunk_points, 1);
  std::vector<PointRow> rows;
  std::vector<int> curve_of;
  std::vector<Point> points;
  std::vector<double> z;  // the space curves' points' third coordinate
  std::vector<PointResult> results;
  std::vector<Point3> at;  // P(t) of each row, when the writer has the point columns
  const bool want_points = writer.columns().point;
  StreamSummary summary;
  while (const std::size_t count = read_chunk(reader, rows, chunk_points)) {
    curve_of.resize(count);
    points.resize(count);
    z.resize(count);
    results.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      curve_of[i] = rows[i].curve;
      points[i] = rows[i].point;
      z[i] = rows[i].z;
      results[i] = PointResult{};
      if (rows[i].curve < 0) {
        // invert() leaves rows with a negative curve as set here.
        results[i].status = Status::invalid_input;
        results[i].reason = rows[i].reason;
      }
    }
    prepare(std::span<const int>(curve_of).first(count));
    // Inverted in slices so the progress callback hears more often than once a chunk (a chunk of
    // a million points can take seconds); a slice is still thousands of batches for the threads.
    // Without a callback, the chunk in one call: each call ends when its slowest thread does.
    ReadProgress progress = reader.progress();
    const std::size_t slice = on_progress ? kProgressSlice : count;
    for (std::size_t begin = 0; begin < count; begin += slice) {
      const std::size_t size = std::min(slice, count - begin);
      invert(plans, std::span<const int>(curve_of).subspan(begin, size),
             std::span<const Point>(points).subspan(begin, size), std::span<const double>(z).subspan(begin, size),
             std::span(results).subspan(begin, size), options);
      progress.points = summary.points + begin + size;
      if (on_progress) on_progress(progress);
    }
    const std::span<const PointResult> answered = std::span(results).first(count);
    for (const PointResult& result : answered) ++summary.by_status[static_cast<std::size_t>(result.status)];
    summary.points += count;
    if (want_points) {
      at.resize(count);
      for (std::size_t i = 0; i < count; ++i) at[i] = point_at(plans, curve_of[i], answered[i].t);
      writer.write_with_points(answered, at);
    } else {
      writer.write(answered);
    }
  }
  return summary;
}

}  // namespace

StreamSummary invert_stream(PointReader& reader, ResultWriter& writer, std::span<const InversionPlan> plans,
                            const InvertOptions& options, std::size_t chunk_points,
                            const std::function<void(const ReadProgress&)>& on_progress) {
  return stream(reader, writer, plans, options, chunk_points, on_progress, [](std::span<const int>) {});
}

StreamSummary invert_stream(PointReader& reader, ResultWriter& writer, std::span<const Curve> curves,
                            const InvertOptions& options, std::size_t chunk_points,
                            const std::function<void(const ReadProgress&)>& on_progress) {
  std::vector<InversionPlan> plans(curves.size());
  std::vector<std::uint8_t> built(curves.size(), 0);
  std::vector<std::size_t> needed;
  const auto prepare = [&](std::span<const int> curve_of) {
    needed.clear();
    for (const int c : curve_of)
      if (c >= 0 && !built[static_cast<std::size_t>(c)]) {
        built[static_cast<std::size_t>(c)] = 1;
        needed.push_back(static_cast<std::size_t>(c));
      }
    if (!needed.empty()) make_plans(curves, needed, plans, options.threads);
  };
  StreamSummary summary = stream(reader, writer, plans, options, chunk_points, on_progress, prepare);
  for (const std::uint8_t b : built) summary.plans_built += b;
  return summary;
}

}  // namespace bezinv
