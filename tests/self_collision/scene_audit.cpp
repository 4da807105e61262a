// A scene's first solver, audited every frame (scene_audit.hpp).
#include "scene_audit.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "drapelab/runner/scene_setup.hpp"

namespace drapelab::fixtures {

SceneAudit audit_scene(const scene::LoadResult& loaded) {
  SceneAudit audit;
  if (!loaded.ok()) {
    ADD_FAILURE() << "the scene does not load: "
                  << (loaded.errors.empty() ? "" : loaded.errors.front());
    return audit;
  }
  const scene::Scene& scene = *loaded.scene;
  const runner::SceneSetup setup = runner::build_scene_setup(scene);
  runner::SimulationOptions options;
  options.on_frame = [&](int, const ClothState& state, const ClothMetrics& metrics) {
    audit.most_crossings = std::max(audit.most_crossings, metrics.self_intersections.value_or(-1));
    audit.final_penetration = metrics.triangle_penetration.value_or(-1.0);
    audit.final_lowest = state.x.row(1).minCoeff();
    ++audit.frames;
  };
  audit.result = runner::simulate_solver(scene, scene.solvers.front(), setup, options);
  return audit;
}

SceneAudit audit_scene_text(const std::string& text, const std::string& name,
                            const std::vector<std::string>& overrides) {
  return audit_scene(scene::load_scene_text(text, name, overrides));
}

}  // namespace drapelab::fixtures
