// Our scene as MJCF text (docs/mujoco.md, "The model"): one body per free particle with three
// world-aligned slide joints, its sphere geom for the colliders (and a second, smaller one for the
// cloth against itself), the static colliders as geoms of the world body and every moving
// collider as a heavy body with a free joint. Pinned particles are not bodies: the solver places
// them and applies their springs' forces itself.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/mujoco/mujoco_mapping.hpp"
#include "drapelab/self_collision.hpp"

namespace drapelab::mujoco {

// A kinematic body's mass (kg) and principal inertia (kg*m^2): heavy enough that the cloth's
// contacts do not move it measurably within a step, after which its pose is set again.
inline constexpr double kKinematicMass = 1e6;

struct MjcfInputs {
  const ClothModel* model = nullptr;
  const std::vector<Collider>* colliders = nullptr;
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};  // m/s^2
  double dt = 0.0;                           // s
  double air_damping = 0.0;                  // 1/s: joint damping air_damping * m per slide
  double particle_radius = 0.0;              // m, the particles' geoms against the colliders
  double contact_stiffness = 0.0;            // N/m
  double contact_damping = 0.0;              // N*s/m
  SelfCollisionSettings self_collision;      // thickness already resolved
  MujocoSettings numerics;
  ConstraintSolver solver = ConstraintSolver::newton;  // chosen_solver's
  std::int64_t contacts = 0;                           // contact_capacity's
  double impratio = 1.0;                               // the settings' or friction_impratio's
};

// Whether collider c is a body of its own (it moves) rather than a world geom.
bool collider_is_body(const Collider& collider);

std::string write_mjcf(const MjcfInputs& inputs);

}  // namespace drapelab::mujoco
