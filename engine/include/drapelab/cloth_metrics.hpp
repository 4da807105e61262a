// Per-frame metrics (docs/metrics.md, "Per frame (`metrics.csv`)"), computed by one function from
// (model, state) so every solver is measured the same way, never from a solver's private data.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"

namespace drapelab {

struct ClothMetrics {
  double kinetic_energy = 0.0;  // J, sum 1/2 m |v|^2
  double gravity_energy = 0.0;  // J, -sum m g.x
  double spring_energy = 0.0;   // J, sum 1/2 k (|d| - L)^2 over every spring kind
  double max_stretch = 0.0;     // max over stretch springs of |d|/L - 1
  double mean_stretch = 0.0;    // mean over stretch springs of |d|/L - 1
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // m, mass-weighted
  double lowest_y = 0.0;                               // m
  double projected_area = 0.0;  // m^2, union of triangles projected along gravity
  // Need colliders or a drape support; empty until a scene provides them.
  std::optional<double> min_clearance;    // m
  std::optional<double> max_penetration;  // m
  std::optional<int> contact_count;
  std::optional<double> drape_coefficient;
  std::optional<int> drape_nodes;
  // The mesh audits of the run's frame loop (self_intersections.hpp, triangle_penetration.hpp);
  // empty until it measures them, triangle_penetration also when the scene has no colliders.
  std::optional<int> self_intersections;       // edges crossing a non-adjacent triangle
  std::optional<double> triangle_penetration;  // m, deepest collider reach into a triangle
  // The hard and rope distance constraints' largest relative length error
  // (distance_constraints.hpp); empty without such constraints.
  std::optional<double> constraint_error;
  // The energy audit (docs/metrics.md, "Energy audit"), filled in by the run's frame loop (J):
  // elastic_energy is the springs' (spring_energy) or, for our continuum solver, the membranes' and
  // hinges'; contact_energy the penalty springs' 1/2 k d^2 (empty without colliders);
  // constraint_energy the soft constraints' and drags' (empty without them); self_contact_energy
  // the self-contacts' penalty springs' (our solver with self-collision only); total_energy
  // kinetic + gravity + elastic + contact + constraint + self-contact. The balance (our solver
  // only, energy_ledger.hpp): dissipated and external_work since t = 0, and energy_error =
  // total_energy + dissipated - external_work minus its value at t = 0.
  std::optional<double> elastic_energy;
  std::optional<double> contact_energy;
  std::optional<double> constraint_energy;
  std::optional<double> self_contact_energy;
  std::optional<double> total_energy;
  std::optional<double> external_work;
  std::optional<double> dissipated;
  std::optional<double> energy_error;
};

ClothMetrics compute_cloth_metrics(const ClothModel& model, const ClothState& state,
                                   const Eigen::Vector3d& gravity);

}  // namespace drapelab
