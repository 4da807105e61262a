// The scene keys of distance constraints (constraints:) and dynamic colliders
// (colliders[].dynamic): every rule a bad scene breaks names the file, the line, the key and what
// was expected, and both survive resolved.yaml unchanged.
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

// A constraints list whose one item is line 39.
TextEdit one_constraint(const std::string& item) {
  return append_text("constraints:\n  - " + item + "\n");
}

std::vector<BadScene> bad_constraints() {
  return {
      {"TypeMustBeDistance",
       one_constraint("{type: spring, a: {index: 0}, b: {point: [0, 2, 0]}}"),
       39,
       "constraints.0.type",
       {"must be one of", "got 'spring'"}},
      {"TypeIsRequired",
       one_constraint("{a: {index: 0}, b: {point: [0, 2, 0]}}"),
       39,
       "constraints.0.type",
       {"is required", "distance"}},
      {"AMustBeAParticle",
       one_constraint("{type: distance, a: 3, b: {point: [0, 2, 0]}}"),
       39,
       "constraints.0.a",
       {"must be a particle: {index: k} or [i, j]", "got '3'"}},
      {"ParticleMustBeOnTheCloth",
       one_constraint("{type: distance, a: {index: 99}, b: {point: [0, 2, 0]}}"),
       39,
       "constraints.0.a",
       {"selects no particle of the cloth"}},
      {"ColliderMustExist",
       one_constraint("{type: distance, a: [1, 2], b: {collider: nobody, offset: [0, 0, 0]}}"),
       39,
       "constraints.0.b.collider",
       {"must name a collider of the scene", "got 'nobody'"}},
      {"PointAndColliderAreOneEndEach",
       one_constraint("{type: distance, a: [1, 2], b: {point: [0, 1, 0], collider: ball}}"),
       39,
       "constraints.0.b",
       {"must be one end", "not both"}},
      {"StiffnessIsForSoftOnly",
       one_constraint("{type: distance, a: {index: 0}, b: {point: [0, 2, 0]}, stiffness: 10}"),
       39,
       "constraints.0.stiffness",
       {"is for mode: soft only"}},
      {"ToleranceIsForHardAndRopeOnly",
       one_constraint(
           "{type: distance, a: {index: 0}, b: {point: [0, 2, 0]}, mode: soft, stiffness: 10, "
           "tolerance: 1e-3}"),
       39,
       "constraints.0.tolerance",
       {"is for modes hard and rope only"}},
      {"SoftNeedsStiffness",
       one_constraint("{type: distance, a: {index: 0}, b: {point: [0, 2, 0]}, mode: soft}"),
       39,
       "constraints.0.stiffness",
       {"is required", "N/m"}},
      {"ModeMustBeKnown",
       one_constraint("{type: distance, a: {index: 0}, b: {point: [0, 2, 0]}, mode: stiff}"),
       39,
       "constraints.0.mode",
       {"must be one of", "got 'stiff'"}},
      {"LengthMustBePositive",
       one_constraint("{type: distance, a: {index: 0}, b: {point: [0, 2, 0]}, length: -1}"),
       39,
       "constraints.0.length",
       {"must be >= 0.001"}},
      {"AParticleIsNotJoinedToItself",
       one_constraint("{type: distance, a: {index: 3}, b: [3, 0]}"),
       39,
       "constraints.0",
       {"joins particle 3 to itself"}},
      {"OneEndMustMove",
       {insert_lines(5, "  pins: [{index: 0}]"),
        one_constraint("{type: distance, a: {index: 0}, b: {point: [0, 2, 0]}}")},
       40,
       "constraints.0",
       {"has both ends held in place", "unpin one end"}},
      {"ConstraintsMustBeAList",
       append_text("constraints: {type: distance}\n"),
       38,
       "constraints",
       {"must be a list of constraints"}},
      // Dynamic colliders
      {"DynamicNeedsAMass",
       insert_lines(14, "    dynamic: {}"),
       15,
       "colliders.0.dynamic.mass",
       {"is required", "kg"}},
      {"DynamicMassMustBePositive",
       insert_lines(14, "    dynamic: {mass: 0}"),
       15,
       "colliders.0.dynamic.mass",
       {"must be >= 1e-09, got 0"}},
      {"APlaneCannotBeDynamic",
       insert_lines(37, "    dynamic: {mass: 1}"),
       38,
       "colliders.4.dynamic",
       {"a plane cannot be dynamic"}},
      {"ADynamicColliderHasNoMotion",
       insert_lines(14, "    dynamic: {mass: 1}\n    motion: {velocity: [0, 1, 0]}"),
       15,
       "colliders.0.dynamic",
       {"a dynamic collider has no motion key"}},
      {"ADynamicColliderHasNoParent",
       insert_lines(14, "    dynamic: {mass: 1}\n    parent: table"),
       15,
       "colliders.0.dynamic",
       {"a dynamic collider has no parent"}},
      {"ADynamicColliderCarriesNoOthers",
       {insert_lines(25, "    parent: ball"), insert_lines(14, "    dynamic: {mass: 1}")},
       27,
       "colliders.2.parent",
       {"names 'ball', a dynamic collider, which cannot carry others"}},
      {"HardConstraintsDoNotHoldToADynamicCollider",
       {insert_lines(14, "    dynamic: {mass: 1}"),
        one_constraint("{type: distance, a: [1, 2], b: {collider: ball, offset: [0, 0, 0]}}")},
       40,
       "constraints.0.b.collider",
       {"names 'ball', a dynamic collider: a hard constraint holds to kinematic colliders only",
        "give mode: soft"}},
      {"RopesDoNotHoldToADynamicCollider",
       {insert_lines(14, "    dynamic: {mass: 1}"),
        one_constraint(
            "{type: distance, a: [1, 2], b: {collider: ball, offset: [0, 0, 0]}, mode: rope}")},
       40,
       "constraints.0.b.collider",
       {"names 'ball', a dynamic collider: a rope constraint holds to kinematic colliders only"}},
      {"TheClassicClothCannotCarryPinsAttachedToADynamicCollider",
       {replace_line(9, "solvers: [{type: bullet_softbody, dt: 0.001041666666666666667}]"),
        insert_lines(14, "    dynamic: {mass: 1}"),
        insert_lines(5, "  pins: [{index: 0, attach: ball}]")},
       10,
       "solvers.0.type",
       {"is bullet_softbody, which cannot carry pins attached to the dynamic collider 'ball'",
        "use bullet_deformable or spring_damper"}},
      {"ADynamicColliderNeedsOurSolverHosted",
       {replace_line(9,
                     "solvers: [{type: spring_damper, dt: 0.001041666666666666667, host: none}]"),
        insert_lines(14, "    dynamic: {mass: 1}")},
       9,
       "solvers.0.host",
       {"is none, but collider 'ball' is dynamic", "use host: bullet"}},
  };
}

class ConstraintErrors : public ::testing::TestWithParam<BadScene> {};

TEST_P(ConstraintErrors, NameTheLineTheKeyAndTheExpectedValue) {
  const BadScene& row = GetParam();
  EXPECT_TRUE(HasKeyedError(load(row.edit.apply(kScene)), at(row.line), row.key, row.wording));
}

INSTANTIATE_TEST_SUITE_P(ConstraintLoader, ConstraintErrors, ::testing::ValuesIn(bad_constraints()),
                         RowName());

// Every kind of end and mode, loaded, written to resolved.yaml and loaded again: the same
// constraints (ends resolved to particle indices, default lengths filled in) and the same dynamic
// mass, and the written text loads to itself.
TEST(ConstraintLoader, ConstraintsAndDynamicCollidersRoundTrip) {
  std::string text = kScene;
  text.insert(text.find("    radius: 0.3\n") + 16, "    dynamic: {mass: 0.75}\n");
  text +=
      "constraints:\n"
      "  - {type: distance, a: [1, 2], b: {point: [0, 2, 0]}}\n"
      "  - {type: distance, a: {index: 4}, b: [0, 3], mode: rope, length: 0.9, tolerance: 1e-8}\n"
      "  - {type: distance, a: {index: 7}, b: {collider: pill, offset: [0.1, 0, 0]}, mode: soft,"
      " stiffness: 50, damping: 0.2}\n"
      "  - {type: distance, a: {index: 3}, b: {collider: ball, offset: [0, 0.3, 0]}, mode: soft,"
      " stiffness: 80}\n";  // a soft constraint may end on a dynamic collider
  const auto loaded = load(text);
  ASSERT_TRUE(loaded.ok()) << (loaded.errors.empty() ? "" : loaded.errors.front());
  const scene::Scene& s = *loaded.scene;
  ASSERT_EQ(s.constraints.size(), 4u);
  EXPECT_EQ(s.colliders[0].dynamic_mass, 0.75);
  const DistanceConstraint& first = s.constraints[0];
  EXPECT_EQ(first.a, 2 * 5 + 1);  // [i, j] on a 5-wide grid
  EXPECT_EQ(first.mode, ConstraintMode::hard);
  EXPECT_EQ(first.tolerance, 1e-6);
  EXPECT_NEAR(first.length,
              (loaded.model->rest_positions.col(11) - Eigen::Vector3d(0, 2, 0)).norm(),
              1e-15);  // the rest distance
  EXPECT_EQ(s.constraints[1].b.particle, 15);
  EXPECT_EQ(s.constraints[1].length, 0.9);
  EXPECT_EQ(s.constraints[1].tolerance, 1e-8);
  EXPECT_EQ(s.constraints[2].b.kind, ConstraintEnd::Kind::collider_point);
  EXPECT_EQ(s.constraints[2].b.collider, 2);
  EXPECT_EQ(s.constraints[2].stiffness, 50.0);
  EXPECT_EQ(s.constraints[3].b.collider, 0);
  EXPECT_EQ(s.constraints[3].mode, ConstraintMode::soft);
  const std::string written = scene::resolved_scene_yaml(s);
  const auto again = load(written);
  ASSERT_TRUE(again.ok()) << (again.errors.empty() ? "" : again.errors.front()) << "\n" << written;
  ASSERT_EQ(again.scene->constraints.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    const DistanceConstraint& a = s.constraints[k];
    const DistanceConstraint& b = again.scene->constraints[k];
    EXPECT_EQ(a.a, b.a);
    EXPECT_EQ(a.b.kind, b.b.kind);
    EXPECT_EQ(a.b.particle, b.b.particle);
    EXPECT_EQ(a.b.collider, b.b.collider);
    EXPECT_EQ(a.b.point, b.b.point);
    EXPECT_EQ(a.length, b.length);
    EXPECT_EQ(a.mode, b.mode);
    EXPECT_EQ(a.stiffness, b.stiffness);
    EXPECT_EQ(a.damping, b.damping);
    EXPECT_EQ(a.tolerance, b.tolerance);
  }
  EXPECT_EQ(again.scene->colliders[0].dynamic_mass, 0.75);
  EXPECT_NE(written.find("dynamic: {mass: 0.75}"), std::string::npos) << written;
  EXPECT_EQ(scene::resolved_scene_yaml(*again.scene), written);
}

}  // namespace
