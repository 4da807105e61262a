// The air as a force term: drag against the wind dissipates, the wind's push does work.
#include "air/air_term.hpp"

namespace drapelab {

AirTerm::AirTerm(const ClothModel& model, const AirSettings& air)
    : model_(model), air_(air), wind_(air) {}

void AirTerm::add(const ForceArgs& at, ForceSink& out) {
  add_air_forces(model_, air_, wind_, at.t, at.x, at.v, out.force, &out.power);
}

}  // namespace drapelab
