// The colliders' sharp edges and corners against the cloth's edges and triangles as a force term
// of the solver's evaluation (core/force_term.hpp). Its totals join the particle contacts' per
// collider after the contact phase.
#pragma once

#include <Eigen/Core>

#include "contact/edge_contact.hpp"
#include "core/force_term.hpp"

namespace drapelab {

class EdgeContactTerm final : public ForceTerm {
 public:
  // `contacts` must outlive the term (the solver's settings hold it).
  EdgeContactTerm(const ClothModel& model, const ContactModel& contacts);
  const char* name() const override { return "collider_edges"; }
  StepPhase phase() const override { return StepPhase::collider_edges; }
  void add(const ForceArgs& at, ForceSink& out) override;

  // Whether any collider has sharp features (a term without them is left out).
  bool active() const { return contact_.active(); }
  const EdgeContact& contact() const { return contact_; }

 private:
  const ContactModel& contacts_;
  const Eigen::VectorXd& inverse_mass_;  // 1/kg per particle, the model's
  EdgeContact contact_;
};

}  // namespace drapelab
