#pragma once
// The whole of POINTS.csv at once, for the tests: open_points read to the end.
#include <string>
#include <vector>

#include "bezinv/io.hpp"

namespace bezinv::detail {

// Throws InputError for a file that cannot be used as a whole (unreadable, missing or wrong
// header, a row with the wrong number of fields); per-row problems become rows with curve = -1.
std::vector<PointRow> read_points_csv(const std::string& path, const std::vector<Curve>& curves);

}  // namespace bezinv::detail
