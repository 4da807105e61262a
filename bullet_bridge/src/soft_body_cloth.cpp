// Shared parts of Bullet's two cloths (see soft_body_cloth.hpp).
#include "soft_body_cloth.hpp"

#include <cmath>
#include <map>

#include "bullet_math.hpp"

namespace drapelab::bullet {

std::unique_ptr<btSoftBody> make_soft_body(btSoftBodyWorldInfo& info, const ClothModel& model,
                                           const ClothState& initial,
                                           const std::function<double(std::size_t)>& link_stiffness,
                                           const Attachments* attachments) {
  const int n = model.particle_count();
  std::vector<btVector3> rest(n);
  std::vector<btScalar> masses(n);
  for (int i = 0; i < n; ++i) {
    rest[i] = to_bullet(model.rest_positions.col(i));
    masses[i] = model.is_pinned(i) ? 0.0 : model.mass[i];  // Bullet: mass 0 = pinned
  }
  if (attachments)
    for (std::size_t k = 0; k < attachments->list.size(); ++k)
      if (attachments->on_dynamic(k)) {
        const int i = attachments->list[k].particle;
        masses[i] = model.mass[i];
      }
  auto body = std::make_unique<btSoftBody>(&info, n, rest.data(), masses.data());
  const SpringSet& s = model.springs;
  std::map<double, btSoftBody::Material*> materials;  // one material per distinct kLST
  for (std::size_t e = 0; e < s.size(); ++e) {
    const double k = link_stiffness(e);
    btSoftBody::Material*& material = materials[k];
    if (!material) {
      material = body->appendMaterial();
      material->m_kLST = k;
    }
    body->appendLink(s.v0[e], s.v1[e], material);
    // m_bbending is a signed one-bit field (0 or -1); Bullet only tests it for non-zero.
    if (s.kind[e] == SpringKind::bend) body->m_links[body->m_links.size() - 1].m_bbending = -1;
  }
  for (Eigen::Index t = 0; t < model.triangles.cols(); ++t)
    body->appendFace(model.triangles(0, t), model.triangles(1, t), model.triangles(2, t));
  body->m_bUpdateRtCst = false;
  body->updateConstants();
  for (std::size_t e = 0; e < s.size(); ++e) {  // our rest lengths, exactly
    btSoftBody::Link& link = body->m_links[static_cast<int>(e)];
    link.m_rl = s.rest_length[e];
    link.m_c1 = link.m_rl * link.m_rl;
  }
  for (int i = 0; i < n; ++i) {
    btSoftBody::Node& node = body->m_nodes[i];
    node.m_x = node.m_q = to_bullet(initial.x.col(i));
    node.m_v = to_bullet(initial.v.col(i));
  }
  body->setActivationState(DISABLE_DEACTIVATION);  // the solvers skip inactive bodies
  return body;
}

void read_soft_body_state(const btSoftBody& body, ClothState& state) {
  for (int i = 0; i < body.m_nodes.size(); ++i) {
    state.x.col(i) = to_eigen(body.m_nodes[i].m_x);
    state.v.col(i) = to_eigen(body.m_nodes[i].m_v);
  }
}

void place_attached_nodes(const Attachments& attachments, double t, btSoftBody& body) {
  for (std::size_t k = 0; k < attachments.list.size(); ++k) {
    if (attachments.on_dynamic(k)) continue;  // anchored to its body
    const auto [position, velocity] = attachments.placement(k, t);
    btSoftBody::Node& node = body.m_nodes[attachments.list[k].particle];
    node.m_x = node.m_q = to_bullet(position);
    node.m_v = node.m_vn = to_bullet(velocity);
  }
}

void anchor_attached_nodes(const Attachments& attachments,
                           const std::function<btRigidBody*(std::size_t)>& body_of,
                           btSoftBody& cloth) {
  for (std::size_t k = 0; k < attachments.list.size(); ++k) {
    if (!attachments.on_dynamic(k)) continue;
    const Attachment& a = attachments.list[k];
    cloth.appendDeformableAnchor(a.particle, body_of(static_cast<std::size_t>(a.collider)));
  }
}

namespace {

// An explicit force (N, 3 x N) over a substep of h (s): each free node's velocity gains h f / m.
void kick_nodes(const ClothModel& model, const Eigen::Matrix3Xd& force, double h,
                btSoftBody& body) {
  for (int i = 0; i < body.m_nodes.size(); ++i)
    if (model.inverse_mass[i] > 0.0 && force.col(i).squaredNorm() > 0.0)
      body.m_nodes[i].m_v += to_bullet((h * model.inverse_mass[i]) * force.col(i));
}

}  // namespace

std::shared_ptr<ColliderPoseTable> follow_own_bodies(
    std::shared_ptr<const DistanceConstraints>& constraints, std::size_t colliders) {
  if (!constraints || !constraints->any_on_dynamic()) return nullptr;
  auto poses = std::make_shared<ColliderPoseTable>(colliders);
  constraints = constraints_on_own_bodies(constraints, poses);
  return poses;
}

void kick_soft_constraints(const DistanceConstraints& constraints, const ClothModel& model,
                           double t, double h, btSoftBody& body, ClothState& scratch,
                           KinematicColliders& bodies) {
  read_soft_body_state(body, scratch);
  Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, scratch.x.cols());
  std::vector<ColliderForce> body_loads;
  constraints.add_soft_forces(t, scratch.x, scratch.v, force, nullptr, &body_loads);
  kick_nodes(model, force, h, body);
  bodies.apply_impulses(body_loads, h);
}

void kick_air(const AirSettings& air, const Wind& wind, const ClothModel& model, double t, double h,
              btSoftBody& body, ClothState& scratch) {
  read_soft_body_state(body, scratch);
  Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, scratch.x.cols());
  add_air_forces(model, air, wind, t, scratch.x, scratch.v, force);
  kick_nodes(model, force, h, body);
}

ConstraintProjection project_node_constraints(const DistanceConstraints& constraints,
                                              const ClothModel& model, double t, double h,
                                              btSoftBody& body, ClothState& scratch) {
  read_soft_body_state(body, scratch);
  ConstraintProjection result = constraints.project_positions(t, model.inverse_mass, scratch.x);
  constraints.project_velocities(t, h, model.inverse_mass, scratch.x, scratch.v, result);
  for (int i = 0; i < body.m_nodes.size(); ++i) {
    if (model.inverse_mass[i] == 0.0) continue;  // pinned and attached nodes are placed already
    btSoftBody::Node& node = body.m_nodes[i];
    node.m_x = node.m_q = to_bullet(scratch.x.col(i));
    node.m_v = node.m_vn = to_bullet(scratch.v.col(i));
  }
  return result;
}

void estimate_contact_forces(const ClothModel& model, const std::vector<NodeContact>& contacts,
                             const Eigen::Matrix3Xd& previous_velocity,
                             const Eigen::Matrix3Xd& velocity, const Eigen::Vector3d& gravity,
                             double h, std::vector<ColliderForce>& forces) {
  forces.assign(forces.size(), ColliderForce{});
  for (const auto& contact : contacts) {
    const int i = contact.node;
    const Eigen::Vector3d force =
        model.mass[i] * ((velocity.col(i) - previous_velocity.col(i)) / h - gravity);
    const double normal = force.dot(contact.normal);
    forces[contact.collider].normal += std::max(0.0, normal);
    forces[contact.collider].friction += (force - normal * contact.normal).norm();
  }
}

}  // namespace drapelab::bullet
