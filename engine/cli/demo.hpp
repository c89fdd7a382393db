#pragma once
// `bezinv demo`: the README's main job on a built-in default (datasets_gen makes the data).
#include <cstddef>

namespace bezinv::cli {

// Generates `points` points with known parameters on the paper's degree-15 Example 2 curve and on a
// cubic, inverts them, prints points/s and the accuracy against the known parameters. Returns the
// process exit code (non-zero when the accuracy is not what the method guarantees).
int run_demo(std::size_t points, int threads);

}  // namespace bezinv::cli
