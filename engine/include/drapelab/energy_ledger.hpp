// The energy that the cloth's non-conservative forces take out or put in, so that a run's energy
// can be balanced: total_energy + dissipated - external_work stays at its start value to within
// the integrator's error (metrics.csv energy_error).
//
// Every force of our solver is either conservative, with a potential counted in total_energy
// (gravity, the springs' or the continuum's elasticity, the penalty contacts' k depth^2 / 2, the
// soft constraints' springs), or one of these:
//   dissipated  the dampers (springs, continuum, contacts, soft constraints), air drag relative to
//               the air, Coulomb friction, and a contact's force beyond its spring (the part a
//               clamp or a step bound removes);
//   external    what moving colliders, wind, drags, and pins on moving colliders do on the cloth.
// Each term reports its power at a force evaluation (PowerSplit, W); the solver adds the last
// evaluation of each step times its step (EnergyLedger, J), a first-order rule whose error falls
// with the step and shows in energy_error beside the integrator's own.
#pragma once

#include <Eigen/Core>

namespace drapelab {

// Power at one force evaluation (W). `dissipated` is the power the forces take out of the
// cloth's mechanical energy (positive for every damper); `external` the power they put in from
// outside the cloth (positive when a moving surface, the wind, a drag or a pin drives it).
struct PowerSplit {
  double dissipated = 0.0;  // W
  double external = 0.0;    // W
  PowerSplit& operator+=(const PowerSplit& other) {
    dissipated += other.dissipated;
    external += other.external;
    return *this;
  }
};

// The energy moved since the start of the run (J).
struct EnergyLedger {
  double dissipated = 0.0;     // J, by dampers, friction and air
  double external_work = 0.0;  // J, by moving colliders, pins, wind and drags
  void add(const PowerSplit& power, double seconds) {
    dissipated += power.dissipated * seconds;
    external_work += power.external * seconds;
  }
};

// The power of one penalty push of magnitude `normal_force` (N, along the unit `normal`) whose
// spring alone would push `spring_force` = k depth (N), on a cloth point moving at
// `relative_velocity` (m/s) relative to a surface moving at `surface_velocity` (m/s): the part
// beyond the spring (its damper, a clamp at zero or a step bound) dissipates, and the whole push
// does external work through the surface's motion. The spring's part is the potential's.
inline PowerSplit push_power(double normal_force, double spring_force,
                             const Eigen::Vector3d& normal,
                             const Eigen::Vector3d& relative_velocity,
                             const Eigen::Vector3d& surface_velocity) {
  return {-(normal_force - spring_force) * normal.dot(relative_velocity),
          normal_force * normal.dot(surface_velocity)};
}

// The power of a friction force `friction` (N) on a cloth point sliding at `relative_velocity`
// (m/s) over a surface moving at `surface_velocity` (m/s).
inline PowerSplit friction_power(const Eigen::Vector3d& friction,
                                 const Eigen::Vector3d& relative_velocity,
                                 const Eigen::Vector3d& surface_velocity) {
  return {-friction.dot(relative_velocity), friction.dot(surface_velocity)};
}

}  // namespace drapelab
