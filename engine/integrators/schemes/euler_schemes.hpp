// The explicit schemes, one class per family: the Euler pair (euler_scheme.cpp), the multi-stage
// Runge-Kutta schemes (stage_schemes.cpp) and the two-level schemes that carry a history
// (two_level_schemes.cpp). Every stage evaluates the whole force at the stage's state and time,
// so colliders move within the step as they do for every other scheme. Pinned particles have zero
// acceleration and zero velocity, so every update leaves them where they are.
#pragma once

#include "integrators/schemes/scheme.hpp"

namespace drapelab {

// Explicit Euler (x1 = x0 + h v0, v1 = v0 + h a0) and symplectic Euler (v1 = v0 + h a0,
// x1 = x0 + h v1). They scan the new state for the health check as they write it.
class EulerScheme final : public IntegratorScheme {
 public:
  using IntegratorScheme::IntegratorScheme;
  std::optional<std::int64_t> step(double h) override;
};

// Explicit midpoint (RK2) and classic RK4.
class StageScheme final : public IntegratorScheme {
 public:
  explicit StageScheme(const SchemeContext& context);
  std::optional<std::int64_t> step(double h) override;

 private:
  void midpoint_step(double h);
  void rk4_step(double h);

  Eigen::Matrix3Xd stage_x_, stage_v_;  // m, m/s: the state a stage evaluates the force at
  Eigen::Matrix3Xd sum_x_, sum_v_;      // RK4's weighted sums of stage slopes (m/s, m/s^2)
  Eigen::Matrix3Xd acceleration_;       // m/s^2: the last stage's
};

// Position (Stoermer) Verlet and leapfrog (kick-drift-kick), each with the history of the step
// it last took.
class TwoLevelScheme final : public IntegratorScheme {
 public:
  explicit TwoLevelScheme(const SchemeContext& context);
  std::optional<std::int64_t> step(double h) override;
  void positions_projected(double h) override;
  void forget_history() override { history_step_ = 0.0; }

 private:
  void verlet_step(double h);
  void leapfrog_step(double h);

  Eigen::Matrix3Xd stage_x_, stage_v_;  // m (Verlet's x(n)), m/s (leapfrog's predicted v(n+1))
  Eigen::Matrix3Xd acceleration_;       // m/s^2: a(n)
  Eigen::Matrix3Xd previous_x_;         // m: Verlet's x(n-1)
  double history_step_ = 0.0;           // s: the h the history holds; 0 = start afresh
};

}  // namespace drapelab
