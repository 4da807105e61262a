// How our scene becomes a MuJoCo model (mujoco_mapping.hpp).
#include "drapelab/mujoco/mujoco_mapping.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace drapelab::mujoco {

const char* constraint_solver_name(ConstraintSolver solver) {
  switch (solver) {
    case ConstraintSolver::automatic:
      return "auto";
    case ConstraintSolver::newton:
      return "newton";
    case ConstraintSolver::cg:
      return "cg";
    case ConstraintSolver::pgs:
      return "pgs";
  }
  return "unknown";
}

ConstraintSolver chosen_solver(ConstraintSolver asked, int dofs) {
  if (asked != ConstraintSolver::automatic) return asked;
  return dofs <= kNewtonLargestDofs ? ConstraintSolver::newton : ConstraintSolver::cg;
}

double friction_impratio(double contact_damping, double mass, double h) {
  const double gain = h * contact_damping / mass;  // the contact's damping over a step
  if (!(gain > 0.0)) return 1.0;
  const double share = std::min(0.99, kImpedance / gain);  // the friction row's share
  const double ratio = share * (1.0 - kImpedance) / (1.0 - share) / kImpedance;
  return std::max(1.0, ratio);
}

double mean_free_mass(const ClothModel& model) {
  double sum = 0.0;  // kg
  int count = 0;
  for (int i = 0; i < model.particle_count(); ++i)
    if (!model.is_pinned(i)) {
      sum += model.mass[i];
      ++count;
    }
  return count > 0 ? sum / count : 1.0;
}

ContactReference contact_reference(double stiffness, double damping, double mass) {
  return {stiffness / mass, damping / mass};
}

ContactReference pair_contact_reference(double stiffness, double damping, double mass) {
  return {2.0 * stiffness / mass, 2.0 * damping / mass};
}

GeomShape geom_shape(const Collider& collider) {
  GeomShape geom;
  // The rotation taking MuJoCo's z axis onto the shape's own axis (unit).
  const auto z_onto = [](const Eigen::Vector3d& axis) {
    return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis.normalized());
  };
  switch (collider.shape) {
    case ColliderShape::sphere:
      geom.type = "sphere";
      geom.size = {collider.radius, 0.0, 0.0};
      break;
    case ColliderShape::cylinder:
      geom.type = "cylinder";  // size: radius, half-height
      geom.size = {collider.radius, 0.5 * collider.height, 0.0};
      geom.local = z_onto(collider.axis);
      break;
    case ColliderShape::capsule:
      geom.type = "capsule";  // size: radius, half the segment
      geom.size = {collider.radius, 0.5 * collider.height, 0.0};
      geom.local = z_onto(collider.axis);
      break;
    case ColliderShape::box:
      geom.type = "box";
      geom.size = collider.half_extents;
      break;
    case ColliderShape::plane:
      geom.type = "plane";  // infinite (sizes 0), solid below its z axis
      geom.size = {0.0, 0.0, 1.0};
      geom.local = z_onto(collider.normal);
      break;
    case ColliderShape::mesh:
      throw std::invalid_argument("collider '" + collider.name +
                                  "' is a mesh, which the MuJoCo solver does not carry");
  }
  return geom;
}

double constraint_buffer_bytes(std::int64_t contacts, std::int64_t dofs) {
  const double rows = 3.0 * static_cast<double>(contacts);  // elliptic cones, condim 3
  const double nv = static_cast<double>(dofs);
  // efc_AR and its column indices (12 B per entry), efc_J and efc_JT with theirs (12 B each).
  return 12.0 * rows * rows + 24.0 * rows * nv;
}

std::int64_t stack_size(std::int64_t contacts, std::int64_t dofs, std::int64_t bodies,
                        ConstraintSolver solver) {
  const std::int64_t rows = 3 * contacts;
  // The broadphase's candidate pairs (measured: 1.43 M for 1,684 bodies) and the solvers' working
  // vectors, with room to spare.
  std::int64_t size = bodies * bodies / 2 + 20 * (dofs + rows) + 100000;
  if (solver == ConstraintSolver::newton) size += 4 * dofs * dofs;  // measured: 3 nv^2
  return size;
}

std::int64_t contact_capacity(int asked, std::int64_t free_particles, std::int64_t dofs) {
  if (asked > 0) return asked;
  // What remains of the 2 GiB once the model's other arrays (under 1 kB per dof) are counted.
  const double room = kBufferLimitBytes - 1024.0 * static_cast<double>(dofs);
  const std::int64_t wanted = free_particles + 64;
  // Largest contact count whose constraint arrays fit: 108 c^2 + 72 nv c - room = 0.
  const double nv = static_cast<double>(dofs);
  const double fitting =
      (-72.0 * nv + std::sqrt(72.0 * 72.0 * nv * nv + 4.0 * 108.0 * room)) / (2.0 * 108.0);
  return std::max<std::int64_t>(1, std::min(wanted, static_cast<std::int64_t>(fitting * 0.95)));
}

}  // namespace drapelab::mujoco
