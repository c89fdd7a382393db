#pragma once
// CURVES.json from text already in memory (engine internal): read_curves_json and
// read_matrix_weighted_json are these after reading the file under its size cap. The fuzz target
// (tests/fuzz/fuzz_curves_json.cpp) parses its inputs here, without a file per input.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/matrix_weighted.hpp"

namespace bezinv::detail {

// As read_curves_json, from `text`; `path` names the file in messages.
std::vector<Curve> parse_curves_json(std::string_view text, const std::string& path);

// As read_matrix_weighted_json, from `text`.
std::vector<std::optional<MatrixWeightedCurve>> parse_matrix_weighted_json(std::string_view text,
                                                                           const std::string& path);

}  // namespace bezinv::detail
