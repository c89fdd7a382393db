// branches_within, the stress tool's proof of how many branches pass within a radius: by
// construction (a crossing, a point on one branch, a far point) and on the two kinds of row a
// sampling missed in a stress run of ten million points (bezinv answered double_point, and was
// right: both parameters within the tolerance, the curve farther than it between, checked in exact
// rational arithmetic).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bezinv/datasets/branches.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/self_intersection.hpp"

namespace {

using bezinv::Curve;
using bezinv::datasets::branches_within;

// The tolerance the engine uses for these curves: 1e-6 x the control points' box diagonal.
double control_diagonal(const Curve& c) {
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
  auto add = [&](double x, double y) {
    x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x), y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
  };
  for (std::size_t i = 0; i < c.x_num.size(); ++i) add(c.x_num[i] / c.x_den[i], c.y_num[i] / c.y_den[i]);
  for (double t : {0.0, 1.0}) add(c.point(t)[0], c.point(t)[1]);
  return std::hypot(x_hi - x_lo, y_hi - y_lo);
}

struct MissedRow {
  Curve curve;
  bezinv::Point point;
};

TEST(Branches, TheRowsASamplingMissedHaveTwoBranchesWithinTheTolerance) {
  const MissedRow rows[] = {
      // noisy, degree 9: t = 0.7999919333745579, t2 = 0.8008475420100473
      {Curve::rational("104", {0.7088616753102199, 1.3581742902015923, 0.11985247317318444, 0.5357468704898415, 0.2614542551020086, 1.1396686012633743, 0.4784778352584335, 0.2586017246467778, 0.19828437013126468, 1.1445339990948185},
         {1.377316125051836, 1.4009451250932694, 0.5625082304060445, 0.8374010292652259, 0.5845252822943858, 1.8085813927974552, 0.6348603102817075, 1.998258957063752, 1.1835568264164638, 1.4227312130832486},
         {0.13301997096270837, 1.2542413258739697, 0.98015389245217, 0.22053954144158322, 1.15895898842166, 0.5680253162615162, 1.0096255015154079, 0.3404095371166459, 0.38767158008783226, 1.184472997532139},
         {1.8003803723785123, 1.4830511994799562, 1.2587613942329723, 0.5121666824145678, 1.9416250068206904, 1.8700811658961982, 1.7690587371946827, 1.1949866531893947, 1.433237435231539, 1.9800611569835205}), {0.32754411734255617, 0.40188889027254898}},
      // weights, degree 8: t = 0.00260120700814773, t2 = 0.0038855597221327362
      {Curve::rational("105", {0.00015477873318330994, 2997.6023638802785, 0.000851848024534651, 6.897625908008989, 22.90439131513085, 82.93876142729862, 0.11380540097639522, 1139.328542293098, 0.43794007062971485},
         {0.00030914788250950933, 8215.020218071642, 0.0022500271962042715, 9.206737963558384, 117.33180570873772, 507.1236145340584, 0.5982792975395747, 1749.7526864967535, 2.4086692648332106},
         {0.34035770661763626, 392.4603821930147, 2478.1026850369753, 132.73692137585593, 0.003642515795835082, 0.6648530953423233, 115.01030490049922, 0.0022290065610976787, 0.0003318881799037248},
         {0.3878194139454944, 660.7427004132226, 3476.7705751001304, 208.27750084787127, 0.04299125616578667, 0.6939464521401146, 206.556636369188, 0.0038132556319738736, 0.0016780330765134267}), {0.3648930856046726, 0.60668571712179742}},
  };
  for (const MissedRow& row : rows) {
    const double tolerance = 1e-6 * control_diagonal(row.curve);
    EXPECT_EQ(branches_within(row.curve, {row.point.x, row.point.y}, tolerance), 2) << row.curve.id;
  }
}

TEST(Branches, OneOnABranchTwoAtACrossingNoneFarAway) {
  std::mt19937_64 rng(5);
  for (const auto kind : {bezinv::CurveKind::bezier, bezinv::CurveKind::rational_bezier, bezinv::CurveKind::rational})
    for (int n = 3; n <= 9; n += 3) {
      const double t1 = 0.3, t2 = 0.7;
      const Curve curve = bezinv::datasets::with_self_intersection(kind, n, t1, t2, rng);
      const double tolerance = 1e-6 * control_diagonal(curve);
      const auto crossing = curve.point(t1);
      EXPECT_EQ(branches_within(curve, {crossing[0], crossing[1]}, tolerance), 2) << to_string(kind) << " " << n;
      const auto on = curve.point(0.5);  // isolated (with_self_intersection checks the crossing only)
      EXPECT_GE(branches_within(curve, {on[0], on[1]}, tolerance), 1) << to_string(kind) << " " << n;
      EXPECT_EQ(branches_within(curve, {on[0] + 10.0, on[1] + 10.0}, tolerance), 0) << to_string(kind) << " " << n;
    }
}

}  // namespace
