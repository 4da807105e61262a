// Time integrators for the particle system M x'' = f(x, v). Pinned particles (inverse mass 0) keep
// their position and a zero velocity under every scheme.
//
// Each family of schemes is a unit of the solver's engine/integrators/schemes/ (make_scheme.cpp
// says which runs each integrator). Each scheme's update, its order, its force evaluations per step
// and its stability on x'' = -w^2 x:
//
// clang-format off
//   scheme            update                                         order  evals  stable undamped
//   explicit_euler    x1 = x0 + h v0, v1 = v0 + h a0                 1      1      never
//   symplectic_euler  v1 = v0 + h a0, x1 = x0 + h v1                 1      1      w h < 2
//   midpoint (RK2)    half step to (xm, vm), then x1 = x0 + h vm,    2      2      never
//                     v1 = v0 + h a(xm, vm)
//   rk4               classic Runge-Kutta                            4      4      w h < 2 sqrt(2)
//   verlet            x1 = 2 x0 - x_prev + h^2 a0 (position Verlet)  2      1      w h < 2
//   leapfrog          kick h/2, drift h, kick h/2 (velocity Verlet)  2      1      w h < 2
//   implicit_euler    (M - h D - h^2 K) dv = h (f0 + h K v0)         1      1+CG   always
//   vbd               the same backward Euler step, x1 minimising    1      sweeps always
//                     its variational form by a fixed number of
//                     per-particle Newton sweeps (vertex_block_descent.hpp)
// clang-format on
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace drapelab {

enum class Integrator {
  explicit_euler,    // v(n+1) = v(n) + a(n) h,  x(n+1) = x(n) + v(n) h      (classic Forward Euler)
  symplectic_euler,  // v(n+1) = v(n) + a(n) h,  x(n+1) = x(n) + v(n+1) h    (semi-implicit Euler)
  midpoint,          // explicit midpoint rule (RK2)
  rk4,               // classic fourth-order Runge-Kutta
  verlet,            // position (Stoermer) Verlet; velocity estimated (two_level_schemes.cpp)
  leapfrog,          // kick-drift-kick (velocity Verlet)
  implicit_euler,    // backward Euler linearised once per step (Baraff & Witkin 1998)
  vbd,  // backward Euler minimised by vertex block descent (Chen et al. 2024), a fixed budget
};

const char* integrator_name(Integrator integrator);
std::optional<Integrator> parse_integrator(std::string_view name);
std::vector<std::string> integrator_names();
std::vector<Integrator> all_integrators();

// Force evaluations per step (implicit Euler: one, plus its linear solve).
int force_evaluations_per_step(Integrator integrator);
// Global order of accuracy on smooth problems.
int order_of_accuracy(Integrator integrator);
// The largest w h for which the scheme stays bounded on the undamped oscillator x'' = -w^2 x:
// 2 for symplectic Euler, Verlet and leapfrog, 2 sqrt(2) for RK4, 0 for explicit Euler and midpoint
// (their stability regions miss the imaginary axis), infinity for implicit Euler.
double undamped_stability_limit(Integrator integrator);

}  // namespace drapelab
