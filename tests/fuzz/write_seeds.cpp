// Writes the fuzz targets' seed inputs taken from the test suites' texts into OUT/scene/ and
// OUT/obj/, which docs/testing.md ("Seeds") merges with scenes/*.yaml into tests/fuzz/corpus/.
// The scene seeds are the loader tests' scenes, some with --set overrides after NUL bytes
// (fuzz_inputs.hpp), and scenes of every cloth shape; the OBJ seeds are the reader tests' files.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "fixtures/sweep_scene.hpp"
#include "scenes/base_scene.hpp"
#include "scenes/collider_scene.hpp"

namespace {

namespace fs = std::filesystem;

// A scene input with overrides: the text, then each override after a NUL byte.
std::string with_overrides(const std::string& text, const std::vector<std::string>& overrides) {
  std::string input = text;
  for (const auto& o : overrides) input += '\0' + o;
  return input;
}

const std::string kDiscScene =
    "name: disc\n"
    "duration: 0.1\n"
    "cloth:\n"
    "  shape: disc\n"
    "  radius: 0.15\n"
    "  rings: 10\n"
    "  center: [0, 0.5, 0]\n"
    "  material: cotton\n"
    "colliders:\n"
    "  - {name: table, type: cylinder, center: [0, 0.25, 0], radius: 0.09, height: 0.49}\n"
    "metrics:\n"
    "  drape_support: table\n"
    "solvers: [{type: spring_damper}]\n";

// `path` names a file of tests/fuzz/meshes/, where the fuzzed scenes stand.
std::string mesh_scene(const std::string& obj) {
  return "name: cape\n"
         "duration: 0.1\n"
         "cloth:\n"
         "  shape: mesh\n"
         "  path: " +
         obj +
         "\n"
         "  scale: 0.5\n"
         "  center: [0, 1, 0]\n"
         "  mass: 0.1\n"
         "  pins: [{within: {center: [0, 1, 0], radius: 0.01}}]\n"
         "solvers: [{type: spring_damper}]\n";
}

void write(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_write_seeds OUT\n";
    return 2;
  }
  const fs::path out = argv[1];
  fs::create_directories(out / "scene");
  fs::create_directories(out / "obj");
  using drapelab::loader_tests::kBase;
  using drapelab::loader_tests::kMinimal;

  const std::vector<std::pair<std::string, std::string>> scenes = {
      {"base.yaml", kBase},
      {"minimal.yaml", kMinimal},
      {"colliders.yaml", drapelab::collider_tests::kScene},
      {"sweep_sheet.yaml", drapelab::fixtures::kSweepSheet},
      {"disc.yaml", kDiscScene},
      {"mesh_square.yaml", mesh_scene("square.obj")},
      {"mesh_quad_uv.yaml", mesh_scene("quad_uv.obj")},
      {"base_set_resolution.yaml", with_overrides(kBase, {"cloth.resolution=[5,7]"})},
      {"base_set_dt_gravity.yaml",
       with_overrides(kBase, {"solvers.0.dt=0.0005208333333333333", "gravity=[0,-1.62,0]"})},
      {"base_set_springs.yaml",
       with_overrides(kBase, {"cloth.springs={stretch: {ks: 100, kd: 0}}"})},
      {"base_set_twice.yaml", with_overrides(kBase, {"seed=3", "seed=4"})},
      {"base_set_bad.yaml",
       with_overrides(kBase, {"cloth..mass=1", "=3", "gravity=[0, 1", "solvers.first.dt=0.001"})},
      {"minimal_set_contact.yaml",
       with_overrides(kMinimal,
                      {"contact.stiffness=1234", "colliders=[{type: sphere, radius: 0.2}]"})},
  };
  for (const auto& [name, text] : scenes) write(out / "scene" / name, text);

  const std::vector<std::pair<std::string, std::string>> objs = {
      {"quad_uv.obj",
       "# a unit square as one quad\no square\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\n"
       "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 1 0\nf 1/1/1 2/2/1 3/3/1 4/4/1\n"},
      {"negative.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf -3 -2 -1\n"},
      {"square.obj",
       "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 0 0\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n"},
      {"normals.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nvn 0 1 0\nf 1//1 2//1 3//1\n"},
      {"uv_only.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n"},
      {"bad_number.obj", "v 0 0 0\nv 1 zero 0\n"},
      {"bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 4\n"},
      {"bad_uv.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1/7 2 3\n"},
      {"no_area.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"},
      {"fan.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nv 0 1 0\nv 0 -1 0\nf 1 2 3\nf 1 2 4\nf 1 2 5\n"},
      {"unused_vertex.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nv 5 5 5\nf 1 2 3\n"},
  };
  for (const auto& [name, text] : objs) write(out / "obj" / name, text);
  return 0;
}
