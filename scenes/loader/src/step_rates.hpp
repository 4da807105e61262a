// What bounds an explicit step of our solver besides the cloth's own springs or elements and the
// collider contact: per particle, the spring-dampers that act on it alone (stability.hpp,
// ParticleRates), and the cost of each method at a scene, from which the solver's integrator is
// chosen when the scene names none.
#pragma once

#include "drapelab/cloth_model.hpp"
#include "drapelab/scene/scene.hpp"
#include "drapelab/stability.hpp"

namespace drapelab::scene {

// Per particle (N/m, N*s/m), the explicit spring-dampers of the scene beyond the cloth and the
// collider contact:
//  - self-collision: one contact's stiffness and damping on every particle (a particle in several
//    takes them bounded by its load, explicit_contact_bound.hpp, so one is what bounds the step);
//  - soft distance constraints: k and c on each end particle, twice that between two particles
//    (the Gershgorin row of a spring);
//  - drags: their stiffness and damping on their particle;
//  - air: the drag's rate rho (C_d + |C_l|) A_i u on particle i of vertex area A_i, at u the wind
//    (with three times its gusts and eddies) plus the particle's terminal speed in still air,
//    sqrt(2 m_i g / (rho C_d A_i)), the fastest it falls flat.
ParticleRates explicit_particle_rates(const Scene& scene, const ClothModel& model);

// Estimated wall time (s) of one solver at a scene on a machine like the one drapelab is measured
// on (docs/physics.md, "The integrator chosen when none is named"): particle-steps times a cost per
// particle and step, measured for each method on the shipped scenes.
double estimated_wall_seconds(const ClothModel& model, const SolverSpec& solver, double duration);

}  // namespace drapelab::scene
