// The scene's `air:` map: every rule a bad scene breaks names the file, the line, the key and what
// was expected, and a full air block survives resolved.yaml unchanged.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "collider_scene.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "fixtures/scene_cases.hpp"

namespace {

using namespace drapelab;
using namespace drapelab::collider_tests;  // collider_scene.hpp: the base scene, lines 1 to 37
using namespace drapelab::fixtures;        // fixtures/scene_cases.hpp

// An air block whose first key is line 39.
TextEdit air(const std::string& keys) { return append_text("air:\n" + keys); }

std::vector<BadScene> bad_air() {
  return {
      {"DensityMustNotBeNegative",
       air("  density: -1\n"),
       39,
       "air.density",
       {"must be >= 0, got -1"}},
      {"DragMustNotBeNegative", air("  drag: -0.5\n"), 39, "air.drag", {"must be >= 0, got -0.5"}},
      {"WindHasThreeComponents",
       air("  wind: [1, 2]\n"),
       39,
       "air.wind",
       {"must be a list of 3 numbers, got a list of 2"}},
      {"UnknownKeysAreRefused",
       air("  wnd: [1, 0, 0]\n"),
       39,
       "air.wnd",
       {"is not a known key", "did you mean air.wind?"}},
      {"GustsNeedAPeriod",
       air("  wind: [3, 0, 0]\n  gusts: {amplitude: 1}\n"),
       40,
       "air.gusts.period",
       {"is required", "s, > 0"}},
      {"GustsNeedAWind",
       air("  gusts: {amplitude: 1, period: 2}\n"),
       39,
       "air.gusts",
       {"vary the wind's speed along its direction, but air.wind is zero"}},
      {"TurbulenceNeedsALength",
       air("  wind: [3, 0, 0]\n  turbulence: {intensity: 1}\n"),
       40,
       "air.turbulence.length",
       {"is required", "m, > 0"}},
      {"TurbulenceLengthMustBePositive",
       air("  wind: [3, 0, 0]\n  turbulence: {intensity: 1, length: 0}\n"),
       40,
       "air.turbulence.length",
       {"must be >= 0.001, got 0"}},
      {"AirMustBeAMap", append_text("air: 3\n"), 38, "air", {"must be a map of keys, got '3'"}},
  };
}

class AirErrors : public ::testing::TestWithParam<BadScene> {};

TEST_P(AirErrors, NameTheLineTheKeyAndTheExpectedValue) {
  const BadScene& row = GetParam();
  EXPECT_TRUE(HasKeyedError(load(row.edit.apply(kScene)), at(row.line), row.key, row.wording));
}

INSTANTIATE_TEST_SUITE_P(AirLoader, AirErrors, ::testing::ValuesIn(bad_air()), RowName());

TEST(AirLoader, AirRoundTripsThroughResolvedYaml) {
  const auto loaded =
      load(kScene +
           "seed: 9\n"
           "air: {density: 1.1, drag: 1.3, lift: 0.25, wind: [4, 0.5, -1],"
           " gusts: {amplitude: 1.5, period: 2}, turbulence: {intensity: 0.7, length: 0.4}}\n");
  ASSERT_TRUE(loaded.ok()) << (loaded.errors.empty() ? "" : loaded.errors.front());
  const AirSettings& a = loaded.scene->air;
  EXPECT_TRUE(a.enabled);
  EXPECT_EQ(a.density, 1.1);
  EXPECT_EQ(a.drag, 1.3);
  EXPECT_EQ(a.lift, 0.25);
  EXPECT_EQ(a.wind, Eigen::Vector3d(4, 0.5, -1));
  EXPECT_EQ(a.gust_amplitude, 1.5);
  EXPECT_EQ(a.gust_period, 2.0);
  EXPECT_EQ(a.turbulence_intensity, 0.7);
  EXPECT_EQ(a.turbulence_length, 0.4);
  EXPECT_EQ(a.seed, 9u);  // the gusts and eddies take the scene's seed
  const std::string written = scene::resolved_scene_yaml(*loaded.scene);
  const auto again = load(written);
  ASSERT_TRUE(again.ok()) << (again.errors.empty() ? "" : again.errors.front()) << written;
  EXPECT_EQ(again.scene->air.wind, a.wind);
  EXPECT_EQ(again.scene->air.gust_period, a.gust_period);
  EXPECT_EQ(again.scene->air.turbulence_length, a.turbulence_length);
  EXPECT_EQ(scene::resolved_scene_yaml(*again.scene), written);
  // Without the key there is no air at all.
  EXPECT_FALSE(load(kScene).scene->air.enabled);
}

}  // namespace
