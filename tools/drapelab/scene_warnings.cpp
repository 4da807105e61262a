// Warnings about a valid scene (scene_warnings.hpp).
#include "scene_warnings.hpp"

#include <sstream>

#include "drapelab/scene/number_format.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/stability.hpp"

namespace drapelab::cli {

namespace {

void add_stability_warnings(const scene::Scene& scene, const ClothModel& model,
                            std::vector<std::string>& warnings) {
  for (const auto& solver : scene.solvers) {
    // Adaptive substeps follow the shape's bound, so the fixed-step warning does not apply.
    if (solver.type != SolverType::spring_damper || solver.adaptive_substeps) continue;
    // Each integrator's own bound (with the contact for every explicit scheme but symplectic
    // Euler).
    const double bound = stable_step_estimate(model, scene.cloth.air_damping, scene.contact_rates(),
                                              solver.integrator);  // s
    std::ostringstream line;
    line.precision(6);
    if (bound == 0.0)
      line << "solver " << solver.name << ": " << integrator_name(solver.integrator)
           << " has no stable step here (an undamped spring, or a contact without "
              "contact.damping); the run may become unstable";
    else if (solver.dt > bound)
      line << "solver " << solver.name << ": dt " << solver.dt << " s is above the "
           << integrator_name(solver.integrator) << " stable step estimate " << bound
           << " s; the run may become unstable (the bound is sufficient, not necessary)";
    else
      continue;
    warnings.push_back(line.str());
  }
}

// Self-collision asked of a solver without it. (A thickness the cloth's spacing breaks is an error
// of the loader.)
void add_self_collision_warnings(const scene::Scene& scene, std::vector<std::string>& warnings) {
  const SelfCollisionSettings& self = scene.cloth.self_collision;
  if (!self.enabled) return;
  for (const auto& solver : scene.solvers)
    if (solver.type == SolverType::bullet_softbody)
      warnings.push_back("solver " + solver.name +
                         ": cloth.self_collision has no effect on bullet_softbody (Bullet 3.24's "
                         "classic cloth has no self-collision that runs; docs/bullet.md, "
                         "\"Self-collision\")");
    else if (solver.type == SolverType::spring_damper && solver.integrator != Integrator::vbd)
      // Only vbd keeps the cloth from crossing itself by construction (offset contact with
      // conservative bounds); the others push layers apart with penalty forces in split steps.
      warnings.push_back("solver " + solver.name + ": self-collision under " +
                         integrator_name(solver.integrator) +
                         " is penalty forces in split steps, which layers pressed hard enough (a "
                         "twist, a crumple) still cross; integrator: vbd keeps the cloth from "
                         "crossing itself (docs/contact.md, \"Self-collision\")");
}

// A solver expected to run for over ten minutes, with the faster choice when there is one.
void add_long_run_warnings(const scene::Scene& scene, std::vector<std::string>& warnings) {
  for (const auto& solver : scene.solvers) {
    if (!(solver.estimated_seconds > 600.0)) continue;
    std::string line = "solver " + solver.name + " is expected to take about " +
                       describe_seconds(solver.estimated_seconds) + " (" +
                       format_number(static_cast<double>(solver.steps_per_frame)) +
                       " steps per frame)";
    line += solver.faster_choice.empty()
                ? "; a larger dt, fewer particles or a shorter duration would shorten it"
                : "; faster: " + solver.faster_choice;
    warnings.push_back(line);
  }
}

}  // namespace

std::vector<std::string> scene_warnings(const scene::Scene& scene, const ClothModel& model) {
  std::vector<std::string> warnings;
  add_long_run_warnings(scene, warnings);
  add_stability_warnings(scene, model, warnings);
  add_self_collision_warnings(scene, warnings);
  return warnings;
}

}  // namespace drapelab::cli
