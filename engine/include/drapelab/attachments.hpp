// Pinned particles carried by colliders (cloth.pins[].attach): each keeps its offset in its
// collider's frame and moves with it, its velocity the collider's point velocity there. Every
// solver places them itself at each of its steps (our solver: spring_damper_solver.cpp; Bullet's
// cloths: bullet_bridge/).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <utility>
#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/collider_pose_table.hpp"

namespace drapelab {

struct Attachment {
  int particle = 0;
  int collider = 0;                                  // index into Attachments::colliders
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // m, in the collider's own frame
};

struct Attachments {
  std::vector<Collider> colliders;  // the scene's colliders, indexed by Attachment::collider
  std::vector<Attachment> list;
  // Where a host world has its dynamic colliders over the current substep (our solver hosted in
  // Bullet): particles attached to a dynamic collider follow its body there. Null: every collider
  // is posed by collider_pose(t).
  std::shared_ptr<const ColliderPoseTable> poses;

  bool empty() const { return list.empty(); }
  // Whether particle k's collider is a dynamic body (its pose is the host's, and the particle's
  // load goes onto it).
  bool on_dynamic(std::size_t k) const {
    return colliders[static_cast<std::size_t>(list[k].collider)].dynamic();
  }
  bool any_on_dynamic() const {
    for (std::size_t k = 0; k < list.size(); ++k)
      if (on_dynamic(k)) return true;
    return false;
  }
  // Where attached particle k is at time t (s): W(t) offset (m), and its velocity (m/s).
  std::pair<Eigen::Vector3d, Eigen::Vector3d> placement(std::size_t k, double t) const;
  // Moves every attached particle of x (m) and v (m/s), 3 x N, to its placement at time t (s).
  void place(double t, Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& v) const;
};

// The attachments of `particles` (pairs of particle, collider index), their offsets taken from the
// positions x (3 x N, m) at time t (s). Throws std::invalid_argument for an index out of range.
Attachments make_attachments(std::vector<Collider> colliders,
                             const std::vector<std::pair<int, int>>& particles,
                             const Eigen::Matrix3Xd& x, double t);

}  // namespace drapelab
