// Levenshtein distance, for "did you mean" suggestions (scene keys, command-line verbs).
#pragma once

#include <cstddef>
#include <string>

namespace drapelab::scene {

// The fewest single-character insertions, deletions and substitutions that turn a into b.
std::size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace drapelab::scene
