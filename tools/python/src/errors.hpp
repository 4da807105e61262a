// The module's exceptions.
#pragma once

#include <string>
#include <vector>

namespace drapelab::python {

// Raises drapelab.SceneError: the message is every loader error on its own line, each naming the
// file, line, key and what was expected; the exception's `errors` attribute lists them.
[[noreturn]] void raise_scene_error(const std::vector<std::string>& errors);

// Raises drapelab.RunError with `message`.
[[noreturn]] void raise_run_error(const std::string& message);

}  // namespace drapelab::python
