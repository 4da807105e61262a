// The self-contacts as a force term: their springs store energy (the ledger reads it from the
// statistics), their dampers and friction dissipate.
#include "self_collision/self_contact_term.hpp"

namespace drapelab {

SelfContactTerm::SelfContactTerm(const ClothModel& model, const SelfCollisionSettings& settings)
    : inverse_mass_(model.inverse_mass), contact_(model, settings) {}

void SelfContactTerm::add(const ForceArgs& at, ForceSink& out) {
  contact_.add_forces(at.x, at.v, at.h, inverse_mass_, out.force, out.couplings);
  out.power.dissipated += contact_.stats().dissipated_power_last;
}

}  // namespace drapelab
