// What our solver reports beside its state: the phases' times, the counters, the loads on the
// colliders, and views of its machinery for tests.
#include "drapelab/spring_damper_solver.hpp"
#include "forces/spring_families.hpp"
#include "integrators/force_evaluator.hpp"
#include "integrators/schemes/scheme.hpp"
#include "self_collision/offset_contacts.hpp"
#include "self_collision/self_contact.hpp"

namespace drapelab {
namespace {

// The phases of the force terms between particles, reported only when the solver has the term.
bool is_pair_term_phase(StepPhase phase) {
  return phase == StepPhase::self_contacts || phase == StepPhase::collider_edges ||
         phase == StepPhase::soft_constraints || phase == StepPhase::air;
}

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
    case StepPhase::collider_edges:
      return "collider_edges";
    case StepPhase::soft_constraints:
      return "soft_constraints";
    case StepPhase::air:
      return "air";
    case StepPhase::count:
      break;
  }
  return "unknown";
}

std::vector<std::string> SpringDamperSolver::force_terms() const { return forces_->term_names(); }

const SelfContact* SpringDamperSolver::self_contact() const { return forces_->self_contact(); }

const SelfContactStats* SpringDamperSolver::self_contact_stats() const {
  if (forces_->self_contact()) return &forces_->self_contact()->stats();
  if (const OffsetContacts* offset = scheme_->offset_contacts()) return &offset->stats();
  return nullptr;
}

const std::vector<ColliderContactTotals>& SpringDamperSolver::contact_totals() const {
  return forces_->contact_totals();
}

const ImplicitEulerSystem* SpringDamperSolver::implicit_system() const {
  return scheme_->implicit_system();
}

const FamilyImplicitSystem* SpringDamperSolver::family_implicit_system() const {
  return scheme_->family_implicit_system();
}

const ImplicitSolveStats* SpringDamperSolver::implicit_stats() const {
  return scheme_->implicit_stats();
}

const VbdStats* SpringDamperSolver::vbd_stats() const { return scheme_->vbd_stats(); }

bool SpringDamperSolver::uses_fast_springs() const { return forces_->spring_families() != nullptr; }

std::optional<double> SpringDamperSolver::self_contact_energy() const {
  const SelfContactStats* self = self_contact_stats();
  if (!self) return std::nullopt;
  return self->spring_energy_last;
}

std::vector<ColliderForce> SpringDamperSolver::collider_forces() const {
  std::vector<ColliderForce> forces;
  for (const auto& total : forces_->contact_totals())
    forces.push_back({total.normal_force, total.friction_force, total.force, total.torque});
  const auto add = [&forces](const std::vector<ColliderForce>& loads) {
    if (forces.size() < loads.size()) forces.resize(loads.size());
    for (std::size_t c = 0; c < loads.size(); ++c) {
      forces[c].force += loads[c].force;
      forces[c].torque += loads[c].torque;
    }
  };
  add(attachment_loads_);
  if (const std::vector<ColliderForce>* loads = forces_->constraint_loads()) add(*loads);
  return forces;
}

std::vector<std::pair<std::string, double>> SpringDamperSolver::phase_seconds() const {
  std::vector<std::pair<std::string, double>> phases;
  for (int p = 0; p < static_cast<int>(StepPhase::count); ++p) {
    const auto phase = static_cast<StepPhase>(p);
    if (phase == StepPhase::step_bound && !settings_.adaptive_substeps) continue;
    // vbd times its own self-contact detections under the self-contacts' phase.
    const bool scheme_runs = phase == StepPhase::self_contacts && scheme_->offset_contacts();
    if (is_pair_term_phase(phase) && !forces_->runs_phase(phase) && !scheme_runs) continue;
    phases.emplace_back(step_phase_name(phase), stats_.seconds[p]);
  }
  return phases;
}

std::vector<std::pair<std::string, double>> SpringDamperSolver::counters() const {
  std::vector<std::pair<std::string, double>> all = scheme_counters();
  if (const SelfContactStats* found = self_contact_stats()) {
    const SelfContactStats& self = *found;
    all.insert(
        all.end(),
        {{"self_contacts_last", static_cast<double>(self.contacts_last)},
         {"self_contacts_mean", self.evaluations > 0 ? static_cast<double>(self.contacts_total) /
                                                           static_cast<double>(self.evaluations)
                                                     : 0.0},
         {"self_collision_searches", static_cast<double>(self.rebuilds)},
         {"self_collision_candidates_last", static_cast<double>(self.candidates)}});
    if (const OffsetContacts* offset = scheme_->offset_contacts())
      all.insert(all.end(),
                 {{"self_collision_truncations", static_cast<double>(self.truncations)},
                  {"self_collision_smallest_gap_last", offset->last_totals().smallest_gap}});
    else
      all.insert(all.end(),
                 {{"self_collision_split_steps", static_cast<double>(stats_.split_steps)},
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
  return scheme_->counters();
}

double SpringDamperSolver::force_phase_seconds() const {
  double total = 0.0;
  for (StepPhase phase : {StepPhase::body_forces, StepPhase::springs, StepPhase::contacts})
    total += stats_.seconds[static_cast<int>(phase)];
  for (int p = 0; p < static_cast<int>(StepPhase::count); ++p)
    if (is_pair_term_phase(static_cast<StepPhase>(p))) total += stats_.seconds[p];
  return total;
}

}  // namespace drapelab
