#pragma once
// Random Bernstein coefficients for the accuracy tests.
#include <cstddef>
#include <random>
#include <vector>

#include "bezinv/datasets/random_numbers.hpp"

namespace bezinv::test_support {

// Coefficients c_0..c_n uniform in [-1, 1). Drawn with datasets_gen's portable uniform (the
// output of std::uniform_real_distribution is implementation-defined), so the measured figures
// quoted in the tests' comments reproduce on any standard library.
inline std::vector<double> random_coefficients(std::mt19937_64& rng, int n) {
  std::vector<double> c(static_cast<std::size_t>(n) + 1);
  for (double& v : c) v = datasets::uniform(rng, -1.0, 1.0);
  return c;
}

}  // namespace bezinv::test_support
