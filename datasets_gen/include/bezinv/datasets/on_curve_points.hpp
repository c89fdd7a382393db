#pragma once
// Points on the curve at known parameters: on the segment, at and near its ends, on its extension.
// Each set keeps only points that are isolated (kIsolation): a candidate parameter that fails the
// check is replaced by another draw, so a set may come back shorter than asked on a curve that
// crosses itself everywhere (never silently mislabelled).
#include <initializer_list>
#include <random>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/known_point.hpp"

namespace bezinv::datasets {

// Attempts per requested point before a point set (on or off the curve) gives up on a curve.
inline constexpr int kAttemptsPerPoint = 20;

// P(t) rounded to the nearest double point.
Point on_curve(const Curve& curve, double t);

// The KnownPoint for P(t) (distance = the rounding, speed, scale); not checked for isolation.
KnownPoint known_on_curve(const Curve& curve, double t);

// True when every branch of the curve other than those at `own` parameters is farther than
// kIsolation * diagonal from the point.
bool isolated(const CurveSampling& sampling, Point point, std::initializer_list<double> own);

// t uniform in [0,1].
std::vector<KnownPoint> segment_points(const CurveSampling& sampling, int count, std::mt19937_64& rng);

// t = 0, 1e-12, 1e-9, 1e-6, 1 - 1e-6, 1 - 1e-9, 1 - 1e-12, 1 (each as the nearest double).
std::vector<KnownPoint> end_points(const CurveSampling& sampling);

// t uniform in [-0.3, -0.01] u [1.01, 1.3], skipping parameters where a denominator falls below
// 1/20 of its largest coefficient (a pole nearby) and points within kIsolation * diagonal of the
// segment.
std::vector<KnownPoint> extension_points(const CurveSampling& sampling, int count, std::mt19937_64& rng);

}  // namespace bezinv::datasets
