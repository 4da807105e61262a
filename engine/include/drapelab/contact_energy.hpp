// The energy stored in the springs of the contact on triangles at a shape of the cloth (J), part of
// the energy audit's total (docs/metrics.md, "Energy audit"): 1/2 k d^2 over every collider edge or
// corner a depth d (m) inside a cloth edge or triangle. Measured from positions alone, the same for
// every solver; the particles' share comes with their clearance queries (collision_metrics.hpp).
#pragma once

#include <Eigen/Core>
#include <memory>

#include "drapelab/cloth_model.hpp"
#include "drapelab/contact_model.hpp"

namespace drapelab {

class EdgeContact;

class ContactEnergyMeter {
 public:
  // `triangles`: whether the colliders' edges and corners push on the cloth's triangles
  // (contact.triangles).
  ContactEnergyMeter(const ClothModel& model, const ContactModel& contacts, bool triangles);
  ~ContactEnergyMeter();
  ContactEnergyMeter(const ContactEnergyMeter&) = delete;
  ContactEnergyMeter& operator=(const ContactEnergyMeter&) = delete;

  // Colliders posed at time t (s) by `contacts` (the scene's, or one solver's bodies'), x 3 x N
  // (m).
  double energy(const ContactModel& contacts, double t, const Eigen::Matrix3Xd& x);

 private:
  std::unique_ptr<EdgeContact> edges_;  // null without sharp features or triangles
};

}  // namespace drapelab
