// Checks on raw text before it is parsed or used: names that become file names, UTF-8 (every
// string of a scene ends up in summary.json, whose writer refuses invalid UTF-8), control
// characters in paths; and how a message shows a value of any length.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

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

// Why `path` (a file path a scene gives) cannot name a file as written, or nothing: a NUL byte
// would end it early (yaml-cpp keeps "good.obj\0x" whole, the operating system reads "good.obj"),
// and other control characters (below U+0020, DEL) are refused with it, since no file name a
// person types holds them.
std::optional<std::string> path_problem(std::string_view path);

// Values longer than this many bytes are cut in messages (shown_value); a --set text, which is
// the error's location, longer than the second.
inline constexpr std::size_t kMaxShownValueBytes = 64;
inline constexpr std::size_t kMaxShownOverrideBytes = 200;

// A value as a message shows it: whole when at most `max_bytes` long; else its first max_bytes - 24
// bytes (on a UTF-8 character boundary), "..." and its length, so that an error about a
// 100,000-digit number is one short line:
// "1234567890123456789012345678901234567890... (100000 characters)".
std::string shown_value(std::string_view text, std::size_t max_bytes = kMaxShownValueBytes);
// The same in single quotes: 'text', or '1234...' (100000 characters).
std::string quoted_value(std::string_view text);
// Names as a message lists them: "a, b, c", the first eight only, then "and N more".
std::string listed_names(const std::vector<std::string>& names);

}  // namespace drapelab::scene
