// A command line whose verb is none of drapelab's: the message names the word typed and the verb
// nearest to it, as a scene's misspelt key names the nearest key.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace drapelab::cli {

// The verb of `verbs` nearest to `word` by edit distance, or nothing when none is close enough to
// be a plausible typo.
std::optional<std::string> nearest_verb(const std::string& word,
                                        const std::vector<std::string>& verbs);

// When the first word of the command line that is not an option is not one of `app`'s verbs:
// "unknown command 'runn'; did you mean 'run'?", or the list of verbs when none is near.
std::optional<std::string> unknown_verb_message(int argc, const char* const* argv,
                                                const CLI::App& app);

}  // namespace drapelab::cli
