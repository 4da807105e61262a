// Located, typed reads from yaml-cpp nodes (see yaml_reader.hpp).
#include "yaml_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>

#include "drapelab/scene/number_format.hpp"
#include "text_checks.hpp"

namespace drapelab::scene {

bool Range::contains(double value) const {
  if (min && (min_inclusive ? value < *min : value <= *min)) return false;
  if (max && (max_inclusive ? value > *max : value >= *max)) return false;
  return true;
}

std::string Range::describe() const {
  std::string text;
  if (min) text += std::string(min_inclusive ? ">= " : "> ") + format_number(*min);
  if (max)
    text += std::string(min ? " and " : "") + (max_inclusive ? "<= " : "< ") + format_number(*max);
  return text.empty() ? "a finite number" : text;
}

std::string Range::violated(double value) const {
  Range side;
  if (min && (min_inclusive ? value < *min : value <= *min)) {
    side.min = min;
    side.min_inclusive = min_inclusive;
  } else {
    side.max = max;
    side.max_inclusive = max_inclusive;
  }
  return "must be " + side.describe();
}

std::string Range::whole_range() const {
  return min && max ? " (the range is " + describe() + ")" : "";
}

std::string join_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string describe_scalar(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a map";
  return quoted_value(node.Scalar());
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string nearest_word(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;  // plausible typo only
  for (const auto& candidate : candidates) {
    const std::size_t distance = edit_distance(word, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best;
}

SceneReader::SceneReader(std::string file_name, std::vector<std::string>* errors)
    : file_name_(std::move(file_name)), errors_(errors) {}

void SceneReader::set_override_origin(const std::string& path, const std::string& origin) {
  override_origins_[path] = origin;
}

void SceneReader::set_key_line(const std::string& path, int line) { key_lines_[path] = line; }

void record_key_lines(SceneReader& reader, const YAML::Node& map, const std::string& path) {
  if (!map.IsMap()) return;
  for (const auto& entry : map)
    if (!entry.first.Mark().is_null())
      reader.set_key_line(join_path(path, entry.first.Scalar()), entry.first.Mark().line);
}

void record_item_lines(SceneReader& reader, const YAML::Node& list, const std::string& path) {
  if (!list.IsSequence() || list.Mark().is_null()) return;
  int line = list.Mark().line;  // a block list's mark is its first item
  for (std::size_t k = 0; k < list.size(); ++k) {
    const YAML::Node item = list[k];
    if (!item.IsNull() && !item.Mark().is_null())
      line = item.Mark().line;
    else if (k > 0)
      ++line;
    reader.set_key_line(path + "." + std::to_string(k), line);
  }
}

std::string SceneReader::where(const YAML::Node& node, const std::string& path,
                               const YAML::Node& parent) const {
  // The longest overridden prefix of the path wins: "--set cloth.springs={...}" covers its keys.
  std::string origin;
  std::size_t origin_length = 0;
  for (const auto& [overridden, text] : override_origins_) {
    const bool covers =
        path == overridden ||
        (path.size() > overridden.size() && path.compare(0, overridden.size(), overridden) == 0 &&
         path[overridden.size()] == '.');
    if (covers && overridden.size() >= origin_length) {
      origin = text;
      origin_length = overridden.size();
    }
  }
  if (!origin.empty()) return file_name_ + ": " + shown_value(origin, kMaxShownOverrideBytes);
  int line = -1;
  const auto key_line = key_lines_.find(path);
  if (node.IsDefined() && !node.IsNull() && !node.Mark().is_null())
    line = node.Mark().line;
  else if (key_line != key_lines_.end())
    line = key_line->second;
  else if (node.IsDefined() && !node.Mark().is_null())
    line = node.Mark().line;
  else if (parent.IsDefined() && !parent.Mark().is_null())
    line = parent.Mark().line;
  // A map or list made by an override has no line of its own: use the line of the nearest key
  // above it that has one.
  for (std::string above = path; line < 0 && !above.empty();) {
    const std::size_t dot = above.rfind('.');
    above = dot == std::string::npos ? std::string() : above.substr(0, dot);
    if (const auto found = key_lines_.find(above); !above.empty() && found != key_lines_.end())
      line = found->second;
  }
  return line >= 0 ? file_name_ + ":" + std::to_string(line + 1) : file_name_;
}

namespace {

// A line longer than kMaxErrorBytes, cut to its first kMaxErrorBytes bytes and its length.
std::string shown_line(const std::string& line) {
  std::size_t end = kMaxErrorBytes;
  while (end > 0 && (static_cast<unsigned char>(line[end]) & 0xC0) == 0x80) --end;
  return line.substr(0, end) + "... (cut: " + std::to_string(line.size()) + " bytes)";
}

// A key path as messages show it: each key cut like a value (an unknown key may be any length).
std::string shown_path(const std::string& path) {
  std::string shown;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t dot = std::min(path.find('.', start), path.size());
    shown += (start ? "." : "") + shown_value(std::string_view(path).substr(start, dot - start));
    start = dot + 1;
  }
  return shown;
}

}  // namespace

void SceneReader::error(const YAML::Node& node, const std::string& path, const std::string& message,
                        const YAML::Node& parent) {
  if (errors_->size() >= kMaxListedErrors) {
    ++unlisted_errors_;
    return;
  }
  std::string line =
      where(node, path, parent) + ": " + (path.empty() ? "" : shown_path(path) + " ") + message;
  // The last guard of a bounded output: values are cut where they are named, and a line that is
  // still long (a path walked through many long keys) is cut as a whole.
  if (line.size() > kMaxErrorBytes) line = shown_line(line);
  errors_->push_back(std::move(line));
}

std::optional<double> SceneReader::number(const YAML::Node& node, const std::string& path,
                                          const Range& range) {
  if (!node.IsScalar()) {
    error(node, path, "must be a number (" + range.describe() + "), got " + describe_scalar(node));
    return std::nullopt;
  }
  const std::string& text = node.Scalar();
  double value = 0.0;
  const char* begin = text.data() + (!text.empty() && text[0] == '+' ? 1 : 0);
  const auto [end, code] = std::from_chars(begin, text.data() + text.size(), value);
  if (code != std::errc() || end != text.data() + text.size()) {
    const bool too_far = code == std::errc::result_out_of_range;  // 1e400, 1e-400
    error(node, path,
          "must be a number (" + range.describe() + "), got " + quoted_value(text) +
              (too_far ? ", beyond what a double holds" : ""));
    return std::nullopt;
  }
  if (!std::isfinite(value)) {
    error(node, path, "must be finite, got " + quoted_value(text));
    return std::nullopt;
  }
  if (!range.contains(value)) {
    error(node, path, range.violated(value) + ", got " + shown_value(text) + range.whole_range());
    return std::nullopt;
  }
  return value;
}

std::optional<long long> SceneReader::integer(const YAML::Node& node, const std::string& path,
                                              const Range& range) {
  const std::string expected = "a whole number (" + range.describe() + ")";
  if (!node.IsScalar()) {
    error(node, path, "must be " + expected + ", got " + describe_scalar(node));
    return std::nullopt;
  }
  const std::string& text = node.Scalar();
  long long value = 0;
  const auto [end, code] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (code != std::errc() || end != text.data() + text.size()) {
    error(node, path, "must be " + expected + ", got " + quoted_value(text));
    return std::nullopt;
  }
  if (!range.contains(static_cast<double>(value))) {
    error(node, path,
          range.violated(static_cast<double>(value)) + ", got " + shown_value(text) +
              range.whole_range());
    return std::nullopt;
  }
  return value;
}

std::optional<bool> SceneReader::boolean(const YAML::Node& node, const std::string& path) {
  if (node.IsScalar()) {
    if (node.Scalar() == "true") return true;
    if (node.Scalar() == "false") return false;
  }
  error(node, path, "must be true or false, got " + describe_scalar(node));
  return std::nullopt;
}

std::optional<std::string> SceneReader::text(const YAML::Node& node, const std::string& path) {
  if (!node.IsScalar()) {
    error(node, path, "must be text, got " + describe_scalar(node));
    return std::nullopt;
  }
  return node.Scalar();
}

std::optional<std::string> SceneReader::choice(const YAML::Node& node, const std::string& path,
                                               const std::vector<std::string>& choices) {
  std::string options;
  for (const auto& c : choices) options += (options.empty() ? "" : " | ") + c;
  if (!node.IsScalar()) {
    error(node, path, "must be one of " + options + ", got " + describe_scalar(node));
    return std::nullopt;
  }
  const std::string& value = node.Scalar();
  if (std::find(choices.begin(), choices.end(), value) != choices.end()) return value;
  const std::string nearest = nearest_word(value, choices);
  error(node, path,
        "must be one of " + options + ", got " + quoted_value(value) +
            (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)"));
  return std::nullopt;
}

std::optional<Eigen::VectorXd> SceneReader::numbers(const YAML::Node& node, const std::string& path,
                                                    int size, const Range& range) {
  if (!node.IsSequence() || node.size() != static_cast<std::size_t>(size)) {
    error(node, path,
          "must be a list of " + std::to_string(size) + " numbers, got " +
              (node.IsSequence() ? "a list of " + std::to_string(node.size())
                                 : describe_scalar(node)));
    return std::nullopt;
  }
  Eigen::VectorXd values(size);
  bool ok = true;
  for (int k = 0; k < size; ++k) {
    const auto value = number(node[k], path + "." + std::to_string(k), range);
    if (value) values[k] = *value;
    ok = ok && value.has_value();
  }
  if (!ok) return std::nullopt;
  return values;
}

std::optional<std::vector<long long>> SceneReader::integers(const YAML::Node& node,
                                                            const std::string& path, int size,
                                                            const Range& range) {
  if (!node.IsSequence() || node.size() != static_cast<std::size_t>(size)) {
    error(node, path,
          "must be a list of " + std::to_string(size) + " whole numbers, got " +
              (node.IsSequence() ? "a list of " + std::to_string(node.size())
                                 : describe_scalar(node)));
    return std::nullopt;
  }
  std::vector<long long> values;
  for (int k = 0; k < size; ++k) {
    const auto value = integer(node[k], path + "." + std::to_string(k), range);
    if (!value) return std::nullopt;
    values.push_back(*value);
  }
  return values;
}

MapReader::MapReader(SceneReader& reader, const YAML::Node& node, std::string path,
                     const std::vector<std::string>& allowed,
                     const std::map<std::string, std::string>& future)
    : reader_(reader), node_(node), path_(std::move(path)) {
  if (!node.IsMap()) {
    reader.error(node, path_, "must be a map of keys, got " + describe_scalar(node));
    return;
  }
  valid_ = true;
  record_key_lines(reader, node, path_);
  std::set<std::string> seen;
  for (const auto& entry : node) {
    const std::string key = entry.first.Scalar();
    const std::string key_path = join_path(path_, key);
    if (!seen.insert(key).second) {
      reader.error(entry.first, key_path, "appears twice in the same map; keep one");
      continue;
    }
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    if (const auto later = future.find(key); later != future.end()) {
      reader.error(entry.first, key_path, later->second);
      continue;
    }
    const std::string nearest = nearest_word(key, allowed);
    std::string valid_keys;
    for (const auto& a : allowed) valid_keys += (valid_keys.empty() ? "" : ", ") + a;
    reader.error(entry.first, key_path,
                 "is not a known key" +
                     (nearest.empty() ? "; valid keys here: " + valid_keys
                                      : "; did you mean " + join_path(path_, nearest) + "?"));
  }
}

bool MapReader::has(const std::string& key) const {
  const YAML::Node& constant = node_;  // the non-const operator[] would insert the key
  return valid_ && constant[key].IsDefined();
}

YAML::Node MapReader::get(const std::string& key) const {
  if (!valid_) return YAML::Node(YAML::NodeType::Undefined);
  const YAML::Node& constant = node_;
  return constant[key];
}

std::string MapReader::path_of(const std::string& key) const { return join_path(path_, key); }

void MapReader::missing(const std::string& key, const std::string& expected) {
  reader_.error(YAML::Node(YAML::NodeType::Undefined), path_of(key), "is required: " + expected,
                node_);
}

std::optional<double> MapReader::number(const std::string& key, const Range& range,
                                        std::optional<double> fallback) {
  if (!has(key)) return fallback;
  return reader_.number(get(key), path_of(key), range);
}

std::optional<long long> MapReader::integer(const std::string& key, const Range& range,
                                            std::optional<long long> fallback) {
  if (!has(key)) return fallback;
  return reader_.integer(get(key), path_of(key), range);
}

std::optional<bool> MapReader::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  return reader_.boolean(get(key), path_of(key));
}

std::optional<std::string> MapReader::text(const std::string& key,
                                           std::optional<std::string> fallback) {
  if (!has(key)) return fallback;
  return reader_.text(get(key), path_of(key));
}

std::optional<std::string> MapReader::choice(const std::string& key,
                                             const std::vector<std::string>& choices,
                                             std::optional<std::string> fallback) {
  if (!has(key)) return fallback;
  return reader_.choice(get(key), path_of(key), choices);
}

std::optional<Eigen::VectorXd> MapReader::numbers(const std::string& key, int size,
                                                  const Range& range,
                                                  std::optional<Eigen::VectorXd> fallback) {
  if (!has(key)) return fallback;
  return reader_.numbers(get(key), path_of(key), size, range);
}

}  // namespace drapelab::scene
