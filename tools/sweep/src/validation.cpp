#include "drapelab/sweep/validation.hpp"

#include <set>

#include "drapelab/scene/scene_loader.hpp"

namespace drapelab::sweep {

namespace {

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

// The key path and its parents: "cloth.springs.bend.ks" -> "cloth", "cloth.springs", ...
std::vector<std::string> key_and_parents(const std::string& key) {
  std::vector<std::string> paths;
  for (std::size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', dot + 1))
    paths.push_back(key.substr(0, dot));
  paths.push_back(key);
  return paths;
}

}  // namespace

bool is_key_path_error(const std::string& error, const std::string& key, const std::string& value) {
  // The loader names the override an error comes from ("scene.yaml: --set key=value: ..."), then
  // the key path it is about. The wording below is the scene loader's (yaml_reader.cpp for unknown
  // keys, overrides.cpp for list indices and single values); test_sweep_cli checks that a misspelt
  // key is still recognised.
  const std::string origin = "--set " + key + "=" + value + ": ";
  const auto at = error.find(origin);
  if (at == std::string::npos) return false;
  const std::string about = error.substr(at + origin.size());
  static const char* const kPathPhrases[] = {"is not a known key", "is a list of",
                                             "is a single value"};
  for (const auto& path : key_and_parents(key)) {
    if (!starts_with(about, path + " ")) continue;
    const std::string phrase = about.substr(path.size() + 1);
    for (const char* known : kPathPhrases)
      if (starts_with(phrase, known)) return true;
  }
  return false;
}

SweepValidation validate_sweep(const std::string& scene_file,
                               const std::vector<std::string>& overrides, const SweepPlan& plan) {
  SweepValidation validation;
  const auto base = scene::load_scene_file(scene_file, overrides);
  if (!base.ok()) {
    validation.base_errors = base.errors;
    return validation;
  }
  validation.scene_name = base.scene->name;
  std::set<std::string> unknown;  // keys already reported
  std::vector<std::optional<std::string>> errors(plan.count());
  for (std::size_t index = 0; index < plan.count(); ++index) {
    std::vector<std::string> all = overrides;
    const auto varied = plan.overrides(index);
    all.insert(all.end(), varied.begin(), varied.end());
    const auto loaded = scene::load_scene_file(scene_file, all);
    if (loaded.ok()) continue;
    errors[index] = loaded.errors.front();
    const auto values = plan.values(index);
    for (std::size_t k = 0; k < plan.keys().size(); ++k) {
      const std::string& key = plan.keys()[k].key;
      if (unknown.count(key)) continue;
      for (const auto& error : loaded.errors) {
        if (!is_key_path_error(error, key, values[k])) continue;
        unknown.insert(key);
        validation.key_errors.push_back("--vary " + key + ": " + error);
        break;
      }
    }
  }
  if (validation.key_errors.empty()) validation.combination_errors = std::move(errors);
  return validation;
}

}  // namespace drapelab::sweep
