// The colliders of a scene as seen by our solver: their FCL geometry, poses over time, and the
// penalty contact phase of a step (core/penalty_contact.hpp), with a bounding-box broad phase so
// that particles far from every collider cost a few comparisons (contact/contact_pass.hpp).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/collider_pose_table.hpp"
#include "drapelab/contact_fcl.hpp"
#include "drapelab/energy_ledger.hpp"

namespace drapelab {

struct ContactParameters {
  double stiffness = 5000.0;  // N/m per particle
  double damping = 5.0;       // N*s/m
};

// What one collider did to the cloth during a force evaluation.
struct ColliderContactTotals {
  int contact_count = 0;        // particles overlapping the collider
  double normal_force = 0.0;    // N, sum of |normal force| over them
  double friction_force = 0.0;  // N, sum of |friction force| over them
  double max_depth = 0.0;       // m, deepest overlap
  // What the cloth exerts on the collider (minus the sum of the contacts' forces on the cloth) and
  // its moment about the world origin, each contact's force acting at its particle or cloth point:
  // the load a dynamic collider's body takes (N, N*m).
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  // The contacts' dissipation (dampers, friction, the clamp) and the work the collider's motion
  // does on the cloth through them (W), for the energy ledger (energy_ledger.hpp).
  PowerSplit power;
};

// A particle that a collider's penalty spring pushed in the last evaluation, for the implicit
// solve: inside the contact the normal force fn n = (k depth - c vn) n changes with x and v as d/dx
// = -k n n^T (the surface taken as flat at the contact) and d/dv = -c n n^T.
struct ActiveContact {
  int particle = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // outward, unit
};

// The contact phase's per-block workspace and the work run on a block once its forces are final
// (contact/contact_pass.hpp).
struct ContactWorkspace;
struct ContactBlockFollowUp;

// How the penalty normal force is timed within a step (penalty_contact.hpp).
enum class ContactNormalScheme {
  explicit_penalty,   // k depth - c u at the state given: any integrator
  linearly_implicit,  // at the end of a symplectic Euler step of h: stable at any h
};

class ContactModel {
 public:
  // `radius`: the particles' contact radius, the cloth's thickness (m). Without `poses` the
  // colliders are posed by collider_pose(t); with them (one entry per collider), by whatever the
  // table holds when a force is evaluated: a host world fills it before each substep
  // (collider_pose_table.hpp).
  ContactModel(std::vector<Collider> colliders, ContactParameters parameters, double radius,
               std::shared_ptr<const ColliderPoseTable> poses = nullptr);

  std::size_t size() const { return colliders_.size(); }
  bool empty() const { return colliders_.empty(); }
  const Collider& collider(std::size_t c) const { return colliders_[c]; }
  const FclCollider& fcl_collider(std::size_t c) const { return fcl_colliders_[c]; }
  const std::vector<Collider>& colliders() const { return colliders_; }
  const ContactParameters& parameters() const { return parameters_; }
  const ParticleContactQuery& query() const { return query_; }
  const ColliderPoseTable* pose_table() const { return poses_.get(); }
  // Collider c's frame -> world at time t (s): from the pose table when there is one, else
  // collider_pose(t). The contact phase uses exactly this pose.
  Eigen::Isometry3d pose(std::size_t c, double t) const;
  // Velocity (m/s) of collider c's material point at world position p at time t (s), moved like
  // pose(): zero for a static collider.
  Eigen::Vector3d surface_velocity(std::size_t c, double t, const Eigen::Vector3d& p) const;
  // FCL shape frame -> world at time t (s), posed like pose().
  Eigen::Isometry3d shape_pose(std::size_t c, double t) const;

  // Adds penalty and friction forces (N) to `force` for the state (x, v) at time t, for a step of
  // h. Friction uses the force already accumulated, so call it after every other force phase.
  // `normal`: the penalty force at the state given, or (for symplectic Euler only) the force the
  // step's end state implies (penalty_contact.hpp), which uses the accumulated force too.
  // `totals` (one per collider) is overwritten. Pinned particles are skipped. When `active` is
  // given, it is cleared and receives every pushing contact (in a fixed order: by block of
  // particles, then collider, then particle; with the end-of-step normal, by block, then particle,
  // then collider). Particles are processed in fixed blocks spread over the threads
  // (core/thread_blocks.hpp); `workspace` keeps the blocks' results between calls (a temporary one
  // when null), and with it the call allocates nothing once grown. `follow_up`, when given, runs on
  // every block once its forces are final (every block, including those without contacts; x and v
  // may be the arrays it updates); the call then returns the lowest particle it flagged, else -1.
  std::int64_t add_contact_forces(
      const ClothModel& model, double t, double h, const Eigen::Matrix3Xd& x,
      const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force,
      std::vector<ColliderContactTotals>& totals, std::vector<ActiveContact>* active = nullptr,
      ContactWorkspace* workspace = nullptr,
      ContactNormalScheme normal = ContactNormalScheme::explicit_penalty,
      const ContactBlockFollowUp* follow_up = nullptr) const;

 private:
  std::vector<Collider> colliders_;
  std::vector<FclCollider> fcl_colliders_;
  ContactParameters parameters_;
  ParticleContactQuery query_;
  std::shared_ptr<const ColliderPoseTable> poses_;  // null: analytic poses
};

}  // namespace drapelab
