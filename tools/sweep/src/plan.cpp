#include "drapelab/sweep/plan.hpp"

#include <algorithm>
#include <cctype>
#include <limits>

namespace drapelab::sweep {

namespace {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

bool file_name_character(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-' ||
         c == '=';
}

}  // namespace

std::optional<std::vector<std::string>> split_values(const std::string& text, std::string* error) {
  std::vector<std::string> values;
  std::string current;
  int depth = 0;      // open [ and { outside quotes
  char quote = '\0';  // the open quote character, or 0
  auto finish = [&]() -> bool {
    std::string value = trimmed(current);
    current.clear();
    if (value.empty()) {
      *error = "an empty value in '" + text + "' (two commas in a row, or a comma at an end)";
      return false;
    }
    values.push_back(std::move(value));
    return true;
  };
  for (const char c : text) {
    if (quote != '\0') {
      // YAML escapes a single quote inside single quotes by doubling it: the toggle handles that.
      if (c == quote) quote = '\0';
    } else if (c == '\'' || c == '"') {
      quote = c;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      if (--depth < 0) {
        *error = "'" + text + "' closes a bracket that was never opened";
        return std::nullopt;
      }
    } else if (c == ',' && depth == 0) {
      if (!finish()) return std::nullopt;
      continue;
    }
    current += c;
  }
  if (quote != '\0' || depth != 0) {
    *error = "'" + text + "' leaves a " + (quote != '\0' ? "quote" : "bracket") +
             " open; a value holding commas is a YAML flow list in brackets, e.g. [5,5],[7,7]";
    return std::nullopt;
  }
  if (!finish()) return std::nullopt;
  return values;
}

std::optional<VariedKey> parse_vary(const std::string& text, std::string* error) {
  const auto equals = text.find('=');
  if (equals == std::string::npos) {
    *error = "--vary " + text +
             ": expected key.path=v1,v2,..., for example --vary cloth.springs.bend.ks=1,10,100";
    return std::nullopt;
  }
  VariedKey varied;
  varied.key = trimmed(text.substr(0, equals));
  if (varied.key.empty() || varied.key.front() == '.' || varied.key.back() == '.' ||
      varied.key.find("..") != std::string::npos) {
    *error = "--vary " + text + ": the key path '" + varied.key + "' is empty or has an empty part";
    return std::nullopt;
  }
  std::string problem;
  auto values = split_values(text.substr(equals + 1), &problem);
  if (!values) {
    *error = "--vary " + text + ": " + problem;
    return std::nullopt;
  }
  varied.values = std::move(*values);
  return varied;
}

SweepPlan::SweepPlan(std::vector<VariedKey> keys) : keys_(std::move(keys)) {
  constexpr std::size_t most = std::numeric_limits<std::size_t>::max();
  for (const auto& key : keys_) {
    const std::size_t n = key.values.size();
    count_ = (n != 0 && count_ > most / n) ? most
                                           : count_ * n;  // saturates: the verb refuses huge sweeps
  }
}

std::vector<std::size_t> SweepPlan::value_indices(std::size_t index) const {
  std::vector<std::size_t> indices(keys_.size(), 0);
  for (std::size_t k = keys_.size(); k-- > 0;) {  // the last key is the fastest digit
    const std::size_t n = keys_[k].values.size();
    indices[k] = index % n;
    index /= n;
  }
  return indices;
}

std::vector<std::string> SweepPlan::values(std::size_t index) const {
  const auto indices = value_indices(index);
  std::vector<std::string> result;
  for (std::size_t k = 0; k < keys_.size(); ++k) result.push_back(keys_[k].values[indices[k]]);
  return result;
}

std::vector<std::string> SweepPlan::overrides(std::size_t index) const {
  const auto chosen = values(index);
  std::vector<std::string> result;
  for (std::size_t k = 0; k < keys_.size(); ++k) result.push_back(keys_[k].key + "=" + chosen[k]);
  return result;
}

std::string SweepPlan::index_label(std::size_t index) const {
  std::string number = std::to_string(index);
  const std::size_t width =
      std::max<std::size_t>(3, std::to_string(count_ == 0 ? 0 : count_ - 1).size());
  if (number.size() < width) number.insert(0, width - number.size(), '0');
  return number;
}

std::string SweepPlan::folder_name(std::size_t index) const {
  std::string name = index_label(index);
  const auto chosen = values(index);
  for (std::size_t k = 0; k < keys_.size(); ++k)
    name += "_" + sanitise_for_file_name(keys_[k].key) + "=" + sanitise_for_file_name(chosen[k]);
  if (name.size() > kMaxFolderName) name.resize(kMaxFolderName);
  return name;
}

std::string sanitise_for_file_name(const std::string& text) {
  std::string name;
  for (const char c : text) {
    if (file_name_character(c))
      name += c;
    else if (!name.empty() && name.back() != '_')
      name += '_';
  }
  while (!name.empty() && name.back() == '_') name.pop_back();
  return name.empty() ? "_" : name;
}

}  // namespace drapelab::sweep
