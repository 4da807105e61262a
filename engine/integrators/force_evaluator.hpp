// Our solver's force evaluation: every force term in a fixed, named order, each timed under its
// phase, with the buffers the terms write and the power they report.
//
//   1. body and springs: gravity, air damping and the springs (or the continuum's elements),
//      overwriting the force buffer
//   2. the terms between particles, in the order of make_pair_terms: self_contacts,
//      collider_edges, soft_constraints, air (each only when the scene has it)
//   3. collider contacts: penalty push and friction of every collider on the particles
//
// The Euler pair fuses phases 1 and 3 with its update where it can (euler_scheme.cpp); the order
// of every floating-point sum stays this one.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/force_term.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/spring_damper_settings.hpp"
#include "drapelab/step_stats.hpp"

namespace drapelab {

class SpringFamilies;
class SelfContact;
class EdgeContact;
class SoftConstraintTerm;
struct ContactWorkspace;
struct ContactBlockFollowUp;

// The particles' masses packed like the force buffer (3 x N, one row per coordinate), so the
// per-particle passes run over unit-stride arrays.
struct CoordinateMasses {
  Eigen::Matrix3Xd mass;          // kg: m_i in each of particle i's three rows
  Eigen::Matrix3Xd inverse_mass;  // 1/kg: 1/m_i, 0 for a pinned particle
  Eigen::Matrix3Xd weight;        // N: m_i g
};

class ForceEvaluator {
 public:
  // `solver_state` is the solver's own state: an evaluation at it may reuse the spring kernel's
  // split copy. Every reference must outlive the evaluator.
  ForceEvaluator(const ClothModel& model, const SpringDamperSettings& settings,
                 const ClothState& solver_state, StepStats& stats);
  ~ForceEvaluator();
  ForceEvaluator(const ForceEvaluator&) = delete;
  ForceEvaluator& operator=(const ForceEvaluator&) = delete;

  // The whole force (N, 3 x N) at (x, v) and time t (s), friction sized for a step of h (s).
  const Eigen::Matrix3Xd& evaluate(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, double t,
                                   double h);

  // The phases on their own, for the schemes that run them apart or fused with their update:
  // phase 1 (overwrites the buffer), phase 2 (adds), phase 3 (adds; `follow_up` runs on each block
  // of particles once its force is final and its flag is returned).
  void set_body_and_spring_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v);
  void add_pair_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, double t, double h);
  std::int64_t add_contact_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, double t,
                                  double h, const ContactBlockFollowUp* follow_up);
  // Phases 1 and 3 at the solver's state in one parallel region (the spring fast path with
  // colliders and no pair terms): each thread runs the contact blocks of its own particles as soon
  // as their spring forces are final, then `follow_up` on them.
  std::int64_t spring_and_contact_forces_together(double t, double h,
                                                  const ContactBlockFollowUp& follow_up);

  // The evaluation's terms in the order it runs them: body_and_springs, the pair terms present,
  // collider_contacts (with colliders).
  std::vector<std::string> term_names() const;
  // Whether a term between particles is timed under `phase`.
  bool runs_phase(StepPhase phase) const;

  Eigen::Matrix3Xd& force() { return force_; }
  const Eigen::Matrix3Xd& force() const { return force_; }
  const CoordinateMasses& masses() const { return masses_; }
  // The spring-family fast path (null: the plain edge-list loop, or the continuum).
  SpringFamilies* spring_families() const { return spring_families_.get(); }
  bool has_pair_terms() const { return !pair_terms_.empty(); }
  bool has_colliders() const { return settings_.contacts != nullptr; }
  // The spring kernel's unit-stride copy of the state equals the solver's state: set by the Euler
  // update that splits each block as it writes it, cleared by every other change of the state.
  void set_split_state_current(bool current) { split_state_is_current_ = current; }

  // The last evaluation's results.
  const std::vector<ColliderContactTotals>& contact_totals() const { return contact_totals_; }
  std::vector<ColliderContactTotals>& contact_totals() { return contact_totals_; }
  // Adds the collider edges' totals to the particle contacts' of the same evaluation.
  void add_edge_contact_totals();
  // Pushing collider contacts (implicit Euler) and contacts between particles (implicit Euler and
  // vbd) of the last evaluation.
  const std::vector<ActiveContact>& active_contacts() const { return active_contacts_; }
  std::vector<WeightedContact>& couplings() { return couplings_; }
  // Power of the last evaluation (W): every phase's, the collider contacts' included.
  PowerSplit power() const;
  // Power of forces a scheme evaluates inside its own solve (W), counted with the last
  // evaluation's.
  void set_scheme_power(const PowerSplit& power) { scheme_power_ = power; }
  // Wall time (s) a scheme spent on a phase inside its own solve.
  void add_phase_seconds(StepPhase phase, double seconds) {
    stats_.seconds[static_cast<int>(phase)] += seconds;
  }
  // The power air damping takes at velocities v (W), c sum m |v|^2.
  double air_damping_power(const Eigen::Matrix3Xd& v) const;

  const SelfContact* self_contact() const { return self_contact_; }
  const EdgeContact* edge_contact() const { return edge_contact_; }
  // The soft constraints' reactions on dynamic colliders (null without soft constraints).
  const std::vector<ColliderForce>* constraint_loads() const;
  // How the collider contact takes its normal force: at the step's end for symplectic Euler.
  ContactNormalScheme contact_normal_scheme() const;

 private:
  const ClothModel& model_;
  const SpringDamperSettings& settings_;
  const ClothState& solver_state_;
  StepStats& stats_;
  Eigen::Matrix3Xd force_;  // N, 3 x N
  CoordinateMasses masses_;
  std::unique_ptr<SpringFamilies> spring_families_;
  // cloth.model: continuum: each element's force before the per-particle sums (9 per triangle, 12
  // per hinge, N); empty for springs.
  std::vector<double> continuum_element_force_;
  bool split_state_is_current_ = false;
  // Phase 2's terms in their order, and typed views of those the solver reports on.
  std::vector<std::unique_ptr<ForceTerm>> pair_terms_;
  const SelfContact* self_contact_ = nullptr;
  const EdgeContact* edge_contact_ = nullptr;
  const SoftConstraintTerm* soft_constraints_ = nullptr;
  std::unique_ptr<ContactWorkspace> contact_workspace_;
  std::vector<ColliderContactTotals> contact_totals_;
  bool keep_active_contacts_ = false;  // implicit Euler
  bool keep_couplings_ = false;        // implicit Euler and vbd
  std::vector<ActiveContact> active_contacts_;
  std::vector<WeightedContact> couplings_;
  // Phase 1's and phase 2's power (W); the collider contacts' is in contact_totals_.
  PowerSplit body_and_spring_power_, pair_power_, scheme_power_;
};

}  // namespace drapelab
