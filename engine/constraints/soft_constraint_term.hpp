// The soft distance constraints and drags as a force term of the solver's evaluation
// (core/force_term.hpp): spring-dampers between particles and points, couplings of the implicit
// solves, and the reactions on dynamic colliders.
#pragma once

#include <vector>

#include "core/force_term.hpp"
#include "drapelab/distance_constraints.hpp"

namespace drapelab {

class SoftConstraintTerm final : public ForceTerm {
 public:
  // `constraints` must outlive the term (the solver's settings hold it).
  explicit SoftConstraintTerm(const DistanceConstraints& constraints);
  const char* name() const override { return "soft_constraints"; }
  StepPhase phase() const override { return StepPhase::soft_constraints; }
  void add(const ForceArgs& at, ForceSink& out) override;

  // The last evaluation's reactions per collider (empty unless some constraint ends on a dynamic
  // collider): the force on each (N) and its moment about the world origin (N*m).
  const std::vector<ColliderForce>& collider_loads() const { return loads_; }

 private:
  const DistanceConstraints& constraints_;
  bool on_bodies_ = false;  // some constraint ends on a dynamic collider
  std::vector<ColliderForce> loads_;
};

}  // namespace drapelab
