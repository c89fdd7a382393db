// The off-curve path's starts (Implementation::nearest_sample), every available implementation.
// Expected parameters come from construction: samples of a straight segment, where the squared
// distance is exactly a parabola in the parameter, so the vertex of the parabola through three
// samples is the foot of the perpendicular.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bezinv/kernels/batch.hpp"
#include "support/bits.hpp"

namespace bezinv::kernels {
namespace {

// Samples k / last of the segment from (0, 0) to (1, 0): x, y of sample k at 2k, 2k + 1.
std::vector<double> segment_samples(int last) {
  std::vector<double> samples;
  for (int k = 0; k <= last; ++k) samples.push_back(static_cast<double>(k) / last), samples.push_back(0.0);
  return samples;
}

// Points above and below the segment, between its first and last sampled neighbours: the start is
// the foot of the perpendicular, to rounding; beyond the ends, the end itself.
TEST(NearestSample, OnASegmentTheStartIsTheFootOfThePerpendicular) {
  constexpr int kLast = 128, kStride = 4;
  const std::vector<double> samples = segment_samples(kLast);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> along(static_cast<double>(kStride) / kLast, 1.0 - static_cast<double>(kStride) / kLast),
      off(-0.3, 0.3);
  for (const Implementation* implementation : available_implementations()) {
    SCOPED_TRACE(std::string(implementation->name));
    std::vector<double> u, v, truth;
    for (int k = 0; k < 37; ++k) u.push_back(along(rng)), v.push_back(off(rng)), truth.push_back(u.back());
    u.push_back(-0.25), v.push_back(0.1), truth.push_back(0.0);
    u.push_back(1.5), v.push_back(-0.2), truth.push_back(1.0);
    std::vector<double> t(u.size(), -1.0);
    implementation->nearest_sample(samples.data(), kLast, kStride, u.size(), u.data(), v.data(), t.data());
    for (std::size_t l = 0; l < u.size(); ++l) EXPECT_NEAR(t[l], truth[l], 1e-12) << l;
    t.assign(1, -1.0);
    implementation->nearest_sample(samples.data(), kLast, kStride, 0, u.data(), v.data(), t.data());
    EXPECT_EQ(t[0], -1.0);  // count 0 writes nothing
  }
}

// Samples of a curve with turns: every implementation chooses the same sample and the same start,
// for every lane count around the vector widths.
TEST(NearestSample, EveryImplementationGivesTheSameBits) {
  constexpr int kLast = 160;
  std::vector<double> samples;
  for (int k = 0; k <= kLast; ++k) {
    const double s = static_cast<double>(k) / kLast;
    samples.push_back(std::cos(7 * s) * (1 + s)), samples.push_back(std::sin(5 * s));
  }
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  for (std::size_t count : {1u, 7u, 8u, 9u, 16u, 17u, 64u}) {
    std::vector<double> u, v;
    for (std::size_t l = 0; l < count; ++l) u.push_back(coordinate(rng)), v.push_back(coordinate(rng));
    std::vector<double> first;
    for (const Implementation* implementation : available_implementations()) {
      std::vector<double> t(count);
      implementation->nearest_sample(samples.data(), kLast, 4, count, u.data(), v.data(), t.data());
      for (double x : t) EXPECT_TRUE(x >= 0.0 && x <= 1.0) << x;
      if (first.empty()) {
        first = t;
        continue;
      }
      for (std::size_t l = 0; l < count; ++l)
        EXPECT_TRUE(test_support::same_bits(t[l], first[l])) << implementation->name << " count " << count << " lane " << l;
    }
  }
}

}  // namespace
}  // namespace bezinv::kernels
