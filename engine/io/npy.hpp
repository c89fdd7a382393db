#pragma once
// The .npy container (numpy format 1.0/2.0/3.0): magic, version, a Python-literal header dict,
// then the raw array (engine internal; the readers and writers of points, indices and results).
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace bezinv::detail {

struct NpyHeader {
  std::string descr;  // the dtype string ('<f8'), or the raw text of a structured dtype ([...])
  bool fortran_order = false;
  std::vector<std::uint64_t> shape;
  std::uint64_t data_offset = 0;  // bytes before the array data
};

// True for a path ending in ".npy" (any case).
bool has_npy_extension(const std::string& path);

// Reads the preamble and leaves `file` at the first data byte. Throws InputError
// "<path>: header: <problem>" (or "<path>: not a .npy file ...").
NpyHeader read_npy_header(std::FILE* file, const std::string& path);

// Throws InputError "<path>: header: <problem>", the form of every header error.
[[noreturn]] void fail_npy_header(const std::string& path, const std::string& problem);

// A shape as numpy prints it: "(3,)", "(3, 2)".
std::string shape_text(const std::vector<std::uint64_t>& shape);

// A version 1.0 preamble for a (rows,) array of `descr` (a Python literal). Its length does not
// depend on `rows`, so the writer can put a placeholder first and the count at the end.
std::string npy_preamble(std::string_view descr, std::uint64_t rows);

// Reads exactly `bytes`, else InputError "<path>: data: truncated ...".
void read_npy_data(std::FILE* file, const std::string& path, void* into, std::size_t bytes);

}  // namespace bezinv::detail
