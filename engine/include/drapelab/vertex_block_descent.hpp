// Vertex block descent (Chen, Liu, Yang and Yuksel, SIGGRAPH 2024): backward Euler solved as the
// minimisation of its variational form
//
//   G(x) = sum_i m_i / (2 h^2) |x_i - y_i|^2 + E(x) + h D(x),   y_i = x_i(n) + h v_i(n) + h^2 a_i,
//
// over the end-of-step positions x, with v(n+1) = (x - x(n)) / h. E holds the springs' and the
// collider contacts' potentials, D the dissipation of the spring and contact dampers, air drag and
// friction (each a function of the displacement x - x(n)), and a_i gravity plus the explicit forces
// of the step (friction between layers). Each iteration visits every particle once and takes one
// Newton step on G with all other particles held, a 3 x 3 solve (Gauss-Seidel on blocks). Particles
// are coloured so that no two of one colour share a spring: a colour's particles are then solved
// in parallel, and the result does not depend on the number of threads. A fixed iteration budget
// keeps the cost of a step fixed; an unconverged step is a softer cloth, never an unstable one,
// because every particle's update lowers G. docs/physics.md gives the equations and what the
// budget does to accuracy.
#pragma once

#include <cstdint>

namespace drapelab {

struct VbdSettings {
  int iterations = 10;  // sweeps over every particle per step
  // 1: backward Euler. 2: BDF2 (second order; the same minimisation with x(n) and v(n) replaced
  // by blends of the last two steps), backward Euler on a first step or after a change of step.
  int order = 1;
  // Chebyshev semi-iterative acceleration of the sweeps (the paper's rho, in [0, 1)): 0 is off.
  double chebyshev_rho = 0.0;
  // Before each sweep, a Newton step on the translations of aggregates of 16 particles, solved
  // exactly: the modes of whole regions, which the sweeps reach slowest.
  bool coarse_correction = true;
  // Friction's smoothing velocity (m/s): a contact whose tangential speed is below it sticks as a
  // stiff spring of mu_s fn / (friction_velocity h), so a sticking particle creeps at most this
  // fast; above it, the Coulomb force mu_k fn opposes the slip.
  double friction_velocity = 1e-4;
};

struct VbdStats {
  std::int64_t steps = 0;
  std::int64_t iterations_total = 0;
  int colors = 0;  // colours of the spring graph
  // The largest move of one particle in the last sweep of the last step (m): how far from
  // converged the budget leaves the step.
  double last_sweep_move = 0.0;
  double last_sweep_move_max = 0.0;  // the largest over all steps (m)
  std::int64_t contacts_last = 0;    // collider contact planes of the last step
  // Offset self-contact detections, summed over steps (one per step, more where moves were cut
  // short at their bounds).
  std::int64_t self_contact_detections = 0;
  // Sweeps past the ones asked for because a passive step's end held more energy than its start,
  // summed over steps.
  std::int64_t energy_sweeps = 0;
  // Factorisations of the coarse step's matrix, summed over steps: one a step, and one more for
  // each coarse step whose system the step's first factorisation did not precondition well.
  std::int64_t coarse_factorizations = 0;
  // Unknowns per aggregate of the coarse step: 6 (a translation and a turn) or 3 (a translation).
  int coarse_unknowns = 0;
  // The search for the colliders' edges and corners near the cloth's, summed over steps (s).
  double feature_search_seconds = 0.0;
};

}  // namespace drapelab
