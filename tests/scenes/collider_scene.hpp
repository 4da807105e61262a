// The scene the collider-loader suites edit line by line (test_collider_loader.cpp,
// test_collider_errors.cpp, test_collider_resolved.cpp), how they load it, and what they compare.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "fixtures/scene_text.hpp"

namespace drapelab::collider_tests {

inline constexpr const char* kName =
    "collider_test.yaml";  // the display name every message must carry

// Everything but the colliders. Nine lines, so "colliders:" is line 10 and its first item line 11.
inline const std::string kHeader =
    "name: colliders\n"                                                 //  1
    "duration: 0.5\n"                                                   //  2
    "cloth:\n"                                                          //  3
    "  resolution: [5, 4]\n"                                            //  4
    "  mass: 0.2\n"                                                     //  5
    "contact:\n"                                                        //  6
    "  friction: 0.2\n"                                                 //  7
    "  static_friction: 0.4\n"                                          //  8
    "solvers: [{type: spring_damper, dt: 0.001041666666666666667}]\n";  //  9  (1/960 s)

// One collider of every type. Line numbers matter: the tests replace lines by number.
inline const std::string kColliders =
    "colliders:\n"                            // 10
    "  - name: ball\n"                        // 11
    "    type: sphere\n"                      // 12
    "    center: [0, 0.5, 0]\n"               // 13
    "    radius: 0.3\n"                       // 14
    "  - name: table\n"                       // 15
    "    type: cylinder\n"                    // 16
    "    center: [0, 0.4, 0]\n"               // 17
    "    radius: 0.4\n"                       // 18
    "    height: 0.8\n"                       // 19
    "    axis: [0, 0, 2]\n"                   // 20
    "  - name: pill\n"                        // 21
    "    type: capsule\n"                     // 22
    "    center: [1, 0.2, -1]\n"              // 23
    "    radius: 0.1\n"                       // 24
    "    height: 0.5\n"                       // 25
    "  - name: crate\n"                       // 26
    "    type: box\n"                         // 27
    "    center: [1, 0.5, 0]\n"               // 28
    "    half_extents: [0.5, 0.25, 0.125]\n"  // 29
    "    rotation: [0, 30, 0]\n"              // 30
    "    friction: 0.6\n"                     // 31
    "  - name: floor\n"                       // 32
    "    type: plane\n"                       // 33
    "    point: [0, -0.1, 0]\n"               // 34
    "    normal: [3, 4, 0]\n"                 // 35
    "    friction: 0.1\n"                     // 36
    "    static_friction: 0.15\n";            // 37

inline const std::string kScene = kHeader + kColliders;

// The header followed by "colliders:" (line 10) and `items` (from line 11 on).
inline std::string with_colliders(const std::string& items) {
  return kHeader + "colliders:\n" + items;
}

// These suites test how each key is read, with colliders wherever their cases need them: where the
// cloth starts against them is test_start_state.cpp's subject, so a start inside is a warning here,
// as with drapelab validate --allow-start-inside.
inline scene::LoadResult load(const std::string& text,
                              const std::vector<std::string>& overrides = {}) {
  return scene::load_scene_text(text, kName, overrides, scene::StartInside::warning);
}

// No error message at all contains `fragment`.
inline ::testing::AssertionResult NoErrorContains(const scene::LoadResult& result,
                                                  const std::string& fragment) {
  for (const auto& error : result.errors)
    if (error.find(fragment) != std::string::npos)
      return ::testing::AssertionFailure() << "unexpected error: " << error;
  return ::testing::AssertionSuccess();
}

// Location prefix for a line of the scene.
inline std::string at(int line) { return fixtures::at_line(kName, line); }
// Location prefix for a --set override.
inline std::string at_set(const std::string& override_text) {
  return fixtures::at_override(kName, override_text);
}

// Loads `text`, which must succeed with exactly `count` colliders; returns them.
inline std::vector<Collider> colliders_of(const std::string& text, std::size_t count,
                                          const std::vector<std::string>& overrides = {}) {
  const auto result = load(text, overrides);
  EXPECT_LOADS(result);
  if (!result.ok()) return {};
  EXPECT_EQ(result.scene->colliders.size(), count);
  return result.scene->colliders;
}

// Every field of two colliders, exactly (numbers are written in round-trip form).
inline void ExpectSameCollider(const Collider& a, const Collider& b) {
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
  EXPECT_EQ(a.parent, b.parent);
  EXPECT_EQ(a.ancestors.size(), b.ancestors.size());
  EXPECT_EQ(a.motion.velocity, b.motion.velocity);
  EXPECT_EQ(a.motion.angular_velocity, b.motion.angular_velocity);
  ASSERT_EQ(a.motion.keyframes.size(), b.motion.keyframes.size());
  for (std::size_t k = 0; k < a.motion.keyframes.size(); ++k) {
    EXPECT_EQ(a.motion.keyframes[k].t, b.motion.keyframes[k].t) << "keyframe " << k;
    EXPECT_EQ(a.motion.keyframes[k].center, b.motion.keyframes[k].center) << "keyframe " << k;
    EXPECT_EQ(a.motion.keyframes[k].rotation, b.motion.keyframes[k].rotation) << "keyframe " << k;
  }
}

// `actual` within `tolerance` of `expected`, relatively or absolutely.
inline void ExpectNear(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected,
                       double tolerance = 1e-15) {
  EXPECT_TRUE(actual.isApprox(expected, tolerance) || (actual - expected).norm() <= tolerance)
      << "got [" << actual.transpose() << "], expected [" << expected.transpose() << "]";
}

}  // namespace drapelab::collider_tests
