#pragma once
// The heaviest property tests draw fewer random cases under AddressSanitizer (the sanitizer tree
// of scripts/test.sh, where the engine runs 5-20x slower): the sanitizers look for what goes
// wrong on a code path, and a fraction of the cases walks the same paths (every degree, kind and
// kernel size is kept; the tests that thin say how). The Release tree (`scripts/test.sh --release`)
// runs every case.
#include <cstddef>

namespace bezinv::test_support {

// GCC says so by __SANITIZE_ADDRESS__, clang (before 15) by __has_feature only.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr int kSanitizerThinning = 4;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr int kSanitizerThinning = 4;
#else
inline constexpr int kSanitizerThinning = 1;
#endif
#else
inline constexpr int kSanitizerThinning = 1;
#endif

// Whether case number `index` is left out in this build: none in Release, all but one in
// kSanitizerThinning under the sanitizers.
inline bool thinned_out(std::size_t index) { return index % kSanitizerThinning != 0; }

}  // namespace bezinv::test_support
