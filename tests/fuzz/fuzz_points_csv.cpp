// libFuzzer target: POINTS.csv (engine/io/points.cpp) from arbitrary bytes, read to the end a few
// rows at a time. The contract: an InputError, or rows each either naming a curve of the list with
// finite coordinates (z exactly for a space curve's point) or rejected with a reason.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/io.hpp"
#include "fuzz_file.hpp"
#include "point_rows.hpp"

namespace {

// Ids a CSV can name: a plane and a space curve, and ids that look like indices (the lookup
// tries an id before an index).
std::vector<bezinv::Curve> fuzz_csv_curves() {
  using bezinv::Curve;
  return {Curve::bezier("a", {{0, 0}, {1, 2}, {3, 1}}),
          Curve::space_bezier("s", {{0, 0, 0}, {1, 2, 3}, {2, -1, 1}}),
          Curve::rational_bezier("1", {{0, 0}, {1, 1}, {2, 0}}, {1, 2, 1}),
          Curve::bezier("x,y", {{0, 0}, {1, 1}})};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::vector<bezinv::Curve> curves = fuzz_csv_curves();
  static bezinv::fuzz::ScratchFiles scratch{{bezinv::fuzz::scratch_path("points.csv")}};
  const std::string& path = scratch.paths[0];
  bezinv::fuzz::write_bytes(path, data, size);
  try {
    const std::unique_ptr<bezinv::PointReader> reader = bezinv::open_points(path, curves);
    const std::uint64_t total = bezinv::fuzz::read_checked_rows(*reader, curves, 3);
    if (reader->progress().points != total) __builtin_trap();
  } catch (const bezinv::InputError&) {
  }
  return 0;
}
