// One key of the scene format, as data: its path, type, range or choices, default, unit and doc
// line. The rows (scene_keys_*.hpp) are the one place a key is declared; the readers take its name,
// range, choices and default from its row, resolved.yaml its name and comment, and the key tables
// of docs/scene-reference.md are produced from the rows (scene_key_docs.cpp).
#pragma once

#include <string_view>

#include "yaml_reader.hpp"

namespace drapelab::scene {

enum class KeyType {
  text,      // a string
  number,    // a finite double in `range`
  integer,   // a whole number in `range`, checked before it is converted
  boolean,   // true or false
  choice,    // one of `choices`
  numbers,   // a list of `size` numbers, each in `range`
  integers,  // a list of `size` whole numbers, each in `range`
  map,       // a map of keys of its own (rows whose parent it is)
  list,      // a list of items (rows below "path[]"), or of a form the doc line gives
};

// How a key left out is filled in.
enum class Given {
  required,  // an error; `fallback` may say when it is required ("required (grid)")
  optional,  // nothing; `fallback` says what that means ("none", "static")
  value,     // `fallback`, a YAML value ("5000", "[0, -9.81, 0]", "springs", "true")
  derived,   // computed by the reader from other keys; `fallback` says how ("`contact.friction`")
};

struct SceneKey {
  // The key's path from the top of the scene: "contact.stiffness". A list's items are "[]":
  // "solvers[].dt" is the dt of every solver.
  std::string_view path;
  KeyType type = KeyType::number;
  int size = 1;      // numbers, integers: how many
  Range range = {};  // number, integer; numbers, integers: each of them
  // choice: the values, "|"-separated, in the order messages list them.
  std::string_view choices = {};
  // The cloth shape or the collider or solver type the key belongs to ("grid", "sphere|box"); empty
  // for every one. A key of another shape or type is an unknown key.
  std::string_view when = {};
  Given given = Given::optional;
  std::string_view fallback = {};  // see Given
  // SI, ASCII as resolved.yaml writes it ("N*s/m", "m/s^2"); empty for a pure number.
  std::string_view unit = {};
  // resolved.yaml's comment after the value (without "# "); empty for none.
  std::string_view comment = {};
  std::string_view doc = {};  // what the key does: one line of the reference's table

  // The last part of the path: "dt" of "solvers[].dt".
  constexpr std::string_view name() const {
    const std::size_t dot = path.rfind('.');
    return dot == std::string_view::npos ? path : path.substr(dot + 1);
  }
  // The map the key lives in: "solvers[]" of "solvers[].dt", empty at the top.
  constexpr std::string_view parent() const {
    const std::size_t dot = path.rfind('.');
    return dot == std::string_view::npos ? std::string_view() : path.substr(0, dot);
  }
};

}  // namespace drapelab::scene
