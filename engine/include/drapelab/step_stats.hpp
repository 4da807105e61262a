// What our solver's step spends its time on and how often it split or capped a step: the phases
// each force term and the integrator are timed under, and the step's counters.
#pragma once

#include <array>
#include <cstdint>

namespace drapelab {

// Wall time spent in each phase, accumulated over all steps (seconds).
// step_bound: the adaptive substeps' shape bound, once per step(h). The force terms between the
// springs and the collider contacts have a phase each: self_contacts (the cloth against itself),
// collider_edges (colliders' edges on the cloth's edges and triangles), soft_constraints (soft
// distance constraints and drags) and air.
enum class StepPhase {
  body_forces,
  springs,
  contacts,
  integrate,
  health_check,
  step_bound,
  self_contacts,
  collider_edges,
  soft_constraints,
  air,
  count
};
const char* step_phase_name(StepPhase phase);

struct StepStats {
  std::array<double, static_cast<int>(StepPhase::count)> seconds{};
  std::int64_t steps = 0;  // integrator steps (substeps when adaptive)
  // Adaptive substeps: calls of step(h), and the fewest and most substeps one of them took.
  std::int64_t outer_steps = 0;
  int substeps_min = 0;
  int substeps_max = 0;
  // Self-collision: steps split so that no particle moves more than half the thickness relative
  // to another, the most pieces one step needed, and steps still above that bound at the finest
  // split allowed (each may let a layer through; summary.json reports the count).
  std::int64_t split_steps = 0;
  int split_pieces_max = 0;
  std::int64_t unresolved_fast_steps = 0;
  // Hard and rope constraints: the most Gauss-Seidel sweeps one step's projection took (positions,
  // velocities), and the steps whose projection reached the cap with a length still outside its
  // tolerance.
  int constraint_position_sweeps_max = 0;
  int constraint_velocity_sweeps_max = 0;
  std::int64_t constraint_unconverged_steps = 0;
};

}  // namespace drapelab
