// MuJoCo 2.2's cloth as a drapelab Solver (docs/mujoco.md): every free particle of our model is a
// MuJoCo body with three slide joints and a sphere geom, our springs (and the air and soft
// constraints, when the scene has them) act on it as applied forces, and MuJoCo integrates it
// (semi-implicit Euler, the air damping as implicit joint damping) and solves its contacts with
// the scene's colliders as soft constraints: a spring-damper along the normal and elliptic
// Coulomb cones. Node i is model particle i. This header includes no MuJoCo header; only
// mujoco_bridge/src does.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/mujoco/mujoco_mapping.hpp"
#include "drapelab/solver.hpp"
#include "drapelab/world.hpp"

namespace drapelab::mujoco {

// The world (drapelab/world.hpp) and MuJoCo's numerics. Of the world, MuJoCo takes gravity, the
// air damping, the contact stiffness and damping, the colliders' friction, the attachments, the
// air, the soft, hard and rope constraints and the cloth against itself (particle spheres of the
// self-collision thickness). The colliders come as their own argument.
struct MujocoOptions : World {
  double dt = 0.0;               // s, MuJoCo's timestep: one mj_step each
  double particle_radius = 0.0;  // m, the particles' sphere geoms: the cloth's thickness
  MujocoSettings numerics;
  double max_speed = 1000.0;  // m/s: a faster particle stops the solver as unstable
};

// Throws std::invalid_argument for what the mapping does not carry (a mesh or dynamic collider)
// and std::runtime_error when MuJoCo refuses the model.
std::unique_ptr<Solver> make_mujoco_solver(std::string name,
                                           std::shared_ptr<const ClothModel> model,
                                           const ClothState& initial,
                                           std::vector<Collider> colliders, MujocoOptions options);

}  // namespace drapelab::mujoco
