// How large a scene's YAML tree and its lists may be, counted from yaml-cpp's parser events before
// YAML::Load builds the tree. yaml-cpp's tree takes about 500 bytes and 10 us per value, list or
// map (a list of 1,000,000 pins {index: 5}: 1.4 GB and half a minute), so a list of a million pins
// or colliders, or a 64 MB file of numbers, is refused here, naming its key, line and limit,
// before any of that memory is taken. The event parser itself holds only the text.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace drapelab::scene {

// Values, lists and maps a scene file may hold: about 250 MB of yaml-cpp's tree at most, ten times
// the nodes of a scene holding a ten-minute drag recorded by the viewer.
inline constexpr long long kMaxSceneNodes = 500'000;

// The most items a list of the scene may have. Each is far above what a scene needs, and bounds
// the work the loader does per item (a pin selector is checked against every particle).
struct ListLimit {
  std::string path;  // key path; "*" stands for any list index: "colliders.*.motion.keyframes"
  long long max_items = 0;
  std::string items;  // what an item is, for messages: "pin selectors"
};
const std::vector<ListLimit>& list_limits();

// A limit the text breaks: where (0-based line, -1 for none) and on which key path.
struct TreeProblem {
  int line = -1;
  std::string path;
  std::string message;  // "has more than 10000 pin selectors; at most 10000 are allowed ..."
};

// The first limit that the YAML `text` breaks, reading its events and stopping there, or nothing.
// `base` is the key path the text stands at: "" for a scene file, the key of a --set override for
// its value. A text that is not valid YAML gives nothing (YAML::Load then reports it).
std::optional<TreeProblem> tree_size_problem(const std::string& text, const std::string& base);

}  // namespace drapelab::scene
