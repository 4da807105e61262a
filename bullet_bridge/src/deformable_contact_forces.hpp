// Contact forces of Bullet's deformable world, read from its own contact solve (not estimated).
#pragma once

#include <BulletSoftBody/btDeformableBodySolver.h>
#include <BulletSoftBody/btSoftBody.h>

#include <vector>

#include "bullet_colliders.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::bullet {

// The force each collider exerted on `cloth` during the step of h (s) just taken, from the
// node-rigid contact constraints that `solver` solved in it. Each constraint holds the velocity
// change its impulses gave the node, m_total_normal_dv and m_total_tangent_dv (m/s): a node of mass
// m (kg) whose velocity a contact changed by dv in a step h received the mean force m dv / h (N).
// The normal part counts only when it pushes (dv . n > 0). These are public members of public
// Bullet classes (btDeformableBodySolver::m_objective -> m_projection.m_nodeRigidConstraints);
// Bullet clears them at the start of the next step, so read them right after stepSimulation.
// `forces` (one per collider) is overwritten.
void deformable_contact_forces(const btDeformableBodySolver& solver, const btSoftBody& cloth,
                               const KinematicColliders& colliders, double h,
                               std::vector<ColliderForce>& forces);

}  // namespace drapelab::bullet
