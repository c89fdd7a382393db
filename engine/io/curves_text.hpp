#pragma once
// CURVES.json's matrix-weighted curves from text already in memory (engine internal):
// read_matrix_weighted_json is this after reading the file under its size cap, as
// read_curves_json is parse_curves_json (bezinv/io.hpp). The fuzz target
// (tests/fuzz/fuzz_curves_json.cpp) parses its inputs with both, without a file per input.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/matrix_weighted.hpp"

namespace bezinv::detail {

// As read_matrix_weighted_json, from `text`.
std::vector<std::optional<MatrixWeightedCurve>> parse_matrix_weighted_json(std::string_view text,
                                                                           const std::string& path);

}  // namespace bezinv::detail
