// Our spring-damper cloth as a Solver. A step reads:
//   place pins -> integrator scheme's step -> place pins -> finish -> project constraints -> check
// The scheme (integrators/schemes/) evaluates the forces as often as it needs; each evaluation
// runs the force terms in their named order (integrators/force_evaluator.hpp), each timed into
// StepStats under its phase:
//   body forces and springs -> self-contacts -> collider edges -> soft constraints -> air ->
//   collider contacts.
// Self-collision splits a step into pieces small enough that no layer passes another; adaptive
// substeps split it into the substeps the cloth's current shape needs. The explicit step allocates
// nothing after the first: every buffer is sized when the solver is built, except the contact
// phase's per-block lists and each thread's FCL buffer, sized by the first step.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/implicit_euler.hpp"
#include "drapelab/machine_load.hpp"
#include "drapelab/solver.hpp"
#include "drapelab/spring_damper_settings.hpp"
#include "drapelab/step_stats.hpp"
#include "drapelab/vertex_block_descent.hpp"

namespace drapelab {

// The step's private machinery (engine/integrators), held by pointer.
class ForceEvaluator;
class IntegratorScheme;
class FamilyImplicitSystem;
class SelfContact;
struct SelfContactStats;
struct ShapeBoundWorkspace;

// The pins carried by colliders at a step's start, for the work the colliders do through them.
struct PinnedStart {
  double kinetic_energy = 0.0;  // J
  Eigen::Matrix3Xd x;           // m, one column per attachment
};

class SpringDamperSolver final : public Solver {
 public:
  SpringDamperSolver(std::string name, std::shared_ptr<const ClothModel> model, ClothState initial,
                     SpringDamperSettings settings);
  ~SpringDamperSolver() override;

  void step(double h) override;
  const ClothState& state() const override { return state_; }
  const std::string& name() const override { return name_; }
  SolverType type() const override { return SolverType::spring_damper; }
  SolverStatus status() const override { return status_; }
  const std::string& message() const override { return message_; }
  std::vector<ColliderForce> collider_forces() const override;
  std::vector<std::pair<std::string, double>> phase_seconds() const override;
  std::vector<std::pair<std::string, double>> counters() const override;
  std::optional<EnergyLedger> energy_ledger() const override { return ledger_; }
  std::optional<double> self_contact_energy() const override;

  const ClothModel& model() const { return *model_; }
  const SpringDamperSettings& settings() const { return settings_; }
  const StepStats& stats() const { return stats_; }

  // Total force on every particle (N, 3 x N) at (x, v) and time t (s): gravity and air drag, then
  // springs, then contacts, with friction sized for a step of h (s). Public so tests can check it;
  // writes only the solver's own buffers.
  const Eigen::Matrix3Xd& evaluate_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                                          double t, double h);
  // The force terms each evaluation runs, in their order (integrators/force_evaluator.hpp).
  std::vector<std::string> force_terms() const;
  // Self-collision's machinery and statistics (null when off).
  const SelfContact* self_contact() const;
  // Self-collision's counters, from the penalty self-contacts or vbd's offset contacts (null
  // without self-collision).
  const SelfContactStats* self_contact_stats() const;
  // What each collider did in the last force evaluation (empty without colliders).
  const std::vector<ColliderContactTotals>& contact_totals() const;
  // The implicit solve: the assembled sparse system (a cloth without spring families, or
  // fast_springs off) or the matrix-free one on spring families; both null unless the integrator is
  // implicit_euler.
  const ImplicitEulerSystem* implicit_system() const;
  const FamilyImplicitSystem* family_implicit_system() const;
  // The statistics of whichever implicit solve runs (null unless the integrator is implicit_euler).
  const ImplicitSolveStats* implicit_stats() const;
  // Vertex block descent's statistics (null unless the integrator is vbd).
  const VbdStats* vbd_stats() const;
  // Whether the spring phase runs the spring-family fast path.
  bool uses_fast_springs() const;

 private:
  // Refuses settings the solver cannot run (std::invalid_argument).
  void check_settings() const;
  // step(h) without self-collision: one integrator step, or the adaptive substeps.
  void advance(double h);
  // step(h) with self-collision: advance() in as many equal pieces as keep every particle's motion
  // relative to the cloth's mean within a quarter of the thickness (so two particles close by at
  // most half of it), predicted from the velocities and checked after each piece; a piece that
  // breaks it sends the step back to its start with twice the pieces.
  void step_without_tunnelling(double h);
  // The largest |x_i - from_i - mean(x - from)| over particles (m).
  double largest_relative_motion(const Eigen::Matrix3Xd& from) const;
  // One integrator step of h (s): pins, the scheme's step, the step's bookkeeping, the health
  // check.
  void single_step(double h);
  // How many substeps step(h) takes when adaptive: h over the shape's stable step times the safety.
  int substeps_for(double h);
  // The hard and rope constraints' projection at the step's end (time t, s), and the energy its
  // impulses take.
  void project_constraints(double t, double h);
  // The loads of the particles attached to dynamic colliders: each particle's force of the step's
  // last evaluation, which its body supplies the reaction to, so it pushes on the body with it.
  void record_attachment_loads();
  double force_phase_seconds() const;
  // The adaptive substeps' counters, or the scheme's.
  std::vector<std::pair<std::string, double>> scheme_counters() const;
  // Stops the solver when a particle is not finite or runs away (health_report.cpp). `scanned`:
  // the step's own scan of the new state, if it made one.
  void check_health(double h, std::optional<std::int64_t> scanned);
  // The energy ledger's share of one step of h (s): the power of the step's last force evaluation
  // times h, and the work of the pins carried by moving colliders from pins_at_start_
  // (energy_ledger.hpp).
  void account_step(double h);
  // Records the pins on colliders at the step's start into pins_at_start_.
  void record_pinned_start();

  std::string name_;
  std::shared_ptr<const ClothModel> model_;
  SpringDamperSettings settings_;
  ClothState state_;
  StepStats stats_;
  std::unique_ptr<ForceEvaluator> forces_;    // every force term, in order
  std::unique_ptr<IntegratorScheme> scheme_;  // settings_.integrator's
  std::unique_ptr<ShapeBoundWorkspace>
      shape_bound_;  // adaptive substeps: each particle's springs, for the bound
  // Self-collision: the state a step restarts from (m, m/s) and the start of its piece (m).
  Eigen::Matrix3Xd step_start_x_, step_start_v_, piece_start_x_;
  Eigen::Matrix3Xd projection_start_v_;  // m/s: hard constraints, the velocity before projection
  PinnedStart pins_at_start_;            // the pins on colliders at the step's start
  std::vector<ColliderForce> attachment_loads_;  // per collider: force (N), moment (N*m)
  bool hard_constraints_ = false;                // settings_.constraints has hard or rope ones
  bool attachments_on_bodies_ = false;           // a pin is attached to a dynamic collider
  EnergyLedger ledger_;                          // energy_ledger.hpp
  SolverStatus status_ = SolverStatus::ok;
  // The other processes' use of the cores, which sets the loops' threads before each step.
  MachineLoad machine_load_;
  std::string message_;
};

}  // namespace drapelab
