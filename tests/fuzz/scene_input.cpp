// The scene loader's fuzz entry (fuzz_inputs.hpp).
#include <array>

#include "drapelab/scene/scene_loader.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "fuzz_inputs.hpp"

namespace drapelab::fuzz {
namespace {

// A mesh cloth's `path` is relative to the scene file: the scenes stand in this folder, so that
// they can name its small OBJ files (tests/fuzz/meshes/).
const std::string kDisplayName = DRAPELAB_FUZZ_MESH_DIR "/fuzz.yaml";

// The loader reads whatever file a mesh scene names. Device and kernel files never end
// (/dev/zero) or block (/dev/stdin): such inputs are skipped rather than reported as hangs.
bool names_system_file(std::string_view data) {
  constexpr std::array<std::string_view, 3> kFolders{"/dev", "/proc", "/sys"};
  for (const auto folder : kFolders)
    if (data.find(folder) != std::string_view::npos) return true;
  return false;
}

std::string first_error(const scene::LoadResult& result) {
  return result.errors.empty() ? std::string("(no message)") : result.errors.front();
}

}  // namespace

SceneInput split_scene_input(std::string_view data) {
  SceneInput input;
  std::size_t end = data.find('\0');
  input.text = std::string(data.substr(0, end));
  while (end != std::string_view::npos && input.overrides.size() < kMaxOverrides) {
    const std::size_t start = end + 1;
    end = data.find('\0', start);
    input.overrides.emplace_back(
        data.substr(start, end == std::string_view::npos ? end : end - start));
  }
  return input;
}

std::optional<std::string> load_scene_input(std::string_view data) {
  if (names_system_file(data)) return std::nullopt;
  const SceneInput input = split_scene_input(data);
  const scene::LoadResult result =
      scene::load_scene_text(input.text, kDisplayName, input.overrides);
  if (!result.ok()) {
    if (result.errors.empty()) return "the scene did not load, yet there is no error message";
    return std::nullopt;
  }
  if (!result.errors.empty()) return "the scene loaded with an error: " + first_error(result);
  if (!result.model) return "the scene loaded without its cloth model";

  // resolved.yaml reproduces the run: it loads again, and resolves to itself.
  const std::string resolved = scene::resolved_scene_yaml(*result.scene);
  const scene::LoadResult again = scene::load_scene_text(resolved, kDisplayName);
  if (!again.ok()) return "the resolved scene does not load again: " + first_error(again);
  const std::string resolved_again = scene::resolved_scene_yaml(*again.scene);
  if (resolved_again != resolved)
    return "the resolved scene changes when loaded again:\n" + resolved + "\nbecomes\n" +
           resolved_again;
  return std::nullopt;
}

}  // namespace drapelab::fuzz
