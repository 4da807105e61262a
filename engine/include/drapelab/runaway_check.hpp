// The health check every solver without its own runs after a step (Bullet's cloths, MuJoCo's):
// the first particle whose position or velocity is not finite, or that moves faster than the
// runaway limit, named with the step and what to try.
#pragma once

#include <optional>
#include <string>

#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"

namespace drapelab {

// A message naming the first non-finite or runaway particle of `state` (faster than max_speed,
// m/s), the step just taken (of h, s) and `advice`; nothing when healthy.
std::optional<std::string> runaway_message(const ClothModel& model, const ClothState& state,
                                           double max_speed, double h, const std::string& advice);

}  // namespace drapelab
