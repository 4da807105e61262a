// The health check after every step: a non-finite or runaway particle stops the solver with a
// message naming the particle, the step, what acted on it, and what to try.
#include <cmath>
#include <sstream>

#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/stability.hpp"
#include "integrators/force_evaluator.hpp"
#include "integrators/particle_loops.hpp"
#include "integrators/schemes/scheme.hpp"
#include "integrators/unstable_cause.hpp"
#include "self_collision/self_contact.hpp"

namespace drapelab {

// Runs every step over particles only (O(N)); the message is built only on failure.
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
  const Integrator integrator = settings_.integrator;

  std::ostringstream text;
  text.precision(4);
  text << model_->describe_particle(i);
  if (!finite)
    text << " has a non-finite position or velocity";
  else
    text << " moves at " << std::sqrt(speed_squared) << " m/s, above the runaway limit of "
         << settings_.max_speed << " m/s";
  text << " after step " << state_.step_count << " (t = " << state_.time << " s, dt = " << h
       << " s, integrator " << integrator_name(integrator) << ").";
  // What acted in that step, by kind: the colliders touched (and how deep), self-contacts, and the
  // constraints and drags on the particle.
  StepContactsSeen seen;
  seen.colliders = settings_.contacts.get();
  seen.totals = &forces_->contact_totals();
  seen.edge_totals = forces_->edge_contact() ? &forces_->edge_contact()->totals() : nullptr;
  seen.self_contacts = self_contact_stats() ? self_contact_stats()->contacts_last : -1;
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
      stable_step_estimate(*model_, settings_.air_damping, contact, integrator);
  const bool contact_bounds_step = !contact_at_step_end(integrator);
  const NetworkRates rates = network_rate_bounds(*model_, settings_.air_damping,
                                                 contact_bounds_step ? contact : ContactRates{});
  // The schemes unstable on an undamped spring (explicit Euler, midpoint) and those stable on
  // every step (implicit Euler, vbd) need other advice than the conditionally stable ones.
  const double limit = undamped_stability_limit(integrator);
  const bool unstable_undamped = limit == 0.0;
  const bool unconditional = std::isinf(limit);
  if (unstable_undamped)
    text << "integrator symplectic_euler, leapfrog or implicit_euler ("
         << integrator_name(integrator)
         << " gains energy on every undamped spring and is stable only while damping outweighs "
            "it), ";
  const std::string advice = scheme_->step_advice();
  if (!advice.empty())
    text << advice;
  else if (stable_step > 0.0 && std::isfinite(stable_step) && stable_step < h)
    text << "a smaller dt (the Gershgorin bound of these springs and dampers"
         << (contact_bounds_step ? " and of the contact" : "") << " gives a stable "
         << integrator_name(integrator) << " step below about " << stable_step << " s), ";
  else if (std::isfinite(stable_step) && stable_step >= h)
    text << "a smaller dt (dt is inside the springs' stable step of about " << stable_step
         << " s, so a contact or a fast collider is the likely cause: try half the dt, or a softer "
            "contact), ";
  // In h^2 K + 2 h C < 4, the larger term says whether springs or dampers limit the step.
  if (unconditional)
    text << "or a softer contact (lower contact.stiffness).";
  else if (unstable_undamped)
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
