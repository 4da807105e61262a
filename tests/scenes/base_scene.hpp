// The scenes the scene-loader suites edit line by line (test_scene_loader.cpp,
// test_scene_errors.cpp, test_scene_overrides.cpp, test_resolved_scene.cpp), and how they load
// them.
#pragma once

#include <string>
#include <vector>

#include "drapelab/scene/scene_loader.hpp"
#include "fixtures/scene_text.hpp"

namespace drapelab::loader_tests {

inline constexpr const char* kName =
    "drape_test.yaml";  // the display name every message must carry

// A small valid scene using every key the loader knows. Line numbers matter: the tests replace
// whole lines by number, and expect errors at those lines.
inline const std::string kBase =
    "# base scene for the loader tests\n"                 //  1
    "name: base\n"                                        //  2
    "duration: 0.5\n"                                     //  3
    "frame_rate: 60\n"                                    //  4
    "gravity: [0, -9.81, 0]\n"                            //  5
    "seed: 1\n"                                           //  6
    "cloth:\n"                                            //  7
    "  shape: grid\n"                                     //  8
    "  size: [1.0, 0.5]\n"                                //  9
    "  resolution: [5, 4]\n"                              // 10
    "  plane: xz\n"                                       // 11
    "  center: [0, 1, 0]\n"                               // 12
    "  mass: 0.2\n"                                       // 13
    "  thickness: 0.004\n"                                // 14
    "  perturbation: 0.001\n"                             // 15
    "  air_damping: 0.1\n"                                // 16
    "  springs:\n"                                        // 17
    "    stretch: {ks: 500, kd: 0.1}\n"                   // 18
    "    shear: {ks: 50, kd: 0.05}\n"                     // 19
    "    bend: {ks: 5, kd: 0.01}\n"                       // 20
    "  pins:\n"                                           // 21
    "    - corners\n"                                     // 22
    "    - [0, 3]\n"                                      // 23
    "    - {index: 2}\n"                                  // 24
    "    - {within: {center: [0, 1, 0], radius: 0.2}}\n"  // 25
    "contact:\n"                                          // 26
    "  stiffness: 4000\n"                                 // 27
    "  damping: 4\n"                                      // 28
    "  friction: 0.2\n"                                   // 29
    "solvers:\n"                                          // 30
    "  - name: ours\n"                                    // 31
    "    type: spring_damper\n"                           // 32
    "    integrator: symplectic_euler\n"                  // 33
    "    dt: 0.001041666666666666667\n";                  // 34  (1/960 s: 16 steps per frame)

// The smallest valid scene: everything else takes its default.
inline const std::string kMinimal =
    "name: minimal\n"
    "duration: 1\n"
    "cloth:\n"
    "  resolution: [3, 3]\n"
    "  mass: 0.1\n"
    "solvers: [{type: spring_damper}]\n";

inline scene::LoadResult load(const std::string& text,
                              const std::vector<std::string>& overrides = {}) {
  return scene::load_scene_text(text, kName, overrides);
}

// Location prefix for a line of the scene.
inline std::string at(int line) { return fixtures::at_line(kName, line); }
// Location prefix for a --set override.
inline std::string at_set(const std::string& override_text) {
  return fixtures::at_override(kName, override_text);
}

}  // namespace drapelab::loader_tests
