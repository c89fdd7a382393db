#pragma once
// The SVD path (paper Sect. 3), for the lanes the fast path leaves, and for every lane without it:
// stage 2 the SVD of B (symmetric: its eigendecomposition), stage 3 the algebraic t from the last
// singular vector, stage 4 refinement, stage 5 decide() with every candidate.
#include <cstddef>

#include "bezinv/invert.hpp"
#include "plan_data.hpp"
#include "pipeline/stage_clock.hpp"
#include "pipeline/workspace.hpp"

namespace bezinv::detail {

// Stages 2-5 for m compacted lanes: lane k's B is entry (r, c) at B[(r n + c) kBatchLanes + k],
// its point (u[k], v[k]), its answer *target[k]. Uses w's SVD and candidate storage.
void svd_path(const PlanData& plan, const double* B, const double* u, const double* v,
              PointResult* const* target, std::size_t m, const InvertOptions& options, BatchWorkspace& w,
              StageClock& clock);

}  // namespace bezinv::detail
