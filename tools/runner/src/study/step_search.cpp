#include "drapelab/runner/step_search.hpp"

#include <algorithm>

namespace drapelab::runner {

StepSearchOutcome search_largest_stable_step(
    int start_k, const StepSearchLimits& limits,
    const std::function<std::optional<bool>(int k)>& trial) {
  StepSearchOutcome outcome;
  // Records a trial; false when it was interrupted.
  auto run = [&](int k) {
    const auto stable = trial(k);
    if (!stable) {
      outcome.stopped = true;
      return false;
    }
    if (*stable)
      outcome.stable_k = std::min(k, outcome.stable_k.value_or(k));
    else
      outcome.unstable_k = std::max(k, outcome.unstable_k.value_or(k));
    return true;
  };
  int k = std::clamp(start_k, limits.smallest_k, limits.largest_k);
  if (!run(k)) return outcome;
  // Bracket: grow the step while stable, shrink it while unstable.
  while (outcome.stable_k && !outcome.unstable_k && *outcome.stable_k > limits.smallest_k) {
    k = std::max(limits.smallest_k, (*outcome.stable_k + 1) / 2);
    if (!run(k)) return outcome;
  }
  while (!outcome.stable_k && *outcome.unstable_k < limits.largest_k) {
    k = *outcome.unstable_k > limits.largest_k / 2 ? limits.largest_k : 2 * *outcome.unstable_k;
    if (!run(k)) return outcome;
  }
  // Bisect on k. Every k tried lies strictly between the two; a stability that is not monotone in
  // the step (a smaller step failing where a larger one passed) is not detected, only bracketed.
  while (outcome.stable_k && outcome.unstable_k && *outcome.stable_k - *outcome.unstable_k > 1 &&
         static_cast<double>(*outcome.stable_k) / *outcome.unstable_k - 1.0 > limits.tolerance) {
    if (!run(*outcome.unstable_k + (*outcome.stable_k - *outcome.unstable_k) / 2)) return outcome;
  }
  return outcome;
}

}  // namespace drapelab::runner
