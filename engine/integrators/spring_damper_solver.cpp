// Our spring-damper cloth solver: the step around the integrator scheme (pins, constraints, the
// energy ledger, the health check) and the splits of a step for self-collision and adaptive
// substeps.
#include "drapelab/spring_damper_solver.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "drapelab/loop_threads.hpp"
#include "drapelab/stability.hpp"
#include "forces/spring_families.hpp"
#include "integrators/force_evaluator.hpp"
#include "integrators/phase_timer.hpp"
#include "integrators/schemes/scheme.hpp"
#include "integrators/shape_bound.hpp"
#include "self_collision/self_contact.hpp"

namespace drapelab {

SpringDamperSolver::SpringDamperSolver(std::string name, std::shared_ptr<const ClothModel> model,
                                       ClothState initial, SpringDamperSettings settings)
    : name_(std::move(name)),
      model_(std::move(model)),
      settings_(std::move(settings)),
      state_(std::move(initial)),
      forces_(std::make_unique<ForceEvaluator>(*model_, settings_, state_, stats_)),
      scheme_(make_scheme({*model_, settings_, state_, *forces_})),
      shape_bound_(std::make_unique<ShapeBoundWorkspace>()) {
  const int n = model_->particle_count();
  // What holds the cloth is fixed for the run: decide once what each step has to do for it.
  hard_constraints_ = settings_.constraints && settings_.constraints->has_hard();
  attachments_on_bodies_ = settings_.attachments && settings_.attachments->any_on_dynamic();
  for (int i = 0; i < n; ++i)
    if (model_->is_pinned(i)) state_.v.col(i).setZero();  // a pin holds its particle still
  check_settings();
  if (settings_.attachments)
    settings_.attachments->place(state_.time, state_.x, state_.v);  // ... or moves with its body
  if (hard_constraints_) projection_start_v_.resize(3, n);
  if (settings_.attachments)
    pins_at_start_.x.resize(3, static_cast<Eigen::Index>(settings_.attachments->list.size()));
  if (forces_->self_contact()) {
    step_start_x_.resize(3, n);
    step_start_v_.resize(3, n);
    piece_start_x_.resize(3, n);
  }
}

// Out of line: the private machinery's types are complete only here.
SpringDamperSolver::~SpringDamperSolver() = default;

void SpringDamperSolver::check_settings() const {
  const int n = model_->particle_count();
  if (settings_.attachments)
    for (const Attachment& a : settings_.attachments->list)
      if (a.particle >= n || !model_->is_pinned(a.particle))
        throw std::invalid_argument("attached particle " + std::to_string(a.particle) +
                                    " is not a pinned particle of the cloth");
  if (settings_.constraints)
    for (const DistanceConstraint& c : settings_.constraints->list)
      if (c.a < 0 || c.a >= n ||
          (c.b.kind == ConstraintEnd::Kind::particle && (c.b.particle < 0 || c.b.particle >= n)) ||
          (c.b.kind == ConstraintEnd::Kind::collider_point &&
           (c.b.collider < 0 ||
            c.b.collider >= static_cast<int>(settings_.constraints->colliders.size()))) ||
          (c.b.kind == ConstraintEnd::Kind::drag
               ? (!c.b.drag || c.b.drag->particle < 0 || c.b.drag->particle >= n)
               : !(c.length > 0.0 || (c.mode == ConstraintMode::soft && c.length == 0.0))))
        // a drag's spring has length 0, and so may any soft one (a seam's shut stitch)
        throw std::invalid_argument(
            "a distance constraint names a particle or collider the scene "
            "does not have, or has a length that is not positive");
  if (!settings_.adaptive_substeps) return;
  // Adaptive substeps follow symplectic Euler's exact damped stability condition (see
  // SpringDamperSettings) and bound the springs' stiffness.
  if (settings_.integrator != Integrator::symplectic_euler)
    throw std::invalid_argument(std::string("adaptive substeps need symplectic_euler, not ") +
                                integrator_name(settings_.integrator));
  if (model_->uses_continuum())
    throw std::invalid_argument(
        "adaptive substeps bound the springs' stiffness; the continuum model has no springs to "
        "bound (give the solver a fixed dt)");
  if (!(settings_.substep_safety > 0.0 && settings_.substep_safety <= 1.0))
    throw std::invalid_argument("substep_safety must be in (0, 1]");
}

const Eigen::Matrix3Xd& SpringDamperSolver::evaluate_forces(const Eigen::Matrix3Xd& x,
                                                            const Eigen::Matrix3Xd& v, double t,
                                                            double h) {
  return forces_->evaluate(x, v, t, h);
}

void SpringDamperSolver::step(double h) {
  if (status_ != SolverStatus::ok) return;
  // The results do not depend on the threads, so they follow the machine's load step by step.
  machine_load_.sample();
  kernels::share_machine(machine_load_);
  if (forces_->self_contact())
    step_without_tunnelling(h);
  else
    advance(h);
}

double SpringDamperSolver::largest_relative_motion(const Eigen::Matrix3Xd& from) const {
  const Eigen::Vector3d mean_motion = (state_.x - from).rowwise().mean();  // m
  double largest2 = 0.0;                                                   // m^2
  for (int i = 0; i < state_.x.cols(); ++i)
    largest2 = std::max(largest2, (state_.x.col(i) - from.col(i) - mean_motion).squaredNorm());
  return std::sqrt(largest2);
}

void SpringDamperSolver::step_without_tunnelling(double h) {
  // At most 2^10 pieces: beyond, the step goes on and is counted (unresolved_fast_steps).
  constexpr int kMostPieces = 1024;
  const double bound = 0.25 * forces_->self_contact()->thickness();  // m
  const Eigen::Vector3d mean_velocity = state_.v.rowwise().mean();
  const double fastest = (state_.v.colwise() - mean_velocity).colwise().norm().maxCoeff();  // m/s
  int pieces = static_cast<int>(
      std::clamp(std::ceil(fastest * h / bound), 1.0, static_cast<double>(kMostPieces)));
  step_start_x_ = state_.x;
  step_start_v_ = state_.v;
  const EnergyLedger start_ledger = ledger_;
  const double start_time = state_.time;
  const std::int64_t start_count = state_.step_count;
  for (;;) {
    bool within = true;
    const double piece = h / pieces;
    for (int k = 0; k < pieces && status_ == SolverStatus::ok; ++k) {
      piece_start_x_ = state_.x;
      advance(piece);
      if (largest_relative_motion(piece_start_x_) > bound) {
        within = false;
        break;
      }
    }
    if (within || status_ != SolverStatus::ok) break;
    if (pieces >= kMostPieces) {
      ++stats_.unresolved_fast_steps;
      break;
    }
    // Back to the step's start with twice the pieces; the schemes forget their history.
    state_.x = step_start_x_;
    state_.v = step_start_v_;
    state_.time = start_time;
    state_.step_count = start_count;
    ledger_ = start_ledger;
    scheme_->forget_history();
    forces_->set_split_state_current(false);
    pieces *= 2;
  }
  if (pieces > 1) ++stats_.split_steps;
  stats_.split_pieces_max = std::max(stats_.split_pieces_max, pieces);
  if (status_ == SolverStatus::ok)
    state_.time = start_time + h;  // the caller's clock, without the pieces' rounding
}

void SpringDamperSolver::advance(double h) {
  if (!settings_.adaptive_substeps) {
    single_step(h);
    return;
  }
  const double start_time = state_.time;
  const int substeps = substeps_for(h);
  const double substep = h / substeps;
  for (int k = 0; k < substeps && status_ == SolverStatus::ok; ++k) single_step(substep);
  if (status_ == SolverStatus::ok)
    state_.time = start_time + h;  // the caller's clock, without the substeps' rounding
  stats_.substeps_min =
      stats_.outer_steps == 0 ? substeps : std::min(stats_.substeps_min, substeps);
  stats_.substeps_max = std::max(stats_.substeps_max, substeps);
  ++stats_.outer_steps;
}

int SpringDamperSolver::substeps_for(double h) {
  PhaseTimer timer(stats_, StepPhase::step_bound);
  SpringFamilies* families = forces_->spring_families();
  const double target = settings_.substep_safety *
                        shape_stable_step(*model_, state_.x, settings_.air_damping, *shape_bound_,
                                          families ? &families->families() : nullptr);  // s
  // At most 10^7 substeps, as the scene format allows per frame (a NaN shape gives one: the health
  // check then stops the run).
  const double count = std::ceil(h / target);
  if (!(count >= 1.0)) return 1;
  return static_cast<int>(std::min(count, 1e7));
}

void SpringDamperSolver::single_step(double h) {
  const auto start = StepClock::now();
  const double force_seconds_before = force_phase_seconds();
  if (settings_.attachments) settings_.attachments->place(state_.time, state_.x, state_.v);
  record_pinned_start();
  // The Euler pair scans the new state as it writes it.
  std::optional<std::int64_t> scanned = scheme_->step(h);
  // The scheme moved the attached particles with their velocities at the step's start; they end
  // it where their colliders are.
  if (settings_.attachments) settings_.attachments->place(state_.time + h, state_.x, state_.v);
  scheme_->finish_step();
  if (attachments_on_bodies_) record_attachment_loads();
  account_step(h);
  if (hard_constraints_) {
    project_constraints(state_.time + h, h);
    scanned.reset();  // the projection moved particles after the Euler pass scanned them
  }
  // Only the Euler pair with colliders keeps the spring kernel's split state in step with the
  // update (and not when attached particles were placed or constraints projected after it).
  if (!scanned || !settings_.contacts || settings_.attachments)
    forces_->set_split_state_current(false);
  // Whatever the step spent outside the force phases is the integrator's own work.
  const double step_seconds = std::chrono::duration<double>(StepClock::now() - start).count();
  stats_.seconds[static_cast<int>(StepPhase::integrate)] +=
      step_seconds - (force_phase_seconds() - force_seconds_before);
  state_.time += h;
  ++state_.step_count;
  ++stats_.steps;
  PhaseTimer timer(stats_, StepPhase::health_check);
  check_health(h, scanned);
}

// Projection with velocity correction: the positions onto the constraints, then the velocities
// onto their tangent spaces (distance_constraints.hpp), the scheme told in between.
void SpringDamperSolver::project_constraints(double t, double h) {
  // The projection's impulses J = m (v_after - v_before) dissipate -J . (v_start + v_after) / 2,
  // with v_start = v_before - h f / m the velocity the particle brought into the step: a rope
  // that catches a particle moving at u takes m u^2 / 2, one already taut takes nothing (there
  // it only takes back, each step, the velocity the step's own forces gave).
  projection_start_v_ = state_.v;
  const DistanceConstraints& constraints = *settings_.constraints;
  ConstraintProjection result = constraints.project_positions(t, model_->inverse_mass, state_.x);
  if (result.moved) scheme_->positions_projected(h);
  constraints.project_velocities(t, h, model_->inverse_mass, state_.x, state_.v, result);
  stats_.constraint_position_sweeps_max =
      std::max(stats_.constraint_position_sweeps_max, result.position_sweeps);
  stats_.constraint_velocity_sweeps_max =
      std::max(stats_.constraint_velocity_sweeps_max, result.velocity_sweeps);
  if (!result.converged) ++stats_.constraint_unconverged_steps;
  const Eigen::Matrix3Xd& mass = forces_->masses().mass;  // kg per coordinate
  ledger_.dissipated +=
      0.5 *
      ((projection_start_v_ - state_.v).array() *
       (mass.array() * (projection_start_v_ + state_.v).array() - h * forces_->force().array()))
          .sum();
}

void SpringDamperSolver::record_attachment_loads() {
  const Attachments& attached = *settings_.attachments;
  const Eigen::Matrix3Xd& force = forces_->force();
  attachment_loads_.assign(attached.colliders.size(), ColliderForce{});
  for (std::size_t k = 0; k < attached.list.size(); ++k) {
    if (!attached.on_dynamic(k)) continue;
    const int i = attached.list[k].particle;
    ColliderForce& load = attachment_loads_[static_cast<std::size_t>(attached.list[k].collider)];
    load.force += force.col(i);
    load.torque += Eigen::Vector3d(state_.x.col(i)).cross(Eigen::Vector3d(force.col(i)));
  }
}

void SpringDamperSolver::record_pinned_start() {
  if (!settings_.attachments) return;
  const std::vector<Attachment>& list = settings_.attachments->list;
  pins_at_start_.kinetic_energy = 0.0;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const int i = list[k].particle;
    pins_at_start_.x.col(static_cast<Eigen::Index>(k)) = state_.x.col(i);
    pins_at_start_.kinetic_energy += 0.5 * model_->mass[i] * state_.v.col(i).squaredNorm();
  }
}

void SpringDamperSolver::account_step(double h) {
  ledger_.add(forces_->power(), h);
  if (!settings_.attachments) return;
  // A pin moved by its collider takes whatever force holds it on its path: the collider's work
  // is the pin's change of kinetic energy less the work of the cloth's own forces on it (the
  // last evaluation's), - sum f . dx.
  const std::vector<Attachment>& list = settings_.attachments->list;
  const Eigen::Matrix3Xd& force = forces_->force();
  const PinnedStart& pins = pins_at_start_;
  double work = -pins.kinetic_energy;  // J
  for (std::size_t k = 0; k < list.size(); ++k) {
    const int i = list[k].particle;
    work += 0.5 * model_->mass[i] * state_.v.col(i).squaredNorm() -
            force.col(i).dot(state_.x.col(i) - pins.x.col(static_cast<Eigen::Index>(k)));
  }
  ledger_.external_work += work;
}

}  // namespace drapelab
