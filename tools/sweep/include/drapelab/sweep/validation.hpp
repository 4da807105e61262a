// Checking a sweep before anything runs: every combination is loaded in-process with its overrides,
// as `drapelab validate` does, so a misspelt key stops the sweep at once (exit 2) while a value
// that is invalid for one combination only makes that combination a bad_input row.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "drapelab/sweep/plan.hpp"

namespace drapelab::sweep {

// Whether a scene loader error says that the key path of the override "key=value" does not exist
// in the scene: the key, or one of its parents, is not a known key; a list index is out of range;
// or a parent is a single value. Errors about the value itself (out of range, wrong type, unknown
// keys *inside* a map given as the value) are not key errors.
bool is_key_path_error(const std::string& error, const std::string& key, const std::string& value);

struct SweepValidation {
  std::vector<std::string> base_errors;  // the scene with --set alone does not load: exit 2
  std::vector<std::string> key_errors;  // a varied key does not exist: exit 2 (one message per key)
  // Per combination: its first loader error, or nothing when it loads. Empty when one of the
  // lists above is not.
  std::vector<std::optional<std::string>> combination_errors;
  std::string scene_name;  // of the scene with --set alone

  bool ok() const { return base_errors.empty() && key_errors.empty(); }
};

// Loads the scene with `overrides` (--set), then once per combination with the combination's
// overrides after them.
SweepValidation validate_sweep(const std::string& scene_file,
                               const std::vector<std::string>& overrides, const SweepPlan& plan);

}  // namespace drapelab::sweep
