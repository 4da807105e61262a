// Read-only views into the Bullet side, for tests and reports: what Bullet built from our model,
// its signed distance to a collider, and where it has the colliders. No Bullet type crosses this
// header.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::bullet {

struct BulletClothLayout {
  Eigen::Matrix3Xd positions;          // m, node i
  Eigen::VectorXd inverse_mass;        // 1/kg, 0 = pinned
  std::vector<int> link_v0, link_v1;   // node indices per link, in our spring order
  std::vector<double> rest_length;     // m
  std::vector<double> link_stiffness;  // kLST
  std::vector<bool> bending;           // Bullet's bending flag per link
  int faces = 0;
  double margin = 0.0;  // m, the soft body's collision margin
};

// The layout of a Bullet cloth (bullet_softbody or bullet_deformable); nothing for any other
// solver.
std::optional<BulletClothLayout> bullet_cloth_layout(const Solver& solver);

// The collider poses (collider frame -> world) Bullet's kinematic bodies hold now, in scene order,
// for Bullet's cloths and our hosted cloth; empty for a solver without a Bullet world.
std::vector<Eigen::Isometry3d> bullet_collider_poses(const Solver& solver);

// Bullet's signed distance (m) from p to the collider posed at time t, as its soft-rigid contact
// sees it (GJK with the shape's margin; negative inside).
double bullet_signed_distance(const Collider& collider, double t, const Eigen::Vector3d& p,
                              double edge_margin);

}  // namespace drapelab::bullet
