// The collider edges' contacts as a force term. Their power is in their per-collider totals,
// which the evaluator adds to the particle contacts' (so the ledger counts it once).
#include "contact/edge_contact_term.hpp"

namespace drapelab {

EdgeContactTerm::EdgeContactTerm(const ClothModel& model, const ContactModel& contacts)
    : contacts_(contacts), inverse_mass_(model.inverse_mass), contact_(model, contacts) {}

void EdgeContactTerm::add(const ForceArgs& at, ForceSink& out) {
  contact_.add_forces(contacts_, at.t, at.h, at.x, at.v, inverse_mass_, out.force, out.couplings);
}

}  // namespace drapelab
