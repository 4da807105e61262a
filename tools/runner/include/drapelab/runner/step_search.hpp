// The search of `drapelab stability`: the largest stable step of the form frame_period / k (k whole
// steps per frame), so every trial records the same frames. Larger k = smaller step = (normally)
// more stable, so the search looks for the smallest stable k:
//   1. try the start k (the scene's step);
//   2. if stable, halve k (double the step) until a trial is unstable or k reaches the smallest
//   allowed;
//      if unstable, double k (halve the step) until a trial is stable or k reaches the largest
//      allowed;
//   3. bisect on k between the smallest stable and the largest unstable k until they are neighbours
//   or
//      the relative gap of their steps, k_stable / k_unstable - 1, is at most the tolerance.
#pragma once

#include <functional>
#include <optional>

namespace drapelab::runner {

struct StepSearchLimits {
  int smallest_k = 1;       // from --max-dt: frame_period / smallest_k is the largest step tried
  int largest_k = 1000000;  // frame_period / 1e6 is the smallest step tried
  double tolerance = 0.01;  // relative gap of the two steps at which the bisection may stop early
};

struct StepSearchOutcome {
  std::optional<int> stable_k;  // smallest k found stable (the largest stable step)
  std::optional<int>
      unstable_k;        // largest k found unstable, below stable_k (the smallest unstable step)
  bool stopped = false;  // a trial was interrupted; the outcome is what was known by then
};

// `trial(k)` runs the solver with frame_period / k and says whether it stayed stable, or nothing
// when it was interrupted. Each k is tried at most once.
StepSearchOutcome search_largest_stable_step(
    int start_k, const StepSearchLimits& limits,
    const std::function<std::optional<bool>(int k)>& trial);

}  // namespace drapelab::runner
