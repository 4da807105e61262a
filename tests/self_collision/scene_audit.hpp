// Runs a scene's first solver as `drapelab run` steps it (runner/simulate_solver.hpp) and audits
// every recorded frame: the self-intersection count, the last frame's triangle penetration and
// lowest particle.
#pragma once

#include <string>
#include <vector>

#include "drapelab/runner/simulate_solver.hpp"
#include "drapelab/scene/scene_loader.hpp"

namespace drapelab::fixtures {

struct SceneAudit {
  runner::SimulationResult result;
  int most_crossings = -1;          // over the recorded frames
  int frames = 0;                   // frames recorded, the start included
  double final_penetration = -1.0;  // m, triangle_penetration of the last frame
  double final_lowest = 0.0;        // m, the last frame's lowest particle
};

// A scene that does not load is a test failure (and an empty audit).
SceneAudit audit_scene(const scene::LoadResult& loaded);
SceneAudit audit_scene_text(const std::string& text, const std::string& name,
                            const std::vector<std::string>& overrides);

}  // namespace drapelab::fixtures
