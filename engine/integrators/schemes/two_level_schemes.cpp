// The two-level explicit schemes: position Verlet and leapfrog, which carry a step of history.
#include "integrators/schemes/euler_schemes.hpp"

namespace drapelab {

TwoLevelScheme::TwoLevelScheme(const SchemeContext& context) : IntegratorScheme(context) {
  const int n = ctx_.model.particle_count();
  if (ctx_.settings.integrator == Integrator::verlet) previous_x_.resize(3, n);
  stage_v_.resize(3, n);
  acceleration_.resize(3, n);
}

std::optional<std::int64_t> TwoLevelScheme::step(double h) {
  if (ctx_.settings.integrator == Integrator::verlet)
    verlet_step(h);
  else
    leapfrog_step(h);
  return std::nullopt;
}

// Verlet, whose velocity is its position difference, takes its velocity from the projected
// positions (so the constraint's impulse stays in its history, as SHAKE does); leapfrog's stored
// end-of-step force was evaluated before the projection, so it evaluates the force afresh at the
// next step.
void TwoLevelScheme::positions_projected(double h) {
  if (ctx_.settings.integrator == Integrator::verlet)
    ctx_.state.v = (ctx_.state.x - previous_x_) / h + (0.5 * h) * acceleration_;
  else
    history_step_ = 0.0;
}

// Position (Stoermer) Verlet: x(n+1) = 2 x(n) - x(n-1) + h^2 a(n). The scheme itself carries no
// velocity, but damping, friction and the outputs need one; it is estimated as
//   v(n+1) = (x(n+1) - x(n)) / h + h/2 a(n),
// the mean velocity over the step advanced by half a step of the last known acceleration (second
// order; exact for a constant acceleration). The first step, or a step after h changed, starts from
// a Taylor step x(1) = x(0) + h v(0) + h^2/2 a(0), which makes free fall exact
// (docs/validation.md, V1).
void TwoLevelScheme::verlet_step(double h) {
  ClothState& state = ctx_.state;
  evaluate(state.x, state.v, state.time, h);
  acceleration_of_force(acceleration_);
  if (history_step_ != h) {
    previous_x_ =
        state.x - h * state.v + 0.5 * h * h * acceleration_;  // x(-1) from the same Taylor series
    history_step_ = h;
  }
  stage_x_ = state.x;  // x(n), kept while x(n+1) is written
  state.x = 2.0 * stage_x_ - previous_x_ + (h * h) * acceleration_;
  previous_x_ = stage_x_;
  state.v = (state.x - previous_x_) / h + (0.5 * h) * acceleration_;
}

// Leapfrog in kick-drift-kick form (velocity Verlet): v(n+1/2) = v(n) + h/2 a(n),
// x(n+1) = x(n) + h v(n+1/2), v(n+1) = v(n+1/2) + h/2 a(n+1). The end-of-step force is evaluated at
// the predicted velocity v(n) + h a(n) (damping needs a velocity there; the prediction is
// second-order accurate) and reused as the next step's first kick, so a step costs one force
// evaluation. With forces that do not depend on velocity this is exactly velocity Verlet,
// symplectic and time-reversible.
void TwoLevelScheme::leapfrog_step(double h) {
  ClothState& state = ctx_.state;
  const double t = state.time;
  if (history_step_ != h) {  // first step (or new h): a(n) from the current state
    evaluate(state.x, state.v, t, h);
    acceleration_of_force(acceleration_);
    history_step_ = h;
  }
  state.v.noalias() += (0.5 * h) * acceleration_;  // kick: v(n+1/2)
  state.x.noalias() += h * state.v;                // drift: x(n+1)
  stage_v_ = state.v + (0.5 * h) * acceleration_;  // predicted v(n+1) = v(n) + h a(n)
  evaluate(state.x, stage_v_, t + h, h);
  acceleration_of_force(acceleration_);
  state.v.noalias() += (0.5 * h) * acceleration_;  // kick: v(n+1)
}

}  // namespace drapelab
