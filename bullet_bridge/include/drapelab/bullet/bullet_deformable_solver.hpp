// Bullet's deformable world (btDeformableMultiBodyDynamicsWorld) with our damped springs as a
// force, as a drapelab Solver: the same ks and kd per spring (bend springs included), gravity as a
// force, contacts as velocity constraints against its own kinematic copies of the scene's
// colliders. This header includes no Bullet header.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "drapelab/air.hpp"
#include "drapelab/attachments.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/distance_constraints.hpp"
#include "drapelab/self_collision.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::bullet {

struct BulletDeformableOptions {
  double margin = 0.0;                       // m, soft collision margin: the cloth's thickness
  double voxel_size = 0.0;                   // m, sparse SDF cell
  double collider_margin = 1e-3;             // m, rounds box and cylinder edges
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};  // m/s^2
  double air_damping = 0.0;                  // 1/s, mapped to drag = 1 - exp(-air_damping h)
  double dt = 0.0;                           // s, the substep (for the drag mapping)
  double max_speed = 1000.0;                 // m/s
  // cloth.self_collision: when enabled, Bullet's face-node repulsion between the cloth's layers,
  // which keep 2 x margin apart (docs/bullet.md, "Self-collision").
  SelfCollisionSettings self_collision;
  // Pinned nodes carried by colliders: placed on them before and after every substep (kinematic
  // nodes). None when null.
  std::shared_ptr<const Attachments> attachments;
  // Distance constraints: the soft ones kick the nodes' velocities before every substep, the hard
  // and rope ones are projected after it (docs/bullet.md, "Constraints"). None when null.
  std::shared_ptr<const DistanceConstraints> constraints;
  // Air (air:): the classic cloth maps it to Bullet's own face aerodynamics; the deformable world,
  // which has none, takes ours as an explicit force (docs/bullet.md, "Air").
  AirSettings air;
};

std::unique_ptr<Solver> make_bullet_deformable_solver(std::string name,
                                                      std::shared_ptr<const ClothModel> model,
                                                      const ClothState& initial,
                                                      std::vector<Collider> colliders,
                                                      BulletDeformableOptions options);

}  // namespace drapelab::bullet
