// Shared by the garment and mesh drape suites: a scene file run through the loader and the
// runner with its first solver, and the widest gap of its seams.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "drapelab/runner/scene_setup.hpp"
#include "drapelab/runner/simulate_solver.hpp"
#include "drapelab/scene/scene_loader.hpp"

namespace drapelab::scene_runs {

struct SceneRun {
  scene::Scene scene;
  runner::SimulationResult result;
};

inline SceneRun run_scene(const std::string& path, const std::vector<std::string>& overrides) {
  const auto loaded =
      scene::load_scene_file(std::string(DRAPELAB_SOURCE_DIR) + "/" + path, overrides);
  EXPECT_TRUE(loaded.ok()) << (loaded.errors.empty() ? "" : loaded.errors.front());
  SceneRun run{*loaded.scene, {}};
  const runner::SceneSetup setup = runner::build_scene_setup(run.scene, loaded.model);
  run.result = runner::simulate_solver(run.scene, run.scene.solvers.front(), setup, {});
  EXPECT_EQ(run.result.status, SolverStatus::ok) << run.result.message;
  return run;
}

// The largest gap (m) between the sewn particles of every seam.
inline double widest_stitch(const SceneRun& run) {
  double widest = 0.0;
  const Eigen::Matrix3Xd& x = run.result.final_state.x;
  for (const scene::SeamSpec& seam : run.scene.cloth.seams)
    for (std::size_t k = 0; k < seam.a.size(); ++k)
      widest = std::max(widest, (x.col(seam.a[k]) - x.col(seam.b[k])).norm());
  return widest;
}

}  // namespace drapelab::scene_runs
