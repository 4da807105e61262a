// Our spring-damper cloth solver: the step as a list of named, timed phases.
#include "drapelab/spring_damper_solver.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

#include "drapelab/forces.hpp"
#include "drapelab/stability.hpp"

namespace drapelab {
namespace {

using Clock = std::chrono::steady_clock;

// Adds the wall time of one phase into the step statistics when it goes out of scope.
class PhaseTimer {
 public:
  PhaseTimer(StepStats& stats, StepPhase phase) : stats_(stats), phase_(phase), start_(Clock::now()) {}
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
    case StepPhase::clear_forces: return "clear_forces";
    case StepPhase::gravity: return "gravity";
    case StepPhase::springs: return "springs";
    case StepPhase::air: return "air";
    case StepPhase::contacts: return "contacts";
    case StepPhase::integrate: return "integrate";
    case StepPhase::health_check: return "health_check";
    case StepPhase::count: break;
  }
  return "unknown";
}

SpringDamperSolver::SpringDamperSolver(std::string name, std::shared_ptr<const ClothModel> model,
                                       ClothState initial, SpringDamperSettings settings)
    : name_(std::move(name)),
      model_(std::move(model)),
      settings_(std::move(settings)),
      state_(std::move(initial)),
      force_(3, model_->particle_count()) {
  if (settings_.contacts) contact_totals_.resize(settings_.contacts->size());
  for (int i = 0; i < model_->particle_count(); ++i)
    if (model_->is_pinned(i)) state_.v.col(i).setZero();  // a pin holds its particle still
}

const Eigen::Matrix3Xd& SpringDamperSolver::evaluate_forces(const Eigen::Matrix3Xd& x,
                                                            const Eigen::Matrix3Xd& v, double t, double h) {
  {
    PhaseTimer timer(stats_, StepPhase::clear_forces);
    force_.setZero();
  }
  {
    PhaseTimer timer(stats_, StepPhase::gravity);
    add_gravity_forces(*model_, settings_.gravity, force_);
  }
  {
    PhaseTimer timer(stats_, StepPhase::springs);
    add_spring_forces(*model_, x, v, force_);
  }
  {
    PhaseTimer timer(stats_, StepPhase::air);
    add_air_damping_forces(*model_, settings_.air_damping, v, force_);
  }
  if (settings_.contacts) {
    PhaseTimer timer(stats_, StepPhase::contacts);
    settings_.contacts->add_contact_forces(*model_, t, h, x, v, force_, contact_totals_);
  }
  return force_;
}

std::vector<ColliderForce> SpringDamperSolver::collider_forces() const {
  std::vector<ColliderForce> forces;
  for (const auto& total : contact_totals_) forces.push_back({total.normal_force, total.friction_force});
  return forces;
}

std::vector<std::pair<std::string, double>> SpringDamperSolver::phase_seconds() const {
  std::vector<std::pair<std::string, double>> phases;
  for (int p = 0; p < static_cast<int>(StepPhase::count); ++p)
    phases.emplace_back(step_phase_name(static_cast<StepPhase>(p)), stats_.seconds[p]);
  return phases;
}

void SpringDamperSolver::step(double h) {
  if (status_ != SolverStatus::ok) return;
  evaluate_forces(state_.x, state_.v, state_.time, h);
  {
    PhaseTimer timer(stats_, StepPhase::integrate);
    switch (settings_.integrator) {
      case Integrator::explicit_euler:
        explicit_euler_update(model_->inverse_mass, force_, h, state_.x, state_.v);
        break;
      case Integrator::symplectic_euler:
        symplectic_euler_update(model_->inverse_mass, force_, h, state_.x, state_.v);
        break;
    }
  }
  state_.time += h;
  ++state_.step_count;
  ++stats_.steps;
  PhaseTimer timer(stats_, StepPhase::health_check);
  check_health(h);
}

// Stops the solver on a non-finite or runaway particle, naming it, the step, and what to try. Runs
// every step over particles only (O(N)); the message is built only on failure.
void SpringDamperSolver::check_health(double h) {
  const double max_speed_squared = settings_.max_speed * settings_.max_speed;
  for (int i = 0; i < model_->particle_count(); ++i) {
    const bool finite = state_.x.col(i).allFinite() && state_.v.col(i).allFinite();
    const double speed_squared = finite ? state_.v.col(i).squaredNorm() : 0.0;
    if (finite && speed_squared <= max_speed_squared) continue;

    std::ostringstream text;
    text.precision(4);
    text << model_->describe_particle(i);
    if (!finite)
      text << " has a non-finite position or velocity";
    else
      text << " moves at " << std::sqrt(speed_squared) << " m/s, above the runaway limit of "
           << settings_.max_speed << " m/s";
    text << " after step " << state_.step_count << " (t = " << state_.time << " s, dt = " << h
         << " s, integrator " << integrator_name(settings_.integrator) << "). Try: ";
    ContactRates contact;
    if (settings_.contacts) contact = {settings_.contacts->parameters().stiffness, settings_.contacts->parameters().damping};
    const double stable_step = symplectic_euler_stable_step(*model_, settings_.air_damping, contact);
    const NetworkRates rates = network_rate_bounds(*model_, settings_.air_damping, contact);
    if (settings_.integrator == Integrator::explicit_euler)
      text << "integrator symplectic_euler (explicit Euler gains energy on every undamped spring), ";
    if (std::isfinite(stable_step))
      text << "a smaller dt (the Gershgorin bound of these springs and dampers guarantees a stable "
              "symplectic step below "
           << stable_step << " s), ";
    // In h^2 K + 2 h C < 4, the larger term says whether springs or dampers limit the step.
    if (2.0 * rates.damping > h * rates.stiffness)
      text << "or less damping (lower kd, air_damping or contact.damping: here the dampers, not the springs, "
              "limit the step; they act per spring or particle, so light particles need small values).";
    else
      text << "or softer springs (lower ks or contact.stiffness).";
    status_ = SolverStatus::unstable;
    message_ = text.str();
    return;
  }
}

}  // namespace drapelab
