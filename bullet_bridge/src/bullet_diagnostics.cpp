// Read-only views into Bullet for tests and reports (see bullet_diagnostics.hpp).
#include "drapelab/bullet/bullet_diagnostics.hpp"

#include <BulletCollision/CollisionShapes/btConvexShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>

#include "bullet_cloth_solver.hpp"
#include "bullet_math.hpp"

namespace drapelab::bullet {

std::optional<BulletClothLayout> bullet_cloth_layout(const Solver& solver) {
  const auto* bullet_solver = dynamic_cast<const BulletClothSolver*>(&solver);
  if (!bullet_solver) return std::nullopt;
  const btSoftBody& cloth = bullet_solver->cloth();
  BulletClothLayout layout;
  layout.positions.resize(3, cloth.m_nodes.size());
  layout.inverse_mass.resize(cloth.m_nodes.size());
  for (int i = 0; i < cloth.m_nodes.size(); ++i) {
    layout.positions.col(i) = to_eigen(cloth.m_nodes[i].m_x);
    layout.inverse_mass[i] = cloth.m_nodes[i].m_im;
  }
  const btSoftBody::Node* first = &cloth.m_nodes[0];
  for (int e = 0; e < cloth.m_links.size(); ++e) {
    const btSoftBody::Link& link = cloth.m_links[e];
    layout.link_v0.push_back(static_cast<int>(link.m_n[0] - first));
    layout.link_v1.push_back(static_cast<int>(link.m_n[1] - first));
    layout.rest_length.push_back(link.m_rl);
    layout.link_stiffness.push_back(link.m_material->m_kLST);
    layout.bending.push_back(link.m_bbending != 0);
  }
  layout.faces = cloth.m_faces.size();
  layout.margin = const_cast<btSoftBody&>(cloth).getCollisionShape()->getMargin();
  return layout;
}

std::vector<Eigen::Isometry3d> bullet_collider_poses(const Solver& solver) {
  std::vector<Eigen::Isometry3d> poses;
  if (const auto* bullet_solver = dynamic_cast<const BulletWorldSolver*>(&solver))
    for (std::size_t c = 0; c < bullet_solver->colliders().size(); ++c)
      poses.push_back(bullet_solver->colliders().collider_pose_in_world(c));
  return poses;
}

double bullet_signed_distance(const Collider& collider, double t, const Eigen::Vector3d& p,
                              double edge_margin) {
  const BulletShape shape = make_bullet_shape(collider, edge_margin);
  const btTransform pose = to_bullet(collider_pose(collider, t) * shape.shape_in_collider);
  btGjkEpaSolver2::sResults results;
  return btGjkEpaSolver2::SignedDistance(
      to_bullet(p), 0.0, static_cast<const btConvexShape*>(shape.shape.get()), pose, results);
}

}  // namespace drapelab::bullet
