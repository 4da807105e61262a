// The penalty contact's stored energy (contact_energy.hpp).
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

ContactEnergyMeter::Stored ContactEnergyMeter::energy(const ContactModel& contacts, double t,
                                                      const Eigen::Matrix3Xd& x) {
  const double k = contacts.parameters().stiffness;    // N/m
  const double thickness = contacts.query().radius();  // m
  Stored stored;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const Eigen::Isometry3d pose = contacts.shape_pose(c, t);
    // Only a particle inside the collider's box grown by the thickness can be in contact.
    const Eigen::AlignedBox3d bounds = collider_bounds(contacts.fcl_collider(c), pose, thickness);
    for (Eigen::Index i = 0; i < x.cols(); ++i) {
      if (!bounds.contains(Eigen::Vector3d(x.col(i)))) continue;
      const double clearance = contacts.query().clearance(contacts.fcl_collider(c), pose, x.col(i));
      if (clearance < 0.0) stored.particles += 0.5 * k * clearance * clearance;
    }
  }
  if (edges_) stored.edges = edges_->stored_energy(contacts, t, x);
  return stored;
}

}  // namespace drapelab
