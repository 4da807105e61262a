// Reading `constraints:` (see constraint_reader.hpp).
#include "constraint_reader.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "drapelab/scene/number_format.hpp"
#include "scene_keys.hpp"
#include "text_checks.hpp"
#include "value_ranges.hpp"

namespace drapelab::scene {
namespace {

const char* const kParticleForms = "{index: k} or [i, j] (a grid's column and row)";
const char* const kEndForms =
    "{index: k}, [i, j] (a grid's column and row), {point: [x, y, z]} or "
    "{collider: NAME, offset: [x, y, z]}";

}  // namespace

// {index: k} or [i, j]: the particle's index, checked on the cloth when it is built.
std::optional<int> read_cloth_particle(SceneReader& reader, const YAML::Node& node,
                                       const std::string& path, const Scene& scene,
                                       const ClothModel* model) {
  std::optional<PinSelector> selector;
  if (node.IsSequence()) {
    if (const auto ij = reader.integers(node, path, 2, grid_coordinate_range()))
      selector = PinGridCoord{static_cast<int>((*ij)[0]), static_cast<int>((*ij)[1])};
  } else if (node.IsMap()) {
    MapReader end(reader, node, path, {"index"});
    if (!end.valid()) return std::nullopt;
    if (!end.has("index")) {
      reader.error(node, path, std::string("must be a particle: ") + kParticleForms);
      return std::nullopt;
    }
    if (const auto index = end.integer("index", particle_index_range(), std::nullopt))
      selector = PinIndex{static_cast<int>(*index)};
  } else {
    reader.error(
        node, path,
        std::string("must be a particle: ") + kParticleForms + ", got " + describe_scalar(node));
  }
  if (!selector) return std::nullopt;
  if (!model) return 0;
  std::string why;
  const std::vector<int> picked = select_cloth_pins(scene.cloth, *selector, &why);
  if (picked.size() != 1) {
    reader.error(node, path, "selects no particle of the cloth: " + why);
    return std::nullopt;
  }
  return picked.front();
}

namespace {

class ConstraintReader {
 public:
  ConstraintReader(SceneReader& reader, const Scene& scene, const ClothModel* model)
      : r_(reader), scene_(scene), model_(model) {}

  std::optional<DistanceConstraint> read(const YAML::Node& item, const std::string& path) {
    MapReader entry(r_, item, path, key_names("constraints[]"));
    if (!entry.valid()) return std::nullopt;
    DistanceConstraint c;
    bool ok = true;
    if (!entry.has("type"))
      entry.missing("type", "the constraint's kind: distance");
    else
      ok = entry.choice(key("constraints[].type")).has_value() && ok;
    const auto mode = entry.choice(key("constraints[].mode"));
    if (!mode) return std::nullopt;
    c.mode = *mode == "hard"   ? ConstraintMode::hard
             : *mode == "rope" ? ConstraintMode::rope
                               : ConstraintMode::soft;
    const bool soft = c.mode == ConstraintMode::soft;
    // Keys of the other modes are mistakes, not silently ignored values.
    for (const char* key : {"stiffness", "damping"})
      if (!soft && entry.has(key))
        r_.error(entry.get(key), entry.path_of(key),
                 std::string("is for mode: soft only (a ") + *mode +
                     " constraint holds its length by projection, with no spring)");
    if (soft && entry.has("tolerance"))
      r_.error(entry.get("tolerance"), entry.path_of("tolerance"),
               "is for modes hard and rope only (a soft constraint is a spring)");
    if (soft) {
      if (!entry.has("stiffness")) entry.missing("stiffness", "the spring's stiffness in N/m, > 0");
      const auto k = entry.number(key("constraints[].stiffness"));
      const auto d = entry.number(key("constraints[].damping"));
      ok = ok && k && d;
      if (k) c.stiffness = *k;
      if (d) c.damping = *d;
    } else {
      const auto tolerance = entry.number(key("constraints[].tolerance"));
      ok = ok && tolerance;
      if (tolerance) c.tolerance = *tolerance;
    }
    std::optional<int> a;
    if (!entry.has("a"))
      entry.missing("a", std::string("the particle at one end: ") + kParticleForms);
    else
      a = read_particle(entry.get("a"), entry.path_of("a"));
    std::optional<ConstraintEnd> b;
    if (!entry.has("b"))
      entry.missing("b", std::string("the other end: ") + kEndForms);
    else
      b = read_end(entry.get("b"), entry.path_of("b"), c.mode);
    const auto length = entry.number(key("constraints[].length"), std::nullopt);
    if (entry.has("length") && !length) ok = false;
    if (!ok || !a || !b) return std::nullopt;
    c.a = *a;
    c.b = *b;
    if (!model_) return c;  // the cloth has errors of its own: ends checked for form only
    if (!check_ends(c, item, path)) return std::nullopt;
    if (length) {
      c.length = *length;
    } else {
      c.length = rest_distance(c);
      if (!(c.length >= key("constraints[].length").range.min.value_or(0.0))) {
        r_.error(item, path,
                 "has ends " + format_number(c.length) +
                     " m apart at rest; give its length (m, at least 0.001)");
        return std::nullopt;
      }
    }
    return c;
  }

 private:
  std::optional<int> read_particle(const YAML::Node& node, const std::string& path) {
    return read_cloth_particle(r_, node, path, scene_, model_);
  }

  std::optional<ConstraintEnd> read_end(const YAML::Node& node, const std::string& path,
                                        ConstraintMode mode) {
    ConstraintEnd end;
    const bool point_map = node.IsMap() && (node["point"] || node["collider"] || node["offset"]);
    if (!point_map) {
      const auto particle = read_particle(node, path);
      if (!particle) return std::nullopt;
      end.kind = ConstraintEnd::Kind::particle;
      end.particle = *particle;
      return end;
    }
    MapReader m(r_, node, path, key_names("constraints[].b"));
    if (!m.valid()) return std::nullopt;
    if (m.has("point")) {
      if (m.has("collider") || m.has("offset")) {
        r_.error(node, path,
                 "must be one end: {point: [x, y, z]} or {collider: NAME, offset: [x, y, z]}, not "
                 "both");
        return std::nullopt;
      }
      const auto point = m.numbers(key("constraints[].b.point"));
      if (!point) return std::nullopt;
      end.kind = ConstraintEnd::Kind::point;
      end.point = *point;
      return end;
    }
    if (!m.has("collider")) {
      m.missing("collider", "the name of the collider that carries the point");
      return std::nullopt;
    }
    const auto name = m.text("collider", std::nullopt);
    const auto offset = m.numbers(key("constraints[].b.offset"));
    if (!name || !offset) return std::nullopt;
    std::vector<std::string> names;
    for (const Collider& c : scene_.colliders) names.push_back(c.name);
    for (std::size_t k = 0; k < names.size(); ++k)
      if (names[k] == *name) end.collider = static_cast<int>(k);
    if (end.collider < 0) {
      const std::string near = nearest_word(*name, names);
      r_.error(m.get("collider"), m.path_of("collider"),
               "must name a collider of the scene" +
                   (names.empty() ? std::string(" (it has none)") : "") + ", got " +
                   quoted_value(*name) + (near.empty() ? "" : "; did you mean " + near + "?"));
      return std::nullopt;
    }
    // A projection would have to move the body too (its mass and inertia in the correction).
    if (mode != ConstraintMode::soft &&
        scene_.colliders[static_cast<std::size_t>(end.collider)].dynamic()) {
      r_.error(m.get("collider"), m.path_of("collider"),
               "names '" + *name + "', a dynamic collider: a " + constraint_mode_name(mode) +
                   " constraint holds to kinematic colliders only; give mode: soft (a spring) "
                   "to tie the cloth to a dynamic one");
      return std::nullopt;
    }
    end.kind = ConstraintEnd::Kind::collider_point;
    end.point = *offset;
    return end;
  }

  // The ends must be two things, and at least one must be able to move.
  bool check_ends(const DistanceConstraint& c, const YAML::Node& item, const std::string& path) {
    const bool b_particle = c.b.kind == ConstraintEnd::Kind::particle;
    if (b_particle && c.b.particle == c.a) {
      r_.error(item, path,
               "joins particle " + std::to_string(c.a) + " to itself; give two different ends");
      return false;
    }
    const bool a_held = model_->is_pinned(c.a);
    // A point on a dynamic collider moves with its body, which the constraint pulls.
    const bool b_body = c.b.kind == ConstraintEnd::Kind::collider_point &&
                        scene_.colliders[static_cast<std::size_t>(c.b.collider)].dynamic();
    const bool b_held = !b_body && (!b_particle || model_->is_pinned(c.b.particle));
    if (a_held && b_held) {
      r_.error(item, path,
               "has both ends held in place (particle " + std::to_string(c.a) +
                   " is pinned, and the other end is " +
                   (b_particle ? "a pinned particle" : "a point") +
                   "): it would act on nothing; unpin one end");
      return false;
    }
    return true;
  }

  // |a - b| in the cloth's rest pose, the colliders at t = 0 (m).
  double rest_distance(const DistanceConstraint& c) const {
    const Eigen::Vector3d a = model_->rest_positions.col(c.a);
    switch (c.b.kind) {
      case ConstraintEnd::Kind::particle:
        return (a - model_->rest_positions.col(c.b.particle)).norm();
      case ConstraintEnd::Kind::point:
        return (a - c.b.point).norm();
      case ConstraintEnd::Kind::collider_point:
        return (a - collider_pose(scene_.colliders[static_cast<std::size_t>(c.b.collider)], 0.0) *
                        c.b.point)
            .norm();
      case ConstraintEnd::Kind::drag:  // interactions:, read elsewhere with length 0
        return 0.0;
    }
    return 0.0;
  }

  SceneReader& r_;
  const Scene& scene_;
  const ClothModel* model_;
};

}  // namespace

std::vector<DistanceConstraint> read_constraints(SceneReader& reader, const YAML::Node& list,
                                                 const Scene& scene, const ClothModel* model) {
  std::vector<DistanceConstraint> out;
  if (!list.IsSequence()) {
    reader.error(list, "constraints",
                 "must be a list of constraints ({type: distance, a: ..., b: ..., mode: ...}), "
                 "got " +
                     describe_scalar(list));
    return out;
  }
  record_item_lines(reader, list, "constraints");
  ConstraintReader constraints(reader, scene, model);
  for (std::size_t k = 0; k < list.size(); ++k)
    if (auto c = constraints.read(list[k], "constraints." + std::to_string(k))) out.push_back(*c);
  return out;
}

}  // namespace drapelab::scene
