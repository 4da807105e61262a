// The viewer's session without a window: a drag made live pulls the grabbed particle toward the
// target in every solver, and the scene it saves (interactions:) replays it exactly: run from the
// saved file, in a session and by `drapelab run`, every solver moves the same particle along the
// same path.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "drapelab/run_folder/point_cache.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "fixtures/cli.hpp"
#include "fixtures/scene_text.hpp"
#include "live_session.hpp"

namespace drapelab {
namespace {

// A small hanging sheet (pinned at its top corners) with our cloth and both Bullet cloths.
const char* const kScene = R"(name: drag_sheet
duration: 2.0
frame_rate: 60
cloth:
  shape: grid
  size: [0.5, 0.5]
  resolution: [9, 9]
  plane: xy
  center: [0, 1, 0]
  mass: 0.05
  pins: [top_corners]
solvers:
  - {name: ours, type: spring_damper}
  - {name: classic, type: bullet_softbody}
  - {name: deformable, type: bullet_deformable}
)";

std::filesystem::path write_text(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path;
}

std::string scientific(double value) {
  std::ostringstream text;
  text << std::scientific << std::setprecision(3) << value;
  return text.str();
}

viewer::LiveSession session_of(const std::filesystem::path& file) {
  const auto loaded = scene::load_scene_file(file, {});
  EXPECT_TRUE(loaded.ok()) << (loaded.errors.empty() ? "" : loaded.errors.front());
  return viewer::LiveSession(*loaded.scene, loaded.model);
}

// Drags the bottom corner particle out and up for 30 frames (the target moving every frame, as the
// mouse does), lets go, runs 20 frames more; returns each solver's path of the particle.
TEST(LiveSession, ADragIsReplayedExactlyFromTheSavedScene) {
  const auto file = write_text("drapelab_drag_sheet.yaml", kScene);
  viewer::LiveSession live = session_of(file);
  constexpr int kParticle = 8;  // grid (8, 0): the bottom right corner
  const Eigen::Vector3d start = live.solvers().front().solver->state().x.col(kParticle);
  std::vector<std::vector<Eigen::Vector3d>> live_path(live.solvers().size());
  auto record = [&](viewer::LiveSession& s, std::vector<std::vector<Eigen::Vector3d>>& path) {
    for (std::size_t k = 0; k < s.solvers().size(); ++k)
      path[k].push_back(s.solvers()[k].solver->state().x.col(kParticle));
  };
  for (int f = 0; f < 10; ++f) live.advance_frame(), record(live, live_path);
  live.press(kParticle, start, 5.0);
  Eigen::Vector3d target = start;
  for (int f = 0; f < 30; ++f) {
    target += Eigen::Vector3d(0.01, 0.01, 0.004);  // m per frame
    live.move(target);
    live.advance_frame();
    record(live, live_path);
  }
  live.release();
  for (int f = 0; f < 20; ++f) live.advance_frame(), record(live, live_path);
  ASSERT_EQ(live.recorded().size(), 1u);
  EXPECT_EQ(live.recorded().front().particle, kParticle);
  for (const auto& solver : live.solvers()) {
    SCOPED_TRACE(solver.solver->name());
    ASSERT_EQ(solver.solver->status(), SolverStatus::ok) << solver.solver->message();
    // Pulled: at the release the particle was well on its way from its start to the target.
    const Eigen::Vector3d at_release = live_path[&solver - live.solvers().data()][39];
    EXPECT_LT((at_release - target).norm(), 0.6 * (start - target).norm());
  }

  const auto saved = std::filesystem::temp_directory_path() / "drapelab_drag_sheet_saved.yaml";
  live.save(saved);
  viewer::LiveSession replay = session_of(saved);
  ASSERT_EQ(replay.scene().interactions.size(), 1u);
  std::vector<std::vector<Eigen::Vector3d>> replay_path(replay.solvers().size());
  for (int f = 0; f < 60; ++f) replay.advance_frame(), record(replay, replay_path);
  for (std::size_t k = 0; k < live.solvers().size(); ++k) {
    SCOPED_TRACE(live.solvers()[k].solver->name());
    double worst = 0.0;  // m
    for (std::size_t f = 0; f < live_path[k].size(); ++f)
      worst = std::max(worst, (live_path[k][f] - replay_path[k][f]).norm());
    // The saved keyframes are the live ones, written to 17 significant digits: the same targets.
    EXPECT_LT(worst, 1e-9);
    RecordProperty(live.solvers()[k].solver->name() + "_replay_difference_m", scientific(worst));
  }

  // drapelab run on the saved scene: its point caches (float32) hold the same path.
  const auto out = std::filesystem::temp_directory_path() / "drapelab_drag_sheet_run";
  const auto run = fixtures::run_drapelab({"run", saved.string(), "--out", out.string(), "--force",
                                           "--meshes", "pc2", "--set", "duration=1", "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (std::size_t k = 0; k < live.solvers().size(); ++k) {
    const std::string name = live.solvers()[k].solver->name();
    SCOPED_TRACE(name);
    const auto cache = out / "meshes" / (name + ".pc2");
    const int points = live.model().particle_count();
    double worst = 0.0;  // m
    for (std::size_t f = 0; f < live_path[k].size(); ++f) {
      const auto x = run_folder::read_pc2_frame(cache, points, static_cast<int>(f) + 1);
      ASSERT_TRUE(x) << cache;
      worst = std::max(worst, (Eigen::Vector3d(x->col(kParticle)) - live_path[k][f]).norm());
    }
    EXPECT_LT(worst, 1e-6);  // float32 positions of about 1 m
    RecordProperty(name + "_drapelab_run_difference_m", scientific(worst));
  }
  std::filesystem::remove_all(out);
}

// A slider's change: every solver continues from where it was, with the new springs (a stiffer
// cloth stretches less under the same weight), and the saved scene carries the new value.
TEST(LiveSession, AParameterChangeContinuesFromThePresentState) {
  const auto file = write_text("drapelab_drag_sheet_parameters.yaml", kScene);
  viewer::LiveSession live = session_of(file);
  for (int f = 0; f < 30; ++f) live.advance_frame();
  std::vector<Eigen::Matrix3Xd> before;
  for (const auto& solver : live.solvers()) before.push_back(solver.solver->state().x);
  const double stretch_before = live.solvers().front().metrics.max_stretch;
  viewer::LiveSession::Parameters p = live.parameters();
  p.stretch_ks *= 4.0;
  live.set_parameters(p);
  for (std::size_t k = 0; k < live.solvers().size(); ++k)
    EXPECT_TRUE(live.solvers()[k].solver->state().x == before[k]);  // the same positions
  EXPECT_EQ(live.scene().cloth.grid.stretch.ks, p.stretch_ks);
  for (int f = 0; f < 60; ++f) live.advance_frame();
  for (const auto& solver : live.solvers())
    ASSERT_EQ(solver.solver->status(), SolverStatus::ok) << solver.solver->message();
  EXPECT_LT(live.solvers().front().metrics.max_stretch, 0.6 * stretch_before);
  EXPECT_NE(live.scene_with_recording().find("ks: " + std::to_string(int(p.stretch_ks))),
            std::string::npos);
}

// The viewer checks every frame as `drapelab run` does: a stretch past the solver's
// runaway_stretch stops that solver as unstable, with the spring, the frame and what to try, while
// the others go on. The sheet hangs from two corners; its springs stretch well past 0.1 % under
// its weight within a few frames.
TEST(LiveSession, ARunawayStretchStopsTheSolverAsDrapelabRunDoes) {
  std::string text = kScene;
  const std::string ours = "  - {name: ours, type: spring_damper}";
  text.replace(text.find(ours), ours.size(),
               "  - {name: ours, type: spring_damper, runaway_stretch: 0.001}");
  const auto file = write_text("drapelab_drag_sheet_runaway.yaml", text);
  viewer::LiveSession live = session_of(file);
  for (int f = 0; f < 30; ++f) live.advance_frame();
  const viewer::LiveSolver& stopped = live.solvers().front();
  EXPECT_EQ(stopped.status, SolverStatus::unstable);
  EXPECT_NE(stopped.message.find("runaway_stretch"), std::string::npos) << stopped.message;
  EXPECT_NE(stopped.message.find("Try:"), std::string::npos) << stopped.message;
  for (std::size_t k = 1; k < live.solvers().size(); ++k)
    EXPECT_EQ(live.solvers()[k].status, SolverStatus::ok) << live.solvers()[k].message;
}

}  // namespace
}  // namespace drapelab
