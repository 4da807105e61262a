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
#include "drapelab/world.hpp"

namespace drapelab::bullet {

// The world (drapelab/world.hpp) and the Bullet numerics. Of the world, the deformable world takes
// our air as an explicit force (it has none of its own); self_collision turns on Bullet's
// face-node repulsion between the cloth's layers, which keep 2 x margin apart (docs/bullet.md,
// "Self-collision"); pins and constraints are handled as by the classic cloth. The colliders come
// as their own argument.
struct BulletDeformableOptions : World {
  double margin = 0.0;            // m, soft collision margin: the cloth's thickness
  double voxel_size = 0.0;        // m, sparse SDF cell
  double collider_margin = 1e-3;  // m, rounds box and cylinder edges
  double dt = 0.0;                // s, the substep (for the drag mapping)
  double max_speed = 1000.0;      // m/s
};

std::unique_ptr<Solver> make_bullet_deformable_solver(std::string name,
                                                      std::shared_ptr<const ClothModel> model,
                                                      const ClothState& initial,
                                                      std::vector<Collider> colliders,
                                                      BulletDeformableOptions options);

}  // namespace drapelab::bullet
