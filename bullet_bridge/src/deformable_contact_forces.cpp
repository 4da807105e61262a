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
  for (int body = 0; body < projection.m_softBodies.size(); ++body) {
    if (projection.m_softBodies[body] != &cloth || body >= projection.m_nodeRigidConstraints.size())
      continue;
    const auto& constraints = projection.m_nodeRigidConstraints[body];
    for (int k = 0; k < constraints.size(); ++k) {
      const btDeformableNodeRigidContactConstraint& constraint = constraints[k];
      const int c = colliders.index_of(constraint.getContact()->m_cti.m_colObj);
      if (c < 0 || constraint.m_node->m_im <= 0.0) continue;  // another body; a pinned node
      const double mass = 1.0 / constraint.m_node->m_im;      // kg
      const Eigen::Vector3d normal = to_eigen(constraint.getContact()->m_cti.m_normal);
      const double normal_dv =
          to_eigen(constraint.m_total_normal_dv).dot(normal);  // m/s, > 0 pushes
      forces[c].normal += mass * std::max(0.0, normal_dv) / h;
      forces[c].friction += mass * to_eigen(constraint.m_total_tangent_dv).norm() / h;
    }
  }
}

}  // namespace drapelab::bullet
