// Typed, located reads from a yaml-cpp tree. Every read checks shape and range and, on failure,
// adds an error naming the file:line (or the --set override), the key path and what was expected.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/scene/edit_distance.hpp"

namespace drapelab::scene {

struct SceneKey;  // scene_key.hpp

// The most errors a load lists; the rest are counted in one line after them.
inline constexpr std::size_t kMaxListedErrors = 20;
// The longest error line, in bytes (values in it are cut shorter still: text_checks.hpp).
inline constexpr std::size_t kMaxErrorBytes = 1000;

// Allowed interval of a number, with the words used in messages.
struct Range {
  std::optional<double> min;
  bool min_inclusive = true;
  std::optional<double> max;
  bool max_inclusive = true;

  static constexpr Range any() { return {}; }
  static constexpr Range positive() { return {0.0, false, std::nullopt, true}; }
  static constexpr Range non_negative() { return {0.0, true, std::nullopt, true}; }
  bool contains(double value) const;
  std::string describe() const;  // "> 0", ">= 0 and <= 1", ...
  // For a value outside the range: the bound it breaks ("must be <= 10000"), and the whole range
  // for messages (" (the range is > 0 and <= 10000)", empty for a one-sided range).
  std::string violated(double value) const;
  std::string whole_range() const;
};

class SceneReader {
 public:
  SceneReader(std::string file_name, std::vector<std::string>* errors);

  // Records that `path` (and everything below it) came from "--set path=value".
  void set_override_origin(const std::string& path, const std::string& origin);
  // Records the line (0-based) of the key or list item at `path`. yaml-cpp places an empty value at
  // the next token, so errors about empty values use this line instead.
  void set_key_line(const std::string& path, int line);

  // "scene.yaml:14" or "scene.yaml: --set a.b=3" for an overridden key.
  std::string where(const YAML::Node& node, const std::string& path,
                    const YAML::Node& parent) const;
  // Records an error; past kMaxListedErrors it is only counted (unlisted_errors), so that a scene
  // with 100,000 unknown keys gives 20 lines and a count, not megabytes of text.
  void error(const YAML::Node& node, const std::string& path, const std::string& message,
             const YAML::Node& parent = YAML::Node());
  // Every error reported, the listed and the unlisted.
  std::size_t error_count() const { return errors_->size() + unlisted_errors_; }
  std::size_t unlisted_errors() const { return unlisted_errors_; }
  const std::string& file_name() const { return file_name_; }

  // Scalars. `node` must be defined; these report and return nullopt when it is not the right
  // shape.
  std::optional<double> number(const YAML::Node& node, const std::string& path, const Range& range);
  std::optional<long long> integer(const YAML::Node& node, const std::string& path,
                                   const Range& range);
  std::optional<bool> boolean(const YAML::Node& node, const std::string& path);
  std::optional<std::string> text(const YAML::Node& node, const std::string& path);
  // A string that must be one of `choices`; suggests the nearest on a miss.
  std::optional<std::string> choice(const YAML::Node& node, const std::string& path,
                                    const std::vector<std::string>& choices);
  // A list of exactly `size` numbers, each in `range`.
  std::optional<Eigen::VectorXd> numbers(const YAML::Node& node, const std::string& path, int size,
                                         const Range& range);
  std::optional<std::vector<long long>> integers(const YAML::Node& node, const std::string& path,
                                                 int size, const Range& range);

 private:
  std::string file_name_;
  std::vector<std::string>* errors_;
  std::map<std::string, std::string> override_origins_;  // key path -> "--set ..."
  std::map<std::string, int> key_lines_;                 // key path -> 0-based line of its key
  std::size_t unlisted_errors_ = 0;                      // errors past kMaxListedErrors
};

// A YAML map read key by key. On construction it reports duplicate keys and keys outside `allowed`
// (with the nearest allowed key); `future` keys get a message saying they are not available yet.
class MapReader {
 public:
  MapReader(SceneReader& reader, const YAML::Node& node, std::string path,
            const std::vector<std::string>& allowed,
            const std::map<std::string, std::string>& future = {});

  bool valid() const { return valid_; }  // false when the node is not a map (already reported)
  bool has(const std::string& key) const;
  YAML::Node get(const std::string& key) const;  // undefined node when absent
  std::string path_of(const std::string& key) const;
  const YAML::Node& node() const { return node_; }
  void missing(const std::string& key, const std::string& expected);  // reports a required key

  std::optional<double> number(const std::string& key, const Range& range,
                               std::optional<double> fallback);
  std::optional<long long> integer(const std::string& key, const Range& range,
                                   std::optional<long long> fallback);
  std::optional<bool> boolean(const std::string& key, bool fallback);
  std::optional<std::string> text(const std::string& key, std::optional<std::string> fallback);
  std::optional<std::string> choice(const std::string& key, const std::vector<std::string>& choices,
                                    std::optional<std::string> fallback);
  std::optional<Eigen::VectorXd> numbers(const std::string& key, int size, const Range& range,
                                         std::optional<Eigen::VectorXd> fallback);

  // The same by a row of the key table (scene_key.hpp): its name, range, size and choices. The
  // first form falls back on the row's default (none unless Given::value); the second on the one
  // given, for a default computed from other keys or a preset (scene_keys.cpp).
  std::optional<double> number(const SceneKey& key);
  std::optional<double> number(const SceneKey& key, std::optional<double> fallback);
  std::optional<long long> integer(const SceneKey& key);
  std::optional<bool> boolean(const SceneKey& key);
  std::optional<std::string> choice(const SceneKey& key);
  std::optional<std::string> choice(const SceneKey& key, std::optional<std::string> fallback);
  std::optional<Eigen::VectorXd> numbers(const SceneKey& key);
  std::optional<Eigen::VectorXd> numbers(const SceneKey& key,
                                         std::optional<Eigen::VectorXd> fallback);

 private:
  SceneReader& reader_;
  YAML::Node node_;
  std::string path_;
  bool valid_ = false;
};

// The candidate nearest to `word`, or empty when none is close enough to be a plausible typo.
std::string nearest_word(const std::string& word, const std::vector<std::string>& candidates);

std::string join_path(const std::string& parent, const std::string& key);
std::string describe_scalar(const YAML::Node& node);  // "-3", "a list", "a map", ...
// Records the line of every item of a list for empty items (see SceneReader::set_key_line): an item
// with a value starts on its own mark; an empty one on the line after the item before it.
void record_item_lines(SceneReader& reader, const YAML::Node& list, const std::string& path);
// Records the line of every key of a map (MapReader does this itself when it is built).
void record_key_lines(SceneReader& reader, const YAML::Node& map, const std::string& path);

}  // namespace drapelab::scene
