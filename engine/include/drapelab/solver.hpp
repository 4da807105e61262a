// The interface the runner drives: every solver (ours and Bullet's two cloths) steps by h and
// exposes its cloth as a ClothState whose node i is model particle i. The runner knows nothing of
// their insides.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "drapelab/cloth_state.hpp"

namespace drapelab {

enum class SolverStatus { ok, unstable, error };

// The kinds of solver a scene can run, named in scene files and outputs by solver_type_name.
enum class SolverType {
  spring_damper,      // ours (engine/)
  bullet_softbody,    // Bullet's classic cloth, btSoftBody
  bullet_deformable,  // Bullet's deformable world
};
inline constexpr std::array<SolverType, 3> kSolverTypes = {
    SolverType::spring_damper, SolverType::bullet_softbody, SolverType::bullet_deformable};
const char* solver_type_name(SolverType type);
std::optional<SolverType> parse_solver_type(std::string_view name);

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
  virtual SolverType type() const = 0;
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
