// The pushes and the friction of weighted contacts (weighted_contact_pass.hpp).
#include "core/weighted_contact_pass.hpp"

#include <algorithm>

#include "core/pair_penalty.hpp"
#include "core/penalty_contact.hpp"

namespace drapelab {

void WeightedContactPass::run(const std::vector<WeightedContactPoint>& contacts,
                              const WeightedContactRules& rules, double stiffness, double damping,
                              double h, const Eigen::Matrix3Xd& v,
                              const Eigen::VectorXd& inverse_mass, Eigen::Matrix3Xd& force,
                              std::vector<WeightedContact>* active,
                              std::vector<WeightedContactTotals>& totals) {
  std::fill(totals.begin(), totals.end(), WeightedContactTotals{});
  outcome_.assign(contacts.size(), WeightedContactOutcome{});
  // Where the relative velocity of a contact's point starts (m/s): minus the surface's velocity,
  // or nothing between two parts of the cloth (a zero, not a negated zero, keeps those bits).
  const auto relative_start = [&rules](const WeightedContactPoint& contact) {
    return rules.against_surface ? Eigen::Vector3d(-contact.surface_velocity)
                                 : Eigen::Vector3d(Eigen::Vector3d::Zero());
  };
  // Every contact's push at once, so that friction below sees all of them.
  const bool bounded = active == nullptr;
  if (bounded) {
    loads_.clear();
    for (const WeightedContactPoint& contact : contacts)
      loads_.add(contact.particle, contact.weight);
  }
  for (std::size_t e = 0; e < contacts.size(); ++e) {
    const WeightedContactPoint& contact = contacts[e];
    Eigen::Vector3d u = relative_start(contact);  // m/s, the cloth point relative to the other side
    double inverse_effective_mass = 0.0;          // 1/kg
    for (int s = 0; s < 4; ++s)
      if (contact.particle[s] >= 0) {
        const int j = contact.particle[s];
        u += contact.weight[s] * v.col(j);
        inverse_effective_mass += contact.weight[s] * contact.weight[s] * inverse_mass[j];
      }
    if (rules.skip_pinned && !(inverse_effective_mass > 0.0)) continue;
    const PenaltyRates rates =
        bounded ? step_bounded_penalty(stiffness, damping, inverse_effective_mass,
                                       loads_.load(contact.particle, contact.weight), h)
                : PenaltyRates{stiffness, damping};
    const double normal_velocity = contact.normal.dot(u);  // m/s, > 0 separating
    const double fn =
        rules.push_needs_overlap
            ? pair_push(contact.depth, normal_velocity, rates.stiffness, rates.damping)
            : penalty_normal_force(contact.depth, normal_velocity, rates.stiffness, rates.damping);
    WeightedContactTotals& total = totals[static_cast<std::size_t>(contact.group)];
    const bool overlaps = contact.depth > 0.0;
    if (overlaps) total.spring_energy += 0.5 * stiffness * contact.depth * contact.depth;
    // The push's power beside its spring's k depth (unbounded: the potential's force).
    const auto add_push_power = [&] {
      total.power +=
          push_power(fn, stiffness * contact.depth, contact.normal, u, contact.surface_velocity);
    };
    if (rules.power_of_clamped_push && overlaps) add_push_power();
    if (fn <= 0.0) continue;
    outcome_[e].push = fn;
    for (int s = 0; s < 4; ++s)
      if (contact.particle[s] >= 0)
        force.col(contact.particle[s]) += (contact.weight[s] * fn) * contact.normal;
    ++total.pushing;
    total.normal_force += fn;
    if (!rules.power_of_clamped_push) add_push_power();
    if (active) {
      WeightedContact w;
      w.particle = contact.particle;
      w.weight = contact.weight;
      w.normal = contact.normal;
      w.stiffness = stiffness;
      w.damping = damping;
      w.depth = contact.depth;
      w.force = fn;
      // A moving collider surface moves the contact's far end: the depth grows at n . its velocity.
      if (rules.against_surface) w.end_rate = contact.normal.dot(contact.surface_velocity);
      active->push_back(w);
    }
  }
  // Friction one contact after another, each seeing the friction before it. Each contact's
  // friction sums to zero over its particles when its weights do, as its push does.
  if (!(h > 0.0)) return;
  for (std::size_t e = 0; e < contacts.size(); ++e) {
    const double fn = outcome_[e].push;  // N
    if (fn <= 0.0) continue;
    const WeightedContactPoint& contact = contacts[e];
    if (rules.friction_needs_static && !(contact.static_friction > 0.0)) continue;
    double inverse_effective_mass = 0.0;              // 1/kg
    Eigen::Vector3d trial = relative_start(contact);  // m/s, after a step of h without friction
    Eigen::Vector3d relative_velocity = relative_start(contact);  // m/s, of the cloth point
    for (int s = 0; s < 4; ++s) {
      const int j = contact.particle[s];
      if (j < 0) continue;
      const double w = contact.weight[s];
      inverse_effective_mass += w * w * inverse_mass[j];
      trial += w * (v.col(j) + h * inverse_mass[j] * force.col(j));
      relative_velocity += w * v.col(j);
    }
    if (inverse_effective_mass <= 0.0) continue;
    const FrictionForce friction =
        weighted_contact_friction(trial, contact.normal, inverse_effective_mass, h, fn,
                                  contact.static_friction, contact.kinetic_friction);
    for (int s = 0; s < 4; ++s)
      if (contact.particle[s] >= 0)
        force.col(contact.particle[s]) += contact.weight[s] * friction.force;
    WeightedContactTotals& total = totals[static_cast<std::size_t>(contact.group)];
    total.friction_force += friction.magnitude;
    total.power += friction_power(friction.force, relative_velocity, contact.surface_velocity);
    outcome_[e].rubbed = true;
    outcome_[e].friction = friction.force;
  }
}

}  // namespace drapelab
