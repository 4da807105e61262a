// The end-of-step normal forces of a particle touching several colliders at once (penalty_contact.hpp).
#include "drapelab/penalty_contact.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <array>

namespace drapelab {

void linearly_implicit_normal_forces(const NormalContact* contacts, int count, const Eigen::Vector3d& velocity,
                                     const Eigen::Vector3d& other_force, double mass, double h, double stiffness,
                                     double damping, double* normal_forces) {
  if (count == 1) {  // the closed form, so a single contact gives the same bits as before
    const NormalContact& only = contacts[0];
    normal_forces[0] =
        linearly_implicit_normal_force(only.depth, (velocity - only.surface_velocity).dot(only.normal),
                                       other_force.dot(only.normal), mass, h, stiffness, damping);
    return;
  }
  const double resistance = damping + h * stiffness;  // N*s/m
  // Which contacts push. Start with all; each pass solves with the active ones, then drops those whose
  // force would pull and re-admits those that would push. A particle touches a handful of colliders at
  // most; past kMaxSimultaneousContacts the rest are left out with zero force.
  const int solved = std::min(count, kMaxSimultaneousContacts);
  std::array<bool, kMaxSimultaneousContacts> active;
  active.fill(true);
  for (int pass = 0; pass <= solved; ++pass) {
    Eigen::Matrix3d system = mass * Eigen::Matrix3d::Identity();   // kg
    Eigen::Vector3d momentum = mass * velocity + h * other_force;  // kg m/s
    for (int a = 0; a < solved; ++a) {
      if (!active[a]) continue;
      const NormalContact& contact = contacts[a];
      system.noalias() += (h * resistance) * contact.normal * contact.normal.transpose();
      momentum += h * (stiffness * contact.depth + resistance * contact.normal.dot(contact.surface_velocity)) *
                  contact.normal;
    }
    const Eigen::Vector3d end_velocity = system.llt().solve(momentum);  // m/s; m I plus PSD terms: SPD
    bool changed = false;
    for (int a = 0; a < solved; ++a) {
      const NormalContact& contact = contacts[a];
      normal_forces[a] =
          stiffness * contact.depth - resistance * contact.normal.dot(end_velocity - contact.surface_velocity);
      const bool pushes = normal_forces[a] > 0.0;
      changed = changed || pushes != active[a];
      active[a] = pushes;
    }
    if (!changed) break;
  }
  // Only pushing forces remain (after the last pass, a force from a set that was still changing is
  // clamped as the single-contact force is).
  for (int a = 0; a < count; ++a)
    if (a >= solved || !active[a]) normal_forces[a] = 0.0;
}

}  // namespace drapelab
