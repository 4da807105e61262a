// The cloth against itself as a force term of the solver's evaluation (core/force_term.hpp): the
// self-contacts' penalty push and friction, their dissipation, and their couplings.
#pragma once

#include <Eigen/Core>

#include "core/force_term.hpp"
#include "self_collision/self_contact.hpp"

namespace drapelab {

class SelfContactTerm final : public ForceTerm {
 public:
  SelfContactTerm(const ClothModel& model, const SelfCollisionSettings& settings);
  const char* name() const override { return "self_contacts"; }
  StepPhase phase() const override { return StepPhase::self_contacts; }
  void add(const ForceArgs& at, ForceSink& out) override;

  const SelfContact& contact() const { return contact_; }

 private:
  const Eigen::VectorXd& inverse_mass_;  // 1/kg per particle, the model's
  SelfContact contact_;
};

}  // namespace drapelab
