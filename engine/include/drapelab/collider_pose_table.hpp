// Collider poses given from outside for one substep. A host world that moves the colliders itself
// (bullet_bridge's Bullet host) writes, before each step of its guest, where its bodies are at the
// start and end of the substep and the velocities it gave them; a ContactModel built with the table
// reads these in place of the analytic collider_pose(t), so the guest touches the colliders the
// host world holds, not a copy of their motion.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace drapelab {

// A collider at one instant, as the contact phase needs it.
struct ColliderKinematics {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();      // collider frame -> world (m)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // m/s of the collider frame's origin
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // rad/s, world axes

  bool moving() const { return !velocity.isZero(0) || !angular_velocity.isZero(0); }
  // Velocity (m/s) of the collider's material point at world position p.
  Eigen::Vector3d point_velocity(const Eigen::Vector3d& p) const {
    return velocity + angular_velocity.cross(p - pose.translation());
  }
};

// One collider's rigid motion over a substep [t0, t1]: the host's poses at both ends and the
// constant velocities that carry the first into the second.
struct ColliderSubstepMotion {
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();     // collider frame -> world at t0
  Eigen::Isometry3d end = Eigen::Isometry3d::Identity();       // collider frame -> world at t1
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // m/s of the collider frame's origin
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // rad/s, world axes
};

class ColliderPoseTable {
 public:
  explicit ColliderPoseTable(std::size_t colliders) : motions_(colliders) {}

  std::size_t size() const { return motions_.size(); }
  double start_time() const { return t0_; }  // s
  double end_time() const { return t1_; }    // s

  // The substep the next guest step covers, then each collider's motion over it (scene order).
  void set_substep(double t0, double t1);
  void set(std::size_t c, const ColliderSubstepMotion& motion) { motions_[c] = motion; }
  const ColliderSubstepMotion& motion(std::size_t c) const { return motions_[c]; }

  // Collider c at time t (s): exactly the start pose at t0 and the end pose at t1; at other times
  // (the inner stages of multi-stage integrators) the start pose carried by the substep's constant
  // velocities. Allocates nothing.
  ColliderKinematics at(std::size_t c, double t) const;

 private:
  std::vector<ColliderSubstepMotion> motions_;
  double t0_ = 0.0;  // s
  double t1_ = 0.0;  // s
};

}  // namespace drapelab
