// libFuzzer target: the .npy readers (engine/io/npy.cpp, points_npy.cpp, results_reader.cpp) from
// arbitrary bytes: the input read as POINTS.npy (for a plane curve, a space curve, a row range), as
// the --curve-index file of a fixed POINTS.npy, by npy_rows, and as an OUT.npy. The contract: an
// InputError, or rows as the CSV reader's (a curve of the list with finite coordinates, or
// rejected with a reason) and results with bezinv's status and path codes.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/io.hpp"
#include "fuzz_file.hpp"
#include "point_rows.hpp"
#include "support/npy_bytes.hpp"

namespace {

std::vector<bezinv::Curve> fuzz_npy_curves() {
  using bezinv::Curve;
  return {Curve::bezier("a", {{0, 0}, {1, 2}, {3, 1}}), Curve::space_bezier("s", {{0, 0, 0}, {1, 2, 3}, {2, -1, 1}}),
          Curve::rational_bezier("r", {{0, 0}, {1, 1}, {2, 0}}, {1, 2, 1})};
}

// Reads every row, two at a time, checking each; an InputError ends the reading.
void read_all_points(const std::string& path, const std::vector<bezinv::Curve>& curves,
                     const bezinv::CurveSelection& selection) {
  try {
    const std::unique_ptr<bezinv::PointReader> reader = bezinv::open_points(path, curves, selection);
    const std::uint64_t total = bezinv::fuzz::read_checked_rows(*reader, curves, 2);
    const bezinv::ReadProgress progress = reader->progress();
    if (progress.points != total || progress.points != progress.points_total) __builtin_trap();
  } catch (const bezinv::InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using bezinv::test_support::le_bytes;
  using bezinv::test_support::npy_file;
  static const std::vector<bezinv::Curve> curves = fuzz_npy_curves();
  static bezinv::fuzz::ScratchFiles scratch{
      {bezinv::fuzz::scratch_path("input.npy"), bezinv::fuzz::scratch_path("three_points.npy")}};
  const std::string& path = scratch.paths[0];
  const std::string& three_points = scratch.paths[1];
  // Written once: three plane points, whose --curve-index is the fuzz input.
  static const bool written = [&] {
    const std::string bytes = npy_file("<f8", "(3, 2)", le_bytes<double>({0, 0, 1, 1, 2, 0.5}));
    bezinv::fuzz::write_bytes(three_points, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    return true;
  }();
  (void)written;
  bezinv::fuzz::write_bytes(path, data, size);

  bezinv::CurveSelection plane, space, rows, indexed;
  plane.curve = "a";
  space.curve = "s";
  rows.curve = "r";
  rows.begin = 1;
  rows.end = 3;
  indexed.index_path = path;
  read_all_points(path, curves, plane);
  read_all_points(path, curves, space);
  read_all_points(path, curves, rows);
  read_all_points(three_points, curves, indexed);
  try {
    (void)bezinv::npy_rows(path);
  } catch (const bezinv::InputError&) {
  }
  try {
    const std::unique_ptr<bezinv::ResultReader> reader = bezinv::open_results_npy(path);
    std::vector<bezinv::PointResult> results(2);
    std::uint64_t total = 0;
    while (const std::size_t got = reader->read(results)) {
      if (got > results.size()) __builtin_trap();
      total += got;
      for (std::size_t i = 0; i < got; ++i)
        if (results[i].status > bezinv::Status::failed || results[i].path > bezinv::Path::projection) __builtin_trap();
    }
    if (total != reader->rows()) __builtin_trap();
  } catch (const bezinv::InputError&) {
  }
  return 0;
}
