// The soft constraints as a force term: the bodies take the reactions of the step's last
// evaluation.
#include "constraints/soft_constraint_term.hpp"

namespace drapelab {

SoftConstraintTerm::SoftConstraintTerm(const DistanceConstraints& constraints)
    : constraints_(constraints), on_bodies_(constraints.any_on_dynamic()) {}

void SoftConstraintTerm::add(const ForceArgs& at, ForceSink& out) {
  constraints_.add_soft_forces(at.t, at.x, at.v, out.force, out.couplings,
                               on_bodies_ ? &loads_ : nullptr, &out.power);
}

}  // namespace drapelab
