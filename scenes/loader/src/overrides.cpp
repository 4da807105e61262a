// Applying --set overrides to a YAML tree (see overrides.hpp).
#include "overrides.hpp"

#include <charconv>

namespace drapelab::scene {
namespace {

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = path.find('.', start);
    parts.push_back(path.substr(start, dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

std::optional<std::size_t> list_index(const std::string& part) {
  std::size_t index = 0;
  const auto [end, code] = std::from_chars(part.data(), part.data() + part.size(), index);
  if (code != std::errc() || end != part.data() + part.size()) return std::nullopt;
  return index;
}

// Applies one override; returns an error message, empty on success.
// Keys the override creates on its way down are recorded in `created`, so that errors about them
// (a misspelled parent key, say) name the override too.
std::string apply_one(YAML::Node& root, const std::vector<std::string>& parts,
                      const YAML::Node& value, std::vector<std::string>& created) {
  YAML::Node node;
  node.reset(root);
  std::string walked;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const std::string& part = parts[p];
    const bool last = p + 1 == parts.size();
    if (node.IsSequence()) {
      const auto index = list_index(part);
      if (!index || *index >= node.size())
        return (walked.empty() ? std::string("the scene") : walked) + " is a list of " +
               std::to_string(node.size()) + " items; '" + part + "' is not an index in 0.." +
               std::to_string(node.size() == 0 ? 0 : node.size() - 1);
      if (last) {
        node[*index] = value;
        return "";
      }
      YAML::Node child = node[*index];
      node.reset(child);
    } else if (node.IsMap() || node.IsNull()) {
      if (last) {
        node[part] = value;
        return "";
      }
      if (!node[part].IsDefined() || node[part].IsNull()) {
        node[part] = YAML::Node(YAML::NodeType::Map);
        created.push_back(join_path(walked, part));
      }
      YAML::Node child = node[part];
      node.reset(child);
    } else {
      return walked + " is a single value, so it has no key '" + part + "'";
    }
    walked = join_path(walked, part);
  }
  return "";
}

}  // namespace

bool apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides,
                     SceneReader& reader) {
  bool ok = true;
  for (const auto& text : overrides) {
    const std::string origin = "--set " + text;
    const std::size_t equals = text.find('=');
    auto fail = [&](const std::string& message) {
      reader.error(YAML::Node(), "", origin + ": " + message);
      ok = false;
    };
    if (equals == std::string::npos || equals == 0) {
      fail("expected key.path=value, for example --set cloth.springs.stretch.ks=500");
      continue;
    }
    const std::string path = text.substr(0, equals);
    const auto parts = split_path(path);
    bool empty_part = false;
    for (const auto& part : parts) empty_part = empty_part || part.empty();
    if (empty_part) {
      fail("the key path '" + path + "' has an empty part");
      continue;
    }
    YAML::Node value;
    try {
      value = YAML::Load(text.substr(equals + 1));
    } catch (const YAML::Exception& e) {
      fail("the value is not valid YAML: " + e.msg);
      continue;
    }
    if (!root.IsMap()) {
      fail("the scene file is not a map of keys, so nothing can be overridden");
      continue;
    }
    std::vector<std::string> created;
    const std::string message = apply_one(root, parts, value, created);
    if (!message.empty()) {
      fail(message);
      continue;
    }
    reader.set_override_origin(path, origin);
    for (const auto& key : created) reader.set_override_origin(key, origin);
  }
  return ok;
}

}  // namespace drapelab::scene
