// Per-particle rates of the step bound and the methods' costs (step_rates.hpp).
#include "step_rates.hpp"

#include <cmath>

namespace drapelab::scene {
namespace {

// Measured cost per particle and step (s) on the two-core reference machine
// (docs/physics.md, "The integrator chosen when none is named"): the explicit step on springs and
// on the continuum's elements, implicit Euler with its conjugate gradient, vbd with its default 10
// sweeps, and Bullet's two cloths.
constexpr double kExplicitSpringCost = 0.15e-6;
constexpr double kExplicitContinuumCost = 0.4e-6;
constexpr double kImplicitEulerCost = 50e-6;
constexpr double kVbdCostPerSweep = 2e-6;
constexpr double kBulletSoftBodyCost = 0.5e-6;
constexpr double kBulletDeformableCost = 1.5e-6;
constexpr double kMujocoCost = 2.5e-6;  // s per particle and step: 65 x 65, 2 ms, its springs

}  // namespace

ParticleRates explicit_particle_rates(const Scene& scene, const ClothModel& model) {
  const int n = model.particle_count();
  ParticleRates rates;
  rates.stiffness = Eigen::VectorXd::Zero(n);
  rates.damping = Eigen::VectorXd::Zero(n);
  if (scene.cloth.self_collision.enabled && model.triangles.cols() > 0) {
    rates.stiffness.array() += scene.cloth.self_collision.stiffness;
    rates.damping.array() += scene.cloth.self_collision.damping;
  }
  for (const DistanceConstraint& c : scene.constraints) {
    if (c.mode != ConstraintMode::soft || c.a < 0 || c.a >= n) continue;
    const bool between_particles = c.b.kind == ConstraintEnd::Kind::particle;
    const double share = between_particles ? 2.0 : 1.0;  // the Gershgorin row of a spring
    rates.stiffness[c.a] += share * c.stiffness;
    rates.damping[c.a] += share * c.damping;
    if (between_particles && c.b.particle >= 0 && c.b.particle < n) {
      rates.stiffness[c.b.particle] += share * c.stiffness;
      rates.damping[c.b.particle] += share * c.damping;
    }
  }
  for (const DragSpec& drag : scene.interactions) {
    if (drag.particle < 0 || drag.particle >= n) continue;
    rates.stiffness[drag.particle] += drag.stiffness;
    rates.damping[drag.particle] += drag.damping;
  }
  const AirSettings& air = scene.air;
  if (air.enabled && air.drag > 0.0 && model.vertex_area.size() == n) {
    const double wind = air.wind.norm() + 3.0 * (air.gust_amplitude + air.turbulence_intensity);
    const double g = scene.gravity.norm();  // m/s^2
    for (int i = 0; i < n; ++i) {
      const double area = model.vertex_area[i];  // m^2
      if (!(area > 0.0)) continue;
      const double terminal = std::sqrt(2.0 * model.mass[i] * g / (air.density * air.drag * area));
      rates.damping[i] += air.density * (air.drag + std::abs(air.lift)) * area * (wind + terminal);
    }
  }
  return rates;
}

double estimated_wall_seconds(const ClothModel& model, const SolverSpec& solver, double duration) {
  const double particle_steps =
      static_cast<double>(model.particle_count()) * std::ceil(duration / solver.dt);
  double cost = kExplicitSpringCost;  // s per particle and step
  switch (solver.type) {
    case SolverType::bullet_softbody:
      cost = kBulletSoftBodyCost * solver.iterations;
      break;
    case SolverType::bullet_deformable:
      cost = kBulletDeformableCost;
      break;
    case SolverType::mujoco:
      cost = kMujocoCost;
      break;
    case SolverType::spring_damper:
      if (solver.integrator == Integrator::implicit_euler)
        cost = kImplicitEulerCost;
      else if (solver.integrator == Integrator::vbd)
        cost = kVbdCostPerSweep * solver.vbd.iterations;
      else {
        cost = solver.continuum ? kExplicitContinuumCost : kExplicitSpringCost;
        if (solver.integrator == Integrator::midpoint) cost *= 2.0;  // stages per step
        if (solver.integrator == Integrator::rk4) cost *= 4.0;
      }
      break;
  }
  return particle_steps * cost;
}

}  // namespace drapelab::scene
