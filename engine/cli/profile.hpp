#pragma once
// `bezinv profile`: throughput of the in-memory pipeline on generated data, stage by stage.
#include <cstddef>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"

namespace bezinv::cli {

struct ProfileOptions {
  CurveKind kind = CurveKind::rational_bezier;
  int degree = 3;
  int dimension = 2;      // 3: space curves (the plane ones lifted off their plane by a random z)
  std::size_t points = 1'000'000;
  int curves = 16;        // distinct random curves the points are spread over (not cache-hot)
  int threads = 0;        // 0 = all cores
  double noise = 0.0;     // points moved off the curve by up to noise x the curve's diagonal
  bool mixed = false;     // with noise: every other point left on the curve (batches of both kinds)
  bool refine = true;
  bool fast_path = true;
  Algebraic algebraic = Algebraic::automatic;
  OffCurve off_curve = OffCurve::nearest;
  bool json = false;
  unsigned long long seed = 20261122;
};

// Prints points/s per stage and in total (one JSON object with --json). Returns the exit code.
int run_profile(const ProfileOptions& options);

}  // namespace bezinv::cli
