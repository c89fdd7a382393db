// libFuzzer target: CURVES.json (engine/io/curves.cpp) from arbitrary bytes. The contract: every
// input is either curves that pass validate() or an InputError; any other exception, a crash, a
// hang or a sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "bezinv/curve.hpp"
#include "bezinv/io.hpp"
#include "bezinv/matrix_weighted.hpp"
#include "io/curves_text.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    for (const bezinv::Curve& curve : bezinv::parse_curves_json(text, "fuzz.json")) {
      bezinv::validate(curve);  // a CurveError here escapes: the reader let an invalid curve through
      if (curve.dimension() == 3 && curve.z_num.size() != curve.x_num.size()) __builtin_trap();
    }
  } catch (const bezinv::InputError&) {
  }
  try {
    // The matrix-weighted curves as written; each was converted once already (a singular M(t) is an
    // InputError), so converting again must not throw.
    for (const auto& curve : bezinv::detail::parse_matrix_weighted_json(text, "fuzz.json"))
      if (curve) bezinv::convert(*curve);
  } catch (const bezinv::InputError&) {
  }
  return 0;
}
