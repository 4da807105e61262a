// cloth: shape, geometry, material preset, mass, springs, pins (cloth_reader.hpp).
#include "cloth_reader.hpp"

#include <cmath>
#include <limits>
#include <map>

#include "drapelab/cloth_limits.hpp"
#include "drapelab/disc_cloth.hpp"
#include "drapelab/obj_reader.hpp"
#include "drapelab/scene/number_format.hpp"
#include "materials.hpp"
#include "scene_keys.hpp"
#include "text_checks.hpp"
#include "value_ranges.hpp"

namespace drapelab::scene {
namespace {

// Why a mesh moved by `scale`, `rotation` and `center` is not a usable cloth: a coordinate beyond
// kMaxCoordinate, a size outside the cloth's length range, or a triangle that lost its area (a
// scale of 1e-150 collapses every triangle), or nothing.
std::optional<std::string> placed_mesh_problem(const TriangleMesh& mesh) {
  const double largest = mesh.vertices.cwiseAbs().maxCoeff();
  if (!(largest <= kMaxCoordinate))
    return "a vertex lies " + format_number(largest) +
           " m from the origin along an axis; at most " + format_number(kMaxCoordinate) +
           " m is allowed";
  const double extent =
      (mesh.vertices.rowwise().maxCoeff() - mesh.vertices.rowwise().minCoeff()).maxCoeff();  // m
  const Range lengths = cloth_length_range();
  if (!lengths.contains(extent))
    return "its size (the longest side of its bounding box) is " + format_number(extent) +
           " m; it must be " + lengths.describe() + " m";
  return mesh_problem(mesh);
}

}  // namespace

ClothReader::ClothReader(SceneReader& reader, Scene& scene, std::filesystem::path folder)
    : r_(reader), scene_(scene), folder_(std::move(folder)) {}

void ClothReader::read(const YAML::Node& node) {
  // The shape decides which keys exist, so read it first.
  std::string shape = default_choice(key("cloth.shape"));
  if (node.IsMap() && node["shape"].IsDefined())
    if (const auto chosen =
            r_.choice(node["shape"], "cloth.shape", key_choices(key("cloth.shape"))))
      shape = *chosen;
  MapReader cloth(r_, node, "cloth", key_names("cloth", shape));
  if (!cloth.valid()) return;
  cloth_node_.reset(node);  // reset: `=` would overwrite the node it held
  ClothSpec& spec = scene_.cloth;
  spec.shape = shape;
  GridClothSpec& common = spec.grid;
  // A mesh keeps its file's coordinates unless moved; grids and discs default to 1 m up.
  const Eigen::Vector3d default_center =
      shape == "mesh" ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0, 1, 0);
  if (const auto center = cloth.numbers(key("cloth.center"), default_center))
    common.center = *center;
  if (const auto rotation = cloth.numbers(key("cloth.rotation"))) common.rotation = *rotation;
  // The table's defaults of the keys a material preset may set (apply_material), and of the
  // springs and continuum parameters it gives.
  common.thickness = default_number(key("cloth.thickness"));
  spec.air_damping = default_number(key("cloth.air_damping"));
  common.stretch = {default_number(key("cloth.springs.stretch.ks")),
                    default_number(key("cloth.springs.stretch.kd"))};
  common.shear = {default_number(key("cloth.springs.shear.ks")),
                  default_number(key("cloth.springs.shear.kd"))};
  common.bend = {default_number(key("cloth.springs.bend.ks")),
                 default_number(key("cloth.springs.bend.kd"))};
  if (shape == "grid") read_grid(cloth);
  if (shape == "disc") read_disc(cloth);
  if (shape == "mesh") read_mesh(cloth);
  apply_material(cloth);
  read_mass(cloth);
  common.thickness =
      cloth.number(key("cloth.thickness"), common.thickness).value_or(common.thickness);
  spec.perturbation = cloth.number(key("cloth.perturbation")).value_or(0.0);
  spec.air_damping =
      cloth.number(key("cloth.air_damping"), spec.air_damping).value_or(spec.air_damping);
  read_model(cloth);
  if (cloth.has("pins")) read_pins(cloth.get("pins"));
  read_self_collision(cloth);
}

void ClothReader::read_self_collision(MapReader& cloth) {
  SelfCollisionSettings& self = scene_.cloth.self_collision;
  self.thickness = scene_.cloth.grid.thickness;  // the default: the cloth's own
  self.static_friction = self.friction;
  if (!cloth.has("self_collision")) return;
  MapReader map(r_, cloth.get("self_collision"), "cloth.self_collision",
                key_names("cloth.self_collision"));
  if (!map.valid()) return;
  self.enabled = map.boolean(key("cloth.self_collision.enabled")).value_or(true);
  self.thickness =
      map.number(key("cloth.self_collision.thickness"), self.thickness).value_or(self.thickness);
  self.stiffness = map.number(key("cloth.self_collision.stiffness")).value_or(self.stiffness);
  self.damping = map.number(key("cloth.self_collision.damping")).value_or(self.damping);
  self.friction = map.number(key("cloth.self_collision.friction")).value_or(self.friction);
  self.static_friction = map.number(key("cloth.self_collision.static_friction"), self.friction)
                             .value_or(self.friction);
  if (map.has("static_friction") && self.static_friction < self.friction)
    r_.error(map.get("static_friction"), "cloth.self_collision.static_friction",
             "must be >= cloth.self_collision.friction (" + format_number(self.friction) +
                 "), got " + format_number(self.static_friction));
}

void ClothReader::read_grid(MapReader& cloth) {
  GridClothSpec& grid = scene_.cloth.grid;
  if (const auto size = cloth.numbers(key("cloth.size"))) grid.size = *size;
  if (const auto plane = cloth.choice(key("cloth.plane")))
    grid.plane = *plane == "xz" ? GridPlane::xz : GridPlane::xy;
  if (!cloth.has("resolution")) {
    cloth.missing("resolution",
                  "particles along each side, for example [33, 33] ([1, N] is a chain)");
    return;
  }
  const SceneKey& row = key("cloth.resolution");
  const auto resolution =
      r_.integers(cloth.get("resolution"), "cloth.resolution", row.size, row.range);
  if (!resolution) return;
  grid.nx = static_cast<int>((*resolution)[0]);
  grid.ny = static_cast<int>((*resolution)[1]);
  if (grid.nx * static_cast<long long>(grid.ny) < 2)
    r_.error(cloth.get("resolution"), "cloth.resolution",
             "must give at least 2 particles in all, got [1, 1]");
  else if (const auto problem = cloth_size_problem(grid_cloth_size(grid.nx, grid.ny)))
    r_.error(cloth.get("resolution"), "cloth.resolution", *problem);
  else
    geometry_ok_ = true;
}

void ClothReader::read_disc(MapReader& cloth) {
  DiscSpec& disc = scene_.cloth.disc;
  const std::size_t errors = r_.error_count();
  if (cloth.has("rings")) rings_node_.reset(cloth.get("rings"));
  disc.radius = cloth.number(key("cloth.radius")).value_or(disc.radius);
  disc.rings = static_cast<int>(
      cloth.integer(key("cloth.rings")).value_or(default_integer(key("cloth.rings"))));
  disc.center = scene_.cloth.grid.center;
  disc.rotation = scene_.cloth.grid.rotation;
  geometry_ok_ = r_.error_count() == errors;
}

void ClothReader::read_mesh(MapReader& cloth) {
  ClothSpec& spec = scene_.cloth;
  spec.mesh_scale = cloth.number(key("cloth.scale")).value_or(1.0);
  if (!cloth.has("path")) {
    cloth.missing(
        "path",
        "the OBJ file of the cloth, relative to the scene file (for example meshes/cape.obj)");
    return;
  }
  const auto path = cloth.text("path", std::nullopt);
  if (!path) return;
  if (const auto problem = path_problem(*path)) {
    r_.error(cloth.get("path"), "cloth.path", *problem);
    return;
  }
  spec.mesh_file =
      std::filesystem::path(*path).is_absolute() ? std::filesystem::path(*path) : folder_ / *path;
  const ObjReadResult read = read_obj_file(spec.mesh_file);
  const std::string shown =
      spec.mesh_file.string() + (read.error_line > 0 ? ":" + std::to_string(read.error_line) : "");
  if (!read.mesh) {
    r_.error(cloth.get("path"), "cloth.path", "'" + shown + "': " + read.error);
    return;
  }
  TriangleMesh mesh = *read.mesh;
  if (const auto problem = mesh_problem(mesh)) {
    r_.error(cloth.get("path"), "cloth.path", "'" + shown + "' is not a usable cloth: " + *problem);
    return;
  }
  // Scaled about the file's origin, turned, then moved by `center`.
  const Eigen::Matrix3d turn = euler_rotation(spec.grid.rotation);
  for (Eigen::Index i = 0; i < mesh.vertices.cols(); ++i)
    mesh.vertices.col(i) = spec.grid.center + turn * (spec.mesh_scale * mesh.vertices.col(i));
  if (const auto problem = placed_mesh_problem(mesh)) {
    r_.error(cloth.get("path"), "cloth.path",
             "'" + shown + "' scaled by " + format_number(spec.mesh_scale) +
                 " and placed is not a usable cloth: " + *problem);
    return;
  }
  spec.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
  geometry_ok_ = true;
}

double ClothReader::particle_spacing() const {
  const ClothSpec& spec = scene_.cloth;
  if (spec.shape == "disc") return spec.disc.radius / spec.disc.rings;
  if (spec.shape == "mesh") {
    double total = 0.0;
    const auto& m = *spec.mesh;
    for (Eigen::Index t = 0; t < m.triangles.cols(); ++t)
      for (int e = 0; e < 3; ++e)
        total += (m.vertices.col(m.triangles(e, t)) - m.vertices.col(m.triangles((e + 1) % 3, t)))
                     .norm();
    return total / (3.0 * static_cast<double>(m.triangles.cols()));
  }
  const GridClothSpec& g = spec.grid;
  double spacing = std::numeric_limits<double>::infinity();
  if (g.nx > 1) spacing = std::min(spacing, g.size.x() / (g.nx - 1));
  if (g.ny > 1) spacing = std::min(spacing, g.size.y() / (g.ny - 1));
  return spacing;
}

void ClothReader::apply_material(MapReader& cloth) {
  if (!cloth.has("material")) return;
  const auto name = cloth.choice(key("cloth.material"));
  if (!name) return;
  const Material material = *find_material(*name);
  preset_continuum_ = material_continuum(material);
  if (!geometry_ok_) return;
  ClothSpec& spec = scene_.cloth;
  spec.material = *name;
  const MaterialSprings springs = material_springs(material, particle_spacing());
  spec.grid.stretch = springs.stretch;
  spec.grid.shear = springs.shear;
  spec.grid.bend = springs.bend;
  spec.grid.areal_density = material.areal_density;
  spec.grid.thickness = material.thickness;
  spec.air_damping = material.air_damping;
}

void ClothReader::read_mass(MapReader& cloth) {
  GridClothSpec& grid = scene_.cloth.grid;
  const bool has_mass = cloth.has("mass"), has_density = cloth.has("areal_density");
  if (has_mass && has_density) {
    r_.error(cloth.get("areal_density"), "cloth.areal_density",
             "cannot be given together with cloth.mass; give one of them");
  } else if (has_mass) {
    grid.areal_density.reset();  // an explicit mass replaces a material's density
    if (const auto mass = cloth.number(key("cloth.mass"))) grid.mass = *mass;
  } else if (has_density) {
    if (const auto density = cloth.number(key("cloth.areal_density"))) {
      grid.areal_density = *density;
      if (scene_.cloth.shape == "grid" && geometry_ok_ && (grid.nx == 1 || grid.ny == 1))
        r_.error(cloth.get("areal_density"), "cloth.areal_density",
                 "needs a two-dimensional cloth, but a chain has no area; give cloth.mass instead");
    }
  } else if (!grid.areal_density && !cloth.has("material")) {  // a bad material is reported already
    cloth.missing(
        "mass",
        "total kg (for example 0.25), or cloth.areal_density in kg/m^2, or a cloth.material");
  }
}

void ClothReader::read_model(MapReader& cloth) {
  const auto model = cloth.choice(key("cloth.model"));
  ClothSpec& spec = scene_.cloth;
  // The fabric's continuum parameters: the preset's values (or the defaults), then the explicit
  // keys, key by key. A springs cloth keeps them for its solvers with model: continuum.
  ContinuumParams params = preset_continuum_.value_or(
      ContinuumParams{default_number(key("cloth.continuum.stretch_modulus")),
                      default_number(key("cloth.continuum.poisson")),
                      default_number(key("cloth.continuum.bending_rigidity")),
                      default_number(key("cloth.continuum.damping"))});
  if (cloth.has("continuum")) {
    spec.continuum_given = true;
    MapReader map(r_, cloth.get("continuum"), "cloth.continuum", key_names("cloth.continuum"));
    if (map.valid()) {
      params.stretch_modulus =
          map.number(key("cloth.continuum.stretch_modulus"), params.stretch_modulus)
              .value_or(params.stretch_modulus);
      params.poisson =
          map.number(key("cloth.continuum.poisson"), params.poisson).value_or(params.poisson);
      params.bending_rigidity =
          map.number(key("cloth.continuum.bending_rigidity"), params.bending_rigidity)
              .value_or(params.bending_rigidity);
      params.damping =
          map.number(key("cloth.continuum.damping"), params.damping).value_or(params.damping);
    }
  }
  spec.continuum = params;
  if (model != "continuum") {
    if (cloth.has("springs")) read_springs(cloth.get("springs"));
    return;
  }
  if (cloth.has("springs"))
    r_.error(at_key(), "cloth.springs",
             "cannot be given with model: continuum: a continuum cloth's springs (for the Bullet "
             "cloths, the stretch metrics and solvers with model: springs) are derived from "
             "cloth.continuum; remove cloth.springs and give the fabric in cloth.continuum "
             "(stretch_modulus, poisson, bending_rigidity, damping)");
  spec.grid.continuum = params;
  if (!geometry_ok_) return;
  const GridClothSpec& grid = spec.grid;
  if (spec.shape == "grid" && (grid.nx == 1 || grid.ny == 1)) {
    r_.error(cloth.get("model"), "cloth.model",
             "is continuum, which needs a two-dimensional cloth, but cloth.resolution [" +
                 std::to_string(grid.nx) + ", " + std::to_string(grid.ny) +
                 "] is a chain, with no triangles; use model: springs, or at least 2 particles "
                 "along each side");
    return;
  }
  // The springs the Bullet cloths, the metrics and solvers with model: springs use, at the cloth's
  // own particle spacing. A preset keeps its own shear rigidity G there: woven fabric shears far
  // more easily than the isotropic membrane, and the springs can say so.
  MaterialSprings springs = continuum_springs(params, particle_spacing());
  if (preset_continuum_) springs.shear = spec.grid.shear;  // the preset's, set by apply_material
  spec.grid.stretch = springs.stretch;
  spec.grid.shear = springs.shear;
  spec.grid.bend = springs.bend;
}

void ClothReader::read_springs(const YAML::Node& node) {
  MapReader springs(r_, node, "cloth.springs", key_names("cloth.springs"));
  if (!springs.valid()) return;
  GridClothSpec& grid = scene_.cloth.grid;
  // Each kind's defaults are a preset's, or the table's (read).
  read_spring_kind(springs, key("cloth.springs.stretch.ks"), key("cloth.springs.stretch.kd"),
                   grid.stretch);
  read_spring_kind(springs, key("cloth.springs.shear.ks"), key("cloth.springs.shear.kd"),
                   grid.shear);
  read_spring_kind(springs, key("cloth.springs.bend.ks"), key("cloth.springs.bend.kd"), grid.bend);
}

void ClothReader::read_spring_kind(MapReader& springs, const SceneKey& ks, const SceneKey& kd,
                                   SpringParams& out) {
  const std::string kind(ks.parent().substr(ks.parent().rfind('.') + 1));
  if (!springs.has(kind)) return;
  MapReader params(r_, springs.get(kind), springs.path_of(kind), key_names(ks.parent()));
  if (!params.valid()) return;
  out.ks = params.number(ks, out.ks).value_or(out.ks);
  out.kd = params.number(kd, out.kd).value_or(out.kd);
}

void ClothReader::read_pins(const YAML::Node& node) {
  if (!node.IsSequence()) {
    r_.error(node, "cloth.pins",
             "must be a list of pin selectors (a set name, [i, j], {index: k}, "
             "{within: {center: [x, y, z], radius: r}}), got " +
                 describe_scalar(node));
    return;
  }
  record_item_lines(r_, node, "cloth.pins");
  for (std::size_t k = 0; k < node.size(); ++k) {
    const YAML::Node item = node[k];
    const std::string path = "cloth.pins." + std::to_string(k);
    std::optional<PinSelector> selector;
    std::string attach;  // the collider the pin's particles move with, if any
    if (item.IsScalar()) {
      if (const auto name = r_.choice(item, path, pin_set_names(scene_.cloth)))
        selector = PinNamed{*name};
    } else if (item.IsSequence()) {
      if (const auto ij = r_.integers(item, path, 2, grid_coordinate_range()))
        selector = PinGridCoord{static_cast<int>((*ij)[0]), static_cast<int>((*ij)[1])};
    } else if (item.IsMap()) {
      selector = read_pin_map(item, path, attach);
    } else {
      r_.error(
          item, path,
          "must be a pin selector (a set name, [i, j], {index: k} or {within: ...}), got nothing");
    }
    if (!selector) continue;
    scene_.cloth.grid.pins.push_back(*selector);
    scene_.cloth.pin_attach.push_back(attach);
    pin_nodes_.push_back(item);
    pin_paths_.push_back(path);
  }
}

std::optional<PinSelector> ClothReader::read_pin_map(const YAML::Node& item,
                                                     const std::string& path, std::string& attach) {
  MapReader pin(r_, item, path, key_names("cloth.pins[]"));
  if (!pin.valid()) return std::nullopt;
  if (const auto name = pin.text("attach", std::nullopt)) attach = *name;
  if (pin.has("index") == pin.has("within")) {
    r_.error(item, path, "must have exactly one of index or within");
    return std::nullopt;
  }
  if (pin.has("index")) {
    const auto index = pin.integer(key("cloth.pins[].index"));
    if (!index) return std::nullopt;
    return PinIndex{static_cast<int>(*index)};
  }
  MapReader ball(r_, pin.get("within"), pin.path_of("within"), key_names("cloth.pins[].within"));
  if (!ball.valid()) return std::nullopt;
  const auto center = ball.numbers(key("cloth.pins[].within.center"));
  const auto radius = ball.number(key("cloth.pins[].within.radius"));
  if (!ball.has("center")) ball.missing("center", "the ball's centre [x, y, z] in m");
  if (!ball.has("radius")) ball.missing("radius", "the ball's radius in m, > 0");
  if (!center || !radius) return std::nullopt;
  return PinWithin{*center, *radius};
}

// The disc's particle count and memory, from its ring radii, before anything is allocated: a ring
// at the drape support a hair inside the rim would otherwise hold billions of particles.
void ClothReader::check_disc_size() {
  const DiscSpec& disc = scene_.cloth.disc;
  std::optional<std::string> problem;
  try {
    problem = cloth_size_problem(disc_cloth_size(disc));
  } catch (const std::exception& e) {
    problem = e.what();
  }
  if (!problem) return;
  const std::string support = disc.ring_at ? " and a ring at the drape support's radius " +
                                                 format_number(*disc.ring_at) + " m"
                                           : "";
  r_.error(rings_node_, "cloth.rings",
           "of " + std::to_string(disc.rings) + " rings over a radius of " +
               format_number(disc.radius) + " m" + support + ": the disc " + *problem,
           cloth_node_);
  geometry_ok_ = false;
}

double ClothReader::particle_count() const {
  const ClothSpec& spec = scene_.cloth;
  if (spec.shape == "disc") return disc_cloth_size(spec.disc).particles;
  if (spec.shape == "mesh") return static_cast<double>(spec.mesh->vertices.cols());
  return grid_cloth_size(spec.grid.nx, spec.grid.ny).particles;
}

void ClothReader::size_error(const std::string& message) {
  const std::string& shape = scene_.cloth.shape;
  if (shape == "disc")
    r_.error(rings_node_, "cloth.rings", message, cloth_node_);
  else
    r_.error(cloth_node_[shape == "mesh" ? "path" : "resolution"],
             shape == "mesh" ? "cloth.path" : "cloth.resolution", message);
}

// Each attach names a collider of the scene.
void ClothReader::check_pin_attach() {
  ClothSpec& spec = scene_.cloth;
  for (std::size_t k = 0; k < spec.pin_attach.size(); ++k) {
    const std::string& name = spec.pin_attach[k];
    if (name.empty()) continue;
    bool found = false;
    std::vector<std::string> known;
    for (const Collider& c : scene_.colliders) {
      found = found || c.name == name;
      known.push_back(c.name);
    }
    if (found) continue;
    r_.error(
        pin_nodes_[k]["attach"], pin_paths_[k] + ".attach",
        "must name a collider of the scene" +
            (known.empty() ? std::string(" (it has none)") : " (" + listed_names(known) + ")") +
            ", got " + quoted_value(name));
  }
}

void ClothReader::finish() {
  ClothSpec& spec = scene_.cloth;
  if (spec.shape == "disc" && scene_.drape_support) {
    const double support = scene_.drape_support->disc.radius;
    if (support > 0.0 && support < spec.disc.radius && spec.disc.rings >= 2)
      spec.disc.ring_at = support;
  }
  if (spec.shape == "disc" && geometry_ok_) check_disc_size();
  if (!geometry_ok_) return;
  check_pin_attach();
  // Pins are checked only on a cloth that can be built (its selectors may be fine on a fixed one).
  std::vector<PinSelector> kept;
  std::vector<std::string> kept_attach;
  std::map<int, std::size_t> holder;  // particle -> the first pin that holds it
  try {
    for (std::size_t k = 0; k < spec.grid.pins.size(); ++k) {
      std::string why;
      const std::vector<int> held = select_cloth_pins(spec, spec.grid.pins[k], &why);
      if (held.empty()) {
        r_.error(pin_nodes_[k], pin_paths_[k], "selects no particle: " + why);
        continue;
      }
      kept.push_back(spec.grid.pins[k]);
      kept_attach.push_back(spec.pin_attach[k]);
      // A particle cannot both stay put and move with a collider, or move with two.
      for (int particle : held) {
        const auto [it, first] = holder.emplace(particle, k);
        const std::string& other = spec.pin_attach[it->second];
        if (first || other == spec.pin_attach[k]) continue;
        const auto held_by = [](const std::string& name) {
          return name.empty() ? std::string("stays in place") : "moves with '" + name + "'";
        };
        r_.error(pin_nodes_[k], pin_paths_[k],
                 "holds particle " + std::to_string(particle) + ", which " +
                     pin_paths_[it->second] + " also holds; one " + held_by(other) +
                     ", the other " + held_by(spec.pin_attach[k]) + ": a particle has one holder");
        break;
      }
    }
  } catch (const std::exception& e) {  // the shape's builder refused it
    r_.error(cloth_node_, "cloth", "cannot be built: " + std::string(e.what()));
    geometry_ok_ = false;
  }
  spec.grid.pins = kept;
  spec.pin_attach = kept_attach;
}

}  // namespace drapelab::scene
