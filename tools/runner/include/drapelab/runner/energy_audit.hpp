// The energy audit of a run (docs/metrics.md, "Energy audit"): every solver's total mechanical
// energy at every frame, and, in a passive scene, a warning at each frame where it rose.
//
// total = kinetic + gravity + elastic + contact + constraint potential, each measured from the
// solver's state alone (the same functions for every solver). A passive scene (nothing drives the
// cloth: no moving or dynamic collider, no pin on a moving collider, no wind, no drag) can only
// lose energy to its dampers, friction and air; a rise of its total above the running minimum by
// more than the tolerance is energy the method made: a step too large for a stiffness, or a contact
// applied where it cannot be stable. The warning names the frame and the likely cause.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/cloth_metrics.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/collision_metrics.hpp"
#include "drapelab/contact_energy.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/distance_constraints.hpp"
#include "drapelab/scene/scene.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::runner {

struct EnergyWarning {
  int frame = 0;
  double time = 0.0;  // s
  double rise = 0.0;  // J, above the lowest total of the frames before
  std::string cause;
};

// What drives the cloth in `scene` ("" when it is passive): e.g. "collider 'ball' moves, wind".
std::string scene_drivers(const scene::Scene& scene);

// The tolerance (J) of the passive-scene check: 1 % of m g L, the cloth's weight over its rest
// size (the diagonal of its rest bounding box), and never below 1e-9 J of rounding.
double energy_rise_tolerance(const ClothModel& model, const Eigen::Vector3d& gravity);

class EnergyAudit {
 public:
  // `model`: the cloth as this solver runs it (with the continuum's elements for our continuum
  // solver); `contacts`: the scene's colliders (null: none).
  EnergyAudit(std::shared_ptr<const ClothModel> model, const scene::Scene& scene,
              const ContactModel* contacts);

  // Fills metrics' elastic, contact, constraint and total energies for `state` at time t (s), with
  // the colliders posed by `contacts`, their particles' clearance queries `collisions` and the soft
  // constraints of `constraints` (each null: none; with dynamic colliders, all three where this
  // solver's own bodies are); and, from `solver`, the self-contacts' energy and the balance
  // (external_work, dissipated, energy_error) where the solver keeps an energy ledger.
  void measure(const ContactModel* contacts, const CollisionMetrics* collisions,
               const DistanceConstraints* constraints, const Solver& solver, double t,
               ClothMetrics& metrics);
  // After measure: in a passive scene, records a warning when the total rose above the tolerance,
  // its cause naming `solver`'s method and step.
  void check(int frame, double time, const ClothMetrics& metrics, const scene::SolverSpec& solver);

  bool passive() const { return passive_; }
  double tolerance() const { return tolerance_; }
  const std::vector<EnergyWarning>& warnings() const { return warnings_; }
  // The largest rise of the total above its running minimum over the run (J), passive or not.
  double worst_rise() const { return worst_rise_; }

 private:
  std::shared_ptr<const ClothModel> model_;
  std::unique_ptr<ContactEnergyMeter> contact_meter_;  // null without colliders
  bool passive_ = false;
  bool self_collision_ = false;
  double tolerance_ = 0.0;        // J
  std::optional<double> lowest_;  // J, the lowest total so far (since the last warning)
  // The contact energies of the last two measures (J), for the cause: a rise shows at the frame
  // after the contact that made it.
  struct ContactShares {
    double particles = 0.0;  // J, particles inside a collider's thickness
    double edges = 0.0;      // J, collider edges and corners inside the cloth's triangles
  };
  ContactShares contact_now_, contact_before_;
  double worst_rise_ = 0.0;
  // total + dissipated - external work at the first measure (J): energy_error's zero.
  std::optional<double> balance_start_;
  std::vector<EnergyWarning> warnings_;
};

// At most this many warnings are kept per solver (a run that gains energy at every frame says so
// in its first ones).
inline constexpr std::size_t kMostEnergyWarnings = 20;

}  // namespace drapelab::runner
