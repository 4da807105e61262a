// The hostile scenes of the reliability review (issue 41) end to end, as a table: each scene (a
// text, or a shipped scene with --set edits), the verb, the exit code and the fragments its output
// must hold. A cloth starting inside a collider, a self-collision thickness its edges break, error
// floods, sizes past their limits (under a memory limit, so that memory taken before the check
// fails the row) and a NUL in a path all end with exit code 2 and a located message; the starts in
// contact that are meant run ok; an unstable run names what acted in its last step.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "fixtures/cli.hpp"
#include "fixtures/scene_cases.hpp"

namespace {

namespace fs = std::filesystem;
using drapelab::fixtures::CommandResult;
using drapelab::fixtures::run_drapelab;
using drapelab::fixtures::run_drapelab_with_address_space_limit;
using drapelab::fixtures::write_text;

const fs::path kScenes = fs::path(DRAPELAB_SOURCE_DIR) / "scenes";

// A level sheet of 11 x 11 particles 1 m above a floor, 0.05 s; colliders appended to it join the
// floor. Line numbers matter.
const std::string kSheet =
    "name: sheet\n"                                         // 1
    "duration: 0.05\n"                                      // 2
    "cloth:\n"                                              // 3
    "  resolution: [11, 11]\n"                              // 4
    "  center: [0, 1, 0]\n"                                 // 5
    "  mass: 0.1\n"                                         // 6
    "solvers: [{type: spring_damper}]\n"                    // 7
    "colliders:\n"                                          // 8
    "  - {name: floor, type: plane, normal: [0, 1, 0]}\n";  // 9

// A chain of two particles, the top one pinned, the other pulled by `pull` (an interactions or
// constraints list) 1e9 N/m hard at 10 steps per frame: far past its stable step.
std::string pulled_chain(const std::string& pull) {
  return "name: chain\nduration: 0.05\ncloth:\n  resolution: [1, 2]\n  plane: xy\n  mass: 0.1\n"
         "  pins: [top_corners]\n" +
         pull + "solvers: [{type: spring_damper, dt: 0.0016666666666666668}]\n";
}

// `count` lines made by `line(k)`.
std::string repeated(int count, const std::function<std::string(int)>& line) {
  std::string text;
  for (int k = 0; k < count; ++k) text += line(k);
  return text;
}

struct HostileScene {
  std::string name;
  std::string verb;                    // validate or run (into DIR/out)
  std::string text;                    // the scene file's text; empty: `file`
  fs::path file;                       // a shipped scene, when `text` is empty
  std::vector<std::string> arguments;  // after the scene: --set, flags
  int exit_code = 0;
  std::vector<std::string> fragments;  // each in the output
  std::size_t max_output_bytes = 20'000;
  std::size_t address_space_kb = 0;  // ulimit -v for the command; 0: none
};

void PrintTo(const HostileScene& row, std::ostream* out) { *out << row.name; }

std::vector<HostileScene> hostile_scenes() {
  const std::string flip = "colliders.0.normal=[0,-1,0]";
  const std::string inside_floor =
      "scene.yaml:9: colliders.0 (plane 'floor': a half-space, solid where y > 0, the side its "
      "normal [0, -1, 0] points away from) holds 121 of the cloth's 121 free particles at t = 0";
  return {
      // A cloth that starts inside or through a collider
      {"PlaneNormalPointingDownUnderAFallingSheet",
       "validate",
       kSheet,
       {},
       {"--set", flip},
       2,
       {"error: " + inside_floor, "The cloth (scene.yaml:3) starts inside it",
        "turn the plane's normal towards the cloth; --allow-start-inside runs it anyway"}},
      {"PlaneNormalPointingDownIsNotRun",
       "run",
       kSheet,
       {},
       {"--set", flip},
       2,
       {"error: " + inside_floor, "nothing was run"}},
      {"PlaneNormalPointingDownRunsWhenAllowedAndSaysWhyItBlowsUp",
       "run",
       kSheet,
       {},
       {"--set", flip, "--allow-start-inside"},
       1,
       {"warning: " + inside_floor, "it runs anyway (--allow-start-inside)",
        "solver 'spring_damper' unstable: particle",
        "In that step: collider contacts with plane 'floor' (121 particles, the deepest 1.005 m "
        "into its contact, deeper than the cloth's thickness 0.005 m: inside the collider). Try:"}},
      {"PlaneTurnedNinetyDegreesThroughTheSheet",
       "validate",
       kSheet,
       {},
       {"--set", "colliders.0.rotation=[0,0,90]"},
       2,
       {"error: scene.yaml:9: colliders.0 (plane 'floor': a half-space, solid where x > 0, the "
        "side its normal [-1, 0, 0] points away from) holds 55 of the cloth's 121"}},
      {"DrapeSupportBallLargerThanTheCloth",
       "validate",
       "",
       kScenes / "sphere_drape.yaml",
       {"--set", "colliders.0.radius=1.5"},
       2,
       {"colliders.0 (sphere 'ball' of radius 1.5 m at [0, 0.5, 0]) holds 1681 of the cloth's "
        "1681 free particles"}},
      {"FlagCentreAtTheFloorNegativeZero",
       "validate",
       "",
       kScenes / "flag.yaml",
       {"--set", "cloth.center.1=-0.0"},
       2,
       {"colliders.1 (plane 'floor': a half-space, solid where y < 0, the side its normal [0, 1, "
        "0] points away from) holds 192 of the cloth's 408 free particles"}},
      {"FlagCentreAtTheFloorSubnormal",
       "validate",
       "",
       kScenes / "flag.yaml",
       {"--set", "cloth.center.1=1e-320"},
       2,
       {"colliders.1 (plane 'floor'", "holds 192 of the cloth's 408 free particles"}},

      // Self-collision thickness against the cloth's edges
      {"SelfCollisionThicknessOfAFifthOfAMetre",
       "validate",
       "",
       kScenes / "heap.yaml",
       {"--set", "cloth.self_collision.thickness=0.2"},
       2,
       {"cloth.self_collision.thickness must be below 0.7 of the cloth's shortest rest edge (0.7 "
        "x 0.025 m = 0.0175 m), got 0.2 m"}},
      {"SelfCollisionThicknessOfAMetre",
       "run",
       "",
       kScenes / "heap.yaml",
       {"--set", "cloth.self_collision.thickness=1"},
       2,
       {"cloth.self_collision.thickness must be below 0.7", "got 1 m", "nothing was run"}},

      // Error floods: 20 errors and a count; long values cut with their length
      {"AHundredThousandUnknownKeys",
       "validate",
       kSheet + repeated(100'000, [](int k) { return "junk" + std::to_string(k) + ": 1\n"; }),
       {},
       {},
       2,
       {"error: scene.yaml:10: junk0 is not a known key",
        "error: scene.yaml: 99980 more errors are not listed (only the first 20 are)"},
       6'000},
      {"AHundredThousandColliders",
       "validate",
       kSheet + repeated(100'000,
                         [](int k) {
                           return "  - {name: c" + std::to_string(k) +
                                  ", type: sphere, center: [0, -5, 0], radius: 0.1, bogus: 1}\n";
                         }),
       {},
       {},
       2,
       {"error: scene.yaml:8: colliders has more than 1000 colliders; at most 1000 are allowed"},
       500},
      {"AHundredThousandDigitNumber",
       "validate",
       "name: big\nduration: 1\ncloth: {resolution: [3, 3], mass: " + std::string(100'000, '7') +
           "}\n",
       {},
       {},
       2,
       {"error: scene.yaml:3: cloth.mass must be a number", "(100000 characters)"},
       400},

      // Sizes before memory is taken: under a limit far below what the allocation would need
      {"ATwoThousandSquareSheet",
       "run",
       "",
       kScenes / "curtain.yaml",
       {"--set", "cloth.resolution=[2000,2000]"},
       2,
       {"cloth.resolution gives 4000000 particles; at most 1000000 are allowed", "nothing was run"},
       2'000,
       1'000'000},
      {"AMillionElementPinList",
       "validate",
       "name: pins\nduration: 1\ncloth:\n  resolution: [3, 3]\n  mass: 0.1\n  pins:\n" +
           repeated(1'000'000, [](int) { return "    - {index: 5}\n"; }),
       {},
       {},
       2,
       {"error: scene.yaml:6: cloth.pins has more than 10000 pin selectors; at most 10000 are "
        "allowed"},
       500,
       500'000},
      {"ARunLargerThanTheProcessMayUse",
       "validate",
       "name: large\nduration: 1\ncloth: {resolution: [1000, 1000], mass: 1}\nsolvers: [{type: "
       "spring_damper}, {type: bullet_softbody}, {type: bullet_deformable}]\n",
       {},
       {},
       2,
       {"error: scene.yaml:3: cloth.resolution gives 1000000 particles, and a run of them needs "
        "about 8100 MB of memory",
        "this process may use (the address space limit (ulimit -v))"},
       2'000,
       2'000'000},

      // Paths
      {"ANulByteInAMeshPath",
       "validate",
       "name: mesh\nduration: 1\ncloth: {shape: mesh, path: \"good.obj\\0x\", mass: 0.1}\n",
       {},
       {},
       2,
       {"error: scene.yaml:3: cloth.path holds a NUL byte (\\0) at character 9, which would end "
        "the file name there"}},

      // Starts in contact that are meant
      {"RestingAtTheThicknessRunsOk",
       "run",
       kSheet,
       {},
       {"--set", "cloth.center=[0,0.005,0]"},
       0,
       {"spring_damper (spring_damper): ok"}},
      {"PinnedInsideABodyThatCarriesItRunsOk",
       "run",
       kSheet + "  - {name: body, type: box, center: [5, 1, 0], half_extents: [0.1, 0.1, 0.1], "
                "motion: {velocity: [0, 0.5, 0]}}\n"
                "  - {name: hand, type: sphere, parent: body, center: [-5, 0, 0], radius: 0.1}\n",
       {},
       {"--set", "cloth.pins=[{within: {center: [0, 1, 0], radius: 0.12}, attach: hand}]"},
       0,
       {"spring_damper (spring_damper): ok"}},

      // An unstable run says what acted in its last step
      {"UnstableThroughADrag",
       "run",
       pulled_chain("interactions: [{type: drag, particle: {index: 0}, stiffness: 1e9, keyframes: "
                    "[{t: 0, target: [0, 3, 0]}]}]\n"),
       {},
       {},
       1,
       {"particle 0 (grid i=0, j=0) moves at",
        "In that step: particle 0 is an end of interactions.0 (a drag). Try:"}},
      {"UnstableThroughASoftConstraint",
       "run",
       pulled_chain("constraints: [{type: distance, a: {index: 0}, b: {point: [0, 3, 0]}, mode: "
                    "soft, stiffness: 1e9}]\n"),
       {},
       {},
       1,
       {"In that step: particle 0 is an end of constraints.0 (soft). Try:"}},
  };
}

class HostileScenes : public drapelab::fixtures::TempDirTest,
                      public ::testing::WithParamInterface<HostileScene> {};

TEST_P(HostileScenes, EndWithTheirExitCodeAndALocatedMessage) {
  const HostileScene& row = GetParam();
  fs::path scene = row.file;
  if (!row.text.empty()) {
    scene = dir() / "scene.yaml";
    write_text(scene, row.text);
    write_text(dir() / "good.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n");
  }
  // Run from the scene's folder, so that messages name it as scene.yaml.
  std::vector<std::string> arguments = {row.verb, row.text.empty() ? scene.string() : "scene.yaml"};
  if (row.verb == "run") arguments.insert(arguments.end(), {"--out", (dir() / "out").string()});
  arguments.insert(arguments.end(), row.arguments.begin(), row.arguments.end());
  const fs::path before = fs::current_path();
  fs::current_path(dir());
  const CommandResult result = row.address_space_kb > 0 ? run_drapelab_with_address_space_limit(
                                                              row.address_space_kb, arguments)
                                                        : run_drapelab(arguments);
  fs::current_path(before);
  EXPECT_EQ(result.exit_code, row.exit_code) << result.output.substr(0, 4000);
  for (const std::string& fragment : row.fragments)
    EXPECT_NE(result.output.find(fragment), std::string::npos)
        << "missing [" << fragment << "] in:\n"
        << result.output.substr(0, 4000);
  EXPECT_LE(result.output.size(), row.max_output_bytes) << result.output.substr(0, 4000);
  if (row.exit_code == 2 && row.verb == "run") {
    EXPECT_FALSE(fs::exists(dir() / "out")) << "nothing may be written for bad input";
  }
}

INSTANTIATE_TEST_SUITE_P(Issue41, HostileScenes, ::testing::ValuesIn(hostile_scenes()),
                         drapelab::fixtures::RowName());

}  // namespace
