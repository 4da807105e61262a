// The contact phase of our step: broad phase by bounding box, exact FCL narrow phase, penalty normal
// force and velocity-level Coulomb friction relative to the collider's moving surface.
#include "drapelab/contact_model.hpp"
#include "drapelab/penalty_contact.hpp"

#include <fcl/geometry/shape/halfspace.h>

#include <stdexcept>
#include <string>

namespace drapelab {
namespace {

// Broad phase for one posed collider: a few multiplications tell that a particle cannot touch it.
// A plane compares the particle's height above it; other shapes test the bounding box and the
// bounding sphere (the box alone is loose for a rotated or round shape).
class NearTest {
 public:
  NearTest(const FclCollider& collider, const Eigen::Isometry3d& pose, double radius) : radius_(radius) {
    plane_ = collider.geometry->getNodeType() == fcl::GEOM_HALFSPACE;
    if (plane_) {
      const auto& halfspace = static_cast<const fcl::Halfspace<double>&>(*collider.geometry);
      normal_ = pose.linear() * halfspace.n;
      offset_ = halfspace.d + normal_.dot(pose.translation());
      return;
    }
    box_ = collider_bounds(collider, pose, radius);
    const fcl::AABBd& local = collider.geometry->aabb_local;
    center_ = pose * local.center();
    reach_ = 0.5 * (local.max_ - local.min_).norm() + radius;
  }

  bool may_touch(const Eigen::Vector3d& x) const {
    if (plane_) return normal_.dot(x) - offset_ < radius_;
    return box_.contains(x) && (x - center_).squaredNorm() < reach_ * reach_;
  }

 private:
  double radius_;
  bool plane_ = false;
  Eigen::Vector3d normal_ = Eigen::Vector3d::Zero();  // plane: world normal
  double offset_ = 0.0;                               // plane: n . p on the plane (m)
  Eigen::AlignedBox3d box_;
  Eigen::Vector3d center_ = Eigen::Vector3d::Zero();  // bounding sphere centre (m)
  double reach_ = 0.0;                                // bounding sphere radius + particle radius (m)
};

}  // namespace

ContactModel::ContactModel(std::vector<Collider> colliders, ContactParameters parameters, double radius,
                           std::shared_ptr<const ColliderPoseTable> poses)
    : colliders_(std::move(colliders)), parameters_(parameters), query_(radius), poses_(std::move(poses)) {
  if (poses_ && poses_->size() != colliders_.size())
    throw std::invalid_argument("collider pose table has " + std::to_string(poses_->size()) + " entries for " +
                                std::to_string(colliders_.size()) + " colliders");
  fcl_colliders_.reserve(colliders_.size());
  for (const auto& collider : colliders_) fcl_colliders_.push_back(make_fcl_collider(collider));
}

Eigen::Isometry3d ContactModel::pose(std::size_t c, double t) const {
  return poses_ ? poses_->at(c, t).pose : collider_pose(colliders_[c], t);
}

Eigen::Isometry3d ContactModel::shape_pose(std::size_t c, double t) const {
  return pose(c, t) * fcl_colliders_[c].shape_in_collider;
}

void ContactModel::add_contact_forces(const ClothModel& model, double t, double h, const Eigen::Matrix3Xd& x,
                                      const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force,
                                      std::vector<ColliderContactTotals>& totals,
                                      std::vector<ActiveContact>* active) const {
  if (active) active->clear();
  totals.assign(colliders_.size(), ColliderContactTotals{});  // capacity kept after the first step
  for (std::size_t c = 0; c < colliders_.size(); ++c) {
    const Collider& collider = colliders_[c];
    // Posed and moving as the host world has it when there is a pose table, else by the collider's
    // own motion (the bare solver: every expression below as it was before hosts existed).
    const ColliderKinematics hosted = poses_ ? poses_->at(c, t) : ColliderKinematics{};
    const Eigen::Isometry3d pose =
        (poses_ ? hosted.pose : collider_pose(collider, t)) * fcl_colliders_[c].shape_in_collider;
    const NearTest near(fcl_colliders_[c], pose, query_.radius());
    const bool moving = poses_ ? hosted.moving() : !collider.motion.is_static();
    ColliderContactTotals& total = totals[c];
    for (int i = 0; i < model.particle_count(); ++i) {
      if (model.is_pinned(i) || !near.may_touch(x.col(i))) continue;  // broad phase
      const auto touching = query_.contact(fcl_colliders_[c], pose, x.col(i));
      if (!touching) continue;
      const Eigen::Vector3d& n = touching->normal;
      const Eigen::Vector3d surface_velocity =
          !moving  ? Eigen::Vector3d::Zero()
          : poses_ ? hosted.point_velocity(x.col(i))
                   : collider_point_velocity(collider, t, x.col(i));
      const Eigen::Vector3d relative_velocity = v.col(i) - surface_velocity;
      const double fn = penalty_normal_force(touching->depth, relative_velocity.dot(n), parameters_.stiffness,
                                             parameters_.damping);
      force.col(i) += fn * n;
      if (active && fn > 0.0) active->push_back({i, n});
      Eigen::Vector3d friction = Eigen::Vector3d::Zero();
      if (fn > 0.0 && collider.static_friction > 0.0) {
        const double mass = model.mass[i];
        const Eigen::Vector3d trial = relative_velocity + (h / mass) * force.col(i);
        friction = coulomb_friction_force(trial - trial.dot(n) * n, mass, h, fn, collider.static_friction,
                                          collider.friction);
        force.col(i) += friction;
      }
      ++total.contact_count;
      total.normal_force += fn;
      total.friction_force += friction.norm();
      total.max_depth = std::max(total.max_depth, touching->depth);
    }
  }
}

}  // namespace drapelab
