// Poses and velocities of kinematic colliders.
#include <cmath>
#include <numbers>

#include "drapelab/collider.hpp"

namespace drapelab {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;  // rad per degree

Eigen::Quaterniond keyframe_rotation(const ColliderKeyframe& k) {
  return Eigen::Quaterniond(euler_rotation(k.rotation));
}

// Index of the keyframe segment holding t, and the fraction along it (clamped to the ends).
std::pair<std::size_t, double> keyframe_segment(const std::vector<ColliderKeyframe>& keys,
                                                double t) {
  if (t <= keys.front().t || keys.size() == 1) return {0, 0.0};
  for (std::size_t k = 0; k + 1 < keys.size(); ++k)
    if (t < keys[k + 1].t) return {k, (t - keys[k].t) / (keys[k + 1].t - keys[k].t)};
  return {keys.size() - 2, 1.0};
}

}  // namespace

const char* collider_shape_name(ColliderShape shape) {
  switch (shape) {
    case ColliderShape::sphere:
      return "sphere";
    case ColliderShape::cylinder:
      return "cylinder";
    case ColliderShape::capsule:
      return "capsule";
    case ColliderShape::box:
      return "box";
    case ColliderShape::plane:
      return "plane";
    case ColliderShape::mesh:
      return "mesh";
  }
  return "unknown";
}

Eigen::Matrix3d euler_rotation(const Eigen::Vector3d& degrees) {
  return (Eigen::AngleAxisd(degrees.z() * kDegree, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(degrees.y() * kDegree, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(degrees.x() * kDegree, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

bool Collider::moves() const {
  if (dynamic() || !motion.is_static()) return true;
  for (const ColliderFrame& frame : ancestors)
    if (!frame.motion.is_static()) return true;
  return false;
}

Eigen::Isometry3d frame_pose(const ColliderFrame& frame, double t) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  const ColliderMotion& motion = frame.motion;
  if (!motion.keyframes.empty()) {
    // Linear in position, spherical-linear in orientation between neighbouring keyframes. The
    // keyframe's rotation turns the frame after its own `rotation` (its orientation at rest),
    // about the keyframe's centre; the frame's `center` plays no part (the keyframes give the
    // centre).
    const auto [k, s] = keyframe_segment(motion.keyframes, t);
    const ColliderKeyframe& a = motion.keyframes[k];
    const ColliderKeyframe& b = motion.keyframes.size() > 1 ? motion.keyframes[k + 1] : a;
    pose.translation() = (1.0 - s) * a.center + s * b.center;
    pose.linear() = keyframe_rotation(a).slerp(s, keyframe_rotation(b)).toRotationMatrix() *
                    euler_rotation(frame.rotation);
    return pose;
  }
  pose.translation() = frame.center + t * motion.velocity;
  const Eigen::Vector3d turn = t * motion.angular_velocity * kDegree;  // rad, rotation vector
  const double angle = turn.norm();
  const Eigen::Matrix3d spin = angle > 0.0
                                   ? Eigen::AngleAxisd(angle, turn / angle).toRotationMatrix()
                                   : Eigen::Matrix3d::Identity();
  pose.linear() = spin * euler_rotation(frame.rotation);
  return pose;
}

Eigen::Vector3d frame_point_velocity(const ColliderFrame& frame, double t,
                                     const Eigen::Vector3d& p) {
  const ColliderMotion& motion = frame.motion;
  if (!motion.keyframes.empty()) {
    // Constant linear and angular velocity within a segment; at rest before the first keyframe and
    // after the last.
    const auto& keys = motion.keyframes;
    if (keys.size() == 1 || t < keys.front().t || t >= keys.back().t)
      return Eigen::Vector3d::Zero();
    const auto [k, s] = keyframe_segment(keys, t);
    const ColliderKeyframe& a = keys[k];
    const ColliderKeyframe& b = keys[k + 1];
    const double span = b.t - a.t;  // s
    Eigen::Quaterniond qa = keyframe_rotation(a), qb = keyframe_rotation(b);
    if (qa.dot(qb) < 0.0) qb.coeffs() = -qb.coeffs();  // slerp takes the shorter way round
    // The frame's own rotation, applied first, cancels from (Rb Rs)(Ra Rs)^T = Rb Ra^T.
    const Eigen::AngleAxisd turn(qb * qa.inverse());
    const Eigen::Vector3d omega = turn.axis() * turn.angle() / span;  // rad/s
    const Eigen::Vector3d center = (1.0 - s) * a.center + s * b.center;
    return (b.center - a.center) / span + omega.cross(p - center);
  }
  const Eigen::Vector3d center = frame.center + t * motion.velocity;
  return motion.velocity + (motion.angular_velocity * kDegree).cross(p - center);
}

Eigen::Isometry3d collider_pose(const Collider& collider, double t) {
  Eigen::Isometry3d pose = frame_pose(collider.frame(), t);
  for (const ColliderFrame& frame : collider.ancestors) pose = frame_pose(frame, t) * pose;
  return pose;
}

Eigen::Vector3d collider_point_velocity(const Collider& collider, double t,
                                        const Eigen::Vector3d& p) {
  if (collider.ancestors.empty()) return frame_point_velocity(collider.frame(), t, p);
  // p = A_root ... A_own q moves by sum_k (A_root ... A_(k+1)) dA_k/dt (A_(k-1) ... A_own q): frame
  // k's own motion at the point, seen from the frames above it, which only turn a velocity.
  Eigen::Isometry3d above = Eigen::Isometry3d::Identity();  // world <- frame k's parent
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  const auto add = [&](const ColliderFrame& frame) {
    velocity += above.linear() * frame_point_velocity(frame, t, above.inverse() * p);
    above = above * frame_pose(frame, t);
  };
  for (auto it = collider.ancestors.rbegin(); it != collider.ancestors.rend(); ++it) add(*it);
  add(collider.frame());
  return velocity;
}

}  // namespace drapelab
