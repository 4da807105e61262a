// Applying --set overrides to a YAML tree (see overrides.hpp).
#include "overrides.hpp"

#include <charconv>
#include <map>
#include <tuple>
#include <utility>

#include "text_checks.hpp"
#include "tree_limits.hpp"

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

// How many places of the tree refer to each node. An alias and its anchor are one yaml-cpp node
// (Node::is), so editing a node that two places refer to would change both: `shear: *s` would take
// a --set of cloth.springs.shear.ks into stretch too. Nodes are bucketed by their mark (an alias
// shares its anchor's) and told apart within a bucket with Node::is.
class References {
 public:
  explicit References(const YAML::Node& root) {
    std::vector<YAML::Node> pending{root};
    while (!pending.empty()) {
      const YAML::Node node = pending.back();
      pending.pop_back();
      if (++entry(node) > 1) continue;  // met again through an alias: its children are counted
      if (node.IsMap())
        for (const auto& item : node) pending.push_back(item.second);
      else if (node.IsSequence())
        for (const auto& item : node) pending.push_back(item);
    }
  }

  // The number of places referring to `node` (0 for a node outside the tree).
  int count(const YAML::Node& node) const {
    const auto bucket = buckets_.find(mark_key(node));
    if (bucket == buckets_.end()) return 0;
    for (const auto& [known, references] : bucket->second)
      if (known.is(node)) return references;
    return 0;
  }

 private:
  using MarkKey = std::tuple<int, int, int>;
  static MarkKey mark_key(const YAML::Node& node) {
    const YAML::Mark mark = node.Mark();
    return {mark.pos, mark.line, mark.column};
  }
  int& entry(const YAML::Node& node) {
    auto& bucket = buckets_[mark_key(node)];
    for (auto& [known, references] : bucket)
      if (known.is(node)) return references;
    bucket.emplace_back(node, 0);
    return bucket.back().second;
  }

  std::map<MarkKey, std::vector<std::pair<YAML::Node, int>>> buckets_;
};

// The node at `part` of a map or list (undefined when absent), read without inserting it.
YAML::Node slot_of(const YAML::Node& container, const std::string& part) {
  if (container.IsSequence()) {
    const auto index = list_index(part);
    return index && *index < container.size() ? container[*index]
                                              : YAML::Node(YAML::NodeType::Undefined);
  }
  return container[part];
}

// A new map or list with the same entries (the same key and value nodes, so their lines are kept)
// but `child` at `part`.
YAML::Node copy_with(const YAML::Node& container, const std::string& part,
                     const YAML::Node& child) {
  if (container.IsSequence()) {
    YAML::Node copy(YAML::NodeType::Sequence);
    const auto index = list_index(part);
    for (std::size_t k = 0; k < container.size(); ++k)
      copy.push_back(index && k == *index ? child : container[k]);
    return copy;
  }
  YAML::Node copy(YAML::NodeType::Map);
  bool found = false;
  for (const auto& item : container) {
    const bool here = item.first.Scalar() == part;
    found = found || here;
    copy.force_insert(item.first, here ? child : item.second);
  }
  if (!found) copy.force_insert(part, child);
  return copy;
}

// The containers from the root down along parts[0 .. depth - 1]; every one exists.
std::vector<YAML::Node> walk(const YAML::Node& root, const std::vector<std::string>& parts,
                             std::size_t depth) {
  std::vector<YAML::Node> path{root};
  for (std::size_t p = 0; p < depth; ++p) path.push_back(slot_of(path.back(), parts[p]));
  return path;
}

// Puts `child` at parts[depth] of path[depth] without changing any node that another place of the
// tree refers to: a container on the path below a shared one is copied (with the new child) and the
// copy put in its parent in turn, up to the first container that only this path reaches.
void put(YAML::Node& root, const std::vector<std::string>& parts, std::size_t depth,
         YAML::Node child) {
  const std::vector<YAML::Node> path = walk(root, parts, depth);
  const References references(root);
  std::vector<bool> shared(path.size(), false);  // the container, or one above it, is shared
  for (std::size_t i = 1; i < path.size(); ++i)
    shared[i] = shared[i - 1] || references.count(path[i]) > 1;
  for (std::size_t i = depth + 1; i-- > 0;) {
    YAML::Node container = path[i];
    const std::string& part = parts[i];
    const YAML::Node old = slot_of(container, part);
    const bool old_shared = old.IsDefined() && references.count(old) > 1;
    if (!shared[i] && container.IsMap()) {
      if (!old_shared) {
        container[part] = child;  // replaces the old node's content: only this place sees it
      } else {
        YAML::Node key;
        for (const auto& item : container)
          if (item.first.Scalar() == part) key = item.first;
        container.remove(part);
        container.force_insert(key, child);  // a new entry: the shared node stays as it is
      }
      return;
    }
    if (!shared[i] && container.IsSequence() && !old_shared) {
      container[*list_index(part)] = child;
      return;
    }
    child.reset(copy_with(container, part, child));  // reset: `=` would overwrite the old child
  }
}

// Applies one override; returns an error message, empty on success.
// Keys the override creates on its way down are recorded in `created`, so that errors about them
// (a misspelled parent key, say) name the override too.
std::string apply_one(YAML::Node& root, const std::vector<std::string>& parts,
                      const YAML::Node& value, std::vector<std::string>& created) {
  std::string walked;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const YAML::Node node = walk(root, parts, p).back();
    const std::string& part = parts[p];
    const bool last = p + 1 == parts.size();
    if (node.IsSequence()) {
      const auto index = list_index(part);
      if (!index || *index >= node.size())
        return (walked.empty() ? std::string("the scene") : walked) + " is a list of " +
               std::to_string(node.size()) + " items; " + quoted_value(part) +
               " is not an index in 0.." + std::to_string(node.size() == 0 ? 0 : node.size() - 1);
    } else if (!node.IsMap()) {
      return walked + " is a single value, so it has no key " + quoted_value(part);
    }
    if (last) {
      put(root, parts, p, value);
      return "";
    }
    const YAML::Node child = slot_of(node, part);
    if (!child.IsDefined() || child.IsNull()) {
      put(root, parts, p, YAML::Node(YAML::NodeType::Map));
      created.push_back(join_path(walked, part));
    }
    walked = join_path(walked, part);
  }
  return "";
}

// The override as shown in messages: bytes that are not printable ASCII as \xNN, so a message
// about a bad override is itself valid text.
std::string shown(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7F) {
      out += c;
    } else {
      const char* digits = "0123456789abcdef";
      out += std::string("\\x") + digits[byte >> 4] + digits[byte & 15];
    }
  }
  return out;
}

}  // namespace

bool apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides,
                     SceneReader& reader) {
  bool ok = true;
  for (const auto& text : overrides) {
    const std::string origin = "--set " + text;
    const std::size_t equals = text.find('=');
    auto fail = [&](const std::string& message) {
      reader.error(YAML::Node(), "", shown_value(origin, kMaxShownOverrideBytes) + ": " + message);
      ok = false;
    };
    if (const auto problem = text_problem(text)) {
      reader.error(YAML::Node(), "",
                   shown_value("--set " + shown(text), kMaxShownOverrideBytes) +
                       ": is not UTF-8 text: " + problem->what + " (byte " +
                       std::to_string(problem->offset + 1) + ")");
      ok = false;
      continue;
    }
    if (equals == std::string::npos || equals == 0) {
      fail("expected key.path=value, for example --set cloth.springs.stretch.ks=500");
      continue;
    }
    const std::string path = text.substr(0, equals);
    const auto parts = split_path(path);
    bool empty_part = false;
    for (const auto& part : parts) empty_part = empty_part || part.empty();
    if (empty_part) {
      fail("the key path " + quoted_value(path) + " has an empty part");
      continue;
    }
    // The value's lists are counted before yaml-cpp builds them (tree_limits.hpp).
    if (const auto problem = tree_size_problem(text.substr(equals + 1), path)) {
      fail(problem->path + " " + problem->message);
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
