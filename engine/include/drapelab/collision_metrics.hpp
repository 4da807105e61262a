// Collision metrics of any solver's state, from the same FCL queries as our contact
// (docs/metrics.md, "Per frame (`metrics.csv`)"): clearance d_c(x_i) - h of every particle to every
// collider, h the cloth's thickness.
#pragma once

#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/contact_model.hpp"

namespace drapelab {

struct ColliderClearance {
  int contact_count = 0;         // particles with clearance <= 0.1 h to this collider
  double min_clearance = 0.0;    // m
  double max_penetration = 0.0;  // m, max(0, -min_clearance)
};

struct CollisionMetrics {
  double min_clearance = 0.0;    // m, over particles and colliders
  double max_penetration = 0.0;  // m
  int contact_count = 0;         // particles with clearance <= 0.1 h for some collider
  double contact_energy = 0.0;   // J: 1/2 k_c c^2 over particles at a clearance c < 0
  std::vector<ColliderClearance> per_collider;
};

// Colliders posed at time t (s). Requires at least one collider.
CollisionMetrics compute_collision_metrics(const ClothModel& model, const ClothState& state,
                                           const ContactModel& contacts, double t);

}  // namespace drapelab
