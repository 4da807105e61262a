// The energy stored in the penalty contact's springs at a shape of the cloth (J), part of the
// energy audit's total (docs/metrics.md, "Energy audit"): 1/2 k d^2 over every particle a depth d
// (m) inside a collider's thickness, and, with contact on triangles, over every collider edge or
// corner as deep inside a cloth edge or triangle. Measured from positions alone, the same for every
// solver.
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

  struct Stored {
    double particles = 0.0;  // J, particles inside a collider's thickness
    double edges = 0.0;      // J, collider edges and corners inside the cloth's edges and triangles
    double total() const { return particles + edges; }
  };
  // Colliders posed at time t (s) by `contacts` (the scene's, or one solver's bodies'), x 3 x N
  // (m).
  Stored energy(const ContactModel& contacts, double t, const Eigen::Matrix3Xd& x);

 private:
  std::unique_ptr<EdgeContact> edges_;  // null without sharp features or triangles
};

}  // namespace drapelab
