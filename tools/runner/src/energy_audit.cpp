// The energy audit of a run (energy_audit.hpp).
#include "drapelab/runner/energy_audit.hpp"

#include <algorithm>
#include <sstream>

#include "drapelab/continuum.hpp"
#include "drapelab/scene/number_format.hpp"

namespace drapelab::runner {

std::string scene_drivers(const scene::Scene& scene) {
  std::vector<std::string> drivers;
  for (const Collider& c : scene.colliders) {
    if (c.dynamic())
      drivers.push_back("collider '" + c.name + "' is a dynamic body");
    else if (c.moves())
      drivers.push_back("collider '" + c.name + "' moves");
  }
  for (std::size_t p = 0; p < scene.cloth.pin_attach.size(); ++p) {
    const std::string& name = scene.cloth.pin_attach[p];
    if (name.empty()) continue;
    for (const Collider& c : scene.colliders)
      if (c.name == name && (c.moves() || c.dynamic())) {
        drivers.push_back("pins ride on collider '" + name + "'");
        break;
      }
  }
  const AirSettings& air = scene.air;
  if (air.enabled &&
      (!air.wind.isZero(0) || air.gust_amplitude > 0.0 || air.turbulence_intensity > 0.0))
    drivers.emplace_back("wind");
  if (!scene.interactions.empty()) drivers.emplace_back("scripted drags");
  for (const scene::SeamSpec& seam : scene.cloth.seams)
    if (seam.close_time > 0.0) {
      drivers.emplace_back("seams being sewn shut");
      break;
    }
  for (const DistanceConstraint& c : scene.constraints)
    if (c.b.kind == ConstraintEnd::Kind::collider_point) {
      const Collider& end = scene.colliders[static_cast<std::size_t>(c.b.collider)];
      if (end.moves() || end.dynamic()) {
        drivers.push_back("a constraint ends on collider '" + end.name + "'");
        break;
      }
    }
  std::string joined;
  for (const std::string& d : drivers) joined += (joined.empty() ? "" : ", ") + d;
  return joined;
}

namespace {

// "symplectic_euler, dt = 8.6e-05 s": the solver's method and step, for the causes.
std::string step_hint(const scene::SolverSpec& spec) {
  std::ostringstream hint;
  hint.precision(3);
  hint << (spec.type == SolverType::spring_damper ? integrator_name(spec.integrator)
                                                  : solver_type_name(spec.type))
       << ", dt = " << spec.dt << " s";
  return hint.str();
}

}  // namespace

double energy_rise_tolerance(const ClothModel& model, const Eigen::Vector3d& gravity) {
  const Eigen::Vector3d low = model.rest_positions.rowwise().minCoeff();
  const Eigen::Vector3d high = model.rest_positions.rowwise().maxCoeff();
  const double size = (high - low).norm();  // m
  return std::max(1e-9, 1e-2 * model.total_mass() * gravity.norm() * size);
}

EnergyAudit::EnergyAudit(std::shared_ptr<const ClothModel> model, const scene::Scene& scene,
                         const ContactModel* contacts)
    : model_(std::move(model)),
      passive_(scene_drivers(scene).empty()),
      self_collision_(scene.cloth.self_collision.enabled),
      tolerance_(energy_rise_tolerance(*model_, scene.gravity)) {
  if (contacts)
    contact_meter_ =
        std::make_unique<ContactEnergyMeter>(*model_, *contacts, scene.contact.triangles);
}

void EnergyAudit::measure(const ContactModel* contacts, const CollisionMetrics* collisions,
                          const DistanceConstraints* constraints, const Solver& solver, double t,
                          ClothMetrics& metrics) {
  const ClothState& state = solver.state();
  const double elastic = model_->uses_continuum() ? continuum_energy(*model_->continuum, state.x)
                                                  : metrics.spring_energy;  // J
  metrics.elastic_energy = elastic;
  double total = metrics.kinetic_energy + metrics.gravity_energy + elastic;
  contact_before_ = contact_now_;
  contact_now_ = {};
  if (contact_meter_ && contacts) {
    contact_now_.particles = collisions ? collisions->contact_energy : 0.0;
    contact_now_.edges = contact_meter_->energy(*contacts, t, state.x);
    metrics.contact_energy = contact_now_.particles + contact_now_.edges;
    total += *metrics.contact_energy;
  }
  if (constraints && constraints->has_soft()) {
    metrics.constraint_energy = constraints->soft_energy(t, state.x);
    total += *metrics.constraint_energy;
  }
  metrics.self_contact_energy = solver.self_contact_energy();
  if (metrics.self_contact_energy) total += *metrics.self_contact_energy;
  metrics.total_energy = total;
  if (const std::optional<EnergyLedger> ledger = solver.energy_ledger()) {
    metrics.external_work = ledger->external_work;
    metrics.dissipated = ledger->dissipated;
    const double balance = total + ledger->dissipated - ledger->external_work;  // J
    if (!balance_start_) balance_start_ = balance;
    metrics.energy_error = balance - *balance_start_;
  }
}

void EnergyAudit::check(int frame, double time, const ClothMetrics& metrics,
                        const scene::SolverSpec& solver) {
  if (!metrics.total_energy) return;
  const double total = *metrics.total_energy;
  if (!lowest_) {
    lowest_ = total;
    return;
  }
  const double rise = total - *lowest_;
  worst_rise_ = std::max(worst_rise_, rise);
  if (!passive_ || rise <= tolerance_) {
    lowest_ = std::min(*lowest_, total);
    return;
  }
  // The contacts in play at this frame or the one before, edges first: they are where an explicit
  // push meets the lightest effective masses.
  std::string cause;
  const auto in_play = [&](double ContactShares::*part) {
    return contact_now_.*part > 0.0 || contact_before_.*part > 0.0;
  };
  if (in_play(&ContactShares::edges))
    cause = "contact of the colliders' edges and corners with the cloth's triangles";
  else if (in_play(&ContactShares::particles))
    cause = "collider contact at the particles";
  else if (self_collision_)
    cause = "self-contact, or the step outrunning the springs (no collider contact is in play)";
  else
    cause = "the step: no contact is in play, so the springs or dampers outrun it";
  cause += " (" + step_hint(solver) + "; try half the dt)";
  if (warnings_.size() < kMostEnergyWarnings) warnings_.push_back({frame, time, rise, cause});
  lowest_ = total;  // the next warning needs a new rise of its own
}

}  // namespace drapelab::runner
