#pragma once
// .npy files written byte by byte, as the numpy format specification (1.0, 2.0) lays them out, for
// the readers' and the command's tests: independent of the engine's own writer.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <type_traits>

namespace bezinv::test_support {

// Appends value's little-endian bytes (an 8-byte or 4-byte number), as array data holds them.
template <class T>
void append_le(std::string& bytes, T value) {
  static_assert(sizeof(T) == 8 || sizeof(T) == 4);
  const auto bits = std::bit_cast<std::conditional_t<sizeof(T) == 8, std::uint64_t, std::uint32_t>>(value);
  for (std::size_t i = 0; i < sizeof(T); ++i) bytes += static_cast<char>((bits >> (8 * i)) & 0xff);
}

template <class T>
std::string le_bytes(std::initializer_list<T> values) {
  std::string bytes;
  for (T value : values) append_le(bytes, value);
  return bytes;
}

// The header dict; descr as it appears in it, quotes included ("'<f8'").
inline std::string npy_dict(const std::string& descr, const std::string& shape, const char* fortran = "False") {
  return "{'descr': " + descr + ", 'fortran_order': " + fortran + ", 'shape': " + shape + ", }";
}

// A .npy file from its parts: magic, version, little-endian header length, the dict padded with
// spaces to a multiple of 64 bytes and ended by '\n', then the data.
inline std::string npy_bytes(const std::string& dict, std::string_view data, int major = 1) {
  const std::size_t length_bytes = major == 1 ? 2 : 4;
  std::string padded = dict;
  while ((6 + 2 + length_bytes + padded.size() + 1) % 64 != 0) padded += ' ';
  padded += '\n';
  std::string bytes = "\x93NUMPY";
  bytes += static_cast<char>(major);
  bytes += '\0';
  for (std::size_t i = 0; i < length_bytes; ++i) bytes += static_cast<char>((padded.size() >> (8 * i)) & 0xff);
  return bytes + padded + std::string(data);
}

// A version 1.0 file of C-order data: descr such as "<f8", shape such as "(6, 2)".
inline std::string npy_file(const std::string& descr, const std::string& shape, std::string_view data) {
  return npy_bytes(npy_dict("'" + descr + "'", shape), data);
}

}  // namespace bezinv::test_support
