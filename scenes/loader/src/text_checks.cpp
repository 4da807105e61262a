// Names and UTF-8 (text_checks.hpp).
#include "text_checks.hpp"

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

}  // namespace drapelab::scene
