// The penalty force of a weighted contact (weighted_contact.hpp) and its Jacobian, as pure
// functions over plain values.
//
// With r = sum_j w_j x_j - anchor (m; anchor the collider's point, zero between two parts of the
// cloth), d = |r| and n = r / d, the force pushes the weighted point away along n:
//   fn = max(0, k (thickness - d) - c n . u),   u = sum_j w_j v_j - anchor_velocity,
//   F_j = w_j fn n.
// It never pulls, and with weights that sum to zero (two parts of the cloth) the forces sum to
// zero. Its Jacobian, with the weights held (they change only where the closest point moves between
// regions), is dF_i/dx_j = w_i w_j G and dF_i/dv_j = -c w_i w_j n n^T with
//   G = -k n n^T - (c / d) n u^T (I - n n^T) + (fn / d) (I - n n^T).
// The implicit solve keeps G's first term only (pair_jacobian_for_solve): the others change with
// the direction of n and would make the system indefinite, as the springs' filtered Jacobian
// drops the compressive part (spring_jacobian.hpp).
#pragma once

#include <Eigen/Core>
#include <array>

#include "core/penalty_contact.hpp"

namespace drapelab {

struct PairPenalty {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // n, unit
  double distance = 0.0;                              // m, d
  double force = 0.0;                                 // N, fn >= 0
};

// The push fn (N) at overlap `depth` = thickness - d (m) and normal velocity n . u (m/s): none at
// all unless the spring pushes, so a closing damper alone never pushes beyond the thickness.
inline double pair_push(double depth, double normal_velocity, double stiffness, double damping) {
  const double spring = stiffness * depth;  // N
  if (spring <= 0.0) return 0.0;
  return std::max(0.0, spring - damping * normal_velocity);
}

// n and d of `separation` = r (m); a zero r takes `fallback_normal`. Only normal and distance are
// set.
inline PairPenalty pair_separation(const Eigen::Vector3d& separation,
                                   const Eigen::Vector3d& fallback_normal) {
  PairPenalty out;
  out.distance = separation.norm();
  out.normal = out.distance > 0.0 ? Eigen::Vector3d(separation / out.distance) : fallback_normal;
  return out;
}

// `separation` = r (m), `relative_velocity` = u (m/s). A zero r takes `fallback_normal`.
inline PairPenalty pair_penalty(const Eigen::Vector3d& separation,
                                const Eigen::Vector3d& relative_velocity,
                                const Eigen::Vector3d& fallback_normal, double thickness,
                                double stiffness, double damping) {
  PairPenalty out = pair_separation(separation, fallback_normal);
  out.force =
      pair_push(thickness - out.distance, out.normal.dot(relative_velocity), stiffness, damping);
  return out;
}

// dF/dr of one contact's force (the full G above, N/m) at a pushing contact; zero when fn = 0.
inline Eigen::Matrix3d pair_force_position_derivative(const PairPenalty& p,
                                                      const Eigen::Vector3d& relative_velocity,
                                                      double stiffness, double damping) {
  if (p.force <= 0.0 || p.distance <= 0.0) return Eigen::Matrix3d::Zero();
  const Eigen::Matrix3d along = p.normal * p.normal.transpose();
  const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - along;
  return -stiffness * along -
         (damping / p.distance) * p.normal * (across * relative_velocity).transpose() +
         (p.force / p.distance) * across;
}

// The Jacobian the implicit solve uses for dF/dr: -k n n^T (N/m), zero when fn = 0.
inline Eigen::Matrix3d pair_jacobian_for_solve(const PairPenalty& p, double stiffness) {
  if (p.force <= 0.0) return Eigen::Matrix3d::Zero();
  return -stiffness * p.normal * p.normal.transpose();
}

// Coulomb friction at a weighted contact (penalty_contact.hpp's rule, with the contact's
// effective mass 1 / sum_j w_j^2 / m_j): `trial` (m/s) is sum_j w_j (v_j + h f_j / m_j) minus the
// other side's velocity, `inverse_effective_mass` = sum_j w_j^2 / m_j (1/kg, > 0). Returns the
// force on the weighted point (N); particle j takes w_j times it.
inline FrictionForce weighted_contact_friction(const Eigen::Vector3d& trial,
                                               const Eigen::Vector3d& normal,
                                               double inverse_effective_mass, double h,
                                               double normal_force, double static_coefficient,
                                               double kinetic_coefficient) {
  return coulomb_friction_force(trial - normal * normal.dot(trial), 1.0 / inverse_effective_mass, h,
                                normal_force, static_coefficient, kinetic_coefficient);
}

}  // namespace drapelab
