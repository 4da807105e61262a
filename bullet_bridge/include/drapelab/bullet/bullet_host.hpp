// Our cloth as a plugin in a Bullet rigid-body world: the solver is stepped by Bullet's pre-tick
// callback, inside a btSoftRigidDynamicsWorld whose kinematic colliders are driven exactly like
// those of Bullet's cloth (the same pre-tick code, the same collider_pose(t)), and whose dynamic
// colliders are rigid bodies that the cloth's contact loads move (two-way coupling: the guest steps
// first, then its loads go onto the bodies, which the world integrates in the same substep). The
// cloth does not collide with Bullet's cloth: each solver has its own world (docs/bullet.md,
// "Parallel worlds with the same colliders").
//
// The guest touches the colliders Bullet holds: just before each guest step the host writes into
// `guest_poses` the substep's start and end poses of its Bullet bodies and the velocities it gave
// them, and the guest's ContactModel is built on that table (collider_pose_table.hpp).
#pragma once

#include <memory>
#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/collider_pose_table.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::bullet {

// `guest_poses` needs one entry per collider (std::invalid_argument otherwise); `collider_margin`
// (m) rounds Bullet's box and cylinder edges, as for Bullet's cloths.
std::unique_ptr<Solver> host_in_bullet_world(std::unique_ptr<Solver> guest,
                                             std::shared_ptr<ColliderPoseTable> guest_poses,
                                             const std::vector<Collider>& colliders,
                                             const Eigen::Vector3d& gravity,
                                             double collider_margin);

}  // namespace drapelab::bullet
