// Collider poses set by a host world for one substep (see collider_pose_table.hpp).
#include "drapelab/collider_pose_table.hpp"

namespace drapelab {

void ColliderPoseTable::set_substep(double t0, double t1) {
  t0_ = t0;
  t1_ = t1;
}

ColliderKinematics ColliderPoseTable::at(std::size_t c, double t) const {
  const ColliderSubstepMotion& m = motions_[c];
  ColliderKinematics k;
  k.velocity = m.velocity;
  k.angular_velocity = m.angular_velocity;
  // The ends are returned as the host holds them, so a guest evaluating at t0 or t1 sees the host's
  // pose bit for bit rather than a re-integrated one.
  if (t == t0_) {
    k.pose = m.start;
  } else if (t == t1_) {
    k.pose = m.end;
  } else {
    const double elapsed = t - t0_;                             // s
    const Eigen::Vector3d turn = elapsed * m.angular_velocity;  // rad, rotation vector
    const double angle = turn.norm();
    k.pose = m.start;
    if (angle > 0.0)
      k.pose.linear() =
          Eigen::AngleAxisd(angle, turn / angle).toRotationMatrix() * m.start.linear();
    k.pose.translation() = m.start.translation() + elapsed * m.velocity;
  }
  return k;
}

}  // namespace drapelab
