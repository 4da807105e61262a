// The health check of the solvers without their own (runaway_check.hpp).
#include "drapelab/runaway_check.hpp"

#include <sstream>

namespace drapelab {

std::optional<std::string> runaway_message(const ClothModel& model, const ClothState& state,
                                           double max_speed, double h, const std::string& advice) {
  for (int i = 0; i < model.particle_count(); ++i) {
    const bool finite = state.x.col(i).allFinite() && state.v.col(i).allFinite();
    const double speed = finite ? state.v.col(i).norm() : 0.0;
    if (finite && speed <= max_speed) continue;
    std::ostringstream text;
    text.precision(4);
    text << "node " << i << " (" << model.describe_particle(i) << ") ";
    if (finite)
      text << "moves at " << speed << " m/s, above the runaway limit of " << max_speed << " m/s";
    else
      text << "has a non-finite position or velocity";
    text << " after step " << state.step_count << " (t = " << state.time << " s, dt = " << h
         << " s). Try: " << advice;
    return text.str();
  }
  return std::nullopt;
}

}  // namespace drapelab
