// Self-contact as offset geometric contact (Chen et al., "Offset Geometric Contact", 2025), for
// vbd's solve. One detection at a state finds
//   - the contacts: every pair of primitives closer than the offset r (the self-collision
//     thickness) whose closest point lies in the feasible region of the feature it is on (a face's
//     inside, an edge nearest on every triangle that has it, a corner nearest on every triangle at
//     it; core/offset_barrier.hpp gives their energy), so neighbouring parts of a flat sheet are
//     never contacts however close their particles are;
//   - each particle's conservative bound: 0.45 times the smallest distance from any primitive it
//     belongs to (itself, its edges, its triangles) to any primitive it does not touch, up to the
//     search reach. While every particle stays within its bound of where the detection saw it, no
//     two primitives can meet: each pair's gap shrinks by at most the sum of two bounds, 0.9 of it.
// vbd truncates every move at the bound and detects again where moves were truncated, so the cloth
// never crosses itself at any step, whatever its stiffness and speed.
//
// Both phases split their work in fixed blocks of particles and of grid buckets (core/
// thread_blocks.hpp) and merge the blocks' lists in block order, and each distance bound is a
// minimum: the result is the same for any number of threads.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "core/offset_barrier.hpp"
#include "core/offset_contact_arrays.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/self_collision.hpp"
#include "self_collision/cloth_topology.hpp"
#include "self_collision/self_contact.hpp"
#include "self_collision/spatial_hash.hpp"

namespace drapelab {

// The fraction of its distance to the nearest primitive a particle may move between two detections.
inline constexpr double kConservativeBoundFraction = 0.45;

class OffsetContacts {
 public:
  OffsetContacts(const ClothModel& model, const SelfCollisionSettings& settings);

  // Finds the contacts and the bounds at x. The bounds are centred on x + shift: a translation
  // (m) every particle shares moves no part of the cloth towards another.
  void detect(const Eigen::Matrix3Xd& x, const Eigen::Vector3d& shift);
  // Moves the bounds' centres to x + shift without detecting again (the same contacts).
  void recentre(const Eigen::Matrix3Xd& x, const Eigen::Vector3d& shift);

  // The contacts and bounds as the sweeps read them.
  OffsetContactArrays arrays() const;
  // The contacts' totals at the step's end x, from the step's start `start`, over h s, with
  // friction's stick-slip boundary at friction_velocity (m/s) times h.
  void record_end_state(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& start, double h,
                        double friction_velocity);
  void count_truncations(std::int64_t truncated) { stats_.truncations += truncated; }
  const OffsetContactTotals& last_totals() const { return totals_; }
  double detection_seconds() const { return detection_seconds_; }  // s, summed

  double offset() const { return barrier_.offset; }  // m
  double reach() const { return reach_; }            // m
  const OffsetBarrier& barrier() const { return barrier_; }
  const SelfContactStats& stats() const { return stats_; }
  const std::vector<double>& bounds() const { return bound_; }  // m per particle
  std::int64_t contact_count() const { return static_cast<std::int64_t>(kind_.size()); }

 private:
  // A contact found by one block: its kind, its particles (unused: -1) and its distance (m).
  struct Found {
    SelfContactKind kind = SelfContactKind::point_face;
    std::array<std::int32_t, 4> particle{-1, -1, -1, -1};
    double distance = 0.0;
    auto operator<=>(const Found&) const = default;
  };
  void find_point_triangle(const Eigen::Matrix3Xd& x);
  void find_edge_edge(const Eigen::Matrix3Xd& x);
  void store_contacts();

  SelfCollisionSettings settings_;
  OffsetBarrier barrier_;
  double reach_ = 0.0;  // m: how far a detection looks for the nearest primitive
  ClothTopology topology_;
  SpatialGrid grid_;
  std::vector<Box> boxes_;
  std::vector<double> edge_reach_;  // m per edge: how far its edge-pair search looks
  // Per block, kept from one detection to the next (each block clears its own): the faces found,
  // the edge pairs found, and the edges and corners to deduplicate.
  std::vector<std::vector<Found>> block_found_;
  std::vector<std::vector<Found>> block_edge_found_;
  std::vector<std::vector<Found>> block_shared_;
  std::vector<Found> shared_;
  // Per particle: the nearest untouched primitive (m), the bound (m) and its centre (m).
  std::vector<double> nearest_;
  std::vector<double> bound_;
  Eigen::Matrix3Xd anchor_;
  // The contacts, as the sweeps read them.
  std::vector<SelfContactKind> kind_;
  std::vector<std::int32_t> particle_;  // 4 per contact
  std::vector<double> normal_force_;    // N per contact: -g' at the detection (friction's load)
  std::vector<std::int32_t> row_offsets_, row_contact_, row_slot_;
  std::vector<std::int32_t> fill_;  // scratch: each particle's next row
  SelfContactStats stats_;
  OffsetContactTotals totals_;
  double detection_seconds_ = 0.0;
};

}  // namespace drapelab
