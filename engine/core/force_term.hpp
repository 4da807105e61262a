// One force of our solver's evaluation, as a unit the evaluator runs in its fixed order: it adds
// its force to the particles, reports its power to the energy ledger, and, for the integrators
// that solve for them (implicit Euler, vbd), hands over its contacts as couplings. Gravity with the
// springs (or the continuum) come first and the collider contacts last; the terms between them
// are listed once, in integrators/force_evaluator.cpp.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "drapelab/energy_ledger.hpp"
#include "drapelab/step_stats.hpp"
#include "drapelab/weighted_contact.hpp"

namespace drapelab {

// Where a term evaluates its force: the particles' state at time t, for a step of h.
struct ForceArgs {
  const Eigen::Matrix3Xd& x;  // m, 3 x N
  const Eigen::Matrix3Xd& v;  // m/s, 3 x N
  double t = 0.0;             // s
  double h = 0.0;             // s: the step friction and damping are sized for
};

// What a term writes: its force added to `force`, its power, and its couplings when asked.
struct ForceSink {
  Eigen::Matrix3Xd& force;                  // N, 3 x N, added to
  std::vector<WeightedContact>* couplings;  // null unless the integrator solves for them
  PowerSplit power;                         // W, this term's alone
};

class ForceTerm {
 public:
  virtual ~ForceTerm() = default;
  // The name the term is known by (the phase's report, the docs' term list).
  virtual const char* name() const = 0;
  // The phase of the step statistics its time is counted under.
  virtual StepPhase phase() const = 0;
  virtual void add(const ForceArgs& at, ForceSink& out) = 0;
};

}  // namespace drapelab
