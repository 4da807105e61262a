// Adds the wall time of one phase of the step into the step statistics when it goes out of scope.
#pragma once

#include <chrono>

#include "drapelab/step_stats.hpp"

namespace drapelab {

using StepClock = std::chrono::steady_clock;

class PhaseTimer {
 public:
  PhaseTimer(StepStats& stats, StepPhase phase)
      : stats_(stats), phase_(phase), start_(StepClock::now()) {}
  ~PhaseTimer() {
    stats_.seconds[static_cast<int>(phase_)] +=
        std::chrono::duration<double>(StepClock::now() - start_).count();
  }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  StepStats& stats_;
  StepPhase phase_;
  StepClock::time_point start_;
};

}  // namespace drapelab
