// Penalty contact and Coulomb friction for one particle against one collider, as pure functions.
//
// Normal: a spring-damper along the collider's outward normal n that only pushes,
//   fn = max(0, k * depth - c * (v_rel . n))            (N; k in N/m, c in N*s/m, depth in m)
// Friction: velocity-level Coulomb with a static/kinetic distinction. Over a step h the friction force
// f_t either cancels the tangential relative velocity the particle would otherwise have at the end of
// the step (sticking: |f_t| <= mu_s fn), or, when that needs more, slides with |f_t| = mu_k fn against
// that velocity. Sticking is therefore exact (no creep) and sliding follows a = g (sin - mu_k cos).
//
// Under symplectic Euler the normal force can instead be the one the step's end state implies
// (linearly_implicit_normal_force): the contact spring and damper then never limit the step size.
#pragma once

#include <Eigen/Core>
#include <algorithm>

namespace drapelab {

// `normal_velocity`: relative velocity along the outward normal, m/s (> 0 separating).
inline double penalty_normal_force(double depth, double normal_velocity, double stiffness, double damping) {
  return std::max(0.0, stiffness * depth - damping * normal_velocity);
}

// The normal force of the same spring-damper evaluated at the end of a symplectic Euler step
// (v' = v + h f / m, x' = x + h v') instead of at its start, with every other force on the particle
// held at its start value. Along the normal, with u the relative normal velocity, f_o the normal
// component of the other forces and the depth advanced to depth - h u', the step is
//   u' = u + (h / m) (f_o + fn'),   fn' = k (depth - h u') - c u',
// linear in u', so
//   fn' = [k depth - (c + h k) (u + h f_o / m)] / [1 + h (c + h k) / m],   clamped at 0 (it only pushes).
// The contact's stiffness and damping thus act like extra mass along the normal (the denominator), and
// symplectic Euler stays stable on them at any step; the springs alone bound the step. At rest (u = 0,
// f_o = -fn') it returns k depth, the explicit force: the penalty sag m g / k is unchanged.
// `mass` kg, `h` s, `other_normal_force` N (> 0 pushing out), others as penalty_normal_force.
inline double linearly_implicit_normal_force(double depth, double normal_velocity, double other_normal_force,
                                             double mass, double h, double stiffness, double damping) {
  const double resistance = damping + h * stiffness;  // N*s/m: the damper plus the spring's h k
  const double free_velocity = normal_velocity + h * other_normal_force / mass;  // m/s: u' without contact
  return std::max(0.0, (stiffness * depth - resistance * free_velocity) / (1.0 + h * resistance / mass));
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
