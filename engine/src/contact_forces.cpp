// The contact phase of our step: broad phase by bounding box, exact FCL narrow phase, penalty normal
// force and velocity-level Coulomb friction relative to the collider's moving surface. Particles are
// handled in fixed blocks spread over the threads; each block keeps its own totals and contact list,
// and the blocks are then summed in block order, so no result depends on the thread count.
#include "drapelab/contact_model.hpp"
#include "drapelab/particle_loops.hpp"
#include "drapelab/penalty_contact.hpp"

#include <fcl/geometry/shape/halfspace.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace drapelab {
namespace {

// Particles per block: large enough that a block's bookkeeping is noise, small enough that the two
// threads' runs of blocks split the cloth near its middle. Fixed, never derived from the thread count,
// so every sum runs in the same order on any machine.
constexpr int kContactBlock = 512;

// The broad phase of one posed collider: a plane compares the particle's height above it; other
// shapes test the bounding box and the shape's exact bounding sphere (the box alone is loose for a
// rotated or round shape; for a sphere collider the bounding sphere is the contact test itself).
kernels::NearCollider near_test(const FclCollider& collider, const Eigen::Isometry3d& shape_pose, double radius) {
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
  Eigen::Map<Eigen::Vector3d>(near.center) = shape_pose.translation();  // FCL shapes are centred on it
  // Widened by a relative 1e-9 so that rounding never drops a particle FCL would call touching.
  const double reach = (bounding_radius(collider) + radius) * (1.0 + 1e-9);
  near.reach_squared = reach * reach;
  return near;
}

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

std::int64_t ContactModel::add_contact_forces(const ClothModel& model, double t, double h, const Eigen::Matrix3Xd& x,
                                              const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force,
                                              std::vector<ColliderContactTotals>& totals,
                                              std::vector<ActiveContact>* active, ContactWorkspace* workspace,
                                              ContactNormalScheme normal_scheme,
                                              const ContactBlockFollowUp* follow_up) const {
  ContactWorkspace temporary;
  ContactWorkspace& work = workspace ? *workspace : temporary;
  const std::size_t collider_count = colliders_.size();
  const int n = model.particle_count();
  const std::int64_t blocks = (n + kContactBlock - 1) / kContactBlock;

  // Pose every collider once: as the host world has it when there is a pose table, else by the
  // collider's own motion (the bare solver).
  work.posed.resize(collider_count);
  for (std::size_t c = 0; c < collider_count; ++c) {
    const ColliderKinematics hosted = poses_ ? poses_->at(c, t) : ColliderKinematics{};
    const Eigen::Isometry3d pose = poses_ ? hosted.pose : collider_pose(colliders_[c], t);
    work.posed[c].shape_pose = pose * fcl_colliders_[c].shape_in_collider;
    work.posed[c].near = near_test(fcl_colliders_[c], work.posed[c].shape_pose, query_.radius());
    work.posed[c].hosted = hosted;
    work.posed[c].moving = poses_ ? hosted.moving() : !colliders_[c].motion.is_static();
  }
  const auto block_count = static_cast<std::size_t>(blocks);
  if (work.blocks.size() < block_count) work.blocks.resize(block_count);
  for (std::size_t b = 0; b < block_count; ++b) {
    ContactBlockWork& record = work.blocks[b];
    record.colliders.assign(collider_count, BlockColliderTotals{});
    if (record.near.size() < static_cast<std::size_t>(kContactBlock)) record.near.resize(kContactBlock);
  }

  // The friction of one contact whose normal force fn (N) is already in its particle's force, sized
  // with everything the particle carries so far, and the contact's share of its collider's totals.
  const auto finish_contact = [&](std::int64_t block, const TouchingContact& touching, double fn) {
    const int i = touching.particle;
    const std::size_t c = static_cast<std::size_t>(touching.collider);
    const Collider& collider = colliders_[c];
    Eigen::Vector3d friction = Eigen::Vector3d::Zero();
    if (fn > 0.0 && collider.static_friction > 0.0) {
      const double mass = model.mass[i];
      const Eigen::Vector3d relative_velocity = v.col(i) - touching.surface_velocity;
      const Eigen::Vector3d trial = relative_velocity + (h / mass) * force.col(i);
      friction = coulomb_friction_force(trial - trial.dot(touching.normal) * touching.normal, mass, h, fn,
                                        collider.static_friction, collider.friction);
      force.col(i) += friction;
    }
    ColliderContactTotals& total = work.blocks[static_cast<std::size_t>(block)].colliders[c].totals;
    ++total.contact_count;
    total.normal_force += fn;
    total.friction_force += friction.norm();
    total.max_depth = std::max(total.max_depth, touching.depth);
  };

  const auto contact_block_forces = [&](std::int64_t block) {
    const int begin = static_cast<int>(block * kContactBlock), end = std::min(n, begin + kContactBlock);
    ContactBlockWork& record = work.blocks[static_cast<std::size_t>(block)];
    std::vector<ActiveContact>& block_active = record.active;
    block_active.clear();
    // 1. Every overlap in the block, collider by collider, each collider's in particle order.
    std::vector<TouchingContact>& found = record.touching;
    found.clear();
    int* near = record.near.data();
    for (std::size_t c = 0; c < collider_count; ++c) {
      const Collider& collider = colliders_[c];
      const PosedCollider& posed = work.posed[c];
      const int near_count = kernels::near_particles(posed.near, x.data(), begin, end, near);  // broad phase
      for (int k = 0; k < near_count; ++k) {
        const int i = near[k];
        if (model.is_pinned(i)) continue;
        const auto touching = query_.contact(fcl_colliders_[c], posed.shape_pose, x.col(i));
        if (!touching) continue;
        const Eigen::Vector3d surface_velocity =
            !posed.moving ? Eigen::Vector3d::Zero()
            : poses_      ? posed.hosted.point_velocity(x.col(i))
                          : collider_point_velocity(collider, t, x.col(i));
        found.push_back({i, static_cast<int>(c), touching->depth, touching->normal, surface_velocity});
      }
    }
    if (normal_scheme == ContactNormalScheme::explicit_penalty) {
      // 2a. In that order, as a serial loop over colliders would: friction sees the normal and friction
      // forces of the colliders before it.
      for (const TouchingContact& touching : found) {
        const int i = touching.particle;
        const double fn = penalty_normal_force(touching.depth, (v.col(i) - touching.surface_velocity).dot(touching.normal),
                                               parameters_.stiffness, parameters_.damping);
        force.col(i) += fn * touching.normal;
        if (active && fn > 0.0) block_active.push_back({i, touching.normal});
        finish_contact(block, touching, fn);
      }
      return;
    }
    // 2b. End of step: each particle's contacts together (penalty_contact.hpp), then their frictions in
    // collider order. The overlaps grouped by particle (a counting sort, stable: colliders stay in order).
    std::array<int, kContactBlock + 1> first{};  // per particle of the block: its first entry in `order`
    for (const TouchingContact& touching : found) ++first[static_cast<std::size_t>(touching.particle - begin) + 1];
    for (int p = 0; p < kContactBlock; ++p) first[p + 1] += first[p];
    std::vector<int>& order = record.order;
    order.resize(found.size());
    std::array<int, kContactBlock> next;
    std::copy(first.begin(), first.end() - 1, next.begin());
    for (std::size_t e = 0; e < found.size(); ++e)
      order[static_cast<std::size_t>(next[static_cast<std::size_t>(found[e].particle - begin)]++)] = static_cast<int>(e);
    std::array<NormalContact, kMaxSimultaneousContacts> normals;
    std::array<double, kMaxSimultaneousContacts> fn;
    for (int p = 0; p < end - begin; ++p) {
      const int touching_count = first[p + 1] - first[p];
      if (touching_count == 0) continue;
      const int count = std::min(touching_count, kMaxSimultaneousContacts);  // any further ones push nothing
      const int i = begin + p;
      for (int a = 0; a < count; ++a) {
        const TouchingContact& touching = found[static_cast<std::size_t>(order[first[p] + a])];
        normals[a] = {touching.normal, touching.depth, touching.surface_velocity};
      }
      linearly_implicit_normal_forces(normals.data(), count, v.col(i), force.col(i), model.mass[i], h,
                                      parameters_.stiffness, parameters_.damping, fn.data());
      for (int a = 0; a < count; ++a) {
        force.col(i) += fn[a] * normals[a].normal;
        if (active && fn[a] > 0.0) block_active.push_back({i, normals[a].normal});
      }
      for (int a = 0; a < touching_count; ++a)
        finish_contact(block, found[static_cast<std::size_t>(order[first[p] + a])], a < count ? fn[a] : 0.0);
    }
  };
  const auto contact_block = [&](std::int64_t block) {
    contact_block_forces(block);
    if (!follow_up) return;
    const std::int64_t begin = block * kContactBlock, end = std::min<std::int64_t>(n, begin + kContactBlock);
    work.blocks[static_cast<std::size_t>(block)].flagged = follow_up->run(follow_up->context, begin, end);
  };
  kernels::for_each_block(blocks, n >= kernels::kParallelParticles, contact_block);

  // The blocks' results in block order.
  totals.assign(collider_count, ColliderContactTotals{});  // capacity kept after the first step
  if (active) active->clear();
  for (std::int64_t block = 0; block < blocks; ++block) {
    for (std::size_t c = 0; c < collider_count; ++c) {
      const ColliderContactTotals& part = work.blocks[static_cast<std::size_t>(block)].colliders[c].totals;
      totals[c].contact_count += part.contact_count;
      totals[c].normal_force += part.normal_force;
      totals[c].friction_force += part.friction_force;
      totals[c].max_depth = std::max(totals[c].max_depth, part.max_depth);
    }
    if (active) {
      const auto& part = work.blocks[static_cast<std::size_t>(block)].active;
      active->insert(active->end(), part.begin(), part.end());
    }
  }
  if (follow_up)  // blocks in increasing particle order: the first flag found is the lowest
    for (std::int64_t block = 0; block < blocks; ++block)
      if (work.blocks[static_cast<std::size_t>(block)].flagged >= 0) return work.blocks[static_cast<std::size_t>(block)].flagged;
  return -1;
}

}  // namespace drapelab
