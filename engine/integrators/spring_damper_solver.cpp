// Our spring-damper cloth solver: the step as a list of named, timed phases.
#include "drapelab/spring_damper_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "contact/contact_pass.hpp"
#include "contact/edge_contact.hpp"
#include "drapelab/stability.hpp"
#include "forces/body_force_loops.hpp"
#include "forces/continuum_arrays.hpp"
#include "forces/forces.hpp"
#include "forces/spring_families.hpp"
#include "integrators/family_implicit.hpp"
#include "integrators/particle_loops.hpp"
#include "integrators/shape_bound.hpp"
#include "integrators/unstable_cause.hpp"
#include "integrators/vbd/vertex_block_descent.hpp"
#include "self_collision/self_contact.hpp"

namespace drapelab {
namespace {

using Clock = std::chrono::steady_clock;

// Adds the wall time of one phase into the step statistics when it goes out of scope.
class PhaseTimer {
 public:
  PhaseTimer(StepStats& stats, StepPhase phase)
      : stats_(stats), phase_(phase), start_(Clock::now()) {}
  ~PhaseTimer() {
    stats_.seconds[static_cast<int>(phase_)] +=
        std::chrono::duration<double>(Clock::now() - start_).count();
  }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  StepStats& stats_;
  StepPhase phase_;
  Clock::time_point start_;
};

}  // namespace

const char* step_phase_name(StepPhase phase) {
  switch (phase) {
    case StepPhase::body_forces:
      return "body_forces";
    case StepPhase::springs:
      return "springs";
    case StepPhase::contacts:
      return "contacts";
    case StepPhase::integrate:
      return "integrate";
    case StepPhase::health_check:
      return "health_check";
    case StepPhase::step_bound:
      return "step_bound";
    case StepPhase::self_contacts:
      return "self_contacts";
    case StepPhase::count:
      break;
  }
  return "unknown";
}

SpringDamperSolver::SpringDamperSolver(std::string name, std::shared_ptr<const ClothModel> model,
                                       ClothState initial, SpringDamperSettings settings)
    : name_(std::move(name)),
      model_(std::move(model)),
      settings_(std::move(settings)),
      state_(std::move(initial)),
      force_(3, model_->particle_count()),
      wind_(settings_.air),
      contact_workspace_(std::make_unique<ContactWorkspace>()),
      shape_bound_(std::make_unique<ShapeBoundWorkspace>()) {
  const int n = model_->particle_count();
  coordinate_mass_ = model_->mass.transpose().replicate(3, 1);
  coordinate_inverse_mass_ = model_->inverse_mass.transpose().replicate(3, 1);
  weight_ = settings_.gravity * model_->mass.transpose();
  if (settings_.contacts) contact_totals_.resize(settings_.contacts->size());
  // What holds the cloth is fixed for the run: decide once what each step has to do for it.
  soft_constraints_ = settings_.constraints && settings_.constraints->has_soft();
  hard_constraints_ = settings_.constraints && settings_.constraints->has_hard();
  constraints_on_bodies_ = settings_.constraints && settings_.constraints->any_on_dynamic();
  attachments_on_bodies_ = settings_.attachments && settings_.attachments->any_on_dynamic();
  // The spring-family fast path serves springs only; the continuum's elements have their own loops.
  if (settings_.fast_springs && !model_->uses_continuum())
    spring_families_ = SpringFamilies::build(*model_);
  if (model_->uses_continuum())
    continuum_element_force_.resize(model_->continuum->force_scratch_size());
  switch (settings_.integrator) {
    case Integrator::explicit_euler:
    case Integrator::symplectic_euler:
      break;
    case Integrator::rk4:
      sum_x_.resize(3, n);
      sum_v_.resize(3, n);
      [[fallthrough]];
    case Integrator::midpoint:
      stage_x_.resize(3, n);
      stage_v_.resize(3, n);
      acceleration_.resize(3, n);
      break;
    case Integrator::verlet:
      previous_x_.resize(3, n);
      [[fallthrough]];
    case Integrator::leapfrog:
      stage_v_.resize(3, n);
      acceleration_.resize(3, n);
      break;
    case Integrator::implicit_euler:
      if (spring_families_)
        family_implicit_ =
            std::make_unique<FamilyImplicitSystem>(*model_, *spring_families_, settings_.implicit);
      else
        implicit_ = std::make_unique<ImplicitEulerSystem>(*model_, settings_.implicit);
      stage_v_.resize(3, n);  // dv
      active_contacts_.reserve(static_cast<std::size_t>(n));
      break;
    case Integrator::vbd:
      vbd_ = std::make_unique<VertexBlockDescent>(*model_, settings_.vbd);
      break;
  }
  for (int i = 0; i < model_->particle_count(); ++i)
    if (model_->is_pinned(i)) state_.v.col(i).setZero();  // a pin holds its particle still
  if (settings_.attachments) {
    for (const Attachment& a : settings_.attachments->list)
      if (a.particle >= n || !model_->is_pinned(a.particle))
        throw std::invalid_argument("attached particle " + std::to_string(a.particle) +
                                    " is not a pinned particle of the cloth");
    settings_.attachments->place(state_.time, state_.x, state_.v);  // ... or moves with its body
  }
  if (settings_.constraints)
    for (const DistanceConstraint& c : settings_.constraints->list)
      if (c.a < 0 || c.a >= n ||
          (c.b.kind == ConstraintEnd::Kind::particle && (c.b.particle < 0 || c.b.particle >= n)) ||
          (c.b.kind == ConstraintEnd::Kind::collider_point &&
           (c.b.collider < 0 ||
            c.b.collider >= static_cast<int>(settings_.constraints->colliders.size()))) ||
          (c.b.kind == ConstraintEnd::Kind::drag
               ? (!c.b.drag || c.b.drag->particle < 0 || c.b.drag->particle >= n)
               : !(c.length > 0.0)))  // a drag's spring has length 0
        throw std::invalid_argument(
            "a distance constraint names a particle or collider the scene "
            "does not have, or has a length that is not positive");
  if (settings_.contacts && settings_.collider_edges && model_->triangles.cols() > 0) {
    edge_contact_ = std::make_unique<EdgeContact>(*model_, *settings_.contacts);
    if (!edge_contact_->active()) edge_contact_.reset();
  }
  if (hard_constraints_) projection_start_v_.resize(3, n);
  if (settings_.self_collision.enabled && model_->triangles.cols() > 0) {
    self_contact_ = std::make_unique<SelfContact>(*model_, settings_.self_collision);
    step_start_x_.resize(3, n);
    step_start_v_.resize(3, n);
    piece_start_x_.resize(3, n);
  }
  if (settings_.adaptive_substeps) {
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
}

const Eigen::Matrix3Xd& SpringDamperSolver::evaluate_forces(const Eigen::Matrix3Xd& x,
                                                            const Eigen::Matrix3Xd& v, double t,
                                                            double h) {
  active_couplings_.clear();
  set_body_and_spring_forces(x, v);
  add_pair_contact_forces(x, v, t, h);
  if (settings_.contacts) add_contact_forces(x, v, t, h, nullptr);
  return force_;
}

void SpringDamperSolver::add_pair_contact_forces(const Eigen::Matrix3Xd& x,
                                                 const Eigen::Matrix3Xd& v, double t, double h) {
  // The implicit solve takes the couplings of its one (start-of-step) evaluation.
  // So does vertex block descent, as the contacts' energies in its descent.
  std::vector<WeightedContact>* couplings = implicit_stats() || vbd_ ? &active_couplings_ : nullptr;
  pair_power_ = {};
  if (self_contact_) {
    PhaseTimer timer(stats_, StepPhase::self_contacts);
    self_contact_->add_forces(x, v, h, model_->inverse_mass, force_, couplings);
    pair_power_.dissipated += self_contact_->stats().dissipated_power_last;
  }
  if (edge_contact_) {
    PhaseTimer timer(stats_, StepPhase::contacts);
    edge_contact_->add_forces(*settings_.contacts, t, h, x, v, model_->inverse_mass, force_,
                              couplings);
  }
  if (soft_constraints_) {
    PhaseTimer timer(stats_, StepPhase::springs);
    // The bodies take the reactions of the step's last evaluation.
    PowerSplit power;
    settings_.constraints->add_soft_forces(
        t, x, v, force_, couplings, constraints_on_bodies_ ? &constraint_loads_ : nullptr, &power);
    pair_power_ += power;
  }
  if (settings_.air.enabled) {
    PhaseTimer timer(stats_, StepPhase::body_forces);
    PowerSplit power;
    add_air_forces(*model_, settings_.air, wind_, t, x, v, force_, &power);
    pair_power_ += power;
  }
}

void SpringDamperSolver::set_body_and_spring_forces(const Eigen::Matrix3Xd& x,
                                                    const Eigen::Matrix3Xd& v) {
  if (spring_families_) {
    // Gravity and air drag inside the spring kernel (the same bits as the pass below). The kernel's
    // split of the state is skipped when the last Euler update left it split already.
    PhaseTimer timer(stats_, StepPhase::springs);
    const bool solver_state = &x == &state_.x && &v == &state_.v;
    spring_families_->set_body_and_spring_forces(x, v, weight_, coordinate_mass_,
                                                 settings_.air_damping, force_,
                                                 solver_state && split_state_is_current_);
    split_state_is_current_ = solver_state;
    body_and_spring_power_ = {spring_families_->damper_power() + air_damping_power(v), 0.0};
    return;
  }
  {
    // Gravity and air drag in one pass that overwrites the buffer (clearing the last evaluation).
    PhaseTimer timer(stats_, StepPhase::body_forces);
    kernels::set_body_forces(model_->particle_count(), weight_.data(), coordinate_mass_.data(),
                             settings_.air_damping, v.data(), force_.data());
  }
  PhaseTimer timer(stats_, StepPhase::springs);
  if (model_->uses_continuum()) {
    const kernels::ContinuumArrays arrays = continuum_arrays(*model_->continuum);
    kernels::add_continuum_forces(arrays, x.data(), v.data(), continuum_element_force_.data(),
                                  force_.data());
    body_and_spring_power_ = {
        kernels::continuum_damping_power(arrays, x.data(), v.data()) + air_damping_power(v), 0.0};
  } else {
    body_and_spring_power_ = {add_spring_forces(*model_, x, v, force_) + air_damping_power(v), 0.0};
  }
}

double SpringDamperSolver::air_damping_power(const Eigen::Matrix3Xd& v) const {
  // Air damping -c m v takes c m |v|^2 from each particle.
  if (!(settings_.air_damping > 0.0)) return 0.0;
  return settings_.air_damping * (coordinate_mass_.array() * v.array().square()).sum();
}

double SpringDamperSolver::kinetic_energy() const {
  return 0.5 * (coordinate_mass_.array() * state_.v.array().square()).sum();
}

PinnedStart SpringDamperSolver::pinned_start() const {
  PinnedStart start;
  if (!settings_.attachments) return start;
  const std::vector<Attachment>& list = settings_.attachments->list;
  start.x.resize(3, static_cast<Eigen::Index>(list.size()));
  for (std::size_t k = 0; k < list.size(); ++k) {
    const int i = list[k].particle;
    start.x.col(static_cast<Eigen::Index>(k)) = state_.x.col(i);
    start.kinetic_energy += 0.5 * model_->mass[i] * state_.v.col(i).squaredNorm();
  }
  return start;
}

void SpringDamperSolver::account_step(double h, const PinnedStart& pins) {
  PowerSplit power = body_and_spring_power_;
  power += pair_power_;
  for (const ColliderContactTotals& total : contact_totals_) power += total.power;
  ledger_.add(power, h);
  if (!settings_.attachments) return;
  // A pin moved by its collider takes whatever force holds it on its path: the collider's work
  // is the pin's change of kinetic energy less the work of the cloth's own forces on it (the
  // last evaluation's), - sum f . dx.
  const std::vector<Attachment>& list = settings_.attachments->list;
  double work = -pins.kinetic_energy;  // J
  for (std::size_t k = 0; k < list.size(); ++k) {
    const int i = list[k].particle;
    work += 0.5 * model_->mass[i] * state_.v.col(i).squaredNorm() -
            force_.col(i).dot(state_.x.col(i) - pins.x.col(static_cast<Eigen::Index>(k)));
  }
  ledger_.external_work += work;
}

std::optional<double> SpringDamperSolver::self_contact_energy() const {
  if (!self_contact_) return std::nullopt;
  return self_contact_->stats().spring_energy_last;
}

std::int64_t SpringDamperSolver::add_contact_forces(const Eigen::Matrix3Xd& x,
                                                    const Eigen::Matrix3Xd& v, double t, double h,
                                                    const ContactBlockFollowUp* follow_up) {
  PhaseTimer timer(stats_, StepPhase::contacts);
  const std::int64_t flagged = settings_.contacts->add_contact_forces(
      *model_, t, h, x, v, force_, contact_totals_, implicit_stats() ? &active_contacts_ : nullptr,
      contact_workspace_.get(), contact_normal_scheme(), follow_up);
  add_edge_contact_totals();  // the particle contacts' totals were just overwritten
  return flagged;
}

void SpringDamperSolver::add_edge_contact_totals() {
  if (!edge_contact_) return;
  for (std::size_t c = 0; c < contact_totals_.size(); ++c) {
    const EdgeContactTotals& edges = edge_contact_->totals()[c];
    contact_totals_[c].contact_count += edges.contact_count;
    contact_totals_[c].normal_force += edges.normal_force;
    contact_totals_[c].friction_force += edges.friction_force;
    contact_totals_[c].max_depth = std::max(contact_totals_[c].max_depth, edges.max_depth);
    contact_totals_[c].force += edges.force;
    contact_totals_[c].torque += edges.torque;
    contact_totals_[c].power += edges.power;
  }
}

ContactNormalScheme SpringDamperSolver::contact_normal_scheme() const {
  return contact_at_step_end(settings_.integrator) ? ContactNormalScheme::linearly_implicit
                                                   : ContactNormalScheme::explicit_penalty;
}

std::vector<ColliderForce> SpringDamperSolver::collider_forces() const {
  std::vector<ColliderForce> forces;
  for (const auto& total : contact_totals_)
    forces.push_back({total.normal_force, total.friction_force, total.force, total.torque});
  for (const auto* loads : {&attachment_loads_, &constraint_loads_}) {
    if (forces.size() < loads->size()) forces.resize(loads->size());
    for (std::size_t c = 0; c < loads->size(); ++c) {
      forces[c].force += (*loads)[c].force;
      forces[c].torque += (*loads)[c].torque;
    }
  }
  return forces;
}

std::vector<std::pair<std::string, double>> SpringDamperSolver::phase_seconds() const {
  std::vector<std::pair<std::string, double>> phases;
  for (int p = 0; p < static_cast<int>(StepPhase::count); ++p) {
    const auto phase = static_cast<StepPhase>(p);
    if (phase == StepPhase::step_bound && !settings_.adaptive_substeps) continue;
    if (phase == StepPhase::self_contacts && !self_contact_) continue;
    phases.emplace_back(step_phase_name(phase), stats_.seconds[p]);
  }
  return phases;
}

// Out of line: the private machinery's types are complete only here.
SpringDamperSolver::~SpringDamperSolver() = default;

const VbdStats* SpringDamperSolver::vbd_stats() const { return vbd_ ? &vbd_->stats() : nullptr; }

const ImplicitSolveStats* SpringDamperSolver::implicit_stats() const {
  if (implicit_) return &implicit_->stats();
  if (family_implicit_) return &family_implicit_->stats();
  return nullptr;
}

std::vector<std::pair<std::string, double>> SpringDamperSolver::counters() const {
  std::vector<std::pair<std::string, double>> all = scheme_counters();
  if (self_contact_) {
    const SelfContactStats& self = self_contact_->stats();
    all.insert(
        all.end(),
        {{"self_contacts_last", static_cast<double>(self.contacts_last)},
         {"self_contacts_mean", self.evaluations > 0 ? static_cast<double>(self.contacts_total) /
                                                           static_cast<double>(self.evaluations)
                                                     : 0.0},
         {"self_collision_searches", static_cast<double>(self.rebuilds)},
         {"self_collision_candidates_last", static_cast<double>(self.candidates)},
         {"self_collision_split_steps", static_cast<double>(stats_.split_steps)},
         {"self_collision_split_pieces_max", static_cast<double>(stats_.split_pieces_max)},
         {"self_collision_unresolved_fast_steps",
          static_cast<double>(stats_.unresolved_fast_steps)}});
  }
  if (hard_constraints_)
    all.insert(all.end(), {{"constraint_position_sweeps_max",
                            static_cast<double>(stats_.constraint_position_sweeps_max)},
                           {"constraint_velocity_sweeps_max",
                            static_cast<double>(stats_.constraint_velocity_sweeps_max)},
                           {"constraint_unconverged_steps",
                            static_cast<double>(stats_.constraint_unconverged_steps)}});
  return all;
}

std::vector<std::pair<std::string, double>> SpringDamperSolver::scheme_counters() const {
  if (settings_.adaptive_substeps)
    return {{"substeps", static_cast<double>(stats_.steps)},
            {"substeps_per_step_mean",
             stats_.outer_steps > 0
                 ? static_cast<double>(stats_.steps) / static_cast<double>(stats_.outer_steps)
                 : 0.0},
            {"substeps_per_step_min", static_cast<double>(stats_.substeps_min)},
            {"substeps_per_step_max", static_cast<double>(stats_.substeps_max)}};
  if (vbd_) {
    const VbdStats& s = vbd_->stats();
    return {{"vbd_iterations", settings_.vbd.iterations},
            {"vbd_order", settings_.vbd.order},
            {"vbd_chebyshev_rho", settings_.vbd.chebyshev_rho},
            {"vbd_colors", s.colors},
            {"vbd_last_sweep_move", s.last_sweep_move},
            {"vbd_last_sweep_move_max", s.last_sweep_move_max},
            {"vbd_contact_planes_last", static_cast<double>(s.contacts_last)}};
  }
  if (!implicit_stats()) return {};
  const ImplicitSolveStats& cg = *implicit_stats();
  const double mean =
      cg.solves > 0 ? static_cast<double>(cg.iterations_total) / static_cast<double>(cg.solves)
                    : 0.0;
  return {{"cg_solves", static_cast<double>(cg.solves)},
          {"cg_iterations_total", static_cast<double>(cg.iterations_total)},
          {"cg_iterations_mean", mean},
          {"cg_iterations_max", cg.iterations_max},
          {"cg_relative_residual_max", cg.residual_max},
          {"cg_unconverged_steps", static_cast<double>(cg.unconverged)},
          {"cg_tolerance", settings_.implicit.tolerance},
          {"cg_max_iterations", settings_.implicit.max_iterations}};
}

double SpringDamperSolver::force_phase_seconds() const {
  double total = 0.0;
  for (StepPhase phase :
       {StepPhase::body_forces, StepPhase::springs, StepPhase::self_contacts, StepPhase::contacts})
    total += stats_.seconds[static_cast<int>(phase)];
  return total;
}

const Eigen::Matrix3Xd& SpringDamperSolver::acceleration_of_force(Eigen::Matrix3Xd& into) const {
  into.noalias() = force_ * model_->inverse_mass.asDiagonal();
  return into;
}

void SpringDamperSolver::step(double h) {
  if (status_ != SolverStatus::ok) return;
  if (self_contact_)
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
  const double bound = 0.25 * self_contact_->thickness();  // m
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
    // Back to the step's start with twice the pieces; the two-level schemes start afresh.
    state_.x = step_start_x_;
    state_.v = step_start_v_;
    state_.time = start_time;
    state_.step_count = start_count;
    ledger_ = start_ledger;
    two_level_step_ = 0.0;
    split_state_is_current_ = false;
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
  const double target =
      settings_.substep_safety *
      shape_stable_step(*model_, state_.x, settings_.air_damping, *shape_bound_,
                        spring_families_ ? &spring_families_->families() : nullptr);  // s
  // At most 10^7 substeps, as the scene format allows per frame (a NaN shape gives one: the health
  // check then stops the run).
  const double count = std::ceil(h / target);
  if (!(count >= 1.0)) return 1;
  return static_cast<int>(std::min(count, 1e7));
}

void SpringDamperSolver::single_step(double h) {
  const auto start = Clock::now();
  const double force_seconds_before = force_phase_seconds();
  std::optional<std::int64_t> scanned;  // the Euler passes scan the new state as they write it
  if (settings_.attachments) settings_.attachments->place(state_.time, state_.x, state_.v);
  const PinnedStart pins = pinned_start();
  switch (settings_.integrator) {
    case Integrator::explicit_euler:
    case Integrator::symplectic_euler:
      scanned = euler_step(h);
      break;
    case Integrator::midpoint:
      midpoint_step(h);
      break;
    case Integrator::rk4:
      rk4_step(h);
      break;
    case Integrator::verlet:
      verlet_step(h);
      break;
    case Integrator::leapfrog:
      leapfrog_step(h);
      break;
    case Integrator::implicit_euler:
      implicit_euler_step(h);
      break;
    case Integrator::vbd:
      vbd_step(h);
      break;
  }
  // The schemes moved the attached particles with their velocities at the step's start; they end
  // it where their colliders are.
  if (settings_.attachments) settings_.attachments->place(state_.time + h, state_.x, state_.v);
  // vbd's backward Euler step evaluates no force: its springs at the end state, where its forces
  // act, give the ledger its dampers' power and the attachments their loads.
  if (settings_.integrator == Integrator::vbd) set_body_and_spring_forces(state_.x, state_.v);
  if (attachments_on_bodies_) record_attachment_loads();
  account_step(h, pins);
  const bool projects = hard_constraints_;
  if (projects) {
    // The projection's impulses J = m (v_after - v_before) dissipate -J . (v_start + v_after) / 2,
    // with v_start = v_before - h f / m the velocity the particle brought into the step: a rope
    // that catches a particle moving at u takes m u^2 / 2, one already taut takes nothing (there
    // it only takes back, each step, the velocity the step's own forces gave).
    projection_start_v_ = state_.v;
    project_constraints(state_.time + h, h);
    ledger_.dissipated +=
        0.5 *
        ((projection_start_v_ - state_.v).array() *
         (coordinate_mass_.array() * (projection_start_v_ + state_.v).array() - h * force_.array()))
            .sum();
    scanned.reset();  // the projection moved particles after the Euler pass scanned them
  }
  // Only the Euler pair with colliders keeps the spring kernel's split state in step with the
  // update (and not when attached particles were placed or constraints projected after it).
  if (!scanned || !settings_.contacts || settings_.attachments || projects)
    split_state_is_current_ = false;
  // Whatever the step spent outside the force phases is the integrator's own work.
  const double step_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  stats_.seconds[static_cast<int>(StepPhase::integrate)] +=
      step_seconds - (force_phase_seconds() - force_seconds_before);
  state_.time += h;
  ++state_.step_count;
  ++stats_.steps;
  PhaseTimer timer(stats_, StepPhase::health_check);
  check_health(h, scanned);
}

// Projection with velocity correction: the positions onto the constraints, then the velocities
// onto their tangent spaces (distance_constraints.hpp). Verlet, whose velocity is its position
// difference, takes its velocity from the projected positions first (so the constraint's impulse
// stays in its history, as SHAKE does); leapfrog's stored end-of-step force was evaluated before
// the projection, so it evaluates the force afresh at the next step.
void SpringDamperSolver::project_constraints(double t, double h) {
  const DistanceConstraints& constraints = *settings_.constraints;
  ConstraintProjection result = constraints.project_positions(t, model_->inverse_mass, state_.x);
  if (result.moved && settings_.integrator == Integrator::verlet)
    state_.v = (state_.x - previous_x_) / h + (0.5 * h) * acceleration_;
  if (result.moved && settings_.integrator == Integrator::leapfrog) two_level_step_ = 0.0;
  constraints.project_velocities(t, h, model_->inverse_mass, state_.x, state_.v, result);
  stats_.constraint_position_sweeps_max =
      std::max(stats_.constraint_position_sweeps_max, result.position_sweeps);
  stats_.constraint_velocity_sweeps_max =
      std::max(stats_.constraint_velocity_sweeps_max, result.velocity_sweeps);
  if (!result.converged) ++stats_.constraint_unconverged_steps;
}

void SpringDamperSolver::record_attachment_loads() {
  const Attachments& attached = *settings_.attachments;
  attachment_loads_.assign(attached.colliders.size(), ColliderForce{});
  for (std::size_t k = 0; k < attached.list.size(); ++k) {
    if (!attached.on_dynamic(k)) continue;
    const int i = attached.list[k].particle;
    ColliderForce& load = attachment_loads_[static_cast<std::size_t>(attached.list[k].collider)];
    load.force += force_.col(i);
    load.torque += Eigen::Vector3d(state_.x.col(i)).cross(Eigen::Vector3d(force_.col(i)));
  }
}

std::int64_t SpringDamperSolver::euler_step(double h) {
  const bool symplectic = settings_.integrator == Integrator::symplectic_euler;
  const double max_speed_squared = settings_.max_speed * settings_.max_speed;
  if (!settings_.contacts) {
    evaluate_forces(state_.x, state_.v, state_.time, h);
    const auto pass = symplectic ? kernels::symplectic_euler_pass : kernels::explicit_euler_pass;
    return pass(model_->particle_count(), coordinate_inverse_mass_.data(), force_.data(), h,
                state_.x.data(), state_.v.data(), max_speed_squared);
  }
  // With contacts, each block of particles is updated as soon as its contact forces are final, on
  // the thread that computed them and while they are in its cache: the same expressions as the pass
  // above, so the same bits, without a pass (and a start of the threads) of its own. The update's
  // time is then counted in the contact phase. On the spring fast path the block's new state is
  // also split into the kernel's unit-stride arrays there, so the next force evaluation skips its
  // own pass over the state (and a barrier).
  struct EulerUpdate {
    bool symplectic;
    const double* inverse_mass;
    const double* force;
    double h;
    double* x;
    double* v;
    double max_speed_squared;
    SpringFamilies* families;  // null off the fast path
  };
  const EulerUpdate update{symplectic,        coordinate_inverse_mass_.data(),
                           force_.data(),     h,
                           state_.x.data(),   state_.v.data(),
                           max_speed_squared, spring_families_.get()};
  const ContactBlockFollowUp follow_up{
      [](const void* context, std::int64_t begin, std::int64_t end) {
        const auto& u = *static_cast<const EulerUpdate*>(context);
        const std::int64_t flagged = kernels::euler_range(
            u.symplectic, begin, end, u.inverse_mass, u.force, u.h, u.x, u.v, u.max_speed_squared);
        if (u.families) u.families->split_state(u.x, u.v, begin, end);
        return flagged;
      },
      &update};
  if (spring_families_ && !has_pair_contacts()) {
    const std::int64_t flagged = spring_and_contact_forces_together(h, follow_up);
    split_state_is_current_ = true;  // every block was split as it was updated
    return flagged;
  }
  set_body_and_spring_forces(state_.x, state_.v);
  add_pair_contact_forces(state_.x, state_.v, state_.time, h);
  const std::int64_t flagged = add_contact_forces(state_.x, state_.v, state_.time, h, &follow_up);
  split_state_is_current_ = false;
  return flagged;
}

std::int64_t SpringDamperSolver::spring_and_contact_forces_together(
    double h, const ContactBlockFollowUp& follow_up) {
  const auto start = Clock::now();
  const ContactPass pass(*settings_.contacts, *model_, state_.time, h, state_.x, state_.v, force_,
                         *contact_workspace_, contact_normal_scheme(), implicit_stats() != nullptr,
                         &follow_up);
  // The phase timers split the region where the thread that runs block 0 turns from springs to
  // contacts (the other thread's turn is within a block's time of it).
  struct Contacts {
    const ContactPass* pass;
    Clock::time_point* turned;
  };
  auto turned = Clock::now();
  const Contacts contacts{&pass, &turned};
  const kernels::ForcesFinalHook hook{
      [](const void* context, std::int64_t first_block, std::int64_t end_block) {
        const auto& c = *static_cast<const Contacts*>(context);
        if (first_block == 0 && end_block > 0) *c.turned = Clock::now();
        for (std::int64_t block = first_block; block < end_block; ++block) c.pass->run_block(block);
      },
      &contacts};
  // The Euler update in the region overwrites the velocities: air damping's power before it.
  const double air_power = air_damping_power(state_.v);  // W
  const auto springs_start = Clock::now();
  spring_families_->set_body_and_spring_forces(state_.x, state_.v, weight_, coordinate_mass_,
                                               settings_.air_damping, force_,
                                               split_state_is_current_, &hook);
  body_and_spring_power_ = {spring_families_->damper_power() + air_power, 0.0};
  const std::int64_t flagged =
      pass.finish(contact_totals_, implicit_stats() ? &active_contacts_ : nullptr);
  const auto end = Clock::now();
  using Seconds = std::chrono::duration<double>;
  stats_.seconds[static_cast<int>(StepPhase::springs)] += Seconds(turned - springs_start).count();
  stats_.seconds[static_cast<int>(StepPhase::contacts)] +=
      Seconds(springs_start - start).count() + Seconds(end - turned).count();
  return flagged;
}

// Backward Euler, linearised at the start of the step (implicit_euler.hpp).
void SpringDamperSolver::implicit_euler_step(double h) {
  evaluate_forces(state_.x, state_.v, state_.time, h);
  const ContactParameters contact =
      settings_.contacts ? settings_.contacts->parameters() : ContactParameters{};
  if (family_implicit_)
    family_implicit_->solve(*model_, state_.x, state_.v, force_, h, settings_.air_damping, contact,
                            active_contacts_, active_couplings_, stage_v_);
  else
    implicit_->solve(*model_, state_.x, state_.v, force_, h, settings_.air_damping, contact,
                     active_contacts_, active_couplings_, stage_v_);
  state_.v += stage_v_;                // v(n+1) = v(n) + dv
  state_.x.noalias() += h * state_.v;  // x(n+1) = x(n) + h v(n+1)
}

// Backward Euler by vertex block descent (vertex_block_descent.hpp). The contacts between particles
// are found at the step's start: their pushes enter the descent as energies of the particles'
// motion, their friction as an explicit force of the step.
void SpringDamperSolver::vbd_step(double h) {
  VbdStepInput input;
  input.t = state_.time;
  input.h = h;
  input.gravity = settings_.gravity;
  input.air_damping = settings_.air_damping;
  input.contacts = settings_.contacts.get();
  if (has_pair_contacts()) {
    active_couplings_.clear();
    force_.setZero();
    add_pair_contact_forces(state_.x, state_.v, state_.time, h);
    for (const WeightedContact& c : active_couplings_)  // leaves the friction only
      for (int s = 0; s < 4; ++s)
        if (c.particle[s] >= 0) force_.col(c.particle[s]) -= (c.weight[s] * c.force) * c.normal;
    input.couplings = &active_couplings_;
    input.explicit_force = &force_;
  }
  vbd_->step(*model_, input, state_.x, state_.v, contact_totals_);
  add_edge_contact_totals();
}

// Stops the solver on a non-finite or runaway particle, naming the first one, the step, and what to
// try. Runs every step over particles only (O(N)); the message is built only on failure.
void SpringDamperSolver::check_health(double h, std::optional<std::int64_t> scanned) {
  const double max_speed_squared = settings_.max_speed * settings_.max_speed;
  // The Euler passes scanned the new state as they wrote it; other schemes scan it here.
  const std::int64_t first =
      scanned ? *scanned
              : kernels::first_unhealthy_particle(model_->particle_count(), state_.x.data(),
                                                  state_.v.data(), max_speed_squared);
  if (first < 0) return;
  const int i = static_cast<int>(first);
  const bool finite = state_.x.col(i).allFinite() && state_.v.col(i).allFinite();
  const double speed_squared = finite ? state_.v.col(i).squaredNorm() : 0.0;

  std::ostringstream text;
  text.precision(4);
  text << model_->describe_particle(i);
  if (!finite)
    text << " has a non-finite position or velocity";
  else
    text << " moves at " << std::sqrt(speed_squared) << " m/s, above the runaway limit of "
         << settings_.max_speed << " m/s";
  text << " after step " << state_.step_count << " (t = " << state_.time << " s, dt = " << h
       << " s, integrator " << integrator_name(settings_.integrator) << ").";
  // What acted in that step, by kind: the colliders touched (and how deep), self-contacts, and the
  // constraints and drags on the particle.
  StepContactsSeen seen;
  seen.colliders = settings_.contacts.get();
  seen.totals = &contact_totals_;
  seen.edge_totals = edge_contact_ ? &edge_contact_->totals() : nullptr;
  seen.self_contacts = self_contact_ ? self_contact_->stats().contacts_last : -1;
  seen.constraints = settings_.constraints.get();
  text << unstable_step_cause(*model_, seen, i) << " Try: ";
  if (settings_.adaptive_substeps)
    text << "a smaller dt or adaptive_substeps: false (the substeps follow the shape's stable "
            "step, taken once "
            "per dt; the cloth may have changed faster than that), ";
  ContactRates contact;
  if (settings_.contacts)
    contact = {settings_.contacts->parameters().stiffness,
               settings_.contacts->parameters().damping};
  const double stable_step =
      stable_step_estimate(*model_, settings_.air_damping, contact, settings_.integrator);
  const bool contact_bounds_step = !contact_at_step_end(settings_.integrator);
  const NetworkRates rates = network_rate_bounds(*model_, settings_.air_damping,
                                                 contact_bounds_step ? contact : ContactRates{});
  if (settings_.integrator == Integrator::explicit_euler ||
      settings_.integrator == Integrator::midpoint)
    text << "integrator symplectic_euler, leapfrog or implicit_euler ("
         << integrator_name(settings_.integrator)
         << " gains energy on every undamped spring and is stable only while damping outweighs "
            "it), ";
  if (settings_.integrator == Integrator::vbd)
    text << "a smaller dt or more vbd iterations (" << settings_.vbd.iterations
         << " sweeps per step left particles moving by up to " << vbd_->stats().last_sweep_move
         << " m in the last sweep; a collider moving faster than its contact can push back also "
            "needs a smaller dt), ";
  else if (settings_.integrator == Integrator::implicit_euler)
    text << "a smaller dt or a larger implicit max_iterations (the conjugate gradient reached a "
            "relative "
            "residual of "
         << implicit_stats()->residual_last << " in " << implicit_stats()->iterations_last
         << " iterations; a collider moving faster than its contact can push back also needs a "
            "smaller dt), ";
  else if (stable_step > 0.0 && std::isfinite(stable_step) && stable_step < h)
    text << "a smaller dt (the Gershgorin bound of these springs and dampers"
         << (contact_bounds_step ? " and of the contact" : "") << " gives a stable "
         << integrator_name(settings_.integrator) << " step below about " << stable_step << " s), ";
  else if (std::isfinite(stable_step) && stable_step >= h)
    text << "a smaller dt (dt is inside the springs' stable step of about " << stable_step
         << " s, so a contact or a fast collider is the likely cause: try half the dt, or a softer "
            "contact), ";
  // In h^2 K + 2 h C < 4, the larger term says whether springs or dampers limit the step.
  if (settings_.integrator == Integrator::implicit_euler || settings_.integrator == Integrator::vbd)
    text << "or a softer contact (lower contact.stiffness).";
  else if (settings_.integrator == Integrator::explicit_euler ||
           settings_.integrator == Integrator::midpoint)
    text << "or more damping for the stiffness (this scheme is stable only for dt below about kd / "
            "ks of "
            "the springs).";
  else if (2.0 * rates.damping > h * rates.stiffness)
    text << (contact_bounds_step ? "or less damping (lower kd, air_damping or contact.damping"
                                 : "or less damping (lower kd or air_damping")
         << ": here the dampers, not the springs, limit the step; they act per spring or particle, "
            "so light "
            "particles need small values).";
  else
    text << (contact_bounds_step ? "or softer springs (lower ks or contact.stiffness)."
                                 : "or softer springs (lower ks).");
  status_ = SolverStatus::unstable;
  message_ = text.str();
}

}  // namespace drapelab
