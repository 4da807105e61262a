// Clearance metrics with a box lower bound, so that only particles that could beat the current
// minimum (or be in contact) pay for an exact FCL query.
#include "drapelab/collision_metrics.hpp"

#include <algorithm>
#include <limits>

namespace drapelab {

CollisionMetrics compute_collision_metrics(const ClothModel& model, const ClothState& state,
                                           const ContactModel& contacts, double t) {
  const double h = contacts.query().radius();
  const double contact_band = 0.1 * h;  // m: "in contact" within a tenth of the thickness
  const double stiffness = contacts.parameters().stiffness;  // N/m
  // A particle inside the thickness has a box distance below h, so it never skips the exact query.
  CollisionMetrics metrics;
  metrics.per_collider.resize(contacts.size());
  std::vector<char> touching(model.particle_count(), 0);
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const Eigen::Isometry3d pose = contacts.shape_pose(c, t);
    const Eigen::AlignedBox3d bounds = collider_bounds(contacts.fcl_collider(c), pose, 0.0);
    ColliderClearance& out = metrics.per_collider[c];
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < model.particle_count(); ++i) {
      // Distance to the bounding box is a lower bound of the distance to the shape.
      const double lower_bound = std::sqrt(bounds.squaredExteriorDistance(state.x.col(i))) - h;
      if (lower_bound > best && lower_bound > contact_band) continue;
      const double clearance =
          contacts.query().clearance(contacts.fcl_collider(c), pose, state.x.col(i));
      best = std::min(best, clearance);
      if (clearance < 0.0) metrics.contact_energy += 0.5 * stiffness * clearance * clearance;
      if (clearance <= contact_band) {
        ++out.contact_count;
        touching[i] = 1;
      }
    }
    out.min_clearance = best;
    out.max_penetration = std::max(0.0, -best);
  }
  metrics.min_clearance = std::numeric_limits<double>::infinity();
  for (const auto& c : metrics.per_collider)
    metrics.min_clearance = std::min(metrics.min_clearance, c.min_clearance);
  metrics.max_penetration = std::max(0.0, -metrics.min_clearance);
  metrics.contact_count = static_cast<int>(std::count(touching.begin(), touching.end(), 1));
  return metrics;
}

}  // namespace drapelab
