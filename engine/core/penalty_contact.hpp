// Penalty contact and Coulomb friction for one particle against one collider, as pure functions.
//
// Normal: a spring-damper along the collider's outward normal n that only pushes,
//   fn = max(0, k * depth - c * (v_rel . n))            (N; k in N/m, c in N*s/m, depth in m)
// Friction: velocity-level Coulomb with a static/kinetic distinction. Over a step h the friction
// force f_t either cancels the tangential relative velocity the particle would otherwise have at
// the end of the step (sticking: |f_t| <= mu_s fn), or, when that needs more, slides with |f_t| =
// mu_k fn against that velocity. Sticking is therefore exact (no creep) and sliding follows a = g
// (sin - mu_k cos).
//
// Under symplectic Euler the normal force can instead be the one the step's end state implies
// (linearly_implicit_normal_force): the contact spring and damper then never limit the step size.
#pragma once

#include <Eigen/Core>
#include <algorithm>

namespace drapelab {

// `normal_velocity`: relative velocity along the outward normal, m/s (> 0 separating).
inline double penalty_normal_force(double depth, double normal_velocity, double stiffness,
                                   double damping) {
  return std::max(0.0, stiffness * depth - damping * normal_velocity);
}

// The normal force of the same spring-damper evaluated at the end of a symplectic Euler step
// (v' = v + h f / m, x' = x + h v') instead of at its start, with every other force on the particle
// held at its start value. Along the normal, with u the relative normal velocity, f_o the normal
// component of the other forces and the depth advanced to depth - h u', the step is
//   u' = u + (h / m) (f_o + fn'),   fn' = k (depth - h u') - c u',
// linear in u', so
//   fn' = [k depth - (c + h k) (u + h f_o / m)] / [1 + h (c + h k) / m],   clamped at 0 (it only
//   pushes).
// The contact's stiffness and damping thus act like extra mass along the normal (the denominator),
// and symplectic Euler stays stable on them at any step; the springs alone bound the step. At rest
// (u = 0, f_o = -fn') it returns k depth, the explicit force: the penalty sag m g / k is unchanged.
// `mass` kg, `h` s, `other_normal_force` N (> 0 pushing out), others as penalty_normal_force.
inline double linearly_implicit_normal_force(double depth, double normal_velocity,
                                             double other_normal_force, double mass, double h,
                                             double stiffness, double damping) {
  const double resistance = damping + h * stiffness;  // N*s/m: the damper plus the spring's h k
  const double free_velocity =
      normal_velocity + h * other_normal_force / mass;  // m/s: u' without contact
  return std::max(0.0,
                  (stiffness * depth - resistance * free_velocity) / (1.0 + h * resistance / mass));
}

// The most colliders whose end-of-step forces are solved together for one particle; a particle
// inside more at once (no scene comes near) gets no normal force from the rest.
constexpr int kMaxSimultaneousContacts = 16;

// One collider's overlap with a particle, as the end-of-step solve below needs it.
struct NormalContact {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // outward, unit
  double depth = 0.0;                                 // m, > 0 inside
  Eigen::Vector3d surface_velocity =
      Eigen::Vector3d::Zero();  // m/s, the collider's surface at the particle
};

// The end-of-step normal forces (N, one per contact, written to `normal_forces`) of a particle
// touching `count` colliders at once, solved together: with v' the particle's velocity at the
// step's end,
//   (m I + h R sum_a n_a n_a^T) v' = m v + h f_o + h sum_a (k d_a + R n_a . s_a) n_a,   R = c + h
//   k,
// over the active set a, and fn_a = k d_a - R n_a . (v' - s_a): the set whose forces all push while
// every contact left out would pull there. That set is unique, and found by flipping the first
// contact that does not fit it, one at a time (Murty's least-index rule). Solving them one
// after another instead would not be stable: each would miss the others' forces, and between two
// colliders a particle can then gain energy at steps the springs allow. One contact reduces exactly
// to linearly_implicit_normal_force, which is what it calls then. At most kMaxSimultaneousContacts
// are solved; forces of any further contacts are zero. `velocity` m/s, `other_force` N (every
// force on the particle but these contacts), `mass` kg, `h` s.
void linearly_implicit_normal_forces(const NormalContact* contacts, int count,
                                     const Eigen::Vector3d& velocity,
                                     const Eigen::Vector3d& other_force, double mass, double h,
                                     double stiffness, double damping, double* normal_forces);

// A friction force and its magnitude, which the sticking case has already computed (a second square
// root per contact would cost a tenth of the contact phase).
struct FrictionForce {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // N, tangential
  double magnitude = 0.0;                           // N, exactly force.norm()
};

// `trial_tangential_velocity` (m/s): the tangential velocity relative to the collider's surface
// that the particle of `mass` (kg) would have after a step of h (s) under every force but friction.
inline FrictionForce coulomb_friction_force(const Eigen::Vector3d& trial_tangential_velocity,
                                            double mass, double h, double normal_force,
                                            double static_coefficient, double kinetic_coefficient) {
  const Eigen::Vector3d sticking =
      -mass / h * trial_tangential_velocity;  // stops it within the step
  const double needed = sticking.norm();
  if (needed <= static_coefficient * normal_force) return {sticking, needed};
  const Eigen::Vector3d sliding = (kinetic_coefficient * normal_force / needed) * sticking;
  return {sliding, sliding.norm()};
}

}  // namespace drapelab
