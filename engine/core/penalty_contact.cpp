// The end-of-step normal forces of a particle touching several colliders at once
// (penalty_contact.hpp).
#include "core/penalty_contact.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>

namespace drapelab {

void linearly_implicit_normal_forces(const NormalContact* contacts, int count,
                                     const Eigen::Vector3d& velocity,
                                     const Eigen::Vector3d& other_force, double mass, double h,
                                     double stiffness, double damping, double* normal_forces) {
  if (count == 1) {  // the closed form: one contact gives linearly_implicit_normal_force's bits
    const NormalContact& only = contacts[0];
    normal_forces[0] = linearly_implicit_normal_force(
        only.depth, (velocity - only.surface_velocity).dot(only.normal),
        other_force.dot(only.normal), mass, h, stiffness, damping);
    return;
  }
  const double resistance = damping + h * stiffness;  // N*s/m
  const int solved = std::min(count, kMaxSimultaneousContacts);
  using Active = std::array<bool, kMaxSimultaneousContacts>;
  // The end velocity with the contacts in `active` pushing, and every contact's force there (N):
  // fn_a = k d_a - R n_a . (v' - s_a). Returns the first contact that does not fit the set (active
  // but not pushing, or left out but pushing), or -1 when the set is consistent.
  const auto solve_with = [&](const Active& active) {
    Eigen::Matrix3d system = mass * Eigen::Matrix3d::Identity();   // kg
    Eigen::Vector3d momentum = mass * velocity + h * other_force;  // kg m/s
    for (int a = 0; a < solved; ++a) {
      if (!active[a]) continue;
      const NormalContact& contact = contacts[a];
      system.noalias() += (h * resistance) * contact.normal * contact.normal.transpose();
      momentum +=
          h *
          (stiffness * contact.depth + resistance * contact.normal.dot(contact.surface_velocity)) *
          contact.normal;
    }
    const Eigen::Vector3d end_velocity =
        system.llt().solve(momentum);  // m/s; m I plus PSD terms: SPD
    int misfit = -1;
    for (int a = 0; a < solved; ++a) {
      const NormalContact& contact = contacts[a];
      normal_forces[a] = stiffness * contact.depth -
                         resistance * contact.normal.dot(end_velocity - contact.surface_velocity);
      if (misfit < 0 && active[a] != (normal_forces[a] > 0.0)) misfit = a;
    }
    return misfit;
  };
  // Murty's least-index pivoting: start with every contact pushing and flip the first one that does
  // not fit, until none is left. In the forces fn the conditions form a linear complementarity
  // problem whose matrix I + (h R / m) [n_a . n_b] is symmetric positive definite, so its solution
  // is unique and this rule reaches it in finitely many flips from any start (solving, then
  // dropping every pulling contact at once, can cycle between sets when normals meet at sharp
  // angles). The cap only guards rounding.
  Active active;
  active.fill(true);
  int misfit = solve_with(active);
  for (int flip = 0; misfit >= 0 && flip < 64 * solved; ++flip) {
    active[misfit] = !active[misfit];
    misfit = solve_with(active);
  }
  // Only pushing forces remain: the consistent set's, or (should rounding ever exhaust the flips)
  // the last set's, clamped as the single-contact force is.
  for (int a = 0; a < count; ++a)
    if (a >= solved || !active[a] || normal_forces[a] < 0.0) normal_forces[a] = 0.0;
}

}  // namespace drapelab
