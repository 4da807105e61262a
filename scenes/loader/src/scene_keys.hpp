// The table of scene keys: every row of scene_keys_*.hpp, looked up by path. `key("a.b")` is
// resolved at compile time, so a reader or the writer naming a key the table lacks does not build.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include "scene_key.hpp"
#include "scene_keys_cloth.hpp"
#include "scene_keys_colliders.hpp"
#include "scene_keys_fabric.hpp"
#include "scene_keys_solvers.hpp"
#include "scene_keys_top.hpp"

namespace drapelab::scene {

// Every row, group by group in the order of the scene file.
inline constexpr std::span<const SceneKey> kSceneKeyGroups[] = {
    kTopKeys, kClothKeys,    kSpringKeys,       kContinuumKeys,  kSelfCollisionKeys,
    kPinKeys, kColliderKeys, kColliderPartKeys, kConstraintKeys, kInteractionKeys,
    kAirKeys, kContactKeys,  kSolverKeys,       kSolverPartKeys, kMetricsOutputKeys};

consteval const SceneKey& key(std::string_view path) {
  for (const auto& group : kSceneKeyGroups)
    for (const SceneKey& row : group)
      if (row.path == path) return row;
  throw "not a path of the scene key table (scene_keys_*.hpp)";  // a compile error at the call
}

// Every row of the table, in order.
std::vector<const SceneKey*> scene_keys();
// The rows of the keys of map `parent` ("cloth", "solvers[]"), in table order; with `when`, only
// those of every shape or type and that shape's or type's own.
std::vector<const SceneKey*> keys_under(std::string_view parent, std::string_view when = {});
// Their names: the keys a map may hold, as MapReader takes them.
std::vector<std::string> key_names(std::string_view parent, std::string_view when = {});
// A choice key's values, in order.
std::vector<std::string> key_choices(const SceneKey& key);
// Whether `when` (a shape or type) is one the key belongs to.
bool key_applies(const SceneKey& key, std::string_view when);

// The default of a key with Given::value, parsed from its YAML text; a logic_error for another.
double default_number(const SceneKey& key);
long long default_integer(const SceneKey& key);
bool default_boolean(const SceneKey& key);
std::string default_choice(const SceneKey& key);
Eigen::VectorXd default_numbers(const SceneKey& key);

}  // namespace drapelab::scene
