// Penalty contact and Coulomb friction for one particle against one collider, as pure functions.
//
// Normal: a spring-damper along the collider's outward normal n that only pushes,
//   fn = max(0, k * depth - c * (v_rel . n))            (N; k in N/m, c in N*s/m, depth in m)
// Friction: velocity-level Coulomb with a static/kinetic distinction. Over a step h the friction force
// f_t either cancels the tangential relative velocity the particle would otherwise have at the end of
// the step (sticking: |f_t| <= mu_s fn), or, when that needs more, slides with |f_t| = mu_k fn against
// that velocity. Sticking is therefore exact (no creep) and sliding follows a = g (sin - mu_k cos).
#pragma once

#include <Eigen/Core>
#include <algorithm>

namespace drapelab {

// `normal_velocity`: relative velocity along the outward normal, m/s (> 0 separating).
inline double penalty_normal_force(double depth, double normal_velocity, double stiffness, double damping) {
  return std::max(0.0, stiffness * depth - damping * normal_velocity);
}

// `trial_tangential_velocity` (m/s): the tangential velocity relative to the collider's surface that
// the particle of `mass` (kg) would have after a step of h (s) under every force but friction.
// Returns the friction force (N), tangential.
inline Eigen::Vector3d coulomb_friction_force(const Eigen::Vector3d& trial_tangential_velocity, double mass,
                                              double h, double normal_force, double static_coefficient,
                                              double kinetic_coefficient) {
  const Eigen::Vector3d sticking = -mass / h * trial_tangential_velocity;  // stops it within the step
  const double needed = sticking.norm();
  if (needed <= static_coefficient * normal_force) return sticking;
  return (kinetic_coefficient * normal_force / needed) * sticking;
}

}  // namespace drapelab
