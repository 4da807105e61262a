// One evaluation of the contact phase in parts a caller can spread over its own threads, and the
// per-block records it keeps between evaluations.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "contact/broad_phase_loops.hpp"
#include "core/thread_blocks.hpp"
#include "drapelab/contact_model.hpp"

namespace drapelab {

// One collider posed for a force evaluation, with its broad phase (broad_phase_loops.hpp).
struct PosedCollider {
  Eigen::Isometry3d shape_pose = Eigen::Isometry3d::Identity();  // FCL shape frame -> world
  ColliderKinematics hosted;  // the host's pose and velocities (with a pose table only)
  bool moving = false;        // the surface moves: friction is relative to it
  kernels::NearCollider near;
};

// A particle found inside a collider's contact shell by the narrow phase.
struct TouchingContact {
  int particle = 0;
  int collider = 0;
  double depth = 0.0;                                          // m, > 0
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();           // outward, unit
  Eigen::Vector3d surface_velocity = Eigen::Vector3d::Zero();  // m/s, the collider's surface there
};

// The force magnitudes one overlap applied (N), kept beside the block's overlaps until the block's
// totals are summed from them.
struct ContactForceMagnitudes {
  double normal = 0.0;                              // N, the penalty force
  double friction = 0.0;                            // N, |friction force|
  PowerSplit power;                                 // W, energy_ledger.hpp
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // N, normal and friction, on the particle
};

// One collider's totals within one block, alone on its cache line (see ContactBlockWork).
struct alignas(64) BlockColliderTotals {
  ColliderContactTotals totals;
};

// One block's share of the contact phase, kept between calls. Each block's record starts a cache
// line of its own and its totals have lines of their own: the two threads append to their blocks'
// lists and add to their totals at once, contact by contact, and records that shared a line would
// make the cores trade it on every contact (false sharing, in the middle of the sheet where the two
// threads' runs meet and a draped cloth's contacts are).
struct alignas(64) ContactBlockWork {
  std::vector<int> near;                        // the broad phase's particles for one collider
  std::vector<TouchingContact> touching;        // overlaps, collider by collider
  std::vector<ContactForceMagnitudes> applied;  // per overlap, what it applied
  std::vector<int> order;                       // those overlaps' indices, particle by particle
  std::vector<ActiveContact> active;            // pushing contacts, in particle order
  std::vector<BlockColliderTotals> colliders;   // per collider
  std::int64_t flagged = -1;                    // what the follow-up flagged here, or -1
};

// What the contact phase keeps between calls: per block of particles and per collider, the totals
// and pushing contacts found there, so that blocks can run on any thread and still be summed in one
// fixed order (results independent of the thread count). Owned by the caller; grows once.
struct ContactWorkspace {
  std::vector<PosedCollider> posed;      // per collider, at the evaluation's time
  std::vector<ContactBlockWork> blocks;  // per block of particles
};

// Work on a block of particles run right after the block's contact forces, on the same thread while
// the block's state and forces are still in its cache: the solver's Euler update, which then needs
// no pass of its own. It may read and write only particles [begin, end) (the contact phase has
// finished with them; other blocks may still be in it) and returns the lowest particle it flags
// there, or -1.
struct ContactBlockFollowUp {
  std::int64_t (*run)(const void* context, std::int64_t begin, std::int64_t end) = nullptr;
  const void* context = nullptr;
};

// One evaluation of the contact phase (ContactModel::add_contact_forces), in three parts so that a
// caller may run the blocks inside a parallel region of its own (the spring kernel's, whose threads
// own the same runs of blocks, core/thread_blocks.hpp kPhaseBlock): the constructor poses every
// collider and readies the workspace (serial); run_block does one block of particles, on any
// thread, each block once, touching only that block's particles and record; finish sums the blocks'
// results in block order (serial). The result is the same whichever thread ran which block.
class ContactPass {
 public:
  // The arguments as for ContactModel::add_contact_forces; `keep_active`: record pushing contacts.
  // Every reference must outlive the pass.
  ContactPass(const ContactModel& contacts, const ClothModel& model, double t, double h,
              const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force,
              ContactWorkspace& workspace, ContactNormalScheme normal, bool keep_active,
              const ContactBlockFollowUp* follow_up);

  std::int64_t block_count() const { return blocks_; }
  // Block `block`'s contact forces, then the follow-up on its particles. Safe to call for different
  // blocks from several threads at once: each writes only its own particles and record.
  void run_block(std::int64_t block) const;
  // Once every block has run: each collider's totals (overwritten), the pushing contacts into
  // `active` when given (cleared first), and the lowest particle the follow-up flagged, else -1.
  std::int64_t finish(std::vector<ColliderContactTotals>& totals,
                      std::vector<ActiveContact>* active) const;

 private:
  void block_forces(std::int64_t block) const;
  void finish_contact(ContactBlockWork& record, std::size_t e, double fn) const;

  const ContactModel& contacts_;
  const ClothModel& model_;
  double t_, h_;  // s
  const Eigen::Matrix3Xd& x_;
  const Eigen::Matrix3Xd& v_;
  Eigen::Matrix3Xd& force_;
  ContactWorkspace& work_;
  ContactNormalScheme normal_scheme_;
  bool keep_active_;
  const ContactBlockFollowUp* follow_up_;
  int particles_;
  std::int64_t blocks_;
};

}  // namespace drapelab
