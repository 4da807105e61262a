// Names, UTF-8, paths and shown values (text_checks.hpp).
#include "text_checks.hpp"

#include <algorithm>
#include <cstdio>

#include "value_ranges.hpp"

namespace drapelab::scene {
namespace {

std::string hex_byte(unsigned char byte) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%02x", byte);
  return text;
}

std::string code_point(char32_t c) {
  char text[16];
  std::snprintf(text, sizeof text, "U+%04X", static_cast<unsigned>(c));
  return text;
}

// YAML 1.2's printable set, for a decoded code point.
bool printable(char32_t c) {
  if (c == 0x09 || c == 0x0A || c == 0x0D || c == 0x85) return true;
  if (c < 0x20 || c == 0x7F || (c >= 0x80 && c < 0xA0)) return false;
  if (c >= 0xD800 && c <= 0xDFFF) return false;
  return c != 0xFFFE && c != 0xFFFF && c <= 0x10FFFF;
}

}  // namespace

std::optional<std::string> name_problem(std::string_view name) {
  if (name.empty())
    return "must use only a-z, 0-9, _ and -, got '' (at least 1 character, at most " +
           std::to_string(kMaxNameLength) + ")";
  if (name.size() > kMaxNameLength)
    return "must be at most " + std::to_string(kMaxNameLength) +
           " characters (it names output files), got " + std::to_string(name.size());
  for (const char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-'))
      return "must use only a-z, 0-9, _ and -, got '" + std::string(name) + "'";
  return std::nullopt;
}

std::optional<TextProblem> text_problem(std::string_view text) {
  int line = 1;
  std::size_t k = 0;
  while (k < text.size()) {
    const auto lead = static_cast<unsigned char>(text[k]);
    const std::size_t start = k;
    auto problem = [&](const std::string& what) { return TextProblem{start, line, what}; };
    std::size_t length = 1;
    char32_t c = lead;
    if (lead >= 0x80) {
      if (lead >= 0xC2 && lead <= 0xDF) {
        length = 2;
        c = lead & 0x1F;
      } else if (lead >= 0xE0 && lead <= 0xEF) {
        length = 3;
        c = lead & 0x0F;
      } else if (lead >= 0xF0 && lead <= 0xF4) {
        length = 4;
        c = lead & 0x07;
      } else {
        return problem("byte " + hex_byte(lead) + " is not valid UTF-8");
      }
      if (start + length > text.size())
        return problem("the text ends inside a UTF-8 character (byte " + hex_byte(lead) + ")");
      for (std::size_t n = 1; n < length; ++n) {
        const auto next = static_cast<unsigned char>(text[start + n]);
        if ((next & 0xC0) != 0x80)
          return problem("byte " + hex_byte(lead) + " followed by " + hex_byte(next) +
                         " is not valid UTF-8");
        c = (c << 6) | (next & 0x3F);
      }
      // Overlong forms and code points past U+10FFFF are not UTF-8.
      const char32_t smallest = length == 2 ? 0x80 : length == 3 ? 0x800 : 0x10000;
      if (c < smallest || c > 0x10FFFF)
        return problem("byte " + hex_byte(lead) + " starts an invalid UTF-8 sequence");
    }
    if (!printable(c))
      return problem(c < 0x80 ? "control character " + hex_byte(static_cast<unsigned char>(c)) +
                                    " is not allowed in YAML text"
                              : "the character " + code_point(c) + " is not allowed in YAML text");
    if (c == '\n') ++line;
    k = start + length;
  }
  return std::nullopt;
}

std::optional<std::string> path_problem(std::string_view path) {
  for (std::size_t k = 0; k < path.size(); ++k) {
    const auto byte = static_cast<unsigned char>(path[k]);
    if (byte == 0)
      return "holds a NUL byte (\\0) at character " + std::to_string(k + 1) +
             ", which would end the file name there; give the path without it";
    if (byte < 0x20 || byte == 0x7F)
      return "holds the control character " + hex_byte(byte) + " at character " +
             std::to_string(k + 1) + "; a file path must be printable text";
  }
  return std::nullopt;
}

namespace {

constexpr std::size_t kCutMarkBytes = 24;  // about the length of "... (100000 characters)"
constexpr std::size_t kListedNames = 8;    // names listed before "and N more"

// Characters of UTF-8 text (bytes that do not continue a character).
std::size_t character_count(std::string_view text) {
  std::size_t count = 0;
  for (const char c : text) count += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return count;
}

// The first `bytes` bytes of `text`, shortened to end on a character boundary.
std::string_view utf8_prefix(std::string_view text, std::size_t bytes) {
  std::size_t end = std::min(bytes, text.size());
  while (end > 0 && end < text.size() && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80)
    --end;
  return text.substr(0, end);
}

}  // namespace

std::string shown_value(std::string_view text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) return std::string(text);
  return std::string(utf8_prefix(text, max_bytes - kCutMarkBytes)) + "... (" +
         std::to_string(character_count(text)) + " characters)";
}

std::string quoted_value(std::string_view text) {
  if (text.size() <= kMaxShownValueBytes) return "'" + std::string(text) + "'";
  return "'" + std::string(utf8_prefix(text, kMaxShownValueBytes - kCutMarkBytes)) + "...' (" +
         std::to_string(character_count(text)) + " characters)";
}

std::string listed_names(const std::vector<std::string>& names) {
  std::string text;
  for (std::size_t k = 0; k < names.size() && k < kListedNames; ++k)
    text += (k ? ", " : "") + shown_value(names[k]);
  if (names.size() > kListedNames)
    text += " and " + std::to_string(names.size() - kListedNames) + " more";
  return text;
}

}  // namespace drapelab::scene
