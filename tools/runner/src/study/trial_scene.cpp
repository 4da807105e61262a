#include "drapelab/runner/trial_scene.hpp"

#include <cmath>
#include <iostream>

#include "drapelab/scene/number_format.hpp"
#include "drapelab/scene/scene_loader.hpp"

namespace drapelab::runner {

std::optional<scene::Scene> load_trial_scene(const std::string& file,
                                             std::vector<std::string> overrides, double duration,
                                             std::shared_ptr<const ClothModel>* model) {
  if (duration > 0.0) overrides.push_back("duration=" + format_number(duration));
  const auto loaded = scene::load_scene_file(file, overrides);
  if (!loaded.ok()) {
    for (const auto& error : loaded.errors) std::cerr << "error: " << error << "\n";
    std::cerr << "nothing was run\n";
    return std::nullopt;
  }
  for (const auto& note : loaded.notes) std::cerr << "note: " << note << "\n";
  if (model) *model = loaded.model;
  return *loaded.scene;
}

std::optional<std::size_t> choose_solver(const scene::Scene& scene, const std::string& name,
                                         bool spring_damper_only, std::string* error) {
  std::string available;
  for (const auto& spec : scene.solvers)
    available +=
        (available.empty() ? "" : ", ") + spec.name + " (" + solver_type_name(spec.type) + ")";
  std::optional<std::size_t> chosen;
  for (std::size_t k = 0; k < scene.solvers.size() && !chosen; ++k) {
    const auto& spec = scene.solvers[k];
    if (name.empty() ? spec.type == SolverType::spring_damper : spec.name == name) chosen = k;
  }
  if (!chosen && name.empty() && !spring_damper_only && !scene.solvers.empty()) chosen = 0;
  if (!chosen) {
    *error = name.empty() ? "scene '" + scene.name +
                                "' has no spring_damper solver; its solvers are: " + available
                          : "scene '" + scene.name + "' has no solver named '" + name +
                                "'; expected one of: " + available;
    return std::nullopt;
  }
  if (spring_damper_only && scene.solvers[*chosen].type != SolverType::spring_damper) {
    *error = "solver '" + name + "' is a " + solver_type_name(scene.solvers[*chosen].type) +
             " solver; this verb varies the integrator of a spring_damper solver. The scene's "
             "solvers are: " +
             available;
    return std::nullopt;
  }
  if (scene.solvers[*chosen].adaptive_substeps) {
    // These verbs vary the step, and an adaptive solver chooses its own substeps whatever dt is.
    *error =
        "solver '" + scene.solvers[*chosen].name +
        "' has adaptive_substeps: true, so it picks its own substeps and the step this verb varies "
        "decides nothing; run it without (--set solvers." +
        std::to_string(*chosen) + ".adaptive_substeps=false)";
    return std::nullopt;
  }
  return chosen;
}

std::optional<int> whole_steps_per_frame(double frame_period, double h) {
  if (!(h > 0.0) || h > frame_period * (1.0 + 1e-12)) return std::nullopt;
  const double steps = frame_period / h;
  const double whole = std::round(steps);
  if (std::abs(steps - whole) > 1e-9 * steps || whole > 2e9) return std::nullopt;
  return static_cast<int>(whole);
}

scene::SolverSpec with_steps_per_frame(scene::SolverSpec spec, double frame_period,
                                       int steps_per_frame) {
  spec.steps_per_frame = steps_per_frame;
  spec.dt = frame_period / steps_per_frame;
  return spec;
}

}  // namespace drapelab::runner
