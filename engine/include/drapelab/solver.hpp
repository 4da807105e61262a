// The interface the runner drives: every solver (ours, and later Bullet's) steps by h and exposes its
// cloth as a ClothState whose node i is model particle i. The runner knows nothing of their insides.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "drapelab/cloth_state.hpp"

namespace drapelab {

enum class SolverStatus { ok, unstable, error };

// The contact force a solver's cloth received from one collider during its last step (N): the sums
// over the touching particles of the magnitudes of the normal and tangential parts.
struct ColliderForce {
  double normal = 0.0;
  double friction = 0.0;
};
const char* solver_status_name(SolverStatus status);

class Solver {
 public:
  virtual ~Solver() = default;
  // Advances the cloth by h seconds. After the status leaves `ok`, step does nothing.
  virtual void step(double h) = 0;
  virtual const ClothState& state() const = 0;
  virtual const std::string& name() const = 0;  // label used in every output
  virtual const std::string& type() const = 0;  // spring_damper, bullet_softbody, ...
  virtual SolverStatus status() const = 0;
  // Why the status is not ok: which particle, which step, what to try. Empty when ok.
  virtual const std::string& message() const = 0;
  // One entry per scene collider, in scene order (empty without colliders).
  virtual std::vector<ColliderForce> collider_forces() const = 0;
  // Wall time per phase of the step (s, accumulated), for solvers that time their phases.
  virtual std::vector<std::pair<std::string, double>> phase_seconds() const { return {}; }
  // Scheme-specific counts worth reporting (implicit Euler: CG iterations and residuals).
  virtual std::vector<std::pair<std::string, double>> counters() const { return {}; }
};

}  // namespace drapelab
