#include "stationary_points.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "bernstein_arithmetic.hpp"
#include "bezinv/tolerances.hpp"
#include "isolation.hpp"
#include "refine.hpp"

namespace bezinv::detail {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
using Poly = BernsteinPoly;

// The polynomials of g = G0 - u0 Gx - v0 Gy (the header's formulas), or with `bound` their bounds.
std::array<Poly, 3> stationary_polynomials(const PlanData& plan, bool bound) {
  auto load = [&](const std::vector<double>& c) {
    Poly p(c.begin(), c.end());
    if (bound)
      for (double& v : p) v = std::abs(v);
    return p;
  };
  const Poly X = load(plan.x_num), Wx = load(plan.x_den), Y = load(plan.y_num), Wy = load(plan.y_den);
  const double minus = bound ? 1.0 : -1.0;
  // H = N' D - N D' (degree 2n - 1 as written; its top coefficient cancels).
  const auto h = [&](const Poly& N, const Poly& D) {
    return combine(product(derivative(N, bound), D), product(N, derivative(D, bound)), minus, bound);
  };
  const Poly Hx = h(X, Wx), Hy = h(Y, Wy);
  if (plan.common_denominator) return {combine(product(X, Hx), product(Y, Hy), 1.0), product(Wx, Hx), product(Wx, Hy)};
  const Poly Wx3 = product(product(Wx, Wx), Wx), Wy3 = product(product(Wy, Wy), Wy);
  return {combine(product(product(X, Hx), Wy3), product(product(Y, Hy), Wx3), 1.0), product(product(Wx, Hx), Wy3),
          product(product(Wy, Hy), Wx3)};
}

// The sign changes of c[0..m], or -1 where an interior coefficient is within `slack` of zero (its
// sign not to be trusted). An end coefficient within it means f' is about 0 at that end of the
// interval (a minimum exactly at a piece's boundary: a symmetric curve's middle): it is counted
// with its neighbour's sign, and near_first / near_last say so; the caller then refines from
// that end, which finds the stationary point there (the interval holds no other it would miss:
// the count without that end's change covers the rest).
int sign_changes(const double* c, int m, double slack, bool& near_first, bool& near_last) {
  const auto trusted = [&](int k) { return std::abs(c[k]) > slack; };  // false for NaN too
  near_first = !trusted(0);
  near_last = !trusted(m);
  if (m == 0 || (near_first && !trusted(1)) || (near_last && !trusted(m - 1))) return -1;
  int changes = 0;
  bool last_negative = (near_first ? c[1] : c[0]) < 0;
  for (int k = 1; k <= m; ++k) {
    if (k < m && !trusted(k)) return -1;
    const bool negative = (k == m && near_last ? c[m - 1] : c[k]) < 0;
    if (negative != last_negative) ++changes;
    last_negative = negative;
  }
  return changes;
}

// A lower bound of the distance from (u0, v0) to the curve on [a, b]: the nearest of the isolation
// boxes of the pieces that meet it (0 where there are none).
double box_lower_bound(const PlanData& plan, double u0, double v0, double a, double b) {
  const int K = plan.isolation_pieces;
  if (K == 0) return 0.0;
  const int first = std::clamp(static_cast<int>(std::floor(a * K)), 0, K - 1);
  const int last = std::clamp(static_cast<int>(std::ceil(b * K)) - 1, first, K - 1);
  double nearest2 = std::numeric_limits<double>::infinity();
  for (int i = first; i <= last; ++i) nearest2 = std::min(nearest2, isolation_box_distance2(plan, i, u0, v0));
  const double nearest = std::sqrt(nearest2);
  return nearest * (1 - kIsolationMargin);
}

// The square of the same from the box around all of piece `piece`'s isolation boxes (one box, so
// looser: it rules out the far pieces before the finer bound above is worth its cost).
double piece_lower_bound2(const OffCurveData& data, double u0, double v0, int piece) {
  return box_distance2(data.stationary_boxes.data() + 4 * piece, u0, v0) *
         ((1 - kIsolationMargin) * (1 - kIsolationMargin));
}

// Where the control polygon of g on [a, b] (coefficients c[0..m]) first crosses from below zero to
// above it: near g's one root there, and inside (a, b).
double polygon_crossing(const double* c, int m, double a, double b) {
  for (int j = 0; j < m; ++j)
    if (c[j] < 0 && c[j + 1] > 0) return a + (b - a) * (j + c[j] / (c[j] - c[j + 1])) / m;
  return 0.5 * (a + b);
}

// The one minimum of f in (a, b), where f' < 0 at a and > 0 at b: Newton's method on f' from
// `start` (in [a, b]), each step kept inside the bracket (bisection where it would leave it), then
// refine_parameter's last steps, so the answer ends as the sampling search's would.
Refined bracketed_minimum(const PlanData& plan, double u0, double v0, double a, double b, double start) {
  double lo = a, hi = b, t = start;
  for (int iteration = 0; iteration < 2 * kNewtonMaxIterations; ++iteration) {
    const CurveJet j = curve_jet(plan, t);
    const double ex = j.x - u0, ey = j.y - v0;
    const double slope1 = ex * j.dx + ey * j.dy;
    const double slope2 = j.dx * j.dx + j.dy * j.dy + ex * j.ddx + ey * j.ddy;
    if (!std::isfinite(slope1) || slope1 == 0) break;
    (slope1 < 0 ? lo : hi) = t;
    double next = slope2 > 0 ? t - slope1 / slope2 : lo - 1;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool done = std::abs(next - t) <= kNewtonStopUlps * kEpsilon * std::max(1.0, std::abs(t));
    t = next;
    if (done || hi - lo <= kNewtonStopUlps * kEpsilon) break;
  }
  return refine_parameter(plan, u0, v0, t, /*stay_on_segment=*/true);
}

}  // namespace

void stationary_pieces(const PlanData& plan, OffCurveData& data) {
  const std::array<Poly, 3> g = stationary_polynomials(plan, false), bound = stationary_polynomials(plan, true);
  const int m = static_cast<int>(g[0].size()) - 1;
  // The sign of Wx^3 Wy^3 (W^3) on [0, 1], so that G0 - u0 Gx - v0 Gy has the sign of f'.
  const double sign = plan.common_denominator ? (plan.x_den[0] > 0 ? 1.0 : -1.0)
                                              : ((plan.x_den[0] > 0) == (plan.y_den[0] > 0) ? 1.0 : -1.0);
  data.stationary_degree = m;
  data.stationary_g.assign(static_cast<std::size_t>(kStationaryPieces) * 3 * (m + 1), 0.0);
  data.stationary_scale.assign(static_cast<std::size_t>(kStationaryPieces) * 3, 0.0);
  data.stationary_boxes.assign(static_cast<std::size_t>(kStationaryPieces) * 4, 0.0);
  // g and its bounds on every piece, as polynomials of [0, 1]: the pieces of one level halved into
  // the next's, in order (each halving rounds once per level on the bound of the terms, within the
  // sign test's kStationarySignUlps).
  static_assert(std::has_single_bit(static_cast<unsigned>(kStationaryPieces)));
  std::vector<std::array<Poly, 6>> pieces{{g[0], g[1], g[2], bound[0], bound[1], bound[2]}};
  while (static_cast<int>(pieces.size()) < kStationaryPieces) {
    std::vector<std::array<Poly, 6>> next(2 * pieces.size());
    for (std::size_t i = 0; i < pieces.size(); ++i)
      for (int which = 0; which < 6; ++which) halve(pieces[i][which], next[2 * i][which], next[2 * i + 1][which]);
    pieces = std::move(next);
  }
  const int K = plan.isolation_pieces;
  for (int piece = 0; piece < kStationaryPieces; ++piece) {
    for (int which = 0; which < 3; ++which) {
      const Poly& on_piece = pieces[piece][which];
      double* out = data.stationary_g.data() + (static_cast<std::size_t>(piece) * 3 + which) * (m + 1);
      for (int k = 0; k <= m; ++k) out[k] = sign * on_piece[k];
      data.stationary_scale[piece * 3 + which] = max_abs(pieces[piece][3 + which]);
    }
    // The box around the isolation boxes of the piece (the whole plane without them).
    double* box = data.stationary_boxes.data() + 4 * piece;
    const double inf = std::numeric_limits<double>::infinity();
    box[0] = box[2] = K > 0 ? inf : -inf;
    box[1] = box[3] = K > 0 ? -inf : inf;
    const double* boxes = plan.isolation_boxes.data();  // x centres, x half-widths, y centres, y half-widths
    for (int q = piece * K / kStationaryPieces; K > 0 && q < (piece + 1) * K / kStationaryPieces; ++q) {
      box[0] = std::min(box[0], boxes[q] - boxes[K + q]), box[1] = std::max(box[1], boxes[q] + boxes[K + q]);
      box[2] = std::min(box[2], boxes[2 * K + q] - boxes[3 * K + q]);
      box[3] = std::max(box[3], boxes[2 * K + q] + boxes[3 * K + q]);
    }
  }
}

NearestOnSegment certified_nearest_on_segment(const PlanData& plan, double u0, double v0, double hint,
                                              double hint_distance, int hint_stationary) {
  const OffCurveData& data = off_curve_data(plan);
  NearestOnSegment best;
  best.distance = std::numeric_limits<double>::infinity();
  const int m = data.stationary_degree;
  if (m <= 0 || !std::isfinite(u0) || !std::isfinite(v0)) return best;
  // A candidate replaces the best so far only when nearer by more than the rounding of the two
  // distances: where two parameters are equally near (a curve traced twice, a point on an axis of
  // symmetry) the first found stays, and the hint is looked at first, as the sampling search does.
  const auto consider = [&](double t, double d) {
    if (d < best.distance * (1 - kNearestTieUlps * kEpsilon)) best.t = t, best.distance = d;
  };
  // The upper bound to beat: the refined hint, then the ends of the segment. Where the hint ends
  // at a stationary point, the interval below that holds it needs no search of its own.
  double stationary_hint = std::numeric_limits<double>::quiet_NaN();
  if (hint >= 0.0 && hint <= 1.0) {
    const bool refined = std::isfinite(hint_distance);
    const Refined r = refined ? Refined{hint, hint_distance}
                              : refine_parameter(plan, u0, v0, hint, /*stay_on_segment=*/true);
    consider(r.t, r.distance);
    if (refined && hint_stationary >= 0 ? hint_stationary == 1 : stationary_point(plan, u0, v0, r.t, r.distance)) {
      stationary_hint = r.t;
      // The quick proof: the isolation certificate with the point's own distance (a point near
      // one branch, most points: one comparison instead of the search below).
      if (nearest_on_segment(plan, u0, v0, r.t, r.distance)) {
        best.certified = true;
        return best;
      }
    }
  }
  // P(0) and P(1) are the first and last of the sampling search's samples (make_plan).
  const double* samples = plan.nearest_samples.data();
  const int sample_count = static_cast<int>(plan.nearest_samples.size() / 2) - 1;
  const auto sample_distance = [&](int k) {
    const double dx = samples[2 * k] - u0, dy = samples[2 * k + 1] - v0;
    return std::sqrt(dx * dx + dy * dy);  // no overflow: the caller brings far points within kFarEqualDistances
  };
  consider(0.0, sample_distance(0));
  consider(1.0, sample_distance(sample_count));
  if (!std::isfinite(best.distance)) return best;

  // The pieces, nearest lower bound first, so the bound tightens before the far ones are looked
  // at; in their own order where the hint is a stationary point (then usually the answer, and
  // the bound is already tight).
  std::array<std::pair<double, int>, kStationaryPieces> order;
  for (int piece = 0; piece < kStationaryPieces; ++piece) order[piece] = {piece_lower_bound2(data, u0, v0, piece), piece};
  if (!(stationary_hint >= 0.0)) std::sort(order.begin(), order.end());

  struct Interval {
    double a, b;
    int halvings;
    std::array<double, kMaxBernsteinDegree + 1> c;
  };
  // Depth first: at most one interval waits per halving level, and the one in hand.
  std::array<Interval, kStationaryMaxHalvings + 2> stack;
  int waiting = 0;
  const double gamma = kStationarySignUlps * (m + 1) * kEpsilon;
  for (const auto& [lower_bound2, piece] : order) {
    if (lower_bound2 > best.distance * best.distance) {
      if (stationary_hint >= 0.0) continue;
      break;  // sorted: so are all the others
    }
    if (box_lower_bound(plan, u0, v0, static_cast<double>(piece) / kStationaryPieces,
                        static_cast<double>(piece + 1) / kStationaryPieces) > best.distance)
      continue;
    const double* G = data.stationary_g.data() + static_cast<std::size_t>(piece) * 3 * (m + 1);
    const double* scale = data.stationary_scale.data() + piece * 3;
    const double slack = gamma * (scale[0] + std::abs(u0) * scale[1] + std::abs(v0) * scale[2]);
    Interval& first = stack[waiting++];
    first.a = static_cast<double>(piece) / kStationaryPieces;
    first.b = static_cast<double>(piece + 1) / kStationaryPieces;
    first.halvings = 0;
    for (int k = 0; k <= m; ++k) first.c[k] = G[k] - u0 * G[m + 1 + k] - v0 * G[2 * (m + 1) + k];
    while (waiting > 0) {
      // The interval in hand stays in its slot: halving writes its two halves over it and the next.
      Interval& here = stack[--waiting];
      if (here.halvings > 0 && box_lower_bound(plan, u0, v0, here.a, here.b) > best.distance) continue;
      // The slack stays that of the whole piece: de Casteljau's convex combinations do not enlarge
      // the terms, and add rounding far below it.
      bool near_first = false, near_last = false;
      const int changes = sign_changes(here.c.data(), m, slack, near_first, near_last);
      if (changes < 0) return best;  // a sign not to be trusted
      for (const auto& [near, end] : {std::pair{near_first, here.a}, std::pair{near_last, here.b}})
        if (near) {
          const Refined r = refine_parameter(plan, u0, v0, end, /*stay_on_segment=*/true);
          consider(r.t, r.distance);
        }
      if (changes == 0) continue;    // f monotone here: its minimum is at an end, looked at elsewhere
      if (changes == 1) {
        // f decreases, then increases: one minimum inside (the first sign as counted).
        if ((near_first ? here.c[1] : here.c[0]) < 0) {
          // The interval's one stationary point is its minimum: the hint's, if it ended inside;
          // otherwise refined from the nearest of the samples inside (or the middle), and kept
          // there by bracketing if the refinement would leave.
          // An end whose coefficient is about 0 may be a stationary point of its own, not this
          // minimum (a maximum where the curve turns back: P' = 0 on an improper parametrization):
          // then the start is where g's control polygon crosses zero, and an answer at that end
          // is refused.
          if (here.a < stationary_hint && stationary_hint < here.b) continue;
          double start = 0.5 * (here.a + here.b), nearest = std::numeric_limits<double>::infinity();
          if (near_first || near_last) {
            start = polygon_crossing(here.c.data(), m, here.a, here.b);
          } else {
            for (int k = static_cast<int>(std::ceil(here.a * sample_count)); k <= sample_count && k <= here.b * sample_count; ++k)
              if (const double d = sample_distance(k); d < nearest) nearest = d, start = static_cast<double>(k) / sample_count;
          }
          Refined r = refine_parameter(plan, u0, v0, start, /*stay_on_segment=*/true);
          const bool at_flagged_end = (near_first && r.t <= here.a) || (near_last && r.t >= here.b);
          if (!(here.a <= r.t && r.t <= here.b && !at_flagged_end && stationary_point(plan, u0, v0, r.t, r.distance)))
            r = bracketed_minimum(plan, u0, v0, here.a, here.b, start);
          consider(r.t, r.distance);
        }
        continue;
      }
      if (here.halvings == kStationaryMaxHalvings) return best;
      // split reads the coefficients into its own workspace first, so `here` (the slot of the
      // right half) may be overwritten; the left half goes on top and is looked at next.
      const double a = here.a, b = here.b, middle = 0.5 * (a + b);
      const int halvings = here.halvings + 1;
      Interval& right = here;
      Interval& left = stack[waiting + 1];
      split(here.c.data(), m, 0.5, left.c.data(), right.c.data());
      left.a = a, left.b = middle, left.halvings = halvings;
      right.a = middle, right.b = b, right.halvings = halvings;
      waiting += 2;
    }
  }
  best.certified = true;
  return best;
}

}  // namespace bezinv::detail
