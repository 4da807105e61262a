// Bullet's classic cloth (btSoftBody in a btSoftRigidDynamicsWorld, double precision) as a drapelab
// Solver: node i is model particle i; masses, pins and rest lengths are ours; the scene's colliders are
// kinematic rigid bodies moved to their pose at the end of every substep. This header includes no
// Bullet header; only bullet_bridge/ does.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::bullet {

// The mapping from our scene to the classic solver's parameters (README, "Bullet's classic cloth"):
struct BulletSoftBodyOptions {
  double dt = 0.0;                             // s, the substep h, one stepSimulation(h, 0) each
  int iterations = 1;                          // position-solver sweeps per substep (piterations)
  double margin = 0.0;                         // m, soft collision margin: the cloth's thickness
  double voxel_size = 0.0;                     // m, sparse SDF cell: <= margin and <= features / 10
  double collider_margin = 1e-3;               // m, rounds box and cylinder edges; keep small
  std::array<std::optional<double>, 3> raw_link_stiffness;  // kLST per spring kind, overriding the mapping
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};    // m/s^2
  double air_damping = 0.0;                    // 1/s, mapped to kDP = 1 - exp(-air_damping h)
  double max_speed = 1000.0;                   // m/s: a faster node stops the solver as unstable
};

// kLST of a link with stiffness ks (N/m) between particles of inverse masses summing to w (1/kg), for
// n sweeps of substep h: 1 - (1 + ks w h^2)^(-1/n) (bullet-notes 1.7; exact for one link, within
// 5 % in a network while ks w h^2 <= 0.1).
double mapped_link_stiffness(double ks, double w, double h, int iterations);

// The largest ks w h^2 over the model's springs at substep h: above about 0.1 the classic cloth is
// measurably softer than our springs.
double largest_link_compliance_ratio(const ClothModel& model, double h);

// A voxel size that resolves the colliders: min(margin, smallest feature / 10) (m).
double default_voxel_size(const std::vector<Collider>& colliders, double margin);

std::unique_ptr<Solver> make_bullet_softbody_solver(std::string name, std::shared_ptr<const ClothModel> model,
                                                    const ClothState& initial, std::vector<Collider> colliders,
                                                    BulletSoftBodyOptions options);

}  // namespace drapelab::bullet
