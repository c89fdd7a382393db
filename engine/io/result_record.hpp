#pragma once
// OUT.npy's record (engine internal): packed (numpy's default for a list dtype), little-endian:
// five '<f8' then two '|u1', the codes the enum values of Status and Path (bezinv/invert.hpp).
#include <bit>
#include <cstddef>
#include <cstring>
#include <span>
#include <string_view>

#include "bezinv/io.hpp"

namespace bezinv::detail {

inline constexpr std::string_view kResultDescr =
    "[('t', '<f8'), ('residual', '<f8'), ('t2', '<f8'), ('sigma_min', '<f8'), ('sigma_next', '<f8'), "
    "('status', '|u1'), ('path', '|u1')]";
// With the point columns (ResultColumns::point): three '<f8' after path.
inline constexpr std::string_view kResultWithPointDescr =
    "[('t', '<f8'), ('residual', '<f8'), ('t2', '<f8'), ('sigma_min', '<f8'), ('sigma_next', '<f8'), "
    "('status', '|u1'), ('path', '|u1'), ('x_t', '<f8'), ('y_t', '<f8'), ('z_t', '<f8')]";
inline constexpr std::size_t kRecordBytes = kResultRecordBytes;

inline std::string_view result_descr_for(const ResultColumns& columns) {
  return columns.point ? kResultWithPointDescr : kResultDescr;
}
inline std::size_t record_bytes_for(const ResultColumns& columns) {
  return kRecordBytes + (columns.point ? kPointColumnsBytes : 0);
}
static_assert(std::endian::native == std::endian::little, "OUT.npy's records are little-endian");

inline void pack_record(char* record, const PointResult& result) {
  const double numbers[5] = {result.t, result.residual, result.t2, result.sigma_min, result.sigma_next};
  std::memcpy(record, numbers, sizeof numbers);
  record[40] = static_cast<char>(result.status);
  record[41] = static_cast<char>(result.path);
}

// The point columns after the record's fixed fields.
inline void pack_point(char* record, const Point3& at) {
  const double numbers[3] = {at.x, at.y, at.z};
  std::memcpy(record + kRecordBytes, numbers, sizeof numbers);
}

inline Point3 point_or_nan(std::span<const Point3> at, std::size_t i) {
  constexpr double nan = PointResult::nan;
  return i < at.size() ? at[i] : Point3{nan, nan, nan};
}

}  // namespace bezinv::detail
