// Writing resolved.yaml by rows of the key table (scene_keys.hpp): each key's name and comment are
// its row's, and put_keys and flow_map walk a map's rows in table order (scene_writer.cpp).
#pragma once

#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "scene_keys.hpp"

namespace drapelab::scene {

// "INDENT name: VALUE  # comment": the name and, unless one is given, the comment of the key's row.
// A map's own line has no value ("springs:  # ...").
inline void put(std::ostream& out, std::string_view indent, const SceneKey& row,
                const std::string& value, std::string_view comment) {
  out << indent << row.name() << ":" << (value.empty() ? "" : " ") << value;
  if (!comment.empty()) out << "  # " << comment;
  out << "\n";
}
inline void put(std::ostream& out, std::string_view indent, const SceneKey& row,
                const std::string& value) {
  put(out, indent, row, value, row.comment);
}

[[noreturn]] inline void value_missing(const SceneKey& row) {
  throw std::logic_error("resolved_scene_yaml writes no value for scene key " +
                         std::string(row.path) + " (scene_writer.cpp)");
}

// Every scalar key of map `parent` (of shape or type `when`) in table order, each with the value
// `value_of` gives for its row (value_missing for a row it does not know).
template <class ValueOf>
void put_keys(std::ostream& out, std::string_view indent, std::string_view parent,
              std::string_view when, const ValueOf& value_of) {
  for (const SceneKey* row : keys_under(parent, when))
    if (row->type != KeyType::map && row->type != KeyType::list)
      put(out, indent, *row, value_of(*row));
}

// "{a: 1, b: 2}": the scalar keys of map `parent` in table order, with their values.
template <class ValueOf>
std::string flow_map(std::string_view parent, const ValueOf& value_of) {
  std::string text;
  for (const SceneKey* row : keys_under(parent))
    if (row->type != KeyType::map && row->type != KeyType::list)
      text += (text.empty() ? "{" : ", ") + std::string(row->name()) + ": " + value_of(*row);
  return text + "}";
}

inline const char* yes_no(bool value) { return value ? "true" : "false"; }

}  // namespace drapelab::scene
