#include "bezinv/datasets/random_numbers.hpp"

#include <cmath>

namespace bezinv::datasets {

double uniform(std::mt19937_64& rng, double lo, double hi) {
  const double fraction = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return lo + (hi - lo) * fraction;
}

int uniform_int(std::mt19937_64& rng, int lo, int hi) {
  const auto range = static_cast<std::uint64_t>(hi - lo) + 1;
  return lo + static_cast<int>(rng() % range);
}

double log_uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::exp(uniform(rng, std::log(lo), std::log(hi)));
}

}  // namespace bezinv::datasets
