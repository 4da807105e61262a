// Warnings about a valid scene (scene_warnings.hpp).
#include "scene_warnings.hpp"

#include <sstream>

#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/stability.hpp"

namespace drapelab::cli {

std::vector<std::string> stability_warnings(const scene::Scene& scene, const ClothModel& model) {
  std::vector<std::string> warnings;
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
  return warnings;
}

}  // namespace drapelab::cli
