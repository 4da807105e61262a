// Self-collision of Bullet's deformable cloth (see deformable_self_collision.hpp).
#include "deformable_self_collision.hpp"

#include <algorithm>
#include <cmath>

namespace drapelab::bullet {
namespace {

// A copy of a face-tree node and its subtree, as Bullet's self-contact search needs it (its own
// copyToDbvnt is private to btSoftBody.cpp). The soft body deletes it with `delete`.
btDbvntNode* copy_with_normal_cones(const btDbvtNode* node) {
  if (node == nullptr) return nullptr;
  auto* copy = new btDbvntNode(node);
  if (node->isinternal()) {
    copy->childs[0] = copy_with_normal_cones(node->childs[0]);
    copy->childs[1] = copy_with_normal_cones(node->childs[1]);
  }
  return copy;
}

}  // namespace

double deformable_self_friction_factor(const SelfCollisionSettings& settings) {
  return std::max(std::sqrt(settings.friction), kMinSelfFrictionFactor);
}

void build_face_tree(btSoftBody& cloth) {
  cloth.m_fdbvt.clear();
  for (int f = 0; f < cloth.m_faces.size(); ++f) {
    btSoftBody::Face& face = cloth.m_faces[f];
    const btVector3 corners[3] = {face.m_n[0]->m_x, face.m_n[1]->m_x, face.m_n[2]->m_x};
    face.m_leaf = cloth.m_fdbvt.insert(btDbvtVolume::FromPoints(corners, 3), &face);
  }
  delete cloth.m_fdbvnt;
  cloth.m_fdbvnt = copy_with_normal_cones(cloth.m_fdbvt.m_root);
}

double deformable_repulsion_stiffness(const SelfCollisionSettings& settings,
                                      double largest_inverse_mass, double h) {
  if (largest_inverse_mass <= 0.0 || h <= 0.0) return settings.stiffness;
  return std::min(settings.stiffness, OVERLAP_REDUCTION_FACTOR / (largest_inverse_mass * h * h));
}

void enable_deformable_self_collision(btSoftBody& cloth, const SelfCollisionSettings& settings,
                                      double h) {
  double largest_inverse_mass = 0.0;
  for (int i = 0; i < cloth.m_nodes.size(); ++i)
    largest_inverse_mass = std::max(largest_inverse_mass, double(cloth.m_nodes[i].m_im));
  cloth.m_cfg.collisions |= btSoftBody::fCollision::VF_DD;
  cloth.setSelfCollision(true);
  cloth.m_repulsionStiffness = deformable_repulsion_stiffness(settings, largest_inverse_mass, h);
  cloth.m_cfg.kDF = deformable_self_friction_factor(settings);
  build_face_tree(cloth);
}

}  // namespace drapelab::bullet
