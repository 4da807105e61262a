// Unit tests of the scene's `colliders:` list and `contact:` friction (scenes/loader/src/
// collider_reader.cpp, scene_loader.cpp read_contact) on scenes that load: every collider type with
// its fields and defaults, the friction defaults, kinematic motion, --set overrides on collider
// keys, and scenes with several errors at once. Each bad input on its own:
// test_collider_errors.cpp; the resolved.yaml round trip: test_collider_resolved.cpp.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "collider_scene.hpp"
#include "drapelab/collider.hpp"
#include "fixtures/scene_text.hpp"

namespace {

using namespace drapelab::collider_tests;  // collider_scene.hpp
using namespace drapelab::fixtures;        // fixtures/scene_text.hpp

using drapelab::Collider;
using drapelab::ColliderShape;
using Eigen::Vector3d;

// ---------------------------------------------------------------------------------------------
// Every type with its fields

TEST(ColliderLoader, EveryTypeLoadsInOrderWithItsFields) {
  const auto colliders = colliders_of(kScene, 5);
  ASSERT_EQ(colliders.size(), 5u);

  const Collider& ball = colliders[0];
  EXPECT_EQ(ball.name, "ball");
  EXPECT_EQ(ball.shape, ColliderShape::sphere);
  EXPECT_EQ(ball.center, Vector3d(0, 0.5, 0));
  EXPECT_EQ(ball.radius, 0.3);

  const Collider& table = colliders[1];
  EXPECT_EQ(table.name, "table");
  EXPECT_EQ(table.shape, ColliderShape::cylinder);
  EXPECT_EQ(table.center, Vector3d(0, 0.4, 0));
  EXPECT_EQ(table.radius, 0.4);
  EXPECT_EQ(table.height, 0.8);
  EXPECT_EQ(table.axis, Vector3d(0, 0, 1));  // [0, 0, 2] normalised

  const Collider& pill = colliders[2];
  EXPECT_EQ(pill.name, "pill");
  EXPECT_EQ(pill.shape, ColliderShape::capsule);
  EXPECT_EQ(pill.center, Vector3d(1, 0.2, -1));
  EXPECT_EQ(pill.radius, 0.1);
  EXPECT_EQ(pill.height, 0.5);
  EXPECT_EQ(pill.axis, Vector3d::UnitY());  // default

  const Collider& crate = colliders[3];
  EXPECT_EQ(crate.name, "crate");
  EXPECT_EQ(crate.shape, ColliderShape::box);
  EXPECT_EQ(crate.center, Vector3d(1, 0.5, 0));
  EXPECT_EQ(crate.half_extents, Vector3d(0.5, 0.25, 0.125));
  EXPECT_EQ(crate.rotation, Vector3d(0, 30, 0));

  const Collider& floor = colliders[4];
  EXPECT_EQ(floor.name, "floor");
  EXPECT_EQ(floor.shape, ColliderShape::plane);
  EXPECT_EQ(floor.center, Vector3d(0, -0.1, 0));  // point -> center
  ExpectNear(floor.normal, Vector3d(0.6, 0.8, 0));
  EXPECT_NEAR(floor.normal.norm(), 1.0, 1e-15);

  for (const Collider& c : colliders) EXPECT_TRUE(c.motion.is_static()) << c.name;
}

TEST(ColliderLoader, RotationDefaultsToZero) {
  const auto colliders = colliders_of(kScene, 5);
  ASSERT_EQ(colliders.size(), 5u);
  for (std::size_t k : {0u, 1u, 2u, 4u})
    EXPECT_EQ(colliders[k].rotation, Vector3d::Zero()) << colliders[k].name;
}

TEST(ColliderLoader, RotationIsReadForEveryType) {
  const auto colliders = colliders_of(
      with_colliders(
          "  - {name: a, type: sphere, center: [0, 0, 0], radius: 1, rotation: [10, -20, 370]}\n"
          "  - {name: b, type: plane, rotation: [0, 0, 45]}\n"),
      2);
  ASSERT_EQ(colliders.size(), 2u);
  EXPECT_EQ(colliders[0].rotation, Vector3d(10, -20, 370));
  EXPECT_EQ(colliders[1].rotation, Vector3d(0, 0, 45));
}

TEST(ColliderLoader, AxisIsNormalised) {
  const auto colliders =
      colliders_of(with_colliders("  - {name: a, type: cylinder, center: [0, 0, 0], radius: 1, "
                                  "height: 2, axis: [3, 0, -4]}\n"
                                  "  - {name: b, type: capsule, center: [0, 0, 0], radius: 1, "
                                  "height: 2, axis: [0, -0.5, 0]}\n"),
                   2);
  ASSERT_EQ(colliders.size(), 2u);
  ExpectNear(colliders[0].axis, Vector3d(0.6, 0, -0.8));
  EXPECT_EQ(colliders[1].axis, Vector3d(0, -1, 0));
}

TEST(ColliderLoader, CylinderAxisDefaultsToY) {
  const auto colliders = colliders_of(
      with_colliders("  - {name: a, type: cylinder, center: [0, 0, 0], radius: 1, height: 2}\n"),
      1);
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].axis, Vector3d(0, 1, 0));
}

TEST(ColliderLoader, PlaneDefaultsToNormalYThroughTheGivenPoint) {
  const auto colliders =
      colliders_of(with_colliders("  - {name: ground, type: plane, point: [1, 2, 3]}\n"), 1);
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].shape, ColliderShape::plane);
  EXPECT_EQ(colliders[0].center, Vector3d(1, 2, 3));
  EXPECT_EQ(colliders[0].normal, Vector3d(0, 1, 0));
}

TEST(ColliderLoader, DownwardPlaneNormalIsKept) {
  const auto colliders = colliders_of(
      with_colliders("  - {name: ceiling, type: plane, point: [0, 3, 0], normal: [0, -7, 0]}\n"),
      1);
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].normal, Vector3d(0, -1, 0));
}

TEST(ColliderLoader, FlowAndBlockStylesGiveTheSameCollider) {
  const auto block = colliders_of(
      with_colliders(
          "  - name: t\n    type: cylinder\n    center: [1, 2, 3]\n    radius: 0.5\n    height: 2\n"
          "    axis: [1, 0, 0]\n    rotation: [0, 0, 90]\n    friction: 0.5\n"),
      1);
  const auto flow = colliders_of(with_colliders("  - {name: t, type: cylinder, center: [1, 2, 3], "
                                                "radius: 0.5, height: 2, axis: [1, 0, 0], "
                                                "rotation: [0, 0, 90], friction: 0.5}\n"),
                                 1);
  ASSERT_EQ(block.size(), 1u);
  ASSERT_EQ(flow.size(), 1u);
  ExpectSameCollider(block[0], flow[0]);
}

TEST(ColliderLoader, NoCollidersKeyGivesNoColliders) {
  const auto result = load(kHeader);
  ASSERT_LOADS(result);
  EXPECT_TRUE(result.scene->colliders.empty());
}

// ---------------------------------------------------------------------------------------------
// Friction defaults

TEST(ColliderFriction, DefaultsComeFromContact) {
  const auto colliders = colliders_of(kScene, 5);
  ASSERT_EQ(colliders.size(), 5u);
  // ball, table, pill: neither key given -> contact.friction 0.2 and contact.static_friction 0.4
  for (std::size_t k : {0u, 1u, 2u}) {
    EXPECT_EQ(colliders[k].friction, 0.2) << colliders[k].name;
    EXPECT_EQ(colliders[k].static_friction, 0.4) << colliders[k].name;
  }
  // floor: both given
  EXPECT_EQ(colliders[4].friction, 0.1);
  EXPECT_EQ(colliders[4].static_friction, 0.15);
}

TEST(ColliderFriction, OnlyOwnFrictionAlsoSetsStaticFriction) {
  // crate gives friction 0.6 only; its static coefficient is its own friction, not contact's 0.4.
  const auto colliders = colliders_of(kScene, 5);
  ASSERT_EQ(colliders.size(), 5u);
  EXPECT_EQ(colliders[3].friction, 0.6);
  EXPECT_EQ(colliders[3].static_friction, 0.6);
  // Also when the own friction is below contact.static_friction.
  const auto low = colliders_of(with_line(kScene, 31, "    friction: 0.05"), 5);
  ASSERT_EQ(low.size(), 5u);
  EXPECT_EQ(low[3].friction, 0.05);
  EXPECT_EQ(low[3].static_friction, 0.05);
}

TEST(ColliderFriction, OnlyStaticFrictionTakesContactFriction) {
  const auto colliders = colliders_of(
      with_colliders(
          "  - {name: a, type: sphere, center: [0, 0, 0], radius: 1, static_friction: 0.9}\n"),
      1);
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].friction, 0.2);
  EXPECT_EQ(colliders[0].static_friction, 0.9);
}

TEST(ColliderFriction, StaticFrictionEqualToFrictionIsAllowed) {
  const auto colliders =
      colliders_of(with_colliders("  - {name: a, type: sphere, center: [0, 0, 0], radius: 1, "
                                  "friction: 0.7, static_friction: 0.7}\n"),
                   1);
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].friction, 0.7);
  EXPECT_EQ(colliders[0].static_friction, 0.7);
}

TEST(ColliderFriction, ZeroFrictionIsAllowed) {
  const auto colliders = colliders_of(
      with_colliders("  - {name: a, type: plane, friction: 0, static_friction: 0}\n"), 1);
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].friction, 0.0);
  EXPECT_EQ(colliders[0].static_friction, 0.0);
}

TEST(ColliderFriction, ContactStaticFrictionDefaultsToContactFriction) {
  const auto result = load(without_lines(kScene, 8, 8));  // contact: {friction: 0.2}
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->contact.friction, 0.2);
  EXPECT_EQ(result.scene->contact.static_friction, 0.2);
  ASSERT_EQ(result.scene->colliders.size(), 5u);
  EXPECT_EQ(result.scene->colliders[0].friction, 0.2);
  EXPECT_EQ(result.scene->colliders[0].static_friction, 0.2);
}

TEST(ColliderFriction, WithoutContactTheContractDefaultsApply) {
  const auto result = load(without_lines(kScene, 6, 8));
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->contact.friction, 0.3);
  EXPECT_EQ(result.scene->contact.static_friction, 0.3);
  EXPECT_EQ(result.scene->contact.stiffness, 5000.0);
  EXPECT_EQ(result.scene->contact.damping, 5.0);
  ASSERT_EQ(result.scene->colliders.size(), 5u);
  EXPECT_EQ(result.scene->colliders[0].friction, 0.3);
  EXPECT_EQ(result.scene->colliders[0].static_friction, 0.3);
  EXPECT_EQ(result.scene->colliders[3].static_friction, 0.6);  // its own friction
}

TEST(ColliderFriction, ContactStaticFrictionIsRead) {
  const auto result = load(kScene);
  ASSERT_LOADS(result);
  EXPECT_EQ(result.scene->contact.friction, 0.2);
  EXPECT_EQ(result.scene->contact.static_friction, 0.4);
}

// ---------------------------------------------------------------------------------------------
// Errors: what they leave out, and several at once

// Of two colliders named alike, only the later one is in error.
TEST(ColliderErrors, TheFirstOfTwoEqualNamesIsFine) {
  EXPECT_TRUE(NoErrorContains(load(with_line(kScene, 26, "  - name: ball")), "colliders.0.name"));
}

// A type far from every known one gets the list of types and no suggestion.
TEST(ColliderErrors, FarUnknownTypeGetsNoSuggestion) {
  EXPECT_TRUE(
      NoErrorContains(load(with_line(kScene, 27, "    type: tetrahedron")), "did you mean"));
}

TEST(ColliderErrors, ErrorsInSeveralCollidersAreAllReported) {
  const auto result =
      load(with_line(with_line(with_line(kScene, 14, "    radius: -1"), 27, "    type: cube"), 35,
                     "    normal: [0, 0, 0]"));
  ASSERT_FALSE(result.ok());
  EXPECT_TRUE(HasError(result, at(14), {"colliders.0.radius must be >= 1e-06"}));
  EXPECT_TRUE(HasError(result, at(27), {"colliders.3.type must be one of"}));
  EXPECT_TRUE(HasError(result, at(35), {"colliders.4.normal must be a non-zero direction"}));
  EXPECT_EQ(result.errors.size(), 3u) << all_errors(result);
}

TEST(ColliderErrors, EveryErrorCarriesTheDisplayNameAndALine) {
  const auto result = load(with_colliders(
      "  - {name: A, type: sphere, radius: -1, friction: -1}\n"
      "  - {name: b, type: box, center: [0, 0], half_extents: [0, 1, 1], radius: 2}\n"
      "  - {name: c, type: spere}\n"));
  ASSERT_FALSE(result.ok());
  // 0: name, center missing, radius, friction; 1: radius unknown, center length, half_extents.0; 2:
  // type.
  EXPECT_EQ(result.errors.size(), 8u) << all_errors(result);
  for (const auto& error : result.errors) {
    EXPECT_TRUE(error.rfind(at(11), 0) == 0 || error.rfind(at(12), 0) == 0 ||
                error.rfind(at(13), 0) == 0)
        << error;
  }
}

// ---------------------------------------------------------------------------------------------
// Motion

TEST(ColliderMotion, VelocityAndAngularVelocityLoad) {
  const auto colliders = colliders_of(
      insert_after(
          kScene, 30,
          "    motion:\n      velocity: [0, 0, 0.5]\n      angular_velocity: [0, 90, -45]"),
      5);
  ASSERT_EQ(colliders.size(), 5u);
  const auto& m = colliders[3].motion;
  EXPECT_EQ(m.velocity, Vector3d(0, 0, 0.5));
  EXPECT_EQ(m.angular_velocity, Vector3d(0, 90, -45));
  EXPECT_TRUE(m.keyframes.empty());
  EXPECT_FALSE(m.is_static());
}

TEST(ColliderMotion, EitherVelocityAloneLeavesTheOtherZero) {
  const auto colliders = colliders_of(
      with_colliders("  - {name: a, type: sphere, center: [0, 0, 0], radius: 1, motion: {velocity: "
                     "[1, 2, 3]}}\n"
                     "  - {name: b, type: plane, motion: {angular_velocity: [0, 0, 10]}}\n"
                     "  - {name: c, type: plane, motion: {}}\n"),
      3);
  ASSERT_EQ(colliders.size(), 3u);
  EXPECT_EQ(colliders[0].motion.velocity, Vector3d(1, 2, 3));
  EXPECT_EQ(colliders[0].motion.angular_velocity, Vector3d::Zero());
  EXPECT_EQ(colliders[1].motion.velocity, Vector3d::Zero());
  EXPECT_EQ(colliders[1].motion.angular_velocity, Vector3d(0, 0, 10));
  EXPECT_TRUE(colliders[2].motion.is_static());
}

TEST(ColliderMotion, KeyframesLoadWithRotationDefaultZero) {
  const auto colliders =
      colliders_of(insert_after(kScene, 14,
                                "    motion:\n"
                                "      keyframes:\n"
                                "        - {t: 0, center: [0, 0.5, 0]}\n"
                                "        - {t: 0.5, center: [0, 1, 0], rotation: [0, 90, 0]}\n"
                                "        - t: 1.25\n"
                                "          center: [1, 1, -1]\n"),
                   5);
  ASSERT_EQ(colliders.size(), 5u);
  const auto& m = colliders[0].motion;
  ASSERT_EQ(m.keyframes.size(), 3u);
  EXPECT_EQ(m.keyframes[0].t, 0.0);
  EXPECT_EQ(m.keyframes[0].center, Vector3d(0, 0.5, 0));
  EXPECT_EQ(m.keyframes[0].rotation, Vector3d::Zero());
  EXPECT_EQ(m.keyframes[1].t, 0.5);
  EXPECT_EQ(m.keyframes[1].center, Vector3d(0, 1, 0));
  EXPECT_EQ(m.keyframes[1].rotation, Vector3d(0, 90, 0));
  EXPECT_EQ(m.keyframes[2].t, 1.25);
  EXPECT_EQ(m.keyframes[2].center, Vector3d(1, 1, -1));
  EXPECT_EQ(m.keyframes[2].rotation, Vector3d::Zero());
  EXPECT_EQ(m.velocity, Vector3d::Zero());
  EXPECT_EQ(m.angular_velocity, Vector3d::Zero());
  EXPECT_FALSE(m.is_static());
  // The collider's own pose fields are untouched by the keyframes.
  EXPECT_EQ(colliders[0].center, Vector3d(0, 0.5, 0));
}

// Keyframes give the centre at every time: a collider's center may be left out (it becomes the
// first keyframe's; one that disagrees is refused, test_collider_errors.cpp). Without keyframes it
// is still required.
TEST(ColliderMotion, KeyframedCenterMayBeLeftOut) {
  const auto colliders = colliders_of(
      with_colliders(
          "  - {name: a, type: sphere, radius: 0.1, motion: {keyframes: [{t: 0, center: [1, 2, "
          "3]}]}}\n"
          "  - {name: b, type: plane, motion: {keyframes: [{t: 0, center: [0, -1, 0]}]}}\n"),
      2);
  ASSERT_EQ(colliders.size(), 2u);
  EXPECT_EQ(colliders[0].center, Vector3d(1, 2, 3));
  EXPECT_EQ(colliders[1].center, Vector3d(0, -1, 0));
  EXPECT_FALSE(load(with_colliders("  - {name: a, type: sphere, radius: 0.1}\n")).ok());
}

// A keyframed collider's own rotation is its orientation at rest; the keyframes turn it further.
TEST(ColliderMotion, KeyframedRotationIsComposedWithTheCollidersRotation) {
  const auto colliders = colliders_of(
      with_colliders("  - name: arm\n"
                     "    type: capsule\n"
                     "    radius: 0.05\n"
                     "    height: 0.4\n"
                     "    rotation: [0, 0, 90]\n"  // the y-axis capsule lies along -x at rest
                     "    motion: {keyframes: [{t: 0, center: [0, 1, 0]}, {t: 1, center: [0, 1, "
                     "0], rotation: [0, 90, 0]}]}\n"),
      1);
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].rotation, Vector3d(0, 0, 90));
  const Vector3d at_rest = drapelab::collider_pose(colliders[0], 0.0).linear() * colliders[0].axis;
  const Vector3d turned = drapelab::collider_pose(colliders[0], 1.0).linear() * colliders[0].axis;
  EXPECT_LT((at_rest - Vector3d(-1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((turned - Vector3d(0, 0, 1)).norm(), 1e-12);  // then a quarter turn about y: -x -> +z
}

TEST(ColliderMotion, OneKeyframeIsEnough) {
  const auto colliders =
      colliders_of(with_colliders("  - {name: a, type: plane, motion: {keyframes: [{t: 2, center: "
                                  "[0, 1, 0], rotation: [5, 0, 0]}]}}\n"),
                   1);
  ASSERT_EQ(colliders.size(), 1u);
  ASSERT_EQ(colliders[0].motion.keyframes.size(), 1u);
  EXPECT_EQ(colliders[0].motion.keyframes[0].t, 2.0);
  EXPECT_EQ(colliders[0].motion.keyframes[0].rotation, Vector3d(5, 0, 0));
}

// Keyframes with a velocity are two kinds of motion given at once, even when the velocity is zero.
TEST(ColliderMotion, KeyframesWithAZeroVelocityAreRefused) {
  EXPECT_FALSE(
      load(
          insert_after(kScene, 14,
                       "    motion: {velocity: [0, 0, 0], keyframes: [{t: 0, center: [0, 0, 0]}]}"))
          .ok());
}

// ---------------------------------------------------------------------------------------------
// --set overrides

TEST(ColliderOverrides, RadiusOverride) {
  const auto colliders = colliders_of(kScene, 5, {"colliders.0.radius=0.5"});
  ASSERT_EQ(colliders.size(), 5u);
  EXPECT_EQ(colliders[0].radius, 0.5);
  EXPECT_EQ(colliders[1].radius, 0.4);  // the others untouched
}

TEST(ColliderOverrides, OverrideCreatesTheMotionMap) {
  const auto colliders = colliders_of(kScene, 5, {"colliders.1.motion.velocity=[0,1,0]"});
  ASSERT_EQ(colliders.size(), 5u);
  EXPECT_EQ(colliders[1].motion.velocity, Vector3d(0, 1, 0));
  EXPECT_EQ(colliders[1].motion.angular_velocity, Vector3d::Zero());
  EXPECT_TRUE(colliders[0].motion.is_static());
}

TEST(ColliderOverrides, SeveralCollidersAndContactOverrides) {
  const auto colliders = colliders_of(
      kScene, 5,
      {"colliders.3.half_extents=[1, 2, 3]", "colliders.4.normal=[0,0,-1]",
       "colliders.2.axis=[1,0,0]", "contact.friction=0.05", "colliders.4.static_friction=0.2",
       "colliders.0.motion={keyframes: [{t: 0, center: [0, 0.5, 0]}, {t: 1, center: [0, 1, 0]}]}"});
  ASSERT_EQ(colliders.size(), 5u);
  EXPECT_EQ(colliders[3].half_extents, Vector3d(1, 2, 3));
  EXPECT_EQ(colliders[4].normal, Vector3d(0, 0, -1));
  EXPECT_EQ(colliders[2].axis, Vector3d(1, 0, 0));
  EXPECT_EQ(colliders[0].friction, 0.05);  // the overridden contact friction is the default
  EXPECT_EQ(colliders[4].static_friction, 0.2);
  ASSERT_EQ(colliders[0].motion.keyframes.size(), 2u);
  EXPECT_EQ(colliders[0].motion.keyframes[1].center, Vector3d(0, 1, 0));
}

TEST(ColliderOverrides, TypeOverrideChangesTheShape) {
  // A sphere's keys (center, radius) are valid for a capsule too, which then also needs a height.
  const auto colliders =
      colliders_of(kScene, 5, {"colliders.0.type=capsule", "colliders.0.height=0.2"});
  ASSERT_EQ(colliders.size(), 5u);
  EXPECT_EQ(colliders[0].shape, ColliderShape::capsule);
  EXPECT_EQ(colliders[0].height, 0.2);
  EXPECT_EQ(colliders[0].radius, 0.3);
}

TEST(ColliderOverrides, WholeListOverrideReplacesTheColliders) {
  const auto colliders = colliders_of(
      kHeader, 1,
      {"colliders=[{name: only, type: box, center: [0, 0, 0], half_extents: [1, 1, 1]}]"});
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].name, "only");
  EXPECT_EQ(colliders[0].shape, ColliderShape::box);
  EXPECT_EQ(colliders[0].half_extents, Vector3d(1, 1, 1));
}

TEST(ColliderOverrides, OverrideCanFixABadCollider) {
  const auto colliders =
      colliders_of(with_line(kScene, 14, "    radius: 0"), 5, {"colliders.0.radius=0.25"});
  ASSERT_EQ(colliders.size(), 5u);
  EXPECT_EQ(colliders[0].radius, 0.25);
}

// A bad override value is reported at the override, not at the file's line of the value it
// replaces.
TEST(ColliderOverrides, BadOverrideValueIsNotReportedAtTheReplacedLine) {
  const auto result = load(kScene, {"colliders.0.radius=-0.5"});
  ASSERT_FALSE(result.ok());
  for (const auto& error : result.errors)
    EXPECT_EQ(error.rfind(at(14), 0), std::string::npos) << error;
}

}  // namespace
