// The resolved.yaml round trip of colliders: load -> write -> load the written text -> write again
// gives the same text and the same colliders, every key and motion written, directions exactly.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "collider_scene.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "fixtures/scene_text.hpp"

namespace {

using namespace drapelab::collider_tests;  // collider_scene.hpp
using namespace drapelab::fixtures;        // fixtures/scene_text.hpp

using drapelab::scene::resolved_scene_yaml;
using drapelab::scene::Scene;
using Eigen::Vector3d;

// Colliders of every type, both kinds of motion, awkward numbers and directions.
const std::string kRoundTripColliders =
    "colliders:\n"
    "  - {name: ball, type: sphere, center: [0.1, 0.5, -0.3], radius: 0.3,\n"
    "     motion: {velocity: [0, 0, 0.5], angular_velocity: [0, 90, 0]}}\n"
    "  - {name: table, type: cylinder, center: [0, 0.4, 0], radius: 0.4, height: 0.8, axis: [0, 0, "
    "2],\n"
    "     rotation: [15, 0, 0]}\n"
    "  - {name: pill, type: capsule, center: [1e-3, 0.2, 1], radius: 0.1, height: 0.5, friction: "
    "0.45,\n"
    "     motion: {keyframes: [{t: 0, center: [1e-3, 0.2, 1]}, {t: 0.25, center: [0.5, 0.2, 1], "
    "rotation: [0, 0, 90]},\n"
    "                         {t: 1.5, center: [0.5, 0.7, 1], rotation: [0.1, 0.2, 0.3]}]}}\n"
    "  - {name: crate, type: box, center: [1, 0.5, 0], half_extents: [0.5, 0.25, 0.125], rotation: "
    "[0, 30, 0],\n"
    "     friction: 0.6, static_friction: 0.8, motion: {angular_velocity: [0, 0, -12.5]}}\n"
    "  - {name: floor, type: plane, point: [0, -0.1, 0], normal: [3, 4, 0], friction: 0.1, "
    "static_friction: 0.15}\n"
    "  - {name: wall, type: plane, point: [2, 0, 0], normal: [-1, 0, 0], rotation: [0, 0, 5]}\n";

// load -> write -> load the written text -> write again: the same text, and the same colliders.
void ExpectCollidersRoundTrip(const std::string& text,
                              const std::vector<std::string>& overrides = {}) {
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
  for (std::size_t k = 0; k < a.colliders.size(); ++k)
    ExpectSameCollider(a.colliders[k], b.colliders[k]);
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

// An articulated chain and a pin carried by one of its colliders: the parent names, the frames
// they resolve to, and the pin's attach all survive resolved.yaml.
TEST(ColliderResolved, ParentsAndCarriedPinsRoundTrip) {
  const std::string chain =
      "colliders:\n"
      "  - {name: pelvis, type: sphere, radius: 0.1, motion: {keyframes: [{t: 0, center: [0, 1, "
      "0]}, {t: 1, center: [0, 1, 0], rotation: [0, 90, 0]}]}}\n"
      "  - {name: arm, type: capsule, parent: shoulder, center: [0, -0.2, 0], radius: 0.04, "
      "height: 0.3}\n"
      "  - {name: shoulder, type: sphere, parent: pelvis, center: [0.2, 0.3, 0], radius: 0.05, "
      "rotation: [10, 0, 0]}\n";
  std::string text = kHeader + chain;
  text.insert(text.find("contact:"), "  pins: [{index: 0, attach: arm}]\n");
  ExpectCollidersRoundTrip(text);
  const auto loaded = load(text);
  ASSERT_LOADS(loaded);
  const auto& c = loaded.scene->colliders;
  ASSERT_EQ(c[1].ancestors.size(), 2u);  // shoulder, then pelvis
  EXPECT_EQ(c[1].ancestors[0].center, Vector3d(0.2, 0.3, 0));
  EXPECT_EQ(c[1].ancestors[0].rotation, Vector3d(10, 0, 0));
  EXPECT_EQ(c[1].ancestors[1].motion.keyframes.size(), 2u);
  EXPECT_TRUE(c[1].moves());
  const std::string written = resolved_scene_yaml(*loaded.scene);
  EXPECT_NE(written.find("parent: shoulder"), std::string::npos) << written;
  EXPECT_NE(written.find("{index: 0, attach: arm}"), std::string::npos) << written;
  EXPECT_EQ(loaded.scene->cloth.pin_attach, std::vector<std::string>{"arm"});
}

// Directions are normalised on load; the normalised value written to resolved.yaml loads back to
// exactly the same vector. Normalising an already-unit vector again would divide by a norm of 1 +-
// 1 ulp and move its last bits (axis [1, 1, 0], written as [0.7071067811865475, 0.7071067811865475,
// 0], would load back as 0.7071067811865476 each), so running resolved.yaml would not reproduce the
// run and writing it again would give different text.
TEST(ColliderResolved, ObliqueDirectionsRoundTripExactly) {
  ExpectCollidersRoundTrip(with_colliders(
      "  - {name: a, type: cylinder, center: [0, 0, 0], radius: 1, height: 1, axis: [1, 1, 0]}\n"
      "  - {name: b, type: capsule, center: [0, 0, 0], radius: 1, height: 1, axis: [1, 2, 3]}\n"
      "  - {name: c, type: plane, normal: [1, 1, 1]}\n"
      "  - {name: d, type: plane, normal: [0.3, -0.7, 0.1]}\n"
      "  - {name: e, type: cylinder, center: [0, 0, 0], radius: 1, height: 1, axis: [-2, 0.1, "
      "7]}\n"));
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
    EXPECT_NE(text.find(expected), std::string::npos) << "missing [" << expected << "] in:\n"
                                                      << text;
  // Keys of other shapes are not written: the plane has no center/radius, the sphere no axis, etc.
  const auto floor = text.find("  - name: floor");
  const auto wall = text.find("  - name: wall");
  ASSERT_NE(floor, std::string::npos);
  ASSERT_NE(wall, std::string::npos);
  const std::string floor_text = text.substr(floor, wall - floor);
  EXPECT_EQ(floor_text.find("center:"), std::string::npos) << floor_text;
  EXPECT_EQ(floor_text.find("radius:"), std::string::npos) << floor_text;
  EXPECT_EQ(floor_text.find("motion:"), std::string::npos) << "a static collider has no motion:\n"
                                                           << floor_text;
}

TEST(ColliderResolved, NoCollidersIsAnEmptyList) {
  const auto result = load(kHeader);
  ASSERT_LOADS(result);
  EXPECT_NE(resolved_scene_yaml(*result.scene).find("colliders: []\n"), std::string::npos);
  ExpectCollidersRoundTrip(kHeader);
}

}  // namespace
