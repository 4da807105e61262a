// Counting a scene's nodes and list items from parser events (tree_limits.hpp).
#include "tree_limits.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/parser.h>

#include <sstream>

#include "yaml_reader.hpp"

namespace drapelab::scene {
namespace {

// Whether key path `path` matches `pattern`, part by part, "*" matching any list index.
bool path_matches(const std::string& path, const std::string& pattern) {
  std::size_t p = 0, q = 0;
  while (true) {
    const std::size_t p_end = std::min(path.find('.', p), path.size());
    const std::size_t q_end = std::min(pattern.find('.', q), pattern.size());
    const std::string_view part(path.data() + p, p_end - p);
    const std::string_view wanted(pattern.data() + q, q_end - q);
    const bool index = !part.empty() && part.find_first_not_of("0123456789") == part.npos;
    if (!(part == wanted || (wanted == "*" && index))) return false;
    if (p_end == path.size() || q_end == pattern.size())
      return p_end == path.size() && q_end == pattern.size();
    p = p_end + 1;
    q = q_end + 1;
  }
}

const ListLimit* limit_for(const std::string& path) {
  for (const ListLimit& limit : list_limits())
    if (path_matches(path, limit.path)) return &limit;
  return nullptr;
}

// Thrown by the handler to stop the parser at the first limit broken.
struct LimitBroken {
  TreeProblem problem;
};

// Follows the events with a stack of the open lists and maps, so that every node knows its key
// path; counts the nodes and each list's items.
class Counter final : public YAML::EventHandler {
 public:
  explicit Counter(std::string base) : base_(std::move(base)) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { leaf(mark, ""); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { leaf(mark, ""); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                const std::string& value) override {
    leaf(mark, value);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    open(mark, false);
  }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    open(mark, true);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapEnd() override { close(); }

 private:
  struct Open {
    bool map = false;
    std::string path;
    int line = 0;  // 0-based: its key's line, or its own
    long long items = 0;
    const ListLimit* limit = nullptr;
    bool at_key = true;  // a map's next node is a key
    std::string key;     // a map's last key
    int key_line = 0;
  };

  // Where a new node stands: its key path and line. A map's key stands at the map's own path.
  std::pair<std::string, int> place(const YAML::Mark& mark) {
    if (open_.empty()) return {base_, mark.line};
    Open& parent = open_.back();
    if (parent.map)
      return parent.at_key ? std::pair{parent.path, mark.line}
                           : std::pair{join_path(parent.path, parent.key), parent.key_line};
    const std::string path = parent.path + "." + std::to_string(parent.items++);
    if (parent.limit && parent.items > parent.limit->max_items)
      throw LimitBroken{{parent.line, parent.path,
                         "has more than " + std::to_string(parent.limit->max_items) + " " +
                             parent.limit->items + "; at most " +
                             std::to_string(parent.limit->max_items) + " are allowed"}};
    return {path, mark.line};
  }

  void count(const YAML::Mark& mark, const std::string& path) {
    if (++nodes_ <= kMaxSceneNodes) return;
    throw LimitBroken{{mark.line, path,
                       "is past the " + std::to_string(kMaxSceneNodes) +
                           " values, lists and maps a scene may hold (yaml-cpp takes about 500 "
                           "bytes for each, and the scene is read whole before it is checked); "
                           "shorten its lists"}};
  }

  // A scalar, null or alias: a key of the map it is in, or a whole value.
  void leaf(const YAML::Mark& mark, const std::string& value) {
    const auto [path, line] = place(mark);
    count(mark, path);
    if (!open_.empty() && open_.back().map && open_.back().at_key) {
      open_.back().key = value;
      open_.back().key_line = line;
    }
    finished();
  }

  void open(const YAML::Mark& mark, bool map) {
    auto [path, line] = place(mark);
    count(mark, path);
    Open next;
    next.map = map;
    next.path = path;
    next.line = line;
    next.limit = map ? nullptr : limit_for(path);
    open_.push_back(std::move(next));
  }

  void close() {
    open_.pop_back();
    finished();
  }

  // A node of the innermost open map ended: keys and values take turns.
  void finished() {
    if (!open_.empty() && open_.back().map) open_.back().at_key = !open_.back().at_key;
  }

  std::string base_;
  std::vector<Open> open_;
  long long nodes_ = 0;
};

}  // namespace

const std::vector<ListLimit>& list_limits() {
  static const std::vector<ListLimit> limits = {
      {"cloth.pins", 10'000, "pin selectors"},
      {"colliders", 1'000, "colliders"},
      {"colliders.*.motion.keyframes", 30'000, "keyframes"},
      {"constraints", 20'000, "constraints"},
      {"interactions", 1'000, "interactions"},
      {"interactions.*.keyframes", 30'000, "keyframes"},
      {"solvers", 64, "solvers"},
  };
  return limits;
}

std::optional<TreeProblem> tree_size_problem(const std::string& text, const std::string& base) {
  std::istringstream stream(text);
  try {
    YAML::Parser parser(stream);
    Counter counter(base);
    parser.HandleNextDocument(counter);
  } catch (const LimitBroken& broken) {
    return broken.problem;
  } catch (const YAML::Exception&) {
  }
  return std::nullopt;
}

}  // namespace drapelab::scene
