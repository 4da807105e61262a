// Checks on raw text before it is parsed or used: names that become file names, and UTF-8 (every
// string of a scene ends up in summary.json, whose writer refuses invalid UTF-8).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace drapelab::scene {

// Why `name` is not a valid name ([a-z0-9_-], 1 to kMaxNameLength characters), or nothing. A plain
// loop: std::regex recurses once per character and overflows the stack on long names.
std::optional<std::string> name_problem(std::string_view name);

struct TextProblem {
  std::size_t offset = 0;  // byte offset of the first bad byte
  int line = 1;            // its 1-based line
  std::string what;        // "byte 0xff is not valid UTF-8", ...
};

// The first byte that makes `text` something other than UTF-8 text of YAML's printable characters
// (tab, line feed, carriage return and everything from U+0020 up, but DEL, the C1 controls other
// than U+0085, surrogates, U+FFFE and U+FFFF), or nothing.
std::optional<TextProblem> text_problem(std::string_view text);

}  // namespace drapelab::scene
