// The plain (edge-list) spring phase, adding into a force buffer (N, 3 x N). Gravity and air drag
// are one pass of body_force_loops.hpp; the grid fast path is spring_families.hpp.
#pragma once

#include <Eigen/Core>

#include "drapelab/cloth_model.hpp"

namespace drapelab {

// Every spring's damped force (spring_force.hpp), +f on v0 and -f on v1. Returns the power the
// dampers take, kd ((v0 - v1) . d / l)^2 summed over the springs (W).
double add_spring_forces(const ClothModel& model, const Eigen::Matrix3Xd& x,
                         const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force);

}  // namespace drapelab
