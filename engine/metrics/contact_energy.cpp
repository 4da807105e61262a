// The stored energy of the contact on triangles (contact_energy.hpp).
#include "drapelab/contact_energy.hpp"

#include "contact/edge_contact.hpp"

namespace drapelab {

ContactEnergyMeter::ContactEnergyMeter(const ClothModel& model, const ContactModel& contacts,
                                       bool triangles) {
  if (!triangles || model.triangles.cols() == 0) return;
  edges_ = std::make_unique<EdgeContact>(model, contacts);
  if (!edges_->active()) edges_.reset();
}

ContactEnergyMeter::~ContactEnergyMeter() = default;

double ContactEnergyMeter::energy(const ContactModel& contacts, double t,
                                  const Eigen::Matrix3Xd& x) {
  return edges_ ? edges_->stored_energy(contacts, t, x) : 0.0;
}

}  // namespace drapelab
