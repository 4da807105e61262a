// The table's lookups, its defaults parsed from their YAML text, and MapReader's reads by row
// (scene_keys.hpp).
#include "scene_keys.hpp"

#include <charconv>
#include <stdexcept>

namespace drapelab::scene {
namespace {

// The parts of `text` between `separator`s.
std::vector<std::string> split(std::string_view text, char separator) {
  std::vector<std::string> parts;
  if (text.empty()) return parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(separator, start);
    parts.emplace_back(text.substr(start, end == std::string_view::npos ? end : end - start));
    if (end == std::string_view::npos) return parts;
    start = end + 1;
  }
}

const std::string_view& value_text(const SceneKey& key) {
  if (key.given != Given::value)
    throw std::logic_error("scene key " + std::string(key.path) + " has no default value");
  return key.fallback;
}

double parse_number(const SceneKey& key, std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, code] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (code != std::errc() || end != text.data() + text.size())
    throw std::logic_error("scene key " + std::string(key.path) + ": default '" +
                           std::string(key.fallback) + "' is not a number");
  return value;
}

}  // namespace

std::vector<const SceneKey*> scene_keys() {
  std::vector<const SceneKey*> rows;
  for (const auto& group : kSceneKeyGroups)
    for (const SceneKey& row : group) rows.push_back(&row);
  return rows;
}

bool key_applies(const SceneKey& key, std::string_view when) {
  if (key.when.empty() || when.empty()) return true;
  for (const std::string& one : split(key.when, '|'))
    if (one == when) return true;
  return false;
}

std::vector<const SceneKey*> keys_under(std::string_view parent, std::string_view when) {
  std::vector<const SceneKey*> rows;
  for (const SceneKey* row : scene_keys())
    if (row->parent() == parent && key_applies(*row, when)) rows.push_back(row);
  return rows;
}

std::vector<std::string> key_names(std::string_view parent, std::string_view when) {
  std::vector<std::string> names;
  for (const SceneKey* row : keys_under(parent, when)) names.emplace_back(row->name());
  return names;
}

std::vector<std::string> key_choices(const SceneKey& key) { return split(key.choices, '|'); }

double default_number(const SceneKey& key) { return parse_number(key, value_text(key)); }

long long default_integer(const SceneKey& key) {
  const std::string_view text = value_text(key);
  long long value = 0;
  const auto [end, code] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (code != std::errc() || end != text.data() + text.size())
    throw std::logic_error("scene key " + std::string(key.path) + ": default '" +
                           std::string(text) + "' is not a whole number");
  return value;
}

bool default_boolean(const SceneKey& key) { return value_text(key) == "true"; }

std::string default_choice(const SceneKey& key) { return std::string(value_text(key)); }

Eigen::VectorXd default_numbers(const SceneKey& key) {
  std::string_view text = value_text(key);
  if (text.size() < 2 || text.front() != '[' || text.back() != ']')
    throw std::logic_error("scene key " + std::string(key.path) + ": default is not a list");
  const std::vector<std::string> parts = split(text.substr(1, text.size() - 2), ',');
  Eigen::VectorXd values(static_cast<Eigen::Index>(parts.size()));
  for (std::size_t k = 0; k < parts.size(); ++k)
    values[static_cast<Eigen::Index>(k)] = parse_number(key, parts[k]);
  return values;
}

// MapReader's reads by row (yaml_reader.hpp): the row's name, range, choices and default.

std::optional<double> MapReader::number(const SceneKey& key) {
  return number(key, key.given == Given::value ? std::optional(default_number(key)) : std::nullopt);
}

std::optional<double> MapReader::number(const SceneKey& key, std::optional<double> fallback) {
  return number(std::string(key.name()), key.range, fallback);
}

std::optional<long long> MapReader::integer(const SceneKey& key) {
  return integer(std::string(key.name()), key.range,
                 key.given == Given::value ? std::optional(default_integer(key)) : std::nullopt);
}

std::optional<bool> MapReader::boolean(const SceneKey& key) {
  return boolean(std::string(key.name()), default_boolean(key));
}

std::optional<std::string> MapReader::choice(const SceneKey& key) {
  return choice(key, key.given == Given::value ? std::optional(default_choice(key)) : std::nullopt);
}

std::optional<std::string> MapReader::choice(const SceneKey& key,
                                             std::optional<std::string> fallback) {
  return choice(std::string(key.name()), key_choices(key), std::move(fallback));
}

std::optional<Eigen::VectorXd> MapReader::numbers(const SceneKey& key) {
  return numbers(key,
                 key.given == Given::value ? std::optional(default_numbers(key)) : std::nullopt);
}

std::optional<Eigen::VectorXd> MapReader::numbers(const SceneKey& key,
                                                  std::optional<Eigen::VectorXd> fallback) {
  return numbers(std::string(key.name()), key.size, key.range, std::move(fallback));
}

}  // namespace drapelab::scene
