// Step-size bounds for explicit integration of the damped spring network
// (docs/physics.md, "The Gershgorin bound"; docs/validation.md, V4). By Gershgorin's theorem the
// stiffness and damping matrices' largest eigenvalues over mass satisfy
//   omega_max^2 <= K = max_i (2 / m_i) sum_j ks_ij     (1/s^2)
//   c_max       <= C = max_i (2 / m_i) sum_j kd_ij + air_damping   (1/s)
// A penalty contact adds its stiffness k_c and damping c_c to the diagonal: K += k_c / m_i and
// C += c_c / m_i for a particle touching one collider.
// Symplectic Euler on x'' + c x' + omega^2 x = 0 is stable iff h^2 omega^2 + 2 h c < 4, so
//   h < (sqrt(C^2 + 4 K) - C) / K   (= 2 / omega_max without damping, 2 / C without springs).
// Light particles on damped springs are often limited by the damping term, not the stiffness.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/integrators.hpp"

namespace drapelab {

struct NetworkRates {
  double stiffness = 0.0;  // K above, 1/s^2
  double damping = 0.0;    // C above, 1/s
};

// Penalty contact parameters that enter the bound (zero without colliders).
struct ContactRates {
  double stiffness = 0.0;  // N/m
  double damping = 0.0;    // N*s/m
};

// What else acts on single particles as an explicit spring-damper, per particle (empty: nothing):
// self-contact, soft distance constraints, drags and the air (step_rates.hpp of the scene loader
// builds them). Each adds to its particle's Gershgorin row as the contact does.
struct ParticleRates {
  Eigen::VectorXd stiffness;  // N/m
  Eigen::VectorXd damping;    // N*s/m
  bool empty() const { return stiffness.size() == 0; }
};

// Gershgorin bounds over the free particles; pinned particles do not move and are skipped.
NetworkRates network_rate_bounds(const ClothModel& model, double air_damping,
                                 ContactRates contact = {}, const ParticleRates& extra = {});

// A step (s) for which symplectic Euler is stable on the whole network (sufficient, from the bounds
// above; typically within a factor 2 of the true limit). Infinity when nothing constrains it.
double symplectic_euler_stable_step(const ClothModel& model, double air_damping,
                                    ContactRates contact = {});

// Explicit Euler and the midpoint rule have no stable step on an undamped spring: their stability
// regions touch the imaginary axis only at 0. A damped mode with rate c and frequency w needs
// |1 + lambda h| < 1, i.e. h < c / w^2 (and h < 2 / c when overdamped). When every spring's damping
// is kd / ks times its stiffness, each mode's c / w^2 is a weighted mean of the springs' kd / ks,
// so
//   h < min over springs (and the contact) of kd / ks
// bounds explicit Euler near the rest shape (air damping only helps). RK2's region contains Euler's
// disc, so the same bound is safe for it. Zero when some spring is undamped.
double damping_ratio_step(const ClothModel& model, ContactRates contact = {});

// Whether `integrator`'s solver takes the penalty contact force at the end of its step (linearly
// implicit along the normal, penalty_contact.hpp): the contact then acts as extra mass along the
// normal and does not bound the step. Symplectic Euler only; the other schemes evaluate it at their
// stages.
inline bool contact_at_step_end(Integrator integrator) {
  return integrator == Integrator::symplectic_euler;
}

// Tighter bounds at one shape x (3 x N, m), for steps chosen as the cloth moves (adaptive
// substeps). Symplectic Euler's stable step (s) at shape x (m, 3 x N), from each particle's
// stiffness and damping tensors at that shape (integrators/shape_bound.hpp, which the adaptive
// substeps use with a workspace kept between calls); without the contact, which that scheme takes
// at the step's end.
double shape_stable_step(const ClothModel& model, const Eigen::Matrix3Xd& x, double air_damping);

// The stable step (s) of each integrator from rates K and C: symplectic Euler's
// (sqrt(C^2 + 4 K) - C) / K for it, Verlet and leapfrog; 1.39 x that for RK4; the smaller of that
// and `damping_ratio` (damping_ratio_step) for explicit Euler and midpoint; infinity for implicit
// Euler.
double step_from_rates(const NetworkRates& rates, Integrator integrator, double damping_ratio);

// A step (s) below which `integrator` is stable on this network, from the bounds above, with the
// contact left out when contact_at_step_end(integrator): symplectic Euler's bound for it, Verlet
// and leapfrog (all w h < 2 undamped); 1.39 x that for RK4 (its region reaches 2.83 on the
// imaginary axis and 2.79 on the negative real axis); min(damping_ratio_step, symplectic bound) for
// explicit Euler and midpoint; infinity for implicit Euler.
double stable_step_estimate(const ClothModel& model, double air_damping, ContactRates contact,
                            Integrator integrator, const ParticleRates& extra = {});

// The step our solver takes when a scene gives none, as each integrator asks for it: its own
// default for the schemes with one (implicit Euler 1/240 s, vbd 1/120 s, the adaptive substeps'
// outer step 1/120 s), otherwise a safety factor times its stable step estimate (0.9), or, for
// explicit Euler and midpoint on an undamped spring (no stable step at all), 0.1 times symplectic
// Euler's.
constexpr double kImplicitEulerDefaultStep = 1.0 / 240.0;  // s
constexpr double kVbdDefaultStep = 1.0 / 120.0;            // s: two steps per 60 Hz frame
constexpr double kAdaptiveOuterStep = 1.0 / 120.0;         // s: the substeps follow the shape
struct DefaultStep {
  double step = 0.0;  // s
  // How it was found: the scheme's own default (false), or `factor` times `bound` (s), the stable
  // step estimate of `bound_integrator`.
  bool from_stable_step = false;
  double factor = 1.0;
  double bound = 0.0;  // s
  Integrator bound_integrator = Integrator::symplectic_euler;
};
DefaultStep default_step(const ClothModel& model, Integrator integrator, bool adaptive_substeps,
                         double air_damping, ContactRates contact, const ParticleRates& extra = {});

}  // namespace drapelab
