#pragma once
// The batch a thread works on: kBatchLanes points of one curve, stored lane by lane (structure of
// arrays), so that each stage is one loop over the batch (docs/README.md, "How a point flows").
#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "bezinv/tolerances.hpp"
#include "pipeline/candidate.hpp"

namespace bezinv::detail {

// Points per batch: enough to fill the kernels' SIMD groups, few enough that a batch's B matrices
// stay in cache up to moderate degrees. Speed only: no answer depends on it. Each stage after the
// seed runs its kernels on the lanes of one kind, compacted, and a kernel's last SIMD group runs
// whole however few lanes it holds: the more lanes a batch has, the less that costs, most of all
// in a batch of both kinds, where each kind has half of them (docs/fast-path.md, "Mixed batches").
// 128 rather than 64: on the curve 1.00-1.04x, off it 0.99-1.05x, mixed batches 1.02-1.06x at
// degrees 2-20; the workspace's matrices, sized for degree 32, then take 1 MB each per thread.
// At most 256: a lane's index is a byte.
inline constexpr std::size_t kBatchLanes = 128;
static_assert(kBatchLanes % 64 == 0 && kBatchLanes <= 256);

// A set of a batch's lanes: lane l is bit l % 64 of word l / 64.
class LaneSet {
 public:
  void add(std::size_t l, bool in) { words_[l / 64] |= static_cast<std::uint64_t>(in) << (l % 64); }
  bool has(std::size_t l) const { return (words_[l / 64] >> (l % 64)) & 1u; }
  // The lanes l < count (count <= kBatchLanes) where in(l) holds, without a branch per lane: each
  // word built in a register and stored once (add() stores to memory at every lane), so that a
  // batch whose lanes alternate between two kinds costs no mispredicted branches.
  template <class In>
  static LaneSet where(std::size_t count, In&& in) {
    LaneSet set;
    for (std::size_t i = 0; 64 * i < count; ++i) {
      std::uint64_t word = 0;
      const std::size_t end = std::min(count, 64 * (i + 1));
      for (std::size_t l = 64 * i; l < end; ++l) word |= std::uint64_t{static_cast<bool>(in(l))} << (l % 64);
      set.words_[i] = word;
    }
    return set;
  }
  // The lanes l < count (count <= kBatchLanes).
  static LaneSet first(std::size_t count) {
    LaneSet set;
    for (std::size_t i = 0; 64 * i < count; ++i)
      set.words_[i] = count >= 64 * (i + 1) ? ~std::uint64_t{0} : (std::uint64_t{1} << (count % 64)) - 1;
    return set;
  }
  // The lanes l < count whose flag is 1 (flags 0 or 1, as the workspace's byte arrays hold): eight
  // lanes a step, their bytes read as one word and gathered into eight bits by a multiplication
  // (byte j, 0 or 1, lands in bit 56 + j of the product, and no two bytes' terms meet).
  static LaneSet of_flags(std::size_t count, const std::uint8_t* flags) {
    static_assert(std::endian::native == std::endian::little, "byte j of the word is flags[l + j]");
    LaneSet set;
    std::size_t l = 0;
    for (; l + 8 <= count; l += 8) {
      std::uint64_t bytes;
      std::memcpy(&bytes, flags + l, sizeof bytes);
      set.words_[l / 64] |= ((bytes * 0x0102040810204080u) >> 56) << (l % 64);
    }
    for (; l < count; ++l) set.add(l, flags[l] != 0);
    return set;
  }
  // Its words, for a kernel that sets the bits of lanes (kernels::FormulaLanes).
  std::uint64_t* words() { return words_.data(); }
  // How many lanes it holds.
  std::size_t size() const {
    std::size_t n = 0;
    for (const std::uint64_t word : words_) n += static_cast<std::size_t>(std::popcount(word));
    return n;
  }
  bool empty() const {
    std::uint64_t any = 0;
    for (const std::uint64_t word : words_) any |= word;
    return any == 0;
  }
  // The lanes of both sets; of this set and not `other`.
  LaneSet both(const LaneSet& other) const {
    return combine(other, [](std::uint64_t a, std::uint64_t b) { return a & b; });
  }
  LaneSet without(const LaneSet& other) const {
    return combine(other, [](std::uint64_t a, std::uint64_t b) { return a & ~b; });
  }
  // f(l) for every lane l of the set, in order, one step per lane (no branch per lane of the batch:
  // where the lanes of two kinds alternate, that branch would be mispredicted half the time).
  template <class F>
  void for_each(F&& f) const {
    for (std::size_t i = 0; i < words_.size(); ++i)
      for (std::uint64_t word = words_[i]; word != 0; word &= word - 1)
        f(64 * i + static_cast<std::size_t>(std::countr_zero(word)));
  }

 private:
  template <class Op>
  LaneSet combine(const LaneSet& other, Op op) const {
    LaneSet out;
    for (std::size_t i = 0; i < words_.size(); ++i) out.words_[i] = op(words_[i], other.words_[i]);
    return out;
  }
  std::array<std::uint64_t, kBatchLanes / 64> words_{};
};

// Where lane l of a batch answers: results[l] for a batch of consecutive points (the common case:
// an address, not a load), *rows[l] for lanes gathered from several batches (by_kind.hpp).
class LaneRows {
 public:
  explicit LaneRows(PointResult* consecutive) : consecutive_(consecutive) {}
  explicit LaneRows(PointResult* const* gathered) : gathered_(gathered) {}
  PointResult& operator[](std::size_t l) const { return gathered_ != nullptr ? *gathered_[l] : consecutive_[l]; }

 private:
  PointResult* consecutive_ = nullptr;
  PointResult* const* gathered_ = nullptr;
};

// Per-thread storage for one batch, sized for the largest degree once: nothing is allocated per
// point or per batch. Matrices and vectors are lane-major: entry i of lane l at [i * kBatchLanes + l].
struct BatchWorkspace {
  std::array<double, kBatchLanes> u, v;          // the points, normalized (PlanData::normalize)
  std::array<std::uint8_t, kBatchLanes> active;  // lane still undecided
  std::vector<double> B = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kMaxDegree * kBatchLanes);
  // The SVD path: singular values and vectors, and the algebraic t read from the last vector.
  std::vector<double> sigma = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kBatchLanes);
  std::vector<double> V = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kMaxDegree * kBatchLanes);
  std::array<double, kBatchLanes> t_algebraic;
  // The fast path's lane-batched refinement: t and |P(t) - P0| (NaN where it left the lane to settle()).
  std::array<double, kBatchLanes> t_refined, distance;
  std::array<std::uint8_t, kBatchLanes> drops;      // a degree drop at the lane's point
  std::array<std::uint8_t, kBatchLanes> certified;  // pass 1: settled by the isolation certificate's first test
  std::array<Candidate, kBatchLanes> main;
  // Fast path (LU null vector): z, defect and the two sigma estimates (sigma_min at [l],
  // sigma_next at [kBatchLanes + l]).
  std::vector<double> z = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kBatchLanes);
  std::array<double, kBatchLanes> defect;
  std::array<double, 2 * kBatchLanes> estimate;
  // The formula path (formula_path.hpp): the lane's t_algebraic is the formula's, not the seed's.
  std::array<std::uint8_t, kBatchLanes> from_formula;
  // The gap pass (fast_path.cpp): its lanes compacted, gap lane k being batch lane gap_lane_of[k],
  // and the full kernel's outputs for them before they go back to their lanes.
  std::vector<double> gap_B = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kMaxDegree * kBatchLanes);
  std::vector<double> gap_z = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kBatchLanes);
  std::array<double, kBatchLanes> gap_defect;
  std::array<double, 2 * kBatchLanes> gap_estimate;
  std::array<std::uint8_t, kBatchLanes> gap_lane_of;
  // The lanes left for the SVD path, compacted to the front: compact lane k is batch lane lane_of[k].
  std::array<std::uint8_t, kBatchLanes> lane_of;
  // Lanes the off-curve path has looked at (fast_path clears it): it does not look at one twice.
  std::array<std::uint8_t, kBatchLanes> off_curve_tried;
};

// This thread's workspace.
BatchWorkspace& batch_workspace();

}  // namespace bezinv::detail
