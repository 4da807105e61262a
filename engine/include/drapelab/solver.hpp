// The interface the runner drives: every solver (ours, Bullet's two cloths and MuJoCo's) steps by h
// and exposes its cloth as a ClothState whose node i is model particle i. The runner knows nothing
// of their insides.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "drapelab/cloth_state.hpp"
#include "drapelab/energy_ledger.hpp"

namespace drapelab {

enum class SolverStatus { ok, unstable, error };

// The kinds of solver a scene can run, named in scene files and outputs by solver_type_name.
enum class SolverType {
  spring_damper,      // ours (engine/)
  bullet_softbody,    // Bullet's classic cloth, btSoftBody
  bullet_deformable,  // Bullet's deformable world
  mujoco,             // MuJoCo 2.2: our cloth's particles as MuJoCo bodies (mujoco_bridge/)
};
inline constexpr std::array<SolverType, 4> kSolverTypes = {
    SolverType::spring_damper, SolverType::bullet_softbody, SolverType::bullet_deformable,
    SolverType::mujoco};
const char* solver_type_name(SolverType type);
std::optional<SolverType> parse_solver_type(std::string_view name);

// The contact force a solver's cloth received from one collider during its last step (N): the sums
// over the touching particles of the magnitudes of the normal and tangential parts.
struct ColliderForce {
  double normal = 0.0;    // N, the sum of the contacts' normal force magnitudes
  double friction = 0.0;  // N, ... and of their friction force magnitudes
  // The load on the collider: the force the cloth exerts on it and its moment about the world
  // origin (N, N*m); zero where a solver does not measure it (Bullet's cloths exert theirs
  // through their own rigid-body coupling).
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
};
const char* solver_status_name(SolverStatus status);

// A dynamic collider's rigid body as one solver holds it (every solver has its own copy).
struct BodyState {
  int collider = 0;                                            // index into the scene's colliders
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();      // collider frame -> world (m)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // m/s of the collider's origin
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // rad/s, world axes
};

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
  // The dynamic colliders' bodies, in scene order (empty without dynamic colliders).
  virtual std::vector<BodyState> bodies() const { return {}; }
  // The energy the cloth's dampers, friction and air took out and its drivers put in since the
  // start (energy_ledger.hpp); none for a solver that cannot account for it.
  virtual std::optional<EnergyLedger> energy_ledger() const { return std::nullopt; }
  // The self-contacts' spring energy at the last force evaluation (J), a potential of the cloth
  // that its state alone does not give; none without self-collision.
  virtual std::optional<double> self_contact_energy() const { return std::nullopt; }
};

}  // namespace drapelab
