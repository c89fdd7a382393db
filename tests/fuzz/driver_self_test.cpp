// A target for mutation_driver.cpp's own test: it fails (a contract check, as the real targets
// make them) on the input "fail", so a run that is given that input must fail.
#include <cstddef>
#include <cstdint>
#include <cstring>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 4 && std::memcmp(data, "fail", 4) == 0) __builtin_trap();
  return 0;
}
