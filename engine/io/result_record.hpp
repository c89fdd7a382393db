#pragma once
// OUT.npy's record (engine internal): packed (numpy's default for a list dtype), little-endian:
// five '<f8' then two '|u1', the codes the enum values of Status and Path (bezinv/invert.hpp).
#include <bit>
#include <cstddef>
#include <cstring>
#include <string_view>

#include "bezinv/io.hpp"

namespace bezinv::detail {

inline constexpr std::string_view kResultDescr =
    "[('t', '<f8'), ('residual', '<f8'), ('t2', '<f8'), ('sigma_min', '<f8'), ('sigma_next', '<f8'), "
    "('status', '|u1'), ('path', '|u1')]";
inline constexpr std::size_t kRecordBytes = kResultRecordBytes;
static_assert(std::endian::native == std::endian::little, "OUT.npy's records are little-endian");

inline void pack_record(char* record, const PointResult& result) {
  const double numbers[5] = {result.t, result.residual, result.t2, result.sigma_min, result.sigma_next};
  std::memcpy(record, numbers, sizeof numbers);
  record[40] = static_cast<char>(result.status);
  record[41] = static_cast<char>(result.path);
}

}  // namespace bezinv::detail
