// The scene key of scripted drags (interactions:): every rule a bad scene breaks names the file,
// the line, the key and what was expected, and the drags survive resolved.yaml unchanged.
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

// An interactions list whose one item is line 39.
TextEdit one_drag(const std::string& item) {
  return append_text("interactions:\n  - " + item + "\n");
}

const char* const kKeys = "keyframes: [{t: 0.1, target: [0, 1, 0]}, {t: 0.3, target: [0, 1.2, 0]}]";

std::vector<BadScene> bad_drags() {
  return {
      {"TypeMustBeDrag",
       one_drag(std::string("{type: poke, particle: [1, 2], stiffness: 50, ") + kKeys + "}"),
       39,
       "interactions.0.type",
       {"must be one of", "got 'poke'"}},
      {"ParticleIsRequired",
       one_drag(std::string("{type: drag, stiffness: 50, ") + kKeys + "}"),
       39,
       "interactions.0.particle",
       {"is required: the particle pulled"}},
      {"ParticleMustBeOnTheCloth",
       one_drag(std::string("{type: drag, particle: {index: 99}, stiffness: 50, ") + kKeys + "}"),
       39,
       "interactions.0.particle",
       {"selects no particle of the cloth"}},
      {"StiffnessIsRequired",
       one_drag(std::string("{type: drag, particle: [1, 2], ") + kKeys + "}"),
       39,
       "interactions.0.stiffness",
       {"is required: the spring's stiffness in N/m"}},
      {"StiffnessMustBePositive",
       one_drag(std::string("{type: drag, particle: [1, 2], stiffness: 0, ") + kKeys + "}"),
       39,
       "interactions.0.stiffness",
       {"must be > 0, got 0"}},
      {"KeyframesMustBeAList",
       one_drag("{type: drag, particle: [1, 2], stiffness: 50, keyframes: 3}"),
       39,
       "interactions.0.keyframes",
       {"must be a non-empty list of {t, target}", "got '3'"}},
      {"KeyframesMustGoForwardInTime",
       one_drag("{type: drag, particle: [1, 2], stiffness: 50, keyframes: [{t: 0.3, target: [0, "
                "1, 0]}, {t: 0.2, target: [0, 1, 0]}]}"),
       39,
       "interactions.0.keyframes.1.t",
       {"must be later than the previous keyframe's t = 0.3, got 0.2"}},
      {"AKeyframeNeedsATarget",
       one_drag("{type: drag, particle: [1, 2], stiffness: 50, keyframes: [{t: 0.3}]}"),
       39,
       "interactions.0.keyframes.0.target",
       {"is required: the point [x, y, z] in m"}},
      {"APinnedParticleCannotBeDragged",
       {insert_lines(5, "  pins: [corners]"),
        one_drag(std::string("{type: drag, particle: [0, 0], stiffness: 50, ") + kKeys + "}")},
       40,
       "interactions.0.particle",
       {"selects particle 0, which is pinned"}},
      {"InteractionsMustBeAList",
       append_text("interactions: {type: drag}\n"),
       38,
       "interactions",
       {"must be a list of drags"}},
  };
}

class InteractionErrors : public ::testing::TestWithParam<BadScene> {};

TEST_P(InteractionErrors, NameTheLineTheKeyAndTheExpectedValue) {
  const BadScene& row = GetParam();
  EXPECT_TRUE(HasKeyedError(load(row.edit.apply(kScene)), at(row.line), row.key, row.wording));
}

INSTANTIATE_TEST_SUITE_P(InteractionLoader, InteractionErrors, ::testing::ValuesIn(bad_drags()),
                         RowName());

// Two drags, loaded, written to resolved.yaml and loaded again: the same particles, springs and
// keyframes, and the written text loads to itself; each becomes a soft constraint of length 0.
TEST(InteractionLoader, DragsRoundTripAndBecomeSoftConstraints) {
  std::string text = kScene;
  text +=
      "interactions:\n"
      "  - {type: drag, particle: [1, 2], stiffness: 50, keyframes: [{t: 0.1, target: [0, 1, 0]},"
      " {t: 0.35, target: [0.2, 1.5, -0.1]}]}\n"
      "  - {type: drag, particle: {index: 7}, stiffness: 20, damping: 0.1, keyframes: [{t: 0.2,"
      " target: [1, 1, 1]}]}\n";
  const auto loaded = load(text);
  ASSERT_TRUE(loaded.ok()) << (loaded.errors.empty() ? "" : loaded.errors.front());
  const scene::Scene& s = *loaded.scene;
  ASSERT_EQ(s.interactions.size(), 2u);
  EXPECT_EQ(s.interactions[0].particle, 2 * 5 + 1);  // [i, j] on a 5-wide grid
  EXPECT_EQ(s.interactions[0].keyframes.size(), 2u);
  EXPECT_EQ(s.interactions[0].keyframes[1].target, Eigen::Vector3d(0.2, 1.5, -0.1));
  EXPECT_EQ(s.interactions[1].damping, 0.1);
  const auto constraints = scene::scene_constraints(s);
  ASSERT_TRUE(constraints);
  ASSERT_EQ(constraints->list.size(), 2u);
  const DistanceConstraint& drag = constraints->list[0];
  EXPECT_EQ(drag.mode, ConstraintMode::soft);
  EXPECT_EQ(drag.length, 0.0);
  EXPECT_EQ(DistanceConstraints::particle_a(drag), 11);
  EXPECT_FALSE(DistanceConstraints::acts(drag, 0.05));  // before its first keyframe
  EXPECT_TRUE(DistanceConstraints::acts(drag, 0.2));
  EXPECT_FALSE(DistanceConstraints::acts(drag, 0.4));  // released after its last
  const auto [target, velocity] = drag.b.drag->target(0.225);
  EXPECT_TRUE(target.isApprox(Eigen::Vector3d(0.1, 1.25, -0.05), 1e-12)) << target.transpose();
  EXPECT_TRUE(velocity.isApprox(Eigen::Vector3d(0.8, 2.0, -0.4), 1e-12)) << velocity.transpose();
  const std::string written = scene::resolved_scene_yaml(s);
  const auto again = load(written);
  ASSERT_TRUE(again.ok()) << (again.errors.empty() ? "" : again.errors.front()) << "\n" << written;
  ASSERT_EQ(again.scene->interactions.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const scene::DragSpec& a = s.interactions[k];
    const scene::DragSpec& b = again.scene->interactions[k];
    EXPECT_EQ(a.particle, b.particle);
    EXPECT_EQ(a.stiffness, b.stiffness);
    EXPECT_EQ(a.damping, b.damping);
    ASSERT_EQ(a.keyframes.size(), b.keyframes.size());
    for (std::size_t f = 0; f < a.keyframes.size(); ++f) {
      EXPECT_EQ(a.keyframes[f].t, b.keyframes[f].t);
      EXPECT_EQ(a.keyframes[f].target, b.keyframes[f].target);
    }
  }
  EXPECT_EQ(scene::resolved_scene_yaml(*again.scene), written);
}

}  // namespace
