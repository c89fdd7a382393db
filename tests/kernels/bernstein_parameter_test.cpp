// The lane-batched read-out (Implementation::bernstein_parameter), every available implementation:
// the inputs are exact Bernstein basis vectors alpha beta^{(n-1)}(t) (support/exact) rounded once to
// double, so the expected parameter is known by construction. tests/engine/null_vector_test.cpp
// checks it against the engine's scalar read-out bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bezinv/kernels/batch.hpp"
#include "support/exact.hpp"

namespace bezinv::kernels {
namespace {

TEST(BernsteinParameter, RecoversTheParameterOfScaledBasisVectors) {
  for (const Implementation* implementation : available_implementations()) {
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int n = 2; n <= kMaxBatchSize; ++n) {
      // Inside the segment, its ends, and outside it (the read-out extrapolates).
      std::vector<double> ts{0.0, 1.0, 1e-3, 0.999, -0.4, 1.6};
      while (ts.size() < 21) ts.push_back(unit(rng));
      const std::size_t count = ts.size(), stride = batch_stride(count);
      std::vector<double> z(n * stride, 0.0), t(count, -7.0);
      for (std::size_t l = 0; l < count; ++l) {
        const double alpha = (l % 2 ? -1.0 : 1.0) * (0.5 + unit(rng));
        const auto beta = exact::bernstein_basis(n - 1, mpq_class(ts[l]));
        for (int i = 0; i < n; ++i) z[i * stride + l] = exact::nearest_double(beta[i] * mpq_class(alpha));
      }
      implementation->bernstein_parameter(n, count, stride, z.data(), t.data());
      for (std::size_t l = 0; l < count; ++l) {
        SCOPED_TRACE(std::string(implementation->name) + " n=" + std::to_string(n) + " t=" + std::to_string(ts[l]));
        // Two components rounded once each: a few ulps of t, relative to max(1, |t|) (at t near
        // 1 the formula's denominator comes from the same components, measured <= 2.3 eps).
        EXPECT_NEAR(t[l], ts[l], 8 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(ts[l])));
      }
      if (n == 2) continue;
      // A zero pair (denominator 0) gives NaN; count lanes only are written.
      std::vector<double> zero(n * stride, 0.0), out(count + 1, -7.0);
      implementation->bernstein_parameter(n, count, stride, zero.data(), out.data());
      EXPECT_TRUE(std::isnan(out[0]));
      EXPECT_EQ(out[count], -7.0);
    }
  }
}

}  // namespace
}  // namespace bezinv::kernels
