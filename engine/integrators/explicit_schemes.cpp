// The multi-stage (midpoint, RK4) and two-level (Verlet, leapfrog) explicit schemes of our solver.
// Every stage evaluates the full force (springs, air, contacts with friction) at the stage's state
// and time, so colliders move within the step as they do for every other scheme. Pinned particles
// have zero acceleration and zero velocity, so every update below leaves them where they are.
#include "drapelab/spring_damper_solver.hpp"

namespace drapelab {

// Explicit midpoint (RK2): a half step of Euler finds (xm, vm); the full step uses their slopes.
void SpringDamperSolver::midpoint_step(double h) {
  const double t = state_.time;
  evaluate_forces(state_.x, state_.v, t, h);
  acceleration_of_force(acceleration_);
  stage_x_ = state_.x + 0.5 * h * state_.v;       // xm = x + h/2 v
  stage_v_ = state_.v + 0.5 * h * acceleration_;  // vm = v + h/2 a(x, v)
  evaluate_forces(stage_x_, stage_v_, t + 0.5 * h, h);
  acceleration_of_force(acceleration_);
  state_.x.noalias() += h * stage_v_;       // x1 = x + h vm
  state_.v.noalias() += h * acceleration_;  // v1 = v + h a(xm, vm)
}

// Classic RK4 on (x, v)' = (v, a(x, v)): slopes k1..k4 weighted 1, 2, 2, 1.
void SpringDamperSolver::rk4_step(double h) {
  const double t = state_.time;
  // k1 at the start.
  evaluate_forces(state_.x, state_.v, t, h);
  acceleration_of_force(acceleration_);
  sum_x_ = state_.v;
  sum_v_ = acceleration_;
  // k2 and k3 at the midpoint, each from the previous slope.
  stage_x_ = state_.x + 0.5 * h * state_.v;
  stage_v_ = state_.v + 0.5 * h * acceleration_;
  for (int half_stage = 0; half_stage < 2; ++half_stage) {
    evaluate_forces(stage_x_, stage_v_, t + 0.5 * h, h);
    acceleration_of_force(acceleration_);
    sum_x_.noalias() += 2.0 * stage_v_;
    sum_v_.noalias() += 2.0 * acceleration_;
    const double reach = half_stage == 0 ? 0.5 * h : h;  // k3 steps half, k4 steps whole
    stage_x_ = state_.x + reach * stage_v_;
    stage_v_ = state_.v + reach * acceleration_;
  }
  // k4 at the end.
  evaluate_forces(stage_x_, stage_v_, t + h, h);
  acceleration_of_force(acceleration_);
  sum_x_.noalias() += stage_v_;
  sum_v_.noalias() += acceleration_;
  state_.x.noalias() += (h / 6.0) * sum_x_;
  state_.v.noalias() += (h / 6.0) * sum_v_;
}

// Position (Stoermer) Verlet: x(n+1) = 2 x(n) - x(n-1) + h^2 a(n). The scheme itself carries no
// velocity, but damping, friction and the outputs need one; it is estimated as
//   v(n+1) = (x(n+1) - x(n)) / h + h/2 a(n),
// the mean velocity over the step advanced by half a step of the last known acceleration (second
// order; exact for a constant acceleration). The first step, or a step after h changed, starts from
// a Taylor step x(1) = x(0) + h v(0) + h^2/2 a(0), which makes free fall exact
// (docs/validation.md, V1).
void SpringDamperSolver::verlet_step(double h) {
  evaluate_forces(state_.x, state_.v, state_.time, h);
  acceleration_of_force(acceleration_);
  if (two_level_step_ != h) {
    previous_x_ =
        state_.x - h * state_.v + 0.5 * h * h * acceleration_;  // x(-1) from the same Taylor series
    two_level_step_ = h;
  }
  stage_x_ = state_.x;  // x(n), kept while x(n+1) is written
  state_.x = 2.0 * stage_x_ - previous_x_ + (h * h) * acceleration_;
  previous_x_ = stage_x_;
  state_.v = (state_.x - previous_x_) / h + (0.5 * h) * acceleration_;
}

// Leapfrog in kick-drift-kick form (velocity Verlet): v(n+1/2) = v(n) + h/2 a(n),
// x(n+1) = x(n) + h v(n+1/2), v(n+1) = v(n+1/2) + h/2 a(n+1). The end-of-step force is evaluated at
// the predicted velocity v(n) + h a(n) (damping needs a velocity there; the prediction is
// second-order accurate) and reused as the next step's first kick, so a step costs one force
// evaluation. With forces that do not depend on velocity this is exactly velocity Verlet,
// symplectic and time-reversible.
void SpringDamperSolver::leapfrog_step(double h) {
  const double t = state_.time;
  if (two_level_step_ != h) {  // first step (or new h): a(n) from the current state
    evaluate_forces(state_.x, state_.v, t, h);
    acceleration_of_force(acceleration_);
    two_level_step_ = h;
  }
  state_.v.noalias() += (0.5 * h) * acceleration_;  // kick: v(n+1/2)
  state_.x.noalias() += h * state_.v;               // drift: x(n+1)
  stage_v_ = state_.v + (0.5 * h) * acceleration_;  // predicted v(n+1) = v(n) + h a(n)
  evaluate_forces(state_.x, stage_v_, t + h, h);
  acceleration_of_force(acceleration_);
  state_.v.noalias() += (0.5 * h) * acceleration_;  // kick: v(n+1)
}

}  // namespace drapelab
