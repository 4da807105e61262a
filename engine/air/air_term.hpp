// Aerodynamic drag and lift on the triangles as a force term of the solver's evaluation
// (core/force_term.hpp). Explicit in every scheme: implicit Euler and vbd take it at the step's
// start, its rate rho C_d A |u_n| / m being far below their steps' limits for cloth in air.
#pragma once

#include "core/force_term.hpp"
#include "drapelab/air.hpp"
#include "drapelab/cloth_model.hpp"

namespace drapelab {

class AirTerm final : public ForceTerm {
 public:
  // `model` and `air` must outlive the term (the solver holds both).
  AirTerm(const ClothModel& model, const AirSettings& air);
  const char* name() const override { return "air"; }
  StepPhase phase() const override { return StepPhase::air; }
  void add(const ForceArgs& at, ForceSink& out) override;

 private:
  const ClothModel& model_;
  const AirSettings& air_;
  Wind wind_;  // the wind over time
};

}  // namespace drapelab
