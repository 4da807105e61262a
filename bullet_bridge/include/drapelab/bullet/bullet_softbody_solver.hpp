// Bullet's classic cloth (btSoftBody in a btSoftRigidDynamicsWorld, double precision) as a drapelab
// Solver: node i is model particle i; masses, pins and rest lengths are ours; the scene's colliders
// are kinematic rigid bodies moved to their pose at the end of every substep. This header includes
// no Bullet header; only bullet_bridge/ does.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/air.hpp"
#include "drapelab/attachments.hpp"
#include "drapelab/bullet/parameter_mapping.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/distance_constraints.hpp"
#include "drapelab/self_collision.hpp"
#include "drapelab/solver.hpp"
#include "drapelab/world.hpp"

namespace drapelab::bullet {

// The mapping from our scene to the classic solver's parameters (docs/bullet.md, "Mapping our
// parameters to the classic cloth"):
// The world (drapelab/world.hpp) and the Bullet numerics. Of the world, the classic cloth maps the
// air to Bullet's own face aerodynamics; its pinned nodes carried by colliders are kinematic nodes
// placed before and after every substep; soft constraints kick the nodes' velocities before every
// substep and hard and rope ones are projected after it (docs/bullet.md, "Constraints");
// self_collision is accepted and without effect: Bullet 3.24's classic cloth has no
// self-collision that runs (VF_SS skips a body against itself and CL_SELF is unreachable;
// docs/bullet.md, "Self-collision"). The colliders come as their own argument.
struct BulletSoftBodyOptions : World {
  double dt = 0.0;                // s, the substep h, one stepSimulation(h, 0) each
  int iterations = 1;             // position-solver sweeps per substep (piterations)
  double margin = 0.0;            // m, soft collision margin: the cloth's thickness
  double voxel_size = 0.0;        // m, sparse SDF cell: <= margin and <= features / 10
  double collider_margin = 1e-3;  // m, rounds box and cylinder edges; keep small
  std::array<std::optional<double>, 3>
      raw_link_stiffness;     // kLST per spring kind, overriding the mapping
  double max_speed = 1000.0;  // m/s: a faster node stops the solver as unstable
};

std::unique_ptr<Solver> make_bullet_softbody_solver(std::string name,
                                                    std::shared_ptr<const ClothModel> model,
                                                    const ClothState& initial,
                                                    std::vector<Collider> colliders,
                                                    BulletSoftBodyOptions options);

}  // namespace drapelab::bullet
