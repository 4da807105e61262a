// SimulationResult's timing record (runner/simulate_solver.hpp): the stepping seconds at every
// recorded frame, and the cost of the run's second half that drapelab bench reports.
#include <gtest/gtest.h>

#include <string>

#include "drapelab/runner/scene_setup.hpp"
#include "drapelab/runner/simulate_solver.hpp"
#include "drapelab/scene/scene_loader.hpp"

namespace drapelab {
namespace {

TEST(SimulationResult, SecondHalfCostIsTheStepTimeFromTheMiddleFrameOn) {
  runner::SimulationResult result;
  result.stepping_seconds_at_frame = {0.0, 1.0, 2.0, 4.0, 8.0};  // frames 0..4
  // Frames 2 to 4: 6 s of stepping for 2 frames of 0.1 s.
  EXPECT_DOUBLE_EQ(result.second_half_wall_seconds_per_simulated_second(0.1), 30.0);
  result.stepping_seconds_at_frame = {0.0, 1.0, 2.0, 4.0, 8.0, 9.0};  // frames 0..5: from frame 2
  EXPECT_DOUBLE_EQ(result.second_half_wall_seconds_per_simulated_second(0.5), 7.0 / 1.5);
  result.stepping_seconds_at_frame = {0.0, 1.0};  // too short to have halves
  EXPECT_EQ(result.second_half_wall_seconds_per_simulated_second(0.1), 0.0);
}

TEST(SimulationResult, RecordsTheSteppingSecondsAtEveryFrame) {
  const std::string text = R"(name: short_fall
duration: 0.2
frame_rate: 20
cloth:
  shape: grid
  size: [0.2, 0.2]
  resolution: [9, 9]
  mass: 0.01
solvers:
  - name: ours
    type: spring_damper
)";
  const auto loaded = scene::load_scene_text(text, "short_fall.yaml", {});
  ASSERT_TRUE(loaded.ok()) << (loaded.errors.empty() ? "" : loaded.errors.front());
  const runner::SceneSetup setup = runner::build_scene_setup(*loaded.scene);
  const runner::SimulationResult result =
      runner::simulate_solver(*loaded.scene, loaded.scene->solvers.front(), setup);
  ASSERT_EQ(result.status, SolverStatus::ok) << result.message;
  ASSERT_EQ(result.frames_recorded, 5);  // frames 0 to 4
  ASSERT_EQ(result.stepping_seconds_at_frame.size(), 5u);
  EXPECT_EQ(result.stepping_seconds_at_frame.front(), 0.0);
  for (std::size_t k = 1; k < result.stepping_seconds_at_frame.size(); ++k)
    EXPECT_GE(result.stepping_seconds_at_frame[k], result.stepping_seconds_at_frame[k - 1]);
  EXPECT_EQ(result.stepping_seconds_at_frame.back(), result.wall_seconds);
  EXPECT_GT(result.second_half_wall_seconds_per_simulated_second(0.05), 0.0);
}

}  // namespace
}  // namespace drapelab
