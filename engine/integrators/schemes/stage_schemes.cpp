// The multi-stage explicit schemes: the midpoint rule (RK2) and classic RK4.
#include "integrators/schemes/euler_schemes.hpp"

namespace drapelab {

StageScheme::StageScheme(const SchemeContext& context) : IntegratorScheme(context) {
  const int n = ctx_.model.particle_count();
  stage_x_.resize(3, n);
  stage_v_.resize(3, n);
  acceleration_.resize(3, n);
  if (ctx_.settings.integrator == Integrator::rk4) {
    sum_x_.resize(3, n);
    sum_v_.resize(3, n);
  }
}

std::optional<std::int64_t> StageScheme::step(double h) {
  if (ctx_.settings.integrator == Integrator::rk4)
    rk4_step(h);
  else
    midpoint_step(h);
  return std::nullopt;
}

// Explicit midpoint (RK2): a half step of Euler finds (xm, vm); the full step uses their slopes.
void StageScheme::midpoint_step(double h) {
  ClothState& state = ctx_.state;
  const double t = state.time;
  evaluate(state.x, state.v, t, h);
  acceleration_of_force(acceleration_);
  stage_x_ = state.x + 0.5 * h * state.v;        // xm = x + h/2 v
  stage_v_ = state.v + 0.5 * h * acceleration_;  // vm = v + h/2 a(x, v)
  evaluate(stage_x_, stage_v_, t + 0.5 * h, h);
  acceleration_of_force(acceleration_);
  state.x.noalias() += h * stage_v_;       // x1 = x + h vm
  state.v.noalias() += h * acceleration_;  // v1 = v + h a(xm, vm)
}

// Classic RK4 on (x, v)' = (v, a(x, v)): slopes k1..k4 weighted 1, 2, 2, 1.
void StageScheme::rk4_step(double h) {
  ClothState& state = ctx_.state;
  const double t = state.time;
  // k1 at the start.
  evaluate(state.x, state.v, t, h);
  acceleration_of_force(acceleration_);
  sum_x_ = state.v;
  sum_v_ = acceleration_;
  // k2 and k3 at the midpoint, each from the previous slope.
  stage_x_ = state.x + 0.5 * h * state.v;
  stage_v_ = state.v + 0.5 * h * acceleration_;
  for (int half_stage = 0; half_stage < 2; ++half_stage) {
    evaluate(stage_x_, stage_v_, t + 0.5 * h, h);
    acceleration_of_force(acceleration_);
    sum_x_.noalias() += 2.0 * stage_v_;
    sum_v_.noalias() += 2.0 * acceleration_;
    const double reach = half_stage == 0 ? 0.5 * h : h;  // k3 steps half, k4 steps whole
    stage_x_ = state.x + reach * stage_v_;
    stage_v_ = state.v + reach * acceleration_;
  }
  // k4 at the end.
  evaluate(stage_x_, stage_v_, t + h, h);
  acceleration_of_force(acceleration_);
  sum_x_.noalias() += stage_v_;
  sum_v_.noalias() += acceleration_;
  state.x.noalias() += (h / 6.0) * sum_x_;
  state.v.noalias() += (h / 6.0) * sum_v_;
}

}  // namespace drapelab
