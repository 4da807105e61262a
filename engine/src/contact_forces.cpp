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
#include <numeric>
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

// A block's per-collider totals from its overlaps' force magnitudes. The overlaps come collider by
// collider, each collider's in particle order, so each sum runs in particle order, the order in which a
// serial loop over the block's particles would add them (and the same on any thread count).
void sum_block_totals(ContactBlockWork& record) {
  const std::vector<TouchingContact>& found = record.touching;
  for (std::size_t e = 0; e < found.size();) {
    const int collider = found[e].collider;
    ColliderContactTotals sum;  // in registers: adding to the record contact by contact stalled on its stores
    for (; e < found.size() && found[e].collider == collider; ++e) {
      ++sum.contact_count;
      sum.normal_force += record.applied[e].normal;
      sum.friction_force += record.applied[e].friction;
      sum.max_depth = std::max(sum.max_depth, found[e].depth);
    }
    record.colliders[static_cast<std::size_t>(collider)].totals = sum;
  }
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

  // The friction of overlap e of a block, whose normal force fn (N) is already in its particle's force,
  // sized with everything the particle carries so far; both magnitudes are kept for the block's totals.
  const auto finish_contact = [&](ContactBlockWork& record, std::size_t e, double fn) {
    const TouchingContact& touching = record.touching[e];
    const int i = touching.particle;
    const Collider& collider = colliders_[static_cast<std::size_t>(touching.collider)];
    double friction_magnitude = 0.0;
    if (fn > 0.0 && collider.static_friction > 0.0) {
      const double mass = model.mass[i];
      const Eigen::Vector3d relative_velocity = v.col(i) - touching.surface_velocity;
      const Eigen::Vector3d trial = relative_velocity + (h / mass) * force.col(i);
      const FrictionForce friction = coulomb_friction_force(trial - trial.dot(touching.normal) * touching.normal,
                                                            mass, h, fn, collider.static_friction, collider.friction);
      force.col(i) += friction.force;
      friction_magnitude = friction.magnitude;
    }
    record.applied[e] = {fn, friction_magnitude};
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
    record.applied.resize(found.size());
    if (normal_scheme == ContactNormalScheme::explicit_penalty) {
      // 2a. In that order, as a serial loop over colliders would: friction sees the normal and friction
      // forces of the colliders before it.
      for (std::size_t e = 0; e < found.size(); ++e) {
        const TouchingContact& touching = found[e];
        const int i = touching.particle;
        const double fn = penalty_normal_force(touching.depth, (v.col(i) - touching.surface_velocity).dot(touching.normal),
                                               parameters_.stiffness, parameters_.damping);
        force.col(i) += fn * touching.normal;
        if (active && fn > 0.0) block_active.push_back({i, touching.normal});
        finish_contact(record, e, fn);
      }
      sum_block_totals(record);
      return;
    }
    // 2b. End of step: each particle's contacts together (penalty_contact.hpp), then their frictions in
    // collider order. The overlaps are grouped by particle: already so when they come in particle order
    // (one collider touched, or each collider's overlaps beyond the last one's), else by a counting sort
    // (stable: a particle's colliders stay in order).
    std::vector<int>& order = record.order;  // overlap indices, particle by particle
    order.resize(found.size());
    const auto by_particle = [](const TouchingContact& a, const TouchingContact& b) { return a.particle < b.particle; };
    if (std::is_sorted(found.begin(), found.end(), by_particle)) {
      std::iota(order.begin(), order.end(), 0);
    } else {
      std::array<int, kContactBlock + 1> first{};  // per particle of the block: its first entry in `order`
      for (const TouchingContact& touching : found) ++first[static_cast<std::size_t>(touching.particle - begin) + 1];
      for (int p = 0; p < kContactBlock; ++p) first[p + 1] += first[p];
      for (std::size_t e = 0; e < found.size(); ++e)
        order[static_cast<std::size_t>(first[static_cast<std::size_t>(found[e].particle - begin)]++)] = static_cast<int>(e);
    }
    std::array<NormalContact, kMaxSimultaneousContacts> normals;
    std::array<double, kMaxSimultaneousContacts> fn;
    for (std::size_t group = 0; group < order.size();) {
      const int i = found[static_cast<std::size_t>(order[group])].particle;
      std::size_t group_end = group + 1;
      while (group_end < order.size() && found[static_cast<std::size_t>(order[group_end])].particle == i) ++group_end;
      const int touching_count = static_cast<int>(group_end - group);
      const int count = std::min(touching_count, kMaxSimultaneousContacts);  // any further ones push nothing
      if (count == 1) {  // nearly every contact: the closed form, as linearly_implicit_normal_forces has it
        const TouchingContact& only = found[static_cast<std::size_t>(order[group])];
        normals[0].normal = only.normal;
        fn[0] = linearly_implicit_normal_force(only.depth, (v.col(i) - only.surface_velocity).dot(only.normal),
                                               force.col(i).dot(only.normal), model.mass[i], h,
                                               parameters_.stiffness, parameters_.damping);
      } else {
        for (int a = 0; a < count; ++a) {
          const TouchingContact& touching = found[static_cast<std::size_t>(order[group + static_cast<std::size_t>(a)])];
          normals[a] = {touching.normal, touching.depth, touching.surface_velocity};
        }
        linearly_implicit_normal_forces(normals.data(), count, v.col(i), force.col(i), model.mass[i], h,
                                        parameters_.stiffness, parameters_.damping, fn.data());
      }
      for (int a = 0; a < count; ++a) {
        force.col(i) += fn[a] * normals[a].normal;
        if (active && fn[a] > 0.0) block_active.push_back({i, normals[a].normal});
      }
      for (int a = 0; a < touching_count; ++a)
        finish_contact(record, static_cast<std::size_t>(order[group + static_cast<std::size_t>(a)]), a < count ? fn[a] : 0.0);
      group = group_end;
    }
    sum_block_totals(record);
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
