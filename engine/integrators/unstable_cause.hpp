// What acted on the cloth in the step where our solver became unstable, for its message beside the
// hint (docs/physics.md, "How unstable runs stop"): each kind of contact and the colliders or
// particles involved. A collider whose particles reach deeper than the cloth's thickness holds them
// inside its solid, the usual cause of a run that blows up in its first steps.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "contact/edge_contact.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/distance_constraints.hpp"

namespace drapelab {

// What the step's last force evaluation saw; each pointer null when the solver has no such kind.
struct StepContactsSeen {
  const ContactModel* colliders = nullptr;
  const std::vector<ColliderContactTotals>* totals = nullptr;   // per collider: particles and edges
  const std::vector<EdgeContactTotals>* edge_totals = nullptr;  // per collider: the edges alone
  std::int64_t self_contacts = -1;                              // -1: no self-collision
  const DistanceConstraints* constraints = nullptr;             // with the drags
};

// " In that step: ..." naming the contacts of every kind that acted, and the constraints and drags
// that end on `particle` (the particle that failed); empty when nothing but springs, gravity and
// air acted.
std::string unstable_step_cause(const ClothModel& model, const StepContactsSeen& seen,
                                int particle);

}  // namespace drapelab
