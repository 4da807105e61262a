// How our scene becomes a MuJoCo model (docs/mujoco.md, "The mapping"): plain arithmetic with no
// MuJoCo header, so that the scene loader can choose MuJoCo's defaults and check its limits
// without linking MuJoCo, and the tests can check each formula alone.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>

#include "drapelab/cloth_model.hpp"
#include "drapelab/collider.hpp"

namespace drapelab::mujoco {

// MuJoCo's constraint solvers. Newton factors a dense nv x nv Hessian in MuJoCo 2.2, so beyond
// kNewtonLargestDofs degrees of freedom the automatic choice is the conjugate gradient.
enum class ConstraintSolver { automatic, newton, cg, pgs };
const char* constraint_solver_name(ConstraintSolver solver);
inline constexpr int kNewtonLargestDofs = 3000;
ConstraintSolver chosen_solver(ConstraintSolver asked, int dofs);

// A MuJoCo solver entry's own numerics (solvers[] keys of type mujoco).
struct MujocoSettings {
  ConstraintSolver constraint_solver = ConstraintSolver::automatic;
  int solver_iterations = 100;  // constraint-solver iterations per step at most
  double tolerance = 1e-10;     // the constraint solver's relative cost improvement to stop
  // Frictional-to-normal impedance ratio of the elliptic cones; 0: friction_impratio's.
  double impratio = 0.0;
  int max_contacts = 0;  // 0: chosen by contact_capacity
};

// solimp's d: the contact's impedance, constant over the penetration. So small that the
// constraint force is the spring-damper of solref alone (the constraint's own hard part, d times
// the unconstrained acceleration, is 1e-4 of it).
inline constexpr double kImpedance = 1e-4;

// The impratio at which MuJoCo's friction takes out one step's sliding in each step, for contact
// damping c (N*s/m) on particles of mass m (kg) at step h (s) (docs/mujoco.md, "Friction").
// MuJoCo's friction rows share the normal row's reference damping c/(m d), which the tiny
// impedance d makes a thousand times the contact's own: a hard friction row would reverse a
// sliding particle's velocity many times over in a step (MuJoCo's no-slip post-solve, which
// makes the rows hard, diverges so). The friction row's share of the constraint force,
// D / (D + 1 - d) with D = d impratio, is set to d / (h c / m), so that the row's velocity gain
// over a step is one. Below the friction angle a particle then creeps at h times its tangential
// acceleration; above it, it slides at the Coulomb limit. At least 1 (MuJoCo's default).
double friction_impratio(double contact_damping, double mass, double h);
// The free particles' mean mass (kg), the m above; 1 when every particle is pinned.
double mean_free_mass(const ClothModel& model);

// solref with MuJoCo's direct (negative) form, (-stiffness, -damping), in 1/s^2 and 1/s: a contact
// of stiffness k (N/m) and damping c (N*s/m) on a particle of mass m (kg) is the reference
// acceleration -(k/m) r - (c/m) v, so the force on it is k r + c v whatever its mass.
struct ContactReference {
  double stiffness = 0.0;  // 1/s^2, k/m
  double damping = 0.0;    // 1/s, c/m
};
ContactReference contact_reference(double stiffness, double damping, double mass);
// The same for a contact between two particles: MuJoCo averages the two geoms' references
// (solmix 1 each), and the pair's effective mass is m1 m2 / (m1 + m2); twice k/m per particle
// gives the pair the force k r + c v.
ContactReference pair_contact_reference(double stiffness, double damping, double mass);

// A collider as one MuJoCo geom: its type, MuJoCo's size, and its pose in the collider's frame
// (MuJoCo's cylinder, capsule and plane lie along their z axis; ours along `axis` or `normal`).
struct GeomShape {
  std::string type;                                // sphere, cylinder, capsule, box, plane
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // MuJoCo's size (m)
  Eigen::Quaterniond local = Eigen::Quaterniond::Identity();  // geom axes -> collider frame
};
// Throws std::invalid_argument for a mesh collider, which this mapping does not carry.
GeomShape geom_shape(const Collider& collider);

// MuJoCo 2.2's data buffer is sized by an int: it must stay under 2 GiB. Its constraint arrays
// take about 8 nefc^2 + 24 nefc nv bytes (efc_AR, efc_J and efc_JT with their column indices, all
// dense-sized even with the sparse Jacobian), with nefc = 3 rows per contact (elliptic cones,
// condim 3).
inline constexpr double kBufferLimitBytes = 2147483647.0;  // bytes
double constraint_buffer_bytes(std::int64_t contacts, std::int64_t dofs);
// The contacts the model makes room for: `asked` when given (> 0), else one per free particle and
// 64 more (a few particles on two colliders at once), or the most that fit the buffer (the solver's
// stack is a separate allocation). Never below 1.
std::int64_t contact_capacity(int asked, std::int64_t free_particles, std::int64_t dofs);
// MuJoCo's stack (mjtNums) for a model of `bodies` bodies: the broadphase's pairs, bodies^2 / 2,
// the working vectors, and for Newton its dense matrices (3 nv^2 measured; 4 nv^2 given).
std::int64_t stack_size(std::int64_t contacts, std::int64_t dofs, std::int64_t bodies,
                        ConstraintSolver solver);

}  // namespace drapelab::mujoco
