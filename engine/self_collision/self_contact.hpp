// Self-collision of our cloth as a force phase (self_collision.hpp gives the model).
//
// Broad phase: candidate pairs (a particle and a triangle it is not a corner of, two edges without
// a shared particle) within the thickness plus a margin, found by a uniform grid (spatial_hash.hpp)
// and kept while no particle has moved more than half the margin relative to the cloth's mean
// motion since they were found: two parts can then not have closed the margin between them, so
// no pair within the thickness is missed. Narrow phase, every force evaluation: the closest points
// of each candidate. A particle nearest a triangle's inside and two edges nearest in their insides
// are contacts as found; a particle nearest a triangle's edge or corner is a particle-edge or
// particle-particle contact, counted once however many triangles share that edge or corner, and
// only when that edge or corner is the nearest part of every triangle that has it (else a face
// next to it is nearer and holds the contact).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "core/weighted_contact_pass.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/self_collision.hpp"
#include "drapelab/weighted_contact.hpp"
#include "self_collision/cloth_topology.hpp"
#include "self_collision/spatial_hash.hpp"

namespace drapelab {

// What self-collision did, summed over force evaluations.
struct SelfContactStats {
  std::int64_t evaluations = 0;
  std::int64_t rebuilds = 0;         // broad-phase searches
  std::int64_t candidates = 0;       // candidate pairs of the last search
  std::int64_t contacts_last = 0;    // pushing contacts of the last evaluation
  std::int64_t contacts_total = 0;   // summed over evaluations
  double normal_force_last = 0.0;    // N, sum of |fn| of the last evaluation
  double friction_force_last = 0.0;  // N, sum of |friction| of the last evaluation
  // The last evaluation's springs' energy, sum of k (thickness - d)^2 / 2 (J), and the power its
  // dampers and friction took (W, energy_ledger.hpp).
  double spring_energy_last = 0.0;
  double dissipated_power_last = 0.0;
  // vbd's offset contacts: moves cut short at a particle's conservative bound, summed.
  std::int64_t truncations = 0;
};

class SelfContact {
 public:
  SelfContact(const ClothModel& model, const SelfCollisionSettings& settings);

  // Adds the self-contact penalty and friction forces (N) for the state (x, v) to `force`, which
  // must already hold every other force but the collider contacts (friction is sized for a step of
  // h s from it). `inverse_mass` 1/kg per particle. Pushing contacts are appended to `active` when
  // given.
  void add_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, double h,
                  const Eigen::VectorXd& inverse_mass, Eigen::Matrix3Xd& force,
                  std::vector<WeightedContact>* active);

  double thickness() const { return thickness_; }  // m
  double margin() const { return margin_; }        // m
  const SelfContactStats& stats() const { return stats_; }
  const std::vector<std::array<std::int32_t, 2>>& edges() const { return topology_.edges(); }

 private:
  // A particle nearest a triangle's edge (c >= 0: particle a, edge b-c) or corner (c < 0: a, b).
  struct SharedFeature {
    int a = 0, b = 0, c = -1;
    auto operator<=>(const SharedFeature&) const = default;
  };

  bool needs_search(const Eigen::Matrix3Xd& x) const;
  void search(const Eigen::Matrix3Xd& x);
  // The contacts at x, each with its normal and depth (pair_penalty.hpp): along the line between
  // its two sides, or the normal found with it where the sides meet.
  void find_contacts(const Eigen::Matrix3Xd& x);
  const ClothModel& model_;
  SelfCollisionSettings settings_;
  double thickness_ = 0.0;  // m
  double margin_ = 0.0;     // m
  // Pairs joined by a mesh edge are never a contact: their spring holds them apart. Pairs a ring or
  // two apart stay candidates: a soft cloth crumpled in a heap folds sharply enough for them to
  // meet (excluding them let layers cross there).
  ClothTopology topology_;
  // Broad phase.
  SpatialGrid grid_;
  std::vector<Box> boxes_;
  Eigen::Matrix3Xd searched_x_;  // m, the positions of the last search
  bool searched_ = false;
  std::vector<std::array<std::int32_t, 2>> point_triangle_;  // (particle, triangle)
  std::vector<std::array<std::int32_t, 2>> edge_edge_;       // (edge, edge)
  // Narrow phase, per evaluation.
  std::vector<WeightedContactPoint> contacts_;
  std::vector<SharedFeature> shared_;
  WeightedContactPass pass_;
  // One group: every self contact.
  std::vector<WeightedContactTotals> totals_ = std::vector<WeightedContactTotals>(1);
  SelfContactStats stats_;
};

}  // namespace drapelab
