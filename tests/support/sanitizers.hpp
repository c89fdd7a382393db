#pragma once
// Whether bezinv runs under AddressSanitizer and UndefinedBehaviorSanitizer here (the tree of
// scripts/test.sh, where the engine runs 5-20x slower). The test files themselves are compiled
// without the sanitizers in that tree (tests/CMakeLists.txt), so the compiler's own macro does not
// say it: the build defines BEZINV_SANITIZER_TREE.
//
// The heaviest property tests draw fewer random cases there: the sanitizers look for what goes
// wrong on a code path, and a fraction of the cases walks the same paths (every degree, kind and
// kernel size is kept; the tests that thin say how). The Release tree (`scripts/test.sh --release`)
// runs every case.
#include <cstddef>

namespace bezinv::test_support {

#if defined(BEZINV_SANITIZER_TREE) || defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitizerTree = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kSanitizerTree = true;
#else
inline constexpr bool kSanitizerTree = false;
#endif
#else
inline constexpr bool kSanitizerTree = false;
#endif

inline constexpr int kSanitizerThinning = kSanitizerTree ? 4 : 1;

// Whether case number `index` is left out in this build: none in Release, all but one in
// kSanitizerThinning under the sanitizers.
inline bool thinned_out(std::size_t index) { return index % kSanitizerThinning != 0; }

}  // namespace bezinv::test_support
