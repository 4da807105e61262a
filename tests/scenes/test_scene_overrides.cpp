// --set overrides of the scene loader: what they change and create, and the errors of bad ones,
// each located at its override (one table row per case).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "base_scene.hpp"
#include "fixtures/scene_cases.hpp"
#include "fixtures/scene_text.hpp"

namespace {

using namespace drapelab::fixtures;      // fixtures/scene_text.hpp, fixtures/scene_cases.hpp
using namespace drapelab::loader_tests;  // base_scene.hpp

// ---------------------------------------------------------------------------------------------
// Overrides that load

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
  EXPECT_DOUBLE_EQ(result.scene->contact.damping,
                   5.0);  // the rest of the new map takes its defaults
}

TEST(SceneOverrides, OverrideReplacesAWholeMap) {
  const auto result = load(kBase, {"cloth.springs={stretch: {ks: 100, kd: 0}}"});
  ASSERT_LOADS(result);
  EXPECT_DOUBLE_EQ(result.scene->cloth.grid.stretch.ks, 100.0);
  EXPECT_DOUBLE_EQ(result.scene->cloth.grid.stretch.kd, 0.0);
  EXPECT_DOUBLE_EQ(result.scene->cloth.grid.shear.ks, 200.0);  // replaced with the map: the default
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

// ---------------------------------------------------------------------------------------------
// Bad overrides, one row per case

std::vector<BadOverride> bad_overrides() {
  return {
      {"InvalidOverrideValueNamesTheOverride",
       {},
       "cloth.springs.stretch.ks=-3",
       "cloth.springs.stretch.ks",
       {"must be > 0, got -3"}},
      {"InvalidValueInsideAnOverriddenMapNamesTheOverride",
       {},
       "cloth.springs={stretch: {ks: -1, kd: 0}}",
       "cloth.springs.stretch.ks",
       {"must be > 0, got -1"}},
      {"OverrideValueOfTheWrongType_Number",
       {},
       "duration=abc",
       "duration",
       {"must be a number", "'abc'"}},
      {"OverrideValueOfTheWrongType_List",
       {},
       "cloth.resolution=[5]",
       "cloth.resolution",
       {"must be a list of 2 whole numbers, got a list of 1"}},
      {"OverriddenDtIsCheckedAgainstTheFramePeriod",
       {},
       "solvers.0.dt=0.001",
       "solvers.0.dt",
       {"must divide the frame period", "round_dt"}},
      {"ListIndexOutOfRange",
       {},
       "solvers.3.dt=0.001",
       "solvers",
       {"is a list of 1 items", "'3' is not an index in 0..0"}},
      {"ListIndexThatIsNotANumber",
       {},
       "solvers.first.dt=0.001",
       "solvers",
       {"is a list", "'first' is not an index"}},
      {"MalformedOverrideWithoutEquals", {}, "cloth.mass", "", {"expected key.path=value"}},
      {"MalformedOverrideWithoutAPath", {}, "=3", "", {"expected key.path=value"}},
      {"OverrideWithAnEmptyPathPart", {}, "cloth..mass=1", "", {"empty part"}},
      {"OverrideValueThatIsNotYaml", {}, "gravity=[0, 1", "", {"not valid YAML"}},
      {"OverrideBelowASingleValue",
       {},
       "duration.x=1",
       "duration",
       {"is a single value", "no key 'x'"}},
      {"OverrideCreatingAnUnknownKeySuggestsTheNearest",
       {},
       "durration=1",
       "durration",
       {"is not a known key", "did you mean duration?"}},
      {"OverrideCreatingAnUnknownClothKeySuggestsTheNearest",
       {},
       "cloth.sise=[1,1]",
       "cloth.sise",
       {"is not a known key", "did you mean cloth.size?"}},
      // A misspelled parent key (--set cloth.springs.strech.ks=1) creates the map "strech"; the
      // "not a known key" error on cloth.springs.strech names the override.
      {"OverrideWithAMisspelledParentKeyNamesTheOverride",
       {},
       "cloth.springs.strech.ks=1",
       "cloth.springs.strech",
       {"is not a known key", "did you mean cloth.springs.stretch?"}},
  };
}

class SceneOverrideErrors : public ::testing::TestWithParam<BadOverride> {};

TEST_P(SceneOverrideErrors, NameTheOverrideTheKeyAndTheExpectedValue) {
  const BadOverride& row = GetParam();
  EXPECT_TRUE(
      HasKeyedError(load(row.edit.apply(kBase), {row.set}), at_set(row.set), row.key, row.wording));
}

INSTANTIATE_TEST_SUITE_P(SceneOverrides, SceneOverrideErrors, ::testing::ValuesIn(bad_overrides()),
                         RowName());

// An invalid override is reported at the override, not at the file's line of the value it replaces.
TEST(SceneOverrides, InvalidOverrideValueIsNotReportedAtTheReplacedLine) {
  const auto result = load(kBase, {"cloth.springs.stretch.ks=-3"});
  ASSERT_FALSE(result.ok());
  for (const auto& error : result.errors)
    EXPECT_EQ(error.rfind(at(18), 0), std::string::npos) << error;
}

TEST(SceneOverrides, FileErrorsKeepTheirLinesBesideOverrideErrors) {
  const auto result = load(with_line(kBase, 14, "  thickness: 0"), {"cloth.mass=-1"});
  EXPECT_TRUE(HasError(result, at(14), {"cloth.thickness must be >= 1e-06"}));
  EXPECT_TRUE(HasError(result, at_set("cloth.mass=-1"), {"cloth.mass must be >= 1e-09"}));
}

}  // namespace
