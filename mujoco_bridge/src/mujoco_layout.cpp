// Where our particles and colliders are in a MuJoCo model (mujoco_layout.hpp).
#include "mujoco_layout.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "mjcf_writer.hpp"

namespace drapelab::mujoco {

MujocoLayout layout_of(const mjModel& m, const ClothModel& model,
                       const std::vector<Collider>& colliders) {
  MujocoLayout layout;
  layout.body_of_collider.assign(colliders.size(), 0);
  int body = 1;
  for (std::size_t c = 0; c < colliders.size(); ++c)
    if (collider_is_body(colliders[c])) layout.body_of_collider[c] = body++;
  layout.particle_body.assign(static_cast<std::size_t>(model.particle_count()), -1);
  for (int i = 0; i < model.particle_count(); ++i)
    if (!model.is_pinned(i)) layout.particle_body[static_cast<std::size_t>(i)] = body++;
  if (m.nbody != body)
    throw std::logic_error("MuJoCo's model has " + std::to_string(m.nbody) +
                           " bodies where the MJCF wrote " + std::to_string(body));
  const auto bodies = static_cast<std::size_t>(m.nbody);
  std::vector<int> collider_of_body(bodies, -1), particle_of_body(bodies, -1);
  std::vector<int> static_colliders;
  for (std::size_t c = 0; c < colliders.size(); ++c) {
    const int b = layout.body_of_collider[c];
    if (b == 0)
      static_colliders.push_back(static_cast<int>(c));
    else
      collider_of_body[static_cast<std::size_t>(b)] = static_cast<int>(c);
  }
  for (std::size_t i = 0; i < layout.particle_body.size(); ++i)
    if (layout.particle_body[i] > 0)
      particle_of_body[static_cast<std::size_t>(layout.particle_body[i])] = static_cast<int>(i);
  layout.geom_collider.assign(static_cast<std::size_t>(m.ngeom), -1);
  layout.geom_particle.assign(static_cast<std::size_t>(m.ngeom), -1);
  std::size_t next_static = 0;
  for (int g = 0; g < m.ngeom; ++g) {
    const auto b = static_cast<std::size_t>(m.geom_bodyid[g]);
    const auto k = static_cast<std::size_t>(g);
    if (b == 0)
      layout.geom_collider[k] = static_colliders.at(next_static++);
    else if (collider_of_body[b] >= 0)
      layout.geom_collider[k] = collider_of_body[b];
    else
      layout.geom_particle[k] = particle_of_body[b];
  }
  return layout;
}

void collect_collider_forces(const mjModel& m, const mjData& d, const MujocoLayout& layout,
                             std::vector<ColliderForce>& forces) {
  for (ColliderForce& f : forces) f = ColliderForce{};
  for (int k = 0; k < d.ncon; ++k) {
    const mjContact& contact = d.contact[k];
    const auto g1 = static_cast<std::size_t>(contact.geom1);
    const auto g2 = static_cast<std::size_t>(contact.geom2);
    int collider = -1;
    double sign = 0.0;  // +1 when the collider is geom2, which the force pushes along the normal
    if (layout.geom_collider[g1] >= 0 && layout.geom_particle[g2] >= 0) {
      collider = layout.geom_collider[g1];
      sign = -1.0;
    } else if (layout.geom_collider[g2] >= 0 && layout.geom_particle[g1] >= 0) {
      collider = layout.geom_collider[g2];
      sign = 1.0;
    }
    if (collider < 0) continue;  // between particles, or between two colliders
    mjtNum local[6];
    mj_contactForce(&m, &d, k, local);
    const Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> frame(contact.frame);
    const Eigen::Vector3d world =
        frame.transpose() * Eigen::Vector3d(local[0], local[1], local[2]);  // N, on geom2
    const Eigen::Vector3d load = sign * world;                              // N, on the collider
    ColliderForce& total = forces[static_cast<std::size_t>(collider)];
    total.normal += std::abs(local[0]);
    total.friction += std::hypot(local[1], local[2]);
    total.force += load;
    total.torque += Eigen::Vector3d(contact.pos[0], contact.pos[1], contact.pos[2]).cross(load);
  }
}

}  // namespace drapelab::mujoco
