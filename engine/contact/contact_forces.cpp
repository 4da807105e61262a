// The contact phase of our step: broad phase by bounding box, exact FCL narrow phase, penalty
// normal force and velocity-level Coulomb friction relative to the collider's moving surface.
// Particles are handled in fixed blocks spread over the threads; each block keeps its own totals
// and contact list, and the blocks are then summed in block order, so no result depends on the
// thread count.
#include <fcl/geometry/shape/halfspace.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <stdexcept>
#include <string>

#include "contact/broad_phase_loops.hpp"
#include "contact/contact_pass.hpp"
#include "core/penalty_contact.hpp"
#include "core/thread_blocks.hpp"
#include "drapelab/contact_model.hpp"

namespace drapelab {
namespace {

// Particles per block: the spring kernel's (core/thread_blocks.hpp kPhaseBlock), so the phase can
// run inside that kernel's parallel region on the particles each thread has just gathered.
constexpr int kContactBlock = static_cast<int>(kernels::kPhaseBlock);

// The broad phase of one posed collider: a plane compares the particle's height above it; other
// shapes test the bounding box and the shape's exact bounding sphere (the box alone is loose for a
// rotated or round shape; for a sphere collider the bounding sphere is the contact test itself).
kernels::NearCollider near_test(const FclCollider& collider, const Eigen::Isometry3d& shape_pose,
                                double radius) {
  kernels::NearCollider near;
  near.plane = collider.geometry->getNodeType() == fcl::GEOM_HALFSPACE;
  if (near.plane) {
    const auto& halfspace = static_cast<const fcl::Halfspace<double>&>(*collider.geometry);
    const Eigen::Vector3d normal = shape_pose.linear() * halfspace.n;
    Eigen::Map<Eigen::Vector3d>(near.normal) = normal;
    near.offset = halfspace.d + normal.dot(shape_pose.translation());
    near.radius = radius;
    return near;
  }
  const Eigen::AlignedBox3d box = collider_bounds(collider, shape_pose, radius);
  Eigen::Map<Eigen::Vector3d>(near.low) = box.min();
  Eigen::Map<Eigen::Vector3d>(near.high) = box.max();
  Eigen::Map<Eigen::Vector3d>(near.center) =
      shape_pose.translation();  // FCL shapes are centred on it
  // Widened by a relative 1e-9 so that rounding never drops a particle FCL would call touching.
  const double reach = (bounding_radius(collider) + radius) * (1.0 + 1e-9);
  near.reach_squared = reach * reach;
  return near;
}

// A block's per-collider totals from its overlaps' force magnitudes. The overlaps come collider by
// collider, each collider's in particle order, so each sum runs in particle order, the order in
// which a serial loop over the block's particles would add them (and the same on any thread count).
void sum_block_totals(ContactBlockWork& record, const Eigen::Matrix3Xd& x) {
  const std::vector<TouchingContact>& found = record.touching;
  for (std::size_t e = 0; e < found.size();) {
    const int collider = found[e].collider;
    ColliderContactTotals
        sum;  // in registers: adding to the record contact by contact stalled on its stores
    for (; e < found.size() && found[e].collider == collider; ++e) {
      ++sum.contact_count;
      sum.normal_force += record.applied[e].normal;
      sum.friction_force += record.applied[e].friction;
      sum.power += record.applied[e].power;
      sum.max_depth = std::max(sum.max_depth, found[e].depth);
      const Eigen::Vector3d& on_cloth = record.applied[e].force;
      sum.force -= on_cloth;
      sum.torque -= Eigen::Vector3d(x.col(found[e].particle)).cross(on_cloth);
    }
    record.colliders[static_cast<std::size_t>(collider)].totals = sum;
  }
}

}  // namespace

ContactModel::ContactModel(std::vector<Collider> colliders, ContactParameters parameters,
                           double radius, std::shared_ptr<const ColliderPoseTable> poses)
    : colliders_(std::move(colliders)),
      parameters_(parameters),
      query_(radius),
      poses_(std::move(poses)) {
  if (poses_ && poses_->size() != colliders_.size())
    throw std::invalid_argument("collider pose table has " + std::to_string(poses_->size()) +
                                " entries for " + std::to_string(colliders_.size()) + " colliders");
  fcl_colliders_.reserve(colliders_.size());
  for (const auto& collider : colliders_) fcl_colliders_.push_back(make_fcl_collider(collider));
}

Eigen::Isometry3d ContactModel::pose(std::size_t c, double t) const {
  return poses_ ? poses_->at(c, t).pose : collider_pose(colliders_[c], t);
}

Eigen::Vector3d ContactModel::surface_velocity(std::size_t c, double t,
                                               const Eigen::Vector3d& p) const {
  if (poses_) return poses_->at(c, t).point_velocity(p);
  return !colliders_[c].moves() ? Eigen::Vector3d::Zero()
                                : collider_point_velocity(colliders_[c], t, p);
}

Eigen::Isometry3d ContactModel::shape_pose(std::size_t c, double t) const {
  return pose(c, t) * fcl_colliders_[c].shape_in_collider;
}

ContactPass::ContactPass(const ContactModel& contacts, const ClothModel& model, double t, double h,
                         const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                         Eigen::Matrix3Xd& force, ContactWorkspace& workspace,
                         ContactNormalScheme normal_scheme, bool keep_active,
                         const ContactBlockFollowUp* follow_up)
    : contacts_(contacts),
      model_(model),
      t_(t),
      h_(h),
      x_(x),
      v_(v),
      force_(force),
      work_(workspace),
      normal_scheme_(normal_scheme),
      keep_active_(keep_active),
      follow_up_(follow_up),
      particles_(model.particle_count()),
      blocks_((particles_ + kContactBlock - 1) / kContactBlock) {
  const std::size_t collider_count = contacts_.size();
  const ColliderPoseTable* poses = contacts_.pose_table();
  // Pose every collider once: as the host world has it when there is a pose table, else by the
  // collider's own motion (the bare solver).
  work_.posed.resize(collider_count);
  for (std::size_t c = 0; c < collider_count; ++c) {
    const Collider& collider = contacts_.collider(c);
    const FclCollider& shape = contacts_.fcl_collider(c);
    const ColliderKinematics hosted = poses ? poses->at(c, t) : ColliderKinematics{};
    const Eigen::Isometry3d pose = poses ? hosted.pose : collider_pose(collider, t);
    PosedCollider& posed = work_.posed[c];
    posed.shape_pose = pose * shape.shape_in_collider;
    posed.near = near_test(shape, posed.shape_pose, contacts_.query().radius());
    posed.hosted = hosted;
    posed.moving = poses ? hosted.moving() : collider.moves();
  }
  const auto block_count = static_cast<std::size_t>(blocks_);
  if (work_.blocks.size() < block_count) work_.blocks.resize(block_count);
  for (std::size_t b = 0; b < block_count; ++b) {
    ContactBlockWork& record = work_.blocks[b];
    record.colliders.assign(collider_count, BlockColliderTotals{});
    if (record.near.size() < static_cast<std::size_t>(kContactBlock))
      record.near.resize(kContactBlock);
  }
}

void ContactPass::finish_contact(ContactBlockWork& record, std::size_t e, double fn) const {
  const TouchingContact& touching = record.touching[e];
  const int i = touching.particle;
  const Collider& collider = contacts_.collider(static_cast<std::size_t>(touching.collider));
  double friction_magnitude = 0.0;
  Eigen::Vector3d on_cloth = fn * touching.normal;                                  // N
  const Eigen::Vector3d relative_velocity = v_.col(i) - touching.surface_velocity;  // m/s
  PowerSplit power = push_power(fn, contacts_.parameters().stiffness * touching.depth,
                                touching.normal, relative_velocity, touching.surface_velocity);
  if (fn > 0.0 && collider.static_friction > 0.0) {
    const double mass = model_.mass[i];
    const Eigen::Vector3d trial = relative_velocity + (h_ / mass) * force_.col(i);
    const FrictionForce friction =
        coulomb_friction_force(trial - trial.dot(touching.normal) * touching.normal, mass, h_, fn,
                               collider.static_friction, collider.friction);
    force_.col(i) += friction.force;
    friction_magnitude = friction.magnitude;
    on_cloth += friction.force;
    power += friction_power(friction.force, relative_velocity, touching.surface_velocity);
  }
  record.applied[e] = {fn, friction_magnitude, power, on_cloth};
}

void ContactPass::block_forces(std::int64_t block) const {
  const int begin = static_cast<int>(block * kContactBlock),
            end = std::min(particles_, begin + kContactBlock);
  ContactBlockWork& record = work_.blocks[static_cast<std::size_t>(block)];
  std::vector<ActiveContact>& block_active = record.active;
  block_active.clear();
  // 1. Every overlap in the block, collider by collider, each collider's in particle order.
  std::vector<TouchingContact>& found = record.touching;
  found.clear();
  int* near = record.near.data();
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    const Collider& collider = contacts_.collider(c);
    const PosedCollider& posed = work_.posed[c];
    const int near_count =
        kernels::near_particles(posed.near, x_.data(), begin, end, near);  // broad phase
    for (int k = 0; k < near_count; ++k) {
      const int i = near[k];
      if (model_.is_pinned(i)) continue;
      const auto touching =
          contacts_.query().contact(contacts_.fcl_collider(c), posed.shape_pose, x_.col(i));
      if (!touching) continue;
      const Eigen::Vector3d surface_velocity =
          !posed.moving            ? Eigen::Vector3d::Zero()
          : contacts_.pose_table() ? posed.hosted.point_velocity(x_.col(i))
                                   : collider_point_velocity(collider, t_, x_.col(i));
      found.push_back(
          {i, static_cast<int>(c), touching->depth, touching->normal, surface_velocity});
    }
  }
  record.applied.resize(found.size());
  if (normal_scheme_ == ContactNormalScheme::explicit_penalty) {
    // 2a. In that order, as a serial loop over colliders would: friction sees the normal and
    // friction forces of the colliders before it.
    for (std::size_t e = 0; e < found.size(); ++e) {
      const TouchingContact& touching = found[e];
      const int i = touching.particle;
      const double fn = penalty_normal_force(
          touching.depth, (v_.col(i) - touching.surface_velocity).dot(touching.normal),
          contacts_.parameters().stiffness, contacts_.parameters().damping);
      force_.col(i) += fn * touching.normal;
      if (keep_active_ && fn > 0.0) block_active.push_back({i, touching.normal});
      finish_contact(record, e, fn);
    }
    sum_block_totals(record, x_);
    return;
  }
  // 2b. End of step: each particle's contacts together (penalty_contact.hpp), then their frictions
  // in collider order. The overlaps are grouped by particle: already so when they come in particle
  // order (one collider touched, or each collider's overlaps beyond the last one's), else by a
  // counting sort (stable: a particle's colliders stay in order).
  std::vector<int>& order = record.order;  // overlap indices, particle by particle
  order.resize(found.size());
  const auto by_particle = [](const TouchingContact& a, const TouchingContact& b) {
    return a.particle < b.particle;
  };
  if (std::is_sorted(found.begin(), found.end(), by_particle)) {
    std::iota(order.begin(), order.end(), 0);
  } else {
    std::array<int, kContactBlock + 1>
        first{};  // per particle of the block: its first entry in `order`
    for (const TouchingContact& touching : found)
      ++first[static_cast<std::size_t>(touching.particle - begin) + 1];
    for (int p = 0; p < kContactBlock; ++p) first[p + 1] += first[p];
    for (std::size_t e = 0; e < found.size(); ++e)
      order[static_cast<std::size_t>(
          first[static_cast<std::size_t>(found[e].particle - begin)]++)] = static_cast<int>(e);
  }
  std::array<NormalContact, kMaxSimultaneousContacts> normals;
  std::array<double, kMaxSimultaneousContacts> fn;
  for (std::size_t group = 0; group < order.size();) {
    const int i = found[static_cast<std::size_t>(order[group])].particle;
    std::size_t group_end = group + 1;
    while (group_end < order.size() &&
           found[static_cast<std::size_t>(order[group_end])].particle == i)
      ++group_end;
    const int touching_count = static_cast<int>(group_end - group);
    const int count =
        std::min(touching_count, kMaxSimultaneousContacts);  // any further ones push nothing
    if (count ==
        1) {  // nearly every contact: the closed form, as linearly_implicit_normal_forces has it
      const TouchingContact& only = found[static_cast<std::size_t>(order[group])];
      normals[0].normal = only.normal;
      fn[0] = linearly_implicit_normal_force(
          only.depth, (v_.col(i) - only.surface_velocity).dot(only.normal),
          force_.col(i).dot(only.normal), model_.mass[i], h_, contacts_.parameters().stiffness,
          contacts_.parameters().damping);
    } else {
      for (int a = 0; a < count; ++a) {
        const TouchingContact& touching =
            found[static_cast<std::size_t>(order[group + static_cast<std::size_t>(a)])];
        normals[a] = {touching.normal, touching.depth, touching.surface_velocity};
      }
      linearly_implicit_normal_forces(normals.data(), count, v_.col(i), force_.col(i),
                                      model_.mass[i], h_, contacts_.parameters().stiffness,
                                      contacts_.parameters().damping, fn.data());
    }
    for (int a = 0; a < count; ++a) {
      force_.col(i) += fn[a] * normals[a].normal;
      if (keep_active_ && fn[a] > 0.0) block_active.push_back({i, normals[a].normal});
    }
    for (int a = 0; a < touching_count; ++a)
      finish_contact(record, static_cast<std::size_t>(order[group + static_cast<std::size_t>(a)]),
                     a < count ? fn[a] : 0.0);
    group = group_end;
  }
  sum_block_totals(record, x_);
}

void ContactPass::run_block(std::int64_t block) const {
  block_forces(block);
  ContactBlockWork& record = work_.blocks[static_cast<std::size_t>(block)];
  record.flagged = -1;
  if (!follow_up_) return;
  const std::int64_t begin = block * kContactBlock,
                     end = std::min<std::int64_t>(particles_, begin + kContactBlock);
  record.flagged = follow_up_->run(follow_up_->context, begin, end);
}

std::int64_t ContactPass::finish(std::vector<ColliderContactTotals>& totals,
                                 std::vector<ActiveContact>* active) const {
  // The blocks' results in block order.
  const std::size_t collider_count = contacts_.size();
  totals.assign(collider_count, ColliderContactTotals{});  // capacity kept after the first step
  if (active) active->clear();
  std::int64_t flagged = -1;
  for (std::int64_t block = 0; block < blocks_; ++block) {
    const ContactBlockWork& record = work_.blocks[static_cast<std::size_t>(block)];
    for (std::size_t c = 0; c < collider_count; ++c) {
      const ColliderContactTotals& part = record.colliders[c].totals;
      totals[c].contact_count += part.contact_count;
      totals[c].normal_force += part.normal_force;
      totals[c].friction_force += part.friction_force;
      totals[c].power += part.power;
      totals[c].max_depth = std::max(totals[c].max_depth, part.max_depth);
      totals[c].force += part.force;
      totals[c].torque += part.torque;
    }
    if (active && keep_active_)
      active->insert(active->end(), record.active.begin(), record.active.end());
    // Blocks in increasing particle order: the first flag found is the lowest.
    if (flagged < 0 && record.flagged >= 0) flagged = record.flagged;
  }
  return flagged;
}

std::int64_t ContactModel::add_contact_forces(
    const ClothModel& model, double t, double h, const Eigen::Matrix3Xd& x,
    const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force, std::vector<ColliderContactTotals>& totals,
    std::vector<ActiveContact>* active, ContactWorkspace* workspace,
    ContactNormalScheme normal_scheme, const ContactBlockFollowUp* follow_up) const {
  ContactWorkspace temporary;
  const ContactPass pass(*this, model, t, h, x, v, force, workspace ? *workspace : temporary,
                         normal_scheme, active != nullptr, follow_up);
  kernels::for_each_block(pass.block_count(), model.particle_count() >= kernels::kParallelParticles,
                          [&pass](std::int64_t block) { pass.run_block(block); });
  return pass.finish(totals, active);
}

}  // namespace drapelab
