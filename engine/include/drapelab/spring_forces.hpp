// The plain (edge-list) spring phase, adding into a force buffer (N, 3 x N): our solver's (its grid
// fast path is forces/spring_families.hpp, gravity and air drag one pass of
// forces/body_force_loops.hpp), and MuJoCo's cloth's, whose springs are ours applied as forces
// (mujoco_bridge/).
#pragma once

#include <Eigen/Core>

#include "drapelab/cloth_model.hpp"

namespace drapelab {

// Every spring's damped force (forces/spring_force.hpp), +f on v0 and -f on v1. Returns the power
// the dampers take, kd ((v0 - v1) . d / l)^2 summed over the springs (W).
double add_spring_forces(const ClothModel& model, const Eigen::Matrix3Xd& x,
                         const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force);

}  // namespace drapelab
