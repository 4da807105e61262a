#include "scene_text_helpers.hpp"

#include <sstream>
#include <stdexcept>

namespace drapelab::testing {

using scene::LoadResult;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& line : lines) text += line + "\n";
  return text;
}

// Replaces 1-based line `number` of `text` with `replacement` (which may hold several lines).
std::string with_line(const std::string& text, int number, const std::string& replacement) {
  auto lines = lines_of(text);
  if (number < 1 || number > static_cast<int>(lines.size())) throw std::out_of_range("no such line");
  lines[number - 1] = replacement;
  return join_lines(lines);
}

// Removes lines first..last (1-based, inclusive).
std::string without_lines(const std::string& text, int first, int last) {
  auto lines = lines_of(text);
  lines.erase(lines.begin() + (first - 1), lines.begin() + last);
  return join_lines(lines);
}

// Inserts `inserted` (one or more lines, no final newline needed) after 1-based line `number`.
std::string insert_after(const std::string& text, int number, const std::string& inserted) {
  auto lines = lines_of(text);
  auto extra = lines_of(inserted);
  lines.insert(lines.begin() + number, extra.begin(), extra.end());
  return join_lines(lines);
}

std::string all_errors(const LoadResult& result) {
  std::string text;
  for (const auto& e : result.errors) text += "\n  " + e;
  return text.empty() ? " (no errors)" : text;
}

// The load failed and one single error message starts with `location` (e.g. "drape_test.yaml:18:"
// or "drape_test.yaml: --set a.b=1:") and contains every fragment (key path, expected wording...).
::testing::AssertionResult HasError(const LoadResult& result, const std::string& location,
                                    const std::vector<std::string>& fragments) {
  if (result.ok()) return ::testing::AssertionFailure() << "the scene loaded, but an error was expected";
  for (const auto& error : result.errors) {
    if (error.rfind(location, 0) != 0) continue;
    bool all = true;
    for (const auto& fragment : fragments) all = all && error.find(fragment) != std::string::npos;
    if (all) return ::testing::AssertionSuccess();
  }
  std::string wanted;
  for (const auto& f : fragments) wanted += " [" + f + "]";
  return ::testing::AssertionFailure() << "no error starts with [" << location << "] and contains" << wanted
                                       << "; errors were:" << all_errors(result);
}

std::string at_line(const std::string& file, int line) { return file + ":" + std::to_string(line) + ":"; }

std::string at_override(const std::string& file, const std::string& override_text) {
  return file + ": --set " + override_text + ":";
}

}  // namespace drapelab::testing
