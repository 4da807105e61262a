// Unit tests of the scene's `colliders:` list and `contact:` friction (scenes/loader/src/
// collider_reader.cpp, scene_loader.cpp read_contact, scene_writer.cpp): every collider type with
// its fields and defaults, every validation rule (each error checked for the display file name, the
// 1-based line or the --set override, the key path and the expected-value wording), kinematic
// motion, --set overrides on collider keys, and the resolved.yaml round trip.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "fixtures/scene_text.hpp"
#include "drapelab/scene/scene_writer.hpp"

namespace {

using namespace drapelab::fixtures;  // fixtures/scene_text.hpp

using drapelab::Collider;
using drapelab::ColliderKeyframe;
using drapelab::ColliderShape;
using drapelab::scene::load_scene_text;
using drapelab::scene::LoadResult;
using drapelab::scene::resolved_scene_yaml;
using drapelab::scene::Scene;
using Eigen::Vector3d;

constexpr const char* kName = "collider_test.yaml";  // the display name every message must carry

// Everything but the colliders. Nine lines, so "colliders:" is line 10 and its first item line 11.
const std::string kHeader =
    "name: colliders\n"                                             //  1
    "duration: 0.5\n"                                               //  2
    "cloth:\n"                                                      //  3
    "  resolution: [5, 4]\n"                                        //  4
    "  mass: 0.2\n"                                                 //  5
    "contact:\n"                                                    //  6
    "  friction: 0.2\n"                                             //  7
    "  static_friction: 0.4\n"                                      //  8
    "solvers: [{type: spring_damper, dt: 0.001041666666666666667}]\n";  //  9  (1/960 s)

// One collider of every type. Line numbers matter: the tests replace lines by number.
const std::string kColliders =
    "colliders:\n"                                  // 10
    "  - name: ball\n"                              // 11
    "    type: sphere\n"                            // 12
    "    center: [0, 0.5, 0]\n"                     // 13
    "    radius: 0.3\n"                             // 14
    "  - name: table\n"                             // 15
    "    type: cylinder\n"                          // 16
    "    center: [0, 0.4, 0]\n"                     // 17
    "    radius: 0.4\n"                             // 18
    "    height: 0.8\n"                             // 19
    "    axis: [0, 0, 2]\n"                         // 20
    "  - name: pill\n"                              // 21
    "    type: capsule\n"                           // 22
    "    center: [1, 0.2, -1]\n"                    // 23
    "    radius: 0.1\n"                             // 24
    "    height: 0.5\n"                             // 25
    "  - name: crate\n"                             // 26
    "    type: box\n"                               // 27
    "    center: [1, 0.5, 0]\n"                     // 28
    "    half_extents: [0.5, 0.25, 0.125]\n"        // 29
    "    rotation: [0, 30, 0]\n"                    // 30
    "    friction: 0.6\n"                           // 31
    "  - name: floor\n"                             // 32
    "    type: plane\n"                             // 33
    "    point: [0, -0.1, 0]\n"                     // 34
    "    normal: [3, 4, 0]\n"                       // 35
    "    friction: 0.1\n"                           // 36
    "    static_friction: 0.15\n";                  // 37

const std::string kScene = kHeader + kColliders;

// The header followed by "colliders:" (line 10) and `items` (from line 11 on).
std::string with_colliders(const std::string& items) { return kHeader + "colliders:\n" + items; }

LoadResult load(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return load_scene_text(text, kName, overrides);
}

// No error message at all contains `fragment`.
::testing::AssertionResult NoErrorContains(const LoadResult& result, const std::string& fragment) {
  for (const auto& error : result.errors)
    if (error.find(fragment) != std::string::npos)
      return ::testing::AssertionFailure() << "unexpected error: " << error;
  return ::testing::AssertionSuccess();
}

// Location prefix for a line of the scene.
std::string at(int line) { return at_line(kName, line); }
// Location prefix for a --set override.
std::string at_set(const std::string& override_text) { return at_override(kName, override_text); }

// Loads `text`, which must succeed with exactly `count` colliders; returns them.
std::vector<Collider> colliders_of(const std::string& text, std::size_t count,
                                   const std::vector<std::string>& overrides = {}) {
  const auto result = load(text, overrides);
  EXPECT_LOADS(result);
  if (!result.ok()) return {};
  EXPECT_EQ(result.scene->colliders.size(), count);
  return result.scene->colliders;
}

// Every field of two colliders, exactly (numbers are written in round-trip form).
void ExpectSameCollider(const Collider& a, const Collider& b) {
  SCOPED_TRACE("collider " + a.name);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.shape, b.shape);
  EXPECT_EQ(a.center, b.center);
  EXPECT_EQ(a.radius, b.radius);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.axis, b.axis);
  EXPECT_EQ(a.half_extents, b.half_extents);
  EXPECT_EQ(a.normal, b.normal);
  EXPECT_EQ(a.rotation, b.rotation);
  EXPECT_EQ(a.friction, b.friction);
  EXPECT_EQ(a.static_friction, b.static_friction);
  EXPECT_EQ(a.motion.velocity, b.motion.velocity);
  EXPECT_EQ(a.motion.angular_velocity, b.motion.angular_velocity);
  ASSERT_EQ(a.motion.keyframes.size(), b.motion.keyframes.size());
  for (std::size_t k = 0; k < a.motion.keyframes.size(); ++k) {
    EXPECT_EQ(a.motion.keyframes[k].t, b.motion.keyframes[k].t) << "keyframe " << k;
    EXPECT_EQ(a.motion.keyframes[k].center, b.motion.keyframes[k].center) << "keyframe " << k;
    EXPECT_EQ(a.motion.keyframes[k].rotation, b.motion.keyframes[k].rotation) << "keyframe " << k;
  }
}

void ExpectNear(const Vector3d& actual, const Vector3d& expected, double tolerance = 1e-15) {
  EXPECT_TRUE(actual.isApprox(expected, tolerance) || (actual - expected).norm() <= tolerance)
      << "got [" << actual.transpose() << "], expected [" << expected.transpose() << "]";
}

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
  for (std::size_t k : {0u, 1u, 2u, 4u}) EXPECT_EQ(colliders[k].rotation, Vector3d::Zero()) << colliders[k].name;
}

TEST(ColliderLoader, RotationIsReadForEveryType) {
  const auto colliders = colliders_of(
      with_colliders("  - {name: a, type: sphere, center: [0, 0, 0], radius: 1, rotation: [10, -20, 370]}\n"
                     "  - {name: b, type: plane, rotation: [0, 0, 45]}\n"),
      2);
  ASSERT_EQ(colliders.size(), 2u);
  EXPECT_EQ(colliders[0].rotation, Vector3d(10, -20, 370));
  EXPECT_EQ(colliders[1].rotation, Vector3d(0, 0, 45));
}

TEST(ColliderLoader, AxisIsNormalised) {
  const auto colliders = colliders_of(
      with_colliders("  - {name: a, type: cylinder, center: [0, 0, 0], radius: 1, height: 2, axis: [3, 0, -4]}\n"
                     "  - {name: b, type: capsule, center: [0, 0, 0], radius: 1, height: 2, axis: [0, -0.5, 0]}\n"),
      2);
  ASSERT_EQ(colliders.size(), 2u);
  ExpectNear(colliders[0].axis, Vector3d(0.6, 0, -0.8));
  EXPECT_EQ(colliders[1].axis, Vector3d(0, -1, 0));
}

TEST(ColliderLoader, CylinderAxisDefaultsToY) {
  const auto colliders =
      colliders_of(with_colliders("  - {name: a, type: cylinder, center: [0, 0, 0], radius: 1, height: 2}\n"), 1);
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].axis, Vector3d(0, 1, 0));
}

TEST(ColliderLoader, PlaneDefaultsToNormalYThroughTheGivenPoint) {
  const auto colliders = colliders_of(with_colliders("  - {name: ground, type: plane, point: [1, 2, 3]}\n"), 1);
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].shape, ColliderShape::plane);
  EXPECT_EQ(colliders[0].center, Vector3d(1, 2, 3));
  EXPECT_EQ(colliders[0].normal, Vector3d(0, 1, 0));
}

TEST(ColliderLoader, DownwardPlaneNormalIsKept) {
  const auto colliders =
      colliders_of(with_colliders("  - {name: ceiling, type: plane, point: [0, 3, 0], normal: [0, -7, 0]}\n"), 1);
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].normal, Vector3d(0, -1, 0));
}

TEST(ColliderLoader, FlowAndBlockStylesGiveTheSameCollider) {
  const auto block = colliders_of(
      with_colliders("  - name: t\n    type: cylinder\n    center: [1, 2, 3]\n    radius: 0.5\n    height: 2\n"
                     "    axis: [1, 0, 0]\n    rotation: [0, 0, 90]\n    friction: 0.5\n"),
      1);
  const auto flow = colliders_of(
      with_colliders("  - {name: t, type: cylinder, center: [1, 2, 3], radius: 0.5, height: 2, axis: [1, 0, 0], "
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
      with_colliders("  - {name: a, type: sphere, center: [0, 0, 0], radius: 1, static_friction: 0.9}\n"), 1);
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].friction, 0.2);
  EXPECT_EQ(colliders[0].static_friction, 0.9);
}

TEST(ColliderFriction, StaticFrictionEqualToFrictionIsAllowed) {
  const auto colliders = colliders_of(
      with_colliders("  - {name: a, type: sphere, center: [0, 0, 0], radius: 1, friction: 0.7, static_friction: 0.7}\n"),
      1);
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].friction, 0.7);
  EXPECT_EQ(colliders[0].static_friction, 0.7);
}

TEST(ColliderFriction, ZeroFrictionIsAllowed) {
  const auto colliders =
      colliders_of(with_colliders("  - {name: a, type: plane, friction: 0, static_friction: 0}\n"), 1);
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

TEST(ColliderFriction, ContactStaticFrictionBelowFrictionIsRefused) {
  EXPECT_TRUE(HasError(load(with_line(kScene, 8, "  static_friction: 0.1")), at(8),
                       {"contact.static_friction must be >= contact.friction (0.2), got 0.1"}));
  // Only static_friction given: it is compared with the default friction 0.3.
  EXPECT_TRUE(HasError(load(without_lines(with_line(kScene, 8, "  static_friction: 0.25"), 7, 7)), at(7),
                       {"contact.static_friction must be >= contact.friction (0.3), got 0.25"}));
}

TEST(ColliderFriction, ContactFrictionMustBeNonNegative) {
  EXPECT_TRUE(HasError(load(with_line(kScene, 7, "  friction: -0.1")), at(7), {"contact.friction must be >= 0, got -0.1"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 8, "  static_friction: -1")), at(8),
                       {"contact.static_friction must be >= 0, got -1"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 8, "  static_friction: much")), at(8),
                       {"contact.static_friction must be a number (>= 0), got 'much'"}));
}

TEST(ColliderFriction, ColliderFrictionMustBeNonNegative) {
  EXPECT_TRUE(HasError(load(with_line(kScene, 31, "    friction: -0.6")), at(31),
                       {"colliders.3.friction must be >= 0, got -0.6"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 37, "    static_friction: -0.15")), at(37),
                       {"colliders.4.static_friction must be >= 0, got -0.15"}));
}

TEST(ColliderFriction, ColliderStaticFrictionBelowItsFrictionIsRefused) {
  const auto result = load(with_line(kScene, 37, "    static_friction: 0.05"));
  EXPECT_TRUE(HasError(result, at(37), {"colliders.4.static_friction must be >= friction (0.1), got 0.05"}));
}

TEST(ColliderFriction, ColliderStaticFrictionBelowContactFrictionIsRefused) {
  // No own friction: the kinetic coefficient is contact.friction 0.2, which the static one may not undercut.
  const auto result =
      load(with_colliders("  - name: a\n    type: plane\n    static_friction: 0.1\n"));  // lines 11..13
  EXPECT_TRUE(HasError(result, at(13), {"colliders.0.static_friction must be >= friction (0.2), got 0.1"}));
}

// ---------------------------------------------------------------------------------------------
// Errors: name and type

TEST(ColliderErrors, MissingNameIsReportedAtTheCollider) {
  // The table's name removed: its item now starts at line 15 with its type.
  const auto result = load(with_line(without_lines(kScene, 16, 16), 15, "  - type: cylinder"));
  EXPECT_TRUE(HasError(result, at(15), {"colliders.1.name is required", "[a-z0-9_-]+"}));
}

TEST(ColliderErrors, NameMustMatchThePattern) {
  EXPECT_TRUE(HasError(load(with_line(kScene, 11, "  - name: Big Ball")), at(11),
                       {"colliders.0.name must use only a-z, 0-9, _ and -, got 'Big Ball'"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 32, "  - name: \"\"")), at(32),
                       {"colliders.4.name must use only a-z, 0-9, _ and -, got ''"}));
}

TEST(ColliderErrors, NameMustBeText) {
  EXPECT_TRUE(HasError(load(with_line(kScene, 11, "  - name: [a, b]")), at(11),
                       {"colliders.0.name must be text, got a list"}));
}

TEST(ColliderErrors, DuplicateNamesAreRefused) {
  const auto result = load(with_line(kScene, 26, "  - name: ball"));
  EXPECT_TRUE(HasError(result, at(26),
                       {"colliders.3.name", "'ball' is already used by another collider", "names must be unique"}));
  // The first one is fine.
  EXPECT_TRUE(NoErrorContains(result, "colliders.0.name"));
}

// The duplicate-name error names colliders.N.name, so its line must be the line of that name, also
// when `name` is not the collider's first key.
// BUG (collider_reader.cpp, read_colliders: reader.error(list[k], path + ".name", ...)): the error is
// located at the collider's map node, i.e. the line of its FIRST key, not the line of `name`. Passing
// the name's own node (e.g. list[k]["name"] via a const reference) would fix it.
TEST(ColliderErrors, DuplicateNameIsReportedAtTheNameLine) {
  const auto result = load(with_colliders("  - {name: ball, type: plane}\n"  // 11
                                          "  - type: plane\n"                // 12
                                          "    name: ball\n"));              // 13
  EXPECT_TRUE(HasError(result, at(13), {"colliders.1.name", "'ball' is already used by another collider"}));
}

TEST(ColliderErrors, MissingTypeIsReportedAtTheCollider) {
  const auto result = load(without_lines(kScene, 27, 27));  // crate's type
  EXPECT_TRUE(HasError(result, at(26),
                       {"colliders.3.type is required: one of sphere | cylinder | capsule | box | plane"}));
}

// yaml-cpp marks an empty value at the NEXT token; the error must still name the line of `type:`.
// BUG (collider_reader.cpp, read_collider): the type is read before the MapReader records the key
// lines of the collider, so SceneReader::where has no key line for colliders.N.type and falls back to
// the empty node's mark, which is the line AFTER `type:` (here 13, the `center:` line).
TEST(ColliderErrors, EmptyTypeIsReportedOnItsOwnLine) {
  const auto result = load(with_line(kScene, 12, "    type:"));
  EXPECT_TRUE(HasError(result, at(12), {"colliders.0.type must be one of", "got nothing"}));
}

TEST(ColliderErrors, UnknownTypeSuggestsTheNearest) {
  EXPECT_TRUE(HasError(load(with_line(kScene, 12, "    type: spere")), at(12),
                       {"colliders.0.type must be one of sphere | cylinder | capsule | box | plane, got 'spere'",
                        "(did you mean 'sphere'?)"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 16, "    type: cilinder")), at(16),
                       {"colliders.1.type", "got 'cilinder'", "(did you mean 'cylinder'?)"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 33, "    type: plain")), at(33),
                       {"colliders.4.type", "got 'plain'", "(did you mean 'plane'?)"}));
}

TEST(ColliderErrors, FarUnknownTypeListsTheTypesWithoutASuggestion) {
  const auto result = load(with_line(kScene, 27, "    type: tetrahedron"));
  EXPECT_TRUE(HasError(result, at(27),
                       {"colliders.3.type must be one of sphere | cylinder | capsule | box | plane, got 'tetrahedron'"}));
  EXPECT_TRUE(NoErrorContains(result, "did you mean"));
}

TEST(ColliderErrors, TypeMustBeText) {
  EXPECT_TRUE(HasError(load(with_line(kScene, 12, "    type: [sphere]")), at(12),
                       {"colliders.0.type must be one of sphere | cylinder | capsule | box | plane, got a list"}));
}

TEST(ColliderErrors, ColliderMustBeAMap) {
  EXPECT_TRUE(HasError(load(with_colliders("  - ball\n")), at(11), {"colliders.0 must be a map of keys, got 'ball'"}));
  EXPECT_TRUE(HasError(load(with_colliders("  - {name: a, type: plane}\n  - [1, 2]\n")), at(12),
                       {"colliders.1 must be a map of keys, got a list"}));
}

TEST(ColliderErrors, EmptyColliderItemIsReportedOnItsOwnLine) {
  EXPECT_TRUE(HasError(load(with_colliders("  - {name: a, type: plane}\n  -\n")), at(12),
                       {"colliders.1 must be a map of keys, got nothing"}));
}

TEST(ColliderErrors, CollidersMustBeAList) {
  EXPECT_TRUE(HasError(load(kHeader + "colliders: ball\n"), at(10), {"colliders must be a list of colliders, got 'ball'"}));
  EXPECT_TRUE(HasError(load(kHeader + "colliders: {name: ball, type: sphere}\n"), at(10),
                       {"colliders must be a list of colliders, got a map"}));
  EXPECT_TRUE(HasError(load(kHeader + "colliders:\n  name: ball\n  type: sphere\n"), at(11),
                       {"colliders must be a list of colliders, got a map"}));
}

TEST(ColliderErrors, UnknownKeySuggestsTheNearest) {
  EXPECT_TRUE(HasError(load(with_line(kScene, 14, "    radus: 0.3")), at(14),
                       {"colliders.0.radus is not a known key", "did you mean colliders.0.radius?"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 30, "    rotaton: [0, 30, 0]")), at(30),
                       {"colliders.3.rotaton is not a known key", "did you mean colliders.3.rotation?"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 35, "    normall: [3, 4, 0]")), at(35),
                       {"colliders.4.normall is not a known key", "did you mean colliders.4.normal?"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 29, "    half_extent: [0.5, 0.25, 0.125]")), at(29),
                       {"colliders.3.half_extent is not a known key", "did you mean colliders.3.half_extents?"}));
}

TEST(ColliderErrors, DuplicateKeyInAColliderIsRefused) {
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    radius: 0.4")), at(15),
                       {"colliders.0.radius appears twice in the same map"}));
}

// A key of another shape is an unknown key for this one: with a suggestion when one is close, or
// else the list of this type's valid keys.
TEST(ColliderErrors, RadiusOnABoxIsUnknown) {
  const auto result = load(insert_after(kScene, 29, "    radius: 0.5"));
  EXPECT_TRUE(HasError(result, at(30), {"colliders.3.radius is not a known key"}));
  EXPECT_TRUE(HasError(result, at(30),
                       {"colliders.3.radius", "valid keys here: name, type, rotation, friction, static_friction, "
                                              "motion, center, half_extents"}));
}

TEST(ColliderErrors, HalfExtentsOnASphereIsUnknown) {
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    half_extents: [1, 1, 1]")), at(15),
                       {"colliders.0.half_extents is not a known key",
                        "valid keys here: name, type, rotation, friction, static_friction, motion, center, radius"}));
}

TEST(ColliderErrors, PointOnASphereIsUnknown) {
  const auto result = load(insert_after(kScene, 14, "    point: [0, 0, 0]"));
  // No key of a sphere is close to `point`, so the message lists the sphere's valid keys.
  EXPECT_TRUE(HasError(result, at(15),
                       {"colliders.0.point is not a known key",
                        "valid keys here: name, type, rotation, friction, static_friction, motion, center, radius"}));
}

TEST(ColliderErrors, OtherShapesKeysAreUnknown) {
  struct Case {
    int after;
    std::string line, path;
  };
  const std::vector<Case> cases = {
      {14, "    height: 1", "colliders.0.height"},        // sphere
      {14, "    axis: [1, 0, 0]", "colliders.0.axis"},    // sphere
      {14, "    normal: [0, 1, 0]", "colliders.0.normal"},  // sphere
      {20, "    half_extents: [1, 1, 1]", "colliders.1.half_extents"},  // cylinder
      {20, "    point: [0, 0, 0]", "colliders.1.point"},  // cylinder
      {25, "    normal: [0, 1, 0]", "colliders.2.normal"},  // capsule
      {29, "    axis: [1, 0, 0]", "colliders.3.axis"},    // box
      {29, "    height: 1", "colliders.3.height"},        // box
      {35, "    center: [0, 0, 0]", "colliders.4.center"},  // plane
      {35, "    radius: 1", "colliders.4.radius"},        // plane
  };
  for (const auto& c : cases) {
    EXPECT_TRUE(HasError(load(insert_after(kScene, c.after, c.line)), at(c.after + 1), {c.path + " is not a known key"}))
        << c.line;
  }
}

TEST(ColliderErrors, SphereNeedsCenterAndRadius) {
  const auto result = load(with_colliders("  - name: ball\n    type: sphere\n"));
  EXPECT_TRUE(HasError(result, at(11), {"colliders.0.center is required", "centre [x, y, z] in m"}));
  EXPECT_TRUE(HasError(result, at(11), {"colliders.0.radius is required", "the radius in m, > 0"}));
}

TEST(ColliderErrors, CylinderAndCapsuleNeedHeight) {
  EXPECT_TRUE(HasError(load(without_lines(kScene, 19, 19)), at(15),
                       {"colliders.1.height is required", "full length along the axis in m, > 0"}));
  EXPECT_TRUE(HasError(load(without_lines(kScene, 25, 25)), at(21), {"colliders.2.height is required", "> 0"}));
  EXPECT_TRUE(HasError(load(without_lines(kScene, 24, 24)), at(21), {"colliders.2.radius is required", "> 0"}));
  EXPECT_TRUE(HasError(load(without_lines(kScene, 17, 17)), at(15), {"colliders.1.center is required"}));
}

TEST(ColliderErrors, BoxNeedsCenterAndHalfExtents) {
  EXPECT_TRUE(HasError(load(without_lines(kScene, 29, 29)), at(26),
                       {"colliders.3.half_extents is required", "half the box's size along x, y, z in m, each > 0"}));
  EXPECT_TRUE(HasError(load(without_lines(kScene, 28, 28)), at(26), {"colliders.3.center is required"}));
}

TEST(ColliderErrors, RadiusAndHeightMustBePositive) {
  EXPECT_TRUE(HasError(load(with_line(kScene, 14, "    radius: 0")), at(14), {"colliders.0.radius must be > 0, got 0"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 18, "    radius: -0.4")), at(18), {"colliders.1.radius must be > 0, got -0.4"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 19, "    height: -1")), at(19), {"colliders.1.height must be > 0, got -1"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 25, "    height: 0")), at(25), {"colliders.2.height must be > 0, got 0"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 24, "    radius: 0.0")), at(24), {"colliders.2.radius must be > 0, got 0.0"}));
}

TEST(ColliderErrors, HalfExtentsMustBePositive) {
  EXPECT_TRUE(HasError(load(with_line(kScene, 29, "    half_extents: [0.5, 0, 0.5]")), at(29),
                       {"colliders.3.half_extents.1 must be > 0, got 0"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 29, "    half_extents: [-1, 1, 1]")), at(29),
                       {"colliders.3.half_extents.0 must be > 0, got -1"}));
}

TEST(ColliderErrors, NumbersMustBeNumbers) {
  EXPECT_TRUE(HasError(load(with_line(kScene, 14, "    radius: big")), at(14),
                       {"colliders.0.radius must be a number (> 0), got 'big'"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 14, "    radius: .nan")), at(14), {"colliders.0.radius must be"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 13, "    center: [0, x, 0]")), at(13),
                       {"colliders.0.center.1 must be a number", "got 'x'"}));
  EXPECT_TRUE(HasError(load(with_line(kScene, 19, "    height: [1]")), at(19),
                       {"colliders.1.height must be a number (> 0), got a list"}));
}

TEST(ColliderErrors, ZeroAxisIsRefused) {
  EXPECT_TRUE(HasError(load(with_line(kScene, 20, "    axis: [0, 0, 0]")), at(20),
                       {"colliders.1.axis must be a non-zero direction, got [0, 0, 0]"}));
}

TEST(ColliderErrors, ZeroNormalIsRefused) {
  EXPECT_TRUE(HasError(load(with_line(kScene, 35, "    normal: [0, 0, 0]")), at(35),
                       {"colliders.4.normal must be a non-zero direction, got [0, 0, 0]"}));
}

TEST(ColliderErrors, VectorsMustHaveThreeNumbers) {
  struct Case {
    int line;
    std::string text, message;
  };
  const std::vector<Case> cases = {
      {13, "    center: [0, 0.5]", "colliders.0.center must be a list of 3 numbers, got a list of 2"},
      {13, "    center: 0.5", "colliders.0.center must be a list of 3 numbers, got '0.5'"},
      {20, "    axis: [0, 1, 0, 0]", "colliders.1.axis must be a list of 3 numbers, got a list of 4"},
      {29, "    half_extents: [0.5, 0.5]", "colliders.3.half_extents must be a list of 3 numbers, got a list of 2"},
      {29, "    half_extents: 0.5", "colliders.3.half_extents must be a list of 3 numbers, got '0.5'"},
      {30, "    rotation: [0, 30]", "colliders.3.rotation must be a list of 3 numbers, got a list of 2"},
      {34, "    point: [0, 0]", "colliders.4.point must be a list of 3 numbers, got a list of 2"},
      {35, "    normal: {x: 0}", "colliders.4.normal must be a list of 3 numbers, got a map"},
      {35, "    normal: []", "colliders.4.normal must be a list of 3 numbers, got a list of 0"},
  };
  for (const auto& c : cases) EXPECT_TRUE(HasError(load(with_line(kScene, c.line, c.text)), at(c.line), {c.message})) << c.text;
}

TEST(ColliderErrors, ErrorsInSeveralCollidersAreAllReported) {
  const auto result =
      load(with_line(with_line(with_line(kScene, 14, "    radius: -1"), 27, "    type: cube"), 35, "    normal: [0, 0, 0]"));
  ASSERT_FALSE(result.ok());
  EXPECT_TRUE(HasError(result, at(14), {"colliders.0.radius must be > 0"}));
  EXPECT_TRUE(HasError(result, at(27), {"colliders.3.type must be one of"}));
  EXPECT_TRUE(HasError(result, at(35), {"colliders.4.normal must be a non-zero direction"}));
  EXPECT_EQ(result.errors.size(), 3u) << all_errors(result);
}

TEST(ColliderErrors, EveryErrorCarriesTheDisplayNameAndALine) {
  const auto result = load(with_colliders("  - {name: A, type: sphere, radius: -1, friction: -1}\n"
                                          "  - {name: b, type: box, center: [0, 0], half_extents: [0, 1, 1], radius: 2}\n"
                                          "  - {name: c, type: spere}\n"));
  ASSERT_FALSE(result.ok());
  // 0: name, center missing, radius, friction; 1: radius unknown, center length, half_extents.0; 2: type.
  EXPECT_EQ(result.errors.size(), 8u) << all_errors(result);
  for (const auto& error : result.errors) {
    EXPECT_TRUE(error.rfind(at(11), 0) == 0 || error.rfind(at(12), 0) == 0 || error.rfind(at(13), 0) == 0) << error;
  }
}

// ---------------------------------------------------------------------------------------------
// Motion

TEST(ColliderMotion, VelocityAndAngularVelocityLoad) {
  const auto colliders = colliders_of(
      insert_after(kScene, 30, "    motion:\n      velocity: [0, 0, 0.5]\n      angular_velocity: [0, 90, -45]"), 5);
  ASSERT_EQ(colliders.size(), 5u);
  const auto& m = colliders[3].motion;
  EXPECT_EQ(m.velocity, Vector3d(0, 0, 0.5));
  EXPECT_EQ(m.angular_velocity, Vector3d(0, 90, -45));
  EXPECT_TRUE(m.keyframes.empty());
  EXPECT_FALSE(m.is_static());
}

TEST(ColliderMotion, EitherVelocityAloneLeavesTheOtherZero) {
  const auto colliders = colliders_of(
      with_colliders("  - {name: a, type: sphere, center: [0, 0, 0], radius: 1, motion: {velocity: [1, 2, 3]}}\n"
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
  const auto colliders = colliders_of(insert_after(kScene, 14,
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

// Keyframes give the centre at every time: a collider's center may be left out (it becomes the first
// keyframe's), and one that disagrees with the first keyframe is refused rather than ignored.
TEST(ColliderMotion, KeyframedCenterMayBeLeftOutAndMustNotDisagree) {
  const auto colliders = colliders_of(
      with_colliders("  - {name: a, type: sphere, radius: 0.1, motion: {keyframes: [{t: 0, center: [1, 2, 3]}]}}\n"
                     "  - {name: b, type: plane, motion: {keyframes: [{t: 0, center: [0, -1, 0]}]}}\n"),
      2);
  ASSERT_EQ(colliders.size(), 2u);
  EXPECT_EQ(colliders[0].center, Vector3d(1, 2, 3));
  EXPECT_EQ(colliders[1].center, Vector3d(0, -1, 0));
  const auto moved = load(insert_after(kScene, 14,
                                       "    motion:\n"                                             // 15
                                       "      keyframes: [{t: 0, center: [0, 0.6, 0]}]\n"));      // 16
  EXPECT_TRUE(HasError(moved, at(13), {"colliders.0.center must equal the first keyframe's center [0, 0.6, 0]",
                                       "or be left out", "got [0, 0.5, 0]"}));
  const auto plane = load(with_colliders(
      "  - name: floor\n"                                                   // 11
      "    type: plane\n"                                                   // 12
      "    point: [0, 0, 0]\n"                                              // 13
      "    motion: {keyframes: [{t: 0, center: [0, -1, 0]}]}\n"));          // 14
  EXPECT_TRUE(HasError(plane, at(13), {"colliders.0.point must equal the first keyframe's center [0, -1, 0]"}));
  // Still required without keyframes.
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
                     "    motion: {keyframes: [{t: 0, center: [0, 1, 0]}, {t: 1, center: [0, 1, 0], rotation: [0, 90, 0]}]}\n"),
      1);
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].rotation, Vector3d(0, 0, 90));
  const Vector3d at_rest = drapelab::collider_pose(colliders[0], 0.0).linear() * colliders[0].axis;
  const Vector3d turned = drapelab::collider_pose(colliders[0], 1.0).linear() * colliders[0].axis;
  EXPECT_LT((at_rest - Vector3d(-1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((turned - Vector3d(0, 0, 1)).norm(), 1e-12);  // then a quarter turn about y: -x -> +z
}

TEST(ColliderMotion, OneKeyframeIsEnough) {
  const auto colliders = colliders_of(
      with_colliders("  - {name: a, type: plane, motion: {keyframes: [{t: 2, center: [0, 1, 0], rotation: [5, 0, 0]}]}}\n"),
      1);
  ASSERT_EQ(colliders.size(), 1u);
  ASSERT_EQ(colliders[0].motion.keyframes.size(), 1u);
  EXPECT_EQ(colliders[0].motion.keyframes[0].t, 2.0);
  EXPECT_EQ(colliders[0].motion.keyframes[0].rotation, Vector3d(5, 0, 0));
}

TEST(ColliderMotion, KeyframesWithVelocityAreRefused) {
  const auto result = load(insert_after(kScene, 14,
                                        "    motion:\n"                                        // 15
                                        "      velocity: [0, 1, 0]\n"                          // 16
                                        "      keyframes: [{t: 0, center: [0, 0, 0]}]\n"));    // 17
  EXPECT_TRUE(HasError(result, at(17), {"colliders.0.motion.keyframes cannot be combined with velocity or "
                                        "angular_velocity; give one kind of motion"}));
  const auto angular = load(insert_after(kScene, 14,
                                         "    motion:\n"                                       // 15
                                         "      keyframes: [{t: 0, center: [0, 0, 0]}]\n"      // 16
                                         "      angular_velocity: [0, 1, 0]\n"));              // 17
  EXPECT_TRUE(HasError(angular, at(16), {"colliders.0.motion.keyframes cannot be combined with velocity"}));
  // Even a zero velocity: it is still two kinds of motion given at once.
  EXPECT_FALSE(load(insert_after(kScene, 14, "    motion: {velocity: [0, 0, 0], keyframes: [{t: 0, center: [0, 0, 0]}]}")).ok());
}

TEST(ColliderMotion, KeyframeTimesMustStrictlyIncrease) {
  const std::string motion =
      "    motion:\n"                                  // 15
      "      keyframes:\n"                             // 16
      "        - {t: 0, center: [0, 0, 0]}\n"          // 17
      "        - {t: 0.5, center: [0, 1, 0]}\n"        // 18
      "        - {t: 0.5, center: [0, 2, 0]}\n";       // 19
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, motion)), at(19),
                       {"colliders.0.motion.keyframes.2.t must be later than the previous keyframe's t = 0.5, got 0.5"}));
  const std::string decreasing =
      "    motion:\n"                                  // 15
      "      keyframes:\n"                             // 16
      "        - {t: 1, center: [0, 0, 0]}\n"          // 17
      "        - {t: 0.25, center: [0, 1, 0]}\n";      // 18
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, decreasing)), at(18),
                       {"colliders.0.motion.keyframes.1.t must be later than the previous keyframe's t = 1, got 0.25"}));
}

TEST(ColliderMotion, KeyframeTimeMustBeANonNegativeNumber) {
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion: {keyframes: [{t: -1, center: [0, 0, 0]}]}")), at(15),
                       {"colliders.0.motion.keyframes.0.t must be >= 0, got -1"}));
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion: {keyframes: [{t: soon, center: [0, 0, 0]}]}")), at(15),
                       {"colliders.0.motion.keyframes.0.t must be a number (>= 0), got 'soon'"}));
}

TEST(ColliderMotion, KeyframeNeedsTAndCenter) {
  const std::string no_t =
      "    motion:\n"                                  // 15
      "      keyframes:\n"                             // 16
      "        - {t: 0, center: [0, 0, 0]}\n"          // 17
      "        - {center: [0, 1, 0]}\n";               // 18
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, no_t)), at(18),
                       {"colliders.0.motion.keyframes.1.t is required", "time in s, >= 0"}));
  const std::string no_center =
      "    motion:\n"                                  // 15
      "      keyframes:\n"                             // 16
      "        - t: 0\n"                               // 17
      "          rotation: [0, 0, 0]\n";               // 18
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, no_center)), at(17),
                       {"colliders.0.motion.keyframes.0.center is required", "[x, y, z] in m"}));
}

TEST(ColliderMotion, KeyframeVectorsAreChecked) {
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion: {keyframes: [{t: 0, center: [0, 0]}]}")), at(15),
                       {"colliders.0.motion.keyframes.0.center must be a list of 3 numbers, got a list of 2"}));
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion: {keyframes: [{t: 0, center: [0, 0, 0], rotation: 9}]}")),
                       at(15), {"colliders.0.motion.keyframes.0.rotation must be a list of 3 numbers, got '9'"}));
}

TEST(ColliderMotion, EmptyKeyframeListIsRefused) {
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion:\n      keyframes: []")), at(16),
                       {"colliders.0.motion.keyframes must be a non-empty list of {t, center, rotation}, got a list"}));
  // An empty value: reported on the line of the key, not the next one.
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion:\n      keyframes:")), at(16),
                       {"colliders.0.motion.keyframes must be a non-empty list", "got nothing"}));
}

TEST(ColliderMotion, KeyframesMustBeAListOfMaps) {
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion: {keyframes: 3}")), at(15),
                       {"colliders.0.motion.keyframes must be a non-empty list", "got '3'"}));
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion:\n      keyframes:\n        - [0, 0, 0]")), at(17),
                       {"colliders.0.motion.keyframes.0 must be a map of keys, got a list"}));
}

TEST(ColliderMotion, UnknownKeysInMotionAreRefused) {
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion:\n      velocty: [0, 1, 0]")), at(16),
                       {"colliders.0.motion.velocty is not a known key", "did you mean colliders.0.motion.velocity?"}));
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion:\n      spin: 3")), at(16),
                       {"colliders.0.motion.spin is not a known key",
                        "valid keys here: velocity, angular_velocity, keyframes"}));
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion: {keyframes: [{t: 0, center: [0, 0, 0], rotaton: [0, 0, 0]}]}")),
                       at(15), {"colliders.0.motion.keyframes.0.rotaton is not a known key",
                                "did you mean colliders.0.motion.keyframes.0.rotation?"}));
}

TEST(ColliderMotion, MotionMustBeAMap) {
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion: fast")), at(15),
                       {"colliders.0.motion must be a map of keys, got 'fast'"}));
}

TEST(ColliderMotion, VelocitiesMustHaveThreeNumbers) {
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion: {velocity: [0, 1]}")), at(15),
                       {"colliders.0.motion.velocity must be a list of 3 numbers, got a list of 2"}));
  EXPECT_TRUE(HasError(load(insert_after(kScene, 14, "    motion: {angular_velocity: [0, x, 1]}")), at(15),
                       {"colliders.0.motion.angular_velocity.1 must be a number", "got 'x'"}));
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
  const auto colliders =
      colliders_of(kScene, 5,
                   {"colliders.3.half_extents=[1, 2, 3]", "colliders.4.normal=[0,0,-1]", "colliders.2.axis=[1,0,0]",
                    "contact.friction=0.05", "colliders.4.static_friction=0.2",
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
  const auto colliders = colliders_of(kScene, 5, {"colliders.0.type=capsule", "colliders.0.height=0.2"});
  ASSERT_EQ(colliders.size(), 5u);
  EXPECT_EQ(colliders[0].shape, ColliderShape::capsule);
  EXPECT_EQ(colliders[0].height, 0.2);
  EXPECT_EQ(colliders[0].radius, 0.3);
}

TEST(ColliderOverrides, WholeListOverrideReplacesTheColliders) {
  const auto colliders =
      colliders_of(kHeader, 1, {"colliders=[{name: only, type: box, center: [0, 0, 0], half_extents: [1, 1, 1]}]"});
  ASSERT_EQ(colliders.size(), 1u);
  EXPECT_EQ(colliders[0].name, "only");
  EXPECT_EQ(colliders[0].shape, ColliderShape::box);
  EXPECT_EQ(colliders[0].half_extents, Vector3d(1, 1, 1));
}

TEST(ColliderOverrides, BadOverrideValueNamesTheOverride) {
  const auto result = load(kScene, {"colliders.0.radius=-0.5"});
  EXPECT_TRUE(HasError(result, at_set("colliders.0.radius=-0.5"), {"colliders.0.radius must be > 0, got -0.5"}));
  for (const auto& error : result.errors) EXPECT_EQ(error.rfind(at(14), 0), std::string::npos) << error;

  EXPECT_TRUE(HasError(load(kScene, {"colliders.1.motion.velocity=[0,1]"}), at_set("colliders.1.motion.velocity=[0,1]"),
                       {"colliders.1.motion.velocity must be a list of 3 numbers, got a list of 2"}));
  EXPECT_TRUE(HasError(load(kScene, {"colliders.0.type=spere"}), at_set("colliders.0.type=spere"),
                       {"colliders.0.type", "got 'spere'", "did you mean 'sphere'?"}));
  EXPECT_TRUE(HasError(load(kScene, {"colliders.4.normal=[0,0,0]"}), at_set("colliders.4.normal=[0,0,0]"),
                       {"colliders.4.normal must be a non-zero direction"}));
  EXPECT_TRUE(HasError(load(kScene, {"colliders.3.static_friction=0.1"}), at_set("colliders.3.static_friction=0.1"),
                       {"colliders.3.static_friction must be >= friction (0.6), got 0.1"}));
  EXPECT_TRUE(HasError(load(kScene, {"contact.static_friction=0.1"}), at_set("contact.static_friction=0.1"),
                       {"contact.static_friction must be >= contact.friction (0.2), got 0.1"}));
}

TEST(ColliderOverrides, ErrorsInsideAnOverriddenColliderNameTheOverride) {
  const std::string set = "colliders.2={name: pill, type: capsule, radius: 0.1}";
  const auto result = load(kScene, {set});
  EXPECT_TRUE(HasError(result, at_set(set), {"colliders.2.center is required"}));
  EXPECT_TRUE(HasError(result, at_set(set), {"colliders.2.height is required"}));
  const std::string keyframes = "colliders.0.motion.keyframes=[{t: 1, center: [0, 0, 0]}, {t: 1, center: [0, 0, 0]}]";
  EXPECT_TRUE(HasError(load(kScene, {keyframes}), at_set(keyframes),
                       {"colliders.0.motion.keyframes.1.t must be later than the previous keyframe's t = 1, got 1"}));
}

TEST(ColliderOverrides, OverrideCreatingAnUnknownKeyNamesTheOverride) {
  EXPECT_TRUE(HasError(load(kScene, {"colliders.0.radus=1"}), at_set("colliders.0.radus=1"),
                       {"colliders.0.radus is not a known key", "did you mean colliders.0.radius?"}));
  EXPECT_TRUE(HasError(load(kScene, {"colliders.3.radius=1"}), at_set("colliders.3.radius=1"),
                       {"colliders.3.radius is not a known key"}));
  EXPECT_TRUE(HasError(load(kScene, {"colliders.1.motion.velocty=[0,1,0]"}), at_set("colliders.1.motion.velocty=[0,1,0]"),
                       {"colliders.1.motion.velocty is not a known key", "did you mean colliders.1.motion.velocity?"}));
}

TEST(ColliderOverrides, DuplicateNameByOverrideNamesTheOverride) {
  EXPECT_TRUE(HasError(load(kScene, {"colliders.1.name=ball"}), at_set("colliders.1.name=ball"),
                       {"colliders.1.name", "'ball' is already used by another collider"}));
}

TEST(ColliderOverrides, ColliderIndexOutOfRange) {
  EXPECT_TRUE(HasError(load(kScene, {"colliders.5.radius=1"}), at_set("colliders.5.radius=1"),
                       {"colliders is a list of 5 items", "'5' is not an index in 0..4"}));
  EXPECT_TRUE(HasError(load(kScene, {"colliders.ball.radius=1"}), at_set("colliders.ball.radius=1"),
                       {"colliders is a list", "'ball' is not an index"}));
}

TEST(ColliderOverrides, OverrideCanFixABadCollider) {
  const auto colliders = colliders_of(with_line(kScene, 14, "    radius: 0"), 5, {"colliders.0.radius=0.25"});
  ASSERT_EQ(colliders.size(), 5u);
  EXPECT_EQ(colliders[0].radius, 0.25);
}

// ---------------------------------------------------------------------------------------------
// resolved.yaml

// Colliders of every type, both kinds of motion, awkward numbers and directions.
const std::string kRoundTripColliders =
    "colliders:\n"
    "  - {name: ball, type: sphere, center: [0.1, 0.5, -0.3], radius: 0.3,\n"
    "     motion: {velocity: [0, 0, 0.5], angular_velocity: [0, 90, 0]}}\n"
    "  - {name: table, type: cylinder, center: [0, 0.4, 0], radius: 0.4, height: 0.8, axis: [0, 0, 2],\n"
    "     rotation: [15, 0, 0]}\n"
    "  - {name: pill, type: capsule, center: [1e-3, 0.2, 1], radius: 0.1, height: 0.5, friction: 0.45,\n"
    "     motion: {keyframes: [{t: 0, center: [1e-3, 0.2, 1]}, {t: 0.25, center: [0.5, 0.2, 1], rotation: [0, 0, 90]},\n"
    "                         {t: 1.5, center: [0.5, 0.7, 1], rotation: [0.1, 0.2, 0.3]}]}}\n"
    "  - {name: crate, type: box, center: [1, 0.5, 0], half_extents: [0.5, 0.25, 0.125], rotation: [0, 30, 0],\n"
    "     friction: 0.6, static_friction: 0.8, motion: {angular_velocity: [0, 0, -12.5]}}\n"
    "  - {name: floor, type: plane, point: [0, -0.1, 0], normal: [3, 4, 0], friction: 0.1, static_friction: 0.15}\n"
    "  - {name: wall, type: plane, point: [2, 0, 0], normal: [-1, 0, 0], rotation: [0, 0, 5]}\n";

// load -> write -> load the written text -> write again: the same text, and the same colliders.
void ExpectCollidersRoundTrip(const std::string& text, const std::vector<std::string>& overrides = {}) {
  const auto first = load(text, overrides);
  ASSERT_LOADS(first);
  const std::string written = resolved_scene_yaml(*first.scene);
  const auto second = load(written);
  ASSERT_LOADS(second) << "\nresolved text:\n" << written;
  EXPECT_EQ(resolved_scene_yaml(*second.scene), written);
  const Scene& a = *first.scene;
  const Scene& b = *second.scene;
  EXPECT_EQ(a.contact.stiffness, b.contact.stiffness);
  EXPECT_EQ(a.contact.damping, b.contact.damping);
  EXPECT_EQ(a.contact.friction, b.contact.friction);
  EXPECT_EQ(a.contact.static_friction, b.contact.static_friction);
  ASSERT_EQ(a.colliders.size(), b.colliders.size()) << written;
  for (std::size_t k = 0; k < a.colliders.size(); ++k) ExpectSameCollider(a.colliders[k], b.colliders[k]);
}

TEST(ColliderResolved, EveryTypeAndMotionRoundTrips) {
  ExpectCollidersRoundTrip(kHeader + kRoundTripColliders);
  ExpectCollidersRoundTrip(kScene);
}

TEST(ColliderResolved, RoundTripKeepsEveryValue) {
  const auto first = load(kHeader + kRoundTripColliders);
  ASSERT_LOADS(first);
  const auto second = load(resolved_scene_yaml(*first.scene));
  ASSERT_LOADS(second);
  const auto& c = second.scene->colliders;
  ASSERT_EQ(c.size(), 6u);
  EXPECT_EQ(c[0].motion.velocity, Vector3d(0, 0, 0.5));
  EXPECT_EQ(c[0].motion.angular_velocity, Vector3d(0, 90, 0));
  EXPECT_EQ(c[1].axis, Vector3d(0, 0, 1));
  EXPECT_EQ(c[1].rotation, Vector3d(15, 0, 0));
  EXPECT_EQ(c[2].friction, 0.45);
  EXPECT_EQ(c[2].static_friction, 0.45);
  ASSERT_EQ(c[2].motion.keyframes.size(), 3u);
  EXPECT_EQ(c[2].motion.keyframes[0].center, Vector3d(1e-3, 0.2, 1));
  EXPECT_EQ(c[2].motion.keyframes[1].rotation, Vector3d(0, 0, 90));
  EXPECT_EQ(c[2].motion.keyframes[2].t, 1.5);
  EXPECT_EQ(c[2].motion.keyframes[2].rotation, Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(c[3].static_friction, 0.8);
  EXPECT_EQ(c[3].motion.velocity, Vector3d::Zero());
  EXPECT_EQ(c[3].motion.angular_velocity, Vector3d(0, 0, -12.5));
  EXPECT_EQ(c[4].center, Vector3d(0, -0.1, 0));
  ExpectNear(c[4].normal, Vector3d(0.6, 0.8, 0));
  EXPECT_EQ(c[5].normal, Vector3d(-1, 0, 0));
  EXPECT_EQ(c[5].friction, 0.2);         // contact.friction
  EXPECT_EQ(c[5].static_friction, 0.4);  // contact.static_friction
  EXPECT_TRUE(c[4].motion.is_static());
}

// Directions are normalised on load; the normalised value written to resolved.yaml must load back
// to exactly the same vector (normalising it again must not move its last bits).
// BUG (collider_reader.cpp, read_direction: `return Eigen::Vector3d(*value).normalized();`): an
// already-unit vector read back from resolved.yaml is divided by a norm that is 1 +- 1 ulp, so its last
// bits change: axis [1, 1, 0] is written as [0.7071067811865475, 0.7071067811865475, 0] and loads
// back as 0.7071067811865476 each; normal [0.3, -0.7, 0.1] moves likewise. Running resolved.yaml thus
// does not reproduce the run exactly, and writing it again gives different text. A fix: keep the
// given vector when its norm is already 1 to within a few ulps (or write and compare with a
// normalisation that is idempotent).
TEST(ColliderResolved, ObliqueDirectionsRoundTripExactly) {
  ExpectCollidersRoundTrip(with_colliders(
      "  - {name: a, type: cylinder, center: [0, 0, 0], radius: 1, height: 1, axis: [1, 1, 0]}\n"
      "  - {name: b, type: capsule, center: [0, 0, 0], radius: 1, height: 1, axis: [1, 2, 3]}\n"
      "  - {name: c, type: plane, normal: [1, 1, 1]}\n"
      "  - {name: d, type: plane, normal: [0.3, -0.7, 0.1]}\n"
      "  - {name: e, type: cylinder, center: [0, 0, 0], radius: 1, height: 1, axis: [-2, 0.1, 7]}\n"));
}

TEST(ColliderResolved, RoundTripWithColliderOverrides) {
  ExpectCollidersRoundTrip(kScene, {"colliders.0.radius=0.5", "colliders.1.motion.velocity=[0,1,0]",
                                    "colliders.3.motion={keyframes: [{t: 0, center: [1, 0.5, 0]}]}",
                                    "contact.static_friction=0.7"});
}

TEST(ColliderResolved, ResolvedTextHoldsEveryColliderKey) {
  const auto result = load(kHeader + kRoundTripColliders);
  ASSERT_LOADS(result);
  const std::string text = resolved_scene_yaml(*result.scene);
  const std::vector<std::string> expectations = {
      "colliders:\n",
      "  - name: ball\n    type: sphere\n    center: [0.1, 0.5, -0.3]",
      "    radius: 0.3",
      "motion: {velocity: [0, 0, 0.5], angular_velocity: [0, 90, 0]}",
      "  - name: table\n    type: cylinder\n",
      "    height: 0.8",
      "    axis: [0, 0, 1]",
      "    rotation: [15, 0, 0]",
      "  - name: pill\n    type: capsule\n",
      "      keyframes:\n",
      "        - {t: 0, center: [0.001, 0.2, 1], rotation: [0, 0, 0]}",
      "        - {t: 0.25, center: [0.5, 0.2, 1], rotation: [0, 0, 90]}",
      "        - {t: 1.5, center: [0.5, 0.7, 1], rotation: [0.1, 0.2, 0.3]}",
      "  - name: crate\n    type: box\n    center: [1, 0.5, 0]",
      "    half_extents: [0.5, 0.25, 0.125]",
      "    friction: 0.6",
      "    static_friction: 0.8",
      "motion: {velocity: [0, 0, 0], angular_velocity: [0, 0, -12.5]}",
      "  - name: floor\n    type: plane\n    point: [0, -0.1, 0]",
      "    static_friction: 0.15",
      "  - name: wall\n    type: plane\n    point: [2, 0, 0]",
      "    normal: [-1, 0, 0]",
      "  friction: 0.2",
      "  static_friction: 0.4",
  };
  for (const auto& expected : expectations)
    EXPECT_NE(text.find(expected), std::string::npos) << "missing [" << expected << "] in:\n" << text;
  // Keys of other shapes are not written: the plane has no center/radius, the sphere no axis, etc.
  const auto floor = text.find("  - name: floor");
  const auto wall = text.find("  - name: wall");
  ASSERT_NE(floor, std::string::npos);
  ASSERT_NE(wall, std::string::npos);
  const std::string floor_text = text.substr(floor, wall - floor);
  EXPECT_EQ(floor_text.find("center:"), std::string::npos) << floor_text;
  EXPECT_EQ(floor_text.find("radius:"), std::string::npos) << floor_text;
  EXPECT_EQ(floor_text.find("motion:"), std::string::npos) << "a static collider has no motion:\n" << floor_text;
}

TEST(ColliderResolved, NoCollidersIsAnEmptyList) {
  const auto result = load(kHeader);
  ASSERT_LOADS(result);
  EXPECT_NE(resolved_scene_yaml(*result.scene).find("colliders: []\n"), std::string::npos);
  ExpectCollidersRoundTrip(kHeader);
}

}  // namespace
