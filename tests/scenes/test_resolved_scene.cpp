// The resolved.yaml round trip: load -> write -> load the written text -> write again gives the
// same text and the same scene, with every default filled in and every override applied.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "base_scene.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "fixtures/scene_text.hpp"

namespace {

using namespace drapelab::fixtures;      // fixtures/scene_text.hpp
using namespace drapelab::loader_tests;  // base_scene.hpp

using drapelab::GridClothSpec;
using drapelab::scene::resolved_scene_yaml;
using drapelab::scene::Scene;

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
  EXPECT_EQ(a.cloth.grid.stretch.kd, b.cloth.grid.stretch.kd);
  EXPECT_EQ(a.cloth.grid.shear.ks, b.cloth.grid.shear.ks);
  EXPECT_EQ(a.cloth.grid.shear.kd, b.cloth.grid.shear.kd);
  EXPECT_EQ(a.cloth.grid.bend.ks, b.cloth.grid.bend.ks);
  EXPECT_EQ(a.cloth.grid.bend.kd, b.cloth.grid.bend.kd);
  ASSERT_EQ(a.cloth.grid.continuum.has_value(), b.cloth.grid.continuum.has_value());
  if (a.cloth.grid.continuum) {
    EXPECT_EQ(a.cloth.grid.continuum->stretch_modulus, b.cloth.grid.continuum->stretch_modulus);
    EXPECT_EQ(a.cloth.grid.continuum->poisson, b.cloth.grid.continuum->poisson);
    EXPECT_EQ(a.cloth.grid.continuum->bending_rigidity, b.cloth.grid.continuum->bending_rigidity);
    EXPECT_EQ(a.cloth.grid.continuum->damping, b.cloth.grid.continuum->damping);
  }
  EXPECT_EQ(a.cloth.material, b.cloth.material);
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

// The base scene's springs (lines 17 to 20) replaced by the continuum model.
std::string continuum_base(const std::string& continuum_lines) {
  return with_line(without_lines(kBase, 18, 20), 17, "  model: continuum" + continuum_lines);
}

TEST(ResolvedScene, ContinuumRoundTrips) {
  ExpectRoundTrip(continuum_base(""));
  ExpectRoundTrip(continuum_base(
      "\n  continuum: {stretch_modulus: 750, poisson: 0.15, bending_rigidity: 3.3e-6, damping: "
      "0.001}"));
  // A preset's values with an explicit key, and overrides.
  ExpectRoundTrip(
      with_line(continuum_base("\n  continuum: {poisson: 0.45}"), 13, "  material: silk"),
      {"cloth.resolution=[7,5]", "cloth.continuum.damping=0.003"});
  // A disc, whose springs are derived at its ring spacing.
  ExpectRoundTrip(
      "name: disc\nduration: 0.1\ncloth:\n  shape: disc\n  radius: 0.2\n  rings: 6\n"
      "  material: denim\n  model: continuum\n  pins: [center]\n"
      "solvers: [{type: spring_damper}, {type: bullet_softbody}]\n");
}

TEST(ResolvedScene, ContinuumIsWrittenWithItsDerivedSpringsAsAComment) {
  const auto result = load(continuum_base(""));
  ASSERT_LOADS(result);
  const std::string text = resolved_scene_yaml(*result.scene);
  const GridClothSpec& g = result.scene->cloth.grid;
  const std::vector<std::string> expectations = {
      "  model: continuum",
      "  continuum:\n    stretch_modulus: 300",
      "    poisson: 0.3",
      "    bending_rigidity: 1e-05",
      "    damping: 0.01",
      "  #   stretch: {ks: 300, kd: " + drapelab::format_number(g.stretch.kd) + "}",
      "  #   shear: {ks: " + drapelab::format_number(g.shear.ks),
      "  #   bend: {ks: " + drapelab::format_number(g.bend.ks)};
  for (const auto& expected : expectations)
    EXPECT_NE(text.find(expected), std::string::npos) << "missing [" << expected << "] in:\n"
                                                      << text;
  EXPECT_EQ(text.find("\n  springs:"), std::string::npos) << "the springs are derived:\n" << text;
}

TEST(ResolvedScene, RoundedDtRoundTrips) {
  ExpectRoundTrip(insert_after(with_line(kBase, 34, "    dt: 0.001"), 34, "    round_dt: true"));
}

TEST(ResolvedScene, AwkwardDescriptionRoundTrips) {
  const auto text =
      insert_after(kBase, 2, R"(description: "a \"quoted\" text: with # and \\ and 'single'")");
  const auto result = load(text);
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->description, R"(a "quoted" text: with # and \ and 'single')");
  ExpectRoundTrip(text);
}

TEST(ResolvedScene, DefaultsAreFilledIn) {
  const auto result = load(kMinimal);
  ASSERT_LOADS(result);
  const std::string text = resolved_scene_yaml(*result.scene);
  const std::vector<std::string> expectations = {
      "name: minimal",
      "duration: 1",
      "frame_rate: 60",
      "gravity: [0, -9.81, 0]",
      "seed: 0",
      "shape: grid",
      "size: [1, 1]",
      "resolution: [3, 3]",
      "plane: xz",
      "center: [0, 1, 0]",
      "mass: 0.1",
      "thickness: 0.005",
      "perturbation: 0",
      "air_damping: 0",
      "model: springs",
      "stretch: {ks: 2000, kd: 1}",
      "shear: {ks: 200, kd: 0.5}",
      "bend: {ks: 20, kd: 0.1}",
      "pins: []",
      "colliders: []",
      "stiffness: 5000",
      "damping: 5",
      "friction: 0.3",
      "name: spring_damper",
      "type: spring_damper",
      "integrator: symplectic_euler",
      "dt: " + drapelab::format_number(result.scene->solvers[0].dt),
      "round_dt: false",
      "runaway_stretch: 10",
      "meshes: none"};
  for (const auto& expected : expectations)
    EXPECT_NE(text.find(expected), std::string::npos) << "missing [" << expected << "] in:\n"
                                                      << text;
  EXPECT_EQ(text.find("areal_density"), std::string::npos);  // only the one given
  EXPECT_EQ(text.find("continuum"), std::string::npos);      // only with model: continuum
}

TEST(ResolvedScene, OverridesAppearInTheResolvedScene) {
  const auto result = load(kBase, {"gravity=[0,-1.62,0]", "cloth.resolution=[5,7]"});
  ASSERT_LOADS(result);
  const std::string text = resolved_scene_yaml(*result.scene);
  EXPECT_NE(text.find("gravity: [0, -1.62, 0]"), std::string::npos) << text;
  EXPECT_NE(text.find("resolution: [5, 7]"), std::string::npos) << text;
}

}  // namespace
