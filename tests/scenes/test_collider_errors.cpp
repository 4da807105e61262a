// Every validation rule of the scene's `colliders:` list and `contact:` friction (docs/scene-reference.md,
// scenes/loader/src/collider_reader.cpp) that a bad scene or --set override breaks, one table row per
// case: the edit of the base scene (collider_scene.hpp), and the error it must cause, with the display
// file name, the 1-based line or the override, the key path and the expected-value wording.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "collider_scene.hpp"
#include "fixtures/scene_cases.hpp"

namespace {

using namespace drapelab::collider_tests;  // collider_scene.hpp
using namespace drapelab::fixtures;        // fixtures/scene_cases.hpp

// The scene with only the colliders `items` (their first line is line 11).
TextEdit only_colliders(const std::string& items) { return whole_scene(with_colliders(items)); }

// A `motion:` map inserted after the ball's radius (line 14), so that it starts on line 15.
TextEdit ball_motion(const std::string& motion) { return insert_lines(14, motion); }

std::vector<BadScene> bad_colliders() {
  return {
      // Friction
      {"ContactStaticFrictionBelowFrictionIsRefused", replace_line(8, "  static_friction: 0.1"), 8,
       "contact.static_friction", {"must be >= contact.friction (0.2), got 0.1"}},
      // Only static_friction given: it is compared with the default friction 0.3.
      {"ContactStaticFrictionBelowTheDefaultFrictionIsRefused",
       {replace_line(8, "  static_friction: 0.25"), remove_lines(7, 7)}, 7, "contact.static_friction",
       {"must be >= contact.friction (0.3), got 0.25"}},
      {"ContactFrictionMustBeNonNegative", replace_line(7, "  friction: -0.1"), 7, "contact.friction",
       {"must be >= 0, got -0.1"}},
      {"ContactStaticFrictionMustBeNonNegative", replace_line(8, "  static_friction: -1"), 8,
       "contact.static_friction", {"must be >= 0, got -1"}},
      {"ContactStaticFrictionMustBeANumber", replace_line(8, "  static_friction: much"), 8, "contact.static_friction",
       {"must be a number (>= 0), got 'much'"}},
      {"ColliderFrictionMustBeNonNegative", replace_line(31, "    friction: -0.6"), 31, "colliders.3.friction",
       {"must be >= 0, got -0.6"}},
      {"ColliderStaticFrictionMustBeNonNegative", replace_line(37, "    static_friction: -0.15"), 37,
       "colliders.4.static_friction", {"must be >= 0, got -0.15"}},
      {"ColliderStaticFrictionBelowItsFrictionIsRefused", replace_line(37, "    static_friction: 0.05"), 37,
       "colliders.4.static_friction", {"must be >= friction (0.1), got 0.05"}},
      // No own friction: the kinetic coefficient is contact.friction 0.2, which the static one may not
      // undercut.
      {"ColliderStaticFrictionBelowContactFrictionIsRefused",
       only_colliders("  - name: a\n    type: plane\n    static_friction: 0.1\n"), 13, "colliders.0.static_friction",
       {"must be >= friction (0.2), got 0.1"}},

      // Name and type
      // The table's name removed: its item starts at line 15 with its type.
      {"MissingNameIsReportedAtTheCollider", {remove_lines(16, 16), replace_line(15, "  - type: cylinder")}, 15,
       "colliders.1.name", {"is required", "[a-z0-9_-]+"}},
      {"NameMustMatchThePattern", replace_line(11, "  - name: Big Ball"), 11, "colliders.0.name",
       {"must use only a-z, 0-9, _ and -, got 'Big Ball'"}},
      {"NameMustMatchThePattern_Empty", replace_line(32, "  - name: \"\""), 32, "colliders.4.name",
       {"must use only a-z, 0-9, _ and -, got ''"}},
      {"NameMustBeText", replace_line(11, "  - name: [a, b]"), 11, "colliders.0.name", {"must be text, got a list"}},
      {"DuplicateNamesAreRefused", replace_line(26, "  - name: ball"), 26, "colliders.3.name",
       {"'ball' is already used by another collider", "names must be unique"}},
      // The duplicate-name error names colliders.N.name, so it sits on the line of that name, also when
      // `name` is not the collider's first key.
      {"DuplicateNameIsReportedAtTheNameLine",
       only_colliders("  - {name: ball, type: plane}\n"  // 11
                      "  - type: plane\n"                // 12
                      "    name: ball\n"),               // 13
       13, "colliders.1.name", {"'ball' is already used by another collider"}},
      {"MissingTypeIsReportedAtTheCollider", remove_lines(27, 27), 26, "colliders.3.type",
       {"is required: one of sphere | cylinder | capsule | box | plane"}},
      // yaml-cpp marks an empty value at the NEXT token; the error still names the line of `type:`.
      {"EmptyTypeIsReportedOnItsOwnLine", replace_line(12, "    type:"), 12, "colliders.0.type",
       {"must be one of", "got nothing"}},
      {"UnknownTypeSuggestsTheNearest_Sphere", replace_line(12, "    type: spere"), 12, "colliders.0.type",
       {"must be one of sphere | cylinder | capsule | box | plane, got 'spere'", "(did you mean 'sphere'?)"}},
      {"UnknownTypeSuggestsTheNearest_Cylinder", replace_line(16, "    type: cilinder"), 16, "colliders.1.type",
       {"must be one of", "got 'cilinder'", "(did you mean 'cylinder'?)"}},
      {"UnknownTypeSuggestsTheNearest_Plane", replace_line(33, "    type: plain"), 33, "colliders.4.type",
       {"must be one of", "got 'plain'", "(did you mean 'plane'?)"}},
      {"FarUnknownTypeListsTheTypes", replace_line(27, "    type: tetrahedron"), 27, "colliders.3.type",
       {"must be one of sphere | cylinder | capsule | box | plane, got 'tetrahedron'"}},
      {"TypeMustBeText", replace_line(12, "    type: [sphere]"), 12, "colliders.0.type",
       {"must be one of sphere | cylinder | capsule | box | plane, got a list"}},
      {"ColliderMustBeAMap_Text", only_colliders("  - ball\n"), 11, "colliders.0",
       {"must be a map of keys, got 'ball'"}},
      {"ColliderMustBeAMap_List", only_colliders("  - {name: a, type: plane}\n  - [1, 2]\n"), 12, "colliders.1",
       {"must be a map of keys, got a list"}},
      {"EmptyColliderItemIsReportedOnItsOwnLine", only_colliders("  - {name: a, type: plane}\n  -\n"), 12,
       "colliders.1", {"must be a map of keys, got nothing"}},
      {"CollidersMustBeAList_Text", whole_scene(kHeader + "colliders: ball\n"), 10, "colliders",
       {"must be a list of colliders, got 'ball'"}},
      {"CollidersMustBeAList_FlowMap", whole_scene(kHeader + "colliders: {name: ball, type: sphere}\n"), 10,
       "colliders", {"must be a list of colliders, got a map"}},
      {"CollidersMustBeAList_BlockMap", whole_scene(kHeader + "colliders:\n  name: ball\n  type: sphere\n"), 11,
       "colliders", {"must be a list of colliders, got a map"}},

      // Keys
      {"UnknownKeySuggestsTheNearest_Radius", replace_line(14, "    radus: 0.3"), 14, "colliders.0.radus",
       {"is not a known key", "did you mean colliders.0.radius?"}},
      {"UnknownKeySuggestsTheNearest_Rotation", replace_line(30, "    rotaton: [0, 30, 0]"), 30,
       "colliders.3.rotaton", {"is not a known key", "did you mean colliders.3.rotation?"}},
      {"UnknownKeySuggestsTheNearest_Normal", replace_line(35, "    normall: [3, 4, 0]"), 35, "colliders.4.normall",
       {"is not a known key", "did you mean colliders.4.normal?"}},
      {"UnknownKeySuggestsTheNearest_HalfExtents", replace_line(29, "    half_extent: [0.5, 0.25, 0.125]"), 29,
       "colliders.3.half_extent", {"is not a known key", "did you mean colliders.3.half_extents?"}},
      {"DuplicateKeyInAColliderIsRefused", insert_lines(14, "    radius: 0.4"), 15, "colliders.0.radius",
       {"appears twice in the same map"}},
      // A key of another shape is an unknown key for this one: with a suggestion when one is close, or
      // else the list of this type's valid keys.
      {"RadiusOnABoxIsUnknown", insert_lines(29, "    radius: 0.5"), 30, "colliders.3.radius",
       {"is not a known key"}},
      {"RadiusOnABoxListsTheBoxKeys", insert_lines(29, "    radius: 0.5"), 30, "colliders.3.radius",
       {"is not a known key",
        "valid keys here: name, type, rotation, friction, static_friction, motion, center, half_extents"}},
      {"HalfExtentsOnASphereIsUnknown", insert_lines(14, "    half_extents: [1, 1, 1]"), 15,
       "colliders.0.half_extents",
       {"is not a known key", "valid keys here: name, type, rotation, friction, static_friction, motion, center, radius"}},
      // No key of a sphere is close to `point`, so the message lists the sphere's valid keys.
      {"PointOnASphereIsUnknown", insert_lines(14, "    point: [0, 0, 0]"), 15, "colliders.0.point",
       {"is not a known key", "valid keys here: name, type, rotation, friction, static_friction, motion, center, radius"}},
      {"OtherShapesKeysAreUnknown_SphereHeight", insert_lines(14, "    height: 1"), 15, "colliders.0.height",
       {"is not a known key"}},
      {"OtherShapesKeysAreUnknown_SphereAxis", insert_lines(14, "    axis: [1, 0, 0]"), 15, "colliders.0.axis",
       {"is not a known key"}},
      {"OtherShapesKeysAreUnknown_SphereNormal", insert_lines(14, "    normal: [0, 1, 0]"), 15, "colliders.0.normal",
       {"is not a known key"}},
      {"OtherShapesKeysAreUnknown_CylinderHalfExtents", insert_lines(20, "    half_extents: [1, 1, 1]"), 21,
       "colliders.1.half_extents", {"is not a known key"}},
      {"OtherShapesKeysAreUnknown_CylinderPoint", insert_lines(20, "    point: [0, 0, 0]"), 21, "colliders.1.point",
       {"is not a known key"}},
      {"OtherShapesKeysAreUnknown_CapsuleNormal", insert_lines(25, "    normal: [0, 1, 0]"), 26,
       "colliders.2.normal", {"is not a known key"}},
      {"OtherShapesKeysAreUnknown_BoxAxis", insert_lines(29, "    axis: [1, 0, 0]"), 30, "colliders.3.axis",
       {"is not a known key"}},
      {"OtherShapesKeysAreUnknown_BoxHeight", insert_lines(29, "    height: 1"), 30, "colliders.3.height",
       {"is not a known key"}},
      {"OtherShapesKeysAreUnknown_PlaneCenter", insert_lines(35, "    center: [0, 0, 0]"), 36, "colliders.4.center",
       {"is not a known key"}},
      {"OtherShapesKeysAreUnknown_PlaneRadius", insert_lines(35, "    radius: 1"), 36, "colliders.4.radius",
       {"is not a known key"}},

      // Required keys
      {"SphereNeedsCenter", only_colliders("  - name: ball\n    type: sphere\n"), 11, "colliders.0.center",
       {"is required", "centre [x, y, z] in m"}},
      {"SphereNeedsRadius", only_colliders("  - name: ball\n    type: sphere\n"), 11, "colliders.0.radius",
       {"is required", "the radius in m, > 0"}},
      {"CylinderNeedsHeight", remove_lines(19, 19), 15, "colliders.1.height",
       {"is required", "full length along the axis in m, > 0"}},
      {"CapsuleNeedsHeight", remove_lines(25, 25), 21, "colliders.2.height", {"is required", "> 0"}},
      {"CapsuleNeedsRadius", remove_lines(24, 24), 21, "colliders.2.radius", {"is required", "> 0"}},
      {"CylinderNeedsCenter", remove_lines(17, 17), 15, "colliders.1.center", {"is required"}},
      {"BoxNeedsHalfExtents", remove_lines(29, 29), 26, "colliders.3.half_extents",
       {"is required", "half the box's size along x, y, z in m, each > 0"}},
      {"BoxNeedsCenter", remove_lines(28, 28), 26, "colliders.3.center", {"is required"}},

      // Values
      {"RadiusAndHeightMustBePositive_SphereRadius", replace_line(14, "    radius: 0"), 14, "colliders.0.radius",
       {"must be > 0, got 0"}},
      {"RadiusAndHeightMustBePositive_CylinderRadius", replace_line(18, "    radius: -0.4"), 18, "colliders.1.radius",
       {"must be > 0, got -0.4"}},
      {"RadiusAndHeightMustBePositive_CylinderHeight", replace_line(19, "    height: -1"), 19, "colliders.1.height",
       {"must be > 0, got -1"}},
      {"RadiusAndHeightMustBePositive_CapsuleHeight", replace_line(25, "    height: 0"), 25, "colliders.2.height",
       {"must be > 0, got 0"}},
      {"RadiusAndHeightMustBePositive_CapsuleRadius", replace_line(24, "    radius: 0.0"), 24, "colliders.2.radius",
       {"must be > 0, got 0.0"}},
      {"HalfExtentsMustBePositive_Zero", replace_line(29, "    half_extents: [0.5, 0, 0.5]"), 29,
       "colliders.3.half_extents.1", {"must be > 0, got 0"}},
      {"HalfExtentsMustBePositive_Negative", replace_line(29, "    half_extents: [-1, 1, 1]"), 29,
       "colliders.3.half_extents.0", {"must be > 0, got -1"}},
      {"NumbersMustBeNumbers_Word", replace_line(14, "    radius: big"), 14, "colliders.0.radius",
       {"must be a number (> 0), got 'big'"}},
      {"NumbersMustBeNumbers_NaN", replace_line(14, "    radius: .nan"), 14, "colliders.0.radius", {"must be"}},
      {"NumbersMustBeNumbers_ListItem", replace_line(13, "    center: [0, x, 0]"), 13, "colliders.0.center.1",
       {"must be a number", "got 'x'"}},
      {"NumbersMustBeNumbers_List", replace_line(19, "    height: [1]"), 19, "colliders.1.height",
       {"must be a number (> 0), got a list"}},
      {"ZeroAxisIsRefused", replace_line(20, "    axis: [0, 0, 0]"), 20, "colliders.1.axis",
       {"must be a non-zero direction, got [0, 0, 0]"}},
      {"ZeroNormalIsRefused", replace_line(35, "    normal: [0, 0, 0]"), 35, "colliders.4.normal",
       {"must be a non-zero direction, got [0, 0, 0]"}},
      {"VectorsMustHaveThreeNumbers_CenterOfTwo", replace_line(13, "    center: [0, 0.5]"), 13, "colliders.0.center",
       {"must be a list of 3 numbers, got a list of 2"}},
      {"VectorsMustHaveThreeNumbers_CenterNumber", replace_line(13, "    center: 0.5"), 13, "colliders.0.center",
       {"must be a list of 3 numbers, got '0.5'"}},
      {"VectorsMustHaveThreeNumbers_AxisOfFour", replace_line(20, "    axis: [0, 1, 0, 0]"), 20, "colliders.1.axis",
       {"must be a list of 3 numbers, got a list of 4"}},
      {"VectorsMustHaveThreeNumbers_HalfExtentsOfTwo", replace_line(29, "    half_extents: [0.5, 0.5]"), 29,
       "colliders.3.half_extents", {"must be a list of 3 numbers, got a list of 2"}},
      {"VectorsMustHaveThreeNumbers_HalfExtentsNumber", replace_line(29, "    half_extents: 0.5"), 29,
       "colliders.3.half_extents", {"must be a list of 3 numbers, got '0.5'"}},
      {"VectorsMustHaveThreeNumbers_RotationOfTwo", replace_line(30, "    rotation: [0, 30]"), 30,
       "colliders.3.rotation", {"must be a list of 3 numbers, got a list of 2"}},
      {"VectorsMustHaveThreeNumbers_PointOfTwo", replace_line(34, "    point: [0, 0]"), 34, "colliders.4.point",
       {"must be a list of 3 numbers, got a list of 2"}},
      {"VectorsMustHaveThreeNumbers_NormalMap", replace_line(35, "    normal: {x: 0}"), 35, "colliders.4.normal",
       {"must be a list of 3 numbers, got a map"}},
      {"VectorsMustHaveThreeNumbers_NormalEmpty", replace_line(35, "    normal: []"), 35, "colliders.4.normal",
       {"must be a list of 3 numbers, got a list of 0"}},

      // Motion
      // A collider's center that disagrees with its first keyframe is refused rather than ignored.
      {"KeyframedCenterMustNotDisagree",
       ball_motion("    motion:\n"                                         // 15
                   "      keyframes: [{t: 0, center: [0, 0.6, 0]}]\n"),  // 16
       13, "colliders.0.center",
       {"must equal the first keyframe's center [0, 0.6, 0]", "or be left out", "got [0, 0.5, 0]"}},
      {"KeyframedPointMustNotDisagree",
       only_colliders("  - name: floor\n"                                           // 11
                      "    type: plane\n"                                           // 12
                      "    point: [0, 0, 0]\n"                                      // 13
                      "    motion: {keyframes: [{t: 0, center: [0, -1, 0]}]}\n"),  // 14
       13, "colliders.0.point", {"must equal the first keyframe's center [0, -1, 0]"}},
      {"KeyframesWithVelocityAreRefused",
       ball_motion("    motion:\n"                                        // 15
                   "      velocity: [0, 1, 0]\n"                          // 16
                   "      keyframes: [{t: 0, center: [0, 0, 0]}]\n"),     // 17
       17, "colliders.0.motion.keyframes",
       {"cannot be combined with velocity or angular_velocity; give one kind of motion"}},
      {"KeyframesWithAngularVelocityAreRefused",
       ball_motion("    motion:\n"                                        // 15
                   "      keyframes: [{t: 0, center: [0, 0, 0]}]\n"       // 16
                   "      angular_velocity: [0, 1, 0]\n"),                // 17
       16, "colliders.0.motion.keyframes", {"cannot be combined with velocity"}},
      {"KeyframeTimesMustStrictlyIncrease_Equal",
       ball_motion("    motion:\n"                                  // 15
                   "      keyframes:\n"                             // 16
                   "        - {t: 0, center: [0, 0, 0]}\n"          // 17
                   "        - {t: 0.5, center: [0, 1, 0]}\n"        // 18
                   "        - {t: 0.5, center: [0, 2, 0]}\n"),      // 19
       19, "colliders.0.motion.keyframes.2.t", {"must be later than the previous keyframe's t = 0.5, got 0.5"}},
      {"KeyframeTimesMustStrictlyIncrease_Decreasing",
       ball_motion("    motion:\n"                                  // 15
                   "      keyframes:\n"                             // 16
                   "        - {t: 1, center: [0, 0, 0]}\n"          // 17
                   "        - {t: 0.25, center: [0, 1, 0]}\n"),     // 18
       18, "colliders.0.motion.keyframes.1.t", {"must be later than the previous keyframe's t = 1, got 0.25"}},
      {"KeyframeTimeMustBeANonNegativeNumber_Negative",
       ball_motion("    motion: {keyframes: [{t: -1, center: [0, 0, 0]}]}"), 15, "colliders.0.motion.keyframes.0.t",
       {"must be >= 0, got -1"}},
      {"KeyframeTimeMustBeANonNegativeNumber_Word",
       ball_motion("    motion: {keyframes: [{t: soon, center: [0, 0, 0]}]}"), 15, "colliders.0.motion.keyframes.0.t",
       {"must be a number (>= 0), got 'soon'"}},
      {"KeyframeNeedsT",
       ball_motion("    motion:\n"                                  // 15
                   "      keyframes:\n"                             // 16
                   "        - {t: 0, center: [0, 0, 0]}\n"          // 17
                   "        - {center: [0, 1, 0]}\n"),              // 18
       18, "colliders.0.motion.keyframes.1.t", {"is required", "time in s, >= 0"}},
      {"KeyframeNeedsCenter",
       ball_motion("    motion:\n"                                  // 15
                   "      keyframes:\n"                             // 16
                   "        - t: 0\n"                               // 17
                   "          rotation: [0, 0, 0]\n"),              // 18
       17, "colliders.0.motion.keyframes.0.center", {"is required", "[x, y, z] in m"}},
      {"KeyframeVectorsAreChecked_Center", ball_motion("    motion: {keyframes: [{t: 0, center: [0, 0]}]}"), 15,
       "colliders.0.motion.keyframes.0.center", {"must be a list of 3 numbers, got a list of 2"}},
      {"KeyframeVectorsAreChecked_Rotation",
       ball_motion("    motion: {keyframes: [{t: 0, center: [0, 0, 0], rotation: 9}]}"), 15,
       "colliders.0.motion.keyframes.0.rotation", {"must be a list of 3 numbers, got '9'"}},
      {"EmptyKeyframeListIsRefused", ball_motion("    motion:\n      keyframes: []"), 16,
       "colliders.0.motion.keyframes", {"must be a non-empty list of {t, center, rotation}, got a list"}},
      // An empty value: reported on the line of the key, not the next one.
      {"EmptyKeyframeValueIsReportedOnItsOwnLine", ball_motion("    motion:\n      keyframes:"), 16,
       "colliders.0.motion.keyframes", {"must be a non-empty list", "got nothing"}},
      {"KeyframesMustBeAListOfMaps_Number", ball_motion("    motion: {keyframes: 3}"), 15,
       "colliders.0.motion.keyframes", {"must be a non-empty list", "got '3'"}},
      {"KeyframesMustBeAListOfMaps_ListItem", ball_motion("    motion:\n      keyframes:\n        - [0, 0, 0]"), 17,
       "colliders.0.motion.keyframes.0", {"must be a map of keys, got a list"}},
      {"UnknownKeysInMotionAreRefused_Near", ball_motion("    motion:\n      velocty: [0, 1, 0]"), 16,
       "colliders.0.motion.velocty", {"is not a known key", "did you mean colliders.0.motion.velocity?"}},
      {"UnknownKeysInMotionAreRefused_Far", ball_motion("    motion:\n      spin: 3"), 16, "colliders.0.motion.spin",
       {"is not a known key", "valid keys here: velocity, angular_velocity, keyframes"}},
      {"UnknownKeysInMotionAreRefused_InAKeyframe",
       ball_motion("    motion: {keyframes: [{t: 0, center: [0, 0, 0], rotaton: [0, 0, 0]}]}"), 15,
       "colliders.0.motion.keyframes.0.rotaton",
       {"is not a known key", "did you mean colliders.0.motion.keyframes.0.rotation?"}},
      {"MotionMustBeAMap", ball_motion("    motion: fast"), 15, "colliders.0.motion",
       {"must be a map of keys, got 'fast'"}},
      {"VelocitiesMustHaveThreeNumbers_Velocity", ball_motion("    motion: {velocity: [0, 1]}"), 15,
       "colliders.0.motion.velocity", {"must be a list of 3 numbers, got a list of 2"}},
      {"VelocitiesMustHaveThreeNumbers_AngularVelocity", ball_motion("    motion: {angular_velocity: [0, x, 1]}"),
       15, "colliders.0.motion.angular_velocity.1", {"must be a number", "got 'x'"}},
  };
}

class ColliderErrors : public ::testing::TestWithParam<BadScene> {};

TEST_P(ColliderErrors, NameTheLineTheKeyAndTheExpectedValue) {
  const BadScene& row = GetParam();
  EXPECT_TRUE(HasKeyedError(load(row.edit.apply(kScene)), at(row.line), row.key, row.wording));
}

INSTANTIATE_TEST_SUITE_P(ColliderLoader, ColliderErrors, ::testing::ValuesIn(bad_colliders()), RowName());

const std::string kPillWithoutCenterOrHeight = "colliders.2={name: pill, type: capsule, radius: 0.1}";

std::vector<BadOverride> bad_collider_overrides() {
  return {
      {"BadOverrideValueNamesTheOverride_Radius", {}, "colliders.0.radius=-0.5", "colliders.0.radius",
       {"must be > 0, got -0.5"}},
      {"BadOverrideValueNamesTheOverride_Velocity", {}, "colliders.1.motion.velocity=[0,1]",
       "colliders.1.motion.velocity", {"must be a list of 3 numbers, got a list of 2"}},
      {"BadOverrideValueNamesTheOverride_Type", {}, "colliders.0.type=spere", "colliders.0.type",
       {"must be one of", "got 'spere'", "did you mean 'sphere'?"}},
      {"BadOverrideValueNamesTheOverride_Normal", {}, "colliders.4.normal=[0,0,0]", "colliders.4.normal",
       {"must be a non-zero direction"}},
      {"BadOverrideValueNamesTheOverride_StaticFriction", {}, "colliders.3.static_friction=0.1",
       "colliders.3.static_friction", {"must be >= friction (0.6), got 0.1"}},
      {"BadOverrideValueNamesTheOverride_ContactStaticFriction", {}, "contact.static_friction=0.1",
       "contact.static_friction", {"must be >= contact.friction (0.2), got 0.1"}},
      {"ErrorsInsideAnOverriddenColliderNameTheOverride_Center", {}, kPillWithoutCenterOrHeight,
       "colliders.2.center", {"is required"}},
      {"ErrorsInsideAnOverriddenColliderNameTheOverride_Height", {}, kPillWithoutCenterOrHeight,
       "colliders.2.height", {"is required"}},
      {"ErrorsInsideAnOverriddenColliderNameTheOverride_Keyframes", {},
       "colliders.0.motion.keyframes=[{t: 1, center: [0, 0, 0]}, {t: 1, center: [0, 0, 0]}]",
       "colliders.0.motion.keyframes.1.t", {"must be later than the previous keyframe's t = 1, got 1"}},
      {"OverrideCreatingAnUnknownKeyNamesTheOverride_Near", {}, "colliders.0.radus=1", "colliders.0.radus",
       {"is not a known key", "did you mean colliders.0.radius?"}},
      {"OverrideCreatingAnUnknownKeyNamesTheOverride_OtherShape", {}, "colliders.3.radius=1", "colliders.3.radius",
       {"is not a known key"}},
      {"OverrideCreatingAnUnknownKeyNamesTheOverride_Motion", {}, "colliders.1.motion.velocty=[0,1,0]",
       "colliders.1.motion.velocty", {"is not a known key", "did you mean colliders.1.motion.velocity?"}},
      {"DuplicateNameByOverrideNamesTheOverride", {}, "colliders.1.name=ball", "colliders.1.name",
       {"'ball' is already used by another collider"}},
      {"ColliderIndexOutOfRange", {}, "colliders.5.radius=1", "colliders",
       {"is a list of 5 items", "'5' is not an index in 0..4"}},
      {"ColliderIndexThatIsNotANumber", {}, "colliders.ball.radius=1", "colliders",
       {"is a list", "'ball' is not an index"}},
  };
}

class ColliderOverrideErrors : public ::testing::TestWithParam<BadOverride> {};

TEST_P(ColliderOverrideErrors, NameTheOverrideTheKeyAndTheExpectedValue) {
  const BadOverride& row = GetParam();
  EXPECT_TRUE(HasKeyedError(load(row.edit.apply(kScene), {row.set}), at_set(row.set), row.key, row.wording));
}

INSTANTIATE_TEST_SUITE_P(ColliderOverrides, ColliderOverrideErrors, ::testing::ValuesIn(bad_collider_overrides()),
                         RowName());

}  // namespace
