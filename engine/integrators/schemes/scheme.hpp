// One integrator family as a unit of its own: its buffers and history, its step, what it does when
// the constraints' projection moves particles or the solver rewinds, and its part of the counters
// and of the advice an unstable run prints. The solver's step around it reads:
//   place pins, scheme.step, place pins, scheme.finish_step, project constraints, check health.
// make_scheme (make_scheme.cpp) builds the one the settings name.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/implicit_euler.hpp"
#include "drapelab/spring_damper_settings.hpp"
#include "drapelab/vertex_block_descent.hpp"
#include "integrators/force_evaluator.hpp"

namespace drapelab {

class FamilyImplicitSystem;
class OffsetContacts;

// What every scheme steps: the solver's model, settings, state and force evaluation.
struct SchemeContext {
  const ClothModel& model;
  const SpringDamperSettings& settings;
  ClothState& state;
  ForceEvaluator& forces;
};

using Counters = std::vector<std::pair<std::string, double>>;

class IntegratorScheme {
 public:
  explicit IntegratorScheme(const SchemeContext& context) : ctx_(context) {}
  virtual ~IntegratorScheme() = default;
  IntegratorScheme(const IntegratorScheme&) = delete;
  IntegratorScheme& operator=(const IntegratorScheme&) = delete;

  // Advances the state by h (s) from state.time, pinned particles held (state.time itself is the
  // solver's to advance). Returns the health scan of the new state (first_unhealthy_particle) when
  // the scheme made one as it wrote it.
  virtual std::optional<std::int64_t> step(double h) = 0;
  // After the pins are placed at the step's end. A scheme whose step evaluates no force at its
  // end state (vbd) evaluates the springs there, so the ledger and the attachments' loads see
  // the forces that act at the end.
  virtual void finish_step() {}
  // The constraints' projection moved particles at the step's end, before it projects their
  // velocities: a scheme whose velocity or stored force comes from positions updates them here.
  virtual void positions_projected(double /*h*/) {}
  // The solver went back to an earlier state: forget what the scheme carries between steps.
  virtual void forget_history() {}
  // The scheme's counters for summary.json (none by default).
  virtual Counters counters() const { return {}; }
  // Advice on the step for an unstable run's message ("a smaller dt ..., "), or empty: then the
  // stable step estimate's advice applies.
  virtual std::string step_advice() const { return {}; }
  // The implicit solves' statistics and systems (null for the other schemes).
  virtual const ImplicitSolveStats* implicit_stats() const { return nullptr; }
  virtual const ImplicitEulerSystem* implicit_system() const { return nullptr; }
  virtual const FamilyImplicitSystem* family_implicit_system() const { return nullptr; }
  virtual const VbdStats* vbd_stats() const { return nullptr; }
  // Self-contact the scheme handles inside its own solve (null: the force evaluation's, if any).
  virtual const OffsetContacts* offset_contacts() const { return nullptr; }

 protected:
  // a = f / m for the force just evaluated (zero on pinned particles).
  const Eigen::Matrix3Xd& acceleration_of_force(Eigen::Matrix3Xd& into) const {
    into.noalias() = ctx_.forces.force() * ctx_.model.inverse_mass.asDiagonal();
    return into;
  }
  // The whole force at (x, v) and time t (s), friction sized for h (s).
  const Eigen::Matrix3Xd& evaluate(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, double t,
                                   double h) {
    return ctx_.forces.evaluate(x, v, t, h);
  }

  SchemeContext ctx_;
};

// The scheme of settings.integrator (throws std::invalid_argument when it cannot run the model).
std::unique_ptr<IntegratorScheme> make_scheme(const SchemeContext& context);

}  // namespace drapelab
