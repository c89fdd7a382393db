#pragma once
// Splitting text the code under test wrote (OUT.csv, stderr) into lines and fields, and writing
// numbers into the text it reads.
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

namespace bezinv::test_support {

// The pieces between separators, empty ones included: "a,,b," -> {"a", "", "b", ""}. A file that
// ends in '\n' therefore splits into its lines plus one empty string.
inline std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(separator, start);
    parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

// v with 17 significant digits: read back, the same double.
inline std::string csv_number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

}  // namespace bezinv::test_support
