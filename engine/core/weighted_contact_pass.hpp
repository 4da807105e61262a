// The penalty pushes and then the Coulomb friction of a set of weighted contacts, in one pass that
// both the self contacts (self_contact.cpp) and a collider's edges and corners against the cloth
// (edge_contact.cpp) run, so that the push, its damper, the friction and their power
// (energy_ledger.hpp) are written once.
//
// A contact's point on the cloth is sum_j w_j x_j (weighted_contact.hpp); with u its velocity
// relative to the other side (sum_j w_j v_j, less the collider surface's velocity when there is
// one) it takes the push fn = max(0, k depth - c n . u) along its normal n, w_j fn n on particle j.
// An explicit scheme (no list of active contacts) takes k and c bounded for its step, each contact
// by its load (explicit_contact_bound.hpp); the implicit solves take the pushing contacts as
// WeightedContact and use k and c as they are. Friction then runs one contact after another from
// the forces with every push in (a Gauss-Seidel sweep), weighted_contact_friction on the point's
// effective mass: each contact sees the friction of those before it, so a particle held by several
// contacts is not stopped several times over (which would reverse it, and grow).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "core/explicit_contact_bound.hpp"
#include "drapelab/energy_ledger.hpp"
#include "drapelab/weighted_contact.hpp"

namespace drapelab {

// One contact as the pass takes it.
struct WeightedContactPoint {
  std::array<int, 4> particle{-1, -1, -1, -1};        // -1: unused slot
  std::array<double, 4> weight{};                     // dimensionless
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // unit: the direction the push acts along
  double depth = 0.0;                                 // m, inside the contact distance when > 0
  Eigen::Vector3d surface_velocity = Eigen::Vector3d::Zero();  // m/s, the collider's surface there
  double static_friction = 0.0;                                // Coulomb coefficients
  double kinetic_friction = 0.0;
  int group = 0;  // the totals it adds to: its collider's index, 0 for self contacts
};

// Where the two kinds of contact still take different rules, each kept here as it was so that
// either kind's results keep their bits.
struct WeightedContactRules {
  // The other side is a collider's surface moving at each contact's surface_velocity, which the
  // relative velocities subtract (collider edges); otherwise both sides are particles of the
  // contact and the relative velocity is the weighted sum alone (self contacts).
  bool against_surface = false;
  // A contact whose particles are all pinned (no effective mass) takes no push (collider edges).
  bool skip_pinned = false;
  // No push at all at zero or negative depth, even from a closing damper (self contacts:
  // pair_penalty.hpp's law); otherwise penalty_normal_force's (collider edges).
  bool push_needs_overlap = false;
  // The push's power is counted wherever the contact overlaps, also where it is clamped to zero
  // (self contacts, as at the particle contacts); otherwise only while it pushes (collider edges).
  bool power_of_clamped_push = false;
  // No friction where the static coefficient is zero (self contacts, as at the particle contacts).
  bool friction_needs_static = false;
};

// What the pass did to one group of contacts.
struct WeightedContactTotals {
  std::int64_t pushing = 0;     // contacts that pushed
  double normal_force = 0.0;    // N, sum of fn
  double friction_force = 0.0;  // N, sum of |friction|
  // J: sum of k depth^2 / 2 over the contacts the pass took that overlap (k unbounded).
  double spring_energy = 0.0;
  PowerSplit power;  // W: what the pushes beyond their springs and the friction did
};

// What the pass did at one contact.
struct WeightedContactOutcome {
  double push = 0.0;                                   // N, fn (0: it did not push)
  bool rubbed = false;                                 // whether friction was applied
  Eigen::Vector3d friction = Eigen::Vector3d::Zero();  // N, on the contact's point
};

class WeightedContactPass {
 public:
  explicit WeightedContactPass(int particle_count = 0) : loads_(particle_count) {}

  // Adds the pushes and then the friction of `contacts` at velocities v (m/s) to `force` (N), which
  // must hold every other force friction is to see (it is sized for a step of h s from it).
  // `stiffness` N/m and `damping` N*s/m are the penalty's k and c, `inverse_mass` 1/kg per
  // particle. Pushing contacts are appended to `active` when given; without it the pushes are
  // bounded for an explicit step of h. `totals`, one per group, are overwritten.
  void run(const std::vector<WeightedContactPoint>& contacts, const WeightedContactRules& rules,
           double stiffness, double damping, double h, const Eigen::Matrix3Xd& v,
           const Eigen::VectorXd& inverse_mass, Eigen::Matrix3Xd& force,
           std::vector<WeightedContact>* active, std::vector<WeightedContactTotals>& totals);

  // Per contact of the last run, in its order.
  const std::vector<WeightedContactOutcome>& outcomes() const { return outcome_; }

 private:
  ContactLoads loads_;  // contacts per particle, for the explicit schemes' bound
  std::vector<WeightedContactOutcome> outcome_;
};

}  // namespace drapelab
