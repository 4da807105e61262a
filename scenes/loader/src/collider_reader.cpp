// Colliders: shape keys per type, pose, friction, kinematic motion (see docs/scene-reference.md).
#include "collider_reader.hpp"

#include <map>
#include <set>

#include "drapelab/mesh_surface.hpp"
#include "drapelab/obj_reader.hpp"
#include "drapelab/scene/number_format.hpp"
#include "scene_keys.hpp"
#include "text_checks.hpp"
#include "value_ranges.hpp"

namespace drapelab::scene {
namespace {

ColliderShape shape_of(const std::string& type) {
  if (type == "cylinder") return ColliderShape::cylinder;
  if (type == "capsule") return ColliderShape::capsule;
  if (type == "box") return ColliderShape::box;
  if (type == "plane") return ColliderShape::plane;
  if (type == "mesh") return ColliderShape::mesh;
  return ColliderShape::sphere;
}

// The unit vector along v, chosen so that normalising it again gives it back bit for bit: then
// resolved.yaml, which writes the unit vector, loads as the same collider.
Eigen::Vector3d stable_normalized(const Eigen::Vector3d& v) {
  Eigen::Vector3d unit = v.normalized();
  for (int round = 0; round < 4; ++round) {
    const Eigen::Vector3d again = unit.normalized();
    if (again == unit) break;
    unit = again;
  }
  return unit;
}

// A direction: three numbers, not all zero; returned normalised.
std::optional<Eigen::Vector3d> read_direction(SceneReader& r, MapReader& map, const SceneKey& row) {
  const auto value = map.numbers(row);
  if (!value) return std::nullopt;
  const std::string name(row.name());
  if (value->norm() < kMinDirection) {
    r.error(map.get(name), map.path_of(name), "must be a non-zero direction, got [0, 0, 0]");
    return std::nullopt;
  }
  return stable_normalized(*value);
}

void read_motion(SceneReader& r, const YAML::Node& node, const std::string& path,
                 ColliderMotion& motion) {
  MapReader map(r, node, path, key_names("colliders[].motion"));
  if (!map.valid()) return;
  if (const auto v = map.numbers(key("colliders[].motion.velocity"))) motion.velocity = *v;
  if (const auto w = map.numbers(key("colliders[].motion.angular_velocity")))
    motion.angular_velocity = *w;
  if (!map.has("keyframes")) return;
  if (map.has("velocity") || map.has("angular_velocity")) {
    r.error(map.get("keyframes"), map.path_of("keyframes"),
            "cannot be combined with velocity or angular_velocity; give one kind of motion");
    return;
  }
  const YAML::Node list = map.get("keyframes");
  const std::string list_path = map.path_of("keyframes");
  if (!list.IsSequence() || list.size() == 0) {
    r.error(list, list_path,
            "must be a non-empty list of {t, center, rotation}, got " + describe_scalar(list));
    return;
  }
  record_item_lines(r, list, list_path);
  double previous_t = -1.0;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string key_path = list_path + "." + std::to_string(k);
    MapReader item(r, list[k], key_path, key_names("colliders[].motion.keyframes[]"));
    if (!item.valid()) continue;
    ColliderKeyframe frame;
    const auto t = item.number(key("colliders[].motion.keyframes[].t"));
    if (!item.has("t")) item.missing("t", "the keyframe's time in s, >= 0");
    const auto center = item.numbers(key("colliders[].motion.keyframes[].center"));
    if (!item.has("center"))
      item.missing("center", "the collider's centre [x, y, z] in m at time t");
    const auto rotation = item.numbers(key("colliders[].motion.keyframes[].rotation"));
    if (!t || !center || !rotation) continue;
    if (*t <= previous_t) {
      r.error(item.get("t"), item.path_of("t"),
              "must be later than the previous keyframe's t = " + format_number(previous_t) +
                  ", got " + format_number(*t));
      continue;
    }
    previous_t = *t;
    frame.t = *t;
    frame.center = *center;
    frame.rotation = *rotation;
    motion.keyframes.push_back(frame);
  }
}

// Keyframes give the collider's centre at every time (its `rotation` is composed with theirs, see
// collider_pose): a `center` (a plane's `point`) that disagrees with the first keyframe would be
// silently ignored, so it is an error; a missing one is the first keyframe's.
void keyframe_center(SceneReader& r, MapReader& map, const std::string& center_key, Collider& c) {
  const Eigen::Vector3d first = c.motion.keyframes.front().center;
  if (!map.has(center_key)) {
    c.center = first;
  } else if (c.center != first) {
    r.error(map.get(center_key), map.path_of(center_key),
            "must equal the first keyframe's center " + format_list(first) +
                " or be left out (with keyframes " +
                "the keyframes give the centre at every time), got " + format_list(c.center));
  }
}

// colliders[].dynamic: {mass: kg}. A body the world moves cannot also follow a motion or a parent,
// and a plane (infinite, solid below) has no mass to give.
void read_dynamic(SceneReader& r, MapReader& map, Collider& c) {
  const std::string path = map.path_of("dynamic");
  MapReader dynamic(r, map.get("dynamic"), path, key_names("colliders[].dynamic"));
  if (!dynamic.valid()) return;
  if (!dynamic.has("mass")) dynamic.missing("mass", "the body's mass in kg, > 0");
  const auto mass = dynamic.number(key("colliders[].dynamic.mass"));
  if (!mass) return;
  const char* clash = c.shape == ColliderShape::plane  ? "a plane cannot be dynamic"
                      : c.shape == ColliderShape::mesh ? "a mesh collider cannot be dynamic"
                      : map.has("motion")              ? "a dynamic collider has no motion key"
                      : map.has("parent")              ? "a dynamic collider has no parent"
                                                       : nullptr;
  if (clash) {
    r.error(map.get("dynamic"), path,
            std::string(clash) +
                ": its rigid body moves under gravity and the cloth's loads (remove dynamic, or "
                "the other key)");
    return;
  }
  c.dynamic_mass = *mass;
}

// colliders[].scale: one number for all three axes, or three.
Eigen::Vector3d read_scale(MapReader& map) {
  const SceneKey& row = key("colliders[].scale");
  if (map.has("scale") && map.get("scale").IsScalar()) {
    const auto one = map.number("scale", row.range, std::nullopt);
    return Eigen::Vector3d::Constant(one.value_or(1.0));
  }
  return map.numbers(row).value_or(Eigen::Vector3d::Ones());
}

// What is odd about a usable surface, for warnings; a mesh wound inwards is turned outwards.
std::vector<std::string> surface_warnings(TriangleMesh& mesh) {
  std::vector<std::string> found;
  const MeshQuality quality = MeshSurface(mesh).quality();
  const auto count = [](int n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
  };
  if (quality.border_edges > 0)
    found.push_back(
        "is open (" + count(quality.border_edges, "edge has", "edges have") +
        " one triangle): the solid is taken to lie behind each face, so cloth that reaches the "
        "back of an open surface is pushed through it to the front");
  if (quality.non_manifold_edges > 0)
    found.push_back("has " + count(quality.non_manifold_edges, "edge", "edges") +
                    " shared by three or more triangles: inside and outside are uncertain there");
  if (quality.misoriented_edges > 0)
    found.push_back("is not wound consistently (" +
                    count(quality.misoriented_edges, "edge runs", "edges run") +
                    " the same way in both its triangles): cloth near those faces may be pushed "
                    "into the solid; wind every face counter-clockwise seen from outside");
  if (quality.border_edges == 0 && quality.misoriented_edges == 0 && quality.volume < 0.0) {
    mesh.triangles.row(1).swap(mesh.triangles.row(2));
    found.push_back("is wound inwards (its enclosed volume is " + format_number(quality.volume) +
                    " m^3); its faces are turned to face outwards");
  }
  return found;
}

// colliders[].file: the OBJ file, its surface scaled into the collider's frame. Errors name the
// file and line; a usable but odd surface gives warnings.
void read_mesh_file(SceneReader& r, MapReader& map, const std::filesystem::path& folder,
                    Collider& c, std::vector<std::string>& warnings) {
  if (!map.has("file")) {
    map.missing("file",
                "the OBJ file of the surface, relative to the scene file (for example "
                "meshes/mannequin.obj)");
    return;
  }
  const auto file = map.text("file", std::nullopt);
  if (!file) return;
  if (const auto problem = path_problem(*file)) {
    r.error(map.get("file"), map.path_of("file"), *problem);
    return;
  }
  const std::filesystem::path full =
      std::filesystem::path(*file).is_absolute() ? std::filesystem::path(*file) : folder / *file;
  c.mesh_file = full.string();
  c.mesh_scale = read_scale(map);
  const ObjReadResult read = read_obj_file(full);
  const std::string shown =
      full.string() + (read.error_line > 0 ? ":" + std::to_string(read.error_line) : "");
  if (!read.mesh) {
    r.error(map.get("file"), map.path_of("file"), "'" + shown + "': " + read.error);
    return;
  }
  TriangleMesh mesh = *read.mesh;
  mesh.uvs.resize(2, 0);
  for (Eigen::Index v = 0; v < mesh.vertices.cols(); ++v)
    mesh.vertices.col(v) = mesh.vertices.col(v).cwiseProduct(c.mesh_scale);
  const double largest = mesh.vertices.cwiseAbs().maxCoeff();  // m
  if (!(largest <= kMaxCoordinate)) {
    r.error(map.get("file"), map.path_of("file"),
            "'" + shown + "' scaled by " + format_list(c.mesh_scale) + " reaches " +
                format_number(largest) + " m from its origin along an axis; at most " +
                format_number(kMaxCoordinate) + " m is allowed");
    return;
  }
  if (const auto problem = mesh_surface_problem(mesh)) {
    r.error(map.get("file"), map.path_of("file"),
            "'" + shown + "' scaled by " + format_list(c.mesh_scale) +
                " is not a usable collider surface: " + *problem);
    return;
  }
  for (const std::string& warning : surface_warnings(mesh))
    warnings.push_back(r.where(map.get("file"), map.path_of("file"), map.node()) + ": " +
                       map.path_of("file") + " '" + full.string() + "' " + warning);
  c.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
}

std::optional<Collider> read_collider(SceneReader& r, const YAML::Node& node,
                                      const std::string& path, const ContactSpec& contact,
                                      const std::filesystem::path& folder,
                                      std::vector<std::string>& warnings) {
  // The type decides which keys are valid, so read it before checking the keys.
  std::string type = "sphere";
  record_key_lines(r, node, path);  // so that an empty type: is reported on its own line
  if (node.IsMap() && node["type"].IsDefined()) {
    const auto chosen =
        r.choice(node["type"], path + ".type", key_choices(key("colliders[].type")));
    if (!chosen) return std::nullopt;
    type = *chosen;
  } else if (node.IsMap()) {
    r.error(YAML::Node(), path + ".type",
            "is required: one of sphere | cylinder | capsule | box | plane | mesh", node);
    return std::nullopt;
  }
  MapReader map(r, node, path, key_names("colliders[]", type));
  if (!map.valid()) return std::nullopt;
  const std::size_t errors_before = r.error_count();

  Collider c;
  c.shape = shape_of(type);
  if (const auto name = map.text("name", std::nullopt)) {
    if (const auto problem = name_problem(*name))
      r.error(map.get("name"), map.path_of("name"), *problem);
    else
      c.name = *name;
  } else if (!map.has("name")) {
    map.missing("name", "a unique label such as ball or table ([a-z0-9_-]+, at most " +
                            std::to_string(kMaxNameLength) + " characters)");
  }
  // A required key left out is reported, and read as a stand-in so that the rest is checked.
  auto required_vector = [&](const SceneKey& row, const std::string& expected) -> Eigen::Vector3d {
    if (!map.has(std::string(row.name()))) map.missing(std::string(row.name()), expected);
    return map.numbers(row, Eigen::Vector3d::Zero()).value_or(Eigen::Vector3d::Zero());
  };
  auto required_length = [&](const SceneKey& row, const std::string& expected) -> double {
    if (!map.has(std::string(row.name()))) map.missing(std::string(row.name()), expected);
    return map.number(row, 1.0).value_or(1.0);
  };
  // With keyframes the centre comes from them, so `center` may be left out.
  const bool keyframed =
      map.has("motion") && map.get("motion").IsMap() && map.get("motion")["keyframes"].IsDefined();
  const std::string center_key = c.shape == ColliderShape::plane ? "point" : "center";
  if (c.shape == ColliderShape::plane) {
    c.center = map.numbers(key("colliders[].point")).value_or(Eigen::Vector3d::Zero());
    c.normal = read_direction(r, map, key("colliders[].normal")).value_or(Eigen::Vector3d::UnitY());
  } else if (keyframed) {
    c.center = map.numbers(key("colliders[].center"), Eigen::Vector3d::Zero())
                   .value_or(Eigen::Vector3d::Zero());
  } else {
    c.center = required_vector(key("colliders[].center"), "the collider's centre [x, y, z] in m");
  }
  if (c.shape == ColliderShape::sphere || c.shape == ColliderShape::cylinder ||
      c.shape == ColliderShape::capsule)
    c.radius = required_length(key("colliders[].radius"), "the radius in m, > 0");
  if (c.shape == ColliderShape::cylinder || c.shape == ColliderShape::capsule) {
    c.height = required_length(
        key("colliders[].height"),
        c.shape == ColliderShape::capsule
            ? "the length of the capsule's axis segment in m (without its caps), > 0"
            : "the full length along the axis in m, > 0");
    c.axis = read_direction(r, map, key("colliders[].axis")).value_or(Eigen::Vector3d::UnitY());
  }
  if (c.shape == ColliderShape::box) {
    if (!map.has("half_extents"))
      map.missing("half_extents", "half the box's size along x, y, z in m, each > 0");
    c.half_extents = map.numbers(key("colliders[].half_extents"), Eigen::Vector3d::Constant(0.5))
                         .value_or(Eigen::Vector3d::Constant(0.5));
  }
  if (c.shape == ColliderShape::mesh) read_mesh_file(r, map, folder, c, warnings);
  c.rotation = map.numbers(key("colliders[].rotation")).value_or(Eigen::Vector3d::Zero());
  c.friction = map.number(key("colliders[].friction"), contact.friction).value_or(contact.friction);
  // A collider that sets only its kinetic coefficient gets the same static one.
  const double static_default = map.has("friction") ? c.friction : contact.static_friction;
  c.static_friction =
      map.number(key("colliders[].static_friction"), static_default).value_or(static_default);
  if (c.static_friction < c.friction && r.error_count() == errors_before)
    r.error(map.has("static_friction") ? map.get("static_friction") : map.get("friction"),
            map.path_of("static_friction"),
            "must be >= friction (" + format_number(c.friction) + "), got " +
                format_number(c.static_friction));
  if (const auto parent = map.text("parent", std::nullopt)) c.parent = *parent;
  if (map.has("motion")) read_motion(r, map.get("motion"), map.path_of("motion"), c.motion);
  if (!c.motion.keyframes.empty()) keyframe_center(r, map, center_key, c);
  if (map.has("dynamic")) read_dynamic(r, map, c);
  if (r.error_count() != errors_before) return std::nullopt;
  return c;
}

// Fills in each collider's ancestors from the `parent` names: each must name another collider of
// the scene, and following them must end at a collider without a parent.
void resolve_parents(SceneReader& r, std::vector<Collider>& colliders,
                     const std::vector<YAML::Node>& parent_nodes,
                     const std::vector<std::string>& paths) {
  std::map<std::string, std::size_t> index;
  for (std::size_t k = 0; k < colliders.size(); ++k) index[colliders[k].name] = k;
  for (std::size_t k = 0; k < colliders.size(); ++k) {
    Collider& c = colliders[k];
    if (c.parent.empty()) continue;
    const std::string path = paths[k] + ".parent";
    if (c.parent == c.name) {
      r.error(parent_nodes[k], path, "names the collider itself; give another collider's name");
      continue;
    }
    if (!index.contains(c.parent)) {
      std::vector<std::string> known;
      for (const auto& [name, at] : index) known.push_back(name);
      r.error(parent_nodes[k], path,
              "must name another collider of the scene (" + listed_names(known) + "), got " +
                  quoted_value(c.parent));
      continue;
    }
    std::vector<ColliderFrame> chain;
    std::set<std::string> seen = {c.name};
    for (std::string name = c.parent; !name.empty();) {
      if (!seen.insert(name).second) {
        r.error(parent_nodes[k], path,
                "makes a loop of parents through '" + name +
                    "'; the chain must end at a "
                    "collider without a parent");
        chain.clear();
        break;
      }
      const auto found = index.find(name);
      if (found == index.end()) break;  // reported at that collider
      const Collider& parent = colliders[found->second];
      if (parent.dynamic()) {
        r.error(parent_nodes[k], path,
                "names '" + name +
                    "', a dynamic collider, which cannot carry others (its pose is each "
                    "solver's own rigid body)");
        chain.clear();
        break;
      }
      chain.push_back(parent.frame());
      name = parent.parent;
    }
    c.ancestors = chain;
  }
}

}  // namespace

std::vector<Collider> read_colliders(SceneReader& reader, const YAML::Node& list,
                                     const ContactSpec& contact,
                                     const std::filesystem::path& folder,
                                     std::vector<std::string>& warnings) {
  std::vector<Collider> colliders;
  if (list.IsNull()) return colliders;
  if (!list.IsSequence()) {
    reader.error(list, "colliders", "must be a list of colliders, got " + describe_scalar(list));
    return colliders;
  }
  record_item_lines(reader, list, "colliders");
  std::set<std::string> names;
  std::vector<YAML::Node> parent_nodes;  // each kept collider's `parent` node, for its errors
  std::vector<std::string> paths;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string path = "colliders." + std::to_string(k);
    auto collider = read_collider(reader, list[k], path, contact, folder, warnings);
    if (!collider) continue;
    if (!names.insert(collider->name).second) {
      const YAML::Node& item = list[k];
      reader.error(
          item["name"], path + ".name",
          "'" + collider->name + "' is already used by another collider; names must be unique");
      continue;
    }
    colliders.push_back(*collider);
    parent_nodes.push_back(list[k]["parent"]);
    paths.push_back(path);
  }
  resolve_parents(reader, colliders, parent_nodes, paths);
  return colliders;
}

}  // namespace drapelab::scene
