// What our spring-damper solver simulates and how: the world every solver of the run shares, and
// our solver's own numerics (the integrator and its options).
#pragma once

#include "drapelab/implicit_euler.hpp"
#include "drapelab/integrators.hpp"
#include "drapelab/vertex_block_descent.hpp"
#include "drapelab/world.hpp"

namespace drapelab {

// The world (world.hpp) and our solver's numerics.
struct SpringDamperSettings : World {
  Integrator integrator = Integrator::symplectic_euler;
  double max_speed = 1000.0;       // m/s: a faster particle means the run has blown up
  ImplicitSolveSettings implicit;  // implicit_euler only: CG tolerance and iteration cap
  VbdSettings vbd;                 // vbd only: sweeps per step and their acceleration
  bool fast_springs =
      true;  // the spring-family fast path when the springs allow (spring_families.hpp)
  // Adaptive substeps: each step(h) is split into as many equal substeps as the current shape's
  // stable step needs (stability.hpp shape_rate_bounds), at `substep_safety` times that step.
  // Symplectic Euler only, the one scheme whose damped stability condition h^2 w^2 + 2 h c < 4 is
  // exact (the bound is tight enough for the others' differences to show: Verlet, whose damping
  // lags a step, diverged at 1.4 times its Gershgorin step on a sheet without shear springs); the
  // constructor refuses the others.
  bool adaptive_substeps = false;
  double substep_safety = 0.9;
};

}  // namespace drapelab
