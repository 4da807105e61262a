// The contacts of the step where a run became unstable (unstable_cause.hpp).
#include "integrators/unstable_cause.hpp"

#include <sstream>

namespace drapelab {
namespace {

// "plane 'floor': 441 particles, the deepest 1.004 m into its contact (deeper than the thickness,
// 0.004 m: inside the collider)" for every collider that touched the cloth.
std::vector<std::string> collider_contacts(const ClothModel& model, const StepContactsSeen& seen) {
  std::vector<std::string> lines;
  if (!seen.colliders || !seen.totals) return lines;
  for (std::size_t c = 0; c < seen.totals->size() && c < seen.colliders->size(); ++c) {
    const ColliderContactTotals& total = (*seen.totals)[c];
    const int edges = seen.edge_totals ? (*seen.edge_totals)[c].contact_count : 0;
    const int particles = total.contact_count - edges;
    if (total.contact_count == 0) continue;
    const Collider& collider = seen.colliders->collider(c);
    std::ostringstream line;
    line.precision(4);
    line << collider_shape_name(collider.shape) << " '" << collider.name << "' (";
    if (particles > 0) line << particles << " particles";
    if (edges > 0) line << (particles > 0 ? " and " : "") << edges << " edge contacts";
    line << ", the deepest " << total.max_depth << " m into its contact";
    if (total.max_depth > model.thickness)
      line << ", deeper than the cloth's thickness " << model.thickness
           << " m: inside the collider";
    line << ")";
    lines.push_back(line.str());
  }
  return lines;
}

// "constraints.2 (soft)", "interactions.0 (a drag)" for each that ends on the particle: drags
// follow the scene's constraints in the list, each kind in the scene's order.
std::vector<std::string> constraints_on(const DistanceConstraints* constraints, int particle) {
  std::vector<std::string> names;
  if (!constraints) return names;
  int constraint = 0, drag = 0;
  for (const DistanceConstraint& c : constraints->list) {
    const bool is_drag = c.b.kind == ConstraintEnd::Kind::drag;
    const bool ends_here = DistanceConstraints::particle_a(c) == particle ||
                           (c.b.kind == ConstraintEnd::Kind::particle && c.b.particle == particle);
    if (ends_here)
      names.push_back(is_drag ? "interactions." + std::to_string(drag) + " (a drag)"
                              : "constraints." + std::to_string(constraint) + " (" +
                                    constraint_mode_name(c.mode) + ")");
    if (is_drag)
      ++drag;
    else
      ++constraint;
  }
  return names;
}

std::string joined(const std::vector<std::string>& parts) {
  std::string text;
  for (std::size_t k = 0; k < parts.size(); ++k)
    text += (k == 0 ? "" : k + 1 == parts.size() ? " and " : ", ") + parts[k];
  return text;
}

}  // namespace

std::string unstable_step_cause(const ClothModel& model, const StepContactsSeen& seen,
                                int particle) {
  std::vector<std::string> kinds;
  if (const auto colliders = collider_contacts(model, seen); !colliders.empty())
    kinds.push_back("collider contacts with " + joined(colliders));
  if (seen.self_contacts > 0)
    kinds.push_back(std::to_string(seen.self_contacts) + " self-contacts");
  if (const auto held = constraints_on(seen.constraints, particle); !held.empty())
    kinds.push_back("particle " + std::to_string(particle) + " is an end of " + joined(held));
  if (kinds.empty()) return "";
  return " In that step: " + joined(kinds) + ".";
}

}  // namespace drapelab
