#pragma once
// `bezinv convert`: CURVES.json with every matrix-weighted curve (Yang, plane or space) written as an
// ordinary rational Bezier curve of degree d n; the other curves pass through as written.
#include <string>

namespace bezinv::cli {

// Throws InputError (the input, as `bezinv invert` reads it; OUT not writable). Returns the exit code.
int run_convert(const std::string& curves_path, const std::string& out_path);

}  // namespace bezinv::cli
