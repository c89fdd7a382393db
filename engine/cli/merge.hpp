#pragma once
// `bezinv merge`: the OUT.npy files of `bezinv invert --rows A:B` runs (one file's rows shared out
// over machines) joined into the OUT of one run, after checking that every row is there once, in
// order.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace bezinv::cli {

struct MergePart {
  std::uint64_t begin = 0, end = 0;  // the --rows range the part was made with (end may pass the last row)
  std::string path;
};

// "A:B" (A <= B, both counts) -> the range; throws std::invalid_argument naming the text.
std::pair<std::uint64_t, std::uint64_t> parse_row_range(const std::string& text);

// "A:B=PATH" -> a part; throws std::invalid_argument naming the text.
MergePart parse_merge_part(const std::string& text);

// rows: the number of points of the input (POINTS.npy's N). Throws InputError naming the part or
// the gap; writes OUT (a .npy) only when every check passed.
int run_merge(std::uint64_t rows, std::vector<MergePart> parts, const std::string& out_path);

}  // namespace bezinv::cli
