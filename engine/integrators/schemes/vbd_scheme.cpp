// Vertex block descent as a scheme. The colliders' edges and corners near the cloth's edges and
// triangles, and the cloth's contacts with itself, are found in the step and measured inside the
// descent. The soft constraints are found at the step's start: their pulls enter the descent as
// energies of the particles' motion; the other forces between particles (air) are an explicit
// force of the step.
#include <sstream>

#include "contact/edge_contact.hpp"
#include "integrators/schemes/implicit_schemes.hpp"
#include "integrators/vbd/vertex_block_descent.hpp"
#include "self_collision/offset_contacts.hpp"

namespace drapelab {

VbdScheme::VbdScheme(const SchemeContext& context)
    : IntegratorScheme(context),
      descent_(std::make_unique<VertexBlockDescent>(ctx_.model, ctx_.settings.vbd)) {
  if (ctx_.settings.self_collision.enabled && ctx_.model.triangles.cols() > 0)
    self_contacts_ = std::make_unique<OffsetContacts>(ctx_.model, ctx_.settings.self_collision);
  if (ctx_.settings.contacts && ctx_.settings.collider_edges && ctx_.model.triangles.cols() > 0) {
    features_ = std::make_unique<EdgeContact>(ctx_.model, *ctx_.settings.contacts);
    if (!features_->active()) features_.reset();
  }
}

VbdScheme::~VbdScheme() = default;

std::optional<std::int64_t> VbdScheme::step(double h) {
  ClothState& state = ctx_.state;
  ForceEvaluator& forces = ctx_.forces;
  VbdStepInput input;
  input.t = state.time;
  input.h = h;
  input.gravity = ctx_.settings.gravity;
  input.air_damping = ctx_.settings.air_damping;
  input.contacts = ctx_.settings.contacts.get();
  if (forces.has_pair_terms()) {
    forces.couplings().clear();
    Eigen::Matrix3Xd& force = forces.force();
    force.setZero();
    forces.add_pair_forces(state.x, state.v, state.time, h);
    for (const WeightedContact& c : forces.couplings())  // leaves the explicit terms only
      for (int s = 0; s < 4; ++s)
        if (c.particle[s] >= 0) force.col(c.particle[s]) -= (c.weight[s] * c.force) * c.normal;
    input.couplings = &forces.couplings();
    input.explicit_force = &force;
  }
  input.self_contacts = self_contacts_.get();
  input.features = features_.get();
  const double detecting_before = self_contacts_ ? self_contacts_->detection_seconds() : 0.0;
  const double searching_before = descent_->stats().feature_search_seconds;
  // The descent records what the collider planes and edges did at the step's end (the edges'
  // totals of the evaluation above are those of the step's start).
  descent_->step(ctx_.model, input, state.x, state.v, forces.contact_totals());
  forces.add_phase_seconds(StepPhase::collider_edges,
                           descent_->stats().feature_search_seconds - searching_before);
  if (self_contacts_) {
    // The detections are the self-contacts' phase; their energy's terms are part of the sweeps.
    forces.add_phase_seconds(StepPhase::self_contacts,
                             self_contacts_->detection_seconds() - detecting_before);
    forces.set_scheme_power({.dissipated = self_contacts_->last_totals().dissipated_power});
  }
  return std::nullopt;
}

// The backward Euler step evaluates no force: its springs at the end state, where its forces act,
// give the ledger its dampers' power and the attachments their loads.
void VbdScheme::finish_step() {
  ctx_.forces.set_body_and_spring_forces(ctx_.state.x, ctx_.state.v);
}

const VbdStats* VbdScheme::vbd_stats() const { return &descent_->stats(); }

Counters VbdScheme::counters() const {
  const VbdStats& s = descent_->stats();
  const VbdSettings& settings = ctx_.settings.vbd;
  return {
      {"vbd_iterations", settings.iterations},
      {"vbd_order", settings.order},
      {"vbd_chebyshev_rho", settings.chebyshev_rho},
      {"vbd_colors", s.colors},
      {"vbd_last_sweep_move", s.last_sweep_move},
      {"vbd_last_sweep_move_max", s.last_sweep_move_max},
      {"vbd_contact_planes_last", static_cast<double>(s.contacts_last)},
      {"vbd_self_contact_detections_per_step",
       s.steps > 0 ? static_cast<double>(s.self_contact_detections) / static_cast<double>(s.steps)
                   : 0.0},
      {"vbd_energy_sweeps_per_step",
       s.steps > 0 ? static_cast<double>(s.energy_sweeps) / static_cast<double>(s.steps) : 0.0},
      {"vbd_coarse_unknowns_per_aggregate", s.coarse_unknowns},
      {"vbd_coarse_factorizations_per_step",
       s.steps > 0 ? static_cast<double>(s.coarse_factorizations) / static_cast<double>(s.steps)
                   : 0.0}};
}

std::string VbdScheme::step_advice() const {
  std::ostringstream text;
  text.precision(4);
  text << "a smaller dt or more vbd iterations (" << ctx_.settings.vbd.iterations
       << " sweeps per step left particles moving by up to " << descent_->stats().last_sweep_move
       << " m in the last sweep; a collider moving faster than its contact can push back also "
          "needs a smaller dt), ";
  return text.str();
}

}  // namespace drapelab
