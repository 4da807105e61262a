// Unit tests of the scene loader (drapelab::scene::load_scene_text / load_scene_file) on scenes
// that load: every value read and every default filled in, the solvers' options, steps and frames,
// and a scene with several errors at once. Each bad input on its own: test_scene_errors.cpp; --set
// overrides: test_scene_overrides.cpp; the resolved.yaml round trip: test_resolved_scene.cpp.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "base_scene.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "drapelab/stability.hpp"
#include "fixtures/scene_text.hpp"

namespace {

using namespace drapelab::fixtures;      // fixtures/scene_text.hpp
using namespace drapelab::loader_tests;  // base_scene.hpp

namespace fs = std::filesystem;
using drapelab::scene::load_scene_file;
using drapelab::scene::load_scene_text;
using drapelab::scene::resolved_scene_yaml;
using drapelab::scene::Scene;

// ---------------------------------------------------------------------------------------------
// Valid scenes and defaults

TEST(SceneLoader, BaseSceneLoadsWithEveryValue) {
  const auto result = load(kBase);
  ASSERT_LOADS(result);
  const Scene& s = *result.scene;
  EXPECT_TRUE(result.notes.empty());
  EXPECT_EQ(s.name, "base");
  EXPECT_DOUBLE_EQ(s.duration, 0.5);
  EXPECT_DOUBLE_EQ(s.frame_rate, 60.0);
  EXPECT_EQ(s.frame_count(), 30);
  EXPECT_EQ(s.seed, 1u);
  EXPECT_EQ(s.cloth.shape, "grid");
  EXPECT_EQ(s.cloth.grid.nx, 5);
  EXPECT_EQ(s.cloth.grid.ny, 4);
  EXPECT_EQ(s.cloth.grid.plane, drapelab::GridPlane::xz);
  EXPECT_DOUBLE_EQ(s.cloth.grid.size.x(), 1.0);
  EXPECT_DOUBLE_EQ(s.cloth.grid.size.y(), 0.5);
  ASSERT_TRUE(s.cloth.grid.mass.has_value());
  EXPECT_DOUBLE_EQ(*s.cloth.grid.mass, 0.2);
  EXPECT_FALSE(s.cloth.grid.areal_density.has_value());
  EXPECT_DOUBLE_EQ(s.cloth.grid.thickness, 0.004);
  EXPECT_DOUBLE_EQ(s.cloth.perturbation, 0.001);
  EXPECT_DOUBLE_EQ(s.cloth.air_damping, 0.1);
  EXPECT_DOUBLE_EQ(s.cloth.grid.stretch.ks, 500.0);
  EXPECT_DOUBLE_EQ(s.cloth.grid.shear.kd, 0.05);
  EXPECT_DOUBLE_EQ(s.cloth.grid.bend.ks, 5.0);
  EXPECT_EQ(s.cloth.grid.pins.size(), 4u);
  EXPECT_DOUBLE_EQ(s.contact.stiffness, 4000.0);
  EXPECT_DOUBLE_EQ(s.contact.damping, 4.0);
  EXPECT_DOUBLE_EQ(s.contact.friction, 0.2);
  ASSERT_EQ(s.solvers.size(), 1u);
  EXPECT_EQ(s.solvers[0].name, "ours");
  EXPECT_EQ(s.solvers[0].type, drapelab::SolverType::spring_damper);
  EXPECT_EQ(s.solvers[0].integrator, drapelab::Integrator::symplectic_euler);
  EXPECT_EQ(s.solvers[0].steps_per_frame, 16);
  EXPECT_DOUBLE_EQ(s.solvers[0].dt, 1.0 / 960.0);
  EXPECT_TRUE(s.solvers[0].note.empty());
}

TEST(SceneLoader, MinimalSceneGetsTheContractDefaults) {
  const auto result = load(kMinimal);
  ASSERT_LOADS(result);
  const Scene& s = *result.scene;
  EXPECT_DOUBLE_EQ(s.frame_rate, 60.0);
  EXPECT_EQ(s.gravity, Eigen::Vector3d(0, -9.81, 0));
  EXPECT_EQ(s.seed, 0u);
  EXPECT_EQ(s.description, "");
  EXPECT_EQ(s.cloth.shape, "grid");
  EXPECT_EQ(s.cloth.grid.plane, drapelab::GridPlane::xz);
  EXPECT_EQ(s.cloth.grid.size, Eigen::Vector2d(1, 1));
  EXPECT_EQ(s.cloth.grid.center, Eigen::Vector3d(0, 1, 0));
  EXPECT_DOUBLE_EQ(s.cloth.grid.thickness, 0.005);
  EXPECT_DOUBLE_EQ(s.cloth.perturbation, 0.0);
  EXPECT_DOUBLE_EQ(s.cloth.air_damping, 0.0);
  EXPECT_TRUE(s.cloth.grid.pins.empty());
  EXPECT_DOUBLE_EQ(s.contact.stiffness, 5000.0);
  EXPECT_DOUBLE_EQ(s.contact.damping, 5.0);
  EXPECT_DOUBLE_EQ(s.contact.friction, 0.3);
  ASSERT_EQ(s.solvers.size(), 1u);
  EXPECT_EQ(s.solvers[0].name, "spring_damper");  // the name defaults to the type
  EXPECT_EQ(s.solvers[0].integrator, drapelab::Integrator::symplectic_euler);
  EXPECT_GT(s.solvers[0].steps_per_frame, 0);
  EXPECT_NEAR(s.solvers[0].dt * s.solvers[0].steps_per_frame, 1.0 / 60.0, 1e-15);
  EXPECT_EQ(s.output.meshes, drapelab::scene::MeshOutput::none);
}

// Without dt, the step is 0.9 of the integrator's stable step estimate (0.1 of the symplectic bound
// when the estimate is zero), implicit Euler's is 1/240 s and vbd's 1/120 s (neither has a stable
// step to follow), rounded down to whole steps per frame.
TEST(SceneLoader, AutomaticDtIsBelowTheStableStepAndDividesTheFrame) {
  for (const std::string& integrator : drapelab::integrator_names()) {
    SCOPED_TRACE(integrator);
    const auto result =
        load(with_line(without_lines(kBase, 34, 34), 33, "    integrator: " + integrator));
    ASSERT_LOADS(result);
    const Scene& s = *result.scene;
    const auto& solver = s.solvers[0];
    const drapelab::ClothModel model = drapelab::build_grid_cloth(s.cloth.grid);
    double bound = drapelab::stable_step_estimate(model, s.cloth.air_damping, s.contact_rates(),
                                                  solver.integrator);
    double factor = 0.9;
    if (bound == 0.0) {
      bound = drapelab::symplectic_euler_stable_step(model, s.cloth.air_damping, s.contact_rates());
      factor = 0.1;
    }
    if (solver.integrator == drapelab::Integrator::implicit_euler) {
      bound = 1.0 / 240.0;
      factor = 1.0;
    }
    if (solver.integrator == drapelab::Integrator::vbd) {
      bound = 1.0 / 120.0;
      factor = 1.0;
    }
    ASSERT_GT(solver.steps_per_frame, 0);
    EXPECT_LE(solver.dt, factor * bound * (1 + 1e-12));
    if (solver.steps_per_frame > 1) {
      EXPECT_GT(solver.dt, factor * bound * (solver.steps_per_frame - 1) / solver.steps_per_frame *
                               (1 - 1e-12))
          << "one step per frame fewer would also be below the bound";
    }
    EXPECT_NEAR(solver.dt * solver.steps_per_frame, s.frame_period(), 1e-15);
    EXPECT_NE(solver.note.find("automatic"), std::string::npos) << solver.note;
  }
}

TEST(SceneLoader, ChainLoadsWithMass) {
  EXPECT_LOADS(load(with_line(kBase, 10, "  resolution: [1, 4]")));
}

TEST(SceneLoader, ArealDensityOnASheetLoads) {
  const auto result = load(with_line(kBase, 13, "  areal_density: 0.3"));
  ASSERT_LOADS(result);
  EXPECT_FALSE(result.scene->cloth.grid.mass.has_value());
  ASSERT_TRUE(result.scene->cloth.grid.areal_density.has_value());
  EXPECT_DOUBLE_EQ(*result.scene->cloth.grid.areal_density, 0.3);
}

TEST(SceneLoader, ZeroShearAndBendAreAllowed) {
  auto text = with_line(kBase, 19, "    shear: {ks: 0, kd: 0}");
  text = with_line(text, 20, "    bend: {ks: 0, kd: 0}");
  EXPECT_LOADS(load(text));
}

TEST(SceneLoader, EmptyCollidersListIsAccepted) { EXPECT_LOADS(load(kBase + "colliders: []\n")); }

TEST(SceneLoader, MissingSolversGiveTheContractsDefaultPair) {
  const auto result = load(without_lines(kBase, 30, 34));
  ASSERT_LOADS(result);
  ASSERT_EQ(result.scene->solvers.size(), 2u);
  EXPECT_EQ(result.scene->solvers[0].type, drapelab::SolverType::spring_damper);
  EXPECT_EQ(result.scene->solvers[0].name, "spring_damper");
  EXPECT_EQ(result.scene->solvers[1].type, drapelab::SolverType::bullet_softbody);
  EXPECT_EQ(result.scene->solvers[1].name, "bullet_softbody");
}

// YAML's own spelling of infinity is refused too (as not a plain number).
TEST(SceneLoader, YamlSpellingOfInfinityIsRefused) {
  EXPECT_FALSE(load(with_line(kBase, 3, "duration: .inf")).ok());
}

// ---------------------------------------------------------------------------------------------
// Pins

TEST(SceneLoader, EveryNamedPinSetLoads) {
  for (const char* name :
       {"corners", "top_corners", "edge_min_x", "edge_max_x", "edge_min_z", "edge_max_z", "center"})
    EXPECT_LOADS(load(with_line(kBase, 22, std::string("    - ") + name))) << name;
}

// A vertical (xy) sheet has y edges (its ball pin, placed for the horizontal sheet, removed).
TEST(SceneLoader, AVerticalSheetHasYEdges) {
  auto vertical = with_line(kBase, 11, "  plane: xy");
  vertical = without_lines(vertical, 25, 25);
  EXPECT_LOADS(load(with_line(vertical, 22, "    - edge_min_y")));
}

TEST(SceneLoader, PinsAtTheLastGridCoordinateAndIndexLoad) {
  EXPECT_LOADS(load(with_line(kBase, 23, "    - [4, 3]")));  // the far corner is inside
  EXPECT_LOADS(load(with_line(kBase, 24, "    - {index: 19}")));
}

// ---------------------------------------------------------------------------------------------
// Colliders and solver options

TEST(SceneLoader, CollidersLoadWithTheirDefaults) {
  const auto result = load(
      kBase + "colliders:\n  - {name: ball, type: sphere, center: [0, 0.5, 0], radius: 0.3}\n");
  ASSERT_TRUE(result.ok()) << (result.errors.empty() ? "" : result.errors[0]);
  ASSERT_EQ(result.scene->colliders.size(), 1u);
  EXPECT_EQ(result.scene->colliders[0].name, "ball");
  EXPECT_DOUBLE_EQ(result.scene->colliders[0].radius, 0.3);
  EXPECT_DOUBLE_EQ(result.scene->colliders[0].friction, result.scene->contact.friction);
}

TEST(SceneLoader, BulletDeformableTakesAMargin) {
  const auto result =
      load(with_line(with_line(kBase, 32, "    type: bullet_deformable"), 33, "    margin: 0.006"));
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->solvers[0].type, drapelab::SolverType::bullet_deformable);
  EXPECT_DOUBLE_EQ(result.scene->solvers[0].margin, 0.006);
}

TEST(SceneLoader, BulletSoftBodyTakesItsOptions) {
  const std::string bullet =
      with_line(with_line(kBase, 32, "    type: bullet_softbody"), 33,
                "    iterations: 4\n    margin: 0.01\n    voxel_size: 0.002\n"
                "    kLST: {shear: 0.5}");
  const auto result = load(bullet);
  ASSERT_LOADS(result);
  const auto& solver = result.scene->solvers[0];
  EXPECT_EQ(solver.iterations, 4);
  EXPECT_DOUBLE_EQ(solver.margin, 0.01);
  EXPECT_DOUBLE_EQ(solver.voxel_size, 0.002);
  EXPECT_FALSE(solver.link_stiffness[0].has_value());
  EXPECT_DOUBLE_EQ(*solver.link_stiffness[1], 0.5);
  // Defaults: margin = the cloth's thickness; an integrator is ours, not Bullet's.
  const auto plain =
      load(with_line(with_line(kBase, 32, "    type: bullet_softbody"), 33, "    round_dt: false"));
  ASSERT_LOADS(plain);
  EXPECT_DOUBLE_EQ(plain.scene->solvers[0].margin, 0.004);
}

TEST(SceneLoader, EveryIntegratorLoads) {
  for (const std::string& integrator : drapelab::integrator_names()) {
    const auto result = load(with_line(kBase, 33, "    integrator: " + integrator));
    ASSERT_LOADS(result);
    EXPECT_EQ(drapelab::integrator_name(result.scene->solvers[0].integrator), integrator);
  }
}

TEST(SceneLoader, ImplicitOptionsAreRead) {
  const auto base = with_line(kBase, 33, "    integrator: implicit_euler");
  const auto result = load(base + "    implicit: {tolerance: 1e-8, max_iterations: 50}\n");
  ASSERT_LOADS(result);
  EXPECT_DOUBLE_EQ(result.scene->solvers[0].implicit.tolerance, 1e-8);
  EXPECT_EQ(result.scene->solvers[0].implicit.max_iterations, 50);
  const auto defaults = load(base);
  ASSERT_LOADS(defaults);
  EXPECT_DOUBLE_EQ(defaults.scene->solvers[0].implicit.tolerance,
                   drapelab::ImplicitSolveSettings{}.tolerance);
}

TEST(SceneLoader, AdaptiveSubstepsAreReadAndGetAHalfFrameStep) {
  // Without dt, an adaptive solver steps at 1/120 s and splits each step itself.
  const auto base = without_lines(kBase, 34, 34);
  const auto result = load(base + "    adaptive_substeps: true\n");
  ASSERT_LOADS(result);
  EXPECT_TRUE(result.scene->solvers[0].adaptive_substeps);
  EXPECT_EQ(result.scene->solvers[0].steps_per_frame, 2);
  const auto plain = load(base);
  ASSERT_LOADS(plain);
  EXPECT_FALSE(plain.scene->solvers[0].adaptive_substeps);
}

TEST(SceneLoader, ExplicitEulerIsAvailable) {
  const auto result = load(with_line(kBase, 33, "    integrator: explicit_euler"));
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->solvers[0].integrator, drapelab::Integrator::explicit_euler);
}

// ---------------------------------------------------------------------------------------------
// Solvers, steps and frames

TEST(SceneLoader, TwoSolversWithDistinctNamesLoadInOrder) {
  const auto result = load(
      kBase + "  - name: theirs\n    integrator: explicit_euler\n    dt: 0.0005208333333333333\n");
  ASSERT_LOADS(result);
  ASSERT_EQ(result.scene->solvers.size(), 2u);
  EXPECT_EQ(result.scene->solvers[0].name, "ours");
  EXPECT_EQ(result.scene->solvers[1].name, "theirs");
  EXPECT_EQ(result.scene->solvers[1].steps_per_frame, 32);
}

TEST(SceneLoader, RoundDtRoundsDownToAWholeNumberOfStepsWithANote) {
  const auto result =
      load(insert_after(with_line(kBase, 34, "    dt: 0.001"), 34, "    round_dt: true"));
  ASSERT_LOADS(result);
  const auto& solver = result.scene->solvers[0];
  EXPECT_EQ(solver.steps_per_frame, 17);  // 16.67 steps per frame rounded up: dt never grows
  EXPECT_DOUBLE_EQ(solver.dt, (1.0 / 60.0) / 17.0);
  EXPECT_LE(solver.dt, 0.001);
  ASSERT_EQ(result.notes.size(), 1u);
  EXPECT_NE(result.notes[0].find("ours"), std::string::npos) << result.notes[0];
  EXPECT_NE(result.notes[0].find("rounded"), std::string::npos) << result.notes[0];
  EXPECT_NE(result.notes[0].find("17 steps per frame"), std::string::npos) << result.notes[0];
  EXPECT_NE(solver.note.find("rounded"), std::string::npos);
}

TEST(SceneLoader, RoundDtLeavesADividingDtAlone) {
  const auto result = load(insert_after(kBase, 34, "    round_dt: true"));
  ASSERT_LOADS(result);
  EXPECT_TRUE(result.notes.empty());
  EXPECT_EQ(result.scene->solvers[0].steps_per_frame, 16);
}

// A step longer than a frame cannot be rounded down to a whole number per frame.
TEST(SceneLoader, RoundDtDoesNotRescueADtLargerThanTheFramePeriod) {
  EXPECT_FALSE(
      load(insert_after(with_line(kBase, 34, "    dt: 0.05"), 34, "    round_dt: true")).ok());
}

TEST(SceneLoader, DtEqualToTheFramePeriodIsOneStepPerFrame) {
  const auto result = load(with_line(kBase, 34, "    dt: 0.016666666666666666"));
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->solvers[0].steps_per_frame, 1);
}

// Run-length bounds (run_limits.hpp): at most 10^7 steps per frame and from 1 to 10^7 frames.
TEST(SceneLoader, StepsPerFrameLoadUpToTenMillion) {
  // Just under the bound still loads, with the exact count.
  const auto result = load(with_line(kBase, 34, "    dt: 3.3333333333333334e-09"));
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->solvers[0].steps_per_frame, 5'000'000);
  EXPECT_FALSE(load(with_line(kBase, 34, "    dt: 8.333333333333334e-10")).ok());  // 2e7 steps
  // round_dt does not rescue it: rounding would overflow the count it rounds to.
  EXPECT_FALSE(
      load(insert_after(with_line(kBase, 34, "    dt: 1e-13"), 34, "    round_dt: true")).ok());
}

TEST(SceneLoader, FrameCountLoadsUpToTenMillion) {
  const auto most = load(with_line(kBase, 3, "duration: 166666.66666666666"));  // 10^7 frames
  ASSERT_LOADS(most);
  EXPECT_EQ(most.scene->frame_count(), 10'000'000);
  EXPECT_FALSE(load(with_line(kBase, 3, "duration: 166667.66666666666")).ok());  // 10^7 + 60 frames
}

TEST(SceneLoader, OtherFrameRatesWork) {
  const auto result = load(with_line(kBase, 4, "frame_rate: 24"));
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->frame_count(), 12);
  EXPECT_EQ(result.scene->solvers[0].steps_per_frame, 40);  // (1/24 s) / (1/960 s)
}

// ---------------------------------------------------------------------------------------------
// Several errors in one scene

TEST(SceneLoader, SeveralErrorsAreAllReportedAtOnce) {
  auto text = with_line(kBase, 3, "durration: 0.5");
  text = with_line(text, 11, "  plane: yz");
  text = with_line(text, 14, "  thickness: 0");
  text = with_line(text, 18, "    stretch: {ks: -3, kd: 0.1}");
  text = with_line(text, 28, "  damping: -4");
  text = with_line(text, 33, "    integrator: rk5");
  const auto result = load(text);
  ASSERT_FALSE(result.ok());
  EXPECT_TRUE(HasError(result, at(3), {"durration is not a known key"}));
  EXPECT_TRUE(HasError(result, at(11), {"cloth.plane"}));
  EXPECT_TRUE(HasError(result, at(14), {"cloth.thickness must be >= 1e-06"}));
  EXPECT_TRUE(HasError(result, at(18), {"cloth.springs.stretch.ks must be > 0"}));
  EXPECT_TRUE(HasError(result, at(28), {"contact.damping must be >= 0"}));
  EXPECT_TRUE(HasError(result, at(33), {"solvers.0.integrator must be one of", "rk4"}));
  EXPECT_GE(result.errors.size(), 6u);
  EXPECT_FALSE(result.scene.has_value());
}

TEST(SceneLoader, EveryErrorCarriesTheDisplayName) {
  auto text = with_line(kBase, 13, "  mass: -1");
  text = with_line(text, 5, "gravity: [1]");
  const auto result = load_scene_text(text, "some/folder/odd name.yaml");
  ASSERT_FALSE(result.ok());
  for (const auto& error : result.errors)
    EXPECT_EQ(error.rfind("some/folder/odd name.yaml:", 0), 0u) << error;
}

// ---------------------------------------------------------------------------------------------
// load_scene_file

class SceneFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("drapelab_scene_file_" + std::string(info->name()) + "_" +
            std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    ASSERT_TRUE(fs::create_directory(dir_));
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  fs::path dir_;
};

TEST_F(SceneFile, MissingFileIsAClearError) {
  const fs::path missing = dir_ / "no_such_scene.yaml";
  const auto result = load_scene_file(missing);
  ASSERT_FALSE(result.ok());
  ASSERT_EQ(result.errors.size(), 1u);
  EXPECT_NE(result.errors[0].find(missing.string()), std::string::npos) << result.errors[0];
  EXPECT_NE(result.errors[0].find("cannot be read"), std::string::npos) << result.errors[0];
  EXPECT_NE(result.errors[0].find("no such file"), std::string::npos) << result.errors[0];
}

TEST_F(SceneFile, FileLoadsAndKnowsItsSource) {
  const fs::path path = write("good.yaml", kBase);
  const auto result = load_scene_file(path);
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->source, path);
  EXPECT_NE(resolved_scene_yaml(*result.scene).find(path.string()), std::string::npos);
}

TEST_F(SceneFile, FileErrorsNameThePathAndLine) {
  const fs::path path = write("bad.yaml", with_line(kBase, 18, "    stretch: {ks: -3, kd: 0.1}"));
  const auto result = load_scene_file(path, {"seed=-2"});
  ASSERT_FALSE(result.ok());
  EXPECT_TRUE(HasError(result, path.string() + ":18:", {"cloth.springs.stretch.ks must be > 0"}));
  EXPECT_TRUE(HasError(result, path.string() + ": --set seed=-2:", {"seed must be >= 0"}));
}

// std::ifstream opens a directory without error on Linux; a folder given as the scene must be
// reported as such, not as an empty scene.
TEST_F(SceneFile, ADirectoryIsNotReportedAsAnEmptyScene) {
  const auto result = load_scene_file(dir_);
  ASSERT_FALSE(result.ok());
  ASSERT_EQ(result.errors.size(), 1u);
  EXPECT_EQ(result.errors[0].find("the scene is empty"), std::string::npos) << result.errors[0];
  EXPECT_NE(result.errors[0].find("not a file"), std::string::npos) << result.errors[0];
}

}  // namespace
