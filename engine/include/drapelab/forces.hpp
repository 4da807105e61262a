// The force phases of a step, as free functions that add into a force buffer (N, 3 x N).
#pragma once

#include <Eigen/Core>

#include "drapelab/cloth_model.hpp"

namespace drapelab {

// f_i += m_i g. Pinned particles receive it too; the integrator ignores them.
void add_gravity_forces(const ClothModel& model, const Eigen::Vector3d& gravity,
                        Eigen::Matrix3Xd& force);

// Every spring's damped force (spring_force.hpp), +f on v0 and -f on v1.
void add_spring_forces(const ClothModel& model, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                       Eigen::Matrix3Xd& force);

// Global viscous air damping: f_i += -air_damping * m_i * v_i (air_damping in 1/s).
void add_air_damping_forces(const ClothModel& model, double air_damping, const Eigen::Matrix3Xd& v,
                            Eigen::Matrix3Xd& force);

}  // namespace drapelab
