// The force evaluation's phases and the terms between particles (force_evaluator.hpp).
#include "integrators/force_evaluator.hpp"

#include <algorithm>

#include "air/air_term.hpp"
#include "constraints/soft_constraint_term.hpp"
#include "contact/contact_pass.hpp"
#include "contact/edge_contact_term.hpp"
#include "drapelab/spring_forces.hpp"
#include "drapelab/stability.hpp"
#include "forces/body_force_loops.hpp"
#include "forces/continuum_arrays.hpp"
#include "forces/spring_families.hpp"
#include "integrators/phase_timer.hpp"
#include "self_collision/self_contact_term.hpp"

namespace drapelab {

ForceEvaluator::ForceEvaluator(const ClothModel& model, const SpringDamperSettings& settings,
                               const ClothState& solver_state, StepStats& stats)
    : model_(model),
      settings_(settings),
      solver_state_(solver_state),
      stats_(stats),
      force_(3, model.particle_count()),
      contact_workspace_(std::make_unique<ContactWorkspace>()) {
  masses_.mass = model_.mass.transpose().replicate(3, 1);
  masses_.inverse_mass = model_.inverse_mass.transpose().replicate(3, 1);
  masses_.weight = settings_.gravity * model_.mass.transpose();
  if (settings_.contacts) contact_totals_.resize(settings_.contacts->size());
  // The spring-family fast path serves springs only; the continuum's elements have their own loops.
  if (settings_.fast_springs && !model_.uses_continuum())
    spring_families_ = SpringFamilies::build(model_);
  if (model_.uses_continuum())
    continuum_element_force_.resize(model_.continuum->force_scratch_size());
  keep_active_contacts_ = settings_.integrator == Integrator::implicit_euler;
  keep_couplings_ = keep_active_contacts_ || settings_.integrator == Integrator::vbd;
  if (keep_active_contacts_)
    active_contacts_.reserve(static_cast<std::size_t>(model_.particle_count()));

  // Phase 2, in its order. A new term between particles is one more entry here.
  const bool has_triangles = model_.triangles.cols() > 0;
  // vbd keeps the cloth off itself inside its own solve (offset contacts, vbd_scheme.cpp).
  if (settings_.self_collision.enabled && has_triangles &&
      settings_.integrator != Integrator::vbd) {
    auto term = std::make_unique<SelfContactTerm>(model_, settings_.self_collision);
    self_contact_ = &term->contact();
    pair_terms_.push_back(std::move(term));
  }
  // vbd measures the collider edges inside its own solve too (vbd_scheme.cpp).
  if (settings_.contacts && settings_.collider_edges && has_triangles &&
      settings_.integrator != Integrator::vbd) {
    auto term = std::make_unique<EdgeContactTerm>(model_, *settings_.contacts);
    if (term->active()) {
      edge_contact_ = &term->contact();
      pair_terms_.push_back(std::move(term));
    }
  }
  if (settings_.constraints && settings_.constraints->has_soft()) {
    auto term = std::make_unique<SoftConstraintTerm>(*settings_.constraints);
    soft_constraints_ = term.get();
    pair_terms_.push_back(std::move(term));
  }
  if (settings_.air.enabled)
    pair_terms_.push_back(std::make_unique<AirTerm>(model_, settings_.air));
}

ForceEvaluator::~ForceEvaluator() = default;

std::vector<std::string> ForceEvaluator::term_names() const {
  std::vector<std::string> names{"body_and_springs"};
  for (const std::unique_ptr<ForceTerm>& term : pair_terms_) names.emplace_back(term->name());
  if (settings_.contacts) names.emplace_back("collider_contacts");
  return names;
}

const Eigen::Matrix3Xd& ForceEvaluator::evaluate(const Eigen::Matrix3Xd& x,
                                                 const Eigen::Matrix3Xd& v, double t, double h) {
  couplings_.clear();
  set_body_and_spring_forces(x, v);
  add_pair_forces(x, v, t, h);
  if (settings_.contacts) add_contact_forces(x, v, t, h, nullptr);
  return force_;
}

void ForceEvaluator::set_body_and_spring_forces(const Eigen::Matrix3Xd& x,
                                                const Eigen::Matrix3Xd& v) {
  if (spring_families_) {
    // Gravity and air drag inside the spring kernel (the same bits as the pass below). The kernel's
    // split of the state is skipped when the last Euler update left it split already.
    PhaseTimer timer(stats_, StepPhase::springs);
    const bool at_solver_state = &x == &solver_state_.x && &v == &solver_state_.v;
    spring_families_->set_body_and_spring_forces(x, v, masses_.weight, masses_.mass,
                                                 settings_.air_damping, force_,
                                                 at_solver_state && split_state_is_current_);
    split_state_is_current_ = at_solver_state;
    body_and_spring_power_ = {spring_families_->damper_power() + air_damping_power(v), 0.0};
    return;
  }
  {
    // Gravity and air drag in one pass that overwrites the buffer (clearing the last evaluation).
    PhaseTimer timer(stats_, StepPhase::body_forces);
    kernels::set_body_forces(model_.particle_count(), masses_.weight.data(), masses_.mass.data(),
                             settings_.air_damping, v.data(), force_.data());
  }
  PhaseTimer timer(stats_, StepPhase::springs);
  if (model_.uses_continuum()) {
    const kernels::ContinuumArrays arrays = continuum_arrays(*model_.continuum);
    kernels::add_continuum_forces(arrays, x.data(), v.data(), continuum_element_force_.data(),
                                  force_.data());
    body_and_spring_power_ = {
        kernels::continuum_damping_power(arrays, x.data(), v.data()) + air_damping_power(v), 0.0};
  } else {
    body_and_spring_power_ = {add_spring_forces(model_, x, v, force_) + air_damping_power(v), 0.0};
  }
}

void ForceEvaluator::add_pair_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, double t,
                                     double h) {
  pair_power_ = {};
  const ForceArgs at{x, v, t, h};
  for (const std::unique_ptr<ForceTerm>& term : pair_terms_) {
    PhaseTimer timer(stats_, term->phase());
    ForceSink out{force_, keep_couplings_ ? &couplings_ : nullptr, {}};
    term->add(at, out);
    pair_power_ += out.power;
  }
}

std::int64_t ForceEvaluator::add_contact_forces(const Eigen::Matrix3Xd& x,
                                                const Eigen::Matrix3Xd& v, double t, double h,
                                                const ContactBlockFollowUp* follow_up) {
  PhaseTimer timer(stats_, StepPhase::contacts);
  const std::int64_t flagged = settings_.contacts->add_contact_forces(
      model_, t, h, x, v, force_, contact_totals_,
      keep_active_contacts_ ? &active_contacts_ : nullptr, contact_workspace_.get(),
      contact_normal_scheme(), follow_up);
  add_edge_contact_totals();  // the particle contacts' totals were just overwritten
  return flagged;
}

std::int64_t ForceEvaluator::spring_and_contact_forces_together(
    double t, double h, const ContactBlockFollowUp& follow_up) {
  const auto start = StepClock::now();
  const ClothState& state = solver_state_;
  const ContactPass pass(*settings_.contacts, model_, t, h, state.x, state.v, force_,
                         *contact_workspace_, contact_normal_scheme(), keep_active_contacts_,
                         &follow_up);
  // The phase timers split the region where the thread that runs block 0 turns from springs to
  // contacts (the other thread's turn is within a block's time of it).
  struct Contacts {
    const ContactPass* pass;
    StepClock::time_point* turned;
  };
  auto turned = StepClock::now();
  const Contacts contacts{&pass, &turned};
  const kernels::ForcesFinalHook hook{
      [](const void* context, std::int64_t first_block, std::int64_t end_block) {
        const auto& c = *static_cast<const Contacts*>(context);
        if (first_block == 0 && end_block > 0) *c.turned = StepClock::now();
        for (std::int64_t block = first_block; block < end_block; ++block) c.pass->run_block(block);
      },
      &contacts};
  // The Euler update in the region overwrites the velocities: air damping's power before it.
  const double air_power = air_damping_power(state.v);  // W
  const auto springs_start = StepClock::now();
  spring_families_->set_body_and_spring_forces(state.x, state.v, masses_.weight, masses_.mass,
                                               settings_.air_damping, force_,
                                               split_state_is_current_, &hook);
  body_and_spring_power_ = {spring_families_->damper_power() + air_power, 0.0};
  const std::int64_t flagged =
      pass.finish(contact_totals_, keep_active_contacts_ ? &active_contacts_ : nullptr);
  const auto end = StepClock::now();
  using Seconds = std::chrono::duration<double>;
  stats_.seconds[static_cast<int>(StepPhase::springs)] += Seconds(turned - springs_start).count();
  stats_.seconds[static_cast<int>(StepPhase::contacts)] +=
      Seconds(springs_start - start).count() + Seconds(end - turned).count();
  return flagged;
}

void ForceEvaluator::add_edge_contact_totals() {
  if (!edge_contact_) return;
  for (std::size_t c = 0; c < contact_totals_.size(); ++c) {
    const EdgeContactTotals& edges = edge_contact_->totals()[c];
    ColliderContactTotals& total = contact_totals_[c];
    total.contact_count += edges.contact_count;
    total.normal_force += edges.normal_force;
    total.friction_force += edges.friction_force;
    total.max_depth = std::max(total.max_depth, edges.max_depth);
    total.force += edges.force;
    total.torque += edges.torque;
    total.power += edges.power;
  }
}

bool ForceEvaluator::runs_phase(StepPhase phase) const {
  for (const std::unique_ptr<ForceTerm>& term : pair_terms_)
    if (term->phase() == phase) return true;
  return false;
}

PowerSplit ForceEvaluator::power() const {
  PowerSplit power = body_and_spring_power_;
  power += pair_power_;
  power += scheme_power_;
  for (const ColliderContactTotals& total : contact_totals_) power += total.power;
  return power;
}

double ForceEvaluator::air_damping_power(const Eigen::Matrix3Xd& v) const {
  // Air damping -c m v takes c m |v|^2 from each particle.
  if (!(settings_.air_damping > 0.0)) return 0.0;
  return settings_.air_damping * (masses_.mass.array() * v.array().square()).sum();
}

const std::vector<ColliderForce>* ForceEvaluator::constraint_loads() const {
  return soft_constraints_ ? &soft_constraints_->collider_loads() : nullptr;
}

ContactNormalScheme ForceEvaluator::contact_normal_scheme() const {
  return contact_at_step_end(settings_.integrator) ? ContactNormalScheme::linearly_implicit
                                                   : ContactNormalScheme::explicit_penalty;
}

}  // namespace drapelab
