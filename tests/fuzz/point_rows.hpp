#pragma once
// The contract every POINTS reader keeps, for the CSV and .npy fuzz targets: each row either names
// a curve of the list with finite coordinates (z exactly for a space curve's point) or is rejected
// (curve -1) with a reason.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/io.hpp"

namespace bezinv::fuzz {

// Reads every row, `step` at a time (rows that straddle the reader's calls), trapping on a row that
// breaks the contract; returns how many were read. An InputError passes to the caller.
inline std::uint64_t read_checked_rows(PointReader& reader, const std::vector<Curve>& curves, std::size_t step) {
  std::vector<PointRow> rows(step);
  std::uint64_t total = 0;
  while (const std::size_t got = reader.read(rows)) {
    if (got > rows.size()) __builtin_trap();
    total += got;
    for (std::size_t i = 0; i < got; ++i) {
      const PointRow& row = rows[i];
      if (row.curve < -1 || row.curve >= static_cast<int>(curves.size()) || row.reason == nullptr) __builtin_trap();
      if (row.curve == -1) {
        if (row.reason[0] == '\0') __builtin_trap();
        continue;
      }
      if (!std::isfinite(row.point.x) || !std::isfinite(row.point.y)) __builtin_trap();
      const bool space = curves[static_cast<std::size_t>(row.curve)].dimension() == 3;
      if (space != !std::isnan(row.z) || (space && !std::isfinite(row.z))) __builtin_trap();
    }
  }
  return total;
}

}  // namespace bezinv::fuzz
