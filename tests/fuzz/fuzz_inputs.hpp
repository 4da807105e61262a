// The fuzz targets' entry points, shared by the libFuzzer executables (fuzz_scene_loader.cpp,
// fuzz_obj_reader.cpp) and the replay test (test_fuzz_replay.cpp), so that every corpus and crash
// input runs through the same code in the regular build as under libFuzzer.
//
// Each entry feeds one input to the code under test and checks what must hold whatever the input:
// no exception escapes, a failure carries a message, a success is consistent. It returns the broken
// property, or nothing. A crash or a sanitizer report is a finding as well.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace drapelab::fuzz {

// A scene input: the scene's YAML text up to the first NUL byte, then --set overrides separated by
// NUL bytes ("key.path=value"), so that one input exercises both the file and the override path.
struct SceneInput {
  std::string text;
  std::vector<std::string> overrides;
};

// At most this many overrides are taken; later pieces are ignored.
inline constexpr std::size_t kMaxOverrides = 8;

SceneInput split_scene_input(std::string_view data);

// Loads the scene with its overrides (load_scene_text). A scene that loads must carry its cloth
// model, and its resolved YAML must load again and resolve to the same text.
std::optional<std::string> load_scene_input(std::string_view data);

// Reads the input as an OBJ file (read_obj). A mesh read must have its indices in range; one that
// passes mesh_problem must build a cloth.
std::optional<std::string> read_obj_input(std::string_view data);

}  // namespace drapelab::fuzz
