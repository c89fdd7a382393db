#include "bezinv/datasets/branches.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace bezinv::datasets {
namespace {

// Pieces kept at once, and halvings of [0, 1]: a piece 2^-60 wide is far below any tolerance's
// parameter span (the runs are what matter, not the pieces' size).
constexpr int kMaxPieces = 4096;
constexpr int kMaxDepth = 60;

struct Piece {
  Real t0, t1;
  int depth;
  std::array<std::vector<Real>, 4> c;  // x_num, x_den, y_num, y_den on [t0, t1]
};

// The control points' box distance from p and its diagonal, or false where a denominator
// coefficient is not positive (no box).
bool box(const Piece& piece, RealPoint p, Real& distance, Real& diagonal) {
  Real x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
  for (std::size_t i = 0; i < piece.c[0].size(); ++i) {
    if (!(piece.c[1][i] > 0) || !(piece.c[3][i] > 0)) return false;
    const Real x = piece.c[0][i] / piece.c[1][i], y = piece.c[2][i] / piece.c[3][i];
    x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x), y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
  }
  const Real dx = std::max({x_lo - p.x, p.x - x_hi, Real(0)}), dy = std::max({y_lo - p.y, p.y - y_hi, Real(0)});
  distance = std::hypot(dx, dy);
  diagonal = std::hypot(x_hi - x_lo, y_hi - y_lo);
  return true;
}

// The halves of a piece (de Casteljau at 1/2).
void halve(const Piece& piece, Piece& left, Piece& right) {
  const Real middle = (piece.t0 + piece.t1) / 2;
  left.t0 = piece.t0, left.t1 = middle, right.t0 = middle, right.t1 = piece.t1;
  left.depth = right.depth = piece.depth + 1;
  for (int k = 0; k < 4; ++k) {
    std::vector<Real> b = piece.c[k];
    const std::size_t n = b.size();
    left.c[k].resize(n);
    right.c[k].resize(n);
    for (std::size_t r = 0; r < n; ++r) {
      left.c[k][r] = b[0];
      right.c[k][n - 1 - r] = b[n - 1 - r];
      for (std::size_t i = 0; i + 1 < n - r; ++i) b[i] = (b[i] + b[i + 1]) / 2;
    }
  }
}

}  // namespace

int branches_within(const Curve& curve, RealPoint point, Real radius) {
  Piece whole;
  whole.t0 = 0, whole.t1 = 1, whole.depth = 0;
  const std::vector<double>* polys[4] = {&curve.x_num, &curve.x_den, &curve.y_num, &curve.y_den};
  for (int k = 0; k < 4; ++k) whole.c[k].assign(polys[k]->begin(), polys[k]->end());
  std::vector<Piece> stack{whole};
  std::vector<std::array<Real, 2>> kept;
  while (!stack.empty()) {
    Piece piece = std::move(stack.back());
    stack.pop_back();
    Real distance = 0, diagonal = 0;
    if (!box(piece, point, distance, diagonal)) return -1;
    if (distance > radius) continue;
    if (diagonal <= radius / 8 || piece.depth >= kMaxDepth) {
      kept.push_back({piece.t0, piece.t1});
      if (static_cast<int>(kept.size()) > kMaxPieces) return -1;
      continue;
    }
    Piece left, right;
    halve(piece, left, right);
    stack.push_back(std::move(right));
    stack.push_back(std::move(left));
    if (static_cast<int>(stack.size()) > kMaxPieces) return -1;
  }
  std::sort(kept.begin(), kept.end());
  int runs = 0;
  for (std::size_t i = 0; i < kept.size(); ++i)
    if (i == 0 || kept[i][0] != kept[i - 1][1]) ++runs;
  return runs;
}

}  // namespace bezinv::datasets
