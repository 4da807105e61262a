// Pinned particles carried by colliders (see attachments.hpp).
#include "drapelab/attachments.hpp"

#include <Eigen/Geometry>
#include <stdexcept>
#include <string>

namespace drapelab {

std::pair<Eigen::Vector3d, Eigen::Vector3d> Attachments::placement(std::size_t k, double t) const {
  const Attachment& a = list[k];
  const auto c = static_cast<std::size_t>(a.collider);
  if (poses && colliders[c].dynamic()) {
    const ColliderKinematics body = poses->at(c, t);
    const Eigen::Vector3d position = body.pose * a.offset;
    return {position, body.point_velocity(position)};
  }
  const Eigen::Vector3d position = collider_pose(colliders[c], t) * a.offset;
  return {position, collider_point_velocity(colliders[c], t, position)};
}

void Attachments::place(double t, Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& v) const {
  // One pose per run of attachments on the same collider (a cape holds a few particles per
  // shoulder, a hammock dozens, listed collider by collider), kept without a heap buffer so that a
  // step allocates nothing.
  std::size_t posed = colliders.size();  // the collider `pose` holds; none yet
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (std::size_t k = 0; k < list.size(); ++k) {
    const Attachment& a = list[k];
    const auto c = static_cast<std::size_t>(a.collider);
    if (poses && colliders[c].dynamic()) {
      const auto [position, velocity] = placement(k, t);
      x.col(a.particle) = position;
      v.col(a.particle) = velocity;
      continue;
    }
    if (posed != c) {
      pose = collider_pose(colliders[c], t);
      posed = c;
    }
    const Eigen::Vector3d position = pose * a.offset;
    x.col(a.particle) = position;
    v.col(a.particle) = collider_point_velocity(colliders[c], t, position);
  }
}

Attachments make_attachments(std::vector<Collider> colliders,
                             const std::vector<std::pair<int, int>>& particles,
                             const Eigen::Matrix3Xd& x, double t) {
  Attachments out;
  out.colliders = std::move(colliders);
  for (const auto& [particle, collider] : particles) {
    if (particle < 0 || particle >= x.cols())
      throw std::invalid_argument("attachment of particle " + std::to_string(particle) +
                                  ": the cloth has " + std::to_string(x.cols()) + " particles");
    if (collider < 0 || collider >= static_cast<int>(out.colliders.size()))
      throw std::invalid_argument("attachment to collider " + std::to_string(collider) +
                                  ": the scene has " + std::to_string(out.colliders.size()));
    const Eigen::Isometry3d pose =
        collider_pose(out.colliders[static_cast<std::size_t>(collider)], t);
    out.list.push_back({particle, collider, pose.inverse() * Eigen::Vector3d(x.col(particle))});
  }
  return out;
}

}  // namespace drapelab
