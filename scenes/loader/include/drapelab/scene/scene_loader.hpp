// Loading and validating a scene file. Every problem is reported, each naming the file and line (or
// the --set override), the key path, and what was expected; nothing runs on a scene with an error.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/scene/scene.hpp"

namespace drapelab::scene {

// A cloth that starts inside or through a collider (docs/scene-reference.md, "Where the cloth
// starts"): an error, or a warning when the user means it (drapelab run --allow-start-inside) or
// the scene was already run (a run folder's resolved.yaml).
enum class StartInside { error, warning };

struct LoadResult {
  std::optional<Scene> scene;       // set only when there is no error
  std::vector<std::string> errors;  // "scene.yaml:14: cloth.springs.stretch.ks must be > 0, got -3"
  std::vector<std::string> notes;   // things the loader did on request (dt rounded, ...)
  // Located problems the scene may still run with (a start inside a collider, allowed).
  std::vector<std::string> warnings;
  // The scene's cloth, built once while loading (the automatic steps measure it); pass it on to
  // build_scene_setup so that a run builds it only once. Set whenever `scene` is.
  std::shared_ptr<const ClothModel> model;
  bool ok() const { return scene.has_value(); }
};

// `overrides` are "key.path=value" strings (--set); list items by index: "solvers.0.dt=1e-4". The
// value is YAML ("[0, -1.62, 0]" is a list) and is validated like the file.
LoadResult load_scene_file(const std::filesystem::path& file,
                           const std::vector<std::string>& overrides = {},
                           StartInside start_inside = StartInside::error);

// Same, from text; `display_name` stands for the file in messages.
LoadResult load_scene_text(const std::string& text, const std::string& display_name,
                           const std::vector<std::string>& overrides = {},
                           StartInside start_inside = StartInside::error);

}  // namespace drapelab::scene
