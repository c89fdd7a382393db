#pragma once
// Time per stage for `bezinv profile` (StageSeconds): a no-op unless the caller asked for it.
#include <chrono>

#include "bezinv/profile.hpp"

namespace bezinv::detail {

class StageClock {
 public:
  explicit StageClock(StageSeconds* stages) : stages_(stages) {
    if (stages_) last_ = std::chrono::steady_clock::now();
  }
  // Adds the time since the last lap to `stage`.
  void lap(double StageSeconds::*stage) {
    if (!stages_) return;
    const auto now = std::chrono::steady_clock::now();
    stages_->*stage += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }

 private:
  StageSeconds* stages_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace bezinv::detail
