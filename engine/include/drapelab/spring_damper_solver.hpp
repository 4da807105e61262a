// Our spring-damper cloth: forces from gravity, damped springs, air damping, self-collision and
// penalty contact with friction, advanced by any integrator of integrators.hpp. A step is a visible
// list of phases, each timed into StepStats:
//   body forces (gravity and air drag) -> springs -> self-contacts -> contacts (collider edges on
//   the cloth's edges and triangles, then particles) -> integrate (pins held) -> health check.
// Multi-stage schemes run the force phases once per stage; "integrate" is the rest of the step
// (stage arithmetic, and for implicit Euler the assembly and conjugate-gradient solve). The Euler
// pair with colliders updates each block of particles inside the contact phase, as soon as its
// forces are final (the same bits as a pass of its own), so there the update's time counts in
// "contacts". The explicit step allocates nothing after the first: every buffer is sized when the
// solver is built, except the contact phase's per-block lists and each thread's FCL buffer, sized
// by the first step.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "drapelab/air.hpp"
#include "drapelab/attachments.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/distance_constraints.hpp"
#include "drapelab/implicit_euler.hpp"
#include "drapelab/integrators.hpp"
#include "drapelab/self_collision.hpp"
#include "drapelab/solver.hpp"
#include "drapelab/stability.hpp"
#include "drapelab/vertex_block_descent.hpp"
#include "drapelab/weighted_contact.hpp"

namespace drapelab {

// The step's private machinery (engine/forces, engine/integrators, engine/contact), held by
// pointer.
class SpringFamilies;
class FamilyImplicitSystem;
struct ShapeBoundWorkspace;
struct ContactWorkspace;
struct ContactBlockFollowUp;
class SelfContact;
class EdgeContact;
class VertexBlockDescent;

struct SpringDamperSettings {
  Integrator integrator = Integrator::symplectic_euler;
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};  // m/s^2
  double air_damping = 0.0;                  // 1/s: force -air_damping * m * v
  double max_speed = 1000.0;                 // m/s: a faster particle means the run has blown up
  std::shared_ptr<const ContactModel> contacts;  // colliders and penalty parameters; none when null
  ImplicitSolveSettings implicit;  // implicit_euler only: CG tolerance and iteration cap
  VbdSettings vbd;                 // vbd only: sweeps per step and their acceleration
  bool fast_springs =
      true;  // the spring-family fast path when the springs allow (spring_families.hpp)
  // Adaptive substeps: each step(h) is split into as many equal substeps as the current shape's
  // stable step needs (stability.hpp shape_rate_bounds), at `substep_safety` times that step.
  // Symplectic Euler only, the one scheme whose damped stability condition h^2 w^2 + 2 h c < 4 is
  // exact (the bound is tight enough for the others' differences to show: Verlet, whose damping
  // lags a step, diverged at 1.4 times its Gershgorin step on a sheet without shear springs); the
  // constructor refuses the others.
  bool adaptive_substeps = false;
  double substep_safety = 0.9;
  // The cloth against itself (self_collision.hpp). With it on, a step in which one particle would
  // move more than half the thickness relative to another is split into smaller equal steps, so
  // that no layer passes through another between two force evaluations (step_without_tunnelling).
  SelfCollisionSettings self_collision;
  // The colliders' sharp edges and corners also push on the cloth's edges and triangles
  // (contact/edge_contact.hpp), not only on its particles.
  bool collider_edges = false;
  // Pinned particles carried by colliders (cloth.pins[].attach): placed on their colliders at the
  // start and the end of every step (and every substep), so each step's schemes move them with
  // the colliders' velocities in between. They must be pinned in the model. None when null.
  std::shared_ptr<const Attachments> attachments;
  // Distance constraints (distance_constraints.hpp): the soft ones are forces of every evaluation
  // (couplings of the implicit Euler and vbd solves); the hard and rope ones are projected at the
  // end of every step (and substep), after the attached particles are placed. None when null.
  std::shared_ptr<const DistanceConstraints> constraints;
  // Aerodynamic drag and lift on the triangles (air.hpp), an explicit force of every evaluation
  // (implicit Euler and vbd take it at the step's start: its rate rho C_d A |u_n| / m is far below
  // their steps' limits for cloth in air).
  AirSettings air;
};

// Wall time spent in each phase, accumulated over all steps (seconds).
// step_bound: the adaptive substeps' shape bound, once per step(h). self_contacts: the cloth
// against itself, between the springs and the collider contacts.
enum class StepPhase {
  body_forces,
  springs,
  contacts,
  integrate,
  health_check,
  step_bound,
  self_contacts,
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
  // Self-collision's machinery and statistics (null when off).
  const SelfContact* self_contact() const { return self_contact_.get(); }
  // What each collider did in the last force evaluation (empty without colliders).
  const std::vector<ColliderContactTotals>& contact_totals() const { return contact_totals_; }
  // The implicit solve: the assembled sparse system (a cloth without spring families, or
  // fast_springs off) or the matrix-free one on spring families; both null unless the integrator is
  // implicit_euler.
  const ImplicitEulerSystem* implicit_system() const { return implicit_.get(); }
  const FamilyImplicitSystem* family_implicit_system() const { return family_implicit_.get(); }
  // The statistics of whichever implicit solve runs (null unless the integrator is implicit_euler).
  const ImplicitSolveStats* implicit_stats() const;
  // Vertex block descent's statistics (null unless the integrator is vbd).
  const VbdStats* vbd_stats() const;
  // Whether the spring phase runs the spring-family fast path.
  bool uses_fast_springs() const { return spring_families_ != nullptr; }

 private:
  // step(h) without self-collision: one integrator step, or the adaptive substeps.
  void advance(double h);
  // step(h) with self-collision: advance() in as many equal pieces as keep every particle's motion
  // relative to the cloth's mean within a quarter of the thickness (so two particles close by at
  // most half of it), predicted from the velocities and checked after each piece; a piece that
  // breaks it sends the step back to its start with twice the pieces.
  void step_without_tunnelling(double h);
  // The largest |x_i - from_i - mean(x - from)| over particles (m).
  double largest_relative_motion(const Eigen::Matrix3Xd& from) const;
  // One integrator step of h (s): the scheme's update, the step's bookkeeping and the health check.
  void single_step(double h);
  // How many substeps step(h) takes when adaptive: h over the shape's stable step times the safety.
  int substeps_for(double h);
  // One step of each scheme (explicit_schemes.cpp, except the Euler pair and implicit Euler here).
  // The Euler pair returns the health scan of the new state (first_unhealthy_particle).
  std::int64_t euler_step(double h);
  void midpoint_step(double h);
  void rk4_step(double h);
  void verlet_step(double h);
  void leapfrog_step(double h);
  void implicit_euler_step(double h);
  void vbd_step(double h);
  // Adds the collider edges' contacts to the particle contacts' totals of the same evaluation.
  void add_edge_contact_totals();
  // The force phases on their own: gravity, air drag and springs overwrite force_; contacts add to
  // it (with `follow_up` run on each block of particles once its force is final; returns its flag).
  void set_body_and_spring_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v);
  // The contacts between particles: self-collision's forces, then the collider edges', then the
  // soft constraints' (each a no-op when off), added to force_ before the particle contacts.
  void add_pair_contact_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, double t,
                               double h);
  // Whether forces act between the springs and the particle contacts (then the two cannot share
  // one parallel region).
  bool has_pair_contacts() const {
    return self_contact_ || edge_contact_ || soft_constraints_ || settings_.air.enabled;
  }
  // The hard and rope constraints' projection at the step's end (time t, s), with the scheme's
  // velocity bookkeeping (Verlet's history, leapfrog's stored force).
  void project_constraints(double t, double h);
  // The loads of the particles attached to dynamic colliders: each particle's force of the step's
  // last evaluation (for vbd, gravity and the springs at the end state),
  // which its body supplies the reaction to, so it pushes on the body with it.
  void record_attachment_loads();
  std::int64_t add_contact_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, double t,
                                  double h, const ContactBlockFollowUp* follow_up);
  // How the integrator takes the penalty normal force: at the step's end for symplectic Euler.
  ContactNormalScheme contact_normal_scheme() const;
  // Both at the solver's state in one parallel region (the spring fast path with colliders): each
  // thread runs the contact blocks of its own particles as soon as their spring forces are final.
  std::int64_t spring_and_contact_forces_together(double h, const ContactBlockFollowUp& follow_up);
  // a = f / m for the force just evaluated (zero on pinned particles).
  const Eigen::Matrix3Xd& acceleration_of_force(Eigen::Matrix3Xd& into) const;
  double force_phase_seconds() const;
  // The integrator's own counters (adaptive substeps or the implicit solve), without
  // self-collision.
  std::vector<std::pair<std::string, double>> scheme_counters() const;
  // `scanned`: the step's own scan of the new state, if it made one.
  void check_health(double h, std::optional<std::int64_t> scanned);
  // The energy ledger's share of one step of h (s): the power of the step's last force evaluation
  // times h, and the work of the pins carried by moving colliders (energy_ledger.hpp).
  void account_step(double h, const PinnedStart& pins);
  // The pins on colliders at the step's start: their kinetic energy (J) and positions (m).
  PinnedStart pinned_start() const;
  // The power air damping takes at velocities v (W), c sum m |v|^2.
  double air_damping_power(const Eigen::Matrix3Xd& v) const;
  // The kinetic energy of all particles (J).
  double kinetic_energy() const;

  std::string name_;
  std::shared_ptr<const ClothModel> model_;
  SpringDamperSettings settings_;
  ClothState state_;
  Eigen::Matrix3Xd force_;  // N, the step's scratch buffer
  // Per coordinate, packed like force_, so the per-particle passes run over unit-stride arrays:
  Eigen::Matrix3Xd coordinate_mass_;          // kg: m_i in each of particle i's three rows
  Eigen::Matrix3Xd coordinate_inverse_mass_;  // 1/kg: 1/m_i, 0 for a pinned particle
  Eigen::Matrix3Xd weight_;                   // N: m_i g
  // Stage buffers of the multi-stage and two-level schemes (3 x N; empty when the scheme needs
  // none):
  Eigen::Matrix3Xd stage_x_, stage_v_;  // m, m/s: the state a stage evaluates the force at
  Eigen::Matrix3Xd sum_x_, sum_v_;      // RK4's weighted sums of stage slopes (m/s, m/s^2)
  Eigen::Matrix3Xd acceleration_;       // m/s^2: the last stage's, or the two-level schemes' a(n)
  Eigen::Matrix3Xd previous_x_;         // m: Verlet's x(n-1)
  double two_level_step_ = 0.0;         // s: the h Verlet/leapfrog history holds; 0 = start afresh
  std::unique_ptr<ImplicitEulerSystem> implicit_;
  std::unique_ptr<FamilyImplicitSystem> family_implicit_;
  std::unique_ptr<SpringFamilies> spring_families_;  // null: the plain edge-list loop
  std::unique_ptr<VertexBlockDescent> vbd_;          // null unless the integrator is vbd
  // cloth.model: continuum: each element's force before the per-particle sums (9 per triangle, 12
  // per hinge, N); empty for springs.
  std::vector<double> continuum_element_force_;
  // The fast path's unit-stride copy of the state equals state_.x and state_.v: set by the Euler
  // update with colliders (which splits each block as it updates it) and by a force evaluation at
  // the solver's state; cleared by every other change of the state.
  bool split_state_is_current_ = false;
  std::vector<ActiveContact>
      active_contacts_;  // implicit Euler: contacts of the start-of-step force
  std::vector<WeightedContact> active_couplings_;  // implicit Euler: contacts between particles
  std::unique_ptr<SelfContact> self_contact_;      // null when self-collision is off
  std::unique_ptr<EdgeContact> edge_contact_;      // null without collider edges
  // Self-collision: the state a step restarts from (m, m/s) and the start of its piece (m).
  Eigen::Matrix3Xd step_start_x_, step_start_v_, piece_start_x_;
  Eigen::Matrix3Xd projection_start_v_;  // m/s: hard constraints, the velocity before projection
  std::vector<ColliderContactTotals> contact_totals_;
  std::vector<ColliderForce> attachment_loads_;  // per collider: force (N), moment (N*m)
  std::vector<ColliderForce> constraint_loads_;  // soft constraints' reactions, per collider
  bool soft_constraints_ = false;                // settings_.constraints has soft ones
  bool hard_constraints_ = false;                // ... hard or rope ones, projected every step
  bool constraints_on_bodies_ = false;           // ... some ending on a dynamic collider
  bool attachments_on_bodies_ = false;           // a pin is attached to a dynamic collider
  Wind wind_;                                    // the air's wind over time (settings_.air)
  std::unique_ptr<ContactWorkspace> contact_workspace_;  // the contact phase's per-block results
  std::unique_ptr<ShapeBoundWorkspace>
      shape_bound_;  // adaptive substeps: each particle's springs, for the bound
  StepStats stats_;
  // The energy ledger (energy_ledger.hpp): its running sums, and the power of the last force
  // evaluation's phases (W): gravity and springs with air damping, and the forces between
  // particles (self-contacts, soft constraints, the air field). The collider contacts' power is in
  // contact_totals_.
  EnergyLedger ledger_;
  PowerSplit body_and_spring_power_, pair_power_;
  SolverStatus status_ = SolverStatus::ok;
  std::string message_;
};

}  // namespace drapelab
