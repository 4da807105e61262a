// The step and integrator the loader chooses when a scene names neither (docs/physics.md, "The step
// chosen when dt is left out" and "The integrator chosen when none is named").
#include <gtest/gtest.h>

#include <string>

#include "drapelab/runner/scene_setup.hpp"
#include "drapelab/runner/simulate_solver.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/scene/scene_loader.hpp"

namespace drapelab {
namespace {

const std::string kSource = DRAPELAB_SOURCE_DIR;

scene::LoadResult load(const std::string& path, const std::vector<std::string>& overrides = {}) {
  auto loaded = scene::load_scene_file(kSource + "/" + path, overrides);
  EXPECT_TRUE(loaded.ok()) << (loaded.errors.empty() ? "" : loaded.errors.front());
  return loaded;
}

// A 16-ring continuum specimen whose explicit step is 8e-7 s: 2 s of it would take minutes
// explicitly, so vbd takes it, and says why.
TEST(AutomaticIntegrator, AStiffLightContinuumGetsVbd) {
  const auto loaded = load("tests/physics/scenes/continuum_cusick_default.yaml");
  const scene::SolverSpec& ours = loaded.scene->solvers.front();
  EXPECT_EQ(ours.integrator, Integrator::vbd);
  EXPECT_EQ(ours.steps_per_frame, 2);
  EXPECT_NE(ours.note.find("integrator chosen automatically: vbd"), std::string::npos) << ours.note;
  EXPECT_LT(ours.estimated_seconds, 60.0);
  // The same scene with the integrator named keeps it, at its tiny stable step.
  const auto named = load("tests/physics/scenes/continuum_cusick_default.yaml",
                          {"solvers.0.integrator=symplectic_euler"});
  const scene::SolverSpec& explicit_run = named.scene->solvers.front();
  EXPECT_EQ(explicit_run.integrator, Integrator::symplectic_euler);
  EXPECT_GT(explicit_run.steps_per_frame, 10000);
  EXPECT_GT(explicit_run.estimated_seconds, 600.0);
  EXPECT_NE(explicit_run.faster_choice.find("vbd"), std::string::npos);
}

// The specimen runs to its end with the integrator chosen (0.5 s of it here).
TEST(AutomaticIntegrator, TheChosenIntegratorRunsTheSpecimenToItsEnd) {
  const auto loaded = load("tests/physics/scenes/continuum_cusick_default.yaml", {"duration=0.5"});
  const runner::SceneSetup setup = runner::build_scene_setup(*loaded.scene, loaded.model);
  const runner::SimulationResult result =
      runner::simulate_solver(*loaded.scene, loaded.scene->solvers.front(), setup);
  EXPECT_EQ(result.status, SolverStatus::ok) << result.message;
  EXPECT_EQ(result.frames_recorded, 31);
}

// A given dt, or a cheap explicit run, keeps symplectic Euler.
TEST(AutomaticIntegrator, AnAffordableExplicitRunKeepsSymplecticEuler) {
  const auto sheet = load("tests/contact/scenes/sheet_on_turned_box.yaml");
  EXPECT_EQ(sheet.scene->solvers.front().integrator, Integrator::symplectic_euler);
  const auto given = load("tests/physics/scenes/continuum_cusick_default.yaml",
                          {"solvers.0.dt=1e-4", "solvers.0.round_dt=true"});
  EXPECT_EQ(given.scene->solvers.front().integrator, Integrator::symplectic_euler);
}

// Self-contact, soft constraints and the air bound the explicit step like the springs do.
TEST(AutomaticStep, SelfContactAndSoftConstraintsShortenIt) {
  const auto plain = load("tests/contact/scenes/sheet_on_turned_box.yaml");
  const double plain_dt = plain.scene->solvers.front().dt;
  const auto self =
      load("tests/contact/scenes/sheet_on_turned_box.yaml",
           {"cloth.self_collision.enabled=true", "cloth.self_collision.stiffness=50000"});
  EXPECT_LT(self.scene->solvers.front().dt, 0.8 * plain_dt);
  const auto tied =
      load("tests/contact/scenes/sheet_on_turned_box.yaml",
           {"constraints=[{type: distance, a: {index: 0}, b: {point: [0, 1, 0]}, mode: soft, "
            "stiffness: 50000, damping: 0}]"});
  EXPECT_LT(tied.scene->solvers.front().dt, 0.8 * plain_dt);
}

TEST(DescribeSeconds, ReadsAsPeopleSayIt) {
  EXPECT_EQ(describe_seconds(0.83), "0.8 s");
  EXPECT_EQ(describe_seconds(42.0), "42 s");
  EXPECT_EQ(describe_seconds(780.0), "13 min");
  EXPECT_EQ(describe_seconds(9000.0), "2.5 h");
}

}  // namespace
}  // namespace drapelab
