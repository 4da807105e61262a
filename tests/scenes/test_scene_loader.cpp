// Unit tests of the scene loader (drapelab::scene::load_scene_text / load_scene_file): every
// validation rule of shared/scene-format.md and scene_loader.cpp, each checked for the display file
// name, the 1-based line (or the --set override), the key path and the expected-value wording; the
// --set overrides; and the resolved.yaml round trip.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "drapelab/grid_cloth.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "fixtures/scene_text.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "drapelab/stability.hpp"

namespace {

using namespace drapelab::fixtures;  // fixtures/scene_text.hpp

namespace fs = std::filesystem;
using drapelab::scene::load_scene_file;
using drapelab::scene::load_scene_text;
using drapelab::scene::LoadResult;
using drapelab::scene::resolved_scene_yaml;
using drapelab::scene::Scene;

constexpr const char* kName = "drape_test.yaml";  // the display name every message must carry

// A small valid scene using every key the loader knows. Line numbers matter: the tests below
// replace whole lines by number, and expect errors at those lines.
const std::string kBase =
    "# base scene for the loader tests\n"                  //  1
    "name: base\n"                                          //  2
    "duration: 0.5\n"                                       //  3
    "frame_rate: 60\n"                                      //  4
    "gravity: [0, -9.81, 0]\n"                              //  5
    "seed: 1\n"                                             //  6
    "cloth:\n"                                              //  7
    "  shape: grid\n"                                       //  8
    "  size: [1.0, 0.5]\n"                                  //  9
    "  resolution: [5, 4]\n"                                // 10
    "  plane: xz\n"                                         // 11
    "  center: [0, 1, 0]\n"                                 // 12
    "  mass: 0.2\n"                                         // 13
    "  thickness: 0.004\n"                                  // 14
    "  perturbation: 0.001\n"                               // 15
    "  air_damping: 0.1\n"                                  // 16
    "  springs:\n"                                          // 17
    "    stretch: {ks: 500, kd: 0.1}\n"                     // 18
    "    shear: {ks: 50, kd: 0.05}\n"                       // 19
    "    bend: {ks: 5, kd: 0.01}\n"                         // 20
    "  pins:\n"                                             // 21
    "    - corners\n"                                       // 22
    "    - [0, 3]\n"                                        // 23
    "    - {index: 2}\n"                                    // 24
    "    - {within: {center: [0, 1, 0], radius: 0.2}}\n"   // 25
    "contact:\n"                                            // 26
    "  stiffness: 4000\n"                                   // 27
    "  damping: 4\n"                                        // 28
    "  friction: 0.2\n"                                     // 29
    "solvers:\n"                                            // 30
    "  - name: ours\n"                                      // 31
    "    type: spring_damper\n"                             // 32
    "    integrator: symplectic_euler\n"                    // 33
    "    dt: 0.001041666666666666667\n";                    // 34  (1/960 s: 16 steps per frame)

// The smallest valid scene: everything else takes its default.
const std::string kMinimal =
    "name: minimal\n"
    "duration: 1\n"
    "cloth:\n"
    "  resolution: [3, 3]\n"
    "  mass: 0.1\n"
    "solvers: [{type: spring_damper}]\n";

LoadResult load(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return load_scene_text(text, kName, overrides);
}

// Location prefix for a line of the scene.
std::string at(int line) { return at_line(kName, line); }
// Location prefix for a --set override.
std::string at_set(const std::string& override_text) { return at_override(kName, override_text); }

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
  EXPECT_EQ(s.solvers[0].type, "spring_damper");
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
// when the estimate is zero), implicit Euler's is 1/240 s, rounded down to whole steps per frame.
TEST(SceneLoader, AutomaticDtIsBelowTheStableStepAndDividesTheFrame) {
  for (const std::string& integrator : drapelab::integrator_names()) {
    SCOPED_TRACE(integrator);
    const auto result = load(with_line(without_lines(kBase, 34, 34), 33, "    integrator: " + integrator));
    ASSERT_LOADS(result);
    const Scene& s = *result.scene;
    const auto& solver = s.solvers[0];
    const drapelab::ClothModel model = drapelab::build_grid_cloth(s.cloth.grid);
    double bound = drapelab::stable_step_estimate(model, s.cloth.air_damping, s.contact_rates(), solver.integrator);
    double factor = 0.9;
    if (bound == 0.0) {
      bound = drapelab::symplectic_euler_stable_step(model, s.cloth.air_damping, s.contact_rates());
      factor = 0.1;
    }
    if (solver.integrator == drapelab::Integrator::implicit_euler) {
      bound = 1.0 / 240.0;
      factor = 1.0;
    }
    ASSERT_GT(solver.steps_per_frame, 0);
    EXPECT_LE(solver.dt, factor * bound * (1 + 1e-12));
    if (solver.steps_per_frame > 1) {
      EXPECT_GT(solver.dt, factor * bound * (solver.steps_per_frame - 1) / solver.steps_per_frame * (1 - 1e-12))
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

TEST(SceneLoader, EmptyCollidersListIsAccepted) {
  EXPECT_LOADS(load(kBase + "colliders: []\n"));
}

// ---------------------------------------------------------------------------------------------
// Required keys

TEST(SceneLoader, MissingNameIsReportedAtTheTopMap) {
  const auto result = load(without_lines(kBase, 2, 2));
  EXPECT_TRUE(HasError(result, at(2), {"name is required", "[a-z0-9_-]+"}));
}

TEST(SceneLoader, MissingDuration) {
  const auto result = load(without_lines(kBase, 3, 3));
  EXPECT_TRUE(HasError(result, at(2), {"duration is required", "> 0"}));
}

TEST(SceneLoader, MissingCloth) {
  const auto result = load(without_lines(kBase, 7, 25));
  EXPECT_TRUE(HasError(result, at(2), {"cloth is required", "map"}));
}

TEST(SceneLoader, MissingResolutionIsReportedAtTheClothMap) {
  const auto result = load(without_lines(kBase, 10, 10));
  EXPECT_TRUE(HasError(result, at(8), {"cloth.resolution is required", "[33, 33]"}));
}

TEST(SceneLoader, MissingMassAndArealDensity) {
  const auto result = load(without_lines(kBase, 13, 13));
  EXPECT_TRUE(HasError(result, at(8), {"cloth.mass is required", "areal_density"}));
}

TEST(SceneLoader, MissingSolversGiveTheContractsDefaultPair) {
  const auto result = load(without_lines(kBase, 30, 34));
  ASSERT_LOADS(result);
  ASSERT_EQ(result.scene->solvers.size(), 2u);
  EXPECT_EQ(result.scene->solvers[0].type, "spring_damper");
  EXPECT_EQ(result.scene->solvers[0].name, "spring_damper");
  EXPECT_EQ(result.scene->solvers[1].type, "bullet_softbody");
  EXPECT_EQ(result.scene->solvers[1].name, "bullet_softbody");
}

TEST(SceneLoader, EmptySolversList) {
  const auto result = load(with_line(without_lines(kBase, 31, 34), 30, "solvers: []"));
  EXPECT_TRUE(HasError(result, at(30), {"solvers must be a non-empty list of solvers"}));
}

TEST(SceneLoader, SolverEntryNotAMap) {
  const auto result = load(with_line(without_lines(kBase, 32, 34), 31, "  - spring_damper"));
  EXPECT_TRUE(HasError(result, at(31), {"solvers.0 must be a map of keys", "'spring_damper'"}));
}

// ---------------------------------------------------------------------------------------------
// Names

TEST(SceneLoader, NameMustMatchThePattern) {
  const auto result = load(with_line(kBase, 2, "name: Bad Name"));
  EXPECT_TRUE(HasError(result, at(2), {"name must use only a-z, 0-9, _ and -", "got 'Bad Name'"}));
}

TEST(SceneLoader, NameMustBeText) {
  const auto result = load(with_line(kBase, 2, "name: [a, b]"));
  EXPECT_TRUE(HasError(result, at(2), {"name must be text", "a list"}));
}

TEST(SceneLoader, SolverNameMustMatchThePattern) {
  const auto result = load(with_line(kBase, 31, "  - name: Ours!"));
  EXPECT_TRUE(HasError(result, at(31), {"solvers.0.name must use only a-z, 0-9, _ and -", "'Ours!'"}));
}

// ---------------------------------------------------------------------------------------------
// Numbers: not numbers, not finite, out of range

TEST(SceneLoader, DurationNotANumber) {
  const auto result = load(with_line(kBase, 3, "duration: abc"));
  EXPECT_TRUE(HasError(result, at(3), {"duration must be a number (> 0)", "got 'abc'"}));
}

TEST(SceneLoader, DurationAList) {
  const auto result = load(with_line(kBase, 3, "duration: [1, 2]"));
  EXPECT_TRUE(HasError(result, at(3), {"duration must be a number", "a list"}));
}

TEST(SceneLoader, DurationMustBePositive) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 3, "duration: 0")), at(3), {"duration must be > 0, got 0"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 3, "duration: -1")), at(3), {"duration must be > 0, got -1"}));
}

TEST(SceneLoader, NonFiniteNumbersAreRefused) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 3, "duration: inf")), at(3), {"duration must be finite", "'inf'"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 3, "duration: nan")), at(3), {"duration must be finite", "'nan'"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 18, "    stretch: {ks: inf, kd: 0.1}")), at(18),
                       {"cloth.springs.stretch.ks must be finite"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 5, "gravity: [0, nan, 0]")), at(5), {"gravity.1 must be finite"}));
  // YAML's own spelling of infinity is refused too (as not a plain number).
  EXPECT_FALSE(load(with_line(kBase, 3, "duration: .inf")).ok());
}

TEST(SceneLoader, FrameRateMustBePositive) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 4, "frame_rate: 0")), at(4), {"frame_rate must be > 0, got 0"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 4, "frame_rate: -30")), at(4), {"frame_rate must be > 0, got -30"}));
}

TEST(SceneLoader, SeedMustBeANonNegativeWholeNumber) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 6, "seed: -1")), at(6), {"seed must be >= 0, got -1"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 6, "seed: 1.5")), at(6), {"seed must be a whole number", "'1.5'"}));
}

TEST(SceneLoader, StretchKsMustBePositive) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 18, "    stretch: {ks: -3, kd: 0.1}")), at(18),
                       {"cloth.springs.stretch.ks must be > 0, got -3"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 18, "    stretch: {ks: 0, kd: 0.1}")), at(18),
                       {"cloth.springs.stretch.ks must be > 0, got 0"}));
}

TEST(SceneLoader, ShearAndBendKsMustBeNonNegative) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 19, "    shear: {ks: -1, kd: 0.05}")), at(19),
                       {"cloth.springs.shear.ks must be >= 0, got -1"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 20, "    bend: {ks: -5, kd: 0.01}")), at(20),
                       {"cloth.springs.bend.ks must be >= 0, got -5"}));
}

TEST(SceneLoader, SpringDampingMustBeNonNegative) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 18, "    stretch: {ks: 500, kd: -0.1}")), at(18),
                       {"cloth.springs.stretch.kd must be >= 0, got -0.1"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 19, "    shear: {ks: 50, kd: -1}")), at(19),
                       {"cloth.springs.shear.kd must be >= 0"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 20, "    bend: {ks: 5, kd: -2}")), at(20),
                       {"cloth.springs.bend.kd must be >= 0"}));
}

TEST(SceneLoader, SpringsMustBeMaps) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 18, "    stretch: 500")), at(18),
                       {"cloth.springs.stretch must be a map of keys", "'500'"}));
  EXPECT_TRUE(HasError(load(with_line(without_lines(kBase, 18, 20), 17, "  springs: stiff")), at(17),
                       {"cloth.springs must be a map of keys", "'stiff'"}));
}

TEST(SceneLoader, ThicknessMustBePositive) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 14, "  thickness: 0")), at(14), {"cloth.thickness must be > 0, got 0"}));
}

TEST(SceneLoader, PerturbationMustBeNonNegative) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 15, "  perturbation: -0.001")), at(15),
                       {"cloth.perturbation must be >= 0, got -0.001"}));
}

TEST(SceneLoader, AirDampingMustBeNonNegative) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 16, "  air_damping: -1")), at(16),
                       {"cloth.air_damping must be >= 0, got -1"}));
}

TEST(SceneLoader, MassAndArealDensityMustBePositive) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 13, "  mass: 0")), at(13), {"cloth.mass must be > 0, got 0"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 13, "  mass: heavy")), at(13), {"cloth.mass must be a number", "'heavy'"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 13, "  areal_density: -1")), at(13),
                       {"cloth.areal_density must be > 0, got -1"}));
}

TEST(SceneLoader, ContactValuesAreChecked) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 27, "  stiffness: 0")), at(27), {"contact.stiffness must be > 0, got 0"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 28, "  damping: -4")), at(28), {"contact.damping must be >= 0, got -4"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 29, "  friction: -0.2")), at(29),
                       {"contact.friction must be >= 0, got -0.2"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 29, "  friction: grippy")), at(29),
                       {"contact.friction must be a number", "'grippy'"}));
}

TEST(SceneLoader, SizeValuesMustBePositive) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 9, "  size: [1.0, 0]")), at(9), {"cloth.size.1 must be > 0, got 0"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 9, "  size: [-1, 0.5]")), at(9), {"cloth.size.0 must be > 0, got -1"}));
}

TEST(SceneLoader, SolverNumbersAreChecked) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 34, "    dt: 0")), at(34), {"solvers.0.dt must be > 0, got 0"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 34, "    dt: fast")), at(34), {"solvers.0.dt must be a number", "'fast'"}));
  EXPECT_TRUE(HasError(load(insert_after(kBase, 34, "    max_speed: -1")), at(35),
                       {"solvers.0.max_speed must be > 0, got -1"}));
  EXPECT_TRUE(HasError(load(insert_after(kBase, 34, "    runaway_stretch: 0")), at(35),
                       {"solvers.0.runaway_stretch must be > 0, got 0"}));
  EXPECT_TRUE(HasError(load(insert_after(kBase, 34, "    round_dt: yes please")), at(35),
                       {"solvers.0.round_dt must be true or false"}));
}

// ---------------------------------------------------------------------------------------------
// List shapes

TEST(SceneLoader, GravityMustHaveThreeNumbers) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 5, "gravity: [0, -9.81]")), at(5),
                       {"gravity must be a list of 3 numbers, got a list of 2"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 5, "gravity: [0, -9.81, 0, 1]")), at(5),
                       {"gravity must be a list of 3 numbers, got a list of 4"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 5, "gravity: -9.81")), at(5),
                       {"gravity must be a list of 3 numbers, got '-9.81'"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 5, "gravity: [0, down, 0]")), at(5),
                       {"gravity.1 must be a number", "'down'"}));
}

TEST(SceneLoader, SizeMustHaveTwoNumbers) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 9, "  size: [1.0]")), at(9),
                       {"cloth.size must be a list of 2 numbers, got a list of 1"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 9, "  size: [1, 1, 1]")), at(9),
                       {"cloth.size must be a list of 2 numbers, got a list of 3"}));
}

TEST(SceneLoader, CenterMustHaveThreeNumbers) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 12, "  center: [0, 1]")), at(12),
                       {"cloth.center must be a list of 3 numbers, got a list of 2"}));
}

TEST(SceneLoader, ResolutionMustHaveTwoWholeNumbers) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 10, "  resolution: [5]")), at(10),
                       {"cloth.resolution must be a list of 2 whole numbers, got a list of 1"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 10, "  resolution: [5, 4, 3]")), at(10),
                       {"cloth.resolution must be a list of 2 whole numbers, got a list of 3"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 10, "  resolution: 33")), at(10),
                       {"cloth.resolution must be a list of 2 whole numbers"}));
}

TEST(SceneLoader, ResolutionMustBeWholeNumbers) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 10, "  resolution: [5.5, 4]")), at(10),
                       {"cloth.resolution.0 must be a whole number", "'5.5'"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 10, "  resolution: [5, many]")), at(10),
                       {"cloth.resolution.1 must be a whole number", "'many'"}));
}

TEST(SceneLoader, ResolutionMustBeAtLeastOne) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 10, "  resolution: [0, 4]")), at(10),
                       {"cloth.resolution.0 must be >= 1", "got 0"}));
}

TEST(SceneLoader, ResolutionOneByOneIsNotACloth) {
  // The pins are removed so that only the resolution is wrong.
  const auto result = load(with_line(without_lines(kBase, 21, 25), 10, "  resolution: [1, 1]"));
  EXPECT_TRUE(HasError(result, at(10), {"cloth.resolution must give at least 2 particles", "[1, 1]"}));
}

// ---------------------------------------------------------------------------------------------
// Mass and density

TEST(SceneLoader, MassAndArealDensityTogetherAreRefused) {
  const auto result = load(insert_after(kBase, 13, "  areal_density: 0.3"));
  EXPECT_TRUE(HasError(result, at(14), {"cloth.areal_density cannot be given together with cloth.mass"}));
}

TEST(SceneLoader, ArealDensityOnAChainIsRefused) {
  auto text = with_line(kBase, 10, "  resolution: [1, 4]");
  text = with_line(text, 13, "  areal_density: 0.2");
  const auto result = load(text);
  EXPECT_TRUE(HasError(result, at(13), {"cloth.areal_density needs a two-dimensional cloth", "chain", "cloth.mass"}));
}

// ---------------------------------------------------------------------------------------------
// Unknown and duplicate keys

TEST(SceneLoader, UnknownTopKeySuggestsTheNearest) {
  const auto result = load(with_line(kBase, 3, "durration: 0.5"));
  EXPECT_TRUE(HasError(result, at(3), {"durration is not a known key", "did you mean duration?"}));
  // ...and the real key is then missing, reported too.
  EXPECT_TRUE(HasError(result, at(2), {"duration is required"}));
}

TEST(SceneLoader, UnknownClothKeySuggestsTheNearest) {
  const auto result = load(with_line(kBase, 9, "  sise: [1.0, 0.5]"));
  EXPECT_TRUE(HasError(result, at(9), {"cloth.sise is not a known key", "did you mean cloth.size?"}));
}

TEST(SceneLoader, UnknownSpringKeySuggestsTheNearest) {
  const auto result = load(with_line(kBase, 18, "    strech: {ks: 500, kd: 0.1}"));
  EXPECT_TRUE(HasError(result, at(18), {"cloth.springs.strech is not a known key",
                                        "did you mean cloth.springs.stretch?"}));
}

TEST(SceneLoader, UnknownSpringParameterSuggestsTheNearest) {
  const auto result = load(with_line(kBase, 18, "    stretch: {ks: 500, kdd: 0.1}"));
  EXPECT_TRUE(HasError(result, at(18), {"cloth.springs.stretch.kdd is not a known key",
                                        "did you mean cloth.springs.stretch.kd?"}));
}

TEST(SceneLoader, UnknownSolverKeySuggestsTheNearest) {
  const auto result = load(with_line(kBase, 33, "    integrater: symplectic_euler"));
  EXPECT_TRUE(HasError(result, at(33), {"solvers.0.integrater is not a known key",
                                        "did you mean solvers.0.integrator?"}));
}

TEST(SceneLoader, UnknownKeyFarFromAnyListsTheValidKeys) {
  const auto result = load(insert_after(kBase, 6, "colour: red"));
  EXPECT_TRUE(HasError(result, at(7), {"colour is not a known key", "valid keys here:", "duration", "cloth"}));
}

TEST(SceneLoader, DuplicateKeysAreRefused) {
  const auto result = load(with_line(kBase, 4, "duration: 1.0"));
  EXPECT_TRUE(HasError(result, at(4), {"duration appears twice"}));
}

TEST(SceneLoader, DuplicateNestedKeysAreRefused) {
  const auto result = load(insert_after(kBase, 14, "  thickness: 0.003"));
  EXPECT_TRUE(HasError(result, at(15), {"cloth.thickness appears twice"}));
}

// ---------------------------------------------------------------------------------------------
// Choices

TEST(SceneLoader, UnknownPlaneSuggestsTheNearest) {
  const auto result = load(with_line(kBase, 11, "  plane: yz"));
  EXPECT_TRUE(HasError(result, at(11), {"cloth.plane must be one of xz | xy", "got 'yz'", "did you mean 'xz'?"}));
}

TEST(SceneLoader, UnknownIntegratorSuggestsTheNearest) {
  const auto result = load(with_line(kBase, 33, "    integrator: symplectic_eulr"));
  EXPECT_TRUE(HasError(result, at(33), {"solvers.0.integrator must be one of", "explicit_euler",
                                        "got 'symplectic_eulr'", "did you mean 'symplectic_euler'?"}));
}

TEST(SceneLoader, UnknownShapeSuggestsTheNearest) {
  const auto result = load(with_line(kBase, 8, "  shape: gird"));
  EXPECT_TRUE(HasError(result, at(8), {"cloth.shape must be one of grid | disc | mesh", "got 'gird'",
                                       "did you mean 'grid'?"}));
}

TEST(SceneLoader, UnknownSolverTypeSuggestsTheNearest) {
  const auto result = load(with_line(kBase, 32, "    type: spring-damper"));
  EXPECT_TRUE(HasError(result, at(32), {"solvers.0.type must be one of", "got 'spring-damper'",
                                        "did you mean 'spring_damper'?"}));
}

TEST(SceneLoader, UnknownMeshOutputSuggestsTheNearest) {
  const auto result = load(kBase + "output:\n  meshes: bothh\n");
  EXPECT_TRUE(HasError(result, at(36), {"output.meshes must be one of none | obj | pc2 | both", "got 'bothh'",
                                        "did you mean 'both'?"}));
}

TEST(SceneLoader, PinSetNamesFollowThePlane) {
  // A horizontal (xz) sheet has no y edges...
  const auto result = load(with_line(kBase, 22, "    - edge_min_y"));
  EXPECT_TRUE(HasError(result, at(22), {"cloth.pins.0 must be one of", "edge_min_z", "got 'edge_min_y'",
                                        "did you mean"}));
  // ...a vertical (xy) sheet has y edges and no z edges.
  auto vertical = with_line(kBase, 11, "  plane: xy");
  vertical = without_lines(vertical, 25, 25);  // the ball pin is placed for the horizontal sheet
  EXPECT_LOADS(load(with_line(vertical, 22, "    - edge_min_y")));
  EXPECT_TRUE(HasError(load(with_line(vertical, 22, "    - edge_max_z")), at(22),
                       {"cloth.pins.0 must be one of", "edge_max_y", "got 'edge_max_z'"}));
}

TEST(SceneLoader, EveryNamedPinSetLoads) {
  for (const char* name : {"corners", "top_corners", "edge_min_x", "edge_max_x", "edge_min_z", "edge_max_z", "center"})
    EXPECT_LOADS(load(with_line(kBase, 22, std::string("    - ") + name))) << name;
}

// ---------------------------------------------------------------------------------------------
// Pins

TEST(SceneLoader, GridCoordinatePinOutOfRange) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 23, "    - [5, 0]")), at(23),
                       {"cloth.pins.1 selects no particle", "[5, 0] is outside the 5 x 4 grid"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 23, "    - [0, 4]")), at(23),
                       {"cloth.pins.1 selects no particle", "[0, 4]"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 23, "    - [-1, 0]")), at(23), {"cloth.pins.1.0 must be >= 0"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 23, "    - [1, 2, 3]")), at(23),
                       {"cloth.pins.1 must be a list of 2 whole numbers, got a list of 3"}));
  EXPECT_LOADS(load(with_line(kBase, 23, "    - [4, 3]")));  // the far corner is inside
}

TEST(SceneLoader, IndexPinOutOfRange) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 24, "    - {index: 20}")), at(24),
                       {"cloth.pins.2 selects no particle", "particle index 20 is outside 0..19"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 24, "    - {index: -1}")), at(24),
                       {"cloth.pins.2.index must be >= 0"}));
  EXPECT_LOADS(load(with_line(kBase, 24, "    - {index: 19}")));
}

TEST(SceneLoader, BallPinSelectingNothing) {
  const auto result = load(with_line(kBase, 25, "    - {within: {center: [5, 5, 5], radius: 0.1}}"));
  EXPECT_TRUE(HasError(result, at(25), {"cloth.pins.3 selects no particle", "no particle lies within the ball"}));
}

TEST(SceneLoader, BallPinValuesAreChecked) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 25, "    - {within: {center: [0, 1, 0], radius: 0}}")), at(25),
                       {"cloth.pins.3.within.radius must be > 0, got 0"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 25, "    - {within: {center: [0, 1, 0]}}")), at(25),
                       {"cloth.pins.3.within.radius is required"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 25, "    - {within: {radius: 0.2}}")), at(25),
                       {"cloth.pins.3.within.center is required"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 25, "    - {within: {center: [0, 1], radius: 0.2}}")), at(25),
                       {"cloth.pins.3.within.center must be a list of 3 numbers"}));
}

TEST(SceneLoader, PinMapNeedsExactlyOneOfIndexAndWithin) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 24, "    - {index: 2, within: {center: [0, 1, 0], radius: 0.2}}")),
                       at(24), {"cloth.pins.2 must have exactly one of index or within"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 24, "    - {}")), at(24),
                       {"cloth.pins.2 must have exactly one of index or within"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 24, "    - {indx: 2}")), at(24),
                       {"cloth.pins.2.indx is not a known key", "did you mean cloth.pins.2.index?"}));
}

TEST(SceneLoader, PinsMustBeAList) {
  const auto result = load(with_line(without_lines(kBase, 22, 25), 21, "  pins: corners"));
  EXPECT_TRUE(HasError(result, at(21), {"cloth.pins must be a list of pin selectors"}));
}

TEST(SceneLoader, EmptyPinSelector) {
  const auto result = load(with_line(kBase, 22, "    - ~"));
  EXPECT_TRUE(HasError(result, at(22), {"cloth.pins.0 must be a pin selector", "got nothing"}));
}

// yaml-cpp marks an empty value ("duration:" or a bare "-") at the NEXT token; the error must still
// name the line of the key or item itself (and never a line past the end of the file).
TEST(SceneLoader, EmptyValueIsReportedOnItsOwnLine) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 3, "duration:")), at(3), {"duration must be a number", "got nothing"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 34, "    dt:")), at(34), {"solvers.0.dt must be a number", "got nothing"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 22, "    -")), at(22), {"cloth.pins.0 must be a pin selector"}));
}

// ---------------------------------------------------------------------------------------------
// Features of later versions: refused with "not available yet", never silently ignored

TEST(SceneLoader, CollidersLoadWithTheirDefaults) {
  const auto result =
      load(kBase + "colliders:\n  - {name: ball, type: sphere, center: [0, 0.5, 0], radius: 0.3}\n");
  ASSERT_TRUE(result.ok()) << (result.errors.empty() ? "" : result.errors[0]);
  ASSERT_EQ(result.scene->colliders.size(), 1u);
  EXPECT_EQ(result.scene->colliders[0].name, "ball");
  EXPECT_DOUBLE_EQ(result.scene->colliders[0].radius, 0.3);
  EXPECT_DOUBLE_EQ(result.scene->colliders[0].friction, result.scene->contact.friction);
}

TEST(SceneLoader, BulletDeformableTakesMarginAndVoxelButNoIterations) {
  const auto result = load(with_line(with_line(kBase, 32, "    type: bullet_deformable"), 33, "    margin: 0.006"));
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->solvers[0].type, "bullet_deformable");
  EXPECT_DOUBLE_EQ(result.scene->solvers[0].margin, 0.006);
  EXPECT_TRUE(HasError(load(with_line(with_line(kBase, 32, "    type: bullet_deformable"), 33, "    iterations: 4")),
                       at(33), {"solvers.0.iterations is not a known key"}));
}

TEST(SceneLoader, BulletSoftBodyTakesItsOptionsAndRefusesAnIntegrator) {
  const std::string bullet = with_line(with_line(kBase, 32, "    type: bullet_softbody"), 33,
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
  const auto plain = load(with_line(with_line(kBase, 32, "    type: bullet_softbody"), 33, "    round_dt: false"));
  ASSERT_LOADS(plain);
  EXPECT_DOUBLE_EQ(plain.scene->solvers[0].margin, 0.004);
  EXPECT_TRUE(HasError(load(with_line(kBase, 32, "    type: bullet_softbody")), at(33),
                       {"solvers.0.integrator is not a known key"}));
  EXPECT_TRUE(HasError(load(with_line(with_line(kBase, 32, "    type: bullet_softbody"), 33, "    kLST: {bend: 1.5}")),
                       at(33), {"solvers.0.kLST.bend must be >= 0 and <= 1"}));
}

TEST(SceneLoader, EveryIntegratorLoads) {
  for (const std::string& integrator : drapelab::integrator_names()) {
    const auto result = load(with_line(kBase, 33, "    integrator: " + integrator));
    ASSERT_LOADS(result);
    EXPECT_EQ(drapelab::integrator_name(result.scene->solvers[0].integrator), integrator);
  }
}

TEST(SceneLoader, ImplicitOptionsAreReadAndChecked) {
  const auto base = with_line(kBase, 33, "    integrator: implicit_euler");
  const auto result = load(base + "    implicit: {tolerance: 1e-8, max_iterations: 50}\n");
  ASSERT_LOADS(result);
  EXPECT_DOUBLE_EQ(result.scene->solvers[0].implicit.tolerance, 1e-8);
  EXPECT_EQ(result.scene->solvers[0].implicit.max_iterations, 50);
  const auto defaults = load(base);
  ASSERT_LOADS(defaults);
  EXPECT_DOUBLE_EQ(defaults.scene->solvers[0].implicit.tolerance, drapelab::ImplicitSolveSettings{}.tolerance);

  const int last = static_cast<int>(std::count(base.begin(), base.end(), '\n')) + 1;
  EXPECT_TRUE(HasError(load(base + "    implicit: {tolerance: 0}\n"), at(last), {"solvers.0.implicit.tolerance must be > 0"}));
  EXPECT_TRUE(HasError(load(base + "    implicit: {max_iterations: 0}\n"), at(last),
                       {"solvers.0.implicit.max_iterations must be >= 1"}));
  EXPECT_TRUE(HasError(load(base + "    implicit: {tolerence: 1e-3}\n"), at(last), {"did you mean", "tolerance"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 33, "    integrator: rk4") + "    implicit: {tolerance: 1e-3}\n"),
                       at(last), {"solvers.0.implicit applies only to integrator: implicit_euler", "rk4"}));
}

TEST(SceneLoader, AdaptiveSubstepsAreReadCheckedAndGetAHalfFrameStep) {
  // Without dt, an adaptive solver steps at 1/120 s and splits each step itself.
  const auto base = without_lines(kBase, 34, 34);
  const auto result = load(base + "    adaptive_substeps: true\n");
  ASSERT_LOADS(result);
  EXPECT_TRUE(result.scene->solvers[0].adaptive_substeps);
  EXPECT_EQ(result.scene->solvers[0].steps_per_frame, 2);
  const auto plain = load(base);
  ASSERT_LOADS(plain);
  EXPECT_FALSE(plain.scene->solvers[0].adaptive_substeps);

  const int last = static_cast<int>(std::count(base.begin(), base.end(), '\n')) + 1;
  for (const char* integrator : {"explicit_euler", "midpoint", "rk4", "verlet", "leapfrog", "implicit_euler"})
    EXPECT_TRUE(HasError(load(with_line(base, 33, std::string("    integrator: ") + integrator) +
                              "    adaptive_substeps: true\n"),
                         at(last), {"solvers.0.adaptive_substeps needs integrator symplectic_euler", integrator}));
  EXPECT_TRUE(HasError(load(base + "    adaptive_substeps: 3\n"), at(last), {"solvers.0.adaptive_substeps"}));
}

TEST(SceneLoader, ExplicitEulerIsAvailable) {
  const auto result = load(with_line(kBase, 33, "    integrator: explicit_euler"));
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->solvers[0].integrator, drapelab::Integrator::explicit_euler);
}

TEST(SceneLoader, BulletKeysOnOurSolverAreUnknown) {
  for (const char* key : {"iterations: 4", "margin: 0.01", "voxel_size: 0.1"}) {
    const std::string name = std::string(key).substr(0, std::string(key).find(':'));
    EXPECT_TRUE(HasError(load(insert_after(kBase, 34, std::string("    ") + key)), at(35),
                         {"solvers.0." + name, "is not a known key"}))
        << key;
  }
}

// ---------------------------------------------------------------------------------------------
// Solvers, steps and frames

TEST(SceneLoader, DuplicateSolverNamesAreRefused) {
  const auto result = load(kBase + "  - name: ours\n    dt: 0.001041666666666666667\n");
  EXPECT_TRUE(HasError(result, at(35), {"solvers.1.name", "'ours' is already used", "unique"}));
}

TEST(SceneLoader, DefaultSolverNamesCollideToo) {
  // Two solvers without names are both named after their type.
  const auto result = load(with_line(without_lines(kBase, 31, 34), 30,
                                     "solvers: [{type: spring_damper}, {type: spring_damper}]"));
  EXPECT_TRUE(HasError(result, at(30), {"solvers.1.name", "'spring_damper' is already used"}));
}

TEST(SceneLoader, TwoSolversWithDistinctNamesLoadInOrder) {
  const auto result = load(kBase + "  - name: theirs\n    integrator: explicit_euler\n    dt: 0.0005208333333333333\n");
  ASSERT_LOADS(result);
  ASSERT_EQ(result.scene->solvers.size(), 2u);
  EXPECT_EQ(result.scene->solvers[0].name, "ours");
  EXPECT_EQ(result.scene->solvers[1].name, "theirs");
  EXPECT_EQ(result.scene->solvers[1].steps_per_frame, 32);
}

TEST(SceneLoader, DtThatDoesNotDivideTheFramePeriodIsRefused) {
  const auto result = load(with_line(kBase, 34, "    dt: 0.001"));
  EXPECT_TRUE(HasError(result, at(34), {"solvers.0.dt must divide the frame period", "round_dt", "got 0.001",
                                        "try dt = "}));
}

TEST(SceneLoader, RoundDtRoundsDownToAWholeNumberOfStepsWithANote) {
  const auto result = load(insert_after(with_line(kBase, 34, "    dt: 0.001"), 34, "    round_dt: true"));
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

TEST(SceneLoader, DtLargerThanTheFramePeriodIsRefused) {
  const auto result = load(with_line(kBase, 34, "    dt: 0.05"));
  EXPECT_TRUE(HasError(result, at(34), {"solvers.0.dt must not exceed the frame period", "got 0.05"}));
  // Even with round_dt: a step longer than a frame cannot be rounded down to a whole number per frame.
  EXPECT_FALSE(load(insert_after(with_line(kBase, 34, "    dt: 0.05"), 34, "    round_dt: true")).ok());
}

TEST(SceneLoader, DtEqualToTheFramePeriodIsOneStepPerFrame) {
  const auto result = load(with_line(kBase, 34, "    dt: 0.016666666666666666"));
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->solvers[0].steps_per_frame, 1);
}

TEST(SceneLoader, DurationTimesFrameRateMustBeWhole) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 3, "duration: 0.51")), at(3),
                       {"duration times frame_rate must be a whole number of frames", "30.6"}));
  // The frame rate can make it fractional too; the error sits on duration.
  const auto result = load(with_line(with_line(kBase, 4, "frame_rate: 25"), 34, "    dt: 0.001"));
  EXPECT_TRUE(HasError(result, at(3), {"duration times frame_rate must be a whole number of frames", "12.5"}));
}

// Run-length bounds (run_limits.hpp): at most 10^7 steps per frame and from 1 to 10^7 frames, checked
// before any count is cast to int.
TEST(SceneLoader, StepsPerFrameAboveTenMillionAreRefused) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 34, "    dt: 1e-13")), at(34),
                       {"solvers.0.dt is 1e-13 s", "166666666666.6666", "steps per frame",
                        "at most 10000000 steps per frame"}));
  // Just under the bound still loads, with the exact count.
  const auto result = load(with_line(kBase, 34, "    dt: 3.3333333333333334e-09"));
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->solvers[0].steps_per_frame, 5'000'000);
  EXPECT_FALSE(load(with_line(kBase, 34, "    dt: 8.333333333333334e-10")).ok());  // 2e7 steps
  // round_dt does not rescue it: rounding would overflow the count it rounds to.
  EXPECT_FALSE(load(insert_after(with_line(kBase, 34, "    dt: 1e-13"), 34, "    round_dt: true")).ok());
}

TEST(SceneLoader, AutomaticStepAboveTenMillionPerFrameIsRefusedAtTheSolver) {
  // Springs so stiff that the stable step is about 1e-11 s; no dt: the error sits on the solver entry.
  const auto result = load(with_line(without_lines(kBase, 34, 34), 18, "    stretch: {ks: 1e16, kd: 0}"));
  EXPECT_TRUE(HasError(result, at(31), {"solvers.0.dt", "chosen automatically", "steps per frame",
                                        "softer springs"}));
}

TEST(SceneLoader, FrameCountMustBeFromOneToTenMillion) {
  EXPECT_TRUE(HasError(load(with_line(kBase, 4, "frame_rate: 1e-300")), at(4),
                       {"frame_rate", "at least 1 frame", "0.5 s x 1e-300 /s"}));
  // Without a frame_rate key the error sits on duration.
  EXPECT_TRUE(HasError(load(with_line(kMinimal, 2, "duration: 1e-300")), at_line(kName, 2),
                       {"duration times frame_rate must give from 1 to 10000000 frames", "6e-299"}));
  EXPECT_TRUE(HasError(load(with_line(kBase, 3, "duration: 4e7")), at(3),
                       {"duration times frame_rate must give from 1 to 10000000 frames", "2.4e+09"}));
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
// Whole-file problems

TEST(SceneLoader, YamlSyntaxErrorReportsItsLine) {
  const auto result = load(with_line(kBase, 9, "  size: [1.0, 0.5]]"));
  EXPECT_TRUE(HasError(result, at(9), {"not valid YAML"}));
  const auto indented = load(with_line(kBase, 14, "   thickness: 0.004"));
  EXPECT_TRUE(HasError(indented, at(14), {"not valid YAML"}));
}

TEST(SceneLoader, EmptyFileIsAnError) {
  EXPECT_TRUE(HasError(load(""), kName, {"the scene is empty", "name", "duration", "cloth", "solvers"}));
  EXPECT_TRUE(HasError(load("# only a comment\n"), kName, {"the scene is empty"}));
}

TEST(SceneLoader, TopLevelMustBeAMap) {
  EXPECT_TRUE(HasError(load("just some words\n"), at(1), {"must be a map of keys", "'just some words'"}));
  EXPECT_TRUE(HasError(load("- a\n- b\n"), at(1), {"must be a map of keys", "a list"}));
}

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
  EXPECT_TRUE(HasError(result, at(14), {"cloth.thickness must be > 0"}));
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
// --set overrides

TEST(SceneOverrides, ResolutionOverride) {
  const auto result = load(kBase, {"cloth.resolution=[5,7]"});
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->cloth.grid.nx, 5);
  EXPECT_EQ(result.scene->cloth.grid.ny, 7);
}

TEST(SceneOverrides, ListItemOverrideByIndex) {
  const auto result = load(kBase, {"solvers.0.dt=0.0005208333333333333"});
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->solvers[0].steps_per_frame, 32);
  EXPECT_DOUBLE_EQ(result.scene->solvers[0].dt, 1.0 / 1920.0);
}

TEST(SceneOverrides, GravityListOverride) {
  const auto result = load(kBase, {"gravity=[0,-1.62,0]"});
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->gravity, Eigen::Vector3d(0, -1.62, 0));
}

TEST(SceneOverrides, OverrideCreatesAMissingKey) {
  const auto result = load(without_lines(kBase, 6, 6), {"seed=3"});
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->seed, 3u);
}

TEST(SceneOverrides, OverrideCreatesAMissingMap) {
  const auto result = load(without_lines(kBase, 26, 29), {"contact.stiffness=1234"});
  ASSERT_LOADS(result);
  EXPECT_DOUBLE_EQ(result.scene->contact.stiffness, 1234.0);
  EXPECT_DOUBLE_EQ(result.scene->contact.damping, 5.0);  // the rest of the new map takes its defaults
}

TEST(SceneOverrides, OverrideReplacesAWholeMap) {
  const auto result = load(kBase, {"cloth.springs={stretch: {ks: 100, kd: 0}}"});
  ASSERT_LOADS(result);
  EXPECT_DOUBLE_EQ(result.scene->cloth.grid.stretch.ks, 100.0);
  EXPECT_DOUBLE_EQ(result.scene->cloth.grid.stretch.kd, 0.0);
  EXPECT_DOUBLE_EQ(result.scene->cloth.grid.shear.ks, 200.0);  // no longer in the scene: the default
}

TEST(SceneOverrides, LaterOverridesWin) {
  const auto result = load(kBase, {"seed=3", "seed=4"});
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->seed, 4u);
}

TEST(SceneOverrides, OverrideCanFixAnInvalidFile) {
  const auto result = load(with_line(kBase, 14, "  thickness: 0"), {"cloth.thickness=0.002"});
  ASSERT_LOADS(result);
  EXPECT_DOUBLE_EQ(result.scene->cloth.grid.thickness, 0.002);
}

TEST(SceneOverrides, InvalidOverrideValueNamesTheOverride) {
  const auto result = load(kBase, {"cloth.springs.stretch.ks=-3"});
  EXPECT_TRUE(HasError(result, at_set("cloth.springs.stretch.ks=-3"),
                       {"cloth.springs.stretch.ks must be > 0, got -3"}));
  // Not the file's line of the replaced value.
  for (const auto& error : result.errors) EXPECT_EQ(error.rfind(at(18), 0), std::string::npos) << error;
}

TEST(SceneOverrides, InvalidValueInsideAnOverriddenMapNamesTheOverride) {
  const std::string set = "cloth.springs={stretch: {ks: -1, kd: 0}}";
  EXPECT_TRUE(HasError(load(kBase, {set}), at_set(set), {"cloth.springs.stretch.ks must be > 0, got -1"}));
}

TEST(SceneOverrides, OverrideValueOfTheWrongType) {
  EXPECT_TRUE(HasError(load(kBase, {"duration=abc"}), at_set("duration=abc"), {"duration must be a number", "'abc'"}));
  EXPECT_TRUE(HasError(load(kBase, {"cloth.resolution=[5]"}), at_set("cloth.resolution=[5]"),
                       {"cloth.resolution must be a list of 2 whole numbers, got a list of 1"}));
}

TEST(SceneOverrides, OverriddenDtIsCheckedAgainstTheFramePeriod) {
  EXPECT_TRUE(HasError(load(kBase, {"solvers.0.dt=0.001"}), at_set("solvers.0.dt=0.001"),
                       {"solvers.0.dt must divide the frame period", "round_dt"}));
}

TEST(SceneOverrides, ListIndexOutOfRange) {
  const auto result = load(kBase, {"solvers.3.dt=0.001"});
  EXPECT_TRUE(HasError(result, at_set("solvers.3.dt=0.001"),
                       {"solvers is a list of 1 items", "'3' is not an index in 0..0"}));
}

TEST(SceneOverrides, ListIndexThatIsNotANumber) {
  EXPECT_TRUE(HasError(load(kBase, {"solvers.first.dt=0.001"}), at_set("solvers.first.dt=0.001"),
                       {"solvers is a list", "'first' is not an index"}));
}

TEST(SceneOverrides, MalformedOverrideWithoutEquals) {
  EXPECT_TRUE(HasError(load(kBase, {"cloth.mass"}), at_set("cloth.mass"), {"expected key.path=value"}));
  EXPECT_TRUE(HasError(load(kBase, {"=3"}), at_set("=3"), {"expected key.path=value"}));
}

TEST(SceneOverrides, OverrideWithAnEmptyPathPart) {
  EXPECT_TRUE(HasError(load(kBase, {"cloth..mass=1"}), at_set("cloth..mass=1"), {"empty part"}));
}

TEST(SceneOverrides, OverrideValueThatIsNotYaml) {
  EXPECT_TRUE(HasError(load(kBase, {"gravity=[0, 1"}), at_set("gravity=[0, 1"), {"not valid YAML"}));
}

TEST(SceneOverrides, OverrideBelowASingleValue) {
  EXPECT_TRUE(HasError(load(kBase, {"duration.x=1"}), at_set("duration.x=1"),
                       {"duration is a single value", "no key 'x'"}));
}

TEST(SceneOverrides, OverrideCreatingAnUnknownKeySuggestsTheNearest) {
  EXPECT_TRUE(HasError(load(kBase, {"durration=1"}), at_set("durration=1"),
                       {"durration is not a known key", "did you mean duration?"}));
  EXPECT_TRUE(HasError(load(kBase, {"cloth.sise=[1,1]"}), at_set("cloth.sise=[1,1]"),
                       {"cloth.sise is not a known key", "did you mean cloth.size?"}));
}

// An override whose path has a misspelled parent key (--set cloth.springs.strech.ks=1) creates the
// map "strech"; the "not a known key" error on cloth.springs.strech must name the override.
TEST(SceneOverrides, OverrideWithAMisspelledParentKeyNamesTheOverride) {
  const auto result = load(kBase, {"cloth.springs.strech.ks=1"});
  EXPECT_TRUE(HasError(result, kName, {"cloth.springs.strech is not a known key",
                                       "did you mean cloth.springs.stretch?"}));  // holds today
  EXPECT_TRUE(HasError(result, at_set("cloth.springs.strech.ks=1"),
                       {"cloth.springs.strech is not a known key", "did you mean cloth.springs.stretch?"}));
}

TEST(SceneOverrides, FileErrorsKeepTheirLinesBesideOverrideErrors) {
  const auto result = load(with_line(kBase, 14, "  thickness: 0"), {"cloth.mass=-1"});
  EXPECT_TRUE(HasError(result, at(14), {"cloth.thickness must be > 0"}));
  EXPECT_TRUE(HasError(result, at_set("cloth.mass=-1"), {"cloth.mass must be > 0"}));
}

// ---------------------------------------------------------------------------------------------
// resolved.yaml

// load -> write -> load the written text -> write again: the same text, and the same scene.
void ExpectRoundTrip(const std::string& text, const std::vector<std::string>& overrides = {}) {
  const auto first = load(text, overrides);
  ASSERT_LOADS(first);
  const std::string written = resolved_scene_yaml(*first.scene);
  const auto second = load(written);
  ASSERT_LOADS(second) << "\nresolved text:\n" << written;
  EXPECT_TRUE(second.notes.empty()) << "a resolved scene needs no rounding";
  EXPECT_EQ(resolved_scene_yaml(*second.scene), written);
  const Scene& a = *first.scene;
  const Scene& b = *second.scene;
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.description, b.description);
  EXPECT_EQ(a.duration, b.duration);
  EXPECT_EQ(a.frame_rate, b.frame_rate);
  EXPECT_EQ(a.gravity, b.gravity);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.cloth.grid.nx, b.cloth.grid.nx);
  EXPECT_EQ(a.cloth.grid.ny, b.cloth.grid.ny);
  EXPECT_EQ(a.cloth.grid.plane, b.cloth.grid.plane);
  EXPECT_EQ(a.cloth.grid.size, b.cloth.grid.size);
  EXPECT_EQ(a.cloth.grid.center, b.cloth.grid.center);
  EXPECT_EQ(a.cloth.grid.mass, b.cloth.grid.mass);
  EXPECT_EQ(a.cloth.grid.areal_density, b.cloth.grid.areal_density);
  EXPECT_EQ(a.cloth.grid.thickness, b.cloth.grid.thickness);
  EXPECT_EQ(a.cloth.grid.stretch.ks, b.cloth.grid.stretch.ks);
  EXPECT_EQ(a.cloth.grid.bend.kd, b.cloth.grid.bend.kd);
  EXPECT_EQ(a.cloth.grid.pins.size(), b.cloth.grid.pins.size());
  EXPECT_EQ(a.cloth.perturbation, b.cloth.perturbation);
  EXPECT_EQ(a.cloth.air_damping, b.cloth.air_damping);
  EXPECT_EQ(a.contact.stiffness, b.contact.stiffness);
  EXPECT_EQ(a.output.meshes, b.output.meshes);
  ASSERT_EQ(a.solvers.size(), b.solvers.size());
  for (std::size_t k = 0; k < a.solvers.size(); ++k) {
    EXPECT_EQ(a.solvers[k].name, b.solvers[k].name);
    EXPECT_EQ(a.solvers[k].integrator, b.solvers[k].integrator);
    EXPECT_EQ(a.solvers[k].dt, b.solvers[k].dt);  // exactly: numbers are written in round-trip form
    EXPECT_EQ(a.solvers[k].steps_per_frame, b.solvers[k].steps_per_frame);
    EXPECT_EQ(a.solvers[k].max_speed, b.solvers[k].max_speed);
    EXPECT_EQ(a.solvers[k].runaway_stretch, b.solvers[k].runaway_stretch);
  }
}

TEST(ResolvedScene, BaseSceneRoundTrips) { ExpectRoundTrip(kBase); }

TEST(ResolvedScene, MinimalSceneRoundTrips) { ExpectRoundTrip(kMinimal); }

TEST(ResolvedScene, ChainWithArealDensityAndOverridesRoundTrips) {
  ExpectRoundTrip(with_line(kBase, 13, "  areal_density: 0.3"),
                  {"gravity=[0,-1.62,0]", "cloth.plane=xy", "cloth.pins=[top_corners, {index: 1}]",
                   "output.meshes=both"});
  ExpectRoundTrip(with_line(kBase, 10, "  resolution: [1, 4]"));
}

TEST(ResolvedScene, RoundedDtRoundTrips) {
  ExpectRoundTrip(insert_after(with_line(kBase, 34, "    dt: 0.001"), 34, "    round_dt: true"));
}

TEST(ResolvedScene, AwkwardDescriptionRoundTrips) {
  const auto text = insert_after(kBase, 2, R"(description: "a \"quoted\" text: with # and \\ and 'single'")");
  const auto result = load(text);
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->description, R"(a "quoted" text: with # and \ and 'single')");
  ExpectRoundTrip(text);
}

TEST(ResolvedScene, DefaultsAreFilledIn) {
  const auto result = load(kMinimal);
  ASSERT_LOADS(result);
  const std::string text = resolved_scene_yaml(*result.scene);
  const std::vector<std::string> expectations = {"name: minimal", "duration: 1", "frame_rate: 60", "gravity: [0, -9.81, 0]", "seed: 0", "shape: grid",
        "size: [1, 1]", "resolution: [3, 3]", "plane: xz", "center: [0, 1, 0]", "mass: 0.1",
        "thickness: 0.005", "perturbation: 0", "air_damping: 0", "stretch: {ks: 2000, kd: 1}",
        "shear: {ks: 200, kd: 0.5}", "bend: {ks: 20, kd: 0.1}", "pins: []", "colliders: []",
        "stiffness: 5000", "damping: 5", "friction: 0.3", "name: spring_damper", "type: spring_damper",
        "integrator: symplectic_euler", "dt: " + drapelab::format_number(result.scene->solvers[0].dt),
        "round_dt: false",
        "runaway_stretch: 10", "meshes: none"};
  for (const auto& expected : expectations)
    EXPECT_NE(text.find(expected), std::string::npos) << "missing [" << expected << "] in:\n" << text;
  EXPECT_EQ(text.find("areal_density"), std::string::npos);  // only the one given
}

TEST(ResolvedScene, OverridesAppearInTheResolvedScene) {
  const auto result = load(kBase, {"gravity=[0,-1.62,0]", "cloth.resolution=[5,7]"});
  ASSERT_LOADS(result);
  const std::string text = resolved_scene_yaml(*result.scene);
  EXPECT_NE(text.find("gravity: [0, -1.62, 0]"), std::string::npos) << text;
  EXPECT_NE(text.find("resolution: [5, 7]"), std::string::npos) << text;
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
