#pragma once
// OUT.npy's record (engine internal): packed (numpy's default for a list dtype), little-endian:
// five '<f8' then two '|u1', the codes the enum values of Status and Path (bezinv/invert.hpp).
#include <bit>
#include <cstddef>
#include <string_view>

namespace bezinv::detail {

inline constexpr std::string_view kResultDescr =
    "[('t', '<f8'), ('residual', '<f8'), ('t2', '<f8'), ('sigma_min', '<f8'), ('sigma_next', '<f8'), "
    "('status', '|u1'), ('path', '|u1')]";
inline constexpr std::size_t kRecordBytes = 5 * 8 + 2;
static_assert(std::endian::native == std::endian::little, "OUT.npy's records are little-endian");

}  // namespace bezinv::detail
