// Contact forces of Bullet's deformable world from its contact constraints (see the header).
#include "deformable_contact_forces.hpp"

#include <BulletSoftBody/btDeformableBackwardEulerObjective.h>

#include <algorithm>

#include "bullet_math.hpp"

namespace drapelab::bullet {

void deformable_contact_forces(const btDeformableBodySolver& solver, const btSoftBody& cloth,
                               const KinematicColliders& colliders, double h,
                               std::vector<ColliderForce>& forces) {
  forces.assign(forces.size(), ColliderForce{});
  const btDeformableContactProjection& projection = solver.m_objective->m_projection;
  // Each contact's velocity changes over the solve, times the mass they moved (the node's, or the
  // face's at the contact point, 1 / m_c2), over the step: its force on the collider.
  const auto add = [&](const auto& constraint) {
    const int c = colliders.index_of(constraint.getContact()->m_cti.m_colObj);
    const double inverse_mass = constraint.getContact()->m_c2;  // 1/kg
    if (c < 0 || inverse_mass <= 0.0) return;                   // another body; a pinned node
    const Eigen::Vector3d normal = to_eigen(constraint.getContact()->m_cti.m_normal);
    const double normal_dv = to_eigen(constraint.m_total_normal_dv).dot(normal);  // m/s, > 0 pushes
    forces[c].normal += std::max(0.0, normal_dv) / (inverse_mass * h);
    forces[c].friction += to_eigen(constraint.m_total_tangent_dv).norm() / (inverse_mass * h);
  };
  for (int body = 0; body < projection.m_softBodies.size(); ++body) {
    if (projection.m_softBodies[body] != &cloth) continue;
    if (body < projection.m_nodeRigidConstraints.size())
      for (int k = 0; k < projection.m_nodeRigidConstraints[body].size(); ++k)
        add(projection.m_nodeRigidConstraints[body][k]);
    if (body < projection.m_faceRigidConstraints.size())
      for (int k = 0; k < projection.m_faceRigidConstraints[body].size(); ++k)
        add(projection.m_faceRigidConstraints[body][k]);
  }
}

}  // namespace drapelab::bullet
