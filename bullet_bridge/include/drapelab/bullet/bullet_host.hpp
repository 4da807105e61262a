// Our cloth as a plugin in a Bullet rigid-body world: the solver is stepped by Bullet as an action
// (btActionInterface), inside a btSoftRigidDynamicsWorld whose kinematic colliders are driven exactly
// like those of Bullet's cloth (the same pre-tick code, the same collider_pose(t)). The cloth does
// not collide with Bullet's cloth: each solver has its own world (bullet-notes 2.3).
#pragma once

#include <memory>
#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::bullet {

std::unique_ptr<Solver> host_in_bullet_world(std::unique_ptr<Solver> guest, const std::vector<Collider>& colliders,
                                             const Eigen::Vector3d& gravity, double collider_margin = 1e-3);

}  // namespace drapelab::bullet
